/* braun run: simulate a model, monitor it, write the CSV and the summary.
 *
 * The simulation runs twice from the same initial state; libbraun is
 * deterministic, so both runs take the same steps. Run 1 has no output
 * callback and is the only one timed: cpu_s is the integration alone.
 * Run 2 samples every step for the metrics and the CSV. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "braun_backends.h"
#include "braun_cli.h"
#include "braun_host.h"

/* What the output callback of run 2 needs. */
typedef struct run_ctx {
    braun_cli_monitor *mon;
    FILE *csv;
    braun_cli_output *csv_out; /* its file, for the errno of a failed write */
    long every;
    int n;
    braun_real t_end;
    long calls;         /* states seen, t = 0 included */
    int last_written;   /* the last stored state has its CSV row */
    int monitor_status; /* non-zero: sampling failed, run stopped */
    double t, *q, *v;   /* last state sampled: the run's final state */
} run_ctx;

static int on_step(const braun_data *d, void *user)
{
    run_ctx *c = (run_ctx *)user;
    int st = braun_cli_monitor_sample(c->mon, d);
    if (st) {
        c->monitor_status = st;
        return 1;
    }
    c->t = (double)d->t;
    for (int i = 0; i < c->n; i++) {
        c->q[i] = (double)d->q[i];
        c->v[i] = (double)d->v[i];
    }
    /* Every K-th state, and the last one so the file ends where the run did. */
    c->last_written = 0;
    if (c->csv && (c->calls % c->every == 0 || d->t >= c->t_end)) {
        if (braun_cli_csv_row(c->csv, c->n, c->t, c->q, c->v, &c->mon->cur, c->mon->has_ref))
            braun_cli_output_failed(c->csv_out);
        c->last_written = 1;
    }
    c->calls++;
    return 0;
}

static int start(braun_data *d, const braun_model *model, const braun_cli_target *tg,
                 void *buf, size_t bytes)
{
    int st = braun_data_init(d, model, buf, bytes);
    if (!st) st = braun_set_state(d, 0, tg->q0, tg->v0);
    return st;
}

static int integrate(braun_data *d, const braun_cli_run_args *a, braun_output_fn out,
                     void *user)
{
    if (a->method == BRAUN_DOPRI5) {
        braun_adaptive ctl = {(braun_real)a->rtol, (braun_real)a->atol, (braun_real)a->dt,
                              0, 0, 0};
        return braun_integrate_adaptive(d, &ctl, (braun_real)a->t_end, 1, out, user);
    }
    return braun_integrate(d, a->method, (braun_real)a->dt, (braun_real)a->t_end, 1, out,
                           user);
}

/* "braun: [<element>: ]<sentence> (<STATUS: meaning>)"; the sentence only
 * when d->error belongs to this failure (early argument checks record
 * nothing); the element of a scene when the guard saw the failing call;
 * for dependent rows that disagree under a --rank-tol, what the tolerance
 * does. */
static void report_failure(const braun_data *d, int st, const braun_cli_guard *guard,
                           const braun_cli_run_args *a)
{
    if (d->error.status == st) {
        char what[256];
        const char *element = guard ? braun_cli_guard_element(guard, d->error.t) : NULL;
        braun_error_format(d, what, sizeof what);
        if (st == BRAUN_ERR_INCONSISTENT && a && a->rank_tol > 0)
            braun_cli_error("%s (%s); with --rank-tol %g, rows whose pivot is below %g times "
                            "the largest count as dependent: a smaller tolerance (or the "
                            "default, 0) may keep them", what, braun_status_str(st),
                            a->rank_tol, a->rank_tol);
        else if (element)
            braun_cli_error("%s: %s (%s)", element, what, braun_status_str(st));
        else
            braun_cli_error("%s (%s)", what, braun_status_str(st));
    } else {
        braun_cli_error("%s", braun_status_str(st));
    }
}

static const char *method_name(unsigned used, unsigned supported)
{
    const unsigned pv = BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY;
    if (used == supported) return "braun";
    if ((used & pv) == pv && !(used & BRAUN_CORRECT_ENERGY)) return "braun-noenergy";
    return "braun-custom";
}

/* The system a run integrates: the target's own (dense), or its scene's
 * sparse system (braun_scene_build_sparse, store in *store) when --sparse
 * asks for it or --backend suitesparse | auto implies it. *none says why
 * the target has no sparsity (NULL if it has one or none was wanted).
 * Returns 0, or an exit status after one message. */
static int choose_system(const braun_cli_run_args *a, const braun_cli_target *tg,
                         braun_system *sys, void **store, const char **none)
{
    const int implied = strcmp(a->backend, "suitesparse") == 0 || strcmp(a->backend, "auto") == 0;
    braun_scene_error err;
    *sys = tg->sys;
    *store = NULL;
    *none = NULL;
    if (!a->sparse && !implied) return 0;
    if (!tg->scene) {
        *none = "a built-in model has no sparsity (scene files without rods have one)";
    } else {
        braun_scene *s = &tg->scene->scene;
        const size_t bytes = braun_scene_sparse_size(s);
        if (bytes == 0) {
            *none = "a scene with rods has no sparsity (a rod couples the mass blocks of its ends)";
        } else if (!(*store = malloc(bytes))) {
            braun_cli_error("out of memory");
            return BRAUN_CLI_FAILED;
        } else {
            const int st = braun_scene_build_sparse(s, sys, *store, bytes, &err);
            if (st) {
                *none = err.what ? err.what : braun_status_str(st);
                free(*store);
                *store = NULL;
                *sys = tg->sys;
            }
        }
    }
    /* Only --sparse insists; the backends fall back to (auto) or refuse
     * (suitesparse, when selected) the dense system. */
    if (*none && a->sparse)
        return braun_cli_error("--sparse: '%s': %s", tg->name, *none);
    return 0;
}

/* The linear solver of --backend for the chosen system. */
static int choose_backend(const braun_cli_run_args *a, const braun_cli_target *tg,
                          braun_model *model, const char *none)
{
    const braun_linsolver *ls = NULL;
    const char *why = NULL;
    if (braun_linsolver_select(a->backend, &model->sys, &ls, &why) != BRAUN_OK) {
        /* Built, but refused for want of a sparsity: say why there is none. */
        if (none && !model->sys.sparsity && braun_linsolver_suitesparse())
            return braun_cli_error("--backend %s: %s; '%s': %s", a->backend,
                                   why ? why : "not available", tg->name, none);
        return braun_cli_error("--backend %s: %s", a->backend, why ? why : "not available");
    }
    model->opt.linsolver = ls;
    return 0;
}

static int run_target(const braun_cli_run_args *a, const braun_cli_target *tg,
                      const braun_model *model);

int braun_cli_run(const braun_cli_run_args *a)
{
    braun_cli_target tg;
    int rc = braun_cli_target_open(a->model, &tg);
    if (rc) return rc;
    braun_system sys;
    void *store; /* the sparse system's pattern and scratch: outlives the run */
    const char *none;
    rc = choose_system(a, &tg, &sys, &store, &none);
    braun_model model;
    if (!rc) {
        /* A scene without rods may be larger than a dense system can be. */
        const int big = sys.n > BRAUN_MAX_DENSE || sys.m > BRAUN_MAX_DENSE ||
                        sys.p > BRAUN_MAX_DENSE;
        int st = braun_model_init(&model, &sys);
        if (st && !sys.sparsity && big) {
            rc = braun_cli_error("'%s' has n = %d, m = %d, p = %d: more than a dense system "
                                 "allows (%d); run it with --sparse", tg.name, sys.n, sys.m,
                                 sys.p, BRAUN_MAX_DENSE);
        } else if (st) {
            braun_cli_error("model '%s' is invalid: %s", tg.name, braun_status_str(st));
            rc = BRAUN_CLI_FAILED;
        } else {
            rc = choose_backend(a, &tg, &model, none);
        }
    }
    if (!rc) rc = run_target(a, &tg, &model);
    free(store);
    braun_cli_target_close(&tg);
    return rc;
}

static int run_target(const braun_cli_run_args *a, const braun_cli_target *tg,
                      const braun_model *model_in)
{
    braun_model model = *model_in;
    int st;
    /* braun_model_init enables every correction the system supports; the
     * target declares its default, the command line may override it. */
    const unsigned supported = model.opt.corrections;
    if (a->corrections_mode == BRAUN_CLI_CORR_LIST) {
        if ((a->corrections & BRAUN_CORRECT_ENERGY) && !(supported & BRAUN_CORRECT_ENERGY))
            return braun_cli_error("model '%s' has no energy law: cannot apply the energy "
                                   "correction", tg->name);
        model.opt.corrections = a->corrections;
    } else if (a->corrections_mode == BRAUN_CLI_CORR_TARGET) {
        model.opt.corrections = tg->corrections & supported;
    }
    model.opt.discretization = a->discretization;
    model.opt.rank_tol = (braun_real)a->rank_tol;
    model.opt.energy_max_rel = (braun_real)a->energy_max_rel;

    const int n = model.sys.n;
    const size_t bytes = braun_data_size(&model);
    /* One block: final state (2n doubles), the run's workspace, the monitor's. */
    double *block = malloc(2 * (size_t)n * sizeof(double) + 2 * bytes);
    if (!block) {
        braun_cli_error("out of memory");
        return BRAUN_CLI_FAILED;
    }
    unsigned char *buf_run = (unsigned char *)(block + 2 * n);
    unsigned char *buf_mon = buf_run + bytes;

    /* Both outputs opened (without blocking, nothing truncated yet), then
     * checked against each other and the scene file, then truncated. */
    braun_cli_output out_summary, out_csv;
    memset(&out_csv, 0, sizeof out_csv);
    int rc = braun_cli_output_open(&out_summary, a->summary_path, "--summary");
    if (!rc && a->out_path) rc = braun_cli_output_open(&out_csv, a->out_path, "--out");
    if (!rc) rc = braun_cli_output_distinct(&out_summary, &out_csv, &tg->id, tg->source);
    if (!rc) rc = braun_cli_output_begin(&out_summary);
    if (!rc) rc = braun_cli_output_begin(&out_csv);
    if (rc) {
        braun_cli_output_abandon(&out_csv);
        braun_cli_output_abandon(&out_summary);
        free(block);
        return rc;
    }
    FILE *csv = out_csv.f, *summary = out_summary.f;

    braun_data d;
    braun_cli_monitor mon;
    braun_cli_guard guard;
    braun_model model2;
    run_ctx ctx;
    const braun_data *failed = &d; /* whose error to report if a start fails */
    int exit_status = 0, st_timed;
    double c0, cpu_s;
    braun_stats timed_stats;
    /* Released on every path (a backend's state; nothing for the built-in
     * kernels): zeroed so that releasing one never initialised is a no-op. */
    memset(&d, 0, sizeof d);
    memset(&mon, 0, sizeof mon);
    memset(&guard, 0, sizeof guard);

    /* Run 1: timed, no callback. */
    st = start(&d, &model, tg, buf_run, bytes);
    if (st) goto init_failed;
    c0 = braun_cli_cpu_seconds();
    st_timed = integrate(&d, a, NULL, NULL);
    cpu_s = braun_cli_cpu_seconds() - c0;
    timed_stats = d.stats;

    /* Run 2: the same steps, monitored (a fresh backend state, too), a
     * scene's callbacks through the guard that names a failing element. */
    braun_data_release(&d);
    braun_cli_guard_wrap(&guard, &model.sys, tg->scene, &model2.sys);
    model2.opt = model.opt;
    st = start(&d, &model2, tg, buf_run, bytes);
    if (st) goto init_failed;
    failed = &mon.scratch;
    st = braun_cli_monitor_init(&mon, &model2, tg->reference, a->ref_h, buf_mon, bytes);
    if (st) goto init_failed;
    ctx.mon = &mon;
    ctx.csv = csv;
    ctx.csv_out = &out_csv;
    ctx.every = a->every;
    ctx.n = n;
    ctx.t_end = (braun_real)a->t_end;
    ctx.calls = 0;
    ctx.last_written = 1;
    ctx.monitor_status = 0;
    ctx.q = block;
    ctx.v = block + n;
    ctx.t = (double)d.t;
    for (int i = 0; i < n; i++) {
        ctx.q[i] = (double)d.q[i];
        ctx.v[i] = (double)d.v[i];
    }
    if (csv) braun_cli_csv_header(csv, n);
    st = integrate(&d, a, on_step, &ctx);
    /* A failed step leaves the last good state unwritten when K > 1. */
    if (csv && !ctx.last_written)
        braun_cli_csv_row(csv, n, ctx.t, ctx.q, ctx.v, &mon.cur, mon.has_ref);

    if (ctx.monitor_status) {
        char what[256] = "reference evaluation failed";
        if (mon.scratch.error.status == ctx.monitor_status)
            braun_error_format(&mon.scratch, what, sizeof what);
        braun_cli_error("monitoring failed after t = %.10g: %s", ctx.t, what);
        exit_status = BRAUN_CLI_FAILED;
    } else if (st) {
        report_failure(&d, st, &guard, a);
        exit_status = BRAUN_CLI_FAILED;
    }
    if (!ctx.monitor_status &&
        (st_timed != st || timed_stats.steps != d.stats.steps ||
         timed_stats.rhs_evals != d.stats.rhs_evals))
        braun_cli_error("warning: the timed run (%s, %ld steps) differs from the monitored "
                        "run (%ld steps); cpu_s may not match", braun_status_str(st_timed),
                        timed_stats.steps, d.stats.steps);

    braun_cli_result r;
    r.args = a;
    r.model = &model;
    r.scene = tg->name;
    r.method = method_name(model.opt.corrections, supported);
    r.stats = d.stats;
    r.cpu_s = cpu_s;
    r.mon = &mon;
    r.backend = braun_linsolver_name(model.opt.linsolver);
    r.sparse = model.sys.sparsity != NULL;
    r.final_t = ctx.t;
    r.final_q = ctx.q;
    r.final_v = ctx.v;
    r.status = st;
    if (braun_cli_write_summary(summary, &r)) braun_cli_output_failed(&out_summary);
    if (braun_cli_output_close(&out_summary)) exit_status = BRAUN_CLI_FAILED;
    if (braun_cli_output_close(&out_csv)) exit_status = BRAUN_CLI_FAILED;
    braun_data_release(&mon.scratch);
    braun_data_release(&d);
    free(block);
    return exit_status;

init_failed:
    /* Nothing was integrated: no summary to speak of. */
    report_failure(failed, st, NULL, a);
    braun_data_release(&mon.scratch);
    braun_data_release(&d);
    braun_cli_output_close(&out_csv);
    braun_cli_output_close(&out_summary);
    free(block);
    return BRAUN_CLI_FAILED;
}
