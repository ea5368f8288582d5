/* Applied torque τ(t) on body a, with its reaction -τ on body b (or the
 * ground): Q_θa += τ, Q_θb -= τ; input power Ė = τ (ω_a - ω_b). */
#include "scene_internal.h"

static int torque_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *Q)
{
    braun_real tau;
    (void)q;
    (void)v;
    braun_scene_fn_eval(&e->f[0], t, &tau, NULL, NULL);
    const int ca = braun_scene__theta_col(s, e->a), cb = braun_scene__theta_col(s, e->b);
    if (ca >= 0) Q[ca] += tau;
    if (cb >= 0) Q[cb] -= tau;
    return 0;
}

static int torque_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, const braun_real *v, braun_real *P)
{
    braun_real tau, wa, wb;
    braun_scene_fn_eval(&e->f[0], t, &tau, NULL, NULL);
    braun_scene__angle(s, e->a, q, v, NULL, &wa);
    braun_scene__angle(s, e->b, q, v, NULL, &wb);
    *P = tau * (wa - wb);
    return 0;
}

/* Torques and motors act between a rigid body and a rigid body or ground. */
static const char *torque_check(const braun_scene *s, const braun_scene_effect *e)
{
    if (braun_scene__is_rigid(s, e->a) &&
        (e->b == BRAUN_SCENE_GROUND || braun_scene__is_rigid(s, e->b)) && e->a != e->b)
        return NULL;
    return "torque needs a rigid body and a different rigid body or the ground";
}

static const braun_scene_field torque_fields[] = {
    {"body", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, a),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_ANGLE, NULL},
    {"reaction", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, b),
     BRAUN_FIELD_GROUND | BRAUN_FIELD_ANGLE, NULL},
    {"torque", BRAUN_FIELD_FN, 0, offsetof(braun_scene_effect, f), BRAUN_FIELD_REQUIRED, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_torque = {
    "torque", "BRAUN_EFFECT_TORQUE", torque_fields, NULL, torque_check, torque_forces, NULL,
    torque_power, NULL, 2};
