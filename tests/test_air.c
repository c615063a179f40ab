/*
 * Air drag, Magnus force, spin drag and rolling resistance, each checked
 * against a computation made here: a tight GSL integration of free flight
 * with drag, the closed-form approach of a rolling disc to its terminal
 * speed, the energy balance with every loss channel on, and zero
 * coefficients reproducing the resistance-free run bit for bit.
 */
#include "test.h"

#include <jumpcyl/jumpcyl.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <stdlib.h>

#define DEG (3.14159265358979323846 / 180.0)

static int simulate(const jc_Setup *s, const jc_SimOptions *o, jc_Model *m, jc_Run *run)
{
    char err[256] = "";
    ENSURE_OK(jc_model_init(m, s, err, sizeof err), err);
    ENSURE_OK(jc_simulate(m, o, run, err, sizeof err), err);
    return 0;
}

/* ---- free flight with drag and Magnus, integrated here ---- */

typedef struct {
    const jc_Model *m;
} flight_params;

/* Centre of mass G, angle th: M a_G = M g + F_air(v_C), I_G th'' = moment of F_air at C - k w|w|. */
static int flight_rhs(double t, const double y[], double f[], void *p)
{
    (void)t;
    const jc_Model *m = ((const flight_params *)p)->m;
    const jc_Setup *s = &m->setup;
    const double M = m->body.mass_kg, d = m->body.cm_offset_m, ig = m->body.inertia_g_kgm2;
    const double th = y[2], w = y[5];
    /* velocity of the centre C = G - d (sin th, cos th) */
    const double vx = y[3] - d * cos(th) * w, vy = y[4] + d * sin(th) * w;
    const double v = hypot(vx, vy), q = 0.5 * s->air_density_kgpm3 * 2.0 * m->body.radius_m * s->length_m * v;
    /* Magnus: C_L at spin ratio r|w|/|v| >= 1, proportionally less below it. */
    const double ratio = m->body.radius_m * w / v;
    const double spin = fabs(ratio) >= 1.0 ? (ratio > 0) - (ratio < 0) : ratio;
    const double fx = q * (-s->drag_coefficient * vx + s->lift_coefficient * spin * vy);
    const double fy = q * (-s->drag_coefficient * vy - s->lift_coefficient * spin * vx);
    /* torque about G (clockwise-positive) of a force at C: r = C - G = -d (sin, cos);
     * clockwise torque = -(r_x f_y - r_y f_x) */
    const double rx = -d * sin(th), ry = -d * cos(th);
    const double torque = -(rx * fy - ry * fx) - s->spin_drag_Nms2 * w * fabs(w);
    f[0] = y[3];
    f[1] = y[4];
    f[2] = w;
    f[3] = s->gravity_mps2 * sin(s->incline_rad) + fx / M;
    f[4] = -s->gravity_mps2 * cos(s->incline_rad) + fy / M;
    f[5] = torque / ig;
    return GSL_SUCCESS;
}

/* From the first lift-off of a run with air, integrate the flight here to the
 * time of the next impact and compare the landing position: the library's
 * flight is an ODE with event location, this one a driver at 1e-13 with no
 * events, evaluated at the library's impact time. */
static int test_flight_with_air_matches_independent_integration(void)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 30 * DEG;
    s.drag_coefficient = 1.0;
    s.lift_coefficient = 0.4;
    s.spin_drag_Nms2 = 2e-6;
    jc_Model m;
    jc_Run run;
    const jc_SimOptions o = jc_default_sim_options();
    if (simulate(&s, &o, &m, &run)) return 1;
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    ENSURE(sum.first_liftoff >= 0);
    const jc_Event *lift = &run.events[sum.first_liftoff];
    const jc_Event *land = &run.events[sum.first_liftoff + 1];
    ENSURE(land->kind == JC_EVENT_BOUNCE || land->kind == JC_EVENT_TOUCHDOWN);
    const double d = m.body.cm_offset_m, th = lift->state.theta_rad, w = lift->state.omega_radps;
    double y[6] = {lift->state.x_m + d * sin(th), lift->state.y_m + d * cos(th), th,
                   lift->state.vx_mps + d * cos(th) * w, lift->state.vy_mps - d * sin(th) * w, w};
    flight_params fp = {&m};
    gsl_odeiv2_system sys = {flight_rhs, NULL, 6, &fp};
    gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-14, 1e-14);
    double t = lift->state.t_s;
    const int st = gsl_odeiv2_driver_apply(drv, &t, land->state.t_s, y);
    gsl_odeiv2_driver_free(drv);
    ENSURE(st == GSL_SUCCESS);
    /* Centre at landing; the impact keeps positions and angle. Tolerance:
     * the two integrations at 1e-11 and 1e-14 over 0.2 s agree to ~1e-10 m. */
    ENSURE_NEAR(y[0] - d * sin(y[2]), land->state.x_m, 1e-9);
    ENSURE_NEAR(y[1] - d * cos(y[2]), m.body.radius_m, 1e-9);
    ENSURE_NEAR(y[2], land->state.theta_rad, 1e-9);
    /* The flight really felt the air: spin drag slowed the spin. */
    ENSURE(fabs(y[5]) < fabs(w));
    jc_run_free(&run);
    return 0;
}

/* ---- a rolling disc with drag reaches its terminal speed ---- */

/* Uniform disc (d = 0) rolling: (M + I_C/r^2) a = M g sin a - k v^2, k = rho C_d A / 2,
 * so v(t) = v_t tanh(t sqrt(k M g sin a) / m_eff), v_t = sqrt(M g sin a / k). */
static int test_rolling_disc_terminal_speed(void)
{
    jc_Setup s = jc_paper_setup();
    s.body = (jc_BodyDef){.radius_m = 0.1, .part_count = 1, .parts = {{JC_PART_DISC, 0.0663, 0, 0, 0.1}}};
    s.paper_cm_offset_m = 0.0;
    s.incline_rad = 20 * DEG;
    s.mu_static = s.mu_kinetic = 1.0; /* rolling needs |F|/N = tan(a)/3 at most */
    s.drag_coefficient = 3.0;
    s.ramp_length_m = 60.0;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = 0.05;
    o.t_max_s = 8.0;
    jc_Model m;
    jc_Run run;
    if (simulate(&s, &o, &m, &run)) return 1;
    const double M = m.body.mass_kg, r = m.body.radius_m, g = s.gravity_mps2;
    const double k = 0.5 * s.air_density_kgpm3 * s.drag_coefficient * 2.0 * r * s.length_m;
    const double m_eff = M + m.body.inertia_c_kgm2 / (r * r), drive = M * g * sin(s.incline_rad);
    const double vt = sqrt(drive / k), rate = sqrt(k * drive) / m_eff;
    ENSURE(run.sample_count > 100);
    double worst = 0.0;
    for (int i = 0; i < run.sample_count; ++i) {
        const jc_Sample *p = &run.samples[i];
        ENSURE(p->mode == JC_MODE_ROLLING);
        const double v = vt * tanh(rate * p->state.t_s);
        worst = fmax(worst, fabs(p->state.vx_mps - v));
        /* x(t) = (v_t / rate) ln cosh(rate t) */
        ENSURE_NEAR(p->state.x_m, vt / rate * log(cosh(rate * p->state.t_s)), 1e-8);
    }
    /* rk8pd at rtol 1e-11 on a 3 m/s speed: 1e-9 m/s has room. */
    ENSURE_MSG(worst < 1e-9, "largest speed error %.3g m/s against v_t tanh(.)", worst);
    /* It got close to terminal speed (the test is about the drag, not the start). */
    ENSURE(run.samples[run.sample_count - 1].state.vx_mps > 0.95 * vt);
    jc_run_free(&run);
    return 0;
}

/* ---- energy balance with every loss channel on ---- */

static int test_energy_balance_every_channel(void)
{
    for (int deg = 15; deg <= 45; deg += 15) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = deg * DEG;
        s.drag_coefficient = 1.0;
        s.lift_coefficient = 0.3;
        s.spin_drag_Nms2 = 1e-6;
        s.rolling_resistance_m = 1e-4;
        jc_SimOptions o = jc_default_sim_options();
        o.sample_dt_s = 0.005;
        jc_Model m;
        jc_Run run;
        if (simulate(&s, &o, &m, &run)) return 1;
        const jc_EnergyReport *e = &run.energy;
        ENSURE(e->air_loss_J > 0.0 && e->rolling_resistance_loss_J > 0.0);
        ENSURE(e->friction_loss_J > 0.0 && e->impact_loss_J > 0.0);
        /* Integrator tolerance 1e-11 relative on ~1 J exchanged. */
        ENSURE_MSG(fabs(e->balance_error_J) < 1e-9, "%d deg: balance error %.3g J", deg, e->balance_error_J);
        const double e0 = run.samples[0].kinetic_J + run.samples[0].potential_J;
        double prev_air = 0.0, prev_rr = 0.0;
        for (int i = 0; i < run.sample_count; ++i) {
            const jc_Sample *p = &run.samples[i];
            const double total = p->kinetic_J + p->potential_J + p->friction_loss_J + p->impact_loss_J +
                                 p->air_loss_J + p->rolling_resistance_loss_J;
            ENSURE_NEAR(total, e0, 1e-9);
            ENSURE(p->air_loss_J >= prev_air - 1e-15 && p->rolling_resistance_loss_J >= prev_rr - 1e-15);
            prev_air = p->air_loss_J;
            prev_rr = p->rolling_resistance_loss_J;
        }
        jc_run_free(&run);
    }
    return 0;
}

/* ---- zero coefficients: the resistance-free run, bit for bit ---- */

static int test_zero_coefficients_are_resistance_free(void)
{
    for (int deg = 15; deg <= 45; deg += 15) {
        jc_Setup a = jc_paper_setup();
        a.incline_rad = deg * DEG;
        jc_Setup b = a;
        b.length_m = 0.3;             /* geometry and air present ... */
        b.air_density_kgpm3 = 1.3;
        b.drag_coefficient = 0.0;     /* ... but every coefficient 0 */
        b.lift_coefficient = 0.0;
        b.spin_drag_Nms2 = 0.0;
        b.rolling_resistance_m = 0.0;
        const jc_SimOptions o = jc_default_sim_options();
        jc_Model ma, mb;
        jc_Run ra, rb;
        if (simulate(&a, &o, &ma, &ra) || simulate(&b, &o, &mb, &rb)) return 1;
        ENSURE(ra.event_count == rb.event_count);
        ENSURE(memcmp(ra.events, rb.events, (size_t)ra.event_count * sizeof(jc_Event)) == 0);
        ENSURE(rb.energy.air_loss_J == 0.0 && rb.energy.rolling_resistance_loss_J == 0.0);
        jc_run_free(&ra);
        jc_run_free(&rb);
    }
    return 0;
}

/* ---- the Magnus sign: C_L > 0 pushes a forward-rolling cylinder into the incline ---- */

static int test_magnus_pushes_topspin_down(void)
{
    /* A uniform disc rolling on a floor at 10 rad/s: N = M g without lift,
     * N = M g + 1/2 rho C_L A v^2 with it (v = r w, topspin). */
    jc_Setup s = jc_paper_setup();
    s.body = (jc_BodyDef){.radius_m = 0.1, .part_count = 1, .parts = {{JC_PART_DISC, 0.0663, 0, 0, 0.1}}};
    s.paper_cm_offset_m = 0.0;
    s.incline_rad = 0.0;
    s.omega0_radps = 10.0;
    s.lift_coefficient = 0.5;
    s.ramp_length_m = 0.5;
    jc_Model m;
    jc_Run run;
    const jc_SimOptions o = jc_default_sim_options();
    if (simulate(&s, &o, &m, &run)) return 1;
    const jc_Sample *p = &run.samples[0];
    const double v = 0.1 * 10.0;
    const double lift = 0.5 * s.air_density_kgpm3 * s.lift_coefficient * 2.0 * 0.1 * s.length_m * v * v;
    ENSURE_REL(p->normal_N, m.body.mass_kg * s.gravity_mps2 + lift, 1e-12);
    jc_run_free(&run);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_flight_with_air_matches_independent_integration);
    RUN_TEST(test_rolling_disc_terminal_speed);
    RUN_TEST(test_energy_balance_every_channel);
    RUN_TEST(test_zero_coefficients_are_resistance_free);
    RUN_TEST(test_magnus_pushes_topspin_down);
    TEST_MAIN_END();
}
