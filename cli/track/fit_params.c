/* The values a fit can free: their names, units, physical ranges, and how
 * each is read from and written into a setup and a start. */
#include "track_fit.h"

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

void cli_fit_param_name(const jc_Setup *s, cli_FitParam p, char *buf, size_t len)
{
    if (p.kind < CLI_FIT_PART_OFFSET) {
        snprintf(buf, len, "%s", fixed_names[p.kind]);
        return;
    }
    const char *kind = p.part >= 0 && p.part < s->body.part_count ? jc_part_kind_name(s->body.parts[p.part].kind) : "?";
    snprintf(buf, len, "%s_%s", kind, p.kind == CLI_FIT_PART_OFFSET ? "offset" : "mass");
}

const char *cli_fit_param_unit(cli_FitParam p)
{
    switch (p.kind) {
    case CLI_FIT_THETA0:
    case CLI_FIT_TILT:
    case CLI_FIT_MARK_ANGLE: return "rad";
    case CLI_FIT_OMEGA0: return "rad/s";
    case CLI_FIT_SURFACE:
    case CLI_FIT_X0:
    case CLI_FIT_PART_OFFSET: return "m";
    case CLI_FIT_PART_MASS: return "kg";
    default: return "";
    }
}

void cli_fit_allowed(const jc_Setup *s, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; k < N_FIXED && used < len; ++k)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", k ? ", " : "", fixed_names[k]);
    for (int kind = JC_PART_DISC; kind <= JC_PART_POINT && used < len; ++kind) {
        const int i = part_of_kind(s, (jc_PartKind)kind);
        if (i < 0) continue;
        const char *name = jc_part_kind_name((jc_PartKind)kind);
        used += (size_t)snprintf(buf + used, len - used, ", %s_mass", name);
        if (kind != JC_PART_DISC && kind != JC_PART_HOOP && used < len)
            used += (size_t)snprintf(buf + used, len - used, ", %s_offset", name);
    }
}

/* One name ("rod-offset" or "rod_offset") into a value; -1 if unknown. */
static int parse_one(const char *text, size_t len, const jc_Setup *s, cli_FitParam *out)
{
    char name[32];
    if (len == 0 || len >= sizeof name) return -1;
    for (size_t i = 0; i < len; ++i) name[i] = text[i] == '-' ? '_' : (char)tolower((unsigned char)text[i]);
    name[len] = '\0';
    for (int k = 0; k < N_FIXED; ++k)
        if (strcmp(name, fixed_names[k]) == 0) {
            out->kind = (cli_FitKind)k;
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
        if (strcmp(name + kl + 1, "mass") == 0) out->kind = CLI_FIT_PART_MASS;
        else if (strcmp(name + kl + 1, "offset") == 0 && !centred) out->kind = CLI_FIT_PART_OFFSET;
        else return -1;
        out->part = part;
        return 0;
    }
    return -1;
}

int cli_fit_param_same(cli_FitParam a, cli_FitParam b) { return a.kind == b.kind && a.part == b.part; }

int cli_fit_parse_free(const char *text, const jc_Setup *s, cli_FitParam *out, int *count, char *err, size_t err_len)
{
    *count = 0;
    char allowed[512];
    cli_fit_allowed(s, allowed, sizeof allowed);
    const char *p = text;
    while (*p) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        cli_FitParam v;
        if (parse_one(p, len, s, &v) != 0) {
            snprintf(err, err_len, "--free '%s': '%.*s' is not a value the fit can free for this body (allowed: %s)",
                     text, (int)(len > 40 ? 40 : len), p, allowed);
            return -1;
        }
        for (int k = 0; k < *count; ++k)
            if (cli_fit_param_same(out[k], v)) {
                snprintf(err, err_len, "--free '%s': '%.*s' is named twice", text, (int)(len > 40 ? 40 : len), p);
                return -1;
            }
        /* Room for the start's three values and the frame's two. */
        if (*count == CLI_FIT_MAX_PARAMS - 5) {
            snprintf(err, err_len, "--free '%s': more than %d values", text, CLI_FIT_MAX_PARAMS - 5);
            return -1;
        }
        out[(*count)++] = v;
        if (!comma) break;
        p = comma + 1;
    }
    if (*count == 0) {
        snprintf(err, err_len, "--free '%s' names no value (allowed: %s)", text, allowed);
        return -1;
    }
    return 0;
}

void cli_fit_range(const jc_Setup *s, cli_FitParam p, double *lo, double *hi)
{
    *lo = -INFINITY, *hi = INFINITY;
    switch (p.kind) {
    case CLI_FIT_MU_S: *lo = 0.0, *hi = MU_MAX; break;
    case CLI_FIT_MU_K: *lo = 0.0, *hi = s->mu_static; break;
    case CLI_FIT_RESTITUTION: *lo = 0.0, *hi = 1.0; break;
    case CLI_FIT_THETA0:
    case CLI_FIT_MARK_ANGLE: *lo = -CLI_TRACK_PI, *hi = CLI_TRACK_PI; break;
    case CLI_FIT_TILT: *lo = -CLI_TRACK_PI / 2, *hi = CLI_TRACK_PI / 2; break;
    case CLI_FIT_OMEGA0: *lo = -OMEGA_MAX_RADPS, *hi = OMEGA_MAX_RADPS; break;
    case CLI_FIT_PART_OFFSET: {
        const jc_Part *q = &s->body.parts[p.part];
        *lo = 0.0, *hi = s->body.radius_m - (q->kind == JC_PART_ROD ? q->radius_m : 0.0);
        break;
    }
    case CLI_FIT_PART_MASS: {
        double total = 0;
        for (int i = 0; i < s->body.part_count; ++i) total += s->body.parts[i].mass_kg;
        const double m = s->body.parts[p.part].mass_kg;
        *lo = 0.0, *hi = MASS_MAX_FACTOR * (m > 0 ? m : total);
        break;
    }
    default: break;
    }
}

double cli_fit_get(const jc_Setup *s, const jc_State *start, const cli_FitFrame *f, cli_FitParam p)
{
    switch (p.kind) {
    case CLI_FIT_MU_S: return s->mu_static;
    case CLI_FIT_MU_K: return s->mu_kinetic;
    case CLI_FIT_RESTITUTION: return s->restitution;
    case CLI_FIT_THETA0: return start->theta_rad;
    case CLI_FIT_OMEGA0: return start->omega_radps;
    case CLI_FIT_X0: return start->x_m;
    case CLI_FIT_MARK_ANGLE: return f->mark_angle_rad;
    case CLI_FIT_TILT: return f->tilt_rad;
    case CLI_FIT_SURFACE: return f->surface_m;
    case CLI_FIT_PART_OFFSET: return s->body.parts[p.part].offset_m;
    case CLI_FIT_PART_MASS: return s->body.parts[p.part].mass_kg;
    }
    return NAN;
}

void cli_fit_set(jc_Setup *s, jc_State *start, cli_FitFrame *f, cli_FitParam p, double v)
{
    switch (p.kind) {
    case CLI_FIT_MU_S: s->mu_static = v; break;
    case CLI_FIT_MU_K: s->mu_kinetic = v; break;
    case CLI_FIT_RESTITUTION: s->restitution = v; break;
    case CLI_FIT_THETA0: start->theta_rad = v; break;
    case CLI_FIT_OMEGA0: start->omega_radps = v; break;
    case CLI_FIT_X0: start->x_m = v; break;
    case CLI_FIT_MARK_ANGLE: f->mark_angle_rad = v; break;
    case CLI_FIT_TILT: f->tilt_rad = v; break;
    case CLI_FIT_SURFACE: f->surface_m = v; break;
    case CLI_FIT_PART_OFFSET: s->body.parts[p.part].offset_m = v; break;
    case CLI_FIT_PART_MASS: s->body.parts[p.part].mass_kg = v; break;
    }
}
