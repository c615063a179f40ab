/* One outcome's summary in bounded memory, for a Monte Carlo too large to
 * keep its values: the values are seen once, in the order given, and not
 * kept. Mean and sd by Welford's update; the 2.5, 50 and 97.5 % quantiles
 * estimated by the P² algorithm (GSL's gsl_rstat_quantile, one workspace
 * per quantile: five markers, whatever the count); the regions from cells
 * one gap wide, each holding its count, sum, lowest and highest value.
 *
 * The regions are the exact ones: no gap wider than a cell fits inside a
 * cell, so a region can only end between two occupied cells, where the
 * neighbours in sorted order are the lower cell's highest value and the
 * upper cell's lowest. The cells are at most JC_SKETCH_CELL_MAX (spread
 * over more, the regions are stated unavailable); a ramp of length L has
 * at most L / gap of them. */
#include "study_internal.h"

#include <gsl/gsl_rstat.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    long long key; /* floor(value / gap) */
    long count;    /* 0: the slot is free */
    double sum, lo, hi;
} cell;

struct jc_Sketch {
    double gap_m;
    long n;
    double mean, m2;
    gsl_rstat_quantile_workspace *q[3]; /* 2.5, 50, 97.5 % */
    cell *cells;                        /* open addressing, a power of two slots, at most half full */
    long slots, used;
    int cells_lost; /* more cells than JC_SKETCH_CELL_MAX, a value too far from 0, or no memory */
};

static const double quantile_p[3] = {0.025, 0.5, 0.975};

jc_Sketch *jc_sketch_alloc(double gap_m)
{
    jc_Sketch *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->gap_m = gap_m;
    s->slots = 256;
    s->cells = calloc((size_t)s->slots, sizeof *s->cells);
    int ok = s->cells != NULL;
    for (int k = 0; k < 3; ++k) ok = (s->q[k] = gsl_rstat_quantile_alloc(quantile_p[k])) != NULL && ok;
    if (!ok) {
        jc_sketch_free(s);
        return NULL;
    }
    return s;
}

void jc_sketch_free(jc_Sketch *s)
{
    if (!s) return;
    for (int k = 0; k < 3; ++k)
        if (s->q[k]) gsl_rstat_quantile_free(s->q[k]);
    free(s->cells);
    free(s);
}

static long slot_of(const cell *cells, long slots, long long key)
{
    unsigned long long h = (unsigned long long)key * 0x9E3779B97F4A7C15ull;
    long i = (long)(h >> 32) & (slots - 1);
    while (cells[i].count && cells[i].key != key) i = (i + 1) & (slots - 1);
    return i;
}

static void lose_cells(jc_Sketch *s)
{
    s->cells_lost = 1;
    free(s->cells);
    s->cells = NULL;
    s->slots = s->used = 0;
}

/* Twice the slots, the cells placed again; the cells lost without memory. */
static void grow_cells(jc_Sketch *s)
{
    const long slots = 2 * s->slots;
    cell *c = calloc((size_t)slots, sizeof *c);
    if (!c) {
        lose_cells(s);
        return;
    }
    for (long i = 0; i < s->slots; ++i)
        if (s->cells[i].count) c[slot_of(c, slots, s->cells[i].key)] = s->cells[i];
    free(s->cells);
    s->cells = c;
    s->slots = slots;
}

static void add_to_cell(jc_Sketch *s, double x)
{
    const double k = floor(x / s->gap_m);
    if (!(fabs(k) < 0x1p62)) {
        lose_cells(s);
        return;
    }
    cell *c = &s->cells[slot_of(s->cells, s->slots, (long long)k)];
    if (c->count == 0) {
        if (s->used == JC_SKETCH_CELL_MAX) {
            lose_cells(s);
            return;
        }
        *c = (cell){.key = (long long)k, .lo = x, .hi = x};
        s->used++;
    }
    c->count++;
    c->sum += x;
    c->lo = fmin(c->lo, x);
    c->hi = fmax(c->hi, x);
    if (2 * s->used > s->slots) grow_cells(s);
}

void jc_sketch_add(jc_Sketch *s, double x)
{
    s->n++;
    const double d = x - s->mean;
    s->mean += d / (double)s->n;
    s->m2 += d * (x - s->mean);
    for (int k = 0; k < 3; ++k) gsl_rstat_quantile_add(x, s->q[k]);
    if (!s->cells_lost) add_to_cell(s, x);
}

static int cmp_cell(const void *a, const void *b)
{
    const long long x = ((const cell *)a)->key, y = ((const cell *)b)->key;
    return (x > y) - (x < y);
}

/* The occupied cells in order of value, runs of them closer than the gap
 * merged into regions, as jc_stats_compute's sorted neighbours. 0, or -1
 * without memory for the copy. */
static int regions(const jc_Sketch *s, jc_Stats *out)
{
    cell *c = malloc((size_t)(s->used > 0 ? s->used : 1) * sizeof *c);
    if (!c) return -1;
    long n = 0;
    for (long i = 0; i < s->slots; ++i)
        if (s->cells[i].count) c[n++] = s->cells[i];
    qsort(c, (size_t)n, sizeof *c, cmp_cell);
    for (long i = 0; i < n;) {
        if (out->region_count == JC_STATS_REGION_MAX) {
            out->regions_truncated = 1;
            break;
        }
        jc_StatsRegion *r = &out->regions[out->region_count++];
        *r = (jc_StatsRegion){.lo_m = c[i].lo, .hi_m = c[i].hi};
        double sum = 0.0;
        long j = i;
        do {
            r->hi_m = c[j].hi;
            r->count += c[j].count;
            sum += c[j].sum;
            ++j;
        } while (j < n && c[j].lo - c[j - 1].hi <= s->gap_m);
        r->mean_m = sum / (double)r->count;
        i = j;
    }
    free(c);
    return 0;
}

void jc_sketch_stats(jc_Sketch *s, long none, long invalid, jc_Stats *out)
{
    *out = (jc_Stats){.n = s->n, .none = none, .invalid = invalid, .mean = NAN, .sd = NAN, .p2_5 = NAN,
                       .p50 = NAN, .p97_5 = NAN, .estimated = 1};
    if (s->n > 0) {
        out->mean = s->mean;
        out->sd = s->n > 1 ? sqrt(s->m2 / (double)(s->n - 1)) : 0.0;
        out->p2_5 = gsl_rstat_quantile_get(s->q[0]);
        out->p50 = gsl_rstat_quantile_get(s->q[1]);
        out->p97_5 = gsl_rstat_quantile_get(s->q[2]);
    }
    out->regions_unavailable = s->cells_lost || regions(s, out) != 0;
}
