/* FILE.part, the rows a sweep or mc keeps for --resume (issue 30), the
 * tool run as a process:
 * - a symlink planted as FILE.part is refused, its target untouched, with
 *   and without --resume; a foreign file there is never cut;
 * - a row changed by hand is refused, naming it; rows forged with valid
 *   checksums are found by the rows computed again;
 * - a second job on the same output is refused while the first runs; of
 *   20 started at once one writes the whole file and 19 are refused;
 * - the final file keeps the mode of the file it replaces;
 * - a full file system (a 96 KiB tmpfs in a user and mount namespace,
 *   when the kernel allows one) and the file size limit (RLIMIT_FSIZE,
 *   EFBIG) stop the job with its whole rows kept, and --resume then ends
 *   in the bytes of an uninterrupted run.
 * Checksums are recomputed here with the test's own FNV-1a (its published
 * constants), not the tool's. */
#define _GNU_SOURCE
#include "../cli_run.h"
#include "../test.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

static char dir[64];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

static const char *const SWEEP[] = {"sweep", "--vary", "incline=20:40:0.05", "--vary", "mu=0.3,0.6", "--quiet", NULL};
#define SWEEP_ROWS 802

/* args with "--output FILE" and extra (NULL-terminated, may be NULL) appended. */
static void with_output(const char *const *args, const char *out, const char *const *extra, const char **argv)
{
    int n = 0;
    for (int i = 0; args[i]; ++i) argv[n++] = args[i];
    argv[n++] = "--output";
    argv[n++] = out;
    for (int i = 0; extra && extra[i]; ++i) argv[n++] = extra[i];
    argv[n] = NULL;
}

static cli_result run_to(const char *const *args, const char *out, const char *const *extra)
{
    const char *argv[32];
    with_output(args, out, extra, argv);
    return cli_run(argv);
}

/* The job's rows as one uninterrupted run writes them (caller frees). */
static char *reference(const char *const *args, const char *name)
{
    char out[128];
    path_in(out, sizeof out, name);
    cli_result r = run_to(args, out, NULL);
    char *text = r.status == 0 ? cli_run_slurp(out) : NULL;
    if (!text) fprintf(stderr, "reference run: %d %s\n", r.status, r.err);
    cli_result_free(&r);
    return text;
}

/* Runs the tool with its file size limited to limit bytes (RLIMIT_FSIZE). */
static cli_result run_limited(const char *const *argv, rlim_t limit)
{
    char out_tmp[64], err_tmp[64];
    struct rlimit old;
    getrlimit(RLIMIT_FSIZE, &old);
    const struct rlimit lim = {old.rlim_max < limit ? old.rlim_max : limit, old.rlim_max};
    /* The soft limit, inherited by the child and put back after (the test's own files are small). */
    setrlimit(RLIMIT_FSIZE, &lim);
    const pid_t pid = cli_run_start(argv, NULL, out_tmp, err_tmp);
    setrlimit(RLIMIT_FSIZE, &old);
    return cli_run_wait(pid, out_tmp, err_tmp, 1);
}

/* ---- the test's own checksums ---- */

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

/* A row's checksum: FNV-1a over the job's hash (8 bytes, little-endian) then the row. */
static uint64_t row_sum(uint64_t job, const char *row, size_t len)
{
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = (unsigned char)(job >> (8 * i));
    return fnv(fnv(0xcbf29ce484222325ULL, b, 8), row, len);
}

/* The job's hash from the .part's first line. */
static uint64_t job_of(const char *text)
{
    const char *j = strstr(text, " job ");
    return j ? strtoull(j + 5, NULL, 16) : 0;
}

/* Whether every row of a .part (from line first_row, 1-based) ends in its
 * checksum and the file ends on a whole row; *rows: how many. */
static int rows_whole_and_summed(const char *text, int first_row, long *rows)
{
    const uint64_t job = job_of(text);
    long line_no = 0;
    *rows = 0;
    for (const char *p = text; *p;) {
        const char *nl = strchr(p, '\n');
        if (!nl) return 0; /* a row cut short */
        ++line_no;
        const size_t n = (size_t)(nl - p);
        if (line_no >= first_row) {
            if (n < 17 || p[n - 17] != '\t' || strtoull(p + n - 16, NULL, 16) != row_sum(job, p, n - 17)) return 0;
            ++*rows;
        }
        p = nl + 1;
    }
    return 1;
}

/* ---- tests ---- */

static int test_symlink_part_is_refused(void)
{
    char lnk[160], target[160], out[128], sub[128];
    path_in(sub, sizeof sub, "elsewhere");
    mkdir(sub, 0700);
    path_in(out, sizeof out, "L.csv");
    snprintf(lnk, sizeof lnk, "%s.part", out);
    snprintf(target, sizeof target, "%s/planted.txt", sub);
    ENSURE(symlink(target, lnk) == 0);
    const char *const *jobs[] = {SWEEP, (const char *const[]){"mc", "--samples", "20", "--quiet", NULL}};
    for (int k = 0; k < 2; ++k) {
        cli_result r = run_to(jobs[k], out, NULL);
        ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "symbolic link"), "%s: %d %s", jobs[k][0],
                   r.status, r.err);
        ENSURE_MSG(!cli_file_exists(target) && !cli_file_exists(out), "%s wrote through the link", jobs[k][0]);
        cli_result_free(&r);
    }
    /* --resume with a link to a file that is not the tool's: refused, the file unchanged */
    static const char precious[] = "precious\0\1";
    FILE *f = fopen(target, "wb");
    ENSURE(f && fwrite(precious, 1, 10, f) == 10 && fclose(f) == 0);
    const char *resume[] = {"--resume", NULL};
    cli_result r = run_to(SWEEP, out, resume);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "symbolic link"), "%d %s", r.status, r.err);
    cli_result_free(&r);
    struct stat st;
    char *after = cli_run_slurp(target);
    ENSURE(after && stat(target, &st) == 0 && st.st_size == 10 && memcmp(after, precious, 10) == 0);
    free(after);
    /* a plain file there without a newline: not the tool's, left as it is */
    remove(lnk);
    f = fopen(lnk, "wb");
    ENSURE(f && fwrite(precious, 1, 10, f) == 10 && fclose(f) == 0);
    r = run_to(SWEEP, out, resume);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "not a .part file"), "%d %s", r.status, r.err);
    cli_result_free(&r);
    after = cli_run_slurp(lnk);
    ENSURE(after && stat(lnk, &st) == 0 && st.st_size == 10 && memcmp(after, precious, 10) == 0);
    free(after);
    /* a hard link to another file: not written through either */
    remove(lnk);
    ENSURE(link(target, lnk) == 0);
    r = run_to(SWEEP, out, resume);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "hard link"), "%d %s", r.status, r.err);
    cli_result_free(&r);
    after = cli_run_slurp(target);
    ENSURE(after && memcmp(after, precious, 10) == 0 && !cli_file_exists(out));
    free(after);
    remove(lnk);
    return 0;
}

/* A .part cut by the file size limit: its text (caller frees), or NULL. */
static char *stopped_part(const char *const *args, const char *out, rlim_t limit)
{
    char part[160];
    snprintf(part, sizeof part, "%s.part", out);
    remove(out);
    remove(part);
    const char *argv[32];
    with_output(args, out, NULL, argv);
    cli_result r = run_limited(argv, limit);
    char *text = r.status == 1 ? cli_run_slurp(part) : NULL;
    if (!text) fprintf(stderr, "limited run: %d %s\n", r.status, r.err);
    cli_result_free(&r);
    return text;
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    return f && fputs(text, f) >= 0 && fclose(f) == 0 ? 0 : -1;
}

/* Row k (0-based) of a .part: the start of its line (line k + 3: the job
 * line and the header come first). */
static char *part_row(char *text, int k)
{
    char *p = text;
    for (int i = 0; i < k + 2 && p; ++i) {
        p = strchr(p, '\n');
        if (p) ++p;
    }
    return p;
}

static int test_forged_rows_are_refused(void)
{
    char out[128], part[160];
    path_in(out, sizeof out, "forged.csv");
    snprintf(part, sizeof part, "%s.part", out);
    char *text = stopped_part(SWEEP, out, 40000);
    ENSURE(text != NULL);
    char *row5 = part_row(text, 5), *term = row5 ? strstr(row5, "ramp_end") : NULL;
    ENSURE_MSG(term && term < strchr(row5, '\n'), "row 5 has no ramp_end: %.200s", row5 ? row5 : "");
    memcpy(term, "ramp_enX", 8);
    ENSURE(write_text(part, text) == 0);
    const char *resume[] = {"--resume", NULL};
    cli_result r = run_to(SWEEP, out, resume);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "line 8 (case 5)") && strstr(r.err, "checksum"),
               "%d %s", r.status, r.err);
    cli_result_free(&r);
    char *after = cli_run_slurp(part);
    ENSURE_MSG(after && strcmp(after, text) == 0 && !cli_file_exists(out), "the refused file was changed");
    free(after);
    free(text);

    /* mc: first_liftoff_x_m = 99 in every row, each with a valid checksum
     * (column 8 of "case,4 inputs...": found by name in the header) */
    const char *mc[] = {"mc", "--samples", "500", "--no-defaults", "--sigma", "theta0=2", "--quiet", NULL};
    path_in(out, sizeof out, "forged_mc.csv");
    snprintf(part, sizeof part, "%s.part", out);
    text = stopped_part(mc, out, 60000);
    ENSURE(text != NULL);
    long rows = 0;
    ENSURE(rows_whole_and_summed(text, 3, &rows) && rows > 20);
    const char *header = strchr(text, '\n') + 1;
    int column = 0;
    for (const char *p = header; p < strstr(header, "first_liftoff_x_m"); ++p) column += *p == ',';
    const uint64_t job = job_of(text);
    char *forged = malloc(strlen(text) * 2 + 64), *o = forged;
    const char *p = text;
    for (int line = 1; *p; ++line) {
        const char *nl = strchr(p, '\n');
        const size_t n = (size_t)(nl - p);
        if (line < 3) {
            memcpy(o, p, n + 1);
            o += n + 1;
        } else {
            char row[2048];
            size_t len = 0;
            int field = 0;
            for (const char *q = p; q < p + n - 17; ++q) {
                if (field == column && *q != ',') continue;
                if (*q == ',' && ++field == column) {
                    len += (size_t)snprintf(row + len, sizeof row - len, ",99");
                    continue;
                }
                row[len++] = *q;
            }
            o += sprintf(o, "%.*s\t%016llx\n", (int)len, row, (unsigned long long)row_sum(job, row, len));
        }
        p = nl + 1;
    }
    *o = '\0';
    ENSURE(write_text(part, forged) == 0);
    long again = 0;
    ENSURE_MSG(rows_whole_and_summed(forged, 3, &again) && again == rows, "the forgery's checksums");
    r = run_to(mc, out, resume);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && strstr(r.err, "computed again") && strstr(r.err, "seed"),
               "%d %s", r.status, r.err);
    ENSURE(strstr(r.out, "9900") == NULL);
    printf("  %ld forged rows with valid checksums: %s", rows, r.err);
    cli_result_free(&r);
    after = cli_run_slurp(part);
    ENSURE(after && strcmp(after, forged) == 0);
    free(after);
    free(forged);
    free(text);
    remove(part);
    return 0;
}

static void sleep_s(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

static const char *const LONG_SWEEP[] = {"sweep", "--vary", "incline=20:40:0.005", "--vary", "mu=0.3,0.6,0.9",
                                         "--threads", "1", "--quiet", NULL};

/* A second job on the output while the first runs: refused, with and
 * without --resume; the first ends with its whole file. */
static int test_second_job_is_refused(void)
{
    char out[128], part[160];
    path_in(out, sizeof out, "locked.csv");
    snprintf(part, sizeof part, "%s.part", out);
    char *expected = reference(LONG_SWEEP, "locked_ref.csv");
    ENSURE(expected != NULL);
    const char *argv[32];
    with_output(LONG_SWEEP, out, NULL, argv);
    char out_tmp[64], err_tmp[64];
    const pid_t first = cli_run_start(argv, NULL, out_tmp, err_tmp);
    ENSURE(first > 0);
    for (int i = 0; i < 2000 && !cli_file_exists(part); ++i) sleep_s(0.002);
    const char *resume[] = {"--resume", NULL};
    cli_result a = run_to(LONG_SWEEP, out, NULL), b = run_to(LONG_SWEEP, out, resume);
    cli_result r = cli_run_wait(first, out_tmp, err_tmp, 1);
    ENSURE_MSG(r.status == 0, "the first job: %d %s", r.status, r.err);
    ENSURE_MSG(a.status == 2 && cli_one_line(a.err) && strstr(a.err, "another job is writing"), "%d %s", a.status,
               a.err);
    ENSURE_MSG(b.status == 2 && cli_one_line(b.err) && strstr(b.err, "another job is writing"), "%d %s", b.status,
               b.err);
    char *got = cli_run_slurp(out);
    ENSURE(got && strcmp(got, expected) == 0 && !cli_file_exists(part));
    free(got);
    free(expected);
    cli_result_free(&a);
    cli_result_free(&b);
    cli_result_free(&r);
    return 0;
}

#define RACERS 20

static int test_twenty_jobs_race(void)
{
    char out[128], part[160];
    path_in(out, sizeof out, "race.csv");
    snprintf(part, sizeof part, "%s.part", out);
    char *expected = reference(LONG_SWEEP, "race_ref.csv");
    ENSURE(expected != NULL);
    const char *argv[32];
    with_output(LONG_SWEEP, out, NULL, argv);
    char out_tmp[RACERS][64], err_tmp[RACERS][64];
    pid_t pid[RACERS];
    for (int i = 0; i < RACERS; ++i) pid[i] = cli_run_start(argv, NULL, out_tmp[i], err_tmp[i]);
    int ok = 0, refused = 0;
    for (int i = 0; i < RACERS; ++i) {
        ENSURE(pid[i] > 0);
        cli_result r = cli_run_wait(pid[i], out_tmp[i], err_tmp[i], 1);
        if (r.status == 0) ++ok;
        else if (r.status == 2 && cli_one_line(r.err) &&
                 (strstr(r.err, "another job is writing") || strstr(r.err, "unfinished job")))
            ++refused;
        else fprintf(stderr, "racer %d: %d %s\n", i, r.status, r.err);
        cli_result_free(&r);
    }
    char *got = cli_run_slurp(out);
    ENSURE_MSG(ok == 1 && refused == RACERS - 1, "%d finished, %d refused", ok, refused);
    ENSURE_MSG(got && strcmp(got, expected) == 0 && !cli_file_exists(part), "the file is not one whole job's");
    printf("  %d jobs on one output: 1 finished with the whole file, %d refused\n", RACERS, refused);
    free(got);
    free(expected);
    return 0;
}

static int mode_of(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (int)(st.st_mode & 07777) : -1;
}

static int test_mode_is_kept(void)
{
    char out[128];
    path_in(out, sizeof out, "mode.csv");
    const char *const mc[] = {"mc", "--samples", "10", "--quiet", NULL};
    const char *const *jobs[] = {SWEEP, mc};
    for (int k = 0; k < 2; ++k) {
        ENSURE(write_text(out, "old\n") == 0 && chmod(out, 0600) == 0);
        cli_result r = run_to(jobs[k], out, NULL);
        ENSURE_MSG(r.status == 0 && mode_of(out) == 0600, "%s: %d, mode %o", jobs[k][0], r.status, mode_of(out));
        cli_result_free(&r);
        ENSURE(chmod(out, 0640) == 0);
        r = run_to(jobs[k], out, NULL);
        ENSURE_MSG(r.status == 0 && mode_of(out) == 0640, "%s: mode %o", jobs[k][0], mode_of(out));
        cli_result_free(&r);
        /* a new file: 0666 less the umask, as every output */
        remove(out);
        const mode_t mask = umask(022);
        r = run_to(jobs[k], out, NULL);
        umask(mask);
        ENSURE_MSG(r.status == 0 && mode_of(out) == 0644, "%s: new file mode %o", jobs[k][0], mode_of(out));
        cli_result_free(&r);
    }
    return 0;
}

/* "N rows kept in FILE.part": N. */
static long rows_kept(const char *err)
{
    const char *p = strstr(err, "; ");
    return p ? strtol(p + 2, NULL, 10) : -1;
}

/* The file size limit: the job stops on a whole row, says so, and --resume ends in the same bytes. */
static int test_file_size_limit_then_resume(void)
{
    char out[128], part[160];
    path_in(out, sizeof out, "fsize.csv");
    snprintf(part, sizeof part, "%s.part", out);
    char *expected = reference(SWEEP, "fsize_ref.csv");
    ENSURE(expected != NULL);
    const char *argv[32];
    with_output(SWEEP, out, NULL, argv);
    cli_result r = run_limited(argv, 50000);
    ENSURE_MSG(r.status == 1 && cli_one_line(r.err) && strstr(r.err, "File too large") && strstr(r.err, "--resume"),
               "%d %s", r.status, r.err);
    char *kept = cli_run_slurp(part);
    long rows = 0;
    ENSURE_MSG(kept && rows_whole_and_summed(kept, 3, &rows) && rows == rows_kept(r.err) && rows > 10 &&
                   rows < SWEEP_ROWS,
               "%ld whole rows kept; the message: %s", rows, r.err);
    printf("  ulimit -f 50000 bytes: %s", r.err);
    cli_result_free(&r);
    free(kept);
    const char *resume[] = {"--resume", NULL};
    r = run_to(SWEEP, out, resume);
    ENSURE_MSG(r.status == 0, "%d %s", r.status, r.err);
    cli_result_free(&r);
    char *got = cli_run_slurp(out);
    ENSURE_MSG(got && strcmp(got, expected) == 0 && !cli_file_exists(part), "the resumed file differs");
    free(got);
    free(expected);
    return 0;
}

/* A full file system: a small tmpfs in a user and mount namespace (no root
 * needed where the kernel allows unprivileged namespaces); skipped, saying
 * so, where it does not. */
static int test_full_disk_then_resume(void)
{
    if (system("unshare --user --map-root-user --mount true >/dev/null 2>&1") != 0) {
        printf("  (no user namespaces here: the full tmpfs is not tried; the file size limit test covers the cut)\n");
        return 0;
    }
    char fs[128], log[128], kept[128], final[128], script[16384];
    path_in(fs, sizeof fs, "fs");
    path_in(log, sizeof log, "full.err");
    path_in(kept, sizeof kept, "full.part");
    path_in(final, sizeof final, "full.csv");
    mkdir(fs, 0700);
    char tool[PATH_MAX];
    ENSURE(realpath(cli_run_tool, tool) != NULL); /* the script runs in the tmpfs */
    char *expected = reference(SWEEP, "full_ref.csv");
    ENSURE(expected != NULL);
    /* 96 KiB: the .part (about 200 bytes a row) fills it before the end;
     * then 4 MiB, and --resume. */
    const char *job = "sweep --vary incline=20:40:0.05 --vary mu=0.3,0.6 --quiet --output out.csv";
    snprintf(script, sizeof script,
             "unshare --user --map-root-user --mount sh -c '"
             "mount -t tmpfs -o size=96k none %s && cd %s && "
             "{ %s %s 2>%s; echo \"rc $?\" >>%s; cp out.csv.part %s; "
             "mount -o remount,size=4m %s && %s %s --resume 2>>%s; echo \"rc $?\" >>%s; cp out.csv %s; }'",
             fs, fs, tool, job, log, log, kept, fs, tool, job, log, log, final);
    ENSURE(system(script) == 0);
    char *err = cli_run_slurp(log);
    ENSURE(err != NULL);
    printf("  tmpfs of 96 KiB, then 4 MiB:\n%s", err);
    ENSURE_MSG(strstr(err, "no space left; ") && strstr(err, "rows kept in out.csv.part; free space and run again "
                                                            "with --resume") &&
                   strstr(err, "rc 1\n"),
               "%s", err);
    char *part = cli_run_slurp(kept);
    long rows = 0;
    ENSURE_MSG(part && rows_whole_and_summed(part, 3, &rows) && rows == rows_kept(err), "%ld rows, %s", rows, err);
    ENSURE_MSG(strstr(err, "resuming after") && strstr(strstr(err, "rc 1\n"), "rc 0\n"), "%s", err);
    char *got = cli_run_slurp(final);
    ENSURE_MSG(got && strcmp(got, expected) == 0, "the resumed file differs from the uninterrupted run");
    free(got);
    free(part);
    free(err);
    free(expected);
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    snprintf(dir, sizeof dir, "/tmp/jc_part_XXXXXX");
    if (!mkdtemp(dir)) return 2;
    RUN_TEST(test_symlink_part_is_refused);
    RUN_TEST(test_forged_rows_are_refused);
    RUN_TEST(test_mode_is_kept);
    RUN_TEST(test_file_size_limit_then_resume);
    RUN_TEST(test_full_disk_then_resume);
    RUN_TEST(test_second_job_is_refused);
    RUN_TEST(test_twenty_jobs_race);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    TEST_MAIN_END();
}
