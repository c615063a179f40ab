/*
 * The mode machine: rolling, sliding and flight phases joined by events and
 * impacts, each transition into the mode consistent with the forces
 * (mode.c). Every loop is bounded: by simulated time, by the event count,
 * and inside each phase by a step bound; every run ends with a reason.
 */
#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

jc_SimOptions jc_default_sim_options(void)
{
    return (jc_SimOptions){
        .t_max_s = 60.0,
        .max_events = 10000,
        .sample_dt_s = 0.0,
        .max_samples = 1000000,
        .ode_rtol = 1e-11,
        .ode_atol = 1e-13,
        .event_tol_s = 1e-12,
        .contact_height_m = 1e-6,
    };
}

int jc_sim_options_validate(const jc_SimOptions *o, char *err, size_t err_len)
{
    if (!(o->t_max_s > 0.0 && o->t_max_s <= 1e6))
        return jc_fail(err, err_len, JC_EINVAL, "time limit %g s is out of range (allowed: (0, 1e6] s)", o->t_max_s);
    if (o->max_events < 1 || o->max_events > 10000000)
        return jc_fail(err, err_len, JC_EINVAL, "event limit %d is out of range (allowed: 1 to 10^7)", o->max_events);
    /* From 1e-9 s, sample k * dt for every k up to t_max / dt <= 1e15 is a
     * distinct double: the grid's times strictly increase. */
    if (!(o->sample_dt_s == 0.0 || (o->sample_dt_s >= 1e-9 && o->sample_dt_s <= 1e6)))
        return jc_fail(err, err_len, JC_EINVAL, "sample step %g s is out of range (allowed: 0, or 1e-9 to 1e6 s)", o->sample_dt_s);
    if (o->max_samples < 1 || o->max_samples > 100000000)
        return jc_fail(err, err_len, JC_EINVAL, "sample limit %d is out of range (allowed: 1 to 10^8)", o->max_samples);
    if (!(o->ode_rtol >= 1e-15 && o->ode_rtol <= 1e-3))
        return jc_fail(err, err_len, JC_EINVAL, "relative tolerance %g is out of range (allowed: [1e-15, 1e-3])", o->ode_rtol);
    if (!(o->ode_atol >= 1e-18 && o->ode_atol <= 1e-3))
        return jc_fail(err, err_len, JC_EINVAL, "absolute tolerance %g is out of range (allowed: [1e-18, 1e-3])", o->ode_atol);
    if (!(o->event_tol_s >= 1e-15 && o->event_tol_s <= 1e-3))
        return jc_fail(err, err_len, JC_EINVAL, "event tolerance %g s is out of range (allowed: [1e-15, 1e-3] s)", o->event_tol_s);
    if (!(o->contact_height_m >= 0.0 && o->contact_height_m <= 1.0))
        return jc_fail(err, err_len, JC_EINVAL, "contact height %g m is out of range (allowed: [0, 1] m)", o->contact_height_m);
    return JC_OK;
}

const char *jc_mode_name(jc_Mode mode)
{
    switch (mode) {
    case JC_MODE_ROLLING: return "rolling";
    case JC_MODE_SLIDING: return "sliding";
    case JC_MODE_FLIGHT: return "flight";
    }
    return "unknown";
}

const char *jc_event_name(jc_EventKind kind)
{
    static const char *const names[JC_EVENT_COUNT] = {"slip", "stick", "slip_reversal", "liftoff", "touchdown",
                                                "bounce", "ramp_end", "ramp_top", "painleve"};
    return kind >= 0 && kind < JC_EVENT_COUNT ? names[kind] : "unknown";
}

const char *jc_termination_name(jc_Termination t)
{
    switch (t) {
    case JC_END_RAMP_END: return "ramp_end";
    case JC_END_RAMP_TOP: return "ramp_top";
    case JC_END_TIME_LIMIT: return "time_limit";
    case JC_END_EVENT_LIMIT: return "event_limit";
    case JC_END_PAINLEVE: return "painleve";
    case JC_END_REST: return "rest";
    case JC_END_STEP_LIMIT: return "step_limit";
    case JC_END_SAMPLE_LIMIT: return "sample_limit";
    }
    return "unknown";
}

/* ---- energy ---- */

double jc_kinetic_energy(const jc_Model *m, const jc_State *s)
{
    const double d = m->body.cm_offset_m, th = s->theta_rad, w = s->omega_radps;
    const double vgx = s->vx_mps + d * cos(th) * w, vgy = s->vy_mps - d * sin(th) * w;
    return 0.5 * m->body.mass_kg * (vgx * vgx + vgy * vgy) + 0.5 * m->body.inertia_g_kgm2 * w * w;
}

static double potential_abs(const jc_Model *m, const jc_State *s)
{
    const double d = m->body.cm_offset_m;
    const double xg = s->x_m + d * sin(s->theta_rad), yg = s->y_m + d * cos(s->theta_rad);
    return m->body.mass_kg * m->setup.gravity_mps2 * (yg * m->cos_incline - xg * m->sin_incline);
}

double jc_potential_energy(const jc_Model *m, const jc_State *s)
{
    const jc_State start = {.y_m = m->body.radius_m, .theta_rad = m->setup.theta0_rad};
    return potential_abs(m, s) - potential_abs(m, &start);
}

/* ---- summary ---- */

void jc_summary_init(jc_RunSummary *out) { *out = (jc_RunSummary){.first_liftoff = -1, .largest_hop = -1}; }

void jc_summary_add(jc_RunSummary *out, const jc_Event *e, int index)
{
    if (e->kind == JC_EVENT_LIFTOFF) {
        if (out->first_liftoff < 0) {
            out->first_liftoff = index;
            out->first_liftoff_state = e->state;
        }
        out->liftoffs++;
    } else if (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT) {
        out->bounces++;
    } else {
        return;
    }
    out->flight_time_s += e->flight_time_s;
    if (out->largest_hop < 0 || e->hop_height_m > out->largest_hop_m) {
        out->largest_hop = index;
        out->largest_hop_m = e->hop_height_m;
    }
}

void jc_run_summarize(const jc_Run *run, jc_RunSummary *out)
{
    jc_summary_init(out);
    for (int i = 0; i < run->event_count; ++i) jc_summary_add(out, &run->events[i], i);
}

void jc_run_free(jc_Run *run)
{
    if (!run) return;
    free(run->events);
    free(run->samples);
    run->events = NULL;
    run->samples = NULL;
    run->event_count = run->sample_count = 0;
}

/* ---- the in-memory recorder behind jc_simulate ---- */

/* Room for one more element: the capacity is implicit (64, then doubling),
 * so that a jc_Run needs no capacity fields. */
static int grow(void **arr, int count, size_t size)
{
    if (count > 0 && (count < 64 || (count & (count - 1)) != 0)) return JC_OK;
    if (count == INT_MAX / 2 + 1) return JC_ENOMEM;
    const size_t n = count ? 2 * (size_t)count : 64;
    void *p = realloc(*arr, n * size);
    if (!p) return JC_ENOMEM;
    *arr = p;
    return JC_OK;
}

static int arrays_event(void *ctx, const jc_Event *e)
{
    jc_Run *a = ctx;
    if (grow((void **)&a->events, a->event_count, sizeof *e)) return JC_ENOMEM;
    a->events[a->event_count++] = *e;
    return JC_OK;
}

static int arrays_sample(void *ctx, const jc_Sample *p)
{
    jc_Run *a = ctx;
    if (grow((void **)&a->samples, a->sample_count, sizeof *p)) return JC_ENOMEM;
    a->samples[a->sample_count++] = *p;
    return JC_OK;
}

jc_Recorder jc_run_recorder(jc_Run *arrays) { return (jc_Recorder){arrays, arrays_event, arrays_sample}; }

/* ---- recording: samples on a fixed grid and at events, events when complete ---- */

/* Events made but not yet pushed: the open flight's lift-off (or bounce)
 * and what follows it until the flight closes (a ramp end, a time limit). */
#define HELD_MAX 4

typedef struct {
    jc_Sim sim;
    jc_Event held[HELD_MAX];
    int held_count;
    int flight_event; /* index in held of the lift-off or bounce whose flight is under way, or -1 */
    int events_made;  /* events created (pushed or held): what max_events counts */
} machine;

/* A recorder's answer as a status: a value that is not one is a stop. */
static int recorder_status(int r)
{
    return r == JC_OK ? JC_OK : r >= JC_EINVAL && r <= JC_ESTOPPED ? r : JC_ESTOPPED;
}

/* The next fixed sample index after a sample at t (the 1e-9 keeps a sample
 * that lands a rounding error before a grid time from doubling it). */
static long long grid_index_after(double t, double dt)
{
    const double k = floor(t / dt + 1e-9) + 1.0;
    return k > 0.0 ? (long long)k : 0;
}

int jc_sim_sample(jc_Sim *sim, const jc_State *s, jc_Mode mode, double normal_N, double friction_N)
{
    if (!sim->rec->sample || sim->sample_limit_hit) return JC_OK;
    if (sim->samples_made >= sim->opt->max_samples) {
        sim->sample_limit_hit = 1; /* the machine ends the run with JC_END_SAMPLE_LIMIT */
        return JC_OK;
    }
    const jc_Model *m = sim->m;
    const double d = m->body.cm_offset_m;
    jc_Sample p;
    memset(&p, 0, sizeof p); /* padding too: a recorder may compare or hash samples bytewise */
    p.state = *s;
    p.mode = mode;
    p.cm_x_m = s->x_m + d * sin(s->theta_rad);
    p.cm_y_m = s->y_m + d * cos(s->theta_rad);
    p.normal_N = normal_N;
    p.friction_N = friction_N;
    p.slip_mps = mode == JC_MODE_FLIGHT ? 0.0 : s->vx_mps - m->body.radius_m * s->omega_radps;
    p.gap_m = mode == JC_MODE_FLIGHT ? jc_flight_gap(m, s) : 0.0;
    p.kinetic_J = jc_kinetic_energy(m, s);
    p.potential_J = jc_potential_energy(m, s);
    p.friction_loss_J = sim->friction_loss_J;
    p.impact_loss_J = sim->impact_loss_J;
    p.air_loss_J = sim->air_loss_J;
    p.rolling_resistance_loss_J = sim->rr_loss_J;
    const int st = recorder_status(sim->rec->sample(sim->rec->ctx, &p));
    if (st != JC_OK) return st;
    sim->samples_made++;
    sim->last_sample_t = fmax(sim->last_sample_t, s->t_s);
    if (sim->opt->sample_dt_s > 0.0) {
        const long long k = grid_index_after(s->t_s, sim->opt->sample_dt_s);
        if (k > sim->sample_k) sim->sample_k = k;
    }
    return JC_OK;
}

int jc_sim_sample_y(jc_Sim *sim, const jc_State *s, const double y[], jc_Mode mode, double normal_N,
                    double friction_N)
{
    const double saved[3] = {sim->friction_loss_J, sim->air_loss_J, sim->rr_loss_J};
    sim->friction_loss_J = y[JC_Y_FRICTION];
    sim->air_loss_J = y[JC_Y_AIR];
    sim->rr_loss_J = y[JC_Y_RR];
    const int st = jc_sim_sample(sim, s, mode, normal_N, friction_N);
    sim->friction_loss_J = saved[0];
    sim->air_loss_J = saved[1];
    sim->rr_loss_J = saved[2];
    return st;
}

int jc_sim_sample_due(jc_Sim *sim, double t_end, double *t)
{
    const double dt = sim->opt->sample_dt_s;
    if (!(dt > 0.0) || !sim->rec->sample || sim->sample_limit_hit) return 0;
    /* A grid time that an event sample already passed is skipped: fixed
     * sample times strictly increase and never repeat an earlier sample's. */
    while ((double)sim->sample_k * dt <= sim->last_sample_t) sim->sample_k++;
    const double next = (double)sim->sample_k * dt;
    if (!(next <= t_end)) return 0;
    *t = next;
    sim->sample_k++; /* taken: whatever time the caller's state rounds to, the next one is later */
    return 1;
}

/* Contact force in the current mode at the current state. */
static void contact_force(const jc_Sim *sim, double *normal, double *friction)
{
    *normal = *friction = 0.0;
    double thdd;
    jc_SlideForces f;
    const double w = sim->s.omega_radps;
    switch (sim->mode) {
    case JC_MODE_ROLLING:
        jc_roll_at(sim->m, sim->s.theta_rad, w, (w > 0.0) - (w < 0.0), &thdd, normal, friction, NULL);
        break;
    case JC_MODE_SLIDING:
        jc_slide_at(sim->m, &sim->s, sim->slip_dir, &f, NULL);
        *normal = f.normal_N;
        *friction = f.friction_N;
        break;
    case JC_MODE_FLIGHT: break;
    }
}

static int sample_now(jc_Sim *sim)
{
    double n, f;
    contact_force(sim, &n, &f);
    return jc_sim_sample(sim, &sim->s, sim->mode, n, f);
}

/* Pushes the held events that are complete: all of them, unless a flight
 * is open (its lift-off waits for close_flight, and later events wait
 * behind it to keep time order). */
static int push_held(machine *mc)
{
    if (mc->flight_event >= 0) return JC_OK;
    jc_Sim *sim = &mc->sim;
    for (int i = 0; i < mc->held_count; ++i) {
        if (sim->rec->event) {
            const int st = recorder_status(sim->rec->event(sim->rec->ctx, &mc->held[i]));
            if (st != JC_OK) {
                mc->held_count = 0;
                return st;
            }
        }
        sim->run->event_count++;
    }
    mc->held_count = 0;
    return JC_OK;
}

/* Makes an event at the current state; forces and slip are those just
 * before. It is held, not pushed, until the next event or the end of the
 * run (or, for a flight's start, until the flight closes): the caller may
 * still fill in its fields through *out until then. */
static int add_event(machine *mc, jc_EventKind kind, jc_Mode before, double normal, double friction,
                     double slip, jc_Event **out)
{
    int st = push_held(mc);
    if (st != JC_OK) return st;
    if (mc->held_count >= HELD_MAX) return JC_ELIMIT; /* a flight cannot hold this many events */
    jc_Event *e = &mc->held[mc->held_count++];
    mc->events_made++;
    memset(e, 0, sizeof *e);
    e->kind = kind;
    e->mode_before = before;
    e->mode_after = mc->sim.mode;
    e->state = mc->sim.s;
    e->slip_mps = slip;
    e->normal_N = normal;
    e->friction_N = friction;
    e->landing_x_m = NAN;
    if (out) *out = e;
    return JC_OK;
}

/* Completes the open flight's event at an impact or at the end of the run. */
static void close_flight(machine *mc, int landed)
{
    if (mc->flight_event < 0) return;
    jc_Event *e = &mc->held[mc->flight_event];
    e->flight_time_s = mc->sim.s.t_s - e->state.t_s;
    e->hop_height_m = mc->sim.hop_height_m;
    e->landing_x_m = landed ? mc->sim.s.x_m : NAN;
    mc->flight_event = -1;
}

/* Puts the body into the mode consistent with the forces at its contact state.
 * Returns the event kind that the change amounts to, or -1 for no change. */
static int enter_contact_mode(machine *mc, int allow_roll, jc_ModeChoice *choice_out)
{
    jc_Sim *sim = &mc->sim;
    int dir = sim->slip_dir;
    jc_ModeChoice c = jc_mode_choose(sim->m, &sim->s, allow_roll, &dir);
    *choice_out = c;
    const jc_Mode before = sim->mode;
    switch (c) {
    case CHOICE_ROLL:
    case CHOICE_REST:
        sim->s.vx_mps = sim->m->body.radius_m * sim->s.omega_radps;
        sim->s.vy_mps = 0.0;
        sim->mode = JC_MODE_ROLLING;
        return before == JC_MODE_SLIDING ? JC_EVENT_STICK : -1;
    case CHOICE_SLIDE: {
        const int reversal = before == JC_MODE_SLIDING && dir != sim->slip_dir;
        sim->mode = JC_MODE_SLIDING;
        sim->slip_dir = dir;
        if (before == JC_MODE_SLIDING) return reversal ? JC_EVENT_SLIP_REVERSAL : -1;
        return JC_EVENT_SLIP;
    }
    case CHOICE_FLY:
        sim->mode = JC_MODE_FLIGHT;
        return JC_EVENT_LIFTOFF;
    case CHOICE_PAINLEVE:
        return JC_EVENT_PAINLEVE;
    }
    return -1;
}

static void finish(machine *mc, jc_Termination why, const char *detail)
{
    jc_Sim *sim = &mc->sim;
    jc_Run *run = sim->run;
    close_flight(mc, 0);
    run->termination = why;
    snprintf(run->termination_detail, sizeof run->termination_detail, "%s", detail);
    run->final_state = sim->s;
    run->final_mode = sim->mode;
    run->micro_slips = sim->micro_slips;
    run->rocking_period_s = sim->periodic_period_s;
    jc_EnergyReport *e = &run->energy;
    e->kinetic_J = jc_kinetic_energy(sim->m, &sim->s);
    e->potential_J = jc_potential_energy(sim->m, &sim->s);
    e->friction_loss_J = sim->friction_loss_J;
    e->impact_loss_J = sim->impact_loss_J;
    e->air_loss_J = sim->air_loss_J;
    e->rolling_resistance_loss_J = sim->rr_loss_J;
    e->balance_error_J = e->kinetic_J + e->potential_J + e->friction_loss_J + e->impact_loss_J + e->air_loss_J +
                         e->rolling_resistance_loss_J - sim->energy0_J;
}

/* One touchdown (docs/physics.md §4): an impact only if the contact point
 * approaches; then a bounce if it leaves fast enough to open the gap, or
 * contact in the mode consistent with the forces. */
static int do_impact(machine *mc, int *from_liftoff, char *err, size_t err_len, int *stop)
{
    jc_Sim *sim = &mc->sim;
    const jc_Model *m = sim->m;
    const jc_State before = sim->s;
    const double k0 = jc_kinetic_energy(m, &before);
    const double slip = before.vx_mps - m->body.radius_m * before.omega_radps;
    jc_ImpactInput in;
    jc_impact_input(m, &before, &in);
    jc_ImpactResult res = {0};
    int bounce = 0;
    if (in.vn >= -JC_APPROACH_MPS) {
        /* No approach, no impulse. If the gap opens again (rate or free
         * acceleration >= 0), the rim only touched: the same flight goes on,
         * without an event. Otherwise it stays in contact. */
        if (in.vn > 0.0 || jc_free_gap_accel(m, &before) >= 0.0) {
            *from_liftoff = 2;
            return JC_OK;
        }
    } else {
        jc_impact_apply(m, &sim->s, m->setup.restitution, &res);
        /* A bounce needs the gap to open by more than the contact height:
         * the rebound rises against the contact point's free normal
         * acceleration -g cos a + d w^2 cos th (+ air), after the impulse. */
        const double acc = jc_free_gap_accel(m, &sim->s);
        const double rebound = res.rebound_speed_mps;
        bounce = !res.painleve && rebound > 0.0 &&
                 (acc >= 0.0 || rebound * rebound / (-2.0 * acc) > sim->opt->contact_height_m);
        if (!bounce && !res.painleve) {
            /* Too small a rebound to leave the incline: a plastic impact, then contact. */
            sim->s = before;
            jc_impact_apply_law(m, &sim->s, m->setup.impact_law, 0.0, &res);
        }
    }
    close_flight(mc, 1);
    jc_Event *e;
    if (res.painleve) {
        sim->s = before;
        int st = add_event(mc, JC_EVENT_PAINLEVE, JC_MODE_FLIGHT, 0.0, 0.0, slip, &e);
        if (st) return jc_fail(err, err_len, st, "out of memory for events");
        finish(mc, JC_END_PAINLEVE, "impact with friction has no consistent impulse (Painleve)");
        *stop = 1;
        return JC_OK;
    }
    if (!bounce) sim->s.vy_mps = 0.0; /* on the incline: the normal velocity of C is 0 */
    const double gain = jc_kinetic_energy(m, &sim->s) - k0;
    sim->impact_loss_J -= gain;
    if (gain > 1e-12 * k0) {
        sim->run->energy_gaining_impacts++;
        sim->run->largest_impact_gain_J = fmax(sim->run->largest_impact_gain_J, gain);
    }
    jc_ModeChoice choice = CHOICE_FLY;
    if (!bounce) {
        sim->mode = JC_MODE_FLIGHT;
        enter_contact_mode(mc, 1, &choice);
        if (choice == CHOICE_FLY) {
            /* No rebound, but the free gap acceleration opens the gap: it
             * leaves as from a lift-off (the gap grows from zero). */
            sim->mode = JC_MODE_FLIGHT;
            *from_liftoff = 1;
        }
    }
    const int st = add_event(mc, bounce || choice == CHOICE_FLY ? JC_EVENT_BOUNCE : JC_EVENT_TOUCHDOWN,
                             JC_MODE_FLIGHT, 0.0, 0.0, slip, &e);
    if (st) return jc_fail(err, err_len, st, "out of memory for events");
    e->impact_speed_mps = res.approach_speed_mps;
    e->impulse_normal_Ns = res.impulse_normal_Ns;
    e->impulse_tangent_Ns = res.impulse_tangent_Ns;
    if (sim->mode == JC_MODE_FLIGHT) mc->flight_event = mc->held_count - 1;
    if (choice == CHOICE_PAINLEVE) {
        finish(mc, JC_END_PAINLEVE, "after an impact, no contact mode is consistent (Painleve)");
        *stop = 1;
    } else if (choice == CHOICE_REST) {
        finish(mc, JC_END_REST, "came to rest at an impact");
        *stop = 1;
    }
    return JC_OK;
}

static int run_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len)
{
    switch (sim->mode) {
    case JC_MODE_ROLLING: return jc_roll_phase(sim, end, err, err_len);
    case JC_MODE_SLIDING: return jc_slide_phase(sim, end, err, err_len);
    case JC_MODE_FLIGHT: return jc_flight_phase(sim, from_liftoff, end, err, err_len);
    }
    return JC_EINVAL;
}

static int alloc_workspaces(jc_Sim *sim)
{
    sim->quad = gsl_integration_workspace_alloc(200);
    return sim->quad ? JC_OK : JC_ENOMEM;
}

static void free_workspaces(jc_Sim *sim)
{
    if (sim->quad) gsl_integration_workspace_free(sim->quad);
}

/* The mode machine proper. Returns a status; sets *stop when the run ended. */
static int step_machine(machine *mc, int *from_liftoff, char *err, size_t err_len, int *stop)
{
    jc_Sim *sim = &mc->sim;
    double n0, f0;
    jc_PhaseEnd end;
    int st = run_phase(sim, *from_liftoff, &end, err, err_len);
    if (st != JC_OK) return st;
    *from_liftoff = 0;
    const jc_Mode before = sim->mode;
    contact_force(sim, &n0, &f0);
    const double slip = before == JC_MODE_FLIGHT ? 0.0 : sim->s.vx_mps - sim->m->body.radius_m * sim->s.omega_radps;
    jc_Event *e;
    switch (end) {
    case PHASE_TOUCHDOWN: return do_impact(mc, from_liftoff, err, err_len, stop);
    case PHASE_LIFTOFF:
        sim->mode = JC_MODE_FLIGHT;
        if ((st = add_event(mc, JC_EVENT_LIFTOFF, before, n0, f0, slip, &e))) break;
        mc->flight_event = mc->held_count - 1;
        *from_liftoff = 1;
        return JC_OK;
    case PHASE_SLIP:
    case PHASE_SLIP_ZERO: {
        jc_ModeChoice choice;
        const int kind = enter_contact_mode(mc, end != PHASE_SLIP, &choice);
        if (kind == JC_EVENT_PAINLEVE) {
            if ((st = add_event(mc, JC_EVENT_PAINLEVE, before, n0, f0, slip, &e))) break;
            finish(mc, JC_END_PAINLEVE, "no contact mode is consistent with the forces (Painleve)");
            *stop = 1;
            return JC_OK;
        }
        if (kind >= 0 && (st = add_event(mc, (jc_EventKind)kind, before, n0, f0, slip, &e))) break;
        if (kind == JC_EVENT_LIFTOFF) {
            mc->flight_event = mc->held_count - 1;
            *from_liftoff = 1;
        }
        if (choice == CHOICE_REST) {
            finish(mc, JC_END_REST, "at rest in equilibrium");
            *stop = 1;
        }
        return JC_OK;
    }
    case PHASE_RAMP_END:
    case PHASE_RAMP_TOP:
        if ((st = add_event(mc, end == PHASE_RAMP_END ? JC_EVENT_RAMP_END : JC_EVENT_RAMP_TOP, before, n0, f0,
                            slip, &e)))
            break;
        finish(mc, end == PHASE_RAMP_END ? JC_END_RAMP_END : JC_END_RAMP_TOP,
               end == PHASE_RAMP_END ? "the centre reached the lower end of the ramp"
                                     : "the centre went uphill past the start");
        *stop = 1;
        return JC_OK;
    case PHASE_PAINLEVE:
        if ((st = add_event(mc, JC_EVENT_PAINLEVE, before, n0, f0, slip, &e))) break;
        finish(mc, JC_END_PAINLEVE,
               "Painleve: sliding with D = 1 + M d sin(th) k / I_G -> 0, the normal force grows without bound");
        *stop = 1;
        return JC_OK;
    case PHASE_TIME_LIMIT:
        if (sim->periodic_period_s > 0.0) {
            char detail[160];
            snprintf(detail, sizeof detail,
                     "simulated time reached the limit; rocks for ever: rolls between th = %.6f and %.6f rad, "
                     "period %.6f s",
                     sim->periodic_th_lo_rad, sim->periodic_th_hi_rad, sim->periodic_period_s);
            finish(mc, JC_END_TIME_LIMIT, detail);
        } else {
            finish(mc, JC_END_TIME_LIMIT, "simulated time reached the limit");
        }
        *stop = 1;
        return JC_OK;
    case PHASE_AT_REST:
        finish(mc, JC_END_REST, jc_model_has_resistance(sim->m) ? "came to rest: rolling resistance holds it"
                                                                  : "at rest: rocking by less than 1 nm");
        *stop = 1;
        return JC_OK;
    case PHASE_STEP_LIMIT: finish(mc, JC_END_STEP_LIMIT, "a phase reached its step bound"); *stop = 1; return JC_OK;
    }
    return st ? jc_fail(err, err_len, st, "out of memory for events") : JC_OK;
}

/* The message for a run stopped while recording; the phases' own say "out
 * of memory", which is right only for JC_ENOMEM. */
static int record_status(int st, char *err, size_t err_len)
{
    if (st == JC_ESTOPPED) return jc_fail(err, err_len, st, "stopped by the recorder");
    if (st == JC_ENOMEM) return jc_fail(err, err_len, st, "out of memory");
    return st;
}

int jc_simulate_stream(const jc_Model *model, const jc_SimOptions *options, const jc_Recorder *rec,
                       jc_Run *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    int st = jc_sim_options_validate(options, err, err_len);
    if (st != JC_OK) return st;
    const jc_Recorder none = {NULL, NULL, NULL};
    machine mc;
    memset(&mc, 0, sizeof mc);
    mc.flight_event = -1;
    jc_Sim *sim = &mc.sim;
    sim->m = model;
    sim->opt = options;
    sim->run = out;
    sim->rec = rec ? rec : &none;
    sim->last_sample_t = -INFINITY;
    const double r = model->body.radius_m;
    sim->s = (jc_State){0.0, 0.0, r, r * model->setup.omega0_radps, 0.0, model->setup.theta0_rad,
                        model->setup.omega0_radps};
    sim->energy0_J = jc_kinetic_energy(model, &sim->s) + jc_potential_energy(model, &sim->s);
    if ((st = alloc_workspaces(sim)) != JC_OK) {
        free_workspaces(sim);
        return jc_fail(err, err_len, st, "out of memory for the integrator");
    }

    /* The start: the mode consistent with the forces, which need not be rolling. */
    int stop = 0, from_liftoff = 0;
    sim->mode = JC_MODE_ROLLING;
    jc_ModeChoice choice;
    const int kind = enter_contact_mode(&mc, 1, &choice);
    if (kind == JC_EVENT_PAINLEVE) {
        st = add_event(&mc, JC_EVENT_PAINLEVE, JC_MODE_ROLLING, 0.0, 0.0, 0.0, NULL);
        finish(&mc, JC_END_PAINLEVE, "no contact mode is consistent at the start (Painleve)");
        stop = 1;
    } else {
        /* A start that cannot roll: the event shows the rolling forces that rule it out. */
        double thdd, n_roll, f_roll;
        jc_roll_at(model, sim->s.theta_rad, sim->s.omega_radps, model->setup.omega0_radps >= 0.0 ? 1 : -1, &thdd,
                   &n_roll, &f_roll, NULL);
        if (kind >= 0) st = add_event(&mc, (jc_EventKind)kind, JC_MODE_ROLLING, n_roll, f_roll, 0.0, NULL);
        if (kind == JC_EVENT_LIFTOFF) {
            mc.flight_event = mc.held_count - 1;
            from_liftoff = 1;
        }
        if (choice == CHOICE_REST) {
            finish(&mc, JC_END_REST, "at rest in equilibrium at the start");
            stop = 1;
        }
    }
    if (st == JC_OK) st = sample_now(sim);
    /* Every phase ends in an event or a turning point of rolling; a phase
     * count far beyond the event limit means the machine is not advancing. */
    const long max_phases = 4L * options->max_events + 1000;
    for (long phase = 0; st == JC_OK && !stop; ++phase) {
        if (mc.events_made >= options->max_events) {
            finish(&mc, JC_END_EVENT_LIMIT, "the event limit was reached");
            break;
        }
        if (sim->sample_limit_hit) {
            finish(&mc, JC_END_SAMPLE_LIMIT, "the sample limit was reached");
            break;
        }
        if (phase >= max_phases) {
            finish(&mc, JC_END_STEP_LIMIT, "the mode machine stopped advancing (phase bound reached)");
            break;
        }
        const int events_before = mc.events_made;
        st = step_machine(&mc, &from_liftoff, err, err_len, &stop);
        if (st == JC_OK && mc.events_made > events_before) st = sample_now(sim);
    }
    if (st == JC_OK && (sim->samples_made == 0 || sim->last_sample_t < sim->s.t_s)) st = sample_now(sim);
    if (st == JC_OK) {
        mc.flight_event = -1; /* finish closed it; an error exit leaves it unpushed */
        st = push_held(&mc);
    }
    out->sample_count = sim->samples_made;
    free_workspaces(sim);
    return record_status(st, err, err_len);
}

int jc_simulate(const jc_Model *model, const jc_SimOptions *options, jc_Run *out, char *err, size_t err_len)
{
    jc_Run arrays = {0};
    const jc_Recorder rec = jc_run_recorder(&arrays);
    const int st = jc_simulate_stream(model, options, &rec, out, err, err_len);
    /* Handed over also after an error: the caller frees them with jc_run_free. */
    out->events = arrays.events;
    out->event_count = arrays.event_count;
    out->samples = arrays.samples;
    out->sample_count = arrays.sample_count;
    return st;
}
