/* The progress line of a run on stderr: time reached, steps, rate and the
 * time left, for a run that takes a while. On a terminal one line rewritten
 * in place (carriage return, erase to the end of line) at most ten times a
 * second and erased at the end; forced onto a file or pipe (--progress) a
 * line per second, so that logs stay readable. The first report comes after
 * the first call and the last at the end, so even a short run shows one.
 * POSIX (isatty, CLOCK_MONOTONIC), confined to this file and cli_clock.c. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "braun_cli.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int braun_cli_stderr_is_terminal(void) { return isatty(STDERR_FILENO); }

void braun_cli_progress_begin(braun_cli_progress *p, int enabled, const char *name,
                              const char *phase, double t0, double t_end)
{
    memset(p, 0, sizeof *p);
    p->enabled = enabled;
    p->terminal = enabled && braun_cli_stderr_is_terminal();
    p->name = name;
    p->phase = phase;
    p->t0 = t0;
    p->t_end = t_end;
    p->wall0 = now();
    p->last = -1e300;
}

/* "12.3k" for rates and counts a person reads. */
static const char *human(double x, char *buf, size_t size)
{
    if (x >= 1e9) snprintf(buf, size, "%.3gG", x / 1e9);
    else if (x >= 1e6) snprintf(buf, size, "%.3gM", x / 1e6);
    else if (x >= 1e4) snprintf(buf, size, "%.3gk", x / 1e3);
    else snprintf(buf, size, "%.0f", x);
    return buf;
}

static const char *duration(double s, char *buf, size_t size)
{
    if (!(s >= 0) || !isfinite(s)) snprintf(buf, size, "?");
    else if (s < 60) snprintf(buf, size, "%.0f s", ceil(s));
    else if (s < 3600) snprintf(buf, size, "%.0f min %02.0f s", floor(s / 60), fmod(floor(s), 60));
    else snprintf(buf, size, "%.0f h %02.0f min", floor(s / 3600), fmod(floor(s / 60), 60));
    return buf;
}

static void show(braun_cli_progress *p, double t, long steps, double wall)
{
    const double elapsed = wall - p->wall0, span = p->t_end - p->t0;
    const double frac = span > 0 ? (t - p->t0) / span : 1;
    char rate[32], left[32], count[32];
    human(elapsed > 0 ? (double)steps / elapsed : 0, rate, sizeof rate);
    human((double)steps, count, sizeof count);
    /* The time left at the simulated-time rate so far. */
    duration(frac > 0 ? elapsed * (1 - frac) / frac : NAN, left, sizeof left);
    /* The scene's name escaped: a CR or ESC in it would rewrite the line. */
    fprintf(stderr, "%sbraun: ", p->terminal ? "\r" : "");
    braun_cli_put_text(stderr, p->name);
    fprintf(stderr, ": t = %.6g of %.6g s (%.0f%%), %s steps, %s steps/s, %s left%s%s%s",
            t, p->t_end, 100 * frac, count, rate, left,
            p->phase ? " [" : "", p->phase ? p->phase : "", p->phase ? "]" : "");
    fputs(p->terminal ? "\033[K" : "\n", stderr);
    fflush(stderr);
    p->shown = 1;
}

void braun_cli_progress_update(braun_cli_progress *p, double t, long steps)
{
    if (!p->enabled) return;
    const double wall = now();
    if (wall - p->last < (p->terminal ? 0.1 : 1.0)) return;
    p->last = wall;
    show(p, t, steps, wall);
}

void braun_cli_progress_end(braun_cli_progress *p, double t, long steps)
{
    if (!p->enabled) return;
    if (p->terminal) {
        if (p->shown) fputs("\r\033[K", stderr);
    } else {
        show(p, t, steps, now());
    }
    fflush(stderr);
}
