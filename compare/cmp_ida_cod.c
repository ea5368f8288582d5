/* A rank-revealing linear solver for IDA's Newton systems.
 *
 * At a kinematic singularity the constraint Jacobian loses rank and with it
 * the Newton matrix of any multiplier formulation; LU with partial
 * pivoting then returns corrections dominated by round-off along the
 * near-null directions (or fails outright). This solver factors the matrix
 * IDA assembles (dense difference quotients) by GSL's complete orthogonal
 * decomposition A P = Q R Z and returns the minimum-norm least-squares
 * correction, dropping directions whose pivot is below rtol·max|R_ii| —
 * the pseudoinverse the paper uses for the same reason (Sec. 3), applied
 * to IDA's iteration instead of the equation of motion. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_permutation.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "cmp.h"

typedef struct cod {
    int N;
    double rtol;
    gsl_matrix *qrzt;
    gsl_vector *tau_q, *tau_z, *work, *res;
    double *dr, *dc, *bs; /* row and column equilibration, scaled b */
    gsl_permutation *perm;
    size_t rank;
    long deficient;
    sunindextype last_flag;
} cod;

#define COD(S) ((cod *)(S)->content)

static SUNLinearSolver_Type cod_type(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID cod_id(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

static int cod_initialize(SUNLinearSolver S)
{
    COD(S)->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
}

static int cod_setup(SUNLinearSolver S, SUNMatrix A)
{
    cod *c = COD(S);
    const int N = c->N;
    /* Equilibrate (as LAPACK's xGEEQU): rows, then columns, to unit max
     * norm. The Newton matrix mixes c_j·M (c_j ~ 1/h) with O(1) constraint
     * gradients; a rank decision on the raw matrix would drop genuine
     * constraint directions once h is small. */
    for (int i = 0; i < N; i++) c->dr[i] = 0;
    for (int j = 0; j < N; j++) {
        const double *col = SUNDenseMatrix_Column(A, j);
        for (int i = 0; i < N; i++)
            if (fabs(col[i]) > c->dr[i]) c->dr[i] = fabs(col[i]);
    }
    for (int i = 0; i < N; i++) c->dr[i] = c->dr[i] > 0 ? 1.0 / c->dr[i] : 1.0;
    double amax = 0;
    for (int j = 0; j < N; j++) {
        const double *col = SUNDenseMatrix_Column(A, j);
        double cmax = 0;
        for (int i = 0; i < N; i++)
            if (fabs(col[i]) * c->dr[i] > cmax) cmax = fabs(col[i]) * c->dr[i];
        c->dc[j] = cmax > 0 ? 1.0 / cmax : 1.0;
        for (int i = 0; i < N; i++)
            gsl_matrix_set(c->qrzt, (size_t)i, (size_t)j, col[i] * c->dr[i] * c->dc[j]);
        if (cmax * c->dc[j] > amax) amax = cmax * c->dc[j];
    }
    /* GSL's tolerance is absolute; max|R_ii| <= sqrt(N)·max|a_ij|, so
     * rtol·sqrt(N)·max|a_ij| bounds the relative rule from above. */
    const double tol = c->rtol > 0 ? c->rtol * amax * sqrt((double)N) : -1.0;
    int st = gsl_linalg_COD_decomp_e(c->qrzt, c->tau_q, c->tau_z, c->perm, tol, &c->rank,
                                     c->work);
    if (st) {
        c->last_flag = SUNLS_PACKAGE_FAIL_REC;
        return SUNLS_PACKAGE_FAIL_REC;
    }
    if ((int)c->rank < N) c->deficient++;
    c->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
}

static int cod_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype tol)
{
    cod *c = COD(S);
    (void)A;
    (void)tol;
    double *bd = N_VGetArrayPointer(b), *xd = N_VGetArrayPointer(x);
    /* Solve (Dr A Dc) y = Dr b, x = Dc y; b and x may be the same vector. */
    for (int i = 0; i < c->N; i++) c->bs[i] = bd[i] * c->dr[i];
    gsl_vector_view bv = gsl_vector_view_array(c->bs, (size_t)c->N);
    gsl_vector_view xv = gsl_vector_view_array(xd, (size_t)c->N);
    int st = gsl_linalg_COD_lssolve(c->qrzt, c->tau_q, c->tau_z, c->perm, c->rank, &bv.vector,
                                    &xv.vector, c->res);
    for (int i = 0; i < c->N; i++) xd[i] *= c->dc[i];
    c->last_flag = st ? SUNLS_PACKAGE_FAIL_REC : SUNLS_SUCCESS;
    return (int)c->last_flag;
}

static sunindextype cod_last_flag(SUNLinearSolver S)
{
    return COD(S)->last_flag;
}

static int cod_space(SUNLinearSolver S, long *lrw, long *liw)
{
    const long N = COD(S)->N;
    *lrw = N * N + 5 * N;
    *liw = N + 2;
    return SUNLS_SUCCESS;
}

static int cod_free(SUNLinearSolver S)
{
    if (!S) return SUNLS_SUCCESS;
    cod *c = COD(S);
    if (c) {
        if (c->qrzt) gsl_matrix_free(c->qrzt);
        if (c->tau_q) gsl_vector_free(c->tau_q);
        if (c->tau_z) gsl_vector_free(c->tau_z);
        if (c->work) gsl_vector_free(c->work);
        if (c->res) gsl_vector_free(c->res);
        if (c->perm) gsl_permutation_free(c->perm);
        free(c->dr);
        free(c);
        S->content = NULL;
    }
    SUNLinSolFreeEmpty(S);
    return SUNLS_SUCCESS;
}

SUNLinearSolver cmp_sunlinsol_cod(int N, double rtol, SUNContext ctx)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
    if (!S) return NULL;
    cod *c = calloc(1, sizeof *c);
    S->content = c;
    S->ops->gettype = cod_type;
    S->ops->getid = cod_id;
    S->ops->initialize = cod_initialize;
    S->ops->setup = cod_setup;
    S->ops->solve = cod_solve;
    S->ops->lastflag = cod_last_flag;
    S->ops->space = cod_space;
    S->ops->free = cod_free;
    if (!c) {
        cod_free(S);
        return NULL;
    }
    c->N = N;
    c->rtol = rtol;
    c->qrzt = gsl_matrix_alloc((size_t)N, (size_t)N);
    c->tau_q = gsl_vector_alloc((size_t)N);
    c->tau_z = gsl_vector_alloc((size_t)N);
    c->work = gsl_vector_alloc((size_t)N);
    c->res = gsl_vector_alloc((size_t)N);
    c->perm = gsl_permutation_alloc((size_t)N);
    c->dr = malloc(3 * (size_t)N * sizeof(double));
    if (c->dr) {
        c->dc = c->dr + N;
        c->bs = c->dc + N;
    }
    if (!c->dr || !c->qrzt || !c->tau_q || !c->tau_z || !c->work || !c->res || !c->perm) {
        cod_free(S);
        return NULL;
    }
    return S;
}

long cmp_sunlinsol_cod_deficient(SUNLinearSolver S)
{
    return S && S->content ? COD(S)->deficient : 0;
}
