/* jumpcyl plot: figures made with gnuplot. The numbers come from the
 * library; they are written as data files with a commented gnuplot script
 * beside them (kept with --keep-script, so that a researcher can restyle the
 * figure), and gnuplot renders the figure file atomically. */
#include "plot.h"

#include <string.h>

enum { NEED_CRITERION = 1, NEED_RUN = 2 };

typedef struct {
    const char *name;
    unsigned needs;
    void (*panel)(FILE *gp, const fig_Data *d); /* NULL: the overview */
    const char *help;
} plot_kind;

static const plot_kind kinds[] = {
    {"paper-criterion", NEED_CRITERION, fig_criterion_panel,
     "both sides of the paper's Eq. 9 against the rotation angle (its Figures 2-4),\n"
     "                      every intersection, the printed jump angle, the exact N = 0 condition"},
    {"forces", NEED_RUN, fig_forces_panel, "N/(M g cos a) and |F|/N along the ramp, friction band, events"},
    {"path", NEED_RUN, fig_path_panel, "gap between rim and incline and the centre's speed; hop heights"},
    {"energy", NEED_RUN, fig_energy_panel, "kinetic, potential, friction and impact losses, their sum"},
    {"overview", NEED_CRITERION | NEED_RUN, NULL, "the four above on one page"},
};
#define KIND_COUNT (int)(sizeof kinds / sizeof kinds[0])
#define KIND_NAMES "paper-criterion, forces, path, energy, overview"

typedef struct {
    const char *what;
    const char *output;
    int keep_script;
} plot_opts;

static void help(void)
{
    puts("Usage: jumpcyl plot --what KIND --output FILE [--keep-script] [SETUP OPTIONS] [SIMULATION OPTIONS]\n"
         "A figure made with gnuplot; the format follows the file name: .png, .svg or .pdf.\n"
         "\n"
         "  --what KIND     the figure:");
    for (int i = 0; i < KIND_COUNT; ++i) printf("    %-16s  %s\n", kinds[i].name, kinds[i].help);
    puts("  --output FILE   the figure file, written whole or not at all\n"
         "  --keep-script   keep the gnuplot script STEM.gp and its data files STEM-*.dat beside the\n"
         "                  figure (STEM: FILE without its extension), to restyle it: in that\n"
         "                  directory, 'gnuplot STEM.gp' renders the figure again\n"
         "  -h, --help      this help\n"
         "\n"
         "forces, path and energy sample the full model finely (about 5000 samples over the run)\n"
         "unless --sample-dt is given. Needs gnuplot (Debian: gnuplot-nox).\n");
    cli_sim_help(stdout);
    putchar('\n');
    cli_setup_help(stdout);
}

static int take_once(const char **slot, const char *name, const char *arg)
{
    if (*slot) {
        cli_error("plot: --%s given twice ('%s' and '%s')", name, *slot, arg);
        return EXIT_USAGE;
    }
    *slot = arg;
    return 0;
}

static int take(int opt, const char *arg, void *ctx)
{
    plot_opts *o = ctx;
    if (opt == 'w') return take_once(&o->what, "what", arg);
    if (opt == 'o') return take_once(&o->output, "output", arg);
    if (opt == 'k') { o->keep_script = 1; return 0; }
    if (opt == 'h') { help(); return -1; }
    return EXIT_USAGE;
}

static const plot_kind *find_kind(const char *name)
{
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
    if (fig_format_from_path(o->output, format) != 0) {
        const char *ext = cli_path_ext(o->output);
        if (*ext) cli_error("plot: --output '%s': unknown format '.%s' (allowed extensions: .png, .svg, .pdf)", o->output, ext);
        else cli_error("plot: --output '%s' has no extension (allowed extensions: .png, .svg, .pdf)", o->output);
        return EXIT_USAGE;
    }
    return 0;
}

/* The command line, for the script's header. */
static void command_line(int argc, char **argv, char *out, size_t len)
{
    snprintf(out, len, "jumpcyl");
    for (int i = 0; i < argc; ++i) {
        const size_t used = strlen(out);
        const int plain = argv[i][strcspn(argv[i], " '\"\\$\n")] == '\0';
        snprintf(out + used, len - used, plain ? " %s" : " '%s'", argv[i]);
    }
    for (char *p = out; *p; ++p)
        if (*p == '\n') *p = ' ';
}

static void write_overview(FILE *gp, const fig_Data *d)
{
    char caption[256], body[256];
    fig_caption(d->model, caption, sizeof caption);
    fig_body_caption(d->model, body, sizeof body);
    fprintf(gp, "\nset multiplot layout 2,2 title \"jumpcyl: %s; %s\" font F_TITLE\n", caption, body);
    fig_criterion_panel(gp, d);
    fig_forces_panel(gp, d);
    fig_path_panel(gp, d);
    fig_energy_panel(gp, d);
    fputs("\nunset multiplot\n", gp);
}

static int write_script(const fig_Data *d, const plot_kind *kind, fig_Format format, const char *output,
                        const char *cmdline, char *script, size_t script_len)
{
    char name[300], out_dir[CLI_PATH_MAX], out_stem[256];
    if (snprintf(name, sizeof name, "%s.gp", d->stem) >= (int)sizeof name ||
        cli_path_join(script, script_len, d->dir, name) != 0 ||
        cli_path_split(output, out_dir, sizeof out_dir, out_stem, sizeof out_stem) != 0) {
        cli_error("plot: path too long: %s", output);
        return EXIT_FAIL;
    }
    cli_AtomicFile af;
    if (cli_atomic_open(&af, script) != 0) return EXIT_FAIL;
    /* Run by hand from its directory, the script writes the figure beside itself. */
    const char *base = strrchr(output, '/') ? strrchr(output, '/') + 1 : output;
    const int overview = kind->panel == NULL;
    fig_script_begin(af.f, format, overview ? 2 : 1, overview ? 2 : 1, base, cmdline);
    if (overview) {
        write_overview(af.f, d);
    } else {
        kind->panel(af.f, d);
    }
    return cli_atomic_commit(&af) == 0 ? EXIT_OK : EXIT_FAIL;
}

/* Data, script, gnuplot; the scratch directory holds gnuplot's messages and,
 * without --keep-script, the data and script too. */
static int make_figure(fig_Data *d, const plot_opts *o, const plot_kind *kind, fig_Format format,
                       const jc_SimOptions *sim, int dt_given, const char *cmdline)
{
    cli_WorkDir work;
    if (cli_workdir_make(&work, "plot") != 0) return EXIT_FAIL;
    char out_dir[CLI_PATH_MAX], log_path[CLI_PATH_MAX], script[CLI_PATH_MAX];
    int rc = EXIT_OK;
    if (cli_path_split(o->output, out_dir, sizeof out_dir, d->stem, sizeof d->stem) != 0 ||
        cli_path_join(log_path, sizeof log_path, work.path, "gnuplot.log") != 0) {
        cli_error("plot: output path too long: %s", o->output);
        rc = EXIT_FAIL;
    }
    if (rc == EXIT_OK) snprintf(d->dir, sizeof d->dir, "%s", o->keep_script ? out_dir : work.path);
    if (rc == EXIT_OK && (kind->needs & NEED_CRITERION)) rc = fig_criterion_prepare(d);
    if (rc == EXIT_OK && (kind->needs & NEED_RUN)) rc = fig_run_prepare(d, sim, dt_given);
    if (rc == EXIT_OK) rc = write_script(d, kind, format, o->output, cmdline, script, sizeof script);
    if (rc == EXIT_OK) rc = fig_render(script, d->dir, o->output, format, log_path);
    if (rc == EXIT_OK && o->keep_script) printf("Script: %s (data: %s/%s-*.dat)\n", script, d->dir, d->stem);
    cli_workdir_remove(&work);
    return rc;
}

static int sim_given(const cli_SimArgs *a, const char *name)
{
    for (int i = 0; i < CLI_SIM_OPTION_COUNT; ++i)
        if (strcmp(cli_sim_options[i].name, name) == 0) return a->value[i] != NULL;
    return 0;
}

static int build_inputs(const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_Model *model, jc_SimOptions *sim)
{
    char err[512];
    jc_Setup setup;
    if (cli_setup_build(sa, &setup, err, sizeof err) != 0 || cli_sim_build(sim_args, sim, err, sizeof err) != 0) {
        cli_error("plot: %s", err);
        return EXIT_USAGE;
    }
    const int st = jc_model_init(model, &setup, err, sizeof err);
    if (st != JC_OK) {
        cli_error("plot: %s", err);
        return st == JC_EINVAL ? EXIT_USAGE : EXIT_FAIL;
    }
    return 0;
}

int cmd_plot(int argc, char **argv)
{
    static const struct option own[] = {{"what", required_argument, 0, 'w'},
                                        {"output", required_argument, 0, 'o'},
                                        {"keep-script", no_argument, 0, 'k'},
                                        {"help", no_argument, 0, 'h'}};
    plot_opts o = {0};
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_parse_args(argc, argv, own, 4, take, &o, &sa, &sim_args);
    if (st) return st < 0 ? EXIT_OK : st;
    const plot_kind *kind;
    fig_Format format;
    if ((st = check_opts(&o, &kind, &format)) != 0) return st;
    fig_Data d;
    memset(&d, 0, sizeof d);
    jc_Model model;
    jc_SimOptions sim;
    if ((st = build_inputs(&sa, &sim_args, &model, &sim)) != 0) return st;
    if (cli_check_output_dir(o.output) != 0) return EXIT_FAIL;
    char gnuplot[CLI_PATH_MAX];
    if (cli_find_program("gnuplot", gnuplot, sizeof gnuplot) != 0) {
        cli_error("plot: gnuplot was not found in PATH; install it (Debian: sudo apt-get install gnuplot-nox)");
        return EXIT_FAIL;
    }
    /* A first Ctrl-C lets the scratch directory be removed before exiting. */
    cli_signals_defer();
    d.model = &model;
    fig_caption(&model, d.caption, sizeof d.caption);
    if (kind->panel == NULL) d.caption[0] = '\0';
    char cmdline[2048];
    command_line(argc, argv, cmdline, sizeof cmdline);
    st = make_figure(&d, &o, kind, format, &sim, sim_given(&sim_args, "sample-dt"), cmdline);
    if (d.have_run) jc_run_free(&d.run);
    if (st == EXIT_OK) printf("Figure: %s\n", o.output);
    return cli_stop_requested() ? cli_stop_status() : st;
}
