/* Angle joint: θ_b - θ_a - α(t) = 0 (1 row), a fixed relative angle or,
 * driven, a prescribed one (a crank turned at a given rate). Linear in q:
 * A_q has +1 at θ_b and -1 at θ_a, b_q = α', b_qv = α''. Also the angle
 * row of the prismatic joint (scene_prismatic.c). */
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

enum { F_A, F_B, F_ANGLE, F_DRIVE };

/* Scene files: an angle left out is the initial relative angle. */
static void angle_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
    if (!BRAUN_FIELD_GIVEN(given, F_ANGLE))
        j->value = braun_scene_initial_angle(s, j->b) - braun_scene_initial_angle(s, j->a);
}

static const char *angle_check(const braun_scene *s, const braun_scene_joint *j)
{
    if ((j->a >= 0 && !braun_scene__is_rigid(s, j->a)) ||
        (j->b >= 0 && !braun_scene__is_rigid(s, j->b)))
        return "angle joint needs rigid bodies (or the ground)";
    return braun_scene__same_body(j->a, j->b, 0);
}

static int angle_rows(const braun_scene_joint *j)
{
    (void)j;
    return 1; /* the drive replaces the constant */
}

static int angle_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                      const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                      braun_real *b, braun_real *bv)
{
    const braun_scene_fn fixed = {BRAUN_FN_CONSTANT, j->value, 0, 0, 0};
    braun_scene__angle_rows(s, j->a, j->b, j->driven ? &j->drive : &fixed, t, q, v, phi, A, b,
                            bv);
    return 0;
}

#define BODY_FLAGS (BRAUN_FIELD_REQUIRED | BRAUN_FIELD_GROUND | BRAUN_FIELD_ANGLE)
static const braun_scene_field angle_fields[] = {
    [F_A] = {"a", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_joint, a), BODY_FLAGS, NULL},
    [F_B] = {"b", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_joint, b), BODY_FLAGS, NULL},
    [F_ANGLE] = {"angle", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_joint, value), 0, "drive"},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive), BRAUN_FIELD_SMOOTH,
                 NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_angle = {
    "angle", "BRAUN_JOINT_ANGLE", 0, angle_fields, angle_defaults, angle_check, angle_rows, NULL,
    angle_eval, 2};
