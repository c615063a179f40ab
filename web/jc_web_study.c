/*
 * The page's studies: a sweep of one parameter, and the spread of the jump
 * site under the library's default tolerances, both on the library's
 * studies layer (include/jumpcyl/study.h, jc_study_run).
 *
 * The request's setup is read as jc_web_simulate reads it (web_read_inputs)
 * and made into a jc_StudyDef as the tool's sweep and mc make theirs
 * (cli/commands/sweep.c, cli/batch/mc_job.c): the preset and parts are the
 * base, the single values given are set over it on every case, the grid's
 * values are start + k step. So a row here is the tool's row for the same
 * options (make test-web compares them), and no text is read per case: the
 * rows come through the study's row callback as outcomes.
 */
#include "jc_web.h"

#include "outputs.h" /* cli_json_number */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SWEEP_POINTS_MIN 2
#define SWEEP_POINTS_MAX 401
#define SPREAD_SAMPLES_MIN 10
#define SPREAD_SAMPLES_MAX 20000
#define SPREAD_SAMPLES_DEFAULT 1000
#define SEED_MAX 9007199254740991.0 /* 2^53 - 1: every whole number up to it is a JSON number */

/* ---- the request ---- */

/* The request as an object of the keys allowed (NULL-terminated; each
 * once); NULL with a message otherwise. */
static cJSON *parse_request(const char *json, const char *const *keys, char *err, size_t err_len)
{
    cJSON *req = json ? cJSON_Parse(json) : NULL;
    if (!cJSON_IsObject(req)) {
        cJSON_Delete(req);
        snprintf(err, err_len, "the request is not a JSON object (e.g. {\"setup\": {\"incline\": 30}, \"%s\": ...})",
                 keys[1]);
        return NULL;
    }
    for (const cJSON *it = req->child; it; it = it->next) {
        int known = 0;
        for (const char *const *k = keys; *k && !known; ++k) known = strcmp(it->string, *k) == 0;
        int repeated = 0;
        for (const cJSON *before = req->child; before != it && !repeated; before = before->next)
            repeated = strcmp(before->string, it->string) == 0;
        if (known && !repeated) continue;
        char allowed[128] = "";
        for (const char *const *k = keys; *k; ++k) {
            const size_t used = strlen(allowed);
            snprintf(allowed + used, sizeof allowed - used, "%s%s", k == keys ? "" : ", ", *k);
        }
        if (repeated)
            snprintf(err, err_len, "'%.60s' given twice (give each key once)", it->string);
        else
            snprintf(err, err_len, "unknown key '%.60s' (allowed: %s)", it->string, allowed);
        cJSON_Delete(req);
        return NULL;
    }
    return req;
}

/* A member as it was written, for messages (cut to fit): a number as the
 * answers write numbers (cli_json_number), every digit that tells it. */
static void shown(const cJSON *v, char *buf, size_t len)
{
    if (cJSON_IsNumber(v)) {
        char number[CLI_JSON_NUMBER_MAX];
        cli_json_number(v->valuedouble, number);
        snprintf(buf, len, "%s", number);
        return;
    }
    char *text = cJSON_PrintUnformatted(v);
    snprintf(buf, len, "%.40s", text ? text : "?");
    free(text);
}

/* Member key as a whole number from lo to hi (a JSON number), dflt when
 * absent. 0, or -1 with a message naming the value and the range. */
static int whole_member(const cJSON *req, const char *key, double lo, double hi, double dflt, double *out,
                        char *err, size_t err_len)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(req, key);
    *out = dflt;
    if (!v) return 0;
    if (cJSON_IsNumber(v) && v->valuedouble >= lo && v->valuedouble <= hi && v->valuedouble == floor(v->valuedouble)) {
        *out = v->valuedouble;
        return 0;
    }
    char was[48];
    shown(v, was, sizeof was);
    snprintf(err, err_len, "%s: %s is not a whole number from %.0f to %.0f", key, was, lo, hi);
    return -1;
}

/* The member "setup" read as jc_web_simulate reads its request ({} when
 * absent). 0, or -1 with a message. */
static int setup_member(const cJSON *req, web_Inputs *in, char *err, size_t err_len)
{
    const cJSON *setup = cJSON_GetObjectItemCaseSensitive(req, "setup");
    if (setup && !cJSON_IsObject(setup)) {
        snprintf(err, err_len, "setup: must be an object of options, as jc_web_simulate takes (e.g. {\"incline\": 30})");
        return -1;
    }
    cJSON *empty = setup ? NULL : cJSON_CreateObject();
    if (!setup && !empty) {
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    const int st = web_read_inputs(setup ? setup : empty, in, err, err_len);
    cJSON_Delete(empty);
    return st;
}

/* Whether a value for id is given, itself or through the rows it sets (mu
 * through mu-s or mu-k): the tool's rule for which default spread the user
 * has taken over (cli/batch/mc_job.c, user_owns). */
static int given(const jc_ParamValues *v, int id)
{
    for (int set = 0; set < jc_param_count(); ++set)
        if (v->given[set] && (set == id || jc_param_sets(id, set))) return 1;
    return 0;
}

/* Drops id from the values, with the rows it sets when it is a shortcut
 * (mu: mu-s and mu-k). */
static void drop(jc_ParamValues *v, int id)
{
    for (int set = 0; set < jc_param_count(); ++set)
        if (set == id || jc_param_sets(id, set)) v->given[set] = 0;
}

/* The display unit's value of one SI unit's worth: the row's unit (deg, cm,
 * g) over its SI unit. */
static double per_si(const jc_ParamInfo *p)
{
    double to_si = 1.0;
    for (int i = 0; p->unit[0] && strcmp(p->unit, p->si_unit) != 0; ++i) {
        const char *u = jc_quantity_unit(p->quantity, i, &to_si);
        if (!u) return 1.0;
        if (strcmp(u, p->unit) == 0) break;
    }
    return 1.0 / to_si;
}

/* ---- the sweep ---- */

/* "radius, disc-mass, ...": the numeric parameters, for messages. */
static void numeric_names(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int id = 0; id < jc_param_count() && used < len; ++id) {
        const jc_ParamInfo *p = jc_param_info(id);
        if (p->quantity == JC_Q_NAME) continue;
        const int w = snprintf(buf + used, len - used, "%s%s", used ? ", " : "", p->name);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* Member "vary": a numeric parameter the setup has (the current value in
 * *current). 0, or -1 with a message. */
static int vary_member(const cJSON *req, const web_Inputs *in, int *id, double *current, char *err, size_t err_len)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(req, "vary");
    char names[512], msg[256];
    numeric_names(names, sizeof names);
    *id = cJSON_IsString(v) ? jc_param_find(v->valuestring) : -1;
    if (*id < 0) {
        char was[48] = "nothing";
        if (v) shown(v, was, sizeof was);
        snprintf(err, err_len, "vary: %s is not a parameter (allowed: %s)", was, names);
        return -1;
    }
    const jc_ParamInfo *p = jc_param_info(*id);
    if (p->quantity == JC_Q_NAME) {
        snprintf(err, err_len, "vary: '%s' takes names, not a range of numbers (allowed: %s)", p->name, names);
        return -1;
    }
    if (strcmp(p->name, "radius") == 0 && in->values.parts_given) {
        snprintf(err, err_len, "vary: radius with a body given part by part: vary a disc+rod body's radius");
        return -1;
    }
    if (jc_param_get(&in->setup, *id, current, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "vary: %s", msg);
        return -1;
    }
    return 0;
}

/* Member key ("lo", "hi"): a value of parameter id, read as the request's
 * values are (a string with units, or a number: SI, angles in degrees),
 * that the parameter takes in the setup. 0, or -1 with a message. */
static int end_member(const cJSON *req, const char *key, int id, const jc_Setup *setup, double *out, char *err,
                      size_t err_len)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(req, key);
    char slot[32], msg[256];
    if (!v) {
        snprintf(err, err_len, "%s: missing (the range's %s end, e.g. \"10deg\" or 10)", key,
                 strcmp(key, "lo") == 0 ? "lower" : "upper");
        return -1;
    }
    const char *text = web_value_text(v, key, slot, err, err_len);
    if (!text) return -1;
    jc_Setup check = *setup;
    if (jc_param_parse(id, text, out, msg, sizeof msg) != JC_OK ||
        jc_param_set(&check, id, *out, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "%s: %s", key, msg);
        return -1;
    }
    return 0;
}

typedef struct {
    cJSON *rows;
    double per_si;
} sweep_ctx;

static void number_or_null(cJSON *o, const char *key, int has, double v)
{
    if (has) cJSON_AddNumberToObject(o, key, v);
    else cJSON_AddNullToObject(o, key);
}

/* What a case did, as `jumpcyl sweep`'s CSV has it (jc_case_format): the
 * first event, the first slip's and lift-off's x, the lift-offs, how it
 * ended; nulls for what it has not (an invalid or failed case has only its
 * termination). */
static void add_outcome(cJSON *r, const jc_CaseOutcome *o)
{
    const jc_RunSummary *s = &o->summary;
    const int ran = o->kind != JC_CASE_INVALID && o->kind != JC_CASE_FAILED;
    cJSON_AddStringToObject(r, "kind", jc_case_kind_name(o->kind));
    if (ran) cJSON_AddStringToObject(r, "first_event", s->first_event >= 0 ? jc_event_name(s->first_event_kind) : "none");
    else cJSON_AddNullToObject(r, "first_event");
    number_or_null(r, "slip_x_m", ran && s->first_slip >= 0, s->first_slip_state.x_m);
    number_or_null(r, "liftoff_x_m", ran && s->first_liftoff >= 0, s->first_liftoff_state.x_m);
    number_or_null(r, "liftoffs", ran, s->liftoffs);
    cJSON_AddStringToObject(r, "termination", ran ? jc_termination_name(o->termination) : jc_case_kind_name(o->kind));
}

/* One row of the grid into the answer; nonzero (stop) when memory ran out. */
static int sweep_row(void *ctx, const jc_StudyRow *row)
{
    const sweep_ctx *c = ctx;
    cJSON *r = cJSON_CreateObject();
    if (!r || !cJSON_AddItemToArray(c->rows, r)) {
        cJSON_Delete(r);
        return 1;
    }
    cJSON_AddNumberToObject(r, "value_si", row->values[0]);
    cJSON_AddNumberToObject(r, "value", row->values[0] * c->per_si);
    add_outcome(r, row->outcome);
    return 0;
}

/* The sweep's definition read from the request: NULL, or the answer that
 * refuses it. values: n values (free them). */
static char *read_sweep(const char *request_json, jc_StudyDef *def, double **values, double *current)
{
    static const char *const keys[] = {"setup", "vary", "lo", "hi", "n", NULL};
    char err[WEB_ERR_LEN];
    cJSON *req = parse_request(request_json, keys, err, sizeof err);
    if (!req) return web_error(err);
    web_Inputs in;
    int id = -1;
    double lo = 0, hi = 0, n = 0;
    int rc = setup_member(req, &in, err, sizeof err) || vary_member(req, &in, &id, current, err, sizeof err) ||
             end_member(req, "lo", id, &in.setup, &lo, err, sizeof err) ||
             end_member(req, "hi", id, &in.setup, &hi, err, sizeof err) ||
             whole_member(req, "n", SWEEP_POINTS_MIN, SWEEP_POINTS_MAX, 51, &n, err, sizeof err);
    if (!rc && !(lo < hi)) {
        char a[64], b[64];
        jc_param_format(id, lo, a, sizeof a);
        jc_param_format(id, hi, b, sizeof b);
        snprintf(err, sizeof err, "lo %s is not below hi %s (allowed: lo < hi)", a, b);
        rc = -1;
    }
    cJSON_Delete(req);
    if (rc) return web_error(err);
    const long count = (long)n;
    *values = malloc((size_t)count * sizeof **values);
    if (!*values) return web_error("out of memory");
    /* start + k step, the last one hi itself: the tool's --vary NAME=lo:hi:step */
    const double step = (hi - lo) / (double)(count - 1);
    for (long k = 0; k < count; ++k) (*values)[k] = lo + (double)k * step;
    (*values)[count - 1] = hi;
    memset(def, 0, sizeof *def);
    def->kind = JC_STUDY_GRID;
    def->base = in.base;
    def->fixed = in.values;
    /* The varied value replaces the setup's own (and a shortcut's rows, mu's
     * mu-s and mu-k); a shortcut setting it stays, set before it (mu, then
     * the varied mu-s). */
    drop(&def->fixed, id);
    def->params[0] = (jc_StudyParam){id, JC_STUDY_VALUES, *values, count, 0.0, 0.0};
    def->param_count = 1;
    def->sim = in.sim;
    return NULL;
}

JC_WEB_EXPORT char *jc_web_sweep(const char *request_json)
{
    jc_StudyDef *def = malloc(sizeof *def);
    if (!def) return NULL;
    double *values = NULL, current = 0;
    char *text = read_sweep(request_json, def, &values, &current);
    if (text) {
        free(def);
        return text;
    }
    const jc_ParamInfo *p = jc_param_info(def->params[0].id);
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddTrueToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "vary", p->name);
    cJSON_AddStringToObject(doc, "label", p->label);
    cJSON_AddStringToObject(doc, "unit", p->unit);
    cJSON_AddStringToObject(doc, "si_unit", p->si_unit);
    sweep_ctx c = {NULL, per_si(p)};
    cJSON_AddNumberToObject(doc, "per_si", c.per_si);
    cJSON_AddNumberToObject(doc, "current_si", current);
    cJSON_AddNumberToObject(doc, "current", current * c.per_si);
    c.rows = cJSON_AddArrayToObject(doc, "rows");
    char err[WEB_ERR_LEN];
    const jc_StudyCallbacks cb = {sweep_row, NULL, &c, 0};
    const int st = c.rows ? jc_study_run(def, 0, def->params[0].count, &cb, err, sizeof err) : JC_ENOMEM;
    free(values);
    free(def);
    if (st != JC_OK) {
        cJSON_Delete(doc);
        return web_error(st == JC_ESTOPPED || st == JC_ENOMEM ? "out of memory for the sweep's rows" : err);
    }
    return web_print(doc);
}

/* ---- the spread of the jump site ---- */

static int tally_row(void *ctx, const jc_StudyRow *row)
{
    return jc_tally_add(ctx, row->outcome) == JC_OK ? 0 : 1;
}

static const char *spread_name(jc_StudySpread s)
{
    return s == JC_STUDY_NORMAL ? "normal" : s == JC_STUDY_UNIFORM ? "uniform" : "values";
}

/* The Monte Carlo's definition: the library's default spreads about the
 * setup, but for what the request sets (the tool's mc without --sigma and
 * --range). why: each spread's words. NULL, or the answer that refuses it. */
static char *read_spread(const char *request_json, jc_StudyDef *def, const char **why)
{
    static const char *const keys[] = {"setup", "samples", "seed", NULL};
    char err[WEB_ERR_LEN];
    cJSON *req = parse_request(request_json, keys, err, sizeof err);
    if (!req) return web_error(err);
    web_Inputs in;
    double samples = 0, seed = 0;
    const int rc = setup_member(req, &in, err, sizeof err) ||
                   whole_member(req, "samples", SPREAD_SAMPLES_MIN, SPREAD_SAMPLES_MAX, SPREAD_SAMPLES_DEFAULT,
                                &samples, err, sizeof err) ||
                   whole_member(req, "seed", 0, SEED_MAX, 1, &seed, err, sizeof err);
    cJSON_Delete(req);
    if (rc) return web_error(err);
    memset(def, 0, sizeof *def);
    def->kind = JC_STUDY_MONTE_CARLO;
    def->base = in.base;
    def->fixed = in.values;
    def->samples = (long)samples;
    def->seed = (uint64_t)seed;
    def->sim = in.sim;
    jc_StudyParam spreads[JC_STUDY_PARAM_MAX];
    const char *words[JC_STUDY_PARAM_MAX];
    const int n = jc_study_default_spreads(&in.setup, spreads, words, JC_STUDY_PARAM_MAX);
    for (int k = 0; k < n && k < JC_STUDY_PARAM_MAX; ++k) {
        if (given(&in.values, spreads[k].id)) continue;
        why[def->param_count] = words[k];
        def->params[def->param_count++] = spreads[k];
    }
    return NULL;
}

static cJSON *spreads_json(const jc_StudyDef *def, const char *const *why)
{
    cJSON *arr = cJSON_CreateArray();
    for (int k = 0; arr && k < def->param_count; ++k) {
        const jc_StudyParam *p = &def->params[k];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(arr, o);
        cJSON_AddStringToObject(o, "name", jc_param_info(p->id)->name);
        cJSON_AddStringToObject(o, "spread", spread_name(p->spread));
        cJSON_AddNumberToObject(o, "a", p->a);
        cJSON_AddNumberToObject(o, "b", p->b);
        cJSON_AddStringToObject(o, "si_unit", jc_param_info(p->id)->si_unit);
        cJSON_AddStringToObject(o, "why", why[k] ? why[k] : "");
    }
    return arr;
}

/* The first lift-off's statistics as `jumpcyl mc --json` names them. */
static cJSON *stats_json(const jc_Stats *s, long valid)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "count", (double)s->n);
    cJSON_AddNumberToObject(o, "fraction", valid ? (double)s->n / (double)valid : 0.0);
    number_or_null(o, "mean", s->n > 0, s->mean);
    number_or_null(o, "sd", s->n > 0, s->sd);
    number_or_null(o, "p2_5", s->n > 0, s->p2_5);
    number_or_null(o, "p50", s->n > 0, s->p50);
    number_or_null(o, "p97_5", s->n > 0, s->p97_5);
    return o;
}

JC_WEB_EXPORT char *jc_web_uncertainty(const char *request_json)
{
    jc_StudyDef *def = malloc(sizeof *def);
    if (!def) return NULL;
    const char *why[JC_STUDY_PARAM_MAX];
    char *text = read_spread(request_json, def, why);
    if (text) {
        free(def);
        return text;
    }
    char err[WEB_ERR_LEN];
    jc_Tally t;
    int st = jc_tally_init(&t, def->samples);
    const jc_StudyCallbacks cb = {tally_row, NULL, &t, 0};
    if (st == JC_OK) st = jc_study_run(def, 0, def->samples, &cb, err, sizeof err);
    cJSON *doc = st == JC_OK ? cJSON_CreateObject() : NULL;
    if (doc) {
        jc_Stats x;
        jc_stats_compute(t.liftoff_x_m, t.liftoffs, t.none, t.invalid, JC_MC_LIFTOFF_GAP_M, &x);
        cJSON_AddTrueToObject(doc, "ok");
        cJSON_AddNumberToObject(doc, "samples", (double)def->samples);
        cJSON_AddNumberToObject(doc, "seed", (double)def->seed);
        cJSON_AddNumberToObject(doc, "valid", (double)t.valid);
        cJSON_AddNumberToObject(doc, "invalid", (double)t.invalid);
        cJSON_AddNumberToObject(doc, "slides_at_start", (double)t.slides);
        cJSON_AddNumberToObject(doc, "no_liftoff", (double)t.none);
        cJSON_AddItemToObject(doc, "first_liftoff_x_m", stats_json(&x, t.valid));
        cJSON_AddItemToObject(doc, "spreads", spreads_json(def, why));
    }
    jc_tally_free(&t);
    free(def);
    if (st != JC_OK) return web_error(st == JC_ESTOPPED || st == JC_ENOMEM ? "out of memory for the samples" : err);
    return web_print(doc);
}
