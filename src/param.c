/* The setup's single-valued parameters, described once: name, quantity and
 * units, range, help, experiment-file section and key. The command line,
 * experiment files, batch jobs, JSON outputs and the web page are made from
 * this table (docs/api.md, "Parameters"). */
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Bounds the body's own check (body.c) applies, the same here. */
#define RADIUS_MIN_M 1e-6
#define RADIUS_MAX_M 1e3
#define PART_MASS_MAX_KG 1e6

/* Where a parameter's value lives in a jc_Setup. */
typedef enum {
    AT_FIELD,  /* the double at offset */
    AT_RADIUS, /* the rim radius; a first disc that fills the rim grows with it */
    AT_PART,   /* a field of the body's first part of a kind */
    AT_MU,     /* mu_static and mu_kinetic */
    AT_LAW     /* impact_law, by index */
} where;

typedef enum { PART_MASS, PART_OFFSET, PART_RADIUS } part_field;

typedef struct {
    jc_ParamInfo info;
    where at;
    size_t offset;      /* AT_FIELD */
    jc_PartKind kind;   /* AT_PART */
    part_field field;   /* AT_PART */
} row;

static const char *const impact_laws[] = {"stronge", "poisson", "newton", NULL};

#define INF HUGE_VAL
/* The rows: name, label, help, quantity, SI unit, unit, min, max, min_open,
 * max_open, bound, choices, sets, flags, section, key, json_key,
 * typical_min, typical_max; then where the value lives. Their order is the
 * order of --help, of experiment files' keys within a section and of the
 * JSON echo. */
static const row rows[] = {
    {{"radius", "radius", "rim radius r (the disc of a disc+rod body fills the rim and grows with it)",
      JC_Q_LENGTH, "m", "cm", RADIUS_MIN_M, RADIUS_MAX_M, 0, 0, NULL, NULL, NULL, JC_PARAM_BODY, "body", "radius",
      NULL, 0.02, 0.30},
     AT_RADIUS, 0, JC_PART_DISC, PART_MASS},
    {{"disc-mass", "disc mass", "mass of the body's (first) disc", JC_Q_MASS, "kg", "g", 0.0, PART_MASS_MAX_KG, 0,
      0, NULL, NULL, NULL, JC_PARAM_BODY | JC_PARAM_SHORTCUT, "body", "disc_mass", NULL, 0.0, 0.2},
     AT_PART, 0, JC_PART_DISC, PART_MASS},
    {{"rod-mass", "rod mass", "mass of the body's (first) rod", JC_Q_MASS, "kg", "g", 0.0, PART_MASS_MAX_KG, 0, 0,
      NULL, NULL, NULL, JC_PARAM_BODY | JC_PARAM_SHORTCUT, "body", "rod_mass", NULL, 0.0, 0.2},
     AT_PART, 0, JC_PART_ROD, PART_MASS},
    {{"rod-offset", "rod offset", "distance of the rod's axis from the cylinder's axis", JC_Q_LENGTH, "m", "cm",
      0.0, INF, 0, 0, "offset + the rod's radius at most r", NULL, NULL, JC_PARAM_BODY | JC_PARAM_SHORTCUT, "body",
      "rod_offset", NULL, 0.0, 0.15},
     AT_PART, 0, JC_PART_ROD, PART_OFFSET},
    {{"rod-radius", "rod radius", "the rod's own radius (0 = a line mass)", JC_Q_LENGTH, "m", "mm", 0.0, INF, 0, 0,
      "the rod's offset + radius at most r", NULL, NULL, JC_PARAM_BODY | JC_PARAM_SHORTCUT, "body", "rod_radius",
      NULL, 0.0, 0.02},
     AT_PART, 0, JC_PART_ROD, PART_RADIUS},
    {{"incline", "incline", "incline angle (0 is a horizontal floor)", JC_Q_ANGLE, "rad", "deg", 0.0,
      JC_MAX_INCLINE_RAD, 0, 1, NULL, NULL, NULL, 0, "incline", "angle", "incline_deg", 0.0, 60.0 * DEG},
     AT_FIELD, offsetof(jc_Setup, incline_rad), JC_PART_DISC, PART_MASS},
    {{"g", "gravity", "gravity (the paper's: 9.78 m/s2)", JC_Q_ACCELERATION, "m/s2", "m/s2", 1e-6, 1e3, 0, 0, NULL,
      NULL, NULL, 0, "incline", "gravity", "g", 1.0, 25.0},
     AT_FIELD, offsetof(jc_Setup, gravity_mps2), JC_PART_DISC, PART_MASS},
    {{"mu", "friction", "static and kinetic friction coefficient, both", JC_Q_NUMBER, "", "", 0.0, 1e6, 0, 0, NULL,
      NULL, "mu-s mu-k", JC_PARAM_SHORTCUT, "contact", "mu", NULL, 0.0, 1.5},
     AT_MU, 0, JC_PART_DISC, PART_MASS},
    {{"mu-s", "static friction", "static friction coefficient (sticking)", JC_Q_NUMBER, "", "", 0.0, 1e6, 0, 0,
      NULL, NULL, NULL, 0, "contact", "mu_s", "mu_s", 0.0, 1.5},
     AT_FIELD, offsetof(jc_Setup, mu_static), JC_PART_DISC, PART_MASS},
    {{"mu-k", "kinetic friction", "kinetic friction coefficient (sliding)", JC_Q_NUMBER, "", "", 0.0, 1e6, 0, 0,
      "at most mu-s", NULL, NULL, 0, "contact", "mu_k", "mu_k", 0.0, 1.5},
     AT_FIELD, offsetof(jc_Setup, mu_kinetic), JC_PART_DISC, PART_MASS},
    {{"restitution", "restitution", "normal restitution at impacts", JC_Q_NUMBER, "", "", 0.0, 1.0, 0, 0, NULL,
      NULL, NULL, 0, "contact", "restitution", "restitution", 0.0, 1.0},
     AT_FIELD, offsetof(jc_Setup, restitution), JC_PART_DISC, PART_MASS},
    {{"impact-law", "impact law",
      "stronge (never creates energy), poisson or newton (these two can gain energy at sticking impacts)",
      JC_Q_NAME, "", "", 0.0, 2.0, 0, 0, NULL, impact_laws, NULL, 0, "contact", "impact_law", NULL, 0.0, 2.0},
     AT_LAW, 0, JC_PART_DISC, PART_MASS},
    {{"theta0", "initial angle", "initial angle of the CM from the outward normal", JC_Q_ANGLE, "rad", "deg", -1e4,
      1e4, 0, 0, NULL, NULL, NULL, 0, "start", "theta0", "theta0", -PI, PI},
     AT_FIELD, offsetof(jc_Setup, theta0_rad), JC_PART_DISC, PART_MASS},
    {{"omega0", "initial angular velocity", "initial angular velocity (> 0 rolls downhill)", JC_Q_ANGULAR_SPEED,
      "rad/s", "rad/s", -1e4, 1e4, 0, 0, NULL, NULL, NULL, 0, "start", "omega0", "omega0", -30.0, 30.0},
     AT_FIELD, offsetof(jc_Setup, omega0_radps), JC_PART_DISC, PART_MASS},
    {{"ramp-length", "ramp length", "from the start contact point to the ramp's lower end", JC_Q_LENGTH, "m", "m",
      0.0, INF, 1, 0, "at most 10^5 turns of the rim", NULL, NULL, 0, "incline", "ramp_length", "ramp_length", 0.2,
      10.0},
     AT_FIELD, offsetof(jc_Setup, ramp_length_m), JC_PART_DISC, PART_MASS},
    {{"length", "length", "cylinder length along its axis, for the air's frontal area 2 r L (the paper's: 5.55 cm)",
      JC_Q_LENGTH, "m", "cm", 0.0, 1e3, 0, 0, NULL, NULL, NULL, 0, "body", "length", "length", 0.0, 0.2},
     AT_FIELD, offsetof(jc_Setup, length_m), JC_PART_DISC, PART_MASS},
    {{"air-density", "air density", "air density rho (1.204: dry air at 20 C and 101.325 kPa)", JC_Q_DENSITY,
      "kg/m3", "kg/m3", 0.0, 100.0, 0, 0, NULL, NULL, NULL, 0, "air", "density", "air_density", 0.0, 2.0},
     AT_FIELD, offsetof(jc_Setup, air_density_kgpm3), JC_PART_DISC, PART_MASS},
    {{"drag-coefficient", "drag coefficient", "C_d: air drag 1/2 rho C_d A |v| v on the centre, A = 2 r L (0: off)",
      JC_Q_NUMBER, "", "", 0.0, 100.0, 0, 0, NULL, NULL, NULL, 0, "air", "drag_coefficient", "drag_coefficient",
      0.0, 3.0},
     AT_FIELD, offsetof(jc_Setup, drag_coefficient), JC_PART_DISC, PART_MASS},
    {{"lift-coefficient", "lift coefficient",
      "C_L: Magnus force 1/2 rho C_L A v^2 across the velocity; C_L > 0 pushes a forward-rolling cylinder into "
      "the incline (0: off)",
      JC_Q_NUMBER, "", "", -100.0, 100.0, 0, 0, NULL, NULL, NULL, 0, "air", "lift_coefficient", "lift_coefficient",
      -1.0, 1.0},
     AT_FIELD, offsetof(jc_Setup, lift_coefficient), JC_PART_DISC, PART_MASS},
    {{"spin-drag", "spin drag", "K: torque -K w|w| on the spin (0: off)", JC_Q_SPIN_DRAG, "N m s2", "N m s2", 0.0,
      1e3, 0, 0, NULL, NULL, NULL, 0, "air", "spin_drag", "spin_drag", 0.0, 1e-5},
     AT_FIELD, offsetof(jc_Setup, spin_drag_Nms2), JC_PART_DISC, PART_MASS},
    {{"rolling-resistance", "rolling resistance", "lever arm b of N against the rolling direction (0: off)",
      JC_Q_LENGTH, "m", "mm", 0.0, INF, 0, 0, "at most r/2", NULL, NULL, 0, "contact", "rolling_resistance",
      "rolling_resistance", 0.0, 0.005},
     AT_FIELD, offsetof(jc_Setup, rolling_resistance_m), JC_PART_DISC, PART_MASS},
    {{"paper-d", "paper-model CM offset",
      "CM offset the paper's model uses; 0 is the body's exact d (the paper preset: the printed 2.65 cm)",
      JC_Q_LENGTH, "m", "cm", 0.0, INF, 0, 0, "at most r", NULL, NULL, 0, "paper", "cm_offset", NULL, 0.0, 0.1},
     AT_FIELD, offsetof(jc_Setup, paper_cm_offset_m), JC_PART_DISC, PART_MASS},
};
#undef INF
#define ROW_COUNT ((int)(sizeof rows / sizeof rows[0]))

int jc_param_count(void) { return ROW_COUNT; }

const jc_ParamInfo *jc_param_info(int id) { return id >= 0 && id < ROW_COUNT ? &rows[id].info : NULL; }

/* Names match with '-' and '_' taken as the same character. */
static int same_name(const char *a, const char *b)
{
    for (; *a && *b; ++a, ++b) {
        const char x = *a == '_' ? '-' : *a, y = *b == '_' ? '-' : *b;
        if (x != y) return 0;
    }
    return *a == *b;
}

int jc_param_find(const char *name)
{
    for (int i = 0; name && i < ROW_COUNT; ++i)
        if (same_name(name, rows[i].info.name)) return i;
    return -1;
}

int jc_param_sets(int shortcut_id, int id)
{
    if (shortcut_id < 0 || shortcut_id >= ROW_COUNT || id < 0 || id >= ROW_COUNT || shortcut_id == id) return 0;
    const char *name = rows[id].info.name;
    const size_t n = strlen(name);
    for (const char *s = rows[shortcut_id].info.sets; s && *s; s += strcspn(s, " "), s += strspn(s, " "))
        if (strncmp(s, name, n) == 0 && (s[n] == ' ' || s[n] == '\0')) return 1;
    return 0;
}

/* The index of the body's first part of a kind, -1 if it has none. */
static int first_part(const jc_BodyDef *b, jc_PartKind kind)
{
    for (int i = 0; i < b->part_count && i < JC_MAX_PARTS; ++i)
        if (b->parts[i].kind == kind) return i;
    return -1;
}

static double *part_field_of(jc_Part *p, part_field f)
{
    return f == PART_MASS ? &p->mass_kg : f == PART_OFFSET ? &p->offset_m : &p->radius_m;
}

static double part_value(const jc_Part *p, part_field f)
{
    return f == PART_MASS ? p->mass_kg : f == PART_OFFSET ? p->offset_m : p->radius_m;
}

/* Angles are shown in degrees, every other value in SI. */
static double shown(const jc_ParamInfo *in, double v_si, const char **unit)
{
    const int angle = in->quantity == JC_Q_ANGLE;
    *unit = angle ? "deg" : in->si_unit;
    return angle ? v_si * (180.0 / PI) : v_si;
}

/* "restitution 2 is out of range (allowed: [0, 1])", as jc_setup_validate says it. */
static int out_of_range(const jc_ParamInfo *in, double v, char *err, size_t err_len)
{
    const char *unit;
    const double x = shown(in, v, &unit), lo = shown(in, in->min, &unit), hi = shown(in, in->max, &unit);
    const char *blank = *unit ? " " : "";
    if (isinf(in->max))
        return jc_fail(err, err_len, JC_EINVAL, "%s %g%s%s is out of range (allowed: %s %g%s%s)", in->label, x, blank,
                       unit, in->min_open ? ">" : ">=", lo, blank, unit);
    return jc_fail(err, err_len, JC_EINVAL, "%s %g%s%s is out of range (allowed: %s%g, %g%s%s%s)", in->label, x, blank,
                   unit, in->min_open ? "(" : "[", lo, hi, in->max_open ? ")" : "]", blank, unit);
}

static int in_range(const jc_ParamInfo *in, double v)
{
    return isfinite(v) && (in->min_open ? v > in->min : v >= in->min) && (in->max_open ? v < in->max : v <= in->max);
}

static int no_part(const row *r, char *err, size_t err_len)
{
    const char *kind = jc_part_kind_name(r->kind);
    return jc_fail(err, err_len, JC_EINVAL, "%s needs a body with a %s part (it sets the body's first %s)",
                   r->info.name, kind, kind);
}

int jc_param_set(jc_Setup *s, int id, double v, char *err, size_t err_len)
{
    if (id < 0 || id >= ROW_COUNT) return jc_fail(err, err_len, JC_EINVAL, "no parameter number %d", id);
    const row *r = &rows[id];
    if (r->at == AT_LAW) {
        if (!(v >= 0.0 && v <= 2.0 && v == floor(v)))
            return jc_fail(err, err_len, JC_EINVAL, "impact law %g is unknown (allowed: 0 stronge, 1 poisson, 2 newton)",
                           v);
        s->impact_law = (jc_ImpactLaw)(int)v;
        return JC_OK;
    }
    if (!in_range(&r->info, v)) return out_of_range(&r->info, v, err, err_len);
    switch (r->at) {
    case AT_FIELD: memcpy((char *)s + r->offset, &v, sizeof v); break; /* the double at that offset */
    case AT_RADIUS: {
        const int disc = first_part(&s->body, JC_PART_DISC);
        if (disc >= 0 && s->body.parts[disc].radius_m == s->body.radius_m) s->body.parts[disc].radius_m = v;
        s->body.radius_m = v;
        break;
    }
    case AT_PART: {
        const int p = first_part(&s->body, r->kind);
        if (p < 0) return no_part(r, err, err_len);
        *part_field_of(&s->body.parts[p], r->field) = v;
        break;
    }
    case AT_MU: s->mu_static = s->mu_kinetic = v; break;
    case AT_LAW: break;
    }
    return JC_OK;
}

int jc_param_get(const jc_Setup *s, int id, double *v, char *err, size_t err_len)
{
    if (id < 0 || id >= ROW_COUNT) return jc_fail(err, err_len, JC_EINVAL, "no parameter number %d", id);
    const row *r = &rows[id];
    switch (r->at) {
    case AT_FIELD: memcpy(v, (const char *)s + r->offset, sizeof *v); break;
    case AT_RADIUS: *v = s->body.radius_m; break;
    case AT_PART: {
        const int p = first_part(&s->body, r->kind);
        if (p < 0) return no_part(r, err, err_len);
        *v = part_value(&s->body.parts[p], r->field);
        break;
    }
    case AT_MU: *v = s->mu_static; break;
    case AT_LAW: *v = (double)s->impact_law; break;
    }
    return JC_OK;
}

/* "stronge, poisson, newton" */
static void choices_text(const jc_ParamInfo *in, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; in->choices[k] && used < len; ++k) {
        const int w = snprintf(buf + used, len - used, "%s%s", k ? ", " : "", in->choices[k]);
        if (w < 0) break;
        used += (size_t)w;
    }
}

int jc_param_parse(int id, const char *text, double *v, char *err, size_t err_len)
{
    const jc_ParamInfo *in = jc_param_info(id);
    if (!in) return jc_fail(err, err_len, JC_EINVAL, "no parameter number %d", id);
    if (in->quantity != JC_Q_NAME) return jc_quantity_parse(text, in->quantity, v, err, err_len);
    for (int k = 0; text && in->choices[k]; ++k)
        if (strcmp(text, in->choices[k]) == 0) {
            *v = (double)k;
            return JC_OK;
        }
    char allowed[128];
    choices_text(in, allowed, sizeof allowed);
    return jc_fail(err, err_len, JC_EINVAL, "unknown %s '%s' (allowed: %s)", in->label, text ? text : "", allowed);
}

int jc_param_format(int id, double v, char *buf, size_t len)
{
    const jc_ParamInfo *in = jc_param_info(id);
    if (!in || !buf || len == 0) return JC_EINVAL;
    if (in->quantity != JC_Q_NAME) return jc_quantity_format(v, in->quantity, in->unit, buf, len);
    int k = 0;
    while (in->choices[k] && (double)k != v) ++k;
    if (!in->choices[k] || snprintf(buf, len, "%s", in->choices[k]) >= (int)len) {
        buf[0] = '\0';
        return JC_EINVAL;
    }
    return JC_OK;
}
