/*
 * Flight with air (docs/physics.md, "Air and rolling resistance"): no
 * closed form, an ODE for ode.c in the body's state (the centre C, the
 * angle by its cosine and sine), ended by the rim touching the incline or
 * the centre passing an end of the ramp; the apexes of C are passed
 * through for the hop's height. flight.c has the closed form without air.
 */
#include "internal.h"
#include "dop853_kernel.h"

#include <math.h>

typedef struct {
    const jc_Model *m;
    double apex_sign; /* sign of vy_C until its next zero (an apex or a dip of the rim) */
    double gap_slack; /* 1 pm after a lift-off: rounding at N = 0 cannot end the flight at once */
    /* The right-hand side's constants, taken once per phase. */
    jc_AirConsts air;
    double inv_m_per_kg, inv_ig, g_sin_mps2, g_cos_mps2;
} flight_ode;

static void flight_ode_consts(const jc_Model *m, flight_ode *c)
{
    /* Reciprocals from the model, as in sliding.c: three divisions at every
     * stage of every step would lie on its chain of dependent operations. */
    const jc_ModelTables *tb = jc_model_tables(m);
    jc_air_consts(m, &c->air);
    c->inv_m_per_kg = tb->inv_mass_per_kg;
    c->inv_ig = tb->inv_inertia_g;
    c->g_sin_mps2 = m->setup.gravity_mps2 * m->sin_incline;
    c->g_cos_mps2 = m->setup.gravity_mps2 * m->cos_incline;
}

static void flight_ode_accel(const flight_ode *k, const double y[], double acc[3], double *air_power)
{
    const double d = k->air.d_m, w = y[JC_Y_W], s = y[JC_Y_SIN], c = y[JC_Y_COS];
    double fx, fy, torque;
    /* The terms that do not wait for the air's loads first: each stage
     * waits for the last one's rates, and the loads wait for a square root
     * (the speed). */
    const double ds = d * s, dc = d * c, w2 = w * w;
    const double free_x = k->g_sin_mps2 + ds * w2, free_y = dc * w2 - k->g_cos_mps2;
    jc_air_loads(&k->air, s, c, y[JC_Y_VX], y[JC_Y_VY], w, &fx, &fy, &torque, air_power);
    const double thdd = torque * k->inv_ig;
    acc[0] = (free_x + fx * k->inv_m_per_kg) - dc * thdd; /* x_C'' */
    acc[1] = (free_y + fy * k->inv_m_per_kg) + ds * thdd; /* y_C'' */
    acc[2] = thdd;
}

static int flight_ode_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const flight_ode *c = params;
    double acc[3], power;
    flight_ode_accel(c, y, acc, &power);
    dydt[JC_Y_X] = y[JC_Y_VX];
    dydt[JC_Y_Y] = y[JC_Y_VY];
    dydt[JC_Y_TH] = y[JC_Y_W];
    dydt[JC_Y_VX] = acc[0];
    dydt[JC_Y_VY] = acc[1];
    dydt[JC_Y_W] = acc[2];
    dydt[JC_Y_FRICTION] = 0.0;
    dydt[JC_Y_AIR] = power;
    dydt[JC_Y_RR] = 0.0;
    dydt[JC_Y_COS] = -y[JC_Y_W] * y[JC_Y_SIN];
    dydt[JC_Y_SIN] = y[JC_Y_W] * y[JC_Y_COS];
    return 0;
}

JC_DOP853_TRY_INSTANCE(flight_ode_try, flight_ode_rhs, 0, JC_Y_DIM)

enum { FE_GAP, FE_END, FE_TOP, FE_APEX, FE_COUNT };

static void flight_ode_events(void *params, const double y[], double ev[])
{
    const flight_ode *c = params;
    ev[FE_GAP] = y[JC_Y_Y] - c->m->body.radius_m + c->gap_slack;
    ev[FE_END] = c->m->setup.ramp_length_m - y[JC_Y_X];
    ev[FE_TOP] = y[JC_Y_X] + JC_RAMP_TOP_SLACK_M;
    ev[FE_APEX] = c->apex_sign * y[JC_Y_VY];
}

/* Their rates, in closed form. */
static void flight_ode_event_rates(void *params, const double y[], const double f[], double dev[])
{
    (void)y;
    const flight_ode *c = params;
    dev[FE_GAP] = f[JC_Y_Y];
    dev[FE_END] = -f[JC_Y_X];
    dev[FE_TOP] = f[JC_Y_X];
    dev[FE_APEX] = c->apex_sign * f[JC_Y_VY];
}

static int flight_ode_sample(jc_Sim *sim, void *params, double t, const double y[])
{
    (void)params;
    jc_State s;
    jc_y_to_state(y, t, &s);
    return jc_record_sample_y(sim, &s, y, JC_MODE_FLIGHT, 0.0, 0.0, jc_flight_gap(sim->m, &s));
}

#define FLIGHT_MAX_APEXES 100000L

/* An apex (or a dip) of the centre is passed through, not a phase's end:
 * its height from the continuous extension (there vy = 0: an error in its
 * time changes the height in second order only), the event's sign flipped,
 * and the integration goes on in the same step. Stopping there would cost
 * a located real step, a restart and the rest of the step again (a drag
 * run has about 7 apexes). */
static int flight_ode_pass(jc_Sim *sim, void *params, int k, double t, const double y[])
{
    (void)t;
    flight_ode *c = params;
    if (k != FE_APEX) return 0;
    sim->hop_height_m = fmax(sim->hop_height_m, y[JC_Y_Y] - sim->m->body.radius_m);
    c->apex_sign = -c->apex_sign;
    return 1;
}

int jc_flight_air_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len)
{
    const double r = sim->m->body.radius_m;
    flight_ode ctx = {.m = sim->m, .apex_sign = sim->s.vy_mps < 0.0 ? -1.0 : 1.0,
                      .gap_slack = from_liftoff ? 1e-12 : 0.0};
    flight_ode_consts(sim->m, &ctx);
    sim->hop_height_m = fmax(sim->s.y_m - r, 0.0);
    for (long k = 0; k < FLIGHT_MAX_APEXES; ++k) {
        const jc_OdePhase phase = {flight_ode_rhs, flight_ode_events, FE_COUNT, flight_ode_sample, &ctx,
                                   JC_Y_DIM, flight_ode_event_rates, flight_ode_try};
        int which;
        const jc_OdeExtras passing = {0, flight_ode_pass};
        int st = jc_ode_run_with(sim, &phase, &passing, &which, err, err_len);
        if (st != JC_OK) return st;
        sim->hop_height_m = fmax(sim->hop_height_m, sim->s.y_m - r);
        switch (which) {
        case FE_APEX:
            ctx.apex_sign = -ctx.apex_sign;
            continue;
        case FE_GAP:
            sim->s.y_m = r;
            *end = PHASE_TOUCHDOWN;
            return JC_OK;
        case FE_END: *end = PHASE_RAMP_END; return JC_OK;
        case FE_TOP: *end = PHASE_RAMP_TOP; return JC_OK;
        case JC_ODE_TIME_LIMIT: *end = PHASE_TIME_LIMIT; return JC_OK;
        default: *end = PHASE_STEP_LIMIT; return JC_OK;
        }
    }
    *end = PHASE_STEP_LIMIT;
    return JC_OK;
}
