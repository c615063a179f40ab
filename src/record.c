/*
 * Recording: what a run pushes to its recorder (jc_Recorder). Samples fall
 * on a fixed grid (k * dt by an integer counter) and at events; an event is
 * held until it is complete (a lift-off until its flight has ended) and
 * pushed then, never changed after. The phases and the driver push here;
 * nothing here calls back into them.
 */
#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* ---- samples ---- */

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

int jc_record_sample(jc_Sim *sim, const jc_State *s, jc_Mode mode, double normal_N, double friction_N,
                     double gap_m)
{
    if (!sim->trace.rec->sample || sim->trace.sample_limit_hit) return JC_OK;
    if (sim->trace.samples_made >= sim->opt->max_samples) {
        sim->trace.sample_limit_hit = 1; /* the machine ends the run with JC_END_SAMPLE_LIMIT */
        return JC_OK;
    }
    const jc_Model *m = sim->m;
    const double d = m->body.cm_offset_m;
    jc_Sample p;
    memset(&p, 0, sizeof p); /* padding too: a recorder may compare or hash samples bytewise */
    p.state = *s;
    p.mode = mode;
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    p.cm_x_m = s->x_m + d * sn;
    p.cm_y_m = s->y_m + d * cs;
    p.normal_N = normal_N;
    p.friction_N = friction_N;
    p.slip_mps = mode == JC_MODE_FLIGHT ? 0.0 : s->vx_mps - m->body.radius_m * s->omega_radps;
    p.gap_m = mode == JC_MODE_FLIGHT ? gap_m : 0.0;
    /* the sample's own sine and cosine, not three more */
    jc_energies_sc(m, s, sn, cs, &p.kinetic_J, &p.potential_J);
    p.friction_loss_J = sim->friction_loss_J;
    p.impact_loss_J = sim->impact_loss_J;
    p.air_loss_J = sim->air_loss_J;
    p.rolling_resistance_loss_J = sim->rr_loss_J;
    const int st = recorder_status(sim->trace.rec->sample(sim->trace.rec->ctx, &p));
    if (st != JC_OK) return st;
    sim->trace.samples_made++;
    sim->trace.last_sample_t = fmax(sim->trace.last_sample_t, s->t_s);
    if (sim->opt->sample_dt_s > 0.0) {
        const long long k = grid_index_after(s->t_s, sim->opt->sample_dt_s);
        if (k > sim->trace.sample_k) sim->trace.sample_k = k;
    }
    return JC_OK;
}

int jc_record_sample_y(jc_Sim *sim, const jc_State *s, const double y[], jc_Mode mode, double normal_N,
                       double friction_N, double gap_m)
{
    const double saved[3] = {sim->friction_loss_J, sim->air_loss_J, sim->rr_loss_J};
    sim->friction_loss_J = y[JC_Y_FRICTION];
    sim->air_loss_J = y[JC_Y_AIR];
    sim->rr_loss_J = y[JC_Y_RR];
    const int st = jc_record_sample(sim, s, mode, normal_N, friction_N, gap_m);
    sim->friction_loss_J = saved[0];
    sim->air_loss_J = saved[1];
    sim->rr_loss_J = saved[2];
    return st;
}

int jc_record_sample_due(jc_Sim *sim, double t_end, double *t)
{
    const double dt = sim->opt->sample_dt_s;
    if (!(dt > 0.0) || !sim->trace.rec->sample || sim->trace.sample_limit_hit) return 0;
    /* A grid time that an event sample already passed is skipped: fixed
     * sample times strictly increase and never repeat an earlier sample's. */
    while ((double)sim->trace.sample_k * dt <= sim->trace.last_sample_t) sim->trace.sample_k++;
    const double next = (double)sim->trace.sample_k * dt;
    if (!(next <= t_end)) return 0;
    *t = next;
    sim->trace.sample_k++; /* taken: whatever time the caller's state rounds to, the next one is later */
    return 1;
}

/* ---- events ---- */

/* Pushes the held events that are complete: all of them, unless a flight
 * is open (its lift-off waits for close_flight, and later events wait
 * behind it to keep time order). */
int jc_record_push(jc_Sim *sim)
{
    jc_Trace *tr = &sim->trace;
    if (tr->flight_event >= 0) return JC_OK;
    for (int i = 0; i < tr->held_count; ++i) {
        if (tr->rec->event) {
            const int st = recorder_status(tr->rec->event(tr->rec->ctx, &tr->held[i]));
            if (st != JC_OK) {
                tr->held_count = 0;
                return st;
            }
        }
        sim->run->event_count++;
    }
    tr->held_count = 0;
    return JC_OK;
}

/* Makes an event at the current state; forces and slip are those just
 * before. It is held, not pushed, until the next event or the end of the
 * run (or, for a flight's start, until the flight closes): the caller may
 * still fill in its fields through *out until then. */
int jc_record_event(jc_Sim *sim, jc_EventKind kind, jc_Mode before, double normal, double friction,
                     double slip, jc_Event **out)
{
    jc_Trace *tr = &sim->trace;
    int st = jc_record_push(sim);
    if (st != JC_OK) return st;
    if (tr->held_count >= JC_HELD_MAX) return JC_ELIMIT; /* a flight cannot hold this many events */
    jc_Event *e = &tr->held[tr->held_count++];
    tr->events_made++;
    memset(e, 0, sizeof *e);
    e->kind = kind;
    e->mode_before = before;
    e->mode_after = sim->mode;
    e->state = sim->s;
    e->slip_mps = slip;
    e->normal_N = normal;
    e->friction_N = friction;
    e->landing_x_m = NAN;
    if (out) *out = e;
    return JC_OK;
}

void jc_record_open_flight(jc_Sim *sim) { sim->trace.flight_event = sim->trace.held_count - 1; }

/* Completes the open flight's event at an impact or at the end of the run:
 * its time, largest gap and landing place. */
void jc_record_close_flight(jc_Sim *sim, int landed)
{
    jc_Trace *tr = &sim->trace;
    if (tr->flight_event < 0) return;
    jc_Event *e = &tr->held[tr->flight_event];
    e->flight_time_s = sim->s.t_s - e->state.t_s;
    e->hop_height_m = sim->hop_height_m;
    e->landing_x_m = landed ? sim->s.x_m : NAN;
    tr->flight_event = -1;
}
