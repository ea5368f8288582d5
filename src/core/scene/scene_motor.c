/* Motor with a linear torque–speed law between rotor a and stator b (or
 * the ground): τ = τ0 (1 - ω/ω0), ω = ω_a - ω_b, τ on a and -τ on b.
 * τ0 is the stall torque, ω0 the no-load speed. Input power Ė = τ ω:
 * positive while it drives, negative when the load overruns it. */
#include "scene_internal.h"

static braun_real speed(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                        const braun_real *v)
{
    braun_real wa, wb;
    braun_scene__angle(s, e->a, q, v, NULL, &wa);
    braun_scene__angle(s, e->b, q, v, NULL, &wb);
    return wa - wb;
}

void braun_scene__motor_forces(const braun_scene *s, const braun_scene_effect *e,
                               const braun_real *q, const braun_real *v, braun_real *Q)
{
    const braun_real tau = e->tau0 * (1 - speed(s, e, q, v) / e->omega0);
    const int ca = braun_scene__theta_col(s, e->a), cb = braun_scene__theta_col(s, e->b);
    if (ca >= 0) Q[ca] += tau;
    if (cb >= 0) Q[cb] -= tau;
}

braun_real braun_scene__motor_power(const braun_scene *s, const braun_scene_effect *e,
                                    const braun_real *q, const braun_real *v)
{
    const braun_real w = speed(s, e, q, v);
    return e->tau0 * (1 - w / e->omega0) * w;
}
