/* Tracked experiments (docs/tracker.md): positions tracked in a video with
 * Tracker (Open Source Physics), read from its .trk files or exported data
 * tables, put in the incline frame of docs/physics.md §1, with what they
 * tell of the centre, the surface, the noise, θ and the hops.
 *
 * Every function here works on arrays (times, points) and values, prints
 * nothing and never exits: what a file cannot tell is said in the track's
 * notes, for the caller to show. Only <jumpcyl/jumpcyl.h> is needed. */
#ifndef JUMPCYL_TRACK_H
#define JUMPCYL_TRACK_H

#include <jumpcyl/jumpcyl.h>

#include <stddef.h>

/* Bounds on what a file may hold: a larger file is refused, not truncated. */
#define CLI_TRACK_MAX_BYTES (64L * 1024 * 1024) /* default file size bound */
#define CLI_TRACK_MAX_FRAMES 1000000L           /* frames of a clip, rows of a table */
#define CLI_TRACK_MAX_TRACKS 16                 /* point-mass tracks, or track column groups */
#define CLI_TRACK_NAME_LEN 64
#define CLI_TRACK_MAX_COORD_M 1e6                /* a position farther from the origin is refused */
#define CLI_TRACK_PI 3.14159265358979323846

/* Where the centre's positions come from. */
typedef enum {
    CLI_CENTRE_NONE = 0,  /* no centre: nothing beyond the tracks can be derived */
    CLI_CENTRE_TRACKED,   /* a track of the axle */
    CLI_CENTRE_FROM_MARK  /* recovered from a mark on the body by fitting rolling (rim.c) */
} cli_CentreSource;

/* Where the incline's angle comes from. */
typedef enum {
    CLI_INCLINE_UNKNOWN = 0, /* axes laid along the incline and no angle given: the incline
                                frame is known, its angle is not */
    CLI_INCLINE_MEASURED,    /* the line through the frames in contact (level axes) */
    CLI_INCLINE_GIVEN        /* given, and not refused: the frames in contact lie within 3 of their
                                sigma or within 2 deg of it (CLI_TRACK_INCLINE_SIGMAS, _TOL_RAD) */
} cli_InclineSource;

/* What a video can tell, one line each in the report. */
typedef enum {
    CLI_Q_CENTRE, /* the centre's path */
    CLI_Q_SURFACE, /* the surface, the incline's angle, the noise */
    CLI_Q_HOPS,   /* heights above the surface, hops */
    CLI_Q_THETA,  /* the body's angle and spin */
    CLI_Q_COUNT
} cli_TrackQuantity;

#define CLI_TRACK_NOTE_LEN 320

typedef struct {
    int ok;                         /* 1: derived (text says how well); 0: not (text says why) */
    char text[CLI_TRACK_NOTE_LEN];  /* one or two sentences, the tool's own words and numbers */
} cli_TrackNote;

/* A hop: frames where the centre stands clearly above the surface. */
typedef struct {
    long first, last;        /* the frames above the threshold (indices into the track) */
    long peak;               /* the highest of them */
    double height_m;         /* the centre's highest point above contact; NaN: not resolved */
    double height_sigma_m;   /* its standard error */
    double bound_m;          /* unresolved: the most the data allow (mark-only tracks) */
    int fitted_flight;       /* the height is the peak of a flight fitted to a mark's frames */
} cli_TrackHop;

/* One tracked experiment in the incline frame, frame by frame. t_s strictly
 * increases. Coordinates are x down the incline (the direction the body went)
 * and y the outward normal, from the surface: the centre is at y = r in
 * contact. NaN marks a value a frame does not have. */
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
    cli_CentreSource centre_source;
    int has_mark;          /* a mark track was found and used */
    int centre_ambiguous;  /* several tracks and none could be told to be the centre */
    double x0_m;           /* where the centre starts along the incline (m) */
    double sigma_m;        /* the position noise of one tracked point (m), from the frames in
                              contact (at least 10 µm) */
    double frame_rate_hz;  /* nominal */
    double dt_jitter_s;    /* largest |dt - nominal| between kept frames */
    long gaps;             /* missing frames of the centre track (or the mark, without one) */
    char centre_name[CLI_TRACK_NAME_LEN], mark_name[CLI_TRACK_NAME_LEN];

    /* The surface and the incline. */
    cli_InclineSource incline_source;
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
    cli_TrackHop *hop;

    /* A centre recovered from a mark (rim.c). */
    double mark_radius_m;      /* the mark's distance from C (the median, or the fitted) */
    double mark_radius_sigma_m;
    double centre_sigma_median_m; /* the median of centre_sigma_m over the frames with a centre ... */
    double centre_sigma_max_m;    /* ... and the largest (a mark alone tells the centre least as it
                                     passes the contact point) */
    long centre_left_out;      /* a centre recovered from a mark: frames left without one (its error there
                                  above 3 noises) */

    /* What the file held, for the report. */
    char format[8];                                         /* "trk", "table" or "model" */
    int track_count;
    char track_names[CLI_TRACK_MAX_TRACKS][CLI_TRACK_NAME_LEN];
    long track_frames[CLI_TRACK_MAX_TRACKS];                /* frames with a position */
    long clip_frames;        /* frames of the clip (steps), or rows of the table */
    double scale_px_per_m;   /* the coordinate system's scale (the first frame's);
                                NaN for a table, already in metres */
    int scale_varies;        /* the scale or axes change from frame to frame */
    double tape_length_m;    /* the calibration tape's world length; NaN if none */
    int axes;                /* cli_TrackAxes used */
    cli_TrackNote note[CLI_Q_COUNT];
} cli_Track;

/* How the tracked world axes sit. */
typedef enum {
    CLI_TRACK_AXES_LEVEL = 0,  /* Tracker's usual: x level, y up (vertical) */
    CLI_TRACK_AXES_INCLINE = 1 /* tilted by the user: x along the incline, y its normal */
} cli_TrackAxes;

typedef struct {
    const char *centre;     /* the centre's track name; NULL: the track named like
                               centre, center, axle, axis, hub, or told by its motion */
    const char *mark;       /* the mark's track name; NULL: the track named like
                               mark, rod, dot, off, led, rim, light, lamp, spot, or told by
                               its motion; "" for none */
    double incline_rad;     /* α given, [0, π/2); NaN: measure it from the video */
    double radius_m;        /* rim radius r, > 0 */
    double gravity_mps2;    /* g, for flights fitted to a mark's frames */
    cli_TrackAxes axes;
    double hop_sigmas;      /* the hop threshold in units of sigma_m (>= 1) */
    long max_bytes;         /* files larger are refused (<= CLI_TRACK_MAX_BYTES) */
    int fit_tilt;           /* 1: the surface is the line fitted through the frames in contact
                               even where it agrees with the incline given */
} cli_TrackOptions;

/* Defaults: no names, level axes, the incline measured (NaN), r = 10 cm
 * (callers set it from the setup), a hop threshold of 5 σ,
 * CLI_TRACK_MAX_BYTES. */
void cli_track_options_default(cli_TrackOptions *opt);

/* The bound that refuses a given incline: the frames in contact disagree
 * with it by more than 3 of their standard errors and by more than 2°. */
#define CLI_TRACK_INCLINE_SIGMAS 3.0
#define CLI_TRACK_INCLINE_TOL_RAD (2.0 * CLI_TRACK_PI / 180.0)

/* Reads a Tracker .trk file (XML) or an exported data table (by content,
 * not by name), picks the centre and mark tracks, converts to the incline
 * frame and derives what the tracks tell. 0 for a readable file, whatever
 * it tells (the notes say what could not be derived, and why); -1 with a
 * one-line message "PATH: what is wrong" in err when the file cannot be
 * read or is not a track file, or when the incline given disagrees with
 * the frames in contact (out then holds nothing to free). */
int cli_track_load(const char *path, const cli_TrackOptions *opt, cli_Track *out, char *err, size_t err_len);
/* The same for bytes in memory; name stands for the file in messages. */
int cli_track_parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                    char *err, size_t err_len);

/* What an analysis needs of a track, checked after a load. */
enum {
    CLI_NEED_CENTRE = 1,  /* the centre's path and the surface */
    CLI_NEED_INCLINE = 2  /* the incline's angle */
};
/* 0, or -1 with "NAME: what is missing and why" (the note's words). */
int cli_track_require(const char *name, const cli_Track *t, unsigned needs, char *err, size_t err_len);

void cli_track_free(cli_Track *t);

#endif /* JUMPCYL_TRACK_H */
