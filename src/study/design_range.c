/* The design search's free parameter, chosen from the parameter table:
 * which rows design can free, and each one's default range over a setup
 * (docs/design.md, "Which options can be free"). A new numeric row of the
 * table is a free parameter, its typical span the default range, with no
 * change here. */
#include "study_internal.h"

#include <math.h>
#include <string.h>

/* Rows that never move the first lift-off, and why: a search over them
 * could only ever find x constant. (Name-valued rows are refused too: their
 * values are not a range.) */
static const struct {
    const char *name, *why;
} inert[] = {
    {"restitution", "it acts at impacts, which all come after the first lift-off"},
    {"ramp-length", "it decides whether the first lift-off is on the ramp, never where"},
    {"paper-d", "only the paper's model uses it, not the simulation"},
};
#define INERT_COUNT (sizeof inert / sizeof inert[0])

/* An end of the typical span that is no valid setup is moved towards the
 * nominal value by bisection, to within this fraction of the span of the
 * edge of validity (an open edge, density > 0 with drag, is never reached),
 * at most VALID_BISECTIONS_MAX times. */
#define VALID_REL_WIDTH 1e-9
#define VALID_BISECTIONS_MAX 200

/* The setup with every value of fixed but the free one's. */
static int nominal_of(int free_id, const jc_Setup *base, const jc_ParamValues *fixed, jc_Setup *out, char *err,
                      size_t err_len)
{
    jc_ParamValues v;
    if (fixed) v = *fixed;
    else memset(&v, 0, sizeof v);
    v.given[free_id] = 0;
    *out = *base;
    return jc_param_values_apply(&v, out, NULL, err, err_len);
}

/* A value given for the free row, or for a row that sets it or that it
 * sets (mu and mu-s), would be silently replaced by the search's: refused. */
static int clash_check(const jc_ParamInfo *in, int free_id, const jc_ParamValues *fixed, char *err, size_t err_len)
{
    if (!fixed) return JC_OK;
    if (fixed->given[free_id])
        return jc_fail(err, err_len, JC_EINVAL, "%s: given a value and free; give one (a range bounds the search)",
                       in->name);
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *g = jc_param_info(id);
        const int given_sets = jc_param_sets(id, free_id);
        if (!fixed->given[id] || !(given_sets || jc_param_sets(free_id, id))) continue;
        return jc_fail(err, err_len, JC_EINVAL, "%s: %s is given too, and %s sets %s; give one", in->name, g->name,
                       given_sets ? g->name : in->name, given_sets ? in->name : g->name);
    }
    return JC_OK;
}

int jc_design_free_check(int free_id, const jc_Setup *base, const jc_ParamValues *fixed, char *err, size_t err_len)
{
    int st;
    const jc_ParamInfo *in = jc_param_info(free_id);
    if (!in)
        return jc_fail(err, err_len, JC_EINVAL, "no parameter number %d (allowed: 0 to %d)", free_id,
                       jc_param_count() - 1);
    if (in->quantity == JC_Q_NAME)
        return jc_fail(err, err_len, JC_EINVAL, "%s: its values are names, not a range of numbers", in->name);
    for (size_t k = 0; k < INERT_COUNT; ++k)
        if (strcmp(in->name, inert[k].name) == 0)
            return jc_fail(err, err_len, JC_EINVAL, "%s: %s", in->name, inert[k].why);
    /* Over a body given part by part radius moves only the rim, which the
     * range of its own (the parts growing with a rim they fill) does not
     * describe. */
    if (fixed && fixed->parts_given && strcmp(in->name, "radius") == 0)
        return jc_fail(err, err_len, JC_EINVAL,
                       "radius: the body is given part by part (allowed: the radius of a preset body)");
    if ((st = clash_check(in, free_id, fixed, err, err_len)) != JC_OK) return st;
    if (!base) return JC_OK;
    jc_Setup nominal;
    char why[256];
    if (nominal_of(free_id, base, fixed, &nominal, why, sizeof why) != JC_OK)
        return jc_fail(err, err_len, JC_EINVAL, "%s: the setup without it is not valid: %s", in->name, why);
    double value;
    return jc_param_get(&nominal, free_id, &value, err, err_len); /* a body without the part it sets */
}

/* ---- the ranges of their own ---- */

/* What the body-aware ranges are made of. */
typedef struct {
    double radius_m;
    const jc_Part *rod; /* the body's first rod, or NULL */
    double rest_kg;     /* the mass of everything but that rod */
    double extent_m;    /* how far the parts that do not fill the rim reach from the axis */
} body_facts;

static body_facts facts_of(const jc_BodyDef *b)
{
    body_facts f = {b->radius_m, NULL, 0.0, 0.0};
    for (int i = 0; i < b->part_count; ++i) {
        const jc_Part *p = &b->parts[i];
        if (p->kind == JC_PART_ROD && !f.rod) f.rod = p;
        else f.rest_kg += p->mass_kg;
        /* Parts that fill the rim grow with it; the others set the smallest radius. */
        const int fills_rim = (p->kind == JC_PART_DISC || p->kind == JC_PART_HOOP) && p->radius_m == b->radius_m;
        if (!fills_rim) f.extent_m = fmax(f.extent_m, p->offset_m + p->radius_m);
    }
    return f;
}

static void rod_offset_range(const body_facts *f, double *lo, double *hi)
{
    *lo = 0.01 * f->radius_m;
    *hi = f->radius_m - f->rod->radius_m;
}

static void rod_mass_range(const body_facts *f, double *lo, double *hi)
{
    *lo = 0.01 * f->rest_kg;
    *hi = 5.0 * f->rest_kg;
}

static void whole_turn(const body_facts *f, double *lo, double *hi)
{
    (void)f;
    *lo = -JC_STUDY_PI;
    *hi = JC_STUDY_PI;
}

static void incline_range(const body_facts *f, double *lo, double *hi)
{
    (void)f;
    *lo = JC_STUDY_PI / 180.0;
    *hi = 85.0 * JC_STUDY_PI / 180.0;
}

static void radius_range(const body_facts *f, double *lo, double *hi)
{
    *lo = fmax(1.01 * f->extent_m, 0.01 * f->radius_m);
    *hi = 3.0 * f->radius_m;
}

/* Ranges of their own, where the body sets what makes sense (or, for the
 * incline, the steep end the typical span stops short of); every other
 * row's default is its typical span. A row with a rod is only reached when
 * the body has one (jc_design_free_check). */
static const struct {
    const char *name;
    void (*range)(const body_facts *f, double *lo, double *hi);
    const char *rule;
} own_range[] = {
    {"rod-offset", rod_offset_range, "1 % of r to the rim less the rod's radius"},
    {"rod-mass", rod_mass_range, "1 % to 5 times the rest of the body's mass"},
    {"theta0", whole_turn, "a whole turn"},
    {"incline", incline_range, "1 to 85 deg"},
    {"radius", radius_range, "just outside the off-centre parts to 3 times r"},
};
#define OWN_RANGE_COUNT (sizeof own_range / sizeof own_range[0])

/* ---- the typical span, cut to valid setups ---- */

/* Whether value v of the free parameter makes a valid setup with def's other values. */
static int valid_at(const jc_DesignDef *def, double v)
{
    jc_ParamValues values = def->fixed;
    values.given[def->free_id] = 1;
    values.value[def->free_id] = v;
    jc_Setup s = def->base;
    return jc_param_values_apply(&values, &s, NULL, NULL, 0) == JC_OK;
}

/* An invalid end moved towards the valid value inside: the valid side of
 * the edge of validity, once the two sides are width apart. */
static double valid_end(const jc_DesignDef *def, double end, double inside, double width)
{
    double a = inside, b = end;
    for (int k = 0; k < VALID_BISECTIONS_MAX && fabs(b - a) > width; ++k) {
        const double mid = a + 0.5 * (b - a);
        if (mid == a || mid == b) break; /* adjacent doubles */
        if (valid_at(def, mid)) a = mid;
        else b = mid;
    }
    return a;
}

/* The row's typical span within its allowed range, its ends moved in to
 * valid setups (mu-k at most mu-s) towards the nominal value; *cut: whether
 * an end moved. */
static void typical_range(const jc_DesignDef *def, double nominal, double *lo, double *hi, int *cut)
{
    const jc_ParamInfo *in = jc_param_info(def->free_id);
    *lo = fmax(in->typical_min, in->min);
    *hi = fmin(in->typical_max, in->max);
    const double width = VALID_REL_WIDTH * (*hi - *lo);
    *cut = 0;
    if (!valid_at(def, nominal)) return;
    if (!valid_at(def, *lo)) {
        *lo = valid_end(def, *lo, nominal, width);
        *cut = 1;
    }
    if (!valid_at(def, *hi)) {
        *hi = valid_end(def, *hi, nominal, width);
        *cut = 1;
    }
}

int jc_design_default_range(jc_DesignDef *def, const char **rule, char *err, size_t err_len)
{
    const int checked = jc_design_free_check(def->free_id, &def->base, &def->fixed, err, err_len);
    if (checked != JC_OK) return checked;
    const jc_ParamInfo *in = jc_param_info(def->free_id);
    jc_Setup nominal;
    double value;
    nominal_of(def->free_id, &def->base, &def->fixed, &nominal, NULL, 0); /* valid: checked */
    jc_param_get(&nominal, def->free_id, &value, NULL, 0);
    for (size_t k = 0; k < OWN_RANGE_COUNT; ++k)
        if (strcmp(in->name, own_range[k].name) == 0) {
            const body_facts f = facts_of(&nominal.body);
            own_range[k].range(&f, &def->lo, &def->hi);
            if (rule) *rule = own_range[k].rule;
            return JC_OK;
        }
    double lo, hi;
    int cut;
    typical_range(def, value, &lo, &hi, &cut);
    if (!(hi > lo)) return jc_fail(err, err_len, JC_EINVAL, "%s: no default range around its value", in->name);
    def->lo = lo;
    def->hi = hi;
    if (rule) *rule = cut ? JC_DESIGN_RANGE_TYPICAL ", cut to valid setups" : JC_DESIGN_RANGE_TYPICAL;
    return JC_OK;
}
