/* src/param.c and src/units.c through the public API: the parameter table
 * enumerated row by row. For each row: the value it reads in each preset
 * against the setup's field read here directly; set and get round trips;
 * a value with units against this file's own SI arithmetic; its text in its
 * unit read back exactly; its range refusing the values just outside and
 * taking those just inside, leaving the setup unchanged on a refusal. And
 * what the table promises: names found in both spellings, sections and
 * keys unique, the body parameters' semantics. */
#include "test.h"
#include "same_setup.h"

#include <jumpcyl/jumpcyl.h>

#include <float.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

/* ---- this file's own view of a setup ---- */

/* The body's first part of a kind, or NULL. */
static const jc_Part *first_of(const jc_Setup *s, jc_PartKind kind)
{
    for (int i = 0; i < s->body.part_count; ++i)
        if (s->body.parts[i].kind == kind) return &s->body.parts[i];
    return NULL;
}

/* The field a parameter names, read from the struct here (not through the
 * library); 0 when the setup has none (no rod). Every row of the table must
 * be known here: a new parameter needs its line. */
static int field_of(const char *name, const jc_Setup *s, double *v, int *known)
{
    const jc_Part *disc = first_of(s, JC_PART_DISC), *rod = first_of(s, JC_PART_ROD);
    *known = 1;
    if (strcmp(name, "radius") == 0) *v = s->body.radius_m;
    else if (strcmp(name, "disc-mass") == 0) { if (!disc) return 0; *v = disc->mass_kg; }
    else if (strcmp(name, "rod-mass") == 0) { if (!rod) return 0; *v = rod->mass_kg; }
    else if (strcmp(name, "rod-offset") == 0) { if (!rod) return 0; *v = rod->offset_m; }
    else if (strcmp(name, "rod-radius") == 0) { if (!rod) return 0; *v = rod->radius_m; }
    else if (strcmp(name, "incline") == 0) *v = s->incline_rad;
    else if (strcmp(name, "g") == 0) *v = s->gravity_mps2;
    else if (strcmp(name, "mu") == 0) *v = s->mu_static;
    else if (strcmp(name, "mu-s") == 0) *v = s->mu_static;
    else if (strcmp(name, "mu-k") == 0) *v = s->mu_kinetic;
    else if (strcmp(name, "restitution") == 0) *v = s->restitution;
    else if (strcmp(name, "impact-law") == 0) *v = (double)s->impact_law;
    else if (strcmp(name, "theta0") == 0) *v = s->theta0_rad;
    else if (strcmp(name, "omega0") == 0) *v = s->omega0_radps;
    else if (strcmp(name, "ramp-length") == 0) *v = s->ramp_length_m;
    else if (strcmp(name, "length") == 0) *v = s->length_m;
    else if (strcmp(name, "air-density") == 0) *v = s->air_density_kgpm3;
    else if (strcmp(name, "drag-coefficient") == 0) *v = s->drag_coefficient;
    else if (strcmp(name, "lift-coefficient") == 0) *v = s->lift_coefficient;
    else if (strcmp(name, "spin-drag") == 0) *v = s->spin_drag_Nms2;
    else if (strcmp(name, "rolling-resistance") == 0) *v = s->rolling_resistance_m;
    else if (strcmp(name, "paper-d") == 0) *v = s->paper_cm_offset_m;
    else *known = 0;
    return *known;
}

/* SI per unit, written here from the units' definitions. */
static int si_per(const char *unit, double *f)
{
    static const struct { const char *unit; double si; } units[] = {
        {"", 1.0},        {"m", 1.0},       {"cm", 0.01},     {"mm", 0.001},   {"km", 1000.0},
        {"kg", 1.0},      {"g", 0.001},     {"mg", 1e-6},     {"rad", 1.0},    {"deg", PI / 180.0},
        {"rad/s", 1.0},   {"deg/s", PI / 180.0}, {"rpm", 2.0 * PI / 60.0}, {"rev/s", 2.0 * PI},
        {"m/s2", 1.0},    {"m/s^2", 1.0},   {"cm/s2", 0.01},  {"s", 1.0},      {"ms", 0.001},
        {"us", 1e-6},     {"kg/m3", 1.0},   {"kg/m^3", 1.0},  {"g/cm3", 1000.0}, {"N m s2", 1.0},
        {"kg m2", 1.0},
    };
    for (size_t k = 0; k < sizeof units / sizeof units[0]; ++k)
        if (strcmp(unit, units[k].unit) == 0) {
            *f = units[k].si;
            return 1;
        }
    return 0;
}

/* ---- the table ---- */

static int test_table_is_whole(void)
{
    const int n = jc_param_count();
    ENSURE(n >= 22 && n <= JC_PARAM_MAX);
    ENSURE(jc_param_info(-1) == NULL && jc_param_info(n) == NULL);
    ENSURE(jc_param_find("no-such-thing") == -1 && jc_param_find(NULL) == -1 && jc_param_find("") == -1);
    /* every option the command line had before the table: each is a row */
    const char *names[] = {"radius", "disc-mass", "rod-mass", "rod-offset", "rod-radius", "incline", "g", "mu",
                           "mu-s", "mu-k", "restitution", "impact-law", "theta0", "omega0", "ramp-length",
                           "paper-d", "length", "air-density", "drag-coefficient", "lift-coefficient",
                           "spin-drag", "rolling-resistance"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) ENSURE_MSG(jc_param_find(names[k]) >= 0, "%s", names[k]);
    for (int id = 0; id < n; ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        ENSURE(in && in->name && in->label && in->help && in->section && in->key && in->unit && in->si_unit);
        ENSURE_MSG(jc_param_find(in->name) == id, "%s", in->name);
        char underscored[64];
        snprintf(underscored, sizeof underscored, "%s", in->name);
        for (char *c = underscored; *c; ++c)
            if (*c == '-') *c = '_';
        ENSURE_MSG(jc_param_find(underscored) == id, "%s", underscored);
        ENSURE_MSG(strcmp(in->si_unit, jc_quantity_si_unit(in->quantity)) == 0, "%s", in->name);
        ENSURE_MSG(!strchr(in->help, '\n') && strlen(in->help) < 200, "%s: one line", in->name);
        ENSURE_MSG(in->typical_min < in->typical_max, "%s", in->name);
        ENSURE_MSG((in->quantity == JC_Q_NAME) == (in->choices != NULL), "%s", in->name);
        ENSURE_MSG(((in->flags & JC_PARAM_SHORTCUT) != 0) || in->sets == NULL, "%s", in->name);
        for (int other = 0; other < id; ++other) {
            const jc_ParamInfo *o = jc_param_info(other);
            ENSURE_MSG(strcmp(o->name, in->name) != 0, "%s twice", in->name);
            ENSURE_MSG(strcmp(o->section, in->section) != 0 || strcmp(o->key, in->key) != 0, "[%s] %s twice",
                       in->section, in->key);
            ENSURE_MSG(!o->json_key || !in->json_key || strcmp(o->json_key, in->json_key) != 0, "%s twice",
                       in->json_key);
        }
        /* the display unit is one of the quantity's */
        int found = in->quantity == JC_Q_NUMBER || in->quantity == JC_Q_NAME;
        for (int k = 0; jc_quantity_unit(in->quantity, k, NULL); ++k)
            found |= strcmp(jc_quantity_unit(in->quantity, k, NULL), in->unit) == 0;
        ENSURE_MSG(found, "%s: unit '%s'", in->name, in->unit);
    }
    return 0;
}

/* Every preset's value of every row is the setup's own field. */
static int test_presets_read_their_fields(void)
{
    for (int k = 0; jc_preset_name(k); ++k) {
        jc_Setup s;
        char err[256];
        ENSURE_OK(jc_preset_setup(jc_preset_name(k), &s, err, sizeof err), err);
        for (int id = 0; id < jc_param_count(); ++id) {
            const char *name = jc_param_info(id)->name;
            double want = NAN, got = NAN;
            int known;
            const int has = field_of(name, &s, &want, &known);
            ENSURE_MSG(known, "row %s has no line in field_of(): a new parameter needs one", name);
            const int st = jc_param_get(&s, id, &got, err, sizeof err);
            ENSURE_MSG((st == JC_OK) == has, "%s of %s: %d (%s)", name, jc_preset_name(k), st, err);
            if (has) ENSURE_MSG(got == want, "%s of %s: %.17g, the field %.17g", name, jc_preset_name(k), got, want);
            else ENSURE_MSG(strstr(err, name) != NULL, "%s of %s: '%s'", name, jc_preset_name(k), err);
        }
    }
    return 0;
}

/* A value inside a row's range, away from its ends, for the paper's setup. */
static double inside_value(const jc_ParamInfo *in, double fraction)
{
    return in->quantity == JC_Q_NAME ? 1.0 : in->typical_min + fraction * (in->typical_max - in->typical_min);
}

static int test_set_get_round_trip(void)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        for (double f = 0.1; f < 1.0; f += 0.2) {
            jc_Setup s = jc_paper_setup();
            char err[256] = "";
            const double v = inside_value(in, f);
            ENSURE_MSG(jc_param_set(&s, id, v, err, sizeof err) == JC_OK, "%s = %g: %s", in->name, v, err);
            double got = NAN, field = NAN;
            int known;
            ENSURE_OK(jc_param_get(&s, id, &got, err, sizeof err), err);
            ENSURE_MSG(got == v, "%s: set %.17g, got %.17g", in->name, v, got);
            ENSURE(field_of(in->name, &s, &field, &known) && field == v);
            /* every other row is as it was, but those the row also sets */
            const jc_Setup paper = jc_paper_setup();
            for (int other = 0; other < jc_param_count(); ++other) {
                const char *on = jc_param_info(other)->name;
                if (other == id || (in->sets && strstr(in->sets, on)) ||
                    (jc_param_info(other)->sets && strstr(jc_param_info(other)->sets, in->name)))
                    continue;
                double a, b;
                ENSURE(field_of(on, &s, &a, &known) && field_of(on, &paper, &b, &known));
                ENSURE_MSG(a == b, "setting %s changed %s", in->name, on);
            }
        }
    }
    return 0;
}

/* A value with the row's unit, against this file's SI arithmetic. */
static int test_parse_with_units(void)
{
    const char *const mantissas[] = {"12.5", "0.3", "7", "1e-2", "-0.75"};
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        char err[256], text[64];
        double v = NAN;
        if (in->quantity == JC_Q_NAME) {
            for (int k = 0; in->choices[k]; ++k) {
                ENSURE_OK(jc_param_parse(id, in->choices[k], &v, err, sizeof err), err);
                ENSURE(v == (double)k);
            }
            ENSURE(jc_param_parse(id, "no-such-name", &v, err, sizeof err) == JC_EINVAL && strstr(err, "no-such-name"));
            continue;
        }
        for (size_t m = 0; m < sizeof mantissas / sizeof mantissas[0]; ++m) {
            /* in the row's unit, and in every unit of its quantity */
            const char *units[16] = {in->unit};
            int n_units = 1;
            while (n_units < 16 && jc_quantity_unit(in->quantity, n_units - 1, NULL)) {
                units[n_units] = jc_quantity_unit(in->quantity, n_units - 1, NULL);
                ++n_units;
            }
            for (int u = 0; u < n_units; ++u) {
                const char *unit = units[u];
                double per;
                ENSURE_MSG(si_per(unit, &per), "unit '%s' unknown here", unit);
                snprintf(text, sizeof text, "%s%s", mantissas[m], unit);
                ENSURE_MSG(jc_param_parse(id, text, &v, err, sizeof err) == JC_OK, "%s '%s': %s", in->name, text, err);
                ENSURE_REL(v, strtod(mantissas[m], NULL) * per, 4 * DBL_EPSILON);
                if (m == 0 && u == 0) { /* one blank between number and unit too */
                    double spaced = NAN;
                    snprintf(text, sizeof text, "%s %s", mantissas[m], unit);
                    ENSURE(!*unit || (jc_param_parse(id, text, &spaced, err, sizeof err) == JC_OK && spaced == v));
                }
            }
            /* a plain number: SI, but degrees for an angle */
            ENSURE_OK(jc_param_parse(id, mantissas[m], &v, err, sizeof err), err);
            ENSURE_REL(v, strtod(mantissas[m], NULL) * (in->quantity == JC_Q_ANGLE ? PI / 180.0 : 1.0), 4 * DBL_EPSILON);
        }
        ENSURE(jc_param_parse(id, "12furlongs", &v, err, sizeof err) == JC_EINVAL && strstr(err, "furlongs"));
        ENSURE(jc_param_parse(id, "nan", &v, err, sizeof err) == JC_EINVAL);
        ENSURE(jc_param_parse(id, "", &v, err, sizeof err) == JC_EINVAL);
    }
    /* a power-of-ten unit moves the decimal point: exactly the double of the SI text */
    double a, b;
    char err[256];
    ENSURE_OK(jc_quantity_parse("32.1g", JC_Q_MASS, &a, err, sizeof err), err);
    ENSURE_OK(jc_quantity_parse("0.0321", JC_Q_MASS, &b, err, sizeof err), err);
    ENSURE(a == b);
    return 0;
}

/* Written in its unit, a value reads back to the same double. */
static int test_format_reads_back(void)
{
    uint64_t rng = 0x9e3779b97f4a7c15ull;
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        for (int k = 0; k < 200; ++k) {
            double v = in->quantity == JC_Q_NAME ? (double)(k % 3)
                                                 : test_uniform(&rng, in->typical_min, in->typical_max);
            if (k == 1 && in->quantity != JC_Q_NAME) v = 0.1 + 0.2; /* 0.30000000000000004 */
            if (k == 2 && in->quantity == JC_Q_ANGLE) v = 30.0 * (PI / 180.0);
            char text[64], err[256];
            double back = NAN;
            ENSURE_MSG(jc_param_format(id, v, text, sizeof text) == JC_OK, "%s %.17g", in->name, v);
            ENSURE_MSG(jc_param_parse(id, text, &back, err, sizeof err) == JC_OK, "%s '%s': %s", in->name, text, err);
            ENSURE_MSG(back == v, "%s: %.17g written '%s' reads %.17g", in->name, v, text, back);
            if (*in->unit && in->quantity != JC_Q_NAME) ENSURE_MSG(strchr(text, ' '), "'%s' has its unit", text);
        }
    }
    char text[64];
    ENSURE(jc_quantity_format(0.0321, JC_Q_MASS, "g", text, sizeof text) == JC_OK && strcmp(text, "32.1 g") == 0);
    ENSURE(jc_quantity_format(30.0 * (PI / 180.0), JC_Q_ANGLE, "deg", text, sizeof text) == JC_OK &&
           strcmp(text, "30 deg") == 0);
    ENSURE(jc_quantity_format(0.1, JC_Q_LENGTH, "furlong", text, sizeof text) == JC_EINVAL);
    ENSURE(jc_quantity_format(0.1, JC_Q_LENGTH, "cm", text, 4) == JC_EINVAL && text[0] == '\0');
    ENSURE(jc_param_format(jc_param_find("impact-law"), 7.0, text, sizeof text) == JC_EINVAL);
    return 0;
}

/* Just outside the range is refused (the setup unchanged), just inside taken. */
static int check_end(int id, double v, int ok)
{
    const jc_ParamInfo *in = jc_param_info(id);
    jc_Setup s = jc_paper_setup();
    const jc_Setup before = s;
    char err[256] = "";
    const int st = jc_param_set(&s, id, v, err, sizeof err);
    if (ok) {
        ENSURE_MSG(st == JC_OK, "%s = %.17g refused: %s", in->name, v, err);
    } else {
        ENSURE_MSG(st == JC_EINVAL, "%s = %.17g taken", in->name, v);
        const char *what;
        ENSURE_MSG(same_setup(&s, &before, &what), "%s = %.17g: refused but changed the setup (%s)", in->name, v,
                   what);
        ENSURE_MSG(strstr(err, "out of range") || strstr(err, "unknown"), "%s: '%s'", in->name, err);
    }
    return 0;
}

static int test_range_ends(void)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        if (in->quantity == JC_Q_NAME) {
            for (int k = 0; in->choices[k]; ++k)
                if (check_end(id, (double)k, 1)) return 1;
            if (check_end(id, -1.0, 0) || check_end(id, 0.5, 0) || check_end(id, 3.0, 0)) return 1;
            continue;
        }
        ENSURE_MSG(isfinite(in->min), "%s: a lower end", in->name);
        if (check_end(id, in->min_open ? in->min : nextafter(in->min, -INFINITY), 0)) return 1;
        if (check_end(id, in->min_open ? nextafter(in->min, INFINITY) : in->min, 1)) return 1;
        if (isfinite(in->max)) {
            if (check_end(id, in->max_open ? in->max : nextafter(in->max, INFINITY), 0)) return 1;
            if (check_end(id, in->max_open ? nextafter(in->max, -INFINITY) : in->max, 1)) return 1;
        }
        if (check_end(id, INFINITY, 0) || check_end(id, -INFINITY, 0) || check_end(id, NAN, 0)) return 1;
        /* the message names the value and the range */
        char err[256];
        jc_Setup s = jc_paper_setup();
        const double bad = in->min_open ? in->min : in->min - 1.0;
        ENSURE(jc_param_set(&s, id, bad, err, sizeof err) == JC_EINVAL && strstr(err, in->label) &&
               strstr(err, "allowed"));
    }
    /* the ranges are jc_setup_validate's: an end the table takes, the setup takes */
    const struct { const char *name; double v; } ends[] = {
        {"incline", nextafter(JC_MAX_INCLINE_RAD, 0)}, {"restitution", 1.0}, {"g", 1e-6}, {"g", 1e3},
        {"air-density", 100.0}, {"lift-coefficient", -100.0}, {"spin-drag", 1e3}, {"length", 1e3}};
    for (size_t k = 0; k < sizeof ends / sizeof ends[0]; ++k) {
        jc_Setup s = jc_paper_setup();
        char err[256];
        ENSURE_OK(jc_param_set(&s, jc_param_find(ends[k].name), ends[k].v, err, sizeof err), err);
        ENSURE_MSG(jc_setup_validate(&s, err, sizeof err) == JC_OK, "%s = %g: %s", ends[k].name, ends[k].v, err);
    }
    return 0;
}

/* What the body parameters and mu do, as the command line always did. */
static int test_semantics(void)
{
    char err[256];
    /* radius: a disc that fills the rim grows with it; the rod stays */
    jc_Setup s = jc_paper_setup();
    ENSURE_OK(jc_param_set(&s, jc_param_find("radius"), 0.12, err, sizeof err), err);
    ENSURE(s.body.radius_m == 0.12 && s.body.parts[0].radius_m == 0.12 && s.body.parts[1].radius_m == 0.5 * 9.50e-3);
    /* a disc smaller than the rim keeps its radius */
    s = jc_paper_setup();
    s.body.parts[0].radius_m = 0.08;
    ENSURE_OK(jc_param_set(&s, jc_param_find("radius"), 0.12, err, sizeof err), err);
    ENSURE(s.body.radius_m == 0.12 && s.body.parts[0].radius_m == 0.08);
    /* the hoop: no disc grows, its hoop part keeps its radius */
    ENSURE_OK(jc_preset_setup("hoop", &s, err, sizeof err), err);
    ENSURE_OK(jc_param_set(&s, jc_param_find("radius"), 0.12, err, sizeof err), err);
    ENSURE(s.body.parts[0].kind == JC_PART_HOOP && s.body.parts[0].radius_m == 0.10);
    /* a body parameter acts on the first part of its kind, and needs one */
    s = jc_paper_setup();
    s.body.part_count = 3;
    s.body.parts[2] = (jc_Part){JC_PART_ROD, 0.01, 0.02, 0.0, 0.001};
    ENSURE_OK(jc_param_set(&s, jc_param_find("rod-offset"), 0.03, err, sizeof err), err);
    ENSURE(s.body.parts[1].offset_m == 0.03 && s.body.parts[2].offset_m == 0.02);
    ENSURE_OK(jc_preset_setup("hoop", &s, err, sizeof err), err);
    const jc_Setup hoop = s;
    ENSURE(jc_param_set(&s, jc_param_find("rod-mass"), 0.05, err, sizeof err) == JC_EINVAL && strstr(err, "rod"));
    const char *what;
    ENSURE_MSG(same_setup(&s, &hoop, &what), "%s differs from the hoop preset", what);
    ENSURE(jc_param_set(&s, jc_param_find("disc-mass"), 0.05, err, sizeof err) == JC_EINVAL);
    /* mu sets both coefficients */
    s = jc_paper_setup();
    ENSURE_OK(jc_param_set(&s, jc_param_find("mu"), 0.8, err, sizeof err), err);
    ENSURE(s.mu_static == 0.8 && s.mu_kinetic == 0.8);
    /* the impact law by index, the names in the library's order */
    const int law = jc_param_find("impact-law");
    for (int k = 0; k < 3; ++k) {
        ENSURE_OK(jc_param_set(&s, law, (double)k, err, sizeof err), err);
        ENSURE(strcmp(jc_impact_law_name(s.impact_law), jc_param_info(law)->choices[k]) == 0);
    }
    /* no such parameter */
    double v;
    ENSURE(jc_param_set(&s, -1, 1.0, err, sizeof err) == JC_EINVAL);
    ENSURE(jc_param_get(&s, jc_param_count(), &v, err, sizeof err) == JC_EINVAL);
    ENSURE(jc_param_parse(99999, "1", &v, err, sizeof err) == JC_EINVAL);
    /* the library's messages need no buffer */
    ENSURE(jc_param_set(&s, jc_param_find("restitution"), 2.0, NULL, 0) == JC_EINVAL);
    return 0;
}

/* jc_param_sets against the table's words, split here with strtok: mu sets
 * mu-s and mu-k and nothing else does; no row sets itself; ids out of range
 * set nothing. */
static int test_shortcuts(void)
{
    const int mu = jc_param_find("mu"), mu_s = jc_param_find("mu-s"), mu_k = jc_param_find("mu-k");
    ENSURE(mu >= 0 && mu_s >= 0 && mu_k >= 0);
    ENSURE(jc_param_sets(mu, mu_s) && jc_param_sets(mu, mu_k));
    ENSURE(!jc_param_sets(mu_s, mu) && !jc_param_sets(mu, mu) && !jc_param_sets(-1, mu_s) &&
           !jc_param_sets(mu, jc_param_count()));
    int pairs = 0;
    for (int a = 0; a < jc_param_count(); ++a)
        for (int b = 0; b < jc_param_count(); ++b) {
            int listed = 0;
            const char *sets = jc_param_info(a)->sets;
            if (sets && a != b) {
                char copy[256];
                snprintf(copy, sizeof copy, "%s", sets);
                for (char *w = strtok(copy, " "); w; w = strtok(NULL, " "))
                    listed |= strcmp(w, jc_param_info(b)->name) == 0;
            }
            ENSURE_MSG(jc_param_sets(a, b) == listed, "%s sets %s: %d", jc_param_info(a)->name,
                       jc_param_info(b)->name, jc_param_sets(a, b));
            pairs += listed;
        }
    ENSURE_MSG(pairs >= 2, "%d pairs", pairs);
    return 0;
}

int main(void)
{
    RUN_TEST(test_table_is_whole);
    RUN_TEST(test_presets_read_their_fields);
    RUN_TEST(test_set_get_round_trip);
    RUN_TEST(test_parse_with_units);
    RUN_TEST(test_format_reads_back);
    RUN_TEST(test_range_ends);
    RUN_TEST(test_semantics);
    RUN_TEST(test_shortcuts);
    TEST_MAIN_END();
}
