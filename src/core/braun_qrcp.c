/* Rank-revealing pseudoinverse: Householder QR with column pivoting of C^T,
 * completed by a QR of the trapezoid when rows are dependent (see
 * braun_linalg.h). Sizes are small and dense; everything is in place. */
#include "braun_linalg.h"

/* Column j of the factor (R above the diagonal, its Householder vector
 * below) is stored where row perm[j] of C was written. */
#define COL(a, f, j, n) ((a) + (size_t)(f)->perm[j] * (size_t)(n))

size_t braun_qrcp_reals(int n, int rows)
{
    int w = n > rows ? n : rows;
    return (size_t)rows * (size_t)n      /* a */
           + (size_t)rows                /* tau */
           + (size_t)rows * (size_t)rows /* s */
           + (size_t)rows                /* stau */
           + (size_t)w                   /* work */
           + BRAUN_QRCP_SOFT_REALS(n, rows); /* soft */
}

size_t braun_qrcp_ints(int rows) { return (size_t)rows; }

void braun_qrcp_bind(braun_qrcp *f, int n, int rows, braun_real *reals,
                     int *ints)
{
    f->n = n;
    f->rows = rows;
    f->rank = 0;
    f->a = reals;
    f->tau = f->a + (size_t)rows * (size_t)n;
    f->s = f->tau + rows;
    f->stau = f->s + (size_t)rows * (size_t)rows;
    f->work = f->stau + rows;
    f->soft = f->work + (n > rows ? n : rows);
    f->nsoft = 0;
    f->dmin = 0;
    f->soft_lam = 0;
    f->r00 = 0;
    f->gram = 0;
    f->norms_given = 0;
    f->perm = ints;
}

/* Householder reflector for x[0..len): on return x[0] = beta, x[1..] = v[1..]
 * (v[0] = 1 implied) and H = I - tau v v^T maps x to beta e1. */
BRAUN_FORCE_INLINE braun_real house_n(int len, braun_real *x, braun_real normx)
{
    braun_real alpha = x[0];
    if (normx == 0) return 0;
    braun_real beta = alpha >= 0 ? -normx : normx;
    braun_real scale = 1 / (alpha - beta);
#define SCALE_BODY(L, UNROLL) \
    UNROLL for (int i = 1; i < (L); i++) x[i] *= scale /* NOLINT(bugprone-macro-parentheses): a pragma */
    BRAUN_SMALL_DISPATCH(len, SCALE_BODY)
#undef SCALE_BODY
    x[0] = beta;
    return (beta - alpha) / beta;
}

#define reflect braun_qrcp__reflect
/* Reflector j of f applied to vec[j..N) inside a dispatched body (its
 * length N - j a constant there); the caller skips tau_j = 0. */
#define REFLECT_J(N, UNROLL, j, vec)                                        \
    do {                                                                    \
        const braun_real *restrict vtail = COL(f->a, f, j, n) + (j) + 1;    \
        const braun_real tau = f->tau[j];                                   \
        braun_real *restrict y = (vec) + (j);                               \
        BRAUN_REFLECT_BODY((N) - (j), UNROLL);                              \
    } while (0)

/* The bound of a loop over indices below the rank k: with compile-time
 * sizes the constant min(n, rows), the body skipping j >= k (BELOW; the
 * loop then unrolls completely), else k itself (BELOW is then 1). */
#ifdef BRAUN_FIXED_N
#define KCAP(f, k) (BRAUN_N((f)->n) < BRAUN_ROWS((f)->rows) ? BRAUN_N((f)->n) : BRAUN_ROWS((f)->rows))
#define BELOW(j, k) ((j) < (k))
#else
#define KCAP(f, k) (k)
#define BELOW(j, k) 1
#endif

BRAUN_FORCE_INLINE braun_real sumsq_n(int len, const braun_real *x)
{
    braun_real s = 0;
#define SUMSQ_BODY(L, UNROLL) \
    UNROLL for (int i = 0; i < (L); i++) s += x[i] * x[i] /* NOLINT(bugprone-macro-parentheses): a pragma */
    BRAUN_SMALL_DISPATCH(len, SUMSQ_BODY)
#undef SUMSQ_BODY
    return s;
}

/* Out of line where the length is not a constant; the dispatched bodies
 * inline house_n and sumsq_n, their lengths folded. */
static braun_real house(int len, braun_real *x, braun_real normx) { return house_n(len, x, normx); }
static braun_real sumsq(int len, const braun_real *x) { return sumsq_n(len, x); }

/* Reflector k applied to the columns after it (the factorization's update;
 * column j at a + perm[j]·n + k): one length dispatch for all of them. */
BRAUN_FORCE_INLINE void reflect_cols(int len, const braun_real *restrict vtail, braun_real tau,
                         braun_real *a, const int *perm, int ncols, int n, int k)
{
    if (tau == 0) return;
#define COLS_BODY(L, UNROLL)                                                   \
    for (int c_ = 0; c_ < ncols; c_++) {                                       \
        braun_real *restrict y = a + (size_t)perm[c_] * (size_t)n + k;         \
        BRAUN_REFLECT_BODY(L, UNROLL);                                         \
    }
    BRAUN_SMALL_DISPATCH(len, COLS_BODY)
#undef COLS_BODY
}

int braun_qrcp_factor(braun_qrcp *f, braun_real tol)
{
    return braun_qrcp_factor_rule(f, tol, tol, f->rows, f->rows, 0);
}

/* Bring the column at position `best` to position k (pivoting permutes
 * the column order only: column j of the factor stays where row perm[j]
 * of C was written). */
static void swap_pivot(braun_qrcp *f, braun_real *norm2, braun_real *ref, int k, int best)
{
    if (best == k) return;
    int t = f->perm[k];
    f->perm[k] = f->perm[best];
    f->perm[best] = t;
    braun_real u = norm2[k];
    norm2[k] = norm2[best];
    norm2[best] = u;
    u = ref[k];
    ref[k] = ref[best];
    ref[best] = u;
}

int braun_qrcp_factor_rule(braun_qrcp *f, braun_real tol, braun_real tol_new, int keep, int cap, int same_rows)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
    int kmax = n < rows ? n : rows;
    if (cap < kmax) kmax = cap;
    braun_real *a = f->a;
    /* Squared norms of the remaining column parts, downdated after each
     * reflection (LAPACK xLAQP2); `ref` holds the value at the last exact
     * computation, to detect cancellation. Both live in scratch that is
     * free until the second stage. */
    braun_real *norm2 = f->work, *ref = f->stau;
    braun_real r00 = 0;
    /* At a step's later stages the rows a rank-deficient factorization of
     * the first stage set aside are set aside again (`aside`, in f->s,
     * free until the dependent rows' QR): the stages, off the manifold by
     * the step's own error, find those rows dependent only to that error,
     * and a stage that dropped another row would take another rank-`keep`
     * approximation of C, one that differs from the first stage's by that
     * error: RK4 lost its order on Bricard's linkage (docs/method.md,
     * "Rank decisions near singular configurations"). The kept rows are
     * still pivoted among themselves; one whose pivot falls to tol_new of
     * the largest column ends the rule (pivoting over every row). */
    braun_real *aside = f->s;
    int fixed = 0;
    if (same_rows && f->rank > 0 && f->rank < rows && f->rank == keep && !f->gram) {
        fixed = f->rank;
        for (int j = 0; j < rows; j++) aside[j] = 0;
        for (int j = fixed; j < rows; j++) aside[f->perm[j]] = 1;
    }

    if (BRAUN_FUSED_NORMS && f->norms_given) {
        /* The same sums, formed with C (braun_dense.h). */
        BRAUN_UNROLL
        for (int j = 0; j < rows; j++) {
            f->perm[j] = j;
            ref[j] = norm2[j];
        }
        f->norms_given = 0;
    } else {
        BRAUN_UNROLL
        for (int j = 0; j < rows; j++) {
            f->perm[j] = j;
            norm2[j] = ref[j] = sumsq(n, a + (size_t)j * (size_t)n);
        }
    }
    f->rank = 0;
    f->nsoft = 0;
    f->gram = 0;
    braun_real dmin = 0;
    BRAUN_UNROLL
    for (int k = 0; k < KCAP(f, kmax); k++) {
        if (!BELOW(k, kmax)) break;
        int best = k;
        if (k < fixed) {
            /* The largest of the rows not set aside (there are `fixed`). */
            best = -1;
            for (int j = k; j < rows; j++)
                if (aside[f->perm[j]] == 0 && (best < 0 || norm2[j] > norm2[best])) best = j;
            if (k == 0) {
                /* r00 the largest column norm, as the pivoted order's. */
                braun_real big = 0;
                for (int j = 0; j < rows; j++)
                    if (norm2[j] > big) big = norm2[j];
                r00 = braun_sqrt(big);
            }
        } else {
            BRAUN_UNROLL
            for (int j = k + 1; j < rows; j++)
                if (norm2[j] > norm2[best]) best = j;
        }
        swap_pivot(f, norm2, ref, k, best);
        braun_real *col = COL(a, f, k, n) + k;
        /* The pivot's norm is recomputed exactly: the rank decision must not
         * rest on a downdated value (at k = 0 the initial norms are exact:
         * the same sum in the same order). */
        braun_real pivot = braun_sqrt(k == 0 ? norm2[0] : sumsq(n - k, col));
        if (k < fixed && !(pivot > tol_new * r00)) {
            /* The kept rows are no longer clearly independent: pivot over
             * every row from here on. */
            fixed = 0;
            best = k;
            for (int j = k + 1; j < rows; j++)
                if (norm2[j] > norm2[best]) best = j;
            swap_pivot(f, norm2, ref, k, best);
            col = COL(a, f, k, n) + k;
            pivot = braun_sqrt(sumsq(n - k, col));
        }
        if (k == 0 && !fixed) r00 = pivot;
        /* Rank decision relative to the largest pivot (≈ ||C||_2); a pivot
         * beyond the first `keep` must also clear tol_new. */
        if (pivot == 0 || pivot <= tol * r00 || (k >= keep && pivot <= tol_new * r00)) break;
        /* |R_kk| = pivot: the smallest kept one, for the soft directions. */
        if (k == 0 || pivot < dmin) dmin = pivot;
        f->tau[k] = house(n - k, col, pivot);
        /* All later columns reflected with one length dispatch, then their
         * norms downdated (each column's operations as before). */
        reflect_cols(n - k, col + 1, f->tau[k], a, f->perm + k + 1, rows - k - 1, n, k);
        BRAUN_UNROLL
        for (int j = k + 1; j < rows; j++) {
            braun_real *cj = COL(a, f, j, n) + k;
            norm2[j] -= cj[0] * cj[0];
            /* Cancellation: recompute once the downdated value has lost
             * more than half of its digits (LAPACK's sqrt(eps) test). */
            if (norm2[j] <= braun_sqrt(BRAUN_EPS) * ref[j])
                norm2[j] = ref[j] = sumsq(n - k - 1, cj + 1);
        }
        f->rank = k + 1;
    }

    f->dmin = dmin;
    f->r00 = r00;
    /* Dependent rows: S = [R11 R12]^T is rows x k; factor it by Householder
     * QR (column-major in f->s) for the least-squares solve of S w = P^T r. */
    const int rk = f->rank;
    if (rk > 0 && rk < rows) {
        braun_real *s = f->s;
        BRAUN_UNROLL
        for (int j = 0; j < KCAP(f, rk); j++) {
            if (!BELOW(j, rk)) break;
            BRAUN_UNROLL
            for (int i = 0; i < rows; i++)
                s[(size_t)j * (size_t)rows + (size_t)i] = i >= j ? COL(a, f, i, n)[j] : 0;
        }
        BRAUN_UNROLL
        for (int j = 0; j < KCAP(f, rk); j++) {
            if (!BELOW(j, rk)) break;
            braun_real *cj = s + (size_t)j * (size_t)rows + j;
            f->stau[j] = house(rows - j, cj, braun_nrm2(rows - j, cj));
            BRAUN_UNROLL
            for (int c = j + 1; c < KCAP(f, rk); c++)
                if (BELOW(c, rk)) reflect(rows - j, cj + 1, f->stau[j], s + (size_t)c * (size_t)rows + j);
            /* The solves use T: its diagonal is the soft directions' gate. */
            const braun_real tjj = braun_fabs(cj[0]);
            if (j == 0 || tjj < f->dmin) f->dmin = tjj;
        }
    }
    return rk;
}

/* The factorization in the column order of the last one, without pivoting:
 * no pivot search, no swaps, no norm downdates. Valid while every pivot
 * clears gate·r00 (r00 the largest column norm, as the pivoted
 * factorization's first pivot): then the rank is full whatever the order,
 * and the solves give C⁺ to round-off. Returns the rank (= rows), or -1 when
 * a pivot falls below the gate; then f->a is spent and the caller forms C
 * again for braun_qrcp_factor_rule. */
int braun_qrcp_factor_ordered(braun_qrcp *f, braun_real gate)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
    braun_real *a = f->a, *norm2 = f->work;
    if (rows > n || f->rank != rows || !(gate < 1)) {
        f->norms_given = 0;
        return -1;
    }
    /* The rows' squared norms: the largest is r00² (the same sums as the
     * pivoted factorization's first pass). */
    if (!(BRAUN_FUSED_NORMS && f->norms_given)) {
        BRAUN_UNROLL
        for (int j = 0; j < rows; j++) norm2[j] = sumsq(n, a + (size_t)j * (size_t)n);
    }
    f->norms_given = 0;
    f->gram = 0;
    braun_real big = 0;
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++)
        if (norm2[j] > big) big = norm2[j];
    const braun_real floor = gate * braun_sqrt(big);
    braun_real dmin = 0;
    f->nsoft = 0;
    /* One dispatch on n (braun_linalg.h): every length n - k a constant. */
#define ORDERED_BODY(N, UNROLL)                                                              \
    UNROLL for (int k = 0; k < (N); k++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        if (k >= rows) break;                                                                \
        braun_real *col = COL(a, f, k, n) + k;                                               \
        const braun_real pivot = braun_sqrt(k == 0 ? norm2[f->perm[0]] : sumsq_n((N) - k, col)); \
        if (!(pivot > floor)) { /* NaN too */                                                \
            f->rank = 0;                                                                     \
            return -1;                                                                       \
        }                                                                                    \
        if (k == 0 || pivot < dmin) dmin = pivot;                                            \
        f->tau[k] = house_n((N) - k, col, pivot);                                              \
        reflect_cols((N) - k, col + 1, f->tau[k], a, f->perm + k + 1, rows - k - 1, n, k);  \
    }
    BRAUN_SMALL_DISPATCH(n, ORDERED_BODY)
#undef ORDERED_BODY
    f->dmin = dmin;
    f->r00 = braun_fabs(COL(a, f, 0, n)[0]); /* |beta| of the first reflector */
    return rows;
}

/* x[n] := Q1 w = H_0 ... H_{k-1} [w; 0], k the rank. (One loop, not a
 * zero fill and a copy: compilers turn a zero fill into a memset call,
 * which costs a small-vector kernel more than the fill itself on a
 * Cortex-M.) */
static inline void apply_q1(const braun_qrcp *f, int k, const braun_real *w, braun_real *x)
{
    const int n = BRAUN_N(f->n);
#ifdef BRAUN_FIXED_N
    BRAUN_UNROLL
    for (int i = 0; i < n; i++) x[i] = i < k ? w[i] : 0;
    BRAUN_UNROLL
    for (int j = KCAP(f, k) - 1; j >= 0; j--)
        if (BELOW(j, k)) reflect(n - j, COL(f->a, f, j, n) + j + 1, f->tau[j], x + j);
#else
    /* One dispatch on n: every reflector's length n - j a constant. */
#define Q1_BODY(N, UNROLL)                                                          \
    UNROLL for (int i = 0; i < (N); i++) x[i] = i < k ? w[i] : 0; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
    UNROLL for (int j = (N) - 1; j >= 0; j--) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        if (j >= k || f->tau[j] == 0) continue;                                     \
        REFLECT_J(N, UNROLL, j, x);                                                 \
    }
    BRAUN_SMALL_DISPATCH(n, Q1_BODY)
#undef Q1_BODY
#endif
}

/* Least squares through S = U T: w = T^-1 (U^T P^T r)[0..k) (rank k < rows). */
static void lsq_deficient(const braun_qrcp *f, braun_real *w, braun_real *resid)
{
    const int rows = BRAUN_ROWS(f->rows), rk = f->rank;
    const braun_real *s = f->s;
    BRAUN_UNROLL
    for (int j = 0; j < KCAP(f, rk); j++)
        if (BELOW(j, rk)) reflect(rows - j, s + (size_t)j * (size_t)rows + j + 1, f->stau[j], w + j);
    /* U^T P^T r below the rank: the part of r outside range(C). */
    if (resid) *resid = braun_nrm2(rows - rk, w + rk);
    BRAUN_UNROLL
    for (int i = KCAP(f, rk) - 1; i >= 0; i--) {
        if (!BELOW(i, rk)) continue;
        braun_real sum = w[i];
        BRAUN_UNROLL
        for (int c = i + 1; c < KCAP(f, rk); c++)
            if (BELOW(c, rk)) sum -= s[(size_t)c * (size_t)rows + (size_t)i] * w[c];
        w[i] = sum / s[(size_t)i * (size_t)rows + (size_t)i];
    }
}

void braun_qrcp__qr_lsq(const braun_qrcp *f, const braun_real *r, braun_real *x,
                        braun_real *resid)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows), rk = f->rank;
    const braun_real *a = f->a;
    braun_real *w = f->work;

    if (resid) *resid = 0;
    if (rk == 0) {
        for (int i = 0; i < n; i++) x[i] = 0;
        if (resid) *resid = braun_nrm2(rows, r);
        return;
    }
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++) w[j] = r[f->perm[j]];
    if (rk == rows) {
        /* S = R11^T is lower triangular: forward substitution. (The bounds
         * are `rows`, equal to the rank here: constants with compile-time
         * sizes.) */
#define FORWARD_BODY(R, UNROLL)                                  \
    UNROLL for (int i = 0; i < (R); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        braun_real sum = w[i];                                   \
        const braun_real *ci = COL(a, f, i, n); /* R(j,i) = ci[j] */ \
        UNROLL for (int j = 0; j < i; j++) sum -= ci[j] * w[j]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        w[i] = sum / ci[i];                                      \
    }
        BRAUN_SMALL_DISPATCH(rows, FORWARD_BODY)
#undef FORWARD_BODY
#ifdef BRAUN_FIXED_N
        apply_q1(f, rows, w, x); /* a constant rank: unrolled */
        return;
#endif
    } else {
        lsq_deficient(f, w, resid);
    }
    apply_q1(f, rk, w, x);
}

/* Two right-hand sides with full row rank (the position and velocity
 * corrections share C): each the operations of braun_qrcp__qr_lsq in the same
 * order, the permutation, the triangle and the reflectors walked once. The
 * second work vector is f->s, scratch unless the rank is deficient. */
void braun_qrcp__qr_pinv2(const braun_qrcp *f, const braun_real *r1, const braun_real *r2,
                          braun_real *x1, braun_real *x2)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows), rk = f->rank;
    if (rk != rows || rk == 0) {
        braun_qrcp__qr_lsq(f, r1, x1, NULL);
        braun_qrcp__qr_lsq(f, r2, x2, NULL);
        return;
    }
    const braun_real *a = f->a;
    braun_real *w = f->work, *w2 = f->s;
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++) {
        w[j] = r1[f->perm[j]];
        w2[j] = r2[f->perm[j]];
    }
#define FORWARD2_BODY(R, UNROLL)                                                    \
    UNROLL for (int i = 0; i < (R); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        braun_real sum = w[i], sum2 = w2[i];                                        \
        const braun_real *ci = COL(a, f, i, n);                                     \
        UNROLL for (int j = 0; j < i; j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            sum -= ci[j] * w[j];                                                    \
            sum2 -= ci[j] * w2[j];                                                  \
        }                                                                           \
        w[i] = sum / ci[i];                                                         \
        w2[i] = sum2 / ci[i];                                                       \
    }
    BRAUN_SMALL_DISPATCH(rows, FORWARD2_BODY)
#undef FORWARD2_BODY
#define Q1_2_BODY(N, UNROLL)                                                        \
    UNROLL for (int i = 0; i < (N); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        x1[i] = i < rk ? w[i] : 0;                                                  \
        x2[i] = i < rk ? w2[i] : 0;                                                 \
    }                                                                               \
    UNROLL for (int j = (N) - 1; j >= 0; j--) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        if (j >= rk || f->tau[j] == 0) continue;                                    \
        REFLECT_J(N, UNROLL, j, x1);                                                \
        REFLECT_J(N, UNROLL, j, x2);                                                \
    }
    BRAUN_SMALL_DISPATCH(n, Q1_2_BODY)
#undef Q1_2_BODY
}

void braun_qrcp__qr_null_project(const braun_qrcp *f, braun_real *z)
{
    const int n = BRAUN_N(f->n), rk = f->rank;
    if (rk == 0) return;
#ifdef BRAUN_FIXED_N
    const braun_real *a = f->a;
    BRAUN_UNROLL
    for (int j = 0; j < KCAP(f, rk); j++)
        if (BELOW(j, rk)) reflect(n - j, COL(a, f, j, n) + j + 1, f->tau[j], z + j);
    /* z := Q [0; z2]: H_j touches z[j..n) only, so zeroing z[j] just before
     * it is the same as zeroing z[0..rk) first (and needs no memset). */
    BRAUN_UNROLL
    for (int j = KCAP(f, rk) - 1; j >= 0; j--) {
        if (!BELOW(j, rk)) continue;
        z[j] = 0;
        reflect(n - j, COL(a, f, j, n) + j + 1, f->tau[j], z + j);
    }
#else
    /* The same with one dispatch on n (apply_q1). */
#define NULL_BODY(N, UNROLL)                                                        \
    UNROLL for (int j = 0; j < (N); j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        if (j >= rk || f->tau[j] == 0) continue;                                    \
        REFLECT_J(N, UNROLL, j, z);                                                 \
    }                                                                               \
    UNROLL for (int j = (N) - 1; j >= 0; j--) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        if (j >= rk) continue;                                                      \
        z[j] = 0;                                                                   \
        if (f->tau[j] == 0) continue;                                               \
        REFLECT_J(N, UNROLL, j, z);                                                 \
    }
    BRAUN_SMALL_DISPATCH(n, NULL_BODY)
#undef NULL_BODY
#endif
}
