/* `jumpcyl plot`: the pieces of a figure. Each kind of figure is a gnuplot
 * "panel" drawn from data files that the C side computes with the library;
 * the overview puts the four panels on one page. */
#ifndef JUMPCYL_PLOT_H
#define JUMPCYL_PLOT_H

#include "figures.h"

typedef enum { FIG_PNG, FIG_SVG, FIG_PDF } fig_Format;

/* Everything the panels need: the model, the computed numbers, and where
 * the data files live. Filled by the *_prepare functions. */
typedef struct {
    const jc_Model *model;
    char dir[CLI_PATH_MAX];  /* data files and script */
    char stem[256];          /* data files are <stem>-<what>.dat */
    char caption[256];       /* the setup in one line (enhanced text); "" in the overview,
                                whose page title carries it */

    /* paper-criterion (plot_criterion.c) */
    jc_PaperResult paper;
    jc_RollingResult rolling;
    double printed_theta_rad; /* NaN when the setup is not in the paper's table */
    double printed_x_m;
    double theta_max_rad, crit_ymax;

    /* forces, path, energy (plot_run.c) */
    jc_Run run;
    int have_run;
    double sample_dt_s;
    double x_min_cm, x_max_cm, t_max_s;
    int time_axis;             /* forces and path against time (the body went back and forth) */
    double axis_min, axis_max; /* their horizontal range: cm, or s */
    double n_min, n_max;       /* N / (M g cos a) */
    double ratio_max;          /* |F| / N */
    double gap_max_mm, speed_max_mps;
    double energy_min_J, energy_max_J;
    double resistance_loss_max_J; /* air and rolling resistance; 0 when switched off */
    int hop_count;
} fig_Data;

/* ---- gnuplot.c: formats, the shared style, running gnuplot ---- */

/* From the output's extension; -1 if it is not png, svg or pdf. */
int fig_format_from_path(const char *path, fig_Format *f);
/* Writes s as a gnuplot single-quoted string. */
void fig_quote(FILE *gp, const char *s);
/* dir/<stem>-<what>.dat; -1 if it does not fit. */
int fig_data_path(const fig_Data *d, const char *what, char *out, size_t len);
/* The script's head: comments, terminal for a cols x rows page of panels,
 * the colours and the style block every panel applies. */
void fig_script_begin(FILE *gp, fig_Format f, int cols, int rows, const char *default_output,
                      const char *command_line);
/* Starts a panel: forgets the previous panel's settings, applies the style. */
void fig_panel_begin(FILE *gp, const char *what);
/* Runs gnuplot on script (in dir) to render output atomically: gnuplot
 * writes a temporary file beside output, which is checked and renamed.
 * log_path collects gnuplot's messages. Returns EXIT_OK or EXIT_FAIL. */
int fig_render(const char *script, const char *dir, const char *output, fig_Format f,
               const char *log_path);
/* The incline and contact in one line, and the body in another, for titles. */
void fig_caption(const jc_Model *m, char *out, size_t len);
void fig_body_caption(const jc_Model *m, char *out, size_t len);

/* ---- plot_criterion.c: the paper's Eq. 9 and the exact N = 0 criterion ---- */
int fig_criterion_prepare(fig_Data *d);
void fig_criterion_panel(FILE *gp, const fig_Data *d);

/* ---- plot_run.c: the full model's trajectory, events and hops ---- */
/* Simulates (with options o; a fine sample_dt is chosen unless dt_given)
 * and writes the run, events and hops data files. */
int fig_run_prepare(fig_Data *d, const jc_SimOptions *o, int dt_given);
/* The readable name of an event ("lift-off", "ramp end"). */
const char *fig_event_label(jc_EventKind k);

/* ---- plot_panels.c: the three panels drawn from a run ---- */
void fig_forces_panel(FILE *gp, const fig_Data *d);
void fig_path_panel(FILE *gp, const fig_Data *d);
void fig_energy_panel(FILE *gp, const fig_Data *d);

#endif
