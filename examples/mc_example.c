/* Where does the paper's cylinder first lift off on a 15 degree incline,
 * given the tolerances of its measurements? A Monte Carlo through the
 * library's studies: the paper's stated tolerances as spreads, 2000 samples
 * on every core, their outcomes tallied and summarised, as
 * `jumpcyl mc --incline 15 --samples 2000` does.
 * Usage: mc_example [SAMPLES] */
#include <jumpcyl/jumpcyl.h>
#include <jumpcyl/study.h>
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Each sample, in sample order, on this thread; 0: go on. */
static int on_row(void *ctx, const jc_StudyRow *row)
{
    return jc_tally_add(ctx, row->outcome) != JC_OK;
}

/* After each block of samples; 0: go on (a stop button returns 1). */
static int on_progress(void *ctx, long done, long count)
{
    (void)ctx;
    (void)done;
    (void)count;
    return 0;
}

int main(int argc, char **argv)
{
    const long samples = argc > 1 ? atol(argv[1]) : 2000;
    gsl_set_error_handler_off(); /* GSL's failures come back as statuses */
    char err[512];

    jc_StudyDef mc;
    memset(&mc, 0, sizeof mc);
    mc.kind = JC_STUDY_MONTE_CARLO;
    mc.base = jc_paper_setup();
    /* The incline, set on every sample (as --incline 15 sets it). */
    const int incline = jc_param_find("incline");
    mc.fixed.given[incline] = 1;
    mc.fixed.value[incline] = 15.0 * 3.14159265358979323846 / 180.0;
    /* The spreads: the paper's tolerances about the setup (radius, masses and
     * the rod's offset +- 0.05 cm or g, theta0 +- 3 deg, friction and
     * restitution uniform over what foam on wood allows). */
    jc_Setup nominal = mc.base;
    if (jc_param_values_apply(&mc.fixed, &nominal, NULL, err, sizeof err) != JC_OK) {
        fprintf(stderr, "mc_example: %s\n", err);
        return 1;
    }
    mc.param_count = jc_study_default_spreads(&nominal, mc.params, NULL, JC_STUDY_PARAM_MAX);
    mc.samples = samples;
    mc.seed = 1;
    mc.sim = jc_default_sim_options();
    mc.threads = 0; /* every core; sample i is the same for any count */

    jc_Tally tally;
    if (jc_tally_init(&tally, samples) != JC_OK) return 1;
    const jc_StudyCallbacks cb = {on_row, on_progress, &tally, 0};
    const int st = jc_study_run(&mc, 0, jc_study_case_count(&mc), &cb, err, sizeof err);
    if (st != JC_OK) {
        fprintf(stderr, "mc_example: %s (%s)\n", err, jc_status_text(st));
        jc_tally_free(&tally);
        return 1;
    }
    jc_Stats x;
    jc_stats_compute(tally.liftoff_x_m, tally.liftoffs, tally.none, tally.invalid, JC_MC_LIFTOFF_GAP_M, &x);
    printf("%ld samples of %d uncertain inputs on %d threads: %ld valid, %ld lift off on the ramp\n", samples,
           mc.param_count, jc_study_threads(&mc), tally.valid, tally.liftoffs);
    if (x.n > 0)
        printf("first lift-off: median %.2f cm, 95 %% between %.2f and %.2f cm, %d region(s)\n", x.p50 * 100,
               x.p2_5 * 100, x.p97_5 * 100, x.region_count);
    jc_tally_free(&tally);
    return 0;
}
