/* The data block: size, initialisation from the caller's buffer, release,
 * and the state. */
#include <stdint.h>

#include "braun_internal.h"

#define BRAUN_ALIGN 16u

/* Dense kernels index n x n and rows x n arrays: bounded sizes. */
static int dense_size_ok(const braun_model *model)
{
    const braun_system *s = &model->sys;
    if (!(braun__model_linsolver(model)->flags & BRAUN_LS_DENSE)) return 1;
    return s->n <= BRAUN_MAX_DENSE && s->m + s->p <= 2 * BRAUN_MAX_DENSE;
}

size_t braun_data_size(const braun_model *model)
{
    if (!model || model->sys.n <= 0 || !dense_size_ok(model)) return 0;
    /* + alignment slack: the caller's buffer may start anywhere. */
    return braun__layout(model, NULL, NULL, NULL, NULL) + BRAUN_ALIGN;
}

/* A backend table (braun_linsolver.h) without an operation the core calls. */
static const char *linsolver_problem(const braun_linsolver *ls)
{
    if (!ls->factor_mass || !ls->solve_rt || !ls->solve_r || !ls->mul_r || !ls->factor_c || !ls->pinv ||
        !ls->lsq || !ls->null_project)
        return "options.linsolver lacks a required operation (factor_mass, solve_rt, solve_r, mul_r, "
               "factor_c, pinv, lsq, null_project)";
    if (ls->create && !ls->destroy) return "options.linsolver has create but no destroy";
    /* Every backend has a state: created, or bound in the data block (a
     * table with neither handed its operations NULL: a crash). */
    if (!ls->create && !ls->bind)
        return "options.linsolver has neither create (and destroy) nor state_bytes and bind";
    if (!ls->create && (!ls->state_bytes != !ls->bind))
        return "options.linsolver needs both state_bytes and bind (or create and destroy)";
    if (!ls->soft_find != !ls->soft_project)
        return "options.linsolver has only one of soft_find and soft_project";
    return NULL;
}

/* Nothing is left to release when this fails (a backend's state is
 * created after every check, and freed again if what follows fails). */
int braun_data_init(braun_data *d, const braun_model *model, void *buffer,
                    size_t bytes)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    d->priv = NULL;
    d->model = model;
    d->error = (braun_error_info){BRAUN_OK, NULL, -1, -1, 0, 0};
    if (!model || !buffer)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, model ? "buffer (NULL)" : "model (NULL)", -1,
                           -1, 0, 0);
    {
        /* A model filled in by hand, or edited after braun_model_init, gets
         * braun_model_init's checks too. */
        const char *why = NULL;
        const int sc = braun_system_check(&model->sys, &why);
        if (sc) return braun__fail(d, sc, why, -1, -1, 0, 0);
        if ((why = linsolver_problem(braun__model_linsolver(model))) != NULL)
            return braun__fail(d, BRAUN_ERR_ARGUMENT, why, -1, -1, 0, 0);
    }
    size_t need = braun_data_size(model);
    if (need == 0)
        return braun__fail(d, BRAUN_ERR_SIZE, "sizes (dense limit)", -1, -1,
                           (double)model->sys.n, 0);
    if (bytes < need)
        return braun__fail(d, BRAUN_ERR_BUFFER, "buffer (smaller than braun_data_size)", -1, -1,
                           (double)bytes, 0);
    {
        /* The data and the model are the caller's structs, not part of the
         * scratch: carved over, the model's callbacks became wild jumps. */
        const uintptr_t lo = (uintptr_t)buffer, hi = lo + bytes;
        const uintptr_t dl = (uintptr_t)d, ml = (uintptr_t)model;
        const int holds_data = dl < hi && lo < dl + sizeof *d;
        if (holds_data || (ml < hi && lo < ml + sizeof *model))
            return braun__fail(d, BRAUN_ERR_ARGUMENT,
                               holds_data ? "buffer (holds the braun_data itself)"
                                          : "buffer (holds the braun_model)",
                               -1, -1, 0, 0);
    }
    d->t = 0;
    d->work_in = 0;
    d->E0 = 0;
    d->has_E0 = 0;
    d->stats = (braun_stats){0, 0, 0, 0, 0, 0, 0, 0};
    /* Every option, before anything is made. */
    int st = braun__check_options(d);
    if (st) return st;
    const braun_linsolver *ls = braun__model_linsolver(model);
    if ((ls->flags & BRAUN_LS_NEEDS_SPARSITY) && !model->sys.sparsity)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "linear solver needs a sparsity", -1, -1, 0, 0);

    uintptr_t addr = (uintptr_t)buffer;
    size_t shift = (size_t)((BRAUN_ALIGN - addr % BRAUN_ALIGN) % BRAUN_ALIGN);
    unsigned char *base = (unsigned char *)buffer + shift;
    braun_priv *pv = (braun_priv *)(void *)base;
    const braun_system *s = &model->sys;
    pv->n = s->n;
    pv->m = s->m;
    pv->p = s->p;
    pv->rows = s->m + s->p;
    pv->need_fq = s->p > 0 && s->m > 0;
    pv->work_rows = s->m + s->p > 0 && !(s->flags & BRAUN_SCLERONOMIC) &&
                    ((s->flags & BRAUN_ENERGY_INPUT) || s->energy);
    pv->R_is_constant = 0;
    pv->state_integrated = 0;
    pv->vel_judged = 0;
    pv->e0_pending = 1;
    pv->mass_check_in = BRAUN_MASS_CHECK_EVERY;
    pv->mass_claim_false = 0;
    pv->state_set = 0;
    pv->flags = s->flags;
    pv->busy = 0;
    pv->has_prev = 0;
    pv->t_lo = 0;
    pv->done = 0;
    pv->rank[0] = pv->rows;
    pv->rank[1] = s->m;
    braun__rank_rule_plain(pv);
    pv->soft_on = pv->have_ref = pv->stage = pv->ref_slot = 0;
    pv->energy_end = pv->de_ok = pv->sat0 = 0;
    pv->sigma0 = 0;
    pv->ref_step = 0;
    pv->step_rank[0] = pv->rows;
    pv->step_rank[1] = s->m;
    pv->Edot = 0;
    braun__layout(model, base, pv, &d->q, &d->v);
    pv->owner = d;
    pv->q_home = d->q;
    pv->v_home = d->v;
    for (int i = 0; i < s->n; i++) d->q[i] = d->v[i] = 0;
    /* Off-pattern entries of a scattered A stay zero from here on. */
    if (pv->sp && pv->dense_A)
        for (size_t i = 0; i < (size_t)pv->rows * (size_t)pv->n; i++) pv->A[i] = 0;
#ifndef BRAUN_NO_LINSOLVER
    if (ls->create) {
        st = ls->create(&pv->ls_state, model);
        if (st) return braun__fail(d, st, "linear solver create", -1, -1, 0, 0);
        pv->ls_owned = 1;
    }
#endif
    d->priv = pv;
    if (s->flags & BRAUN_MASS_CONSTANT) {
        braun__at(pv, 0, d->q, d->v, 0, 0);
        st = braun__stage_mass(d);
        if (st) {
            braun_data_release(d);
            d->priv = NULL;
            return st;
        }
        pv->R_is_constant = 1;
    }
    return BRAUN_OK;
}

int braun_data_release(braun_data *d)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    if (!d->priv) return BRAUN_OK;
    braun_priv *pv = braun__priv(d);
    /* From a callback of a running driver or step: the run would go on
     * without its scratch. A struct copy (b = a) is not the data: releasing
     * it freed a's backend state, and a's next step read through NULL. */
    if (pv->busy || pv->owner != d) return braun__check_usable(d, 0);
#ifndef BRAUN_NO_LINSOLVER
    if (pv->ls_owned && pv->ls_state && pv->ls->destroy) pv->ls->destroy(pv->ls_state);
#endif
    pv->ls_state = NULL;
    pv->ls_owned = 0;
    /* Released: every call refuses it until braun_data_init (a backend's
     * state is gone); q and v still point at the last state. */
    d->priv = NULL;
    return BRAUN_OK;
}

int braun_set_state(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = braun__check_usable(d, 0);
    if (st) return st;
    if (!q || !v) return braun__fail(d, BRAUN_ERR_ARGUMENT, q ? "state v (NULL)" : "state q (NULL)", -1, -1, 0, (double)t);
    const int n = d->model->sys.n;
    if (!braun_is_finite(t)) return braun__fail(d, BRAUN_ERR_NONFINITE, "state t", -1, -1, (double)t, (double)t);
    st = braun__check_finite(d, n, q, "state q", 0, t);
    if (st) return st;
    st = braun__check_finite(d, n, v, "state v", 0, t);
    if (st) return st;
    /* E0 and the mass claim first: a start whose energy cannot be
     * evaluated changes nothing (the last run's state stays, and so does
     * whether one is set). */
    braun_real E0;
    st = braun__energy(d, t, q, v, &E0);
    if (!st) st = braun__check_mass_claim(d, t, q);
    if (st) return st;
    for (int i = 0; i < n; i++) {
        d->q[i] = q[i];
        d->v[i] = v[i];
    }
    braun_priv *pv = braun__priv(d);
    d->t = t;
    d->work_in = 0;
    /* A new run: its statistics start from zero (the constant M's one
     * factorization, made at braun_data_init, stays counted). */
    d->stats = (braun_stats){0, 0, 0, pv->R_is_constant ? 1 : 0, 0, 0, 0, 0};
    pv->state_integrated = 0;
    pv->vel_judged = 0;
    pv->e0_pending = 1;
    pv->mass_check_in = BRAUN_MASS_CHECK_EVERY;
    pv->state_set = 1;
    pv->has_prev = 0;
    pv->t_lo = 0;
    braun__clear_compensation(pv);
    pv->have_ref = 0;
#ifdef BRAUN_NO_LINSOLVER
    braun__dense_new_run(pv->ls_state);
#else
    if (pv->ls == &braun__dense_linsolver) braun__dense_new_run(pv->ls_state);
#endif
    /* A new run decides its first rank by the plain tolerance. */
    pv->step_rank[0] = pv->rows;
    pv->step_rank[1] = pv->m;
    d->E0 = E0;
    d->has_E0 = d->model->sys.energy != NULL;
    /* The guard's scales come from the first step's start (its forward pass
     * is at this state): no evaluation here. */
    pv->guard_pending = 1;
    pv->vel_induced0 = 0;
    pv->start_row = -1;
    pv->start_off = 0;
    d->guard.pos = d->guard.vel = d->guard.energy = 0;
    d->guard.pos0 = d->guard.vel0 = d->guard.energy0 = 0;
    return BRAUN_OK;
}
