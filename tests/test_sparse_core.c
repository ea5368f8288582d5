/* Sparse system structure through libbraun's built-in dense kernels: the
 * compressed A and block M a sparse system's callbacks write are scattered
 * into the dense matrices, so a sparse chain must follow exactly the path of
 * the same chain written densely. Also: validation of the pattern, sizes. */
#include "test_util.h"

/* Planar chain of NL rigid links (x, y, θ each; length 1, mass 1), hanging
 * from the origin by revolute joints; optional duplicated first joint
 * (redundant rows) and a knife edge on the last link (nonholonomic row).
 * The mass block is SPD but not diagonal, so the block scatter is tested. */
#define NL 5
#define NMAX (3 * NL)
typedef struct chain {
    int sparse, redundant, knife;
    int m, p;
    int row_ptr[2 * NL + 4], col[(2 * NL + 4) * 6], block[NL];
    braun_sparsity sp;
} chain;

static const double Mb[9] = {1.0, 0.1, 0.0, 0.1, 1.0, 0.05, 0.0, 0.05, 1.0 / 12};

/* Joint k (0: link 0 to the ground) rows: end a of link k minus end b of
 * link k-1: r_k - ½e_k - (r_{k-1} + ½e_{k-1}), e = (cos θ, sin θ). */
static void joint_rows(int k, const double *q, const double *v, double *phi, double rowA[2][6],
                       double *bv)
{
    const double *a = q + 3 * k, *va = v + 3 * k;
    double ca = cos(a[2]), sa = sin(a[2]);
    double px = a[0] - 0.5 * ca, py = a[1] - 0.5 * sa;
    double ax = -0.5 * va[2] * va[2] * ca, ay = -0.5 * va[2] * va[2] * sa; /* ½θ'² e */
    double r0[6] = {1, 0, 0.5 * sa, 0, 0, 0}, r1[6] = {0, 1, -0.5 * ca, 0, 0, 0};
    if (k > 0) {
        const double *b = q + 3 * (k - 1), *vb = v + 3 * (k - 1);
        double cb = cos(b[2]), sb = sin(b[2]);
        px -= b[0] + 0.5 * cb;
        py -= b[1] + 0.5 * sb;
        ax -= 0.5 * vb[2] * vb[2] * cb;
        ay -= 0.5 * vb[2] * vb[2] * sb;
        r0[3] = -1, r0[5] = 0.5 * sb;
        r1[4] = -1, r1[5] = -0.5 * cb;
    }
    if (phi) phi[0] = px, phi[1] = py;
    /* Φ̈ = A v' - b_v with b_v = -(∂(A v)/∂q) v. */
    if (bv) bv[0] = ax, bv[1] = ay;
    for (int j = 0; j < 6; j++) rowA[0][j] = r0[j], rowA[1][j] = r1[j];
}

static int joint_of_row(const chain *c, int r) { return c->redundant && r >= 2 * NL ? 0 : r / 2; }

/* Columns of a joint's row: link k's then link k-1's coordinates. */
static int row_cols(int k, int *cols)
{
    int nc = 0;
    if (k > 0)
        for (int j = 0; j < 3; j++) cols[nc++] = 3 * (k - 1) + j;
    for (int j = 0; j < 3; j++) cols[nc++] = 3 * k + j;
    return nc;
}

static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const chain *c = user;
    (void)t, (void)q;
    if (c->sparse) {
        for (int k = 0; k < NL; k++)
            for (int i = 0; i < 9; i++) M[9 * k + i] = Mb[i];
        return 0;
    }
    for (int i = 0; i < NMAX * NMAX; i++) M[i] = 0;
    for (int k = 0; k < NL; k++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) M[(3 * k + i) * NMAX + 3 * k + j] = Mb[3 * i + j];
    return 0;
}

static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                  void *user)
{
    (void)t, (void)q, (void)v, (void)user;
    for (int i = 0; i < NMAX; i++) Q[i] = (i % 3 == 1) ? -9.81 : 0;
    return 0;
}

static int holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                     braun_real *A, braun_real *b, braun_real *bv, void *user)
{
    const chain *c = user;
    (void)t;
    for (int r = 0; r < c->m; r += 2) {
        double rowA[2][6], ph[2], bb[2];
        int k = joint_of_row(c, r), cols[6];
        joint_rows(k, q, v, ph, rowA, bb);
        int nc = row_cols(k, cols);
        for (int i = 0; i < 2; i++) {
            if (phi) phi[r + i] = ph[i];
            if (b) b[r + i] = 0;
            if (bv) bv[r + i] = bb[i];
            if (!A) continue;
            /* rowA lists link k (0..2) then link k-1 (3..5); cols are sorted. */
            for (int j = 0; j < nc; j++) {
                double val = k > 0 ? (j < 3 ? rowA[i][3 + j] : rowA[i][j - 3]) : rowA[i][j];
                if (c->sparse) A[c->row_ptr[r + i] + j] = val;
                else A[(r + i) * NMAX + cols[j]] = val;
            }
            if (!c->sparse)
                for (int j = 0; j < NMAX; j++) {
                    int in = 0;
                    for (int l = 0; l < nc; l++) in |= cols[l] == j;
                    if (!in) A[(r + i) * NMAX + j] = 0;
                }
        }
    }
    return 0;
}

/* Knife edge on the last link: no velocity across it. */
static int knife(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                 braun_real *A, braun_real *bv, void *user)
{
    const chain *c = user;
    const int o = 3 * (NL - 1);
    double s = sin(q[o + 2]), co = cos(q[o + 2]);
    (void)t;
    if (phi) phi[0] = -s * v[o] + co * v[o + 1];
    if (bv) bv[0] = (co * v[o] + s * v[o + 1]) * v[o + 2];
    if (A) {
        double row[3] = {-s, co, 0};
        if (c->sparse) {
            for (int j = 0; j < 3; j++) A[j] = row[j];
        } else {
            for (int j = 0; j < NMAX; j++) A[j] = 0;
            for (int j = 0; j < 3; j++) A[o + j] = row[j];
        }
    }
    return 0;
}

static int energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                  braun_real *dEdq, braun_real *dEdv, braun_real *dEdt, void *user)
{
    double T = 0, V = 0;
    (void)t, (void)user;
    for (int k = 0; k < NL; k++)
        for (int i = 0; i < 3; i++) {
            double Mv = 0;
            for (int j = 0; j < 3; j++) Mv += Mb[3 * i + j] * v[3 * k + j];
            T += 0.5 * v[3 * k + i] * Mv;
            if (dEdv) dEdv[3 * k + i] = Mv;
            if (dEdq) dEdq[3 * k + i] = i == 1 ? 9.81 : 0;
            if (i == 1) V += 9.81 * q[3 * k + 1];
        }
    if (E) *E = T + V;
    if (dEdt) *dEdt = 0;
    return 0;
}

static braun_system chain_system(chain *c, int sparse, int redundant, int knife_row)
{
    c->sparse = sparse;
    c->redundant = redundant;
    c->knife = knife_row;
    c->m = 2 * NL + (redundant ? 2 : 0);
    c->p = knife_row ? 1 : 0;
    int nnz = 0;
    c->row_ptr[0] = 0;
    for (int r = 0; r < c->m; r++) {
        int cols[6], nc = row_cols(joint_of_row(c, r), cols);
        for (int j = 0; j < nc; j++) c->col[nnz++] = cols[j];
        c->row_ptr[r + 1] = nnz;
    }
    if (knife_row) {
        for (int j = 0; j < 3; j++) c->col[nnz++] = 3 * (NL - 1) + j;
        c->row_ptr[c->m + 1] = nnz;
    }
    for (int k = 0; k < NL; k++) c->block[k] = 3;
    c->sp = (braun_sparsity){c->row_ptr, c->col, NL, c->block};
    braun_system s = {NMAX, c->m, c->p, BRAUN_MASS_CONSTANT, mass, forces, holonomic,
                      knife_row ? knife : NULL, energy, NULL, c, sparse ? &c->sp : NULL, NULL};
    return s;
}

/* A consistent start: links hanging at angles θ_k, at rest (with a knife the
 * rest state satisfies the knife row too). */
static void chain_state(double *q, double *v)
{
    double x = 0, y = 0;
    for (int k = 0; k < NL; k++) {
        double th = -1.0 + 0.2 * k, c = cos(th), s = sin(th);
        q[3 * k] = x + 0.5 * c, q[3 * k + 1] = y + 0.5 * s, q[3 * k + 2] = th;
        x += c, y += s;
        v[3 * k] = v[3 * k + 1] = v[3 * k + 2] = 0;
    }
}

/* Dense and sparse forms of one chain, stepped side by side. */
static void run_pair(int redundant, int knife_row, braun_method method, int steps)
{
    chain cd, cs;
    braun_system sd = chain_system(&cd, 0, redundant, knife_row);
    braun_system ss = chain_system(&cs, 1, redundant, knife_row);
    test_sim a, b;
    assert_int_equal(test_sim_open(&a, &sd, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(test_sim_open(&b, &ss, BRAUN_CORRECT_ALL), BRAUN_OK);
    double q[NMAX], v[NMAX];
    chain_state(q, v);
    /* A small inconsistency so the position and velocity corrections act. */
    q[0] += 1e-4;
    v[5] = 0.3;
    assert_int_equal(braun_set_state(&a.data, 0, q, v), BRAUN_OK);
    assert_int_equal(braun_set_state(&b.data, 0, q, v), BRAUN_OK);
    for (int i = 0; i < steps; i++) {
        assert_int_equal(braun_step(&a.data, method, 1e-3), BRAUN_OK);
        assert_int_equal(braun_step(&b.data, method, 1e-3), BRAUN_OK);
    }
    /* Same dense matrices, same kernels: the same numbers, bit for bit. */
    assert_memory_equal(a.data.q, b.data.q, sizeof(double) * NMAX);
    assert_memory_equal(a.data.v, b.data.v, sizeof(double) * NMAX);
    assert_int_equal(a.data.stats.rank_deficient, b.data.stats.rank_deficient);
    if (redundant) assert_true(b.data.stats.rank_deficient > 0);
    double pa, va, ea, pb, vb, eb;
    assert_int_equal(braun_residuals(&a.data, a.data.t, a.data.q, a.data.v, &pa, &va, &ea), 0);
    assert_int_equal(braun_residuals(&b.data, b.data.t, b.data.q, b.data.v, &pb, &vb, &eb), 0);
    assert_true(pa == pb && va == vb && ea == eb);
    /* The corrections did their work: the 1e-4 start error is down to the
     * local error of the method (O(h^3) for Heun, O(h^5) for RK4). */
    assert_le(pb, method == BRAUN_RK4 ? 1e-9 : 1e-8);
    test_sim_close(&a);
    test_sim_close(&b);
}

static void test_sparse_equals_dense(void **state)
{
    (void)state;
    run_pair(0, 0, BRAUN_RK4, 300);
}

static void test_sparse_redundant_rows(void **state)
{
    (void)state;
    run_pair(1, 0, BRAUN_RK4, 300);
}

static void test_sparse_nonholonomic_rows(void **state)
{
    (void)state;
    run_pair(0, 1, BRAUN_RK4, 300);
    run_pair(1, 1, BRAUN_HEUN, 100);
}

static void test_sparse_adaptive(void **state)
{
    (void)state;
    chain cd, cs;
    braun_system sd = chain_system(&cd, 0, 0, 0), ss = chain_system(&cs, 1, 0, 0);
    test_sim a, b;
    assert_int_equal(test_sim_open(&a, &sd, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(test_sim_open(&b, &ss, BRAUN_CORRECT_ALL), BRAUN_OK);
    double q[NMAX], v[NMAX];
    chain_state(q, v);
    assert_int_equal(braun_set_state(&a.data, 0, q, v), BRAUN_OK);
    assert_int_equal(braun_set_state(&b.data, 0, q, v), BRAUN_OK);
    braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&a.data, &ctl, 1.0, 1, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_integrate_adaptive(&b.data, &ctl, 1.0, 1, NULL, NULL), BRAUN_OK);
    assert_memory_equal(a.data.q, b.data.q, sizeof(double) * NMAX);
    assert_int_equal(a.data.stats.steps, b.data.stats.steps);
    test_sim_close(&a);
    test_sim_close(&b);
}

static void test_sparsity_validation(void **state)
{
    (void)state;
    chain c;
    braun_model model;
    braun_system s = chain_system(&c, 1, 0, 0);
    assert_int_equal(braun_model_init(&model, &s), BRAUN_OK);
    /* Unsorted columns in a row. */
    int t = c.col[0];
    c.col[0] = c.col[1], c.col[1] = t;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
    c.col[1] = c.col[0], c.col[0] = t;
    /* A column outside the matrix. */
    c.col[c.row_ptr[2 * NL] - 1] = NMAX;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
    c.col[c.row_ptr[2 * NL] - 1] = NMAX - 1;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_OK);
    /* Decreasing row pointers. */
    c.row_ptr[3] = c.row_ptr[2] - 1;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
    chain_system(&c, 1, 0, 0);
    /* Blocks that do not tile the diagonal. */
    c.block[0] = 2;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
    c.block[0] = 0;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
    c.block[0] = 3;
    c.sp.nblocks = 0;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_ARGUMENT);
}

/* Dense systems stay within 4096; a sparsity lifts the bound, but the
 * built-in kernels are dense and refuse what they cannot index. */
static void test_sizes(void **state)
{
    (void)state;
    static int row_ptr[1] = {0}, block[1] = {5000};
    braun_sparsity sp = {row_ptr, NULL, 1, block};
    braun_system s = {5000, 0, 0, BRAUN_MASS_CONSTANT, mass, forces, NULL, NULL, NULL, NULL,
                      NULL, NULL, NULL};
    braun_model model;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_ERR_SIZE);
    s.sparsity = &sp;
    assert_int_equal(braun_model_init(&model, &s), BRAUN_OK);
    assert_int_equal(braun_data_size(&model), 0);
    braun_data d;
    char buf[64];
    assert_int_equal(braun_data_init(&d, &model, buf, sizeof buf), BRAUN_ERR_SIZE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sparse_equals_dense),
        cmocka_unit_test(test_sparse_redundant_rows),
        cmocka_unit_test(test_sparse_nonholonomic_rows),
        cmocka_unit_test(test_sparse_adaptive),
        cmocka_unit_test(test_sparsity_validation),
        cmocka_unit_test(test_sizes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
