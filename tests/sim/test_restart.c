/*
 * jc_simulate_from and jc_Workspace (issue: one model, many runs, from any
 * state):
 * - a run with a workspace and a recorder that does not allocate makes no
 *   heap allocation at all (malloc, calloc and realloc are counted here by
 *   interposing them on glibc's own);
 * - a run restarted from the state of one of its events repeats the rest of
 *   the original run: the same events, at the same times to 1e-9 s;
 * - bad start states are refused with a message naming the value.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>

/* ---- counting allocations (glibc; not under AddressSanitizer, which owns malloc) ---- */

#if defined(__SANITIZE_ADDRESS__)
#define COUNTING 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COUNTING 0
#endif
#endif
#ifndef COUNTING
#define COUNTING 1
#endif

static long allocations;

#if COUNTING
void *__libc_malloc(size_t size);
void *__libc_calloc(size_t n, size_t size);
void *__libc_realloc(void *p, size_t size);

void *malloc(size_t size)
{
    allocations++;
    return __libc_malloc(size);
}

void *calloc(size_t n, size_t size)
{
    allocations++;
    return __libc_calloc(n, size);
}

void *realloc(void *p, size_t size)
{
    allocations++;
    return __libc_realloc(p, size);
}
#endif

typedef struct {
    int events;
    int samples;
} counts;

static int count_event(void *ctx, const jc_Event *e)
{
    (void)e;
    ((counts *)ctx)->events++;
    return JC_OK;
}

static int count_sample(void *ctx, const jc_Sample *s)
{
    (void)s;
    ((counts *)ctx)->samples++;
    return JC_OK;
}

static int test_no_allocation_per_run(void)
{
    if (!COUNTING) {
        printf("  (allocations are not counted under AddressSanitizer)\n");
        return 0;
    }
    const char *const presets[] = {"paper", "hoop", "rocking-hoop"};
    const long at_start = allocations;
    jc_Workspace *ws = jc_workspace_new();
    ENSURE(ws != NULL);
    /* The counting itself works: the workspace is allocated. */
    ENSURE_MSG(allocations > at_start, "malloc is not interposed: no allocation counted for jc_workspace_new");
    for (int p = 0; p < 3; ++p) {
        for (int drag = 0; drag < 2; ++drag) {
            jc_Setup s;
            char err[256];
            ENSURE_OK(jc_preset_setup(presets[p], &s, err, sizeof err), err);
            s.drag_coefficient = drag ? 0.6 : 0.0;
            jc_Model m;
            ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
            jc_SimOptions o = jc_default_sim_options();
            o.sample_dt_s = 0.01;
            o.t_max_s = 5.0;
            counts c = {0, 0};
            const jc_Recorder rec = {&c, count_event, count_sample};
            const jc_State start = jc_start_state(&m);
            jc_Run run;
            const long before = allocations;
            ENSURE_OK(jc_simulate_from(&m, &start, &o, &rec, ws, &run, err, sizeof err), err);
            const long made = allocations - before;
            printf("  %-12s drag %d: %d events, %d samples, %s; %ld allocations\n", presets[p], drag, c.events,
                   c.samples, jc_termination_name(run.termination), made);
            ENSURE_MSG(made == 0, "%s (drag %d): %ld heap allocations in one run", presets[p], drag, made);
            ENSURE(c.events > 0 && c.samples > 10);
        }
    }
    jc_workspace_free(ws);
    return 0;
}

/* The run from the state of event k repeats the original's later events. */
static int check_restart(const char *preset, double incline_deg)
{
    jc_Setup s;
    char err[256];
    ENSURE_OK(jc_preset_setup(preset, &s, err, sizeof err), err);
    if (incline_deg >= 0.0) s.incline_rad = incline_deg * DEG;
    jc_Model m;
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    const jc_SimOptions o = jc_default_sim_options();
    jc_Run full;
    ENSURE_OK(jc_simulate(&m, &o, &full, err, sizeof err), err);
    int restarts = 0;
    for (int k = 0; k < full.event_count - 1; ++k) {
        const jc_Event *from = &full.events[k];
        /* Restart at a change into contact or into sliding: the state there is
         * the whole story (a flight's start also needs the held lift-off). */
        if (from->mode_after == JC_MODE_FLIGHT || from->kind == JC_EVENT_RAMP_END) continue;
        jc_Run part;
        const int st = jc_simulate_from(&m, &from->state, &o, NULL, NULL, &part, err, sizeof err);
        if (st != JC_OK) {
            jc_run_free(&full);
            ENSURE_MSG(0, "%s: restart from event %d (%s): %s", preset, k, jc_event_name(from->kind), err);
        }
        jc_Run arrays = {0};
        const jc_Recorder rec = jc_run_recorder(&arrays);
        ENSURE_OK(jc_simulate_from(&m, &from->state, &o, &rec, NULL, &part, err, sizeof err), err);
        /* The mode at the start is chosen again: a start that does not roll
         * is the restart's first event (a slip), at the start (or, on the
         * cone's edge, after rolling for a rounding error of time); the
         * original's next event follows it. */
        const int skip = arrays.event_count > 0 && fabs(arrays.events[0].state.t_s - from->state.t_s) <= 1e-9;
        const int offset = k + 1;
        const int compare = full.event_count - offset < arrays.event_count - skip ? full.event_count - offset
                                                                                   : arrays.event_count - skip;
        int ok = compare > 0 && part.termination == full.termination;
        for (int i = 0; ok && i < compare; ++i) {
            const jc_Event *a = &full.events[offset + i], *b = &arrays.events[skip + i];
            ok = a->kind == b->kind && fabs(a->state.t_s - b->state.t_s) <= 1e-9 &&
                 fabs(a->state.x_m - b->state.x_m) <= 1e-9;
            if (!ok)
                fprintf(stderr, "  %s restart from event %d: event %d is %s at %.12f s, the original's %s at %.12f s\n",
                        preset, k, i, jc_event_name(b->kind), b->state.t_s, jc_event_name(a->kind), a->state.t_s);
        }
        jc_run_free(&arrays);
        if (!ok) {
            jc_run_free(&full);
            ENSURE_MSG(0, "%s: the run restarted from event %d differs", preset, k);
        }
        restarts++;
    }
    printf("  %s %.0f deg: %d events, %d restarts repeat the rest\n", preset,
           s.incline_rad / DEG, full.event_count, restarts);
    jc_run_free(&full);
    ENSURE(restarts > 0);
    return 0;
}

static int test_restart_repeats_the_run(void)
{
    if (check_restart("paper", 15.0) || check_restart("paper", 30.0) || check_restart("paper", 45.0)) return 1;
    return check_restart("hoop", -1.0);
}

static int test_bad_start_states_are_refused(void)
{
    jc_Model m;
    char err[256];
    const jc_Setup s = jc_paper_setup();
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    const jc_SimOptions o = jc_default_sim_options();
    const jc_State good = jc_start_state(&m);
    struct {
        jc_State s;
        const char *says;
    } bad[] = {
        {good, "below the incline"},
        {good, "off the ramp"},
        {good, "not a finite number"},
        {good, "moves into the incline"},
        {good, "start time"},
    };
    bad[0].s.y_m = 0.09;
    bad[1].s.x_m = -0.5;
    bad[2].s.omega_radps = NAN;
    bad[3].s.vy_mps = -0.1;
    bad[4].s.t_s = 1e9;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        jc_Run run;
        err[0] = 0;
        ENSURE(jc_simulate_from(&m, &bad[i].s, &o, NULL, NULL, &run, err, sizeof err) == JC_EINVAL);
        ENSURE_MSG(strstr(err, bad[i].says) != NULL, "message \"%s\" does not say \"%s\"", err, bad[i].says);
    }
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_no_allocation_per_run);
    RUN_TEST(test_restart_repeats_the_run);
    RUN_TEST(test_bad_start_states_are_refused);
    TEST_MAIN_END();
}
