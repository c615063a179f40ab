/*
 * The WebAssembly entry point's functions (web/jc_web.c: single runs, the
 * parameter table, downloads; web/jc_web_study.c: sweeps and the spread of
 * the jump site, on the library's studies), and what the two files share:
 * a request's setup read as jc_web_simulate reads it, and the answers'
 * JSON. docs/web.md, "The entry point".
 *
 * Every returned string is malloc'd and owned by the caller: free it with
 * jc_web_free. A bad request gives {"ok": false, "error": "..."} (one
 * line), never an abort. NULL only when memory ran out.
 */
#ifndef JUMPCYL_WEB_H
#define JUMPCYL_WEB_H

#include <cjson/cJSON.h>
#include <jumpcyl/study.h>

#include <stddef.h>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define JC_WEB_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define JC_WEB_EXPORT
#endif

/* ---- exported: what the page calls ---- */

JC_WEB_EXPORT char *jc_web_simulate(const char *request_json);
JC_WEB_EXPORT char *jc_web_csv(const char *request_json);
JC_WEB_EXPORT char *jc_web_config(const char *request_json);
JC_WEB_EXPORT char *jc_web_presets(void);
JC_WEB_EXPORT char *jc_web_params(void);
JC_WEB_EXPORT const char *jc_web_version(void);
JC_WEB_EXPORT void jc_web_free(char *text);
/* {"setup": {request}, "vary": NAME, "lo": V, "hi": V, "n": N}: the setup
 * with NAME on n values from lo to hi (jc_study_run on a grid), a row per
 * value. */
JC_WEB_EXPORT char *jc_web_sweep(const char *request_json);
/* {"setup": {request}, "samples": N, "seed": S}: the first lift-off's
 * spread under the library's default tolerances (jc_study_default_spreads),
 * as `jumpcyl mc --json` summarises it. */
JC_WEB_EXPORT char *jc_web_uncertainty(const char *request_json);

/* ---- shared by the entry point's files ---- */

#define WEB_ERR_LEN 512

/* A request's setup, read as jc_web_simulate reads it (the command line's
 * option names and values, cli/inputs/setup_args.c). */
typedef struct {
    jc_Setup setup;        /* built and checked */
    jc_Setup base;         /* the preset and the parts: what the single values are set over */
    jc_ParamValues values; /* the single values given, read once (cli_setup_values) */
    jc_SimOptions sim;
    int binary;            /* "sample-format": "binary" */
} web_Inputs;

/* Reads the request object's members into in. 0, or -1 with a one-line
 * message. Switches GSL's aborting error handler off first. */
int web_read_inputs(const cJSON *req, web_Inputs *in, char *err, size_t err_len);
/* A member's value as the command line's text: a string as it is, a finite
 * number printed with %.17g into slot (32 chars). NULL with a message
 * naming key otherwise. */
const char *web_value_text(const cJSON *v, const char *key, char *slot, char *err, size_t err_len);
/* {"ok": false, "error": msg}, the message on one line. */
char *web_error(const char *msg);
/* doc printed (cli_json_text: every number exact) and deleted; the
 * out-of-memory error when it cannot be. */
char *web_print(cJSON *doc);

#endif
