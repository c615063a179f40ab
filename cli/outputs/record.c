/* The simulation as the commands run it: through a recorder that also
 * watches for a stop signal, so that a long run behind a plot, a film or a
 * streamed table stops at the next event or sample after Ctrl-C. And the
 * library's statuses as the commands' exit statuses (cli_exit_status). */
#include "outputs.h"

typedef struct {
    const jc_Recorder *inner; /* NULL: nothing kept */
} watch;

static int watch_event(void *ctx, const jc_Event *e)
{
    const watch *w = ctx;
    if (cli_stop_requested()) return JC_ESTOPPED;
    return w->inner && w->inner->event ? w->inner->event(w->inner->ctx, e) : JC_OK;
}

static int watch_sample(void *ctx, const jc_Sample *s)
{
    const watch *w = ctx;
    if (cli_stop_requested()) return JC_ESTOPPED;
    return w->inner->sample(w->inner->ctx, s);
}

int cli_simulate_stream(const jc_Model *m, const jc_SimOptions *o, const jc_Recorder *rec, jc_Run *run,
                        const char *cmd)
{
    watch w = {rec};
    /* Without a sample callback no sample is computed at all. */
    const jc_Recorder watched = {&w, watch_event, rec && rec->sample ? watch_sample : NULL};
    char err[512];
    const int st = jc_simulate_stream(m, o, &watched, run, err, sizeof err);
    /* Stopped by a signal or by the caller's recorder (a failed write):
     * the command says why. */
    if (st == JC_ESTOPPED) return st;
    if (st != JC_OK) cli_error("%s: simulation failed: %s", cmd, err);
    return st;
}

int cli_simulate(const jc_Model *m, const jc_SimOptions *o, jc_Run *run, const char *cmd)
{
    jc_Run arrays = {0};
    const jc_Recorder rec = jc_run_recorder(&arrays);
    const int st = cli_simulate_stream(m, o, &rec, run, cmd);
    run->events = arrays.events;
    run->event_count = arrays.event_count;
    run->samples = arrays.samples;
    run->sample_count = arrays.sample_count;
    return st;
}

int cli_simulate_probe(const jc_Model *m, const jc_SimOptions *o, jc_Run *run, const char *cmd)
{
    return cli_simulate_stream(m, o, NULL, run, cmd);
}

int cli_exit_status(int jc_status, cli_Inputs inputs)
{
    if (jc_status == JC_OK) return EXIT_OK;
    if (jc_status == JC_ESTOPPED && cli_stop_requested()) return cli_stop_status();
    if (jc_status == JC_ENOMEM) return EXIT_FAIL; /* the machine's limit, not the input's fault */
    if (inputs == CLI_INPUTS_VIDEO || (inputs == CLI_INPUTS_GIVEN && jc_status == JC_EINVAL)) return EXIT_USAGE;
    return EXIT_FAIL;
}
