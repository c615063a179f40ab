/* The setup parameters a job varies (--vary) or samples (--sigma, --range),
 * by the names of the library's table (jc_param_find). They become the
 * library's typed study parameters (cli_param_study): a case's values are
 * set as values over the job's own options, read once, in the order the
 * command line's are (jc_param_values_apply), so a case of a sweep is
 * exactly the run that `jumpcyl simulate` with those options makes, and no
 * text is read per case. */
#include "batch.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void cli_param_describe(int id, cli_Param *p)
{
    const jc_ParamInfo *in = jc_param_info(id);
    jc_StudyColumn c;
    jc_study_column(id, &c);
    p->id = id;
    p->q = in->quantity;
    p->is_name = in->quantity == JC_Q_NAME;
    snprintf(p->column, sizeof p->column, "%s", c.name);
    snprintf(p->unit, sizeof p->unit, "%s", c.unit);
    p->column_scale = c.per_si;
}

jc_StudyParam cli_param_study(const cli_Param *p)
{
    return (jc_StudyParam){p->id, p->kind, p->values, p->count, p->a, p->b};
}

/* "radius, disc-mass, ...": the names of the table's parameters. */
static void param_names(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int id = 0; id < jc_param_count() && used < len; ++id) {
        const int w = snprintf(buf + used, len - used, "%s%s", id ? ", " : "", jc_param_info(id)->name);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* Which parameter NAME names, and how its values read. */
static int param_begin(const char *text, size_t name_len, const char *flag, cli_Param *p, char *err, size_t err_len)
{
    char name[40];
    memset(p, 0, sizeof *p);
    p->text = text;
    if (name_len == 0 || name_len >= sizeof name) {
        snprintf(err, err_len, "%s '%s': expected NAME=VALUES with NAME a setup parameter (e.g. incline=15:45:5)",
                 flag, text);
        return -1;
    }
    memcpy(name, text, name_len);
    name[name_len] = '\0';
    const int id = jc_param_find(name);
    if (id < 0) {
        char names[512];
        param_names(names, sizeof names);
        snprintf(err, err_len, "%s '%s': '%s' is not a single-valued setup option (allowed: %s; see 'jumpcyl params')",
                 flag, text, name, names);
        return -1;
    }
    cli_param_describe(id, p);
    return 0;
}

void cli_param_column_value(const cli_Param *p, double v, char *out, size_t len)
{
    if (p->is_name) jc_param_format(p->id, v, out, len);
    else snprintf(out, len, "%.12g", v * p->column_scale);
}

void cli_param_free(cli_Param *p)
{
    free(p->values);
    p->values = NULL;
}

double cli_param_nominal(int id, const jc_Setup *s)
{
    double v = NAN;
    return jc_param_get(s, id, &v, NULL, 0) == JC_OK ? v : NAN;
}

int cli_case_setup(const jc_Setup *base, const cli_SetupValues *job, const cli_Param *params, int n,
                   const double *values, jc_Setup *out, char *err, size_t err_len)
{
    cli_SetupValues v = *job;
    for (int i = 0; i < n && i < CLI_PARAM_MAX; ++i) {
        v.given[params[i].id] = 1;
        v.value[params[i].id] = values[i];
    }
    *out = *base;
    return cli_setup_apply_values(&v, out, err, err_len);
}

void cli_study_init(jc_StudyDef *def, jc_StudyKind kind, const jc_Setup *base, const cli_SetupValues *values,
                    const cli_Param *params, int n, const jc_SimOptions *sim)
{
    memset(def, 0, sizeof *def);
    def->kind = kind;
    def->base = *base;
    def->fixed = *values;
    def->param_count = n < CLI_PARAM_MAX ? n : CLI_PARAM_MAX;
    for (int j = 0; j < def->param_count; ++j) def->params[j] = cli_param_study(&params[j]);
    def->sim = *sim;
}

/* One value of a list: a number with units, or one of the parameter's names. */
static int parse_value(const cli_Param *p, const char *flag, const char *tok, double *v, char *err, size_t err_len)
{
    char msg[256];
    if (jc_param_parse(p->id, tok, v, msg, sizeof msg) != JC_OK) {
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
    p->kind = JC_STUDY_VALUES;
    if (!eq[1]) {
        snprintf(err, err_len, "--vary '%s': no values (give START:STOP:STEP or V1,V2,...)", text);
        return -1;
    }
    const int is_range = strchr(eq + 1, ':') != NULL;
    if (is_range && p->is_name) {
        snprintf(err, err_len, "--vary '%s': %s is listed by name (e.g. %s=%s,%s)", text, jc_param_info(p->id)->name,
                 jc_param_info(p->id)->name, jc_param_info(p->id)->choices[0], jc_param_info(p->id)->choices[1]);
        return -1;
    }
    if ((is_range ? parse_range(p, eq + 1, err, err_len) : parse_list(p, eq + 1, err, err_len)) != 0) {
        cli_param_free(p);
        return -1;
    }
    /* Each value alone on the job's setup: a value no setup allows (a
     * negative mass, a 95 degree incline) is refused before any work. */
    jc_Setup base, s;
    cli_SetupValues values;
    char msg[400];
    if (cli_setup_base(base_args, &base, msg, sizeof msg) != 0 || cli_setup_values(base_args, &values, msg, sizeof msg) != 0) {
        snprintf(err, err_len, "%s", msg);
        cli_param_free(p);
        return -1;
    }
    for (long k = 0; k < p->count; ++k) {
        if (cli_case_setup(&base, &values, p, 1, &p->values[k], &s, msg, sizeof msg) != 0) {
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

int cli_param_parse_spread(const char *text, jc_StudySpread kind, const jc_Setup *nominal, cli_Param *p, char *err,
                           size_t err_len)
{
    const char *flag = kind == JC_STUDY_NORMAL ? "--sigma" : "--range";
    const char *eq = strchr(text, '=');
    if (param_begin(text, eq ? (size_t)(eq - text) : 0, flag, p, err, err_len)) return -1;
    p->kind = kind;
    if (p->is_name) {
        snprintf(err, err_len, "%s '%s': %s is a name, not a number (vary it with a sweep)", flag, text,
                 jc_param_info(p->id)->name);
        return -1;
    }
    const double nominal_value = cli_param_nominal(p->id, nominal);
    if (isnan(nominal_value)) {
        snprintf(err, err_len, "%s '%s': the setup's body has no such part (use a disc+rod body)", flag, text);
        return -1;
    }
    if (kind == JC_STUDY_NORMAL) {
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
