/* The battery of bad inputs: options, numbers, units, physical ranges,
 * experiment files, unreadable inputs and unwritable outputs, run through
 * the built tool (argv[1], optionally under a wrapper such as valgrind).
 *
 * Each case asserts the exit status (2: bad input, 1: an output could not
 * be written), a one-line message on stderr that contains a key substring
 * naming the bad value (or the path), nothing on stdout, and that no output
 * file was written: simulate cases carry --csv into a scratch directory,
 * alternately a new file, which must not appear, and an existing one,
 * which must keep its content; and nothing else (no temporary file) may
 * appear in the directory. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include "cli_run.h"

#include <dirent.h>
#include <sys/stat.h>

#define MAX_ARGS 16
#define KEEP_TEXT "an earlier result\n"

enum { CSV = 0, NO_CSV = 1 };

typedef struct {
    const char *args[MAX_ARGS]; /* "@NAME": NAME in the scratch directory */
    int status;
    const char *message;        /* must appear in the one-line message */
    int flags;                  /* NO_CSV: the case sets its own outputs */
    const char *file;           /* written to @case.ini first, or NULL */
    size_t file_len;            /* 0: strlen(file) */
    const char *stdout_path;    /* NULL: captured and must stay empty */
} bad_case;

#define A(...) {__VA_ARGS__, NULL}
#define SIM(...) A("simulate", __VA_ARGS__)
/* An experiment file (written to case.ini) that simulate --config refuses
 * with the message. */
#define INI_CASE(message, file) {SIM("--config", "@case.ini"), 2, message, CSV, file, 0, NULL}
#define LONG_LINE "[body]\nradius = 0.1 m ; " \
    "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\n"

static const bad_case cases[] = {
    /* ---- options ---- */
    {SIM("--bogus"), 2, "--bogus", CSV, NULL, 0, NULL},
    {SIM("--help=1"), 2, "option '--help' takes no value", CSV, NULL, 0, NULL},
    {SIM("stray"), 2, "stray", CSV, NULL, 0, NULL},
    {SIM("--radius", "10cm", "--radius", "12cm"), 2, "twice", CSV, NULL, 0, NULL},
    {SIM("--mu", "0.5", "--mu-s", "0.4"), 2, "--mu", CSV, NULL, 0, NULL},
    {SIM("--preset", "nosuch"), 2, "nosuch", CSV, NULL, 0, NULL},
    {A("simulate", "--t-max"), 2, "--t-max", NO_CSV, NULL, 0, NULL},
    {A("simulate", "--csv"), 2, "--csv", NO_CSV, NULL, 0, NULL},
    {A("frobnicate"), 2, "frobnicate", NO_CSV, NULL, 0, NULL},
    {A("paper", "--incline", "20"), 2, "--incline", NO_CSV, NULL, 0, NULL},
    /* The paper measured its own cylinder only: no comparison for another body. */
    {A("paper", "--preset", "hoop"), 2, "--preset hoop gives a body other than the paper's cylinder", NO_CSV, NULL,
     0, NULL},
    {A("--preset", "disc", "--json"), 2, "--preset disc gives a body other", NO_CSV, NULL, 0, NULL},
    {A("paper", "--rod-offset", "4cm"), 2, "--rod-offset 4cm gives a body other", NO_CSV, NULL, 0, NULL},
    {A("paper", "--part", "disc:mass=66.3g"), 2, "--part disc:mass=66.3g gives", NO_CSV, NULL, 0, NULL},
    {A("paper", "--config", "@case.ini"), 2, "case.ini gives a body other", NO_CSV, "[body]\nradius = 12 cm\n", 0,
     NULL},
    {A("plot", "--what", "paper-uncertainty", "--preset", "hoop", "--output", "@fig.png"), 2,
     "--what paper-uncertainty: --preset hoop gives a body other", NO_CSV, NULL, 0, NULL},
    /* ---- numbers and units ---- */
    {SIM("--radius", "10furlongs"), 2, "furlongs", CSV, NULL, 0, NULL},
    {SIM("--mu", "nan"), 2, "'nan'", CSV, NULL, 0, NULL},
    {SIM("--mu", "inf"), 2, "'inf'", CSV, NULL, 0, NULL},
    {SIM("--mu", "-infinity"), 2, "'-infinity'", CSV, NULL, 0, NULL},
    {SIM("--incline", "30x"), 2, "30x", CSV, NULL, 0, NULL},
    {SIM("--radius", ""), 2, "empty value", CSV, NULL, 0, NULL},
    {SIM("--radius", "1e400"), 2, "'1e400' is too large", CSV, NULL, 0, NULL},
    {SIM("--radius", "1e-400"), 2, "'1e-400' is too small", CSV, NULL, 0, NULL},
    {SIM("--mu", "0x1p3"), 2, "0x1p3", CSV, NULL, 0, NULL},
    {SIM("--mu", " 0.5"), 2, "' 0.5'", CSV, NULL, 0, NULL},
    {SIM("--mu", "0.5 "), 2, "'0.5 '", CSV, NULL, 0, NULL},
    {SIM("--mu", "0.5.1"), 2, "0.5.1", CSV, NULL, 0, NULL},
    {SIM("--g", "9.78 m/s"), 2, "'m/s'", CSV, NULL, 0, NULL},
    {SIM("--t-max", "5q"), 2, "'5q'", CSV, NULL, 0, NULL},
    {SIM("--max-events", "1.5"), 2, "'1.5'", CSV, NULL, 0, NULL},
    {SIM("--max-events", "1e8"), 2, "'1e8'", CSV, NULL, 0, NULL},
    {SIM("--part", "rod:mass=fast"), 2, "fast", CSV, NULL, 0, NULL},
    /* ---- physical ranges (the message gives the allowed range) ---- */
    {SIM("--incline", "95"), 2, "incline 95 deg is out of range (allowed: [0, 90) deg)", CSV, NULL, 0, NULL},
    {SIM("--incline", "90"), 2, "incline 90 deg", CSV, NULL, 0, NULL},
    {SIM("--incline", "-5"), 2, "incline -5 deg", CSV, NULL, 0, NULL},
    {SIM("--radius", "0"), 2, "radius 0 m is out of range", CSV, NULL, 0, NULL},
    {SIM("--part", "rod:mass=1e-12,offset=1cm,radius=1mm"), 2, "total mass 1e-12 kg is out of range (allowed: at least 1e-09 kg)", CSV, NULL, 0, NULL},
    {SIM("--radius", "-10cm"), 2, "radius -0.1 m", CSV, NULL, 0, NULL},
    {SIM("--g", "0"), 2, "gravity 0 m/s2 is out of range", CSV, NULL, 0, NULL},
    {SIM("--g", "1e4"), 2, "gravity 10000", CSV, NULL, 0, NULL},
    {SIM("--mu-s", "-0.1"), 2, "static friction -0.1", CSV, NULL, 0, NULL},
    {SIM("--mu-k", "-1"), 2, "kinetic friction -1", CSV, NULL, 0, NULL},
    {SIM("--restitution", "1.5"), 2, "restitution 1.5 ", CSV, NULL, 0, NULL},
    {SIM("--restitution", "-0.1"), 2, "restitution -0.1", CSV, NULL, 0, NULL},
    {SIM("--ramp-length", "0"), 2, "ramp length 0 m", CSV, NULL, 0, NULL},
    {SIM("--ramp-length", "1e9"), 2, "ramp length 1e+09 m", CSV, NULL, 0, NULL},
    {SIM("--theta0", "1e5rad"), 2, "initial angle 5.72958e+06 deg is out of range (allowed: [-572958, 572958] deg)", CSV, NULL, 0, NULL},
    {SIM("--omega0", "1e5"), 2, "initial angular velocity 100000", CSV, NULL, 0, NULL},
    {SIM("--paper-d", "20cm"), 2, "paper-model CM offset 0.2", CSV, NULL, 0, NULL},
    {SIM("--part", "rod:mass=-1g"), 2, "mass -0.001 kg", CSV, NULL, 0, NULL},
    {SIM("--part", "disc:mass=0"), 2, "total mass 0 kg", CSV, NULL, 0, NULL},
    /* Fuzzing found that 1e308 kg overflowed the model and wrote past an array. */
    {SIM("--part", "disc:mass=1e308", "--part", "rod:mass=1g,offset=1cm"), 2, "mass 1e+308 kg is out of range (allowed: [0, 1e+06] kg)", CSV, NULL, 0, NULL},
    {SIM("--radius", "2km"), 2, "radius 2000 m is out of range (allowed: [1e-06, 1000] m)", CSV, NULL, 0, NULL},
    {SIM("--part", "disc:mass=1g", "--part", "point:mass=1g,offset=20cm"), 2, "outside the rim", CSV, NULL, 0, NULL},
    {SIM("--part", "point:mass=1g,radius=1mm"), 2, "must be 0", CSV, NULL, 0, NULL},
    {SIM("--part", "cube:mass=1"), 2, "cube", CSV, NULL, 0, NULL},
    {SIM("--part", "disc:mass=1g,color=red"), 2, "color", CSV, NULL, 0, NULL},
    {SIM("--drag-coefficient", "-1"), 2, "drag coefficient -1", CSV, NULL, 0, NULL},
    {SIM("--air-density", "1000"), 2, "air density 1000", CSV, NULL, 0, NULL},
    {SIM("--rolling-resistance", "6cm"), 2, "rolling resistance 0.06", CSV, NULL, 0, NULL},
    /* ---- simulator bounds ---- */
    {SIM("--t-max", "0"), 2, "time limit 0 s", CSV, NULL, 0, NULL},
    {SIM("--t-max", "1e7"), 2, "time limit 1e+07 s", CSV, NULL, 0, NULL},
    {SIM("--max-events", "0"), 2, "'0' is out of range", CSV, NULL, 0, NULL},
    {SIM("--sample-dt", "-1"), 2, "sample step -1", CSV, NULL, 0, NULL},
    {SIM("--rtol", "1"), 2, "relative tolerance 1", CSV, NULL, 0, NULL},
    {SIM("--atol", "0"), 2, "absolute tolerance 0", CSV, NULL, 0, NULL},
    {SIM("--event-tol", "1"), 2, "event tolerance 1", CSV, NULL, 0, NULL},
    {SIM("--contact-height", "2m"), 2, "contact height 2 m", CSV, NULL, 0, NULL},
    /* ---- input files ---- */
    {SIM("--config", "@missing.ini"), 2, "missing.ini: No such file or directory", CSV, NULL, 0, NULL},
    {SIM("--config", "@"), 2, "Is a directory", CSV, NULL, 0, NULL},
    {SIM("--config", "@case.ini", "--config", "@case.ini"), 2, "--config given twice", CSV, "", 0, NULL},
    {A("predict", "--dump-config", "--mu", "nan"), 2, "'nan'", NO_CSV, NULL, 0, NULL},
    /* ---- experiment files: FILE:LINE: and the bad key or value ---- */
    INI_CASE("case.ini:3: unknown key 'colour' in [body] (allowed: radius, length, disc_mass, rod_mass, rod_offset, rod_radius)",
             "[body]\nradius = 10 cm\ncolour = red\n"),
    INI_CASE("case.ini:2: unknown section [bodyy]", "; a comment\n[bodyy]\nradius = 1\n"),
    INI_CASE("case.ini:5: section [body] given twice (first on line 1)",
             "[body]\nradius = 10 cm\n[incline]\nangle = 5\n[body]\n"),
    INI_CASE("case.ini:3: key 'mu_s' given twice in [contact] (first on line 2)",
             "[contact]\nmu_s = 0.1\nmu_s = 0.2\n"),
    INI_CASE("case.ini:1: key 'radius' before any section", "radius = 1\n"),
    INI_CASE("case.ini:2: angle: 'steep' is not a number", "[incline]\nangle = steep\n"),
    INI_CASE("case.ini:2: radius: '10 furlongs' has an unknown unit 'furlongs'", "[body]\nradius = 10 furlongs\n"),
    INI_CASE("case.ini:2: mu_k: 'nan' is not a number", "[contact]\nmu_k = nan\n"),
    INI_CASE("case.ini:2: restitution: empty value", "[contact]\nrestitution =\n"),
    INI_CASE("case.ini:2: restitution: '0.5 0.6' has an unknown unit '0.6'", "[contact]\nrestitution = 0.5 0.6\n"),
    INI_CASE("case.ini:2: gravity: '1e999 m/s2' is too large", "[incline]\ngravity = 1e999 m/s2\n"),
    INI_CASE("case.ini:2: expected 'key = value', '[section]' or a comment", "[body]\njust words\n"),
    INI_CASE("case.ini:3: expected 'key = value'", "[contact]\nmu_s = 0.3\n    0.4\n"),
    INI_CASE("case.ini:1: section header without ']'", "[body\nradius = 1\n"),
    INI_CASE("case.ini:1: unexpected text after ']'", "[body] radius = 1\n"),
    INI_CASE("case.ini:4: [part.3] without [part.2]",
             "[part.1]\nkind = disc\nmass = 1 g\n[part.3]\nkind = rod\nmass = 1 g\n"),
    INI_CASE("case.ini:1: [part.1] needs 'mass'", "[part.1]\nkind = disc\n"),
    INI_CASE("case.ini:2: kind: unknown part kind 'cube'", "[part.1]\nkind = cube\nmass = 1 g\n"),
    INI_CASE("case.ini:1: unknown section [part.0]", "[part.0]\n"),
    INI_CASE("case.ini:1: unknown section [part.17]", "[part.17]\n"),
    INI_CASE("case.ini:2: line too long (allowed: at most 160 characters)", LONG_LINE),
    /* INI_CASE but for the length: the file goes on past its NUL byte. */
    {SIM("--config", "@case.ini"), 2, "case.ini:2: NUL byte", CSV, "[body]\nradius\0 = 1\n", 19, NULL},
    INI_CASE("restitution 2 is out of range (allowed: [0, 1])", "[contact]\nrestitution = 2\n"),
    INI_CASE("reaches outside the rim", "[body]\nradius = 5 cm\n"),
    INI_CASE("air density 5000 kg/m3", "[air]\ndensity = 5 g/cm3\n"),
    /* ---- the figure commands share the options and the checks ---- */
    {A("plot", "--what", "nosuch", "--output", "@fig.png"), 2, "'nosuch'", NO_CSV, NULL, 0, NULL},
    {A("plot", "--what", "overview", "--output", "@fig.png", "--mu", "nan"), 2, "'nan'", NO_CSV, NULL, 0, NULL},
    {A("plot", "--what", "overview", "--output", "@fig.png", "--config", "@case.ini"), 2, "case.ini:1: unknown section",
     NO_CSV, "[plot]\n", 0, NULL},
    {A("animate", "--size", " 960x540", "--output", "@film.gif"), 2, "--size ' 960x540'", NO_CSV, NULL, 0, NULL},
    {A("animate", "--fps", "0", "--output", "@film.gif"), 2, "--fps '0'", NO_CSV, NULL, 0, NULL},
    /* ---- map: both axes and the output are checked before any case runs ---- */
    {A("map", "--x", "incline=5:5:1", "--y", "mu=0.1,0.2", "--output", "@map.png", "--keep-script"), 2,
     "--x 'incline=5:5:1': 1 value (allowed: at least 2", NO_CSV, NULL, 0, NULL},
    {A("map", "--x", "incline=10,30,20", "--y", "mu=0.1,0.2", "--output", "@map.png"), 2, "the values must increase",
     NO_CSV, NULL, 0, NULL},
    {A("map", "--x", "incline=5,6", "--y", "incline=7,8", "--output", "@map.png"), 2, "both vary incline", NO_CSV,
     NULL, 0, NULL},
    {A("map", "--x", "impact-law=newton,stronge", "--y", "mu=0.1,0.2", "--output", "@map.png"), 2,
     "impact-law is a name", NO_CSV, NULL, 0, NULL},
    {A("map", "--x", "incline=5,6", "--y", "mu=0.1,nan", "--output", "@map.png"), 2, "'nan'", NO_CSV, NULL, 0, NULL},
    {A("map", "--x", "incline=5,6", "--y", "mu=0.1,0.2", "--output", "@map.jpg"), 2, "'.jpg'", NO_CSV, NULL, 0, NULL},
    /* ---- outputs that cannot be written: exit 1, the path named ---- */
    {A("simulate", "--csv", "@nodir/out.csv"), 1, "nodir/out.csv: No such file or directory", NO_CSV, NULL, 0, NULL},
    {A("simulate", "--csv", "/dev/full"), 1, "cannot write /dev/full: No space left on device", NO_CSV, NULL, 0, NULL},
    {A("predict"), 1, "cannot write standard output", NO_CSV, NULL, 0, "/dev/full"},
    {A("predict", "--json"), 1, "standard output", NO_CSV, NULL, 0, "/dev/full"},
    {A("predict", "--dump-config"), 1, "standard output", NO_CSV, NULL, 0, "/dev/full"},
    {A("paper"), 1, "standard output", NO_CSV, NULL, 0, "/dev/full"},
    {A("plot", "--what", "overview", "--output", "@nodir/fig.png"), 1, "nodir/fig.png", NO_CSV, NULL, 0, NULL},
    {A("map", "--x", "incline=5,6", "--y", "mu=0.1,0.2", "--output", "@nodir/map.png", "--keep-script"), 1,
     "nodir/map.png", NO_CSV, NULL, 0, NULL},
};
#define CASE_COUNT ((int)(sizeof cases / sizeof cases[0]))

static char dir[64];

/* "@NAME" -> DIR/NAME, "@" -> DIR. */
static const char *expand(const char *arg, char *buf, size_t n)
{
    if (arg[0] != '@') return arg;
    snprintf(buf, n, "%s%s%s", dir, arg[1] ? "/" : "", arg + 1);
    return buf;
}

static int write_file(const char *name, const char *text, size_t len)
{
    char path[128];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    const int bad = fwrite(text, 1, len, f) != len;
    return fclose(f) != 0 || bad ? -1 : 0;
}

/* The scratch directory holds exactly the expected files; keep.csv
 * unchanged. */
static int dir_is_clean(int with_case_file)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int count = 0, clean = 1;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        ++count;
        if (strcmp(e->d_name, "keep.csv") != 0 && strcmp(e->d_name, "case.ini") != 0) {
            fprintf(stderr, "  unexpected file in the scratch directory: %s\n", e->d_name);
            clean = 0;
        }
    }
    closedir(d);
    char path[128];
    snprintf(path, sizeof path, "%s/keep.csv", dir);
    char *keep = cli_run_slurp(path);
    const int kept = keep && strcmp(keep, KEEP_TEXT) == 0;
    free(keep);
    if (!kept) fprintf(stderr, "  keep.csv was changed\n");
    return clean && kept && count == 1 + with_case_file;
}

static int run_case(int i)
{
    const bad_case *c = &cases[i];
    char bufs[MAX_ARGS][160], csv[128];
    const char *argv[MAX_ARGS + 4];
    int n = 0;
    for (; c->args[n]; ++n) argv[n] = expand(c->args[n], bufs[n], sizeof bufs[n]);
    if (!(c->flags & NO_CSV)) {
        /* Alternately a new file (must not appear) and an existing one (must not change). */
        snprintf(csv, sizeof csv, "%s/%s", dir, i % 2 ? "keep.csv" : "out.csv");
        argv[n++] = "--csv";
        argv[n++] = csv;
    }
    argv[n] = NULL;
    if (c->file && write_file("case.ini", c->file, c->file_len ? c->file_len : strlen(c->file)) != 0) return 1;
    cli_result r = cli_run_to(argv, c->stdout_path);
    const int named = r.err && strstr(r.err, c->message) != NULL;
    const int one_line = cli_one_line(r.err);
    const int quiet = r.out && r.out[0] == '\0';
    const int clean = dir_is_clean(c->file != NULL);
    if (r.status != c->status || !named || !one_line || !quiet || !clean) {
        fprintf(stderr, "case %d:", i);
        for (int k = 0; argv[k]; ++k) fprintf(stderr, " '%s'", argv[k]);
        fprintf(stderr, "\n  status %d (signal %d), expected %d; stderr: %s", r.status, r.signal, c->status,
                r.err ? r.err : "(none)\n");
    }
    cli_result_free(&r);
    char path[128];
    snprintf(path, sizeof path, "%s/case.ini", dir);
    unlink(path);
    ENSURE_MSG(r.status == c->status, "case %d: exit status", i);
    ENSURE_MSG(named, "case %d: the message does not contain '%s'", i, c->message);
    ENSURE_MSG(one_line, "case %d: the message is not exactly one line", i);
    ENSURE_MSG(quiet, "case %d: printed on standard output", i);
    ENSURE_MSG(clean, "case %d: an output file was written or changed", i);
    return 0;
}

static int test_battery(void)
{
    int failed = 0;
    for (int i = 0; i < CASE_COUNT; ++i) failed += run_case(i);
    printf("%d bad inputs, %d failed\n", CASE_COUNT, failed);
    ENSURE(CASE_COUNT >= 40);
    ENSURE(failed == 0);
    return 0;
}

int main(int argc, char **argv)
{
    if (cli_run_init(argc, argv) != 0) return 2;
    strcpy(dir, "/tmp/jc_bad_input_XXXXXX");
    if (!mkdtemp(dir) || write_file("keep.csv", KEEP_TEXT, strlen(KEEP_TEXT)) != 0) {
        perror("scratch directory");
        return 2;
    }
    RUN_TEST(test_battery);
    char path[128];
    snprintf(path, sizeof path, "%s/keep.csv", dir);
    unlink(path);
    rmdir(dir);
    TEST_MAIN_END();
}
