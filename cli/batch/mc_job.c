/* Monte Carlo samples: the uncertain setup options, each drawn per sample
 * from a normal (--sigma) or a uniform (--range) spread, or the library's
 * defaults (jc_study_default_spreads), as the library's study
 * (jc_study_case: Philox numbers keyed by seed, sample and draw, so that
 * sample i is the same on any thread, shard or rank). */
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A spread given on the command line. */
static int add_param(cli_McJob *job, const char *cmd, const char *text, jc_StudySpread kind, const jc_Setup *nominal,
                     const char *why)
{
    char err[512];
    if (job->n == CLI_PARAM_MAX) {
        cli_error("%s: too many uncertain inputs (allowed: at most %d)", cmd, CLI_PARAM_MAX);
        return EXIT_USAGE;
    }
    cli_Param *p = &job->params[job->n];
    if (cli_param_parse_spread(text, kind, nominal, p, err, sizeof err) != 0) {
        cli_error("%s: %s", cmd, err);
        return EXIT_USAGE;
    }
    for (int i = 0; i < job->n; ++i)
        if (job->params[i].id == p->id) {
            cli_error("%s: %s: %s already has a spread (give one --sigma or --range per input)", cmd, text,
                      jc_param_info(p->id)->name);
            return EXIT_USAGE;
        }
    const char *name = jc_param_info(p->id)->name;
    const int mu_clash = (strcmp(name, "mu") == 0 && (cli_setup_given(job->args, "mu-s") ||
                                                      cli_setup_given(job->args, "mu-k"))) ||
                         (strncmp(name, "mu-", 3) == 0 && cli_setup_given(job->args, "mu"));
    if (mu_clash) {
        cli_error("%s: %s: --mu sets both coefficients; spread either mu or mu-s/mu-k, as given on the line", cmd,
                  text);
        return EXIT_USAGE;
    }
    job->why[job->n++] = why;
    return EXIT_OK;
}

/* Whether the option is already spread or set by the user (then a default
 * spread would override what the user asked for). */
static int user_owns(const cli_McJob *job, int id)
{
    for (int i = 0; i < job->n; ++i)
        if (job->params[i].id == id) return 1;
    if (strcmp(jc_param_info(id)->name, "mu") == 0)
        return cli_setup_given(job->args, "mu-s") || cli_setup_given(job->args, "mu-k") || job->args->value[id];
    return job->args->value[id] != NULL;
}

int cli_mc_job_init(cli_McJob *job, const char *cmd, const cli_SetupArgs *sa, const char *const *sigma, int n_sigma,
                    const char *const *range, int n_range, int no_defaults, uint64_t seed)
{
    char err[512];
    memset(job, 0, sizeof *job);
    job->args = sa;
    job->seed = seed;
    jc_Setup nominal;
    if (cli_setup_base(sa, &job->base, err, sizeof err) != 0 || cli_setup_build(sa, &nominal, err, sizeof err) != 0 ||
        cli_setup_values(sa, &job->values, err, sizeof err) != 0) {
        cli_error("%s: %s", cmd, err);
        return EXIT_USAGE;
    }
    int st = EXIT_OK;
    for (int i = 0; st == EXIT_OK && i < n_sigma; ++i)
        st = add_param(job, cmd, sigma[i], JC_STUDY_NORMAL, &nominal, "--sigma");
    for (int i = 0; st == EXIT_OK && i < n_range; ++i)
        st = add_param(job, cmd, range[i], JC_STUDY_UNIFORM, &nominal, "--range");
    /* The defaults for the inputs the body has (a hoop has no rod), unless
     * the user spread or set them. */
    jc_StudyParam spreads[CLI_PARAM_MAX];
    const char *why[CLI_PARAM_MAX];
    const int n_defaults = no_defaults ? 0 : jc_study_default_spreads(&nominal, spreads, why, CLI_PARAM_MAX);
    for (int k = 0; st == EXIT_OK && k < n_defaults && k < CLI_PARAM_MAX; ++k) {
        if (user_owns(job, spreads[k].id)) continue;
        if (job->n == CLI_PARAM_MAX) {
            cli_error("%s: too many uncertain inputs (allowed: at most %d)", cmd, CLI_PARAM_MAX);
            return EXIT_USAGE;
        }
        cli_Param *p = &job->params[job->n];
        memset(p, 0, sizeof *p);
        cli_param_describe(spreads[k].id, p);
        p->kind = spreads[k].spread;
        p->a = spreads[k].a;
        p->b = spreads[k].b;
        p->text = jc_param_info(spreads[k].id)->name;
        job->why[job->n++] = why[k];
    }
    return st;
}

void cli_mc_study(jc_StudyDef *def, const cli_McJob *job, long samples, const jc_SimOptions *sim)
{
    cli_study_init(def, JC_STUDY_MONTE_CARLO, &job->base, &job->values, job->params, job->n, sim);
    def->samples = samples;
    def->seed = job->seed;
}

void cli_mc_consume(void *ctx, long index, const jc_CaseOutcome *o, const char *row, int row_len)
{
    (void)index;
    (void)row;
    (void)row_len;
    jc_tally_add(ctx, o); /* room for every sample was made first, or none is kept */
}

/* The library's cancellation: a stop signal. */
static int stop_asked(void *ctx, long done, long count)
{
    (void)ctx;
    (void)done;
    (void)count;
    return cli_stop_requested() != 0;
}

/* The samples' outcomes, and the invalid and failed ones for the note a
 * batch job ends with. */
typedef struct {
    jc_Tally *t;
    long invalid, failed, first_invalid;
} tally_ctx;

static int tally_row(void *ctx, const jc_StudyRow *row)
{
    tally_ctx *c = ctx;
    if (row->outcome->kind == JC_CASE_INVALID && c->invalid++ == 0) c->first_invalid = row->index;
    c->failed += row->outcome->kind == JC_CASE_FAILED;
    return jc_tally_add(c->t, row->outcome) == JC_OK ? 0 : 1;
}

int cli_mc_liftoff_stats(const char *cmd, const cli_SetupArgs *sa, double incline_deg, long samples, uint64_t seed,
                         jc_Stats *out, jc_Tally *counts)
{
    cli_SetupArgs args = *sa;
    char incline[32];
    snprintf(incline, sizeof incline, "%.17gdeg", incline_deg);
    args.value[jc_param_find("incline")] = incline;
    cli_McJob job;
    int st = cli_mc_job_init(&job, cmd, &args, NULL, 0, NULL, 0, 0, seed);
    if (st != EXIT_OK) return st;
    jc_Tally t;
    if ((st = jc_tally_init(&t, samples)) != JC_OK) {
        jc_tally_free(&t);
        cli_error("%s: out of memory", cmd);
        return cli_exit_status(st, CLI_INPUTS_CHECKED);
    }
    const jc_SimOptions sim = jc_default_sim_options();
    jc_StudyDef def;
    cli_mc_study(&def, &job, samples, &sim);
    tally_ctx c = {&t, 0, 0, -1};
    const jc_StudyCallbacks cb = {tally_row, stop_asked, &c, 0};
    char err[256];
    const int run = cli_stop_requested() ? JC_ESTOPPED : jc_study_run(&def, 0, samples, &cb, err, sizeof err);
    if (c.invalid > 0)
        cli_error("%s: %ld case(s) are not valid setups (first: case %ld)", cmd, c.invalid, c.first_invalid);
    if (c.failed > 0) cli_error("%s: %ld case(s) failed numerically", cmd, c.failed);
    st = cli_exit_status(run, CLI_INPUTS_CHECKED);
    if (st == EXIT_OK) jc_stats_compute(t.liftoff_x_m, t.liftoffs, t.none, t.invalid, JC_MC_LIFTOFF_GAP_M, out);
    else if (st == EXIT_FAIL) cli_error("%s: %s", cmd, err);
    if (counts) {
        *counts = t;
        counts->liftoff_x_m = counts->hop_m = NULL;
    }
    jc_tally_free(&t);
    return st;
}
