/* The setup and simulation options every command shares, on the command
 * line: their help, argv parsed (getopt), --config's experiment file under
 * the setup (cli_setup_base), --dump-config, and a command's inputs built
 * or the one-line error. The options themselves, collected as text and
 * built into a jc_Setup and jc_SimOptions without any file, are
 * setup_args.c's, which the web page shares. */
#include "inputs.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The placeholder of a value in the help: --radius LEN. */
static const char *metavar(const jc_ParamInfo *in)
{
    switch (in->quantity) {
    case JC_Q_LENGTH: return "LEN";
    case JC_Q_MASS: return "MASS";
    case JC_Q_ANGLE: return "ANGLE";
    case JC_Q_ANGULAR_SPEED: return "W";
    case JC_Q_ACCELERATION: return "ACCEL";
    case JC_Q_TIME: return "T";
    case JC_Q_DENSITY: return "RHO";
    case JC_Q_SPIN_DRAG: return "K";
    case JC_Q_NAME: return "NAME";
    case JC_Q_NUMBER: break;
    }
    return "X";
}

#define HELP_INDENT 23
#define HELP_WIDTH 90

/* "  --radius LEN         text", the text wrapped at HELP_WIDTH under itself. */
static void help_item(FILE *out, const char *head, const char *text)
{
    int col = fprintf(out, "  %s", head);
    if (col >= HELP_INDENT) {
        fputc('\n', out);
        col = 0;
    }
    fprintf(out, "%*s", HELP_INDENT - col, "");
    col = HELP_INDENT;
    while (*text) {
        const size_t word = strcspn(text, " ");
        if (col > HELP_INDENT && col + 1 + (int)word > HELP_WIDTH) {
            fprintf(out, "\n%*s", HELP_INDENT, "");
            col = HELP_INDENT;
        } else if (col > HELP_INDENT) {
            fputc(' ', out);
            ++col;
        }
        fwrite(text, 1, word, out);
        col += (int)word;
        text += word;
        text += strspn(text, " ");
    }
    fputc('\n', out);
}

void cli_setup_help(FILE *out)
{
    fputs("Setup options (a plain number is SI, angles are degrees; a number may carry a unit:\n"
          "10cm, 34.2g, 15deg, 0.3rad, 9.78m/s2, 120rpm, and the forms the figures print: 15\u00b0,\n"
          "9.78m/s\u00b2). Without --preset or --part the setup is the 'paper' preset on a 30 deg\n"
          "incline. 'jumpcyl params' lists every parameter with its unit, range, each preset's\n"
          "value and its experiment-file key.\n",
          out);
    help_item(out, "--preset NAME", "built-in setup: paper, hoop, rocking-hoop, disc ('jumpcyl presets')");
    help_item(out, "--config FILE",
              "experiment file (docs/config.md): its values replace the preset's; the other options replace the "
              "file's");
    help_item(out, "--dump-config",
              "print the setup these options give, in the file format (exact: it reads back to the same setup), "
              "and exit");
    fputs("  --part KIND:KEY=VALUE,...\n"
          "                       a body part; repeat for each; parts replace the preset's body.\n"
          "                       KIND: disc, hoop, rod, point; KEY: mass (required), offset,\n"
          "                       radius (disc, hoop default: the rim radius), angle.\n"
          "                       e.g. --part disc:mass=34.2g --part rod:mass=32.1g,offset=5.5cm\n",
          out);
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        char head[64], text[400], range[80] = "";
        snprintf(head, sizeof head, "--%s %s", in->name, metavar(in));
        /* a short range is worth its words: [0, 90) deg, [0, 1] */
        const int angle = in->quantity == JC_Q_ANGLE;
        const double k = angle ? 180.0 / CLI_PI : 1.0;
        const char *unit = angle ? "deg" : in->si_unit;
        if (in->quantity != JC_Q_NAME && isfinite(in->max) && fabs(in->min * k) <= 100.0 && fabs(in->max * k) <= 100.0)
            snprintf(range, sizeof range, ", %s%g, %g%s%s%s", in->min_open ? "(" : "[", in->min * k, in->max * k,
                     in->max_open ? ")" : "]", *unit ? " " : "", unit);
        snprintf(text, sizeof text, "%s%s%s%s", in->help, range, in->bound ? "; " : "", in->bound ? in->bound : "");
        help_item(out, head, text);
    }
}

void cli_merge_options(struct option *dst, int dst_cap, const struct option *cmd, int cmd_count)
{
    int n = 0;
    for (int i = 0; i < cmd_count && n < dst_cap - 1; ++i) dst[n++] = cmd[i];
    n += cli_setup_option_table(dst + n, dst_cap - 1 - n);
    dst[n] = (struct option){0, 0, 0, 0};
}

int cli_setup_base(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    if (cli_setup_preset(a, s, err, err_len) != 0) return -1;
    /* The file's values replace the preset's; the options below replace the file's. */
    if (a->config && cli_config_load(a->config, s, err, err_len) != 0) return -1;
    return cli_setup_parts(a, s, err, err_len);
}

int cli_setup_build(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    return cli_setup_base(a, s, err, err_len) != 0 ? -1 : cli_setup_apply(a, s, err, err_len);
}

/* The edit distance of a and b (their first 63 bytes): insertions,
 * deletions and substitutions, each 1. */
static int edit_distance(const char *a, const char *b)
{
    int row[64];
    const int n = (int)strnlen(b, 63), m = (int)strnlen(a, 63);
    for (int j = 0; j <= n; ++j) row[j] = j;
    for (int i = 1; i <= m; ++i) {
        int diag = row[0];
        row[0] = i;
        for (int j = 1; j <= n; ++j) {
            const int up = row[j];
            const int sub = diag + (a[i - 1] != b[j - 1]);
            row[j] = sub < up + 1 ? sub : up + 1;
            if (row[j - 1] + 1 < row[j]) row[j] = row[j - 1] + 1;
            diag = up;
        }
    }
    return row[n];
}

/* "; did you mean --incline?" for a long option the table does not have:
 * the options it begins (an ambiguous abbreviation, up to 4 named), else
 * the nearest by edit distance when it is near (at most 2, or a third of
 * its length); "" when none is. */
static void option_hint(const struct option *all, const char *given, char *out, size_t len)
{
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(given, "="), given);
    const size_t n = strlen(name);
    int starts = 0, best = -1, best_d = 1 << 20;
    size_t used = (size_t)snprintf(out, len, "; did you mean ");
    for (int i = 0; all[i].name; ++i) {
        if (n > 0 && strncmp(all[i].name, name, n) == 0) {
            if (starts < 4 && used < len)
                used += (size_t)snprintf(out + used, len - used, "%s--%s", starts ? ", " : "", all[i].name);
            ++starts;
        }
        const int d = edit_distance(name, all[i].name);
        if (d < best_d) {
            best_d = d;
            best = i;
        }
    }
    if (starts > 1) {
        if (used < len) snprintf(out + used, len - used, "%s?", starts > 4 ? ", ..." : "");
        return;
    }
    const int near = best_d <= 2 || best_d * 3 <= (int)n;
    if (best >= 0 && near && n > 0) snprintf(out, len, "; did you mean --%s?", all[best].name);
    else out[0] = '\0';
}

/* getopt's '?': an unknown or ambiguous option, or a value given to a flag
 * ("--quiet=1"). getopt leaves optind past a long option; an unknown short
 * one is named by optopt. */
static void unknown_option(char **argv, int next, const struct option *all)
{
    const char *arg = argv[next - 1];
    const int is_long = strncmp(arg, "--", 2) == 0 && arg[2];
    if (optopt && is_long && strchr(arg, '=')) {
        cli_error("%s: option '%.*s' takes no value (see 'jumpcyl %s --help')", argv[0], (int)strcspn(arg, "="), arg,
                  argv[0]);
    } else if (optopt > 0 && optopt < 128) {
        cli_error("%s: unknown option '-%c' (see 'jumpcyl %s --help')", argv[0], optopt, argv[0]);
    } else {
        char hint[256] = "";
        if (is_long) option_hint(all, arg + 2, hint, sizeof hint);
        cli_error("%s: unknown option '%s'%s (see 'jumpcyl %s --help')", argv[0], arg, hint, argv[0]);
    }
}

/* "--radius 10 cm": a number, then a unit as a word of its own, which the
 * parse finds as an unexpected argument. Whether unit is such a word after
 * the value number: number and unit together read as a quantity. */
static int is_unit_after(const char *number, const char *unit)
{
    static const cli_Quantity quantities[] = {Q_LENGTH, Q_MASS,    Q_ANGLE,   Q_ANGULAR_SPEED,
                                              Q_ACCELERATION, Q_TIME, Q_DENSITY, Q_SPIN_DRAG};
    char token[128];
    double v;
    if (snprintf(token, sizeof token, "%s%s", number, unit) >= (int)sizeof token) return 0;
    if (cli_parse_quantity(number, Q_NUMBER, &v, NULL, 0) != 0) return 0; /* not a plain number */
    for (size_t k = 0; k < sizeof quantities / sizeof quantities[0]; ++k)
        if (cli_parse_quantity(token, quantities[k], &v, NULL, 0) == 0) return 1;
    return 0;
}

/* The unexpected argument word (getopt has moved every word that is not
 * an option or its value to the end): "write 10cm" when, in the words as
 * given (words), it follows an option's number as its unit. */
static void unexpected_argument(char **argv, const char *word, char *const *words, int count)
{
    for (int i = 2; i < count; ++i) {
        if (words[i] != word || strncmp(words[i - 2], "--", 2) != 0 || strchr(words[i - 2], '=') ||
            !is_unit_after(words[i - 1], word))
            continue;
        cli_error("%s: unexpected argument '%s': a unit goes with its number, without a blank: write %s %s%s",
                  argv[0], word, words[i - 2], words[i - 1], word);
        return;
    }
    cli_error("%s: unexpected argument '%s' (see 'jumpcyl %s --help')", argv[0], word, argv[0]);
}

/* A plain number is SI: "--radius 15" is a 15 m wheel. A length over 1 m
 * or a mass over 10 kg given without a unit, for a parameter people give in
 * cm, mm or g, is most likely meant in that unit: a one-line note says how it
 * was read (the ramp's length is metres by nature and gets none). */
static void note_bare_units(const char *cmd, const cli_SetupArgs *a)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        const char *text = a->value[id];
        const int length = in->quantity == JC_Q_LENGTH, mass = in->quantity == JC_Q_MASS;
        if (!text || !(length || mass) || strcmp(in->unit, in->si_unit) == 0) continue;
        char *end;
        const double v = strtod(text, &end);
        if (end == text || *end || !(v > (mass ? 10.0 : 1.0))) continue; /* has a unit, or is small */
        fprintf(stderr, "jumpcyl: %s: note: --%s %s was read as %s %s (a plain number is SI); write %s%s for %s\n",
                cmd, in->name, text, text, in->si_unit, text, in->unit,
                strcmp(in->unit, "g") == 0 ? "grams" : strcmp(in->unit, "cm") == 0 ? "centimetres" : "millimetres");
    }
}

int cli_build_inputs(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_Setup *setup,
                     jc_SimOptions *sim, jc_Model *model)
{
    char err[512];
    if (cli_setup_build(sa, setup, err, sizeof err) != 0 ||
        (sim_args && sim && cli_sim_build(sim_args, sim, err, sizeof err) != 0)) {
        cli_error("%s: %s", cmd, err);
        return EXIT_USAGE;
    }
    const int st = model ? jc_model_init(model, setup, err, sizeof err) : JC_OK;
    if (st != JC_OK) {
        cli_error("%s: %s", cmd, err);
        return cli_exit_status(st, CLI_INPUTS_GIVEN);
    }
    note_bare_units(cmd, sa);
    return EXIT_OK;
}

int cli_build_model(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_SimOptions *sim,
                    jc_Model *model)
{
    jc_Setup setup;
    return cli_build_inputs(cmd, sa, sim_args, &setup, sim, model);
}

int cli_run_inputs_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, cli_RunInputs *in)
{
    return cli_command_parse(argc, argv, cmd, ctx, &in->args, &in->sim_args);
}

int cli_run_inputs_build(const char *cmd, cli_RunInputs *in)
{
    return cli_build_model(cmd, &in->args, &in->sim_args, &in->sim, &in->model);
}

int cli_take_once(const char *cmd, const char **slot, const char *name, const char *arg)
{
    if (*slot) {
        cli_error("%s: --%s given twice ('%s' and '%s')", cmd, name, *slot, arg);
        return EXIT_USAGE;
    }
    *slot = arg;
    return CLI_GO_ON;
}

int cli_parse_seed(const char *cmd, const char *text, uint64_t *seed)
{
    char *end;
    errno = 0;
    const unsigned long long s = strtoull(text, &end, 10);
    /* Digits alone: strtoull would also skip blanks and take a sign (and
     * wrap "-1" round); past 2^64 - 1 it sets errno. */
    if (!isdigit((unsigned char)text[0]) || *end || errno) {
        cli_error("%s: --seed '%s' is not valid (allowed: a whole number from 0 to %llu)", cmd, text,
                  (unsigned long long)UINT64_MAX);
        return EXIT_USAGE;
    }
    *seed = (uint64_t)s;
    return EXIT_OK;
}

/* --dump-config: the setup (and simulation options, when the command has
 * them) is built and checked as for a run, then printed instead of run.
 * The exit status: EXIT_OK when it is printed. */
static int dump_config(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim)
{
    jc_Setup setup;
    jc_SimOptions opts;
    const int rc = cli_build_inputs(cmd, sa, sim, &setup, &opts, NULL);
    if (rc != EXIT_OK) return rc;
    cli_config_write(stdout, &setup);
    return cli_stdout_finish();
}

/* Options a command takes many times, each adding one item. */
static int is_repeatable(const char *name)
{
    static const char *const names[] = {"vary", "sigma", "range"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (strcmp(name, names[i]) == 0) return 1;
    return 0;
}

/* What the parse knows while it goes through argv. */
typedef struct {
    char **argv;
    const struct option *all; /* every option the command takes */
    const struct option *own;
    int own_count;
    unsigned own_seen; /* the command's own options given so far, by index */
    cli_own_take_fn own_take;
    void *ctx;
    cli_SetupArgs *setup_args;
    cli_SimArgs *sim_args;
} parse_state;

/* A setup or simulation option; CLI_OPTION_REFUSED after the message. */
static cli_OptionTake take_shared(const parse_state *p, int c, const char *arg)
{
    char msg[512];
    cli_OptionTake took = cli_setup_take(p->setup_args, c, arg, msg, sizeof msg);
    if (took == CLI_OPTION_NOT_OURS && p->sim_args) took = cli_sim_take(p->sim_args, c, arg, msg, sizeof msg);
    if (took == CLI_OPTION_REFUSED) cli_error("%s: %s", p->argv[0], msg);
    return took;
}

/* A command's own option, which counts once as the setup options do
 * (unless repeatable), then its take. CLI_GO_ON, or the exit status. */
static int take_own(parse_state *p, int c, const char *arg)
{
    for (int i = 0; i < p->own_count && i < 32; ++i) {
        if (p->own[i].val != c || c == 'h' || is_repeatable(p->own[i].name)) continue;
        if (p->own_seen & (1u << i)) {
            cli_error("%s: --%s given twice", p->argv[0], p->own[i].name);
            return EXIT_USAGE;
        }
        p->own_seen |= 1u << i;
    }
    return p->own_take(c, arg, p->ctx);
}

/* One option getopt_long returned. CLI_GO_ON, or the exit status. */
static int take_option(parse_state *p, int c, const char *arg)
{
    if (c == '?') {
        unknown_option(p->argv, optind, p->all);
        return EXIT_USAGE;
    }
    if (c == ':') {
        cli_error("%s: option '%s' needs a value", p->argv[0], p->argv[optind - 1]);
        return EXIT_USAGE;
    }
    const cli_OptionTake shared = take_shared(p, c, arg);
    if (shared == CLI_OPTION_REFUSED) return EXIT_USAGE;
    return shared == CLI_OPTION_TAKEN ? CLI_GO_ON : take_own(p, c, arg);
}

int cli_parse_args(int argc, char **argv, const struct option *own, int own_count,
                   cli_own_take_fn own_take, void *ctx, cli_SetupArgs *setup_args, cli_SimArgs *sim_args)
{
    struct option cmd[32], all[32 + CLI_SETUP_OPTION_MAX + 1];
    int n = 0;
    for (int i = 0; i < own_count && n < 32; ++i) cmd[n++] = own[i];
    for (int i = 0; sim_args && i < CLI_SIM_OPTION_COUNT && n < 32; ++i) cmd[n++] = cli_sim_options[i];
    cli_merge_options(all, (int)(sizeof all / sizeof all[0]), cmd, n);
    *setup_args = (cli_SetupArgs){0};
    if (sim_args) *sim_args = (cli_SimArgs){0};
    parse_state p = {argv, all, own, own_count, 0, own_take, ctx, setup_args, sim_args};
    /* the words as given, before getopt moves them: for the hint on a unit given apart */
    char *words[256];
    const int count = argc < 256 ? argc : 256;
    for (int i = 0; i < count; ++i) words[i] = argv[i];
    optind = 0; /* glibc: a full restart, also of a scan left inside "-hh" (tests, fuzzing) */
    opterr = 0;
    int c, index = -1;
    while ((c = getopt_long(argc, argv, ":h", all, &index)) != -1) {
        /* an output option (optional_argument): its FILE, or "-" */
        const char *arg = c != '?' && c != ':' && index >= 0 && all[index].has_arg == optional_argument
                              ? cli_output_optarg(argc, argv)
                              : optarg;
        const int st = take_option(&p, c, arg);
        if (st != CLI_GO_ON) return st;
        index = -1;
    }
    if (optind < argc) {
        unexpected_argument(argv, argv[optind], words, count);
        return EXIT_USAGE;
    }
    return setup_args->dump_config ? dump_config(argv[0], setup_args, sim_args) : CLI_GO_ON;
}

/* A command's take, with --help answered the same way for every command. */
typedef struct {
    const cli_Command *cmd;
    void *ctx;
    int with_sim;
} command_take;

static int take_or_help(int opt, const char *arg, void *p)
{
    const command_take *t = p;
    if (opt != 'h') return t->cmd->take(opt, arg, t->ctx);
    t->cmd->help();
    cli_options_help(stdout, t->with_sim);
    return EXIT_OK;
}

int cli_command_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, cli_SetupArgs *setup_args,
                      cli_SimArgs *sim_args)
{
    command_take t = {cmd, ctx, sim_args != NULL};
    return cli_parse_args(argc, argv, cmd->own, cmd->own_count, take_or_help, &t, setup_args, sim_args);
}

int cli_output_value_follows(const char *next)
{
    return next && (next[0] != '-' || strcmp(next, "-") == 0);
}

const char *cli_output_optarg(int argc, char **argv)
{
    if (optarg) return optarg;
    if (optind < argc && cli_output_value_follows(argv[optind])) return argv[optind++];
    return "-";
}

static int take_json(int opt, const char *arg, void *ctx)
{
    if (opt != 'j') return EXIT_USAGE;
    *(const char **)ctx = arg;
    return CLI_GO_ON;
}

int cli_json_command_parse(int argc, char **argv, void (*help)(void), const char **json, cli_SetupArgs *setup_args)
{
    static const struct option own[] = {CLI_JSON_OPTION('j'), {"help", no_argument, 0, 'h'}};
    const cli_Command cmd = {own, 2, take_json, help};
    return cli_command_parse(argc, argv, &cmd, json, setup_args, NULL);
}

/* ---- simulator options (their table and reading: setup_args.c) ---- */

void cli_sim_help(FILE *out)
{
    const jc_SimOptions d = jc_default_sim_options();
    fprintf(out,
            "Simulation options:\n"
            "  --t-max T            simulated time limit, s (default %g)\n"
            "  --max-events N       event limit (default %d)\n"
            "  --sample-dt T        trajectory sample spacing, s (default: samples at events only)\n"
            "  --rtol X, --atol X   sliding integrator tolerances (default %g, %g)\n"
            "  --event-tol T        event location tolerance, s (default %g)\n"
            "  --contact-height LEN an impact whose rebound would rise less than this ends in\n"
            "                       contact: ends Zeno bounce sequences (default %g m)\n",
            d.t_max_s, d.max_events, d.ode_rtol, d.ode_atol, d.event_tol_s, d.contact_height_m);
}

void cli_options_help(FILE *out, int with_sim)
{
    if (with_sim) {
        cli_sim_help(out);
        fputc('\n', out);
    }
    cli_setup_help(out);
}
