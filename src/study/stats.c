/* The distribution of an outcome over Monte Carlo samples: moments,
 * percentiles, and the separate regions its values fall in (a first
 * lift-off can happen in one of several windows of the ramp); and the
 * tally that gathers the outcomes case by case, keeping them up to its
 * bound and summarising them in one pass past it (sketch.c). */
#include "study_internal.h"

#include <math.h>
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double jc_quantile(const double *v, long n, double p)
{
    if (n <= 0) return NAN;
    const double h = p * (double)(n - 1);
    const long i = (long)floor(h);
    if (i >= n - 1) return v[n - 1];
    return v[i] + (h - (double)i) * (v[i + 1] - v[i]);
}

void jc_stats_compute(double *v, long n, long none, long invalid, double gap_m, jc_Stats *out)
{
    *out = (jc_Stats){.n = n, .none = none, .invalid = invalid, .mean = NAN, .sd = NAN,
                       .p2_5 = NAN, .p50 = NAN, .p97_5 = NAN};
    if (n <= 0) return;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    /* Welford's update: one pass, no cancellation for a narrow spread. */
    double mean = 0.0, m2 = 0.0;
    for (long i = 0; i < n; ++i) {
        const double d = v[i] - mean;
        mean += d / (double)(i + 1);
        m2 += d * (v[i] - mean);
    }
    out->mean = mean;
    out->sd = n > 1 ? sqrt(m2 / (double)(n - 1)) : 0.0;
    out->p2_5 = jc_quantile(v, n, 0.025);
    out->p50 = jc_quantile(v, n, 0.5);
    out->p97_5 = jc_quantile(v, n, 0.975);
    long start = 0;
    for (long i = 1; i <= n; ++i) {
        if (i < n && v[i] - v[i - 1] <= gap_m) continue;
        if (out->region_count == JC_STATS_REGION_MAX) {
            out->regions_truncated = 1;
            break;
        }
        jc_StatsRegion *r = &out->regions[out->region_count++];
        r->lo_m = v[start];
        r->hi_m = v[i - 1];
        r->count = i - start;
        double s = 0.0;
        for (long k = start; k < i; ++k) s += v[k];
        r->mean_m = s / (double)r->count;
        start = i;
    }
}

/* ---- the tally ---- */

struct jc_TallySketch {
    jc_Sketch *liftoff, *hop;
};

static void sketch_free(jc_TallySketch *k)
{
    if (!k) return;
    jc_sketch_free(k->liftoff);
    jc_sketch_free(k->hop);
    free(k);
}

static jc_TallySketch *sketch_alloc(const jc_Tally *t)
{
    jc_TallySketch *k = calloc(1, sizeof *k);
    if (!k) return NULL;
    k->liftoff = jc_sketch_alloc(t->liftoff_gap_m);
    k->hop = jc_sketch_alloc(t->hop_gap_m);
    if (!k->liftoff || !k->hop) {
        sketch_free(k);
        return NULL;
    }
    return k;
}

/* Room for cap values in both arrays; JC_OK or JC_ENOMEM (t unchanged). */
static int grow(jc_Tally *t, long cap)
{
    if ((unsigned long)cap > SIZE_MAX / sizeof(double)) return JC_ENOMEM;
    double *a = realloc(t->liftoff_x_m, (size_t)cap * sizeof *a);
    if (!a) return JC_ENOMEM;
    t->liftoff_x_m = a;
    double *b = realloc(t->hop_m, (size_t)cap * sizeof *b);
    if (!b) return JC_ENOMEM;
    t->hop_m = b;
    t->cap = cap;
    return JC_OK;
}

/* Past keep_max: the kept values into the one-pass summaries in their
 * order, and no longer kept. JC_OK or JC_ENOMEM (t unchanged). */
static int stop_keeping(jc_Tally *t)
{
    jc_TallySketch *k = sketch_alloc(t);
    if (!k) return JC_ENOMEM;
    for (long i = 0; i < t->liftoffs; ++i) jc_sketch_add(k->liftoff, t->liftoff_x_m[i]);
    for (long i = 0; i < t->valid; ++i) jc_sketch_add(k->hop, t->hop_m[i]);
    free(t->liftoff_x_m);
    free(t->hop_m);
    t->liftoff_x_m = t->hop_m = NULL;
    t->cap = 0;
    t->sketch = k;
    return JC_OK;
}

int jc_tally_init_bounded(jc_Tally *t, long expected, long keep_max, double liftoff_gap_m, double hop_gap_m)
{
    memset(t, 0, sizeof *t);
    if (keep_max < 1 || !(liftoff_gap_m > 0 && liftoff_gap_m <= DBL_MAX) || !(hop_gap_m > 0 && hop_gap_m <= DBL_MAX))
        return JC_EINVAL;
    t->keep_max = keep_max;
    t->liftoff_gap_m = liftoff_gap_m;
    t->hop_gap_m = hop_gap_m;
    if (expected > keep_max) return (t->sketch = sketch_alloc(t)) ? JC_OK : JC_ENOMEM;
    return grow(t, expected > 0 ? expected : 1);
}

int jc_tally_init(jc_Tally *t, long expected)
{
    return jc_tally_init_bounded(t, expected, LONG_MAX, JC_MC_LIFTOFF_GAP_M, JC_MC_HOP_GAP_M);
}

/* The valid case's values: into the one-pass summaries past keep_max,
 * else kept. JC_OK or JC_ENOMEM (nothing added). */
static int add_values(jc_Tally *t, double liftoff_x_m, double hop_m)
{
    if (!t->sketch && t->valid >= t->keep_max && stop_keeping(t) != JC_OK) return JC_ENOMEM;
    if (t->sketch) {
        jc_sketch_add(t->sketch->hop, hop_m);
        if (!isnan(liftoff_x_m)) jc_sketch_add(t->sketch->liftoff, liftoff_x_m);
        return JC_OK;
    }
    if (t->valid >= t->cap) {
        const long cap = t->cap > t->keep_max / 2 ? t->keep_max : 2 * t->cap;
        if (grow(t, cap) != JC_OK) return JC_ENOMEM;
    }
    t->hop_m[t->valid] = hop_m;
    if (!isnan(liftoff_x_m)) t->liftoff_x_m[t->liftoffs] = liftoff_x_m;
    return JC_OK;
}

int jc_tally_add(jc_Tally *t, const jc_CaseOutcome *o)
{
    if (o->kind == JC_CASE_INVALID || o->kind == JC_CASE_FAILED) {
        t->invalid++;
        return JC_OK;
    }
    if (add_values(t, o->liftoff_x_m, o->largest_hop_m) != JC_OK) return JC_ENOMEM;
    t->valid++;
    if (o->kind == JC_CASE_SLIDES_AT_START) t->slides++;
    if (!isnan(o->liftoff_x_m)) t->liftoffs++;
    else t->none++;
    return JC_OK;
}

void jc_tally_stats(jc_Tally *t, jc_Stats *liftoff, jc_Stats *hop)
{
    if (t->sketch) {
        if (liftoff) jc_sketch_stats(t->sketch->liftoff, t->none, t->invalid, liftoff);
        if (hop) jc_sketch_stats(t->sketch->hop, 0, t->invalid, hop);
        return;
    }
    if (liftoff) jc_stats_compute(t->liftoff_x_m, t->liftoffs, t->none, t->invalid, t->liftoff_gap_m, liftoff);
    if (hop) jc_stats_compute(t->hop_m, t->valid, 0, t->invalid, t->hop_gap_m, hop);
}

void jc_tally_free(jc_Tally *t)
{
    free(t->liftoff_x_m);
    free(t->hop_m);
    sketch_free(t->sketch);
    memset(t, 0, sizeof *t);
}
