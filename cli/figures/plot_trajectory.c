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
 * in cm. */
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Outlines at events closer than this many radii share one (they would
 * overprint); the separation doubles until at most MAX_OUTLINES remain. */
#define OUTLINE_SEPARATION_RADII 2.0
#define MAX_OUTLINES 24
/* The page: a 2400 x 1500 px canvas (plot.c, kind "trajectory"). */
#define PAGE_W_PX 2400.0
#define PAGE_H_PX 1500.0
/* The plot area is about the panel less this much (px) for tics, labels,
 * title and key; ranges are widened to its aspect so that the equal axes
 * fill it. */
#define FRAME_W_PX 190.0
#define FRAME_H_PX 250.0
/* Rough size of a label of F_SMALL text (px): to keep labels apart. */
#define CHAR_W_PX 9.5
#define LINE_H_PX 26.0
#define LABEL_LEVELS 4
/* The close-up spans this many gap heights above and below the gap. */
#define CLOSEUP_GAPS 3.0
#define CLOSEUP_MIN_HALF_M 1e-5
#define RIM_ARC_POINTS 400
#define PI 3.14159265358979323846

typedef struct {
    double X, Y; /* picture coordinates, cm */
} fig_Pt;

typedef struct {
    double lo_X, hi_X, lo_Y, hi_Y; /* cm */
} fig_Box;

/* A panel's place on the page (screen fractions) and its plot area (px). */
typedef struct {
    double x, y, w, h;
} fig_Place;

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

static const fig_Box empty_box = {INFINITY, -INFINITY, INFINITY, -INFINITY};

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

static void write_path_header(const fig_Data *d)
{
    const jc_BodyDef *b = &d->model->setup.body;
    fputs("# jumpcyl plot: the body's path in the laboratory frame (picture cm: X right, Y up; the incline\n"
          "# descends to the right from (0, 0)), at every sample of the run. C: the centre (geometric\n"
          "# axis); G: the centre of mass (jc_Sample cm_x_m, cm_y_m); then the axis of each off-centre part.\n"
          "# columns: t_s mode X_C_cm Y_C_cm X_G_cm Y_G_cm",
          d->gp);
    for (int i = 0; i < b->part_count; ++i)
        if (off_centre(&b->parts[i])) fprintf(d->gp, " X_part%d_cm Y_part%d_cm", i + 1, i + 1);
    fputs("\n# parts:", d->gp);
    for (int i = 0; i < b->part_count; ++i)
        if (off_centre(&b->parts[i]))
            fprintf(d->gp, " part%d %s at %.4g cm;", i + 1, jc_part_kind_name(b->parts[i].kind), b->parts[i].offset_m * 100);
    fputc('\n', d->gp);
}

static void write_path(const fig_Data *d)
{
    const jc_Model *m = d->model;
    const double a = m->setup.incline_rad;
    fig_block_begin(d->gp, "path");
    write_path_header(d);
    for (int i = 0; i < d->run.sample_count; ++i) {
        const jc_Sample *p = &d->run.samples[i];
        const fig_Pt c = picture(a, p->state.x_m, p->state.y_m), g = picture(a, p->cm_x_m, p->cm_y_m);
        fprintf(d->gp, "%.12g %d %.10g %.10g %.10g %.10g", p->state.t_s, (int)p->mode, c.X, c.Y, g.X, g.Y);
        for (int k = 0; k < m->setup.body.part_count; ++k) {
            const jc_Part *q = &m->setup.body.parts[k];
            if (!off_centre(q)) continue;
            const fig_Pt pp = body_point(m, &p->state, q->offset_m, q->angle_rad);
            fprintf(d->gp, " %.10g %.10g", pp.X, pp.Y);
        }
        fputc('\n', d->gp);
    }
    fig_block_end(d->gp);
}

/* ---- outlines at the events ---- */

typedef struct {
    int event;       /* the event whose state is drawn */
    int first, last; /* the events it stands for */
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

static double event_distance_m(const jc_Event *a, const jc_Event *b)
{
    return hypot(a->state.x_m - b->state.x_m, a->state.y_m - b->state.y_m);
}

/* Groups events lying within sep_m of their group's first; the count, or
 * -1 when there would be more than max. */
static int group_events(const jc_Run *run, double sep_m, fig_Outline *out, int max)
{
    int n = 0;
    for (int lead = 0; lead < run->event_count;) {
        int last = lead, best = lead;
        while (last + 1 < run->event_count && event_distance_m(&run->events[last + 1], &run->events[lead]) <= sep_m)
            ++last;
        for (int i = lead; i <= last; ++i)
            if (event_rank(run->events[i].kind) > event_rank(run->events[best].kind)) best = i;
        if (n == max) return -1;
        out[n++] = (fig_Outline){best, lead, last};
        lead = last + 1;
    }
    return n;
}

static int choose_outlines(const fig_Data *d, fig_Outline *out, double *sep_m)
{
    *sep_m = OUTLINE_SEPARATION_RADII * d->model->body.radius_m;
    int n;
    while ((n = group_events(&d->run, *sep_m, out, MAX_OUTLINES)) < 0) *sep_m *= 2;
    return n;
}

static void write_outline_row(const fig_Data *d, const fig_Outline *o)
{
    const jc_Model *m = d->model;
    const jc_State *s = &d->run.events[o->event].state;
    const fig_Pt c = picture(m->setup.incline_rad, s->x_m, s->y_m);
    const fig_Pt ref = body_point(m, s, m->body.radius_m, 0.0);
    const fig_Pt g = body_point(m, s, m->body.cm_offset_m, m->body.cm_angle_rad);
    char label[64];
    fig_event_cluster_label(&d->run, o->first, o->last, label, sizeof label);
    fprintf(d->gp, "%.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.12g %s \"%s\"\n", s->x_m * 100, c.X, c.Y,
            m->body.radius_m * 100, ref.X, ref.Y, g.X, g.Y, s->t_s, jc_event_name(d->run.events[o->event].kind),
            label);
}

static void write_outline_parts(const fig_Data *d, const fig_Outline *o, int n)
{
    const jc_Model *m = d->model;
    fig_block_begin(d->gp, "outline_parts");
    fputs("# jumpcyl plot: the off-centre parts at each outline of $outlines (same order): where the part's\n"
          "# axis is (picture cm) and its own radius (cm; 0 for a point mass or a line rod).\n"
          "# columns: outline X_cm Y_cm radius_cm kind\n",
          d->gp);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < m->setup.body.part_count; ++k) {
            const jc_Part *q = &m->setup.body.parts[k];
            if (!off_centre(q)) continue;
            const fig_Pt p = body_point(m, &d->run.events[o[i].event].state, q->offset_m, q->angle_rad);
            fprintf(d->gp, "%d %.10g %.10g %.10g %s\n", i + 1, p.X, p.Y, q->radius_m * 100, jc_part_kind_name(q->kind));
        }
    fig_block_end(d->gp);
}

static void write_outlines(const fig_Data *d)
{
    fig_Outline o[MAX_OUTLINES];
    double sep_m;
    const int n = choose_outlines(d, o, &sep_m);
    fig_block_begin(d->gp, "outlines");
    fprintf(d->gp,
            "# jumpcyl plot: the body's outline at the events (jc_Event state). Events closer than %.3g cm\n"
            "# (%.3g rim radii) to the first of a group share one outline, drawn at its lift-off, else its\n"
            "# first impact, else its slip, else its first event; the label names them all. At most %d.\n"
            "# contact_x_cm: where the rim touches (or is over) the incline, x along it from the start.\n"
            "# X_ref, Y_ref: the end of the radius along the body's reference direction (the rotation).\n"
            "# columns: contact_x_cm X_C_cm Y_C_cm r_cm X_ref_cm Y_ref_cm X_G_cm Y_G_cm t_s kind label\n",
            sep_m * 100, sep_m / d->model->body.radius_m, MAX_OUTLINES);
    for (int i = 0; i < n; ++i) write_outline_row(d, &o[i]);
    fig_block_end(d->gp);
    write_outline_parts(d, o, n);
}

/* ---- the first flight's close-up ---- */

/* The sample of the first flight with the largest gap under the rim; -1
 * when no flight holds a sample. */
static int first_apex(const fig_Data *d)
{
    const jc_Run *run = &d->run;
    int e = 0;
    while (e < run->event_count && !fig_event_flies(&run->events[e])) ++e;
    if (e == run->event_count) return -1;
    const double t0 = run->events[e].state.t_s, t1 = t0 + run->events[e].flight_time_s;
    int best = -1;
    for (int i = 0; i < run->sample_count; ++i) {
        const jc_Sample *p = &run->samples[i];
        if (p->state.t_s >= t0 && p->state.t_s <= t1 && (best < 0 || p->gap_m > run->samples[best].gap_m)) best = i;
    }
    return best;
}

/* The rim's arc near its lowest point, finely enough that a gap of a
 * micrometre is not lost in the polygon (gnuplot's circles are coarser). */
static void write_rim_arc(const fig_Data *d, const jc_State *s, double half_m)
{
    const jc_Model *m = d->model;
    const double r = m->body.radius_m, span = fmin(PI, 2 * asin(fmin(1.0, half_m / r)) + 1e-3);
    fig_block_begin(d->gp, "closeup_rim");
    fputs("# jumpcyl plot: the rim near its lowest point at the first flight's highest sample (picture cm).\n"
          "# columns: X_cm Y_cm\n",
          d->gp);
    for (int i = 0; i <= RIM_ARC_POINTS; ++i) {
        const double phi = PI + span * (2.0 * i / RIM_ARC_POINTS - 1.0); /* from the outward normal */
        const fig_Pt p = picture(m->setup.incline_rad, s->x_m + r * sin(phi), s->y_m + r * cos(phi));
        fprintf(d->gp, "%.12g %.12g\n", p.X, p.Y);
    }
    fig_block_end(d->gp);
}

static void write_closeup(const fig_Data *d, int apex)
{
    const jc_Sample *p = &d->run.samples[apex];
    const double a = d->model->setup.incline_rad;
    const double half_m = fmax(CLOSEUP_GAPS * p->gap_m, CLOSEUP_MIN_HALF_M);
    const fig_Pt low = picture(a, p->state.x_m, p->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = picture(a, p->state.x_m, 0.0);
    fig_block_begin(d->gp, "closeup");
    fputs("# jumpcyl plot: the first flight at its highest sample: the rim's lowest point, the point of the\n"
          "# incline under it, the gap between them (mm), the time, and the close-up's half height (cm).\n"
          "# columns: X_low_cm Y_low_cm X_foot_cm Y_foot_cm gap_mm t_s half_cm\n",
          d->gp);
    fprintf(d->gp, "%.12g %.12g %.12g %.12g %.10g %.12g %.10g\n", low.X, low.Y, foot.X, foot.Y, p->gap_m * 1e3,
            p->state.t_s, half_m * 100);
    fig_block_end(d->gp);
    write_rim_arc(d, &p->state, half_m * 1.6 * 1.8); /* the window is wider than tall */
}

int fig_trajectory_prepare(fig_Data *d)
{
    write_ramp(d);
    write_path(d);
    write_outlines(d);
    const int apex = first_apex(d);
    if (apex >= 0) write_closeup(d, apex);
    return EXIT_OK;
}

/* ---- panels ---- */

/* Ranges of equal scale that hold the box and fill a plot area of w x h
 * px: the shorter side is widened about its middle. */
static fig_Box fit(fig_Box b, double w_px, double h_px)
{
    double w = fmax(b.hi_X - b.lo_X, 1e-9), h = fmax(b.hi_Y - b.lo_Y, 1e-9);
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

static void set_ranges(FILE *gp, fig_Box b)
{
    fprintf(gp, "# Equal scales on both axes: the picture is to scale (size ratio -1).\n"
                "set size ratio -1\nset xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n",
            b.lo_X, b.hi_X, b.lo_Y, b.hi_Y);
    fputs("set xlabel 'X (cm), horizontal'\nset ylabel 'Y (cm), vertical'\n"
          "set clip two   # lines crossing the view with both ends outside it (the incline in a close-up)\n",
          gp);
}

static void place(FILE *gp, fig_Place p)
{
    fprintf(gp, "set origin %.4g,%.4g\nset size %.4g,%.4g\n", p.x, p.y, p.w, p.h);
}

/* The box the run covers between t_lo and t_hi: the rim's extent. */
static fig_Box run_box(const fig_Data *d, double t_lo, double t_hi)
{
    fig_Box b = empty_box;
    const double a = d->model->setup.incline_rad, r_cm = d->model->body.radius_m * 100;
    for (int i = 0; i < d->run.sample_count; ++i) {
        const jc_State *s = &d->run.samples[i].state;
        if (s->t_s >= t_lo && s->t_s <= t_hi) box_add(&b, picture(a, s->x_m, s->y_m), 1.05 * r_cm);
    }
    if (!isfinite(b.lo_X)) box_add(&b, picture(a, 0, d->model->body.radius_m), 1.05 * r_cm);
    return b;
}

/* The paths of the centre, the parts and the centre of mass. */
static void plot_paths(FILE *gp, const fig_Data *d, int titled)
{
    const jc_BodyDef *b = &d->model->setup.body;
    fprintf(gp, "     PATH using 3:4 with lines lc rgb C_BLUE lw LW %s", titled ? "title 'centre C (axis)'" : "notitle");
    for (int i = 0, col = 7; i < b->part_count; ++i) {
        if (!off_centre(&b->parts[i])) continue;
        fprintf(gp, ", \\\n     PATH using %d:%d with lines lc rgb C_ORANGE lw 0.7*LW ", col, col + 1);
        if (titled) fprintf(gp, "title 'axis of part %d (%s)'", i + 1, jc_part_kind_name(b->parts[i].kind));
        else fputs("notitle", gp);
        col += 2;
    }
    if (!cm_on_a_part(d->model))
        fprintf(gp, ", \\\n     PATH using 5:6 with lines lc rgb C_GREEN lw 0.6*LW dt (6,4) %s",
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

typedef struct {
    double lo_X, hi_X, lo_Y, hi_Y;
} fig_Rect;

static int overlaps(const fig_Rect *a, const fig_Rect *b)
{
    return a->lo_X < b->hi_X && b->lo_X < a->hi_X && a->lo_Y < b->hi_Y && b->lo_Y < a->hi_Y;
}

/* Where an outline's label goes: its lower left corner just beyond the rim
 * along the incline's outward normal (the empty side), so that the text,
 * running right and up from there, clears the rim; pushed further out until
 * it clears the labels placed before it. */
static fig_Rect place_label(fig_Pt c, double r_cm, double a, double w_cm, double h_cm, const fig_Rect *placed, int n)
{
    fig_Rect box = {0, 0, 0, 0};
    for (int k = 0; k < LABEL_LEVELS * 3; ++k) {
        const double out = r_cm + (0.3 + 1.1 * k) * h_cm;
        const double X = c.X + out * sin(a), Y = c.Y + out * cos(a);
        box = (fig_Rect){X, X + w_cm, Y, Y + h_cm};
        int clear = 1;
        for (int i = 0; i < n && clear; ++i) clear = !overlaps(&box, &placed[i]);
        if (clear) break;
    }
    return box;
}

/* The outlines' labels as a data block, each clear of the others (widths
 * estimated from the scale of view); widens the box b to hold the labels
 * of the outlines in view. */
static void label_rows(FILE *gp, const fig_Data *d, fig_Box view, fig_Box *b, double w_px)
{
    const double cm_per_px = (view.hi_X - view.lo_X) / w_px, r_cm = d->model->body.radius_m * 100;
    const double a = d->model->setup.incline_rad;
    fig_Outline o[MAX_OUTLINES];
    fig_Rect placed[MAX_OUTLINES];
    double sep_m;
    const int n = choose_outlines(d, o, &sep_m);
    fputs("$labels << EOD\n# X_cm Y_cm label: each outline's label (left end), clear of the others\n", gp);
    for (int i = 0; i < n; ++i) {
        const jc_State *s = &d->run.events[o[i].event].state;
        const fig_Pt c = picture(a, s->x_m, s->y_m);
        char label[64];
        fig_event_cluster_label(&d->run, o[i].first, o[i].last, label, sizeof label);
        const double w_cm = CHAR_W_PX * (double)strlen(label) * cm_per_px;
        placed[i] = place_label(c, r_cm, a, w_cm, LINE_H_PX * cm_per_px, placed, i);
        fprintf(gp, "%.10g %.10g \"%s\"\n", placed[i].lo_X, 0.5 * (placed[i].lo_Y + placed[i].hi_Y), label);
        /* Only the labels of outlines in view count for the panel's box. */
        if (c.X >= view.lo_X && c.X <= view.hi_X && c.Y >= view.lo_Y && c.Y <= view.hi_Y) {
            b->hi_X = fmax(b->hi_X, placed[i].hi_X);
            b->hi_Y = fmax(b->hi_Y, placed[i].hi_Y);
        }
    }
    fputs("EOD\n", gp);
}

static void data_names(FILE *gp)
{
    fputs("RAMP = '$ramp'; PATH = '$path'; OUTLINES = '$outlines'; OUTLINE_PARTS = '$outline_parts'\n", gp);
}

/* The main panel: zoomed on the first lift-off and the hops. */
static fig_Box main_panel(FILE *gp, const fig_Data *d, fig_Place p, double w_px, double h_px)
{
    fig_panel_begin(gp, "trajectory (zoomed on the first lift-off and the hops)");
    data_names(gp);
    const double t_lo = d->zoomed ? d->zoom_t_lo_s : 0.0, t_hi = d->zoomed ? d->zoom_t_hi_s : d->t_max_s;
    fig_Box b = run_box(d, t_lo, t_hi);
    label_rows(gp, d, fit(b, w_px, h_px), &b, w_px);
    b = fit(b, w_px, h_px);
    char zoom[200] = "the whole run";
    if (d->zoomed) fig_zoom_caption(d, zoom, sizeof zoom);
    place(gp, p);
    fig_Outline o[MAX_OUTLINES];
    double sep_m;
    choose_outlines(d, o, &sep_m);
    fprintf(gp, "set title \"Path to scale, %s\\nthe outline at the events; events within %.3g cm share one\"\n", zoom,
            sep_m * 100);
    set_ranges(gp, b);
    const fig_Box view = b;
    fputs("set key inside top right Left reverse vertical opaque\n", gp);
    plot_ramp(gp, d, view);
    plot_paths(gp, d, 1);
    plot_outlines(gp);
    fputs(", \\\n     $labels using 1:2:3 with labels left font F_SMALL textcolor rgb C_INK notitle\n", gp);
    return b;
}

/* The whole ramp, with the main panel's box marked. */
static void ramp_panel(FILE *gp, const fig_Data *d, fig_Place p, double w_px, double h_px, fig_Box zoom)
{
    fig_panel_begin(gp, "the whole ramp, the zoom marked");
    data_names(gp);
    const jc_Model *m = d->model;
    fig_Box b = run_box(d, 0, d->t_max_s);
    box_add(&b, picture(m->setup.incline_rad, 0, 0), 0);
    box_add(&b, picture(m->setup.incline_rad, m->setup.ramp_length_m, 0), 0);
    place(gp, p);
    fprintf(gp, "set title \"The whole ramp (%.4g cm); the box: the zoom above\"\n", m->setup.ramp_length_m * 100);
    const fig_Box view = fit(b, w_px, h_px);
    set_ranges(gp, view);
    fprintf(gp, "set object 1 rect from %.10g,%.10g to %.10g,%.10g front fs empty border lc rgb C_RED lw 2\n",
            zoom.lo_X, zoom.lo_Y, zoom.hi_X, zoom.hi_Y);
    plot_ramp(gp, d, view);
    plot_paths(gp, d, 0);
    fputs(", \\\n     OUTLINES using 2:3 with points pt 7 ps 0.6*PS lc rgb C_INK notitle\n", gp);
}

/* The first flight at its highest: the gap under the rim, to scale. */
static void closeup_panel(FILE *gp, const fig_Data *d, fig_Place p, double w_px, double h_px)
{
    fig_panel_begin(gp, "close-up of the first flight's gap");
    data_names(gp);
    const int apex = first_apex(d);
    const jc_Sample *s = &d->run.samples[apex];
    const double a = d->model->setup.incline_rad;
    const double half_cm = 100 * fmax(CLOSEUP_GAPS * s->gap_m, CLOSEUP_MIN_HALF_M);
    const fig_Pt low = picture(a, s->state.x_m, s->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = picture(a, s->state.x_m, 0.0);
    const fig_Pt mid = {0.5 * (low.X + foot.X), 0.5 * (low.Y + foot.Y)};
    const fig_Box b = {mid.X - half_cm, mid.X + half_cm, mid.Y - half_cm, mid.Y + half_cm};
    place(gp, p);
    fprintf(gp, "set title \"Close-up: the first flight at its highest (t = %.4g s), gap %.3g mm\"\n", s->state.t_s,
            s->gap_m * 1e3);
    const fig_Box view = fit(b, w_px, h_px);
    set_ranges(gp, view);
    fputs("set format x '%.4g'\nset format y '%.4g'\n", gp);
    plot_ramp(gp, d, view);
    fputs("     $closeup_rim using 1:2 with lines lc rgb C_INK lw 2 notitle, \\\n"
          "     $closeup using 1:2:($3 - $1):($4 - $2) with vectors heads lc rgb C_RED lw 2 notitle, \\\n"
          "     $closeup using (($1 + $3) / 2):(($2 + $4) / 2):(sprintf('  gap %.3g mm', $5)) with labels left "
          "font F_SMALL textcolor rgb C_RED notitle\n",
          gp);
}

/* The page: wide pictures (shallow inclines) take the top, the others
 * the left; the whole ramp and the close-up share the rest. */
void fig_trajectory_panels(FILE *gp, const fig_Data *d)
{
    char caption[256], body[256];
    fig_caption(d->model, caption, sizeof caption);
    fig_body_caption(d->model, body, sizeof body);
    fprintf(gp, "\nset multiplot title \"jumpcyl trajectory: %s; %s\" font F_TITLE\n", caption, body);
    const double t_hi = d->zoomed ? d->zoom_t_hi_s : d->t_max_s;
    const fig_Box z = run_box(d, d->zoomed ? d->zoom_t_lo_s : 0.0, t_hi);
    const int wide = (z.hi_X - z.lo_X) > 1.6 * (z.hi_Y - z.lo_Y);
    const int closeup = first_apex(d) >= 0;
    fig_Place pm = wide ? (fig_Place){0, 0.42, 1, 0.55} : (fig_Place){0, 0, 0.6, 0.96};
    fig_Place pr = wide ? (fig_Place){0, 0, closeup ? 0.5 : 1, 0.42} : (fig_Place){0.6, closeup ? 0.48 : 0, 0.4, closeup ? 0.48 : 0.96};
    const fig_Place pc = wide ? (fig_Place){0.5, 0, 0.5, 0.42} : (fig_Place){0.6, 0, 0.4, 0.48};
    const fig_Box zoom = main_panel(gp, d, pm, pm.w * PAGE_W_PX - FRAME_W_PX, pm.h * PAGE_H_PX - FRAME_H_PX);
    ramp_panel(gp, d, pr, pr.w * PAGE_W_PX - FRAME_W_PX, pr.h * PAGE_H_PX - FRAME_H_PX, zoom);
    if (closeup) closeup_panel(gp, d, pc, pc.w * PAGE_W_PX - FRAME_W_PX, pc.h * PAGE_H_PX - FRAME_H_PX);
    fputs("\nunset multiplot\n", gp);
}
