/*
 * The streaming API (jc_simulate_stream, jc_Recorder, jc_summary_add): the
 * same events and samples as the in-memory jc_simulate, bit for bit; every
 * event final when it is pushed (a lift-off arrives with its flight's
 * length); sample times strictly increasing on the fixed grid k * dt; a
 * recorder that stops the run; the sample limit named as the termination.
 */
#include "sim_common.h"

#include "../stream_setups.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>

typedef struct {
    jc_Event *events;
    jc_Sample *samples;
    int n_events, n_samples, cap_events, cap_samples;
    int stop_after; /* stop with JC_ESTOPPED after this many events; 0: never */
    int open_flights; /* flight-starting events pushed with flight_time_s <= 0 */
    double last_t;
    int sample_order_broken;
    jc_RunSummary summary;
} collector;

/* Room for one more element of *arr (count used, *cap allocated). */
static int grow(void **arr, int count, int *cap, size_t size)
{
    if (count < *cap) return JC_OK;
    const int n = *cap ? 2 * *cap : 64;
    void *p = realloc(*arr, size * (size_t)n);
    if (!p) return JC_ENOMEM;
    *arr = p;
    *cap = n;
    return JC_OK;
}

static int on_event(void *ctx, const jc_Event *e)
{
    collector *c = ctx;
    if (grow((void **)&c->events, c->n_events, &c->cap_events, sizeof *e)) return JC_ENOMEM;
    const int flies = e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT);
    if (flies && !(e->flight_time_s > 0.0)) c->open_flights++;
    jc_summary_add(&c->summary, e, c->n_events);
    c->events[c->n_events++] = *e;
    return c->stop_after && c->n_events >= c->stop_after ? JC_ESTOPPED : JC_OK;
}

static int on_sample(void *ctx, const jc_Sample *s)
{
    collector *c = ctx;
    if (grow((void **)&c->samples, c->n_samples, &c->cap_samples, sizeof *s)) return JC_ENOMEM;
    if (c->n_samples && !(s->state.t_s >= c->last_t)) c->sample_order_broken = 1;
    c->last_t = s->state.t_s;
    c->samples[c->n_samples++] = *s;
    return JC_OK;
}

static void collector_free(collector *c)
{
    free(c->events);
    free(c->samples);
}

/* Stream and array agree to the bit on a run with many flights. */
static int same_as_array(const jc_Setup *s, double dt, int max_events, int min_flights)
{
    jc_Model m;
    if (sim_model(&m, s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = dt;
    o.max_events = max_events;
    jc_Run run, streamed;
    if (sim_run(&m, &o, &run)) return 1;
    collector c = {0};
    jc_summary_init(&c.summary);
    const jc_Recorder rec = {&c, on_event, on_sample};
    char err[256] = "";
    const int st = jc_simulate_stream(&m, &o, &rec, &streamed, err, sizeof err);
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    const int same_events = c.n_events == run.event_count && streamed.event_count == run.event_count &&
                            memcmp(c.events, run.events, sizeof *c.events * (size_t)c.n_events) == 0;
    const int same_samples = c.n_samples == run.sample_count && streamed.sample_count == run.sample_count &&
                             memcmp(c.samples, run.samples, sizeof *c.samples * (size_t)c.n_samples) == 0;
    const int same_end = streamed.termination == run.termination && streamed.events == NULL &&
                         memcmp(&streamed.final_state, &run.final_state, sizeof run.final_state) == 0 &&
                         memcmp(&streamed.energy, &run.energy, sizeof run.energy) == 0;
    const int same_summary = memcmp(&sum, &c.summary, sizeof sum) == 0;
    const int flights = sum.liftoffs + sum.bounces, open = c.open_flights, order = c.sample_order_broken;
    const int events = run.event_count;
    jc_run_free(&run);
    collector_free(&c);
    ENSURE_OK(st, err);
    ENSURE_MSG(events > 5 && flights >= min_flights, "the run has %d events, %d flights", events, flights);
    ENSURE_MSG(same_events, "events differ from jc_simulate's");
    ENSURE_MSG(same_samples, "samples differ from jc_simulate's");
    ENSURE_MSG(same_end, "termination, final state or energy differ");
    ENSURE_MSG(same_summary, "jc_summary_add differs from jc_run_summarize");
    /* A flight's event is pushed only once the flight has ended. */
    ENSURE_MSG(open == 0, "%d flight event(s) pushed before their flight ended", open);
    ENSURE_MSG(!order, "samples out of time order");
    return 0;
}

/* Slip and stick chatter: hundreds of events. */
static int test_hoop_same_as_array(void)
{
    const jc_Setup s = rocking_hoop_setup();
    return same_as_array(&s, 0.0, 400, 0) || same_as_array(&s, 0.01, 400, 0);
}

static int test_bouncing_same_as_array(void)
{
    const jc_Setup s = bouncing_setup();
    return same_as_array(&s, 0.0, 10000, 10) || same_as_array(&s, 1e-4, 10000, 10);
}

static int test_paper_same_as_array(void)
{
    const jc_Setup s = jc_paper_setup();
    return same_as_array(&s, 1e-3, 10000, 1);
}

/* The stuck sampler: in flight, t0 + (t - t0) rounded to just below
 * t and the next sample time did not advance (200 MB of identical rows).
 * Fixed samples sit at k * dt exactly and their times strictly increase. */
static int test_sample_grid_strictly_increases(void)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 0.0;
    s.body = (jc_BodyDef){0};
    s.body.radius_m = 0.14;
    s.body.part_count = 2;
    s.body.parts[0] = (jc_Part){JC_PART_DISC, 0.124, 0.0, 0.0, 0.14};
    s.body.parts[1] = (jc_Part){JC_PART_POINT, 0.051, 0.118, 0.0, 0.0};
    s.mu_static = s.mu_kinetic = 0.8;
    s.restitution = 0.0;
    s.theta0_rad = -1.41578797;
    s.omega0_radps = 21.0;
    s.paper_cm_offset_m = 0.0;
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.t_max_s = 0.7;
    o.sample_dt_s = 0.001;
    jc_Run run;
    if (sim_run(&m, &o, &run)) return 1;
    int strictly = 1, on_grid = 0;
    for (int i = 1; i < run.sample_count; ++i) {
        if (!(run.samples[i].state.t_s > run.samples[i - 1].state.t_s)) strictly = 0;
        const double k = round(run.samples[i].state.t_s / o.sample_dt_s);
        if (fabs(run.samples[i].state.t_s - k * o.sample_dt_s) < 1e-15) on_grid++;
    }
    const int n = run.sample_count;
    const double t_end = run.final_state.t_s;
    jc_run_free(&run);
    ENSURE_MSG(strictly, "sample times do not strictly increase");
    /* 0.7 s at 1 ms: about 700 grid samples plus one per event. */
    ENSURE_MSG(n > 650 && n < 800, "%d samples for %.3f s", n, t_end);
    ENSURE_MSG(on_grid > 650, "%d samples on the grid", on_grid);
    return 0;
}

/* A recorder that says stop: the run ends with its status, after exactly
 * the events it accepted. */
static int test_recorder_stops_run(void)
{
    const jc_Setup s = rocking_hoop_setup();
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    collector c = {.stop_after = 7};
    const jc_Recorder rec = {&c, on_event, NULL};
    jc_Run run;
    char err[256] = "";
    const int st = jc_simulate_stream(&m, &o, &rec, &run, err, sizeof err);
    const int n = c.n_events, samples = c.n_samples;
    collector_free(&c);
    ENSURE_MSG(st == JC_ESTOPPED, "status %d, expected JC_ESTOPPED", st);
    ENSURE_MSG(strstr(err, "stopped by the recorder") != NULL, "message: %s", err);
    ENSURE_MSG(n == 7, "%d events pushed", n);
    ENSURE_MSG(samples == 0, "samples computed without a sample callback");
    return 0;
}

/* max_samples is a named termination, not a silent cut. */
static int test_sample_limit_is_named(void)
{
    const jc_Setup s = jc_paper_setup();
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = 1e-4;
    o.max_samples = 100;
    jc_Run run;
    if (sim_run(&m, &o, &run)) return 1;
    const jc_Termination t = run.termination;
    const int n = run.sample_count;
    jc_run_free(&run);
    ENSURE_MSG(t == JC_END_SAMPLE_LIMIT, "termination %s", jc_termination_name(t));
    ENSURE_MSG(n == 100, "%d samples", n);
    ENSURE(strcmp(jc_termination_name(JC_END_SAMPLE_LIMIT), "sample_limit") == 0);
    return 0;
}

static int test_sample_dt_range(void)
{
    jc_SimOptions o = jc_default_sim_options();
    char err[256];
    o.sample_dt_s = 1e-10;
    ENSURE(jc_sim_options_validate(&o, err, sizeof err) == JC_EINVAL);
    o.sample_dt_s = 1e-9;
    ENSURE(jc_sim_options_validate(&o, err, sizeof err) == JC_OK);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_hoop_same_as_array);
    RUN_TEST(test_bouncing_same_as_array);
    RUN_TEST(test_paper_same_as_array);
    RUN_TEST(test_sample_grid_strictly_increases);
    RUN_TEST(test_recorder_stops_run);
    RUN_TEST(test_sample_limit_is_named);
    RUN_TEST(test_sample_dt_range);
    TEST_MAIN_END();
}
