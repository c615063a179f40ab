/*
 * Robust edges of the mode machine (physics.md §4a): starts that are not
 * rolling, Zeno bounce sequences, limits, bad options, and the invariants
 * every run must satisfy (a known termination, the final time within the
 * limit, events in time order, lift-offs with positive flight time and
 * non-negative hop height) over a sweep of setups.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>

/* Runs a setup with the given options; the run is left for the caller. */
static int simulate(const jc_Setup *s, const jc_SimOptions *o, jc_Model *m, jc_Run *run)
{
    if (sim_model(m, s)) return 1;
    if (sim_run(m, o, run)) return 1;
    if (check_run_invariants(o, run)) {
        jc_run_free(run);
        return 1;
    }
    return 0;
}

/* (a) 60 deg, mu 0.05: at rest the paper's cylinder needs |F|/N = 0.6 or so
 * to roll, far outside the cone: it slides from t = 0. */
static int test_starts_sliding(void)
{
    const jc_Setup s = paper_at(60.0, 0.05);
    jc_Model m;
    jc_Run run;
    const jc_SimOptions o = jc_default_sim_options();
    if (simulate(&s, &o, &m, &run)) return 1;
    const int n = run.event_count;
    const jc_Event first = n > 0 ? run.events[0] : (jc_Event){.kind = JC_EVENT_COUNT};
    jc_run_free(&run);
    ENSURE(n >= 1);
    ENSURE_MSG(first.kind == JC_EVENT_SLIP && first.state.t_s == 0.0, "first event %s at %g s",
               jc_event_name(first.kind), first.state.t_s);
    ENSURE(first.mode_before == JC_MODE_ROLLING && first.mode_after == JC_MODE_SLIDING);
    /* Independently: the rolling friction the start would need. At th = 0,
     * w = 0: th'' = M g (r + d) sin a / I_P(0), F = M ((r + d) th'' - g sin a). */
    const double M = m.body.mass_kg, r = m.body.radius_m, d = m.body.cm_offset_m, g = s.gravity_mps2;
    const double ip0 = m.body.inertia_c_kgm2 + M * r * r + 2.0 * M * r * d;
    const double thdd = M * g * (r + d) * sin(s.incline_rad) / ip0;
    const double f = M * ((r + d) * thdd - g * sin(s.incline_rad)), nrm = M * g * cos(s.incline_rad);
    ENSURE_MSG(fabs(f) > s.mu_static * nrm, "rolling would fit the cone: |F| %g, mu N %g", fabs(f), s.mu_static * nrm);
    return 0;
}

/* (b) A fast spin with the CM on top: d w0^2 > g cos a. The first event is a
 * lift-off at t = 0, and the flight that follows has a real length (a
 * zero-length flight would mean a wrong mode choice, repeated). */
static int check_flies_at_once(jc_Setup s, double w0)
{
    s.omega0_radps = w0;
    jc_Model m;
    jc_Run run;
    jc_SimOptions o = jc_default_sim_options();
    o.t_max_s = 5.0;
    if (simulate(&s, &o, &m, &run)) return 1;
    const double d = m.body.cm_offset_m;
    const jc_Event first = run.event_count > 0 ? run.events[0] : (jc_Event){.kind = JC_EVENT_COUNT};
    int short_flights = 0;
    for (int i = 0; i < run.event_count; ++i) {
        const jc_Event *e = &run.events[i];
        if ((e->kind == JC_EVENT_LIFTOFF) && !(e->flight_time_s > 1e-6)) short_flights++;
    }
    jc_run_free(&run);
    ENSURE_MSG(d * w0 * w0 > s.gravity_mps2 * cos(s.incline_rad), "setup error: d w0^2 = %g", d * w0 * w0);
    ENSURE_MSG(first.kind == JC_EVENT_LIFTOFF && first.state.t_s == 0.0, "first event %s at %g s",
               jc_event_name(first.kind), first.state.t_s);
    ENSURE_MSG(first.flight_time_s > 1e-6, "first flight lasts %g s", first.flight_time_s);
    ENSURE_MSG(short_flights == 0, "%d lift-offs with flights of 1 us or less", short_flights);
    return 0;
}

static int test_fast_spin_flies_at_once(void)
{
    /* Paper body at 30 deg: d = 2.663 cm, g cos a = 8.47 m/s^2, so w0 > 17.8 rad/s. */
    if (check_flies_at_once(paper_at(30.0, 0.5), 25.0)) return 1;
    if (check_flies_at_once(paper_at(30.0, 0.5), 18.0)) return 1;
    /* Hoop with a rim mass on the floor: d = 9.09 cm, w0 > 10.4 rad/s. */
    if (check_flies_at_once(hoop_with_mass(0.10, 0.010, 0.100, 0.0), 11.0)) return 1;
    return 0;
}

/* (c) Zeno: restitution 0.5; bounce sequences end in contact (the contact
 * height threshold), never by the event limit. */
static int check_bounces_end(jc_Setup s, double t_max, int *sequences)
{
    s.restitution = 0.5;
    jc_Model m;
    jc_Run run;
    jc_SimOptions o = jc_default_sim_options();
    o.t_max_s = t_max;
    if (simulate(&s, &o, &m, &run)) return 1;
    const jc_Termination why = run.termination;
    /* A bounce sequence: bounces ended by a touchdown. */
    int in_sequence = 0;
    for (int i = 0; i < run.event_count; ++i) {
        if (run.events[i].kind == JC_EVENT_BOUNCE) in_sequence++;
        else if (run.events[i].kind == JC_EVENT_TOUCHDOWN) {
            if (in_sequence >= 2) (*sequences)++;
            in_sequence = 0;
        }
    }
    const int n = run.event_count;
    jc_run_free(&run);
    ENSURE_MSG(why == JC_END_RAMP_END || why == JC_END_TIME_LIMIT, "termination %s after %d events",
               jc_termination_name(why), n);
    return 0;
}

static int test_zeno_bounces_end(void)
{
    int sequences = 0;
    if (check_bounces_end(paper_at(15.0, 0.5), 60.0, &sequences)) return 1;
    if (check_bounces_end(paper_at(45.0, 0.5), 60.0, &sequences)) return 1;
    if (check_bounces_end(hoop_with_mass(0.10, 0.010, 0.100, 20.0), 10.0, &sequences)) return 1;
    /* The sequences happened (otherwise this tests nothing). */
    ENSURE_MSG(sequences >= 2, "%d bounce sequences ending in touchdown", sequences);
    return 0;
}

/* (e) Limits: a tiny t_max ends by time; max_events 2 by events. */
static int test_limits(void)
{
    const jc_Setup s = paper_at(30.0, 0.5);
    jc_Model m;
    jc_Run run;
    jc_SimOptions o = jc_default_sim_options();
    o.t_max_s = 0.01;
    if (simulate(&s, &o, &m, &run)) return 1;
    const jc_Termination why = run.termination;
    const double t_end = run.final_state.t_s;
    jc_run_free(&run);
    ENSURE_MSG(why == JC_END_TIME_LIMIT, "termination %s", jc_termination_name(why));
    /* Rolling from rest: the limit is reached exactly (time inversion to 1e-13). */
    ENSURE_NEAR(t_end, 0.01, 1e-12);

    o = jc_default_sim_options();
    o.max_events = 2;
    if (simulate(&s, &o, &m, &run)) return 1;
    const jc_Termination why2 = run.termination;
    const int n = run.event_count;
    jc_run_free(&run);
    ENSURE_MSG(why2 == JC_END_EVENT_LIMIT, "termination %s", jc_termination_name(why2));
    ENSURE_MSG(n == 2, "%d events", n);

    /* Time limit inside a flight and inside a sliding phase: 0.8 s (in the
     * first flight at 30 deg) and 0.6 s (sliding after the first slip). */
    const double limits[] = {0.8, 0.6};
    for (int i = 0; i < 2; ++i) {
        o = jc_default_sim_options();
        o.t_max_s = limits[i];
        if (simulate(&s, &o, &m, &run)) return 1;
        const jc_Termination w = run.termination;
        const double te = run.final_state.t_s;
        const jc_Mode mode = run.final_mode;
        jc_run_free(&run);
        ENSURE_MSG(w == JC_END_TIME_LIMIT, "termination %s", jc_termination_name(w));
        ENSURE_NEAR(te, limits[i], 1e-12);
        ENSURE(mode == (i == 0 ? JC_MODE_FLIGHT : JC_MODE_SLIDING));
    }
    return 0;
}

/* (f) Bad options: JC_EINVAL with a message, and a run that is safe to free. */
static int check_rejected(jc_SimOptions o, const char *what)
{
    const jc_Setup s = paper_at(30.0, 0.5);
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_Run run;
    char err[256] = "";
    const int st = jc_simulate(&m, &o, &run, err, sizeof err);
    const int events = run.event_count, samples = run.sample_count;
    jc_run_free(&run);
    ENSURE_MSG(st == JC_EINVAL, "%s: status %d", what, st);
    ENSURE_MSG(strlen(err) > 10, "%s: message '%s'", what, err);
    ENSURE_MSG(events == 0 && samples == 0, "%s: %d events, %d samples", what, events, samples);
    return 0;
}

static int test_bad_options(void)
{
    const jc_SimOptions d = jc_default_sim_options();
    jc_SimOptions o;
    o = d; o.t_max_s = 0.0;
    if (check_rejected(o, "t_max 0")) return 1;
    o = d; o.t_max_s = -1.0;
    if (check_rejected(o, "t_max -1")) return 1;
    o = d; o.t_max_s = NAN;
    if (check_rejected(o, "t_max NaN")) return 1;
    o = d; o.t_max_s = INFINITY;
    if (check_rejected(o, "t_max inf")) return 1;
    o = d; o.sample_dt_s = -1e-3;
    if (check_rejected(o, "sample_dt -1e-3")) return 1;
    o = d; o.sample_dt_s = NAN;
    if (check_rejected(o, "sample_dt NaN")) return 1;
    o = d; o.max_events = 0;
    if (check_rejected(o, "max_events 0")) return 1;
    o = d; o.ode_rtol = NAN;
    if (check_rejected(o, "rtol NaN")) return 1;
    o = d; o.event_tol_s = 0.0;
    if (check_rejected(o, "event_tol 0")) return 1;
    o = d; o.contact_height_m = -1.0;
    if (check_rejected(o, "contact height -1")) return 1;
    /* And the message names the quantity: t_max's says "time limit". */
    o = d; o.t_max_s = -1.0;
    const jc_Setup s = paper_at(30.0, 0.5);
    jc_Model m;
    if (sim_model(&m, &s)) return 1;
    jc_Run run;
    char err[256] = "";
    jc_simulate(&m, &o, &run, err, sizeof err);
    jc_run_free(&run);
    ENSURE_MSG(strstr(err, "time limit") && strstr(err, "-1"), "message '%s'", err);
    return 0;
}

/* (d, g) A sweep of setups: every run succeeds and satisfies the invariants.
 * All failures are reported, then the test fails if there were any. */
static int sweep_one(const jc_Setup *s, double t_max, const char *label, int *failures)
{
    jc_Model m;
    if (sim_model(&m, s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.t_max_s = t_max;
    jc_Run run;
    char err[512] = "";
    const int st = jc_simulate(&m, &o, &run, err, sizeof err);
    if (st != JC_OK) {
        printf("  %s: jc_simulate returned %d (%s): %s\n", label, st, jc_status_text(st), err);
        (*failures)++;
    } else if (check_run_invariants(&o, &run)) {
        printf("  %s: invariants violated (above)\n", label);
        (*failures)++;
    } else if (run.termination == JC_END_STEP_LIMIT || run.termination == JC_END_EVENT_LIMIT) {
        printf("  %s: ended by %s (%s) at t %g s after %d events\n", label, jc_termination_name(run.termination),
               run.termination_detail, run.final_state.t_s, run.event_count);
        (*failures)++;
    }
    jc_run_free(&run);
    return 0;
}

/* A grid of three parameters (a, b, c): the setup of one point, and its label. */
typedef int (*grid_setup)(double a, double b, double c, jc_Setup *s, char *label, size_t label_len);

typedef struct {
    const double *v;
    int n;
} axis;

/* Runs every point of the grid for t_max; every run is checked and reported,
 * and the test fails if any failed. */
static int sweep_grid(const char *what, axis a, axis b, axis c, grid_setup make, double t_max)
{
    int failures = 0, runs = 0;
    for (int i = 0; i < a.n; ++i)
        for (int j = 0; j < b.n; ++j)
            for (int k = 0; k < c.n; ++k) {
                jc_Setup s;
                char label[96];
                if (make(a.v[i], b.v[j], c.v[k], &s, label, sizeof label)) return 1;
                if (sweep_one(&s, t_max, label, &failures)) return 1;
                runs++;
            }
    printf("  %d %s runs, %d failed\n", runs, what, failures);
    ENSURE(failures == 0);
    return 0;
}

static int paper_point(double incline_deg, double mu, double e, jc_Setup *s, char *label, size_t label_len)
{
    *s = paper_at(incline_deg, mu);
    s->restitution = e;
    snprintf(label, label_len, "paper %g deg mu %g e %g", incline_deg, mu, e);
    return 0;
}

static int test_sweep_paper(void)
{
    static const double inclines[] = {5.0, 15.0, 30.0, 45.0, 60.0, 75.0};
    static const double mus[] = {0.05, 0.2, 0.5, 1.0};
    static const double es[] = {0.0, 0.3, 0.5};
    return sweep_grid("paper", (axis){inclines, 6}, (axis){mus, 4}, (axis){es, 3}, paper_point, 60.0);
}

/* The built-in hoop preset (10 g hoop, 100 g rim mass, floor) at several
 * spins, frictions and restitutions: long runs of rocking, slipping and
 * hopping. */
static int hoop_point(double w0, double mu, double e, jc_Setup *s, char *label, size_t label_len)
{
    char err[256] = "";
    ENSURE_OK(jc_preset_setup("rocking-hoop", s, err, sizeof err), err);
    s->omega0_radps = w0;
    s->mu_static = s->mu_kinetic = mu;
    s->restitution = e;
    snprintf(label, label_len, "hoop preset w0 %g mu %g e %g", w0, mu, e);
    return 0;
}

static int test_sweep_hoop_preset(void)
{
    static const double w0s[] = {0.01, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0};
    static const double mus[] = {0.3, 0.5, 1.0};
    static const double es[] = {0.3, 0.5};
    return sweep_grid("hoop", (axis){w0s, 7}, (axis){mus, 3}, (axis){es, 2}, hoop_point, 20.0);
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_starts_sliding);
    RUN_TEST(test_fast_spin_flies_at_once);
    RUN_TEST(test_zeno_bounces_end);
    RUN_TEST(test_limits);
    RUN_TEST(test_bad_options);
    RUN_TEST(test_sweep_paper);
    RUN_TEST(test_sweep_hoop_preset);
    TEST_MAIN_END();
}
