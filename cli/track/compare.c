/* A tracked experiment against the model run from its first tracked state:
 * residuals of the centre's path and of the mark's angle, and the hops
 * found by one detector in both (the model's own exact events beside). */
#include "track_fit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Frames the start's velocities are estimated from: 0.1 s at 60 fps, over
 * which rolling from rest is a parabola to a few microns. */
#define START_SPAN 7
/* Hops are runs of frames this many sigma above contact (never less than
 * HOP_MIN_M, so that a noise-free track does not count rounding). */
#define HOP_SIGMAS 5.0
#define HOP_MIN_M 1e-4
#define START_FIT_S 0.4
#define START_FIT_ITER 50

void cli_compare_free(cli_Compare *c)
{
    free(c->x_m);
    free(c->y_m);
    free(c->theta_rad);
    memset(c, 0, sizeof *c);
}

static int make_start(const cli_Track *t, const jc_Model *m, long first, cli_StartKind kind, double thr,
                      jc_State *s, char *err, size_t err_len)
{
    const double r = m->body.radius_m;
    if (kind == CLI_START_SETUP) {
        /* The setup's own start (θ0, ω0, rolling) where the frame has the centre. */
        memset(s, 0, sizeof *s);
        s->t_s = t->t_s[first];
        s->x_m = t->x_m[first];
        s->y_m = r;
        s->theta_rad = m->setup.theta0_rad;
        s->omega_radps = m->setup.omega0_radps;
        s->vx_mps = r * s->omega_radps;
        return 0;
    }
    if (cli_track_start_estimate(t, first, START_SPAN, r, m->setup.theta0_rad, thr, s) != 0) {
        snprintf(err, err_len, "fewer than 3 frames to estimate the first tracked state from");
        return -1;
    }
    /* The mark's angle is G's minus the body's offset between the two. */
    if (t->has_mark) s->theta_rad += cli_track_mark_offset_rad(m);
    return 0;
}

/* A parabola through a few noisy frames gives omega to a fraction of a
 * rad/s at 60 fps and 1 px, which grows into centimetres down the ramp:
 * the start is refined by fitting the model's own start (x0, omega0, and
 * theta0 when the mark is tracked) to the frames of the first START_FIT_S. */
static void refine_start(const jc_Setup *setup, const cli_Track *t, const jc_SimOptions *o, long first, jc_State *s)
{
    cli_FitOptions fo;
    memset(&fo, 0, sizeof fo);
    fo.free_mask = (1u << CLI_FIT_X0) | (1u << CLI_FIT_OMEGA0) | (t->has_mark ? 1u << CLI_FIT_THETA0 : 0u);
    fo.loss = CLI_LOSS_LINEAR;
    fo.from_s = t->t_s[first];
    fo.to_s = t->t_s[first] + START_FIT_S;
    fo.max_iter = START_FIT_ITER;
    fo.start = CLI_START_TRACKED;
    fo.sigma_m = t->sigma_m > 0.0 ? 0.0 : 1e-3; /* a noise-free track: any scale has the same minimum */
    cli_FitResult r;
    char err[256];
    if (cli_track_fit(setup, t, &fo, o, &r, err, sizeof err) == 0 && r.stop != CLI_FIT_STOP_ITERATIONS) *s = r.start;
}

static void residuals(cli_Compare *c, const cli_Track *t, double mark_offset)
{
    double path = 0.0, th = 0.0;
    long n_th = 0;
    c->max_path_m = 0.0;
    for (long i = 0; i < c->count; ++i) {
        const long j = c->first + i;
        c->theta_rad[i] -= mark_offset; /* G's angle to the mark's */
        const double d2 = pow(t->x_m[j] - c->x_m[i], 2) + pow(t->y_m[j] - c->y_m[i], 2);
        path += d2;
        c->max_path_m = fmax(c->max_path_m, sqrt(d2));
        if (t->has_mark && isfinite(t->theta_rad[j])) {
            th += pow(t->theta_rad[j] - c->theta_rad[i], 2);
            ++n_th;
        }
    }
    c->rms_path_m = sqrt(path / (double)c->count);
    c->rms_theta_rad = n_th ? sqrt(th / (double)n_th) : NAN;
}

int cli_track_compare(const jc_Setup *setup, const cli_Track *t, const jc_SimOptions *o, cli_StartKind start,
                      double from_s, double to_s, cli_Compare *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    cli_track_window(t, from_s, to_s, &out->first, &out->count);
    if (out->count < 3) {
        snprintf(err, err_len, "the window holds %ld frame(s); at least 3 are needed", out->count);
        return -1;
    }
    jc_Model m;
    if (cli_track_model(setup, &m, err, err_len) != 0) return -1;
    const double r = m.body.radius_m;
    out->threshold_m = fmax(HOP_SIGMAS * t->sigma_m, HOP_MIN_M);
    if (make_start(t, &m, out->first, start, out->threshold_m, &out->start, err, err_len) != 0) return -1;
    if (start == CLI_START_TRACKED) refine_start(setup, t, o, out->first, &out->start);
    /* The model starts where the run does (its energies and the closed
     * form of a tiny first swing refer to its own start). */
    jc_Setup at_start = *setup;
    at_start.theta0_rad = out->start.theta_rad;
    at_start.omega0_radps = out->start.omega_radps;
    if (cli_track_model(&at_start, &m, err, err_len) != 0) return -1;
    const size_t n = (size_t)out->count;
    out->x_m = malloc(n * sizeof *out->x_m);
    out->y_m = malloc(n * sizeof *out->y_m);
    out->theta_rad = malloc(n * sizeof *out->theta_rad);
    cli_TrackSim sim;
    if (!out->x_m || !out->y_m || !out->theta_rad || cli_track_sim_init(&sim) != 0) {
        cli_compare_free(out);
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    sim.shift_m = cli_track_sim_shift(t);
    const double *ts = t->t_s + out->first;
    int rc = cli_track_sim_run(&sim, &m, &out->start, o, ts, out->count, out->x_m, out->y_m, out->theta_rad, err,
                               err_len);
    if (rc == 0) {
        residuals(out, t, cli_track_mark_offset_rad(&m));
        cli_track_find_hops(ts, t->x_m + out->first, t->y_m + out->first, out->count, r, out->threshold_m,
                            &out->measured);
        cli_track_find_hops(ts, out->x_m, out->y_m, out->count, r, out->threshold_m, &out->simulated);
        const jc_RunSummary *sum = &sim.sum;
        out->model_liftoffs = sum->liftoffs;
        out->model_bounces = sum->bounces;
        out->model_largest_hop_m = sum->largest_hop_m;
        out->model_liftoff_t_s = sum->first_liftoff >= 0 ? sum->first_liftoff_state.t_s : NAN;
        out->model_liftoff_x_m =
            sum->first_liftoff >= 0 ? sum->first_liftoff_state.x_m - sim.shift_m : NAN;
    }
    cli_track_sim_free(&sim);
    if (rc != 0) cli_compare_free(out);
    return rc;
}
