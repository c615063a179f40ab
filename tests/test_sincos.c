/* src/sincos.h: jc_sincos against libm's sin and cos, over the angles the
 * simulator meets (|th| up to 1e4 rad and beyond), near the multiples of
 * pi/2 where the reduction cancels, and at the edges (0, -0, huge, NaN). */
#include "test.h"

#include "sincos.h" /* src/, added by tests/CMakeLists.txt */

#include <float.h>

/* xorshift64*: a fixed, portable stream of angles. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(double lo, double hi) { return test_uniform(&rng_state, lo, hi); }

/* |a - ref| in units in the last place of ref. */
static double ulps(double a, double ref)
{
    const double u = fabs(nextafter(ref, INFINITY) - ref);
    return fabs(a - ref) / (u > 0.0 ? u : DBL_TRUE_MIN);
}

/* Measured: at most 2 ulp of the result and half an ulp of 1 (0.5 eps) from libm. */
static int close_to_libm(double x)
{
    double s, c;
    jc_sincos(x, &s, &c);
    const double rs = sin(x), rc = cos(x);
    ENSURE_MSG(ulps(s, rs) <= 2.0 && ulps(c, rc) <= 2.0, "x %.17g: sin %.17g vs %.17g, cos %.17g vs %.17g", x, s,
               rs, c, rc);
    ENSURE_MSG(fabs(s - rs) <= 0.75 * DBL_EPSILON && fabs(c - rc) <= 0.75 * DBL_EPSILON, "x %.17g", x);
    return 0;
}

static int test_random_angles(void)
{
    const double ranges[4] = {1.0, 10.0, 1e4, 9.99e5};
    for (int i = 0; i < 4000000; ++i) {
        const double r = ranges[i % 4];
        if (close_to_libm(uniform(-r, r))) return 1;
    }
    return 0;
}

static int test_near_quarter_turns(void)
{
    /* The doubles nearest k pi/2 and a few ulps around them: sin or cos is
     * ~1e-16 |x| there, all of it from the reduction. */
    for (int i = 0; i < 200000; ++i) {
        const double k = floor(uniform(-6e5, 6e5));
        double x = k * 1.57079632679489661923;
        for (int j = 0; j < 3; ++j) x = nextafter(x, (i & 1) ? INFINITY : -INFINITY);
        if (close_to_libm(x) || close_to_libm(k * 1.57079632679489661923)) return 1;
    }
    return 0;
}

static int test_edges(void)
{
    double s, c;
    jc_sincos(0.0, &s, &c);
    ENSURE(s == 0.0 && c == 1.0);
    jc_sincos(-0.0, &s, &c);
    ENSURE(s == 0.0 && c == 1.0); /* the sign of -0 is not kept (nothing here needs it) */
    jc_sincos(1e-300, &s, &c);
    ENSURE(s == 1e-300 && c == 1.0);
    /* Beyond the reduction's range: libm's. */
    const double big[3] = {1e6, -3.5e9, 1e300};
    for (int i = 0; i < 3; ++i) {
        jc_sincos(big[i], &s, &c);
        ENSURE(s == sin(big[i]) && c == cos(big[i]));
    }
    jc_sincos(NAN, &s, &c);
    ENSURE(isnan(s) && isnan(c));
    jc_sincos(INFINITY, &s, &c);
    ENSURE(isnan(s) && isnan(c));
    return 0;
}

int main(void)
{
    RUN_TEST(test_random_angles);
    RUN_TEST(test_near_quarter_turns);
    RUN_TEST(test_edges);
    TEST_MAIN_END();
}
