/* One animation frame drawn with cairo (geometry in draw.h). Everything is
 * drawn to scale in metres and converted to pixels by the view; only line
 * widths, markers and text are sized in pixels, relative to the frame. */
#include "draw.h"

#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846
/* The camera shows this many rim radii across the frame's shorter side. */
#define VIEW_RADII 8.0
/* A force of M g is drawn this many rim radii long; longer arrows are clipped. */
#define FORCE_RADII_PER_WEIGHT 1.5
#define FORCE_MAX_RADII 3.0

static void rgb_hex(cairo_t *cr, unsigned hex, double alpha)
{
    cairo_set_source_rgba(cr, ((hex >> 16) & 0xff) / 255.0, ((hex >> 8) & 0xff) / 255.0, (hex & 0xff) / 255.0, alpha);
}

enum {
    COL_INK = 0x222222, COL_RAMP = 0xeadfcb, COL_RAMP_EDGE = 0x6b4f2a, COL_RIM = 0x333333, COL_FACE = 0xf6f6f6,
    COL_DISC = 0xdce6ef, COL_HOOP = 0x555555, COL_ROD = 0xc8962e, COL_ROD_EDGE = 0x7a5a1a, COL_POINT = 0x6a3d9a,
    COL_TRACE = 0x0072b2, COL_NORMAL = 0x0072b2, COL_FRICTION = 0xd55e00, COL_GREY = 0x777777,
    COL_ROLLING = 0x009e73, COL_SLIDING = 0xe69f00, COL_FLIGHT = 0xd55e00
};

void draw_part_rgb(jc_PartKind kind, double rgb[3])
{
    const unsigned hex = kind == JC_PART_DISC ? COL_DISC : kind == JC_PART_HOOP ? COL_HOOP
                       : kind == JC_PART_ROD ? COL_ROD : COL_POINT;
    rgb[0] = ((hex >> 16) & 0xff) / 255.0;
    rgb[1] = ((hex >> 8) & 0xff) / 255.0;
    rgb[2] = (hex & 0xff) / 255.0;
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

draw_View draw_view_follow(const jc_Model *m, int width_px, int height_px, const jc_State *s)
{
    draw_View v = {width_px, height_px, 0, 0, 0, m->setup.incline_rad};
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

/* Pixels per "unit" of line width and text: relative to the frame. */
static double unit_px(const draw_View *v)
{
    const int shorter = v->width_px < v->height_px ? v->width_px : v->height_px;
    return fmax(shorter / 360.0, 0.5);
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
    line_to(cr, v, x1 - depth * sin(a), -depth * cos(a)); /* straight down in the picture */
    line_to(cr, v, x0 - depth * sin(a), -depth * cos(a));
    cairo_close_path(cr);
    rgb_hex(cr, COL_RAMP, 1);
    cairo_fill(cr);
    move_to(cr, v, x0, 0);
    line_to(cr, v, x1, 0);
    rgb_hex(cr, COL_RAMP_EDGE, 1);
    cairo_set_line_width(cr, 2.5 * unit_px(v));
    cairo_stroke(cr);
}

static void draw_scale(cairo_t *cr, const draw_View *v, double x0, double x1)
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
        cairo_move_to(cr, px - te.width / 2 - te.x_bearing, py - te.height / 2 - te.y_bearing);
        cairo_show_text(cr, label);
    }
}

static void draw_incline(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    double lo, hi;
    visible_x(v, &lo, &hi);
    /* The ramp starts above the start position and ends at its lower end. */
    const double x0 = fmax(lo, -1.0 - 2 * f->model->body.radius_m), x1 = fmin(hi, f->model->setup.ramp_length_m);
    if (x1 <= x0) return;
    draw_ramp_body(cr, v, x0, x1);
    draw_scale(cr, v, x0, x1);
}

/* ---- the trace of the centre ---- */

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
    const double r = 6 * unit_px(&f->view);
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
    circle(cr, v, s->x_m, s->y_m, 2.5 * u); /* the axis C */
    rgb_hex(cr, COL_RIM, 1);
    cairo_fill(cr);
    draw_cm(cr, f);
}

/* ---- contact and forces ---- */

static void arrow(cairo_t *cr, double x0, double y0, double x1, double y1, double u)
{
    const double len = hypot(x1 - x0, y1 - y0);
    if (len < 2) return;
    const double ux = (x1 - x0) / len, uy = (y1 - y0) / len, head = fmin(10 * u, 0.6 * len);
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
 * contact point, drawn as an arrow that ends there: the body stays in view. */
static void force_arrow(cairo_t *cr, const draw_Frame *f, double fx, double fy, unsigned colour, const char *name)
{
    const draw_View *v = &f->view;
    const jc_Model *m = f->model;
    const double weight = m->body.mass_kg * m->setup.gravity_mps2, r = m->body.radius_m;
    const double len = FORCE_RADII_PER_WEIGHT * r * hypot(fx, fy) / weight;
    if (!(len > 0)) return;
    const double k = FORCE_RADII_PER_WEIGHT * r / weight * fmin(len, FORCE_MAX_RADII * r) / len;
    const double x = f->sample->state.x_m, u = unit_px(v);
    double px0, py0, px1, py1;
    draw_to_pixel(v, x - k * fx, -k * fy, &px0, &py0);
    draw_to_pixel(v, x, 0, &px1, &py1);
    rgb_hex(cr, colour, 1);
    arrow(cr, px0, py0, px1, py1, u);
    const double d = hypot(px1 - px0, py1 - py0);
    if (d < 8 * u) return;
    /* The name beyond the tail, lifted off the incline's surface. */
    cairo_set_font_size(cr, 13 * u);
    cairo_text_extents_t te;
    cairo_text_extents(cr, name, &te);
    const double a = v->incline_rad, lift = fy == 0.0 ? 10 * u : 0.0;
    const double cx = px0 - 9 * u * (px1 - px0) / d + lift * sin(a), cy = py0 - 9 * u * (py1 - py0) / d - lift * cos(a);
    cairo_move_to(cr, cx - te.width / 2 - te.x_bearing, cy - te.height / 2 - te.y_bearing);
    cairo_show_text(cr, name);
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

/* ---- clock, mode, legend ---- */

/* Right-aligned text at (right, baseline). */
static void text_right(cairo_t *cr, const char *s, double right, double baseline)
{
    cairo_text_extents_t te;
    cairo_text_extents(cr, s, &te);
    cairo_move_to(cr, right - te.x_advance, baseline);
    cairo_show_text(cr, s);
}

static void draw_mode_badge(cairo_t *cr, const draw_Frame *f, double right, double top, double u)
{
    const jc_Mode mode = f->sample->mode;
    const char *name = jc_mode_name(mode);
    cairo_set_font_size(cr, 14 * u);
    cairo_text_extents_t te;
    cairo_text_extents(cr, name, &te);
    const double w = te.x_advance + 14 * u, h = 20 * u;
    rgb_hex(cr, mode == JC_MODE_ROLLING ? COL_ROLLING : mode == JC_MODE_SLIDING ? COL_SLIDING : COL_FLIGHT, 1);
    cairo_rectangle(cr, right - w, top, w, h);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_move_to(cr, right - w + 7 * u, top + 15 * u);
    cairo_show_text(cr, name);
}

static void draw_hud(cairo_t *cr, const draw_Frame *f)
{
    const draw_View *v = &f->view;
    const double u = unit_px(v), right = v->width_px - 10 * u;
    const jc_State *s = &f->sample->state;
    char line[96];
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, 18 * u);
    rgb_hex(cr, COL_INK, 1);
    snprintf(line, sizeof line, "t = %.3f s", s->t_s);
    text_right(cr, line, right, 26 * u);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12 * u);
    rgb_hex(cr, COL_GREY, 1);
    if (f->slowmo > 0 && f->slowmo != 1) snprintf(line, sizeof line, "slow motion \xc3\x97%g", f->slowmo);
    else snprintf(line, sizeof line, "real time");
    text_right(cr, line, right, 44 * u);
    snprintf(line, sizeof line, "x = %.1f cm, %.4g\xc2\xb0 incline", s->x_m * 100, f->model->setup.incline_rad * 180 / PI);
    text_right(cr, line, right, 60 * u);
    draw_mode_badge(cr, f, right, 68 * u, u);
    cairo_set_font_size(cr, 11 * u);
    rgb_hex(cr, COL_GREY, 1);
    text_right(cr, "arrows: N (blue), F (orange)", right, 106 * u);
    text_right(cr, "\xe2\x97\x90 centre of mass", right, 121 * u);
}

void draw_frame(cairo_t *cr, const draw_Frame *f)
{
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    draw_incline(cr, f);
    draw_trace(cr, f);
    draw_body(cr, f);
    draw_contact(cr, f);
    draw_hud(cr, f);
    cairo_restore(cr);
}
