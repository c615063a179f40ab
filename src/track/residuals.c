/* The residuals of a model against a track's frames, in units of the
 * noise, and a runs test of their signs.
 *
 * With a tracked centre: the centre's x and y at every frame and, where the
 * mark was tracked, the mark's displacement across its radius,
 * a Δθ + Δx cos θ − Δy sin θ. The mark's angle alone would not do: it was
 * measured from the tracked centre, so its error holds the centre's; the
 * displacement across the radius is the mark's own position error,
 * independent of the centre's. With a centre recovered from the mark, the
 * mark's own x and y (the recovered centre's errors are the mark's). */
#include "track_internal.h"

#include <math.h>
#include <string.h>

static int from_mark(const jc_TrackResiduals *r) { return r->t->centre_source == JC_TRACK_CENTRE_FROM_MARK; }

long jc_track_residual_count(const jc_TrackResiduals *r)
{
    const jc_Track *t = r->t;
    long k = 0;
    for (long i = r->first; i < r->first + r->count; ++i) {
        if (from_mark(r)) {
            k += isfinite(t->mark_x_m[i]) ? 2 : 0;
            continue;
        }
        if (!isfinite(t->x_m[i])) continue;
        k += 2;
        k += r->mark_radius > 0.0 && isfinite(t->theta_rad[i]);
    }
    return k;
}

void jc_track_misfit(const jc_Track *t, long first, long count, const double *x, const double *y,
                     const double *th_mark, double *rms_path_m, double *max_path_m, double *rms_theta_rad)
{
    double path = 0.0, th = 0.0, largest = 0.0;
    long n_path = 0, n_th = 0;
    for (long i = 0; i < count; ++i) {
        const long j = first + i;
        if (isfinite(t->x_m[j])) {
            const double d2 = pow(t->x_m[j] - x[i], 2) + pow(t->y_m[j] - y[i], 2);
            path += d2;
            largest = fmax(largest, d2);
            n_path++;
        }
        if (t->has_mark && isfinite(t->theta_rad[j])) {
            th += pow(remainder(t->theta_rad[j] - th_mark[i], 2.0 * JC_TRACK_PI), 2);
            n_th++;
        }
    }
    *rms_path_m = n_path ? sqrt(path / (double)n_path) : NAN;
    if (max_path_m) *max_path_m = sqrt(largest);
    *rms_theta_rad = n_th ? sqrt(th / (double)n_th) : NAN;
}

int jc_track_residuals_frame(const jc_Track *t, long j, double sigma, double a, double x, double y, double thm,
                             double f[3])
{
    if (t->centre_source == JC_TRACK_CENTRE_FROM_MARK) {
        if (!isfinite(t->mark_x_m[j])) return 0;
        f[0] = (t->mark_x_m[j] - (x + a * sin(thm))) / sigma;
        f[1] = (t->mark_y_m[j] - (y + a * cos(thm))) / sigma;
        return 2;
    }
    if (!isfinite(t->x_m[j])) return 0;
    const double dx = t->x_m[j] - x, dy = t->y_m[j] - y, tht = t->theta_rad[j];
    f[0] = dx / sigma;
    f[1] = dy / sigma;
    if (!(a > 0.0 && isfinite(tht))) return 2;
    /* The angles' difference within half a turn: an unwrapping across
     * dropped frames may have counted a turn more or less. */
    f[2] = (a * remainder(tht - thm, 2.0 * JC_TRACK_PI) + dx * cos(tht) - dy * sin(tht)) / sigma;
    return 3;
}

void jc_track_residuals_eval(const jc_TrackResiduals *r, const double *x, const double *y, const double *th, double *f,
                             unsigned char *series)
{
    long k = 0;
    for (long i = 0; i < r->count; ++i) {
        double v[3];
        /* the model's mark angle: G's less the offset */
        const int n = jc_track_residuals_frame(r->t, r->first + i, r->sigma, r->mark_radius, x[i], y[i],
                                               th[i] - r->mark_offset, v);
        for (int m = 0; m < n; ++m) {
            if (series) series[k] = (unsigned char)m;
            f[k++] = v[m];
        }
    }
}

double jc_track_residuals_runs_z(const double *f, const unsigned char *series, long n, const char **which)
{
    static const char *const names[3] = {"along the incline", "across the incline", "of the mark across its radius"};
    double worst = INFINITY;
    *which = "";
    for (int k = 0; k < 3; ++k) {
        double n1 = 0, n2 = 0, runs = 0;
        int prev = 0;
        for (long i = 0; i < n; ++i) {
            if (series[i] != k || f[i] == 0.0 || !isfinite(f[i])) continue;
            const int sgn = f[i] > 0 ? 1 : -1;
            if (sgn > 0) n1 += 1;
            else n2 += 1;
            if (sgn != prev) runs += 1;
            prev = sgn;
        }
        const double m = n1 + n2;
        if (n1 < 2 || n2 < 2) continue;
        const double mu = 2 * n1 * n2 / m + 1, var = 2 * n1 * n2 * (2 * n1 * n2 - m) / (m * m * (m - 1));
        if (!(var > 0)) continue;
        const double z = (runs - mu) / sqrt(var);
        if (z < worst) {
            worst = z;
            *which = names[k];
        }
    }
    return worst;
}
