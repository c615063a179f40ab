/* A study's cases computed on every thread: blocks of cases shared by the
 * threads (OpenMP, dynamic schedule, one workspace each), each block's rows
 * then handed to the caller in case order on the calling thread. What a row
 * holds does not depend on the thread that computed it, so the rows are the
 * same for any thread count. */
#include "study_internal.h"

#include <stdlib.h>

/* Cases per thread in a block: a block takes a few tens of milliseconds, so
 * a stop is honoured quickly and rows reach the caller steadily. */
#define BLOCK_CASES_PER_THREAD 256

typedef struct {
    long cap;             /* cases a block holds */
    int threads;
    double *values;       /* cap x JC_STUDY_PARAM_MAX */
    jc_CaseOutcome *outcome;
    char *csv;            /* cap x JC_STUDY_ROW_MAX, or NULL */
    int *csv_len;
    jc_Workspace **ws;    /* one per thread */
} block_room;

static void room_free(block_room *b)
{
    for (int t = 0; b->ws && t < b->threads; ++t) jc_workspace_free(b->ws[t]);
    free(b->ws);
    free(b->values);
    free(b->outcome);
    free(b->csv);
    free(b->csv_len);
}

static int room_alloc(block_room *b, long cap, int threads, int csv)
{
    *b = (block_room){cap, threads, NULL, NULL, NULL, NULL, NULL};
    b->values = malloc((size_t)cap * JC_STUDY_PARAM_MAX * sizeof *b->values);
    b->outcome = malloc((size_t)cap * sizeof *b->outcome);
    b->ws = calloc((size_t)threads, sizeof *b->ws);
    if (csv) {
        b->csv = malloc((size_t)cap * JC_STUDY_ROW_MAX);
        b->csv_len = malloc((size_t)cap * sizeof *b->csv_len);
    }
    int ok = b->values && b->outcome && b->ws && (!csv || (b->csv && b->csv_len));
    for (int t = 0; ok && t < threads; ++t) ok = (b->ws[t] = jc_workspace_new()) != NULL;
    return ok ? JC_OK : JC_ENOMEM;
}

/* Cases [first, first + n) into the block's room, on every thread. */
static void compute(const jc_StudyDef *def, long first, long n, block_room *b)
{
    JC_OMP("omp parallel for schedule(dynamic, 4) num_threads(b->threads)")
    for (long i = 0; i < n; ++i) {
        double *values = b->values + i * JC_STUDY_PARAM_MAX;
        jc_Setup s;
        char why[256];
        const int ok = jc_study_case(def, first + i, values, &s, why, sizeof why) == JC_OK;
        jc_case_run(ok ? &s : NULL, &def->sim, b->ws[jc_thread_index()], &b->outcome[i]);
        if (b->csv)
            b->csv_len[i] = jc_study_row_format(def, first + i, values, &b->outcome[i], b->csv + i * JC_STUDY_ROW_MAX,
                                                JC_STUDY_ROW_MAX);
    }
}

/* The block's rows to the caller, in order; *taken: how many it had when
 * it asked to stop (nonzero returned), or n. */
static int deliver(const jc_StudyCallbacks *cb, long first, long n, const block_room *b, long *taken)
{
    *taken = n;
    for (long i = 0; cb && cb->row && i < n; ++i) {
        const jc_StudyRow row = {first + i, b->values + i * JC_STUDY_PARAM_MAX, &b->outcome[i],
                                 b->csv ? b->csv + i * JC_STUDY_ROW_MAX : NULL, b->csv ? b->csv_len[i] : 0};
        if (cb->row(cb->ctx, &row) != 0) {
            *taken = i + 1;
            return 1;
        }
    }
    return 0;
}

int jc_study_run(const jc_StudyDef *def, long first, long count, const jc_StudyCallbacks *cb, char *err,
                 size_t err_len)
{
    const int st = jc_study_check(def, err, err_len);
    if (st != JC_OK) return st;
    const long total = jc_study_case_count(def);
    if (first < 0 || count < 0 || first > total || count > total - first)
        return jc_fail(err, err_len, JC_EINVAL, "study: cases %ld .. %ld are not all the study's (allowed: 0 .. %ld)",
                       first, first + count - 1, total - 1);
    if (count == 0) return JC_OK;
    const int threads = jc_study_threads(def);
    const long per_block = (long)BLOCK_CASES_PER_THREAD * threads;
    block_room b;
    if (room_alloc(&b, count < per_block ? count : per_block, threads, cb && cb->csv) != JC_OK) {
        room_free(&b);
        return jc_fail(err, err_len, JC_ENOMEM, "study: out of memory for %ld cases on %d threads", b.cap, threads);
    }
    long done = 0;
    int stop = 0;
    while (done < count && !stop) {
        const long n = count - done < b.cap ? count - done : b.cap;
        compute(def, first + done, n, &b);
        long taken;
        stop = deliver(cb, first + done, n, &b, &taken);
        done += taken;
        if (!stop && cb && cb->progress) stop = cb->progress(cb->ctx, done, count) != 0;
    }
    room_free(&b);
    /* A stop asked for after the last case changes nothing: the range is done. */
    if (done < count)
        return jc_fail(err, err_len, JC_ESTOPPED, "study: stopped by its caller after %ld of %ld cases", done, count);
    return JC_OK;
}
