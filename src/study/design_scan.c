/* The design search's runs, its dense scan, the discontinuities' edges and
 * the continuous branches between them. Every run is a study's case: the
 * values set with jc_param_values_apply, the run by jc_case_run, so a
 * design value is exactly the run `jumpcyl simulate` makes with it. */
#include "study_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Edges are bisected until their sides lie the result's edge_width apart
 * (a 1e-12 fraction of the range, design.c: a few ulp of p at most, 35 to
 * 40 runs per edge), or this many times at most. */
#define EDGE_BISECTIONS_MAX 200
/* Discontinuities located inside one scan step at most (a no-lift-off
 * sliver inside a lift-off branch is two). */
#define EDGES_PER_STEP_MAX 8
/* A step whose change is this many times its neighbours' is checked for a
 * discontinuity (a smooth x changes alike over neighbouring steps; a
 * square-root onset changes 2.4 times more over its first step, and the
 * check finds it continuous). */
#define STEP_RATIO_SUSPECT 2.0
/* Scan points per thread between two calls of the progress callback. */
#define SCAN_BLOCK_PER_THREAD 64

void jc_design_eval(const jc_DesignDef *def, double p, jc_Workspace *ws, jc_DesignPoint *out)
{
    jc_ParamValues v = def->fixed;
    v.given[def->free_id] = 1;
    v.value[def->free_id] = p;
    jc_Setup s = def->base;
    const int ok = jc_param_values_apply(&v, &s, NULL, NULL, 0) == JC_OK;
    jc_CaseOutcome r;
    jc_case_run(ok ? &s : NULL, &def->sim, ws, &r);
    out->p = p;
    /* A body that slides from the start may still lift off later: the
     * first lift-off is what design is about. */
    out->kind = !isnan(r.liftoff_x_m) ? JC_CASE_LIFTOFF : r.kind;
    out->x_m = out->kind == JC_CASE_LIFTOFF ? r.liftoff_x_m : NAN;
}

int jc_design_report(const jc_DesignDef *def, const char *stage, long done, long total)
{
    if (!def->progress) return 0;
    const jc_DesignProgress p = {stage, done, total};
    return def->progress(def->progress_ctx, &p) != 0;
}

/* How far apart two outcomes are: infinite across kinds, the lift-offs'
 * distance within lift-offs, 0 within another kind. */
static double outcome_distance(const jc_DesignPoint *a, const jc_DesignPoint *b)
{
    if (a->kind != b->kind) return INFINITY;
    return a->kind == JC_CASE_LIFTOFF ? fabs(a->x_m - b->x_m) : 0.0;
}

static int is_edge(const jc_DesignPoint *a, const jc_DesignPoint *b)
{
    return outcome_distance(a, b) > JC_DESIGN_JUMP_M;
}

/* Bisects [a, b] towards the half that changes more, until its sides are
 * width apart: a discontinuity keeps its whole change in one half, a
 * continuous x loses it. Returns the runs made. */
static long bisect_edge(const jc_DesignDef *def, jc_DesignPoint *a, jc_DesignPoint *b, double width,
                        jc_Workspace *ws)
{
    long runs = 0;
    for (int k = 0; k < EDGE_BISECTIONS_MAX && b->p - a->p > width; ++k) {
        const double mid = a->p + 0.5 * (b->p - a->p);
        if (!(mid > a->p && mid < b->p)) break; /* adjacent doubles */
        jc_DesignPoint m;
        jc_design_eval(def, mid, ws, &m);
        ++runs;
        if (outcome_distance(&m, b) > outcome_distance(a, &m)) *a = m;
        else *b = m;
    }
    return runs;
}

/* The discontinuities inside one scan step [a, b]: each one located, then
 * the pieces on either side searched again when their ends still differ
 * in kind (a sliver of another outcome inside the step). */
static int edges_in_step(const jc_DesignDef *def, const jc_DesignPoint *a0, const jc_DesignPoint *b0, double width,
                         jc_Workspace *ws, jc_DesignEdge *out, long *runs)
{
    jc_DesignPoint todo_a[EDGES_PER_STEP_MAX], todo_b[EDGES_PER_STEP_MAX];
    int todo = 1, found = 0;
    todo_a[0] = *a0;
    todo_b[0] = *b0;
    while (todo > 0 && found < EDGES_PER_STEP_MAX) {
        --todo;
        const jc_DesignPoint u = todo_a[todo], v = todo_b[todo];
        jc_DesignPoint a = u, b = v;
        *runs += bisect_edge(def, &a, &b, width, ws);
        if (!is_edge(&a, &b)) continue; /* steep, but continuous */
        out[found++] = (jc_DesignEdge){a, b};
        if (a.kind != u.kind && todo < EDGES_PER_STEP_MAX) {
            todo_a[todo] = u;
            todo_b[todo++] = a;
        }
        if (b.kind != v.kind && todo < EDGES_PER_STEP_MAX) {
            todo_a[todo] = b;
            todo_b[todo++] = v;
        }
    }
    return found;
}

/* Whether scan step i (between points i and i + 1) may hold a
 * discontinuity: the outcome changes kind, the change is out of line with
 * the neighbouring steps', or x - X changes sign (a root is polished only
 * where x is known to be continuous). */
static int step_suspect(const jc_DesignDef *def, const jc_DesignPoint *s, long n, long i)
{
    const jc_DesignPoint *a = &s[i], *b = &s[i + 1];
    if (a->kind != b->kind) return 1;
    if (a->kind != JC_CASE_LIFTOFF) return 0;
    const double d = fabs(b->x_m - a->x_m);
    if (d <= JC_DESIGN_JUMP_M) return 0;
    if ((a->x_m - def->target_x_m) * (b->x_m - def->target_x_m) <= 0.0) return 1;
    double neighbours = 0.0;
    if (i > 0 && s[i - 1].kind == JC_CASE_LIFTOFF) neighbours = fmax(neighbours, fabs(a->x_m - s[i - 1].x_m));
    if (i + 2 < n && s[i + 2].kind == JC_CASE_LIFTOFF) neighbours = fmax(neighbours, fabs(s[i + 2].x_m - b->x_m));
    return d > STEP_RATIO_SUSPECT * neighbours;
}

static int edge_order(const void *a, const void *b)
{
    const double pa = ((const jc_DesignEdge *)a)->lo.p, pb = ((const jc_DesignEdge *)b)->lo.p;
    return (pa > pb) - (pa < pb);
}

/* The scan's points on every thread, in blocks: the progress callback is
 * called between them, on the calling thread. Nonzero when it asked to stop. */
static int scan(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws)
{
    const long n = r->scan_count, block = (long)SCAN_BLOCK_PER_THREAD * r->threads_used;
    for (long first = 0; first < n; first += block) {
        const long last = first + block < n ? first + block : n;
        JC_OMP("omp parallel for schedule(dynamic, 8) num_threads(r->threads_used)")
        for (long i = first; i < last; ++i) {
            const double p = i == n - 1 ? def->hi : def->lo + (def->hi - def->lo) * (double)i / (double)(n - 1);
            jc_design_eval(def, p, ws[jc_thread_index()], &r->scan[i]);
        }
        r->evaluations += last - first;
        if (jc_design_report(def, "scan", last, n)) return 1;
    }
    return 0;
}

/* Every suspect step bisected (on every thread); the edges in p order. */
static int locate_edges(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws)
{
    const long n = r->scan_count;
    long *suspects = malloc((size_t)n * sizeof *suspects);
    if (!suspects) return -1;
    long count = 0;
    for (long i = 0; i + 1 < n; ++i)
        if (step_suspect(def, r->scan, n, i)) suspects[count++] = i;
    jc_DesignEdge *found = malloc((size_t)(count > 0 ? count : 1) * EDGES_PER_STEP_MAX * sizeof *found);
    int *found_count = calloc((size_t)(count > 0 ? count : 1), sizeof *found_count);
    if (!found || !found_count) {
        free(suspects);
        free(found);
        free(found_count);
        return -1;
    }
    long runs = 0;
    JC_OMP("omp parallel for schedule(dynamic, 1) reduction(+ : runs) num_threads(r->threads_used)")
    for (long k = 0; k < count; ++k) {
        const long i = suspects[k];
        found_count[k] = edges_in_step(def, &r->scan[i], &r->scan[i + 1], r->edge_width, ws[jc_thread_index()],
                                       &found[k * EDGES_PER_STEP_MAX], &runs);
    }
    r->evaluations += runs;
    int total = 0;
    for (long k = 0; k < count; ++k) total += found_count[k];
    r->edges = malloc((size_t)(total > 0 ? total : 1) * sizeof *r->edges);
    if (r->edges) {
        for (long k = 0; k < count; ++k)
            for (int j = 0; j < found_count[k]; ++j) r->edges[r->edge_count++] = found[k * EDGES_PER_STEP_MAX + j];
        qsort(r->edges, (size_t)r->edge_count, sizeof *r->edges, edge_order);
    }
    free(suspects);
    free(found);
    free(found_count);
    return r->edges ? 0 : -1;
}

static void branch_take(jc_DesignBranch *b, const jc_DesignPoint *pt)
{
    if (pt->kind != b->kind || pt->kind != JC_CASE_LIFTOFF) return;
    b->x_min_m = fmin(b->x_min_m, pt->x_m);
    b->x_max_m = fmax(b->x_max_m, pt->x_m);
}

/* The branches between the edges: their extent, kind and lift-off range. */
static int make_branches(jc_DesignResult *r)
{
    r->branch_count = r->edge_count + 1;
    r->branches = malloc((size_t)r->branch_count * sizeof *r->branches);
    if (!r->branches) return -1;
    long i = 0;
    for (int k = 0; k < r->branch_count; ++k) {
        jc_DesignBranch *b = &r->branches[k];
        const jc_DesignPoint *first = k > 0 ? &r->edges[k - 1].hi : &r->scan[0];
        const jc_DesignPoint *last = k < r->edge_count ? &r->edges[k].lo : &r->scan[r->scan_count - 1];
        *b = (jc_DesignBranch){first->p, last->p, first->kind, INFINITY, -INFINITY};
        branch_take(b, first);
        branch_take(b, last);
        for (; i < r->scan_count && r->scan[i].p <= last->p; ++i)
            if (r->scan[i].p >= first->p) branch_take(b, &r->scan[i]);
    }
    return 0;
}

int jc_design_scan(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws)
{
    if (scan(def, r, ws)) return JC_ESTOPPED;
    if (jc_design_report(def, "edges", 0, 0)) return JC_ESTOPPED;
    if (locate_edges(def, r, ws) != 0 || make_branches(r) != 0) return JC_ENOMEM;
    return JC_OK;
}
