/* Weld (rigid, fixed) joint: the points coincide (3 rows) and the two
 * bodies keep their initial relative orientation (3 rows u1·r2, r1·w2,
 * w1·u2 = 0 of two body-fixed frames that coincide initially,
 * scene_frames.c): no relative motion at all. */
#include "scene_internal.h"

static void weld_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    (void)given;
    if (braun_scene__dot3(j->axis, j->axis) == 0) j->axis[0] = 1; /* a's body x axis */
    braun_scene__frame_defaults(s, j, braun_scene__body_of(s, j->a),
                                braun_scene__body_of(s, j->b), 0);
}

static const char *weld_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (j->driven) return "a weld cannot be driven";
    return braun_scene__frame_check(s, j, braun_scene__body_of(s, j->a),
                                    braun_scene__body_of(s, j->b), 1);
}

static int weld_rows(const braun_scene_joint *j)
{
    (void)j;
    return 6;
}

static int weld_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                     const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                     braun_real *b, braun_real *bv)
{
    const int n = s->n;
    scene_frames F;
    (void)t;
    braun_scene__coincide_rows(s, j->a, j->b, q, v, phi, A, b, bv);
    braun_scene__frames(s, j, braun_scene__body_of(s, j->a), braun_scene__body_of(s, j->b), q, v,
                        &F);
    braun_scene__orient_rows(&F, BRAUN_SCENE__AT(phi, 3), BRAUN_SCENE__ROW(A, 3, n), n,
                             BRAUN_SCENE__AT(b, 3), BRAUN_SCENE__AT(bv, 3));
    return 0;
}

static const braun_scene_field weld_fields[] = {
    {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_weld = {
    "weld", "BRAUN_JOINT_WELD", 0, weld_fields, weld_defaults, weld_check, weld_rows, NULL,
    weld_eval, 3};
