/* Applied force at a point, world components f_x(t), f_y(t), f_z(t) (f_z
 * = 0 in a planar scene): Q += J_Pᵀ F, input power Ė = F·P'. */
#include "scene_internal.h"

static int force_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, const braun_real *v, braun_real *Q)
{
    scene_pt P;
    braun_real F[3];
    (void)v;
    for (int k = 0; k < 3; k++) braun_scene_fn_eval(&e->f[k], t, &F[k], NULL, NULL);
    braun_scene__point(s, e->a, q, NULL, &P);
    braun_scene_pt_grad(&P, F, Q);
    return 0;
}

static int force_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                       const braun_real *q, const braun_real *v, braun_real *Pout)
{
    scene_pt P;
    braun_real F[3];
    for (int k = 0; k < 3; k++) braun_scene_fn_eval(&e->f[k], t, &F[k], NULL, NULL);
    braun_scene__point(s, e->a, q, v, &P);
    *Pout = F[0] * P.vel[0] + F[1] * P.vel[1] + F[2] * P.vel[2]; /* + 0 in a planar scene */
    return 0;
}

static const char *force_check(const braun_scene *s, const braun_scene_effect *e)
{
    const braun_scene_fn *fz = &e->f[2];
    if (braun_scene__body_of(s, e->a) < 0) return "force on a ground point";
    if (s->dim == 2 && (fz->kind != BRAUN_FN_CONSTANT || fz->a != 0))
        return "a force in a planar scene has no z component (fz)";
    return NULL;
}

static const braun_scene_field force_fields[] = {
    {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"fx", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f), 0, NULL},
    {"fy", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + sizeof(braun_scene_fn), 0, NULL},
    {"fz", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + 2 * sizeof(braun_scene_fn), 0,
     NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_force = {
    "force", "BRAUN_EFFECT_FORCE", force_fields, NULL, force_check, force_forces, NULL,
    force_power, NULL, 0};
