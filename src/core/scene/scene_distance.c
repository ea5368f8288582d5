/* Distance joint: |d|² - L(t)² = 0 with d = P_b - P_a (1 row); a massless
 * rigid link between two points, or a linear actuator when driven.
 *   A_q  = 2 dᵀ (J_b - J_a)
 *   b_q  = -∂Φ/∂t = 2 L L'
 *   b_qv = -2|d'|² - 2 d·(cc_b - cc_a) + 2 (L'² + L L'')
 * (Φ'' = 2|d'|² + 2 d·(J_b v' + cc_b - J_a v' - cc_a) - 2(L'² + L L'')). */
#include "scene_internal.h"

enum { F_A, F_B, F_LENGTH, F_DRIVE };

/* Scene files: a length left out is the initial distance. */
static void distance_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
    if (!BRAUN_FIELD_GIVEN(given, F_LENGTH)) j->value = braun_scene_initial_distance(s, j->a, j->b);
}

static const char *distance_check(const braun_scene *s, const braun_scene_joint *j)
{
    const char *same = braun_scene__same_body_points(s, j->a, j->b, 0);
    if (same) return same;
    if (!j->driven && !(j->value > 0)) return "distance must be > 0";
    /* The row |P_b - P_a|^2 - L^2 cannot tell L from -L: a drive of -1 ran
     * as a length of 1, status OK. A length that starts at or below 0, or a
     * sine that reaches 0 (a + b sin: a <= |b|), is refused as `length`
     * is; a linear drive that shrinks reaches 0 at t = -a/b, where the row
     * loses its rank and the run stops. */
    if (j->driven) {
        braun_real L0 = 0;
        if (braun_scene_fn_eval(&j->drive, 0, &L0, NULL, NULL) != BRAUN_OK || !(L0 > 0))
            return "drive: the length at t = 0 must be > 0 (the row cannot tell L from -L)";
        if (j->drive.kind == BRAUN_FN_SINE && !(j->drive.a > braun_fabs(j->drive.b)))
            return "drive: a sine length a + b sin(...) must stay > 0 (offset a > |amplitude b|)";
    }
    return NULL;
}

static int distance_rows(const braun_scene_joint *j)
{
    (void)j;
    return 1; /* the drive replaces the constant */
}

static int distance_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *phi,
                         braun_real *A, braun_real *b, braun_real *bv)
{
    scene_pt Pa, Pb;
    braun_real L = j->value, dL = 0, ddL = 0;
    if (j->driven) braun_scene_fn_eval(&j->drive, t, &L, &dL, &ddL);
    braun_scene__point(s, j->a, q, v, &Pa);
    braun_scene__point(s, j->b, q, v, &Pb);
    /* In a planar scene the z terms are exact zeros: the sums are those of
     * the planar rows, bit for bit. */
    const braun_real dx = Pb.pos[0] - Pa.pos[0], dy = Pb.pos[1] - Pa.pos[1],
                     dz = Pb.pos[2] - Pa.pos[2];
    if (phi) phi[0] = dx * dx + dy * dy + dz * dz - L * L;
    if (A) {
        const braun_real gb[3] = {BRAUN_R(2.0) * dx, BRAUN_R(2.0) * dy, BRAUN_R(2.0) * dz};
        const braun_real ga[3] = {-gb[0], -gb[1], -gb[2]};
        braun_scene_pt_grad(&Pb, gb, A);
        braun_scene_pt_grad(&Pa, ga, A);
    }
    if (b) b[0] = BRAUN_R(2.0) * L * dL;
    if (bv) {
        const braun_real ux = Pb.vel[0] - Pa.vel[0], uy = Pb.vel[1] - Pa.vel[1],
                         uz = Pb.vel[2] - Pa.vel[2];
        const braun_real cx = Pb.cc[0] - Pa.cc[0], cy = Pb.cc[1] - Pa.cc[1],
                         cz = Pb.cc[2] - Pa.cc[2];
        bv[0] = BRAUN_R(-2.0) * (ux * ux + uy * uy + uz * uz) -
                BRAUN_R(2.0) * (dx * cx + dy * cy + dz * cz);
        if (j->driven) bv[0] += BRAUN_R(2.0) * (dL * dL + L * ddL);
    }
    return 0;
}

static const braun_scene_field distance_fields[] = {
    [F_A] = {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
    [F_B] = {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED, NULL},
    [F_LENGTH] = {"length", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_joint, value),
                  BRAUN_FIELD_POSITIVE, "drive"},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive), BRAUN_FIELD_SMOOTH,
                 NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_distance = {
    "distance", "BRAUN_JOINT_DISTANCE", 0, distance_fields, distance_defaults, distance_check,
    distance_rows, NULL, distance_eval, 0};
