/* A shipped scene run by libbraun with all the corrections it declares,
 * its reported point sampled on the benchmark's output grid. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ifm_run.h"

int ifm_scene_report_index(const braun_scene_file *sf, const char *name)
{
    for (int k = 0; k < sf->nreports; k++)
        if (strcmp(sf->report_names[k], name) == 0) return k;
    return -1;
}

typedef struct sampler {
    const braun_scene_file *sf;
    int point, dim, velocity;
    double dt_out;
    long next;          /* next grid sample to write */
    ifm_result *res;
    int have_prev;
    double t_prev, P_prev[3], V_prev[3];
} sampler;

/* Grid samples between two step ends, from the point's positions and
 * velocities there: the cubic Hermite interpolant (4th order, as DOPRI5's
 * usual dense output) and its derivative; a grid time that is a step end
 * (h dividing the output step) takes the step's own values. */
static void fill(sampler *s, double t1, const double *P1, const double *V1)
{
    ifm_result *r = s->res;
    const int w = r->y.width;
    const double t0 = s->t_prev, h = t1 - t0;
    while (s->next < r->y.count) {
        const double tj = (double)s->next * s->dt_out;
        const double tol = 1e-9 * s->dt_out;
        if (tj > t1 + tol) break;
        double *y = r->y.y + s->next * w;
        if (fabs(tj - t1) <= tol || !s->have_prev || h <= 0) {
            for (int k = 0; k < s->dim; k++) {
                y[k] = P1[k];
                if (s->velocity) y[s->dim + k] = V1[k];
            }
        } else {
            const double x = (tj - t0) / h;
            const double h00 = (1 + 2 * x) * (1 - x) * (1 - x), h10 = x * (1 - x) * (1 - x);
            const double h01 = x * x * (3 - 2 * x), h11 = x * x * (x - 1);
            const double d00 = 6 * x * (x - 1), d10 = (1 - x) * (1 - 3 * x);
            const double d01 = -d00, d11 = x * (3 * x - 2);
            for (int k = 0; k < s->dim; k++) {
                const double *P0 = s->P_prev, *V0 = s->V_prev;
                y[k] = h00 * P0[k] + h10 * h * V0[k] + h01 * P1[k] + h11 * h * V1[k];
                if (s->velocity)
                    y[s->dim + k] =
                        (d00 * P0[k] + d01 * P1[k]) / h + d10 * V0[k] + d11 * V1[k];
            }
        }
        s->next++;
    }
}

/* Every step (and the start): the point, grid samples up to here, and the
 * residuals at step ends that reach a new output interval. */
static int on_step(const braun_data *d, void *u)
{
    sampler *s = u;
    const double t = (double)d->t;
    if (s->have_prev && t <= s->t_prev) return 0; /* the driver's final call again */
    double P[3], V[3];
    braun_scene_point_state(&s->sf->scene, s->point, d->q, d->v, P, V);
    const long before = s->next;
    fill(s, t, P, V);
    if (s->next > before || !s->have_prev) {
        braun_real p = 0, e = 0;
        /* braun_residuals takes a mutable data and changes nothing of the state. */
        braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, NULL, &e);
        s->res->max_pos = fmax(s->res->max_pos, (double)p);
        s->res->max_energy_abs = fmax(s->res->max_energy_abs, (double)e);
    }
    s->have_prev = 1;
    s->t_prev = t;
    memcpy(s->P_prev, P, sizeof P);
    memcpy(s->V_prev, V, sizeof V);
    return 0;
}

/* The status code's name: braun_status_str up to its colon. */
static void set_name(ifm_result *r, int st)
{
    snprintf(r->status_name, sizeof r->status_name, "%s", braun_status_str(st));
    char *colon = strchr(r->status_name, ':');
    if (colon) *colon = '\0';
}

static int one_run(const braun_scene_file *sf, const ifm_setting *set, double T, sampler *s,
                   double *cpu, char *why, size_t whysize)
{
    braun_model model;
    int st = braun_model_init(&model, &sf->sys);
    if (st != BRAUN_OK) {
        snprintf(why, whysize, "%s: braun_model_init: %s", sf->name, braun_status_str(st));
        return -1;
    }
    model.opt.corrections = sf->corrections;
    const size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes);
    braun_data d;
    if (!buf) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    st = braun_data_init(&d, &model, buf, bytes);
    if (st == BRAUN_OK) st = braun_set_state(&d, 0, sf->q0, sf->v0);
    if (st != BRAUN_OK) {
        snprintf(why, whysize, "%s: data/state: %s", sf->name, braun_status_str(st));
        braun_data_release(&d);
        free(buf);
        return -1;
    }
    ifm_result *r = s->res;
    s->next = 0;
    s->have_prev = 0;
    r->max_pos = r->max_energy_abs = 0;
    for (long i = 0; i < r->y.count * r->y.width; i++) r->y.y[i] = NAN;
    const double c0 = ifm_cpu_seconds();
    if (set->method == BRAUN_DOPRI5) {
        braun_adaptive ctl = {set->rtol, set->atol, 0.1 * s->dt_out, 0, 0, 0};
        st = braun_integrate_adaptive(&d, &ctl, T, 1, on_step, s);
    } else {
        st = braun_integrate(&d, set->method, set->h, T, 1, on_step, s);
    }
    *cpu = ifm_cpu_seconds() - c0;
    r->status = st;
    set_name(r, st);
    r->t_reached = (double)d.t;
    r->steps = d.stats.steps;
    r->rejected = d.stats.rejected_steps;
    r->rhs_evals = d.stats.rhs_evals;
    braun_data_release(&d);
    free(buf);
    return 0;
}

int ifm_braun_run(const braun_scene_file *sf, int report, int dim, int velocity,
                  const ifm_setting *set, double T, double dt_out, int reps, ifm_result *res,
                  char *why, size_t whysize)
{
    memset(res, 0, sizeof *res);
    const long count = lround(T / dt_out) + 1;
    const int width = velocity ? 2 * dim : dim;
    if (report < 0 || report >= sf->nreports) {
        snprintf(why, whysize, "%s: no such reported point", sf->name);
        return -1;
    }
    if (set->method != BRAUN_DOPRI5 && !(set->h > 0)) {
        snprintf(why, whysize, "%s: h = %g", sf->name, set->h);
        return -1;
    }
    if (ifm_series_init(&res->y, count, width, 0, dt_out)) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    sampler s;
    memset(&s, 0, sizeof s);
    s.sf = sf;
    s.point = sf->report_points[report];
    s.dim = dim;
    s.velocity = velocity;
    s.dt_out = dt_out;
    s.res = res;
    double cpu = 0, total = 0, best = INFINITY;
    if (one_run(sf, set, T, &s, &cpu, why, whysize)) return -1;
    best = total = cpu;
    for (int k = 1; k < reps && total < 0.5; k++) {
        if (one_run(sf, set, T, &s, &cpu, why, whysize)) return -1;
        total += cpu;
        if (cpu < best) best = cpu;
    }
    res->cpu_s = best;
    return 0;
}

void ifm_result_free(ifm_result *res)
{
    ifm_series_free(&res->y);
}
