/* One animation frame drawn at a known state (cli/films/draw.c, called directly):
 * the body parts are where the geometry puts them. The positions are
 * computed here from the geometry alone (incline coordinates, the picture's
 * rotation, the view's scale and centre) and the pixels are read back. */
#include "../test.h"

#include "draw.h"

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

int main(void)
{
    if (make_model()) return 1;
    RUN_TEST(test_to_pixel);
    RUN_TEST(test_parts_in_flight);
    RUN_TEST(test_parts_rolling_other_angle);
    cairo_debug_reset_static_data(); /* cairo's font caches: no false leaks under ASan */
    TEST_MAIN_END();
}
