/* The fit's statistics on synthetic experiments (issue 16, item 6): the
 * paper's cylinder on 30°, filmed at 60 fps and tracked with 1 mm noise
 * (about a pixel of a phone's frame 2 m wide), fitted 200 times with
 * independent noise. The fit must recover the known values within 2 of its
 * reported sigma in 95 % of the trials, and the reported sigma must match
 * the spread of the estimates within 20 %.
 *
 * A 2-sigma interval covers 95.45 % of a perfect estimator's trials, so 200
 * trials count 190.9 on average with a binomial spread of 2.9: a literal
 * ">= 190 of 200" for each of five values would fail a perfect fit about
 * half the time. The test asks instead: at least 95 % over all the intervals
 * (1000: spread 0.66 %), less one spread; and at least 92 % (95 % less two
 * spreads of 200) for each value. A fit whose sigma were 20 % too small
 * would cover 89 %. Not converged fits count as misses.
 *
 * Environment: JC_FIT_TRIALS (default 200), JC_FIT_SEED (default 16). */
#include "track_fit.h"
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>

#define DEFAULT_TRIALS 200
#define DEFAULT_SEED 16u
#define POOLED_COVERAGE (0.95 - 0.0066)
#define PER_VALUE_COVERAGE 0.92
/* The truth's first lift-off (jumpcyl simulate --mu-k 0.4). */
#define TRUE_LIFTOFF_M 1.19267614379

/* The experiment: the paper's cylinder on 30° with mu_k below mu_s (the
 * preset has them equal, at the edge of the allowed range), filmed from
 * release until it leaves the ramp. It slips at 0.53 s, sticks, slips,
 * lifts off at 1.19 m and bounces three times: every free value shapes the
 * path. */
static jc_Setup truth(void)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 30.0 * CLI_PI / 180.0;
    s.mu_static = 0.5;
    s.mu_kinetic = 0.4;
    s.restitution = 0.3;
    return s;
}

static cli_SynthOptions synth(uint64_t seed, uint64_t trial)
{
    cli_SynthOptions o = {60.0, 1e-3, 1.5, 0.055, 0.0, seed, trial};
    return o;
}

/* The values the fit frees and what they are in truth. */
static const cli_FitParam freed[] = {CLI_FIT_MU_K, CLI_FIT_RESTITUTION, CLI_FIT_THETA0,
                                     CLI_FIT_OMEGA0, CLI_FIT_X0};
#define NFREE (int)(sizeof freed / sizeof freed[0])

static double true_value(cli_FitParam p)
{
    const jc_Setup s = truth();
    switch (p) {
    case CLI_FIT_MU_S: return s.mu_static;
    case CLI_FIT_MU_K: return s.mu_kinetic;
    case CLI_FIT_RESTITUTION: return s.restitution;
    default: return 0.0; /* released at rest with G up, at the ramp's top */
    }
}

static int run_trials(int trials, uint64_t seed)
{
    unsigned mask = 0;
    for (int k = 0; k < NFREE; ++k) mask |= 1u << freed[k];
    /* The fit starts from values off the truth, as a user's guess would be. */
    jc_Setup guess = truth();
    guess.mu_kinetic = 0.35;
    guess.restitution = 0.4;
    const cli_FitOptions fo = {mask, CLI_LOSS_LINEAR, NAN, NAN, 100, 0.0, CLI_START_TRACKED};
    const jc_SimOptions so = jc_default_sim_options();
    int inside[NFREE] = {0}, done = 0, failed = 0;
    double sum[NFREE] = {0}, sum2[NFREE] = {0}, sig[NFREE] = {0};
    cli_FitResult *res = calloc((size_t)trials, sizeof *res);
    int *rc = calloc((size_t)trials, sizeof *rc);
    ENSURE(res && rc);
    /* The trials are independent (a fit keeps no state outside its own
     * memory): on every core. */
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < trials; ++i) {
        cli_Track t;
        char err[256];
        const cli_SynthOptions o = synth(seed, (uint64_t)i);
        const jc_Setup ts = truth();
        rc[i] = cli_track_synthesize(&ts, &o, &t, err, sizeof err) != 0 ? 1
                : cli_track_fit(&guess, &t, &fo, &so, &res[i], err, sizeof err) != 0 ? 2 : 0;
        if (rc[i] != 1) cli_track_free(&t); /* a failed synthesis leaves nothing to free */
        if (rc[i]) fprintf(stderr, "trial %d (seed %llu): %s\n", i, (unsigned long long)seed, err);
    }
    int lift_inside = 0;
    for (int i = 0; i < trials; ++i) {
        const cli_FitResult r = res[i];
        if (rc[i] != 0) {
            free(res);
            free(rc);
            ENSURE_MSG(0, "trial %d failed (seed %llu)", i, (unsigned long long)seed);
        }
        if (r.stop == CLI_FIT_STOP_ITERATIONS || r.singular) {
            ++failed;
            continue;
        }
        ++done;
        lift_inside += fabs(r.liftoff_x_m - TRUE_LIFTOFF_M) <= 2.0 * r.liftoff_sigma_m;
        if (getenv("JC_FIT_VERBOSE")) {
            printf("T %d chi2 %.3f it %d stop %d lift %.5f", i, r.chi2_dof, r.iterations, (int)r.stop, r.liftoff_x_m);
            for (int k = 0; k < NFREE; ++k) printf(" %+.2f", (r.value[k] - true_value(freed[k])) / r.sigma[k]);
            printf("\n");
        }
        for (int k = 0; k < NFREE; ++k) {
            const double v = r.value[k], sg = r.sigma[k], d = v - true_value(freed[k]);
            inside[k] += fabs(d) <= 2.0 * sg;
            sum[k] += v;
            sum2[k] += v * v;
            sig[k] += sg * sg;
        }
        if (i < 3) {
            printf("trial %d: chi2/dof %.3f, %d iterations, %s\n", i, r.chi2_dof, r.iterations, cli_fit_stop_text(r.stop));
            for (int k = 0; k < NFREE; ++k)
                printf("  %-12s %.6g +- %.3g (true %.6g)\n", cli_fit_param_name(freed[k]), r.value[k], r.sigma[k],
                       true_value(freed[k]));
            printf("  lift-off %.4f +- %.4f m\n", r.liftoff_x_m, r.liftoff_sigma_m);
        }
    }
    free(res);
    free(rc);
    printf("%d trials fitted, %d not converged (seed %llu); predicted first lift-off within 2 sigma of the "
           "truth in %.1f %%\n", done, failed, (unsigned long long)seed, 100.0 * lift_inside / trials);
    int bad = 0, covered = 0;
    for (int k = 0; k < NFREE; ++k) {
        const double mean = sum[k] / done, sd = sqrt(fmax(sum2[k] / done - mean * mean, 0.0) * done / (done - 1));
        const double rms_sigma = sqrt(sig[k] / done), cover = (double)inside[k] / trials;
        printf("  %-12s coverage %.3f, mean %.6g (true %.6g), spread %.4g, reported sigma (rms) %.4g, ratio %.3f\n",
               cli_fit_param_name(freed[k]), cover, mean, true_value(freed[k]), sd, rms_sigma, rms_sigma / sd);
        if (cover < PER_VALUE_COVERAGE || fabs(rms_sigma / sd - 1.0) > 0.2) bad = 1;
        covered += inside[k];
    }
    const double pooled = (double)covered / (NFREE * trials);
    printf("  all values: coverage %.4f (%d of %d intervals)\n", pooled, covered, NFREE * trials);
    if (pooled < POOLED_COVERAGE) bad = 1;
    ENSURE_MSG(!bad, "coverage or sigma spread out of bounds (seed %llu, %d trials)", (unsigned long long)seed,
               trials);
    return 0;
}

static unsigned long long env_number(const char *name, unsigned long long dflt)
{
    const char *v = getenv(name);
    return v && *v ? strtoull(v, NULL, 10) : dflt;
}

static int test_fit_statistics(void)
{
    return run_trials((int)env_number("JC_FIT_TRIALS", DEFAULT_TRIALS), env_number("JC_FIT_SEED", DEFAULT_SEED));
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_fit_statistics);
    TEST_MAIN_END();
}
