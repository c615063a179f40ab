/*
 * What a run is and reports: its options, the names of modes, events and
 * terminations, the energies of a state, the summary of its hops.
 */
#include "internal.h"

#include <math.h>
#include <stdlib.h>

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

/* K and M g h(G) of a state whose th has sine sn and cosine cs. */
static double kinetic_sc(const jc_Model *m, const jc_State *s, double sn, double cs)
{
    const double d = m->body.cm_offset_m, w = s->omega_radps;
    const double vgx = s->vx_mps + d * cs * w, vgy = s->vy_mps - d * sn * w;
    return 0.5 * m->body.mass_kg * (vgx * vgx + vgy * vgy) + 0.5 * m->body.inertia_g_kgm2 * w * w;
}

static double potential_abs_sc(const jc_Model *m, const jc_State *s, double sn, double cs)
{
    const double d = m->body.cm_offset_m;
    const double xg = s->x_m + d * sn, yg = s->y_m + d * cs;
    return m->body.mass_kg * m->setup.gravity_mps2 * (yg * m->cos_incline - xg * m->sin_incline);
}

static double potential_start(const jc_Model *m)
{
    const jc_State start = {.y_m = m->body.radius_m, .theta_rad = m->setup.theta0_rad};
    double sn, cs;
    jc_sincos(start.theta_rad, &sn, &cs);
    return potential_abs_sc(m, &start, sn, cs);
}

double jc_kinetic_energy(const jc_Model *m, const jc_State *s)
{
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    return kinetic_sc(m, s, sn, cs);
}

double jc_potential_energy(const jc_Model *m, const jc_State *s)
{
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    return potential_abs_sc(m, s, sn, cs) - potential_start(m);
}

void jc_energies_sc(const jc_Model *m, const jc_State *s, double sn, double cs, double *kinetic_J,
                    double *potential_J)
{
    *kinetic_J = kinetic_sc(m, s, sn, cs);
    *potential_J = potential_abs_sc(m, s, sn, cs) - potential_start(m);
}

/* ---- summary ---- */

void jc_summary_init(jc_RunSummary *out)
{
    *out = (jc_RunSummary){.first_liftoff = -1, .largest_hop = -1, .first_event = -1,
                           .first_event_kind = JC_EVENT_COUNT, .first_slip = -1};
}

void jc_summary_add(jc_RunSummary *out, const jc_Event *e, int index)
{
    if (out->first_event < 0) {
        out->first_event = index;
        out->first_event_kind = e->kind;
    }
    if (e->kind == JC_EVENT_SLIP && out->first_slip < 0) {
        out->first_slip = index;
        out->first_slip_state = e->state;
    }
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
