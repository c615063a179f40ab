/*
 * The WebAssembly entry point: one setup in (a JSON object whose keys are
 * the command line's option names and whose values are read as the command
 * line reads them), one run out (`jumpcyl simulate --json`'s document plus
 * the sampled trajectory as columns and the first lift-off).
 *
 * A thin client of the tool's own code, compiled into the wasm too: the
 * options are collected with cli_setup_take / cli_sim_take and built with
 * cli_setup_from_options / cli_sim_build (cli/inputs/setup_args.c,
 * units.c: the command line's options without its files), the document is
 * cli_sim_json_doc's (cli/outputs/sim_json.c, report.c), printed with the
 * tool's exact numbers (cli_json_text, cli/outputs/json_text.c). The page
 * and the tool cannot disagree on a setup or on a field. The page reads no
 * file: 'config' is refused.
 *
 * jc_web_params gives the library's parameter table (what `jumpcyl params
 * --json` prints), from which the page makes its controls. Sweeps and the
 * spread of the jump site are web/jc_web_study.c's, on the library's
 * studies; both files read a setup with web_read_inputs (here).
 *
 * Every returned string is malloc'd and owned by the caller: free it with
 * jc_web_free. A bad request gives {"ok": false, "error": "..."} (one
 * line), never an abort. NULL only when memory ran out.
 *
 * No global mutable state; the only process-wide setting touched is GSL's
 * error handler, switched off as the library's header asks.
 */
#include "jc_web.h"

#include "inputs.h"
#include "figures.h" /* cli_paper_row (cli/figures/paper_row.c) */

#include <gsl/gsl_errno.h>
#include <jumpcyl/jumpcyl.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WEB_DEFAULT_MAX_SAMPLES 100000 /* the library's default is 10^6: too much JSON for a page */
#define NUM_LEN 32

/* ---- the request ---- */

/* The parsed request and the texts the option collectors point into: the
 * cJSON tree (strings as they are) and one slot per member for a number
 * printed with %.17g (reads back to the same double). Kept until the
 * setup and the options are built. */
typedef struct {
    cli_SetupArgs setup;
    cli_SimArgs sim;
    const char *max_samples;
    int binary; /* sample-format "binary" */
    char (*numbers)[NUM_LEN];
} request_args;

const char *web_value_text(const cJSON *v, const char *key, char *slot, char *err, size_t err_len)
{
    if (cJSON_IsString(v)) return v->valuestring;
    if (cJSON_IsNumber(v) && isfinite(v->valuedouble)) {
        snprintf(slot, NUM_LEN, "%.17g", v->valuedouble);
        return slot;
    }
    snprintf(err, err_len, "'%.60s' must be a number or a string (as on the command line: \"10cm\", \"15deg\")",
             key);
    return NULL;
}

/* One member: a simulation option, max-samples, or a setup option. */
static int take_member(request_args *a, const cJSON *it, char *slot, char *err, size_t err_len)
{
    const char *key = it->string;
    if (strcmp(key, "config") == 0 || strcmp(key, "dump-config") == 0) {
        snprintf(err, err_len, "'%s' is not available in the browser (no files): give the options themselves", key);
        return -1;
    }
    for (int i = 0; i < CLI_SIM_OPTION_COUNT; ++i)
        if (strcmp(key, cli_sim_options[i].name) == 0) {
            const char *text = web_value_text(it, key, slot, err, err_len);
            if (!text) return -1;
            return cli_sim_take(&a->sim, cli_sim_options[i].val, text, err, err_len) == CLI_OPTION_REFUSED ? -1 : 0;
        }
    if (strcmp(key, "sample-format") == 0) { /* the page's own: "json" (default) or "binary" */
        const int json = cJSON_IsString(it) && strcmp(it->valuestring, "json") == 0;
        a->binary = cJSON_IsString(it) && strcmp(it->valuestring, "binary") == 0;
        if (json || a->binary) return 0;
        snprintf(err, err_len, "sample-format: must be \"json\" or \"binary\"");
        return -1;
    }
    if (strcmp(key, "max-samples") == 0) { /* the page's own: the tool keeps every sample */
        a->max_samples = web_value_text(it, key, slot, err, err_len);
        return a->max_samples ? 0 : -1;
    }
    struct option table[CLI_SETUP_OPTION_MAX];
    const int n = cli_setup_option_table(table, CLI_SETUP_OPTION_MAX);
    int idx = 0;
    while (idx < n && strcmp(table[idx].name, key) != 0) ++idx;
    if (idx == n) {
        snprintf(err, err_len, "unknown option '%.60s' (the keys are the command line's option names, docs/web.md)",
                 key);
        return -1;
    }
    const int val = table[idx].val;
    if (strcmp(key, "part") == 0 && cJSON_IsArray(it)) { /* --part, once per string */
        for (const cJSON *p = it->child; p; p = p->next) {
            if (!cJSON_IsString(p)) {
                snprintf(err, err_len, "'part' must be a string or an array of strings (\"rod:mass=32.1g,offset=5.5cm\")");
                return -1;
            }
            if (cli_setup_take(&a->setup, val, p->valuestring, err, err_len) == CLI_OPTION_REFUSED) return -1;
        }
        return 0;
    }
    const char *text = web_value_text(it, key, slot, err, err_len);
    return !text || cli_setup_take(&a->setup, val, text, err, err_len) == CLI_OPTION_REFUSED ? -1 : 0;
}

int web_read_inputs(const cJSON *req, web_Inputs *in, char *err, size_t err_len)
{
    gsl_set_error_handler_off(); /* GSL reports failures as status codes, never aborts */
    memset(in, 0, sizeof *in);
    request_args a;
    memset(&a, 0, sizeof a);
    const int members = cJSON_GetArraySize(req);
    a.numbers = calloc((size_t)(members > 0 ? members : 1), sizeof *a.numbers);
    if (!a.numbers) {
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    int rc = 0, k = 0;
    for (const cJSON *it = req->child; !rc && it; it = it->next, ++k)
        rc = take_member(&a, it, a.numbers[k], err, err_len);
    jc_SimOptions *o = &in->sim;
    if (!rc) rc = cli_setup_from_options(&a.setup, &in->setup, err, err_len) || cli_sim_build(&a.sim, o, err, err_len);
    /* The same setup in a study's terms: the preset and parts, and the
     * single values set over them (as the tool's batch jobs take them). */
    if (!rc)
        rc = cli_setup_preset(&a.setup, &in->base, err, err_len) || cli_setup_parts(&a.setup, &in->base, err, err_len) ||
             cli_setup_values(&a.setup, &in->values, err, err_len);
    if (!rc) {
        double v = WEB_DEFAULT_MAX_SAMPLES;
        char msg[256];
        if (a.max_samples && (cli_parse_quantity(a.max_samples, Q_NUMBER, &v, msg, sizeof msg) != 0 ||
                              v != floor(v) || v < 1 || v > 1e7)) {
            snprintf(err, err_len, "max-samples: '%.40s' is not a whole number from 1 to 10000000", a.max_samples);
            rc = -1;
        }
        o->max_samples = (int)v;
        if (!rc && jc_sim_options_validate(o, msg, sizeof msg) != JC_OK) {
            snprintf(err, err_len, "invalid simulation options: %s", msg);
            rc = -1;
        }
    }
    free(a.numbers);
    in->binary = a.binary;
    return rc ? -1 : 0;
}

/* ---- the answer ---- */

/* A growing text, for the sample columns: printed straight, not through a
 * cJSON node per number. */
typedef struct {
    char *text;
    size_t len, cap;
    int failed;
} text_buf;

static void put(text_buf *b, const char *s, size_t n)
{
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + n + 1) cap *= 2;
        char *p = realloc(b->text, cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->text = p;
        b->cap = cap;
    }
    memcpy(b->text + b->len, s, n);
    b->len += n;
    b->text[b->len] = '\0';
}

/* %.17g: reads back to the same double, as every number of the answer
 * does, with one printf. The rest of the answer has the shortest such form
 * (cli_json_number: up to three printf and strtod calls each), which in
 * wasm (musl) takes four to five times as long for the sample columns,
 * where the answer's time goes. null for NaN and infinities. */
static void put_number(text_buf *b, double v)
{
    char tmp[32];
    if (!isfinite(v)) {
        put(b, "null", 4);
        return;
    }
    const int n = snprintf(tmp, sizeof tmp, "%.17g", v);
    put(b, tmp, (size_t)n);
}

static void put_text(text_buf *b, const char *s)
{
    put(b, s, strlen(s));
}

/* The modes as a JSON array of names. */
static void put_modes(text_buf *b, const jc_Run *run)
{
    put(b, "[", 1);
    for (int i = 0; i < run->sample_count; ++i) {
        if (i) put(b, ",", 1);
        put(b, "\"", 1);
        put_text(b, jc_mode_name(run->samples[i].mode));
        put(b, "\"", 1);
    }
    put(b, "]", 1);
}

/* The library's sample columns (jc_sample_column_info), each an array:
 * {"count": N, "t_s": [...], "mode": [...], "x_m": [...], ...} as raw JSON,
 * in the table's order. With binary, {"count": N, "mode": [...],
 * "columns": ["t_s", "x_m", ...], "buffer": ADDRESS} instead: the numeric
 * columns' names, and ADDRESS that of count doubles per numeric column,
 * column after column in that order, which the caller reads from the wasm
 * memory and frees with jc_web_free (no printing, no parsing: the page's
 * way). NaN and infinities stay as they are there. */
static cJSON *samples_json(const jc_Run *run, int binary)
{
    text_buf b = {NULL, 0, 0, 0};
    char head[64];
    put(&b, head, (size_t)snprintf(head, sizeof head, "{\"count\":%d", run->sample_count));
    if (binary) {
        const size_t n = (size_t)run->sample_count;
        double *buf = malloc((n ? n : 1) * JC_SAMPLE_COLUMNS * sizeof *buf);
        if (!buf) b.failed = 1;
        put_text(&b, ",\"mode\":");
        put_modes(&b, run);
        put_text(&b, ",\"columns\":[");
        size_t k = 0; /* numeric columns so far */
        for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
            const jc_SampleColumn *col = jc_sample_column_info(c);
            if (col->is_mode) continue;
            put_text(&b, k ? ",\"" : "\"");
            put_text(&b, col->name);
            put(&b, "\"", 1);
            for (size_t i = 0; buf && i < n; ++i) buf[k * n + i] = jc_sample_value(&run->samples[i], c);
            ++k;
        }
        char tail[48];
        put(&b, tail, (size_t)snprintf(tail, sizeof tail, "],\"buffer\":%lu}", (unsigned long)(uintptr_t)buf));
        cJSON *raw = b.failed ? NULL : cJSON_CreateRaw(b.text);
        if (!raw) free(buf); /* (if memory runs out after this, the buffer is lost with the answer) */
        free(b.text);
        return raw;
    }
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        const jc_SampleColumn *col = jc_sample_column_info(c);
        put_text(&b, ",\"");
        put_text(&b, col->name);
        put_text(&b, "\":");
        if (col->is_mode) {
            put_modes(&b, run);
            continue;
        }
        put(&b, "[", 1);
        for (int i = 0; i < run->sample_count; ++i) {
            if (i) put(&b, ",", 1);
            put_number(&b, jc_sample_value(&run->samples[i], c));
        }
        put(&b, "]", 1);
    }
    put(&b, "}", 1);
    cJSON *raw = b.failed ? NULL : cJSON_CreateRaw(b.text);
    free(b.text);
    return raw;
}

/* The samples as `jumpcyl simulate --csv` writes them: the header, then a
 * row per sample (jc_sample_format_row), the same bytes. NULL when memory
 * ran out. */
static char *samples_csv(const jc_Run *run)
{
    text_buf b = {NULL, 0, 0, 0};
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        if (c) put(&b, ",", 1);
        put_text(&b, jc_sample_column_info(c)->name);
    }
    put(&b, "\n", 1);
    char row[JC_SAMPLE_ROW_MAX + 1];
    for (int i = 0; i < run->sample_count; ++i) {
        size_t n = (size_t)jc_sample_format_row(&run->samples[i], row, sizeof row - 1);
        row[n++] = '\n';
        put(&b, row, n);
    }
    if (b.failed) {
        free(b.text);
        return NULL;
    }
    return b.text;
}

static void add_state(cJSON *o, const jc_State *st)
{
    cJSON_AddNumberToObject(o, "t", st->t_s);
    cJSON_AddNumberToObject(o, "x", st->x_m);
    cJSON_AddNumberToObject(o, "y", st->y_m);
    cJSON_AddNumberToObject(o, "theta", st->theta_rad);
    cJSON_AddNumberToObject(o, "omega", st->omega_radps);
    cJSON_AddNumberToObject(o, "vx", st->vx_mps);
    cJSON_AddNumberToObject(o, "vy", st->vy_mps);
}

/* {"ok": true, "version"} + `simulate --json`'s members (cli_sim_json_doc),
 * with the samples after the events, then the page's extras. */
static cJSON *run_json(const jc_Model *m, const jc_Run *run, int binary)
{
    cJSON *sim = cli_sim_json_doc(m, run);
    cJSON *samples = samples_json(run, binary);
    cJSON *doc = cJSON_CreateObject();
    if (!sim || !samples || !doc) {
        cJSON_Delete(sim);
        cJSON_Delete(samples);
        cJSON_Delete(doc);
        return NULL;
    }
    cJSON_AddTrueToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "version", jc_version());
    for (cJSON *it = sim->child; it; it = sim->child) {
        cJSON_DetachItemViaPointer(sim, it);
        cJSON_AddItemToObject(doc, it->string, it);
        if (strcmp(it->string, "events") == 0) {
            cJSON_AddItemToObject(doc, "samples", samples);
            samples = NULL;
        }
    }
    cJSON_Delete(sim);
    if (samples) cJSON_AddItemToObject(doc, "samples", samples);
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    cJSON_AddStringToObject(doc, "final_mode", jc_mode_name(run->final_mode));
    cJSON_AddNumberToObject(doc, "ode_steps", (double)run->ode_steps);
    if (sum.first_liftoff >= 0) {
        cJSON *fl = cJSON_AddObjectToObject(doc, "first_liftoff");
        cJSON_AddNumberToObject(fl, "event", sum.first_liftoff);
        add_state(fl, &sum.first_liftoff_state);
    } else {
        cJSON_AddNullToObject(doc, "first_liftoff");
    }
    /* Table 1's row when the setup is the paper's cylinder on one of its
     * inclines (cli_paper_row: what `jumpcyl animate` marks), else null. */
    const jc_PaperTableRow *row = cli_paper_row(&m->setup);
    if (row) {
        cJSON *pr = cJSON_AddObjectToObject(doc, "paper_row");
        cJSON_AddNumberToObject(pr, "incline_deg", row->incline_deg);
        cJSON_AddNumberToObject(pr, "printed_theta_rad", row->printed_theta_rad);
        cJSON_AddNumberToObject(pr, "printed_x_m", row->printed_x_m);
        cJSON_AddNumberToObject(pr, "measured_x_m", row->measured_x_m);
        cJSON_AddNumberToObject(pr, "measured_error_m", row->measured_error_m);
    } else {
        cJSON_AddNullToObject(doc, "paper_row");
    }
    return doc;
}

char *web_error(const char *msg)
{
    char line[WEB_ERR_LEN];
    snprintf(line, sizeof line, "%s", msg);
    for (char *c = line; *c; ++c)
        if (*c == '\n' || *c == '\r') *c = ' ';
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddFalseToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "error", line);
    char *text = cli_json_text(doc, 0);
    cJSON_Delete(doc);
    return text;
}

char *web_print(cJSON *doc)
{
    char *text = cli_json_text(doc, 0);
    cJSON_Delete(doc);
    return text ? text : web_error("out of memory for the answer");
}

/* ---- exported ---- */

/* Reads and checks a request: NULL, or the answer that refuses it. */
static char *read_request(const char *request_json, web_Inputs *in)
{
    char err[WEB_ERR_LEN];
    cJSON *req = request_json ? cJSON_Parse(request_json) : NULL;
    if (!cJSON_IsObject(req)) {
        cJSON_Delete(req);
        return web_error("the request is not a JSON object (e.g. {\"incline\": 30})");
    }
    const int rc = web_read_inputs(req, in, err, sizeof err);
    cJSON_Delete(req);
    return rc ? web_error(err) : NULL;
}

/* Runs the request: NULL and the run (free it with jc_run_free), or the
 * answer that refuses the request or reports the failure. */
static char *run_request(const char *request_json, jc_Model *model, jc_Run *run, int *binary)
{
    char err[WEB_ERR_LEN];
    web_Inputs in;
    char *refused = read_request(request_json, &in);
    if (refused) return refused;
    *binary = in.binary;
    if (jc_model_init(model, &in.setup, err, sizeof err) != JC_OK) return web_error(err);
    const int st = jc_simulate(model, &in.sim, run, err, sizeof err);
    if (st != JC_OK) {
        char msg[WEB_ERR_LEN + 40];
        snprintf(msg, sizeof msg, "simulation failed (%s): %s", jc_status_text(st), err);
        jc_run_free(run);
        return web_error(msg);
    }
    return NULL;
}

JC_WEB_EXPORT char *jc_web_simulate(const char *request_json)
{
    jc_Model *model = malloc(sizeof *model);
    if (!model) return NULL;
    jc_Run run = {0};
    int binary = 0;
    char *text = run_request(request_json, model, &run, &binary);
    if (!text) {
        text = web_print(run_json(model, &run, binary));
        jc_run_free(&run);
    }
    free(model);
    return text;
}

/* The request's run as {"ok": true, "csv": "..."}: its samples as
 * `jumpcyl simulate --csv` writes them (the same columns, digits and
 * bytes), for the page's download. */
JC_WEB_EXPORT char *jc_web_csv(const char *request_json)
{
    jc_Model *model = malloc(sizeof *model);
    if (!model) return NULL;
    jc_Run run = {0};
    int binary = 0;
    char *text = run_request(request_json, model, &run, &binary);
    if (!text) {
        char *csv = samples_csv(&run);
        cJSON *doc = csv ? cJSON_CreateObject() : NULL;
        cJSON_AddTrueToObject(doc, "ok");
        cJSON_AddStringToObject(doc, "csv", csv);
        free(csv);
        text = web_print(doc);
        jc_run_free(&run);
    }
    free(model);
    return text;
}

JC_WEB_EXPORT char *jc_web_presets(void)
{
    cJSON *arr = cJSON_CreateArray();
    for (int i = 0; arr && jc_preset_name(i); ++i) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", jc_preset_name(i));
        cJSON_AddStringToObject(o, "description", jc_preset_description(i));
        cJSON_AddItemToArray(arr, o);
    }
    return web_print(arr);
}

/* The parameter table (the library's, jc_param_info), as `jumpcyl params
 * --json` prints it: every setup option the page can set, with its
 * quantity, units, range, typical span and each preset's value. The page
 * builds its controls from it. */
JC_WEB_EXPORT char *jc_web_params(void)
{
    return web_print(cli_json_params());
}

JC_WEB_EXPORT const char *jc_web_version(void)
{
    return jc_version();
}

JC_WEB_EXPORT void jc_web_free(char *text)
{
    free(text);
}

/* The request's setup as an experiment file (`jumpcyl --config`'s format,
 * cli_config_write: what `simulate --dump-config` prints), as
 * {"ok": true, "config": "..."}; simulation options are read and checked
 * but not written (the file holds the setup only). */
JC_WEB_EXPORT char *jc_web_config(const char *request_json)
{
    web_Inputs in; /* the simulation options are read and checked, not written */
    char *refused = read_request(request_json, &in);
    if (refused) return refused;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return web_error("out of memory");
    const int wr = cli_config_write(f, &in.setup);
    if (fclose(f) != 0 || wr != 0 || !text) {
        free(text);
        return web_error("could not write the experiment file");
    }
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddTrueToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "config", text);
    free(text);
    return web_print(doc);
}
