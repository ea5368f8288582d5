/* Universal (Hooke, Cardan) joint: the points coincide (3 rows) and the
 * cross's two axes — u1 on a's body, u2 on b's body — stay perpendicular:
 * u1·u2 = 0 (1 row, scene_frames.c). */
#include "scene_internal.h"

static void universal_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    (void)s;
    (void)given;
    braun_scene__normalize3(j->axis);
    braun_scene__normalize3(j->axis_b);
}


static const char *universal_check(const braun_scene *s, const braun_scene_joint *j)
{
    const int a = braun_scene__body_of(s, j->a), b = braun_scene__body_of(s, j->b);
    if (j->driven) return "a universal joint cannot be driven";
    if (a == b) return "joint connects a body to itself";
    if (!braun_scene__has_frame(s, a) || !braun_scene__has_frame(s, b))
        return "a body of the joint has no orientation (a particle): its axes need rigid3d "
               "bodies or the ground";
    if (!braun_scene__is_unit3(j->axis) || !braun_scene__is_unit3(j->axis_b))
        return "the joint's axis and axis_b must be unit vectors (scene files and "
               "braun_scene_defaults() normalise them)";
    return NULL;
}

static int universal_rows(const braun_scene_joint *j)
{
    (void)j;
    return 4;
}

static int universal_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *phi,
                          braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    scene_pt U1, U2;
    scene_vec u1, u2;
    braun_scene__coincide_rows(s, j->a, j->b, q, v, phi, A, b, bv);
    braun_scene_dir_eval(s, braun_scene__body_of(s, j->a), j->axis, q, v, &U1);
    braun_scene_dir_eval(s, braun_scene__body_of(s, j->b), j->axis_b, q, v, &U2);
    braun_scene__vec(&u1, &U1, NULL);
    braun_scene__vec(&u2, &U2, NULL);
    braun_scene__dot_row(&u1, &u2, NULL, t, BRAUN_SCENE__AT(phi, 3), BRAUN_SCENE__ROW(A, 3, n),
                         BRAUN_SCENE__AT(b, 3), BRAUN_SCENE__AT(bv, 3));
    return 0;
}

static const braun_scene_field universal_fields[] = {
    {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    {"axis", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    {"axis_b", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis_b),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_universal = {
    "universal", "BRAUN_JOINT_UNIVERSAL", 0, universal_fields, universal_defaults,
    universal_check, universal_rows, NULL, universal_eval, 3};
