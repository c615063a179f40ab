/* jumpcyl animate end to end (argv[1] is the built tool), on small frames:
 * one frame per 1/(fps slowmo) of simulated time, numbered PNG files of the
 * asked size; GIF and MP4 files from ffmpeg; without ffmpeg the frames are
 * kept and the message gives the ffmpeg command; bad input exits 2. */
#include "fig_common.h"

#include <gsl/gsl_errno.h>
#include <jumpcyl/jumpcyl.h>

#define PI 3.14159265358979323846

static const char *cli;
static char dir[1024];

static int run_ok(const char *args)
{
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 0;
    if (!ok) fprintf(stderr, "'%s': status %d, stderr: %s\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    return ok;
}

/* The film holds its last picture this long after the motion (animate.c). */
#define HOLD_S 0.5

/* The frames a run of the paper's cylinder on 45 degrees should give: one
 * per 1/(fps slowmo) of the run (it ends at the ramp's end), then the hold. */
static int expected_frames(double fps, double slowmo)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 45 * PI / 180;
    jc_Model m;
    char err[256];
    if (jc_model_init(&m, &s, err, sizeof err) != JC_OK) return -1;
    jc_SimOptions o = jc_default_sim_options();
    jc_Run run;
    const int st = jc_simulate(&m, &o, &run, err, sizeof err);
    const double t_end = run.final_state.t_s;
    jc_run_free(&run);
    return st == JC_OK ? (int)floor(t_end * fps * slowmo * (1 + 1e-12)) + 1 + (int)ceil(HOLD_S * fps - 1e-9) : -1;
}

/* The follow camera still works: frames of the same count. */
static int test_follow_camera(void)
{
    char out[1100], args[2048];
    snprintf(out, sizeof out, "%s/follow/", dir);
    snprintf(args, sizeof args, "animate --incline 45 --camera follow --size 160x90 --fps 10 --slowmo 2 --output '%s'",
             out);
    ENSURE(run_ok(args));
    ENSURE(fig_count_entries(out) == expected_frames(10, 2));
    return 0;
}

static int test_frames_directory(void)
{
    char out[1100], args[2048], frame[1200];
    snprintf(out, sizeof out, "%s/frames/", dir);
    snprintf(args, sizeof args, "animate --incline 45 --size 160x90 --fps 10 --slowmo 2 --output '%s'", out);
    ENSURE(run_ok(args));
    const int want = expected_frames(10, 2);
    ENSURE_MSG(fig_count_entries(out) == want, "%d frames, want %d", fig_count_entries(out), want);
    for (int i = 0; i < want; ++i) {
        int w, h;
        snprintf(frame, sizeof frame, "%sframe-%05d.png", out, i);
        ENSURE_MSG(fig_png_size(frame, &w, &h) == 0 && w == 160 && h == 90, "%s", frame);
    }
    /* Again into the same directory: its frames are replaced, not added to. */
    snprintf(args, sizeof args, "animate --incline 45 --size 160x90 --fps 5 --slowmo 2 --output '%s'", out);
    ENSURE(run_ok(args));
    ENSURE(fig_count_entries(out) == expected_frames(5, 2));
    return 0;
}

static int test_gif_and_mp4(void)
{
    char out[1100], args[2048];
    unsigned char head[8];
    snprintf(out, sizeof out, "%s/film.gif", dir);
    snprintf(args, sizeof args, "animate --incline 45 --size 160x90 --fps 10 --slowmo 2 --output '%s'", out);
    ENSURE(run_ok(args));
    ENSURE(fig_head(out, head, 6) == 0 && memcmp(head, "GIF89a", 6) == 0);
    ENSURE(fig_file_size(out) > 2000);
    snprintf(out, sizeof out, "%s/film.mp4", dir);
    snprintf(args, sizeof args, "animate --incline 45 --size 161x91 --fps 10 --slowmo 2 --output '%s'", out);
    ENSURE(run_ok(args));
    ENSURE(fig_head(out, head, 8) == 0 && memcmp(head + 4, "ftyp", 4) == 0);
    ENSURE(fig_file_size(out) > 2000);
    return 0;
}

static int test_missing_ffmpeg(void)
{
    char out[1100], args[2048], frames[1200];
    snprintf(out, sizeof out, "%s/noff.gif", dir);
    snprintf(args, sizeof args, "animate --incline 45 --size 160x90 --fps 10 --slowmo 1 --output '%s'", out);
    if (fig_without_tools(cli, dir, args, out, "ffmpeg was not found", "ffmpeg -nostdin -y -framerate 10", 0))
        return 1;
    snprintf(frames, sizeof frames, "%s/noff-frames", dir);
    ENSURE_MSG(fig_count_entries(frames) == expected_frames(10, 1), "%d frames kept", fig_count_entries(frames));
    return 0;
}

static int usage_error(const char *opts, const char *needle)
{
    char out[1100], args[2048];
    snprintf(out, sizeof out, "%s/bad.gif", dir);
    snprintf(args, sizeof args, "animate %s --output '%s'", opts, out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 2 && r.err && strstr(r.err, needle) && strchr(r.err, '\n') == r.err + strlen(r.err) - 1;
    if (!ok) fprintf(stderr, "'%s': status %d, stderr: %s\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE(!cli_file_exists(out));
    return 0;
}

/* The hoop preset rocks on a floor until the default 60 s limit: its film
 * stops FILM_AFTER_LANDING_S = 1 s of simulated time after its last landing
 * (computed here from the library's events), then holds HOLD_S; the frame
 * count printed before the work is the count made. With --t-max the film
 * goes to the limit asked for. */
static int test_film_ends_with_motion(void)
{
    jc_Setup s;
    jc_Model m;
    char err[256], out[1100], args[2048], want_line[64];
    ENSURE(jc_preset_setup("hoop", &s, err, sizeof err) == JC_OK && jc_model_init(&m, &s, err, sizeof err) == JC_OK);
    const jc_SimOptions o = jc_default_sim_options();
    jc_Run run;
    ENSURE(jc_simulate(&m, &o, &run, err, sizeof err) == JC_OK);
    double landed = NAN;
    for (int i = 0; i < run.event_count; ++i)
        if (run.events[i].kind == JC_EVENT_TOUCHDOWN) landed = run.events[i].state.t_s;
        else if (run.events[i].kind == JC_EVENT_LIFTOFF || run.events[i].kind == JC_EVENT_BOUNCE) landed = NAN;
    ENSURE(run.termination == JC_END_TIME_LIMIT && isfinite(landed));
    jc_run_free(&run);
    const double fps = 10, slowmo = 2, film_end = landed + 1.0;
    const int motion = (int)floor(film_end * fps * slowmo * (1 + 1e-12)) + 1, hold = (int)ceil(HOLD_S * fps - 1e-9);
    snprintf(out, sizeof out, "%s/hoop/", dir);
    snprintf(args, sizeof args, "animate --preset hoop --size 160x90 --fps 10 --slowmo 2 --output '%s'", out);
    cli_result r = cli_run_line(cli, NULL, args);
    snprintf(want_line, sizeof want_line, "Film: %d frames", motion + hold);
    const int said = r.status == 0 && r.out && strstr(r.out, want_line);
    if (!said) fprintf(stderr, "status %d, stdout: %s, want '%s'\n", r.status, r.out ? r.out : "?", want_line);
    cli_result_free(&r);
    ENSURE(said);
    ENSURE_MSG(fig_count_entries(out) == motion + hold, "%d frames, want %d", fig_count_entries(out), motion + hold);
    /* The last frame of the motion is within one frame of the end; the film
     * lasts at most HOLD_S longer. */
    ENSURE((motion - 1) / (fps * slowmo) <= film_end && film_end - (motion - 1) / (fps * slowmo) < 1 / (fps * slowmo));
    ENSURE((motion + hold) / fps - film_end * slowmo <= HOLD_S + 1 / fps);
    snprintf(args, sizeof args, "animate --preset hoop --t-max 2.5 --size 160x90 --fps 10 --slowmo 2 --output '%s'",
             out);
    ENSURE(run_ok(args));
    ENSURE_MSG(fig_count_entries(out) == 51 + hold, "%d frames with --t-max 2.5", fig_count_entries(out));
    return 0;
}

/* A body at rest in equilibrium at the start (the paper's cylinder on a
 * floor, its mass straight above the centre) is filmed as one still
 * picture and the hold: the run ends at t = 0, and the film's time limit
 * is not set to that 0. */
static int test_film_of_rest(void)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 0.0;
    jc_Model m;
    char err[256], out[1100], args[2048];
    ENSURE(jc_model_init(&m, &s, err, sizeof err) == JC_OK);
    const jc_SimOptions o = jc_default_sim_options();
    jc_Run run;
    ENSURE(jc_simulate(&m, &o, &run, err, sizeof err) == JC_OK);
    const int at_rest = run.termination == JC_END_REST && run.final_state.t_s == 0.0;
    jc_run_free(&run);
    ENSURE(at_rest);
    snprintf(out, sizeof out, "%s/rest/", dir);
    snprintf(args, sizeof args, "animate --incline 0 --size 160x90 --fps 10 --slowmo 2 --output '%s'", out);
    ENSURE(run_ok(args));
    const int want = 1 + (int)ceil(HOLD_S * 10 - 1e-9);
    ENSURE_MSG(fig_count_entries(out) == want, "%d frames, want %d", fig_count_entries(out), want);
    return 0;
}

static int test_bad_input(void)
{
    if (usage_error("--camera xyz", "--camera 'xyz' is not a camera (allowed: fixed, follow)")) return 1;
    if (usage_error("--fps 0", "'0'") || usage_error("--fps 1000", "'1000'") || usage_error("--slowmo 0", "'0'") ||
        usage_error("--slowmo -2", "'-2'") || usage_error("--size 12x5", "'12x5'") ||
        usage_error("--size wide", "'wide'") || usage_error("--sample-dt 0.1", "--sample-dt"))
        return 1;
    char args[2048], out[1100];
    snprintf(out, sizeof out, "%s/film.avi", dir);
    snprintf(args, sizeof args, "animate --output '%s'", out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 2 && r.err && strstr(r.err, ".avi");
    cli_result_free(&r);
    ENSURE(ok && !cli_file_exists(out));
    return 0;
}

int main(int argc, char **argv)
{
    const int rc = fig_main_begin(argc, argv, "animate", &cli, dir, sizeof dir);
    if (rc != 0) return rc;
    RUN_TEST(test_frames_directory);
    RUN_TEST(test_gif_and_mp4);
    RUN_TEST(test_follow_camera);
    RUN_TEST(test_missing_ffmpeg);
    RUN_TEST(test_film_ends_with_motion);
    RUN_TEST(test_film_of_rest);
    RUN_TEST(test_bad_input);
    fig_main_end(dir);
    TEST_MAIN_END();
}
