/* Error records: every failing call says in d->error what failed, where and
 * when (braun_error_format() in the host tier turns it into a sentence). */
#include "braun_internal.h"

int braun__fail(braun_data *d, int status, const char *where, int index,
                int index2, double value, double t)
{
    d->error.status = status;
    d->error.where = where;
    d->error.index = index;
    d->error.index2 = index2;
    d->error.value = value;
    d->error.t = t;
    return status;
}

int braun__callback_failed(braun_data *d, int rc, const char *where, braun_real t)
{
    return braun__fail(d, rc < 0 ? BRAUN_ERR_CALLBACK : BRAUN_ERR_CALLBACK_RECOVERABLE,
                       where, rc, -1, (double)rc, (double)t);
}

BRAUN_NOINLINE int braun__callback_missing(braun_data *d, const char *where, braun_real t)
{
    (void)where;
    return braun__fail(d, BRAUN_ERR_MISSING_CALLBACK,
                       "a system callback is NULL: the model changed while a step ran (from a callback)", -1,
                       -1, 0, (double)t);
}

int braun__check_finite(braun_data *d, int n, const braun_real *x,
                        const char *where, int cols, braun_real t)
{
    if (braun_all_finite(n, x)) return BRAUN_OK;
    for (int i = 0; i < n; i++)
        if (!braun_is_finite(x[i]))
            return braun__fail(d, BRAUN_ERR_NONFINITE, where,
                               cols > 0 ? i / cols : i, cols > 0 ? i % cols : -1,
                               (double)x[i], (double)t);
    return BRAUN_OK;
}

int braun__check_usable(braun_data *d, int busy_allowed)
{
    if (!d->priv || !d->model)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "data not initialised (braun_data_init not called, failed, or released)", -1, -1,
                           0, 0);
    /* A struct copy (b = a) shares a's buffer but is no second data
     * (docs/api.md, "Copies"): refused rather than run on a's scratch. */
    if (braun__priv(d)->owner != d)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "data is a copy (b = a) or was moved: use the braun_data that "
                           "braun_data_init made (a second run needs its own buffer and init)",
                           -1, -1, 0, 0);
    const int busy = braun__priv(d)->busy;
    if (busy > busy_allowed)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           busy == 2 ? "re-entrant call: a step's stages are running on this data (called "
                                       "from a system callback)"
                                     : "re-entrant call: a driver is running on this data (called from "
                                       "its callback)",
                           -1, -1, 0, (double)d->t);
    /* The state's pointers are the library's (a program that wrote one
     * would have the library write through it). */
    const braun_priv *pv = braun__priv(d);
    if (d->q != pv->q_home || d->v != pv->v_home)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           d->q != pv->q_home ? "state pointer q (changed: it is the library's, into the buffer)"
                                              : "state pointer v (changed: it is the library's, into the buffer)",
                           -1, -1, 0, (double)d->t);
    return braun__check_system(d);
}

/* A guard scale a program set is NaN, Inf or negative: name it. */
static BRAUN_NOINLINE int bad_guard_scale(braun_data *d)
{
    const braun_real g[6] = {d->guard.pos, d->guard.vel, d->guard.energy,
                             d->guard.pos0, d->guard.vel0, d->guard.energy0};
    static const char *const name[6] = {
        "guard.pos (a scale must be finite and >= 0)",    "guard.vel (a scale must be finite and >= 0)",
        "guard.energy (a scale must be finite and >= 0)", "guard.pos0 (a scale must be finite and >= 0)",
        "guard.vel0 (a scale must be finite and >= 0)",   "guard.energy0 (a scale must be finite and >= 0)"};
    int k = 0;
    while (k < 5 && g[k] >= 0 && braun_is_finite(g[k])) k++;
    return braun__fail(d, BRAUN_ERR_ARGUMENT, name[k], -1, -1, (double)g[k], (double)d->t);
}

/* Fields of braun_data a program can write (braun.h): t is set by
 * braun_set_state only, the guard's scales may be the program's own. */
static int check_written_fields(braun_data *d)
{
    if (!braun_is_finite(d->t))
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "state t (not finite: the state is set by braun_set_state only)", -1, -1,
                           (double)d->t, 0);
    /* A program's own integrator keeps ∫Ė there (braun_energy_rate). */
    if (!braun_is_finite(d->work_in))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "state work_in (not finite)", -1, -1,
                           (double)d->work_in, (double)d->t);
    if (!braun__priv(d)->guard_pending) {
        /* (Measured at the first step: till then they are not used.) */
        const braun_real g0 = d->guard.pos, g1 = d->guard.vel, g2 = d->guard.energy;
        const braun_real g3 = d->guard.pos0, g4 = d->guard.vel0, g5 = d->guard.energy0;
        if (!(g0 >= 0 && g1 >= 0 && g2 >= 0 && g3 >= 0 && g4 >= 0 && g5 >= 0) ||
            !(g0 * 0 + g1 * 0 + g2 * 0 + g3 * 0 + g4 * 0 + g5 * 0 == 0))
            return bad_guard_scale(d);
    }
    return BRAUN_OK;
}

int braun__data_intact(const braun_data *d, const braun_priv *pv, int busy)
{
    return d->priv == pv && pv->busy == busy;
}

/* A driver may run on d: usable (busy up to busy_allowed), a state set,
 * the fields a program writes valid, the options valid. */
static int check_ready(braun_data *d, int busy_allowed)
{
    int st = braun__check_usable(d, busy_allowed);
    if (st) return st;
    if (!braun__priv(d)->state_set)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "no state: call braun_set_state first", -1, -1,
                           0, (double)d->t);
    st = check_written_fields(d);
    return st ? st : braun__check_options(d);
}

int braun__output(braun_data *d, braun_output_fn out, void *user)
{
    const braun_priv *pv = braun__priv(d);
    if (out(d, user)) return BRAUN_STOPPED;
    /* braun_data_init in the callback resets busy (and release is refused
     * there): the driver's scratch is no longer its own. */
    if (!braun__data_intact(d, pv, 1))
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "the output callback re-initialised the data a driver runs on", -1, -1, 0,
                           (double)d->t);
    /* Then every check a call makes, the driver's own busy allowed. */
    return check_ready(d, 1);
}

int braun__check_ready(braun_data *d)
{
    return check_ready(d, 0);
}
