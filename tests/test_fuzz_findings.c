/* What fuzzing found in the library, as plain regression tests on the public
 * API (the inputs themselves are replayed from fuzz/corpus/simulate/regress-*
 * by the fuzz_replay_simulate test; see fuzz/README.md, "Findings"). */
#include "test.h"

#include <gsl/gsl_errno.h>
#include <jumpcyl/jumpcyl.h>

#define DEG (3.14159265358979323846 / 180.0)

static int simulate(const jc_Setup *s, jc_Run *run, int *status, char *err, size_t err_len)
{
    static jc_Model m; /* large: off the stack */
    ENSURE_OK(jc_model_init(&m, s, err, err_len), err);
    const jc_SimOptions o = jc_default_sim_options();
    *status = jc_simulate(&m, &o, run, err, err_len);
    return 0;
}

/* The numbers of a setup fuzzing found, on the paper's body; the rest as
 * the paper's. */
typedef struct {
    double incline_deg, gravity, mu, restitution, theta0, omega0, ramp, length, air_density, drag, spin_drag;
} finding;

static jc_Setup finding_setup(const finding *f)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = f->incline_deg * DEG;
    s.gravity_mps2 = f->gravity;
    s.mu_static = s.mu_kinetic = f->mu;
    s.restitution = f->restitution;
    s.theta0_rad = f->theta0;
    s.omega0_radps = f->omega0;
    s.ramp_length_m = f->ramp;
    s.length_m = f->length;
    s.air_density_kgpm3 = f->air_density;
    s.drag_coefficient = f->drag;
    s.spin_drag_Nms2 = f->spin_drag;
    return s;
}

/* A 1.8e308 kg part overflowed the rolling model to NaN, and a product of
 * trigonometric polynomials then wrote past a stack array; subnormal masses
 * and gravity made NaN states. Now they are out of range, with the range in
 * the message. */
static int test_extreme_magnitudes_are_rejected(void)
{
    jc_Setup s = jc_paper_setup();
    s.body.parts[0].mass_kg = 1.7976931348623157e308;
    char err[256] = "";
    jc_Model m;
    ENSURE(jc_model_init(&m, &s, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "mass 1.79769e+308 kg is out of range (allowed: [0, 1e+06] kg)"), "%s", err);
    s = jc_paper_setup();
    s.body.radius_m = 2e3;
    ENSURE(jc_setup_validate(&s, err, sizeof err) == JC_EINVAL && strstr(err, "(allowed: [1e-06, 1000] m)"));
    /* A subnormal total mass made an impact's impulse NaN. */
    s = jc_paper_setup();
    s.body.part_count = 1;
    s.body.parts[0] = (jc_Part){JC_PART_ROD, 5.2e-312, 0.05, 0.0, 0.01};
    ENSURE(jc_setup_validate(&s, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "total mass 5.2e-312 kg is out of range (allowed: at least 1e-09 kg)"), "%s", err);
    /* A subnormal gravity made a flight's time -inf and its state NaN. */
    s = jc_paper_setup();
    s.gravity_mps2 = 2.27e-322;
    ENSURE(jc_setup_validate(&s, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "(allowed: [1e-06, 1000] m/s2)"), "%s", err);
    return 0;
}

/* Spin drag on a millimetre rod: stiff. A stage of the integrator
 * overflowed, GSL accepted the NaN step and the run "ended" at its time
 * limit with NaN energies. Now the step is retried shorter: the run
 * reaches the ramp's end with a balanced energy account. */
static int test_stiff_spin_drag_stays_finite(void)
{
    const finding f = {73.77, 81.98, 1.64, 0.82, 4.4745, 31.96, 16.39, 0.2459, 1.639, 1.639, 8.196e-5};
    jc_Setup s = finding_setup(&f);
    s.body.radius_m = 1e-3;
    s.body.part_count = 1;
    s.body.parts[0] = (jc_Part){JC_PART_ROD, 0.2, 0.5e-3, 0.0, 0.1e-3};
    s.paper_cm_offset_m = 0.0;
    jc_Run run;
    int st;
    char err[256] = "";
    if (simulate(&s, &run, &st, err, sizeof err)) return 1;
    const jc_EnergyReport e = run.energy;
    const jc_Termination end = run.termination;
    const double x = run.final_state.x_m;
    jc_run_free(&run);
    ENSURE_OK(st, err);
    ENSURE_MSG(end == JC_END_RAMP_END, "ended: %s", jc_termination_name(end));
    ENSURE(isfinite(x) && isfinite(e.kinetic_J) && isfinite(e.air_loss_J));
    ENSURE_MSG(fabs(e.balance_error_J) <= 1e-9 * (e.kinetic_J + fabs(e.potential_J)), "balance %g J", e.balance_error_J);
    return 0;
}

/* A lift-off at the start, with air: the flight starts at vy = 0, where its
 * apex event is 0, and event location returned that root at the start again
 * and again: 10^5 "apexes" at t = 0, then step_limit. Now the flight goes
 * on (a 0.1 ms hop) and the run reaches the ramp's end. */
static int test_air_flight_from_rest_advances(void)
{
    /* Found with mu_s 0.000122 < mu_k 0.00388, now refused (docs/physics.md
     * §4); the same lift-off with both at the kinetic value. */
    const finding f = {45.0, 61.76, 0.00388, 0.113, 0.526, 47.18, 19.97, 0.187, 1.23, 1.247, 6.24e-5};
    const jc_Setup s = finding_setup(&f);
    jc_Run run;
    int st;
    char err[256] = "";
    if (simulate(&s, &run, &st, err, sizeof err)) return 1;
    const jc_Termination end = run.termination;
    const double t = run.final_state.t_s;
    const int first_is_liftoff = run.event_count > 0 && run.events[0].kind == JC_EVENT_LIFTOFF;
    jc_run_free(&run);
    ENSURE_OK(st, err);
    ENSURE(first_is_liftoff);
    ENSURE_MSG(end == JC_END_RAMP_END && t > 1.0, "ended: %s at t = %g s", jc_termination_name(end), t);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_extreme_magnitudes_are_rejected);
    RUN_TEST(test_stiff_spin_drag_stays_finite);
    RUN_TEST(test_air_flight_from_rest_advances);
    TEST_MAIN_END();
}
