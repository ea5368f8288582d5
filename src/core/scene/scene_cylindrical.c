/* Cylindrical joint: point P (a) stays on the line through A (b) with
 * direction u1 on A's body, and P's body keeps its axis u2 parallel to u1
 * (it may turn about and slide along the line). With e = P - A and the
 * frames of scene_frames.c (frame 1 on the line's body):
 *   r1·u2 = 0, w1·u2 = 0       (axes parallel, 2 rows)
 *   r1·e = 0, w1·e = 0         (P on the line, 2 rows) */
#include "scene_internal.h"

enum { F_POINT, F_LINE, F_AXIS, F_AXIS_B };

static void cylindrical_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    int b1, b2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    braun_scene__frame_defaults(s, j, b1, b2, (int)BRAUN_FIELD_GIVEN(given, F_AXIS_B));
}

static const char *cylindrical_check(const braun_scene *s, const braun_scene_joint *j)
{
    int b1, b2;
    if (j->driven) return "a cylindrical joint cannot be driven";
    braun_scene__frame_bodies(s, j, &b1, &b2);
    return braun_scene__frame_check(s, j, b1, b2, 1);
}

static int cylindrical_rows(const braun_scene_joint *j)
{
    (void)j;
    return 4;
}

static int cylindrical_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv)
{
    (void)t;
    braun_scene__line_rows(s, j, 1, q, v, phi, A, b, bv);
    return 0;
}

static const braun_scene_field cylindrical_fields[] = {
    [F_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [F_LINE] = {"line", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b),
                BRAUN_FIELD_REQUIRED, NULL},
    [F_AXIS] = {"axis", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    [F_AXIS_B] = {"axis_b", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis_b),
                  BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_cylindrical = {
    "cylindrical", "BRAUN_JOINT_CYLINDRICAL", 0, cylindrical_fields, cylindrical_defaults,
    cylindrical_check, cylindrical_rows, NULL, cylindrical_eval, 3};

