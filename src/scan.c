/*
 * First crossing of zero among several functions f(th) = T0 + th T1.
 *
 * The guarantee: with K >= |f''| on the scanned range (trigpoly.c),
 *     f(th + h) >= f(th) + f'(th) h - K h^2 / 2,
 * so while f > 0 the step h* that zeroes this lower bound cannot cross a
 * root: no root window, however narrow, is stepped over. Near a simple root
 * h* tends to the Newton step, so the approach is quadratic; once the root
 * is provably unique ahead (f' stays negative over the bracket because
 * K * width < |f'|), the sign change is confirmed and GSL's Brent solver
 * polishes it. Values within rounding noise of zero count as zero.
 * A function that only touches zero (a double root) is reported
 * as grazing once the safe step falls below the tolerance.
 */
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <float.h>
#include <math.h>

/* Enough for ~1e5 turns of the rim with room for slow grazing approaches. */
#define SCAN_MAX_STEPS 20000000L
#define POLISH_MAX_ITER 200

typedef struct {
    const jc_TrigLin *f;
    double sign;
} signed_fn;

static double signed_value(double th, void *params)
{
    const signed_fn *sf = params;
    return sf->sign * jc_tl_value(sf->f, th);
}

/* Largest h for which the quadratic lower bound stays >= 0 (g > 0 or g = 0, gd > 0). */
static double safe_step(double g, double gd, double K)
{
    if (K <= 0.0) return gd < 0.0 ? g / -gd : INFINITY;
    double root = sqrt(gd * gd + 2.0 * K * g);
    return gd >= 0.0 ? (gd + root) / K : 2.0 * g / (root - gd);
}

/* Root of sign*f between a (positive) and b (<= 0), a unique one. */
static int polish(const jc_TrigLin *f, double sign, double a, double b, double tol,
                  double *root, char *err, size_t err_len)
{
    signed_fn sf = {f, sign};
    if (signed_value(b, &sf) == 0.0) { *root = b; return JC_OK; }
    double lo = a < b ? a : b, hi = a < b ? b : a;
    gsl_function fn = {signed_value, &sf};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) return jc_fail(err, err_len, JC_ENOMEM, "root polishing: out of memory");
    gsl_root_fsolver_set(s, &fn, lo, hi);
    int status = GSL_CONTINUE, iter = 0;
    while (status == GSL_CONTINUE && iter++ < POLISH_MAX_ITER) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                        gsl_root_fsolver_x_upper(s), tol, 0.0);
    }
    *root = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    if (status != GSL_SUCCESS)
        return jc_fail(err, err_len, JC_ENUMERIC,
                       "root polishing did not converge in [%.17g, %.17g] rad", lo, hi);
    return JC_OK;
}

int jc_scan_first(const jc_ScanSet *set, double th_from, double th_to, double tol_rad,
                  jc_ScanHit *hit, char *err, size_t err_len)
{
    const double dir = th_to >= th_from ? 1.0 : -1.0;
    const double span = fabs(th_to - th_from);
    const double th_abs_max = fmax(fabs(th_from), fabs(th_to));
    /* Below a few ulps of th a step would not move th at all. */
    const double tol = fmax(tol_rad, 8.0 * DBL_EPSILON * th_abs_max);
    double K[JC_SCAN_MAX], noise[JC_SCAN_MAX];
    for (int i = 0; i < set->count; ++i) {
        K[i] = jc_tl_curvature_bound(set->f[i], th_abs_max);
        noise[i] = 64.0 * DBL_EPSILON * jc_tl_magnitude_bound(set->f[i], th_abs_max);
    }

    double u = 0.0;          /* distance travelled from th_from */
    double cand_u = span;    /* a confirmed root (or the range end) ahead */
    int cand_i = -1;
    *hit = (jc_ScanHit){.index = -1, .theta = th_to, .grazing = 0, .steps = 0};

    for (long step = 0; step < SCAN_MAX_STEPS; ++step) {
        const double th = th_from + dir * u;
        double h = cand_u - u;
        int min_i = -1;
        hit->steps = (int)(step < 2147483647L ? step : 2147483647L);
        for (int i = 0; i < set->count; ++i) {
            if (i == cand_i) continue; /* positive up to its confirmed root */
            double f, df;
            jc_tl_eval(set->f[i], th, &f, &df);
            double g = set->sign[i] * f;
            const double gd = set->sign[i] * dir * df;
            /* Within rounding noise of zero is zero: rising away from it is
             * fine (a turning point at the start), falling is a crossing. */
            if (g <= noise[i]) {
                if (gd <= 0.0 || g < -noise[i]) {
                    hit->index = i;
                    hit->theta = th;
                    hit->grazing = (gd == 0.0);
                    return JC_OK;
                }
                g = 0.0;
            }
            double hi = safe_step(g, gd, K[i]);
            if (gd < 0.0) {
                /* Bracket a simple root where it is provably unique. */
                const double hn = g / -gd;
                if (2.0 * hn * K[i] < -gd && u + 2.0 * hn < cand_u) {
                    const double b = th + dir * 2.0 * hn;
                    if (set->sign[i] * jc_tl_value(set->f[i], b) <= 0.0) {
                        double root = b;
                        int st = polish(set->f[i], set->sign[i], th, b, tol, &root, err, err_len);
                        if (st != JC_OK) return st;
                        cand_u = fmin(fabs(root - th_from), cand_u);
                        cand_i = i;
                        h = fmin(h, cand_u - u);
                        continue;
                    }
                }
            }
            if (hi < h) { h = hi; min_i = i; }
        }
        if (u + h >= cand_u) {
            hit->index = cand_i;
            hit->theta = cand_i < 0 ? th_to : th_from + dir * cand_u;
            return JC_OK;
        }
        if (h < tol && min_i >= 0) {
            /* A double root: the function touches zero within the tolerance. */
            hit->index = min_i;
            hit->theta = th;
            hit->grazing = 1;
            return JC_OK;
        }
        u += h;
    }
    return jc_fail(err, err_len, JC_ELIMIT,
                   "crossing search took more than %ld steps between th = %.6g and %.6g rad",
                   SCAN_MAX_STEPS, th_from, th_to);
}
