/* Applied force at a point, world components f_x(t), f_y(t):
 * Q += J_Pᵀ F, input power Ė = F·P'. */
#include "scene_internal.h"

static int force_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, const braun_real *v, braun_real *Q)
{
    scene_pt P;
    braun_real fx, fy;
    (void)v;
    braun_scene_fn_eval(&e->f[0], t, &fx, NULL, NULL);
    braun_scene_fn_eval(&e->f[1], t, &fy, NULL, NULL);
    braun_scene__point(s, e->a, q, NULL, &P);
    braun_scene__add_grad(&P, fx, fy, Q);
    return 0;
}

static int force_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                       const braun_real *q, const braun_real *v, braun_real *Pout)
{
    scene_pt P;
    braun_real fx, fy;
    braun_scene_fn_eval(&e->f[0], t, &fx, NULL, NULL);
    braun_scene_fn_eval(&e->f[1], t, &fy, NULL, NULL);
    braun_scene__point(s, e->a, q, v, &P);
    *Pout = fx * P.vel[0] + fy * P.vel[1];
    return 0;
}

static const char *force_check(const braun_scene *s, const braun_scene_effect *e)
{
    return braun_scene__body_of(s, e->a) < 0 ? "force on a ground point" : NULL;
}

static const braun_scene_field force_fields[] = {
    {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"fx", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f), 0, NULL},
    {"fy", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + sizeof(braun_scene_fn), 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_force = {
    "force", "BRAUN_EFFECT_FORCE", force_fields, NULL, force_check, force_forces, NULL,
    force_power, NULL};
