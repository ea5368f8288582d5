/* Cholesky factorization M = R^T R of the mass matrix and its solves.
 * The solves skip the zero envelope of R (diagonal, banded and block mass
 * matrices cost O(n) or O(n·band) instead of O(n²)) — except at the short
 * lengths a dispatched body unrolls whole (below) — and multiply by the
 * stored reciprocal pivots. */
#include "braun_linalg.h"

void braun_chol_bind(braun_chol *c, int n, braun_real *reals, int *ints)
{
    c->n = n;
    c->R = reals;
    c->dinv = reals + (size_t)n * (size_t)n;
    c->first = ints;
    c->last = ints + n;
    c->diagonal = 0;
}

int braun_chol_factor(braun_chol *c, const braun_real *M, braun_real sym_tol,
                      int *bad_i, int *bad_j, braun_real *bad_value)
{
    const int n = BRAUN_N(c->n);
    braun_real *R = c->R;
    int i, j, k;
    /* Symmetry is checked, not assumed: a non-symmetric M is a modelling bug
     * the factorization would otherwise hide by reading one triangle. Each
     * pair against its own diagonal entries, |M_ij − M_ji| > sym_tol·
     * sqrt(|M_ii M_jj|) (M_ij has the units of that root: kg·m between a
     * position and an angle), so no change of a coordinate's unit changes
     * the verdict; against the largest M_ii (kg beside kg m²) an asymmetry
     * of a small body's coupling went unseen. Squared: no root per pair. */
    for (i = 0; i < n; i++)
        for (j = i + 1; j < n; j++) {
            braun_real asym = braun_fabs(M[i * n + j] - M[j * n + i]);
            if (asym * asym > sym_tol * sym_tol * braun_fabs(M[i * n + i] * M[j * n + j])) {
                if (bad_i) *bad_i = i;
                if (bad_j) *bad_j = j;
                if (bad_value) *bad_value = asym;
                return BRAUN_ERR_MASS_NOT_SYMMETRIC;
            }
        }
    /* Upper-triangle Cholesky, row by row (works in place when R == M). */
    for (i = 0; i < n; i++) {
        braun_real s = M[i * n + i];
        for (k = 0; k < i; k++) s -= R[k * n + i] * R[k * n + i];
        /* A pivot at round-off level of its own diagonal entry means M is
         * singular to working precision: refuse rather than amplify noise.
         * Its own entry, not the largest: this is the rule n·ε·max H_jj of
         * H = D M D, D = diag(M_jj^-1/2) (H_jj = 1), so no change of a
         * coordinate's unit (D M D for any diagonal D) changes the verdict;
         * max M_jj compared kg m² with kg and refused any rigid body whose
         * radius of gyration is below sqrt(n·ε) m. M_jj <= 0 or NaN fails. */
        if (!(s > (braun_real)n * BRAUN_EPS * braun_fabs(M[i * n + i]))) {
            if (bad_i) *bad_i = i;
            if (bad_j) *bad_j = i;
            if (bad_value) *bad_value = s;
            return BRAUN_ERR_MASS_NOT_SPD;
        }
        braun_real rii = braun_sqrt(s);
        R[i * n + i] = rii;
        c->dinv[i] = 1 / rii;
        for (j = i + 1; j < n; j++) {
            braun_real t = M[i * n + j];
            for (k = 0; k < i; k++) t -= R[k * n + i] * R[k * n + j];
            R[i * n + j] = t * c->dinv[i];
        }
        for (j = 0; j < i; j++) R[i * n + j] = 0;
    }
    /* Envelope: first nonzero row of each column, last nonzero column of
     * each row (exact zeros of R, e.g. all off-diagonals of a diagonal M). */
    for (j = 0; j < n; j++) {
        for (i = 0; i < j && R[i * n + j] == 0; i++) {}
        c->first[j] = i;
    }
    c->diagonal = 1;
    for (i = 0; i < n; i++) {
        for (j = n - 1; j > i && R[i * n + j] == 0; j--) {}
        c->last[i] = j;
        if (j != i) c->diagonal = 0;
    }
    return BRAUN_OK;
}

/* The solves and the product at a short length the compiler knows
 * (braun_linalg.h, BRAUN_SMALL_CONST): the whole triangle, unrolled, instead
 * of the envelope's loops, whose bounds cost 12–14 instructions per flop at
 * n = 6 (the four-bar's banded R: a quarter of its step). The zeros the
 * envelope skips add exact zeros (x finite): the same values, in the same
 * order. */
#define RT_BODY(N, UNROLL)                                                              \
    if (BRAUN_SMALL_CONST(N)) {                                                         \
        BRAUN_CHOL_RT_WHOLE(N, UNROLL, R, c->dinv, b, x)                                \
    } else {                                                                            \
        for (int i = 0; i < (N); i++) {                                                 \
            braun_real s = b[i];                                                        \
            for (int k = c->first[i]; k < i; k++) s -= R[k * (N) + i] * x[k];           \
            x[i] = s * c->dinv[i];                                                      \
        }                                                                               \
    }

void braun_chol_solve_rt_to(const braun_chol *c, const braun_real *b, braun_real *x)
{
    /* R^T is lower triangular: (R^T)_ik = R_ki, nonzero for k >= first[i]. */
    const int n = BRAUN_N(c->n);
    const braun_real *R = c->R;
    if (c->diagonal) {
        braun_chol_solve_diag(c, b, x);
        return;
    }
    BRAUN_SMALL_DISPATCH(n, RT_BODY)
}
#undef RT_BODY

#define R_BODY(N, UNROLL)                                                               \
    UNROLL for (int i = (N) - 1; i >= 0; i--) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        const braun_real *row = c->R + (size_t)i * (size_t)(N);                         \
        braun_real s = b[i];                                                            \
        if (BRAUN_SMALL_CONST(N)) {                                                     \
            UNROLL for (int k = i + 1; k < (N); k++) s -= row[k] * x[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        } else {                                                                        \
            for (int k = i + 1; k <= c->last[i]; k++) s -= row[k] * x[k];               \
        }                                                                               \
        x[i] = s * c->dinv[i];                                                          \
    }

void braun_chol_solve_r_to(const braun_chol *c, const braun_real *b, braun_real *x)
{
    const int n = BRAUN_N(c->n);
    if (c->diagonal) {
        braun_chol_solve_diag(c, b, x);
        return;
    }
    BRAUN_SMALL_DISPATCH(n, R_BODY)
}
#undef R_BODY

void braun_chol_solve_rt(const braun_chol *c, braun_real *x) { braun_chol_solve_rt_to(c, x, x); }

void braun_chol_solve_r(const braun_chol *c, braun_real *x) { braun_chol_solve_r_to(c, x, x); }

#define MUL_BODY(N, UNROLL)                                                             \
    UNROLL for (int i = 0; i < (N); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        const braun_real *row = c->R + (size_t)i * (size_t)(N);                         \
        braun_real s = 0;                                                               \
        if (BRAUN_SMALL_CONST(N)) {                                                     \
            UNROLL for (int k = i; k < (N); k++) s += row[k] * x[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        } else {                                                                        \
            for (int k = i; k <= c->last[i]; k++) s += row[k] * x[k];                   \
        }                                                                               \
        y[i] = s;                                                                       \
    }

void braun_chol_mul_r(const braun_chol *c, const braun_real *x, braun_real *y)
{
    const int n = BRAUN_N(c->n);
    BRAUN_SMALL_DISPATCH(n, MUL_BODY)
}
#undef MUL_BODY
