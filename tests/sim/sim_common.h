/*
 * Shared helpers of the simulator tests (tests/sim): building models and
 * runs, the invariants every run must satisfy, and the rigid-body kinematics
 * written here from docs/physics.md §1, independently of src/.
 *
 * Everything is static inline so that each test uses what it needs without
 * unused-function warnings.
 */
#ifndef JC_SIM_COMMON_H
#define JC_SIM_COMMON_H

#include "../test.h"

#include <jumpcyl/jumpcyl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* The seed of a random test: JC_TEST_SEED if set, else the test's own;
 * seeds *state and returns the seed (printed on a failure). */
static inline uint64_t sim_seed(uint64_t fallback, uint64_t *state)
{
    const char *env = getenv("JC_TEST_SEED");
    const uint64_t seed = env ? strtoull(env, NULL, 10) : fallback;
    *state = seed * 0x9E3779B97F4A7C15ull + 1;
    return seed;
}

/* |energy balance error| relative to the energy that changed hands, or to
 * M g r for a body that hardly moved (as `jumpcyl simulate` reports it). */
static inline double sim_balance_rel(const jc_Model *m, const jc_Run *run)
{
    const jc_EnergyReport *e = &run->energy;
    const double losses = e->friction_loss_J + e->impact_loss_J + e->air_loss_J + e->rolling_resistance_loss_J;
    const double scale = fmax(e->kinetic_J + fabs(e->potential_J) + fabs(losses),
                              m->body.mass_kg * m->setup.gravity_mps2 * m->body.radius_m);
    return fabs(e->balance_error_J) / scale;
}

/* Validates and builds a model; prints the library's message on failure. */
static inline int sim_model(jc_Model *m, const jc_Setup *s)
{
    char err[512] = "";
    ENSURE_OK(jc_model_init(m, s, err, sizeof err), err);
    return 0;
}

/* Runs the simulator; on failure prints the message and frees the run. */
static inline int sim_run(const jc_Model *m, const jc_SimOptions *o, jc_Run *run)
{
    char err[512] = "";
    const int st = jc_simulate(m, o, run, err, sizeof err);
    if (st != JC_OK) {
        fprintf(stderr, "jc_simulate returned %d (%s): %s\n", st, jc_status_text(st), err);
        jc_run_free(run);
        return 1;
    }
    return 0;
}

/* The setup's model and its run with default options sampled every dt. */
static inline int sim_run_sampled(const jc_Setup *s, double dt, jc_Model *m, jc_SimOptions *o, jc_Run *run)
{
    if (sim_model(m, s)) return 1;
    *o = jc_default_sim_options();
    o->sample_dt_s = dt;
    return sim_run(m, o, run);
}

/* The paper's preset at an incline (degrees) and friction coefficient. */
static inline jc_Setup paper_at(double incline_deg, double mu)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = incline_deg * DEG;
    s.mu_static = s.mu_kinetic = mu;
    return s;
}

/* A thin hoop of radius r and mass hoop_kg with a point mass point_kg on its
 * rim at angle 0 (so th is the mass's angle from the top), on a floor, mass
 * on top at the start. */
static inline jc_Setup hoop_with_mass(double r, double hoop_kg, double point_kg, double omega0)
{
    jc_Setup s = jc_paper_setup();
    s.body = (jc_BodyDef){0};
    s.body.radius_m = r;
    s.body.part_count = 2;
    s.body.parts[0] = (jc_Part){JC_PART_HOOP, hoop_kg, 0.0, 0.0, r};
    s.body.parts[1] = (jc_Part){JC_PART_POINT, point_kg, r, 0.0, 0.0};
    s.incline_rad = 0.0;
    s.theta0_rad = 0.0;
    s.omega0_radps = omega0;
    s.ramp_length_m = 3.0;
    s.paper_cm_offset_m = 0.0;
    return s;
}

/* ---- kinematics (physics.md §1): G = C + d (sin th, cos th) ---- */

static inline void cm_position(const jc_Model *m, const jc_State *s, double *xg, double *yg)
{
    const double d = m->body.cm_offset_m;
    *xg = s->x_m + d * sin(s->theta_rad);
    *yg = s->y_m + d * cos(s->theta_rad);
}

/* dG/dt = v_C + d w (cos th, -sin th). */
static inline void cm_velocity(const jc_Model *m, const jc_State *s, double *vgx, double *vgy)
{
    const double d = m->body.cm_offset_m, w = s->omega_radps;
    *vgx = s->vx_mps + d * w * cos(s->theta_rad);
    *vgy = s->vy_mps - d * w * sin(s->theta_rad);
}

/* K = M |v_G|^2 / 2 + I_G w^2 / 2. */
static inline double my_kinetic(const jc_Model *m, const jc_State *s)
{
    double vx, vy;
    cm_velocity(m, s, &vx, &vy);
    return 0.5 * m->body.mass_kg * (vx * vx + vy * vy) +
           0.5 * m->body.inertia_g_kgm2 * s->omega_radps * s->omega_radps;
}

/* U = M g (height of G above the incline's line, measured vertically),
 * relative to the start state (C at (0, r), th = th0). */
static inline double my_potential(const jc_Model *m, const jc_State *s)
{
    const double M = m->body.mass_kg, g = m->setup.gravity_mps2, a = m->setup.incline_rad;
    const double d = m->body.cm_offset_m, r = m->body.radius_m, th0 = m->setup.theta0_rad;
    double xg, yg;
    cm_position(m, s, &xg, &yg);
    const double xg0 = d * sin(th0), yg0 = r + d * cos(th0);
    /* Height along the true vertical: y cos a - x sin a (x points downhill). */
    return M * g * ((yg - yg0) * cos(a) - (xg - xg0) * sin(a));
}

/* ---- invariants of every run (the item 8 d, g) ---- */

static inline int termination_is_known(jc_Termination t)
{
    switch (t) {
    case JC_END_RAMP_END:
    case JC_END_RAMP_TOP:
    case JC_END_TIME_LIMIT:
    case JC_END_EVENT_LIMIT:
    case JC_END_PAINLEVE:
    case JC_END_AT_REST:
    case JC_END_STEP_LIMIT:
    case JC_END_SAMPLE_LIMIT: return 1;
    }
    return 0;
}

/* A finished run: a known termination, the final time within the limit,
 * events in time order, every flight of positive length and non-negative
 * height, every sample in time order. */
static inline int check_run_invariants(const jc_SimOptions *o, const jc_Run *run)
{
    ENSURE_MSG(termination_is_known(run->termination), "termination %d", (int)run->termination);
    ENSURE_MSG(run->final_state.t_s <= o->t_max_s, "final t %.17g > t_max %.17g", run->final_state.t_s,
               o->t_max_s);
    ENSURE(run->event_count <= o->max_events);
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        ENSURE_MSG(isfinite(e->state.t_s) && e->state.t_s >= 0.0, "event %d at t %g", i, e->state.t_s);
        if (i > 0)
            ENSURE_MSG(e->state.t_s >= run->events[i - 1].state.t_s, "event %d (%s) at %.17g before event %d at %.17g",
                       i, jc_event_name(e->kind), e->state.t_s, i - 1, run->events[i - 1].state.t_s);
        if (e->kind == JC_EVENT_LIFTOFF) {
            ENSURE_MSG(e->flight_time_s > 0.0, "lift-off %d: flight time %g", i, e->flight_time_s);
            ENSURE_MSG(e->hop_height_m >= 0.0, "lift-off %d: hop height %g", i, e->hop_height_m);
        }
    }
    for (int i = 1; i < run->sample_count; ++i)
        ENSURE_MSG(run->samples[i].state.t_s >= run->samples[i - 1].state.t_s, "sample %d at %.17g before %.17g", i,
                   run->samples[i].state.t_s, run->samples[i - 1].state.t_s);
    return 0;
}

static inline int count_events(const jc_Run *run, jc_EventKind kind)
{
    int n = 0;
    for (int i = 0; i < run->event_count; ++i) n += run->events[i].kind == kind;
    return n;
}

#endif
