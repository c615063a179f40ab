/* The values a fit can free: their names, units, physical ranges, and how
 * each is read from and written into a setup and a start. */
#include "track_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define MU_MAX 2.0             /* friction beyond 2 is not met on a ramp or a floor */
#define MASS_MAX_FACTOR 10.0   /* a part's mass: up to ten times the setup's */
#define OMEGA_MAX_RADPS 500.0

static const char *const fixed_names[] = {"mu_s", "mu_k", "restitution", "theta0", "omega0",
                                         "x0",   "mark_angle", "tilt", "surface"};
#define N_FIXED (int)(sizeof fixed_names / sizeof fixed_names[0])

/* The first part of a kind in the body, -1 if none. */
static int part_of_kind(const jc_Setup *s, jc_PartKind kind)
{
    for (int i = 0; i < s->body.part_count; ++i)
        if (s->body.parts[i].kind == kind) return i;
    return -1;
}

void jc_fit_param_name(const jc_Setup *s, jc_TrackFitParam p, char *buf, size_t len)
{
    if ((int)p.kind < 0 || p.kind > JC_FIT_PART_MASS) {
        snprintf(buf, len, "?");
        return;
    }
    if (p.kind < JC_FIT_PART_OFFSET) {
        snprintf(buf, len, "%s", fixed_names[p.kind]);
        return;
    }
    const char *kind = p.part >= 0 && p.part < s->body.part_count && p.part < JC_MAX_PARTS
                           ? jc_part_kind_name(s->body.parts[p.part].kind)
                           : "?";
    snprintf(buf, len, "%s_%s", kind, p.kind == JC_FIT_PART_OFFSET ? "offset" : "mass");
}

const char *jc_fit_param_unit(jc_TrackFitParam p)
{
    switch (p.kind) {
    case JC_FIT_THETA0:
    case JC_FIT_TILT:
    case JC_FIT_MARK_ANGLE: return "rad";
    case JC_FIT_OMEGA0: return "rad/s";
    case JC_FIT_SURFACE:
    case JC_FIT_X0:
    case JC_FIT_PART_OFFSET: return "m";
    case JC_FIT_PART_MASS: return "kg";
    default: return "";
    }
}

/* One name ("rod-offset", "rod_offset" or "Rod_Offset") of len bytes into a value; -1 if unknown. */
static int parse_one(const char *text, size_t len, const jc_Setup *s, jc_TrackFitParam *out)
{
    char name[32];
    if (len == 0 || len >= sizeof name) return -1;
    for (size_t i = 0; i < len; ++i) name[i] = text[i] == '-' ? '_' : (char)tolower((unsigned char)text[i]);
    name[len] = '\0';
    for (int k = 0; k < N_FIXED; ++k)
        if (strcmp(name, fixed_names[k]) == 0) {
            out->kind = (jc_TrackFitKind)k;
            out->part = -1;
            return 0;
        }
    for (int kind = JC_PART_DISC; kind <= JC_PART_POINT; ++kind) {
        const char *kn = jc_part_kind_name((jc_PartKind)kind);
        const size_t kl = strlen(kn);
        if (strncmp(name, kn, kl) != 0 || name[kl] != '_') continue;
        const int part = part_of_kind(s, (jc_PartKind)kind);
        if (part < 0) return -1;
        const int centred = kind == JC_PART_DISC || kind == JC_PART_HOOP;
        if (strcmp(name + kl + 1, "mass") == 0) out->kind = JC_FIT_PART_MASS;
        else if (strcmp(name + kl + 1, "offset") == 0 && !centred) out->kind = JC_FIT_PART_OFFSET;
        else return -1;
        out->part = part;
        return 0;
    }
    return -1;
}

int jc_fit_param_same(jc_TrackFitParam a, jc_TrackFitParam b) { return a.kind == b.kind && a.part == b.part; }

int jc_fit_param_find(const jc_Setup *s, const char *name, jc_TrackFitParam *out)
{
    return parse_one(name, strlen(name), s, out) == 0 ? JC_OK : JC_EINVAL;
}

int jc_fit_param_list(const jc_Setup *s, jc_TrackFitParam *out, int cap)
{
    int n = 0;
    for (int k = 0; k < N_FIXED; ++k, ++n)
        if (n < cap) out[n] = (jc_TrackFitParam){(jc_TrackFitKind)k, -1};
    for (int kind = JC_PART_DISC; kind <= JC_PART_POINT; ++kind) {
        const int i = part_of_kind(s, (jc_PartKind)kind);
        if (i < 0) continue;
        if (n < cap) out[n] = (jc_TrackFitParam){JC_FIT_PART_MASS, i};
        ++n;
        if (kind == JC_PART_DISC || kind == JC_PART_HOOP) continue;
        if (n < cap) out[n] = (jc_TrackFitParam){JC_FIT_PART_OFFSET, i};
        ++n;
    }
    return n;
}

int jc_fit_param_check(const jc_Setup *s, jc_TrackFitParam p)
{
    if (p.kind < JC_FIT_MU_S || p.kind > JC_FIT_PART_MASS) return JC_EINVAL;
    if (p.kind < JC_FIT_PART_OFFSET) return JC_OK;
    if (p.part < 0 || p.part >= s->body.part_count || p.part >= JC_MAX_PARTS) return JC_EINVAL;
    const jc_PartKind k = s->body.parts[p.part].kind;
    return p.kind == JC_FIT_PART_OFFSET && (k == JC_PART_DISC || k == JC_PART_HOOP) ? JC_EINVAL : JC_OK;
}

void jc_fit_range(const jc_Setup *s, jc_TrackFitParam p, double *lo, double *hi)
{
    *lo = -INFINITY, *hi = INFINITY;
    switch (p.kind) {
    case JC_FIT_MU_S: *lo = 0.0, *hi = MU_MAX; break;
    case JC_FIT_MU_K: *lo = 0.0, *hi = s->mu_static; break;
    case JC_FIT_RESTITUTION: *lo = 0.0, *hi = 1.0; break;
    case JC_FIT_THETA0:
    case JC_FIT_MARK_ANGLE: *lo = -JC_TRACK_PI, *hi = JC_TRACK_PI; break;
    case JC_FIT_TILT: *lo = -JC_TRACK_PI / 2, *hi = JC_TRACK_PI / 2; break;
    case JC_FIT_OMEGA0: *lo = -OMEGA_MAX_RADPS, *hi = OMEGA_MAX_RADPS; break;
    case JC_FIT_PART_OFFSET: {
        const jc_Part *q = &s->body.parts[p.part];
        *lo = 0.0, *hi = s->body.radius_m - (q->kind == JC_PART_ROD ? q->radius_m : 0.0);
        break;
    }
    case JC_FIT_PART_MASS: {
        double total = 0;
        for (int i = 0; i < s->body.part_count; ++i) total += s->body.parts[i].mass_kg;
        const double m = s->body.parts[p.part].mass_kg;
        *lo = 0.0, *hi = MASS_MAX_FACTOR * (m > 0 ? m : total);
        break;
    }
    default: break;
    }
}

double jc_fit_get(const jc_Setup *s, const jc_State *start, const jc_TrackFitFrame *f, jc_TrackFitParam p)
{
    switch (p.kind) {
    case JC_FIT_MU_S: return s->mu_static;
    case JC_FIT_MU_K: return s->mu_kinetic;
    case JC_FIT_RESTITUTION: return s->restitution;
    case JC_FIT_THETA0: return start->theta_rad;
    case JC_FIT_OMEGA0: return start->omega_radps;
    case JC_FIT_X0: return start->x_m;
    case JC_FIT_MARK_ANGLE: return f->mark_angle_rad;
    case JC_FIT_TILT: return f->tilt_rad;
    case JC_FIT_SURFACE: return f->surface_m;
    case JC_FIT_PART_OFFSET: return s->body.parts[p.part].offset_m;
    case JC_FIT_PART_MASS: return s->body.parts[p.part].mass_kg;
    }
    return NAN;
}

void jc_fit_set(jc_Setup *s, jc_State *start, jc_TrackFitFrame *f, jc_TrackFitParam p, double v)
{
    switch (p.kind) {
    case JC_FIT_MU_S: s->mu_static = v; break;
    case JC_FIT_MU_K: s->mu_kinetic = v; break;
    case JC_FIT_RESTITUTION: s->restitution = v; break;
    case JC_FIT_THETA0: start->theta_rad = v; break;
    case JC_FIT_OMEGA0: start->omega_radps = v; break;
    case JC_FIT_X0: start->x_m = v; break;
    case JC_FIT_MARK_ANGLE: f->mark_angle_rad = v; break;
    case JC_FIT_TILT: f->tilt_rad = v; break;
    case JC_FIT_SURFACE: f->surface_m = v; break;
    case JC_FIT_PART_OFFSET: s->body.parts[p.part].offset_m = v; break;
    case JC_FIT_PART_MASS: s->body.parts[p.part].mass_kg = v; break;
    }
}
