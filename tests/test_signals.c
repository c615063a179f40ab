/* Failure safety under SIGINT and SIGTERM, through the built tool (argv[1]).
 *
 * - paper (many short runs) stops between runs: it prints the rows complete
 *   by then, says so in one line and exits 130 (SIGINT) or 143 (SIGTERM);
 *   its JSON stays valid and says what stopped it.
 * - a command killed while writing its CSV leaves neither a partial file
 *   nor a temporary one.
 * The workloads take seconds, so that the signal lands mid-work; the
 * tests check the outcome, which does not depend on the exact moment. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include "cli_run.h"

#include <dirent.h>
#include <time.h>

/* A paper table that takes about 2 s (RelWithDebInfo): 27 runs of hundreds
 * of bounces each. */
#define SLOW_PAPER "--g", "1000", "--mu", "0.05", "--restitution", "0.9", "--ramp-length", "60000"

static void sleep_ms(long ms)
{
    struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

static int stop_paper(int sig, int json)
{
    const char *args[] = {"paper", SLOW_PAPER, json ? "--json" : NULL, NULL};
    char out_tmp[64], err_tmp[64];
    cli_result r;
    /* Past start-up (a few ms; more under a sanitizer on a loaded machine),
     * well inside the seconds of runs. A process ended by the signal itself
     * got it before its handler was installed: tried again, later. */
    for (long delay_ms = 150;; delay_ms *= 2) {
        const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
        ENSURE(pid > 0);
        sleep_ms(delay_ms);
        kill(pid, sig);
        r = cli_run_wait(pid, out_tmp, err_tmp, 1);
        if (r.signal != sig || delay_ms >= 1200) break;
        fprintf(stderr, "  (the signal came before start-up ended after %ld ms; again)\n", delay_ms);
        cli_result_free(&r);
    }
    const char *name = sig == SIGINT ? "SIGINT" : "SIGTERM";
    const int status_ok = r.status == 128 + sig;
    const int said = r.err && strstr(r.err, "stopped by") && strstr(r.err, name) && cli_one_line(r.err);
    /* Whatever was printed is complete: the text ends with its notes, the
     * JSON is one whole document naming the signal. */
    int complete = r.out != NULL;
    if (complete && r.out[0] && json) complete = strstr(r.out, "\"stopped_by\"") && strstr(r.out, name) &&
                                                 r.out[strlen(r.out) - 2] == '}';
    if (complete && r.out[0] && !json) complete = strstr(r.out, "Notes:") != NULL;
    if (!status_ok || !said || !complete)
        fprintf(stderr, "paper stopped by %s: status %d (signal %d), stderr: %s", name, r.status, r.signal,
                r.err ? r.err : "(none)\n");
    cli_result_free(&r);
    ENSURE_MSG(status_ok, "exit status, expected %d", 128 + sig);
    ENSURE_MSG(said, "the one-line message");
    ENSURE_MSG(complete, "the output printed is not complete");
    return 0;
}

static int test_paper_sigint(void) { return stop_paper(SIGINT, 0); }
static int test_paper_sigterm_json(void) { return stop_paper(SIGTERM, 1); }

static int count_files(const char *dir, int *temporary)
{
    DIR *d = opendir(dir);
    int n = 0;
    *temporary = 0;
    for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
        if (e->d_name[0] == '.') continue;
        ++n;
        if (strstr(e->d_name, ".tmp-")) *temporary = 1;
    }
    if (d) closedir(d);
    return n;
}

/* SIGTERM while the CSV is being written: nothing stays behind. */
static int test_csv_killed_while_writing(void)
{
    char dir[] = "/tmp/jc_signals_XXXXXX";
    ENSURE(mkdtemp(dir));
    char csv[128];
    snprintf(csv, sizeof csv, "%s/run.csv", dir);
    /* Samples every 10 us to the ramp end: a CSV of about 25 MB, long enough to catch. */
    const char *args[] = {"simulate", "--t-max", "10", "--sample-dt", "1e-5", "--csv", csv, NULL};
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
    ENSURE(pid > 0);
    int seen = 0, temporary = 0;
    for (int i = 0; i < 60000 && !seen; ++i) { /* up to a minute */
        count_files(dir, &temporary);
        if (temporary) seen = 1;
        else sleep_ms(1);
    }
    kill(pid, SIGTERM);
    cli_result r = cli_run_wait(pid, out_tmp, err_tmp, 1);
    const int left = count_files(dir, &temporary);
    if (left == 1) unlink(csv);
    rmdir(dir);
    const int killed = r.status == 128 + SIGTERM;
    cli_result_free(&r);
    ENSURE_MSG(seen, "the temporary file never appeared");
    ENSURE_MSG(killed, "the process did not exit with 128 + SIGTERM");
    ENSURE_MSG(left == 0, "%d file(s) left behind", left);
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    RUN_TEST(test_paper_sigint);
    RUN_TEST(test_paper_sigterm_json);
    RUN_TEST(test_csv_killed_while_writing);
    TEST_MAIN_END();
}
