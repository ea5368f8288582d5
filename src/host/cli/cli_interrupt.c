/* SIGINT (Ctrl-C) and SIGTERM during a run: the run stops at its next
 * reported state and keeps what it has — the CSV's rows up to that state,
 * each whole, and a summary that says it stopped — instead of dying in the
 * middle of a line with the buffered rows lost. A second signal ends the
 * process as before — but not one within BRAUN_CLI_SIGNAL_COPY seconds of
 * the first: GNU timeout sends its signal to the child and again to the
 * child's process group, microseconds apart, and that copy killed the
 * tool in the middle of a row a third of the time. A signal the caller
 * ignores (SIGINT of a background job, nohup) stays ignored. The flag is
 * the tool's, not the library's: the core has no global state, and the
 * run stops through its output callback (BRAUN_STOPPED). The POSIX
 * feature macro for sigaction and clock_gettime (async-signal-safe). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <signal.h>
#include <string.h>
#include <time.h>

#include "braun_cli.h"

#define BRAUN_CLI_SIGNAL_COPY 0.25

static volatile sig_atomic_t caught;
static struct timespec caught_at;
static struct sigaction old_int, old_term;
static int have_int, have_term;

/* Installed with sigaction and no SA_RESETHAND: signal() under a POSIX
 * feature macro has System V semantics, which reset the handler at the
 * first delivery — the copy then found the default. */
static void on_signal(int sig)
{
    struct timespec now;
    const int clock_ok = clock_gettime(CLOCK_MONOTONIC, &now) == 0;
    if (!caught) {
        if (clock_ok) caught_at = now;
        else caught_at.tv_sec = -1; /* no time: a second signal is a second request */
        caught = sig;
        return;
    }
    if (clock_ok && caught_at.tv_sec >= 0) {
        const double since = (double)(now.tv_sec - caught_at.tv_sec) +
                             1e-9 * (double)(now.tv_nsec - caught_at.tv_nsec);
        if (since >= 0 && since < BRAUN_CLI_SIGNAL_COPY) return; /* the same request again */
    }
    /* A second request: the process ends now, by this signal. */
    struct sigaction dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, NULL);
    raise(sig);
}

/* The handler for sig, unless the signal is ignored; *old: what it was.
 * 1 when *old is to be restored. */
static int catch_unless_ignored(int sig, struct sigaction *old)
{
    if (sigaction(sig, NULL, old) != 0 || old->sa_handler == SIG_IGN) return 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    return sigaction(sig, &sa, NULL) == 0;
}

void braun_cli_interrupt_begin(void)
{
    caught = 0;
    have_int = catch_unless_ignored(SIGINT, &old_int);
    have_term = catch_unless_ignored(SIGTERM, &old_term);
}

void braun_cli_interrupt_end(void)
{
    if (have_int) sigaction(SIGINT, &old_int, NULL);
    if (have_term) sigaction(SIGTERM, &old_term, NULL);
    have_int = have_term = 0;
}

int braun_cli_interrupted(void)
{
    return caught;
}

const char *braun_cli_signal_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}
