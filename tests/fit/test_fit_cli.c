/* compare and fit against synthetic videos whose truth is known (issue 26):
 *  - a noise-free video compared from the setup's start: the model to the
 *    interpolation's level, the lift-off of `simulate`;
 *  - mis-clicked frames: the linear fit says misfit, the Cauchy loss sets
 *    them aside;
 *  - a value the video does not determine is flagged and held;
 *  - a wrong body gives the misfit verdict (exit 3), and freeing the body
 *    value finds the right one;
 *  - a hand's push before the free motion is found and left out;
 *  - a wrong --incline is refused naming the video's;
 *  - bad option values: one line, exit 2, no file;
 *  - a stop signal ends a long fit at once, without a report. */
#include <jumpcyl/track.h>
#include "../track/synth_table.h"
#include "../cli_run.h"
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>

static jc_Setup truth(void)
{
    jc_Setup s = jc_paper_setup();
    s.mu_kinetic = 0.4;
    return s;
}

/* The run of simulate: the same setup from its own start. */
static int simulate_liftoff(const jc_Setup *s, double *x, double *t)
{
    jc_Model m;
    char err[256];
    jc_Run run;
    const jc_SimOptions o = jc_default_sim_options();
    if (jc_model_init(&m, s, err, sizeof err) != JC_OK || jc_simulate(&m, &o, &run, err, sizeof err) != JC_OK) {
        jc_run_free(&run);
        return -1;
    }
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    *x = sum.first_liftoff_state.x_m;
    *t = sum.first_liftoff_state.t_s;
    jc_run_free(&run);
    return sum.first_liftoff >= 0 ? 0 : -1;
}

static int test_noise_free_compare(void)
{
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 0.0, JC_TRACK_SYNTH_BOTH, 1u, 0.055);
    jc_Track t;
    char err[256];
    ENSURE_MSG(jc_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    printf("noise-free video: incline measured %.12f deg (true 30)\n", t.incline_rad * 180 / SYNTH_PI);
    ENSURE_NEAR(t.incline_rad, s.incline_rad, 1e-9);
    double x_sim, t_sim;
    ENSURE(simulate_liftoff(&s, &x_sim, &t_sim) == 0);
    const jc_SimOptions o = jc_default_sim_options();
    jc_TrackCompare c;
    /* From the setup's own start: the same run, sampled at the frames. */
    ENSURE_MSG(jc_track_compare(&s, &t, &o, JC_TRACK_START_SETUP, NAN, NAN, 0.0, &c, err, sizeof err) == 0, "%s", err);
    printf("hops: %d measured, %d simulated\n", c.measured.hops, c.simulated.hops);
    printf("setup start: RMS path %.3g m (largest %.3g), theta %.3g rad; lift-off %.12g m at %.12g s (simulate "
           "%.12g m at %.12g s)\n",
           c.rms_path_m, c.max_path_m, c.rms_theta_rad, c.model_liftoff_x_m, c.model_liftoff_t_s, x_sim, t_sim);
    const int ok1 = c.max_path_m < 1e-6 && c.rms_theta_rad < 1e-6 && fabs(c.model_liftoff_x_m - x_sim) < 1e-9 &&
                    fabs(c.model_liftoff_t_s - t_sim) < 1e-9 && c.measured.hops == c.simulated.hops &&
                    c.measured.hops >= 1;
    jc_track_compare_free(&c);
    /* From the state the frames show (fitted to the first 0.4 s). */
    ENSURE_MSG(jc_track_compare(&s, &t, &o, JC_TRACK_START_TRACKED, NAN, NAN, 0.0, &c, err, sizeof err) == 0, "%s", err);
    printf("tracked start: frame %ld, RMS path %.3g m (largest %.3g); lift-off %.9g m\n", c.launch.frame, c.rms_path_m,
           c.max_path_m, c.model_liftoff_x_m);
    const int ok2 = c.launch.frame == 0 && c.max_path_m < 1e-5 && fabs(c.model_liftoff_x_m - x_sim) < 1e-5 &&
                    c.measured.hops == c.simulated.hops;
    jc_track_compare_free(&c);
    /* Frames off the simulator's grid (the clip starts 4.1 ms after the
     * release): the cubic Hermite interpolation between samples is what is
     * compared, to below a micron. */
    for (long i = 0; i < t.n; ++i) t.t_s[i] += 0.0041;
    ENSURE_MSG(jc_track_compare(&s, &t, &o, JC_TRACK_START_SETUP, NAN, NAN, 0.0, &c, err, sizeof err) == 0, "%s", err);
    printf("off the grid: largest path residual %.3g m, theta RMS %.3g rad\n", c.max_path_m, c.rms_theta_rad);
    const int ok3 = c.max_path_m > 0.0 && c.max_path_m < 1e-6 && c.rms_theta_rad < 1e-5;
    jc_track_compare_free(&c);
    jc_track_free(&t);
    ENSURE(ok1);
    ENSURE(ok2);
    ENSURE(ok3);
    return 0;
}

static jc_TrackFitOptions fit_options(void)
{
    jc_TrackFitOptions fo;
    jc_fit_options_default(&fo);
    fo.free[0] = (jc_TrackFitParam){JC_FIT_MU_K, -1};
    fo.free[1] = (jc_TrackFitParam){JC_FIT_RESTITUTION, -1};
    fo.free_count = 2;
    fo.profiles = 0;
    return fo;
}

static int slot(const jc_TrackFitResult *r, jc_TrackFitKind k)
{
    for (int i = 0; i < r->count; ++i)
        if (r->param[i].kind == k) return i;
    return -1;
}

/* Four mis-clicked frames (2 cm off) in a video with 10 % of its frames
 * dropped: the linear fit's verdict is a misfit and its sigma swell; the
 * Cauchy loss sets them aside (the truth within 3 sigma of it). */
static int test_robust_loss(void)
{
    const jc_Setup s = truth();
    jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 5u, 0.055);
    so.drop_fraction = 0.1;
    jc_Track t;
    char err[256];
    ENSURE_MSG(jc_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    ENSURE(t.gaps > 0);
    const long bad[] = {10, 25, 40, 55};
    for (int k = 0; k < 4; ++k) {
        t.x_m[bad[k]] += 0.02;
        t.y_m[bad[k]] -= 0.01;
    }
    jc_Setup guess = s;
    guess.mu_kinetic = 0.35;
    guess.restitution = 0.4;
    const jc_SimOptions o = jc_default_sim_options();
    jc_TrackFitOptions fo = fit_options();
    jc_TrackFitResult lin, cau;
    const int rc1 = jc_track_fit(&guess, &t, &fo, &o, &lin, err, sizeof err);
    fo.loss = JC_FIT_LOSS_CAUCHY;
    const int rc2 = rc1 == 0 ? jc_track_fit(&guess, &t, &fo, &o, &cau, err, sizeof err) : -1;
    jc_track_free(&t);
    ENSURE_MSG(rc1 == 0 && rc2 == 0, "%s", err);
    const int k = slot(&lin, JC_FIT_MU_K), e = slot(&lin, JC_FIT_RESTITUTION);
    printf("linear: chi2/dof %.2f, mu_k %.5f +- %.5f, e %.5f +- %.5f; %s\n", lin.chi2_dof, lin.value[k], lin.sigma[k],
           lin.value[e], lin.sigma[e], lin.verdict);
    printf("cauchy: chi2/dof %.2f, mu_k %.5f +- %.5f, e %.5f +- %.5f\n", cau.chi2_dof, cau.value[k], cau.sigma[k],
           cau.value[e], cau.sigma[e]);
    ENSURE(lin.misfit && lin.chi2_dof > 5.0 && cau.chi2_dof < 2.0);
    ENSURE(lin.sigma[k] > 2.0 * cau.sigma[k] && lin.sigma[e] > 2.0 * cau.sigma[e]);
    ENSURE(fabs(cau.value[k] - 0.4) < 3.0 * cau.sigma[k] && fabs(cau.value[e] - 0.3) < 3.0 * cau.sigma[e]);
    return 0;
}

/* Restitution acts only through landings: in the frames before the first
 * lift-off (0.76 s) it changes nothing, and the fit must say so and hold it
 * (its sigma cannot be had), fitting mu_k alone; the verdict stays good. */
static int test_undetermined_flagged(void)
{
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 7u, 0.055);
    jc_Track t;
    char err[256];
    ENSURE_MSG(jc_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    jc_TrackFitOptions fo = fit_options();
    fo.to_s = 0.7;
    fo.profiles = 1;
    const jc_SimOptions o = jc_default_sim_options();
    jc_TrackFitResult r;
    const int rc = jc_track_fit(&s, &t, &fo, &o, &r, err, sizeof err);
    jc_track_free(&t);
    ENSURE_MSG(rc == 0, "%s", err);
    const int e = slot(&r, JC_FIT_RESTITUTION), k = slot(&r, JC_FIT_MU_K);
    printf("before the lift-off: restitution %s (%s), held at %.3g; mu_k %.5f +- %.5f; %s\n",
           r.flag[e] ? "flagged" : "determined", jc_fit_flag_text(r.flag[e]), r.value[e], r.value[k], r.sigma[k],
           r.verdict);
    ENSURE(r.flag[e] != JC_FIT_DETERMINED && r.flag[k] == JC_FIT_DETERMINED && !r.misfit);
    ENSURE(fabs(r.value[k] - 0.4) < 3.0 * r.sigma[k]);
    return 0;
}

/* The value of a fit's report line "  NAME  initial  fitted +- sigma". */
static int reported(const char *out, const char *name, double *v, double *s)
{
    char key[64];
    snprintf(key, sizeof key, "\n  %s ", name);
    const char *p = out ? strstr(out, key) : NULL;
    return p && sscanf(p + strlen(key), "%*g %lg +- %lg", v, s) == 2 ? 0 : -1;
}

/* The paper's cylinder with its rod 1 cm too far in (4.5 cm): the fit of
 * friction, restitution and the start cannot follow the video, and says
 * so (exit 3; 0 with --allow-misfit). Freeing the rod's offset finds the
 * true 5.5 cm, and the verdict is good. */
static int test_wrong_body(void)
{
    char dir[] = "/tmp/jc_fit_cli_XXXXXX", track[256];
    ENSURE(cli_scratch(dir, track, sizeof track, "track.txt") == 0);
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 3u, 0.055);
    ENSURE(synth_table_write(track, &s, &so, NULL) == 0);
    const char *wrong[] = {"fit", "--track", track, "--rod-offset", "4.5cm", "--mu-k", "0.4", "--free", "mu_k,restitution", NULL};
    cli_result r = cli_run(wrong);
    const int misfit = r.status == 3 && r.out && strstr(r.out, "the model does not describe this video") &&
                       !strstr(r.out, "converged") && cli_one_line(r.err);
    printf("rod 1 cm too far in: exit %d; %s", r.status, r.out && strstr(r.out, "Verdict") ? strstr(r.out, "Verdict") : "\n");
    cli_result_free(&r);
    const char *allowed[] = {"fit", "--track", track, "--rod-offset", "4.5cm", "--mu-k", "0.4", "--free",
                             "mu_k,restitution", "--allow-misfit", NULL};
    r = cli_run(allowed);
    const int allowed_ok = r.status == 0 && r.out && strstr(r.out, "the model does not describe this video");
    cli_result_free(&r);
    const char *freed[] = {"fit", "--track", track, "--rod-offset", "4.5cm", "--mu-k", "0.4", "--free",
                           "mu_k,restitution,rod_offset", NULL};
    r = cli_run(freed);
    double off = NAN, sig = NAN;
    /* the report spells the names as the options do, whichever --free was given */
    const int found = reported(r.out, "rod-offset", &off, &sig) == 0;
    printf("rod-offset freed: exit %d, %.5f +- %.5f m (true 0.055)\n", r.status, off, sig);
    const int freed_ok = r.status == 0 && found && fabs(off - 0.055) < 3.0 * sig && sig < 0.002;
    cli_result_free(&r);
    remove(track);
    rmdir(dir);
    ENSURE(misfit);
    ENSURE(allowed_ok);
    ENSURE(freed_ok);
    return 0;
}

/* A hand pushes the hoop for 0.2 s before it rolls free: compare finds the
 * free motion's first frame (within a frame of 0.2 s) and follows the video
 * from there; started at the first frame it would not. */
static int test_launch_found(void)
{
    jc_Setup s;
    char err[256];
    ENSURE(jc_preset_setup("hoop", &s, err, sizeof err) == JC_OK);
    s.mu_static = s.mu_kinetic = 0.8;
    jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 11u, 0.055);
    so.mark_radius_m = 0.1;
    so.t_end_s = 1.0;
    so.hand_s = 0.2;
    jc_Track t;
    ENSURE_MSG(jc_track_synthesize(&s, &so, &t, err, sizeof err) == 0, "%s", err);
    const jc_SimOptions o = jc_default_sim_options();
    jc_TrackCompare c;
    ENSURE_MSG(jc_track_compare(&s, &t, &o, JC_TRACK_START_TRACKED, NAN, NAN, 0.0, &c, err, sizeof err) == 0, "%s", err);
    const double t_free = t.t_s[c.launch.frame];
    printf("hand for 0.2 s: free motion from t = %.4f s (frame %ld, %ld pushed, chi2/dof %.3g with them, %.3g "
           "without); path RMS %.2f mm at sigma %.2f mm\n",
           t_free, c.launch.frame, c.launch.pushed, c.launch.chi2_dof_with, c.launch.chi2_dof, c.rms_path_m * 1e3,
           t.sigma_m * 1e3);
    const int ok = fabs(t_free - 0.2) <= 1.01 / 60.0 && c.rms_path_m < 3.0 * t.sigma_m && c.launch.chi2_dof_with > 10;
    jc_track_compare_free(&c);
    jc_track_free(&t);
    ENSURE(ok);
    return 0;
}

/* Whether a wrong incline's refusal names the video's: "disagrees with the
 * video: the centres in contact lie on a line at V +- S deg", with the
 * truth within 3 S of V. */
static int names_true_incline(const char *err, double truth_deg)
{
    const char *p = err && strstr(err, "disagrees") ? strstr(err, "lie on a line at ") : NULL;
    double v = NAN, sd = NAN;
    if (!p || sscanf(p, "lie on a line at %lf +- %lf deg", &v, &sd) != 2) return 0;
    printf("wrong incline refused: the video's %.4g +- %.2g deg (true %g)\n", v, sd, truth_deg);
    return sd > 0.0 && fabs(v - truth_deg) <= 3.0 * sd;
}

static int test_bad_options(void)
{
    char dir[] = "/tmp/jc_fit_cli_XXXXXX", track[256], fig[256];
    ENSURE(cli_scratch(dir, track, sizeof track, "track.txt") == 0);
    snprintf(fig, sizeof fig, "%s/out.png", dir);
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 1e-3, JC_TRACK_SYNTH_BOTH, 1u, 0.055);
    ENSURE(synth_table_write(track, &s, &so, NULL) == 0);
    /* Each case: the arguments, and whether it gives an incline the video
     * refuses (the refusal must then name the video's, which holds the
     * truth within 3 of its sigma). */
    const struct {
        const char *args[14];
        int wrong_incline;
    } cases[] = {
        {{"fit", "--track", track, "--output", fig, NULL}, 0}, /* no --free */
        {{"fit", "--track", track, "--free", "mu_q", "--output", fig, NULL}, 0}, /* unknown value */
        {{"fit", "--track", track, "--free", "mu_k,mu_k", "--output", fig, NULL}, 0}, /* twice */
        {{"fit", "--track", track, "--free", "point_mass", "--output", fig, NULL}, 0}, /* no such part */
        {{"fit", "--track", track, "--free", "mu_k", "--loss", "square", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--max-iter", "0", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--max-iter", "2.5", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--starts", "0", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--sigma", "-1mm", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--from", "1", "--to", "0.5", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--mark-angle", "1000", "--output", fig, NULL}, 0},
        {{"fit", "--track", track, "--free", "mu_k", "--incline", "25", "--output", fig, NULL}, 1}, /* wrong incline */
        {{"compare", "--output", fig, NULL}, 0}, /* no --track */
        {{"compare", "--track", track, "--axes", "tilted", "--output", fig, NULL}, 0},
        {{"compare", "--track", track, "--from", "-1", "--output", fig, NULL}, 0},
        {{"compare", "--track", track, "--hop-sigmas", "0.5", "--output", fig, NULL}, 0},
        {{"compare", "--track", track, "--output", "out.gif", NULL}, 0},
        {{"compare", "--track", track, "--from", "1.29", "--output", fig, NULL}, 0}, /* 1 frame */
        {{"compare", "--track", "/nonexistent/t.txt", "--output", fig, NULL}, 0},
        {{"compare", "--track", track, "--mu-k", "0.6", "--output", fig, NULL}, 0}, /* mu_k > mu_s */
        {{"compare", "--track", track, "--incline", "35", "--output", fig, NULL}, 1}, /* wrong incline */
        {{"compare", "--track", track, "--axes", "incline", "--output", fig, NULL}, 0}, /* axes off the ramp */
    };
    int bad = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const char *const *args = cases[i].args;
        cli_result r = cli_run(args);
        if (r.status != 2 || !cli_one_line(r.err) || cli_file_exists(fig)) {
            fprintf(stderr, "case %zu (%s %s %s %s %s ...): status %d, stderr '%s', figure %s\n", i, args[0], args[1],
                    args[2] ? args[2] : "", args[3] ? args[3] : "", args[3] && args[4] ? args[4] : "", r.status,
                    r.err ? r.err : "", cli_file_exists(fig) ? "written" : "absent");
            bad = 1;
        }
        if (cases[i].wrong_incline && !names_true_incline(r.err, s.incline_rad * 180 / SYNTH_PI)) {
            fprintf(stderr, "case %zu: the refusal does not name the video's incline: '%s'\n", i, r.err ? r.err : "");
            bad = 1;
        }
        cli_result_free(&r);
    }
    /* The same track and options that work: exit 0, the figure written. */
    const char *good[] = {"fit", "--track", track, "--mu-k", "0.35", "--free", "mu_k,restitution", "--output", fig, NULL};
    cli_result r = cli_run(good);
    const int good_ok = r.status == 0 && cli_file_exists(fig) && strstr(r.out, "chi2/dof") &&
                        strstr(r.out, "Predicted first lift-off") && strstr(r.out, "the model describes this video");
    if (!good_ok) fprintf(stderr, "good fit: status %d, stderr '%s'\n", r.status, r.err ? r.err : "");
    cli_result_free(&r);
    remove(fig);
    remove(track);
    rmdir(dir);
    ENSURE(!bad);
    ENSURE(good_ok);
    return 0;
}

/* The same through the tool and a Tracker table (7 digits): the path to
 * the table's rounding, the lift-off of simulate to a micron. */
static int test_noise_free_compare_tool(void)
{
    char dir[] = "/tmp/jc_fit_cli_XXXXXX", track[256];
    ENSURE(cli_scratch(dir, track, sizeof track, "track.txt") == 0);
    const jc_Setup s = truth();
    const jc_TrackSynthOptions so = synth_camera(60.0, 0.0, JC_TRACK_SYNTH_BOTH, 1u, 0.055);
    ENSURE(synth_table_write(track, &s, &so, NULL) == 0);
    const char *args[] = {"compare", "--track", track, "--mu-k", "0.4", "--from-setup-start", NULL};
    cli_result r = cli_run(args);
    remove(track);
    rmdir(dir);
    const char *rms = r.out ? strstr(r.out, "centre's path: RMS ") : NULL;
    const char *ev = r.out ? strstr(r.out, "model's own lift-off event") : NULL;
    double rms_mm = NAN, x_cm = NAN, x_sim, t_sim;
    if (rms) rms_mm = strtod(rms + strlen("centre's path: RMS "), NULL);
    if (ev && (ev = strstr(ev, "x = "))) x_cm = strtod(ev + 4, NULL);
    ENSURE(simulate_liftoff(&s, &x_sim, &t_sim) == 0);
    printf("tool: RMS %.4f mm, lift-off %.2f cm (simulate %.4f cm)\n", rms_mm, x_cm, x_sim * 100);
    const int ok = r.status == 0 && rms_mm < 0.01 && fabs(x_cm - x_sim * 100) < 0.01;
    cli_result_free(&r);
    ENSURE(ok);
    return 0;
}

/* The sample experiments of examples/tracker (docs/tracker.md; the
 * directory in JC_EXAMPLES_DIR), fitted as the docs fit them: exit 0, the
 * verdict good, the known values within 3 of their sigma. The examples
 * numbered in `which` (0 to 3, in the order of runs[] below). */
static const char *examples_dir;

static int check_examples(const int *which, int count)
{
    /* ctest sets it (tests/fit/CMakeLists.txt): unset, the examples would
     * go untested and the test pass all the same. */
    ENSURE_MSG(examples_dir && *examples_dir, "JC_EXAMPLES_DIR is not set: the examples' directory");
    char incline[512], floor[512], led[512];
    snprintf(incline, sizeof incline, "%s/incline.trk", examples_dir);
    snprintf(floor, sizeof floor, "%s/floor.trk", examples_dir);
    snprintf(led, sizeof led, "%s/floor-led.txt", examples_dir);
    const char *a[] = {"fit", "--track", incline, "--free", "mu_s,mu_k,restitution", NULL};
    const char *b[] = {"fit", "--track", floor, "--preset", "hoop", "--free", "mu_s,mu_k,restitution", NULL};
    /* The ring never slides: mu_k does not change the residuals, and is held. */
    const char *c[] = {"fit", "--track", led, "--preset", "hoop", "--part", "hoop:mass=0.1", "--part",
                       "point:mass=0.1,offset=0.1", "--mu", "0.8", "--free", "mu_k", NULL};
    /* The start held at its fit to the first 0.4 s. */
    const char *d[] = {"fit", "--track", incline, "--free", "mu_k,restitution", "--hold-start", NULL};
    const char *const *runs[] = {a, b, c, d};
    const char *names[4][2] = {{"mu-k", "restitution"}, {"mu-k", "restitution"}, {NULL, NULL}, {"mu-k", "restitution"}};
    const double known[4][2] = {{0.4, 0.3}, {0.5, 0.3}, {0, 0}, {0.4, 0.3}};
    int bad = 0;
    for (int i = 0; i < count; ++i) {
        const int k = which[i];
        cli_result r = cli_run(runs[k]);
        int ok = r.status == 0 && r.out && strstr(r.out, "the model describes this video");
        if (k == 2) ok = ok && strstr(r.out, "mu-k: the residuals do not change with it");
        if (k == 0) {
            /* The model's incline: the paper's 30 deg within 3 of its sigma. */
            const char *line = r.out ? strstr(r.out, "Incline in the model: ") : NULL;
            double v = NAN, sd = NAN;
            const int found = line && sscanf(line, "Incline in the model: %lf +- %lf", &v, &sd) == 2;
            printf("example 0: incline in the model %.4f +- %.4f deg (true 30)\n", v, sd);
            ok = ok && found && fabs(v - 30.0) <= 3.0 * sd;
        }
        for (int j = 0; j < 2 && names[k][j]; ++j) {
            double v = NAN, s = NAN;
            const int found = reported(r.out, names[k][j], &v, &s) == 0;
            printf("example %d: %s = %.5g +- %.2g (true %g)\n", k, names[k][j], v, s, known[k][j]);
            ok = ok && found && fabs(v - known[k][j]) <= 3.0 * s;
        }
        if (!ok) fprintf(stderr, "example %d: status %d\n%s\n%s\n", k, r.status, r.out ? r.out : "", r.err ? r.err : "");
        bad += !ok;
        cli_result_free(&r);
    }
    ENSURE(bad == 0);
    return 0;
}

static int test_examples(void)
{
    static const int which[] = {0, 2, 3};
    return check_examples(which, 3);
}

/* The hoop on a floor with mu_s free: a fit of about 15 s (its profile of
 * mu_s), one of the long tests (tests/CMakeLists.txt). */
static int test_example_hoop_floor(void)
{
    static const int which[] = {1};
    return check_examples(which, 1);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The hoop on a floor with mu_s free takes 13 s (its profile of mu_s):
 * SIGTERM after 1.5 s ends it at the fit's next iteration (the progress
 * callback tells the library to stop), exit 143, no report. Before, the
 * fit ran to its end and printed it. */
static int test_stop_signal(void)
{
    ENSURE(examples_dir && *examples_dir);
    char floor[512];
    snprintf(floor, sizeof floor, "%s/floor.trk", examples_dir);
    const char *args[] = {"fit", "--track", floor, "--preset", "hoop", "--free", "mu_s,mu_k,restitution", NULL};
    char out_tmp[64], err_tmp[64];
    const pid_t pid = cli_run_start(args, NULL, out_tmp, err_tmp);
    ENSURE(pid > 0);
    const struct timespec wait = {1, 500000000L};
    nanosleep(&wait, NULL);
    const double sent = now_s();
    kill(pid, SIGTERM);
    cli_result r = cli_run_wait(pid, out_tmp, err_tmp, 1);
    const double took = now_s() - sent;
    printf("SIGTERM during a fit: exit %d %.3f s after the signal, %zu bytes of report\n", r.status, took,
           r.out ? strlen(r.out) : 0);
    const int ok = r.status == 143 && took < 3.0 && r.out && r.out[0] == '\0';
    cli_result_free(&r);
    ENSURE(ok);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    examples_dir = getenv("JC_EXAMPLES_DIR");
    if (cli_run_init(argc, argv) != 0) return 2;
    RUN_TEST(test_noise_free_compare);
    RUN_TEST(test_robust_loss);
    RUN_TEST(test_undetermined_flagged);
    RUN_TEST(test_launch_found);
    RUN_TEST(test_noise_free_compare_tool);
    RUN_TEST(test_wrong_body);
    RUN_TEST(test_bad_options);
    RUN_TEST(test_examples);
    RUN_TEST(test_example_hoop_floor);
    RUN_TEST(test_stop_signal);
    TEST_MAIN_END();
}
