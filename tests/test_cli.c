/* The command-line tool end to end: runs the built binary (argv[1]), reads its
 * JSON back with cJSON and compares the numbers with the library called here
 * on the same setup; exit statuses and one-line messages for bad input. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"
#include "cli_run.h"

#include <cjson/cJSON.h>
#include <jumpcyl/jumpcyl.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
/* The tool writes every double of its JSON so that it reads back to the same
 * double (cli_json_text); 1e-15 allows for a setup built here with another
 * rounding of the tool's units (55 * 1e-3 for "55mm"), and nothing more. */
#define JSON_TOL 1e-15

static const char *cli_path;

/* Runs "jumpcyl ARGS", capturing stdout and stderr. */
static cli_result run(const char *args) { return cli_run_line(cli_path, NULL, args); }

/* Runs a command that must succeed with JSON on stdout and nothing on stderr. */
static cJSON *run_json(const char *args)
{
    cli_result r = run(args);
    cJSON *doc = NULL;
    if (r.status != 0 || !r.out || !r.err || r.err[0])
        fprintf(stderr, "'%s': status %d, stderr '%s'\n", args, r.status, r.err ? r.err : "?");
    else if (!(doc = cJSON_Parse(r.out)))
        fprintf(stderr, "'%s': stdout is not JSON\n", args);
    cli_result_free(&r);
    return doc;
}

/* A number at a dotted path ("rolling.slip.theta"); NAN if absent or not a number. */
static double num(const cJSON *o, const char *path)
{
    char key[128];
    while (o && *path) {
        const size_t n = strcspn(path, ".");
        snprintf(key, sizeof key, "%.*s", (int)n, path);
        o = cJSON_GetObjectItemCaseSensitive(o, key);
        path += n + (path[n] == '.');
    }
    return cJSON_IsNumber(o) ? o->valuedouble : NAN;
}

static int setup_model(const jc_Setup *s, jc_Model *m, jc_PaperResult *p, jc_RollingResult *r)
{
    char err[256] = "";
    ENSURE_OK(jc_model_init(m, s, err, sizeof err), err);
    ENSURE_OK(jc_paper_solve(m, p, err, sizeof err), err);
    ENSURE_OK(jc_rolling_predict(m, r, err, sizeof err), err);
    return 0;
}

static int check_crossing(const cJSON *c, const jc_RollingCrossing *want)
{
    if (!want->found) {
        ENSURE(cJSON_IsNull(c));
        return 0;
    }
    ENSURE_REL(num(c, "theta"), want->state.theta_rad, JSON_TOL);
    ENSURE_REL(num(c, "x"), want->state.x_m, JSON_TOL);
    ENSURE_REL(num(c, "omega"), want->state.omega_radps, JSON_TOL);
    /* Forces may be ~0 at a crossing (N = 0): relative to their size or to
     * 1e-13 N, a 1e-13 part of the paper cylinder's weight (0.65 N). */
    ENSURE_NEAR(num(c, "normal"), want->state.normal_N, JSON_TOL * fabs(want->state.normal_N) + 1e-13);
    ENSURE_NEAR(num(c, "friction"), want->state.friction_N, JSON_TOL * fabs(want->state.friction_N) + 1e-13);
    return 0;
}

/* `jumpcyl predict --json ARGS` against the library on setup s. */
static int check_predict(const char *args, const jc_Setup *s)
{
    jc_Model m;
    jc_PaperResult p;
    jc_RollingResult r;
    if (setup_model(s, &m, &p, &r)) return 1;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "predict --json %s", args);
    cJSON *doc = run_json(cmd);
    ENSURE(doc);
    int bad = 0;
    const cJSON *roots = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(doc, "paper_model"), "roots");
    bad |= !cJSON_IsArray(roots) || cJSON_GetArraySize(roots) != p.root_count;
    for (int i = 0; !bad && i < p.root_count; ++i)
        bad |= !(fabs(cJSON_GetArrayItem(roots, i)->valuedouble - p.theta_rad[i]) <= JSON_TOL * p.theta_rad[i]);
    if (p.first >= 0) {
        bad |= !(fabs(num(doc, "paper_model.first.theta") - p.theta_rad[p.first]) <= JSON_TOL * p.theta_rad[p.first]);
        bad |= !(fabs(num(doc, "paper_model.first.x") - p.x_m[p.first]) <= JSON_TOL * p.x_m[p.first]);
    }
    bad |= !(fabs(num(doc, "paper_model.cm_offset") - m.paper_d_m) <= JSON_TOL * m.paper_d_m);
    const cJSON *ro = cJSON_GetObjectItemCaseSensitive(doc, "rolling");
    bad |= check_crossing(cJSON_GetObjectItemCaseSensitive(ro, "liftoff"), &r.liftoff);
    bad |= check_crossing(cJSON_GetObjectItemCaseSensitive(ro, "slip"), &r.slip);
    const cJSON *end = cJSON_GetObjectItemCaseSensitive(ro, "end");
    bad |= !cJSON_IsString(end) || strcmp(end->valuestring, jc_rolling_end_name(r.end)) != 0;
    bad |= !(fabs(num(doc, "setup.body.cm_offset") - m.body.cm_offset_m) <= JSON_TOL * m.body.cm_offset_m);
    bad |= !(fabs(num(doc, "setup.incline_deg") - s->incline_rad / DEG) <= 1e-13); /* deg conversion */
    /* The setup as the tool read it (SI; exact decimal round trip). */
    const double want[] = {s->gravity_mps2, s->mu_static, s->mu_kinetic, s->restitution, s->theta0_rad,
                           s->omega0_radps, s->ramp_length_m, s->body.radius_m, m.body.mass_kg};
    const char *keys[] = {"setup.g", "setup.mu_s", "setup.mu_k", "setup.restitution", "setup.theta0",
                          "setup.omega0", "setup.ramp_length", "setup.body.radius", "setup.body.mass"};
    for (int i = 0; i < 9; ++i) {
        const int off = !(fabs(num(doc, keys[i]) - want[i]) <= JSON_TOL * fabs(want[i]));
        if (off) fprintf(stderr, "%s: %.17g, expected %.17g\n", keys[i], num(doc, keys[i]), want[i]);
        bad |= off;
    }
    cJSON_Delete(doc);
    ENSURE_MSG(!bad, "'%s' differs from the library", cmd);
    return 0;
}

static int test_predict_json(void)
{
    jc_Setup s = jc_paper_setup();
    if (check_predict("", &s)) return 1;
    jc_PaperResult p;
    jc_RollingResult r;
    jc_Model m;
    if (setup_model(&s, &m, &p, &r)) return 1;
    ENSURE(p.root_count > 0 && r.liftoff.found && r.slip.found); /* the comparison above was not vacuous */

    s.incline_rad = 45 * DEG;
    s.mu_static = s.mu_kinetic = 0.3;
    s.theta0_rad = 10 * DEG;
    s.omega0_radps = 2.0;
    return check_predict("--incline 45 --mu 0.3 --theta0 10 --omega0 2", &s);
}

static int test_paper_json(void)
{
    cJSON *doc = run_json("paper --json");
    ENSURE(doc);
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(doc, "rows");
    const jc_PaperTableRow *table;
    const int n = jc_paper_table(&table);
    int bad = !cJSON_IsArray(rows) || cJSON_GetArraySize(rows) != 3 || n != 3;
    const double inclines[3] = {15, 30, 45};
    for (int i = 0; !bad && i < 3; ++i) {
        const cJSON *row = cJSON_GetArrayItem(rows, i);
        jc_Setup s = jc_paper_setup();
        s.incline_rad = inclines[i] * DEG;
        jc_Model m;
        jc_PaperResult p;
        jc_RollingResult r;
        if (setup_model(&s, &m, &p, &r)) bad = 1;
        bad |= num(row, "incline_deg") != inclines[i];
        bad |= num(row, "printed.theta") != table[i].printed_theta_rad || num(row, "printed.x") != table[i].printed_x_m;
        bad |= num(row, "measured.x") != table[i].measured_x_m || num(row, "measured.error") != table[i].measured_error_m;
        bad |= p.first < 0; /* every row of the paper's setup has an intersection */
        if (!bad) {
            bad |= !(fabs(num(row, "paper_model.theta") - p.theta_rad[p.first]) <= JSON_TOL * p.theta_rad[p.first]);
            bad |= !(fabs(num(row, "paper_model.x") - p.x_m[p.first]) <= JSON_TOL * p.x_m[p.first]);
        }
        bad |= !r.liftoff.found || !r.slip.found;
        if (!bad) {
            bad |= !(fabs(num(row, "rolling.theta") - r.liftoff.state.theta_rad) <= JSON_TOL * r.liftoff.state.theta_rad);
            bad |= !(fabs(num(row, "rolling.x") - r.liftoff.state.x_m) <= JSON_TOL * r.liftoff.state.x_m);
            bad |= !(fabs(num(row, "rolling.slip.theta") - r.slip.state.theta_rad) <= JSON_TOL * r.slip.state.theta_rad);
            bad |= !(fabs(num(row, "rolling.slip.x") - r.slip.state.x_m) <= JSON_TOL * r.slip.state.x_m);
        }
        if (bad) fprintf(stderr, "row %d (%g deg) differs from the library\n", i, inclines[i]);
    }
    cJSON_Delete(doc);
    ENSURE(!bad);
    return 0;
}

/* Same structure and strings; numbers equal to rel of max(|a|, |b|, 1): the
 * floor of 1 (SI) is for values that are zero up to rounding, such as N at
 * the N = 0 crossing (~1e-16 N) or the slip's N (a difference of larger terms). */
static int json_near(const cJSON *a, const cJSON *b, double rel)
{
    if (!a || !b || (a->type & 0xFF) != (b->type & 0xFF)) return 0;
    if (cJSON_IsNumber(a))
        return fabs(a->valuedouble - b->valuedouble) <=
               rel * fmax(fmax(fabs(a->valuedouble), fabs(b->valuedouble)), 1.0);
    if (cJSON_IsString(a)) return strcmp(a->valuestring, b->valuestring) == 0;
    if (cJSON_IsArray(a) || cJSON_IsObject(a)) {
        if (cJSON_GetArraySize(a) != cJSON_GetArraySize(b)) return 0;
        for (const cJSON *x = a->child, *y = b->child; x; x = x->next, y = y->next)
            if (!y || (x->string && strcmp(x->string, y->string) != 0) || !json_near(x, y, rel)) return 0;
    }
    return 1;
}

/* Two commands whose JSON outputs must agree: a value in another unit differs
 * from the SI one by at most an ulp of the conversion, which moves results by
 * a few ulps times their condition number; 1e-12 has room. */
static int same_json(const char *a, const char *b)
{
    cJSON *x = run_json(a), *y = run_json(b);
    const int same = x && y && json_near(x, y, 1e-12);
    cJSON_Delete(x);
    cJSON_Delete(y);
    ENSURE_MSG(same, "'%s' and '%s' differ", a, b);
    return 0;
}

static int test_units(void)
{
    if (same_json("predict --json --radius 10cm", "predict --json --radius 0.1")) return 1;
    if (same_json("predict --json --rod-mass 32.1g", "predict --json --rod-mass 0.0321")) return 1;
    if (same_json("predict --json --ramp-length 3200mm", "predict --json --ramp-length 3.2")) return 1;
    if (same_json("predict --json --incline 30deg", "predict --json")) return 1;

    /* Values as SI, read back from the setup the tool reports. */
    cJSON *doc = run_json("predict --json --rod-mass 32.1g --radius 10cm --omega0 60rpm --g 978cm/s2");
    ENSURE(doc);
    const cJSON *parts = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(doc, "setup"), "body"), "parts");
    const double rod_mass = num(cJSON_GetArrayItem(parts, 1), "mass");
    const double radius = num(doc, "setup.body.radius"), omega0 = num(doc, "setup.omega0"), g = num(doc, "setup.g");
    cJSON_Delete(doc);
    ENSURE_REL(rod_mass, 0.0321, 1e-15); /* 32.1 * 1e-3: one rounding */
    ENSURE_REL(radius, 0.1, 1e-15);
    ENSURE_REL(omega0, 2 * PI, 1e-15);
    ENSURE_REL(g, 9.78, 1e-15);

    /* 0.5 rad: compared with the library at exactly 0.5 rad. */
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 0.5;
    if (check_predict("--incline 0.5rad", &s)) return 1;

    /* The paper's body built from parts (the model then uses the exact d). */
    s = jc_paper_setup();
    s.paper_cm_offset_m = 0.0;
    s.mu_static = s.mu_kinetic = 0.4;
    /* The tool converts "55mm" as 55 * 1e-3 and "34.2g" as 34.2 * 1e-3; the same here. */
    s.body.parts[0].mass_kg = 34.2 * 1e-3;
    s.body.parts[1].mass_kg = 32.1 * 1e-3;
    s.body.parts[1].offset_m = 55 * 1e-3;
    s.body.parts[1].radius_m = 4.75 * 1e-3;
    return check_predict("--mu 0.4 --part disc:mass=34.2g --part rod:mass=32.1g,offset=55mm,radius=4.75mm", &s);
}

/* The units the tool itself prints (UTF-8) read as their ASCII forms,
 * and exactly: the same setup to the last bit. */
static int test_printed_units(void)
{
    if (same_json("predict --json --incline 30\u00b0", "predict --json --incline 30deg")) return 1;
    if (same_json("predict --json --incline '30 \u00b0'", "predict --json --incline 30deg")) return 1;
    if (same_json("predict --json --g 9.81m/s\u00b2", "predict --json --g 9.81m/s2")) return 1;
    if (same_json("predict --json --g 981cm/s\u00b2", "predict --json --g 981cm/s2")) return 1;
    if (same_json("predict --json --air-density 1.2kg/m\u00b3", "predict --json --air-density 1.2kg/m3")) return 1;
    if (same_json("predict --json --omega0 90\u00b0/s", "predict --json --omega0 90deg/s")) return 1;
    if (same_json("predict --json --spin-drag '1e-6 N m s\u00b2'", "predict --json --spin-drag 1e-6")) return 1;
    /* 30 deg, compared with the library: pi/6 as the tool reads degrees */
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 30.0 * DEG;
    return check_predict("--incline 30\u00b0", &s);
}

/* A one-line message on standard error, exit 2, holding each of want. */
static int hint(const char *args, const char *want1, const char *want2)
{
    cli_result r = run(args);
    const int ok = r.status == 2 && cli_one_line(r.err) && strstr(r.err, want1) && (!want2 || strstr(r.err, want2));
    if (!ok) fprintf(stderr, "'jumpcyl %s': status %d, stderr '%s'\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    ENSURE_MSG(ok, "jumpcyl %s: no '%s' in its message", args, want1);
    return 0;
}

/* What a user who mistypes is told. */
static int test_hints(void)
{
    /* a unit given as a word of its own */
    if (hint("predict --radius 10 cm", "write --radius 10cm", "predict: ")) return 1;
    if (hint("simulate --mu 0.4 --incline 30 deg", "write --incline 30deg", NULL)) return 1;
    if (hint("design --jump-at 1.2 m --free rod-offset", "write --jump-at 1.2m", NULL)) return 1;
    if (hint("predict --mu 0.4 stray", "unexpected argument 'stray'", NULL)) return 1;
    /* an unknown option: the nearest of the command's own */
    if (hint("simulate --inclne 30", "did you mean --incline?", "simulate: ")) return 1;
    if (hint("predict --radis 10cm", "did you mean --radius?", NULL)) return 1;
    if (hint("sweep --varry incline=10:20:5 --output -", "did you mean --vary?", NULL)) return 1;
    if (hint("mc --sigmas rod-offset=1mm", "did you mean --sigma?", NULL)) return 1;
    if (hint("predict --rod 3cm", "--rod-mass, --rod-offset, --rod-radius", NULL)) return 1;
    {
        cli_result r = run("predict --xyzzy");
        const int far = r.status == 2 && r.err && !strstr(r.err, "did you mean");
        cli_result_free(&r);
        ENSURE_MSG(far, "predict --xyzzy: a guess for an option that is like none");
    }
    /* a repeated setup option names its command, as every other error */
    if (hint("predict --incline 30 --incline 40", "predict: --incline given twice", NULL)) return 1;
    if (hint("simulate --mu 0.3 --mu 0.4", "simulate: --mu given twice", NULL)) return 1;
    /* a value given to a flag */
    if (hint("sweep --quiet=1 --vary incline=10:20:5 --output -", "option '--quiet' takes no value", NULL)) return 1;
    return 0;
}

/* Whether two runs print the same standard output, both exit 0. */
static int same_output(const char *a, const char *b)
{
    cli_result x = run(a), y = run(b);
    const int same = x.status == 0 && y.status == 0 && x.out && y.out && strcmp(x.out, y.out) == 0;
    if (!same) fprintf(stderr, "'%s' (status %d) and '%s' (status %d) differ\n", a, x.status, b, y.status);
    cli_result_free(&x);
    cli_result_free(&y);
    ENSURE_MSG(same, "'%s' and '%s' differ", a, b);
    return 0;
}

/* One spelling, the options' (mu-k, rod-offset), in every list of names,
 * and the other (mu_k) read the same wherever a name is taken. */
static int test_names(void)
{
    char a[512], b[512];
    snprintf(a, sizeof a, "fit --track '%s/tracker/incline.trk' --free mu-k,restitution --seed 1 --starts 4",
             JC_EXAMPLES_DIR);
    snprintf(b, sizeof b, "fit --track '%s/tracker/incline.trk' --free mu_k,Restitution --seed 1 --starts 4",
             JC_EXAMPLES_DIR);
    if (same_output(a, b)) return 1;
    cli_result r = run(a);
    ENSURE(r.status == 0 && r.out);
    /* the report names the values as the options do */
    const int spelled = strstr(r.out, "\n  mu-k ") && strstr(r.out, "restitution") && !strstr(r.out, "mu_k ");
    cli_result_free(&r);
    ENSURE_MSG(spelled, "fit's report does not name mu-k as the option does");
    snprintf(a, sizeof a, "fit --track '%s/tracker/incline.trk' --free mu_q", JC_EXAMPLES_DIR);
    r = run(a);
    const int allowed = r.err && strstr(r.err, "allowed: mu-s, mu-k, restitution, theta0") != NULL;
    cli_result_free(&r);
    ENSURE_MSG(allowed, "fit's refusal does not list the names in the options' spelling");
    r = run("fit --help");
    ENSURE(r.out && strstr(r.out, "mu-s, mu-k") && !strstr(r.out, "mu_s, mu_k") && strstr(r.out, "rod-offset"));
    cli_result_free(&r);
    /* --vary (map's --x and --y read theirs as --vary does), --sigma, --range, design --free */
    if (same_output("sweep --vary mu_k=0.3,0.4 --output - --quiet", "sweep --vary mu-k=0.3,0.4 --output - --quiet"))
        return 1;
    if (same_output("mc --samples 10 --seed 2 --no-defaults --sigma rod_offset=1mm --range mu_k=0.3:0.5 --threads 1 "
                    "--quiet --json",
                    "mc --samples 10 --seed 2 --no-defaults --sigma rod-offset=1mm --range mu-k=0.3:0.5 --threads 1 "
                    "--quiet --json"))
        return 1;
    cli_result d1 = run("design --jump-at 1.3m --free mu_k --points 40 --threads 1 --csv -");
    cli_result d2 = run("design --jump-at 1.3m --free mu-k --points 40 --threads 1 --csv -");
    const int same_design = d1.status == 0 && d2.status == 0 && d1.out && d2.out && strcmp(d1.out, d2.out) == 0;
    cli_result_free(&d1);
    cli_result_free(&d2);
    ENSURE_MSG(same_design, "design --free mu_k and --free mu-k differ");
    return 0;
}

typedef struct {
    const char *args;
    const char *token; /* the bad value, which the message must name */
} bad_input;

static int test_bad_input_exit_2(void)
{
    const bad_input cases[] = {
        {"predict --bogus", "--bogus"},
        {"predict --radius 10furlongs", "10furlongs"},
        {"predict --mu nan", "nan"},
        {"predict --mu inf", "inf"},
        {"predict --incline 30x", "30x"},
        {"predict --incline 95", "95"},
        {"predict --incline -5", "-5"},
        {"predict --incline", "--incline"},
        {"predict --g 0", "gravity"},
        {"predict --restitution 2", "restitution"},
        {"predict --ramp-length -1", "ramp"},
        {"predict --mu 1e400", "1e400"},
        {"predict --radius 10cm --radius 12cm", "twice"},
        {"predict --mu 0.5 --mu-s 0.4", "--mu"},
        {"predict --preset nosuch", "nosuch"},
        {"predict stray", "stray"},
        {"predict --part cube:mass=1", "cube"},
        {"predict --part rod:mass=1g,color=red", "color"},
        {"predict --part rod:offset=1cm", "mass"},
        {"predict --part rod:mass=1g,", "rod:mass=1g,"},
        {"predict --part rod:mass=1g,mass=2g", "twice"},
        {"predict --part rod:mass=fast", "fast"},
        {"predict --part disc:mass=-1g", "mass"},
        {"predict --part disc:mass=34.2g --part point:mass=10g,offset=20cm", "0.2"},
        {"paper --incline 20", "--incline"},
        {"presets extra", "presets"},
        {"frobnicate", "frobnicate"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        cli_result r = run(cases[i].args);
        const int status = r.status;
        const int named = r.err && strstr(r.err, cases[i].token) != NULL;
        const char *nl = r.err ? strchr(r.err, '\n') : NULL;
        const int one_line = nl && nl[1] == '\0';
        const int quiet = r.out && r.out[0] == '\0';
        if (status != 2 || !named || !one_line || !quiet)
            fprintf(stderr, "'%s': status %d, stderr '%s'\n", cases[i].args, status, r.err ? r.err : "?");
        cli_result_free(&r);
        ENSURE_MSG(status == 2, "'%s' exit status", cases[i].args);
        ENSURE_MSG(named, "'%s': message does not name '%s'", cases[i].args, cases[i].token);
        ENSURE_MSG(one_line, "'%s': message is not exactly one line", cases[i].args);
        ENSURE_MSG(quiet, "'%s': printed on stdout", cases[i].args);
    }
    return 0;
}

static int test_help_and_version(void)
{
    /* every command's --help and -h exit 0 with text on stdout, nothing on stderr */
    const char *ok[] = {"--help", "-h", "help", "predict --help", "paper --help", "presets", "--version", "",
                        "simulate --help", "plot --help", "animate --help", "sweep --help", "mc --help",
                        "map --help", "presets --help", "presets -h", "sweep -h", "mc -h"};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; ++i) {
        cli_result r = run(ok[i]);
        const int good = r.status == 0 && r.out && r.out[0] && r.err && !r.err[0];
        int expected = 1;
        if (good && strcmp(ok[i], "--version") == 0) expected = strstr(r.out, JC_VERSION_STRING) != NULL;
        if (good && strcmp(ok[i], "presets") == 0)
            for (int k = 0; jc_preset_name(k); ++k) expected &= strstr(r.out, jc_preset_name(k)) != NULL;
        cli_result_free(&r);
        ENSURE_MSG(good && expected, "'jumpcyl %s' did not print what it should with status 0", ok[i]);
    }
    return 0;
}

/* A plain body length over 1 m or mass over 10 kg gets a one-line note on
 * how it was read; with a unit, or small, nothing. The paper's model names
 * the start values it ignores. */
static int test_notes(void)
{
    cli_result r = run("predict --radius 1.5 --disc-mass 12");
    ENSURE_MSG(r.status == 0 && strstr(r.err, "--radius 1.5 was read as 1.5 m") && strstr(r.err, "1.5cm") &&
                   strstr(r.err, "--disc-mass 12 was read as 12 kg") && strstr(r.err, "12g"),
               "stderr: %s", r.err);
    int lines = 0;
    for (const char *c = r.err; *c; ++c) lines += *c == '\n';
    ENSURE_MSG(lines == 2, "%d lines", lines);
    cli_result_free(&r);
    r = run("predict --radius 15cm --disc-mass 40g --ramp-length 5");
    ENSURE_MSG(r.status == 0 && r.err[0] == '\0', "stderr: %s", r.err);
    ENSURE(strstr(r.out, "ignores theta0") == NULL);
    cli_result_free(&r);
    r = run("predict --theta0 5");
    ENSURE(r.status == 0 && strstr(r.out, "ignores theta0 = 5 deg"));
    cli_result_free(&r);
    r = run("paper --omega0 2");
    ENSURE(r.status == 0 && strstr(r.out, "paper's model ignores theta0 = 0 deg and omega0 = 2 rad/s"));
    cli_result_free(&r);
    r = run("paper");
    ENSURE(r.status == 0 && !strstr(r.out, "model ignores"));
    cli_result_free(&r);
    /* The paper's own body, given option by option, is still the body it
     * measured (another is refused: tests/test_bad_input.c). */
    r = run("paper --preset paper --rod-offset 5.5cm --radius 0.1 --mu 0.3");
    ENSURE_MSG(r.status == 0 && strstr(r.out, "Measured jump position"), "stderr: %s", r.err);
    cli_result_free(&r);
    return 0;
}

/* "-0.000" (a value that rounds to zero, printed with a sign) in text. */
static const char *negative_zero(const char *s)
{
    for (const char *p = strstr(s, "-0"); p; p = strstr(p + 1, "-0")) {
        const char *q = p + 2;
        if (*q == '.') ++q;
        while (*q == '0') ++q;
        if (q > p + 2 && !(*q >= '1' && *q <= '9')) return p;
    }
    return NULL;
}

static int test_no_negative_zeros(void)
{
    const char *runs[] = {"simulate --incline 15", "simulate --incline 30", "simulate --incline 45",
                          "simulate --preset hoop --t-max 2", "simulate --preset rocking-hoop --t-max 2",
                          "simulate --preset disc", "predict", "predict --incline 45", "predict --preset hoop",
                          "paper"};
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; ++i) {
        cli_result r = run(runs[i]);
        const char *z = r.status == 0 ? negative_zero(r.out) : "failed";
        char shown[48];
        snprintf(shown, sizeof shown, "%.40s", z ? z : "");
        cli_result_free(&r);
        ENSURE_MSG(z == NULL, "'jumpcyl %s' prints a negative zero: ...%s", runs[i], shown);
    }
    ENSURE(negative_zero("F = -0.0000 N") && negative_zero("-0.00") && !negative_zero("-0.0012") &&
           !negative_zero("x -0.5") && !negative_zero("1e-05"));
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH_TO_JUMPCYL\n", argv[0]);
        return 2;
    }
    cli_path = argv[1];
    RUN_TEST(test_predict_json);
    RUN_TEST(test_notes);
    RUN_TEST(test_no_negative_zeros);
    RUN_TEST(test_paper_json);
    RUN_TEST(test_units);
    RUN_TEST(test_printed_units);
    RUN_TEST(test_hints);
    RUN_TEST(test_names);
    RUN_TEST(test_bad_input_exit_2);
    RUN_TEST(test_help_and_version);
    TEST_MAIN_END();
}
