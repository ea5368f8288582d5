/* The LAPACK backend (src/backends/braun_lapack.c) against libbraun's own
 * dense kernels (braun_chol_*, braun_qrcp_*) on the same matrices, and
 * against definitions that involve neither: R^-1 R^-T M x = x, C x = r for
 * consistent r, the normal equations and minimum norm of least squares,
 * C N z = 0 and N N = N.
 *
 * End to end: built-in models and test systems integrated with
 * opt.linsolver = LAPACK and NULL agree to ~1e-10.
 *
 *   BRAUN_BENCH_LAPACK=1 build/tests/test_backend_lapack
 * also times factor_mass + factor_c + pinv (and a whole evaluation's
 * linear algebra) for random systems, n = 6 ... 800, rows = 2n/3, dense
 * and block-structured, against the built-in kernels. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <time.h>

#include "test_util.h"
#include "braun_backends.h"
#include "braun_linalg.h"
#include "braun_models.h"
#include "test_systems.h"
#include "heap_interpose.h"

/* ------------------------------------------------------------------ */
static braun_real *vec(size_t len)
{
    braun_real *p = calloc(len ? len : 1, sizeof *p);
    assert_non_null(p);
    return p;
}

/* Random SPD M = D (B^T B / n + I/2) D, D diagonal in [0.5, 2]. */
static void random_spd(int n, unsigned long long seed, braun_real *M)
{
    braun_real *B = vec((size_t)n * (size_t)n), *d = vec((size_t)n);
    for (int i = 0; i < n * n; i++) B[i] = test_frand(&seed);
    for (int i = 0; i < n; i++) d[i] = 1.25 + 0.75 * test_frand(&seed);
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= i; j++) {
            double s = 0;
            for (int k = 0; k < n; k++) s += B[k * n + i] * B[k * n + j];
            s = s / n + (i == j ? 0.5 : 0);
            M[i * n + j] = M[j * n + i] = d[i] * s * d[j];
        }
    free(B);
    free(d);
}

static void random_fill(int len, unsigned long long seed, braun_real *x)
{
    for (int i = 0; i < len; i++) x[i] = test_frand(&seed);
}

/* max_i |a_i - b_i| / max(1, max_i |b_i|). */
static double rel_diff(int len, const braun_real *a, const braun_real *b)
{
    double d = 0, s = 1;
    for (int i = 0; i < len; i++) {
        d = fmax(d, fabs((double)a[i] - (double)b[i]));
        s = fmax(s, fabs((double)b[i]));
    }
    return d / s;
}

static double norm2(int len, const braun_real *x)
{
    double s = 0;
    for (int i = 0; i < len; i++) s += (double)x[i] * (double)x[i];
    return sqrt(s);
}

static int all_finite(int len, const braun_real *x)
{
    for (int i = 0; i < len; i++)
        if (!isfinite((double)x[i])) return 0;
    return 1;
}

/* y := A x, A rows x n row-major (plain loops: independent of both). */
static void matvec(int rows, int n, const braun_real *A, const braun_real *x, braun_real *y)
{
    for (int i = 0; i < rows; i++) {
        double s = 0;
        for (int k = 0; k < n; k++) s += (double)A[(size_t)i * (size_t)n + (size_t)k] * x[k];
        y[i] = (braun_real)s;
    }
}

/* y := A^T x. */
static void matvec_t(int rows, int n, const braun_real *A, const braun_real *x, braun_real *y)
{
    for (int k = 0; k < n; k++) y[k] = 0;
    for (int i = 0; i < rows; i++)
        for (int k = 0; k < n; k++) y[k] += A[(size_t)i * (size_t)n + (size_t)k] * x[i];
}

/* ------------------------------------------------------------------ */
/* The built-in kernels on caller buffers: M = R^T R, C = A R^-1 factored
 * as braun_eval.c does it (slot by slot). */
typedef struct ref_kernels {
    int n;
    braun_chol chol;
    braun_real *chol_reals;
    int *chol_ints;
    braun_qrcp f[2];
    braun_real *qr_reals[2];
    int *qr_ints[2];
} ref_kernels;

static void ref_open(ref_kernels *r, int n, int rows0, int rows1)
{
    memset(r, 0, sizeof *r);
    r->n = n;
    r->chol_reals = vec(BRAUN_CHOL_REALS(n));
    r->chol_ints = calloc(BRAUN_CHOL_INTS(n), sizeof(int));
    assert_non_null(r->chol_ints);
    braun_chol_bind(&r->chol, n, r->chol_reals, r->chol_ints);
    const int rows[2] = {rows0, rows1};
    for (int s = 0; s < 2; s++) {
        r->qr_reals[s] = vec(braun_qrcp_reals(n, rows[s]));
        r->qr_ints[s] = calloc(braun_qrcp_ints(rows[s]) + 1, sizeof(int));
        assert_non_null(r->qr_ints[s]);
        braun_qrcp_bind(&r->f[s], n, rows[s], r->qr_reals[s], r->qr_ints[s]);
    }
}

static void ref_close(ref_kernels *r)
{
    free(r->chol_reals);
    free(r->chol_ints);
    for (int s = 0; s < 2; s++) {
        free(r->qr_reals[s]);
        free(r->qr_ints[s]);
    }
}

static int ref_factor_c(ref_kernels *r, int slot, int rows, const braun_real *A, braun_real tol,
                        const braun_real *atil, braun_real *resid)
{
    const int n = r->n;
    braun_qrcp *f = &r->f[slot];
    f->rows = rows;
    for (int i = 0; i < rows; i++) {
        braun_real *ci = f->a + (size_t)i * (size_t)n;
        braun_chol_solve_rt_to(&r->chol, A + (size_t)i * (size_t)n, ci);
        if (atil && resid) resid[i] -= braun_dot(n, ci, atil);
    }
    return braun_qrcp_factor(f, tol);
}

/* The backend for a system of this size (create only reads the sizes). */
typedef struct backend {
    const braun_linsolver *ls;
    void *st;
} backend;

static void be_open(backend *b, int n, int m, int p)
{
    braun_model model;
    memset(&model, 0, sizeof model);
    model.sys.n = n;
    model.sys.m = m;
    model.sys.p = p;
    b->ls = braun_linsolver_lapack();
    assert_non_null(b->ls);
    b->st = NULL;
    assert_int_equal(b->ls->create(&b->st, &model), BRAUN_OK);
    assert_non_null(b->st);
}

static void be_close(backend *b)
{
    b->ls->destroy(b->st);
    b->st = NULL;
}

static braun_real default_tol(int rows, int n)
{
    return (braun_real)(10.0 * (rows > n ? rows : n) * DBL_EPSILON);
}

/* ------------------------------------------------------------------ */
static void test_table(void **state)
{
    (void)state;
    const braun_linsolver *ls = braun_linsolver_lapack();
    assert_non_null(ls);
    assert_string_equal(ls->name, "lapack");
    assert_int_equal(ls->flags, BRAUN_LS_DENSE);
    assert_non_null(ls->create);
    assert_non_null(ls->destroy);
    assert_non_null(ls->factor_mass);
    assert_non_null(ls->solve_rt);
    assert_non_null(ls->solve_r);
    assert_non_null(ls->mul_r);
    assert_non_null(ls->factor_c);
    assert_non_null(ls->pinv);
    assert_non_null(ls->lsq);
    assert_non_null(ls->null_project);
    assert_string_equal(braun_linsolver_name(ls), "lapack");
}

/* A table with neither create nor bind (a copy of this one with create and
 * destroy cleared): refused at braun_data_init, naming it (its operations
 * were handed a NULL state: "invalid argument 'mass'", and with
 * SuiteSparse's table a crash). */
static void test_table_without_state(void **state)
{
    (void)state;
    braun_linsolver t = *braun_linsolver_lapack();
    t.create = NULL;
    t.destroy = NULL;
    const braun_builtin *b = braun_builtin_find("four-bar");
    braun_model model;
    assert_int_equal(braun_model_init(&model, &b->sys), BRAUN_OK);
    model.opt.linsolver = &t;
    const size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes ? bytes : 1);
    braun_data d = {0};
    assert_int_equal(braun_data_init(&d, &model, buf, bytes), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(d.error.where, "neither create"));
    free(buf);
}

static const int SIZES[] = {5, 7, 12, 23, 40, 60};
#define NSIZES ((int)(sizeof SIZES / sizeof SIZES[0]))

/* factor_mass, solve_rt, solve_r, mul_r: the built-in results, and
 * R^-1 R^-T (M x) = x, R^T R x = M x. */
static void test_mass(void **state)
{
    (void)state;
    for (int t = 0; t < NSIZES; t++) {
        const int n = SIZES[t];
        braun_real *M = vec((size_t)n * (size_t)n), *x = vec((size_t)n), *b = vec((size_t)n),
                   *y1 = vec((size_t)n), *y2 = vec((size_t)n), *y3 = vec((size_t)n);
        random_spd(n, 100 + (unsigned long long)n, M);
        random_fill(n, 7 + (unsigned long long)n, x);
        ref_kernels ref;
        backend be;
        ref_open(&ref, n, 0, 0);
        be_open(&be, n, 0, 0);
        assert_int_equal(braun_chol_factor(&ref.chol, M, 1e3 * DBL_EPSILON, NULL, NULL, NULL),
                         BRAUN_OK);
        assert_int_equal(be.ls->factor_mass(be.st, M, 1e3 * DBL_EPSILON, NULL, NULL, NULL),
                         BRAUN_OK);

        /* R x against the built-in R x, and R^-T (M x) = R x. */
        be.ls->mul_r(be.st, x, y1);
        braun_chol_mul_r(&ref.chol, x, y2);
        assert_le(rel_diff(n, y1, y2), 1e-13);
        matvec(n, n, M, x, b);
        be.ls->solve_rt(be.st, b, y3);
        assert_le(rel_diff(n, y3, y1), 1e-12);

        /* Out of place and in place (x may alias b). */
        be.ls->solve_rt(be.st, b, y1);
        braun_chol_solve_rt_to(&ref.chol, b, y2);
        assert_le(rel_diff(n, y1, y2), 1e-12);
        memcpy(y3, b, (size_t)n * sizeof *b);
        be.ls->solve_rt(be.st, y3, y3);
        assert_le(rel_diff(n, y3, y1), 0);
        be.ls->solve_r(be.st, y1, y2);
        assert_le(rel_diff(n, y2, x), 1e-12); /* R^-1 R^-T M x = x */
        braun_chol_solve_r_to(&ref.chol, y1, y3);
        assert_le(rel_diff(n, y2, y3), 1e-12);
        be.ls->solve_r(be.st, y1, y1);
        assert_le(rel_diff(n, y1, y2), 0);

        be_close(&be);
        ref_close(&ref);
        free(M);
        free(x);
        free(b);
        free(y1);
        free(y2);
        free(y3);
    }
}

/* How the rows of A are built. */
enum a_kind {
    A_RANDOM,     /* full row rank (rows <= n) */
    A_DUPLICATE,  /* some rows repeated, some scaled copies */
    A_COMBINED,   /* rows that are combinations of earlier ones */
    A_ZERO_ROW,   /* an all-zero row */
    A_TALL,       /* more rows than coordinates */
    A_ZERO        /* A = 0 */
};

/* Fills A (rows x n); returns its rank. */
static int build_a(enum a_kind kind, int rows, int n, unsigned long long seed, braun_real *A)
{
    random_fill(rows * n, seed, A);
    switch (kind) {
    case A_RANDOM:
        return rows;
    case A_DUPLICATE: {
        /* rows/3 rows copy (or scale) earlier independent rows. */
        int dep = rows / 3 > 0 ? rows / 3 : 1;
        for (int i = rows - dep; i < rows; i++) {
            int src = (i * 7) % (rows - dep);
            double scale = (i % 2) ? 1.0 : -2.5;
            for (int k = 0; k < n; k++) A[i * n + k] = scale * A[src * n + k];
        }
        return rows - dep;
    }
    case A_COMBINED: {
        int dep = rows / 4 > 0 ? rows / 4 : 1;
        int indep = rows - dep;
        for (int i = indep; i < rows; i++) {
            unsigned long long s2 = seed + 1000 + (unsigned long long)i;
            for (int k = 0; k < n; k++) A[i * n + k] = 0;
            for (int j = 0; j < indep; j++) {
                double c = test_frand(&s2);
                for (int k = 0; k < n; k++) A[i * n + k] += c * A[j * n + k];
            }
        }
        return indep;
    }
    case A_ZERO_ROW:
        for (int k = 0; k < n; k++) A[(rows / 2) * n + k] = 0;
        return rows - 1;
    case A_TALL:
        return n;
    case A_ZERO:
        for (int i = 0; i < rows * n; i++) A[i] = 0;
        return 0;
    }
    return -1;
}

/* One system: both implementations on the same M and A (slot `slot`,
 * rows rows), every operation compared, and the definitions checked. */
static void check_case(int n, int rows, enum a_kind kind, unsigned long long seed)
{
    const int m = rows, p = 0;
    braun_real *M = vec((size_t)n * (size_t)n), *A = vec((size_t)rows * (size_t)n),
               *atil = vec((size_t)n), *res1 = vec((size_t)rows), *res2 = vec((size_t)rows),
               *r = vec((size_t)rows), *x1 = vec((size_t)n), *x2 = vec((size_t)n),
               *z1 = vec((size_t)n), *z2 = vec((size_t)n), *t1 = vec((size_t)n),
               *cr = vec((size_t)rows), *y = vec((size_t)n);
    random_spd(n, seed, M);
    const int expect = build_a(kind, rows, n, seed + 1, A);
    random_fill(n, seed + 2, atil);
    random_fill(rows, seed + 3, res1);
    memcpy(res2, res1, (size_t)rows * sizeof *res1);

    ref_kernels ref;
    backend be;
    ref_open(&ref, n, rows, 0);
    be_open(&be, n, m, p);
    const braun_real tol = default_tol(rows, n);
    assert_int_equal(braun_chol_factor(&ref.chol, M, 1e3 * DBL_EPSILON, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e3 * DBL_EPSILON, NULL, NULL, NULL), BRAUN_OK);
    int k1 = be.ls->factor_c(be.st, 0, rows, A, tol, atil, res1);
    int k2 = ref_factor_c(&ref, 0, rows, A, tol, atil, res2);
    assert_int_equal(k1, expect);
    assert_int_equal(k2, expect);
    assert_le(rel_diff(rows, res1, res2), 1e-12); /* resid -= C atil */

    /* C v = A R^-1 v, with the built-in R (independent of the backend's
     * QR): the test's own C. */
    braun_real *C = vec((size_t)rows * (size_t)n);
    for (int i = 0; i < rows; i++)
        braun_chol_solve_rt_to(&ref.chol, A + (size_t)i * (size_t)n, C + (size_t)i * (size_t)n);

    /* Inconsistent r (random) and consistent r (= C y). */
    for (int consistent = 0; consistent < 2; consistent++) {
        if (consistent) {
            random_fill(n, seed + 5, y);
            matvec(rows, n, C, y, r);
        } else {
            random_fill(rows, seed + 4, r);
        }
        braun_real rn1 = -1, rn2 = -1;
        be.ls->lsq(be.st, 0, r, x1, &rn1);
        braun_qrcp_lsq(&ref.f[0], r, x2, &rn2);
        const double scale = 1 + norm2(rows, r);
        assert_le(rel_diff(n, x1, x2), 1e-10);
        assert_near(rn1, rn2, 1e-10 * scale);
        /* pinv gives the same x. */
        be.ls->pinv(be.st, 0, r, z1);
        assert_le(rel_diff(n, z1, x1), 0);
        /* Residual definition: ||r - C x||. */
        matvec(rows, n, C, x1, cr);
        for (int i = 0; i < rows; i++) cr[i] = r[i] - cr[i];
        assert_near(rn1, norm2(rows, cr), 1e-10 * scale);
        if (consistent || expect == rows) {
            assert_le(rn1, 1e-10 * scale);
            assert_le(norm2(rows, cr), 1e-10 * scale);
        } else {
            assert_true(rn1 > 1e-3); /* a random r leaves range(C) */
        }
        /* Least squares: C^T (r - C x) = 0 ... */
        matvec_t(rows, n, C, cr, t1);
        assert_le(norm2(n, t1), 1e-10 * scale * (1 + norm2(rows * n, C)));
        /* ... of minimum norm: x in range(C^T), N x = 0. */
        memcpy(z1, x1, (size_t)n * sizeof *x1);
        be.ls->null_project(be.st, 0, z1);
        assert_le(norm2(n, z1), 1e-10 * scale);
    }

    /* N z: the built-in's, C N z = 0, N N z = N z, and N z = z - C^+ C z. */
    random_fill(n, seed + 6, z1);
    memcpy(z2, z1, (size_t)n * sizeof *z1);
    memcpy(y, z1, (size_t)n * sizeof *z1);
    be.ls->null_project(be.st, 0, z1);
    braun_qrcp_null_project(&ref.f[0], z2);
    assert_le(rel_diff(n, z1, z2), 1e-11);
    matvec(rows, n, C, z1, cr);
    assert_le(norm2(rows, cr), 1e-11 * (1 + norm2(rows * n, C)));
    memcpy(t1, z1, (size_t)n * sizeof *z1);
    be.ls->null_project(be.st, 0, t1);
    assert_le(rel_diff(n, t1, z1), 1e-12);
    matvec(rows, n, C, y, cr);
    be.ls->pinv(be.st, 0, cr, x1);
    for (int i = 0; i < n; i++) t1[i] = y[i] - x1[i];
    assert_le(rel_diff(n, t1, z1), 1e-10);
    if (expect == 0)
        assert_le(rel_diff(n, z1, y), 0); /* N = I */

    be_close(&be);
    ref_close(&ref);
    free(M);
    free(A);
    free(atil);
    free(res1);
    free(res2);
    free(r);
    free(x1);
    free(x2);
    free(z1);
    free(z2);
    free(t1);
    free(cr);
    free(y);
    free(C);
}

static void test_full_rank(void **state)
{
    (void)state;
    for (int t = 0; t < NSIZES; t++) {
        const int n = SIZES[t];
        check_case(n, 1, A_RANDOM, 11 + (unsigned long long)n);
        check_case(n, n / 3 > 0 ? n / 3 : 1, A_RANDOM, 12 + (unsigned long long)n);
        check_case(n, 2 * n / 3, A_RANDOM, 13 + (unsigned long long)n);
        check_case(n, n, A_RANDOM, 14 + (unsigned long long)n);
    }
}

static void test_rank_deficient(void **state)
{
    (void)state;
    for (int t = 0; t < NSIZES; t++) {
        const int n = SIZES[t];
        const int rows = 2 * n / 3 > 2 ? 2 * n / 3 : 3;
        check_case(n, rows, A_DUPLICATE, 21 + (unsigned long long)n);
        check_case(n, rows, A_COMBINED, 22 + (unsigned long long)n);
        check_case(n, rows, A_ZERO_ROW, 23 + (unsigned long long)n);
        check_case(n, n + n / 2 + 1, A_TALL, 24 + (unsigned long long)n);
        check_case(n, n, A_DUPLICATE, 25 + (unsigned long long)n);
        check_case(n, rows, A_ZERO, 26 + (unsigned long long)n);
    }
}

/* Slot 1 (C_q: the first m rows) and slot 0 (C_v: all m + p rows) keep
 * separate factorizations, in either order. */
static void test_two_slots(void **state)
{
    (void)state;
    const int n = 30, m = 12, p = 8, rows = m + p;
    braun_real *M = vec((size_t)n * n), *A = vec((size_t)rows * n), *r = vec((size_t)rows),
               *x1 = vec((size_t)n), *x2 = vec((size_t)n), *z1 = vec((size_t)n), *z2 = vec((size_t)n);
    random_spd(n, 31, M);
    random_fill(rows * n, 32, A);
    for (int k = 0; k < n; k++) A[5 * n + k] = A[2 * n + k]; /* C_q: rank m - 1 */
    random_fill(rows, 33, r);
    random_fill(n, 34, z1);
    ref_kernels ref;
    backend be;
    ref_open(&ref, n, rows, m);
    be_open(&be, n, m, p);
    assert_int_equal(braun_chol_factor(&ref.chol, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_c(be.st, 1, m, A, default_tol(m, n), NULL, NULL), m - 1);
    assert_int_equal(be.ls->factor_c(be.st, 0, rows, A, default_tol(rows, n), NULL, NULL),
                     rows - 1);
    assert_int_equal(ref_factor_c(&ref, 1, m, A, default_tol(m, n), NULL, NULL), m - 1);
    assert_int_equal(ref_factor_c(&ref, 0, rows, A, default_tol(rows, n), NULL, NULL), rows - 1);
    for (int slot = 0; slot < 2; slot++) {
        braun_real rn1, rn2;
        be.ls->lsq(be.st, slot, r, x1, &rn1);
        braun_qrcp_lsq(&ref.f[slot], r, x2, &rn2);
        assert_le(rel_diff(n, x1, x2), 1e-11);
        assert_near(rn1, rn2, 1e-11);
        memcpy(z2, z1, (size_t)n * sizeof *z1);
        memcpy(x1, z1, (size_t)n * sizeof *z1);
        be.ls->null_project(be.st, slot, x1);
        braun_qrcp_null_project(&ref.f[slot], z2);
        assert_le(rel_diff(n, x1, z2), 1e-11);
    }
    /* The slots differ (else the test proves nothing). */
    be.ls->pinv(be.st, 0, r, x1);
    be.ls->pinv(be.st, 1, r, x2);
    assert_true(rel_diff(n, x1, x2) > 1e-3);
    /* Slot 1 after a new slot 0 is untouched. */
    assert_int_equal(be.ls->factor_c(be.st, 0, rows, A + 0, default_tol(rows, n), NULL, NULL),
                     rows - 1);
    be.ls->pinv(be.st, 1, r, x1);
    assert_le(rel_diff(n, x1, x2), 0);
    /* Slot 1 holds m rows at most; with p = 0 there is no slot 1. */
    assert_int_equal(be.ls->factor_c(be.st, 1, m + 1, A, 1e-12, NULL, NULL), BRAUN_ERR_SIZE);
    be_close(&be);
    be_open(&be, n, m, 0);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_c(be.st, 1, m, A, 1e-12, NULL, NULL), BRAUN_ERR_SIZE);
    assert_int_equal(be.ls->factor_c(be.st, 0, m, A, default_tol(m, n), NULL, NULL), m - 1);
    be_close(&be);
    ref_close(&ref);
    free(M);
    free(A);
    free(r);
    free(x1);
    free(x2);
    free(z1);
    free(z2);
}

/* The rank tolerance decides, as in the built-in kernels: a row 1e-10
 * away from dependence is kept by the default and dropped by 1e-6. */
static void test_rank_tolerance(void **state)
{
    (void)state;
    const int n = 3;
    const braun_real M[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const braun_real A[6] = {1, 0, 0, 1, 1e-10, 0};
    backend be;
    be_open(&be, n, 2, 0);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_c(be.st, 0, 2, A, 3 * DBL_EPSILON, NULL, NULL), 2);
    assert_int_equal(be.ls->factor_c(be.st, 0, 2, A, 1e-6, NULL, NULL), 1);
    be_close(&be);
}

/* The rank decision is relative: C scaled by 1e-150 ... 1e150 keeps its
 * rank, and C^+ scales inversely. */
static void test_rank_scale_invariant(void **state)
{
    (void)state;
    const int n = 9, rows = 6;
    braun_real M[81], A[54], As[54], r[6], x0[9], x[9], xs[9];
    random_spd(n, 81, M);
    build_a(A_DUPLICATE, rows, n, 82, A);
    random_fill(rows, 83, r);
    backend be;
    be_open(&be, n, rows, 0);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_c(be.st, 0, rows, A, default_tol(rows, n), NULL, NULL), 4);
    be.ls->pinv(be.st, 0, r, x0);
    const double scales[4] = {1e-150, 1e-12, 1e12, 1e150};
    for (int t = 0; t < 4; t++) {
        for (int i = 0; i < rows * n; i++) As[i] = A[i] * scales[t];
        assert_int_equal(be.ls->factor_c(be.st, 0, rows, As, default_tol(rows, n), NULL, NULL), 4);
        be.ls->pinv(be.st, 0, r, xs);
        for (int i = 0; i < n; i++) x[i] = xs[i] * scales[t];
        assert_le(rel_diff(n, x, x0), 1e-12);
    }
    be_close(&be);
}

/* S = D M D, D_kk = 2^(-40 + 60k/(n-1)): M with its coordinates in other
 * units, exactly (powers of 2). */
static void in_units(int n, const braun_real *M, braun_real *S)
{
    for (int k = 0; k < n * n; k++)
        S[k] = M[k] * (braun_real)ldexp(1, -40 + 60 * (k / n) / (n - 1)) *
               (braun_real)ldexp(1, -40 + 60 * (k % n) / (n - 1));
}

/* Errors of factor_mass: the same status, entry and value as
 * braun_chol_factor. */
static void check_mass_error(int n, const braun_real *M, int expect)
{
    ref_kernels ref;
    backend be;
    ref_open(&ref, n, 0, 0);
    be_open(&be, n, 1, 0);
    int i1 = -1, j1 = -1, i2 = -2, j2 = -2;
    braun_real v1 = 0, v2 = 1;
    const braun_real tol = 1e3 * DBL_EPSILON;
    assert_int_equal(braun_chol_factor(&ref.chol, M, tol, &i2, &j2, &v2), expect);
    assert_int_equal(be.ls->factor_mass(be.st, M, tol, &i1, &j1, &v1), expect);
    assert_int_equal(i1, i2);
    assert_int_equal(j1, j2);
    double dmax = 0;
    for (int i = 0; i < n; i++) dmax = fmax(dmax, fabs(M[i * n + i]));
    assert_near(v1, v2, 1e-10 * dmax);
    /* No factor: factor_c refuses. */
    assert_int_equal(be.ls->factor_c(be.st, 0, 1, M, 1e-12, NULL, NULL), BRAUN_ERR_ARGUMENT);
    /* NULL outputs are allowed. */
    assert_int_equal(be.ls->factor_mass(be.st, M, tol, NULL, NULL, NULL), expect);
    be_close(&be);
    ref_close(&ref);
}

static void test_mass_errors(void **state)
{
    (void)state;
    for (int t = 0; t < NSIZES; t++) {
        const int n = SIZES[t];
        braun_real *M = vec((size_t)n * (size_t)n), *S = vec((size_t)n * (size_t)n);
        random_spd(n, 41 + (unsigned long long)n, M);
        /* Nonsymmetric: one entry of the upper triangle off by 1e-6. */
        memcpy(S, M, (size_t)n * (size_t)n * sizeof *M);
        S[(n / 2) * n + n - 1] += 1e-6;
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SYMMETRIC);
        /* The lower triangle too (the check compares both). */
        memcpy(S, M, (size_t)n * (size_t)n * sizeof *M);
        S[(n - 1) * n + 1] -= 1e-6;
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SYMMETRIC);
        /* Indefinite: a negative diagonal entry (fails at pivot n - 2 at
         * the latest). */
        memcpy(S, M, (size_t)n * (size_t)n * sizeof *M);
        S[(n - 2) * n + n - 2] = -1;
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SPD);
        /* Semidefinite: row/column 3 duplicates row/column 1 (pivot 3 at
         * round-off level, or exactly 0). */
        memcpy(S, M, (size_t)n * (size_t)n * sizeof *M);
        for (int k = 0; k < n; k++) S[3 * n + k] = S[1 * n + k];
        for (int k = 0; k < n; k++) S[k * n + 3] = S[k * n + 1];
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SPD);
        /* Zero diagonal entry at 0. */
        memcpy(S, M, (size_t)n * (size_t)n * sizeof *M);
        for (int k = 0; k < n; k++) S[k] = S[k * n] = 0;
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SPD);
        /* In other units, D M D with D_kk from 2^-40 to 2^20 (powers of 2:
         * the factorization scales exactly): the same verdicts, each pivot
         * judged against its own diagonal entry. Diagonal entries 2^-80
         * beside 2^40 were refused (n·ε·max M_kk). */
        in_units(n, M, S);
        backend be;
        be_open(&be, n, 0, 0);
        assert_int_equal(be.ls->factor_mass(be.st, S, 1e-12, NULL, NULL, NULL), BRAUN_OK);
        be_close(&be);
        braun_real *T = vec((size_t)n * (size_t)n);
        memcpy(T, M, (size_t)n * (size_t)n * sizeof *M);
        for (int k = 0; k < n; k++) T[3 * n + k] = T[1 * n + k];
        for (int k = 0; k < n; k++) T[k * n + 3] = T[k * n + 1];
        in_units(n, T, S);
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SPD);
        /* An asymmetry of the pair (0, 1), 1e-6 of its own entries' root,
         * in those units (2^-40 of the largest): refused as the core
         * refuses it (against the largest entry it went unseen). */
        memcpy(T, M, (size_t)n * (size_t)n * sizeof *M);
        T[1] += (braun_real)(1e-6 * sqrt((double)M[0] * (double)M[n + 1]));
        in_units(n, T, S);
        check_mass_error(n, S, BRAUN_ERR_MASS_NOT_SYMMETRIC);
        free(T);
        free(M);
        free(S);
    }
    /* NaN on the diagonal: not SPD, at that pivot. */
    braun_real N3[9] = {2, 0, 0, 0, NAN, 0, 0, 0, 2};
    backend be;
    be_open(&be, 3, 0, 0);
    int bi = -1;
    assert_int_equal(be.ls->factor_mass(be.st, N3, 1e-12, &bi, NULL, NULL), BRAUN_ERR_MASS_NOT_SPD);
    assert_int_equal(bi, 1);
    be_close(&be);
}

/* Arguments: sizes at create, slots and row counts at factor_c. */
static void test_arguments(void **state)
{
    (void)state;
    const braun_linsolver *ls = braun_linsolver_lapack();
    braun_model model;
    memset(&model, 0, sizeof model);
    void *st = (void *)&model;
    assert_int_equal(ls->create(NULL, &model), BRAUN_ERR_ARGUMENT);
    assert_int_equal(ls->create(&st, NULL), BRAUN_ERR_ARGUMENT);
    assert_null(st);
    model.sys.n = 0;
    assert_int_equal(ls->create(&st, &model), BRAUN_ERR_SIZE);
    model.sys.n = 3;
    model.sys.m = -1;
    assert_int_equal(ls->create(&st, &model), BRAUN_ERR_SIZE);
    model.sys.m = 1;
    model.sys.p = BRAUN_MAX_DENSE + 1;
    assert_int_equal(ls->create(&st, &model), BRAUN_ERR_SIZE);
    model.sys.n = BRAUN_MAX_DENSE + 1;
    model.sys.p = 0;
    assert_int_equal(ls->create(&st, &model), BRAUN_ERR_SIZE);
    assert_null(st);
    ls->destroy(NULL);

    backend be;
    be_open(&be, 3, 2, 0);
    const braun_real M[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2}, A[6] = {1, 0, 0, 0, 1, 0};
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(be.ls->factor_c(be.st, 2, 2, A, 1e-12, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(be.ls->factor_c(be.st, -1, 2, A, 1e-12, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(be.ls->factor_c(be.st, 0, 3, A, 1e-12, NULL, NULL), BRAUN_ERR_SIZE);
    assert_int_equal(be.ls->factor_c(be.st, 0, -1, A, 1e-12, NULL, NULL), BRAUN_ERR_SIZE);
    assert_int_equal(be.ls->factor_c(be.st, 0, 2, NULL, 1e-12, NULL, NULL), BRAUN_ERR_ARGUMENT);
    /* Zero rows: rank 0, C^+ maps to 0, N = I. */
    assert_int_equal(be.ls->factor_c(be.st, 0, 0, A, 1e-12, NULL, NULL), 0);
    braun_real x[3] = {9, 9, 9}, z[3] = {1, 2, 3}, rn = -1;
    be.ls->lsq(be.st, 0, A, x, &rn);
    assert_true(x[0] == 0 && x[1] == 0 && x[2] == 0 && rn == 0);
    be.ls->null_project(be.st, 0, z);
    assert_true(z[0] == 1 && z[1] == 2 && z[2] == 3);
    /* Known answer: M = 2I, A = [e1; e2]: C = A/sqrt(2), C^+ r = sqrt(2) [r; 0]. */
    assert_int_equal(be.ls->factor_c(be.st, 0, 2, A, 1e-12, NULL, NULL), 2);
    const braun_real r[2] = {1, -3};
    be.ls->pinv(be.st, 0, r, x);
    assert_near(x[0], sqrt(2.0), 1e-15);
    assert_near(x[1], -3 * sqrt(2.0), 1e-15);
    assert_near(x[2], 0, 0);
    be.ls->null_project(be.st, 0, z);
    assert_near(z[0], 0, 1e-15);
    assert_near(z[1], 0, 1e-15);
    assert_near(z[2], 3, 1e-15);
    be_close(&be);
}

/* NaN reaches the results (the core checks results only), and Inf is
 * treated as by the built-in kernels: an infinite first pivot makes
 * every pivot "small" (Inf <= tol·Inf), rank 0, in both. */
static void test_nonfinite(void **state)
{
    (void)state;
    const int n = 6, rows = 4;
    braun_real M[36], A[24], atil[6], res[4], res2[4], r[4], x[6], x2[6];
    random_spd(n, 51, M);
    random_fill(rows, 53, r);
    ref_kernels ref;
    backend be;
    ref_open(&ref, n, rows, 0);
    be_open(&be, n, rows, 0);
    assert_int_equal(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_chol_factor(&ref.chol, M, 1e-12, NULL, NULL, NULL), BRAUN_OK);
    for (int bad = 0; bad < 4; bad++) {
        random_fill(rows * n, 52, A);
        random_fill(n, 54, atil);
        for (int i = 0; i < rows; i++) res[i] = res2[i] = 0;
        if (bad == 0) A[2 * n + 3] = NAN;
        if (bad == 1) atil[1] = NAN;
        if (bad == 2) A[n + 5] = INFINITY;
        if (bad == 3) A[n + 5] = -INFINITY;
        int k = be.ls->factor_c(be.st, 0, rows, A, default_tol(rows, n), atil, res);
        int k2 = ref_factor_c(&ref, 0, rows, A, default_tol(rows, n), atil, res2);
        assert_int_equal(k, k2);
        assert_int_equal(all_finite(rows, res), all_finite(rows, res2));
        be.ls->pinv(be.st, 0, bad == 1 ? res : r, x);
        braun_qrcp_pinv_apply(&ref.f[0], bad == 1 ? res2 : r, x2);
        assert_int_equal(all_finite(n, x), all_finite(n, x2));
        if (bad < 2) {
            assert_false(all_finite(n, x));
        } else {
            assert_int_equal(k, 0);
            assert_false(all_finite(rows, res));
        }
    }
    be_close(&be);
    ref_close(&ref);
}

/* The per-call operations never allocate. */
static void test_no_allocation(void **state)
{
    (void)state;
    if (!heap_counting()) {
        print_message("heap calls cannot be counted here (sanitizer, valgrind): skipped\n");
        skip();
    }
    const int n = 40, m = 15, p = 10, rows = m + p;
    braun_real *M = vec((size_t)n * n), *A = vec((size_t)rows * n), *atil = vec((size_t)n),
               *res = vec((size_t)rows), *x = vec((size_t)n), *y = vec((size_t)n);
    random_spd(n, 61, M);
    random_fill(rows * n, 62, A);
    for (int k = 0; k < n; k++) A[(rows - 1) * n + k] = A[k]; /* rank deficient */
    random_fill(n, 63, atil);
    backend be;
    be_open(&be, n, m, p);
    long before = heap_calls;
    braun_real rn;
    for (int rep = 0; rep < 3; rep++) {
        assert_true(be.ls->factor_mass(be.st, M, 1e-12, NULL, NULL, NULL) == BRAUN_OK);
        be.ls->solve_rt(be.st, atil, x);
        be.ls->solve_r(be.st, x, x);
        be.ls->mul_r(be.st, x, y);
        assert_true(be.ls->factor_c(be.st, 1, m, A, 1e-12, NULL, NULL) == m);
        assert_true(be.ls->factor_c(be.st, 0, rows, A, 1e-12, atil, res) == rows - 1);
        be.ls->pinv(be.st, 0, res, x);
        be.ls->lsq(be.st, 1, res, x, &rn);
        be.ls->null_project(be.st, 0, x);
        be.ls->null_project(be.st, 1, x);
    }
    long calls = heap_calls - before;
    be_close(&be);
    free(M);
    free(A);
    free(atil);
    free(res);
    free(x);
    free(y);
    assert_int_equal(calls, 0);
}

/* ------------------------------------------------------------------ */
/* End to end: the core with opt.linsolver = LAPACK against the built-in
 * kernels (NULL), 1000 RK4 steps from the same state. */
typedef struct run_result {
    double q[16], v[16];
    braun_stats stats;
    long allocs, frees, step_heap_calls;
} run_result;

static void run_steps(const braun_system *sys, const braun_real *q0, const braun_real *v0,
                      const braun_linsolver *ls, double h, int steps, run_result *out)
{
    braun_model model;
    braun_data data;
    const int n = sys->n;
    assert_true(n <= 16);
    assert_int_equal(braun_model_init(&model, sys), BRAUN_OK);
    model.opt.corrections = BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY |
                            (sys->energy ? BRAUN_CORRECT_ENERGY : 0u);
    model.opt.linsolver = ls;
    const size_t bytes = braun_data_size(&model);
    assert_true(bytes > 0);
    void *buffer = malloc(bytes);
    assert_non_null(buffer);
    const long a0 = heap_allocs, f0 = heap_frees;
    assert_int_equal(braun_data_init(&data, &model, buffer, bytes), BRAUN_OK);
    assert_int_equal(braun_set_state(&data, 0, q0, v0), BRAUN_OK);
    const long c0 = heap_calls;
    for (int k = 0; k < steps; k++) assert_int_equal(braun_step(&data, BRAUN_RK4, h), BRAUN_OK);
    out->step_heap_calls = heap_calls - c0;
    for (int i = 0; i < n; i++) {
        out->q[i] = data.q[i];
        out->v[i] = data.v[i];
    }
    out->stats = data.stats;
    braun_data_release(&data);
    braun_data_release(&data); /* twice is safe */
    out->allocs = heap_allocs - a0;
    out->frees = heap_frees - f0;
    free(buffer);
}

static void compare_runs(const char *what, const braun_system *sys, const braun_real *q0,
                         const braun_real *v0, double h, int steps)
{
    run_result a, b;
    run_steps(sys, q0, v0, NULL, h, steps, &a);
    run_steps(sys, q0, v0, braun_linsolver_lapack(), h, steps, &b);
    double dq = 0, dv = 0, sq = 1, sv = 1;
    for (int i = 0; i < sys->n; i++) {
        dq = fmax(dq, fabs(a.q[i] - b.q[i]));
        dv = fmax(dv, fabs(a.v[i] - b.v[i]));
        sq = fmax(sq, fabs(a.q[i]));
        sv = fmax(sv, fabs(a.v[i]));
    }
    print_message("%-28s %d RK4 steps h=%g: max|dq| %.2e max|dv| %.2e (rank deficient %ld / %ld)\n",
                  what, steps, h, dq, dv, b.stats.rank_deficient,
                  b.stats.constraint_factorizations);
    assert_le(dq, 1e-10 * sq);
    assert_le(dv, 1e-10 * sv);
    assert_int_equal(a.stats.steps, b.stats.steps);
    assert_int_equal(a.stats.rhs_evals, b.stats.rhs_evals);
    assert_int_equal(a.stats.mass_factorizations, b.stats.mass_factorizations);
    assert_int_equal(a.stats.constraint_factorizations, b.stats.constraint_factorizations);
    assert_int_equal(a.stats.rank_deficient, b.stats.rank_deficient);
    if (strstr(what, "singular") || strstr(what, "pendulum")) assert_true(b.stats.rank_deficient > 0);
    if (heap_counting()) {
        /* The built-in kernels allocate nothing; the backend allocates in
         * braun_data_init only, and braun_data_release frees all of it. */
        assert_int_equal(a.allocs, 0);
        assert_int_equal(a.frees, 0);
        assert_true(b.allocs > 0);
        assert_int_equal(b.frees, b.allocs);
        assert_int_equal(a.step_heap_calls, 0);
        assert_int_equal(b.step_heap_calls, 0);
    }
}

static void test_end_to_end_builtin_models(void **state)
{
    (void)state;
    const braun_builtin *sc = braun_builtin_find("slider-crank");
    const braun_builtin *fb = braun_builtin_find("four-bar");
    assert_non_null(sc);
    assert_non_null(fb);
    compare_runs("slider-crank", &sc->sys, sc->q0, sc->v0, 1e-3, 1000);
    compare_runs("four-bar", &fb->sys, fb->q0, fb->v0, 1e-2, 1000);
    /* From its singular configuration (all links horizontal: the five rows
     * lose rank), as tests/test_paper.c. */
    const braun_real q0[6] = {1, 0, 2, 0, 3, 0}, v0[6] = {0, 1, 0, 1, 0, 1};
    compare_runs("four-bar from singularity", &fb->sys, q0, v0, 1e-2, 1000);
}

/* Both slots (m = 2 holonomic + p = 1 nonholonomic rows) and redundant
 * rows (duplicated, duplicated and scaled: every factorization rank
 * deficient, C^+ through the complete orthogonal decomposition). */
static void test_end_to_end_test_systems(void **state)
{
    (void)state;
    braun_system g = generic_system();
    double qd[4], vd[4];
    braun_real q[4], v[4];
    generic_consistent_state(qd, vd);
    for (int i = 0; i < 4; i++) {
        q[i] = (braun_real)qd[i];
        v[i] = (braun_real)vd[i];
    }
    compare_runs("generic (m = 2, p = 1)", &g, q, v, 1e-3, 1000);
    q[0] += 1e-3; /* off the constraint: the corrections work */
    v[1] -= 2e-3;
    compare_runs("generic, perturbed", &g, q, v, 1e-3, 1000);
    for (int red = 1; red <= 2; red++) {
        pendulum_params prm;
        memset(&prm, 0, sizeof prm);
        prm.mass = 1;
        prm.L = 1;
        prm.g = 9.81;
        prm.redundancy = red;
        braun_system ps = pendulum_system(&prm);
        const braun_real q0[2] = {1.005, 0}, v0[2] = {0.1, 0.3};
        compare_runs(red == 1 ? "pendulum, duplicated row" : "pendulum, scaled duplicate", &ps,
                     q0, v0, 1e-3, 1000);
    }
    /* Rheonomic bead whose constraint power the core computes (mul_r). */
    double w = 1.3;
    braun_system bs = bead_system(&w);
    const braun_real bq0[2] = {1, 0}, bv0[2] = {0, 1.3};
    compare_runs("bead, constraint work", &bs, bq0, bv0, 1e-3, 1000);
}

/* The selection by name gives this table. */
static void test_select_by_name(void **state)
{
    (void)state;
    const braun_builtin *sc = braun_builtin_find("slider-crank");
    const braun_linsolver *ls = NULL;
    const char *why = "unset";
    assert_int_equal(braun_linsolver_select("lapack", &sc->sys, &ls, &why), BRAUN_OK);
    assert_ptr_equal(ls, braun_linsolver_lapack());
    assert_null(why);
}

/* ------------------------------------------------------------------ */
/* Timing (BRAUN_BENCH_LAPACK=1): factor_mass + factor_c + pinv. */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One evaluation's worth of linear algebra as braun_eval.c does it with
 * all corrections: factor M, atil = R^-T Q, factor C_v (b_v -= C atil),
 * u = C^+ b_v, lsq, a null-space projection, R^-1 z. what: 0 the three
 * operations of the brief (factor_mass + factor_c + pinv), 1 all. */
typedef struct bench_case {
    int n, rows;
    braun_real *M, *A, *Q, *b0, *res, *atil, *x, *z;
} bench_case;

static void run_builtin(bench_case *c, ref_kernels *ref, int what)
{
    const int n = c->n, rows = c->rows;
    braun_real rn;
    memcpy(c->res, c->b0, (size_t)rows * sizeof *c->res);
    assert_true(braun_chol_factor(&ref->chol, c->M, 1e-12, NULL, NULL, NULL) == BRAUN_OK);
    braun_chol_solve_rt_to(&ref->chol, c->Q, c->atil);
    ref_factor_c(ref, 0, rows, c->A, default_tol(rows, n), c->atil, c->res);
    braun_qrcp_pinv_apply(&ref->f[0], c->res, c->x);
    if (what) {
        braun_qrcp_lsq(&ref->f[0], c->res, c->z, &rn);
        braun_qrcp_null_project(&ref->f[0], c->z);
        braun_chol_solve_r_to(&ref->chol, c->z, c->z);
    }
}

static void run_lapack(bench_case *c, backend *be, int what)
{
    const int n = c->n, rows = c->rows;
    braun_real rn;
    memcpy(c->res, c->b0, (size_t)rows * sizeof *c->res);
    assert_true(be->ls->factor_mass(be->st, c->M, 1e-12, NULL, NULL, NULL) == BRAUN_OK);
    be->ls->solve_rt(be->st, c->Q, c->atil);
    be->ls->factor_c(be->st, 0, rows, c->A, default_tol(rows, n), c->atil, c->res);
    be->ls->pinv(be->st, 0, c->res, c->x);
    if (what) {
        be->ls->lsq(be->st, 0, c->res, c->z, &rn);
        be->ls->null_project(be->st, 0, c->z);
        be->ls->solve_r(be->st, c->z, c->z);
    }
}

/* Zero M outside 3x3 diagonal blocks, and each row of A outside two
 * blocks (M stays SPD: a principal block of an SPD matrix is SPD). */
static void mechanism_like(int n, int rows, braun_real *M, braun_real *A)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (i / 3 != j / 3) M[i * n + j] = 0;
    const int nb = (n + 2) / 3;
    for (int i = 0; i < rows; i++) {
        const int b1 = i % nb, b2 = (i * 7 + 1) % nb;
        for (int k = 0; k < n; k++)
            if (k / 3 != b1 && k / 3 != b2) A[i * n + k] = 0;
    }
}

static void bench_one(int kind, int n)
{
    bench_case c;
    const int rows = 2 * n / 3;
    c.n = n;
    c.rows = rows;
    c.M = vec((size_t)n * n);
    c.A = vec((size_t)rows * n);
    c.Q = vec((size_t)n);
    c.b0 = vec((size_t)rows);
    c.res = vec((size_t)rows);
    c.atil = vec((size_t)n);
    c.x = vec((size_t)n);
    c.z = vec((size_t)n);
    random_spd(n, 71, c.M);
    random_fill(rows * n, 72, c.A);
    if (kind == 1) mechanism_like(n, rows, c.M, c.A);
    random_fill(n, 73, c.Q);
    random_fill(rows, 74, c.b0);
    ref_kernels ref;
    backend be;
    ref_open(&ref, n, rows, 0);
    be_open(&be, n, rows, 0);
    braun_real *x1 = vec((size_t)n);
    /* Enough repetitions for ~0.1 s per implementation and round. */
    double flops = (double)n * n * n / 3 + (double)n * n * rows + 2.0 * n * rows * rows;
    int reps = (int)(1e8 / flops);
    if (reps < 2) reps = 2;
    double best[2][2] = {{1e30, 1e30}, {1e30, 1e30}};
    for (int what = 0; what < 2; what++)
        for (int round = 0; round < 5; round++) {
            double t0 = now();
            for (int k = 0; k < reps; k++) run_builtin(&c, &ref, what);
            best[what][0] = fmin(best[what][0], (now() - t0) / reps);
            memcpy(x1, c.x, (size_t)n * sizeof *x1);
            t0 = now();
            for (int k = 0; k < reps; k++) run_lapack(&c, &be, what);
            best[what][1] = fmin(best[what][1], (now() - t0) / reps);
            assert_le(rel_diff(n, c.x, x1), 1e-8);
        }
    print_message("%6s %5d %5d | %9.4f %9.4f %6.2f | %9.4f %9.4f %6.2f\n",
                  kind ? "blocks" : "dense", n, rows,
                  1e3 * best[0][0], 1e3 * best[0][1], best[0][0] / best[0][1],
                  1e3 * best[1][0], 1e3 * best[1][1], best[1][0] / best[1][1]);
    be_close(&be);
    ref_close(&ref);
    free(c.M);
    free(c.A);
    free(c.Q);
    free(c.b0);
    free(c.res);
    free(c.atil);
    free(c.x);
    free(c.z);
    free(x1);
}

static void test_bench(void **state)
{
    (void)state;
    const char *env = getenv("BRAUN_BENCH_LAPACK");
    if (!env || !*env || strcmp(env, "0") == 0) {
        print_message("BRAUN_BENCH_LAPACK=1 times the backend: skipped\n");
        skip();
    }
    static const int NB[] = {6, 10, 15, 20, 30, 40, 50, 70, 100, 200, 400, 800};
    print_message("ms per call (best of 5 rounds), rows = 2n/3.\n"
                  "  3 ops: factor_mass + factor_c + pinv;  eval: the same + solve_rt, lsq,\n"
                  "  null_project, solve_r (one evaluation's linear algebra).\n"
                  "  dense: random dense M and A;  blocks: block-diagonal M (3x3 blocks) and\n"
                  "  rows touching two blocks (a planar multibody system handed over dense).\n");
    print_message("%6s %5s %5s | %9s %9s %6s | %9s %9s %6s\n", "", "n", "rows", "3 ops", "",
                  "", "eval", "", "");
    print_message("%6s %5s %5s | %9s %9s %6s | %9s %9s %6s\n", "kind", "", "", "built-in",
                  "lapack", "ratio", "built-in", "lapack", "ratio");
    for (int kind = 0; kind < 2; kind++)
        for (size_t t = 0; t < sizeof NB / sizeof NB[0]; t++) bench_one(kind, NB[t]);
}

int main(void)
{
    if (!braun_linsolver_lapack()) {
        /* libbraun_backends.a built with BRAUN_LAPACK=0: tools/run-tests
         * counts this line as one skipped test and says so. */
        printf("[  SKIPPED ] lapack backend not built (BRAUN_LAPACK=0)\n");
        return 0;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_table_without_state),
        cmocka_unit_test(test_mass),
        cmocka_unit_test(test_full_rank),
        cmocka_unit_test(test_rank_deficient),
        cmocka_unit_test(test_two_slots),
        cmocka_unit_test(test_rank_tolerance),
        cmocka_unit_test(test_rank_scale_invariant),
        cmocka_unit_test(test_mass_errors),
        cmocka_unit_test(test_arguments),
        cmocka_unit_test(test_nonfinite),
        cmocka_unit_test(test_no_allocation),
        cmocka_unit_test(test_end_to_end_builtin_models),
        cmocka_unit_test(test_end_to_end_test_systems),
        cmocka_unit_test(test_select_by_name),
        cmocka_unit_test(test_bench),
    };
    return cmocka_run_group_tests_name("backend_lapack", tests, NULL, NULL);
}
