/* The distribution of an outcome over Monte Carlo samples: moments,
 * percentiles, and the separate regions its values fall in (a first
 * lift-off can happen in one of several windows of the ramp). */
#include "batch.h"

#include <math.h>
#include <stdlib.h>

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cli_quantile(const double *v, long n, double p)
{
    if (n <= 0) return NAN;
    const double h = p * (double)(n - 1);
    const long i = (long)floor(h);
    if (i >= n - 1) return v[n - 1];
    return v[i] + (h - (double)i) * (v[i + 1] - v[i]);
}

void cli_stats_compute(double *v, long n, long none, long invalid, double gap_m, cli_Stats *out)
{
    *out = (cli_Stats){.n = n, .none = none, .invalid = invalid, .mean = NAN, .sd = NAN,
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
    out->p2_5 = cli_quantile(v, n, 0.025);
    out->p50 = cli_quantile(v, n, 0.5);
    out->p97_5 = cli_quantile(v, n, 0.975);
    long start = 0;
    for (long i = 1; i <= n; ++i) {
        if (i < n && v[i] - v[i - 1] <= gap_m) continue;
        if (out->region_count == CLI_REGION_MAX) {
            out->regions_truncated = 1;
            break;
        }
        cli_Region *r = &out->regions[out->region_count++];
        r->lo_m = v[start];
        r->hi_m = v[i - 1];
        r->count = i - start;
        double s = 0.0;
        for (long k = start; k < i; ++k) s += v[k];
        r->mean_m = s / (double)r->count;
        start = i;
    }
}
