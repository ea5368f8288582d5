/* Butcher tableaus of the explicit Runge–Kutta methods (braun_tableau.c). */
#ifndef BRAUN_TABLEAU_H
#define BRAUN_TABLEAU_H

#include "braun_internal.h"

typedef struct braun_tableau {
    const char *name;
    int stages;
    int order;
    /* In working precision: a float build would otherwise convert a double
     * coefficient in software (__aeabi_d2f) at every use. */
    braun_real c[BRAUN_MAX_STAGES];
    braun_real a[BRAUN_MAX_STAGES][BRAUN_MAX_STAGES];
    braun_real b[BRAUN_MAX_STAGES];      /* solution weights */
    braun_real e[BRAUN_MAX_STAGES];      /* b - b_hat (embedded error), zero if none */
} braun_tableau;

const braun_tableau *braun__tableau(braun_method method);

/* Where a step evaluates the corrections (Eqs. 16, 17, 20) and applies them
 * (docs/method.md, "Where the corrections are evaluated"). */
typedef enum {
    /* Once, at the step's start (the first stage's factorization), added to
     * the end with weight h: the per-step form of fixed steps. */
    BRAUN__CORR_AT_START = 0,
    /* At every stage with Δ = Φ/h: BRAUN_PER_STAGE. */
    BRAUN__CORR_AT_STAGES,
    /* Not in the attempt: its driver applies them to the end it accepts
     * (braun__corrections_at_end, with the last stage's factorization: the
     * end for DOPRI5). The attempt runs the accuracy guard at its start and
     * keeps the residuals there. */
    BRAUN__CORR_AT_END
} braun__corr_at;

/* Compute one step of size h from the start vector pv->y0 = [q; v; ∫Ė] at
 * d->t into y1 (and the embedded error estimate into yerr when non-NULL),
 * without changing the state. With yerr or BRAUN__CORR_AT_END the residuals
 * at the start are kept in pv->phi0, pv->ev0 and those at the last stage
 * are left in pv->phi, pv->ev. first_known: pv->k[0] already holds the
 * first stage at this start, with phi0, ev0 and step_rank (the adaptive
 * driver's reuse; never where the first stage computes corrections, which
 * depend on h): it is not evaluated again. On return pv->stage is the last
 * stage evaluated (set before its evaluation). (src/braun_step.c) */
int braun__rk_attempt(braun_data *d, const braun_tableau *tb, braun_real h,
                      braun__corr_at where, braun_real *y1, braun_real *yerr, int first_known);
/* Whether the last stage of tb is evaluated at the step's end, with the
 * weights b (c = 1, a_last = b): its value there is the next step's first
 * stage when nothing changes the end (first same as last). */
static inline int braun__tableau_fsal(const braun_tableau *tb)
{
    const int l = tb->stages - 1;
    if (l < 1 || tb->c[l] != 1) return 0;
    for (int j = 0; j < l; j++)
        if (tb->a[l][j] != tb->b[j]) return 0;
    return tb->b[l] == 0;
}
/* The residuals at a step's start (pv->phi, pv->ev there) kept as
 * pv->phi0, pv->ev0 for the adaptive error test. */
static inline void braun__keep_start_residuals(braun_priv *pv)
{
    for (int i = 0; i < pv->rows; i++) {
        pv->phi0[i] = pv->phi[i];
        pv->ev0[i] = pv->ev[i];
    }
}
/* pv->y0 := current state. */
void braun__load_state(braun_data *d);
/* Accept y1 as the state at t_new and count the step. */
/* Accept y1 at t_new; t_lo is the clock's compensation (braun_internal.h). */
void braun__commit(braun_data *d, const braun_real *y1, braun_real t_new, braun_real t_lo);
/* The clock advanced by h: the new d->t and its compensation. */
static inline braun_real braun__clock_advance(const braun_data *d, braun_real t_lo, braun_real h,
                                              braun_real *t_lo_new)
{
    const braun_real y = h + t_lo;
    const braun_real t_new = d->t + y;
    *t_lo_new = y - (t_new - d->t);
    return t_new;
}

#endif
