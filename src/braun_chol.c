/* Cholesky factorization M = R^T R of the mass matrix and its solves. */
#include "braun_linalg.h"

int braun_chol_factor(int n, const braun_real *M, braun_real *R,
                      braun_real sym_tol, int *bad_i, int *bad_j,
                      braun_real *bad_value)
{
    braun_real dmax = 0;
    int i, j, k;
    for (i = 0; i < n; i++) {
        braun_real d = braun_fabs(M[i * n + i]);
        if (d > dmax) dmax = d;
    }
    /* Symmetry is checked, not assumed: a non-symmetric M is a modelling bug
     * the factorization would otherwise hide by reading one triangle. */
    for (i = 0; i < n; i++)
        for (j = i + 1; j < n; j++) {
            braun_real asym = braun_fabs(M[i * n + j] - M[j * n + i]);
            if (asym > sym_tol * dmax) {
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
        /* A pivot at round-off level of the largest diagonal entry means M is
         * singular to working precision: refuse rather than amplify noise. */
        if (!(s > (braun_real)n * BRAUN_EPS * dmax)) {
            if (bad_i) *bad_i = i;
            if (bad_j) *bad_j = i;
            if (bad_value) *bad_value = s;
            return BRAUN_ERR_MASS_NOT_SPD;
        }
        braun_real rii = braun_sqrt(s);
        R[i * n + i] = rii;
        for (j = i + 1; j < n; j++) {
            braun_real t = M[i * n + j];
            for (k = 0; k < i; k++) t -= R[k * n + i] * R[k * n + j];
            R[i * n + j] = t / rii;
        }
        for (j = 0; j < i; j++) R[i * n + j] = 0;
    }
    return BRAUN_OK;
}

void braun_chol_solve_rt(int n, const braun_real *R, braun_real *x)
{
    /* R^T is lower triangular: (R^T)_ik = R_ki. */
    for (int i = 0; i < n; i++) {
        braun_real s = x[i];
        for (int k = 0; k < i; k++) s -= R[k * n + i] * x[k];
        x[i] = s / R[i * n + i];
    }
}

void braun_chol_solve_r(int n, const braun_real *R, braun_real *x)
{
    for (int i = n - 1; i >= 0; i--) {
        braun_real s = x[i];
        const braun_real *row = R + i * n;
        for (int k = i + 1; k < n; k++) s -= row[k] * x[k];
        x[i] = s / row[i];
    }
}
