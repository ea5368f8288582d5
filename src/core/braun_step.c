/* One explicit Runge–Kutta step of the corrected equation of motion.
 *
 * Discretisation (docs/method.md): with BRAUN_PER_STEP the integrator
 * advances the ideal flow and the correction terms of Eqs. 16, 17, 20 are
 * evaluated once, at the step's start, and added with weight h: h·Φ/h then
 * cancels exactly, no 1/h term meets the stages, and the method keeps its
 * order. For Euler this is the paper's equation itself. */
#include "braun_tableau.h"

/* A NaN/Inf from a callback, or a mass matrix that is not positive
 * definite, at a state the integrator produced (a later stage, or the start
 * of any step after the first): the solution left the region where the
 * model is defined — it diverged, and the adaptive driver retries smaller
 * (a05's flyball governor at a first trial step of 0.1 s reached a stage
 * whose M lost a pivot, and the run stopped there). d->error keeps the
 * callback and entry, or the mass pivot. */
static int diverged_if_integrated(braun_data *d, int stage, int st)
{
    if ((st == BRAUN_ERR_NONFINITE || st == BRAUN_ERR_MASS_NOT_SPD) &&
        (stage > 0 || braun__priv(d)->state_integrated))
        d->error.status = st = BRAUN_ERR_DIVERGED;
    return st;
}

/* dst = src + Σ_t c_t k_t over the nonzero coefficients of coef[0..count)
 * times h, in passes of up to four terms: the same sums in the same order
 * as one pass per term, without re-reading dst. Returns Σ dst·0 of the last
 * pass (braun_all_finite's test: 0 unless dst holds a NaN or an Inf). The
 * stage states and the step's end both take it. A pass's terms are held in
 * scalars, not arrays: GCC at -O3 -flto could not see that a pass reads
 * only the entries written and warned (-Wmaybe-uninitialized). */
BRAUN_FORCE_INLINE braun_real combine(int N, const braun_real *src, braun_real *dst, const braun_real *coef,
                          int count, braun_real h, braun_real *const *k)
{
    braun_real chk = 0;
    int s = 0;
    do {
        const braun_real *k0 = dst, *k1 = dst, *k2 = dst, *k3 = dst;
        braun_real b0 = 0, b1 = 0, b2 = 0, b3 = 0;
        int terms = 0;
        for (; s < count && terms < 4; s++) {
            const braun_real b = coef[s] * h;
            if (b == 0) continue;
            switch (terms++) {
            case 0: k0 = k[s]; b0 = b; break;
            case 1: k1 = k[s]; b1 = b; break;
            case 2: k2 = k[s]; b2 = b; break;
            default: k3 = k[s]; b3 = b; break;
            }
        }
        /* Zero coefficients after a pass's fourth term start no pass. */
        while (s < count && coef[s] * h == 0) s++;
        chk = 0;
        switch (terms) {
        case 4:
            for (int i = 0; i < N; i++) {
                dst[i] = src[i] + b0 * k0[i] + b1 * k1[i] + b2 * k2[i] + b3 * k3[i];
                chk += dst[i] * 0;
            }
            break;
        case 3:
            for (int i = 0; i < N; i++) {
                dst[i] = src[i] + b0 * k0[i] + b1 * k1[i] + b2 * k2[i];
                chk += dst[i] * 0;
            }
            break;
        case 2:
            for (int i = 0; i < N; i++) {
                dst[i] = src[i] + b0 * k0[i] + b1 * k1[i];
                chk += dst[i] * 0;
            }
            break;
        case 1:
            for (int i = 0; i < N; i++) {
                dst[i] = src[i] + b0 * k0[i];
                chk += dst[i] * 0;
            }
            break;
        default: /* no nonzero coefficient: dst = src */
            for (int i = 0; i < N; i++) {
                dst[i] = src[i];
                chk += dst[i] * 0;
            }
            break;
        }
        src = dst;
    } while (s < count);
    return chk;
}

static int rk_stages(braun_data *d, const braun_tableau *tb, braun_real h, braun__corr_at where,
                     braun_real *y1, braun_real *yerr, int first_known)
{
    const int per_stage = where == BRAUN__CORR_AT_STAGES, at_end = where == BRAUN__CORR_AT_END;
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n), N = 2 * n + 1;
    const unsigned corr = d->model->opt.corrections;
    const braun_real *y0 = pv->y0;
    int st;

    /* Rank decisions (braun_internal.h, rule_keep/rule_cap): the first
     * stage keeps the last step's rank and raises it only on clear
     * evidence; the later stages, off the manifold by the method's own
     * error, keep the first stage's rank. */
    pv->rule_keep[0] = pv->step_rank[0];
    pv->rule_keep[1] = pv->step_rank[1];
    pv->rule_cap[0] = pv->rows;
    pv->rule_cap[1] = pv->m;
    pv->rule_stage = 0;
    /* The soft-direction filter acts on the stages of a fixed step. An
     * adaptive step shrinks where the soft mode is stiff instead, and a
     * filtered stage would disturb its error estimate (parallelogram,
     * DOPRI5 rtol 1e-10: STEP_TOO_SMALL at 2.7 s with it, 254.7 s without). */
    pv->soft_on = !yerr && pv->rows > 0 && d->model->opt.soft_tol >= 0 && braun__has_soft(pv);
    /* Per step, the energy force is sized at the step's ideal end
     * (braun__energy_at_end): its direction comes from this first stage.
     * Euler's ideal end is the first-order prediction itself: its step
     * stays the paper's equation, evaluated at the start. */
    pv->energy_end = where == BRAUN__CORR_AT_START && tb->stages > 1;
    pv->de_ok = 0;
    /* Stages of weight 0 at the end (DOPRI5's 7th, first-same-as-last)
     * serve the error estimate only: without one they are not evaluated. */
    int stages = tb->stages;
    if (!yerr)
        while (stages > 1 && tb->b[stages - 1] == 0) stages--;
    int s0 = 0, retried = 0;
    if (first_known) {
        /* k[0], phi0, ev0 and step_rank are this start's already. */
        pv->rule_keep[0] = pv->step_rank[0];
        pv->rule_keep[1] = pv->step_rank[1];
        pv->rule_stage = 1;
        s0 = 1;
    }
    for (int s = s0; s < stages; s++) {
        const braun_real *ys = y0;
        if (s > 0) {
            braun_real *w = pv->ys;
            const braun_real nonfinite = combine(N, y0, w, tb->a[s], s, h, pv->k);
            ys = w;
            /* A stage state that overflowed means the step diverged: say so,
             * rather than let a callback report the NaN it was handed. */
            if (!(nonfinite == 0))
                return braun__fail(d, BRAUN_ERR_DIVERGED, "step stage", s, -1, (double)h, (double)d->t);
        }
        const braun_real ts = d->t + (braun_real)tb->c[s] * h;
        braun_real *k = pv->k[s];
        const int wants_corr = corr && (per_stage || (s == 0 && !at_end));
        /* An adaptive step measures its normal error from the residuals at
         * its start and at its last stage (the end of the ideal flow), where
         * the corrections at the end are computed. */
        const int wants_res = wants_corr || ((yerr || at_end) && (s == 0 || s == tb->stages - 1));
        /* Stage s of the method: the ideal flow at (ts, ys), its energy input,
         * and — at the step's start, or at every stage per stage — the
         * corrections, at the same point. */
        braun__at(pv, ts, ys, ys + n, ys[2 * n], h);
        pv->stage = s;
        st = diverged_if_integrated(
            d, s, braun__forward(d, BRAUN_WITH_POWER | (wants_res ? BRAUN_WITH_RESIDUALS : 0u), k + n));
        if (st) return st;
        if (s == 0) {
            pv->step_rank[0] = pv->rule_keep[0] = pv->rank[0];
            pv->step_rank[1] = pv->rule_keep[1] = pv->rank[1];
            pv->rule_stage = 1;
        }
        if (at_end && s == 0 && corr) {
            /* The state the last step left passes the guard here; the
             * corrections come at the end. */
            st = diverged_if_integrated(d, s, braun__guard_start(d, k + n));
            if (st) return st;
        }
        if ((yerr || at_end) && s == 0) braun__keep_start_residuals(pv);
        for (int i = 0; i < n; i++) k[i] = ys[n + i];
        k[2 * n] = pv->Edot;
        if (wants_corr) {
            pv->start_retry = s == 0 && !pv->state_integrated && !retried;
            st = braun__corrections(d, k + n, s == 0);
            pv->start_retry = 0;
            if (st == BRAUN__START_AMBIGUOUS) {
                /* A start off a redundant set's manifold, its rank taken
                 * from the start's residual (start_rank_check): its
                 * positions projected, the step taken again from there,
                 * its rank by the plain tolerance. */
                int moved = 0;
                braun_real r0 = 0;
                const int energy_end = pv->energy_end, soft_on = pv->soft_on;
                pv->vel_judged = 0;
                st = braun__project_positions(d, pv->y0, &moved, &r0, 1);
                if (st) return st;
                /* The projection's evaluations are points, not a step's
                 * stages: the step's own settings back (the energy force
                 * sized at its end: without, Heun's first step kept its
                 * energy error, 1e-7 J). */
                pv->energy_end = energy_end;
                pv->soft_on = soft_on;
                pv->de_ok = 0;
                retried = 1;
                pv->step_rank[0] = pv->rule_keep[0] = pv->rows;
                pv->step_rank[1] = pv->rule_keep[1] = pv->m;
                pv->rule_stage = 0;
                s = -1;
                continue;
            }
            st = diverged_if_integrated(d, s, st);
            if (st) return st;
            if (per_stage) /* the literal Eqs. 16-17 with Δ = Φ/h */
                for (int i = 0; i < n; i++) {
                    k[i] += pv->dq[i] / h;
                    k[n + i] += pv->dv[i] / h;
                }
        }
    }
    braun__rank_rule_plain(pv);
    pv->soft_on = 0;
    /* y1 = y0 + Σ_s (b_s h) k_s; its finiteness check rides on the pass
     * that last writes y1. */
    const int add_corr = corr && where == BRAUN__CORR_AT_START;
    /* Compensated (Kahan): the increments of a small step fall below the
     * state's ulp — in float a slider-crank released from rest at h = 1e-5
     * moved h·v ≈ 1e-9 per step against an ulp of 6e-8 and never fell, its
     * energy force taking back the kinetic energy the stalled positions
     * could not turn into a fall (status OK, found by an outside client).
     * The rounding of each step's sum is carried to the next (ylo1, which
     * braun__commit keeps; not ys: the last stage's point, pv->at, may be
     * it and the corrections at the end read it). */
    braun_real y1_0;
    if (BRAUN_COMPENSATED_STATE) {
        /* q and ∫Ė only: v's increments h·a are not small against v's
         * ulp where v is small, and v's carried rounding, invisible to the
         * velocity correction, raised ‖[Φ̇_q; Φ_v]‖ to an ulp of v (float
         * slider-crank, h = 1e-6: 1.8e-9). */
        y1_0 = combine(N, pv->ylo, y1, tb->b, stages, h, pv->k);
        for (int i = 0; i < N; i++) {
            const braun_real a = y1[i], y = y0[i] + a;
            pv->ylo1[i] = i >= n && i < 2 * n ? 0 : a - (y - y0[i]);
            y1[i] = y;
        }
    } else {
        y1_0 = combine(N, y0, y1, tb->b, stages, h, pv->k);
    }
    if (yerr) {
        for (int i = 0; i < N; i++) yerr[i] = 0;
        for (int s = 0; s < tb->stages; s++) {
            const braun_real e = (braun_real)tb->e[s] * h;
            if (e == 0) continue;
            for (int i = 0; i < N; i++) yerr[i] += e * pv->k[s][i];
        }
    }
    if (corr && pv->energy_end) {
        st = diverged_if_integrated(d, 1, braun__energy_at_end(d, d->t + h, y1));
        pv->energy_end = 0;
        if (st) return st;
    }
    if (add_corr) {
        y1_0 = 0;
        for (int i = 0; i < n; i++) {
            y1[i] += pv->dq[i];
            y1[n + i] += pv->dv[i];
            y1_0 += y1[i] * 0 + y1[n + i] * 0;
        }
    }
    if (!(y1_0 == 0) || (yerr && !braun_all_finite(N, yerr))) {
        int bad = 0;
        while (bad < N && braun_is_finite(y1[bad])) bad++;
        return braun__fail(d, BRAUN_ERR_DIVERGED, "step", bad, -1, (double)h, (double)d->t);
    }
    return BRAUN_OK;
}

void braun__guard_rollback(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    if (!pv->has_prev) return;
    for (int i = 0; i < n; i++) {
        d->q[i] = pv->yprev[i];
        d->v[i] = pv->yprev[n + i];
    }
    d->work_in = pv->yprev[2 * n];
    d->t = pv->tprev;
    pv->t_lo = pv->tprev_lo;
    d->guard.pos = pv->guard_prev[0];
    d->guard.vel = pv->guard_prev[1];
    d->guard.energy = pv->guard_prev[2];
    d->guard.pos0 = pv->guard_prev[3];
    d->guard.vel0 = pv->guard_prev[4];
    d->guard.energy0 = pv->guard_prev[5];
    /* (A start off its positions measures its allowance again while pos0
     * is back in force: braun_corrections.c, allow_induced_velocity.) */
    if (pv->vel_induced0 > 0 && d->guard.pos0 > 0) pv->start_off = 1;
    d->stats.steps--;
    pv->has_prev = 0;
    braun__clear_compensation(pv);
}

void braun__load_state(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    for (int i = 0; i < n; i++) {
        pv->y0[i] = d->q[i];
        pv->y0[n + i] = d->v[i];
    }
    pv->y0[2 * n] = d->work_in;
}

void braun__commit(braun_data *d, const braun_real *y1, braun_real t_new, braun_real t_lo)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    /* The state being left stays as the guard's way back: y0 holds it. */
    braun_real *keep = pv->y0;
    pv->y0 = pv->yprev;
    pv->yprev = keep;
    pv->tprev = d->t;
    pv->tprev_lo = pv->t_lo;
    pv->t_lo = t_lo;
    pv->has_prev = 1;
    /* The step's rounding, carried to the next step (rk_stages). */
    if (BRAUN_COMPENSATED_STATE) {
        braun_real *lo = pv->ylo;
        pv->ylo = pv->ylo1;
        pv->ylo1 = lo;
    }
    /* ... and its guard scales: a refused state raised them (the slow
     * path measures them at the state it judges), and a retry from the
     * kept state was judged by the blown-up state's (a velocity residual
     * 12 times its bound passed). */
    pv->guard_prev[0] = d->guard.pos;
    pv->guard_prev[1] = d->guard.vel;
    pv->guard_prev[2] = d->guard.energy;
    pv->guard_prev[3] = d->guard.pos0;
    pv->guard_prev[4] = d->guard.vel0;
    pv->guard_prev[5] = d->guard.energy0;
    for (int i = 0; i < n; i++) {
        d->q[i] = y1[i];
        d->v[i] = y1[n + i];
    }
    d->work_in = y1[2 * n];
    d->t = t_new;
    BRAUN__COUNT(d->stats.steps);
    braun__priv(d)->state_integrated = 1;
}

/* The stages call the system's callbacks: a call from one of them back
 * into this data is refused while they run (braun_priv.busy = 2). */
int braun__rk_attempt(braun_data *d, const braun_tableau *tb, braun_real h,
                      braun__corr_at where, braun_real *y1, braun_real *yerr, int first_known)
{
    braun_priv *pv = braun__priv(d);
    const int outer = pv->busy;
    pv->busy = 2;
    const int st = rk_stages(d, tb, h, where, y1, yerr, first_known);
    /* braun_data_init from a system callback resets busy (release is
     * refused there): the stages ran on scratch no longer theirs. */
    if (!braun__data_intact(d, pv, 2))
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "re-entrant call: braun_data_init from a system callback while a step's "
                           "stages ran on this data",
                           -1, -1, 0, (double)d->t);
    pv->busy = outer;
    return st;
}

/* A system callback may have changed the model while a driver's stages
 * ran: a step made under another system or invalid options is not kept
 * (a NaN rank_tol set from a force callback returned BRAUN_OK; n changed
 * ran on to t_end). The drivers check at every step they take; a single
 * braun_step is checked at its next call, as every call is. */
int braun__check_unchanged(braun_data *d)
{
    const int st = braun__check_system(d);
    return st ? st : braun__check_options(d);
}

int braun_step(braun_data *d, braun_method method, braun_real h)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = braun__check_ready(d);
    if (st) return st;
    const braun_tableau *tb = braun__tableau(method);
    if (!tb) return braun__fail(d, BRAUN_ERR_ARGUMENT, "method", (int)method, -1, 0, (double)d->t);
    if (!(h > 0) || !braun_is_finite(h))
        return braun__fail(d, BRAUN_ERR_STEP, "step size", -1, -1, (double)h, (double)d->t);
    braun_priv *pv = braun__priv(d);
    /* The step integrates h itself; the clock shows the nearest time it can
     * (refused when that is more than 10 % off h: the float horizon). */
    braun_real t_lo;
    const braun_real t_new = braun__clock_advance(d, pv->t_lo, h, &t_lo);
    st = braun__time_step_ok(d, d->t, t_new, h, 0);
    if (!st) st = braun__mass_claim_due(d, d->t, d->q);
    if (st) return st;
    braun__load_state(d);
    st = braun__rk_attempt(d, tb, h,
                           d->model->opt.discretization == BRAUN_PER_STAGE ? BRAUN__CORR_AT_STAGES
                                                                          : BRAUN__CORR_AT_START,
                           pv->y1, NULL, 0);
    if (st == BRAUN_ERR_ACCURACY) braun__guard_rollback(d);
    if (st) return st;
    braun__commit(d, pv->y1, t_new, t_lo);
    return BRAUN_OK;
}
