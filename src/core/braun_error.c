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
    const int busy = braun__priv(d)->busy;
    if (busy > busy_allowed)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           busy == 2 ? "re-entrant call: a step's stages are running on this data (called "
                                       "from a system callback)"
                                     : "re-entrant call: a driver is running on this data (called from "
                                       "its callback)",
                           -1, -1, 0, (double)d->t);
    return braun__check_system(d);
}

int braun__check_ready(braun_data *d)
{
    int st = braun__check_usable(d, 0);
    if (st) return st;
    if (!braun__priv(d)->state_set)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "no state: call braun_set_state first", -1, -1,
                           0, (double)d->t);
    return braun__check_options(d);
}
