/* One animation frame drawn at a known state (cli/films/draw.c, called directly):
 * the body parts are where the geometry puts them. The positions are
 * computed here from the geometry alone (incline coordinates, the picture's
 * rotation, the view's scale and centre) and the pixels are read back. */
#include "../test.h"

#include "films.h"

#include <cairo.h>

#define PI 3.14159265358979323846
#define W 640
#define H 360

static jc_Model model;

/* A body whose centre of mass is off every part's direction: a disc, a rod
 * at 0.7 rad and a point mass at 2.5 rad, on a 30 degree incline. */
static int make_model(void)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 30 * PI / 180;
    s.paper_cm_offset_m = 0;
    s.body.radius_m = 0.1;
    s.body.part_count = 3;
    s.body.parts[0] = (jc_Part){JC_PART_DISC, 0.05, 0.0, 0.0, 0.1};
    s.body.parts[1] = (jc_Part){JC_PART_ROD, 0.03, 0.05, 0.7, 0.005};
    s.body.parts[2] = (jc_Part){JC_PART_POINT, 0.02, 0.08, 2.5, 0.0};
    char err[256];
    ENSURE_OK(jc_model_init(&model, &s, err, sizeof err), err);
    return 0;
}

/* The pixel of an incline point, by the formulas of the brief. */
static void pixel_of(const draw_View *v, double x, double y, double *px, double *py)
{
    const double a = model.setup.incline_rad;
    const double X = x * cos(a) + y * sin(a), Y = -x * sin(a) + y * cos(a);
    *px = W / 2.0 + v->scale_px_per_m * (X - v->center_X_m);
    *py = H / 2.0 - v->scale_px_per_m * (Y - v->center_Y_m);
}

/* Where a part sits: C + a (sin psi, cos psi), psi = theta - cm_angle + phi. */
static void part_at(const jc_State *s, double cm_angle, const jc_Part *p, double sense, double *x, double *y)
{
    const double psi = sense * s->theta_rad - cm_angle + p->angle_rad;
    *x = s->x_m + p->offset_m * sin(psi);
    *y = s->y_m + p->offset_m * cos(psi);
}

static void rgb_at(cairo_surface_t *surface, double px, double py, double rgb[3])
{
    const unsigned char *data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    const int ix = (int)floor(px + 0.5), iy = (int)floor(py + 0.5);
    rgb[0] = rgb[1] = rgb[2] = -1;
    if (ix < 0 || iy < 0 || ix >= W || iy >= H) return;
    const unsigned v = *(const unsigned *)(const void *)(data + iy * stride + 4 * ix);
    rgb[0] = ((v >> 16) & 0xff) / 255.0;
    rgb[1] = ((v >> 8) & 0xff) / 255.0;
    rgb[2] = (v & 0xff) / 255.0;
}

static int same_colour(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) < 3 / 255.0 && fabs(a[1] - b[1]) < 3 / 255.0 && fabs(a[2] - b[2]) < 3 / 255.0;
}

/* Renders the state and checks every rod and point mass: its colour at the
 * predicted centre; not there when mirrored through C or turned the wrong way. */
static int check_state(const jc_State *state, jc_Mode mode)
{
    const jc_Sample sample = {.state = *state, .mode = mode};
    const draw_View view = draw_view_follow(&model, W, H, state);
    ENSURE(view.width_px == W && view.height_px == H);
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(surface);
    const draw_TracePoint trace[2] = {{state->x_m - 0.05, state->y_m, state->t_s - 0.01}, {state->x_m, state->y_m, state->t_s}};
    const draw_Frame frame = {.model = &model, .view = view, .sample = &sample, .trace = trace, .trace_count = 2,
                              .trace_fade_s = 0.3, .slowmo = 8};
    draw_frame(cr, &frame);
    cairo_surface_flush(surface);
    /* The centre of mass's direction, from the parts (the first moment). */
    double sx = 0, sy = 0;
    for (int i = 0; i < model.setup.body.part_count; ++i) {
        const jc_Part *p = &model.setup.body.parts[i];
        sx += p->mass_kg * p->offset_m * sin(p->angle_rad);
        sy += p->mass_kg * p->offset_m * cos(p->angle_rad);
    }
    const double cm_angle = atan2(sx, sy);
    int bad = fabs(cm_angle - model.body.cm_angle_rad) > 1e-12;
    if (bad) fprintf(stderr, "cm angle %.17g vs %.17g\n", cm_angle, model.body.cm_angle_rad);
    for (int i = 1; !bad && i < model.setup.body.part_count; ++i) {
        const jc_Part *p = &model.setup.body.parts[i];
        double want[3], got[3], x, y, px, py;
        draw_part_rgb(p->kind, want);
        part_at(state, cm_angle, p, 1.0, &x, &y);
        pixel_of(&view, x, y, &px, &py);
        rgb_at(surface, px, py, got);
        if (!same_colour(got, want)) {
            fprintf(stderr, "part %d at (%.1f, %.1f): rgb %.3f %.3f %.3f, want %.3f %.3f %.3f\n", i, px, py, got[0],
                    got[1], got[2], want[0], want[1], want[2]);
            bad = 1;
        }
        pixel_of(&view, 2 * state->x_m - x, 2 * state->y_m - y, &px, &py); /* mirrored through C */
        rgb_at(surface, px, py, got);
        if (same_colour(got, want)) bad = fprintf(stderr, "part %d also mirrored\n", i) > 0;
        part_at(state, cm_angle, p, -1.0, &x, &y); /* rotated the wrong way */
        pixel_of(&view, x, y, &px, &py);
        rgb_at(surface, px, py, got);
        if (same_colour(got, want)) bad = fprintf(stderr, "part %d also where the opposite rotation puts it\n", i) > 0;
    }
    /* The incline: ramp colour just under the surface, white just above it
     * (a radius behind the body, where nothing else is drawn). */
    double px, py, under[3], above[3];
    const double white[3] = {1, 1, 1}, r = model.body.radius_m;
    pixel_of(&view, state->x_m - 2.5 * r, -0.01, &px, &py);
    rgb_at(surface, px, py, under);
    pixel_of(&view, state->x_m + 2.5 * r, 0.3 * r, &px, &py);
    rgb_at(surface, px, py, above);
    if (same_colour(under, white) || !same_colour(above, white))
        bad = fprintf(stderr, "incline: under %.3f %.3f %.3f, above %.3f %.3f %.3f\n", under[0], under[1], under[2],
                      above[0], above[1], above[2]) > 0;
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    return bad;
}

static int test_parts_in_flight(void)
{
    const jc_State s = {0.5, 0.4, model.body.radius_m + 0.02, 1.0, 0.1, 1.1, 20.0};
    return check_state(&s, JC_MODE_FLIGHT);
}

static int test_parts_rolling_other_angle(void)
{
    const jc_State s = {0.2, 0.13, model.body.radius_m, 0.5, 0.0, -2.3, 5.0};
    return check_state(&s, JC_MODE_ROLLING);
}

/* The projection itself: the brief's formulas, through the module's own. */
static int test_to_pixel(void)
{
    const jc_State s = {0, 0.7, 0.1, 0, 0, 0, 0};
    const draw_View v = draw_view_follow(&model, W, H, &s);
    double px, py, qx, qy;
    draw_to_pixel(&v, 0.31, -0.04, &px, &py);
    pixel_of(&v, 0.31, -0.04, &qx, &qy);
    ENSURE_NEAR(px, qx, 1e-9);
    ENSURE_NEAR(py, qy, 1e-9);
    /* Downhill is to the right and down on the screen. */
    draw_to_pixel(&v, 0.0, 0.0, &px, &py);
    draw_to_pixel(&v, 0.1, 0.0, &qx, &qy);
    ENSURE(qx > px && qy > py);
    ENSURE_NEAR(atan2(qy - py, qx - px), model.setup.incline_rad, 1e-12);
    return 0;
}

/* ---- the fixed camera, the forces' scale, the marks ---- */

/* The paper's 3.2 m ramp with the test body, seen whole: the ramp's two
 * ends and the air a body radius above them are inside the frame, and
 * the picture is not a postage stamp (one side of it fills most of the frame). */
static int test_fixed_view_whole_ramp(void)
{
    const double r = model.body.radius_m, L = model.setup.ramp_length_m;
    const draw_View v = draw_view_fixed(&model, W, H, -r, L + r, 3 * r, NULL);
    const double xs[4] = {0, L, -r, L + r}, ys[4] = {0, 0, 3 * r, 3 * r};
    double lo_x = W, hi_x = 0, lo_y = H, hi_y = 0;
    for (int i = 0; i < 4; ++i) {
        double px, py;
        pixel_of(&v, xs[i], ys[i], &px, &py);
        ENSURE_MSG(px >= 0 && px <= W && py >= 0 && py <= H, "point %d at (%.1f, %.1f)", i, px, py);
        lo_x = fmin(lo_x, px), hi_x = fmax(hi_x, px), lo_y = fmin(lo_y, py), hi_y = fmax(hi_y, py);
    }
    ENSURE_MSG(hi_x - lo_x > 0.8 * W || hi_y - lo_y > 0.6 * H, "box %.0f x %.0f px", hi_x - lo_x, hi_y - lo_y);
    return 0;
}

static cairo_surface_t *render(const draw_View *view, const jc_Sample *sample, const draw_Marks *marks)
{
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(surface);
    const draw_Frame frame = {.model = &model, .view = *view, .sample = sample, .slowmo = 8, .marks = marks,
                              };
    draw_frame(cr, &frame);
    cairo_surface_flush(surface);
    cairo_destroy(cr);
    return surface;
}

/* Pixels of colour rgb along the ray from (px, py) in direction (dx, dy),
 * from the first one to the last before a gap of three (a pixel on the
 * antialiased edge of a slanted line is not a gap): a drawn line's length. */
static double run_length(cairo_surface_t *surface, double px, double py, double dx, double dy, const double rgb[3])
{
    double first = -1, last = -1, got[3];
    for (int k = 0; k < 400; ++k) {
        rgb_at(surface, px + k * dx, py + k * dy, got);
        if (same_colour(got, rgb)) {
            if (first < 0) first = k;
            last = k;
        } else if (first >= 0 && k - last >= 3) break;
    }
    return first < 0 ? -1 : last;
}

/* The scale bar is bar_N x px_per_N long, bar_N a round number (1, 2 or 5
 * times a power of ten) not above M g; a normal force of 2 bar_N is drawn
 * twice as long, measured on the rendered frame. */
static int test_force_scale_bar(void)
{
    const double r = model.body.radius_m, L = model.setup.ramp_length_m, a = model.setup.incline_rad;
    const draw_View view = draw_view_fixed(&model, W, H, -r, L + r, 3 * r, NULL);
    const draw_ForceScale fs = draw_force_scale(&view, &model);
    const double weight = model.body.mass_kg * model.setup.gravity_mps2;
    const double mantissa = fs.bar_N / pow(10, floor(log10(fs.bar_N)));
    ENSURE_MSG(fabs(mantissa - 1) < 1e-9 || fabs(mantissa - 2) < 1e-9 || fabs(mantissa - 5) < 1e-9, "bar %g N",
               fs.bar_N);
    ENSURE(fs.bar_N <= weight && fs.bar_N > weight / 2.5);
    const jc_Sample sample = {.state = {0, 2.5, r, 1, 0, 25, 10}, .mode = JC_MODE_ROLLING, .normal_N = 2 * fs.bar_N};
    cairo_surface_t *surface = render(&view, &sample, NULL);
    double ink[3], blue[3];
    draw_colour_rgb(DRAW_INK, ink);
    draw_colour_rgb(DRAW_NORMAL, blue);
    const double bar_px = run_length(surface, fs.bar_x_px - 3, floor(fs.bar_y_px), 1, 0, ink) - 3;
    ENSURE_NEAR(bar_px, fs.bar_N * fs.px_per_N, 2.0);
    /* The normal arrow ends at the contact point; its tail is under the
     * incline along the inward normal, picture direction (-sin a, -cos a),
     * in pixels (-sin a, +cos a). */
    double cx, cy;
    pixel_of(&view, 2.5, 0, &cx, &cy);
    const double arrow_px = run_length(surface, cx, cy, -sin(a), cos(a), blue);
    ENSURE_NEAR(arrow_px, 2 * fs.bar_N * fs.px_per_N, 2.5);
    cairo_surface_destroy(surface);
    return 0;
}

/* Each mark in its colour where it says, just above the incline's surface;
 * the measured band under the surface over its whole width; white between. */
static int test_marks(void)
{
    const double r = model.body.radius_m, L = model.setup.ramp_length_m;
    const draw_View view = draw_view_fixed(&model, W, H, -r, L + r, 3 * r, NULL);
    const draw_Marks marks = {1.6, 1.9, 2.4, 0.1};
    const jc_Sample sample = {.state = {0, 0.3, r, 1, 0, 3, 10}, .mode = JC_MODE_ROLLING, .normal_N = 0.1};
    cairo_surface_t *surface = render(&view, &sample, &marks);
    const double u = view.unit_px, s = view.scale_px_per_m;
    const struct {
        double x_m, y_m;
        draw_Colour colour;
    } probes[] = {{1.6, 5 * u / s, DRAW_MARK_PAPER},     {1.9, 5 * u / s, DRAW_MARK_MODEL},
                  {2.4, 5 * u / s, DRAW_MARK_MEASURED},  {2.31, -3.5 * u / s, DRAW_MARK_MEASURED},
                  {2.49, -3.5 * u / s, DRAW_MARK_MEASURED}};
    for (size_t i = 0; i < sizeof probes / sizeof probes[0]; ++i) {
        double px, py, want[3], got[3];
        pixel_of(&view, probes[i].x_m, probes[i].y_m, &px, &py);
        draw_colour_rgb(probes[i].colour, want);
        /* A 2-unit line: its colour is whole on one of the pixels next to its centre line. */
        int found = 0;
        for (int j = 0; j < 9 && !found; ++j) {
            rgb_at(surface, px + j % 3 - 1, py + j / 3 - 1, got);
            found = same_colour(got, want);
        }
        ENSURE_MSG(found, "probe %zu at (%.1f, %.1f): %.3f %.3f %.3f", i, px, py, got[0], got[1],
                   got[2]);
    }
    const double white[3] = {1, 1, 1};
    double px, py, got[3];
    pixel_of(&view, 1.75, 5 * u / s, &px, &py);
    rgb_at(surface, px, py, got);
    ENSURE_MSG(same_colour(got, white), "between the marks: %.3f %.3f %.3f", got[0], got[1], got[2]);
    cairo_surface_destroy(surface);
    return 0;
}

int main(void)
{
    if (make_model()) return 1;
    RUN_TEST(test_to_pixel);
    RUN_TEST(test_parts_in_flight);
    RUN_TEST(test_parts_rolling_other_angle);
    RUN_TEST(test_fixed_view_whole_ramp);
    RUN_TEST(test_force_scale_bar);
    RUN_TEST(test_marks);
    cairo_debug_reset_static_data(); /* cairo's font caches: no false leaks under ASan */
    TEST_MAIN_END();
}
