/* The tool as a process (cli/process/), the lowest layer of the tool: its
 * exit statuses and one-line error messages (error.c), the stop signals
 * (signals.c), child programs (spawn.c), private scratch directories and
 * the few file-name operations they need (workdir.c). It calls nothing of
 * the tool above it (docs/architecture.md, Layers). */
#ifndef JUMPCYL_PROCESS_H
#define JUMPCYL_PROCESS_H

#include <signal.h>
#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

/* Exit statuses: what cmd_* returns, and every function of the tool whose
 * comment says "an exit status" (docs/architecture.md, "Return values").
 * EXIT_OK there always means "it went well"; a stop signal's status is
 * cli_stop_status(). */
enum { EXIT_OK = 0, EXIT_FAIL = 1, EXIT_USAGE = 2, EXIT_MISFIT = 3 /* fit: the model does not describe the video */ };

#define CLI_PATH_MAX 4096

/* ---- error.c ---- */

/* Prints "jumpcyl: <msg>" on stderr, on one line (control characters
 * shown as '?'). */
void cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* ---- signals.c: SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ ---- */

/* At start-up. The first signal sets a flag (and ends the running child);
 * commands check cli_stop_requested where they can stop, keep targets as
 * they were and return cli_stop_status(). A second signal ends the process
 * at once, after removing the recorded temporary files and directories. */
void cli_signals_install(void);
int cli_stop_requested(void); /* the signal number, 0 if none */
int cli_stop_status(void);    /* 128 + the signal number: 130 SIGINT, 143 SIGTERM */
const char *cli_signal_name(int sig);
/* Whether a write that failed with err (errno) went to a pipe whose reader
 * went away: the stop is SIGPIPE, or err is EPIPE (where the caller ignores
 * SIGPIPE). Nobody reads the rest, so such a failure of standard output is
 * not reported: the command ends quietly, with 128 + SIGPIPE after the signal. */
int cli_pipe_closed(int err);
/* Blocks the stop signals (while a record and the thing it records change
 * together, or around starting a child); release restores the old mask. */
void cli_signals_hold(sigset_t *old);
void cli_signals_release(const sigset_t *old);
/* The running child, ended by a signal; 0 when none. */
void cli_child_set(pid_t pid);
/* mkstemp, recorded so that a signal that ends the process removes the file.
 * Returns the descriptor or -1 (errno); *slot is the record. */
int cli_tmpfile_create(char *template_path, int *slot);
/* Renames the temporary file to final_path (removes it if final_path is
 * NULL, or if the rename fails) and drops the record. 0 or -1 (errno). */
int cli_tmpfile_finish(int slot, const char *tmp_path, const char *final_path);
/* A scratch directory, removed with its files by a signal that ends the
 * process; returns the record (-1 if none is free) for cli_tmpdir_untrack. */
int cli_tmpdir_track(const char *path);
void cli_tmpdir_untrack(int slot);

/* Whether a write to a pipe, FIFO or terminal that failed with err (errno;
 * EIO when stdio lost it) was cut short by the stop signal that came
 * (EINTR): the stop is what to report, not the write. */
int cli_write_stopped(int err);
/* The reason of a write error whose errno stdio lost (ferror set, errno
 * gone): EFBIG when a write crossed the file size limit (SIGXFSZ came),
 * ENOSPC when fd's file system is full, else EIO. */
int cli_lost_write_errno(int fd);

/* ---- files.c: opening and reading without waiting for ever ---- */

/* open(path, flags, mode) with O_NONBLOCK (cleared once open), O_CLOEXEC and
 * O_NOCTTY: the open itself never waits. A FIFO without a reader refuses a
 * writer (ENXIO: "... (a FIFO without a reader)"); a FIFO opened to read
 * opens at once. A directory is refused; so is anything but a regular file
 * when regular_only. Returns the descriptor, or -1 with the reason (strerror
 * or "not a regular file (a FIFO)") in why. The one open for every file the
 * tool names: outputs in place, batch rows, inputs. */
int cli_open_nowait(const char *path, int flags, mode_t mode, int regular_only, char *why, size_t why_len);
/* The same as a stdio stream (stdio_mode as for fdopen); NULL with why. */
FILE *cli_fopen_nowait(const char *path, const char *stdio_mode, int flags, int regular_only, char *why,
                       size_t why_len);
/* Reads fd to its end into *buf (malloc'd, *len bytes), refusing more than
 * max bytes ("larger than MAX bytes"). Waits with poll, so that the first
 * stop signal ends a wait on a pipe or FIFO whose writer is silent (or has
 * not come yet). 0; 1 when a stop signal came (no message: main says it);
 * -1 with the reason in why. */
int cli_read_all(int fd, long max, char **buf, size_t *len, char *why, size_t why_len);

/* ---- spawn.c: external programs ---- */

/* Full path of an executable named name found in $PATH; 0, or -1 if none. */
int cli_find_program(const char *name, char *path, size_t len);
/* Called about every 10 ms while a child runs (a progress line's redraw). */
typedef void (*cli_WaitTick)(void *ctx);
/* How a child program's run ended. */
typedef enum {
    CLI_RUN_EXITED,  /* it exited: its exit status is in *exit_status */
    CLI_RUN_FAILED,  /* it could not start, or a signal killed it: the message is printed */
    CLI_RUN_STOPPED, /* a stop signal came: the child was ended and reaped; no message */
    CLI_RUN_EFBIG    /* a write of the child crossed the file size limit (ulimit -f); no message */
} cli_RunEnd;
/* Runs argv (argv[0] looked up in $PATH) in the directory cwd (NULL: ours)
 * with stdin from /dev/null and stdout and stderr appended to log_path
 * (NULL: inherited), waits for it, calling tick(ctx) meanwhile (tick may be
 * NULL). */
cli_RunEnd cli_run_program(char *const argv[], const char *cwd, const char *log_path, cli_WaitTick tick, void *ctx,
                           int *exit_status);
/* Copies the last lines of a program's log to stderr, indented. */
void cli_print_log_tail(const char *log_path);

/* ---- workdir.c: scratch directories and file names ---- */

typedef struct {
    char path[CLI_PATH_MAX];
    int slot; /* its record in signals.c: a signal that ends the process removes it */
} cli_WorkDir;

/* A new private directory under $TMPDIR (or /tmp); 0, or -1 after a message. */
int cli_workdir_make(cli_WorkDir *w, const char *cmd);
/* Removes the directory and the files in it (it holds no subdirectories). */
void cli_workdir_remove(cli_WorkDir *w);
/* Removes a directory's regular files and the directory; 0, or -1. */
int cli_remove_flat_dir(const char *path);

/* The extension of the file name in path, without the dot ("" if none). */
const char *cli_path_ext(const char *path);
/* Splits path into its directory ("." if none) and its base name without
 * the extension. -1 if a part does not fit. */
int cli_path_split(const char *path, char *dir, size_t dir_len, char *stem, size_t stem_len);
/* path made absolute against the working directory; 0, or -1. */
int cli_path_absolute(const char *path, char *out, size_t len);
/* Whether the directory that will hold path exists and is writable, so that
 * a command fails before its work, not after; 0, or -1 after a message. */
int cli_check_output_dir(const char *path);
/* dir/name; -1 if it does not fit. */
int cli_path_join(char *out, size_t len, const char *dir, const char *name);

#endif
