/* jumpcyl compare: a tracked video against the model run from the state the
 * frames show where the free motion starts (docs/tracker.md, "Compare"). */
#include "commands.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void help(void)
{
    puts("Usage: jumpcyl compare --track FILE [--from T] [--to T] [--from-setup-start] [--output FIG]\n"
         "                       [SETUP OPTIONS] [SIMULATION OPTIONS]\n"
         "Runs the model from the state the frames show where the free motion starts (frames a hand\n"
         "pushes are found and left out; x0, omega0 and theta0 fitted to the next 0.4 s, as fit\n"
         "starts) and reports measured against simulated: the first lift-off, the hops and their\n"
         "heights, and the residuals of the centre's path and of the mark's angle\n"
         "(docs/tracker.md). The incline is the video's unless --incline is given.\n");
    cli_track_args_help(1);
    puts("  -h, --help          this help\n");
}

static int take(int opt, const char *arg, void *ctx) { return cli_track_args_take("compare", ctx, opt, arg); }

static const struct option own[] = {CLI_TRACK_ARG_OPTIONS, {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

static void print_hops(const char *label, const jc_TrackHops *h)
{
    printf("  %-28s %d", label, h->hops);
    if (h->hops > 0) {
        printf(" (heights");
        for (int k = 0; k < h->hops && k < JC_TRACK_MAX_HOPS; ++k) printf("%s %.1f", k ? "," : "", h->height_m[k] * 1e3);
        printf(" mm)");
    }
    putchar('\n');
}

static void print_liftoff(const char *label, const jc_TrackHops *h)
{
    if (isnan(h->first_liftoff_t_s)) printf("  %-28s none\n", label);
    else printf("  %-28s t = %.4f s, x = %.2f cm (the last frame in contact)\n", label, h->first_liftoff_t_s,
                h->first_liftoff_x_m * 100);
}

static void report(const jc_Model *m, const jc_Track *t, const jc_TrackCompare *c, int setup_start)
{
    const jc_State *s = &c->launch.start;
    cli_track_print_launch(t, &c->launch);
    printf("Start (%s) at t = %.4f s: x = %.2f cm, %s, theta = %.4f rad, omega = %.4f rad/s\n\n",
           setup_start ? "the setup's theta0 and omega0" : "the state the frames show, fitted to the next 0.4 s",
           s->t_s, s->x_m * 100, s->y_m > m->body.radius_m ? "in flight" : "rolling", s->theta_rad, s->omega_radps);
    printf("Hops: the centre more than %.2f mm (%.0f sigma) above contact in 2 frames or more\n", t->hop_threshold_m * 1e3,
           t->hop_sigmas);
    print_liftoff("measured first lift-off", &c->measured);
    print_liftoff("simulated first lift-off", &c->simulated);
    if (isnan(c->model_liftoff_t_s)) printf("  %-28s none\n", "model's own lift-off event");
    else printf("  %-28s t = %.4f s, x = %.2f cm\n", "model's own lift-off event", c->model_liftoff_t_s,
                c->model_liftoff_x_m * 100);
    print_hops("measured hops", &c->measured);
    print_hops("simulated hops", &c->simulated);
    printf("  %-28s %d lift-off(s), %d bounce(s), largest %.2f mm\n\n", "model's own events", c->model_liftoffs,
           c->model_bounces, c->model_largest_hop_m * 1e3);
    printf("Residuals (tracked - model) over %ld frames:\n  centre's path: RMS %.3f mm (%.2f sigma), largest %.3f mm\n",
           c->count, c->rms_path_m * 1e3, c->rms_path_m / t->sigma_m, c->max_path_m * 1e3);
    if (t->has_mark && isfinite(c->rms_theta_rad)) printf("  mark's angle:  RMS %.4f rad\n", c->rms_theta_rad);
    printf("  (agreement at the noise is an RMS of the path near sqrt(2) sigma%s)\n",
           t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? "; the centre here is recovered from the mark" : "");
}

static int figure(const char *out, const jc_Setup *setup, const jc_Model *m, const jc_Track *t, const jc_TrackCompare *c,
                  const jc_SimOptions *o, int argc, char **argv)
{
    cli_TrackFigure f;
    memset(&f, 0, sizeof f);
    f.track = t;
    f.first = c->first;
    f.count = c->count;
    f.sim_x = c->x_m;
    f.sim_y = c->y_m;
    f.sim_theta = c->theta_rad;
    f.mark_radius_m = t->has_mark ? jc_track_mark_radius(t, m) : 0.0;
    f.sigma_m = t->sigma_m;
    f.hop_threshold_m = t->hop_threshold_m;
    snprintf(f.title, sizeof f.title, "jumpcyl compare: %.4g° incline; path residuals RMS %.2f mm (%.2f σ)",
             cli_deg(t->incline_rad), c->rms_path_m * 1e3, c->rms_path_m / t->sigma_m);
    return cli_track_figure_draw("compare", "out of memory for the figure's path", &f, setup, &c->launch.start, NULL, o,
                                 out, argc, argv);
}

int cmd_compare(int argc, char **argv)
{
    cli_TrackArgs a;
    memset(&a, 0, sizeof a);
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_command_parse(argc, argv, &command, &a, &sa, &sim_args);
    if (st != CLI_GO_ON) return st;
    if ((st = cli_track_args_check("compare", &a)) != EXIT_OK) return st;
    jc_Setup setup;
    jc_SimOptions opts;
    if ((st = cli_build_inputs("compare", &sa, &sim_args, &setup, &opts, NULL)) != EXIT_OK) return st;
    jc_Track t;
    if ((st = cli_track_args_load_for_model("compare", &a, &sa, &setup, &t)) != EXIT_OK) return st;
    /* The setup the runs use, its ramp without their margin uphill: printed,
     * and its body for the report and the figure (built once: a failure is
     * an error, not a setup left unprinted). */
    jc_Setup shown = jc_track_setup(&setup, &t);
    shown.ramp_length_m -= JC_TRACK_RAMP_MARGIN_M;
    jc_Model model;
    char err[512];
    jc_TrackCompare c;
    if ((st = jc_model_init(&model, &shown, err, sizeof err)) != JC_OK ||
        (st = jc_track_compare(&setup, &t, &opts, a.from_setup_start ? JC_TRACK_START_SETUP : JC_TRACK_START_TRACKED,
                               a.from_s, a.to_s, a.mark_angle_rad, &c, err, sizeof err)) != JC_OK) {
        cli_error("compare: %s", err);
        jc_track_free(&t);
        return cli_exit_status(st, CLI_INPUTS_VIDEO);
    }
    cli_track_print_head(a.track, &t, c.first, c.count);
    cli_print_setup(stdout, &model, 1);
    putchar('\n');
    report(&model, &t, &c, a.from_setup_start);
    st = a.output ? figure(a.output, &setup, &model, &t, &c, &opts, argc, argv) : EXIT_OK;
    if (st == EXIT_OK && a.output) printf("Figure: %s\n", a.output);
    jc_track_compare_free(&c);
    jc_track_free(&t);
    return st == EXIT_OK ? cli_stdout_finish() : st;
}
