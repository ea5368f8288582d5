/* braun plot MODEL [run options] -o FILE, or braun plot MODEL --traj CSV
 * -o FILE: see the motion. The extension picks the picture:
 *   .svg   a stroboscopic view (configurations over the window, earlier
 *          ones fainter, the paths of --points; the paper's Fig. 1), or
 *          with --plot the chosen coordinates against time;
 *   .html  a self-contained animation page (play/pause, time slider);
 *   .png   the same drawn by gnuplot.
 * The run is `braun run`'s (same options, same monitored steps, the same
 * guard); only the states that passed are drawn. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

enum { FMT_SVG, FMT_HTML, FMT_PNG };

static int format_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    char ext[8] = "";
    if (dot && strlen(dot) < sizeof ext)
        for (size_t i = 0; dot[i]; i++) ext[i] = (char)tolower((unsigned char)dot[i]);
    if (strcmp(ext, ".svg") == 0) return FMT_SVG;
    if (strcmp(ext, ".html") == 0 || strcmp(ext, ".htm") == 0) return FMT_HTML;
    if (strcmp(ext, ".png") == 0) return FMT_PNG;
    return -1;
}

typedef struct plot_run {
    plot_samples *samples;
    double *row;
    int n;
    int status; /* the run's (done) */
    double last_t; /* the latest state's time, kept or not */
} plot_run;

static void on_state(void *user, double t, const double *q, const double *v,
                     const braun_cli_errors *e)
{
    plot_run *pr = (plot_run *)user;
    const int n = pr->n;
    pr->last_t = t;
    pr->row[0] = t;
    memcpy(pr->row + 1, q, (size_t)n * sizeof *q);
    memcpy(pr->row + 1 + n, v, (size_t)n * sizeof *v);
    pr->row[1 + 2 * n] = e->pos;
    pr->row[2 + 2 * n] = e->vel;
    pr->row[3 + 2 * n] = e->energy;
    pr->row[4 + 2 * n] = e->traj;
    plot_samples_add(pr->samples, pr->row);
}

/* --plot: columns ("crank.theta", "pos_err", "q[2]"), a point's coordinate
 * ("rod.B.x"), or x, y, z of every --points point. */
static int resolve_series(plot_job *job, plot_drawing *dr, const braun_cli_target *t,
                          const char *list)
{
    const int n = t->sys.n;
    const int most = (int)(sizeof job->series / sizeof job->series[0]);
    for (const char *p = list; *p;) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char item[128];
        if (len == 0 || len >= sizeof item)
            return braun_cli_error("--plot '%s': give names separated by commas "
                                   "(crank.theta,rod.B.x; x,y with --points)", list);
        memcpy(item, p, len);
        item[len] = '\0';
        p = comma ? comma + 1 : p + len;
        const int col = braun_cli_column_find(t, n, item);
        const int axis = strchr("xyz", item[len - 1]) && (len == 1 || item[len - 2] == '.')
                             ? item[len - 1] - 'x'
                             : -1;
        if (col > 0 && strcmp(item, "traj_err") == 0 && !t->reference && !job->args->traj_path) {
            /* Its column is empty without a reference: an empty chart with
             * exit 0 looked like a chart (found by an outside client). */
            return braun_cli_error("--plot traj_err: '%s' has no reference solution, so its "
                                   "trajectory error is not known (a scene names one with \"reference\": docs/scene-format.md)",
                                   t->name);
        } else if (col > 0) {
            if (job->nseries == most) return braun_cli_error("--plot: at most %d series", most);
            plot_series *sr = &job->series[job->nseries++];
            sr->column = col;
            braun_cli_column_name(t, n, col, sr->label, sizeof sr->label, &sr->unit);
        } else if (axis == 2 && dr && dr->scene && dr->scene->dim != 3) {
            /* As --view refuses z on a planar scene: its z is 0 throughout. */
            return braun_cli_error("--plot %s: '%s' is planar (no z)", item, t->name);
        } else if (axis >= 0 && len == 1) {
            if (!dr || dr->ntraces == 0)
                return braun_cli_error("--plot %s: a coordinate of the --points points; give "
                                       "--points A,B (or write A.%s)", item, item);
            for (int i = 0; i < dr->ntraces; i++) {
                if (job->nseries == most) return braun_cli_error("--plot: at most %d series", most);
                plot_series *sr = &job->series[job->nseries++];
                sr->column = -1;
                sr->anchor = dr->traces[i].anchor;
                sr->axis = axis;
                sr->unit = "m";
                snprintf(sr->label, sizeof sr->label, "%s.%c", dr->traces[i].name, item[0]);
            }
        } else if (axis >= 0 && dr) {
            char ref[128];
            memcpy(ref, item, len - 2);
            ref[len - 2] = '\0';
            const int a = plot_drawing_point(dr, t, ref);
            if (a < 0) return BRAUN_CLI_USAGE;
            if (job->nseries == most) return braun_cli_error("--plot: at most %d series", most);
            plot_series *sr = &job->series[job->nseries++];
            sr->column = -1;
            sr->anchor = a;
            sr->axis = axis;
            sr->unit = "m";
            snprintf(sr->label, sizeof sr->label, "%s", item);
        } else {
            return braun_cli_error("--plot: '%s' is not a column of '%s' (braun run %s --out "
                                   "names them) nor POINT.x, POINT.y, POINT.z", item, t->name,
                                   t->name);
        }
    }
    return 0;
}

/* The envelope's values of a state: each --plot series', or each traced
 * point's position across and up the view (cli_plot_samples.c). */
typedef struct plot_extra {
    const plot_job *job;
    const plot_drawing *dr;
    double *pos;
    braun_real *qr;
} plot_extra;

static void extra_values(void *ctx, const double *row, double *out)
{
    const plot_extra *x = (const plot_extra *)ctx;
    const plot_job *job = x->job;
    if (x->dr) plot_drawing_eval(x->dr, row + 1, x->qr, x->pos);
    if (job->nseries > 0) {
        for (int k = 0; k < job->nseries; k++) {
            const plot_series *sr = &job->series[k];
            out[k] = sr->column >= 0 ? row[sr->column]
                     : x->dr       ? x->pos[3 * sr->anchor + sr->axis]
                                   : NAN;
        }
        return;
    }
    if (!x->dr) return; /* paths without a drawing: none (the caller's rule) */
    for (int i = 0; i < x->dr->ntraces; i++) {
        const double *p = x->pos + 3 * x->dr->traces[i].anchor;
        out[2 * i] = p[x->dr->axis_u];
        out[2 * i + 1] = p[x->dr->axis_v];
    }
}

static int done(void *user, const braun_cli_result *r)
{
    ((plot_run *)user)->status = r->status;
    plot_samples_finish(((plot_run *)user)->samples);
    return 0;
}

int braun_cli_plot(int argc, char **argv)
{
    braun_cli_run_args a;
    int rc = braun_cli_parse_run(argc, argv, &a, 1);
    if (rc) return rc;
    const int fmt = format_of(a.plot_path);
    if (fmt < 0)
        return braun_cli_error("-o %s: the extension picks the picture: .svg (drawing), .html "
                               "(animation) or .png (gnuplot)", a.plot_path);
    braun_cli_target tg;
    rc = braun_cli_target_open(a.model, &tg);
    if (rc) return rc;

    plot_drawing dr;
    plot_samples samples;
    plot_job job;
    braun_cli_output out;
    memset(&dr, 0, sizeof dr);
    memset(&samples, 0, sizeof samples);
    memset(&job, 0, sizeof job);
    memset(&out, 0, sizeof out);
    double *row = NULL;
    char caption[512] = "";
    /* The drawing: always, unless --plot names columns only of a system
     * without a scene. */
    const int want_drawing = tg.drawing || !a.plot_columns;
    if (want_drawing) rc = plot_drawing_build(&dr, &tg, a.view);
    if (!rc && a.points) {
        if (!tg.drawing)
            rc = braun_cli_error("--points: '%s' has no scene to name points in", tg.name);
        else
            rc = plot_drawing_trace(&dr, &tg, a.points);
    }
    job.target = &tg;
    job.args = &a;
    job.samples = &samples;
    if (!rc && a.plot_columns) rc = resolve_series(&job, want_drawing ? &dr : NULL, &tg, a.plot_columns);
    job.frames = a.frames > 0 ? a.frames : fmt == FMT_HTML ? 400 : 12;
    const long cap = a.samples > 0 ? a.samples : (job.frames > 2000 ? job.frames : 2000);
    /* The envelope of what the picture joins by lines: the chart's series,
     * else the traced points' paths. */
    plot_extra ex = {&job, want_drawing ? &dr : NULL, NULL, NULL};
    if (!rc && (job.nseries > 0 || (want_drawing && dr.ntraces > 0))) {
        samples.nextra = job.nseries > 0 ? job.nseries : 2 * dr.ntraces;
        samples.paired = job.nseries == 0;
        samples.extra = extra_values;
        samples.extra_ctx = &ex;
        ex.pos = want_drawing ? malloc((size_t)dr.nanchors * 3 * sizeof *ex.pos + 1) : NULL;
        ex.qr = malloc((size_t)tg.sys.n * sizeof *ex.qr + 1);
        if ((want_drawing && !ex.pos) || !ex.qr) rc = braun_cli_error("out of memory");
    }

    /* Written whole: a picture that fails to be written leaves the file as
     * it was. */
    if (!rc) rc = braun_cli_output_open_whole(&out, a.plot_path, "-o");
    if (!rc) rc = braun_cli_output_distinct(&out, NULL, &tg.id, tg.source);
    if (!rc && a.traj_path) {
        braun_cli_id traj_id;
        braun_cli_path_id(a.traj_path, &traj_id);
        if (braun_cli_same_file(&out.id, &traj_id))
            rc = braun_cli_error("-o '%s' is the --traj input: refused (it would be overwritten)",
                                 a.plot_path);
    }
    if (!rc && a.traj_path) {
        samples.from = a.from;
        samples.cap = cap;
        rc = plot_traj_read(a.traj_path, &tg, &samples);
        snprintf(caption, sizeof caption, "%s: %s, t = %g ... %g s", tg.name, a.traj_path,
                 samples.count ? samples.rows[0] : 0,
                 samples.count ? samples.rows[(size_t)(samples.count - 1) * (size_t)samples.cols] : 0);
    } else if (!rc) {
        const double from = isnan(a.from) ? 0 : a.from;
        if (from >= a.t_end) rc = braun_cli_error("--from %g is not before --t-end %g", from, a.t_end);
        if (!rc && plot_samples_init(&samples, tg.sys.n, cap, from, a.t_end))
            rc = braun_cli_error("out of memory");
        row = rc ? NULL : malloc((size_t)samples.cols * sizeof *row);
        if (!rc && !row) rc = braun_cli_error("out of memory");
        if (!rc) {
            plot_run pr = {&samples, row, tg.sys.n, BRAUN_OK, NAN};
            braun_cli_observer obs = {on_state, done, &pr};
            a.plot_output = &out;
            /* A failed run still draws up to its last good state. */
            rc = braun_cli_run_target(&a, &tg, &obs);
            /* Stopped before the window: say that nothing was drawn (only
             * the run's own message did, and the file stayed as it was). */
            if (rc && samples.count == 0) {
                if (isfinite(pr.last_t))
                    (void)braun_cli_error("no picture written (-o %s left as it was): the run "
                                          "stopped at t = %g s, before --from %g", a.plot_path,
                                          pr.last_t, from);
                goto finish;
            }
            if (a.method == BRAUN_DOPRI5)
                snprintf(caption, sizeof caption, "%s: dopri5, rtol %g, t = %g ... %g s", tg.name,
                         a.rtol, samples.count ? samples.rows[0] : from,
                         samples.count ? samples.rows[(size_t)(samples.count - 1) * (size_t)samples.cols] : from);
            else
                snprintf(caption, sizeof caption, "%s: %s, h = %g s, t = %g ... %g s", tg.name,
                         braun_method_name(a.method), a.dt, samples.count ? samples.rows[0] : from,
                         samples.count ? samples.rows[(size_t)(samples.count - 1) * (size_t)samples.cols] : from);
            /* A picture of a run that stopped says so, in itself: only
             * stderr did, and the file looked like a finished run's. */
            const size_t len = strlen(caption);
            if (rc && pr.status != BRAUN_OK && len < sizeof caption) {
                char st[64];
                snprintf(caption + len, sizeof caption - len, " (of %g s: stopped, %s)", a.t_end,
                         braun_cli_status_name(pr.status, st, sizeof st));
            }
        }
    }
    /* A failed or interrupted run (128 + the signal) draws up to its last
     * good state and keeps its exit status. */
    const int interrupted = rc > 128 && rc < 128 + 65;
    if (!(rc == 0 || rc == BRAUN_CLI_FAILED || interrupted) || samples.count == 0) {
        if (!rc) rc = braun_cli_error("nothing to draw: no state in the window");
        goto finish;
    }
    {
        long frames = job.frames < samples.count ? job.frames : samples.count;
        /* The configurations drawn: frames whose nearest kept state is
         * another frame's are one (uneven adaptive steps). */
        if (frames > 1) {
            long distinct = 0, last = -1;
            for (long k = 0; k < frames; k++) {
                const long r = plot_frame_row(&job, k);
                if (r != last) distinct++;
                last = r;
            }
            frames = distinct;
        }
        size_t len = strlen(caption);
        /* The plane shown, where there is a choice (a spatial scene) or a
         * mirror: the PNG's axis labels said it, the SVG and HTML did not. */
        if (!a.plot_columns && want_drawing && (dr.scene->dim == 3 || strcmp(dr.view, "xy") != 0) &&
            len < sizeof caption) {
            snprintf(caption + len, sizeof caption - len, ", view %s (%c across, %c up)", dr.view,
                     dr.view[0], dr.view[1]);
            len = strlen(caption);
        }
        if (!a.plot_columns && fmt != FMT_HTML && len < sizeof caption)
            snprintf(caption + len, sizeof caption - len, frames == 1 ? ", %ld configuration"
                                                                        : ", %ld configurations (earlier fainter)",
                     frames);
        job.caption = caption;
        /* With --plot the job has series and the writers draw the chart;
         * the drawing (if any) gives the points' coordinates. */
        job.drawing = want_drawing ? &dr : NULL;
        if (want_drawing && plot_drawing_fit_guides(&dr, &samples)) {
            rc = braun_cli_error("out of memory");
            goto finish;
        }
        /* A picture that would place NaN is not written: bad input for
         * --traj, a failed run otherwise. */
        if (plot_job_fits(&job)) {
            rc = a.traj_path ? BRAUN_CLI_USAGE : BRAUN_CLI_FAILED;
            goto finish;
        }
        /* Lines that would show a motion the states between the kept ones
         * did not take: the picture says what it drew instead. */
        const int strays = plot_job_resolution(&job);
        len = strlen(caption);
        if (strays && len < sizeof caption)
            snprintf(caption + len, sizeof caption - len,
                     job.nseries > 0 ? "; shaded: least to greatest value between the %ld kept "
                                       "states (the motion is faster than they resolve)"
                                     : "; paths: dots where the motion left the line between "
                                       "the %ld kept states",
                     samples.count);
        /* A .png is rendered before the output is touched: a gnuplot that
         * fails leaves a file that existed as it was (and removes one this
         * command created, at finish). */
        FILE *img = NULL;
        if (fmt == FMT_PNG && !(img = plot_render_png(&job))) {
            rc = BRAUN_CLI_FAILED; /* out abandoned at finish */
        } else {
            int wrc = braun_cli_output_begin(&out);
            if (!wrc) {
                if (fmt == FMT_SVG) {
                    wrc = plot_write_svg(out.f, &job);
                } else if (fmt == FMT_HTML) {
                    wrc = plot_write_html(out.f, &job);
                    /* A large scene's animation is large: a 1000-link
                     * chain's was 131 MB at the default 400 frames, and
                     * said nothing (found by an outside client). */
                    const long bytes = wrc ? -1 : ftell(out.f);
                    if (bytes > 100L * 1000 * 1000)
                        fprintf(stderr, "braun: note: %s is %.0f MB (%ld frames): --frames N makes it "
                                        "smaller\n", a.plot_path, (double)bytes / 1e6, job.frames);
                } else {
                    wrc = plot_copy_png(img, out.f); /* closes img */
                    img = NULL;
                    if (wrc) braun_cli_output_failed(&out); /* the write's errno, for the message */
                }
            }
            if (img) fclose(img);
            if (braun_cli_output_close(&out) || wrc) rc = BRAUN_CLI_FAILED;
            /* Interrupted: drawn, and the exit status stays 128 + the signal. */
            else if (!interrupted && (a.progress > 0 || (a.progress < 0 && braun_cli_stderr_is_terminal())))
                fprintf(stderr, "braun: wrote %s (%s)\n", a.plot_path,
                        a.plot_columns ? "chart" : fmt == FMT_HTML ? "animation" : "stroboscopic view");
        }
    }
finish:
    free(job.hide);
    braun_cli_output_abandon(&out);
    free(row);
    free(ex.pos);
    free(ex.qr);
    plot_samples_free(&samples);
    plot_drawing_free(&dr);
    braun_cli_target_close(&tg);
    return rc;
}
