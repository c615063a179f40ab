/*
 * jumpcyl track (issue 16, import): synthetic experiments written as
 * Tracker writes them (.trk, exported tables with tab, semicolon or comma
 * delimiters and a decimal point or comma) are read back by jc_track_read_file
 * to the pixel noise; θ and the hops match the simulation; hostile and
 * malformed files get one line on standard error, exit 2 and no output.
 *
 *   test_track PATH_TO_JUMPCYL
 * JC_TEST_SEED=N repeats the random cases with another seed.
 */
#define _POSIX_C_SOURCE 200809L
#include "../test.h"
#include "../cli_run.h"
#include "synth.h"
#include <jumpcyl/track.h>

#include <cjson/cJSON.h>
#include <sys/stat.h>

static char scratch[] = "/tmp/jc_track_test_XXXXXX";
static uint64_t base_seed = 16;

static void scratch_path(char *buf, size_t len, const char *name) { snprintf(buf, len, "%s/%s", scratch, name); }

static syn_Camera camera(double noise_px, uint64_t seed)
{
    /* Rolled, scaled and offset, with a few frames of each track missing;
     * the rest of the camera model (jitter, mirror, pan) is off. */
    return (syn_Camera){
        .fps = 60,
        .stepsize = 1,
        .startframe = 5,
        .px_per_m = 560,
        .roll_deg = 3.5,
        .cx_px = 110,
        .cy_px = 160,
        .noise_px = noise_px,
        .mark_offset_m = 0.055, /* the paper's rod: on the direction C -> G */
        .missing_centre = {17, 40, 41},
        .n_missing_centre = 3,
        .missing_mark = {23, 51},
        .n_missing_mark = 2,
        .seed = seed,
    };
}

/* What a load must recover, measured against the truth. */
typedef struct {
    double rms_x_m, rms_h_m, rms_theta_rad, med_omega_err;
    long true_hops, hops;
    long ambiguous;    /* frames whose true height is within 4 sigma of the threshold */
    long flag_errors;  /* frames beyond that whose airborne flag is wrong */
} recovery;

static int cmp_d(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Matches kept frames to the truth by time. */
static int measure(const syn_Experiment *e, const jc_Track *t, double sigma, recovery *r)
{
    memset(r, 0, sizeof *r);
    double sx = 0, sh = 0, sth = 0;
    long nx = 0, nth = 0, j = 0;
    double *werr = malloc((size_t)t->n * sizeof *werr);
    long nw = 0;
    if (!werr) return -1;
    double t0 = NAN; /* the truth's first recorded time */
    t0 = e->t_s[0];
    double theta_shift = NAN;
    int prev_air = 0;
    for (long i = 0; i < t->n; ++i) {
        while (j < e->n && e->t_s[j] - t0 < t->t_s[i] - 1e-6) j++;
        if (j >= e->n || fabs(e->t_s[j] - t0 - t->t_s[i]) > 1e-6) {
            free(werr);
            fprintf(stderr, "frame %ld at t = %.9f has no true frame\n", i, t->t_s[i]);
            return -1;
        }
        const double dx = t->x_m[i] - e->x_m[j], dh = t->y_m[i] - e->y_m[j];
        sx += dx * dx;
        sh += dh * dh;
        nx++;
        if (!isnan(t->theta_rad[i])) {
            if (isnan(theta_shift)) theta_shift = 2 * SYN_PI * floor((t->theta_rad[i] - e->theta_rad[j]) / (2 * SYN_PI) + 0.5);
            const double d = t->theta_rad[i] - theta_shift - e->theta_rad[j];
            sth += d * d;
            nth++;
        }
        if (!isnan(t->omega_radps[i])) werr[nw++] = fabs(t->omega_radps[i] - e->omega_radps[j]);
        const double gap = e->y_m[j] - e->radius_m;
        const int air = gap > t->hop_threshold_m;
        if (air && !prev_air) r->true_hops++;
        prev_air = air;
        if (fabs(gap - t->hop_threshold_m) < 4 * sigma) r->ambiguous++;
        else if (air != t->airborne[i]) r->flag_errors++;
    }
    qsort(werr, (size_t)nw, sizeof *werr, cmp_d);
    r->med_omega_err = nw ? werr[nw / 2] : NAN;
    free(werr);
    r->rms_x_m = sqrt(sx / (double)nx);
    r->rms_h_m = sqrt(sh / (double)nx);
    r->rms_theta_rad = nth ? sqrt(sth / (double)nth) : NAN;
    r->hops = t->hops;
    return 0;
}

static void default_options(jc_TrackOptions *o, const jc_Setup *s)
{
    jc_track_options_default(o);
    o->incline_rad = s->incline_rad;
    o->radius_m = s->body.radius_m;
    o->centre = "axle";
    o->mark = "rod";
}

/* The recovery figures of the last trk and table cases, printed at the end. */
static double worst_ratio_x, worst_ratio_h, worst_ratio_theta;
static double sum_ratio_x, sum_ratio_h, sum_ratio_theta;
static int ratio_cases, hops_exact;
static long hops_true_total;

/* One synthetic case: write, load, compare. kind: "trk" or a table style. */
static int round_trip(const char *kind, syn_Camera c, const char *what)
{
    jc_Setup s = jc_paper_setup(); /* 30 deg: slips, lifts off at 1.19 m, three flights */
    syn_Experiment e;
    ENSURE(syn_make(&s, &c, &e) == 0);
    char path[256];
    scratch_path(path, sizeof path, strcmp(kind, "trk") == 0 ? "case.trk" : "case.txt");
    int st;
    if (strcmp(kind, "trk") == 0) st = syn_write_trk(path, &c, &e, "axle", "rod");
    else if (strcmp(kind, "tab") == 0) st = syn_write_table(path, &c, &e, "axle", "rod", '\t', 0);
    else if (strcmp(kind, "semicolon-comma") == 0) st = syn_write_table(path, &c, &e, "axle", "rod", ';', 1);
    else if (strcmp(kind, "tab-comma") == 0) st = syn_write_table(path, &c, &e, "axle", "rod", '\t', 1);
    else st = syn_write_table(path, &c, &e, "axle", "rod", ',', 0);
    ENSURE(st == 0);
    jc_TrackOptions o;
    default_options(&o, &s);
    o.axes = c.axes_incline ? JC_TRACK_AXES_INCLINE : JC_TRACK_AXES_LEVEL;
    jc_Track t;
    char err[512];
    if (jc_track_read_file(path, &o, &t, err, sizeof err) != 0) {
        syn_free(&e);
        ENSURE_MSG(0, "%s (%s, seed %llu): %s", what, kind, (unsigned long long)c.seed, err);
    }
    recovery r;
    const double sigma = c.noise_px / c.px_per_m;
    const int mst = measure(&e, &t, sigma, &r);
    const double sigma_theta = sqrt(2.0) * sigma / c.mark_offset_m;
    const long n = e.n;
    syn_free(&e);
    const jc_Track tc = t;
    jc_track_free(&t);
    ENSURE_MSG(mst == 0, "%s (%s, seed %llu): frames do not match the truth", what, kind, (unsigned long long)c.seed);
    const double rx = r.rms_x_m / sigma, rh = r.rms_h_m / sigma, rt = r.rms_theta_rad / sigma_theta;
    if (rx > worst_ratio_x) worst_ratio_x = rx;
    if (rh > worst_ratio_h) worst_ratio_h = rh;
    if (rt > worst_ratio_theta) worst_ratio_theta = rt;
    sum_ratio_x += rx;
    sum_ratio_h += rh;
    sum_ratio_theta += rt;
    ratio_cases++;
#define CASE_MSG "%s (%s, noise %.1f px, seed %llu): "
#define CASE_ARGS what, kind, c.noise_px, (unsigned long long)c.seed
    ENSURE_MSG(tc.n == n - c.n_missing_centre, CASE_MSG "%ld frames kept of %ld", CASE_ARGS, tc.n, n);
    ENSURE_MSG(tc.gaps == c.n_missing_centre, CASE_MSG "%ld gaps, %d made", CASE_ARGS, tc.gaps, c.n_missing_centre);
    /* The clip's rate exactly; a table's from its jittered times (the span's
     * ends are off by up to the jitter). */
    const double rate_tol = strcmp(kind, "trk") == 0 ? 1e-9 : 3e-3;
    ENSURE_MSG(fabs(tc.frame_rate_hz - c.fps) < rate_tol * c.fps, CASE_MSG "frame rate %g", CASE_ARGS, tc.frame_rate_hz);
    ENSURE_MSG(tc.has_mark && strcmp(tc.centre_name, "axle") == 0 && strcmp(tc.mark_name, "rod") == 0,
               CASE_MSG "tracks '%s', '%s'", CASE_ARGS, tc.centre_name, tc.mark_name);
    /* Positions to the noise: the RMS error of each coordinate is sigma for
     * Gaussian noise; 1.5 sigma allows for the fitted surface and the sample. */
    ENSURE_MSG(rx < 1.5, CASE_MSG "RMS x error %.3g mm = %.2f sigma", CASE_ARGS, r.rms_x_m * 1e3, rx);
    ENSURE_MSG(rh < 1.5, CASE_MSG "RMS height error %.3g mm = %.2f sigma", CASE_ARGS, r.rms_h_m * 1e3, rh);
    ENSURE_MSG(rt < 1.5, CASE_MSG "RMS theta error %.3g rad = %.2f sigma_theta", CASE_ARGS, r.rms_theta_rad, rt);
    /* omega by central differences: noise sigma_theta / dt, and the impacts. */
    ENSURE_MSG(r.med_omega_err < 1.5 * sigma_theta * c.fps, CASE_MSG "median omega error %.3g rad/s", CASE_ARGS,
               r.med_omega_err);
    /* The hops the camera saw: runs of frames whose true height is above
     * the threshold (a bounce between two frames in the air is one). */
    ENSURE_MSG(r.true_hops >= 2, CASE_MSG "the truth has %ld hops", CASE_ARGS, r.true_hops);
    /* Frames clearly above or below the threshold are flagged as they are;
     * each frame near it (noise can put it either side) may add or split a hop. */
    ENSURE_MSG(r.flag_errors == 0, CASE_MSG "%ld frames far from the threshold flagged wrongly", CASE_ARGS,
               r.flag_errors);
    hops_exact += r.hops == r.true_hops;
    hops_true_total += r.true_hops;
    ENSURE_MSG(labs(r.hops - r.true_hops) <= r.ambiguous, CASE_MSG "%ld hops found, %ld true, %ld frames near the threshold",
               CASE_ARGS, r.hops, r.true_hops, r.ambiguous);
    if (strcmp(kind, "trk") == 0) {
        ENSURE_MSG(fabs(tc.scale_px_per_m - c.px_per_m) < 1e-9, CASE_MSG "scale %g", CASE_ARGS, tc.scale_px_per_m);
        ENSURE_MSG(tc.dt_jitter_s < 1e-9, CASE_MSG "jitter %g s", CASE_ARGS, tc.dt_jitter_s);
        ENSURE_MSG(fabs(tc.tape_length_m - 1.0) < 1e-12, CASE_MSG "tape %g", CASE_ARGS, tc.tape_length_m);
    } else if (c.jitter_fine > 0) {
        /* Two neighbours off by up to jitter_fine twentieths of a frame each, against a rate known to 3e-3. */
        const double max_jitter = 2.0 * c.jitter_fine / 20.0 / c.fps + 3e-3 * 2 / c.fps;
        ENSURE_MSG(tc.dt_jitter_s > 0 && tc.dt_jitter_s <= max_jitter, CASE_MSG "jitter %g s (at most %g)", CASE_ARGS,
                   tc.dt_jitter_s, max_jitter);
    }
    return 0;
}

static uint64_t seed_of(int i) { return base_seed * 1000 + (uint64_t)i; }

static int test_trk_level_axes(void)
{
    const double noise[] = {0.5, 1.0, 2.0};
    for (int i = 0; i < 6; ++i) {
        syn_Camera c = camera(noise[i % 3], seed_of(i));
        if (round_trip("trk", c, "trk, level axes, camera rolled 3.5 deg") != 0) return 1;
    }
    return 0;
}

static int test_trk_incline_axes_mirrored_stepsize(void)
{
    for (int i = 0; i < 4; ++i) {
        syn_Camera c = camera(1.0, seed_of(100 + i));
        c.axes_incline = 1;
        c.mirror = i % 2;
        c.stepsize = 2; /* a 120 fps video tracked every second frame */
        c.startframe = 0;
        c.roll_deg = -2.0;
        c.cx_px = 1800;
        if (round_trip("trk", c, "trk, axes along the incline, every 2nd frame") != 0) return 1;
    }
    return 0;
}

/* A hand-held camera moved by 40 px at step 30: the .trk's axes have a key
 * frame there; the table, in world coordinates, is as before. */
static int test_camera_moved(void)
{
    const char *kinds[] = {"trk", "tab"};
    for (int i = 0; i < 4; ++i) {
        syn_Camera c = camera(1.0, seed_of(400 + i));
        c.pan_from_step = 30;
        c.pan_dx_px = -40;
        c.pan_dy_px = 12;
        if (round_trip(kinds[i % 2], c, "camera moved, axes key frame") != 0) return 1;
    }
    return 0;
}

static int test_tables(void)
{
    const char *kinds[] = {"tab", "semicolon-comma", "comma", "tab-comma"};
    for (int i = 0; i < 8; ++i) {
        syn_Camera c = camera(i % 2 ? 2.0 : 0.5, seed_of(200 + i));
        c.jitter_fine = 2; /* frame times off by up to 0.1 frame */
        c.mirror = i >= 4;
        if (round_trip(kinds[i % 4], c, "table with jittered times") != 0) return 1;
    }
    return 0;
}

/* A file's text, written to the scratch directory. */
static void put(const char *name, const char *text)
{
    char path[256];
    scratch_path(path, sizeof path, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* The tool on a file: must fail with exit 2, one line naming want, no output file. */
static int refused(const char *name, const char *want, const char *extra)
{
    char path[256], csv[256];
    scratch_path(path, sizeof path, name);
    scratch_path(csv, sizeof csv, "out.csv");
    unlink(csv);
    const char *args[] = {"track", path, "--csv", csv, extra, NULL};
    cli_result r = cli_run(args);
    struct stat sb;
    const int made = stat(csv, &sb) == 0;
    const int ok = r.status == 2 && cli_one_line(r.err) && r.out && r.out[0] == '\0' && !made &&
                   (!want || strstr(r.err, want) != NULL);
    if (!ok)
        fprintf(stderr, "%s: status %d, stdout '%.80s', stderr '%s', csv %s (wanted '%s')\n", name, r.status,
                r.out ? r.out : "", r.err ? r.err : "", made ? "made" : "not made", want ? want : "");
    cli_result_free(&r);
    return ok ? 0 : 1;
}

/* A file of text that the tool must refuse, naming want (as refused). */
static int put_refused(const char *name, const char *text, const char *want)
{
    put(name, text);
    return refused(name, want, NULL);
}

#define TRK_HEAD                                                                                                   \
    "<?xml version=\"1.0\"?>\n<object class=\"org.opensourcephysics.cabrillo.tracker.TrackerPanel\">\n"
#define TRK_CLIP                                                                                                   \
    "<property name=\"videoclip\" type=\"object\"><object class=\"org.opensourcephysics.media.core.VideoClip\">"   \
    "<property name=\"startframe\" type=\"int\">0</property><property name=\"stepsize\" type=\"int\">1</property>" \
    "<property name=\"stepcount\" type=\"int\">4</property></object></property>\n"
#define TRK_DT(v)                                                                                                   \
    "<property name=\"clipcontrol\" type=\"object\"><object class=\"org.opensourcephysics.media.core.ClipControl\">" \
    "<property name=\"delta_t\" type=\"double\">" v "</property></object></property>\n"
#define TRK_COORDS(scale)                                                                                          \
    "<property name=\"coords\" type=\"object\"><object class=\"org.opensourcephysics.media.core.ImageCoordSystem\">" \
    "<property name=\"framedata\" type=\"array\"><property name=\"[0]\" type=\"object\">"                          \
    "<object class=\"org.opensourcephysics.media.core.ImageCoordSystem$FrameData\">"                               \
    "<property name=\"xorigin\" type=\"double\">10</property><property name=\"yorigin\" type=\"double\">300</property>" \
    "<property name=\"angle\" type=\"double\">0</property><property name=\"xscale\" type=\"double\">" scale       \
    "</property><property name=\"yscale\" type=\"double\">" scale "</property></object></property></property>"     \
    "</object></property>\n"
#define PT(i, x, y)                                                                                                 \
    "<property name=\"[" #i "]\" type=\"object\"><object class=\"org.opensourcephysics.cabrillo.tracker.PointMass$FrameData\">" \
    "<property name=\"x\" type=\"double\">" x "</property><property name=\"y\" type=\"double\">" y                 \
    "</property></object></property>"
#define TRK_TRACK(x2)                                                                                              \
    "<property name=\"tracks\" type=\"collection\"><property name=\"item\" type=\"object\">"                       \
    "<object class=\"org.opensourcephysics.cabrillo.tracker.PointMass\"><property name=\"name\" type=\"string\">axle</property>" \
    "<property name=\"framedata\" type=\"array\">" PT(0, "10", "290") PT(1, "20", "295") PT(2, x2, "300")        \
    PT(3, "40", "305") "</property></object></property></property>\n"
#define TRK_TAIL "</object>\n"

static int test_good_small_files(void)
{
    /* The minimal .trk and table the refusals below are variations of. */
    put("ok.trk", TRK_HEAD TRK_CLIP TRK_DT("40") TRK_COORDS("100") TRK_TRACK("30") TRK_TAIL);
    put("ok.txt", "mass A\nt\tx\ty\n0\t0\t0\n0.04\t0.01\t-0.001\n0.08\t0.02\t-0.002\n0.12\t0.03\t-0.003\n");
    const char *files[] = {"ok.trk", "ok.txt"};
    const char *inclines[] = {"26.565", "5.711"}; /* the points' slopes */
    for (int i = 0; i < 2; ++i) {
        char path[256];
        scratch_path(path, sizeof path, files[i]);
        const char *args[] = {"track", path, "--incline", inclines[i], NULL};
        cli_result r = cli_run(args);
        const int ok = r.status == 0 && r.out && strstr(r.out, "25.000 frames/s") && strstr(r.out, "0 hop(s)") &&
                       strstr(r.out, "as given") && strstr(r.out, "(agreed)");
        if (!ok) fprintf(stderr, "%s: status %d\n%s\n%s\n", files[i], r.status, r.out ? r.out : "", r.err ? r.err : "");
        cli_result_free(&r);
        ENSURE(ok);
    }
    return 0;
}

/* Arguments: one file, and an option of compare's or fit's reported as
 * unknown, not its value as a second file. */
static int test_arguments(void)
{
    static const char table[] = "mass A\nt\tx\ty\n0\t0\t0\n0.04\t0.01\t-0.001\n0.08\t0.02\t-0.002\n0.12\t0.03\t-0.003\n";
    char a[256], b[256];
    put("arg-a.txt", table);
    put("arg-b.txt", table);
    scratch_path(a, sizeof a, "arg-a.txt");
    scratch_path(b, sizeof b, "arg-b.txt");
    const struct {
        const char *args[8];
        const char *want;
    } cases[] = {
        {{"track", a, "--from", "1", NULL}, "unknown option '--from'"},
        {{"track", "--from", "1", a, NULL}, "unknown option '--from'"},
        {{"track", a, "--to=1", b, NULL}, "unknown option '--to=1'"},
        {{"track", a, b, NULL}, "one file at a time"},
        {{"track", a, "--incline", "5.711", b, NULL}, "one file at a time"},
        {{"track", "--incline", "5.711", NULL}, "which file?"},
    };
    int bad = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        cli_result r = cli_run(cases[i].args);
        if (r.status != 2 || !cli_one_line(r.err) || !strstr(r.err, cases[i].want)) {
            fprintf(stderr, "case %zu: status %d, stderr '%s' (wanted '%s')\n", i, r.status, r.err ? r.err : "",
                    cases[i].want);
            bad = 1;
        }
        cli_result_free(&r);
    }
    ENSURE(!bad);
    return 0;
}

/* Tables as people make them: Tracker's single-track export (a name row
 * starting with the delimiter, a trailing delimiter), units in the header,
 * a byte order mark and CRLF line ends. */
static int test_table_forms(void)
{
    static const struct {
        const char *text;
        double last_x_m; /* along the incline (level: the incline is 0) */
        const char *name;
    } cases[] = {
        {"\taxle\t\t\nt\tx\ty\t\n0\t0\t0.1\n0.1\t0.01\t0.1\n0.2\t0.02\t0.1\n0.3\t0.03\t0.1\n", 0.03, "axle"},
        {"\xEF\xBB\xBFt (ms);x (cm);y (mm)\r\n0;0;100\r\n100;1,5;100\r\n200;3;100\r\n300;4,5;100\r\n", 0.045, "mass A"},
        {"t x y\n0 0 0.1\n0.1 -0.01 0.1\n0.2 -0.02 0.1\n0.3 -0.04 0.1\n", 0.04, "mass A"}, /* rolls to the left */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        jc_TrackOptions o;
        jc_track_options_default(&o);
        o.incline_rad = 0;
        o.radius_m = 0.1;
        jc_Track t;
        char err[256];
        const int st = jc_track_parse("table", cases[i].text, strlen(cases[i].text), &o, &t, err, sizeof err);
        ENSURE_MSG(st == 0, "case %zu: %s", i, err);
        const int ok = t.n == 4 && fabs(t.x_m[3] - cases[i].last_x_m) < 1e-12 && fabs(t.t_s[3] - 0.3) < 1e-12 &&
                       fabs(t.y_m[2] - 0.1) < 1e-9 && strcmp(t.centre_name, cases[i].name) == 0 && !t.has_mark;
        if (!ok)
            fprintf(stderr, "case %zu: n %ld, x %g, t %g, y %g, centre '%s'\n", i, t.n, t.n ? t.x_m[t.n - 1] : NAN,
                    t.n ? t.t_s[t.n - 1] : NAN, t.n > 2 ? t.y_m[2] : NAN, t.centre_name);
        jc_track_free(&t);
        ENSURE(ok);
    }
    return 0;
}

static int test_refusals(void)
{
    int bad = 0;
    bad += put_refused("empty.trk", "", "empty");
    bad += put_refused("truncated.trk", TRK_HEAD TRK_CLIP TRK_DT("40") "<property name=\"coords\" type=\"obj", "line");
    bad += put_refused("laughs.trk",
                       "<?xml version=\"1.0\"?>\n<!DOCTYPE lolz [<!ENTITY lol \"lol\">"
                       "<!ENTITY lol2 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\">"
                       "<!ENTITY lol3 \"&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;\">]>\n"
                       "<object class=\"org.opensourcephysics.cabrillo.tracker.TrackerPanel\">&lol3;</object>\n",
                       "DTD");
    bad += put_refused("external.trk",
                       "<?xml version=\"1.0\"?>\n<!DOCTYPE x SYSTEM \"http://example.invalid/x.dtd\">\n"
                       "<object class=\"org.opensourcephysics.cabrillo.tracker.TrackerPanel\"></object>\n",
                       "DTD");
    bad += put_refused("nocoords.trk", TRK_HEAD TRK_CLIP TRK_DT("40") TRK_TRACK("30") TRK_TAIL, "coordinate system");
    bad += put_refused("nodt.trk", TRK_HEAD TRK_CLIP TRK_COORDS("100") TRK_TRACK("30") TRK_TAIL, "frame duration");
    bad +=
        put_refused("zeroscale.trk", TRK_HEAD TRK_CLIP TRK_DT("40") TRK_COORDS("0") TRK_TRACK("30") TRK_TAIL, "scale");
    bad += put_refused("nan.trk", TRK_HEAD TRK_CLIP TRK_DT("40") TRK_COORDS("100") TRK_TRACK("NaN") TRK_TAIL,
                       "not a finite number");
    bad +=
        put_refused("negdt.trk", TRK_HEAD TRK_CLIP TRK_DT("-40") TRK_COORDS("100") TRK_TRACK("30") TRK_TAIL, "delta_t");
    bad += put_refused("notracker.trk", "<?xml version=\"1.0\"?>\n<svg></svg>\n", "TrackerPanel");
    bad +=
        put_refused("notracks.trk", TRK_HEAD TRK_CLIP TRK_DT("40") TRK_COORDS("100") TRK_TAIL, "no point-mass track");
    bad += put_refused("backwards.txt", "t\tx\ty\n0\t0\t0\n0.04\t0.01\t0\n0.03\t0.02\t0\n0.12\t0.03\t0\n",
                       "does not increase");
    bad += put_refused("nan.txt", "t;x;y\n0;0;0\n0,04;NaN;0\n0,08;0,02;0\n0,12;0,03;0\n", "not a number");
    bad += put_refused("xonly.txt", "t,x\n0,0\n0.04,0.01\n0.08,0.02\n", "but no");
    bad += put_refused("noheader.txt", "1 2 3\n4 5 6\n", "header");
    bad += put_refused("short.txt", "t\tx\ty\n0\t0\t0\n", "fewer than 3");
    bad += put_refused("binary.txt", "t\tx\ty\n\x01\x02\x7f\xff\n", "not a number");
    bad += put_refused("two.txt",
                       "\tmass A\t\tmass B\t\t\nt\tx\ty\tx\ty\t\n0\t0\t0\t0\t0.05\n0.1\t0.1\t0\t0.1\t0.05\n"
                       "0.2\t0.2\t0\t0.2\t0.05\n0.3\t0.3\t0\t0.3\t0.05\n",
                       "which track is the centre");
    bad += refused("two.txt", "no track named", "--centre=wheel");
    /* Larger than the bound: a sparse file of 65 MiB. */
    char path[256];
    scratch_path(path, sizeof path, "huge.trk");
    FILE *f = fopen(path, "w");
    if (f) {
        fclose(f);
        if (truncate(path, 65L * 1024 * 1024) != 0) bad++;
    }
    bad += refused("huge.trk", "larger than", NULL);
    /* Many elements within the size bound. */
    scratch_path(path, sizeof path, "many.trk");
    f = fopen(path, "w");
    if (f) {
        fputs(TRK_HEAD, f);
        for (long i = 0; i < 4100000; ++i) fputs("<a/><b/>", f);
        fputs(TRK_TAIL, f);
        fclose(f);
    }
    bad += refused("many.trk", "XML elements", NULL);
    ENSURE_MSG(bad == 0, "%d hostile files were not refused as they should be", bad);
    return 0;
}

/* The command's outputs: the CSV and JSON carry every kept frame. */
static int test_cli_outputs(void)
{
    jc_Setup s = jc_paper_setup();
    syn_Camera c = camera(1.0, seed_of(300));
    syn_Experiment e;
    ENSURE(syn_make(&s, &c, &e) == 0);
    char trk[256], csv[256], json[256];
    scratch_path(trk, sizeof trk, "cli.trk");
    scratch_path(csv, sizeof csv, "cli.csv");
    scratch_path(json, sizeof json, "cli.json");
    const long n = e.n - c.n_missing_centre;
    ENSURE(syn_write_trk(trk, &c, &e, "axle", "rod") == 0);
    syn_free(&e);
    const char *args[] = {"track", "--preset", "paper", trk, "--csv", csv, "--json", json, "--mass", "rod", NULL};
    cli_result r = cli_run(args);
    const int ok = r.status == 0 && r.out && strstr(r.out, "tracked ('axle'") && strstr(r.out, "from the mark 'rod'");
    if (!ok) fprintf(stderr, "status %d\n%s\n%s\n", r.status, r.out ? r.out : "", r.err ? r.err : "");
    cli_result_free(&r);
    ENSURE(ok);
    char *text = cli_run_slurp(csv);
    ENSURE(text);
    long lines = 0;
    for (const char *p = text; *p; ++p) lines += *p == '\n';
    static const char head[] = "t_s,x_m,y_m,height_m,centre_sigma_m,mark_x_m,mark_y_m,theta_rad,omega_radps,contact,airborne\n";
    const int head_ok = strncmp(text, head, sizeof head - 1) == 0;
    free(text);
    ENSURE_MSG(head_ok && lines == n + 1, "CSV: %ld lines for %ld frames", lines, n);
    text = cli_run_slurp(json);
    ENSURE(text);
    cJSON *doc = cJSON_Parse(text);
    free(text);
    ENSURE(doc);
    const cJSON *frames = cJSON_GetObjectItem(doc, "frames");
    const cJSON *fd = cJSON_GetObjectItem(doc, "frames_data");
    const cJSON *hops = cJSON_GetObjectItem(doc, "hops");
    const cJSON *derived = cJSON_GetObjectItem(doc, "derived");
    const int jok = cJSON_IsNumber(frames) && (long)frames->valuedouble == n && fd &&
                    cJSON_GetArraySize(cJSON_GetObjectItem(fd, "theta_rad")) == n && cJSON_GetArraySize(hops) >= 2 &&
                    cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetObjectItem(derived, "surface"), "known")) &&
                    cJSON_IsString(cJSON_GetObjectItem(doc, "incline_source"));
    cJSON_Delete(doc);
    ENSURE(jok);
    return 0;
}

static void remove_scratch(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", scratch);
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    const char *env = getenv("JC_TEST_SEED");
    if (env) base_seed = strtoull(env, NULL, 10);
    if (!mkdtemp(scratch)) return 2;
    printf("seed %llu (JC_TEST_SEED)\n", (unsigned long long)base_seed);
    RUN_TEST(test_trk_level_axes);
    RUN_TEST(test_trk_incline_axes_mirrored_stepsize);
    RUN_TEST(test_tables);
    RUN_TEST(test_camera_moved);
    RUN_TEST(test_good_small_files);
    RUN_TEST(test_arguments);
    RUN_TEST(test_table_forms);
    RUN_TEST(test_refusals);
    RUN_TEST(test_cli_outputs);
    if (ratio_cases > 0)
        printf("RMS error / noise over %d cases (of sigma, sigma, sqrt(2) sigma / mark offset): mean x %.2f, height %.2f,\n"
               "theta %.2f; worst x %.2f, height %.2f, theta %.2f\n",
               ratio_cases, sum_ratio_x / ratio_cases, sum_ratio_h / ratio_cases, sum_ratio_theta / ratio_cases,
               worst_ratio_x, worst_ratio_h, worst_ratio_theta);
    if (ratio_cases > 0)
        printf("hops: the count the camera saw found exactly in %d of %d cases (%ld true hops in all)\n", hops_exact,
               ratio_cases, hops_true_total);
    remove_scratch();
    TEST_MAIN_END();
}
