/* A motor on the axis of a revolute3d or cylindrical joint: torque–speed
 * law τ = τ0 (1 - θ'/ω0) about the axis, on the body turning about it (the
 * joint's second frame) and -τ on the axis's body:
 *   Q += τ ∂θ/∂q,  input power Ė = τ θ'. */
#include "scene_internal.h"

static braun_real torque(const braun_scene_effect *e, braun_real rate)
{
    return e->tau0 * (1 - rate / e->omega0);
}

static int motor3d_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *Q)
{
    braun_real th, rate;
    (void)t;
    braun_scene__joint_angle(s, &s->joints[e->a], q, v, &th, &rate, 0, NULL);
    braun_scene__joint_angle(s, &s->joints[e->a], q, NULL, &th, NULL, torque(e, rate), Q);
    return 0;
}

static int motor3d_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *P)
{
    braun_real th, rate;
    (void)t;
    braun_scene__joint_angle(s, &s->joints[e->a], q, v, &th, &rate, 0, NULL);
    *P = torque(e, rate) * rate;
    return 0;
}

static const char *motor3d_check(const braun_scene *s, const braun_scene_effect *e)
{
    const braun_scene_joint_class *c = s->joints[e->a].type;
    if (c != &braun_scene_joint_revolute3d && c != &braun_scene_joint_cylindrical)
        return "the joint of a motor3d must be a revolute3d or cylindrical joint";
    if (e->omega0 == 0) return "a motor's no-load speed must not be 0";
    return NULL;
}

static const braun_scene_field motor3d_fields[] = {
    {"joint", BRAUN_FIELD_JOINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"stall_torque", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, tau0), BRAUN_FIELD_REQUIRED,
     NULL},
    {"no_load_speed", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, omega0),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_motor3d = {
    "motor3d", "BRAUN_EFFECT_MOTOR3D", motor3d_fields, NULL, motor3d_check, motor3d_forces, NULL,
    motor3d_power, NULL, 3};
