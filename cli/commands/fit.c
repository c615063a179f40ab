/* jumpcyl fit: setup values and the start fitted to a tracked video by
 * nonlinear least squares from many start points, with what the video
 * determines and a verdict on the fit (docs/tracker.md, "Fit"). */
#include "commands.h"
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_MAX_ITER 100
#define MAX_MAX_ITER 10000
#define MAX_STARTS 10000

typedef struct {
    cli_TrackArgs track;
    const char *free_list, *loss, *max_iter, *sigma, *starts, *seed;
    int allow_misfit, hold_start;
} fit_opts;

static void help(void)
{
    puts("Usage: jumpcyl fit --track FILE --free LIST [--loss linear|huber|cauchy] [--max-iter N]\n"
         "                   [--sigma LEN] [--starts N] [--seed N] [--hold-start] [--allow-misfit]\n"
         "                   [--from T] [--to T] [--output FIG] [SETUP OPTIONS]\n"
         "Fits setup values and the start to the tracked frames by nonlinear least squares (GSL,\n"
         "Levenberg-Marquardt), from many start points: a Latin hypercube over the bounded values\n"
         "is screened and the best few descended from, as the first lift-off leaps between\n"
         "branches when the values change. The residuals are the centre's x and y at every frame\n"
         "and the mark's displacement across its radius (or the mark's x and y, when the centre\n"
         "was recovered from it), in units of the noise. Reports each value with its standard\n"
         "error (scaled by chi2/dof when the noise is the measured one), their correlations, the\n"
         "minima that compete with the best, the values the video does not determine (held, with a\n"
         "chi2 profile along their range), the predicted first lift-off, and a verdict: whether the\n"
         "model describes the video (chi2/dof at most 3, no long runs of same-sign residuals, the\n"
         "same hops). Exit 3 when it does not, unless --allow-misfit (docs/tracker.md).\n"
         "\n"
         "  --free LIST         comma-separated values to fit (mu_k for mu-k will do): mu-s, mu-k,\n"
         "                      restitution, mark-angle, theta0, omega0, x0, tilt, surface, and the\n"
         "                      body's: disc-mass, hoop-mass, rod-mass, rod-offset, point-mass,\n"
         "                      point-offset (those its parts have); at most 9, each kept in its\n"
         "                      physical range (0 <= mu-k <= mu-s <= 2, 0 <= e <= 1, offsets inside\n"
         "                      the rim). The start (x0, theta0, omega0 at the first frame of the\n"
         "                      free motion) and the video frame's tilt and surface are always\n"
         "                      fitted with them; a start value named here is fitted even with\n"
         "                      --hold-start\n"
         "  --hold-start        hold the start instead, at the state fitted to the first 0.4 s with\n"
         "                      the setup's values\n"
         "  --loss KIND         linear (default), huber or cauchy: robust, by reweighting\n"
         "  --max-iter N        trust-region iterations per descent (default 100)\n"
         "  --sigma LEN         the position noise (default: the track's, measured from the frames in\n"
         "                      contact; standard errors are then scaled by chi2/dof)\n"
         "  --starts N          points of the Latin hypercube screened (default: 8 per bounded\n"
         "                      value + 8, 16 to 64); the setup's own values are screened too, so\n"
         "                      the report counts N + 1\n"
         "  --seed N            the screening's Latin hypercube (default 1)\n"
         "  --allow-misfit      exit 0 even when the verdict is that the model does not describe the\n"
         "                      video (the report says so all the same)");
    cli_track_args_help(1);
    puts("  -h, --help          this help\n"
         "The other setup values are held at the setup options' values; the free ones start from\n"
         "them.\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    fit_opts *o = ctx;
    switch (opt) {
    case 'f': return cli_take_once("fit", &o->free_list, "free", arg);
    case 'l': return cli_take_once("fit", &o->loss, "loss", arg);
    case 'i': return cli_take_once("fit", &o->max_iter, "max-iter", arg);
    case 's': return cli_take_once("fit", &o->sigma, "sigma", arg);
    case 'n': return cli_take_once("fit", &o->starts, "starts", arg);
    case 'r': return cli_take_once("fit", &o->seed, "seed", arg);
    case 'a': o->allow_misfit = 1; return CLI_GO_ON;
    case 'H': o->hold_start = 1; return CLI_GO_ON;
    default: return cli_track_args_take("fit", &o->track, opt, arg);
    }
}

static const struct option own[] = {CLI_TRACK_ARG_OPTIONS,
                                    {"free", required_argument, 0, 'f'},
                                    {"loss", required_argument, 0, 'l'},
                                    {"max-iter", required_argument, 0, 'i'},
                                    {"sigma", required_argument, 0, 's'},
                                    {"starts", required_argument, 0, 'n'},
                                    {"seed", required_argument, 0, 'r'},
                                    {"allow-misfit", no_argument, 0, 'a'},
                                    {"hold-start", no_argument, 0, 'H'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

static int whole(const char *text, const char *name, double lo, double hi, double *v)
{
    char err[256];
    if (cli_parse_quantity(text, Q_NUMBER, v, err, sizeof err) != 0 || !(*v >= lo && *v <= hi) || *v != floor(*v)) {
        cli_error("fit: --%s '%s' (allowed: a whole number from %.0f to %.0f)", name, text, lo, hi);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* A value's name as the options spell it ("mu-k", "rod-offset"): the
 * library's name ("mu_k", the Python package's key) with '-' for '_'. */
static void fit_name(const jc_Setup *s, jc_TrackFitParam p, char *buf, size_t len)
{
    jc_fit_param_name(s, p, buf, len);
    for (char *c = buf; *c; ++c)
        if (*c == '_') *c = '-';
}

/* The names the setup's body allows, comma-separated, for messages. */
static void allowed_names(const jc_Setup *s, char *buf, size_t len)
{
    jc_TrackFitParam p[JC_FIT_MAX_PARAMS * 2];
    const int n = jc_fit_param_list(s, p, (int)(sizeof p / sizeof p[0]));
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; k < n && k < (int)(sizeof p / sizeof p[0]) && used < len; ++k) {
        char name[48];
        fit_name(s, p[k], name, sizeof name);
        used += (size_t)snprintf(buf + used, len - used, "%s%s", k ? ", " : "", name);
    }
}

/* --free's comma-separated names ("mu-k,restitution,rod_offset") into out;
 * 0, or -1 with a one-line message naming the bad entry and what is
 * allowed. */
static int parse_free(const char *text, const jc_Setup *s, jc_TrackFitParam *out, int *count, char *err,
                      size_t err_len)
{
    *count = 0;
    char allowed[512];
    allowed_names(s, allowed, sizeof allowed);
    const char *p = text;
    while (*p) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char name[32];
        jc_TrackFitParam v;
        int known = len < sizeof name;
        if (known) {
            memcpy(name, p, len);
            name[len] = '\0';
            known = jc_fit_param_find(s, name, &v) == JC_OK;
        }
        if (!known) {
            snprintf(err, err_len, "--free '%s': '%.*s' is not a value the fit can free for this body (allowed: %s)",
                     text, (int)(len > 40 ? 40 : len), p, allowed);
            return -1;
        }
        for (int k = 0; k < *count; ++k)
            if (out[k].kind == v.kind && out[k].part == v.part) {
                snprintf(err, err_len, "--free '%s': '%.*s' is named twice", text, (int)(len > 40 ? 40 : len), p);
                return -1;
            }
        /* Room for the start's three values and the frame's two. */
        if (*count == JC_FIT_MAX_PARAMS - 5) {
            snprintf(err, err_len, "--free '%s': more than %d values", text, JC_FIT_MAX_PARAMS - 5);
            return -1;
        }
        out[(*count)++] = v;
        if (!comma) break;
        p = comma + 1;
    }
    if (*count == 0) {
        snprintf(err, err_len, "--free '%s' names no value (allowed: %s)", text, allowed);
        return -1;
    }
    return 0;
}

/* The fit's own options into fo; 0 or EXIT_USAGE after a one-line message. */
static int check(const fit_opts *o, const jc_Setup *setup, jc_TrackFitOptions *fo)
{
    char err[1024];
    jc_fit_options_default(fo);
    if (!o->free_list) {
        char allowed[512];
        allowed_names(setup, allowed, sizeof allowed);
        cli_error("fit: --free LIST is required (allowed: %s)", allowed);
        return EXIT_USAGE;
    }
    if (parse_free(o->free_list, setup, fo->free, &fo->free_count, err, sizeof err) != 0) {
        cli_error("fit: %s", err);
        return EXIT_USAGE;
    }
    if (o->loss && jc_fit_loss_parse(o->loss, &fo->loss) != 0) {
        cli_error("fit: --loss '%s' (allowed: linear, huber, cauchy)", o->loss);
        return EXIT_USAGE;
    }
    double v;
    if (o->max_iter) {
        if (whole(o->max_iter, "max-iter", 1, MAX_MAX_ITER, &v) != EXIT_OK) return EXIT_USAGE;
        fo->max_iter = (int)v;
    }
    if (o->starts) {
        if (whole(o->starts, "starts", 1, MAX_STARTS, &v) != EXIT_OK) return EXIT_USAGE;
        fo->starts = (int)v;
    }
    if (o->seed && cli_parse_seed("fit", o->seed, &fo->seed) != EXIT_OK) return EXIT_USAGE;
    if (o->sigma && (cli_parse_quantity(o->sigma, Q_LENGTH, &fo->sigma_m, err, sizeof err) != 0 ||
                     !(fo->sigma_m > 0.0 && fo->sigma_m <= 1.0))) {
        cli_error("fit: --sigma '%s' (allowed: a length in (0, 1] m, e.g. 1mm)", o->sigma);
        return EXIT_USAGE;
    }
    fo->hold_start = o->hold_start;
    fo->from_s = o->track.from_s;
    fo->to_s = o->track.to_s;
    fo->mark_angle_rad = o->track.mark_angle_rad;
    fo->start = o->track.from_setup_start ? JC_TRACK_START_SETUP : JC_TRACK_START_TRACKED;
    return EXIT_OK;
}

static void name_of(const jc_TrackFitResult *r, int k, char *buf, size_t len)
{
    char base[48];
    fit_name(&r->setup, r->param[k], base, sizeof base);
    const jc_TrackFitKind kind = r->param[k].kind;
    snprintf(buf, len, "%s%s", base,
             !r->start_value[k] ? "" : kind == JC_FIT_TILT || kind == JC_FIT_SURFACE ? " (frame)" : " (start)");
}

/* " unit", or "" for a value without one. */
static const char *spaced_unit(const jc_TrackFitResult *r, int k, char *buf, size_t len)
{
    const char *u = jc_fit_param_unit(r->param[k]);
    snprintf(buf, len, "%s%s", u[0] ? " " : "", u);
    return buf;
}

static void print_values(const jc_TrackFitResult *r)
{
    printf("  %-20s %13s   %13s %s\n", "value", "initial", "fitted", "+- standard error");
    for (int k = 0; k < r->count; ++k) {
        char nm[64];
        name_of(r, k, nm, sizeof nm);
        char u[16];
        printf("  %-20s %13.6g   %13.6g ", nm, r->initial[k], r->value[k]);
        if (r->flag[k] == JC_FIT_DETERMINED) printf("+- %.3g%s\n", r->sigma[k], spaced_unit(r, k, u, sizeof u));
        else printf("held (below)\n");
    }
}

static void print_held(const jc_TrackFitResult *r)
{
    int any = 0;
    for (int k = 0; k < r->count; ++k) any |= r->flag[k] != JC_FIT_DETERMINED;
    if (!any) return;
    printf("\nHeld, as the video does not determine them inside their ranges (the others fitted again):\n");
    for (int k = 0; k < r->count; ++k) {
        if (r->flag[k] == JC_FIT_DETERMINED) continue;
        char nm[64];
        name_of(r, k, nm, sizeof nm);
        printf("  %s: %s", nm, jc_fit_flag_text(r->flag[k]));
        if (r->flag[k] == JC_FIT_WIDER_THAN_RANGE)
            printf(" (%.3g against [%.3g, %.3g])", r->sigma[k], r->lo[k], r->hi[k]);
        if (r->flag[k] == JC_FIT_CORRELATED && r->other[k] >= 0) {
            char on[64];
            name_of(r, r->other[k], on, sizeof on);
            printf(" (%s, rho = %.4f)", on, r->rho[k]);
        }
        char u[16];
        printf("; held at %.6g%s\n", r->value[k], spaced_unit(r, k, u, sizeof u));
        if (r->profiled[k]) {
            printf("    chi2 along it (the others fitted):");
            double least = INFINITY;
            for (int i = 0; i < JC_FIT_PROFILE_POINTS; ++i) {
                printf("%s %.3g: %.5g", i ? "," : "", r->profile_x[k][i], r->profile_chi2[k][i]);
                least = fmin(least, r->profile_chi2[k][i]);
            }
            /* The values whose chi2 lies within 3.84 (95 % for one value) of
             * the least, the held value (at the fit's chi2) among them. */
            least = fmin(least, r->chi2);
            const double cut = least + 3.84 * fmax(1.0, r->chi2_dof);
            double lo = r->chi2 <= cut ? r->value[k] : INFINITY, hi = r->chi2 <= cut ? r->value[k] : -INFINITY;
            for (int i = 0; i < JC_FIT_PROFILE_POINTS; ++i)
                if (r->profile_chi2[k][i] <= cut) lo = fmin(lo, r->profile_x[k][i]), hi = fmax(hi, r->profile_x[k][i]);
            printf("\n    chi2 within %.3g of its least from %.3g to %.3g%s (of those points and the held value)\n",
                   cut - least, lo, hi, u);
        }
    }
}

static void print_minima(const jc_TrackFitResult *r)
{
    if (r->minima <= 1) {
        printf("\nOther minima within chi2 + %.3g of the best: none of the %d descents found one\n", r->delta_chi2,
               r->descents);
        return;
    }
    printf("\nMinima within chi2 + %.3g of the best (the video does not tell them apart):\n  %10s", r->delta_chi2,
           "chi2");
    for (int k = 0; k < r->count; ++k) {
        char nm[48];
        fit_name(&r->setup, r->param[k], nm, sizeof nm);
        printf(" %12.12s", nm);
    }
    putchar('\n');
    for (int m = 0; m < r->minima; ++m) {
        printf("  %10.5g", r->minimum[m].chi2);
        for (int k = 0; k < r->count; ++k) printf(" %12.5g", r->minimum[m].value[k]);
        putchar('\n');
    }
}

static void print_correlations(const jc_TrackFitResult *r)
{
    printf("\nCorrelations (of the values fitted at the end):\n  %-14s", "");
    for (int k = 0; k < r->count; ++k) {
        if (r->flag[k] != JC_FIT_DETERMINED) continue;
        char nm[48];
        fit_name(&r->setup, r->param[k], nm, sizeof nm);
        printf(" %12.12s", nm);
    }
    putchar('\n');
    for (int i = 0; i < r->count; ++i) {
        if (r->flag[i] != JC_FIT_DETERMINED) continue;
        char nm[48];
        fit_name(&r->setup, r->param[i], nm, sizeof nm);
        printf("  %-14.14s", nm);
        for (int j = 0; j < r->count; ++j)
            if (r->flag[j] == JC_FIT_DETERMINED) printf(" %12.3f", cli_shown(r->corr[i][j], 3));
        putchar('\n');
    }
}

static void report(const char *file, const jc_Track *t, const jc_TrackFitResult *r, const jc_TrackFitOptions *fo)
{
    cli_track_print_head(file, t, r->first, r->frames);
    cli_track_print_launch(t, &r->launch);
    int asked = 0;
    for (int k = 0; k < r->count; ++k) asked += !r->start_value[k];
    printf("Fit: %ld residuals (sigma %.3g mm, %s), %d value(s) asked for, %s%s, loss %s\n", r->residuals,
           r->sigma_m * 1e3, r->noise_measured ? "measured" : "given", asked,
           fo->hold_start ? "the start held" : "the start's x0, theta0, omega0",
           fo->hold_frame ? "" : " and the video frame's tilt and surface", jc_fit_loss_name(fo->loss));
    printf("Search: %d start points screened, %d descents, %d iterations in all\n", r->screened, r->descents,
           r->iterations);
    printf("chi2/dof = %.4g (chi2 %.4g, dof %ld)\n", r->chi2_dof, r->chi2, r->dof);
    const double deg = 180.0 / CLI_PI;
    if (t->incline_source == JC_TRACK_INCLINE_MEASURED && r->incline_sigma_rad > 0.0)
        printf("Incline in the model: %.3f +- %.3f deg (the video's %.3f deg turned by the fitted tilt)\n\n",
               r->setup.incline_rad * deg, r->incline_sigma_rad * deg, t->incline_rad * deg);
    else
        printf("Incline in the model: %.3f deg (%s)\n\n", r->setup.incline_rad * deg,
               t->incline_source == JC_TRACK_INCLINE_MEASURED ? "measured" : "as given");
    print_values(r);
    print_held(r);
    print_minima(r);
    print_correlations(r);
    if (r->has_liftoff)
        printf("\nPredicted first lift-off: x = %.2f +- %.2f cm along the track (t = %.4f s)\n", r->liftoff_x_m * 100,
               r->liftoff_sigma_m * 100, r->liftoff_t_s);
    else
        printf("\nPredicted first lift-off: none (the fitted model does not lift off)\n");
    printf("Residuals at the fit: centre's path RMS %.3f mm", r->rms_path_m * 1e3);
    if (t->has_mark && isfinite(r->rms_theta_rad)) printf(", mark's angle RMS %.4f rad", r->rms_theta_rad);
    printf("\n\nVerdict: %s\n", r->verdict);
}

/* The figure's frames: the track's, and the fitted model's at them (x, y, th). */
static void figure_frames(cli_TrackFigure *f, const jc_Track *t, const jc_TrackFitResult *r, const double *x,
                          const double *y, const double *th)
{
    memset(f, 0, sizeof *f);
    f->track = t;
    f->first = r->first;
    f->count = r->frames;
    f->sim_x = x;
    f->sim_y = y;
    f->sim_theta = th;
    f->mark_radius_m = r->mark_radius_m;
    f->sigma_m = r->sigma_m;
    f->hop_threshold_m = t->hop_threshold_m;
    snprintf(f->title, sizeof f->title, "jumpcyl fit: μ_s = %.4g, μ_k = %.4g, e = %.4g; χ²/dof = %.3g%s",
             r->setup.mu_static, r->setup.mu_kinetic, r->setup.restitution, r->chi2_dof,
             r->misfit ? " (the model does not describe the video)" : "");
}

static int figure(const char *out, const jc_Track *t, const jc_TrackFitResult *r, const jc_SimOptions *o, int argc,
                  char **argv)
{
    static const char no_path[] = "the fitted model's path for the figure failed";
    const size_t n = (size_t)r->frames;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *th = malloc(n * sizeof *th);
    char err[256];
    /* The fitted model at the frames, in the video's frame, the mark's angle. */
    const int have = x && y && th &&
                     jc_track_model_path(&r->setup, t, &r->start, &r->frame, o, t->t_s + r->first, r->frames, x, y, th,
                                         err, sizeof err) == JC_OK;
    int rc = EXIT_FAIL;
    if (have) {
        cli_TrackFigure f;
        figure_frames(&f, t, r, x, y, th);
        rc = cli_track_figure_draw("fit", no_path, &f, &r->setup, &r->start, &r->frame, o, out, argc, argv);
    } else {
        cli_error("fit: %s", no_path);
    }
    free(x);
    free(y);
    free(th);
    return rc;
}

/* The fit's progress line on a terminal: its stage, descents begun and the
 * part done; a stop signal (SIGINT, ...) ends the fit. */
static int show_progress(void *ctx, const jc_TrackFitProgress *p)
{
    cli_Progress *bar = ctx;
    snprintf(bar->label, sizeof bar->label, "fit: %-50.50s descent %3d, %3.0f%%", p->stage, p->descents,
             100.0 * p->fraction);
    cli_progress_update(bar, 0, 0);
    return cli_stop_requested() != 0;
}

int cmd_fit(int argc, char **argv)
{
    fit_opts o;
    memset(&o, 0, sizeof o);
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_command_parse(argc, argv, &command, &o, &sa, &sim_args);
    if (st != CLI_GO_ON) return st;
    if ((st = cli_track_args_check("fit", &o.track)) != EXIT_OK) return st;
    jc_Setup setup;
    jc_SimOptions opts;
    if ((st = cli_build_inputs("fit", &sa, &sim_args, &setup, &opts, NULL)) != EXIT_OK) return st;
    jc_TrackFitOptions fo;
    if ((st = check(&o, &setup, &fo)) != EXIT_OK) return st;
    jc_Track t;
    if ((st = cli_track_args_load_for_model("fit", &o.track, &sa, &setup, &t)) != EXIT_OK) return st;
    char err[512];
    jc_TrackFitResult r;
    cli_Progress progress;
    cli_progress_begin(&progress, "fit");
    fo.progress = show_progress;
    fo.progress_ctx = &progress;
    const int fitted = jc_track_fit(&setup, &t, &fo, &opts, &r, err, sizeof err);
    cli_progress_end(&progress);
    if (fitted != JC_OK) { /* stopped by a signal: no message, no report */
        if (fitted != JC_ESTOPPED) cli_error("fit: %s", err);
        jc_track_free(&t);
        return cli_exit_status(fitted, CLI_INPUTS_VIDEO);
    }
    report(o.track.track, &t, &r, &fo);
    st = o.track.output ? figure(o.track.output, &t, &r, &opts, argc, argv) : EXIT_OK;
    if (st == EXIT_OK && o.track.output) printf("Figure: %s\n", o.track.output);
    jc_track_free(&t);
    if (st != EXIT_OK) return st;
    st = cli_stdout_finish();
    if (st == EXIT_OK && r.misfit && !o.allow_misfit) {
        cli_error("fit: the model does not describe this video (see the verdict); --allow-misfit to exit 0");
        return EXIT_MISFIT;
    }
    return st;
}
