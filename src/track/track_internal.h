/* What the files of src/track share (not installed). The tracks as a file
 * holds them (jc_TrackRaw, <jumpcyl/track.h>) and the steps from them to a
 * jc_Track: the readers (trk.c, table.c), the conversion to the incline
 * frame (frame.c), the derivation (surface.c, rim.c, derive.c), and the
 * whole of it (read.c); data.c allocates and frees. Then the model against
 * a track: runs sampled at the frames (model_path.c), starts, windows and
 * hops (start.c), residuals (residuals.c), the fit's values (fit_params.c),
 * the least squares (fit.c), where the free motion starts (launch.c), the
 * whole fit (fit_video.c), the comparison (compare.c), synthetic videos
 * (synthetic.c). Their random numbers are the library's Philox
 * (src/random.c, <jumpcyl/study.h>).
 *
 * Calls run one way, no file calling back into one that calls it:
 *   read.c -> trk.c, table.c, frame.c, derive.c; derive.c -> rim.c, frame.c;
 *   frame.c, rim.c -> surface.c; read.c, trk.c, table.c, frame.c -> data.c;
 *   fit_video.c -> launch.c -> fit.c -> model_path.c, start.c, residuals.c,
 *   fit_params.c; model_path.c -> start.c; compare.c -> launch.c,
 *   model_path.c; synthetic.c -> read.c, data.c; compare.c,
 *   launch.c and fit.c check the track with read.c's jc_track_require. */
#ifndef JUMPCYL_TRACK_INTERNAL_H
#define JUMPCYL_TRACK_INTERNAL_H

#include "jumpcyl/study.h" /* jc_random_uniform, jc_random_normal */
#include "jumpcyl/track.h"

#include <math.h>
#include <stdio.h>

#define JC_TRACK_PI 3.14159265358979323846

/* Each reader fills raw (zeroed first), or returns a status with "NAME:
 * message" (raw then holds nothing to free): trk.c for Tracker's .trk XML,
 * table.c for its exported data tables. */
int jc_track_trk_parse(const char *name, const char *data, size_t len, jc_TrackRaw *raw, char *err, size_t err_len);
int jc_track_table_parse(const char *name, const char *data, size_t len, jc_TrackRaw *raw, char *err, size_t err_len);

/* The angle Tracker's level axes are turned by to put the tracks in the
 * incline frame: the incline given, or none (no incline given: the video's
 * is measured; incline axes: taken as they are). derive.c then turns the
 * frame onto the surface the frames in contact show. */
static inline double jc_track_frame_angle(const jc_TrackOptions *opt)
{
    return opt->axes == JC_TRACK_AXES_LEVEL && !isnan(opt->incline_rad) ? opt->incline_rad : 0.0;
}

/* (x, y) in axes turned counter-clockwise by an angle of cosine c and
 * sine s: (x c + y s, -x s + y c). */
static inline void jc_track_turn(double x, double y, double c, double s, double *u, double *v)
{
    *u = x * c + y * s;
    *v = -x * s + y * c;
}

/* frame.c: the chosen tracks in a frame turned by angle_rad from
 * Tracker's level axes (or in Tracker's own with incline axes), into out
 * (whose report fields are set here). JC_OK, or JC_EINVAL or JC_ENOMEM
 * with a message (out then holds nothing to free): a radius not > 0 or an
 * incline outside [0, 90) deg, a track name given that is not in the file
 * (or the centre and the mark naming one track), a time that jumps by more than
 * JC_TRACK_MAX_FRAMES frames, a position beyond JC_TRACK_MAX_COORD_M. */
int jc_track_frame_raw(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, double angle_rad,
                       jc_Track *out, char *err, size_t err_len);
/* The tracks' names, quoted and comma-separated, for messages. */
void jc_track_list_names(const jc_TrackRaw *raw, char *buf, size_t len);
/* 1 when a track's name says it is the centre (centre, center, axle, axis, hub). */
int jc_track_named_centre(const char *name);

/* The least noise a track is taken to have: no video resolves 10 µm. */
#define JC_TRACK_NOISE_FLOOR_M 1e-5

/* surface.c: the line y = a + b (x - x_mid) through the frames in contact
 * (runs within 3 sigma of it of at least 4 frames and 0.1 s at fps, less
 * 0.05 s at an end that meets a frame off it; sigma the scatter of those
 * frames about it, at least floor_m; the first cut at 3 start_m, the
 * frame-to-frame noise, when it is > 0). */
typedef struct {
    double a, b, x_mid;
    double var_a, var_b; /* a and b are uncorrelated about x_mid */
    double sxx;          /* sum of (x - x_mid)^2 over the frames in contact */
    double sigma_m;      /* robust scatter (MAD x 1.4826) of those frames about the line */
    long contact;
} jc_TrackSurfaceLine;
/* 0; -1 with fewer than 3 frames in contact (contact[] all 0); -2 out of memory. */
int jc_track_surface_fit(const double *x, const double *y, long n, double fps, double floor_m, double start_m,
                         unsigned char *contact, jc_TrackSurfaceLine *out);

/* The median of v[0..n) (reordered; the mean of the middle two for an
 * even n); NaN for n = 0. */
double jc_track_median(double *v, long n);

/* The noise of a path from its third differences (work: 2 n doubles):
 * those of a smooth path are small next to noise, whose third difference
 * has variance 20 sigma^2; their median absolute value (x 1.4826 for a
 * Gaussian) ignores the impacts. 0 with fewer than 4 points. */
double jc_track_frame_noise(const double *x, const double *y, long n, double *work);

/* rim.c: the centre recovered from a mark on the body by fitting rolling. */
typedef struct {
    const double *t_s, *x_m, *y_m; /* the mark in the frame of jc_track_frame_raw (no NaN) */
    long n;
    double radius_m;               /* r */
    double sigma_floor_m;          /* the noise is not taken below this */
    double gravity_mps2;           /* for the flights */
} jc_TrackRimInput;

typedef struct {
    double tilt_rad, tilt_sigma_rad; /* the rolling line against the frame's x */
    double a_m, a_sigma_m;           /* the mark's distance from C */
    double line_sigma_m;             /* standard error of the centre line's height */
    double noise_m;                  /* the mark's position noise (per coordinate) */
    long rolling_frames;
    /* Per frame, the caller's arrays of n: the surface frame (x along the
     * rolling line, y from the surface). */
    double *mark_x, *mark_y, *cx, *cy, *c_sigma, *theta, *omega;
    unsigned char *rolling;
    long departures;                 /* runs of frames rolling does not explain */
    jc_TrackHop *dep;               /* the caller's array of n / 2 + 1 */
} jc_TrackRimResult;
/* The frames a rolling fit takes at most (its Jacobian is dense, 2 n by
 * about n / 2: a second or two at 1000 frames). */
#define JC_TRACK_RIM_MAX_FRAMES 1000
/* The rolling fit and the departures from it (no flights fitted to them
 * yet: jc_track_rim_flights, once the incline is decided). 0, or -1 when the
 * frames are too few or too many or the fit fails. */
int jc_track_rim_recover(const jc_TrackRimInput *in, jc_TrackRimResult *out);
/* A flight (a parabola under gravity at incline_rad to the rolling line,
 * with a constant spin) fitted to each departure in out, from the rolling
 * state before it; where one fits, its peak is the departure's height and
 * its path the frames' centre, θ and ω. Nothing with incline_rad NaN. */
void jc_track_rim_flights(const jc_TrackRimInput *in, double incline_rad, jc_TrackRimResult *out);

/* derive.c: the surface, the incline, heights and hops, θ and ω, the
 * noise, and the notes. JC_OK, or JC_EINVAL with a message (a given
 * incline, or incline axes, the frames in contact refuse), JC_ENOMEM. */
int jc_track_derive(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, jc_Track *t, char *err,
                    size_t err_len);

/* ---- model_path.c: the model at the frames' times ---- */

/* A run's samples kept for interpolation, and the workspace: made once and
 * reused by every run of a fit, so that runs do not allocate. */
typedef struct {
    jc_Sample *samples;
    int count, cap;
    double *impact_t_s; /* times of impacts: velocities jump there */
    int impacts, impact_cap;
    jc_Workspace *ws;
    /* x in the run = x in the track + shift_m (jc_track_sim_shift). */
    double shift_m;
    jc_RunSummary sum;   /* of the last run */
    jc_Run run;          /* its end */
    int failed;          /* out of memory in the recorder */
} jc_TrackSim;

/* JC_OK or JC_ENOMEM. */
int jc_track_sim_init(jc_TrackSim *s);
double jc_track_sim_shift(const jc_Track *t);
void jc_track_sim_free(jc_TrackSim *s);

/* jc_track_setup's setup as a model. JC_OK, or jc_model_init's status. */
int jc_track_model(const jc_Setup *setup, const jc_Track *t, jc_Model *model, char *err, size_t err_len);

/* Runs the model from start (track coordinates; the model's setup θ0 and ω0
 * should be the start's) and gives the centre and G's angle at each of the
 * n times (increasing, >= start->t_s), by cubic Hermite interpolation
 * between samples a fraction of a frame apart (linear in an interval that
 * ends at an impact). Past the run's end the body flies on freely. JC_OK,
 * or a status with a message. */
int jc_track_sim_run(jc_TrackSim *s, const jc_Model *model, const jc_State *start, const jc_SimOptions *o,
                     const double *t_s, long n, double *x_m, double *y_m, double *theta_rad, char *err,
                     size_t err_len);

/* The model's positions and angles (n of each; th may be NULL) into the
 * video's frame: turned by the tilt about the start, moved up by the
 * surface. */
void jc_fit_to_video(const jc_TrackFitFrame *fr, const jc_State *start, double *x, double *y, double *th, long n);

/* ---- start.c: the state at a frame, the frames of a window, hops ---- */

/* The setup's own start (θ0, ω0, rolling: y = r, vx = r ω) at the first
 * frame from `first` on, before `end`, that has the centre. */
void jc_track_start_setup(const jc_Track *t, long first, long end, double radius_m, const jc_Setup *setup,
                          jc_State *out);
/* The body's state at frame `first` from quadratic least squares over the
 * next few frames (at most `span`): in contact it rolls (y = r, vy = 0,
 * vx = r ω, ω weighted from the mark and the centre). θ is the mark's
 * (theta_fallback_rad without one). -1 when fewer than 3 frames are left. */
int jc_track_start_estimate(const jc_Track *t, long first, long span, double radius_m, double theta_fallback_rad,
                            double hop_threshold_m, jc_State *out);

/* G's angle minus the mark's: the body's angle of G less the mark's
 * angle on the body (mark_angle_rad, a part's angle; 0: the reference
 * direction, where the paper's rod and the hoop's mass sit). */
double jc_track_mark_offset_rad(const jc_Model *m, double mark_angle_rad);

/* Hops (jc_TrackHops) in a sampled height. */
void jc_track_find_hops(const double *t_s, const double *x_m, const double *y_m, long n, double radius_m,
                        double threshold_m, jc_TrackHops *out);

/* The frames of a window [from, to] (NaN: open end): first index and count. */
void jc_track_window(const jc_Track *t, double from_s, double to_s, long *first, long *count);

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
} jc_TrackResiduals;

/* How many residuals the frames give. */
long jc_track_residual_count(const jc_TrackResiduals *r);
/* The model (x, y and the mark's angle th_mark at count frames from
 * first) against the track: the centre's path RMS and largest distance
 * (max_path_m may be NULL) over frames with a centre, the mark's angle RMS
 * (modulo 2 pi) over frames with it (NaN without). */
void jc_track_misfit(const jc_Track *t, long first, long count, const double *x, const double *y,
                     const double *th_mark, double *rms_path_m, double *max_path_m, double *rms_theta_rad);
/* Residuals in units of sigma for the model's centre and G's angle at the
 * frames: f[0 .. count). Series k (0, 1, 2) of residual i: which = i's. */
void jc_track_residuals_eval(const jc_TrackResiduals *r, const double *x, const double *y, const double *th,
                             double *f, unsigned char *series);
/* The Wald-Wolfowitz runs test on each series' signs in frame order: the
 * most negative z (too few runs) and its series' name. */
double jc_track_residuals_runs_z(const double *f, const unsigned char *series, long n, const char **which);

/* ---- fit_params.c: the values a fit can free ---- */

/* 1 when a and b name the same value. */
int jc_fit_param_same(jc_TrackFitParam a, jc_TrackFitParam b);
/* JC_OK when the setup's body has p (a kind of the enum; a part that is
 * there, with an offset for an offset); else JC_EINVAL. */
int jc_fit_param_check(const jc_Setup *s, jc_TrackFitParam p);
/* The physical range of a value: [lo, hi], either may be infinite; the
 * setup gives the radius, masses and mu_s. */
void jc_fit_range(const jc_Setup *s, jc_TrackFitParam p, double *lo, double *hi);
/* A value in a setup, start and frame, and one set into them. */
double jc_fit_get(const jc_Setup *s, const jc_State *start, const jc_TrackFitFrame *f, jc_TrackFitParam p);
void jc_fit_set(jc_Setup *s, jc_State *start, jc_TrackFitFrame *f, jc_TrackFitParam p, double v);

/* ---- fit.c: the least squares; launch.c: where the free motion starts ---- */

/* The part [lo, hi] of the caller's whole that a fit's progress covers
 * (fn NULL: no progress reported). */
typedef struct {
    jc_TrackFitProgressFn fn;
    void *ctx;
    double lo, hi;
} jc_TrackFitSpan;

/* The options checked: a positive iteration limit, values to free that
 * the setup's body has, a loss and a start kind of their enums. JC_OK, or
 * JC_EINVAL with a message. */
int jc_fit_options_check(const jc_Setup *setup, const jc_TrackFitOptions *o, char *err, size_t err_len);
/* The least squares from the window's first frame, its start estimated
 * there, or refined (not NULL: the launch's fitted start), or the setup's
 * (o->start): jc_track_fit without the search for the free motion's start.
 * out->launch is left zeroed. JC_OK, or a status with a message. */
int jc_track_fit_solve(const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o,
                       const jc_SimOptions *sim, const jc_State *refined, const jc_TrackFitSpan *span,
                       jc_TrackFitResult *out, char *err, size_t err_len);

/* From frame `from` on, the first frame from which the model, started with
 * the state the frames show (x0, ω0 and θ0 fitted to the next 0.4 s),
 * follows them at the noise: frames before it show a push (an acceleration
 * the model cannot produce). theta0 is searched around the circle when no
 * mark tells it; frames after to_s (NaN: none) are not used; at most 45
 * start frames are tried, a stride apart at high frame rates. scan 0:
 * `from` is the start (set by the user), only its state is fitted. span:
 * the window fits' progress (NULL: none). JC_OK, or a status with a
 * message (JC_ESTOPPED when the progress callback asked). */
int jc_track_launch(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, long from, double to_s,
                    int scan, double mark_angle_rad, const jc_TrackFitSpan *span, jc_TrackLaunch *out, char *err,
                    size_t err_len);

#endif
