/* What a track tells beyond positions: the surface and the incline's angle
 * (from the frames in contact, checked against an angle given), the noise,
 * the centre (tracked, or recovered from a mark by rim.c), the heights and
 * the hops with their uncertainties, θ unwrapped and ω; and, for each
 * quantity, a note saying how well it is known or why it is not. */
#include "track_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEG (180.0 / JC_TRACK_PI)
#define HOP_MIN_FRAMES 2
#define TURN_PASSES 8
/* A single track whose scatter about its line is this many times the
 * frame-to-frame noise swings about the line: a mark, not a centre. */
#define MARK_SWING_RATIO 4.0
#define DIRECTION_TOL_RAD (0.5 * JC_TRACK_PI / 180.0) /* see along_axes */
#define MARK_MIN_RADIUS_R 0.2   /* a recovered mark at least 0.2 r from C ... */
#define MARK_MIN_NOISES 10.0    /* ... and 10 noises */
#define MARK_MIN_ROLLING 0.5    /* rolling explains at least half the frames ... */
#define MARK_MAX_NOISE_RATIO 2.0 /* ... scattered at most twice the frames' own noise */
#define CENTRE_MAX_NOISES 2.0   /* a recovered centre whose error is above 2 noises is left out */
/* The helpers' failures: -1 with a message (a refused incline), or this. */
#define OUT_OF_MEMORY (-2)

static void note(jc_Track *t, jc_TrackQuantity q, int ok, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->note[q].text, sizeof t->note[q].text, fmt, ap);
    va_end(ap);
    t->note[q].ok = ok;
}

/* The points (x NaN: none) in axes turned counter-clockwise by angle. */
static void turn(double *x, double *y, long n, double angle)
{
    const double c = cos(angle), s = sin(angle);
    for (long i = 0; i < n; ++i)
        if (!isnan(x[i])) jc_track_turn(x[i], y[i], c, s, &x[i], &y[i]);
}

/* The incline a measured one gives the model: a floor measured a hair
 * below level (within 3 sigma or 2 deg) is level; a body that went up a
 * slope leaves it unknown (NaN: the model takes inclines from 0). */
static double measured_incline(double measured, double sig, jc_Track *t)
{
    if (measured >= 0.0) return measured;
    if (-measured <= fmax(JC_TRACK_INCLINE_SIGMAS * sig, JC_TRACK_INCLINE_TOL_RAD)) return 0.0;
    t->incline_source = JC_TRACK_INCLINE_UNKNOWN;
    t->uphill = 1;
    return NAN;
}

/* Whether a given incline is refused by a measured one (the frames in
 * contact, sigma theirs): beyond 3 sigma and beyond 2 degrees. */
static int refuses(double given, double measured, double sigma)
{
    const double d = fabs(given - measured);
    return d > JC_TRACK_INCLINE_SIGMAS * sigma && d > JC_TRACK_INCLINE_TOL_RAD;
}

static int agrees(double given, double measured, double sigma)
{
    return fabs(given - measured) <= JC_TRACK_INCLINE_SIGMAS * sigma;
}

/* ---- a tracked centre ---- */


/* The incline from the line through the frames in contact (tilt tau
 * against the frame's x, sigma its error), into t. -1 with a message when
 * the given one is refused. */
static int decide_incline(const char *name, const jc_TrackOptions *opt, double frame_angle, double tau,
                          double sig, long frames, jc_Track *t, char *err, size_t err_len)
{
    const int given = !isnan(opt->incline_rad);
    t->surface_tilt_rad = tau;
    t->surface_tilt_sigma_rad = sig;
    if (opt->axes == JC_TRACK_AXES_LEVEL) {
        const double measured = frame_angle - tau;
        if (given && refuses(opt->incline_rad, measured, sig)) {
            snprintf(err, err_len,
                     "%s: the incline given, %.2f deg, disagrees with the video: the centres in contact lie on a "
                     "line at %.2f +- %.2f deg (%ld frames); leave the incline out to take the video's, or check "
                     "the axes (level or incline)",
                     name, opt->incline_rad * DEG, measured * DEG, sig * DEG, frames);
            return -1;
        }
        t->incline_source = given ? JC_TRACK_INCLINE_GIVEN : JC_TRACK_INCLINE_MEASURED;
        t->incline_rad = given ? opt->incline_rad : measured_incline(measured, sig, t);
        t->incline_sigma_rad = given ? 0.0 : sig;
        return 0;
    }
    /* Axes along the incline: the line should lie along x. */
    if (refuses(0.0, tau, sig)) {
        snprintf(err, err_len,
                 "%s: the axes are not along the incline: the centres in contact lie on a line at %+.2f +- %.2f deg "
                 "to them (%ld frames); lay Tracker's x axis along the ramp, or use level axes",
                 name, tau * DEG, sig * DEG, frames);
        return -1;
    }
    t->incline_source = given ? JC_TRACK_INCLINE_GIVEN : JC_TRACK_INCLINE_UNKNOWN;
    t->incline_rad = given ? opt->incline_rad : NAN;
    t->incline_sigma_rad = given ? 0.0 : NAN;
    return 0;
}

/* Whether the surface is taken along the frame's x as it is: along the
 * incline given (level axes) or along the axes (incline axes), when the
 * frames in contact (tilt tau, sigma its error) lie within 3 sigma of it
 * or within DIRECTION_TOL_RAD, unless opt->fit_tilt asks for their line. The
 * line through the frames in contact can be off by more than its sigma
 * (bounces too low to show lift its far end: up to 0.28 deg, 4.6 sigma, in
 * tests/track/test_track.c's synthetic videos of the paper's cylinder), and
 * a measured angle that close is the better direction. */
static int along_axes(const jc_TrackOptions *opt, double frame_angle, double tau, double sig)
{
    if (opt->fit_tilt) return 0;
    const double d = opt->axes == JC_TRACK_AXES_LEVEL ? opt->incline_rad - (frame_angle - tau) : tau;
    return fabs(d) <= fmax(JC_TRACK_INCLINE_SIGMAS * sig, DIRECTION_TOL_RAD);
}

/* How the surface's direction came about, for the notes. */
static const char *direction_words(const jc_TrackOptions *opt, const jc_Track *t, int level, int agreed)
{
    const int level_axes = opt->axes == JC_TRACK_AXES_LEVEL;
    if (level && agreed) return level_axes ? " (agreed)" : "";
    if (level)
        return level_axes ? ": beyond 3 sigma but within 0.5 deg, so the surface is taken along the incline given"
                          : ": beyond 3 sigma but within 0.5 deg, so the surface is taken along the axes";
    if (t->centre_source != JC_TRACK_CENTRE_FROM_MARK && opt->fit_tilt) return ": the surface is their line (--fit-tilt)";
    return level_axes && t->incline_source == JC_TRACK_INCLINE_GIVEN
               ? ": the surface is their line, the model's incline the one given"
               : ": the surface is their line";
}

/* Degrees as printed to places decimals: a value that rounds to zero is
 * 0 (not -0.00). */
static double shown_deg(double rad, int places)
{
    const double d = rad * DEG;
    return fabs(d) < 0.5 * pow(10.0, -places) ? 0.0 : d;
}

/* level: the surface taken along the frame's x (along_axes). */
static void surface_note(jc_Track *t, const jc_TrackOptions *opt, int level)
{
    const double measured_rad = jc_track_frame_angle(opt) - t->surface_tilt_rad;
    const double sig = t->surface_tilt_sigma_rad * DEG;
    /* A level line may also be a video whose axes were laid along an incline. */
    const char *hint = opt->axes == JC_TRACK_AXES_LEVEL && isnan(opt->incline_rad)
                           ? "; if Tracker's axes lie along an incline, give --axes incline --incline DEG"
                           : "";
    /* A mark alone: the frames it rolls in (the body in contact). */
    const char *in = t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? "frames the mark rolls in" : "frames in contact";
    const int agreed = opt->axes == JC_TRACK_AXES_LEVEL
                           ? !isnan(opt->incline_rad) && agrees(opt->incline_rad, measured_rad, t->surface_tilt_sigma_rad)
                           : agrees(0.0, t->surface_tilt_rad, t->surface_tilt_sigma_rad);
    const char *words = direction_words(opt, t, level, agreed);

    if (t->uphill)
        note(t, JC_TRACK_Q_SURFACE, 1, "the body went up a slope: the %s lie at %.2f +- %.2f deg against its travel; "
             "noise %.2f mm; compare and fit read bodies that go downhill or along a floor", in,
             shown_deg(measured_rad, 2), sig, t->sigma_m * 1e3);
    else if (t->incline_source == JC_TRACK_INCLINE_MEASURED && measured_rad < 0.0)
        note(t, JC_TRACK_Q_SURFACE, 1, "incline 0 deg, a floor: the line through %ld %s lies at %.3f +- %.3f deg, level "
             "within its error; noise %.2f mm (their scatter about it)%s", t->contact_frames, in,
             shown_deg(measured_rad, 3), sig, t->sigma_m * 1e3, hint);
    else if (t->incline_source == JC_TRACK_INCLINE_MEASURED)
        note(t, JC_TRACK_Q_SURFACE, 1, "incline %.2f +- %.2f deg, measured: the line through %ld %s; noise %.2f mm (their "
             "scatter about it)%s", shown_deg(t->incline_rad, 2), sig, t->contact_frames, in, t->sigma_m * 1e3,
             t->incline_rad < 3.0 * t->surface_tilt_sigma_rad ? hint : "");
    else if (t->incline_source == JC_TRACK_INCLINE_UNKNOWN)
        note(t, JC_TRACK_Q_SURFACE, 1, "the surface: the %ld %s lie at %+.2f +- %.2f deg to the axes%s; noise "
             "%.2f mm; the incline's angle is not known: the axes lie along it and none was given",
             t->contact_frames, in, shown_deg(t->surface_tilt_rad, 2), sig, words, t->sigma_m * 1e3);
    else if (opt->axes == JC_TRACK_AXES_LEVEL)
        note(t, JC_TRACK_Q_SURFACE, 1, "incline %.2f deg as given; the %ld %s lie at %.2f +- %.2f deg%s; noise %.2f mm",
             t->incline_rad * DEG, t->contact_frames, in, shown_deg(measured_rad, 2), sig, words, t->sigma_m * 1e3);
    else
        note(t, JC_TRACK_Q_SURFACE, 1, "incline %.2f deg as given (axes along it); the %ld %s lie at %+.2f +- %.2f deg to "
             "the axes%s; noise %.2f mm", t->incline_rad * DEG, t->contact_frames, in,
             shown_deg(t->surface_tilt_rad, 2), sig, words, t->sigma_m * 1e3);
}

/* The surface under a tracked centre (frame_noise_m: the frame-to-frame
 * noise of its frames), the frame turned onto it, heights. 1 when no line
 * holds the centre (too few frames in contact), 0 when placed, -1 with a
 * message (a refused incline) or OUT_OF_MEMORY with one. */
static int tracked_surface(const char *name, const jc_TrackOptions *opt, double frame_angle, double frame_noise_m,
                           jc_Track *t, char *err, size_t err_len)
{
    jc_TrackSurfaceLine L;
    int st = jc_track_surface_fit(t->x_m, t->y_m, t->n, t->frame_rate_hz, JC_TRACK_NOISE_FLOOR_M, frame_noise_m,
                                  t->contact, &L);
    if (st == -2) {
        snprintf(err, err_len, "%s: out of memory", name);
        return OUT_OF_MEMORY;
    }
    if (st != 0) return 1;
    const double tau = atan(L.b), sig = sqrt(L.var_b) / (1.0 + L.b * L.b);
    if (decide_incline(name, opt, frame_angle, tau, sig, L.contact, t, err, err_len) != 0) return -1;
    const int level = t->incline_source != JC_TRACK_INCLINE_MEASURED && along_axes(opt, frame_angle, tau, sig);
    double turn_by = level ? 0.0 : tau;
    /* Turned until the line through the frames in contact (which may change
     * with the turn) lies along x: the frame is then the incline's exactly,
     * not sheared onto it. */
    double turned = 0.0;
    for (int pass = 0; turn_by != 0.0 && pass < TURN_PASSES; ++pass) {
        turn(t->x_m, t->y_m, t->n, turn_by);
        turn(t->mark_x_m, t->mark_y_m, t->n, turn_by);
        turned += turn_by;
        if (jc_track_surface_fit(t->x_m, t->y_m, t->n, t->frame_rate_hz, JC_TRACK_NOISE_FLOOR_M, frame_noise_m,
                                 t->contact, &L) != 0)
            return 1;
        turn_by = fabs(L.b) > 1e-12 ? atan(L.b) : 0.0;
    }
    if (turned != 0.0) {
        t->surface_tilt_rad = turned;
        if (t->incline_source == JC_TRACK_INCLINE_MEASURED)
            t->incline_rad = measured_incline(frame_angle - turned, t->surface_tilt_sigma_rad, t);
    }
    /* A level surface through the frames in contact: their mean height
     * (the least-squares line's value at their mean x). */
    const double b = level ? 0.0 : L.b;
    for (long i = 0; i < t->n; ++i) {
        const double s = L.a + b * (t->x_m[i] - L.x_mid) - t->radius_m;
        t->y_m[i] -= s;
        if (!isnan(t->mark_y_m[i])) t->mark_y_m[i] -= s;
        t->centre_sigma_m[i] = L.sigma_m;
    }
    t->contact_frames = L.contact;
    t->sigma_m = L.sigma_m;
    t->surface_sigma_m = sqrt(L.var_a);
    surface_note(t, opt, level);
    t->hop_threshold_m = t->hop_sigmas * t->sigma_m;
    /* Hops: runs of at least 2 frames clearly above the surface; a peak's
     * error holds the noise and the surface's, there. */
    t->hops = 0;
    long i = 0;
    while (i < t->n) {
        if (!(t->y_m[i] - t->radius_m > t->hop_threshold_m)) {
            i++;
            continue;
        }
        long j = i;
        while (j + 1 < t->n && t->y_m[j + 1] - t->radius_m > t->hop_threshold_m) j++;
        if (j - i + 1 >= HOP_MIN_FRAMES) {
            jc_TrackHop *h = &t->hop[t->hops++];
            memset(h, 0, sizeof *h);
            h->first = i, h->last = j, h->peak = i;
            for (long k = i; k <= j; ++k) {
                if (t->y_m[k] > t->y_m[h->peak]) h->peak = k;
                t->airborne[k] = 1;
            }
            const double dx = t->x_m[h->peak] - L.x_mid;
            h->height_m = t->y_m[h->peak] - t->radius_m;
            h->height_sigma_m = sqrt(t->sigma_m * t->sigma_m + L.var_a + (level ? 0.0 : L.var_b * dx * dx));
            h->bound_m = NAN;
        }
        i = j + 1;
    }
    return 0;
}

/* ---- a centre recovered from a mark ---- */

static int alloc_rim(jc_TrackRimResult *r, long n)
{
    memset(r, 0, sizeof *r);
    double **a[] = {&r->mark_x, &r->mark_y, &r->cx, &r->cy, &r->c_sigma, &r->theta, &r->omega};
    int ok = 1;
    for (size_t k = 0; k < sizeof a / sizeof a[0]; ++k) ok = (*a[k] = malloc((size_t)n * sizeof(double))) && ok;
    r->rolling = malloc((size_t)n);
    r->dep = malloc((size_t)(n / 2 + 1) * sizeof *r->dep);
    return ok && r->rolling && r->dep ? 0 : -1;
}

static void free_rim(jc_TrackRimResult *r)
{
    free(r->mark_x), free(r->mark_y), free(r->cx), free(r->cy), free(r->c_sigma), free(r->theta), free(r->omega);
    free(r->rolling), free(r->dep);
}

static jc_TrackRimInput rim_input(const jc_TrackOptions *opt, const jc_Track *t)
{
    const jc_TrackRimInput in = {t->t_s, t->mark_x_m, t->mark_y_m, t->n, opt->radius_m, JC_TRACK_NOISE_FLOOR_M,
                             opt->gravity_mps2 > 0 ? opt->gravity_mps2 : 9.81};
    return in;
}

static int run_rim(const jc_TrackOptions *opt, const jc_Track *t, jc_TrackRimResult *r)
{
    if (alloc_rim(r, t->n) != 0) return -2;
    const jc_TrackRimInput in = rim_input(opt, t);
    return jc_track_rim_recover(&in, r);
}

/* Whether a recovered mark is one: far enough from C to be told from
 * noise, within the rim, with rolling explaining most frames at about
 * the noise the frames show by themselves (frame_noise_m, from their third
 * differences: it can only run high for a fast mark, never low; a rolling
 * path fitted to a body that slides scatters the frames far wider). */
static int plausible_mark(const jc_TrackRimResult *r, const jc_Track *t, double frame_noise_m)
{
    /* Every point of the body lies within the rim: a mark found farther
     * out than its error allows is rolling fitted to motion it is not. */
    return r->a_m >= MARK_MIN_RADIUS_R * t->radius_m && r->a_m >= MARK_MIN_NOISES * r->noise_m &&
           r->a_m <= t->radius_m + 3.0 * r->a_sigma_m && r->noise_m <= MARK_MAX_NOISE_RATIO * frame_noise_m &&
           (double)r->rolling_frames >= MARK_MIN_ROLLING * (double)t->n;
}

/* The recovered centre into the track: the surface frame, the incline
 * (checked against one given), the flights fitted to the departures under
 * it, heights, the departures and hops. */
static int adopt_rim(const char *name, const jc_TrackOptions *opt, double frame_angle, jc_TrackRimResult *r,
                     jc_Track *t, char *err, size_t err_len)
{
    if (decide_incline(name, opt, frame_angle, r->tilt_rad, r->tilt_sigma_rad, r->rolling_frames, t, err,
                       err_len) != 0)
        return -1;
    /* Gravity at the incline decided, the model's; a body that went up a
     * slope, which the model has no incline for, flew under the slope's. */
    const jc_TrackRimInput in = rim_input(opt, t);
    jc_track_rim_flights(&in, t->uphill ? frame_angle - r->tilt_rad : t->incline_rad, r);
    t->centre_source = JC_TRACK_CENTRE_FROM_MARK;
    t->has_mark = 1;
    /* Where the mark barely moves (it passes the contact point), above
     * all at the clip's ends, it tells the centre poorly, and the linear
     * error understates how poorly: a centre whose error is above
     * CENTRE_MAX_NOISES noises is left out, with its angle. */
    t->centre_left_out = 0;
    for (long i = 0; i < t->n; ++i) {
        const int known = r->c_sigma[i] <= CENTRE_MAX_NOISES * r->noise_m;
        t->mark_x_m[i] = r->mark_x[i], t->mark_y_m[i] = r->mark_y[i];
        t->x_m[i] = known ? r->cx[i] : NAN, t->y_m[i] = known ? r->cy[i] : NAN;
        t->centre_sigma_m[i] = known ? r->c_sigma[i] : NAN;
        t->theta_rad[i] = known ? r->theta[i] : NAN, t->omega_radps[i] = known ? r->omega[i] : NAN;
        t->contact[i] = r->rolling[i];
        t->centre_left_out += !known && isfinite(r->cx[i]);
    }
    t->sigma_m = r->noise_m;
    t->contact_frames = r->rolling_frames;
    t->surface_sigma_m = r->line_sigma_m;
    t->mark_radius_m = r->a_m;
    t->mark_radius_sigma_m = r->a_sigma_m;
    /* A departure smaller than this leaves the mark within the outlier
     * cut of the rolling path, and does not show. */
    t->hop_threshold_m = t->hop_sigmas * t->sigma_m;
    surface_note(t, opt, 0);
    t->hops = 0;
    for (long k = 0; k < r->departures; ++k) {
        jc_TrackHop h = r->dep[k];
        const int hop = h.fitted_flight && h.height_m > t->hop_threshold_m && h.height_m > 3.0 * h.height_sigma_m;
        if (!hop) h.height_m = h.height_sigma_m = NAN;
        t->hop[t->hops++] = h;
        if (hop)
            for (long i = h.first; i <= h.last; ++i) t->airborne[i] = 1;
    }
    return 0;
}

/* A single track not named as the centre that swings about its line by
 * more than its frame-to-frame noise (frame_noise_m) may be a mark on the
 * body: rolling is fitted to it and kept if it fits (0, or -1 or
 * OUT_OF_MEMORY with a message); 1: a centre after all (*tried: rolling was fitted and did not
 * explain it). */
static int single_track_as_mark(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt,
                                double frame_angle, double frame_noise_m, jc_Track *t, int *tried, char *err,
                                size_t err_len)
{
    *tried = 0;
    if (raw->track_count != 1 || t->has_mark || opt->centre || opt->mark || jc_track_named_centre(t->centre_name))
        return 1;
    jc_TrackSurfaceLine L;
    const int st =
        jc_track_surface_fit(t->x_m, t->y_m, t->n, t->frame_rate_hz, JC_TRACK_NOISE_FLOOR_M, 0.0, t->contact, &L);
    if (st == 0 && !(L.sigma_m > MARK_SWING_RATIO * frame_noise_m)) return 1;
    for (long i = 0; i < t->n; ++i) t->mark_x_m[i] = t->x_m[i], t->mark_y_m[i] = t->y_m[i];
    jc_TrackRimResult r;
    int rc = 1;
    const int fit = run_rim(opt, t, &r);
    *tried = fit != -2;
    if (fit == -2) {
        snprintf(err, err_len, "%s: out of memory", name);
        rc = OUT_OF_MEMORY;
    } else if (fit == 0 && plausible_mark(&r, t, frame_noise_m)) {
        memcpy(t->mark_name, t->centre_name, sizeof t->mark_name);
        t->centre_name[0] = '\0';
        rc = adopt_rim(name, opt, frame_angle, &r, t, err, err_len);
    }
    if (rc == 1)
        for (long i = 0; i < t->n; ++i) t->mark_x_m[i] = t->mark_y_m[i] = NAN;
    free_rim(&r);
    return rc;
}

/* ---- θ, ω and the notes ---- */

static void derive_angles(jc_Track *t, double *work)
{
    long m = 0, prev = -1;
    for (long i = 0; i < t->n; ++i) {
        if (isnan(t->mark_x_m[i]) || isnan(t->x_m[i])) continue;
        const double dx = t->mark_x_m[i] - t->x_m[i], dy = t->mark_y_m[i] - t->y_m[i];
        work[m++] = hypot(dx, dy);
        double th = atan2(dx, dy);
        if (prev >= 0) th += 2 * JC_TRACK_PI * nearbyint((t->theta_rad[prev] - th) / (2 * JC_TRACK_PI));
        t->theta_rad[i] = th;
        prev = i;
    }
    t->mark_radius_m = jc_track_median(work, m);
    for (long i = 0; i < t->n; ++i) {
        t->omega_radps[i] = NAN;
        if (isnan(t->theta_rad[i])) continue;
        const long lo = i > 0 && !isnan(t->theta_rad[i - 1]) ? i - 1 : i;
        const long hi = i + 1 < t->n && !isnan(t->theta_rad[i + 1]) ? i + 1 : i;
        if (hi > lo) t->omega_radps[i] = (t->theta_rad[hi] - t->theta_rad[lo]) / (t->t_s[hi] - t->t_s[lo]);
    }
}

static long resolved_hops(const jc_Track *t)
{
    long k = 0;
    for (long i = 0; i < t->hops; ++i) k += !isnan(t->hop[i].height_m);
    return k;
}

static void hop_note(jc_Track *t)
{
    const long hops = resolved_hops(t), open = t->hops - hops;
    if (t->centre_source == JC_TRACK_CENTRE_TRACKED) {
        note(t, JC_TRACK_Q_HOPS, 1, "%ld hop(s): the centre more than %.0f sigma (%.2f mm) above the surface in %d "
             "frames or more", hops, t->hop_sigmas, t->hop_threshold_m * 1e3, HOP_MIN_FRAMES);
        return;
    }
    char tail[160] = "";
    if (t->hops > 0)
        snprintf(tail, sizeof tail, "; %ld departure(s) from rolling: %ld fitted as flights (hops), %ld a slip or "
                 "a hop the mark cannot resolve", t->hops, hops, open);
    note(t, JC_TRACK_Q_HOPS, 1, "the only track is a mark on the body: hops cannot be told apart from the mark's own "
         "motion to better than %.1f mm%s", t->hop_threshold_m * 1e3, tail);
}

static void theta_note(jc_Track *t)
{
    if (t->centre_source == JC_TRACK_CENTRE_FROM_MARK)
        note(t, JC_TRACK_Q_THETA, 1, "theta and omega from the rolling fit of the mark '%s' (at %.2f +- %.2f cm from the "
             "centre)", t->mark_name, t->mark_radius_m * 100, t->mark_radius_sigma_m * 100);
    else if (t->has_mark)
        note(t, JC_TRACK_Q_THETA, 1, "theta and omega from the mark '%s' at %.2f cm from the centre (median)", t->mark_name,
             t->mark_radius_m * 100);
    else
        note(t, JC_TRACK_Q_THETA, 0, "no mark was tracked: theta and omega are not measured (compare and fit take the "
             "start's theta from the centre's motion)");
}

static void centre_note(jc_Track *t, const jc_TrackRaw *raw)
{
    if (t->centre_source == JC_TRACK_CENTRE_TRACKED) {
        note(t, JC_TRACK_Q_CENTRE, 1, "tracked ('%s': %ld frames, %ld missing between its first and last)",
             t->centre_name, t->n, t->gaps);
    } else if (t->centre_source == JC_TRACK_CENTRE_FROM_MARK) {
        char left_out[128] = "";
        if (t->centre_left_out > 0)
            snprintf(left_out, sizeof left_out, "; left out in %ld frame(s) where the mark, passing the contact "
                     "point, tells it worse", t->centre_left_out);
        note(t, JC_TRACK_Q_CENTRE, 1, "recovered from the mark '%s' (a = %.2f +- %.2f cm from it) by fitting rolling, "
             "which explains %ld of its %ld frames: standard error %.2f mm (median; up to %.1f mm, %.0f noises)%s; "
             "noise %.2f mm", t->mark_name, t->mark_radius_m * 100,
             t->mark_radius_sigma_m * 100, t->contact_frames, t->n, t->centre_sigma_median_m * 1e3,
             t->centre_sigma_max_m * 1e3, CENTRE_MAX_NOISES, left_out, t->sigma_m * 1e3);
    } else if (t->centre_ambiguous) {
        char names[400];
        jc_track_list_names(raw, names, sizeof names);
        note(t, JC_TRACK_Q_CENTRE, 0, "not known: which track is the centre? none is named like the axle (centre, "
             "center, axle, axis, hub)%s; give --centre NAME (tracks: %s)",
             raw->track_count == 2 ? " and their motion does not tell" : "", names);
    } else {
        note(t, JC_TRACK_Q_CENTRE, 0, "not known: the file has no frames with a position");
    }
}

static void nothing_more(jc_Track *t, const char *why)
{
    note(t, JC_TRACK_Q_SURFACE, 0, "not known: %s", why);
    note(t, JC_TRACK_Q_HOPS, 0, "not known: %s", why);
}

int jc_track_derive(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, jc_Track *t, char *err,
                    size_t err_len)
{
    const double frame_angle = jc_track_frame_angle(opt);
    t->hop = calloc((size_t)(t->n / 2 + 1), sizeof *t->hop);
    double *work = malloc((size_t)(2 * t->n + 2) * sizeof *work);
    if (!t->hop || !work) {
        free(work);
        snprintf(err, err_len, "%s: out of memory", name);
        return JC_ENOMEM;
    }
    int rc = 0;
    if (t->centre_source == JC_TRACK_CENTRE_TRACKED && t->n >= 3) {
        /* The frame-to-frame noise, for both: single_track_as_mark leaves
         * the frames as they are when it returns 1. */
        const double frame_noise_m = jc_track_frame_noise(t->x_m, t->y_m, t->n, work);
        int tried = 0;
        rc = single_track_as_mark(name, raw, opt, frame_angle, frame_noise_m, t, &tried, err, err_len);
        if (rc == 1) rc = tracked_surface(name, opt, frame_angle, frame_noise_m, t, err, err_len);
        if (rc == 1) {
            nothing_more(t, tried ? "the track's frames lie on no line (fewer than 3 of them in runs of 4 within 3 "
                                    "sigma of one), and rolling does not explain them as a mark on the body either"
                                  : "the centre's frames lie on no line: fewer than 3 of them in runs of 4 within 3 "
                                    "sigma of one (is the track the axle?)");
            rc = 0;
        }
    } else if (t->centre_source == JC_TRACK_CENTRE_FROM_MARK && t->n >= 3) {
        jc_TrackRimResult r;
        const int st = run_rim(opt, t, &r);
        if (st == -2) {
            rc = OUT_OF_MEMORY;
            snprintf(err, err_len, "%s: out of memory", name);
        } else if (st == 0 && plausible_mark(&r, t, jc_track_frame_noise(t->mark_x_m, t->mark_y_m, t->n, work))) {
            rc = adopt_rim(name, opt, frame_angle, &r, t, err, err_len);
        } else {
            t->centre_source = JC_TRACK_CENTRE_NONE;
            if (t->n > JC_TRACK_RIM_MAX_FRAMES)
                note(t, JC_TRACK_Q_CENTRE, 0, "not recovered: the mark '%s' has %ld frames, more than the rolling fit "
                     "takes (%d); export a shorter clip from Tracker, or track the axle too",
                     t->mark_name, t->n, JC_TRACK_RIM_MAX_FRAMES);
            else
                note(t, JC_TRACK_Q_CENTRE, 0, "not recovered: rolling does not explain the mark '%s' (in fewer than a "
                     "quarter of its %ld frames, or not as a mark on a rolling body: the body slides or flies most "
                     "of the time); track the axle too", t->mark_name, t->n);
            nothing_more(t, "the centre is not known");
        }
        free_rim(&r);
    } else if (t->centre_source != JC_TRACK_CENTRE_NONE) {
        long frames = 0;
        for (int k = 0; k < t->track_count; ++k)
            if (strcmp(t->track_names[k], t->centre_source == JC_TRACK_CENTRE_TRACKED ? t->centre_name : t->mark_name) == 0)
                frames = t->track_frames[k];
        note(t, JC_TRACK_Q_CENTRE, 0, "not known: the track '%s' has %ld frame(s) with a position, fewer than 3%s",
             t->centre_source == JC_TRACK_CENTRE_TRACKED ? t->centre_name : t->mark_name, frames,
             isfinite(t->frame_rate_hz) ? "" : " (and no time step)");
        t->centre_source = JC_TRACK_CENTRE_NONE;
        nothing_more(t, "fewer than 3 frames");
    } else {
        nothing_more(t, "no centre");
    }
    if (rc == 0) {
        if (t->centre_source == JC_TRACK_CENTRE_TRACKED && t->has_mark) derive_angles(t, work);
        for (long i = 0; i < t->n && isnan(t->x0_m); ++i) t->x0_m = t->x_m[i];
        long m = 0;
        t->centre_sigma_max_m = 0.0;
        for (long i = 0; i < t->n; ++i)
            if (!isnan(t->x_m[i]) && !isnan(t->centre_sigma_m[i])) {
                work[m++] = t->centre_sigma_m[i];
                t->centre_sigma_max_m = fmax(t->centre_sigma_max_m, t->centre_sigma_m[i]);
            }
        t->centre_sigma_median_m = jc_track_median(work, m);
        if (!t->note[JC_TRACK_Q_CENTRE].text[0]) centre_note(t, raw);
        if (t->centre_source != JC_TRACK_CENTRE_NONE && !isnan(t->sigma_m)) hop_note(t);
        if (t->centre_source != JC_TRACK_CENTRE_NONE) theta_note(t);
        else note(t, JC_TRACK_Q_THETA, 0, "not known: a mark's angle is seen from the centre, which is not known");
    }
    free(work);
    return rc == 0 ? JC_OK : rc == OUT_OF_MEMORY ? JC_ENOMEM : JC_EINVAL;
}
