/*
 * Convergence: the first lift-off (time and position) of the paper's setup
 * as the sliding integrator's tolerances (ode_rtol, ode_atol) and the event
 * location tolerance (event_tol_s) tighten together. The rolling phases are
 * closed forms (independent of these options); the lift-off happens at the
 * end of a sliding phase, so its error is the integrator's and the event
 * locator's. The differences from the tightest run must shrink level by
 * level (down to a floor of rounding), and the default options must agree
 * with the tightest to 1e-9 s and 1e-9 m.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>

#define LEVELS 4
static const double rtols[LEVELS] = {1e-6, 1e-8, 1e-11, 1e-13};
static const double atols[LEVELS] = {1e-8, 1e-10, 1e-13, 1e-15};
static const double etols[LEVELS] = {1e-6, 1e-9, 1e-12, 1e-14};
#define DEFAULT_LEVEL 2

/* Below this the runs agree to rounding of the event search: differences no
 * longer have to shrink. The tightest run's own error is ~1e-13 s. */
#define FLOOR_S 1e-12
#define FLOOR_M 1e-12
/* The brief: the tight and default runs agree to 1e-9 s and 1e-9 m (the
 * default's own tolerances, rtol 1e-11 over a ~1 s motion and 1e-12 s event
 * location, put it near 1e-11). */
#define AGREE_S 1e-9
#define AGREE_M 1e-9

static int first_liftoff_with(double incline_deg, double rtol, double atol, double etol, double *t, double *x)
{
    const jc_Setup s = paper_at(incline_deg, 0.5);
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.ode_rtol = rtol;
    o.ode_atol = atol;
    o.event_tol_s = etol;
    jc_Run run;
    if (sim_run(&m, &o, &run)) return 1;
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    const int ok = sum.first_liftoff >= 0;
    if (ok) {
        *t = run.events[sum.first_liftoff].state.t_s;
        *x = run.events[sum.first_liftoff].state.x_m;
    }
    jc_run_free(&run);
    ENSURE_MSG(ok, "no lift-off at %g deg, rtol %g", incline_deg, rtol);
    return 0;
}

static int first_liftoff(double incline_deg, int level, double *t, double *x)
{
    if (level == DEFAULT_LEVEL) {
        /* The default options are this level. */
        const jc_SimOptions o = jc_default_sim_options();
        ENSURE(o.ode_rtol == rtols[level] && o.ode_atol == atols[level] && o.event_tol_s == etols[level]);
    }
    return first_liftoff_with(incline_deg, rtols[level], atols[level], etols[level], t, x);
}

static int check_convergence(double incline_deg)
{
    double t[LEVELS], x[LEVELS];
    for (int l = 0; l < LEVELS; ++l)
        if (first_liftoff(incline_deg, l, &t[l], &x[l])) return 1;
    const int tight = LEVELS - 1;
    printf("  %g deg: first lift-off t, x by level (rtol):", incline_deg);
    for (int l = 0; l < LEVELS; ++l)
        printf(" [%g] %.13f s %.12f m (dt %.1e, dx %.1e)", rtols[l], t[l], x[l], t[l] - t[tight], x[l] - x[tight]);
    printf("\n");
    for (int l = 1; l < tight; ++l) {
        const double dt_prev = fabs(t[l - 1] - t[tight]), dt = fabs(t[l] - t[tight]);
        const double dx_prev = fabs(x[l - 1] - x[tight]), dx = fabs(x[l] - x[tight]);
        ENSURE_MSG(dt <= fmax(dt_prev, FLOOR_S), "%g deg: time error grew from %.3g s to %.3g s at rtol %g",
                   incline_deg, dt_prev, dt, rtols[l]);
        ENSURE_MSG(dx <= fmax(dx_prev, FLOOR_M), "%g deg: position error grew from %.3g m to %.3g m at rtol %g",
                   incline_deg, dx_prev, dx, rtols[l]);
    }
    /* The loosest level must be visibly off (otherwise the options do not
     * reach the computation and the test above proves nothing). */
    ENSURE_MSG(fabs(t[0] - t[tight]) > 10.0 * FLOOR_S, "%g deg: loose options change nothing", incline_deg);
    ENSURE_NEAR(t[DEFAULT_LEVEL], t[tight], AGREE_S);
    ENSURE_NEAR(x[DEFAULT_LEVEL], x[tight], AGREE_M);
    return 0;
}

/* The integrator alone: the event tolerance held at 1e-14 s, the ODE
 * tolerances tightened from 1e-3 (the loosest allowed) to 1e-13. rk8pd with
 * steps capped at 0.3 rad of rotation is already good to ~1e-12 at rtol
 * 1e-5, so below 1e-11 (s, m) the differences are rounding of the event
 * search and need not shrink further. */
#define INTEGRATOR_FLOOR 1e-11
static int test_integrator_alone(void)
{
    enum { N = 6 };
    const double rt[N] = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13};
    double t[N], x[N];
    for (int l = 0; l < N; ++l)
        if (first_liftoff_with(30.0, rt[l], 1e-2 * rt[l], 1e-14, &t[l], &x[l])) return 1;
    printf("  30 deg, event tol 1e-14 s:");
    for (int l = 0; l < N; ++l) printf(" [rtol %g] dt %.1e dx %.1e", rt[l], t[l] - t[N - 1], x[l] - x[N - 1]);
    printf("\n");
    for (int l = 1; l < N - 1; ++l) {
        ENSURE_MSG(fabs(t[l] - t[N - 1]) <= fmax(fabs(t[l - 1] - t[N - 1]), INTEGRATOR_FLOOR),
                   "time error grew at rtol %g", rt[l]);
        ENSURE_MSG(fabs(x[l] - x[N - 1]) <= fmax(fabs(x[l - 1] - x[N - 1]), INTEGRATOR_FLOOR),
                   "position error grew at rtol %g", rt[l]);
    }
    ENSURE_NEAR(t[N - 2], t[N - 1], AGREE_S);
    ENSURE_NEAR(x[N - 2], x[N - 1], AGREE_M);
    return 0;
}

static int test_paper_30(void) { return check_convergence(30.0); }
static int test_paper_15(void) { return check_convergence(15.0); }
static int test_paper_45(void) { return check_convergence(45.0); }

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_paper_30);
    RUN_TEST(test_paper_15);
    RUN_TEST(test_paper_45);
    RUN_TEST(test_integrator_alone);
    TEST_MAIN_END();
}
