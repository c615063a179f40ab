/* The studies API (include/jumpcyl/study.h) against computations made here:
 * a grid's rows equal jc_case_run on setups built with jc_param_set by hand
 * and rows written with printf, for 1, 2 and 3 threads; a Monte Carlo
 * sample's values are Philox draws computed here (Random123 called
 * directly), redrawn while invalid, and the same for any range and thread
 * count; a run stops at the block or row its callbacks ask; statistics
 * against values worked by hand; the default spreads against the paper's
 * tolerances in SI; the design search's root against a bisection made
 * here, its sensitivity against a difference quotient, its edges against
 * runs on either side; the design's default ranges against values worked
 * here from the paper's cylinder, and the rows it refuses. */
#include "test.h"

#include <jumpcyl/jumpcyl.h>
#include <jumpcyl/study.h>

#include <Random123/philox.h>
#include <gsl/gsl_errno.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static int id_of(const char *name)
{
    const int id = jc_param_find(name);
    if (id < 0) {
        fprintf(stderr, "no parameter %s\n", name);
        exit(2);
    }
    return id;
}

/* ---- the outcome as a row, written here with printf ---- */

static void add(char *buf, size_t len, const char *fmt, double v)
{
    const size_t used = strlen(buf);
    snprintf(buf + used, len - used, fmt, v);
}

static void add_text(char *buf, size_t len, const char *s)
{
    const size_t used = strlen(buf);
    snprintf(buf + used, len - used, "%s", s);
}

static void state_fields(char *buf, size_t len, int index, const jc_State *s)
{
    if (index < 0) {
        add_text(buf, len, ",,,");
        return;
    }
    add(buf, len, ",%.12g", s->theta_rad);
    add(buf, len, ",%.12g", s->x_m);
    add(buf, len, ",%.12g", s->t_s);
}

/* The outcome's fields as docs/batch.md lists them, with printf. */
static void outcome_fields(const jc_CaseOutcome *o, char *buf, size_t len)
{
    buf[0] = '\0';
    if (o->kind == JC_CASE_INVALID || o->kind == JC_CASE_FAILED) {
        snprintf(buf, len, ",,,,,,,,,,%s,,,", o->kind == JC_CASE_INVALID ? "invalid_setup" : "failed");
        return;
    }
    const jc_RunSummary *s = &o->summary;
    add_text(buf, len, s->first_event >= 0 ? jc_event_name(s->first_event_kind) : "none");
    state_fields(buf, len, s->first_slip, &s->first_slip_state);
    state_fields(buf, len, s->first_liftoff, &s->first_liftoff_state);
    add(buf, len, ",%.0f", (double)s->liftoffs);
    add(buf, len, ",%.0f", (double)s->bounces);
    add(buf, len, ",%.12g", s->largest_hop >= 0 ? s->largest_hop_m : 0.0);
    add_text(buf, len, ",");
    add_text(buf, len, jc_termination_name(o->termination));
    add(buf, len, ",%.12g", o->end.x_m);
    add(buf, len, ",%.12g", o->end.t_s);
    add(buf, len, ",%.3g", o->energy_balance_error_J);
}

/* Two outcomes of the same run: the same to the bit. */
static int same_outcome(const jc_CaseOutcome *a, const jc_CaseOutcome *b)
{
    if (a->kind != b->kind) return 0;
    if (a->kind == JC_CASE_INVALID || a->kind == JC_CASE_FAILED) return 1;
    return memcmp(&a->liftoff_x_m, &b->liftoff_x_m, sizeof(double)) == 0 && a->largest_hop_m == b->largest_hop_m &&
           a->termination == b->termination && a->end.x_m == b->end.x_m && a->end.t_s == b->end.t_s &&
           a->end.theta_rad == b->end.theta_rad && a->summary.liftoffs == b->summary.liftoffs &&
           a->summary.bounces == b->summary.bounces &&
           a->energy_balance_error_J == b->energy_balance_error_J;
}

/* ---- collecting a run's rows ---- */

#define ROWS_MAX 1200

typedef struct {
    long first, count;
    long index[ROWS_MAX];
    double values[ROWS_MAX][JC_STUDY_PARAM_MAX];
    jc_CaseOutcome outcome[ROWS_MAX];
    char csv[ROWS_MAX][JC_STUDY_ROW_MAX];
    int in_order;
    long stop_at_row;   /* the row callback asks to stop at this many rows (0: never) */
    long stop_at_block; /* the progress callback asks to stop at this call (0: never) */
    long progress_calls;
} rows;

static int take_row(void *ctx, const jc_StudyRow *row)
{
    rows *r = ctx;
    if (r->count >= ROWS_MAX) return 1;
    if (row->index != r->first + r->count) r->in_order = 0;
    const long k = r->count++;
    r->index[k] = row->index;
    memcpy(r->values[k], row->values, JC_STUDY_PARAM_MAX * sizeof(double));
    r->outcome[k] = *row->outcome;
    snprintf(r->csv[k], JC_STUDY_ROW_MAX, "%s", row->csv ? row->csv : "");
    return r->stop_at_row > 0 && r->count >= r->stop_at_row;
}

static int take_progress(void *ctx, long done, long count)
{
    rows *r = ctx;
    (void)done;
    (void)count;
    ++r->progress_calls;
    return r->stop_at_block > 0 && r->progress_calls >= r->stop_at_block;
}

/* Cases [first, first + count) of the study on threads into r (appended). */
static int run_range(jc_StudyDef *def, int threads, long first, long count, rows *r, char *err)
{
    def->threads = threads;
    r->first = first;
    const long before = r->count;
    r->in_order = 1;
    r->first -= before; /* the row callback checks index == first + count */
    jc_StudyCallbacks cb = {take_row, take_progress, r, 1};
    return jc_study_run(def, first, count, &cb, err, 256);
}

static void rows_reset(rows *r)
{
    memset(r, 0, sizeof *r);
    r->in_order = 1;
}

/* ---- a grid against jc_param_set and jc_case_run by hand ---- */

static const double inclines_deg[6] = {10, 20, 30, 40, 50, 60};
static const double mus[3] = {0.3, 0.5, 1.0};

static void grid_def(jc_StudyDef *def)
{
    memset(def, 0, sizeof *def);
    def->kind = JC_STUDY_GRID;
    def->base = jc_paper_setup();
    static double incline_rad[6];
    for (int k = 0; k < 6; ++k) incline_rad[k] = inclines_deg[k] * DEG;
    def->params[0] = (jc_StudyParam){id_of("incline"), JC_STUDY_VALUES, incline_rad, 6, 0, 0};
    def->params[1] = (jc_StudyParam){id_of("mu"), JC_STUDY_VALUES, mus, 3, 0, 0};
    def->param_count = 2;
    def->sim = jc_default_sim_options();
}

static int test_grid_rows_against_case_run(void)
{
    static rows r;
    jc_StudyDef def;
    grid_def(&def);
    char err[256];
    char header[2 * JC_STUDY_ROW_MAX];
    jc_study_header(&def, header, sizeof header);
    ENSURE_MSG(strcmp(header, "case,incline_deg,mu,first_event,first_slip_theta_rad,first_slip_x_m,first_slip_t_s,"
                              "first_liftoff_theta_rad,first_liftoff_x_m,first_liftoff_t_s,liftoffs,bounces,"
                              "largest_hop_m,termination,end_x_m,end_t_s,energy_balance_error_J\n") == 0,
               "header %s", header);
    ENSURE(jc_study_case_count(&def) == 18);
    char first_csv[18][JC_STUDY_ROW_MAX];
    for (int threads = 1; threads <= 3; ++threads) {
        rows_reset(&r);
        ENSURE_OK(run_range(&def, threads, 0, 18, &r, err), err);
        ENSURE(r.count == 18 && r.in_order);
        for (long i = 0; i < 18; ++i) {
            /* By hand: the index taken apart, the last parameter fastest. */
            const double incline_deg = inclines_deg[i / 3], mu = mus[i % 3];
            jc_Setup s = jc_paper_setup();
            ENSURE_OK(jc_param_set(&s, id_of("incline"), incline_deg * DEG, err, sizeof err), err);
            ENSURE_OK(jc_param_set(&s, id_of("mu"), mu, err, sizeof err), err);
            ENSURE_OK(jc_setup_validate(&s, err, sizeof err), err);
            jc_CaseOutcome o;
            jc_case_run(&s, &def.sim, NULL, &o);
            ENSURE_MSG(same_outcome(&o, &r.outcome[i]), "case %ld on %d threads", i, threads);
            ENSURE(r.values[i][0] == incline_deg * DEG && r.values[i][1] == mu);
            char want[2 * JC_STUDY_ROW_MAX], fields[JC_STUDY_ROW_MAX];
            outcome_fields(&o, fields, sizeof fields);
            snprintf(want, sizeof want, "%ld,%.12g,%.12g,%s\n", i, incline_deg * DEG * (180.0 / PI), mu, fields);
            ENSURE_MSG(strcmp(want, r.csv[i]) == 0, "case %ld: printf '%s', the library '%s'", i, want, r.csv[i]);
            if (threads == 1) snprintf(first_csv[i], sizeof first_csv[i], "%s", r.csv[i]);
            ENSURE(strcmp(first_csv[i], r.csv[i]) == 0);
        }
    }
    /* Real runs: each lifts off, further down the ramp on a gentler incline. */
    for (long i = 0; i < 18; ++i) ENSURE(r.outcome[i].kind == JC_CASE_LIFTOFF);
    ENSURE(r.outcome[0].liftoff_x_m > r.outcome[15].liftoff_x_m);
    return 0;
}

/* The setup of a grid case equals the parameters set by hand in the table's
 * order (the body's first; the paper's printed d dropped when it changes). */
static int test_grid_setup_by_hand(void)
{
    static const double offsets[2] = {0.03, 0.05}, radii[2] = {0.09, 0.11};
    jc_StudyDef def;
    memset(&def, 0, sizeof def);
    def.kind = JC_STUDY_GRID;
    def.base = jc_paper_setup();
    def.fixed.given[id_of("rod-mass")] = 1;
    def.fixed.value[id_of("rod-mass")] = 0.040;
    def.fixed.given[id_of("restitution")] = 1;
    def.fixed.value[id_of("restitution")] = 0.45;
    def.params[0] = (jc_StudyParam){id_of("rod-offset"), JC_STUDY_VALUES, offsets, 2, 0, 0};
    def.params[1] = (jc_StudyParam){id_of("radius"), JC_STUDY_VALUES, radii, 2, 0, 0};
    def.param_count = 2;
    def.sim = jc_default_sim_options();
    char err[256];
    ENSURE_OK(jc_study_check(&def, err, sizeof err), err);
    for (long i = 0; i < 4; ++i) {
        double values[JC_STUDY_PARAM_MAX];
        jc_Setup got;
        ENSURE_OK(jc_study_case(&def, i, values, &got, err, sizeof err), err);
        jc_Setup want = jc_paper_setup();
        want.body.radius_m = radii[i % 2];
        want.body.parts[0].radius_m = radii[i % 2]; /* the paper's disc fills the rim */
        want.body.parts[1].mass_kg = 0.040;
        want.body.parts[1].offset_m = offsets[i / 2];
        want.paper_cm_offset_m = 0.0;
        want.restitution = 0.45;
        ENSURE(want.body.parts[0].kind == JC_PART_DISC && want.body.parts[1].kind == JC_PART_ROD);
        ENSURE(got.body.part_count == want.body.part_count);
        for (int p = 0; p < want.body.part_count; ++p) {
            ENSURE(got.body.parts[p].kind == want.body.parts[p].kind);
            ENSURE(got.body.parts[p].mass_kg == want.body.parts[p].mass_kg);
            ENSURE(got.body.parts[p].offset_m == want.body.parts[p].offset_m);
            ENSURE(got.body.parts[p].radius_m == want.body.parts[p].radius_m);
            ENSURE(got.body.parts[p].angle_rad == want.body.parts[p].angle_rad);
        }
        ENSURE(got.body.radius_m == want.body.radius_m && got.paper_cm_offset_m == 0.0);
        for (int id = 0; id < jc_param_count(); ++id) {
            double a, b;
            ENSURE_OK(jc_param_get(&got, id, &a, err, sizeof err), err);
            ENSURE_OK(jc_param_get(&want, id, &b, err, sizeof err), err);
            ENSURE_MSG(a == b, "case %ld: %s %.17g, by hand %.17g", i, jc_param_info(id)->name, a, b);
        }
    }
    /* The values that make no setup: named by the library, the setup refused. */
    jc_ParamValues v;
    memset(&v, 0, sizeof v);
    v.given[id_of("rod-mass")] = 1;
    v.value[id_of("rod-mass")] = 0.01;
    jc_Setup hoop;
    ENSURE_OK(jc_preset_setup("hoop", &hoop, err, sizeof err), err);
    int failed = -2;
    ENSURE(jc_param_values_apply(&v, &hoop, &failed, err, sizeof err) == JC_EINVAL && failed == id_of("rod-mass"));
    memset(&v, 0, sizeof v);
    v.given[id_of("mu-k")] = 1;
    v.value[id_of("mu-k")] = 0.9; /* above the paper's mu_s 0.5 */
    jc_Setup paper = jc_paper_setup();
    ENSURE(jc_param_values_apply(&v, &paper, &failed, err, sizeof err) == JC_EINVAL && failed == -1);
    return 0;
}

/* ---- Monte Carlo samples ---- */

/* Philox4x32-10 as the API documents its stream: key (seed), counter
 * (sample, draw, 0x6a63); 53 bits of the first two words; Box-Muller. */
static double philox_uniform_here(uint64_t seed, uint64_t sample, uint32_t draw, int second)
{
    const philox4x32_key_t key = {{(uint32_t)seed, (uint32_t)(seed >> 32)}};
    const philox4x32_ctr_t ctr = {{(uint32_t)sample, (uint32_t)(sample >> 32), draw, 0x6a63u}};
    const philox4x32_ctr_t r = philox4x32(ctr, key);
    const uint32_t hi = second ? r.v[2] : r.v[0], lo = second ? r.v[3] : r.v[1];
    return ((double)(((uint64_t)hi << 21) ^ (uint64_t)(lo >> 11)) + 0.5) / 9007199254740992.0;
}

static double philox_normal_here(uint64_t seed, uint64_t sample, uint32_t draw)
{
    const double u1 = philox_uniform_here(seed, sample, draw, 0), u2 = philox_uniform_here(seed, sample, draw, 1);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PI * u2);
}

static int test_philox(void)
{
    const long count = 200000;
    const double n = (double)count;
    double su = 0, su2 = 0, sn = 0, sn2 = 0;
    for (long i = 0; i < count; ++i) {
        const uint64_t seed = 0x123456789abcdefull + (uint64_t)(i % 7);
        const double u = jc_random_uniform(seed, (uint64_t)i << 20, (uint32_t)(i % 33));
        const double z = jc_random_normal(seed, (uint64_t)i, 5);
        ENSURE(u > 0.0 && u < 1.0);
        if (i % 97 == 0) {
            ENSURE(u == philox_uniform_here(seed, (uint64_t)i << 20, (uint32_t)(i % 33), 0));
            ENSURE(z == philox_normal_here(seed, (uint64_t)i, 5));
        }
        su += u;
        su2 += u * u;
        sn += z;
        sn2 += z * z;
    }
    /* Means within 5 standard errors; variances within 2 %. */
    ENSURE_NEAR(su / n, 0.5, 5.0 * sqrt(1.0 / 12.0 / n));
    ENSURE_NEAR(su2 / n - (su / n) * (su / n), 1.0 / 12.0, 0.02 / 12.0);
    ENSURE_NEAR(sn / n, 0.0, 5.0 / sqrt(n));
    ENSURE_NEAR(sn2 / n - (sn / n) * (sn / n), 1.0, 0.02);
    return 0;
}

/* The paper's cylinder at 15 deg with the default spreads, as `jumpcyl mc
 * --incline 15` makes it. */
static int mc_def(jc_StudyDef *def, long samples, uint64_t seed)
{
    memset(def, 0, sizeof *def);
    def->kind = JC_STUDY_MONTE_CARLO;
    def->base = jc_paper_setup();
    def->fixed.given[id_of("incline")] = 1;
    def->fixed.value[id_of("incline")] = 15 * DEG;
    jc_Setup nominal = def->base;
    nominal.incline_rad = 15 * DEG;
    def->param_count = jc_study_default_spreads(&nominal, def->params, NULL, JC_STUDY_PARAM_MAX);
    def->samples = samples;
    def->seed = seed;
    def->sim = jc_default_sim_options();
    return def->param_count;
}

static int test_mc_sample_independent_of_range_and_threads(void)
{
    static rows a, b;
    jc_StudyDef def;
    ENSURE(mc_def(&def, 300, 7) == 7);
    char err[256];
    rows_reset(&a);
    ENSURE_OK(run_range(&def, 1, 0, 300, &a, err), err);
    ENSURE(a.count == 300 && a.in_order);
    /* The same samples in other ranges and on other thread counts. */
    rows_reset(&b);
    ENSURE_OK(run_range(&def, 2, 120, 180, &b, err), err);
    ENSURE_OK(run_range(&def, 3, 0, 120, &b, err), err);
    ENSURE(b.count == 300);
    for (long k = 0; k < 300; ++k) {
        const long i = b.index[k];
        ENSURE(i >= 0 && i < 300 && a.index[i] == i);
        ENSURE(memcmp(a.values[i], b.values[k], (size_t)def.param_count * sizeof(double)) == 0);
        ENSURE_MSG(same_outcome(&a.outcome[i], &b.outcome[k]) && strcmp(a.csv[i], b.csv[k]) == 0, "sample %ld", i);
    }
    /* Sample i's values: the draws computed here (every sample of this
     * setup is valid at its first attempt: draw j for parameter j). */
    for (long i = 0; i < 300; ++i) {
        ENSURE(a.outcome[i].kind != JC_CASE_INVALID);
        for (int j = 0; j < def.param_count; ++j) {
            const jc_StudyParam *p = &def.params[j];
            const double want = p->spread == JC_STUDY_NORMAL
                                    ? p->a + p->b * philox_normal_here(7, (uint64_t)i, (uint32_t)j)
                                    : p->a + (p->b - p->a) * philox_uniform_here(7, (uint64_t)i, (uint32_t)j, 0);
            ENSURE_MSG(a.values[i][j] == want, "sample %ld, %s: %.17g, here %.17g", i, jc_param_info(p->id)->name,
                       a.values[i][j], want);
        }
    }
    /* The run's rows are jc_case_run of jc_study_case's setups. */
    for (long i = 0; i < 300; i += 37) {
        double values[JC_STUDY_PARAM_MAX];
        jc_Setup s;
        ENSURE_OK(jc_study_case(&def, i, values, &s, err, sizeof err), err);
        jc_CaseOutcome o;
        jc_case_run(&s, &def.sim, NULL, &o);
        ENSURE(same_outcome(&o, &a.outcome[i]));
    }
    return 0;
}

/* A sample whose draws make no valid setup is drawn again with the next
 * attempt's draws (attempt * 16 + j), up to 64 times. */
static int test_mc_attempts(void)
{
    jc_StudyDef def;
    memset(&def, 0, sizeof def);
    def.kind = JC_STUDY_MONTE_CARLO;
    def.base = jc_paper_setup();
    const int rod_mass = id_of("rod-mass");
    def.params[0] = (jc_StudyParam){rod_mass, JC_STUDY_NORMAL, NULL, 0, 0.0321, 0.05}; /* often negative */
    def.param_count = 1;
    def.samples = 200;
    def.seed = 11;
    def.sim = jc_default_sim_options();
    char err[256];
    int redrawn = 0;
    for (long i = 0; i < 200; ++i) {
        double want = NAN;
        int a = 0;
        for (; a < JC_STUDY_MC_ATTEMPTS; ++a) {
            want = 0.0321 + 0.05 * philox_normal_here(11, (uint64_t)i, (uint32_t)(a * JC_STUDY_PARAM_MAX));
            jc_Setup s = jc_paper_setup();
            if (jc_param_set(&s, rod_mass, want, NULL, 0) == JC_OK && jc_setup_validate(&s, NULL, 0) == JC_OK) break;
        }
        redrawn += a > 0;
        double got[JC_STUDY_PARAM_MAX];
        jc_Setup s;
        ENSURE_OK(jc_study_case(&def, i, got, &s, err, sizeof err), err);
        ENSURE_MSG(got[0] == want && s.body.parts[1].mass_kg == want, "sample %ld: %.17g, here %.17g (attempt %d)", i,
                   got[0], want, a);
    }
    ENSURE_MSG(redrawn > 40, "%d samples redrawn", redrawn); /* P(mass < 0) = 26 % */
    /* No valid draw at all: the sample is an invalid case. */
    def.params[0].a = -1.0;
    def.params[0].b = 1e-3;
    double v[JC_STUDY_PARAM_MAX];
    jc_Setup s;
    ENSURE(jc_study_case(&def, 3, v, &s, err, sizeof err) == JC_EINVAL);
    ENSURE(v[0] == -1.0 + 1e-3 * philox_normal_here(11, 3, (uint32_t)((JC_STUDY_MC_ATTEMPTS - 1) * JC_STUDY_PARAM_MAX)));
    static rows r;
    rows_reset(&r);
    ENSURE_OK(run_range(&def, 2, 3, 2, &r, err), err);
    ENSURE(r.count == 2 && r.outcome[0].kind == JC_CASE_INVALID && strstr(r.csv[0], ",invalid_setup,,,\n"));
    return 0;
}

/* ---- stopping ---- */

static int test_cancel(void)
{
    static double incline_rad[60], mu[10];
    for (int k = 0; k < 60; ++k) incline_rad[k] = (5 + 0.5 * k) * DEG;
    for (int k = 0; k < 10; ++k) mu[k] = 0.3 + 0.05 * k;
    jc_StudyDef def;
    memset(&def, 0, sizeof def);
    def.kind = JC_STUDY_GRID;
    def.base = jc_paper_setup();
    def.params[0] = (jc_StudyParam){id_of("incline"), JC_STUDY_VALUES, incline_rad, 60, 0, 0};
    def.params[1] = (jc_StudyParam){id_of("mu"), JC_STUDY_VALUES, mu, 10, 0, 0};
    def.param_count = 2;
    def.sim = jc_default_sim_options();
    char err[256];
    static rows r;
    /* The progress callback's stop: after the first block (256 cases a thread). */
    rows_reset(&r);
    r.stop_at_block = 1;
    ENSURE(run_range(&def, 1, 0, 600, &r, err) == JC_ESTOPPED);
    ENSURE_MSG(r.count == 256 && r.progress_calls == 1, "%ld rows, %ld progress calls", r.count, r.progress_calls);
    /* The row callback's: at once, no later row. */
    rows_reset(&r);
    r.stop_at_row = 10;
    ENSURE(run_range(&def, 2, 100, 500, &r, err) == JC_ESTOPPED);
    ENSURE(r.count == 10 && r.progress_calls == 0 && r.in_order && r.index[9] == 109);
    /* Asked after the last case: the range is done. */
    rows_reset(&r);
    r.stop_at_row = 5;
    ENSURE_OK(run_range(&def, 1, 595, 5, &r, err), err);
    /* A range outside the study's cases, a study the library refuses. */
    ENSURE(run_range(&def, 1, 590, 11, &r, err) == JC_EINVAL);
    def.params[1].spread = JC_STUDY_NORMAL;
    ENSURE(run_range(&def, 1, 0, 1, &r, err) == JC_EINVAL);
    return 0;
}

/* ---- statistics, the tally, the defaults, the columns ---- */

static int test_stats(void)
{
    double v[5] = {5, 1, 4, 2, 3};
    jc_Stats s;
    jc_stats_compute(v, 5, 2, 1, 10.0, &s);
    ENSURE(s.n == 5 && s.none == 2 && s.invalid == 1);
    ENSURE_NEAR(s.mean, 3.0, 1e-15);
    ENSURE_NEAR(s.sd, sqrt(2.5), 1e-15);
    ENSURE_NEAR(s.p50, 3.0, 1e-15);
    ENSURE_NEAR(s.p2_5, 1.0 + 0.025 * 4, 1e-15);   /* h = p (n - 1) = 0.1 */
    ENSURE_NEAR(s.p97_5, 4.0 + 0.9, 1e-15);        /* h = 3.9 */
    ENSURE(s.region_count == 1 && s.regions[0].count == 5);
    double w[6] = {0.50, 0.51, 1.40, 0.52, 1.41, 2.90};
    jc_stats_compute(w, 6, 0, 0, 0.02, &s);
    ENSURE(s.region_count == 3);
    ENSURE(s.regions[0].count == 3 && s.regions[0].lo_m == 0.50 && s.regions[0].hi_m == 0.52);
    ENSURE_NEAR(s.regions[0].mean_m, 0.51, 1e-15);
    ENSURE(s.regions[1].count == 2 && s.regions[2].count == 1 && s.regions[2].mean_m == 2.90);
    jc_stats_compute(w, 0, 4, 0, 0.02, &s);
    ENSURE(s.n == 0 && isnan(s.mean) && isnan(s.p50) && s.region_count == 0);
    ENSURE(isnan(jc_quantile(w, 0, 0.5)));

    jc_Tally t;
    ENSURE(jc_tally_init(&t, 1) == JC_OK);
    jc_CaseOutcome o;
    memset(&o, 0, sizeof o);
    const struct {
        jc_CaseKind kind;
        double x, hop;
    } cases[] = {{JC_CASE_LIFTOFF, 1.2, 0.03},      {JC_CASE_INVALID, NAN, 0},     {JC_CASE_NO_LIFTOFF, NAN, 0},
                 {JC_CASE_SLIDES_AT_START, NAN, 0}, {JC_CASE_SLIDES_AT_START, 2.5, 0.01}, {JC_CASE_FAILED, NAN, 0},
                 {JC_CASE_LIFTOFF, 1.3, 0.04}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        o.kind = cases[k].kind;
        o.liftoff_x_m = cases[k].x;
        o.largest_hop_m = cases[k].hop;
        ENSURE(jc_tally_add(&t, &o) == JC_OK);
    }
    ENSURE(t.valid == 5 && t.invalid == 2 && t.liftoffs == 3 && t.none == 2 && t.slides == 2);
    ENSURE(t.liftoff_x_m[0] == 1.2 && t.liftoff_x_m[1] == 2.5 && t.liftoff_x_m[2] == 1.3);
    ENSURE(t.hop_m[0] == 0.03 && t.hop_m[4] == 0.04 && t.cap >= 5);
    jc_tally_free(&t);
    ENSURE(t.liftoff_x_m == NULL && t.valid == 0);
    return 0;
}

/* ---- a tally past its bound: the values summarised in one pass ---- */

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The values given as lift-offs (hop x / 10) into a tally keeping at most
 * keep_max; its summaries. */
static int tally_of(const double *v, long n, long expected, long keep_max, jc_Stats *lift, jc_Stats *hop)
{
    jc_Tally t;
    ENSURE(jc_tally_init_bounded(&t, expected, keep_max, 0.02, 0.005) == JC_OK);
    jc_CaseOutcome o;
    memset(&o, 0, sizeof o);
    for (long i = 0; i < n; ++i) {
        o.kind = JC_CASE_LIFTOFF;
        o.liftoff_x_m = v[i];
        o.largest_hop_m = v[i] / 10;
        ENSURE(jc_tally_add(&t, &o) == JC_OK);
    }
    ENSURE(t.valid == n && (n <= keep_max) == (t.sketch == NULL) && (t.sketch == NULL) == (t.liftoff_x_m != NULL));
    jc_tally_stats(&t, lift, hop);
    jc_tally_free(&t);
    return 0;
}

/* The quantile of sorted values written here (R's type 7, as GSL's). */
static double quantile_here(const double *sorted, long n, double p)
{
    const double h = p * (double)(n - 1);
    const long i = (long)h;
    return i + 1 < n ? sorted[i] + (h - (double)i) * (sorted[i + 1] - sorted[i]) : sorted[n - 1];
}

/* The P² estimates against the exact quantiles of the same values: within
 * tol of the 2.5 .. 97.5 % range. Mean and sd to rounding, regions the
 * same. */
static int check_estimate(const char *what, double *v, long n, double tol)
{
    jc_Stats est, exact;
    ENSURE(tally_of(v, n, n, 1000, &est, NULL) == 0);
    ENSURE(est.estimated == 1 && est.regions_unavailable == 0 && est.n == n);
    double *sorted = malloc((size_t)n * sizeof *sorted);
    ENSURE(sorted != NULL);
    memcpy(sorted, v, (size_t)n * sizeof *v);
    qsort(sorted, (size_t)n, sizeof *sorted, cmp_double);
    const double p[3] = {0.025, 0.5, 0.975}, got[3] = {est.p2_5, est.p50, est.p97_5};
    const double range = quantile_here(sorted, n, 0.975) - quantile_here(sorted, n, 0.025);
    for (int k = 0; k < 3; ++k) {
        const double want = quantile_here(sorted, n, p[k]);
        printf("  %s: p %.3f exact %.6f estimate %.6f, off by %.2e of the 95 %% range\n", what, p[k], want, got[k],
               fabs(got[k] - want) / range);
        ENSURE_MSG(fabs(got[k] - want) <= tol * range, "%s p %.3f", what, p[k]);
    }
    jc_stats_compute(sorted, n, 0, 0, 0.02, &exact);
    ENSURE_REL(est.mean, exact.mean, 1e-12);
    ENSURE_REL(est.sd, exact.sd, 1e-9);
    ENSURE(est.region_count == exact.region_count && est.regions_truncated == exact.regions_truncated);
    for (int r = 0; r < exact.region_count; ++r) {
        ENSURE(est.regions[r].lo_m == exact.regions[r].lo_m && est.regions[r].hi_m == exact.regions[r].hi_m);
        ENSURE(est.regions[r].count == exact.regions[r].count);
        ENSURE_REL(est.regions[r].mean_m, exact.regions[r].mean_m, 1e-12);
    }
    free(sorted);
    return 0;
}

static int test_tally_bounded(void)
{
    const long n = 1000000;
    double *v = malloc((size_t)n * sizeof *v);
    ENSURE(v != NULL);
    uint64_t state = 7;
    /* A normal (Box-Muller), 10^6 values: the estimates within 0.2 % of
     * the 95 % range (3.92 sd). */
    for (long i = 0; i < n; i += 2) {
        const double u = test_uniform(&state, 1e-300, 1), w = test_uniform(&state, 0, 2 * PI);
        v[i] = 1.18 + 0.015 * sqrt(-2 * log(u)) * cos(w);
        v[i + 1] = 1.18 + 0.015 * sqrt(-2 * log(u)) * sin(w);
    }
    ENSURE(check_estimate("normal", v, n, 2e-3) == 0);
    /* Lift-offs in two windows of the ramp, 6 % in the earlier one (so the
     * 2.5 % point falls in it) and a skewed tail (an exponential). */
    for (long i = 0; i < n; ++i) {
        const double u = test_uniform(&state, 1e-300, 1);
        v[i] = i % 50 < 3 ? test_uniform(&state, 0.62, 0.65) : 1.15 - 0.01 * log(u);
    }
    ENSURE(check_estimate("two windows", v, n, 5e-3) == 0);

    /* The same values in the same order: the same summary whether the tally
     * switched on the way (expected 1) or began past its bound. */
    jc_Stats a, b, ha, hb;
    ENSURE(tally_of(v, 5000, 1, 1000, &a, &ha) == 0 && tally_of(v, 5000, 5000, 1000, &b, &hb) == 0);
    ENSURE(memcmp(&a, &b, sizeof a) == 0 && memcmp(&ha, &hb, sizeof ha) == 0);
    ENSURE(a.estimated == 1 && ha.estimated == 1 && ha.n == 5000 && a.region_count >= 2);
    /* Up to the bound, every value kept: jc_stats_compute's summary. */
    ENSURE(tally_of(v, 1000, 1000, 1000, &a, NULL) == 0);
    memcpy(v + n / 2, v, 1000 * sizeof *v);
    jc_stats_compute(v + n / 2, 1000, 0, 0, 0.02, &b);
    ENSURE(a.estimated == 0 && memcmp(&a, &b, sizeof a) == 0);
    /* Spread over more cells than JC_SKETCH_CELL_MAX: no regions. */
    for (long i = 0; i < 200000; ++i) v[i] = 0.02 * (double)i;
    ENSURE(tally_of(v, 200000, 200000, 10, &a, NULL) == 0);
    ENSURE(a.regions_unavailable == 1 && a.region_count == 0 && a.n == 200000);
    ENSURE_NEAR(a.p50, 0.02 * 99999.5, 0.02 * 200000 * 1e-3);
    /* A bound the tally refuses. */
    jc_Tally t;
    ENSURE(jc_tally_init_bounded(&t, 10, 0, 0.02, 0.005) == JC_EINVAL);
    ENSURE(jc_tally_init_bounded(&t, 10, 10, 0.0, 0.005) == JC_EINVAL);
    free(v);
    return 0;
}

static int test_default_spreads(void)
{
    jc_StudyParam p[JC_STUDY_PARAM_MAX];
    const char *why[JC_STUDY_PARAM_MAX];
    const jc_Setup paper = jc_paper_setup();
    ENSURE(jc_study_default_spreads(&paper, p, why, JC_STUDY_PARAM_MAX) == 7);
    const struct {
        const char *name;
        jc_StudySpread spread;
        double a, b;
    } want[7] = {{"radius", JC_STUDY_NORMAL, 0.100, 0.05e-2},     {"disc-mass", JC_STUDY_NORMAL, 0.0342, 0.05e-3},
                 {"rod-mass", JC_STUDY_NORMAL, 0.0321, 0.05e-3},  {"rod-offset", JC_STUDY_NORMAL, 0.055, 0.05e-2},
                 {"theta0", JC_STUDY_NORMAL, 0.0, 3 * DEG},       {"mu", JC_STUDY_UNIFORM, 0.3, 1.0},
                 {"restitution", JC_STUDY_UNIFORM, 0.1, 0.6}};
    for (int k = 0; k < 7; ++k) {
        ENSURE_MSG(p[k].id == id_of(want[k].name) && p[k].spread == want[k].spread, "spread %d", k);
        ENSURE_NEAR(p[k].a, want[k].a, 1e-15);
        ENSURE_NEAR(p[k].b, want[k].b, 1e-15);
        ENSURE(why[k] && *why[k]);
    }
    /* The nominal is the setup's own value; a body without a rod has no rod spreads. */
    jc_Setup s = paper;
    s.theta0_rad = 0.25;
    ENSURE(jc_study_default_spreads(&s, p, NULL, JC_STUDY_PARAM_MAX) == 7 && p[4].a == 0.25);
    jc_Setup hoop;
    char err[256];
    ENSURE_OK(jc_preset_setup("hoop", &hoop, err, sizeof err), err);
    const int n = jc_study_default_spreads(&hoop, p, NULL, JC_STUDY_PARAM_MAX);
    ENSURE_MSG(n == 4, "%d spreads for the hoop", n);
    ENSURE(p[0].id == id_of("radius") && p[1].id == id_of("theta0") && p[2].id == id_of("mu"));
    ENSURE(jc_study_default_spreads(&paper, p, NULL, 2) == 7); /* the count, whatever cap */
    return 0;
}

static int test_columns_and_invalid_case(void)
{
    ENSURE(jc_case_column_count() == JC_CASE_COLUMNS && jc_case_column(JC_CASE_COLUMNS) == NULL);
    for (int i = 0; i < JC_CASE_COLUMNS; ++i) {
        const jc_CaseColumn *c = jc_case_column(i);
        const size_t n = strlen(c->name), u = strlen(c->unit);
        /* A unit is the name's suffix. */
        ENSURE_MSG(u == 0 || (n > u + 1 && strcmp(c->name + n - u, c->unit) == 0 && c->name[n - u - 1] == '_'),
                   "column %s, unit %s", c->name, c->unit);
    }
    jc_CaseOutcome o;
    const jc_SimOptions sim = jc_default_sim_options();
    jc_case_run(NULL, &sim, NULL, &o);
    char buf[JC_STUDY_ROW_MAX];
    ENSURE(o.kind == JC_CASE_INVALID && isnan(o.liftoff_x_m) && o.largest_hop_m == 0.0);
    ENSURE(jc_case_format(&o, buf, sizeof buf) == (int)strlen(",,,,,,,,,,invalid_setup,,,"));
    ENSURE(strcmp(buf, ",,,,,,,,,,invalid_setup,,,") == 0);
    jc_Setup bad = jc_paper_setup();
    bad.restitution = 2.0;
    jc_case_run(&bad, &sim, NULL, &o);
    ENSURE(o.kind == JC_CASE_INVALID);
    ENSURE(strcmp(jc_case_kind_name(JC_CASE_SLIDES_AT_START), "slides_at_start") == 0);
    jc_StudyColumn c;
    ENSURE(jc_study_column(id_of("g"), &c) == JC_OK && strcmp(c.name, "g_mps2") == 0 && c.per_si == 1.0);
    ENSURE(jc_study_column(id_of("theta0"), &c) == JC_OK && strcmp(c.name, "theta0_deg") == 0);
    ENSURE_NEAR(c.per_si, 180.0 / PI, 1e-13);
    ENSURE(jc_study_column(id_of("impact-law"), &c) == JC_OK && strcmp(c.name, "impact_law") == 0 && !*c.unit);
    ENSURE(jc_study_column(-1, &c) == JC_EINVAL);
    /* A small buffer: cut, terminated. */
    jc_Setup s = jc_paper_setup();
    jc_case_run(&s, &sim, NULL, &o);
    char small[12];
    ENSURE(jc_case_format(&o, small, sizeof small) == 11 && strlen(small) == 11);
    return 0;
}

/* ---- design ---- */

/* x(p) for the paper's cylinder with rod-offset p, run here. */
static double liftoff_at(double p)
{
    jc_Setup s = jc_paper_setup();
    if (jc_param_set(&s, id_of("rod-offset"), p, NULL, 0) != JC_OK) return NAN;
    s.paper_cm_offset_m = 0.0; /* the body changed */
    const jc_SimOptions sim = jc_default_sim_options();
    jc_CaseOutcome o;
    jc_case_run(&s, &sim, NULL, &o);
    return o.liftoff_x_m;
}

static void design_def(jc_DesignDef *d, double lo, double hi, double target)
{
    memset(d, 0, sizeof *d);
    d->base = jc_paper_setup();
    d->free_id = id_of("rod-offset");
    d->lo = lo;
    d->hi = hi;
    d->target_x_m = target;
    d->points = 40;
    d->threads = 2;
    d->sim = jc_default_sim_options();
}

/* On a smooth branch the search finds the root a bisection finds here. */
static int test_design_smooth_branch(void)
{
    const double lo = 0.024, hi = 0.030, target = 1.20;
    jc_DesignDef d;
    design_def(&d, lo, hi, target);
    jc_DesignResult r;
    char err[256];
    ENSURE_OK(jc_design_run(&d, &r, err, sizeof err), err);
    ENSURE_MSG(r.edge_count == 0 && r.branch_count == 1 && r.solution_count == 1, "%d edges, %d solutions",
               r.edge_count, r.solution_count);
    ENSURE(r.scan_count == 40 && r.scan[0].p == lo && r.scan[39].p == hi && r.threads_used == 2);
    ENSURE(r.branches[0].kind == JC_CASE_LIFTOFF && r.branches[0].p_lo == lo && r.branches[0].p_hi == hi);
    /* The bisection, on runs made here. */
    double a = lo, b = hi;
    const double fa = liftoff_at(a) - target;
    ENSURE(fa * (liftoff_at(b) - target) < 0);
    for (int k = 0; k < 100 && b - a > 1e-15; ++k) {
        const double m = 0.5 * (a + b), fm = liftoff_at(m) - target;
        if ((fm < 0) == (fa < 0)) a = m;
        else b = m;
    }
    const jc_DesignSolution *s = &r.solutions[0];
    /* dX/dp against a difference quotient here (1e-6 of the range each side). */
    const double h = 1e-6 * (hi - lo);
    const double slope = (liftoff_at(s->p + h) - liftoff_at(s->p - h)) / (2 * h);
    ENSURE_REL(s->dxdp, slope, 1e-6);
    /* The roots agree within what |x - X| <= JC_DESIGN_ROOT_M allows. */
    ENSURE_NEAR(s->p, 0.5 * (a + b), 2 * JC_DESIGN_ROOT_M / fabs(slope) + 1e-15);
    ENSURE_NEAR(s->x_m, target, JC_DESIGN_VERIFY_M);
    ENSURE_NEAR(liftoff_at(s->p), s->x_m, 0.0); /* run again here: the same run */
    ENSURE(isinf(s->edge_margin) && s->branch == 0 && r.unverified == 0 && r.at_edge == 0);
    ENSURE(r.evaluations > 40);
    jc_design_free(&r);
    ENSURE(r.scan == NULL && r.solutions == NULL);
    return 0;
}

/* Across leaps: each located edge has lift-offs a leap apart on its sides,
 * as runs here show, and they lie within the edge width. */
static int test_design_edges(void)
{
    jc_DesignDef d;
    design_def(&d, 0.010, 0.030, 1.20);
    d.points = 200;
    jc_DesignResult r;
    char err[256];
    ENSURE_OK(jc_design_run(&d, &r, err, sizeof err), err);
    ENSURE_MSG(r.edge_count == 2 && r.branch_count == 3, "%d edges", r.edge_count);
    ENSURE_NEAR(r.edge_width, 0.020 * 1e-12, 1e-20);
    for (int k = 0; k < r.edge_count; ++k) {
        const jc_DesignEdge *e = &r.edges[k];
        ENSURE(e->hi.p > e->lo.p && e->hi.p - e->lo.p <= r.edge_width);
        const double below = liftoff_at(e->lo.p), above = liftoff_at(e->hi.p);
        ENSURE(below == e->lo.x_m && above == e->hi.x_m);
        ENSURE_MSG(below - above > 0.3, "edge %d: %.6f -> %.6f m", k, below, above);
        ENSURE(r.branches[k].p_hi == e->lo.p && r.branches[k + 1].p_lo == e->hi.p);
    }
    /* X = 1.20 m lies on the last branch only; its margin is its distance to the leap. */
    ENSURE(r.solution_count == 1 && r.solutions[0].branch == 2);
    ENSURE(r.solutions[0].edge_margin == r.solutions[0].p - r.edges[1].hi.p);
    double lo[8], hi[8];
    const int n = jc_design_reachable(&r, lo, hi, 8);
    ENSURE(n == 3 && lo[0] < hi[0] && hi[0] < lo[1] && hi[1] < lo[2]);
    jc_design_free(&r);
    return 0;
}

static int stop_at_once(void *ctx, const jc_DesignProgress *p)
{
    int *calls = ctx;
    ++*calls;
    return strcmp(p->stage, "scan") == 0;
}

static int test_design_stop_and_bad_input(void)
{
    jc_DesignDef d;
    design_def(&d, 0.024, 0.030, 1.20);
    d.points = 1000;
    int calls = 0;
    d.progress = stop_at_once;
    d.progress_ctx = &calls;
    jc_DesignResult r;
    char err[256];
    ENSURE(jc_design_run(&d, &r, err, sizeof err) == JC_ESTOPPED && calls == 1 && r.solution_count == 0);
    jc_design_free(&r);
    design_def(&d, 0.030, 0.024, 1.20);
    ENSURE(jc_design_run(&d, &r, err, sizeof err) == JC_EINVAL);
    jc_design_free(&r);
    design_def(&d, 0.024, 0.2, 1.20); /* a rod outside the rim at the end */
    ENSURE(jc_design_run(&d, &r, err, sizeof err) == JC_EINVAL && strstr(err, "rod-offset"));
    jc_design_free(&r);
    design_def(&d, 0.024, 0.030, 1.20);
    d.free_id = id_of("impact-law");
    ENSURE(jc_design_run(&d, &r, err, sizeof err) == JC_EINVAL);
    jc_design_free(&r);
    return 0;
}

/* ---- design's free parameter and default range ---- */

/* def over setup base (fixed empty) with free row name, its range by default. */
static int default_range(const char *name, const jc_Setup *base, const jc_ParamValues *fixed, jc_DesignDef *d,
                         const char **rule, char *err, size_t err_len)
{
    memset(d, 0, sizeof *d);
    d->base = *base;
    if (fixed) d->fixed = *fixed;
    d->free_id = id_of(name);
    d->lo = d->hi = -1.0; /* untouched unless JC_OK */
    return jc_design_default_range(d, rule, err, err_len);
}

/* The ranges of their own, worked here from the paper's cylinder as it
 * prints it: r = 10 cm, a disc of 34.2 g filling the rim, a rod of 32.1 g
 * of radius 0.475 cm at 5.5 cm. */
static int test_design_default_ranges_of_their_own(void)
{
    const jc_Setup paper = jc_paper_setup();
    const double r = 0.10, disc_kg = 0.0342, rod_r = 0.00475, rod_offset = 0.055;
    const struct {
        const char *name;
        double lo, hi;
        const char *rule;
    } own[] = {
        {"rod-offset", 0.01 * r, r - rod_r, "1 % of r to the rim less the rod's radius"},
        {"rod-mass", 0.01 * disc_kg, 5 * disc_kg, "1 % to 5 times the rest of the body's mass"},
        {"theta0", -PI, PI, "a whole turn"},
        {"incline", 1 * DEG, 85 * DEG, "1 to 85 deg"},
        {"radius", 1.01 * (rod_offset + rod_r), 3 * r, "just outside the off-centre parts to 3 times r"},
    };
    for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) {
        jc_DesignDef d;
        const char *rule = ""; /* stays empty unless written */
        char err[256];
        ENSURE_OK(default_range(own[k].name, &paper, NULL, &d, &rule, err, sizeof err), err);
        const int near = fabs(d.lo - own[k].lo) <= 1e-15 * fabs(own[k].lo) &&
                         fabs(d.hi - own[k].hi) <= 1e-15 * fabs(own[k].hi);
        ENSURE_MSG(near, "%s: %.17g .. %.17g, worked %.17g .. %.17g", own[k].name, d.lo, d.hi, own[k].lo, own[k].hi);
        ENSURE_MSG(strcmp(rule, own[k].rule) == 0, "%s: '%s'", own[k].name, rule);
        ENSURE_OK(jc_design_free_check(d.free_id, &paper, NULL, err, sizeof err), err);
    }
    return 0;
}

/* The other rows: the typical span, an end that is no valid setup moved in
 * to within 1e-9 of the span of the edge of validity. */
static int test_design_default_typical_spans(void)
{
    const jc_Setup paper = jc_paper_setup();
    jc_DesignDef d;
    const char *rule = "";
    char err[256];
    const jc_ParamInfo *in = jc_param_info(id_of("omega0"));
    ENSURE_OK(default_range("omega0", &paper, NULL, &d, &rule, err, sizeof err), err);
    ENSURE(d.lo == in->typical_min && d.hi == in->typical_max && strcmp(rule, JC_DESIGN_RANGE_TYPICAL) == 0);
    /* mu-k at most mu-s: the paper's 0.5 (its nominal value, exactly), then mu-s 0.8 given. */
    in = jc_param_info(id_of("mu-k"));
    const double span = in->typical_max - in->typical_min;
    ENSURE_OK(default_range("mu-k", &paper, NULL, &d, &rule, err, sizeof err), err);
    ENSURE(d.lo == in->typical_min && d.hi == 0.5);
    ENSURE(strcmp(rule, JC_DESIGN_RANGE_TYPICAL ", cut to valid setups") == 0);
    jc_ParamValues fixed;
    memset(&fixed, 0, sizeof fixed);
    fixed.given[id_of("mu-s")] = 1;
    fixed.value[id_of("mu-s")] = 0.8;
    ENSURE_OK(default_range("mu-k", &paper, &fixed, &d, &rule, err, sizeof err), err);
    ENSURE_MSG(d.hi <= 0.8 && d.hi >= 0.8 - 1e-9 * span, "hi %.17g", d.hi);
    /* air-density with drag: above 0 (an open edge), within 1e-9 of the span. */
    in = jc_param_info(id_of("air-density"));
    memset(&fixed, 0, sizeof fixed);
    fixed.given[id_of("drag-coefficient")] = 1;
    fixed.value[id_of("drag-coefficient")] = 1.0;
    ENSURE_OK(default_range("air-density", &paper, &fixed, &d, &rule, err, sizeof err), err);
    ENSURE_MSG(d.lo > 0 && d.lo <= 1e-9 * (in->typical_max - in->typical_min) && d.hi == in->typical_max,
               "%.17g .. %.17g", d.lo, d.hi);
    /* Without drag every density is valid: the span as it is. */
    ENSURE_OK(default_range("air-density", &paper, NULL, &d, &rule, err, sizeof err), err);
    ENSURE(d.lo == in->typical_min && strcmp(rule, JC_DESIGN_RANGE_TYPICAL) == 0);
    return 0;
}

/* The rows design refuses, and setups without a default range. */
static int test_design_refused_rows(void)
{
    const jc_Setup paper = jc_paper_setup();
    char err[256];
    const char *rule = "";
    jc_DesignDef d;
    const char *refused[] = {"restitution", "ramp-length", "paper-d", "impact-law"};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; ++k) {
        char head[64];
        snprintf(head, sizeof head, "%s: ", refused[k]);
        ENSURE(jc_design_free_check(id_of(refused[k]), NULL, NULL, err, sizeof err) == JC_EINVAL);
        ENSURE_MSG(strncmp(err, head, strlen(head)) == 0 && strchr(err, '\n') == NULL, "%s", err);
        ENSURE(default_range(refused[k], &paper, NULL, &d, &rule, err, sizeof err) == JC_EINVAL);
        ENSURE(d.lo == -1.0 && d.hi == -1.0);
    }
    ENSURE(jc_design_free_check(-1, NULL, NULL, err, sizeof err) == JC_EINVAL);
    ENSURE(jc_design_free_check(jc_param_count(), NULL, NULL, err, sizeof err) == JC_EINVAL);
    /* Every other numeric row is free (a row added to the table too). */
    for (int id = 0; id < jc_param_count(); ++id) {
        int is_refused = jc_param_info(id)->quantity == JC_Q_NAME;
        for (size_t k = 0; k < sizeof refused / sizeof refused[0]; ++k)
            is_refused |= strcmp(jc_param_info(id)->name, refused[k]) == 0;
        ENSURE_MSG((jc_design_free_check(id, NULL, NULL, NULL, 0) == JC_OK) == !is_refused, "%s",
                   jc_param_info(id)->name);
    }
    /* A hoop has no rod to move or weigh. */
    jc_Setup hoop;
    ENSURE_OK(jc_preset_setup("hoop", &hoop, err, sizeof err), err);
    ENSURE(jc_design_free_check(id_of("rod-offset"), NULL, NULL, err, sizeof err) == JC_OK);
    ENSURE(jc_design_free_check(id_of("rod-offset"), &hoop, NULL, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "rod-offset needs a body with a rod part"), "%s", err);
    ENSURE(default_range("rod-mass", &hoop, NULL, &d, &rule, err, sizeof err) == JC_EINVAL && d.lo == -1.0);
    /* radius over a body given part by part. */
    jc_ParamValues parts;
    memset(&parts, 0, sizeof parts);
    parts.parts_given = 1;
    ENSURE(jc_design_free_check(id_of("radius"), NULL, &parts, err, sizeof err) == JC_EINVAL);
    ENSURE(jc_design_free_check(id_of("rod-offset"), &paper, &parts, err, sizeof err) == JC_OK);
    /* A value given for the free row, or for a row that sets it (mu sets
     * mu-s and mu-k) or that it sets, would be replaced by the search's. */
    jc_ParamValues given;
    memset(&given, 0, sizeof given);
    given.given[id_of("rod-offset")] = 1;
    ENSURE(jc_design_free_check(id_of("rod-offset"), &paper, &given, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "rod-offset: given a value and free"), "%s", err);
    ENSURE(jc_design_free_check(id_of("mu-s"), &paper, &given, err, sizeof err) == JC_OK);
    memset(&given, 0, sizeof given);
    given.given[id_of("mu")] = 1;
    ENSURE(jc_design_free_check(id_of("mu-k"), NULL, &given, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "mu-k: mu is given too, and mu sets mu-k"), "%s", err);
    memset(&given, 0, sizeof given);
    given.given[id_of("mu-s")] = 1;
    ENSURE(jc_design_free_check(id_of("mu"), NULL, &given, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strstr(err, "mu: mu-s is given too, and mu sets mu-s"), "%s", err);
    ENSURE(jc_design_free_check(id_of("radius"), NULL, &given, err, sizeof err) == JC_OK);
    /* mu-s = mu-k = 0: mu-k has no valid value but 0, so no range. */
    jc_Setup still = paper;
    ENSURE_OK(jc_param_set(&still, id_of("mu"), 0.0, err, sizeof err), err);
    ENSURE(default_range("mu-k", &still, NULL, &d, &rule, err, sizeof err) == JC_EINVAL);
    ENSURE_MSG(strcmp(err, "mu-k: no default range around its value") == 0 && d.lo == -1.0, "%s", err);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_grid_rows_against_case_run);
    RUN_TEST(test_grid_setup_by_hand);
    RUN_TEST(test_philox);
    RUN_TEST(test_mc_sample_independent_of_range_and_threads);
    RUN_TEST(test_mc_attempts);
    RUN_TEST(test_cancel);
    RUN_TEST(test_stats);
    RUN_TEST(test_tally_bounded);
    RUN_TEST(test_default_spreads);
    RUN_TEST(test_columns_and_invalid_case);
    RUN_TEST(test_design_smooth_branch);
    RUN_TEST(test_design_edges);
    RUN_TEST(test_design_stop_and_bad_input);
    RUN_TEST(test_design_default_ranges_of_their_own);
    RUN_TEST(test_design_default_typical_spans);
    RUN_TEST(test_design_refused_rows);
    TEST_MAIN_END();
}
