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

static int motor_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, const braun_real *v, braun_real *Q)
{
    (void)t;
    const braun_real tau = e->tau0 * (1 - speed(s, e, q, v) / e->omega0);
    const int ca = braun_scene__theta_col(s, e->a), cb = braun_scene__theta_col(s, e->b);
    if (ca >= 0) Q[ca] += tau;
    if (cb >= 0) Q[cb] -= tau;
    return 0;
}

static int motor_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                       const braun_real *q, const braun_real *v, braun_real *P)
{
    (void)t;
    const braun_real w = speed(s, e, q, v);
    *P = e->tau0 * (1 - w / e->omega0) * w;
    return 0;
}

static const char *motor_check(const braun_scene *s, const braun_scene_effect *e)
{
    if (!(braun_scene__is_rigid(s, e->a) &&
          (e->b == BRAUN_SCENE_GROUND || braun_scene__is_rigid(s, e->b)) && e->a != e->b))
        return "motor needs a rigid rotor and a different rigid stator or the ground";
    if (e->omega0 == 0) return "motor no-load speed must not be 0";
    return NULL;
}

static const braun_scene_field motor_fields[] = {
    {"rotor", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, a),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_ANGLE, NULL},
    {"stator", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, b),
     BRAUN_FIELD_GROUND | BRAUN_FIELD_ANGLE, NULL},
    {"stall_torque", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, tau0), BRAUN_FIELD_REQUIRED,
     NULL},
    {"no_load_speed", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, omega0),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_motor = {
    "motor", "BRAUN_EFFECT_MOTOR", motor_fields, NULL, motor_check, motor_forces, NULL,
    motor_power, NULL, 2};
