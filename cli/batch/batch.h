/* Many runs of the full model: sweeps over a grid of setup values, Monte
 * Carlo samples of uncertain inputs, regime maps (docs/batch.md). The cases
 * are the library's studies (include/jumpcyl/study.h: typed parameters,
 * each case one run computed on every core); here the options' text
 * becomes those parameters, and the cases of a job are shared by several
 * processes (MPI) or disjoint shards (Slurm job arrays) and written in case
 * order, so that the output never depends on how the work was spread. */
#ifndef JUMPCYL_BATCH_H
#define JUMPCYL_BATCH_H

#include "inputs.h"

#include <jumpcyl/study.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/types.h>

/* ---- params.c: the varied or sampled setup options ---- */

#define CLI_PARAM_MAX JC_STUDY_PARAM_MAX /* varied or sampled options per job */
#define CLI_PARAM_VALUES_MAX JC_STUDY_VALUES_MAX
#define CLI_TOKEN_MAX 48

/* A varied or sampled option as the command line gave it: the library's
 * typed parameter (cli_param_study) and what messages and tables show. */
typedef struct {
    int id;                     /* the parameter (jc_param_info) */
    int is_name;                /* impact-law: values are names, not numbers */
    cli_Quantity q;
    char column[48];            /* CSV column: "rod_offset_m", "incline_deg", "impact_law" (jc_study_column) */
    double column_scale;        /* SI value times this is the column's value (1, or 180/pi for degrees) */
    char unit[16];              /* the column's unit as in its name ("m", "deg", "radps"; "" for numbers and names) */
    jc_StudySpread kind;
    /* JC_STUDY_VALUES: the values, SI (numbers) or indices into names (impact-law) */
    long count;
    double *values;
    const char *text;           /* the user's text, for messages */
    /* JC_STUDY_NORMAL: nominal, sigma; JC_STUDY_UNIFORM: lo, hi (SI) */
    double a, b;
} cli_Param;

/* The column, unit and scale of parameter id (SI, angles in degrees). */
void cli_param_describe(int id, cli_Param *p);
/* Parses "NAME=START:STOP:STEP" or "NAME=V1,V2,..." (values with units as
 * on the command line). Every value is checked alone on the base setup
 * (base_args: the job's other setup options), so that a bad one is refused
 * before any work. 0, or -1 with a one-line message in err. */
int cli_param_parse_vary(const char *text, const cli_SetupArgs *base_args, cli_Param *p, char *err, size_t err_len);
/* "NAME=SIGMA" (kind JC_STUDY_NORMAL) or "NAME=LO:HI" (JC_STUDY_UNIFORM);
 * the nominal value of a normal comes from the setup. 0, or -1 with a message. */
int cli_param_parse_spread(const char *text, jc_StudySpread kind, const jc_Setup *nominal, cli_Param *p, char *err,
                           size_t err_len);
/* Frees a parameter's list of values. */
void cli_param_free(cli_Param *p);
/* The SI value of a parameter in a setup (the mean of a normal); NaN when
 * the setup has none (rod-mass of a body without a rod). */
double cli_param_nominal(int id, const jc_Setup *s);
/* The value as its CSV column: "%.12g" of the value in the column's unit, or the name. */
void cli_param_column_value(const cli_Param *p, double si_or_index, char *out, size_t len);
/* The library's parameter (its values point into p's). */
jc_StudyParam cli_param_study(const cli_Param *p);
/* The setup of one case: base (the job's setup before its single-valued
 * options) with the job's options (read once: cli_setup_values) and the
 * case's values over them, set as values (cli_setup_apply_values: the
 * messages name the options). */
int cli_case_setup(const jc_Setup *base, const cli_SetupValues *job, const cli_Param *params, int n,
                   const double *values, jc_Setup *out, char *err, size_t err_len);
/* The study of a job: its kind, base setup, single values, parameters and
 * simulation options (threads and, for a Monte Carlo, samples and seed are
 * the caller's to set). */
void cli_study_init(jc_StudyDef *def, jc_StudyKind kind, const jc_Setup *base, const cli_SetupValues *values,
                    const cli_Param *params, int n, const jc_SimOptions *sim);

/* ---- outcome.c: a case's row, computed or read back ---- */

typedef struct {
    jc_CaseOutcome outcome; /* read back from a row: kind, liftoff_x_m and largest_hop_m only */
    int row_len;
    char row[JC_STUDY_ROW_MAX]; /* the whole CSV line, '\n' included */
} cli_CaseResult;

/* The result of a row read back from a file (for --resume and mc
 * --summarize): 0, or -1 if the line is not a row of input_columns inputs. */
int cli_case_from_row(const char *line, size_t len, int input_columns, cli_CaseResult *r);

/* ---- part_file.c: FILE.part, the rows of an unfinished job ---- */

/* What a job's FILE.part must hold, for cli_part_read. */
typedef struct {
    const char *job_line;   /* the first line (cli_part_job_line), '\n' included */
    const char *csv_header; /* the rows' header expected next, or NULL (a shard past the first has none) */
    uint64_t job;           /* the job's hash (cli_part_job_hash): each row's checksum is keyed by it */
    int input_columns;
    long first, count;      /* the rows are cases first, first + 1, ..., at most count of them */
    /* Each row whose checksum holds (line: its text, no checksum, no '\n'):
     * 0 to take it, nonzero when it is not that case's. May be NULL. */
    int (*row)(void *ctx, long index, const char *line, size_t len, const cli_CaseResult *r);
    void *ctx;
} cli_PartReader;

typedef struct {
    long rows;      /* whole rows read and taken */
    off_t good_end; /* the bytes up to the last whole line (a last line cut short is not counted) */
    int header_done;
} cli_PartRead;

/* The hash of what decides a job's rows: the tool's version, the study
 * (kind, base setup, fixed values, parameters and their values or spreads,
 * samples and seed, simulation options) and the cases [lo, hi) it keeps. */
uint64_t cli_part_job_hash(const jc_StudyDef *def, long lo, long hi);
/* A row's checksum, keyed by the job's hash (row: no '\n'). */
uint64_t cli_part_row_sum(uint64_t job, const char *row, size_t len);
/* "jumpcyl-part 1 CMD version V job HASH cases LO-LAST\n"; its length. */
int cli_part_job_line(const char *cmd, uint64_t job, long lo, long hi, char *out, size_t len);
/* Reads a FILE.part from its start: 0 when it is this job's (out: its
 * whole rows, each checked, and where they end), 1 when it holds nothing of
 * value (empty, or this job's first line cut short), -1 when it is not this
 * job's file or a row is refused (err: why, naming the line). Reads at most
 * a row's length at a time, whatever the file. */
int cli_part_read(FILE *f, const cli_PartReader *rd, cli_PartRead *out, char *err, size_t err_len);

typedef struct {
    int fd;                  /* open and locked (flock) from begin to end; -1 when closed */
    char path[CLI_PATH_MAX]; /* FILE.part */
    uint64_t job;
    off_t end, synced_end;   /* the end of the last whole row written, and synced */
    long rows, synced_rows;  /* the rows there */
    char *buf;               /* rows not yet written, with their checksums */
    size_t len, cap;
    long pending;            /* rows in buf */
    double last_sync_s;
    int created, job_line_done, header_done;
} cli_PartFile;

/* FILE.part of output: created (O_EXCL, O_NOFOLLOW), or with want_resume
 * opened (O_NOFOLLOW; a regular file of one link owned by the user) and
 * read with rd (*done: its rows); locked in either case; the job line and
 * header written. EXIT_OK, or an exit status after a message: another job
 * holds it, it is another job's or not this tool's (left untouched), a row
 * is refused. */
int cli_part_begin(cli_PartFile *p, const char *cmd, const char *output, int want_resume, const cli_PartReader *rd,
                   long *done);
/* A row ('\n'-terminated) into the buffer of the next write; 0, or -1 when memory runs out. */
int cli_part_add(cli_PartFile *p, const char *row, int row_len);
/* The buffered rows written at once, fsynced when the last sync is a
 * second old (always when final). 0; or -1 after a message, the file cut
 * back to its last whole row ("no space left; N rows kept in FILE.part;
 * free space and run again with --resume"). */
int cli_part_flush(cli_PartFile *p, const char *cmd, int final);
/* fn on each kept row of an open FILE.part (i from 0; row: its text, no
 * checksum, no '\n') until fn returns nonzero. 0, or -1 (errno) when it
 * cannot be read. */
int cli_part_each_row(cli_PartFile *p, int has_header, int (*fn)(void *ctx, long i, const char *row, size_t len),
                      void *ctx);
/* complete: the rows (without the job line and the checksums) become
 * output, written as every output is (the mode of the file it replaces
 * kept), and FILE.part is removed. Then the file is closed and unlocked.
 * 0, or -1 after a message (FILE.part kept). has_header: the rows' file
 * has a header line. */
int cli_part_end(cli_PartFile *p, const char *cmd, const char *output, int complete, int has_header);

/* ---- batch.c: the job ---- */

typedef struct {
    long k, n; /* shard k of n, 1 <= k <= n */
} cli_Shard;
/* "K/N"; 0, or -1 with a message naming the value and the allowed range. */
int cli_shard_parse(const char *text, cli_Shard *s, char *err, size_t err_len);

typedef struct cli_Batch_s cli_Batch;
struct cli_Batch_s {
    const char *cmd;            /* "sweep", "mc", "map": for messages */
    const jc_StudyDef *study;   /* the cases (its threads are the job's, below) */
    cli_Shard shard;
    int threads;                /* 0: OpenMP's default (every core) */
    int quiet;                  /* no progress line */
    int resume;
    const char *output;         /* the rows' file, "-" for standard output; NULL: none */
    /* Every case in index order, on the process that writes (rank 0):
     * summaries, maps. row: its CSV line, '\n' included, when there is an
     * output or consume_rows; NULL otherwise (no row is written then). May
     * be NULL. */
    void (*consume)(void *ctx, long index, const jc_CaseOutcome *o, const char *row, int row_len);
    void *consume_ctx;
    int consume_rows;
};

/* The cases of this shard: [*lo, *hi). */
void cli_shard_range(const cli_Shard *s, long total, long *lo, long *hi);
/* Runs the job; EXIT_OK, EXIT_USAGE/EXIT_FAIL after a message, or the stop
 * status after a signal (the finished rows kept for --resume). */
int cli_batch_run(const cli_Batch *b);
/* Whether this process prints results (always, except MPI ranks other than 0). */
int cli_batch_is_writer(void);
/* MPI, when built with it: start and end around a batch command. */
void cli_batch_mpi_begin(int *argc, char ***argv);
void cli_batch_mpi_end(void);

/* --threads N: 0, or -1 with a message. */
int cli_threads_parse(const char *text, int *threads, char *err, size_t err_len);

/* The options every batch command has: --output, --threads, --shard,
 * --resume, --quiet (short codes 'o', 't', 's', 'r', 'q'). */
typedef struct {
    const char *output, *threads, *shard;
    int resume, quiet;
} cli_BatchArgs;
#define CLI_BATCH_OPTIONS                                                                                  \
    {"output", required_argument, 0, 'o'}, {"threads", required_argument, 0, 't'},                        \
        {"shard", required_argument, 0, 's'}, {"resume", no_argument, 0, 'r'}, {"quiet", no_argument, 0, 'q'}
/* A command's take for them: CLI_GO_ON when taken, EXIT_USAGE after a
 * message (or for an opt that is not one of them). */
int cli_batch_take(const char *cmd, cli_BatchArgs *a, int opt, const char *arg);
/* Their values into a new job (every other field zero): EXIT_OK, or
 * EXIT_USAGE after a message. */
int cli_batch_configure(const char *cmd, const cli_BatchArgs *a, cli_Batch *b);
/* cli_build_inputs for a batch command: --sample-dt is refused first (a
 * case records no trajectory). EXIT_OK, or the exit status after a message. */
int cli_batch_build_inputs(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_Setup *setup,
                           jc_SimOptions *sim, jc_Model *model);
/* A batch command's inputs (mc, sweep): its setup and simulation options as
 * given, and the job configured from its batch options. */
typedef struct {
    cli_SetupArgs args;
    cli_SimArgs sim_args;
    cli_Batch job;
} cli_BatchInputs;
/* cli_command_parse into in's options, then cli_batch_configure of
 * batch_args (the command's batch options, in ctx: filled by the parse)
 * into in->job. CLI_GO_ON, or the exit status after --help or a message. */
int cli_batch_command_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, const cli_BatchArgs *batch_args,
                            cli_BatchInputs *in);
/* Their help lines. */
void cli_batch_help(void);

/* ---- mc_job.c: Monte Carlo samples of uncertain inputs ---- */

typedef struct {
    jc_Setup base;              /* the setup before its single-valued options */
    const cli_SetupArgs *args;  /* the job's options */
    cli_SetupValues values;     /* their single values, read once */
    cli_Param params[CLI_PARAM_MAX];
    const char *why[CLI_PARAM_MAX]; /* where each spread comes from */
    int n;
    uint64_t seed;
} cli_McJob;

/* The job for the options sa: the spreads given (--sigma, --range texts),
 * then the library's defaults (jc_study_default_spreads: the paper's stated
 * tolerances, and ranges for the friction and restitution it did not
 * measure) for every option that is neither given a spread nor set on the
 * command line, unless no_defaults. EXIT_OK, or EXIT_USAGE after a message. */
int cli_mc_job_init(cli_McJob *job, const char *cmd, const cli_SetupArgs *sa, const char *const *sigma, int n_sigma,
                    const char *const *range, int n_range, int no_defaults, uint64_t seed);
/* The study of the job's samples. */
void cli_mc_study(jc_StudyDef *def, const cli_McJob *job, long samples, const jc_SimOptions *sim);
/* A batch's consume: the case into the jc_Tally ctx. */
void cli_mc_consume(void *ctx, long index, const jc_CaseOutcome *o, const char *row, int row_len);
/* The first lift-off's distribution for the options sa on an incline
 * (degrees), with the default spreads, computed on every core: for
 * `paper` and its figure. counts (may be NULL) receives the tally's counts
 * (its arrays NULL). EXIT_OK, an exit status after a message, or the stop
 * status. */
int cli_mc_liftoff_stats(const char *cmd, const cli_SetupArgs *sa, double incline_deg, long samples, uint64_t seed,
                         jc_Stats *out, jc_Tally *counts);
/* Samples per incline of `paper` and `plot --what paper-uncertainty`. */
#define CLI_PAPER_MC_SAMPLES 2000
#define CLI_PAPER_MC_SEED 1

#endif
