/* What a track file holds before it is put in the incline frame: positions
 * in Tracker's world axes (metres), one row per frame; and the steps from
 * it to a cli_Track. Shared by the readers and the table writer (trk.c,
 * table.c), the conversion (frame.c), the derivation (surface.c, rim.c,
 * derive.c), the whole of it (load.c), and synthetic.c, which makes raw
 * data from the model (as do the tests, tests/track and tests/fit). */
#ifndef JUMPCYL_TRACK_RAW_H
#define JUMPCYL_TRACK_RAW_H

#include "track.h"

#include <math.h>
#include <stdio.h>

typedef struct {
    char name[CLI_TRACK_NAME_LEN];
    double *x_m, *y_m; /* world axes, metres; NaN where the frame has no position */
} cli_RawTrack;

typedef struct cli_RawData_s {
    long frames;          /* rows: clip steps or table rows */
    double *t_s;          /* time of each row */
    int track_count;
    cli_RawTrack tracks[CLI_TRACK_MAX_TRACKS];
    double px_per_m;      /* scale of the first frame; NaN for a table */
    int scale_varies;     /* origin, angle or scale differ between frames */
    double tape_length_m; /* NaN without a calibration tape */
    double nominal_dt_s;  /* the clip's frame duration; NaN for a table */
    char format[8];
} cli_RawData;

/* Each reader fills raw (zeroed first) or returns -1 with "NAME: message". */
int cli_trk_parse(const char *name, const char *data, size_t len, cli_RawData *raw, char *err, size_t err_len);
int cli_table_parse(const char *name, const char *data, size_t len, cli_RawData *raw, char *err, size_t err_len);
/* table.c: raw data written as Tracker exports a table (tab-separated, a
 * name row), which cli_table_parse reads back. 0, or -1 on a write error. */
int cli_track_write_table(FILE *f, const cli_RawData *raw);
/* Allocates frames rows for the times and track_count tracks (NaN filled). 0 or -1. */
int cli_raw_alloc(cli_RawData *raw, long frames, int track_count);
void cli_raw_free(cli_RawData *raw);

/* The angle Tracker's level axes are turned by to put the tracks in the
 * incline frame: the incline given, or none (no incline given: the video's
 * is measured; incline axes: taken as they are). derive.c then turns the
 * frame onto the surface the frames in contact show. */
static inline double cli_track_frame_angle(const cli_TrackOptions *opt)
{
    return opt->axes == CLI_TRACK_AXES_LEVEL && !isnan(opt->incline_rad) ? opt->incline_rad : 0.0;
}

/* (x, y) in axes turned counter-clockwise by an angle of cosine c and
 * sine s: (x c + y s, -x s + y c). */
static inline void cli_track_turn(double x, double y, double c, double s, double *u, double *v)
{
    *u = x * c + y * s;
    *v = -x * s + y * c;
}

/* frame.c: the chosen tracks in a frame turned by angle_rad from
 * Tracker's level axes (or in Tracker's own with incline axes), into out
 * (whose report fields are set here). 0, or -1 with a message (out then
 * holds nothing to free): a radius not > 0 or an incline outside [0, 90)
 * deg, a track name given that is not in the file (or --centre and --mass
 * naming one track), a time that jumps by more than CLI_TRACK_MAX_FRAMES
 * frames, a position beyond CLI_TRACK_MAX_COORD_M, out of memory. */
int cli_track_from_raw(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, double angle_rad,
                       cli_Track *out, char *err, size_t err_len);
/* The whole of it: the frame for the incline given (or Tracker's level one
 * turned by nothing, to measure it), then derive.c. 0, or -1 with a message
 * (out then holds nothing to free). */
int cli_track_from_raw_data(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, cli_Track *out,
                            char *err, size_t err_len);
/* The tracks' names, quoted and comma-separated, for messages. */
void cli_track_list_names(const cli_RawData *raw, char *buf, size_t len);
/* 1 when a track's name says it is the centre (centre, center, axle, axis, hub). */
int cli_track_named_centre(const char *name);

/* The least noise a track is taken to have: no video resolves 10 µm. */
#define CLI_TRACK_NOISE_FLOOR_M 1e-5

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
} cli_SurfaceLine;
/* 0; -1 with fewer than 3 frames in contact (contact[] all 0); -2 out of memory. */
int cli_surface_fit(const double *x, const double *y, long n, double fps, double floor_m, double start_m,
                    unsigned char *contact, cli_SurfaceLine *out);

/* The median of v[0..n) (reordered; the mean of the middle two for an
 * even n); NaN for n = 0. */
double cli_track_median(double *v, long n);

/* The noise of a path from its third differences (work: 2 n doubles):
 * those of a smooth path are small next to noise, whose third difference
 * has variance 20 sigma^2; their median absolute value (x 1.4826 for a
 * Gaussian) ignores the impacts. 0 with fewer than 4 points. */
double cli_track_frame_noise(const double *x, const double *y, long n, double *work);

/* rim.c: the centre recovered from a mark on the body by fitting rolling. */
typedef struct {
    const double *t_s, *x_m, *y_m; /* the mark in the frame of cli_track_from_raw (no NaN) */
    long n;
    double radius_m;               /* r */
    double sigma_floor_m;          /* the noise is not taken below this */
    double gravity_mps2;           /* for the flights */
} cli_RimInput;

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
    cli_TrackHop *dep;               /* the caller's array of n / 2 + 1 */
} cli_RimResult;
/* The frames a rolling fit takes at most (its Jacobian is dense, 2 n by
 * about n / 2: a second or two at 1000 frames). */
#define CLI_RIM_MAX_FRAMES 1000
/* The rolling fit and the departures from it (no flights fitted to them
 * yet: cli_rim_flights, once the incline is decided). 0, or -1 when the
 * frames are too few or too many or the fit fails. */
int cli_rim_recover(const cli_RimInput *in, cli_RimResult *out);
/* A flight (a parabola under gravity at incline_rad to the rolling line,
 * with a constant spin) fitted to each departure in out, from the rolling
 * state before it; where one fits, its peak is the departure's height and
 * its path the frames' centre, θ and ω. Nothing with incline_rad NaN. */
void cli_rim_flights(const cli_RimInput *in, double incline_rad, cli_RimResult *out);

/* derive.c: the surface, the incline, heights and hops, θ and ω, the
 * noise, and the notes. 0, or -1 with a message (a given incline, or
 * incline axes, the frames in contact refuse; out of memory). */
int cli_track_derive(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, cli_Track *t, char *err,
                     size_t err_len);

#endif
