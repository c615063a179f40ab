/*
 * The rolling equation of motion (docs/physics.md §2.5, §2.6, §9.2): th'',
 * N and F of a body rolling without slipping, with the loads of air and
 * rolling resistance or without them. It is written once, here. The
 * resistance-free model is this law with every resistance coefficient 0
 * (jc_roll_consts with loaded = 0): every load is then an exact zero, and
 * adding or subtracting it leaves the closed form's terms unchanged to the
 * last bit. Internal; included by internal.h.
 *
 * With the loads at the rolling velocity v = (r w, 0): drag F_x against it,
 * the Magnus force F_y normal to the incline (spin ratio 1, into the incline
 * for C_L > 0 and w > 0), spin drag -k w|w|, and the normal force acting a
 * lever b_s = b clamp(w / band) ahead of the contact point P, the torques
 * about P give
 *
 *   I_eff th'' = M g Q + M r d sin th w^2 + r F_x - k w|w| - b_s (M g cos a - M d cos th w^2 - F_y),
 *   I_eff      = I_P - b_s M d sin th,
 *   Q          = (r + d cos th) sin a + d sin th cos a,
 *
 * the form of physics.md §9.2 with the air force's moments about G and P
 * collected (F_x acts at C, a height r above P; F_y's line passes through
 * P). The first two terms are the closed form I_P th'' = M g Q + M r d sin th
 * w^2 (§2.5), and they are summed first so that zero loads leave them as
 * they are. N and F follow from Newton's law for G:
 *
 *   N = M (g cos a - d sin th th'' - d cos th w^2) - F_y
 *   F = M ((r + d cos th) th'' - d sin th w^2 - g sin a) - F_x
 *
 * model.c holds the resistance-free law in another form, as exact functions
 * of th: the same N and F times I_P^2, with w^2 from the energy integral,
 * which is what the crossing search needs. Tests against computations of
 * their own: tests/sim/test_rolling_law.c (this law, with and without
 * loads), tests/sim/test_lagrange.c and tests/test_rolling.c (the exact
 * rolling model and the polynomials).
 */
#ifndef JUMPCYL_ROLLING_LAW_H
#define JUMPCYL_ROLLING_LAW_H

#include "jumpcyl/jumpcyl.h"

#include <math.h>

/* rad/s: below this spin rolling resistance ramps linearly to 0 (air.h
 * says why). */
#define JC_RR_BAND_RADPS 1e-3

/* clamp(w / band, -1, 1) as fmax(-1, fmin(1, .)) has it (NaN -> 1), without
 * calls into libm, dividing only inside the band (w / band reaches +-1
 * exactly at w = +-band, so the values are the same). */
static inline double jc_rr_ramp(double w)
{
    return !(w < JC_RR_BAND_RADPS) ? 1.0 : (w > -JC_RR_BAND_RADPS ? w / JC_RR_BAND_RADPS : -1.0);
}

/* The model's constants of the law, taken once: each is a leading product
 * of the expression it stands in, formed in the same order, so that the
 * law computes the same numbers as from the model's fields. */
typedef struct {
    double m_kg, r_m, d_m;
    double ip0_kgm2;       /* I_C + M r^2: I_P = ip0 + mrd2 cos th */
    double mrd2_kgm2;      /* 2 M r d */
    double mrd_kgm2;       /* M r d */
    double md_kgm;         /* M d */
    double mg_N;           /* M g */
    double sin_a, cos_a;   /* of the incline */
    double g_cos_mps2, g_sin_mps2; /* g cos a, g sin a */
    double mg_cos_N;       /* M g cos a */
    /* The resistance coefficients, all 0 for the resistance-free law. */
    double qcd_kgpm, qcl_kgpm; /* 1/2 rho A C_d, 1/2 rho A C_L, A = 2 r L (drag = qcd v^2) */
    double spin_drag_Nms2;
    double rr_m;           /* rolling resistance lever b */
} jc_RollConsts;

/* The constants of model m; with loaded = 0 without its resistances (the
 * exact rolling model of rolling.c and the closed-form rolling phase). */
static inline void jc_roll_consts(const jc_Model *m, int loaded, jc_RollConsts *k)
{
    const jc_Setup *s = &m->setup;
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m, g = s->gravity_mps2;
    const double half_rho_area = 0.5 * s->air_density_kgpm3 * 2.0 * r * s->length_m;
    k->m_kg = M;
    k->r_m = r;
    k->d_m = d;
    k->ip0_kgm2 = m->body.inertia_c_kgm2 + M * r * r;
    k->mrd2_kgm2 = 2.0 * M * r * d;
    k->mrd_kgm2 = M * r * d;
    k->md_kgm = M * d;
    k->mg_N = M * g;
    k->sin_a = m->sin_incline;
    k->cos_a = m->cos_incline;
    k->g_cos_mps2 = g * m->cos_incline;
    k->g_sin_mps2 = g * m->sin_incline;
    k->mg_cos_N = M * g * m->cos_incline;
    k->qcd_kgpm = loaded ? half_rho_area * s->drag_coefficient : 0.0;
    k->qcl_kgpm = loaded ? half_rho_area * s->lift_coefficient : 0.0;
    k->spin_drag_Nms2 = loaded ? s->spin_drag_Nms2 : 0.0;
    k->rr_m = loaded ? s->rolling_resistance_m : 0.0;
}

/* I_P at th given by its cosine. */
static inline double jc_roll_inertia_p(const jc_RollConsts *k, double cos_th)
{
    return k->ip0_kgm2 + k->mrd2_kgm2 * cos_th;
}

/* What the law gives at a state. */
typedef struct {
    double thdd_radps2;
    double normal_N, friction_N;
    double fx_N;  /* the air's force along the incline (drag) */
    double rr_m;  /* b_s: the normal force's lever ahead of the contact point */
} jc_RollForces;

/* The law at th given by its sine s and cosine c, spin w; dir is the
 * direction about to be taken when w = 0, against which rolling resistance
 * acts then with its full lever: the static question, whether a body at
 * rest starts (rest_direction, rolling_phase.c). The motion itself takes
 * dir 0, the ramp's own value at w = 0, so that the lever is continuous in
 * w (rolling_phase.c's roll_ode_law). */
static inline void jc_roll_law(const jc_RollConsts *k, double s, double c, double w, int dir, jc_RollForces *out)
{
    const double r = k->r_m, d = k->d_m, w2 = w * w;
    const double rw = r * w, speed = fabs(rw);
    const double fx = -k->qcd_kgpm * speed * rw;          /* drag against the centre's velocity */
    const double fy = -k->qcl_kgpm * rw * rw;             /* Magnus, into the incline for w > 0 */
    const double couple = k->spin_drag_Nms2 * w * fabs(w); /* spin drag */
    const double bs = k->rr_m * (w == 0.0 ? (double)dir : jc_rr_ramp(w));
    const double ds = d * s, dc = d * c;
    /* The closed form's terms, then the loads' (exact zeros without them). */
    const double gravity = k->mg_N * ((r + dc) * k->sin_a + ds * k->cos_a);
    const double closed = gravity + (k->mrd_kgm2 * s) * w2;
    const double loads = (r * fx - couple) - bs * ((k->mg_cos_N - (k->md_kgm * c) * w2) - fy);
    const double ieff = jc_roll_inertia_p(k, c) - bs * (k->md_kgm * s);
    const double acc = (closed + loads) / ieff;
    out->thdd_radps2 = acc;
    out->normal_N = k->m_kg * ((k->g_cos_mps2 - ds * acc) - dc * w2) - fy;
    out->friction_N = k->m_kg * (((r + dc) * acc - ds * w2) - k->g_sin_mps2) - fx;
    out->fx_N = fx;
    out->rr_m = bs;
}

/* The power lost to the air (drag on the centre and spin drag; the Magnus
 * force does no work) at spin w. */
static inline double jc_roll_air_power(const jc_RollConsts *k, double w)
{
    const double speed = fabs(k->r_m * w);
    return k->qcd_kgpm * speed * speed * speed + k->spin_drag_Nms2 * fabs(w) * w * w;
}

#endif
