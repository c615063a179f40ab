/*
 * src/dop853.c, the integrator of the phases without a closed form:
 * - its order (8) and its continuous extension's (7) on y'' = -y, against
 *   the exact solution;
 * - against GSL's rk8pd (the integrator it replaced) on 1,000 random
 *   sliding phases: the sliding equations of motion (docs/physics.md §3,
 *   forces from jc_sliding_accel) integrated by both over the same time, at
 *   tolerances 1e-12, must agree to 1e-9 of the state's scale.
 * The seed is printed on a failure; JC_TEST_SEED=N reruns one.
 */
#include "sim_common.h"

#include "../../src/internal.h"
#include "../../src/dop853_kernel.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

static int oscillator(double t, const double y[], double f[], void *ctx)
{
    (void)t;
    (void)ctx;
    f[0] = y[1];
    f[1] = -y[0];
    return 0;
}

/* A stepper at the start of y'' = -y from (1, 0): y = (cos t, -sin t). */
static void oscillator_start(jc_Dop853 *d)
{
    jc_dop853_init(d, 2, 2, 1e-10, 1e-10);
    const double y0[2] = {1.0, 0.0};
    jc_dop853_start(d, oscillator, NULL, 0.0, y0);
}

/* |error| at t = 1 after n fixed steps. */
static double fixed_step_error(int n)
{
    jc_Dop853 d;
    oscillator_start(&d);
    for (int i = 0; i < n; ++i) {
        if (jc_dop853_step(&d, oscillator, NULL, 1.0 / n) != 0) return NAN;
        jc_dop853_advance(&d);
    }
    return hypot(d.y0[0] - cos(1.0), d.y0[1] + sin(1.0));
}

/* The largest error of the continuous extension inside one step of size h. */
static double dense_error(double h)
{
    jc_Dop853 d;
    oscillator_start(&d);
    if (jc_dop853_step(&d, oscillator, NULL, h) != 0 || jc_dop853_dense(&d, oscillator, NULL) != 0) return NAN;
    double worst = 0.0;
    for (int k = 1; k < 8; ++k) {
        double y[2];
        const double tau = h * k / 8.0;
        jc_dop853_eval(&d, tau, y);
        worst = fmax(worst, hypot(y[0] - cos(tau), y[1] + sin(tau)));
    }
    return worst;
}

/* Errors at step h and h/2 whose ratio is about 2^8, and the smaller one
 * already small. */
static int check_order(const char *what, double e_h, double e_half, double ratio_lo, double ratio_hi)
{
    printf("  %s: error %.3g (h), %.3g (h/2), ratio %.1f\n", what, e_h, e_half, e_h / e_half);
    ENSURE_MSG(e_h / e_half > ratio_lo && e_h / e_half < ratio_hi, "%s: error ratio %.1f, 2^8 = 256 wanted", what,
               e_h / e_half);
    ENSURE(e_half < 1e-9);
    return 0;
}

/* Global error ~ h^8: halving h divides it by 256 (outside rounding). */
static int test_order_eight(void)
{
    return check_order("fixed steps on y'' = -y, t = 1 (4 and 8 steps)", fixed_step_error(4), fixed_step_error(8),
                       180.0, 360.0);
}

/* The continuous extension's local error ~ h^8 (order 7). */
static int test_continuous_extension_order_seven(void)
{
    return check_order("continuous extension inside one step (h 0.8)", dense_error(0.8), dense_error(0.4), 150.0,
                       400.0);
}

/* ---- sliding phases: DOP853 against GSL's rk8pd ---- */

typedef struct {
    const jc_Model *m;
    int dir;
} slide;

/* x, th, vx, w: the sliding equations (no air), sine and cosine taken here. */
static int slide_rhs(double t, const double y[], double f[], void *ctx)
{
    (void)t;
    const slide *c = ctx;
    jc_SlidingForces sf;
    jc_sliding_accel(c->m, sin(y[1]), cos(y[1]), y[3], c->dir, NULL, &sf);
    f[0] = y[2];
    f[1] = y[3];
    f[2] = sf.x_acc;
    f[3] = sf.theta_acc;
    return 0;
}

/* The same equations one place further on, after a carried component
 * (y[0], held at its start value): a range that starts past 0, as rolling's. */
static int slide_rhs_shifted(double t, const double y[], double f[], void *ctx)
{
    f[0] = 0.0;
    return slide_rhs(t, y + 1, f + 1, ctx);
}

JC_DOP853_TRY_INSTANCE(slide_try, slide_rhs, 0, 4)
JC_DOP853_TRY_INSTANCE(slide_try_shifted, slide_rhs_shifted, 1, 4)

/* Adaptive DOP853 from y to time T (no events), by jc_dop853_try or by an
 * instance of it (try_step; first: where the 4 integrated components start). */
static int dop_to_with(slide *c, jc_DopTry try_step, int first, double y[4], double T, long *steps)
{
    jc_Dop853 d;
    jc_dop853_init_range(&d, first, 4, first + 4, 1e-12, 1e-14);
    double y_full[5] = {42.0};
    for (int i = 0; i < 4; ++i) y_full[first + i] = y[i];
    jc_dop853_start(&d, first ? slide_rhs_shifted : slide_rhs, c, 0.0, y_full);
    double h = 1e-4;
    *steps = 0;
    while (d.t0 < T && *steps < 1000000) {
        const int last = d.t0 + h >= T;
        if (last) h = T - d.t0;
        double h_next;
        const double e = try_step ? try_step(&d, c, h, &h_next) : jc_dop853_try(&d, slide_rhs, c, h, &h_next);
        ++*steps;
        if (e <= 1.0) {
            jc_dop853_advance(&d);
            if (last) d.t0 = T;
        }
        h = h_next;
    }
    for (int i = 0; i < 4; ++i) y[i] = d.y0[first + i];
    if (first && d.y0[0] != 42.0) return 1; /* the carried component moved */
    return d.t0 >= T ? 0 : 1;
}

static int dop_to(slide *c, double y[4], double T, long *steps) { return dop_to_with(c, NULL, 0, y, T, steps); }

static int test_sliding_phases_match_gsl_rk8pd(void)
{
    uint64_t rng;
    const uint64_t seed = sim_seed(853, &rng);
    double worst = 0.0;
    long dop_steps = 0, phases = 0;
    for (int i = 0; i < 1000; ++i) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = test_uniform(&rng, 0.0, 60.0) * DEG;
        s.mu_static = test_uniform(&rng, 0.05, 1.0);
        s.mu_kinetic = s.mu_static * test_uniform(&rng, 0.3, 1.0);
        s.body.parts[1].offset_m = test_uniform(&rng, 0.0, 0.09);
        jc_Model m;
        char err[256];
        ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
        const double r = m.body.radius_m;
        double y[4] = {0.0, test_uniform(&rng, -PI, PI), test_uniform(&rng, -3.0, 3.0), test_uniform(&rng, -30.0, 30.0)};
        const double slip = y[2] - r * y[3];
        slide c = {&m, slip > 0.0 ? 1 : -1};
        jc_SlidingForces f0;
        jc_sliding_accel(&m, sin(y[1]), cos(y[1]), y[3], c.dir, NULL, &f0);
        /* A sliding phase needs a consistent contact force: D well above 0. */
        if (!(f0.denominator > 0.2)) continue;
        const double T = 0.05;
        double y_gsl[4] = {y[0], y[1], y[2], y[3]};
        long steps;
        ENSURE_MSG(dop_to(&c, y, T, &steps) == 0, "seed %llu case %d: DOP853 did not reach T",
                   (unsigned long long)seed, i);
        gsl_odeiv2_system sys = {slide_rhs, NULL, 4, &c};
        gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-4, 1e-14, 1e-12);
        ENSURE(drv != NULL);
        double t = 0.0;
        const int st = gsl_odeiv2_driver_apply(drv, &t, T, y_gsl);
        gsl_odeiv2_driver_free(drv);
        ENSURE_MSG(st == GSL_SUCCESS, "seed %llu case %d: rk8pd failed", (unsigned long long)seed, i);
        const double scale[4] = {1.0, 1.0, 1.0, 10.0}; /* m, rad, m/s, rad/s */
        for (int k = 0; k < 4; ++k) {
            const double diff = fabs(y[k] - y_gsl[k]) / fmax(scale[k], fabs(y_gsl[k]));
            worst = fmax(worst, diff);
            ENSURE_MSG(diff < 1e-9, "seed %llu case %d component %d: DOP853 %.15g, rk8pd %.15g",
                       (unsigned long long)seed, i, k, y[k], y_gsl[k]);
        }
        dop_steps += steps;
        phases++;
    }
    printf("  %ld sliding phases of 0.05 s: largest difference from rk8pd %.2g of scale, %.1f DOP853 steps each\n",
           phases, worst, (double)dop_steps / (double)phases);
    ENSURE(phases >= 500);
    return 0;
}

/* The phases step with instances of jc_dop853_try whose right-hand side is
 * inlined (JC_DOP853_TRY_INSTANCE): the same operations in the same order
 * as the generic stepper, so the same steps and the same numbers to the
 * last bit, on ranges from 0 and from past it. */
static int test_inlined_instances_match_generic_stepper(void)
{
    uint64_t rng;
    const uint64_t seed = sim_seed(8530, &rng);
    int compared = 0;
    for (int i = 0; i < 200; ++i) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = test_uniform(&rng, 0.0, 60.0) * DEG;
        s.body.parts[1].offset_m = test_uniform(&rng, 0.0, 0.09);
        jc_Model m;
        char err[256];
        ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
        const double y0[4] = {0.0, test_uniform(&rng, -PI, PI), test_uniform(&rng, -3.0, 3.0),
                              test_uniform(&rng, -30.0, 30.0)};
        slide c = {&m, y0[2] - m.body.radius_m * y0[3] > 0.0 ? 1 : -1};
        jc_SlidingForces f0;
        jc_sliding_accel(&m, sin(y0[1]), cos(y0[1]), y0[3], c.dir, NULL, &f0);
        if (!(f0.denominator > 0.2)) continue;
        double y_gen[4], y_inst[4], y_shift[4];
        long n_gen, n_inst, n_shift;
        memcpy(y_gen, y0, sizeof y_gen);
        memcpy(y_inst, y0, sizeof y_inst);
        memcpy(y_shift, y0, sizeof y_shift);
        ENSURE(dop_to(&c, y_gen, 0.05, &n_gen) == 0);
        ENSURE(dop_to_with(&c, slide_try, 0, y_inst, 0.05, &n_inst) == 0);
        ENSURE_MSG(dop_to_with(&c, slide_try_shifted, 1, y_shift, 0.05, &n_shift) == 0,
                   "seed %llu case %d: the shifted range failed or moved its carried component",
                   (unsigned long long)seed, i);
        ENSURE_MSG(n_inst == n_gen && n_shift == n_gen, "seed %llu case %d: %ld, %ld and %ld steps",
                   (unsigned long long)seed, i, n_gen, n_inst, n_shift);
        for (int k = 0; k < 4; ++k)
            ENSURE_MSG(y_inst[k] == y_gen[k] && y_shift[k] == y_gen[k],
                       "seed %llu case %d component %d: generic %.17g, instance %.17g, shifted %.17g",
                       (unsigned long long)seed, i, k, y_gen[k], y_inst[k], y_shift[k]);
        compared++;
    }
    ENSURE(compared >= 100);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_order_eight);
    RUN_TEST(test_continuous_extension_order_seven);
    RUN_TEST(test_sliding_phases_match_gsl_rk8pd);
    RUN_TEST(test_inlined_instances_match_generic_stepper);
    TEST_MAIN_END();
}
