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
    cmp_dae *dae;      /* callbacks' residual (NULL when the scene's is used) */
    cmp_ggl *ggl;      /* the scene provider (NULL if none or unused) */
    int scene_res;     /* 1: residual from ggl */
    int jac;           /* KLU: resolved cmp_jac_kind (ANALYTIC, COLORED, COLUMN) */
    int N, n;
    cmp_outcome *out;
    /* Sparse Jacobian (KLU): fixed pattern, CSC. */
    int nnz;
    const int *colptr, *rowind;
    int *own_colptr, *own_rowind;   /* when the pattern came from cmp_dae */
    cmp_fdjac *fd;
    long jac_res;      /* residual calls of the FD Jacobian not yet counted */
    long jac_res_total;
    double *ysave;     /* N: restart scratch */
} ida_ctx;

static int res_any(void *user, double t, const double *y, const double *yp, double *r)
{
    ida_ctx *c = user;
    return c->scene_res ? cmp_ggl_residual(c->ggl, t, y, yp, r)
                        : cmp_dae_residual(c->dae, t, y, yp, r);
}

static int residual(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user)
{
    return res_any(user, t, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp),
                   N_VGetArrayPointer(rr));
}

static int consistent(ida_ctx *c, double t, const double *q0, const double *v0, double *y,
                      double *yp)
{
    return c->scene_res ? cmp_ggl_consistent(c->ggl, t, q0, v0, y, yp)
                        : cmp_dae_consistent(c->dae, t, q0, v0, y, yp);
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

/* IDALsJacFn for KLU: the scene's analytic Jacobian, or finite differences
 * (colored, or column by column) packed into the pattern. */
static int sparse_jac(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                      SUNMatrix J, void *user, N_Vector t1, N_Vector t2, N_Vector t3)
{
    ida_ctx *c = user;
    const int N = c->N;
    const double *y = N_VGetArrayPointer(yy), *ypd = N_VGetArrayPointer(yp);
    (void)t1;
    (void)t2;
    (void)t3;
    sunindextype *cp = SUNSparseMatrix_IndexPointers(J), *ri = SUNSparseMatrix_IndexValues(J);
    double *val = SUNSparseMatrix_Data(J);
    for (int j = 0; j <= N; j++) cp[j] = c->colptr[j];
    for (int k = 0; k < c->nnz; k++) ri[k] = c->rowind[k];
    if (c->jac == CMP_JAC_ANALYTIC) return cmp_ggl_jacobian(c->ggl, t, cj, y, ypd, val);
    return cmp_fdjac_eval(c->fd, res_any, c, t, cj, y, ypd, N_VGetArrayPointer(rr), val,
                          &c->jac_res);
}

/* Add IDA's counters to *k (called before IDAReInit, which zeroes them). */
static void add_counts(void *mem, ida_ctx *c, cmp_counts *k)
{
    long v = 0, w = 0;
    IDAGetNumSteps(mem, &v);
    k->steps += v;
    IDAGetNumResEvals(mem, &v);
    IDAGetNumLinResEvals(mem, &w);
    k->rhs_evals += v + w;
    IDAGetNumJacEvals(mem, &v);
    k->jac_evals += v;
    /* The sparse finite-difference Jacobian calls the residual outside
     * IDA's counters: once per color (once per column without coloring). */
    k->rhs_evals += c->jac_res;
    c->jac_res_total += c->jac_res;
    c->jac_res = 0;
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

/* What a run is asked for beyond the spec, and what it reports back. */
typedef struct ida_io {
    const struct braun_scene *scene; /* for the provider (NULL: none) */
    long nout;                       /* output times (increasing, last = end) */
    const double *tout;
    int sample_t0;                   /* also sample the initial state */
    int (*sample)(void *u, long j, double t, const double *q, const double *v);
    void *u;
    long max_steps;                  /* per output interval */
    int stop_time;                   /* IDASetStopTime(last output time) */
    double *q_end, *v_end;           /* final state (may be NULL) */
    /* Reported. */
    int N, nnz, colors, jac, residual;
    long jac_res;
    double t_last;                   /* last output time reached */
    double cpu_setup, cpu_solve;
} ida_io;

static void setup_failed(cmp_outcome *out, const char *detail)
{
    snprintf(out->status_name, sizeof out->status_name, "SETUP_FAILED");
    if (detail && !out->detail[0]) snprintf(out->detail, sizeof out->detail, "%s", detail);
    out->status = -1;
}

/* The residual and Jacobian a KLU run uses (cmp_ida_opts.jac, .residual):
 * the scene provider when it exists and is wanted, callbacks and finite
 * differences otherwise. Sets c->ggl, c->scene_res, c->jac; 0 or -1. */
static int choose_klu(ida_ctx *c, const cmp_spec *spec, int index1,
                      const struct braun_scene *scene, cmp_outcome *out)
{
    int jac = spec->ida.jac, res = spec->ida.residual;
    const char *why = "index-1 form";
    if (!index1 && (jac == CMP_JAC_AUTO || jac == CMP_JAC_ANALYTIC || res != CMP_RES_CALLBACKS))
        c->ggl = cmp_ggl_new(scene, &why);
    if (!c->ggl && (jac == CMP_JAC_ANALYTIC || res == CMP_RES_SCENE)) {
        snprintf(out->detail, sizeof out->detail, "no analytic Jacobian for this target: %s",
                 why ? why : "?");
        return -1;
    }
    if (res == CMP_RES_AUTO) res = c->ggl ? CMP_RES_SCENE : CMP_RES_CALLBACKS;
    if (jac == CMP_JAC_AUTO) jac = c->ggl ? CMP_JAC_ANALYTIC : CMP_JAC_COLORED;
    if (c->ggl && res == CMP_RES_CALLBACKS && jac != CMP_JAC_ANALYTIC) {
        cmp_ggl_free(c->ggl);
        c->ggl = NULL;
    }
    c->scene_res = res == CMP_RES_SCENE;
    c->jac = jac;
    if (c->ggl) cmp_ggl_set_reg(c->ggl, spec->ida.reg);
    return 0;
}

static void run_core(const cmp_target *tg, const cmp_spec *spec, ida_io *io, cmp_outcome *out)
{
    const int index1 = spec->method == CMP_IDA_INDEX1;
    const int n = tg->sys.n;
    const double t0 = cmp_cpu_seconds();
    ida_ctx c;
    memset(&c, 0, sizeof c);
    memset(out, 0, sizeof *out);
    c.out = out;
    c.n = n;

    SUNContext ctx = NULL;
    N_Vector yy = NULL, yp = NULL, id = NULL, avtol = NULL;
    SUNMatrix J = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    long flag = 0;
    int counted = 0; /* counters already added (a restart that failed midway) */
    double t1 = t0;

    c.N = 2 * n + tg->sys.m + tg->sys.p + (index1 ? 0 : tg->sys.m);
    const int N = c.N;
    cmp_linsol linsol = spec->ida.linsol;
    if (linsol == CMP_LS_AUTO) linsol = N >= CMP_KLU_MIN_N ? CMP_LS_KLU : CMP_LS_DENSE;
    if (linsol == CMP_LS_KLU) {
        if (choose_klu(&c, spec, index1, io->scene, out)) {
            setup_failed(out, NULL);
            goto done;
        }
    }
    if (!c.scene_res) {
        c.dae = cmp_dae_new(tg, index1);
        if (!c.dae || cmp_dae_size(c.dae) != N) {
            setup_failed(out, NULL);
            goto done;
        }
        cmp_dae_set_reg(c.dae, spec->ida.reg);
    }
    if (SUNContext_Create(NULL, &ctx)) {
        setup_failed(out, NULL);
        goto done;
    }
    yy = N_VNew_Serial(N, ctx);
    yp = N_VNew_Serial(N, ctx);
    id = N_VNew_Serial(N, ctx);
    avtol = N_VNew_Serial(N, ctx);
    c.ysave = malloc((size_t)N * sizeof(double));
    if (!yy || !yp || !id || !avtol || !c.ysave) {
        setup_failed(out, NULL);
        goto done;
    }
    double *y = N_VGetArrayPointer(yy), *ydot = N_VGetArrayPointer(yp);
    if (consistent(&c, 0.0, tg->q0, tg->v0, y, ydot)) {
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
        setup_failed(out, NULL);
        goto done;
    }
    flag = IDAInit(mem, residual, 0.0, yy, yp);
    if (!flag) flag = IDASVtolerances(mem, spec->rtol, avtol);
    if (!flag) flag = IDASetUserData(mem, &c);
    if (!flag) flag = IDASetErrHandlerFn(mem, on_error, &c);
    if (!flag) flag = IDASetId(mem, id);
    if (!flag && !spec->ida.no_suppress) flag = IDASetSuppressAlg(mem, SUNTRUE);
    if (!flag) flag = IDASetMaxNumSteps(mem, io->max_steps);
    if (!flag && spec->ida.max_step > 0) flag = IDASetMaxStep(mem, spec->ida.max_step);
    if (!flag && spec->ida.max_order > 0) flag = IDASetMaxOrd(mem, spec->ida.max_order);
    if (!flag && spec->ida.nl_conv_coef > 0)
        flag = IDASetNonlinConvCoef(mem, spec->ida.nl_conv_coef);
    if (!flag && io->stop_time && io->nout > 0)
        flag = IDASetStopTime(mem, io->tout[io->nout - 1]);
    if (!flag) {
        if (linsol == CMP_LS_KLU) {
            /* The pattern: the scene's when its residual or Jacobian is
             * used, else found from the callbacks at the consistent state. */
            if (c.ggl && (c.scene_res || c.jac == CMP_JAC_ANALYTIC)) {
                c.nnz = cmp_ggl_pattern(c.ggl, &c.colptr, &c.rowind);
            } else {
                c.nnz = cmp_dae_pattern(c.dae, y, ydot, &c.own_colptr, &c.own_rowind);
                c.colptr = c.own_colptr;
                c.rowind = c.own_rowind;
            }
            if (c.nnz < 0) flag = -1;
            if (!flag && c.jac != CMP_JAC_ANALYTIC) {
                c.fd = cmp_fdjac_new(N, c.colptr, c.rowind, c.jac == CMP_JAC_COLORED);
                if (!c.fd) flag = -1;
            }
            if (!flag) {
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

    t1 = cmp_cpu_seconds();
    if (io->sample_t0 && io->sample(io->u, -1, 0.0, y, y + n)) {
        flag = -1;
        goto finish;
    }
    for (long j = 0; j < io->nout; j++) {
        double tout = io->tout[j], tret = 0;
        flag = IDASolve(mem, tout, &tret, yy, yp, IDA_NORMAL);
        if (flag < 0 && flag != IDA_MEM_NULL && out->counts.restarts < spec->ida.restarts) {
            /* IDA returned the last successful step's state at tret:
             * re-project it, restart BDF at order 1 with a given first
             * step (which jumps over the point where the corrector failed)
             * and retry this output interval. */
            memcpy(c.ysave, y, (size_t)N * sizeof(double));
            if (tret < tout && consistent(&c, tret, c.ysave, c.ysave + n, y, ydot) == 0) {
                add_counts(mem, &c, &out->counts); /* IDAReInit zeroes them */
                if (IDAReInit(mem, tret, yy, yp) != IDA_SUCCESS ||
                    IDASetInitStep(mem, spec->ida.restart_h0) != IDA_SUCCESS) {
                    counted = 1;
                    break;
                }
                out->counts.restarts++;
                j--;
                continue;
            }
            memcpy(y, c.ysave, (size_t)N * sizeof(double));
        }
        if (flag < 0) break;
        if (io->sample && io->sample(io->u, j, tret, y, y + n)) {
            flag = -1;
            break;
        }
        io->t_last = tret;
    }
finish:
    io->cpu_solve = cmp_cpu_seconds() - t1;
    if (flag < 0) {
        set_status(out, flag);
    } else {
        out->status = 0;
        snprintf(out->status_name, sizeof out->status_name, "IDA_SUCCESS");
    }
    if (io->q_end) memcpy(io->q_end, y, (size_t)n * sizeof(double));
    if (io->v_end) memcpy(io->v_end, y + n, (size_t)n * sizeof(double));

done:
    io->cpu_setup = t1 - t0;
    io->N = N;
    io->nnz = c.nnz;
    io->colors = c.fd ? cmp_fdjac_colors(c.fd) : 0;
    io->jac = linsol == CMP_LS_KLU ? c.jac : 0;
    io->residual = c.scene_res ? CMP_RES_SCENE : CMP_RES_CALLBACKS;
    if (mem) {
        sunrealtype tcur = 0;
        IDAGetCurrentTime(mem, &tcur);
        out->t_reached = out->status ? io->t_last : spec->T;
        if (out->status && tcur > out->t_reached) out->t_reached = tcur;
        if (!counted) add_counts(mem, &c, &out->counts);
        IDAFree(&mem);
    }
    io->jac_res = c.jac_res_total;
    if (LS) SUNLinSolFree(LS);
    if (J) SUNMatDestroy(J);
    if (yy) N_VDestroy(yy);
    if (yp) N_VDestroy(yp);
    if (id) N_VDestroy(id);
    if (avtol) N_VDestroy(avtol);
    if (ctx) SUNContext_Free(&ctx);
    free(c.ysave);
    free(c.own_colptr);
    free(c.own_rowind);
    cmp_fdjac_free(c.fd);
    cmp_ggl_free(c.ggl);
    cmp_dae_free(c.dae);
}

/* The study's sampling: every output time into the trajectory. */
static int push_traj(void *u, long j, double t, const double *q, const double *v)
{
    (void)j;
    return cmp_traj_push(u, t, q, v);
}

void cmp_run_ida(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                 cmp_outcome *out)
{
    cmp_traj_clear(tr);
    const long nout = (long)floor(spec->T / spec->dt_out + 0.5);
    double *tout = malloc(((size_t)(nout > 0 ? nout : 0) + 1) * sizeof(double));
    if (!tout) {
        memset(out, 0, sizeof *out);
        setup_failed(out, "out of memory");
        return;
    }
    for (long j = 1; j <= nout; j++) tout[j - 1] = j == nout ? spec->T : (double)j * spec->dt_out;
    ida_io io;
    memset(&io, 0, sizeof io);
    io.scene = cmp_target_scene(tg);
    io.nout = nout;
    io.tout = tout;
    io.sample_t0 = 1;
    io.sample = push_traj;
    io.u = tr;
    io.max_steps = 5000;
    run_core(tg, spec, &io, out);
    free(tout);
}

/* ------------------------------------------------------------ scaling entry point */
typedef struct run_samples {
    const cmp_ida_run_opts *o;
    int n;
} run_samples;

static int store_sample(void *u, long j, double t, const double *q, const double *v)
{
    run_samples *rs = u;
    (void)t;
    if (j < 0 || j >= rs->o->n_out) return 0; /* t_end itself when not asked for */
    if (rs->o->q_out) memcpy(rs->o->q_out + (size_t)j * rs->n, q, (size_t)rs->n * sizeof(double));
    if (rs->o->v_out) memcpy(rs->o->v_out + (size_t)j * rs->n, v, (size_t)rs->n * sizeof(double));
    return 0;
}

int cmp_ida_klu_run(const cmp_ida_problem *pb, const cmp_ida_run_opts *o,
                    cmp_ida_run_result *res)
{
    memset(res, 0, sizeof *res);
    cmp_target tg;
    memset(&tg, 0, sizeof tg);
    snprintf(tg.name, sizeof tg.name, "ida-klu-run");
    if (pb->sys) {
        tg.sys = *pb->sys;
    } else if (o->residual == CMP_RES_CALLBACKS) {
        snprintf(res->status, sizeof res->status, "SETUP_FAILED");
        snprintf(res->detail, sizeof res->detail, "the callbacks' residual needs a system");
        return -1;
    } else {
        /* Sizes from the scene (the provider must accept it: no callbacks). */
        const char *why = NULL;
        cmp_ggl *g = cmp_ggl_new(pb->scene, &why);
        if (!g) {
            snprintf(res->status, sizeof res->status, "SETUP_FAILED");
            snprintf(res->detail, sizeof res->detail, "no system, and the scene: %s",
                     why ? why : "?");
            return -1;
        }
        tg.sys.n = cmp_ggl_n(g);
        tg.sys.m = (cmp_ggl_size(g) - 2 * tg.sys.n) / 2;
        cmp_ggl_free(g);
    }
    tg.q0 = (double *)pb->q0;
    tg.v0 = (double *)pb->v0;
    tg.scene_point = -1;

    cmp_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.method = CMP_IDA_GGL;
    spec.integrator = -1;
    spec.rtol = o->rtol;
    spec.atol = o->atol > 0 ? o->atol : o->rtol;
    spec.T = o->t_end;
    spec.dt_out = o->t_end;
    spec.ida.linsol = CMP_LS_KLU;
    spec.ida.alg_atol = o->alg_atol;
    spec.ida.max_order = o->max_order;
    spec.ida.jac = o->jac;
    spec.ida.residual = o->residual;
    spec.ida.reg = o->reg;

    /* Output times: the samples asked for, then t_end. */
    const int ns = o->n_out > 0 && o->t_out ? o->n_out : 0;
    double *tout = malloc(((size_t)ns + 1) * sizeof(double));
    if (!tout) {
        snprintf(res->status, sizeof res->status, "SETUP_FAILED");
        return -1;
    }
    long nout = 0;
    for (int j = 0; j < ns; j++) tout[nout++] = o->t_out[j];
    if (nout == 0 || tout[nout - 1] < o->t_end) tout[nout++] = o->t_end;
    run_samples rs = {o, tg.sys.n};
    ida_io io;
    memset(&io, 0, sizeof io);
    io.scene = pb->scene;
    io.nout = nout;
    io.tout = tout;
    io.sample = store_sample;
    io.u = &rs;
    io.max_steps = o->max_steps > 0 ? o->max_steps : 100000;
    io.stop_time = 1;
    io.q_end = o->q_end;
    io.v_end = o->v_end;
    cmp_outcome out;
    run_core(&tg, &spec, &io, &out);
    free(tout);

    res->success = out.status == 0;
    snprintf(res->status, sizeof res->status, "%s", out.status_name);
    snprintf(res->detail, sizeof res->detail, "%s", out.detail);
    res->t_reached = out.t_reached;
    res->N = io.N;
    res->nnz = io.nnz;
    res->colors = io.colors;
    res->jac = io.jac;
    res->residual = io.residual;
    res->steps = out.counts.steps;
    res->jac_res_evals = io.jac_res;
    res->res_evals = out.counts.rhs_evals - io.jac_res;
    res->jac_evals = out.counts.jac_evals;
    res->lin_setups = out.counts.lin_setups;
    res->nl_iters = out.counts.lin_solves;
    res->err_fails = out.counts.err_fails;
    res->conv_fails = out.counts.conv_fails;
    res->cpu_setup_s = io.cpu_setup;
    res->cpu_solve_s = io.cpu_solve;
    return res->success ? 0 : -1;
}
