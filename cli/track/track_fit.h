/* The model against a tracked experiment (docs/tracker.md): the model
 * sampled at the frames' times from a tracked state, the comparison of the
 * two, the least-squares fit of setup values and start, and synthetic
 * experiments made from the model for tests and examples. */
#ifndef JUMPCYL_TRACK_FIT_H
#define JUMPCYL_TRACK_FIT_H

#include "track.h"

#include <stdint.h>

/* ---- synthetic.c: a tracked experiment made from the model ---- */

typedef struct {
    double fps_hz;        /* frame rate, > 0 */
    double sigma_m;       /* Gaussian noise on every tracked point (m), >= 0 */
    double t_end_s;       /* last frame at or before this time (s); the run's end if sooner */
    double mark_radius_m; /* distance of the tracked mark from C; 0: no mark tracked */
    double drop_fraction; /* frames left out at random, [0, 0.5] */
    uint64_t seed;        /* Philox key (cli/batch/random.c): the same track for the same seed */
    uint64_t trial;       /* Philox sample index: independent tracks for one seed */
} cli_SynthOptions;

/* Simulates the setup from its start with samples at k / fps and tracks
 * them as a video would: the centre and the mark (at mark_radius_m from C
 * in G's direction) each get independent noise of sigma_m in both
 * coordinates; θ is the angle of the noisy mark seen from the noisy centre,
 * unwrapped. x0_m is 0 (the setup's start is the ramp's top), sigma_m is the
 * noise. 0, or -1 with a message. */
int cli_track_synthesize(const jc_Setup *setup, const cli_SynthOptions *o, cli_Track *out, char *err,
                         size_t err_len);

/* ---- model_path.c: the model at the frames' times ---- */

/* The ramp is lengthened uphill by this margin in every run against a
 * track, so that a start estimated a little above the ramp's top (noise) is
 * still on the ramp; x along the track is x in the run minus the margin. */
#define CLI_TRACK_RAMP_MARGIN_M 1.0

/* A run's samples kept for interpolation, and the workspace: made once and
 * reused by every run of a fit, so that runs do not allocate. */
typedef struct {
    jc_Sample *samples;
    int count, cap;
    double *impact_t_s; /* times of impacts: velocities jump there */
    int impacts, impact_cap;
    jc_Workspace *ws;
    /* x in the run = x in the track + shift_m: the track's x0_m (the first
     * frame's centre) is the setup's start, the ramp's top, and the ramp is
     * lengthened uphill by the margin. cli_track_sim_shift gives it. */
    double shift_m;
    jc_RunSummary sum;   /* of the last run */
    jc_Run run;          /* its end */
    int failed;          /* out of memory in the recorder */
} cli_TrackSim;

int cli_track_sim_init(cli_TrackSim *s);
double cli_track_sim_shift(const cli_Track *t);
void cli_track_sim_free(cli_TrackSim *s);

/* The setup as runs against a track use it: the ramp lengthened uphill by
 * CLI_TRACK_RAMP_MARGIN_M (its lower end stays where it was). */
int cli_track_model(const jc_Setup *setup, jc_Model *model, char *err, size_t err_len);

/* Runs the model from start (in the track's coordinates: x along the ramp
 * from its top; the model's setup θ0 and ω0 should be the start's, so that
 * a tiny uphill swing at the start is taken in closed form) and gives the
 * centre and G's angle at each of the n times
 * (increasing, >= start->t_s), by cubic Hermite interpolation between
 * samples a fraction of a frame apart (linear in an interval that ends at an
 * impact). Past the run's end (the ramp's end) the body flies on freely.
 * The run's summary is in s->sum, in the run's coordinates (x of the
 * summary's states minus s->shift_m is along the track). 0, or -1 with a
 * message. */
int cli_track_sim_run(cli_TrackSim *s, const jc_Model *model, const jc_State *start, const jc_SimOptions *o,
                      const double *t_s, long n, double *x_m, double *y_m, double *theta_rad, char *err,
                      size_t err_len);

/* ---- start.c: the state at a frame, from the frames that follow ---- */

/* The body's state at frame `first`: position, angle and velocities from
 * quadratic least squares over the next few frames (at most `span`). In
 * contact (the centre less than the hop threshold above r) it is put on
 * the incline rolling: y = r, vy = 0, vx = r ω; ω from the mark's angle,
 * or vx / r without a mark (θ is then theta_fallback_rad). In the track's
 * coordinates. -1 when fewer than 3 frames are left. */
int cli_track_start_estimate(const cli_Track *t, long first, long span, double radius_m, double theta_fallback_rad,
                             double hop_threshold_m, jc_State *out);

/* The mark's angle minus G's (θ of the mark = θ of G - this): the body's
 * cm_angle_rad, as the mark sits on the body's reference direction. */
double cli_track_mark_offset_rad(const jc_Model *m);

/* The mark's distance from C: the track's (the median measured by the
 * import) when it has one, else the off-centre part farthest from C (the
 * paper's rod: 5.5 cm). */
double cli_track_mark_radius(const cli_Track *t, const jc_Model *m);

/* Hops seen in a sampled height: runs of frames whose centre is more than
 * threshold above r. */
#define CLI_TRACK_MAX_HOPS 64
typedef struct {
    int hops;                          /* runs of airborne frames (at most CLI_TRACK_MAX_HOPS kept) */
    double first_liftoff_t_s;          /* the last frame in contact before the first hop; NaN if none */
    double first_liftoff_x_m;          /* x at that frame */
    double height_m[CLI_TRACK_MAX_HOPS]; /* highest centre above r in each hop */
} cli_TrackHops;

void cli_track_find_hops(const double *t_s, const double *x_m, const double *y_m, long n, double radius_m,
                         double threshold_m, cli_TrackHops *out);

/* The frames of a window [from, to] (NaN: open end): first index and count. */
void cli_track_window(const cli_Track *t, double from_s, double to_s, long *first, long *count);

/* ---- compare.c: measured against simulated ---- */

typedef struct {
    long first, count;         /* the frames compared */
    jc_State start;            /* the run's start (track coordinates) */
    double *x_m, *y_m, *theta_rad; /* the model at the frames (theta: of the mark) */
    double rms_path_m;         /* centre: sqrt(mean(dx^2 + dy^2)) */
    double rms_theta_rad;      /* over frames with the mark; NaN without */
    double max_path_m;
    cli_TrackHops measured, simulated; /* the same detector on both */
    double threshold_m;
    /* The model's own events (exact times): */
    int model_liftoffs, model_bounces;
    double model_liftoff_t_s, model_liftoff_x_m; /* NaN if none */
    double model_largest_hop_m;
} cli_Compare;

typedef enum { CLI_START_TRACKED, CLI_START_SETUP } cli_StartKind;

/* Runs the model from the track's first frame in [from, to] (tracked state,
 * or the setup's θ0 and ω0 at the tracked position) and compares. 0, or -1
 * with a message. Free with cli_compare_free. */
int cli_track_compare(const jc_Setup *setup, const cli_Track *t, const jc_SimOptions *o, cli_StartKind start,
                      double from_s, double to_s, cli_Compare *out, char *err, size_t err_len);
void cli_compare_free(cli_Compare *c);

/* ---- fit.c: least squares ---- */

typedef enum {
    CLI_FIT_MU_S,
    CLI_FIT_MU_K,
    CLI_FIT_RESTITUTION,
    CLI_FIT_THETA0,
    CLI_FIT_OMEGA0,
    CLI_FIT_X0,
    CLI_FIT_PARAMS
} cli_FitParam;

typedef enum { CLI_LOSS_LINEAR, CLI_LOSS_HUBER, CLI_LOSS_CAUCHY } cli_FitLoss;

/* "mu_s", "mu_k", "restitution", "theta0", "omega0", "x0". */
const char *cli_fit_param_name(cli_FitParam p);
/* A comma-separated list into a mask of (1 << cli_FitParam); 0, or -1 with a message. */
int cli_fit_parse_free(const char *text, unsigned *mask, char *err, size_t err_len);
/* "linear", "huber", "cauchy"; -1 for an unknown name. */
int cli_fit_parse_loss(const char *text, cli_FitLoss *out);

typedef struct {
    unsigned free_mask;
    cli_FitLoss loss;
    double from_s, to_s;   /* window; NaN: open */
    int max_iter;          /* trust-region iterations per pass, > 0 */
    double sigma_m;        /* position noise; <= 0: the track's */
    cli_StartKind start;   /* the fixed start values: tracked (estimated) or the setup's */
} cli_FitOptions;

typedef enum { CLI_FIT_STOP_STEP, CLI_FIT_STOP_GRADIENT, CLI_FIT_STOP_ITERATIONS, CLI_FIT_STOP_NO_PROGRESS } cli_FitStop;
const char *cli_fit_stop_text(cli_FitStop s);

typedef struct {
    int count;                        /* free parameters */
    cli_FitParam param[CLI_FIT_PARAMS];
    double initial[CLI_FIT_PARAMS], value[CLI_FIT_PARAMS], sigma[CLI_FIT_PARAMS]; /* SI */
    double corr[CLI_FIT_PARAMS][CLI_FIT_PARAMS];
    double cov[CLI_FIT_PARAMS][CLI_FIT_PARAMS]; /* of the values, scaled by chi2/dof */
    long residuals;                   /* n */
    double chi2, chi2_dof;            /* of the residuals in units of sigma (robust: weighted) */
    int iterations;                   /* trust-region iterations, all passes */
    int passes;                       /* robust reweighting passes */
    cli_FitStop stop;
    int singular;                     /* a parameter has no effect on the residuals (sigma infinite) */
    jc_Setup setup;                   /* the setup with the fitted values */
    jc_State start;                   /* the fitted start (track coordinates) */
    long first, frames;               /* frames fitted */
    double rms_path_m, rms_theta_rad;
    int has_liftoff;
    double liftoff_x_m, liftoff_sigma_m, liftoff_t_s; /* predicted first lift-off (track coordinates) */
    double sigma_m;                   /* the noise used */
    double mark_radius_m;
} cli_FitResult;

/* Fits the free values to the track's frames in the window. 0, or -1 with a
 * message (no frames, a setup the model refuses, a numerical failure). */
int cli_track_fit(const jc_Setup *setup, const cli_Track *t, const cli_FitOptions *o, const jc_SimOptions *sim,
                  cli_FitResult *out, char *err, size_t err_len);

/* ---- cli/figures/plot_track.c: the figure of compare and fit ---- */

typedef struct {
    const cli_Track *track;
    long first, count;               /* the frames shown */
    const double *sim_x, *sim_y, *sim_theta; /* the model at those frames (theta: the mark's) */
    const double *path_t, *path_x, *path_y;  /* the model finely sampled, for its curves */
    long path_n;
    double radius_m, incline_rad;
    double mark_radius_m;            /* > 0: the mark's residual across its radius is shown */
    double hop_threshold_m;
    char title[256];                 /* text the tool made (numbers, fixed words) */
} cli_TrackFigure;

/* Three panels (to scale in the laboratory frame: the tracked centre over
 * the model's path; the centre's height above the surface against time;
 * the residuals against time), rendered by gnuplot in a scratch directory
 * and written to output (.png, .svg, .pdf) whole or not at all. cmdline is
 * for the script's header. EXIT_OK, or an exit status after a message. */
int cli_track_figure(const char *cmd, const cli_TrackFigure *f, const char *output, const char *cmdline);

/* ---- cli/commands/track_input.c: what compare and fit share ---- */

enum {
    CLI_TRACK_OPT_TRACK = 2000, CLI_TRACK_OPT_CENTRE, CLI_TRACK_OPT_MASS, CLI_TRACK_OPT_AXES, CLI_TRACK_OPT_FROM,
    CLI_TRACK_OPT_TO, CLI_TRACK_OPT_OUTPUT, CLI_TRACK_OPT_SETUP_START
};
#define CLI_TRACK_ARG_OPTIONS                                                                                   \
    {"track", required_argument, 0, CLI_TRACK_OPT_TRACK}, {"centre", required_argument, 0, CLI_TRACK_OPT_CENTRE}, \
        {"mass", required_argument, 0, CLI_TRACK_OPT_MASS}, {"axes", required_argument, 0, CLI_TRACK_OPT_AXES},    \
        {"from", required_argument, 0, CLI_TRACK_OPT_FROM}, {"to", required_argument, 0, CLI_TRACK_OPT_TO},        \
        {"output", required_argument, 0, CLI_TRACK_OPT_OUTPUT},                                                    \
        {"from-setup-start", no_argument, 0, CLI_TRACK_OPT_SETUP_START}

typedef struct {
    const char *track, *centre, *mass, *axes, *from, *to, *output;
    int from_setup_start;
} cli_TrackArgs;

/* 0 when it took the option, EXIT_USAGE after a message, 1 when the option is not one of these. */
int cli_track_args_take(const char *cmd, cli_TrackArgs *a, int opt, const char *arg);
void cli_track_args_help(void);
/* Checks the options before any work (the window, the figure's name and
 * target, gnuplot); 0 or the exit status after a one-line message. */
int cli_track_args_check(const char *cmd, const cli_TrackArgs *a, double *from_s, double *to_s);
/* Reads the track for the model's incline and radius; 0 or the exit status after a message. */
int cli_track_args_load(const char *cmd, const cli_TrackArgs *a, const jc_Model *m, cli_Track *t);
void cli_track_print_head(const char *file, const cli_Track *t, long first, long count);
/* The model's path every quarter frame from start to t_end_s (for the
 * figure); 0, or -1 (the arrays are then to be freed all the same). */
int cli_track_fine_path(const jc_Setup *setup, const cli_Track *t, const jc_State *start, const jc_SimOptions *o,
                        double t_end_s, double **pt, double **px, double **py, long *n);
/* The last step of compare's and fit's figure, one piece so the two figures
 * cannot drift apart: the caller fills f's frames, model values, mark radius,
 * hop threshold and title; this samples the model's fine path from start to
 * the last frame shown, takes the radius and incline from m, draws the figure
 * to out (cmdline from argv) and frees the path. EXIT_OK or an exit status
 * after a message, or CLI_TRACK_FIGURE_NO_PATH when the path could not be
 * made (no message: the caller says it in its own words). */
#define CLI_TRACK_FIGURE_NO_PATH (-1)
int cli_track_figure_draw(const char *cmd, cli_TrackFigure *f, const jc_Setup *setup, const jc_Model *m,
                          const jc_State *start, const jc_SimOptions *o, const char *out, int argc, char **argv);

int cmd_compare(int argc, char **argv);
int cmd_fit(int argc, char **argv);

#endif
