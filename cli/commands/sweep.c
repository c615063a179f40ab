/* jumpcyl sweep: the full model over every combination of setup values. */
#include "commands.h"
#include "batch.h"
#include "figures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cases of one job at most: far beyond a week of one machine's work. */
#define MAX_CASES 1e10

typedef struct {
    const char *vary[CLI_PARAM_MAX + 1];
    int vary_count;
    cli_BatchArgs batch;
} sweep_opts;

static void help(void)
{
    puts("Usage: jumpcyl sweep --vary NAME=VALUES [--vary ...] --output FILE.csv [SETUP OPTIONS]\n"
         "                     [SIMULATION OPTIONS] [--threads N] [--shard K/N] [--resume] [--quiet]\n"
         "The full model for every combination of the varied setup values: one CSV row per case.\n"
         "\n"
         "  --vary NAME=START:STOP:STEP   values START, START+STEP, ... up to STOP\n"
         "  --vary NAME=V1,V2,...         the values listed\n"
         "                  NAME: a setup option (incline, rod-offset, mu, theta0, impact-law, ...);\n"
         "                  values with units as on the command line (angles: degrees, or 0.3rad);\n"
         "                  several --vary make a grid, the last one varying fastest\n"
         "  --output FILE   the CSV file (- for standard output), written as FILE.part while\n"
         "                  the job runs");
    cli_batch_help();
    puts("\n"
         "Columns: case, the varied values (SI, angles in degrees: incline_deg), then the\n"
         "outcome: first_event; first slip and first lift-off (theta_rad, x_m, t_s; empty if\n"
         "none); liftoffs and bounces on the ramp; largest_hop_m (rim above the incline);\n"
         "termination (ramp_end, ramp_top, rest, ..., invalid_setup for a combination that is\n"
         "not a valid setup); end_x_m, end_t_s; energy_balance_error_J.\n"
         "  -h, --help      this help\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    sweep_opts *o = ctx;
    if (opt == 'v') {
        if (o->vary_count == CLI_PARAM_MAX) {
            cli_error("sweep: too many --vary options (allowed: at most %d)", CLI_PARAM_MAX);
            return EXIT_USAGE;
        }
        o->vary[o->vary_count++] = arg;
        return CLI_GO_ON;
    }
    return cli_batch_take("sweep", &o->batch, opt, arg);
}

static const struct option own[] = {{"vary", required_argument, 0, 'v'}, CLI_BATCH_OPTIONS,
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

typedef struct {
    jc_Setup base;
    cli_SetupValues values; /* the job's own single values */
    cli_Param params[CLI_PARAM_MAX];
    int n;
} sweep_job;

/* The varied options, checked against the others. */
static int parse_params(const sweep_opts *o, const cli_SetupArgs *sa, sweep_job *job)
{
    char err[512];
    if (o->vary_count == 0) {
        cli_error("sweep: give at least one --vary NAME=VALUES (e.g. --vary incline=15:45:5)");
        return EXIT_USAGE;
    }
    for (int j = 0; j < o->vary_count; ++j) {
        if (cli_param_parse_vary(o->vary[j], sa, &job->params[j], err, sizeof err) != 0) {
            cli_error("sweep: %s", err);
            return EXIT_USAGE;
        }
        job->n = j + 1;
        const cli_Param *p = &job->params[j];
        const char *name = jc_param_info(p->id)->name;
        for (int i = 0; i < j; ++i)
            if (job->params[i].id == p->id) {
                cli_error("sweep: --vary %s given twice; give all its values in one --vary", name);
                return EXIT_USAGE;
            }
        if (sa->value[p->id]) {
            cli_error("sweep: --%s and --vary %s both given; give one", name, name);
            return EXIT_USAGE;
        }
        if (strcmp(name, "radius") == 0 && sa->part_count > 0) {
            cli_error("sweep: --vary radius with --part bodies: vary a disc+rod body's radius, or list the bodies");
            return EXIT_USAGE;
        }
    }
    return EXIT_OK;
}

static void free_params(sweep_job *job)
{
    for (int j = 0; j < job->n; ++j) cli_param_free(&job->params[j]);
}

int cmd_sweep(int argc, char **argv)
{
    sweep_opts o;
    memset(&o, 0, sizeof o);
    cli_BatchInputs in;
    int st = cli_batch_command_parse(argc, argv, &command, &o, &o.batch, &in);
    if (st != CLI_GO_ON) return st;
    if (!o.batch.output) {
        cli_error("sweep: --output FILE.csv is required (- for standard output)");
        return EXIT_USAGE;
    }
    sweep_job job;
    memset(&job, 0, sizeof job);
    jc_SimOptions sim;
    if ((st = cli_batch_build_inputs("sweep", &in.args, &in.sim_args, &job.base, &sim, NULL)) != EXIT_OK) return st;
    char err[512];
    if (cli_setup_base(&in.args, &job.base, err, sizeof err) != 0 ||
        cli_setup_values(&in.args, &job.values, err, sizeof err) != 0) {
        cli_error("sweep: %s", err);
        return EXIT_USAGE;
    }
    if ((st = parse_params(&o, &in.args, &job)) != EXIT_OK) {
        free_params(&job);
        return st;
    }
    double total = 1;
    for (int j = 0; j < job.n; ++j) total *= (double)job.params[j].count;
    if (total > MAX_CASES) {
        cli_error("sweep: %.3g cases (allowed: at most %.0e; split the grid)", total, MAX_CASES);
        free_params(&job);
        return EXIT_USAGE;
    }
    /* The grid: every combination of the values, the last --vary fastest. */
    jc_StudyDef study;
    cli_study_init(&study, JC_STUDY_GRID, &job.base, &job.values, job.params, job.n, &sim);
    in.job.study = &study;
    const double t0 = cli_now_s();
    st = cli_batch_run(&in.job);
    long lo, hi;
    cli_shard_range(&in.job.shard, jc_study_case_count(&study), &lo, &hi);
    if (st == EXIT_OK && cli_batch_is_writer() && strcmp(in.job.output, "-") != 0)
        printf("Sweep: %ld cases%s in %s (%.1f s)\n", hi - lo, in.job.shard.n > 1 ? " (this shard)" : "", in.job.output,
               cli_now_s() - t0);
    free_params(&job);
    return st;
}
