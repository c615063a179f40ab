/* Monte Carlo samples: each uncertain setup option is drawn, per sample,
 * from a normal (--sigma) or a uniform (--range) spread with Philox numbers
 * keyed by (seed, sample, draw), so that sample i is the same on any thread,
 * shard or rank. */
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The default spreads. The paper states its tolerances (docs/physics.md
 * §5.1): r, masses and the rod's offset to the last digit it printed
 * (± 0.05 cm, ± 0.05 g), the initial angle to about ± 3 degrees; each is
 * taken as one standard deviation of a normal. It did not measure friction
 * or restitution: Styrofoam on wood lies between mu 0.3 and 1.0 for any
 * surface finish, and a foam cylinder on a wooden ramp bounces with e
 * between 0.1 and 0.6, so both are uniform over those ranges. */
static const struct {
    const char *spread;
    cli_ParamKind kind;
    const char *why;
} defaults[] = {
    {"radius=0.05cm", PARAM_NORMAL, "paper: r +- 0.05 cm"},
    {"disc-mass=0.05g", PARAM_NORMAL, "paper: masses +- 0.05 g"},
    {"rod-mass=0.05g", PARAM_NORMAL, "paper: masses +- 0.05 g"},
    {"rod-offset=0.05cm", PARAM_NORMAL, "paper: offset +- 0.05 cm"},
    {"theta0=3", PARAM_NORMAL, "paper: initial angle about +- 3 deg"},
    {"mu=0.3:1.0", PARAM_UNIFORM, "not measured: foam on wood"},
    {"restitution=0.1:0.6", PARAM_UNIFORM, "not measured: foam on wood"},
};

static int add_param(cli_McJob *job, const char *cmd, const char *text, cli_ParamKind kind, const jc_Setup *nominal,
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
        st = add_param(job, cmd, sigma[i], PARAM_NORMAL, &nominal, "--sigma");
    for (int i = 0; st == EXIT_OK && i < n_range; ++i)
        st = add_param(job, cmd, range[i], PARAM_UNIFORM, &nominal, "--range");
    for (size_t k = 0; st == EXIT_OK && !no_defaults && k < sizeof defaults / sizeof defaults[0]; ++k) {
        char name[32];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(defaults[k].spread, "="), defaults[k].spread);
        const int id = jc_param_find(name);
        /* A body without the part (a hoop) has no such input. */
        if (user_owns(job, id) || isnan(cli_param_nominal(id, &nominal))) continue;
        st = add_param(job, cmd, defaults[k].spread, defaults[k].kind, &nominal, defaults[k].why);
    }
    return st;
}

/* The sample's values, attempt a: draw number a * CLI_PARAM_MAX + j for input j. */
static void draw(const cli_McJob *job, long index, int a, double *values)
{
    for (int j = 0; j < job->n; ++j) {
        const cli_Param *p = &job->params[j];
        const uint32_t d = (uint32_t)(a * CLI_PARAM_MAX + j);
        if (p->kind == PARAM_NORMAL)
            values[j] = p->b > 0 ? p->a + p->b * cli_random_normal(job->seed, (uint64_t)index, d) : p->a;
        else
            values[j] = p->a + (p->b - p->a) * cli_random_uniform(job->seed, (uint64_t)index, d);
    }
}

int cli_mc_make_case(const void *ctx, long index, char *inputs, size_t len, jc_Setup *setup, char *why,
                     size_t why_len)
{
    const cli_McJob *job = ctx;
    double values[CLI_PARAM_MAX];
    int st = -1;
    for (int a = 0; a < CLI_MC_ATTEMPTS && st != 0; ++a) {
        draw(job, index, a, values);
        st = cli_case_setup(&job->base, &job->values, job->params, job->n, values, setup, why, why_len);
    }
    cli_param_columns(job->params, job->n, values, inputs, len);
    return st;
}

int cli_mc_tally_init(cli_McTally *t, long samples)
{
    memset(t, 0, sizeof *t);
    t->cap = samples > 0 ? samples : 1;
    t->liftoff_x_m = malloc((size_t)t->cap * sizeof *t->liftoff_x_m);
    t->hop_m = malloc((size_t)t->cap * sizeof *t->hop_m);
    return t->liftoff_x_m && t->hop_m ? 0 : -1;
}

void cli_mc_tally_free(cli_McTally *t)
{
    free(t->liftoff_x_m);
    free(t->hop_m);
    t->liftoff_x_m = t->hop_m = NULL;
}

void cli_mc_consume(void *ctx, long index, const cli_CaseResult *r)
{
    (void)index;
    cli_McTally *t = ctx;
    if (r->kind == CASE_INVALID || r->kind == CASE_FAILED) {
        t->invalid++;
        return;
    }
    if (t->valid >= t->cap) {
        t->out_of_memory = 1;
        return;
    }
    t->hop_m[t->valid++] = r->largest_hop_m;
    if (r->kind == CASE_SLIDES_AT_START) t->slides++;
    if (!isnan(r->liftoff_x_m)) t->liftoff_x_m[t->liftoffs++] = r->liftoff_x_m;
    else t->none++;
}

void cli_mc_batch(cli_Batch *b, const cli_McJob *job, cli_McTally *tally, long samples, const jc_SimOptions *sim)
{
    b->total = samples;
    b->input_columns = job->n;
    b->sim = sim;
    b->make_case = cli_mc_make_case;
    b->ctx = job;
    b->consume = cli_mc_consume;
    b->consume_ctx = tally;
}

int cli_mc_liftoff_stats(const char *cmd, const cli_SetupArgs *sa, double incline_deg, long samples, uint64_t seed,
                         cli_Stats *out, cli_McTally *tally_out)
{
    cli_SetupArgs args = *sa;
    char incline[32];
    snprintf(incline, sizeof incline, "%.17gdeg", incline_deg);
    args.value[jc_param_find("incline")] = incline;
    cli_McJob job;
    int st = cli_mc_job_init(&job, cmd, &args, NULL, 0, NULL, 0, 0, seed);
    if (st != EXIT_OK) return st;
    cli_McTally t;
    if (cli_mc_tally_init(&t, samples) != 0) {
        cli_mc_tally_free(&t);
        cli_error("%s: out of memory", cmd);
        return EXIT_FAIL;
    }
    const jc_SimOptions sim = jc_default_sim_options();
    cli_Batch b;
    memset(&b, 0, sizeof b);
    b.cmd = cmd;
    b.shard = (cli_Shard){1, 1};
    b.quiet = 1;
    cli_mc_batch(&b, &job, &t, samples, &sim);
    st = cli_batch_run(&b);
    if (st == EXIT_OK) cli_stats_compute(t.liftoff_x_m, t.liftoffs, t.none, t.invalid, 0.02, out);
    if (tally_out) {
        tally_out->liftoffs = t.liftoffs;
        tally_out->valid = t.valid;
        tally_out->none = t.none;
        tally_out->invalid = t.invalid;
    }
    cli_mc_tally_free(&t);
    return st;
}
