/* The trajectory figure: the body's path in the laboratory frame, drawn to
 * scale (equal axes in every panel), with the incline, the paths of the
 * centre, of every off-centre part and of the centre of mass, and the body's
 * outline at the events. Here: the path (each flight sampled again densely
 * by the library), the outlines, the data blocks and the panels' script; the
 * picture's geometry and the frames are trajectory_view.c's, the labels'
 * places trajectory_labels.c's, the page's layout trajectory_layout.c's. */
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Outlines closer than this many radii would overlap: the events of such a
 * group share one outline; the separation doubles until at most
 * FIG_MAX_OUTLINES remain. */
#define OUTLINE_SEPARATION_RADII 2.2
/* Points of the rim's arc in the close-up. */
#define RIM_ARC_POINTS 400
/* Samples the library is asked for across each flight in the main panel
 * (the run's own grid may have a handful there), and flights so resampled. */
#define FLIGHT_SAMPLES 240
#define MAX_FLIGHTS 200
#define PI 3.14159265358979323846

/* ---- the path, each flight sampled densely by the library ---- */

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
    const fig_Pt end = fig_picture(a, m->setup.ramp_length_m, 0);
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
        if (fig_off_centre(&b->parts[i])) fprintf(gp, " X_part%d_cm Y_part%d_cm", i + 1, i + 1);
    fputs("\n# parts:", gp);
    for (int i = 0; i < b->part_count; ++i)
        if (fig_off_centre(&b->parts[i]))
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
        const fig_Pt c = fig_picture(a, p->state.x_m, p->state.y_m), g = fig_picture(a, p->cm_x_m, p->cm_y_m);
        fprintf(gp, "%.12g %d %.10g %.10g %.10g %.10g", p->state.t_s, (int)p->mode, c.X, c.Y, g.X, g.Y);
        for (int k = 0; k < m->setup.body.part_count; ++k) {
            const jc_Part *q = &m->setup.body.parts[k];
            if (!fig_off_centre(q)) continue;
            const fig_Pt pp = fig_body_point(m, &p->state, q->offset_m, q->angle_rad);
            fprintf(gp, " %.10g %.10g", pp.X, pp.Y);
        }
        fputc('\n', gp);
    }
    fig_block_end(gp);
}

/* ---- outlines at the events ---- */

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
    return fig_picture(d->model->setup.incline_rad, s->x_m, s->y_m);
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
 * cycles; a label too long for FIG_LABEL_MAX ends in "and N more". */
static void outline_label(const jc_Run *run, const int *ev, int n, char *out, size_t len)
{
    char items[16][FIG_LABEL_MAX];
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
            snprintf(items[count], FIG_LABEL_MAX, "%d stick–slip cycles", sticks > slips ? sticks : slips);
        } else {
            j = i + 1;
            while (j < n && run->events[ev[j]].kind == k) ++j;
            if (j - i > 1) snprintf(items[count], FIG_LABEL_MAX, "%d %ss", j - i, fig_event_label(k));
            else snprintf(items[count], FIG_LABEL_MAX, "%s", fig_event_label(k));
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
        for (int k = 0; k < n; ++k)
            snprintf(out[k].label, FIG_LABEL_MAX, "%s", fig_event_label(run->events[out[k].event].kind));
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
        outline_label(run, members, m, out[k].label, FIG_LABEL_MAX);
    }
    free(members);
    free(owner);
    return n;
}

static int choose_outlines(const fig_Data *d, double t_lo, double t_hi, fig_Outline *out, double *sep_m)
{
    *sep_m = OUTLINE_SEPARATION_RADII * d->model->body.radius_m;
    int n;
    while ((n = pick_outlines(d, t_lo, t_hi, *sep_m, out, FIG_MAX_OUTLINES)) < 0) *sep_m *= 2;
    return n;
}

static void write_outline_row(FILE *gp, const fig_Data *d, const fig_Outline *o)
{
    const jc_Model *m = d->model;
    const jc_State *s = &d->run.events[o->event].state;
    const fig_Pt ref = fig_body_point(m, s, m->body.radius_m, 0.0);
    const fig_Pt g = fig_body_point(m, s, m->body.cm_offset_m, m->body.cm_angle_rad);
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
            if (!fig_off_centre(q)) continue;
            const fig_Pt p = fig_body_point(m, &d->run.events[o[i].event].state, q->offset_m, q->angle_rad);
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
            sep_m * 100, sep_m / d->model->body.radius_m, FIG_MAX_OUTLINES);
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

/* ---- panels ---- */

static void set_frame(FILE *gp, const fig_Frame *f)
{
    fprintf(gp,
            "# To scale: the plot area (page fractions) and the ranges have the same cm per pixel on\n"
            "# both axes (%.4g px per cm); size ratio -1 keeps it so if the margins are changed.\n"
            "set size ratio -1\n"
            "set lmargin at screen %.5f\nset rmargin at screen %.5f\nset bmargin at screen %.5f\nset tmargin at screen %.5f\n"
            "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n",
            fig_px_per_cm(f), f->area.lo_X / FIG_PAGE_W_PX, f->area.hi_X / FIG_PAGE_W_PX, f->area.lo_Y / FIG_PAGE_H_PX,
            f->area.hi_Y / FIG_PAGE_H_PX, f->view.lo_X, f->view.hi_X, f->view.lo_Y, f->view.hi_Y);
    fputs("set xlabel 'X (cm), horizontal'\nset ylabel 'Y (cm), vertical'\n"
          "set clip two   # lines crossing the view with both ends outside it (the incline in a close-up)\n",
          gp);
}

/* The column of $path a curve's coordinates start in, and its legend. */
static void part_title(const jc_BodyDef *b, int i, char *out, size_t len)
{
    int same = 0, nth = 0;
    for (int k = 0; k < b->part_count; ++k)
        if (fig_off_centre(&b->parts[k]) && b->parts[k].kind == b->parts[i].kind) {
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
        if (!fig_off_centre(&b->parts[i])) continue;
        snprintf(using, sizeof using, win, col, col + 1);
        fprintf(gp, ", \\\n     PATH using %s with lines lc rgb C_ORANGE lw 0.7*LW ", using);
        char name[64];
        part_title(b, i, name, sizeof name);
        if (titled) fprintf(gp, "title \"%s\"", name);
        else fputs("notitle", gp);
        col += 2;
    }
    snprintf(using, sizeof using, win, 5, 6);
    if (!fig_cm_on_a_part(d->model))
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
    const fig_Pt end = fig_picture(m->setup.incline_rad, m->setup.ramp_length_m, 0);
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
    const double s = fig_px_per_cm(f);
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
    fprintf(gp, "set key at screen %.5f,%.5f left top Left reverse horizontal maxrows %d\n", f->area.lo_X / FIG_PAGE_W_PX,
            (f->area.lo_Y - FIG_MARGIN_B_PX + 8) / FIG_PAGE_H_PX, l->key_rows);
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
    const double r = m->body.radius_m, half_m = 0.01 * hypot(fig_box_w(f->view), fig_box_h(f->view));
    const double span = fmin(PI, 2 * asin(fmin(1.0, half_m / r)) + 1e-3);
    fig_block_begin(gp, "closeup_rim");
    fputs("# jumpcyl plot: the rim near its lowest point at the first flight's highest sample (picture cm).\n"
          "# columns: X_cm Y_cm\n",
          gp);
    for (int i = 0; i <= RIM_ARC_POINTS; ++i) {
        const double phi = PI + span * (2.0 * i / RIM_ARC_POINTS - 1.0); /* from the outward normal */
        const fig_Pt p = fig_picture(m->setup.incline_rad, s->x_m + r * sin(phi), s->y_m + r * cos(phi));
        fprintf(gp, "%.12g %.12g\n", p.X, p.Y);
        px[i] = fig_to_px(f, p);
    }
    fig_block_end(gp);
}

/* The first flight at its highest: the gap under the rim, to scale. */
static void closeup_panel(FILE *gp, const fig_Data *d, const fig_Layout *l, const char *title, const jc_Sample *s)
{
    const fig_Frame *f = &l->closeup;
    const double a = d->model->setup.incline_rad;
    const fig_Pt low = fig_picture(a, s->state.x_m, s->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = fig_picture(a, s->state.x_m, 0.0);
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
    px[RIM_ARC_POINTS + 2] = fig_to_px(f, low);
    px[RIM_ARC_POINTS + 3] = fig_to_px(f, foot);
    const fig_Pt mid = {0.5 * (px[RIM_ARC_POINTS + 2].X + px[RIM_ARC_POINTS + 3].X),
                        0.5 * (px[RIM_ARC_POINTS + 2].Y + px[RIM_ARC_POINTS + 3].Y)};
    char text[48];
    snprintf(text, sizeof text, "gap %.3g mm", s->gap_m * 1e3);
    const fig_Obstacles ob = {px, RIM_ARC_POINTS + 4, NULL, NULL, 0, fig_to_px(f, (fig_Pt){0, 0}), {cos(a), -sin(a)}, 1,
                              NULL, 0, f->area};
    const fig_Box box = fig_place_label(&ob, mid, 0, -a, fig_label_w_px(text), FIG_SMALL_LINE_PX);
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

/* The page: the main panel on top or on the left (whichever draws it
 * larger), the whole ramp and the close-up in the rest. */
void fig_trajectory_panels(FILE *gp, const fig_Data *d)
{
    const double t_lo = d->zoomed ? d->zoom_t_lo_s : 0.0, t_hi = d->zoomed ? d->zoom_t_hi_s : d->t_max_s;
    fig_Path path = dense_path(d, t_lo, t_hi);
    if (!path.s) path = (fig_Path){d->run.samples, d->run.sample_count};
    fig_Outline o[FIG_MAX_OUTLINES];
    fig_Box labels[FIG_MAX_OUTLINES];
    double sep_m;
    const int n = choose_outlines(d, t_lo, t_hi, o, &sep_m);
    write_path(gp, d, &path);
    write_outlines(gp, d, o, n, sep_m);
    const int apex_i = first_apex(&d->run, &path);
    jc_Sample apex;
    if (apex_i >= 0) apex = path.s[apex_i];
    fig_Layout l;
    fig_Titles t;
    fig_trajectory_lay_out(d, &path, t_lo, t_hi, o, n, labels, &l, &t, apex_i >= 0 ? &apex : NULL, sep_m * 100);

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
