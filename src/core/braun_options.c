/* Options are checked where they are used: braun_data_init checks them
 * before it creates anything, and every driver (braun_eval, braun_step,
 * braun_integrate, braun_integrate_adaptive) checks them again, so options
 * changed after braun_data_init are validated too (a few compares per call;
 * the linear solver cannot change: its state was made for the one chosen). */
#include "braun_internal.h"

/* NaN, ±Inf. */
static int bad_real(braun_real x) { return !braun_is_finite(x); }

int braun__check_options(braun_data *d)
{
    const braun_options *o = &d->model->opt;
    /* Widened to double only where an error is recorded: this runs every
     * step, and in a float build on an FPU without double that is a call. */
    const braun_real t = d->t;
    if (o->corrections & ~(unsigned)BRAUN_CORRECT_ALL)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.corrections (unknown bits)", -1, -1,
                           (double)o->corrections, (double)t);
    if (o->discretization != BRAUN_PER_STEP && o->discretization != BRAUN_PER_STAGE)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.discretization", -1, -1,
                           (double)o->discretization, (double)t);
    /* A relative rank tolerance of 1 or more declares every pivot zero. */
    if (bad_real(o->rank_tol) || o->rank_tol >= 1)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.rank_tol (must be < 1)", -1, -1,
                           (double)o->rank_tol, (double)t);
    if (bad_real(o->energy_max_rel))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.energy_max_rel", -1, -1,
                           (double)o->energy_max_rel, (double)t);
    if (bad_real(o->symmetry_tol))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.symmetry_tol", -1, -1,
                           (double)o->symmetry_tol, (double)t);
    if (bad_real(o->inconsistency_tol))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.inconsistency_tol", -1, -1,
                           (double)o->inconsistency_tol, (double)t);
    if (bad_real(o->guard))
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.guard", -1, -1, (double)o->guard, (double)t);
    /* A relative threshold of 1 or more would filter every direction. */
    if (bad_real(o->soft_tol) || o->soft_tol >= 1)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "options.soft_tol (must be < 1)", -1, -1,
                           (double)o->soft_tol, (double)t);
    if ((o->corrections & BRAUN_CORRECT_ENERGY) && !d->model->sys.energy)
        return braun__fail(d, BRAUN_ERR_NO_ENERGY_LAW, "options", -1, -1, 0, (double)t);
#ifdef BRAUN_NO_LINSOLVER
    if (o->linsolver)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "linear solver (not in this build)", -1, -1, 0, (double)t);
#endif
    /* The solver the data block was made for. */
    if (d->priv && braun__priv(d)->ls != braun__model_linsolver(d->model))
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "options.linsolver changed after braun_data_init", -1, -1, 0, (double)t);
    return BRAUN_OK;
}

/* Out of line: the message of a required callback made NULL after
 * braun_data_init, in braun_system_check's words. */
static BRAUN_NOINLINE int system_callback_missing(braun_data *d)
{
    const char *why = NULL;
    (void)braun_system_check(&d->model->sys, &why);
    return braun__fail(d, BRAUN_ERR_MISSING_CALLBACK, why ? why : "a required callback is NULL", -1, -1, 0,
                       (double)d->t);
}

int braun__check_system(braun_data *d)
{
    const braun_system *s = &d->model->sys;
    const braun_priv *pv = braun__priv(d);
    /* The buffers were laid out, and the per-system decisions taken, for
     * these (docs/api.md: the system may not change after braun_data_init). */
    if (s->n != pv->n || s->m != pv->m || s->p != pv->p || s->flags != pv->flags ||
        s->sparsity != pv->sp)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "model->sys changed after braun_data_init (n, m, p, flags or sparsity)", -1,
                           -1, 0, (double)d->t);
    if (!s->mass || !s->forces || (pv->m > 0 && !s->holonomic) || (pv->p > 0 && !s->nonholonomic) ||
        ((s->flags & BRAUN_ENERGY_INPUT) && !s->power))
        return system_callback_missing(d);
    return BRAUN_OK;
}
