/* Adaptive driver: Dormand–Prince 5(4) with a standard step-size controller.
 * The embedded estimate measures the ideal flow's local error; the
 * corrections (applied once per accepted step, whatever the model's
 * discretization option) are not part of it. */
#include <math.h>

#include "braun_tableau.h"

static double error_norm(int count, const braun_real *y0, const braun_real *y1,
                         const braun_real *yerr, braun_real rtol, braun_real atol)
{
    double sum = 0;
    for (int i = 0; i < count; i++) {
        double a = fabs((double)y0[i]), b = fabs((double)y1[i]);
        double sc = (double)atol + (double)rtol * (a > b ? a : b);
        double e = (double)yerr[i] / sc;
        sum += e * e;
    }
    return sqrt(sum / count);
}

/* Error control sees only the error along the constraint manifold. The
 * normal part is what the position and velocity corrections remove at the
 * next step; near a singular configuration the ideal flow's normal
 * sensitivity grows like the inverse of the small pivot, and measuring it
 * would shrink h without end (measured: the four-bar at rtol 1e-10 stopped
 * with BRAUN_ERR_STEP_TOO_SMALL at t = 102.2 s). The last DOPRI5 stage was
 * evaluated at the end of the step, so pv->fv holds C_v there: in weighted
 * coordinates the tangent space is null(C), projected by N. Position errors
 * are projected only when all rows are holonomic (then C_q = C_v). */
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

int braun_integrate_adaptive(braun_data *d, const braun_adaptive *ctl,
                             braun_real t_end, long every, braun_output_fn out,
                             void *out_user)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = braun__check_ready(d, "braun_integrate_adaptive");
    if (st) return st;
    if (!ctl) return braun__fail(d, BRAUN_ERR_ARGUMENT, "adaptive control (NULL)", -1, -1, 0, (double)d->t);
    if (!(ctl->rtol >= 0) || !(ctl->atol >= 0) || (ctl->rtol == 0 && ctl->atol == 0))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "tolerances", -1, -1, (double)ctl->rtol, (double)d->t);
    if (!braun_is_finite(t_end) || !(t_end > d->t))
        return braun__fail(d, BRAUN_ERR_TIME, "t_end", -1, -1, (double)t_end, (double)d->t);
    const braun_tableau *tb = braun__tableau(BRAUN_DOPRI5);
    braun_priv *pv = braun__priv(d);
    const int n = pv->n;
    const double span = (double)(t_end - d->t);
    double h = ctl->h0 > 0 ? (double)ctl->h0 : 1e-3 * span;
    const double hmin = ctl->h_min > 0 ? (double)ctl->h_min : 1e-12 * span;
    const double hmax = ctl->h_max > 0 ? (double)ctl->h_max : span;
    const long max_steps = ctl->max_steps > 0 ? ctl->max_steps : 100000000L;
    /* The step limit counts this call's attempts, accepted and rejected. */
    long accepted = 0, rejected = 0;

    if (out && out(d, out_user)) return BRAUN_STOPPED;
    while (d->t < t_end) {
        if (h > hmax) h = hmax;
        int last = 0;
        if ((double)d->t + h >= (double)t_end * (1 - 1e-15) || (double)d->t + h >= (double)t_end) {
            h = (double)(t_end - d->t);
            last = 1;
        }
        if (accepted + rejected >= max_steps)
            return braun__fail(d, BRAUN_ERR_TOO_MANY_STEPS, "adaptive", -1, -1, (double)max_steps, (double)d->t);
        braun__load_state(d);
        /* Always per step: with a varying h the literal Δ = Φ/h changes
         * meaning from one trial step to the next and the error test, which
         * would see the 1/h terms, rejects without end. */
        st = braun__rk_attempt(d, tb, (braun_real)h, 0, pv->y1, pv->yerr);
        double err;
        if (st == BRAUN_ERR_CALLBACK_RECOVERABLE || st == BRAUN_ERR_DIVERGED) {
            err = 1e10; /* retry smaller, as SUNDIALS does for recoverable failures */
        } else if (st) {
            return st;
        } else {
            project_error_tangent(d);
            err = error_norm(2 * n, pv->y0, pv->y1, pv->yerr, ctl->rtol, ctl->atol);
        }
        if (err <= 1) {
            braun__commit(d, pv->y1, last ? t_end : (braun_real)((double)d->t + h));
            d->error.status = BRAUN_OK;
            accepted++;
            if (out && ((every > 0 && accepted % every == 0) || d->t >= t_end) &&
                out(d, out_user))
                return BRAUN_STOPPED;
            double fac = err > 0 ? 0.9 * pow(err, -0.2) : 5.0;
            h *= fac > 5.0 ? 5.0 : (fac < 0.2 ? 0.2 : fac);
        } else {
            d->stats.rejected_steps++;
            rejected++;
            double fac = 0.9 * pow(err, -0.2);
            h *= fac < 0.1 ? 0.1 : (fac > 0.9 ? 0.9 : fac);
            if (h < hmin) {
                if (st) return st;
                return braun__fail(d, BRAUN_ERR_STEP_TOO_SMALL, "adaptive", -1, -1, h, (double)d->t);
            }
        }
    }
    return BRAUN_OK;
}
