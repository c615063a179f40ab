/* The setup options a job varies (--vary) or samples (--sigma, --range).
 * A case's values reach the setup as option text ("0.5235987755982989rad"),
 * through the very code that reads the command line, so a case of a sweep
 * is exactly the run that `jumpcyl simulate` with those options makes. */
#include "batch.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* SI unit of the option text, column suffix and column scale per quantity. */
static const char *si_unit(cli_Quantity q)
{
    switch (q) {
    case Q_LENGTH: return "m";
    case Q_MASS: return "kg";
    case Q_ANGLE: return "rad";
    case Q_ANGULAR_SPEED: return "rad/s";
    case Q_ACCELERATION: return "m/s2";
    case Q_TIME: return "s";
    case Q_DENSITY: return "kg/m3";
    case Q_NUMBER:
    case Q_SPIN_DRAG: break; /* a plain number is already SI */
    }
    return "";
}

static const char *column_suffix(cli_Quantity q)
{
    switch (q) {
    case Q_LENGTH: return "_m";
    case Q_MASS: return "_kg";
    case Q_ANGLE: return "_deg";
    case Q_ANGULAR_SPEED: return "_radps";
    case Q_ACCELERATION: return "_mps2";
    case Q_TIME: return "_s";
    case Q_DENSITY: return "_kgpm3";
    case Q_SPIN_DRAG: return "_Nms2";
    case Q_NUMBER: break;
    }
    return "";
}

/* Which option NAME names, and how its values read. */
static int param_begin(const char *text, size_t name_len, const char *flag, cli_Param *p, char *err, size_t err_len)
{
    char name[40];
    memset(p, 0, sizeof *p);
    p->text = text;
    if (name_len == 0 || name_len >= sizeof name) {
        snprintf(err, err_len, "%s '%s': expected NAME=VALUES with NAME a setup option (e.g. incline=15:45:5)", flag,
                 text);
        return -1;
    }
    memcpy(name, text, name_len);
    name[name_len] = '\0';
    p->option = cli_setup_option_index(name);
    const int how = p->option >= 0 ? cli_setup_option_quantity(p->option, &p->q) : -1;
    if (how < 0) {
        snprintf(err, err_len,
                 "%s '%s': '%s' is not a single-valued setup option (allowed: radius, disc-mass, rod-mass, "
                 "rod-offset, rod-radius, incline, g, mu, mu-s, mu-k, restitution, impact-law, theta0, omega0, "
                 "ramp-length, paper-d, length, air-density, drag-coefficient, lift-coefficient, spin-drag, "
                 "rolling-resistance)",
                 flag, text, name);
        return -1;
    }
    p->is_name = how == 1;
    const char *suffix = p->is_name ? "" : column_suffix(p->q);
    p->unit = *suffix ? suffix + 1 : "";
    snprintf(p->column, sizeof p->column, "%s%s", name, suffix);
    for (char *c = p->column; *c; ++c)
        if (*c == '-') *c = '_';
    p->column_scale = !p->is_name && p->q == Q_ANGLE ? 180.0 / CLI_PI : 1.0;
    return 0;
}

void cli_param_token(const cli_Param *p, double v, char *out, size_t len)
{
    if (p->is_name) snprintf(out, len, "%s", jc_impact_law_name((jc_ImpactLaw)(int)v));
    else snprintf(out, len, "%.17g%s", v, si_unit(p->q));
}

void cli_param_column_value(const cli_Param *p, double v, char *out, size_t len)
{
    if (p->is_name) snprintf(out, len, "%s", jc_impact_law_name((jc_ImpactLaw)(int)v));
    else snprintf(out, len, "%.12g", v * p->column_scale);
}

void cli_param_columns(const cli_Param *params, int n, const double *values, char *out, size_t len)
{
    size_t used = 0;
    out[0] = '\0';
    for (int j = 0; j < n; ++j) {
        char v[CLI_TOKEN_MAX];
        cli_param_column_value(&params[j], values[j], v, sizeof v);
        const int w = snprintf(out + used, len - used, "%s%s", j ? "," : "", v);
        if (w > 0) used += (size_t)w < len - used ? (size_t)w : len - used - 1;
    }
}

void cli_param_free(cli_Param *p)
{
    free(p->values);
    p->values = NULL;
}

double cli_param_nominal(int option, const jc_Setup *s)
{
    double v = NAN;
    return cli_setup_option_value(s, option, &v) == 0 ? v : NAN;
}

int cli_case_setup(const jc_Setup *base, const cli_SetupArgs *args, const cli_Param *params, int n,
                   const double *values, jc_Setup *out, char *err, size_t err_len)
{
    cli_SetupArgs a = *args;
    char tokens[CLI_PARAM_MAX][CLI_TOKEN_MAX];
    for (int i = 0; i < n && i < CLI_PARAM_MAX; ++i) {
        cli_param_token(&params[i], values[i], tokens[i], sizeof tokens[i]);
        a.value[params[i].option] = tokens[i];
    }
    *out = *base;
    return cli_setup_apply(&a, out, err, err_len);
}

/* One value of a list: a number with units, or an impact law's name. */
static int parse_value(const cli_Param *p, const char *flag, const char *tok, double *v, char *err, size_t err_len)
{
    if (p->is_name) {
        jc_ImpactLaw law;
        if (jc_impact_law_parse(tok, &law) != JC_OK) {
            snprintf(err, err_len, "%s '%s': unknown law '%s' (allowed: stronge, poisson, newton)", flag, p->text,
                     tok);
            return -1;
        }
        *v = (double)law;
        return 0;
    }
    char msg[256];
    if (cli_parse_quantity(tok, p->q, v, msg, sizeof msg) != 0) {
        snprintf(err, err_len, "%s '%s': %s", flag, p->text, msg);
        return -1;
    }
    return 0;
}

/* The fields of "a:b:c" or "a,b,c" into their own strings; the count, or -1. */
static int split(const char *s, char sep, char fields[][64], int cap)
{
    int n = 0;
    for (;;) {
        const size_t len = strcspn(s, (char[]){sep, '\0'});
        if (n == cap || len == 0 || len >= 64) return -1;
        memcpy(fields[n], s, len);
        fields[n++][len] = '\0';
        if (s[len] == '\0') return n;
        s += len + 1;
    }
}

static int parse_range(cli_Param *p, const char *vals, char *err, size_t err_len)
{
    char f[3][64];
    double lo, hi, step;
    if (split(vals, ':', f, 3) != 3) {
        snprintf(err, err_len, "--vary '%s': a range is START:STOP:STEP (e.g. incline=15:45:5)", p->text);
        return -1;
    }
    if (parse_value(p, "--vary", f[0], &lo, err, err_len) || parse_value(p, "--vary", f[1], &hi, err, err_len) ||
        parse_value(p, "--vary", f[2], &step, err, err_len))
        return -1;
    if (!(step > 0) || hi < lo) {
        snprintf(err, err_len, "--vary '%s': needs STOP >= START and STEP > 0", p->text);
        return -1;
    }
    const double n = floor((hi - lo) / step + 1e-9) + 1.0;
    if (!(n <= (double)CLI_PARAM_VALUES_MAX)) {
        snprintf(err, err_len, "--vary '%s': %.0f values (allowed: at most %ld per option)", p->text, n,
                 CLI_PARAM_VALUES_MAX);
        return -1;
    }
    p->count = (long)n;
    p->values = malloc((size_t)p->count * sizeof *p->values);
    if (!p->values) {
        snprintf(err, err_len, "--vary '%s': out of memory", p->text);
        return -1;
    }
    /* start + k step, not an accumulated sum; the last value is STOP itself
     * when it lies within rounding of it. */
    for (long k = 0; k < p->count; ++k) p->values[k] = lo + (double)k * step;
    if (fabs(p->values[p->count - 1] - hi) <= 1e-9 * step) p->values[p->count - 1] = hi;
    return 0;
}

static int parse_list(cli_Param *p, const char *vals, char *err, size_t err_len)
{
    long n = 1;
    for (const char *c = vals; *c; ++c) n += *c == ',';
    if (n > CLI_PARAM_VALUES_MAX) {
        snprintf(err, err_len, "--vary '%s': %ld values (allowed: at most %ld per option)", p->text, n,
                 CLI_PARAM_VALUES_MAX);
        return -1;
    }
    p->values = malloc((size_t)n * sizeof *p->values);
    if (!p->values) {
        snprintf(err, err_len, "--vary '%s': out of memory", p->text);
        return -1;
    }
    p->count = 0;
    for (const char *s = vals;;) {
        char tok[64];
        const size_t len = strcspn(s, ",");
        if (len == 0 || len >= sizeof tok) {
            snprintf(err, err_len, "--vary '%s': %s value in the list", p->text, len ? "an overlong" : "an empty");
            return -1;
        }
        memcpy(tok, s, len);
        tok[len] = '\0';
        if (parse_value(p, "--vary", tok, &p->values[p->count++], err, err_len)) return -1;
        if (s[len] == '\0') return 0;
        s += len + 1;
    }
}

int cli_param_parse_vary(const char *text, const cli_SetupArgs *base_args, cli_Param *p, char *err, size_t err_len)
{
    const char *eq = strchr(text, '=');
    if (param_begin(text, eq ? (size_t)(eq - text) : 0, "--vary", p, err, err_len)) return -1;
    p->kind = PARAM_LIST;
    if (!eq[1]) {
        snprintf(err, err_len, "--vary '%s': no values (give START:STOP:STEP or V1,V2,...)", text);
        return -1;
    }
    const int is_range = strchr(eq + 1, ':') != NULL;
    if (is_range && p->is_name) {
        snprintf(err, err_len, "--vary '%s': impact laws are listed by name (e.g. impact-law=stronge,newton)", text);
        return -1;
    }
    if ((is_range ? parse_range(p, eq + 1, err, err_len) : parse_list(p, eq + 1, err, err_len)) != 0) {
        cli_param_free(p);
        return -1;
    }
    /* Each value alone on the job's setup: a value no setup allows (a
     * negative mass, a 95 degree incline) is refused before any work. */
    jc_Setup base, s;
    char msg[400];
    if (cli_setup_base(base_args, &base, msg, sizeof msg) != 0) {
        snprintf(err, err_len, "%s", msg);
        cli_param_free(p);
        return -1;
    }
    for (long k = 0; k < p->count; ++k) {
        if (cli_case_setup(&base, base_args, p, 1, &p->values[k], &s, msg, sizeof msg) != 0) {
            char shown[64];
            cli_param_column_value(p, p->values[k], shown, sizeof shown);
            snprintf(err, err_len, "--vary '%s': the value %s%s is not allowed: %s", text, shown,
                     p->q == Q_ANGLE && !p->is_name ? " deg" : "", msg);
            cli_param_free(p);
            return -1;
        }
    }
    return 0;
}

int cli_param_parse_spread(const char *text, cli_ParamKind kind, const jc_Setup *nominal, cli_Param *p, char *err,
                           size_t err_len)
{
    const char *flag = kind == PARAM_NORMAL ? "--sigma" : "--range";
    const char *eq = strchr(text, '=');
    if (param_begin(text, eq ? (size_t)(eq - text) : 0, flag, p, err, err_len)) return -1;
    p->kind = kind;
    if (p->is_name) {
        snprintf(err, err_len, "%s '%s': impact-law is a name, not a number (vary it with a sweep)", flag, text);
        return -1;
    }
    const double nominal_value = cli_param_nominal(p->option, nominal);
    if (isnan(nominal_value)) {
        snprintf(err, err_len, "%s '%s': the setup's body has no such part (use a disc+rod body)", flag, text);
        return -1;
    }
    if (kind == PARAM_NORMAL) {
        if (parse_value(p, flag, eq + 1, &p->b, err, err_len)) return -1;
        if (!(p->b >= 0)) {
            snprintf(err, err_len, "%s '%s': a standard deviation is >= 0", flag, text);
            return -1;
        }
        p->a = nominal_value;
        return 0;
    }
    char f[2][64];
    if (split(eq + 1, ':', f, 2) != 2) {
        snprintf(err, err_len, "%s '%s': a range is LO:HI (e.g. mu=0.3:1.0)", flag, text);
        return -1;
    }
    if (parse_value(p, flag, f[0], &p->a, err, err_len) || parse_value(p, flag, f[1], &p->b, err, err_len))
        return -1;
    if (!(p->b >= p->a)) {
        snprintf(err, err_len, "%s '%s': needs HI >= LO", flag, text);
        return -1;
    }
    return 0;
}

char *cli_batch_header(const cli_Param *params, int n)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m) return NULL;
    fputs("case", m);
    for (int j = 0; j < n; ++j) fprintf(m, ",%s", params[j].column);
    fputc(',', m);
    cli_outcome_header(m);
    fputc('\n', m);
    if (fclose(m) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}
