/*
 * `jumpcyl simulate` end to end (argv[1] is the built binary): its --json is
 * read back with cJSON and compared, event by event, with jc_simulate called
 * here on the same setup (paper preset, 30 deg, mu 0.5, default options);
 * --csv writes a trajectory whose rows parse and match the library's
 * samples; an unwritable --csv path fails with exit status 1, a message
 * naming the path, and no file (not even a temporary one) left behind.
 */
#define _POSIX_C_SOURCE 200809L
#include "sim_common.h"

#include "../cli_run.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* The tool writes every double of its JSON so that it reads back to the same
 * double (cli_json_text): its numbers are the library's, exactly. */
#define JSON_REL 0.0

static const char *cli_path;

/* Runs "jumpcyl ARGS" through the shell, capturing stdout and stderr. */
static cli_result run_cli(const char *args) { return cli_run_line(cli_path, NULL, args); }

/* The library's run of the same setup. */
static int library_run(double sample_dt, jc_Model *m, jc_Run *run)
{
    jc_Setup s;
    char err[256] = "";
    ENSURE_OK(jc_preset_setup("paper", &s, err, sizeof err), err);
    s.incline_rad = 30.0 * DEG; /* the CLI's plain angles: value * (pi / 180) */
    s.mu_static = s.mu_kinetic = 0.5;
    if (sim_model(m, &s)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = sample_dt;
    return sim_run(m, &o, run);
}

static int number_is(const cJSON *obj, const char *key, double want)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    ENSURE_MSG(cJSON_IsNumber(v), "'%s' missing or not a number", key);
    ENSURE_MSG(v->valuedouble == want || fabs(v->valuedouble - want) <= JSON_REL * fabs(want),
               "'%s': JSON %.17g, library %.17g", key, v->valuedouble, want);
    return 0;
}

static int string_is(const cJSON *obj, const char *key, const char *want)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    ENSURE_MSG(cJSON_IsString(v), "'%s' missing or not a string", key);
    ENSURE_MSG(strcmp(v->valuestring, want) == 0, "'%s': JSON '%s', library '%s'", key, v->valuestring, want);
    return 0;
}

static int compare_event(const cJSON *je, const jc_Event *e, int i)
{
    const jc_State *s = &e->state;
    int bad = string_is(je, "kind", jc_event_name(e->kind)) || string_is(je, "mode_before", jc_mode_name(e->mode_before)) ||
              string_is(je, "mode_after", jc_mode_name(e->mode_after)) || number_is(je, "t", s->t_s) ||
              number_is(je, "x", s->x_m) || number_is(je, "y", s->y_m) || number_is(je, "theta", s->theta_rad) ||
              number_is(je, "omega", s->omega_radps) || number_is(je, "vx", s->vx_mps) ||
              number_is(je, "vy", s->vy_mps) || number_is(je, "slip", e->slip_mps) ||
              number_is(je, "normal", e->normal_N) || number_is(je, "friction", e->friction_N);
    const int into_flight = e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT);
    if (!bad && into_flight) {
        bad = number_is(je, "flight_time", e->flight_time_s) || number_is(je, "hop_height", e->hop_height_m);
        const cJSON *lx = cJSON_GetObjectItemCaseSensitive(je, "landing_x");
        if (!bad && isnan(e->landing_x_m)) bad = !cJSON_IsNull(lx);
        else if (!bad) bad = number_is(je, "landing_x", e->landing_x_m);
    }
    if (!bad && e->kind == JC_EVENT_LIFTOFF) {
        /* Every lift-off carries its flight's record, positive and non-negative. */
        const cJSON *ft = cJSON_GetObjectItemCaseSensitive(je, "flight_time");
        const cJSON *hh = cJSON_GetObjectItemCaseSensitive(je, "hop_height");
        bad = !(cJSON_IsNumber(ft) && ft->valuedouble > 0.0 && cJSON_IsNumber(hh) && hh->valuedouble >= 0.0);
    }
    if (bad) fprintf(stderr, "  (event %d, %s)\n", i, jc_event_name(e->kind));
    return bad;
}

static int test_json_matches_library(void)
{
    cli_result r = run_cli("simulate --preset paper --incline 30 --mu 0.5 --json");
    cJSON *doc = r.status == 0 && r.out ? cJSON_Parse(r.out) : NULL;
    const int status = r.status;
    const int quiet = r.err && r.err[0] == '\0';
    cli_result_free(&r);
    ENSURE_MSG(status == 0, "exit status %d", status);
    ENSURE_MSG(doc != NULL, "stdout is not JSON");
    jc_Model m;
    jc_Run run;
    if (library_run(0.0, &m, &run)) {
        cJSON_Delete(doc);
        return 1;
    }
    int bad = !quiet;
    if (bad) fprintf(stderr, "stderr not empty\n");
    const cJSON *events = cJSON_GetObjectItemCaseSensitive(doc, "events");
    if (!bad && !(cJSON_IsArray(events) && cJSON_GetArraySize(events) == run.event_count)) {
        fprintf(stderr, "events: %d in JSON, %d from the library\n", cJSON_GetArraySize(events), run.event_count);
        bad = 1;
    }
    int liftoffs = 0;
    for (int i = 0; i < run.event_count && !bad; ++i) {
        bad = compare_event(cJSON_GetArrayItem(events, i), &run.events[i], i);
        liftoffs += run.events[i].kind == JC_EVENT_LIFTOFF;
    }
    if (!bad) bad = string_is(doc, "termination", jc_termination_name(run.termination)) ||
                    number_is(doc, "t_end", run.final_state.t_s);
    const cJSON *energy = cJSON_GetObjectItemCaseSensitive(doc, "energy");
    if (!bad) bad = !cJSON_IsObject(energy);
    if (!bad) bad = number_is(energy, "kinetic", run.energy.kinetic_J) ||
                    number_is(energy, "potential", run.energy.potential_J) ||
                    number_is(energy, "friction_loss", run.energy.friction_loss_J) ||
                    number_is(energy, "impact_loss", run.energy.impact_loss_J) ||
                    number_is(energy, "balance_error", run.energy.balance_error_J);
    /* The summary: the first lift-off. */
    jc_RunSummary sum;
    jc_run_summarize(&run, &sum);
    const cJSON *summary = cJSON_GetObjectItemCaseSensitive(doc, "summary");
    if (!bad && sum.first_liftoff >= 0)
        bad = !cJSON_IsObject(summary) || number_is(summary, "liftoffs", sum.liftoffs) ||
              number_is(summary, "first_liftoff_x", run.events[sum.first_liftoff].state.x_m);
    const int n = run.event_count;
    jc_run_free(&run);
    cJSON_Delete(doc);
    ENSURE(!bad);
    ENSURE_MSG(n >= 4 && liftoffs >= 1, "%d events, %d lift-offs: the comparison covered little", n, liftoffs);
    return 0;
}

/* Splits a CSV line in place; returns the field count. */
static int split(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        fields[n++] = p;
        char *c = strchr(p, ',');
        if (!c) break;
        *c = '\0';
        p = c + 1;
    }
    return n;
}

static int parse_number(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

/* Columns the rows are checked against the library by; the file may have
 * more (it names them in its header line). */
#define MAX_COLUMNS 64
static const char *const required[] = {"t_s", "mode", "x_m", "y_m", "vx_mps", "vy_mps", "theta_rad", "omega_radps",
                                       "cm_x_m", "cm_y_m", "kinetic_J", "potential_J", "friction_loss_J",
                                       "impact_loss_J"};
#define REQUIRED_COUNT ((int)(sizeof required / sizeof required[0]))

static double sample_value(const jc_Sample *p, int k)
{
    switch (k) {
    case 0: return p->state.t_s;
    case 2: return p->state.x_m;
    case 3: return p->state.y_m;
    case 4: return p->state.vx_mps;
    case 5: return p->state.vy_mps;
    case 6: return p->state.theta_rad;
    case 7: return p->state.omega_radps;
    case 8: return p->cm_x_m;
    case 9: return p->cm_y_m;
    case 10: return p->kinetic_J;
    case 11: return p->potential_J;
    case 12: return p->friction_loss_J;
    case 13: return p->impact_loss_J;
    }
    return NAN;
}

static int check_csv_rows(const char *path, const jc_Run *run)
{
    FILE *f = fopen(path, "r");
    ENSURE_MSG(f != NULL, "cannot read %s", path);
    char *text = cli_run_read_all(f);
    fclose(f);
    ENSURE(text != NULL);
    int bad = 0, row = 0, columns = 0, where[REQUIRED_COUNT];
    char *save = NULL;
    char *line = strtok_r(text, "\n", &save);
    /* The first line is the header: names, the required ones among them,
     * "t_s" first. */
    char *names[MAX_COLUMNS + 1];
    if (!line) {
        fprintf(stderr, "empty file\n");
        bad = 1;
    } else {
        columns = split(line, names, MAX_COLUMNS + 1);
        for (int k = 0; k < REQUIRED_COUNT && !bad; ++k) {
            where[k] = -1;
            for (int c = 0; c < columns; ++c)
                if (strcmp(names[c], required[k]) == 0) where[k] = c;
            if (where[k] < 0) {
                fprintf(stderr, "header has no column '%s'\n", required[k]);
                bad = 1;
            }
        }
        if (!bad && where[0] != 0) {
            fprintf(stderr, "the header does not start with t_s\n");
            bad = 1;
        }
    }
    for (line = strtok_r(NULL, "\n", &save); line && !bad; line = strtok_r(NULL, "\n", &save), ++row) {
        char *fields[MAX_COLUMNS + 1];
        const int n = split(line, fields, MAX_COLUMNS + 1);
        if (n != columns) {
            fprintf(stderr, "row %d has %d fields, the header %d\n", row, n, columns);
            bad = 1;
            break;
        }
        if (row >= run->sample_count) {
            fprintf(stderr, "more rows than the library's %d samples\n", run->sample_count);
            bad = 1;
            break;
        }
        const jc_Sample *p = &run->samples[row];
        /* Every field but the mode is a finite number. */
        for (int c = 0; c < n && !bad; ++c) {
            double v;
            if (c == where[1]) continue;
            if (!parse_number(fields[c], &v)) {
                fprintf(stderr, "row %d, column %s: '%s' is not a number\n", row, names[c], fields[c]);
                bad = 1;
            }
        }
        if (!bad && strcmp(fields[where[1]], jc_mode_name(p->mode)) != 0) {
            fprintf(stderr, "row %d: mode '%s', library '%s'\n", row, fields[where[1]], jc_mode_name(p->mode));
            bad = 1;
        }
        /* The values are the library's samples, written with %.12g or %.9g:
         * 1e-8 relative plus 1e-14 absolute (for values that are 0 up to
         * rounding). */
        for (int k = 0; k < REQUIRED_COUNT && !bad; ++k) {
            if (k == 1) continue;
            double v;
            parse_number(fields[where[k]], &v);
            const double want = sample_value(p, k);
            if (!(fabs(v - want) <= 1e-8 * fabs(want) + 1e-14)) {
                fprintf(stderr, "row %d, column %s: %.17g, library %.17g\n", row, required[k], v, want);
                bad = 1;
            }
        }
    }
    if (!bad && row != run->sample_count) {
        fprintf(stderr, "%d rows, library %d samples\n", row, run->sample_count);
        bad = 1;
    }
    free(text);
    ENSURE(!bad);
    ENSURE_MSG(row > 100, "only %d rows", row);
    return 0;
}

static int test_csv(void)
{
    char dir[] = "/tmp/jc_sim_cli_XXXXXX", path[256], args[512];
    ENSURE(cli_scratch(dir, path, sizeof path, "trajectory.csv") == 0);
    snprintf(args, sizeof args, "simulate --preset paper --incline 30 --mu 0.5 --sample-dt 0.01 --csv '%s'", path);
    cli_result r = run_cli(args);
    const int status = r.status;
    cli_result_free(&r);
    jc_Model m;
    jc_Run run;
    int bad = status != 0;
    if (bad) fprintf(stderr, "exit status %d\n", status);
    if (!bad) bad = library_run(0.01, &m, &run);
    if (!bad) {
        bad = check_csv_rows(path, &run);
        jc_run_free(&run);
    }
    remove(path);
    rmdir(dir);
    ENSURE(!bad);
    return 0;
}

/* The names in a directory other than "." and "..", counted; the first in *one. */
static int dir_entries(const char *dir, char *one, size_t one_len)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        if (n++ == 0 && one) snprintf(one, one_len, "%s", e->d_name);
    }
    closedir(d);
    return n;
}

static int test_csv_unwritable(void)
{
    /* A directory that does not exist. */
    const char *missing = "/nonexistent-dir/x.csv";
    cli_result r = run_cli("simulate --preset paper --incline 30 --mu 0.5 --csv /nonexistent-dir/x.csv");
    const int status = r.status;
    const int names = r.err && strstr(r.err, missing) != NULL;
    const int one_line = r.err && strchr(r.err, '\n') == r.err + strlen(r.err) - 1;
    const int quiet_out = r.out && r.out[0] == '\0';
    if (!names) fprintf(stderr, "stderr: '%s'\n", r.err ? r.err : "(none)");
    cli_result_free(&r);
    ENSURE_MSG(status == 1, "exit status %d", status);
    ENSURE(names && one_line && quiet_out);
    ENSURE(access(missing, F_OK) != 0);

    /* A target that cannot be replaced (a directory): the write goes to a
     * temporary file beside it, and the failure must remove that. */
    char dir[] = "/tmp/jc_sim_cli_XXXXXX", target[256], args[512];
    ENSURE(cli_scratch(dir, target, sizeof target, "out.csv") == 0);
    int bad = mkdir(target, 0700) != 0;
    snprintf(args, sizeof args, "simulate --preset paper --incline 30 --mu 0.5 --csv '%s'", target);
    r = run_cli(args);
    const int status2 = r.status;
    const int names2 = r.err && strstr(r.err, target) != NULL;
    cli_result_free(&r);
    char first[256] = "";
    const int entries = dir_entries(dir, first, sizeof first);
    struct stat st;
    const int still_dir = stat(target, &st) == 0 && S_ISDIR(st.st_mode);
    rmdir(target);
    rmdir(dir);
    ENSURE(!bad);
    ENSURE_MSG(status2 == 1, "exit status %d", status2);
    ENSURE(names2);
    ENSURE_MSG(entries == 1 && strcmp(first, "out.csv") == 0, "%d entries left in the directory (first '%s')",
               entries, first);
    ENSURE(still_dir);
    return 0;
}

/* --impact-law: Newton's law on the repro gains energy and says so on
 * standard error, with the gain, which the JSON reports too; Stronge's law
 * (the default) gains nothing and warns nothing. Unknown laws and
 * mu_k > mu_s are usage errors (exit 2) with a message naming them. */
static int test_impact_law_option(void)
{
    cli_result r = run_cli("simulate --incline 45 --restitution 1 --impact-law newton --json");
    const int ok_newton = r.status == 0 && r.err && strstr(r.err, "gained kinetic energy under Newton's law") != NULL;
    cJSON *doc = r.out ? cJSON_Parse(r.out) : NULL;
    const cJSON *gains = cJSON_GetObjectItemCaseSensitive(doc, "energy_gaining_impacts");
    const cJSON *gain = cJSON_GetObjectItemCaseSensitive(doc, "largest_impact_gain_J");
    const int json_ok = cJSON_IsNumber(gains) && gains->valuedouble >= 1 && cJSON_IsNumber(gain) &&
                        gain->valuedouble > 0 && string_is(doc, "impact_law", "newton") == 0;
    char want[64] = "";
    if (cJSON_IsNumber(gain)) snprintf(want, sizeof want, "%+.6g J", gain->valuedouble);
    const int names_gain = r.err && want[0] && strstr(r.err, want) != NULL;
    cJSON_Delete(doc);
    cli_result_free(&r);
    ENSURE_MSG(ok_newton && json_ok && names_gain, "newton: warning %d, json %d, gain in the warning %d", ok_newton,
               json_ok, names_gain);

    r = run_cli("simulate --incline 45 --restitution 1 --json");
    doc = r.out ? cJSON_Parse(r.out) : NULL;
    gains = cJSON_GetObjectItemCaseSensitive(doc, "energy_gaining_impacts");
    const int quiet = r.status == 0 && r.err && r.err[0] == '\0' && cJSON_IsNumber(gains) && gains->valuedouble == 0 &&
                      string_is(doc, "impact_law", "stronge") == 0;
    cJSON_Delete(doc);
    cli_result_free(&r);
    ENSURE_MSG(quiet, "stronge: a warning or a gain");

    r = run_cli("simulate --impact-law elastic");
    const int bad_law = r.status == 2 && r.err && strstr(r.err, "elastic") && strstr(r.err, "stronge, poisson, newton");
    cli_result_free(&r);
    ENSURE(bad_law);
    r = run_cli("simulate --mu-s 0.3 --mu-k 0.5");
    const int bad_mu = r.status == 2 && r.err && strstr(r.err, "larger than static friction");
    cli_result_free(&r);
    ENSURE(bad_mu);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH-TO-jumpcyl\n", argv[0]);
        return 2;
    }
    cli_path = argv[1];
    gsl_set_error_handler_off();
    RUN_TEST(test_json_matches_library);
    RUN_TEST(test_csv);
    RUN_TEST(test_csv_unwritable);
    RUN_TEST(test_impact_law_option);
    TEST_MAIN_END();
}
