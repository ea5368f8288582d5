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
    /* At most 256 MB of rows (the grid's and the fine ones), whatever
     * --samples asks. */
    const double most = 128e6 / (8.0 * s->cols);
    if ((double)cap > most) cap = (long)most;
    if (cap < 2) cap = 2;
    s->cap = cap;
    s->from = from;
    s->to = to;
    s->step = to > from ? (to - from) / (double)(cap - 1) : 0;
    s->next = from;
    s->rows = malloc((size_t)cap * (size_t)s->cols * sizeof *s->rows);
    s->last = malloc((size_t)s->cols * sizeof *s->last);
    s->fine = malloc((size_t)cap * (size_t)s->cols * sizeof *s->fine);
    s->fine_next = from;
    if (!s->rows || !s->last || !s->fine) {
        plot_samples_free(s);
        return -1;
    }
    return 0;
}

/* The fine rows: every state fine_step apart; full, every other dropped and
 * the spacing doubled (they stay even in time, between cap/2 and cap). */
static void fine_add(plot_samples *s, const double *row)
{
    const size_t w = (size_t)s->cols;
    const double t = row[0];
    if (t < s->fine_next) return;
    if (s->fine_count >= s->cap - 1) {
        long k = 0;
        for (long i = 0; i < s->fine_count; i += 2, k++)
            memmove(s->fine + (size_t)k * w, s->fine + (size_t)i * w, w * sizeof *s->fine);
        s->fine_count = k;
        const double span = s->fine[(size_t)(k - 1) * w] - s->fine[0];
        s->fine_step = k > 1 ? span / (double)(k - 1) : 0;
        s->fine_next = s->fine[(size_t)(k - 1) * w] + s->fine_step;
        if (t < s->fine_next) return;
    }
    memcpy(s->fine + (size_t)s->fine_count * w, row, w * sizeof *row);
    s->fine_count++;
    s->fine_next = t + s->fine_step;
}

void plot_samples_add(plot_samples *s, const double *row)
{
    const double t = row[0];
    if (t < s->from || !s->rows) return;
    memcpy(s->last, row, (size_t)s->cols * sizeof *row);
    s->have_last = 1;
    if (s->fine) fine_add(s, row);
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
    /* A run that stopped before the window's end reached fewer grid times
     * than it has fine rows: those are drawn. */
    if (s->fine && s->fine_count > s->count) {
        double *tmp = s->rows;
        s->rows = s->fine;
        s->fine = tmp;
        s->count = s->fine_count;
        s->fine_count = 0;
    }
    const double *prev = s->count ? s->rows + (size_t)(s->count - 1) * (size_t)s->cols : NULL;
    if (prev && prev[0] == s->last[0]) return;
    memcpy(s->rows + (size_t)s->count * (size_t)s->cols, s->last, (size_t)s->cols * sizeof *s->last);
    s->count++;
}

void plot_samples_free(plot_samples *s)
{
    free(s->rows);
    free(s->last);
    free(s->fine);
    s->rows = s->last = s->fine = NULL;
    s->fine_count = 0;
    s->count = 0;
}
