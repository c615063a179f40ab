/* jumpcyl fit: setup values and the start fitted to a tracked video by
 * nonlinear least squares (docs/tracker.md, "Fit"). */
#include "track_fit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_MAX_ITER 100
#define MAX_MAX_ITER 10000

typedef struct {
    cli_TrackArgs track;
    const char *free_list, *loss, *max_iter, *sigma;
} fit_opts;

static void help(void)
{
    puts("Usage: jumpcyl fit --track FILE --free LIST [--loss linear|huber|cauchy] [--max-iter N]\n"
         "                   [--sigma LEN] [--from T] [--to T] [--output FIG] [SETUP OPTIONS]\n"
         "Fits setup values and the start to the tracked frames by nonlinear least squares (GSL,\n"
         "Levenberg-Marquardt): the residuals are the centre's x and y at every frame and, where\n"
         "the mark was tracked, the mark's displacement across its radius, in units of the\n"
         "position noise. Reports each value with its standard error (covariance scaled by\n"
         "chi2/dof), their correlations, chi2/dof, the iterations and why they stopped, and the\n"
         "predicted first lift-off with its standard error (docs/tracker.md).\n"
         "\n"
         "  --free LIST         comma-separated values to fit: mu_s, mu_k, restitution (bounded:\n"
         "                      0 <= mu_k <= mu_s, 0 <= e <= 1), theta0, omega0, x0 (the state\n"
         "                      at the first frame; without them, the state the first frames show)\n"
         "  --loss KIND         linear (default), huber or cauchy: robust, by reweighting\n"
         "  --max-iter N        trust-region iterations per pass (default 100; reported if reached)\n"
         "  --sigma LEN         the position noise (default: the track's)");
    cli_track_args_help();
    puts("  -h, --help          this help\n"
         "The other setup values are held at the setup options' values; mu_s, mu_k and\n"
         "restitution start from them.\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    fit_opts *o = ctx;
    const int rc = cli_track_args_take("fit", &o->track, opt, arg);
    if (rc != 1) return rc;
    if (opt == 'f') return cli_take_once("fit", &o->free_list, "free", arg);
    if (opt == 'l') return cli_take_once("fit", &o->loss, "loss", arg);
    if (opt == 'i') return cli_take_once("fit", &o->max_iter, "max-iter", arg);
    if (opt == 's') return cli_take_once("fit", &o->sigma, "sigma", arg);
    return EXIT_USAGE;
}

static const struct option own[] = {CLI_TRACK_ARG_OPTIONS,
                                    {"free", required_argument, 0, 'f'},
                                    {"loss", required_argument, 0, 'l'},
                                    {"max-iter", required_argument, 0, 'i'},
                                    {"sigma", required_argument, 0, 's'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* The fit's own options into fo; 0 or EXIT_USAGE after a one-line message. */
static int check(const fit_opts *o, cli_FitOptions *fo)
{
    char err[512];
    memset(fo, 0, sizeof *fo);
    if (!o->free_list) {
        cli_error("fit: --free LIST is required (allowed: mu_s, mu_k, restitution, theta0, omega0, x0)");
        return EXIT_USAGE;
    }
    if (cli_fit_parse_free(o->free_list, &fo->free_mask, err, sizeof err) != 0) {
        cli_error("fit: %s", err);
        return EXIT_USAGE;
    }
    if (o->loss && cli_fit_parse_loss(o->loss, &fo->loss) != 0) {
        cli_error("fit: --loss '%s' (allowed: linear, huber, cauchy)", o->loss);
        return EXIT_USAGE;
    }
    double v = DEFAULT_MAX_ITER;
    if (o->max_iter && (cli_parse_quantity(o->max_iter, Q_NUMBER, &v, err, sizeof err) != 0 || !(v >= 1) ||
                        v > MAX_MAX_ITER || v != floor(v))) {
        cli_error("fit: --max-iter '%s' (allowed: a whole number from 1 to %d)", o->max_iter, MAX_MAX_ITER);
        return EXIT_USAGE;
    }
    fo->max_iter = (int)v;
    if (o->sigma && (cli_parse_quantity(o->sigma, Q_LENGTH, &fo->sigma_m, err, sizeof err) != 0 ||
                     !(fo->sigma_m > 0.0 && fo->sigma_m <= 1.0))) {
        cli_error("fit: --sigma '%s' (allowed: a length in (0, 1] m, e.g. 1mm)", o->sigma);
        return EXIT_USAGE;
    }
    return 0;
}

static const char *unit_of(cli_FitParam p)
{
    return p == CLI_FIT_THETA0 ? "rad" : p == CLI_FIT_OMEGA0 ? "rad/s" : p == CLI_FIT_X0 ? "m" : "";
}

static void report(const char *file, const cli_Track *t, const cli_FitResult *r, const cli_FitOptions *fo)
{
    static const char *const loss_names[] = {"linear", "huber", "cauchy"};
    cli_track_print_head(file, t, r->first, r->frames);
    printf("Fit: %ld residuals (sigma %.3g mm), %d free value(s), loss %s", r->residuals, r->sigma_m * 1e3, r->count,
           loss_names[fo->loss]);
    if (fo->loss != CLI_LOSS_LINEAR) printf(", %d reweighting pass(es)", r->passes);
    printf("\nStopped after %d iteration(s): %s\n", r->iterations, cli_fit_stop_text(r->stop));
    printf("chi2/dof = %.4g (chi2 %.4g, dof %ld)\n\n", r->chi2_dof, r->chi2, r->residuals - r->count);
    printf("  %-12s %14s   %14s %s\n", "value", "initial", "fitted", "+- standard error");
    for (int k = 0; k < r->count; ++k)
        printf("  %-12s %14.6g   %14.6g +- %.3g %s\n", cli_fit_param_name(r->param[k]), r->initial[k], r->value[k],
               r->sigma[k], unit_of(r->param[k]));
    if (r->singular)
        printf("  (a standard error is undefined: that value does not change the residuals here; hold it\n"
               "   fixed, or fit a window where it acts: mu_s only if the body slips, restitution only if it lands)\n");
    printf("\nCorrelations:\n  %-12s", "");
    for (int k = 0; k < r->count; ++k) printf(" %12s", cli_fit_param_name(r->param[k]));
    putchar('\n');
    for (int i = 0; i < r->count; ++i) {
        printf("  %-12s", cli_fit_param_name(r->param[i]));
        for (int j = 0; j < r->count; ++j) printf(" %12.3f", cli_shown(r->corr[i][j], 3));
        putchar('\n');
    }
    if (r->has_liftoff)
        printf("\nPredicted first lift-off: x = %.2f +- %.2f cm along the track (t = %.4f s)\n", r->liftoff_x_m * 100,
               r->liftoff_sigma_m * 100, r->liftoff_t_s);
    else
        printf("\nPredicted first lift-off: none (the fitted model does not lift off)\n");
    printf("Residuals at the fit: centre's path RMS %.3f mm", r->rms_path_m * 1e3);
    if (t->has_mark) printf(", mark's angle RMS %.4f rad", r->rms_theta_rad);
    printf("\n");
}

static int figure(const char *out, const cli_Track *t, const cli_FitResult *r, const jc_SimOptions *o, int argc,
                  char **argv)
{
    jc_Model m;
    char err[256];
    if (cli_track_model(&r->setup, &m, err, sizeof err) != 0) {
        cli_error("fit: %s", err);
        return EXIT_FAIL;
    }
    const size_t n = (size_t)r->frames;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *th = malloc(n * sizeof *th);
    cli_TrackFigure f;
    memset(&f, 0, sizeof f);
    cli_TrackSim sim;
    int rc = x && y && th && cli_track_sim_init(&sim) == 0 ? 0 : -1;
    if (rc == 0) {
        sim.shift_m = cli_track_sim_shift(t);
        rc = cli_track_sim_run(&sim, &m, &r->start, o, t->t_s + r->first, r->frames, x, y, th, err, sizeof err);
        cli_track_sim_free(&sim);
    }
    if (rc == 0) {
        for (size_t i = 0; i < n; ++i) th[i] -= cli_track_mark_offset_rad(&m);
        f.track = t;
        f.first = r->first;
        f.count = r->frames;
        f.sim_x = x;
        f.sim_y = y;
        f.sim_theta = th;
        f.mark_radius_m = t->has_mark ? r->mark_radius_m : 0.0;
        f.hop_threshold_m = fmax(5.0 * r->sigma_m, 1e-4);
        snprintf(f.title, sizeof f.title,
                 "jumpcyl fit: μ_s = %.4g, μ_k = %.4g, e = %.4g; χ²/dof = %.3g, residuals RMS %.2f mm",
                 r->setup.mu_static, r->setup.mu_kinetic, r->setup.restitution, r->chi2_dof, r->rms_path_m * 1e3);
        rc = cli_track_figure_draw("fit", &f, &r->setup, &m, &r->start, o, out, argc, argv);
    } else {
        rc = CLI_TRACK_FIGURE_NO_PATH;
    }
    if (rc == CLI_TRACK_FIGURE_NO_PATH) {
        cli_error("fit: the fitted model's path for the figure failed");
        rc = EXIT_FAIL;
    }
    free(x);
    free(y);
    free(th);
    return rc;
}

int cmd_fit(int argc, char **argv)
{
    fit_opts o;
    memset(&o, 0, sizeof o);
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_command_parse(argc, argv, &command, &o, &sa, &sim_args);
    if (st != CLI_GO_ON) return st;
    cli_FitOptions fo;
    if ((st = check(&o, &fo)) != 0) return st;
    if ((st = cli_track_args_check("fit", &o.track, &fo.from_s, &fo.to_s)) != 0) return st;
    fo.start = o.track.from_setup_start ? CLI_START_SETUP : CLI_START_TRACKED;
    jc_Setup setup;
    jc_SimOptions opts;
    jc_Model model;
    if ((st = cli_build_inputs("fit", &sa, &sim_args, &setup, &opts, &model)) != 0) return st;
    cli_Track t;
    if ((st = cli_track_args_load("fit", &o.track, &model, &t)) != 0) return st;
    cli_FitResult r;
    char err[512];
    if (cli_track_fit(&setup, &t, &fo, &opts, &r, err, sizeof err) != 0) {
        cli_error("fit: %s", err);
        cli_track_free(&t);
        return EXIT_USAGE;
    }
    report(o.track.track, &t, &r, &fo);
    st = o.track.output ? figure(o.track.output, &t, &r, &opts, argc, argv) : EXIT_OK;
    if (st == EXIT_OK && o.track.output) printf("Figure: %s\n", o.track.output);
    cli_track_free(&t);
    return st == EXIT_OK ? cli_stdout_finish() : st;
}
