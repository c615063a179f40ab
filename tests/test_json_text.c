/* JSON numbers written exactly (cli/outputs/json_text.c): every finite
 * double's text reads back to the same double bit for bit, is the shortest
 * of its %.15g, %.16g and %.17g forms that does (so never longer than
 * %.17g), and is cJSON's own %.15g wherever that was already exact; NaN and
 * infinities are null. Random doubles (every exponent, subnormals, values of
 * computations) with the seed printed (JC_TEST_SEED replays one), edge cases
 * by hand, and whole documents printed and parsed back. */
#include "test.h"

#include "outputs.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <stdlib.h>
#include <string.h>

#define RANDOM_DOUBLES 50000

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* The properties of cli_json_number's text for v, checked against printf
 * and strtod themselves. */
static int check_number(double v, unsigned long long seed)
{
    char text[CLI_JSON_NUMBER_MAX];
    const int n = cli_json_number(v, text);
    ENSURE_MSG(n == (int)strlen(text), "%.17g (seed %llu): length %d for '%s'", v, seed, n, text);
    if (!isfinite(v)) {
        ENSURE_MSG(strcmp(text, "null") == 0, "%g: '%s', want null", v, text);
        return 0;
    }
    char *end = NULL;
    const double back = strtod(text, &end);
    ENSURE_MSG(*end == '\0' && same_bits(back, v), "%.17g (seed %llu): '%s' reads back as %.17g", v, seed, text,
               back);
    char forms[3][40];
    int exact[3], len[3];
    for (int k = 0; k < 3; ++k) {
        len[k] = snprintf(forms[k], sizeof forms[k], "%.*g", 15 + k, v);
        exact[k] = same_bits(strtod(forms[k], NULL), v);
    }
    ENSURE_MSG(exact[2], "%.17g: %%.17g does not read back", v); /* printf's own promise */
    ENSURE_MSG(n <= len[2], "%.17g (seed %llu): '%s' is longer than %%.17g's '%s'", v, seed, text, forms[2]);
    int is_form = 0;
    for (int k = 0; k < 3; ++k) {
        is_form |= strcmp(text, forms[k]) == 0;
        ENSURE_MSG(!exact[k] || n <= len[k], "%.17g (seed %llu): '%s', but '%s' reads back too and is shorter", v,
                   seed, text, forms[k]);
    }
    ENSURE_MSG(is_form, "%.17g (seed %llu): '%s' is none of %%.15g, %%.16g, %%.17g", v, seed, text);
    /* Where cJSON's first try was already exact, the text is unchanged
     * (unless an exponent made it longer than %.17g, 1e15 <= |v| < 1e17). */
    if (exact[0] && len[0] <= len[2]) ENSURE_MSG(strcmp(text, forms[0]) == 0, "%.17g: '%s', cJSON's exact '%s'", v, text, forms[0]);
    return 0;
}

/* The significant digits of a number's text (before any exponent). */
static int significant_digits(const char *text)
{
    int n = 0, leading = 1;
    for (const char *c = text; *c && *c != 'e'; ++c) {
        if (*c < '0' || *c > '9') continue;
        leading = leading && *c == '0';
        n += !leading;
    }
    return n;
}

static uint64_t next_bits(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return *state * 2685821657736338717ull;
}

static int test_random_doubles(void)
{
    const char *env = getenv("JC_TEST_SEED");
    const unsigned long long seed = env ? strtoull(env, NULL, 10) : 20261201ull;
    uint64_t state = seed * 0x9E3779B97F4A7C15ull + 1;
    printf("  seed %llu (JC_TEST_SEED replays it), %d doubles of each kind\n", seed, RANDOM_DOUBLES);
    int subnormals = 0, needed_17 = 0, cjson_lost = 0;
    for (int i = 0; i < RANDOM_DOUBLES; ++i) {
        /* Any bit pattern: every exponent, subnormals, both signs. */
        const uint64_t bits = next_bits(&state);
        double v;
        memcpy(&v, &bits, sizeof v);
        if (isfinite(v) && check_number(v, seed)) return 1;
        subnormals += isfinite(v) && v != 0 && fabs(v) < DBL_MIN;
        /* A quotient of whole numbers and a sum, as a computation makes
         * them, and a whole number up to 2^57 (where %.15g and %.16g may
         * need an exponent that %.17g does not). */
        const double a = floor(test_uniform(&state, 1, 1e6)), b = floor(test_uniform(&state, 1, 1e3));
        const double q = a / b, s = test_uniform(&state, -1, 1) + test_uniform(&state, 0, 1e-3);
        const double whole = floor(test_uniform(&state, -0x1p57, 0x1p57));
        if (check_number(q, seed) || check_number(s, seed) || check_number(-q * 1e-9, seed) ||
            check_number(whole, seed))
            return 1;
        char t15[40];
        snprintf(t15, sizeof t15, "%.15g", s);
        const double r = strtod(t15, NULL);
        /* cJSON's test: %.15g within a relative DBL_EPSILON; here it is not exact. */
        cjson_lost += r != s && fabs(r - s) <= fmax(fabs(r), fabs(s)) * DBL_EPSILON;
        char text[CLI_JSON_NUMBER_MAX];
        cli_json_number(s, text);
        needed_17 += significant_digits(text) == 17;
    }
    printf("  %d subnormal bit patterns; of the sums, %d needed 17 digits, %d that cJSON would have cut to %%.15g\n",
           subnormals, needed_17, cjson_lost);
    ENSURE_MSG(subnormals > 0 && cjson_lost > 0, "the sample missed a kind of double (seed %llu)", seed);
    return 0;
}

/* Each edge case and the text it must have. */
static int test_edge_cases(void)
{
    static const struct {
        double v;
        const char *text;
    } cases[] = {
        {0.0, "0"},
        {-0.0, "-0"},
        {3.0, "3"},
        {-7.0, "-7"},
        {1e15, "1e+15"},
        {123456789.0, "123456789"},
        {0.1, "0.1"},
        {0.1 + 0.2, "0.30000000000000004"}, /* cJSON wrote 0.3: a relative DBL_EPSILON away */
        {1.0 / 3.0, "0.3333333333333333"},
        {2.0 / 3.0, "0.6666666666666666"},
        {0.7, "0.7"},
        {5e-324 * 3, "1.48219693752374e-323"},
        {1e300, "1e+300"},
        {-1e-300, "-1e-300"},
        {9007199254740993.0, "9007199254740992"}, /* 2^53 + 1 is 2^53 as a double: 16 digits, not %.15g's */
        {9007199254740994.0, "9007199254740994"},
        {12345678901234568.0, "12345678901234568"},
        {12345678901234560.0, "12345678901234560"}, /* %.16g reads back too, with an exponent: longer */
        {1234567890123450.0, "1234567890123450"},   /* as %.15g's exact 1.23456789012345e+15 */
        {1234567890123456.0, "1234567890123456"},
        {1.5e16, "1.5e+16"},
        {DBL_MAX, "1.7976931348623157e+308"},
        {DBL_MIN, "2.2250738585072014e-308"},
        {4.9406564584124654e-324, "4.94065645841247e-324"}, /* the smallest subnormal */
        {2 * 4.9406564584124654e-324, "9.88131291682493e-324"},
        {NAN, "null"},
        {INFINITY, "null"},
        {-INFINITY, "null"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        char text[CLI_JSON_NUMBER_MAX];
        cli_json_number(cases[k].v, text);
        ENSURE_MSG(strcmp(text, cases[k].text) == 0, "%.17g: '%s', want '%s'", cases[k].v, text, cases[k].text);
        if (check_number(cases[k].v, 0)) return 1;
    }
    return 0;
}

/* A document with numbers at every depth. */
static cJSON *sample_doc(const double *values, int n)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddNumberToObject(doc, "first", values[0]);
    cJSON *arr = cJSON_AddArrayToObject(doc, "list");
    cJSON *inner = cJSON_CreateObject();
    for (int k = 1; k < n; ++k) cJSON_AddItemToArray(arr, cJSON_CreateNumber(values[k]));
    cJSON_AddStringToObject(inner, "word", "1.5");
    cJSON_AddNullToObject(inner, "none");
    cJSON_AddBoolToObject(inner, "flag", 1);
    cJSON_AddNumberToObject(inner, "last", values[n - 1]);
    cJSON_AddItemToArray(arr, inner);
    return doc;
}

static int test_documents(void)
{
    const double values[] = {0.1 + 0.2, -0.0, 1e-310, 42.0, 2.0 / 3.0, NAN, 0.5, -1e22};
    const int n = (int)(sizeof values / sizeof values[0]);
    /* Unformatted, by hand. */
    cJSON *doc = sample_doc(values, n);
    char *flat = cli_json_text(doc, 0);
    cJSON_Delete(doc);
    const char *want = "{\"first\":0.30000000000000004,\"list\":[-0,9.99999999999997e-311,42,0.6666666666666666,null,0.5,-1e+22,"
                       "{\"word\":\"1.5\",\"none\":null,\"flag\":true,\"last\":-1e+22}]}";
    ENSURE_MSG(flat && strcmp(flat, want) == 0, "'%s'\nwant '%s'", flat ? flat : "(null)", want);
    /* Formatted: parsed back, every number bit for bit, and the layout cJSON's own. */
    doc = sample_doc(values, n);
    char *pretty = cli_json_text(doc, 1);
    cJSON_Delete(doc);
    cJSON *back = pretty ? cJSON_Parse(pretty) : NULL;
    ENSURE_MSG(back, "the formatted text does not parse: %s", pretty ? pretty : "(null)");
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(back, "list");
    int ok = same_bits(cJSON_GetObjectItemCaseSensitive(back, "first")->valuedouble, values[0]);
    for (int k = 1; k < n; ++k) {
        const cJSON *it = cJSON_GetArrayItem(list, k - 1);
        ok &= isnan(values[k]) ? cJSON_IsNull(it) : cJSON_IsNumber(it) && same_bits(it->valuedouble, values[k]);
    }
    char *reprinted = cJSON_Print(back); /* cJSON's layout; its numbers may differ, its lines do not */
    int lines_a = 0, lines_b = 0;
    for (const char *c = pretty; *c; ++c) lines_a += *c == '\n';
    for (const char *c = reprinted; c && *c; ++c) lines_b += *c == '\n';
    cJSON_Delete(back);
    free(reprinted);
    free(pretty);
    free(flat);
    ENSURE_MSG(ok, "a number of the formatted document did not read back");
    ENSURE_MSG(lines_a == lines_b && lines_a > 5, "%d lines, cJSON's %d", lines_a, lines_b);
    /* Numbers %.15g already held exactly: the text is cJSON's, byte for byte. */
    const double plain[] = {0.25, 3.0, -12.5, 1e-5, 6.02e23};
    doc = sample_doc(plain, 5);
    char *ours = cli_json_text(doc, 1);
    cJSON_Delete(doc);
    doc = sample_doc(plain, 5);
    char *theirs = cJSON_Print(doc);
    cJSON_Delete(doc);
    ok = ours && theirs && strcmp(ours, theirs) == 0;
    free(ours);
    free(theirs);
    ENSURE_MSG(ok, "a document of short numbers differs from cJSON's text");
    ENSURE(cli_json_text(NULL, 1) == NULL);
    return 0;
}

int main(void)
{
    RUN_TEST(test_edge_cases);
    RUN_TEST(test_random_doubles);
    RUN_TEST(test_documents);
    TEST_MAIN_END();
}
