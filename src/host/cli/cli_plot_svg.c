/* SVG of `braun plot`: the stroboscopic view (configurations of the
 * mechanism over the time window, earlier ones fainter, as the paper's
 * Fig. 1, with the paths of the traced points) and the chart of --plot
 * (coordinates against time). Plain SVG 1.1 with presentation attributes
 * only — no CSS, script or external reference — so any viewer and
 * rsvg-convert draw it the same. The animation page (cli_plot_html.c)
 * reuses the configurations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

#define CANVAS_WIDTH 800.0
#define CANVAS_MAX_PLOT_HEIGHT 560.0
#define CANVAS_MARGIN 28.0
#define CANVAS_BOTTOM 40.0

static double series_value(const plot_job *job, const plot_series *sr, const double *row,
                           double *pos, braun_real *qr);

const char *plot_colour(int i)
{
    /* One per series or trace (at most 16 of either): with 8 the 9th
     * series took the 1st's colour. */
    static const char *const c[] = {"#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                    "#17becf", "#8c564b", "#e377c2", "#7f7f7f",
                                    "#1f77b4", "#bcbd22", "#393b79", "#ad494a",
                                    "#637939", "#8c6d31", "#7b4173", "#000000"};
    return c[(unsigned)i % (sizeof c / sizeof c[0])];
}

void plot_xml_text(FILE *f, const char *s)
{
    char buf[5];
    for (const unsigned char *p = (const unsigned char *)s; p && *p; p++) {
        if (*p == '&') fputs("&amp;", f);
        else if (*p == '<') fputs("&lt;", f);
        else if (*p == '>') fputs("&gt;", f);
        else if (*p == '"') fputs("&quot;", f);
        else fputs(braun_cli_text_byte(*p, buf), f); /* control bytes as \xNN */
    }
}

/* Caption text: 13 px, estimated at 0.66 em a letter (capitals and digits
 * of DejaVu Sans are 0.6 to 0.77 em). */
#define CAPTION_FONT 13.0
#define EM_ESTIMATE 0.66

/* Append word (len letters) to the wrapped lines: a new line first when
 * it does not fit; line k kept in out. */
typedef struct wrap_state {
    size_t most, used;
    int line, k;
    char buf[1024];
    char *out;
    size_t size;
} wrap_state;

static void wrap_word(wrap_state *w, const char *word, size_t len)
{
    char cut[1024];
    if (len >= sizeof cut) len = sizeof cut - 1;
    if (len > w->most) {
        /* A name longer than a line: its head and tail around "...". */
        const size_t head = (w->most - 3) / 2, tail = w->most - 3 - head;
        memcpy(cut, word, head);
        cut[head] = cut[head + 1] = cut[head + 2] = '.';
        memcpy(cut + head + 3, word + len - tail, tail);
        word = cut;
        len = w->most;
    }
    if (w->used > 0 && w->used + 1 + len > w->most) {
        if (w->line == w->k && w->out) snprintf(w->out, w->size, "%s", w->buf);
        w->line++;
        w->used = 0;
    }
    if (w->used > 0) w->buf[w->used++] = ' ';
    memcpy(w->buf + w->used, word, len);
    w->used += len;
    w->buf[w->used] = '\0';
}

int plot_caption_wrap(const char *caption, double width, double font, int k, char *out,
                      size_t size)
{
    wrap_state w;
    memset(&w, 0, sizeof w);
    w.most = (size_t)(width / (EM_ESTIMATE * font));
    if (w.most < 12) w.most = 12;
    if (w.most > sizeof w.buf / 2) w.most = sizeof w.buf / 2;
    w.k = k;
    w.out = out;
    w.size = size;
    if (out && size) out[0] = '\0';
    /* Lines break between clauses — after ", " or "; ", before " (" — so
     * "(of 3 s: stopped, BRAUN_ERR_ACCURACY)" stays whole; a clause
     * longer than a line breaks between its words. */
    const char *p = caption ? caption : "";
    while (*p) {
        while (*p == ' ') p++;
        if (!*p) break;
        const char *end = p;
        for (;;) {
            const char *sp = strchr(end, ' ');
            if (!sp) {
                end += strlen(end);
                break;
            }
            const int paren = *p != '(' && sp[1] == '(';
            const int clause = sp > end && (sp[-1] == ',' || sp[-1] == ';') && *p != '(';
            end = sp;
            if (paren || clause || (*p == '(' && sp > p && sp[-1] == ')')) break;
            end = sp + 1;
        }
        while (end[-1] == ' ') end--; /* stops after p, which is no blank */
        const size_t len = (size_t)(end - p);
        if (len <= w.most) {
            wrap_word(&w, p, len);
        } else {
            for (const char *q = p; q < end;) {
                while (q < end && *q == ' ') q++;
                const char *e = q;
                while (e < end && *e != ' ') e++;
                if (e > q) wrap_word(&w, q, (size_t)(e - q));
                q = e;
            }
        }
        p = end;
    }
    if (w.line == k && out) snprintf(out, size, "%s", w.buf);
    return w.line + 1;
}

/* The scale bar's length in m: 1, 2 or 5 times a power of ten, about a
 * fifth of the width (0 when there is none). */
static double scale_bar_length(const plot_canvas *cv)
{
    const double want = (cv->width - 2 * cv->margin) / 5 / cv->scale;
    if (!(want > 0) || !isfinite(want)) return 0;
    const double p = pow(10, floor(log10(want)));
    return want / p >= 5 ? 5 * p : want / p >= 2 ? 2 * p : p;
}

long plot_frame_row(const plot_job *job, long k)
{
    const plot_samples *s = job->samples;
    const long frames = job->frames < s->count ? job->frames : s->count;
    if (frames <= 1) return s->count - 1;
    /* As many frames as kept states: each state once. The nearest row of
     * evenly spaced times repeated some of an adaptive run's uneven steps
     * and skipped others (21 states, "21 configurations", 18 drawn). */
    if (frames == s->count) return k;
    const double t0 = s->rows[0], t1 = s->rows[(size_t)(s->count - 1) * (size_t)s->cols];
    const double want = t0 + (t1 - t0) * (double)k / (double)(frames - 1);
    /* The row nearest want (the last frame: the last row). The first at or
     * after it took a frame one step late whenever want rounded an ulp
     * above a kept time (0.6000000000000001: 0.61 drawn, 0.6 kept). */
    long lo = 0, hi = s->count - 1;
    if (k == frames - 1) return hi;
    while (lo < hi) {
        const long mid = lo + (hi - lo) / 2;
        if (s->rows[(size_t)mid * (size_t)s->cols] < want) lo = mid + 1;
        else hi = mid;
    }
    if (lo > 0 && want - s->rows[(size_t)(lo - 1) * (size_t)s->cols] <=
                      s->rows[(size_t)lo * (size_t)s->cols] - want)
        lo--;
    return lo;
}

void plot_canvas_xy(const plot_canvas *cv, const plot_drawing *dr, const double *pos, double *x,
                    double *y)
{
    *x = cv->margin + (pos[dr->axis_u] - cv->u0) * cv->scale;
    *y = cv->height - cv->bottom - cv->margin - (pos[dr->axis_v] - cv->v0) * cv->scale;
}

/* Anchors that count for the extent: all but those of guides only. */
static void extent_mask(const plot_drawing *dr, char *use)
{
    memset(use, 0, (size_t)dr->nanchors);
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        if (it->kind == PLOT_GUIDE) continue;
        if (it->kind == PLOT_OUTLINE) {
            for (int k = 0; k < it->count; k++) use[it->a + k] = 1;
        } else {
            use[it->a] = 1;
            if (it->kind == PLOT_BAR || it->kind == PLOT_LINK || it->kind == PLOT_SPRING ||
                it->kind == PLOT_BLADE)
                use[it->b] = 1;
        }
    }
    for (int i = 0; i < dr->ntraces; i++) use[dr->traces[i].anchor] = 1;
}

void plot_canvas_fit(plot_canvas *cv, const plot_job *job)
{
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    double pos_stack[3 * 256];
    braun_real qr_stack[256];
    double *pos = dr->nanchors <= 256 ? pos_stack : malloc((size_t)dr->nanchors * 3 * sizeof *pos);
    braun_real *qr = s->n <= 256 ? qr_stack : malloc((size_t)s->n * sizeof *qr);
    char use_stack[256];
    char *use = dr->nanchors <= 256 ? use_stack : malloc((size_t)dr->nanchors);
    cv->margin = CANVAS_MARGIN;
    cv->bottom = CANVAS_BOTTOM;
    cv->width = CANVAS_WIDTH;
    if (pos && qr && use) {
        extent_mask(dr, use);
        for (long r = 0; r < s->count; r++) {
            plot_drawing_eval(dr, s->rows + (size_t)r * (size_t)s->cols + 1, qr, pos);
            for (int i = 0; i < dr->nanchors; i++) {
                if (!use[i]) continue;
                const double uv[2] = {pos[3 * i + dr->axis_u], pos[3 * i + dr->axis_v]};
                for (int k = 0; k < 2; k++) {
                    if (!isfinite(uv[k])) continue;
                    if (uv[k] < lo[k]) lo[k] = uv[k];
                    if (uv[k] > hi[k]) hi[k] = uv[k];
                }
            }
        }
    }
    if (pos != pos_stack) free(pos);
    if (qr != qr_stack) free(qr);
    if (use != use_stack) free(use);
    if (!(lo[0] <= hi[0])) lo[0] = hi[0] = 0;
    if (!(lo[1] <= hi[1])) lo[1] = hi[1] = 0;
    double du = hi[0] - lo[0], dv = hi[1] - lo[1];
    const double size = du > dv ? du : dv;
    /* Room for the marks drawn around points (rings, blocks, ground). */
    const double pad = size > 0 ? 0.04 * size : 0.5;
    lo[0] -= pad, hi[0] += pad, lo[1] -= pad, hi[1] += pad;
    du = hi[0] - lo[0], dv = hi[1] - lo[1];
    const double avail_w = cv->width - 2 * cv->margin;
    cv->scale = avail_w / du;
    if (dv * cv->scale > CANVAS_MAX_PLOT_HEIGHT) cv->scale = CANVAS_MAX_PLOT_HEIGHT / dv;
    double plot_h = dv * cv->scale;
    if (plot_h < 120) plot_h = 120;
    /* The caption left of the scale bar, on as many lines as it takes: a
     * long one ran under the bar and off the canvas, losing the run's
     * status at its end. */
    const double bar = scale_bar_length(cv) * cv->scale;
    cv->caption_width = cv->width - 2 * cv->margin - (isfinite(bar) ? bar : 0) - 24;
    cv->caption_lines = plot_caption_wrap(job->caption, cv->caption_width, CAPTION_FONT, 0, NULL, 0);
    /* Room for two lines always: most captions take one or two, and a
     * picture's size should not hang on which (--traj's and the run's
     * captions differ, their drawings do not). */
    cv->bottom += 16.0 * (cv->caption_lines > 2 ? cv->caption_lines - 1 : 1);
    cv->height = plot_h + 2 * cv->margin + cv->bottom;
    cv->u0 = lo[0] - (avail_w / cv->scale - du) / 2;
    cv->v0 = lo[1] - (plot_h / cv->scale - dv) / 2;
}

/* ------------------------------------------------------------ the items */
static void xy_of(const plot_job *job, const plot_canvas *cv, const double *pos, int a, double *x,
                  double *y)
{
    plot_canvas_xy(cv, job->drawing, pos + 3 * a, x, y);
}

static void line(FILE *f, const char *in, double x0, double y0, double x1, double y1,
                 const char *style)
{
    fprintf(f, "%s<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", in, x0, y0, x1,
            y1, style);
}

static void spring(FILE *f, const char *in, double x0, double y0, double x1, double y1)
{
    const double dx = x1 - x0, dy = y1 - y0, len = hypot(dx, dy);
    if (!(len > 0)) return;
    const double ux = dx / len, uy = dy / len, nx = -uy, ny = ux;
    const int coils = 8;
    fprintf(f, "%s<polyline points=\"%.2f,%.2f", in, x0, y0);
    for (int k = 0; k <= 2 * coils; k++) {
        const double s = 0.15 + 0.7 * k / (2.0 * coils);
        const double w = k == 0 || k == 2 * coils ? 0 : (k % 2 ? 5 : -5);
        fprintf(f, " %.2f,%.2f", x0 + s * dx + w * nx, y0 + s * dy + w * ny);
    }
    fprintf(f, " %.2f,%.2f\" fill=\"none\" stroke=\"#3a8a3a\" stroke-width=\"1.6\" "
               "stroke-linejoin=\"round\"/>\n", x1, y1);
}

static void block(FILE *f, const char *in, double x, double y, double gx0, double gy0,
                  double gx1, double gy1)
{
    double dx = gx1 - gx0, dy = gy1 - gy0, len = hypot(dx, dy);
    if (!(len > 0)) dx = 1, dy = 0, len = 1;
    const double ux = dx / len, uy = dy / len, nx = -uy, ny = ux, a = 11, b = 6.5;
    fprintf(f, "%s<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"#d9a441\" "
               "stroke=\"#6b4a10\" stroke-width=\"1.2\"/>\n", in,
            x - a * ux - b * nx, y - a * uy - b * ny, x + a * ux - b * nx, y + a * uy - b * ny,
            x + a * ux + b * nx, y + a * uy + b * ny, x - a * ux + b * nx, y - a * uy + b * ny);
}

/* Three quarters of a circle about (x, y), from the side and over the top
 * to the bottom, and its head there: counter-clockwise on screen for
 * sense > 0 (from the right; SVG's sweep 0 in y-down coordinates), else
 * clockwise (from the left). The arc ended at the top, with sweep 0 and the
 * large-arc flag, which put its centre 15 px off the body's. */
static void rotor(FILE *f, const char *in, double x, double y, int sense)
{
    const double r = 15, s = sense < 0 ? -1 : 1;
    fprintf(f, "%s<path d=\"M %.2f %.2f A %.1f %.1f 0 1 %d %.2f %.2f\" fill=\"none\" "
               "stroke=\"#b8322f\" stroke-width=\"1.6\"/>\n", in, x + s * r, y, r, r,
            sense < 0 ? 1 : 0, x, y + r);
    fprintf(f, "%s<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"#b8322f\"/>\n", in,
            x, y + r - 4.5, x, y + r + 4.5, x + s * 7, y + r);
}

static void ground(FILE *f, const char *in, double x, double y)
{
    fprintf(f, "%s<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"#ffffff\" "
               "stroke=\"#222222\" stroke-width=\"1.2\"/>\n", in, x, y, x - 8, y + 12, x + 8, y + 12);
    line(f, in, x - 12, y + 12, x + 12, y + 12, "stroke=\"#222222\" stroke-width=\"1.2\"");
    for (int k = 0; k < 4; k++)
        line(f, in, x - 10 + 6 * k, y + 12, x - 14 + 6 * k, y + 17,
             "stroke=\"#222222\" stroke-width=\"1\"");
}

void plot_svg_items(FILE *f, const plot_job *job, const plot_canvas *cv, const double *pos,
                    double t, int layer, const char *in)
{
    const plot_drawing *dr = job->drawing;
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        /* Layers: the ground's guides and springs under everything, the
         * moving items, the ground marks on top; rotors only where asked. */
        const int mine = layer == PLOT_LAYER_UNDER   ? it->fixed && it->kind != PLOT_GROUND
                         : layer == PLOT_LAYER_MARKS ? it->fixed && it->kind == PLOT_GROUND
                         : layer == PLOT_LAYER_MOVING ? !it->fixed && it->kind != PLOT_ROTOR
                                                      : !it->fixed;
        if (!mine) continue;
        double xa, ya, xb, yb, xc, yc;
        xy_of(job, cv, pos, it->a, &xa, &ya);
        xy_of(job, cv, pos, it->b, &xb, &yb);
        xy_of(job, cv, pos, it->c, &xc, &yc);
        switch (it->kind) {
        case PLOT_OUTLINE:
            fprintf(f, "%s<polygon points=\"", in);
            for (int k = 0; k < it->count; k++) {
                double x, y;
                xy_of(job, cv, pos, it->a + k, &x, &y);
                fprintf(f, "%s%.2f,%.2f", k ? " " : "", x, y);
            }
            fputs("\" fill=\"#9cc0e6\" stroke=\"#1f4e79\" stroke-width=\"1.6\" "
                  "stroke-linejoin=\"round\"/>\n", f);
            break;
        case PLOT_BAR:
            line(f, in, xa, ya, xb, yb, "stroke=\"#1f4e79\" stroke-width=\"9\" stroke-linecap=\"round\"");
            line(f, in, xa, ya, xb, yb, "stroke=\"#9cc0e6\" stroke-width=\"5.5\" stroke-linecap=\"round\"");
            break;
        case PLOT_LINK:
            line(f, in, xa, ya, xb, yb, "stroke=\"#444444\" stroke-width=\"2\"");
            break;
        case PLOT_MASS:
            fprintf(f, "%s<circle cx=\"%.2f\" cy=\"%.2f\" r=\"8\" fill=\"#1f4e79\" "
                       "stroke=\"#0d2238\" stroke-width=\"1\"/>\n", in, xa, ya);
            break;
        case PLOT_PIN:
            fprintf(f, "%s<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.6\" fill=\"#ffffff\" "
                       "stroke=\"#111111\" stroke-width=\"1.5\"/>\n", in, xa, ya);
            break;
        case PLOT_GUIDE:
            line(f, in, xa, ya, xb, yb,
                 "stroke=\"#777777\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"");
            break;
        case PLOT_BLOCK:
            block(f, in, xa, ya, xb, yb, xc, yc);
            fprintf(f, "%s<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.6\" fill=\"#ffffff\" "
                       "stroke=\"#111111\" stroke-width=\"1.5\"/>\n", in, xa, ya);
            break;
        case PLOT_BLADE:
            line(f, in, xa, ya, xb, yb, "stroke=\"#111111\" stroke-width=\"4\" stroke-linecap=\"round\"");
            break;
        case PLOT_SPRING:
            spring(f, in, xa, ya, xb, yb);
            break;
        case PLOT_ROTOR: {
            /* The sense is about +z (x towards y); a view that shows the
             * plane mirrored (yx, xz, zy: across and up not in the order
             * x, y, z, x) turns it over on screen. */
            const int mirrored = (dr->axis_v - dr->axis_u + 3) % 3 != 1;
            const int sense = plot_item_sense(it, t) * (mirrored ? -1 : 1);
            if (sense) rotor(f, in, xa, ya, sense);
            break;
        }
        case PLOT_GROUND:
            ground(f, in, xa, ya);
            break;
        default:
            break;
        }
    }
}

/* Whether the states between kept rows left the straight line joining
 * values a and b by more than tol: their envelope, lo ... hi, reaches past
 * the segment's own range. */
static int bin_strays(double lo, double hi, double a, double b, double tol)
{
    const double top = a > b ? a : b, bot = a < b ? a : b;
    return hi - top > tol || bot - lo > tol;
}

/* Trace i's segment from row r to r + 1, at world (u, v) a and b: whether
 * the point may have left it by more than tol. A path of length L between
 * ends c apart stays within sqrt(L^2 - c^2) / 2 of their chord (an
 * ellipse with the ends as foci), and a chord across a swing is far
 * shorter than the arc. */
int plot_path_strays(const plot_samples *s, int i, long r, const double *a, const double *b,
                       double tol)
{
    const double *e = plot_samples_env(s, r);
    if (!e || !s->paired || s->nextra < 2 * (i + 1)) return 0;
    const double len = e[2 * s->nextra + i], c = hypot(b[0] - a[0], b[1] - a[1]);
    return len > c && sqrt(len * len - c * c) / 2 > tol;
}

/* Every traced point's (u, v) at every kept row, trace by trace (NULL
 * when out of memory). */
static double *trace_uv(const plot_job *job)
{
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    double *pos = malloc((size_t)dr->nanchors * 3 * sizeof *pos + 1);
    braun_real *qr = malloc((size_t)s->n * sizeof *qr + 1);
    double *uv = malloc((size_t)dr->ntraces * (size_t)s->count * 2 * sizeof *uv + 1);
    if (!pos || !qr || !uv) {
        free(pos);
        free(qr);
        free(uv);
        return NULL;
    }
    for (long r = 0; r < s->count; r++) {
        plot_drawing_eval(dr, s->rows + (size_t)r * (size_t)s->cols + 1, qr, pos);
        for (int i = 0; i < dr->ntraces; i++) {
            const double *p = pos + 3 * dr->traces[i].anchor;
            double *o = uv + ((size_t)i * (size_t)s->count + (size_t)r) * 2;
            o[0] = p[dr->axis_u];
            o[1] = p[dr->axis_v];
        }
    }
    free(pos);
    free(qr);
    return uv;
}


void plot_svg_paths(FILE *f, const plot_job *job, const plot_canvas *cv, const char *style)
{
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    if (dr->ntraces == 0) return;
    double *uv = trace_uv(job);
    if (!uv) return;
    const double tol = PLOT_PATH_TOL_PX / cv->scale;
    for (int i = 0; i < dr->ntraces; i++) {
        const double *p = uv + (size_t)i * (size_t)s->count * 2;
        /* Polylines through the rows joined by segments that do not
         * stray, a dot at a row that joins none: a chord across the
         * swing's circle is a path the motion never took. */
        long start = 0;
        for (long r = 0; r < s->count; r++) {
            const int end = r == s->count - 1 ||
                            (job->strays[i] && plot_path_strays(s, i, r, p + 2 * r, p + 2 * r + 2, tol));
            if (!end) continue;
            if (r == start && job->strays[i]) {
                double x, y, pw[3];
                pw[dr->axis_u] = p[2 * r], pw[dr->axis_v] = p[2 * r + 1];
                pw[3 - dr->axis_u - dr->axis_v] = 0;
                plot_canvas_xy(cv, dr, pw, &x, &y);
                if (isfinite(x) && isfinite(y))
                    fprintf(f, "  <circle cx=\"%.2f\" cy=\"%.2f\" r=\"1.3\" fill=\"%s\"/>\n", x, y,
                            plot_colour(i));
            } else {
                fprintf(f, "  <polyline fill=\"none\" stroke=\"%s\" %s points=\"", plot_colour(i),
                        style);
                for (long k = start; k <= r; k++) {
                    double x, y, pw[3];
                    pw[dr->axis_u] = p[2 * k], pw[dr->axis_v] = p[2 * k + 1];
                    pw[3 - dr->axis_u - dr->axis_v] = 0;
                    plot_canvas_xy(cv, dr, pw, &x, &y);
                    if (isfinite(x) && isfinite(y)) fprintf(f, "%s%.2f,%.2f", k > start ? " " : "", x, y);
                }
                fputs("\"/>\n", f);
            }
            start = r + 1;
        }
    }
    free(uv);
}

int plot_job_resolution(plot_job *job)
{
    const plot_samples *s = job->samples;
    const plot_drawing *dr = job->drawing;
    int count = 0;
    memset(job->strays, 0, sizeof job->strays);
    if (s->nextra == 0 || !s->env || s->count < 2) return 0;
    if (job->nseries > 0) {
        /* Two pixels of the chart's value axis (about 400 px high). */
        double *pos = dr ? malloc((size_t)dr->nanchors * 3 * sizeof *pos + 1) : NULL;
        braun_real *qr = malloc((size_t)s->n * sizeof *qr + 1);
        double range[4];
        if ((dr && !pos) || !qr || plot_chart_range(job, pos, qr, range)) {
            free(pos);
            free(qr);
            return 0;
        }
        const double tol = (range[1] - range[0]) / 200;
        for (int k = 0; k < job->nseries && k < s->nextra; k++) {
            double prev = NAN;
            for (long r = 0; r < s->count; r++) {
                const double *row = s->rows + (size_t)r * (size_t)s->cols;
                const double v = series_value(job, &job->series[k], row, pos, qr);
                if (r > 0 && isfinite(prev) && isfinite(v)) {
                    const double *ep = plot_samples_env(s, r - 1);
                    if (bin_strays(ep[k], ep[s->nextra + k], prev, v, tol)) {
                        /* Rows r - 1 and r leave the line (the envelope
                         * shows what lay between them). */
                        if (!job->hide)
                            job->hide = calloc((size_t)s->count * (size_t)job->nseries, 1);
                        if (job->hide) {
                            job->hide[(size_t)(r - 1) * (size_t)job->nseries + (size_t)k] = 1;
                            job->hide[(size_t)r * (size_t)job->nseries + (size_t)k] = 1;
                        }
                        job->strays[k] = 1;
                    }
                }
                prev = v;
            }
            count += job->strays[k];
        }
        free(pos);
        free(qr);
        return count;
    }
    if (!dr || dr->ntraces == 0) return 0;
    plot_canvas cv;
    plot_canvas_fit(&cv, job);
    double *uv = trace_uv(job);
    if (!uv || !(cv.scale > 0)) {
        free(uv);
        return 0;
    }
    const double tol = PLOT_PATH_TOL_PX / cv.scale;
    for (int i = 0; i < dr->ntraces; i++) {
        const double *p = uv + (size_t)i * (size_t)s->count * 2;
        for (long r = 0; r + 1 < s->count && !job->strays[i]; r++)
            job->strays[i] = plot_path_strays(s, i, r, p + 2 * r, p + 2 * r + 2, tol);
        count += job->strays[i];
    }
    free(uv);
    return count;
}

/* A scale bar of 1, 2 or 5 times a power of ten metres, about a fifth of
 * the width, at the lower right. */
void plot_svg_scale_bar(FILE *f, const plot_canvas *cv)
{
    const double len = scale_bar_length(cv);
    if (!(len > 0)) return;
    const double x1 = cv->width - cv->margin, x0 = x1 - len * cv->scale;
    const double y = cv->height - 14;
    line(f, "  ", x0, y, x1, y, "stroke=\"#222222\" stroke-width=\"2\"");
    line(f, "  ", x0, y - 4, x0, y + 4, "stroke=\"#222222\" stroke-width=\"1.5\"");
    line(f, "  ", x1, y - 4, x1, y + 4, "stroke=\"#222222\" stroke-width=\"1.5\"");
    fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"12\" "
               "text-anchor=\"middle\">%g m</text>\n", (x0 + x1) / 2, y - 6, len);
}

void plot_svg_caption(FILE *f, const plot_job *job, const plot_canvas *cv)
{
    for (int k = 0; k < cv->caption_lines; k++) {
        char text[1024];
        plot_caption_wrap(job->caption, cv->caption_width, CAPTION_FONT, k, text, sizeof text);
        fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"13\">",
                cv->margin, cv->height - 12 - 16.0 * (cv->caption_lines - 1 - k));
        plot_xml_text(f, text);
        fputs("</text>\n", f);
    }
    const plot_drawing *dr = job->drawing;
    for (int i = 0; dr && i < dr->ntraces; i++) {
        fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"12\" "
                   "fill=\"%s\">", cv->margin, cv->margin + 14.0 * i, plot_colour(i));
        plot_xml_text(f, dr->traces[i].name);
        fputs("</text>\n", f);
    }
}

void plot_svg_header(FILE *f, double width, double height, const char *title, int inline_html)
{
    /* Inline in HTML the namespace is implied (and the page names no URL). */
    fprintf(f, "<svg%s version=\"1.1\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\">\n",
            inline_html ? "" : " xmlns=\"http://www.w3.org/2000/svg\"", width, height, width, height);
    fputs("  <title>", f);
    plot_xml_text(f, title);
    fputs("</title>\n", f);
    fprintf(f, "  <rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n",
            width, height);
}

int plot_write_svg(FILE *f, const plot_job *job)
{
    if (job->nseries > 0 || !job->drawing) {
        fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", f);
        return plot_svg_chart(f, job, CANVAS_WIDTH, 480, 0);
    }
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    plot_canvas cv;
    plot_canvas_fit(&cv, job);
    double *pos = malloc((size_t)dr->nanchors * 3 * sizeof *pos);
    braun_real *qr = malloc((size_t)s->n * sizeof *qr);
    if (!pos || !qr) {
        free(pos);
        free(qr);
        braun_cli_error("out of memory");
        return -1;
    }
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", f);
    plot_svg_header(f, cv.width, cv.height, job->caption, 0);
    const long frames = job->frames < s->count ? job->frames : s->count;
    plot_drawing_eval(dr, s->rows + 1, qr, pos);
    fputs("  <g id=\"ground\">\n", f);
    plot_svg_items(f, job, &cv, pos, s->rows[0], PLOT_LAYER_UNDER, "    ");
    fputs("  </g>\n", f);
    plot_svg_paths(f, job, &cv, "stroke-width=\"1.5\" stroke-opacity=\"0.9\"");
    /* Earlier configurations fainter: opacity 0.2 ... 1. */
    for (long k = 0; k < frames; k++) {
        const long r = plot_frame_row(job, k);
        const double *row = s->rows + (size_t)r * (size_t)s->cols;
        plot_drawing_eval(dr, row + 1, qr, pos);
        const double op = frames > 1 ? 0.2 + 0.8 * (double)k / (double)(frames - 1) : 1;
        char t[BRAUN_CLI_NUMBER_SIZE];
        fprintf(f, "  <g class=\"frame\" data-t=\"%s\" opacity=\"%.3f\">\n",
                braun_cli_number(row[0], t), op);
        /* Motors and torques once, on the newest configuration. */
        plot_svg_items(f, job, &cv, pos, row[0],
                       k == frames - 1 ? PLOT_LAYER_ALL_MOVING : PLOT_LAYER_MOVING,
                       "    ");
        for (int i = 0; i < dr->ntraces; i++) {
            double x, y;
            plot_canvas_xy(&cv, dr, pos + 3 * dr->traces[i].anchor, &x, &y);
            fprintf(f, "    <circle cx=\"%.2f\" cy=\"%.2f\" r=\"2.8\" fill=\"%s\"/>\n", x, y,
                    plot_colour(i));
        }
        fputs("  </g>\n", f);
    }
    plot_drawing_eval(dr, s->rows + 1, qr, pos);
    plot_svg_items(f, job, &cv, pos, s->rows[0], PLOT_LAYER_MARKS, "  ");
    plot_svg_caption(f, job, &cv);
    plot_svg_scale_bar(f, &cv);
    fputs("</svg>\n", f);
    free(pos);
    free(qr);
    return 0;
}

/* ------------------------------------------------------------ the chart */
/* Ticks at 1, 2 or 5 times a power of ten, about six over the range. */
double plot_tick_step(double lo, double hi)
{
    const double want = (hi - lo) / 6;
    if (!(want > 0) || !isfinite(want)) return 1;
    const double p = pow(10, floor(log10(want)));
    return want / p >= 5 ? 5 * p : want / p >= 2 ? 2 * p : p;
}

/* A tick's value: an ulp off zero is zero. */
static double tick_value(double first, double step, long i)
{
    const double v = first + (double)i * step;
    return fabs(v) < 1e-12 * step ? 0.0 : v;
}

int plot_tick_digits(double first, double step, long n)
{
    /* Four digits read 999.9 for 999.90 ... 999.98 and 1e+08 for every
     * tick near 1e8: as many as consecutive ticks need to differ. */
    for (int p = 4; p < 17; p++) {
        int same = 0;
        char a[40], b[40];
        snprintf(a, sizeof a, "%.*g", p, tick_value(first, step, 0));
        for (long i = 1; i <= n && !same; i++) {
            snprintf(b, sizeof b, "%.*g", p, tick_value(first, step, i));
            same = strcmp(a, b) == 0;
            memcpy(a, b, sizeof a);
        }
        if (!same) return p;
    }
    return 17;
}

/* Value of series k at row r. */
static double series_value(const plot_job *job, const plot_series *sr, const double *row,
                           double *pos, braun_real *qr)
{
    if (sr->column >= 0 || !pos || !job->drawing) return sr->column >= 0 ? row[sr->column] : NAN;
    plot_drawing_eval(job->drawing, row + 1, qr, pos);
    return pos[3 * sr->anchor + sr->axis];
}

int plot_chart_range(const plot_job *job, double *pos, braun_real *qr, double range[4])
{
    const plot_samples *s = job->samples;
    double t0 = s->rows[0], t1 = s->rows[(size_t)(s->count - 1) * (size_t)s->cols];
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int k = 0; k < job->nseries; k++)
        for (long r = 0; r < s->count; r++) {
            const double y = series_value(job, &job->series[k], s->rows + (size_t)r * (size_t)s->cols, pos, qr);
            if (isfinite(y) && y < lo) lo = y;
            if (isfinite(y) && y > hi) hi = y;
        }
    if (!(lo <= hi)) lo = hi = 0;
    if (hi - lo < 1e-12 * (fabs(lo) + fabs(hi)) || hi == lo) lo -= 0.5 + fabs(lo) * 0.1, hi += 0.5 + fabs(hi) * 0.1;
    if (!(t1 > t0)) t1 = t0 + 1;
    const double ty = plot_tick_step(lo, hi);
    lo = floor(lo / ty) * ty, hi = ceil(hi / ty) * ty;
    range[0] = lo, range[1] = hi, range[2] = t0, range[3] = t1;
    /* A span past the largest double (1e308 and -1e308) would place every
     * point at NaN. */
    return isfinite(hi - lo) && hi > lo && isfinite(t1 - t0) && t1 > t0 ? 0 : -1;
}

int plot_svg_chart(FILE *f, const plot_job *job, double width, double height, int inline_html)
{
    const plot_samples *s = job->samples;
    const plot_drawing *dr = job->drawing;
    double *pos = dr ? malloc((size_t)dr->nanchors * 3 * sizeof *pos) : NULL;
    braun_real *qr = malloc((size_t)s->n * sizeof *qr);
    if ((dr && !pos) || !qr) {
        free(pos);
        free(qr);
        braun_cli_error("out of memory");
        return -1;
    }
    /* The caption on its own lines under the time axis's label (it ran
     * over "t [s]" at the right). */
    const int lines = plot_caption_wrap(job->caption, width - 20, 11, 0, NULL, 0);
    const double mr = 20, mt = 20 + 16.0 * job->nseries, mb = 50 + 14.0 * lines;
    double range[4];
    if (plot_chart_range(job, pos, qr, range)) {
        free(pos);
        free(qr);
        braun_cli_error("--plot: the values or times span more than a double holds");
        return -1;
    }
    const double lo = range[0], hi = range[1];
    const double t0 = range[2], t1 = range[3];
    const double ty = plot_tick_step(lo, hi), tt = plot_tick_step(t0, t1);
    const long nv = lround((hi - lo) / ty);
    const double first = ceil(t0 / tt) * tt;
    const long nt = (long)floor((t1 - first) / tt + 1e-9);
    const int dv = plot_tick_digits(lo, ty, nv), dt = plot_tick_digits(first, tt, nt);
    /* Room on the left for the longest value label (about 7 px a digit). */
    size_t widest = 0;
    for (long i = 0; i <= nv; i++) {
        char num[40];
        const size_t w = (size_t)snprintf(num, sizeof num, "%.*g", dv, tick_value(lo, ty, i));
        if (w > widest) widest = w;
    }
    const double ml = 12 + 7.0 * (double)widest > 70 ? 12 + 7.0 * (double)widest : 70;
    const double pw = width - ml - mr, ph = height - mt - mb;
#define X(t) (ml + ((t) - t0) / (t1 - t0) * pw)
#define Y(v) (mt + ph - ((v) - lo) / (hi - lo) * ph)
    plot_svg_header(f, width, height, job->caption, inline_html);
    fprintf(f, "  <rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"none\" "
               "stroke=\"#222222\"/>\n", ml, mt, pw, ph);
    for (long i = 0; i <= nv; i++) {
        const double v = lo + (double)i * ty, y = Y(v);
        char num[40];
        snprintf(num, sizeof num, "%.*g", dv, tick_value(lo, ty, i));
        line(f, "  ", ml, y, ml + pw, y, "stroke=\"#dddddd\" stroke-width=\"1\"");
        fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"12\" "
                   "text-anchor=\"end\">%s</text>\n", ml - 6, y + 4, num);
    }
    for (long i = 0; i <= nt; i++) {
        const double t = first + (double)i * tt, x = X(t);
        line(f, "  ", x, mt + ph, x, mt + ph + 5, "stroke=\"#222222\" stroke-width=\"1\"");
        fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"12\" "
                   "text-anchor=\"middle\">%.*g</text>\n", x, mt + ph + 18, dt, tick_value(first, tt, i));
    }
    fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"13\" "
               "text-anchor=\"middle\">t [s]</text>\n", ml + pw / 2, mt + ph + 36);
    /* A series faster than the kept states resolve: its envelope, each
     * bin's least to greatest value over the bin's time, shaded under the
     * line (as an oscilloscope's), so no swing is drawn that did not
     * happen. */
    for (int k = 0; k < job->nseries; k++) {
        if (!job->strays[k]) continue;
        fprintf(f, "  <polygon class=\"envelope\" fill=\"%s\" fill-opacity=\"0.35\" "
                   "stroke=\"none\" points=\"", plot_colour(k));
        for (int side = 0; side < 2; side++)
            for (long i = 0; i < s->count; i++) {
                const long r = side ? s->count - 1 - i : i;
                const double *e = plot_samples_env(s, r);
                const double v = e[side ? k : s->nextra + k];
                const double ta = s->rows[(size_t)r * (size_t)s->cols];
                const double tb = r + 1 < s->count ? s->rows[(size_t)(r + 1) * (size_t)s->cols] : ta;
                if (!isfinite(v)) continue;
                fprintf(f, "%s%.2f,%.2f %.2f,%.2f", side || i ? " " : "", X(side ? tb : ta), Y(v),
                        X(side ? ta : tb), Y(v));
            }
        fputs("\"/>\n", f);
    }
    for (int k = 0; k < job->nseries; k++) {
        const plot_series *sr = &job->series[k];
        /* The line joins the kept rows, but not across a segment the
         * envelope shades (job->hide): one polyline per run of rows. */
        int open = 0;
        for (long r = 0; r < s->count; r++) {
            const double *row = s->rows + (size_t)r * (size_t)s->cols;
            const double y = series_value(job, sr, row, pos, qr);
            const int shown = isfinite(y) && !(job->hide && job->hide[(size_t)r * (size_t)job->nseries + (size_t)k]);
            if (shown && !open) {
                fprintf(f, "  <polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\" points=\"",
                        plot_colour(k));
                open = 1;
                fprintf(f, "%.2f,%.2f", X(row[0]), Y(y));
            } else if (shown) {
                fprintf(f, " %.2f,%.2f", X(row[0]), Y(y));
            } else if (open && !isfinite(y)) {
                continue; /* a missing value (traj_err) does not break the line, as before */
            } else if (open) {
                fputs("\"/>\n", f);
                open = 0;
            }
        }
        if (open) fputs("\"/>\n", f);
        fprintf(f, "  <text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"13\" "
                   "fill=\"%s\">", ml, 16.0 + 16.0 * k, plot_colour(k));
        plot_xml_text(f, sr->label);
        if (sr->unit) {
            fputs(" [", f);
            plot_xml_text(f, sr->unit);
            fputc(']', f);
        }
        fputs("</text>\n", f);
    }
#undef X
#undef Y
    for (int k = 0; k < lines; k++) {
        char text[1024];
        plot_caption_wrap(job->caption, width - 20, 11, k, text, sizeof text);
        fprintf(f, "  <text x=\"10\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"11\" "
                   "fill=\"#555555\">", height - 10 - 14.0 * (lines - 1 - k));
        plot_xml_text(f, text);
        fputs("</text>\n", f);
    }
    fputs("</svg>\n", f);
    free(pos);
    free(qr);
    return 0;
}
