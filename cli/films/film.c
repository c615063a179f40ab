/* A film's frames from a run: the views (a fixed laboratory camera or one
 * that follows the body), the centre's path and its fading trace, the marks;
 * draw.c draws each. jumpcyl animate and the layout test build frames here. */
#include "films.h"

#include <math.h>
#include <stdlib.h>

/* The trace of the centre fades over this much playback time. */
#define TRACE_FADE_PLAYBACK_S 2.0
/* A ramp longer than this many times the distance the body travels is
 * "very long": the fixed camera shows the travel, not the whole ramp. */
#define LONG_RAMP_FACTOR 3.0

/* The rim is drawn at least this many units across its radius, or the
 * fixed camera follows the body and an inset shows the whole ramp. */
#define FILM_MIN_RIM_UNITS 30.0

/* The fixed camera's stretch: the whole ramp from above the start to its
 * lower end (and wherever the body went), or on a floor or a very long ramp
 * the stretch the body travels, with the air above up to its highest rim. */
static void fixed_stretch(film_Film *film)
{
    const jc_Model *m = film->model;
    const jc_Run *run = film->run;
    const double r = m->body.radius_m, ramp = m->setup.ramp_length_m;
    double x_lo = 0, x_hi = 0, y_hi = r;
    for (int i = 0; i < run->sample_count; ++i) {
        const jc_State *s = &run->samples[i].state;
        x_lo = fmin(x_lo, s->x_m);
        x_hi = fmax(x_hi, s->x_m);
        y_hi = fmax(y_hi, s->y_m);
    }
    const int whole_ramp = m->setup.incline_rad > 0 && ramp <= LONG_RAMP_FACTOR * fmax(x_hi - x_lo, r);
    if (whole_ramp) x_hi = fmax(x_hi, ramp);
    film->x_lo_m = x_lo - 1.5 * r;
    film->x_hi_m = x_hi + 1.5 * r;
    film->y_top_m = y_hi + 1.5 * r;
}

int film_init(film_Film *film, const jc_Model *m, const jc_Run *run, int width_px, int height_px, double slowmo,
              film_Camera camera, const draw_Marks *marks)
{
    *film = (film_Film){.model = m, .run = run, .width_px = width_px, .height_px = height_px, .slowmo = slowmo,
                        .camera = camera};
    film->marks = marks ? *marks : (draw_Marks){NAN, NAN, NAN, NAN};
    fixed_stretch(film);
    film->fixed = draw_view_fixed(m, width_px, height_px, film->x_lo_m, film->x_hi_m, film->y_top_m, &film->marks);
    film->fixed_follows = m->body.radius_m * film->fixed.scale_px_per_m < FILM_MIN_RIM_UNITS * film->fixed.unit_px;
    film->trace = malloc(sizeof *film->trace * (size_t)(run->sample_count ? run->sample_count : 1));
    if (!film->trace) return -1;
    for (int i = 0; i < run->sample_count; ++i) {
        const jc_State *s = &run->samples[i].state;
        film->trace[i] = (draw_TracePoint){s->x_m, s->y_m, s->t_s};
    }
    return 0;
}

void film_free(film_Film *film)
{
    free(film->trace);
    film->trace = NULL;
}

/* A hop can carry the body of a following camera up into the legend (on a
 * steep incline, up and to the right): the camera then pans so that the
 * body stays left of it. */
static void keep_off_legend(const film_Film *film, draw_Frame *f)
{
    double box[4], px, py;
    draw_legend_box(&f->view, &film->marks, box);
    draw_to_pixel(&f->view, f->sample->state.x_m, f->sample->state.y_m, &px, &py);
    const double rim = film->model->body.radius_m * f->view.scale_px_per_m + 8 * f->view.unit_px;
    const double over = px + rim - box[0];
    if (over > 0 && py + rim > box[1] && py - rim < box[3]) f->view.center_X_m += over / f->view.scale_px_per_m;
}

draw_Frame film_frame(const film_Film *film, int i)
{
    const jc_Sample *p = &film->run->samples[i];
    const double fade = TRACE_FADE_PLAYBACK_S / film->slowmo;
    int first = i;
    while (first > 0 && film->trace[first - 1].t_s >= p->state.t_s - fade) --first;
    draw_Frame f = {.model = film->model,
                    .view = film->fixed,
                    .sample = p,
                    .trace = film->trace + first,
                    .trace_count = i - first + 1,
                    .trace_fade_s = fade,
                    .slowmo = film->slowmo,
                    .path = film->trace,
                    .path_count = i + 1,
                    .marks = &film->marks};
    if (film->camera == FILM_CAMERA_FIXED && !film->fixed_follows) return f;
    f.view = draw_view_follow(film->model, film->width_px, film->height_px, &p->state);
    if (film->camera == FILM_CAMERA_FIXED) {
        draw_inset(&f.view, film->x_lo_m, film->x_hi_m, film->y_top_m, &f.overview, &f.inset_x_px, &f.inset_y_px);
    }
    keep_off_legend(film, &f);
    return f;
}
