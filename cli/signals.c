/* SIGINT and SIGTERM: stop cleanly, never leave a half-written file behind.
 *
 * By default a signal ends the process at once, as the default action would
 * (the shell sees 128 + the signal number), after removing the temporary
 * files of outputs still being written: an interrupted command leaves
 * neither a partial output nor a stray temporary file. Commands made of many
 * short runs (paper's rows and friction sweep) call cli_signals_defer: the
 * first signal then only sets a flag that they check between runs; they keep
 * the completed results and exit with 128 + the signal number. A second
 * signal ends the process at once.
 *
 * This state is the command-line tool's, process-wide by nature (signal
 * dispositions are); the library has none. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Output files written at the same time; one is the usual case. */
#define TRACK_SLOTS 8

static volatile sig_atomic_t stop_signal;
static volatile sig_atomic_t deferring;
static volatile sig_atomic_t tracked_used[TRACK_SLOTS];
static char tracked_path[TRACK_SLOTS][CLI_PATH_MAX];

/* Only async-signal-safe calls here: unlink, signal, raise. */
static void on_signal(int sig)
{
    if (deferring && !stop_signal) {
        stop_signal = sig;
        return;
    }
    for (int i = 0; i < TRACK_SLOTS; ++i)
        if (tracked_used[i]) unlink(tracked_path[i]);
    signal(sig, SIG_DFL);
    raise(sig); /* delivered when the handler returns: the process ends by the signal */
}

static void install(int sig)
{
    struct sigaction old;
    /* A signal ignored by whoever started us (nohup, a background job)
     * stays ignored. */
    if (sigaction(sig, NULL, &old) == 0 && old.sa_handler == SIG_IGN) return;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART; /* output calls are not cut short by a deferred signal */
    sigaction(sig, &sa, NULL);
}

void cli_signals_install(void)
{
    install(SIGINT);
    install(SIGTERM);
}

void cli_signals_defer(void) { deferring = 1; }

int cli_stop_requested(void) { return stop_signal; }

int cli_stop_status(void) { return 128 + stop_signal; }

const char *cli_signal_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

/* Blocks SIGINT and SIGTERM while a temporary file and its record change
 * together, so that a signal never sees one without the other. */
static void hold(sigset_t *old)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigprocmask(SIG_BLOCK, &set, old);
}

static void release(const sigset_t *old) { sigprocmask(SIG_SETMASK, old, NULL); }

int cli_tmpfile_create(char *template_path, int *slot)
{
    *slot = -1;
    if (strlen(template_path) >= CLI_PATH_MAX) return -1;
    sigset_t old;
    hold(&old);
    const int fd = mkstemp(template_path);
    for (int i = 0; fd >= 0 && i < TRACK_SLOTS; ++i) {
        if (tracked_used[i]) continue;
        strcpy(tracked_path[i], template_path);
        /* The path must be complete before the handler may read it. */
        atomic_signal_fence(memory_order_seq_cst);
        tracked_used[i] = 1;
        *slot = i;
        break;
    }
    release(&old);
    return fd; /* more files than slots: still written, only not cleaned up by a signal */
}

int cli_tmpfile_finish(int slot, const char *tmp_path, const char *final_path)
{
    sigset_t old;
    hold(&old);
    int st = final_path ? rename(tmp_path, final_path) : unlink(tmp_path);
    if (st != 0 && final_path) {
        const int saved = errno; /* the rename's reason is the one to report */
        unlink(tmp_path);
        errno = saved;
    }
    if (slot >= 0 && slot < TRACK_SLOTS) tracked_used[slot] = 0;
    release(&old);
    return st;
}
