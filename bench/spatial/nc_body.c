/* Natural coordinates of a spatial rigid body (nc_body.h).
 *   P = r + X u + Y v + Z w            (linear in q: J_P constant, cc = 0)
 *   T = ½ m |r'|² + ½ Σ_ij J_ij e_i'·e_j',  J = ½ tr(I) 𝟙 - I
 *       (J_ij = ∫ X_i X_j dm, the second moments; I the inertia tensor)
 *   M = diag(m 𝟙, J ⊗ 𝟙): constant, positive definite when the second
 *       moments are (a body with volume in every direction)
 *   rows  u·u - 1, v·v - 1, w·w - 1, u·v, v·w, w·u = 0 (b_qv = -2 e_i'·e_j')
 *   ω = ½ (u × u' + v × v' + w × w')   (exact for an orthonormal frame). */
#include <stddef.h>

#include "nc_body.h"

#define AT(i, j, ld) ((size_t)(i) * (size_t)(ld) + (size_t)(j))

/* J = ½ tr(I) 𝟙 - I as a symmetric 3 x 3. */
static void moments(const braun_scene_body *b, braun_real *J)
{
    const braun_real *t = b->tensor;
    const braun_real h = (t[0] + t[1] + t[2]) / 2;
    J[0] = h - t[0], J[4] = h - t[1], J[8] = h - t[2];
    J[1] = J[3] = -t[3];
    J[2] = J[6] = -t[4];
    J[5] = J[7] = -t[5];
}

static const char *nc_check(const braun_scene *s, const braun_scene_body *b)
{
    braun_real J[9];
    (void)s;
    moments(b, J);
    if (!(b->mass > 0)) return "a body needs a mass > 0";
    const braun_real m2 = J[0] * J[4] - J[1] * J[1];
    const braun_real m3 = J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
                          J[2] * (J[3] * J[7] - J[4] * J[6]);
    if (!(J[0] > 0) || !(m2 > 0) || !(m3 > 0))
        return "natural coordinates need positive second moments (a body with volume in every "
               "direction)";
    return NULL;
}

static void nc_mass(const braun_scene_body *b, braun_real *M, int ld)
{
    braun_real J[9];
    moments(b, J);
    for (int i = 0; i < 3; i++) M[AT(i, i, ld)] += b->mass;
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
            for (int i = 0; i < 3; i++) M[AT(3 + 3 * a + i, 3 + 3 * c + i, ld)] += J[3 * a + c];
}

static braun_real nc_kinetic(const braun_scene_body *b, const braun_real *v, braun_real *dEdv)
{
    braun_real J[9], T = 0;
    moments(b, J);
    for (int i = 0; i < 3; i++) {
        T += b->mass * v[i] * v[i];
        if (dEdv) dEdv[i] += b->mass * v[i];
    }
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < 3; i++) {
            braun_real p = 0; /* (M v) at axis a, component i */
            for (int c = 0; c < 3; c++) p += J[3 * a + c] * v[3 + 3 * c + i];
            T += p * v[3 + 3 * a + i];
            if (dEdv) dEdv[3 + 3 * a + i] += p;
        }
    return T / 2;
}

/* jac[0..2] = X, Y, Z (∂P/∂e_k = X_k 𝟙). */
static void frame_vector(const braun_real *d, const braun_real *q, const braun_real *v,
                         braun_scene_pt *P)
{
    for (int k = 0; k < 3; k++) P->jac[k] = d[k];
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) {
            P->pos[i] += d[k] * q[3 + 3 * k + i];
            if (v) P->vel[i] += d[k] * v[3 + 3 * k + i];
        }
    }
}

static void nc_point(const braun_scene_body *b, const braun_scene_point *pt, const braun_real *q,
                     const braun_real *v, braun_scene_pt *P)
{
    const braun_real d[3] = {pt->x, pt->y, pt->z};
    (void)b;
    for (int i = 0; i < 3; i++) {
        P->pos[i] = q[i];
        if (v) P->vel[i] = v[i];
    }
    frame_vector(d, q, v, P);
}

static void nc_direction(const braun_scene_body *b, const braun_real *d, const braun_real *q,
                         const braun_real *v, braun_scene_pt *P)
{
    (void)b;
    for (int i = 0; i < 3; i++) P->pos[i] = 0;
    P->direction = 1;
    frame_vector(d, q, v, P);
}

static void nc_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row)
{
    if (!P->direction)
        for (int i = 0; i < 3; i++) row[i] += g[i];
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) row[3 + 3 * k + i] += P->jac[k] * g[i];
}

static void nc_weight(const braun_scene_body *b, const braun_real *g, braun_real *Q)
{
    for (int i = 0; i < 3; i++) Q[i] += b->mass * g[i];
}

static braun_real nc_gravity_potential(const braun_scene_body *b, const braun_real *g,
                                       const braun_real *q)
{
    return -(b->mass * (g[0] * q[0] + g[1] * q[1] + g[2] * q[2]));
}

/* Rows (a, c): e_a·e_c - δ_ac, in the order (0,0), (1,1), (2,2), (0,1),
 * (1,2), (2,0). */
static const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};

static void nc_constraint(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                          braun_real *phi, braun_real *A, int ld, braun_real *bv)
{
    (void)b;
    for (int r = 0; r < 6; r++) {
        const int a = pairs[r][0], c = pairs[r][1];
        const braun_real *ea = q + 3 + 3 * a, *ec = q + 3 + 3 * c;
        braun_real d = 0, dd = 0;
        for (int i = 0; i < 3; i++) d += ea[i] * ec[i];
        if (phi) phi[r] = d - (a == c);
        if (A)
            for (int i = 0; i < 3; i++) {
                A[AT(r, 3 + 3 * a + i, ld)] += ec[i];
                A[AT(r, 3 + 3 * c + i, ld)] += ea[i];
            }
        if (bv) {
            const braun_real *va = v + 3 + 3 * a, *vc = v + 3 + 3 * c;
            for (int i = 0; i < 3; i++) dd += va[i] * vc[i];
            bv[r] = -2 * dd;
        }
    }
}

/* ω = ½ Σ e_k × e_k': W = ½ [0 | ẽ_0 | ẽ_1 | ẽ_2]. */
static void nc_omega(const braun_scene_body *b, const braun_real *q, braun_real *W)
{
    (void)b;
    for (int i = 0; i < 36; i++) W[i] = 0;
    for (int k = 0; k < 3; k++) {
        const braun_real *e = q + 3 + 3 * k;
        const int c = 3 + 3 * k;
        /* row i of ẽ: ẽ = [[0, -e2, e1], [e2, 0, -e0], [-e1, e0, 0]] */
        W[0 * 12 + c + 1] = -e[2] / 2, W[0 * 12 + c + 2] = e[1] / 2;
        W[1 * 12 + c + 0] = e[2] / 2, W[1 * 12 + c + 2] = -e[0] / 2;
        W[2 * 12 + c + 0] = -e[1] / 2, W[2 * 12 + c + 1] = e[0] / 2;
    }
}

/* From rigid3d's description: e_k = R(p) ê_k, e_k' = ω × e_k. */
static void nc_initial(const braun_scene_body *b, braun_real *q, braun_real *v)
{
    const braun_real *p = b->q0 + 3, *w = b->v0 + 3;
    const braun_real e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const braun_real R[9] = {
        e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2),
        2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1),
        2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3};
    for (int i = 0; i < 3; i++) {
        q[i] = b->q0[i];
        v[i] = b->v0[i];
    }
    for (int k = 0; k < 3; k++) {
        const braun_real e[3] = {R[k], R[3 + k], R[6 + k]}; /* column k */
        for (int i = 0; i < 3; i++) q[3 + 3 * k + i] = e[i];
        v[3 + 3 * k + 0] = w[1] * e[2] - w[2] * e[1];
        v[3 + 3 * k + 1] = w[2] * e[0] - w[0] * e[2];
        v[3 + 3 * k + 2] = w[0] * e[1] - w[1] * e[0];
    }
}

static const braun_scene_field nc_fields[] = {
    {"mass", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, mass),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    {"inertia", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, tensor),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    {"products", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, tensor) + 3 * sizeof(braun_real),
     0, NULL},
    {"position", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, q0), BRAUN_FIELD_REQUIRED, NULL},
    {"orientation", BRAUN_FIELD_REAL, 4, offsetof(braun_scene_body, q0) + 3 * sizeof(braun_real),
     BRAUN_FIELD_NONZERO, NULL},
    {"velocity", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, v0), 0, NULL},
    {"omega", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, v0) + 3 * sizeof(braun_real), 0,
     NULL},
    {"points", BRAUN_FIELD_POINTS, 3, 0, 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_body_class bench_body_nc = {
    "rigid3d_nc", "&bench_body_nc", 12, 3, -1, 0u, nc_fields, nc_check,
    nc_mass, nc_kinetic, nc_point, nc_grad, nc_weight, nc_gravity_potential,
    NULL, NULL, NULL, 6, nc_constraint, nc_direction, nc_omega, nc_initial, NULL};
