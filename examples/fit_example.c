/* Friction and restitution from a tracked video, with the library: the
 * paper's cylinder filmed on its 30 degree incline and tracked in Tracker
 * (examples/tracker/incline.trk), read and fitted as
 * `jumpcyl fit --track FILE --free mu_k,restitution` does.
 * Usage: fit_example [FILE.trk] */
#include <jumpcyl/jumpcyl.h>
#include <jumpcyl/track.h>
#include <gsl/gsl_errno.h>
#include <stdio.h>

/* Called at every descent and iteration of the fit; 0: go on. */
static int progress(void *ctx, const jc_TrackFitProgress *p)
{
    int *calls = ctx;
    ++*calls;
    (void)p; /* p->stage, p->descents, p->fraction: for a progress bar */
    return 0;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "examples/tracker/incline.trk";
    gsl_set_error_handler_off(); /* GSL's failures come back as statuses */
    jc_Setup setup = jc_paper_setup(); /* the body that was filmed */
    char err[512];

    jc_TrackFitOptions fo;
    jc_fit_options_default(&fo);
    if (jc_fit_param_find(&setup, "mu_k", &fo.free[0]) != JC_OK ||
        jc_fit_param_find(&setup, "restitution", &fo.free[1]) != JC_OK)
        return 1;
    fo.free_count = 2; /* the start (x0, theta0, omega0) and the frame are fitted with them */
    int calls = 0;
    fo.progress = progress;
    fo.progress_ctx = &calls;

    jc_TrackOptions opt;
    jc_track_options_default(&opt);
    opt.radius_m = setup.body.radius_m; /* the centre is r above the surface in contact */
    opt.gravity_mps2 = setup.gravity_mps2;
    jc_Track track;
    if (jc_track_read_file(path, &opt, &track, err, sizeof err) != JC_OK) {
        fprintf(stderr, "fit_example: %s\n", err);
        return 1;
    }
    printf("%s: %ld frames at %.4g frames/s, noise %.2f mm, incline %.3f deg (%s)\n", path, track.n,
           track.frame_rate_hz, track.sigma_m * 1e3, track.incline_rad * 180 / 3.14159265358979,
           track.incline_source == JC_TRACK_INCLINE_MEASURED ? "measured" : "given or not known");
    setup.incline_rad = track.incline_rad; /* the video's incline, not the preset's */

    const jc_SimOptions sim = jc_default_sim_options();
    jc_TrackFitResult fit;
    const int st = jc_track_fit(&setup, &track, &fo, &sim, &fit, err, sizeof err);
    jc_track_free(&track);
    if (st != JC_OK) {
        fprintf(stderr, "fit_example: %s (%s)\n", err, jc_status_text(st));
        return 1;
    }
    for (int k = 0; k < fit.count; ++k) {
        char name[48];
        jc_fit_param_name(&fit.setup, fit.param[k], name, sizeof name);
        if (!fit.start_value[k]) printf("%-12s = %.5f +- %.5f\n", name, fit.value[k], fit.sigma[k]);
    }
    printf("chi2/dof = %.3f after %d descents (%d progress calls)\n", fit.chi2_dof, fit.descents, calls);
    if (fit.has_liftoff) printf("first lift-off at x = %.2f cm\n", fit.liftoff_x_m * 100);
    printf("verdict: %s\n", fit.verdict);
    return fit.misfit ? 3 : 0;
}
