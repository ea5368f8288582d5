/* SIGINT (Ctrl-C) and SIGTERM during a run: the run stops at its next
 * reported state and keeps what it has — the CSV's rows up to that state,
 * each whole, and a summary that says it stopped — instead of dying in the
 * middle of a line with the buffered rows lost. A second signal ends the
 * process as before (the handler restores the default at once). A signal
 * the caller ignores (SIGINT of a background job, nohup) stays ignored.
 * The flag is the tool's, not the library's: the core has no global
 * state, and the run stops through its output callback (BRAUN_STOPPED). */
#include <signal.h>

#include "braun_cli.h"

static volatile sig_atomic_t caught;
static void (*old_int)(int) = SIG_DFL;
static void (*old_term)(int) = SIG_DFL;

static void on_signal(int sig)
{
    caught = sig;
    signal(sig, SIG_DFL);
}

/* The handler for sig, unless the signal is ignored; the old disposition. */
static void (*catch_unless_ignored(int sig))(int)
{
    void (*old)(int) = signal(sig, SIG_IGN);
    if (old != SIG_IGN && old != SIG_ERR) signal(sig, on_signal);
    return old;
}

void braun_cli_interrupt_begin(void)
{
    caught = 0;
    old_int = catch_unless_ignored(SIGINT);
    old_term = catch_unless_ignored(SIGTERM);
}

void braun_cli_interrupt_end(void)
{
    if (old_int != SIG_ERR) signal(SIGINT, old_int);
    if (old_term != SIG_ERR) signal(SIGTERM, old_term);
}

int braun_cli_interrupted(void)
{
    return caught;
}

const char *braun_cli_signal_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}
