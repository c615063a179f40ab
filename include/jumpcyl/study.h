/*
 * jumpcyl studies: many runs of the full model on typed inputs (parameter
 * ids and SI values, never text). Grids (sweeps, regime maps) and Monte
 * Carlo samples of uncertain inputs, each case one run kept as its summary;
 * the summary statistics of a Monte Carlo; and the design search, the
 * values of one parameter for which the first lift-off happens at a chosen
 * place (branch by branch, with its leaps and gaps). docs/api.md,
 * "Studies"; the tool's sweep, mc, map and design are thin clients of it.
 *
 * The conventions of <jumpcyl/jumpcyl.h> hold: SI units and radians, int
 * statuses with a message in the caller's buffer, no global state, nothing
 * printed. Cases are computed on OpenMP threads; rows, progress and
 * stopping go through the caller's callbacks, called on the calling thread.
 */
#ifndef JUMPCYL_STUDY_H
#define JUMPCYL_STUDY_H

#include <jumpcyl/jumpcyl.h>

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Random numbers (src/random.c)                                             */
/* ------------------------------------------------------------------------ */

/* Random123's Philox4x32-10 keyed by the seed, with (sample, draw) as the
 * counter: the number is a pure function of its three arguments, whatever
 * the thread, process or order. A uniform strictly inside (0, 1) (53 bits),
 * and a standard normal (Box-Muller on one block). The Monte Carlo's draws,
 * the fit's start points and the synthetic videos' noise are these. */
JC_API double jc_random_uniform(uint64_t seed, uint64_t sample, uint32_t draw);
JC_API double jc_random_normal(uint64_t seed, uint64_t sample, uint32_t draw);

/* ------------------------------------------------------------------------ */
/* One case: a run kept as its summary (src/study/outcome.c)                 */
/* ------------------------------------------------------------------------ */

typedef enum {
    JC_CASE_LIFTOFF,         /* lifts off on the ramp */
    JC_CASE_NO_LIFTOFF,      /* reaches the ramp's end, its top, rest or a limit without a lift-off */
    JC_CASE_SLIDES_AT_START, /* cannot roll: it slips at the very start (it may still lift off later) */
    JC_CASE_INVALID,         /* the values make no valid setup */
    JC_CASE_FAILED           /* the run failed numerically */
} jc_CaseKind;

/* A slip within this distance of the start means the body never rolled. */
#define JC_CASE_SLIDES_AT_START_M 1e-9

typedef struct {
    jc_CaseKind kind;
    double liftoff_x_m;     /* the first lift-off's x, NaN if none (also after sliding from the start) */
    double largest_hop_m;   /* the highest flight's gap under the rim, 0 if none */
    /* The run (zero, and jc_summary_init's -1 indices, for an invalid or failed case): */
    jc_RunSummary summary;  /* first event, first slip and lift-off states, lift-offs, bounces, largest hop */
    jc_Termination termination;
    jc_State end;           /* the final state */
    double energy_balance_error_J;
} jc_CaseOutcome;

/* Runs setup from its start (jc_start_state) with sim, keeping only the
 * summary; ws: a workspace (jc_Workspace, one per thread) or NULL. setup
 * NULL or not a valid setup: JC_CASE_INVALID. The run allocates nothing
 * with a workspace. */
JC_API void jc_case_run(const jc_Setup *setup, const jc_SimOptions *sim, jc_Workspace *ws, jc_CaseOutcome *out);
/* "liftoff", "no_liftoff", "slides_at_start", "invalid_setup", "failed". */
JC_API const char *jc_case_kind_name(jc_CaseKind kind);

/* The outcome's CSV columns: name (with its unit as a suffix), unit ("" for
 * names and counts) and a line of help. */
typedef struct {
    const char *name; /* "first_liftoff_x_m" */
    const char *unit; /* "m" */
    const char *help;
} jc_CaseColumn;
#define JC_CASE_COLUMNS 14
JC_API int jc_case_column_count(void);
/* Column i, NULL out of range. */
JC_API const jc_CaseColumn *jc_case_column(int i);
/* The outcome's fields, comma-separated, in the columns' order (no leading
 * comma, no newline): names as jc_event_name and jc_termination_name give
 * them, numbers as printf's "%.12g" writes them ("%.3g" for the energy
 * balance), empty fields for what a case does not have; an invalid or failed
 * case has only its termination, "invalid_setup" or "failed". Returns the
 * length written (cut to fit len, terminated). */
JC_API int jc_case_format(const jc_CaseOutcome *o, char *buf, size_t len);

/* ------------------------------------------------------------------------ */
/* Setups from parameter values (src/param_values.c)                         */
/* ------------------------------------------------------------------------ */

/* Values by parameter id (jc_param_find), set together over a base setup. */
typedef struct {
    unsigned char given[JC_PARAM_MAX]; /* 1: value[id] is set */
    double value[JC_PARAM_MAX];        /* SI; a name's index (jc_param_set) */
    /* The base's body was given part by part, not as a preset's: radius then
     * moves only the rim (the parts keep the radii given), and the paper's
     * printed d no longer applies. */
    int parts_given;
} jc_ParamValues;

/* Sets the given values over s in the table's order, the body's first (so
 * that a disc+rod body's parameters act on the rim given with them), drops
 * the paper's printed d when the body changed, then checks the whole setup
 * (jc_setup_validate). A shortcut and a row it sets may both be given (mu
 * and mu-s): the table's order decides. JC_OK, or JC_EINVAL with the
 * message of jc_param_set (*failed_id: the parameter) or of
 * jc_setup_validate (*failed_id: -1); failed_id may be NULL. */
JC_API int jc_param_values_apply(const jc_ParamValues *v, jc_Setup *s, int *failed_id, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* Studies: grids and Monte Carlo samples (src/study/)                       */
/* ------------------------------------------------------------------------ */

#define JC_STUDY_PARAM_MAX 16      /* parameters a study varies or samples */
#define JC_STUDY_VALUES_MAX 1000000L /* values of one parameter of a grid */
#define JC_STUDY_ROW_MAX 1536      /* a case's CSV row, '\n' and '\0' included */
/* A Monte Carlo sample whose draws make no valid setup (a normal reaching a
 * negative mass) is drawn again, up to this many times: a truncation of the
 * spreads to valid setups. */
#define JC_STUDY_MC_ATTEMPTS 64

typedef enum {
    JC_STUDY_VALUES,  /* a list of values (a grid's axis) */
    JC_STUDY_NORMAL,  /* a normal spread: a the mean, b the standard deviation (0: a fixed value) */
    JC_STUDY_UNIFORM  /* a uniform spread over [a, b] */
} jc_StudySpread;

typedef struct {
    int id;                /* the parameter (jc_param_find) */
    jc_StudySpread spread;
    const double *values;  /* JC_STUDY_VALUES: count values, SI (a name's index); the caller's memory */
    long count;
    double a, b;           /* JC_STUDY_NORMAL, JC_STUDY_UNIFORM: SI */
} jc_StudyParam;

typedef enum {
    JC_STUDY_GRID,       /* every combination of the parameters' values, the last varying fastest */
    JC_STUDY_MONTE_CARLO /* samples: each parameter drawn from its spread */
} jc_StudyKind;

typedef struct {
    jc_StudyKind kind;
    jc_Setup base;          /* the setup the values are set over */
    jc_ParamValues fixed;   /* values set on every case, with the case's (jc_param_values_apply) */
    jc_StudyParam params[JC_STUDY_PARAM_MAX];
    int param_count;        /* 0 .. JC_STUDY_PARAM_MAX (a grid: at least 1) */
    long samples;           /* JC_STUDY_MONTE_CARLO: how many */
    uint64_t seed;          /* JC_STUDY_MONTE_CARLO: the draws' key */
    jc_SimOptions sim;      /* every case's (sample_dt is not used) */
    int threads;            /* OpenMP threads; 0: OpenMP's default */
} jc_StudyDef;

/* JC_OK, or JC_EINVAL with a message: parameter ids unknown or repeated, a
 * spread of the other kind, a list empty or longer than
 * JC_STUDY_VALUES_MAX, values not finite, a spread not ordered (sigma < 0,
 * hi < lo) or of a name, negative samples or threads, a grid of more cases
 * than a long holds. */
JC_API int jc_study_check(const jc_StudyDef *def, char *err, size_t err_len);
/* Cases: the product of the lists' lengths (a grid), or samples. */
JC_API long jc_study_case_count(const jc_StudyDef *def);
/* The threads a run of the study uses: def->threads, or OpenMP's default
 * (1 without OpenMP). */
JC_API int jc_study_threads(const jc_StudyDef *def);
/* Case index's values (param_count of them, SI) and setup: a grid's index
 * taken apart (the last parameter fastest); a sample's values drawn with
 * jc_random_normal or jc_random_uniform keyed by (seed, index, draw), draw
 * = attempt * JC_STUDY_PARAM_MAX + j for parameter j, attempts 0, 1, ...
 * until the setup is valid (JC_STUDY_MC_ATTEMPTS at most): sample i is the
 * same for any thread count, range, shard or process. JC_OK; JC_EINVAL with
 * why (the values, the last attempt's, still written) when they make no
 * valid setup or index is out of range. def: one jc_study_check accepts. */
JC_API int jc_study_case(const jc_StudyDef *def, long index, double *values, jc_Setup *setup, char *why,
                         size_t why_len);

/* A parameter's CSV column: name_unit ("incline_deg", "rod_offset_m",
 * "g_mps2", "impact_law"); values in SI, angles in degrees. */
typedef struct {
    char name[48];
    char unit[16];  /* "deg", "m", "mps2"; "" for numbers and names */
    double per_si;  /* the column's value is the SI value times this */
} jc_StudyColumn;
JC_API int jc_study_column(int id, jc_StudyColumn *out);
/* The rows' header, "case,<the parameters' columns>,<the outcome's>\n"
 * (terminated, cut to fit len); returns its length. */
JC_API int jc_study_header(const jc_StudyDef *def, char *buf, size_t len);
/* A case's row: "index,<values>,<jc_case_format>\n", each value as its
 * column holds it ("%.12g", or the name); o NULL: "index,<values>" alone.
 * Returns the length (cut to fit len, terminated). */
JC_API int jc_study_row_format(const jc_StudyDef *def, long index, const double *values, const jc_CaseOutcome *o,
                               char *buf, size_t len);

/* One computed case, as the row callback receives it. */
typedef struct {
    long index;
    const double *values;            /* param_count values, SI */
    const jc_CaseOutcome *outcome;
    const char *csv;                 /* jc_study_row_format's row when jc_StudyCallbacks.csv, else NULL */
    int csv_len;
} jc_StudyRow;

typedef struct {
    /* Every case of the range in index order; nonzero stops the run. */
    int (*row)(void *ctx, const jc_StudyRow *row);
    /* After each block of cases (done of count); nonzero stops the run. */
    int (*progress)(void *ctx, long done, long count);
    void *ctx;
    int csv; /* 1: each case's CSV row is made too, on the threads that compute */
} jc_StudyCallbacks;

/* Cases [first, first + count) on jc_study_threads threads, in blocks of a
 * few hundred per thread; after each block its rows go to cb->row in index
 * order and then cb->progress is called, both on the calling thread (cb or
 * its members may be NULL). A callback's nonzero stops the run: no later
 * row is delivered and no later block computed. JC_OK when every case of
 * the range was delivered (a stop asked after the last one changes
 * nothing); JC_ESTOPPED when a callback stopped it before; JC_EINVAL (the
 * study, or a range outside 0 .. jc_study_case_count), JC_ENOMEM; each
 * but JC_OK with a message. */
JC_API int jc_study_run(const jc_StudyDef *def, long first, long count, const jc_StudyCallbacks *cb, char *err,
                        size_t err_len);

/* The paper's stated tolerances as spreads about a setup (docs/physics.md
 * §5.1): radius, masses and the rod's offset to the last digit printed
 * (normal, sigma 0.05 cm or 0.05 g), theta0 about 3 deg (normal), and the
 * friction and restitution it did not measure, uniform over what foam on
 * wood allows (mu 0.3 .. 1.0, restitution 0.1 .. 0.6). Each one the
 * setup's body has (a hoop has no rod), in that order, into out with a few
 * words of where it comes from in why (either may be NULL); at most cap.
 * Returns how many there are. */
JC_API int jc_study_default_spreads(const jc_Setup *nominal, jc_StudyParam *out, const char **why, int cap);

/* ------------------------------------------------------------------------ */
/* Summary statistics (src/study/stats.c)                                    */
/* ------------------------------------------------------------------------ */

typedef struct {
    double lo_m, hi_m; /* the extent of the values in it */
    long count;
    double mean_m;
} jc_StatsRegion;

#define JC_STATS_REGION_MAX 16

typedef struct {
    long n;           /* values */
    long none;        /* cases without a value (no lift-off), as given */
    long invalid;     /* invalid or failed cases, as given */
    double mean, sd;  /* NaN without values; sd 0 for one */
    double p2_5, p50, p97_5;
    int region_count; /* separate clusters: sorted neighbours further apart than the gap start a new one */
    jc_StatsRegion regions[JC_STATS_REGION_MAX];
    int regions_truncated;
    /* 0: from every value, sorted (jc_stats_compute). 1: from a tally past
     * its keep_max, the values seen once and not kept (jc_tally_stats):
     * the quantiles are P² estimates (GSL's gsl_rstat_quantile; docs/cli.md
     * "Memory" states their accuracy), mean and sd exact but for rounding,
     * the regions exact but for rounding in their means. */
    int estimated;
    int regions_unavailable; /* 1: estimated over more than JC_SKETCH_CELL_MAX cells of the gap: no regions */
} jc_Stats;

/* Sorts v[0 .. n) in place and summarises it: mean and sd (Welford), the
 * 2.5, 50 and 97.5 % quantiles (jc_quantile), the regions separated by
 * gaps wider than gap_m. */
JC_API void jc_stats_compute(double *v, long n, long none, long invalid, double gap_m, jc_Stats *out);
/* The p-quantile of sorted values, linear between order statistics (NaN for n = 0). */
JC_API double jc_quantile(const double *sorted, long n, double p);

/* A Monte Carlo's outcomes gathered case by case (the rows of jc_study_run,
 * or rows read back from a file: only kind, liftoff_x_m and largest_hop_m
 * are read), in the order given. Up to keep_max valid cases their values
 * are kept (16 bytes a case); past it they are summarised as they come in
 * bounded memory and not kept (the arrays NULL, sketch set): the kept ones
 * first, in their order, then each new one. The same cases in the same
 * order give the same summary, however they were computed. */
typedef struct jc_TallySketch jc_TallySketch;
typedef struct {
    double *liftoff_x_m; /* the first lift-offs of the valid cases (NULL past keep_max) */
    long liftoffs;
    double *hop_m;       /* the largest hops of the valid cases, 0 without a hop (NULL past keep_max) */
    long valid;          /* neither invalid nor failed */
    long none;           /* valid without a lift-off */
    long slides;         /* JC_CASE_SLIDES_AT_START */
    long invalid;        /* invalid or failed */
    long cap;
    long keep_max;                  /* the most valid cases whose values are kept */
    double liftoff_gap_m, hop_gap_m; /* the regions' gaps of jc_tally_stats */
    jc_TallySketch *sketch;         /* past keep_max: the one-pass summaries, else NULL */
} jc_Tally;

/* Room for expected cases (it grows past them); every value kept, the
 * regions' gaps JC_MC_LIFTOFF_GAP_M and JC_MC_HOP_GAP_M. JC_OK or JC_ENOMEM. */
JC_API int jc_tally_init(jc_Tally *t, long expected);
/* The same, the values kept for at most keep_max (>= 1) valid cases, the
 * regions' gaps given (> 0). Expecting more than keep_max, it keeps none.
 * JC_OK, JC_ENOMEM, or JC_EINVAL. */
JC_API int jc_tally_init_bounded(jc_Tally *t, long expected, long keep_max, double liftoff_gap_m, double hop_gap_m);
/* JC_OK, or JC_ENOMEM (the case not counted). */
JC_API int jc_tally_add(jc_Tally *t, const jc_CaseOutcome *o);
/* The first lift-offs' and the largest hops' summaries (either may be
 * NULL) with the tally's gaps: jc_stats_compute on the kept values (which
 * it sorts), or past keep_max the one-pass ones (estimated = 1). */
JC_API void jc_tally_stats(jc_Tally *t, jc_Stats *liftoff, jc_Stats *hop);
JC_API void jc_tally_free(jc_Tally *t);
/* Past keep_max, the regions are found in cells one gap wide; spread over
 * more cells than this (a ramp more than 65536 gaps long), they are not. */
#define JC_SKETCH_CELL_MAX 65536L
/* Region gaps of `jumpcyl mc`: first lift-offs, largest hops. */
#define JC_MC_LIFTOFF_GAP_M 0.02
#define JC_MC_HOP_GAP_M 0.005

/* ------------------------------------------------------------------------ */
/* Design: the values of one parameter that put the first lift-off at X      */
/* (src/study/design.c, design_scan.c, design_solve.c, design_range.c)       */
/* ------------------------------------------------------------------------ */

/* The first lift-off x(p) is a discontinuous function of most parameters:
 * a near-miss of the normal force turns into a lift-off, and x leaps. So
 * the search goes branch by branch: a dense scan, every suspicious step
 * bisected until the discontinuity's edge is pinned down, and Brent's
 * method only on brackets inside one continuous branch. Each root is run
 * again; an edge is never a solution; targets between the two sides of a
 * leap are gaps. */
#define JC_DESIGN_POINTS_MIN 10L
#define JC_DESIGN_POINTS_MAX 200000L
/* A solution run again lands within this of X. */
#define JC_DESIGN_VERIFY_M 1e-6
/* Roots are polished until |x - X| is below this: a margin under the check. */
#define JC_DESIGN_ROOT_M 1e-8
/* Neighbours whose lift-offs differ by more than this, once bisected to the
 * edge width, straddle a discontinuity. */
#define JC_DESIGN_JUMP_M 1e-6

typedef struct {
    const char *stage; /* "scan" (the only one with a count), "edges", "roots" */
    long done, total;  /* scan points done of total; 0, 0 for the others */
} jc_DesignProgress;

typedef struct {
    jc_Setup base;        /* the setup the values are set over */
    jc_ParamValues fixed; /* set on every run, with the free parameter's value */
    int free_id;          /* the parameter chosen: a numeric one (jc_param_find) */
    double lo, hi;        /* its range, SI, lo < hi; both ends valid setups */
    double target_x_m;    /* X, the wanted first lift-off (> 0) */
    long points;          /* scan points, JC_DESIGN_POINTS_MIN .. MAX */
    int threads;          /* OpenMP threads; 0: OpenMP's default */
    jc_SimOptions sim;
    /* Called on the calling thread after each block of the scan and as each
     * later stage begins; nonzero stops the search (JC_ESTOPPED). May be NULL. */
    int (*progress)(void *ctx, const jc_DesignProgress *p);
    void *progress_ctx;
} jc_DesignDef;

/* One evaluated value of the free parameter. */
typedef struct {
    double p;         /* the value, SI */
    jc_CaseKind kind; /* JC_CASE_LIFTOFF whenever it lifts off on the ramp (even after sliding from the start) */
    double x_m;       /* the first lift-off, NaN unless JC_CASE_LIFTOFF */
} jc_DesignPoint;

/* A discontinuity: the outcome changes kind, or x leaps, between lo and hi,
 * which lie within the edge width of each other. */
typedef struct {
    jc_DesignPoint lo, hi;
} jc_DesignEdge;

/* A continuous piece of x(p), or a piece with one outcome and no lift-off. */
typedef struct {
    double p_lo, p_hi;       /* its extent: edges' sides, or the range's ends */
    jc_CaseKind kind;
    double x_min_m, x_max_m; /* the first lift-offs it reaches (JC_CASE_LIFTOFF), from its points */
} jc_DesignBranch;

typedef struct {
    double p;           /* SI */
    double x_m;         /* the verified first lift-off */
    double dxdp;        /* dX/dp, m per SI unit of p (a central difference inside the branch) */
    double edge_margin; /* distance to the nearest discontinuity, SI (INFINITY: none in the range) */
    int branch;
} jc_DesignSolution;

typedef struct {
    jc_DesignPoint *scan;          /* the scan's points, in p order */
    long scan_count;
    jc_DesignEdge *edges;          /* in p order */
    int edge_count;
    jc_DesignBranch *branches;     /* in p order, edge_count + 1 of them */
    int branch_count;
    jc_DesignSolution *solutions;  /* in p order */
    int solution_count;
    int unverified;                /* roots that did not pass the run again (none expected; counted, not listed) */
    int at_edge;                   /* roots at a discontinuity's edge: X is a side's limit there (counted, not listed) */
    double edge_width;             /* p_hi - p_lo of every located edge, at most */
    long evaluations;              /* runs of the model, all told */
    int threads_used;
    double seconds;                /* the search's wall time */
} jc_DesignResult;

/* The search: scan, edges, branches, then the roots with their
 * sensitivities. Every run is jc_case_run of def's setup with the free
 * value set (jc_param_values_apply). JC_OK (with or without solutions);
 * JC_EINVAL (def), JC_ENOMEM, JC_ESTOPPED (the progress callback asked),
 * with a message. Free the result with jc_design_free in every case. */
JC_API int jc_design_run(const jc_DesignDef *def, jc_DesignResult *out, char *err, size_t err_len);
JC_API void jc_design_free(jc_DesignResult *r);
/* The union of the lift-off branches' ranges, merged and sorted: at most cap
 * intervals [lo[k], hi[k]]; returns their count. Ranges less than
 * JC_DESIGN_JUMP_M apart are merged (the two ends of a whole turn of theta0
 * are one setup, computed from -pi and pi). */
JC_API int jc_design_reachable(const jc_DesignResult *r, double *lo, double *hi, int cap);

/* The free parameter (src/study/design_range.c). Design frees every numeric
 * row of the parameter table but those that never move the first lift-off
 * (restitution, ramp-length, paper-d): JC_OK, or JC_EINVAL with
 * "NAME: why" (no such id, a row of names, one of those three). With fixed
 * (base may be NULL), radius over a body given part by part is refused
 * too (it moves only the rim there), and so is a value given for the free
 * row or for a row that sets it or that it sets (mu for mu-s): the search
 * would replace it. With base: the setup of base and fixed
 * without the free value must be valid and have the part the row sets
 * (else jc_param_get's message: rod-offset of a hoop). */
JC_API int jc_design_free_check(int free_id, const jc_Setup *base, const jc_ParamValues *fixed, char *err,
                                size_t err_len);
/* The rule of a default range that is the row's typical span: *rule starts
 * with these words. */
#define JC_DESIGN_RANGE_TYPICAL "its typical span"
/* The default range of def->free_id over def->base and def->fixed (without
 * the free value) into def->lo, def->hi: for rod-offset 1 % of r to the rim
 * less the rod's radius, rod-mass 1 % to 5 times the rest of the body's
 * mass, theta0 a whole turn, incline 1 to 85 deg, radius just outside the
 * parts that do not fill the rim to 3 r; for every other row its typical
 * span (jc_ParamInfo typical_min .. typical_max) within its range, an end
 * that is no valid setup with the other values moved in by bisection
 * towards the nominal value, to 1e-9 of the span. *rule (rule may be NULL):
 * those words, constant text ("1 to 85 deg"; JC_DESIGN_RANGE_TYPICAL, with
 * ", cut to valid setups" when an end moved). JC_OK, or JC_EINVAL with a
 * message: jc_design_free_check's, or "NAME: no default range around its
 * value" (no valid value but the nominal one). */
JC_API int jc_design_default_range(jc_DesignDef *def, const char **rule, char *err, size_t err_len);

#ifdef __cplusplus
}
#endif

#endif
