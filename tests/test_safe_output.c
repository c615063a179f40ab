/* Safe output, through the built tool (argv[1]): file names are data,
 * outputs are whole or untouched, every signal and limit is handled.
 *
 * - hostile output names make exactly the named file and run nothing (a
 *   marker file that a command would create stays absent);
 * - a full disk (a small tmpfs when running as root, else none) and a file
 *   size limit (RLIMIT_FSIZE, as `ulimit -f`): a one-line error naming the
 *   file and the cause, the old file byte for byte, no temporary left;
 * - each stop signal while gnuplot or ffmpeg runs, and while the simulation
 *   behind a plot runs: exit 128 + signal, nothing printed as done, target
 *   unchanged, scratch and temporary files gone, the child gone;
 * - /dev/full, a FIFO as --config, repeated options, --csv -, read-only
 *   targets, the size budgets of plots and films, the stuck sampler;
 * - the resident memory of a 150,000-event run (wait4's ru_maxrss).
 * Children are found by polling /proc with a bounded timeout, not by
 * sleeping a guessed time, so the tests hold under `ctest -j`. */
#define _GNU_SOURCE /* wait4, mount */
#include "test.h"

#include "cli_run.h"

#include <dirent.h>
#include <errno.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>

/* The rocking hoop (the former hoop preset) as explicit parts, for the
 * budgets: a 60 s run of it makes a film of 14,400 frames. */
#define HOOP "--incline", "0", "--radius", "10cm", "--part", "hoop:mass=10g", "--part", \
             "point:mass=100g,offset=10cm", "--mu", "0.5", "--restitution", "1", "--omega0", "0.1"

/* An event-rich long run: the same hoop without friction, with elastic
 * impacts, spun just past the hopping threshold (d w^2 > g at 10.4 rad/s)
 * on a 62 km floor. Nothing dissipates, so it hops for ever: about 240,000
 * impacts before the floor ends (measured), more than the runs below ask. */
#define LONG_RUN "--incline", "0", "--radius", "10cm", "--part", "hoop:mass=10g", "--part", \
                 "point:mass=100g,offset=10cm", "--mu", "0", "--restitution", "1", "--omega0", "10.5", \
                 "--ramp-length", "62000m", "--t-max", "1e6"
#define LONG_RUN_EVENTS 150000

static char base[256]; /* this run's own directory */

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sleep_ms(long ms)
{
    const struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

/* A new empty directory under base. */
static int new_dir(char *out, size_t len, const char *name)
{
    static int serial;
    snprintf(out, len, "%s/%s-%d", base, name, ++serial);
    return mkdir(out, 0755);
}

/* A fresh directory named after `name`, and the paths of two files in it. */
static int dir_with_two(char dir[512], const char *name, char a[600], const char *name_a, char b[600],
                        const char *name_b)
{
    if (new_dir(dir, 512, name) != 0) return -1;
    snprintf(a, 600, "%s/%s", dir, name_a);
    snprintf(b, 600, "%s/%s", dir, name_b);
    return 0;
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    const int bad = fputs(text, f) == EOF;
    return fclose(f) != 0 || bad ? -1 : 0;
}

/* Entries of a directory (dot files too); the first name in first. */
static int entries(const char *dir, char *first, size_t len)
{
    DIR *d = opendir(dir);
    int n = 0;
    if (first) first[0] = '\0';
    for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        if (n++ == 0 && first) snprintf(first, len, "%s", e->d_name);
    }
    if (d) closedir(d);
    return n;
}

/* Exactly one message of the tool on stderr (a sanitizer's statistics
 * may follow it in the sanitizer build). */
static int one_message(const char *err)
{
    int n = 0;
    for (const char *p = err; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : p + strlen(p))
        n += strncmp(p, "jumpcyl:", 8) == 0;
    return n == 1 && (strncmp(err, "jumpcyl:", 8) == 0);
}

static int same_content(const char *path, const char *text)
{
    char *got = cli_run_slurp(path);
    const int same = got && strcmp(got, text) == 0;
    free(got);
    return same;
}

/* The pid of a child of parent whose command name starts with comm, 0 if none. */
static pid_t find_child(pid_t parent, const char *comm)
{
    DIR *d = opendir("/proc");
    pid_t found = 0;
    for (struct dirent *e; d && !found && (e = readdir(d)) != NULL;) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        char path[300], stat_line[512];
        snprintf(path, sizeof path, "/proc/%s/stat", e->d_name);
        FILE *f = fopen(path, "r");
        if (!f) continue;
        const size_t n = fread(stat_line, 1, sizeof stat_line - 1, f);
        fclose(f);
        stat_line[n] = '\0';
        /* "pid (comm) state ppid ..." */
        const char *open = strchr(stat_line, '('), *close = strrchr(stat_line, ')');
        if (!open || !close || close < open) continue;
        int ppid = 0;
        char state;
        if (sscanf(close + 1, " %c %d", &state, &ppid) != 2 || ppid != parent) continue;
        if (strncmp(open + 1, comm, strlen(comm)) == 0) found = (pid_t)atoi(e->d_name);
    }
    if (d) closedir(d);
    return found;
}

/* Polls until the child appears or timeout_s passes; its pid or 0. */
static pid_t wait_for_child(pid_t parent, const char *comm, double timeout_s)
{
    const double end = now_s() + timeout_s;
    while (now_s() < end) {
        const pid_t c = find_child(parent, comm);
        if (c) return c;
        sleep_ms(2);
    }
    return 0;
}

/* Polls until dir has at least one entry; 1 if it did in time. */
static int wait_for_entry(const char *dir, double timeout_s)
{
    const double end = now_s() + timeout_s;
    while (now_s() < end) {
        if (entries(dir, NULL, 0) > 0) return 1;
        sleep_ms(2);
    }
    return 0;
}

/* Not running: gone, or a zombie (killed, waiting for init to reap it). */
static int process_gone(pid_t pid)
{
    char path[64], line[512];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    FILE *f = fopen(path, "r");
    if (!f) return 1;
    const size_t n = fread(line, 1, sizeof line - 1, f);
    fclose(f);
    line[n] = '\0';
    const char *close = strrchr(line, ')');
    return close && close[1] == ' ' && (close[2] == 'Z' || close[2] == 'X');
}

/* Runs the tool with TMPDIR set (NULL: unchanged). */
static cli_result run_env(const char *const *args, const char *tmpdir)
{
    char *old_tmp = getenv("TMPDIR") ? strdup(getenv("TMPDIR")) : NULL;
    if (tmpdir) setenv("TMPDIR", tmpdir, 1);
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
    if (old_tmp) setenv("TMPDIR", old_tmp, 1);
    else unsetenv("TMPDIR");
    free(old_tmp);
    return cli_run_wait(pid, out_tmp, err_tmp, 1);
}

/* The same with the limit applied in the child: the parent lowers its own
 * soft limit only around the fork. */
static cli_result run_limited(const char *const *args, const char *tmpdir, rlim_t fsize)
{
    struct rlimit old_lim, lim;
    getrlimit(RLIMIT_FSIZE, &old_lim);
    char *old_tmp = getenv("TMPDIR") ? strdup(getenv("TMPDIR")) : NULL;
    if (tmpdir) setenv("TMPDIR", tmpdir, 1);
    char out_tmp[64], err_tmp[64];
    /* The capture files exist (empty) before the limit applies. */
    strcpy(out_tmp, "/tmp/jc_cli_out_XXXXXX");
    strcpy(err_tmp, "/tmp/jc_cli_err_XXXXXX");
    const int fo = mkstemp(out_tmp), fe = mkstemp(err_tmp);
    if (fo >= 0) close(fo);
    if (fe >= 0) close(fe);
    fflush(NULL);
    lim = old_lim;
    lim.rlim_cur = fsize;
    setrlimit(RLIMIT_FSIZE, &lim);
    const pid_t pid = fork();
    if (pid == 0) cli_run_child(args, out_tmp, err_tmp);
    setrlimit(RLIMIT_FSIZE, &old_lim);
    if (old_tmp) setenv("TMPDIR", old_tmp, 1);
    else unsetenv("TMPDIR");
    free(old_tmp);
    return cli_run_wait(pid, out_tmp, err_tmp, 1);
}

/* ---- names ---- */

/* A command in a name would create the file $JC_MARKER (an absolute path set
 * in the environment, which a shell started by gnuplot inherits), wherever
 * it ran: in the figure's directory or in the scratch directory. */
static const char *const hostile[] = {
    "<touch $JC_MARKER #.png", "|touch $JC_MARKER #.png", "a'b\"c.png", "back\\slash.png", "new\nline.png",
    "sp ace.png", "-dash.png", "\xc3\xbcn\xc3\xaf.png", "$(touch $JC_MARKER).png", "`touch $JC_MARKER`.png",
    "x;touch $JC_MARKER;.svg", "'; system('touch $JC_MARKER') #.pdf",
};

static char marker[600];

static int marker_exists(void)
{
    struct stat st;
    return stat(marker, &st) == 0;
}

/* A new directory under base, made the working directory; *cwd keeps the old. */
static int enter_new_dir(const char *name, char *cwd, size_t len)
{
    char dir[512];
    return getcwd(cwd, len) != NULL && new_dir(dir, sizeof dir, name) == 0 && chdir(dir) == 0 ? 0 : -1;
}

/* Each name: exit 0, exactly that one file in the directory, no marker. */
static int test_injection_names(void)
{
    char cwd[1024];
    for (size_t i = 0; i < sizeof hostile / sizeof hostile[0]; ++i) {
        ENSURE(enter_new_dir("names", cwd, sizeof cwd) == 0);
        const char *args[] = {"plot", "--what", "paper-criterion", "--output", hostile[i], NULL};
        cli_result r = cli_run(args);
        char first[512];
        const int n = entries(".", first, sizeof first);
        const int ok = r.status == 0 && n == 1 && strcmp(first, hostile[i]) == 0;
        if (!ok) fprintf(stderr, "name %zu: status %d, %d entries (first '%s'), stderr: %s", i, r.status, n, first,
                         r.err ? r.err : "");
        cli_result_free(&r);
        ENSURE(chdir(cwd) == 0);
        ENSURE_MSG(ok, "name %zu did not make exactly itself", i);
        ENSURE_MSG(!marker_exists(), "name %zu ran a command: the marker exists", i);
    }
    return 0;
}

/* The kept script of a hostile name, run by hand with gnuplot, runs nothing
 * and reads no file: its data are inside it. */
static int test_injection_kept_script(void)
{
    char cwd[1024];
    ENSURE(enter_new_dir("kept", cwd, sizeof cwd) == 0);
    const char *args[] = {"plot", "--what", "energy", "--keep-script", "--output", "<touch $JC_MARKER #.png", NULL};
    cli_result r = cli_run(args);
    const int status = r.status;
    cli_result_free(&r);
    const int two = entries(".", NULL, 0) == 2;
    struct stat st;
    const int has_script = stat("<touch $JC_MARKER #.gp", &st) == 0;
    /* By hand, as a researcher would: the script under a plain name. */
    const int renamed = rename("<touch $JC_MARKER #.gp", "kept.gp") == 0;
    const int ran = renamed && system("gnuplot kept.gp >/dev/null 2>&1") == 0;
    const int ran_command = marker_exists();
    const int figure = stat("f_touch__JC_MARKER__.png", &st) == 0 && st.st_size > 1000;
    ENSURE(chdir(cwd) == 0);
    ENSURE_MSG(status == 0, "status %d", status);
    ENSURE_MSG(two && has_script, "the figure and its script are not exactly what was made");
    ENSURE_MSG(ran, "gnuplot failed on the kept script");
    ENSURE_MSG(!ran_command, "a command ran: the marker exists");
    ENSURE_MSG(figure, "the kept script did not write its figure under the safe name");
    return 0;
}

/* ffmpeg reads names only as files: a URL-like name and a leading '-'. */
static int test_ffmpeg_names(void)
{
    char cwd[1024];
    ENSURE(enter_new_dir("films", cwd, sizeof cwd) == 0);
    ENSURE(mkdir("tcp:", 0755) == 0 && mkdir("tcp:/127.0.0.1:9", 0755) == 0);
    const char *names[] = {"tcp://127.0.0.1:9/x.gif", "-y.gif", "pipe:1.gif"};
    int ok = 1;
    for (size_t i = 0; i < 3; ++i) {
        const char *args[] = {"animate", "--size", "64x64", "--fps", "5", "--slowmo", "1", "--output", names[i], NULL};
        cli_result r = cli_run(args);
        struct stat st;
        const int made = stat(names[i], &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 100;
        if (r.status != 0 || !made) {
            fprintf(stderr, "'%s': status %d, made %d, stderr: %s", names[i], r.status, made, r.err ? r.err : "");
            ok = 0;
        }
        cli_result_free(&r);
    }
    const int count = entries(".", NULL, 0); /* tcp:, -y.gif, pipe:1.gif */
    ENSURE(chdir(cwd) == 0);
    ENSURE(ok);
    ENSURE_MSG(count == 3, "%d entries", count);
    return 0;
}

/* ---- full disk and file size limit ---- */

#define OLD_TEXT "the old file: must survive byte for byte\n"

/* Fills the file system of dir until ENOSPC. */
static void fill(const char *dir)
{
    char path[600];
    snprintf(path, sizeof path, "%s/filler", dir);
    FILE *f = fopen(path, "wb");
    static const char block[4096];
    while (f && fwrite(block, 1, sizeof block, f) == sizeof block) {}
    if (f) fclose(f);
    /* Small remainders: the last bytes too. */
    f = fopen(path, "ab");
    while (f && fputc('x', f) != EOF && fflush(f) == 0) {}
    if (f) fclose(f);
}

/* One failed write: status 1, one line naming the file and cause, the old
 * file as it was, nothing else new in the directory (old file + filler). */
static int expect_refused(const char *const *args, const char *tmpdir, const char *dir, const char *target,
                          const char *cause, int other_entries)
{
    cli_result r = run_env(args, tmpdir);
    const char *name = strrchr(target, '/') + 1;
    const int ok = r.status == 1 && r.err && one_message(r.err) && strstr(r.err, name) && strstr(r.err, cause);
    if (!ok) fprintf(stderr, "status %d, stderr: %s", r.status, r.err ? r.err : "");
    const int quiet = r.out && !strstr(r.out, "Figure:");
    cli_result_free(&r);
    ENSURE_MSG(ok, "expected one line naming %s and '%s'", name, cause);
    ENSURE_MSG(quiet, "printed as done");
    ENSURE_MSG(same_content(target, OLD_TEXT), "the old file changed");
    ENSURE_MSG(entries(dir, NULL, 0) == 1 + other_entries, "%d entries left in %s", entries(dir, NULL, 0), dir);
    return 0;
}

static int test_disk_full(void)
{
    if (geteuid() != 0) {
        printf("skipped: test_disk_full needs root to mount a small tmpfs (the file size limit test still runs)\n");
        return 0;
    }
    char dir[512], target[600], csv[600];
    ENSURE(new_dir(dir, sizeof dir, "full") == 0);
    if (mount("tmpfs", dir, "tmpfs", 0, "size=512k") != 0) {
        printf("skipped: test_disk_full: mount tmpfs: %s\n", strerror(errno));
        return 0;
    }
    snprintf(target, sizeof target, "%s/fig.png", dir);
    snprintf(csv, sizeof csv, "%s/run.csv", dir);
    int bad = write_text(target, OLD_TEXT) != 0 || write_text(csv, OLD_TEXT) != 0;
    fill(dir);
    /* gnuplot renders in /tmp; the copy beside the target finds the disk full. */
    const char *plot[] = {"plot", "--what", "energy", "--output", target, NULL};
    if (!bad) bad = expect_refused(plot, NULL, dir, target, "No space left on device", 2);
    /* Scratch on the full disk too: gnuplot's own write fails. */
    if (!bad) bad = expect_refused(plot, dir, dir, target, "No space left on device", 2);
    const char *sim[] = {"simulate", "--sample-dt", "1e-4", "--csv", csv, NULL};
    if (!bad) bad = expect_refused(sim, NULL, dir, csv, "No space left on device", 2);
    umount2(dir, MNT_DETACH);
    return bad;
}

static int test_file_size_limit(void)
{
    char dir[512], target[600], csv[600];
    ENSURE(new_dir(dir, sizeof dir, "fsize") == 0);
    snprintf(target, sizeof target, "%s/fig.png", dir);
    snprintf(csv, sizeof csv, "%s/run.csv", dir);
    ENSURE(write_text(target, OLD_TEXT) == 0 && write_text(csv, OLD_TEXT) == 0);
    const char *sim[] = {"simulate", "--sample-dt", "1e-4", "--csv", csv, NULL};
    cli_result r = run_limited(sim, NULL, 20000);
    int ok = r.status == 1 && r.err && one_message(r.err) && strstr(r.err, "run.csv: File too large");
    if (!ok) fprintf(stderr, "simulate: status %d (signal %d), stderr: %s", r.status, r.signal, r.err ? r.err : "");
    cli_result_free(&r);
    ENSURE_MSG(ok, "simulate under a file size limit");
    /* gnuplot's figure (and our copy of it) are larger than the limit. */
    const char *plot[] = {"plot", "--what", "energy", "--output", target, NULL};
    r = run_limited(plot, dir, 20000);
    ok = r.status == 1 && r.err && one_message(r.err) && strstr(r.err, "fig.png") &&
         (strstr(r.err, "File too large") || strstr(r.err, "not a complete PNG"));
    if (!ok) fprintf(stderr, "plot: status %d (signal %d), stderr: %s", r.status, r.signal, r.err ? r.err : "");
    cli_result_free(&r);
    ENSURE_MSG(ok, "plot under a file size limit");
    ENSURE(same_content(target, OLD_TEXT) && same_content(csv, OLD_TEXT));
    ENSURE_MSG(entries(dir, NULL, 0) == 2, "%d entries (temporary or scratch files left)", entries(dir, NULL, 0));
    return 0;
}

/* ---- signals ---- */

/* Starts args with TMPDIR = scratch, waits for a child named comm (or, with
 * comm NULL, for the scratch directory to appear), sends sig (twice when
 * twice), and checks the outcome. */
static int stop_while(const char *const *args, const char *comm, int sig, int twice, const char *dir,
                      const char *target)
{
    char scratch[600];
    snprintf(scratch, sizeof scratch, "%s/scratch", dir);
    ENSURE(mkdir(scratch, 0700) == 0);
    setenv("TMPDIR", scratch, 1);
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
    unsetenv("TMPDIR");
    ENSURE(pid > 0);
    pid_t child = 0;
    int seen = 0;
    if (comm) seen = (child = wait_for_child(pid, comm, 120.0)) != 0;
    else seen = wait_for_entry(scratch, 120.0);
    kill(pid, sig);
    /* Another signal, so that the two cannot merge into one pending signal. */
    if (twice) kill(pid, SIGINT);
    cli_result r = cli_run_wait(pid, out_tmp, err_tmp, 1);
    /* Twice: ended by the second signal, or (when the first was handled
     * before the second came) by the normal path of the first. */
    const int status_ok = twice ? (r.signal == SIGINT || r.status == 128 + sig) : r.status == 128 + sig;
    const int quiet = r.out && !strstr(r.out, "Figure:") && !strstr(r.out, "Animation:");
    const int said = twice || sig == SIGPIPE || (r.err && strstr(r.err, "stopped by") && one_message(r.err));
    if (!status_ok || !said)
        fprintf(stderr, "signal %d%s: status %d (signal %d), stderr: %s", sig, twice ? " twice" : "", r.status,
                r.signal, r.err ? r.err : "");
    cli_result_free(&r);
    const int scratch_left = entries(scratch, NULL, 0);
    rmdir(scratch);
    ENSURE_MSG(seen, "%s never appeared", comm ? comm : "the scratch directory");
    ENSURE_MSG(status_ok, "exit status, expected %d", 128 + sig);
    ENSURE_MSG(said, "one line saying what stopped it");
    ENSURE_MSG(quiet, "printed as done");
    ENSURE_MSG(scratch_left == 0, "%d scratch entries left", scratch_left);
    ENSURE_MSG(same_content(target, OLD_TEXT), "the target changed");
    ENSURE_MSG(entries(dir, NULL, 0) == 1, "%d entries (temporary files left)", entries(dir, NULL, 0));
    /* Reaped by the tool: gone, not a zombie of init's. Give a killed
     * orphan (second signal) a moment to end. */
    for (int i = 0; child && i < 2000 && !process_gone(child); ++i) sleep_ms(5);
    ENSURE_MSG(!child || process_gone(child), "%s (pid %d) is still running", comm, (int)child);
    return 0;
}

/* Each stop signal, sent while the child comm runs "args --output DIR/file". */
static int each_stop_signal(const char *comm, const char *file, const char *const *args)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; ++i) {
        char dir[512], target[600];
        ENSURE(new_dir(dir, sizeof dir, comm) == 0);
        snprintf(target, sizeof target, "%s/%s", dir, file);
        ENSURE(write_text(target, OLD_TEXT) == 0);
        const char *argv[32];
        int n = 0;
        for (; n < 28 && args[n]; ++n) argv[n] = args[n];
        argv[n++] = "--output";
        argv[n++] = target;
        argv[n] = NULL;
        if (stop_while(argv, comm, sigs[i], 0, dir, target)) return 1;
    }
    return 0;
}

static int test_signals_while_gnuplot_runs(void)
{
    /* 130,000 samples on four panels: gnuplot renders for seconds. */
    const char *args[] = {"plot", "--what", "overview", "--incline", "45", "--sample-dt", "1e-5",
                          "--max-samples", "1000000", NULL};
    return each_stop_signal("gnuplot", "fig.png", args);
}

/* ffmpeg starts once every frame is drawn, and the signal goes as soon as
 * it runs. A small film (278 frames of 160x90) keeps ffmpeg busy for about
 * a second; the full-size one (1280x720: ffmpeg for about 20 s, but the
 * frames take 20 s of CPU to draw, for each of the five signals) is in the
 * long tests (ctest label "long", make test-long). */
static int signals_while_ffmpeg_runs(const char *size)
{
    const char *args[] = {"animate", "--incline", "45", "--size", size, NULL};
    return each_stop_signal("ffmpeg", "film.mp4", args);
}

static int test_signals_while_ffmpeg_runs(void) { return signals_while_ffmpeg_runs("160x90"); }

static int test_signals_while_ffmpeg_runs_full_size(void) { return signals_while_ffmpeg_runs("1280x720"); }

/* A long simulation behind a plot (its first run, which keeps nothing). */
static int test_signal_while_simulating(void)
{
    char dir[512], target[600];
    ENSURE(new_dir(dir, sizeof dir, "sig-sim") == 0);
    snprintf(target, sizeof target, "%s/fig.png", dir);
    ENSURE(write_text(target, OLD_TEXT) == 0);
    const char *args[] = {"plot", "--what", "energy", LONG_RUN, "--max-events", "150000", "--output", target, NULL};
    return stop_while(args, NULL, SIGINT, 0, dir, target);
}

/* Two signals (SIGTERM, then SIGINT): the second ends the process at once;
 * its handler still removes the scratch directory and ends gnuplot. */
static int test_second_signal(void)
{
    char dir[512], target[600];
    ENSURE(new_dir(dir, sizeof dir, "sig-twice") == 0);
    snprintf(target, sizeof target, "%s/fig.png", dir);
    ENSURE(write_text(target, OLD_TEXT) == 0);
    const char *args[] = {"plot", "--what", "overview", "--incline", "45", "--sample-dt", "1e-5",
                          "--max-samples", "1000000", "--output", target, NULL};
    return stop_while(args, "gnuplot", SIGTERM, 1, dir, target);
}

/* ---- inputs, options, standard output ---- */

/* "jumpcyl ARGS" (standard output to stdout_path, NULL: captured) ends with
 * status and one message containing needle, and prints nothing. */
static int expect_error(const char *const *args, const char *stdout_path, int status, const char *needle)
{
    cli_result r = cli_run_to(args, stdout_path);
    const int ok = r.status == status && r.err && one_message(r.err) && strstr(r.err, needle) && r.out &&
                   r.out[0] == '\0';
    if (!ok) {
        fprintf(stderr, "'%s %s ...': status %d, stdout %zu bytes, stderr: %s", args[0], args[1] ? args[1] : "",
                r.status, r.out ? strlen(r.out) : 0, r.err ? r.err : "");
    }
    cli_result_free(&r);
    ENSURE_MSG(ok, "expected status %d and '%s'", status, needle);
    return 0;
}

static int test_dev_full(void)
{
    const char *help[] = {"--help", NULL};
    const char *sim_help[] = {"simulate", "--help", NULL};
    const char *json[] = {"simulate", "--json", NULL};
    const char *csv[] = {"simulate", "--csv", "/dev/full", NULL};
    const char *const *cases[] = {help, sim_help, json};
    for (int i = 0; i < 3; ++i)
        if (expect_error(cases[i], "/dev/full", 1, "standard output: No space left on device")) return 1;
    if (expect_error(csv, NULL, 1, "/dev/full: No space left on device")) return 1;
    /* A closed standard output is an error too, not a silent success. */
    if (expect_error(help, CLI_RUN_CLOSED, 1, "standard output: Bad file descriptor")) return 1;
    return 0;
}

static int test_fifo_config(void)
{
    char dir[512], fifo[600];
    ENSURE(new_dir(dir, sizeof dir, "fifo") == 0);
    snprintf(fifo, sizeof fifo, "%s/setup.ini", dir);
    ENSURE(mkfifo(fifo, 0600) == 0);
    const char *args[] = {"simulate", "--config", fifo, NULL};
    const double t0 = now_s();
    cli_result r = cli_run(args); /* would block forever on open() without O_NONBLOCK */
    const double took = now_s() - t0;
    const int ok = r.status == 2 && r.err && one_message(r.err) && strstr(r.err, "not a regular file");
    if (!ok) fprintf(stderr, "status %d, stderr: %s", r.status, r.err ? r.err : "");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE_MSG(took < 10.0, "took %.1f s", took);
    const char *dev[] = {"simulate", "--config", "/dev/zero", NULL};
    return expect_error(dev, NULL, 2, "/dev/zero: not a regular file");
}

static int test_repeated_options(void)
{
    char dir[512], a[600], b[600];
    ENSURE(new_dir(dir, sizeof dir, "repeat") == 0);
    snprintf(a, sizeof a, "%s/a.csv", dir);
    snprintf(b, sizeof b, "%s/b.csv", dir);
    const char *csv[] = {"simulate", "--csv", a, "--csv", b, NULL};
    const char *json[] = {"simulate", "--json", "--json", NULL};
    const char *keep[] = {"plot", "--what", "energy", "--keep-script", "--keep-script", "--output", a, NULL};
    const char *frames[] = {"animate", "--max-frames", "10", "--max-frames", "20", "--output", a, NULL};
    const char *incline[] = {"simulate", "--incline", "10", "--incline", "20", NULL};
    const char *const *cases[] = {csv, json, keep, frames, incline};
    const char *names[] = {"--csv given twice", "--json given twice", "--keep-script given twice",
                           "--max-frames given twice", "--incline given twice"};
    for (int i = 0; i < 5; ++i)
        if (expect_error(cases[i], NULL, 2, names[i])) return 1;
    ENSURE_MSG(entries(dir, NULL, 0) == 0, "a file was written");
    return 0;
}

static int test_csv_to_stdout(void)
{
    char cwd[1024];
    ENSURE(enter_new_dir("csv-stdout", cwd, sizeof cwd) == 0);
    const char *args[] = {"simulate", "--sample-dt", "0.01", "--csv", "-", NULL};
    cli_result r = cli_run(args);
    int rows = 0;
    for (const char *p = r.out; p && *p; ++p) rows += *p == '\n';
    const int header = r.out && strncmp(r.out, "t_s,mode,x_m", 12) == 0;
    const int status = r.status;
    cli_result_free(&r);
    const int left = entries(".", NULL, 0);
    const char *both[] = {"simulate", "--json", "--csv", "-", NULL};
    r = cli_run(both);
    const int refused = r.status == 2 && r.err && strstr(r.err, "standard output");
    cli_result_free(&r);
    ENSURE(chdir(cwd) == 0);
    ENSURE(status == 0 && header);
    /* 1.3 s at 10 ms plus a row per event and the header. */
    ENSURE_MSG(rows > 130 && rows < 150, "%d lines", rows);
    ENSURE_MSG(left == 0, "a file named '-' (or another) was made");
    ENSURE(refused);
    return 0;
}

static int test_read_only_target(void)
{
    char dir[512], fig[600], csv[600];
    ENSURE(dir_with_two(dir, "readonly", fig, "fig.png", csv, "run.csv") == 0);
    ENSURE(write_text(fig, OLD_TEXT) == 0 && write_text(csv, OLD_TEXT) == 0);
    ENSURE(chmod(fig, 0444) == 0 && chmod(csv, 0444) == 0);
    const char *plot[] = {"plot", "--what", "energy", "--output", fig, NULL};
    const char *sim[] = {"simulate", "--csv", csv, NULL};
    if (expect_error(plot, NULL, 1, "fig.png: the file is read-only") ||
        expect_error(sim, NULL, 1, "run.csv: the file is read-only"))
        return 1;
    ENSURE(same_content(fig, OLD_TEXT) && same_content(csv, OLD_TEXT));
    ENSURE(entries(dir, NULL, 0) == 2);
    return 0;
}

/* Films and figures past their budget are refused before the work, naming
 * the flag that raises it. */
static int test_budgets(void)
{
    char dir[512], film[600], fig[600];
    ENSURE(dir_with_two(dir, "budget", film, "long.gif", fig, "fine.png") == 0);
    /* 60 s at 30 fps x 8: 14,400 frames (asked for: the film would stop a
     * second after the hoop's last landing). */
    const char *animate[] = {"animate", HOOP, "--t-max", "60", "--output", film, NULL};
    if (expect_error(animate, NULL, 2, "over the budget of 5000; raise it with --max-frames")) return 1;
    const char *plot[] = {"plot", "--what", "path", "--sample-dt", "1e-5", "--output", fig, NULL};
    if (expect_error(plot, NULL, 2, "over the budget of 100000; raise it with --max-samples")) return 1;
    ENSURE(entries(dir, NULL, 0) == 0);
    return 0;
}

/* The stuck sampler: 200 MB of identical rows before; now about
 * 700 rows, times strictly increasing. */
static int test_stuck_sampler(void)
{
    char dir[512], csv[600];
    ENSURE(new_dir(dir, sizeof dir, "sampler") == 0);
    snprintf(csv, sizeof csv, "%s/s.csv", dir);
    const char *args[] = {"simulate", "--incline", "0", "--radius", "0.14m", "--part", "disc:mass=0.124kg",
                          "--part", "point:mass=0.051kg,offset=0.118m", "--mu", "0.8", "--restitution", "0",
                          "--theta0", "-1.41578797rad", "--omega0", "21", "--t-max", "0.7", "--csv", csv,
                          "--sample-dt", "0.001", NULL};
    cli_result r = cli_run(args);
    const int status = r.status;
    cli_result_free(&r);
    ENSURE(status == 0);
    FILE *f = fopen(csv, "r");
    ENSURE(f);
    char line[1024];
    int rows = 0, increasing = 1;
    double last = -1.0;
    ENSURE(fgets(line, sizeof line, f) != NULL); /* header */
    while (fgets(line, sizeof line, f)) {
        const double t = strtod(line, NULL);
        if (!(t > last)) increasing = 0;
        last = t;
        ++rows;
    }
    fclose(f);
    ENSURE_MSG(rows > 650 && rows < 800, "%d rows", rows);
    ENSURE_MSG(increasing, "sample times do not strictly increase");
    return 0;
}

/* ---- memory ---- */

/* A run of LONG_RUN_EVENTS events streams: its resident memory stays far
 * below what holding them took (674 MB for 300,000 events with the whole
 * event list and JSON tree in memory). The run must really make that many
 * events: it ends at the event limit, and the document holds them all. */
static int test_long_run_memory(void)
{
#ifdef JC_SANITIZED
    /* The sanitizers' shadow memory and quarantine are no measure of ours. */
    const int events = 3000;
#else
    const int events = LONG_RUN_EVENTS;
#endif
    char events_arg[32], json[600];
    snprintf(events_arg, sizeof events_arg, "%d", events);
    snprintf(json, sizeof json, "%s/long.json", base);
    const char *args[] = {"simulate", LONG_RUN, "--max-events", events_arg, "--json", NULL};
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, json, out_tmp, err_tmp);
    ENSURE(pid > 0);
    int ws = 0;
    struct rusage ru;
    ENSURE(wait4(pid, &ws, 0, &ru) == pid);
    unlink(out_tmp);
    unlink(err_tmp);
    ENSURE(WIFEXITED(ws) && WEXITSTATUS(ws) == 0);
    /* Count the events in the document: one "kind" member each after "events". */
    FILE *f = fopen(json, "r");
    ENSURE(f != NULL);
    long kinds = 0;
    int limit_reached = 0, in_events = 0;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strstr(line, "\"events\":")) in_events = 1; /* the setup's parts have kinds too */
        if (in_events && strstr(line, "\"kind\":")) kinds++;
        if (strstr(line, "\"termination\":") && strstr(line, "\"event_limit\"")) limit_reached = 1;
    }
    fclose(f);
    unlink(json);
    const long max_rss_kb = ru.ru_maxrss;
    printf("  simulate --max-events %d --json: %ld events, max RSS %ld kB\n", events, kinds, max_rss_kb);
    ENSURE_MSG(kinds == events && limit_reached, "%ld events in the document, want %d ending at event_limit", kinds,
               events);
#ifndef JC_SANITIZED
    ENSURE_MSG(max_rss_kb < 32 * 1024, "max RSS %ld kB, over 32 MB", max_rss_kb);
#endif
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    /* Some tests run the tool from another working directory. */
    static char tool[4096];
    if (!realpath(argv[1], tool)) return 2;
    cli_run_tool = tool;
    /* Under a wrapper (valgrind) only the quick checks: the others time children. */
    const int wrapped = argc > 2;
    snprintf(base, sizeof base, "/tmp/jc_safe_output_XXXXXX");
    if (!mkdtemp(base)) return 2;
    snprintf(marker, sizeof marker, "%s/marker", base);
    setenv("JC_MARKER", marker, 1);
    RUN_TEST(test_injection_names);
    RUN_TEST(test_injection_kept_script);
    RUN_TEST(test_dev_full);
    RUN_TEST(test_fifo_config);
    RUN_TEST(test_repeated_options);
    RUN_TEST(test_csv_to_stdout);
    RUN_TEST(test_read_only_target);
    RUN_TEST(test_budgets);
    RUN_TEST(test_stuck_sampler);
    if (!wrapped) {
        RUN_TEST(test_ffmpeg_names);
        RUN_TEST(test_disk_full);
        RUN_TEST(test_file_size_limit);
        RUN_TEST(test_signals_while_gnuplot_runs);
        RUN_TEST(test_signals_while_ffmpeg_runs);
        RUN_TEST(test_signals_while_ffmpeg_runs_full_size);
        RUN_TEST(test_signal_while_simulating);
        RUN_TEST(test_second_signal);
        RUN_TEST(test_long_run_memory);
    }
    if (jc_test_failed_count == 0) {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", base);
    } else {
        fprintf(stderr, "files kept in %s\n", base);
    }
    TEST_MAIN_END();
}
