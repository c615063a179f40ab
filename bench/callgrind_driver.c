/*
 * A deterministic workload for instruction counts (valgrind --tool=callgrind):
 * what `make bench` times, without the clock. Usage:
 *   callgrind_driver sim|drag|roll [reps]
 * sim: full runs of the paper's cylinder at 15, 30 and 45 deg (reps each);
 * drag: the same with air drag (C_d 0.6); roll: rolling predictions.
 * Runs go through jc_simulate_from with one workspace and a recorder that
 * keeps nothing (the run itself, not the arrays jc_simulate grows).
 */
#include <jumpcyl/jumpcyl.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int count_event(void *ctx, const jc_Event *e)
{
    (void)e;
    ++*(long *)ctx;
    return JC_OK;
}

int main(int argc, char **argv)
{
    const char *what = argc > 1 ? argv[1] : "sim";
    const int reps = argc > 2 ? atoi(argv[2]) : 100;
    const int drag = strcmp(what, "drag") == 0, roll = strcmp(what, "roll") == 0;
    const double inclines[3] = {15, 30, 45};
    char err[256];
    long events = 0, steps = 0;
    double check = 0.0;
    jc_Workspace *ws = jc_workspace_new();
    if (!ws) return 1;
    const jc_Recorder rec = {&events, count_event, NULL};
    const jc_SimOptions o = jc_default_sim_options();
    for (int c = 0; c < 3; ++c) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = inclines[c] * 3.14159265358979323846 / 180.0;
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
    printf("%s: %d runs, %ld events, %ld ode steps, check %.17g\n", what, 3 * reps, events, steps, check);
    return 0;
}
