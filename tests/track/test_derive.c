/* What a video tells (issue 26): synthetic videos with known truth, read as
 * a file is (cli/track/synthetic.c writes Tracker's level axes).
 *  - a mark on the rim alone: the centre recovered by fitting rolling, within
 *    2 mm (RMS over the frames in contact) at 30 to 120 frames/s and 1 to
 *    1.5 mm of noise, each frame within 4 of its stated errors; no hops;
 *  - clips without a jump report no hops (a uniform disc on 30 deg, tracked;
 *    a ring on the floor, its mark alone);
 *  - the incline measured from the frames in contact, within 3 of its
 *    errors; a wrong one given is refused naming the video's; axes laid
 *    along the incline leave its angle unknown, and compare says so;
 *  - every readable file gives a report (exit 0), and an output that needs
 *    what the file lacks is refused (exit 2, one line, no file).
 *
 *   test_derive PATH_TO_JUMPCYL; JC_TEST_SEED=N for other seeds. */
#define _POSIX_C_SOURCE 200809L
#include <jumpcyl/track.h>
#include "synth_table.h"
#include "../cli_run.h"
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

static uint64_t base_seed = 26;
static char scratch[] = "/tmp/jc_derive_test_XXXXXX";

static int test_rim_mark_recovery(void)
{
    const jc_Setup s = synth_loaded_ring();
    const double fps[] = {30, 30, 60, 120}, noise[] = {1.5e-3, 1.5e-3, 1.5e-3, 1e-3};
    for (int c = 0; c < 4; ++c) {
        const uint64_t seed = base_seed * 100 + (uint64_t)c;
        jc_TrackSynthOptions o = synth_camera(fps[c], noise[c], JC_TRACK_SYNTH_MARK_ONLY, seed, 0.1);
        jc_Track t, truth;
        char err[256];
        ENSURE_MSG(jc_track_synthesize(&s, &o, &t, err, sizeof err) == 0, "%s", err);
        o.sigma_m = 0.0;
        o.tracks = JC_TRACK_SYNTH_BOTH;
        ENSURE_MSG(jc_track_synthesize(&s, &o, &truth, err, sizeof err) == 0, "%s", err);
        /* Both frames are Tracker's level axes turned onto their measured
         * surface; the truth's (noise-free) is the floor exactly. */
        double ss = 0, worst = 0;
        long m = 0, beyond = 0;
        for (long i = 0; i < t.n && i < truth.n; ++i) {
            if (!t.contact[i] || isnan(t.x_m[i])) continue;
            const double d = hypot(t.x_m[i] - truth.x_m[i], t.y_m[i] - truth.y_m[i]);
            ss += d * d;
            worst = fmax(worst, d);
            beyond += d > 4.0 * t.centre_sigma_m[i] + 5e-4;
            m++;
        }
        const double rms = m ? sqrt(ss / (double)m) : NAN;
        printf("mark only, %.0f fps, %.1f mm: centre %s, %ld of %ld frames rolling, error RMS %.2f mm (largest "
               "%.2f, %ld beyond 4 stated sigma), stated %.2f mm (median); a = %.2f +- %.2f cm; noise %.2f mm; %ld "
               "hops; incline %.3f +- %.3f deg\n",
               fps[c], noise[c] * 1e3, t.centre_source == JC_TRACK_CENTRE_FROM_MARK ? "recovered" : "NOT recovered", m, t.n,
               rms * 1e3, worst * 1e3, beyond, t.centre_sigma_median_m * 1e3, t.mark_radius_m * 100,
               t.mark_radius_sigma_m * 100, t.sigma_m * 1e3, t.hops, t.incline_rad * 180 / SYNTH_PI,
               t.incline_sigma_rad * 180 / SYNTH_PI);
        const int ok = t.centre_source == JC_TRACK_CENTRE_FROM_MARK && m >= t.n * 9 / 10 && rms <= 2e-3 && beyond == 0 &&
                       t.hops == 0 && fabs(t.mark_radius_m - 0.1) <= 3.0 * t.mark_radius_sigma_m + 2e-4 &&
                       fabs(t.incline_rad) <= 3.0 * t.incline_sigma_rad + 1e-4;
        jc_track_free(&t);
        jc_track_free(&truth);
        ENSURE_MSG(ok, "seed %llu", (unsigned long long)seed);
    }
    return 0;
}

/* A uniform disc on 30 deg (d = 0: it never jumps), both tracks, 2 mm of
 * noise: no hops, the incline within 3 of its errors. */
static int test_no_jump_no_hops(void)
{
    jc_Setup s;
    char err[256];
    ENSURE(jc_preset_setup("disc", &s, err, sizeof err) == JC_OK);
    for (int c = 0; c < 4; ++c) {
        const uint64_t seed = base_seed * 100 + 10 + (uint64_t)c;
        const jc_TrackSynthOptions o = synth_camera(c % 2 ? 60 : 240, 2e-3, JC_TRACK_SYNTH_BOTH, seed, 0.05);
        jc_Track t;
        ENSURE_MSG(jc_track_synthesize(&s, &o, &t, err, sizeof err) == 0, "%s", err);
        const double dev = (t.incline_rad - s.incline_rad) / t.incline_sigma_rad;
        printf("disc on 30 deg, %.0f fps: %ld hops, %ld of %ld frames in contact, incline %.3f +- %.3f deg (%.1f "
               "sigma off), noise %.2f mm (true 2)\n",
               o.fps_hz, t.hops, t.contact_frames, t.n, t.incline_rad * 180 / SYNTH_PI,
               t.incline_sigma_rad * 180 / SYNTH_PI, dev, t.sigma_m * 1e3);
        const int ok = t.hops == 0 && fabs(dev) <= 3.0 && t.contact_frames >= t.n * 9 / 10;
        jc_track_free(&t);
        ENSURE_MSG(ok, "seed %llu", (unsigned long long)seed);
    }
    return 0;
}

static void path_of(char *buf, size_t len, const char *name) { snprintf(buf, len, "%s/%s", scratch, name); }

/* Runs of spaces and line breaks as one space: the report wraps its notes. */
static void squeeze(char *s)
{
    char *w = s;
    for (const char *p = s; *p; ++p) {
        const int space = *p == ' ' || *p == '\n';
        if (space && w > s && w[-1] == ' ') continue;
        *w++ = space ? ' ' : *p;
    }
    *w = '\0';
}

/* The tool's run; 0 when its status is want and its output holds text
 * (stdout for 0, a single stderr line for others), and no file out was made. */
static int expect(const char *const *args, int want, const char *text, const char *out)
{
    if (out) unlink(out);
    cli_result r = cli_run(args);
    if (r.out) squeeze(r.out);
    const char *where = want == 0 ? r.out : r.err;
    const int ok = r.status == want && where && (!text || strstr(where, text)) && (want == 0 || cli_one_line(r.err)) &&
                   (!out || want == 0 || !cli_file_exists(out));
    if (!ok)
        fprintf(stderr, "%s %s ...: status %d (want %d), wanted '%s'\nstdout: %s\nstderr: %s\n", args[0], args[1],
                r.status, want, text ? text : "", r.out ? r.out : "", r.err ? r.err : "");
    cli_result_free(&r);
    return ok ? 0 : 1;
}

/* The paper's cylinder on 30 deg with level axes: the incline measured;
 * --incline 25 refused naming it; 31 (within 2 deg, beyond 3 sigma and 0.5
 * deg) read with the data's surface, 30.3 (within 0.5 deg) with the surface
 * along it; axes along the incline without an angle: the
 * report says unknown, compare refuses and says to give --incline. */
static int test_incline(void)
{
    char level[256], along[256];
    path_of(level, sizeof level, "level.txt");
    path_of(along, sizeof along, "along.txt");
    jc_Setup s = jc_paper_setup();
    s.mu_kinetic = 0.4;
    const jc_TrackSynthOptions o = synth_camera(60, 1e-3, JC_TRACK_SYNTH_BOTH, base_seed * 100 + 20, 0.055);
    ENSURE(synth_table_write(level, &s, &o, NULL) == 0);
    int bad = 0;
    const char *measured[] = {"track", level, NULL};
    bad += expect(measured, 0, "measured: the line through", NULL);
    const char *wrong[] = {"track", level, "--incline", "25", NULL};
    bad += expect(wrong, 2, "disagrees with the video: the centres in contact lie on a line at", NULL);
    const char *near[] = {"track", level, "--incline", "31", NULL};
    bad += expect(near, 0, "the surface is their line, the model's incline the one given", NULL);
    const char *nearer[] = {"track", level, "--incline", "30.3", NULL};
    bad += expect(nearer, 0, "beyond 3 sigma but within 0.5 deg, so the surface is taken along the incline given",
                  NULL);
    const char *compare_wrong[] = {"compare", "--track", level, "--incline", "35", NULL};
    bad += expect(compare_wrong, 2, "disagrees with the video", NULL);
    /* Axes along the incline: Tracker's world is then the incline frame.
     * The table of a ring rolled along a floor is such a video of a ring on
     * a ramp whose angle the axes hide: read with --axes incline. */
    const jc_Setup run = synth_loaded_ring();
    const jc_TrackSynthOptions oa = synth_camera(60, 1e-3, JC_TRACK_SYNTH_BOTH, base_seed * 100 + 21, 0.055);
    ENSURE(synth_table_write(along, &run, &oa, NULL) == 0);
    const char *unknown[] = {"track", along, "--axes", "incline", NULL};
    bad += expect(unknown, 0, "the incline's angle is not known", NULL);
    const char *cmp_unknown[] = {"compare", "--track", along, "--axes", "incline", NULL};
    bad += expect(cmp_unknown, 2, "give --incline ANGLE", NULL);
    /* Read with level axes it is a floor, which the report says may be an
     * incline filmed along. */
    const char *as_floor[] = {"track", along, NULL};
    bad += expect(as_floor, 0, "if Tracker's axes lie along an incline, give --axes incline --incline DEG", NULL);
    unlink(level);
    unlink(along);
    ENSURE_MSG(bad == 0, "%d of the incline cases", bad);
    return 0;
}

/* A rim mark's table with its one track named name. */
static int write_mark_named(const char *path, const char *name)
{
    const jc_Setup s = synth_loaded_ring();
    const jc_TrackSynthOptions o = synth_camera(30, 1.5e-3, JC_TRACK_SYNTH_MARK_ONLY, base_seed * 100 + 31, 0.1);
    return synth_table_write(path, &s, &o, name);
}

/* The CSV's height_m (its 4th column) empty on every row; -1 for a file
 * that cannot be read or has no rows. */
static int heights_empty(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[512];
    long rows = 0, filled = 0;
    if (!fgets(line, sizeof line, f)) rows = -1;
    while (rows >= 0 && fgets(line, sizeof line, f)) {
        const char *p = line;
        for (int comma = 0; comma < 3 && p; ++comma) p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL;
        rows++;
        filled += p && *p != ',';
    }
    fclose(f);
    if (rows <= 0) return -1;
    return filled == 0;
}

/* A single track named like the centre is the centre, however it moves:
 * a rim mark named 'axle' is read as a centre whose frames lie on no line,
 * and its CSV has no heights (there is no surface to measure them from);
 * the same track named 'LED' is a mark, the centre recovered. */
static int test_named_centre_kept(void)
{
    char axle[256], led[256], csv[256];
    path_of(axle, sizeof axle, "axle.txt");
    path_of(led, sizeof led, "led.txt");
    path_of(csv, sizeof csv, "axle.csv");
    ENSURE(write_mark_named(axle, "axle") == 0);
    ENSURE(write_mark_named(led, "LED") == 0);
    int bad = 0;
    const char *as_centre[] = {"track", axle, "--preset", "hoop", NULL};
    bad += expect(as_centre, 0, "tracked ('axle'", NULL);
    bad += expect(as_centre, 0, "lie on no line", NULL);
    const char *with_csv[] = {"track", axle, "--preset", "hoop", "--csv", csv, NULL};
    bad += expect(with_csv, 0, "CSV: 46 frames written", NULL);
    const int empty = heights_empty(csv);
    ENSURE_MSG(empty == 1, "height_m in %s: %s", csv, empty < 0 ? "no rows" : "written without a surface");
    const char *as_mark[] = {"track", led, "--preset", "hoop", NULL};
    bad += expect(as_mark, 0, "recovered from the mark 'LED'", NULL);
    unlink(axle);
    unlink(led);
    unlink(csv);
    ENSURE_MSG(bad == 0, "%d of the named-centre cases", bad);
    return 0;
}

/* Every readable file gives a report: three unnamed tracks (which is the
 * centre?), two frames, a mark on a hoop that slides most of the time (rolling
 * does not explain it); --csv, which needs the centre, is refused for them. */
static int test_every_file_reports(void)
{
    char three[256], two[256], slide[256], csv[256];
    path_of(three, sizeof three, "three.txt");
    path_of(two, sizeof two, "two.txt");
    path_of(slide, sizeof slide, "slide.txt");
    path_of(csv, sizeof csv, "out.csv");
    FILE *f = fopen(three, "w");
    ENSURE(f);
    fputs("#multi:\n\tA\t\tB\t\tC\t\nt\tx\ty\tx\ty\tx\ty\n", f);
    for (int i = 0; i < 20; ++i)
        fprintf(f, "%.4f\t%.4f\t0.1\t%.4f\t0.15\t%.4f\t0.2\n", i / 30.0, 0.01 * i, 0.01 * i + 0.05, 0.01 * i - 0.05);
    fclose(f);
    f = fopen(two, "w");
    ENSURE(f);
    fputs("t\tx\ty\n0\t0\t0.1\n0.0333\t0.01\t0.1\n", f);
    fclose(f);
    jc_Setup hoop;
    char err[128];
    ENSURE(jc_preset_setup("hoop", &hoop, err, sizeof err) == JC_OK);
    const jc_TrackSynthOptions o = synth_camera(30, 1.5e-3, JC_TRACK_SYNTH_MARK_ONLY, base_seed * 100 + 30, 0.1);
    ENSURE(synth_table_write(slide, &hoop, &o, NULL) == 0);
    int bad = 0;
    const char *a[] = {"track", three, NULL};
    bad += expect(a, 0, "which track is the centre? none is named like the axle (centre, center, axle, axis, hub); "
                  "give --centre NAME", NULL);
    bad += expect(a, 0, "theta: not known: a mark's angle is seen from the centre, which is not known", NULL);
    const char *a_csv[] = {"track", three, "--csv", csv, NULL};
    bad += expect(a_csv, 2, "--csv needs the centre's path", csv);
    const char *b[] = {"track", two, NULL};
    bad += expect(b, 0, "fewer than 3 frames", NULL);
    const char *c[] = {"track", slide, "--preset", "hoop", NULL};
    bad += expect(c, 0, "not recovered: rolling does not explain the mark", NULL);
    const char *c_fit[] = {"fit", "--track", slide, "--preset", "hoop", "--free", "mu_k", NULL};
    bad += expect(c_fit, 2, "the centre's path is not recovered", NULL);
    unlink(three);
    unlink(two);
    unlink(slide);
    ENSURE_MSG(bad == 0, "%d of the report cases", bad);
    return 0;
}

/* Two tracks named nothing that tells (Tracker's 'mass A', 'mass B'): the
 * centre is the one that keeps to a line. */
static int test_tracks_told_by_motion(void)
{
    char path[256];
    path_of(path, sizeof path, "ab.txt");
    jc_Setup s = jc_paper_setup();
    const jc_TrackSynthOptions o = synth_camera(60, 1e-3, JC_TRACK_SYNTH_BOTH, base_seed * 100 + 40, 0.055);
    jc_TrackRaw raw;
    char err[256];
    ENSURE(jc_track_synth_raw(&s, &o, &raw, err, sizeof err) == 0);
    /* The mark first, then the centre, both named as Tracker names them. */
    jc_TrackPoints tmp = raw.tracks[0];
    raw.tracks[0] = raw.tracks[1];
    raw.tracks[1] = tmp;
    snprintf(raw.tracks[0].name, JC_TRACK_NAME_LEN, "mass A");
    snprintf(raw.tracks[1].name, JC_TRACK_NAME_LEN, "mass B");
    FILE *f = fopen(path, "w");
    ENSURE(f);
    jc_track_write_table(f, &raw);
    fclose(f);
    jc_track_raw_free(&raw);
    const char *args[] = {"track", path, NULL};
    const int bad = expect(args, 0, "tracked ('mass B'", NULL);
    unlink(path);
    ENSURE(bad == 0);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (cli_run_init(argc, argv) != 0) return 2;
    const char *env = getenv("JC_TEST_SEED");
    if (env) base_seed = strtoull(env, NULL, 10);
    if (!mkdtemp(scratch)) return 2;
    printf("seed %llu (JC_TEST_SEED)\n", (unsigned long long)base_seed);
    RUN_TEST(test_rim_mark_recovery);
    RUN_TEST(test_no_jump_no_hops);
    RUN_TEST(test_incline);
    RUN_TEST(test_named_centre_kept);
    RUN_TEST(test_every_file_reports);
    RUN_TEST(test_tracks_told_by_motion);
    rmdir(scratch);
    TEST_MAIN_END();
}
