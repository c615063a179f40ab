/* The trajectory figure's picture and frames: the picture's geometry in cm,
 * boxes, and each panel's frame on the page (its ranges and plot area,
 * sized to its data at one scale on both axes).
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

/* A title's line and the gap under it (px). */
#define TITLE_LINE_PX 37.0
#define TITLE_GAP_PX 35.0
/* A plot area is never thinner than this (px): a flatter picture gets its
 * range widened instead. */
#define MIN_PLOT_PX 160.0
/* The close-up spans this many gap heights above and below the gap. */
#define CLOSEUP_GAPS 3.0
#define CLOSEUP_MIN_HALF_M 1e-5

const fig_Box fig_empty_box = {INFINITY, -INFINITY, INFINITY, -INFINITY};

fig_Pt fig_picture(double incline_rad, double x_m, double y_m)
{
    const fig_Pt p = {100 * (x_m * cos(incline_rad) + y_m * sin(incline_rad)),
                      100 * (-x_m * sin(incline_rad) + y_m * cos(incline_rad))};
    return p;
}

/* A body point (offset from C, body angle) for the state s, in the picture. */
fig_Pt fig_body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad)
{
    const double psi = s->theta_rad - m->body.cm_angle_rad + body_angle_rad;
    return fig_picture(m->setup.incline_rad, s->x_m + offset_m * sin(psi), s->y_m + offset_m * cos(psi));
}

/* Parts whose axis is off the centre: each traces its own path. */
int fig_off_centre(const jc_Part *p) { return p->offset_m > 0; }

/* Whether the centre of mass sits on an off-centre part's axis (a rod
 * alone): then its path is that part's, and is not drawn twice. */
int fig_cm_on_a_part(const jc_Model *m)
{
    const jc_State s = jc_start_state(m);
    const fig_Pt g = fig_body_point(m, &s, m->body.cm_offset_m, m->body.cm_angle_rad);
    for (int i = 0; i < m->setup.body.part_count; ++i) {
        const jc_Part *p = &m->setup.body.parts[i];
        const fig_Pt q = fig_body_point(m, &s, p->offset_m, p->angle_rad);
        if (fig_off_centre(p) && hypot(q.X - g.X, q.Y - g.Y) < 1e-7) return 1;
    }
    return m->body.cm_offset_m == 0;
}

void fig_box_add(fig_Box *b, fig_Pt p, double pad)
{
    b->lo_X = fmin(b->lo_X, p.X - pad);
    b->hi_X = fmax(b->hi_X, p.X + pad);
    b->lo_Y = fmin(b->lo_Y, p.Y - pad);
    b->hi_Y = fmax(b->hi_Y, p.Y + pad);
}

void fig_box_join(fig_Box *b, fig_Box o)
{
    b->lo_X = fmin(b->lo_X, o.lo_X);
    b->hi_X = fmax(b->hi_X, o.hi_X);
    b->lo_Y = fmin(b->lo_Y, o.lo_Y);
    b->hi_Y = fmax(b->hi_Y, o.hi_Y);
}

double fig_box_w(fig_Box b) { return b.hi_X - b.lo_X; }
double fig_box_h(fig_Box b) { return b.hi_Y - b.lo_Y; }

int fig_box_overlaps(fig_Box a, fig_Box b)
{
    return a.lo_X < b.hi_X && b.lo_X < a.hi_X && a.lo_Y < b.hi_Y && b.lo_Y < a.hi_Y;
}

int fig_box_inside(fig_Box in, fig_Box out)
{
    return in.lo_X >= out.lo_X && in.hi_X <= out.hi_X && in.lo_Y >= out.lo_Y && in.hi_Y <= out.hi_Y;
}

/* ---- the page ---- */

/* The page px of a picture point in a frame. */
fig_Pt fig_to_px(const fig_Frame *f, fig_Pt p)
{
    const double s = fig_box_w(f->area) / fig_box_w(f->view);
    return (fig_Pt){f->area.lo_X + (p.X - f->view.lo_X) * s, f->area.lo_Y + (p.Y - f->view.lo_Y) * s};
}

double fig_px_per_cm(const fig_Frame *f) { return fig_box_w(f->area) / fig_box_w(f->view); }

/* Ranges of equal scale that hold the box and fill a plot area of w x h
 * px: the shorter side is widened about its middle. */
static fig_Box fit(fig_Box b, double w_px, double h_px)
{
    const double w = fmax(fig_box_w(b), 1e-9), h = fmax(fig_box_h(b), 1e-9);
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
fig_Frame fig_frame_in(fig_Box region, fig_Box box, double top_px, double bottom_px, int fill)
{
    const fig_Box room = {region.lo_X + FIG_MARGIN_L_PX, region.hi_X - FIG_MARGIN_R_PX, region.lo_Y + bottom_px,
                          region.hi_Y - top_px};
    const double aw = fmax(fig_box_w(room), MIN_PLOT_PX), ah = fmax(fig_box_h(room), MIN_PLOT_PX);
    fig_Frame f = {box, room, region};
    if (fill) {
        f.view = fit(box, aw, ah);
        f.area = (fig_Box){room.lo_X, room.lo_X + aw, room.lo_Y, room.lo_Y + ah};
        return f;
    }
    const double bw = fmax(fig_box_w(box), 1e-9), bh = fmax(fig_box_h(box), 1e-9);
    const double s = fmin(aw / bw, ah / bh);
    const double w = fmin(fmax(bw * s, MIN_PLOT_PX), aw), h = fmin(fmax(bh * s, MIN_PLOT_PX), ah);
    f.view = fit(box, w, h);
    const double cx = 0.5 * (room.lo_X + room.lo_X + aw), cy = 0.5 * (room.lo_Y + room.lo_Y + ah);
    f.area = (fig_Box){cx - w / 2, cx + w / 2, cy - h / 2, cy + h / 2};
    return f;
}

/* Room above a plot area for a title of so many lines. */
double fig_title_px(int lines) { return lines * TITLE_LINE_PX + TITLE_GAP_PX; }

/* The page split for the main panel's box: the main panel on top (the rest
 * below it) or on the left (the rest to its right), whichever draws it at
 * the larger scale; its room sized to its box. */
fig_Box fig_main_region(fig_Box box, double top_px, double bottom_px, int alone, int *on_top)
{
    *on_top = 1;
    if (alone) return (fig_Box){0, FIG_PAGE_W_PX, 0, FIG_PAGE_H_PX - FIG_PAGE_TITLE_PX};
    const double H = FIG_PAGE_H_PX - FIG_PAGE_TITLE_PX, bw = fmax(fig_box_w(box), 1e-9), bh = fmax(fig_box_h(box), 1e-9);
    const double side_w = FIG_MARGIN_L_PX + FIG_MARGIN_R_PX, side_h = top_px + bottom_px;
    /* On top: the full width, as tall as the box needs, within 35-62 %. */
    const double s_top_w = (FIG_PAGE_W_PX - side_w) / bw;
    const double h_top = fmin(fmax(bh * s_top_w + side_h, 0.35 * H), 0.62 * H);
    const double s_top = fmin(s_top_w, (h_top - side_h) / bh);
    /* On the left: the full height, as wide as the box needs, within 40-68 %. */
    const double s_left_h = (H - side_h) / bh;
    const double w_left = fmin(fmax(bw * s_left_h + side_w, 0.40 * FIG_PAGE_W_PX), 0.68 * FIG_PAGE_W_PX);
    const double s_left = fmin(s_left_h, (w_left - side_w) / bw);
    *on_top = s_top >= s_left;
    return *on_top ? (fig_Box){0, FIG_PAGE_W_PX, FIG_PAGE_H_PX - FIG_PAGE_TITLE_PX - h_top, FIG_PAGE_H_PX - FIG_PAGE_TITLE_PX}
                   : (fig_Box){0, w_left, 0, H};
}

/* The box of the curves drawn between t_lo and t_hi: the paths of the
 * centre, of the off-centre parts and of the centre of mass. */
fig_Box fig_curves_box(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi)
{
    const jc_Model *m = d->model;
    const double a = m->setup.incline_rad;
    fig_Box b = fig_empty_box;
    for (int i = 0; i < path->n; ++i) {
        const jc_Sample *s = &path->s[i];
        if (s->state.t_s < t_lo || s->state.t_s > t_hi) continue;
        fig_box_add(&b, fig_picture(a, s->state.x_m, s->state.y_m), 0);
        fig_box_add(&b, fig_picture(a, s->cm_x_m, s->cm_y_m), 0);
        for (int k = 0; k < m->setup.body.part_count; ++k)
            if (fig_off_centre(&m->setup.body.parts[k]))
                fig_box_add(&b,
                            fig_body_point(m, &s->state, m->setup.body.parts[k].offset_m, m->setup.body.parts[k].angle_rad),
                            0);
    }
    if (!isfinite(b.lo_X)) fig_box_add(&b, fig_picture(a, 0, m->body.radius_m), m->body.radius_m * 100);
    return b;
}

/* A box grown by a small fraction of its size, so that no curve runs along the border. */
fig_Box fig_box_margin(fig_Box b)
{
    const double pad = 0.015 * fmax(fig_box_w(b), fig_box_h(b));
    return (fig_Box){b.lo_X - pad, b.hi_X + pad, b.lo_Y - pad, b.hi_Y + pad};
}

/* The close-up's box: CLOSEUP_GAPS gaps about the middle of the gap. */
fig_Box fig_closeup_box(const fig_Data *d, const jc_Sample *s)
{
    const double a = d->model->setup.incline_rad;
    const double half_cm = 100 * fmax(CLOSEUP_GAPS * s->gap_m, CLOSEUP_MIN_HALF_M);
    const fig_Pt low = fig_picture(a, s->state.x_m, s->state.y_m - d->model->body.radius_m);
    const fig_Pt foot = fig_picture(a, s->state.x_m, 0.0);
    const fig_Pt mid = {0.5 * (low.X + foot.X), 0.5 * (low.Y + foot.Y)};
    return (fig_Box){mid.X - half_cm, mid.X + half_cm, mid.Y - half_cm, mid.Y + half_cm};
}

/* The side panels (the whole ramp, the close-up) in the room the main
 * panel leaves: beside each other under it, or above each other beside it. */
void fig_side_frames(fig_Layout *l, int on_top, fig_Box ramp_box, fig_Box close_box)
{
    const fig_Box rest = on_top ? (fig_Box){0, FIG_PAGE_W_PX, 0, l->main.region.lo_Y}
                                : (fig_Box){l->main.region.hi_X, FIG_PAGE_W_PX, 0, FIG_PAGE_H_PX - FIG_PAGE_TITLE_PX};
    const double tr = fig_title_px(l->title_lines[1]), tc = fig_title_px(l->title_lines[2]);
    fig_Box rr = rest, rc = rest;
    if (!l->ramp_shown) {
        if (l->closeup_shown) l->closeup = fig_frame_in(rc, close_box, tc, FIG_MARGIN_B_PX, 1);
        return;
    }
    if (l->closeup_shown && on_top) {
        const double want = fig_box_w(ramp_box) * (fig_box_h(rest) - tr - FIG_MARGIN_B_PX) / fmax(fig_box_h(ramp_box), 1e-9);
        const double w = fmin(fmax(want + FIG_MARGIN_L_PX + FIG_MARGIN_R_PX, 0.35 * FIG_PAGE_W_PX), 0.65 * FIG_PAGE_W_PX);
        rr.hi_X = rc.lo_X = w;
    } else if (l->closeup_shown) {
        const double want =
            fig_box_h(ramp_box) * (fig_box_w(rest) - FIG_MARGIN_L_PX - FIG_MARGIN_R_PX) / fmax(fig_box_w(ramp_box), 1e-9);
        const double h = fmin(fmax(want + tr + FIG_MARGIN_B_PX, 0.35 * fig_box_h(rest)), 0.6 * fig_box_h(rest));
        rr.lo_Y = rc.hi_Y = rest.hi_Y - h;
    }
    l->ramp = fig_frame_in(rr, ramp_box, tr, FIG_MARGIN_B_PX, 0);
    if (l->closeup_shown) l->closeup = fig_frame_in(rc, close_box, tc, FIG_MARGIN_B_PX, 1);
}
