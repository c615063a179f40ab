/* The model at a video's frame times. Frames come at any times (a camera's
 * jitter, dropped frames), while the simulator samples on its own grid
 * k * dt; the run is sampled a fraction of a frame apart and interpolated
 * with the velocities it carries (cubic Hermite: exact in flight, where the
 * path is a parabola, and O(dt^4) while rolling or sliding). */
#include "track_internal.h"

#include <stdio.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Samples per shortest frame interval: Hermite's error at 8 per 1/60 s is
 * below 1 um for the paper's cylinder. */
#define SAMPLES_PER_FRAME 8.0
#define MIN_SAMPLE_DT_S 1e-5
/* Frames within this fraction of a step of a grid are on it (a table's
 * times written to a microsecond). */
#define GRID_TOL 1e-3
/* Uphill swings shorter than this are taken in closed form (below). */
#define TINY_SWING_M 1e-6

int jc_track_sim_init(jc_TrackSim *s)
{
    memset(s, 0, sizeof *s);
    s->ws = jc_workspace_new();
    s->shift_m = JC_TRACK_RAMP_MARGIN_M;
    return s->ws ? JC_OK : JC_ENOMEM;
}

double jc_track_sim_shift(const jc_Track *t)
{
    return JC_TRACK_RAMP_MARGIN_M - (isfinite(t->x0_m) ? t->x0_m : 0.0);
}

void jc_track_sim_free(jc_TrackSim *s)
{
    free(s->samples);
    free(s->impact_t_s);
    jc_workspace_free(s->ws);
    memset(s, 0, sizeof *s);
}

/* Beyond the last frame the ramp goes on this far at least. */
#define RAMP_BEYOND_M 0.5

jc_Setup jc_track_setup(const jc_Setup *setup, const jc_Track *t)
{
    jc_Setup s = *setup;
    /* A video that goes on past the setup's ramp shows a longer one (a
     * floor, most often): the ramp holds every frame. */
    double far = 0.0;
    for (long i = 0; t && i < t->n; ++i)
        if (isfinite(t->x_m[i])) far = fmax(far, t->x_m[i] - t->x0_m);
    if (far > s.ramp_length_m) s.ramp_length_m = far + RAMP_BEYOND_M;
    s.ramp_length_m += JC_TRACK_RAMP_MARGIN_M;
    return s;
}

int jc_track_model(const jc_Setup *setup, const jc_Track *t, jc_Model *model, char *err, size_t err_len)
{
    const jc_Setup s = jc_track_setup(setup, t);
    return jc_model_init(model, &s, err, err_len);
}

static int grow(void **p, int *cap, int count, size_t size)
{
    if (count < *cap) return 0;
    const int n = *cap ? 2 * *cap : 256;
    void *q = realloc(*p, (size_t)n * size);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

static int on_sample(void *ctx, const jc_Sample *p)
{
    jc_TrackSim *s = ctx;
    if (grow((void **)&s->samples, &s->cap, s->count, sizeof *p) != 0) {
        s->failed = 1;
        return JC_ENOMEM;
    }
    s->samples[s->count++] = *p;
    return JC_OK;
}

static int on_event(void *ctx, const jc_Event *e)
{
    jc_TrackSim *s = ctx;
    jc_summary_add(&s->sum, e, s->run.event_count);
    s->run.event_count++;
    if (e->kind != JC_EVENT_TOUCHDOWN && e->kind != JC_EVENT_BOUNCE) return JC_OK;
    if (grow((void **)&s->impact_t_s, &s->impact_cap, s->impacts, sizeof *s->impact_t_s) != 0) {
        s->failed = 1;
        return JC_ENOMEM;
    }
    s->impact_t_s[s->impacts++] = e->state.t_s;
    return JC_OK;
}

static int is_impact(const jc_TrackSim *s, double t)
{
    for (int i = 0; i < s->impacts; ++i)
        if (fabs(s->impact_t_s[i] - t) <= 1e-12) return 1;
    return 0;
}

/* Cubic Hermite on [0, h] from values and slopes at both ends. */
static double hermite(double f0, double d0, double f1, double d1, double h, double u)
{
    const double s = u / h, s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * f0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * f1 + (s3 - s2) * h * d1;
}

/* The body after the run's end: free flight from the final state. */
static void fly_on(const jc_Model *m, const jc_State *f, double t, double *x, double *y, double *th)
{
    const double u = t - f->t_s, g = m->setup.gravity_mps2;
    *x = f->x_m + f->vx_mps * u + 0.5 * g * m->sin_incline * u * u;
    *y = f->y_m + f->vy_mps * u - 0.5 * g * m->cos_incline * u * u;
    *th = f->theta_rad + f->omega_radps * u;
}

/* The step dt of a grid the times lie on (each within GRID_TOL of a whole
 * multiple of it), or 0 when they do not. */
static double frame_grid(const double *t, long n, double dt_min)
{
    if (n < 2 || !(dt_min > 0)) return 0.0;
    const double steps = nearbyint((t[n - 1] - t[0]) / dt_min);
    if (!(steps >= 1 && steps < 1e8)) return 0.0;
    const double dt = (t[n - 1] - t[0]) / steps;
    /* Aligned to the absolute grid k dt, where the simulator samples. */
    for (long i = 0; i < n; ++i)
        if (fabs(t[i] / dt - nearbyint(t[i] / dt)) > GRID_TOL) return 0.0;
    return dt;
}

static void at_time(const jc_TrackSim *s, const jc_Model *m, int *k, double t, double *x, double *y, double *th)
{
    const jc_Sample *p = s->samples;
    if (s->count == 0 || t >= p[s->count - 1].state.t_s) {
        fly_on(m, s->count ? &p[s->count - 1].state : &s->run.final_state, t, x, y, th);
        return;
    }
    if (s->count == 1 || t <= p[0].state.t_s) {
        /* At or before the first sample (a start moved past a tiny swing):
         * its state, carried by its velocities. */
        const jc_State *a = &p[0].state;
        const double d = t - a->t_s;
        *x = a->x_m + a->vx_mps * d, *y = a->y_m + a->vy_mps * d, *th = a->theta_rad + a->omega_radps * d;
        return;
    }
    /* Times only grow: the search goes on from the last interval. */
    while (*k + 1 < s->count - 1 && p[*k + 1].state.t_s <= t) ++*k;
    const jc_State *a = &p[*k].state, *b = &p[*k + 1].state;
    const double h = b->t_s - a->t_s, u = t - a->t_s;
    const jc_State *near = fabs(u) <= fabs(t - b->t_s) ? a : b;
    if (fabs(t - near->t_s) <= GRID_TOL * h) {
        /* A sample at the frame (up to a table's rounding of its time). */
        const double d = t - near->t_s;
        *x = near->x_m + near->vx_mps * d, *y = near->y_m + near->vy_mps * d, *th = near->theta_rad + near->omega_radps * d;
    } else if (!(h > 1e-15)) {
        *x = b->x_m, *y = b->y_m, *th = b->theta_rad;
    } else if (is_impact(s, b->t_s)) {
        /* b carries the velocities after the impulse: positions are
         * continuous, velocities are not, so straight lines (error
         * a dt^2 / 8: microns). */
        const double w = u / h;
        *x = a->x_m + w * (b->x_m - a->x_m);
        *y = a->y_m + w * (b->y_m - a->y_m);
        *th = a->theta_rad + w * (b->theta_rad - a->theta_rad);
    } else {
        *x = hermite(a->x_m, a->vx_mps, b->x_m, b->vx_mps, h, u);
        *y = hermite(a->y_m, a->vy_mps, b->y_m, b->vy_mps, h, u);
        *th = hermite(a->theta_rad, a->omega_radps, b->theta_rad, b->omega_radps, h, u);
    }
}

/* A rolling start with a tiny uphill spin (a start estimated from frames
 * of a body at rest, or a fit's step around omega0 = 0) turns back within
 * a few nanometres; the simulator takes a swing of less than 1 nm for rest
 * and ends the run there. Physically the body turns back at
 * th0 - w0^2 / (2 th'') after |w0| / th'' and rolls on as from rest: the
 * start is moved to that turning point (errors of order w0^3), which also
 * keeps the path smooth in omega0 across 0 for the fit. */
static void past_tiny_swing(const jc_Model *model, jc_State *s)
{
    const double r = model->body.radius_m;
    if (!(s->omega_radps < 0.0) || s->y_m > r || s->vy_mps != 0.0) return;
    jc_RollingState rs;
    char err[128];
    if (model->setup.theta0_rad != s->theta_rad || model->setup.omega0_radps != s->omega_radps ||
        jc_rolling_state(model, s->theta_rad, &rs, err, sizeof err) != JC_OK || !(rs.alpha_radps2 > 0.0))
        return;
    const double w = s->omega_radps, dth = -w * w / (2.0 * rs.alpha_radps2);
    if (!(r * fabs(dth) < TINY_SWING_M)) return;
    s->t_s += -w / rs.alpha_radps2;
    s->theta_rad += dth;
    s->x_m += r * dth;
    s->omega_radps = 0.0;
    s->vx_mps = 0.0;
}

int jc_track_sim_run(jc_TrackSim *s, const jc_Model *model, const jc_State *start, const jc_SimOptions *o,
                     const double *t_s, long n, double *x_m, double *y_m, double *theta_rad, char *err,
                      size_t err_len)
{
    if (n <= 0) {
        snprintf(err, err_len, "no frames to compare with");
        return JC_EINVAL;
    }
    double dt_min = INFINITY;
    for (long i = 1; i < n; ++i) dt_min = fmin(dt_min, t_s[i] - t_s[i - 1]);
    if (!isfinite(dt_min)) dt_min = 0.01;
    jc_SimOptions opt = *o;
    /* Frames on a grid of whole steps (a camera's clip, dropped frames
     * included) are sampled on it: the simulator's k-th sample is at exactly
     * k dt, so each frame has its own sample. Others (a table's jittered
     * times) are interpolated between samples a fraction of a frame apart. */
    const double grid = frame_grid(t_s, n, dt_min);
    /* At most SAMPLES_PER_FRAME a frame on average, whatever the gaps. */
    const double span = fmax(t_s[n - 1], start->t_s) - start->t_s;
    opt.sample_dt_s = grid > 0 ? grid
                               : fmax(fmax(dt_min / SAMPLES_PER_FRAME, MIN_SAMPLE_DT_S),
                                      span / (SAMPLES_PER_FRAME * (double)n + 1000.0));
    opt.t_max_s = fmax(t_s[n - 1], start->t_s) + 2.0 * opt.sample_dt_s;
    const double samples = (opt.t_max_s - start->t_s) / opt.sample_dt_s + 1000.0;
    opt.max_samples = samples < 1e8 ? (int)samples : 100000000;
    jc_State st0 = *start;
    st0.x_m += s->shift_m;
    past_tiny_swing(model, &st0);
    s->count = 0;
    s->impacts = 0;
    s->failed = 0;
    memset(&s->run, 0, sizeof s->run);
    jc_summary_init(&s->sum);
    const jc_Recorder rec = {s, on_event, on_sample};
    int event_count = 0;
    jc_Run run;
    const int st = jc_simulate_from(model, &st0, &opt, &rec, s->ws, &run, err, err_len);
    event_count = s->run.event_count;
    if (st != JC_OK) {
        if (!s->failed) return st;
        snprintf(err, err_len, "out of memory for the run's samples");
        return JC_ENOMEM;
    }
    s->run = run;
    s->run.event_count = event_count;
    int k = 0;
    for (long i = 0; i < n; ++i) {
        double th;
        at_time(s, model, &k, t_s[i], &x_m[i], &y_m[i], &th);
        x_m[i] -= s->shift_m;
        if (theta_rad) theta_rad[i] = th;
    }
    return JC_OK;
}

void jc_fit_to_video(const jc_TrackFitFrame *fr, const jc_State *start, double *x, double *y, double *th, long n)
{
    if (fr->tilt_rad == 0.0 && fr->surface_m == 0.0) return;
    const double c = cos(fr->tilt_rad), s = sin(fr->tilt_rad);
    for (long i = 0; i < n; ++i) {
        const double dx = x[i] - start->x_m, dy = y[i] - start->y_m;
        x[i] = start->x_m + dx * c + dy * s;
        y[i] = start->y_m - dx * s + dy * c + fr->surface_m;
        if (th) th[i] += fr->tilt_rad;
    }
}

int jc_track_model_path(const jc_Setup *setup, const jc_Track *t, const jc_State *start,
                        const jc_TrackFitFrame *frame, const jc_SimOptions *o, const double *t_s, long n, double *x_m,
                        double *y_m, double *mark_theta_rad, char *err, size_t err_len)
{
    /* The model starts where the run does (its energies and the closed
     * form of a tiny first swing refer to its own start). */
    jc_Setup at_start = *setup;
    at_start.theta0_rad = start->theta_rad;
    at_start.omega0_radps = start->omega_radps;
    jc_Model model;
    int st = jc_track_model(&at_start, t, &model, err, err_len);
    if (st != JC_OK) return st;
    jc_TrackSim sim;
    if ((st = jc_track_sim_init(&sim)) != JC_OK) {
        snprintf(err, err_len, "out of memory");
        return st;
    }
    sim.shift_m = jc_track_sim_shift(t);
    st = jc_track_sim_run(&sim, &model, start, o, t_s, n, x_m, y_m, mark_theta_rad, err, err_len);
    jc_track_sim_free(&sim);
    if (st != JC_OK) return st;
    const jc_TrackFitFrame none = {0.0, 0.0, 0.0};
    if (!frame) frame = &none;
    jc_fit_to_video(frame, start, x_m, y_m, mark_theta_rad, n);
    if (mark_theta_rad) {
        const double off = jc_track_mark_offset_rad(&model, frame->mark_angle_rad);
        for (long i = 0; i < n; ++i) mark_theta_rad[i] -= off; /* G's angle to the mark's */
    }
    return JC_OK;
}
