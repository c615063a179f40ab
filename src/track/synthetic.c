/* Synthetic experiments: the model filmed and tracked, with the noise a
 * tracker adds, as Tracker's level axes hold them (world metres, the start's
 * contact point at the origin, downhill to the right). They test the
 * import and the fit against known values (tests/track, tests/fit) and make
 * the sample experiments of examples/tracker. Random numbers are Philox
 * draws (random.c), so a track is a pure function of (seed, trial). */
#include "track_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Philox draws per frame: centre x, y, mark x, y, the drop decision. */
#define DRAWS_PER_FRAME 5u
#define SYNTH_MAX_FRAMES 1000000.0

static int check(const jc_TrackSynthOptions *o, char *err, size_t err_len)
{
    if (!(o->fps_hz > 0.0 && o->fps_hz <= 1e5)) {
        snprintf(err, err_len, "frame rate %g Hz is out of range (allowed: (0, 1e5])", o->fps_hz);
        return JC_EINVAL;
    }
    if (!(o->sigma_m >= 0.0 && o->sigma_m < 1.0) || !(o->t_end_s > 0.0 && o->t_end_s <= 3600.0) ||
        !(o->mark_radius_m >= 0.0) || !(o->drop_fraction >= 0.0 && o->drop_fraction <= 0.5) ||
        !(o->hand_s >= 0.0 && o->hand_s <= 10.0) || !isfinite(o->mark_angle_rad)) {
        snprintf(err, err_len, "synthetic track: noise, duration, mark, drop fraction or push out of range");
        return JC_EINVAL;
    }
    return JC_OK;
}

/* Whether a sample is on the frame grid k / fps (not one at an event). */
static int on_grid(double t, double dt)
{
    const double k = t / dt;
    return fabs(k - nearbyint(k)) < 1e-6;
}

/* The incline frame into Tracker's level axes: downhill to the right. */
static void world(double alpha, double x, double y, double *X, double *Y)
{
    jc_track_turn(x, y, cos(alpha), sin(alpha), X, Y);
}

/* The state at time u before the free start (u < 0): a hand pushing the
 * body from rest, rolling, with a constant acceleration that reaches the
 * start's spin at u = 0. */
static void pushed(const jc_State *s0, double r, double hand_s, double u, jc_State *out)
{
    const double acc = s0->omega_radps / hand_s, v = fmax(u + hand_s, 0.0); /* time since the push began */
    *out = *s0;
    out->t_s = u;
    out->omega_radps = acc * v;
    out->theta_rad = s0->theta_rad - 0.5 * acc * hand_s * hand_s + 0.5 * acc * v * v;
    out->x_m = s0->x_m + r * (out->theta_rad - s0->theta_rad);
    out->vx_mps = r * out->omega_radps;
}

int jc_track_synth_raw(const jc_Setup *setup, const jc_TrackSynthOptions *o, jc_TrackRaw *raw, char *err,
                       size_t err_len)
{
    memset(raw, 0, sizeof *raw);
    int rc = check(o, err, err_len);
    if (rc != JC_OK) return rc;
    jc_Model m;
    if ((rc = jc_model_init(&m, setup, err, err_len)) != JC_OK) return rc;
    jc_SimOptions so = jc_default_sim_options();
    so.sample_dt_s = 1.0 / o->fps_hz;
    so.t_max_s = o->t_end_s;
    const double hand_frames = ceil(o->hand_s * o->fps_hz - 1e-9);
    const double frames = floor(o->t_end_s * o->fps_hz) + 1.0 + hand_frames;
    if (frames > SYNTH_MAX_FRAMES) {
        snprintf(err, err_len, "synthetic track: %.0f frames, more than %.0f", frames, SYNTH_MAX_FRAMES);
        return JC_EINVAL;
    }
    so.max_samples = (int)frames + 100000;
    jc_Run run;
    if ((rc = jc_simulate(&m, &so, &run, err, err_len)) != JC_OK) {
        jc_run_free(&run);
        return rc;
    }
    const int centre = o->tracks != JC_TRACK_SYNTH_MARK_ONLY;
    const int mark = o->tracks != JC_TRACK_SYNTH_CENTRE_ONLY && o->mark_radius_m > 0.0;
    if (jc_track_raw_alloc(raw, run.sample_count + (long)hand_frames + 1, (centre ? 1 : 0) + (mark ? 1 : 0)) != 0) {
        jc_run_free(&run);
        snprintf(err, err_len, "out of memory for a synthetic track");
        return JC_ENOMEM;
    }
    snprintf(raw->format, sizeof raw->format, "model");
    raw->px_per_m = raw->tape_length_m = NAN;
    raw->nominal_dt_s = 1.0 / o->fps_hz;
    int ci = centre ? 0 : -1, mi = mark ? (centre ? 1 : 0) : -1;
    if (ci >= 0) snprintf(raw->tracks[ci].name, JC_TRACK_NAME_LEN, "centre");
    if (mi >= 0) snprintf(raw->tracks[mi].name, JC_TRACK_NAME_LEN, "%s", centre ? "mark" : "LED");
    const double mark_offset = jc_track_mark_offset_rad(&m, o->mark_angle_rad), s = o->sigma_m, r = m.body.radius_m;
    const double alpha = setup->incline_rad, t0 = -hand_frames / o->fps_hz;
    long n = 0;
    for (int i = -(int)hand_frames; i < run.sample_count; ++i) {
        jc_State st;
        if (i < 0) pushed(&run.samples[0].state, r, o->hand_s, (double)i / o->fps_hz, &st);
        else st = run.samples[i].state;
        const jc_State *p = &st;
        if (i >= 0 && !on_grid(p->t_s, so.sample_dt_s)) continue;
        const long frame = (long)nearbyint((p->t_s - t0) * o->fps_hz);
        const uint32_t d = (uint32_t)frame * DRAWS_PER_FRAME;
        raw->t_s[n] = p->t_s - t0;
        if (n > 0 && jc_random_uniform(o->seed, o->trial, d + 4) < o->drop_fraction) {
            ++n;
            continue;
        }
        if (ci >= 0)
            world(alpha, p->x_m + s * jc_random_normal(o->seed, o->trial, d),
                  p->y_m + s * jc_random_normal(o->seed, o->trial, d + 1), &raw->tracks[ci].x_m[n],
                  &raw->tracks[ci].y_m[n]);
        if (mi >= 0) {
            const double a = o->mark_radius_m, th = p->theta_rad - mark_offset;
            world(alpha, p->x_m + a * sin(th) + s * jc_random_normal(o->seed, o->trial, d + 2),
                  p->y_m + a * cos(th) + s * jc_random_normal(o->seed, o->trial, d + 3), &raw->tracks[mi].x_m[n],
                  &raw->tracks[mi].y_m[n]);
        }
        ++n;
    }
    raw->frames = n;
    jc_run_free(&run);
    if (n < 3) {
        jc_track_raw_free(raw);
        snprintf(err, err_len, "synthetic track: only %ld frames", n);
        return JC_EINVAL;
    }
    return JC_OK;
}

int jc_track_synthesize(const jc_Setup *setup, const jc_TrackSynthOptions *o, jc_Track *out, char *err,
                        size_t err_len)
{
    memset(out, 0, sizeof *out);
    jc_TrackRaw raw;
    const int st = jc_track_synth_raw(setup, o, &raw, err, err_len);
    if (st != JC_OK) return st;
    jc_TrackOptions opt;
    jc_track_options_default(&opt);
    opt.radius_m = setup->body.radius_m;
    opt.gravity_mps2 = setup->gravity_mps2;
    const int rc = jc_track_from_raw("synthetic", &raw, &opt, out, err, err_len);
    jc_track_raw_free(&raw);
    return rc;
}
