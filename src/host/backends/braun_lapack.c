/*
 * LAPACK backend of the linear-solver table (braun_linsolver.h): the same
 * operations as libbraun's dense kernels (src/core/braun_chol.c,
 * src/core/braun_qrcp.c), with LAPACK's blocked factorizations.
 *
 *   M = R^T R          xPOTRF. The row-major M is read as a column-major
 *                      matrix whose lower triangle is M's upper triangle
 *                      (the triangle braun_chol_factor reads); the factor
 *                      L = R^T then occupies, column-major, exactly the
 *                      memory of the row-major upper R.
 *   C^T = R^-T A^T     xTRSM on a copy of A: row-major A (rows x n) is A^T
 *                      column-major (n x rows, lda n).
 *   C^T P = Q R        xGEQP3 (QR with column pivoting of C^T = row pivoting
 *                      of C); rank k = leading pivots |R_jj| > tol·|R_00|.
 *   [R11 R12] = [T 0] Z  xTZRZF when k < rows: a complete orthogonal
 *                      decomposition (as xGELSY), so C^+ is the minimum-norm
 *                      least-squares solution.
 *
 *   C^+ r = Q1 T^-T [I 0] Z P^T r     (Z = I when k = rows)
 *   ||r - C C^+ r|| = ||(Z P^T r)[k..rows)||
 *   z - C^+ C z = z - Q1 Q1^T z
 * The per-call products with Q and Z use the unblocked xORM2R / xORMR3: for
 * a single vector they are the cheapest (the blocked xORMQR / xORMRZ would
 * rebuild their triangular block factors at every call). No explicit
 * inverse, no allocation outside create().
 *
 * The Fortran routines are declared here (no LAPACKE): every argument by
 * reference, the hidden lengths of CHARACTER arguments passed explicitly
 * (size_t, gfortran >= 8), since gfortran may forward them in tail calls.
 */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "braun_backends.h"

#ifdef BRAUN_SINGLE
#define LA(name) s##name##_
#define LS_EPS FLT_EPSILON
#else
#define LA(name) d##name##_
#define LS_EPS DBL_EPSILON
#endif

typedef size_t fstrlen; /* hidden length of a CHARACTER argument */

/* BLAS */
void LA(trsv)(const char *uplo, const char *trans, const char *diag, const int *n,
              const braun_real *a, const int *lda, braun_real *x, const int *incx,
              fstrlen, fstrlen, fstrlen);
void LA(trmv)(const char *uplo, const char *trans, const char *diag, const int *n,
              const braun_real *a, const int *lda, braun_real *x, const int *incx,
              fstrlen, fstrlen, fstrlen);
void LA(trsm)(const char *side, const char *uplo, const char *transa, const char *diag,
              const int *m, const int *n, const braun_real *alpha, const braun_real *a,
              const int *lda, braun_real *b, const int *ldb, fstrlen, fstrlen, fstrlen,
              fstrlen);
void LA(gemv)(const char *trans, const int *m, const int *n, const braun_real *alpha,
              const braun_real *a, const int *lda, const braun_real *x, const int *incx,
              const braun_real *beta, braun_real *y, const int *incy, fstrlen);
braun_real LA(nrm2)(const int *n, const braun_real *x, const int *incx);
/* LAPACK */
void LA(potrf)(const char *uplo, const int *n, braun_real *a, const int *lda, int *info,
               fstrlen);
void LA(geqp3)(const int *m, const int *n, braun_real *a, const int *lda, int *jpvt,
               braun_real *tau, braun_real *work, const int *lwork, int *info);
void LA(tzrzf)(const int *m, const int *n, braun_real *a, const int *lda, braun_real *tau,
               braun_real *work, const int *lwork, int *info);
void LA(orm2r)(const char *side, const char *trans, const int *m, const int *n,
               const int *k, braun_real *a, const int *lda, const braun_real *tau,
               braun_real *c, const int *ldc, braun_real *work, int *info, fstrlen,
               fstrlen);
void LA(ormr3)(const char *side, const char *trans, const int *m, const int *n,
               const int *k, const int *l, braun_real *a, const int *lda,
               const braun_real *tau, braun_real *c, const int *ldc, braun_real *work,
               int *info, fstrlen, fstrlen);

static const int ONE = 1;

/* One factorization of C (slot 0: C_v, slot 1: C_q). */
typedef struct lapack_slot {
    int cap;          /* rows allocated (0: slot unused) */
    int rows;         /* rows of the current factorization */
    int rank;         /* k */
    braun_real *ct;   /* n x cap column-major: C^T, then QR / RZ factors */
    braun_real *tau;  /* min(n, cap): reflectors of Q */
    braun_real *ztau; /* cap: reflectors of Z */
    int *jpvt;        /* cap: column j of the factor is row jpvt[j] - 1 of C */
    int *kept;        /* cap: 1 for a row the last factorization kept */
    /* The rank rule of the next factorization (braun_linsolver.h). */
    int rule_keep, rule_cap;
    braun_real rule_tol_new;
} lapack_slot;

typedef struct lapack_state {
    int n;
    int have_r;       /* factor_mass succeeded */
    braun_real *R;    /* n x n: column-major L = R^T (row-major R) */
    lapack_slot slot[2];
    braun_real *w;    /* max(n, rows) + 1: permuted right-hand side */
    braun_real *work; /* lwork */
    int lwork;
    int later;        /* a step's later stages (ls_stage_order) */
} lapack_state;

static void ls_destroy(void *state)
{
    lapack_state *s = state;
    if (!s) return;
    free(s->R);
    for (int k = 0; k < 2; k++) {
        free(s->slot[k].ct);
        free(s->slot[k].tau);
        free(s->slot[k].ztau);
        free(s->slot[k].jpvt);
        free(s->slot[k].kept);
    }
    free(s->w);
    free(s->work);
    free(s);
}

static int imax(int a, int b) { return a > b ? a : b; }
static int imin(int a, int b) { return a < b ? a : b; }

/* Optimal workspace of xGEQP3 (n x rows) and of xTZRZF for any rank
 * deficient k (< rows, <= n); -1 on a failed query. */
static int query_lwork(int n, int rows)
{
    int lw = imax(n, rows) + 1, info = 0, minus1 = -1;
    braun_real q = 0, dummy[1] = {0};
    int jdummy[1] = {0};
    if (rows <= 0) return lw;
    LA(geqp3)(&n, &rows, dummy, &n, jdummy, dummy, &q, &minus1, &info);
    if (info != 0) return -1;
    lw = imax(lw, (int)q + 1);
    int kmax = imin(n, rows - 1);
    if (kmax > 0) {
        LA(tzrzf)(&kmax, &rows, dummy, &kmax, dummy, &q, &minus1, &info);
        if (info != 0) return -1;
        lw = imax(lw, (int)q + 1);
    }
    return lw;
}

static int ls_create(void **state, const braun_model *model)
{
    if (!state) return BRAUN_ERR_ARGUMENT;
    *state = NULL;
    if (!model) return BRAUN_ERR_ARGUMENT;
    const int n = model->sys.n, m = model->sys.m, p = model->sys.p;
    if (n < 1 || m < 0 || p < 0 || n > BRAUN_MAX_DENSE || m > BRAUN_MAX_DENSE ||
        p > BRAUN_MAX_DENSE)
        return BRAUN_ERR_SIZE;
    const int rows = m + p;
    lapack_state *s = calloc(1, sizeof *s);
    if (!s) return BRAUN_ERR_BUFFER;
    s->n = n;
    s->slot[0].cap = rows;
    s->slot[1].cap = (m > 0 && p > 0) ? m : 0;
    for (int k = 0; k < 2; k++) { /* no rule yet: the plain tolerance */
        s->slot[k].rule_keep = s->slot[k].rule_cap = s->slot[k].cap;
        s->slot[k].rule_tol_new = 0;
    }

    int ok = (s->R = malloc((size_t)n * (size_t)n * sizeof *s->R)) != NULL;
    s->lwork = imax(n, rows) + 1;
    for (int k = 0; k < 2 && ok; k++) {
        lapack_slot *f = &s->slot[k];
        if (f->cap == 0) continue;
        int lw = query_lwork(n, f->cap);
        if (lw < 0) {
            ls_destroy(s);
            return BRAUN_ERR_ARGUMENT;
        }
        s->lwork = imax(s->lwork, lw);
        ok = (f->ct = malloc((size_t)n * (size_t)f->cap * sizeof *f->ct)) != NULL &&
             (f->tau = malloc((size_t)imin(n, f->cap) * sizeof *f->tau)) != NULL &&
             (f->ztau = malloc((size_t)f->cap * sizeof *f->ztau)) != NULL &&
             (f->jpvt = malloc((size_t)f->cap * sizeof *f->jpvt)) != NULL &&
             (f->kept = malloc((size_t)f->cap * sizeof *f->kept)) != NULL;
    }
    ok = ok && (s->w = malloc(((size_t)imax(n, rows) + 1) * sizeof *s->w)) != NULL &&
         (s->work = malloc((size_t)s->lwork * sizeof *s->work)) != NULL;
    if (!ok) {
        ls_destroy(s);
        return BRAUN_ERR_BUFFER;
    }
    *state = s;
    return BRAUN_OK;
}

static int ls_factor_mass(void *state, const braun_real *M, braun_real sym_tol,
                          int *bad_i, int *bad_j, braun_real *bad_value)
{
    lapack_state *s = state;
    if (!s || !M) return BRAUN_ERR_ARGUMENT;
    const int n = s->n;
    s->have_r = 0;
    /* Symmetry is checked, not assumed (same order and test as
     * braun_chol_factor, each pair against its own diagonal entries: the
     * same entry is named). */
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            braun_real asym = M[(size_t)i * (size_t)n + (size_t)j] -
                              M[(size_t)j * (size_t)n + (size_t)i];
            const braun_real dd = M[(size_t)i * (size_t)n + (size_t)i] * M[(size_t)j * (size_t)n + (size_t)j];
            if (asym < 0) asym = -asym;
            if (asym * asym > sym_tol * sym_tol * (dd < 0 ? -dd : dd)) {
                if (bad_i) *bad_i = i;
                if (bad_j) *bad_j = j;
                if (bad_value) *bad_value = asym;
                return BRAUN_ERR_MASS_NOT_SYMMETRIC;
            }
        }
    memcpy(s->R, M, (size_t)n * (size_t)n * sizeof *s->R);
    int info = 0;
    LA(potrf)("L", &n, s->R, &n, &info, 1);
    if (info < 0) return BRAUN_ERR_ARGUMENT;
    /* A pivot at round-off level of its own diagonal entry means M is
     * singular to working precision (braun_chol_factor's test on the pivot
     * before its square root, n·ε·|M_ii|: no change of a coordinate's unit
     * changes it); the first one is named. A failed pivot (info > 0) is
     * left in place by xPOTRF. */
    const int failed = info > 0 ? info - 1 : n; /* xPOTRF's failed pivot */
    for (int i = 0; i < n && i <= failed; i++) {
        braun_real rii = s->R[(size_t)i * (size_t)n + (size_t)i];
        braun_real piv = i < failed ? rii * rii : rii;
        braun_real mii = M[(size_t)i * (size_t)n + (size_t)i];
        if (mii < 0) mii = -mii;
        if (!(piv > (braun_real)n * (braun_real)LS_EPS * mii)) {
            if (bad_i) *bad_i = i;
            if (bad_j) *bad_j = i;
            if (bad_value) *bad_value = piv;
            return BRAUN_ERR_MASS_NOT_SPD;
        }
    }
    s->have_r = 1;
    return BRAUN_OK;
}

/* x := R^-T b = L^-1 b. */
static void ls_solve_rt(void *state, const braun_real *b, braun_real *x)
{
    lapack_state *s = state;
    if (x != b) memcpy(x, b, (size_t)s->n * sizeof *x);
    LA(trsv)("L", "N", "N", &s->n, s->R, &s->n, x, &ONE, 1, 1, 1);
}

/* x := R^-1 b = L^-T b. */
static void ls_solve_r(void *state, const braun_real *b, braun_real *x)
{
    lapack_state *s = state;
    if (x != b) memcpy(x, b, (size_t)s->n * sizeof *x);
    LA(trsv)("L", "T", "N", &s->n, s->R, &s->n, x, &ONE, 1, 1, 1);
}

/* y := R x = L^T x. */
static void ls_mul_r(void *state, const braun_real *x, braun_real *y)
{
    lapack_state *s = state;
    if (y != x) memcpy(y, x, (size_t)s->n * sizeof *y);
    LA(trmv)("L", "T", "N", &s->n, s->R, &s->n, y, &ONE, 1, 1, 1);
}

static int ls_factor_c(void *state, int slot, int rows, const braun_real *A,
                       braun_real tol, const braun_real *atil, braun_real *resid)
{
    lapack_state *s = state;
    if (!s || slot < 0 || slot > 1) return BRAUN_ERR_ARGUMENT;
    lapack_slot *f = &s->slot[slot];
    const int n = s->n;
    /* At a step's later stages, the rows a rank-deficient first stage kept
     * are kept again (braun_linsolver.h, stage_order): xGEQP3 factors the
     * columns marked in jpvt first, then pivots over the others. */
    const int prev_rank = f->rank;
    const int same_rows = s->later && f->rows == rows && prev_rank > 0 && prev_rank < rows &&
                          prev_rank == f->rule_keep;
    if (same_rows) {
        for (int j = 0; j < rows; j++) f->kept[j] = 0;
        for (int j = 0; j < prev_rank; j++) f->kept[f->jpvt[j] - 1] = 1;
    }
    f->rows = 0;
    f->rank = 0;
    if (rows < 0 || rows > f->cap) return BRAUN_ERR_SIZE;
    if (!s->have_r || (rows > 0 && !A)) return BRAUN_ERR_ARGUMENT;
    if (rows == 0) return 0;

    const braun_real tol_new = f->rule_tol_new > tol ? f->rule_tol_new : tol;
    const braun_real one = 1, minus_one = -1;
    braun_real r00 = 0;
    int info = 0;
    for (int pass = same_rows ? 0 : 1; pass < 2; pass++) {
        /* C^T = L^-1 A^T (n x rows, column-major). */
        memcpy(f->ct, A, (size_t)rows * (size_t)n * sizeof *f->ct);
        LA(trsm)("L", "L", "N", "N", &n, &rows, &one, s->R, &n, f->ct, &n, 1, 1, 1, 1);
        /* resid -= C atil = (C^T)^T atil (once). */
        if (atil && resid && pass == (same_rows ? 0 : 1))
            LA(gemv)("T", &n, &rows, &minus_one, f->ct, &n, atil, &ONE, &one, resid, &ONE, 1);
        if (pass == 0) {
            /* r00 the largest column norm, as the pivoted order's first
             * pivot; the kept rows' pivots must clear tol_new of it. */
            for (int j = 0; j < rows; j++) {
                const braun_real c = LA(nrm2)(&n, f->ct + (size_t)j * (size_t)n, &ONE);
                if (c > r00) r00 = c;
                f->jpvt[j] = f->kept[j];
            }
        } else {
            /* C^T P = Q R, every column free to move. */
            for (int j = 0; j < rows; j++) f->jpvt[j] = 0;
        }
        LA(geqp3)(&n, &rows, f->ct, &n, f->jpvt, f->tau, s->work, &s->lwork, &info);
        if (info != 0) return BRAUN_ERR_ARGUMENT;
        if (pass == 1) {
            r00 = f->ct[0] < 0 ? -f->ct[0] : f->ct[0];
            break;
        }
        int clear = 1;
        for (int k = 0; k < prev_rank; k++) {
            braun_real piv = f->ct[(size_t)k * (size_t)n + (size_t)k];
            if (piv < 0) piv = -piv;
            if (!(piv > tol_new * r00)) clear = 0;
        }
        if (clear) break;
        /* The kept rows are no longer clearly independent: pivot freely. */
        r00 = 0;
    }
    f->rows = rows;

    /* Rank relative to the largest pivot, as braun_qrcp_factor (the same
     * comparisons: NaN pivots count, so NaN reaches the results). */
    const int kmax = imin(imin(n, rows), f->rule_cap);
    int k = 0;
    for (; k < kmax; k++) {
        braun_real piv = f->ct[(size_t)k * (size_t)n + (size_t)k];
        if (piv < 0) piv = -piv;
        if (piv == 0 || piv <= tol * r00 || (k >= f->rule_keep && piv <= tol_new * r00)) break;
    }
    f->rank = k;
    /* Dependent rows: [R11 R12] = [T 0] Z (R22 dropped). xTZRZF leaves the
     * Householder vectors of Q below the diagonal alone. */
    if (k > 0 && k < rows) {
        LA(tzrzf)(&k, &rows, f->ct, &n, f->ztau, s->work, &s->lwork, &info);
        if (info != 0) {
            f->rank = 0;
            return BRAUN_ERR_ARGUMENT;
        }
    }
    return k;
}

static void ls_lsq(void *state, int slot, const braun_real *r, braun_real *x,
                   braun_real *resid_norm)
{
    lapack_state *s = state;
    lapack_slot *f = &s->slot[slot];
    const int n = s->n, rows = f->rows, k = f->rank;
    braun_real *w = s->w;
    int info = 0;

    for (int i = 0; i < n; i++) x[i] = 0;
    if (resid_norm) *resid_norm = 0;
    if (k == 0) {
        if (resid_norm && rows > 0) *resid_norm = LA(nrm2)(&rows, r, &ONE);
        return;
    }
    for (int j = 0; j < rows; j++) w[j] = r[f->jpvt[j] - 1];
    if (k < rows) {
        /* w := Z P^T r; what lies below the rank is outside range(C). */
        const int l = rows - k;
        LA(ormr3)("L", "N", &rows, &ONE, &k, &l, f->ct, &n, f->ztau, w, &rows, s->work,
                  &info, 1, 1);
        if (resid_norm) *resid_norm = LA(nrm2)(&l, w + k, &ONE);
    }
    /* T^T y = w[0..k) (T: R11 when k = rows). */
    LA(trsv)("U", "T", "N", &k, f->ct, &n, w, &ONE, 1, 1, 1);
    /* x = Q [y; 0]. */
    memcpy(x, w, (size_t)k * sizeof *x);
    LA(orm2r)("L", "N", &n, &ONE, &k, f->ct, &n, f->tau, x, &n, s->work, &info, 1, 1);
}

static void ls_pinv(void *state, int slot, const braun_real *r, braun_real *x)
{
    ls_lsq(state, slot, r, x, NULL);
}

static void ls_null_project(void *state, int slot, braun_real *z)
{
    lapack_state *s = state;
    lapack_slot *f = &s->slot[slot];
    const int n = s->n, k = f->rank;
    int info = 0;
    if (k == 0) return;
    LA(orm2r)("L", "T", &n, &ONE, &k, f->ct, &n, f->tau, z, &n, s->work, &info, 1, 1);
    for (int j = 0; j < k; j++) z[j] = 0;
    LA(orm2r)("L", "N", &n, &ONE, &k, f->ct, &n, f->tau, z, &n, s->work, &info, 1, 1);
}

/* The next factorizations are a step's later stages (1) or its first. */
static void ls_stage_order(void *state, int later)
{
    lapack_state *s = state;
    if (s) s->later = later;
}

/* The rank rule of the slot's next factorization, as the built-in kernels'
 * (the same comparisons on the same pivots). */
static void ls_rank_rule(void *state, int slot, int keep, int cap, braun_real tol_new)
{
    lapack_state *s = state;
    if (!s || slot < 0 || slot > 1) return;
    s->slot[slot].rule_keep = keep;
    s->slot[slot].rule_cap = cap;
    s->slot[slot].rule_tol_new = tol_new;
}

static const braun_linsolver lapack_table = {
    "lapack",
    BRAUN_LS_DENSE,
    ls_create,
    ls_destroy,
    ls_factor_mass,
    ls_solve_rt,
    ls_solve_r,
    ls_mul_r,
    ls_factor_c,
    ls_pinv,
    ls_lsq,
    ls_null_project,
    NULL, /* state_bytes: created, not in the data block */
    NULL, /* bind */
    NULL, /* mass_buffer: the core keeps M */
    ls_rank_rule,
    NULL, /* soft_find: no soft-direction filter (docs/method.md) */
    NULL, /* soft_project */
    NULL, /* rhs_floor: the complete orthogonal decomposition's C^+ r is exact */
    ls_stage_order,
};

const braun_linsolver *braun_linsolver_lapack(void) { return &lapack_table; }
