/* design: the whole search on every core: the scan, the edges and the
 * branches (scan.c), then the roots within the branches (solve.c), one
 * workspace per thread. */
#include "design.h"

#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

static int thread_count(int threads)
{
#ifdef _OPENMP
    if (threads > 0) omp_set_num_threads(threads);
    return omp_get_max_threads();
#else
    (void)threads;
    return 1;
#endif
}

int cli_design_run(const cli_DesignJob *job, cli_DesignResult *r)
{
    memset(r, 0, sizeof *r);
    const double t0 = cli_now_s();
    r->threads_used = thread_count(job->threads);
    jc_Workspace **ws = calloc((size_t)r->threads_used, sizeof *ws);
    int ok = ws != NULL;
    for (int t = 0; ok && t < r->threads_used; ++t) ok = (ws[t] = jc_workspace_new()) != NULL;
    int st = ok && cli_design_scan(job, r, ws) == 0 ? EXIT_OK : EXIT_FAIL;
    if (st == EXIT_FAIL) cli_error("design: out of memory for %ld points", job->points);
    if (st == EXIT_OK && !cli_stop_requested()) st = cli_design_solve(job, r, ws);
    if (st == EXIT_OK && cli_stop_requested()) st = cli_stop_status();
    for (int t = 0; ws && t < r->threads_used; ++t) jc_workspace_free(ws[t]);
    free(ws);
    r->seconds = cli_now_s() - t0;
    return st;
}
