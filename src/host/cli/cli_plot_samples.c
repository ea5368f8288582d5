/* The states `braun plot` keeps: rows of the trajectory CSV's columns,
 * evenly in time over the window drawn (--from to the end), at most cap of
 * them (--samples), and always the last. A run of 10^7 steps keeps 2000
 * rows, not 10^7. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

int plot_samples_init(plot_samples *s, int n, long cap, double from, double to)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->cols = braun_cli_column_count(n);
    /* At most 256 MB of rows, whatever --samples asks. */
    const double most = 256e6 / (8.0 * s->cols);
    if ((double)cap > most) cap = (long)most;
    if (cap < 2) cap = 2;
    s->cap = cap;
    s->from = from;
    s->to = to;
    s->step = to > from ? (to - from) / (double)(cap - 1) : 0;
    s->next = from;
    s->rows = malloc((size_t)cap * (size_t)s->cols * sizeof *s->rows);
    s->last = malloc((size_t)s->cols * sizeof *s->last);
    if (!s->rows || !s->last) {
        plot_samples_free(s);
        return -1;
    }
    return 0;
}

void plot_samples_add(plot_samples *s, const double *row)
{
    const double t = row[0];
    if (t < s->from || !s->rows) return;
    memcpy(s->last, row, (size_t)s->cols * sizeof *row);
    s->have_last = 1;
    /* Keep the first row at or after each of cap evenly spaced times; a
     * jump over several of them (large steps) keeps one row. */
    if (t < s->next || s->count >= s->cap - 1) return;
    memcpy(s->rows + (size_t)s->count * (size_t)s->cols, row, (size_t)s->cols * sizeof *row);
    s->count++;
    if (s->step > 0) s->next = s->from + (floor((t - s->from) / s->step) + 1) * s->step;
    else s->next = HUGE_VAL;
}

void plot_samples_finish(plot_samples *s)
{
    if (!s->have_last || !s->rows) return;
    const double *prev = s->count ? s->rows + (size_t)(s->count - 1) * (size_t)s->cols : NULL;
    if (prev && prev[0] == s->last[0]) return;
    memcpy(s->rows + (size_t)s->count * (size_t)s->cols, s->last, (size_t)s->cols * sizeof *s->last);
    s->count++;
}

void plot_samples_free(plot_samples *s)
{
    free(s->rows);
    free(s->last);
    s->rows = s->last = NULL;
    s->count = 0;
}
