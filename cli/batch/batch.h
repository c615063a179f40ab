/* Many runs of the full model: sweeps over a grid of setup values, Monte
 * Carlo samples of uncertain inputs, regime maps (docs/batch.md). Every
 * case is one run of the library on a setup of its own; the cases of a job
 * are numbered, computed on all cores (OpenMP), on several processes (MPI)
 * or in disjoint shards (Slurm job arrays), and written in case order, so
 * that the output never depends on how the work was spread. */
#ifndef JUMPCYL_BATCH_H
#define JUMPCYL_BATCH_H

#include "cli.h"

#include <stdint.h>

/* ---- params.c: the varied or sampled setup options ---- */

#define CLI_PARAM_MAX 16          /* varied or sampled options per job */
#define CLI_PARAM_VALUES_MAX 1000000L
#define CLI_TOKEN_MAX 48

typedef enum { PARAM_LIST, PARAM_NORMAL, PARAM_UNIFORM, PARAM_FIXED } cli_ParamKind;

typedef struct {
    int id;                     /* the parameter (jc_param_info) */
    int is_name;                /* impact-law: values are names, not numbers */
    cli_Quantity q;
    char column[48];            /* CSV column: "rod_offset_m", "incline_deg", "impact_law" */
    double column_scale;        /* SI value times this is the column's value (1, or 180/pi for degrees) */
    char unit[16];              /* the column's unit as in its name ("m", "deg", "radps"; "" for numbers and names) */
    cli_ParamKind kind;
    /* PARAM_LIST: the values, SI (numbers) or indices into names (impact-law) */
    long count;
    double *values;
    const char *text;           /* the user's text, for messages */
    /* PARAM_NORMAL: nominal, sigma; PARAM_UNIFORM: lo, hi (SI) */
    double a, b;
} cli_Param;

/* The column, unit and scale of parameter id (SI, angles in degrees). */
void cli_param_describe(int id, cli_Param *p);
/* Parses "NAME=START:STOP:STEP" or "NAME=V1,V2,..." (values with units as
 * on the command line). Every value is checked alone on the base setup
 * (base_args: the job's other setup options), so that a bad one is refused
 * before any work. 0, or -1 with a one-line message in err. */
int cli_param_parse_vary(const char *text, const cli_SetupArgs *base_args, cli_Param *p, char *err, size_t err_len);
/* "NAME=SIGMA" (kind PARAM_NORMAL) or "NAME=LO:HI" (PARAM_UNIFORM); the
 * nominal value of a normal comes from the setup. 0, or -1 with a message. */
int cli_param_parse_spread(const char *text, cli_ParamKind kind, const jc_Setup *nominal, cli_Param *p, char *err,
                           size_t err_len);
/* Frees a parameter's list of values. */
void cli_param_free(cli_Param *p);
/* The SI value of a parameter in a setup (the mean of a normal); NaN when
 * the setup has none (rod-mass of a body without a rod). */
double cli_param_nominal(int id, const jc_Setup *s);
/* The value as its CSV column: "%.12g" of the value in the column's unit, or the name. */
void cli_param_column_value(const cli_Param *p, double si_or_index, char *out, size_t len);
/* The rows' header: "case,<the parameters' columns>,<outcome>\n"; NULL when
 * out of memory (free it). */
char *cli_batch_header(const cli_Param *params, int n);
/* The values' CSV columns, comma-separated. */
void cli_param_columns(const cli_Param *params, int n, const double *values, char *out, size_t len);
/* The setup of one case: base (the job's setup before its single-valued
 * options) with the job's options (read once: cli_setup_values) and the
 * case's values over them, set as values (cli_setup_apply_values). */
int cli_case_setup(const jc_Setup *base, const cli_SetupValues *job, const cli_Param *params, int n,
                   const double *values, jc_Setup *out, char *err, size_t err_len);

/* ---- number.c: numbers in rows ---- */

#define CLI_NUMBER_MAX 32
/* printf("%.*g", precision, v), the same bytes, without printf (exact
 * digits in integers); out holds CLI_NUMBER_MAX chars. Returns the length. */
int cli_format_g(double v, int precision, char *out);

/* ---- random.c: counter-based random numbers (Random123's Philox) ---- */

/* The d-th draw of sample i under seed, the same wherever and whenever it
 * is computed: a uniform in (0, 1) and a standard normal. */
double cli_random_uniform(uint64_t seed, uint64_t sample, uint32_t draw);
double cli_random_normal(uint64_t seed, uint64_t sample, uint32_t draw);

/* ---- outcome.c: one case, run and written as a CSV row ---- */

#define CLI_ROW_MAX 1536

typedef enum {
    CASE_LIFTOFF,          /* lifts off on the ramp */
    CASE_NO_LIFTOFF,       /* reaches the ramp's end, its top, rest or a limit without a lift-off */
    CASE_SLIDES_AT_START,  /* cannot roll: it slips at the very start */
    CASE_INVALID,          /* the combination of values is not a valid setup */
    CASE_FAILED            /* the run failed (a numerical failure, reported in the row) */
} cli_CaseKind;

typedef struct {
    cli_CaseKind kind;
    double liftoff_x_m;    /* first lift-off, NaN if none */
    double largest_hop_m;  /* 0 if none */
    int row_len;
    char row[CLI_ROW_MAX]; /* the whole CSV line, '\n' included */
} cli_CaseResult;

/* The outcome columns, after the case index and the input columns. */
void cli_outcome_header(FILE *out);
#define CLI_OUTCOME_COLUMNS 14
/* Runs the case and writes its row: "index,inputs,outcome\n". setup may be
 * NULL: an invalid case (its row says so). */
void cli_case_run(long index, const char *inputs, const jc_Setup *setup, const jc_SimOptions *sim,
                  jc_Workspace *ws, cli_CaseResult *r);
/* The result of a row read back from a file (for --resume): 0, or -1 if the
 * line is not a row of input_columns inputs. */
int cli_case_from_row(const char *line, size_t len, int input_columns, cli_CaseResult *r);

/* ---- batch.c: the job ---- */

typedef struct {
    long k, n; /* shard k of n, 1 <= k <= n */
} cli_Shard;
/* "K/N"; 0, or -1 with a message naming the value and the allowed range. */
int cli_shard_parse(const char *text, cli_Shard *s, char *err, size_t err_len);

typedef struct cli_Batch_s cli_Batch;
struct cli_Batch_s {
    const char *cmd;            /* "sweep", "mc", "map": for messages */
    long total;                 /* cases in the whole job (every shard) */
    cli_Shard shard;
    int threads;                /* 0: OpenMP's default (every core) */
    int quiet;                  /* no progress line */
    int resume;
    const char *output;         /* the rows' file, "-" for standard output; NULL: none */
    int input_columns;
    /* The header of the rows' file (first line, shard 1 only), '\n' included. */
    const char *header;
    const jc_SimOptions *sim;
    /* Case i: its input columns (comma-separated, no leading comma) and its
     * setup; returns 0, or -1 with why set for a combination that is not a
     * valid setup. Called from several threads at once. */
    int (*make_case)(const void *ctx, long index, char *inputs, size_t inputs_len, jc_Setup *setup, char *why,
                     size_t why_len);
    const void *ctx;
    /* Every case in index order, on the process that writes (rank 0):
     * summaries, maps. May be NULL. */
    void (*consume)(void *ctx, long index, const cli_CaseResult *r);
    void *consume_ctx;
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
/* Takes one of them: 0 when taken, EXIT_USAGE after a message, 1 if opt is not one. */
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

/* ---- stats.c: the distribution of an outcome ---- */

typedef struct {
    double lo_m, hi_m;  /* extent of the samples in it */
    long count;
    double mean_m;
} cli_Region;

#define CLI_REGION_MAX 16

typedef struct {
    long n;                    /* samples with a value */
    long none;                 /* samples without one (no lift-off on the ramp) */
    long invalid;              /* invalid or failed cases */
    double mean, sd;
    double p2_5, p50, p97_5;
    int region_count;          /* separate clusters of values (gaps wider than the gap given) */
    cli_Region regions[CLI_REGION_MAX];
    int regions_truncated;
} cli_Stats;

/* Sorts v[0..n) and summarises it; gap_m separates regions. */
void cli_stats_compute(double *v, long n, long none, long invalid, double gap_m, cli_Stats *out);
/* The p-quantile of sorted values (linear between order statistics). */
double cli_quantile(const double *sorted, long n, double p);

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

/* Sample draws tried before a sample is given up as an invalid setup (a
 * normal spread can reach a negative mass): a truncation of the spread. */
#define CLI_MC_ATTEMPTS 64
/* The job for the options sa: the spreads given (--sigma, --range texts),
 * then the defaults (the paper's stated tolerances, and ranges for the
 * friction and restitution it did not measure) for every option that is
 * neither given a spread nor set on the command line, unless no_defaults.
 * EXIT_OK, or EXIT_USAGE after a message. */
int cli_mc_job_init(cli_McJob *job, const char *cmd, const cli_SetupArgs *sa, const char *const *sigma, int n_sigma,
                    const char *const *range, int n_range, int no_defaults, uint64_t seed);
/* The batch's make_case for the job's samples. */
int cli_mc_make_case(const void *ctx, long index, char *inputs, size_t len, jc_Setup *setup, char *why,
                     size_t why_len);

/* The outcomes of the samples, gathered by the batch's consume. */
typedef struct {
    double *liftoff_x_m;  /* first lift-offs on the ramp */
    long liftoffs;
    double *hop_m;        /* largest hops of the valid samples (0 without a hop) */
    long valid;
    long none, slides, invalid;
    long cap;
    int out_of_memory;
} cli_McTally;
int cli_mc_tally_init(cli_McTally *t, long samples);
void cli_mc_tally_free(cli_McTally *t);
void cli_mc_consume(void *ctx, long index, const cli_CaseResult *r);

/* The batch's fields for the job's samples, gathered into tally. */
void cli_mc_batch(cli_Batch *b, const cli_McJob *job, cli_McTally *tally, long samples, const jc_SimOptions *sim);
/* The first lift-off's distribution for the options sa on an incline
 * (degrees), with the default spreads, computed on every core: for
 * `paper` and its figure. tally (may be NULL) receives the counts only.
 * EXIT_OK, an exit status after a message, or the stop status. */
int cli_mc_liftoff_stats(const char *cmd, const cli_SetupArgs *sa, double incline_deg, long samples, uint64_t seed,
                         cli_Stats *out, cli_McTally *tally);
/* Samples per incline of `paper` and `plot --what paper-uncertainty`. */
#define CLI_PAPER_MC_SAMPLES 2000
#define CLI_PAPER_MC_SEED 1

/* ---- sweep.c, mc.c, map.c ---- */
int cmd_sweep(int argc, char **argv);
int cmd_mc(int argc, char **argv);
int cmd_map(int argc, char **argv);

#endif
