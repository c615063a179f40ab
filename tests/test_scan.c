/* src/scan.c: jc_scan_first must never step over a root window, however
 * narrow; roots are checked against their analytic places. */
#include "test.h"

#include "internal.h" /* src/, added by tests/CMakeLists.txt */

#include <gsl/gsl_poly.h>
#include <stdint.h>

#define PI 3.14159265358979323846
#define EPS 2.220446049250313e-16

/* f = c + cos(k th): negative exactly on windows of half-width acos(c)/k
 * around the odd multiples of pi/k. */
static jc_TrigLin window_fn(double c, int k)
{
    jc_TrigLin p;
    jc_tl_zero(&p);
    jc_tl_add_cos(&p, 0, 0, c);
    jc_tl_add_cos(&p, 0, k, 1.0);
    return p;
}

/* acos(c) for c just below 1 without cancellation (1 - c is exact there). */
static double acos_near_one(double c) { return 2.0 * asin(sqrt((1.0 - c) / 2.0)); }

/* scan.c counts |f| <= 64 eps sum|coefficients| as zero (rounding noise), so
 * a root is defined only up to that noise over the slope there,
 * k sin(acos c) = k sqrt(1 - c^2); 1e-11 on top for the polishing. */
static double noise_of(double c) { return 64.0 * EPS * (1.0 + fabs(c)); }
static double root_tol(double c, int k)
{
    return 1e-11 + 2.0 * noise_of(c) / (k * sqrt((1.0 - c) * (1.0 + c)));
}

static int scan1(const jc_TrigLin *f, double sign, double from, double to, jc_ScanHit *hit)
{
    jc_ScanSet set = {.count = 1, .f = {f}, .sign = {sign}};
    char err[256] = "";
    ENSURE_OK(jc_scan_first(&set, from, to, 1e-13, hit, err, sizeof err), err);
    return 0;
}

static int test_narrow_windows_found(void)
{
    /* Window widths from 1e-2 down to 2e-7 rad, for every degree k. */
    const double widths[] = {1e-2, 1e-4, 1e-5, 1e-6, 5e-7, 3e-7, 2e-7};
    int located = 0;
    for (int k = 1; k <= JC_TRIG_DEGREE; ++k) {
        for (size_t i = 0; i < sizeof widths / sizeof widths[0]; ++i) {
            const double c = cos(k * widths[i] / 2);
            const jc_TrigLin f = window_fn(c, k);
            jc_ScanHit hit;
            if (scan1(&f, 1.0, 0.0, 200.0, &hit)) return 1;
            ENSURE_MSG(hit.index == 0, "k %d width %g: window stepped over (index %d)", k, widths[i], hit.index);
            const double depth = 1.0 - c;
            if (depth < 2.0 * noise_of(c)) {
                /* Shallower than twice the noise: the library may call the window
                 * a touch; it must still stop where |f| is within noise of 0. */
                const double zone = sqrt(2.0 * (noise_of(c) + depth)) / k;
                ENSURE_NEAR(hit.theta, PI / k, zone * 1.01); /* 1%: quadratic approximation of cos */
                continue;
            }
            ++located;
            const double first = (PI - acos_near_one(c)) / k, tol = root_tol(c, k);
            ENSURE_MSG(tol < 0.25 * widths[i], "window %g too narrow to test at k = %d", widths[i], k);
            /* Forward from 0, over many periods: the first window is the first root. */
            ENSURE_NEAR(hit.theta, first, tol);
            ENSURE(hit.steps > 0);
            /* Starting past the first window, the next one is found. */
            if (scan1(&f, 1.0, first + 2 * widths[i], 200.0, &hit)) return 1;
            ENSURE(hit.index == 0);
            ENSURE_NEAR(hit.theta, first + 2 * PI / k, tol + 1e-14); /* + rounding of the shift */
            /* Backwards from 2 pi / k: the window's far edge, pi/k + acos(c)/k. */
            if (scan1(&f, 1.0, 2 * PI / k, -0.5, &hit)) return 1;
            ENSURE(hit.index == 0);
            ENSURE_NEAR(hit.theta, (PI + acos_near_one(c)) / k, tol);
        }
    }
    ENSURE(located >= 20); /* most cases are real, located windows */
    return 0;
}

static int test_narrow_window_among_others(void)
{
    /* Several functions: a positive one, a far root, and a 1e-6 window first. */
    jc_TrigLin pos, far, narrow;
    jc_tl_zero(&pos);
    jc_tl_add_cos(&pos, 0, 0, 2.0);
    jc_tl_add_sin(&pos, 0, 3, 1.0);
    jc_tl_zero(&far); /* 1 - th/50: root at 50 */
    jc_tl_add_cos(&far, 0, 0, 1.0);
    jc_tl_add_cos(&far, 1, 0, -1.0 / 50);
    const double c = cos(3 * 0.5e-6);
    narrow = window_fn(c, 3);
    jc_ScanSet set = {.count = 3, .f = {&pos, &far, &narrow}, .sign = {1, 1, 1}};
    jc_ScanHit hit;
    char err[256] = "";
    ENSURE_OK(jc_scan_first(&set, 0.0, 100.0, 1e-13, &hit, err, sizeof err), err);
    ENSURE(hit.index == 2);
    ENSURE_NEAR(hit.theta, (PI - acos_near_one(c)) / 3, root_tol(c, 3));
    /* Without the window, the linear root: exact in binary arithmetic, 1e-11. */
    set.count = 2;
    ENSURE_OK(jc_scan_first(&set, 0.0, 100.0, 1e-13, &hit, err, sizeof err), err);
    ENSURE(hit.index == 1 && hit.grazing == 0);
    ENSURE_NEAR(hit.theta, 50.0, 1e-11);
    return 0;
}

static int test_sign_and_linear_roots(void)
{
    /* sign = -1 watches -f: f = th cos(th) - 10 is negative until its first root. */
    jc_TrigLin f;
    jc_tl_zero(&f);
    jc_tl_add_cos(&f, 0, 0, -10.0);
    jc_tl_add_cos(&f, 1, 1, 1.0);
    jc_ScanHit hit;
    if (scan1(&f, -1.0, 0.0, 40.0, &hit)) return 1;
    ENSURE(hit.index == 0);
    /* th cos th < 10 up to 3.5 pi (2 pi cos 2 pi = 6.3); from 3.5 pi to 4 pi it
     * rises from 0 to 12.6 monotonically: the first root is there, bisect it. */
    double lo = 3.5 * PI, hi = 4 * PI;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid * cos(mid) < 10.0) lo = mid; else hi = mid;
    }
    /* slope |cos th - th sin th| ~ 13 here: 1e-11 is far above rounding. */
    ENSURE_NEAR(hit.theta, 0.5 * (lo + hi), 1e-11);
    return 0;
}

static int test_root_at_start(void)
{
    jc_TrigLin f;
    jc_tl_zero(&f);
    jc_tl_add_sin(&f, 0, 1, -1.0); /* -sin th: zero at 0 and falling */
    jc_ScanHit hit;
    if (scan1(&f, 1.0, 0.0, 3.0, &hit)) return 1;
    ENSURE(hit.index == 0 && hit.theta == 0.0);
    /* Already negative at the start: reported there. */
    if (scan1(&f, 1.0, 0.5, 3.0, &hit)) return 1;
    ENSURE(hit.index == 0 && hit.theta == 0.5);
    /* Zero at the start but rising away from it (sin th from 0): not a root; the
     * next one is at pi. */
    if (scan1(&f, -1.0, 0.0, 4.0, &hit)) return 1;
    ENSURE(hit.index == 0);
    ENSURE_NEAR(hit.theta, PI, 1e-11); /* slope 1: root known to ~1e-16 */
    return 0;
}

static int test_no_root(void)
{
    const jc_TrigLin f = window_fn(1.5, 2); /* >= 0.5 everywhere */
    jc_ScanHit hit;
    if (scan1(&f, 1.0, 0.0, 50.0, &hit)) return 1;
    ENSURE(hit.index == -1 && hit.theta == 50.0);
    if (scan1(&f, 1.0, 50.0, -3.0, &hit)) return 1;
    ENSURE(hit.index == -1 && hit.theta == -3.0);
    /* Ending just before a window: nothing; just inside it: the root. */
    const double c = cos(1e-4 / 2);
    const jc_TrigLin g = window_fn(c, 1);
    const double first = PI - acos_near_one(c);
    if (scan1(&g, 1.0, 0.0, first - 1e-9, &hit)) return 1;
    ENSURE(hit.index == -1 && hit.theta == first - 1e-9);
    if (scan1(&g, 1.0, 0.0, first + 1e-9, &hit)) return 1;
    ENSURE(hit.index == 0);
    ENSURE_NEAR(hit.theta, first, root_tol(c, 1));
    /* Empty range. */
    if (scan1(&g, 1.0, 1.0, 1.0, &hit)) return 1;
    ENSURE(hit.index == -1 && hit.theta == 1.0);
    return 0;
}

static int test_touching_zero_is_grazing(void)
{
    /* 1 + cos th touches 0 at pi without changing sign: a grazing hit near pi.
     * Where exactly is limited by rounding: |f| < 64 eps * 2 is "zero", so
     * |th - pi| < sqrt(2 * 128 eps) ~ 2.4e-7; 1e-6 is the stated slack. */
    const jc_TrigLin f = window_fn(1.0, 1);
    jc_ScanHit hit;
    if (scan1(&f, 1.0, 0.0, 6.0, &hit)) return 1;
    ENSURE(hit.index == 0);
    ENSURE_NEAR(hit.theta, PI, 1e-6);
    ENSURE_MSG(hit.grazing == 1, "a double root reported as a clean crossing (grazing = %d) at %.17g",
               hit.grazing, hit.theta);
    return 0;
}

/* jc_scan_fns, the general form: a callback function of u. */
typedef struct {
    double centre, half; /* f = (u - centre)^2 - half^2 */
} parabola;

static void parabola_eval(const void *ctx, double u, double out[3])
{
    const parabola *p = ctx;
    out[0] = (u - p->centre) * (u - p->centre) - p->half * p->half;
    out[1] = 2 * (u - p->centre);
    out[2] = 2;
}

static int test_scan_fns_callback(void)
{
    const double halves[] = {1e-2, 1e-5, 1e-7};
    /* Each root polished by GSL's Brent solver (i < 3) and by the Newton
     * iteration the flight's functions use (i >= 3): the same places. */
    for (int i = 0; i < 6; ++i) {
        const parabola p = {3.0, halves[i % 3]};
        /* f''' = 0 exactly: third bound 0; rounding of f ~ a few eps * centre^2. */
        const double noise = 16 * EPS * 9.0;
        const jc_ScanFn fn = {parabola_eval, &p, 0.0, noise, 1.0, NULL, i / 3, 0.0};
        jc_ScanHit hit;
        char err[256] = "";
        ENSURE_OK(jc_scan_fns(&fn, 1, 0.0, 10.0, 1e-14, &hit, err, sizeof err), err);
        ENSURE(hit.index == 0);
        /* slope 2 half at the root: located to ~1e-14 plus the noise over the slope. */
        ENSURE_NEAR(hit.theta, 3.0 - halves[i % 3], 1e-13 + 2 * noise / (2 * halves[i % 3]));
        ENSURE_OK(jc_scan_fns(&fn, 1, 10.0, 0.0, 1e-14, &hit, err, sizeof err), err);
        ENSURE(hit.index == 0);
        ENSURE_NEAR(hit.theta, 3.0 + halves[i % 3], 1e-13 + 2 * noise / (2 * halves[i % 3]));
        ENSURE_OK(jc_scan_fns(&fn, 1, 0.0, 2.9, 1e-14, &hit, err, sizeof err), err);
        ENSURE(hit.index == -1 && hit.theta == 2.9);
    }
    return 0;
}

/* The safe step's cubic root against GSL's gsl_poly_solve_cubic, on random
 * cubics of the form the search makes (c < 0: a positive root exists) and on
 * the degenerate ones (double and triple roots). */
static int test_cubic_root_matches_gsl(void)
{
    uint64_t state = 20261124;
    int compared = 0;
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        double a, b, c;
        if (i < 3) {
            /* (x - 1)^3, (x - 1)^2 (x - 2), (x - 2)^2 (x - 1) */
            const double r[3][3] = {{1, 1, 1}, {1, 1, 2}, {2, 2, 1}};
            a = -(r[i][0] + r[i][1] + r[i][2]);
            b = r[i][0] * r[i][1] + r[i][1] * r[i][2] + r[i][0] * r[i][2];
            c = -r[i][0] * r[i][1] * r[i][2];
        } else {
            const double scale = pow(10.0, test_uniform(&state, -6.0, 6.0));
            a = test_uniform(&state, -10.0, 10.0) * scale;
            b = test_uniform(&state, -10.0, 10.0) * scale * scale;
            c = -test_uniform(&state, 0.0, 10.0) * scale * scale * scale;
        }
        double x[3];
        const int n = gsl_poly_solve_cubic(a, b, c, &x[0], &x[1], &x[2]);
        double want = INFINITY;
        for (int k = 0; k < n; ++k)
            if (x[k] > 0.0 && x[k] < want) want = x[k];
        const double got = jc_cubic_first_positive(a, b, c);
        ENSURE_MSG(isfinite(want) == isfinite(got), "x^3 + %.17g x^2 + %.17g x + %.17g: %.17g vs GSL %.17g", a, b, c,
                   got, want);
        if (!isfinite(want)) continue;
        /* Both are the same formulas: rounding, amplified near a double root. */
        const double tol = 1e-9 * (fabs(want) + fabs(a) / 3.0 + sqrt(fabs(a * a - 3.0 * b)) / 3.0);
        ENSURE_MSG(fabs(got - want) <= tol, "x^3 + %.17g x^2 + %.17g x + %.17g: %.17g vs GSL %.17g", a, b, c, got,
                   want);
        worst = fmax(worst, fabs(got - want) / fmax(fabs(want), 1e-300));
        compared++;
    }
    printf("  %d cubics: largest relative difference from GSL %.2g\n", compared, worst);
    ENSURE(compared > 100000);
    return 0;
}

/* Without a lent solver the trigonometric functions' roots are polished by
 * Newton's iteration, with one by GSL's Brent solver: on random sets of
 * T0 + th T1 functions the same function must be hit first, at the same
 * place to the tolerance (1e-12 rad each). */
/* A jc_TrigLin as a general watched function, for GSL's Brent polishing. */
static void poly_eval(const void *ctx, double u, double out[3]) { jc_tl_eval3(ctx, u, out); }
static double poly_value(const void *ctx, double u) { return jc_tl_value(ctx, u); }

/* The first crossing of the set by jc_scan_fns_with, its roots polished by
 * GSL's Brent solver (jc_scan_first's sets polish by Halley's iteration). */
static int scan_brent(const jc_ScanSet *set, double from, double to, double tol, gsl_root_fsolver *brent,
                      jc_ScanHit *hit, char *err, size_t err_len)
{
    jc_ScanFn fns[JC_SCAN_MAX];
    const double th_abs_max = fmax(fabs(from), fabs(to));
    for (int i = 0; i < set->count; ++i)
        fns[i] = (jc_ScanFn){poly_eval, set->f[i], jc_tl_third_bound(set->f[i], th_abs_max),
                             64.0 * EPS * jc_tl_magnitude_bound(set->f[i], th_abs_max), set->sign[i], poly_value,
                             0, 0.0};
    return jc_scan_fns_with(fns, set->count, from, to, tol, brent, hit, err, err_len);
}

static int test_newton_polish_matches_brent(void)
{
    uint64_t state = 20261125;
    gsl_root_fsolver *brent = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    ENSURE(brent != NULL);
    int hits = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        jc_TrigLin f[3];
        jc_ScanSet set = {.count = 3};
        for (int i = 0; i < 3; ++i) {
            jc_tl_zero(&f[i]);
            /* Positive at th = 0 (the constant dominates there), crossing later. */
            jc_tl_add_cos(&f[i], 0, 0, test_uniform(&state, 0.5, 2.0));
            for (int k = 1; k <= JC_TRIG_DEGREE; ++k) {
                jc_tl_add_cos(&f[i], 0, k, test_uniform(&state, -0.3, 0.3));
                jc_tl_add_sin(&f[i], 0, k, test_uniform(&state, -0.3, 0.3));
            }
            jc_tl_add_cos(&f[i], 1, 0, -test_uniform(&state, 0.01, 0.3));
            set.f[i] = &f[i];
            set.sign[i] = 1.0;
        }
        jc_ScanHit newton, gsl;
        char err[256] = "";
        int st = jc_scan_first(&set, 0.0, 50.0, 1e-12, &newton, err, sizeof err);
        if (st == JC_OK) st = scan_brent(&set, 0.0, 50.0, 1e-12, brent, &gsl, err, sizeof err);
        if (st != JC_OK) gsl_root_fsolver_free(brent);
        ENSURE_OK(st, err);
        if (!(newton.index == gsl.index && fabs(newton.theta - gsl.theta) <= 2e-12)) gsl_root_fsolver_free(brent);
        ENSURE_MSG(newton.index == gsl.index && fabs(newton.theta - gsl.theta) <= 2e-12,
                   "trial %d: Newton hit %d at %.17g, Brent hit %d at %.17g", trial, newton.index, newton.theta,
                   gsl.index, gsl.theta);
        hits += newton.index >= 0 && !newton.grazing;
    }
    gsl_root_fsolver_free(brent);
    ENSURE_MSG(hits > 1500, "only %d of 2000 trials crossed", hits);
    return 0;
}

int main(void)
{
    RUN_TEST(test_narrow_windows_found);
    RUN_TEST(test_narrow_window_among_others);
    RUN_TEST(test_sign_and_linear_roots);
    RUN_TEST(test_root_at_start);
    RUN_TEST(test_no_root);
    RUN_TEST(test_touching_zero_is_grazing);
    RUN_TEST(test_scan_fns_callback);
    RUN_TEST(test_cubic_root_matches_gsl);
    RUN_TEST(test_newton_polish_matches_brent);
    TEST_MAIN_END();
}
