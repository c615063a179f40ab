/* The model against a tracked experiment (docs/tracker.md): the model
 * sampled at the frames' times from a tracked state, where the free motion
 * starts, the comparison of the two, the least-squares fit of setup values
 * and start with what the video determines and a verdict, and synthetic
 * experiments made from the model for tests and examples. Functions on
 * arrays and values: they print nothing and never exit. */
#ifndef JUMPCYL_TRACK_FIT_H
#define JUMPCYL_TRACK_FIT_H

#include <jumpcyl/track.h>

#define CLI_TRACK_PI 3.14159265358979323846

#include <stdint.h>
#include <stdio.h>

/* ---- synthetic.c: a tracked experiment made from the model ---- */

typedef enum {
    CLI_SYNTH_BOTH = 0,      /* the centre and the mark */
    CLI_SYNTH_CENTRE_ONLY,   /* the centre alone */
    CLI_SYNTH_MARK_ONLY      /* the mark alone (an LED on the rim) */
} cli_SynthTracks;

typedef struct {
    double fps_hz;         /* frame rate, > 0 */
    double sigma_m;        /* Gaussian noise on every tracked point (m), >= 0 */
    double t_end_s;        /* last frame at or before this time (s); the run's end if sooner */
    double mark_radius_m;  /* distance of the tracked mark from C; 0: no mark tracked */
    double drop_fraction;  /* frames left out at random, [0, 0.5] */
    uint64_t seed;         /* Philox key (cli/batch/random.c): the same track for the same seed */
    uint64_t trial;        /* Philox sample index: independent tracks for one seed */
    cli_SynthTracks tracks;
    double mark_angle_rad; /* the mark's angle on the body (as a part's angle); 0: the reference direction */
    double hand_s;         /* frames of a hand pushing the body from rest up to the start's spin
                              before the free motion (0: none); the clip starts with them */
} cli_SynthOptions;

/* The setup's run from its start filmed at fps as Tracker's level axes hold
 * it (metres, the start's contact point at the origin, downhill to the
 * right), each tracked point with independent noise. The raw data of
 * raw.h; 0, or -1 with a message. */
int cli_track_synth_raw(const jc_Setup *setup, const cli_SynthOptions *o, jc_TrackRaw *raw, char *err,
                        size_t err_len);
/* The same read as a file is: the incline measured, the setup's radius. */
int cli_track_synthesize(const jc_Setup *setup, const cli_SynthOptions *o, jc_Track *out, char *err,
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
    /* x in the run = x in the track + shift_m (cli_track_sim_shift). */
    double shift_m;
    jc_RunSummary sum;   /* of the last run */
    jc_Run run;          /* its end */
    int failed;          /* out of memory in the recorder */
} cli_TrackSim;

int cli_track_sim_init(cli_TrackSim *s);
double cli_track_sim_shift(const jc_Track *t);
void cli_track_sim_free(cli_TrackSim *s);

/* The setup as runs against a track use it: the ramp lengthened uphill by
 * CLI_TRACK_RAMP_MARGIN_M and downhill to hold every frame. (The incline is
 * the caller's: compare and fit take the track's.) */
int cli_track_model(const jc_Setup *setup, const jc_Track *t, jc_Model *model, char *err, size_t err_len);
/* The setup's values for runs against the track (what cli_track_model builds). */
jc_Setup cli_track_setup(const jc_Setup *setup, const jc_Track *t);

/* Runs the model from start (track coordinates; the model's setup θ0 and ω0
 * should be the start's) and gives the centre and G's angle at each of the
 * n times (increasing, >= start->t_s), by cubic Hermite interpolation
 * between samples a fraction of a frame apart (linear in an interval that
 * ends at an impact). Past the run's end the body flies on freely. 0, or -1
 * with a message. */
int cli_track_sim_run(cli_TrackSim *s, const jc_Model *model, const jc_State *start, const jc_SimOptions *o,
                      const double *t_s, long n, double *x_m, double *y_m, double *theta_rad, char *err,
                      size_t err_len);

/* ---- start.c: the state at a frame, the frames of a window, hops ---- */

/* The setup's own start (θ0, ω0, rolling: y = r, vx = r ω) at the first
 * frame from `first` on, before `end`, that has the centre. */
void cli_track_start_setup(const jc_Track *t, long first, long end, double radius_m, const jc_Setup *setup,
                           jc_State *out);
/* The body's state at frame `first` from quadratic least squares over the
 * next few frames (at most `span`): in contact it rolls (y = r, vy = 0,
 * vx = r ω, ω weighted from the mark and the centre). θ is the mark's
 * (theta_fallback_rad without one). -1 when fewer than 3 frames are left. */
int cli_track_start_estimate(const jc_Track *t, long first, long span, double radius_m, double theta_fallback_rad,
                             double hop_threshold_m, jc_State *out);

/* G's angle minus the mark's: the body's angle of G less the mark's
 * angle on the body (mark_angle_rad, a part's angle; 0: the reference
 * direction, where the paper's rod and the hoop's mass sit). */
double cli_track_mark_offset_rad(const jc_Model *m, double mark_angle_rad);

/* The mark's distance from C: the track's when it has one, else the
 * off-centre part farthest from C. */
double cli_track_mark_radius(const jc_Track *t, const jc_Model *m);

#define CLI_TRACK_MAX_HOPS 64
/* Hops seen in a sampled height: runs of at least 2 frames whose centre is
 * more than threshold above r. */
typedef struct {
    int hops;                            /* runs (at most CLI_TRACK_MAX_HOPS kept) */
    double first_liftoff_t_s;            /* the last frame in contact before the first hop; NaN if none */
    double first_liftoff_x_m;
    long first[CLI_TRACK_MAX_HOPS], last[CLI_TRACK_MAX_HOPS]; /* frames of each (indices into the arrays) */
    double height_m[CLI_TRACK_MAX_HOPS]; /* highest centre above r in each hop */
} cli_TrackHops;

void cli_track_find_hops(const double *t_s, const double *x_m, const double *y_m, long n, double radius_m,
                         double threshold_m, cli_TrackHops *out);

/* The frames of a window [from, to] (NaN: open end): first index and count. */
void cli_track_window(const jc_Track *t, double from_s, double to_s, long *first, long *count);

/* ---- launch.c: where the free motion starts ---- */

typedef struct {
    long frame;            /* the first frame of the free motion (an index into the track) */
    long pushed;           /* frames before it that the model cannot follow (a hand) */
    double chi2_dof_with;  /* the first window's fit with the pushed frames in; NaN when none */
    double chi2_dof;       /* the window's fit from the start found */
    jc_State start;        /* the state there, refined (track coordinates, G's angle) */
} cli_Launch;

/* From frame `from` on, the first frame from which the model, started with
 * the state the frames show (x0, ω0 and θ0 fitted to the next 0.4 s),
 * follows them at the noise: frames before it show a push (an acceleration
 * the model cannot produce). theta0 is searched around the circle when no
 * mark tells it; frames after to_s (NaN: none) are not used; at most 45
 * start frames are tried, a stride apart at high frame rates. scan 0:
 * `from` is the start (set by the user), only its state is fitted. 0, or
 * -1 with a message. */
int cli_track_launch(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, long from, double to_s,
                     int scan, double mark_angle_rad, cli_Launch *out, char *err, size_t err_len);

/* ---- compare.c: measured against simulated ---- */

typedef struct {
    long first, count;         /* the frames compared */
    cli_Launch launch;         /* the start (the free motion's first frame) */
    double *x_m, *y_m, *theta_rad; /* the model at the frames (theta: of the mark) */
    double rms_path_m;         /* centre: sqrt(mean(dx^2 + dy^2)) over frames with a centre */
    double rms_theta_rad;      /* over frames with the mark; NaN without */
    double max_path_m;
    cli_TrackHops measured, simulated; /* the same detector on both, at the track's hop threshold */
    /* The model's own events (exact times): */
    int model_liftoffs, model_bounces;
    double model_liftoff_t_s, model_liftoff_x_m; /* NaN if none */
    double model_largest_hop_m;
} cli_Compare;

typedef enum { CLI_START_TRACKED, CLI_START_SETUP } cli_StartKind;

/* Runs the model from the free motion's first frame in [from, to] (the
 * state the frames show, or the setup's θ0 and ω0 at the tracked position)
 * and compares. 0, or -1 with a message. Free with cli_compare_free. */
int cli_track_compare(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, cli_StartKind start,
                      double from_s, double to_s, double mark_angle_rad, cli_Compare *out, char *err,
                      size_t err_len);
void cli_compare_free(cli_Compare *c);

/* ---- fit_params.c: the values a fit can free ---- */

typedef enum {
    CLI_FIT_MU_S,
    CLI_FIT_MU_K,
    CLI_FIT_RESTITUTION,
    CLI_FIT_THETA0,
    CLI_FIT_OMEGA0,
    CLI_FIT_X0,
    CLI_FIT_MARK_ANGLE,  /* the mark's angle on the body */
    CLI_FIT_TILT,        /* the video's frame against the model's incline frame (see cli_FitFrame) */
    CLI_FIT_SURFACE,     /* the surface's height in the video's frame */
    CLI_FIT_PART_OFFSET, /* a body part's distance from C (part: which) */
    CLI_FIT_PART_MASS    /* a body part's mass */
} cli_FitKind;

/* What a fit holds beside the setup and the start: the mark's angle on the
 * body, and how the video's frame sits on the model's. The video's frame
 * was turned onto the surface the frames in contact show; that surface is
 * known to the noise, so the model's positions are turned by tilt about
 * the start and moved up by surface before they meet the frames, and a
 * measured incline is the video's plus tilt (a tilted surface tilts
 * gravity's direction against it too). */
typedef struct {
    double mark_angle_rad;
    double tilt_rad;
    double surface_m;
} cli_FitFrame;

typedef struct {
    cli_FitKind kind;
    int part;            /* the body part, for the last two */
} cli_FitParam;

#define CLI_FIT_MAX_PARAMS 14

/* 1 when a and b name the same value. */
int cli_fit_param_same(cli_FitParam a, cli_FitParam b);
/* A value's name ("mu_s", "rod_offset", ...) into buf. */
void cli_fit_param_name(const jc_Setup *s, cli_FitParam p, char *buf, size_t len);
/* Its unit ("", "rad", "rad/s", "m", "kg"). */
const char *cli_fit_param_unit(cli_FitParam p);
/* Parses a comma-separated list ("mu_k,restitution,rod-offset"; - or _)
 * against the setup's body. 0, or -1 with a one-line message naming the
 * bad entry and what is allowed. */
int cli_fit_parse_free(const char *text, const jc_Setup *s, cli_FitParam *out, int *count, char *err,
                       size_t err_len);
/* The names the setup's body allows, for messages and help. */
void cli_fit_allowed(const jc_Setup *s, char *buf, size_t len);

/* The physical range of a value: [lo, hi], either may be infinite; the
 * setup gives the radius, masses and mu_s. */
void cli_fit_range(const jc_Setup *s, cli_FitParam p, double *lo, double *hi);
/* A value in a setup, start and frame, and one set into them. */
double cli_fit_get(const jc_Setup *s, const jc_State *start, const cli_FitFrame *f, cli_FitParam p);
void cli_fit_set(jc_Setup *s, jc_State *start, cli_FitFrame *f, cli_FitParam p, double v);

/* ---- fit.c: least squares ---- */

typedef enum { CLI_LOSS_LINEAR, CLI_LOSS_HUBER, CLI_LOSS_CAUCHY } cli_FitLoss;
/* "linear", "huber", "cauchy"; -1 for an unknown name. */
int cli_fit_parse_loss(const char *text, cli_FitLoss *out);
/* The model's positions and angles (n of each; th may be NULL) into the
 * video's frame: turned by the tilt about the start, moved up by the
 * surface. */
void cli_fit_to_video(const cli_FitFrame *fr, const jc_State *start, double *x, double *y, double *th, long n);

typedef struct {
    cli_FitParam free[CLI_FIT_MAX_PARAMS]; /* the values asked for */
    int free_count;
    int hold_start;        /* 0: x0, θ0 and ω0 are fitted with them (the start is never exact);
                              1: held at the start refined on the first 0.4 s */
    int hold_frame;        /* 0: the frame's tilt and surface are fitted with them (with a
                              measured incline, the incline with the tilt) */
    cli_FitLoss loss;
    double from_s, to_s;   /* window; NaN: open */
    int max_iter;          /* trust-region iterations per descent, > 0 */
    double sigma_m;        /* position noise; <= 0: the track's (measured: σ are then scaled by chi2/dof) */
    cli_StartKind start;   /* the start's values: tracked (estimated) or the setup's */
    int starts;            /* start points screened over the bounded values (0: by the count of them) */
    int descents;          /* best screened points descended from (0: 3) */
    uint64_t seed;         /* the screening's Latin hypercube (Philox) */
    double mark_angle_rad; /* the mark's angle on the body, when not fitted */
    int profiles;          /* 1: a chi2 profile for each value not determined */
    /* Called as each descent begins (NULL: not): what the fit is doing and
     * how many descents it has begun in that stage, for a progress line
     * (the fit prints nothing itself). */
    void (*progress)(void *ctx, const char *stage, int descents);
    void *progress_ctx;
    int start_window;      /* 0: a fit: the free motion's first frame is found and the start's
                              values fitted alone to its first 0.4 s first (launch.c: a start
                              estimated from a few frames is far off, and every descent would
                              begin from it); 1: such a fit of the start itself, which works out
                              the values and chi2 only (no lift-off, RMS, verdict or profiles) */
} cli_FitOptions;

void cli_fit_options_default(cli_FitOptions *o);

/* Why a value was taken out of the fit. */
typedef enum {
    CLI_FIT_DETERMINED = 0,
    CLI_FIT_ON_BOUND,       /* it sits on a bound of its range */
    CLI_FIT_WIDER_THAN_RANGE, /* its sigma exceeds its range */
    CLI_FIT_CORRELATED,     /* |rho| > 0.99 with another value */
    CLI_FIT_NO_EFFECT       /* the residuals do not change with it */
} cli_FitFlag;
const char *cli_fit_flag_text(cli_FitFlag f);

#define CLI_FIT_MAX_MINIMA 6
#define CLI_FIT_PROFILE_POINTS 9

typedef struct {
    double value[CLI_FIT_MAX_PARAMS]; /* SI, the values of the fit's free list */
    double chi2;
} cli_FitMinimum;

typedef struct {
    int count;                        /* the values asked for (and the start's) */
    cli_FitParam param[CLI_FIT_MAX_PARAMS];
    int start_value[CLI_FIT_MAX_PARAMS]; /* 1: x0, θ0, ω0, tilt, surface added by the fit */
    double initial[CLI_FIT_MAX_PARAMS], value[CLI_FIT_MAX_PARAMS], sigma[CLI_FIT_MAX_PARAMS]; /* SI */
    double lo[CLI_FIT_MAX_PARAMS], hi[CLI_FIT_MAX_PARAMS]; /* ranges */
    cli_FitFlag flag[CLI_FIT_MAX_PARAMS]; /* CLI_FIT_DETERMINED, or why it was held */
    int other[CLI_FIT_MAX_PARAMS];    /* CLI_FIT_CORRELATED: the value it moves with */
    double rho[CLI_FIT_MAX_PARAMS];   /* that correlation */
    double corr[CLI_FIT_MAX_PARAMS][CLI_FIT_MAX_PARAMS]; /* of the values fitted at the end */
    long residuals;                   /* n */
    double chi2, chi2_dof;            /* of the residuals in units of sigma */
    long dof;                         /* residuals less the values fitted at the end */
    int noise_measured;               /* sigma from the track: sigmas scaled by sqrt(chi2/dof) */
    int iterations;                   /* trust-region iterations, all descents */
    int screened, descents;           /* start points evaluated, descents made */
    int minima;                       /* distinct minima within the threshold of the best (>= 1) */
    cli_FitMinimum minimum[CLI_FIT_MAX_MINIMA];
    double delta_chi2;                /* the threshold for a competing minimum */
    /* chi2 along each held value's range, the others fitted at each point */
    int profiled[CLI_FIT_MAX_PARAMS];
    double profile_x[CLI_FIT_MAX_PARAMS][CLI_FIT_PROFILE_POINTS];
    double profile_chi2[CLI_FIT_MAX_PARAMS][CLI_FIT_PROFILE_POINTS];
    jc_Setup setup;                   /* the setup with the fitted values (the track's incline) */
    jc_State start;                   /* the fitted start (track coordinates) */
    cli_FitFrame frame;               /* the fitted mark angle and frame */
    double incline_sigma_rad;         /* the fitted incline's, when it was measured (the tilt's) */
    cli_Launch launch;
    long first, frames;               /* frames fitted */
    double rms_path_m, rms_theta_rad;
    int has_liftoff;
    double liftoff_x_m, liftoff_sigma_m, liftoff_t_s; /* predicted first lift-off (track coordinates) */
    double sigma_m;                   /* the noise used */
    double mark_radius_m;
    /* The verdict: the model describes the video, or not, and why. */
    int misfit;
    double runs_z;                    /* the worst Wald-Wolfowitz z of the residual series */
    char verdict[400];
} cli_FitResult;

/* Fits the free values to the track's frames in the window. 0, or -1 with a
 * message (no frames, a setup the model refuses, a numerical failure). */
int cli_track_fit(const jc_Setup *setup, const jc_Track *t, const cli_FitOptions *o, const jc_SimOptions *sim,
                  cli_FitResult *out, char *err, size_t err_len);

/* ---- residuals.c: the residuals of a model against the frames ---- */

/* What a fit or a comparison holds against the frames: the centre's x and
 * y per frame and the mark's displacement across its radius (a tracked
 * centre), or the mark's x and y (a centre recovered from the mark). */
typedef struct {
    const jc_Track *t;
    long first, count;
    double sigma;         /* metres per sigma */
    double mark_radius;   /* a: the mark's distance from C (0: no mark in the residuals) */
    double mark_offset;   /* G's angle minus the mark's */
} cli_Residuals;

/* How many residuals the frames give. */
long cli_residual_count(const cli_Residuals *r);
/* The model (x, y and the mark's angle th_mark at count frames from
 * first) against the track: the centre's path RMS and largest distance
 * (max_path_m may be NULL) over frames with a centre, the mark's angle RMS
 * (modulo 2 pi) over frames with it (NaN without). */
void cli_track_misfit(const jc_Track *t, long first, long count, const double *x, const double *y,
                      const double *th_mark, double *rms_path_m, double *max_path_m, double *rms_theta_rad);

/* The residuals of frame j (an index into t) against the model's centre
 * (x, y) and mark angle thm, in units of sigma, into f: the centre's x and
 * y, then (a > 0, θ tracked there) the mark's displacement across its
 * radius a; or, with a centre recovered from the mark, the mark's x and y.
 * Returns how many (0: nothing tracked there); f[m] is of series m. */
int cli_residuals_frame(const jc_Track *t, long j, double sigma, double a, double x, double y, double thm,
                        double f[3]);
/* Residuals in units of sigma for the model's centre and G's angle at the
 * frames: f[0 .. count). Series k (0, 1, 2) of residual i: which = i's. */
void cli_residuals_eval(const cli_Residuals *r, const double *x, const double *y, const double *th, double *f,
                        unsigned char *series);
/* The Wald-Wolfowitz runs test on each series' signs in frame order: the
 * most negative z (too few runs) and its series' name. */
double cli_residuals_runs_z(const double *f, const unsigned char *series, long n, const char **which);

/* ---- cli/figures/plot_track.c: the figure of compare and fit ---- */

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
