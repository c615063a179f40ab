/* What compare and fit share: the track file and how to read it, the time
 * window, the figure's file, and the model's fine path for the figure. */
#include "figures.h"
#include "plot.h"
#include "track_fit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int cli_track_args_take(const char *cmd, cli_TrackArgs *a, int opt, const char *arg)
{
    switch (opt) {
    case CLI_TRACK_OPT_TRACK: return cli_take_once(cmd, &a->track, "track", arg);
    case CLI_TRACK_OPT_CENTRE: return cli_take_once(cmd, &a->centre, "centre", arg);
    case CLI_TRACK_OPT_MASS: return cli_take_once(cmd, &a->mass, "mass", arg);
    case CLI_TRACK_OPT_AXES: return cli_take_once(cmd, &a->axes, "axes", arg);
    case CLI_TRACK_OPT_FROM: return cli_take_once(cmd, &a->from, "from", arg);
    case CLI_TRACK_OPT_TO: return cli_take_once(cmd, &a->to, "to", arg);
    case CLI_TRACK_OPT_OUTPUT: return cli_take_once(cmd, &a->output, "output", arg);
    case CLI_TRACK_OPT_SETUP_START: a->from_setup_start = 1; return 0;
    default: return 1; /* not one of these */
    }
}

void cli_track_args_help(void)
{
    puts("  --track FILE        the tracked video: a Tracker .trk file or a data table it exported\n"
         "                      (see 'jumpcyl track --help'); required\n"
         "  --centre TRACK      the axle's track (default: as 'jumpcyl track' picks it)\n"
         "  --mass TRACK        the off-centre mark's track; --mass '' for none\n"
         "  --axes level|incline  how Tracker's axes were laid (default: level, y up)\n"
         "  --from T, --to T    the frames from T to T (s; default: all)\n"
         "  --from-setup-start  start the model with the setup's theta0 and omega0 at the first\n"
         "                      frame's position, not with the state the first frames show\n"
         "                      (with --theta0 and --omega0: a start of your own)\n"
         "  --output FILE       the figure (gnuplot): .png, .svg or .pdf, written whole or not at all");
}

static int parse_time(const char *cmd, const char *name, const char *text, double *out)
{
    char err[256];
    if (!text) {
        *out = NAN;
        return 0;
    }
    if (cli_parse_quantity(text, Q_TIME, out, err, sizeof err) != 0 || !(*out >= 0.0 && *out <= 1e6)) {
        cli_error("%s: --%s '%s' is not a time from 0 to 1e6 s", cmd, name, text);
        return EXIT_USAGE;
    }
    return 0;
}

int cli_track_args_check(const char *cmd, const cli_TrackArgs *a, double *from_s, double *to_s)
{
    if (!a->track || !*a->track) {
        cli_error("%s: --track FILE is required (a Tracker .trk file or an exported data table)", cmd);
        return EXIT_USAGE;
    }
    if (a->axes && strcmp(a->axes, "level") != 0 && strcmp(a->axes, "incline") != 0) {
        cli_error("%s: --axes '%s' (allowed: level, incline)", cmd, a->axes);
        return EXIT_USAGE;
    }
    int rc = parse_time(cmd, "from", a->from, from_s);
    if (rc == 0) rc = parse_time(cmd, "to", a->to, to_s);
    if (rc != 0) return rc;
    if (!isnan(*from_s) && !isnan(*to_s) && !(*from_s < *to_s)) {
        cli_error("%s: --from %g s is not before --to %g s", cmd, *from_s, *to_s);
        return EXIT_USAGE;
    }
    if (a->output) {
        const char *ext = cli_path_ext(a->output);
        if (strcasecmp(ext, "png") != 0 && strcasecmp(ext, "svg") != 0 && strcasecmp(ext, "pdf") != 0) {
            cli_error("%s: --output '%s': the format follows the extension (allowed: .png, .svg, .pdf)", cmd,
                      a->output);
            return EXIT_USAGE;
        }
        if (cli_output_check_target(a->output) != 0) return EXIT_FAIL;
        char gnuplot[CLI_PATH_MAX];
        if (cli_find_program("gnuplot", gnuplot, sizeof gnuplot) != 0) {
            cli_error("%s: gnuplot was not found in PATH; install it (Debian: sudo apt-get install gnuplot-nox)",
                      cmd);
            return EXIT_FAIL;
        }
    }
    return 0;
}

int cli_track_args_load(const char *cmd, const cli_TrackArgs *a, const jc_Model *m, cli_Track *t)
{
    cli_TrackOptions opt;
    cli_track_options_default(&opt);
    opt.centre = a->centre;
    opt.mark = a->mass;
    opt.incline_rad = m->setup.incline_rad;
    opt.radius_m = m->body.radius_m;
    opt.axes = a->axes && strcmp(a->axes, "incline") == 0 ? CLI_TRACK_AXES_INCLINE : CLI_TRACK_AXES_LEVEL;
    char err[512];
    if (cli_track_load(a->track, &opt, t, err, sizeof err) != 0) {
        cli_error("%s: %s", cmd, err);
        return EXIT_USAGE;
    }
    if (!(t->sigma_m > 0.0)) {
        cli_track_free(t);
        cli_error("%s: %s: no position noise could be told (no scale, too few frames)", cmd, a->track);
        return EXIT_USAGE;
    }
    return 0;
}

void cli_track_print_head(const char *file, const cli_Track *t, long first, long count)
{
    printf("Track: %s: %ld of %ld frames used (t = %.4f to %.4f s), %.4g fps nominal, %ld gap(s);\n"
           "       noise sigma %.3g mm; mark %s\n",
           file, count, t->n, t->t_s[first], t->t_s[first + count - 1], t->frame_rate_hz, t->gaps, t->sigma_m * 1e3,
           t->has_mark ? "tracked" : "not tracked (theta is not compared)");
}

/* The model's path every quarter frame, for the figure's curves. */
int cli_track_fine_path(const jc_Setup *setup, const cli_Track *t, const jc_State *start, const jc_SimOptions *o,
                        double t_end_s, double **pt, double **px, double **py, long *n)
{
    jc_Setup at_start = *setup;
    at_start.theta0_rad = start->theta_rad;
    at_start.omega0_radps = start->omega_radps;
    jc_Model model;
    char err[256];
    if (cli_track_model(&at_start, &model, err, sizeof err) != 0) return -1;
    const double dt = 0.25 / (t->frame_rate_hz > 0.0 ? t->frame_rate_hz : 60.0);
    const double span = t_end_s - start->t_s;
    *n = span > 0.0 ? (long)fmin(floor(span / dt) + 1.0, 2e6) : 1;
    *pt = malloc((size_t)*n * sizeof **pt);
    *px = malloc((size_t)*n * sizeof **px);
    *py = malloc((size_t)*n * sizeof **py);
    cli_TrackSim sim;
    if (!*pt || !*px || !*py || cli_track_sim_init(&sim) != 0) return -1;
    for (long i = 0; i < *n; ++i) (*pt)[i] = start->t_s + (double)i * dt;
    sim.shift_m = cli_track_sim_shift(t);
    const int rc = cli_track_sim_run(&sim, &model, start, o, *pt, *n, *px, *py, NULL, err, sizeof err);
    cli_track_sim_free(&sim);
    return rc;
}

int cli_track_figure_draw(const char *cmd, cli_TrackFigure *f, const jc_Setup *setup, const jc_Model *m,
                          const jc_State *start, const jc_SimOptions *o, const char *out, int argc, char **argv)
{
    const cli_Track *t = f->track;
    double *pt = NULL, *px = NULL, *py = NULL;
    int rc = cli_track_fine_path(setup, t, start, o, t->t_s[f->first + f->count - 1], &pt, &px, &py, &f->path_n);
    if (rc == 0) {
        f->path_t = pt;
        f->path_x = px;
        f->path_y = py;
        f->radius_m = m->body.radius_m;
        f->incline_rad = m->setup.incline_rad;
        char cmdline[2048];
        fig_command_line(argc, argv, cmdline, sizeof cmdline);
        rc = cli_track_figure(cmd, f, out, cmdline);
        f->path_t = f->path_x = f->path_y = NULL;
    } else {
        rc = CLI_TRACK_FIGURE_NO_PATH;
    }
    free(pt);
    free(px);
    free(py);
    return rc;
}
