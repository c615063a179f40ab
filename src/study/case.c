/* A study's cases: the grid's index taken apart or the Monte Carlo's
 * draws, the setup the values make, and the case as a CSV row. */
#include "study_internal.h"

#include <limits.h>
#include <math.h>
#include <string.h>

/* ---- the study checked ---- */

static int check_param(const jc_StudyDef *def, int j, char *err, size_t err_len)
{
    const jc_StudyParam *p = &def->params[j];
    const jc_ParamInfo *in = jc_param_info(p->id);
    if (!in) return jc_fail(err, err_len, JC_EINVAL, "study parameter %d: no parameter number %d", j, p->id);
    for (int i = 0; i < j; ++i)
        if (def->params[i].id == p->id)
            return jc_fail(err, err_len, JC_EINVAL, "study: %s is given twice (allowed: once)", in->name);
    if (def->kind == JC_STUDY_GRID) {
        if (p->spread != JC_STUDY_VALUES)
            return jc_fail(err, err_len, JC_EINVAL, "study: %s has a spread; a grid's parameters are lists of values",
                           in->name);
        if (!p->values || p->count < 1 || p->count > JC_STUDY_VALUES_MAX)
            return jc_fail(err, err_len, JC_EINVAL, "study: %s has %ld values (allowed: 1 to %ld)", in->name,
                           p->values ? p->count : 0L, JC_STUDY_VALUES_MAX);
        for (long k = 0; k < p->count; ++k)
            if (!isfinite(p->values[k]))
                return jc_fail(err, err_len, JC_EINVAL, "study: %s's value %ld is not a finite number", in->name, k);
        return JC_OK;
    }
    if (p->spread != JC_STUDY_NORMAL && p->spread != JC_STUDY_UNIFORM)
        return jc_fail(err, err_len, JC_EINVAL, "study: %s is a list; a Monte Carlo's parameters have spreads",
                       in->name);
    if (in->quantity == JC_Q_NAME)
        return jc_fail(err, err_len, JC_EINVAL, "study: %s is a name, not a number: it has no spread", in->name);
    if (!isfinite(p->a) || !isfinite(p->b))
        return jc_fail(err, err_len, JC_EINVAL, "study: %s's spread is not finite", in->name);
    if (p->spread == JC_STUDY_NORMAL && !(p->b >= 0))
        return jc_fail(err, err_len, JC_EINVAL, "study: %s's standard deviation %g is negative (allowed: >= 0)",
                       in->name, p->b);
    if (p->spread == JC_STUDY_UNIFORM && !(p->b >= p->a))
        return jc_fail(err, err_len, JC_EINVAL, "study: %s's range %g .. %g is not ordered (allowed: lo <= hi)",
                       in->name, p->a, p->b);
    return JC_OK;
}

int jc_study_check(const jc_StudyDef *def, char *err, size_t err_len)
{
    if (!def) return jc_fail(err, err_len, JC_EINVAL, "study: no study");
    if (def->kind != JC_STUDY_GRID && def->kind != JC_STUDY_MONTE_CARLO)
        return jc_fail(err, err_len, JC_EINVAL, "study: kind %d is unknown (allowed: grid, Monte Carlo)", (int)def->kind);
    const int min = def->kind == JC_STUDY_GRID ? 1 : 0;
    if (def->param_count < min || def->param_count > JC_STUDY_PARAM_MAX)
        return jc_fail(err, err_len, JC_EINVAL, "study: %d parameters (allowed: %d to %d)", def->param_count, min,
                       JC_STUDY_PARAM_MAX);
    if (def->threads < 0) return jc_fail(err, err_len, JC_EINVAL, "study: %d threads (allowed: >= 0)", def->threads);
    if (def->kind == JC_STUDY_MONTE_CARLO && def->samples < 0)
        return jc_fail(err, err_len, JC_EINVAL, "study: %ld samples (allowed: >= 0)", def->samples);
    double cases = 1.0;
    for (int j = 0; j < def->param_count; ++j) {
        const int st = check_param(def, j, err, err_len);
        if (st != JC_OK) return st;
        cases *= (double)def->params[j].count;
    }
    if (def->kind == JC_STUDY_GRID && !(cases <= (double)(LONG_MAX / 2)))
        return jc_fail(err, err_len, JC_EINVAL, "study: %.3g cases (allowed: fewer than %.3g)", cases,
                       (double)(LONG_MAX / 2));
    return JC_OK;
}

long jc_study_case_count(const jc_StudyDef *def)
{
    if (def->kind == JC_STUDY_MONTE_CARLO) return def->samples;
    long n = 1;
    for (int j = 0; j < def->param_count; ++j) n *= def->params[j].count;
    return n;
}

int jc_study_threads(const jc_StudyDef *def) { return jc_thread_count(def->threads); }

/* ---- a case ---- */

/* The setup of the values: the fixed values and the case's over the base. */
static int case_setup(const jc_StudyDef *def, const double *values, jc_Setup *out, char *why, size_t why_len)
{
    jc_ParamValues v = def->fixed;
    for (int j = 0; j < def->param_count; ++j) {
        v.given[def->params[j].id] = 1;
        v.value[def->params[j].id] = values[j];
    }
    *out = def->base;
    return jc_param_values_apply(&v, out, NULL, why, why_len);
}

/* Sample index's values, attempt a: draw a * JC_STUDY_PARAM_MAX + j for parameter j. */
static void draw(const jc_StudyDef *def, long index, int a, double *values)
{
    for (int j = 0; j < def->param_count; ++j) {
        const jc_StudyParam *p = &def->params[j];
        const uint32_t d = (uint32_t)(a * JC_STUDY_PARAM_MAX + j);
        if (p->spread == JC_STUDY_NORMAL)
            values[j] = p->b > 0 ? p->a + p->b * jc_random_normal(def->seed, (uint64_t)index, d) : p->a;
        else
            values[j] = p->a + (p->b - p->a) * jc_random_uniform(def->seed, (uint64_t)index, d);
    }
}

int jc_study_case(const jc_StudyDef *def, long index, double *values, jc_Setup *setup, char *why, size_t why_len)
{
    if (index < 0 || index >= jc_study_case_count(def))
        return jc_fail(why, why_len, JC_EINVAL, "case %ld is not one of the study's (allowed: 0 to %ld)", index,
                       jc_study_case_count(def) - 1);
    if (def->kind == JC_STUDY_GRID) {
        long rest = index;
        for (int j = def->param_count - 1; j >= 0; --j) {
            values[j] = def->params[j].values[rest % def->params[j].count];
            rest /= def->params[j].count;
        }
        return case_setup(def, values, setup, why, why_len);
    }
    int st = JC_EINVAL;
    for (int a = 0; a < JC_STUDY_MC_ATTEMPTS && st != JC_OK; ++a) {
        draw(def, index, a, values);
        st = case_setup(def, values, setup, why, why_len);
    }
    return st;
}

/* ---- columns and rows ---- */

/* A column holds SI values, angles in degrees. */
static double column_per_si(const jc_ParamInfo *in)
{
    return in->quantity == JC_Q_ANGLE ? 180.0 / JC_STUDY_PI : 1.0;
}

/* The unit as a name's suffix: "m/s2" -> "mps2", "N m s2" -> "Nms2". */
static void unit_suffix(const char *unit, char *out, size_t len)
{
    size_t n = 0;
    for (; *unit && n + 1 < len; ++unit) {
        if (*unit == ' ' || *unit == '^') continue;
        out[n++] = *unit == '/' ? 'p' : *unit;
    }
    out[n] = '\0';
}

int jc_study_column(int id, jc_StudyColumn *out)
{
    const jc_ParamInfo *in = jc_param_info(id);
    memset(out, 0, sizeof *out);
    if (!in) return JC_EINVAL;
    const int is_name = in->quantity == JC_Q_NAME;
    unit_suffix(is_name ? "" : in->quantity == JC_Q_ANGLE ? "deg" : in->si_unit, out->unit, sizeof out->unit);
    jc_RowText t = {out->name, sizeof out->name, 0};
    jc_row_text(&t, in->name);
    if (*out->unit) {
        jc_row_text(&t, "_");
        jc_row_text(&t, out->unit);
    }
    for (char *c = out->name; *c; ++c)
        if (*c == '-') *c = '_';
    out->per_si = column_per_si(in);
    return JC_OK;
}

int jc_study_header(const jc_StudyDef *def, char *buf, size_t len)
{
    jc_RowText t = {buf, len, 0};
    if (len > 0) buf[0] = '\0';
    jc_row_text(&t, "case");
    for (int j = 0; j < def->param_count && j < JC_STUDY_PARAM_MAX; ++j) {
        jc_StudyColumn c;
        jc_study_column(def->params[j].id, &c);
        jc_row_text(&t, ",");
        jc_row_text(&t, c.name);
    }
    for (int i = 0; i < JC_CASE_COLUMNS; ++i) {
        jc_row_text(&t, ",");
        jc_row_text(&t, jc_case_column(i)->name);
    }
    jc_row_text(&t, "\n");
    return (int)t.used;
}

int jc_study_row_format(const jc_StudyDef *def, long index, const double *values, const jc_CaseOutcome *o, char *buf,
                        size_t len)
{
    jc_RowText t = {buf, len, 0};
    if (len > 0) buf[0] = '\0';
    jc_row_long(&t, index);
    for (int j = 0; j < def->param_count && j < JC_STUDY_PARAM_MAX; ++j) {
        const jc_ParamInfo *in = jc_param_info(def->params[j].id);
        jc_row_text(&t, ",");
        if (!in) continue;
        if (in->quantity == JC_Q_NAME) {
            char name[48];
            if (jc_param_format(def->params[j].id, values[j], name, sizeof name) == JC_OK) jc_row_text(&t, name);
        } else {
            jc_row_number(&t, values[j] * column_per_si(in), 12);
        }
    }
    if (!o) return (int)t.used;
    jc_row_text(&t, ",");
    if (t.used + 1 < t.len) t.used += (size_t)jc_case_format(o, buf + t.used, t.len - t.used);
    jc_row_text(&t, "\n");
    return (int)t.used;
}
