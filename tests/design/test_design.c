/* jumpcyl design end to end (argv[1] is the built tool). Every answer is
 * fed back to the library here, with setups built in this file (not by the
 * tool's option code), and must lift off at X to 1e-6 m; the 20 deg
 * discontinuity near a 3.9 cm rod offset is found as a gap, and a target
 * inside it has no solution; a target with several solutions gets them all
 * (a brute dense scan here finds the same crossings); bad options give one
 * line on stderr, exit 2 and no file. */
#include "../figures/fig_common.h"

#include <cjson/cJSON.h>
#include <jumpcyl/jumpcyl.h>

static const char *cli;
static char dir[1024];

#define VERIFY_M 1e-6
#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* ---- the library, independently of the tool ---- */

/* The paper's cylinder on an incline with one option set to v (SI). */
static jc_Setup paper_with(const char *free, double v, double incline_deg)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = incline_deg * DEG;
    for (int i = 0; i < s.body.part_count; ++i) {
        jc_Part *p = &s.body.parts[i];
        if (p->kind == JC_PART_ROD && strcmp(free, "rod-offset") == 0) p->offset_m = v;
        if (p->kind == JC_PART_ROD && strcmp(free, "rod-mass") == 0) p->mass_kg = v;
        if (p->kind == JC_PART_DISC && strcmp(free, "radius") == 0) p->radius_m = v; /* the disc fills the rim */
    }
    if (strcmp(free, "radius") == 0) s.body.radius_m = v;
    if (strcmp(free, "theta0") == 0) s.theta0_rad = v;
    if (strcmp(free, "incline") == 0) s.incline_rad = v;
    return s;
}

/* The first lift-off of the full model, NaN if none on the ramp. */
static double first_liftoff(const jc_Setup *s)
{
    jc_Model m;
    jc_Run run;
    char err[256];
    const jc_SimOptions o = jc_default_sim_options();
    double x = NAN;
    memset(&run, 0, sizeof run);
    if (jc_model_init(&m, s, err, sizeof err) == JC_OK && jc_simulate(&m, &o, &run, err, sizeof err) == JC_OK) {
        jc_RunSummary sum;
        jc_run_summarize(&run, &sum);
        if (sum.first_liftoff >= 0) x = sum.first_liftoff_state.x_m;
    }
    jc_run_free(&run);
    return x;
}

static double liftoff_at(const char *free, double v, double incline_deg)
{
    const jc_Setup s = paper_with(free, v, incline_deg);
    return first_liftoff(&s);
}

/* ---- the tool ---- */

/* Runs design with --json into the scratch directory; the parsed document,
 * or NULL (the failure printed). */
static cJSON *design_json(const char *args, char **out_text)
{
    char path[1100], line[3000];
    snprintf(path, sizeof path, "%s/design.json", dir);
    remove(path);
    snprintf(line, sizeof line, "design %s --json '%s'", args, path);
    cli_result r = cli_run_line(cli, NULL, line);
    if (r.status != 0) {
        fprintf(stderr, "'%s': status %d: %s\n", line, r.status, r.err ? r.err : "?");
        cli_result_free(&r);
        return NULL;
    }
    if (out_text) *out_text = r.out;
    else free(r.out);
    free(r.err);
    char *text = cli_run_slurp(path);
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    if (!doc) fprintf(stderr, "'%s': no JSON document\n", line);
    return doc;
}

static double num(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* Every solution of the document, run here: it lifts off at X to 1e-6 m,
 * and its dX/dp agrees with a central difference made here. */
static int check_solutions(const cJSON *doc, const char *free, double incline_deg, int expected)
{
    const double target = num(doc, "target_x_m");
    const cJSON *sol = cJSON_GetObjectItemCaseSensitive(doc, "solutions");
    ENSURE(cJSON_IsArray(sol));
    ENSURE_MSG(cJSON_GetArraySize(sol) == expected, "%s: %d solutions, expected %d", free, cJSON_GetArraySize(sol),
               expected);
    const cJSON *s;
    cJSON_ArrayForEach(s, sol)
    {
        const double p = num(s, "value");
        const double x = liftoff_at(free, p, incline_deg);
        ENSURE_MSG(fabs(x - target) <= VERIFY_M, "%s = %.17g: the library lifts off at %.9f m, X = %.9f m", free, p, x,
                   target);
        const double h = 1e-7 * fmax(fabs(p), 1e-3);
        const double slope = (liftoff_at(free, p + h, incline_deg) - liftoff_at(free, p - h, incline_deg)) / (2 * h);
        ENSURE_MSG(fabs(num(s, "dxdp") - slope) <= 0.02 * fabs(slope) + 1e-6, "%s = %.17g: dX/dp %g, here %g", free,
                   p, num(s, "dxdp"), slope);
    }
    return 0;
}

static int test_answers_jump_at_x(void)
{
    static const struct {
        const char *free, *args;
        double incline_deg, target_m;
        int solutions;
    } cases[] = {
        {"rod-offset", "--free rod-offset --incline 20 --jump-at 1.20m", 20, 1.20, 1},
        {"rod-offset", "--free rod-offset --incline 30 --jump-at 60cm", 30, 0.60, 1},
        {"theta0", "--free theta0 --incline 30 --jump-at 1.00m", 30, 1.00, 1},
        {"incline", "--free incline --jump-at 1.00m", 30, 1.00, 1},
        {"rod-mass", "--free rod-mass --incline 30 --jump-at 1.20m", 30, 1.20, 1},
        {"radius", "--free radius --incline 30 --jump-at 1.20m --range 8cm:14cm", 30, 1.20, -1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        cJSON *doc = design_json(cases[k].args, NULL);
        ENSURE(doc);
        const double target = num(doc, "target_x_m");
        const int n = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "solutions"));
        const int rc = check_solutions(doc, cases[k].free, cases[k].incline_deg,
                                       cases[k].solutions >= 0 ? cases[k].solutions : n);
        cJSON_Delete(doc);
        ENSURE_MSG(rc == 0, "%s", cases[k].args);
        ENSURE_NEAR(target, cases[k].target_m, 1e-15);
        ENSURE_MSG(n >= 1, "%s: no solution", cases[k].args);
    }
    return 0;
}

/* The 30 deg example of the issue: 1.00 m lies in a gap for the rod offset. */
static int test_issue_example(void)
{
    char *text = NULL;
    cJSON *doc = design_json("--free rod-offset --incline 30 --jump-at 1.00m", &text);
    ENSURE(doc && text);
    const int n = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "solutions"));
    int in_gap = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(doc, "discontinuities"))
    {
        const double a = num(cJSON_GetObjectItemCaseSensitive(e, "below"), "x_m");
        const double b = num(cJSON_GetObjectItemCaseSensitive(e, "above"), "x_m");
        in_gap |= (a - 1.0) * (b - 1.0) < 0;
    }
    cJSON_Delete(doc);
    const int said = strstr(text, "No solution") && strstr(text, "gap");
    free(text);
    ENSURE_MSG(n == 0, "%d solutions", n);
    ENSURE(in_gap);
    ENSURE(said);
    return 0;
}

/* The discontinuity of the issue: on a 20 deg incline the first lift-off
 * leaps from 1.81 m to 1.26 m as the rod offset passes about 3.9 cm. */
static int test_gap_at_20_deg(void)
{
    char *text = NULL;
    cJSON *doc = design_json("--free rod-offset --incline 20 --jump-at 1.50m", &text);
    ENSURE(doc && text);
    const cJSON *found = NULL, *e;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(doc, "discontinuities"))
    {
        const double p = num(cJSON_GetObjectItemCaseSensitive(e, "below"), "value");
        if (p > 0.038 && p < 0.040) found = e;
    }
    ENSURE_MSG(found, "no discontinuity between 3.8 and 4.0 cm");
    const cJSON *lo = cJSON_GetObjectItemCaseSensitive(found, "below"), *hi = cJSON_GetObjectItemCaseSensitive(found, "above");
    const double p_lo = num(lo, "value"), p_hi = num(hi, "value");
    ENSURE_MSG(p_hi > p_lo && p_hi - p_lo <= 1e-12, "edge [%.17g, %.17g]", p_lo, p_hi);
    ENSURE_NEAR(num(lo, "x_m"), 1.81, 0.01);
    ENSURE_NEAR(num(hi, "x_m"), 1.26, 0.01);
    /* The leap is the library's: a micrometre either side of the edge. */
    ENSURE_NEAR(liftoff_at("rod-offset", p_lo - 1e-6, 20), num(lo, "x_m"), 1e-4);
    ENSURE_NEAR(liftoff_at("rod-offset", p_hi + 1e-6, 20), num(hi, "x_m"), 1e-3);
    /* 1.50 m is inside that gap and reached nowhere else: no solution, said so. */
    const int n = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "solutions"));
    cJSON_Delete(doc);
    const int said = strstr(text, "No solution") && strstr(text, "lies in the gap");
    free(text);
    ENSURE_MSG(n == 0, "%d solutions inside the gap", n);
    ENSURE(said);
    return 0;
}

/* theta0 over a whole turn: -180 and 180 deg are one start, so the two
 * branches that meet there reach one range of first lift-offs, and the leap
 * at -13.19 deg (65.13 -> 121.21 cm) is no gap: the values between are
 * reached on the other side of the turn. */
static int test_theta0_turn_has_no_gap(void)
{
    const double x_minus = liftoff_at("theta0", -PI, 30), x_plus = liftoff_at("theta0", PI, 30);
    ENSURE_NEAR(x_minus, x_plus, 1e-6);
    char *text = NULL;
    cJSON *doc = design_json("--free theta0 --incline 30 --jump-at 1.00m", &text);
    ENSURE(doc && text);
    const cJSON *reach = cJSON_GetObjectItemCaseSensitive(doc, "reachable_m");
    const int ranges = cJSON_GetArraySize(reach);
    const double lo = cJSON_GetArrayItem(cJSON_GetArrayItem(reach, 0), 0)->valuedouble;
    const double hi = cJSON_GetArrayItem(cJSON_GetArrayItem(reach, 0), 1)->valuedouble;
    const cJSON *leap = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(doc, "discontinuities"), 0);
    const double a = leap ? num(cJSON_GetObjectItemCaseSensitive(leap, "below"), "x_m") : NAN;
    const double b = leap ? num(cJSON_GetObjectItemCaseSensitive(leap, "above"), "x_m") : NAN;
    cJSON_Delete(doc);
    const int no_gap = strstr(text, "no gap") != NULL && strstr(text, "(gap") == NULL;
    free(text);
    ENSURE_MSG(ranges == 1, "%d reachable ranges", ranges);
    ENSURE_MSG(lo <= fmin(a, b) && fmax(a, b) <= hi, "leap %g -> %g m outside %g - %g m", a, b, lo, hi);
    ENSURE(no_gap);
    return 0;
}

/* design's document for args and its first leap (the discontinuity) with
 * the parameter's value at the leap's lower side; NULL, after a message,
 * without the document or without a leap. */
static cJSON *design_with_leap(const char *args, const cJSON **leap, double *edge)
{
    cJSON *doc = design_json(args, NULL);
    *leap = doc ? cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(doc, "discontinuities"), 0) : NULL;
    if (doc && !*leap) {
        fprintf(stderr, "'%s': no discontinuity listed\n", args);
        cJSON_Delete(doc);
        return NULL;
    }
    *edge = *leap ? num(cJSON_GetObjectItemCaseSensitive(*leap, "below"), "value") : NAN;
    return doc;
}

/* A target between the branch's turning point and its side at the edge:
 * two roots, the second a few micrometres of x before the leap. Both are
 * inside the branch, neither is the edge. */
static int test_near_edge_not_edge(void)
{
    const cJSON *e;
    double edge;
    cJSON *doc = design_with_leap("--free rod-offset --incline 20 --jump-at 1.80837m --range 3.7cm:4.1cm", &e, &edge);
    ENSURE(doc);
    const cJSON *s;
    int rc = check_solutions(doc, "rod-offset", 20, 2);
    cJSON_ArrayForEach(s, cJSON_GetObjectItemCaseSensitive(doc, "solutions"))
    {
        if (!(num(s, "value") < edge - 1e-9)) rc = 1;
    }
    cJSON_Delete(doc);
    ENSURE(rc == 0);
    return 0;
}

/* X set to a side of the leap itself: the root there is the edge, which is
 * said (at_edge) and never listed; a root farther inside the branch is. */
static int test_edge_limit_not_listed(void)
{
    const cJSON *e;
    double edge;
    cJSON *doc = design_with_leap("--free rod-offset --incline 20 --jump-at 1.50m --range 3.7cm:4.1cm", &e, &edge);
    ENSURE(doc);
    const double below = num(cJSON_GetObjectItemCaseSensitive(e, "below"), "x_m");
    const double above = num(cJSON_GetObjectItemCaseSensitive(e, "above"), "x_m");
    cJSON_Delete(doc);
    const double sides[2] = {above, below};
    const int listed[2] = {0, 1}; /* above: the branch's top, reached only at the edge; below: one root inside */
    for (int k = 0; k < 2; ++k) {
        char args[256];
        snprintf(args, sizeof args, "--free rod-offset --incline 20 --jump-at %.17gm --range 3.7cm:4.1cm", sides[k]);
        doc = design_json(args, NULL);
        ENSURE(doc);
        const double at_edge = num(doc, "at_edge");
        int rc = check_solutions(doc, "rod-offset", 20, listed[k]);
        const cJSON *s;
        cJSON_ArrayForEach(s, cJSON_GetObjectItemCaseSensitive(doc, "solutions"))
        {
            if (!(fabs(num(s, "value") - edge) * fabs(num(s, "dxdp")) > VERIFY_M)) rc = 1;
        }
        cJSON_Delete(doc);
        ENSURE_MSG(rc == 0, "X = %.17g m", sides[k]);
        ENSURE_MSG(at_edge == 1, "X = %.17g m: at_edge %g", sides[k], at_edge);
    }
    return 0;
}

/* A brute dense scan with the library: the crossings of X between
 * neighbours whose lift-offs are close (no leap between them); each must
 * hold exactly one of the tool's solutions, and there are no others. */
static int brute_compare(const char *args, const char *free, double incline_deg, double lo, double hi, long n,
                         int at_least)
{
    cJSON *doc = design_json(args, NULL);
    ENSURE(doc);
    const double target = num(doc, "target_x_m");
    const cJSON *sol = cJSON_GetObjectItemCaseSensitive(doc, "solutions");
    const int count = cJSON_GetArraySize(sol);
    int crossings = 0, matched = 0;
    double prev_p = lo, prev_x = liftoff_at(free, lo, incline_deg);
    for (long i = 1; i < n; ++i) {
        const double p = lo + (hi - lo) * (double)i / (double)(n - 1);
        const double x = liftoff_at(free, p, incline_deg);
        if (!isnan(x) && !isnan(prev_x) && fabs(x - prev_x) < 0.01 && (x - target) * (prev_x - target) < 0) {
            ++crossings;
            int inside = 0;
            const cJSON *s;
            cJSON_ArrayForEach(s, sol) inside += num(s, "value") >= prev_p && num(s, "value") <= p;
            matched += inside == 1;
        }
        prev_p = p;
        prev_x = x;
    }
    const int rc = check_solutions(doc, free, incline_deg, count);
    cJSON_Delete(doc);
    ENSURE(rc == 0);
    ENSURE_MSG(crossings >= at_least, "%s: the brute scan finds %d crossings", args, crossings);
    ENSURE_MSG(count == crossings && matched == crossings, "%s: %d solutions, brute scan %d crossings (%d matched)",
               args, count, crossings, matched);
    return 0;
}

static int test_several_solutions(void)
{
    /* One branch with a minimum below X: two roots. */
    ENSURE(brute_compare("--free rod-offset --incline 20 --jump-at 1.1736m --range 5cm:9cm", "rod-offset", 20, 0.05,
                         0.09, 801, 2) == 0);
    /* The whole default range at 30 deg: the branch 2.2 - 6.0 cm dips to 1.173 m. */
    ENSURE(brute_compare("--free rod-offset --incline 30 --jump-at 1.18m", "rod-offset", 30, 0.001, 0.09525, 3000, 2) ==
           0);
    /* The initial angle over a whole turn. */
    ENSURE(brute_compare("--free theta0 --incline 30 --jump-at 1.10m", "theta0", 30, -180 * DEG, 180 * DEG, 2000, 1) ==
           0);
    return 0;
}

/* The table says it in words and units. */
static int test_text(void)
{
    cli_result r = cli_run_line(cli, NULL, "design --free rod-offset --incline 20 --jump-at 1.20m");
    ENSURE_MSG(r.status == 0, "status %d: %s", r.status, r.err ? r.err : "?");
    ENSURE(r.out && strstr(r.out, "Solutions (1;") && strstr(r.out, "cm per mm") &&
           strstr(r.out, "Discontinuities") && strstr(r.out, "Reachable first lift-offs:"));
    ENSURE(r.err && r.err[0] == '\0');
    cli_result_free(&r);
    return 0;
}

/* --csv and --figure: the points in order with the solution among them,
 * and a whole PNG. */
static int test_files(void)
{
    char csv[1100], png[1100], line[3000];
    snprintf(csv, sizeof csv, "%s/d.csv", dir);
    snprintf(png, sizeof png, "%s/d.png", dir);
    snprintf(line, sizeof line,
             "design --free rod-offset --incline 20 --jump-at 1.20m --points 200 --csv '%s' --figure '%s'", csv, png);
    cli_result r = cli_run_line(cli, NULL, line);
    ENSURE_MSG(r.status == 0, "status %d: %s", r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    char *text = cli_run_slurp(csv);
    ENSURE(text);
    const int header = strncmp(text, "rod_offset_m,first_liftoff_x_m,outcome,point\n", 45) == 0;
    int rows = 0, solutions = 0, ordered = 1;
    double prev = -1;
    for (char *l = strchr(text, '\n'); l && l[1]; l = strchr(l + 1, '\n')) {
        const double p = strtod(l + 1, NULL);
        ordered &= p >= prev;
        prev = p;
        ++rows;
        const char *end = strchr(l + 1, '\n');
        const char *sol = strstr(l + 1, ",solution");
        solutions += sol && end && sol < end;
    }
    free(text);
    ENSURE(header);
    ENSURE_MSG(rows >= 200 && solutions == 1 && ordered, "%d rows, %d solutions, ordered %d", rows, solutions,
               ordered);
    int w, h;
    ENSURE(fig_png_size(png, &w, &h) == 0 && w == 1200 && h == 750);
    return 0;
}

/* The answer does not depend on the number of threads. */
static int test_threads(void)
{
    char *text[2] = {NULL, NULL};
    for (int t = 0; t < 2; ++t) {
        cJSON *doc = design_json(t == 0 ? "--free rod-offset --incline 30 --jump-at 1.18m --threads 1"
                                        : "--free rod-offset --incline 30 --jump-at 1.18m --threads 2",
                                 NULL);
        ENSURE(doc);
        cJSON_DeleteItemFromObjectCaseSensitive(doc, "seconds"); /* the one field that may differ */
        text[t] = cJSON_PrintUnformatted(doc);
        cJSON_Delete(doc);
    }
    const int same = text[0] && text[1] && strcmp(text[0], text[1]) == 0;
    free(text[0]);
    free(text[1]);
    ENSURE(same);
    return 0;
}

/* Bad options: one line on stderr, exit 2, nothing written. */
static int test_bad_options(void)
{
    static const char *const bad[] = {
        "--jump-at 1m --free restitution",
        "--jump-at 1m --free impact-law",
        "--jump-at 1m --free bogus",
        "--jump-at 1m --free mu --mu-s 0.4",
        "--jump-at 1m --free mu-k --mu 0.4",
        "--jump-at 1m --free mu-k --range 0.1:0.9",
        "--jump-at 1m --free disc-mass --preset hoop",
        "--jump-at 5m --free rod-offset",
        "--jump-at -10cm --free rod-offset",
        "--jump-at 0 --free rod-offset",
        "--jump-at 1kg --free rod-offset",
        "--jump-at 1m --free rod-offset --range 5cm:5cm",
        "--jump-at 1m --free rod-offset --range 6cm:2cm",
        "--jump-at 1m --free rod-offset --range 2cm:12cm",
        "--jump-at 1m --free rod-offset --range 2cm",
        "--jump-at 1m --free theta0 --range 1cm:2cm",
        "--jump-at 1m --free rod-offset --rod-offset 3cm",
        "--free rod-offset",
        "--jump-at 1m",
        "--jump-at 1m --free rod-offset --points 3",
        "--jump-at 1m --free rod-offset --preset hoop",
        "--jump-at 1m --free radius --part disc:mass=30g --part rod:mass=30g,offset=5cm",
        "--jump-at 1m --free rod-offset --sample-dt 1ms",
        "--jump-at 1m --free rod-offset --free theta0",
        "--jump-at 1m --free rod-offset --range 2cm:3cm --range 3cm:4cm",
    };
    char sub[1100];
    snprintf(sub, sizeof sub, "%s/bad", dir);
    ENSURE(mkdir(sub, 0700) == 0);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        char line[4000];
        snprintf(line, sizeof line, "design %s --json '%s/a.json' --csv '%s/a.csv' --figure '%s/a.png'", bad[k], sub,
                 sub, sub);
        cli_result r = cli_run_line(cli, NULL, line);
        const int ok = r.status == 2 && cli_one_line(r.err) && r.out && r.out[0] == '\0';
        if (!ok) fprintf(stderr, "'%s': status %d, stdout '%s', stderr '%s'\n", bad[k], r.status, r.out, r.err);
        cli_result_free(&r);
        ENSURE(ok);
        ENSURE_MSG(fig_count_entries(sub) == 0, "'%s' left a file", bad[k]);
    }
    /* A figure format gnuplot is not asked for. */
    char line[4000];
    snprintf(line, sizeof line, "design --jump-at 1m --free rod-offset --json '%s/a.json' --figure '%s/a.gif'", sub,
             sub);
    cli_result r = cli_run_line(cli, NULL, line);
    ENSURE_MSG(r.status == 2 && cli_one_line(r.err), "status %d: %s", r.status, r.err);
    cli_result_free(&r);
    ENSURE(fig_count_entries(sub) == 0);
    return 0;
}

int main(int argc, char **argv)
{
    const int st = fig_main_begin(argc, argv, "design", &cli, dir, sizeof dir);
    if (st) return st;
    RUN_TEST(test_answers_jump_at_x);
    RUN_TEST(test_issue_example);
    RUN_TEST(test_gap_at_20_deg);
    RUN_TEST(test_theta0_turn_has_no_gap);
    RUN_TEST(test_near_edge_not_edge);
    RUN_TEST(test_edge_limit_not_listed);
    RUN_TEST(test_several_solutions);
    RUN_TEST(test_text);
    RUN_TEST(test_files);
    RUN_TEST(test_threads);
    RUN_TEST(test_bad_options);
    fig_main_end(dir);
    TEST_MAIN_END();
}
