/* The accuracy guard's bounds as the core applied them in a run (braun.h:
 * options.guard, braun_data.guard): the relative guard times the scales
 * measured at the first step, or the residual found at the initial state
 * when that was larger; each residual is checked only with the correction
 * that computes it. The tool reports them in the summary; the
 * core applies them at every step's start and to a driver's last state. */
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
