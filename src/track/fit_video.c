/* jc_track_fit: a video's fit. The free motion's first frame is found
 * first and the start fitted there (launch.c); the least squares (fit.c)
 * begin from that start. The two share the fit's progress: the search for
 * the free motion's start its first part, the least squares the rest. */
#include "track_internal.h"

#include <string.h>

/* The part of the progress the search for the free motion's start takes. */
#define LAUNCH_PART 0.15

/* The free motion's first frame and the start fitted there, for a start
 * taken from the video: searched for when the window's start was not given
 * (a hand may push the body first), fitted at the window's first frame when
 * it was. *refined: 1 when launch->start holds that fit (0 for the setup's
 * start, a fit of a start window itself, or a given window whose first
 * frames the model cannot start from: the start is then estimated from
 * them). JC_OK, or a status with a message. */
static int find_launch(const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o, const jc_SimOptions *sim,
                       const jc_TrackFitSpan *span, jc_TrackLaunch *launch, int *refined, char *err, size_t err_len)
{
    long first, count;
    jc_track_window(t, o->from_s, o->to_s, &first, &count);
    memset(launch, 0, sizeof *launch);
    launch->frame = first;
    launch->chi2_dof = launch->chi2_dof_with = NAN;
    *refined = 0;
    if (o->start_window || o->start != JC_TRACK_START_TRACKED || count <= 0) return JC_OK;
    const int scan = isnan(o->from_s);
    jc_TrackLaunch found;
    const int st = jc_track_launch(setup, t, sim, first, o->to_s, scan, o->mark_angle_rad, span, &found, err, err_len);
    if (st != JC_OK) return scan || st == JC_ESTOPPED ? st : JC_OK;
    *launch = found;
    *refined = 1;
    return JC_OK;
}

int jc_track_fit(const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o, const jc_SimOptions *sim,
                 jc_TrackFitResult *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    int rc = jc_fit_options_check(setup, o, err, err_len);
    if (rc != JC_OK) return rc;
    const jc_TrackFitSpan launch_span = {o->progress, o->progress_ctx, 0.0, LAUNCH_PART};
    jc_TrackLaunch launch;
    int refined;
    if ((rc = find_launch(setup, t, o, sim, &launch_span, &launch, &refined, err, err_len)) != JC_OK) return rc;
    jc_TrackFitOptions q = *o;
    if (refined) q.from_s = t->t_s[launch.frame];
    const jc_TrackFitSpan fit_span = {o->progress, o->progress_ctx, LAUNCH_PART, 1.0};
    rc = jc_track_fit_solve(setup, t, &q, sim, refined ? &launch.start : NULL, &fit_span, out, err, err_len);
    out->launch = launch;
    if (rc == JC_OK && o->progress) {
        const jc_TrackFitProgress done = {"done", 0, 1.0};
        (void)o->progress(o->progress_ctx, &done);
    }
    return rc;
}
