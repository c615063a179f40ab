/* Synthetic experiments: the model filmed and tracked, with the noise a
 * tracker adds. They test the fit against known values (tests/fit) and make
 * the examples of docs/tracker.md. Random numbers are Philox draws
 * (cli/batch/random.c), so a track is a pure function of (seed, trial). */
#include "track_fit.h"
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Philox draws per frame: centre x, y, mark x, y, the drop decision. */
#define DRAWS_PER_FRAME 5u
#define SYNTH_MAX_FRAMES 1000000.0

static int check(const cli_SynthOptions *o, char *err, size_t err_len)
{
    if (!(o->fps_hz > 0.0 && o->fps_hz <= 1e5)) {
        snprintf(err, err_len, "frame rate %g Hz is out of range (allowed: (0, 1e5])", o->fps_hz);
        return -1;
    }
    if (!(o->sigma_m >= 0.0 && o->sigma_m < 1.0) || !(o->t_end_s > 0.0 && o->t_end_s <= 3600.0) ||
        !(o->mark_radius_m >= 0.0) || !(o->drop_fraction >= 0.0 && o->drop_fraction <= 0.5)) {
        snprintf(err, err_len, "synthetic track: noise, duration, mark radius or drop fraction out of range");
        return -1;
    }
    return 0;
}

static int alloc_track(cli_Track *t, long cap)
{
    memset(t, 0, sizeof *t);
    t->t_s = malloc((size_t)cap * sizeof *t->t_s);
    t->x_m = malloc((size_t)cap * sizeof *t->x_m);
    t->y_m = malloc((size_t)cap * sizeof *t->y_m);
    t->theta_rad = malloc((size_t)cap * sizeof *t->theta_rad);
    return t->t_s && t->x_m && t->y_m && t->theta_rad ? 0 : -1;
}

/* Whether a sample is on the frame grid k / fps (not one at an event). */
static int on_grid(double t, double dt)
{
    const double k = t / dt;
    return fabs(k - nearbyint(k)) < 1e-6;
}

int cli_track_synthesize(const jc_Setup *setup, const cli_SynthOptions *o, cli_Track *out, char *err,
                         size_t err_len)
{
    memset(out, 0, sizeof *out);
    if (check(o, err, err_len) != 0) return -1;
    jc_Model m;
    if (jc_model_init(&m, setup, err, err_len) != JC_OK) return -1;
    jc_SimOptions so = jc_default_sim_options();
    so.sample_dt_s = 1.0 / o->fps_hz;
    so.t_max_s = o->t_end_s;
    const double frames = floor(o->t_end_s * o->fps_hz) + 1.0;
    if (frames > SYNTH_MAX_FRAMES) {
        snprintf(err, err_len, "synthetic track: %.0f frames, more than %.0f", frames, SYNTH_MAX_FRAMES);
        return -1;
    }
    so.max_samples = (int)frames + 100000;
    jc_Run run;
    if (jc_simulate(&m, &so, &run, err, err_len) != JC_OK) {
        jc_run_free(&run);
        return -1;
    }
    if (alloc_track(out, run.sample_count + 1) != 0) {
        jc_run_free(&run);
        cli_track_free(out);
        snprintf(err, err_len, "out of memory for a synthetic track");
        return -1;
    }
    const double mark_offset = cli_track_mark_offset_rad(&m), s = o->sigma_m;
    long n = 0;
    for (int i = 0; i < run.sample_count; ++i) {
        const jc_State *p = &run.samples[i].state;
        if (!on_grid(p->t_s, so.sample_dt_s)) continue;
        const uint32_t d = (uint32_t)nearbyint(p->t_s * o->fps_hz) * DRAWS_PER_FRAME;
        if (n > 0 && cli_random_uniform(o->seed, o->trial, d + 4) < o->drop_fraction) {
            out->gaps++;
            continue;
        }
        const double cx = p->x_m + s * cli_random_normal(o->seed, o->trial, d);
        const double cy = p->y_m + s * cli_random_normal(o->seed, o->trial, d + 1);
        out->t_s[n] = p->t_s;
        out->x_m[n] = cx;
        out->y_m[n] = cy;
        out->theta_rad[n] = NAN;
        if (o->mark_radius_m > 0.0) {
            const double a = o->mark_radius_m, th = p->theta_rad - mark_offset;
            const double mx = p->x_m + a * sin(th) + s * cli_random_normal(o->seed, o->trial, d + 2);
            const double my = p->y_m + a * cos(th) + s * cli_random_normal(o->seed, o->trial, d + 3);
            double seen = atan2(mx - cx, my - cy);
            /* Unwrapped: the nearest turn to the previous frame's angle. */
            const double prev = n > 0 ? out->theta_rad[n - 1] : th;
            seen += 2.0 * CLI_PI * nearbyint((prev - seen) / (2.0 * CLI_PI));
            out->theta_rad[n] = seen;
        }
        ++n;
    }
    jc_run_free(&run);
    out->n = n;
    out->has_mark = o->mark_radius_m > 0.0;
    out->x0_m = 0.0;
    out->sigma_m = s;
    out->frame_rate_hz = o->fps_hz;
    out->noise_m = s;
    out->incline_rad = setup->incline_rad;
    out->radius_m = m.body.radius_m;
    out->mark_radius_m = out->has_mark ? o->mark_radius_m : NAN;
    out->hop_threshold_m = 5.0 * s;
    snprintf(out->format, sizeof out->format, "model");
    snprintf(out->centre_name, sizeof out->centre_name, "centre");
    snprintf(out->mark_name, sizeof out->mark_name, "%s", out->has_mark ? "mark" : "");
    if (n < 3) {
        cli_track_free(out);
        snprintf(err, err_len, "synthetic track: only %ld frames", n);
        return -1;
    }
    return 0;
}
