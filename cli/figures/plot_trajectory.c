/* The trajectory figure: the body's path in the laboratory frame, drawn to
 * scale (equal axes in every panel), with the incline, the paths of the
 * centre, of every off-centre part and of the centre of mass, and the body's
 * outline at the events.
 *
 * Geometry (as cli/films/draw.h, written again here: plot does not link the
 * films). Incline coordinates: x downhill along the incline from the start
 * contact point, y along the outward normal. Picture coordinates (X right,
 * Y up) put the incline descending to the right at angle a:
 *     X = x cos a + y sin a,   Y = -x sin a + y cos a,
 * so the incline is the line through the origin along (cos a, -sin a). A
 * part at body angle phi and offset a_p sits at C + a_p (sin psi, cos psi),
 * psi = theta - cm_angle + phi (docs/physics.md 1.1). Everything is written
 * in cm.
 *
 * Layout: the page is laid out here, in pixels, rather than by gnuplot:
 * each panel's plot area is placed with margins "at screen" and sized to
 * its data at one scale on both axes, so that ranges are the data's own
 * (not widened to the panel's shape), and the outlines' labels are placed
 * where they clear every curve, outline and other label. */
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Outlines closer than this many radii would overlap: the events of such a
 * group share one outline; the separation doubles until at most
 * MAX_OUTLINES remain. */
#define OUTLINE_SEPARATION_RADII 2.2
#define MAX_OUTLINES 24
#define LABEL_MAX 64
/* The page: a 2400 x 1500 px canvas (plot.c, kind "trajectory"), and the
 * room its title takes at the top. */
#define PAGE_W_PX 2400.0
#define PAGE_H_PX 1500.0
#define PAGE_TITLE_PX 75.0
/* A panel's room around its plot area (px): tic labels and the y label on
 * the left, the x tic labels and label below, a line of title. */
#define MARGIN_L_PX 140.0
#define MARGIN_R_PX 50.0
#define MARGIN_B_PX 120.0
#define TITLE_LINE_PX 37.0
#define TITLE_GAP_PX 35.0
#define KEY_ROW_PX 32.0
#define KEY_ENTRY_PX 330.0
/* Text sizes (px) on the PNG page, the largest of the three terminals:
 * F_SMALL's mean character width and line height, F_TITLE's width. */
#define SMALL_CHAR_PX 11.0
#define SMALL_LINE_PX 24.0
#define TITLE_CHAR_PX 14.5
/* Room kept between a label and anything else (px). */
#define LABEL_PAD_PX 5.0
/* A plot area is never thinner than this (px): a flatter picture gets its
 * range widened instead. */
#define MIN_PLOT_PX 160.0
/* The close-up spans this many gap heights above and below the gap; it is
 * drawn only when the gap is thinner than CLOSEUP_GAP_PX in the main panel
 * and the close-up spans less than half of the main panel's view. */
#define CLOSEUP_GAPS 3.0
#define CLOSEUP_MIN_HALF_M 1e-5
#define CLOSEUP_GAP_PX 40.0
#define RIM_ARC_POINTS 400
/* Samples the library is asked for across each flight in the main panel
 * (the run's own grid may have a handful there), and flights so resampled. */
#define FLIGHT_SAMPLES 240
#define MAX_FLIGHTS 200
#define LAYOUT_ROUNDS 6
#define PI 3.14159265358979323846

typedef struct {
    double X, Y; /* picture coordinates, cm (or page px) */
} fig_Pt;

typedef struct {
    double lo_X, hi_X, lo_Y, hi_Y; /* cm (or page px) */
} fig_Box;

static const fig_Box empty_box = {INFINITY, -INFINITY, INFINITY, -INFINITY};

static fig_Pt picture(double incline_rad, double x_m, double y_m)
{
    const fig_Pt p = {100 * (x_m * cos(incline_rad) + y_m * sin(incline_rad)),
                      100 * (-x_m * sin(incline_rad) + y_m * cos(incline_rad))};
    return p;
}

/* A body point (offset from C, body angle) for the state s, in the picture. */
static fig_Pt body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad)
{
    const double psi = s->theta_rad - m->body.cm_angle_rad + body_angle_rad;
    return picture(m->setup.incline_rad, s->x_m + offset_m * sin(psi), s->y_m + offset_m * cos(psi));
}

/* Parts whose axis is off the centre: each traces its own path. */
static int off_centre(const jc_Part *p) { return p->offset_m > 0; }

/* Whether the centre of mass sits on an off-centre part's axis (a rod
 * alone): then its path is that part's, and is not drawn twice. */
static int cm_on_a_part(const jc_Model *m)
{
    const jc_State s = jc_start_state(m);
    const fig_Pt g = body_point(m, &s, m->body.cm_offset_m, m->body.cm_angle_rad);
    for (int i = 0; i < m->setup.body.part_count; ++i) {
        const jc_Part *p = &m->setup.body.parts[i];
        const fig_Pt q = body_point(m, &s, p->offset_m, p->angle_rad);
        if (off_centre(p) && hypot(q.X - g.X, q.Y - g.Y) < 1e-7) return 1;
    }
    return m->body.cm_offset_m == 0;
}

static void box_add(fig_Box *b, fig_Pt p, double pad)
{
    b->lo_X = fmin(b->lo_X, p.X - pad);
    b->hi_X = fmax(b->hi_X, p.X + pad);
    b->lo_Y = fmin(b->lo_Y, p.Y - pad);
    b->hi_Y = fmax(b->hi_Y, p.Y + pad);
}

static void box_join(fig_Box *b, fig_Box o)
{
    b->lo_X = fmin(b->lo_X, o.lo_X);
    b->hi_X = fmax(b->hi_X, o.hi_X);
    b->lo_Y = fmin(b->lo_Y, o.lo_Y);
    b->hi_Y = fmax(b->hi_Y, o.hi_Y);
}

static double box_w(fig_Box b) { return b.hi_X - b.lo_X; }
static double box_h(fig_Box b) { return b.hi_Y - b.lo_Y; }

static int box_overlaps(fig_Box a, fig_Box b)
{
    return a.lo_X < b.hi_X && b.lo_X < a.hi_X && a.lo_Y < b.hi_Y && b.lo_Y < a.hi_Y;
}

static int box_inside(fig_Box in, fig_Box out)
{
    return in.lo_X >= out.lo_X && in.hi_X <= out.hi_X && in.lo_Y >= out.lo_Y && in.hi_Y <= out.hi_Y;
}

/* ---- the path, each flight sampled densely by the library ---- */

typedef struct {
    jc_Sample *s;
    int n;
} fig_Path;

typedef struct {
    jc_Sample *s;
    int n, cap;
    double t_end_s;
} fig_Flight;

static int keep_flight_sample(void *ctx, const jc_Sample *s)
{
    fig_Flight *f = ctx;
    if (s->state.t_s > f->t_end_s || f->n == f->cap) return JC_ESTOPPED;
    if (s->mode == JC_MODE_FLIGHT) f->s[f->n++] = *s;
    return JC_OK;
}

/* The flight that event e starts, sampled FLIGHT_SAMPLES times by running
 * the library again from the event's state (with the run's options); the
 * samples written to out, their count returned, 0 when the run again does
 * not fly as the first one did (the run's own samples are kept then). */
static int flight_samples(const fig_Data *d, const jc_Event *e, jc_Workspace *ws, jc_Sample *out, int cap)
{
    jc_SimOptions o = d->sim;
    const double t_end = e->state.t_s + e->flight_time_s;
    o.sample_dt_s = fmax(e->flight_time_s / FLIGHT_SAMPLES, 1e-9);
    o.t_max_s = fmin(o.t_max_s, t_end + 2 * o.sample_dt_s);
    o.max_samples = cap + 16;
    fig_Flight f = {out, 0, cap, t_end + 1e-9};
    const jc_Recorder rec = {&f, NULL, keep_flight_sample};
    jc_Run run;
    memset(&run, 0, sizeof run);
    char err[160];
    const int rc = jc_simulate_from(d->model, &e->state, &o, &rec, ws, &run, err, sizeof err);
    jc_run_free(&run);
    if ((rc != JC_OK && rc != JC_ESTOPPED) || f.n < FLIGHT_SAMPLES / 2) return 0;
    return f.n;
}

static int by_time(const void *a, const void *b)
{
    const double ta = ((const jc_Sample *)a)->state.t_s, tb = ((const jc_Sample *)b)->state.t_s;
    return (ta > tb) - (ta < tb);
}

/* The run's samples, with those of each flight that starts in [t_lo, t_hi]
 * replaced by the library's dense ones; in time order. Caller frees p->s. */
static fig_Path dense_path(const fig_Data *d, double t_lo, double t_hi)
{
    const jc_Run *run = &d->run;
    int flights = 0;
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        flights += fig_event_flies(e) && e->state.t_s >= t_lo && e->state.t_s <= t_hi;
    }
    if (flights > MAX_FLIGHTS) flights = MAX_FLIGHTS;
    const int cap = FLIGHT_SAMPLES + 8;
    fig_Path p = {malloc(sizeof(jc_Sample) * ((size_t)run->sample_count + (size_t)flights * cap + 1)), 0};
    double *span = malloc(sizeof(double) * 2 * ((size_t)flights + 1));
    jc_Workspace *ws = jc_workspace_new();
    if (!p.s || !span || !ws) {
        free(p.s);
        free(span);
        jc_workspace_free(ws);
        return (fig_Path){NULL, 0};
    }
    int done = 0;
    for (int i = 0; i < run->event_count && done < flights; ++i) {
        const jc_Event *e = &run->events[i];
        if (!fig_event_flies(e) || e->state.t_s < t_lo || e->state.t_s > t_hi) continue;
        const int n = flight_samples(d, e, ws, p.s + p.n, cap);
        if (n == 0) continue;
        p.n += n;
        span[2 * done] = e->state.t_s;
        span[2 * done + 1] = e->state.t_s + e->flight_time_s;
        ++done;
    }
    jc_workspace_free(ws);
    for (int i = 0; i < run->sample_count; ++i) {
        const double t = run->samples[i].state.t_s;
        int inside = 0;
        for (int k = 0; k < done && !inside; ++k) inside = t > span[2 * k] && t < span[2 * k + 1];
        if (!inside) p.s[p.n++] = run->samples[i];
    }
    free(span);
    qsort(p.s, (size_t)p.n, sizeof *p.s, by_time);
    return p;
}

/* ---- data blocks ---- */

static void write_ramp(const fig_Data *d)
{
    const jc_Model *m = d->model;
    const double a = m->setup.incline_rad, depth_cm = 50 * m->body.radius_m;
    const fig_Pt end = picture(a, m->setup.ramp_length_m, 0);
    fig_block_begin(d->gp, "ramp");
    fputs("# jumpcyl plot: the ramp, a closed polygon (picture cm). Its first two rows are the incline:\n"
          "# from the start contact point (0, 0) to the ramp's lower end; the rest close a wedge under it.\n"
          "# columns: X_cm Y_cm\n",
          d->gp);
    fprintf(d->gp, "0 0\n%.10g %.10g\n%.10g %.10g\n0 %.10g\n0 0\n", end.X, end.Y, end.X, end.Y - depth_cm,
            end.Y - depth_cm);
    fig_block_end(d->gp);
}

static void write_path_header(FILE *gp, const fig_Data *d)
{
    const jc_BodyDef *b = &d->model->setup.body;
    fprintf(gp,
            "# jumpcyl plot: the body's path in the laboratory frame (picture cm: X right, Y up; the incline\n"
            "# descends to the right from (0, 0)), at every sample of the run; each flight from t = %.4g to\n"
            "# %.4g s sampled %d times by running the library again from its start (jc_simulate_from).\n"
            "# C: the centre (geometric axis); G: the centre of mass (jc_Sample cm_x_m, cm_y_m); then the\n"
            "# axis of each off-centre part.\n"
            "# columns: t_s mode X_C_cm Y_C_cm X_G_cm Y_G_cm",
            d->zoomed ? d->zoom_t_lo_s : 0.0, d->zoomed ? d->zoom_t_hi_s : d->t_max_s, FLIGHT_SAMPLES);
    for (int i = 0; i < b->part_count; ++i)
        if (off_centre(&b->parts[i])) fprintf(gp, " X_part%d_cm Y_part%d_cm", i + 1, i + 1);
    fputs("\n# parts:", gp);
    for (int i = 0; i < b->part_count; ++i)
        if (off_centre(&b->parts[i]))
            fprintf(gp, " part%d %s at %.4g cm;", i + 1, jc_part_kind_name(b->parts[i].kind), b->parts[i].offset_m * 100);
    fputc('\n', gp);
}

static void write_path(FILE *gp, const fig_Data *d, const fig_Path *path)
{
    const jc_Model *m = d->model;
    const double a = m->setup.incline_rad;
    fig_block_begin(gp, "path");
    write_path_header(gp, d);
    for (int i = 0; i < path->n; ++i) {
        const jc_Sample *p = &path->s[i];
        const fig_Pt c = picture(a, p->state.x_m, p->state.y_m), g = picture(a, p->cm_x_m, p->cm_y_m);
        fprintf(gp, "%.12g %d %.10g %.10g %.10g %.10g", p->state.t_s, (int)p->mode, c.X, c.Y, g.X, g.Y);
        for (int k = 0; k < m->setup.body.part_count; ++k) {
            const jc_Part *q = &m->setup.body.parts[k];
            if (!off_centre(q)) continue;
            const fig_Pt pp = body_point(m, &p->state, q->offset_m, q->angle_rad);
            fprintf(gp, " %.10g %.10g", pp.X, pp.Y);
        }
        fputc('\n', gp);
    }
    fig_block_end(gp);
}

/* ---- outlines at the events ---- */

typedef struct {
    int event;           /* the event whose state is drawn */
    fig_Pt c;            /* its centre (picture cm) */
    char label[LABEL_MAX];
} fig_Outline;

/* Which event of a group is drawn: the lift-off, then an impact (the
 * landing), then a slip; otherwise the first. */
static int event_rank(jc_EventKind k)
{
    switch (k) {
    case JC_EVENT_LIFTOFF: return 4;
    case JC_EVENT_TOUCHDOWN:
    case JC_EVENT_BOUNCE: return 3;
    case JC_EVENT_SLIP: return 2;
    default: return 1;
    }
}

static int in_window(const jc_Event *e, double t_lo, double t_hi) { return e->state.t_s >= t_lo && e->state.t_s <= t_hi; }

static fig_Pt event_centre(const fig_Data *d, int i)
{
    const jc_State *s = &d->run.events[i].state;
    return picture(d->model->setup.incline_rad, s->x_m, s->y_m);
}

/* Adds "what" to out, after ", " unless it is the first. */
static void add_item(char *out, size_t len, const char *what)
{
    const size_t used = strlen(out);
    snprintf(out + used, len - used, "%s%s", used ? ", " : "", what);
}

/* The events of one outline in plain words, in time order: "slip,
 * lift-off", "4 bounces, touchdown, 306 stick–slip cycles". A stretch of
 * alternating slips and sticks (three of each or more) is counted as
 * cycles; a label too long for LABEL_MAX ends in "and N more". */
static void outline_label(const jc_Run *run, const int *ev, int n, char *out, size_t len)
{
    char items[16][LABEL_MAX];
    int counts[16], count = 0;
    for (int i = 0; i < n && count < 16;) {
        const jc_EventKind k = run->events[ev[i]].kind;
        int j = i, sticks = 0, slips = 0;
        while (j < n && (run->events[ev[j]].kind == JC_EVENT_SLIP || run->events[ev[j]].kind == JC_EVENT_STICK ||
                         run->events[ev[j]].kind == JC_EVENT_SLIP_REVERSAL)) {
            sticks += run->events[ev[j]].kind == JC_EVENT_STICK;
            slips += run->events[ev[j]].kind == JC_EVENT_SLIP;
            ++j;
        }
        if (sticks >= 3 && slips >= 3) {
            snprintf(items[count], LABEL_MAX, "%d stick–slip cycles", sticks > slips ? sticks : slips);
        } else {
            j = i + 1;
            while (j < n && run->events[ev[j]].kind == k) ++j;
            if (j - i > 1) snprintf(items[count], LABEL_MAX, "%d %ss", j - i, fig_event_label(k));
            else snprintf(items[count], LABEL_MAX, "%s", fig_event_label(k));
        }
        counts[count++] = j - i;
        i = j;
    }
    out[0] = '\0';
    int shown = 0, left = n;
    for (; shown < count; ++shown) {
        if (strlen(out) + strlen(items[shown]) + 2 + (shown + 1 < count ? 16 : 0) >= len) break;
        add_item(out, len, items[shown]);
        left -= counts[shown];
    }
    if (shown < count) {
        char more[32];
        snprintf(more, sizeof more, "and %d more", left);
        add_item(out, len, more);
    }
}

/* Picks outlines among the events in [t_lo, t_hi] at least sep_m apart,
 * the highest ranked first (the first lift-off always), then gives every
 * event to its nearest outline; the outlines in time order. The count, or
 * -1 when there would be more than max. */
static int pick_outlines(const fig_Data *d, double t_lo, double t_hi, double sep_m, fig_Outline *out, int max)
{
    const jc_Run *run = &d->run;
    int n = 0;
    for (int rank = 4; rank >= 1; --rank)
        for (int i = 0; i < run->event_count; ++i) {
            if (event_rank(run->events[i].kind) != rank || !in_window(&run->events[i], t_lo, t_hi)) continue;
            const fig_Pt c = event_centre(d, i);
            int clear = 1;
            for (int k = 0; k < n && clear; ++k) clear = hypot(c.X - out[k].c.X, c.Y - out[k].c.Y) > 100 * sep_m;
            if (!clear) continue;
            if (n == max) return -1;
            out[n++] = (fig_Outline){i, c, ""};
        }
    /* In time order (insertion sort: n is small). */
    for (int i = 1; i < n; ++i)
        for (int k = i; k > 0 && out[k].event < out[k - 1].event; --k) {
            const fig_Outline t = out[k];
            out[k] = out[k - 1];
            out[k - 1] = t;
        }
    int *members = malloc(sizeof(int) * ((size_t)run->event_count + 1));
    int *owner = malloc(sizeof(int) * ((size_t)run->event_count + 1));
    if (!members || !owner) {
        free(members);
        free(owner);
        for (int k = 0; k < n; ++k) snprintf(out[k].label, LABEL_MAX, "%s", fig_event_label(run->events[out[k].event].kind));
        return n;
    }
    for (int i = 0; i < run->event_count; ++i) {
        owner[i] = -1;
        if (!in_window(&run->events[i], t_lo, t_hi)) continue;
        const fig_Pt c = event_centre(d, i);
        double best = INFINITY;
        for (int k = 0; k < n; ++k) {
            const double dist = hypot(c.X - out[k].c.X, c.Y - out[k].c.Y);
            if (dist < best) best = dist, owner[i] = k;
        }
    }
    for (int k = 0; k < n; ++k) {
        int m = 0;
        for (int i = 0; i < run->event_count; ++i)
            if (owner[i] == k) members[m++] = i;
        outline_label(run, members, m, out[k].label, LABEL_MAX);
    }
    free(members);
    free(owner);
    return n;
}

static int choose_outlines(const fig_Data *d, double t_lo, double t_hi, fig_Outline *out, double *sep_m)
{
    *sep_m = OUTLINE_SEPARATION_RADII * d->model->body.radius_m;
    int n;
    while ((n = pick_outlines(d, t_lo, t_hi, *sep_m, out, MAX_OUTLINES)) < 0) *sep_m *= 2;
    return n;
}

static void write_outline_row(FILE *gp, const fig_Data *d, const fig_Outline *o)
{
    const jc_Model *m = d->model;
    const jc_State *s = &d->run.events[o->event].state;
    const fig_Pt ref = body_point(m, s, m->body.radius_m, 0.0);
    const fig_Pt g = body_point(m, s, m->body.cm_offset_m, m->body.cm_angle_rad);
    fprintf(gp, "%.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.12g %s \"%s\"\n", s->x_m * 100, o->c.X, o->c.Y,
            m->body.radius_m * 100, ref.X, ref.Y, g.X, g.Y, s->t_s, jc_event_name(d->run.events[o->event].kind),
            o->label);
}

static void write_outline_parts(FILE *gp, const fig_Data *d, const fig_Outline *o, int n)
{
    const jc_Model *m = d->model;
    fig_block_begin(gp, "outline_parts");
    fputs("# jumpcyl plot: the off-centre parts at each outline of $outlines (same order): where the part's\n"
          "# axis is (picture cm) and its own radius (cm; 0 for a point mass or a line rod).\n"
          "# columns: outline X_cm Y_cm radius_cm kind\n",
          gp);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < m->setup.body.part_count; ++k) {
            const jc_Part *q = &m->setup.body.parts[k];
            if (!off_centre(q)) continue;
            const fig_Pt p = body_point(m, &d->run.events[o[i].event].state, q->offset_m, q->angle_rad);
            fprintf(gp, "%d %.10g %.10g %.10g %s\n", i + 1, p.X, p.Y, q->radius_m * 100, jc_part_kind_name(q->kind));
        }
    fig_block_end(gp);
}

static void write_outlines(FILE *gp, const fig_Data *d, const fig_Outline *o, int n, double sep_m)
{
    fig_block_begin(gp, "outlines");
    fprintf(gp,
            "# jumpcyl plot: the body's outline at the events of the main panel (jc_Event state), at least\n"
            "# %.3g cm (%.3g rim radii) apart: drawn at the lift-offs, then the impacts, the slips, the\n"
            "# other events; every event is named in the label of the outline nearest to it. At most %d.\n"
            "# contact_x_cm: where the rim touches (or is over) the incline, x along it from the start.\n"
            "# X_ref, Y_ref: the end of the radius along the body's reference direction (the rotation).\n"
            "# columns: contact_x_cm X_C_cm Y_C_cm r_cm X_ref_cm Y_ref_cm X_G_cm Y_G_cm t_s kind label\n",
            sep_m * 100, sep_m / d->model->body.radius_m, MAX_OUTLINES);
    for (int i = 0; i < n; ++i) write_outline_row(gp, d, &o[i]);
    fig_block_end(gp);
    write_outline_parts(gp, d, o, n);
}

/* ---- the first flight's close-up ---- */

/* The sample of the first flight with the largest gap under the rim; -1
 * when no flight holds a sample. */
static int first_apex(const jc_Run *run, const fig_Path *path)
{
    int e = 0;
    while (e < run->event_count && !fig_event_flies(&run->events[e])) ++e;
    if (e == run->event_count) return -1;
    const double t0 = run->events[e].state.t_s, t1 = t0 + run->events[e].flight_time_s;
    int best = -1;
    for (int i = 0; i < path->n; ++i) {
        const jc_Sample *p = &path->s[i];
        if (p->state.t_s >= t0 && p->state.t_s <= t1 && (best < 0 || p->gap_m > path->s[best].gap_m)) best = i;
    }
    return best;
}

/* ---- the page ---- */

/* A panel on the page: its ranges (cm), its plot area (page px from the
 * lower left) and the room it was given. */
typedef struct {
    fig_Box view, area, region;
} fig_Frame;

/* The page px of a picture point in a frame. */
static fig_Pt to_px(const fig_Frame *f, fig_Pt p)
{
    const double s = box_w(f->area) / box_w(f->view);
    return (fig_Pt){f->area.lo_X + (p.X - f->view.lo_X) * s, f->area.lo_Y + (p.Y - f->view.lo_Y) * s};
}

static double px_per_cm(const fig_Frame *f) { return box_w(f->area) / box_w(f->view); }

/* Ranges of equal scale that hold the box and fill a plot area of w x h
 * px: the shorter side is widened about its middle. */
static fig_Box fit(fig_Box b, double w_px, double h_px)
{
    const double w = fmax(box_w(b), 1e-9), h = fmax(box_h(b), 1e-9);
    if (w / h < w_px / h_px) {
        const double grow = (h * w_px / h_px - w) / 2;
        b.lo_X -= grow;
        b.hi_X += grow;
    } else {
        const double grow = (w * h_px / w_px - h) / 2;
        b.lo_Y -= grow;
        b.hi_Y += grow;
    }
    return b;
}

/* The frame of a picture box in a region of the page with top_px and
 * bottom_px of room above and below the plot area: the plot area is sized
 * to the box at the largest scale that fits (its range is the box's, except
 * a side thinner than MIN_PLOT_PX, widened) and centred in the room; with
 * fill, the plot area takes the whole room and the box is widened to it. */
static fig_Frame frame_in(fig_Box region, fig_Box box, double top_px, double bottom_px, int fill)
{
    const fig_Box room = {region.lo_X + MARGIN_L_PX, region.hi_X - MARGIN_R_PX, region.lo_Y + bottom_px,
                          region.hi_Y - top_px};
    const double aw = fmax(box_w(room), MIN_PLOT_PX), ah = fmax(box_h(room), MIN_PLOT_PX);
    fig_Frame f = {box, room, region};
    if (fill) {
        f.view = fit(box, aw, ah);
        f.area = (fig_Box){room.lo_X, room.lo_X + aw, room.lo_Y, room.lo_Y + ah};
        return f;
    }
    const double bw = fmax(box_w(box), 1e-9), bh = fmax(box_h(box), 1e-9);
    const double s = fmin(aw / bw, ah / bh);
    const double w = fmin(fmax(bw * s, MIN_PLOT_PX), aw), h = fmin(fmax(bh * s, MIN_PLOT_PX), ah);
    f.view = fit(box, w, h);
    const double cx = 0.5 * (room.lo_X + room.lo_X + aw), cy = 0.5 * (room.lo_Y + room.lo_Y + ah);
    f.area = (fig_Box){cx - w / 2, cx + w / 2, cy - h / 2, cy + h / 2};
    return f;
}

typedef struct {
    fig_Frame main, ramp, closeup;
    int ramp_shown, closeup_shown;
    int key_rows;
    int title_lines[3]; /* main, ramp, close-up */
} fig_Layout;

/* Room above a plot area for a title of so many lines. */
static double title_px(int lines) { return lines * TITLE_LINE_PX + TITLE_GAP_PX; }

/* ---- labels placed clear of everything ---- */

/* What a label must clear, in page px: curves (polylines broken by NaN),
 * discs (the outlines), the incline (labels stay above it), labels placed. */
typedef struct {
    const fig_Pt *pts;
    int n;
    const fig_Pt *disc_c;
    const double *disc_r;
    int discs;
    fig_Pt incline_at, incline_dir; /* a point of the incline and its direction (px) */
    int above_incline;
    fig_Box *labels;
    int label_count;
    fig_Box area; /* labels stay inside */
} fig_Obstacles;

static int segment_hits(fig_Box r, fig_Pt a, fig_Pt b)
{
    if (fmax(a.X, b.X) < r.lo_X || fmin(a.X, b.X) > r.hi_X || fmax(a.Y, b.Y) < r.lo_Y || fmin(a.Y, b.Y) > r.hi_Y)
        return 0;
    const double dx = b.X - a.X, dy = b.Y - a.Y;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {a.X - r.lo_X, r.hi_X - a.X, a.Y - r.lo_Y, r.hi_Y - a.Y};
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0) return 0;
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0) t0 = fmax(t0, t);
        else t1 = fmin(t1, t);
        if (t0 > t1) return 0;
    }
    return 1;
}

static int disc_hits(fig_Box r, fig_Pt c, double radius)
{
    const double dx = c.X - fmin(fmax(c.X, r.lo_X), r.hi_X), dy = c.Y - fmin(fmax(c.Y, r.lo_Y), r.hi_Y);
    return dx * dx + dy * dy < radius * radius;
}

/* Whether the box r, padded, clears every obstacle; inside: also within the area. */
static int clear_of(const fig_Obstacles *o, fig_Box r, int inside)
{
    const fig_Box p = {r.lo_X - LABEL_PAD_PX, r.hi_X + LABEL_PAD_PX, r.lo_Y - LABEL_PAD_PX, r.hi_Y + LABEL_PAD_PX};
    if (inside && !box_inside(r, o->area)) return 0;
    if (o->above_incline) {
        const fig_Pt corner[4] = {{p.lo_X, p.lo_Y}, {p.hi_X, p.lo_Y}, {p.lo_X, p.hi_Y}, {p.hi_X, p.hi_Y}};
        for (int k = 0; k < 4; ++k) {
            const double side = (corner[k].X - o->incline_at.X) * o->incline_dir.Y -
                                (corner[k].Y - o->incline_at.Y) * o->incline_dir.X;
            if (side > 0) return 0; /* below the incline (it runs to the right, down) */
        }
    }
    for (int i = 0; i < o->label_count; ++i)
        if (box_overlaps(p, o->labels[i])) return 0;
    for (int i = 0; i < o->discs; ++i)
        if (disc_hits(p, o->disc_c[i], o->disc_r[i])) return 0;
    for (int i = 0; i + 1 < o->n; ++i)
        if (!isnan(o->pts[i].X) && !isnan(o->pts[i + 1].X) && segment_hits(p, o->pts[i], o->pts[i + 1])) return 0;
    return 1;
}

/* A w x h px box for a label next to a mark at c of radius r_px (px), on
 * the side given by the angle: touching the circle of radius dist there. */
static fig_Box beside(fig_Pt c, double dist, double ang, double w, double h)
{
    const double X = c.X + dist * cos(ang), Y = c.Y + dist * sin(ang), cs = cos(ang), sn = sin(ang);
    const double lo_X = cs > 0.3 ? X : cs < -0.3 ? X - w : X - w * (0.5 - cs / 0.6);
    const double lo_Y = sn > 0.3 ? Y : sn < -0.3 ? Y - h : Y - h * (0.5 - sn / 0.6);
    return (fig_Box){lo_X, lo_X + w, lo_Y, lo_Y + h};
}

/* The place of a w x h px label next to a mark (centre c, radius r_px):
 * the nearest clear box, trying sides from the preferred angle outwards and
 * rings further out: within 75 degrees of it inside the area, then outside
 * it (the caller widens the view), then on any side; else the preferred
 * place. */
static fig_Box place_label(const fig_Obstacles *o, fig_Pt c, double r_px, double prefer, double w, double h)
{
    for (int pass = 0; pass < 4; ++pass)
        for (int ring = 0, inside = pass % 2 == 0, sides = pass < 2 ? 10 : 24; ring < 8; ++ring)
            for (int k = 0; k < sides; ++k) {
                const double ang = prefer + (k % 2 ? -1 : 1) * ((k + 1) / 2) * (PI / 12);
                const fig_Box b = beside(c, r_px + LABEL_PAD_PX + 2 + ring * 0.7 * h, ang, w, h);
                if (clear_of(o, b, inside)) return b;
            }
    return beside(c, r_px + LABEL_PAD_PX + 2, prefer, w, h);
}

static double label_w_px(const char *s)
{
    size_t chars = 0;
    for (; *s; ++s) chars += ((unsigned char)*s & 0xC0) != 0x80; /* UTF-8 characters */
    return SMALL_CHAR_PX * (double)chars + 4;
}

/* The main panel's curves in page px: each path within [t_lo, t_hi], the
 * curves broken by NaN. Caller frees. */
static fig_Pt *curves_px(const fig_Data *d, const fig_Path *path, const fig_Frame *f, double t_lo, double t_hi, int *n)
{
    const jc_Model *m = d->model;
    const int per = 3 + m->setup.body.part_count;
    fig_Pt *p = malloc(sizeof(fig_Pt) * ((size_t)path->n + 1) * (size_t)per);
    *n = 0;
    if (!p) return NULL;
    const fig_Pt gap = {NAN, NAN};
    for (int curve = 0; curve < per - 1; ++curve) {
        const jc_Part *q = curve >= 2 ? &m->setup.body.parts[curve - 2] : NULL;
        if (q && !off_centre(q)) continue;
        for (int i = 0; i < path->n; ++i) {
            const jc_Sample *s = &path->s[i];
            if (s->state.t_s < t_lo || s->state.t_s > t_hi) continue;
            const fig_Pt c = curve == 0   ? picture(m->setup.incline_rad, s->state.x_m, s->state.y_m)
                             : curve == 1 ? picture(m->setup.incline_rad, s->cm_x_m, s->cm_y_m)
                                          : body_point(m, &s->state, q->offset_m, q->angle_rad);
            p[(*n)++] = to_px(f, c);
        }
        p[(*n)++] = gap;
    }
    return p;
}

/* Places the outlines' labels in the main frame (page px); returns how
 * many fall outside its plot area. */
static int place_outline_labels(const fig_Data *d, const fig_Path *path, const fig_Frame *f, double t_lo, double t_hi,
                                const fig_Outline *o, int n, fig_Box *labels)
{
    const double r_px = d->model->body.radius_m * 100 * px_per_cm(f), a = d->model->setup.incline_rad;
    fig_Pt disc_c[MAX_OUTLINES];
    double disc_r[MAX_OUTLINES];
    for (int i = 0; i < n; ++i) {
        disc_c[i] = to_px(f, o[i].c);
        disc_r[i] = r_px;
    }
    int count;
    fig_Pt *pts = curves_px(d, path, f, t_lo, t_hi, &count);
    fig_Obstacles ob = {pts, count, disc_c, disc_r, n, to_px(f, (fig_Pt){0, 0}), {cos(a), -sin(a)}, 1, labels, 0,
                        f->area};
    int outside = 0;
    for (int i = 0; i < n; ++i) {
        labels[i] = place_label(&ob, disc_c[i], r_px, PI / 2 - a, label_w_px(o[i].label), SMALL_LINE_PX);
        outside += !box_inside(labels[i], f->area);
        ob.label_count = i + 1;
    }
    free(pts);
    return outside;
}

/* ---- the layout ---- */

/* The parts of a title, joined with ", " into lines no wider than
 * width_px (estimated); "\n" between lines, as gnuplot reads it. */
static int wrap_title(const char *const *parts, int n, double width_px, char *out, size_t len)
{
    const size_t max_chars = (size_t)fmax(width_px / TITLE_CHAR_PX, 20);
    size_t line = 0;
    int lines = 1;
    out[0] = '\0';
    for (int i = 0; i < n; ++i) {
        size_t chars = 0;
        for (const char *s = parts[i]; *s; ++s) chars += ((unsigned char)*s & 0xC0) != 0x80;
        const size_t used = strlen(out);
        if (i > 0 && line + 2 + chars > max_chars) {
            snprintf(out + used, len - used, ",\\n%s", parts[i]);
            line = chars;
            ++lines;
        } else {
            snprintf(out + used, len - used, "%s%s", i ? ", " : "", parts[i]);
            line += (i ? 2 : 0) + chars;
        }
    }
    return lines;
}

typedef struct {
    char main[400], ramp[200], closeup[200];
} fig_Titles;

/* The width a title centred over a frame's plot area may take in its region. */
static double title_room(const fig_Frame *f)
{
    const double c = 0.5 * (f->area.lo_X + f->area.hi_X);
    return 2 * fmin(c - f->region.lo_X, f->region.hi_X - c) - 30;
}

/* The three titles, wrapped to their regions' widths. */
static void make_titles(const fig_Data *d, const jc_Sample *apex, fig_Layout *l, fig_Titles *t, double sep_cm)
{
    char a[160], b[120], c[120], e[80];
    if (d->zoomed)
        snprintf(a, sizeof a, "Path to scale: x = %.3g–%.3g cm down the incline (t = %.3g–%.3g s)", d->zoom_x_lo_cm,
                 d->zoom_x_hi_cm, d->zoom_t_lo_s, d->zoom_t_hi_s);
    else snprintf(a, sizeof a, "Path to scale: the whole run");
    snprintf(b, sizeof b, "%s", d->zoomed ? "around the first lift-off and the hops" : "nothing lifts off");
    snprintf(c, sizeof c, "outlines at the events, at least %.3g cm apart", sep_cm);
    const char *pm[] = {a, b, c};
    l->title_lines[0] = wrap_title(pm, 3, title_room(&l->main), t->main, sizeof t->main);
    snprintf(a, sizeof a, "The whole ramp (%.4g cm)", d->model->setup.ramp_length_m * 100);
    const char *pr[] = {a, "in red: the main panel's view"};
    l->title_lines[1] = wrap_title(pr, 2, title_room(&l->ramp), t->ramp, sizeof t->ramp);
    l->title_lines[2] = 0;
    if (apex) {
        snprintf(a, sizeof a, "Close-up: the first flight at its highest");
        snprintf(e, sizeof e, "t = %.4g s, gap %.3g mm", apex->state.t_s, apex->gap_m * 1e3);
        const char *pc[] = {a, e};
        l->title_lines[2] = wrap_title(pc, 2, title_room(&l->closeup), t->closeup, sizeof t->closeup);
    }
}

/* The page split for the main panel's box: the main panel on top (the rest
 * below it) or on the left (the rest to its right), whichever draws it at
 * the larger scale; its room sized to its box. */
static fig_Box main_region(fig_Box box, double top_px, double bottom_px, int alone, int *on_top)
{
    *on_top = 1;
    if (alone) return (fig_Box){0, PAGE_W_PX, 0, PAGE_H_PX - PAGE_TITLE_PX};
    const double H = PAGE_H_PX - PAGE_TITLE_PX, bw = fmax(box_w(box), 1e-9), bh = fmax(box_h(box), 1e-9);
    const double side_w = MARGIN_L_PX + MARGIN_R_PX, side_h = top_px + bottom_px;
    /* On top: the full width, as tall as the box needs, within 35-62 %. */
    const double s_top_w = (PAGE_W_PX - side_w) / bw;
    const double h_top = fmin(fmax(bh * s_top_w + side_h, 0.35 * H), 0.62 * H);
    const double s_top = fmin(s_top_w, (h_top - side_h) / bh);
    /* On the left: the full height, as wide as the box needs, within 40-68 %. */
    const double s_left_h = (H - side_h) / bh;
    const double w_left = fmin(fmax(bw * s_left_h + side_w, 0.40 * PAGE_W_PX), 0.68 * PAGE_W_PX);
    const double s_left = fmin(s_left_h, (w_left - side_w) / bw);
    *on_top = s_top >= s_left;
    return *on_top ? (fig_Box){0, PAGE_W_PX, PAGE_H_PX - PAGE_TITLE_PX - h_top, PAGE_H_PX - PAGE_TITLE_PX}
                   : (fig_Box){0, w_left, 0, H};
}

/* The box of the curves drawn between t_lo and t_hi: the paths of the
 * centre, of the off-centre parts and of the centre of mass. */
static fig_Box curves_box(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi)
{
    const jc_Model *m = d->model;
    const double a = m->setup.incline_rad;
    fig_Box b = empty_box;
    for (int i = 0; i < path->n; ++i) {
        const jc_Sample *s = &path->s[i];
        if (s->state.t_s < t_lo || s->state.t_s > t_hi) continue;
        box_add(&b, picture(a, s->state.x_m, s->state.y_m), 0);
        box_add(&b, picture(a, s->cm_x_m, s->cm_y_m), 0);
        for (int k = 0; k < m->setup.body.part_count; ++k)
            if (off_centre(&m->setup.body.parts[k]))
                box_add(&b, body_point(m, &s->state, m->setup.body.parts[k].offset_m, m->setup.body.parts[k].angle_rad), 0);
    }
    if (!isfinite(b.lo_X)) box_add(&b, picture(a, 0, m->body.radius_m), m->body.radius_m * 100);
    return b;
}

/* A box grown by a small fraction of its size, so that no curve runs along the border. */
static fig_Box margin(fig_Box b)
{
    const double pad = 0.015 * fmax(box_w(b), box_h(b));
    return (fig_Box){b.lo_X - pad, b.hi_X + pad, b.lo_Y - pad, b.hi_Y + pad};
}

/* The close-up's box: CLOSEUP_GAPS gaps about the middle of the gap. */
static fig_Box closeup_box(const fig_Data *d, const jc_Sample *s)
{
    const double a = d->model->setup.incline_rad;
    const double half_cm = 100 * fmax(CLOSEUP_GAPS * s->gap_m, CLOSEUP_MIN_HALF_M);
    const fig_Pt low = picture(a, s->state.x_m, s->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = picture(a, s->state.x_m, 0.0);
    const fig_Pt mid = {0.5 * (low.X + foot.X), 0.5 * (low.Y + foot.Y)};
    return (fig_Box){mid.X - half_cm, mid.X + half_cm, mid.Y - half_cm, mid.Y + half_cm};
}

/* The side panels (the whole ramp, the close-up) in the room the main
 * panel leaves: beside each other under it, or above each other beside it. */
static void side_frames(fig_Layout *l, int on_top, fig_Box ramp_box, fig_Box close_box)
{
    const fig_Box rest = on_top ? (fig_Box){0, PAGE_W_PX, 0, l->main.region.lo_Y}
                                : (fig_Box){l->main.region.hi_X, PAGE_W_PX, 0, PAGE_H_PX - PAGE_TITLE_PX};
    const double tr = title_px(l->title_lines[1]), tc = title_px(l->title_lines[2]);
    fig_Box rr = rest, rc = rest;
    if (!l->ramp_shown) {
        if (l->closeup_shown) l->closeup = frame_in(rc, close_box, tc, MARGIN_B_PX, 1);
        return;
    }
    if (l->closeup_shown && on_top) {
        const double want = box_w(ramp_box) * (box_h(rest) - tr - MARGIN_B_PX) / fmax(box_h(ramp_box), 1e-9);
        const double w = fmin(fmax(want + MARGIN_L_PX + MARGIN_R_PX, 0.35 * PAGE_W_PX), 0.65 * PAGE_W_PX);
        rr.hi_X = rc.lo_X = w;
    } else if (l->closeup_shown) {
        const double want = box_h(ramp_box) * (box_w(rest) - MARGIN_L_PX - MARGIN_R_PX) / fmax(box_w(ramp_box), 1e-9);
        const double h = fmin(fmax(want + tr + MARGIN_B_PX, 0.35 * box_h(rest)), 0.6 * box_h(rest));
        rr.lo_Y = rc.hi_Y = rest.hi_Y - h;
    }
    l->ramp = frame_in(rr, ramp_box, tr, MARGIN_B_PX, 0);
    if (l->closeup_shown) l->closeup = frame_in(rc, close_box, tc, MARGIN_B_PX, 1);
}

/* ---- panels ---- */

static void set_frame(FILE *gp, const fig_Frame *f)
{
    fprintf(gp,
            "# To scale: the plot area (page fractions) and the ranges have the same cm per pixel on\n"
            "# both axes (%.4g px per cm); size ratio -1 keeps it so if the margins are changed.\n"
            "set size ratio -1\n"
            "set lmargin at screen %.5f\nset rmargin at screen %.5f\nset bmargin at screen %.5f\nset tmargin at screen %.5f\n"
            "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n",
            px_per_cm(f), f->area.lo_X / PAGE_W_PX, f->area.hi_X / PAGE_W_PX, f->area.lo_Y / PAGE_H_PX,
            f->area.hi_Y / PAGE_H_PX, f->view.lo_X, f->view.hi_X, f->view.lo_Y, f->view.hi_Y);
    fputs("set xlabel 'X (cm), horizontal'\nset ylabel 'Y (cm), vertical'\n"
          "set clip two   # lines crossing the view with both ends outside it (the incline in a close-up)\n",
          gp);
}

/* The column of $path a curve's coordinates start in, and its legend. */
static void part_title(const jc_BodyDef *b, int i, char *out, size_t len)
{
    int same = 0, nth = 0;
    for (int k = 0; k < b->part_count; ++k)
        if (off_centre(&b->parts[k]) && b->parts[k].kind == b->parts[i].kind) {
            ++same;
            if (k <= i) ++nth;
        }
    const char *name = b->parts[i].kind == JC_PART_POINT ? "point mass" : jc_part_kind_name(b->parts[i].kind);
    if (same > 1) snprintf(out, len, "%s %d%s", name, nth, b->parts[i].kind == JC_PART_POINT ? "" : "'s axis");
    else snprintf(out, len, "%s%s", name, b->parts[i].kind == JC_PART_POINT ? "" : "'s axis");
}

/* The paths of the centre, the parts and the centre of mass; in
 * [t_lo, t_hi] only when windowed. */
static void plot_paths(FILE *gp, const fig_Data *d, int titled, int windowed)
{
    const jc_BodyDef *b = &d->model->setup.body;
    const char *win = windowed ? "($1 < T_LO || $1 > T_HI ? NaN : $%d):%d" : "%d:%d";
    char using[64];
    snprintf(using, sizeof using, win, 3, 4);
    fprintf(gp, "     PATH using %s with lines lc rgb C_BLUE lw LW %s", using, titled ? "title 'centre C (axis)'" : "notitle");
    for (int i = 0, col = 7; i < b->part_count; ++i) {
        if (!off_centre(&b->parts[i])) continue;
        snprintf(using, sizeof using, win, col, col + 1);
        fprintf(gp, ", \\\n     PATH using %s with lines lc rgb C_ORANGE lw 0.7*LW ", using);
        char name[64];
        part_title(b, i, name, sizeof name);
        if (titled) fprintf(gp, "title \"%s\"", name);
        else fputs("notitle", gp);
        col += 2;
    }
    snprintf(using, sizeof using, win, 5, 6);
    if (!cm_on_a_part(d->model))
        fprintf(gp, ", \\\n     PATH using %s with lines lc rgb C_GREEN lw 0.6*LW dt (6,4) %s", using,
                titled ? "title 'centre of mass G'" : "notitle");
}

/* Sutherland-Hodgman: the part of polygon in[0..n) on the side of the
 * line where inside() holds; the count written to out. */
typedef struct {
    int axis;     /* 0: X, 1: Y */
    double limit;
    int keep_low; /* keep coordinates <= limit */
} fig_Edge;

static int inside_edge(fig_Pt p, fig_Edge e)
{
    const double v = e.axis ? p.Y : p.X;
    return e.keep_low ? v <= e.limit : v >= e.limit;
}

static fig_Pt cross_edge(fig_Pt a, fig_Pt b, fig_Edge e)
{
    const double va = e.axis ? a.Y : a.X, vb = e.axis ? b.Y : b.X, f = (e.limit - va) / (vb - va);
    return (fig_Pt){a.X + f * (b.X - a.X), a.Y + f * (b.Y - a.Y)};
}

static int clip_edge(const fig_Pt *in, int n, fig_Edge e, fig_Pt *out)
{
    int m = 0;
    for (int i = 0; i < n; ++i) {
        const fig_Pt a = in[i], b = in[(i + 1) % n];
        if (inside_edge(a, e)) out[m++] = a;
        if (inside_edge(a, e) != inside_edge(b, e)) out[m++] = cross_edge(a, b, e);
    }
    return m;
}

/* The wedge under the incline, clipped to the view here: gnuplot 5.4 fills
 * a polygon with corners far outside the view wrongly (over the incline). */
#define RAMP_CORNERS 16
static void plot_ramp(FILE *gp, const fig_Data *d, fig_Box view)
{
    const jc_Model *m = d->model;
    const double depth_cm = 50 * m->body.radius_m;
    const fig_Pt end = picture(m->setup.incline_rad, m->setup.ramp_length_m, 0);
    fig_Pt a[RAMP_CORNERS] = {{0, 0}, end, {end.X, end.Y - depth_cm}, {0, end.Y - depth_cm}}, b[RAMP_CORNERS];
    const fig_Edge edges[4] = {{0, view.lo_X, 0}, {0, view.hi_X, 1}, {1, view.lo_Y, 0}, {1, view.hi_Y, 1}};
    int n = 4;
    for (int k = 0; k < 4; ++k) {
        n = clip_edge(a, n, edges[k], b);
        memcpy(a, b, sizeof a);
    }
    if (n >= 3) {
        fputs("# The ramp ($ramp) clipped to the view\nset object 2 polygon", gp);
        for (int i = 0; i <= n; ++i) fprintf(gp, " %s %.10g,%.10g", i ? "to" : "from", a[i % n].X, a[i % n].Y);
        fputs(" back fc rgb C_GREY fs transparent solid 0.15 noborder\n", gp);
    }
    fputs("plot RAMP every ::0::1 using 1:2 with lines lc rgb C_INK lw 1.5 notitle, \\\n", gp);
}

static void plot_outlines(FILE *gp)
{
    fputs(", \\\n     OUTLINES using 2:3:4 with circles lc rgb C_INK lw 1.2 fs empty title 'outline at events', \\\n"
          "     OUTLINES using 2:3:($5 - $2):($6 - $3) with vectors nohead lc rgb C_INK lw 1 notitle, \\\n"
          "     OUTLINE_PARTS using ($4 > 0 ? $2 : NaN):3:4 with circles lc rgb C_ORANGE fs solid 0.6 noborder notitle, \\\n"
          "     OUTLINE_PARTS using 2:3 with points pt 7 ps 0.8*PS lc rgb C_ORANGE notitle, \\\n"
          "     OUTLINES using 2:3 with points pt 7 ps 0.6*PS lc rgb C_BLUE notitle, \\\n"
          "     OUTLINES using 7:8 with points pt 6 ps 1.0*PS lc rgb C_GREEN notitle",
          gp);
}

static void data_names(FILE *gp)
{
    fputs("RAMP = '$ramp'; PATH = '$path'; OUTLINES = '$outlines'; OUTLINE_PARTS = '$outline_parts'\n", gp);
}

/* The page px of a label box back in the frame's cm: its left end, middle height. */
static fig_Pt label_anchor(const fig_Frame *f, fig_Box b)
{
    const double s = px_per_cm(f);
    return (fig_Pt){f->view.lo_X + (b.lo_X + 2 - f->area.lo_X) / s,
                    f->view.lo_Y + (0.5 * (b.lo_Y + b.hi_Y) - f->area.lo_Y) / s};
}

/* The main panel: the window of the run (zoomed on the first lift-off and
 * the hops), its outlines and their labels. */
static void main_panel(FILE *gp, const fig_Data *d, const fig_Layout *l, const char *title, const fig_Outline *o,
                       int n, const fig_Box *labels, double t_lo, double t_hi)
{
    const fig_Frame *f = &l->main;
    fig_panel_begin(gp, "trajectory (zoomed on the first lift-off and the hops)");
    data_names(gp);
    fprintf(gp, "T_LO = %.12g; T_HI = %.12g   # the window of the run shown (s)\n", t_lo, t_hi);
    fputs("$labels << EOD\n# X_cm Y_cm label: each outline's label (left end, middle), clear of curves, outlines and "
          "each other\n",
          gp);
    for (int i = 0; i < n; ++i) {
        const fig_Pt p = label_anchor(f, labels[i]);
        fprintf(gp, "%.10g %.10g \"%s\"\n", p.X, p.Y, o[i].label);
    }
    fputs("EOD\n", gp);
    fprintf(gp, "set title \"%s\"\n", title);
    set_frame(gp, f);
    fprintf(gp, "set key at screen %.5f,%.5f left top Left reverse horizontal maxrows %d\n", f->area.lo_X / PAGE_W_PX,
            (f->area.lo_Y - MARGIN_B_PX + 8) / PAGE_H_PX, l->key_rows);
    plot_ramp(gp, d, f->view);
    plot_paths(gp, d, 1, 1);
    plot_outlines(gp);
    fputs(", \\\n     $labels using 1:2:3 with labels left font F_SMALL textcolor rgb C_INK notitle\n", gp);
}

/* The whole ramp, with the main panel's view marked. */
static void ramp_panel(FILE *gp, const fig_Data *d, const fig_Layout *l, const char *title)
{
    fig_panel_begin(gp, "the whole ramp, the main panel's view marked");
    data_names(gp);
    fprintf(gp, "set title \"%s\"\n", title);
    set_frame(gp, &l->ramp);
    const fig_Box z = l->main.view;
    fprintf(gp, "set object 1 rect from %.10g,%.10g to %.10g,%.10g front fs empty border lc rgb C_RED lw 2\n",
            fmax(z.lo_X, l->ramp.view.lo_X), fmax(z.lo_Y, l->ramp.view.lo_Y), fmin(z.hi_X, l->ramp.view.hi_X),
            fmin(z.hi_Y, l->ramp.view.hi_Y));
    plot_ramp(gp, d, l->ramp.view);
    plot_paths(gp, d, 0, 0);
    fputs(", \\\n     OUTLINES using 2:3 with points pt 7 ps 0.6*PS lc rgb C_INK notitle\n", gp);
}

/* The rim's arc near its lowest point across the close-up's view, finely
 * enough that a gap of a micrometre is not lost in the polygon (gnuplot's
 * circles are coarser); in cm, and in page px in px[]. */
static void write_rim_arc(FILE *gp, const fig_Data *d, const jc_State *s, const fig_Frame *f, fig_Pt *px)
{
    const jc_Model *m = d->model;
    const double r = m->body.radius_m, half_m = 0.01 * hypot(box_w(f->view), box_h(f->view));
    const double span = fmin(PI, 2 * asin(fmin(1.0, half_m / r)) + 1e-3);
    fig_block_begin(gp, "closeup_rim");
    fputs("# jumpcyl plot: the rim near its lowest point at the first flight's highest sample (picture cm).\n"
          "# columns: X_cm Y_cm\n",
          gp);
    for (int i = 0; i <= RIM_ARC_POINTS; ++i) {
        const double phi = PI + span * (2.0 * i / RIM_ARC_POINTS - 1.0); /* from the outward normal */
        const fig_Pt p = picture(m->setup.incline_rad, s->x_m + r * sin(phi), s->y_m + r * cos(phi));
        fprintf(gp, "%.12g %.12g\n", p.X, p.Y);
        px[i] = to_px(f, p);
    }
    fig_block_end(gp);
}

/* The first flight at its highest: the gap under the rim, to scale. */
static void closeup_panel(FILE *gp, const fig_Data *d, const fig_Layout *l, const char *title, const jc_Sample *s)
{
    const fig_Frame *f = &l->closeup;
    const double a = d->model->setup.incline_rad;
    const fig_Pt low = picture(a, s->state.x_m, s->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = picture(a, s->state.x_m, 0.0);
    fig_panel_begin(gp, "close-up of the first flight's gap");
    data_names(gp);
    fig_block_begin(gp, "closeup");
    fputs("# jumpcyl plot: the first flight at its highest sample: the rim's lowest point, the point of the\n"
          "# incline under it, the gap between them (mm), the time.\n"
          "# columns: X_low_cm Y_low_cm X_foot_cm Y_foot_cm gap_mm t_s\n",
          gp);
    fprintf(gp, "%.12g %.12g %.12g %.12g %.10g %.12g\n", low.X, low.Y, foot.X, foot.Y, s->gap_m * 1e3, s->state.t_s);
    fig_block_end(gp);
    /* The gap's label, clear of the rim, the incline and the arrow. */
    fig_Pt px[RIM_ARC_POINTS + 4];
    write_rim_arc(gp, d, &s->state, f, px);
    px[RIM_ARC_POINTS + 1] = (fig_Pt){NAN, NAN};
    px[RIM_ARC_POINTS + 2] = to_px(f, low);
    px[RIM_ARC_POINTS + 3] = to_px(f, foot);
    const fig_Pt mid = {0.5 * (px[RIM_ARC_POINTS + 2].X + px[RIM_ARC_POINTS + 3].X),
                        0.5 * (px[RIM_ARC_POINTS + 2].Y + px[RIM_ARC_POINTS + 3].Y)};
    char text[48];
    snprintf(text, sizeof text, "gap %.3g mm", s->gap_m * 1e3);
    const fig_Obstacles ob = {px, RIM_ARC_POINTS + 4, NULL, NULL, 0, to_px(f, (fig_Pt){0, 0}), {cos(a), -sin(a)}, 1,
                              NULL, 0, f->area};
    const fig_Box box = place_label(&ob, mid, 0, -a, label_w_px(text), SMALL_LINE_PX);
    const fig_Pt at = label_anchor(f, box);
    fprintf(gp, "set title \"%s\"\n", title);
    set_frame(gp, f);
    fputs("set format x '%.4g'\nset format y '%.4g'\n", gp);
    fprintf(gp, "set label 1 \"%s\" at %.12g,%.12g left font F_SMALL textcolor rgb C_RED front\n", text, at.X, at.Y);
    plot_ramp(gp, d, f->view);
    fputs("     $closeup_rim using 1:2 with lines lc rgb C_INK lw 2 notitle, \\\n"
          "     $closeup using 1:2:($3 - $1):($4 - $2) with vectors heads lc rgb C_RED lw 2 notitle\n",
          gp);
}

/* ---- the figure ---- */

int fig_trajectory_prepare(fig_Data *d, const jc_SimOptions *o)
{
    d->sim = *o;
    write_ramp(d);
    return EXIT_OK;
}

/* The legend's entries: the centre, each off-centre part, G, the outlines. */
static int key_entries(const jc_Model *m)
{
    int n = 2 + !cm_on_a_part(m);
    for (int i = 0; i < m->setup.body.part_count; ++i) n += off_centre(&m->setup.body.parts[i]);
    return n;
}

/* The main panel's frame for its box, with room below for the key: as
 * many rows as the plot area's width needs (gnuplot fills a row across
 * it). */
static void main_frame(fig_Layout *l, fig_Box box, int entries, int alone, int *on_top)
{
    const double top = title_px(l->title_lines[0]);
    l->key_rows = 1;
    for (int k = 0; k < 3; ++k) {
        const double bottom = MARGIN_B_PX + l->key_rows * KEY_ROW_PX + 8;
        l->main = frame_in(main_region(box, top, bottom, alone, on_top), box, top, bottom, 0);
        const int cols = (int)fmax(1, floor(box_w(l->main.area) / KEY_ENTRY_PX));
        const int rows = (entries + cols - 1) / cols;
        if (rows == l->key_rows) break;
        l->key_rows = rows;
    }
}

/* The layout: the main panel's box grown until its labels fit in it. */
static void lay_out(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi, const fig_Outline *o, int n,
                    fig_Box *labels, fig_Layout *l, fig_Titles *t, const jc_Sample *apex, double sep_cm)
{
    const jc_Model *m = d->model;
    fig_Box box = curves_box(d, path, t_lo, t_hi), ramp = curves_box(d, path, 0, d->t_max_s);
    for (int i = 0; i < n; ++i) box_add(&box, o[i].c, m->body.radius_m * 100);
    box = margin(box);
    box_add(&ramp, picture(m->setup.incline_rad, 0, 0), 0);
    box_add(&ramp, picture(m->setup.incline_rad, m->setup.ramp_length_m, 0), 0);
    ramp = margin(ramp);
    const fig_Box close = apex ? closeup_box(d, apex) : empty_box;
    memset(l, 0, sizeof *l);
    l->title_lines[0] = 2;
    l->title_lines[1] = l->title_lines[2] = 1;
    for (int round = 0; round < LAYOUT_ROUNDS; ++round) {
        int on_top;
        /* The whole ramp adds nothing when the main panel shows nearly all of it. */
        const double tol = 0.03 * fmax(box_w(ramp), box_h(ramp));
        l->ramp_shown = !(box.lo_X <= ramp.lo_X + tol && box.hi_X >= ramp.hi_X - tol && box.lo_Y <= ramp.lo_Y + tol &&
                          box.hi_Y >= ramp.hi_Y - tol);
        l->closeup_shown = apex != NULL;
        main_frame(l, box, key_entries(m), !l->ramp_shown && !l->closeup_shown, &on_top);
        l->closeup_shown = apex && 100 * apex->gap_m * px_per_cm(&l->main) < CLOSEUP_GAP_PX;
        if (!l->ramp_shown && !l->closeup_shown) main_frame(l, box, key_entries(m), 1, &on_top);
        side_frames(l, on_top, ramp, close);
        if (l->closeup_shown) {
            const fig_Box v = l->closeup.view;
            l->closeup_shown = box_w(v) < 0.5 * box_w(l->main.view) && box_h(v) < 0.5 * box_h(l->main.view);
            if (!l->ramp_shown && !l->closeup_shown) main_frame(l, box, key_entries(m), 1, &on_top);
            side_frames(l, on_top, ramp, close);
        }
        /* The titles' lines set the frames' room, the frames the titles' widths. */
        for (int k = 0; k < 2; ++k) {
            make_titles(d, l->closeup_shown ? apex : NULL, l, t, sep_cm);
            side_frames(l, on_top, ramp, close);
        }
        make_titles(d, l->closeup_shown ? apex : NULL, l, t, sep_cm);
        const int outside = place_outline_labels(d, path, &l->main, t_lo, t_hi, o, n, labels);
        if (outside == 0 && round > 0) break;
        const double s = px_per_cm(&l->main);
        for (int i = 0; i < n; ++i) {
            const fig_Box b = labels[i];
            const double pad = 8;
            const fig_Pt lo = {l->main.view.lo_X + (b.lo_X - pad - l->main.area.lo_X) / s,
                               l->main.view.lo_Y + (b.lo_Y - pad - l->main.area.lo_Y) / s};
            const fig_Pt hi = {l->main.view.lo_X + (b.hi_X + pad - l->main.area.lo_X) / s,
                               l->main.view.lo_Y + (b.hi_Y + pad - l->main.area.lo_Y) / s};
            box_join(&box, (fig_Box){lo.X, hi.X, lo.Y, hi.Y});
        }
    }
}

/* The page: the main panel on top or on the left (whichever draws it
 * larger), the whole ramp and the close-up in the rest. */
void fig_trajectory_panels(FILE *gp, const fig_Data *d)
{
    const double t_lo = d->zoomed ? d->zoom_t_lo_s : 0.0, t_hi = d->zoomed ? d->zoom_t_hi_s : d->t_max_s;
    fig_Path path = dense_path(d, t_lo, t_hi);
    if (!path.s) path = (fig_Path){d->run.samples, d->run.sample_count};
    fig_Outline o[MAX_OUTLINES];
    fig_Box labels[MAX_OUTLINES];
    double sep_m;
    const int n = choose_outlines(d, t_lo, t_hi, o, &sep_m);
    write_path(gp, d, &path);
    write_outlines(gp, d, o, n, sep_m);
    const int apex_i = first_apex(&d->run, &path);
    jc_Sample apex;
    if (apex_i >= 0) apex = path.s[apex_i];
    fig_Layout l;
    fig_Titles t;
    lay_out(d, &path, t_lo, t_hi, o, n, labels, &l, &t, apex_i >= 0 ? &apex : NULL, sep_m * 100);

    char caption[256], body[256];
    fig_caption(d->model, caption, sizeof caption);
    fig_body_caption(d->model, body, sizeof body);
    fprintf(gp, "\nset multiplot title \"jumpcyl trajectory: %s; %s\" font F_TITLE\n", caption, body);
    main_panel(gp, d, &l, t.main, o, n, labels, t_lo, t_hi);
    if (l.ramp_shown) ramp_panel(gp, d, &l, t.ramp);
    if (l.closeup_shown) closeup_panel(gp, d, &l, t.closeup, &apex);
    fputs("\nunset multiplot\n", gp);
    if (path.s != d->run.samples) free(path.s);
}
