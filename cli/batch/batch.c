/* The engine of batch jobs. The cases are the library's study
 * (jc_study_run: blocks of cases on every thread, each block's rows in case
 * order); in an MPI job the processes each take a slice of every block and
 * rank 0 gathers the slices. The rows are appended in case order, each
 * made by the same code whatever the number of threads, processes or
 * shards, so the file is byte for byte the same.
 *
 * The rows go to FILE.part, flushed after every block and fsynced at least
 * every second, and FILE.part becomes FILE only when the job is complete:
 * a stop (Ctrl-C, a kill, the end of a Slurm allocation) leaves every
 * finished row in FILE.part and an older FILE untouched, and --resume
 * checks the rows there and continues after them. */
#include "batch.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef JC_HAVE_MPI
#include <mpi.h>
#endif

/* Cases per thread in an MPI job's block (the library's blocks are as
 * large): a block takes a few tens of milliseconds, so a stop is honoured
 * quickly and rows reach the file steadily. */
#define BLOCK_CASES_PER_THREAD 256
#define FSYNC_PERIOD_S 1.0
#define HEADER_MAX (2 * JC_STUDY_ROW_MAX)

/* ---- processes (MPI) ---- */

static int mpi_rank(void)
{
#ifdef JC_HAVE_MPI
    int up = 0, rank = 0;
    MPI_Initialized(&up);
    if (up) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
#else
    return 0;
#endif
}

static int mpi_size(void)
{
#ifdef JC_HAVE_MPI
    int up = 0, size = 1;
    MPI_Initialized(&up);
    if (up) MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
#else
    return 1;
#endif
}

void cli_batch_mpi_begin(int *argc, char ***argv)
{
#ifdef JC_HAVE_MPI
    int up = 0;
    MPI_Initialized(&up);
    if (!up) MPI_Init(argc, argv);
#else
    (void)argc;
    (void)argv;
#endif
}

void cli_batch_mpi_end(void)
{
#ifdef JC_HAVE_MPI
    int up = 0, down = 0;
    MPI_Initialized(&up);
    MPI_Finalized(&down);
    if (up && !down) MPI_Finalize();
#endif
}

int cli_batch_is_writer(void) { return mpi_rank() == 0; }

/* A value decided on rank 0, known to every rank. */
static long share_long(long v)
{
#ifdef JC_HAVE_MPI
    if (mpi_size() > 1) MPI_Bcast(&v, 1, MPI_LONG, 0, MPI_COMM_WORLD);
#endif
    return v;
}

#ifdef JC_HAVE_MPI
/* The largest of a value over the ranks (a failure on any rank is every rank's). */
static long worst_long(long v)
{
    if (mpi_size() > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_MAX, MPI_COMM_WORLD);
    return v;
}
#endif

/* ---- options ---- */

int cli_shard_parse(const char *text, cli_Shard *s, char *err, size_t err_len)
{
    char *end;
    errno = 0;
    const long k = strtol(text, &end, 10);
    const int k_ok = end != text && *end == '/' && errno == 0;
    const char *n_text = k_ok ? end + 1 : "";
    const long n = k_ok ? strtol(n_text, &end, 10) : 0;
    if (!k_ok || end == n_text || *end || errno || text[0] == '+' || n_text[0] == '+' || n < 1 || n > 1000000 ||
        k < 1 || k > n) {
        snprintf(err, err_len, "--shard '%s' is not valid (allowed: K/N with 1 <= K <= N <= 1000000, e.g. 3/8)", text);
        return -1;
    }
    s->k = k;
    s->n = n;
    return 0;
}

void cli_shard_range(const cli_Shard *s, long total, long *lo, long *hi)
{
    /* Floor of (k-1) total / n in 128-bit-safe form: total and n are small enough for long double. */
    *lo = (long)((long double)total * (long double)(s->k - 1) / (long double)s->n);
    *hi = (long)((long double)total * (long double)s->k / (long double)s->n);
    if (s->k == s->n) *hi = total;
}

int cli_threads_parse(const char *text, int *threads, char *err, size_t err_len)
{
    char *end;
    errno = 0;
    const long n = strtol(text, &end, 10);
    if (end == text || *end || errno || text[0] == '+' || n < 1 || n > 1024) {
        snprintf(err, err_len, "--threads '%s' is not valid (allowed: a whole number from 1 to 1024)", text);
        return -1;
    }
    *threads = (int)n;
    return 0;
}

int cli_batch_take(const char *cmd, cli_BatchArgs *a, int opt, const char *arg)
{
    switch (opt) {
    case 'o': return cli_take_once(cmd, &a->output, "output", arg);
    case 't': return cli_take_once(cmd, &a->threads, "threads", arg);
    case 's': return cli_take_once(cmd, &a->shard, "shard", arg);
    case 'r': a->resume = 1; return CLI_GO_ON;
    case 'q': a->quiet = 1; return CLI_GO_ON;
    default: return EXIT_USAGE; /* not one of them (getopt passes none such) */
    }
}

int cli_batch_configure(const char *cmd, const cli_BatchArgs *a, cli_Batch *b)
{
    char err[256];
    /* The whole job starts here: what the command adds later is zero until then. */
    *b = (cli_Batch){.cmd = cmd, .output = a->output, .resume = a->resume, .quiet = a->quiet, .shard = {1, 1}};
    if ((a->threads && cli_threads_parse(a->threads, &b->threads, err, sizeof err) != 0) ||
        (a->shard && cli_shard_parse(a->shard, &b->shard, err, sizeof err) != 0)) {
        cli_error("%s: %s", cmd, err);
        return EXIT_USAGE;
    }
    if (a->output && !*a->output) {
        cli_error("%s: --output needs a file name (or - for standard output)", cmd);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

int cli_batch_command_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, const cli_BatchArgs *batch_args,
                            cli_BatchInputs *in)
{
    const int st = cli_command_parse(argc, argv, cmd, ctx, &in->args, &in->sim_args);
    if (st != CLI_GO_ON) return st;
    /* argv[0] is the command's name, as in the parse's messages. */
    const int configured = cli_batch_configure(argv[0], batch_args, &in->job);
    return configured == EXIT_OK ? CLI_GO_ON : configured;
}

int cli_batch_build_inputs(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_Setup *setup,
                           jc_SimOptions *sim, jc_Model *model)
{
    if (cli_sim_given(sim_args, "sample-dt")) {
        cli_error("%s: --sample-dt has no effect here: a case keeps its events' summary, not a trajectory "
                  "(use 'jumpcyl simulate --sample-dt' for one run)",
                  cmd);
        return EXIT_USAGE;
    }
    return cli_build_inputs(cmd, sa, sim_args, setup, sim, model);
}

void cli_batch_help(void)
{
    puts("  --threads N     threads (default: every core; the output does not depend on it)\n"
         "  --shard K/N     only the K-th of N equal, disjoint parts of the cases (Slurm job\n"
         "                  arrays: --shard $SLURM_ARRAY_TASK_ID/N); only part 1 has the header,\n"
         "                  so 'cat' of the parts in order is the whole job's file\n"
         "  --resume        continue an unfinished job from FILE.part (rows are kept there,\n"
         "                  fsynced every second, until the job completes and it becomes FILE)\n"
         "  --quiet         no progress line (it is only shown on a terminal anyway)\n"
         "Under mpirun (a build with -DJUMPCYL_MPI=ON) the processes share the cases and\n"
         "rank 0 writes them in order: the same file as one process.");
}

/* ---- the rows' file ---- */

/* The job as it runs: the batch, its study with the job's threads, the
 * rows' header, and whether the rows' text is wanted (a file, or a
 * consumer of rows: every rank knows it). */
typedef struct {
    const cli_Batch *b;
    jc_StudyDef def;
    char header[HEADER_MAX];
    int rows;
} job;

typedef struct {
    FILE *f;
    int to_stdout;   /* written in place: "-", or a device or FIFO (no FILE.part, no rename) */
    int opened;      /* a device or FIFO we opened (closed at the end) */
    char part[CLI_PATH_MAX];
    double last_sync_s;
} rows_file;

/* Whether the row's inputs (the text between the index and the outcome)
 * are those the job gives that case. */
static int row_matches(const job *j, long index, const char *line, size_t len)
{
    double values[JC_STUDY_PARAM_MAX];
    char head[JC_STUDY_ROW_MAX], why[256];
    jc_Setup s;
    jc_study_case(&j->def, index, values, &s, why, sizeof why);
    const int n = jc_study_row_format(&j->def, index, values, NULL, head, sizeof head - 1);
    head[n] = ',';
    return (size_t)n + 1 <= len && memcmp(head, line, (size_t)n + 1) == 0;
}

/* Reads the rows FILE.part holds, checks that they are this job's, hands
 * them to the consumer and cuts off a last line left half written. The
 * number of complete rows, or -1 after a message. */
static long resume_rows(const job *j, FILE *f, const char *part, long lo, long hi)
{
    const cli_Batch *b = j->b;
    char *line = NULL;
    size_t cap = 0;
    long rows = 0, line_no = 0;
    off_t good_end = 0;
    ssize_t n;
    int bad = 0;
    const int want_header = b->shard.k == 1;
    while ((n = getline(&line, &cap, f)) > 0) {
        ++line_no;
        if (line[n - 1] != '\n') break; /* half written when the job stopped: rewritten below */
        if (want_header && line_no == 1) {
            if (strcmp(line, j->header) != 0) {
                cli_error("%s: %s: its header is not this job's (other --vary, --sigma or --range options?); "
                          "remove it to start again",
                          b->cmd, part);
                bad = 1;
                break;
            }
        } else {
            cli_CaseResult r;
            const long index = lo + rows;
            if (index >= hi || cli_case_from_row(line, (size_t)n - 1, j->def.param_count, &r) != 0 ||
                !row_matches(j, index, line, (size_t)n)) {
                cli_error("%s: %s: line %ld is not case %ld of this job; remove the file to start again", b->cmd,
                          part, line_no, index);
                bad = 1;
                break;
            }
            if (b->consume) b->consume(b->consume_ctx, index, &r.outcome, line, (int)n);
            ++rows;
        }
        good_end += (off_t)n;
    }
    free(line);
    if (bad) return -1;
    if (ferror(f) || ftruncate(fileno(f), good_end) != 0 || fseeko(f, good_end, SEEK_SET) != 0) {
        cli_error("%s: cannot read or cut %s: %s", b->cmd, part, strerror(errno));
        return -1;
    }
    if (want_header && good_end == 0) return 0; /* not even the header: start afresh */
    return rows;
}

/* Opens the rows' file; *done receives the rows already there (resume).
 * EXIT_OK or an exit status after a message. */
static int rows_open(const job *j, rows_file *w, long lo, long hi, long *done)
{
    const cli_Batch *b = j->b;
    memset(w, 0, sizeof *w);
    *done = 0;
    struct stat target;
    if (!b->output) return EXIT_OK;
    if (strcmp(b->output, "-") == 0) {
        if (b->resume) {
            cli_error("%s: --resume needs --output FILE (standard output cannot be continued)", b->cmd);
            return EXIT_USAGE;
        }
        w->f = stdout;
        w->to_stdout = 1;
    } else if (stat(b->output, &target) == 0 && !S_ISREG(target.st_mode)) {
        /* /dev/null, a FIFO, a terminal: written in place, never renamed
         * over (a rename would replace the device node); a directory is refused. */
        if (cli_output_check_target(b->output) != 0) return EXIT_USAGE;
        if (b->resume) {
            cli_error("%s: --resume needs --output FILE, a regular file ('%s' is not one)", b->cmd, b->output);
            return EXIT_USAGE;
        }
        char why[128]; /* a FIFO without a reader is an error, not a hang */
        w->f = cli_fopen_nowait(b->output, "w", O_WRONLY, 0, why, sizeof why);
        if (!w->f) {
            cli_error("%s: cannot open %s: %s", b->cmd, b->output, why);
            return EXIT_FAIL;
        }
        w->to_stdout = w->opened = 1;
    } else {
        if (cli_output_check_target(b->output) != 0) return EXIT_FAIL;
        if (snprintf(w->part, sizeof w->part, "%s.part", b->output) >= (int)sizeof w->part) {
            cli_error("%s: --output '%s': the name is too long", b->cmd, b->output);
            return EXIT_USAGE;
        }
        if (cli_check_output_dir(b->output) != 0) return EXIT_FAIL;
        struct stat st;
        const int exists = stat(w->part, &st) == 0;
        if (exists && !b->resume) {
            cli_error("%s: %s holds the rows of an unfinished job: continue it with --resume, or remove it", b->cmd,
                      w->part);
            return EXIT_USAGE;
        }
        char why[128]; /* a FIFO there would make the rows' reading wait for ever */
        w->f = cli_fopen_nowait(w->part, exists ? "r+" : "w", exists ? O_RDWR : O_WRONLY | O_CREAT | O_TRUNC, 1,
                                why, sizeof why);
        if (!w->f) {
            cli_error("%s: cannot open %s: %s", b->cmd, w->part, why);
            return EXIT_FAIL;
        }
        if (exists) {
            const long rows = resume_rows(j, w->f, w->part, lo, hi);
            if (rows < 0) {
                fclose(w->f);
                w->f = NULL;
                return EXIT_USAGE;
            }
            *done = rows;
            if (cli_batch_is_writer() && rows > 0)
                fprintf(stderr, "%s: resuming after %ld finished cases in %s\n", b->cmd, rows, w->part);
        }
    }
    if (b->shard.k == 1 && (w->to_stdout || ftello(w->f) == 0)) fputs(j->header, w->f);
    w->last_sync_s = cli_now_s();
    return EXIT_OK;
}

/* The rows so far flushed; fsynced when the last sync is a second old
 * (always when final). 0, or -1 after a message. */
static int rows_flush(const cli_Batch *b, rows_file *w, int final)
{
    if (!w->f) return 0;
    int bad = fflush(w->f) != 0 || ferror(w->f);
    if (!bad && !w->to_stdout && (final || cli_now_s() - w->last_sync_s >= FSYNC_PERIOD_S)) {
        bad = fsync(fileno(w->f)) != 0;
        w->last_sync_s = cli_now_s();
    }
    const int err = errno ? errno : EIO;
    if (bad && !(w->to_stdout && cli_pipe_closed(err)))
        cli_error("%s: cannot write %s: %s", b->cmd, w->opened ? b->output : w->to_stdout ? "standard output" : w->part,
                  strerror(err));
    return bad ? -1 : 0;
}

/* Closes the file; when the job is complete FILE.part becomes FILE. */
static int rows_close(const cli_Batch *b, rows_file *w, int complete)
{
    if (w->opened) {
        const int bad = fclose(w->f) != 0;
        w->f = NULL;
        if (bad) cli_error("%s: cannot write %s: %s", b->cmd, b->output, strerror(errno));
        return bad ? -1 : 0;
    }
    if (!w->f || w->to_stdout) return 0;
    int bad = fflush(w->f) != 0 || fsync(fileno(w->f)) != 0;
    bad |= fclose(w->f) != 0;
    w->f = NULL;
    if (!bad && complete) {
        bad = rename(w->part, b->output) != 0;
        if (!bad) cli_sync_dir(b->output);
    }
    if (bad) cli_error("%s: cannot finish %s: %s", b->cmd, complete ? b->output : w->part, strerror(errno));
    return bad ? -1 : 0;
}

/* ---- computing ---- */

/* The kinds of cases seen, for the closing note. */
typedef struct {
    long invalid, failed;
    long first_invalid;
} case_notes;

/* What the writing process does with each case, in case order. */
typedef struct {
    const job *j;
    rows_file *w;
    case_notes notes;
    cli_Progress progress;
    long lo, done;  /* the shard's first case; rows there before (resume) */
    long next;      /* the next case to take */
    int write_failed;
} taker;

static void take_case(taker *t, long index, const jc_CaseOutcome *o, const char *row, int row_len)
{
    const cli_Batch *b = t->j->b;
    if (b->consume) b->consume(b->consume_ctx, index, o, row, row_len);
    if (o->kind == JC_CASE_INVALID && t->notes.invalid++ == 0) t->notes.first_invalid = index;
    t->notes.failed += o->kind == JC_CASE_FAILED;
    if (t->w->f && row) fwrite(row, 1, (size_t)row_len, t->w->f);
    t->next = index + 1;
}

/* After a block: its rows flushed, the progress line; 0, or -1 when the
 * rows cannot be written. */
static int block_done(taker *t, long hi)
{
    if (rows_flush(t->j->b, t->w, t->next == hi) != 0) {
        t->write_failed = 1;
        return -1;
    }
    cli_progress_update(&t->progress, t->next - t->lo - t->done, hi - t->lo - t->done);
    return 0;
}

typedef struct {
    taker *t;
    long hi;
} here_ctx;

static int here_row(void *ctx, const jc_StudyRow *row)
{
    const here_ctx *h = ctx;
    take_case(h->t, row->index, row->outcome, row->csv, row->csv_len);
    return 0;
}

/* The library's cancellation: a stop signal, or rows that cannot be written. */
static int here_progress(void *ctx, long done, long count)
{
    (void)done;
    (void)count;
    const here_ctx *h = ctx;
    if (block_done(h->t, h->hi) != 0) return 1;
    return cli_stop_requested() != 0;
}

/* One process: the cases [t->next, hi) by one call of the library, the rows
 * taken as each block ends. EXIT_OK (complete or stopped by a signal), or
 * EXIT_FAIL after a message. */
static int run_here(taker *t, long hi)
{
    if (cli_stop_requested()) return EXIT_OK;
    here_ctx h = {t, hi};
    const jc_StudyCallbacks cb = {here_row, here_progress, &h, t->j->rows};
    char err[256];
    const int st = jc_study_run(&t->j->def, t->next, hi - t->next, &cb, err, sizeof err);
    if (t->write_failed) return EXIT_FAIL;
    if (st == JC_ESTOPPED && cli_stop_requested()) return EXIT_OK; /* the cases not taken tell the caller */
    const int rc = cli_exit_status(st, CLI_INPUTS_CHECKED);
    if (rc != EXIT_OK) cli_error("%s: %s", t->j->b->cmd, err);
    return rc;
}

#ifdef JC_HAVE_MPI
typedef struct {
    long first;
    cli_CaseResult *r;
} slice_ctx;

static int slice_row(void *ctx, const jc_StudyRow *row)
{
    const slice_ctx *c = ctx;
    cli_CaseResult *r = &c->r[row->index - c->first];
    r->outcome = *row->outcome;
    r->row_len = row->csv_len;
    if (row->csv) memcpy(r->row, row->csv, (size_t)row->csv_len + 1);
    return 0;
}

/* Cases [first, first + n) of the block: this rank's slice computed here
 * (the library, every thread), the others gathered from their ranks onto
 * rank 0. 0, or -1 after a message. */
static int compute_block(const job *j, long first, long n, cli_CaseResult *r)
{
    const int size = mpi_size(), rank = mpi_rank();
    int counts[256], displs[256];
    for (int p = 0; p < size && p < 256; ++p) {
        const long a = n * p / size, z = n * (p + 1) / size;
        counts[p] = (int)((z - a) * (long)sizeof *r);
        displs[p] = (int)(a * (long)sizeof *r);
    }
    const long a = n * rank / size, z = n * (rank + 1) / size;
    slice_ctx c = {first + a, r + a};
    const jc_StudyCallbacks cb = {slice_row, NULL, &c, j->rows};
    char err[256];
    const int st = jc_study_run(&j->def, first + a, z - a, &cb, err, sizeof err);
    if (st != JC_OK) cli_error("%s: %s", j->b->cmd, err);
    MPI_Gatherv(rank == 0 ? MPI_IN_PLACE : (void *)(r + a), counts[rank], MPI_BYTE, r, counts, displs, MPI_BYTE, 0,
                MPI_COMM_WORLD);
    return st == JC_OK ? 0 : -1;
}

/* Several processes: the cases [t->next, hi) block by block, each shared
 * by the ranks; rank 0 decides whether to go on (a stop signal reaches it
 * first) and takes the rows. EXIT_OK (complete or stopped), or EXIT_FAIL. */
static int run_ranks(taker *t, long hi, int writer)
{
    const long block = (long)BLOCK_CASES_PER_THREAD * jc_study_threads(&t->j->def) * mpi_size();
    cli_CaseResult *r = malloc((size_t)block * sizeof *r);
    int rc = (int)worst_long(r ? EXIT_OK : EXIT_FAIL);
    if (rc != EXIT_OK) {
        cli_error("%s: out of memory", t->j->b->cmd);
        free(r);
        return EXIT_FAIL;
    }
    while (rc == EXIT_OK && t->next < hi) {
        if (share_long(cli_stop_requested()) != 0) break;
        const long first = t->next, n = hi - first < block ? hi - first : block;
        if (worst_long(compute_block(t->j, first, n, r) != 0)) rc = EXIT_FAIL; /* a slice missing: no row taken */
        if (writer && rc == EXIT_OK) {
            for (long i = 0; i < n; ++i)
                take_case(t, first + i, &r[i].outcome, t->j->rows ? r[i].row : NULL, r[i].row_len);
            if (block_done(t, hi) != 0) rc = EXIT_FAIL;
        }
        t->next = first + n; /* the ranks that do not write keep count too */
        rc = (int)share_long(rc);
    }
    free(r);
    return rc;
}
#endif

int cli_batch_run(const cli_Batch *b)
{
    job j = {b, *b->study, "", b->output != NULL || b->consume_rows};
    j.def.threads = b->threads;
    char err[256];
    const int checked = jc_study_check(&j.def, err, sizeof err);
    if (checked != JC_OK) {
        cli_error("%s: %s", b->cmd, err);
        return cli_exit_status(checked, CLI_INPUTS_CHECKED);
    }
    jc_study_header(&j.def, j.header, sizeof j.header);
    long lo, hi, done = 0;
    cli_shard_range(&b->shard, jc_study_case_count(&j.def), &lo, &hi);
    const int writer = cli_batch_is_writer(), size = mpi_size();
    if (size > 256) {
        if (writer) cli_error("%s: at most 256 MPI processes (got %d)", b->cmd, size);
        return EXIT_USAGE;
    }
    rows_file w;
    int rc = writer ? rows_open(&j, &w, lo, hi, &done) : EXIT_OK;
    if (!writer) memset(&w, 0, sizeof w);
    rc = (int)share_long(rc);
    if (rc != EXIT_OK) return rc;
    done = share_long(done);

    taker t;
    memset(&t, 0, sizeof t);
    t.j = &j;
    t.w = &w;
    t.notes.first_invalid = -1;
    t.lo = lo;
    t.done = done;
    t.next = lo + done;
    char label[64];
    snprintf(label, sizeof label, "%s: cases", b->cmd);
    cli_progress_begin(&t.progress, label);
    if (b->quiet || !writer) t.progress.enabled = 0;
#ifdef JC_HAVE_MPI
    if (size > 1) rc = run_ranks(&t, hi, writer);
    else
#endif
        rc = run_here(&t, hi);
    cli_progress_end(&t.progress);
    const long next = t.next;
    const int complete = rc == EXIT_OK && next >= hi;
    if (writer && rows_close(b, &w, complete) != 0 && rc == EXIT_OK) rc = EXIT_FAIL;
    if (writer && !complete && w.part[0] && cli_stop_requested())
        cli_error("%s: stopped after %ld of %ld cases; they are kept in %s: run the same command with --resume to "
                  "continue",
                  b->cmd, next - lo, hi - lo, w.part);
    if (writer && t.notes.invalid > 0)
        cli_error("%s: %ld case(s) are not valid setups (first: case %ld)%s", b->cmd, t.notes.invalid,
                  t.notes.first_invalid, b->output ? "; their rows say invalid_setup" : "");
    if (writer && t.notes.failed > 0)
        cli_error("%s: %ld case(s) failed numerically%s", b->cmd, t.notes.failed,
                  b->output ? "; their rows say failed" : "");
    if (rc == EXIT_OK && !complete) return writer ? cli_stop_status() : EXIT_FAIL;
    return rc;
}
