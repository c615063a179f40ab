/* One case: a full run of the library from the setup's start, kept only as
 * its summary (no event or sample is stored, nothing is allocated), and its
 * fields as a CSV row holds them. */
#include "study_internal.h"

#include <math.h>
#include <string.h>

static const jc_CaseColumn columns[JC_CASE_COLUMNS] = {
    {"first_event", "", "the run's first event (slip, liftoff, ...), none if it has none"},
    {"first_slip_theta_rad", "rad", "theta at the first slip (rolling to sliding); empty if none"},
    {"first_slip_x_m", "m", "the centre's travel down the ramp at the first slip"},
    {"first_slip_t_s", "s", "the time of the first slip"},
    {"first_liftoff_theta_rad", "rad", "theta at the first lift-off; empty if none"},
    {"first_liftoff_x_m", "m", "the centre's travel at the first lift-off"},
    {"first_liftoff_t_s", "s", "the time of the first lift-off"},
    {"liftoffs", "", "lift-offs on the ramp (hops)"},
    {"bounces", "", "impacts that ended in flight again"},
    {"largest_hop_m", "m", "the highest flight's gap of the rim above the incline (0 without a hop)"},
    {"termination", "", "how the run ended (ramp_end, ramp_top, rest, ...; invalid_setup, failed)"},
    {"end_x_m", "m", "the centre's travel at the end"},
    {"end_t_s", "s", "the time at the end"},
    {"energy_balance_error_J", "J", "the energy balance's error over the run"},
};

int jc_case_column_count(void) { return JC_CASE_COLUMNS; }

const jc_CaseColumn *jc_case_column(int i) { return i >= 0 && i < JC_CASE_COLUMNS ? &columns[i] : NULL; }

const char *jc_case_kind_name(jc_CaseKind kind)
{
    switch (kind) {
    case JC_CASE_LIFTOFF: return "liftoff";
    case JC_CASE_NO_LIFTOFF: return "no_liftoff";
    case JC_CASE_SLIDES_AT_START: return "slides_at_start";
    case JC_CASE_INVALID: return "invalid_setup";
    case JC_CASE_FAILED: return "failed";
    }
    return "unknown";
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

/* An outcome with no run: the kind alone. */
static void no_run(jc_CaseOutcome *o, jc_CaseKind kind)
{
    memset(o, 0, sizeof *o);
    o->kind = kind;
    o->liftoff_x_m = NAN;
    o->largest_hop_m = 0.0;
    jc_summary_init(&o->summary);
}

void jc_case_run(const jc_Setup *setup, const jc_SimOptions *sim, jc_Workspace *ws, jc_CaseOutcome *out)
{
    jc_Model model;
    char err[256];
    if (!setup || jc_model_init(&model, setup, err, sizeof err) != JC_OK) {
        no_run(out, JC_CASE_INVALID);
        return;
    }
    summary_ctx ctx;
    jc_summary_init(&ctx.sum);
    ctx.count = 0;
    const jc_Recorder rec = {&ctx, on_event, NULL};
    const jc_State start = jc_start_state(&model);
    jc_Run run;
    if (jc_simulate_from(&model, &start, sim, &rec, ws, &run, err, sizeof err) != JC_OK) {
        no_run(out, JC_CASE_FAILED);
        return;
    }
    const jc_RunSummary *s = &ctx.sum;
    out->summary = *s;
    out->kind = s->first_liftoff >= 0 ? JC_CASE_LIFTOFF : JC_CASE_NO_LIFTOFF;
    out->liftoff_x_m = s->first_liftoff >= 0 ? s->first_liftoff_state.x_m : NAN;
    if (s->first_slip == 0 && s->first_slip_state.x_m <= JC_CASE_SLIDES_AT_START_M) out->kind = JC_CASE_SLIDES_AT_START;
    out->largest_hop_m = s->largest_hop >= 0 ? s->largest_hop_m : 0.0;
    out->termination = run.termination;
    out->end = run.final_state;
    out->energy_balance_error_J = run.energy.balance_error_J;
}

/* ---- text in bounds, without printf ---- */

void jc_row_text(jc_RowText *t, const char *s)
{
    if (t->len == 0) return;
    const size_t room = t->len - t->used, n = strlen(s);
    const size_t k = n < room ? n : room - 1;
    memcpy(t->buf + t->used, s, k);
    t->used += k;
    t->buf[t->used] = '\0';
}

void jc_row_number(jc_RowText *t, double v, int precision)
{
    char number[JC_NUMBER_MAX];
    jc_format_g(v, precision, number);
    jc_row_text(t, number);
}

void jc_row_long(jc_RowText *t, long v)
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
    jc_row_text(t, text);
}

/* ",theta,x,t" of an event's state, or three empty fields. */
static void event_state(jc_RowText *t, int index, const jc_State *s)
{
    if (index < 0) {
        jc_row_text(t, ",,,");
        return;
    }
    jc_row_text(t, ",");
    jc_row_number(t, s->theta_rad, 12);
    jc_row_text(t, ",");
    jc_row_number(t, s->x_m, 12);
    jc_row_text(t, ",");
    jc_row_number(t, s->t_s, 12);
}

int jc_case_format(const jc_CaseOutcome *o, char *buf, size_t len)
{
    jc_RowText t = {buf, len, 0};
    if (len > 0) buf[0] = '\0';
    /* The reason is not a field (it would need CSV quoting in every reader):
     * the termination column says what happened. */
    if (o->kind == JC_CASE_INVALID || o->kind == JC_CASE_FAILED) {
        jc_row_text(&t, ",,,,,,,,,,");
        jc_row_text(&t, jc_case_kind_name(o->kind));
        jc_row_text(&t, ",,,");
        return (int)t.used;
    }
    const jc_RunSummary *s = &o->summary;
    jc_row_text(&t, s->first_event >= 0 ? jc_event_name(s->first_event_kind) : "none");
    event_state(&t, s->first_slip, &s->first_slip_state);
    event_state(&t, s->first_liftoff, &s->first_liftoff_state);
    jc_row_text(&t, ",");
    jc_row_long(&t, s->liftoffs);
    jc_row_text(&t, ",");
    jc_row_long(&t, s->bounces);
    jc_row_text(&t, ",");
    jc_row_number(&t, o->largest_hop_m, 12);
    jc_row_text(&t, ",");
    jc_row_text(&t, jc_termination_name(o->termination));
    jc_row_text(&t, ",");
    jc_row_number(&t, o->end.x_m, 12);
    jc_row_text(&t, ",");
    jc_row_number(&t, o->end.t_s, 12);
    jc_row_text(&t, ",");
    jc_row_number(&t, o->energy_balance_error_J, 3);
    return (int)t.used;
}
