/*
 * First crossing of zero among several watched functions of one variable u
 * (the angle th on the rolling path, the time t in flight).
 *
 * The guarantee: with M3 >= |f'''| over the scanned range,
 *     f(u + h) >= f + f' h + f'' h^2/2 - M3 h^3/6,
 * so while f > 0 the step h* to the first positive root of this cubic lower
 * bound cannot cross a root: no root window, however narrow, is stepped
 * over. (A cubic rather than a quadratic bound because a body leaving the
 * incline starts with a gap that grows like t^3: with only a bound on f''
 * the first steps would crawl.) Near a simple root h* tends to the Newton
 * step, so the approach is fast; once the root is provably unique ahead
 * (f' stays negative across the bracket), the sign change is confirmed and
 * Halley's iteration on the exact derivatives (or, for a general function
 * that asks for it, GSL's Brent solver) polishes it. Values within rounding
 * noise of zero count as zero. A function that only touches zero (a double
 * root) is reported as grazing once the safe step falls below the tolerance.
 */
#include "internal.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* Enough for ~1e5 turns of the rim with room for slow grazing approaches. */
#define SCAN_MAX_STEPS 20000000L
#define POLISH_MAX_ITER 200
/* The longest step where a bound on |f'''| grows with |u| (third_slope): the
 * bound is taken over the step's window rather than over the whole range
 * (the rolling path's th T1(th) terms made it grow with the ramp's end, 32
 * rad for the paper's ramp, where the first events lie at 1 to 13 rad).
 * Shorter windows give tighter bounds and longer steps, but more windows:
 * 1 rad is about where that balances (docs/performance.md). */
#ifndef SCAN_WINDOW
#define SCAN_WINDOW 1.0
#endif

static double fn_value(double u, void *params)
{
    const jc_ScanFn *fn = params;
    if (fn->value) return fn->sign * fn->value(fn->ctx, u);
    double d[3];
    fn->eval(fn->ctx, u, d);
    return fn->sign * d[0];
}

/* The cube root of x >= 0: a first guess from the exponent bits (within a
 * few per cent), then Halley's iteration, cubically convergent: three steps
 * reach rounding (at most 4 ulps from libm's over 2e7 values from 1e-290 to
 * 1e290; the safe step shades its root by 1e-12, and tests/test_scan.c
 * holds the cubic's root to GSL's). Not libm's cbrt, which splits and
 * rebuilds the exponent by function calls (frexp, ldexp), a visible part
 * of a rolling prediction's time. Outside [1e-290, 1e290], where y^3 could
 * leave the normal range: libm. */
static double cube_root(double x)
{
    if (!(x >= 1e-290 && x <= 1e290)) return cbrt(x);
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits = bits / 3 + UINT64_C(0x2a9f7893782da1ce);
    double y;
    memcpy(&y, &bits, sizeof y);
    for (int i = 0; i < 3; ++i) {
        const double y3 = y * y * y;
        y -= y * ((y3 - x) / (2.0 * y3 + x));
    }
    return y;
}

double jc_cubic_first_positive(double a, double b, double c)
{
    /* GSL's gsl_poly_solve_cubic, term for term, with a cube root for its
     * pow(x, 1/3) and one sincos for its three cosines (calls into libm),
     * and only the smallest positive root kept (tests/test_scan.c compares
     * the two). */
    const double q = a * a - 3.0 * b, r = 2.0 * a * a * a - 9.0 * a * b + 27.0 * c;
    const double Q = q / 9.0, R = r / 54.0, Q3 = Q * Q * Q, R2 = R * R;
    const double CR2 = 729.0 * r * r, CQ3 = 2916.0 * q * q * q, shift = a / 3.0;
    double x[3];
    int n = 3;
    if (R == 0.0 && Q == 0.0) {
        x[0] = x[1] = x[2] = -shift;
    } else if (CR2 == CQ3) {
        const double sq = sqrt(Q);
        x[0] = R > 0.0 ? -2.0 * sq - shift : -sq - shift;
        x[1] = R > 0.0 ? sq - shift : -sq - shift;
        x[2] = R > 0.0 ? sq - shift : 2.0 * sq - shift;
    } else if (R2 < Q3) {
        const double ratio = (R >= 0.0 ? 1.0 : -1.0) * sqrt(R2 / Q3);
        const double third = acos(ratio) / 3.0, norm = -2.0 * sqrt(Q);
        const double ct = cos(third), st = sin(third), half_sqrt3 = 0.86602540378443864676;
        x[0] = norm * ct - shift;
        x[1] = norm * (-0.5 * ct - half_sqrt3 * st) - shift; /* cos(third + 2 pi/3) */
        x[2] = norm * (-0.5 * ct + half_sqrt3 * st) - shift; /* cos(third - 2 pi/3) */
    } else {
        const double A = -(R >= 0.0 ? 1.0 : -1.0) * cube_root(fabs(R) + sqrt(R2 - Q3));
        x[0] = A + Q / A - shift;
        n = 1;
    }
    double best = INFINITY;
    for (int i = 0; i < n; ++i)
        if (x[i] > 0.0 && x[i] < best) best = x[i];
    return best;
}

/* Smallest h > 0 with g + g1 h + g2 h^2/2 - m3 h^3/6 = 0 (g >= 0), or INFINITY. */
static double safe_step(double g, double g1, double g2, double m3)
{
    double roots[3];
    int n = 0;
    if (g == 0.0) {
        /* Rising from zero: p(h)/h = g1 + g2 h/2 - m3 h^2/6 (h = 0 is not a step). */
        n = gsl_poly_solve_quadratic(-m3 / 6.0, 0.5 * g2, g1, &roots[0], &roots[1]);
        double h = INFINITY;
        for (int i = 0; i < n; ++i)
            if (roots[i] > 0.0 && roots[i] < h) h = roots[i];
        return h * (1.0 - 1e-12);
    }
    if (m3 > 0.0) {
        const double a = -3.0 * g2 / m3, b = -6.0 * g1 / m3, c = -6.0 * g / m3;
        if (isfinite(a) && isfinite(b) && isfinite(c)) return jc_cubic_first_positive(a, b, c) * (1.0 - 1e-12);
        m3 = 0.0; /* the cubic term is negligible at every usable scale */
    }
    if (m3 <= 0.0) n = gsl_poly_solve_quadratic(0.5 * g2, g1, g, &roots[0], &roots[1]);
    double h = INFINITY;
    for (int i = 0; i < n; ++i)
        if (roots[i] > 0.0 && roots[i] < h) h = roots[i];
    /* Shade the root by rounding so the step never lands past it. */
    return h * (1.0 - 1e-12);
}

/* Whether g + g1 x + g2 x^2/2 - m3 x^3/6 stays >= 0 on [0, h], by a
 * sufficient test: there -m3 x^3/6 >= -m3 h x^2/6, which leaves a quadratic.
 * Spares the exact cubic root, the costly part of a step, for every
 * function but the limiting one. */
static int safe_over(double g, double g1, double g2, double m3, double h)
{
    const double c = g2 - m3 * h / 3.0;
    if (g + h * (g1 + 0.5 * c * h) < 0.0) return 0;
    if (c <= 0.0 || g1 >= 0.0) return 1;
    const double x = -g1 / c; /* the convex quadratic's vertex */
    return x >= h || g - 0.5 * g1 * g1 / c >= 0.0;
}

/* The root between a (f > 0) and b (f < 0), where f' provably keeps its
 * sign and |f'| >= slope_min, by Halley's iteration on the f' and f'' eval
 * supplies, kept inside the bracket (bisection where it would leave it). It
 * starts from a, where the step's own evaluation gave f, f', f'' (da). It
 * stops where the root is provably within tol / 4 of x or of one more,
 * free, Newton step from x (below), or where the bracket is narrower than
 * tol (then its end nearer zero, as Brent's root). Halley's rather than
 * Newton's step and no evaluation repeated at a or b: a root takes about
 * two evaluations, where Brent's method took three times as many.
 * tests/test_scan.c compares the roots with GSL's Brent solver's. */
static int polish_newton(const jc_ScanFn *fn, double a, const double da[3], double b, double slope_min, double m3,
                         double tol, double *root, char *err, size_t err_len)
{
    const double sign = fn->sign, close = 0.25 * slope_min * tol;
    double pos = a, neg = b, f_pos = sign * da[0], f_neg = -INFINITY, x = a;
    double f = f_pos, df = sign * da[1], d2f = sign * da[2];
    for (int iter = 0; iter < POLISH_MAX_ITER; ++iter) {
        if (iter > 0) {
            double d[3];
            fn->eval(fn->ctx, x, d);
            f = sign * d[0];
            df = sign * d[1];
            d2f = sign * d[2];
            if (f == 0.0) {
                *root = x;
                return JC_OK;
            }
            /* The root is within e = |f| / slope_min of x, and one more
             * Newton step, free, lands within (|f''| + m3 e) e^2 / (2 |f'|)
             * of it: done where that is below tol / 4, often one
             * evaluation before the bracket would tell. */
            const double e = fabs(f) / slope_min;
            if (fabs(f) <= close || (fabs(d2f) + m3 * e) * e * e <= 0.5 * tol * fabs(df)) {
                const double next = x - f / df;
                *root = next > fmin(a, b) && next < fmax(a, b) ? next : x;
                return JC_OK;
            }
            if (f > 0.0) { pos = x; f_pos = f; }
            else { neg = x; f_neg = f; }
        }
        const double lo = pos < neg ? pos : neg, hi = pos < neg ? neg : pos;
        if (hi - lo < tol) {
            *root = f_pos <= -f_neg ? pos : neg;
            return JC_OK;
        }
        double next = 0.5 * (pos + neg);
        if (isfinite(df) && df != 0.0) {
            /* Halley: the Newton step over 1 + (Newton step) f'' / (2 f');
             * Newton's where that correction is large (far from the root). */
            const double newton = -f / df, den = 1.0 + 0.5 * newton * d2f / df;
            next = x + (den >= 0.5 && den <= 2.0 ? newton / den : newton);
        }
        /* A converged step probes half a tolerance beyond, so that the
         * bracket itself closes to the tolerance. */
        if (fabs(next - x) < 0.5 * tol) next = x + (next >= x ? 0.5 : -0.5) * tol;
        if (!(next > lo && next < hi)) next = 0.5 * (pos + neg);
        x = next;
    }
    return jc_fail(err, err_len, JC_ENUMERIC, "root polishing did not converge in [%.17g, %.17g]", fmin(a, b),
                   fmax(a, b));
}

/* By GSL's Brent solver: the caller's (a run's workspace), or NULL to make one. */
static int polish_brent(const jc_ScanFn *fn, double a, double b, double tol, gsl_root_fsolver *brent, double *root,
                        char *err, size_t err_len)
{
    const double lo = a < b ? a : b, hi = a < b ? b : a;
    gsl_function f = {fn_value, (void *)fn};
    gsl_root_fsolver *s = brent ? brent : gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) return jc_fail(err, err_len, JC_ENOMEM, "root polishing: out of memory");
    gsl_root_fsolver_set(s, &f, lo, hi);
    int status = GSL_CONTINUE, iter = 0;
    while (status == GSL_CONTINUE && iter++ < POLISH_MAX_ITER) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), tol, 0.0);
    }
    *root = gsl_root_fsolver_root(s);
    if (s != brent) gsl_root_fsolver_free(s);
    if (status != GSL_SUCCESS)
        return jc_fail(err, err_len, JC_ENUMERIC, "root polishing did not converge in [%.17g, %.17g]", lo, hi);
    return JC_OK;
}

static inline double min_d(double a, double b) { return b < a ? b : a; }
static inline double max_d(double a, double b) { return b > a ? b : a; }

/* Every watched function's f, f', f'' at u at once (d[i] for fns[i]): a set
 * that shares work between its functions (the trigonometric sets below). */
typedef void (*scan_eval_all)(void *ctx, double u, double d[][3]);

/* The scan, inlined into its two callers: jc_scan_fns_with (each function
 * evaluated by its own eval) and jc_trig_scan_run, where the shared
 * evaluation trig_eval_all is inlined into each step as well (SCAN_FLATTEN):
 * each step's size waits for its values, which then do not pass through a
 * call and memory (the same results as through the pointer). */
#if defined(__GNUC__)
#define SCAN_INLINE inline __attribute__((always_inline))
#define SCAN_FLATTEN __attribute__((flatten))
#else
#define SCAN_INLINE inline
#define SCAN_FLATTEN
#endif
static SCAN_INLINE int scan_core(const jc_ScanFn *fns, int count, scan_eval_all eval_all, void *all_ctx, double u_from,
                     double u_to, double tol_in, gsl_root_fsolver *brent, jc_ScanHit *hit, char *err,
                     size_t err_len)
{
    const double dir = u_to >= u_from ? 1.0 : -1.0;
    const double span = fabs(u_to - u_from);
    /* Below a few ulps of u a step would not move u at all. */
    const double tol = fmax(tol_in, 8.0 * DBL_EPSILON * fmax(fabs(u_from), fabs(u_to)));
    double u = 0.0;       /* distance travelled from u_from */
    double cand_u = span; /* a confirmed root (or the range end) ahead */
    int cand_i = -1;
    int first = 0;        /* the function that limited the last step goes first */
    *hit = (jc_ScanHit){.index = -1, .theta = u_to, .grazing = 0, .steps = 0};

    int windowed = 0;
    for (int i = 0; i < count; ++i) windowed |= fns[i].third_slope > 0.0;
    for (long step = 0; step < SCAN_MAX_STEPS; ++step) {
        const double at = u_from + dir * u;
        /* The third-derivative bounds hold over [at, at + dir reach]. */
        const double reach = windowed ? min_d(cand_u - u, SCAN_WINDOW) : cand_u - u;
        const double u_abs = max_d(fabs(at), fabs(at + dir * reach));
        double h = reach;
        int min_i = -1;
        hit->steps = (int)step;
        double all[JC_SCAN_MAX][3];
        if (eval_all) eval_all(all_ctx, at, all);
        for (int j = 0, i = first; j < count; ++j, i = i + 1 == count ? 0 : i + 1) {
            if (i == cand_i) continue; /* positive up to its confirmed root */
            const double m3 = fns[i].third_bound + fns[i].third_slope * u_abs;
            double own[3];
            const double *d = own;
            if (eval_all) d = all[i];
            else fns[i].eval(fns[i].ctx, at, own);
            double g = fns[i].sign * d[0];
            const double g1 = fns[i].sign * dir * d[1], g2 = fns[i].sign * d[2];
            if (g <= fns[i].noise) {
                /* Rising away from zero is fine (a turning point at the start);
                 * falling, or below the noise, is a crossing here. */
                if (g < -fns[i].noise || g1 < 0.0 || (g1 == 0.0 && g2 <= 0.0)) {
                    hit->index = i;
                    hit->theta = at;
                    /* Touching rather than crossing: within the tolerance the
                     * slope moves the function by less than its noise. */
                    hit->grazing = fabs(g1) * tol <= fns[i].noise;
                    return JC_OK;
                }
                g = 0.0;
            }
            /* Bracket a simple root where f' provably stays negative: over
             * w = 2 g / -g1, g1 + max(g2, 0) w + m3 w^2 / 2 < 0, which times
             * g1^2 / |g1| reads 2 max(g2, 0) g + 2 m3 g^2 / |g1| < g1^2, and
             * needs w <= reach. Tested so first (with room for rounding),
             * without the division on the path of every step. */
            const double g2p = g2 > 0.0 ? g2 : 0.0;
            if (g1 < 0.0 && 2.0 * g <= reach * -g1 &&
                (2.0 * g2p * g) * -g1 + 2.0 * m3 * g * g <= (1.0 + 1e-9) * (-g1 * g1 * g1)) {
                const double w = 2.0 * g / -g1;
                const double slope = g1 + g2p * w + 0.5 * m3 * w * w; /* f' is below it over [0, w] */
                if (slope < 0.0 && w <= reach && u + w < cand_u) {
                    const double b = at + dir * w;
                    /* A clear sign change only: a value within noise of zero
                     * may be a double root touched, not crossed. The Taylor
                     * bound f(b) <= g + g1 w + g2 w^2/2 + m3 w^3/6 proves it
                     * mostly without evaluating f at b. */
                    const double f_b_max = -g + (0.5 * g2 + m3 * w / 6.0) * w * w;
                    if (f_b_max + 1e-9 * g < -fns[i].noise || fn_value(b, (void *)&fns[i]) < -fns[i].noise) {
                        double root = b;
                        int st = fns[i].newton ? polish_newton(&fns[i], at, d, b, -slope, m3, tol, &root, err, err_len)
                                               : polish_brent(&fns[i], at, b, tol, brent, &root, err, err_len);
                        if (st != JC_OK) return st;
                        cand_u = min_d(fabs(root - u_from), cand_u);
                        cand_i = i;
                        h = min_d(h, cand_u - u);
                        continue;
                    }
                }
            }
            if (safe_over(g, g1, g2, m3, h)) continue;
            const double hi = safe_step(g, g1, g2, m3);
            if (hi < h) { h = hi; min_i = i; }
        }
        if (min_i >= 0) first = min_i;
        if (u + h >= cand_u) {
            hit->index = cand_i;
            hit->theta = cand_i < 0 ? u_to : u_from + dir * cand_u;
            return JC_OK;
        }
        if (h < tol && min_i >= 0) {
            /* A double root: the function touches zero within the tolerance. */
            hit->index = min_i;
            hit->theta = at;
            hit->grazing = 1;
            return JC_OK;
        }
        u += h;
    }
    return jc_fail(err, err_len, JC_ELIMIT, "crossing search took more than %ld steps between %.6g and %.6g",
                   SCAN_MAX_STEPS, u_from, u_to);
}

int jc_scan_fns(const jc_ScanFn *fns, int count, double u_from, double u_to, double tol_in,
                jc_ScanHit *hit, char *err, size_t err_len)
{
    return scan_core(fns, count, NULL, NULL, u_from, u_to, tol_in, NULL, hit, err, err_len);
}

int jc_scan_fns_with(const jc_ScanFn *fns, int count, double u_from, double u_to, double tol_in,
                     gsl_root_fsolver *brent, jc_ScanHit *hit, char *err, size_t err_len)
{
    return scan_core(fns, count, NULL, NULL, u_from, u_to, tol_in, brent, hit, err, err_len);
}

/* ---- the rolling and paper models' form: f = T0(th) + th T1(th) ---- */

/* cos(k th), sin(k th) up to degree deg only (the energy alone is of degree 1). */
static void basis_upto(jc_TrigBasis *b, double th, int deg)
{
    double c1, s1;
    jc_sincos(th, &s1, &c1);
    b->th = th;
    b->c[1] = c1;
    b->s[1] = s1;
    for (int k = 2; k <= deg; ++k) {
        b->c[k] = b->c[k - 1] * c1 - b->s[k - 1] * s1;
        b->s[k] = b->s[k - 1] * c1 + b->c[k - 1] * s1;
    }
}

/* f, f', f'' of p (degree <= deg) on the basis: jc_tl_eval3_basis_upto with
 * the k = 0 term (a constant) apart, inline in the scan's step. */
static inline void eval3(const jc_TrigLin *p, const jc_TrigBasis *b, int deg, double out[3])
{
    double t0 = p->c0[0], d0 = 0.0, e0 = 0.0, t1 = p->c1[0], d1 = 0.0, e1 = 0.0;
    for (int k = 1; k <= deg; ++k) {
        const double ck = b->c[k], sk = b->s[k], kd = (double)k, k2 = kd * kd;
        const double a0 = p->c0[k] * ck + p->s0[k] * sk, a1 = p->c1[k] * ck + p->s1[k] * sk;
        t0 += a0;
        d0 += kd * (p->s0[k] * ck - p->c0[k] * sk);
        e0 -= k2 * a0;
        t1 += a1;
        d1 += kd * (p->s1[k] * ck - p->c1[k] * sk);
        e1 -= k2 * a1;
    }
    const double th = b->th;
    out[0] = t0 + th * t1;
    out[1] = d0 + t1 + th * d1;
    out[2] = e0 + 2.0 * d1 + th * e1;
}

/* One scan of a prepared set: the functions watched (active), the basis they
 * share, and one of them alone for root polishing. */
typedef struct trig_run trig_run;
typedef struct {
    const trig_run *run;
    int i; /* in the set */
} trig_fn;
struct trig_run {
    const jc_TrigScan *set;
    int n;                   /* functions watched */
    int idx[JC_SCAN_MAX];    /* their places in the set */
    int degree;              /* the basis's */
    jc_TrigBasis *basis;     /* shared, cached by th */
    trig_fn one[JC_SCAN_MAX];
};

static void run_basis(const trig_run *r, double th)
{
    if (r->basis->th != th) basis_upto(r->basis, th, r->degree);
}

/* All watched functions in one pass: one basis, no call per function. */
static void trig_eval_all(void *ctx, double th, double d[][3])
{
    const trig_run *r = ctx;
    run_basis(r, th);
    for (int j = 0; j < r->n; ++j) {
        const int i = r->idx[j];
        eval3(r->set->f[i], r->basis, r->set->bounds[i].degree, d[j]);
    }
}

static void trig_eval(const void *ctx, double th, double out[3])
{
    const trig_fn *t = ctx;
    run_basis(t->run, th);
    eval3(t->run->set->f[t->i], t->run->basis, t->run->set->bounds[t->i].degree, out);
}

/* The value alone (the bracket's far end, Brent's polishing). */
static double trig_value(const void *ctx, double th)
{
    const trig_fn *t = ctx;
    run_basis(t->run, th);
    const jc_TrigLin *f = t->run->set->f[t->i];
    const jc_TrigBasis *b = t->run->basis;
    double t0 = f->c0[0], t1 = f->c1[0];
    for (int k = 1; k <= t->run->set->bounds[t->i].degree; ++k) {
        t0 += f->c0[k] * b->c[k] + f->s0[k] * b->s[k];
        t1 += f->c1[k] * b->c[k] + f->s1[k] * b->s[k];
    }
    return t0 + th * t1;
}

void jc_trig_scan_init(jc_TrigScan *s, const jc_ScanSet *set)
{
    s->count = set->count;
    for (int i = 0; i < set->count; ++i) {
        s->f[i] = set->f[i];
        s->sign[i] = set->sign[i];
        jc_tl_bounds(set->f[i], &s->bounds[i]);
    }
}

SCAN_FLATTEN int jc_trig_scan_run(const jc_TrigScan *s, unsigned active, double th_from, double th_to,
                                  double tol_rad, jc_ScanHit *hit, char *err, size_t err_len)
{
    const double th_abs_max = fmax(fabs(th_from), fabs(th_to));
    jc_TrigBasis basis;
    basis.th = NAN; /* nothing cached */
    basis.c[0] = 1.0;
    basis.s[0] = 0.0;
    trig_run run = {.set = s, .n = 0, .degree = 1, .basis = &basis};
    jc_ScanFn fns[JC_SCAN_MAX];
    /* Roots are polished by Halley's iteration on the exact derivatives,
     * also where the caller lends a Brent solver (jc_scan_first_with):
     * it locates them to rounding, where Brent's stopped anywhere in a
     * 1e-12 rad bracket, and takes fewer evaluations. A turning point's
     * place enters a swing's time like the square root of its error: with
     * Brent's roots the rocking hoop's period (tests/sim/test_repros.c)
     * moved by 1.4e-8 with the steps' lengths; with these it agrees to
     * 1e-9. tests/test_scan.c keeps Brent's roots as the cross-check. */
    for (int i = 0; i < s->count; ++i) {
        if (!(active & (1u << i))) continue;
        const jc_TrigBounds *b = &s->bounds[i];
        const int j = run.n++;
        run.idx[j] = i;
        run.one[j] = (trig_fn){&run, i};
        if (b->degree > run.degree) run.degree = b->degree;
        fns[j] = (jc_ScanFn){trig_eval, &run.one[j], b->third0,
                             64.0 * DBL_EPSILON * (b->mag0 + th_abs_max * b->mag1), s->sign[i], trig_value,
                             1, b->third_slope};
    }
    int st = scan_core(fns, run.n, trig_eval_all, &run, th_from, th_to, tol_rad, NULL, hit, err, err_len);
    if (hit->index >= 0) hit->index = run.idx[hit->index];
    return st;
}

int jc_scan_first(const jc_ScanSet *set, double th_from, double th_to, double tol_rad,
                  jc_ScanHit *hit, char *err, size_t err_len)
{
    return jc_scan_first_with(set, th_from, th_to, tol_rad, NULL, hit, err, err_len);
}

int jc_scan_first_with(const jc_ScanSet *set, double th_from, double th_to, double tol_rad, gsl_root_fsolver *brent,
                       jc_ScanHit *hit, char *err, size_t err_len)
{
    (void)brent; /* see jc_trig_scan_run */
    jc_TrigScan s;
    jc_trig_scan_init(&s, set);
    return jc_trig_scan_run(&s, ~0u, th_from, th_to, tol_rad, hit, err, err_len);
}
