/* jumpcyl track FILE: a video's tracked points (Tracker) read, put in the
 * incline frame, with θ, ω, the centre's height and its hops derived
 * (docs/tracker.md). */
#include "cli.h"
#include "track.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *centre, *mark, *axes, *hop_sigmas, *csv, *json;
    int fit_tilt;
} track_opts;

static void help(void)
{
    puts("Usage: jumpcyl track FILE [--centre TRACK] [--mass TRACK] [--axes level|incline]\n"
         "                     [--csv FILE] [--json FILE] [SETUP OPTIONS]\n"
         "Reads the points tracked in a video with Tracker (Open Source Physics): its .trk file or\n"
         "a data table it exported (File > Export > Data: tab, comma or semicolon separated,\n"
         "decimal point or comma). Reports the tracks, frames, frame rate, time step jitter,\n"
         "gaps and scale; puts the centre and the off-centre mark in the incline frame\n"
         "(docs/physics.md: x down the incline, y its normal) and derives theta (unwrapped),\n"
         "omega, the centre's height above the surface and the hops (docs/tracker.md).\n"
         "The incline angle and the radius come from the setup options (--incline, --radius,\n"
         "--preset, --config).\n"
         "\n"
         "  --centre TRACK      the track of the axle (default: the track named centre, center,\n"
         "                      axle, axis or hub, or the only track)\n"
         "  --mass TRACK        the track of the off-centre mass or a mark on the body (default:\n"
         "                      the track named mark, rod, dot or off, or the other of two tracks\n"
         "                      when the centre is named); --mass '' for none\n"
         "  --axes level        Tracker's axes are level, y up (Tracker's default; the default)\n"
         "  --axes incline      Tracker's x axis was laid along the incline (y its outward normal)\n"
         "  --hop-sigmas K      a hop: the centre higher than r + K sigma above the surface\n"
         "                      (sigma: the position noise; default 5)\n"
         "  --fit-tilt          the surface is the line through the frames in contact, tilted as\n"
         "                      they say (axes set by eye); without it, parallel to the incline\n"
         "                      at the angle given, only its height fitted (the tilt is reported)\n"
         "  --csv FILE          t_s,x_m,y_m,height_m,theta_rad,omega_radps,airborne per frame\n"
         "  --json FILE         the report and the frames as JSON\n"
         "  -h, --help          this help\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    track_opts *o = ctx;
    switch (opt) {
    case 'c': o->centre = arg; return 0;
    case 'm': o->mark = arg; return 0;
    case 'a': o->axes = arg; return 0;
    case 'k': o->hop_sigmas = arg; return 0;
    case 'v': o->csv = arg; return 0;
    case 'j': o->json = arg; return 0;
    case 't': o->fit_tilt = 1; return 0;
    default: return EXIT_USAGE;
    }
}

static const struct option own[] = {{"centre", required_argument, 0, 'c'}, {"mass", required_argument, 0, 'm'},
                                    {"axes", required_argument, 0, 'a'},   {"hop-sigmas", required_argument, 0, 'k'},
                                    {"csv", required_argument, 0, 'v'},    {"json", required_argument, 0, 'j'},
                                    {"fit-tilt", no_argument, 0, 't'},     {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* Whether the long option written as text ("--inc", "--incline=30") takes
 * the next argument as its value: matched as getopt_long matches it, by an
 * exact name or an unambiguous prefix. */
static int takes_next(const char *text)
{
    if (strncmp(text, "--", 2) != 0 || strchr(text, '=')) return 0;
    const char *name = text + 2;
    const size_t len = strlen(name);
    int matches = 0, needs = 0;
    for (size_t i = 0; i < sizeof own / sizeof own[0] + CLI_SETUP_OPTION_COUNT; ++i) {
        const struct option *o = i < sizeof own / sizeof own[0] ? &own[i] : &cli_setup_options[i - sizeof own / sizeof own[0]];
        if (strncmp(o->name, name, len) != 0) continue;
        if (strlen(o->name) == len) return o->has_arg == required_argument;
        matches++;
        needs = o->has_arg == required_argument;
    }
    return matches == 1 && needs;
}

/* The one argument that is not an option or an option's value: the file.
 * It is taken out of argv (which keeps its order). NULL after a message. */
static const char *take_file(int *argc, char **argv, int *help)
{
    const char *file = NULL;
    int out = 1;
    for (int i = 1; i < *argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) *help = 1;
        if (strcmp(a, "--") == 0 && i + 1 < *argc && !file) {
            file = argv[++i];
            continue;
        }
        if (a[0] == '-' && a[1]) {
            argv[out++] = argv[i];
            if (takes_next(a) && i + 1 < *argc) argv[out++] = argv[++i];
            continue;
        }
        if (file) {
            cli_error("track: one file at a time ('%s' and '%s')", file, a);
            return NULL;
        }
        file = a;
    }
    *argc = out;
    argv[out] = NULL;
    if (!file && !*help) cli_error("track: which file? 'jumpcyl track FILE' (see 'jumpcyl track --help')");
    return file;
}

static cJSON *num(double v) { return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull(); }

static cJSON *series(const double *v, long n)
{
    cJSON *a = cJSON_CreateArray();
    for (long i = 0; a && i < n; ++i) cJSON_AddItemToArray(a, num(v[i]));
    return a;
}

/* A hop: a run of airborne frames [a, b]. */
typedef struct {
    long a, b, peak;
} hop_span;

static int next_hop(const cli_Track *t, long from, hop_span *h)
{
    long i = from;
    while (i < t->n && !t->airborne[i]) i++;
    if (i >= t->n) return 0;
    h->a = h->peak = i;
    while (i < t->n && t->airborne[i]) {
        if (t->y_m[i] > t->y_m[h->peak]) h->peak = i;
        i++;
    }
    h->b = i - 1;
    return 1;
}

static cJSON *track_json(const char *file, const cli_Track *t, const cli_TrackOptions *opt)
{
    cJSON *d = cJSON_CreateObject();
    cJSON_AddStringToObject(d, "file", file);
    cJSON_AddStringToObject(d, "format", t->format);
    cJSON *tr = cJSON_AddArrayToObject(d, "tracks");
    for (int i = 0; i < t->track_count; ++i) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", t->track_names[i]);
        cJSON_AddNumberToObject(o, "frames", (double)t->track_frames[i]);
        cJSON_AddItemToArray(tr, o);
    }
    cJSON_AddStringToObject(d, "centre", t->centre_name);
    if (t->has_mark) cJSON_AddStringToObject(d, "mark", t->mark_name);
    else cJSON_AddNullToObject(d, "mark");
    cJSON_AddNumberToObject(d, "clip_frames", (double)t->clip_frames);
    cJSON_AddNumberToObject(d, "frames", (double)t->n);
    cJSON_AddNumberToObject(d, "gaps", (double)t->gaps);
    cJSON_AddItemToObject(d, "frame_rate_hz", num(t->frame_rate_hz));
    cJSON_AddItemToObject(d, "dt_jitter_s", num(t->dt_jitter_s));
    cJSON_AddItemToObject(d, "scale_px_per_m", num(t->scale_px_per_m));
    cJSON_AddBoolToObject(d, "scale_varies", t->scale_varies);
    cJSON_AddItemToObject(d, "tape_length_m", num(t->tape_length_m));
    cJSON_AddItemToObject(d, "incline_rad", num(t->incline_rad));
    cJSON_AddStringToObject(d, "axes", opt->axes == CLI_TRACK_AXES_INCLINE ? "incline" : "level");
    cJSON_AddBoolToObject(d, "fit_tilt", opt->fit_tilt);
    cJSON_AddItemToObject(d, "radius_m", num(t->radius_m));
    cJSON_AddItemToObject(d, "x0_m", num(t->x0_m));
    cJSON_AddItemToObject(d, "sigma_m", num(t->sigma_m));
    cJSON_AddItemToObject(d, "noise_m", num(t->noise_m));
    cJSON_AddItemToObject(d, "surface_tilt_rad", num(t->surface_tilt_rad));
    cJSON_AddItemToObject(d, "mark_radius_m", num(t->mark_radius_m));
    cJSON_AddItemToObject(d, "hop_threshold_m", num(t->hop_threshold_m));
    cJSON *hops = cJSON_AddArrayToObject(d, "hops");
    hop_span h;
    for (long from = 0; next_hop(t, from, &h); from = h.b + 1) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToObject(o, "start_s", num(t->t_s[h.a]));
        cJSON_AddItemToObject(o, "end_s", num(t->t_s[h.b]));
        cJSON_AddItemToObject(o, "x_m", num(t->x_m[h.a]));
        cJSON_AddItemToObject(o, "peak_height_m", num(t->y_m[h.peak] - t->radius_m));
        cJSON_AddItemToArray(hops, o);
    }
    cJSON *fr = cJSON_AddObjectToObject(d, "frames_data");
    cJSON_AddItemToObject(fr, "t_s", series(t->t_s, t->n));
    cJSON_AddItemToObject(fr, "x_m", series(t->x_m, t->n));
    cJSON_AddItemToObject(fr, "y_m", series(t->y_m, t->n));
    cJSON_AddItemToObject(fr, "theta_rad", series(t->theta_rad, t->n));
    cJSON_AddItemToObject(fr, "omega_radps", series(t->omega_radps, t->n));
    cJSON *air = cJSON_AddArrayToObject(fr, "airborne");
    for (long i = 0; air && i < t->n; ++i) cJSON_AddItemToArray(air, cJSON_CreateBool(t->airborne[i]));
    return d;
}

static void csv_value(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, ",%.10g", v);
    else fputc(',', f);
}

static void write_csv(FILE *f, const cli_Track *t)
{
    fputs("t_s,x_m,y_m,height_m,theta_rad,omega_radps,airborne\n", f);
    for (long i = 0; i < t->n; ++i) {
        fprintf(f, "%.10g", t->t_s[i]);
        csv_value(f, t->x_m[i]);
        csv_value(f, t->y_m[i]);
        csv_value(f, t->y_m[i] - t->radius_m);
        csv_value(f, t->theta_rad[i]);
        csv_value(f, t->omega_radps[i]);
        fprintf(f, ",%d\n", t->airborne[i]);
    }
}

static void print_report(const char *file, const cli_Track *t, cli_TrackAxes axes, int fit_tilt)
{
    printf("Track file: ");
    cli_shell_word(stdout, file);
    printf(" (%s)\n", strcmp(t->format, "trk") == 0 ? "Tracker .trk" : "exported data table");
    printf("Tracks:");
    for (int i = 0; i < t->track_count; ++i)
        printf("%s '%s' %ld frames", i ? "," : "", t->track_names[i], t->track_frames[i]);
    printf("\nFrames: %ld in the %s at %.3f frames/s (step %.4f ms); time step jitter %.4f ms\n", t->clip_frames,
           strcmp(t->format, "trk") == 0 ? "clip" : "table", t->frame_rate_hz, 1e3 / t->frame_rate_hz,
           t->dt_jitter_s * 1e3);
    printf("Centre '%s': %ld frames kept, %ld missing between its first and last\n", t->centre_name, t->n, t->gaps);
    if (t->has_mark)
        printf("Mark '%s': at %.2f cm from the centre (median)\n", t->mark_name, t->mark_radius_m * 100);
    else printf("Mark: none (no theta, omega)\n");
    if (isfinite(t->scale_px_per_m))
        printf("Scale: %.4g px/m (1 px = %.3f mm)%s", t->scale_px_per_m, 1e3 / t->scale_px_per_m,
               t->scale_varies ? "; the axes or scale change between frames" : "");
    else printf("Scale: the table is in metres already");
    if (isfinite(t->tape_length_m)) printf("; calibration tape %.4g m", t->tape_length_m);
    printf("\nIncline frame: incline %.2f deg, Tracker's axes %s; radius r = %.2f cm\n", cli_deg(t->incline_rad),
           axes == CLI_TRACK_AXES_INCLINE ? "along the incline" : "level", t->radius_m * 100);
    printf("Position noise: %.3f mm estimated (sigma used %.3f mm); the centres in contact lie on a line\n"
           "  tilted %+.3f deg from the incline's x axis (%s)\n",
           t->noise_m * 1e3, t->sigma_m * 1e3, cli_deg(t->surface_tilt_rad),
           fit_tilt ? "removed: --fit-tilt" : "a check of --incline and --axes; --fit-tilt removes it");
    printf("Start: x0 = %.2f cm", t->x0_m * 100);
    if (t->has_mark) {
        long i = 0;
        while (i < t->n && isnan(t->theta_rad[i])) i++;
        if (i < t->n) printf(", theta = %.4f rad at t = %.4f s", t->theta_rad[i], t->t_s[i]);
    }
    printf("; end: t = %.4f s, x = %.2f cm\n", t->t_s[t->n - 1], t->x_m[t->n - 1] * 100);
    printf("Hops (centre above r + %.2f mm): %ld\n", t->hop_threshold_m * 1e3, t->hops);
    hop_span h;
    int k = 0;
    if (t->hops > 0) printf("    #   from (s)     to (s)   x (cm)  peak (mm)  frames\n");
    for (long from = 0; next_hop(t, from, &h); from = h.b + 1)
        printf("  %3d %10.4f %10.4f %8.2f %10.3f %7ld\n", ++k, t->t_s[h.a], t->t_s[h.b], t->x_m[h.a] * 100,
               (t->y_m[h.peak] - t->radius_m) * 1e3, h.b - h.a + 1);
}

/* Both files made whole, then both published: neither or both appear. */
static int write_outputs(const track_opts *o, const char *file, const cli_Track *t, const cli_TrackOptions *opt)
{
    cli_Output csv, json;
    memset(&csv, 0, sizeof csv);
    memset(&json, 0, sizeof json);
    if (o->csv && cli_output_begin(&csv, o->csv, 0) != 0) return EXIT_FAIL;
    if (o->json && cli_output_begin(&json, o->json, 0) != 0) {
        cli_output_abort(&csv);
        return EXIT_FAIL;
    }
    int ok = 1;
    if (o->csv) {
        write_csv(csv.f, t);
        ok = cli_output_finish(&csv, CLI_CHECK_WRITES) == 0;
    }
    if (ok && o->json) {
        cJSON *doc = track_json(file, t, opt);
        char *text = doc ? cJSON_Print(doc) : NULL;
        cJSON_Delete(doc);
        if (!text) {
            cli_error("track: out of memory for the JSON document");
            ok = 0;
        } else {
            fputs(text, json.f);
            fputc('\n', json.f);
            free(text);
            ok = cli_output_finish(&json, CLI_CHECK_WRITES) == 0;
        }
    }
    ok = ok && (!o->csv || cli_output_publish(&csv) == 0) && (!o->json || cli_output_publish(&json) == 0);
    cli_output_abort(&csv);
    cli_output_abort(&json);
    return ok ? EXIT_OK : EXIT_FAIL;
}

int cmd_track(int argc, char **argv)
{
    int want_help = 0;
    char **args = malloc(((size_t)argc + 1) * sizeof *args);
    if (!args) {
        cli_error("track: out of memory");
        return EXIT_FAIL;
    }
    memcpy(args, argv, (size_t)argc * sizeof *args);
    args[argc] = NULL;
    int n = argc;
    const char *file = take_file(&n, args, &want_help);
    if (!file && !want_help) {
        free(args);
        return EXIT_USAGE;
    }
    track_opts o = {0};
    cli_SetupArgs sa;
    int st = cli_command_parse(n, args, &command, &o, &sa, NULL);
    free(args);
    if (st != CLI_GO_ON) return st;
    jc_Setup setup;
    if ((st = cli_build_inputs("track", &sa, NULL, &setup, NULL, NULL)) != 0) return st;
    cli_TrackOptions opt;
    cli_track_options_default(&opt);
    opt.centre = o.centre;
    opt.mark = o.mark;
    opt.incline_rad = setup.incline_rad;
    opt.radius_m = setup.body.radius_m;
    opt.fit_tilt = o.fit_tilt;
    if (o.axes) {
        if (strcmp(o.axes, "level") == 0) opt.axes = CLI_TRACK_AXES_LEVEL;
        else if (strcmp(o.axes, "incline") == 0) opt.axes = CLI_TRACK_AXES_INCLINE;
        else {
            cli_error("track: --axes '%s' (allowed: level, incline)", o.axes);
            return EXIT_USAGE;
        }
    }
    if (o.hop_sigmas) {
        char err[256];
        if (cli_parse_quantity(o.hop_sigmas, Q_NUMBER, &opt.hop_sigmas, err, sizeof err) != 0 ||
            !(opt.hop_sigmas >= 1 && opt.hop_sigmas <= 100)) {
            cli_error("track: --hop-sigmas '%s': a number from 1 to 100", o.hop_sigmas);
            return EXIT_USAGE;
        }
    }
    if ((o.csv && strcmp(o.csv, "-") == 0) || (o.json && strcmp(o.json, "-") == 0)) {
        cli_error("track: --csv and --json write files; the report goes to standard output");
        return EXIT_USAGE;
    }
    if (o.csv && o.json && strcmp(o.csv, o.json) == 0) {
        cli_error("track: --csv and --json name the same file");
        return EXIT_USAGE;
    }
    cli_Track t;
    char err[1024];
    if (cli_track_load(file, &opt, &t, err, sizeof err) != 0) {
        for (char *p = err; *p; ++p)
            if (*p == '\n' || *p == '\r') *p = ' ';
        cli_error("track: %s", err);
        return EXIT_USAGE;
    }
    st = write_outputs(&o, file, &t, &opt);
    if (st == EXIT_OK) {
        print_report(file, &t, opt.axes, opt.fit_tilt);
        if (o.csv) printf("Frames: %ld rows written to %s\n", t.n, o.csv);
        if (o.json) printf("JSON written to %s\n", o.json);
    }
    cli_track_free(&t);
    if (cli_stop_requested()) return cli_stop_status();
    return st == EXIT_OK ? cli_stdout_finish() : st;
}
