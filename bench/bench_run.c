/* The measured work of one target: a workspace per configuration, blocks of
 * steps or right-hand sides from fixed states. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "braun_reference.h"

struct bench_run {
    const bench_target *tg;
    long steps;
    int has[BENCH_ITEMS];
    braun_system free_sys;         /* same bodies, no constraint rows */
    braun_model model[BENCH_ITEMS];
    braun_data data[BENCH_ITEMS];
    void *buf[BENCH_ITEMS];
    /* States at which the right-hand sides are evaluated: the start of
     * every step of the fully corrected run (t, q, v, ∫Ė), recorded on
     * first use so that a count of the step items never runs it. */
    braun_real *rec;
    int rec_done;
    braun_real *qdot, *vdot;
    /* Floor: state, and recorded states for its right-hand side. */
    double t, y[4];
    double *yrec;
    int yrec_done;
    double dydt[4];
    /* The specialised floor: its state, and how far its trajectory ended
     * from the library's ideal step over one block (bench_special_agreement). */
    double ysp[12];
    double special_dev;
};

/* Which workspace an item uses (the right-hand sides have their own). */
static int uses_data(bench_item it)
{
    return it != BENCH_STEP_FLOOR && it != BENCH_RHS_FLOOR && it != BENCH_STEP_SPECIAL;
}

/* The specialised floor exists for the built-in slider-crank in a double
 * build (bench_special.c writes that model out). */
static int special_applies(const bench_target *tg)
{
#ifdef BRAUN_SINGLE
    (void)tg;
    return 0;
#else
    return strcmp(tg->source, "built-in") == 0 &&
           strcmp(tg->name, "slider-crank") == 0 && tg->sys.n == 6 && tg->sys.m == 5 &&
           tg->sys.p == 0;
#endif
}

static void special_start(bench_run *r)
{
    for (int i = 0; i < 6; i++) {
        r->ysp[i] = (double)r->tg->q0[i];
        r->ysp[6 + i] = (double)r->tg->v0[i];
    }
}

/* One block of the specialised step against one of the library's ideal
 * step from the same start: the largest difference of q and v at the end,
 * relative to the largest entry. A floor that does not simulate the same
 * motion is no floor: bench_run_new drops it above 1e-9. */
static double special_agreement(bench_run *r)
{
    braun_data *d = &r->data[BENCH_STEP_NONE];
    const braun_link_params *p = (const braun_link_params *)r->tg->sys.user;
    const double h = r->tg->h;
    special_start(r);
    if (braun_set_state(d, 0, r->tg->q0, r->tg->v0)) return INFINITY;
    for (long s = 0; s < r->steps; s++) {
        bench_special_step(p, h, r->ysp);
        if (braun_step(d, BRAUN_RK4, (braun_real)h)) return INFINITY;
    }
    double dev = 0, big = 0;
    for (int i = 0; i < 6; i++) {
        const double e[2] = {r->ysp[i] - (double)d->q[i], r->ysp[6 + i] - (double)d->v[i]};
        for (int j = 0; j < 2; j++)
            if (!(fabs(e[j]) <= dev)) dev = fabs(e[j]); /* NaN too */
        if (fabs((double)d->q[i]) > big) big = fabs((double)d->q[i]);
        if (fabs((double)d->v[i]) > big) big = fabs((double)d->v[i]);
    }
    return dev / (big > 1 ? big : 1);
}

bench_run *bench_run_new(const bench_target *tg, long steps, char *err, size_t errsize)
{
    const int n = tg->sys.n;
    bench_run *r = calloc(1, sizeof *r);
    if (!r) goto oom;
    r->tg = tg;
    r->steps = steps;
    r->free_sys = tg->sys;
    r->free_sys.m = r->free_sys.p = 0;
    r->free_sys.holonomic = NULL;
    r->free_sys.nonholonomic = NULL;
    /* no rows: no constraint work */
    r->free_sys.flags = (r->free_sys.flags & ~(unsigned)BRAUN_CONSTRAINT_WORK) | BRAUN_SCLERONOMIC;
    for (int i = 0; i < BENCH_ITEMS; i++) {
        bench_item it = (bench_item)i;
        r->has[i] = it == BENCH_STEP_SPECIAL ? special_applies(tg)
                                             : uses_data(it) || tg->minimal != NULL;
        if (!uses_data(it)) continue;
        const braun_system *sys = it == BENCH_STEP_FREE ? &r->free_sys : &tg->sys;
        int st = braun_model_init(&r->model[i], sys);
        if (st && it == BENCH_STEP_FREE) {
            /* A build with compile-time sizes (BRAUN_FIXED_N/ROWS) refuses
             * m = p = 0: no free baseline there. */
            r->has[i] = 0;
            continue;
        }
        if (st) {
            snprintf(err, errsize, "%s: braun_model_init: %s", tg->name, braun_status_str(st));
            bench_run_free(r);
            return NULL;
        }
        r->model[i].opt.corrections = it == BENCH_STEP_FREE ? 0u : bench_item_corrections(tg, it);
        size_t bytes = braun_data_size(&r->model[i]);
        r->buf[i] = malloc(bytes);
        if (!r->buf[i]) goto oom;
        st = braun_data_init(&r->data[i], &r->model[i], r->buf[i], bytes);
        if (!st) st = braun_set_state(&r->data[i], 0, tg->q0, tg->v0);
        if (st) {
            snprintf(err, errsize, "%s: %s: %s", tg->name, bench_item_name(it),
                     braun_status_str(st));
            bench_run_free(r);
            return NULL;
        }
    }
    r->rec = malloc((size_t)steps * (size_t)(2 * n + 2) * sizeof *r->rec);
    r->qdot = malloc(2 * (size_t)n * sizeof *r->qdot);
    r->yrec = malloc((size_t)steps * 3 * sizeof *r->yrec);
    if (!r->rec || !r->qdot || !r->yrec) goto oom;
    r->vdot = r->qdot + n;
    r->special_dev = NAN;
    if (r->has[BENCH_STEP_SPECIAL]) {
        r->special_dev = special_agreement(r);
        if (!(r->special_dev <= 1e-9)) {
            fprintf(stderr, "braun-bench: %s: step-special ends %g from step-none after %ld steps: "
                            "not the same motion, not timed\n", tg->name, r->special_dev, steps);
            r->has[BENCH_STEP_SPECIAL] = 0;
        }
    }
    return r;
oom:
    snprintf(err, errsize, "out of memory");
    bench_run_free(r);
    return NULL;
}

void bench_run_free(bench_run *r)
{
    if (!r) return;
    for (int i = 0; i < BENCH_ITEMS; i++) free(r->buf[i]);
    free(r->rec);
    free(r->qdot);
    free(r->yrec);
    free(r);
}

double bench_run_special_agreement(const bench_run *r)
{
    return r->special_dev;
}

int bench_run_has(const bench_run *r, bench_item it)
{
    return (unsigned)it < BENCH_ITEMS && r->has[it];
}

/* The corrected run's states, one per step start. */
static void record_states(bench_run *r)
{
    const int n = r->tg->sys.n, w = 2 * n + 2;
    braun_data *d = &r->data[BENCH_STEP_ALL];
    braun_set_state(d, 0, r->tg->q0, r->tg->v0);
    for (long s = 0; s < r->steps; s++) {
        braun_real *x = r->rec + (size_t)s * (size_t)w;
        x[0] = d->t;
        memcpy(x + 1, d->q, (size_t)n * sizeof *x);
        memcpy(x + 1 + n, d->v, (size_t)n * sizeof *x);
        x[1 + 2 * n] = d->work_in;
        /* A failed step leaves the state: later records repeat it. */
        (void)braun_step(d, BRAUN_RK4, (braun_real)r->tg->h);
    }
    r->rec_done = 1;
}

static void floor_start(bench_run *r)
{
    const braun_builtin *b = r->tg->minimal;
    r->t = 0;
    for (int i = 0; i < braun_minimal_find(b->name)->dim; i++) r->y[i] = braun_minimal_find(b->name)->y0[i];
}

static void record_floor(bench_run *r)
{
    floor_start(r);
    for (long s = 0; s < r->steps; s++) {
        double *x = r->yrec + (size_t)s * 3;
        x[0] = r->t;
        x[1] = r->y[0];
        x[2] = r->y[1];
        bench_floor_step(r->tg->minimal, r->t, r->tg->h, r->y);
        r->t = (double)(s + 1) * r->tg->h;
    }
    r->yrec_done = 1;
}

void bench_run_reset(bench_run *r, bench_item it)
{
    if (!bench_run_has(r, it)) return;
    switch (it) {
    case BENCH_STEP_FLOOR: floor_start(r); break;
    case BENCH_STEP_SPECIAL: special_start(r); break;
    case BENCH_RHS_FLOOR:
        if (!r->yrec_done) record_floor(r);
        break;
    case BENCH_RHS_IDEAL:
    case BENCH_RHS_CORR:
        if (!r->rec_done) record_states(r);
        break;
    default: braun_set_state(&r->data[it], 0, r->tg->q0, r->tg->v0); break;
    }
}

/* callgrind counts the instructions of this function and its callees
 * (--toggle-collect=bench_run_block): it must stay a function even when the
 * library is built with -flto. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
long bench_run_block(bench_run *r, bench_item it, int *status)
{
    const bench_target *tg = r->tg;
    const braun_real h = (braun_real)tg->h;
    const int n = tg->sys.n, w = 2 * n + 2;
    *status = 0;
    if (!bench_run_has(r, it)) return 0;
    switch (it) {
    case BENCH_STEP_FLOOR:
        for (long s = 0; s < r->steps; s++) {
            bench_floor_step(tg->minimal, r->t, tg->h, r->y);
            r->t = (double)(s + 1) * tg->h;
        }
        return r->steps;
    case BENCH_STEP_SPECIAL: {
        const braun_link_params *p = (const braun_link_params *)tg->sys.user;
        for (long s = 0; s < r->steps; s++) bench_special_step(p, tg->h, r->ysp);
        return r->steps;
    }
    case BENCH_RHS_FLOOR:
        for (long s = 0; s < r->steps; s++) {
            const double *x = r->yrec + (size_t)s * 3;
            bench_floor_rhs(tg->minimal, x[0], x + 1, r->dydt);
        }
        return r->steps;
    case BENCH_RHS_IDEAL:
    case BENCH_RHS_CORR: {
        braun_data *d = &r->data[it];
        for (long s = 0; s < r->steps; s++) {
            const braun_real *x = r->rec + (size_t)s * (size_t)w;
            d->work_in = x[1 + 2 * n];
            int st = braun_eval(d, x[0], x + 1, x + 1 + n, h, r->qdot, r->vdot);
            if (st) {
                *status = st;
                return s;
            }
        }
        return r->steps;
    }
    default: {
        braun_data *d = &r->data[it];
        for (long s = 0; s < r->steps; s++) {
            int st = braun_step(d, BRAUN_RK4, h);
            if (st) {
                *status = st;
                return s;
            }
        }
        return r->steps;
    }
    }
}
