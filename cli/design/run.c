/* design: the library's search (jc_design_run) on the command's job, with
 * the scan's progress line on a terminal and a stop signal as its
 * cancellation. */
#include "design.h"

#include <string.h>

/* The scan's progress line, cleared when the scan is over; nonzero (stop)
 * after a stop signal. */
static int progress(void *ctx, const jc_DesignProgress *p)
{
    cli_Progress *line = ctx;
    if (strcmp(p->stage, "scan") == 0) cli_progress_update(line, p->done, p->total);
    else cli_progress_end(line);
    return cli_stop_requested() != 0;
}

int cli_design_run(const cli_DesignJob *job, jc_DesignResult *r)
{
    jc_DesignDef def;
    memset(&def, 0, sizeof def);
    def.base = job->base;
    def.fixed = job->values;
    def.free_id = job->param.id;
    def.lo = job->lo;
    def.hi = job->hi;
    def.target_x_m = job->target_m;
    def.points = job->points;
    def.threads = job->threads;
    def.sim = job->sim;
    cli_Progress line;
    cli_progress_begin(&line, "design: scan");
    def.progress = progress;
    def.progress_ctx = &line;
    char err[512];
    const int st = jc_design_run(&def, r, err, sizeof err);
    cli_progress_end(&line);
    const int rc = cli_exit_status(st, CLI_INPUTS_CHECKED);
    if (rc == EXIT_FAIL) cli_error("%s", err);
    return rc;
}
