/*
 * The web page's entry point (web/jc_web.c) built natively, with the tool's
 * files it shares (JC_TOOL_SHARED_SOURCES, cmake/sources.cmake) linked as
 * objects, not from an archive: the link itself shows that they need
 * nothing but the library, cJSON and GSL (no experiment-file reader, no
 * output files, no stand-in, no code dropped as unreachable). Then the
 * page's answers against the tool's, byte for byte, as both run on the
 * same machine: the CSV download against `simulate --csv`, the experiment
 * file against `--dump-config`, a sweep's rows against `sweep --output -`
 * (the same doubles: every field printed as the tool prints it is the same
 * text) and the jump site's spread against `mc --json` (equal doubles).
 *
 * Usage: test_web_link JUMPCYL_BINARY
 */
#include "test.h"

#include <cjson/cJSON.h>
#include <jumpcyl/jumpcyl.h>

#include <stdio.h>
#include <stdlib.h>

char *jc_web_simulate(const char *request_json);
char *jc_web_csv(const char *request_json);
char *jc_web_config(const char *request_json);
char *jc_web_sweep(const char *request_json);
char *jc_web_uncertainty(const char *request_json);
void jc_web_free(char *text);

static const char *tool;

/* The tool's standard output for the arguments (at most cap - 1 bytes). */
static size_t run_tool(const char *args, char *out, size_t cap)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "'%s' %s", tool, args);
    FILE *p = popen(cmd, "r");
    if (!p) return 0;
    const size_t n = fread(out, 1, cap - 1, p);
    out[n] = '\0';
    pclose(p);
    return n;
}

/* The member's string of an {"ok": true, member: "..."} answer, copied (free it). */
static char *member(const char *answer, const char *name)
{
    cJSON *doc = cJSON_Parse(answer);
    const cJSON *ok = cJSON_GetObjectItemCaseSensitive(doc, "ok");
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(doc, name);
    char *copy = cJSON_IsTrue(ok) && cJSON_IsString(m) ? strdup(m->valuestring) : NULL;
    cJSON_Delete(doc);
    return copy;
}

static int test_csv_is_the_tools(void)
{
    static const struct { const char *request, *args; } cases[] = {
        {"{\"incline\": 45, \"sample-dt\": \"5ms\"}", "simulate --incline 45 --sample-dt 5ms --csv -"},
        {"{\"preset\": \"hoop\", \"sample-dt\": 0.01, \"t-max\": 3}", "simulate --preset hoop --sample-dt 0.01 --t-max 3 --csv -"},
        {"{\"incline\": 30, \"drag-coefficient\": 1.2, \"sample-dt\": \"2ms\"}",
         "simulate --incline 30 --drag-coefficient 1.2 --sample-dt 2ms --csv -"},
    };
    static char native[1 << 22];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        char *answer = jc_web_csv(cases[k].request);
        ENSURE(answer != NULL);
        char *csv = member(answer, "csv");
        jc_web_free(answer);
        ENSURE_MSG(csv != NULL, "%s", cases[k].request);
        const size_t n = run_tool(cases[k].args, native, sizeof native);
        const int same = n > 100 && strcmp(csv, native) == 0;
        free(csv);
        ENSURE_MSG(same, "%s: the page's CSV differs from `jumpcyl %s` (%zu bytes)", cases[k].request, cases[k].args, n);
    }
    return 0;
}

static int test_config_is_the_tools(void)
{
    static char native[1 << 16];
    char *answer = jc_web_config("{\"preset\": \"hoop\", \"incline\": \"12deg\", \"mu-k\": 0.25}");
    ENSURE(answer != NULL);
    char *ini = member(answer, "config");
    jc_web_free(answer);
    ENSURE(ini != NULL);
    run_tool("simulate --preset hoop --incline 12deg --mu-k 0.25 --dump-config", native, sizeof native);
    const int same = strcmp(ini, native) == 0;
    free(ini);
    ENSURE(same);
    return 0;
}

/* A request naming a file is refused with one line; the entry point goes on. */
static int test_no_files(void)
{
    char *answer = jc_web_simulate("{\"config\": \"examples/hoop.ini\"}");
    ENSURE(answer != NULL);
    ENSURE_MSG(strstr(answer, "\"ok\":false") && strstr(answer, "config") && !strchr(answer, '\n'), "%s", answer);
    jc_web_free(answer);
    answer = jc_web_simulate("{\"incline\": 30}");
    ENSURE(answer != NULL && strncmp(answer, "{\"ok\":true", 10) == 0);
    jc_web_free(answer);
    return 0;
}

/* A sweep's rows against `jumpcyl sweep`'s CSV for the same setup and grid:
 * the grid's step given to the tool as the double the page's n makes,
 * (hi - lo) / (n - 1) in SI with its SI unit, so that both grids are the
 * same doubles. Every field the answer has, printed with %.12g (the tool's
 * digits), is the CSV's text. */
static int sweep_matches(const char *request, const char *setup_args, const char *name, const char *lo,
                         const char *hi, int n)
{
    const int id = jc_param_find(name);
    double a, b;
    ENSURE(jc_param_parse(id, lo, &a, NULL, 0) == JC_OK && jc_param_parse(id, hi, &b, NULL, 0) == JC_OK);
    char args[512];
    snprintf(args, sizeof args, "sweep %s --vary %s=%s:%s:%.17g%s --output -", setup_args, name, lo, hi,
             (b - a) / (n - 1), jc_param_info(id)->si_unit);
    static char native[1 << 20];
    ENSURE_MSG(run_tool(args, native, sizeof native) > 0, "%s", args);
    char *answer = jc_web_sweep(request);
    cJSON *doc = cJSON_Parse(answer);
    jc_web_free(answer);
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(doc, "rows");
    ENSURE_MSG(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(doc, "ok")) && cJSON_GetArraySize(rows) == n, "%s", request);
    /* CSV columns: case, the value, first_event, first_slip_{theta,x,t}, first_liftoff_{theta,x,t}, liftoffs, ..., termination */
    static const struct { int col; const char *key; } fields[] = {
        {2, "first_event"}, {4, "slip_x_m"}, {7, "liftoff_x_m"}, {9, "liftoffs"}, {12, "termination"}};
    char *line = strchr(native, '\n');
    int k = 0;
    for (const cJSON *r = rows->child; r; r = r->next, ++k) {
        ENSURE(line != NULL);
        char *row = line + 1;
        line = strchr(row, '\n');
        if (line) *line = '\0';
        char *cell[16];
        int nc = 0;
        for (char *c = row; nc < 16; ++nc) {
            cell[nc] = c;
            c = strchr(c, ',');
            if (!c) break;
            *c++ = '\0';
        }
        ENSURE_MSG(nc >= 12, "%s: row %d '%s'", args, k, row);
        char mine[64];
        snprintf(mine, sizeof mine, "%.12g", cJSON_GetObjectItemCaseSensitive(r, "value_si")->valuedouble *
                                                 (strcmp(name, "incline") == 0 ? 180 / 3.14159265358979323846 : 1));
        ENSURE_MSG(strcmp(mine, cell[1]) == 0, "%s: row %d value %s vs %s", args, k, mine, cell[1]);
        for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
            const cJSON *v = cJSON_GetObjectItemCaseSensitive(r, fields[f].key);
            if (cJSON_IsString(v)) snprintf(mine, sizeof mine, "%s", v->valuestring);
            else if (cJSON_IsNumber(v)) snprintf(mine, sizeof mine, "%.12g", v->valuedouble);
            else snprintf(mine, sizeof mine, "%s", "");
            ENSURE_MSG(strcmp(mine, cell[fields[f].col]) == 0, "%s: row %d %s: '%s' vs the tool's '%s'", args, k,
                       fields[f].key, mine, cell[fields[f].col]);
        }
    }
    cJSON_Delete(doc);
    return 0;
}

static int test_sweep_is_the_tools(void)
{
    ENSURE(sweep_matches("{\"setup\": {\"incline\": 30}, \"vary\": \"rod-offset\", \"lo\": \"2cm\", \"hi\": \"8cm\", \"n\": 13}",
                         "--incline 30", "rod-offset", "2cm", "8cm", 13) == 0);
    /* The setup's own incline is replaced by the varied one. */
    ENSURE(sweep_matches("{\"setup\": {\"preset\": \"hoop\", \"incline\": 12, \"restitution\": 0.4}, \"vary\": \"incline\", "
                         "\"lo\": \"5deg\", \"hi\": \"40deg\", \"n\": 8}",
                         "--preset hoop --restitution 0.4", "incline", "5deg", "40deg", 8) == 0);
    /* mu's rows (mu-s, mu-k) give way to the varied mu; steep enough to slip at once. */
    ENSURE(sweep_matches("{\"setup\": {\"incline\": 45, \"mu-s\": 0.6, \"mu-k\": 0.5}, \"vary\": \"mu\", \"lo\": 0.05, \"hi\": 1.2, \"n\": 24}",
                         "--incline 45", "mu", "0.05", "1.2", 24) == 0);
    return 0;
}

static int test_sweep_refuses(void)
{
    static const struct { const char *request, *words[3]; } bad[] = {
        {"{\"vary\": \"incline\", \"lo\": 10, \"hi\": 40, \"n\": 1000}", {"n: 1000", "from 2 to 401", NULL}},
        {"{\"vary\": \"incline\", \"lo\": 10, \"hi\": 40, \"n\": 2.5}", {"n: 2.5", "from 2 to 401", NULL}},
        {"{\"vary\": \"incline\", \"lo\": 10, \"hi\": 95}", {"hi: ", "95", "90"}},
        {"{\"vary\": \"incline\", \"lo\": 40, \"hi\": 10}", {"lo 40 deg", "hi 10 deg", NULL}},
        {"{\"vary\": \"impact-law\", \"lo\": 0, \"hi\": 2}", {"impact-law", "names", NULL}},
        {"{\"vary\": \"inclination\", \"lo\": 0, \"hi\": 2}", {"inclination", "allowed: radius", NULL}},
        {"{\"vary\": \"incline\", \"lo\": \"10furlongs\", \"hi\": 40}", {"lo: ", "furlongs", NULL}},
        {"{\"vary\": \"incline\", \"hi\": 40}", {"lo: missing", NULL, NULL}},
        {"{\"vary\": \"rod-mass\", \"lo\": 0.01, \"hi\": 0.05, \"setup\": {\"preset\": \"hoop\"}}", {"vary: ", "rod", NULL}},
        {"{\"vary\": \"incline\", \"lo\": 10, \"hi\": 40, \"setup\": {\"incline\": 95}}", {"incline 95 deg", NULL, NULL}},
        {"{\"vary\": \"incline\", \"lo\": 10, \"hi\": 40, \"points\": 5}", {"unknown key 'points'", "allowed: setup", NULL}},
        {"[1]", {"not a JSON object", NULL, NULL}},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        char *answer = jc_web_sweep(bad[k].request);
        ENSURE(answer != NULL);
        int ok = strncmp(answer, "{\"ok\":false,\"error\":", 20) == 0 && !strchr(answer, '\n');
        for (int w = 0; w < 3 && bad[k].words[w]; ++w) ok = ok && strstr(answer, bad[k].words[w]) != NULL;
        ENSURE_MSG(ok, "%s -> %s", bad[k].request, answer);
        jc_web_free(answer);
    }
    return 0;
}

/* The jump site's spread against `jumpcyl mc --json` for the same setup,
 * samples and seed: the same counts and the same doubles (the same cases,
 * drawn by Philox, in the same order). */
static int spread_matches(const char *request, const char *args)
{
    static char native[1 << 16];
    ENSURE_MSG(run_tool(args, native, sizeof native) > 0, "%s", args);
    char *answer = jc_web_uncertainty(request);
    cJSON *web = cJSON_Parse(answer), *mc = cJSON_Parse(native);
    ENSURE_MSG(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(web, "ok")), "%s", answer);
    jc_web_free(answer);
    static const char *const counts[] = {"samples", "valid", "invalid", "slides_at_start", "no_liftoff"};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; ++k)
        ENSURE_MSG(cJSON_GetObjectItemCaseSensitive(web, counts[k])->valuedouble ==
                       cJSON_GetObjectItemCaseSensitive(mc, counts[k])->valuedouble, "%s: %s", args, counts[k]);
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(web, "first_liftoff_x_m");
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(mc, "first_liftoff_x_m");
    static const char *const stats[] = {"count", "fraction", "mean", "sd", "p2_5", "p50", "p97_5"};
    for (size_t k = 0; k < sizeof stats / sizeof stats[0]; ++k) {
        const double a = cJSON_GetObjectItemCaseSensitive(w, stats[k])->valuedouble;
        const double b = cJSON_GetObjectItemCaseSensitive(t, stats[k])->valuedouble;
        ENSURE_MSG(a == b, "%s: %s %.17g vs the tool's %.17g", args, stats[k], a, b);
    }
    cJSON_Delete(web);
    cJSON_Delete(mc);
    return 0;
}

static int test_spread_is_the_tools(void)
{
    ENSURE(spread_matches("{\"setup\": {\"incline\": 15}, \"samples\": 300}", "mc --incline 15 --samples 300 --json") == 0);
    /* A value the user set is not spread (mu here), as in the tool. */
    ENSURE(spread_matches("{\"setup\": {\"incline\": 30, \"mu\": 0.4}, \"samples\": 200, \"seed\": 7}",
                          "mc --incline 30 --mu 0.4 --samples 200 --seed 7 --json") == 0);
    ENSURE(spread_matches("{\"setup\": {\"preset\": \"hoop\", \"mu-k\": 0.3}, \"samples\": 100}",
                          "mc --preset hoop --mu-k 0.3 --samples 100 --json") == 0);
    char *answer = jc_web_uncertainty("{\"samples\": 5}");
    const int refused = strstr(answer, "samples: 5 is not a whole number from 10 to 20000") != NULL;
    jc_web_free(answer);
    ENSURE(refused);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_web_link JUMPCYL_BINARY\n");
        return 2;
    }
    tool = argv[1];
    RUN_TEST(test_no_files);
    RUN_TEST(test_csv_is_the_tools);
    RUN_TEST(test_config_is_the_tools);
    RUN_TEST(test_sweep_is_the_tools);
    RUN_TEST(test_sweep_refuses);
    RUN_TEST(test_spread_is_the_tools);
    TEST_MAIN_END();
}
