/*
 * A uniform disc (d = 0, the "disc" preset: r = 10 cm, M = 66.3 g,
 * I_C = M r^2 / 2) on an incline a, derived by hand:
 *
 * Rolling without slip, x = r th: M x'' = M g sin a + F, I_C th'' = -r F, so
 *   x'' = g sin a / (1 + I_C / (M r^2)) = (2/3) g sin a,
 *   F = -(1/3) M g sin a,   N = M g cos a.
 * Rolling needs |F| <= mu N, i.e. mu >= tan(a) / 3.
 *
 * Below that the disc slides from t = 0 (at rest, slip 0, rolling would need
 * more friction than the cone holds); the slip v_s = x' - r w is positive
 * (the centre outruns the rotation), friction is F = -mu N uphill, and
 *   x'' = g (sin a - mu cos a),   th'' = mu N r / I_C = 2 mu g cos a / r,
 *   v_s' = g (sin a - 3 mu cos a) > 0,
 * so it slides all the way down. Either way N = M g cos a > 0 and the
 * centre of mass is the centre: nothing can pull the rim off the incline, so
 * a uniform disc never lifts off.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>

/* The brief's tolerance for x(t) = a t^2 / 2. The rolling phase finds th(t)
 * by inverting a quadrature (relative 1e-13) with a root finder (1e-13 rad),
 * so x is good to ~1e-14 m plus ~1e-13 relative: 1e-9 relative holds with
 * margin once x is above ~1e-5 m. Samples every 10 ms give x >= 3 mm. */
#define X_REL_TOL 1e-9
/* The sliding phase integrates a quadratic polynomial in t with rk8pd: exact
 * up to rounding of ~100 steps, ~1e-14 relative. */
#define SLIDE_REL_TOL 1e-9

static jc_Setup disc_at(double incline_deg, double mu)
{
    jc_Setup s;
    char err[256] = "";
    if (jc_preset_setup("disc", &s, err, sizeof err) != JC_OK) fprintf(stderr, "%s\n", err);
    s.incline_rad = incline_deg * DEG;
    s.mu_static = s.mu_kinetic = mu;
    return s;
}

static int run_disc(const jc_Setup *s, jc_Model *m, jc_Run *run, double sample_dt)
{
    if (sim_model(m, s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = sample_dt;
    if (sim_run(m, &o, run)) return 1;
    if (check_run_invariants(&o, run)) {
        jc_run_free(run);
        return 1;
    }
    return 0;
}

/* No lift-off, every sample in contact with y = r exactly and v_y = 0. */
static int check_stays_on_incline(const jc_Model *m, const jc_Run *run)
{
    ENSURE_MSG(count_events(run, JC_EVENT_LIFTOFF) == 0, "a uniform disc lifted off");
    ENSURE(count_events(run, JC_EVENT_BOUNCE) == 0 && count_events(run, JC_EVENT_TOUCHDOWN) == 0);
    for (int k = 0; k < run->sample_count; ++k) {
        const jc_Sample *p = &run->samples[k];
        ENSURE_MSG(p->mode == JC_MODE_ROLLING || p->mode == JC_MODE_SLIDING, "sample %d in %s", k,
                   jc_mode_name(p->mode));
        ENSURE_MSG(p->state.y_m == m->body.radius_m, "sample %d: y %.17g", k, p->state.y_m);
        ENSURE(p->state.vy_mps == 0.0);
        ENSURE(p->gap_m == 0.0);
        /* N = M g cos a in both modes. */
        ENSURE_REL(p->normal_N, m->body.mass_kg * m->setup.gravity_mps2 * cos(m->setup.incline_rad), 1e-12);
    }
    ENSURE(run->final_mode != JC_MODE_FLIGHT);
    return 0;
}

/* The disc preset's body really is the hand-derived one. */
static int test_body_is_uniform_disc(void)
{
    const jc_Setup s = disc_at(30.0, 0.5);
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    ENSURE(m.body.cm_offset_m == 0.0);
    ENSURE_REL(m.body.inertia_c_kgm2, 0.5 * m.body.mass_kg * m.body.radius_m * m.body.radius_m, 1e-15);
    return 0;
}

/* mu >= tan(a)/3: rolls from start to ramp end, x(t) = (2/3) g sin(a) t^2 / 2. */
static int rolls_checks(const jc_Setup *sp, const jc_Model *mp, const jc_Run *rp, double *worst_rel)
{
    const jc_Setup s = *sp;
    const jc_Model m = *mp;
    const jc_Run run = *rp;
    if (check_stays_on_incline(&m, &run)) return 1;
    const double g = s.gravity_mps2, r = s.body.radius_m;
    const double acc = 2.0 / 3.0 * g * sin(s.incline_rad);
    /* The only event: the ramp's end, at x = L, t = sqrt(2 L / acc). */
    ENSURE_MSG(run.event_count == 1 && run.events[0].kind == JC_EVENT_RAMP_END, "%d events, first %s",
               run.event_count, run.event_count ? jc_event_name(run.events[0].kind) : "-");
    ENSURE(run.termination == JC_END_RAMP_END);
    ENSURE_REL(run.final_state.t_s, sqrt(2.0 * s.ramp_length_m / acc), X_REL_TOL);
    int checked = 0;
    for (int k = 0; k < run.sample_count; ++k) {
        const jc_Sample *p = &run.samples[k];
        const double t = p->state.t_s, x = 0.5 * acc * t * t;
        ENSURE_MSG(p->mode == JC_MODE_ROLLING, "sample %d at %g s is %s", k, t, jc_mode_name(p->mode));
        if (t == 0.0) {
            ENSURE(p->state.x_m == 0.0 && p->state.omega_radps == 0.0);
            continue;
        }
        ENSURE_REL(p->state.x_m, x, X_REL_TOL);
        ENSURE_REL(p->state.theta_rad, x / r, X_REL_TOL);
        ENSURE_REL(p->state.omega_radps, acc * t / r, X_REL_TOL);
        ENSURE_REL(p->state.vx_mps, acc * t, X_REL_TOL);
        ENSURE_NEAR(p->slip_mps, 0.0, 1e-15);
        /* F = -M g sin(a) / 3 (uphill). */
        ENSURE_REL(p->friction_N, -m.body.mass_kg * g * sin(s.incline_rad) / 3.0, 1e-12);
        *worst_rel = fmax(*worst_rel, fabs(p->state.x_m - x) / x);
        checked++;
    }
    ENSURE_MSG(checked >= 20, "only %d samples", checked);
    return 0;
}

/* mu < tan(a)/3: slides from t = 0, x(t) = g (sin a - mu cos a) t^2 / 2,
 * w(t) = 2 mu g cos(a) t / r. */
static int slides_checks(const jc_Setup *sp, const jc_Model *mp, const jc_Run *rp, double *worst_rel)
{
    const jc_Setup s = *sp;
    const jc_Model m = *mp;
    const jc_Run run = *rp;
    const double mu = s.mu_kinetic;
    if (check_stays_on_incline(&m, &run)) return 1;
    const double g = s.gravity_mps2, r = s.body.radius_m, a = s.incline_rad;
    const double acc = g * (sin(a) - mu * cos(a)), wacc = 2.0 * mu * g * cos(a) / r;
    ENSURE_MSG(run.event_count == 2, "%d events", run.event_count);
    const jc_Event *e = &run.events[0];
    ENSURE_MSG(e->kind == JC_EVENT_SLIP && e->state.t_s == 0.0, "first event %s at %g s", jc_event_name(e->kind),
               e->state.t_s);
    ENSURE(e->mode_before == JC_MODE_ROLLING && e->mode_after == JC_MODE_SLIDING);
    ENSURE(run.events[1].kind == JC_EVENT_RAMP_END && run.termination == JC_END_RAMP_END);
    /* The ramp end at x = L: the event is located to 1e-12 s. */
    ENSURE_REL(run.final_state.t_s, sqrt(2.0 * s.ramp_length_m / acc), SLIDE_REL_TOL);
    int checked = 0;
    for (int k = 0; k < run.sample_count; ++k) {
        const jc_Sample *p = &run.samples[k];
        const double t = p->state.t_s;
        if (t == 0.0) continue;
        ENSURE_MSG(p->mode == JC_MODE_SLIDING, "sample %d at %g s is %s", k, t, jc_mode_name(p->mode));
        const double x = 0.5 * acc * t * t;
        ENSURE_REL(p->state.x_m, x, SLIDE_REL_TOL);
        ENSURE_REL(p->state.vx_mps, acc * t, SLIDE_REL_TOL);
        ENSURE_REL(p->state.omega_radps, wacc * t, SLIDE_REL_TOL);
        ENSURE_REL(p->state.theta_rad, 0.5 * wacc * t * t, SLIDE_REL_TOL);
        /* Friction -mu N, uphill; the slip grows as g (sin a - 3 mu cos a) t. */
        ENSURE_REL(p->friction_N, -mu * m.body.mass_kg * g * cos(a), 1e-12);
        ENSURE_REL(p->slip_mps, g * (sin(a) - 3.0 * mu * cos(a)) * t, SLIDE_REL_TOL);
        /* Energy lost to friction: integral of mu N v_s dt = mu N g (sin a - 3 mu cos a) t^2 / 2. */
        ENSURE_REL(p->friction_loss_J,
                   mu * m.body.mass_kg * g * cos(a) * 0.5 * g * (sin(a) - 3.0 * mu * cos(a)) * t * t, 1e-9);
        *worst_rel = fmax(*worst_rel, fabs(p->state.x_m - x) / x);
        checked++;
    }
    ENSURE_MSG(checked >= 20, "only %d samples", checked);
    return 0;
}

typedef int (*disc_checks)(const jc_Setup *s, const jc_Model *m, const jc_Run *run, double *worst_rel);

/* Runs the uniform disc at an incline and friction and applies the checks;
 * what on a failure. */
static int check_disc(double incline_deg, double mu, disc_checks checks, const char *what, double *worst_rel)
{
    const jc_Setup s = disc_at(incline_deg, mu);
    jc_Model m;
    jc_Run run;
    if (run_disc(&s, &m, &run, 0.01)) return 1;
    const int bad = checks(&s, &m, &run, worst_rel);
    if (bad) fprintf(stderr, "  (uniform disc %s at %g deg, mu %g)\n", what, incline_deg, mu);
    jc_run_free(&run);
    return bad;
}

static int check_rolls(double incline_deg, double mu, double *worst_rel)
{
    return check_disc(incline_deg, mu, rolls_checks, "rolling", worst_rel);
}

static int check_slides(double incline_deg, double mu, double *worst_rel)
{
    return check_disc(incline_deg, mu, slides_checks, "sliding", worst_rel);
}

static int test_rolls_when_friction_suffices(void)
{
    const double inclines[] = {10.0, 30.0, 60.0, 80.0};
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double threshold = tan(inclines[i] * DEG) / 3.0;
        /* Well above, and 1% above the threshold (the cone's edge). */
        if (check_rolls(inclines[i], fmax(0.5, 2.0 * threshold), &worst)) return 1;
        if (check_rolls(inclines[i], 1.01 * threshold, &worst)) return 1;
    }
    printf("  rolling: worst |x - a t^2/2| / x = %.2e\n", worst);
    return 0;
}

static int test_slides_when_friction_does_not(void)
{
    const double inclines[] = {10.0, 30.0, 60.0, 80.0};
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double threshold = tan(inclines[i] * DEG) / 3.0;
        /* 1% below the threshold, and a quarter of it. */
        if (check_slides(inclines[i], 0.99 * threshold, &worst)) return 1;
        if (check_slides(inclines[i], 0.25 * threshold, &worst)) return 1;
    }
    /* Frictionless: pure translation, w stays 0. */
    if (check_slides(30.0, 0.0, &worst)) return 1;
    printf("  sliding: worst |x - a t^2/2| / x = %.2e\n", worst);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_body_is_uniform_disc);
    RUN_TEST(test_rolls_when_friction_suffices);
    RUN_TEST(test_slides_when_friction_does_not);
    TEST_MAIN_END();
}
