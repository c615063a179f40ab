/* Running external programs (gnuplot, ffmpeg) without a shell: the
 * arguments are passed as they are, so file names with spaces or quotes
 * need no escaping, and a missing program is reported as such. */
#define _POSIX_C_SOURCE 200809L
#include "figures.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
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

static int setup_actions(posix_spawn_file_actions_t *fa, const char *log_path)
{
    if (posix_spawn_file_actions_init(fa) != 0) return -1;
    int bad = posix_spawn_file_actions_addopen(fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
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

/* Waits for pid; polls while a progress line may need redrawing. */
static int wait_child(pid_t pid, int *status, cli_Progress *progress)
{
    for (;;) {
        const pid_t r = waitpid(pid, status, progress && progress->enabled ? WNOHANG : 0);
        if (r == pid) return 0;
        if (r < 0 && errno != EINTR) return -1;
        if (r == 0) {
            cli_progress_update(progress, 0, 0);
            const struct timespec ts = {0, 20 * 1000 * 1000};
            nanosleep(&ts, NULL);
        }
    }
}

int cli_run_program(char *const argv[], const char *log_path, cli_Progress *progress)
{
    posix_spawn_file_actions_t fa;
    if (setup_actions(&fa, log_path) != 0) {
        cli_error("cannot start %s: out of memory", argv[0]);
        return -1;
    }
    pid_t pid;
    const int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        cli_error("cannot start %s: %s", argv[0], strerror(rc));
        return -1;
    }
    int status = 0;
    if (wait_child(pid, &status, progress) != 0) {
        cli_error("waiting for %s: %s", argv[0], strerror(errno));
        return -1;
    }
    if (WIFSIGNALED(status)) {
        cli_error("%s was killed by signal %d", argv[0], WTERMSIG(status));
        return -1;
    }
    return WEXITSTATUS(status);
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
