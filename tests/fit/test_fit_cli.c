/* compare on a noise-free synthetic track (in memory): residuals at the
 * interpolation's level and the model's lift-off that of `simulate`; and
 * the tool's compare and fit with bad option values: one line on standard
 * error, exit status 2, no file written. */
#include "track_fit.h"
#include "../cli_run.h"
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <sys/stat.h>

static jc_Setup truth(void)
{
    jc_Setup s = jc_paper_setup();
    s.mu_kinetic = 0.4;
    return s;
}

/* The run of simulate: the same setup from its own start. */
static int simulate_liftoff(const jc_Setup *s, double *x, double *t)
{
    jc_Model m;
    char err[256];
    jc_Run run;
    const jc_SimOptions o = jc_default_sim_options();
    if (jc_model_init(&m, s, err, sizeof err) != JC_OK || jc_simulate(&m, &o, &run, err, sizeof err) != JC_OK) {
        jc_run_free(&run);
        return -1;
    }
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    *x = sum.first_liftoff_state.x_m;
    *t = sum.first_liftoff_state.t_s;
    jc_run_free(&run);
    return sum.first_liftoff >= 0 ? 0 : -1;
}

static int test_noise_free_compare(void)
{
    const jc_Setup s = truth();
    const cli_SynthOptions so = {60.0, 0.0, 1.5, 0.055, 0.0, 1u, 0u};
    cli_Track t;
    char err[256];
    ENSURE_MSG(cli_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    double x_sim, t_sim;
    ENSURE(simulate_liftoff(&s, &x_sim, &t_sim) == 0);
    const jc_SimOptions o = jc_default_sim_options();
    cli_Compare c;
    /* From the setup's own start: the same run, sampled elsewhere. */
    ENSURE_MSG(cli_track_compare(&s, &t, &o, CLI_START_SETUP, NAN, NAN, &c, err, sizeof err) == 0, "%s", err);
    printf("setup start: RMS path %.3g m (largest %.3g), theta %.3g rad; lift-off %.12g m at %.12g s (simulate "
           "%.12g m at %.12g s)\n",
           c.rms_path_m, c.max_path_m, c.rms_theta_rad, c.model_liftoff_x_m, c.model_liftoff_t_s, x_sim, t_sim);
    const int ok1 = c.max_path_m < 1e-6 && c.rms_theta_rad < 1e-6 && fabs(c.model_liftoff_x_m - x_sim) < 1e-9 &&
                    fabs(c.model_liftoff_t_s - t_sim) < 1e-9 && c.measured.hops == c.simulated.hops &&
                    c.measured.first_liftoff_t_s == c.simulated.first_liftoff_t_s;
    cli_compare_free(&c);
    /* From the state the first frames show (estimated, then refined). */
    ENSURE_MSG(cli_track_compare(&s, &t, &o, CLI_START_TRACKED, NAN, NAN, &c, err, sizeof err) == 0, "%s", err);
    printf("tracked start: RMS path %.3g m (largest %.3g), theta %.3g rad; lift-off %.9g m\n", c.rms_path_m,
           c.max_path_m, c.rms_theta_rad, c.model_liftoff_x_m);
    const int ok2 = c.max_path_m < 1e-5 && fabs(c.model_liftoff_x_m - x_sim) < 1e-5 && c.measured.hops == c.simulated.hops;
    cli_compare_free(&c);
    /* Frames off the simulator's sample grid (the clip starts 4.1 ms after
     * the release): the cubic Hermite interpolation between samples is
     * what is compared, to below a micron. */
    for (long i = 0; i < t.n; ++i) t.t_s[i] += 0.0041;
    ENSURE_MSG(cli_track_compare(&s, &t, &o, CLI_START_SETUP, NAN, NAN, &c, err, sizeof err) == 0, "%s", err);
    printf("off the grid: largest path residual %.3g m, theta RMS %.3g rad\n", c.max_path_m, c.rms_theta_rad);
    const int ok3 = c.max_path_m > 0.0 && c.max_path_m < 1e-6 && c.rms_theta_rad < 1e-5;
    cli_compare_free(&c);
    cli_track_free(&t);
    ENSURE(ok1);
    ENSURE(ok2);
    ENSURE(ok3);
    return 0;
}

/* Four mis-clicked frames (2 cm off) in a track with 10 % of its frames
 * dropped: the linear fit's chi2/dof says so and its sigma swell; the
 * Cauchy loss sets them aside (sigma as without them, the truth within 3
 * of them). */
static int test_robust_loss(void)
{
    const jc_Setup s = truth();
    const cli_SynthOptions so = {60.0, 1e-3, 1.5, 0.055, 0.1, 5u, 0u};
    cli_Track t;
    char err[256];
    ENSURE_MSG(cli_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    ENSURE(t.gaps > 0);
    const long bad[] = {10, 25, 40, 55};
    for (int k = 0; k < 4; ++k) {
        t.x_m[bad[k]] += 0.02;
        t.y_m[bad[k]] -= 0.01;
    }
    jc_Setup guess = s;
    guess.mu_kinetic = 0.35;
    guess.restitution = 0.4;
    const jc_SimOptions o = jc_default_sim_options();
    cli_FitOptions fo = {(1u << CLI_FIT_MU_K) | (1u << CLI_FIT_RESTITUTION) | (1u << CLI_FIT_THETA0) |
                             (1u << CLI_FIT_OMEGA0) | (1u << CLI_FIT_X0),
                         CLI_LOSS_LINEAR, NAN, NAN, 100, 0.0, CLI_START_TRACKED};
    cli_FitResult lin, cau;
    const int rc1 = cli_track_fit(&guess, &t, &fo, &o, &lin, err, sizeof err);
    fo.loss = CLI_LOSS_CAUCHY;
    const int rc2 = rc1 == 0 ? cli_track_fit(&guess, &t, &fo, &o, &cau, err, sizeof err) : -1;
    cli_track_free(&t);
    ENSURE_MSG(rc1 == 0 && rc2 == 0, "%s", err);
    printf("linear: chi2/dof %.2f, mu_k %.5f +- %.5f, e %.5f +- %.5f\n", lin.chi2_dof, lin.value[0], lin.sigma[0],
           lin.value[1], lin.sigma[1]);
    printf("cauchy: chi2/dof %.2f, mu_k %.5f +- %.5f, e %.5f +- %.5f (%d passes)\n", cau.chi2_dof, cau.value[0],
           cau.sigma[0], cau.value[1], cau.sigma[1], cau.passes);
    ENSURE(lin.chi2_dof > 5.0 && cau.chi2_dof < 1.5);
    ENSURE(lin.sigma[0] > 2.0 * cau.sigma[0] && lin.sigma[1] > 2.0 * cau.sigma[1]);
    ENSURE(fabs(cau.value[0] - 0.4) < 3.0 * cau.sigma[0] && fabs(cau.value[1] - 0.3) < 3.0 * cau.sigma[1]);
    return 0;
}

/* A track file the tool reads: the synthetic track as Tracker's table. */
static int write_table(const char *path, double sigma_m)
{
    const jc_Setup s = truth();
    const cli_SynthOptions so = {60.0, sigma_m, 1.5, 0.055, 0.0, 1u, 0u};
    cli_Track t;
    char err[256];
    if (cli_track_synthesize(&s, &so, &t, err, sizeof err) != 0) return -1;
    FILE *f = fopen(path, "w");
    if (!f) {
        cli_track_free(&t);
        return -1;
    }
    fprintf(f, "#multi:\ncentre\t\t\tmass\t\nt\tx\ty\tx\ty\n");
    for (long i = 0; i < t.n; ++i)
        fprintf(f, "%.6f\t%.7g\t%.7g\t%.7g\t%.7g\n", t.t_s[i], t.x_m[i], t.y_m[i], t.x_m[i] + 0.055 * sin(t.theta_rad[i]),
                t.y_m[i] + 0.055 * cos(t.theta_rad[i]));
    cli_track_free(&t);
    return fclose(f);
}

static int exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

static int test_bad_options(void)
{
    char dir[] = "/tmp/jc_fit_cli_XXXXXX", track[256], fig[256];
    ENSURE(cli_scratch(dir, track, sizeof track, "track.txt") == 0);
    snprintf(fig, sizeof fig, "%s/out.png", dir);
    ENSURE(write_table(track, 1e-3) == 0);
    const char *cases[][12] = {
        {"fit", "--track", track, "--axes", "incline", "--output", fig, NULL},                       /* no --free */
        {"fit", "--track", track, "--free", "mu_q", "--output", fig, NULL},                          /* unknown value */
        {"fit", "--track", track, "--free", "mu_k,mu_k", "--output", fig, NULL},                     /* twice */
        {"fit", "--track", track, "--free", "mu_k", "--loss", "square", "--output", fig, NULL},
        {"fit", "--track", track, "--free", "mu_k", "--max-iter", "0", "--output", fig, NULL},
        {"fit", "--track", track, "--free", "mu_k", "--max-iter", "2.5", "--output", fig, NULL},
        {"fit", "--track", track, "--free", "mu_k", "--sigma", "-1mm", "--output", fig, NULL},
        {"fit", "--track", track, "--free", "mu_k", "--from", "1", "--to", "0.5", "--output", fig, NULL},
        {"compare", "--output", fig, NULL},                                                          /* no --track */
        {"compare", "--track", track, "--axes", "tilted", "--output", fig, NULL},
        {"compare", "--track", track, "--from", "-1", "--output", fig, NULL},
        {"compare", "--track", track, "--output", "out.gif", NULL},
    };
    const char *more[][12] = {
        {"compare", "--track", track, "--axes", "incline", "--from", "1.29", "--output", fig, NULL}, /* 1 frame */
        {"compare", "--track", "/nonexistent/t.txt", "--output", fig, NULL},
        {"compare", "--track", track, "--mu-k", "0.6", "--output", fig, NULL},                       /* mu_k > mu_s */
    };
    int bad = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0] + sizeof more / sizeof more[0]; ++i) {
        const char *const *args = i < sizeof cases / sizeof cases[0] ? cases[i] : more[i - sizeof cases / sizeof cases[0]];
        cli_result r = cli_run(args);
        if (r.status != 2 || !cli_one_line(r.err) || exists(fig)) {
            fprintf(stderr, "case %zu (%s %s %s ...): status %d, stderr '%s', figure %s\n", i, args[0], args[1],
                    args[2] ? args[2] : "", r.status, r.err ? r.err : "", exists(fig) ? "written" : "absent");
            bad = 1;
        }
        cli_result_free(&r);
    }
    /* The same track and options that work: exit 0, the figure written. */
    const char *good[] = {"fit", "--track", track, "--axes", "incline", "--mu-k", "0.35", "--free",
                          "mu_k,restitution,theta0,omega0,x0", "--output", fig, NULL};
    cli_result r = cli_run(good);
    const int good_ok = r.status == 0 && exists(fig) && strstr(r.out, "chi2/dof") && strstr(r.out, "Predicted first lift-off");
    if (!good_ok) fprintf(stderr, "good fit: status %d, stderr '%s'\n", r.status, r.err ? r.err : "");
    cli_result_free(&r);
    remove(fig);
    remove(track);
    rmdir(dir);
    ENSURE(!bad);
    ENSURE(good_ok);
    return 0;
}

/* The same through the tool and a Tracker table (7 digits): the path to
 * the table's rounding, the lift-off of simulate to a micron. */
static int test_noise_free_compare_tool(void)
{
    char dir[] = "/tmp/jc_fit_cli_XXXXXX", track[256];
    ENSURE(cli_scratch(dir, track, sizeof track, "track.txt") == 0);
    ENSURE(write_table(track, 0.0) == 0);
    const char *args[] = {"compare", "--track", track, "--axes", "incline", "--mu-k", "0.4", "--from-setup-start", NULL};
    cli_result r = cli_run(args);
    remove(track);
    rmdir(dir);
    const char *rms = r.out ? strstr(r.out, "centre's path: RMS ") : NULL;
    const char *ev = r.out ? strstr(r.out, "model's own lift-off event") : NULL;
    double rms_mm = NAN, x_cm = NAN, x_sim, t_sim;
    if (rms) rms_mm = strtod(rms + strlen("centre's path: RMS "), NULL);
    if (ev && (ev = strstr(ev, "x = "))) x_cm = strtod(ev + 4, NULL);
    const jc_Setup s = truth();
    ENSURE(simulate_liftoff(&s, &x_sim, &t_sim) == 0);
    printf("tool: RMS %.4f mm, lift-off %.2f cm (simulate %.4f cm)\n", rms_mm, x_cm, x_sim * 100);
    const int ok = r.status == 0 && rms_mm < 0.01 && fabs(x_cm - x_sim * 100) < 0.01;
    cli_result_free(&r);
    ENSURE(ok);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (cli_run_init(argc, argv) != 0) return 2;
    RUN_TEST(test_noise_free_compare);
    RUN_TEST(test_robust_loss);
    RUN_TEST(test_noise_free_compare_tool);
    RUN_TEST(test_bad_options);
    TEST_MAIN_END();
}
