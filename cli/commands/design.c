/* jumpcyl design: the values of one setup option for which the first
 * lift-off happens at X on the ramp (cli/design/, docs/design.md). */
#include "commands.h"
#include "design.h"
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *jump_at, *free, *range, *points, *threads, *json, *csv, *figure;
} design_opts;

#define HELP_INDENT 18
#define HELP_WIDTH 96

/* Text wrapped at HELP_WIDTH, each line indented by HELP_INDENT. */
static void print_wrapped(const char *text)
{
    int col = printf("%*s", HELP_INDENT, "");
    for (const char *s = text; *s;) {
        const size_t word = strcspn(s, " ");
        if (col > HELP_INDENT && col + 1 + (int)word > HELP_WIDTH) col = printf("\n%*s", HELP_INDENT, "") - 1;
        else if (col > HELP_INDENT) col += printf(" ");
        col += printf("%.*s", (int)word, s);
        s += word;
        s += strspn(s, " ");
    }
    putchar('\n');
}

static void help(void)
{
    char names[512], refused[256], rest[512];
    cli_design_free_names(0, names, sizeof names);
    cli_design_free_names(1, refused, sizeof refused);
    snprintf(rest, sizeof rest,
             "(not also given as a setup option; the others are). Not %s: they never move the first lift-off",
             refused);
    printf("Usage: jumpcyl design --jump-at X --free NAME [--range LO:HI] [--points N] [SETUP OPTIONS]\n"
           "                      [SIMULATION OPTIONS] [--threads N] [--json FILE] [--csv FILE] [--figure FILE]\n"
           "Every value of one setup option for which the full model's first lift-off happens\n"
           "at X down the ramp (the centre's travel from its start), each with the jump's\n"
           "sensitivity to that option. The first lift-off leaps at discontinuities (a\n"
           "near-miss of the normal force turning into a lift-off): the search goes branch by\n"
           "branch, locates every leap, and reports the targets no value reaches as gaps.\n"
           "\n"
           "  --jump-at X     the wanted first lift-off, a length (1.00m, 100cm); on the ramp\n"
           "  --free NAME     the option to choose, one of ('jumpcyl params'):\n");
    print_wrapped(names);
    print_wrapped(rest);
    puts("  --range LO:HI   its range, with units as on the command line (rod-offset=2cm:8cm\n"
         "                  is --range 2cm:8cm; angles in degrees). Default: rod-offset 1 % of r\n"
         "                  to the rim, rod-mass 1 % to 5 times the rest of the body, theta0\n"
         "                  -180 to 180 deg, incline 1 to 85 deg, radius just outside the\n"
         "                  off-centre parts to 3 times r; the others their typical span\n"
         "                  ('jumpcyl params'), its ends moved in to valid setups (mu-k <= mu-s)\n"
         "  --points N      scan points over the range (default 1000; 10 to 200000)\n"
         "  --threads N     threads (default: every core; the answer does not depend on it)\n"
         "  --json FILE     the branches, discontinuities, reachable ranges and solutions (SI);\n"
         "                  - (or no FILE) is standard output, in place of the text\n"
         "  --csv FILE      every scanned and located point: value, first_liftoff_x_m, outcome, point;\n"
         "                  - is standard output, in place of the text\n"
         "  --figure FILE   the first lift-off against the option, X and the solutions marked\n"
         "                  (gnuplot; .png, .svg or .pdf)\n"
         "  -h, --help      this help\n"
         "\n"
         "Exit status: 0 when the search ran, whether or not it found a solution (the output\n"
         "says plainly when none exists); 2 for bad options.\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    design_opts *o = ctx;
    switch (opt) {
    case 'x': return cli_take_once("design", &o->jump_at, "jump-at", arg);
    case 'f': return cli_take_once("design", &o->free, "free", arg);
    case 'r': return cli_take_once("design", &o->range, "range", arg);
    case 'n': return cli_take_once("design", &o->points, "points", arg);
    case 't': return cli_take_once("design", &o->threads, "threads", arg);
    case 'j': return cli_take_once("design", &o->json, "json", arg);
    case 'c': return cli_take_once("design", &o->csv, "csv", arg);
    case 'g': return cli_take_once("design", &o->figure, "figure", arg);
    default: break;
    }
    return EXIT_USAGE;
}

static const struct option own[] = {
    {"jump-at", required_argument, 0, 'x'}, {"free", required_argument, 0, 'f'},
    {"range", required_argument, 0, 'r'},   {"points", required_argument, 0, 'n'},
    {"threads", required_argument, 0, 't'}, CLI_JSON_OPTION('j'),               
    {"csv", required_argument, 0, 'c'},     {"figure", required_argument, 0, 'g'},
    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* --range LO:HI in the option's units; EXIT_OK or EXIT_USAGE. */
static int parse_range(const char *text, cli_DesignJob *job)
{
    char lo[64], hi[64], msg[256];
    const char *colon = strchr(text, ':');
    const size_t n = colon ? (size_t)(colon - text) : 0;
    if (!colon || n == 0 || n >= sizeof lo || strlen(colon + 1) >= sizeof hi || !colon[1] || strchr(colon + 1, ':')) {
        cli_error("design: --range '%s': expected LO:HI (e.g. --range 2cm:8cm)", text);
        return EXIT_USAGE;
    }
    memcpy(lo, text, n);
    lo[n] = '\0';
    snprintf(hi, sizeof hi, "%s", colon + 1);
    if (cli_parse_quantity(lo, job->param.q, &job->lo, msg, sizeof msg) != 0 ||
        cli_parse_quantity(hi, job->param.q, &job->hi, msg, sizeof msg) != 0) {
        cli_error("design: --range '%s': %s", text, msg);
        return EXIT_USAGE;
    }
    if (!(job->hi > job->lo)) {
        cli_error("design: --range '%s' is empty (allowed: LO < HI)", text);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* Both ends of the range must be valid setups (values between them that
 * are not show as a branch "not a valid setup"). */
static int check_range_ends(const cli_DesignJob *job, const char *range_text)
{
    const double ends[2] = {job->lo, job->hi};
    for (int k = 0; k < 2; ++k) {
        jc_Setup s;
        char msg[400];
        if (cli_case_setup(&job->base, &job->values, &job->param, 1, &ends[k], &s, msg, sizeof msg) != 0) {
            const jc_ParamInfo *in = jc_param_info(job->param.id);
            const char *unit = in->quantity == JC_Q_ANGLE ? "deg" : in->si_unit; /* the column's value: SI, or deg */
            char shown[CLI_TOKEN_MAX];
            cli_param_column_value(&job->param, ends[k], shown, sizeof shown);
            cli_error("design: %s%s%s: --%s %s%s%s is not allowed: %s", range_text ? "--range '" : "the default range",
                      range_text ? range_text : "", range_text ? "'" : "", in->name, shown, *unit ? " " : "", unit,
                      msg);
            return EXIT_USAGE;
        }
    }
    return EXIT_OK;
}

static int parse_points(const char *text, long *out)
{
    char *end;
    errno = 0;
    const long n = text ? strtol(text, &end, 10) : CLI_DESIGN_POINTS_DEFAULT;
    if (text && (end == text || *end || errno || text[0] == '+' || n < JC_DESIGN_POINTS_MIN ||
                 n > JC_DESIGN_POINTS_MAX)) {
        cli_error("design: --points '%s' is not valid (allowed: a whole number from %ld to %ld)", text,
                  JC_DESIGN_POINTS_MIN, JC_DESIGN_POINTS_MAX);
        return EXIT_USAGE;
    }
    *out = n;
    return EXIT_OK;
}

/* X, the points, the threads and the output files, before any work. */
static int parse_rest(const design_opts *o, cli_DesignJob *job)
{
    char msg[256];
    if (cli_parse_quantity(o->jump_at, Q_LENGTH, &job->target_m, msg, sizeof msg) != 0) {
        cli_error("design: --jump-at: %s", msg);
        return EXIT_USAGE;
    }
    const double ramp = job->nominal.ramp_length_m;
    if (!(job->target_m > 0.0 && job->target_m <= ramp)) {
        cli_error("design: --jump-at %s is off the ramp (allowed: more than 0 and at most the ramp's %.4g m)",
                  o->jump_at, ramp);
        return EXIT_USAGE;
    }
    if (parse_points(o->points, &job->points) != EXIT_OK) return EXIT_USAGE;
    if (o->threads && cli_threads_parse(o->threads, &job->threads, msg, sizeof msg) != 0) {
        cli_error("design: %s", msg);
        return EXIT_USAGE;
    }
    if (cli_output_file_only("design", "figure", o->figure, "a figure") != 0) return EXIT_USAGE;
    fig_Format f;
    if (o->figure && fig_format_from_path(o->figure, &f) != 0) {
        cli_error("design: --figure '%s': unknown format (allowed extensions: .png, .svg, .pdf)", o->figure);
        return EXIT_USAGE;
    }
    if (o->json && o->csv && strcmp(o->json, o->csv) == 0) {
        cli_error(strcmp(o->json, "-") == 0
                      ? "design: --json - and --csv - would both write to standard output; give one of them a file"
                      : "design: --json and --csv name the same file");
        return EXIT_USAGE;
    }
    const char *files[3] = {o->json, o->csv, o->figure};
    for (int k = 0; k < 3; ++k)
        if (files[k] && strcmp(files[k], "-") != 0 && cli_output_check_target(files[k]) != 0) return EXIT_FAIL;
    if (o->figure) {
        char gnuplot[CLI_PATH_MAX];
        if (cli_find_program("gnuplot", gnuplot, sizeof gnuplot) != 0) {
            cli_error("design: gnuplot was not found in PATH; install it (Debian: sudo apt-get install gnuplot-nox)");
            return EXIT_FAIL;
        }
    }
    return EXIT_OK;
}

/* The job from the options: EXIT_OK, or the exit status after a message. */
static int make_job(const design_opts *o, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, cli_DesignJob *job,
                    char *note, size_t note_len)
{
    if (!o->jump_at || !o->free) {
        cli_error("design: --jump-at X and --free NAME are required (e.g. --jump-at 1.00m --free rod-offset)");
        return EXIT_USAGE;
    }
    int st = cli_design_free_param(o->free, sa, &job->param);
    if (st == EXIT_OK && (st = cli_batch_build_inputs("design", sa, sim_args, &job->nominal, &job->sim, NULL)) != EXIT_OK)
        return st;
    char err[512];
    if (st == EXIT_OK && (cli_setup_base(sa, &job->base, err, sizeof err) != 0 ||
                          cli_setup_values(sa, &job->values, err, sizeof err) != 0)) {
        cli_error("design: %s", err);
        return EXIT_USAGE;
    }
    if (st == EXIT_OK) {
        st = cli_design_default_range(job, note, note_len);
        if (st == EXIT_OK && o->range) {
            st = parse_range(o->range, job);
            snprintf(note, note_len, "--range");
        }
    }
    if (st == EXIT_OK) st = check_range_ends(job, o->range);
    if (st == EXIT_OK) st = parse_rest(o, job);
    return st;
}

int cmd_design(int argc, char **argv)
{
    design_opts o;
    memset(&o, 0, sizeof o);
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_command_parse(argc, argv, &command, &o, &sa, &sim_args);
    if (st != CLI_GO_ON) return st;
    cli_DesignJob job;
    memset(&job, 0, sizeof job);
    char note[128];
    if ((st = make_job(&o, &sa, &sim_args, &job, note, sizeof note)) != EXIT_OK) return st;
    jc_DesignResult r;
    st = cli_design_run(&job, &r);
    /* standard output carries a document given "-" alone */
    const int text = !(o.json && strcmp(o.json, "-") == 0) && !(o.csv && strcmp(o.csv, "-") == 0);
    if (st == EXIT_OK && text) cli_design_print(&job, &r, note);
    if (st == EXIT_OK && o.json) st = cli_design_write_json(&job, &r, o.json);
    if (st == EXIT_OK && o.csv) st = cli_design_write_csv(&job, &r, o.csv);
    if (st == EXIT_OK && o.figure) {
        char cmdline[2048];
        fig_command_line(argc, argv, cmdline, sizeof cmdline);
        st = cli_design_figure(&job, &r, o.figure, cmdline);
    }
    if (st == EXIT_OK && text) {
        if (o.json) printf("JSON: %s\n", o.json);
        if (o.csv) printf("CSV: %s\n", o.csv);
        if (o.figure) printf("Figure: %s\n", o.figure);
    }
    jc_design_free(&r);
    return st == EXIT_OK ? cli_stdout_finish() : st;
}
