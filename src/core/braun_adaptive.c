/* Adaptive driver: Dormand–Prince 5(4) with a standard step-size controller.
 * The corrections are applied once per accepted step, whatever the model's
 * discretization option, at its end: computed with the factorization of the
 * last stage (the end of the ideal flow) and added there, where they
 * remove the residuals themselves — unless that end is next to a singular
 * configuration, where the start's are kept (braun__corrections_at_end).
 * Computed at a start next to a singular configuration and added at the
 * end, a correction — a velocity e/σ along a weak direction that turns fast
 * there — was no correction at the end but a new error (four-bar, rtol
 * 1e-10: ‖[Φ̇_q; Φ_v]‖ up to 5e-8 for several steps; docs/method.md,
 * "Where the corrections are evaluated").
 *
 * The error of a step has two parts, measured separately:
 *  - along the constraint manifold: the embedded estimate of the ideal
 *    flow, projected on the tangent space. Its normal part is not used:
 *    near a singular configuration the ideal flow's normal sensitivity grows
 *    like the inverse of the small pivot, and measuring it that way shrank
 *    h without end (measured: the four-bar at rtol 1e-10 stopped with
 *    BRAUN_ERR_STEP_TOO_SMALL at t = 102.2 s).
 *  - across it: the drift of the step in the constrained directions, the
 *    deviation of the residuals at its end from their first-order
 *    prediction at its start,
 *        e_q = Φ(y1) − Φ(y0) − h Φ̇(y0),   e_v = Φ̇(y1) − Φ̇(y0)
 *    (y1 the end of the ideal flow, the last DOPRI5 stage), as the
 *    displacements R⁻¹C⁺e_q and R⁻¹C⁺e_v in q and v units: what the
 *    correction at the end removes, to first order. This is the error of
 *    the constrained directions themselves: without it a mechanism with no
 *    free motion (every coordinate driven: an empty tangent space) had no
 *    error at all and its step grew without bound.
 * Both are scaled by atol + rtol·|y| and combined in one RMS norm. */
#include <math.h>

#include "braun_tableau.h"

static double scaled(double e, double y0, double y1, braun_real rtol, braun_real atol)
{
    const double a = fabs(y0), b = fabs(y1);
    const double sc = (double)atol + (double)rtol * (a > b ? a : b);
    /* atol = 0 where y is 0: no error is allowed, and none is none. */
    if (sc == 0) return e == 0 ? 0 : HUGE_VAL;
    return e / sc;
}

/* The tangential error of the embedded estimate: in weighted coordinates
 * the tangent space is null(C), projected by N (pv's factorization is the
 * last stage's, at the end of the step). Position errors are projected only
 * when all rows are holonomic (then C_q = C_v). */
static void project_error_tangent(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n;
    if (pv->rows == 0) return;
    for (int part = 0; part < 2; part++) {
        braun_real *e = pv->yerr + (part ? n : 0);
        if (part == 0 && pv->p > 0) continue;
        braun__mul_r(pv, e, pv->tmp);
        braun__null_project(pv, 0, pv->tmp);
        for (int i = 0; i < n; i++) e[i] = pv->tmp[i];
        braun__solve_r(pv, e, e);
    }
}

/* A change of a residual below the residuals' own round-off is no error a
 * step size controls: e shrunk towards 0 by that floor (continuously, for
 * the controller). Next to a singular configuration R⁻¹C⁺ maps even
 * round-off to a displacement ~ε/σ: unshrunk, the four-bar at rtol 1e-10,
 * atol 1e-12 stopped with BRAUN_ERR_STEP_TOO_SMALL at t = 28.4 s, every
 * trial step rejected for |Φ_q| changes of 3e-16 at σ = 6e-7‖C‖. */
static braun_real above_roundoff(braun_real e, braun_real floor)
{
    if (e > floor) return e - floor;
    if (e < -floor) return e + floor;
    return 0;
}

/* The round-off floor of row i's residual at the end of the ideal flow:
 * 8ε (|A_i||x| + |c|) for Φ_q (x = q, c = 0) or [Φ̇_q; Φ_v] (x = v, c =
 * b_q): the start's and the end's round-off, a few operations each. */
static braun_real roundoff_floor(const braun_priv *pv, int i, const braun_real *absx, braun_real c)
{
    return 8 * BRAUN_EPS * (braun__row_abs_dot(pv, i, absx) + braun_fabs(c));
}

/* Sum of squares of the scaled normal error (see the top of this file),
 * from the residuals the attempt kept: pv->phi0/ev0 (start), pv->phi/ev
 * (end of the ideal flow, with A there). */
static double normal_error2(braun_data *d, braun_real h, braun_real rtol, braun_real atol)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n, m = pv->m, rows = pv->rows;
    const braun_real *y0 = pv->y0, *y1 = pv->y1;
    braun_real *absx = pv->ce; /* scratch until the corrections */
    double sum = 0;
    if (rows == 0) return 0;
    if (m > 0) {
        for (int i = 0; i < n; i++) absx[i] = braun_fabs(y1[i]);
        for (int i = 0; i < m; i++)
            pv->enorm[i] = above_roundoff(pv->phi[i] - pv->phi0[i] - h * pv->ev0[i],
                                          roundoff_floor(pv, i, absx, 0));
        braun__pinv(pv, pv->need_fq ? 1 : 0, pv->enorm, pv->tmp);
        braun__solve_r(pv, pv->tmp, pv->tmp);
        for (int i = 0; i < n; i++) {
            const double e = scaled((double)pv->tmp[i], (double)y0[i], (double)y1[i], rtol, atol);
            sum += e * e;
        }
    }
    for (int i = 0; i < n; i++) absx[i] = braun_fabs(y1[n + i]);
    for (int i = 0; i < rows; i++)
        pv->enorm[i] = above_roundoff(pv->ev[i] - pv->ev0[i],
                                      roundoff_floor(pv, i, absx, i < m ? pv->b[i] : 0));
    braun__pinv(pv, 0, pv->enorm, pv->tmp);
    braun__solve_r(pv, pv->tmp, pv->tmp);
    for (int i = 0; i < n; i++) {
        const double e = scaled((double)pv->tmp[i], (double)y0[n + i], (double)y1[n + i], rtol, atol);
        sum += e * e;
    }
    return sum;
}

static double error_norm(braun_data *d, braun_real h, braun_real rtol, braun_real atol)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n;
    const double normal = normal_error2(d, h, rtol, atol);
    project_error_tangent(d);
    double sum = normal;
    for (int i = 0; i < 2 * n; i++) {
        const double e = scaled((double)pv->yerr[i], (double)pv->y0[i], (double)pv->y1[i], rtol, atol);
        sum += e * e;
    }
    return sqrt(sum / (2 * n));
}

static int integrate_adaptive(braun_data *d, const braun_adaptive *ctl, braun_real t_end, long every,
                              braun_output_fn out, void *out_user)
{
    int st;
    if (!ctl) return braun__fail(d, BRAUN_ERR_ARGUMENT, "adaptive control (NULL)", -1, -1, 0, (double)d->t);
    /* rtol >= 1 asks for no digit at all; NaN and Inf for nothing. */
    if (!(ctl->rtol >= 0) || !(ctl->rtol < 1) || !(ctl->atol >= 0) || !braun_is_finite(ctl->atol) ||
        (ctl->rtol == 0 && ctl->atol == 0))
    {
        /* Name the one at fault, and its value. */
        const int bad_rtol = !(ctl->rtol >= 0) || !(ctl->rtol < 1);
        const int both_zero = !bad_rtol && ctl->rtol == 0 && ctl->atol == 0;
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           bad_rtol    ? "tolerance rtol (must be in [0, 1))"
                           : both_zero ? "tolerances rtol and atol (both 0)"
                                       : "tolerance atol (must be finite and >= 0)",
                           -1, -1, bad_rtol || both_zero ? (double)ctl->rtol : (double)ctl->atol,
                           (double)d->t);
    }
    if (!braun_is_finite(t_end) || !(t_end > d->t))
        return braun__fail(d, BRAUN_ERR_TIME, "t_end", -1, -1, (double)t_end, (double)d->t);
    /* The step limits: <= 0 selects a default; NaN and Inf mean nothing. */
    if (!braun_is_finite(ctl->h0) || !braun_is_finite(ctl->h_min) || !braun_is_finite(ctl->h_max))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "adaptive step limits h0, h_min, h_max (not finite)", -1, -1,
                           0, (double)d->t);
    const braun_tableau *tb = braun__tableau(BRAUN_DOPRI5);
    braun_priv *pv = braun__priv(d);
    const double span = (double)(t_end - d->t);
    double h = ctl->h0 > 0 ? (double)ctl->h0 : 1e-3 * span;
    /* A span of a few subnormals: 1e-3 of it is 0. */
    if (!(h > 0)) h = span;
    const double hmax = ctl->h_max > 0 ? (double)ctl->h_max : span;
    double hmin = ctl->h_min > 0 ? (double)ctl->h_min : 1e-12 * span;
    /* The time's resolution where it exceeds the span, else 0. */
    double span_unresolved = 0;
    if (!(ctl->h_min > 0)) {
        /* The default stays above the time resolution, where t + h would
         * no longer advance t by h (braun__time_step_ok): a float run whose
         * callback failed for good, or whose force jumped, shrank its step
         * to there and was reported as the float horizon, not as the
         * callback's failure or a step too small. */
        const double tmax = fabs((double)d->t) > fabs((double)t_end) ? fabs((double)d->t) : fabs((double)t_end);
        const double resolution = 16 * (double)BRAUN_EPS * tmax;
        if (hmin < resolution) hmin = resolution;
        /* A span below the resolution: one step, to t_end; rejected, it is
         * the float horizon (below). A maximum the program set below the
         * default minimum is refused: no step could lie in [h_min, h_max]. */
        if (hmin > hmax && !(ctl->h_max > 0)) {
            span_unresolved = resolution;
            hmin = hmax;
        }
        if (hmin > hmax)
            return braun__fail(d, BRAUN_ERR_ARGUMENT,
                               "adaptive h_max (below the default h_min, 1e-12 of the span but at least "
                               "16 eps max(|t|, |t_end|): set h_min too)",
                               -1, -1, hmax, (double)d->t);
    }
    /* No step can lie between a minimum above the maximum. */
    if (hmin > hmax)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "adaptive step limits (h_min > h_max)", -1, -1, hmin,
                           (double)d->t);
    /* Every step but the last, which lands on t_end, lies in [h_min, h_max]. */
    if (h < hmin) h = hmin;
    const long max_steps = ctl->max_steps > 0 ? ctl->max_steps : 100000000L;
    /* Corrections at each accepted end where the backend can tell the ends
     * next to a singular configuration (soft directions: the built-in dense
     * kernels), which keep the start's; without that test (LAPACK,
     * SuiteSparse) at the start, as fixed steps: corrected at the end there
     * too, the redundant parallelogram at rtol 1e-8 stopped with
     * BRAUN_ERR_STEP_TOO_SMALL at t = 8.7 s (it completes 1000 s). */
    const braun__corr_at where = braun__has_soft(pv) ? BRAUN__CORR_AT_END : BRAUN__CORR_AT_START;
    /* The step limit counts this call's attempts, accepted and rejected. */
    long accepted = 0, rejected = 0;
    /* The next attempt's first stage is known: after a rejection it is the
     * rejected attempt's (the same start); after an accepted step that no
     * correction changed, the last stage's (DOPRI5's 7th is evaluated at
     * the end, first same as last). An end that the corrections move is
     * another point: its first stage is evaluated anew. */
    int first_known = 0;
    /* The corrections the attempts follow (an output callback may change
     * them between steps). */
    unsigned corr = d->model->opt.corrections;
    const int last_stage = tb->stages - 1;

    /* A new run's start off its constraints is projected onto them first
     * (braun__project_start): its first state, reported at t0, is on them,
     * and the start is judged there — at the end of a first step, an exact
     * start was taken for an inconsistent one (the end's residual is the
     * step's own) and E0 re-taken seconds later from the drifted energy
     * (the pendulum at rtol 2.7e-3: E0 0 -> 0.74 J at t = 3.5 s, status
     * OK). */
    if (!pv->state_integrated) {
        int moved = 0;
        braun__load_state(d);
        st = braun__project_start(d, pv->y0, &moved);
        if (st) return st;
        if (moved)
            for (int i = 0; i < pv->n; i++) {
                d->q[i] = pv->y0[i];
                d->v[i] = pv->y0[pv->n + i];
            }
    }
    if (out && (st = braun__output(d, out, out_user)) != BRAUN_OK) return st;
    /* An accepted state is reported once the next attempt's start has
     * passed the accuracy guard (or the final check has): a run the guard
     * stops has reported only states that passed. */
    int pending = 0, fresh = 1;
    st = BRAUN_OK;
    while (d->t < t_end) {
        if (h > hmax) h = hmax;
        int last = 0;
        if ((double)d->t + h >= (double)t_end * (1 - 1e-15) || (double)d->t + h >= (double)t_end) {
            h = (double)(t_end - d->t);
            last = 1;
        }
        if (accepted + rejected >= max_steps) {
            st = braun__fail(d, BRAUN_ERR_TOO_MANY_STEPS, "adaptive", -1, -1, (double)max_steps, (double)d->t);
            break;
        }
        /* The step in working precision, and the time it lands on: a step
         * that cannot advance t (or not by about h) is a status, not a loop
         * of rejections. */
        const braun_real t_new = last ? t_end : (braun_real)((double)d->t + h);
        st = braun__time_step_ok(d, d->t, t_new, (braun_real)h, last);
        if (st) break;
        const braun_real hr = t_new - d->t;
        /* The mass claim at a new start (a repeated attempt starts where the
         * rejected one did: counted once, and its kept first stage is left
         * alone). */
        if (fresh) st = braun__mass_claim_due(d, d->t, d->q);
        if (st) break;
        fresh = 0;
        braun__load_state(d);
        /* Always per step: with a varying h the literal Δ = Φ/h changes
         * meaning from one trial step to the next and the error test, which
         * would see the 1/h terms, rejects without end. */
        st = braun__rk_attempt(d, tb, hr, where, pv->y1, pv->yerr, first_known);
        if (!st) st = braun__check_unchanged(d);
        /* k[0] is this start's first stage if it was kept or if a later
         * stage was reached (pv->stage is set before a stage's evaluation). */
        /* The first stage holds no correction unless they are computed
         * there (at the start: every placement but the end). */
        first_known = !(corr && where != BRAUN__CORR_AT_END) && (first_known || pv->stage > 0);
        double err = 0;
        if (!st) {
            err = error_norm(d, hr, ctl->rtol, ctl->atol);
            /* An accepted step is corrected at its end (DOPRI5's last
             * stage is the end: its factorization and residuals). */
            if (err <= 1 && where == BRAUN__CORR_AT_END)
                st = braun__corrections_at_end(d, pv->k[tb->stages - 1] + pv->n, pv->y1, hr);
        }
        if (st == BRAUN_ERR_CALLBACK_RECOVERABLE || st == BRAUN_ERR_DIVERGED) {
            err = 1e10; /* retry smaller, as SUNDIALS does for recoverable failures */
        } else if (st) {
            break;
        }
        if (err <= 1) {
            /* First same as last: the last stage was evaluated at d->t + hr
             * (c = 1), which is t_new unless hr lost a bit, under the rank
             * rule of a step's later stages (a rank can fall there, not
             * rise): taken when it had full rank, which a new first stage
             * would find too. Kept before the output callback below, whose
             * braun_residuals overwrites the residuals and A with the
             * reported state's. */
            first_known = braun__tableau_fsal(tb) && !corr && d->t + hr == t_new && pv->rank[0] == pv->rows &&
                          (!pv->need_fq || pv->rank[1] == pv->m);
            if (first_known) {
                braun_real *k0 = pv->k[0];
                pv->k[0] = pv->k[last_stage];
                pv->k[last_stage] = k0;
                braun__keep_start_residuals(pv); /* the end's: the next start's */
                pv->step_rank[0] = pv->rank[0];
                pv->step_rank[1] = pv->rank[1];
            }
        }
        /* The last accepted state, once this attempt's start has passed. */
        if (!st && pending) {
            pending = 0;
            const int so = braun__output(d, out, out_user);
            if (so) return so;
            if (d->model->opt.corrections != corr) {
                /* The callback changed the corrections (valid between
                 * steps): the next first stage is evaluated under them. */
                corr = d->model->opt.corrections;
                first_known = 0;
            }
        }
        if (err <= 1) {
            braun__commit(d, pv->y1, t_new, 0);
            fresh = 1;
            d->error.status = BRAUN_OK;
            st = BRAUN_OK;
            accepted++;
            pending = out && every > 0 && accepted % every == 0;
            double fac = err > 0 ? 0.9 * pow(err, -0.2) : 5.0;
            h *= fac > 5.0 ? 5.0 : (fac < 0.2 ? 0.2 : fac);
            if (h < hmin) h = hmin;
        } else {
            BRAUN__COUNT(d->stats.rejected_steps);
            rejected++;
            /* (NaN: an error the tolerances cannot measure, e.g. rtol tiny
             * and atol 0 where y = 0, is a rejection too.) */
            double fac = err == err ? 0.9 * pow(err, -0.2) : 0.1;
            const double tried = h;
            h *= fac < 0.1 ? 0.1 : (fac > 0.9 ? 0.9 : fac);
            if (h < hmin) {
                /* Once more at h_min, unless that is what failed (or the
                 * last step, shorter, to t_end). */
                if (tried <= hmin) {
                    /* The whole span rejected where it is below the time's
                     * resolution: a shorter step would be below it too, the
                     * fixed-step drivers' status (it was "step too small
                     * (h = 6.4)" at t = 1e17, the resolution 355). */
                    if (!st && span_unresolved > 0)
                        st = braun__fail(d, BRAUN_ERR_TIME_RESOLUTION, "time (span below its resolution)", -1, -1,
                                         span_unresolved, (double)d->t);
                    if (!st) st = braun__fail(d, BRAUN_ERR_STEP_TOO_SMALL, "adaptive", -1, -1, h, (double)d->t);
                    break;
                }
                h = hmin;
            }
        }
    }
    if (st == BRAUN_ERR_ACCURACY) {
        braun__guard_rollback(d);
        return st;
    }
    /* The state kept (t_end, or where another failure stopped the run) is
     * checked, then reported if it has not been: the final output. */
    const int failed = st;
    const braun_error_info failure = d->error;
    if (!braun__data_intact(d, pv, 1)) return failed; /* re-initialised by a system callback */
    st = braun__final_checks(d);
    if (st == BRAUN_ERR_ACCURACY) braun__guard_rollback(d);
    if (st) return st;
    if (failed) d->error = failure;
    if (out && (pending || !failed) && (st = braun__output(d, out, out_user)) != BRAUN_OK) return st;
    return failed;
}

/* Busy while it runs, its output callback included (braun_priv.busy). */
int braun_integrate_adaptive(braun_data *d, const braun_adaptive *ctl,
                             braun_real t_end, long every, braun_output_fn out,
                             void *out_user)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = braun__check_ready(d);
    if (st) return st;
    braun_priv *pv = braun__priv(d);
    pv->busy = 1;
    st = integrate_adaptive(d, ctl, t_end, every, out, out_user);
    pv->busy = 0;
    return st;
}
