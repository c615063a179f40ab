/* A reader that went away: every command run with its standard output a
 * pipe whose read end is closed (`jumpcyl paper | head -1` once head has
 * exited) ends quietly, as docs/cli.md says and as the signal ends any
 * other tool: nothing on standard error, exit status 128 + SIGPIPE (141)
 * from the tool itself (not killed by a repeated SIGPIPE), and nothing
 * reported as done. Where the caller ignores SIGPIPE the writes fail with
 * EPIPE instead: quietly again, status 1. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include "cli_run.h"

#define MAX_WORDS 16
#define TRACK JC_EXAMPLES_DIR "/tracker/incline.trk"
#define EXIT_PIPE (128 + SIGPIPE)

/* Every command, in each of its ways of writing to standard output (text,
 * JSON, CSV to "-", help, version, the experiment file); %s: a scratch
 * directory for the files of plot and animate. */
static const char *const cases[][MAX_WORDS] = {
    {"paper"},
    {"paper", "--json"},
    {"--help"},
    {"--version"},
    {"simulate", "--help"},
    {"predict"},
    {"predict", "--json"},
    {"predict", "--dump-config"},
    {"simulate"},
    {"simulate", "--json"},
    {"simulate", "--sample-dt", "0.01", "--csv", "-"},
    {"presets"},
    {"params"},
    {"params", "--json"},
    {"sweep", "--vary", "incline=10:60:5", "--output", "-", "--quiet"},
    {"mc", "--samples", "200", "--quiet"},
    {"mc", "--samples", "200", "--json", "--quiet"},
    {"map", "--x", "incline=10:40:10", "--y", "mu=0.3,0.5", "--output", "%s/map.png", "--quiet"},
    {"design", "--jump-at", "1.2m", "--free", "rod-offset", "--points", "50"},
    {"track", TRACK},
    {"compare", "--track", TRACK, "--mu-k", "0.4"},
    {"fit", "--track", TRACK, "--free", "mu_k", "--seed", "1"},
    {"plot", "--what", "gap", "--output", "%s/gap.png"},
    {"animate", "--incline", "45", "--size", "320x180", "--output", "%s/film.gif"},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

/* The case's words with the scratch directory filled in (words[] point into
 * store). */
static void case_args(int k, const char *dir, char store[MAX_WORDS][512], const char *words[MAX_WORDS + 1])
{
    int n = 0;
    for (; n < MAX_WORDS && cases[k][n]; ++n) {
        const char *w = cases[k][n];
        if (strstr(w, "%s")) {
            snprintf(store[n], sizeof store[n], "%s%s", dir, strstr(w, "%s") + 2);
            words[n] = store[n];
        } else {
            words[n] = w;
        }
    }
    words[n] = NULL;
}

static int quiet_run(int k, const char *how, int status, const char *dir)
{
    char store[MAX_WORDS][512];
    const char *args[MAX_WORDS + 1];
    case_args(k, dir, store, args);
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, how, out_tmp, err_tmp);
    ENSURE(pid > 0);
    cli_result r = cli_run_wait(pid, out_tmp, err_tmp, 0);
    const int ok = r.signal == 0 && r.status == status && r.err && r.err[0] == '\0';
    if (!ok)
        fprintf(stderr, "jumpcyl %s ... (%s): status %d, signal %d, stderr: %s\n", args[0], how, r.status, r.signal,
                r.err ? r.err : "(none)");
    cli_result_free(&r);
    ENSURE_MSG(ok, "case %d: expected exit status %d and nothing on standard error", k, status);
    return 0;
}

static int test_reader_gone(void)
{
    char dir[] = "/tmp/jc_closed_stdout_XXXXXX";
    ENSURE(mkdtemp(dir) != NULL);
    for (int k = 0; k < CASE_COUNT; ++k)
        if (quiet_run(k, CLI_RUN_READER_GONE, EXIT_PIPE, dir)) return 1;
    /* The film's line comes before its frames: the stop leaves no film. */
    char film[600];
    snprintf(film, sizeof film, "%s/film.gif", dir);
    const int film_made = cli_file_exists(film);
    char path[600];
    const char *names[] = {"map.png", "gap.png", "film.gif"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
    }
    ENSURE_MSG(rmdir(dir) == 0, "%s: other files left behind", dir);
    ENSURE_MSG(!film_made, "animate made its film for a reader that was gone");
    return 0;
}

static int test_sigpipe_ignored(void)
{
    char dir[] = "/tmp/jc_closed_stdout_XXXXXX";
    ENSURE(mkdtemp(dir) != NULL);
    /* The text, the JSON, a streamed CSV and a batch's rows. */
    const int some[] = {0, 1, 10, 14};
    for (size_t i = 0; i < sizeof some / sizeof some[0]; ++i)
        if (quiet_run(some[i], CLI_RUN_READER_GONE_SIGPIPE_IGNORED, 1, dir)) return 1;
    ENSURE(rmdir(dir) == 0);
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    RUN_TEST(test_reader_gone);
    RUN_TEST(test_sigpipe_ignored);
    TEST_MAIN_END();
}
