/* Angle joint: θ_b - θ_a - α(t) = 0 (1 row), a fixed relative angle or,
 * driven, a prescribed one (a crank turned at a given rate). Linear in q:
 * A_q has +1 at θ_b and -1 at θ_a, b_q = α', b_qv = α''. Also the angle
 * row of the prismatic joint (scene_slider.c). */
#include "scene_internal.h"

void braun_scene__angle_rows(const braun_scene *s, int body_a, int body_b,
                             const braun_scene_fn *alpha, braun_real t, const braun_real *q,
                             const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                             braun_real *bv)
{
    braun_real ta, tb, x, dx, ddx;
    const int ca = braun_scene__angle(s, body_a, q, v, &ta, NULL);
    const int cb = braun_scene__angle(s, body_b, q, v, &tb, NULL);
    braun_scene_fn_eval(alpha, t, &x, &dx, &ddx);
    if (phi) phi[0] = tb - ta - x;
    if (A) {
        if (cb >= 0) A[cb] += 1;
        if (ca >= 0) A[ca] -= 1;
    }
    if (b) b[0] = dx;
    if (bv) bv[0] = ddx;
}
