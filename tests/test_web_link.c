/*
 * The web page's entry point (web/jc_web.c) built natively, with the tool's
 * files it shares (JC_TOOL_SHARED_SOURCES, cmake/sources.cmake) linked as
 * objects, not from an archive: the link itself shows that they need
 * nothing but the library, cJSON and GSL (no experiment-file reader, no
 * output files, no stand-in, no code dropped as unreachable). Then the
 * page's answers against the tool's, byte for byte, as both run on the
 * same machine: the CSV download against `simulate --csv`, the experiment
 * file against `--dump-config`.
 *
 * Usage: test_web_link JUMPCYL_BINARY
 */
#include "test.h"

#include <cjson/cJSON.h>

#include <stdio.h>
#include <stdlib.h>

char *jc_web_simulate(const char *request_json);
char *jc_web_csv(const char *request_json);
char *jc_web_config(const char *request_json);
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
    TEST_MAIN_END();
}
