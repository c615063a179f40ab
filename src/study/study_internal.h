/* What the files of src/study share (not installed): the studies of
 * <jumpcyl/study.h>. Numbers written without printf (number.c); a case run
 * and its CSV fields (outcome.c); a study's cases, columns and rows
 * (case.c); the run on OpenMP threads (run.c); the default spreads
 * (defaults.c); statistics and the tally (stats.c), a one-pass summary
 * in bounded memory (sketch.c); the design search:
 * its runs, scan, edges and branches (design_scan.c), its roots
 * (design_solve.c), the whole (design.c), the free parameter and its
 * default range (design_range.c); thread counts and the wall clock
 * (threads.c).
 *
 * Calls run one way, no file calling back into one that calls it:
 *   run.c -> case.c, outcome.c, threads.c;
 *   case.c -> outcome.c, threads.c, ../random.c, ../param_values.c;
 *   outcome.c -> number.c; stats.c -> sketch.c; defaults.c and sketch.c call
 *   no file of these;
 *   design.c -> design_scan.c, design_solve.c, threads.c;
 *   design_solve.c -> design_scan.c -> outcome.c, threads.c, ../param_values.c;
 *   design_range.c -> ../param_values.c. */
#ifndef JUMPCYL_STUDY_INTERNAL_H
#define JUMPCYL_STUDY_INTERNAL_H

#include "../internal.h" /* jc_fail */
#include "jumpcyl/study.h"

#include <stdio.h>

#define JC_STUDY_PI 3.14159265358979323846

/* OpenMP's pragmas only where it is there (the web build has none): no
 * unknown-pragma warnings. */
#ifdef _OPENMP
#define JC_OMP(directive) _Pragma(directive)
#else
#define JC_OMP(directive)
#endif

/* ---- number.c ---- */

#define JC_NUMBER_MAX 32
/* printf("%.*g", precision, v), the same bytes, without printf (exact
 * digits in integers); out holds JC_NUMBER_MAX chars. Returns the length. */
int jc_format_g(double v, int precision, char *out);

/* ---- outcome.c: text appended to a row in bounds, without printf ---- */

typedef struct {
    char *buf;
    size_t len; /* room, the '\0' included */
    size_t used;
} jc_RowText;

void jc_row_text(jc_RowText *t, const char *s);
void jc_row_number(jc_RowText *t, double v, int precision); /* "%.*g" */
void jc_row_long(jc_RowText *t, long v);                    /* "%ld" */

/* ---- sketch.c: one outcome summarised in one pass, its values not kept ---- */

typedef struct jc_Sketch jc_Sketch;
/* NULL without memory; gap_m > 0 is the regions' gap. */
jc_Sketch *jc_sketch_alloc(double gap_m);
void jc_sketch_add(jc_Sketch *s, double x);
/* As jc_stats_compute would, but the quantiles estimated (estimated = 1). */
void jc_sketch_stats(jc_Sketch *s, long none, long invalid, jc_Stats *out);
void jc_sketch_free(jc_Sketch *s);

/* ---- threads.c ---- */

/* threads > 0, or OpenMP's default (1 without OpenMP). */
int jc_thread_count(int threads);
/* The calling thread's number in a parallel loop (0 without OpenMP). */
int jc_thread_index(void);
/* Seconds of a wall clock, for durations. */
double jc_wall_s(void);

/* ---- design_scan.c ---- */

/* x at p: one run of def's setup with p as the free value. */
void jc_design_eval(const jc_DesignDef *def, double p, jc_Workspace *ws, jc_DesignPoint *out);
/* Whether the search should stop: def's progress callback, on the calling
 * thread, told which stage (the scan's counts in done and total). */
int jc_design_report(const jc_DesignDef *def, const char *stage, long done, long total);
/* The scan, the edges and the branches into r (ws: one workspace per
 * thread). JC_OK, JC_ENOMEM, or JC_ESTOPPED. */
int jc_design_scan(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws);

/* ---- design_solve.c ---- */

/* Brackets of x - X inside each lift-off branch (turning points near X
 * refined), Brent's method on each, every root verified by a fresh run,
 * sensitivities. JC_OK or JC_ENOMEM. */
int jc_design_solve(const jc_DesignDef *def, jc_DesignResult *r, jc_Workspace **ws);

#endif
