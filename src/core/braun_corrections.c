/* The corrections of the equation of motion, as named stages scaled by the
 * step h: the ideal impulse of Eq. 16 (position), the Δ_v term of Eq. 17
 * (velocity) and the nonideal energy force of Eq. 20 (energy), and their
 * composition braun__corrections. They run at the point of a forward pass
 * that computed the residuals (braun_forward.c). */
#include "braun_internal.h"

/* ================================================================ */
/* Stage position: the ideal impulse of Eq. 16, scaled by h. With
 * Δ_q = Φ_q/h the position correction of one step is
 *   dq = h(q' − v) = R⁻¹C_q⁺(h(b_q − A_q v) − Φ_q) = −R⁻¹C_q⁺(Φ_q + hΦ̇_q),
 * the minimum-norm (in M) displacement that removes the first-order
 * prediction of Φ_q at the end of the step. Dependent rows must agree: a
 * position error outside range(C_q) is one no motion can remove — the
 * constraints have no solution there (e.g. x = 0 and x = 1) — and fails
 * with BRAUN_ERR_INCONSISTENT; only rank-deficient factorizations pay for
 * that check. */

static int stage_position(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int m = pv->m;
    const braun_real h = pv->at.h;
    /* C_q is its own factorization (slot 1) when there are nonholonomic
     * rows too; otherwise it is C_v. */
    const int slot = pv->need_fq ? 1 : 0;
    const int deficient = pv->need_fq ? pv->rank[1] < m : pv->rank[0] < pv->rows;
    for (int i = 0; i < m; i++) pv->ep[i] = -(pv->phi[i] + h * pv->ev[i]);
    if (deficient) {
        braun_real resid;
        braun__lsq(pv, slot, pv->ep, pv->dq, &resid);
        const braun_real tol = d->model->opt.inconsistency_tol > 0 ? d->model->opt.inconsistency_tol
                                                                   : braun_sqrt(BRAUN_EPS);
        if (resid > tol)
            return braun__fail(d, BRAUN_ERR_INCONSISTENT, "holonomic constraints", -1, -1,
                               (double)resid, (double)pv->at.t);
    } else {
        braun__pinv(pv, slot, pv->ep, pv->dq);
    }
    braun__solve_r(pv, pv->dq, pv->dq);
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage velocity: the velocity-level force of Eq. 17, its Δ_v term scaled
 * by h. With Δ_v = [Φ̇_q; Φ_v]/h,
 *   dv = −h R⁻¹C_v⁺Δ_v = −R⁻¹C_v⁺[Φ̇_q; Φ_v],
 * the minimum-norm (in M) velocity change that removes the velocity-level
 * error of both kinds of rows. The pseudoinverse is linear, so the sign is
 * applied to the result (exactly: IEEE negation is sign-symmetric). */

static int stage_velocity(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    braun__pinv(pv, 0, pv->ev, pv->dv);
    braun__solve_r(pv, pv->dv, pv->dv);
    for (int i = 0; i < n; i++) pv->dv[i] = -pv->dv[i];
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage energy: the nonideal energy force of Eq. 20, scaled by h and added
 * to dv. The energy law (Eq. 18) Φ_e = E − E0 − ∫Ė is a nonideal
 * nonholonomic constraint; at the acceleration level (Eq. 19) A_e = ∂E/∂v,
 * b_e = −∂E/∂t − (∂E/∂q)v + Ė. Q0 = Rᵀ[C_e N_v]⁺(b_ev − A_ev a − Δ_ev)
 * acts through R⁻¹N_vR⁻ᵀ (Eq. 17): the minimum-norm velocity change
 * tangent to the kinematic constraints (N_v) that removes the first-order
 * prediction of Φ_e at the end of the step, given the ideal acceleration
 * and the velocity correction dv of this step. With x = N_v C_eᵀ the
 * pseudoinverse is x/‖x‖², and ‖x‖² ≈ 2·kinetic energy: at rest or at a
 * turning point it would explode. The guard: the relative change σ of the
 * weighted velocity is saturated at energy_max_rel (docs/method.md). */

static int stage_energy(braun_data *d, const braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = BRAUN_N(pv->n);
    const braun_real t = pv->at.t, *q = pv->at.q, *v = pv->at.v, h = pv->at.h;
    braun_real E = 0, dEdt = 0;
    int st = braun__callback(d, s->energy(t, q, v, &E, pv->dEdq, pv->dEdv, &dEdt, s->user), "energy",
                         t);
    if (st) return st;
    st = braun__check_finite(d, 1, &E, "energy E", 0, t);
    if (!st) st = braun__check_finite(d, n, pv->dEdq, "energy dE/dq", 0, t);
    if (!st) st = braun__check_finite(d, n, pv->dEdv, "energy dE/dv", 0, t);
    if (!st) st = braun__check_finite(d, 1, &dEdt, "energy dE/dt", 0, t);
    if (st) return st;

    /* Eq. 18 and Eq. 19. */
    const braun_real phi_e = E - d->E0 - pv->at.W;
    const braun_real b_e = -dEdt - braun_dot(n, pv->dEdq, v) + pv->Edot;
    /* h·(b_ev − A_ev a − Δ_ev) of Eq. 20, written with the ideal
     * acceleration and the velocity correction dv of this step (0 when off):
     *   r = −(Φ_e + h (A_e q''_ideal − b_e) + A_e dv). */
    const braun_real r = -(phi_e + h * (braun_dot(n, pv->dEdv, vdot) - b_e) +
                           braun_dot(n, pv->dEdv, pv->dv));
    /* x = N_v C_eᵀ, C_e = A_e R⁻¹. */
    braun__solve_rt(pv, pv->dEdv, pv->ce);
    if (pv->rows > 0) braun__null_project(pv, 0, pv->ce);
    const braun_real xx = braun_dot(n, pv->ce, pv->ce);
    const braun_real smax = d->model->opt.energy_max_rel > 0 ? d->model->opt.energy_max_rel
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
    for (int i = 0; i < n; i++) pv->dv[i] += pv->tmp[i];
    return BRAUN_OK;
}

/* ================================================================ */
/* Composition. */
int braun__corrections(braun_data *d, const braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const int n = BRAUN_N(pv->n);
    const int energy = (corr & BRAUN_CORRECT_ENERGY) && d->model->sys.energy && d->has_E0;
    /* The forward pass at this point with the residuals (and Ė for the
     * energy force) is what the corrections work on. */
    int st = braun__need(d, BRAUN_DONE_IDEAL | BRAUN_DONE_RESIDUALS |
                                (energy ? BRAUN_DONE_POWER : 0u),
                         "corrections before a forward pass with residuals at the point");
    if (st) return st;
    /* A stage that runs writes all of its increment; one that is off leaves
     * it zero. */
    if (pv->rows > 0 && pv->m > 0 && (corr & BRAUN_CORRECT_POSITION)) st = stage_position(d);
    else for (int i = 0; i < n; i++) pv->dq[i] = 0;
    if (!st && pv->rows > 0 && (corr & BRAUN_CORRECT_VELOCITY)) st = stage_velocity(d);
    else for (int i = 0; i < n; i++) pv->dv[i] = 0;
    if (!st && energy) st = stage_energy(d, vdot);
    return st;
}
