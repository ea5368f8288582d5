/* SUNDIALS IDA (6.4.1 API) on the DAE forms of cmp_dae.c.
 *
 * λ and μ are algebraic (IDASetId 0) and, unless spec->ida.no_suppress,
 * left out of the local error test (IDASetSuppressAlg). Their absolute
 * tolerance (spec->ida.alg_atol) still weighs them in the Newton
 * convergence test, which is where the singular configurations bite
 * (docs/compare.md, "IDA near singular configurations").
 *
 * Output: IDA_NORMAL to each grid time, interpolated by IDA. A failure
 * stops the run; the outcome keeps IDA's flag name, its last message and
 * the time reached. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "cmp.h"

typedef struct ida_ctx {
    cmp_dae *dae;
    int N;
    cmp_outcome *out;
    /* Sparse finite-difference Jacobian (KLU): fixed pattern, CSC. */
    sunindextype nnz, *colptr, *rowind;
    double *r0, *r1, *ypert, *yppert;
    long dropped;  /* Jacobian entries outside the pattern (should stay 0) */
} ida_ctx;

static int residual(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user)
{
    ida_ctx *c = user;
    return cmp_dae_residual(c->dae, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                            N_VGetArrayPointer(rr));
}

/* Keep IDA's last message for the outcome instead of printing it. */
static void on_error(int code, const char *module, const char *function, char *msg,
                     void *user)
{
    ida_ctx *c = user;
    (void)module;
    if (code < 0 && c->out)
        snprintf(c->out->detail, sizeof c->out->detail, "%s: %s", function, msg);
}

/* Column j of J = ∂F/∂y + c_j ∂F/∂y' by one forward difference, perturbing
 * y_j and y'_j together (as IDA's own dense difference quotient does). */
static int fd_column(ida_ctx *c, double t, double cj, const double *y, const double *yp,
                     int j, double *col)
{
    const int N = c->N;
    memcpy(c->ypert, y, (size_t)N * sizeof(double));
    memcpy(c->yppert, yp, (size_t)N * sizeof(double));
    double dj = 1.4901161193847656e-08 * fmax(fabs(y[j]), 1.0);
    c->ypert[j] += dj;
    c->yppert[j] += cj * dj;
    int st = cmp_dae_residual(c->dae, t, c->ypert, c->yppert, c->r1);
    if (st) return st;
    for (int i = 0; i < N; i++) col[i] = (c->r1[i] - c->r0[i]) / dj;
    return 0;
}

/* Sparsity pattern: the union of nonzeros of the difference-quotient
 * Jacobian at y0 and at three perturbed states (an entry that is zero at
 * y0 by coincidence, like a constraint gradient component at x = 0, is
 * nonzero at a perturbed state). */
static int sparse_pattern(ida_ctx *c, const double *y0, const double *yp0)
{
    const int N = c->N;
    unsigned char *mark = calloc((size_t)N * (size_t)N, 1);
    double *y = malloc(2 * (size_t)N * sizeof(double)), *col = malloc((size_t)N * sizeof(double));
    int st = -1;
    if (!mark || !y || !col) goto done;
    double *yp = y + N;
    unsigned long seed = 12345;
    for (int trial = 0; trial < 4; trial++) {
        for (int i = 0; i < N; i++) {
            seed = seed * 6364136223846793005UL + 1442695040888963407UL;
            double u = trial ? (double)(seed >> 11) / 9007199254740992.0 - 0.5 : 0.0;
            y[i] = y0[i] + 0.2 * u * fmax(fabs(y0[i]), 1.0);
            yp[i] = yp0[i] + 0.2 * u;
        }
        if (cmp_dae_residual(c->dae, 0.0, y, yp, c->r0)) goto done;
        for (int j = 0; j < N; j++) {
            if (fd_column(c, 0.0, 1.0, y, yp, j, col)) goto done;
            for (int i = 0; i < N; i++)
                if (col[i] != 0.0) mark[(size_t)j * N + i] = 1;
        }
    }
    for (int j = 0; j < N; j++) mark[(size_t)j * N + j] = 1; /* c_j on the diagonal */
    c->nnz = 0;
    for (size_t k = 0; k < (size_t)N * N; k++) c->nnz += mark[k];
    c->colptr = malloc(((size_t)N + 1) * sizeof(sunindextype));
    c->rowind = malloc((size_t)c->nnz * sizeof(sunindextype));
    if (!c->colptr || !c->rowind) goto done;
    sunindextype k = 0;
    for (int j = 0; j < N; j++) {
        c->colptr[j] = k;
        for (int i = 0; i < N; i++)
            if (mark[(size_t)j * N + i]) c->rowind[k++] = i;
    }
    c->colptr[N] = k;
    st = 0;
done:
    free(mark);
    free(y);
    free(col);
    return st;
}

/* IDALsJacFn for KLU: difference-quotient columns packed into the pattern. */
static int sparse_jac(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                      SUNMatrix J, void *user, N_Vector t1, N_Vector t2, N_Vector t3)
{
    ida_ctx *c = user;
    const int N = c->N;
    const double *y = N_VGetArrayPointer(yy), *ypd = N_VGetArrayPointer(yp);
    double *col = N_VGetArrayPointer(t1);
    (void)t2;
    (void)t3;
    memcpy(c->r0, N_VGetArrayPointer(rr), (size_t)N * sizeof(double));
    sunindextype *cp = SUNSparseMatrix_IndexPointers(J), *ri = SUNSparseMatrix_IndexValues(J);
    double *val = SUNSparseMatrix_Data(J);
    for (int j = 0; j <= N; j++) cp[j] = c->colptr[j];
    for (sunindextype k = 0; k < c->nnz; k++) ri[k] = c->rowind[k];
    for (int j = 0; j < N; j++) {
        int st = fd_column(c, t, cj, y, ypd, j, col);
        if (st) return st;
        for (sunindextype k = c->colptr[j]; k < c->colptr[j + 1]; k++) {
            val[k] = col[c->rowind[k]];
            col[c->rowind[k]] = 0;
        }
        for (int i = 0; i < N; i++)
            if (col[i] != 0.0) c->dropped++;
    }
    return 0;
}

/* Add IDA's counters to *k (called before IDAReInit, which zeroes them). */
static void add_counts(void *mem, cmp_linsol linsol, int N, cmp_counts *k)
{
    long v = 0, w = 0;
    IDAGetNumSteps(mem, &v);
    k->steps += v;
    IDAGetNumResEvals(mem, &v);
    IDAGetNumLinResEvals(mem, &w);
    k->rhs_evals += v + w;
    IDAGetNumJacEvals(mem, &v);
    k->jac_evals += v;
    /* The sparse Jacobian's difference quotients call the residual N times
     * per evaluation, outside IDA's counters. */
    if (linsol == CMP_LS_KLU) k->rhs_evals += v * (long)N;
    IDAGetNumLinSolvSetups(mem, &v);
    k->lin_setups += v;
    IDAGetNumNonlinSolvIters(mem, &v);
    k->lin_solves += v;
    IDAGetNumErrTestFails(mem, &v);
    k->err_fails += v;
    IDAGetNumNonlinSolvConvFails(mem, &v);
    k->conv_fails += v;
}

static void set_status(cmp_outcome *out, long flag)
{
    char *name = IDAGetReturnFlagName(flag);
    snprintf(out->status_name, sizeof out->status_name, "%s", name ? name : "IDA_UNKNOWN");
    free(name);
    out->status = (int)flag;
}

void cmp_run_ida(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                 cmp_outcome *out)
{
    const int index1 = spec->method == CMP_IDA_INDEX1;
    const int n = tg->sys.n;
    ida_ctx c;
    memset(&c, 0, sizeof c);
    memset(out, 0, sizeof *out);
    c.out = out;
    cmp_traj_clear(tr);

    SUNContext ctx = NULL;
    N_Vector yy = NULL, yp = NULL, id = NULL, avtol = NULL;
    SUNMatrix J = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    long flag = 0;
    int counted = 0; /* counters already added (a restart that failed midway) */
    cmp_linsol linsol = CMP_LS_DENSE;

    c.dae = cmp_dae_new(tg, index1);
    if (!c.dae || SUNContext_Create(NULL, &ctx)) {
        snprintf(out->status_name, sizeof out->status_name, "SETUP_FAILED");
        out->status = -1;
        goto done;
    }
    c.N = cmp_dae_size(c.dae);
    cmp_dae_set_reg(c.dae, spec->ida.reg);
    const int N = c.N;
    yy = N_VNew_Serial(N, ctx);
    yp = N_VNew_Serial(N, ctx);
    id = N_VNew_Serial(N, ctx);
    avtol = N_VNew_Serial(N, ctx);
    c.r0 = malloc(4 * (size_t)N * sizeof(double));
    if (!yy || !yp || !id || !avtol || !c.r0) {
        snprintf(out->status_name, sizeof out->status_name, "SETUP_FAILED");
        out->status = -1;
        goto done;
    }
    c.r1 = c.r0 + N;
    c.ypert = c.r1 + N;
    c.yppert = c.ypert + N;
    double *y = N_VGetArrayPointer(yy), *ydot = N_VGetArrayPointer(yp);
    if (cmp_dae_consistent(c.dae, 0.0, tg->q0, tg->v0, y, ydot)) {
        snprintf(out->status_name, sizeof out->status_name, "INCONSISTENT_INIT");
        snprintf(out->detail, sizeof out->detail, "projection of the initial state failed");
        out->status = -1;
        goto done;
    }
    double *idv = N_VGetArrayPointer(id), *atv = N_VGetArrayPointer(avtol);
    const double alg_atol = spec->ida.alg_atol > 0 ? spec->ida.alg_atol : spec->atol;
    for (int i = 0; i < N; i++) {
        const int differential = i < 2 * n;
        idv[i] = differential ? 1.0 : 0.0;
        atv[i] = differential ? spec->atol : alg_atol;
    }

    mem = IDACreate(ctx);
    if (!mem) {
        snprintf(out->status_name, sizeof out->status_name, "SETUP_FAILED");
        out->status = -1;
        goto done;
    }
    flag = IDAInit(mem, residual, 0.0, yy, yp);
    if (!flag) flag = IDASVtolerances(mem, spec->rtol, avtol);
    if (!flag) flag = IDASetUserData(mem, &c);
    if (!flag) flag = IDASetErrHandlerFn(mem, on_error, &c);
    if (!flag) flag = IDASetId(mem, id);
    if (!flag && !spec->ida.no_suppress) flag = IDASetSuppressAlg(mem, SUNTRUE);
    if (!flag) flag = IDASetMaxNumSteps(mem, 5000);
    if (!flag && spec->ida.max_step > 0) flag = IDASetMaxStep(mem, spec->ida.max_step);
    if (!flag && spec->ida.max_order > 0) flag = IDASetMaxOrd(mem, spec->ida.max_order);
    if (!flag && spec->ida.nl_conv_coef > 0)
        flag = IDASetNonlinConvCoef(mem, spec->ida.nl_conv_coef);
    linsol = spec->ida.linsol;
    if (linsol == CMP_LS_AUTO) linsol = N >= CMP_KLU_MIN_N ? CMP_LS_KLU : CMP_LS_DENSE;
    if (!flag) {
        if (linsol == CMP_LS_KLU) {
            if (sparse_pattern(&c, y, ydot)) {
                flag = -1;
            } else {
                J = SUNSparseMatrix(N, N, c.nnz, CSC_MAT, ctx);
                LS = J ? SUNLinSol_KLU(yy, J, ctx) : NULL;
                flag = LS ? IDASetLinearSolver(mem, LS, J) : -1;
                if (!flag) flag = IDASetJacFn(mem, sparse_jac);
            }
        } else {
            J = SUNDenseMatrix(N, N, ctx);
            if (linsol == CMP_LS_COD)
                LS = J ? cmp_sunlinsol_cod(N, spec->ida.cod_rtol, ctx) : NULL;
            else
                LS = J ? SUNLinSol_Dense(yy, J, ctx) : NULL;
            flag = LS ? IDASetLinearSolver(mem, LS, J) : -1;
        }
    }
    if (flag) {
        set_status(out, flag);
        if (!out->detail[0]) snprintf(out->detail, sizeof out->detail, "IDA setup failed");
        goto done;
    }

    cmp_traj_push(tr, 0.0, y, y + n);
    const long nout = (long)floor(spec->T / spec->dt_out + 0.5);
    for (long j = 1; j <= nout; j++) {
        double tout = j == nout ? spec->T : (double)j * spec->dt_out, tret = 0;
        flag = IDASolve(mem, tout, &tret, yy, yp, IDA_NORMAL);
        if (flag < 0 && flag != IDA_MEM_NULL && out->counts.restarts < spec->ida.restarts) {
            /* IDA returned the last successful step's state at tret:
             * re-project it, restart BDF at order 1 with a given first
             * step (which jumps over the point where the corrector failed)
             * and retry this output interval. */
            memcpy(c.ypert, y, (size_t)N * sizeof(double));
            if (tret < tout && cmp_dae_consistent(c.dae, tret, c.ypert, c.ypert + n, y, ydot) == 0) {
                add_counts(mem, linsol, c.N, &out->counts); /* IDAReInit zeroes them */
                if (IDAReInit(mem, tret, yy, yp) != IDA_SUCCESS ||
                    IDASetInitStep(mem, spec->ida.restart_h0) != IDA_SUCCESS) {
                    counted = 1;
                    break;
                }
                out->counts.restarts++;
                j--;
                continue;
            }
            memcpy(y, c.ypert, (size_t)N * sizeof(double));
        }
        if (flag < 0) break;
        if (cmp_traj_push(tr, tret, y, y + n)) {
            flag = -1;
            break;
        }
    }
    if (flag < 0) {
        set_status(out, flag);
    } else {
        out->status = 0;
        snprintf(out->status_name, sizeof out->status_name, "IDA_SUCCESS");
    }

done:
    if (mem) {
        sunrealtype tcur = 0;
        IDAGetCurrentTime(mem, &tcur);
        out->t_reached = out->status ? (tr->count ? tr->t[tr->count - 1] : 0.0) : spec->T;
        if (out->status && tcur > out->t_reached) out->t_reached = tcur;
        if (!counted) add_counts(mem, linsol, c.N, &out->counts);
        IDAFree(&mem);
    }
    if (LS) SUNLinSolFree(LS);
    if (J) SUNMatDestroy(J);
    if (yy) N_VDestroy(yy);
    if (yp) N_VDestroy(yp);
    if (id) N_VDestroy(id);
    if (avtol) N_VDestroy(avtol);
    if (ctx) SUNContext_Free(&ctx);
    free(c.r0);
    free(c.colptr);
    free(c.rowind);
    cmp_dae_free(c.dae);
}
