/* Applied torque τ(t) on body a, with its reaction -τ on body b (or the
 * ground): Q_θa += τ, Q_θb -= τ; input power Ė = τ (ω_a - ω_b). */
#include "scene_internal.h"

void braun_scene__torque_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                                braun_real *Q)
{
    braun_real tau;
    braun_scene_fn_eval(&e->f[0], t, &tau, NULL, NULL);
    const int ca = braun_scene__theta_col(s, e->a), cb = braun_scene__theta_col(s, e->b);
    if (ca >= 0) Q[ca] += tau;
    if (cb >= 0) Q[cb] -= tau;
}

braun_real braun_scene__torque_power(const braun_scene *s, const braun_scene_effect *e,
                                     braun_real t, const braun_real *q, const braun_real *v)
{
    braun_real tau, wa, wb;
    braun_scene_fn_eval(&e->f[0], t, &tau, NULL, NULL);
    braun_scene__angle(s, e->a, q, v, NULL, &wa);
    braun_scene__angle(s, e->b, q, v, NULL, &wb);
    return tau * (wa - wb);
}
