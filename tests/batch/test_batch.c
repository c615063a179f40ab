/* Batch jobs (sweep, mc) end to end, the tool run as a process:
 * - a sweep's rows are the runs `simulate` makes, value by value;
 * - the file is the same bytes for 1, 2 and 4 threads and for shards put
 *   back together with cat;
 * - a sweep stopped by SIGTERM keeps its finished rows and --resume ends in
 *   the same bytes; a half-written last row is cut, another job's file refused;
 * - Monte Carlo with no spread is the deterministic run; with a small normal
 *   spread of theta0 its mean and standard deviation converge to the
 *   linearised propagation (slope by central differences of two runs);
 * - past --exact-limit the percentiles are estimated (near the exact ones
 *   of the rows kept, said in the output), mean and regions as the exact
 *   job's, and --summarize of many rows stays in bounded memory;
 * - bad --vary, --sigma, --range, --shard, --threads, --samples: exit 2,
 *   one line, no file. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* wait4 */
#include "../cli_run.h"
#include "../test.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>

static char dir[64];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

/* The number of a JSON object's member, NaN when it is absent. */
static double num(const cJSON *o, const char *name)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, name);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* A field of a CSV line by 0-based index, as a number (NaN if empty). */
static double csv_num(const char *line, int index)
{
    const char *p = line;
    for (int i = 0; i < index && p; ++i) {
        p = strchr(p, ',');
        if (p) ++p;
    }
    if (!p || *p == ',' || *p == '\n' || *p == '\0') return NAN;
    return strtod(p, NULL);
}

static void csv_text(const char *line, int index, char *out, size_t len)
{
    const char *p = line;
    for (int i = 0; i < index && p; ++i) {
        p = strchr(p, ',');
        if (p) ++p;
    }
    const size_t n = p ? strcspn(p, ",\n") : 0;
    snprintf(out, len, "%.*s", (int)n, p ? p : "");
}

/* The k-th line (0-based) of text, NULL if there is none. */
static const char *line_at(const char *text, int k)
{
    for (int i = 0; i < k && text; ++i) {
        text = strchr(text, '\n');
        if (text) ++text;
    }
    return text && *text ? text : NULL;
}

/* Rows of a sweep over the incline against `simulate --json` at each value. */
static int test_sweep_rows_are_simulate_runs(void)
{
    const char *incl[] = {"12", "30", "45", "60"};
    const char *args[] = {"sweep", "--vary", "incline=12,30,45,60", "--mu", "0.4", "--output", "-", NULL};
    cli_result r = cli_run(args);
    ENSURE_MSG(r.status == 0, "sweep exit %d: %s", r.status, r.err);
    ENSURE_MSG(strncmp(r.out, "case,incline_deg,first_event,first_slip_theta_rad,first_slip_x_m,first_slip_t_s,"
                              "first_liftoff_theta_rad,first_liftoff_x_m,first_liftoff_t_s,liftoffs,bounces,"
                              "largest_hop_m,termination,end_x_m,end_t_s,energy_balance_error_J\n",
                       strlen("case,incline_deg,")) == 0,
               "header: %.200s", r.out);
    for (int k = 0; k < 4; ++k) {
        const char *row = line_at(r.out, k + 1);
        ENSURE_MSG(row != NULL, "row %d missing", k);
        const char *sargs[] = {"simulate", "--incline", incl[k], "--mu", "0.4", "--json", NULL};
        cli_result s = cli_run(sargs);
        ENSURE(s.status == 0);
        cJSON *doc = cJSON_Parse(s.out);
        ENSURE(doc != NULL);
        const cJSON *sum = cJSON_GetObjectItemCaseSensitive(doc, "summary");
        const cJSON *events = cJSON_GetObjectItemCaseSensitive(doc, "events");
        const cJSON *e0 = cJSON_GetArrayItem(events, 0);
        char term[32], first[32];
        csv_text(row, 12, term, sizeof term);
        csv_text(row, 2, first, sizeof first);
        const cJSON *jt = cJSON_GetObjectItemCaseSensitive(doc, "termination");
        const cJSON *jk = cJSON_GetObjectItemCaseSensitive(e0, "kind");
        /* %.12g in the row: 1e-11 relative */
        const double tol = 2e-11;
        ENSURE_MSG(csv_num(row, 0) == k && csv_num(row, 1) == atof(incl[k]), "row %d: %s", k, row);
        ENSURE_MSG(cJSON_IsString(jt) && strcmp(term, jt->valuestring) == 0, "termination %s", term);
        ENSURE_MSG(cJSON_IsString(jk) && strcmp(first, jk->valuestring) == 0, "first event %s", first);
        if (strcmp(first, "slip") == 0) {
            ENSURE_REL(csv_num(row, 3), num(e0, "theta"), tol);
            ENSURE_REL(csv_num(row, 4), num(e0, "x"), tol);
            ENSURE_REL(csv_num(row, 5), num(e0, "t"), tol);
        }
        const double lx = num(sum, "first_liftoff_x");
        if (isnan(lx)) ENSURE(isnan(csv_num(row, 7)));
        else {
            ENSURE_REL(csv_num(row, 7), lx, tol);
            ENSURE_REL(csv_num(row, 6), num(sum, "first_liftoff_theta"), tol);
        }
        ENSURE(csv_num(row, 9) == num(sum, "liftoffs") && csv_num(row, 10) == num(sum, "bounces"));
        if (num(sum, "liftoffs") > 0) ENSURE_REL(csv_num(row, 11), num(sum, "largest_hop"), tol);
        ENSURE_REL(csv_num(row, 14), num(doc, "t_end"), tol);
        cJSON_Delete(doc);
        cli_result_free(&s);
    }
    ENSURE(line_at(r.out, 5) == NULL);
    cli_result_free(&r);
    return 0;
}

/* A grid sweep to a file with the given extra options; its bytes (caller frees). */
static char *grid_sweep(const char *name, const char *opt1, const char *opt2)
{
    char out[128], part[160];
    path_in(out, sizeof out, name);
    snprintf(part, sizeof part, "%s.part", out);
    remove(out);
    remove(part);
    const char *args[] = {"sweep", "--vary", "incline=10:50:8", "--vary", "rod-offset=2cm:8cm:1.5cm", "--vary",
                          "impact-law=stronge,newton", "--output", out, opt1, opt2, NULL};
    cli_result r = cli_run(args);
    char *text = r.status == 0 && !cli_file_exists(part) ? cli_run_slurp(out) : NULL;
    if (!text) fprintf(stderr, "sweep %s %s: exit %d: %s\n", opt1 ? opt1 : "", opt2 ? opt2 : "", r.status, r.err);
    cli_result_free(&r);
    return text;
}

static int test_same_bytes_for_threads_and_shards(void)
{
    char *one = grid_sweep("t1.csv", "--threads", "1");
    char *two = grid_sweep("t2.csv", "--threads", "2");
    char *four = grid_sweep("t4.csv", "--threads", "4");
    ENSURE(one && two && four);
    ENSURE_MSG(strcmp(one, two) == 0 && strcmp(one, four) == 0, "thread counts differ");
    /* 6 x 5 x 2 = 60 cases and a header */
    ENSURE(line_at(one, 60) != NULL && line_at(one, 61) == NULL);
    size_t len = 0;
    char joined[65536] = "";
    for (int k = 1; k <= 7; ++k) {
        char shard[16], name[32];
        snprintf(shard, sizeof shard, "%d/7", k);
        snprintf(name, sizeof name, "s%d.csv", k);
        char *part = grid_sweep(name, "--shard", shard);
        ENSURE(part != NULL);
        ENSURE(len + strlen(part) < sizeof joined);
        memcpy(joined + len, part, strlen(part) + 1);
        len += strlen(part);
        free(part);
    }
    ENSURE_MSG(strcmp(joined, one) == 0, "the 7 shards put together are not the single file");
    free(one);
    free(two);
    free(four);
    return 0;
}

static void sleep_s(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* The rows FILE.part holds as the final file will hold them: its first
 * line (the job's) dropped, and each row's checksum (a tab and 16 hex
 * digits) cut. Frees text; NULL for NULL. */
static char *part_rows(char *text)
{
    if (!text) return NULL;
    const char *p = strchr(text, '\n');
    char *out = malloc(strlen(text) + 1), *o = out;
    for (p = p ? p + 1 : text + strlen(text); out && *p;) {
        const char *nl = strchr(p, '\n');
        const size_t n = nl ? (size_t)(nl - p) : strlen(p);
        const size_t keep = n >= 17 && p[n - 17] == '\t' ? n - 17 : n;
        memcpy(o, p, keep);
        o += keep;
        if (nl) *o++ = '\n';
        p += n + (nl != NULL);
    }
    if (out) *o = '\0';
    free(text);
    return out;
}

static int test_stopped_sweep_resumes_to_the_same_bytes(void)
{
    char out[128], part[160], ref[128];
    path_in(out, sizeof out, "stop.csv");
    path_in(ref, sizeof ref, "ref.csv");
    snprintf(part, sizeof part, "%s.part", out);
    remove(out);
    remove(part);
    const char *job[] = {"sweep", "--vary", "incline=20:40:0.01", "--vary", "mu=0.3,0.6,0.9", "--output", NULL,
                         "--quiet", NULL, NULL};
    job[6] = ref;
    cli_result whole = cli_run(job);
    ENSURE_MSG(whole.status == 0, "%s", whole.err);
    cli_result_free(&whole);
    char *expected = cli_run_slurp(ref);
    ENSURE(expected != NULL);

    job[6] = out;
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(job, NULL, out_tmp, err_tmp);
    ENSURE(pid > 0);
    /* Stop it once it has written some rows, well before its end. */
    for (int i = 0; i < 2000 && file_size(part) < 4000; ++i) sleep_s(0.005);
    kill(pid, SIGTERM);
    cli_result r = cli_run_wait(pid, out_tmp, err_tmp, 1);
    ENSURE_MSG(r.status == 143 || r.status == 0, "exit %d after SIGTERM: %s", r.status, r.err);
    if (r.status == 143) {
        ENSURE_MSG(!cli_file_exists(out) && cli_file_exists(part), "a stopped job keeps FILE.part and makes no FILE");
        ENSURE_MSG(strstr(r.err, "--resume") != NULL, "the message names --resume: %s", r.err);
        char *kept = part_rows(cli_run_slurp(part));
        ENSURE(kept && strlen(kept) < strlen(expected) && strncmp(kept, expected, strlen(kept)) == 0);
        printf("  stopped after %ld bytes of %zu; the kept rows are the first rows of the whole job\n",
               (long)strlen(kept), strlen(expected));
        free(kept);
        /* A half-written row at the end, as a kill during a write leaves it. */
        FILE *f = fopen(part, "a");
        ENSURE(f != NULL);
        fputs("999999,25.5,0.3,sl", f);
        fclose(f);
        /* without --resume: refused, nothing touched */
        job[8] = NULL;
        cli_result again = cli_run(job);
        ENSURE_MSG(again.status == 2 && cli_one_line(again.err) && strstr(again.err, "--resume"), "%s", again.err);
        cli_result_free(&again);
        job[8] = "--resume";
        cli_result res = cli_run(job);
        ENSURE_MSG(res.status == 0, "resume exit %d: %s", res.status, res.err);
        cli_result_free(&res);
        job[8] = NULL;
    } else {
        printf("  (the job ended before the stop; nothing to resume)\n");
    }
    cli_result_free(&r);
    char *got = cli_run_slurp(out);
    ENSURE_MSG(got && strcmp(got, expected) == 0, "the resumed file differs from the uninterrupted one");
    ENSURE(!cli_file_exists(part));
    free(got);

    /* Another job's rows are refused. */
    FILE *f = fopen(part, "w");
    ENSURE(f != NULL);
    fputs(expected, f); /* header of a 2-parameter job, resumed as a 1-parameter one */
    fclose(f);
    const char *other[] = {"sweep", "--vary", "incline=20:40:1", "--output", out, "--resume", NULL};
    cli_result o = cli_run(other);
    ENSURE_MSG(o.status == 2 && cli_one_line(o.err) && strstr(o.err, "not a .part file"), "exit %d: %s", o.status,
               o.err);
    char *after = cli_run_slurp(part);
    ENSURE_MSG(after && strcmp(after, expected) == 0, "a file not the tool's was changed");
    free(after);
    cli_result_free(&o);
    remove(part);
    free(expected);
    return 0;
}

static cJSON *mc_json(const char *const *extra, cli_result *keep)
{
    const char *args[24] = {"mc", "--json", "--quiet"};
    int n = 3;
    for (int i = 0; extra[i] && n < 23; ++i) args[n++] = extra[i];
    args[n] = NULL;
    *keep = cli_run(args);
    if (keep->status != 0) fprintf(stderr, "mc: exit %d: %s\n", keep->status, keep->err);
    return keep->status == 0 ? cJSON_Parse(keep->out) : NULL;
}

static double first_liftoff_x(const char *theta0)
{
    const char *args[] = {"simulate", "--json", "--theta0", theta0, NULL};
    cli_result r = cli_run(args);
    cJSON *doc = r.status == 0 ? cJSON_Parse(r.out) : NULL;
    const double x = doc ? num(cJSON_GetObjectItemCaseSensitive(doc, "summary"), "first_liftoff_x") : NAN;
    cJSON_Delete(doc);
    cli_result_free(&r);
    return x;
}

static int test_mc_without_spread_is_the_run(void)
{
    const char *extra[] = {"--no-defaults", "--samples", "40", NULL};
    cli_result r;
    cJSON *doc = mc_json(extra, &r);
    ENSURE(doc != NULL);
    const cJSON *l = cJSON_GetObjectItemCaseSensitive(doc, "first_liftoff_x_m");
    const double x0 = first_liftoff_x("0");
    ENSURE(num(l, "count") == 40 && num(l, "sd") == 0.0);
    ENSURE_REL(num(l, "mean"), x0, 1e-14);
    ENSURE_REL(num(l, "p2_5"), x0, 1e-14);
    cJSON_Delete(doc);
    cli_result_free(&r);
    return 0;
}

/* theta0 ~ N(0, (0.5 deg)^2) at 30 degrees: the first lift-off is nearly
 * linear in theta0 over +-2 deg, so x ~ N(x0, (|dx/dtheta0| 0.5 deg)^2). */
static int test_mc_converges_to_the_linearised_spread(void)
{
    const double h_deg = 1.0, sigma_deg = 0.5;
    const double slope = (first_liftoff_x("1") - first_liftoff_x("-1")) / (2 * h_deg); /* m per degree */
    const double x0 = first_liftoff_x("0"), sd_lin = fabs(slope) * sigma_deg;
    ENSURE(isfinite(slope) && sd_lin > 1e-4);
    const char *sizes[] = {"250", "1000", "8000"};
    double prev_err = INFINITY;
    for (int k = 0; k < 3; ++k) {
        const char *extra[] = {"--no-defaults", "--sigma", "theta0=0.5", "--samples", sizes[k], "--seed", "7", NULL};
        cli_result r;
        cJSON *doc = mc_json(extra, &r);
        ENSURE(doc != NULL);
        const cJSON *l = cJSON_GetObjectItemCaseSensitive(doc, "first_liftoff_x_m");
        const double n = atof(sizes[k]), mean = num(l, "mean"), sd = num(l, "sd");
        /* 4 standard errors: of a mean sd/sqrt(n), of a normal's sd sd/sqrt(2n) */
        ENSURE_MSG(fabs(mean - x0) <= 4 * sd_lin / sqrt(n) + 1e-6, "n %.0f: mean %.9g vs %.9g", n, mean, x0);
        const double err = fabs(sd / sd_lin - 1);
        ENSURE_MSG(err <= 4 / sqrt(2 * n) + 0.01, "n %.0f: sd %.6g vs linearised %.6g", n, sd, sd_lin);
        ENSURE_MSG(fabs(num(l, "p97_5") - num(l, "p2_5") - 2 * 1.959964 * sd_lin) <= 8 * sd_lin / sqrt(n) + 2e-5,
                   "n %.0f: the 95 %% interval %.6g wide", n, num(l, "p97_5") - num(l, "p2_5"));
        printf("  n %5.0f: mean %.6f m (run %.6f), sd %.4g mm (linearised %.4g mm)\n", n, mean, x0, sd * 1e3,
               sd_lin * 1e3);
        if (k == 2) ENSURE_MSG(err < 0.05 && err <= prev_err + 0.03, "sd error %.3g after %.3g", err, prev_err);
        prev_err = err;
        cJSON_Delete(doc);
        cli_result_free(&r);
    }
    return 0;
}

/* The sampled values are those of the seed and the sample index alone:
 * shards of a Monte Carlo job put together are the whole job. */
static int test_mc_shards_are_the_whole_job(void)
{
    char whole[128], a[128], b[128];
    path_in(whole, sizeof whole, "mc.csv");
    path_in(a, sizeof a, "mc1.csv");
    path_in(b, sizeof b, "mc2.csv");
    const char *j0[] = {"mc", "--samples", "300", "--seed", "99", "--output", whole, "--threads", "2", NULL};
    const char *j1[] = {"mc", "--samples", "300", "--seed", "99", "--output", a, "--shard", "1/2", "--threads", "1", NULL};
    const char *j2[] = {"mc", "--samples", "300", "--seed", "99", "--output", b, "--shard", "2/2", NULL};
    cli_result r0 = cli_run(j0), r1 = cli_run(j1), r2 = cli_run(j2);
    ENSURE(r0.status == 0 && r1.status == 0 && r2.status == 0);
    char *w = cli_run_slurp(whole), *p1 = cli_run_slurp(a), *p2 = cli_run_slurp(b);
    ENSURE(w && p1 && p2 && strlen(p1) + strlen(p2) == strlen(w));
    ENSURE(strncmp(w, p1, strlen(p1)) == 0 && strcmp(w + strlen(p1), p2) == 0);
    ENSURE(strstr(r0.out, "radius") && strstr(r0.out, "uniform"));
    /* The summary of the whole job, read back from its rows, is the job's own
     * to the rows' 12 significant digits. */
    const char *sum[] = {"mc", "--summarize", whole, "--json", NULL};
    const char *job[] = {"mc", "--samples", "300", "--seed", "99", "--json", NULL};
    cli_result rs = cli_run(sum), rj = cli_run(job);
    ENSURE_MSG(rs.status == 0 && rj.status == 0, "%s %s", rs.err, rj.err);
    cJSON *ds = cJSON_Parse(rs.out), *dj = cJSON_Parse(rj.out);
    ENSURE(ds && dj);
    const char *keys[] = {"mean", "sd", "p2_5", "p50", "p97_5"};
    for (int k = 0; k < 5; ++k) {
        const double from_rows = num(cJSON_GetObjectItemCaseSensitive(ds, "first_liftoff_x_m"), keys[k]);
        const double from_job = num(cJSON_GetObjectItemCaseSensitive(dj, "first_liftoff_x_m"), keys[k]);
        ENSURE_REL(from_rows, from_job, k == 1 ? 1e-9 : 1e-11);
    }
    ENSURE(num(ds, "samples") == 300 && num(ds, "valid") == num(dj, "valid"));
    cJSON_Delete(ds);
    cJSON_Delete(dj);
    cli_result_free(&rs);
    cli_result_free(&rj);
    free(w);
    free(p1);
    free(p2);
    cli_result_free(&r0);
    cli_result_free(&r1);
    cli_result_free(&r2);
    return 0;
}

/* ---- past --exact-limit: the summary in bounded memory ---- */

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The quantile of sorted values, linear between order statistics. */
static double quantile_of(const double *sorted, long n, double p)
{
    const double h = p * (double)(n - 1);
    const long i = (long)h;
    return i + 1 < n ? sorted[i] + (h - (double)i) * (sorted[i + 1] - sorted[i]) : sorted[n - 1];
}

/* The JSON summary's percentiles against those of the values (sorted
 * here), within tol of their 2.5 .. 97.5 % range. */
static int percentiles_near(const cJSON *stats, double *v, long n, double tol)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    const double range = quantile_of(v, n, 0.975) - quantile_of(v, n, 0.025);
    const char *keys[] = {"p2_5", "p50", "p97_5"};
    const double p[] = {0.025, 0.5, 0.975};
    for (int k = 0; k < 3; ++k) {
        const double want = quantile_of(v, n, p[k]), got = num(stats, keys[k]);
        printf("  %s: exact %.6f, estimated %.6f: %.2g of the 95 %% range\n", keys[k], want, got,
               fabs(got - want) / range);
        ENSURE_MSG(fabs(got - want) <= tol * range, "%s %.9g, exact %.9g", keys[k], got, want);
    }
    return 0;
}

static int write_rows(const char *path, long n, double *x);

/* 3000 samples past --exact-limit 1000: the percentiles estimated within
 * 5 % of the 95 % range of the exact ones of the rows kept (P² with few
 * samples is coarse: about 2 % here), said in the text and the JSON; the
 * mean to rounding, the regions the same as the exact job's; --summarize
 * with the limit estimates too, and says when the regions are not known. */
static int test_mc_estimated_past_the_limit(void)
{
    char rows[128];
    path_in(rows, sizeof rows, "est.csv");
    const char *est[] = {"--samples", "3000", "--seed", "5", "--exact-limit", "1000", "--output", rows, NULL};
    const char *exact[] = {"--samples", "3000", "--seed", "5", NULL};
    cli_result re, rx;
    cJSON *de = mc_json(est, &re), *dx = mc_json(exact, &rx);
    ENSURE(de && dx);
    const cJSON *pe = cJSON_GetObjectItemCaseSensitive(de, "percentiles");
    ENSURE(cJSON_IsString(pe) && strcmp(pe->valuestring, "estimated") == 0 && num(de, "exact_limit") == 1000);
    ENSURE(cJSON_GetObjectItemCaseSensitive(dx, "percentiles") == NULL && isnan(num(dx, "exact_limit")));
    char *text = cli_run_slurp(rows);
    ENSURE(text != NULL);
    const char *header = text;
    int column = 0;
    for (const char *c = header; c < strstr(header, "first_liftoff_x_m"); ++c) column += *c == ',';
    double *x = malloc(3000 * sizeof *x);
    long n = 0;
    for (const char *line = line_at(text, 1); line && n < 3000; line = line_at(line, 1)) {
        const double v = csv_num(line, column);
        if (!isnan(v)) x[n++] = v;
    }
    const cJSON *le = cJSON_GetObjectItemCaseSensitive(de, "first_liftoff_x_m");
    const cJSON *lx = cJSON_GetObjectItemCaseSensitive(dx, "first_liftoff_x_m");
    ENSURE(n > 2000 && num(le, "count") == (double)n);
    ENSURE(percentiles_near(le, x, n, 0.05) == 0);
    ENSURE_REL(num(le, "mean"), num(lx, "mean"), 1e-12);
    ENSURE_REL(num(le, "sd"), num(lx, "sd"), 1e-9);
    const cJSON *ge = cJSON_GetObjectItemCaseSensitive(le, "regions"), *gx = cJSON_GetObjectItemCaseSensitive(lx, "regions");
    ENSURE(cJSON_GetArraySize(ge) == cJSON_GetArraySize(gx) && cJSON_GetArraySize(gx) >= 1);
    for (int k = 0; k < cJSON_GetArraySize(gx); ++k) {
        const cJSON *a = cJSON_GetArrayItem(ge, k), *b = cJSON_GetArrayItem(gx, k);
        ENSURE(num(a, "lo") == num(b, "lo") && num(a, "hi") == num(b, "hi"));
        ENSURE(num(a, "fraction") == num(b, "fraction"));
        ENSURE_REL(num(a, "mean"), num(b, "mean"), 1e-12);
    }
    /* The text says which. */
    const char *t_est[] = {"mc", "--samples", "1200", "--exact-limit", "1000", "--quiet", NULL};
    const char *t_exact[] = {"mc", "--samples", "1000", "--exact-limit", "1000", "--quiet", NULL};
    cli_result a = cli_run(t_est), b = cli_run(t_exact);
    ENSURE(a.status == 0 && strstr(a.out, "Percentiles estimated in one pass: more than 1000 samples"));
    ENSURE(b.status == 0 && !strstr(b.out, "estimated"));
    /* The rows read back past the limit: estimated too, near the job's. */
    const char *sum[] = {"--summarize", rows, "--exact-limit", "1000", NULL};
    cli_result rs;
    cJSON *ds = mc_json(sum, &rs);
    ENSURE(ds && cJSON_GetObjectItemCaseSensitive(ds, "percentiles") != NULL);
    ENSURE(percentiles_near(cJSON_GetObjectItemCaseSensitive(ds, "first_liftoff_x_m"), x, n, 0.05) == 0);
    /* 70,000 distinct lift-offs, a gap of 1 nm: more cells than the
     * summary holds (65,536), so no regions, said so. */
    char many[128];
    path_in(many, sizeof many, "many.csv");
    ENSURE(write_rows(many, 70000, NULL) == 0);
    const char *tiny[] = {"mc", "--summarize", many, "--exact-limit", "1000", "--region-gap", "0.000001mm", NULL};
    const char *tiny_json[] = {"--summarize", many, "--exact-limit", "1000", "--region-gap", "0.000001mm", NULL};
    cli_result rt = cli_run(tiny), rtj;
    cJSON *dt = mc_json(tiny_json, &rtj);
    ENSURE_MSG(rt.status == 0 && strstr(rt.out, "separate regions: not known"), "%s", rt.out);
    ENSURE(dt && cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(dt, "first_liftoff_x_m"),
                                                                "regions")));
    cJSON_Delete(dt);
    cli_result_free(&rt);
    cli_result_free(&rtj);
    remove(many);
    const char *bad[] = {"mc", "--exact-limit", "0", NULL};
    cli_result rb = cli_run(bad);
    ENSURE(rb.status == 2 && cli_one_line(rb.err) && strstr(rb.err, "--exact-limit '0'"));
    free(x);
    free(text);
    cJSON_Delete(de);
    cJSON_Delete(dx);
    cJSON_Delete(ds);
    cli_result_free(&re);
    cli_result_free(&rx);
    cli_result_free(&rs);
    cli_result_free(&rb);
    cli_result_free(&a);
    cli_result_free(&b);
    return 0;
}

/* Rows of a job with no spread inputs (the columns mc writes with
 * --no-defaults): first lift-offs normal about 1.18 m, sd 1.5 cm, the
 * largest hops uniform to 0.1 m; their lift-offs as printed, in x. */
static int write_rows(const char *path, long n, double *x)
{
    FILE *f = fopen(path, "w");
    ENSURE(f != NULL);
    fputs("case,first_event,first_slip_theta_rad,first_slip_x_m,first_slip_t_s,first_liftoff_theta_rad,"
          "first_liftoff_x_m,first_liftoff_t_s,liftoffs,bounces,largest_hop_m,termination,end_x_m,end_t_s,"
          "energy_balance_error_J\n",
          f);
    uint64_t state = 11;
    for (long i = 0; i < n; ++i) {
        const double u = test_uniform(&state, 1e-300, 1), w = test_uniform(&state, 0, 2 * 3.14159265358979323846);
        char v[32];
        snprintf(v, sizeof v, "%.12g", 1.18 + 0.015 * sqrt(-2 * log(u)) * cos(w));
        if (x) x[i] = strtod(v, NULL);
        fprintf(f, "%ld,slip,,,,,%s,,1,,%.12g,ramp_end,,,\n", i, v, test_uniform(&state, 0, 0.1));
    }
    ENSURE(fclose(f) == 0);
    return 0;
}

/* mc --summarize FILE's peak resident memory (wait4's ru_maxrss, kB) and
 * its JSON. */
static long summarize_rss_kb(const char *path, const char *limit, cJSON **doc)
{
    const char *args[] = {"mc", "--summarize", path, "--json", "--exact-limit", limit, NULL};
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
    int ws = 0;
    struct rusage ru;
    if (pid <= 0 || wait4(pid, &ws, 0, &ru) != pid || !WIFEXITED(ws) || WEXITSTATUS(ws) != 0) return -1;
    char *out = cli_run_slurp(out_tmp);
    unlink(out_tmp);
    unlink(err_tmp);
    if (doc) *doc = out ? cJSON_Parse(out) : NULL;
    free(out);
    return ru.ru_maxrss;
}

/* The summary of 500,000 rows past --exact-limit 1000 takes no more
 * memory than that of 10,000 (within 3 MB), where keeping them would take
 * 12 MB more (and does: the exact summary of the same rows, at least 8 MB
 * more); its median within 0.2 % of the 95 % range of the exact one. */
static int test_mc_summarize_memory_is_bounded(void)
{
    const long n = 500000;
    char big[128], small[128];
    path_in(big, sizeof big, "big.csv");
    path_in(small, sizeof small, "small.csv");
    double *x = malloc((size_t)n * sizeof *x);
    ENSURE(x && write_rows(big, n, x) == 0 && write_rows(small, 10000, NULL) == 0);
    cJSON *doc = NULL;
    const long rss_small = summarize_rss_kb(small, "1000", NULL), rss_big = summarize_rss_kb(big, "1000", &doc);
    const long rss_exact = summarize_rss_kb(big, "100000000", NULL);
    printf("  peak RSS: %ld kB for 10^4 rows, %ld kB for %ld rows past the limit, %ld kB kept exact\n", rss_small,
           rss_big, n, rss_exact);
    ENSURE(rss_small > 0 && rss_big > 0 && rss_exact > 0 && doc);
#ifndef JC_SANITIZED
    ENSURE_MSG(rss_big <= rss_small + 3 * 1024, "%ld kB against %ld kB", rss_big, rss_small);
    ENSURE_MSG(rss_exact >= rss_big + 8 * 1024, "kept exact %ld kB, bounded %ld kB", rss_exact, rss_big);
#endif
    ENSURE(num(doc, "valid") == (double)n);
    ENSURE(percentiles_near(cJSON_GetObjectItemCaseSensitive(doc, "first_liftoff_x_m"), x, n, 2e-3) == 0);
    cJSON_Delete(doc);
    free(x);
    remove(big);
    remove(small);
    return 0;
}

/* A case's words (the test's own, one space apart) as arguments, in place;
 * returns how many. */
static int split_words(char *words, const char **args, int max)
{
    int n = 0;
    char *save = NULL;
    for (char *w = strtok_r(words, " ", &save); w && n < max; w = strtok_r(NULL, " ", &save)) args[n++] = w;
    return n;
}

static int test_bad_values(void)
{
    char out[128];
    path_in(out, sizeof out, "bad.csv");
    /* Each is refused with --output FILE added, and FILE is not written. */
    static const char *const cases[] = {
        "sweep --vary incline=95",
        "sweep --vary incline=30:10:5",
        "sweep --vary incline=10:30:0",
        "sweep --vary incline=",
        "sweep --vary incline=10,,20",
        "sweep --vary wheels=3",
        "sweep --vary preset=paper",
        "sweep --vary mu=-0.5",
        "sweep --vary impact-law=elastic",
        "sweep --vary incline=0:80:1e-9",
        "sweep --vary incline=10 --incline 20",
        "sweep --vary incline=10 --shard 0/3",
        "sweep --vary incline=10 --shard 4/3",
        "sweep --vary incline=10 --shard 1/x",
        "sweep --vary incline=10 --threads 0",
        "mc --sigma mu=-1",
        "mc --sigma impact-law=1",
        "mc --range mu=1:0.5",
        "mc --range mu=0.5",
        "mc --samples 0",
        "mc --samples 10 --seed -4",
        "mc --samples 10 --seed +4",
        "mc --samples 10 --seed 18446744073709551616", /* 2^64 */
        "mc --samples 10 --seed 4.0",
        "mc --sigma rod-offset=1mm --sigma rod-offset=2mm",
        "sweep --vary incline=10 --sample-dt 0.01",
        "mc --samples 10 --sample-dt 0.01",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char words[256];
        snprintf(words, sizeof words, "%s", cases[i]);
        const char *args[16];
        int n = split_words(words, args, 13);
        args[n++] = "--output";
        args[n++] = out;
        args[n] = NULL;
        remove(out);
        cli_result r = cli_run(args);
        ENSURE_MSG(r.status == 2 && cli_one_line(r.err), "case %zu (%s): exit %d, stderr: %s", i, cases[i], r.status,
                   r.err);
        ENSURE_MSG(!cli_file_exists(out), "case %zu left a file", i);
        cli_result_free(&r);
    }
    printf("  %zu bad values refused with one line each\n", sizeof cases / sizeof cases[0]);
    return 0;
}

/* paper's uncertainty: for each incline the 95 % interval of the first
 * lift-off is ordered, holds the nominal run, says rightly whether the
 * measurement is inside, and is the interval `mc` gives for that incline. */
static int test_paper_uncertainty(void)
{
    const char *args[] = {"paper", "--json", NULL};
    cli_result r = cli_run(args);
    ENSURE_MSG(r.status == 0, "%s", r.err);
    cJSON *doc = cJSON_Parse(r.out);
    ENSURE(doc != NULL);
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(doc, "rows");
    ENSURE(cJSON_GetArraySize(rows) == 3);
    for (int i = 0; i < 3; ++i) {
        const cJSON *row = cJSON_GetArrayItem(rows, i);
        const cJSON *u = cJSON_GetObjectItemCaseSensitive(row, "full_uncertainty");
        const double lo = num(u, "p2_5"), mid = num(u, "p50"), hi = num(u, "p97_5");
        const double x = num(cJSON_GetObjectItemCaseSensitive(row, "full"), "x");
        const double meas = num(cJSON_GetObjectItemCaseSensitive(row, "measured"), "x");
        ENSURE_MSG(lo < mid && mid < hi && lo <= x && x <= hi, "row %d: %g %g %g, nominal %g", i, lo, mid, hi, x);
        const cJSON *in = cJSON_GetObjectItemCaseSensitive(u, "measured_inside");
        ENSURE(cJSON_IsBool(in) && cJSON_IsTrue(in) == (meas >= lo && meas <= hi));
        printf("  %2.0f deg: 95 %% interval %.2f .. %.2f cm, measured %.1f cm: %s\n",
               num(row, "incline_deg"), lo * 100, hi * 100, meas * 100, cJSON_IsTrue(in) ? "inside" : "outside");
        if (i == 1) {
            const char *extra[] = {"--incline", "30", "--samples", "2000", "--seed", "1", NULL};
            cli_result m;
            cJSON *mc = mc_json(extra, &m);
            ENSURE(mc != NULL);
            const cJSON *l = cJSON_GetObjectItemCaseSensitive(mc, "first_liftoff_x_m");
            ENSURE(num(l, "p2_5") == lo && num(l, "p97_5") == hi);
            cJSON_Delete(mc);
            cli_result_free(&m);
        }
    }
    cJSON_Delete(doc);
    cli_result_free(&r);
    char png[128];
    path_in(png, sizeof png, "u.png");
    const char *plot[] = {"plot", "--what", "paper-uncertainty", "--output", png, NULL};
    cli_result p = cli_run(plot);
    ENSURE_MSG(p.status == 0, "%s", p.err);
    char *img = cli_run_slurp(png);
    ENSURE(img && memcmp(img, "\x89PNG", 4) == 0);
    free(img);
    cli_result_free(&p);
    const char *bad[] = {"plot", "--what", "paper-uncertainty", "--incline", "20", "--output", png, NULL};
    p = cli_run(bad);
    ENSURE(p.status == 2 && cli_one_line(p.err));
    cli_result_free(&p);
    return 0;
}

/* A device or FIFO is written in place, never renamed over; a directory or
 * a full device is refused with one line. */
static int test_special_outputs(void)
{
    const char *to_null[] = {"sweep", "--vary", "incline=10,20", "--output", "/dev/null", NULL};
    cli_result r = cli_run(to_null);
    struct stat st;
    ENSURE_MSG(r.status == 0 && stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode) && !cli_file_exists("/dev/null.part"),
               "%s", r.err);
    cli_result_free(&r);
    const char *to_full[] = {"sweep", "--vary", "incline=10,20", "--output", "/dev/full", NULL};
    r = cli_run(to_full);
    ENSURE_MSG(r.status == 1 && cli_one_line(r.err) && strstr(r.err, "No space"), "%d %s", r.status, r.err);
    cli_result_free(&r);
    const char *to_dir[] = {"sweep", "--vary", "incline=10,20", "--output", dir, NULL};
    r = cli_run(to_dir);
    char part[128];
    snprintf(part, sizeof part, "%s.part", dir);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err) && !cli_file_exists(part), "%d %s", r.status, r.err);
    cli_result_free(&r);
    const char *resume_null[] = {"mc", "--samples", "5", "--output", "/dev/null", "--resume", NULL};
    r = cli_run(resume_null);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err), "%d %s", r.status, r.err);
    cli_result_free(&r);
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    snprintf(dir, sizeof dir, "/tmp/jc_batch_XXXXXX");
    if (!mkdtemp(dir)) return 2;
    RUN_TEST(test_sweep_rows_are_simulate_runs);
    RUN_TEST(test_same_bytes_for_threads_and_shards);
    RUN_TEST(test_stopped_sweep_resumes_to_the_same_bytes);
    RUN_TEST(test_mc_without_spread_is_the_run);
    RUN_TEST(test_mc_converges_to_the_linearised_spread);
    RUN_TEST(test_mc_shards_are_the_whole_job);
    RUN_TEST(test_mc_estimated_past_the_limit);
    RUN_TEST(test_mc_summarize_memory_is_bounded);
    RUN_TEST(test_bad_values);
    RUN_TEST(test_paper_uncertainty);
    RUN_TEST(test_special_outputs);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    TEST_MAIN_END();
}
