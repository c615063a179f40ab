/* `jumpcyl params --json` enumerated: every row of the table works as an
 * option (--NAME VALUE), as an experiment-file key (--config; also under
 * its option name), as `sweep --vary NAME=A,B` (each row the run the option
 * makes), is listed in every setup command's --help and is offered by the
 * bash completion (completions/jumpcyl.bash, run in bash). The value given
 * is checked by reading --dump-config back (cli_config_parse) against the
 * library's jc_param_set on the preset. Every numeric row that moves the
 * first lift-off works as `design --free NAME` (a value found is run again
 * by `simulate --NAME`), the others are refused in one line. */
#include "test.h"
#include "cli_run.h"
#include "inputs.h"

#include <cjson/cJSON.h>

/* A row of the JSON table. */
typedef struct {
    const cJSON *row;
    int id;
    const char *name, *section, *key;
    int is_name, body;
} row_t;

static int row_of(const cJSON *r, row_t *out)
{
    out->row = r;
    out->name = cJSON_GetStringValue(cJSON_GetObjectItem(r, "name"));
    out->section = cJSON_GetStringValue(cJSON_GetObjectItem(r, "section"));
    out->key = cJSON_GetStringValue(cJSON_GetObjectItem(r, "key"));
    out->is_name = cJSON_IsArray(cJSON_GetObjectItem(r, "choices"));
    out->body = cJSON_IsTrue(cJSON_GetObjectItem(r, "body"));
    out->id = out->name ? jc_param_find(out->name) : -1;
    return out->name && out->section && out->key && out->id >= 0 ? 0 : -1;
}

/* The setup the value should give: the paper's with the value set, the
 * printed paper d dropped for a body parameter (as the options do). */
static int expected_setup(const row_t *r, double v, jc_Setup *s)
{
    *s = jc_paper_setup();
    if (jc_param_set(s, r->id, v, NULL, 0) != JC_OK) return -1;
    if (r->body) s->paper_cm_offset_m = 0.0;
    return jc_setup_validate(s, NULL, 0) == JC_OK ? 0 : -1;
}

/* Two valid values that differ from the paper's: fractions of the row's
 * typical span (names: the choices other than the preset's). */
static int pick_values(const row_t *r, double v[2])
{
    const jc_Setup paper = jc_paper_setup();
    double now = NAN;
    jc_param_get(&paper, r->id, &now, NULL, 0);
    const double lo = cJSON_GetNumberValue(cJSON_GetObjectItem(r->row, "typical_min"));
    const double hi = cJSON_GetNumberValue(cJSON_GetObjectItem(r->row, "typical_max"));
    static const double fractions[] = {0.3, 0.7, 0.1, 0.9, 0.45, 0.55, 0.2, 0.8};
    int n = 0;
    for (size_t k = 0; k < (r->is_name ? 3 : sizeof fractions / sizeof fractions[0]) && n < 2; ++k) {
        const double x = r->is_name ? (double)k : lo + fractions[k] * (hi - lo);
        jc_Setup s;
        if (x != now && expected_setup(r, x, &s) == 0) v[n++] = x;
    }
    return n == 2 ? 0 : -1;
}

/* The value as a person types it: in the row's unit, no blank before it ("12.5cm"). */
static int value_text(const row_t *r, double v, char *out, size_t len)
{
    if (jc_param_format(r->id, v, out, len) != JC_OK) return -1;
    char *blank = strchr(out, ' ');
    if (blank && !r->is_name) memmove(blank, blank + 1, strlen(blank));
    return 0;
}

/* The tool's --dump-config output read back, compared with the expected setup. */
static int dump_matches(const char *dump, const jc_Setup *want, const char *what)
{
    jc_Setup got = jc_paper_setup();
    char err[512] = "";
    ENSURE_MSG(dump && cli_config_parse("dump", dump, strlen(dump), &got, err, sizeof err) == 0, "%s: %s", what, err);
    double a, b;
    for (int id = 0; id < jc_param_count(); ++id) {
        const int ha = jc_param_get(&got, id, &a, NULL, 0) == JC_OK, hb = jc_param_get(want, id, &b, NULL, 0) == JC_OK;
        ENSURE_MSG(ha == hb && (!ha || a == b), "%s: %s is %.17g, want %.17g", what, jc_param_info(id)->name, a, b);
    }
    return 0;
}

/* --NAME VALUE, and the same value as an experiment-file key (by its key,
 * and by its option name): the dumps are the expected setup's. */
static int check_option_and_file(const row_t *r, double v)
{
    char text[80], opt[80];
    ENSURE(value_text(r, v, text, sizeof text) == 0);
    snprintf(opt, sizeof opt, "--%s", r->name);
    jc_Setup want;
    ENSURE(expected_setup(r, v, &want) == 0);
    const char *args[] = {"predict", opt, text, "--dump-config", NULL};
    cli_result res = cli_run(args);
    char what[160];
    snprintf(what, sizeof what, "%s %s", opt, text);
    ENSURE_MSG(res.status == 0, "%s: exit %d: %s", what, res.status, res.err);
    const int bad = dump_matches(res.out, &want, what);
    char *option_dump = res.out;
    res.out = NULL;
    cli_result_free(&res);
    if (bad) {
        free(option_dump);
        return 1;
    }
    for (int alias = 0; alias < 2; ++alias) {
        char dir[] = "/tmp/jc_params_XXXXXX", path[256], key[64];
        ENSURE(cli_scratch(dir, path, sizeof path, "t.ini") == 0);
        snprintf(key, sizeof key, "%s", alias ? r->name : r->key);
        for (char *c = key; alias && *c; ++c)
            if (*c == '-') *c = '_';
        FILE *f = fopen(path, "w");
        ENSURE(f);
        fprintf(f, "[%s]\n%s = %s\n", r->section, key, text);
        fclose(f);
        const char *fargs[] = {"predict", "--config", path, "--dump-config", NULL};
        cli_result fr = cli_run(fargs);
        unlink(path);
        rmdir(dir);
        const int same = fr.status == 0 && option_dump && strcmp(fr.out, option_dump) == 0;
        if (!same) fprintf(stderr, "[%s] %s = %s: exit %d: %s\n%s\n", r->section, key, text, fr.status, fr.err, fr.out);
        cli_result_free(&fr);
        if (!same) free(option_dump);
        ENSURE_MSG(same, "[%s] %s = %s differs from %s", r->section, key, text, what);
    }
    free(option_dump);
    return 0;
}

/* The CSV line's fields after the first skip ones (the outcome). */
static const char *after_fields(const char *line, int skip)
{
    for (int k = 0; k < skip && line; ++k) {
        line = strchr(line, ',');
        if (line) ++line;
    }
    return line;
}

/* sweep --vary NAME=A,B: each row is the run --NAME A makes (a sweep of a
 * fixed other value, the same columns after the inputs). */
static int check_sweep(const row_t *r, const double v[2])
{
    char a[80], b[80], vary[200];
    ENSURE(value_text(r, v[0], a, sizeof a) == 0 && value_text(r, v[1], b, sizeof b) == 0);
    snprintf(vary, sizeof vary, "%s=%s,%s", r->name, a, b);
    const char *args[] = {"sweep", "--vary", vary, "--output", "-", "--quiet", "--threads", "1", NULL};
    cli_result res = cli_run(args);
    ENSURE_MSG(res.status == 0, "--vary %s: exit %d: %s", vary, res.status, res.err);
    /* header, then two rows */
    char *line[3] = {res.out, NULL, NULL};
    for (int k = 1; k < 3 && line[k - 1]; ++k) {
        char *nl = strchr(line[k - 1], '\n');
        if (nl) *nl = '\0';
        line[k] = nl ? nl + 1 : NULL;
    }
    ENSURE_MSG(line[2] && strncmp(line[0], "case,", 5) == 0, "--vary %s: %s", vary, res.out);
    char column[64]; /* the column starts with the name, '_' for '-' */
    snprintf(column, sizeof column, "case,%s", r->name);
    for (char *c = column; *c; ++c)
        if (*c == '-') *c = '_';
    ENSURE_MSG(strncmp(line[0], column, strlen(column)) == 0, "header '%s'", line[0]);
    for (int k = 0; k < 2; ++k) {
        char *nl = strchr(line[k + 1], '\n');
        if (nl) *nl = '\0';
        ENSURE_MSG(!strstr(line[k + 1], "invalid_setup"), "--vary %s: row %d: %s", vary, k, line[k + 1]);
        /* the same value given as an option, in a one-case sweep of another parameter */
        char opt[80], fixed[80];
        snprintf(opt, sizeof opt, "--%s", r->name);
        snprintf(fixed, sizeof fixed, "%s", strcmp(r->name, "g") == 0 ? "ramp-length=3.2" : "g=9.78");
        const char *one[] = {"sweep", "--vary", fixed, opt, k ? b : a, "--output", "-", "--quiet", "--threads", "1", NULL};
        cli_result o = cli_run(one);
        const char *row = o.out ? strchr(o.out, '\n') : NULL;
        const char *want = row ? after_fields(row + 1, 2) : NULL, *got = after_fields(line[k + 1], 2);
        const int same = o.status == 0 && want && got && strncmp(want, got, strlen(got)) == 0;
        if (!same) fprintf(stderr, "sweep row: %s\noption run: %s (%s)\n", line[k + 1], o.out, o.err);
        cli_result_free(&o);
        if (!same) cli_result_free(&res);
        ENSURE_MSG(same, "--vary %s row %d is not the run of %s %s", vary, k, opt, k ? b : a);
    }
    cli_result_free(&res);
    return 0;
}

/* Runs the completion function in bash for the words given; its reply. */
static char *complete(const char *completion_file, const char *words)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "bash -c 'source \"%s\"; COMP_WORDS=(\"%s\" %s); COMP_CWORD=$((${#COMP_WORDS[@]}-1)); _jumpcyl; "
             "printf \"%%s\\n\" \"${COMPREPLY[@]}\"'",
             completion_file, cli_run_tool, words);
    FILE *p = popen(cmd, "r");
    if (!p) return NULL;
    char *out = cli_run_read_all(p);
    pclose(p);
    return out;
}

/* A whole line of text equals word. */
static int has_line(const char *text, const char *word)
{
    const size_t n = strlen(word);
    for (const char *s = text; s && *s; s = strchr(s, '\n') ? strchr(s, '\n') + 1 : NULL)
        if (strncmp(s, word, n) == 0 && (s[n] == '\n' || s[n] == '\0')) return 1;
    return 0;
}

static int test_every_row(const char *completion_file)
{
    const char *args[] = {"params", "--json", NULL};
    cli_result res = cli_run(args);
    ENSURE_MSG(res.status == 0, "params --json: %d %s", res.status, res.err);
    cJSON *doc = cJSON_Parse(res.out);
    cli_result_free(&res);
    const cJSON *rows = cJSON_GetObjectItem(doc, "params");
    ENSURE(cJSON_IsArray(rows) && cJSON_GetArraySize(rows) == jc_param_count());
    /* the help of a setup command, and the completions */
    const char *help_args[] = {"simulate", "--help", NULL};
    cli_result help = cli_run(help_args);
    char *options = complete(completion_file, "simulate \"--\"");
    char *varied = complete(completion_file, "sweep --vary \"\"");
    int st = help.status == 0 && options && varied ? 0 : 1;
    const cJSON *it;
    int checked = 0;
    cJSON_ArrayForEach(it, rows)
    {
        row_t r;
        double v[2];
        char word[80];
        if (st || (st = row_of(it, &r)) != 0) break;
        if ((st = pick_values(&r, v)) != 0) {
            fprintf(stderr, "%s: no two valid values to try\n", r.name);
            break;
        }
        snprintf(word, sizeof word, "  --%s ", r.name);
        if (!strstr(help.out, word)) {
            fprintf(stderr, "simulate --help has no '%s'\n", word);
            st = 1;
            break;
        }
        snprintf(word, sizeof word, "--%s", r.name);
        if (!has_line(options, word)) {
            fprintf(stderr, "the completion of 'simulate --' has no %s:\n%s\n", word, options);
            st = 1;
            break;
        }
        snprintf(word, sizeof word, "%s=", r.name);
        if (!has_line(varied, word)) {
            fprintf(stderr, "the completion of 'sweep --vary ' has no %s:\n%s\n", word, varied);
            st = 1;
            break;
        }
        if ((st = check_option_and_file(&r, v[0])) != 0 || (st = check_sweep(&r, v)) != 0) break;
        /* the JSON's defaults are the library's on each preset */
        const cJSON *defaults = cJSON_GetObjectItem(r.row, "defaults");
        for (int k = 0; !st && jc_preset_name(k); ++k) {
            jc_Setup s;
            double want;
            jc_preset_setup(jc_preset_name(k), &s, NULL, 0);
            const cJSON *d = cJSON_GetObjectItem(defaults, jc_preset_name(k));
            const int has = jc_param_get(&s, r.id, &want, NULL, 0) == JC_OK;
            if (has ? !(cJSON_IsNumber(d) && d->valuedouble == want) : !cJSON_IsNull(d)) {
                fprintf(stderr, "%s: the default of %s\n", r.name, jc_preset_name(k));
                st = 1;
            }
        }
        ++checked;
    }
    printf("  %d of %d rows: option, file key, sweep --vary, --help, completion\n", checked, jc_param_count());
    cli_result_free(&help);
    free(options);
    free(varied);
    cJSON_Delete(doc);
    return st;
}

/* The text listing: a line per row beginning with its name, and its choices. */
static int test_text_listing(void)
{
    const char *args[] = {"params", NULL};
    cli_result res = cli_run(args);
    ENSURE_MSG(res.status == 0, "%s", res.err);
    for (int id = 0; id < jc_param_count(); ++id) {
        char start[80];
        snprintf(start, sizeof start, "\n%s  ", jc_param_info(id)->name);
        ENSURE_MSG(strstr(res.out, start), "params has no line for %s", jc_param_info(id)->name);
    }
    ENSURE(strstr(res.out, "name: stronge, poisson, newton"));
    cli_result_free(&res);
    const char *bad[] = {"params", "--bogus", NULL};
    res = cli_run(bad);
    ENSURE(res.status == 2 && cli_one_line(res.err));
    cli_result_free(&res);
    /* an unambiguous prefix, as getopt takes it everywhere */
    const char *prefix[] = {"params", "--js", NULL};
    res = cli_run(prefix);
    cJSON *doc = res.status == 0 ? cJSON_Parse(res.out) : NULL;
    const int parsed = cJSON_IsArray(cJSON_GetObjectItem(doc, "params"));
    cJSON_Delete(doc);
    cli_result_free(&res);
    ENSURE(parsed);
    return 0;
}

/* ---- design --free ---- */

/* The rows design refuses: names (impact-law), and the rows that never move
 * the first lift-off (test_design_inert checks that they do not). */
static int design_refuses(const row_t *r)
{
    static const char *const inert[] = {"restitution", "ramp-length", "paper-d"};
    for (size_t k = 0; k < sizeof inert / sizeof inert[0]; ++k)
        if (strcmp(r->name, inert[k]) == 0) return 1;
    return r->is_name;
}

/* The index of a CSV header's column, -1 if absent. */
static int column_index(const char *header, const char *name)
{
    const size_t n = strlen(name);
    int k = 0;
    for (const char *s = header; s; s = strchr(s, ','), s = s ? s + 1 : NULL, ++k)
        if (strncmp(s, name, n) == 0 && (s[n] == ',' || s[n] == '\n' || s[n] == '\0')) return k;
    return -1;
}

/* A refused numeric row never moves the first lift-off: a sweep of two of
 * its values gives the same first_liftoff_x_m (the paper's, at 15 and 30
 * deg, with an initial spin and air drag, which make g and the air's rows
 * matter). */
static int check_inert(const row_t *r)
{
    double v[2];
    char a[80], b[80], vary[200];
    ENSURE(pick_values(r, v) == 0 && value_text(r, v[0], a, sizeof a) == 0 && value_text(r, v[1], b, sizeof b) == 0);
    snprintf(vary, sizeof vary, "%s=%s,%s", r->name, a, b);
    const char *args[] = {"sweep", "--vary", vary, "--vary", "incline=15,30", "--omega0", "3", "--drag-coefficient",
                          "1", "--output", "-", "--quiet", "--threads", "1", NULL};
    cli_result res = cli_run(args);
    ENSURE_MSG(res.status == 0, "--vary %s: %s", vary, res.err);
    const int col = column_index(res.out, "first_liftoff_x_m");
    char *line[5] = {res.out, NULL, NULL, NULL, NULL};
    for (int k = 1; k < 5 && line[k - 1]; ++k) {
        char *nl = strchr(line[k - 1], '\n');
        if (nl) *nl = '\0';
        line[k] = nl ? nl + 1 : NULL;
    }
    int same = col >= 0 && line[4] != NULL, both = 0;
    for (int k = 0; same && k < 2; ++k) { /* rows: (a, 15), (a, 30), (b, 15), (b, 30) */
        const char *x = after_fields(line[1 + k], col), *y = after_fields(line[3 + k], col);
        same = x && y;
        if (!same || x[0] == ',' || y[0] == ',') continue; /* no lift-off on one ramp (ramp-length) */
        same = strcspn(x, ",") == strcspn(y, ",") && strncmp(x, y, strcspn(x, ",")) == 0;
        ++both;
    }
    if (!same || !both) fprintf(stderr, "%s\n%s\n%s\n%s\n", line[1], line[2], line[3], line[4]);
    cli_result_free(&res);
    ENSURE_MSG(same && both, "%s moves the first lift-off, yet design refuses it", r->name);
    return 0;
}

/* The setup design --free is tried on: the paper's with an initial spin
 * and air drag, so that every row moves the first lift-off (g only moves it
 * with a spin: without one, every force scales with g or v^2 and the path
 * does not change); the free row itself is not given. Appended at args[n]
 * and NULL-terminated. */
static void add_base(const row_t *r, const char **args, int n)
{
    if (strcmp(r->name, "omega0") != 0) {
        args[n++] = "--omega0";
        args[n++] = "3";
    }
    if (strcmp(r->name, "drag-coefficient") != 0) {
        args[n++] = "--drag-coefficient";
        args[n++] = "1";
    }
    args[n] = NULL;
}

/* design --free NAME --jump-at X on that setup, 40 scan points; its JSON
 * document, or NULL. */
static cJSON *design_doc(const row_t *r, const char *x, const char *json_path)
{
    const char *args[24] = {"design", "--free", r->name, "--jump-at", x, "--points", "40", "--threads", "1",
                            "--json", json_path};
    add_base(r, args, 11);
    cli_result res = cli_run(args);
    const int ok = res.status == 0 && res.err[0] == '\0';
    if (!ok) fprintf(stderr, "design --free %s --jump-at %s: exit %d: %s\n", r->name, x, res.status, res.err);
    cli_result_free(&res);
    char *text = ok ? cli_run_slurp(json_path) : NULL;
    unlink(json_path);
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    return doc;
}

static double num(const cJSON *o, const char *key) { return cJSON_GetNumberValue(cJSON_GetObjectItem(o, key)); }

/* The middle value of the widest lift-off branch (the one the scan
 * resolves best) among those whose first lift-offs span 20 um; NaN if none. */
static double widest_branch_middle(const cJSON *doc)
{
    double best = 0.0, p = NAN;
    const cJSON *b;
    cJSON_ArrayForEach(b, cJSON_GetObjectItem(doc, "branches"))
    {
        const char *outcome = cJSON_GetStringValue(cJSON_GetObjectItem(b, "outcome"));
        if (!outcome || strcmp(outcome, jc_case_kind_name(JC_CASE_LIFTOFF)) != 0) continue;
        const double lo = num(b, "lo"), hi = num(b, "hi");
        if (num(b, "x_max_m") - num(b, "x_min_m") > 2e-5 && hi - lo > best) {
            best = hi - lo;
            p = 0.5 * (lo + hi);
        }
    }
    return p;
}

/* The first lift-off of `simulate --NAME VALUE` on the setup design_doc uses. */
static double simulated_liftoff(const row_t *r, double v)
{
    char text[80], opt[80];
    if (value_text(r, v, text, sizeof text) != 0) return NAN;
    snprintf(opt, sizeof opt, "--%s", r->name);
    const char *args[12] = {"simulate", opt, text, "--json"};
    add_base(r, args, 4);
    cli_result res = cli_run(args);
    cJSON *doc = res.status == 0 ? cJSON_Parse(res.out) : NULL;
    const cJSON *x = cJSON_GetObjectItem(cJSON_GetObjectItem(doc, "summary"), "first_liftoff_x");
    const double out = cJSON_IsNumber(x) ? x->valuedouble : NAN;
    if (!doc) fprintf(stderr, "simulate %s %s: exit %d: %s\n", opt, text, res.status, res.err);
    cJSON_Delete(doc);
    cli_result_free(&res);
    return out;
}

/* Both ends of the search's range are valid setups for the library. */
static int valid_with(const row_t *r, double v)
{
    jc_Setup s = jc_paper_setup();
    if (strcmp(r->name, "omega0") != 0) s.omega0_radps = 3.0;
    if (strcmp(r->name, "drag-coefficient") != 0) s.drag_coefficient = 1.0;
    return jc_param_set(&s, r->id, v, NULL, 0) == JC_OK && jc_setup_validate(&s, NULL, 0) == JC_OK;
}

/* design --free NAME finds a value that puts the first lift-off at X, and
 * simulate --NAME with that value lifts off at X within the design's
 * verification tolerance. X: where simulate lifts off with the middle value
 * of the widest branch of a first search (one that X = 1 m need not hit). */
static int check_design_free(const row_t *r, const char *json_path)
{
    cJSON *doc = design_doc(r, "1m", json_path);
    ENSURE_MSG(doc, "design --free %s", r->name);
    const double middle = widest_branch_middle(doc);
    const cJSON *fr = cJSON_GetObjectItem(doc, "free");
    const double lo = num(fr, "lo"), hi = num(fr, "hi");
    cJSON_Delete(doc);
    ENSURE_MSG(!isnan(middle), "design --free %s: no branch spans 20 um of first lift-offs", r->name);
    ENSURE_MSG(lo < hi && valid_with(r, lo) && valid_with(r, hi), "design --free %s: the range %.17g .. %.17g",
               r->name, lo, hi);
    const double x = simulated_liftoff(r, middle);
    ENSURE_MSG(!isnan(x), "simulate --%s %.17g (SI): no lift-off", r->name, middle);
    char target[64];
    snprintf(target, sizeof target, "%.17gm", x);
    doc = design_doc(r, target, json_path);
    ENSURE_MSG(doc, "design --free %s --jump-at %s", r->name, target);
    const cJSON *sol = cJSON_GetArrayItem(cJSON_GetObjectItem(doc, "solutions"), 0);
    const double v = num(sol, "value"), want = num(doc, "target_x_m");
    cJSON_Delete(doc);
    ENSURE_MSG(sol && v >= lo && v <= hi, "design --free %s --jump-at %s: no solution", r->name, target);
    const double got = simulated_liftoff(r, v);
    ENSURE_MSG(fabs(got - want) <= JC_DESIGN_VERIFY_M, "design --free %s --jump-at %s: %s = %.17g lifts off at %.9f m",
               r->name, target, r->name, v, got);
    printf("  design --free %-19s X = %.6f m: %.10g (SI), simulate lifts off %.1e m from X\n", r->name, want, v,
           fabs(got - want));
    return 0;
}

/* The refusal: exit 2, one line naming the row and the names allowed. */
static int check_design_refused(const row_t *r, const char *allowed)
{
    const char *args[] = {"design", "--free", r->name, "--jump-at", "1m", NULL};
    cli_result res = cli_run(args);
    char want[600];
    snprintf(want, sizeof want, "(allowed: %s)", allowed);
    const int ok = res.status == 2 && cli_one_line(res.err) && res.out[0] == '\0' && strstr(res.err, r->name) &&
                   strstr(res.err, want);
    if (!ok) fprintf(stderr, "design --free %s: exit %d: %s", r->name, res.status, res.err);
    cli_result_free(&res);
    ENSURE_MSG(ok, "design --free %s is not refused in one line listing %s", r->name, allowed);
    return 0;
}

static int test_design_free(const char *completion_file)
{
    const char *args[] = {"params", "--json", NULL};
    cli_result res = cli_run(args);
    cJSON *doc = res.status == 0 ? cJSON_Parse(res.out) : NULL;
    cli_result_free(&res);
    const cJSON *rows = cJSON_GetObjectItem(doc, "params");
    ENSURE(cJSON_IsArray(rows));
    char *offered = complete(completion_file, "design --free \"\"");
    char allowed[600] = "", dir[] = "/tmp/jc_design_free_XXXXXX", path[256];
    const cJSON *it;
    int st = offered && cli_scratch(dir, path, sizeof path, "d.json") == 0 ? 0 : 1, freed = 0, refused = 0;
    cJSON_ArrayForEach(it, rows) /* the names allowed, in the table's order */
    {
        row_t r;
        if (row_of(it, &r) == 0 && !design_refuses(&r))
            snprintf(allowed + strlen(allowed), sizeof allowed - strlen(allowed), "%s%s", allowed[0] ? ", " : "",
                     r.name);
    }
    cJSON_ArrayForEach(it, rows)
    {
        row_t r;
        if (st || (st = row_of(it, &r)) != 0) break;
        const int refuses = design_refuses(&r);
        if (has_line(offered, r.name) == refuses) {
            fprintf(stderr, "the completion of 'design --free ' %s %s:\n%s\n", refuses ? "offers" : "lacks", r.name,
                    offered);
            st = 1;
            break;
        }
        if (refuses) {
            st = check_design_refused(&r, allowed);
            if (!st && !r.is_name) st = check_inert(&r);
            ++refused;
        } else {
            st = check_design_free(&r, path);
            ++freed;
        }
    }
    printf("  design --free: %d rows found a jump at X, %d refused\n", freed, refused);
    rmdir(dir);
    free(offered);
    cJSON_Delete(doc);
    return st;
}

static const char *completion_path;
static int test_every_row_run(void) { return test_every_row(completion_path); }
static int test_design_free_run(void) { return test_design_free(completion_path); }

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s PATH_TO_JUMPCYL PATH_TO_COMPLETION\n", argv[0]);
        return 2;
    }
    completion_path = argv[2];
    char *tool_only[] = {argv[0], argv[1], NULL};
    if (cli_run_init(2, tool_only) != 0) return 2;
    RUN_TEST(test_text_listing);
    RUN_TEST(test_every_row_run);
    RUN_TEST(test_design_free_run);
    TEST_MAIN_END();
}
