/* Spatial revolute joint (hinge): the points coincide (3 rows) and the
 * axis u1 on a's body stays parallel to u2 on b's body (2 rows: r1·u2 = 0,
 * w1·u2 = 0, scene_frames.c). Driven, the angle θ of b's body about the
 * axis — 0 in the initial configuration — follows f(t): one more row
 * cos f (w1·r2) - sin f (r1·r2) = 0, i.e. |r1||r2| sin(θ - f) = 0: θ = f
 * near the initial configuration (the other zero, θ = f + π, is a
 * half-turn away), so a drive starts at f(0) = 0. */
#include "scene_internal.h"

enum { F_A, F_B, F_AXIS, F_AXIS_B, F_DRIVE };

static void revolute3d_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    int b1, b2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
    braun_scene__frame_defaults(s, j, b1, b2, (int)BRAUN_FIELD_GIVEN(given, F_AXIS_B));
}

static const char *revolute3d_check(const braun_scene *s, const braun_scene_joint *j)
{
    int b1, b2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    const char *why = braun_scene__frame_check(s, j, b1, b2, 1);
    if (why || !j->driven) return why;
    /* θ(0) = 0: the row's nearest zero is θ = f(0) only while cos f(0) > 0;
     * beyond π/2 it is f(0) ∓ π, which the run would hold (exit 0, the
     * mechanism half a turn off the drive). */
    braun_real f0 = 0, df = 0, ddf = 0;
    braun_scene_fn_eval(&j->drive, 0, &f0, &df, &ddf);
    braun_real S, C;
    braun_sincos(f0, &S, &C);
    if (!(C > 0))
        return "drive: f(0) is pi/2 or more from the joint's initial angle, 0 (the angle is measured "
               "from the initial configuration), where the row sin(theta - f) = 0 would hold "
               "theta = f - pi instead: give a drive with f(0) near 0, or start the bodies at the "
               "driven angle";
    return NULL;
}

static int revolute3d_rows(const braun_scene_joint *j)
{
    return j->driven ? 6 : 5;
}

static int revolute3d_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                           const braun_real *q, const braun_real *v, braun_real *phi,
                           braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    int b1, b2;
    scene_frames F;
    braun_scene__coincide_rows(s, j->a, j->b, q, v, phi, A, b, bv);
    braun_scene__frame_bodies(s, j, &b1, &b2);
    braun_scene__frames(s, j, b1, b2, q, v, &F);
    braun_scene__parallel_rows(&F, BRAUN_SCENE__AT(phi, 3), BRAUN_SCENE__ROW(A, 3, n), n,
                               BRAUN_SCENE__AT(b, 3), BRAUN_SCENE__AT(bv, 3));
    if (j->driven)
        braun_scene__drive_row(&F, &j->drive, t, BRAUN_SCENE__AT(phi, 5),
                               BRAUN_SCENE__ROW(A, 5, n), BRAUN_SCENE__AT(b, 5),
                               BRAUN_SCENE__AT(bv, 5));
    return 0;
}

static const braun_scene_field revolute3d_fields[] = {
    [F_A] = {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    [F_B] = {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    [F_AXIS] = {"axis", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    [F_AXIS_B] = {"axis_b", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis_b),
                  BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive),
                 BRAUN_FIELD_SMOOTH, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_revolute3d = {
    "revolute3d", "BRAUN_JOINT_REVOLUTE3D", 0, revolute3d_fields, revolute3d_defaults,
    revolute3d_check, revolute3d_rows, NULL, revolute3d_eval, 3};
