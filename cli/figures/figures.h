/* `jumpcyl plot` and the figures of the other commands (cli/figures/):
 * each kind of figure is a gnuplot "panel" drawn from data that the C side
 * computes with the library, written as data blocks into the script
 * itself; the overview puts four panels on one page (gnuplot.c: formats,
 * the shared style, running gnuplot). Also the paper's Table 1 beside a
 * setup (paper_row.c), which the films and the page mark. */
#ifndef JUMPCYL_FIGURES_H
#define JUMPCYL_FIGURES_H

#include "outputs.h"

#include <jumpcyl/jumpcyl.h>
#include <jumpcyl/study.h>
#include <jumpcyl/track.h>

#include <stddef.h>
#include <stdio.h>

/* ---- paper_row.c: the paper's Table 1 beside the model ---- */

/* The row of Table 1 for the setup: the paper's cylinder on one of the
 * table's inclines (friction, restitution and the start may differ, as the
 * paper's model has none of them); NULL for any other setup. */
const jc_PaperTableRow *cli_paper_row(const jc_Setup *s);

typedef enum { FIG_PNG, FIG_SVG, FIG_PDF } fig_Format;

/* How a run that only reached the default time limit is cut for the
 * figures: not at all; 1 s after its last landing; where its losses have
 * settled (it never lifted off); a few periods of lossless rocking. */
typedef enum { FIG_CUT_NONE, FIG_CUT_LANDING, FIG_CUT_SETTLED, FIG_CUT_PERIODIC } fig_Cut;

/* Everything the panels need: the model, the computed numbers, and the
 * script being written. Filled by the *_prepare functions, which write their
 * data as data blocks ($run << EOD ... EOD) into the script itself: the
 * script reads no file, so no name of the user's ever reaches gnuplot. */
typedef struct {
    const jc_Model *model;
    /* paper-uncertainty: the first lift-off's Monte Carlo spread at each
     * incline of the paper's table, in the table's order, computed by the
     * caller (the figure draws what it is given); how many samples and the
     * seed, for the script's comments and the title. */
    int table_rows;            /* at most FIG_TABLE_ROWS_MAX */
    const jc_Stats *site_stats; /* table_rows of them */
    int mc_samples, mc_seed;
    FILE *gp;                /* the script, in the scratch directory */
    char caption[256];       /* the setup in one line (enhanced text); "" in the overview,
                                whose page title carries it */

    /* paper-criterion (plot_criterion.c) */
    jc_PaperResult paper;
    jc_RollingResult rolling;
    double printed_theta_rad; /* NaN when the setup is not in the paper's table */
    double printed_x_m;
    double theta_max_rad, crit_ymax;
    int crit_clipped; /* crit_ymax left the kinetic side's peaks where no crossing can be out */

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
    int event_label_chars;     /* the longest line of the forces panel's event labels (characters) */

    /* The zoom on what matters: from before the first lift-off to after the
     * last flight's landing (plot_run.c). zoomed is 0 when nothing flies. */
    int zoom_wanted; /* set before fig_run_prepare: forces, gap, energy panels take the zoom (overview) */
    /* Set before fig_run_prepare: a run that only reaches the default time
     * limit (no --t-max given; a body rocking for ever) is shown to 1 s
     * after its last landing, as animate films it; one that never lifts off
     * until its losses have settled (plot_run.c). cut says which, and
     * run_end_s where the whole run ends. */
    int end_after_landing;
    fig_Cut cut;
    double run_end_s;
    int zoomed;
    int zoom_from_warning; /* the zoom starts before the first slip or near-miss of N = 0 (overview) */
    double zoom_x_lo_cm, zoom_x_hi_cm; /* centre's distance down the incline */
    double zoom_t_lo_s, zoom_t_hi_s;

    /* trajectory (plot_trajectory.c): the run's options, to sample its
     * flights again densely */
    jc_SimOptions sim;
} fig_Data;

/* ---- gnuplot.c: formats, the shared style, running gnuplot ---- */

/* From the output's extension; -1 if it is not png, svg or pdf. */
int fig_format_from_path(const char *path, fig_Format *f);
/* Writes s as a gnuplot single-quoted string (newlines become spaces). */
void fig_quote(FILE *gp, const char *s);
/* "$name << EOD" and "EOD": a data block of the script. */
void fig_block_begin(FILE *gp, const char *name);
void fig_block_end(FILE *gp);
/* The script's head: comments, terminal for a cols x rows page of panels
 * (a panel is 1200 x 750 px; a page may hold fractions of them), the
 * colours and the style block every panel applies. */
void fig_script_begin(FILE *gp, fig_Format f, double cols, double rows, const char *default_output,
                      const char *command_line);
/* Starts a panel: forgets the previous panel's settings, applies the style. */
void fig_panel_begin(FILE *gp, const char *what);
/* The names the tool gives the script, the figure and gnuplot's log in the
 * scratch directory: the only names gnuplot is ever given. */
#define FIG_SCRIPT_NAME "figure.gp"
#define FIG_LOG_NAME "gnuplot.log"
/* "figure.png", "figure.svg", "figure.pdf". */
const char *fig_scratch_name(fig_Format f);
/* How a finished figure of the format is checked (outputs.h). */
cli_Check fig_check(fig_Format f);
/* Runs gnuplot in the scratch directory work on FIG_SCRIPT_NAME, which
 * writes fig_scratch_name(f) there; checks that it is complete. cmd
 * ("plot", "map") and output, the user's name, are for messages only.
 * Returns EXIT_OK, EXIT_FAIL after a message, or cli_stop_status() after a
 * stop signal. */
int fig_render(const char *cmd, const char *work, fig_Format f, const char *output);
/* The command line (argv[0] the command's name), for a script's header:
 * shell-quoted words on one line, control characters shown as '?'. */
void fig_command_line(int argc, char **argv, char *out, size_t len);
/* The incline and contact in one line, and the body in another, for titles. */
void fig_caption(const jc_Model *m, char *out, size_t len);
void fig_body_caption(const jc_Model *m, char *out, size_t len);

/* ---- plot_criterion.c: the paper's Eq. 9 and the exact N = 0 criterion ---- */
int fig_criterion_prepare(fig_Data *d);
void fig_criterion_panel(FILE *gp, const fig_Data *d);
/* An inset on the first crossings when they are narrow (a small window or
 * low in the graph), placed in the criterion panel drawn before (after
 * every panel of a page: it does not take a place of the layout). */
void fig_criterion_inset(FILE *gp, const fig_Data *d);
/* paper-criterion on its own page: the panel and its inset. */
void fig_criterion_figure(FILE *gp, const fig_Data *d);

/* ---- plot_uncertainty.c: the paper's jump sites with the full model's band ---- */
/* Rows of the paper's table the figure shows at most. */
#define FIG_TABLE_ROWS_MAX 8
/* Writes the sites' data block: per row of the table, the printed site, the
 * nominal run's first lift-off and d->site_stats' band, the measurement. */
int fig_uncertainty_prepare(fig_Data *d);
void fig_uncertainty_panels(FILE *gp, const fig_Data *d);

/* ---- plot_run.c: the full model's trajectory, events and hops ---- */
/* Simulates (with options o; a fine sample_dt is chosen unless dt_given;
 * refused past max_samples samples, estimated by a first run that keeps
 * nothing) and writes the run, events and hops data blocks. */
int fig_run_prepare(fig_Data *d, const jc_SimOptions *o, int dt_given, double max_samples);
/* The readable name of an event ("lift-off", "ramp end"). */
const char *fig_event_label(jc_EventKind k);
/* "bounce ×4, touchdown": the kinds of events first..last of a run in order,
 * repeats counted (per-kind totals when that is too long for len). */
void fig_event_cluster_label(const jc_Run *run, int first, int last, char *out, size_t len);
/* Whether an event starts a flight (a lift-off, or a bounce into flight). */
int fig_event_flies(const jc_Event *e);
/* "zoomed to x = 53.8–320 cm (t = 0.43–1.09 s), around the first lift-off
 * and the hops": the zoom in words, for titles (d->zoomed). */
void fig_zoom_caption(const fig_Data *d, char *out, size_t len);

/* "shown to t = 12.2 s, where the losses reach 99 % of their total; it
 * rocks on to 60 s (all: --t-max 60)": the cut in words, for titles ("" when
 * d->cut is FIG_CUT_NONE). */
void fig_cut_caption(const fig_Data *d, char *out, size_t len);

/* ---- plot_trajectory.c: the body's path to scale in the laboratory frame ---- */
/* Keeps the run's options o (its flights are sampled again densely, with
 * them) and writes the ramp's data block (after fig_run_prepare). */
int fig_trajectory_prepare(fig_Data *d, const jc_SimOptions *o);
/* Its data blocks and panels: a main one zoomed on the lift-off and the
 * hops, the whole ramp with the main panel's view marked, and a close-up of
 * the first flight's gap when the main panel shows it too thin to read. */
void fig_trajectory_panels(FILE *gp, const fig_Data *d);

/* ---- the trajectory figure's own parts: its files only ----
 * Data flow one way: trajectory_view.c (the picture's geometry in cm, boxes,
 * the panels' frames on the page) <- trajectory_labels.c (labels placed
 * clear of everything) <- trajectory_layout.c (the page laid out, the
 * titles) <- plot_trajectory.c (the path, the outlines, the script). */

/* The page: a 2400 x 1500 px canvas (plot.c, kind "trajectory"), and the
 * room its title takes at the top. */
#define FIG_PAGE_W_PX 2400.0
#define FIG_PAGE_H_PX 1500.0
#define FIG_PAGE_TITLE_PX 75.0
/* A panel's room around its plot area (px): tic labels and the y label on
 * the left, the x tic labels and label below. */
#define FIG_MARGIN_L_PX 140.0
#define FIG_MARGIN_R_PX 50.0
#define FIG_MARGIN_B_PX 120.0
/* F_SMALL's line height (px) on the PNG page, the largest of the three terminals. */
#define FIG_SMALL_LINE_PX 24.0
/* Outlines drawn at most, and the length of an outline's label. */
#define FIG_MAX_OUTLINES 24
#define FIG_LABEL_MAX 64

typedef struct {
    double X, Y; /* picture coordinates, cm (or page px) */
} fig_Pt;

typedef struct {
    double lo_X, hi_X, lo_Y, hi_Y; /* cm (or page px) */
} fig_Box;

/* The samples drawn: the run's, each flight's replaced by denser ones. */
typedef struct {
    jc_Sample *s;
    int n;
} fig_Path;

/* An outline at the events: the body drawn at one event's state, named for
 * every event nearest to it. */
typedef struct {
    int event;           /* the event whose state is drawn */
    fig_Pt c;            /* its centre (picture cm) */
    char label[FIG_LABEL_MAX];
} fig_Outline;

/* A panel on the page: its ranges (cm), its plot area (page px from the
 * lower left) and the room it was given. */
typedef struct {
    fig_Box view, area, region;
} fig_Frame;

typedef struct {
    fig_Frame main, ramp, closeup;
    int ramp_shown, closeup_shown;
    int key_rows;
    int title_lines[3]; /* main, ramp, close-up */
} fig_Layout;

typedef struct {
    char main[400], ramp[200], closeup[200];
} fig_Titles;

/* What a label must clear, in page px: curves (polylines broken by NaN),
 * discs (the outlines), the incline (labels stay above it), labels placed. */
typedef struct {
    const fig_Pt *pts;
    int n;
    const fig_Pt *disc_c;
    const double *disc_r;
    int discs;
    fig_Pt incline_at, incline_dir; /* a point of the incline and its direction (px) */
    int above_incline;
    fig_Box *labels;
    int label_count;
    fig_Box area; /* labels stay inside */
} fig_Obstacles;

/* trajectory_view.c: geometry and frames */
extern const fig_Box fig_empty_box; /* holds nothing: fig_box_add grows it to the first point */
/* Incline coordinates (m) to the picture (cm). */
fig_Pt fig_picture(double incline_rad, double x_m, double y_m);
/* A body point (offset from C, body angle) for the state s, in the picture. */
fig_Pt fig_body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad);
/* Whether a part's axis is off the centre (it traces its own path). */
int fig_off_centre(const jc_Part *p);
/* Whether the centre of mass sits on an off-centre part's axis, or on C. */
int fig_cm_on_a_part(const jc_Model *m);
void fig_box_add(fig_Box *b, fig_Pt p, double pad);
void fig_box_join(fig_Box *b, fig_Box o);
double fig_box_w(fig_Box b);
double fig_box_h(fig_Box b);
int fig_box_overlaps(fig_Box a, fig_Box b);
int fig_box_inside(fig_Box in, fig_Box out);
/* The page px of a picture point in a frame; the frame's scale. */
fig_Pt fig_to_px(const fig_Frame *f, fig_Pt p);
double fig_px_per_cm(const fig_Frame *f);
/* The frame of a picture box in a region of the page (fill: the plot area
 * takes the whole room, the box widened to it). */
fig_Frame fig_frame_in(fig_Box region, fig_Box box, double top_px, double bottom_px, int fill);
/* Room above a plot area for a title of so many lines. */
double fig_title_px(int lines);
/* The main panel's region: on top or on the left, whichever is larger. */
fig_Box fig_main_region(fig_Box box, double top_px, double bottom_px, int alone, int *on_top);
/* The box of the curves drawn between t_lo and t_hi. */
fig_Box fig_curves_box(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi);
/* A box grown by a small fraction of its size. */
fig_Box fig_box_margin(fig_Box b);
/* The close-up's box about the first flight's gap at sample s. */
fig_Box fig_closeup_box(const fig_Data *d, const jc_Sample *s);
/* The whole ramp's and the close-up's frames in the room the main panel leaves. */
void fig_side_frames(fig_Layout *l, int on_top, fig_Box ramp_box, fig_Box close_box);

/* trajectory_labels.c: labels clear of everything */
/* The place (page px) of a w x h px label next to a mark at c of radius r_px. */
fig_Box fig_place_label(const fig_Obstacles *o, fig_Pt c, double r_px, double prefer, double w, double h);
/* A label's width in page px (F_SMALL). */
double fig_label_w_px(const char *s);
/* Places the outlines' labels in the main frame; how many fall outside it. */
int fig_place_outline_labels(const fig_Data *d, const fig_Path *path, const fig_Frame *f, double t_lo, double t_hi,
                             const fig_Outline *o, int n, fig_Box *labels);

/* trajectory_layout.c: the page */
/* The frames and titles, the main panel's view grown until the outlines'
 * labels fit in it (placed in labels); apex: the close-up's sample or NULL. */
void fig_trajectory_lay_out(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi, const fig_Outline *o,
                            int n, fig_Box *labels, fig_Layout *l, fig_Titles *t, const jc_Sample *apex, double sep_cm);

/* ---- plot_panels.c: the three panels drawn from a run ---- */
void fig_forces_panel(FILE *gp, const fig_Data *d);
void fig_path_panel(FILE *gp, const fig_Data *d);
void fig_energy_panel(FILE *gp, const fig_Data *d);

/* ---- plot_map.c: jumpcyl map, the first lift-off over two setup options ---- */

/* What a cell of the map is: the batch's case kinds (batch.h, cli_CaseKind). */
enum { FIG_CELL_LIFTOFF, FIG_CELL_NONE, FIG_CELL_SLIDES, FIG_CELL_INVALID, FIG_CELL_FAILED, FIG_CELL_KINDS };

typedef struct {
    char label[96];         /* "incline (°)", "rod-offset (cm)": enhanced text */
    long count;             /* >= 2 */
    const double *values;   /* the axis' values in its unit, increasing */
} fig_MapAxis;

#define FIG_MAP_PAPER_MAX 3

typedef struct {
    fig_Format format;
    fig_MapAxis x, y;
    const unsigned char *kind; /* per cell, cell iy * x.count + ix: FIG_CELL_* */
    const double *liftoff_cm;  /* per cell: first lift-off x (cm), NaN if none */
    double ramp_cm;            /* the colour scale when nothing lifts off */
    char title[256], subtitle[256]; /* the fixed setup (enhanced text) */
    /* The paper's setups: points in the axes' units, labels ("paper 15°"). */
    int paper_count;
    double paper_x[FIG_MAP_PAPER_MAX], paper_y[FIG_MAP_PAPER_MAX];
    char paper_label[FIG_MAP_PAPER_MAX][40];
    int paper_differs;         /* the map's other options are not the paper's */
} fig_Map;

/* Writes the map's data blocks and its panel into the script (after
 * fig_script_begin). */
void fig_map_write(FILE *gp, const fig_Map *m);

/* ---- plot_track.c: the figure of compare and fit ---- */

typedef struct {
    const jc_Track *track;
    long first, count;               /* the frames shown */
    const double *sim_x, *sim_y, *sim_theta; /* the model at those frames (theta: the mark's) */
    const double *path_t, *path_x, *path_y;  /* the model finely sampled, for its curves */
    long path_n;
    double radius_m;                 /* the body's: a height shown is the centre's y less it */
    double mark_radius_m;            /* > 0: the mark's residual across its radius is shown */
    double sigma_m;                  /* residuals are shown in units of it */
    double hop_threshold_m;
    char title[256];                 /* text the tool made (numbers, fixed words) */
} cli_TrackFigure;

/* Three panels, each sized to its data: the centre along the incline
 * against time; its height above the surface against time (the hops); the
 * residuals in units of sigma. Rendered by gnuplot in a scratch directory
 * and written to output (.png, .svg, .pdf) whole or not at all. cmdline is
 * for the script's header. EXIT_OK, or an exit status after a message. */
int cli_track_figure(const char *cmd, const cli_TrackFigure *f, const char *output, const char *cmdline);

#endif
