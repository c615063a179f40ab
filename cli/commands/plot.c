/* jumpcyl plot: figures made with gnuplot. The numbers come from the
 * library; they are written as data files with a commented gnuplot script
 * beside them (kept with --keep-script, so that a researcher can restyle the
 * figure), and gnuplot renders the figure file atomically. */
#include "batch.h"
#include "commands.h"
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NEED_CRITERION = 1, NEED_RUN = 2, NEED_UNCERTAINTY = 4, NEED_TRAJECTORY = 8 };

typedef struct {
    const char *name;
    unsigned needs;
    void (*panel)(FILE *gp, const fig_Data *d); /* NULL: the overview */
    const char *help;
    double cols, rows; /* the page, in panels of 1200 x 750 px */
} plot_kind;

static const plot_kind kinds[] = {
    {"paper-criterion", NEED_CRITERION, fig_criterion_figure,
     "both sides of the paper's Eq. 9 against the rotation angle (its Figures 2-4),\n"
     "                      every intersection, the printed jump angle, the exact N = 0 condition", 1, 1},
    {"forces", NEED_RUN, fig_forces_panel, "N/(M g cos a) and |F|/N along the ramp, friction band, events", 1, 1},
    {"gap", NEED_RUN, fig_path_panel,
     "gap between rim and incline and the centre's speed; hop heights ('path' is its former name)", 1, 1},
    {"energy", NEED_RUN, fig_energy_panel, "kinetic, potential, friction and impact losses, their sum", 1, 1},
    {"trajectory", NEED_RUN | NEED_TRAJECTORY, fig_trajectory_panels,
     "the body's path to scale: centre, parts, centre of mass, outlines at the events;\n"
     "                      zoomed on the lift-off and hops; the whole ramp and the first flight's gap\n                      when the zoom leaves them out or too small to see", 2, 2},
    {"overview", NEED_CRITERION | NEED_RUN, NULL,
     "paper-criterion, forces, gap, energy on one page, zoomed on the lift-off and hops", 2, 2},
    {"paper-uncertainty", NEED_UNCERTAINTY, fig_uncertainty_panels,
     "the paper's three inclines: printed jump site, the full model's first lift-off\n"
     "                      with its 95 % band (Monte Carlo of the inputs' uncertainties), measured;\n"
     "                      the paper's cylinder only (the body it measured)", 1.5, 1.2},
};
#define KIND_COUNT (int)(sizeof kinds / sizeof kinds[0])
#define KIND_NAMES "paper-criterion, forces, gap, energy, trajectory, overview, paper-uncertainty"

typedef struct {
    const char *what;
    const char *output;
    const char *max_samples;
    int keep_script;
} plot_opts;

/* Samples a figure may hold unless --max-samples says otherwise: a figure
 * of every kind is made of about 5000 (plus one per event). */
#define DEFAULT_MAX_SAMPLES 100000.0
#define MAX_MAX_SAMPLES 1e8

static void help(void)
{
    puts("Usage: jumpcyl plot --what KIND --output FILE [--keep-script] [SETUP OPTIONS] [SIMULATION OPTIONS]\n"
         "A figure made with gnuplot; the format follows the file name: .png, .svg or .pdf.\n"
         "\n"
         "  --what KIND     the figure:");
    for (int i = 0; i < KIND_COUNT; ++i) printf("    %-16s  %s\n", kinds[i].name, kinds[i].help);
    puts("  --output FILE   the figure file, written whole or not at all\n"
         "  --keep-script   keep the gnuplot script STEM.gp beside the figure (STEM: FILE without\n"
         "                  its extension; the data are inside it), to restyle it: in that\n"
         "                  directory, 'gnuplot ./STEM.gp' renders the figure again\n"
         "  --max-samples N refuse a figure of more than N samples (default 100000), estimated\n"
         "                  before the work starts\n"
         "  -h, --help      this help\n"
         "\n"
         "forces, gap, energy, trajectory and overview sample the full model finely (about 5000 samples over the run)\n"
         "unless --sample-dt is given. Needs gnuplot (Debian: gnuplot-nox).\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    plot_opts *o = ctx;
    if (opt == 'w') return cli_take_once("plot", &o->what, "what", arg);
    if (opt == 'o') return cli_take_once("plot", &o->output, "output", arg);
    if (opt == 'k') { o->keep_script = 1; return CLI_GO_ON; }
    if (opt == 'm') return cli_take_once("plot", &o->max_samples, "max-samples", arg);
    return EXIT_USAGE;
}

/* The command's own options; the setup and simulation options come with cli_command_parse. */
static const struct option own[] = {{"what", required_argument, 0, 'w'},
                                    {"output", required_argument, 0, 'o'},
                                    {"keep-script", no_argument, 0, 'k'},
                                    {"max-samples", required_argument, 0, 'm'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

static const plot_kind *find_kind(const char *name)
{
    if (strcmp(name, "path") == 0) name = "gap"; /* the former name: scripts that use it still work */
    for (int i = 0; i < KIND_COUNT; ++i)
        if (strcmp(kinds[i].name, name) == 0) return &kinds[i];
    return NULL;
}

/* Checks --what and --output before any work. */
static int check_opts(const plot_opts *o, const plot_kind **kind, fig_Format *format)
{
    if (!o->what) {
        cli_error("plot: --what KIND is required (allowed: " KIND_NAMES ")");
        return EXIT_USAGE;
    }
    if (!(*kind = find_kind(o->what))) {
        cli_error("plot: --what '%s' is not a kind of figure (allowed: " KIND_NAMES ")", o->what);
        return EXIT_USAGE;
    }
    if (!o->output || !*o->output) {
        cli_error("plot: --output FILE is required (allowed extensions: .png, .svg, .pdf)");
        return EXIT_USAGE;
    }
    if (cli_output_file_only("plot", "output", o->output, "a figure") != 0) return EXIT_USAGE;
    if (fig_format_from_path(o->output, format) != 0) {
        const char *ext = cli_path_ext(o->output);
        if (*ext) cli_error("plot: --output '%s': unknown format '.%s' (allowed extensions: .png, .svg, .pdf)", o->output, ext);
        else cli_error("plot: --output '%s' has no extension (allowed extensions: .png, .svg, .pdf)", o->output);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static void write_overview(FILE *gp, const fig_Data *d)
{
    char caption[256], body[256];
    fig_caption(d->model, caption, sizeof caption);
    fig_body_caption(d->model, body, sizeof body);
    char zoom[320] = "";
    if (d->zoomed) {
        char words[200];
        fig_zoom_caption(d, words, sizeof words);
        snprintf(zoom, sizeof zoom, "\\nforces, hops, energy %s; the whole run: plot --what forces", words);
    } else if (d->cut != FIG_CUT_NONE) {
        char words[256];
        fig_cut_caption(d, words, sizeof words);
        snprintf(zoom, sizeof zoom, "\\nforces, hops, energy %s", words);
    }
    fprintf(gp, "\nset multiplot layout 2,2 title \"jumpcyl: %s; %s%s\" font F_TITLE\n", caption, body, zoom);
    fig_criterion_panel(gp, d);
    fig_forces_panel(gp, d);
    fig_path_panel(gp, d);
    fig_energy_panel(gp, d);
    fig_criterion_inset(gp, d);
    fputs("\nunset multiplot\n", gp);
}

/* The script in the scratch directory: header, data blocks, panels. */
static int write_script(fig_Data *d, const plot_kind *kind, fig_Format format, const plot_opts *o,
                        const jc_SimOptions *sim, int dt_given, double max_samples, const char *cmdline,
                        const char *script)
{
    FILE *gp = fopen(script, "w");
    if (!gp) {
        cli_error("cannot write %s: %s", script, strerror(errno));
        return EXIT_FAIL;
    }
    d->gp = gp;
    /* Run by hand, the kept script writes a figure beside itself, under a
     * name no program can take for a command. */
    const char *slash = strrchr(o->output, '/');
    char base[256];
    cli_safe_name(slash ? slash + 1 : o->output, base, sizeof base);
    const int overview = kind->panel == NULL;
    fig_script_begin(gp, format, kind->cols, kind->rows, base, cmdline);
    fputs("\n# ---- Data ----\n", gp);
    int rc = EXIT_OK;
    if (kind->needs & NEED_CRITERION) rc = fig_criterion_prepare(d);
    d->zoom_wanted = overview;
    if (rc == EXIT_OK && (kind->needs & NEED_RUN)) rc = fig_run_prepare(d, sim, dt_given, max_samples);
    if (rc == EXIT_OK && (kind->needs & NEED_TRAJECTORY)) rc = fig_trajectory_prepare(d, sim);
    if (rc == EXIT_OK && (kind->needs & NEED_UNCERTAINTY)) rc = fig_uncertainty_prepare(d);
    if (rc == EXIT_OK && overview) write_overview(gp, d);
    else if (rc == EXIT_OK) kind->panel(gp, d);
    int err = fflush(gp) != 0 ? errno : 0;
    if (!err && ferror(gp)) err = EIO; /* an earlier write failed; its errno is gone */
    if (fclose(gp) != 0 && !err) err = errno;
    d->gp = NULL;
    if (rc == EXIT_OK && err) {
        cli_error("cannot write %s: %s (writing its script %s)", o->output, strerror(err), script);
        rc = EXIT_FAIL;
    }
    return rc;
}

/* STEM.gp beside the figure; -1 if it does not fit. */
static int kept_script_path(const char *output, char *out, size_t len)
{
    char dir[CLI_PATH_MAX], stem[CLI_PATH_MAX], name[CLI_PATH_MAX + 8];
    if (cli_path_split(output, dir, sizeof dir, stem, sizeof stem) != 0) return -1;
    if (snprintf(name, sizeof name, "%s.gp", stem) >= (int)sizeof name) return -1;
    return strrchr(output, '/') ? cli_path_join(out, len, dir, name) : (snprintf(out, len, "%s", name) < (int)len ? 0 : -1);
}

/* The figure (and the kept script) from the scratch directory to their
 * places: both are complete and checked before either is renamed. */
static int publish(const plot_opts *o, fig_Format format, const char *figure, const char *script)
{
    cli_Output fig, kept;
    char kept_path[CLI_PATH_MAX];
    memset(&kept, 0, sizeof kept);
    if (cli_output_begin(&fig, o->output, 0) != 0) return EXIT_FAIL;
    int ok = cli_output_copy_from(&fig, figure) == 0 && cli_output_finish(&fig, fig_check(format)) == 0;
    if (ok && o->keep_script) {
        ok = kept_script_path(o->output, kept_path, sizeof kept_path) == 0 &&
             cli_output_begin(&kept, kept_path, 0) == 0 && cli_output_copy_from(&kept, script) == 0 &&
             cli_output_finish(&kept, CLI_CHECK_WRITES) == 0;
    }
    ok = ok && cli_output_publish(&fig) == 0 && (!o->keep_script || cli_output_publish(&kept) == 0);
    cli_output_abort(&fig);
    cli_output_abort(&kept);
    if (!ok && cli_stop_requested()) return cli_stop_status();
    if (ok && o->keep_script)
        printf("Script: %s%s (its data inside)\n", cli_gnuplot_load_prefix(kept_path), kept_path);
    return ok ? EXIT_OK : EXIT_FAIL;
}

/* paper-uncertainty's numbers: the first lift-off's Monte Carlo spread at
 * each incline of the paper's table (the paper command's, cli/batch/mc_job.c),
 * handed to the figure in d. EXIT_OK, an exit status after a message, or the
 * stop status. */
static int site_spreads(const cli_SetupArgs *sa, jc_Stats *sites, fig_Data *d)
{
    const jc_PaperTableRow *t;
    int n = jc_paper_table(&t);
    if (n > FIG_TABLE_ROWS_MAX) n = FIG_TABLE_ROWS_MAX;
    for (int i = 0; i < n; ++i) {
        const int rc = cli_mc_liftoff_stats("plot", sa, t[i].incline_deg, CLI_PAPER_MC_SAMPLES, CLI_PAPER_MC_SEED,
                                            &sites[i], NULL);
        if (rc != EXIT_OK) return rc;
    }
    d->table_rows = n;
    d->site_stats = sites;
    d->mc_samples = CLI_PAPER_MC_SAMPLES;
    d->mc_seed = CLI_PAPER_MC_SEED;
    return EXIT_OK;
}

/* Script and gnuplot in a private scratch directory, then the results moved
 * into place. */
static int make_figure(fig_Data *d, const plot_opts *o, const plot_kind *kind, fig_Format format,
                       const jc_SimOptions *sim, int dt_given, double max_samples, const char *cmdline)
{
    cli_WorkDir work;
    if (cli_workdir_make(&work, "plot") != 0) return EXIT_FAIL;
    char script[CLI_PATH_MAX], figure[CLI_PATH_MAX];
    int rc = EXIT_OK;
    if (cli_path_join(script, sizeof script, work.path, FIG_SCRIPT_NAME) != 0 ||
        cli_path_join(figure, sizeof figure, work.path, fig_scratch_name(format)) != 0) {
        cli_error("plot: scratch path too long: %s", work.path);
        rc = EXIT_FAIL;
    }
    if (rc == EXIT_OK) rc = write_script(d, kind, format, o, sim, dt_given, max_samples, cmdline, script);
    if (rc == EXIT_OK) rc = fig_render("plot", work.path, format, o->output);
    if (rc == EXIT_OK) rc = publish(o, format, figure, script);
    cli_workdir_remove(&work);
    if (rc != EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    return rc;
}

int cmd_plot(int argc, char **argv)
{
    plot_opts o = {0};
    cli_RunInputs in;
    int st = cli_run_inputs_parse(argc, argv, &command, &o, &in);
    if (st != CLI_GO_ON) return st;
    const plot_kind *kind;
    fig_Format format;
    if ((st = check_opts(&o, &kind, &format)) != EXIT_OK) return st;
    fig_Data d;
    memset(&d, 0, sizeof d);
    if ((st = cli_run_inputs_build("plot", &in)) != EXIT_OK) return st;
    double max_samples = DEFAULT_MAX_SAMPLES;
    if (o.max_samples) {
        char msg[256];
        if (cli_parse_quantity(o.max_samples, Q_NUMBER, &max_samples, msg, sizeof msg) != 0 ||
            !(max_samples >= 1 && max_samples <= MAX_MAX_SAMPLES) || max_samples != floor(max_samples)) {
            cli_error("plot: --max-samples '%s' is out of range (allowed: a whole number from 1 to %.0f)",
                      o.max_samples, MAX_MAX_SAMPLES);
            return EXIT_USAGE;
        }
    }
    /* Every target is checked before the work: a read-only or impossible
     * one is refused at once. */
    char kept_path[CLI_PATH_MAX];
    if (cli_output_check_target(o.output) != 0) return EXIT_FAIL;
    if (o.keep_script && (kept_script_path(o.output, kept_path, sizeof kept_path) != 0 ||
                          cli_output_check_target(kept_path) != 0))
        return EXIT_FAIL;
    char gnuplot[CLI_PATH_MAX];
    if (cli_find_program("gnuplot", gnuplot, sizeof gnuplot) != 0) {
        cli_error("plot: gnuplot was not found in PATH; install it (Debian: sudo apt-get install gnuplot-nox)");
        return EXIT_FAIL;
    }
    if ((kind->needs & NEED_UNCERTAINTY) && cli_setup_given(&in.args, "incline")) {
        cli_error("plot: --what %s shows the table's inclines (15, 30, 45 deg); leave out --incline", kind->name);
        return EXIT_USAGE;
    }
    if ((kind->needs & NEED_UNCERTAINTY) &&
        (st = cli_paper_body_only("plot", "--what paper-uncertainty: ", "mc", &in.args, &in.model.setup)) != EXIT_OK)
        return st;
    jc_Stats sites[FIG_TABLE_ROWS_MAX];
    if ((kind->needs & NEED_UNCERTAINTY) && (st = site_spreads(&in.args, sites, &d)) != EXIT_OK) return st;
    d.model = &in.model;
    fig_caption(&in.model, d.caption, sizeof d.caption);
    if (kind->panel == NULL) d.caption[0] = '\0';
    char cmdline[2048];
    fig_command_line(argc, argv, cmdline, sizeof cmdline);
    /* The trajectory keeps the whole run (its panels choose their views). */
    d.end_after_landing = !(kind->needs & NEED_TRAJECTORY) && !cli_sim_given(&in.sim_args, "t-max");
    st = make_figure(&d, &o, kind, format, &in.sim, cli_sim_given(&in.sim_args, "sample-dt"), max_samples, cmdline);
    if (d.have_run) jc_run_free(&d.run);
    if (st == EXIT_OK) printf("Figure: %s\n", o.output);
    return st;
}
