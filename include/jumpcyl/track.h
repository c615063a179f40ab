/*
 * jumpcyl/track.h: tracked videos (docs/tracker.md, docs/api.md "Tracked
 * videos and fits"). Positions tracked in a video with Tracker (Open Source
 * Physics), read from its .trk files or its exported data tables, or given
 * as arrays, are put in the incline frame of docs/physics.md §1 with what
 * they tell of the centre, the surface, the noise, θ and the hops; the
 * model is compared with them and fitted to them; synthetic videos are made
 * from the model.
 *
 * The conventions of <jumpcyl/jumpcyl.h> hold: SI units and radians, int
 * status codes (JC_OK, JC_EINVAL, JC_ENOMEM, ...) with a one-line message in
 * a caller's buffer, no global mutable state. Nothing here prints or exits.
 * What a video cannot tell is not an error: the track's notes say it, for
 * the caller to show.
 *
 * Reading .trk files uses libxml2 (linked into libjumpcyl), which keeps
 * process-wide state of its own: a program reading .trk files on several
 * threads at once calls libxml2's xmlInitParser() once first.
 */
#ifndef JUMPCYL_TRACK_H
#define JUMPCYL_TRACK_H

#include <jumpcyl/jumpcyl.h>

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bounds on what a file may hold: a larger file is refused, not truncated. */
#define JC_TRACK_MAX_BYTES (64L * 1024 * 1024) /* default file size bound */
#define JC_TRACK_MAX_FRAMES 1000000L           /* frames of a clip, rows of a table */
#define JC_TRACK_MAX_TRACKS 16                 /* point-mass tracks, or track column groups */
#define JC_TRACK_NAME_LEN 64
#define JC_TRACK_MAX_COORD_M 1e6               /* a position farther from the origin is refused */

/* ---- the points as tracked: times and, per named track, positions ---- */

/* One tracked point (a track of Tracker's): its name and its positions in
 * Tracker's world axes, one per frame of the jc_TrackRaw holding it. */
typedef struct {
    char name[JC_TRACK_NAME_LEN];
    double *x_m, *y_m; /* world axes, metres; NaN where the frame has no position */
} jc_TrackPoints;

/* A file's content, or the caller's arrays: the frames' times and the
 * tracks' positions in Tracker's world axes (level axes: x level, y up;
 * or x laid along the incline, jc_TrackOptions.axes). Which track is the
 * centre and which the mark is told by the options' names, else by the
 * tracks' names and motion (jc_TrackOptions). */
typedef struct {
    long frames;          /* rows: clip steps or table rows */
    double *t_s;          /* time of each row (s), increasing */
    int track_count;      /* 1 to JC_TRACK_MAX_TRACKS */
    jc_TrackPoints tracks[JC_TRACK_MAX_TRACKS];
    double px_per_m;      /* the video's scale at its first frame; NaN: not known (a table) */
    int scale_varies;     /* origin, angle or scale differ between frames */
    double tape_length_m; /* a calibration tape's world length; NaN without one */
    double nominal_dt_s;  /* the clip's frame duration; NaN: taken from the times */
    char format[8];       /* "trk", "table", "model" (jc_track_synth_raw) or "arrays" */
} jc_TrackRaw;

/* An empty jc_TrackRaw for the caller's own arrays: no frames or tracks,
 * format "arrays", the scale, tape and frame duration not known (NaN).
 * Point t_s and the tracks' x_m, y_m at the caller's arrays, set frames,
 * track_count and the names; do not pass it to jc_track_raw_free. */
JC_API void jc_track_raw_init(jc_TrackRaw *raw);
/* Allocates frames rows of times (raw->t_s) and track_count tracks (their
 * x_m, y_m), all NaN, into an empty raw (jc_track_raw_init); sets frames
 * and track_count and leaves the other fields as they are. JC_OK, JC_EINVAL
 * (frames < 0, track_count outside 0 to JC_TRACK_MAX_TRACKS) or JC_ENOMEM
 * (raw then holds nothing to free). */
JC_API int jc_track_raw_alloc(jc_TrackRaw *raw, long frames, int track_count);
/* Frees what jc_track_raw_alloc, jc_track_synth_raw allocated; raw is left empty. */
JC_API void jc_track_raw_free(jc_TrackRaw *raw);
/* Writes raw as Tracker exports a data table (a "#multi:" line, the names
 * row, tab-separated, numbers to 7 digits), which jc_track_parse reads
 * back. The caller checks ferror(f) and fclose's result. */
JC_API void jc_track_write_table(FILE *f, const jc_TrackRaw *raw);

/* ---- how to read them ---- */

/* How the tracked world axes sit. */
typedef enum {
    JC_TRACK_AXES_LEVEL = 0,  /* Tracker's usual: x level, y up (vertical) */
    JC_TRACK_AXES_INCLINE = 1 /* tilted by the user: x along the incline, y its normal */
} jc_TrackAxes;

typedef struct {
    const char *centre;     /* the centre's track name; NULL: the track named like
                               centre, center, axle, axis, hub, or told by its motion */
    const char *mark;       /* the mark's track name; NULL: the track named like
                               mark, rod, dot, off, led, rim, light, lamp, spot, or told by
                               its motion; "" for none */
    double incline_rad;     /* α given, [0, π/2); NaN: measure it from the video */
    double radius_m;        /* rim radius r, > 0 */
    double gravity_mps2;    /* g, for flights fitted to a mark's frames */
    jc_TrackAxes axes;
    double hop_sigmas;      /* the hop threshold in units of sigma_m (>= 1) */
    long max_bytes;         /* files larger are refused (<= JC_TRACK_MAX_BYTES) */
    int fit_tilt;           /* 1: the surface is the line fitted through the frames in contact
                               even where it agrees with the incline given */
} jc_TrackOptions;

/* Defaults: no names, level axes, the incline measured (NaN), r = 10 cm
 * (callers set it from the setup), g = 9.81 m/s², a hop threshold of 5 σ,
 * JC_TRACK_MAX_BYTES. */
JC_API void jc_track_options_default(jc_TrackOptions *opt);

/* The bound that refuses a given incline: the frames in contact disagree
 * with it by more than 3 of their standard errors and by more than 2°. */
#define JC_TRACK_INCLINE_SIGMAS 3.0
#define JC_TRACK_INCLINE_TOL_RAD (2.0 * 3.14159265358979323846 / 180.0)

/* ---- what they tell: the track in the incline frame ---- */

/* Where the centre's positions come from. */
typedef enum {
    JC_TRACK_CENTRE_NONE = 0,  /* no centre: nothing beyond the tracks can be derived */
    JC_TRACK_CENTRE_TRACKED,   /* a track of the axle */
    JC_TRACK_CENTRE_FROM_MARK  /* recovered from a mark on the body by fitting rolling */
} jc_TrackCentreSource;

/* Where the incline's angle comes from. */
typedef enum {
    JC_TRACK_INCLINE_UNKNOWN = 0, /* axes laid along the incline and no angle given: the incline
                                     frame is known, its angle is not */
    JC_TRACK_INCLINE_MEASURED,    /* the line through the frames in contact (level axes) */
    JC_TRACK_INCLINE_GIVEN        /* given, and not refused: the frames in contact lie within 3 of their
                                     sigma or within 2 deg of it (JC_TRACK_INCLINE_SIGMAS, _TOL_RAD) */
} jc_TrackInclineSource;

/* What a video can tell, one note each. */
typedef enum {
    JC_TRACK_Q_CENTRE,  /* the centre's path */
    JC_TRACK_Q_SURFACE, /* the surface, the incline's angle, the noise */
    JC_TRACK_Q_HOPS,    /* heights above the surface, hops */
    JC_TRACK_Q_THETA,   /* the body's angle and spin */
    JC_TRACK_Q_COUNT
} jc_TrackQuantity;

#define JC_TRACK_NOTE_LEN 320

typedef struct {
    int ok;                        /* 1: derived (text says how well); 0: not (text says why) */
    char text[JC_TRACK_NOTE_LEN];  /* one or two sentences on one line, with their numbers */
} jc_TrackNote;

/* A hop: frames where the centre stands clearly above the surface. */
typedef struct {
    long first, last;        /* the frames above the threshold (indices into the track) */
    long peak;               /* the highest of them */
    double height_m;         /* the centre's highest point above contact; NaN: not resolved */
    double height_sigma_m;   /* its standard error */
    double bound_m;          /* unresolved: the most the data allow (mark-only tracks) */
    int fitted_flight;       /* the height is the peak of a flight fitted to a mark's frames */
} jc_TrackHop;

/* One tracked experiment in the incline frame, frame by frame. t_s strictly
 * increases. Coordinates are x down the incline (the direction the body went)
 * and y the outward normal, from the surface: the centre is at y = r in
 * contact. NaN marks a value a frame does not have. Free with jc_track_free. */
typedef struct {
    long n;                /* frames kept */
    double *t_s;           /* time of each frame (s), the clip's first frame at 0 */
    double *x_m, *y_m;     /* the centre C (NaN where it is unknown) */
    double *centre_sigma_m;/* the centre's standard error per frame: the noise for a tracked centre */
    double *mark_x_m, *mark_y_m; /* the off-centre mark (NaN where it was not tracked) */
    /* The mark's angle from the incline's normal, seen from C, growing as the
     * body rolls downhill, unwrapped; the mark need not be G: G's angle is
     * theta + the body's angle between the two. */
    double *theta_rad;
    double *omega_radps;   /* dθ/dt (central differences, or the recovered spline's) */
    unsigned char *contact;  /* 1: a frame the surface was placed through (rolling) */
    unsigned char *airborne; /* 1: in a hop */
    jc_TrackCentreSource centre_source;
    int has_mark;          /* a mark track was found and used */
    int centre_ambiguous;  /* several tracks and none could be told to be the centre */
    double x0_m;           /* where the centre starts along the incline (m) */
    double sigma_m;        /* the position noise of one tracked point (m), from the frames in
                              contact (at least 10 µm) */
    double frame_rate_hz;  /* nominal */
    double dt_jitter_s;    /* largest |dt - nominal| between kept frames */
    long gaps;             /* missing frames of the centre track (or the mark, without one) */
    char centre_name[JC_TRACK_NAME_LEN], mark_name[JC_TRACK_NAME_LEN];

    /* The surface and the incline. */
    jc_TrackInclineSource incline_source;
    double incline_rad;        /* α used (NaN when unknown) */
    double incline_sigma_rad;  /* its standard error when measured */
    double given_incline_rad;  /* what the caller gave (NaN: none) */
    int uphill;                /* the body went up a slope (the incline is then unknown) */
    double radius_m;           /* r used for the height above the surface */
    long contact_frames;       /* frames the surface was placed through (a centre recovered from a
                                  mark: the frames the rolling fit explains) */
    double surface_tilt_rad;   /* the line through them against the axes' x (level axes: the
                                  incline measured; incline axes: the axes' misalignment) */
    double surface_tilt_sigma_rad;
    double surface_sigma_m;    /* standard error of the surface's height at the frames' middle */

    /* Hops. */
    double hop_sigmas;         /* K: a hop is K sigma above the surface for at least 2 frames */
    double hop_threshold_m;    /* K sigma; with a mark alone also the smallest departure from
                                  rolling that shows */
    long hops;
    jc_TrackHop *hop;

    /* A centre recovered from a mark. */
    double mark_radius_m;      /* the mark's distance from C (the median, or the fitted) */
    double mark_radius_sigma_m;
    double centre_sigma_median_m; /* the median of centre_sigma_m over the frames with a centre ... */
    double centre_sigma_max_m;    /* ... and the largest (a mark alone tells the centre least as it
                                     passes the contact point) */
    long centre_left_out;      /* a centre recovered from a mark: frames left without one (its error there
                                  above 2 noises) */

    /* What the file held, for the report. */
    char format[8];                                         /* jc_TrackRaw's */
    int track_count;
    char track_names[JC_TRACK_MAX_TRACKS][JC_TRACK_NAME_LEN];
    long track_frames[JC_TRACK_MAX_TRACKS];                 /* frames with a position */
    long clip_frames;        /* frames of the clip (steps), or rows of the table */
    double scale_px_per_m;   /* the coordinate system's scale (the first frame's);
                                NaN for a table, already in metres */
    int scale_varies;        /* the scale or axes change from frame to frame */
    double tape_length_m;    /* the calibration tape's world length; NaN if none */
    int axes;                /* jc_TrackAxes used */
    jc_TrackNote note[JC_TRACK_Q_COUNT];
} jc_Track;

/* Reads a Tracker .trk file (XML) or an exported data table (told by the
 * content, not the name), picks the centre and mark tracks, converts to the
 * incline frame and derives what the tracks tell. JC_OK for a readable file,
 * whatever it tells (the notes say what could not be derived, and why);
 * JC_EINVAL with "PATH: what is wrong" when the file cannot be read or is
 * not a track file, when a track named in opt is not in it, or when the
 * incline given disagrees with the frames in contact; JC_ENOMEM. On
 * failure out holds nothing to free. */
JC_API int jc_track_read_file(const char *path, const jc_TrackOptions *opt, jc_Track *out, char *err,
                              size_t err_len);
/* The same for a file's bytes in memory; name stands for the file in messages. */
JC_API int jc_track_parse(const char *name, const char *data, size_t len, const jc_TrackOptions *opt,
                          jc_Track *out, char *err, size_t err_len);
/* The same for tracks already in arrays (a reader's, jc_track_synth_raw's,
 * or the caller's: jc_track_raw_init); raw is only read. */
JC_API int jc_track_from_raw(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, jc_Track *out,
                             char *err, size_t err_len);

/* What an analysis needs of a track, checked after a read. */
enum {
    JC_TRACK_NEED_CENTRE = 1,  /* the centre's path and the surface */
    JC_TRACK_NEED_INCLINE = 2  /* the incline's angle */
};
/* JC_OK, or JC_EINVAL with "NAME: what is missing and why" (the note's words). */
JC_API int jc_track_require(const char *name, const jc_Track *t, unsigned needs, char *err, size_t err_len);

/* Frees a track's arrays; t is left empty. NULL or an empty track: nothing. */
JC_API void jc_track_free(jc_Track *t);

/* ---- the model against a track ---- */

/* Every run against a track lengthens the ramp uphill by this margin, so
 * that a start estimated a little above the ramp's top (noise) is still on
 * it; positions along the track are the run's less the margin. */
#define JC_TRACK_RAMP_MARGIN_M 1.0

/* The setup as runs against the track use it: the ramp lengthened uphill by
 * JC_TRACK_RAMP_MARGIN_M and downhill to hold every frame (t may be NULL:
 * the margin only). The incline stays the setup's: compare and fit take
 * the track's (jc_Track.incline_rad). */
JC_API jc_Setup jc_track_setup(const jc_Setup *setup, const jc_Track *t);

/* The mark's distance from C: the track's when it has one, else the
 * off-centre part of the model's body farthest from C (else its radius). */
JC_API double jc_track_mark_radius(const jc_Track *t, const jc_Model *m);

/* How a fit places the video's frame on the model's, beside the setup and
 * the start: the mark's angle on the body (a part's angle; 0: the reference
 * direction, where the paper's rod and the hoop's mass sit), and the video
 * frame's tilt and the surface's height. The video's frame was turned onto
 * the surface the frames in contact show, which is known to the noise: the
 * model's positions are turned by tilt_rad about the start and moved up by
 * surface_m before they meet the frames, and a measured incline is the
 * video's plus the tilt. */
typedef struct {
    double mark_angle_rad;
    double tilt_rad;
    double surface_m;
} jc_TrackFitFrame;

/* The model run from start (track coordinates, G's angle: a jc_TrackLaunch's
 * or jc_TrackFitResult's start) with the setup's values, its θ0 and ω0 taken
 * from start, on the ramp jc_track_setup makes, sampled at the n times t_s
 * (increasing, at or after start->t_s; past the run's end the body flies
 * on freely): the centre into x_m, y_m and the mark's angle into
 * mark_theta_rad (NULL: not wanted), in the video's frame placed by frame
 * (NULL: the mark at angle 0, no tilt, no surface offset). Between the
 * simulator's samples, a fraction of a frame apart, values are
 * interpolated (cubic Hermite; linear across an impact). JC_OK, or a status
 * with a message (the setup refused, JC_ENOMEM, the simulator's failure). */
JC_API int jc_track_model_path(const jc_Setup *setup, const jc_Track *t, const jc_State *start,
                               const jc_TrackFitFrame *frame, const jc_SimOptions *o, const double *t_s, long n,
                               double *x_m, double *y_m, double *mark_theta_rad, char *err, size_t err_len);

/* The residuals of frame j of t (an index into it) against the model's
 * centre (x_m, y_m) and mark angle mark_theta_rad, in units of sigma_m,
 * into f: the centre's along and across the incline, then (mark_radius_m
 * > 0 and θ tracked at j) the mark's displacement across its radius
 * a Δθ + Δx cos θ − Δy sin θ; or, with a centre recovered from the mark,
 * the mark's own x and y. Returns how many (0: nothing tracked at j); f[k]
 * is of series k. These are the residuals jc_track_fit minimizes. */
JC_API int jc_track_residuals_frame(const jc_Track *t, long j, double sigma_m, double mark_radius_m, double x_m,
                                    double y_m, double mark_theta_rad, double f[3]);

/* ---- where the free motion starts, and the comparison ---- */

/* The free motion's first frame: a clip often begins with a hand holding
 * or pushing the body, frames the model cannot follow. */
typedef struct {
    long frame;            /* the first frame of the free motion (an index into the track) */
    long pushed;           /* frames before it that the model cannot follow (a hand) */
    double chi2_dof_with;  /* the first window's fit with the pushed frames in; NaN when none */
    double chi2_dof;       /* the window's fit from the start found */
    jc_State start;        /* the state there, fitted to the next 0.4 s (track coordinates, G's angle) */
} jc_TrackLaunch;

#define JC_TRACK_MAX_HOPS 64
/* Hops seen in a sampled height: runs of at least 2 frames whose centre is
 * more than a threshold above r. */
typedef struct {
    int hops;                            /* runs (at most JC_TRACK_MAX_HOPS kept) */
    double first_liftoff_t_s;            /* the last frame in contact before the first hop; NaN if none */
    double first_liftoff_x_m;
    long first[JC_TRACK_MAX_HOPS], last[JC_TRACK_MAX_HOPS]; /* frames of each (indices into the frames compared) */
    double height_m[JC_TRACK_MAX_HOPS];  /* highest centre above r in each hop */
} jc_TrackHops;

/* Where the model starts from. */
typedef enum {
    JC_TRACK_START_TRACKED, /* the state the frames show at the free motion's first frame */
    JC_TRACK_START_SETUP    /* the setup's θ0 and ω0 at the first tracked position, rolling */
} jc_TrackStartKind;

/* A track against the model. Free with jc_track_compare_free. */
typedef struct {
    long first, count;             /* the frames compared */
    jc_TrackLaunch launch;         /* the start (the free motion's first frame) */
    double *x_m, *y_m, *theta_rad; /* the model at the frames (theta: the mark's) */
    double rms_path_m;             /* centre: sqrt(mean(dx^2 + dy^2)) over frames with a centre */
    double rms_theta_rad;          /* over frames with the mark; NaN without */
    double max_path_m;
    jc_TrackHops measured, simulated; /* the same detector on both, at the track's hop threshold */
    /* The model's own events (exact times): */
    int model_liftoffs, model_bounces;
    double model_liftoff_t_s, model_liftoff_x_m; /* NaN if none */
    double model_largest_hop_m;
} jc_TrackCompare;

/* Runs the model from the free motion's first frame in the window
 * [from_s, to_s] (NaN: open ends) and compares it with the frames. With
 * JC_TRACK_START_TRACKED the start is the state the frames show there:
 * frames a hand pushes are found and left out when from_s is NaN (from_s
 * given: the start is there), and x0, ω0 and θ0 are fitted to the next
 * 0.4 s. The incline is the track's (jc_track_require's
 * JC_TRACK_NEED_CENTRE | JC_TRACK_NEED_INCLINE must hold); mark_angle_rad
 * is the tracked mark's angle on the body. JC_OK, or a status with a
 * message (out then holds nothing to free). */
JC_API int jc_track_compare(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, jc_TrackStartKind start,
                            double from_s, double to_s, double mark_angle_rad, jc_TrackCompare *out, char *err,
                            size_t err_len);
JC_API void jc_track_compare_free(jc_TrackCompare *c);

/* ---- the fit ---- */

/* The values a fit can free. */
typedef enum {
    JC_FIT_MU_S,
    JC_FIT_MU_K,
    JC_FIT_RESTITUTION,
    JC_FIT_THETA0,      /* the start's (at the free motion's first frame) */
    JC_FIT_OMEGA0,
    JC_FIT_X0,
    JC_FIT_MARK_ANGLE,  /* the mark's angle on the body */
    JC_FIT_TILT,        /* the video's frame against the model's incline frame (jc_TrackFitFrame) */
    JC_FIT_SURFACE,     /* the surface's height in the video's frame */
    JC_FIT_PART_OFFSET, /* a body part's distance from C (part: which) */
    JC_FIT_PART_MASS    /* a body part's mass */
} jc_TrackFitKind;

typedef struct {
    jc_TrackFitKind kind;
    int part;            /* the body part (an index into setup.body.parts), for the last two; else -1 */
} jc_TrackFitParam;

#define JC_FIT_MAX_PARAMS 14

/* A value's name ("mu_s", "rod_offset", ...) into buf. */
JC_API void jc_fit_param_name(const jc_Setup *s, jc_TrackFitParam p, char *buf, size_t len);
/* Its unit ("", "rad", "rad/s", "m", "kg"). */
JC_API const char *jc_fit_param_unit(jc_TrackFitParam p);
/* The value a name means for the setup's body: mu_s, mu_k, restitution,
 * theta0, omega0, x0, mark_angle, tilt, surface, and KIND_mass and
 * KIND_offset for the first part of a kind (disc, hoop, rod, point; no
 * offset for the centred disc and hoop); '-' may stand for '_', in any
 * case. JC_OK, or JC_EINVAL for a name the body does not allow. */
JC_API int jc_fit_param_find(const jc_Setup *s, const char *name, jc_TrackFitParam *out);
/* The values the setup's body allows, in the order above, into out (at
 * most cap of them). Returns how many there are. */
JC_API int jc_fit_param_list(const jc_Setup *s, jc_TrackFitParam *out, int cap);

/* How residuals count. */
typedef enum {
    JC_FIT_LOSS_LINEAR, /* least squares */
    JC_FIT_LOSS_HUBER,  /* robust, by reweighting: Huber's weights at 1.345 */
    JC_FIT_LOSS_CAUCHY  /* Cauchy's at 2.385 */
} jc_TrackFitLoss;
/* "linear", "huber", "cauchy". */
JC_API const char *jc_fit_loss_name(jc_TrackFitLoss loss);
/* JC_OK, or JC_EINVAL for another name. */
JC_API int jc_fit_loss_parse(const char *name, jc_TrackFitLoss *out);

/* What a fit reports as it goes (jc_TrackFitOptions.progress). */
typedef struct {
    const char *stage;  /* what it is doing, in words ("descents from the best start points", ...) */
    int descents;       /* descents begun in this stage */
    double fraction;    /* of the whole fit done: a rough estimate in [0, 1], never decreasing */
} jc_TrackFitProgress;
/* Called as each descent begins and after each of its iterations, and once
 * with fraction 1 at the end. Returns 0 to go on; anything else stops the
 * fit, which then returns JC_ESTOPPED. */
typedef int (*jc_TrackFitProgressFn)(void *ctx, const jc_TrackFitProgress *p);

typedef struct {
    jc_TrackFitParam free[JC_FIT_MAX_PARAMS]; /* the values asked for */
    int free_count;        /* the start's 3 and the frame's 2 join them (unless held or named here):
                              at most JC_FIT_MAX_PARAMS in all, so up to 9 always fit */
    int hold_start;        /* 0: x0, θ0 and ω0 are fitted with them (the start is never exact);
                              1: held at the start fitted to the first 0.4 s */
    int hold_frame;        /* 0: the frame's tilt and surface are fitted with them (with a
                              measured incline, the incline with the tilt) */
    jc_TrackFitLoss loss;
    double from_s, to_s;   /* window; NaN: open (from_s NaN: the free motion's start is found) */
    int max_iter;          /* trust-region iterations per descent, > 0 */
    double sigma_m;        /* position noise; <= 0: the track's (measured: σ are then scaled by chi2/dof) */
    jc_TrackStartKind start;   /* the start's values: tracked (estimated) or the setup's */
    int starts;            /* start points screened over the bounded values (0: by the count of them) */
    int descents;          /* best screened points descended from (0: 3) */
    uint64_t seed;         /* the screening's Latin hypercube (Philox): the same fit for the same seed */
    double mark_angle_rad; /* the mark's angle on the body, when not fitted */
    int profiles;          /* 1: a chi2 profile for each value not determined */
    jc_TrackFitProgressFn progress; /* NULL: none (the fit prints nothing itself) */
    void *progress_ctx;
    int start_window;      /* 0: a fit: the free motion's first frame is found and the start's
                              values fitted alone to its first 0.4 s first (a start estimated
                              from a few frames is far off, and every descent would begin from
                              it); 1: such a fit of the start itself, which works out the values
                              and chi2 only (no lift-off, RMS, verdict or profiles) */
} jc_TrackFitOptions;

/* Defaults: nothing free, the start and frame fitted, linear loss, the
 * whole track, 100 iterations, the track's noise, the tracked start, the
 * screening's own count of points, 3 descents, seed 1, mark angle 0,
 * profiles on, no progress callback. */
JC_API void jc_fit_options_default(jc_TrackFitOptions *o);

/* Why a value was taken out of the fit. */
typedef enum {
    JC_FIT_DETERMINED = 0,
    JC_FIT_ON_BOUND,         /* it sits on a bound of its range */
    JC_FIT_WIDER_THAN_RANGE, /* its sigma exceeds its range */
    JC_FIT_CORRELATED,       /* |rho| > 0.99 with another value */
    JC_FIT_NO_EFFECT         /* the residuals do not change with it */
} jc_TrackFitFlag;
/* A sentence for a flag ("it sits on a bound of its range ..."). */
JC_API const char *jc_fit_flag_text(jc_TrackFitFlag f);

#define JC_FIT_MAX_MINIMA 6
#define JC_FIT_PROFILE_POINTS 9

typedef struct {
    double value[JC_FIT_MAX_PARAMS]; /* SI, in the order of jc_TrackFitResult.param */
    double chi2;
} jc_TrackFitMinimum;

typedef struct {
    int count;                        /* the values asked for, then the start's and the frame's */
    jc_TrackFitParam param[JC_FIT_MAX_PARAMS];
    int start_value[JC_FIT_MAX_PARAMS]; /* 1: x0, θ0, ω0, tilt, surface added by the fit */
    double initial[JC_FIT_MAX_PARAMS], value[JC_FIT_MAX_PARAMS], sigma[JC_FIT_MAX_PARAMS]; /* SI */
    double lo[JC_FIT_MAX_PARAMS], hi[JC_FIT_MAX_PARAMS]; /* ranges */
    jc_TrackFitFlag flag[JC_FIT_MAX_PARAMS]; /* JC_FIT_DETERMINED, or why it was held */
    int other[JC_FIT_MAX_PARAMS];    /* JC_FIT_CORRELATED: the value it moves with */
    double rho[JC_FIT_MAX_PARAMS];   /* that correlation */
    double corr[JC_FIT_MAX_PARAMS][JC_FIT_MAX_PARAMS]; /* of the values fitted at the end */
    long residuals;                   /* n */
    double chi2, chi2_dof;            /* of the residuals in units of sigma */
    long dof;                         /* residuals less the values fitted at the end */
    int noise_measured;               /* sigma from the track: sigmas scaled by sqrt(chi2/dof) */
    int iterations;                   /* trust-region iterations, all descents */
    int screened, descents;           /* start points evaluated, descents made */
    int minima;                       /* distinct minima within the threshold of the best (>= 1) */
    jc_TrackFitMinimum minimum[JC_FIT_MAX_MINIMA];
    double delta_chi2;                /* the threshold for a competing minimum */
    /* chi2 along each held value's range, the others fitted at each point */
    int profiled[JC_FIT_MAX_PARAMS];
    double profile_x[JC_FIT_MAX_PARAMS][JC_FIT_PROFILE_POINTS];
    double profile_chi2[JC_FIT_MAX_PARAMS][JC_FIT_PROFILE_POINTS];
    jc_Setup setup;                   /* the setup with the fitted values (the track's incline) */
    jc_State start;                   /* the fitted start (track coordinates) */
    jc_TrackFitFrame frame;           /* the fitted mark angle and frame */
    double incline_sigma_rad;         /* the fitted incline's, when it was measured (the tilt's) */
    jc_TrackLaunch launch;
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
} jc_TrackFitResult;

/* Fits the free values, with the start's and the frame's, to the track's
 * frames in the window by nonlinear least squares (GSL's
 * gsl_multifit_nlinear, Levenberg-Marquardt): a Latin hypercube over the
 * bounded values screened and the best few points descended from, the
 * values the video does not determine held (with a chi2 profile), the
 * predicted first lift-off, and the verdict (docs/tracker.md, "Fit"). The
 * track must have a centre and an incline (jc_track_require); the setup's
 * values not freed are held, the freed ones start from it. JC_OK, or
 * JC_EINVAL (bad options, too few frames, a setup the model refuses),
 * JC_ENOMEM, JC_ESTOPPED (the progress callback asked) with a message. */
JC_API int jc_track_fit(const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o,
                        const jc_SimOptions *sim, jc_TrackFitResult *out, char *err, size_t err_len);

/* ---- synthetic videos: the model filmed and tracked ---- */

typedef enum {
    JC_TRACK_SYNTH_BOTH = 0,    /* the centre and the mark */
    JC_TRACK_SYNTH_CENTRE_ONLY, /* the centre alone */
    JC_TRACK_SYNTH_MARK_ONLY    /* the mark alone (an LED on the rim) */
} jc_TrackSynthTracks;

typedef struct {
    double fps_hz;         /* frame rate, (0, 1e5] */
    double sigma_m;        /* Gaussian noise on every tracked point (m), [0, 1) */
    double t_end_s;        /* last frame at or before this time (s), (0, 3600]; the run's end if sooner */
    double mark_radius_m;  /* distance of the tracked mark from C; 0: no mark tracked */
    double drop_fraction;  /* frames left out at random, [0, 0.5] */
    uint64_t seed;         /* Philox key: the same track for the same seed and trial */
    uint64_t trial;        /* Philox sample index: independent tracks for one seed */
    jc_TrackSynthTracks tracks;
    double mark_angle_rad; /* the mark's angle on the body (as a part's angle); 0: the reference direction */
    double hand_s;         /* frames of a hand pushing the body from rest up to the start's spin
                              before the free motion, [0, 10] s (0: none); the clip starts with them */
} jc_TrackSynthOptions;

/* The setup's run from its start filmed at fps_hz as Tracker's level axes
 * hold it (metres, the start's contact point at the origin, downhill to the
 * right), each tracked point with independent noise, format "model"; the
 * tracks are named "centre" and "mark" ("LED" for a mark alone). JC_OK, or
 * a status with a message (raw then holds nothing to free). Free raw with
 * jc_track_raw_free. */
JC_API int jc_track_synth_raw(const jc_Setup *setup, const jc_TrackSynthOptions *o, jc_TrackRaw *raw, char *err,
                              size_t err_len);
/* The same read as a file is (jc_track_from_raw): the incline measured, the
 * setup's radius and g. */
JC_API int jc_track_synthesize(const jc_Setup *setup, const jc_TrackSynthOptions *o, jc_Track *out, char *err,
                               size_t err_len);

#ifdef __cplusplus
}
#endif

#endif /* JUMPCYL_TRACK_H */
