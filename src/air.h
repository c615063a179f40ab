/*
 * Air and rolling resistance (docs/physics.md, "Air and rolling resistance"),
 * included by internal.h.
 * All optional; with every coefficient 0 the simulator keeps its closed forms
 * and these loads are never evaluated.
 *
 * - Drag through the centre C, against its velocity v: -1/2 rho C_d A |v| v,
 *   A = 2 r L (diameter times length, the frontal area in cross-flow).
 * - Magnus force perpendicular to v: 1/2 rho C_L A |v| s (vy, -vx), with
 *   s = clamp(r w / |v|, -1, 1): full C_L from spin ratio 1 (rolling), and
 *   vanishing with the spin below it, as the real force does. For a cylinder
 *   rolling downhill (w > 0, v along +x) this is (0, -...): C_L > 0 pushes
 *   it into the incline, as topspin pushes a real cylinder. No work.
 * - Spin drag: a torque -k w |w| on the rotation.
 * - Rolling resistance: the normal force acts a lever b ahead of the contact
 *   point in the rolling direction, a torque -b s N against the rolling,
 *   s = clamp(w / 1 mrad/s, -1, 1).
 * Both switches are continuous: a sign switch at w = 0 made the integrator
 * chatter for 10^7 steps where the other torques drive w to 0 (found by
 * fuzzing). The rolling phase still treats w = 0 exactly (a turn event and a
 * static check, rolling.c).
 */
#ifndef JUMPCYL_AIR_H
#define JUMPCYL_AIR_H

#include <math.h>

/* The loads beyond gravity and the contact force. */
typedef struct {
    double fx_N, fy_N;       /* air force, acting at the centre C */
    double torque_Nm;        /* about G, th sense: the air force's moment plus spin drag */
    double rr_torque_per_N;  /* rolling resistance torque per newton of N (-b sgn w) */
    double air_power_W;      /* rate of energy lost to the air, >= 0 */
} jc_Loads;
/* Whether any of them is on; inline: asked at every stage of the drag runs' rolling. */
static inline int jc_model_has_resistance(const jc_Model *m) { return jc_model_tables(m)->has_resistance; }
/* rad/s: below this spin rolling resistance ramps linearly to 0. */
#define JC_RR_BAND_RADPS 1e-3

/* The loads at angle th given by its sine and cosine. Inline: they run at
 * every stage of every step of the drag runs' phases (measured with
 * callgrind: a drag run 1.318M -> 1.227M instructions once inlined). */
static inline void jc_loads_at(const jc_Model *m, double sin_th, double cos_th, double vx, double vy, double w, jc_Loads *out)
{
    const jc_Setup *s = &m->setup;
    const double d = m->body.cm_offset_m;
    /* Not hypot: velocities here are far from overflow, and hypot was 1 % of
     * a drag run's time (measured). In contact (vy = 0) no square root at
     * all: sqrt(vx^2) is |vx| to the last bit (unless vx^2 underflows, below
     * 1e-154 m/s), and the root's latency held up every stage of the
     * rolling and sliding phases with drag (measured: a drag run 3-4 % less
     * time, the same numbers). */
    const double speed = vy == 0.0 ? fabs(vx) : sqrt(vx * vx + vy * vy);
    const double r = m->body.radius_m;
    const double cd = s->drag_coefficient, cl = s->lift_coefficient;
    /* spin ratio r w / |v| clamped to [-1, 1] (0 when the centre is at rest);
     * only the Magnus force uses it: without lift its division is skipped
     * (it waits for the square root above, at every stage of every step). */
    const double spin = cl == 0.0 ? 0.0 : (fabs(r * w) >= speed ? (w > 0.0) - (w < 0.0) : r * w / speed);
    /* clamp(w / band, -1, 1) as fmax(-1, fmin(1, .)) has it (NaN -> 1),
     * without the calls into libm, and dividing only inside the band (the
     * same values: w / band reaches +-1 exactly at w = +-band). */
    const double roll = !(w < JC_RR_BAND_RADPS) ? 1.0 : (w > -JC_RR_BAND_RADPS ? w / JC_RR_BAND_RADPS : -1.0);
    const double q = 0.5 * s->air_density_kgpm3 * 2.0 * m->body.radius_m * s->length_m * speed;
    out->fx_N = q * (-cd * vx + cl * spin * vy);
    out->fy_N = q * (-cd * vy - cl * spin * vx);
    /* Torque about G in the th sense (clockwise-positive): the moment of the
     * air force acting at C, R = C - G = -d (sin th, cos th), plus spin drag. */
    out->torque_Nm = d * sin_th * out->fy_N - d * cos_th * out->fx_N - s->spin_drag_Nms2 * w * fabs(w);
    out->rr_torque_per_N = -s->rolling_resistance_m * roll;
    /* Power lost to the air: drag on the centre and spin drag (Magnus does no work). */
    out->air_power_W = q * cd * speed * speed + s->spin_drag_Nms2 * fabs(w) * w * w;
}

#endif
