/* Progress of long jobs on stderr. A line is rewritten in place with '\r',
 * so it is shown only when stderr is a terminal: in a log file or a pipe it
 * would be noise. It appears after the first second, so that quick jobs
 * print nothing at all. */
#define _POSIX_C_SOURCE 200809L
#include "outputs.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define PROGRESS_DELAY_S 1.0
#define PROGRESS_PERIOD_S 0.1

double cli_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_begin(cli_Progress *p, const char *label)
{
    memset(p, 0, sizeof *p);
    snprintf(p->label, sizeof p->label, "%s", label);
    p->enabled = isatty(STDERR_FILENO);
    p->start_s = cli_now_s();
}

void cli_progress_update(cli_Progress *p, long done, long total)
{
    if (!p->enabled) return;
    const double now = cli_now_s(), elapsed = now - p->start_s;
    if (elapsed < PROGRESS_DELAY_S || now - p->last_s < PROGRESS_PERIOD_S) return;
    p->last_s = now;
    if (total > 0 && done > 0) {
        const double eta = elapsed * (double)(total - done) / (double)done;
        fprintf(stderr, "\r%s %ld/%ld (%3.0f%%), %.3g/s, ETA %.0f s   ", p->label, done, total,
                100.0 * (double)done / (double)total, (double)done / elapsed, eta);
    } else {
        fprintf(stderr, "\r%s (%.0f s)   ", p->label, elapsed);
    }
    fflush(stderr);
    p->shown = 1;
}

void cli_progress_end(cli_Progress *p)
{
    if (!p->shown) return;
    /* Clear the line so that the next message starts on a clean line. */
    fprintf(stderr, "\r%*s\r", (int)strlen(p->label) + 40, "");
    fflush(stderr);
    p->shown = 0;
}

void cli_progress_tick(void *progress)
{
    cli_progress_update(progress, 0, 0);
}
