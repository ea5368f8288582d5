/* Revolute joint (pin): two points coincide, P_a - P_b = 0 (2 rows). As in
 * the paper's Eq. 22: with P'' = J v' + cc (scene_point.c),
 * Φ'' = A_q v' + cc_a - cc_b, so b_q = 0 and b_qv = cc_b - cc_a. */
#include "scene_internal.h"

static const char *revolute_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (j->driven) return "a revolute joint cannot be driven";
    return braun_scene__same_body_points(s, j->a, j->b, 0);
}

static int revolute_rows(const braun_scene_joint *j)
{
    (void)j;
    return 2;
}

static int revolute_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *phi,
                         braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    scene_pt Pa, Pb;
    (void)t;
    braun_scene__point(s, j->a, q, v, &Pa);
    braun_scene__point(s, j->b, q, v, &Pb);
    for (int k = 0; k < 2; k++) {
        if (phi) phi[k] = Pa.pos[k] - Pb.pos[k];
        if (A) {
            braun_real *row = A + braun_scene__at(k, 0, n);
            const braun_real ex = k == 0 ? BRAUN_R(1.0) : BRAUN_R(0.0), ey = 1 - ex;
            braun_scene__add_grad(&Pa, ex, ey, row);
            braun_scene__add_grad(&Pb, -ex, -ey, row);
        }
        if (b) b[k] = 0;
        if (bv) bv[k] = Pb.cc[k] - Pa.cc[k];
    }
    return 0;
}

static const braun_scene_field revolute_fields[] = {
    {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_revolute = {
    "revolute", "BRAUN_JOINT_REVOLUTE", 0, revolute_fields, NULL, revolute_check,
    revolute_rows, NULL, revolute_eval, 2};
