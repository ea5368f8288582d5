/* braun run: simulate a model, monitor it, write the CSV and the summary.
 *
 * The simulation runs twice from the same initial state; libbraun is
 * deterministic, so both runs take the same steps. Run 1 has no output
 * callback and is the only one timed: cpu_s is the integration alone.
 * Run 2 samples every step for the metrics and the CSV. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "braun_backends.h"
#include "braun_cli.h"
#include "braun_host.h"

/* One state of the monitored run with its errors; index: its place among
 * the states the run reported (t0 is 0), for --every. */
typedef struct run_state {
    double t, *q, *v;
    braun_cli_errors e;
    long index;
    long steps; /* the run's steps up to it (d->stats.steps when reported) */
} run_state;

/* What the output callback of the monitored run needs. The drivers report
 * a state only once it has passed the accuracy guard (the next step's
 * start, or the final check), so every state seen here is one the run
 * keeps: the CSV, the maxima and a plot never see a state the guard
 * refused, and the last one seen is the final state. */
typedef struct run_ctx {
    braun_cli_monitor *mon;
    const braun_cli_target *tg; /* its scene's reported points */
    FILE *csv;
    braun_cli_output *csv_out; /* its file, for the errno of a failed write */
    long every;
    int n;
    const braun_cli_observer *obs;
    braun_cli_progress *progress;
    long calls;         /* states reported, t = t0 included */
    int have_good;
    run_state good;     /* the last state reported */
    int good_written;   /* good has its CSV row */
    int monitor_status; /* non-zero: sampling failed, run stopped */
    double failed_t;    /* the time of the state it failed on */
} run_ctx;

static void write_good(run_ctx *c)
{
    if (braun_cli_csv_row(c->csv, c->tg, c->n, c->good.t, c->good.q, c->good.v, &c->good.e,
                          c->mon->has_ref))
        braun_cli_output_failed(c->csv_out);
    c->good_written = 1;
}

static int on_step(const braun_data *d, void *user)
{
    run_ctx *c = (run_ctx *)user;
    int st = braun_cli_monitor_measure(c->mon, d, &c->good.e);
    if (st) {
        c->monitor_status = st;
        c->failed_t = (double)d->t;
        return 1;
    }
    c->good.t = (double)d->t;
    c->good.steps = d->stats.steps;
    for (int i = 0; i < c->n; i++) {
        c->good.q[i] = (double)d->q[i];
        c->good.v[i] = (double)d->v[i];
    }
    c->good.index = c->calls++;
    c->have_good = 1;
    braun_cli_monitor_accept(c->mon, &c->good.e);
    c->good_written = 0;
    if (c->csv && c->good.index % c->every == 0) write_good(c);
    if (c->obs && c->obs->state)
        c->obs->state(c->obs->user, c->good.t, c->good.q, c->good.v, &c->good.e);
    braun_cli_progress_update(c->progress, (double)d->t, d->stats.steps);
    /* Interrupted: this state is the last one kept (BRAUN_STOPPED). */
    return braun_cli_interrupted() != 0;
}

/* The timed run's only callback, every few steps: the progress line and
 * an interruption. */
static int on_timed(const braun_data *d, void *user)
{
    braun_cli_progress_update((braun_cli_progress *)user, (double)d->t, d->stats.steps);
    return braun_cli_interrupted() != 0;
}

static int start(braun_data *d, const braun_model *model, const braun_cli_target *tg,
                 void *buf, size_t bytes)
{
    int st = braun_data_init(d, model, buf, bytes);
    if (!st) st = braun_set_state(d, 0, tg->q0, tg->v0);
    return st;
}

static int integrate(braun_data *d, const braun_cli_run_args *a, long every,
                     braun_output_fn out, void *user)
{
    if (a->method == BRAUN_DOPRI5) {
        braun_adaptive ctl = {(braun_real)a->rtol, (braun_real)a->atol, (braun_real)a->dt,
                              0, 0, a->max_steps};
        return braun_integrate_adaptive(d, &ctl, (braun_real)a->t_end, every, out, user);
    }
    return braun_integrate(d, a->method, (braun_real)a->dt, (braun_real)a->t_end, every, out,
                           user);
}

/* For rows that disagree (BRAUN_ERR_INCONSISTENT: d->error.index and
 * index2, -1 when the core does not know them), the elements of the scene
 * that own them: "; row 0 is joint 'left' (revolute), row 2 is joint
 * 'right' (revolute)"; "" without a scene or rows. */
static const char *disagreeing_rows(const braun_data *d, const braun_cli_target *tg, char *buf,
                                    size_t size)
{
    char a[160], b[160];
    const int i = d->error.index, j = d->error.index2;
    const braun_scene_file *sf = tg ? tg->scene : NULL;
    const char *oa = braun_cli_row_owner(sf, i, a, sizeof a);
    const char *ob = j != i ? braun_cli_row_owner(sf, j, b, sizeof b) : NULL;
    buf[0] = '\0';
    if (oa && ob) snprintf(buf, size, "; row %d is %s, row %d is %s", i, oa, j, ob);
    else if (oa || ob) snprintf(buf, size, "; row %d is %s", oa ? i : j, oa ? oa : ob);
    return buf;
}

/* For the accuracy guard's position or velocity residual: the element that
 * owns its largest row (d->error.index), "; its largest row, 5, is joint
 * 'far' (distance)", and for a refusal a start off its position
 * constraints caused, the element of the start's largest position row
 * (d->error.index2), "; the start's largest position error is row 2, joint
 * 'drive' (revolute3d)"; "" without a scene. */
static const char *largest_row(const braun_data *d, const braun_cli_target *tg, char *buf, size_t size)
{
    char a[160], b[160];
    const char *owner = braun_cli_row_owner(tg ? tg->scene : NULL, d->error.index, a, sizeof a);
    const char *off_row = d->error.index2 >= 0
                              ? braun_cli_row_owner(tg ? tg->scene : NULL, d->error.index2, b, sizeof b)
                              : NULL;
    buf[0] = '\0';
    if (owner && off_row)
        snprintf(buf, size, "; its largest row, %d, is %s; the start's largest position error is row %d, %s",
                 d->error.index, owner, d->error.index2, off_row);
    else if (owner)
        snprintf(buf, size, "; its largest row, %d, is %s", d->error.index, owner);
    return buf;
}

/* "braun: [<element>: ]<sentence> (<STATUS: meaning>)"; the sentence only
 * when d->error belongs to this failure (early argument checks record
 * nothing); the element of a scene when the guard saw the failing call;
 * for dependent rows that disagree, the joints they belong to, and under a
 * --rank-tol what the tolerance does. */
static void report_failure(const braun_data *d, int st, const braun_cli_guard *guard,
                           const braun_cli_run_args *a, const braun_cli_target *tg)
{
    if (d->error.status == st) {
        char what[512], rows[400];
        const char *element = guard ? braun_cli_guard_element(guard, d->error.t) : NULL;
        braun_error_format(d, what, sizeof what);
        /* The rows that disagree, or the row whose residual the guard
         * refused (its largest). */
        const char *owners = st == BRAUN_ERR_INCONSISTENT ? disagreeing_rows(d, tg, rows, sizeof rows)
                             : st == BRAUN_ERR_ACCURACY && d->error.index >= 0
                                 ? largest_row(d, tg, rows, sizeof rows)
                                 : "";
        if (st == BRAUN_ERR_INCONSISTENT && a && a->rank_tol > 0)
            braun_cli_error("%s%s (%s); with --rank-tol %g, rows whose pivot is below %g times "
                            "the largest count as dependent: a smaller tolerance (or the "
                            "default, 0) may keep them", what, owners, braun_status_str(st),
                            a->rank_tol, a->rank_tol);
        else if (element && st != BRAUN_ERR_INCONSISTENT)
            braun_cli_error("%s: %s%s (%s)", element, what, owners, braun_status_str(st));
        else
            braun_cli_error("%s%s (%s)", what, owners, braun_status_str(st));
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

static int run_model(const braun_cli_run_args *a, const braun_cli_target *tg,
                     const braun_model *model, const braun_cli_observer *obs);

int braun_cli_run_target(const braun_cli_run_args *a, const braun_cli_target *tg,
                         const braun_cli_observer *obs)
{
    braun_system sys;
    void *store; /* the sparse system's pattern and scratch: outlives the run */
    const char *none;
    int rc = choose_system(a, tg, &sys, &store, &none);
    braun_model model;
    if (!rc) {
        /* A scene without rods may be larger than a dense system can be. */
        const int big = sys.n > BRAUN_MAX_DENSE || sys.m > BRAUN_MAX_DENSE ||
                        sys.p > BRAUN_MAX_DENSE;
        int st = braun_model_init(&model, &sys);
        /* The dense kernels named for a system beyond them: the one line
         * below (which names the backend that runs it), not the selection's. */
        const int dense_named = strcmp(a->backend, "dense") == 0 || strcmp(a->backend, "lapack") == 0;
        if (!st && !(big && dense_named)) rc = choose_backend(a, tg, &model, none);
        if ((st || (!rc && (!model.opt.linsolver ||
                               model.opt.linsolver != braun_linsolver_suitesparse()))) &&
            big) {
            /* Only SuiteSparse goes beyond: the core's own kernels stop there
             * with --sparse too, and LAPACK's (they gave
             * "invalid sizes" at the data's initialisation, exit 1). */
            rc = braun_cli_error("'%s' has n = %d, m = %d, p = %d: more than a dense system "
                                 "allows (%d); run it with --backend suitesparse (or auto)",
                                 tg->name, sys.n, sys.m, sys.p, BRAUN_MAX_DENSE);
        } else if (st) {
            braun_cli_error("model '%s' is invalid: %s", tg->name, braun_status_str(st));
            rc = BRAUN_CLI_FAILED;
        } else {
            if (!rc && !model.opt.linsolver && sys.n >= BRAUN_CLI_DENSE_NOTE_N)
                fprintf(stderr, "braun: note: '%s' has n = %d on the dense kernels: O(n^3) per step%s\n",
                        tg->name, sys.n,
                        tg->scene && braun_scene_sparse_size(&tg->scene->scene) > 0 && braun_linsolver_suitesparse()
                            ? "; --sparse --backend suitesparse takes O(n)"
                            : "");
        }
    }
    if (!rc) {
        braun_cli_interrupt_begin();
        rc = run_model(a, tg, &model, obs);
        braun_cli_interrupt_end();
    }
    free(store);
    return rc;
}

int braun_cli_run(const braun_cli_run_args *a)
{
    braun_cli_target tg;
    int rc = braun_cli_target_open(a->model, &tg);
    if (rc) return rc;
    rc = braun_cli_run_target(a, &tg, NULL);
    braun_cli_target_close(&tg);
    return rc;
}

/* Progress and interruption every this many steps of the timed run: a
 * clock read per 64 steps (each of at least a microsecond) costs well
 * under 0.1 %. */
#define TIMED_PROGRESS_EVERY 64

/* A run that ends before its monitored run writes: the outputs it
 * created are removed, files that existed stay as they were. rc back. */
static int give_up(braun_cli_output *csv, braun_cli_output *summary, double *block, int rc)
{
    braun_cli_output_abandon(csv);
    braun_cli_output_abandon(summary);
    free(block);
    return rc;
}

static int run_model(const braun_cli_run_args *a, const braun_cli_target *tg,
                     const braun_model *model_in, const braun_cli_observer *obs)
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
    model.opt.guard = (braun_real)a->guard;
    model.opt.soft_tol = (braun_real)a->soft_tol;

    const int n = model.sys.n;
    const size_t bytes = braun_data_size(&model);
    /* One block: the last state (2n doubles), the run's workspace, the
     * monitor's. */
    double *block = malloc(2 * (size_t)n * sizeof(double) + 2 * bytes);
    if (!block) {
        braun_cli_error("out of memory");
        return BRAUN_CLI_FAILED;
    }
    unsigned char *buf_run = (unsigned char *)(block + 2 * n);
    unsigned char *buf_mon = buf_run + bytes;

    /* Both outputs opened (without blocking, nothing truncated yet), then
     * checked against each other and the scene file; truncated when the
     * monitored run begins (an interrupted timing run leaves a file that
     * existed as it was: it was left empty). */
    braun_cli_output out_summary, out_csv;
    memset(&out_csv, 0, sizeof out_csv);
    memset(&out_summary, 0, sizeof out_summary);
    int rc = 0;
    if (a->summary_path) rc = braun_cli_output_open(&out_summary, a->summary_path, "--summary");
    if (!rc && a->out_path) rc = braun_cli_output_open(&out_csv, a->out_path, "--out");
    if (!rc) rc = braun_cli_output_distinct(&out_summary, &out_csv, &tg->id, tg->source);
    if (!rc) rc = braun_cli_output_distinct(&out_summary, a->plot_output, NULL, NULL);
    if (!rc) rc = braun_cli_output_distinct(&out_csv, a->plot_output, NULL, NULL);
    /* A fixed-step run's CSV has a row every --every steps (1 by default):
     * 1e8 steps of a small scene are gigabytes, written without a word
     * before. Said once, above 1 GB (about 20 bytes a number). */
    if (!rc && a->out_path && a->method != BRAUN_DOPRI5 && a->every > 0) {
        const double rows = braun_cli_fixed_steps(a->dt, a->t_end) / (double)a->every + 1;
        const double gb = rows * braun_cli_csv_column_count(tg, n) * 20 / 1e9;
        if (gb > 1)
            fprintf(stderr, "braun: note: --out will hold about %.3g rows, some %.0f GB: --every N "
                            "writes every N-th step\n", rows, gb);
    }
    if (rc) return give_up(&out_csv, &out_summary, block, rc);
    FILE *csv = out_csv.f, *summary = out_summary.f;

    braun_data d;
    braun_cli_monitor mon;
    braun_cli_guard guard;
    braun_cli_progress progress;
    braun_model model2;
    run_ctx ctx;
    const braun_data *failed = &d; /* whose error to report if a start fails */
    int exit_status = 0, st_timed = BRAUN_OK, timed = a->timing;
    double c0, cpu_s = NAN, cpu_monitored;
    braun_stats timed_stats;
    memset(&timed_stats, 0, sizeof timed_stats);
    /* Released on every path (a backend's state; nothing for the built-in
     * kernels): zeroed so that releasing one never initialised is a no-op. */
    memset(&d, 0, sizeof d);
    memset(&mon, 0, sizeof mon);
    memset(&guard, 0, sizeof guard);
    const int show = a->progress > 0 || (a->progress < 0 && braun_cli_stderr_is_terminal());

    /* Run 1: timed, no monitoring (the progress line, when shown, reads the
     * clock every 64 steps). */
    if (timed) {
        st = start(&d, &model, tg, buf_run, bytes);
        if (st) goto init_failed;
        braun_cli_progress_begin(&progress, show, tg->name, "run 1 of 2: timing, no monitoring",
                                 (double)d.t, a->t_end);
        c0 = braun_cli_cpu_seconds();
        st_timed = integrate(&d, a, TIMED_PROGRESS_EVERY, on_timed, &progress);
        cpu_s = braun_cli_cpu_seconds() - c0;
        braun_cli_progress_end(&progress, (double)d.t, d.stats.steps);
        timed_stats = d.stats;
        const int sig = st_timed == BRAUN_STOPPED ? braun_cli_interrupted() : 0;
        if (sig) {
            /* Run 1 writes nothing: the files stay as they were begun. */
            braun_cli_error("interrupted by %s during the timing run (run 1 of 2) at t = %.10g: "
                            "nothing integrated is kept (the monitored run writes --out and "
                            "--summary; 'braun plot' runs without the timing run)",
                            braun_cli_signal_name(sig), (double)d.t);
            braun_data_release(&d);
            return give_up(&out_csv, &out_summary, block, 128 + sig);
        }
        braun_data_release(&d);
    }

    rc = braun_cli_output_begin(&out_summary);
    if (!rc) rc = braun_cli_output_begin(&out_csv);
    if (rc) return give_up(&out_csv, &out_summary, block, rc);
    /* Run 2: the same steps, monitored (a fresh backend state, too), a
     * scene's callbacks through the guard that names a failing element. */
    braun_cli_guard_wrap(&guard, &model.sys, tg->scene, &model2.sys);
    model2.opt = model.opt;
    st = start(&d, &model2, tg, buf_run, bytes);
    if (st) goto init_failed;
    failed = &mon.scratch;
    /* The reference's default substep, 1e-4 s, finer than a fixed step as
     * an explicit --ref-h must be: dt/10 below 1e-3 (--dt 1e-5 ran against
     * a reference at the run's own step, which --ref-h 1e-4 is refused for). */
    const double ref_h = a->ref_h > 0 ? a->ref_h
                         : a->method != BRAUN_DOPRI5 && a->dt < 1e-3 ? a->dt / 10
                                                                     : 0; /* the reference's 1e-4 */
    st = braun_cli_monitor_init(&mon, &model2, tg->reference, ref_h, buf_mon, bytes);
    if (st) goto init_failed;
    memset(&ctx, 0, sizeof ctx);
    ctx.mon = &mon;
    ctx.tg = tg;
    ctx.csv = csv;
    ctx.csv_out = &out_csv;
    ctx.every = a->every;
    ctx.n = n;
    ctx.obs = obs;
    ctx.progress = &progress;
    ctx.good.q = block;
    ctx.good.v = block + n;
    if (csv && braun_cli_csv_header(csv, tg, n)) braun_cli_output_failed(&out_csv);
    braun_cli_progress_begin(&progress, show, tg->name,
                             timed ? "run 2 of 2: monitoring" : "monitoring", (double)d.t,
                             a->t_end);
    c0 = braun_cli_cpu_seconds();
    st = integrate(&d, a, 1, on_step, &ctx);
    braun_cli_stop stop;
    memset(&stop, 0, sizeof stop);
    braun_cli_guard_bounds(&d, &stop.bounds);
    /* A state the guard refused was never reported: the run keeps the one
     * before it. */
    if (st == BRAUN_ERR_ACCURACY && d.error.status == st) {
        stop.dropped = 1;
        stop.dropped_t = d.error.t;
    }
    cpu_monitored = braun_cli_cpu_seconds() - c0;
    braun_cli_progress_end(&progress, ctx.have_good ? ctx.good.t : (double)d.t,
                           ctx.monitor_status && ctx.have_good ? ctx.good.steps : d.stats.steps);
    /* The file ends where the run did: the last state that passed. */
    if (csv && ctx.have_good && !ctx.good_written) write_good(&ctx);

    if (ctx.monitor_status) {
        char what[256] = "reference evaluation failed";
        if (mon.scratch.error.status == ctx.monitor_status)
            braun_error_format(&mon.scratch, what, sizeof what);
        /* Like every failure line, it names the status (the monitor's). */
        braun_cli_error("monitoring failed after t = %.10g: %s (%s)",
                        ctx.have_good ? ctx.good.t : (double)d.t, what,
                        braun_status_str(ctx.monitor_status));
        exit_status = BRAUN_CLI_FAILED;
    } else if (st == BRAUN_STOPPED && braun_cli_interrupted()) {
        const int sig = braun_cli_interrupted(); /* the same test as `interrupted` below */
        braun_cli_error("interrupted by %s at t = %.10g: the run stopped there; %s", braun_cli_signal_name(sig),
                        ctx.have_good ? ctx.good.t : (double)d.t,
                        a->plot_output ? (summary ? "the picture is drawn up to that state "
                                                    "(--summary: status BRAUN_STOPPED)"
                                                  : "the picture is drawn up to that state")
                        : csv || summary ? "what it wrote ends at that state (--summary: status "
                                           "BRAUN_STOPPED)"
                                         : "nothing was written");
        exit_status = 128 + sig;
    } else if (st) {
        report_failure(&d, st, &guard, a, tg);
        exit_status = BRAUN_CLI_FAILED;
    }
    const int interrupted = st == BRAUN_STOPPED && !ctx.monitor_status && braun_cli_interrupted();
    if (interrupted) cpu_s = NAN; /* run 1 went further than run 2's stats */
    if (timed && !ctx.monitor_status && !interrupted &&
        (st_timed != st || timed_stats.steps != d.stats.steps ||
         timed_stats.rhs_evals != d.stats.rhs_evals))
        braun_cli_error("warning: the timed run (%s, %ld steps) differs from the monitored "
                        "run (%ld steps); cpu_s may not match", braun_status_str(st_timed),
                        timed_stats.steps, d.stats.steps);

    braun_cli_result r;
    memset(&r, 0, sizeof r);
    r.args = a;
    r.target = tg;
    r.model = &model;
    r.scene = tg->name;
    r.method = method_name(model.opt.corrections, supported);
    r.stats = d.stats;
    /* A state the monitoring failed on is not kept (the file and final_*
     * end before it): nor is its step. The other counters keep the work
     * done, its step's included, as a failing step's are. */
    if (ctx.monitor_status) r.stats.steps = ctx.have_good ? ctx.good.steps : 0;
    r.cpu_s = cpu_s;
    r.interrupted = interrupted ? braun_cli_interrupted() : 0;
    r.cpu_monitored_s = cpu_monitored;
    r.mon = &mon;
    r.backend = braun_linsolver_name(model.opt.linsolver);
    r.sparse = model.sys.sparsity != NULL;
    r.final_t = ctx.have_good ? ctx.good.t : (double)d.t;
    if (ctx.have_good) {
        r.final_q = ctx.good.q;
        r.final_v = ctx.good.v;
    } else {
        /* No state passed the monitor (it failed at t0): the initial one. */
        for (int i = 0; i < n; i++) {
            ctx.good.q[i] = (double)tg->q0[i];
            ctx.good.v[i] = (double)tg->v0[i];
        }
        r.final_q = ctx.good.q;
        r.final_v = ctx.good.v;
    }
    /* A failure of the monitoring (the state's energy +Inf: a run without
     * corrections overflowing) is the run's status: it read BRAUN_STOPPED,
     * which says a signal or callback stopped it. */
    r.status = ctx.monitor_status ? ctx.monitor_status : st;
    r.stop = stop;
    /* The monitoring's failure: the time of the state it failed on (the
     * stderr line's "at t = ..."), after final_t. */
    r.error_t = ctx.monitor_status ? ctx.failed_t : st && d.error.status == st ? d.error.t : NAN;
    if (summary && braun_cli_write_summary(summary, &r)) braun_cli_output_failed(&out_summary);
    if (show) braun_cli_write_human(stderr, &r);
    if (braun_cli_output_close(&out_summary)) exit_status = BRAUN_CLI_FAILED;
    if (braun_cli_output_close(&out_csv)) exit_status = BRAUN_CLI_FAILED;
    if (obs && obs->done && obs->done(obs->user, &r)) exit_status = BRAUN_CLI_FAILED;
    braun_data_release(&mon.scratch);
    braun_data_release(&d);
    free(block);
    return exit_status;

init_failed:
    /* Nothing was integrated: no summary to speak of. */
    report_failure(failed, st, NULL, a, tg);
    braun_data_release(&mon.scratch);
    braun_data_release(&d);
    braun_cli_output_close(&out_csv);
    braun_cli_output_close(&out_summary);
    free(block);
    return BRAUN_CLI_FAILED;
}
