/* jumpcyl mc: Monte Carlo propagation of input uncertainties through the
 * full model: where the first lift-off falls, how sure that is, and in how
 * many separate windows of the ramp. */
#include "commands.h"
#include "batch.h"
#include "figures.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_SAMPLES 1000
#define MAX_SAMPLES 100000000L /* days of computing; the summary's memory is bounded by --exact-limit */
/* The most samples whose outcomes are kept for the exact percentiles: 16
 * bytes a sample and 8 more while sorting, 48 MB here. Past it they are
 * estimated in one pass (P²), within about 0.2 % of the 2.5 .. 97.5 %
 * range, no more than the sampling error of the percentiles themselves
 * at this count (docs/cli.md "Memory"). */
#define DEFAULT_EXACT_LIMIT 2000000L
#define DEFAULT_GAP_M JC_MC_LIFTOFF_GAP_M /* lift-offs further apart than this are separate regions */
#define HOP_GAP_M JC_MC_HOP_GAP_M         /* the same for the largest hops */

typedef struct {
    const char *samples, *seed, *gap, *summarize, *exact_limit;
    const char *sigma[CLI_PARAM_MAX], *range[CLI_PARAM_MAX];
    int n_sigma, n_range, no_defaults;
    const char *json; /* its file, "-" for standard output; NULL: none */
    cli_BatchArgs batch;
} mc_opts;

static void help(void)
{
    puts("Usage: jumpcyl mc [SETUP OPTIONS] [SIMULATION OPTIONS] [--samples N] [--seed S]\n"
         "                  [--sigma NAME=VALUE ...] [--range NAME=LO:HI ...] [--no-defaults]\n"
         "                  [--output FILE.csv] [--threads N] [--shard K/N] [--resume] [--json FILE]\n"
         "                  [--exact-limit N]\n"
         "Monte Carlo propagation of input uncertainties through the full model: the\n"
         "distribution of the first lift-off and of the largest hop.\n"
         "\n"
         "  --samples N     samples (default 1000)\n"
         "  --seed S        seed of the random numbers, 0 .. 2^64-1 (default 1); sample i is\n"
         "                  the same for any --threads, --shard or MPI process count\n"
         "  --sigma NAME=VALUE  a normal spread of a setup option about its value, with units\n"
         "                  (--sigma rod-offset=0.5mm, --sigma theta0=2); 0 fixes it\n"
         "  --range NAME=LO:HI  a uniform spread (--range mu=0.3:1.0)\n"
         "  --no-defaults   only the spreads given; by default the paper's stated tolerances are\n"
         "                  normal standard deviations (radius 0.05 cm, disc-mass and rod-mass\n"
         "                  0.05 g, rod-offset 0.05 cm, theta0 3 deg) and friction and\n"
         "                  restitution, which it did not measure, are uniform (mu 0.3..1.0,\n"
         "                  restitution 0.1..0.6); an option set on the line keeps its value\n"
         "  --region-gap LEN  lift-offs further apart than this are separate regions (default 2cm)\n"
         "  --json FILE     the summary as JSON into FILE (- or no FILE: standard output, in\n"
         "                  place of the text)\n"
         "  --output FILE   also keep every sample's row (its drawn values and outcome, as sweep);\n"
         "                  - is standard output, which then carries the rows alone\n"
         "  --summarize FILE  the summary of rows kept earlier (shards put together with cat),\n"
         "                  without running anything");
    cli_batch_help();
    puts("A sample whose drawn values make no valid setup (a negative mass) is drawn again, up\n"
         "to 64 times: the normals are truncated to valid setups.\n"
         "Memory: 24 bytes per sample for the exact percentiles (24 MB per million), up to\n"
         "  --exact-limit N  samples (default 2000000: 48 MB); past it no outcome is kept, the\n"
         "                  percentiles are estimated in one pass (P2, GSL's gsl_rstat_quantile:\n"
         "                  at 10^6 samples within about 0.2 % of the 2.5..97.5 % range, coarser\n"
         "                  with fewer) and the output says so; mean and sd stay exact, and the\n"
         "                  regions (cells one --region-gap wide, at most 65536, else not known)\n"
         "  -h, --help      this help\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    mc_opts *o = ctx;
    switch (opt) {
    case 'n': return cli_take_once("mc", &o->samples, "samples", arg);
    case 'S': return cli_take_once("mc", &o->seed, "seed", arg);
    case 'g': return cli_take_once("mc", &o->gap, "region-gap", arg);
    case 'D': o->no_defaults = 1; return CLI_GO_ON;
    case 'f': return cli_take_once("mc", &o->summarize, "summarize", arg);
    case 'x': return cli_take_once("mc", &o->exact_limit, "exact-limit", arg);
    case 'j': o->json = arg; return CLI_GO_ON;
    case 'z':
    case 'u': {
        const char **list = opt == 'z' ? o->sigma : o->range;
        int *n = opt == 'z' ? &o->n_sigma : &o->n_range;
        if (*n == CLI_PARAM_MAX) {
            cli_error("mc: too many --%s options (allowed: at most %d)", opt == 'z' ? "sigma" : "range",
                      CLI_PARAM_MAX);
            return EXIT_USAGE;
        }
        list[(*n)++] = arg;
        return CLI_GO_ON;
    }
    default: return cli_batch_take("mc", &o->batch, opt, arg);
    }
}

static const struct option own[] = {
    {"samples", required_argument, 0, 'n'}, {"seed", required_argument, 0, 'S'},
    {"sigma", required_argument, 0, 'z'},   {"range", required_argument, 0, 'u'},
    {"no-defaults", no_argument, 0, 'D'},   {"region-gap", required_argument, 0, 'g'},
    CLI_JSON_OPTION('j'),                   {"summarize", required_argument, 0, 'f'},
    {"exact-limit", required_argument, 0, 'x'}, CLI_BATCH_OPTIONS,
    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* A whole number from 1 to max, or the one-line error. */
static int parse_count(const char *text, const char *name, long max, long *out)
{
    char *end;
    errno = 0;
    *out = strtol(text, &end, 10);
    if (end == text || *end || errno || text[0] == '+' || *out < 1 || *out > max) {
        cli_error("mc: --%s '%s' is not valid (allowed: a whole number from 1 to %ld)", name, text, max);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static int parse_numbers(const mc_opts *o, long *samples, uint64_t *seed, double *gap, long *exact_limit)
{
    *samples = DEFAULT_SAMPLES;
    *exact_limit = DEFAULT_EXACT_LIMIT;
    *seed = 1;
    *gap = DEFAULT_GAP_M;
    if (o->samples && parse_count(o->samples, "samples", MAX_SAMPLES, samples) != EXIT_OK) return EXIT_USAGE;
    if (o->exact_limit && parse_count(o->exact_limit, "exact-limit", MAX_SAMPLES, exact_limit) != EXIT_OK)
        return EXIT_USAGE;
    if (o->seed && cli_parse_seed("mc", o->seed, seed) != EXIT_OK) return EXIT_USAGE;
    char msg[256];
    if (o->gap && (cli_parse_quantity(o->gap, Q_LENGTH, gap, msg, sizeof msg) != 0 || !(*gap > 0))) {
        cli_error("mc: --region-gap '%s' is not valid (allowed: a length > 0, e.g. 2cm)", o->gap);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

static void print_spreads(const cli_McJob *job)
{
    printf("Uncertain inputs (%d):\n", job->n);
    if (job->n == 0) printf("  none: every sample is the same run\n");
    for (int j = 0; j < job->n; ++j) {
        const cli_Param *p = &job->params[j];
        const double k = p->column_scale;
        const char *unit = p->unit;
        if (p->kind == JC_STUDY_NORMAL)
            printf("  %-14s normal  %.6g %s, sigma %.4g %s   (%s)\n", jc_param_info(p->id)->name, p->a * k, unit,
                   p->b * k, unit, job->why[j]);
        else
            printf("  %-14s uniform %.6g .. %.6g %s   (%s)\n", jc_param_info(p->id)->name, p->a * k, p->b * k,
                   unit, job->why[j]);
    }
}

static void print_stats(const char *what, const jc_Stats *s, long total, double scale, const char *unit)
{
    if (s->n == 0) {
        printf("  no sample has one\n");
        return;
    }
    printf("  %s: mean %.2f %s, sd %.2f %s; 2.5 %% %.2f, median %.2f, 97.5 %% %.2f %s\n", what, s->mean * scale, unit,
           s->sd * scale, unit, s->p2_5 * scale, s->p50 * scale, s->p97_5 * scale, unit);
    if (s->regions_unavailable) {
        printf("  separate regions: not known (the values spread over more than %ld cells of the gap;\n"
               "  a larger --exact-limit keeps them all)\n",
               JC_SKETCH_CELL_MAX);
        return;
    }
    printf("  %d separate region(s)%s:\n", s->region_count, s->regions_truncated ? " (first 16 shown)" : "");
    for (int i = 0; i < s->region_count; ++i) {
        const jc_StatsRegion *r = &s->regions[i];
        printf("    %8.2f .. %8.2f %s: %5.1f %% of the samples (mean %.2f %s)\n", r->lo_m * scale, r->hi_m * scale,
               unit, 100.0 * (double)r->count / (double)total, r->mean_m * scale, unit);
    }
}

static cJSON *json_stats(const jc_Stats *s, long total)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "count", (double)s->n);
    cJSON_AddNumberToObject(o, "fraction", total ? (double)s->n / (double)total : 0.0);
    if (s->n > 0) {
        cJSON_AddNumberToObject(o, "mean", s->mean);
        cJSON_AddNumberToObject(o, "sd", s->sd);
        cJSON_AddNumberToObject(o, "p2_5", s->p2_5);
        cJSON_AddNumberToObject(o, "p50", s->p50);
        cJSON_AddNumberToObject(o, "p97_5", s->p97_5);
    }
    if (s->regions_unavailable) {
        cJSON_AddNullToObject(o, "regions");
        return o;
    }
    cJSON *regions = cJSON_AddArrayToObject(o, "regions");
    for (int i = 0; i < s->region_count; ++i) {
        cJSON *r = cJSON_CreateObject();
        cJSON_AddNumberToObject(r, "lo", s->regions[i].lo_m);
        cJSON_AddNumberToObject(r, "hi", s->regions[i].hi_m);
        cJSON_AddNumberToObject(r, "mean", s->regions[i].mean_m);
        cJSON_AddNumberToObject(r, "fraction", (double)s->regions[i].count / (double)total);
        cJSON_AddItemToArray(regions, r);
    }
    return o;
}

/* Whether standard output carries something other than the text: the
 * JSON document, or the rows (--output -). */
static int stdout_taken(const mc_opts *o, const char *output)
{
    return (o->json && strcmp(o->json, "-") == 0) || (output && strcmp(output, "-") == 0);
}

/* The summary: the JSON document into json (NULL: none), then the text
 * unless text is 0. The exit status. */
static int report(const cli_McJob *job, jc_Tally *t, long samples, const char *json, int text, const cli_Shard *shard)
{
    jc_Stats lift, hop;
    const long valid = t->valid;
    jc_tally_stats(t, &lift, &hop);
    if (json) {
        cJSON *doc = cJSON_CreateObject();
        cJSON_AddNumberToObject(doc, "samples", (double)samples);
        cJSON_AddNumberToObject(doc, "valid", (double)valid);
        cJSON_AddNumberToObject(doc, "invalid", (double)t->invalid);
        cJSON_AddNumberToObject(doc, "slides_at_start", (double)t->slides);
        cJSON_AddNumberToObject(doc, "no_liftoff", (double)t->none);
        if (t->sketch) { /* only then: the documents of smaller jobs stay as they were */
            cJSON_AddStringToObject(doc, "percentiles", "estimated");
            cJSON_AddNumberToObject(doc, "exact_limit", (double)t->keep_max);
        }
        cJSON *l = json_stats(&lift, valid);
        cJSON_AddItemToObject(doc, "first_liftoff_x_m", l);
        cJSON_AddItemToObject(doc, "largest_hop_m", json_stats(&hop, valid));
        const int rc = cli_json_write(doc, json);
        if (rc != EXIT_OK) return rc;
    }
    if (!text) return EXIT_OK;
    if (shard->n > 1)
        printf("(shard %ld of %ld: these samples only; 'cat' the shards' files for the whole set)\n", shard->k,
               shard->n);
    if (job) print_spreads(job);
    printf("\n%ld samples, %ld valid setups", samples, valid);
    if (t->invalid) printf(" (%ld invalid or failed)", t->invalid);
    printf(".\nFirst lift-off on the ramp: %ld of %ld (%.1f %%); no lift-off: %ld (%.1f %%)", t->liftoffs, valid,
           valid ? 100.0 * (double)t->liftoffs / (double)valid : 0.0, t->none,
           valid ? 100.0 * (double)t->none / (double)valid : 0.0);
    if (t->slides) printf("; slides from the start: %ld", t->slides);
    printf("\n");
    if (t->sketch)
        printf("Percentiles estimated in one pass: more than %ld samples (--exact-limit), none kept.\n"
               "(P2, GSL's gsl_rstat_quantile: at 10^6 samples within about 0.2 %% of the 2.5..97.5 %%\n"
               "range, coarser with fewer; mean, sd and regions exact.)\n",
               t->keep_max);
    print_stats("position x", &lift, valid, 100.0, "cm");
    printf("Largest hop (rim above the incline; 0 without a hop):\n");
    print_stats("height", &hop, valid, 1000.0, "mm");
    if (json) printf("JSON written to %s\n", json);
    return EXIT_OK;
}

/* --summarize FILE: the rows of an earlier job (its shards put together)
 * read back and summarised as the job would have been. */
static int summarize(const mc_opts *o, double gap, long exact_limit)
{
    char why[128]; /* a FIFO's open does not wait; its reads end on a stop signal */
    FILE *f = cli_fopen_nowait(o->summarize, "r", O_RDONLY, 0, why, sizeof why);
    if (!f) {
        cli_error("mc: --summarize '%s': %s", o->summarize, why);
        return EXIT_USAGE;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t n = getline(&line, &cap, f);
    int commas = 0;
    for (ssize_t i = 0; i < n; ++i) commas += line[i] == ',';
    const int inputs = commas - JC_CASE_COLUMNS;
    int st = EXIT_OK;
    if (n <= 0 && cli_stop_requested()) {
        st = cli_stop_status(); /* a pipe's silent writer: the wait ended by a signal */
    } else if (n <= 0 || strncmp(line, "case,", 5) != 0 || inputs < 0) {
        cli_error("mc: --summarize '%s': the first line is not the header of mc or sweep rows (case,...)",
                  o->summarize);
        st = EXIT_USAGE;
    }
    jc_Tally t;
    long rows = 0, line_no = 1;
    memset(&t, 0, sizeof t);
    if (st == EXIT_OK)
        st = cli_exit_status(jc_tally_init_bounded(&t, 1 << 16, exact_limit, gap, HOP_GAP_M), CLI_INPUTS_CHECKED);
    while (st == EXIT_OK && (n = getline(&line, &cap, f)) > 0) {
        ++line_no;
        cli_CaseResult r;
        if (line[n - 1] != '\n' || cli_case_from_row(line, (size_t)n - 1, inputs, &r) != 0) {
            cli_error("mc: --summarize '%s': line %ld is not a whole row of %d input columns", o->summarize, line_no,
                      inputs);
            st = EXIT_USAGE;
            break;
        }
        /* the tally grows: a merged file has no stated size */
        if ((st = cli_exit_status(jc_tally_add(&t, &r.outcome), CLI_INPUTS_CHECKED)) != EXIT_OK) {
            cli_error("mc: --summarize: out of memory after %ld rows", rows);
            break;
        }
        ++rows;
    }
    free(line);
    if (st == EXIT_OK && ferror(f)) {
        const int err = errno;
        if (cli_stop_requested()) st = cli_stop_status();
        else {
            cli_error("mc: --summarize '%s': %s", o->summarize, strerror(err));
            st = EXIT_FAIL;
        }
    }
    fclose(f);
    if (st == cli_stop_status() && cli_stop_requested())
        cli_error("mc: --summarize '%s': stopped by %s after %ld rows; nothing was summarized", o->summarize,
                  cli_signal_name(cli_stop_requested()), rows);
    if (st == EXIT_OK) {
        const int text = !stdout_taken(o, NULL);
        if (text) printf("Summary of %ld rows in %s\n", rows, o->summarize);
        const cli_Shard whole = {1, 1};
        st = report(NULL, &t, rows, o->json, text, &whole);
    }
    jc_tally_free(&t);
    return st;
}

int cmd_mc(int argc, char **argv)
{
    mc_opts o;
    memset(&o, 0, sizeof o);
    cli_BatchInputs in;
    int st = cli_batch_command_parse(argc, argv, &command, &o, &o.batch, &in);
    if (st != CLI_GO_ON) return st;
    long samples;
    uint64_t seed;
    double gap;
    long exact_limit;
    if ((st = parse_numbers(&o, &samples, &seed, &gap, &exact_limit)) != EXIT_OK) return st;
    if (o.summarize) return summarize(&o, gap, exact_limit);
    if (in.job.output && o.json && strcmp(in.job.output, o.json) == 0) {
        cli_error(strcmp(o.json, "-") == 0
                      ? "mc: --output - and --json would both write to standard output; give one of them a file"
                      : "mc: --output and --json name the same file");
        return EXIT_USAGE;
    }
    jc_Setup setup;
    jc_SimOptions sim;
    jc_Model model;
    if ((st = cli_batch_build_inputs("mc", &in.args, &in.sim_args, &setup, &sim, &model)) != EXIT_OK) return st;
    cli_McJob job;
    if ((st = cli_mc_job_init(&job, "mc", &in.args, o.sigma, o.n_sigma, o.range, o.n_range, o.no_defaults, seed)) != EXIT_OK)
        return st;
    /* this process's samples: past exact_limit none is kept */
    long lo, hi;
    cli_shard_range(&in.job.shard, samples, &lo, &hi);
    jc_Tally tally;
    if ((st = jc_tally_init_bounded(&tally, hi - lo, exact_limit, gap, HOP_GAP_M)) != JC_OK) {
        cli_error("mc: out of memory for %ld samples", samples);
        jc_tally_free(&tally);
        return cli_exit_status(st, CLI_INPUTS_CHECKED);
    }
    jc_StudyDef study;
    cli_mc_study(&study, &job, samples, &sim);
    in.job.study = &study;
    in.job.consume = cli_mc_consume;
    in.job.consume_ctx = &tally;
    st = cli_batch_run(&in.job);
    if (st == EXIT_OK && cli_batch_is_writer()) {
        const int text = !stdout_taken(&o, in.job.output);
        if (text) {
            printf("Monte Carlo: %ld samples (seed %llu) of the full model about this setup:\n", hi - lo,
                   (unsigned long long)seed);
            cli_print_setup(stdout, &model, 1);
            printf("\n");
        }
        st = report(&job, &tally, hi - lo, o.json, text, &in.job.shard);
    }
    jc_tally_free(&tally);
    return st;
}
