/* The library's API for tracked videos and fits (include/jumpcyl/track.h),
 * beyond what the tool's commands exercise:
 *  - a fit's progress: fractions in [0, 1] that never decrease, ending at 1;
 *    the same fit with and without a callback, to the bit;
 *  - a callback that asks to stop: JC_ESTOPPED at once, in the search for
 *    the free motion's start and in the least squares;
 *  - the values a fit can free: listed for the body, found by their names;
 *  - the model sampled at a noise-free video's frames against the frames
 *    themselves, and placed in a tilted video frame;
 *  - a track from the caller's own arrays, the same as from the reader's;
 *  - bad inputs: statuses and one-line messages. */
#include <jumpcyl/track.h>
#include "../track/synth_table.h"
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>

static jc_Setup truth(void)
{
    jc_Setup s = jc_paper_setup();
    s.mu_kinetic = 0.4;
    return s;
}

/* The paper's cylinder at 60 fps with 1 mm of noise, centre and mark. */
static int video(jc_Track *t, uint64_t seed)
{
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, seed, 0.055);
    char err[256];
    return jc_track_synthesize(&s, &so, t, err, sizeof err);
}

static jc_TrackFitOptions mu_k_and_e(void)
{
    jc_TrackFitOptions fo;
    jc_fit_options_default(&fo);
    fo.free[0] = (jc_TrackFitParam){JC_FIT_MU_K, -1};
    fo.free[1] = (jc_TrackFitParam){JC_FIT_RESTITUTION, -1};
    fo.free_count = 2;
    return fo;
}

typedef struct {
    int calls, stop_at;        /* stop_at > 0: ask to stop at that call */
    int decreased, outside;    /* a fraction below the last one, or outside [0, 1] */
    int no_stage;
    double last;
    char last_stage[64];
} progress_log;

static int on_progress(void *ctx, const jc_TrackFitProgress *p)
{
    progress_log *log = ctx;
    log->calls++;
    if (p->fraction < log->last) log->decreased++;
    if (!(p->fraction >= 0.0 && p->fraction <= 1.0)) log->outside++;
    if (!p->stage || !p->stage[0]) log->no_stage++;
    log->last = p->fraction;
    snprintf(log->last_stage, sizeof log->last_stage, "%s", p->stage ? p->stage : "");
    return log->stop_at > 0 && log->calls >= log->stop_at;
}

static int test_progress(void)
{
    jc_Track t;
    ENSURE(video(&t, 3u) == JC_OK);
    const jc_SimOptions o = jc_default_sim_options();
    const jc_Setup guess = jc_paper_setup();
    char err[256];
    jc_TrackFitOptions fo = mu_k_and_e();
    jc_TrackFitResult quiet, told;
    ENSURE_MSG(jc_track_fit(&guess, &t, &fo, &o, &quiet, err, sizeof err) == JC_OK, "%s", err);
    progress_log log = {0, 0, 0, 0, 0, 0.0, ""};
    fo.progress = on_progress;
    fo.progress_ctx = &log;
    ENSURE_MSG(jc_track_fit(&guess, &t, &fo, &o, &told, err, sizeof err) == JC_OK, "%s", err);
    printf("progress: %d calls, last '%s' at %g; mu_k %.6f, e %.6f\n", log.calls, log.last_stage, log.last,
           told.value[0], told.value[1]);
    /* Each descent at least once, and every iteration: far more calls than descents. */
    ENSURE(log.calls > told.descents);
    ENSURE(log.decreased == 0 && log.outside == 0 && log.no_stage == 0);
    ENSURE(log.last == 1.0 && strcmp(log.last_stage, "done") == 0);
    /* The callback changes nothing in the fit. */
    ENSURE(told.count == quiet.count && told.iterations == quiet.iterations && told.chi2 == quiet.chi2);
    for (int k = 0; k < told.count; ++k) ENSURE(told.value[k] == quiet.value[k] && told.sigma[k] == quiet.sigma[k]);
    /* And the fit found the values the video was made with (2 sigma). */
    ENSURE(fabs(told.value[0] - 0.4) < 2.0 * told.sigma[0]);
    ENSURE(fabs(told.value[1] - truth().restitution) < 2.0 * told.sigma[1]);
    jc_track_free(&t);
    return 0;
}

static int test_stop(void)
{
    jc_Track t;
    ENSURE(video(&t, 4u) == JC_OK);
    const jc_SimOptions o = jc_default_sim_options();
    const jc_Setup guess = jc_paper_setup();
    char err[256];
    jc_TrackFitOptions fo = mu_k_and_e();
    fo.progress = on_progress;
    /* The first call comes from the search for the free motion's start;
     * the fortieth from the least squares. */
    const int stops[] = {1, 40};
    for (int i = 0; i < 2; ++i) {
        progress_log log = {0, stops[i], 0, 0, 0, 0.0, ""};
        fo.progress_ctx = &log;
        jc_TrackFitResult r;
        err[0] = '\0';
        const int st = jc_track_fit(&guess, &t, &fo, &o, &r, err, sizeof err);
        printf("stop at call %d: status %d (%s) after %d calls in '%s': %s\n", stops[i], st, jc_status_text(st),
               log.calls, log.last_stage, err);
        ENSURE(st == JC_ESTOPPED);
        ENSURE(log.calls == stops[i]); /* asked once, never called again */
        ENSURE(err[0] && !strchr(err, '\n'));
    }
    jc_track_free(&t);
    return 0;
}

/* The values the paper's body allows, counted from its parts here. */
static int test_param_names(void)
{
    const jc_Setup s = jc_paper_setup();
    int expected = 9;
    int seen[4] = {0};
    for (int i = 0; i < s.body.part_count; ++i) {
        const jc_PartKind k = s.body.parts[i].kind;
        if (seen[k]++) continue;
        expected += k == JC_PART_DISC || k == JC_PART_HOOP ? 1 : 2;
    }
    jc_TrackFitParam p[32];
    const int n = jc_fit_param_list(&s, p, 32);
    ENSURE(n == expected);
    for (int k = 0; k < n; ++k) {
        char name[48];
        jc_fit_param_name(&s, p[k], name, sizeof name);
        jc_TrackFitParam back;
        ENSURE_MSG(jc_fit_param_find(&s, name, &back) == JC_OK, "%s", name);
        ENSURE_MSG(back.kind == p[k].kind && back.part == p[k].part, "%s", name);
    }
    jc_TrackFitParam a, b;
    ENSURE(jc_fit_param_find(&s, "rod_offset", &a) == JC_OK && jc_fit_param_find(&s, "Rod-Offset", &b) == JC_OK);
    ENSURE(a.kind == JC_FIT_PART_OFFSET && b.kind == a.kind && b.part == a.part);
    ENSURE(strcmp(jc_fit_param_unit(a), "m") == 0 && strcmp(jc_fit_param_unit((jc_TrackFitParam){JC_FIT_MU_K, -1}), "") == 0);
    ENSURE(jc_fit_param_find(&s, "disc_offset", &a) == JC_EINVAL); /* a centred disc has none */
    ENSURE(jc_fit_param_find(&s, "hoop_mass", &a) == JC_EINVAL);  /* no hoop in this body */
    ENSURE(jc_fit_param_find(&s, "mu", &a) == JC_EINVAL);
    jc_TrackFitLoss loss;
    for (int k = JC_FIT_LOSS_LINEAR; k <= JC_FIT_LOSS_CAUCHY; ++k)
        ENSURE(jc_fit_loss_parse(jc_fit_loss_name((jc_TrackFitLoss)k), &loss) == JC_OK && (int)loss == k);
    ENSURE(jc_fit_loss_parse("l2", &loss) == JC_EINVAL);
    return 0;
}

/* The model at a noise-free video's frames from the run's own start: the
 * frames themselves (the video samples the run at the frames; the path
 * interpolates samples of another run a fraction of a frame apart). */
static int test_model_path(void)
{
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 0.0, JC_TRACK_SYNTH_BOTH, 1u, 0.055);
    jc_Track t;
    char err[256];
    ENSURE_MSG(jc_track_synthesize(&s, &so, &t, err, sizeof err) == JC_OK, "%s", err);
    const jc_SimOptions o = jc_default_sim_options();
    jc_Setup on_track = s;
    on_track.incline_rad = t.incline_rad;
    /* The setup's start at the first frame, rolling (docs/physics.md §1). */
    jc_State start = {0};
    start.x_m = t.x_m[0];
    start.y_m = s.body.radius_m;
    start.theta_rad = s.theta0_rad;
    start.omega_radps = s.omega0_radps;
    start.vx_mps = s.body.radius_m * s.omega0_radps;
    const long n = t.n;
    double *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y), *th = malloc((size_t)n * sizeof *th);
    double *xt = malloc((size_t)n * sizeof *xt), *yt = malloc((size_t)n * sizeof *yt);
    ENSURE(x && y && th && xt && yt);
    ENSURE_MSG(jc_track_model_path(&on_track, &t, &start, NULL, &o, t.t_s, n, x, y, th, err, sizeof err) == JC_OK,
               "%s", err);
    double path = 0.0, angle = 0.0;
    for (long i = 0; i < n; ++i) {
        path = fmax(path, hypot(x[i] - t.x_m[i], y[i] - t.y_m[i]));
        if (isfinite(t.theta_rad[i])) angle = fmax(angle, fabs(remainder(th[i] - t.theta_rad[i], 2 * SYNTH_PI)));
    }
    /* A tilted, raised video frame: the same path turned about the start
     * by the tilt and moved up by the surface; the mark's angle turned too. */
    const jc_TrackFitFrame fr = {0.0, 0.01, 0.002};
    ENSURE(jc_track_model_path(&on_track, &t, &start, &fr, &o, t.t_s, n, xt, yt, NULL, err, sizeof err) == JC_OK);
    double turned = 0.0;
    for (long i = 0; i < n; ++i) {
        const double dx = x[i] - start.x_m, dy = y[i] - start.y_m, c = cos(0.01), sn = sin(0.01);
        turned = fmax(turned, hypot(xt[i] - (start.x_m + dx * c + dy * sn), yt[i] - (start.y_m - dx * sn + dy * c + 0.002)));
    }
    printf("model path: %ld frames, largest distance from the frames %.3g m, mark angle %.3g rad; "
           "turned frame off by %.3g m\n", n, path, angle, turned);
    /* The residuals of a frame against the model there are the frame's. */
    double f[3];
    const int k = jc_track_residuals_frame(&t, n / 2, 1e-3, t.mark_radius_m, x[n / 2], y[n / 2], th[n / 2], f);
    ENSURE(k == 3 && fabs(f[0]) < 1e-3 && fabs(f[1]) < 1e-3 && fabs(f[2]) < 1e-3);
    free(x), free(y), free(th), free(xt), free(yt);
    jc_track_free(&t);
    ENSURE(path < 1e-6 && angle < 1e-6 && turned < 1e-12);
    return 0;
}

/* A track from the caller's arrays (jc_track_raw_init, nothing allocated
 * by the library) is the track the synthetic raw data gives. */
static int test_caller_arrays(void)
{
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 5u, 0.055);
    jc_TrackRaw made;
    char err[256];
    ENSURE_MSG(jc_track_synth_raw(&s, &so, &made, err, sizeof err) == JC_OK, "%s", err);
    const long n = made.frames;
    double *buf = malloc((size_t)(5 * n) * sizeof *buf);
    ENSURE(buf);
    jc_TrackRaw mine;
    jc_track_raw_init(&mine);
    ENSURE(strcmp(mine.format, "arrays") == 0 && isnan(mine.px_per_m) && isnan(mine.nominal_dt_s));
    mine.frames = n;
    mine.t_s = buf;
    mine.track_count = 2;
    for (int k = 0; k < 2; ++k) {
        mine.tracks[k].x_m = buf + (1 + 2 * k) * n;
        mine.tracks[k].y_m = buf + (2 + 2 * k) * n;
        /* Named as a user would name them: told by their names. */
        snprintf(mine.tracks[k].name, JC_TRACK_NAME_LEN, "%s", k == 0 ? "my axle" : "the rod");
    }
    for (long i = 0; i < n; ++i) {
        buf[i] = made.t_s[i];
        for (int k = 0; k < 2; ++k) {
            mine.tracks[k].x_m[i] = made.tracks[k].x_m[i];
            mine.tracks[k].y_m[i] = made.tracks[k].y_m[i];
        }
    }
    jc_TrackOptions opt;
    jc_track_options_default(&opt);
    opt.radius_m = s.body.radius_m;
    jc_Track a, b;
    ENSURE_MSG(jc_track_from_raw("mine", &mine, &opt, &a, err, sizeof err) == JC_OK, "%s", err);
    ENSURE_MSG(jc_track_from_raw("made", &made, &opt, &b, err, sizeof err) == JC_OK, "%s", err);
    printf("caller's arrays: %ld frames, centre '%s', mark '%s', incline %.4f deg\n", a.n, a.centre_name, a.mark_name,
           a.incline_rad * 180 / SYNTH_PI);
    ENSURE(a.n == b.n && a.centre_source == JC_TRACK_CENTRE_TRACKED && a.has_mark);
    ENSURE(strcmp(a.centre_name, "my axle") == 0 && strcmp(a.format, "arrays") == 0);
    ENSURE(a.incline_rad == b.incline_rad && a.sigma_m == b.sigma_m && a.hops == b.hops);
    for (long i = 0; i < a.n; ++i) ENSURE(a.x_m[i] == b.x_m[i] && a.y_m[i] == b.y_m[i]);
    jc_track_free(&a);
    jc_track_free(&b);
    jc_track_raw_free(&made);
    free(buf);
    return 0;
}

static int test_bad_inputs(void)
{
    char err[256];
    jc_TrackOptions opt;
    jc_track_options_default(&opt);
    jc_Track t;
    ENSURE(jc_track_read_file("/nonexistent/run.trk", &opt, &t, err, sizeof err) == JC_EINVAL);
    ENSURE(strstr(err, "/nonexistent/run.trk: cannot open") == err && t.t_s == NULL);
    ENSURE(jc_track_parse("x.txt", "t\tx\n", 4, &opt, &t, NULL, 0) == JC_EINVAL); /* no message wanted */
    jc_TrackRaw raw;
    jc_track_raw_init(&raw);
    ENSURE(jc_track_raw_alloc(&raw, -1, 1) == JC_EINVAL && jc_track_raw_alloc(&raw, 5, JC_TRACK_MAX_TRACKS + 1) == JC_EINVAL);
    ENSURE(jc_track_raw_alloc(&raw, 5, 2) == JC_OK && isnan(raw.t_s[4]) && isnan(raw.tracks[1].y_m[4]));
    jc_track_raw_free(&raw);
    ENSURE(video(&t, 6u) == JC_OK);
    const jc_Setup s = jc_paper_setup();
    const jc_SimOptions o = jc_default_sim_options();
    jc_TrackFitResult r;
    jc_TrackFitOptions fo = mu_k_and_e();
    fo.free_count = JC_FIT_MAX_PARAMS + 1;
    ENSURE(jc_track_fit(&s, &t, &fo, &o, &r, err, sizeof err) == JC_EINVAL);
    printf("too many values: %s\n", err);
    fo = mu_k_and_e();
    fo.free[1] = (jc_TrackFitParam){JC_FIT_PART_MASS, 7}; /* the paper's body has 2 parts */
    ENSURE(jc_track_fit(&s, &t, &fo, &o, &r, err, sizeof err) == JC_EINVAL);
    printf("a part not there: %s\n", err);
    fo = mu_k_and_e();
    fo.max_iter = 0;
    ENSURE(jc_track_fit(&s, &t, &fo, &o, &r, err, sizeof err) == JC_EINVAL);
    jc_TrackCompare c;
    ENSURE(jc_track_compare(&s, &t, &o, JC_TRACK_START_TRACKED, 5.0, NAN, 0.0, &c, err, sizeof err) == JC_EINVAL);
    printf("an empty window: %s\n", err);
    ENSURE(c.x_m == NULL);
    jc_track_free(&t);
    jc_TrackSynthOptions so = synth_camera(0.0, 1e-3, JC_TRACK_SYNTH_BOTH, 1u, 0.05);
    ENSURE(jc_track_synthesize(&s, &so, &t, err, sizeof err) == JC_EINVAL && t.t_s == NULL);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_progress);
    RUN_TEST(test_stop);
    RUN_TEST(test_param_names);
    RUN_TEST(test_model_path);
    RUN_TEST(test_caller_arrays);
    RUN_TEST(test_bad_inputs);
    TEST_MAIN_END();
}
