/* jumpcyl design: which values of one setup option make the first lift-off
 * happen at a chosen place X on the ramp (docs/design.md).
 *
 * The first lift-off x(p) is a discontinuous function of most options: a
 * near-miss of the normal force turns into a lift-off, and x leaps by tens
 * of centimetres. So the search goes branch by branch: a dense scan (every
 * core, one workspace per thread), every suspicious step bisected until the
 * discontinuity's edge is pinned down, and then GSL's Brent solver only on
 * brackets inside one continuous branch. Each root is verified by running
 * it again; an edge is never a solution. Targets between the two sides of a
 * discontinuity are gaps, reported as such. */
#ifndef JUMPCYL_DESIGN_H
#define JUMPCYL_DESIGN_H

#include "batch.h"

/* The options design can free: the setup options of the same names. */
#define CLI_DESIGN_FREE_NAMES "rod-offset, rod-mass, theta0, incline, radius"
#define CLI_DESIGN_POINTS_DEFAULT 1000L
#define CLI_DESIGN_POINTS_MIN 10L
#define CLI_DESIGN_POINTS_MAX 200000L
/* A solution re-simulated lands within this of X (the brief of issue 16). */
#define CLI_DESIGN_VERIFY_M 1e-6
/* Roots are polished until |x - X| is below this: a margin under the check. */
#define CLI_DESIGN_ROOT_M 1e-8
/* Neighbours whose lift-offs differ by more than this, once bisected to the
 * edge width, straddle a discontinuity; below it the difference is of no
 * consequence for a 1e-6 m target. */
#define CLI_DESIGN_JUMP_M 1e-6

/* One evaluated value of the free option. */
typedef struct {
    double p;          /* the value, SI (rad for angles) */
    cli_CaseKind kind; /* CASE_LIFTOFF whenever it lifts off on the ramp (even after sliding from the start) */
    double x_m;        /* the first lift-off, NaN unless CASE_LIFTOFF */
} cli_DesignPoint;

/* A discontinuity: the outcome changes kind, or x leaps, between lo and hi,
 * which lie within the edge width of each other. */
typedef struct {
    cli_DesignPoint lo, hi;
} cli_DesignEdge;

/* A continuous piece of x(p) (or a piece with one outcome and no lift-off). */
typedef struct {
    double p_lo, p_hi;  /* its extent: edges' sides, or the range's ends */
    cli_CaseKind kind;
    double x_min_m, x_max_m; /* the first lift-offs it reaches (CASE_LIFTOFF), from its points */
} cli_DesignBranch;

typedef struct {
    double p;           /* SI */
    double x_m;         /* the verified first lift-off */
    double dxdp;        /* dX/dp, m per SI unit of p (a central difference inside the branch) */
    double edge_margin; /* distance to the nearest discontinuity, SI (INFINITY: none in the range) */
    int branch;
} cli_DesignSolution;

typedef struct {
    jc_Setup base;               /* before the single-valued options */
    jc_Setup nominal;            /* the whole setup, the free option at its preset's value (for the report) */
    cli_SetupValues values;      /* the command line's single setup values (the free one absent) */
    cli_Param param;             /* the free parameter (id: what cli_case_setup needs) */
    jc_SimOptions sim;
    double target_m;             /* X */
    double lo, hi;               /* the range, SI, lo < hi */
    long points;                 /* scan points, >= 2 */
    int threads;                 /* 0: every core */
} cli_DesignJob;

typedef struct {
    cli_DesignPoint *scan;        /* points of the scan, in p order */
    long scan_count;
    cli_DesignEdge *edges;        /* in p order */
    int edge_count;
    cli_DesignBranch *branches;   /* in p order, edge_count + 1 of them */
    int branch_count;
    cli_DesignSolution *solutions; /* in p order */
    int solution_count;
    int unverified;               /* roots that did not pass the re-run (none expected; said, not listed) */
    int at_edge;                  /* roots at a discontinuity's edge: X is a side's limit there (said, not listed) */
    double edge_width;            /* p_hi - p_lo of every located edge, at most */
    long evaluations;             /* runs of the model, all told */
    int threads_used;
    double seconds;
} cli_DesignResult;

/* ---- scan.c: the runs, the scan, the edges and branches ---- */

/* x at p: one run of the full model on the job's setup with p as the free
 * parameter's value (through cli_case_setup, so exactly `jumpcyl simulate`). */
void cli_design_eval(const cli_DesignJob *job, double p, jc_Workspace *ws, cli_DesignPoint *out);
/* The calling thread's number in the parallel loops: the index of its workspace. */
int cli_design_thread_index(void);
/* The scan, the edges and the branches into r (ws: one workspace per
 * thread). 0, or -1 when memory ran out; a stop signal cuts it short. */
int cli_design_scan(const cli_DesignJob *job, cli_DesignResult *r, jc_Workspace **ws);
void cli_design_free(cli_DesignResult *r);

/* ---- run.c: the whole search ---- */

/* The scan, the edges and the branches (scan.c); then the solutions
 * (solve.c). EXIT_OK, EXIT_FAIL after a message (out of memory), or the
 * stop status. */
int cli_design_run(const cli_DesignJob *job, cli_DesignResult *r);

/* ---- solve.c: roots within branches ---- */

/* Brackets of x - X inside each lift-off branch (turning points near X
 * refined), Brent's method on each, every root verified by a fresh run,
 * sensitivities. EXIT_OK, or EXIT_FAIL after a message. */
int cli_design_solve(const cli_DesignJob *job, cli_DesignResult *r, jc_Workspace **ws);
/* The union of the branches' lift-off ranges, merged and sorted: at most
 * cap intervals [lo[i], hi[i]]; the count. */
int cli_design_reachable(const cli_DesignResult *r, double *lo, double *hi, int cap);

/* ---- report.c: what the command prints and writes ---- */

/* How the free option is shown: its display unit and the factor from SI. */
typedef struct {
    const char *unit;     /* "cm", "g", "deg" */
    double per_si;
    const char *dx_unit;  /* the sensitivity's: "cm per mm", "cm per g", "cm per deg" */
    double dx_per_si;     /* dX/dp in m per SI unit times this */
} cli_DesignUnits;
cli_DesignUnits cli_design_units(const cli_DesignJob *job);
void cli_design_print(const cli_DesignJob *job, const cli_DesignResult *r, const char *range_note);
/* --json FILE, --csv FILE: EXIT_OK or EXIT_FAIL after a message; the file is
 * written whole or not at all. */
int cli_design_write_json(const cli_DesignJob *job, const cli_DesignResult *r, const char *path);
int cli_design_write_csv(const cli_DesignJob *job, const cli_DesignResult *r, const char *path);

/* ---- figure.c: x(p) with X and the solutions (gnuplot, figures.h) ---- */
int cli_design_figure(const cli_DesignJob *job, const cli_DesignResult *r, const char *path, const char *cmdline);

/* ---- commands/design.c ---- */
int cmd_design(int argc, char **argv);

#endif
