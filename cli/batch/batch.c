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
#include <time.h>
#include <unistd.h>

#ifdef JC_HAVE_MPI
#include <mpi.h>
#endif

/* Cases per thread in an MPI job's block (the library's blocks are as
 * large): a block takes a few tens of milliseconds, so a stop is honoured
 * quickly and rows reach the file steadily. */
#define BLOCK_CASES_PER_THREAD 256
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
         "                  fsynced every second, until the job completes and they become FILE;\n"
         "                  only this job's own FILE.part is taken: each row's checksum is\n"
         "                  checked and 1 % of them computed again)\n"
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
    FILE *f;         /* in place: "-", or a device or FIFO (no FILE.part) */
    int to_stdout;   /* written in place */
    int opened;      /* a device or FIFO we opened (closed at the end) */
    cli_PartFile part; /* FILE.part, when part.fd >= 0 */
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

/* A kept row read back on --resume: this case's inputs, handed to the consumer. */
static int resumed_row(void *ctx, long index, const char *line, size_t len, const cli_CaseResult *r)
{
    const job *j = ctx;
    if (!row_matches(j, index, line, len)) return -1;
    if (j->b->consume) {
        char row[JC_STUDY_ROW_MAX + 1];
        memcpy(row, line, len);
        row[len] = '\n';
        row[len + 1 < sizeof row ? len + 1 : len] = '\0';
        j->b->consume(j->b->consume_ctx, index, &r->outcome, row, (int)len + 1);
    }
    return 0;
}

/* Rows computed again on --resume: 1 % of the kept rows, at least 3 (all
 * when fewer), one drawn in each of as many equal stretches of the file. */
#define RECHECK_PERCENT 1
#define RECHECK_MIN 3

typedef struct {
    const job *j;
    long lo;          /* the first kept row's case */
    long k, rows;     /* stretches; kept rows */
    uint64_t seed;
    long next;        /* the next stretch */
    long pick;        /* the row chosen in it */
    long bad_line;    /* the first row that differs (its 0-based row), -1 if none */
} recheck;

/* The row chosen in stretch s. */
static long recheck_pick(const recheck *c, long s)
{
    const long a = (long)((long double)c->rows * s / c->k), z = (long)((long double)c->rows * (s + 1) / c->k);
    const long at = a + (long)(jc_random_uniform(c->seed, (uint64_t)s, 0) * (double)(z - a));
    return at < z ? at : z - 1;
}

typedef struct {
    char csv[JC_STUDY_ROW_MAX];
    int len;
} one_row;

static int one_row_take(void *ctx, const jc_StudyRow *row)
{
    one_row *o = ctx;
    o->len = row->csv ? row->csv_len : 0;
    if (row->csv) memcpy(o->csv, row->csv, (size_t)row->csv_len);
    return 0;
}

static int recheck_row(void *ctx, long i, const char *line, size_t len)
{
    recheck *c = ctx;
    if (c->next >= c->k || i != c->pick) return 0;
    one_row o = {.len = 0};
    const jc_StudyCallbacks cb = {one_row_take, NULL, &o, 1};
    char err[256];
    jc_StudyDef one = c->j->def;
    one.threads = 1;
    const int st = jc_study_run(&one, c->lo + i, 1, &cb, err, sizeof err);
    if (st != JC_OK || (size_t)o.len != len + 1 || memcmp(o.csv, line, len) != 0) {
        c->bad_line = i;
        return 1;
    }
    if (++c->next < c->k) c->pick = recheck_pick(c, c->next);
    return 0;
}

/* Some kept rows computed again and compared: EXIT_OK, or EXIT_USAGE after
 * a message naming the row that differs. */
static int recheck_rows(const job *j, rows_file *w, long lo, long rows, long *rechecked, uint64_t *seed_out)
{
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    recheck c = {j, lo, 0, rows, 0, 0, 0, -1};
    c.seed = ((uint64_t)now.tv_sec * 1000000007ULL) ^ (uint64_t)now.tv_nsec ^ ((uint64_t)getpid() << 40);
    c.k = rows * RECHECK_PERCENT / 100 + (rows % (100 / RECHECK_PERCENT) != 0);
    if (c.k < RECHECK_MIN) c.k = RECHECK_MIN;
    if (c.k > rows) c.k = rows;
    *rechecked = c.k;
    *seed_out = c.seed;
    if (c.k == 0) return EXIT_OK;
    c.pick = recheck_pick(&c, 0);
    const int st = cli_part_each_row(&w->part, j->b->shard.k == 1, recheck_row, &c);
    if (st < 0) {
        cli_error("%s: cannot read %s: %s", j->b->cmd, w->part.path, strerror(errno));
        return EXIT_FAIL;
    }
    if (c.bad_line >= 0) {
        cli_error("%s: %s: row %ld (case %ld), computed again, differs from the row kept there (rows chosen with "
                  "seed %llu); it is left as it is: remove it to start again",
                  j->b->cmd, w->part.path, c.bad_line + 1, lo + c.bad_line, (unsigned long long)c.seed);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* FILE.part: created, or read, checked and continued (--resume). EXIT_OK
 * or an exit status after a message. */
static int part_open(const job *j, rows_file *w, long lo, long hi, long *done)
{
    const cli_Batch *b = j->b;
    const uint64_t hash = cli_part_job_hash(&j->def, lo, hi);
    char job_line[256];
    cli_part_job_line(b->cmd, hash, lo, hi, job_line, sizeof job_line);
    const cli_PartReader rd = {job_line, b->shard.k == 1 ? j->header : NULL, hash, j->def.param_count, lo, hi - lo,
                               resumed_row, (void *)j};
    int st = cli_part_begin(&w->part, b->cmd, b->output, b->resume, &rd, done);
    if (st != EXIT_OK || *done == 0) return st;
    long rechecked = 0;
    uint64_t seed = 0;
    st = recheck_rows(j, w, lo, *done, &rechecked, &seed);
    if (st != EXIT_OK) {
        cli_part_end(&w->part, b->cmd, b->output, 0, 0);
        return st;
    }
    fprintf(stderr, "%s: resuming after %ld finished cases in %s (%ld of them, chosen with seed %llu, computed again: "
                    "the same)\n",
            b->cmd, *done, w->part.path, rechecked, (unsigned long long)seed);
    return EXIT_OK;
}

/* Opens the rows' file; *done receives the rows already there (resume).
 * EXIT_OK or an exit status after a message. */
static int rows_open(const job *j, rows_file *w, long lo, long hi, long *done)
{
    const cli_Batch *b = j->b;
    memset(w, 0, sizeof *w);
    w->part.fd = -1;
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
        if (cli_check_output_dir(b->output) != 0) return EXIT_FAIL;
        return part_open(j, w, lo, hi, done);
    }
    if (b->shard.k == 1) fputs(j->header, w->f);
    return EXIT_OK;
}

/* The rows so far flushed; fsynced when the last sync is a second old
 * (always when final). 0, or -1 after a message. */
static int rows_flush(const cli_Batch *b, rows_file *w, int final)
{
    if (w->part.fd >= 0) return cli_part_flush(&w->part, b->cmd, final);
    if (!w->f) return 0;
    int bad = fflush(w->f) != 0 || ferror(w->f);
    const int err = errno ? errno : EIO;
    if (bad && !(w->to_stdout && cli_pipe_closed(err)))
        cli_error("%s: cannot write %s: %s", b->cmd, w->opened ? b->output : "standard output", strerror(err));
    return bad ? -1 : 0;
}

/* Closes the file; when the job is complete FILE.part's rows become FILE. */
static int rows_close(const cli_Batch *b, rows_file *w, int complete)
{
    if (w->part.fd >= 0) return cli_part_end(&w->part, b->cmd, b->output, complete, b->shard.k == 1);
    if (w->opened) {
        const int bad = fclose(w->f) != 0;
        w->f = NULL;
        if (bad) cli_error("%s: cannot write %s: %s", b->cmd, b->output, strerror(errno));
        return bad ? -1 : 0;
    }
    return 0;
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
    if (t->w->part.fd >= 0 && row) {
        if (!t->write_failed && cli_part_add(&t->w->part, row, row_len) != 0) {
            cli_error("%s: out of memory for the rows; %ld rows kept in %s: run again with --resume", b->cmd,
                      t->w->part.rows, t->w->part.path);
            t->write_failed = 1;
        }
    } else if (t->w->f && row) fwrite(row, 1, (size_t)row_len, t->w->f);
    t->next = index + 1;
}

/* After a block: its rows flushed, the progress line; 0, or -1 when the
 * rows cannot be written. */
static int block_done(taker *t, long hi)
{
    if (t->write_failed || rows_flush(t->j->b, t->w, t->next == hi) != 0) {
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
    if (!writer) {
        memset(&w, 0, sizeof w);
        w.part.fd = -1;
    }
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
    if (writer && rows_close(b, &w, complete) != 0 && rc == EXIT_OK) {
        rc = EXIT_FAIL;
        if (cli_stop_requested()) { /* between the last row and FILE: every row is kept */
            cli_error("%s: stopped before %s was written; all %ld cases are kept in %s: run the same command with "
                      "--resume to finish", b->cmd, b->output, hi - lo, w.part.path);
            rc = cli_stop_status();
        }
    }
    if (writer && !complete && w.part.path[0] && cli_stop_requested() && !t.write_failed)
        cli_error("%s: stopped after %ld of %ld cases; they are kept in %s: run the same command with --resume to "
                  "continue",
                  b->cmd, next - lo, hi - lo, w.part.path);
    if (writer && t.notes.invalid > 0)
        cli_error("%s: %ld case(s) are not valid setups (first: case %ld)%s", b->cmd, t.notes.invalid,
                  t.notes.first_invalid, b->output ? "; their rows say invalid_setup" : "");
    if (writer && t.notes.failed > 0)
        cli_error("%s: %ld case(s) failed numerically%s", b->cmd, t.notes.failed,
                  b->output ? "; their rows say failed" : "");
    if (rc == EXIT_OK && !complete) return writer ? cli_stop_status() : EXIT_FAIL;
    return rc;
}
