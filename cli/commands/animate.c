/* jumpcyl animate: the full model's motion as a film. Frames are samples of
 * jc_simulate at dt = 1 / (fps * slowmo), drawn with cairo (draw.c) and
 * assembled with ffmpeg (video.c), or kept as numbered PNG files. The film
 * ends when the motion does (film_end_s), then holds its last picture for
 * FILM_HOLD_S of playback. */
#include "commands.h"
#include "inputs.h"
#include "figures.h" /* cli_paper_row */
#include "films.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_SIZE "960x540"
#define DEFAULT_FPS 30.0
#define DEFAULT_SLOWMO 8.0 /* a 240 fps high-speed camera played back at 30 fps */
#define MIN_SIDE 64
#define MAX_W 7680
#define MAX_H 4320
#define MAX_FPS 240.0
#define MAX_SLOWMO 10000.0
/* Frames a film may have unless --max-frames says otherwise (about three
 * minutes at 30 fps); VID_MAX_FRAMES is the most the frame names allow. */
#define DEFAULT_MAX_FRAMES 5000
/* Playback time the last picture stays after the motion ends. */
#define FILM_HOLD_S 0.5
/* A run that only reached the default time limit (a body rocking for ever
 * on a floor) is filmed to this much simulated time after its last landing. */
#define FILM_AFTER_LANDING_S 1.0

typedef struct {
    const char *output, *size, *fps, *slowmo, *max_frames, *camera;
} animate_args;

typedef struct {
    int width, height;
    int max_frames;
    double fps, slowmo;
    vid_Format format;
    film_Camera camera;
    int t_max_given; /* --t-max: film to it, even past the last landing */
    const char *output;
} animate_opts;

static void help(void)
{
    printf("Usage: jumpcyl animate --output FILE [--size WxH] [--fps F] [--slowmo K] [--camera fixed|follow]\n"
           "                       [SETUP OPTIONS] [SIMULATION OPTIONS]\n"
           "The full motion as a film: the cylinder to scale with every body part and its centre of\n"
           "mass; the ramp with a distance scale from the start contact point; marks along it for\n"
           "the model's first lift-off and, for the paper's cylinder on 15, 30 or 45 degrees, the\n"
           "paper's printed jump point and its measured band (Table 1); the centre's whole path and\n"
           "a fading recent trace; the normal force N and friction F at the contact to a stated scale\n"
           "(a scale bar in newtons); readouts of t, x, theta, omega, N, |F|/N and the mode.\n"
           "The film ends when the motion does (rest, the ramp's end, or the run's end) and holds the\n"
           "last picture for %g s; a run that only reached the default time limit (a body rocking on\n"
           "a floor) ends %g s of simulated time after its last landing (--t-max films to the limit).\n"
           "\n"
           "  --output FILE  .gif or .mp4 (made with ffmpeg), or a directory (a name ending in '/'\n"
           "                 or without extension) for numbered PNG frames frame-00000.png, ...\n"
           "  --size WxH     frame size in pixels (default %s; %d to %d by %d to %d)\n"
           "  --fps F        frames per second of playback (default %g; 0 < F <= %g)\n"
           "  --slowmo K     slow motion: K seconds of film per simulated second (default %g, a\n"
           "                 240 fps camera played at 30 fps; 0 < K <= %g). Frames are %s\n"
           "                 apart in simulated time: dt = 1/(F K).\n"
           "  --camera C     fixed (default): the laboratory's view of the whole ramp (on a floor or\n"
           "                 a very long ramp: of the way the body travels); where the body would\n"
           "                 be less than a sixth of the frame's height across, a camera follows it\n"
           "                 and an inset shows the whole ramp; follow: a camera that follows the\n"
           "                 body, without the inset\n"
           "  --max-frames N refuse a film of more than N frames (default %d; at most %d),\n"
           "                 counted (and the count printed) before any frame is drawn\n"
           "  -h, --help     this help\n"
           "\n"
           "Without ffmpeg (Debian: ffmpeg), a .gif or .mp4 is left as PNG frames in a directory\n"
           "beside it, and the message gives the ffmpeg command that assembles them.\n"
           "--sample-dt is set by --fps and --slowmo; --t-max limits the film.\n\n",
           FILM_HOLD_S, FILM_AFTER_LANDING_S, DEFAULT_SIZE, MIN_SIDE, MAX_W, MIN_SIDE, MAX_H, DEFAULT_FPS, MAX_FPS, DEFAULT_SLOWMO, MAX_SLOWMO,
           "1/(F K)", DEFAULT_MAX_FRAMES, VID_MAX_FRAMES);
}

static int take(int opt, const char *arg, void *ctx)
{
    animate_args *a = ctx;
    if (opt == 'o') return cli_take_once("animate", &a->output, "output", arg);
    if (opt == 's') return cli_take_once("animate", &a->size, "size", arg);
    if (opt == 'f') return cli_take_once("animate", &a->fps, "fps", arg);
    if (opt == 'k') return cli_take_once("animate", &a->slowmo, "slowmo", arg);
    if (opt == 'm') return cli_take_once("animate", &a->max_frames, "max-frames", arg);
    if (opt == 'c') return cli_take_once("animate", &a->camera, "camera", arg);
    return EXIT_USAGE;
}

/* The command's own options; the setup and simulation options come with cli_command_parse. */
static const struct option own[] = {{"output", required_argument, 0, 'o'}, {"size", required_argument, 0, 's'},
                                    {"fps", required_argument, 0, 'f'},    {"slowmo", required_argument, 0, 'k'},
                                    {"max-frames", required_argument, 0, 'm'}, {"camera", required_argument, 0, 'c'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* "960x540" within the allowed sizes. */
static int parse_size(const char *text, int *w, int *h)
{
    char *end;
    const long lw = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X')) return -1;
    const char *rest = end + 1;
    const long lh = strtol(rest, &end, 10);
    /* Digits only on both sides: strtol would also take blanks and signs. */
    if (end == rest || *end || !isdigit((unsigned char)text[0]) || !isdigit((unsigned char)*rest)) return -1;
    if (lw < MIN_SIDE || lw > MAX_W || lh < MIN_SIDE || lh > MAX_H) return -1;
    *w = (int)lw;
    *h = (int)lh;
    return 0;
}

/* A number in (0, max]. */
static int parse_positive(const char *name, const char *text, double max, double *out)
{
    char msg[256];
    if (cli_parse_quantity(text, Q_NUMBER, out, msg, sizeof msg) != 0 || !(*out > 0) || *out > max) {
        cli_error("animate: --%s '%s' is out of range (allowed: a number > 0 and <= %g)", name, text, max);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static int check_args(const animate_args *a, animate_opts *o)
{
    if (!a->output || !*a->output) {
        cli_error("animate: --output FILE is required (.gif, .mp4, or a directory for PNG frames)");
        return EXIT_USAGE;
    }
    if (cli_output_file_only("animate", "output", a->output, "a film or its frames") != 0) return EXIT_USAGE;
    o->output = a->output;
    if (vid_format_from_path(a->output, &o->format) != 0) {
        cli_error("animate: --output '%s': unknown format '.%s' (allowed: .gif, .mp4, or a directory: a name "
                  "ending in '/' or without extension)", a->output, cli_path_ext(a->output));
        return EXIT_USAGE;
    }
    if (parse_size(a->size ? a->size : DEFAULT_SIZE, &o->width, &o->height) != 0) {
        cli_error("animate: --size '%s' is out of range (allowed: WxH, W from %d to %d, H from %d to %d pixels)",
                  a->size, MIN_SIDE, MAX_W, MIN_SIDE, MAX_H);
        return EXIT_USAGE;
    }
    o->fps = DEFAULT_FPS;
    o->slowmo = DEFAULT_SLOWMO;
    if (a->fps && parse_positive("fps", a->fps, MAX_FPS, &o->fps)) return EXIT_USAGE;
    if (a->slowmo && parse_positive("slowmo", a->slowmo, MAX_SLOWMO, &o->slowmo)) return EXIT_USAGE;
    double max_frames = DEFAULT_MAX_FRAMES;
    char msg[256];
    if (a->max_frames && (cli_parse_quantity(a->max_frames, Q_NUMBER, &max_frames, msg, sizeof msg) != 0 ||
                          !(max_frames >= 1 && max_frames <= VID_MAX_FRAMES) || max_frames != floor(max_frames))) {
        cli_error("animate: --max-frames '%s' is out of range (allowed: a whole number from 1 to %d)", a->max_frames,
                  VID_MAX_FRAMES);
        return EXIT_USAGE;
    }
    o->max_frames = (int)max_frames;
    o->camera = FILM_CAMERA_FIXED;
    if (a->camera && strcmp(a->camera, "fixed") != 0) {
        if (strcmp(a->camera, "follow") != 0) {
            cli_error("animate: --camera '%s' is not a camera (allowed: fixed, follow)", a->camera);
            return EXIT_USAGE;
        }
        o->camera = FILM_CAMERA_FOLLOW;
    }
    return EXIT_OK;
}

static int build_inputs(cli_RunInputs *in, animate_opts *o)
{
    o->t_max_given = cli_sim_given(&in->sim_args, "t-max");
    if (cli_sim_given(&in->sim_args, "sample-dt")) {
        cli_error("animate: --sample-dt is set by --fps and --slowmo (dt = 1/(fps slowmo)); leave it out");
        return EXIT_USAGE;
    }
    const int rc = cli_run_inputs_build("animate", in);
    if (rc == EXIT_OK) in->sim.sample_dt_s = 1.0 / (o->fps * o->slowmo);
    return rc;
}

/* When the film's motion ends, from the run's events (film_end_s). */
typedef struct {
    double landed_s; /* the last landing's time; NaN: none, or in flight since */
} film_Watch;

static int watch_event(void *ctx, const jc_Event *e)
{
    film_Watch *w = ctx;
    if (e->kind == JC_EVENT_TOUCHDOWN) w->landed_s = e->state.t_s;
    else if (e->kind == JC_EVENT_LIFTOFF || e->kind == JC_EVENT_BOUNCE) w->landed_s = NAN;
    return JC_OK;
}

/* The simulated time the film shows: the whole run when it ended by itself
 * (rest, ramp end, ...) or at a --t-max someone asked for; a run that only
 * reached the default time limit (rocking for ever) is shown to
 * FILM_AFTER_LANDING_S after its last landing, when it landed. */
static double film_end_s(const jc_Run *run, const film_Watch *w, int t_max_given)
{
    const double t_end = run->final_state.t_s;
    if (run->termination != JC_END_TIME_LIMIT || t_max_given || !isfinite(w->landed_s)) return t_end;
    return fmin(t_end, w->landed_s + FILM_AFTER_LANDING_S);
}

/* Frames of the motion (one per dt from t = 0 to t_end) and of the hold. */
static double motion_frames(double t_end_s, const animate_opts *o)
{
    return floor(t_end_s * o->fps * o->slowmo * (1 + 1e-12)) + 1;
}

static int hold_frames(const animate_opts *o)
{
    return (int)ceil(FILM_HOLD_S * o->fps - 1e-9);
}

/* Frame k shows the last sample at or before k dt: the regular samples, not
 * the extra ones the run records at events (those still feed the trace).
 * The hold frames repeat the last one. */
static int select_frames(const jc_Run *run, const animate_opts *o, int **idx)
{
    const double dt = 1.0 / (o->fps * o->slowmo);
    const double n_motion = motion_frames(run->final_state.t_s, o);
    if (n_motion + hold_frames(o) > VID_MAX_FRAMES) return -(int)fmin(n_motion + hold_frames(o), 2e9);
    const int n = (int)n_motion + hold_frames(o);
    *idx = malloc(sizeof **idx * (size_t)n);
    if (!*idx) return 0;
    int j = 0;
    for (int k = 0; k < n; ++k) {
        const double t = fmin(k, n_motion - 1) * dt * (1 + 1e-12);
        while (j + 1 < run->sample_count && run->samples[j + 1].state.t_s <= t) ++j;
        (*idx)[k] = j;
    }
    return n;
}

/* The run's first lift-off, and Table 1's printed and measured jump points
 * for the paper's cylinder on one of its inclines. */
static draw_Marks make_marks(const jc_Model *m, const jc_Run *run)
{
    draw_Marks mk = {NAN, NAN, NAN, NAN};
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    if (sum.first_liftoff >= 0) mk.model_x_m = sum.first_liftoff_state.x_m;
    const jc_PaperTableRow *row = cli_paper_row(&m->setup);
    if (!row) return mk;
    mk.paper_x_m = row->printed_x_m;
    mk.measured_x_m = row->measured_x_m;
    mk.measured_error_m = row->measured_error_m;
    return mk;
}

typedef struct {
    const film_Film *film;
    const animate_opts *opts;
    const int *frames; /* the sample each frame shows */
    int frame_count;
} animate_job;

/* The PNG written through our own stream, so that a failed write keeps its
 * errno (cairo_surface_write_to_png says only "write error"). */
typedef struct {
    FILE *f;
    int err;
} png_sink;

static cairo_status_t png_write(void *ctx, const unsigned char *data, unsigned int len)
{
    png_sink *s = ctx;
    if (fwrite(data, 1, len, s->f) == len) return CAIRO_STATUS_SUCCESS;
    if (!s->err) s->err = errno ? errno : EIO;
    return CAIRO_STATUS_WRITE_ERROR;
}

/* 0, or -1 with the reason in *err (errno). */
static int write_png(cairo_surface_t *surface, const char *path, int *err)
{
    png_sink s = {fopen(path, "wb"), 0};
    if (!s.f) {
        *err = errno;
        return -1;
    }
    const cairo_status_t st = cairo_surface_write_to_png_stream(surface, png_write, &s);
    if (fflush(s.f) != 0 && !s.err) s.err = errno;
    if (fclose(s.f) != 0 && !s.err) s.err = errno;
    if (st != CAIRO_STATUS_SUCCESS && !s.err) s.err = st == CAIRO_STATUS_NO_MEMORY ? ENOMEM : EIO;
    *err = s.err;
    return s.err ? -1 : 0;
}

static int render_one(cairo_t *cr, cairo_surface_t *surface, const animate_job *job, int k, const char *dir, int *err)
{
    const draw_Frame f = film_frame(job->film, job->frames[k]);
    draw_frame(cr, &f);
    cairo_surface_flush(surface);
    char path[CLI_PATH_MAX];
    if (vid_frame_path(path, sizeof path, dir, k) != 0) {
        *err = ENAMETOOLONG;
        return -1;
    }
    return write_png(surface, path, err);
}

static int render_frames(const animate_job *job, const char *dir)
{
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, job->opts->width, job->opts->height);
    cairo_t *cr = cairo_create(surface);
    int rc = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? EXIT_OK : EXIT_FAIL;
    if (rc != EXIT_OK) cli_error("animate: out of memory for %dx%d frames", job->opts->width, job->opts->height);
    cli_Progress progress;
    int err = 0;
    cli_progress_begin(&progress, "animate: frame");
    for (int k = 0; rc == EXIT_OK && k < job->frame_count; ++k) {
        if (cli_stop_requested()) rc = cli_stop_status();
        else if (render_one(cr, surface, job, k, dir, &err) != 0) {
            if (cli_stop_requested()) rc = cli_stop_status();
            else {
                cli_error("animate: cannot write frame %d in %s: %s", k, dir, strerror(err));
                rc = EXIT_FAIL;
            }
        }
        cli_progress_update(&progress, k + 1, job->frame_count);
    }
    cli_progress_end(&progress);
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    cairo_debug_reset_static_data(); /* font caches: leak checkers see a clean exit */
    return rc;
}

/* Frames into a new directory beside target, then moved to target. */
static int frames_to_dir(const animate_job *job, const char *target)
{
    char tmp[CLI_PATH_MAX];
    int slot;
    if (vid_frames_tmpdir(target, tmp, sizeof tmp, &slot) != 0) return EXIT_FAIL;
    int rc = render_frames(job, tmp);
    if (rc == EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    if (rc == EXIT_OK) rc = vid_publish_frames(tmp, target, job->frame_count);
    if (rc != EXIT_OK) cli_remove_flat_dir(tmp);
    cli_tmpdir_untrack(slot);
    return rc;
}

/* No ffmpeg: keep the frames beside the video and say how to finish it. */
static int frames_without_ffmpeg(const animate_job *job)
{
    char dir[CLI_PATH_MAX], stem[256], frames[CLI_PATH_MAX], name[300];
    const char *out = job->opts->output;
    if (cli_path_split(out, dir, sizeof dir, stem, sizeof stem) != 0 ||
        snprintf(name, sizeof name, "%s-frames", stem) >= (int)sizeof name ||
        cli_path_join(frames, sizeof frames, dir, name) != 0) {
        cli_error("cannot write %s: path too long", out);
        return EXIT_FAIL;
    }
    const int rc = frames_to_dir(job, frames);
    if (rc != EXIT_OK) return rc;
    cli_error("animate: ffmpeg was not found in PATH, so %s was not made (Debian: sudo apt-get install ffmpeg)", out);
    fprintf(stderr, "The %d frames are in %s/; assemble them with:\n", job->frame_count, frames);
    vid_print_command(stderr, frames, job->opts->fps, out, job->opts->format);
    return EXIT_FAIL;
}

static int frames_to_video(const animate_job *job)
{
    cli_WorkDir work;
    if (cli_workdir_make(&work, "animate") != 0) return EXIT_FAIL;
    int rc = render_frames(job, work.path);
    if (rc == EXIT_OK) rc = vid_assemble(work.path, job->opts->fps, job->opts->output, job->opts->format);
    cli_workdir_remove(&work);
    return rc;
}

static int make_film(const animate_job *job)
{
    char ffmpeg[CLI_PATH_MAX];
    if (job->opts->format == VID_FRAMES) return frames_to_dir(job, job->opts->output);
    if (cli_find_program("ffmpeg", ffmpeg, sizeof ffmpeg) != 0) return frames_without_ffmpeg(job);
    return frames_to_video(job);
}

/* A run that keeps nothing first gives the film's length, so that a film
 * past the frame budget is refused before samples are stored or a frame
 * is drawn; the count is printed before the work. *film_end_s: the
 * simulated time the film shows. */
static int check_length(const jc_Model *model, const jc_SimOptions *sim, const animate_opts *o, double *film_end)
{
    jc_SimOptions probe_opts = *sim;
    probe_opts.sample_dt_s = 0.0;
    jc_Run probe;
    film_Watch w = {NAN};
    const jc_Recorder rec = {&w, watch_event, NULL};
    const int st = cli_simulate_stream(model, &probe_opts, &rec, &probe, "animate");
    if (st != JC_OK) return cli_exit_status(st, CLI_INPUTS_CHECKED);
    *film_end = film_end_s(&probe, &w, o->t_max_given);
    const double frames = motion_frames(*film_end, o) + hold_frames(o);
    if (frames > o->max_frames) {
        cli_error("animate: the film needs %.0f frames, over the budget of %d; raise it with --max-frames N "
                  "(at most %d), or shorten the film with --t-max, --slowmo or --fps", frames, o->max_frames,
                  VID_MAX_FRAMES);
        return EXIT_USAGE;
    }
    /* On standard output, before the work: stderr is for what went wrong. */
    const int cut = *film_end < probe.final_state.t_s;
    char why[64] = "";
    if (cut) snprintf(why, sizeof why, ", to %g s after the last landing", FILM_AFTER_LANDING_S);
    printf("Film: %.0f frames (%.1f s at %g fps): %.4g s simulated%s (the run: %s at %.4g s), then the last "
           "picture held %g s\n", frames, frames / o->fps, o->fps, *film_end, why, jc_termination_name(probe.termination),
           probe.final_state.t_s, FILM_HOLD_S);
    fflush(stdout);
    return EXIT_OK;
}

static int animate_run(const jc_Model *model, const jc_Run *run, const animate_opts *o)
{
    int *frames = NULL;
    const int n = select_frames(run, o, &frames);
    if (n <= 0) {
        if (n < 0)
            cli_error("animate: %d frames is too many (allowed: at most %d); shorten the film with --t-max, "
                      "--slowmo or --fps", -n, VID_MAX_FRAMES);
        else cli_error("animate: out of memory");
        return n < 0 ? EXIT_USAGE : EXIT_FAIL;
    }
    const draw_Marks marks = make_marks(model, run);
    film_Film film;
    if (film_init(&film, model, run, o->width, o->height, o->slowmo, o->camera, &marks) != 0) {
        free(frames);
        cli_error("animate: out of memory");
        return EXIT_FAIL;
    }
    const animate_job job = {&film, o, frames, n};
    const int rc = make_film(&job);
    film_free(&film);
    free(frames);
    if (rc == EXIT_OK)
        printf("Animation: %s (%d frames, %dx%d, %g fps, slow motion x%g, %.4g s simulated)\n", o->output, n,
               o->width, o->height, o->fps, o->slowmo, run->final_state.t_s);
    return rc;
}

int cmd_animate(int argc, char **argv)
{
    animate_args a = {0};
    cli_RunInputs in;
    int st = cli_run_inputs_parse(argc, argv, &command, &a, &in);
    if (st != CLI_GO_ON) return st;
    animate_opts o;
    if ((st = check_args(&a, &o)) != EXIT_OK || (st = build_inputs(&in, &o)) != EXIT_OK) return st;
    /* The target is checked before the work: a read-only file is refused at once. */
    if ((o.format == VID_FRAMES ? cli_check_output_dir(o.output) : cli_output_check_target(o.output)) != 0)
        return EXIT_FAIL;
    jc_Run run;
    double film_end = 0;
    if ((st = check_length(&in.model, &in.sim, &o, &film_end)) != EXIT_OK) return st;
    /* The film's run stops where the film does: the same run up to there
     * (a run that ends at its start, at rest, needs no limit). */
    if (film_end > 0.0) in.sim.t_max_s = fmin(in.sim.t_max_s, film_end);
    in.sim.max_samples = (int)fmin(1e8, (double)o.max_frames + in.sim.max_events + 16.0);
    if ((st = cli_simulate(&in.model, &in.sim, &run, "animate")) != JC_OK) {
        jc_run_free(&run);
        return cli_exit_status(st, CLI_INPUTS_CHECKED);
    }
    st = animate_run(&in.model, &run, &o);
    jc_run_free(&run);
    return st != EXIT_OK && cli_stop_requested() ? cli_stop_status() : st;
}
