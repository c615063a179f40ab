/* Tracked experiments (docs/tracker.md): positions tracked in a video with
 * Tracker (Open Source Physics), read from its .trk files or exported data
 * tables, converted to the incline frame of docs/physics.md §1, and compared
 * with or fitted by the model. */
#ifndef JUMPCYL_TRACK_H
#define JUMPCYL_TRACK_H

#include "cli.h"

#include <stddef.h>

/* Bounds on what a file may hold: a larger file is refused, not truncated. */
#define CLI_TRACK_MAX_BYTES (64L * 1024 * 1024) /* default file size bound */
#define CLI_TRACK_MAX_FRAMES 1000000L           /* frames of a clip, rows of a table */
#define CLI_TRACK_MAX_TRACKS 16                 /* point-mass tracks, or track column groups */
#define CLI_TRACK_NAME_LEN 64

/* One tracked experiment in the incline frame, frame by frame. Frames where
 * the centre is missing are left out; t_s strictly increases. */
typedef struct {
    long n;                /* frames kept */
    double *t_s;           /* time of each frame (s), the clip's first frame at 0 */
    double *x_m, *y_m;     /* centre C: along the incline (downhill) from where
                              the first frame has it plus x0_m, and height above
                              the incline's surface (r in contact) */
    /* The tracked off-centre mark: its angle as θ of docs/physics.md (from the
     * incline's normal, growing as the body rolls downhill), unwrapped; NaN in
     * every frame where the mark is missing, or all NaN when no mark is tracked.
     * The mark need not be G: G's angle is theta + the setup's offset between
     * the mark and G (0 for the paper's cylinder, whose rod is its only
     * off-centre part). */
    double *theta_rad;
    int has_mark;          /* a mark track was found and used */
    double x0_m;           /* where the centre starts along the incline (m) */
    double sigma_m;        /* a pixel in metres: the position noise to expect */
    double frame_rate_hz;  /* nominal */
    double dt_jitter_s;    /* largest |dt - nominal| between kept frames */
    long gaps;             /* missing frames of the centre track */
    char centre_name[CLI_TRACK_NAME_LEN], mark_name[CLI_TRACK_NAME_LEN];

    /* Derived (derive.c). */
    double *omega_radps;     /* dθ/dt by central differences over neighbouring
                                kept frames (one-sided at the ends); NaN where
                                θ or a neighbour's θ is */
    unsigned char *airborne; /* 1 where y_m > radius_m + hop_sigmas σ: in a hop */
    long hops;               /* runs of airborne frames */
    double incline_rad;      /* α used for the conversion */
    double radius_m;         /* r used for the height above the surface */
    double hop_threshold_m;  /* y_m above radius_m + this is airborne */
    double mark_radius_m;    /* median distance of the mark from C; NaN without */
    double noise_m;          /* position noise estimated from the centre's third
                                differences (robust: MAD); sigma_m is the larger of
                                this and a pixel */
    double surface_tilt_rad; /* angle of the line through the frames in contact
                                against the incline's x axis: a check of α and
                                the axes (removed from y_m with fit_tilt) */

    /* What the file held, for the report. */
    char format[8];                                         /* "trk" or "table" */
    int track_count;
    char track_names[CLI_TRACK_MAX_TRACKS][CLI_TRACK_NAME_LEN];
    long track_frames[CLI_TRACK_MAX_TRACKS];                /* frames with a position */
    long clip_frames;        /* frames of the clip (steps), or rows of the table */
    double scale_px_per_m;   /* the coordinate system's scale (the first frame's);
                                NaN for a table, already in metres */
    int scale_varies;        /* the scale or axes change from frame to frame */
    double tape_length_m;    /* the calibration tape's world length; NaN if none */
} cli_Track;

/* How the tracked world axes sit. */
typedef enum {
    CLI_TRACK_AXES_LEVEL = 0,  /* Tracker's usual: x level, y up (vertical) */
    CLI_TRACK_AXES_INCLINE = 1 /* tilted by the user: x along the incline, y its normal */
} cli_TrackAxes;

typedef struct {
    const char *centre;     /* the centre's track name; NULL: the track named like
                               centre, center, axle, axis, or the only track */
    const char *mark;       /* the mark's track name; NULL: the track named like
                               mass, mark, rod, or none; "" for none */
    double incline_rad;     /* α, [0, π/2) */
    double radius_m;        /* rim radius r, > 0 */
    cli_TrackAxes axes;
    double hop_sigmas;      /* the hop threshold in units of sigma_m (≥ 1) */
    long max_bytes;         /* files larger are refused (≤ CLI_TRACK_MAX_BYTES) */
    int fit_tilt;           /* 1: the surface is the line fitted through the frames
                               in contact (axes set by eye); 0: parallel to the
                               incline's x axis, only its height fitted */
} cli_TrackOptions;

/* Defaults: no names, level axes, 30° and the paper's r (callers set both
 * from the setup), a hop threshold of 5 σ, CLI_TRACK_MAX_BYTES. */
void cli_track_options_default(cli_TrackOptions *opt);

/* Reads a Tracker .trk file (XML) or an exported data table (by content,
 * not by name), picks the centre and mark tracks, converts to the incline
 * frame and derives θ, ω, the height and the hops. 0, or -1 with a one-line
 * message "PATH: what is wrong" in err (out then holds nothing to free). */
int cli_track_load(const char *path, const cli_TrackOptions *opt, cli_Track *out, char *err, size_t err_len);
/* The same for bytes in memory; name stands for the file in messages. */
int cli_track_parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                    char *err, size_t err_len);

void cli_track_free(cli_Track *t);

#endif /* JUMPCYL_TRACK_H */
