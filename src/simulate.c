/*
 * The driver: the mode machine. It chooses the mode consistent with the
 * forces (mode.c) at the start, after every event and after every impact
 * (impact.c), and calls the phase of that mode (rolling_phase.c,
 * sliding.c, flight.c); phases push samples into the recording (record.c)
 * and return how they ended. Every loop is bounded: by simulated time, by
 * the event count, and inside each phase by a step bound; every run ends
 * with a reason.
 */
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Contact force in the current mode at the current state. */
static void contact_force(const jc_Sim *sim, double *normal, double *friction)
{
    *normal = *friction = 0.0;
    double thdd;
    jc_SlidingForces f;
    const double w = sim->s.omega_radps;
    switch (sim->mode) {
    case JC_MODE_ROLLING:
        jc_rolling_at(sim->m, sim->s.theta_rad, w, (w > 0.0) - (w < 0.0), &thdd, normal, friction);
        break;
    case JC_MODE_SLIDING:
        jc_sliding_at(sim->m, &sim->s, sim->slip_dir, &f, NULL);
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
    const double gap = sim->mode == JC_MODE_FLIGHT ? jc_flight_gap(sim->m, &sim->s) : 0.0;
    return jc_record_sample(sim, &sim->s, sim->mode, n, f, gap);
}

/* Puts the body into the mode consistent with the forces at its contact state.
 * Returns the event kind that the change amounts to, or -1 for no change. */
static int enter_contact_mode(jc_Sim *sim, int allow_roll, jc_ModeChoice *choice_out)
{
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

static void finish(jc_Sim *sim, jc_Termination why, const char *detail)
{
    jc_Run *run = sim->run;
    jc_record_close_flight(sim, 0);
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
static int do_impact(jc_Sim *sim, int *from_liftoff, char *err, size_t err_len, int *stop)
{
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
    jc_record_close_flight(sim, 1);
    jc_Event *e;
    if (res.painleve) {
        sim->s = before;
        int st = jc_record_event(sim, JC_EVENT_PAINLEVE, JC_MODE_FLIGHT, 0.0, 0.0, slip, &e);
        if (st) return jc_fail(err, err_len, st, "out of memory for events");
        finish(sim, JC_END_PAINLEVE, "impact with friction has no consistent impulse (Painleve)");
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
        enter_contact_mode(sim, 1, &choice);
        if (choice == CHOICE_FLY) {
            /* No rebound, but the free gap acceleration opens the gap: it
             * leaves as from a lift-off (the gap grows from zero). */
            sim->mode = JC_MODE_FLIGHT;
            *from_liftoff = 1;
        }
    }
    const int st = jc_record_event(sim, bounce || choice == CHOICE_FLY ? JC_EVENT_BOUNCE : JC_EVENT_TOUCHDOWN,
                             JC_MODE_FLIGHT, 0.0, 0.0, slip, &e);
    if (st) return jc_fail(err, err_len, st, "out of memory for events");
    e->impact_speed_mps = res.approach_speed_mps;
    e->impulse_normal_Ns = res.impulse_normal_Ns;
    e->impulse_tangent_Ns = res.impulse_tangent_Ns;
    if (sim->mode == JC_MODE_FLIGHT) jc_record_open_flight(sim);
    if (choice == CHOICE_PAINLEVE) {
        finish(sim, JC_END_PAINLEVE, "after an impact, no contact mode is consistent (Painleve)");
        *stop = 1;
    } else if (choice == CHOICE_REST) {
        finish(sim, JC_END_REST, "came to rest at an impact");
        *stop = 1;
    }
    return JC_OK;
}

static int run_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len)
{
    switch (sim->mode) {
    case JC_MODE_ROLLING: return jc_rolling_phase(sim, end, err, err_len);
    case JC_MODE_SLIDING: return jc_sliding_phase(sim, end, err, err_len);
    case JC_MODE_FLIGHT: return jc_flight_phase(sim, from_liftoff, end, err, err_len);
    }
    return JC_EINVAL;
}

/* The mode machine proper. Returns a status; sets *stop when the run ended. */
static int step_machine(jc_Sim *sim, int *from_liftoff, char *err, size_t err_len, int *stop)
{
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
    case PHASE_TOUCHDOWN: return do_impact(sim, from_liftoff, err, err_len, stop);
    case PHASE_LIFTOFF:
        sim->mode = JC_MODE_FLIGHT;
        if ((st = jc_record_event(sim, JC_EVENT_LIFTOFF, before, n0, f0, slip, &e))) break;
        jc_record_open_flight(sim);
        *from_liftoff = 1;
        return JC_OK;
    case PHASE_SLIP:
    case PHASE_SLIP_ZERO: {
        jc_ModeChoice choice;
        const int kind = enter_contact_mode(sim, end != PHASE_SLIP, &choice);
        if (kind == JC_EVENT_PAINLEVE) {
            if ((st = jc_record_event(sim, JC_EVENT_PAINLEVE, before, n0, f0, slip, &e))) break;
            finish(sim, JC_END_PAINLEVE, "no contact mode is consistent with the forces (Painleve)");
            *stop = 1;
            return JC_OK;
        }
        if (kind >= 0 && (st = jc_record_event(sim, (jc_EventKind)kind, before, n0, f0, slip, &e))) break;
        if (kind == JC_EVENT_LIFTOFF) {
            jc_record_open_flight(sim);
            *from_liftoff = 1;
        }
        if (choice == CHOICE_REST) {
            finish(sim, JC_END_REST, "at rest in equilibrium");
            *stop = 1;
        }
        return JC_OK;
    }
    case PHASE_RAMP_END:
    case PHASE_RAMP_TOP:
        if ((st = jc_record_event(sim, end == PHASE_RAMP_END ? JC_EVENT_RAMP_END : JC_EVENT_RAMP_TOP, before, n0, f0,
                            slip, &e)))
            break;
        finish(sim, end == PHASE_RAMP_END ? JC_END_RAMP_END : JC_END_RAMP_TOP,
               end == PHASE_RAMP_END ? "the centre reached the lower end of the ramp"
                                     : "the centre went uphill past the start");
        *stop = 1;
        return JC_OK;
    case PHASE_PAINLEVE:
        if ((st = jc_record_event(sim, JC_EVENT_PAINLEVE, before, n0, f0, slip, &e))) break;
        finish(sim, JC_END_PAINLEVE,
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
            finish(sim, JC_END_TIME_LIMIT, detail);
        } else {
            finish(sim, JC_END_TIME_LIMIT, "simulated time reached the limit");
        }
        *stop = 1;
        return JC_OK;
    case PHASE_AT_REST:
        finish(sim, JC_END_REST, jc_model_has_resistance(sim->m) ? "came to rest: rolling resistance holds it"
                                                                  : "at rest: rocking by less than 1 nm");
        *stop = 1;
        return JC_OK;
    case PHASE_STEP_LIMIT: finish(sim, JC_END_STEP_LIMIT, "a phase reached its step bound"); *stop = 1; return JC_OK;
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

/* The run's first mode, and its first event when the start is not rolling
 * (the event shows the rolling forces that rule rolling out). */
static int start_mode(jc_Sim *sim, int *from_liftoff, int *stop)
{
    const jc_Model *model = sim->m;
    const double r = model->body.radius_m;
    if (sim->s.y_m > r || sim->s.vy_mps > 0.0) {
        sim->mode = JC_MODE_FLIGHT; /* above the incline, or leaving it */
        sim->hop_height_m = sim->s.y_m - r;
        return JC_OK;
    }
    int st = JC_OK;
    sim->mode = JC_MODE_ROLLING;
    jc_ModeChoice choice;
    const int kind = enter_contact_mode(sim, 1, &choice);
    if (kind == JC_EVENT_PAINLEVE) {
        st = jc_record_event(sim, JC_EVENT_PAINLEVE, JC_MODE_ROLLING, 0.0, 0.0, 0.0, NULL);
        finish(sim, JC_END_PAINLEVE, "no contact mode is consistent at the start (Painleve)");
        *stop = 1;
        return st;
    }
    double thdd, n_roll, f_roll;
    const double w = sim->s.omega_radps;
    jc_rolling_at(model, sim->s.theta_rad, w, w > 0.0 || (w == 0.0 && model->setup.omega0_radps >= 0.0) ? 1 : -1, &thdd,
                  &n_roll, &f_roll);
    if (kind >= 0) st = jc_record_event(sim, (jc_EventKind)kind, JC_MODE_ROLLING, n_roll, f_roll, 0.0, NULL);
    if (kind == JC_EVENT_LIFTOFF) {
        jc_record_open_flight(sim);
        *from_liftoff = 1;
    }
    if (choice == CHOICE_REST) {
        finish(sim, JC_END_REST, "at rest in equilibrium at the start");
        *stop = 1;
    }
    return st;
}

/* Phases until a termination: every phase ends in an event or a turning
 * point of rolling; a phase count far beyond the event limit means the
 * machine is not advancing. */
static int run_machine(jc_Sim *sim, char *err, size_t err_len)
{
    const jc_SimOptions *options = sim->opt;
    int stop = 0, from_liftoff = 0;
    int st = start_mode(sim, &from_liftoff, &stop);
    if (st == JC_OK) st = sample_now(sim);
    const long max_phases = 4L * options->max_events + 1000;
    for (long phase = 0; st == JC_OK && !stop; ++phase) {
        if (sim->trace.events_made >= options->max_events) {
            finish(sim, JC_END_EVENT_LIMIT, "the event limit was reached");
            break;
        }
        if (sim->trace.sample_limit_hit) {
            finish(sim, JC_END_SAMPLE_LIMIT, "the sample limit was reached");
            break;
        }
        if (phase >= max_phases) {
            finish(sim, JC_END_STEP_LIMIT, "the mode machine stopped advancing (phase bound reached)");
            break;
        }
        const int events_before = sim->trace.events_made;
        st = step_machine(sim, &from_liftoff, err, err_len, &stop);
        if (st == JC_OK && sim->trace.events_made > events_before) st = sample_now(sim);
    }
    if (st == JC_OK && (sim->trace.samples_made == 0 || sim->trace.last_sample_t < sim->s.t_s)) st = sample_now(sim);
    if (st == JC_OK) {
        sim->trace.flight_event = -1; /* finish closed it; an error exit leaves it unpushed */
        st = jc_record_push(sim);
    }
    sim->run->sample_count = sim->trace.samples_made;
    return record_status(st, err, err_len);
}

jc_State jc_start_state(const jc_Model *model)
{
    const double r = model->body.radius_m, w0 = model->setup.omega0_radps;
    return (jc_State){0.0, 0.0, r, r * w0, 0.0, model->setup.theta0_rad, w0};
}

int jc_start_validate(const jc_Model *model, const jc_State *s, const jc_SimOptions *options, char *err,
                      size_t err_len)
{
    const double r = model->body.radius_m, L = model->setup.ramp_length_m;
    const double v[7] = {s->t_s, s->x_m, s->y_m, s->vx_mps, s->vy_mps, s->theta_rad, s->omega_radps};
    static const char *const names[7] = {"time", "x", "y", "vx", "vy", "angle", "angular velocity"};
    for (int i = 0; i < 7; ++i)
        if (!isfinite(v[i])) return jc_fail(err, err_len, JC_EINVAL, "start %s %g is not a finite number", names[i], v[i]);
    if (!(s->t_s >= 0.0 && s->t_s < options->t_max_s))
        return jc_fail(err, err_len, JC_EINVAL, "start time %g s is out of range (allowed: [0, %g) s, the time limit)",
                       s->t_s, options->t_max_s);
    if (!(s->x_m >= 0.0 && s->x_m <= L))
        return jc_fail(err, err_len, JC_EINVAL, "start x %g m is off the ramp (allowed: [0, %g] m)", s->x_m, L);
    if (!(s->y_m >= r))
        return jc_fail(err, err_len, JC_EINVAL, "start height y %g m is below the incline (allowed: >= r = %g m)",
                       s->y_m, r);
    if (!(fabs(s->theta_rad) <= 1e4 && fabs(s->omega_radps) <= 1e4 && hypot(s->vx_mps, s->vy_mps) <= 1e4 * r))
        return jc_fail(err, err_len, JC_EINVAL,
                       "start angle %g rad, angular velocity %g rad/s or speed %g m/s is out of range (allowed: "
                       "|angle| <= 1e4 rad, |w| <= 1e4 rad/s, speed <= 1e4 r/s = %g m/s)",
                       s->theta_rad, s->omega_radps, hypot(s->vx_mps, s->vy_mps), 1e4 * r);
    if (s->y_m == r && s->vy_mps < 0.0)
        return jc_fail(err, err_len, JC_EINVAL,
                       "start vy %g m/s moves into the incline from contact (allowed: vy >= 0 at y = r)", s->vy_mps);
    return JC_OK;
}

int jc_simulate_from(const jc_Model *model, const jc_State *start, const jc_SimOptions *options,
                     const jc_Recorder *rec, jc_Workspace *ws, jc_Run *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    int st = jc_sim_options_validate(options, err, err_len);
    if (st == JC_OK) st = jc_start_validate(model, start, options, err, err_len);
    if (st != JC_OK) return st;
    jc_Workspace *own = NULL;
    if (!ws && !(ws = own = jc_workspace_new()))
        return jc_fail(err, err_len, JC_ENOMEM, "out of memory for the run's workspace");
    static const jc_Recorder none = {NULL, NULL, NULL};
    jc_Sim sim = {
        .m = model,
        .opt = options,
        .run = out,
        .s = *start,
        .trace = {.rec = rec ? rec : &none, .last_sample_t = -INFINITY, .flight_event = -1},
        .ws = ws,
    };
    sim.energy0_J = jc_kinetic_energy(model, &sim.s) + jc_potential_energy(model, &sim.s);
    st = run_machine(&sim, err, err_len);
    jc_workspace_free(own);
    return st;
}

int jc_simulate_stream(const jc_Model *model, const jc_SimOptions *options, const jc_Recorder *rec,
                       jc_Run *out, char *err, size_t err_len)
{
    const jc_State start = jc_start_state(model);
    return jc_simulate_from(model, &start, options, rec, NULL, out, err, err_len);
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
