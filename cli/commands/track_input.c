/* What track, compare and fit share: the track file and how to read it, the
 * time window, the mark's angle, the figure's file, and the model's fine
 * path for the figure. */
#include "commands.h"

#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

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
    case CLI_TRACK_OPT_MARK_ANGLE: return cli_take_once(cmd, &a->mark_angle, "mark-angle", arg);
    case CLI_TRACK_OPT_HOP_SIGMAS: return cli_take_once(cmd, &a->hop_sigmas, "hop-sigmas", arg);
    case CLI_TRACK_OPT_SETUP_START: a->from_setup_start = 1; return CLI_GO_ON;
    case CLI_TRACK_OPT_FIT_TILT: a->fit_tilt = 1; return CLI_GO_ON;
    default: return EXIT_USAGE; /* not one of these (getopt passes none such) */
    }
}

void cli_track_args_help(int window)
{
    if (window)
        puts("  --track FILE        the tracked video: a Tracker .trk file or a data table it exported\n"
             "                      (see 'jumpcyl track --help'); required");
    puts("  --centre TRACK      the axle's track (default: the track named centre, center, axle, axis\n"
         "                      or hub; or told by its motion: the one that keeps to a line)\n"
         "  --mass TRACK        the off-centre mark's track (default: the track named mark, rod, dot,\n"
         "                      off, led, rim, light, lamp or spot, or the other of two); --mass ''\n"
         "                      for none. A file with a mark alone (an LED on the rim) is read too:\n"
         "                      the centre is recovered by fitting rolling to it\n"
         "  --axes level        Tracker's axes are level, y up (Tracker's default; the default): the\n"
         "                      incline's angle is measured from the frames in contact\n"
         "  --axes incline      Tracker's x axis was laid along the incline (its angle is then not\n"
         "                      in the video: give --incline for compare and fit)\n"
         "  --incline ANGLE     (a setup option) checked against the video's: refused when the frames\n"
         "                      in contact lie more than 3 sigma and 2 deg away; without it the\n"
         "                      video's angle is used, never a preset's\n"
         "  --hop-sigmas K      a hop: the centre more than K sigma above the surface for 2 frames or\n"
         "                      more (sigma: the noise of the frames in contact; default 5)\n"
         "  --fit-tilt          the surface is the line through the frames in contact even where it\n"
         "                      agrees with the incline given");
    if (!window) return;
    puts("  --from T, --to T    the frames from T to T (s; default: all). --from sets where the free\n"
         "                      motion starts; without it, frames at the start that the model cannot\n"
         "                      follow (a hand's push) are found and left out\n"
         "  --from-setup-start  the start at the first frame used (no push is looked for): its\n"
         "                      position with the setup's theta0 and omega0, not the state the\n"
         "                      frames show. compare runs the model from it; fit's start values\n"
         "                      begin there and are fitted with the others, unless --hold-start,\n"
         "                      which holds them there\n"
         "  --mark-angle ANGLE  the tracked mark's angle on the body, as a part's angle (default 0:\n"
         "                      the reference direction, where the paper's rod and the hoop's mass sit)\n"
         "  --output FILE       the figure (gnuplot): .png, .svg or .pdf, written whole or not at all");
}

static int parse_time(const char *cmd, const char *name, const char *text, double *out)
{
    char err[256];
    if (!text) {
        *out = NAN;
        return EXIT_OK;
    }
    if (cli_parse_quantity(text, Q_TIME, out, err, sizeof err) != 0 || !(*out >= 0.0 && *out <= 1e6)) {
        cli_error("%s: --%s '%s' is not a time from 0 to 1e6 s", cmd, name, text);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

int cli_track_args_check_reading(const char *cmd, cli_TrackArgs *a)
{
    if (a->axes && strcmp(a->axes, "level") != 0 && strcmp(a->axes, "incline") != 0) {
        cli_error("%s: --axes '%s' (allowed: level, incline)", cmd, a->axes);
        return EXIT_USAGE;
    }
    if (a->hop_sigmas) {
        char err[256];
        double k;
        if (cli_parse_quantity(a->hop_sigmas, Q_NUMBER, &k, err, sizeof err) != 0 || !(k >= 1 && k <= 100)) {
            cli_error("%s: --hop-sigmas '%s': a number from 1 to 100", cmd, a->hop_sigmas);
            return EXIT_USAGE;
        }
        a->hop_sigmas_k = k;
    }
    return EXIT_OK;
}

int cli_track_args_check(const char *cmd, cli_TrackArgs *a)
{
    a->from_s = a->to_s = NAN;
    a->mark_angle_rad = 0.0;
    if (!a->track || !*a->track) {
        cli_error("%s: --track FILE is required (a Tracker .trk file or an exported data table)", cmd);
        return EXIT_USAGE;
    }
    int rc = cli_track_args_check_reading(cmd, a);
    if (rc == EXIT_OK) rc = parse_time(cmd, "from", a->from, &a->from_s);
    if (rc == EXIT_OK) rc = parse_time(cmd, "to", a->to, &a->to_s);
    if (rc != EXIT_OK) return rc;
    if (!isnan(a->from_s) && !isnan(a->to_s) && !(a->from_s < a->to_s)) {
        cli_error("%s: --from %g s is not before --to %g s", cmd, a->from_s, a->to_s);
        return EXIT_USAGE;
    }
    if (a->mark_angle) {
        char err[256];
        if (cli_parse_quantity(a->mark_angle, Q_ANGLE, &a->mark_angle_rad, err, sizeof err) != 0 ||
            !(fabs(a->mark_angle_rad) <= 2 * CLI_PI)) {
            cli_error("%s: --mark-angle '%s': an angle from -360 to 360 deg", cmd, a->mark_angle);
            return EXIT_USAGE;
        }
    }
    if (cli_output_file_only(cmd, "output", a->output, "a figure") != 0) return EXIT_USAGE;
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
    return EXIT_OK;
}

/* Whether the incline was given: --incline, or an experiment file's key. */
static int incline_given(const cli_SetupArgs *sa)
{
    if (cli_setup_given(sa, "incline")) return 1;
    if (!sa->config) return 0;
    jc_Setup probe;
    memset(&probe, 0, sizeof probe);
    probe.incline_rad = NAN;
    char err[256];
    return cli_config_load(sa->config, &probe, err, sizeof err) == 0 && !isnan(probe.incline_rad);
}

/* The file's bytes, read here rather than by jc_track_read_file: the open
 * never waits (a FIFO without a writer yet), and the first stop signal ends
 * a wait for a pipe's or FIFO's writer (cli_read_all: poll). EXIT_OK, the
 * stop status (main says it), or an exit status after a message. */
static int read_track_bytes(const char *cmd, const char *path, char **data, size_t *len)
{
    char why[256];
    const int fd = cli_open_nowait(path, O_RDONLY, 0, 0, why, sizeof why);
    if (fd < 0) {
        cli_error("%s: %s: cannot open: %s", cmd, path, why);
        return EXIT_USAGE;
    }
    struct stat st;
    int r;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > (off_t)JC_TRACK_MAX_BYTES) {
        snprintf(why, sizeof why, "larger than %ld bytes", JC_TRACK_MAX_BYTES); /* refused before reading */
        r = -1;
    } else {
        r = cli_read_all(fd, JC_TRACK_MAX_BYTES, data, len, why, sizeof why);
    }
    close(fd);
    if (r > 0) return cli_stop_status();
    if (r < 0) {
        cli_error("%s: %s: %s", cmd, path, why);
        return strcmp(why, "out of memory") == 0 ? EXIT_FAIL : EXIT_USAGE;
    }
    return EXIT_OK;
}

int cli_track_args_load(const char *cmd, const char *path, const cli_TrackArgs *a, const cli_SetupArgs *sa,
                        const jc_Setup *setup, jc_Track *t)
{
    jc_TrackOptions opt;
    jc_track_options_default(&opt);
    opt.centre = a->centre;
    opt.mark = a->mass;
    opt.incline_rad = incline_given(sa) ? setup->incline_rad : NAN;
    opt.radius_m = setup->body.radius_m;
    opt.gravity_mps2 = setup->gravity_mps2;
    opt.fit_tilt = a->fit_tilt;
    opt.axes = a->axes && strcmp(a->axes, "incline") == 0 ? JC_TRACK_AXES_INCLINE : JC_TRACK_AXES_LEVEL;
    if (a->hop_sigmas) opt.hop_sigmas = a->hop_sigmas_k;
    char *data;
    size_t len;
    memset(t, 0, sizeof *t);
    const int rc = read_track_bytes(cmd, path, &data, &len);
    if (rc != EXIT_OK) return rc;
    char err[1024];
    const int st = jc_track_parse(path, data, len, &opt, t, err, sizeof err);
    free(data);
    if (st != JC_OK) cli_error("%s: %s", cmd, err);
    return cli_exit_status(st, CLI_INPUTS_VIDEO);
}

int cli_track_args_load_for_model(const char *cmd, const cli_TrackArgs *a, const cli_SetupArgs *sa, jc_Setup *setup,
                                  jc_Track *t)
{
    int rc = cli_track_args_load(cmd, a->track, a, sa, setup, t);
    if (rc != EXIT_OK) return rc;
    char err[1024];
    if ((rc = jc_track_require(a->track, t, JC_TRACK_NEED_CENTRE | JC_TRACK_NEED_INCLINE, err, sizeof err)) != JC_OK) {
        jc_track_free(t);
        cli_error("%s: %s", cmd, err);
        return cli_exit_status(rc, CLI_INPUTS_VIDEO);
    }
    setup->incline_rad = t->incline_rad;
    return EXIT_OK;
}

const char *const cli_track_centre_sources[JC_TRACK_CENTRE_FROM_MARK + 1] = {"none", "tracked", "recovered from the mark"};

void cli_track_print_head(const char *file, const jc_Track *t, long first, long count)
{
    printf("Track: %s: %ld of %ld frames used (t = %.4f to %.4f s), %.4g fps nominal, %ld gap(s);\n"
           "       noise sigma %.3g mm (the frames %s); centre %s; mark %s\n",
           file, count, t->n, t->t_s[first], t->t_s[first + count - 1], t->frame_rate_hz, t->gaps, t->sigma_m * 1e3,
           t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? "the mark rolls in" : "in contact",
           cli_track_centre_sources[t->centre_source], t->has_mark ? "tracked" : "not tracked (theta is not compared)");
    printf("       incline %.2f deg (%s)\n", cli_deg(t->incline_rad),
           t->incline_source == JC_TRACK_INCLINE_MEASURED ? "measured from the video" : "as given");
}

/* The model's path every quarter frame, for the figure's curves. */
int cli_track_fine_path(const jc_Setup *setup, const jc_Track *t, const jc_State *start,
                        const jc_TrackFitFrame *frame, const jc_SimOptions *o, double t_end_s, double **pt,
                        double **px, double **py, long *n)
{
    const double dt = 0.25 / (t->frame_rate_hz > 0.0 ? t->frame_rate_hz : 60.0);
    const double span = t_end_s - start->t_s;
    *n = span > 0.0 ? (long)fmin(floor(span / dt) + 1.0, 2e6) : 1;
    *pt = malloc((size_t)*n * sizeof **pt);
    *px = malloc((size_t)*n * sizeof **px);
    *py = malloc((size_t)*n * sizeof **py);
    if (!*pt || !*px || !*py) return -1;
    for (long i = 0; i < *n; ++i) (*pt)[i] = start->t_s + (double)i * dt;
    char err[256];
    return jc_track_model_path(setup, t, start, frame, o, *pt, *n, *px, *py, NULL, err, sizeof err) == JC_OK ? 0 : -1;
}

int cli_track_figure_draw(const char *cmd, const char *no_path, cli_TrackFigure *f, const jc_Setup *setup,
                          const jc_State *start, const jc_TrackFitFrame *frame, const jc_SimOptions *o, const char *out,
                          int argc, char **argv)
{
    const jc_Track *t = f->track;
    double *pt = NULL, *px = NULL, *py = NULL;
    int rc = EXIT_FAIL;
    if (cli_track_fine_path(setup, t, start, frame, o, t->t_s[f->first + f->count - 1], &pt, &px, &py, &f->path_n) ==
        0) {
        f->path_t = pt;
        f->path_x = px;
        f->path_y = py;
        f->radius_m = t->radius_m;
        char cmdline[2048];
        fig_command_line(argc, argv, cmdline, sizeof cmdline);
        rc = cli_track_figure(cmd, f, out, cmdline);
        f->path_t = f->path_x = f->path_y = NULL;
    } else {
        cli_error("%s: %s", cmd, no_path);
    }
    free(pt);
    free(px);
    free(py);
    return rc;
}

void cli_track_print_launch(const jc_Track *t, const jc_TrackLaunch *L)
{
    if (L->pushed <= 0) return;
    printf("Launch: the first %ld frame(s) (to t = %.4f s) show a push the model cannot follow (chi2/dof %.3g\n"
           "        with them, %.3g from frame %ld): the free motion starts at t = %.4f s\n",
           L->pushed, t->t_s[L->frame - 1], L->chi2_dof_with, L->chi2_dof, L->frame, t->t_s[L->frame]);
}
