/* Whether a picture can hold what `braun plot` draws, checked before a
 * byte is written: every number the writers place must be finite. A value
 * that is not (a --traj CSV's nan or inf is refused when read) can still
 * come from finite ones: coordinates at 1e308 and -1e308 span inf, and the
 * canvas's scale, the chart's ticks and each screen position would be NaN.
 * Such a picture is refused with one message instead of written. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

/* The anchors an item places (the others of a, b, c are unused). */
static int item_anchors(const plot_item *it, int *a)
{
    int k = 0;
    a[k++] = it->a;
    if (it->kind == PLOT_BAR || it->kind == PLOT_LINK || it->kind == PLOT_GUIDE ||
        it->kind == PLOT_BLADE || it->kind == PLOT_SPRING || it->kind == PLOT_BLOCK)
        a[k++] = it->b;
    if (it->kind == PLOT_BLOCK) a[k++] = it->c;
    return k;
}

/* Every anchor drawn, at every state kept (paths use them all), lands on a
 * finite screen position of the canvas. */
static int drawing_fits(const plot_job *job)
{
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    plot_canvas cv;
    plot_canvas_fit(&cv, job);
    /* Too narrow (points 1e-310 apart: the canvas over that span
     * overflows, scale inf) was called "more than the range of a double",
     * as too wide (1e308 and -1e308: scale 0 or NaN) is. */
    const int narrow = cv.scale > 0 && !isfinite(cv.scale);
    if (!(isfinite(cv.scale) && cv.scale > 0 && isfinite(cv.u0) && isfinite(cv.v0) &&
          isfinite(cv.height))) {
        if (narrow)
            return braun_cli_error("the drawing's points span less than a double's smallest normal "
                                   "number (%g): its scale would overflow; nothing written", DBL_MIN);
        return braun_cli_error("the drawing's points span more than the range of a double (its "
                               "scale and positions would be NaN): nothing written");
    }
    double *pos = malloc((size_t)dr->nanchors * 3 * sizeof *pos + 1);
    braun_real *qr = malloc((size_t)s->n * sizeof *qr + 1);
    char *use = calloc((size_t)dr->nanchors + 1, 1);
    if (!pos || !qr || !use) {
        free(pos);
        free(qr);
        free(use);
        return braun_cli_error("out of memory");
    }
    for (int i = 0; i < dr->nitems; i++) {
        int a[3];
        const int k = item_anchors(&dr->items[i], a);
        for (int j = 0; j < k; j++) use[a[j]] = 1;
        if (dr->items[i].kind == PLOT_OUTLINE)
            for (int j = 0; j < dr->items[i].count; j++) use[dr->items[i].a + j] = 1;
    }
    for (int i = 0; i < dr->ntraces; i++) use[dr->traces[i].anchor] = 1;
    int rc = 0;
    for (long r = 0; !rc && r < s->count; r++) {
        const double *row = s->rows + (size_t)r * (size_t)s->cols;
        plot_drawing_eval(dr, row + 1, qr, pos);
        for (int i = 0; !rc && i < dr->nanchors; i++) {
            double x, y;
            if (!use[i]) continue;
            plot_canvas_xy(&cv, dr, pos + 3 * i, &x, &y);
            if (!isfinite(x) || !isfinite(y))
                rc = braun_cli_error("at t = %g a point of the drawing lies at (%g, %g, %g), "
                                     "beyond what the picture can place: nothing written", row[0],
                                     pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
        }
    }
    free(pos);
    free(qr);
    free(use);
    return rc;
}

int plot_job_fits(const plot_job *job)
{
    if (job->nseries == 0 && job->drawing) return drawing_fits(job);
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    double *pos = dr ? malloc((size_t)dr->nanchors * 3 * sizeof *pos + 1) : NULL;
    braun_real *qr = malloc((size_t)s->n * sizeof *qr + 1);
    double range[4];
    int rc = 0;
    if ((dr && !pos) || !qr) rc = braun_cli_error("out of memory");
    else if (plot_chart_range(job, pos, qr, range))
        rc = braun_cli_error("--plot: the values (%g ... %g) or the times (%g ... %g s) span "
                             "more than the range of a double: nothing written", range[0],
                             range[1], range[2], range[3]);
    free(pos);
    free(qr);
    return rc;
}
