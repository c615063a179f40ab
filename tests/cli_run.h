/*
 * Runs the command-line tool as a child process, without a shell: an exact
 * argv, standard output captured or sent to a chosen file (/dev/full),
 * standard error captured, every signal the tool handles at its default action.
 *
 * The test executables take the tool's path, optionally followed by a
 * wrapper command that every run goes through, e.g.
 *     test_bad_input build/jumpcyl valgrind -q --error-exitcode=1 --leak-check=full
 * (the valgrind tests in tests/CMakeLists.txt).
 */
#ifndef JC_CLI_RUN_H
#define JC_CLI_RUN_H

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define CLI_RUN_MAX_ARGS 64
/* As stdout_path: the tool starts with standard output closed. */
#define CLI_RUN_CLOSED "(closed)"
/* As stdout_path: standard output is a pipe whose reader has gone
 * (`jumpcyl paper | head -1` once head has exited); the second also with
 * SIGPIPE ignored, as a caller may leave it. */
#define CLI_RUN_READER_GONE "(reader gone)"
#define CLI_RUN_READER_GONE_SIGPIPE_IGNORED "(reader gone, SIGPIPE ignored)"

typedef struct {
    int status; /* exit status; -1 if it ended by a signal */
    int signal; /* the signal that ended it, 0 if it exited */
    char *out;  /* captured standard output ("" when sent to a file) */
    char *err;  /* captured standard error */
} cli_result;

static const char *cli_run_tool __attribute__((unused));
static char **cli_run_wrapper __attribute__((unused)); /* NULL-terminated, may be empty */

/* main's arguments: argv[1] the tool, argv[2..] the wrapper. */
static inline int cli_run_init(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH_TO_JUMPCYL [WRAPPER COMMAND...]\n", argv[0]);
        return -1;
    }
    cli_run_tool = argv[1];
    cli_run_wrapper = argv + 2;
    return 0;
}

/* A whole stream as a NUL-terminated string (NULL when out of memory). */
static inline char *cli_run_read_all(FILE *f)
{
    size_t cap = 4096, len = 0, n;
    char *buf = malloc(cap);
    while (buf && (n = fread(buf + len, 1, cap - len - 1, f)) > 0) {
        len += n;
        if (cap - len < 2) {
            char *bigger = realloc(buf, cap *= 2);
            if (!bigger) free(buf);
            buf = bigger;
        }
    }
    if (buf) buf[len] = '\0';
    return buf;
}

static inline char *cli_run_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = cli_run_read_all(f);
    fclose(f);
    return buf;
}

static inline void cli_run_child(const char *const *args, const char *out_path, const char *err_path)
{
    /* Whatever the test runner ignores, the tool starts with the defaults. */
    const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; ++i) signal(sigs[i], SIG_DFL);
    const int closed = strcmp(out_path, CLI_RUN_CLOSED) == 0;
    const int ignored = strcmp(out_path, CLI_RUN_READER_GONE_SIGPIPE_IGNORED) == 0;
    const int gone = ignored || strcmp(out_path, CLI_RUN_READER_GONE) == 0;
    int reader_gone[2] = {-1, -1};
    if (gone && pipe(reader_gone) != 0) _exit(126);
    if (gone) close(reader_gone[0]);
    if (ignored) signal(SIGPIPE, SIG_IGN);
    const int out = closed ? -1 : gone ? reader_gone[1] : open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if ((!closed && (out < 0 || dup2(out, 1) < 0)) || err < 0 || dup2(err, 2) < 0) _exit(126);
    if (closed) close(1);
    const char *argv[CLI_RUN_MAX_ARGS + 16];
    int n = 0;
    for (char **w = cli_run_wrapper; *w && n < 15; ++w) argv[n++] = *w;
    argv[n++] = cli_run_tool;
    for (int i = 0; args[i] && n < CLI_RUN_MAX_ARGS + 15; ++i) argv[n++] = args[i];
    argv[n] = NULL;
    execvp(argv[0], (char *const *)argv);
    _exit(127);
}

/* Starts "jumpcyl ARGS" (args NULL-terminated). stdout_path NULL captures
 * standard output (or CLI_RUN_CLOSED, CLI_RUN_READER_GONE...). Returns the child's pid (for cli_run_wait), -1 on failure. */
static inline pid_t cli_run_start(const char *const *args, const char *stdout_path, char *out_tmp, char *err_tmp)
{
    strcpy(out_tmp, "/tmp/jc_cli_out_XXXXXX");
    strcpy(err_tmp, "/tmp/jc_cli_err_XXXXXX");
    const int fo = mkstemp(out_tmp), fe = mkstemp(err_tmp);
    if (fo >= 0) close(fo);
    if (fe >= 0) close(fe);
    if (fo < 0 || fe < 0) return -1;
    fflush(NULL);
    const pid_t pid = fork();
    if (pid == 0) cli_run_child(args, stdout_path ? stdout_path : out_tmp, err_tmp);
    return pid;
}

static inline cli_result cli_run_wait(pid_t pid, const char *out_tmp, const char *err_tmp, int captured)
{
    cli_result r = {-1, 0, NULL, NULL};
    int ws = 0;
    if (pid > 0 && waitpid(pid, &ws, 0) == pid) {
        if (WIFEXITED(ws)) r.status = WEXITSTATUS(ws);
        if (WIFSIGNALED(ws)) r.signal = WTERMSIG(ws);
    }
    r.out = captured ? cli_run_slurp(out_tmp) : calloc(1, 1);
    r.err = cli_run_slurp(err_tmp);
    unlink(out_tmp);
    unlink(err_tmp);
    return r;
}

static inline cli_result cli_run_to(const char *const *args, const char *stdout_path)
{
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, stdout_path, out_tmp, err_tmp);
    return cli_run_wait(pid, out_tmp, err_tmp, stdout_path == NULL);
}

static inline cli_result cli_run(const char *const *args) { return cli_run_to(args, NULL); }

static inline void cli_result_free(cli_result *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/* Runs "TOOL ARGS" through /bin/sh, with PATH set to path_env when it is
 * not NULL (to make gnuplot or ffmpeg missing); stdout and stderr captured.
 * ARGS are the test's own fixed words, quoted as in a shell; tests that
 * pass names from elsewhere use cli_run (an exact argv, no shell). */
static inline cli_result cli_run_line(const char *tool, const char *path_env, const char *args)
{
    cli_result r = {-1, 0, NULL, NULL};
    char err_path[] = "/tmp/jc_cli_line_err_XXXXXX";
    const int fd = mkstemp(err_path);
    if (fd < 0) return r;
    close(fd);
    char cmd[8192];
    if (path_env) snprintf(cmd, sizeof cmd, "env PATH='%s' '%s' %s 2>'%s'", path_env, tool, args, err_path);
    else snprintf(cmd, sizeof cmd, "'%s' %s 2>'%s'", tool, args, err_path);
    FILE *p = popen(cmd, "r");
    if (p) {
        r.out = cli_run_read_all(p);
        const int ws = pclose(p);
        r.status = ws != -1 && WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
    }
    r.err = cli_run_slurp(err_path);
    remove(err_path);
    return r;
}

/* Exactly one line on standard error. */
static inline int cli_one_line(const char *s)
{
    const char *nl = s ? strchr(s, '\n') : NULL;
    return nl && nl[1] == '\0';
}

/* Whether a file (or anything else) is at path: what a refused run must
 * not leave, and a run that works must write. */
static inline int cli_file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* A fresh scratch directory from the template dir ("/tmp/name_XXXXXX",
 * filled in place) and path, the file name inside it; 0, or -1 when the
 * directory could not be made. The test removes both. */
static inline int cli_scratch(char *dir, char *path, size_t path_len, const char *name)
{
    if (!mkdtemp(dir)) return -1;
    snprintf(path, path_len, "%s/%s", dir, name);
    return 0;
}

#endif
