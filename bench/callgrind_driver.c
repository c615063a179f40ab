/*
 * A deterministic workload for instruction counts (valgrind --tool=callgrind):
 * what `make bench` times, without the clock. Usage:
 *   callgrind_driver sim|drag|roll [reps]
 *   callgrind_driver hoop|sample30 [reps] [sample_dt]
 * sim: full runs of the paper's cylinder at 15, 30 and 45 deg (reps each);
 * drag: the same with air drag (C_d 0.6); roll: rolling predictions.
 * hoop: the hoop preset (60 s, rocking) sampled every sample_dt (default
 * 0.01 s); sample30: the paper's cylinder at 30 deg sampled every sample_dt
 * (default 1 ms); sample_dt 0 for the same runs without samples.
 * Runs go through jc_simulate_from with one workspace and a recorder that
 * keeps nothing (the run itself, not the arrays jc_simulate grows); it
 * counts events and samples.
 */
#include <jumpcyl/jumpcyl.h>

#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    long events, samples;
} counts;

static int count_event(void *ctx, const jc_Event *e)
{
    (void)e;
    ((counts *)ctx)->events++;
    return JC_OK;
}

static int count_sample(void *ctx, const jc_Sample *p)
{
    (void)p;
    ((counts *)ctx)->samples++;
    return JC_OK;
}

int main(int argc, char **argv)
{
    const char *what = argc > 1 ? argv[1] : "sim";
    const int reps = argc > 2 ? atoi(argv[2]) : 100;
    const int drag = strcmp(what, "drag") == 0, roll = strcmp(what, "roll") == 0;
    const int hoop = strcmp(what, "hoop") == 0, sample30 = strcmp(what, "sample30") == 0;
    const double sample_dt = argc > 3 ? atof(argv[3]) : (hoop ? 0.01 : (sample30 ? 0.001 : 0.0));
    const double inclines[3] = {15, 30, 45};
    char err[256];
    counts n = {0, 0};
    long steps = 0;
    double check = 0.0;
    gsl_set_error_handler_off(); /* the library's quadrature falls back on failure (as the tool does) */
    jc_Workspace *ws = jc_workspace_new();
    if (!ws) return 1;
    const jc_Recorder rec = {&n, count_event, count_sample};
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = sample_dt;
    const int cases = hoop || sample30 ? 1 : 3;
    for (int c = 0; c < cases; ++c) {
        jc_Setup s = jc_paper_setup();
        if (hoop) {
            if (jc_preset_setup("hoop", &s, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        } else {
            s.incline_rad = (sample30 ? 30.0 : inclines[c]) * 3.14159265358979323846 / 180.0;
        }
        if (drag) s.drag_coefficient = 0.6;
        jc_Model m;
        if (jc_model_init(&m, &s, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
        const jc_State start = jc_start_state(&m);
        for (int i = 0; i < reps; ++i) {
            if (roll) {
                jc_RollingResult rr;
                if (jc_rolling_predict(&m, &rr, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
                check += rr.end_theta_rad;
                continue;
            }
            jc_Run run;
            if (jc_simulate_from(&m, &start, &o, &rec, ws, &run, err, sizeof err)) {
                fprintf(stderr, "%s\n", err);
                return 1;
            }
            steps += run.ode_steps;
            check += run.final_state.t_s;
        }
    }
    jc_workspace_free(ws);
    printf("%s: %d runs, %ld events, %ld samples, %ld ode steps, check %.17g\n", what, cases * reps, n.events,
           n.samples, steps, check);
    return 0;
}
