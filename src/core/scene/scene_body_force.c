/* A follower force: components f_x(t), f_y(t), f_z(t) in the frame of the
 * body of its point, F = R(q) f in the world:
 *   Q += J_Pᵀ F,  input power Ė = F·P'. */
#include "scene_internal.h"

static void world_force(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, braun_real *F)
{
    braun_real fb[3];
    scene_pt D;
    for (int k = 0; k < 3; k++) braun_scene_fn_eval(&e->f[k], t, &fb[k], NULL, NULL);
    braun_scene_dir_eval(s, braun_scene__body_of(s, e->a), fb, q, NULL, &D);
    for (int k = 0; k < 3; k++) F[k] = D.pos[k];
}

static int body_force_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                             const braun_real *q, const braun_real *v, braun_real *Q)
{
    scene_pt P;
    braun_real F[3];
    (void)v;
    world_force(s, e, t, q, F);
    braun_scene__point(s, e->a, q, NULL, &P);
    braun_scene_pt_grad(&P, F, Q);
    return 0;
}

static int body_force_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *Pout)
{
    scene_pt P;
    braun_real F[3];
    world_force(s, e, t, q, F);
    braun_scene__point(s, e->a, q, v, &P);
    *Pout = braun_scene__dot3(F, P.vel);
    return 0;
}

static const char *body_force_check(const braun_scene *s, const braun_scene_effect *e)
{
    const int b = braun_scene__body_of(s, e->a);
    if (b < 0) return "force on a ground point";
    if (!braun_scene__has_frame(s, b))
        return "a body_force needs a point of a body with an orientation (rigid3d)";
    return NULL;
}

static const braun_scene_field body_force_fields[] = {
    {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"fx", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f), 0, NULL},
    {"fy", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + sizeof(braun_scene_fn), 0, NULL},
    {"fz", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + 2 * sizeof(braun_scene_fn), 0,
     NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_body_force = {
    "body_force", "BRAUN_EFFECT_BODY_FORCE", body_force_fields, NULL, body_force_check,
    body_force_forces, NULL, body_force_power, NULL, 3};
