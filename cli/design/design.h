/* jumpcyl design: which values of one setup option make the first lift-off
 * happen at a chosen place X on the ramp (docs/design.md). The search is
 * the library's (jc_design_run, include/jumpcyl/study.h: branch by branch,
 * every discontinuity's edge located, roots only inside a continuous
 * branch, each run again; targets between the sides of a leap are gaps);
 * here the options become its definition, and its result is printed and
 * written. */
#ifndef JUMPCYL_DESIGN_H
#define JUMPCYL_DESIGN_H

#include "batch.h"

/* The options design can free: the setup options of the same names. */
#define CLI_DESIGN_FREE_NAMES "rod-offset, rod-mass, theta0, incline, radius"
#define CLI_DESIGN_POINTS_DEFAULT 1000L

typedef struct {
    jc_Setup base;               /* before the single-valued options */
    jc_Setup nominal;            /* the whole setup, the free option at its preset's value (for the report) */
    cli_SetupValues values;      /* the command line's single setup values (the free one absent) */
    cli_Param param;             /* the free parameter (id, column and unit) */
    jc_SimOptions sim;
    double target_m;             /* X */
    double lo, hi;               /* the range, SI, lo < hi */
    long points;                 /* scan points, JC_DESIGN_POINTS_MIN .. MAX */
    int threads;                 /* 0: every core */
} cli_DesignJob;

/* ---- run.c: the library's search ---- */

/* The search (jc_design_run) with a progress line on a terminal, stopped
 * by a signal. EXIT_OK, EXIT_FAIL after a message, or the stop status; r
 * is to be freed with jc_design_free in every case. */
int cli_design_run(const cli_DesignJob *job, jc_DesignResult *r);

/* ---- report.c: what the command prints and writes ---- */

/* How the free option is shown: its display unit and the factor from SI. */
typedef struct {
    const char *unit;     /* "cm", "g", "deg" */
    double per_si;
    const char *dx_unit;  /* the sensitivity's: "cm per mm", "cm per g", "cm per deg" */
    double dx_per_si;     /* dX/dp in m per SI unit times this */
} cli_DesignUnits;
cli_DesignUnits cli_design_units(const cli_DesignJob *job);
void cli_design_print(const cli_DesignJob *job, const jc_DesignResult *r, const char *range_note);
/* --json FILE, --csv FILE: EXIT_OK or EXIT_FAIL after a message; the file is
 * written whole or not at all. */
int cli_design_write_json(const cli_DesignJob *job, const jc_DesignResult *r, const char *path);
int cli_design_write_csv(const cli_DesignJob *job, const jc_DesignResult *r, const char *path);

/* ---- figure.c: x(p) with X and the solutions (gnuplot, figures.h) ---- */
int cli_design_figure(const cli_DesignJob *job, const jc_DesignResult *r, const char *path, const char *cmdline);

/* ---- commands/design.c ---- */
int cmd_design(int argc, char **argv);

#endif
