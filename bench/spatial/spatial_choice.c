/* The coordinate study of docs/method.md, "Spatial rigid bodies": Euler
 * parameters (rigid3d) against natural coordinates (nc_body.c) on the same
 * scenes (spatial_models.c), measured as accuracy per CPU-second.
 *
 *   braun-spatial-choice [--quick]          CSV on stdout
 *
 * For each mechanism and formulation: RK4 at a ladder of steps with all
 * corrections (the default options), the error being the largest distance
 * over an output grid between the tracked bodies' centres and a reference
 * — the same mechanism in Euler parameters with RK4 at a step 16 times
 * below the smallest of the ladder (4 for the stiff governor, whose
 * errors are 1e-11 there already) — plus the largest ‖Φ_q‖ and |Φ_e|
 * along the run (each formulation's own rows) and the CPU time of the run
 * (CLOCK_PROCESS_CPUTIME_ID, best of three). The two formulations' fine
 * references are compared too (`ref_gap`): both discretise one motion. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "braun.h"
#include "nc_body.h"
#include "spatial_models.h"

typedef struct study {
    const char *model;
    int N;
    double t_end, out_dt;
    double h[5];
    double ref_div; /* reference step: the smallest h over this */
} study;

typedef struct record {
    int nout, tracked;
    double *c; /* nout x tracked x 3 */
} record;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One run; rec (may be NULL) gets the centres on the output grid. Returns
 * the CPU seconds, or -1 on a failed step. */
static double run(const spatial_model *m, const braun_system *sys, double h, double t_end,
                  double out_dt, record *rec, double *max_pos, double *max_energy)
{
    braun_model model;
    braun_data d;
    int st = braun_model_init(&model, sys);
    const size_t bytes = st ? 0 : braun_data_size(&model);
    void *buf = malloc(bytes + 1);
    double *q = malloc(sizeof(double) * (size_t)sys->n), *v = malloc(sizeof(double) * (size_t)sys->n);
    if (!st && buf && q && v) st = braun_data_init(&d, &model, buf, bytes);
    if (!st) {
        braun_scene_initial_state(&m->scene, q, v);
        st = braun_set_state(&d, 0, q, v);
    }
    if (st || !buf || !q || !v) {
        fprintf(stderr, "setting up failed: %s\n", braun_status_str(st));
        return -1;
    }
    const long steps = lround(t_end / h), every = lround(out_dt / h);
    double cpu = -now();
    int k = 0, failed = 0;
    *max_pos = *max_energy = 0;
    for (long i = 0; i <= steps; i++) {
        if (i % every == 0) {
            if (rec && k < rec->nout)
                for (int b = 0; b < rec->tracked; b++)
                    for (int c = 0; c < 3; c++)
                        rec->c[(k * rec->tracked + b) * 3 + c] = d.q[m->bodies[b].iq + c];
            k++;
            double pos, vel, en;
            cpu += now();
            braun_residuals(&d, d.t, d.q, d.v, &pos, &vel, &en);
            cpu -= now();
            if (pos > *max_pos) *max_pos = pos;
            if (en > *max_energy) *max_energy = en;
        }
        if (i < steps && (st = braun_step(&d, BRAUN_RK4, h)) != 0) {
            fprintf(stderr, "h = %g: step %ld failed (%s at '%s', value %g, t = %g)\n", h, i,
                    braun_status_str(st), d.error.where ? d.error.where : "?", d.error.value,
                    d.error.t);
            failed = 1;
            break;
        }
    }
    cpu = failed ? -1 : cpu + now();
    braun_data_release(&d);
    free(buf);
    free(q);
    free(v);
    return cpu;
}

static double distance(const record *a, const record *b)
{
    double worst = 0;
    for (int k = 0; k < a->nout; k++)
        for (int i = 0; i < a->tracked; i++) {
            const double *x = &a->c[(k * a->tracked + i) * 3], *y = &b->c[(k * b->tracked + i) * 3];
            const double d = sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                                  (x[2] - y[2]) * (x[2] - y[2]));
            if (d > worst) worst = d;
        }
    return worst;
}

static int alloc_record(record *r, const study *st, int tracked)
{
    r->nout = (int)lround(st->t_end / st->out_dt) + 1;
    r->tracked = tracked;
    r->c = calloc((size_t)r->nout * (size_t)tracked * 3, sizeof *r->c);
    return r->c ? 0 : -1;
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    const study studies[] = {
        {"bricard", 0, 10, 0.05, {1e-2, 5e-3, 2.5e-3, 1.25e-3, 0}, 16},
        {"governor", 0, 2, 0.01, {2e-4, 1e-4, 5e-5, 2.5e-5, 0}, 4},
        {"chain", 10, 5, 0.05, {1e-2, 5e-3, 2.5e-3, 1.25e-3, 0}, 16},
    };
    const braun_scene_body_class *const classes[2] = {BRAUN_BODY_RIGID3D, &bench_body_nc};
    const char *const names[2] = {"euler", "natural"};
    printf("model,formulation,n,m,h,steps,cpu_s,cpu_per_step_us,max_error,max_pos_err,max_energy_err,ref_gap\n");
    for (size_t s = 0; s < sizeof studies / sizeof studies[0]; s++) {
        const study *st = &studies[s];
        spatial_model m[2];
        braun_system sys[2];
        record ref[2], rec;
        double hmin = st->h[0];
        for (int i = 0; st->h[i] > 0 && i < 5; i++) hmin = st->h[i];
        const double href = hmin / (quick ? 4 : st->ref_div);
        for (int c = 0; c < 2; c++)
            if (spatial_model_make(&m[c], st->model, st->N, classes[c], &sys[c])) return 1;
        double pe, ee;
        for (int c = 0; c < 2; c++) {
            if (alloc_record(&ref[c], st, m[c].tracked)) return 1;
            if (run(&m[c], &sys[c], href, st->t_end, st->out_dt, &ref[c], &pe, &ee) < 0) {
                fprintf(stderr, "%s %s: the reference failed\n", st->model, names[c]);
                return 1;
            }
        }
        const double gap = distance(&ref[0], &ref[1]);
        if (alloc_record(&rec, st, m[0].tracked)) return 1;
        for (int i = 0; i < 5 && st->h[i] > 0; i++)
            for (int c = 0; c < 2; c++) {
                double best = -1;
                for (int rep = 0; rep < (quick ? 1 : 3); rep++) {
                    const double cpu = run(&m[c], &sys[c], st->h[i], st->t_end, st->out_dt, &rec,
                                           &pe, &ee);
                    if (cpu >= 0 && (best < 0 || cpu < best)) best = cpu;
                }
                const long steps = lround(st->t_end / st->h[i]);
                const double err = best < 0 ? NAN : distance(&rec, &ref[0]);
                printf("%s%s%.0d,%s,%d,%d,%.6g,%ld,%.6g,%.6g,%.3e,%.3e,%.3e,%.3e\n", st->model,
                       st->N ? "-" : "", st->N, names[c], sys[c].n, sys[c].m, st->h[i], steps,
                       best, best / (double)steps * 1e6, err, pe, ee, gap);
                fflush(stdout);
            }
        free(rec.c);
        for (int c = 0; c < 2; c++) {
            free(ref[c].c);
            spatial_model_free(&m[c]);
        }
    }
    return 0;
}
