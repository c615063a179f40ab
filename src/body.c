/* Composite bodies: parts in the body frame -> M, d, I_C, I_G. */
#include "internal.h"

#include <math.h>

/* Parts may touch the rim: allow for rounding in offset + radius. */
#define RIM_SLACK 1e-12
/* Upper bounds far beyond any cylinder that rolls down a ramp, low enough
 * that every product the models form (M^2 r d^2 g I_P^2 ...) stays finite:
 * a 1e308 kg part overflowed the rolling model to NaN (found by fuzzing). */
#define MAX_PART_MASS_KG 1e6
#define MAX_RADIUS_M 1e3
/* Lower bounds, a microgram and a micrometre, for the same reason: a
 * subnormal total mass (5e-312 kg) made an impulse NaN (found by fuzzing),
 * and r^2 d^2 of a smaller body underflows. */
#define MIN_TOTAL_MASS_KG 1e-9
#define MIN_RADIUS_M 1e-6

const char *jc_part_kind_name(jc_PartKind kind)
{
    switch (kind) {
    case JC_PART_DISC: return "disc";
    case JC_PART_HOOP: return "hoop";
    case JC_PART_ROD: return "rod";
    case JC_PART_POINT: return "point";
    }
    return "unknown";
}

/* Moment of inertia of a part about its own axis. */
static double own_inertia(const jc_Part *p)
{
    switch (p->kind) {
    case JC_PART_DISC: return 0.5 * p->mass_kg * p->radius_m * p->radius_m;
    case JC_PART_HOOP: return p->mass_kg * p->radius_m * p->radius_m;
    case JC_PART_ROD: return 0.5 * p->mass_kg * p->radius_m * p->radius_m;
    case JC_PART_POINT: return 0.0;
    }
    return 0.0;
}

static int check_part(const jc_Part *p, int i, double rim_m, char *err, size_t err_len)
{
    const char *kind = jc_part_kind_name(p->kind);
    if (p->kind < JC_PART_DISC || p->kind > JC_PART_POINT)
        return jc_fail(err, err_len, JC_EINVAL, "part %d: unknown kind %d (allowed: disc, hoop, rod, point)", i + 1, (int)p->kind);
    if (!(p->mass_kg >= 0.0 && p->mass_kg <= MAX_PART_MASS_KG))
        return jc_fail(err, err_len, JC_EINVAL, "part %d (%s): mass %g kg is out of range (allowed: [0, %g] kg)", i + 1, kind,
                       p->mass_kg, MAX_PART_MASS_KG);
    if (!isfinite(p->offset_m) || p->offset_m < 0.0)
        return jc_fail(err, err_len, JC_EINVAL, "part %d (%s): offset %g m is out of range (allowed: finite, >= 0)", i + 1, kind, p->offset_m);
    if (!isfinite(p->angle_rad))
        return jc_fail(err, err_len, JC_EINVAL, "part %d (%s): angle %g rad is not a finite number", i + 1, kind, p->angle_rad);
    if (!isfinite(p->radius_m))
        return jc_fail(err, err_len, JC_EINVAL, "part %d (%s): radius %g m is not a finite number", i + 1, kind, p->radius_m);
    switch (p->kind) {
    case JC_PART_DISC:
    case JC_PART_HOOP:
        if (p->radius_m <= 0.0)
            return jc_fail(err, err_len, JC_EINVAL, "part %d (%s): radius %g m is out of range (allowed: > 0, up to the rim radius %g m)", i + 1, kind, p->radius_m, rim_m);
        break;
    case JC_PART_ROD:
        if (p->radius_m < 0.0)
            return jc_fail(err, err_len, JC_EINVAL, "part %d (rod): radius %g m is out of range (allowed: >= 0; 0 is a line mass)", i + 1, p->radius_m);
        break;
    case JC_PART_POINT:
        if (p->radius_m != 0.0)
            return jc_fail(err, err_len, JC_EINVAL, "part %d (point): radius %g m must be 0 (use a rod for a mass with size)", i + 1, p->radius_m);
        break;
    }
    if (p->offset_m + p->radius_m > rim_m * (1.0 + RIM_SLACK))
        return jc_fail(err, err_len, JC_EINVAL,
                       "part %d (%s): offset %g m + radius %g m = %g m reaches outside the rim (allowed: <= rim radius %g m)",
                       i + 1, kind, p->offset_m, p->radius_m, p->offset_m + p->radius_m, rim_m);
    return JC_OK;
}

int jc_body_compute(const jc_BodyDef *def, jc_Body *out, char *err, size_t err_len)
{
    if (!(def->radius_m >= MIN_RADIUS_M && def->radius_m <= MAX_RADIUS_M))
        return jc_fail(err, err_len, JC_EINVAL, "radius %g m is out of range (allowed: [%g, %g] m)", def->radius_m,
                       MIN_RADIUS_M, MAX_RADIUS_M);
    if (def->part_count < 1 || def->part_count > JC_MAX_PARTS)
        return jc_fail(err, err_len, JC_EINVAL, "body has %d parts (allowed: 1 to %d)", def->part_count, JC_MAX_PARTS);

    double mass = 0.0, mx = 0.0, my = 0.0, inertia_c = 0.0, disc_mass = 0.0;
    for (int i = 0; i < def->part_count; ++i) {
        const jc_Part *p = &def->parts[i];
        int st = check_part(p, i, def->radius_m, err, err_len);
        if (st != JC_OK) return st;
        mass += p->mass_kg;
        /* Body frame: angle measured from the reference direction towards rolling. */
        mx += p->mass_kg * p->offset_m * sin(p->angle_rad);
        my += p->mass_kg * p->offset_m * cos(p->angle_rad);
        inertia_c += own_inertia(p) + p->mass_kg * p->offset_m * p->offset_m;
        if (p->kind == JC_PART_DISC) disc_mass += p->mass_kg;
    }
    if (!(mass >= MIN_TOTAL_MASS_KG))
        return jc_fail(err, err_len, JC_EINVAL, "total mass %g kg is out of range (allowed: at least %g kg)", mass,
                       MIN_TOTAL_MASS_KG);

    const double d = hypot(mx, my) / mass;
    out->radius_m = def->radius_m;
    out->mass_kg = mass;
    out->cm_offset_m = d;
    out->cm_angle_rad = d > 0.0 ? atan2(mx, my) : 0.0;
    out->inertia_c_kgm2 = inertia_c;
    /* I_G = I_C - M d^2 >= 0 always (parallel axes); clamp rounding only. */
    out->inertia_g_kgm2 = fmax(inertia_c - mass * d * d, 0.0);
    out->disc_mass_kg = disc_mass;
    /* Relative test: a lone point mass leaves I_G at rounding level (~1e-20),
     * not at exactly 0. */
    if (!(out->inertia_g_kgm2 > 1e-12 * mass * def->radius_m * def->radius_m))
        return jc_fail(err, err_len, JC_EINVAL,
                       "the body has no rotational inertia about its centre of mass (a single point mass); add a disc, hoop or rod");
    return JC_OK;
}
