/* Spherical joint (ball and socket): two points coincide in space,
 * P_a - P_b = 0 (3 rows); b_q = 0, b_qv = cc_b - cc_a (scene_frames.c). */
#include "scene_internal.h"

static const char *spherical_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (j->driven) return "a spherical joint cannot be driven";
    return braun_scene__same_body_points(s, j->a, j->b, 0);
}

static int spherical_rows(const braun_scene_joint *j)
{
    (void)j;
    return 3;
}

static int spherical_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *phi,
                          braun_real *A, braun_real *b, braun_real *bv)
{
    (void)t;
    braun_scene__coincide_rows(s, j->a, j->b, q, v, phi, A, b, bv);
    return 0;
}

static const braun_scene_field spherical_fields[] = {
    {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_spherical = {
    "spherical", "BRAUN_JOINT_SPHERICAL", 0, spherical_fields, NULL, spherical_check,
    spherical_rows, NULL, spherical_eval, 3};
