/*
 * jumpcyl/track.h: tracked videos (docs/tracker.md, docs/api.md "Tracked
 * videos and fits"). Positions tracked in a video with Tracker (Open Source
 * Physics), read from its .trk files or its exported data tables, or given
 * as arrays, are put in the incline frame of docs/physics.md §1 with what
 * they tell of the centre, the surface, the noise, θ and the hops.
 *
 * The conventions of <jumpcyl/jumpcyl.h> hold: SI units and radians, int
 * status codes (JC_OK, JC_EINVAL, JC_ENOMEM, ...) with a one-line message in
 * a caller's buffer, no global mutable state. Nothing here prints or exits.
 * What a video cannot tell is not an error: the track's notes say it, for
 * the caller to show.
 *
 * Reading .trk files uses libxml2 (linked into libjumpcyl), which keeps its
 * own process-wide parser state, set up once and thread-safe.
 */
#ifndef JUMPCYL_TRACK_H
#define JUMPCYL_TRACK_H

#include <jumpcyl/jumpcyl.h>

#include <stddef.h>
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

#ifdef __cplusplus
}
#endif

#endif /* JUMPCYL_TRACK_H */
