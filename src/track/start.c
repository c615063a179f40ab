/* What a track says about the body at one frame (its state, from the frames
 * that follow), where its hops are, and which frames a window holds. */
#include "track_internal.h"

#include <math.h>
#include <string.h>

/* Value and slope at t0 of the least-squares quadratic through (t, v):
 * over a few frames the motion is smooth enough for a parabola, and a
 * parabola averages the noise of every frame. -1 with fewer than 3 points. */
static int quad_fit(const double *t, const double *v, long n, double t0, double *val, double *slope)
{
    double s[5] = {0}, b[3] = {0};
    long used = 0;
    for (long i = 0; i < n; ++i) {
        if (!isfinite(v[i])) continue;
        const double u = t[i] - t0;
        double p = 1.0;
        for (int k = 0; k < 5; ++k, p *= u) {
            s[k] += p;
            if (k < 3) b[k] += p * v[i];
        }
        ++used;
    }
    if (used < 3) return -1;
    /* Normal equations [s0 s1 s2; s1 s2 s3; s2 s3 s4] c = b, by Cramer. */
    const double a00 = s[0], a01 = s[1], a02 = s[2], a11 = s[2], a12 = s[3], a22 = s[4];
    const double det = a00 * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02);
    if (!(fabs(det) > 0.0)) return -1;
    const double c0 = (b[0] * (a11 * a22 - a12 * a12) - a01 * (b[1] * a22 - a12 * b[2]) + a02 * (b[1] * a12 - a11 * b[2])) / det;
    const double c1 = (a00 * (b[1] * a22 - a12 * b[2]) - b[0] * (a01 * a22 - a12 * a02) + a02 * (a01 * b[2] - b[1] * a02)) / det;
    *val = c0;
    *slope = c1;
    return 0;
}

int jc_track_start_estimate(const jc_Track *t, long first, long span, double radius_m, double theta_fallback_rad,
                            double hop_threshold_m, jc_State *out)
{
    if (first < 0 || span < 3 || t->n - first < 3) return -1;
    const long n = t->n - first < span ? t->n - first : span;
    const double *ts = t->t_s + first, t0 = t->t_s[first];
    double x, vx, y, vy, th = theta_fallback_rad, w = NAN;
    if (quad_fit(ts, t->x_m + first, n, t0, &x, &vx) != 0 || quad_fit(ts, t->y_m + first, n, t0, &y, &vy) != 0)
        return -1;
    if (t->has_mark && t->theta_rad && quad_fit(ts, t->theta_rad + first, n, t0, &th, &w) != 0) th = theta_fallback_rad;
    out->t_s = t0;
    out->x_m = x;
    out->theta_rad = th;
    if (y - radius_m < hop_threshold_m) {
        /* In contact: rolling, the only start the frames can tell apart
         * from noise. */
        /* Both tell omega when rolling: the centre's speed over r, and the
         * mark's angle; weighted by their inverse variances (a mark at a
         * from C has angle noise sigma sqrt 2 / a, the centre sigma / r). */
        const double a = isfinite(t->mark_radius_m) && t->mark_radius_m > 0.0 ? t->mark_radius_m : radius_m;
        const double wx = radius_m * radius_m, wt = 0.5 * a * a;
        w = isfinite(w) ? (wt * w + wx * vx / radius_m) / (wt + wx) : vx / radius_m;
        out->y_m = radius_m;
        out->vy_mps = 0.0;
        out->omega_radps = w;
        out->vx_mps = radius_m * w;
    } else {
        out->y_m = y;
        out->vy_mps = vy;
        out->vx_mps = vx;
        out->omega_radps = isfinite(w) ? w : 0.0;
    }
    return 0;
}

double jc_track_mark_offset_rad(const jc_Model *m, double mark_angle_rad)
{
    return m->body.cm_angle_rad - mark_angle_rad;
}

double jc_track_mark_radius(const jc_Track *t, const jc_Model *m)
{
    if (t->has_mark && isfinite(t->mark_radius_m) && t->mark_radius_m > 0.0) return t->mark_radius_m;
    double a = 0.0;
    for (int i = 0; i < m->setup.body.part_count; ++i) a = fmax(a, m->setup.body.parts[i].offset_m);
    return a > 0.0 ? a : m->body.radius_m;
}

void jc_track_find_hops(const double *t_s, const double *x_m, const double *y_m, long n, double radius_m,
                        double threshold_m, jc_TrackHops *out)
{
    memset(out, 0, sizeof *out);
    out->first_liftoff_t_s = out->first_liftoff_x_m = NAN;
    long i = 0;
    while (i < n) {
        if (!(y_m[i] - radius_m > threshold_m)) {
            i++;
            continue;
        }
        long j = i;
        double top = y_m[i] - radius_m;
        while (j + 1 < n && y_m[j + 1] - radius_m > threshold_m) top = fmax(top, y_m[++j] - radius_m);
        if (j > i) {
            if (out->hops == 0) {
                const long c = i > 0 ? i - 1 : i; /* the last frame in contact */
                out->first_liftoff_t_s = t_s[c];
                out->first_liftoff_x_m = x_m[c];
            }
            if (out->hops < JC_TRACK_MAX_HOPS) {
                out->first[out->hops] = i;
                out->last[out->hops] = j;
                out->height_m[out->hops] = top;
            }
            out->hops++;
        }
        i = j + 1;
    }
}

void jc_track_window(const jc_Track *t, double from_s, double to_s, long *first, long *count)
{
    long a = 0, b = t->n;
    while (a < t->n && !isnan(from_s) && t->t_s[a] < from_s) ++a;
    while (b > a && !isnan(to_s) && t->t_s[b - 1] > to_s) --b;
    *first = a;
    *count = b - a;
}

void jc_track_start_setup(const jc_Track *t, long first, long end, double radius_m, const jc_Setup *setup,
                          jc_State *out)
{
    while (first + 1 < end && !isfinite(t->x_m[first])) first++;
    memset(out, 0, sizeof *out);
    out->t_s = t->t_s[first];
    out->x_m = t->x_m[first];
    out->y_m = radius_m;
    out->theta_rad = setup->theta0_rad;
    out->omega_radps = setup->omega0_radps;
    out->vx_mps = radius_m * out->omega_radps;
}
