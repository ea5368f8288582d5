/* Applied torque τ(t) on a spatial body, its reaction -τ on a second body
 * or the ground; world components (torque3d) or components in the body's
 * frame (body_torque: a torque that turns with the body). With the body
 * class's angular-velocity Jacobian W (ω = W v):
 *   Q += W_aᵀ τ - W_bᵀ τ,   input power Ė = τ·(ω_a - ω_b). */
#include "scene_internal.h"

/* τ in the world at (t, q): body frame components turned by R(q) when
 * body_frame. */
static void torque_world(const braun_scene *s, const braun_scene_effect *e, int body_frame,
                         braun_real t, const braun_real *q, braun_real *tau)
{
    braun_real tb[3];
    for (int k = 0; k < 3; k++) braun_scene_fn_eval(&e->f[k], t, &tb[k], NULL, NULL);
    if (!body_frame) {
        for (int k = 0; k < 3; k++) tau[k] = tb[k];
        return;
    }
    scene_pt D;
    braun_scene_dir_eval(s, e->a, tb, q, NULL, &D);
    for (int k = 0; k < 3; k++) tau[k] = D.pos[k];
}

/* Q += sign Wᵀτ at the body's columns, or ω·τ into *power (when Q is NULL). */
static void apply(const braun_scene *s, int body, braun_real sign, const braun_real *tau,
                  const braun_real *q, const braun_real *v, braun_real *Q, braun_real *power)
{
    if (body < 0) return;
    const braun_scene_body *bd = &s->bodies[body];
    const int dof = bd->kind->dof;
    braun_real W[3 * BRAUN_SCENE_MAX_DOF];
    bd->kind->omega(bd, q + bd->iq, W);
    for (int c = 0; c < dof; c++) {
        const braun_real wt = W[c] * tau[0] + W[dof + c] * tau[1] + W[2 * dof + c] * tau[2];
        if (Q) Q[bd->iq + c] += sign * wt;
        else *power += sign * wt * v[bd->iq + c];
    }
}

static int forces(const braun_scene *s, const braun_scene_effect *e, int body_frame,
                  braun_real t, const braun_real *q, braun_real *Q)
{
    braun_real tau[3];
    torque_world(s, e, body_frame, t, q, tau);
    apply(s, e->a, 1, tau, q, NULL, Q, NULL);
    apply(s, e->b, -1, tau, q, NULL, Q, NULL);
    return 0;
}

static int power(const braun_scene *s, const braun_scene_effect *e, int body_frame,
                 braun_real t, const braun_real *q, const braun_real *v, braun_real *P)
{
    braun_real tau[3];
    *P = 0;
    torque_world(s, e, body_frame, t, q, tau);
    apply(s, e->a, 1, tau, q, v, NULL, P);
    apply(s, e->b, -1, tau, q, v, NULL, P);
    return 0;
}

static int torque3d_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                           const braun_real *q, const braun_real *v, braun_real *Q)
{
    (void)v;
    return forces(s, e, 0, t, q, Q);
}

static int torque3d_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *P)
{
    return power(s, e, 0, t, q, v, P);
}

static int body_torque_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                              const braun_real *q, const braun_real *v, braun_real *Q)
{
    (void)v;
    return forces(s, e, 1, t, q, Q);
}

static int body_torque_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                             const braun_real *q, const braun_real *v, braun_real *P)
{
    return power(s, e, 1, t, q, v, P);
}

static const char *torque3d_check(const braun_scene *s, const braun_scene_effect *e)
{
    if (e->a == e->b) return "a torque's body and reaction are the same body";
    if (s->bodies[e->a].kind->omega == NULL || (e->b >= 0 && s->bodies[e->b].kind->omega == NULL))
        return "a torque needs bodies with an orientation (rigid3d) or the ground as reaction";
    return NULL;
}

static const braun_scene_field torque3d_fields[] = {
    {"body", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"reaction", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, b), BRAUN_FIELD_GROUND, NULL},
    {"tx", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f), 0, NULL},
    {"ty", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + sizeof(braun_scene_fn), 0, NULL},
    {"tz", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f) + 2 * sizeof(braun_scene_fn), 0,
     NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_torque3d = {
    "torque3d", "BRAUN_EFFECT_TORQUE3D", torque3d_fields, NULL, torque3d_check,
    torque3d_forces, NULL, torque3d_power, NULL, 3};

const braun_scene_effect_class braun_scene_effect_body_torque = {
    "body_torque", "BRAUN_EFFECT_BODY_TORQUE", torque3d_fields, NULL, torque3d_check,
    body_torque_forces, NULL, body_torque_power, NULL, 3};
