/* Running external programs (gnuplot, ffmpeg) without a shell: the
 * arguments are passed as they are, so file names with spaces or quotes
 * need no escaping, and a missing program is reported as such. The child
 * runs in the scratch directory (only names made there reach it) and is
 * recorded, so that a signal ends it and no child outlives the tool. */
#define _GNU_SOURCE /* posix_spawn_file_actions_addchdir_np (glibc 2.29) */
#include "process.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

int cli_find_program(const char *name, char *path, size_t len)
{
    const char *dirs = getenv("PATH");
    if (!dirs || !*dirs) return -1;
    while (*dirs) {
        const size_t n = strcspn(dirs, ":");
        /* An empty PATH entry means the working directory. */
        const int w = n ? snprintf(path, len, "%.*s/%s", (int)n, dirs, name) : snprintf(path, len, "./%s", name);
        struct stat st;
        if (w > 0 && (size_t)w < len && stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0)
            return 0;
        dirs += n + (dirs[n] == ':');
    }
    return -1;
}

static int setup_actions(posix_spawn_file_actions_t *fa, const char *cwd, const char *log_path)
{
    if (posix_spawn_file_actions_init(fa) != 0) return -1;
    int bad = posix_spawn_file_actions_addopen(fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (cwd) bad |= posix_spawn_file_actions_addchdir_np(fa, cwd);
    if (log_path) {
        bad |= posix_spawn_file_actions_addopen(fa, STDOUT_FILENO, log_path, O_WRONLY | O_CREAT | O_APPEND, 0600);
        bad |= posix_spawn_file_actions_adddup2(fa, STDOUT_FILENO, STDERR_FILENO);
    }
    if (bad) {
        posix_spawn_file_actions_destroy(fa);
        return -1;
    }
    return 0;
}

/* Seconds a child may take to end after SIGTERM before it gets SIGKILL. */
#define CHILD_GRACE_S 3.0

static double monotonic_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Waits for pid, polling so that the caller's tick runs (a progress line)
 * and a stop request ends the child (SIGTERM, then SIGKILL after a grace
 * period). */
static int wait_child(pid_t pid, int *status, cli_WaitTick tick, void *ctx)
{
    double stop_at = -1.0;
    for (;;) {
        const pid_t r = waitpid(pid, status, WNOHANG);
        if (r == pid) return 0;
        if (r < 0 && errno != EINTR) return -1;
        if (cli_stop_requested()) {
            const double now = monotonic_s();
            if (stop_at < 0) {
                stop_at = now;
                kill(pid, SIGTERM);
            } else if (now - stop_at > CHILD_GRACE_S) {
                kill(pid, SIGKILL);
            }
        } else if (tick) {
            tick(ctx);
        }
        const struct timespec ts = {0, 10 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
}

/* The started child's end, waited for. */
static cli_RunEnd child_end(const char *name, pid_t pid, cli_WaitTick tick, void *ctx, int *exit_status)
{
    int status = 0;
    const int waited = wait_child(pid, &status, tick, ctx);
    cli_child_set(0);
    if (waited != 0) {
        cli_error("waiting for %s: %s", name, strerror(errno));
        return CLI_RUN_FAILED;
    }
    if (cli_stop_requested()) return CLI_RUN_STOPPED;
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) return CLI_RUN_EFBIG;
    if (WIFSIGNALED(status)) {
        cli_error("%s was killed by signal %d", name, WTERMSIG(status));
        return CLI_RUN_FAILED;
    }
    *exit_status = WEXITSTATUS(status);
    return CLI_RUN_EXITED;
}

cli_RunEnd cli_run_program(char *const argv[], const char *cwd, const char *log_path, cli_WaitTick tick, void *ctx,
                           int *exit_status)
{
    *exit_status = -1;
    posix_spawn_file_actions_t fa;
    if (setup_actions(&fa, cwd, log_path) != 0) {
        cli_error("cannot start %s: out of memory", argv[0]);
        return CLI_RUN_FAILED;
    }
    /* The child starts with no signal blocked; ours stay blocked until its
     * pid is recorded, so that a signal cannot miss it. */
    posix_spawnattr_t attr;
    sigset_t none, old;
    sigemptyset(&none);
    if (posix_spawnattr_init(&attr) != 0 || posix_spawnattr_setsigmask(&attr, &none) != 0 ||
        posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK) != 0) {
        posix_spawn_file_actions_destroy(&fa);
        cli_error("cannot start %s: out of memory", argv[0]);
        return CLI_RUN_FAILED;
    }
    cli_signals_hold(&old);
    pid_t pid;
    const int rc = cli_stop_requested() ? ECANCELED : posix_spawnp(&pid, argv[0], &fa, &attr, argv, environ);
    if (rc == 0) cli_child_set(pid);
    cli_signals_release(&old);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&attr);
    if (rc == ECANCELED) return CLI_RUN_STOPPED;
    if (rc != 0) {
        cli_error("cannot start %s: %s", argv[0], strerror(rc));
        return CLI_RUN_FAILED;
    }
    return child_end(argv[0], pid, tick, ctx, exit_status);
}

void cli_print_log_tail(const char *log_path)
{
    FILE *f = fopen(log_path, "r");
    if (!f) return;
    /* Keep the last few lines: the error is at the end of a program's output. */
    enum { KEEP = 8 };
    char lines[KEEP][512];
    int n = 0;
    while (fgets(lines[n % KEEP], sizeof lines[0], f)) ++n;
    fclose(f);
    for (int i = n > KEEP ? n - KEEP : 0; i < n; ++i) {
        const char *s = lines[i % KEEP];
        fprintf(stderr, "    %s%s", s, s[strlen(s) - 1] == '\n' ? "" : "\n");
    }
}
