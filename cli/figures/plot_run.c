/* The full model's run as data for the forces, path and energy panels: the
 * trajectory samples, the events (with labels grouped so that they do not
 * overprint each other) and the hops (with their heights). */
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* About this many samples over the run: smooth curves, files of ~1 MB. */
#define RUN_TARGET_SAMPLES 5000.0
#define RUN_MIN_DT_S 2e-5
/* An event's label, rotated, takes this stretch of the axis beside its
 * line (fractions of the axis: about one line of the labels' font on a
 * panel 1200 px wide); events closer than EVENT_SAME_FRACTION are at one
 * place and share a label. */
#define EVENT_LABEL_NEAR 0.005
#define EVENT_LABEL_ONE_LINE 0.021
#define EVENT_LABEL_TWO_LINES 0.044
#define EVENT_SAME_FRACTION 0.004
/* A label longer than this (bytes) is split in two lines at a comma: it
 * must fit in the panel's top (LABEL_HEADROOM, plot_panels.c). */
#define EVENT_LINE_CHARS 15
#define HOP_CLUSTER_FRACTION 0.04
/* Hop labels: rows at the panel's top; the stretch of the axis a label
 * takes per character and around it (fractions of the axis; the labels'
 * font on a panel 1200 px wide). */
#define HOP_LABEL_ROWS 4
#define HOP_LABEL_CHAR_FRACTION 0.0125
#define HOP_LABEL_GAP 0.015
/* Longest label (bytes): a rotated label must fit in the panel's height. */
#define LABEL_MAX 34
/* Going back more than this fraction of the distance covered puts the
 * panels against time. */
#define BACKTRACK_FRACTION 0.02
/* The zoom starts this many rim radii before the first lift-off (the slip
 * that leads to it is usually in view) and ends this many after the last
 * landing. */
#define ZOOM_BEFORE_RADII 3.0
#define ZOOM_AFTER_RADII 1.5
/* A dip of the normal force below this fraction of M g cos a in contact is
 * a near-miss of N = 0: the overview's zoom shows it. */
#define NEAR_MISS_FRACTION 0.15
/* The overview does not zoom when the zoom would show this much of the run. */
#define ZOOM_WHOLE_FRACTION 0.9
/* A run that only reached the default time limit (a body rocking for ever)
 * is shown to this much simulated time after its last landing, as animate
 * films it. */
#define SHOW_AFTER_LANDING_S 1.0
/* Such a run that never lifted off is shown until its losses (friction,
 * impacts, air, rolling resistance) reach this fraction of their value at
 * the limit: what follows dissipates the last 1 %, the same rocking slowly
 * dying down. They are found on samples this fine (of the whole run). */
#define SHOW_LOSS_FRACTION 0.99
#define SHOW_LOSS_SAMPLES 6000.0
/* A run that loses nothing and rocks periodically (rocking_period_s) is
 * shown for this many periods after its last event. */
#define SHOW_PERIODS 3.0
/* A cut that would keep more than this fraction of the run is none. */
#define SHOW_WHOLE_FRACTION 0.9

const char *fig_event_label(jc_EventKind k)
{
    switch (k) {
    case JC_EVENT_SLIP: return "slip";
    case JC_EVENT_STICK: return "stick";
    case JC_EVENT_SLIP_REVERSAL: return "slip reversal";
    case JC_EVENT_LIFTOFF: return "lift-off";
    case JC_EVENT_TOUCHDOWN: return "touchdown";
    case JC_EVENT_BOUNCE: return "bounce";
    case JC_EVENT_RAMP_END: return "ramp end";
    case JC_EVENT_RAMP_TOP: return "ramp top";
    case JC_EVENT_PAINLEVE: return "Painlevé";
    case JC_EVENT_COUNT: break;
    }
    return "event";
}

/* The time of the run's last landing (a touchdown not followed by a
 * flight); NaN when it never landed or ends in flight. */
static double last_landing_s(const jc_Run *run)
{
    double landed = NAN;
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        if (e->kind == JC_EVENT_TOUCHDOWN) landed = e->state.t_s;
        else if (fig_event_flies(e)) landed = NAN;
    }
    return landed;
}

static int run_flies(const jc_Run *run)
{
    for (int i = 0; i < run->event_count; ++i)
        if (fig_event_flies(&run->events[i])) return 1;
    return 0;
}

static double losses_J(double friction, double impact, double air, double rolling)
{
    return friction + impact + air + rolling;
}

/* The first sample at which the losses reach a target (a recorder that
 * stops the run there). */
typedef struct {
    double target_J, t_s;
} loss_watch;

static int loss_sample(void *ctx, const jc_Sample *p)
{
    loss_watch *w = ctx;
    if (losses_J(p->friction_loss_J, p->impact_loss_J, p->air_loss_J, p->rolling_resistance_loss_J) < w->target_J)
        return JC_OK;
    w->t_s = p->state.t_s;
    return JC_ESTOPPED;
}

/* When the run's losses first reach SHOW_LOSS_FRACTION of their value at
 * its end (probe: the whole run); NaN when it lost nothing. */
static int settled_s(const fig_Data *d, const jc_SimOptions *o, const jc_Run *probe, double *t_s)
{
    const jc_EnergyReport *e = &probe->energy;
    const double lost = losses_J(e->friction_loss_J, e->impact_loss_J, e->air_loss_J, e->rolling_resistance_loss_J);
    *t_s = NAN;
    if (!(lost > 1e-9 * fabs(e->kinetic_J) + 1e-15)) return EXIT_OK;
    jc_SimOptions opts = *o;
    opts.sample_dt_s = fmax(probe->final_state.t_s / SHOW_LOSS_SAMPLES, RUN_MIN_DT_S);
    loss_watch w = {SHOW_LOSS_FRACTION * lost, NAN};
    const jc_Recorder rec = {&w, NULL, loss_sample};
    jc_Run run;
    const int st = cli_simulate_stream(d->model, &opts, &rec, &run, "plot");
    if (st != JC_OK && !(st == JC_ESTOPPED && isfinite(w.t_s) && !cli_stop_requested()))
        return cli_exit_status(st, CLI_INPUTS_CHECKED);
    *t_s = w.t_s;
    return EXIT_OK;
}

/* A run that only reached the default time limit (rocking for ever) when
 * d->end_after_landing: shown to SHOW_AFTER_LANDING_S after its last
 * landing; when it never flew, until its losses have settled (settled_s),
 * or when it lost nothing and repeats, SHOW_PERIODS periods after its last
 * event. Its events (a run that keeps only them) give the times; d->cut
 * says which, and *t_end becomes the shown end. */
static int cut_rocking(fig_Data *d, jc_SimOptions *opts, const jc_Run *probe, double *t_end)
{
    jc_Run events;
    const int st = cli_simulate(d->model, opts, &events, "plot");
    const double landed = st == JC_OK ? last_landing_s(&events) : NAN;
    const int flies = st == JC_OK && run_flies(&events);
    const double last_event = st == JC_OK && events.event_count ? events.events[events.event_count - 1].state.t_s : 0.0;
    jc_run_free(&events);
    if (st != JC_OK) return cli_exit_status(st, CLI_INPUTS_CHECKED);
    double cut = NAN;
    fig_Cut why = FIG_CUT_NONE;
    if (isfinite(landed)) {
        cut = landed + SHOW_AFTER_LANDING_S;
        why = FIG_CUT_LANDING;
    } else if (!flies) {
        const int rc = settled_s(d, opts, probe, &cut);
        if (rc != EXIT_OK) return rc;
        why = FIG_CUT_SETTLED;
        if (!isfinite(cut) && probe->rocking_period_s > 0) {
            cut = last_event + SHOW_PERIODS * probe->rocking_period_s;
            why = FIG_CUT_PERIODIC;
        }
    }
    /* The landing's cut as before; the others only when they leave out much. */
    const double keep = why == FIG_CUT_LANDING ? 1.0 : SHOW_WHOLE_FRACTION;
    if (isfinite(cut) && cut < keep * *t_end) {
        d->cut = why;
        d->run_end_s = *t_end;
        *t_end = cut;
        opts->t_max_s = *t_end;
    }
    return EXIT_OK;
}

/* Runs the full model. Without a given --sample-dt, a first run without
 * samples finds the duration, so that every run gets about the same number
 * of samples whatever its length. */
static int simulate(fig_Data *d, const jc_SimOptions *o, int dt_given, double max_samples)
{
    jc_SimOptions opts = *o;
    /* A first run that keeps nothing gives the duration and the event
     * count: the figure's size is known, and refused past the budget,
     * before anything is stored. */
    jc_Run probe;
    opts.sample_dt_s = 0.0;
    const int st = cli_simulate_probe(d->model, &opts, &probe, "plot");
    if (st != JC_OK) return cli_exit_status(st, CLI_INPUTS_CHECKED);
    double t_end = probe.final_state.t_s;
    if (d->end_after_landing && probe.termination == JC_END_TIME_LIMIT) {
        const int rc = cut_rocking(d, &opts, &probe, &t_end);
        if (rc != EXIT_OK) return rc;
    }
    opts.sample_dt_s = dt_given ? o->sample_dt_s : fmax(t_end / RUN_TARGET_SAMPLES, RUN_MIN_DT_S);
    const double samples = floor(t_end / opts.sample_dt_s) + 2.0 + probe.event_count;
    if (samples > max_samples) {
        cli_error("plot: the run needs about %.0f samples (%.4g s at --sample-dt %g s, %d events), over the budget "
                  "of %.0f; raise it with --max-samples N, or shorten the run (--t-max, --max-events, --sample-dt)",
                  samples, t_end, opts.sample_dt_s, probe.event_count, max_samples);
        return EXIT_USAGE;
    }
    opts.max_samples = (int)fmin(samples + 16.0, 1e8);
    d->sample_dt_s = opts.sample_dt_s;
    const int run_st = cli_simulate(d->model, &opts, &d->run, "plot");
    if (run_st != JC_OK) {
        jc_run_free(&d->run);
        return cli_exit_status(run_st, CLI_INPUTS_CHECKED);
    }
    d->have_run = 1;
    return EXIT_OK;
}

static void put(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, " %.10g", v);
    else fputs(" NaN", f);
}

/* |F|/N is undefined without a normal force (in flight, and at N = 0). */
static double friction_ratio(const fig_Data *d, const jc_Sample *p)
{
    const double tiny = 1e-9 * d->model->body.mass_kg * d->model->setup.gravity_mps2;
    return p->mode != JC_MODE_FLIGHT && p->normal_N > tiny ? fabs(p->friction_N) / p->normal_N : NAN;
}

/* The ranges of the panels' curves (the vertical axes). */
static void track_values(fig_Data *d, const jc_Sample *p, double n_norm, double ratio, double sum)
{
    const double speed = hypot(p->state.vx_mps, p->state.vy_mps);
    d->n_min = fmin(d->n_min, n_norm);
    d->n_max = fmax(d->n_max, n_norm);
    if (isfinite(ratio)) d->ratio_max = fmax(d->ratio_max, ratio);
    d->gap_max_mm = fmax(d->gap_max_mm, p->gap_m * 1e3);
    d->speed_max_mps = fmax(d->speed_max_mps, speed);
    const double e[5] = {p->kinetic_J, p->potential_J, p->friction_loss_J, p->impact_loss_J, sum};
    for (int k = 0; k < 5; ++k) {
        d->energy_min_J = fmin(d->energy_min_J, e[k]);
        d->energy_max_J = fmax(d->energy_max_J, e[k]);
    }
}

static void reset_values(fig_Data *d)
{
    d->n_min = d->n_max = d->ratio_max = d->gap_max_mm = d->speed_max_mps = 0.0;
    d->energy_min_J = d->energy_max_J = 0.0;
}

static void track_ranges(fig_Data *d, const jc_Sample *p, double n_norm, double ratio, double sum)
{
    const double x = p->state.x_m * 100;
    d->x_min_cm = fmin(d->x_min_cm, x);
    d->x_max_cm = fmax(d->x_max_cm, x);
    d->t_max_s = fmax(d->t_max_s, p->state.t_s);
    track_values(d, p, n_norm, ratio, sum);
}

/* A zoomed panel scales its vertical axis to the curves inside the zoom:
 * a large force after it (the hoop's rocking) would squeeze them. */
static void zoom_values(fig_Data *d)
{
    const jc_Model *m = d->model;
    const double weight_n = m->body.mass_kg * m->setup.gravity_mps2 * m->cos_incline;
    reset_values(d);
    for (int i = 0; i < d->run.sample_count; ++i) {
        const jc_Sample *p = &d->run.samples[i];
        if (p->state.t_s < d->zoom_t_lo_s || p->state.t_s > d->zoom_t_hi_s) continue;
        const double resist = p->air_loss_J + p->rolling_resistance_loss_J;
        const double sum = p->kinetic_J + p->potential_J + p->friction_loss_J + p->impact_loss_J + resist;
        track_values(d, p, p->normal_N / weight_n, friction_ratio(d, p), sum);
    }
}

static int write_samples(fig_Data *d)
{
    FILE *f = d->gp;
    fig_block_begin(f, "run");
    const jc_Model *m = d->model;
    const double weight_n = m->body.mass_kg * m->setup.gravity_mps2 * m->cos_incline;
    fprintf(f, "# jumpcyl plot: samples of the full model (jc_simulate, sample_dt_s = %.17g, and at every event).\n"
                  "# M g cos(a) = %.10g N. mode: 0 rolling, 1 sliding, 2 flight. F/N: NaN without contact.\n"
                  "# columns: t_s x_cm mode N_over_Mgcosa absF_over_N gap_mm speed_mps kinetic_J potential_J\n"
                  "#          friction_loss_J impact_loss_J sum_J normal_N friction_N air_and_rolling_resistance_loss_J\n"
                  "# sum_J = kinetic + potential + all losses: constant up to the integration error.\n",
            d->sample_dt_s, weight_n);
    d->x_min_cm = d->x_max_cm = 0.0;
    d->t_max_s = d->resistance_loss_max_J = 0.0;
    reset_values(d);
    for (int i = 0; i < d->run.sample_count; ++i) {
        const jc_Sample *p = &d->run.samples[i];
        const double n_norm = p->normal_N / weight_n, ratio = friction_ratio(d, p);
        const double resist = p->air_loss_J + p->rolling_resistance_loss_J;
        const double sum = p->kinetic_J + p->potential_J + p->friction_loss_J + p->impact_loss_J + resist;
        fprintf(f, "%.12g", p->state.t_s);
        put(f, p->state.x_m * 100);
        fprintf(f, " %d", (int)p->mode);
        const double v[] = {n_norm, ratio, p->gap_m * 1e3, hypot(p->state.vx_mps, p->state.vy_mps), p->kinetic_J,
                            p->potential_J, p->friction_loss_J, p->impact_loss_J, sum, p->normal_N, p->friction_N,
                            resist};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; ++k) put(f, v[k]);
        fputc('\n', f);
        track_ranges(d, p, n_norm, ratio, sum);
        d->resistance_loss_max_J = fmax(d->resistance_loss_max_J, resist);
    }
    fig_block_end(f);
    return EXIT_OK;
}

static void append(char *out, size_t len, const char *part)
{
    const size_t used = strlen(out);
    if (used + strlen(part) + 2 >= len) {
        if (used + 4 < len && !strstr(out, "…")) strcat(out, "…");
        return;
    }
    if (used) strcat(out, ", ");
    strcat(out, part);
}

/* Per-kind totals in order of first appearance: "slip ×12, stick ×11", for
 * clusters whose sequence is too long to spell out. */
static void kind_totals(const jc_Run *run, int first, int last, char *out, size_t len)
{
    int count[JC_EVENT_COUNT] = {0}, order[JC_EVENT_COUNT], kinds = 0;
    for (int i = first; i <= last; ++i) {
        const int k = (int)run->events[i].kind;
        if (k < 0 || k >= JC_EVENT_COUNT) continue;
        if (count[k]++ == 0) order[kinds++] = k;
    }
    out[0] = '\0';
    for (int i = 0; i < kinds; ++i) {
        char part[64];
        if (count[order[i]] > 1) snprintf(part, sizeof part, "%s ×%d", fig_event_label((jc_EventKind)order[i]), count[order[i]]);
        else snprintf(part, sizeof part, "%s", fig_event_label((jc_EventKind)order[i]));
        append(out, len, part);
    }
}

static int stick_or_slip(jc_EventKind k)
{
    return k == JC_EVENT_SLIP || k == JC_EVENT_STICK || k == JC_EVENT_SLIP_REVERSAL;
}

/* A stretch of alternating slips and sticks from event i (three of each or
 * more), up to event last: its last event, and "51 stick–slip cycles" in
 * part; -1 when there is none. */
static int stick_slip_cycles(const jc_Run *run, int i, int last, char *part, size_t len)
{
    int j = i, sticks = 0, slips = 0;
    while (j <= last && stick_or_slip(run->events[j].kind)) {
        sticks += run->events[j].kind == JC_EVENT_STICK;
        slips += run->events[j].kind == JC_EVENT_SLIP;
        ++j;
    }
    if (sticks < 3 || slips < 3) return -1;
    snprintf(part, len, "%d stick–slip cycles", sticks > slips ? sticks : slips);
    return j - 1;
}

/* "bounce ×4, touchdown": the kinds of events first..last in order, repeats
 * counted, a stretch of alternating slips and sticks in plain words ("51
 * stick–slip cycles"); per-kind totals when that is longer than a label can
 * be. */
void fig_event_cluster_label(const jc_Run *run, int first, int last, char *out, size_t len)
{
    char seq[512];
    seq[0] = '\0';
    for (int i = first; i <= last;) {
        char part[64];
        const int cycles_end = stick_slip_cycles(run, i, last, part, sizeof part);
        if (cycles_end >= 0) {
            append(seq, sizeof seq, part);
            i = cycles_end + 1;
            continue;
        }
        int j = i;
        while (j < last && run->events[j + 1].kind == run->events[i].kind) ++j;
        if (j > i) snprintf(part, sizeof part, "%s ×%d", fig_event_label(run->events[i].kind), j - i + 1);
        else snprintf(part, sizeof part, "%s", fig_event_label(run->events[i].kind));
        append(seq, sizeof seq, part);
        i = j + 1;
    }
    if (strlen(seq) < len) snprintf(out, len, "%s", seq);
    else kind_totals(run, first, last, out, len);
}

/* Where something at (x, t) sits on the panels' horizontal axis. */
static double axis_of(const fig_Data *d, double x_m, double t_s) { return d->time_axis ? t_s : x_m * 100; }

/* An event's position on the panels' axis, as a fraction of the axis. */
static double axis_fraction(const fig_Data *d, const jc_Event *e)
{
    return (axis_of(d, e->state.x_m, e->state.t_s) - d->axis_min) / fmax(d->axis_max - d->axis_min, 1e-12);
}

/* Whether the stretch [lo, hi] of the axis (fractions) can take a label:
 * inside the axis, across no event's line other than those of events
 * first..last, and clear of the label placed before (which ends at prev_hi). */
static int label_fits(const fig_Data *d, double lo, double hi, int first, int last, double prev_hi)
{
    if (lo < 0.0 || hi > 1.0 || lo < prev_hi) return 0;
    for (int i = 0; i < d->run.event_count; ++i) {
        if (i >= first && i <= last) continue;
        const double a = axis_fraction(d, &d->run.events[i]);
        if (a >= lo && a <= hi) return 0; /* outside the axis: not drawn, never inside [lo, hi] */
    }
    return 1;
}

typedef struct {
    int lead, last;          /* the events sharing the label */
    char line[2][LABEL_MAX]; /* its lines (the second empty for one) */
    int side;                /* -1: left of the lead's line, +1: right of the last's */
    double lo, hi;           /* the stretch of the axis it takes (fractions) */
} fig_EventLabel;

/* The label's text, in two lines split at a comma when it is long. */
static void label_lines(const jc_Run *run, fig_EventLabel *l)
{
    char text[LABEL_MAX];
    fig_event_cluster_label(run, l->lead, l->last, text, sizeof text);
    snprintf(l->line[0], sizeof l->line[0], "%s", text);
    l->line[1][0] = '\0';
    const size_t n = strlen(text);
    if (n <= EVENT_LINE_CHARS) return;
    size_t best = 0;
    for (size_t i = 1; i + 1 < n; ++i)
        if (text[i] == ',' && text[i + 1] == ' ' && (best == 0 || fabs((double)i - (double)n / 2.0) < fabs((double)best - (double)n / 2.0)))
            best = i;
    if (best == 0) return;
    snprintf(l->line[0], sizeof l->line[0], "%.*s", (int)best + 1, text);
    snprintf(l->line[1], sizeof l->line[1], "%s", text + best + 2);
}

/* Places the label left of its first line if it fits, else right of its
 * last; -1 if neither fits. */
static int place_label(const fig_Data *d, fig_EventLabel *l, double prev_hi)
{
    label_lines(&d->run, l);
    const double width = l->line[1][0] ? EVENT_LABEL_TWO_LINES : EVENT_LABEL_ONE_LINE;
    const double a = axis_fraction(d, &d->run.events[l->lead]), b = axis_fraction(d, &d->run.events[l->last]);
    for (int side = -1; side <= 1; side += 2) {
        const double lo = side < 0 ? a - EVENT_LABEL_NEAR - width : b + EVENT_LABEL_NEAR;
        const double hi = side < 0 ? a - EVENT_LABEL_NEAR : b + EVENT_LABEL_NEAR + width;
        if (label_fits(d, lo, hi, l->lead, l->last, prev_hi)) {
            l->side = side;
            l->lo = lo;
            l->hi = hi;
            return 0;
        }
    }
    return -1;
}

/* Every event line gets its own label beside it, left or right, where the
 * label crosses no other line and no other label; events at one place
 * (closer than EVENT_SAME_FRACTION) share one, and events whose label fits
 * nowhere join the label before them ("slip, stick"), until it fits.
 * Returns the number of labels in out (at most event_count). */
static int place_event_labels(const fig_Data *d, fig_EventLabel *out)
{
    const jc_Run *run = &d->run;
    int n = 0;
    for (int lead = 0; lead < run->event_count;) {
        const double at = axis_fraction(d, &run->events[lead]);
        if (at < 0.0 || at > 1.0) { /* outside the (zoomed) axis: not drawn, no label */
            ++lead;
            continue;
        }
        int last = lead;
        while (last + 1 < run->event_count && fabs(axis_fraction(d, &run->events[last + 1]) - at) <= EVENT_SAME_FRACTION &&
               axis_fraction(d, &run->events[last + 1]) <= 1.0)
            ++last;
        out[n].lead = lead;
        out[n].last = last;
        ++n;
        while (place_label(d, &out[n - 1], n > 1 ? out[n - 2].hi : -INFINITY) != 0) {
            if (n == 1) { /* the first fits nowhere: beside itself, inside the axis */
                out[0].side = axis_fraction(d, &run->events[0]) > 2 * EVENT_LABEL_TWO_LINES ? -1 : 1;
                out[0].hi = axis_fraction(d, &run->events[out[0].last]) + EVENT_LABEL_TWO_LINES;
                break;
            }
            out[n - 2].last = out[n - 1].last;
            --n;
        }
        lead = last + 1;
    }
    return n;
}

/* Characters of a UTF-8 string. */
static int utf8_chars(const char *s)
{
    int n = 0;
    for (; *s; ++s) n += ((unsigned char)*s & 0xC0) != 0x80;
    return n;
}

static int imax(int a, int b) { return a > b ? a : b; }

static int write_events(fig_Data *d)
{
    FILE *f = d->gp;
    fig_block_begin(f, "events");
    fputs("# jumpcyl plot: the events of the run (jc_simulate), in time order. Labels sit beside the lines:\n"
          "# side -1, left of the line, on the first row of the events sharing it; side 1, right of the\n"
          "# line, on the last row; line1 and line2 are the label in one or two lines (left: line2 is\n"
          "# nearest the line, right: line1 is).\n"
          "# columns: x_cm t_s kind label side line1 line2\n",
          f);
    const jc_Run *run = &d->run;
    fig_EventLabel *labels = run->event_count ? malloc(sizeof *labels * (size_t)run->event_count) : NULL;
    if (run->event_count && !labels) {
        cli_error("plot: out of memory");
        return EXIT_FAIL;
    }
    const int n = labels ? place_event_labels(d, labels) : 0;
    int k = 0;
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        while (k < n && labels[k].last < i) ++k;
        const fig_EventLabel *l = k < n && labels[k].lead <= i ? &labels[k] : NULL;
        if (!l || i != (l->side < 0 ? l->lead : l->last)) {
            fprintf(f, "%.10g %.12g %s \"\" 0 \"\" \"\"\n", e->state.x_m * 100, e->state.t_s, jc_event_name(e->kind));
            continue;
        }
        label_lines(run, &labels[k]);
        char text[LABEL_MAX];
        fig_event_cluster_label(run, l->lead, l->last, text, sizeof text);
        /* Left: the only line nearest the line (line2); right: line1. */
        const int two = l->line[1][0] != '\0';
        const char *line1 = two || l->side > 0 ? l->line[0] : "", *line2 = two ? l->line[1] : l->side < 0 ? l->line[0] : "";
        d->event_label_chars = imax(d->event_label_chars, imax(utf8_chars(line1), utf8_chars(line2)));
        fprintf(f, "%.10g %.12g %s \"%s\" %d \"%s\" \"%s\"\n", e->state.x_m * 100, e->state.t_s, jc_event_name(e->kind),
                text, l->side, line1, line2);
    }
    free(labels);
    fig_block_end(f);
    return EXIT_OK;
}

typedef struct {
    double x_cm, t_s;            /* the centre at the flight's highest point */
    double start_t_s, height_mm, flight_s;
} fig_Hop;

/* The highest sample of a flight, or its middle when the flight is too short
 * to hold samples (a hop of a few micrometres still gets a mark). */
static fig_Hop hop_of(const fig_Data *d, const jc_Event *e, int *cursor)
{
    const jc_Run *run = &d->run;
    const double t1 = e->state.t_s + e->flight_time_s;
    fig_Hop h = {NAN, NAN, e->state.t_s, e->hop_height_m * 1e3, e->flight_time_s};
    double best_gap = -1.0;
    while (*cursor < run->sample_count && run->samples[*cursor].state.t_s < e->state.t_s) ++*cursor;
    for (int i = *cursor; i < run->sample_count && run->samples[i].state.t_s <= t1; ++i)
        if (run->samples[i].gap_m > best_gap) {
            best_gap = run->samples[i].gap_m;
            h.x_cm = run->samples[i].state.x_m * 100;
            h.t_s = run->samples[i].state.t_s;
        }
    if (best_gap < 0.5 * e->hop_height_m) {
        const double end = isnan(e->landing_x_m) ? run->final_state.x_m : e->landing_x_m;
        h.x_cm = 50 * (e->state.x_m + end);
        h.t_s = e->state.t_s + 0.5 * e->flight_time_s;
    }
    return h;
}

static int collect_hops(const fig_Data *d, fig_Hop *hops)
{
    int n = 0, cursor = 0;
    for (int i = 0; i < d->run.event_count; ++i) {
        const jc_Event *e = &d->run.events[i];
        if (fig_event_flies(e)) hops[n++] = hop_of(d, e, &cursor);
    }
    return n;
}

/* "19.5 mm"; "0.822, 0.0657 mm"; "5 hops, 0.0013–0.822 mm". */
static void hop_label(const fig_Hop *h, int first, int last, char *out, size_t len)
{
    double lo = h[first].height_mm, hi = lo;
    for (int i = first; i <= last; ++i) {
        lo = fmin(lo, h[i].height_mm);
        hi = fmax(hi, h[i].height_mm);
    }
    const int n = last - first + 1;
    if (n > 3) {
        snprintf(out, len, "%d hops, %.2g–%.3g mm", n, lo, hi);
        return;
    }
    out[0] = '\0';
    for (int i = first; i <= last; ++i) {
        char part[32];
        snprintf(part, sizeof part, "%.3g%s", h[i].height_mm, i == last ? " mm" : "");
        append(out, len, part);
    }
}

/* Where a hop's label goes on the panels' axis (fraction of it): centred
 * over its apex, but inside the axis. */
static double label_at(const fig_Data *d, const fig_Hop *h, double width)
{
    const double a = (axis_of(d, h->x_cm / 100, h->t_s) - d->axis_min) / fmax(d->axis_max - d->axis_min, 1e-12);
    return fmin(fmax(a, 0.5 * width), 1.0 - 0.5 * width);
}

/* Hops close together on the axis share a label ("0.766, 0.0702 mm"); the
 * labels sit in rows in the top of the panel, above every curve
 * (LABEL_HEADROOM), each in the first row where it overlaps no other. */
static void write_hop_rows(FILE *f, const fig_Data *d, const fig_Hop *h, int n)
{
    double row_end[HOP_LABEL_ROWS];
    for (int r = 0; r < HOP_LABEL_ROWS; ++r) row_end[r] = -INFINITY;
    for (int lead = 0; lead < n;) {
        const double apex = (axis_of(d, h[lead].x_cm / 100, h[lead].t_s) - d->axis_min) / fmax(d->axis_max - d->axis_min, 1e-12);
        int last = lead, top = lead;
        while (last + 1 < n &&
               fabs((axis_of(d, h[last + 1].x_cm / 100, h[last + 1].t_s) - d->axis_min) / fmax(d->axis_max - d->axis_min, 1e-12) -
                    apex) <= HOP_CLUSTER_FRACTION)
            ++last;
        for (int i = lead; i <= last; ++i)
            if (h[i].height_mm > h[top].height_mm) top = i;
        char label[64];
        hop_label(h, lead, last, label, sizeof label);
        const double width = utf8_chars(label) * HOP_LABEL_CHAR_FRACTION + HOP_LABEL_GAP;
        const double at = label_at(d, &h[top], width);
        int row = -1; /* no label: outside the axis, or no room */
        if (apex >= 0.0 && apex <= 1.0)
            for (int r = 0; r < HOP_LABEL_ROWS && row < 0; ++r)
                if (at - 0.5 * width >= row_end[r]) row = r;
        if (row >= 0) row_end[row] = at + 0.5 * width;
        const double at_axis = d->axis_min + at * (d->axis_max - d->axis_min);
        for (int i = lead; i <= last; ++i)
            fprintf(f, "%.10g %.12g %.12g %.10g %.10g \"%s\" %.10g %d\n", h[i].x_cm, h[i].t_s, h[i].start_t_s,
                    h[i].height_mm, h[i].flight_s, i == top && row >= 0 ? label : "", at_axis, i == top ? row : -1);
        lead = last + 1;
    }
}

static int write_hops(fig_Data *d)
{
    FILE *f = d->gp;
    fig_block_begin(f, "hops");
    fputs("# jumpcyl plot: every flight (a lift-off, or a bounce into flight) of the run. height: the largest\n"
          "# gap between rim and incline (jc_Event hop_height_m); x, t: the centre at the flight's highest\n"
          "# sample (its middle when too short to sample). Hops close together share the label, placed\n"
          "# at label_at on the panels' axis (cm, or s when the panels are against time), in label_row\n"
          "# of the rows at the panel's top (0 the highest; -1: no label on this row).\n"
          "# columns: x_apex_cm t_apex_s t_start_s height_mm flight_time_s label label_at label_row\n",
          f);
    fig_Hop *hops = d->run.event_count ? malloc(sizeof *hops * (size_t)d->run.event_count) : NULL;
    if (d->run.event_count && !hops) {
        cli_error("plot: out of memory");
        return EXIT_FAIL;
    }
    d->hop_count = hops ? collect_hops(d, hops) : 0;
    for (int i = 0; i < d->hop_count; ++i) d->gap_max_mm = fmax(d->gap_max_mm, hops[i].height_mm);
    write_hop_rows(f, d, hops, d->hop_count);
    free(hops);
    fig_block_end(f);
    return EXIT_OK;
}

int fig_event_flies(const jc_Event *e)
{
    return e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT);
}

/* The time the centre was last at or before x_cm going back from sample i
 * (the zoom's start in time); 0 if never. */
static double time_back_to(const jc_Run *run, int i, double x_cm)
{
    for (; i >= 0; --i)
        if (run->samples[i].state.x_m * 100 <= x_cm) return run->samples[i].state.t_s;
    return 0.0;
}

/* The time the centre first reaches x_cm after t_s; NaN if never. */
static double time_forward_to(const jc_Run *run, double t_s, double x_cm)
{
    for (int i = 0; i < run->sample_count; ++i)
        if (run->samples[i].state.t_s >= t_s && run->samples[i].state.x_m * 100 >= x_cm) return run->samples[i].state.t_s;
    return NAN;
}

/* Where the first warning of a lift-off comes before time t_s (cm): the
 * first slip, or the first near-miss of N = 0 (N below NEAR_MISS_FRACTION
 * of M g cos a in contact); +inf if none. */
static double first_warning_cm(const fig_Data *d, double t_s)
{
    const jc_Run *run = &d->run;
    const jc_Model *m = d->model;
    const double weight_n = m->body.mass_kg * m->setup.gravity_mps2 * m->cos_incline;
    double at = INFINITY;
    for (int i = 0; i < run->event_count && run->events[i].state.t_s < t_s; ++i)
        if (run->events[i].kind == JC_EVENT_SLIP) {
            at = run->events[i].state.x_m * 100;
            break;
        }
    for (int i = 0; i < run->sample_count && run->samples[i].state.t_s < t_s; ++i) {
        const jc_Sample *p = &run->samples[i];
        if (p->mode != JC_MODE_FLIGHT && p->normal_N < NEAR_MISS_FRACTION * weight_n) {
            at = fmin(at, p->state.x_m * 100);
            break;
        }
    }
    return at;
}

/* The zoom: from ZOOM_BEFORE_RADII rim radii (or 15 % of the hops' span)
 * before what matters first — in the overview (d->zoom_wanted) the first
 * slip or near-miss of N = 0 when they come earlier, else the first
 * lift-off to ZOOM_AFTER_RADII radii (or 5 %) after the
 * last flight's landing, within the run. In time, the same stretch; when
 * the body never gets that far again (it rocks), a quarter of the stretch
 * after the last landing. */
static void find_zoom(fig_Data *d)
{
    const jc_Run *run = &d->run;
    int first = -1, last = -1;
    for (int i = 0; i < run->event_count; ++i)
        if (fig_event_flies(&run->events[i])) {
            if (first < 0) first = i;
            last = i;
        }
    d->zoomed = first >= 0 && run->sample_count > 1;
    if (!d->zoomed) return;
    const jc_Event *a = &run->events[first], *b = &run->events[last];
    const double r_cm = d->model->body.radius_m * 100;
    const double start_cm = a->state.x_m * 100;
    const double end_cm = (isnan(b->landing_x_m) ? run->final_state.x_m : b->landing_x_m) * 100;
    const double span = fabs(end_cm - start_cm), t_end = b->state.t_s + b->flight_time_s;
    const double warning_cm = d->zoom_wanted && !d->time_axis ? first_warning_cm(d, a->state.t_s) : INFINITY;
    d->zoom_from_warning = warning_cm < start_cm;
    const double from_cm = fmin(start_cm, warning_cm);
    d->zoom_x_lo_cm = fmax(fmin(from_cm, end_cm) - fmax(ZOOM_BEFORE_RADII * r_cm, 0.15 * span), d->x_min_cm);
    d->zoom_x_hi_cm = fmin(fmax(start_cm, end_cm) + fmax(ZOOM_AFTER_RADII * r_cm, 0.05 * span), d->x_max_cm);
    int i = 0;
    while (i + 1 < run->sample_count && run->samples[i + 1].state.t_s <= a->state.t_s) ++i;
    d->zoom_t_lo_s = time_back_to(run, i, d->zoom_x_lo_cm);
    const double reached = time_forward_to(run, t_end, d->zoom_x_hi_cm);
    d->zoom_t_hi_s = isnan(reached) || d->time_axis ? fmin(d->t_max_s, t_end + 0.25 * (t_end - d->zoom_t_lo_s)) : reached;
    if (!(d->zoom_t_hi_s > d->zoom_t_lo_s)) d->zoom_t_hi_s = d->t_max_s;
    /* A zoom over most of the run is none (45°: the first slip is near the start). */
    if (d->zoom_wanted && !d->time_axis && d->zoom_x_hi_cm - d->zoom_x_lo_cm >= ZOOM_WHOLE_FRACTION * (d->x_max_cm - d->x_min_cm))
        d->zoomed = 0;
}

void fig_zoom_caption(const fig_Data *d, char *out, size_t len)
{
    snprintf(out, len, "zoomed to x = %.3g–%.3g cm (t = %.3g–%.3g s), %s", d->zoom_x_lo_cm, d->zoom_x_hi_cm, d->zoom_t_lo_s,
             d->zoom_t_hi_s,
             d->zoom_from_warning ? "from the first slip or near-miss of N = 0 to the hops"
                                  : "around the first lift-off and the hops");
}

void fig_cut_caption(const fig_Data *d, char *out, size_t len)
{
    const double shown = d->t_max_s, end = d->run_end_s;
    switch (d->cut) {
    case FIG_CUT_LANDING:
        snprintf(out, len, "shown to t = %.3g s, %g s after the last landing; it rocks on to %.3g s (all: --t-max %.3g)", shown,
                 SHOW_AFTER_LANDING_S, end, end);
        return;
    case FIG_CUT_SETTLED:
        snprintf(out, len, "shown to t = %.3g s, where the losses reach %g %% of their total; it rocks on to %.3g s (all: --t-max %.3g)",
                 shown, 100 * SHOW_LOSS_FRACTION, end, end);
        return;
    case FIG_CUT_PERIODIC:
        snprintf(out, len, "shown to t = %.3g s, %g periods of its rocking%s; it rocks on to %.3g s (all: --t-max %.3g)", shown,
                 SHOW_PERIODS, d->run.event_count ? " after the last event" : "", end, end);
        return;
    case FIG_CUT_NONE: break;
    }
    if (len) out[0] = '\0';
}

/* Distance down the incline is the natural axis, unless the body goes back
 * and forth (it rocks, or rolls back): then curves would overprint, and the
 * panels are drawn against time. */
static void choose_axis(fig_Data *d)
{
    double furthest = -INFINITY, back = 0.0;
    for (int i = 0; i < d->run.sample_count; ++i) {
        const double x = d->run.samples[i].state.x_m * 100;
        furthest = fmax(furthest, x);
        back = fmax(back, furthest - x);
    }
    d->time_axis = back > BACKTRACK_FRACTION * fmax(d->x_max_cm - d->x_min_cm, 1e-9);
    d->axis_min = d->time_axis ? 0.0 : d->x_min_cm;
    d->axis_max = d->time_axis ? d->t_max_s : d->x_max_cm;
    if (!(d->axis_max > d->axis_min)) d->axis_max = d->axis_min + 1;
    find_zoom(d);
    if (d->zoom_wanted && d->zoomed) {
        d->axis_min = d->time_axis ? d->zoom_t_lo_s : d->zoom_x_lo_cm;
        d->axis_max = d->time_axis ? d->zoom_t_hi_s : d->zoom_x_hi_cm;
        zoom_values(d);
    }
}

int fig_run_prepare(fig_Data *d, const jc_SimOptions *o, int dt_given, double max_samples)
{
    int rc = simulate(d, o, dt_given, max_samples);
    if (rc == EXIT_OK) rc = write_samples(d);
    if (rc == EXIT_OK) choose_axis(d);
    if (rc == EXIT_OK) rc = write_events(d);
    if (rc == EXIT_OK) rc = write_hops(d);
    return rc;
}
