/* Linear-algebra kernels: Cholesky and the rank-revealing pseudoinverse,
 * checked against definitions (Moore–Penrose conditions), not against
 * numbers the code printed. */
#include "test_util.h"
#include "braun_linalg.h"
#include "braun_sincos.h"
#include "braun_dense.h"

#include <string.h>

#define NMAX 8

static double frand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffff) / 32768.0 - 1.0;
}

static int chol_ints[16];
static braun_real chol_reals[64];

static braun_chol chol_of(int n)
{
    braun_chol c;
    braun_chol_bind(&c, n, chol_reals, chol_ints);
    return c;
}

static void test_chol_known(void **state)
{
    (void)state;
    /* M = R^T R with R = [2 1 0; 0 3 1; 0 0 4]. */
    const braun_real Rk[9] = {2, 1, 0, 0, 3, 1, 0, 0, 4};
    braun_real M[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += Rk[k * 3 + i] * Rk[k * 3 + j];
            M[i * 3 + j] = s;
        }
    braun_chol c = chol_of(3);
    assert_int_equal(braun_chol_factor(&c, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    for (int i = 0; i < 9; i++) assert_near(c.R[i], Rk[i], 1e-14);
    /* Envelope: column 2 starts at row 1, row 0 ends at column 1. */
    assert_int_equal(c.first[2], 1);
    assert_int_equal(c.last[0], 1);
    /* Solves: R^-T then R^-1 of M x gives x. */
    braun_real x[3] = {1, -2, 3}, y[3];
    braun_gemv(3, 3, M, x, y);
    braun_chol_solve_rt(&c, y);
    braun_chol_solve_r(&c, y);
    for (int i = 0; i < 3; i++) assert_near(y[i], x[i], 1e-13);
}

/* Block-diagonal M: the envelope skips the zero blocks and the solves are
 * still exact. */
static void test_chol_envelope(void **state)
{
    (void)state;
    const braun_real M[16] = {4, 1, 0, 0, 1, 3, 0, 0, 0, 0, 2, 0.5, 0, 0, 0.5, 1};
    braun_chol c = chol_of(4);
    assert_int_equal(braun_chol_factor(&c, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(c.first[2], 2);
    assert_int_equal(c.first[3], 2);
    assert_int_equal(c.last[1], 1);
    braun_real x[4] = {0.3, -1, 2, 0.7}, y[4];
    braun_gemv(4, 4, M, x, y);
    braun_chol_solve_rt(&c, y);
    braun_chol_solve_r(&c, y);
    for (int i = 0; i < 4; i++) assert_near(y[i], x[i], 1e-14);
}

static void test_chol_rejects(void **state)
{
    (void)state;
    int bi = -1, bj = -1;
    braun_real bad = 0;
    braun_chol c = chol_of(3);
    const braun_real asym[9] = {2, 1, 0, 0.5, 2, 0, 0, 0, 2};
    assert_int_equal(braun_chol_factor(&c, asym, 1e-12, &bi, &bj, &bad),
                     BRAUN_ERR_MASS_NOT_SYMMETRIC);
    assert_int_equal(bi, 0);
    assert_int_equal(bj, 1);
    const braun_real indef[9] = {1, 2, 0, 2, 1, 0, 0, 0, 1};
    assert_int_equal(braun_chol_factor(&c, indef, 1e-12, &bi, &bj, &bad),
                     BRAUN_ERR_MASS_NOT_SPD);
    assert_int_equal(bi, 1);
    assert_true(bad < 0);
    const braun_real singular[4] = {1, 1, 1, 1};
    braun_chol c2 = chol_of(2);
    assert_int_equal(braun_chol_factor(&c2, singular, 1e-12, &bi, &bj, &bad),
                     BRAUN_ERR_MASS_NOT_SPD);
}

/* The pivot rule does not depend on the coordinates' units: M and D M D
 * (D diagonal, a coordinate in other units) get the same verdict at the
 * same pivot. A rigid body whose radius of gyration is 1e-10 m, M =
 * diag(1, 1, 1e-20), was refused (pivot 1e-20 <= n·ε·max M_ii = 6.7e-16:
 * its inertia compared with its mass); M singular or indefinite in any
 * units still is. */
static void test_chol_unit_scale(void **state)
{
    (void)state;
    int bi = -1, bj = -1;
    braun_real bad = 0;
    braun_chol c = chol_of(3);
    const braun_real body[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1e-20};
    assert_int_equal(braun_chol_factor(&c, body, 1e-12, &bi, &bj, &bad), BRAUN_OK);
    /* Symmetry against the pair's own entries: a coupling of the small one
     * asymmetric by 1e-13 (against sqrt(1·1e-20) = 1e-10: 1e-3 of it)
     * went unseen against the largest entry (1e-12·1). */
    const braun_real skew[9] = {1, 0, 0, 0, 1, 1e-13, 0, 0, 1e-20};
    bi = bj = -1;
    assert_int_equal(braun_chol_factor(&c, skew, 1e-12, &bi, &bj, &bad), BRAUN_ERR_MASS_NOT_SYMMETRIC);
    assert_int_equal(bi, 1);
    assert_int_equal(bj, 2);
    braun_real y[3] = {1, 2, 3e-20};
    braun_chol_solve_rt(&c, y);
    braun_chol_solve_r(&c, y);
    for (int i = 0; i < 3; i++) assert_near(y[i], i + 1, 1e-15);
    /* test_chol_known's M (R = [2 1 0; 0 3 1; 0 0 4]), a rank-2 M (row 2 =
     * row 0 + row 1: its last pivot is exactly 0) and an indefinite one, in
     * units 2^-27, 1 and 2^17 times their own and the other way round
     * (powers of 2: D M D factors exactly as R D, so the verdicts are those
     * of M bit for bit). */
    const braun_real spd[9] = {4, 2, 0, 2, 10, 3, 0, 3, 17};
    const braun_real rank2[9] = {4, 2, 6, 2, 10, 12, 6, 12, 18};
    const braun_real indef[9] = {1, 2, 0, 2, 1, 0, 0, 0, 1};
    const braun_real lo = (braun_real)ldexp(1, -27), hi = (braun_real)ldexp(1, 17);
    const braun_real units[2][3] = {{lo, 1, hi}, {hi, 1, lo}};
    for (int u = 0; u < 2; u++) {
        const braun_real *d = units[u];
        braun_real S[9];
        for (int i = 0; i < 9; i++) S[i] = spd[i] * d[i / 3] * d[i % 3];
        assert_int_equal(braun_chol_factor(&c, S, 1e-12, &bi, &bj, &bad), BRAUN_OK);
        /* R of D M D is R_known D, column j scaled by d_j. */
        const braun_real Rk[9] = {2, 1, 0, 0, 3, 1, 0, 0, 4};
        for (int i = 0; i < 9; i++)
            assert_true(fabs((double)(c.R[i] - Rk[i] * d[i % 3])) <= 1e-14 * fabs((double)d[i % 3]));
        for (int i = 0; i < 9; i++) S[i] = rank2[i] * d[i / 3] * d[i % 3];
        bi = -1;
        assert_int_equal(braun_chol_factor(&c, S, 1e-12, &bi, &bj, &bad), BRAUN_ERR_MASS_NOT_SPD);
        assert_int_equal(bi, 2);
        for (int i = 0; i < 9; i++) S[i] = indef[i] * d[i / 3] * d[i % 3];
        bi = -1;
        assert_int_equal(braun_chol_factor(&c, S, 1e-12, &bi, &bj, &bad), BRAUN_ERR_MASS_NOT_SPD);
        assert_int_equal(bi, 1);
        assert_true(bad < 0);
    }
    /* A zero diagonal entry (a massless coordinate) beside tiny ones. */
    const braun_real zero[9] = {1e-30, 0, 0, 0, 0, 0, 0, 0, 1e-30};
    assert_int_equal(braun_chol_factor(&c, zero, 1e-12, &bi, &bj, &bad), BRAUN_ERR_MASS_NOT_SPD);
    assert_int_equal(bi, 1);
}

/* X = C^+ built column by column; then the four Penrose conditions. */
typedef struct pinv_case {
    int rows, n;
    braun_real C[NMAX * NMAX];
} pinv_case;

static int factor(const pinv_case *c, braun_qrcp *f, braun_real *reals, int *ints,
                  braun_real tol)
{
    braun_qrcp_bind(f, c->n, c->rows, reals, ints);
    for (int i = 0; i < c->rows * c->n; i++) f->a[i] = c->C[i];
    return braun_qrcp_factor(f, tol);
}

static void pinv_matrix(const braun_qrcp *f, int rows, int n, braun_real *X)
{
    braun_real e[NMAX], x[NMAX];
    for (int j = 0; j < rows; j++) {
        for (int i = 0; i < rows; i++) e[i] = i == j;
        braun_qrcp_pinv_apply(f, e, x);
        for (int i = 0; i < n; i++) X[i * rows + j] = x[i]; /* X is n x rows */
    }
}

static void matmul(int a, int b, int c, const braun_real *A, const braun_real *B,
                   braun_real *AB)
{
    for (int i = 0; i < a; i++)
        for (int j = 0; j < c; j++) {
            double s = 0;
            for (int k = 0; k < b; k++) s += A[i * b + k] * B[k * c + j];
            AB[i * c + j] = s;
        }
}

static void check_penrose(const pinv_case *c, int expect_rank, double tol)
{
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX];
    braun_qrcp f;
    assert_true(braun_qrcp_reals(c->n, c->rows) <= sizeof reals / sizeof reals[0]);
    /* With tolerance 0 round-off pivots (~1e-16) would count as rank: the
     * tolerance is what makes the decomposition rank-revealing. */
    int rank = factor(c, &f, reals, ints, (braun_real)(NMAX * DBL_EPSILON));
    assert_int_equal(rank, expect_rank);
    const int m = c->rows, n = c->n;
    braun_real X[NMAX * NMAX], CX[NMAX * NMAX], XC[NMAX * NMAX], T1[NMAX * NMAX],
        T2[NMAX * NMAX];
    pinv_matrix(&f, m, n, X);
    matmul(m, n, m, c->C, X, CX);  /* m x m */
    matmul(n, m, n, X, c->C, XC);  /* n x n */
    matmul(m, m, n, CX, c->C, T1); /* C X C = C */
    for (int i = 0; i < m * n; i++) assert_near(T1[i], c->C[i], tol);
    matmul(n, n, m, XC, X, T2);    /* X C X = X */
    for (int i = 0; i < n * m; i++) assert_near(T2[i], X[i], tol);
    for (int i = 0; i < m; i++)    /* C X symmetric */
        for (int j = 0; j < m; j++) assert_near(CX[i * m + j], CX[j * m + i], tol);
    for (int i = 0; i < n; i++)    /* X C symmetric */
        for (int j = 0; j < n; j++) assert_near(XC[i * n + j], XC[j * n + i], tol);
    /* N z = z - X C z: C N z = 0 and N N z = N z. */
    braun_real z[NMAX], nz[NMAX], cz[NMAX];
    unsigned seed = 7;
    for (int i = 0; i < n; i++) z[i] = frand(&seed);
    for (int i = 0; i < n; i++) nz[i] = z[i];
    braun_qrcp_null_project(&f, nz);
    braun_gemv(m, n, c->C, nz, cz);
    for (int i = 0; i < m; i++) assert_near(cz[i], 0, tol);
    braun_real xcz[NMAX];
    braun_gemv(n, n, XC, z, xcz);
    for (int i = 0; i < n; i++) assert_near(nz[i], z[i] - xcz[i], tol);
}

static void test_pinv_full_rank(void **state)
{
    (void)state;
    unsigned seed = 1;
    pinv_case c = {3, 5, {0}};
    for (int i = 0; i < 15; i++) c.C[i] = frand(&seed);
    check_penrose(&c, 3, 1e-13);
    /* Full row rank: C C^+ r = r for any r. */
    braun_real reals[2 * NMAX * NMAX + 4 * NMAX], x[NMAX], r[3] = {1, -2, 0.5}, cr[3];
    int ints[NMAX];
    braun_qrcp f;
    factor(&c, &f, reals, ints, 0);
    braun_qrcp_pinv_apply(&f, r, x);
    braun_gemv(3, 5, c.C, x, cr);
    for (int i = 0; i < 3; i++) assert_near(cr[i], r[i], 1e-13);
}

static void test_pinv_duplicated_and_scaled_rows(void **state)
{
    (void)state;
    unsigned seed = 3;
    pinv_case c = {4, 5, {0}};
    for (int i = 0; i < 10; i++) c.C[i] = frand(&seed);
    for (int j = 0; j < 5; j++) {
        c.C[2 * 5 + j] = c.C[j];           /* duplicated row */
        c.C[3 * 5 + j] = -3.0 * c.C[5 + j]; /* scaled duplicate */
    }
    check_penrose(&c, 2, 1e-12);
}

static void test_pinv_more_rows_than_columns(void **state)
{
    (void)state;
    unsigned seed = 5;
    pinv_case c = {5, 3, {0}};
    for (int i = 0; i < 15; i++) c.C[i] = frand(&seed);
    check_penrose(&c, 3, 1e-12);
}

static void test_pinv_zero_and_rank_one(void **state)
{
    (void)state;
    pinv_case z = {2, 3, {0}};
    check_penrose(&z, 0, 0);
    pinv_case r1 = {3, 4, {1, 2, 3, 4, 2, 4, 6, 8, -1, -2, -3, -4}};
    check_penrose(&r1, 1, 1e-13);
}

/* The rank tolerance decides: a row 1e-10 away from dependence is kept by
 * the default max(m,n)·ε and dropped by a loose 1e-6. */
static void test_rank_tolerance(void **state)
{
    (void)state;
    pinv_case c = {2, 3, {1, 0, 0, 1, 1e-10, 0}};
    braun_real reals[2 * NMAX * NMAX + 4 * NMAX];
    int ints[NMAX];
    braun_qrcp f;
    assert_int_equal(factor(&c, &f, reals, ints, 3 * DBL_EPSILON), 2);
    assert_int_equal(factor(&c, &f, reals, ints, 1e-6), 1);
}

/* Soft directions (braun_qrcp_soft.c): C = U diag(σ) Vᵀ with known
 * orthonormal U, V; redundant copies of a row make the rank-deficient
 * case. soft_find must find exactly the directions below the gate 10λ
 * (λ = rel·|r_00|), and soft_project must return the part of x along
 * them, each weighted by w = λ⁴/(σ⁴ + λ⁴), and nothing of x elsewhere. */
static void orthonormal_columns(int n, int k, braun_real *Q, unsigned *seed)
{
    for (int c = 0; c < k; c++) {
        for (int i = 0; i < n; i++) Q[i * k + c] = frand(seed);
        for (int pass = 0; pass < 2; pass++)
            for (int e = 0; e < c; e++) {
                double d = 0;
                for (int i = 0; i < n; i++) d += Q[i * k + c] * Q[i * k + e];
                for (int i = 0; i < n; i++) Q[i * k + c] -= d * Q[i * k + e];
            }
        double nn = 0;
        for (int i = 0; i < n; i++) nn += Q[i * k + c] * Q[i * k + c];
        for (int i = 0; i < n; i++) Q[i * k + c] /= sqrt(nn);
    }
}

static void soft_case(const double *sig, int k, int redundant, int expect_soft)
{
    const int n = 6, rows = k + redundant;
    const double rel = 1e-4;
    unsigned seed = 11u + (unsigned)k * 7u + (unsigned)redundant;
    braun_real U[NMAX * NMAX], V[NMAX * NMAX];
    orthonormal_columns(k, k, U, &seed);
    orthonormal_columns(n, k, V, &seed);
    pinv_case c = {rows, n, {0}};
    for (int i = 0; i < k; i++)
        for (int j = 0; j < n; j++) {
            double sum = 0;
            for (int l = 0; l < k; l++) sum += U[i * k + l] * sig[l] * V[j * k + l];
            c.C[i * n + j] = sum;
        }
    for (int r = 0; r < redundant; r++) /* row k + r = 2·row 0 + row 1 */
        for (int j = 0; j < n; j++) c.C[(k + r) * n + j] = 2 * c.C[j] + c.C[n + j];
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX];
    braun_qrcp f;
    assert_true(braun_qrcp_reals(n, rows) <= sizeof reals / sizeof reals[0]);
    assert_int_equal(factor(&c, &f, reals, ints, (braun_real)(NMAX * DBL_EPSILON)), k);
    assert_int_equal(braun_qrcp_soft_find(&f, rel), expect_soft);
    braun_real x[NMAX], y[NMAX];
    for (int i = 0; i < n; i++) x[i] = frand(&seed);
    braun_qrcp_soft_project(&f, x, y, 0);
    double r00 = 0; /* |r_00|: the largest row norm of C */
    for (int i = 0; i < rows; i++) {
        double s2 = 0;
        for (int j = 0; j < n; j++) s2 += c.C[i * n + j] * c.C[i * n + j];
        if (sqrt(s2) > r00) r00 = sqrt(s2);
    }
    const double lam = rel * r00;
    /* Round-off ε‖C‖ in C turns a direction of singular value σ toward the
     * null space by about ε‖C‖/σ (a few ε·rows·n·‖C‖ after the
     * factorizations): that far from Vᵀ the soft directions of the
     * computed C may lie. */
    double smin = 1;
    for (int l = 0; l < k; l++)
        if (sig[l] < smin) smin = sig[l];
    const double tol = 1e-13 + 64 * DBL_EPSILON * (double)(rows * n) * r00 / smin;
    double py[NMAX];
    for (int i = 0; i < n; i++) py[i] = y[i];
    for (int l = 0; l < k; l++) {
        double xv = 0, yv = 0;
        for (int i = 0; i < n; i++) {
            xv += x[i] * V[i * k + l];
            yv += y[i] * V[i * k + l];
        }
        const double l4 = pow(lam, 4), w = l4 / (pow(sig[l], 4) + l4);
        const int soft = sig[l] < BRAUN_SOFT_GATE * lam;
        assert_near(yv, soft ? w * xv : 0, tol);
        for (int i = 0; i < n; i++) py[i] -= yv * V[i * k + l];
    }
    for (int i = 0; i < n; i++) assert_near(py[i], 0, tol); /* nothing outside range(Cᵀ) */
    /* With a rate: the weights times z⁴/(1 + z⁴), z = rate/σ (here the
     * rate is the smallest σ: the stiffest direction gets half). Only
     * without redundant rows: a dependent row changes C's singular values
     * (Cᵀ C gains its outer product), so sig is no longer their value. */
    if (redundant) return;
    braun_real y2[NMAX];
    braun_qrcp_soft_project(&f, x, y2, (braun_real)smin);
    for (int l = 0; l < k; l++) {
        double xv = 0, yv = 0;
        for (int i = 0; i < n; i++) {
            xv += x[i] * V[i * k + l];
            yv += y2[i] * V[i * k + l];
        }
        const double l4 = pow(lam, 4), s4 = pow(sig[l], 4), r4 = pow(smin, 4);
        const double w = l4 / (s4 + l4) * r4 / (r4 + s4);
        assert_near(yv, sig[l] < BRAUN_SOFT_GATE * lam ? w * xv : 0, tol);
    }
}

static void test_soft_directions(void **state)
{
    (void)state;
    const double none[4] = {1, 0.7, 0.3, 0.05}, one[4] = {1, 0.6, 0.2, 1e-7},
                 two[4] = {1, 0.5, 2e-5, 3e-8}, edge[4] = {1, 0.5, 0.25, 1e-4};
    soft_case(none, 4, 0, 0);
    soft_case(one, 4, 0, 1);
    soft_case(two, 4, 0, 2);
    soft_case(one, 4, 1, 1); /* a dependent row: the triangle is T of S = U T */
    soft_case(two, 4, 2, 2);
    soft_case(edge, 4, 0, 1); /* w between 0 and 1: σ = 1e-4, λ ~ 1e-4 */
}

/* braun_qrcp_factor_ordered (the later stages of a step): C close to the
 * last factorized matrix is factored in its column order, and C^+ is the
 * pivoted factorization's to round-off; a dependent row, a rank-deficient
 * last factorization or a NaN is refused (-1), never a wrong factor. */
static void test_factor_ordered(void **state)
{
    (void)state;
    enum { M = 5, N = 6 };
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX], reals2[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX], ints2[NMAX];
    braun_qrcp f, g;
    unsigned seed = 11;
    int skipped = 0;
    for (int trial = 0; trial < 50; trial++) {
        pinv_case c = {M, N, {0}}, c2 = {M, N, {0}};
        /* Rows of very different norms: the pivoted order is not 0..4. */
        for (int i = 0; i < M; i++)
            for (int j = 0; j < N; j++) c.C[i * N + j] = frand(&seed) * (1 + 3 * (i == (trial % M)));
        for (int i = 0; i < M * N; i++) c2.C[i] = c.C[i] + 1e-3 * frand(&seed);
        assert_int_equal(factor(&c, &f, reals, ints, 1e-14), M);
        int perm[M];
        for (int j = 0; j < M; j++) perm[j] = f.perm[j];
        for (int i = 0; i < M * N; i++) f.a[i] = c2.C[i];
        const int rank = braun_qrcp_factor_ordered(&f, 1e-2);
        if (rank < 0) { skipped++; continue; } /* a pivot below 1e-2: allowed, rare */
        assert_int_equal(rank, M);
        for (int j = 0; j < M; j++) assert_int_equal(f.perm[j], perm[j]); /* no pivoting */
        assert_int_equal(factor(&c2, &g, reals2, ints2, 1e-14), M);
        braun_real X[NMAX * NMAX], Y[NMAX * NMAX], z[NMAX], nz[NMAX], nz2[NMAX];
        pinv_matrix(&f, M, N, X);
        pinv_matrix(&g, M, N, Y);
        for (int i = 0; i < M * N; i++) assert_near(X[i], Y[i], 1e-12 * (1 + fabs(Y[i])));
        for (int i = 0; i < N; i++) nz[i] = nz2[i] = z[i] = frand(&seed);
        braun_qrcp_null_project(&f, nz);
        braun_qrcp_null_project(&g, nz2);
        for (int i = 0; i < N; i++) assert_near(nz[i], nz2[i], 1e-13);
        /* C C^+ = I (full row rank). */
        braun_real CX[NMAX * NMAX];
        matmul(M, N, M, c2.C, X, CX);
        for (int i = 0; i < M; i++)
            for (int j = 0; j < M; j++) assert_near(CX[i * M + j], i == j, 1e-13);
    }
    assert_true(skipped <= 10); /* the path is taken, not skipped */
    /* A row dependent on two others: some pivot is round-off in any order. */
    pinv_case c = {M, N, {0}};
    for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed);
    assert_int_equal(factor(&c, &f, reals, ints, 1e-14), M);
    for (int j = 0; j < N; j++) c.C[4 * N + j] = 0.5 * c.C[j] - 2 * c.C[2 * N + j];
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor_ordered(&f, 1e-2), -1);
    /* The last factorization rank-deficient (f.rank is now 0): refused. */
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), 4);
    assert_int_equal(braun_qrcp_factor_ordered(&f, 1e-2), -1);
    /* A NaN entry: refused, not factored. */
    for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    f.a[7] = NAN;
    assert_int_equal(braun_qrcp_factor_ordered(&f, 1e-2), -1);
    /* More rows than columns: never full row rank. */
    pinv_case t = {N, M, {0}};
    for (int i = 0; i < M * N; i++) t.C[i] = frand(&seed);
    factor(&t, &g, reals2, ints2, 1e-14);
    assert_int_equal(braun_qrcp_factor_ordered(&g, 1e-2), -1);
}

/* ---- The Gram path (src/core/braun_qrcp_gram.c): C⁺ through
 * G = C Cᵀ = L D Lᵀ where the last factorization had full rank and every
 * pivot clears the gate. Checked against the pivoted QR of the same C and
 * against the definitions (C C⁺ = I, C N = 0), at every dispatched size;
 * what it refuses leaves C and its norms for the pivoted QR. */
static void gram_check(int M, int N, unsigned seed, double scale_row)
{
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX], reals2[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX], ints2[NMAX];
    braun_qrcp f, g;
    pinv_case c = {M, N, {0}};
    for (int i = 0; i < M; i++)
        for (int j = 0; j < N; j++) c.C[i * N + j] = frand(&seed) * (i == 0 ? scale_row : 1);
    assert_int_equal(factor(&c, &f, reals, ints, 1e-14), M);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    f.norms_given = 0;
    assert_int_equal(braun_qrcp_factor_gram(&f, 1e-2, 0), M);
    assert_int_equal(f.gram, 1);
    assert_int_equal(f.rank, M);
    for (int i = 0; i < M * N; i++) assert_true(f.a[i] == c.C[i]); /* C kept */
    assert_int_equal(factor(&c, &g, reals2, ints2, 1e-14), M);
    assert_int_equal(g.gram, 0);
    /* dmin and r00 are |R_ii| and the largest column norm, as the QR's. */
    assert_near(f.r00, g.r00, 1e-14 * g.r00);
    assert_true(f.dmin > 1e-2 * f.r00 && f.dmin <= f.r00);
    braun_real r[NMAX], r2[NMAX], x[NMAX], y[NMAX], x2[NMAX], y2[NMAX], cr[NMAX], res = -1;
    for (int i = 0; i < M; i++) {
        r[i] = frand(&seed);
        r2[i] = frand(&seed);
    }
    braun_qrcp_gram_lsq(&f, r, x, &res);
    assert_true(res == 0); /* full row rank: every r is reached */
    braun_qrcp_lsq(&g, r, y, NULL);
    for (int i = 0; i < N; i++) assert_near(x[i], y[i], 1e-12 * (1 + fabs(y[i])));
    braun_gemv(M, N, c.C, x, cr);
    for (int i = 0; i < M; i++) assert_near(cr[i], r[i], 1e-12);
    /* Two right-hand sides: each bit for bit the single solve. */
    braun_qrcp_gram_pinv2(&f, r, r2, x, x2);
    braun_qrcp_gram_lsq(&f, r, y, NULL);
    braun_qrcp_gram_lsq(&f, r2, y2, NULL);
    for (int i = 0; i < N; i++) {
        assert_true(x[i] == y[i]);
        assert_true(x2[i] == y2[i]);
    }
    /* The null-space projector: C N z = 0, and N z as the QR's. */
    braun_real z[NMAX], nz[NMAX], nz2[NMAX], cz[NMAX];
    for (int i = 0; i < N; i++) nz[i] = nz2[i] = z[i] = frand(&seed);
    braun_qrcp_gram_null_project(&f, nz);
    braun_qrcp_null_project(&g, nz2);
    braun_gemv(M, N, c.C, nz, cz);
    for (int i = 0; i < M; i++) assert_near(cz[i], 0, 1e-12);
    for (int i = 0; i < N; i++) {
        assert_near(nz[i], nz2[i], 1e-12);
        if (M == N) assert_true(nz[i] == 0); /* no null space: exactly 0, as the QR's */
    }
}

static void test_factor_gram(void **state)
{
    (void)state;
    /* Every dispatched size and one beyond (BRAUN_SMALL_MAX 8). */
    for (int n = 2; n <= NMAX; n++)
        for (int m = 1; m <= n; m++) gram_check(m, n, 100u + 7u * (unsigned)(n * NMAX + m), 1);
    /* One row 30 times the others (the pivots still clear 1e-2). */
    gram_check(5, 6, 4, 30);

    enum { M = 5, N = 6 };
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX], reals2[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX], ints2[NMAX];
    braun_qrcp f, g;
    unsigned seed = 21;
    pinv_case c = {M, N, {0}};
    for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed);
    assert_int_equal(factor(&c, &f, reals, ints, 1e-14), M);
    /* Row 4 within 1e-3 of a combination of rows 0 and 2: its pivot is far
     * below the gate. Refused, with C and its norms (f->work) left as they
     * were for the pivoted QR, which then gives what a fresh one gives. */
    for (int j = 0; j < N; j++) c.C[4 * N + j] = 0.5 * c.C[j] - 2 * c.C[2 * N + j] + 1e-3 * frand(&seed);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    f.norms_given = 0;
    assert_int_equal(braun_qrcp_factor_gram(&f, 1e-2, 0), -1);
    assert_int_equal(f.gram, 0);
    for (int i = 0; i < M * N; i++) assert_true(f.a[i] == c.C[i]);
    assert_int_equal(f.norms_given, 1);
    for (int i = 0; i < M; i++) {
        double s = 0;
        for (int j = 0; j < N; j++) s += c.C[i * N + j] * c.C[i * N + j];
        assert_true(f.work[i] == s);
    }
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
    assert_int_equal(factor(&c, &g, reals2, ints2, 1e-14), M);
    assert_true(f.dmin == g.dmin);
    for (int i = 0; i < M * N; i++) assert_true(f.a[i] == g.a[i]);
    /* The same C accepted under a gate below its smallest pivot. */
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor_gram(&f, 1e-6, 0), M);
    /* After a Gram factorization the pivoted QR of the C it kept is the
     * fresh one (the soft-direction search relies on it: braun_dense.h). */
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
    assert_int_equal(f.gram, 0);
    for (int i = 0; i < M * N; i++) assert_true(f.a[i] == g.a[i]);
    /* The last factorization rank-deficient: refused. */
    for (int j = 0; j < N; j++) c.C[4 * N + j] = 0.5 * c.C[j] - 2 * c.C[2 * N + j];
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), 4);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor_gram(&f, 1e-2, 0), -1);
    /* A NaN or an infinite entry: refused, not factored. */
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        f.a[7] = k ? INFINITY : NAN;
        f.norms_given = 0;
        assert_int_equal(braun_qrcp_factor_gram(&f, 1e-2, 0), -1);
    }
    /* A gate of 1 or more (or NaN) accepts nothing. (A refusal leaves the
     * norms it summed for the next factorization of the same C: a new C
     * clears them.) */
    f.norms_given = 0;
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor_gram(&f, 1, 0), -1);
    assert_int_equal(braun_qrcp_factor_gram(&f, NAN, 0), -1);
    assert_int_equal(braun_qrcp_factor_gram(&f, 0.1, 1), -1);
    assert_int_equal(braun_qrcp_factor_gram(&f, 0.1, NAN), -1);
    /* More rows than columns: never full row rank. */
    pinv_case t = {N, M, {0}};
    for (int i = 0; i < M * N; i++) t.C[i] = frand(&seed);
    factor(&t, &g, reals2, ints2, 1e-14);
    assert_int_equal(braun_qrcp_factor_gram(&g, 1e-2, 0), -1);

    /* The second gate is relative to each row's own norm: a row 20 times
     * shorter than the others but independent of them passes it (the
     * first gate, relative to the longest row, only asks 1e-2)... */
    for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed) * (i < N ? 0.05 : 1);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    f.norms_given = 0;
    assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
    for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
    assert_int_equal(braun_qrcp_factor_gram(&f, 1e-2, 0.1), M);
    /* ... while a row within 3 % of a combination of two others fails it
     * whatever its length: -2, the rank still full (every pivot above the
     * first gate), and an ordered QR then takes the same C. */
    for (int scale = 0; scale < 2; scale++) {
        for (int i = 0; i < M * N; i++) c.C[i] = frand(&seed);
        for (int j = 0; j < N; j++)
            c.C[4 * N + j] = (scale ? 1e-3 : 1) * (0.5 * c.C[j] - 2 * c.C[2 * N + j] + 0.03 * frand(&seed));
        f.norms_given = 0;
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        assert_int_equal(braun_qrcp_factor_gram(&f, 1e-5, 0.1), -2);
        assert_int_equal(f.gram, 0);
        for (int i = 0; i < M * N; i++) assert_true(f.a[i] == c.C[i]);
        assert_int_equal(braun_qrcp_factor_ordered(&f, 1e-5), M);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        f.norms_given = 0;
        assert_int_equal(braun_qrcp_factor(&f, 1e-14), M);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        assert_int_equal(braun_qrcp_factor_gram(&f, 1e-5, 0), M); /* without the second gate */
    }
}

/* The Gram path's accuracy against its gate (docs/method.md, "The Gram
 * path"): C with singular values from 1 down to 1/κ, the smallest pivot
 * just above the gate. The solves' error against the QR's stays within
 * 10·ε·κ² (the normal equations' bound), and the QR's within ε·κ·10. */
static void test_gram_accuracy(void **state)
{
    (void)state;
    enum { M = 5, N = 6 };
    braun_real reals[2 * NMAX * NMAX + 12 * NMAX], reals2[2 * NMAX * NMAX + 12 * NMAX];
    int ints[NMAX], ints2[NMAX];
    braun_qrcp f, g;
    unsigned seed = 33;
    const double kappas[3] = {3, 20, 90};
    for (int kk = 0; kk < 3; kk++) {
        const double kappa = kappas[kk];
        /* C = U diag(σ) Vᵀ with Householder-made orthogonal U, V. */
        double u[M], v[N], U[M * M], V[N * N];
        double nu = 0, nv = 0;
        for (int i = 0; i < M; i++) {
            u[i] = frand(&seed);
            nu += u[i] * u[i];
        }
        for (int i = 0; i < N; i++) {
            v[i] = frand(&seed);
            nv += v[i] * v[i];
        }
        for (int i = 0; i < M; i++)
            for (int j = 0; j < M; j++) U[i * M + j] = (i == j) - 2 * u[i] * u[j] / nu;
        for (int i = 0; i < N; i++)
            for (int j = 0; j < N; j++) V[i * N + j] = (i == j) - 2 * v[i] * v[j] / nv;
        pinv_case c = {M, N, {0}};
        for (int i = 0; i < M; i++)
            for (int j = 0; j < N; j++) {
                double s = 0;
                for (int k = 0; k < M; k++) s += U[i * M + k] * pow(kappa, -(double)k / (M - 1)) * V[j * N + k];
                c.C[i * N + j] = s;
            }
        assert_int_equal(factor(&c, &f, reals, ints, 1e-14), M);
        for (int i = 0; i < M * N; i++) f.a[i] = c.C[i];
        f.norms_given = 0;
        assert_int_equal(braun_qrcp_factor_gram(&f, 0.5 / (kappa * sqrt((double)M)), 0), M);
        assert_int_equal(factor(&c, &g, reals2, ints2, 1e-14), M);
        /* The exact C⁺ r = V Σ⁻¹ Uᵀ r. */
        braun_real r[M], x[N], y[N];
        double exact[N], utr[M], nx = 0;
        for (int i = 0; i < M; i++) r[i] = frand(&seed);
        for (int k = 0; k < M; k++) {
            double s = 0;
            for (int i = 0; i < M; i++) s += U[i * M + k] * r[i];
            utr[k] = s / pow(kappa, -(double)k / (M - 1));
        }
        for (int j = 0; j < N; j++) {
            double s = 0;
            for (int k = 0; k < M; k++) s += V[j * N + k] * utr[k];
            exact[j] = s;
            nx += s * s;
        }
        braun_qrcp_gram_lsq(&f, r, x, NULL);
        braun_qrcp_lsq(&g, r, y, NULL);
        double ex = 0, ey = 0;
        for (int j = 0; j < N; j++) {
            ex += (x[j] - exact[j]) * (x[j] - exact[j]);
            ey += (y[j] - exact[j]) * (y[j] - exact[j]);
        }
        ex = sqrt(ex / nx);
        ey = sqrt(ey / nx);
        print_message("gram accuracy: kappa %g: Gram %.3g, QR %.3g relative (eps*kappa^2 = %.3g)\n",
                      kappa, ex, ey, DBL_EPSILON * kappa * kappa);
        assert_true(ex <= 10 * DBL_EPSILON * kappa * kappa);
        assert_true(ey <= 10 * DBL_EPSILON * kappa);
    }
}

/* The dense backend's choice (braun_dense.h, braun__dense_factor_c): a
 * factorization after a full-rank one goes through the Gram matrix, and a
 * soft-direction search on it (a wide window: here 0.09·r00, above a row
 * 20 times shorter than the longest and orthogonal to the others, which
 * the Gram gates accept) factors the kept C by QR first, finding what a
 * QR alone finds. */
static void test_dense_soft_after_gram(void **state)
{
    (void)state;
    enum { M = 5, N = 6 };
    braun_dense s, t;
    braun_real chol_r[2][N * N + N], reals[2][2 * NMAX * NMAX + 12 * NMAX + 64];
    int chol_i[2][2 * N], ints[2][NMAX];
    braun_real eye[N * N], A[M * N];
    for (int i = 0; i < N * N; i++) eye[i] = (i % (N + 1)) == 0;
    braun_dense *st[2] = {&s, &t};
    for (int k = 0; k < 2; k++) {
        memset(st[k], 0, sizeof s);
        st[k]->n = N;
        braun_chol_bind(&st[k]->chol, N, chol_r[k], chol_i[k]);
        assert_int_equal(braun_chol_factor(&st[k]->chol, eye, 1e-12, NULL, NULL, NULL), BRAUN_OK);
        assert_true(braun_qrcp_reals(N, M) <= sizeof reals[k] / sizeof reals[k][0]);
        braun_qrcp_bind(&st[k]->fv, N, M, reals[k], ints[k]);
        braun__dense_rank_rule(st[k], 0, M, M, 0);
    }
    unsigned seed = 41;
    /* Rows 0-3 well conditioned (near the unit vectors); row 4: */
    for (int i = 0; i < M * N; i++) A[i] = (i / N == i % N) + 0.3 * frand(&seed);
    /* Row 4: orthogonal to the others (Gram–Schmidt), 0.05 of the longest
     * row's norm: a singular value of 0.05·r00 that the Gram gates pass. */
    double big = 0;
    for (int i = 0; i < 4; i++) {
        double nn = 0;
        for (int j = 0; j < N; j++) nn += A[i * N + j] * A[i * N + j];
        big = fmax(big, sqrt(nn));
    }
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < 4; i++) {
            double d = 0, nn = 0;
            for (int j = 0; j < N; j++) {
                d += A[4 * N + j] * A[i * N + j];
                nn += A[i * N + j] * A[i * N + j];
            }
            for (int j = 0; j < N; j++) A[4 * N + j] -= d / nn * A[i * N + j];
        }
    double n4 = 0;
    for (int j = 0; j < N; j++) n4 += A[4 * N + j] * A[4 * N + j];
    for (int j = 0; j < N; j++) A[4 * N + j] *= 0.05 * big / sqrt(n4);
    /* s: a first factorization (pivoted QR), then the same C again: Gram. */
    assert_int_equal(braun__dense_factor_c(&s, 0, M, A, 1e-14, NULL, NULL), M);
    assert_int_equal(s.fv.gram, 0);
    assert_int_equal(braun__dense_factor_c(&s, 0, M, A, 1e-14, NULL, NULL), M);
    assert_int_equal(s.fv.gram, 1);
    /* t: the pivoted QR only. */
    assert_int_equal(braun__dense_factor_c(&t, 0, M, A, 1e-14, NULL, NULL), M);
    assert_int_equal(t.fv.gram, 0);
    const braun_real rel = 9e-3;
    const int ns = braun__dense_soft_find(&s, 0, rel), nt = braun__dense_soft_find(&t, 0, rel);
    assert_int_equal(nt, 1); /* the short row's direction */
    assert_int_equal(ns, nt);
    assert_int_equal(s.fv.gram, 0); /* now the QR */
    braun_real x[N], ys[N], yt[N];
    for (int i = 0; i < N; i++) x[i] = frand(&seed);
    braun__dense_soft_project(&s, 0, x, ys, 0);
    braun__dense_soft_project(&t, 0, x, yt, 0);
    for (int i = 0; i < N; i++) assert_true(ys[i] == yt[i]);
    /* Below the window (the default soft_tol's 1e-6): nothing, and the
     * Gram factor stays. */
    assert_int_equal(braun__dense_factor_c(&s, 0, M, A, 1e-14, NULL, NULL), M);
    assert_int_equal(s.fv.gram, 1);
    assert_int_equal(braun__dense_soft_find(&s, 0, 1e-6), 0);
    assert_int_equal(s.fv.gram, 1);
}

/* ---- sin and cos with one argument reduction, the float build's
 * braun_sincos (src/core/braun_sincos.h): against the double sin and cos,
 * in ulps of the float result, over the whole reduced range, near the
 * multiples of π/2 (where the reduction cancels) and at its edges. */
/* The error in ulps of the result; next to a zero of sin or cos (where
 * the reduction's last term, n·P3, carries an absolute error of ~1e-13)
 * in units of 2^-24·1e-4 instead (absolute 6e-12). */
static double ulp_error(float got, double exact)
{
    const double mag = fabs(exact) > 1e-4 ? fabs(exact) : 1e-4;
    const float e = (float)mag;
    const double ulp = nextafterf(e, INFINITY) - e;
    return fabs((double)got - exact) / ulp;
}

static void test_sincosf(void **state)
{
    (void)state;
    double worst = 0, worst_x = 0;
    long checked = 0;
    /* A grid over ±BRAUN_SINCOS_MAX, and the float neighbours of n·π/2. */
    for (long k = -3000000; k <= 3000000; k++) {
        for (int near = 0; near < 2; near++) {
            float x;
            if (!near) {
                x = (float)((double)k * (BRAUN_SINCOS_MAX / 3000000.0) * 0.99999);
            } else {
                if (k % 1000) continue;
                const long n = k / 1000;
                x = (float)((double)n * 1.57079632679489661923);
                x = (k & 1) ? nextafterf(x, INFINITY) : x;
            }
            float s, c;
            braun_sincosf(x, &s, &c);
            const double es = ulp_error(s, sin((double)x)), ec = ulp_error(c, cos((double)x));
            if (es > worst || ec > worst) {
                worst = es > ec ? es : ec;
                worst_x = x;
            }
            checked++;
        }
    }
    print_message("braun_sincosf: %ld arguments, worst error %.3g ulp at x = %.9g\n", checked, worst,
                  worst_x);
    assert_true(worst <= 2.5); /* measured 2.35; newlib's sinf, cosf: below 1 */
    /* Small arguments: sin x = x, cos x = 1 to the last bit. */
    float s, c;
    braun_sincosf(1e-20f, &s, &c);
    assert_true(s == 1e-20f && c == 1);
    braun_sincosf(-0.0f, &s, &c);
    assert_true(s == 0 && c == 1);
    /* Beyond the reduced range, NaN and ±Inf: sinf and cosf themselves. */
    const float far[4] = {BRAUN_SINCOS_MAX, -1e6f, INFINITY, NAN};
    for (int i = 0; i < 4; i++) {
        braun_sincosf(far[i], &s, &c);
        const float s0 = sinf(far[i]), c0 = cosf(far[i]);
        assert_true(memcmp(&s, &s0, sizeof s) == 0 || (isnan(s) && isnan(s0)));
        assert_true(memcmp(&c, &c0, sizeof c) == 0 || (isnan(c) && isnan(c0)));
    }
    braun_sincosf(NAN, &s, &c);
    assert_true(isnan(s) && isnan(c));
}

/* ---- The size-dispatched kernels (braun_linalg.h, BRAUN_SMALL_DISPATCH)
 * equal plain loops bit for bit, at every dispatched length and beyond it:
 * the reference below is the factorization, solve and projection written
 * once more without dispatch, in the same operation order. */
#define KMAX 11
static double ref_sumsq(int len, const double *x)
{
    double s = 0;
    for (int i = 0; i < len; i++) s += x[i] * x[i];
    return s;
}
static double ref_house(int len, double *x, double normx)
{
    double alpha = x[0];
    if (normx == 0) return 0;
    double beta = alpha >= 0 ? -normx : normx;
    double scale = 1 / (alpha - beta);
    for (int i = 1; i < len; i++) x[i] *= scale;
    x[0] = beta;
    return (beta - alpha) / beta;
}
static void ref_reflect(int len, const double *v, double tau, double *y)
{
    if (tau == 0) return;
    double w = y[0];
    for (int i = 1; i < len; i++) w += v[i - 1] * y[i];
    w *= tau;
    y[0] -= w;
    for (int i = 1; i < len; i++) y[i] -= w * v[i - 1];
}

static void test_small_kernels_bitwise(void **state)
{
    (void)state;
    unsigned seed = 23;
    int checked = 0;
    for (int n = 1; n <= KMAX; n++)
        for (int rows = 1; rows <= n; rows++) {
            braun_real reals[2 * KMAX * KMAX + 12 * KMAX], C[KMAX * KMAX], a[KMAX * KMAX];
            int ints[KMAX];
            braun_qrcp f;
            assert_true(braun_qrcp_reals(n, rows) <= sizeof reals / sizeof reals[0]);
            braun_qrcp_bind(&f, n, rows, reals, ints);
            for (int i = 0; i < rows * n; i++) f.a[i] = C[i] = frand(&seed);
            assert_int_equal(braun_qrcp_factor(&f, 1e-14), rows);
            for (int i = 0; i < rows * n; i++) a[i] = f.a[i] = C[i] + 1e-3 * frand(&seed);
            if (braun_qrcp_factor_ordered(&f, 1e-3) != rows) continue;
            /* reference factorization in f's column order */
            double norm2[KMAX], tau[KMAX], big = 0;
            for (int j = 0; j < rows; j++) norm2[j] = ref_sumsq(n, a + j * n);
            for (int j = 0; j < rows; j++)
                if (norm2[j] > big) big = norm2[j];
            for (int k = 0; k < rows; k++) {
                double *col = a + f.perm[k] * n + k;
                const double pivot = sqrt(k == 0 ? norm2[f.perm[0]] : ref_sumsq(n - k, col));
                tau[k] = ref_house(n - k, col, pivot);
                for (int j = k + 1; j < rows; j++) ref_reflect(n - k, col + 1, tau[k], a + f.perm[j] * n + k);
            }
            assert_memory_equal(f.a, a, sizeof(double) * (size_t)(rows * n));
            assert_memory_equal(f.tau, tau, sizeof(double) * (size_t)rows);
            /* the least-squares solve: x = Q1 R^-T P^T r */
            double r[KMAX], w[KMAX], x[KMAX], xr[KMAX], z[KMAX], zr[KMAX];
            for (int i = 0; i < rows; i++) r[i] = frand(&seed);
            braun_qrcp_lsq(&f, r, x, NULL);
            for (int j = 0; j < rows; j++) w[j] = r[f.perm[j]];
            for (int i = 0; i < rows; i++) {
                double sum = w[i];
                const double *ci = a + f.perm[i] * n;
                for (int j = 0; j < i; j++) sum -= ci[j] * w[j];
                w[i] = sum / ci[i];
            }
            for (int i = 0; i < n; i++) xr[i] = i < rows ? w[i] : 0;
            for (int j = rows - 1; j >= 0; j--) ref_reflect(n - j, a + f.perm[j] * n + j + 1, tau[j], xr + j);
            assert_memory_equal(x, xr, sizeof(double) * (size_t)n);
            /* the null-space projection */
            for (int i = 0; i < n; i++) z[i] = zr[i] = frand(&seed);
            braun_qrcp_null_project(&f, z);
            for (int j = 0; j < rows; j++) ref_reflect(n - j, a + f.perm[j] * n + j + 1, tau[j], zr + j);
            for (int j = rows - 1; j >= 0; j--) {
                zr[j] = 0;
                ref_reflect(n - j, a + f.perm[j] * n + j + 1, tau[j], zr + j);
            }
            assert_memory_equal(z, zr, sizeof(double) * (size_t)n);
            checked++;
        }
    /* 66 shapes; a pivot below the gate skips one, rarely */
    assert_true(checked >= 60);
}

/* The Cholesky solves and product at the dispatched lengths (the whole
 * triangle unrolled, braun_chol.c) against the envelope loops, and the
 * dense backend's rows of C = A R⁻¹ (braun_dense.h, unrolled in place)
 * against the solve: equal values at every n <= KMAX, on banded mass
 * matrices with zeros inside the envelope (the four-bar's pattern: x and y
 * blocks interleaved) and on dense ones. Fails if an unrolled body reads
 * the wrong entry or sums in another order. */
static void test_chol_small_kernels(void **state)
{
    (void)state;
    unsigned seed = 7;
    int checked = 0;
    for (int n = 1; n <= KMAX; n++)
        for (int band = 0; band < 3; band++) {
            /* band 0: dense SPD; 1: couples i and i+2 only; 2: tridiagonal. */
            braun_real M[KMAX * KMAX], B[KMAX * KMAX];
            for (int i = 0; i < n * n; i++) B[i] = frand(&seed);
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    double sum = 0;
                    for (int k = 0; k < n; k++) sum += B[i * n + k] * B[j * n + k];
                    const int off = i > j ? i - j : j - i;
                    const int keep = band == 0 || off == 0 || (band == 1 ? off == 2 : off == 1);
                    M[i * n + j] = keep ? (i == j ? sum + n : 0.3 * sum / n) : 0;
                }
            braun_real cr[KMAX * KMAX + KMAX];
            int ci[2 * KMAX];
            braun_chol c;
            braun_chol_bind(&c, n, cr, ci);
            assert_int_equal(braun_chol_factor(&c, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
            braun_real b[KMAX], x[KMAX], xr[KMAX];
            for (int i = 0; i < n; i++) b[i] = frand(&seed);
            /* x = R^-T b: forward over the envelope */
            braun_chol_solve_rt_to(&c, b, x);
            for (int i = 0; i < n; i++) {
                double sum = b[i];
                for (int k = c.first[i]; k < i; k++) sum -= c.R[k * n + i] * xr[k];
                xr[i] = sum * c.dinv[i];
            }
            for (int i = 0; i < n; i++) assert_true(x[i] == xr[i]);
            /* x = R^-1 b: backward over the envelope; in place too */
            braun_chol_solve_r_to(&c, b, x);
            for (int i = n - 1; i >= 0; i--) {
                double sum = b[i];
                for (int k = i + 1; k <= c.last[i]; k++) sum -= c.R[i * n + k] * xr[k];
                xr[i] = sum * c.dinv[i];
            }
            for (int i = 0; i < n; i++) assert_true(x[i] == xr[i]);
            for (int i = 0; i < n; i++) x[i] = b[i];
            braun_chol_solve_r(&c, x);
            for (int i = 0; i < n; i++) assert_true(x[i] == xr[i]);
            /* y = R b */
            braun_chol_mul_r(&c, b, x);
            for (int i = 0; i < n; i++) {
                double sum = 0;
                for (int k = i; k <= c.last[i]; k++) sum += c.R[i * n + k] * b[k];
                assert_true(x[i] == sum);
            }
            /* The dense backend's C = A R^-1 with r_v and the rows' norms. */
            if (n >= 2 && !c.diagonal) {
                const int rows = n - 1;
                braun_dense s;
                braun_real reals[2 * KMAX * KMAX + 12 * KMAX + 64], A[KMAX * KMAX], at[KMAX], rv[KMAX];
                int ints[KMAX];
                memset(&s, 0, sizeof s);
                s.n = n;
                s.chol = c;
                assert_true(braun_qrcp_reals(n, rows) <= sizeof reals / sizeof reals[0]);
                braun_qrcp_bind(&s.fv, n, rows, reals, ints);
                for (int i = 0; i < rows * n; i++) A[i] = frand(&seed);
                for (int i = 0; i < n; i++) at[i] = frand(&seed);
                for (int i = 0; i < rows; i++) rv[i] = frand(&seed);
                braun_real rv0[KMAX];
                memcpy(rv0, rv, sizeof rv);
                braun__dense_form_c(&s, &s.fv, rows, A, at, rv);
                for (int i = 0; i < rows; i++) {
                    braun_real row[KMAX];
                    braun_chol_solve_rt_to(&c, A + i * n, row);
                    double dot = 0, nn = 0;
                    for (int j = 0; j < n; j++) {
                        assert_true(s.fv.a[i * n + j] == row[j]);
                        dot += row[j] * at[j];
                        nn += row[j] * row[j];
                    }
                    assert_true(rv[i] == rv0[i] - dot);
                    if (BRAUN_FUSED_NORMS) assert_true(s.fv.work[i] == nn);
                }
            }
            checked++;
        }
    assert_int_equal(checked, 3 * KMAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chol_known),
        cmocka_unit_test(test_chol_envelope),
        cmocka_unit_test(test_chol_rejects),
        cmocka_unit_test(test_chol_unit_scale),
        cmocka_unit_test(test_pinv_full_rank),
        cmocka_unit_test(test_pinv_duplicated_and_scaled_rows),
        cmocka_unit_test(test_pinv_more_rows_than_columns),
        cmocka_unit_test(test_pinv_zero_and_rank_one),
        cmocka_unit_test(test_rank_tolerance),
        cmocka_unit_test(test_soft_directions),
        cmocka_unit_test(test_factor_ordered),
        cmocka_unit_test(test_factor_gram),
        cmocka_unit_test(test_gram_accuracy),
        cmocka_unit_test(test_sincosf),
        cmocka_unit_test(test_dense_soft_after_gram),
        cmocka_unit_test(test_small_kernels_bitwise),
        cmocka_unit_test(test_chol_small_kernels),
    };
    return cmocka_run_group_tests_name("linalg", tests, NULL, NULL);
}
