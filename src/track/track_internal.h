/* What the files of src/track share (not installed). The tracks as a file
 * holds them (jc_TrackRaw, <jumpcyl/track.h>) and the steps from them to a
 * jc_Track: the readers (trk.c, table.c), the conversion to the incline
 * frame (frame.c), the derivation (surface.c, rim.c, derive.c), and the
 * whole of it (read.c); data.c allocates and frees. Calls run one way:
 * read.c -> the readers, frame.c, derive.c -> surface.c, rim.c -> data.c. */
#ifndef JUMPCYL_TRACK_INTERNAL_H
#define JUMPCYL_TRACK_INTERNAL_H

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
 * (or --centre and --mass naming one track), a time that jumps by more than
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

#endif
