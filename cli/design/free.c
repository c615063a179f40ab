/* design: the parameter --free NAME chooses, from the library's parameter
 * table (jumpcyl params): which rows design can free, and each one's
 * default range. A new numeric row of the table is a free parameter with
 * no change here. */
#include "design.h"

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

const char *cli_design_not_free(int id)
{
    const jc_ParamInfo *in = jc_param_info(id);
    if (!in) return "it is not a parameter";
    if (in->quantity == JC_Q_NAME) return "its values are names, not a range of numbers";
    for (size_t k = 0; k < INERT_COUNT; ++k)
        if (strcmp(in->name, inert[k].name) == 0) return inert[k].why;
    return NULL;
}

void cli_design_free_names(int refused, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int id = 0; id < jc_param_count() && used < len; ++id) {
        if ((cli_design_not_free(id) != NULL) != (refused != 0)) continue;
        const int w = snprintf(buf + used, len - used, "%s%s", used ? ", " : "", jc_param_info(id)->name);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* Whether name is one of the blank-separated names of list. */
static int in_list(const char *list, const char *name)
{
    const size_t n = strlen(name);
    for (const char *s = list; s && *s; s += strcspn(s, " "), s += strspn(s, " "))
        if (strncmp(s, name, n) == 0 && (s[n] == ' ' || s[n] == '\0')) return 1;
    return 0;
}

/* A setup option given that sets what the free one sets (mu and mu-s). */
static int clashing_option(int free_id, const cli_SetupArgs *sa)
{
    const jc_ParamInfo *f = jc_param_info(free_id);
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *g = jc_param_info(id);
        if (id != free_id && sa->value[id] && (in_list(f->sets, g->name) || in_list(g->sets, f->name))) return id;
    }
    return -1;
}

int cli_design_free_param(const char *name, const cli_SetupArgs *sa, cli_Param *p)
{
    const int id = jc_param_find(name);
    char allowed[512];
    cli_design_free_names(0, allowed, sizeof allowed);
    if (id < 0) {
        cli_error("design: --free '%s' is not a parameter design can choose (allowed: %s)", name, allowed);
        return EXIT_USAGE;
    }
    const char *why = cli_design_not_free(id);
    if (why) {
        cli_error("design: --free %s: %s (allowed: %s)", name, why, allowed);
        return EXIT_USAGE;
    }
    memset(p, 0, sizeof *p);
    cli_param_describe(id, p); /* column and unit: SI, angles in degrees */
    name = jc_param_info(id)->name;
    if (sa->value[id]) {
        cli_error("design: --%s and --free %s both given; give one (--range LO:HI bounds the search)", name, name);
        return EXIT_USAGE;
    }
    const int clash = clashing_option(id, sa);
    if (clash >= 0) {
        const char *given = jc_param_info(clash)->name;
        const int given_sets = in_list(jc_param_info(clash)->sets, name);
        cli_error("design: --%s and --free %s both given: %s sets %s too; give one", given, name,
                  given_sets ? given : name, given_sets ? name : given);
        return EXIT_USAGE;
    }
    if (strcmp(name, "radius") == 0 && sa->part_count > 0) {
        cli_error("design: --free radius with --part bodies: choose the radius of a preset body (paper, disc, hoop)");
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* ---- the default ranges ---- */

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
    *lo = -CLI_PI;
    *hi = CLI_PI;
}

static void incline_range(const body_facts *f, double *lo, double *hi)
{
    (void)f;
    *lo = CLI_PI / 180.0;
    *hi = 85.0 * CLI_PI / 180.0;
}

static void radius_range(const body_facts *f, double *lo, double *hi)
{
    *lo = fmax(1.01 * f->extent_m, 0.01 * f->radius_m);
    *hi = 3.0 * f->radius_m;
}

/* Ranges of their own, where the body sets what makes sense (or, for the
 * incline, the steep end the typical span stops short of); every other
 * row's default is its typical span. A row with a rod is only reached when
 * the body has one (jc_param_get answered). */
static const struct {
    const char *name;
    void (*range)(const body_facts *f, double *lo, double *hi);
    const char *note;
} own_range[] = {
    {"rod-offset", rod_offset_range, "1 % of r to the rim less the rod's radius"},
    {"rod-mass", rod_mass_range, "1 % to 5 times the rest of the body's mass"},
    {"theta0", whole_turn, "a whole turn"},
    {"incline", incline_range, "1 to 85 deg"},
    {"radius", radius_range, "just outside the off-centre parts to 3 times r"},
};
#define OWN_RANGE_COUNT (sizeof own_range / sizeof own_range[0])

/* Whether value v of the free parameter makes a valid setup with the job's other options. */
static int valid_at(const cli_DesignJob *job, double v)
{
    jc_Setup s;
    return cli_case_setup(&job->base, &job->values, &job->param, 1, &v, &s, NULL, 0) == 0;
}

/* An invalid end moved towards the valid value inside: the valid side of
 * the edge of validity, once the two sides are width apart. */
static double valid_end(const cli_DesignJob *job, double end, double inside, double width)
{
    double a = inside, b = end;
    for (int k = 0; k < VALID_BISECTIONS_MAX && fabs(b - a) > width; ++k) {
        const double mid = a + 0.5 * (b - a);
        if (mid == a || mid == b) break; /* adjacent doubles */
        if (valid_at(job, mid)) a = mid;
        else b = mid;
    }
    return a;
}

/* The row's typical span within its allowed range, its ends moved in to
 * valid setups (mu-k at most mu-s) towards the nominal value. */
static int typical_range(cli_DesignJob *job, double nominal, char *note, size_t note_len)
{
    const jc_ParamInfo *in = jc_param_info(job->param.id);
    job->lo = fmax(in->typical_min, in->min);
    job->hi = fmin(in->typical_max, in->max);
    const double width = VALID_REL_WIDTH * (job->hi - job->lo);
    int moved = 0;
    if (valid_at(job, nominal)) {
        if (!valid_at(job, job->lo)) {
            job->lo = valid_end(job, job->lo, nominal, width);
            moved = 1;
        }
        if (!valid_at(job, job->hi)) {
            job->hi = valid_end(job, job->hi, nominal, width);
            moved = 1;
        }
    }
    snprintf(note, note_len, "the default: its typical span ('jumpcyl params')%s",
             moved ? ", cut to valid setups" : "");
    if (!(job->hi > job->lo)) {
        cli_error("design: --free %s: no default range around its value (give --range LO:HI)", in->name);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

int cli_design_default_range(cli_DesignJob *job, char *note, size_t note_len)
{
    const char *name = jc_param_info(job->param.id)->name;
    double nominal;
    char err[256];
    if (jc_param_get(&job->nominal, job->param.id, &nominal, err, sizeof err) != JC_OK) {
        cli_error("design: --free %s: %s", name, err); /* a body without the part it sets */
        return EXIT_USAGE;
    }
    for (size_t k = 0; k < OWN_RANGE_COUNT; ++k)
        if (strcmp(name, own_range[k].name) == 0) {
            const body_facts f = facts_of(&job->nominal.body);
            own_range[k].range(&f, &job->lo, &job->hi);
            snprintf(note, note_len, "the default: %s", own_range[k].note);
            return EXIT_OK;
        }
    return typical_range(job, nominal, note, note_len);
}
