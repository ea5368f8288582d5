/* Point in a plane: point P (a) stays in the plane through A (b) with
 * normal n on A's body: n·(P - A) = 0 (1 row, scene_frames.c). P's body may
 * be a particle. */
#include "scene_internal.h"

static void point_plane_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    (void)s;
    (void)given;
    braun_scene__normalize3(j->axis);
}

static const char *point_plane_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (j->driven) return "a point_plane joint cannot be driven";
    const char *same = braun_scene__same_body_points(s, j->a, j->b, 0);
    if (same) return same;
    if (!braun_scene__has_frame(s, braun_scene__body_of(s, j->b)))
        return "the plane's body has no orientation (a particle): it must be a rigid3d body or "
               "the ground";
    if (!braun_scene__is_unit3(j->axis))
        return "the plane's normal must be a unit vector (scene files and braun_scene_defaults() "
               "normalise it)";
    return NULL;
}

static int point_plane_rows(const braun_scene_joint *j)
{
    (void)j;
    return 1;
}

static int point_plane_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv)
{
    scene_pt P, Pa, N;
    scene_vec e, nv;
    braun_scene__point(s, j->a, q, v, &P);
    braun_scene__point(s, j->b, q, v, &Pa);
    braun_scene_dir_eval(s, braun_scene__body_of(s, j->b), j->axis, q, v, &N);
    braun_scene__vec(&e, &P, &Pa);
    braun_scene__vec(&nv, &N, NULL);
    braun_scene__dot_row(&nv, &e, NULL, t, phi, A, b, bv);
    return 0;
}

static const braun_scene_field point_plane_fields[] = {
    {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    {"plane", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    {"normal", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_joint, axis),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO | BRAUN_FIELD_UNIT, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_point_plane = {
    "point_plane", "BRAUN_JOINT_POINT_PLANE", 0, point_plane_fields, point_plane_defaults,
    point_plane_check, point_plane_rows, NULL, point_plane_eval, 3};
