/* The setup and simulation options as text, collected and built: the
 * options' values as the command line gives them (--preset, --part, --NAME
 * for every parameter of the library's table, the simulation options), and
 * the jc_Setup and jc_SimOptions they make. Reads no file and prints
 * nothing, so that the web page, which shares this file with the tool, has
 * no experiment-file reader to link: --config is options.c's
 * (cli_setup_base). */
#include "inputs.h"

#include <math.h>
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

/* An option's value, stored once: refused with a message when it comes again. */
static cli_OptionTake take_value(const char **slot, const char *name, const char *text, char *err, size_t err_len)
{
    if (*slot) {
        snprintf(err, err_len, "--%s given twice ('%s' and '%s')", name, *slot, text);
        return CLI_OPTION_REFUSED;
    }
    *slot = text;
    return CLI_OPTION_TAKEN;
}

cli_OptionTake cli_setup_take(cli_SetupArgs *args, int opt, const char *text, char *err, size_t err_len)
{
    const int i = opt - B;
    if (i < 0 || i >= CLI_OPT_PARAMS + jc_param_count()) return CLI_OPTION_NOT_OURS;
    if (i == CLI_OPT_PART) {
        if (args->part_count >= JC_MAX_PARTS) {
            snprintf(err, err_len, "--part: too many parts (allowed: at most %d)", JC_MAX_PARTS);
            return CLI_OPTION_REFUSED;
        }
        args->part_text[args->part_count++] = text;
        return CLI_OPTION_TAKEN;
    }
    if (i == CLI_OPT_DUMP_CONFIG) {
        if (args->dump_config) {
            snprintf(err, err_len, "--dump-config given twice");
            return CLI_OPTION_REFUSED;
        }
        args->dump_config = 1;
        return CLI_OPTION_TAKEN;
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

int cli_setup_preset(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    char msg[256];
    *s = jc_paper_setup();
    if (a->preset && jc_preset_setup(a->preset, s, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "--preset: %s", msg);
        return -1;
    }
    return 0;
}

int cli_setup_parts(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
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

int cli_setup_from_options(const cli_SetupArgs *a, jc_Setup *s, char *err, size_t err_len)
{
    if (a->config) {
        snprintf(err, err_len, "--config: no experiment files here; give the options themselves");
        return -1;
    }
    if (cli_setup_preset(a, s, err, err_len) != 0 || cli_setup_parts(a, s, err, err_len) != 0) return -1;
    return cli_setup_apply(a, s, err, err_len);
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

cli_OptionTake cli_sim_take(cli_SimArgs *args, int opt, const char *text, char *err, size_t err_len)
{
    const int i = opt - SB;
    if (i < 0 || i >= CLI_SIM_OPTION_COUNT) return CLI_OPTION_NOT_OURS;
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
