/* Monitors of a run: constraint and energy residuals (braun_residuals) and
 * the distance to the model's exact reference, at every sampled state. */
#include <math.h>

#include "braun_cli.h"
#include "braun_reference.h"

/* Keeps NaN once seen: a maximum over a run that met a NaN is not a number. */
static void track_max(double *mx, double x)
{
    if (isnan(*mx)) return;
    if (isnan(x) || x > *mx) *mx = x;
}

int braun_cli_monitor_init(braun_cli_monitor *mon, const braun_model *model,
                           const braun_builtin *builtin, double ref_h,
                           void *buffer, size_t bytes)
{
    /* The residuals run on a workspace of their own so that monitoring
     * cannot touch the integrator's scratch or its statistics. */
    int st = braun_data_init(&mon->scratch, model, buffer, bytes);
    if (st) return st;
    mon->builtin = builtin;
    /* References are lifted into fixed arrays of BRAUN_MODEL_MAX_N. */
    mon->has_ref = model->sys.n <= BRAUN_MODEL_MAX_N &&
                   braun_reference_init(&mon->ref, builtin, ref_h) == 0;
    mon->has_point = mon->has_ref && builtin->point_x >= 0 && builtin->point_y >= 0;
    mon->ref_h = mon->has_ref ? mon->ref.ref_h : NAN;
    mon->cur.pos = mon->cur.vel = mon->cur.energy = NAN;
    mon->cur.traj = mon->cur.point = NAN;
    mon->max.pos = mon->max.vel = mon->max.energy = 0;
    mon->max.traj = mon->has_ref ? 0 : NAN;
    mon->max.point = mon->has_point ? 0 : NAN;
    mon->samples = 0;
    return BRAUN_OK;
}

int braun_cli_monitor_measure(braun_cli_monitor *mon, const braun_data *d, braun_cli_errors *e)
{
    braun_data *s = &mon->scratch;
    const int n = d->model->sys.n;
    braun_real pos, vel, energy;
    /* |Φ_e| = |E - E0 - ∫Ė| needs the run's E0 and work integral. */
    s->E0 = d->E0;
    s->has_E0 = d->has_E0;
    s->work_in = d->work_in;
    int st = braun_residuals(s, d->t, d->q, d->v, &pos, &vel, &energy);
    if (st) return st;
    e->pos = (double)pos;
    e->vel = (double)vel;
    e->energy = (double)energy;
    e->traj = e->point = NAN;
    if (mon->has_ref) {
        double qr[BRAUN_MODEL_MAX_N], vr[BRAUN_MODEL_MAX_N], sum = 0;
        /* The run's times never decrease, as braun_reference_eval requires. */
        st = braun_reference_eval(&mon->ref, (double)d->t, qr, vr);
        if (st) return st;
        for (int i = 0; i < n; i++) {
            double err = (double)d->q[i] - qr[i];
            sum += err * err;
        }
        e->traj = sqrt(sum);
        if (mon->has_point) {
            const int ix = mon->builtin->point_x, iy = mon->builtin->point_y;
            e->point = hypot((double)d->q[ix] - qr[ix], (double)d->q[iy] - qr[iy]);
        }
    }
    return BRAUN_OK;
}

void braun_cli_monitor_accept(braun_cli_monitor *mon, const braun_cli_errors *e)
{
    mon->cur = *e;
    track_max(&mon->max.pos, mon->cur.pos);
    track_max(&mon->max.vel, mon->cur.vel);
    track_max(&mon->max.energy, mon->cur.energy);
    if (mon->has_ref) track_max(&mon->max.traj, mon->cur.traj);
    if (mon->has_point) track_max(&mon->max.point, mon->cur.point);
    mon->samples++;
}
