/* Fuzz target: the values of batch jobs. The input is one option value as
 * a user would type it after --vary, --sigma, --range, --shard or --threads;
 * it goes through each parser.
 *
 * Invariants: a parser that refuses leaves a message; an accepted --vary
 * has 1 .. CLI_PARAM_VALUES_MAX finite values, each of which makes a valid
 * setup, and its text in its unit (jc_param_format) reads back to the same value; an accepted
 * spread has a finite, ordered range (sigma >= 0, LO <= HI); an accepted
 * shard is 1 <= K <= N, and its ranges tile the cases. */
#include "fuzz.h"

#include "batch.h"

#include <math.h>
#include <string.h>

#define MAX_INPUT 512

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

static void check_vary(const char *text)
{
    cli_SetupArgs args;
    memset(&args, 0, sizeof args);
    cli_Param p;
    char err[600] = "";
    if (cli_param_parse_vary(text, &args, &p, err, sizeof err) != 0) {
        FUZZ_CHECK(err[0] != '\0');
        return;
    }
    FUZZ_CHECK(p.count >= 1 && p.count <= CLI_PARAM_VALUES_MAX);
    jc_Setup base, s;
    cli_SetupValues values;
    FUZZ_CHECK(cli_setup_base(&args, &base, err, sizeof err) == 0);
    FUZZ_CHECK(cli_setup_values(&args, &values, err, sizeof err) == 0);
    const long step = p.count > 64 ? p.count / 64 : 1; /* a sample of long lists: each is a whole setup build */
    for (long k = 0; k < p.count; k += step) {
        FUZZ_CHECK(isfinite(p.values[k]));
        FUZZ_CHECK(cli_case_setup(&base, &values, &p, 1, &p.values[k], &s, err, sizeof err) == 0);
        /* the value as text, in the parameter's unit, reads back to itself */
        char written[80];
        double back = NAN;
        FUZZ_CHECK(jc_param_format(p.id, p.values[k], written, sizeof written) == JC_OK);
        FUZZ_CHECK(jc_param_parse(p.id, written, &back, err, sizeof err) == JC_OK && back == p.values[k]);
    }
    cli_param_free(&p);
}

static void check_spread(const char *text, jc_StudySpread kind)
{
    const jc_Setup nominal = jc_paper_setup();
    cli_Param p;
    char err[600] = "";
    if (cli_param_parse_spread(text, kind, &nominal, &p, err, sizeof err) != 0) {
        FUZZ_CHECK(err[0] != '\0');
        return;
    }
    FUZZ_CHECK(isfinite(p.a) && isfinite(p.b));
    FUZZ_CHECK(kind == JC_STUDY_NORMAL ? p.b >= 0 : p.a <= p.b);
}

static void check_shard(const char *text)
{
    cli_Shard s;
    char err[300] = "";
    if (cli_shard_parse(text, &s, err, sizeof err) != 0) {
        FUZZ_CHECK(err[0] != '\0');
        return;
    }
    FUZZ_CHECK(s.k >= 1 && s.k <= s.n);
    /* The parts of any job are disjoint and contiguous, and cover it. */
    const long totals[] = {0, 1, 7, 1000003, 10000000000L};
    for (size_t i = 0; i < sizeof totals / sizeof totals[0]; ++i) {
        long lo, hi, prev_lo, prev_hi;
        cli_shard_range(&s, totals[i], &lo, &hi);
        FUZZ_CHECK(0 <= lo && lo <= hi && hi <= totals[i]);
        if (s.k > 1) {
            const cli_Shard before = {s.k - 1, s.n};
            cli_shard_range(&before, totals[i], &prev_lo, &prev_hi);
            FUZZ_CHECK(prev_hi == lo);
        }
        if (s.k == s.n) FUZZ_CHECK(hi == totals[i]);
        if (s.k == 1) FUZZ_CHECK(lo == 0);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > MAX_INPUT) return 0;
    char text[MAX_INPUT + 1];
    memcpy(text, data, size);
    text[size] = '\0';
    if (strlen(text) != size) return 0; /* an argument holds no NUL */
    check_vary(text);
    check_spread(text, JC_STUDY_NORMAL);
    check_spread(text, JC_STUDY_UNIFORM);
    check_shard(text);
    int threads;
    char err[300] = "";
    if (cli_threads_parse(text, &threads, err, sizeof err) == 0) FUZZ_CHECK(threads >= 1 && threads <= 1024);
    else FUZZ_CHECK(err[0] != '\0');
    return 0;
}
