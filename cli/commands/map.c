/* jumpcyl map: a regime map, the first lift-off position of the full model
 * over a grid of two setup options, drawn with gnuplot. The cases are a
 * sweep's (the batch engine, cli/batch/batch.h): with --keep-script the
 * map's rows are written as `jumpcyl sweep --vary Y --vary X` writes them,
 * byte for byte. */
#include "commands.h"
#include "batch.h"
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* Cells of one map at most: a megapixel, far beyond what a figure shows. */
#define MAX_CELLS 1000000L
#define MIN_AXIS_VALUES 2

typedef struct {
    const char *x, *y;
    cli_BatchArgs batch; /* --output, --threads, --quiet */
    int keep_script;
} map_opts;

static void help(void)
{
    puts("Usage: jumpcyl map --x NAME=VALUES --y NAME=VALUES --output FILE [--keep-script]\n"
         "                   [SETUP OPTIONS] [SIMULATION OPTIONS] [--threads N] [--quiet]\n"
         "A regime map: where the full model first lifts off the ramp, over a grid of two\n"
         "setup options, as a colour map (gnuplot); the format follows the file name: .png,\n"
         ".svg or .pdf.\n"
         "\n"
         "  --x NAME=START:STOP:STEP   the horizontal axis: values START, START+STEP, ... up to STOP\n"
         "  --x NAME=V1,V2,...         the values listed, increasing\n"
         "  --y NAME=VALUES            the vertical axis, likewise\n"
         "                  NAME: a numeric setup option (incline, rod-offset, mu, theta0, ...),\n"
         "                  a different one on each axis and not also given plainly; values with\n"
         "                  units as on the command line (angles: degrees, or 0.3rad); at least 2\n"
         "                  values per axis and at most 1000000 cells in all\n"
         "  --output FILE   the figure, written whole or not at all\n"
         "  --keep-script   keep beside the figure the gnuplot script STEM.gp (the map's data\n"
         "                  inside; 'gnuplot ./STEM.gp' in that directory renders it again) and\n"
         "                  STEM.csv, the cases' rows, the same as 'jumpcyl sweep --vary Y\n"
         "                  --vary X' writes (STEM: FILE without its extension)\n"
         "  --threads N     threads (default: every core; the map does not depend on it)\n"
         "  --quiet         no progress line (it is only shown on a terminal anyway)\n"
         "  -h, --help      this help\n"
         "\n"
         "Colours: the first lift-off's distance down the ramp (cm); light grey: no lift-off on\n"
         "the ramp; vermillion: it slides from the start (cannot roll); white: not a valid setup;\n"
         "hatched: the run failed. Circles mark the paper's setups (15, 30, 45 deg) where they\n"
         "fall inside the map. Needs gnuplot (Debian: gnuplot-nox).\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    map_opts *o = ctx;
    if (opt == 'x') return cli_take_once("map", &o->x, "x", arg);
    if (opt == 'y') return cli_take_once("map", &o->y, "y", arg);
    if (opt == 'k') {
        o->keep_script = 1;
        return CLI_GO_ON;
    }
    return cli_batch_take("map", &o->batch, opt, arg);
}

static const struct option own[] = {{"x", required_argument, 0, 'x'},
                                    {"y", required_argument, 0, 'y'},
                                    {"output", required_argument, 0, 'o'},
                                    {"keep-script", no_argument, 0, 'k'},
                                    {"threads", required_argument, 0, 't'},
                                    {"quiet", no_argument, 0, 'q'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* ---- the cases: a sweep over (y, x), x varying fastest ---- */

typedef struct {
    jc_Setup base;
    cli_SetupValues values; /* the job's own single values */
    cli_Param params[2]; /* [0] y, [1] x: the sweep's order, so that case = iy * nx + ix */
    int n;
} map_job;

/* What the cases gave, in case order; and their rows, for STEM.csv. */
typedef struct {
    unsigned char *kind;
    double *liftoff_cm;
    long done;
    FILE *rows; /* NULL without --keep-script */
} map_grid;

static void consume(void *ctx, long index, const jc_CaseOutcome *o, const char *row, int row_len)
{
    map_grid *g = ctx;
    g->kind[index] = (unsigned char)o->kind;
    g->liftoff_cm[index] = o->kind == JC_CASE_LIFTOFF ? 100.0 * o->liftoff_x_m : NAN;
    g->done = index + 1;
    if (g->rows && row) fwrite(row, 1, (size_t)row_len, g->rows);
}

/* ---- the axes ---- */

/* The unit an axis shows its parameter in: the table's (degrees for
 * angles, centimetres or millimetres for the body's lengths, grams for
 * masses), written as a figure writes it. */
typedef struct {
    double per_si;
    const char *unit;
} axis_unit;

static axis_unit unit_of(const cli_Param *p)
{
    static const struct { const char *unit, *shown; } pretty[] = {
        {"deg", "°"}, {"m/s2", "m/s²"}, {"kg/m3", "kg/m³"}, {"N m s2", "N m s²"}};
    const jc_ParamInfo *in = jc_param_info(p->id);
    double to_si = 1.0;
    for (int k = 0; jc_quantity_unit(in->quantity, k, NULL); ++k)
        if (strcmp(jc_quantity_unit(in->quantity, k, NULL), in->unit) == 0) jc_quantity_unit(in->quantity, k, &to_si);
    const char *shown = in->unit;
    for (size_t k = 0; k < sizeof pretty / sizeof pretty[0]; ++k)
        if (strcmp(in->unit, pretty[k].unit) == 0) shown = pretty[k].shown;
    /* degrees: 180 / pi, as the columns scale them */
    return (axis_unit){in->quantity == JC_Q_ANGLE ? 180.0 / CLI_PI : 1.0 / to_si, shown};
}

/* The --x message from cli_param_parse_vary's, which names --vary (flag is
 * shorter, so the message is rewritten in place). */
static void name_flag(char *err, const char *flag)
{
    static const char vary[] = "--vary ";
    const size_t skip = sizeof vary - 1, flag_len = strlen(flag);
    if (strncmp(err, vary, skip) != 0 || flag_len + 1 > skip) return;
    memmove(err + flag_len + 1, err + skip, strlen(err + skip) + 1);
    memcpy(err, flag, flag_len);
    err[flag_len] = ' ';
}

/* One axis: parsed and checked on the job's setup. EXIT_OK or EXIT_USAGE after a message. */
static int parse_axis(const char *flag, const char *text, const cli_SetupArgs *sa, cli_Param *p)
{
    char err[640];
    char given[40];
    snprintf(given, sizeof given, "%.*s", (int)strcspn(text, "="), text);
    const int named = jc_param_find(given);
    if (named >= 0 && jc_param_info(named)->quantity == JC_Q_NAME) {
        cli_error("map: %s '%s': %s is a name, not a number (allowed on an axis: a numeric setup option; "
                  "make one map per value with --%s, or compare them with sweep)",
                  flag, text, jc_param_info(named)->name, jc_param_info(named)->name);
        return EXIT_USAGE;
    }
    if (cli_param_parse_vary(text, sa, p, err, sizeof err) != 0) {
        name_flag(err, flag);
        cli_error("map: %s", err);
        return EXIT_USAGE;
    }
    const char *name = jc_param_info(p->id)->name;
    if (p->count < MIN_AXIS_VALUES) {
        cli_error("map: %s '%s': %ld value (allowed: at least %d values on an axis)", flag, text, p->count,
                  MIN_AXIS_VALUES);
        return EXIT_USAGE;
    }
    for (long k = 1; k < p->count; ++k)
        if (!(p->values[k] > p->values[k - 1])) {
            cli_error("map: %s '%s': the values must increase (allowed: V1 < V2 < ...)", flag, text);
            return EXIT_USAGE;
        }
    if (sa->value[p->id]) {
        cli_error("map: --%s and %s %s both given; give one", name, flag, name);
        return EXIT_USAGE;
    }
    if (strcmp(name, "radius") == 0 && sa->part_count > 0) {
        cli_error("map: %s radius with --part bodies: vary a disc+rod body's radius instead", flag);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static int parse_axes(const map_opts *o, const cli_SetupArgs *sa, map_job *job)
{
    /* Counted before they are parsed: free_job frees whatever a refused axis holds. */
    job->n = 2;
    int st = parse_axis("--y", o->y, sa, &job->params[0]);
    if (st != EXIT_OK || (st = parse_axis("--x", o->x, sa, &job->params[1])) != EXIT_OK) return st;
    if (job->params[0].id == job->params[1].id) {
        cli_error("map: --x and --y both vary %s (allowed: two different setup options)",
                  jc_param_info(job->params[0].id)->name);
        return EXIT_USAGE;
    }
    const double cells = (double)job->params[0].count * (double)job->params[1].count;
    if (cells > (double)MAX_CELLS) {
        cli_error("map: --x '%s' gives %ld values and --y '%s' %ld: %.0f cells (allowed: at most %ld; take a larger "
                  "STEP)",
                  o->x, job->params[1].count, o->y, job->params[0].count, cells, MAX_CELLS);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static void free_job(map_job *job)
{
    for (int j = 0; j < job->n; ++j) cli_param_free(&job->params[j]);
}

/* The axis in the figure: values in its unit, its label. */
static int figure_axis(const cli_Param *p, fig_MapAxis *a, double **values)
{
    const axis_unit u = unit_of(p);
    *values = malloc((size_t)p->count * sizeof **values);
    if (!*values) return -1;
    for (long k = 0; k < p->count; ++k) (*values)[k] = p->values[k] * u.per_si;
    const char *name = jc_param_info(p->id)->name;
    if (*u.unit) snprintf(a->label, sizeof a->label, "%s (%s)", name, u.unit);
    else snprintf(a->label, sizeof a->label, "%s", name);
    a->count = p->count;
    a->values = *values;
    return 0;
}

/* ---- the figure's words: the fixed setup, the paper's setups ---- */

static int is_axis(const map_job *job, const char *name)
{
    for (int j = 0; j < job->n; ++j)
        if (strcmp(jc_param_info(job->params[j].id)->name, name) == 0) return 1;
    return 0;
}

/* Appends printf text to a caption, separated by sep when it is not empty. */
static void add(char *out, size_t len, const char *sep, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static void add(char *out, size_t len, const char *sep, const char *fmt, ...)
{
    const size_t used = strlen(out);
    if (used + 1 >= len) return;
    int w = used ? snprintf(out + used, len - used, "%s", sep) : 0;
    if (w < 0 || used + (size_t)w >= len) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out + used + (size_t)w, len - used - (size_t)w, fmt, ap);
    va_end(ap);
}

/* The options the axes do not vary, in two lines: the incline and contact,
 * then the body. Enhanced text. */
static void captions(const map_job *job, const jc_Setup *s, char *title, size_t tlen, char *body, size_t blen)
{
    snprintf(title, tlen, "First lift-off on the ramp");
    char fixed[256] = "";
    if (!is_axis(job, "incline")) add(fixed, sizeof fixed, ", ", "%.4g° incline", cli_deg(s->incline_rad));
    if (!is_axis(job, "mu") && !is_axis(job, "mu-s")) add(fixed, sizeof fixed, ", ", "μ_s = %.3g", s->mu_static);
    if (!is_axis(job, "mu") && !is_axis(job, "mu-k")) add(fixed, sizeof fixed, ", ", "μ_k = %.3g", s->mu_kinetic);
    if (!is_axis(job, "restitution")) add(fixed, sizeof fixed, ", ", "e = %.3g", s->restitution);
    if (!is_axis(job, "ramp-length")) add(fixed, sizeof fixed, ", ", "ramp %.4g m", s->ramp_length_m);
    if (!is_axis(job, "theta0") && s->theta0_rad != 0.0)
        add(fixed, sizeof fixed, ", ", "θ_0 = %.4g°", cli_deg(s->theta0_rad));
    if (!is_axis(job, "omega0") && s->omega0_radps != 0.0)
        add(fixed, sizeof fixed, ", ", "ω_0 = %.4g rad/s", s->omega0_radps);
    if (!is_axis(job, "g") && s->gravity_mps2 != jc_paper_setup().gravity_mps2)
        add(fixed, sizeof fixed, ", ", "g = %.4g m/s²", s->gravity_mps2);
    if (s->impact_law != JC_IMPACT_STRONGE)
        add(fixed, sizeof fixed, ", ", "%s impacts", jc_impact_law_name(s->impact_law));
    if (jc_setup_has_resistance(s)) add(fixed, sizeof fixed, ", ", "air/rolling resistance");
    if (*fixed) add(title, tlen, ": ", "%s", fixed);

    /* The body part by part; a value an axis varies is left out. The
     * options reach the first disc and the first rod (jc_param_get). */
    body[0] = '\0';
    if (!is_axis(job, "radius")) add(body, blen, "; ", "r = %.4g cm", s->body.radius_m * 100);
    int first_disc = -1, first_rod = -1;
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_PartKind k = s->body.parts[i].kind;
        if (k == JC_PART_DISC && first_disc < 0) first_disc = i;
        if (k == JC_PART_ROD && first_rod < 0) first_rod = i;
    }
    char parts[200] = "";
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_Part *p = &s->body.parts[i];
        const int mass_varied =
            (i == first_disc && is_axis(job, "disc-mass")) || (i == first_rod && is_axis(job, "rod-mass"));
        const int offset_varied = i == first_rod && is_axis(job, "rod-offset");
        char one[64];
        snprintf(one, sizeof one, "%s", jc_part_kind_name(p->kind));
        if (!mass_varied) add(one, sizeof one, " ", "%.4g g", p->mass_kg * 1e3);
        if (!offset_varied && p->offset_m != 0.0) add(one, sizeof one, " ", "at %.4g cm", p->offset_m * 100);
        add(parts, sizeof parts, ", ", "%s", one);
    }
    add(body, blen, "; ", "%s", parts);
}

/* Whether two setups make the same run of the full model (the paper
 * model's d, which the full model does not use, aside). */
static int same_run(const jc_Setup *a, const jc_Setup *b)
{
#define NEAR(u, v) (fabs((u) - (v)) <= 1e-9 * fmax(fabs(u), fabs(v)))
    if (a->body.part_count != b->body.part_count || !NEAR(a->body.radius_m, b->body.radius_m)) return 0;
    for (int i = 0; i < a->body.part_count; ++i) {
        const jc_Part *p = &a->body.parts[i], *q = &b->body.parts[i];
        if (p->kind != q->kind || !NEAR(p->mass_kg, q->mass_kg) || !NEAR(p->offset_m, q->offset_m) ||
            !NEAR(p->angle_rad, q->angle_rad) || !NEAR(p->radius_m, q->radius_m))
            return 0;
    }
    return a->impact_law == b->impact_law && NEAR(a->incline_rad, b->incline_rad) &&
           NEAR(a->gravity_mps2, b->gravity_mps2) && NEAR(a->mu_static, b->mu_static) &&
           NEAR(a->mu_kinetic, b->mu_kinetic) && NEAR(a->restitution, b->restitution) &&
           NEAR(a->theta0_rad, b->theta0_rad) && NEAR(a->omega0_radps, b->omega0_radps) &&
           NEAR(a->ramp_length_m, b->ramp_length_m) && NEAR(a->length_m, b->length_m) &&
           NEAR(a->air_density_kgpm3, b->air_density_kgpm3) && NEAR(a->drag_coefficient, b->drag_coefficient) &&
           NEAR(a->lift_coefficient, b->lift_coefficient) && NEAR(a->spin_drag_Nms2, b->spin_drag_Nms2) &&
           NEAR(a->rolling_resistance_m, b->rolling_resistance_m);
#undef NEAR
}

/* The paper's setups inside the map: with incline on an axis, its three
 * inclines at the paper's value of the other option; otherwise one point at
 * the paper's values, which all three share. paper_differs when the map's
 * other options are not the paper's. */
static void paper_points(const map_job *job, const fig_MapAxis *ax, const fig_MapAxis *ay, fig_Map *m)
{
    const jc_Setup paper = jc_paper_setup();
    const cli_Param *py = &job->params[0], *px = &job->params[1];
    const int incline = jc_param_find("incline");
    const int incline_axis = px->id == incline ? 1 : py->id == incline ? 0 : -1;
    static const double inclines_deg[FIG_MAP_PAPER_MAX] = {15.0, 30.0, 45.0};
    const int n = incline_axis >= 0 ? FIG_MAP_PAPER_MAX : 1;
    const double xlo = ax->values[0] - 0.5 * (ax->values[1] - ax->values[0]);
    const double xhi = ax->values[ax->count - 1] + 0.5 * (ax->values[ax->count - 1] - ax->values[ax->count - 2]);
    const double ylo = ay->values[0] - 0.5 * (ay->values[1] - ay->values[0]);
    const double yhi = ay->values[ay->count - 1] + 0.5 * (ay->values[ay->count - 1] - ay->values[ay->count - 2]);
    m->paper_count = 0;
    m->paper_differs = 0;
    for (int k = 0; k < n; ++k) {
        jc_Setup want = paper;
        if (incline_axis >= 0) want.incline_rad = inclines_deg[k] * CLI_PI / 180.0;
        double si[2]; /* [0] y, [1] x, as the job's parameters */
        if (jc_param_get(&want, py->id, &si[0], NULL, 0) != JC_OK || jc_param_get(&want, px->id, &si[1], NULL, 0) != JC_OK)
            return; /* the paper's body has no such part */
        const double x = si[1] * unit_of(px).per_si, y = si[0] * unit_of(py).per_si;
        if (!(x >= xlo && x <= xhi && y >= ylo && y <= yhi)) continue;
        jc_Setup s;
        char why[256];
        if (cli_case_setup(&job->base, &job->values, job->params, 2, si, &s, why, sizeof why) != 0) continue;
        if (incline_axis < 0) want.incline_rad = s.incline_rad; /* all three inclines */
        if (!same_run(&s, &want)) m->paper_differs = 1;
        const int i = m->paper_count++;
        m->paper_x[i] = x;
        m->paper_y[i] = y;
        if (incline_axis >= 0) snprintf(m->paper_label[i], sizeof m->paper_label[i], "paper %.0f°", inclines_deg[k]);
        else snprintf(m->paper_label[i], sizeof m->paper_label[i], "paper (all inclines)");
    }
}

/* ---- files: the figure, STEM.gp and STEM.csv beside it ---- */

/* STEM.ext beside the figure; -1 if it does not fit. */
static int kept_path(const char *output, const char *ext, char *out, size_t len)
{
    char dir[CLI_PATH_MAX], stem[CLI_PATH_MAX], name[CLI_PATH_MAX + 8];
    if (cli_path_split(output, dir, sizeof dir, stem, sizeof stem) != 0) return -1;
    if (snprintf(name, sizeof name, "%s.%s", stem, ext) >= (int)sizeof name) return -1;
    return strrchr(output, '/') ? cli_path_join(out, len, dir, name)
                                : (snprintf(out, len, "%s", name) < (int)len ? 0 : -1);
}

typedef struct {
    const char *output;
    fig_Format format;
    int keep;
    char gp_path[CLI_PATH_MAX], csv_path[CLI_PATH_MAX];
    cli_Output csv; /* open from before the cases to the end; written as they come */
} map_files;

static int check_output(const map_opts *o, map_files *files)
{
    files->output = o->batch.output;
    files->keep = o->keep_script;
    if (!files->output || !*files->output) {
        cli_error("map: --output FILE is required (allowed extensions: .png, .svg, .pdf)");
        return EXIT_USAGE;
    }
    if (cli_output_file_only("map", "output", files->output, "a figure") != 0) return EXIT_USAGE;
    if (fig_format_from_path(files->output, &files->format) != 0) {
        const char *ext = cli_path_ext(files->output);
        if (*ext)
            cli_error("map: --output '%s': unknown format '.%s' (allowed extensions: .png, .svg, .pdf)", files->output,
                      ext);
        else cli_error("map: --output '%s' has no extension (allowed extensions: .png, .svg, .pdf)", files->output);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* Every target, before any work: a read-only or impossible one is refused at once. */
static int check_targets(map_files *files)
{
    if (cli_output_check_target(files->output) != 0) return EXIT_FAIL;
    if (!files->keep) return EXIT_OK;
    if (kept_path(files->output, "gp", files->gp_path, sizeof files->gp_path) != 0 ||
        kept_path(files->output, "csv", files->csv_path, sizeof files->csv_path) != 0) {
        cli_error("cannot write %s: %s (its kept script and rows)", files->output, strerror(ENAMETOOLONG));
        return EXIT_FAIL;
    }
    if (cli_output_check_target(files->gp_path) != 0 || cli_output_check_target(files->csv_path) != 0)
        return EXIT_FAIL;
    return EXIT_OK;
}

static int write_script(const fig_Map *m, const map_files *files, const char *cmdline, const char *script)
{
    FILE *gp = fopen(script, "w");
    if (!gp) {
        cli_error("cannot write %s: %s", script, strerror(errno));
        return EXIT_FAIL;
    }
    const char *slash = strrchr(files->output, '/');
    char base[256];
    cli_safe_name(slash ? slash + 1 : files->output, base, sizeof base);
    fig_script_begin(gp, files->format, 1, 1, base, cmdline);
    fputs("\n# ---- Data ----\n", gp);
    fig_map_write(gp, m);
    int err = fflush(gp) != 0 ? errno : 0;
    if (!err && ferror(gp)) err = EIO;
    if (fclose(gp) != 0 && !err) err = errno;
    if (err) {
        cli_error("cannot write %s: %s (writing its script %s)", files->output, strerror(err), script);
        return EXIT_FAIL;
    }
    return EXIT_OK;
}

/* The figure, and with --keep-script the script and the rows: each one
 * complete and checked before any is renamed into place. */
static int publish(map_files *files, const char *figure, const char *script)
{
    cli_Output fig, kept;
    memset(&kept, 0, sizeof kept);
    if (cli_output_begin(&fig, files->output, 0) != 0) return EXIT_FAIL;
    int ok = cli_output_copy_from(&fig, figure) == 0 && cli_output_finish(&fig, fig_check(files->format)) == 0;
    if (ok && files->keep)
        ok = cli_output_begin(&kept, files->gp_path, 0) == 0 && cli_output_copy_from(&kept, script) == 0 &&
             cli_output_finish(&kept, CLI_CHECK_WRITES) == 0 && cli_output_finish(&files->csv, CLI_CHECK_WRITES) == 0;
    ok = ok && cli_output_publish(&fig) == 0 &&
         (!files->keep || (cli_output_publish(&kept) == 0 && cli_output_publish(&files->csv) == 0));
    cli_output_abort(&fig);
    cli_output_abort(&kept);
    cli_output_abort(&files->csv);
    if (!ok && cli_stop_requested()) return cli_stop_status();
    return ok ? EXIT_OK : EXIT_FAIL;
}

static int make_figure(const fig_Map *m, map_files *files, const char *cmdline)
{
    cli_WorkDir work;
    if (cli_workdir_make(&work, "map") != 0) return EXIT_FAIL;
    char script[CLI_PATH_MAX], figure[CLI_PATH_MAX];
    int rc = EXIT_OK;
    if (cli_path_join(script, sizeof script, work.path, FIG_SCRIPT_NAME) != 0 ||
        cli_path_join(figure, sizeof figure, work.path, fig_scratch_name(files->format)) != 0) {
        cli_error("map: scratch path too long: %s", work.path);
        rc = EXIT_FAIL;
    }
    if (rc == EXIT_OK) rc = write_script(m, files, cmdline, script);
    if (rc == EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    if (rc == EXIT_OK) rc = fig_render("map", work.path, files->format, files->output);
    if (rc == EXIT_OK) rc = publish(files, figure, script);
    cli_workdir_remove(&work);
    if (rc != EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    return rc;
}

/* ---- the command ---- */

static void summary(const map_grid *g, long total, long nx, long ny, double seconds)
{
    long counts[FIG_CELL_KINDS] = {0};
    for (long i = 0; i < total; ++i) ++counts[g->kind[i] < FIG_CELL_KINDS ? g->kind[i] : FIG_CELL_FAILED];
    printf("Map: %ld cases (%ld x %ld) in %.1f s: %ld lift off on the ramp, %ld do not", total, nx, ny, seconds,
           counts[FIG_CELL_LIFTOFF], counts[FIG_CELL_NONE]);
    if (counts[FIG_CELL_SLIDES]) printf(", %ld slide from the start", counts[FIG_CELL_SLIDES]);
    if (counts[FIG_CELL_INVALID]) printf(", %ld are not valid setups", counts[FIG_CELL_INVALID]);
    if (counts[FIG_CELL_FAILED]) printf(", %ld failed", counts[FIG_CELL_FAILED]);
    printf("\n");
}

/* The cases, then the figure. */
static int run(const cli_Batch *options, map_job *job, const jc_Setup *fixed, const jc_SimOptions *sim,
               map_files *files, const char *cmdline)
{
    cli_Batch b = *options;
    int st = EXIT_OK;
    const long nx = job->params[1].count, ny = job->params[0].count, total = nx * ny;
    map_grid g = {malloc((size_t)total), malloc((size_t)total * sizeof(double)), 0, NULL};
    /* The cases: a sweep over (y, x), x varying fastest, so that case = iy * nx + ix. */
    jc_StudyDef study;
    cli_study_init(&study, JC_STUDY_GRID, &job->base, &job->values, job->params, 2, sim);
    char header[2 * JC_STUDY_ROW_MAX];
    jc_study_header(&study, header, sizeof header);
    double *xv = NULL, *yv = NULL;
    fig_Map m;
    memset(&m, 0, sizeof m);
    if (!g.kind || !g.liftoff_cm || figure_axis(&job->params[1], &m.x, &xv) != 0 ||
        figure_axis(&job->params[0], &m.y, &yv) != 0) {
        cli_error("map: out of memory for %ld cells", total);
        st = EXIT_FAIL;
    }
    memset(&files->csv, 0, sizeof files->csv);
    if (st == EXIT_OK && files->keep) {
        if (cli_output_begin(&files->csv, files->csv_path, 0) != 0) st = EXIT_FAIL;
        else {
            fputs(header, files->csv.f);
            g.rows = files->csv.f;
        }
    }
    if (st == EXIT_OK) {
        b.study = &study;
        b.consume = consume;
        b.consume_rows = files->keep; /* STEM.csv */
        b.consume_ctx = &g;
        const double t0 = cli_now_s();
        st = cli_batch_run(&b);
        if (st == EXIT_OK && g.done != total) st = cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
        if (st == EXIT_OK && cli_batch_is_writer()) summary(&g, total, nx, ny, cli_now_s() - t0);
    }
    if (st == EXIT_OK && cli_batch_is_writer()) {
        m.format = files->format;
        m.kind = g.kind;
        m.liftoff_cm = g.liftoff_cm;
        m.ramp_cm = fixed->ramp_length_m * 100.0;
        captions(job, fixed, m.title, sizeof m.title, m.subtitle, sizeof m.subtitle);
        paper_points(job, &m.x, &m.y, &m);
        st = make_figure(&m, files, cmdline);
        if (st == EXIT_OK) {
            printf("Figure: %s\n", files->output);
            if (files->keep)
                printf("Script: %s%s (its data inside)\nRows: %s\n", cli_gnuplot_load_prefix(files->gp_path),
                       files->gp_path, files->csv_path);
        }
    }
    if (cli_stop_requested() && cli_batch_is_writer())
        cli_error("map: stopped by %s after %ld of %ld cases; no output file was written or changed",
                  cli_signal_name(cli_stop_requested()), g.done, total);
    cli_output_abort(&files->csv);
    free(xv);
    free(yv);
    free(g.kind);
    free(g.liftoff_cm);
    return st;
}

int cmd_map(int argc, char **argv)
{
    map_opts o;
    memset(&o, 0, sizeof o);
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_command_parse(argc, argv, &command, &o, &sa, &sim_args);
    if (st != CLI_GO_ON) return st;
    if (!o.x || !o.y) {
        cli_error("map: --x NAME=VALUES and --y NAME=VALUES are required (e.g. --x incline=5:60:1 --y "
                  "rod-offset=1cm:9cm:0.2cm)");
        return EXIT_USAGE;
    }
    map_files files;
    memset(&files, 0, sizeof files);
    if ((st = check_output(&o, &files)) != EXIT_OK) return st;
    cli_Batch b;
    if ((st = cli_batch_configure("map", &o.batch, &b)) != EXIT_OK) return st;
    b.output = NULL; /* the rows go to the consumer (the map, STEM.csv), not to a file of the engine's */
    map_job job;
    memset(&job, 0, sizeof job);
    jc_Setup fixed;
    jc_SimOptions sim;
    if ((st = cli_batch_build_inputs("map", &sa, &sim_args, &fixed, &sim, NULL)) != EXIT_OK) return st;
    char err[512];
    if (cli_setup_base(&sa, &job.base, err, sizeof err) != 0 || cli_setup_values(&sa, &job.values, err, sizeof err) != 0) {
        cli_error("map: %s", err);
        return EXIT_USAGE;
    }
    if ((st = parse_axes(&o, &sa, &job)) == EXIT_OK && (st = check_targets(&files)) == EXIT_OK) {
        char gnuplot[CLI_PATH_MAX];
        if (cli_find_program("gnuplot", gnuplot, sizeof gnuplot) != 0) {
            cli_error("map: gnuplot was not found in PATH; install it (Debian: sudo apt-get install gnuplot-nox)");
            st = EXIT_FAIL;
        }
    }
    if (st == EXIT_OK) {
        char cmdline[2048];
        fig_command_line(argc, argv, cmdline, sizeof cmdline);
        st = run(&b, &job, &fixed, &sim, &files, cmdline);
    }
    free_job(&job);
    return st;
}
