/* braun_error_format: d->error as one sentence for people (host only). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "braun_host.h"
#include "braun_c_locale.h"

/* snprintf that appends: keeps writing into what is left of buf and counts
 * the full length, so the caller can report truncation as snprintf does. */
typedef struct msg {
    char *buf;
    size_t size;
    size_t len; /* length the whole message needs so far */
} msg;

static void put(msg *w, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *at = NULL;
    size_t room = 0;
    if (w->buf && w->len < w->size) {
        at = w->buf + w->len;
        room = w->size - w->len;
    }
    /* clang-analyzer 14 reports ap as uninitialized here (it is started
     * above): a known false positive of valist.Uninitialized. */
    int k = braun__c_vsnprintf(at, room, fmt, ap); /* NOLINT(clang-analyzer-valist.Uninitialized) */
    va_end(ap);
    if (k > 0) w->len += (size_t)k;
}

/* "[i]", "[i][j]" or nothing, for the entry a check pointed at. */
static void put_index(msg *w, int i, int j)
{
    if (i >= 0) put(w, "[%d]", i);
    if (i >= 0 && j >= 0) put(w, "[%d]", j);
}

static void put_time(msg *w, double t) { put(w, " at t = %.10g", t); }

static const char *nonfinite_name(double x)
{
    if (isnan(x)) return "NaN";
    return x > 0 ? "+Inf" : "-Inf";
}

/* The core's `where` strings are terse identifiers; name the mass matrix
 * as people say it, keep the rest (they already read as nouns). */
static const char *noun(const char *where)
{
    if (!where) return "a value";
    if (strcmp(where, "mass") == 0) return "mass matrix";
    return where;
}

/* Entry bad of the integrator state [q; v; ∫Ė] (length 2n + 1), or of the
 * error estimate past its end. */
static void put_state_entry(msg *w, const braun_data *d, int bad)
{
    const int n = d->model ? d->model->sys.n : -1;
    if (n <= 0 || bad < 0) return;
    if (bad < n) put(w, ", q[%d] not finite", bad);
    else if (bad < 2 * n) put(w, ", v[%d] not finite", bad - n);
    else if (bad == 2 * n) put(w, ", energy input integral not finite");
    else put(w, ", error estimate not finite");
}

static void describe(msg *w, const braun_data *d)
{
    const braun_error_info *e = &d->error;
    const char *where = e->where;
    switch (e->status) {
    case BRAUN_OK:
        put(w, "no error");
        return;
    case BRAUN_STOPPED:
        put(w, "stopped by the output callback");
        break;
    case BRAUN_ERR_ARGUMENT:
        if (where && strcmp(where, "method") == 0)
            put(w, "unknown integration method %d", e->index);
        else if (where && strcmp(where, "tolerances") == 0)
            put(w, "invalid tolerances (rtol = %.3g; need 0 <= rtol < 1, atol >= 0 and finite, not both 0)",
                e->value);
        else if (where)
            put(w, "invalid argument '%s'", where);
        else
            put(w, "invalid argument (NULL pointer or option out of range)");
        if (where) break;
        return; /* nothing recorded: no time to report */
    case BRAUN_ERR_SIZE:
        /* The rule broken (braun_system_check's words): "invalid sizes n,
         * m, p" alone did not say which. */
        if (where && strcmp(where, "sizes (dense limit)") == 0)
            put(w, "invalid sizes: n = %.0f for the dense kernels, which take n <= BRAUN_MAX_DENSE "
                   "(4096) and m + p <= 8192 (a larger sparse system needs a sparse backend)", e->value);
        else if (where)
            put(w, "invalid sizes: %s", where);
        else
            put(w, "invalid sizes n, m, p");
        return;
    case BRAUN_ERR_BUFFER:
        if (where && strncmp(where, "buffer", 6) == 0 && d->model)
            put(w, "workspace buffer of %.0f bytes is smaller than braun_data_size() = %zu bytes", e->value,
                braun_data_size(d->model));
        else
            put(w, "workspace buffer smaller than braun_data_size(), or a backend could not allocate");
        return;
    case BRAUN_ERR_NONFINITE:
        put(w, "%s", noun(where));
        put_index(w, e->index, e->index2);
        put(w, " is %s", nonfinite_name(e->value));
        break;
    case BRAUN_ERR_MASS_NOT_SYMMETRIC:
        put(w, "mass matrix not symmetric: |M[%d][%d] - M[%d][%d]| = %.3g", e->index,
            e->index2, e->index2, e->index, e->value);
        break;
    case BRAUN_ERR_MASS_NOT_SPD:
        put(w, "mass matrix not positive definite at pivot %d (value %.3g, not above n*eps times its "
               "own diagonal entry)", e->index, e->value);
        break;
    case BRAUN_ERR_CALLBACK:
        put(w, "callback '%s' failed (returned %d)", where ? where : "?", e->index);
        break;
    case BRAUN_ERR_CALLBACK_RECOVERABLE:
        put(w, "callback '%s' failed recoverably (returned %d) and the step could not be retried",
            where ? where : "?", e->index);
        break;
    case BRAUN_ERR_STEP:
        put(w, "step size h = %.6g is not finite and positive", e->value);
        break;
    case BRAUN_ERR_TIME:
        put(w, "t_end = %.10g is not finite or not after the current time", e->value);
        break;
    case BRAUN_ERR_DIVERGED:
        if (where && strcmp(where, "step stage") == 0) {
            /* t is the step's start, the last good state. */
            put(w, "step diverged");
            put_time(w, e->t);
            put(w, " (h = %.6g, stage %d not finite)", e->value, e->index);
        } else if (!where || strcmp(where, "step") == 0) {
            put(w, "step diverged");
            put_time(w, e->t);
            put(w, " (h = %.6g", e->value);
            put_state_entry(w, d, e->index);
            put(w, ")");
        } else if (strcmp(where, "mass") == 0 && isfinite(e->value)) {
            /* The mass matrix lost a pivot at a state the step reached. */
            put(w, "step diverged: the mass matrix is not positive definite there (pivot %d is "
                   "%.3g, not above n*eps times its own diagonal entry)", e->index, e->value);
            put_time(w, e->t);
        } else {
            /* A callback output overflowed at a later stage of a step that
             * started finite: the record is that output, t the stage's time. */
            put(w, "step diverged: %s", noun(where));
            put_index(w, e->index, e->index2);
            put(w, " is %s", nonfinite_name(e->value));
            put_time(w, e->t);
        }
        return;
    case BRAUN_ERR_STEP_TOO_SMALL:
        put(w, "adaptive step fell below its minimum (h = %.3g)", e->value);
        break;
    case BRAUN_ERR_TOO_MANY_STEPS:
        if (where && strcmp(where, "adaptive") == 0)
            put(w, "step limit of %.0f steps reached before t_end", e->value);
        else
            put(w, "too many steps requested (%.3g)", e->value);
        break;
    case BRAUN_ERR_MISSING_CALLBACK:
        /* Which callback, and what requires it (the sizes or a flag:
         * "power is NULL but flags has BRAUN_ENERGY_INPUT"). */
        if (where)
            put(w, "a required callback is missing: %s", where);
        else
            put(w, "a callback the system requires is NULL");
        return;
    case BRAUN_ERR_NO_ENERGY_LAW:
        put(w, "energy correction requested but the system has no energy law");
        return;
    case BRAUN_ERR_TIME_RESOLUTION:
        /* The adaptive driver's whole span rejected below the resolution
         * (braun_adaptive.c): the figure is the resolution, not a step. */
        if (where && strcmp(where, "time (span below its resolution)") == 0)
            put(w, "the time's resolution here, 16 eps max(|t|, |t_end|) = %.3g (the adaptive "
                   "driver's minimum step), exceeds the span to t_end: its one step, the whole "
                   "span, was rejected, and a shorter one would be below the resolution (the "
                   "float horizon)", e->value);
        else
            put(w, "the step h = %.6g cannot advance time here in this precision (t + h rounds to "
                   "t, or more than 10%% away from it: the float horizon)", e->value);
        break;
    case BRAUN_ERR_ACCURACY: {
        /* The bound the guard used (braun.h: options.guard, braun_data.guard). */
        const double g = d->model && d->model->opt.guard > 0 ? (double)d->model->opt.guard : 1e-3;
        double scale = 0, r0 = 0;
        const char *what = "residual";
        /* (The residual's name: a refusal caused by a start off its
         * position constraints names them in every `where`.) */
        if (where && strstr(where, "position residual")) {
            scale = (double)d->guard.pos; r0 = (double)d->guard.pos0; what = "position residual ||Phi_q||";
        } else if (where && strstr(where, "velocity residual")) {
            scale = (double)d->guard.vel; r0 = (double)d->guard.vel0;
            what = "velocity residual ||[dPhi_q/dt; Phi_v]||";
        } else if (where && strstr(where, "energy")) {
            scale = (double)d->guard.energy; r0 = (double)d->guard.energy0; what = "energy residual |Phi_e|";
        }
        /* e->t: the state whose residual failed; d->t: the one kept. */
        if (g * scale >= r0)
            put(w, "%s = %.3g exceeds the accuracy guard %.3g (guard %.3g x scale %.3g)", what, e->value,
                g * scale, g, scale);
        else /* an inconsistent start: its own residual is the bound */
            put(w, "%s = %.3g exceeds the accuracy guard %.3g (the residual at the start; guard %.3g x "
                   "scale %.3g is smaller)", what, e->value, r0, g, scale);
        /* Two different times that print alike at 10 digits (a driver
         * crawling in steps of 6e-10) are given in full. */
        char a10[40], b10[40];
        braun__c_snprintf(a10, sizeof a10, "%.10g", e->t);
        braun__c_snprintf(b10, sizeof b10, "%.10g", (double)d->t);
        const int digits = strcmp(a10, b10) == 0 && e->t != (double)d->t ? 17 : 10;
        put(w, " at t = %.*g; the state kept is the last one that passed, at t = %.*g", digits, e->t,
            digits, (double)d->t);
        /* Refused while the allowance of a start off its position
         * constraints was in use: that start is the cause (braun.h,
         * error.index2: its largest row). */
        if (where && strstr(where, "a start off its position constraints"))
            put(w, "; the cause is the start's position error, allowed while the corrections remove "
                   "it: the start is too far off for them, or the step too large (start nearer the "
                   "constraints: braun check prints the assembly)");
        return;
    }
    case BRAUN_ERR_INCONSISTENT:
        if (d->stats.steps > 0)
            /* Rows that held for the steps before: the motion drifted off
             * rows dependent here (Bricard's linkage at dopri5 rtol 1e-2
             * was told "the constraints have no solution here"). */
            put(w, "dependent %s disagree by %.3g after %ld steps that held them: the motion "
                   "drifted off them (a step, or rtol and atol, too large for these rows?)",
                where ? where : "constraints", e->value, (long)d->stats.steps);
        else
            put(w, "dependent %s disagree by %.3g: the constraints have no solution here",
                where ? where : "constraints", e->value);
        if (e->index >= 0 && e->index2 >= 0) put(w, " (rows %d and %d disagree most)", e->index, e->index2);
        else if (e->index >= 0 && e->index2 == -2)
            put(w, " (row %d: its gradient is zero here, its error is not)", e->index);
        else if (e->index >= 0)
            put(w, " (row %d: its gradient depends on the other rows' here, its error does not)", e->index);
        break;
    default:
        put(w, "unknown status %d", e->status);
        if (where) put(w, " in '%s'", where);
        break;
    }
    put_time(w, e->t);
}

int braun_error_format(const braun_data *d, char *buf, size_t size)
{
    if (buf && size > 0) buf[0] = '\0';
    if (!d) return -1;
    msg w = {buf, size, 0};
    describe(&w, d);
    if (buf && size > 0 && w.len >= size) buf[size - 1] = '\0';
    return (int)w.len;
}
