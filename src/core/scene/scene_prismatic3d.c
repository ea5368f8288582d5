/* Spatial prismatic joint: point P (a) slides along the line through A (b)
 * with direction u1 on A's body, and the two bodies keep their initial
 * relative orientation. With e = P - A and the frames of scene_frames.c
 * (frame 1 on the line's body):
 *   u1·r2 = 0, r1·w2 = 0, w1·u2 = 0     (orientation, 3 rows)
 *   r1·e = 0, w1·e = 0                 (P on the line, 2 rows)
 *   driven: u1·e - f(t) = 0            (1 row; b_q = f', b_qv += f'') */
#include "scene_internal.h"

enum { F_POINT, F_LINE, F_AXIS, F_DRIVE };

static void prismatic3d_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    int b1, b2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
    braun_scene__frame_defaults(s, j, b1, b2, 0);
}

static const char *prismatic3d_check(const braun_scene *s, const braun_scene_joint *j)
{
    int b1, b2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    return braun_scene__frame_check(s, j, b1, b2, 1);
}

static int prismatic3d_rows(const braun_scene_joint *j)
{
    return j->driven ? 6 : 5;
}

static int prismatic3d_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    int b1, b2;
    scene_frames F;
    scene_pt P, Pa;
    scene_vec e, r1, w1, u1;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    braun_scene__frames(s, j, b1, b2, q, v, &F);
    braun_scene__orient_rows(&F, phi, A, n, b, bv);
    braun_scene__point(s, j->a, q, v, &P);
    braun_scene__point(s, j->b, q, v, &Pa);
    braun_scene__vec(&e, &P, &Pa);
    braun_scene__vec(&r1, &F.r1, NULL);
    braun_scene__vec(&w1, &F.w1, NULL);
    braun_scene__dot_row(&r1, &e, NULL, t, BRAUN_SCENE__AT(phi, 3), BRAUN_SCENE__ROW(A, 3, n),
                         BRAUN_SCENE__AT(b, 3), BRAUN_SCENE__AT(bv, 3));
    braun_scene__dot_row(&w1, &e, NULL, t, BRAUN_SCENE__AT(phi, 4), BRAUN_SCENE__ROW(A, 4, n),
                         BRAUN_SCENE__AT(b, 4), BRAUN_SCENE__AT(bv, 4));
    if (j->driven) {
        braun_scene__vec(&u1, &F.u1, NULL);
        braun_scene__dot_row(&u1, &e, &j->drive, t, BRAUN_SCENE__AT(phi, 5),
                             BRAUN_SCENE__ROW(A, 5, n), BRAUN_SCENE__AT(b, 5),
                             BRAUN_SCENE__AT(bv, 5));
    }
    return 0;
}

static const braun_scene_field prismatic3d_fields[] = {
    [F_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [F_LINE] = {"line", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b),
                BRAUN_FIELD_REQUIRED, NULL},
    [F_AXIS] = {"axis", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive),
                 BRAUN_FIELD_SMOOTH, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_prismatic3d = {
    "prismatic3d", "BRAUN_JOINT_PRISMATIC3D", 0, prismatic3d_fields, prismatic3d_defaults,
    prismatic3d_check, prismatic3d_rows, NULL, prismatic3d_eval, 3};
