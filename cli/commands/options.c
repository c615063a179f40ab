/* The setup options every command shares, and how they build a jc_Setup:
 * --preset, --part, --config, --dump-config, and --NAME for every parameter
 * of the library's table (jc_param_info). */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define B CLI_SETUP_OPT_BASE

/* The options of the setup that are not parameters. */
static const struct option own_setup_options[CLI_OPT_PARAMS] = {
    {"preset", required_argument, 0, B + CLI_OPT_PRESET},
    {"part", required_argument, 0, B + CLI_OPT_PART},
    {"config", required_argument, 0, B + CLI_OPT_CONFIG},
    {"dump-config", no_argument, 0, B + CLI_OPT_DUMP_CONFIG},
};

int cli_setup_option_table(struct option *dst, int cap)
{
    int n = 0;
    for (int i = 0; i < CLI_OPT_PARAMS && n < cap; ++i) dst[n++] = own_setup_options[i];
    for (int id = 0; id < jc_param_count() && n < cap; ++id)
        dst[n++] = (struct option){jc_param_info(id)->name, required_argument, 0, B + CLI_OPT_PARAMS + id};
    return n;
}

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
          "10cm, 34.2g, 15deg, 0.3rad, 9.78m/s2, 120rpm). Without --preset or --part the setup\n"
          "is the 'paper' preset on a 30 deg incline. 'jumpcyl params' lists every parameter\n"
          "with its unit, range, each preset's value and its experiment-file key.\n",
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

/* An option's value, stored once: 1, or -1 with a message when it comes again. */
static int take_value(const char **slot, const char *name, const char *text, char *err, size_t err_len)
{
    if (*slot) {
        snprintf(err, err_len, "--%s given twice ('%s' and '%s')", name, *slot, text);
        return -1;
    }
    *slot = text;
    return 1;
}

int cli_setup_take(cli_SetupArgs *args, int opt, const char *text, char *err, size_t err_len)
{
    const int i = opt - B;
    if (i < 0 || i >= CLI_OPT_PARAMS + jc_param_count()) return 0;
    if (i == CLI_OPT_PART) {
        if (args->part_count >= JC_MAX_PARTS) {
            snprintf(err, err_len, "--part: too many parts (allowed: at most %d)", JC_MAX_PARTS);
            return -1;
        }
        args->part_text[args->part_count++] = text;
        return 1;
    }
    if (i == CLI_OPT_DUMP_CONFIG) {
        if (args->dump_config) {
            snprintf(err, err_len, "--dump-config given twice");
            return -1;
        }
        args->dump_config = 1;
        return 1;
    }
    if (i == CLI_OPT_PRESET) return take_value(&args->preset, "preset", text, err, err_len);
    if (i == CLI_OPT_CONFIG) return take_value(&args->config, "config", text, err, err_len);
    const int id = i - CLI_OPT_PARAMS;
    return take_value(&args->value[id], jc_param_info(id)->name, text, err, err_len);
}

int cli_setup_given(const cli_SetupArgs *args, const char *long_name)
{
    if (strcmp(long_name, "preset") == 0) return args->preset != NULL;
    if (strcmp(long_name, "part") == 0) return args->part_count > 0;
    if (strcmp(long_name, "config") == 0) return args->config != NULL;
    if (strcmp(long_name, "dump-config") == 0) return args->dump_config;
    const int id = jc_param_find(long_name);
    return id >= 0 && args->value[id] != NULL;
}

static int parse_kind(const char *s, size_t len, jc_PartKind *kind)
{
    static const jc_PartKind kinds[] = {JC_PART_DISC, JC_PART_HOOP, JC_PART_ROD, JC_PART_POINT};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
        const char *name = jc_part_kind_name(kinds[k]);
        if (strlen(name) == len && strncmp(s, name, len) == 0) {
            *kind = kinds[k];
            return 0;
        }
    }
    return -1;
}

/* "rod:mass=32.1g,offset=5.5cm,radius=4.75mm,angle=0" */
static int parse_part(const char *text, double rim_m, jc_Part *p, char *err, size_t err_len)
{
    const char *colon = strchr(text, ':');
    size_t kind_len = colon ? (size_t)(colon - text) : strlen(text);
    if (parse_kind(text, kind_len, &p->kind) != 0) {
        snprintf(err, err_len, "--part '%s': unknown kind '%.*s' (allowed: disc, hoop, rod, point)",
                 text, (int)kind_len, text);
        return -1;
    }
    *p = (jc_Part){p->kind, 0.0, 0.0, 0.0, 0.0};
    if (p->kind == JC_PART_DISC || p->kind == JC_PART_HOOP) p->radius_m = rim_m;
    int have_mass = 0, seen[4] = {0};
    const char *keys[4] = {"mass", "offset", "radius", "angle"};
    const cli_Quantity qs[4] = {Q_MASS, Q_LENGTH, Q_LENGTH, Q_ANGLE};
    double *dst[4] = {&p->mass_kg, &p->offset_m, &p->radius_m, &p->angle_rad};
    const char *s = colon ? colon + 1 : "";
    while (*s) {
        char item[128];
        size_t n = strcspn(s, ",");
        if (n == 0 || n >= sizeof item) {
            snprintf(err, err_len, "--part '%s': %s item (expected KEY=VALUE)", text, n ? "overlong" : "empty");
            return -1;
        }
        memcpy(item, s, n);
        item[n] = '\0';
        s += n + (s[n] == ',');
        if (s[-1] == ',' && !*s) {
            snprintf(err, err_len, "--part '%s': trailing comma", text);
            return -1;
        }
        char *eq = strchr(item, '=');
        if (!eq) {
            snprintf(err, err_len, "--part '%s': '%s' is not KEY=VALUE", text, item);
            return -1;
        }
        *eq = '\0';
        int k = 0;
        while (k < 4 && strcmp(item, keys[k]) != 0) ++k;
        if (k == 4) {
            snprintf(err, err_len, "--part '%s': unknown key '%s' (allowed: mass, offset, radius, angle)", text, item);
            return -1;
        }
        if (seen[k]++) {
            snprintf(err, err_len, "--part '%s': key '%s' given twice", text, item);
            return -1;
        }
        char msg[200];
        if (cli_parse_quantity(eq + 1, qs[k], dst[k], msg, sizeof msg) != 0) {
            snprintf(err, err_len, "--part '%s': %s: %s", text, keys[k], msg);
            return -1;
        }
        if (k == 0) have_mass = 1;
    }
    if (!have_mass) {
        snprintf(err, err_len, "--part '%s': mass is required (e.g. %s:mass=30g)", text, jc_part_kind_name(p->kind));
        return -1;
    }
    return 0;
}

/* One option's value read as its parameter reads it; 0, or -1 with "--NAME: ...". */
static int parse_param(const cli_SetupArgs *a, int id, double *out, char *err, size_t err_len)
{
    char msg[256];
    if (jc_param_parse(id, a->value[id], out, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "--%s: %s", jc_param_info(id)->name, msg);
        return -1;
    }
    return 0;
}

int cli_setup_base(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    char msg[256];
    *s = jc_paper_setup();
    if (a->preset && jc_preset_setup(a->preset, s, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "--preset: %s", msg);
        return -1;
    }
    /* The file's values replace the preset's; the options below replace the file's. */
    if (a->config && cli_config_load(a->config, s, err, err_len) != 0) return -1;
    if (a->part_count > 0) {
        /* A disc or hoop given without a radius fills the rim the options give. */
        const int radius = jc_param_find("radius");
        double r = s->body.radius_m;
        if (a->value[radius] && parse_param(a, radius, &r, err, err_len)) return -1;
        s->body.part_count = a->part_count;
        for (int i = 0; i < a->part_count; ++i)
            if (parse_part(a->part_text[i], r, &s->body.parts[i], err, err_len)) return -1;
    }
    return 0;
}

int cli_setup_build(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    return cli_setup_base(a, s, err, err_len) != 0 ? -1 : cli_setup_apply(a, s, err, err_len);
}

int cli_setup_values(const cli_SetupArgs *a, cli_SetupValues *v, char *err, size_t err_len)
{
    memset(v, 0, sizeof *v);
    v->parts_given = a->part_count > 0;
    for (int id = 0; id < jc_param_count(); ++id) {
        if (!a->value[id]) continue;
        if (parse_param(a, id, &v->value[id], err, err_len)) return -1;
        v->given[id] = 1;
    }
    return 0;
}

/* The ids of the rows a shortcut sets (its 'sets' names); how many. */
static int set_ids(const jc_ParamInfo *in, int *ids, int cap)
{
    int n = 0;
    for (const char *s = in->sets; s && *s && n < cap; s += strspn(s, " ")) {
        char name[40];
        const size_t len = strcspn(s, " ");
        if (len < sizeof name) {
            memcpy(name, s, len);
            name[len] = '\0';
            const int id = jc_param_find(name);
            if (id >= 0) ids[n++] = id;
        }
        s += len;
    }
    return n;
}

/* A shortcut given with a row it sets (--mu with --mu-s): 0, or -1 with a message. */
static int check_shortcuts(const cli_SetupValues *v, char *err, size_t err_len)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        if (!v->given[id] || !in->sets) continue;
        int ids[8], clash = 0;
        const int n = set_ids(in, ids, 8);
        for (int k = 0; k < n; ++k) clash |= v->given[ids[k]];
        if (!clash) continue;
        char both[128] = "", either[128] = "";
        for (int k = 0; k < n; ++k) {
            const char *name = jc_param_info(ids[k])->name;
            size_t used = strlen(both);
            snprintf(both + used, sizeof both - used, "%s--%s", k ? " and " : "", name);
            used = strlen(either);
            snprintf(either + used, sizeof either - used, "%s--%s", k ? "/" : "", name);
        }
        snprintf(err, err_len, "--%s sets %s; give either --%s or %s", in->name, both, in->name, either);
        return -1;
    }
    return 0;
}

int cli_setup_apply_values(const cli_SetupValues *v, jc_Setup *s, char *err, size_t err_len)
{
    char msg[256];
    if (check_shortcuts(v, err, err_len)) return -1;
    /* The library sets them in the table's order, the body first, and checks the setup. */
    int failed = -1;
    if (jc_param_values_apply(v, s, &failed, msg, sizeof msg) == JC_OK) return 0;
    double now;
    if (failed >= 0 && jc_param_get(s, failed, &now, NULL, 0) != JC_OK) /* a body without the part it sets */
        snprintf(err, err_len, "--%s; with --part, give it in the part", msg);
    else
        snprintf(err, err_len, "invalid setup: %s", msg);
    return -1;
}

int cli_setup_apply(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    cli_SetupValues v;
    return cli_setup_values(a, &v, err, err_len) != 0 ? -1 : cli_setup_apply_values(&v, s, err, err_len);
}

/* getopt's '?': an unknown option, or a value given to a flag ("--json=1"). */
static void unknown_option(char **argv, int next)
{
    const char *arg = argv[next - 1];
    if (optopt && strncmp(arg, "--", 2) == 0)
        cli_error("%s: option '%s' takes no value (see 'jumpcyl %s --help')", argv[0], arg, argv[0]);
    else if (optopt > 0 && optopt < 128)
        cli_error("%s: unknown option '-%c' (see 'jumpcyl %s --help')", argv[0], optopt, argv[0]);
    else
        cli_error("%s: unknown option '%s' (see 'jumpcyl %s --help')", argv[0], arg, argv[0]);
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
        return st == JC_EINVAL ? EXIT_USAGE : EXIT_FAIL;
    }
    note_bare_units(cmd, sa);
    return 0;
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
    return 0;
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
    return 0;
}

/* --dump-config: the setup (and simulation options, when the command has
 * them) is built and checked as for a run, then printed instead of run.
 * Returns -1 (done, exit 0) or an exit status. */
static int dump_config(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim)
{
    jc_Setup setup;
    jc_SimOptions opts;
    const int rc = cli_build_inputs(cmd, sa, sim, &setup, &opts, NULL);
    if (rc != 0) return rc;
    cli_config_write(stdout, &setup);
    return cli_stdout_finish() == EXIT_OK ? -1 : EXIT_FAIL;
}

/* Options a command takes many times, each adding one item. */
static int is_repeatable(const char *name)
{
    static const char *const names[] = {"vary", "sigma", "range"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (strcmp(name, names[i]) == 0) return 1;
    return 0;
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
    optind = 0; /* glibc: a full restart, also of a scan left inside "-hh" (tests, fuzzing) */
    opterr = 0;
    int c;
    unsigned own_seen = 0;
    while ((c = getopt_long(argc, argv, ":h", all, NULL)) != -1) {
        char msg[512];
        if (c == '?') {
            unknown_option(argv, optind);
            return EXIT_USAGE;
        }
        if (c == ':') {
            cli_error("%s: option '%s' needs a value", argv[0], argv[optind - 1]);
            return EXIT_USAGE;
        }
        int took = cli_setup_take(setup_args, c, optarg, msg, sizeof msg);
        if (took < 0) {
            cli_error("%s", msg);
            return EXIT_USAGE;
        }
        if (took > 0) continue;
        if (sim_args && (took = cli_sim_take(sim_args, c, optarg, msg, sizeof msg)) != 0) {
            if (took > 0) continue;
            cli_error("%s", msg);
            return EXIT_USAGE;
        }
        /* A command's own option counts once, as the setup options do. */
        for (int i = 0; i < own_count && i < 32; ++i) {
            if (own[i].val != c || c == 'h' || is_repeatable(own[i].name)) continue;
            if (own_seen & (1u << i)) {
                cli_error("%s: --%s given twice", argv[0], own[i].name);
                return EXIT_USAGE;
            }
            own_seen |= 1u << i;
        }
        int r = own_take(c, optarg, ctx);
        if (r != 0) return r;
    }
    if (optind < argc) {
        cli_error("%s: unexpected argument '%s' (see 'jumpcyl %s --help')", argv[0], argv[optind], argv[0]);
        return EXIT_USAGE;
    }
    if (setup_args->dump_config) return dump_config(argv[0], setup_args, sim_args);
    return 0;
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
    return -1;
}

int cli_command_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, cli_SetupArgs *setup_args,
                      cli_SimArgs *sim_args)
{
    command_take t = {cmd, ctx, sim_args != NULL};
    const int st = cli_parse_args(argc, argv, cmd->own, cmd->own_count, take_or_help, &t, setup_args, sim_args);
    if (st < 0) return EXIT_OK; /* --help or --dump-config printed what was asked */
    return st ? st : CLI_GO_ON;
}

static int take_json(int opt, const char *arg, void *ctx)
{
    (void)arg;
    if (opt != 'j') return EXIT_USAGE;
    *(int *)ctx = 1;
    return 0;
}

int cli_json_command_parse(int argc, char **argv, void (*help)(void), int *json, cli_SetupArgs *setup_args)
{
    static const struct option own[] = {{"json", no_argument, 0, 'j'}, {"help", no_argument, 0, 'h'}};
    const cli_Command cmd = {own, 2, take_json, help};
    return cli_command_parse(argc, argv, &cmd, json, setup_args, NULL);
}

/* ---- simulator options ---- */

enum { S_T_MAX, S_MAX_EVENTS, S_SAMPLE_DT, S_RTOL, S_ATOL, S_EVENT_TOL, S_CONTACT_HEIGHT };
#define SB CLI_SIM_OPT_BASE
const struct option cli_sim_options[CLI_SIM_OPTION_COUNT] = {
    {"t-max", required_argument, 0, SB + S_T_MAX},
    {"max-events", required_argument, 0, SB + S_MAX_EVENTS},
    {"sample-dt", required_argument, 0, SB + S_SAMPLE_DT},
    {"rtol", required_argument, 0, SB + S_RTOL},
    {"atol", required_argument, 0, SB + S_ATOL},
    {"event-tol", required_argument, 0, SB + S_EVENT_TOL},
    {"contact-height", required_argument, 0, SB + S_CONTACT_HEIGHT},
};

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

int cli_sim_take(cli_SimArgs *args, int opt, const char *text, char *err, size_t err_len)
{
    const int i = opt - SB;
    if (i < 0 || i >= CLI_SIM_OPTION_COUNT) return 0;
    return take_value(&args->value[i], cli_sim_options[i].name, text, err, err_len);
}

int cli_sim_given(const cli_SimArgs *args, const char *long_name)
{
    for (int i = 0; i < CLI_SIM_OPTION_COUNT; ++i)
        if (strcmp(cli_sim_options[i].name, long_name) == 0) return args->value[i] != NULL;
    return 0;
}

int cli_sim_build(const cli_SimArgs *a, jc_SimOptions *o, char *err, size_t err_len)
{
    *o = jc_default_sim_options();
    char msg[256];
    for (int i = 0; i < CLI_SIM_OPTION_COUNT; ++i) {
        if (!a->value[i]) continue;
        double v = 0.0;
        int bad;
        switch (i) {
        case S_T_MAX: case S_SAMPLE_DT: case S_EVENT_TOL: bad = cli_parse_quantity(a->value[i], Q_TIME, &v, msg, sizeof msg); break;
        case S_CONTACT_HEIGHT: bad = cli_parse_quantity(a->value[i], Q_LENGTH, &v, msg, sizeof msg); break;
        default: bad = cli_parse_quantity(a->value[i], Q_NUMBER, &v, msg, sizeof msg); break;
        }
        if (!bad && i == S_MAX_EVENTS && (v != floor(v) || v < 1 || v > 1e7)) {
            snprintf(msg, sizeof msg, "'%s' is out of range (allowed: a whole number from 1 to 10000000)", a->value[i]);
            bad = 1;
        }
        if (bad) {
            snprintf(err, err_len, "--%s: %s", cli_sim_options[i].name, msg);
            return -1;
        }
        switch (i) {
        case S_T_MAX: o->t_max_s = v; break;
        case S_MAX_EVENTS: o->max_events = (int)v; break;
        case S_SAMPLE_DT: o->sample_dt_s = v; break;
        case S_RTOL: o->ode_rtol = v; break;
        case S_ATOL: o->ode_atol = v; break;
        case S_EVENT_TOL: o->event_tol_s = v; break;
        case S_CONTACT_HEIGHT: o->contact_height_m = v; break;
        }
    }
    if (jc_sim_options_validate(o, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "invalid simulation options: %s", msg);
        return -1;
    }
    return 0;
}

void cli_options_help(FILE *out, int with_sim)
{
    if (with_sim) {
        cli_sim_help(out);
        fputc('\n', out);
    }
    cli_setup_help(out);
}
