/* The design search's roots of x(p) - X inside the continuous branches. A
 * bracket never spans an edge (the branches end at the edges' sides), so
 * Brent's method converges to a true root, not to a leap; each root is then
 * run again and kept only when it lands within 1e-6 m of X. */
#include "study_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>


#define BRENT_ITERATIONS_MAX 200
#define MIN_ITERATIONS_MAX 100
/* Turning points refined per branch at most (a wiggly x near X). */
#define TURNS_PER_BRANCH_MAX 64
/* A turning point is refined when X lies within this many of its steps'
 * changes: the true extremum can pass X between scan points. */
#define TURN_REACH_STEPS 2.0
/* A root this many edge widths from a leap is taken as its edge. */
#define EDGE_NEAR_WIDTHS 1e3
/* The sensitivity's step, as a fraction of the range. */
#define DIFF_REL_STEP 1e-6

typedef struct {
    const jc_DesignDef *def;
    jc_Workspace *ws;
    double sign;    /* +1, or -1 to minimise -x (a maximum) */
    long runs;
    double last_p, last_f;
} eval_ctx;

/* x(p) - X; NaN where it does not lift off (Brent then stops). */
static double offset_from_target(double p, void *params)
{
    eval_ctx *c = params;
    jc_DesignPoint pt;
    jc_design_eval(c->def, p, c->ws, &pt);
    ++c->runs;
    c->last_p = p;
    c->last_f = pt.x_m - c->def->target_x_m;
    return c->sign * c->last_f;
}

typedef struct {
    jc_DesignPoint a, b;
    int branch;
} bracket;

/* The extremum of x near a scan point j (a minimum when sign is +1), by
 * Brent's minimiser on [a, b]; 0 and *out, or -1. */
static int refine_turn(const jc_DesignDef *def, const jc_DesignPoint *a, const jc_DesignPoint *m,
                       const jc_DesignPoint *b, double sign, jc_Workspace *ws, double width, jc_DesignPoint *out,
                       long *runs)
{
    eval_ctx c = {def, ws, sign, 0, NAN, NAN};
    gsl_function f = {offset_from_target, &c};
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    if (!s) return -1;
    const double target = def->target_x_m;
    int st = gsl_min_fminimizer_set_with_values(s, &f, m->p, sign * (m->x_m - target), a->p, sign * (a->x_m - target),
                                                b->p, sign * (b->x_m - target));
    for (int k = 0; st == GSL_SUCCESS && k < MIN_ITERATIONS_MAX; ++k) {
        st = gsl_min_fminimizer_iterate(s);
        if (st != GSL_SUCCESS) break;
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), width, 0.0) ==
            GSL_SUCCESS)
            break;
        /* Once past X the bracket is known: no need for the extremum itself. */
        if (gsl_min_fminimizer_f_minimum(s) < 0.0) break;
    }
    const double p = st == GSL_SUCCESS ? gsl_min_fminimizer_x_minimum(s) : NAN;
    gsl_min_fminimizer_free(s);
    *runs += c.runs;
    if (isnan(p)) return -1;
    jc_design_eval(def, p, ws, out);
    ++*runs;
    return out->kind == JC_CASE_LIFTOFF ? 0 : -1;
}

/* The lift-off points of branch k in p order: its first side, the scan
 * points inside, its last side. */
static int branch_points(const jc_DesignResult *r, int k, jc_DesignPoint *out, long cap)
{
    const jc_DesignBranch *b = &r->branches[k];
    long n = 0;
    const jc_DesignPoint *first = k > 0 ? &r->edges[k - 1].hi : &r->scan[0];
    const jc_DesignPoint *last = k < r->edge_count ? &r->edges[k].lo : &r->scan[r->scan_count - 1];
    if (n < cap && first->kind == JC_CASE_LIFTOFF) out[n++] = *first;
    for (long i = 0; i < r->scan_count && n < cap; ++i) {
        const jc_DesignPoint *s = &r->scan[i];
        if (s->p > b->p_lo && s->p < b->p_hi && s->kind == JC_CASE_LIFTOFF) out[n++] = *s;
    }
    if (n < cap && last->kind == JC_CASE_LIFTOFF && last->p > first->p) out[n++] = *last;
    return (int)n;
}

static int point_order(const void *a, const void *b)
{
    const double pa = ((const jc_DesignPoint *)a)->p, pb = ((const jc_DesignPoint *)b)->p;
    return (pa > pb) - (pa < pb);
}

static int crosses(const jc_DesignPoint *a, const jc_DesignPoint *b, double target)
{
    return (a->x_m - target) * (b->x_m - target) <= 0.0;
}

/* Turning points that may pass X between scan points, refined and added
 * to the branch's points (kept sorted). Returns the new count. */
static long add_turns(const jc_DesignDef *def, jc_DesignPoint *pts, long n, long cap, double width,
                      jc_Workspace *ws, long *runs)
{
    const double target = def->target_x_m;
    const long n0 = n;
    int turns = 0;
    for (long j = 1; j + 1 < n0 && turns < TURNS_PER_BRANCH_MAX && n < cap; ++j) {
        const jc_DesignPoint *a = &pts[j - 1], *m = &pts[j], *b = &pts[j + 1];
        const double da = m->x_m - a->x_m, db = b->x_m - m->x_m;
        if (!(da * db < 0.0) || crosses(a, m, target) || crosses(m, b, target)) continue;
        const double reach = TURN_REACH_STEPS * fmax(fabs(da), fabs(db));
        if (fabs(m->x_m - target) > reach) continue;
        const double sign = da < 0.0 ? 1.0 : -1.0; /* a minimum, or a maximum */
        if (sign * (m->x_m - target) < 0.0) continue; /* on the far side of X already: no crossing to add */
        jc_DesignPoint turn;
        ++turns;
        if (refine_turn(def, a, m, b, sign, ws, width, &turn, runs) == 0) pts[n++] = turn;
    }
    qsort(pts, (size_t)n, sizeof *pts, point_order);
    return n;
}

/* Brent's method on one bracket inside a branch; the root, or NaN. */
static double polish(const jc_DesignDef *def, const bracket *br, jc_Workspace *ws, double width, long *runs)
{
    const double target = def->target_x_m;
    if (fabs(br->a.x_m - target) <= JC_DESIGN_ROOT_M) return br->a.p;
    if (fabs(br->b.x_m - target) <= JC_DESIGN_ROOT_M) return br->b.p;
    eval_ctx c = {def, ws, 1.0, 0, NAN, NAN};
    gsl_function f = {offset_from_target, &c};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) return NAN;
    double root = NAN;
    int st = gsl_root_fsolver_set(s, &f, br->a.p, br->b.p);
    for (int k = 0; st == GSL_SUCCESS && k < BRENT_ITERATIONS_MAX; ++k) {
        if ((st = gsl_root_fsolver_iterate(s)) != GSL_SUCCESS) break;
        const double p = gsl_root_fsolver_root(s);
        if (c.last_p == p && fabs(c.last_f) <= JC_DESIGN_ROOT_M) {
            root = p;
            break;
        }
        /* The bracket cannot shrink further: its best end. */
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), width * 1e-3, 0.0) ==
            GSL_SUCCESS) {
            root = p;
            break;
        }
    }
    gsl_root_fsolver_free(s);
    *runs += c.runs;
    return root;
}

/* dX/dp by a central difference inside the branch (one-sided by its ends). */
static double slope(const jc_DesignDef *def, const jc_DesignBranch *b, double p, double x, jc_Workspace *ws,
                    long *runs)
{
    const double h = (def->hi - def->lo) * DIFF_REL_STEP;
    const double lo = fmax(p - h, b->p_lo), hi = fmin(p + h, b->p_hi);
    jc_DesignPoint u = {p, JC_CASE_LIFTOFF, x}, v = u;
    if (lo < p) {
        jc_design_eval(def, lo, ws, &u);
        ++*runs;
    }
    if (hi > p) {
        jc_design_eval(def, hi, ws, &v);
        ++*runs;
    }
    if (u.kind != JC_CASE_LIFTOFF || v.kind != JC_CASE_LIFTOFF || !(v.p > u.p)) return NAN;
    return (v.x_m - u.x_m) / (v.p - u.p);
}

/* The distance from p to the nearer end of its branch that is an edge
 * (INFINITY when both ends are the range's). */
static double edge_margin(const jc_DesignResult *r, int branch, double p)
{
    const jc_DesignBranch *b = &r->branches[branch];
    double m = INFINITY;
    if (branch > 0) m = fmin(m, p - b->p_lo);
    if (branch < r->branch_count - 1) m = fmin(m, b->p_hi - p);
    return m;
}

/* The brackets of every lift-off branch; NULL when out of memory. */
static bracket *find_brackets(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace *ws, int *count)
{
    const long cap = r->scan_count + 2 + TURNS_PER_BRANCH_MAX;
    jc_DesignPoint *pts = malloc((size_t)cap * sizeof *pts);
    long bcap = 16;
    bracket *out = malloc((size_t)bcap * sizeof *out);
    *count = 0;
    for (int k = 0; pts && out && k < r->branch_count; ++k) {
        if (r->branches[k].kind != JC_CASE_LIFTOFF) continue;
        long n = branch_points(r, k, pts, cap);
        n = add_turns(def, pts, n, cap, r->edge_width, ws, &r->evaluations);
        for (long j = 0; j < n; ++j) { /* refined turning points widen the branch's range */
            r->branches[k].x_min_m = fmin(r->branches[k].x_min_m, pts[j].x_m);
            r->branches[k].x_max_m = fmax(r->branches[k].x_max_m, pts[j].x_m);
        }
        for (long j = 0; j + 1 < n; ++j) {
            if (!crosses(&pts[j], &pts[j + 1], def->target_x_m)) continue;
            /* x equal to X at a shared point: one bracket, not two. */
            if (j > 0 && pts[j].x_m == def->target_x_m && crosses(&pts[j - 1], &pts[j], def->target_x_m)) continue;
            if (*count == bcap) {
                bracket *bigger = realloc(out, (size_t)(bcap *= 2) * sizeof *out);
                if (!bigger) {
                    free(out);
                    out = NULL;
                    break;
                }
                out = bigger;
            }
            out[(*count)++] = (bracket){pts[j], pts[j + 1], k};
        }
    }
    if (!pts) {
        free(out);
        out = NULL;
    }
    free(pts);
    return out;
}

int jc_design_solve(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws)
{
    int count = 0;
    bracket *br = find_brackets(def, r, ws[0], &count);
    jc_DesignSolution *sol = malloc((size_t)(count > 0 ? count : 1) * sizeof *sol);
    if (!br || !sol) {
        free(br);
        free(sol);
        return JC_ENOMEM;
    }
    long runs = 0;
    JC_OMP("omp parallel for schedule(dynamic, 1) reduction(+ : runs) num_threads(r->threads_used)")
    for (int k = 0; k < count; ++k) {
        sol[k].p = NAN;
        sol[k].x_m = NAN;
        jc_Workspace *w = ws[jc_thread_index()];
        const double p = polish(def, &br[k], w, r->edge_width, &runs);
        if (isnan(p)) continue;
        /* Verified by a run of its own: what the user will see. */
        jc_DesignPoint check;
        jc_design_eval(def, p, w, &check);
        ++runs;
        if (check.kind != JC_CASE_LIFTOFF || !(fabs(check.x_m - def->target_x_m) <= JC_DESIGN_VERIFY_M)) continue;
        const jc_DesignBranch *b = &r->branches[br[k].branch];
        const double dxdp = slope(def, b, p, check.x_m, w, &runs);
        const double margin = edge_margin(r, br[k].branch, p);
        /* A root so near a leap that going all the way to the edge changes
         * x by less than the check's tolerance is the edge's limit: not a
         * value anyone could build. Said, never listed. */
        if (margin <= EDGE_NEAR_WIDTHS * r->edge_width || margin * fabs(dxdp) <= JC_DESIGN_VERIFY_M) {
            sol[k].x_m = INFINITY;
            continue;
        }
        sol[k] = (jc_DesignSolution){p, check.x_m, dxdp, margin, br[k].branch};
    }
    r->evaluations += runs;
    for (int k = 0; k < count; ++k) {
        if (isnan(sol[k].p)) {
            if (isinf(sol[k].x_m)) ++r->at_edge;
            else ++r->unverified;
            continue;
        }
        sol[r->solution_count++] = sol[k];
    }
    r->solutions = sol;
    free(br);
    return JC_OK;
}

static int interval_order(const void *a, const void *b)
{
    const double pa = ((const double *)a)[0], pb = ((const double *)b)[0];
    return (pa > pb) - (pa < pb);
}

int jc_design_reachable(const jc_DesignResult *r, double *lo, double *hi, int cap)
{
    double (*iv)[2] = malloc((size_t)(r->branch_count > 0 ? r->branch_count : 1) * sizeof *iv);
    if (!iv) return 0;
    int n = 0;
    for (int k = 0; k < r->branch_count; ++k)
        if (r->branches[k].kind == JC_CASE_LIFTOFF && r->branches[k].x_min_m <= r->branches[k].x_max_m) {
            iv[n][0] = r->branches[k].x_min_m;
            iv[n++][1] = r->branches[k].x_max_m;
        }
    qsort(iv, (size_t)n, sizeof *iv, interval_order);
    int m = 0;
    for (int k = 0; k < n; ++k) {
        if (m > 0 && iv[k][0] <= hi[m - 1] + JC_DESIGN_JUMP_M) { /* closer is no leap (study.h) */
            hi[m - 1] = fmax(hi[m - 1], iv[k][1]);
        } else if (m < cap) {
            lo[m] = iv[k][0];
            hi[m++] = iv[k][1];
        }
    }
    free(iv);
    return m;
}
