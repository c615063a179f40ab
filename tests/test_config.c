/* Experiment files (cli/inputs/config.c, docs/config.md): the examples read as
 * documented, --dump-config round-trips exactly (dump -> read -> dump is
 * byte-identical, and the setup read back equals the original bit for bit),
 * command-line options override the file's values. Parts run in-process
 * (cli_config_parse, cli_config_write), parts through the built tool
 * (argv[1], optionally under a wrapper such as valgrind). */
#define _POSIX_C_SOURCE 200809L
#include "test.h"
#include "same_setup.h"

#include "inputs.h"
#include "cli_run.h"

#include <stdint.h>

#define PI 3.14159265358979323846

static char *dump(const jc_Setup *s, size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f) return NULL;
    const int st = cli_config_write(f, s);
    fclose(f);
    if (st != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* dump -> read (over a different setup) -> equal bits -> dump: same bytes. */
static int round_trip(const jc_Setup *s, const char *label)
{
    size_t len = 0, len2 = 0;
    char *text = dump(s, &len);
    ENSURE(text);
    jc_Setup back;
    char perr[256] = "";
    ENSURE_OK(jc_preset_setup("hoop", &back, perr, sizeof perr), perr);
    char err[512] = "";
    const int st = cli_config_parse("dump.ini", text, len, &back, err, sizeof err);
    const char *what = "";
    const int same = st == 0 && same_setup(s, &back, &what);
    char *again = st == 0 ? dump(&back, &len2) : NULL;
    const int identical = again && len == len2 && memcmp(text, again, len) == 0;
    if (!same || !identical) fprintf(stderr, "%s: %s; differs in %s; dump:\n%s", label, err, what, text);
    free(text);
    free(again);
    ENSURE_MSG(st == 0, "%s: the dump does not read back", label);
    ENSURE_MSG(same, "%s: read back, %s differs", label, what);
    ENSURE_MSG(identical, "%s: the second dump differs from the first", label);
    return 0;
}

static int test_round_trip_presets(void)
{
    for (int i = 0; jc_preset_name(i); ++i) {
        jc_Setup s;
        char err[256] = "";
        ENSURE_OK(jc_preset_setup(jc_preset_name(i), &s, err, sizeof err), err);
        if (round_trip(&s, jc_preset_name(i))) return 1;
        /* Every field away from its default: air on, negative start, 16 parts. */
        s.drag_coefficient = 0.6;
        s.lift_coefficient = -0.25;
        s.spin_drag_Nms2 = 1.5e-6;
        s.rolling_resistance_m = 1e-3 / 3.0;
        s.theta0_rad = -0.0;
        s.omega0_radps = -2.0 * PI;
        s.body.part_count = JC_MAX_PARTS;
        for (int k = 2; k < JC_MAX_PARTS; ++k)
            s.body.parts[k] = (jc_Part){(jc_PartKind)(k % 4), 1e-3 * k, 1e-3 * k, 0.1 * k, k % 4 == 3 ? 0.0 : 1e-3};
        if (round_trip(&s, "every field set")) return 1;
    }
    return 0;
}

/* A normal double of any sign and magnitude: the shortest decimal form is
 * where round trips usually fail (17 digits, exponents, powers of two). */
static double random_double(uint64_t *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    const uint64_t r = *state >> 11;
    const double mantissa = 1.0 + (double)(r & ((1ULL << 40) - 1)) / (double)(1ULL << 40);
    const int exponent = (int)((*state >> 52) % 600) - 300;
    const double v = ldexp(mantissa, exponent);
    return (*state >> 63) ? -v : v;
}

/* A random double inside [lo, hi] (drawn as above until one falls there):
 * the reader takes each parameter only in its range (jc_param_set). */
static double random_in(uint64_t *state, double lo, double hi)
{
    for (;;) {
        const double v = random_double(state);
        if (v >= lo && v <= hi) return v;
        if (-v >= lo && -v <= hi) return -v;
    }
}

/* The range of a parameter by name (the table's). */
static void range_of(const char *name, double *lo, double *hi)
{
    const jc_ParamInfo *in = jc_param_info(jc_param_find(name));
    *lo = in->min;
    *hi = isinf(in->max) ? 1e300 : in->max_open ? nextafter(in->max, 0.0) : in->max;
}

static int test_round_trip_random(void)
{
    uint64_t state = 20240601;
    for (int n = 0; n < 2000; ++n) {
        jc_Setup s = jc_paper_setup();
        /* parts' fields are any double (the file does not check them); every parameter in its range */
        s.body.parts[0].mass_kg = random_double(&state);
        s.body.parts[1].offset_m = random_double(&state);
        s.body.parts[1].angle_rad = random_double(&state);
        const struct { double *field; const char *name; } fields[] = {
            {&s.body.radius_m, "radius"}, {&s.incline_rad, "incline"}, {&s.gravity_mps2, "g"},
            {&s.mu_static, "mu-s"}, {&s.mu_kinetic, "mu-k"}, {&s.restitution, "restitution"},
            {&s.theta0_rad, "theta0"}, {&s.omega0_radps, "omega0"}, {&s.ramp_length_m, "ramp-length"},
            {&s.paper_cm_offset_m, "paper-d"}, {&s.length_m, "length"}, {&s.air_density_kgpm3, "air-density"},
            {&s.drag_coefficient, "drag-coefficient"}, {&s.lift_coefficient, "lift-coefficient"},
            {&s.spin_drag_Nms2, "spin-drag"}, {&s.rolling_resistance_m, "rolling-resistance"}};
        for (size_t i = 0; i < sizeof fields / sizeof fields[0]; ++i) {
            double lo, hi;
            range_of(fields[i].name, &lo, &hi);
            *fields[i].field = random_in(&state, lo, hi);
        }
        if (round_trip(&s, "random setup")) return 1;
    }
    /* a value out of its range is refused at its line */
    const char *bad = "[contact]\nmu_s = 0.5\n\n[incline]\ngravity = -3.9e21\n";
    jc_Setup s = jc_paper_setup();
    char err[512] = "";
    ENSURE(cli_config_parse("bad.ini", bad, strlen(bad), &s, err, sizeof err) != 0);
    ENSURE_MSG(strstr(err, "bad.ini:5: gravity: gravity -3.9e+21 m/s2 is out of range"), "%s", err);
    return 0;
}

static int load_example(const char *name, jc_Setup *s)
{
    char path[512], err[512] = "";
    snprintf(path, sizeof path, "%s/%s", JC_EXAMPLES_DIR, name);
    *s = jc_paper_setup();
    ENSURE_OK(cli_config_load(path, s, err, sizeof err), err);
    ENSURE_OK(jc_setup_validate(s, err, sizeof err), err);
    return 0;
}

/* The examples say what the presets say, in units a person writes. */
static int test_examples(void)
{
    const char *what = "";
    jc_Setup s, want = jc_paper_setup();
    if (load_example("paper-30deg.ini", &s)) return 1;
    ENSURE_MSG(same_setup(&s, &want, &what), "paper-30deg.ini: %s differs from the paper preset", what);
    const double inclines[] = {15, 45};
    const char *files[] = {"paper-15deg.ini", "paper-45deg.ini"};
    for (int i = 0; i < 2; ++i) {
        if (load_example(files[i], &s)) return 1;
        want.incline_rad = inclines[i] * (PI / 180.0);
        ENSURE_MSG(same_setup(&s, &want, &what), "%s: %s differs", files[i], what);
    }
    if (load_example("hopping-hoop.ini", &s)) return 1;
    char err[256] = "";
    ENSURE_OK(jc_preset_setup("hoop", &want, err, sizeof err), err);
    want.omega0_radps = 8.0;
    ENSURE_MSG(same_setup(&s, &want, &what), "hopping-hoop.ini: %s differs from the hoop preset at 8 rad/s", what);
    if (load_example("heavy-wheel.ini", &s)) return 1;
    ENSURE(s.body.part_count == 2 && s.body.parts[0].kind == JC_PART_DISC && s.body.parts[1].kind == JC_PART_POINT);
    ENSURE(s.body.parts[0].radius_m == 0.25 && s.body.parts[1].offset_m == 0.2 && s.paper_cm_offset_m == 0.0);
    return 0;
}

/* A file over a preset: what it leaves out comes from the preset; a new rim
 * radius takes the parts that filled the old rim along. */
static int test_partial_file(void)
{
    jc_Setup s;
    char err[512] = "";
    ENSURE_OK(jc_preset_setup("hoop", &s, err, sizeof err), err);
    const char text[] = "[body]\nradius = 20 cm\n\n[contact]\nmu_s: 0.25 ; inline comment\n";
    ENSURE_OK(cli_config_parse("partial.ini", text, sizeof text - 1, &s, err, sizeof err), err);
    ENSURE(s.body.radius_m == 0.2 && s.body.parts[0].radius_m == 0.2); /* the hoop follows */
    ENSURE(s.body.parts[1].offset_m == 0.1);                            /* the point mass stays */
    ENSURE(s.mu_static == 0.25 && s.mu_kinetic == 0.5 && s.incline_rad == 0.0);
    return 0;
}

/* ---- through the tool ---- */

static char scratch[64];

static char *tool_dump(const char *const *args)
{
    cli_result r = cli_run(args);
    char *out = NULL;
    if (r.status == 0 && r.err && !r.err[0]) {
        out = r.out;
        r.out = NULL;
    } else {
        fprintf(stderr, "status %d: %s", r.status, r.err ? r.err : "");
    }
    cli_result_free(&r);
    return out;
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    fputs(text, f);
    return fclose(f);
}

/* jumpcyl ... --dump-config > a.ini; jumpcyl --config a.ini --dump-config:
 * the same bytes. */
static int cli_round_trip(const char *const *args, const char *label)
{
    char *first = tool_dump(args);
    ENSURE_MSG(first, "%s: --dump-config failed", label);
    char path[128];
    snprintf(path, sizeof path, "%s/dump.ini", scratch);
    ENSURE(write_text(path, first) == 0);
    const char *again_args[] = {"predict", "--config", path, "--dump-config", NULL};
    char *second = tool_dump(again_args);
    const int same = second && strcmp(first, second) == 0;
    if (!same) fprintf(stderr, "first:\n%s\nsecond:\n%s\n", first, second ? second : "(failed)");
    free(first);
    free(second);
    unlink(path);
    ENSURE_MSG(same, "%s: dump -> read -> dump differs", label);
    return 0;
}

/* One vocabulary: every single-valued setup option, written under its own
 * name in its section of a file (with a hyphen as on the command line, and
 * with an underscore), gives the setup the option gives. */
static int test_option_names_in_files(void)
{
    static const struct {
        const char *option, *section, *value;
    } cases[] = {
        {"radius", "body", "12cm"},          {"disc-mass", "body", "40g"},         {"rod-mass", "body", "30g"},
        {"rod-offset", "body", "6cm"},       {"rod-radius", "body", "3mm"},        {"length", "body", "8cm"},
        {"incline", "incline", "20"},        {"g", "incline", "9.81"},             {"ramp-length", "incline", "4"},
        {"mu", "contact", "0.4"},            {"mu-s", "contact", "0.7"},           {"mu-k", "contact", "0.3"},
        {"restitution", "contact", "0.5"},   {"impact-law", "contact", "newton"},
        {"rolling-resistance", "contact", "1mm"}, {"theta0", "start", "10"},      {"omega0", "start", "2"},
        {"air-density", "air", "1.1"},       {"drag-coefficient", "air", "0.6"},   {"lift-coefficient", "air", "0.2"},
        {"spin-drag", "air", "1e-6"},        {"paper-d", "paper", "2.7cm"},
    };
    int checked = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        cli_SetupArgs a;
        memset(&a, 0, sizeof a);
        const int idx = jc_param_find(cases[i].option);
        ENSURE_MSG(idx >= 0, "%s", cases[i].option);
        a.value[idx] = cases[i].value;
        jc_Setup from_option;
        char err[512] = "";
        ENSURE_MSG(cli_setup_build(&a, &from_option, err, sizeof err) == 0, "--%s %s: %s", cases[i].option,
                   cases[i].value, err);
        for (int underscore = 0; underscore < 2; ++underscore) {
            char key[64], text[256];
            snprintf(key, sizeof key, "%s", cases[i].option);
            for (char *c = key; underscore && *c; ++c)
                if (*c == '-') *c = '_';
            snprintf(text, sizeof text, "[%s]\n%s = %s\n", cases[i].section, key, cases[i].value);
            jc_Setup from_file = jc_paper_setup();
            ENSURE_MSG(cli_config_parse("t.ini", text, strlen(text), &from_file, err, sizeof err) == 0, "%s: %s", text,
                       err);
            const char *what = "";
            ENSURE_MSG(same_setup(&from_option, &from_file, &what), "'%s' in [%s]: %s differs from --%s %s", key,
                       cases[i].section, what, cases[i].option, cases[i].value);
            ++checked;
        }
    }
    /* every single-valued option of the command line (every parameter) is in the list */
    const int options = jc_param_count();
    ENSURE_MSG(options == (int)(sizeof cases / sizeof cases[0]), "%d options, %zu cases", options,
               sizeof cases / sizeof cases[0]);
    const char *both = "[contact]\nmu = 0.4\nmu_s = 0.5\n";
    jc_Setup s = jc_paper_setup();
    char err[512] = "";
    ENSURE(cli_config_parse("t.ini", both, strlen(both), &s, err, sizeof err) != 0 && strstr(err, "either mu"));
    printf("  %d option names read from files as the options read them\n", checked);
    return 0;
}

static int test_cli_round_trip(void)
{
    const char *plain[] = {"predict", "--dump-config", NULL};
    const char *hoop[] = {"simulate", "--preset", "hoop", "--dump-config", NULL};
    const char *options[] = {"predict", "--incline", "17.3deg", "--mu-s", "0.3", "--mu-k", "0.2", "--omega0", "33rpm",
                             "--part", "hoop:mass=12.5g", "--part", "rod:mass=3g,offset=4cm,radius=1mm,angle=90deg",
                             "--drag-coefficient", "0.6", "--air-density", "1.2kg/m3", "--dump-config", NULL};
    if (cli_round_trip(plain, "paper") || cli_round_trip(hoop, "hoop") || cli_round_trip(options, "options")) return 1;
    const char *examples[] = {"paper-15deg.ini", "paper-30deg.ini", "paper-45deg.ini", "hopping-hoop.ini",
                              "heavy-wheel.ini"};
    for (size_t i = 0; i < sizeof examples / sizeof examples[0]; ++i) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", JC_EXAMPLES_DIR, examples[i]);
        const char *args[] = {"paper", "--config", path, "--dump-config", NULL};
        if (cli_round_trip(args, examples[i])) return 1;
    }
    return 0;
}

/* Options replace the file's values, whatever their order on the line. */
static int test_cli_overrides(void)
{
    char path[512];
    snprintf(path, sizeof path, "%s/paper-15deg.ini", JC_EXAMPLES_DIR);
    const char *with_file[] = {"predict", "--incline", "45", "--config", path, "--mu", "0.3", "--rod-mass", "40g",
                               "--dump-config", NULL};
    const char *without[] = {"predict", "--incline", "45", "--mu", "0.3", "--rod-mass", "40g", "--dump-config", NULL};
    char *a = tool_dump(with_file), *b = tool_dump(without);
    const int same = a && b && strcmp(a, b) == 0;
    free(a);
    free(b);
    ENSURE_MSG(same, "--config FILE with options differs from the same options alone");
    return 0;
}

/* Each example runs through every command that reads a setup; paper only
 * with the paper's cylinder (the body its Table 1 measured), refuses the others. */
static int test_cli_examples_run(void)
{
    const char *examples[] = {"paper-45deg.ini", "hopping-hoop.ini", "heavy-wheel.ini"};
    const char *commands[] = {"predict", "simulate", "paper"};
    for (size_t i = 0; i < sizeof examples / sizeof examples[0]; ++i) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", JC_EXAMPLES_DIR, examples[i]);
        for (size_t k = 0; k < sizeof commands / sizeof commands[0]; ++k) {
            const char *args[] = {commands[k], "--config", path, "--json", NULL};
            cli_result r = cli_run(args);
            const int refused = k == 2 && i > 0;
            const int ok = refused ? r.status == 2 && r.err && strstr(r.err, "other than the paper's cylinder") &&
                                         r.out && !r.out[0]
                                   : r.status == 0 && r.err && !r.err[0] && r.out && r.out[0] == '{';
            if (!ok) fprintf(stderr, "%s --config %s: status %d, %s", commands[k], examples[i], r.status, r.err);
            cli_result_free(&r);
            ENSURE_MSG(ok, "%s with %s", commands[k], examples[i]);
        }
    }
    return 0;
}

/* A CSV written whole, with the mode of a new file, and replacing an
 * existing file (and no temporary file left beside it). */
static int test_cli_csv_written(void)
{
    char path[128];
    snprintf(path, sizeof path, "%s/run.csv", scratch);
    ENSURE(write_text(path, "old\n") == 0);
    const char *args[] = {"simulate", "--preset", "hoop", "--omega0", "8", "--csv", path, NULL};
    cli_result r = cli_run(args);
    const int ok = r.status == 0 && r.err && !r.err[0];
    cli_result_free(&r);
    ENSURE_MSG(ok, "simulate --csv failed");
    char *csv = cli_run_slurp(path);
    const int whole = csv && strncmp(csv, "t_s,mode,", 9) == 0 && csv[strlen(csv) - 1] == '\n';
    free(csv);
    unlink(path);
    ENSURE_MSG(whole, "the CSV is not complete");
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    strcpy(scratch, "/tmp/jc_config_XXXXXX");
    if (!mkdtemp(scratch)) return 2;
    RUN_TEST(test_round_trip_presets);
    RUN_TEST(test_round_trip_random);
    RUN_TEST(test_examples);
    RUN_TEST(test_partial_file);
    RUN_TEST(test_option_names_in_files);
    RUN_TEST(test_cli_round_trip);
    RUN_TEST(test_cli_overrides);
    RUN_TEST(test_cli_examples_run);
    RUN_TEST(test_cli_csv_written);
    rmdir(scratch);
    TEST_MAIN_END();
}
