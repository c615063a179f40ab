/* The surface under a tracked centre: the line through the frames in
 * contact, its tilt with a standard error, and the noise of the tracked
 * points measured as their scatter about it. */
#include "track_internal.h"

#include <gsl/gsl_sort_double.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A run of frames in contact is at least min_run long (jc_track_surface_fit's:
 * 4 frames and 0.1 s at the frame rate): a flight's low first and last frames and a low bounce
 * between two flights make shorter runs, left out as they would tilt the
 * line where the body is mostly in the air. */
#define SURFACE_CUT_SIGMAS 3.0
#define CONTACT_RUN_FRAMES 4.0
#define CONTACT_RUN_S 0.1
#define CONTACT_ERODE_S 0.05
#define RUN_ABOVE_SIGMAS 3.0
#define SURFACE_PASSES 30
#define MAD_TO_SIGMA 1.4826

/* The variance of a unit Gaussian cut at +-c. */
static double truncated_variance(double c)
{
    if (!(c > 0.5)) c = 0.5;
    const double phi = exp(-0.5 * c * c) / sqrt(2.0 * JC_TRACK_PI), mass = erf(c / sqrt(2.0));
    return 1.0 - 2.0 * c * phi / mass;
}

double jc_track_median(double *v, long n)
{
    return n > 0 ? gsl_stats_median(v, 1, (size_t)n) : NAN;
}

/* The q-quantile of v[0..n) (reordered): the element of nearest rank, not
 * a mean of two (jc_track_median's); NaN for n = 0. */
static double quantile(double *v, long n, double q)
{
    if (n <= 0) return NAN;
    gsl_sort(v, 1, (size_t)n);
    const long k = (long)floor(q * (double)(n - 1) + 0.5);
    return v[k < 0 ? 0 : k >= n ? n - 1 : k];
}

/* Least squares y = a + b (x - xm) over the kept frames; -1 with fewer than 3. */
static int line_fit(const double *x, const double *y, const unsigned char *keep, long n, jc_TrackSurfaceLine *L)
{
    double sw = 0, sx = 0;
    for (long i = 0; i < n; ++i)
        if (keep[i]) sw += 1, sx += x[i];
    if (sw < 3) return -1;
    const double xm = sx / sw;
    double sxx = 0, sy = 0, sxy = 0;
    for (long i = 0; i < n; ++i) {
        if (!keep[i]) continue;
        const double u = x[i] - xm;
        sxx += u * u, sy += y[i], sxy += u * y[i];
    }
    L->x_mid = xm;
    L->b = sxx > 0 ? sxy / sxx : 0.0;
    L->a = sy / sw;
    L->sxx = sxx;
    L->contact = (long)sw;
    return 0;
}

/* Robust scale of the kept frames' residuals: MAD x 1.4826, at least floor. */
static double scale_of(const double *x, const double *y, const unsigned char *keep, long n, const jc_TrackSurfaceLine *L,
                       double floor_m, double *work)
{
    long m = 0;
    for (long i = 0; i < n; ++i)
        if (keep[i]) work[m++] = fabs(y[i] - (L->a + L->b * (x[i] - L->x_mid)));
    const double s = MAD_TO_SIGMA * quantile(work, m, 0.5);
    return s >= floor_m ? s : floor_m;
}

/* The first line, by consensus: the frames are cut into runs (at most
 * CHUNKS, of 3 frames at least), each
 * stands for its median point, and of the lines through two of those the one
 * with the most frames within 3 start_m of it wins (frames in contact lie on
 * one line; flights lie above it, however many they are). Without a scale,
 * the median of slopes between frames half the clip apart, through a low
 * quarter of the heights. */
#define CHUNKS 60
#define COUNT_FRAMES 2000 /* frames a candidate is counted on, evenly spaced */

static void median_slope_line(const double *x, const double *y, long n, jc_TrackSurfaceLine *L, double *work)
{
    const long h = n / 2 > 0 ? n / 2 : 1;
    long m = 0;
    for (long i = 0; i + h < n; ++i) {
        const double dx = x[i + h] - x[i];
        if (fabs(dx) > 0) work[m++] = (y[i + h] - y[i]) / dx;
    }
    L->b = m > 0 ? quantile(work, m, 0.5) : 0.0;
    for (long i = 0; i < n; ++i) work[i] = y[i] - L->b * (x[i] - L->x_mid);
    L->a = quantile(work, n, 0.25);
}

static void first_line(const double *x, const double *y, long n, double scale, jc_TrackSurfaceLine *L, double *work)
{
    double xm = 0;
    for (long i = 0; i < n; ++i) xm += x[i];
    L->x_mid = xm / (double)n;
    const int chunks = n / 3 < CHUNKS ? (int)(n / 3) : CHUNKS;
    if (!(scale > 0) || chunks < 4) {
        median_slope_line(x, y, n, L, work);
        return;
    }
    double cx[CHUNKS], cy[CHUNKS];
    for (int k = 0; k < chunks; ++k) {
        const long a = n * k / chunks, b = n * (k + 1) / chunks;
        for (long i = a; i < b; ++i) work[i - a] = x[i];
        cx[k] = quantile(work, b - a, 0.5);
        for (long i = a; i < b; ++i) work[i - a] = y[i];
        cy[k] = quantile(work, b - a, 0.5);
    }
    const long stride = n > COUNT_FRAMES ? n / COUNT_FRAMES : 1;
    const double cut = SURFACE_CUT_SIGMAS * scale;
    long best = -1;
    for (int p = 0; p < chunks; ++p)
        for (int q = p + 1; q < chunks; ++q) {
            const double dx = cx[q] - cx[p];
            if (!(fabs(dx) > 0)) continue;
            const double b = (cy[q] - cy[p]) / dx, a = cy[p] + b * (L->x_mid - cx[p]);
            long count = 0;
            for (long i = 0; i < n; i += stride) count += fabs(y[i] - (a + b * (x[i] - L->x_mid))) <= cut;
            if (count > best) best = count, L->a = a, L->b = b;
        }
    if (best < 0) median_slope_line(x, y, n, L, work);
}

/* The frames within cut of the line, in runs of at least min_run (or all
 * of them when the clip is shorter than a run). A run goes on across a
 * lone frame off the line (noise: a hop lasts 2 frames at least), which is
 * itself left out. A run's end that meets frames off the line loses erode
 * frames: a flight rises from contact by less than the noise for a while
 * (by t^3 from a slide), and those frames, last before the hop and so far
 * along the ramp, would tilt the line. */
static int near_line(const double *x, const double *y, const jc_TrackSurfaceLine *L, double cut, long i)
{
    return fabs(y[i] - (L->a + L->b * (x[i] - L->x_mid))) <= cut;
}

static long mark_contact(const double *x, const double *y, long n, const jc_TrackSurfaceLine *L, double cut,
                         long min_run, long erode, unsigned char *keep)
{
    const long need = n < min_run ? 1 : min_run;
    long kept = 0, i = 0;
    memset(keep, 0, (size_t)(n > 0 ? n : 0));
    while (i < n) {
        if (!near_line(x, y, L, cut, i)) {
            i++;
            continue;
        }
        long last = i; /* the run's last frame near the line */
        for (long j = i + 1; j < n; ++j) {
            if (near_line(x, y, L, cut, j)) last = j;
            else if (!(j + 1 < n && near_line(x, y, L, cut, j + 1))) break;
        }
        if (last - i + 1 >= need) {
            const long a = i > 0 ? i + erode : 0, b = last + 1 < n ? last + 1 - erode : n;
            for (long k = a; k < b; ++k)
                if (near_line(x, y, L, cut, k)) keep[k] = 1, kept++;
        }
        i = last + 1;
    }
    return kept;
}

/* Least-squares sums of a set of frames. */
typedef struct {
    double w, x, y, xx, xy;
} sums;

static void add_frame(sums *s, double x, double y, double sign)
{
    s->w += sign, s->x += sign * x, s->y += sign * y, s->xx += sign * x * x, s->xy += sign * x * y;
}

/* Drops the runs of contact that sit above the line the other runs give
 * (their mean residual beyond 3 noises over its root length and half a
 * noise): a low flight's frames, not contact, which a line through all of
 * them would tilt to meet, most where few frames far along the ramp pull
 * hardest. The surface is never above the frames in contact. Only a run the
 * others outweigh is judged. Returns the frames dropped. */
static long drop_runs_above(const double *x, const double *y, long n, double noise, unsigned char *keep)
{
    sums all = {0};
    for (long i = 0; i < n; ++i)
        if (keep[i]) add_frame(&all, x[i], y[i], 1.0);
    long dropped = 0;
    for (long a = 0; a < n;) {
        if (!keep[a]) {
            a++;
            continue;
        }
        /* A run, as mark_contact makes them: across a lone frame left out. */
        long b = a;
        sums run = {0};
        while (b < n && (keep[b] || (b + 1 < n && keep[b + 1]))) {
            if (keep[b]) add_frame(&run, x[b], y[b], 1.0);
            b++;
        }
        const sums rest = {all.w - run.w, all.x - run.x, all.y - run.y, all.xx - run.xx, all.xy - run.xy};
        const double det = rest.w * rest.xx - rest.x * rest.x;
        /* The others outweigh the run: a line they give is the better. */
        if (rest.w >= 3 && rest.w > run.w && det > 1e-12 * rest.w * rest.xx) {
            const double bb = (rest.w * rest.xy - rest.x * rest.y) / det, aa = (rest.y - bb * rest.x) / rest.w;
            double mean = 0;
            for (long k = a; k < b; ++k)
                if (keep[k]) mean += y[k] - (aa + bb * x[k]);
            mean /= run.w;
            if (mean > RUN_ABOVE_SIGMAS * noise / sqrt(run.w) && mean > 0.5 * noise) {
                for (long k = a; k < b; ++k) keep[k] = 0;
                dropped += (long)run.w;
            }
        }
        a = b;
    }
    return dropped;
}

double jc_track_frame_noise(const double *x, const double *y, long n, double *work)
{
    long m = 0;
    for (long i = 0; i + 3 < n; ++i) {
        work[m++] = fabs(x[i + 3] - 3 * x[i + 2] + 3 * x[i + 1] - x[i]);
        work[m++] = fabs(y[i + 3] - 3 * y[i + 2] + 3 * y[i + 1] - y[i]);
    }
    return m > 0 ? MAD_TO_SIGMA * quantile(work, m, 0.5) / sqrt(20.0) : 0.0;
}

int jc_track_surface_fit(const double *x, const double *y, long n, double fps, double floor_m, double start_m,
                         unsigned char *contact, jc_TrackSurfaceLine *out)
{
    /* A run of contact: CONTACT_RUN_FRAMES and CONTACT_RUN_S at least; its
     * ends next to a hop lose CONTACT_ERODE_S (a frame at least). */
    const int rate = isfinite(fps) && fps > 0;
    const long min_run = (long)(rate ? fmax(CONTACT_RUN_FRAMES, ceil(CONTACT_RUN_S * fps - 1e-9)) : CONTACT_RUN_FRAMES);
    const long erode = rate ? (long)fmax(1.0, ceil(CONTACT_ERODE_S * fps - 1e-9)) : 1;
    memset(out, 0, sizeof *out);
    memset(contact, 0, (size_t)(n > 0 ? n : 0));
    if (n < 3) return -1;
    double *work = malloc((size_t)n * sizeof *work);
    unsigned char *prev = malloc((size_t)n);
    if (!work || !prev) {
        free(work);
        free(prev);
        return -2;
    }
    first_line(x, y, n, start_m >= floor_m ? start_m : 0.0, out, work);
    memset(contact, 1, (size_t)n);
    /* The first cut is tight, at the frame-to-frame noise when it is known:
     * a scale taken from every frame would hold the flights' low ends. */
    double s = start_m >= floor_m ? start_m : scale_of(x, y, contact, n, out, floor_m, work);
    int rc = -1;
    for (int pass = 0; pass < SURFACE_PASSES; ++pass) {
        memcpy(prev, contact, (size_t)n);
        if (mark_contact(x, y, n, out, SURFACE_CUT_SIGMAS * s, min_run, erode, contact) < 3) {
            rc = -1;
            break;
        }
        drop_runs_above(x, y, n, s, contact);
        if (line_fit(x, y, contact, n, out) != 0) {
            rc = -1;
            break;
        }
        /* The cut never narrows below the frame-to-frame noise: a scale from
         * a few frames can run small and lose frames in contact each pass. */
        s = fmax(scale_of(x, y, contact, n, out, floor_m, work), start_m);
        rc = 0;
        if (pass > 0 && memcmp(prev, contact, (size_t)n) == 0) break;
    }
    if (rc == 0) {
        /* The noise: the RMS of the frames in contact about the line (more
         * exact than the median's scale used to pick them), less the line's
         * two values, for a Gaussian cut at the cut used (its variance
         * shrinks by truncated_variance; a fixed point in sigma). */
        double ss = 0;
        for (long i = 0; i < n; ++i)
            if (contact[i]) ss += pow(y[i] - (out->a + out->b * (x[i] - out->x_mid)), 2);
        const double rms = out->contact > 2 ? sqrt(ss / (double)(out->contact - 2)) : s;
        double sigma = rms;
        for (int k = 0; k < 20; ++k) sigma = rms / sqrt(truncated_variance(SURFACE_CUT_SIGMAS * s / sigma));
        s = sigma >= floor_m ? sigma : floor_m;
        out->sigma_m = s;
        out->var_a = s * s / (double)out->contact;
        out->var_b = out->sxx > 0 ? s * s / out->sxx : INFINITY;
    } else {
        memset(contact, 0, (size_t)n);
    }
    free(work);
    free(prev);
    return rc;
}
