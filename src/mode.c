/*
 * Choosing the contact mode consistent with the forces (docs/physics.md §4a),
 * at the start, after every event and after every impact, instead of
 * assuming one. Getting this wrong produces zero-length flights that repeat
 * forever, or a body that keeps rolling with a negative normal force.
 */
#include "internal.h"

#include <math.h>

/* Free flight needs the rim's lowest point to accelerate away:
 * y_C'' = -g cos a + Fy/M + d sin th T/I_G + d cos th w^2 >= 0, which without
 * air is the paper's d w^2 cos th >= g cos a. */
double jc_free_gap_accel(const jc_Model *m, const jc_State *s)
{
    const double d = m->body.cm_offset_m, th = s->theta_rad, w = s->omega_radps;
    double sn, cs;
    jc_sincos(th, &sn, &cs); /* inline: libm's sin and cos are calls through the PLT */
    double acc = d * w * w * cs - m->setup.gravity_mps2 * m->cos_incline;
    if (jc_model_has_resistance(m)) {
        jc_Loads l;
        jc_loads_at(m, sn, cs, s->vx_mps, s->vy_mps, w, &l);
        acc += l.fy_N / m->body.mass_kg + d * sn * l.torque_Nm / m->body.inertia_g_kgm2;
    }
    return acc;
}

static int flight_consistent(const jc_Model *m, const jc_State *s)
{
    return jc_free_gap_accel(m, s) >= 0.0;
}

/* Sliding from zero slip, trying dir first: N > 0 with D > 0 (else the
 * direction has no consistent contact force) and a slip acceleration along
 * dir. A direction that fails is not yet a Painleve case: the other
 * direction, and then flight, may be consistent (found at mu = 1000: D < 0
 * for the first direction while the free gap acceleration was > 0). */
static jc_ModeChoice start_slide(const jc_Model *m, const jc_State *s, int dir, int *slip_dir)
{
    const double r = m->body.radius_m;
    for (int attempt = 0; attempt < 2; ++attempt, dir = -dir) {
        jc_SlidingForces f;
        jc_sliding_at(m, s, dir, &f, NULL);
        if (!(f.denominator > 0.0 && f.normal_N > 0.0)) continue;
        /* At a slip onset friction is already at the cone's edge, so the
         * slip acceleration starts from zero: only a clear opposition (beyond
         * rounding of the terms) rules a direction out. */
        const double slip_acc = f.x_acc - r * f.theta_acc;
        const double scale = m->setup.gravity_mps2 + fabs(f.x_acc) + r * fabs(f.theta_acc);
        if (dir * slip_acc >= -1e-9 * scale) {
            *slip_dir = dir;
            return CHOICE_SLIDE;
        }
    }
    return flight_consistent(m, s) ? CHOICE_FLY : CHOICE_PAINLEVE;
}

jc_ModeChoice jc_mode_choose(const jc_Model *m, const jc_State *s, int allow_roll, int *slip_dir)
{
    const double r = m->body.radius_m;
    const double slip = s->vx_mps - r * s->omega_radps;
    if (fabs(slip) > JC_NO_SLIP_MPS) {
        const int dir = slip > 0.0 ? 1 : -1;
        jc_SlidingForces f;
        jc_sliding_at(m, s, dir, &f, NULL);
        if (f.denominator <= 0.0) return CHOICE_PAINLEVE;
        if (f.normal_N > 0.0) {
            *slip_dir = dir;
            return CHOICE_SLIDE;
        }
        return CHOICE_FLY;
    }
    double thdd, normal, friction;
    const int roll_dir = s->omega_radps > 0.0 ? 1 : (s->omega_radps < 0.0 ? -1 : 0);
    jc_rolling_at(m, s->theta_rad, s->omega_radps, roll_dir, &thdd, &normal, &friction);
    if (allow_roll && normal > 0.0 && fabs(friction) <= m->setup.mu_static * normal) {
        if (s->omega_radps == 0.0 && thdd == 0.0) return CHOICE_REST;
        return CHOICE_ROLL;
    }
    if (normal <= 0.0 && flight_consistent(m, s)) return CHOICE_FLY;
    /* Rolling needs more friction than the cone holds (or a pull into the
     * incline at N <= 0): slide so that friction acts along the friction
     * rolling needed. */
    return start_slide(m, s, friction > 0.0 ? -1 : 1, slip_dir);
}
