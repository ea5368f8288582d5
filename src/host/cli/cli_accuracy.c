/* The accuracy guard's bounds as the core applied them in a run (braun.h:
 * options.guard, braun_data.guard): the relative guard times the scales
 * measured at the first step, or the residual found at the initial state
 * when that was larger; each residual is checked only with the correction
 * that computes it. The tool reports them in the summary and applies the
 * same bounds to the final state, which no step start has checked. */
#include <math.h>

#include "braun_cli.h"

static double larger(double a, double b) { return a > b ? a : b; }

void braun_cli_guard_bounds(const braun_data *d, braun_cli_bounds *b)
{
    const braun_model *model = d->model;
    const unsigned corr = model->opt.corrections;
    const int m = model->sys.m, rows = model->sys.m + model->sys.p;
    b->guard = model->opt.guard > 0 ? (double)model->opt.guard : 1e-3;
    b->on = model->opt.guard >= 0;
    b->pos_scale = (double)d->guard.pos;
    b->vel_scale = (double)d->guard.vel;
    b->energy_scale = (double)d->guard.energy;
    b->pos = b->vel = b->energy = NAN;
    if (!b->on) return;
    if ((corr & BRAUN_CORRECT_POSITION) && m > 0)
        b->pos = larger(b->guard * b->pos_scale, (double)d->guard.pos0);
    if ((corr & BRAUN_CORRECT_VELOCITY) && rows > 0)
        b->vel = larger(b->guard * b->vel_scale, (double)d->guard.vel0);
    if ((corr & BRAUN_CORRECT_ENERGY) && model->sys.energy && d->has_E0)
        b->energy = larger(b->guard * b->energy_scale, (double)d->guard.energy0);
}

const char *braun_cli_guard_exceeded(const braun_cli_bounds *b, const braun_cli_errors *e,
                                     double *value, double *bound)
{
    if (!b->on) return NULL;
    /* In the core's order; a NaN residual exceeds every bound. */
    if (!isnan(b->pos) && !(e->pos <= b->pos)) {
        *value = e->pos, *bound = b->pos;
        return "position residual ||Phi_q||";
    }
    if (!isnan(b->vel) && !(e->vel <= b->vel)) {
        *value = e->vel, *bound = b->vel;
        return "velocity residual ||[dPhi_q/dt; Phi_v]||";
    }
    if (!isnan(b->energy) && !(e->energy <= b->energy)) {
        *value = e->energy, *bound = b->energy;
        return "energy residual |Phi_e|";
    }
    return NULL;
}
