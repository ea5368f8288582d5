/* Point on a line: the cylindrical joint's last two rows, P (a) on the
 * line through A (b) along u1 on A's body: r1·(P - A) = 0, w1·(P - A) = 0
 * (2 rows, scene_frames.c). P's body may be a particle (no axis of its
 * own). */
#include "scene_internal.h"

enum { L_POINT, L_LINE, L_AXIS };

static void point_line_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    int b1, b2;
    (void)given;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    /* Frame 2 is not used: only frame 1 (the line's body) is filled. */
    braun_scene__frame_defaults(s, j, b1, -1, 0);
}

static const char *point_line_check(const braun_scene *s, const braun_scene_joint *j)
{
    int b1, b2;
    if (j->driven) return "a point_line joint cannot be driven";
    braun_scene__frame_bodies(s, j, &b1, &b2);
    return braun_scene__frame_check(s, j, b1, -1, 0);
}

static int point_line_rows(const braun_scene_joint *j)
{
    (void)j;
    return 2;
}

static int point_line_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                           const braun_real *q, const braun_real *v, braun_real *phi,
                           braun_real *A, braun_real *b, braun_real *bv)
{
    (void)t;
    braun_scene__line_rows(s, j, 0, q, v, phi, A, b, bv);
    return 0;
}

static const braun_scene_field point_line_fields[] = {
    [L_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [L_LINE] = {"line", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b),
                BRAUN_FIELD_REQUIRED, NULL},
    [L_AXIS] = {"axis", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_point_line = {
    "point_line", "BRAUN_JOINT_POINT_LINE", 0, point_line_fields, point_line_defaults,
    point_line_check, point_line_rows, NULL, point_line_eval, 3};
