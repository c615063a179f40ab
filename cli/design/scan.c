/* design: the runs, the dense scan, the discontinuities' edges and the
 * continuous branches between them (run.c runs it, then solve.c). Every run goes through cli_case_setup
 * and cli_case_run, the sweep engine's path: a design value is exactly the
 * run `jumpcyl simulate` makes with that option. */
#include "design.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* Edges are bisected until their sides lie this fraction of the range
 * apart (a few ulp of p at most): 35 to 40 runs per edge. */
#define EDGE_REL_WIDTH 1e-12
#define EDGE_BISECTIONS_MAX 200
/* Discontinuities located inside one scan step at most (a no-lift-off
 * sliver inside a lift-off branch is two). */
#define EDGES_PER_STEP_MAX 8
/* A step whose change is this many times its neighbours' is checked for a
 * discontinuity (a smooth x changes alike over neighbouring steps; a
 * square-root onset changes 2.4 times more over its first step, and the
 * check finds it continuous). */
#define STEP_RATIO_SUSPECT 2.0

void cli_design_eval(const cli_DesignJob *job, double p, jc_Workspace *ws, cli_DesignPoint *out)
{
    jc_Setup s;
    char why[256];
    const int ok = cli_case_setup(&job->base, &job->values, &job->param, 1, &p, &s, why, sizeof why) == 0;
    cli_CaseResult r;
    cli_case_run(0, "", ok ? &s : NULL, &job->sim, ws, &r);
    out->p = p;
    /* A body that slides from the start may still lift off later: the
     * first lift-off is what design is about. */
    out->kind = !isnan(r.liftoff_x_m) ? CASE_LIFTOFF : r.kind;
    out->x_m = out->kind == CASE_LIFTOFF ? r.liftoff_x_m : NAN;
}

/* How far apart two outcomes are: infinite across kinds, the lift-offs'
 * distance within lift-offs, 0 within another kind. */
static double outcome_distance(const cli_DesignPoint *a, const cli_DesignPoint *b)
{
    if (a->kind != b->kind) return INFINITY;
    return a->kind == CASE_LIFTOFF ? fabs(a->x_m - b->x_m) : 0.0;
}

static int is_edge(const cli_DesignPoint *a, const cli_DesignPoint *b)
{
    return outcome_distance(a, b) > CLI_DESIGN_JUMP_M;
}

/* Bisects [a, b] towards the half that changes more, until its sides are
 * width apart: a discontinuity keeps its whole change in one half, a
 * continuous x loses it. Returns the runs made. */
static long bisect_edge(const cli_DesignJob *job, cli_DesignPoint *a, cli_DesignPoint *b, double width,
                        jc_Workspace *ws)
{
    long runs = 0;
    for (int k = 0; k < EDGE_BISECTIONS_MAX && b->p - a->p > width; ++k) {
        const double mid = a->p + 0.5 * (b->p - a->p);
        if (!(mid > a->p && mid < b->p)) break; /* adjacent doubles */
        cli_DesignPoint m;
        cli_design_eval(job, mid, ws, &m);
        ++runs;
        if (outcome_distance(&m, b) > outcome_distance(a, &m)) *a = m;
        else *b = m;
    }
    return runs;
}

/* The discontinuities inside one scan step [a, b]: each one located, then
 * the pieces on either side searched again when their ends still differ
 * in kind (a sliver of another outcome inside the step). */
static int edges_in_step(const cli_DesignJob *job, const cli_DesignPoint *a0, const cli_DesignPoint *b0, double width,
                         jc_Workspace *ws, cli_DesignEdge *out, long *runs)
{
    cli_DesignPoint todo_a[EDGES_PER_STEP_MAX], todo_b[EDGES_PER_STEP_MAX];
    int todo = 1, found = 0;
    todo_a[0] = *a0;
    todo_b[0] = *b0;
    while (todo > 0 && found < EDGES_PER_STEP_MAX) {
        --todo;
        const cli_DesignPoint u = todo_a[todo], v = todo_b[todo];
        cli_DesignPoint a = u, b = v;
        *runs += bisect_edge(job, &a, &b, width, ws);
        if (!is_edge(&a, &b)) continue; /* steep, but continuous */
        out[found++] = (cli_DesignEdge){a, b};
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
static int step_suspect(const cli_DesignJob *job, const cli_DesignPoint *s, long n, long i)
{
    const cli_DesignPoint *a = &s[i], *b = &s[i + 1];
    if (a->kind != b->kind) return 1;
    if (a->kind != CASE_LIFTOFF) return 0;
    const double d = fabs(b->x_m - a->x_m);
    if (d <= CLI_DESIGN_JUMP_M) return 0;
    if ((a->x_m - job->target_m) * (b->x_m - job->target_m) <= 0.0) return 1;
    double neighbours = 0.0;
    if (i > 0 && s[i - 1].kind == CASE_LIFTOFF) neighbours = fmax(neighbours, fabs(a->x_m - s[i - 1].x_m));
    if (i + 2 < n && s[i + 2].kind == CASE_LIFTOFF) neighbours = fmax(neighbours, fabs(s[i + 2].x_m - b->x_m));
    return d > STEP_RATIO_SUSPECT * neighbours;
}

static int edge_order(const void *a, const void *b)
{
    const double pa = ((const cli_DesignEdge *)a)->lo.p, pb = ((const cli_DesignEdge *)b)->lo.p;
    return (pa > pb) - (pa < pb);
}

/* The calling thread's number in the design's parallel loops (0 without
 * OpenMP): which workspace it may use. */
int cli_design_thread_index(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/* The scan's points on every thread, with a progress line on a terminal. */
static void scan(const cli_DesignJob *job, cli_DesignResult *r, jc_Workspace **ws)
{
    cli_Progress progress;
    cli_progress_begin(&progress, "design: scan");
    long done = 0;
    const long n = r->scan_count;
#pragma omp parallel for schedule(dynamic, 8)
    for (long i = 0; i < n; ++i) {
        if (cli_stop_requested()) continue; /* an OpenMP loop cannot break: the rest is skipped */
        const double p = i == n - 1 ? job->hi : job->lo + (job->hi - job->lo) * (double)i / (double)(n - 1);
        cli_design_eval(job, p, ws[cli_design_thread_index()], &r->scan[i]);
        long now;
#pragma omp atomic capture
        now = ++done;
        /* The progress record is shared: one thread at a time (it returns
         * at once unless a redraw is due). */
#pragma omp critical(design_progress)
        cli_progress_update(&progress, now, n);
    }
    cli_progress_end(&progress);
    r->evaluations += n;
}

/* Every suspect step bisected (on every thread); the edges in p order. */
static int locate_edges(const cli_DesignJob *job, cli_DesignResult *r, jc_Workspace **ws)
{
    const long n = r->scan_count;
    long *suspects = malloc((size_t)n * sizeof *suspects);
    if (!suspects) return -1;
    long count = 0;
    for (long i = 0; i + 1 < n; ++i)
        if (step_suspect(job, r->scan, n, i)) suspects[count++] = i;
    cli_DesignEdge *found = malloc((size_t)(count > 0 ? count : 1) * EDGES_PER_STEP_MAX * sizeof *found);
    int *found_count = calloc((size_t)(count > 0 ? count : 1), sizeof *found_count);
    if (!found || !found_count) {
        free(suspects);
        free(found);
        free(found_count);
        return -1;
    }
    long runs = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : runs)
    for (long k = 0; k < count; ++k) {
        if (cli_stop_requested()) continue;
        const long i = suspects[k];
        found_count[k] = edges_in_step(job, &r->scan[i], &r->scan[i + 1], r->edge_width, ws[cli_design_thread_index()],
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

static void branch_take(cli_DesignBranch *b, const cli_DesignPoint *pt)
{
    if (pt->kind != b->kind || pt->kind != CASE_LIFTOFF) return;
    b->x_min_m = fmin(b->x_min_m, pt->x_m);
    b->x_max_m = fmax(b->x_max_m, pt->x_m);
}

/* The branches between the edges: their extent, kind and lift-off range. */
static int make_branches(const cli_DesignJob *job, cli_DesignResult *r)
{
    r->branch_count = r->edge_count + 1;
    r->branches = malloc((size_t)r->branch_count * sizeof *r->branches);
    if (!r->branches) return -1;
    long i = 0;
    for (int k = 0; k < r->branch_count; ++k) {
        cli_DesignBranch *b = &r->branches[k];
        const cli_DesignPoint *first = k > 0 ? &r->edges[k - 1].hi : &r->scan[0];
        const cli_DesignPoint *last = k < r->edge_count ? &r->edges[k].lo : &r->scan[r->scan_count - 1];
        *b = (cli_DesignBranch){first->p, last->p, first->kind, INFINITY, -INFINITY};
        branch_take(b, first);
        branch_take(b, last);
        for (; i < r->scan_count && r->scan[i].p <= last->p; ++i)
            if (r->scan[i].p >= first->p) branch_take(b, &r->scan[i]);
    }
    (void)job;
    return 0;
}

int cli_design_scan(const cli_DesignJob *job, cli_DesignResult *r, jc_Workspace **ws)
{
    r->scan_count = job->points;
    r->edge_width = (job->hi - job->lo) * EDGE_REL_WIDTH;
    r->scan = malloc((size_t)job->points * sizeof *r->scan);
    if (!r->scan) return -1;
    scan(job, r, ws);
    if (!cli_stop_requested() && locate_edges(job, r, ws) != 0) return -1;
    if (!cli_stop_requested() && make_branches(job, r) != 0) return -1;
    return 0;
}

void cli_design_free(cli_DesignResult *r)
{
    free(r->scan);
    free(r->edges);
    free(r->branches);
    free(r->solutions);
    memset(r, 0, sizeof *r);
}
