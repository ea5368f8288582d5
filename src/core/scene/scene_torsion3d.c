/* Rotational spring and damper on the angle θ of a revolute3d or
 * cylindrical joint (θ = 0 in the initial configuration, scene_frames.c):
 * with δ = θ - rest taken in (-π, π],
 *   Q += -(k δ + c θ') ∂θ/∂q,  potential V = ½ k δ²,  input power -c θ'². */
#include "scene_internal.h"

/* δ in (-π, π]: the turns taken off in one operation (a loop of 2π
 * subtractions took minutes, and piled up rounding, for a rest_angle of
 * 1e12, which the scene format allows). The rest angle is wrapped
 * first: th - 1e12 kept th to 1e-4 rad only. */
static braun_real wrap(braun_real x)
{
    const braun_real pi = BRAUN_SCENE__PI, two_pi = 2 * BRAUN_SCENE__PI;
    if (x > pi || x <= -pi) x -= two_pi * braun_floor((x + pi) / two_pi);
    if (x > pi) x -= two_pi; /* rounding at the ends */
    if (x <= -pi) x += two_pi;
    return x;
}

static const braun_scene_joint *joint_of(const braun_scene *s, const braun_scene_effect *e)
{
    return &s->joints[e->a];
}

static int torsion3d_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *Q)
{
    braun_real th, rate;
    (void)t;
    braun_scene__joint_angle(s, joint_of(s, e), q, v, &th, &rate, 0, NULL);
    const braun_real tau = -(e->k * wrap(th - wrap(e->rest)) + e->c * rate);
    braun_scene__joint_angle(s, joint_of(s, e), q, NULL, &th, NULL, tau, Q);
    return 0;
}

static int torsion3d_potential(const braun_scene *s, const braun_scene_effect *e,
                               const braun_real *q, braun_real *V, braun_real *dVdq)
{
    braun_real th;
    braun_scene__joint_angle(s, joint_of(s, e), q, NULL, &th, NULL, 0, NULL);
    const braun_real d = wrap(th - wrap(e->rest));
    *V = BRAUN_R(0.5) * e->k * d * d;
    if (dVdq) braun_scene__joint_angle(s, joint_of(s, e), q, NULL, &th, NULL, e->k * d, dVdq);
    return 0;
}

static int torsion3d_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                           const braun_real *q, const braun_real *v, braun_real *P)
{
    braun_real th, rate;
    (void)t;
    braun_scene__joint_angle(s, joint_of(s, e), q, v, &th, &rate, 0, NULL);
    *P = -e->c * rate * rate;
    return 0;
}

static int torsion3d_inputs(const braun_scene_effect *e)
{
    return e->c != 0;
}

/* The joint must have an axis and an angle about it. */
static const char *torsion3d_check(const braun_scene *s, const braun_scene_effect *e)
{
    const braun_scene_joint_class *c = s->joints[e->a].type;
    if (c != &braun_scene_joint_revolute3d && c != &braun_scene_joint_cylindrical)
        return "the joint of a torsion3d must be a revolute3d or cylindrical joint";
    if (e->k < 0 || e->c < 0) return "stiffness and damping must be >= 0";
    return NULL;
}

static const braun_scene_field torsion3d_fields[] = {
    {"joint", BRAUN_FIELD_JOINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    {"stiffness", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, k), BRAUN_FIELD_NONNEG, NULL},
    {"damping", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, c), BRAUN_FIELD_NONNEG, NULL},
    {"rest_angle", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, rest), 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_torsion3d = {
    "torsion3d", "BRAUN_EFFECT_TORSION3D", torsion3d_fields, NULL, torsion3d_check,
    torsion3d_forces, torsion3d_potential, torsion3d_power, torsion3d_inputs, 3};
