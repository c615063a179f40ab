/*
 * Rocking under rolling resistance: the hopping hoop (`--preset hoop`, a
 * 100 g point on the rim of a 10 g hoop of radius 10 cm, on a floor) with a
 * rolling-resistance lever b rocks about the mass's lowest position with
 * decaying amplitude and comes to rest where rolling resistance holds it.
 * The simulator is compared with what is computed here, independently of
 * src/:
 *
 * - The motion from a rocking start, against the rolling body integrated
 *   here (GSL rk8pd) with exact Coulomb rolling resistance: the normal force
 *   acting a lever b_s = b sgn(w) ahead of the contact point, no ramp.
 *   Newton-Euler for G with the rolling constraint (physics.md §2.1),
 *     a_G = (a (r + d c) - w^2 d s, -a d s - w^2 d c),   s, c = sin th, cos th,
 *     M a_Gx = M g sin al + F,   M a_Gy = -M g cos al + N,
 *     I_G a = -(r + d c) F - (b_s - d s) N       (moments about G, th sense),
 *   solved here for a. At every turning point (w = 0) the body is held when
 *   some lever in [-b, b] balances gravity about the contact point, that is
 *   when |Q| <= b cos al, Q = (r + d c) sin al + d s cos al (the static
 *   condition: the gravity torque about the contact, M g Q, within b N,
 *   N = M g cos al); otherwise it starts the way gravity turns it.
 * - Energy: K + U of the final state computed here (sim_common.h) and the
 *   run's losses must add up to K + U at the start.
 *
 * The simulator ramps rolling resistance over |w| < 1 mrad/s (physics.md
 * §9.1) and ends the run at rest once the spin is inside that band where
 * the static condition holds; the exact model crawls on from there to its
 * last turn. The tolerances below bound those differences.
 *
 * Before the fix, each turn started the rolling phase at w = 0 with the
 * full lever in the integrator's first stage and the ramp's ~0 beyond it:
 * the first step was rejected down to ~1e-11 s, and from t ~ 8 s below the
 * integrator's floor (1e-12 t): `jumpcyl simulate --preset hoop
 * --rolling-resistance 1mm` failed at t = 8.2175 s ("integration diverged").
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#define SAMPLE_DT_S 1e-3
/* rad/s: the simulator's rolling-resistance band (physics.md §9.1). */
#define BAND_RADPS 1e-3
#define MAX_TURNS 64

typedef struct {
    double M, ig, r, d, g, sa, ca, b;
    int dir; /* the sign of w on this swing: the lever's side */
} coulomb_body;

static coulomb_body body_of(const jc_Model *m, double b)
{
    const jc_Setup *s = &m->setup;
    return (coulomb_body){m->body.mass_kg,  m->body.inertia_g_kgm2, m->body.radius_m,   m->body.cm_offset_m,
                          s->gravity_mps2,  sin(s->incline_rad),    cos(s->incline_rad), b, 0};
}

/* th'' of rolling with the lever b dir: F = M (a h - w^2 d s - g sa) and
 * N = M (g ca - a d s - w^2 d c), h = r + d c, put into the moment equation. */
static double coulomb_thdd(const coulomb_body *k, double th, double w)
{
    const double s = sin(th), c = cos(th), bs = k->b * k->dir, h = k->r + k->d * c, w2 = w * w;
    const double lhs = k->ig + k->M * h * h - k->M * (bs - k->d * s) * k->d * s;
    const double rhs = k->M * h * (w2 * k->d * s + k->g * k->sa) - k->M * (bs - k->d * s) * (k->g * k->ca - w2 * k->d * c);
    return rhs / lhs;
}

static int coulomb_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    dydt[0] = y[1];
    dydt[1] = coulomb_thdd(params, y[0], y[1]);
    return GSL_SUCCESS;
}

/* Q: the gravity torque about the contact point per M g. */
static double gravity_lever(const coulomb_body *k, double th)
{
    return (k->r + k->d * cos(th)) * k->sa + k->d * sin(th) * k->ca;
}

/* I_P = I_G + M |G - P|^2, G - P = (d s, r + d c). */
static double inertia_p(const coulomb_body *k, double th)
{
    const double gx = k->d * sin(th), gy = k->r + k->d * cos(th);
    return k->ig + k->M * (gx * gx + gy * gy);
}

/* The Coulomb model's motion: (th, w) at t, its turning points, rest. */
typedef struct {
    coulomb_body k;
    double t, y[2];
    int at_rest;
    double turn_th[MAX_TURNS], turn_t[MAX_TURNS];
    int turns;
} coulomb_run;

/* (th, w) dt after y0 on the current swing (smooth: the lever is fixed). */
static int swing_step(coulomb_run *c, const double y0[2], double dt, double y[2])
{
    gsl_odeiv2_system sys = {coulomb_rhs, NULL, 2, &c->k};
    gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-14, 1e-14);
    ENSURE(drv != NULL);
    y[0] = y0[0];
    y[1] = y0[1];
    double t = 0.0;
    const int st = gsl_odeiv2_driver_apply(drv, &t, dt, y);
    gsl_odeiv2_driver_free(drv);
    ENSURE_MSG(st == GSL_SUCCESS, "rk8pd: %s", gsl_strerror(st));
    return 0;
}

/* At w = 0: held (rest), or started the way gravity turns it. */
static void coulomb_turn(coulomb_run *c)
{
    const double q = gravity_lever(&c->k, c->y[0]);
    c->y[1] = 0.0;
    if (fabs(q) <= c->k.b * c->k.ca) c->at_rest = 1;
    else c->k.dir = q > 0.0 ? 1 : -1;
}

/* Advances to t_to, or to rest before it (c->t is then the time of rest),
 * in chunks far shorter than a swing (0.14 s): w changes sign at most once
 * in each. A swing ends where w reaches 0, found by bisection in time (the
 * swing's smooth continuation past the turn has w of the other sign). */
static int coulomb_advance(coulomb_run *c, double t_to)
{
    while (!c->at_rest && c->t < t_to) {
        const double dt = fmin(t_to - c->t, SAMPLE_DT_S);
        double y[2];
        if (swing_step(c, c->y, dt, y)) return 1;
        if (y[1] * c->k.dir > 0.0) {
            c->t += dt;
            c->y[0] = y[0];
            c->y[1] = y[1];
            continue;
        }
        double lo = 0.0, hi = dt;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            if (swing_step(c, c->y, mid, y)) return 1;
            if (y[1] * c->k.dir > 0.0) lo = mid;
            else hi = mid;
        }
        if (swing_step(c, c->y, hi, y)) return 1;
        c->t += hi;
        c->y[0] = y[0];
        ENSURE(c->turns < MAX_TURNS);
        c->turn_t[c->turns] = c->t;
        c->turn_th[c->turns++] = y[0];
        coulomb_turn(c);
    }
    return 0;
}

/* The hoop preset with rolling resistance b, on its floor. */
static int hoop_model(double b, jc_Model *m)
{
    jc_Setup s;
    char err[256] = "";
    ENSURE_OK(jc_preset_setup("hoop", &s, err, sizeof err), err);
    ENSURE_MSG(s.incline_rad == 0.0, "the hoop preset's incline is %g rad", s.incline_rad);
    s.rolling_resistance_m = b;
    return sim_model(m, &s);
}

/* K + U of a state, computed here (sim_common.h). */
static double mechanical_energy(const jc_Model *m, const jc_State *s) { return my_kinetic(m, s) + my_potential(m, s); }

static double run_losses(const jc_Run *run)
{
    const jc_EnergyReport *e = &run->energy;
    return e->friction_loss_J + e->impact_loss_J + e->air_loss_J + e->rolling_resistance_loss_J;
}

/* `jumpcyl simulate --preset hoop --rolling-resistance B` from its start:
 * hops, slips and sticks, then rocking that ends at rest, at an angle where
 * the body is held, with K0 + U0 = K + U + losses to 1e-9 J (of the 0.33 J
 * that change hands). */
static int check_issue_run(double b)
{
    jc_Model m;
    if (hoop_model(b, &m)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    jc_Run run;
    if (sim_run(&m, &o, &run)) return 1;
    const jc_Termination t = run.termination;
    const jc_State f = run.final_state, s0 = jc_start_state(&m);
    const double balance = mechanical_energy(&m, &s0) - mechanical_energy(&m, &f) - run_losses(&run);
    const coulomb_body k = body_of(&m, b);
    const double q = gravity_lever(&k, f.theta_rad);
    const jc_Mode mode = run.final_mode;
    const int events = run.event_count;
    jc_run_free(&run);
    printf("  b = %g mm: %s at %.6f s after %d events, |Q| %.4f mm there, K0 + U0 - K - U - losses %.2g J\n",
           b * 1e3, jc_termination_name(t), f.t_s, events, fabs(q) * 1e3, balance);
    ENSURE_MSG(t == JC_END_REST, "b = %g m: ended %s at %.9g s", b, jc_termination_name(t), f.t_s);
    ENSURE(mode == JC_MODE_ROLLING && f.omega_radps == 0.0 && f.vx_mps == 0.0);
    ENSURE_MSG(fabs(q) <= b, "b = %g m: at rest at th = %.9g rad, where |Q| = %.6g m > b", b, f.theta_rad, fabs(q));
    ENSURE_MSG(fabs(balance) <= 1e-9, "b = %g m: K0 + U0 - K - U - losses = %.3g J", b, balance);
    return 0;
}

static int test_issue_hoop_comes_to_rest(void)
{
    /* 1 mm is the issue's; 2 mm and 5 mm failed the same way, earlier. */
    const double levers[] = {0.1e-3, 0.5e-3, 1e-3, 2e-3, 5e-3};
    for (size_t i = 0; i < sizeof levers / sizeof levers[0]; ++i)
        if (check_issue_run(levers[i])) return 1;
    return 0;
}

/* The simulator's turning points from its samples: w changes sign between
 * samples i and i + 1, and the turn is at th - w^2 / (2 a), t - w / a from
 * sample i, with a from samples i - 1 and i, on the same side of the turn
 * (the acceleration jumps there by 2 b N / I_P). */
static int sampled_turns(const jc_Run *run, double th[], double t[])
{
    int n = 0;
    for (int i = 1; i + 1 < run->sample_count && n < MAX_TURNS; ++i) {
        const jc_State *a0 = &run->samples[i - 1].state, *a1 = &run->samples[i].state;
        if (a1->omega_radps * run->samples[i + 1].state.omega_radps < 0.0) {
            const double acc = (a1->omega_radps - a0->omega_radps) / (a1->t_s - a0->t_s);
            t[n] = a1->t_s - a1->omega_radps / acc;
            th[n++] = a1->theta_rad - a1->omega_radps * a1->omega_radps / (2.0 * acc);
        }
    }
    return n;
}

/* Rocking from rest 0.3 rad from the mass's lowest position, started at
 * t = 20 s (where the integrator's step floor is 2e-11 s), against the
 * Coulomb model integrated here: the same turning points to 1e-7 rad (the
 * ramp acts on the last band^2 I_P / (2 M g |Q|) of rolling into each, 5e-8
 * rad at the last turn, and takes less than b N over it), and times to 1e-4 s (leaving a turn through the ramp gains at most
 * band I_P (1/(M g |Q| - b N) - 1/(M g |Q|)) on the Coulomb model, 4e-5 s at
 * the last turn, where M g |Q| is twice b N, and 1e-6 s at the first), all
 * of the energy lost to rolling resistance, and rest in the static band
 * where the Coulomb model rests, within the crawl from 1 mrad/s that the
 * simulator skips. */
static int test_rocking_against_coulomb(void)
{
    const double b = 1e-3, phi0 = 0.3, t0 = 20.0;
    jc_Model m;
    if (hoop_model(b, &m)) return 1;
    const jc_State start = {t0, 0.0, m.body.radius_m, 0.0, 0.0, PI - phi0, 0.0};
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = SAMPLE_DT_S;
    jc_Run run = {0};
    const jc_Recorder rec = jc_run_recorder(&run);
    char err[512] = "";
    const int st = jc_simulate_from(&m, &start, &o, &rec, NULL, &run, err, sizeof err);
    if (st != JC_OK) jc_run_free(&run);
    ENSURE_OK(st, err);
    int rolling = 1;
    for (int i = 0; i < run.sample_count; ++i) rolling &= run.samples[i].mode == JC_MODE_ROLLING;
    double sim_th[MAX_TURNS], sim_t[MAX_TURNS];
    const int sim_turns = sampled_turns(&run, sim_th, sim_t);
    const jc_Termination t = run.termination;
    const jc_State f = run.final_state;
    const int events = run.event_count;
    const double rr_loss = run.energy.rolling_resistance_loss_J;
    const double others = run.energy.friction_loss_J + run.energy.impact_loss_J + run.energy.air_loss_J;
    jc_run_free(&run);
    const double balance = mechanical_energy(&m, &start) - mechanical_energy(&m, &f) - rr_loss;

    coulomb_run c = {body_of(&m, b), t0, {start.theta_rad, 0.0}, 0, {0}, {0}, 0};
    coulomb_turn(&c);
    if (coulomb_advance(&c, t0 + 60.0)) return 1;
    const coulomb_body *k = &c.k;
    double worst_th = 0.0, worst_t = 0.0;
    for (int i = 0; i < sim_turns && i < c.turns; ++i) {
        worst_th = fmax(worst_th, fabs(sim_th[i] - c.turn_th[i]));
        worst_t = fmax(worst_t, fabs(sim_t[i] - c.turn_t[i]));
    }
    printf("  from %.2f rad: %d turns (here %d), worst %.2g rad, %.2g s; rest at %.6f s, %+.6f rad (here %.6f s, "
           "%+.6f rad); K0 + U0 - K - U - rolling resistance %.2g J\n",
           phi0, sim_turns, c.turns, worst_th, worst_t, f.t_s, f.theta_rad - PI, c.t, c.y[0] - PI, balance);
    ENSURE_MSG(events == 0 && rolling, "%d events; rolling throughout: %d", events, rolling);
    ENSURE_MSG(t == JC_END_REST, "ended %s at %.9g s", jc_termination_name(t), f.t_s);
    ENSURE_MSG(c.at_rest && c.turns >= 10, "the Coulomb model: rest %d after %d turns", c.at_rest, c.turns);
    /* The Coulomb model rests at its last turn; the simulator, on its way there. */
    ENSURE_MSG(sim_turns == c.turns - 1, "%d turning points, the Coulomb model %d", sim_turns, c.turns);
    ENSURE_MSG(worst_th <= 1e-7, "a turning point %.3g rad off the Coulomb model's", worst_th);
    ENSURE_MSG(worst_t <= 1e-4, "a turning point %.3g s off the Coulomb model's", worst_t);
    /* The amplitude falls: every turn further from the bottom than the next. */
    for (int i = 0; i + 1 < c.turns; ++i)
        ENSURE_MSG(fabs(c.turn_th[i + 1] - PI) < fabs(c.turn_th[i] - PI), "turn %d", i);
    const double q = fabs(gravity_lever(k, f.theta_rad));
    ENSURE_MSG(q <= b, "at rest at th = %.9g rad, where |Q| = %.6g m > b", f.theta_rad, q);
    /* From w = band the Coulomb model decelerates at least at
     * (b N - M g |Q|) / I_P, N >= 0.99 M g (|d s th''| and d w^2 are below
     * 1e-3 g there): it crawls at most band^2 I_P / (2 that) further, for
     * band I_P / that, after the 1e-4 s it may lag. */
    const double margin = k->M * k->g * (0.99 * b - q), ip = inertia_p(k, f.theta_rad);
    ENSURE(margin > 0.0);
    const double crawl_rad = BAND_RADPS * BAND_RADPS * ip / (2.0 * margin), crawl_s = BAND_RADPS * ip / margin;
    ENSURE_MSG(fabs(c.y[0] - f.theta_rad) <= crawl_rad + 1e-7, "rest at %.9g rad, the Coulomb model's %.9g rad (crawl %.3g rad)",
               f.theta_rad, c.y[0], crawl_rad);
    ENSURE_MSG(c.t >= f.t_s - 1e-4 && c.t <= f.t_s + crawl_s + 1e-4, "rest at %.9g s, the Coulomb model's %.9g s (crawl %.3g s)",
               f.t_s, c.t, crawl_s);
    ENSURE_MSG(others == 0.0, "friction, impacts and air took %.3g J", others);
    ENSURE_MSG(fabs(balance) <= 1e-9, "K0 + U0 - K - U - rolling resistance = %.3g J", balance);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_issue_hoop_comes_to_rest);
    RUN_TEST(test_rocking_against_coulomb);
    TEST_MAIN_END();
}
