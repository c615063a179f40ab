/*
 * Fixed-time samples of the closed-form rolling phase against an independent
 * computation: the rolling equation of motion (physics.md §2)
 *   I_P(th) th'' = M g ((r + d cos th) sin a + d sin th cos a) + M r d sin th th'^2,
 * integrated here with GSL's rk8pd (eps 1e-14) from each rolling sample to the
 * next (no event between them), through turning points. The simulator finds
 * a sample's angle by walking the quadrature t(th) = int dth / w(th) from
 * sample to sample (rolling_phase.c); this checks that every such sample is
 * the state on the path at its time: |dth| <= th_tol = TH_TOL + TH_REL |th|,
 * |dw| <= W_TOL sqrt(g / r) + |th''| th_tol / |w| (what th_tol allows near a
 * turning point) and x = x_prev + r dth. Pairs with a turning
 * point between them are not compared: a turning angle is located to 1e-12
 * rad, which puts its time off by up to sqrt(2e-12 / |th''|) (measured: 3e-9
 * s), before and after this change alike; the samples after it are checked
 * against each other.
 *
 * Setups: the hoop preset (60 s of rocking, sampled every 10 ms), the
 * paper's cylinder at 15, 30, 45 deg (1 ms), and RUNS random bodies without
 * air or rolling resistance (their rolling is an ODE phase), random sample
 * spacing 0.2..20 ms. JC_TEST_SEED sets the seed; it is printed on a failure.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#define RUNS 300
#define TH_TOL 1e-10   /* rad (seed 5, run 21: 3.6e-11 before and after the change alike) */
#define TH_REL 1e-12
#define W_TOL 1e-9     /* times sqrt(g / r), rad/s */
/* An event against the ODE from the last rolling sample before it: 1e-12
 * rad + 1e-13 |th|, plus what the event's own time allows, |w| times
 * EVENT_T_REL of its time (the quadrature over the whole swing is asked for
 * 1e-13 of its result; seed 20261125 found 5.1e-12 rad at 13.8 rad/s and
 * 2.2 s). Sample times chained from sample to sample everywhere, turning
 * points included, drifted by up to 2e-8 of the swing's time; chained down
 * to 1e-3 of the energy scale (rolling_phase.c's JC_WALK_P_FLOOR), seed 4
 * failed here by 1.14e-11 rad against 1.07e-11. */
#define EVENT_TH_TOL 1e-12
#define EVENT_TH_REL 1e-13
#define EVENT_T_REL 2e-13

static uint64_t rng_state, seed_used;

static double uniform(double lo, double hi) { return test_uniform(&rng_state, lo, hi); }

static int rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const jc_Model *m = params;
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m, g = m->setup.gravity_mps2;
    const double a = m->setup.incline_rad, s = sin(y[0]), c = cos(y[0]);
    const double ip = m->body.inertia_c_kgm2 + M * r * r + 2.0 * M * r * d * c;
    dydt[0] = y[1];
    dydt[1] = (M * g * ((r + d * c) * sin(a) + d * s * cos(a)) + M * r * d * s * y[1] * y[1]) / ip;
    return GSL_SUCCESS;
}

typedef struct {
    int checked, turns, events;
    double worst_th, worst_w, worst_event; /* relative to their tolerances */
} stats;

/* Every rolling sample that follows a rolling sample with no event between
 * them, against the equation of motion integrated from the earlier one. */
static int check_run(const jc_Model *m, const jc_Run *run, const char *what, stats *st)
{
    const double r = m->body.radius_m, wscale = sqrt(m->setup.gravity_mps2 / r);
    gsl_odeiv2_system sys = {rhs, NULL, 2, (void *)m};
    gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-14, 1e-14);
    ENSURE(drv);
    int ev = 0, bad = 0;
    for (int i = 1; i < run->sample_count && !bad; ++i) {
        const jc_Sample *a = &run->samples[i - 1], *b = &run->samples[i];
        const double t0 = a->state.t_s, t1 = b->state.t_s;
        while (ev < run->event_count && run->events[ev].state.t_s <= t0) ev++;
        if (a->mode != JC_MODE_ROLLING || b->mode != JC_MODE_ROLLING || !(t1 > t0)) continue;
        if (ev < run->event_count && run->events[ev].state.t_s <= t1) continue; /* an event between them */
        if (!(a->state.omega_radps * b->state.omega_radps > 0.0)) {
            /* A turning point between them: its time is off by up to
             * sqrt(2 tol / |a|) for a turning angle located to tol = 1e-12
             * rad (the old and the new sampling alike), which is not what is
             * checked here. */
            st->turns++;
            continue;
        }
        double y[2] = {a->state.theta_rad, a->state.omega_radps}, t = t0;
        gsl_odeiv2_driver_reset(drv);
        gsl_odeiv2_driver_reset_hstart(drv, fmin(1e-4, t1 - t0));
        const int s = gsl_odeiv2_driver_apply(drv, &t, t1, y);
        if (s != GSL_SUCCESS) {
            fprintf(stderr, "%s: rk8pd failed (%d) from %.17g s\n", what, s, t0);
            bad = 1;
            break;
        }
        const double dth = fabs(b->state.theta_rad - y[0]), dw = fabs(b->state.omega_radps - y[1]);
        /* On the path w is a function of th, w dw = a dth: near a turning
         * point an angle within its tolerance moves w by a th_tol / |w|. */
        double dydt[2];
        rhs(t1, y, dydt, (void *)m);
        const double th_tol = TH_TOL + TH_REL * fabs(y[0]);
        const double w_tol = W_TOL * wscale + fabs(dydt[1]) * th_tol / fmax(fabs(y[1]), 1e-300);
        const double dx = fabs(b->state.x_m - a->state.x_m - r * (b->state.theta_rad - a->state.theta_rad));
        st->worst_th = fmax(st->worst_th, dth / th_tol);
        st->worst_w = fmax(st->worst_w, dw / w_tol);
        st->checked++;
        if (dth > th_tol || dw > w_tol || dx > 1e-12 * fmax(1.0, fabs(b->state.x_m))) {
            fprintf(stderr,
                    "%s (seed %llu): sample at %.17g s (after %.17g s): th %.17g, ODE %.17g (|d| %.3g > %.3g?); "
                    "w %.17g, ODE %.17g (|d| %.3g > %.3g?); x off by %.3g m\n",
                    what, (unsigned long long)seed_used, t1, t0, b->state.theta_rad, y[0], dth, th_tol,
                    b->state.omega_radps, y[1], dw, w_tol, dx);
            bad = 1;
        }
    }
    /* The last rolling sample before each event, against the event: sample
     * times come from short quadratures chained from sample to sample where
     * the path is smooth, event times from the quadrature over the whole
     * swing; a drift between the two would show here and nowhere above. */
    int i = 0;
    for (int k = 0; k < run->event_count && !bad; ++k) {
        const jc_State *e = &run->events[k].state;
        while (i + 1 < run->sample_count && run->samples[i + 1].state.t_s < e->t_s) i++;
        const jc_Sample *a = &run->samples[i];
        if (a->mode != JC_MODE_ROLLING || !(a->state.t_s < e->t_s) || (k > 0 && run->events[k - 1].state.t_s > a->state.t_s))
            continue;
        if (!(a->state.omega_radps * e->omega_radps > 0.0)) continue; /* a turning point between: see above */
        double y[2] = {a->state.theta_rad, a->state.omega_radps}, t = a->state.t_s;
        gsl_odeiv2_driver_reset(drv);
        gsl_odeiv2_driver_reset_hstart(drv, fmin(1e-4, e->t_s - t));
        if (gsl_odeiv2_driver_apply(drv, &t, e->t_s, y) != GSL_SUCCESS) continue;
        const double th_tol = EVENT_TH_TOL + EVENT_TH_REL * fabs(y[0]) + fabs(e->omega_radps) * EVENT_T_REL * e->t_s;
        const double dth = fabs(e->theta_rad - y[0]);
        st->worst_event = fmax(st->worst_event, dth / th_tol);
        st->events++;
        if (dth > th_tol) {
            fprintf(stderr, "%s (seed %llu): event %d (%s, w %.6g rad/s, sample w %.6g) at %.17g s, th %.17g; from the sample at %.17g s the ODE gives "
                    "%.17g (|d| %.3g > %.3g)\n", what, (unsigned long long)seed_used, k, jc_event_name(run->events[k].kind), e->omega_radps, a->state.omega_radps, e->t_s, e->theta_rad,
                    a->state.t_s, y[0], dth, th_tol);
            bad = 1;
        }
    }
    gsl_odeiv2_driver_free(drv);
    return bad;
}

static int run_and_check(const jc_Setup *s, double dt, double t_max, const char *what, stats *st)
{
    jc_Model m;
    if (sim_model(&m, s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = dt;
    o.t_max_s = t_max;
    o.max_samples = 1000000;
    jc_Run run;
    if (sim_run(&m, &o, &run)) return 1;
    const int bad = check_run(&m, &run, what, st);
    jc_run_free(&run);
    return bad;
}

static int test_presets(void)
{
    stats st = {0};
    jc_Setup s;
    char err[256];
    ENSURE_OK(jc_preset_setup("hoop", &s, err, sizeof err), err);
    ENSURE(run_and_check(&s, 0.01, 60.0, "hoop", &st) == 0);
    const int hoop = st.checked;
    ENSURE_MSG(hoop > 3000, "only %d hoop samples checked", hoop);
    const double inclines[3] = {15, 30, 45};
    for (int i = 0; i < 3; ++i) {
        char what[32];
        snprintf(what, sizeof what, "paper %g deg", inclines[i]);
        s = paper_at(inclines[i], 0.5);
        ENSURE(run_and_check(&s, 1e-3, 60.0, what, &st) == 0);
    }
    ENSURE_MSG(st.checked - hoop > 500, "only %d paper samples checked", st.checked - hoop);
    printf("  presets: %d rolling samples (hoop %d; %d after a turning point not compared), worst |dth| %.2g and "
           "|dw| %.2g of their tolerances; %d events after a rolling sample, worst |dth| %.2g of it\n", st.checked,
           hoop, st.turns, st.worst_th, st.worst_w, st.events, st.worst_event);
    return 0;
}

static jc_Setup random_setup(void)
{
    jc_Setup s = jc_paper_setup();
    const double r = uniform(0.02, 0.3);
    s.body = (jc_BodyDef){0};
    s.body.radius_m = r;
    s.body.part_count = 2;
    const double heavy = exp(uniform(log(0.01), log(20.0)));
    switch ((int)uniform(0.0, 3.0)) {
    case 0:
        s.body.parts[0] = (jc_Part){JC_PART_DISC, 1.0, 0.0, 0.0, r};
        s.body.parts[1] = (jc_Part){JC_PART_ROD, heavy, uniform(0.0, 0.9 * r), uniform(0, 2 * PI), 0.05 * r};
        break;
    case 1:
        s.body.parts[0] = (jc_Part){JC_PART_HOOP, 1.0, 0.0, 0.0, r};
        s.body.parts[1] = (jc_Part){JC_PART_POINT, heavy, uniform(0.0, r), uniform(0, 2 * PI), 0.0};
        break;
    default:
        s.body.parts[0] = (jc_Part){JC_PART_HOOP, 0.1, 0.0, 0.0, r};
        s.body.parts[1] = (jc_Part){JC_PART_POINT, 1.0, r, 0.0, 0.0};
        break;
    }
    s.incline_rad = uniform(0.0, 1.0) < 0.3 ? 0.0 : uniform(0.0, 40.0) * DEG;
    s.mu_static = uniform(0.2, 2.0);
    s.mu_kinetic = uniform(0.0, s.mu_static);
    s.restitution = uniform(0.0, 1.0);
    s.theta0_rad = uniform(-PI, PI);
    s.omega0_radps = uniform(0.0, 1.0) < 0.2 ? 0.0 : uniform(-3.0, 15.0);
    s.ramp_length_m = uniform(0.3, 3.0);
    s.paper_cm_offset_m = 0.0;
    return s;
}

static int test_random(void)
{
    stats st = {0};
    for (int i = 0; i < RUNS; ++i) {
        const jc_Setup s = random_setup();
        const double dt = exp(uniform(log(2e-4), log(2e-2)));
        char what[64];
        snprintf(what, sizeof what, "random run %d (dt %.3g s)", i, dt);
        ENSURE_MSG(run_and_check(&s, dt, 5.0, what, &st) == 0, "%s, seed %llu", what, (unsigned long long)seed_used);
    }
    ENSURE_MSG(st.checked > 10000, "only %d samples checked", st.checked);
    printf("  %d random setups (seed %llu): %d rolling samples (%d after a turning point not compared), worst "
           "|dth| %.2g and |dw| %.2g of their tolerances; %d events after a rolling sample, worst |dth| %.2g of it\n",
           RUNS, (unsigned long long)seed_used, st.checked, st.turns, st.worst_th, st.worst_w, st.events,
           st.worst_event);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    seed_used = sim_seed(20261125ull, &rng_state);
    RUN_TEST(test_presets);
    RUN_TEST(test_random);
    TEST_MAIN_END();
}
