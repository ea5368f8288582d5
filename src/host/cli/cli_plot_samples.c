/* The states `braun plot` keeps: rows of the trajectory CSV's columns,
 * evenly in time over the window drawn (--from to the end), at most cap of
 * them (--samples), and always the last. A run of 10^7 steps keeps 2000
 * rows, not 10^7. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

/* Doubles per row of the envelope: lows, highs, lengths travelled. */
static size_t env_width(const plot_samples *s)
{
    return 2 * (size_t)s->nextra + (s->paired ? (size_t)s->nextra / 2 : 0);
}

int plot_samples_init(plot_samples *s, int n, long cap, double from, double to)
{
    /* The envelope's values are the caller's choice: kept. */
    const int nextra = s->nextra, paired = s->paired;
    void (*extra)(void *, const double *, double *) = s->extra;
    void *extra_ctx = s->extra_ctx;
    plot_samples_free(s);
    memset(s, 0, sizeof *s);
    s->nextra = extra && nextra > 0 ? nextra : 0;
    s->paired = s->nextra && paired;
    s->extra = extra;
    s->extra_ctx = extra_ctx;
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
    const size_t m = (size_t)s->nextra;
    if (m) {
        s->env = malloc((size_t)cap * env_width(s) * sizeof *s->env);
        s->fine_env = malloc((size_t)cap * env_width(s) * sizeof *s->fine_env);
        s->ex = malloc(m * sizeof *s->ex);
        s->last_ex = malloc(m * sizeof *s->last_ex);
    }
    if (!s->rows || !s->last || !s->fine ||
        (m && (!s->env || !s->fine_env || !s->ex || !s->last_ex))) {
        plot_samples_free(s);
        return -1;
    }
    return 0;
}

/* A bin's envelope: set to the values of one state (nothing travelled),
 * or widened by them. */
static void env_set(const plot_samples *s, double *env, const double *ex)
{
    if (!env) return;
    memcpy(env, ex, (size_t)s->nextra * sizeof *ex);
    memcpy(env + s->nextra, ex, (size_t)s->nextra * sizeof *ex);
    if (s->paired)
        for (int j = 0; j < s->nextra / 2; j++) env[2 * s->nextra + j] = 0;
}

static void env_widen(const plot_samples *s, double *env, const double *lo, const double *hi)
{
    if (!env) return;
    for (int j = 0; j < s->nextra; j++) {
        if (lo[j] < env[j] || isnan(env[j])) env[j] = lo[j];
        if (hi[j] > env[s->nextra + j] || isnan(env[s->nextra + j])) env[s->nextra + j] = hi[j];
    }
}

/* A bin joined by the next: its envelope and the length travelled. */
static void env_join(const plot_samples *s, double *env, const double *next)
{
    if (!env) return;
    env_widen(s, env, next, next + s->nextra);
    if (s->paired)
        for (int j = 0; j < s->nextra / 2; j++) env[2 * s->nextra + j] += next[2 * s->nextra + j];
}

/* The step from the previous state to this one, added to the bin it ends. */
static void env_travel(const plot_samples *s, double *env, const double *from, const double *to)
{
    if (!env || !s->paired) return;
    for (int j = 0; j < s->nextra / 2; j++) {
        const double d = hypot(to[2 * j] - from[2 * j], to[2 * j + 1] - from[2 * j + 1]);
        if (isfinite(d)) env[2 * s->nextra + j] += d;
    }
}

static double *env_at(double *env, const plot_samples *s, long r)
{
    return env ? env + (size_t)r * env_width(s) : NULL;
}

const double *plot_samples_env(const plot_samples *s, long r)
{
    return s->nextra && s->env && r >= 0 && r < s->count ? env_at(s->env, s, r) : NULL;
}

/* The fine rows: every state fine_step apart; full, every other dropped and
 * the spacing doubled (they stay even in time, between cap/2 and cap), the
 * dropped row's bin joined to the one before. */
static void fine_add(plot_samples *s, const double *row, const double *ex)
{
    const size_t w = (size_t)s->cols;
    const double t = row[0];
    if (s->fine_count > 0 && s->have_prev)
        env_travel(s, env_at(s->fine_env, s, s->fine_count - 1), s->last_ex, ex);
    if (s->fine_count > 0 && t < s->fine_next) {
        env_widen(s, env_at(s->fine_env, s, s->fine_count - 1), ex, ex);
        return;
    }
    if (s->fine_count >= s->cap - 1) {
        long k = 0;
        for (long i = 0; i < s->fine_count; i += 2, k++) {
            memmove(s->fine + (size_t)k * w, s->fine + (size_t)i * w, w * sizeof *s->fine);
            double *e = env_at(s->fine_env, s, k);
            if (!e) continue;
            memmove(e, env_at(s->fine_env, s, i), env_width(s) * sizeof *e);
            if (i + 1 < s->fine_count) env_join(s, e, env_at(s->fine_env, s, i + 1));
        }
        s->fine_count = k;
        const double span = s->fine[(size_t)(k - 1) * w] - s->fine[0];
        s->fine_step = k > 1 ? span / (double)(k - 1) : 0;
        s->fine_next = s->fine[(size_t)(k - 1) * w] + s->fine_step;
        if (t < s->fine_next) {
            env_widen(s, env_at(s->fine_env, s, k - 1), ex, ex);
            return;
        }
    }
    memcpy(s->fine + (size_t)s->fine_count * w, row, w * sizeof *row);
    env_set(s, env_at(s->fine_env, s, s->fine_count), ex);
    s->fine_count++;
    s->fine_next = t + s->fine_step;
}

void plot_samples_add(plot_samples *s, const double *row)
{
    const double t = row[0];
    if (t < s->from || !s->rows) return;
    memcpy(s->last, row, (size_t)s->cols * sizeof *row);
    s->have_prev = s->have_last;
    s->have_last = 1;
    if (s->nextra) s->extra(s->extra_ctx, row, s->ex);
    if (s->fine) fine_add(s, row, s->ex);
    if (s->count > 0 && s->have_prev) env_travel(s, env_at(s->env, s, s->count - 1), s->last_ex, s->ex);
    if (s->nextra) memcpy(s->last_ex, s->ex, (size_t)s->nextra * sizeof *s->ex);
    /* Keep the first row at or after each of cap evenly spaced times; a
     * jump over several of them (large steps) keeps one row. A state not
     * kept widens the bin of the row before it. */
    if (t < s->next || s->count >= s->cap - 1) {
        if (s->count > 0) env_widen(s, env_at(s->env, s, s->count - 1), s->ex, s->ex);
        return;
    }
    memcpy(s->rows + (size_t)s->count * (size_t)s->cols, row, (size_t)s->cols * sizeof *row);
    env_set(s, env_at(s->env, s, s->count), s->ex);
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
        tmp = s->env;
        s->env = s->fine_env;
        s->fine_env = tmp;
        s->count = s->fine_count;
        s->fine_count = 0;
    }
    const double *prev = s->count ? s->rows + (size_t)(s->count - 1) * (size_t)s->cols : NULL;
    if (prev && prev[0] == s->last[0]) return;
    memcpy(s->rows + (size_t)s->count * (size_t)s->cols, s->last, (size_t)s->cols * sizeof *s->last);
    env_set(s, env_at(s->env, s, s->count), s->last_ex);
    s->count++;
}

void plot_samples_free(plot_samples *s)
{
    free(s->rows);
    free(s->last);
    free(s->fine);
    free(s->env);
    free(s->fine_env);
    free(s->ex);
    free(s->last_ex);
    s->rows = s->last = s->fine = NULL;
    s->env = s->fine_env = s->ex = s->last_ex = NULL;
    s->fine_count = 0;
    s->count = 0;
}
