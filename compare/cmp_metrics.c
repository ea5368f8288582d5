/* Metrics of a sampled trajectory (docs/compare.md, "Columns"):
 * ||Φ_q||, ||[Φ̇_q; Φ_v]||, |Φ_e| from libbraun's braun_residuals on a
 * workspace of the harness, and the distance to the reference. Maxima and
 * final values over the samples; a NaN, once met, stays (a maximum over a
 * run that produced a NaN is not a number). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of n values (sorted in place); NaN if none or any is NaN. */
static double median_of(double *x, long n)
{
    if (n <= 0) return NAN;
    for (long i = 0; i < n; i++)
        if (isnan(x[i])) return NAN;
    qsort(x, (size_t)n, sizeof *x, by_value);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

static void track(double *mx, double x)
{
    if (isnan(*mx)) return;
    if (isnan(x) || x > *mx) *mx = x;
}

int cmp_metrics_compute(const cmp_target *tg, const cmp_traj *tr, cmp_ref *ref,
                        cmp_metrics *mt, cmp_sample_fn each, void *user)
{
    const int n = tg->sys.n;
    braun_model model;
    braun_data d;
    void *buf = NULL;
    double *qr = malloc(2 * (size_t)n * sizeof(double));
    int st = qr ? braun_model_init(&model, &tg->sys) : -1;
    int rc = 0;
    if (!st) {
        size_t bytes = braun_data_size(&model);
        buf = malloc(bytes);
        st = buf ? braun_data_init(&d, &model, buf, bytes) : -1;
    }
    /* E0 from the initial state every method starts from. */
    if (!st) st = braun_set_state(&d, 0, tg->q0, tg->v0);
    memset(mt, 0, sizeof *mt);
    if (st) {
        free(qr);
        free(buf);
        return -1;
    }
    double *vr = qr + n;
    const int has_ref = ref != NULL;
    mt->traj_max = mt->traj_final = has_ref ? 0 : NAN;
    mt->point_max = mt->point_final = has_ref && tg->has_point ? 0 : NAN;
    /* Φ_e = E - E0 - ∫Ė dτ needs the work put in. Without input it is 0.
     * With input, every method is measured against the same work integral:
     * the trajectory reference's (libbraun's, constraint work included),
     * else the trapezoidal rule of Ė on the samples. */
    /* Moving constraints do work unless the system is scleronomic. */
    const int constraint_work = !(tg->sys.flags & BRAUN_SCLERONOMIC) && tg->sys.m + tg->sys.p > 0;
    const unsigned input = (tg->sys.flags & BRAUN_ENERGY_INPUT) || constraint_work;
    const int power = (tg->sys.flags & BRAUN_ENERGY_INPUT) && tg->sys.power;
    double work = 0, p_prev = 0, p_prev2 = 0, t_prev = 0, dt_prev = 0;
    long nref = 0; /* samples the reference knows */
    /* Every sample's ||Φ_q|| and |Φ_e|, for their medians. */
    double *pos_all = malloc(2 * (size_t)(tr->count > 0 ? tr->count : 1) * sizeof(double));
    double *en_all = pos_all ? pos_all + (tr->count > 0 ? tr->count : 1) : NULL;

    for (long k = 0; k < tr->count; k++) {
        const double t = tr->t[k], *q = tr->q + (size_t)k * n, *v = tr->v + (size_t)k * n;
        cmp_sample_err e;
        e.t = t;
        if (input) {
            double W;
            if (cmp_ref_work(ref, t, &W) == 0) {
                d.work_in = W;
            } else if (power && !constraint_work) {
                braun_real P = 0;
                if (tg->sys.power(t, q, v, &P, tg->sys.user)) P = NAN;
                const double dt = t - t_prev;
                /* On a uniform grid the interval's integral of the parabola
                 * through the last three samples (local error O(dt⁴));
                 * otherwise the trapezoidal rule. */
                if (k >= 2 && fabs(dt - dt_prev) <= 1e-9 * dt)
                    work += dt / 12.0 * (5.0 * P + 8.0 * p_prev - p_prev2);
                else if (k >= 1)
                    work += 0.5 * dt * (p_prev + P);
                p_prev2 = p_prev;
                p_prev = P;
                dt_prev = dt;
                t_prev = t;
                d.work_in = work;
            } else {
                d.work_in = NAN;
            }
        }
        braun_real pos, vel, en;
        if (braun_residuals(&d, t, q, v, &pos, &vel, &en) == 0) {
            e.pos = pos;
            e.vel = vel;
            e.energy = en;
        } else {
            e.pos = e.vel = e.energy = NAN;
            rc = -1;
        }
        e.traj = e.point = e.obs = e.obs_ref = NAN;
        if (tg->has_point) {
            double xy[2];
            tg->point(tg, q, xy);
            e.obs = xy[0];
        }
        int known = 0;
        if (has_ref) {
            const int rs = cmp_ref_eval(ref, t, qr, vr);
            known = rs == 0;
            if (rs < 0) rc = -1;
            if (known) {
                double s = 0;
                for (int i = 0; i < n; i++) s += (q[i] - qr[i]) * (q[i] - qr[i]);
                e.traj = sqrt(s);
                if (tg->has_point) {
                    double a[2], b[2];
                    tg->point(tg, q, a);
                    tg->point(tg, qr, b);
                    e.point = hypot(a[0] - b[0], a[1] - b[1]);
                    e.obs_ref = b[0];
                }
            }
            /* A reference that does not know this time (a published point)
             * leaves the sample out of the trajectory metrics. */
            if (known || rs < 0) {
                nref++;
                track(&mt->traj_max, e.traj);
                mt->traj_final = e.traj;
                if (tg->has_point) {
                    track(&mt->point_max, e.point);
                    mt->point_final = e.point;
                }
            }
        }
        if (pos_all) {
            pos_all[mt->samples] = e.pos;
            en_all[mt->samples] = e.energy;
        }
        track(&mt->pos_max, e.pos);
        track(&mt->vel_max, e.vel);
        track(&mt->energy_max, e.energy);
        mt->pos_final = e.pos;
        mt->vel_final = e.vel;
        mt->energy_final = e.energy;
        mt->samples++;
        if (each) each(&e, user);
    }
    if (has_ref && nref == 0) mt->traj_max = mt->traj_final = mt->point_max = mt->point_final = NAN;
    mt->pos_median = pos_all ? median_of(pos_all, mt->samples) : NAN;
    mt->energy_median = pos_all ? median_of(en_all, mt->samples) : NAN;
    free(pos_all);
    free(qr);
    free(buf);
    return rc;
}
