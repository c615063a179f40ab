/* The setup options every command shares, and how they build a jc_Setup. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum {
    O_PRESET, O_RADIUS, O_DISC_MASS, O_ROD_MASS, O_ROD_OFFSET, O_ROD_RADIUS, O_PART,
    O_INCLINE, O_G, O_MU, O_MU_S, O_MU_K, O_RESTITUTION, O_THETA0, O_OMEGA0,
    O_RAMP_LENGTH, O_PAPER_D, O_LENGTH, O_AIR_DENSITY, O_DRAG, O_LIFT, O_SPIN_DRAG, O_ROLLING_RES,
    O_CONFIG, O_DUMP_CONFIG, O_IMPACT_LAW
};

#define B CLI_SETUP_OPT_BASE
const struct option cli_setup_options[CLI_SETUP_OPTION_COUNT] = {
    {"preset", required_argument, 0, B + O_PRESET},
    {"radius", required_argument, 0, B + O_RADIUS},
    {"disc-mass", required_argument, 0, B + O_DISC_MASS},
    {"rod-mass", required_argument, 0, B + O_ROD_MASS},
    {"rod-offset", required_argument, 0, B + O_ROD_OFFSET},
    {"rod-radius", required_argument, 0, B + O_ROD_RADIUS},
    {"part", required_argument, 0, B + O_PART},
    {"incline", required_argument, 0, B + O_INCLINE},
    {"g", required_argument, 0, B + O_G},
    {"mu", required_argument, 0, B + O_MU},
    {"mu-s", required_argument, 0, B + O_MU_S},
    {"mu-k", required_argument, 0, B + O_MU_K},
    {"restitution", required_argument, 0, B + O_RESTITUTION},
    {"theta0", required_argument, 0, B + O_THETA0},
    {"omega0", required_argument, 0, B + O_OMEGA0},
    {"ramp-length", required_argument, 0, B + O_RAMP_LENGTH},
    {"paper-d", required_argument, 0, B + O_PAPER_D},
    {"length", required_argument, 0, B + O_LENGTH},
    {"air-density", required_argument, 0, B + O_AIR_DENSITY},
    {"drag-coefficient", required_argument, 0, B + O_DRAG},
    {"lift-coefficient", required_argument, 0, B + O_LIFT},
    {"spin-drag", required_argument, 0, B + O_SPIN_DRAG},
    {"rolling-resistance", required_argument, 0, B + O_ROLLING_RES},
    {"config", required_argument, 0, B + O_CONFIG},
    {"dump-config", no_argument, 0, B + O_DUMP_CONFIG},
    {"impact-law", required_argument, 0, B + O_IMPACT_LAW},
};

void cli_setup_help(FILE *out)
{
    fputs(
        "Setup options (a plain number is SI, angles are degrees; a number may carry a unit:\n"
        "10cm, 34.2g, 15deg, 0.3rad, 9.78m/s2, 120rpm). Without --preset or --part the setup\n"
        "is the 'paper' preset on a 30 deg incline.\n"
        "  --preset NAME        built-in setup: paper, hoop, rocking-hoop, disc ('jumpcyl presets')\n"
        "  --config FILE        experiment file (docs/config.md): its values replace the\n"
        "                       preset's; the other options replace the file's\n"
        "  --dump-config        print the setup these options give, in the file format\n"
        "                       (exact: it reads back to the same setup), and exit\n"
        "  --radius LEN         rim radius r (the disc of a disc+rod body fills the rim)\n"
        "  --disc-mass MASS     mass of the disc                 (disc+rod bodies)\n"
        "  --rod-mass MASS      mass of the rod                  (disc+rod bodies)\n"
        "  --rod-offset LEN     distance of the rod's axis from the cylinder's axis\n"
        "  --rod-radius LEN     the rod's own radius (0 = a line mass)\n"
        "  --part KIND:KEY=VALUE,...\n"
        "                       a body part; repeat for each; parts replace the preset's body.\n"
        "                       KIND: disc, hoop, rod, point; KEY: mass (required), offset,\n"
        "                       radius (disc, hoop default: the rim radius), angle.\n"
        "                       e.g. --part disc:mass=34.2g --part rod:mass=32.1g,offset=5.5cm\n"
        "  --incline ANGLE      incline angle, [0, 90) deg; 0 is a horizontal floor\n"
        "  --g ACCEL            gravity (paper: 9.78 m/s2)\n"
        "  --mu X               static and kinetic friction coefficient\n"
        "  --mu-s X, --mu-k X   static, kinetic friction coefficient separately\n"
        "  --restitution X      normal restitution at impacts, [0, 1]\n"
        "  --impact-law LAW     stronge (default: never creates energy), poisson or newton\n"
        "                       (these two can gain energy at sticking impacts; a warning says so)\n"
        "  --theta0 ANGLE       initial angle of the CM from the outward normal\n"
        "  --omega0 W           initial angular velocity (> 0 rolls downhill), rad/s\n"
        "  --ramp-length LEN    from the start contact point to the ramp's lower end\n"
        "  --paper-d LEN        CM offset the paper's model uses (default: the printed\n"
        "                       2.65 cm for the paper preset, the exact d otherwise)\n"
        "Air and rolling resistance (all off by default, as in the paper):\n"
        "  --drag-coefficient X C_d: drag 1/2 rho C_d A |v| v on the centre, A = 2 r L\n"
        "  --lift-coefficient X C_L: Magnus force 1/2 rho C_L A v^2 across the velocity;\n"
        "                       C_L > 0 pushes a forward-rolling cylinder into the incline\n"
        "  --spin-drag K        torque -K w|w| on the spin, N m s2\n"
        "  --rolling-resistance LEN  lever arm b of N against the rolling direction, [0, r/2]\n"
        "  --length LEN         cylinder length along its axis (paper: 5.55 cm)\n"
        "  --air-density RHO    kg/m3 (default 1.204, dry air at 20 C and 101.325 kPa)\n",
        out);
}

void cli_merge_options(struct option *dst, int dst_cap, const struct option *cmd, int cmd_count)
{
    int n = 0;
    for (int i = 0; i < cmd_count && n < dst_cap - 1; ++i) dst[n++] = cmd[i];
    for (int i = 0; i < CLI_SETUP_OPTION_COUNT && n < dst_cap - 1; ++i) dst[n++] = cli_setup_options[i];
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
    if (i < 0 || i >= CLI_SETUP_OPTION_COUNT) return 0;
    if (i == O_PART) {
        if (args->part_count >= JC_MAX_PARTS) {
            snprintf(err, err_len, "--part: too many parts (allowed: at most %d)", JC_MAX_PARTS);
            return -1;
        }
        args->part_text[args->part_count++] = text;
        return 1;
    }
    if (!text) text = ""; /* a flag (--dump-config): present, no value */
    if (take_value(&args->value[i], cli_setup_options[i].name, text, err, err_len) < 0) return -1;
    if (i == O_PRESET) args->preset = text;
    return 1;
}

int cli_setup_given(const cli_SetupArgs *args, const char *long_name)
{
    for (int i = 0; i < CLI_SETUP_OPTION_COUNT; ++i)
        if (strcmp(cli_setup_options[i].name, long_name) == 0)
            return i == O_PART ? args->part_count > 0 : args->value[i] != NULL;
    return 0;
}

static int parse_option(const cli_SetupArgs *args, int i, cli_Quantity q, double *out, char *err,
                        size_t err_len)
{
    char msg[256];
    if (cli_parse_quantity(args->value[i], q, out, msg, sizeof msg) != 0) {
        snprintf(err, err_len, "--%s: %s", cli_setup_options[i].name, msg);
        return -1;
    }
    return 0;
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

/* The first part of a kind, for the disc+rod shortcuts. */
static jc_Part *find_part(jc_BodyDef *b, jc_PartKind kind)
{
    for (int i = 0; i < b->part_count; ++i)
        if (b->parts[i].kind == kind) return &b->parts[i];
    return NULL;
}

static int apply_body_options(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    double v;
    if (a->value[O_RADIUS]) {
        if (parse_option(a, O_RADIUS, Q_LENGTH, &v, err, err_len)) return -1;
        /* A preset's rim-filling disc grows with the rim; a disc given with
         * --part keeps the radius given there (its default was already r). */
        jc_Part *disc = a->part_count == 0 ? find_part(&s->body, JC_PART_DISC) : NULL;
        if (disc && disc->radius_m == s->body.radius_m) disc->radius_m = v;
        s->body.radius_m = v;
    }
    static const struct { int opt; jc_PartKind kind; int field; } shortcut[] = {
        {O_DISC_MASS, JC_PART_DISC, 0}, {O_ROD_MASS, JC_PART_ROD, 0},
        {O_ROD_OFFSET, JC_PART_ROD, 1}, {O_ROD_RADIUS, JC_PART_ROD, 2}};
    for (size_t k = 0; k < sizeof shortcut / sizeof shortcut[0]; ++k) {
        const int o = shortcut[k].opt;
        if (!a->value[o]) continue;
        jc_Part *p = find_part(&s->body, shortcut[k].kind);
        if (!p) {
            snprintf(err, err_len, "--%s needs a body with a %s part (the paper or disc preset); with --part, set it in the part",
                     cli_setup_options[o].name, jc_part_kind_name(shortcut[k].kind));
            return -1;
        }
        if (parse_option(a, o, shortcut[k].field == 0 ? Q_MASS : Q_LENGTH, &v, err, err_len)) return -1;
        *(shortcut[k].field == 0 ? &p->mass_kg : shortcut[k].field == 1 ? &p->offset_m : &p->radius_m) = v;
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
    if (a->value[O_CONFIG] && cli_config_load(a->value[O_CONFIG], s, err, err_len) != 0) return -1;
    if (a->part_count > 0) {
        double r = s->body.radius_m;
        if (a->value[O_RADIUS] && parse_option(a, O_RADIUS, Q_LENGTH, &r, err, err_len)) return -1;
        s->body.part_count = a->part_count;
        for (int i = 0; i < a->part_count; ++i)
            if (parse_part(a->part_text[i], r, &s->body.parts[i], err, err_len)) return -1;
    }
    return 0;
}

/* How each single-valued setup option reads its number (the same table
 * builds the setup below). */
static const struct { int opt; cli_Quantity q; size_t field; } scalars[] = {
    {O_INCLINE, Q_ANGLE, offsetof(jc_Setup, incline_rad)},
    {O_G, Q_ACCELERATION, offsetof(jc_Setup, gravity_mps2)},
    {O_MU, Q_NUMBER, offsetof(jc_Setup, mu_static)},
    {O_MU_S, Q_NUMBER, offsetof(jc_Setup, mu_static)},
    {O_MU_K, Q_NUMBER, offsetof(jc_Setup, mu_kinetic)},
    {O_RESTITUTION, Q_NUMBER, offsetof(jc_Setup, restitution)},
    {O_THETA0, Q_ANGLE, offsetof(jc_Setup, theta0_rad)},
    {O_OMEGA0, Q_ANGULAR_SPEED, offsetof(jc_Setup, omega0_radps)},
    {O_RAMP_LENGTH, Q_LENGTH, offsetof(jc_Setup, ramp_length_m)},
    {O_PAPER_D, Q_LENGTH, offsetof(jc_Setup, paper_cm_offset_m)},
    {O_LENGTH, Q_LENGTH, offsetof(jc_Setup, length_m)},
    {O_AIR_DENSITY, Q_DENSITY, offsetof(jc_Setup, air_density_kgpm3)},
    {O_DRAG, Q_NUMBER, offsetof(jc_Setup, drag_coefficient)},
    {O_LIFT, Q_NUMBER, offsetof(jc_Setup, lift_coefficient)},
    {O_SPIN_DRAG, Q_SPIN_DRAG, offsetof(jc_Setup, spin_drag_Nms2)},
    {O_ROLLING_RES, Q_LENGTH, offsetof(jc_Setup, rolling_resistance_m)},
};

int cli_setup_option_quantity(int index, cli_Quantity *q)
{
    if (index == O_RADIUS || index == O_ROD_OFFSET || index == O_ROD_RADIUS) *q = Q_LENGTH;
    else if (index == O_DISC_MASS || index == O_ROD_MASS) *q = Q_MASS;
    else if (index == O_IMPACT_LAW) return 1;
    else {
        size_t k = 0;
        while (k < sizeof scalars / sizeof scalars[0] && scalars[k].opt != index) ++k;
        if (k == sizeof scalars / sizeof scalars[0]) return -1;
        *q = scalars[k].q;
    }
    return 0;
}

int cli_setup_option_index(const char *long_name)
{
    for (int i = 0; i < CLI_SETUP_OPTION_COUNT; ++i)
        if (strcmp(cli_setup_options[i].name, long_name) == 0) return i;
    return -1;
}

int cli_setup_option_value(const jc_Setup *s, int index, double *out)
{
    static const struct { int opt; jc_PartKind kind; int field; } parts[] = {
        {O_DISC_MASS, JC_PART_DISC, 0}, {O_ROD_MASS, JC_PART_ROD, 0},
        {O_ROD_OFFSET, JC_PART_ROD, 1}, {O_ROD_RADIUS, JC_PART_ROD, 2}};
    if (index == O_RADIUS) {
        *out = s->body.radius_m;
        return 0;
    }
    for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k) {
        if (parts[k].opt != index) continue;
        const jc_Part *p = NULL;
        for (int i = s->body.part_count - 1; i >= 0; --i)
            if (s->body.parts[i].kind == parts[k].kind) p = &s->body.parts[i]; /* the first of its kind */
        if (!p) return -1;
        *out = parts[k].field == 0 ? p->mass_kg : parts[k].field == 1 ? p->offset_m : p->radius_m;
        return 0;
    }
    for (size_t k = 0; k < sizeof scalars / sizeof scalars[0]; ++k) {
        if (scalars[k].opt != index) continue;
        memcpy(out, (const char *)s + scalars[k].field, sizeof *out);
        return 0;
    }
    return -1;
}

int cli_setup_build(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    return cli_setup_base(a, s, err, err_len) != 0 ? -1 : cli_setup_apply(a, s, err, err_len);
}

int cli_setup_apply(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    char msg[256];
    if (apply_body_options(a, s, err, err_len)) return -1;
    const int body_changed = a->part_count > 0 || a->value[O_RADIUS] || a->value[O_DISC_MASS] ||
                             a->value[O_ROD_MASS] || a->value[O_ROD_OFFSET] || a->value[O_ROD_RADIUS];
    if (body_changed) s->paper_cm_offset_m = 0.0; /* the printed d was for the paper's body */

    for (size_t k = 0; k < sizeof scalars / sizeof scalars[0]; ++k) {
        double v;
        if (!a->value[scalars[k].opt]) continue;
        if (parse_option(a, scalars[k].opt, scalars[k].q, &v, err, err_len)) return -1;
        memcpy((char *)s + scalars[k].field, &v, sizeof v); /* the double at that offset */
        if (scalars[k].opt == O_MU) s->mu_kinetic = v;
    }
    if (a->value[O_IMPACT_LAW] && jc_impact_law_parse(a->value[O_IMPACT_LAW], &s->impact_law) != JC_OK) {
        snprintf(err, err_len, "--impact-law: unknown law '%s' (allowed: stronge, poisson, newton)",
                 a->value[O_IMPACT_LAW]);
        return -1;
    }
    if (a->value[O_MU] && (a->value[O_MU_S] || a->value[O_MU_K])) {
        snprintf(err, err_len, "--mu sets both coefficients; give either --mu or --mu-s/--mu-k");
        return -1;
    }
    if (jc_setup_validate(s, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "invalid setup: %s", msg);
        return -1;
    }
    return 0;
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

/* A plain number is SI: "--radius 15" is a 15 m wheel. A body length over
 * 1 m or a mass over 10 kg given without a unit is most likely meant in cm
 * or g: a one-line note says how it was read (the ramp's length is metres
 * by nature and gets none). */
static void note_bare_units(const char *cmd, const cli_SetupArgs *a)
{
    static const struct { int opt; double above; const char *unit, *hint; } checks[] = {
        {O_RADIUS, 1.0, "m", "cm"},      {O_ROD_OFFSET, 1.0, "m", "cm"}, {O_ROD_RADIUS, 1.0, "m", "mm"},
        {O_LENGTH, 1.0, "m", "cm"},      {O_PAPER_D, 1.0, "m", "cm"},    {O_ROLLING_RES, 1.0, "m", "mm"},
        {O_DISC_MASS, 10.0, "kg", "g"},  {O_ROD_MASS, 10.0, "kg", "g"},
    };
    for (size_t k = 0; k < sizeof checks / sizeof checks[0]; ++k) {
        const char *text = a->value[checks[k].opt];
        char *end;
        if (!text) continue;
        const double v = strtod(text, &end);
        if (end == text || *end || !(v > checks[k].above)) continue; /* has a unit, or is small */
        fprintf(stderr, "jumpcyl: %s: note: --%s %s was read as %s %s (a plain number is SI); write %s%s for %s\n",
                cmd, cli_setup_options[checks[k].opt].name, text, text, checks[k].unit, text, checks[k].hint,
                strcmp(checks[k].hint, "g") == 0 ? "grams" : strcmp(checks[k].hint, "cm") == 0 ? "centimetres"
                                                                                         : "millimetres");
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
    struct option cmd[32], all[64];
    int n = 0;
    for (int i = 0; i < own_count && n < 32; ++i) cmd[n++] = own[i];
    for (int i = 0; sim_args && i < CLI_SIM_OPTION_COUNT && n < 32; ++i) cmd[n++] = cli_sim_options[i];
    cli_merge_options(all, 64, cmd, n);
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
    if (setup_args->value[O_DUMP_CONFIG]) return dump_config(argv[0], setup_args, sim_args);
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
