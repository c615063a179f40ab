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
/* The zoom box: its share of the frame's width and height, and the rim
 * radii across its shorter side. */
#define ZOOM_BOX_W 0.34
#define ZOOM_BOX_H 0.42
#define ZOOM_RADII 6.0
#define ZOOM_MIN 2.5
/* ... shown only when the whole view draws the rim smaller than this many units. */
#define ZOOM_BELOW_UNITS 30.0

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
    return draw_view_zoom(m, width_px, height_px, s, VIEW_RADII, frame_unit_px(width_px, height_px));
}

draw_View draw_view_zoom(const jc_Model *m, int width_px, int height_px, const jc_State *s, double radii,
                         double unit)
{
    draw_View v = {width_px, height_px, 0, 0, 0, m->setup.incline_rad, unit};
    const int shorter = width_px < height_px ? width_px : height_px;
    v.scale_px_per_m = shorter / (radii * m->body.radius_m);
    /* Follow the point the centre has while in contact, a little left of and
     * above the frame's centre: more of the ramp ahead is in view. */
    double X, Y;
    draw_picture(v.incline_rad, s->x_m, m->body.radius_m, &X, &Y);
    v.center_X_m = X + 0.08 * width_px / v.scale_px_per_m;
    v.center_Y_m = Y - 0.05 * height_px / v.scale_px_per_m;
    return v;
}

/* Margins of the fixed view, in units: the readouts' column keeps clear of
 * nothing (the incline descends to the right, so the top right corner is
 * air), the scale's labels need room under the incline's lower end. */
#define FIXED_MARGIN_SIDE 14.0
#define FIXED_MARGIN_TOP 14.0
#define FIXED_MARGIN_BOTTOM 40.0

draw_View draw_view_fixed(const jc_Model *m, int width_px, int height_px, double x_lo_m, double x_hi_m,
                          double y_top_m)
{
    draw_View v = {width_px, height_px, 1, 0, 0, m->setup.incline_rad, frame_unit_px(width_px, height_px)};
    const double xs[2] = {x_lo_m, x_hi_m}, ys[2] = {0.0, y_top_m};
    double X_lo = INFINITY, X_hi = -INFINITY, Y_lo = INFINITY, Y_hi = -INFINITY;
    for (int i = 0; i < 4; ++i) {
        double X, Y;
        draw_picture(v.incline_rad, xs[i % 2], ys[i / 2], &X, &Y);
        X_lo = fmin(X_lo, X);
        X_hi = fmax(X_hi, X);
        Y_lo = fmin(Y_lo, Y);
        Y_hi = fmax(Y_hi, Y);
    }
    const double u = v.unit_px, side = FIXED_MARGIN_SIDE * u, top = FIXED_MARGIN_TOP * u;
    const double bottom = FIXED_MARGIN_BOTTOM * u;
    const double room_w = fmax(width_px - 2 * side, 1.0), room_h = fmax(height_px - top - bottom, 1.0);
    v.scale_px_per_m = fmin(room_w / fmax(X_hi - X_lo, 1e-9), room_h / fmax(Y_hi - Y_lo, 1e-9));
    /* The box's middle goes to the middle of the room left by the margins. */
    v.center_X_m = 0.5 * (X_lo + X_hi);
    v.center_Y_m = 0.5 * (Y_lo + Y_hi) - 0.5 * (bottom - top) / v.scale_px_per_m;
    return v;
}

/* How far under the incline's surface the marks' labels reach, in units. */
#define MARK_LABELS_UNITS 80.0

void draw_inset_rect(const draw_View *v, double *x_px, double *y_px, double *w_px, double *h_px)
{
    const double u = unit_px(v), s = v->scale_px_per_m, bottom = v->height_px - 8 * u;
    *w_px = floor(ZOOM_BOX_W * v->width_px);
    *x_px = floor(8 * u);
    /* Under the incline and its marks' labels where the box's right edge is
     * (the incline is highest there of the box's width), at least 0.2 H tall. */
    const double X = v->center_X_m + (*x_px + *w_px - 0.5 * v->width_px) / s;
    const double surface_py = 0.5 * v->height_px - s * (-X * tan(v->incline_rad) - v->center_Y_m);
    const double top = fmax(surface_py + MARK_LABELS_UNITS * u, bottom - ZOOM_BOX_H * v->height_px);
    *y_px = floor(fmin(top, bottom - 0.2 * v->height_px));
    *h_px = floor(bottom - *y_px);
}

/* 1, 2 or 5 times a power of ten, the largest not above w (w > 0). */
static double round_down_125(double w)
{
    const double p = pow(10.0, floor(log10(w)));
    const double m = w / p;
    return p * (m >= 5 ? 5 : m >= 2 ? 2 : 1);
}

/* The readouts' column ends this many units from the top; the scale bar sits there. */
#define HUD_BAR_UNITS 134.0

draw_ForceScale draw_force_scale(const draw_View *v, const jc_Model *m)
{
    const double u = unit_px(v), weight_N = m->body.mass_kg * m->setup.gravity_mps2;
    draw_ForceScale fs;
    fs.px_per_N = FORCE_UNITS_PER_WEIGHT * u / weight_N;
    fs.bar_N = round_down_125(weight_N);
    fs.bar_x_px = round(v->width_px - 10 * u - fs.bar_N * fs.px_per_N);
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
 * 60 px apart: 1 mm, 5 mm, 1 cm, 5 cm, 10 cm, 50 cm, 1 m, ... */
static double major_spacing(const draw_View *v)
{
    double step = 1e-3;
    for (int i = 0; i < 24 && step * v->scale_px_per_m < 60 * unit_px(v); ++i) step *= (i % 2 == 0) ? 5.0 : 2.0;
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

static void draw_scale(cairo_t *cr, const draw_View *v, draw_Layout *L, double x0, double x1)
{
    const double u = unit_px(v), s = v->scale_px_per_m, major = major_spacing(v), minor = major / 5;
    cairo_set_line_width(cr, 1.2 * u);
    cairo_set_font_size(cr, 10 * u);
    rgb_hex(cr, COL_RAMP_EDGE, 1);
    for (double k = ceil(x0 / minor); k * minor <= x1; k += 1) {
        const double x = k * minor;
        const int is_major = fmod(fabs(k), 5.0) == 0.0;
        move_to(cr, v, x, 0);
        line_to(cr, v, x, -(is_major ? 12 : 6) * u / s);
        cairo_stroke(cr);
        if (!is_major || x < -1e-9) continue;
        char label[32];
        snprintf(label, sizeof label, "%g cm", round(x * 1e5) / 1e3);
        cairo_text_extents_t te;
        cairo_text_extents(cr, label, &te);
        double px, py;
        draw_to_pixel(v, x, -26 * u / s, &px, &py);
        show_text(cr, L, px - te.width / 2 - te.x_bearing, py - te.height / 2 - te.y_bearing, label);
    }
}

/* A mark: a line across the surface from just above it down to its label,
 * which hangs level units under the surface and ends at the line. */
static void draw_mark(cairo_t *cr, const draw_View *v, draw_Layout *L, double x, double level, unsigned colour,
                      const char *label)
{
    /* Without a label (the close-up) the line only crosses the surface. */
    if (!label) level = 8;
    if (!isfinite(x)) return;
    const double u = unit_px(v), s = v->scale_px_per_m;
    move_to(cr, v, x, 8 * u / s);
    line_to(cr, v, x, -level * u / s);
    rgb_hex(cr, colour, 1);
    cairo_set_line_width(cr, 2 * u);
    cairo_stroke(cr);
    if (!label) return;
    double px, py;
    draw_to_pixel(v, x, -level * u / s, &px, &py);
    cairo_set_font_size(cr, 10 * u);
    cairo_text_extents_t te;
    cairo_text_extents(cr, label, &te);
    /* Right-aligned: the incline descends to the right, so the text runs
     * away from its surface. */
    show_text(cr, L, px - 3 * u - te.x_advance, py - te.y_bearing - te.height / 2, label);
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

/* Labels hang below the scale's labels, one level each, so that marks a
 * few pixels apart (the paper's and the model's on a whole-ramp view)
 * still read; without labels, short lines across the surface and the band. */
static void draw_marks(cairo_t *cr, const draw_View *v, draw_Layout *L, const draw_Marks *mk, int labels)
{
    if (!mk) return;
    char label[64];
    draw_band(cr, v, mk->measured_x_m, mk->measured_error_m);
    if (isfinite(mk->measured_x_m)) {
        snprintf(label, sizeof label, "measured %.1f \xc2\xb1 %.1f cm", mk->measured_x_m * 100,
                 mk->measured_error_m * 100);
        draw_mark(cr, v, L, mk->measured_x_m, 68, COL_MEASURED, labels ? label : NULL);
    }
    snprintf(label, sizeof label, "model %.1f cm", mk->model_x_m * 100);
    draw_mark(cr, v, L, mk->model_x_m, 54, COL_MODEL, labels ? label : NULL);
    snprintf(label, sizeof label, "paper %.1f cm", mk->paper_x_m * 100);
    draw_mark(cr, v, L, mk->paper_x_m, 40, COL_PAPER, labels ? label : NULL);
}

static void draw_incline(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    double lo, hi;
    visible_x(v, &lo, &hi);
    /* The ramp starts a little above the start position (the run ends if
     * the centre goes uphill past it) and ends at its lower end. */
    const double x0 = fmax(lo, -2 * f->model->body.radius_m), x1 = fmin(hi, f->model->setup.ramp_length_m);
    if (x1 <= x0) return;
    draw_ramp_body(cr, v, x0, x1);
    draw_scale(cr, v, f->layout, x0, x1);
    draw_marks(cr, v, f->layout, f->marks, 0);
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

/* The force (fx along the incline, fy along its normal) acting at the
 * contact point, drawn at the frame's px_per_N as an arrow that ends there
 * (the body stays in view). Past FORCE_MAX_WEIGHTS M g it is cut, and its
 * label gives its value. */
static void force_arrow(cairo_t *cr, const draw_Frame *f, double fx, double fy, unsigned colour, const char *name)
{
    const draw_View *v = &f->view;
    const jc_Model *m = f->model;
    const double force_N = hypot(fx, fy), a = v->incline_rad, u = unit_px(v);
    if (!(force_N > 0)) return;
    const draw_ForceScale fs = draw_force_scale(v, m);
    const double cap_N = FORCE_MAX_WEIGHTS * m->body.mass_kg * m->setup.gravity_mps2;
    const double len = fmin(force_N, cap_N) * fs.px_per_N;
    /* The force's direction in pixels (picture Y up, pixel y down). */
    const double dx = (fx * cos(a) + fy * sin(a)) / force_N, dy = -(-fx * sin(a) + fy * cos(a)) / force_N;
    double px1, py1;
    draw_to_pixel(v, f->sample->state.x_m, 0, &px1, &py1);
    const double px0 = px1 - len * dx, py0 = py1 - len * dy;
    rgb_hex(cr, colour, 1);
    arrow(cr, f->layout, px0, py0, px1, py1, u);
    if (len < 8 * u) return;
    char label[48];
    if (force_N > cap_N) snprintf(label, sizeof label, "%s %.3g N", name, force_N);
    else snprintf(label, sizeof label, "%s", name);
    /* The name beyond the tail, lifted off the incline's surface. */
    cairo_set_font_size(cr, 13 * u);
    cairo_text_extents_t te;
    cairo_text_extents(cr, label, &te);
    const double lift = fy == 0.0 ? 10 * u : 0.0, gap = 9 * u + 0.5 * fabs(te.width * dx);
    const double cx = px0 - gap * dx + lift * sin(a), cy = py0 - gap * dy - lift * cos(a);
    show_text(cr, f->layout, cx - te.width / 2 - te.x_bearing, cy - te.height / 2 - te.y_bearing, label);
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
    const double u = unit_px(v), right = v->width_px - 10 * u;
    const int first = f->layout->count;
    f->layout->panel_now = DRAW_PANEL_LEGEND;
    draw_readouts(cr, f, right, u);
    cairo_set_font_size(cr, 10 * u);
    rgb_hex(cr, COL_GREY, 1);
    text_right(cr, f->layout, "arrows: N (blue), F (orange)  \xe2\x97\x90 centre of mass", right, 117 * u);
    draw_force_bar(cr, f, u);
    f->layout->panel_now = DRAW_PANEL_FRAME;
    record_legend(cr, f->layout, first, f);
}

/* ---- the frame ---- */

/* Everything that lives in the incline's coordinates, in f's view, but the
 * marks' labels (draw_frame puts them over the close-up). */
static void draw_scene(cairo_t *cr, const draw_Frame *f)
{
    draw_incline(cr, f);
    draw_path(cr, f);
    draw_trace(cr, f);
    draw_body(cr, f);
    draw_contact(cr, f);
}

/* The body up close in a box in the bottom left corner (under the incline,
 * which descends to the right), with the same forces' scale. */
static void draw_zoom_box(cairo_t *cr, const draw_Frame *f)
{
    double x, y, w, h;
    draw_inset_rect(&f->view, &x, &y, &w, &h);
    const double u = unit_px(&f->view);
    draw_Frame g = *f;
    /* At least ZOOM_MIN times the whole view, or the close-up shows nothing new. */
    const double shorter = fmin(w, h), r = f->model->body.radius_m;
    const double radii = fmin(ZOOM_RADII, shorter / (ZOOM_MIN * f->view.scale_px_per_m * r));
    g.view = draw_view_zoom(f->model, (int)w, (int)h, &f->sample->state, radii, u);
    f->layout->panel_now = DRAW_PANEL_INSET;
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rectangle(cr, 0, 0, w, h);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_scene(cr, &g);
    char label[48];
    snprintf(label, sizeof label, "close-up \xc3\x97%.2g", g.view.scale_px_per_m / f->view.scale_px_per_m);
    cairo_set_font_size(cr, 11 * u);
    rgb_hex(cr, COL_INK, 1);
    show_text(cr, f->layout, 6 * u, 14 * u, label);
    cairo_restore(cr);
    f->layout->panel_now = DRAW_PANEL_FRAME;
    layout_add(cr, f->layout, DRAW_BOX_INSET, x, y, x + w, y + h, 0, NULL);
    cairo_rectangle(cr, x, y, w, h);
    rgb_hex(cr, COL_INK, 1);
    cairo_set_line_width(cr, 1.5 * u);
    cairo_stroke(cr);
}

void draw_frame(cairo_t *cr, const draw_Frame *frame)
{
    /* The boxes are always kept (labels give way to what is drawn); the
     * caller sees them when it asked. */
    draw_Layout local;
    draw_Frame g = *frame;
    if (!g.layout) g.layout = &local;
    g.layout->count = g.layout->dropped = 0;
    g.layout->panel_now = DRAW_PANEL_FRAME;
    const draw_Frame *f = &g;
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    draw_scene(cr, f);
    if (f->zoom_box && f->model->body.radius_m * f->view.scale_px_per_m < ZOOM_BELOW_UNITS * unit_px(&f->view))
        draw_zoom_box(cr, f);
    draw_marks(cr, &f->view, f->layout, f->marks, 1);
    draw_hud(cr, f);
    cairo_restore(cr);
}
