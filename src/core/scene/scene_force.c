/* Applied force at a point, world components f_x(t), f_y(t):
 * Q += J_Pᵀ F, input power Ė = F·P'. */
#include "scene_internal.h"

void braun_scene__force_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                               const braun_real *q, braun_real *Q)
{
    scene_pt P;
    braun_real fx, fy;
    braun_scene_fn_eval(&e->f[0], t, &fx, NULL, NULL);
    braun_scene_fn_eval(&e->f[1], t, &fy, NULL, NULL);
    braun_scene__point(s, e->a, q, NULL, &P);
    braun_scene__add_grad(&P, fx, fy, Q);
}

braun_real braun_scene__force_power(const braun_scene *s, const braun_scene_effect *e,
                                    braun_real t, const braun_real *q, const braun_real *v)
{
    scene_pt P;
    braun_real fx, fy;
    braun_scene_fn_eval(&e->f[0], t, &fx, NULL, NULL);
    braun_scene_fn_eval(&e->f[1], t, &fy, NULL, NULL);
    braun_scene__point(s, e->a, q, v, &P);
    return fx * P.vel[0] + fy * P.vel[1];
}
