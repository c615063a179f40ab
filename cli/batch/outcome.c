/* One case of a batch job: a full run of the library from the setup's start,
 * kept only as its summary (no event or sample is stored, nothing is
 * allocated), written as one CSV row. */
#include "batch.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* A slip within this distance of the start means the body never rolled. */
#define SLIDES_AT_START_M 1e-9

void cli_outcome_header(FILE *out)
{
    fputs("first_event,first_slip_theta_rad,first_slip_x_m,first_slip_t_s,"
          "first_liftoff_theta_rad,first_liftoff_x_m,first_liftoff_t_s,liftoffs,bounces,largest_hop_m,"
          "termination,end_x_m,end_t_s,energy_balance_error_J",
          out);
}

typedef struct {
    jc_RunSummary sum;
    int count;
} summary_ctx;

static int on_event(void *ctx, const jc_Event *e)
{
    summary_ctx *c = ctx;
    jc_summary_add(&c->sum, e, c->count++);
    return JC_OK;
}

/* Appends printf text to the row, keeping it terminated and in bounds. */
static void row_add(cli_CaseResult *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void row_add(cli_CaseResult *r, const char *fmt, ...)
{
    const size_t room = sizeof r->row - (size_t)r->row_len;
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(r->row + r->row_len, room, fmt, ap);
    va_end(ap);
    if (n > 0) r->row_len += (size_t)n < room ? n : (int)room - 1;
}

/* ",v" with v as %.*g writes it (cli_format_g: no printf per number). */
static void add_number(cli_CaseResult *r, double v, int precision)
{
    if (sizeof r->row - (size_t)r->row_len < CLI_NUMBER_MAX + 2) {
        row_add(r, ",%.*g", precision, v);
        return;
    }
    r->row[r->row_len++] = ',';
    r->row_len += cli_format_g(v, precision, r->row + r->row_len);
}

/* Text as it is (a name, a separator), kept in bounds: no printf. */
static void add_text(cli_CaseResult *r, const char *text)
{
    const size_t room = sizeof r->row - (size_t)r->row_len, n = strlen(text);
    const size_t k = n < room ? n : room - 1;
    memcpy(r->row + r->row_len, text, k);
    r->row_len += (int)k;
    r->row[r->row_len] = '\0';
}

/* A whole number in decimal, as %ld writes it. */
static void add_long(cli_CaseResult *r, long v)
{
    char digits[24];
    int n = 0;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    do {
        digits[sizeof digits - 1 - (size_t)n++] = (char)('0' + (int)(u % 10));
        u /= 10;
    } while (u);
    if (v < 0) digits[sizeof digits - 1 - (size_t)n++] = '-';
    char text[24];
    memcpy(text, digits + sizeof digits - (size_t)n, (size_t)n);
    text[n] = '\0';
    add_text(r, text);
}

/* ",theta,x,t" of an event's state, or three empty fields. */
static void add_event_state(cli_CaseResult *r, int index, const jc_State *s)
{
    if (index < 0) {
        add_text(r, ",,,");
        return;
    }
    add_number(r, s->theta_rad, 12);
    add_number(r, s->x_m, 12);
    add_number(r, s->t_s, 12);
}

/* The reason is not a field (it would need CSV quoting in every reader):
 * the termination column says what happened, stderr counts such cases. */
static void row_invalid(cli_CaseResult *r, const char *termination)
{
    row_add(r, ",,,,,,,,,,,%s,,,\n", termination);
}

void cli_case_run(long index, const char *inputs, const jc_Setup *setup, const jc_SimOptions *sim,
                  jc_Workspace *ws, cli_CaseResult *r)
{
    r->row_len = 0;
    r->liftoff_x_m = NAN;
    r->largest_hop_m = 0.0;
    add_long(r, index);
    if (*inputs) add_text(r, ",");
    add_text(r, inputs);
    jc_Model model;
    char err[256];
    if (!setup || jc_model_init(&model, setup, err, sizeof err) != JC_OK) {
        r->kind = CASE_INVALID;
        row_invalid(r, "invalid_setup");
        return;
    }
    summary_ctx ctx;
    jc_summary_init(&ctx.sum);
    ctx.count = 0;
    const jc_Recorder rec = {&ctx, on_event, NULL};
    const jc_State start = jc_start_state(&model);
    jc_Run run;
    if (jc_simulate_from(&model, &start, sim, &rec, ws, &run, err, sizeof err) != JC_OK) {
        r->kind = CASE_FAILED;
        row_invalid(r, "failed");
        return;
    }
    const jc_RunSummary *s = &ctx.sum;
    if (s->first_liftoff >= 0) {
        r->kind = CASE_LIFTOFF;
        r->liftoff_x_m = s->first_liftoff_state.x_m;
    } else {
        r->kind = CASE_NO_LIFTOFF;
    }
    if (s->first_slip == 0 && s->first_slip_state.x_m <= SLIDES_AT_START_M) r->kind = CASE_SLIDES_AT_START;
    r->largest_hop_m = s->largest_hop >= 0 ? s->largest_hop_m : 0.0;
    add_text(r, ",");
    add_text(r, s->first_event >= 0 ? jc_event_name(s->first_event_kind) : "none");
    add_event_state(r, s->first_slip, &s->first_slip_state);
    add_event_state(r, s->first_liftoff, &s->first_liftoff_state);
    add_text(r, ",");
    add_long(r, s->liftoffs);
    add_text(r, ",");
    add_long(r, s->bounces);
    add_number(r, r->largest_hop_m, 12);
    add_text(r, ",");
    add_text(r, jc_termination_name(run.termination));
    add_number(r, run.final_state.x_m, 12);
    add_number(r, run.final_state.t_s, 12);
    add_number(r, run.energy.balance_error_J, 3);
    add_text(r, "\n");
}

/* The n-th comma-separated field of a line (0-based), as a pointer and length. */
static const char *field(const char *line, size_t len, int n, size_t *flen)
{
    const char *p = line, *end = line + len;
    for (int i = 0; i < n; ++i) {
        p = memchr(p, ',', (size_t)(end - p));
        if (!p) return NULL;
        ++p;
    }
    const char *c = memchr(p, ',', (size_t)(end - p));
    *flen = c ? (size_t)(c - p) : (size_t)(end - p);
    return p;
}

static double number_field(const char *line, size_t len, int n)
{
    size_t flen;
    const char *f = field(line, len, n, &flen);
    char buf[64];
    if (!f || flen == 0 || flen >= sizeof buf) return NAN;
    memcpy(buf, f, flen);
    buf[flen] = '\0';
    return strtod(buf, NULL);
}

int cli_case_from_row(const char *line, size_t len, int input_columns, cli_CaseResult *r)
{
    int commas = 0;
    for (size_t i = 0; i < len; ++i) commas += line[i] == ',';
    if (commas != input_columns + CLI_OUTCOME_COLUMNS || len == 0 || len >= sizeof r->row) return -1;
    memcpy(r->row, line, len);
    r->row[len] = '\0';
    r->row_len = (int)len;
    const int o = 1 + input_columns; /* the first outcome column */
    size_t flen;
    const char *term = field(line, len, o + 10, &flen);
    const char *first = field(line, len, o, &flen);
    r->liftoff_x_m = number_field(line, len, o + 5);
    r->largest_hop_m = number_field(line, len, o + 9);
    if (isnan(r->largest_hop_m)) r->largest_hop_m = 0.0;
    if (term && strncmp(term, "invalid_setup", 13) == 0) r->kind = CASE_INVALID;
    else if (term && strncmp(term, "failed,", 7) == 0) r->kind = CASE_FAILED;
    else if (first && strncmp(first, "slip,", 5) == 0 && number_field(line, len, o + 2) <= SLIDES_AT_START_M)
        r->kind = CASE_SLIDES_AT_START;
    else r->kind = isnan(r->liftoff_x_m) ? CASE_NO_LIFTOFF : CASE_LIFTOFF;
    return 0;
}
