/* `simulate --json` streams its document (cli_sim_json_begin/event/end) so
 * that memory does not grow with the run; the text must be the one the
 * in-memory document (cli_sim_json_doc, printed by cli_json_text) gives, byte for
 * byte, on runs with no events, a few, and thousands, with and without
 * lift-offs. */
#include "test.h"

#include "outputs.h"
#include "stream_setups.h"

#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

static int compare(const jc_Setup *s, int max_events, int min_events)
{
    jc_Model m;
    char err[512] = "";
    ENSURE_OK(jc_model_init(&m, s, err, sizeof err), err);
    jc_SimOptions o = jc_default_sim_options();
    o.max_events = max_events;
    jc_Run run;
    ENSURE_OK(jc_simulate(&m, &o, &run, err, sizeof err), err);
    /* In memory, as simulate printed it before it streamed. */
    cJSON *doc = cli_sim_json_doc(&m, &run);
    char *whole = cli_json_text(doc, 1);
    cJSON_Delete(doc);
    /* Streamed. */
    char *streamed = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&streamed, &len);
    jc_RunSummary sum;
    jc_summary_init(&sum);
    int bad = !f || cli_sim_json_begin(f, &m) != 0;
    for (int i = 0; !bad && i < run.event_count; ++i) {
        bad = cli_sim_json_event(f, &run.events[i], i) != 0;
        jc_summary_add(&sum, &run.events[i], i);
    }
    if (!bad) bad = cli_sim_json_end(f, &m, &run, &sum) != 0;
    if (f) fclose(f);
    const int events = run.event_count;
    jc_run_free(&run);
    const size_t n = whole ? strlen(whole) : 0;
    const int same = !bad && whole && streamed && len == n + 1 && memcmp(streamed, whole, n) == 0 &&
                     streamed[n] == '\n';
    if (!same && whole && streamed) {
        size_t k = 0;
        while (k < n && k < len && whole[k] == streamed[k]) ++k;
        fprintf(stderr, "first difference at byte %zu of %zu/%zu: ...%.40s... vs ...%.40s...\n", k, n, len,
                whole + (k > 20 ? k - 20 : 0), streamed + (k > 20 ? k - 20 : 0));
    }
    free(whole);
    free(streamed);
    ENSURE_MSG(events >= min_events, "%d events", events);
    ENSURE_MSG(same, "the streamed JSON differs from the in-memory document");
    return 0;
}

static int test_paper(void)
{
    const jc_Setup s = jc_paper_setup();
    return compare(&s, 10000, 5);
}

static int test_no_events(void)
{
    jc_Setup s = jc_paper_setup();
    s.body.parts[1].mass_kg = 0.0; /* a centred disc on a gentle slope rolls to the end */
    s.incline_rad = 0.05;
    return compare(&s, 10000, 0);
}

static int test_bouncing(void)
{
    const jc_Setup s = bouncing_setup();
    return compare(&s, 10000, 10);
}

static int test_many_events(void)
{
    const jc_Setup s = rocking_hoop_setup();
    return compare(&s, 3000, 500);
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_paper);
    RUN_TEST(test_no_events);
    RUN_TEST(test_bouncing);
    RUN_TEST(test_many_events);
    TEST_MAIN_END();
}
