/* A tracked experiment against the model run from its first tracked state:
 * residuals of the centre's path and of the mark's angle, and the hops
 * found by one detector in both (the model's own exact events beside). */
#include "track_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void jc_track_compare_free(jc_TrackCompare *c)
{
    free(c->x_m);
    free(c->y_m);
    free(c->theta_rad);
    memset(c, 0, sizeof *c);
}

static void residuals(jc_TrackCompare *c, const jc_Track *t, double mark_offset)
{
    for (long i = 0; i < c->count; ++i) c->theta_rad[i] -= mark_offset; /* G's angle to the mark's */
    jc_track_misfit(t, c->first, c->count, c->x_m, c->y_m, c->theta_rad, &c->rms_path_m, &c->max_path_m,
                    &c->rms_theta_rad);
}

int jc_track_compare(const jc_Setup *setup, const jc_Track *t, const jc_SimOptions *o, jc_TrackStartKind start,
                     double from_s, double to_s, double mark_angle_rad, jc_TrackCompare *out, char *err,
                      size_t err_len)
{
    memset(out, 0, sizeof *out);
    int st = jc_track_require("the track", t, JC_TRACK_NEED_CENTRE | JC_TRACK_NEED_INCLINE, err, err_len);
    if (st != JC_OK) return st;
    long first, count;
    jc_track_window(t, from_s, to_s, &first, &count);
    if (count < 3) {
        snprintf(err, err_len, "the window holds %ld frame(s); at least 3 are needed", count);
        return JC_EINVAL;
    }
    jc_Setup on_track = *setup;
    on_track.incline_rad = t->incline_rad; /* the frames' incline frame */
    setup = &on_track;
    jc_Model m;
    if ((st = jc_track_model(setup, t, &m, err, err_len)) != JC_OK) return st;
    const double r = m.body.radius_m;
    if (start == JC_TRACK_START_SETUP) {
        memset(&out->launch, 0, sizeof out->launch);
        out->launch.frame = first;
        out->launch.chi2_dof = out->launch.chi2_dof_with = NAN;
        jc_track_start_setup(t, first, t->n, m.body.radius_m, &m.setup, &out->launch.start);
    } else {
        /* The free motion's first frame, where from_s did not set it, and
         * the start there fitted to the frames (as fit starts). */
        st = jc_track_launch(setup, t, o, first, to_s, isnan(from_s), mark_angle_rad, NULL, &out->launch, err, err_len);
        if (st != JC_OK) return st;
    }
    out->first = out->launch.frame;
    out->count = first + count - out->first;
    if (out->count < 3) {
        snprintf(err, err_len, "fewer than 3 frames after the free motion's start");
        return JC_EINVAL;
    }
    /* The model starts where the run does (its energies and the closed
     * form of a tiny first swing refer to its own start). */
    jc_Setup at_start = *setup;
    at_start.theta0_rad = out->launch.start.theta_rad;
    at_start.omega0_radps = out->launch.start.omega_radps;
    if ((st = jc_track_model(&at_start, t, &m, err, err_len)) != JC_OK) return st;
    const size_t n = (size_t)out->count;
    out->x_m = malloc(n * sizeof *out->x_m);
    out->y_m = malloc(n * sizeof *out->y_m);
    out->theta_rad = malloc(n * sizeof *out->theta_rad);
    jc_TrackSim sim;
    if (!out->x_m || !out->y_m || !out->theta_rad || jc_track_sim_init(&sim) != 0) {
        jc_track_compare_free(out);
        snprintf(err, err_len, "out of memory");
        return JC_ENOMEM;
    }
    sim.shift_m = jc_track_sim_shift(t);
    const double *ts = t->t_s + out->first;
    int rc = jc_track_sim_run(&sim, &m, &out->launch.start, o, ts, out->count, out->x_m, out->y_m, out->theta_rad,
                              err, err_len);
    if (rc == JC_OK) {
        residuals(out, t, jc_track_mark_offset_rad(&m, mark_angle_rad));
        jc_track_find_hops(ts, t->x_m + out->first, t->y_m + out->first, out->count, r, t->hop_threshold_m,
                           &out->measured);
        jc_track_find_hops(ts, out->x_m, out->y_m, out->count, r, t->hop_threshold_m, &out->simulated);
        const jc_RunSummary *sum = &sim.sum;
        out->model_liftoffs = sum->liftoffs;
        out->model_bounces = sum->bounces;
        out->model_largest_hop_m = sum->largest_hop_m;
        out->model_liftoff_t_s = sum->first_liftoff >= 0 ? sum->first_liftoff_state.t_s : NAN;
        out->model_liftoff_x_m = sum->first_liftoff >= 0 ? sum->first_liftoff_state.x_m - sim.shift_m : NAN;
    }
    jc_track_sim_free(&sim);
    if (rc != JC_OK) jc_track_compare_free(out);
    return rc;
}
