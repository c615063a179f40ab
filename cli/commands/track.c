/* jumpcyl track FILE: a video's tracked points (Tracker) read, put in the
 * incline frame, and a report of what they tell: the centre (tracked or
 * recovered from a mark), the surface and the incline, the noise, the hops
 * and θ, each with how well it is known or why it is not
 * (docs/tracker.md). Every readable file gives a report. */
#include "commands.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    cli_TrackArgs read;
    const char *csv, *json;
} track_opts;

static void help(void)
{
    puts("Usage: jumpcyl track FILE [--centre TRACK] [--mass TRACK] [--axes level|incline]\n"
         "                     [--csv FILE] [--json FILE] [SETUP OPTIONS]\n"
         "Reads the points tracked in a video with Tracker (Open Source Physics): its .trk file or\n"
         "a data table it exported (File > Export > Data: tab, comma or semicolon separated,\n"
         "decimal point or comma). Reports the tracks, frames, frame rate, time step jitter, gaps\n"
         "and scale, then what the video tells and what it cannot, and why: the centre (tracked,\n"
         "or recovered from a mark on the rim by fitting rolling), the surface and the incline's\n"
         "angle (measured from the frames in contact, or checked against --incline), the noise\n"
         "(the scatter of those frames), theta and omega, and the hops with their heights'\n"
         "uncertainties (docs/tracker.md). The radius and g come from the setup options.\n"
         "Exit 0 for a report; 2 for a file that cannot be read, an incline the video refuses, or\n"
         "an output that needs what the video does not tell.\n");
    cli_track_args_help(0);
    puts("  --csv FILE          per frame: t_s,x_m,y_m,height_m,centre_sigma_m,mark_x_m,mark_y_m,\n"
         "                      theta_rad,omega_radps,contact,airborne (needs the centre;\n"
         "                      height_m empty when the surface is not known)\n"
         "  --json FILE         the report and the frames as JSON\n"
         "                      (--csv and --json: - is standard output, in place of the report;\n"
         "                      --json alone is --json -)\n"
         "  -h, --help          this help\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    track_opts *o = ctx;
    if (opt == 'v') return cli_take_once("track", &o->csv, "csv", arg);
    if (opt == 'j') return cli_take_once("track", &o->json, "json", arg);
    return cli_track_args_take("track", &o->read, opt, arg);
}

static const struct option own[] = {CLI_TRACK_READ_OPTIONS,
                                    {"csv", required_argument, 0, 'v'},
                                    CLI_JSON_OPTION('j'),
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* The option the long option written as text ("--inc", "--incline=30")
 * names, matched as getopt_long matches it: by an exact name or an
 * unambiguous prefix. Its has_arg, or -1 for none (or an ambiguous prefix). */
static int long_match(const char *text)
{
    const size_t n_own = sizeof own / sizeof own[0];
    struct option all[sizeof own / sizeof own[0] + CLI_SETUP_OPTION_MAX + 1];
    cli_merge_options(all, (int)(sizeof all / sizeof all[0]), own, (int)n_own);
    const char *name = text + 2, *eq = strchr(name, '=');
    const size_t len = eq ? (size_t)(eq - name) : strlen(name);
    int found = -1, matches = 0;
    for (size_t i = 0; all[i].name; ++i) {
        if (strncmp(all[i].name, name, len) != 0) continue;
        if (strlen(all[i].name) == len) return all[i].has_arg;
        matches++;
        found = all[i].has_arg;
    }
    return matches == 1 ? found : -1;
}

/* Whether the option written as text takes next (NULL: none), the next
 * argument, as its value: an output option's FILE only when one follows. */
static int takes_next(const char *text, const char *next)
{
    if (strncmp(text, "--", 2) != 0 || strchr(text, '=')) return 0;
    const int has_arg = long_match(text);
    return has_arg == required_argument || (has_arg == optional_argument && cli_output_value_follows(next));
}

/* Whether the option written as text is one the parser refuses (the only
 * short option is -h; "--" ends the options). */
static int is_unknown(const char *text)
{
    if (strcmp(text, "--") == 0) return 0;
    if (strncmp(text, "--", 2) == 0) return long_match(text) < 0;
    return text[strspn(text + 1, "h") + 1] != '\0';
}

/* The arguments that are not options or their values, taken out of argv
 * (which keeps its order): the file, and an extra one (NULL when none).
 * Returns whether an option is one the parser will refuse. */
static int take_file(int *argc, char **argv, int *help, const char **file, const char **extra)
{
    int out = 1, unknown = 0;
    *file = *extra = NULL;
    for (int i = 1; i < *argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) *help = 1;
        if (strcmp(a, "--") == 0 && i + 1 < *argc && !*file) {
            *file = argv[++i];
            continue;
        }
        if (a[0] == '-' && a[1]) {
            unknown |= is_unknown(a);
            argv[out++] = argv[i];
            if (i + 1 < *argc && takes_next(a, argv[i + 1])) argv[out++] = argv[++i];
            continue;
        }
        if (!*file) *file = a;
        else if (!*extra) *extra = a;
    }
    *argc = out;
    argv[out] = NULL;
    return unknown;
}

/* One file, not two, and none only for --help: EXIT_OK, or EXIT_USAGE after
 * a message. */
static int one_file(const char *file, const char *extra, int help)
{
    if (extra) {
        cli_error("track: one file at a time ('%s' and '%s')", file, extra);
        return EXIT_USAGE;
    }
    if (!file && !help) {
        cli_error("track: which file? 'jumpcyl track FILE' (see 'jumpcyl track --help')");
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static cJSON *num(double v) { return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull(); }

static cJSON *series(const double *v, long n)
{
    cJSON *a = cJSON_CreateArray();
    for (long i = 0; a && i < n; ++i) cJSON_AddItemToArray(a, num(v[i]));
    return a;
}

static const char *const quantity_names[JC_TRACK_Q_COUNT] = {"centre", "surface", "hops", "theta"};
static const char *const incline_sources[] = {"unknown", "measured", "given"};

static cJSON *hop_json(const jc_Track *t, const jc_TrackHop *h)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "start_s", num(t->t_s[h->first]));
    cJSON_AddItemToObject(o, "end_s", num(t->t_s[h->last]));
    cJSON_AddItemToObject(o, "x_m", num(t->x_m[h->first]));
    cJSON_AddItemToObject(o, "peak_height_m", num(h->height_m));
    cJSON_AddItemToObject(o, "peak_height_sigma_m", num(h->height_sigma_m));
    cJSON_AddItemToObject(o, "bound_m", num(h->bound_m));
    cJSON_AddBoolToObject(o, "resolved", !isnan(h->height_m));
    cJSON_AddBoolToObject(o, "fitted_flight", h->fitted_flight);
    return o;
}

static cJSON *track_json(const char *file, const jc_Track *t)
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
    if (t->centre_name[0]) cJSON_AddStringToObject(d, "centre", t->centre_name);
    else cJSON_AddNullToObject(d, "centre");
    cJSON_AddStringToObject(d, "centre_source", cli_track_centre_sources[t->centre_source]);
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
    cJSON_AddStringToObject(d, "axes", t->axes == JC_TRACK_AXES_INCLINE ? "incline" : "level");
    cJSON_AddItemToObject(d, "incline_rad", num(t->incline_rad));
    cJSON_AddItemToObject(d, "incline_sigma_rad", num(t->incline_sigma_rad));
    cJSON_AddStringToObject(d, "incline_source", incline_sources[t->incline_source]);
    cJSON_AddItemToObject(d, "given_incline_rad", num(t->given_incline_rad));
    cJSON_AddItemToObject(d, "radius_m", num(t->radius_m));
    cJSON_AddItemToObject(d, "x0_m", num(t->x0_m));
    cJSON_AddItemToObject(d, "sigma_m", num(t->sigma_m));
    cJSON_AddNumberToObject(d, "contact_frames", (double)t->contact_frames);
    cJSON_AddItemToObject(d, "surface_tilt_rad", num(t->surface_tilt_rad));
    cJSON_AddItemToObject(d, "surface_tilt_sigma_rad", num(t->surface_tilt_sigma_rad));
    cJSON_AddItemToObject(d, "surface_sigma_m", num(t->surface_sigma_m));
    cJSON_AddItemToObject(d, "mark_radius_m", num(t->mark_radius_m));
    cJSON_AddItemToObject(d, "mark_radius_sigma_m", num(t->mark_radius_sigma_m));
    cJSON_AddItemToObject(d, "centre_sigma_median_m", num(t->centre_sigma_median_m));
    cJSON_AddItemToObject(d, "centre_sigma_max_m", num(t->centre_sigma_max_m));
    cJSON_AddItemToObject(d, "hop_threshold_m", num(t->hop_threshold_m));
    cJSON *notes = cJSON_AddObjectToObject(d, "derived");
    for (int q = 0; q < JC_TRACK_Q_COUNT; ++q) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddBoolToObject(o, "known", t->note[q].ok);
        cJSON_AddStringToObject(o, "how", t->note[q].text);
        cJSON_AddItemToObject(notes, quantity_names[q], o);
    }
    cJSON *hops = cJSON_AddArrayToObject(d, "hops");
    for (long k = 0; k < t->hops; ++k) cJSON_AddItemToArray(hops, hop_json(t, &t->hop[k]));
    cJSON *fr = cJSON_AddObjectToObject(d, "frames_data");
    cJSON_AddItemToObject(fr, "t_s", series(t->t_s, t->n));
    cJSON_AddItemToObject(fr, "x_m", series(t->x_m, t->n));
    cJSON_AddItemToObject(fr, "y_m", series(t->y_m, t->n));
    cJSON_AddItemToObject(fr, "centre_sigma_m", series(t->centre_sigma_m, t->n));
    cJSON_AddItemToObject(fr, "mark_x_m", series(t->mark_x_m, t->n));
    cJSON_AddItemToObject(fr, "mark_y_m", series(t->mark_y_m, t->n));
    cJSON_AddItemToObject(fr, "theta_rad", series(t->theta_rad, t->n));
    cJSON_AddItemToObject(fr, "omega_radps", series(t->omega_radps, t->n));
    cJSON *con = cJSON_AddArrayToObject(fr, "contact"), *air = cJSON_AddArrayToObject(fr, "airborne");
    for (long i = 0; i < t->n; ++i) {
        cJSON_AddItemToArray(con, cJSON_CreateBool(t->contact[i]));
        cJSON_AddItemToArray(air, cJSON_CreateBool(t->airborne[i]));
    }
    return d;
}

static void csv_value(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, ",%.10g", v);
    else fputc(',', f);
}

static void write_csv(FILE *f, const jc_Track *t)
{
    /* Heights only above a known surface: empty where the frames lie on no line. */
    const int surface = t->note[JC_TRACK_Q_SURFACE].ok;
    fputs("t_s,x_m,y_m,height_m,centre_sigma_m,mark_x_m,mark_y_m,theta_rad,omega_radps,contact,airborne\n", f);
    for (long i = 0; i < t->n; ++i) {
        fprintf(f, "%.10g", t->t_s[i]);
        csv_value(f, t->x_m[i]);
        csv_value(f, t->y_m[i]);
        csv_value(f, surface ? t->y_m[i] - t->radius_m : NAN);
        csv_value(f, t->centre_sigma_m[i]);
        csv_value(f, t->mark_x_m[i]);
        csv_value(f, t->mark_y_m[i]);
        csv_value(f, t->theta_rad[i]);
        csv_value(f, t->omega_radps[i]);
        fprintf(f, ",%d,%d\n", t->contact[i], t->airborne[i]);
    }
}

/* A note, wrapped at 96 columns under its label. */
static void print_wrapped(const char *label, const char *text)
{
    printf("  %-9s", label);
    int col = 11, first = 1;
    const char *p = text;
    while (*p) {
        while (*p == ' ') p++;
        const char *sp = strchr(p, ' ');
        const int w = sp ? (int)(sp - p) : (int)strlen(p);
        if (w == 0) break;
        if (!first && col + 1 + w > 96) {
            printf("\n           ");
            col = 11;
        } else if (!first) {
            putchar(' ');
            col++;
        }
        printf("%.*s", w, p);
        col += w;
        p += w;
        first = 0;
    }
    putchar('\n');
}

static void print_hops(const jc_Track *t)
{
    if (t->hops == 0) return;
    printf("\n%s:\n    #   from (s)     to (s)  from x (cm)   peak above contact\n",
           t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? "Departures from rolling" : "Hops");
    for (long k = 0; k < t->hops; ++k) {
        const jc_TrackHop *h = &t->hop[k];
        printf("  %3ld %10.4f %10.4f ", k + 1, t->t_s[h->first], t->t_s[h->last]);
        if (isfinite(t->x_m[h->first])) printf("%12.2f", t->x_m[h->first] * 100);
        else printf("%12s", "?");
        if (!isnan(h->height_m))
            printf("   %.1f +- %.1f mm%s\n", h->height_m * 1e3, h->height_sigma_m * 1e3,
                   h->fitted_flight ? " (a flight fitted to the mark)" : "");
        else
            printf("   a slip or a hop: at most %.0f mm (the mark alone)\n", h->bound_m * 1e3);
    }
}

static void print_report(const char *file, const jc_Track *t)
{
    printf("Track file: ");
    cli_shell_word(stdout, file);
    printf(" (%s)\n", strcmp(t->format, "trk") == 0 ? "Tracker .trk" : "exported data table");
    printf("Tracks:");
    for (int i = 0; i < t->track_count; ++i)
        printf("%s '%s' %ld frames", i ? "," : "", t->track_names[i], t->track_frames[i]);
    if (isfinite(t->frame_rate_hz))
        printf("\nFrames: %ld in the %s at %.3f frames/s (step %.4f ms); time step jitter %.4f ms; %ld missing\n",
               t->clip_frames, strcmp(t->format, "trk") == 0 ? "clip" : "table", t->frame_rate_hz,
               1e3 / t->frame_rate_hz, t->dt_jitter_s * 1e3, t->gaps);
    else
        printf("\nFrames: %ld in the %s; no time step\n", t->clip_frames,
               strcmp(t->format, "trk") == 0 ? "clip" : "table");
    if (isfinite(t->scale_px_per_m))
        printf("Scale: %.4g px/m (1 px = %.3f mm)%s", t->scale_px_per_m, 1e3 / t->scale_px_per_m,
               t->scale_varies ? "; the axes or scale change between frames" : "");
    else printf("Scale: the table is in metres already");
    if (isfinite(t->tape_length_m)) printf("; calibration tape %.4g m", t->tape_length_m);
    printf("\nAxes: %s; radius r = %.2f cm (the setup's)\n",
           t->axes == JC_TRACK_AXES_INCLINE ? "along the incline" : "level", t->radius_m * 100);
    printf("\nWhat the video tells:\n");
    for (int q = 0; q < JC_TRACK_Q_COUNT; ++q) {
        char label[16];
        snprintf(label, sizeof label, "%s:", quantity_names[q]);
        print_wrapped(label, t->note[q].text[0] ? t->note[q].text : "not known");
    }
    if (t->centre_source == JC_TRACK_CENTRE_NONE || t->n == 0) return;
    long i = 0;
    while (i < t->n && isnan(t->x_m[i])) i++;
    long e = t->n - 1;
    while (e > 0 && isnan(t->x_m[e])) e--;
    if (i < t->n) {
        printf("\nStart: x0 = %.2f cm", t->x_m[i] * 100);
        if (isfinite(t->theta_rad[i])) printf(", theta = %.4f rad", t->theta_rad[i]);
        printf(" at t = %.4f s; end: t = %.4f s, x = %.2f cm\n", t->t_s[i], t->t_s[e], t->x_m[e] * 100);
    }
    print_hops(t);
}

/* Both files made whole, then both published: neither or both appear. */
static int write_outputs(const track_opts *o, const char *file, const jc_Track *t)
{
    cli_Output csv, json;
    memset(&csv, 0, sizeof csv);
    memset(&json, 0, sizeof json);
    if (o->csv && cli_output_begin(&csv, o->csv, 1) != 0) return EXIT_FAIL;
    if (o->json && cli_output_begin(&json, o->json, 1) != 0) {
        cli_output_abort(&csv);
        return EXIT_FAIL;
    }
    int ok = 1;
    if (o->csv) {
        write_csv(csv.f, t);
        ok = cli_output_finish(&csv, CLI_CHECK_WRITES) == 0;
    }
    if (ok && o->json) {
        cJSON *doc = track_json(file, t);
        char *text = cli_json_text(doc, 1);
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
    const char *file, *extra;
    /* An unknown option is reported first (by the parser): its value may
     * have been taken for a file ("--from 1"). */
    const int unknown = take_file(&n, args, &want_help, &file, &extra);
    if (!unknown && one_file(file, extra, want_help) != EXIT_OK) {
        free(args);
        return EXIT_USAGE;
    }
    track_opts o;
    memset(&o, 0, sizeof o);
    cli_SetupArgs sa;
    int st = cli_command_parse(n, args, &command, &o, &sa, NULL);
    free(args);
    if (st != CLI_GO_ON) return st;
    if ((st = one_file(file, extra, 0)) != EXIT_OK) return st;
    jc_Setup setup;
    if ((st = cli_build_inputs("track", &sa, NULL, &setup, NULL, NULL)) != EXIT_OK) return st;
    if (o.csv && o.json && strcmp(o.csv, o.json) == 0) {
        cli_error(strcmp(o.csv, "-") == 0
                      ? "track: --csv - and --json - would both write to standard output; give one of them a file"
                      : "track: --csv and --json name the same file");
        return EXIT_USAGE;
    }
    if ((st = cli_track_args_check_reading("track", &o.read)) != EXIT_OK) return st;
    jc_Track t;
    if ((st = cli_track_args_load("track", file, &o.read, &sa, &setup, &t)) != EXIT_OK) return st;
    if (o.csv && t.centre_source == JC_TRACK_CENTRE_NONE) {
        cli_error("track: --csv needs the centre's path, which is %s", t.note[JC_TRACK_Q_CENTRE].text);
        jc_track_free(&t);
        return EXIT_USAGE;
    }
    st = write_outputs(&o, file, &t);
    /* standard output carries a file given "-" alone */
    const int text = !(o.csv && strcmp(o.csv, "-") == 0) && !(o.json && strcmp(o.json, "-") == 0);
    if (st == EXIT_OK && text) {
        print_report(file, &t);
        if (o.csv) printf("CSV: %ld frames written to %s\n", t.n, o.csv);
        if (o.json) printf("JSON written to %s\n", o.json);
    }
    jc_track_free(&t);
    if (cli_stop_requested()) return cli_stop_status();
    return st == EXIT_OK ? cli_stdout_finish() : st;
}
