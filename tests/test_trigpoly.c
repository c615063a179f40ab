/* src/trigpoly.c: f(th) = T0(th) + th T1(th). Products against the product
 * of directly evaluated factors, derivatives against finite differences, and
 * the bounds on f'' and f''' against finite differences of f at many points. */
#include "test.h"

#include "internal.h" /* src/, added by tests/CMakeLists.txt */
#include "trig_direct.h"

#define K_MAX JC_TRIG_DEGREE
#define EPS 2.220446049250313e-16
/* Rounding of trig_direct() below, relative to the sum of |terms| (deriv_bound(p, 0, |th|)):
 * ~20 terms, each with libm's cos/sin error and a product: 16 eps. */
#define EVAL_ROUND (16 * EPS)

/* xorshift64*: a fixed, portable stream of test coefficients. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(double lo, double hi) { return test_uniform(&rng_state, lo, hi); }

static jc_TrigLin random_poly(int deg, int lin)
{
    jc_TrigLin p;
    jc_tl_zero(&p);
    for (int k = 0; k <= deg; ++k) {
        p.c0[k] = uniform(-1, 1);
        if (k > 0) p.s0[k] = uniform(-1, 1);
        if (lin) {
            p.c1[k] = uniform(-1, 1);
            if (k > 0) p.s1[k] = uniform(-1, 1);
        }
    }
    return p;
}


/* sum of k^n |coefficient| over T0, and over T1 */
static double ksum(const double *c, const double *s, int n)
{
    double b = 0;
    for (int k = 0; k <= K_MAX; ++k) b += pow(k, n) * (fabs(c[k]) + fabs(s[k]));
    return b;
}

/* A bound on |f^(n)| for |th| <= T, derived here: d^n (th T1) = th T1^(n) + n T1^(n-1). */
static double deriv_bound(const jc_TrigLin *p, int n, double T)
{
    double b = ksum(p->c0, p->s0, n) + T * ksum(p->c1, p->s1, n);
    if (n > 0) b += n * ksum(p->c1, p->s1, n - 1);
    return b;
}

static int test_mul_matches_product(void)
{
    for (int trial = 0; trial < 300; ++trial) {
        const int dx = (int)uniform(0, K_MAX + 0.999);
        const int dy = (int)uniform(0, K_MAX - dx + 0.999);
        const int which = trial % 3; /* T1 in x, in y, or in neither */
        jc_TrigLin x = random_poly(dx, which == 0), y = random_poly(dy, which == 1), out;
        ENSURE(jc_tl_mul(&out, &x, &y) == JC_OK);
        for (int i = 0; i < 50; ++i) {
            const double th = uniform(-20, 20);
            const double want = trig_direct(&x, th) * trig_direct(&y, th);
            /* Product-to-sum rounds relative to the coefficients, not to the
             * product (which can vanish): 1e-12 of the factors' scales. */
            const double scale = deriv_bound(&x, 0, fabs(th)) * deriv_bound(&y, 0, fabs(th));
            ENSURE_NEAR(jc_tl_value(&out, th), want, 1e-12 * scale);
        }
    }
    return 0;
}

static int test_mul_refuses(void)
{
    jc_TrigLin x = random_poly(1, 1), y = random_poly(1, 1), out;
    ENSURE(jc_tl_mul(&out, &x, &y) == JC_EINVAL); /* th^2 terms do not fit */
    x = random_poly(3, 0);
    y = random_poly(2, 0);
    ENSURE(jc_tl_mul(&out, &x, &y) == JC_EINVAL); /* degree 5 > JC_TRIG_DEGREE */
    x = random_poly(2, 1);
    y = random_poly(2, 0);
    ENSURE(jc_tl_mul(&out, &x, &y) == JC_OK); /* degree 4, one linear factor */
    return 0;
}

static int test_add_and_axpby(void)
{
    jc_TrigLin p;
    jc_tl_zero(&p);
    jc_tl_add_cos(&p, 0, -2, 0.5);   /* cos(-2th) = cos(2th) */
    jc_tl_add_sin(&p, 1, -3, 0.25);  /* th sin(-3th) = -th sin(3th) */
    jc_tl_add_sin(&p, 0, 0, 7.0);    /* sin(0) = 0: nothing */
    jc_tl_add_cos(&p, 1, 0, -0.125); /* -th/8 */
    jc_tl_add_cos(&p, 0, 1, 1.0);
    jc_TrigLin x = random_poly(4, 1), y = random_poly(3, 1), z;
    jc_tl_axpby(&z, 1.5, &x, -0.75, &y);
    for (int i = 0; i < 200; ++i) {
        const double th = uniform(-30, 30);
        const double want = 0.5 * cos(2 * th) - 0.25 * th * sin(3 * th) - th / 8 + cos(th);
        /* a handful of terms of size <= 30: 1e-14 absolute */
        ENSURE_NEAR(jc_tl_value(&p, th), want, 1e-13);
        ENSURE_NEAR(jc_tl_value(&z, th), 1.5 * trig_direct(&x, th) - 0.75 * trig_direct(&y, th),
                    1e-14 * (deriv_bound(&x, 0, 30) + deriv_bound(&y, 0, 30)));
    }
    return 0;
}

/* h, the step of the finite differences the derivatives are checked against. */
static const double FD_H = 1e-3;

/* Calls `check` at 50 random angles in [-20, 20] on each of 100 random
 * polynomials (odd trials with a linear part); the first failure ends it. */
static int for_random_points(int (*check)(const jc_TrigLin *p, double th))
{
    for (int trial = 0; trial < 100; ++trial) {
        jc_TrigLin p = random_poly(K_MAX, trial % 2);
        for (int i = 0; i < 50; ++i)
            if (check(&p, uniform(-20, 20))) return 1;
    }
    return 0;
}

static int check_value_and_derivative(const jc_TrigLin *p, double th)
{
    double f, df;
    jc_tl_eval(p, th, &f, &df);
    /* The angle-addition recurrence vs libm: rounding of ~10 terms. */
    ENSURE_NEAR(f, trig_direct(p, th), 1e-13 * deriv_bound(p, 0, fabs(th)));
    ENSURE(jc_tl_value(p, th) == f);
    /* 5-point central difference: truncation h^4/30 |f^(5)|, rounding
     * (18/12) EVAL_ROUND |f| / h; doubled for the bounds' own looseness. */
    const double fd = (trig_direct(p, th - 2 * FD_H) - 8 * trig_direct(p, th - FD_H) + 8 * trig_direct(p, th + FD_H) -
                       trig_direct(p, th + 2 * FD_H)) / (12 * FD_H);
    const double T = fabs(th) + 2 * FD_H;
    const double tol = 2 * (pow(FD_H, 4) / 30 * deriv_bound(p, 5, T) + 1.5 * EVAL_ROUND * deriv_bound(p, 0, T) / FD_H);
    ENSURE_NEAR(df, fd, tol);
    return 0;
}

static int test_eval_value_and_derivative(void)
{
    return for_random_points(check_value_and_derivative);
}

static int test_curvature_bound_bounds(void)
{
    const double h = 1e-3;
    for (int trial = 0; trial < 200; ++trial) {
        const int deg = 1 + trial % K_MAX;
        jc_TrigLin p = random_poly(deg, trial % 3 != 0);
        const double T = uniform(0.5, 40);
        const double K = jc_tl_curvature_bound(&p, T);
        const double B = jc_tl_magnitude_bound(&p, T);
        for (int i = 0; i < 200; ++i) {
            const double th = uniform(-T + h, T - h);
            /* Second difference: truncation h^2/12 |f''''|, rounding 4 eps |f| / h^2. */
            const double f2 = (trig_direct(&p, th + h) - 2 * trig_direct(&p, th) + trig_direct(&p, th - h)) / (h * h);
            const double slack = h * h / 12 * deriv_bound(&p, 4, T) + 4 * EVAL_ROUND * deriv_bound(&p, 0, T) / (h * h);
            ENSURE_MSG(fabs(f2) <= K + slack, "trial %d th %.17g: |f''| ~ %.17g > bound %.17g (+%.3g)", trial,
                       th, fabs(f2), K, slack);
            ENSURE_MSG(fabs(trig_direct(&p, th)) <= B * (1 + 1e-12), "|f| %.17g > magnitude bound %.17g",
                       fabs(trig_direct(&p, th)), B);
        }
    }
    /* Not vacuous: for a cos(k th) the bound is k^2 |a|, attained at th = 0
     * (1e-12: the bound's own stated allowance for rounding). */
    for (int k = 1; k <= K_MAX; ++k) {
        jc_TrigLin p;
        jc_tl_zero(&p);
        jc_tl_add_cos(&p, 0, k, -0.7);
        ENSURE_REL(jc_tl_curvature_bound(&p, 100.0), k * k * 0.7, 2e-12);
        /* th sin(k th): f'' = 2k cos(k th) - k^2 th sin(k th), at most 2k + T k^2. */
        jc_tl_zero(&p);
        jc_tl_add_sin(&p, 1, k, 1.0);
        ENSURE_REL(jc_tl_curvature_bound(&p, 3.0), 2.0 * k + 3.0 * k * k, 2e-12);
    }
    return 0;
}

static int check_second_derivative(const jc_TrigLin *p, double th)
{
    double d[3], f, df;
    jc_tl_eval3(p, th, d);
    jc_tl_eval(p, th, &f, &df);
    /* The same sums as jc_tl_eval: equal up to a few ulps of the terms. */
    ENSURE_NEAR(d[0], f, 1e-14 * deriv_bound(p, 0, fabs(th)));
    ENSURE_NEAR(d[1], df, 1e-14 * deriv_bound(p, 1, fabs(th)));
    /* 5-point second difference: truncation h^4/90 |f^(6)|, rounding
     * (64/12) EVAL_ROUND |f| / h^2; doubled for the bounds' looseness. */
    const double fd = (-trig_direct(p, th - 2 * FD_H) + 16 * trig_direct(p, th - FD_H) - 30 * trig_direct(p, th) +
                       16 * trig_direct(p, th + FD_H) - trig_direct(p, th + 2 * FD_H)) / (12 * FD_H * FD_H);
    const double T = fabs(th) + 2 * FD_H;
    const double tol = 2 * (pow(FD_H, 4) / 90 * deriv_bound(p, 6, T) +
                            64.0 / 12 * EVAL_ROUND * deriv_bound(p, 0, T) / (FD_H * FD_H));
    ENSURE_NEAR(d[2], fd, tol);
    return 0;
}

static int test_eval3_second_derivative(void)
{
    return for_random_points(check_second_derivative);
}

static int test_third_bound_bounds(void)
{
    const double h = 1e-3;
    for (int trial = 0; trial < 200; ++trial) {
        jc_TrigLin p = random_poly(1 + trial % K_MAX, trial % 3 != 0);
        const double T = uniform(0.5, 40);
        const double K3 = jc_tl_third_bound(&p, T);
        for (int i = 0; i < 200; ++i) {
            const double th = uniform(-T + 2 * h, T - 2 * h);
            /* Central third difference: truncation h^2/4 |f^(5)|, rounding 6 EVAL_ROUND |f| / (2 h^3). */
            const double f3 = (trig_direct(&p, th + 2 * h) - 2 * trig_direct(&p, th + h) + 2 * trig_direct(&p, th - h) -
                               trig_direct(&p, th - 2 * h)) / (2 * h * h * h);
            const double slack = h * h / 4 * deriv_bound(&p, 5, T) + 3 * EVAL_ROUND * deriv_bound(&p, 0, T) / (h * h * h);
            ENSURE_MSG(fabs(f3) <= K3 + slack, "trial %d th %.17g: third derivative ~ %.17g > bound %.17g (+%.3g)",
                       trial, th, fabs(f3), K3, slack);
        }
    }
    /* Not vacuous: a sin(k th) has |f'''| = k^3 |a| at th = 0; th cos(k th) has
     * f''' = -3k^2 cos + k^3 th sin, at most 3k^2 + T k^3 (2e-12: the bound's rounding allowance). */
    for (int k = 1; k <= K_MAX; ++k) {
        jc_TrigLin p;
        jc_tl_zero(&p);
        jc_tl_add_sin(&p, 0, k, 0.3);
        ENSURE_REL(jc_tl_third_bound(&p, 50.0), 0.3 * k * k * k, 2e-12);
        jc_tl_zero(&p);
        jc_tl_add_cos(&p, 1, k, -1.0);
        ENSURE_REL(jc_tl_third_bound(&p, 2.0), 3.0 * k * k + 2.0 * k * k * k, 2e-12);
    }
    return 0;
}

/* The bound split in its constant part and its growth with |th| (the crossing
 * search takes it over each step's window): pointwise at least |f'''|, and
 * the same as jc_tl_third_bound at th_abs_max = T up to its rounding. */
static int test_third_slope_bounds(void)
{
    const double h = 1e-3;
    for (int trial = 0; trial < 200; ++trial) {
        jc_TrigLin p = random_poly(1 + trial % K_MAX, trial % 3 != 0);
        const double T = uniform(0.5, 40);
        const double K0 = jc_tl_third_bound(&p, 0.0), S = jc_tl_third_slope(&p);
        ENSURE_REL(K0 + S * T, jc_tl_third_bound(&p, T), 4e-16 * (1 + T));
        for (int i = 0; i < 200; ++i) {
            const double th = uniform(-T + 2 * h, T - 2 * h);
            const double f3 = (trig_direct(&p, th + 2 * h) - 2 * trig_direct(&p, th + h) + 2 * trig_direct(&p, th - h) -
                               trig_direct(&p, th - 2 * h)) / (2 * h * h * h);
            const double slack = h * h / 4 * deriv_bound(&p, 5, T) + 3 * EVAL_ROUND * deriv_bound(&p, 0, T) / (h * h * h);
            ENSURE_MSG(fabs(f3) <= K0 + S * fabs(th) + slack,
                       "trial %d th %.17g: third derivative ~ %.17g > bound %.17g (+%.3g)", trial, th, fabs(f3),
                       K0 + S * fabs(th), slack);
        }
    }
    /* th cos(k th): f''' = -3k^2 cos + k^3 th sin, slope k^3. */
    for (int k = 1; k <= K_MAX; ++k) {
        jc_TrigLin p;
        jc_tl_zero(&p);
        jc_tl_add_cos(&p, 1, k, -1.0);
        ENSURE_REL(jc_tl_third_slope(&p), (double)k * k * k, 2e-12);
        ENSURE_REL(jc_tl_third_bound(&p, 0.0), 3.0 * k * k, 2e-12);
    }
    return 0;
}

int main(void)
{
    RUN_TEST(test_mul_matches_product);
    RUN_TEST(test_mul_refuses);
    RUN_TEST(test_add_and_axpby);
    RUN_TEST(test_eval_value_and_derivative);
    RUN_TEST(test_curvature_bound_bounds);
    RUN_TEST(test_eval3_second_derivative);
    RUN_TEST(test_third_bound_bounds);
    RUN_TEST(test_third_slope_bounds);
    TEST_MAIN_END();
}
