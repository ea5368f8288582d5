/* The corrected equation of motion: Eqs. 16, 17 and 20 (Sec. 2.4-2.5). */
#include "braun_internal.h"

static braun_real rank_tol(const braun_data *d, int rows)
{
    const braun_real t = d->model->opt.rank_tol;
    const int n = d->model->sys.n;
    return t > 0 ? t : braun_default_rank_tol(rows, n);
}

/* A result of braun__eval_ideal was NaN/Inf: find the callback output that
 * made it (in evaluation order), or blame the arithmetic (overflow). */
static int nonfinite_culprit(braun_data *d, braun_real t, unsigned want)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n, m = pv->m, rows = pv->rows;
    int st = braun__check_finite(d, n, pv->Q, "forces", 0, t);
    if (!st && rows > 0) {
        if (pv->sp)
            st = braun__check_finite(d, pv->sp->row_ptr[rows], pv->Avals,
                                     "constraint Jacobian (compressed)", 0, t);
        else
            st = braun__check_finite(d, rows * n, pv->A, "constraint Jacobian", n, t);
    }
    if (!st && rows > 0) st = braun__check_finite(d, rows, pv->bv, "constraint b_v", 0, t);
    if (!st && rows > 0 && (want & BRAUN_WANT_PHI)) {
        st = braun__check_finite(d, rows, pv->phi, "constraint Φ", 0, t);
        if (!st && m > 0) st = braun__check_finite(d, m, pv->b, "constraint b_q", 0, t);
    }
    if (!st) st = braun__fail(d, BRAUN_ERR_NONFINITE, "acceleration (overflow)", -1, -1, 0, (double)t);
    return st;
}

/* A factorization of C_v (slot 0) or C_q (slot 1) of `rows` rows found
 * this rank: kept for the corrections, counted in the statistics. */
static void record_rank(braun_data *d, int slot, int rank, int rows)
{
    braun__priv(d)->rank[slot] = rank;
    d->stats.constraint_factorizations++;
    if (rank < rows) d->stats.rank_deficient++;
}

#ifndef BRAUN_NO_LINSOLVER
/* Backend path of the constraint factorizations: C_q (when separate, and
 * only when the corrections need it) and C_v, with b_v -= C_v atil. */
static int factor_backend(braun_data *d, int wphi)
{
    braun_priv *pv = braun__priv(d);
    const int m = pv->m, rows = pv->rows;
    const braun_real *A = pv->dense_A ? pv->A : pv->Avals;
    if (pv->dense_A && pv->sp) braun__scatter_A(pv);
    if (pv->need_fq && wphi) {
        int rq = pv->ls->factor_c(pv->ls_state, 1, m, A, rank_tol(d, m), NULL, NULL);
        if (rq < 0) return braun__fail(d, rq, "linear solver (C_q)", -1, -1, 0, (double)d->t);
        record_rank(d, 1, rq, m);
    }
    int rank = pv->ls->factor_c(pv->ls_state, 0, rows, A, rank_tol(d, rows), pv->atil, pv->bv);
    if (rank < 0) return braun__fail(d, rank, "linear solver (C_v)", -1, -1, 0, (double)d->t);
    return rank;
}
#else
static int factor_backend(braun_data *d, int wphi)
{
    (void)wphi;
    return braun__fail(d, BRAUN_ERR_ARGUMENT, "linear solver", -1, -1, 0, (double)d->t);
}
#endif

int braun__eval_ideal(braun_data *d, braun_real t, const braun_real *q,
                      const braun_real *v, unsigned want, braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = BRAUN_N(pv->n), m = pv->m, p = pv->p, rows = BRAUN_ROWS(pv->rows);
    int st;

    d->stats.rhs_evals++;
    st = braun__mass_update(d, t, q);
    if (st) return st;

    /* a = M^-1 Q is kept in weighted form atil = R^-T Q (a = R^-1 atil). */
    st = braun__callback(d, s->forces(t, q, v, pv->Q, s->user), "forces", t);
    if (st) return st;
    braun__solve_rt(pv, pv->Q, pv->atil);

    if (rows > 0) {
        const int wphi = (want & BRAUN_WANT_PHI) != 0;
        if (m > 0) {
            st = braun__callback(d, s->holonomic(t, q, v, wphi ? pv->phi : NULL,
                                                 braun__A_out(pv, 0), wphi ? pv->b : NULL,
                                                 pv->bv, s->user),
                                 "holonomic", t);
            if (st) return st;
        }
        if (p > 0) {
            st = braun__callback(d, s->nonholonomic(t, q, v, wphi ? pv->phi + m : NULL,
                                                    braun__A_out(pv, m), pv->bv + m, s->user),
                                 "nonholonomic", t);
            if (st) return st;
        }
        if (wphi) {
            /* Velocity-level error [Φ̇_q; Φ_v] (Sec. 2.2). */
            for (int i = 0; i < m; i++) pv->ev[i] = braun__row_dot(pv, i, v) - pv->b[i];
            for (int i = m; i < rows; i++) pv->ev[i] = pv->phi[i];
        }
        int rank;
        if (BRAUN_LS(pv)) {
            rank = factor_backend(d, wphi);
            if (rank < 0) return rank;
        } else {
            if (pv->sp) braun__scatter_A(pv);
            /* C_v = A_v R^-1, row by row: row_i(C) = R^-T A_i^T. */
            braun_real *C = pv->fv.a;
            for (int i = 0; i < rows; i++) {
                braun_real *ci = C + (size_t)i * (size_t)n;
                braun_chol_solve_rt_to(&pv->chol, pv->A + (size_t)i * (size_t)n, ci);
                /* Residual of Eq. 10 without corrections: b_v - C_v atil. */
                pv->bv[i] -= braun_dot(n, ci, pv->atil);
            }
            if (pv->need_fq && wphi) {
                for (size_t i = 0; i < (size_t)m * (size_t)n; i++) pv->fq.a[i] = C[i];
                record_rank(d, 1, braun_qrcp_factor(&pv->fq, rank_tol(d, m)), m);
            }
            rank = braun_qrcp_factor(&pv->fv, rank_tol(d, rows));
        }
        record_rank(d, 0, rank, rows);
        /* Ideal constraint force, weighted: u = C_v^+ (b_v - C_v atil) (Eq. 11). */
        braun__pinv(pv, 0, pv->bv, pv->u);
        for (int i = 0; i < n; i++) pv->z[i] = pv->atil[i] + pv->u[i];
    } else {
        for (int i = 0; i < n; i++) pv->z[i] = pv->atil[i];
    }
    /* NaN and Inf propagate through every operation above, so one check of
     * the results covers all callback outputs; only on failure are they
     * scanned, to name the culprit. */
    /* b_v - C_v atil carries the Jacobian: an infinite entry of A makes every
     * QR pivot "small" (rank 0, u = 0, z finite) but not this residual. */
    if (!braun_all_finite(n, pv->z) || (rows > 0 && !braun_all_finite(rows, pv->bv)) ||
        ((want & BRAUN_WANT_PHI) && rows > 0 &&
         (!braun_all_finite(rows, pv->ev) || !braun_all_finite(m, pv->phi))))
        return nonfinite_culprit(d, t, want);
    if (vdot) braun__solve_r(pv, pv->z, vdot);
    return BRAUN_OK;
}

int braun__power(braun_data *d, braun_real t, const braun_real *q,
                 const braun_real *v, braun_real *Edot)
{
    const braun_system *s = &d->model->sys;
    braun_priv *pv = braun__priv(d);
    *Edot = 0;
    if (s->flags & BRAUN_ENERGY_INPUT) {
        int st = braun__callback(d, s->power(t, q, v, Edot, s->user), "power", t);
        if (!st) st = braun__check_finite(d, 1, Edot, "power", 0, t);
        if (st) return st;
    }
    if ((s->flags & BRAUN_CONSTRAINT_WORK) && pv->rows > 0) {
        /* Power of the ideal constraint force Q_c = R^T u at this state
         * (u from the braun__eval_ideal just done): Q_c·v = u·(R v). */
        braun__mul_r(pv, v, pv->tmp);
        *Edot += braun_dot(pv->n, pv->u, pv->tmp);
    }
    return BRAUN_OK;
}

/* Energy force of Eq. 20, scaled by h, added to dv: the minimum-norm
 * velocity change tangent to the kinematic constraints (N_v) that removes
 * the first-order prediction of Φ_e at the end of the step. */
static int energy_correction(braun_data *d, braun_real t, const braun_real *q,
                             const braun_real *v, braun_real W, braun_real h,
                             const braun_real *vdot, braun_real *dv)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = BRAUN_N(pv->n);
    braun_real E = 0, dEdt = 0, Edot = 0;
    int st = braun__callback(d, s->energy(t, q, v, &E, pv->dEdq, pv->dEdv, &dEdt, s->user),
                             "energy", t);
    if (st) return st;
    st = braun__check_finite(d, 1, &E, "energy E", 0, t);
    if (!st) st = braun__check_finite(d, n, pv->dEdq, "energy dE/dq", 0, t);
    if (!st) st = braun__check_finite(d, n, pv->dEdv, "energy dE/dv", 0, t);
    if (!st) st = braun__check_finite(d, 1, &dEdt, "energy dE/dt", 0, t);
    if (!st) st = braun__power(d, t, q, v, &Edot);
    if (st) return st;

    /* Eq. 18 and Eq. 19: Φ_e, A_e = dE/dv, b_e = -∂Φ_e/∂t - (∂Φ_e/∂q) v. */
    const braun_real phi_e = E - d->E0 - W;
    const braun_real b_e = -dEdt - braun_dot(n, pv->dEdq, v) + Edot;
    /* h·(b_ev - A_ev a - Δ_ev) of Eq. 20, written with the ideal acceleration
     * and the velocity correction dv applied in this step (0 when off):
     *   r = -(Φ_e + h (A_e q''_ideal - b_e) + A_e dv_c). */
    const braun_real r = -(phi_e + h * (braun_dot(n, pv->dEdv, vdot) - b_e) +
                           braun_dot(n, pv->dEdv, dv));
    /* x = N_v C_e^T, C_e = A_e R^-1. */
    braun__solve_rt(pv, pv->dEdv, pv->ce);
    if (pv->rows > 0) braun__null_project(pv, 0, pv->ce);
    const braun_real xx = braun_dot(n, pv->ce, pv->ce);
    /* [C_e N_v]^+ = x / ||x||^2 divides by ≈ 2·kinetic energy: at rest or at a
     * turning point it would explode. sigma is the relative change of the
     * (weighted) velocity; it is saturated at energy_max_rel. */
    braun_real smax = d->model->opt.energy_max_rel > 0 ? d->model->opt.energy_max_rel
                                                       : BRAUN_R(0.01);
    braun_real sigma;
    if (braun_fabs(r) <= smax * xx) {
        sigma = xx > 0 ? r / xx : 0;
    } else {
        sigma = r > 0 ? smax : -smax;
        d->stats.energy_guard_hits++;
    }
    if (sigma == 0) return BRAUN_OK;
    for (int i = 0; i < n; i++) pv->tmp[i] = sigma * pv->ce[i];
    braun__solve_r(pv, pv->tmp, pv->tmp);
    for (int i = 0; i < n; i++) dv[i] += pv->tmp[i];
    return BRAUN_OK;
}

/* The factorization the position correction uses dropped rows. */
static int position_rank_deficient(const braun_priv *pv)
{
    return pv->need_fq ? pv->rank[1] < pv->m : pv->rank[0] < pv->rows;
}

int braun__eval_corrections(braun_data *d, braun_real t, const braun_real *q,
                            const braun_real *v, braun_real W, braun_real h,
                            const braun_real *vdot, braun_real *dq,
                            braun_real *dv)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const int n = BRAUN_N(pv->n), m = pv->m, rows = BRAUN_ROWS(pv->rows);

    for (int i = 0; i < n; i++) dq[i] = dv[i] = 0;
    if (rows > 0 && (corr & BRAUN_CORRECT_POSITION) && m > 0) {
        /* Eq. 16 × h: dq = R^-1 C_q^+ (h (b_q - A_q v) - Φ_q). */
        const int slot = pv->need_fq ? 1 : 0;
        for (int i = 0; i < m; i++) pv->ep[i] = -(pv->phi[i] + h * pv->ev[i]);
        if (position_rank_deficient(pv)) {
            /* Dependent rows must agree: a position error outside range(C_q)
             * is one no motion can remove — the constraints have no
             * solution here (e.g. x = 0 and x = 1). Only rank-deficient
             * factorizations pay for this check. */
            braun_real resid;
            braun__lsq(pv, slot, pv->ep, dq, &resid);
            braun_real tol = d->model->opt.inconsistency_tol > 0 ? d->model->opt.inconsistency_tol
                                                                 : braun_sqrt(BRAUN_EPS);
            if (resid > tol)
                return braun__fail(d, BRAUN_ERR_INCONSISTENT, "holonomic constraints", -1, -1,
                                   (double)resid, (double)t);
        } else {
            braun__pinv(pv, slot, pv->ep, dq);
        }
        braun__solve_r(pv, dq, dq);
    }
    if (rows > 0 && (corr & BRAUN_CORRECT_VELOCITY)) {
        /* Δ_v term of Eq. 17 × h: dv = -R^-1 C_v^+ [Φ̇_q; Φ_v]. */
        for (int i = 0; i < rows; i++) pv->ev[i] = -pv->ev[i];
        braun__pinv(pv, 0, pv->ev, dv);
        for (int i = 0; i < rows; i++) pv->ev[i] = -pv->ev[i];
        braun__solve_r(pv, dv, dv);
    }
    if ((corr & BRAUN_CORRECT_ENERGY) && d->model->sys.energy && d->has_E0)
        return energy_correction(d, t, q, v, W, h, vdot, dv);
    return BRAUN_OK;
}

static int check_state(braun_data *d, braun_real t, const braun_real *q,
                       const braun_real *v)
{
    const int n = d->model->sys.n;
    if (!braun_is_finite(t))
        return braun__fail(d, BRAUN_ERR_NONFINITE, "state t", -1, -1, (double)t, (double)t);
    int st = braun__check_finite(d, n, q, "state q", 0, t);
    if (!st) st = braun__check_finite(d, n, v, "state v", 0, t);
    return st;
}

int braun_eval(braun_data *d, braun_real t, const braun_real *q,
               const braun_real *v, braun_real h, braun_real *qdot,
               braun_real *vdot)
{
    if (!d || !d->priv || !q || !v || !qdot || !vdot) return BRAUN_ERR_ARGUMENT;
    const unsigned corr = d->model->opt.corrections;
    const int n = d->model->sys.n;
    int st = check_state(d, t, q, v);
    if (st) return st;
    if (corr && !(h > 0 && braun_is_finite(h)))
        return braun__fail(d, BRAUN_ERR_STEP, "braun_eval h", -1, -1, (double)h, (double)t);
    st = braun__eval_ideal(d, t, q, v, corr ? BRAUN_WANT_PHI : 0u, vdot);
    if (st) return st;
    for (int i = 0; i < n; i++) qdot[i] = v[i];
    if (!corr) return BRAUN_OK;
    braun_priv *pv = braun__priv(d);
    st = braun__eval_corrections(d, t, q, v, d->work_in, h, vdot, pv->dq, pv->dv);
    if (st) return st;
    /* Continuous form: the increments are h times the correction terms. */
    for (int i = 0; i < n; i++) {
        qdot[i] += pv->dq[i] / h;
        vdot[i] += pv->dv[i] / h;
    }
    return BRAUN_OK;
}

int braun_energy(braun_data *d, braun_real t, const braun_real *q,
                 const braun_real *v, braun_real *E)
{
    if (!d || !d->priv || !q || !v || !E) return BRAUN_ERR_ARGUMENT;
    const braun_system *s = &d->model->sys;
    *E = 0;
    if (!s->energy) return BRAUN_OK;
    int st = braun__callback(d, s->energy(t, q, v, E, NULL, NULL, NULL, s->user), "energy", t);
    if (!st) st = braun__check_finite(d, 1, E, "energy E", 0, t);
    return st;
}

int braun_residuals(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v, braun_real *pos, braun_real *vel,
                    braun_real *energy)
{
    if (!d || !d->priv || !q || !v) return BRAUN_ERR_ARGUMENT;
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int m = pv->m, p = pv->p;
    int st = check_state(d, t, q, v);
    if (st) return st;
    if (m > 0) {
        st = braun__callback(d, s->holonomic(t, q, v, pv->phi, braun__A_out(pv, 0), pv->b,
                                             pv->bv, s->user),
                             "holonomic", t);
        if (st) return st;
        for (int i = 0; i < m; i++) pv->ev[i] = braun__row_dot(pv, i, v) - pv->b[i];
    }
    if (p > 0) {
        st = braun__callback(d, s->nonholonomic(t, q, v, pv->phi + m, braun__A_out(pv, m),
                                                pv->bv + m, s->user),
                             "nonholonomic", t);
        if (st) return st;
        for (int i = m; i < m + p; i++) pv->ev[i] = pv->phi[i];
    }
    if (pos) *pos = m > 0 ? braun_nrm2(m, pv->phi) : 0;
    if (vel) *vel = m + p > 0 ? braun_nrm2(m + p, pv->ev) : 0;
    if (energy) {
        braun_real E = 0;
        *energy = 0;
        if (s->energy && d->has_E0) {
            st = braun_energy(d, t, q, v, &E);
            if (st) return st;
            *energy = braun_fabs(E - d->E0 - d->work_in);
        }
    }
    return BRAUN_OK;
}
