/* design: the table on standard output, --json and --csv files. Lengths
 * are shown in cm, masses in g, angles in degrees, numbers bare, the other
 * quantities in SI; the files keep SI (angles in degrees in the CSV, as
 * sweep writes them). */
#include "design.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Intervals of reachable first lift-offs shown at most. */
#define REACHABLE_MAX 64

/* The display unit and its factor from SI; the sensitivity's unit, x in cm
 * per step of the option (a mm, a g, a degree, 0.01 of a number, one SI
 * unit of the others), and its factor from m per SI unit. */
static cli_DesignUnits units_of(const char *unit, double per_si, const char *step, double dx_per_si)
{
    cli_DesignUnits u;
    snprintf(u.unit, sizeof u.unit, "%s%s", *unit ? " " : "", unit);
    snprintf(u.paren, sizeof u.paren, *unit ? " (%s)" : "%s", unit);
    u.per_si = per_si;
    snprintf(u.dx_unit, sizeof u.dx_unit, "cm per %s", step);
    u.dx_per_si = dx_per_si;
    return u;
}

cli_DesignUnits cli_design_units(const cli_DesignJob *job)
{
    switch (job->param.q) {
    case Q_LENGTH: return units_of("cm", 100.0, "mm", 100.0 / 1e3);
    case Q_MASS: return units_of("g", 1e3, "g", 100.0 / 1e3);
    case Q_ANGLE: return units_of("deg", 180.0 / CLI_PI, "deg", 100.0 * CLI_PI / 180.0);
    case Q_NUMBER: return units_of("", 1.0, "0.01", 1.0);
    default: break;
    }
    const char *si = jc_param_info(job->param.id)->si_unit;
    return units_of(si, 1.0, si, 100.0);
}

static const char *free_name(const cli_DesignJob *job) { return jc_param_info(job->param.id)->name; }

static const char *outcome_words(jc_CaseKind k)
{
    switch (k) {
    case JC_CASE_LIFTOFF: return "lifts off";
    case JC_CASE_NO_LIFTOFF: return "no lift-off on the ramp";
    case JC_CASE_SLIDES_AT_START: return "slides from the start, no lift-off";
    case JC_CASE_INVALID: return "not a valid setup";
    case JC_CASE_FAILED: return "the run failed";
    }
    return "?";
}

static void print_branches(const cli_DesignJob *job, const jc_DesignResult *r, cli_DesignUnits u)
{
    printf("\nFirst lift-off along %s, branch by branch (continuous within each):\n", free_name(job));
    printf("  %-30s %s\n", "", "first lift-off (cm)");
    for (int k = 0; k < r->branch_count; ++k) {
        const jc_DesignBranch *b = &r->branches[k];
        char span[64];
        snprintf(span, sizeof span, "%.6g - %.6g%s", b->p_lo * u.per_si, b->p_hi * u.per_si, u.unit);
        if (b->kind == JC_CASE_LIFTOFF)
            printf("  %-30s %.4f - %.4f\n", span, b->x_min_m * 100, b->x_max_m * 100);
        else printf("  %-30s %s\n", span, outcome_words(b->kind));
    }
}

static void print_side(const jc_DesignPoint *s)
{
    if (s->kind == JC_CASE_LIFTOFF) printf("%14.4f cm", s->x_m * 100);
    else printf("  %s", outcome_words(s->kind));
}

/* The first lift-offs between the two sides of a leap, a to b, that no
 * branch reaches (lo, hi: the reachable ranges, sorted and merged). */
static void print_gap(double a, double b, const double *lo, const double *hi, int n)
{
    int parts = 0;
    for (int k = 0; k <= n && a < b; ++k) {
        const double end = k < n ? fmin(b, lo[k]) : b;
        if (end > a) printf("%s %.4f - %.4f cm", parts++ ? "," : "   (gap", a * 100, end * 100);
        if (k < n) a = fmax(a, hi[k]);
    }
    printf("%s", parts ? ")" : "   (reached on other branches: no gap)");
}

static void print_edges(const cli_DesignJob *job, const jc_DesignResult *r, cli_DesignUnits u, const double *lo,
                        const double *hi, int n)
{
    if (r->edge_count == 0) {
        printf("\nNo discontinuity: the first lift-off is continuous over the whole range.\n");
        return;
    }
    printf("\nDiscontinuities (each located to %.2g%s; first lift-offs between the two sides that no branch reaches are gaps):\n",
           r->edge_width * u.per_si, u.unit);
    for (int k = 0; k < r->edge_count; ++k) {
        const jc_DesignEdge *e = &r->edges[k];
        printf("  at %s = %.10g%s: ", free_name(job), 0.5 * (e->lo.p + e->hi.p) * u.per_si, u.unit);
        print_side(&e->lo);
        printf("  ->");
        print_side(&e->hi);
        if (e->lo.kind == JC_CASE_LIFTOFF && e->hi.kind == JC_CASE_LIFTOFF)
            print_gap(fmin(e->lo.x_m, e->hi.x_m), fmax(e->lo.x_m, e->hi.x_m), lo, hi, n);
        putchar('\n');
    }
}

/* No solution: where X lies among the reachable first lift-offs. */
static void print_no_solution(const cli_DesignJob *job, const jc_DesignResult *r, cli_DesignUnits u,
                              const double *lo, const double *hi, int n)
{
    printf("\nNo solution: no %s in %.6g - %.6g%s makes the first lift-off happen at %.4f cm.\n", free_name(job),
           job->lo * u.per_si, job->hi * u.per_si, u.unit, job->target_m * 100);
    if (n == 0) {
        printf("Nothing in the range lifts off on the ramp.\n");
        return;
    }
    double below = -INFINITY, above = INFINITY;
    for (int k = 0; k < n; ++k) {
        if (lo[k] <= job->target_m && job->target_m <= hi[k]) {
            printf("%.4f cm lies in the reachable range %.4f - %.4f cm, but only as the limit of the first\n"
                   "lift-off at a discontinuity's edge%s.\n",
                   job->target_m * 100, lo[k] * 100, hi[k] * 100,
                   r->at_edge ? "" : ", or between scan points too far apart (raise --points)");
            return;
        }
        if (hi[k] < job->target_m) below = fmax(below, hi[k]);
        if (lo[k] > job->target_m) above = fmin(above, lo[k]);
    }
    if (isfinite(below) && isfinite(above))
        printf("%.4f cm lies in the gap %.4f - %.4f cm that no value reaches.\n", job->target_m * 100, below * 100,
               above * 100);
    else if (isfinite(below))
        printf("%.4f cm lies beyond every reachable first lift-off (the farthest is %.4f cm).\n",
               job->target_m * 100, below * 100);
    else
        printf("%.4f cm lies before every reachable first lift-off (the nearest is %.4f cm).\n",
               job->target_m * 100, above * 100);
    for (int k = 0; k < r->edge_count; ++k) {
        const jc_DesignEdge *e = &r->edges[k];
        if (e->lo.kind == JC_CASE_LIFTOFF && e->hi.kind == JC_CASE_LIFTOFF &&
            (e->lo.x_m - job->target_m) * (e->hi.x_m - job->target_m) < 0.0)
            printf("At %s = %.6g%s the first lift-off leaps over it, from %.4f to %.4f cm.\n", free_name(job),
                   0.5 * (e->lo.p + e->hi.p) * u.per_si, u.unit, e->lo.x_m * 100, e->hi.x_m * 100);
    }
}

void cli_design_print(const cli_DesignJob *job, const jc_DesignResult *r, const char *range_note)
{
    const cli_DesignUnits u = cli_design_units(job);
    jc_Model m;
    char err[256];
    printf("Design: the %s that makes the first lift-off happen at X = %.4f cm down the ramp\n", free_name(job),
           job->target_m * 100);
    if (jc_model_init(&m, &job->nominal, err, sizeof err) == JC_OK) cli_print_setup(stdout, &m, 1);
    printf("Free: %s from %.6g to %.6g%s (%s); the setup line shows its nominal value\n", free_name(job),
           job->lo * u.per_si, job->hi * u.per_si, u.unit, range_note);
    printf("Search: %ld scan points, %ld runs of the model in all, %.2f s on %d thread%s\n", r->scan_count,
           r->evaluations, r->seconds, r->threads_used, r->threads_used == 1 ? "" : "s");
    print_branches(job, r, u);
    double lo[REACHABLE_MAX], hi[REACHABLE_MAX];
    const int n = jc_design_reachable(r, lo, hi, REACHABLE_MAX);
    print_edges(job, r, u, lo, hi, n);
    printf("\nReachable first lift-offs:");
    for (int k = 0; k < n; ++k) printf("%s %.4f - %.4f cm", k ? "," : "", lo[k] * 100, hi[k] * 100);
    printf("%s\n", n ? "" : " none (nothing lifts off on the ramp)");
    if (r->solution_count == 0) print_no_solution(job, r, u, lo, hi, n);
    else {
        printf("\nSolutions (%d; each run again and found within %g m of X):\n", r->solution_count,
               JC_DESIGN_VERIFY_M);
        char head[64];
        snprintf(head, sizeof head, "%s%s", free_name(job), u.paren);
        char margin_head[48];
        snprintf(margin_head, sizeof margin_head, "to a leap%s", u.paren);
        printf("  %2s %-22s %20s %12s   %-22s %s\n", "#", head, "first lift-off (cm)", "x - X (m)", "dX/dp",
               margin_head);
        for (int k = 0; k < r->solution_count; ++k) {
            const jc_DesignSolution *s = &r->solutions[k];
            char slope[48];
            snprintf(slope, sizeof slope, "%+.4g %s", s->dxdp * u.dx_per_si, u.dx_unit);
            printf("  %2d %-22.10g %20.6f %12.2e   %-22s ", k + 1, s->p * u.per_si, s->x_m * 100,
                   s->x_m - job->target_m, slope);
            if (isfinite(s->edge_margin)) printf("%.4g\n", s->edge_margin * u.per_si);
            else printf("none in the range\n");
        }
    }
    if (r->at_edge > 0)
        printf("Note: %d root(s) lie so near a discontinuity that its edge is within %g m of X: there X is the\n"
               "limit of the first lift-off at the edge, not a value one could build, so not listed.\n",
               r->at_edge, JC_DESIGN_VERIFY_M);
    if (r->unverified > 0)
        printf("Note: %d bracket(s) did not give a root that lands within %g m of X when run again; they are not\n"
               "listed (raise --points to resolve the scan there).\n",
               r->unverified, JC_DESIGN_VERIFY_M);
}

/* ---- --json ---- */

static cJSON *side_json(const jc_DesignPoint *s)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "value", s->p);
    cJSON_AddStringToObject(o, "outcome", jc_case_kind_name(s->kind));
    if (s->kind == JC_CASE_LIFTOFF) cJSON_AddNumberToObject(o, "x_m", s->x_m);
    else cJSON_AddNullToObject(o, "x_m");
    return o;
}

static cJSON *design_json(const cli_DesignJob *job, const jc_DesignResult *r, cli_DesignUnits u)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddNumberToObject(doc, "target_x_m", job->target_m);
    cJSON *fr = cJSON_AddObjectToObject(doc, "free");
    cJSON_AddStringToObject(fr, "name", free_name(job));
    cJSON_AddStringToObject(fr, "si_unit", jc_param_info(job->param.id)->si_unit);
    cJSON_AddNumberToObject(fr, "lo", job->lo);
    cJSON_AddNumberToObject(fr, "hi", job->hi);
    cJSON_AddNumberToObject(doc, "points", (double)r->scan_count);
    cJSON_AddNumberToObject(doc, "evaluations", (double)r->evaluations);
    cJSON_AddNumberToObject(doc, "seconds", r->seconds);
    cJSON_AddNumberToObject(doc, "edge_width", r->edge_width);
    cJSON *br = cJSON_AddArrayToObject(doc, "branches");
    for (int k = 0; k < r->branch_count; ++k) {
        const jc_DesignBranch *b = &r->branches[k];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "lo", b->p_lo);
        cJSON_AddNumberToObject(o, "hi", b->p_hi);
        cJSON_AddStringToObject(o, "outcome", jc_case_kind_name(b->kind));
        if (b->kind == JC_CASE_LIFTOFF) {
            cJSON_AddNumberToObject(o, "x_min_m", b->x_min_m);
            cJSON_AddNumberToObject(o, "x_max_m", b->x_max_m);
        }
        cJSON_AddItemToArray(br, o);
    }
    cJSON *ed = cJSON_AddArrayToObject(doc, "discontinuities");
    for (int k = 0; k < r->edge_count; ++k) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToObject(o, "below", side_json(&r->edges[k].lo));
        cJSON_AddItemToObject(o, "above", side_json(&r->edges[k].hi));
        cJSON_AddItemToArray(ed, o);
    }
    double lo[REACHABLE_MAX], hi[REACHABLE_MAX];
    const int n = jc_design_reachable(r, lo, hi, REACHABLE_MAX);
    cJSON *re = cJSON_AddArrayToObject(doc, "reachable_m");
    for (int k = 0; k < n; ++k) cJSON_AddItemToArray(re, cJSON_CreateDoubleArray((double[]){lo[k], hi[k]}, 2));
    cJSON *so = cJSON_AddArrayToObject(doc, "solutions");
    for (int k = 0; k < r->solution_count; ++k) {
        const jc_DesignSolution *s = &r->solutions[k];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "value", s->p);
        cJSON_AddNumberToObject(o, "x_m", s->x_m);
        cJSON_AddNumberToObject(o, "error_m", s->x_m - job->target_m);
        cJSON_AddNumberToObject(o, "dxdp", s->dxdp);
        cJSON *sens = cJSON_AddObjectToObject(o, "sensitivity");
        cJSON_AddNumberToObject(sens, "value", s->dxdp * u.dx_per_si);
        cJSON_AddStringToObject(sens, "unit", u.dx_unit);
        if (isfinite(s->edge_margin)) cJSON_AddNumberToObject(o, "edge_margin", s->edge_margin);
        else cJSON_AddNullToObject(o, "edge_margin");
        cJSON_AddNumberToObject(o, "branch", s->branch);
        cJSON_AddItemToArray(so, o);
    }
    cJSON_AddNumberToObject(doc, "unverified", r->unverified);
    cJSON_AddNumberToObject(doc, "at_edge", r->at_edge);
    return doc;
}

int cli_design_write_json(const cli_DesignJob *job, const jc_DesignResult *r, const char *path)
{
    return cli_json_write(design_json(job, r, cli_design_units(job)), path);
}

/* ---- --csv: every point the search ran, in p order ---- */

typedef struct {
    jc_DesignPoint pt;
    const char *what;
} csv_row;

static int row_order(const void *a, const void *b)
{
    const double pa = ((const csv_row *)a)->pt.p, pb = ((const csv_row *)b)->pt.p;
    return (pa > pb) - (pa < pb);
}

int cli_design_write_csv(const cli_DesignJob *job, const jc_DesignResult *r, const char *path)
{
    const long n = r->scan_count + 2L * r->edge_count + r->solution_count;
    csv_row *rows = malloc((size_t)n * sizeof *rows);
    if (!rows) {
        cli_error("design: out of memory for the CSV rows");
        return EXIT_FAIL;
    }
    long m = 0;
    for (long i = 0; i < r->scan_count; ++i) rows[m++] = (csv_row){r->scan[i], "scan"};
    for (int k = 0; k < r->edge_count; ++k) {
        rows[m++] = (csv_row){r->edges[k].lo, "edge_below"};
        rows[m++] = (csv_row){r->edges[k].hi, "edge_above"};
    }
    for (int k = 0; k < r->solution_count; ++k)
        rows[m++] = (csv_row){{r->solutions[k].p, JC_CASE_LIFTOFF, r->solutions[k].x_m}, "solution"};
    qsort(rows, (size_t)m, sizeof *rows, row_order);
    cli_Output o;
    if (cli_output_begin(&o, path, 1) != 0) {
        free(rows);
        return EXIT_FAIL;
    }
    fprintf(o.f, "%s,first_liftoff_x_m,outcome,point\n", job->param.column);
    for (long i = 0; i < m; ++i) {
        char v[CLI_TOKEN_MAX];
        cli_param_column_value(&job->param, rows[i].pt.p, v, sizeof v);
        if (rows[i].pt.kind == JC_CASE_LIFTOFF)
            fprintf(o.f, "%s,%.12g,%s,%s\n", v, rows[i].pt.x_m, jc_case_kind_name(rows[i].pt.kind), rows[i].what);
        else fprintf(o.f, "%s,,%s,%s\n", v, jc_case_kind_name(rows[i].pt.kind), rows[i].what);
    }
    free(rows);
    return cli_output_commit(&o, CLI_CHECK_WRITES) == 0 ? EXIT_OK : EXIT_FAIL;
}
