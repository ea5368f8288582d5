/* SUNDIALS IDA on a reference model's stabilised index-2 form (Gear,
 * Gupta & Leimkuhler 1985), unknowns y = [q, v, W, λ, μ]:
 *   q' = v - Gᵀμ,  M v' = F + Gᵀλ,  W' = Qᵀv,  ψ(q, v) = 0,  φ(q) = 0,
 * μ = 0 on the exact solution. Dense direct solver with IDA's own
 * difference-quotient Jacobian; λ and μ out of the error test. The grid
 * (out->count, out->dt) is the caller's; IDA's interpolant gives each
 * sample. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "ifm.h"

typedef struct ida_user {
    const ifm_model *md;
    int failed;
} ida_user;

static int residual(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *u)
{
    const ida_user *c = u;
    const ifm_model *md = c->md;
    const int n = md->n, m = md->m;
    const double *y = N_VGetArrayPointer(yy), *yd = N_VGetArrayPointer(yp);
    double *r = N_VGetArrayPointer(rr);
    const double *q = y, *v = y + n, *lam = y + 2 * n + 1, *mu = lam + m;
    double M[IFM_MAX_N * IFM_MAX_N], F[IFM_MAX_N], G[IFM_MAX_M * IFM_MAX_N];
    ifm_mass(md, q, M);
    ifm_forces(md, t, q, v, F);
    if (m > 0) ifm_jacobian(md, q, G);
    for (int i = 0; i < n; i++) {
        double gm = 0, gl = 0, Ma = 0;
        for (int k = 0; k < m; k++) {
            gm += G[k * n + i] * mu[k];
            gl += G[k * n + i] * lam[k];
        }
        for (int j = 0; j < n; j++) Ma += M[i * n + j] * yd[n + j];
        r[i] = yd[i] - v[i] + gm;
        r[n + i] = Ma - F[i] - gl;
    }
    r[2 * n] = yd[2 * n] - ifm_power(md, t, q, v);
    if (m > 0) {
        ifm_psi(md, q, v, r + 2 * n + 1);
        ifm_phi(md, q, r + 2 * n + 1 + m);
    }
    for (int i = 0; i < 2 * n + 1 + 2 * m; i++)
        if (!isfinite(r[i])) return 1; /* recoverable: IDA cuts the step */
    return 0;
}

static double cpu_now(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

/* Record sample j from the state y. */
static void record(const ifm_model *md, ifm_series *out, long j, const double *y, double E0)
{
    const int n = md->n, m = md->m;
    const double *q = y, *v = y + n;
    if (out->q) memcpy(out->q + j * n, q, (size_t)n * sizeof *q);
    if (out->v) memcpy(out->v + j * n, v, (size_t)n * sizeof *v);
    md->report(md, q, v, out->y + j * out->width);
    if (m > 0) {
        double phi[IFM_MAX_M];
        ifm_phi(md, q, phi);
        for (int r = 0; r < m; r++) out->max_phi = fmax(out->max_phi, fabs(phi[r]));
    }
    const double T = ifm_kinetic(md, q, v);
    out->max_kinetic = fmax(out->max_kinetic, T);
    out->max_energy = fmax(out->max_energy, fabs(ifm_energy(md, q, v) - E0 - y[2 * n]));
}

int ifm_ida_run(const ifm_model *md, const double *q0, const double *v0, double rtol,
                double atol, ifm_series *out, char *why, size_t whysize)
{
    const int n = md->n, m = md->m, N = 2 * n + 1 + 2 * m;
    const double c0 = cpu_now();
    SUNContext ctx = NULL;
    N_Vector yy = NULL, yp = NULL, id = NULL, av = NULL;
    SUNMatrix J = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    int st = -1;
    ida_user user = {md, 0};
    snprintf(out->how, sizeof out->how, "IDA GGL, dense, rtol %.0e atol %.0e", rtol, atol);
    out->max_phi = out->max_energy = out->max_kinetic = 0;

    if (SUNContext_Create(NULL, &ctx)) goto done;
    yy = N_VNew_Serial(N, ctx);
    yp = N_VNew_Serial(N, ctx);
    id = N_VNew_Serial(N, ctx);
    av = N_VNew_Serial(N, ctx);
    if (!yy || !yp || !id || !av) goto done;
    double *y = N_VGetArrayPointer(yy), *yd = N_VGetArrayPointer(yp);
    double *idv = N_VGetArrayPointer(id), *atv = N_VGetArrayPointer(av);
    /* Consistent values: (q0, v0) on φ = 0, ψ = 0 (the caller's job, checked
     * here), v' and λ from the KKT system, μ = 0. */
    memset(y, 0, (size_t)N * sizeof *y);
    memset(yd, 0, (size_t)N * sizeof *yd);
    memcpy(y, q0, (size_t)n * sizeof *y);
    memcpy(y + n, v0, (size_t)n * sizeof *y);
    if (m > 0) {
        double phi[IFM_MAX_M], psi[IFM_MAX_M], e = 0;
        ifm_phi(md, q0, phi);
        ifm_psi(md, q0, v0, psi);
        for (int r = 0; r < m; r++) e = fmax(e, fmax(fabs(phi[r]), fabs(psi[r])));
        if (e > 1e-12) {
            snprintf(why, whysize, "%s: initial state off its constraints by %.3g", md->name, e);
            goto done;
        }
    }
    if (ifm_accel(md, 0.0, q0, v0, yd + n, y + 2 * n + 1)) {
        snprintf(why, whysize, "%s: singular KKT system at t = 0", md->name);
        goto done;
    }
    memcpy(yd, v0, (size_t)n * sizeof *yd);
    yd[2 * n] = ifm_power(md, 0.0, q0, v0);
    for (int i = 0; i < N; i++) {
        idv[i] = i <= 2 * n ? 1.0 : 0.0;
        atv[i] = i <= 2 * n ? atol : 1e6;
    }
    const double E0 = ifm_energy(md, q0, v0);

    mem = IDACreate(ctx);
    if (!mem) goto done;
    int flag = IDAInit(mem, residual, 0.0, yy, yp);
    if (!flag) flag = IDASVtolerances(mem, rtol, av);
    if (!flag) flag = IDASetUserData(mem, &user);
    if (!flag) flag = IDASetId(mem, id);
    if (!flag) flag = IDASetSuppressAlg(mem, SUNTRUE);
    if (!flag) flag = IDASetMaxNumSteps(mem, 10000000L);
    if (!flag) flag = IDASetStopTime(mem, (double)(out->count - 1) * out->dt);
    if (!flag) {
        J = SUNDenseMatrix(N, N, ctx);
        LS = J ? SUNLinSol_Dense(yy, J, ctx) : NULL;
        flag = LS ? IDASetLinearSolver(mem, LS, J) : -1;
    }
    if (flag) {
        snprintf(why, whysize, "%s: IDA setup failed (%d)", md->name, flag);
        goto done;
    }
    record(md, out, 0, y, E0);
    for (long j = 1; j < out->count; j++) {
        double tret = 0;
        flag = IDASolve(mem, out->t[j], &tret, yy, yp, IDA_NORMAL);
        if (flag < 0) {
            char *name = IDAGetReturnFlagName(flag);
            snprintf(why, whysize, "%s: IDASolve failed at t = %.9g (%s)", md->name, tret,
                     name ? name : "?");
            free(name);
            goto done;
        }
        record(md, out, j, y, E0);
    }
    st = 0;
done:
    out->cpu_s = cpu_now() - c0;
    if (mem) IDAFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (J) SUNMatDestroy(J);
    if (yy) N_VDestroy(yy);
    if (yp) N_VDestroy(yp);
    if (id) N_VDestroy(id);
    if (av) N_VDestroy(av);
    if (ctx) SUNContext_Free(&ctx);
    if (st && why[0] == '\0') snprintf(why, whysize, "%s: IDA failed", md->name);
    return st;
}
