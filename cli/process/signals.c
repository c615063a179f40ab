/* Signals: stop cleanly, never leave a half-written file, a temporary file,
 * a scratch directory or a running child behind.
 *
 * SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGPIPE: the first one sets a flag
 * and ends the running child (gnuplot, ffmpeg) at once. The command notices
 * the flag where it next looks (each event and sample the simulation
 * pushes, each frame, when the child has exited, and just before an output
 * is renamed into place), removes what it made, leaves every target as it
 * was, and exits with 128 + the signal number. A second signal ends the
 * process at once, after killing the child (SIGKILL) and removing the
 * temporary files and scratch directories recorded here.
 *
 * SIGPIPE is how a reader that went away shows (`jumpcyl paper | head -1`):
 * the command stops as for the others but says nothing, as the signal ends
 * any other Unix tool quietly (cli_pipe_closed). A closed pipe raises it
 * again on every later write; that is the write failing, not a second
 * request to stop, so it never ends the process at once.
 *
 * SIGXFSZ (a file grew past `ulimit -f`): caught and otherwise ignored, so
 * that the write fails with EFBIG and is reported as "File too large"; it
 * is noted, as stdio may have lost the errno by the time the error shows
 * (cli_lost_write_errno).
 *
 * No SA_RESTART: a read or write that waits on a pipe, FIFO or terminal
 * (`sleep 30 | jumpcyl track /dev/stdin`) returns EINTR on the first stop
 * signal instead of waiting on, and the command stops there. Reads and
 * writes of regular files are not interrupted by signals.
 *
 * This state is the command-line tool's, process-wide by nature (signal
 * dispositions are); the library has none. */
#define _GNU_SOURCE /* syscall(SYS_getdents64): directory listing that is async-signal-safe */
#include "process.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/statvfs.h>
#include <sys/syscall.h>
#include <unistd.h>

/* Output files written at the same time; one or two is the usual case. */
#define TRACK_SLOTS 8
#define DIR_SLOTS 2

static const int stop_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};
#define STOP_SIGNAL_COUNT (int)(sizeof stop_signals / sizeof stop_signals[0])

static volatile sig_atomic_t stop_signal;
static volatile sig_atomic_t size_limit_crossed;
static volatile sig_atomic_t child_pid;
static volatile sig_atomic_t tracked_used[TRACK_SLOTS];
static char tracked_path[TRACK_SLOTS][CLI_PATH_MAX];
static volatile sig_atomic_t dir_used[DIR_SLOTS];
static char dir_path[DIR_SLOTS][CLI_PATH_MAX];

/* Removes a directory's entries and the directory with async-signal-safe
 * calls only (open, getdents64, unlinkat, rmdir): readdir may allocate. */
static void remove_dir_now(const char *path)
{
    const int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    char buf[4096];
    for (;;) {
        const long n = syscall(SYS_getdents64, fd, buf, sizeof buf);
        if (n <= 0) break;
        for (long off = 0; off < n;) {
            /* struct linux_dirent64: ino (8), off (8), reclen (2), type (1), name */
            unsigned short reclen;
            memcpy(&reclen, buf + off + 16, sizeof reclen);
            const char *name = buf + off + 19;
            if (!(name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))))
                unlinkat(fd, name, 0);
            off += reclen;
        }
    }
    close(fd);
    rmdir(path);
}

/* Only async-signal-safe calls here. */
static void on_signal(int sig)
{
    const int saved = errno;
    if (sig == SIGXFSZ) { /* the write that crossed the limit returns EFBIG */
        size_limit_crossed = 1;
        errno = saved;
        return;
    }
    if (sig == SIGPIPE && stop_signal) {
        errno = saved;
        return;
    }
    const pid_t child = (pid_t)child_pid;
    if (child > 0) kill(child, SIGTERM);
    if (!stop_signal) {
        stop_signal = sig;
        errno = saved;
        return;
    }
    /* The process ends now and cannot wait for the child to finish: it is
     * killed outright (it only ever writes into the scratch directory). */
    if (child > 0) kill(child, SIGKILL);
    for (int i = 0; i < TRACK_SLOTS; ++i)
        if (tracked_used[i]) unlink(tracked_path[i]);
    for (int i = 0; i < DIR_SLOTS; ++i)
        if (dir_used[i]) remove_dir_now(dir_path[i]);
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
    sa.sa_flags = 0; /* no SA_RESTART: a wait on a pipe ends with EINTR (above) */
    sigaction(sig, &sa, NULL);
}

void cli_signals_install(void)
{
    for (int i = 0; i < STOP_SIGNAL_COUNT; ++i) install(stop_signals[i]);
    install(SIGXFSZ);
}

int cli_stop_requested(void) { return stop_signal; }

int cli_stop_status(void) { return 128 + stop_signal; }

int cli_pipe_closed(int err) { return stop_signal == SIGPIPE || err == EPIPE; }

int cli_write_stopped(int err) { return stop_signal && (err == EINTR || err == EIO); }

int cli_lost_write_errno(int fd)
{
    if (size_limit_crossed) return EFBIG;
    struct statvfs vfs;
    if (fd >= 0 && fstatvfs(fd, &vfs) == 0 && (geteuid() == 0 ? vfs.f_bfree : vfs.f_bavail) == 0) return ENOSPC;
    return EIO;
}

const char *cli_signal_name(int sig)
{
    switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    case SIGPIPE: return "SIGPIPE";
    case SIGXFSZ: return "SIGXFSZ";
    }
    return "a signal";
}

void cli_signals_hold(sigset_t *old)
{
    sigset_t set;
    sigemptyset(&set);
    for (int i = 0; i < STOP_SIGNAL_COUNT; ++i) sigaddset(&set, stop_signals[i]);
    sigprocmask(SIG_BLOCK, &set, old);
}

void cli_signals_release(const sigset_t *old) { sigprocmask(SIG_SETMASK, old, NULL); }

void cli_child_set(pid_t pid)
{
    child_pid = pid;
    /* A signal that came before the child was recorded ends it too. */
    if (pid > 0 && stop_signal) kill(pid, SIGTERM);
}

int cli_tmpfile_create(char *template_path, int *slot)
{
    *slot = -1;
    if (strlen(template_path) >= CLI_PATH_MAX) return -1;
    sigset_t old;
    cli_signals_hold(&old);
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
    if (fd >= 0 && *slot < 0) { /* more files than slots: refused, as a signal could not clean it up */
        close(fd);
        unlink(template_path);
        errno = EMFILE;
        cli_signals_release(&old);
        return -1;
    }
    cli_signals_release(&old);
    return fd;
}

int cli_tmpfile_finish(int slot, const char *tmp_path, const char *final_path)
{
    sigset_t old;
    cli_signals_hold(&old);
    int st = final_path ? rename(tmp_path, final_path) : unlink(tmp_path);
    if (st != 0 && final_path) {
        const int saved = errno; /* the rename's reason is the one to report */
        unlink(tmp_path);
        errno = saved;
    }
    if (slot >= 0 && slot < TRACK_SLOTS) tracked_used[slot] = 0;
    cli_signals_release(&old);
    return st;
}

int cli_tmpdir_track(const char *path)
{
    if (strlen(path) >= CLI_PATH_MAX) return -1;
    sigset_t old;
    cli_signals_hold(&old);
    int slot = -1;
    for (int i = 0; i < DIR_SLOTS && slot < 0; ++i) {
        if (dir_used[i]) continue;
        strcpy(dir_path[i], path);
        atomic_signal_fence(memory_order_seq_cst);
        dir_used[i] = 1;
        slot = i;
    }
    cli_signals_release(&old);
    return slot;
}

void cli_tmpdir_untrack(int slot)
{
    if (slot < 0 || slot >= DIR_SLOTS) return;
    sigset_t old;
    cli_signals_hold(&old);
    dir_used[slot] = 0;
    cli_signals_release(&old);
}
