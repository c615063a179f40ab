/* The distribution of an outcome over Monte Carlo samples: moments,
 * percentiles, and the separate regions its values fall in (a first
 * lift-off can happen in one of several windows of the ramp); and the
 * tally that gathers the outcomes case by case. */
#include "study_internal.h"

#include <math.h>
#include <limits.h>
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

/* Room for cap values in both arrays; JC_OK or JC_ENOMEM (t unchanged). */
static int grow(jc_Tally *t, long cap)
{
    double *a = realloc(t->liftoff_x_m, (size_t)cap * sizeof *a);
    if (!a) return JC_ENOMEM;
    t->liftoff_x_m = a;
    double *b = realloc(t->hop_m, (size_t)cap * sizeof *b);
    if (!b) return JC_ENOMEM;
    t->hop_m = b;
    t->cap = cap;
    return JC_OK;
}

int jc_tally_init(jc_Tally *t, long expected)
{
    memset(t, 0, sizeof *t);
    return grow(t, expected > 0 ? expected : 1);
}

int jc_tally_add(jc_Tally *t, const jc_CaseOutcome *o)
{
    if (o->kind == JC_CASE_INVALID || o->kind == JC_CASE_FAILED) {
        t->invalid++;
        return JC_OK;
    }
    if (t->valid >= t->cap && (t->cap > LONG_MAX / 2 || grow(t, 2 * t->cap) != JC_OK)) return JC_ENOMEM;
    t->hop_m[t->valid++] = o->largest_hop_m;
    if (o->kind == JC_CASE_SLIDES_AT_START) t->slides++;
    if (!isnan(o->liftoff_x_m)) t->liftoff_x_m[t->liftoffs++] = o->liftoff_x_m;
    else t->none++;
    return JC_OK;
}

void jc_tally_free(jc_Tally *t)
{
    free(t->liftoff_x_m);
    free(t->hop_m);
    memset(t, 0, sizeof *t);
}
