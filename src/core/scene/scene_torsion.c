/* Rotational spring and damper between two bodies (or a body and the
 * ground) on the relative angle Δ = θ_b - θ_a:
 *   torque on b  τ = -(k (Δ - rest) + c Δ'),  on a -τ
 *   potential    V = ½ k (Δ - rest)²,  input power Ė = -c Δ'². */
#include "scene_internal.h"

static int relative(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                    const braun_real *v, braun_real *d, braun_real *dd, int *ca, int *cb)
{
    braun_real ta, tb, wa, wb;
    *ca = braun_scene__angle(s, e->a, q, v, &ta, &wa);
    *cb = braun_scene__angle(s, e->b, q, v, &tb, &wb);
    *d = tb - ta;
    *dd = wb - wa;
    return 0;
}

void braun_scene__torsion_forces(const braun_scene *s, const braun_scene_effect *e,
                                 const braun_real *q, const braun_real *v, braun_real *Q)
{
    braun_real d, dd;
    int ca, cb;
    relative(s, e, q, v, &d, &dd, &ca, &cb);
    const braun_real tau = -(e->k * (d - e->rest) + e->c * dd);
    if (cb >= 0) Q[cb] += tau;
    if (ca >= 0) Q[ca] -= tau;
}

braun_real braun_scene__torsion_potential(const braun_scene *s, const braun_scene_effect *e,
                                          const braun_real *q, braun_real *dVdq)
{
    braun_real d, dd;
    int ca, cb;
    relative(s, e, q, NULL, &d, &dd, &ca, &cb);
    const braun_real x = d - e->rest;
    if (dVdq) {
        if (cb >= 0) dVdq[cb] += e->k * x;
        if (ca >= 0) dVdq[ca] -= e->k * x;
    }
    return BRAUN_R(0.5) * e->k * x * x;
}

braun_real braun_scene__torsion_power(const braun_scene *s, const braun_scene_effect *e,
                                      const braun_real *q, const braun_real *v)
{
    braun_real d, dd;
    int ca, cb;
    relative(s, e, q, v, &d, &dd, &ca, &cb);
    return -e->c * dd * dd;
}
