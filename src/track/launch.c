/* Where the free motion starts. A clip often begins before the release: a
 * hand holds the body, or pushes it to give it its spin. Those frames show
 * an acceleration the model cannot produce, and a model started from them
 * misses everything after. The free motion's first frame is the first from
 * which the model, started with the state the frames show (x0, ω0 and θ0
 * fitted to the next LAUNCH_WINDOW_S), follows them at the noise. */
#include "track_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define LAUNCH_WINDOW_S 0.4   /* 0.4 s of rolling tells the start's x0, ω0 and θ0 */
#define LAUNCH_MIN_FRAMES 8
#define LAUNCH_MAX_S 1.5      /* a push longer than this is not looked for */
#define LAUNCH_CHI2_DOF 3.0   /* the model follows the frames at the noise ... */
#define LAUNCH_BETTER 0.85    /* ... and a frame later it would not follow them better */
#define LAUNCH_CANDIDATES 45  /* start frames tried at most */

/* The window fits' progress: each takes half of what is left of the
 * launch's part (their count is not known in advance). */
typedef struct {
    const jc_TrackFitSpan *span; /* NULL: none */
    int fits;                    /* window fits begun */
    int stopped;                 /* the callback asked to stop */
} launch_progress;

/* The start fitted to the frames from k on (up to frame end, exclusive);
 * its chi2/dof (NaN on failure). */
static double window_fit(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, long k, long end,
                         double mark_angle_rad, launch_progress *lp, jc_State *start)
{
    long last = k;
    while (last + 1 < end && (t->t_s[last + 1] - t->t_s[k] <= LAUNCH_WINDOW_S || last + 1 - k < LAUNCH_MIN_FRAMES))
        last++;
    jc_TrackFitOptions fo;
    jc_fit_options_default(&fo);
    fo.from_s = t->t_s[k];
    fo.to_s = t->t_s[last];
    fo.max_iter = 50;
    fo.descents = 2;
    fo.profiles = 0;
    fo.hold_frame = 1; /* 0.4 s does not tell the frame's tilt; the start is what is asked */
    fo.start_window = 1;
    fo.mark_angle_rad = mark_angle_rad;
    jc_TrackFitSpan part = {NULL, NULL, 0.0, 0.0};
    if (lp->span) {
        const double lo = lp->span->lo, w = lp->span->hi - lo;
        part = *lp->span;
        part.lo = lo + w * (1.0 - ldexp(1.0, -lp->fits));
        part.hi = lo + w * (1.0 - ldexp(1.0, -(lp->fits + 1)));
    }
    lp->fits++;
    jc_TrackFitResult r;
    char err[256];
    const int st = jc_track_fit_solve(setup, t, &fo, o, NULL, &part, &r, err, sizeof err);
    if (st == JC_ESTOPPED) lp->stopped = 1;
    if (st != JC_OK) return NAN;
    *start = r.start;
    return r.chi2_dof;
}

/* The next frame with a centre after k (end if none). */
static long next_frame(const jc_Track *t, long k, long stride, long end)
{
    long j = k + stride;
    while (j < end && !isfinite(t->x_m[j])) j++;
    return j < end ? j : end;
}

int jc_track_launch(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, long from, double to_s,
                    int scan, double mark_angle_rad, const jc_TrackFitSpan *span, jc_TrackLaunch *out, char *err,
                    size_t err_len)
{
    memset(out, 0, sizeof *out);
    out->chi2_dof_with = NAN;
    const int st = jc_track_require("the track", t, JC_TRACK_NEED_CENTRE | JC_TRACK_NEED_INCLINE, err, err_len);
    if (st != JC_OK) return st;
    launch_progress lp = {span && span->fn ? span : NULL, 0, 0};
    long end = t->n;
    while (end > 0 && !isnan(to_s) && t->t_s[end - 1] > to_s) end--;
    long left = 0;
    for (long i = from > 0 ? from : 0; i < end; ++i) left += isfinite(t->x_m[i]);
    if (left < 3) {
        snprintf(err, err_len, "fewer than 3 frames with a centre to start the model from");
        return JC_EINVAL;
    }
    /* The first frame with a centre. */
    while (!isfinite(t->x_m[from])) from++;
    /* Candidates a stride apart: at most LAUNCH_CANDIDATES over LAUNCH_MAX_S,
     * however high the frame rate. */
    const double fps = isfinite(t->frame_rate_hz) ? t->frame_rate_hz : 30.0;
    const long stride = (long)fmax(1.0, ceil(fps * LAUNCH_MAX_S / LAUNCH_CANDIDATES));
    /* The first candidate from which the window fits at the noise, and from
     * which the next fits no better (a push's last frames still raise
     * chi2/dof a little; noise moves it by about sqrt(2/dof)). */
    double best = INFINITY, q = NAN;
    jc_State s, s_best, s_from;
    for (long k = from; k + 3 <= end && t->t_s[k] - t->t_s[from] <= (scan ? LAUNCH_MAX_S : 0.0);) {
        if (isnan(q)) q = window_fit(setup, t, o, k, end, mark_angle_rad, &lp, &s);
        if (lp.stopped) break;
        if (k == from) out->chi2_dof_with = q, s_from = s;
        if (q < best) best = q, out->frame = k, out->chi2_dof = q, s_best = s;
        const long next = next_frame(t, k, stride, end);
        if (!(q <= LAUNCH_CHI2_DOF) || !scan || next + 3 > end) {
            q = NAN;
            k = next;
            continue;
        }
        jc_State s_next;
        const double q_next = window_fit(setup, t, o, next, end, mark_angle_rad, &lp, &s_next);
        if (lp.stopped) break;
        if (!(q_next < LAUNCH_BETTER * q)) {
            best = q, out->frame = k, out->chi2_dof = q, s_best = s;
            break;
        }
        q = q_next, s = s_next, k = next;
    }
    if (lp.stopped) {
        snprintf(err, err_len, "stopped (the progress callback asked)");
        return JC_ESTOPPED;
    }
    if (!isfinite(best)) {
        snprintf(err, err_len, "the model could not be started from the first frames");
        return JC_EINVAL;
    }
    out->start = s_best;
    /* No frame fits: the clip is taken from its first frame (the fit's
     * verdict then says the model does not describe it). */
    if (best > LAUNCH_CHI2_DOF && out->frame != from && isfinite(out->chi2_dof_with))
        out->frame = from, out->chi2_dof = out->chi2_dof_with, out->start = s_from;
    out->pushed = out->frame - from;
    if (out->pushed == 0) out->chi2_dof_with = NAN;
    return JC_OK;
}
