/* The films' layout (cli/films/, as jumpcyl animate builds its frames): for
 * every preset and several inclines, every frame of the run passes the
 * layout check (layout_check.h): no text over another text, the body, an
 * arrow, the inset or the legend; nothing cut by the frame's or the inset's
 * edge; the body at least MIN_BODY_UNITS across (a unit is 1/360 of the
 * frame's shorter side: 60 px at 640x360). The frames are drawn on a cairo
 * recording surface: the same drawing, without the pixels. And the check
 * itself fails on a deliberate overlap, a cut and a small body. */
#include "../test.h"

#include "films.h"
#include "layout_check.h"

#include <cairo.h>
#include <gsl/gsl_errno.h>

#define PI 3.14159265358979323846
/* The body's least size across, in units of the frame's shorter side / 360. */
#define MIN_BODY_UNITS 60.0

typedef struct {
    const char *name;   /* for messages */
    const char *preset;
    double incline_deg; /* NaN: the preset's */
    double t_max_s;     /* the film's length (animate's, for presets that rock for ever) */
    int width, height;
    double fps, slowmo;
    film_Camera camera;
} film_case;

/* Table 1's marks for the paper's cylinder on one of its inclines, the
 * run's first lift-off for any body. */
static draw_Marks marks_for(const jc_Setup *s, const jc_Run *run, int paper_cylinder)
{
    draw_Marks mk = {NAN, NAN, NAN, NAN};
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    if (sum.first_liftoff >= 0) mk.model_x_m = sum.first_liftoff_state.x_m;
    const jc_PaperTableRow *rows;
    const int n = jc_paper_table(&rows);
    for (int i = 0; paper_cylinder && i < n; ++i)
        if (fabs(s->incline_rad * 180 / PI - rows[i].incline_deg) < 1e-9) {
            mk.paper_x_m = rows[i].printed_x_m;
            mk.measured_x_m = rows[i].measured_x_m;
            mk.measured_error_m = rows[i].measured_error_m;
        }
    return mk;
}

/* Draws every sample of the case's run as a frame and checks it; prints a
 * line per case. Returns the number of frames that fail. */
static int check_case(const film_case *c)
{
    jc_Setup s;
    char err[256];
    if (jc_preset_setup(c->preset, &s, err, sizeof err) != JC_OK) return fprintf(stderr, "%s\n", err), 1;
    if (isfinite(c->incline_deg)) s.incline_rad = c->incline_deg * PI / 180;
    jc_Model m;
    if (jc_model_init(&m, &s, err, sizeof err) != JC_OK) return fprintf(stderr, "%s\n", err), 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = 1.0 / (c->fps * c->slowmo);
    if (c->t_max_s > 0) o.t_max_s = c->t_max_s;
    jc_Run run;
    if (jc_simulate(&m, &o, &run, err, sizeof err) != JC_OK) return fprintf(stderr, "%s\n", err), jc_run_free(&run), 1;
    const draw_Marks marks = marks_for(&s, &run, strcmp(c->preset, "paper") == 0);
    film_Film film;
    if (film_init(&film, &m, &run, c->width, c->height, c->slowmo, c->camera, &marks) != 0) return 1;
    const cairo_rectangle_t extents = {0, 0, c->width, c->height};
    const double unit = fmin(c->width, c->height) / 360.0;
    draw_Layout layout;
    int failing = 0;
    double body_lo = INFINITY, body_hi = 0;
    for (int i = 0; i < run.sample_count; ++i) {
        cairo_surface_t *surface = cairo_recording_surface_create(CAIRO_CONTENT_COLOR, &extents);
        cairo_t *cr = cairo_create(surface);
        draw_Frame f = film_frame(&film, i);
        f.layout = &layout;
        draw_frame(cr, &f);
        cairo_destroy(cr);
        cairo_surface_destroy(surface);
        const lc_Result r = lc_check(&layout, c->width, c->height, MIN_BODY_UNITS * unit);
        body_lo = fmin(body_lo, r.body_px), body_hi = fmax(body_hi, r.body_px);
        if (r.problems > 0 && failing++ < 3)
            fprintf(stderr, "%s, frame at t = %.4f s: %d problems, first %s\n", c->name, run.samples[i].state.t_s,
                    r.problems, r.first);
    }
    printf("%-28s %dx%d: %4d frames, %4d failing; body %.0f-%.0f px across\n", c->name, c->width, c->height,
           run.sample_count, failing, body_lo, body_hi);
    film_free(&film);
    jc_run_free(&run);
    return failing;
}

static int check_cases(const film_case *cases, int n)
{
    int failing = 0;
    for (int i = 0; i < n; ++i) failing += check_case(&cases[i]) > 0;
    ENSURE_MSG(failing == 0, "%d of %d films have frames that fail the layout check", failing, n);
    return 0;
}

/* make run's films and every preset's at make run's size and speed. */
static int test_presets(void)
{
    const film_case cases[] = {
        {"paper 45 (make run)", "paper", 45, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"hoop (make run)", "hoop", NAN, 1.747, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"paper", "paper", NAN, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"rocking-hoop", "rocking-hoop", NAN, 3, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"disc", "disc", NAN, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
    };
    return check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

/* The paper's cylinder on other inclines, from a floor to a steep ramp. */
static int test_inclines(void)
{
    const film_case cases[] = {
        {"paper 5", "paper", 5, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"paper 15", "paper", 15, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"paper 60", "paper", 60, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"disc 45", "disc", 45, 0, 640, 360, 25, 6, FILM_CAMERA_FIXED},
        {"hoop 10", "hoop", 10, 1.5, 640, 360, 25, 6, FILM_CAMERA_FIXED},
    };
    return check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

/* animate's default size and speed, a full-HD frame, and the follow camera. */
static int test_sizes_and_cameras(void)
{
    const film_case cases[] = {
        {"paper 45 (default)", "paper", 45, 0, 960, 540, 30, 8, FILM_CAMERA_FIXED},
        {"hoop (default)", "hoop", NAN, 1.747, 960, 540, 30, 8, FILM_CAMERA_FIXED},
        {"paper 30 full HD", "paper", 30, 0, 1920, 1080, 25, 6, FILM_CAMERA_FIXED},
        {"paper 45 follow", "paper", 45, 0, 640, 360, 25, 6, FILM_CAMERA_FOLLOW},
        {"hoop follow", "hoop", NAN, 1.747, 640, 360, 25, 6, FILM_CAMERA_FOLLOW},
    };
    return check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

/* ---- the check itself ---- */

static draw_Layout one_layout(void)
{
    draw_Layout L = {0};
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_FRAME, 10, 10, 60, 22, 0, "a"};
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_BODY, DRAW_PANEL_FRAME, 200, 200, 280, 280, 0, ""}; /* 80 px */
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_LEGEND, DRAW_PANEL_FRAME, 500, 0, 640, 120, 0, ""};
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_LEGEND, 520, 10, 630, 24, 0, "t = 0 s"};
    return L;
}

static int test_check_finds_problems(void)
{
    draw_Layout L = one_layout();
    ENSURE(lc_check(&L, 640, 360, 60).problems == 0);
    /* Two texts that overlap by 2 px both ways. */
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_FRAME, 58, 20, 100, 30, 0, "b"};
    ENSURE(lc_check(&L, 640, 360, 60).problems == 1);
    /* Moved 3 px to the right: apart. */
    L.boxes[L.count - 1].x0 += 3, L.boxes[L.count - 1].x1 += 3;
    ENSURE(lc_check(&L, 640, 360, 60).problems == 0);
    /* A text over the body's rim, but not over its bounding square's corner only. */
    L.boxes[L.count - 1] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_FRAME, 270, 270, 290, 290, 0, "corner"};
    ENSURE(lc_check(&L, 640, 360, 60).problems == 0);
    L.boxes[L.count - 1] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_FRAME, 275, 230, 295, 245, 0, "on the rim"};
    const lc_Result rim = lc_check(&L, 640, 360, 60);
    ENSURE_MSG(rim.problems == 1, "%d problems: %s", rim.problems, rim.first);
    /* Cut by the frame's edge. */
    L.boxes[L.count - 1] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_FRAME, 610, 350, 650, 362, 0, "cut"};
    ENSURE(lc_check(&L, 640, 360, 60).problems >= 1);
    /* An arrow across a text, and one that passes it 5 px away. */
    L.boxes[L.count - 1] = (draw_Box){DRAW_BOX_ARROW, DRAW_PANEL_FRAME, 5, 45, 85, 5, 6, ""};
    const lc_Result across = lc_check(&L, 640, 360, 60);
    ENSURE_MSG(across.problems == 1, "%d problems: %s", across.problems, across.first);
    L.boxes[L.count - 1] = (draw_Box){DRAW_BOX_ARROW, DRAW_PANEL_FRAME, 5, 30, 85, 30, 6, ""};
    ENSURE(lc_check(&L, 640, 360, 60).problems == 0);
    /* The body into the legend. */
    L.boxes[1].x0 = 450, L.boxes[1].x1 = 530, L.boxes[1].y0 = 50, L.boxes[1].y1 = 130;
    ENSURE(lc_check(&L, 640, 360, 60).problems == 1);
    /* A small body. */
    L.boxes[1] = (draw_Box){DRAW_BOX_BODY, DRAW_PANEL_FRAME, 200, 200, 222, 222, 0, ""};
    const lc_Result r = lc_check(&L, 640, 360, 60);
    ENSURE_MSG(r.problems == 1 && r.body_px == 22, "%d problems, body %g px: %s", r.problems, r.body_px, r.first);
    return 0;
}

/* The inset: its own texts inside it pass; the frame's text under it, or
 * an inset's text past its edge, fail. */
static int test_check_inset(void)
{
    draw_Layout L = one_layout();
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_INSET, DRAW_PANEL_FRAME, 8, 200, 190, 352, 0, ""};
    L.boxes[L.count++] = (draw_Box){DRAW_BOX_TEXT, DRAW_PANEL_INSET, 14, 206, 80, 218, 0, "whole ramp"};
    ENSURE(lc_check(&L, 640, 360, 60).problems == 0);
    L.boxes[L.count - 1].panel = DRAW_PANEL_FRAME;
    ENSURE(lc_check(&L, 640, 360, 60).problems == 1);
    L.boxes[L.count - 1].panel = DRAW_PANEL_INSET;
    L.boxes[L.count - 1].x0 = 2;
    ENSURE(lc_check(&L, 640, 360, 60).problems == 1);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off(); /* as the tool does: the library reports GSL's failures */
    RUN_TEST(test_check_finds_problems);
    RUN_TEST(test_check_inset);
    RUN_TEST(test_presets);
    RUN_TEST(test_inclines);
    RUN_TEST(test_sizes_and_cameras);
    cairo_debug_reset_static_data(); /* cairo's font caches: no false leaks under ASan */
    TEST_MAIN_END();
}
