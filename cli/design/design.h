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

/* ---- free.c: the parameter --free NAME chooses ---- */

/* The names of the rows design can free (refused: of those it cannot,
 * jc_design_free_check), in the table's order, ", " between them, cut to
 * fit len. */
void cli_design_free_names(int refused, char *buf, size_t len);
/* --free NAME against the setup options given (not the free one itself, nor
 * one that sets what it sets): its id, column and unit into p. EXIT_OK, or
 * EXIT_USAGE after a message. */
int cli_design_free_param(const char *name, const cli_SetupArgs *sa, cli_Param *p);
/* The library's default range (jc_design_default_range) into job->lo, hi,
 * over job->base and job->values; note says which ("the default: ...").
 * EXIT_OK, or EXIT_USAGE after a message (a body without the part the row
 * sets). */
int cli_design_default_range(cli_DesignJob *job, char *note, size_t note_len);

/* ---- run.c: the library's search ---- */

/* The search (jc_design_run) with a progress line on a terminal, stopped
 * by a signal. EXIT_OK, EXIT_FAIL after a message, or the stop status; r
 * is to be freed with jc_design_free in every case. */
int cli_design_run(const cli_DesignJob *job, jc_DesignResult *r);

/* ---- report.c: what the command prints and writes ---- */

/* How the free option is shown: its display unit and the factor from SI.
 * Lengths in cm, masses in g, angles in degrees, numbers bare, the other
 * quantities in SI. */
typedef struct {
    char unit[16];        /* after a value: " cm", " g", " deg", " m/s2"; "" for numbers */
    char paren[20];       /* after a name in a heading: " (cm)"; "" for numbers */
    double per_si;
    char dx_unit[32];     /* the sensitivity's: "cm per mm", "cm per g", "cm per deg", "cm per 0.01" */
    double dx_per_si;     /* dX/dp in m per SI unit times this */
} cli_DesignUnits;
cli_DesignUnits cli_design_units(const cli_DesignJob *job);
void cli_design_print(const cli_DesignJob *job, const jc_DesignResult *r, const char *range_note);
/* --json FILE, --csv FILE: EXIT_OK or EXIT_FAIL after a message; the file is
 * written whole or not at all ("-": standard output). */
int cli_design_write_json(const cli_DesignJob *job, const jc_DesignResult *r, const char *path);
int cli_design_write_csv(const cli_DesignJob *job, const jc_DesignResult *r, const char *path);

/* ---- figure.c: x(p) with X and the solutions (gnuplot, figures.h) ---- */
int cli_design_figure(const cli_DesignJob *job, const jc_DesignResult *r, const char *path, const char *cmdline);

#endif
