/* One animation frame drawn with cairo (geometry in draw.h). Everything is
 * drawn to scale in metres and converted to pixels by the view; only line
 * widths, markers and text are sized in pixels, relative to the frame. */
#include "films.h"

#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846
/* The camera shows this many rim radii across the frame's shorter side. */
#define VIEW_RADII 8.0
/* A force of M g is drawn this many units long (about a tenth of the frame's
 * shorter side), in both views; arrows are cut at FORCE_MAX_WEIGHTS M g
 * (impacts and sticking can ask for many times the weight) and then say
 * their value. */
#define FORCE_UNITS_PER_WEIGHT 40.0
#define FORCE_MAX_WEIGHTS 4.0
/* The inset (the whole ramp beside a camera that follows the body): its
 * share of the frame's width and at most of its height. */
#define INSET_W 0.34
#define INSET_H 0.5
/* Room under the incline's surface for the scale's labels, in units. */
#define SCALE_LABELS_UNITS 40.0

static void rgb_hex(cairo_t *cr, unsigned hex, double alpha)
{
    cairo_set_source_rgba(cr, ((hex >> 16) & 0xff) / 255.0, ((hex >> 8) & 0xff) / 255.0, (hex & 0xff) / 255.0, alpha);
}

enum {
    COL_INK = 0x222222, COL_RAMP = 0xeadfcb, COL_RAMP_EDGE = 0x6b4f2a, COL_RIM = 0x333333, COL_FACE = 0xf6f6f6,
    COL_DISC = 0xdce6ef, COL_HOOP = 0x555555, COL_ROD = 0xc8962e, COL_ROD_EDGE = 0x7a5a1a, COL_POINT = 0x6a3d9a,
    COL_TRACE = 0x0072b2, COL_NORMAL = 0x0072b2, COL_FRICTION = 0xd55e00, COL_GREY = 0x777777,
    COL_ROLLING = 0x009e73, COL_SLIDING = 0xe69f00, COL_FLIGHT = 0xd55e00,
    /* The marks along the incline (Okabe-Ito, apart from the forces' colours). */
    COL_PAPER = 0xcc79a7, COL_MODEL = 0x009e73, COL_MEASURED = 0x56b4e9
};

static void hex_rgb(unsigned hex, double rgb[3])
{
    rgb[0] = ((hex >> 16) & 0xff) / 255.0;
    rgb[1] = ((hex >> 8) & 0xff) / 255.0;
    rgb[2] = (hex & 0xff) / 255.0;
}

void draw_colour_rgb(draw_Colour c, double rgb[3])
{
    static const unsigned hex[] = {COL_PAPER, COL_MODEL, COL_MEASURED, COL_NORMAL, COL_FRICTION, COL_INK};
    hex_rgb(hex[c], rgb);
}

void draw_part_rgb(jc_PartKind kind, double rgb[3])
{
    const unsigned hex = kind == JC_PART_DISC ? COL_DISC : kind == JC_PART_HOOP ? COL_HOOP
                       : kind == JC_PART_ROD ? COL_ROD : COL_POINT;
    hex_rgb(hex, rgb);
}

void draw_picture(double a, double x, double y, double *X, double *Y)
{
    *X = x * cos(a) + y * sin(a);
    *Y = -x * sin(a) + y * cos(a);
}

void draw_to_pixel(const draw_View *v, double x, double y, double *px, double *py)
{
    double X, Y;
    draw_picture(v->incline_rad, x, y, &X, &Y);
    *px = 0.5 * v->width_px + v->scale_px_per_m * (X - v->center_X_m);
    *py = 0.5 * v->height_px - v->scale_px_per_m * (Y - v->center_Y_m);
}

void draw_body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad, double *x,
                     double *y)
{
    const double psi = s->theta_rad - m->body.cm_angle_rad + body_angle_rad;
    *x = s->x_m + offset_m * sin(psi);
    *y = s->y_m + offset_m * cos(psi);
}

/* Pixels per "unit" of line width and text: relative to the frame. */
static double frame_unit_px(int width_px, int height_px)
{
    const int shorter = width_px < height_px ? width_px : height_px;
    return fmax(shorter / 360.0, 0.5);
}

static double unit_px(const draw_View *v)
{
    return v->unit_px;
}

draw_View draw_view_follow(const jc_Model *m, int width_px, int height_px, const jc_State *s)
{
    draw_View v = {width_px, height_px, 0, 0, 0, m->setup.incline_rad, frame_unit_px(width_px, height_px)};
    const int shorter = width_px < height_px ? width_px : height_px;
    v.scale_px_per_m = shorter / (VIEW_RADII * m->body.radius_m);
    /* Follow the point the centre has while in contact, a little left of and
     * above the frame's centre: more of the ramp ahead is in view. */
    double X, Y;
    draw_picture(v.incline_rad, s->x_m, m->body.radius_m, &X, &Y);
    v.center_X_m = X + 0.08 * width_px / v.scale_px_per_m;
    v.center_Y_m = Y - 0.05 * height_px / v.scale_px_per_m;
    return v;
}

/* The legend (readouts, force scale, the marks' key) in the top right
 * corner: its lines' baselines in units from the top, and the box it keeps
 * to (its longest line is the arrows' key). */
#define HUD_BAR_UNITS 134.0
#define HUD_MARKS_UNITS 152.0
#define HUD_MARK_LINE_UNITS 13.0
#define HUD_WIDTH_UNITS 236.0
#define HUD_RIGHT_UNITS 10.0

static int mark_count(const draw_Marks *mk)
{
    return mk ? isfinite(mk->paper_x_m) + isfinite(mk->model_x_m) + isfinite(mk->measured_x_m) : 0;
}

/* The legend's box in pixels: x0, y0, x1, y1. */
static void legend_box(int width_px, double u, const draw_Marks *mk, double box[4])
{
    const int lines = mark_count(mk);
    box[0] = width_px - (HUD_RIGHT_UNITS + HUD_WIDTH_UNITS) * u;
    box[1] = 0;
    box[2] = width_px - HUD_RIGHT_UNITS * u;
    box[3] = (lines ? HUD_MARKS_UNITS + (lines - 1) * HUD_MARK_LINE_UNITS + 4 : HUD_BAR_UNITS + 6) * u;
}

void draw_legend_box(const draw_View *v, const draw_Marks *marks, double box[4])
{
    legend_box(v->width_px, v->unit_px, marks, box);
}

/* Margins of the fixed view, in units: the scale's labels and the normal
 * force (M g is 40 units long, its label beyond its tail) need room under
 * the incline. */
#define FIXED_MARGIN_SIDE 14.0
#define FIXED_MARGIN_TOP 14.0
#define FIXED_MARGIN_BOTTOM 60.0

/* Whether the convex polygon p (n corners) and the rectangle r (x0, y0, x1,
 * y1) overlap: no axis of either separates them. */
static int polygon_meets_rect(const double (*p)[2], int n, const double r[4])
{
    const double rc[4][2] = {{r[0], r[1]}, {r[2], r[1]}, {r[2], r[3]}, {r[0], r[3]}};
    for (int e = 0; e < n + 2; ++e) {
        /* The axes: x, y, and each edge's normal. */
        double ax = e == 0, ay = e == 1;
        if (e >= 2) {
            const double *a = p[e - 2], *b = p[(e - 1) % n];
            ax = b[1] - a[1], ay = a[0] - b[0];
        }
        double plo = INFINITY, phi = -INFINITY, rlo = INFINITY, rhi = -INFINITY;
        for (int i = 0; i < n; ++i) plo = fmin(plo, p[i][0] * ax + p[i][1] * ay), phi = fmax(phi, p[i][0] * ax + p[i][1] * ay);
        for (int i = 0; i < 4; ++i) rlo = fmin(rlo, rc[i][0] * ax + rc[i][1] * ay), rhi = fmax(rhi, rc[i][0] * ax + rc[i][1] * ay);
        if (phi <= rlo || rhi <= plo) return 0;
    }
    return 1;
}

/* The view that fits the picture box (X_lo..X_hi, Y_lo..Y_hi, m) into the
 * room (x0, y0, x1, y1 in pixels), at its top, centred or at its left. */
static draw_View fit_room(draw_View v, const double box[4], const double room[4], int at_left)
{
    const double room_w = fmax(room[2] - room[0], 1.0), room_h = fmax(room[3] - room[1], 1.0);
    v.scale_px_per_m = fmin(room_w / fmax(box[1] - box[0], 1e-9), room_h / fmax(box[3] - box[2], 1e-9));
    const double s = v.scale_px_per_m;
    v.center_X_m = at_left ? box[0] + (0.5 * v.width_px - room[0]) / s
                           : 0.5 * (box[0] + box[1]) - (0.5 * (room[0] + room[2]) - 0.5 * v.width_px) / s;
    v.center_Y_m = box[3] - (0.5 * v.height_px - room[1]) / s;
    return v;
}

/* The picture box of the incline's stretch x_lo..x_hi and the air above it
 * to y_top: X_lo, X_hi, Y_lo, Y_hi (m). */
static void picture_box(double a, double x_lo_m, double x_hi_m, double y_top_m, double box[4])
{
    const double xs[2] = {x_lo_m, x_hi_m}, ys[2] = {0.0, y_top_m};
    box[0] = box[2] = INFINITY;
    box[1] = box[3] = -INFINITY;
    for (int i = 0; i < 4; ++i) {
        double X, Y;
        draw_picture(a, xs[i % 2], ys[i / 2], &X, &Y);
        box[0] = fmin(box[0], X), box[1] = fmax(box[1], X);
        box[2] = fmin(box[2], Y), box[3] = fmax(box[3], Y);
    }
}

draw_View draw_view_fixed(const jc_Model *m, int width_px, int height_px, double x_lo_m, double x_hi_m,
                          double y_top_m, const draw_Marks *marks)
{
    const draw_View v0 = {width_px, height_px, 1, 0, 0, m->setup.incline_rad, frame_unit_px(width_px, height_px)};
    double box[4], legend[4];
    picture_box(v0.incline_rad, x_lo_m, x_hi_m, y_top_m, box);
    const double u = v0.unit_px, side = FIXED_MARGIN_SIDE * u, top = FIXED_MARGIN_TOP * u;
    const double bottom = height_px - FIXED_MARGIN_BOTTOM * u, right = width_px - side, gap = 6 * u;
    legend_box(width_px, u, marks, legend);
    const double keep[4] = {legend[0] - gap, legend[1], legend[2], legend[3] + gap};
    /* Rooms: the whole frame (where the legend is air on a descending
     * incline), the frame under the legend, the frame left of it. The
     * largest picture that keeps off the legend wins; the picture sits at
     * the room's top, leaving the room below for arrows and labels. */
    const double rooms[3][4] = {{side, top, right, bottom}, {side, keep[3], right, bottom}, {side, top, keep[0], bottom}};
    draw_View best = v0;
    best.scale_px_per_m = 0;
    for (int k = 0; k < 6; ++k) {
        const draw_View v = fit_room(v0, box, rooms[k / 2], k % 2);
        if (!(v.scale_px_per_m > best.scale_px_per_m * (1 + 1e-9))) continue;
        double corners[4][2];
        const double xs[4] = {x_lo_m, x_hi_m, x_hi_m, x_lo_m}, ys[4] = {0, 0, y_top_m, y_top_m};
        for (int i = 0; i < 4; ++i) draw_to_pixel(&v, xs[i], ys[i], &corners[i][0], &corners[i][1]);
        if (k < 2 && polygon_meets_rect((const double(*)[2])corners, 4, keep)) continue;
        best = v;
    }
    return best;
}

/* The overview's margins, in units: room for its title at the top; the
 * scale's labels go where they fit. */
#define OVERVIEW_SIDE 6.0
#define OVERVIEW_TOP 18.0

/* The stretch and air (picture box box) fitted into the inset, w x h. */
static draw_View overview_view(double incline_rad, const double box[4], double w, double h, double u)
{
    const draw_View v0 = {(int)w, (int)h, 1, 0, 0, incline_rad, u};
    const double room[4] = {OVERVIEW_SIDE * u, OVERVIEW_TOP * u, w - OVERVIEW_SIDE * u, h - OVERVIEW_SIDE * u};
    draw_View v = fit_room(v0, box, room, 0);
    /* Centred in height too. */
    v.center_Y_m = 0.5 * (box[2] + box[3]) - (0.5 * v.height_px - 0.5 * (room[1] + room[3])) / v.scale_px_per_m;
    return v;
}

/* The inset's top under the incline and its scale's labels where the box's
 * right edge is (the incline is highest there of the box's width), at most
 * INSET_H of the frame tall and at least 0.2 of it. */
static double inset_top(const draw_View *v, double x_px, double w_px, double bottom)
{
    const double u = unit_px(v), s = v->scale_px_per_m;
    const double X = v->center_X_m + (x_px + w_px - 0.5 * v->width_px) / s;
    const double surface_py = 0.5 * v->height_px - s * (-X * tan(v->incline_rad) - v->center_Y_m);
    const double top = fmax(surface_py + SCALE_LABELS_UNITS * u, bottom - INSET_H * v->height_px);
    return floor(fmin(top, bottom - 0.2 * v->height_px));
}

void draw_inset(const draw_View *v, double x_lo_m, double x_hi_m, double y_top_m, draw_View *overview,
                double *x_px, double *y_px)
{
    const double u = unit_px(v), bottom = v->height_px - 8 * u, margin = 2 * OVERVIEW_SIDE * u;
    double box[4];
    picture_box(v->incline_rad, x_lo_m, x_hi_m, y_top_m, box);
    const double aspect = (box[1] - box[0]) / fmax(box[3] - box[2], 1e-9);
    /* As wide as the whole stretch needs at the inset's height, at most
     * INSET_W of the frame: a narrower box reaches higher under a
     * descending incline. */
    *x_px = floor(8 * u);
    double w = floor(INSET_W * v->width_px), top = inset_top(v, *x_px, w, bottom);
    for (int k = 0; k < 3; ++k) {
        const double h = bottom - top;
        w = floor(fmin(INSET_W * v->width_px, fmax(0.5 * h, (h - OVERVIEW_TOP * u - OVERVIEW_SIDE * u) * aspect + margin)));
        top = inset_top(v, *x_px, w, bottom);
    }
    *y_px = top;
    *overview = overview_view(v->incline_rad, box, w, floor(bottom - top), u);
}

/* 1, 2 or 5 times a power of ten, the largest not above w (w > 0). */
static double round_down_125(double w)
{
    const double p = pow(10.0, floor(log10(w)));
    const double m = w / p;
    return p * (m >= 5 ? 5 : m >= 2 ? 2 : 1);
}

draw_ForceScale draw_force_scale(const draw_View *v, const jc_Model *m)
{
    const double u = unit_px(v), weight_N = m->body.mass_kg * m->setup.gravity_mps2;
    draw_ForceScale fs;
    fs.px_per_N = FORCE_UNITS_PER_WEIGHT * u / weight_N;
    fs.bar_N = round_down_125(weight_N);
    fs.bar_x_px = round(v->width_px - HUD_RIGHT_UNITS * u - fs.bar_N * fs.px_per_N);
    fs.bar_y_px = round(HUD_BAR_UNITS * u) + 0.5; /* a 1 px line on a pixel row */
    return fs;
}

static void move_to(cairo_t *cr, const draw_View *v, double x, double y)
{
    double px, py;
    draw_to_pixel(v, x, y, &px, &py);
    cairo_move_to(cr, px, py);
}

static void line_to(cairo_t *cr, const draw_View *v, double x, double y)
{
    double px, py;
    draw_to_pixel(v, x, y, &px, &py);
    cairo_line_to(cr, px, py);
}

static void circle(cairo_t *cr, const draw_View *v, double x, double y, double radius_px)
{
    double px, py;
    draw_to_pixel(v, x, y, &px, &py);
    cairo_new_sub_path(cr);
    cairo_arc(cr, px, py, radius_px, 0, 2 * PI);
}

/* ---- what was drawn where (draw_Layout) ---- */

/* A box in user coordinates (a translation of the frame's pixels: the inset),
 * recorded in the frame's pixels. */
static void layout_add(cairo_t *cr, draw_Layout *L, draw_BoxKind kind, double x0, double y0, double x1, double y1,
                       double width_px, const char *text)
{
    if (!L) return;
    if (L->count >= DRAW_LAYOUT_MAX) {
        L->dropped++;
        return;
    }
    cairo_user_to_device(cr, &x0, &y0);
    cairo_user_to_device(cr, &x1, &y1);
    draw_Box *b = &L->boxes[L->count++];
    const int is_arrow = kind == DRAW_BOX_ARROW;
    *b = (draw_Box){kind, L->panel_now, is_arrow ? x0 : fmin(x0, x1), is_arrow ? y0 : fmin(y0, y1),
                    is_arrow ? x1 : fmax(x0, x1), is_arrow ? y1 : fmax(y0, y1), width_px, ""};
    if (text) snprintf(b->text, sizeof b->text, "%s", text);
}

/* Text with its baseline starting at (x, y); its ink box is recorded. */
static void show_text(cairo_t *cr, draw_Layout *L, double x, double y, const char *s)
{
    cairo_text_extents_t te;
    cairo_text_extents(cr, s, &te);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s);
    layout_add(cr, L, DRAW_BOX_TEXT, x + te.x_bearing, y + te.y_bearing, x + te.x_bearing + te.width,
               y + te.y_bearing + te.height, 0, s);
}

/* Labels keep this far (px) from what they may not touch. */
#define CLEAR_PX 1.5

/* Whether a recorded box is in the way of what the panel being drawn adds:
 * the panel's own boxes, and for the frame the legend and the inset. */
static int in_the_way(const draw_Layout *L, const draw_Box *b)
{
    if (b->panel == L->panel_now) return 1;
    return L->panel_now == DRAW_PANEL_FRAME && (b->kind == DRAW_BOX_LEGEND || b->kind == DRAW_BOX_INSET);
}

static double point_rect_distance(double px, double py, const draw_Box *r)
{
    const double dx = fmax(fmax(r->x0 - px, px - r->x1), 0.0), dy = fmax(fmax(r->y0 - py, py - r->y1), 0.0);
    return hypot(dx, dy);
}

static double point_segment_distance(double px, double py, const draw_Box *a)
{
    const double dx = a->x1 - a->x0, dy = a->y1 - a->y0, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? fmin(fmax(((px - a->x0) * dx + (py - a->y0) * dy) / l2, 0.0), 1.0) : 0.0;
    return hypot(px - (a->x0 + t * dx), py - (a->y0 + t * dy));
}

/* Whether a label's rectangle (user coordinates) is free: inside the panel,
 * clear of every recorded box in the way. */
static int label_fits(cairo_t *cr, const draw_Layout *L, double x0, double y0, double x1, double y1)
{
    cairo_user_to_device(cr, &x0, &y0);
    cairo_user_to_device(cr, &x1, &y1);
    const draw_Box r = {DRAW_BOX_TEXT, L->panel_now, x0, y0, x1, y1, 0, ""};
    const double *pb = L->panel_box;
    if (x0 < pb[0] + CLEAR_PX || y0 < pb[1] + CLEAR_PX || x1 > pb[2] - CLEAR_PX || y1 > pb[3] - CLEAR_PX) return 0;
    for (int i = 0; i < L->count; ++i) {
        const draw_Box *b = &L->boxes[i];
        if (!in_the_way(L, b)) continue;
        if (b->kind == DRAW_BOX_BODY) {
            const double cx = 0.5 * (b->x0 + b->x1), cy = 0.5 * (b->y0 + b->y1);
            if (point_rect_distance(cx, cy, &r) < 0.5 * (b->x1 - b->x0) + CLEAR_PX) return 0;
        } else if (b->kind == DRAW_BOX_ARROW) {
            /* The nearest point of the arrow's centre line: sampled a pixel apart. */
            const int n = 1 + (int)hypot(b->x1 - b->x0, b->y1 - b->y0);
            for (int k = 0; k <= n; ++k) {
                const double t = (double)k / n;
                const double px = b->x0 + t * (b->x1 - b->x0), py = b->y0 + t * (b->y1 - b->y0);
                if (point_rect_distance(px, py, &r) < 0.5 * b->width_px + CLEAR_PX) return 0;
            }
        } else if (x0 < b->x1 + CLEAR_PX && b->x0 < x1 + CLEAR_PX && y0 < b->y1 + CLEAR_PX && b->y0 < y1 + CLEAR_PX) {
            return 0;
        }
    }
    return 1;
}

/* Whether an arrow (user coordinates, width_px across) is free: inside the
 * panel, clear of every rectangle in the way (it may meet the body and the
 * other arrow at the contact point). */
static int arrow_fits(cairo_t *cr, const draw_Layout *L, double x0, double y0, double x1, double y1, double width_px)
{
    cairo_user_to_device(cr, &x0, &y0);
    cairo_user_to_device(cr, &x1, &y1);
    const draw_Box a = {DRAW_BOX_ARROW, L->panel_now, x0, y0, x1, y1, width_px, ""};
    const double *pb = L->panel_box, pad = 0.5 * width_px + CLEAR_PX;
    if (fmin(x0, x1) < pb[0] + pad || fmin(y0, y1) < pb[1] + pad || fmax(x0, x1) > pb[2] - pad ||
        fmax(y0, y1) > pb[3] - pad)
        return 0;
    for (int i = 0; i < L->count; ++i) {
        const draw_Box *b = &L->boxes[i];
        if (!in_the_way(L, b) || b->kind == DRAW_BOX_BODY || b->kind == DRAW_BOX_ARROW) continue;
        const double corners[4][2] = {{b->x0, b->y0}, {b->x1, b->y0}, {b->x1, b->y1}, {b->x0, b->y1}};
        const int n = 1 + (int)hypot(x1 - x0, y1 - y0);
        for (int k = 0; k <= n; ++k) {
            const double t = (double)k / n;
            if (point_rect_distance(x0 + t * (x1 - x0), y0 + t * (y1 - y0), b) < pad) return 0;
        }
        for (int c = 0; c < 4; ++c)
            if (point_segment_distance(corners[c][0], corners[c][1], &a) < pad) return 0;
    }
    return 1;
}

/* ---- the incline ---- */

/* Incline x range that can be in view: the frame's diagonal around its centre. */
static void visible_x(const draw_View *v, double *lo, double *hi)
{
    const double a = v->incline_rad;
    const double xc = v->center_X_m * cos(a) - v->center_Y_m * sin(a); /* inverse rotation */
    const double half = hypot(v->width_px, v->height_px) / v->scale_px_per_m;
    *lo = xc - half;
    *hi = xc + half;
}

/* Major tick spacing (1 or 5 times a power of ten metres), labels at least
 * 60 units apart (40 in the small overview): 1 mm, 5 mm, 1 cm, 5 cm, 10 cm,
 * 50 cm, 1 m, ... */
static double major_spacing(const draw_Frame *f)
{
    const double apart = f->layout->panel_now == DRAW_PANEL_INSET ? 40 : 60;
    double step = 1e-3;
    for (int i = 0; i < 24 && step * f->view.scale_px_per_m < apart * unit_px(&f->view); ++i)
        step *= (i % 2 == 0) ? 5.0 : 2.0;
    return step;
}

static void draw_ramp_body(cairo_t *cr, const draw_View *v, double x0, double x1)
{
    /* The ramp is the region under its surface, cut vertically at its ends. */
    const double depth = 3.0 * (v->width_px + v->height_px) / v->scale_px_per_m;
    const double a = v->incline_rad;
    move_to(cr, v, x0, 0);
    line_to(cr, v, x1, 0);
    /* (sin a, -cos a) in incline coordinates is straight down in the picture. */
    line_to(cr, v, x1 + depth * sin(a), -depth * cos(a));
    line_to(cr, v, x0 + depth * sin(a), -depth * cos(a));
    cairo_close_path(cr);
    rgb_hex(cr, COL_RAMP, 1);
    cairo_fill(cr);
    move_to(cr, v, x0, 0);
    line_to(cr, v, x1, 0);
    rgb_hex(cr, COL_RAMP_EDGE, 1);
    cairo_set_line_width(cr, 2.5 * unit_px(v));
    cairo_stroke(cr);
}

/* The scale's ticks along the incline, every minor spacing. */
static void draw_ticks(cairo_t *cr, const draw_Frame *f, double x0, double x1)
{
    const draw_View *v = &f->view;
    const double u = unit_px(v), s = v->scale_px_per_m, minor = major_spacing(f) / 5;
    cairo_set_line_width(cr, 1.2 * u);
    rgb_hex(cr, COL_RAMP_EDGE, 1);
    for (double k = ceil(x0 / minor); k * minor <= x1; k += 1) {
        const int is_major = fmod(fabs(k), 5.0) == 0.0;
        move_to(cr, v, k * minor, 0);
        line_to(cr, v, k * minor, -(is_major ? 12 : 6) * u / s);
        cairo_stroke(cr);
    }
}

/* The incline's stretch in view: from a little above the start position
 * (the run ends if the centre goes uphill past it) to its lower end. */
static int incline_in_view(const draw_Frame *f, double *x0, double *x1)
{
    double lo, hi;
    visible_x(&f->view, &lo, &hi);
    *x0 = fmax(lo, -2 * f->model->body.radius_m);
    *x1 = fmin(hi, f->model->setup.ramp_length_m);
    return *x1 > *x0;
}

/* The scale's labels at the major ticks, under the surface: drawn last in
 * their panel, each where it is whole and clear of what is drawn (a force's
 * arrow or label, the body, the legend, the inset), left out elsewhere. */
static void draw_scale_labels(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    double x0, x1;
    if (!incline_in_view(f, &x0, &x1)) return;
    const double u = unit_px(v), s = v->scale_px_per_m, major = major_spacing(f);
    cairo_set_font_size(cr, 10 * u);
    rgb_hex(cr, COL_RAMP_EDGE, 1);
    for (double k = ceil(fmax(x0, 0.0) / major); k * major <= x1; k += 1) {
        char label[32];
        snprintf(label, sizeof label, "%g cm", round(k * major * 1e5) / 1e3);
        cairo_text_extents_t te;
        cairo_text_extents(cr, label, &te);
        double px, py;
        draw_to_pixel(v, k * major, -26 * u / s, &px, &py);
        const double left = px - te.width / 2, top = py - te.height / 2;
        if (!label_fits(cr, f->layout, left, top, left + te.width, top + te.height)) continue;
        show_text(cr, f->layout, left - te.x_bearing, top - te.y_bearing, label);
    }
}

/* A mark: a short line across the surface in its colour (the legend names it). */
static void draw_mark(cairo_t *cr, const draw_View *v, double x, unsigned colour)
{
    if (!isfinite(x)) return;
    const double u = unit_px(v), s = v->scale_px_per_m;
    move_to(cr, v, x, 8 * u / s);
    line_to(cr, v, x, -8 * u / s);
    rgb_hex(cr, colour, 1);
    cairo_set_line_width(cr, 2 * u);
    cairo_stroke(cr);
}

/* The measured band: a thick stripe just under the surface. */
static void draw_band(cairo_t *cr, const draw_View *v, double x, double err)
{
    if (!isfinite(x) || !isfinite(err)) return;
    const double u = unit_px(v), s = v->scale_px_per_m;
    move_to(cr, v, x - err, -3.5 * u / s);
    line_to(cr, v, x + err, -3.5 * u / s);
    rgb_hex(cr, COL_MEASURED, 1);
    cairo_set_line_width(cr, 7 * u);
    cairo_stroke(cr);
}

static void draw_marks(cairo_t *cr, const draw_View *v, const draw_Marks *mk)
{
    if (!mk) return;
    draw_band(cr, v, mk->measured_x_m, mk->measured_error_m);
    draw_mark(cr, v, mk->measured_x_m, COL_MEASURED);
    draw_mark(cr, v, mk->model_x_m, COL_MODEL);
    draw_mark(cr, v, mk->paper_x_m, COL_PAPER);
}

static void draw_incline(cairo_t *cr, const draw_Frame *f)
{
    double x0, x1;
    if (!incline_in_view(f, &x0, &x1)) return;
    draw_ramp_body(cr, &f->view, x0, x1);
    draw_ticks(cr, f, x0, x1);
    draw_marks(cr, &f->view, f->marks);
}

/* ---- the trace of the centre ---- */

/* The whole path so far, thin and light: hops stand out against the incline. */
static void draw_path(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    if (!f->path || f->path_count < 2) return;
    move_to(cr, v, f->path[0].x_m, f->path[0].y_m);
    for (int i = 1; i < f->path_count; ++i) line_to(cr, v, f->path[i].x_m, f->path[i].y_m);
    line_to(cr, v, f->sample->state.x_m, f->sample->state.y_m);
    rgb_hex(cr, COL_TRACE, 0.45);
    cairo_set_line_width(cr, 1.3 * unit_px(v));
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke(cr);
}

static void draw_trace(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    const double now = f->sample->state.t_s, fade = f->trace_fade_s > 0 ? f->trace_fade_s : 1.0;
    cairo_set_line_width(cr, 2 * unit_px(v));
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int i = 1; i < f->trace_count; ++i) {
        const draw_TracePoint *p = &f->trace[i - 1], *q = &f->trace[i];
        const double age = now - 0.5 * (p->t_s + q->t_s);
        if (age > fade || age < 0) continue;
        rgb_hex(cr, COL_TRACE, 0.85 * (1.0 - age / fade));
        move_to(cr, v, p->x_m, p->y_m);
        line_to(cr, v, q->x_m, q->y_m);
        cairo_stroke(cr);
    }
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
}

/* ---- the body ---- */

static void draw_parts_of(cairo_t *cr, const draw_Frame *f, jc_PartKind kind)
{
    const draw_View *v = &f->view;
    const jc_BodyDef *b = &f->model->setup.body;
    const double u = unit_px(v);
    for (int i = 0; i < b->part_count; ++i) {
        const jc_Part *p = &b->parts[i];
        if (p->kind != kind) continue;
        double x, y;
        draw_body_point(f->model, &f->sample->state, p->offset_m, p->angle_rad, &x, &y);
        const double rad_px = p->radius_m * v->scale_px_per_m;
        if (kind == JC_PART_HOOP) {
            circle(cr, v, x, y, rad_px);
            rgb_hex(cr, COL_HOOP, 1);
            cairo_set_line_width(cr, 3 * u);
            cairo_stroke(cr);
            continue;
        }
        /* Rods and points are never smaller than a visible dot. */
        circle(cr, v, x, y, kind == JC_PART_DISC ? rad_px : fmax(rad_px, 3.5 * u));
        rgb_hex(cr, kind == JC_PART_DISC ? COL_DISC : kind == JC_PART_ROD ? COL_ROD : COL_POINT, 1);
        if (kind == JC_PART_DISC) {
            cairo_fill(cr);
            continue;
        }
        cairo_fill_preserve(cr);
        rgb_hex(cr, kind == JC_PART_ROD ? COL_ROD_EDGE : COL_INK, 1);
        cairo_set_line_width(cr, 1.0 * u);
        cairo_stroke(cr);
    }
}

/* The usual centre-of-mass symbol: a circle with two opposite black quarters. */
static void draw_cm(cairo_t *cr, const draw_Frame *f)
{
    const jc_Model *m = f->model;
    double x, y, px, py;
    draw_body_point(m, &f->sample->state, m->body.cm_offset_m, m->body.cm_angle_rad, &x, &y);
    draw_to_pixel(&f->view, x, y, &px, &py);
    /* Never more than a third of the rim: on a whole-ramp view the body is small. */
    const double r = fmin(6 * unit_px(&f->view), m->body.radius_m * f->view.scale_px_per_m / 3);
    cairo_arc(cr, px, py, r, 0, 2 * PI);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_fill(cr);
    for (int q = 0; q < 2; ++q) {
        cairo_move_to(cr, px, py);
        cairo_arc(cr, px, py, r, q * PI, q * PI + PI / 2);
        cairo_close_path(cr);
    }
    rgb_hex(cr, COL_INK, 1);
    cairo_fill(cr);
    cairo_arc(cr, px, py, r, 0, 2 * PI);
    cairo_set_line_width(cr, 1.2 * unit_px(&f->view));
    cairo_stroke(cr);
}

static void draw_body(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    const jc_State *s = &f->sample->state;
    const double r = f->model->body.radius_m, u = unit_px(v);
    circle(cr, v, s->x_m, s->y_m, r * v->scale_px_per_m);
    rgb_hex(cr, COL_FACE, 1);
    cairo_fill(cr);
    draw_parts_of(cr, f, JC_PART_DISC);
    /* A radius along the body's reference direction shows the rotation. */
    double x, y;
    draw_body_point(f->model, s, r, 0.0, &x, &y);
    move_to(cr, v, s->x_m, s->y_m);
    line_to(cr, v, x, y);
    rgb_hex(cr, COL_RIM, 1);
    cairo_set_line_width(cr, 2 * u);
    cairo_stroke(cr);
    draw_parts_of(cr, f, JC_PART_HOOP);
    circle(cr, v, s->x_m, s->y_m, r * v->scale_px_per_m);
    rgb_hex(cr, COL_RIM, 1);
    cairo_set_line_width(cr, 2.5 * u);
    cairo_stroke(cr);
    draw_parts_of(cr, f, JC_PART_ROD);
    draw_parts_of(cr, f, JC_PART_POINT);
    double cx, cy;
    const double rim_px = r * v->scale_px_per_m + 1.25 * u;
    draw_to_pixel(v, s->x_m, s->y_m, &cx, &cy);
    layout_add(cr, f->layout, DRAW_BOX_BODY, cx - rim_px, cy - rim_px, cx + rim_px, cy + rim_px, 0, NULL);
    circle(cr, v, s->x_m, s->y_m, 2.5 * u); /* the axis C */
    rgb_hex(cr, COL_RIM, 1);
    cairo_fill(cr);
    draw_cm(cr, f);
}

/* ---- contact and forces ---- */

static void arrow(cairo_t *cr, draw_Layout *L, double x0, double y0, double x1, double y1, double u)
{
    const double len = hypot(x1 - x0, y1 - y0);
    if (len < 2) return;
    const double ux = (x1 - x0) / len, uy = (y1 - y0) / len, head = fmin(10 * u, 0.6 * len);
    layout_add(cr, L, DRAW_BOX_ARROW, x0, y0, x1, y1, 0.9 * head, NULL);
    cairo_set_line_width(cr, 3 * u);
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1 - ux * head * 0.8, y1 - uy * head * 0.8);
    cairo_stroke(cr);
    cairo_move_to(cr, x1, y1);
    cairo_line_to(cr, x1 - ux * head - uy * head * 0.45, y1 - uy * head + ux * head * 0.45);
    cairo_line_to(cr, x1 - ux * head + uy * head * 0.45, y1 - uy * head - ux * head * 0.45);
    cairo_close_path(cr);
    cairo_fill(cr);
}

/* An arrow's name: its text, extents and where it goes (the rectangle's
 * top left), beyond the tail and lifted off the incline's surface. */
typedef struct {
    char text[48];
    cairo_text_extents_t te;
    double left, top;
} force_Label;

static void force_label(cairo_t *cr, const draw_View *v, force_Label *lb, double px0, double py0, double dx,
                        double dy, int along_surface)
{
    const double u = unit_px(v), a = v->incline_rad;
    cairo_text_extents(cr, lb->text, &lb->te);
    const double lift = along_surface ? 10 * u : 0.0, gap = 9 * u + 0.5 * fabs(lb->te.width * dx);
    const double cx = px0 - gap * dx + lift * sin(a), cy = py0 - gap * dy - lift * cos(a);
    lb->left = cx - lb->te.width / 2;
    lb->top = cy - lb->te.height / 2;
}

/* The force (fx along the incline, fy along its normal) acting at the
 * contact point, drawn at the frame's px_per_N as an arrow that ends there
 * (the body stays in view). Past FORCE_MAX_WEIGHTS M g, or where its full
 * length would run off the panel or into a label, the legend or the inset,
 * it is cut, and its label gives its value. */
static void force_arrow(cairo_t *cr, const draw_Frame *f, double fx, double fy, unsigned colour, const char *name)
{
    const draw_View *v = &f->view;
    const jc_Model *m = f->model;
    const double force_N = hypot(fx, fy), a = v->incline_rad, u = unit_px(v);
    if (!(force_N > 0)) return;
    const draw_ForceScale fs = draw_force_scale(v, m);
    const double cap_N = FORCE_MAX_WEIGHTS * m->body.mass_kg * m->setup.gravity_mps2;
    const double full = force_N * fs.px_per_N, want = fmin(force_N, cap_N) * fs.px_per_N;
    /* The force's direction in pixels (picture Y up, pixel y down). */
    const double dx = (fx * cos(a) + fy * sin(a)) / force_N, dy = -(-fx * sin(a) + fy * cos(a)) / force_N;
    double px1, py1;
    draw_to_pixel(v, f->sample->state.x_m, 0, &px1, &py1);
    cairo_set_font_size(cr, 13 * u);
    /* The longest arrow up to want that fits with its label; a short one
     * (under 8 units) has no label. */
    const double step = fmax(0.5 * u, want / 64);
    for (double len = want; len >= 2; len -= step) {
        const double px0 = px1 - len * dx, py0 = py1 - len * dy;
        if (!arrow_fits(cr, f->layout, px0, py0, px1, py1, 9 * u)) continue;
        force_Label lb;
        if (len < full * (1 - 1e-9)) snprintf(lb.text, sizeof lb.text, "%s %.3g N", name, force_N);
        else snprintf(lb.text, sizeof lb.text, "%s", name);
        force_label(cr, v, &lb, px0, py0, dx, dy, fy == 0.0);
        const int labelled = len >= 8 * u;
        if (labelled && !label_fits(cr, f->layout, lb.left, lb.top, lb.left + lb.te.width, lb.top + lb.te.height))
            continue;
        rgb_hex(cr, colour, 1);
        arrow(cr, f->layout, px0, py0, px1, py1, u);
        if (labelled) show_text(cr, f->layout, lb.left - lb.te.x_bearing, lb.top - lb.te.y_bearing, lb.text);
        return;
    }
}

static void draw_contact(cairo_t *cr, const draw_Frame *f)
{
    const jc_Sample *p = f->sample;
    if (p->mode == JC_MODE_FLIGHT) return;
    force_arrow(cr, f, 0.0, p->normal_N, COL_NORMAL, "N");
    force_arrow(cr, f, p->friction_N, 0.0, COL_FRICTION, "F");
    circle(cr, &f->view, p->state.x_m, 0.0, 3.5 * unit_px(&f->view));
    rgb_hex(cr, COL_INK, 1);
    cairo_fill(cr);
}

/* ---- readouts, legend, force scale ---- */

/* Right-aligned text at (right, baseline). */
static void text_right(cairo_t *cr, draw_Layout *L, const char *s, double right, double baseline)
{
    cairo_text_extents_t te;
    cairo_text_extents(cr, s, &te);
    show_text(cr, L, right - te.x_advance, baseline, s);
}

static void draw_mode_badge(cairo_t *cr, const draw_Frame *f, double right, double top, double u)
{
    const jc_Mode mode = f->sample->mode;
    const char *name = jc_mode_name(mode);
    cairo_set_font_size(cr, 13 * u);
    cairo_text_extents_t te;
    cairo_text_extents(cr, name, &te);
    const double w = te.x_advance + 14 * u, h = 18 * u;
    rgb_hex(cr, mode == JC_MODE_ROLLING ? COL_ROLLING : mode == JC_MODE_SLIDING ? COL_SLIDING : COL_FLIGHT, 1);
    cairo_rectangle(cr, right - w, top, w, h);
    cairo_fill(cr);
    layout_add(cr, f->layout, DRAW_BOX_TEXT, right - w, top, right, top + h, 0, name);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_move_to(cr, right - w + 7 * u, top + 13.5 * u);
    cairo_show_text(cr, name);
}

/* t, x, theta, omega, N, |F|/N, one line each, right-aligned. */
static void draw_readouts(cairo_t *cr, const draw_Frame *f, double right, double u)
{
    const jc_Sample *p = f->sample;
    const jc_State *s = &p->state;
    char line[96];
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, 17 * u);
    rgb_hex(cr, COL_INK, 1);
    snprintf(line, sizeof line, "t = %.3f s", s->t_s);
    text_right(cr, f->layout, line, right, 22 * u);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 11 * u);
    rgb_hex(cr, COL_GREY, 1);
    if (f->slowmo > 0 && f->slowmo != 1) snprintf(line, sizeof line, "slow motion \xc3\x97%g", f->slowmo);
    else snprintf(line, sizeof line, "real time");
    text_right(cr, f->layout, line, right, 36 * u);
    rgb_hex(cr, COL_INK, 1);
    snprintf(line, sizeof line, "x = %.1f cm on %.4g\xc2\xb0", s->x_m * 100, f->model->setup.incline_rad * 180 / PI);
    text_right(cr, f->layout, line, right, 51 * u);
    snprintf(line, sizeof line, "\xce\xb8 = %.0f\xc2\xb0   \xcf\x89 = %.1f rad/s", s->theta_rad * 180 / PI, s->omega_radps);
    text_right(cr, f->layout, line, right, 65 * u);
    if (p->mode == JC_MODE_FLIGHT) snprintf(line, sizeof line, "N = 0 N   |F|/N: none");
    else if (p->normal_N > 0)
        snprintf(line, sizeof line, "N = %.3f N   |F|/N = %.3f", p->normal_N, fabs(p->friction_N) / p->normal_N);
    else snprintf(line, sizeof line, "N = %.3f N", p->normal_N);
    text_right(cr, f->layout, line, right, 79 * u);
    draw_mode_badge(cr, f, right, 85 * u, u);
}

static void draw_force_bar(cairo_t *cr, const draw_Frame *f, double u)
{
    const draw_ForceScale fs = draw_force_scale(&f->view, f->model);
    const double len = fs.bar_N * fs.px_per_N;
    rgb_hex(cr, COL_INK, 1);
    cairo_rectangle(cr, fs.bar_x_px, fs.bar_y_px - 1.5 * u, len, 3 * u);
    cairo_fill(cr);
    cairo_set_line_width(cr, 1.2 * u);
    for (int e = 0; e < 2; ++e) { /* end ticks */
        cairo_move_to(cr, fs.bar_x_px + e * len, fs.bar_y_px - 5 * u);
        cairo_line_to(cr, fs.bar_x_px + e * len, fs.bar_y_px + 5 * u);
        cairo_stroke(cr);
    }
    char label[64];
    snprintf(label, sizeof label, "forces: %g N", fs.bar_N);
    cairo_set_font_size(cr, 11 * u);
    text_right(cr, f->layout, label, fs.bar_x_px - 6 * u, fs.bar_y_px + 4 * u);
}

/* The marks' key under the force scale: a swatch of each mark's colour and
 * what it marks, right-aligned. */
static void draw_marks_key(cairo_t *cr, const draw_Frame *f, double right, double u)
{
    const draw_Marks *mk = f->marks;
    if (!mk) return;
    const struct {
        double x_m;
        unsigned colour;
        const char *what;
    } keys[3] = {{mk->paper_x_m, COL_PAPER, "paper"}, {mk->model_x_m, COL_MODEL, "model"},
                 {mk->measured_x_m, COL_MEASURED, "measured"}};
    double baseline = HUD_MARKS_UNITS * u;
    cairo_set_font_size(cr, 10 * u);
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(keys[i].x_m)) continue;
        char line[64];
        if (i == 2 && isfinite(mk->measured_error_m))
            snprintf(line, sizeof line, "%s %.1f \xc2\xb1 %.1f cm", keys[i].what, keys[i].x_m * 100,
                     mk->measured_error_m * 100);
        else snprintf(line, sizeof line, "%s %.1f cm", keys[i].what, keys[i].x_m * 100);
        cairo_text_extents_t te;
        cairo_text_extents(cr, line, &te);
        rgb_hex(cr, COL_INK, 1);
        text_right(cr, f->layout, line, right, baseline);
        const double x1 = right - te.x_advance - 5 * u, x0 = x1 - 14 * u, y = baseline - 3.5 * u;
        rgb_hex(cr, keys[i].colour, 1);
        cairo_rectangle(cr, x0, y - 2 * u, x1 - x0, 4 * u);
        cairo_fill(cr);
        layout_add(cr, f->layout, DRAW_BOX_TEXT, x0, y - 2 * u, x1, y + 2 * u, 0, "(swatch)");
        baseline += HUD_MARK_LINE_UNITS * u;
    }
}

/* The legend's box: everything drawn in it. */
static void record_legend(cairo_t *cr, draw_Layout *L, int first, const draw_Frame *f)
{
    const draw_ForceScale fs = draw_force_scale(&f->view, f->model);
    const double u = unit_px(&f->view);
    double x0 = fs.bar_x_px, y0 = fs.bar_y_px - 5 * u, x1 = fs.bar_x_px + fs.bar_N * fs.px_per_N, y1 = fs.bar_y_px + 5 * u;
    for (int i = first; i < L->count; ++i) {
        x0 = fmin(x0, L->boxes[i].x0), y0 = fmin(y0, L->boxes[i].y0);
        x1 = fmax(x1, L->boxes[i].x1), y1 = fmax(y1, L->boxes[i].y1);
    }
    layout_add(cr, L, DRAW_BOX_LEGEND, x0, y0, x1, y1, 0, NULL);
}

static void draw_hud(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    const double u = unit_px(v), right = v->width_px - HUD_RIGHT_UNITS * u;
    const int first = f->layout->count;
    f->layout->panel_now = DRAW_PANEL_LEGEND;
    draw_readouts(cr, f, right, u);
    cairo_set_font_size(cr, 10 * u);
    rgb_hex(cr, COL_GREY, 1);
    text_right(cr, f->layout, "arrows: N (blue), F (orange)  \xe2\x97\x90 centre of mass", right, 117 * u);
    draw_force_bar(cr, f, u);
    draw_marks_key(cr, f, right, u);
    f->layout->panel_now = DRAW_PANEL_FRAME;
    record_legend(cr, f->layout, first, f);
}

/* ---- the frame ---- */

/* Everything that lives in the incline's coordinates, in f's view; the
 * scale's labels come last, where they are clear. */
static void draw_scene(cairo_t *cr, const draw_Frame *f, int forces)
{
    draw_incline(cr, f);
    draw_path(cr, f);
    draw_trace(cr, f);
    draw_body(cr, f);
    if (forces) draw_contact(cr, f);
    draw_scale_labels(cr, f);
}

/* The main view's field in the overview: a thin grey frame. */
static void draw_field(cairo_t *cr, const draw_View *main, const draw_View *over)
{
    const double s = main->scale_px_per_m, so = over->scale_px_per_m;
    const double X0 = main->center_X_m - 0.5 * main->width_px / s, X1 = main->center_X_m + 0.5 * main->width_px / s;
    const double Y0 = main->center_Y_m - 0.5 * main->height_px / s, Y1 = main->center_Y_m + 0.5 * main->height_px / s;
    const double px0 = 0.5 * over->width_px + so * (X0 - over->center_X_m);
    const double py0 = 0.5 * over->height_px - so * (Y1 - over->center_Y_m);
    cairo_rectangle(cr, px0, py0, so * (X1 - X0), so * (Y1 - Y0));
    rgb_hex(cr, COL_GREY, 1);
    cairo_set_line_width(cr, 1.0 * unit_px(main));
    cairo_stroke(cr);
}

/* The whole ramp in the inset (bottom left, under the incline, which
 * descends to the right): the body where it is on it, the marks, the path,
 * and the main view's field; no forces (they are drawn at one scale for
 * the frame, too large here). */
static void draw_overview(cairo_t *cr, const draw_Frame *f, double x, double y, double w, double h)
{
    const double u = unit_px(&f->view);
    draw_Frame g = *f;
    g.view = f->overview;
    draw_Layout *L = f->layout;
    L->panel_now = DRAW_PANEL_INSET;
    const double frame_box[4] = {L->panel_box[0], L->panel_box[1], L->panel_box[2], L->panel_box[3]};
    L->panel_box[0] = x, L->panel_box[1] = y, L->panel_box[2] = x + w, L->panel_box[3] = y + h;
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rectangle(cr, 0, 0, w, h);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_font_size(cr, 11 * u);
    rgb_hex(cr, COL_INK, 1);
    show_text(cr, L, 6 * u, 14 * u, "whole ramp");
    draw_scene(cr, &g, 0);
    draw_field(cr, &f->view, &g.view);
    cairo_restore(cr);
    L->panel_now = DRAW_PANEL_FRAME;
    for (int i = 0; i < 4; ++i) L->panel_box[i] = frame_box[i];
    cairo_rectangle(cr, x, y, w, h);
    rgb_hex(cr, COL_INK, 1);
    cairo_set_line_width(cr, 1.5 * u);
    cairo_stroke(cr);
}

void draw_frame(cairo_t *cr, const draw_Frame *frame)
{
    /* The boxes are always kept (labels and arrows give way to what is
     * drawn); the caller sees them when it asked. */
    draw_Layout local, scratch;
    draw_Frame g = *frame;
    if (!g.layout) g.layout = &local;
    draw_Layout *L = g.layout;
    L->count = L->dropped = 0;
    L->panel_now = DRAW_PANEL_FRAME;
    L->panel_box[0] = L->panel_box[1] = 0;
    L->panel_box[2] = g.view.width_px, L->panel_box[3] = g.view.height_px;
    const draw_Frame *f = &g;
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    /* The legend and the inset first measured, so that the scene keeps off
     * them; the legend is drawn last, over everything. */
    cairo_push_group(cr);
    draw_hud(cr, f);
    cairo_pattern_destroy(cairo_pop_group(cr));
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    double x, y, w, h;
    const int inset = f->overview.width_px > 0;
    if (inset) {
        x = f->inset_x_px, y = f->inset_y_px, w = f->overview.width_px, h = f->overview.height_px;
        layout_add(cr, L, DRAW_BOX_INSET, x, y, x + w, y + h, 0, NULL);
    }
    draw_scene(cr, f, 1);
    if (inset) draw_overview(cr, f, x, y, w, h);
    g.layout = &scratch;
    scratch = *L;
    draw_hud(cr, f);
    cairo_restore(cr);
}
