/* What a track says beyond positions: the noise, the surface, the height of
 * the centre above it and the hops, θ unwrapped and ω. */
#include "raw.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of v[0..n) (reordered); NaN for n = 0. */
static double median(double *v, long n)
{
    if (n <= 0) return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The noise of the centre's coordinates: third differences of a smooth
 * path are small next to noise, whose third difference has variance 20 σ²;
 * the median absolute value (× 1.4826 for a Gaussian) ignores the impacts. */
static double noise_estimate(const cli_Track *t, double *work)
{
    long m = 0;
    for (long i = 0; i + 3 < t->n; ++i) {
        work[m++] = fabs(t->x_m[i + 3] - 3 * t->x_m[i + 2] + 3 * t->x_m[i + 1] - t->x_m[i]);
        work[m++] = fabs(t->y_m[i + 3] - 3 * t->y_m[i + 2] + 3 * t->y_m[i + 1] - t->y_m[i]);
    }
    return m > 0 ? 1.4826 * median(work, m) / sqrt(20.0) : NAN;
}

/* The line y = a + b x through the frames in contact. It starts level
 * through the first frames (the body is released on the surface); each pass
 * keeps the runs of at least SURFACE_RUN consecutive frames within cut of
 * the line and fits it again by least squares. A flight's low first and
 * last frames and a bounce seen between two frames make short runs: left
 * out, as they would tilt the line where the body is mostly in the air. */
#define SURFACE_RUN 4
#define SURFACE_START 8

static int surface_line(const cli_Track *t, double cut, int fit_tilt, double *work, unsigned char *keep, double *a,
                        double *b, double *tilt)
{
    const long first = t->n < SURFACE_START ? t->n : SURFACE_START;
    for (long i = 0; i < first; ++i) work[i] = t->y_m[i];
    *a = median(work, first);
    *b = 0;
    for (int pass = 0; pass < 6; ++pass) {
        long run = 0;
        for (long i = 0; i <= t->n; ++i) {
            const int near = i < t->n && !(t->y_m[i] - (*a + *b * t->x_m[i]) > cut);
            if (i < t->n) keep[i] = 0;
            if (near) {
                run++;
                continue;
            }
            if (run >= SURFACE_RUN)
                for (long k = i - run; k < i; ++k) keep[k] = 1;
            run = 0;
        }
        double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (long i = 0; i < t->n; ++i) {
            if (!keep[i]) continue;
            sw += 1;
            sx += t->x_m[i];
            sy += t->y_m[i];
            sxx += t->x_m[i] * t->x_m[i];
            sxy += t->x_m[i] * t->y_m[i];
        }
        if (sw < 3) return -1;
        const double det = sw * sxx - sx * sx;
        /* A centre that hardly moved along the incline: a level line. */
        *tilt = det > 1e-12 * sw * sxx ? (sw * sxy - sx * sy) / det : 0.0;
        /* Without fit_tilt the given incline and axes are trusted: a tilt
         * fitted on the frames in contact, mostly before the first hop,
         * would move the far end of the ramp by more than the noise. */
        *b = fit_tilt ? *tilt : 0.0;
        *a = (sy - *b * sx) / sw;
    }
    return 0;
}

int cli_track_derive(const char *name, const cli_TrackOptions *opt, cli_Track *t, char *err, size_t err_len)
{
    double *work = malloc((size_t)(2 * t->n + 2) * sizeof *work);
    if (!work) {
        snprintf(err, err_len, "%s: out of memory", name);
        return -1;
    }
    t->noise_m = noise_estimate(t, work);
    double sigma = t->noise_m;
    if (!isnan(t->sigma_m) && !(sigma >= t->sigma_m)) sigma = t->sigma_m;
    /* Noiseless or very short data: no finer than 10 µm, beyond what any video resolves. */
    if (!(sigma >= 1e-5)) sigma = 1e-5;
    t->sigma_m = sigma;
    const double k = opt->hop_sigmas >= 1 ? opt->hop_sigmas : 5.0;
    double a, b, tilt;
    if (surface_line(t, 3 * sigma, opt->fit_tilt, work, t->airborne, &a, &b, &tilt) != 0) {
        free(work);
        snprintf(err, err_len, "%s: too few frames in contact to place the surface (check --incline and --axes)", name);
        return -1;
    }
    t->surface_tilt_rad = atan(tilt);
    for (long i = 0; i < t->n; ++i) t->y_m[i] = t->radius_m + t->y_m[i] - (a + b * t->x_m[i]);
    /* Hops: runs of frames with the centre clearly above r. */
    t->hop_threshold_m = k * sigma;
    t->hops = 0;
    for (long i = 0; i < t->n; ++i) {
        t->airborne[i] = t->y_m[i] > t->radius_m + t->hop_threshold_m;
        if (t->airborne[i] && (i == 0 || !t->airborne[i - 1])) t->hops++;
    }
    /* θ unwrapped along the frames that have it; ω by central differences. */
    long prev = -1, m = 0;
    for (long i = 0; i < t->n; ++i) {
        if (isnan(t->theta_rad[i])) continue;
        if (prev >= 0) {
            const double d = t->theta_rad[i] - t->theta_rad[prev];
            t->theta_rad[i] -= 2 * CLI_PI * floor(d / (2 * CLI_PI) + 0.5);
        }
        prev = i;
    }
    for (long i = 0; i < t->n; ++i) {
        t->omega_radps[i] = NAN;
        if (isnan(t->theta_rad[i])) continue;
        const long lo = i > 0 && !isnan(t->theta_rad[i - 1]) ? i - 1 : i;
        const long hi = i + 1 < t->n && !isnan(t->theta_rad[i + 1]) ? i + 1 : i;
        if (hi > lo) t->omega_radps[i] = (t->theta_rad[hi] - t->theta_rad[lo]) / (t->t_s[hi] - t->t_s[lo]);
    }
    if (t->has_mark) {
        for (long i = 0; i < t->n; ++i)
            if (!isnan(t->theta_rad[i])) m++;
        if (m < 2) {
            free(work);
            snprintf(err, err_len, "%s: the mark track '%s' has fewer than 2 frames with the centre", name, t->mark_name);
            return -1;
        }
    }
    free(work);
    return 0;
}
