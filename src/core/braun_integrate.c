/* Fixed-step driver: from d->t to t_end with an output callback. */
#include <limits.h>
#include <math.h>

#include "braun_tableau.h"

/* A step failed other than by the guard: the state kept (the last step's)
 * is checked as a last state is, and reported if its output was due. */
static int finish_failed(braun_data *d, int failed, int due, braun_output_fn out, void *out_user)
{
    const braun_error_info failure = d->error;
    /* Re-initialised by a system callback: nothing of the run is left to
     * check (braun__rk_attempt said so). */
    if (!braun__data_intact(d, braun__priv(d), 1)) return failed;
    int st = braun__final_checks(d);
    if (st == BRAUN_ERR_ACCURACY) braun__guard_rollback(d);
    if (st) return st;
    d->error = failure;
    if (due && (st = braun__output(d, out, out_user)) != BRAUN_OK) return st;
    return failed;
}

static int integrate(braun_data *d, braun_method method, braun_real h, braun_real t_end, long every,
                     braun_output_fn out, void *out_user)
{
    int st;
    const braun_tableau *tb = braun__tableau(method);
    if (!tb) return braun__fail(d, BRAUN_ERR_ARGUMENT, "method", (int)method, -1, 0, (double)d->t);
    if (!(h > 0) || !braun_is_finite(h))
        return braun__fail(d, BRAUN_ERR_STEP, "step size", -1, -1, (double)h, (double)d->t);
    if (!braun_is_finite(t_end) || !(t_end > d->t))
        return braun__fail(d, BRAUN_ERR_TIME, "t_end", -1, -1, (double)t_end, (double)d->t);
    braun_priv *pv = braun__priv(d);
    const double t0 = (double)d->t, span = (double)t_end - t0;
    const double ratio = span / (double)h;
    /* The step counter is a long: 32 bits on a Cortex-M (and Windows), where
     * a span of more than ~2.1e9 steps would overflow it. */
    const double most = LONG_MAX > 2147483647L ? 9.0e18 : (double)LONG_MAX - 1.0;
    if (ratio > most) return braun__fail(d, BRAUN_ERR_TOO_MANY_STEPS, "step count", -1, -1, ratio, t0);
    long steps = braun__fixed_step_count(ratio);

    if (out && (st = braun__output(d, out, out_user)) != BRAUN_OK) return st;
    for (long i = 1; i <= steps; i++) {
        /* Each step integrates h (the last one lands on t_end); the clock is
         * compensated, so t stays t0 + i·h to round-off over 10^6 steps
         * without double arithmetic in a float build. */
        braun_real t_lo = 0, hi = h, t_new;
        if (i == steps) {
            t_new = t_end;
            hi = (t_end - d->t) - pv->t_lo;
        } else {
            t_new = braun__clock_advance(d, pv->t_lo, h, &t_lo);
        }
        st = braun__time_step_ok(d, d->t, t_new, h, i == steps);
        if (!st) st = braun__mass_claim_due(d, d->t, d->q);
        if (st) return finish_failed(d, st, out && every > 0 && i > 1 && (i - 1) % every == 0, out, out_user);
        braun__load_state(d);
        /* Read at every step: an output callback may change it. */
        const int per_stage = d->model->opt.discretization == BRAUN_PER_STAGE;
        st = braun__rk_attempt(d, tb, hi, per_stage ? BRAUN__CORR_AT_STAGES : BRAUN__CORR_AT_START,
                               pv->y1, NULL, 0);
        if (!st) st = braun__check_unchanged(d);
        if (st == BRAUN_ERR_ACCURACY) {
            braun__guard_rollback(d);
            return st;
        }
        if (st) return finish_failed(d, st, out && every > 0 && i > 1 && (i - 1) % every == 0, out, out_user);
        /* This step's start passed the guard: only now is the state the
         * last step left reported, so a run the guard stops has reported
         * only states that passed. */
        if (out && every > 0 && i > 1 && (i - 1) % every == 0 &&
            (st = braun__output(d, out, out_user)) != BRAUN_OK)
            return st;
        braun__commit(d, pv->y1, t_new, t_lo);
    }
    st = braun__final_checks(d);
    if (st == BRAUN_ERR_ACCURACY) braun__guard_rollback(d);
    if (st) return st;
    if (out && (st = braun__output(d, out, out_user)) != BRAUN_OK) return st;
    return BRAUN_OK;
}

/* Busy while it runs, its output callback included (braun_priv.busy). */
int braun_integrate(braun_data *d, braun_method method, braun_real h,
                    braun_real t_end, long every, braun_output_fn out,
                    void *out_user)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = braun__check_ready(d);
    if (st) return st;
    braun_priv *pv = braun__priv(d);
    pv->busy = 1;
    st = integrate(d, method, h, t_end, every, out, out_user);
    pv->busy = 0;
    return st;
}
