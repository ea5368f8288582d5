/* braun and braun-noenergy: libbraun itself (Eqs. 16, 17, 20), fixed-step
 * Euler, Heun, RK4 (braun_integrate) or adaptive Dormand–Prince 5(4)
 * (braun_integrate_adaptive), default options otherwise. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

typedef struct sink {
    cmp_traj *tr;
    int failed;
} sink;

static int on_output(const braun_data *d, void *user)
{
    sink *s = user;
    if (cmp_traj_push(s->tr, (double)d->t, d->q, d->v)) {
        s->failed = 1;
        return 1;
    }
    return 0;
}

/* "BRAUN_ERR_DIVERGED: meaning" -> "BRAUN_ERR_DIVERGED". */
void cmp_status_from_braun(cmp_outcome *out, int st)
{
    const char *s = braun_status_str(st), *colon = strchr(s, ':');
    int len = colon ? (int)(colon - s) : (int)strlen(s);
    snprintf(out->status_name, sizeof out->status_name, "%.*s", len, s);
    out->status = st;
}

/* Sampling interval in steps: the grid spacing when it is a whole number of
 * steps (the study's grids are), else every step. */
long cmp_every(double dt_out, double h)
{
    double r = dt_out / h;
    long k = (long)floor(r + 0.5);
    return k >= 1 && fabs(r - (double)k) <= 1e-9 * r ? k : 1;
}

void cmp_run_braun(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                   cmp_outcome *out)
{
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    braun_model model;
    braun_data d;
    int st = braun_model_init(&model, &tg->sys);
    if (st) {
        cmp_status_from_braun(out, st);
        return;
    }
    if (spec->method == CMP_BRAUN_NOENERGY)
        model.opt.corrections &= BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY;
    size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes);
    if (!buf) {
        snprintf(out->status_name, sizeof out->status_name, "OUT_OF_MEMORY");
        out->status = -1;
        return;
    }
    st = braun_data_init(&d, &model, buf, bytes);
    if (!st) st = braun_set_state(&d, 0, tg->q0, tg->v0);
    sink s = {tr, 0};
    if (!st) {
        if (spec->integrator == BRAUN_DOPRI5) {
            braun_adaptive ctl;
            memset(&ctl, 0, sizeof ctl);
            ctl.rtol = spec->rtol;
            ctl.atol = spec->atol;
            st = braun_integrate_adaptive(&d, &ctl, spec->T, 1, on_output, &s);
        } else {
            st = braun_integrate(&d, (braun_method)spec->integrator, spec->h, spec->T,
                                 cmp_every(spec->dt_out, spec->h), on_output, &s);
        }
    }
    cmp_status_from_braun(out, s.failed ? BRAUN_ERR_BUFFER : st);
    if (st && d.error.status == st)
        snprintf(out->detail, sizeof out->detail, "at t = %.9g (%s)", d.error.t,
                 d.error.where ? d.error.where : "");
    out->t_reached = (double)d.t;
    out->counts.steps = d.stats.steps;
    out->counts.rejected = d.stats.rejected_steps;
    out->counts.rhs_evals = d.stats.rhs_evals;
    out->counts.lin_setups = d.stats.constraint_factorizations;
    out->counts.lin_solves = d.stats.rhs_evals;
    free(buf);
}
