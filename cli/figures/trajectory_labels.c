/* The trajectory figure's labels: each placed in page px where it clears
 * every curve, outline and other label (and stays above the incline). */
#include "figures.h"

#include <math.h>
#include <stdlib.h>

/* Text sizes (px) on the PNG page, the largest of the three terminals:
 * F_SMALL's mean character width. */
#define SMALL_CHAR_PX 11.0
/* Room kept between a label and anything else (px). */
#define LABEL_PAD_PX 5.0
#define PI 3.14159265358979323846

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
    if (inside && !fig_box_inside(r, o->area)) return 0;
    if (o->above_incline) {
        const fig_Pt corner[4] = {{p.lo_X, p.lo_Y}, {p.hi_X, p.lo_Y}, {p.lo_X, p.hi_Y}, {p.hi_X, p.hi_Y}};
        for (int k = 0; k < 4; ++k) {
            const double side = (corner[k].X - o->incline_at.X) * o->incline_dir.Y -
                                (corner[k].Y - o->incline_at.Y) * o->incline_dir.X;
            if (side > 0) return 0; /* below the incline (it runs to the right, down) */
        }
    }
    for (int i = 0; i < o->label_count; ++i)
        if (fig_box_overlaps(p, o->labels[i])) return 0;
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
fig_Box fig_place_label(const fig_Obstacles *o, fig_Pt c, double r_px, double prefer, double w, double h)
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

double fig_label_w_px(const char *s)
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
        if (q && !fig_off_centre(q)) continue;
        for (int i = 0; i < path->n; ++i) {
            const jc_Sample *s = &path->s[i];
            if (s->state.t_s < t_lo || s->state.t_s > t_hi) continue;
            const fig_Pt c = curve == 0   ? fig_picture(m->setup.incline_rad, s->state.x_m, s->state.y_m)
                             : curve == 1 ? fig_picture(m->setup.incline_rad, s->cm_x_m, s->cm_y_m)
                                          : fig_body_point(m, &s->state, q->offset_m, q->angle_rad);
            p[(*n)++] = fig_to_px(f, c);
        }
        p[(*n)++] = gap;
    }
    return p;
}

/* Places the outlines' labels in the main frame (page px); returns how
 * many fall outside its plot area. */
int fig_place_outline_labels(const fig_Data *d, const fig_Path *path, const fig_Frame *f, double t_lo, double t_hi,
                                const fig_Outline *o, int n, fig_Box *labels)
{
    const double r_px = d->model->body.radius_m * 100 * fig_px_per_cm(f), a = d->model->setup.incline_rad;
    fig_Pt disc_c[FIG_MAX_OUTLINES];
    double disc_r[FIG_MAX_OUTLINES];
    for (int i = 0; i < n; ++i) {
        disc_c[i] = fig_to_px(f, o[i].c);
        disc_r[i] = r_px;
    }
    int count;
    fig_Pt *pts = curves_px(d, path, f, t_lo, t_hi, &count);
    fig_Obstacles ob = {pts, count, disc_c, disc_r, n, fig_to_px(f, (fig_Pt){0, 0}), {cos(a), -sin(a)}, 1, labels, 0,
                        f->area};
    int outside = 0;
    for (int i = 0; i < n; ++i) {
        labels[i] = fig_place_label(&ob, disc_c[i], r_px, PI / 2 - a, fig_label_w_px(o[i].label), FIG_SMALL_LINE_PX);
        outside += !fig_box_inside(labels[i], f->area);
        ob.label_count = i + 1;
    }
    free(pts);
    return outside;
}
