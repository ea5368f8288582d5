/* PNG of `braun plot` through gnuplot (the pngcairo terminal of Debian's
 * gnuplot-nox): the stroboscopic view as lines and marks, or the --plot
 * chart. gnuplot reads the script and its data on a pipe and writes the
 * image to a temporary file's descriptor, so no file name ever goes into
 * the script; names in titles are single-quoted with quotes doubled and
 * control bytes as \xNN (braun_cli_text_byte). POSIX (fork, exec, pipe), confined to this file. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_plot.h"

/* A single-quoted gnuplot string. */
static void gp_string(FILE *g, const char *s)
{
    char buf[5];
    fputc('\'', g);
    for (const unsigned char *p = (const unsigned char *)s; p && *p; p++) {
        if (*p == '\'') fputs("''", g);
        else fputs(braun_cli_text_byte(*p, buf), g); /* control bytes as \xNN */
    }
    fputc('\'', g);
}

/* #AARRGGBB: gnuplot's alpha is a transparency. */
static void gp_colour(FILE *g, const char *rgb, double opacity)
{
    const int a = (int)lround(255 * (1 - opacity));
    fprintf(g, "'#%02x%s'", a < 0 ? 0 : a > 255 ? 255 : a, rgb + 1);
}

static void segment(FILE *g, const double *p, const double *q, const plot_drawing *dr)
{
    fprintf(g, "%.9g %.9g\n%.9g %.9g\n\n", p[dr->axis_u], p[dr->axis_v], q[dr->axis_u],
            q[dr->axis_v]);
}

/* The lines, marks and springs of one configuration as three data blocks;
 * bit 0 set if there are lines, bit 1 if marks, bit 2 if springs (an empty
 * block is not plotted: gnuplot warns about it). Springs apart: drawn as
 * the bodies' thick lines they looked like rigid links. */
static int frame_blocks(FILE *g, const plot_drawing *dr, const double *pos, const char *k,
                        int fixed)
{
    int have = 0;
    fprintf(g, "$L%s << EOD\n", k);
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        if (it->fixed != fixed) continue;
        const double *a = pos + 3 * it->a, *b = pos + 3 * it->b;
        if (it->kind == PLOT_OUTLINE)
            for (int e = 0; e < it->count; e++, have |= 1)
                segment(g, pos + 3 * (it->a + e), pos + 3 * (it->a + (e + 1) % it->count), dr);
        else if (it->kind == PLOT_BAR || it->kind == PLOT_LINK || it->kind == PLOT_BLADE ||
                 it->kind == PLOT_GUIDE)
            segment(g, a, b, dr), have |= 1;
    }
    fputs("EOD\n", g);
    fprintf(g, "$W%s << EOD\n", k);
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        if (it->fixed == fixed && it->kind == PLOT_SPRING)
            segment(g, pos + 3 * it->a, pos + 3 * it->b, dr), have |= 4;
    }
    fputs("EOD\n", g);
    fprintf(g, "$P%s << EOD\n", k);
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        if (it->fixed != fixed) continue;
        if (it->kind == PLOT_PIN || it->kind == PLOT_MASS || it->kind == PLOT_BLOCK ||
            it->kind == PLOT_GROUND || it->kind == PLOT_ROTOR)
            fprintf(g, "%.9g %.9g %d\n", pos[3 * it->a + dr->axis_u], pos[3 * it->a + dr->axis_v],
                    it->kind), have |= 2;
    }
    fputs("EOD\n", g);
    return have;
}

static int script(FILE *g, const plot_job *job)
{
    const plot_samples *s = job->samples;
    const plot_drawing *dr = job->drawing;
    int height = 700;
    if (dr && job->nseries == 0) {
        /* The picture's own proportions, with room for the title and axes. */
        plot_canvas cv;
        plot_canvas_fit(&cv, job);
        height = (int)lround(900 * (cv.height - 2 * cv.margin - cv.bottom) / (cv.width - 2 * cv.margin)) + 140;
        if (height < 300) height = 300;
        if (height > 1400) height = 1400;
    }
    fprintf(g, "set terminal pngcairo noenhanced size 1000,%d font 'sans,11' background '#ffffff'\n"
               "set output\nset grid\n", height);
    /* The title wrapped as the SVG's caption (1000 px at 11 pt): on one
     * line a long one ran off both sides. */
    fputs("set title ", g);
    const int lines = plot_caption_wrap(job->caption, 960, 15, 0, NULL, 0);
    for (int k = 0; k < lines; k++) {
        char text[1024];
        plot_caption_wrap(job->caption, 960, 15, k, text, sizeof text);
        if (k) fputs(" . \"\\n\" . ", g);
        gp_string(g, text);
    }
    fputc('\n', g);
    double *pos = dr ? malloc((size_t)dr->nanchors * 3 * sizeof *pos) : NULL;
    braun_real *qr = malloc((size_t)s->n * sizeof *qr);
    if ((dr && !pos) || !qr) {
        free(pos);
        free(qr);
        return -1;
    }
    if (!dr || job->nseries > 0) {
        /* The chart: t against each series. */
        fputs("set xlabel 't [s]'\nset key top left opaque\n", g);
        /* The SVG's ranges and ticks, with digits enough to tell ticks
         * apart: gnuplot's own read 1e+08 on every tick near 1e8. */
        double range[4];
        if (plot_chart_range(job, pos, qr, range) == 0) {
            const double ty = plot_tick_step(range[0], range[1]);
            const double tt = plot_tick_step(range[2], range[3]);
            const double first = ceil(range[2] / tt) * tt;
            const long nv = lround((range[1] - range[0]) / ty);
            const long nt = (long)floor((range[3] - first) / tt + 1e-9);
            fprintf(g, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n", range[2], range[3],
                    range[0], range[1]);
            fprintf(g, "set xtics %.17g, %.17g\nset ytics %.17g, %.17g\n", first, tt, range[0], ty);
            fprintf(g, "set format x '%%.%dg'\nset format y '%%.%dg'\n",
                    plot_tick_digits(first, tt, nt), plot_tick_digits(range[0], ty, nv));
        }
        fputs("$S << EOD\n", g);
        for (long r = 0; r < s->count; r++) {
            const double *row = s->rows + (size_t)r * (size_t)s->cols;
            fprintf(g, "%.17g", row[0]);
            if (dr) plot_drawing_eval(dr, row + 1, qr, pos);
            for (int k = 0; k < job->nseries; k++) {
                const plot_series *sr = &job->series[k];
                double v = NAN;
                if (sr->column >= 0) v = row[sr->column];
                else if (pos) v = pos[3 * sr->anchor + sr->axis];
                /* Off the line where the envelope is shaded (the SVG's). */
                if (job->hide && job->hide[(size_t)r * (size_t)job->nseries + (size_t)k]) v = NAN;
                if (isfinite(v)) fprintf(g, " %.17g", v);
                else fputs(" NaN", g);
            }
            fputc('\n', g);
        }
        fputs("EOD\n", g);
        /* A series faster than the kept states: its envelope, shaded
         * (the SVG's), each bin's least to greatest value over its time. */
        for (int k = 0; k < job->nseries; k++) {
            if (!job->strays[k]) continue;
            fprintf(g, "$E%d << EOD\n", k);
            for (long r = 0; r < s->count; r++) {
                const double *e = plot_samples_env(s, r);
                const double ta = s->rows[(size_t)r * (size_t)s->cols];
                const double tb = r + 1 < s->count ? s->rows[(size_t)(r + 1) * (size_t)s->cols] : ta;
                if (e && isfinite(e[k]) && isfinite(e[s->nextra + k]))
                    fprintf(g, "%.17g %.17g %.17g\n%.17g %.17g %.17g\n", ta, e[k],
                            e[s->nextra + k], tb, e[k], e[s->nextra + k]);
            }
            fputs("EOD\n", g);
        }
        fputs("plot ", g);
        for (int k = 0; k < job->nseries; k++)
            if (job->strays[k])
                fprintf(g, "$E%d using 1:2:3 with filledcurves fc rgb '%s' fs transparent solid "
                           "0.35 noborder notitle, ", k, plot_colour(k));
        for (int k = 0; k < job->nseries; k++) {
            char title[160];
            snprintf(title, sizeof title, "%s%s%s%s", job->series[k].label,
                     job->series[k].unit ? " [" : "", job->series[k].unit ? job->series[k].unit : "",
                     job->series[k].unit ? "]" : "");
            fprintf(g, "%s$S using 1:%d with lines lw 2 lc rgb '%s' title ", k ? ", " : "", k + 2,
                    plot_colour(k));
            gp_string(g, title);
        }
        fputc('\n', g);
    } else {
        plot_canvas cv;
        plot_canvas_fit(&cv, job);
        const double w = (cv.width - 2 * cv.margin) / cv.scale;
        const double h = (cv.height - 2 * cv.margin - cv.bottom) / cv.scale;
        fprintf(g, "set size ratio -1\nunset key\nset xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n",
                cv.u0, cv.u0 + w, cv.v0, cv.v0 + h);
        fprintf(g, "set xlabel '%c [m]'\nset ylabel '%c [m]'\n", dr->view[0], dr->view[1]);
        const long frames = job->frames < s->count ? job->frames : s->count;
        plot_drawing_eval(dr, s->rows + 1, qr, pos);
        const int ground = frame_blocks(g, dr, pos, "G", 1);
        int moving = 0;
        for (long k = 0; k < frames; k++) {
            char name[24];
            snprintf(name, sizeof name, "%ld", k);
            plot_drawing_eval(dr, s->rows + (size_t)plot_frame_row(job, k) * (size_t)s->cols + 1, qr, pos);
            moving = frame_blocks(g, dr, pos, name, 0);
        }
        /* A path is broken (a blank line) where the motion left the line
         * between kept rows, as the SVG's. */
        const double tol = PLOT_PATH_TOL_PX / cv.scale;
        for (int i = 0; i < dr->ntraces; i++) {
            double prev[2] = {0, 0};
            fprintf(g, "$T%d << EOD\n", i);
            for (long r = 0; r < s->count; r++) {
                plot_drawing_eval(dr, s->rows + (size_t)r * (size_t)s->cols + 1, qr, pos);
                const double *p = pos + 3 * dr->traces[i].anchor;
                const double uv[2] = {p[dr->axis_u], p[dr->axis_v]};
                if (r > 0 && job->strays[i] && plot_path_strays(s, i, r - 1, prev, uv, tol))
                    fputc('\n', g);
                fprintf(g, "%.9g %.9g\n", uv[0], uv[1]);
                prev[0] = uv[0], prev[1] = uv[1];
            }
            fputs("EOD\n", g);
        }
        /* Ground (block -1) with a dashed line, then paths, then the
         * configurations, earlier ones more transparent. */
        /* Every configuration has the same items: one's blocks say for all. */
        const char *sep = "plot ";
        if (ground & 1) fprintf(g, "%s$LG with lines dt 2 lw 1.5 lc rgb '#777777'", sep), sep = ", ";
        if (ground & 4) fprintf(g, "%s$WG with lines dt 3 lw 2 lc rgb '#2e7d32'", sep), sep = ", ";
        if (ground & 2)
            fprintf(g, "%s$PG using 1:2 with points pt 9 ps 2 lc rgb '#222222'", sep), sep = ", ";
        for (int i = 0; i < dr->ntraces; i++, sep = ", ")
            fprintf(g, "%s$T%d with %s lw 1.5 lc rgb '%s'", sep, i,
                    job->strays[i] ? "linespoints pt 7 ps 0.3" : "lines", plot_colour(i));
        for (long k = 0; k < frames; k++) {
            const double op = frames > 1 ? 0.2 + 0.8 * (double)k / (double)(frames - 1) : 1;
            if (moving & 1) {
                fprintf(g, "%s$L%ld with lines lw 4 lc rgb ", sep, k);
                gp_colour(g, "#1f4e79", op);
                sep = ", ";
            }
            if (moving & 4) { /* springs: dotted green, as the SVG's zigzags are green */
                fprintf(g, "%s$W%ld with lines dt 3 lw 2 lc rgb ", sep, k);
                gp_colour(g, "#2e7d32", op);
                sep = ", ";
            }
            if (moving & 2) {
                fprintf(g, "%s$P%ld using 1:2 with points pt 7 ps 1 lc rgb ", sep, k);
                gp_colour(g, "#111111", op);
                sep = ", ";
            }
        }
        fputc('\n', g);
    }
    free(pos);
    free(qr);
    return ferror(g) ? -1 : 0;
}

/* gnuplot's image in a temporary file (unlinked: tmpfile), checked to be
 * a PNG: gnuplot exits 0 when its own write fails (a .png on /dev/full
 * said exit 0) and a gnuplot that writes nothing left an empty file. NULL
 * after a message. */
FILE *plot_render_png(const plot_job *job)
{
    FILE *img = tmpfile();
    if (!img) {
        braun_cli_error("cannot make a temporary file for the .png: %s", strerror(errno));
        return NULL;
    }
    int fds[2];
    if (pipe(fds) != 0) {
        braun_cli_error("cannot start gnuplot: %s", strerror(errno));
        fclose(img);
        return NULL;
    }
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        braun_cli_error("cannot start gnuplot: %s", strerror(errno));
        fclose(img);
        return NULL;
    }
    if (pid == 0) {
        /* gnuplot: the script on stdin, the image on stdout (the file). */
        if (dup2(fds[0], STDIN_FILENO) < 0 || dup2(fileno(img), STDOUT_FILENO) < 0) _exit(126);
        close(fds[0]);
        close(fds[1]);
        execlp("gnuplot", "gnuplot", (char *)NULL);
        _exit(127);
    }
    close(fds[0]);
    /* A gnuplot that stops early must not kill us with SIGPIPE. */
    void (*old)(int) = signal(SIGPIPE, SIG_IGN);
    FILE *g = fdopen(fds[1], "w");
    int rc = g ? script(g, job) : -1;
    if (g && fclose(g) != 0) rc = -1;
    if (!g) close(fds[1]);
    int status = 0;
    pid_t waited;
    do {
        waited = waitpid(pid, &status, 0);
    } while (waited < 0 && errno == EINTR);
    signal(SIGPIPE, old);
    if (waited < 0) {
        braun_cli_error("gnuplot: cannot wait for it: %s", strerror(errno));
        fclose(img);
        return NULL;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
        braun_cli_error("a .png needs gnuplot, which was not found (Debian: apt-get install "
                        "gnuplot-nox); .svg and .html need nothing");
        fclose(img);
        return NULL;
    }
    if (WIFSIGNALED(status)) {
        braun_cli_error("gnuplot was killed by signal %d before the .png was written",
                        WTERMSIG(status));
        fclose(img);
        return NULL;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || rc) {
        braun_cli_error("gnuplot failed to write the .png (exit %d)",
                        WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        fclose(img);
        return NULL;
    }
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[8];
    rewind(img);
    if (fread(head, 1, sizeof head, img) != sizeof head || memcmp(head, sig, sizeof sig) != 0) {
        braun_cli_error("gnuplot exited 0 but wrote no .png (is its pngcairo terminal there? "
                        "Debian: gnuplot-nox)");
        fclose(img);
        return NULL;
    }
    rewind(img);
    return img;
}

/* The rendered image into out; errors are out's (braun_cli_output_close
 * reports them). */
int plot_copy_png(FILE *img, FILE *out)
{
    char buf[65536];
    size_t got;
    int rc = 0;
    while ((got = fread(buf, 1, sizeof buf, img)) > 0)
        if (fwrite(buf, 1, got, out) != got) {
            rc = -1;
            break;
        }
    if (ferror(img)) {
        braun_cli_error("cannot read back the rendered .png: %s", strerror(errno));
        rc = -1;
    }
    fclose(img);
    return rc;
}
