/*
 * Air and rolling resistance (docs/physics.md, "Air and rolling resistance"),
 * included by internal.h.
 * All optional; with every coefficient 0 the simulator keeps its closed forms
 * and these loads are never evaluated. In rolling they are those of the
 * rolling law (rolling_law.h), at the rolling velocity; here, those of
 * sliding and flight, at any velocity.
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
 * static check with the full lever, rolling_phase.c); the motion from there
 * takes the ramp, 0 at w = 0.
 */
#ifndef JUMPCYL_AIR_H
#define JUMPCYL_AIR_H

#include "rolling_law.h"

#include <math.h>

/* The loads beyond gravity and the contact force. */
typedef struct {
    double fx_N, fy_N;       /* air force, acting at the centre C */
    double torque_Nm;        /* about G, th sense: the air force's moment plus spin drag */
    double rr_torque_per_N;  /* rolling resistance torque per newton of N (-b sgn w) */
    double air_power_W;      /* rate of energy lost to the air, >= 0 */
} jc_Loads;

/* The loads at angle th given by its sine and cosine. Inline: they run at
 * every stage of every step of the sliding phase with resistance. */
static inline void jc_loads_at(const jc_Model *m, double sin_th, double cos_th, double vx, double vy, double w, jc_Loads *out)
{
    const jc_Setup *s = &m->setup;
    const double d = m->body.cm_offset_m;
    /* Not hypot, a call into libm: velocities here are far from overflow.
     * In contact (vy = 0) no square root at all: sqrt(vx^2) is |vx| to the
     * last bit (unless vx^2 underflows, below 1e-154 m/s), and the root's
     * latency would hold up every stage of the sliding phase with drag. */
    const double speed = vy == 0.0 ? fabs(vx) : sqrt(vx * vx + vy * vy);
    const double r = m->body.radius_m;
    const double cd = s->drag_coefficient, cl = s->lift_coefficient;
    /* spin ratio r w / |v| clamped to [-1, 1] (0 when the centre is at rest);
     * only the Magnus force uses it: without lift its division is skipped
     * (it waits for the square root above, at every stage of every step). */
    const double spin = cl == 0.0 ? 0.0 : (fabs(r * w) >= speed ? (w > 0.0) - (w < 0.0) : r * w / speed);
    const double roll = jc_rr_ramp(w);
    const double q = 0.5 * s->air_density_kgpm3 * 2.0 * m->body.radius_m * s->length_m * speed;
    out->fx_N = q * (-cd * vx + cl * spin * vy);
    out->fy_N = q * (-cd * vy - cl * spin * vx);
    /* Torque about G in the th sense (clockwise-positive): the moment of the
     * air force acting at C, R = C - G = -d (sin th, cos th), plus spin drag;
     * grouped so that the forces pass two operations only. */
    out->torque_Nm = ((d * sin_th) * out->fy_N - s->spin_drag_Nms2 * w * fabs(w)) - (d * cos_th) * out->fx_N;
    out->rr_torque_per_N = -s->rolling_resistance_m * roll;
    /* Power lost to the air: drag on the centre and spin drag (Magnus does no work). */
    out->air_power_W = q * cd * speed * speed + s->spin_drag_Nms2 * fabs(w) * w * w;
}

/* The air loads at any velocity (flight) by constants of the model taken
 * once per phase, not at every stage: the same as jc_loads_at without
 * rolling resistance (no contact); tests/sim/test_rolling_law.c checks them
 * against it. */
typedef struct {
    double r_m, d_m;
    double qcd_kgpm, qcl_kgpm; /* 1/2 rho A C_d, 1/2 rho A C_L */
    double spin_drag_Nms2;
} jc_AirConsts;

static inline void jc_air_consts(const jc_Model *m, jc_AirConsts *k)
{
    const jc_Setup *s = &m->setup;
    const double half_rho_area = 0.5 * s->air_density_kgpm3 * 2.0 * m->body.radius_m * s->length_m;
    k->r_m = m->body.radius_m;
    k->d_m = m->body.cm_offset_m;
    k->qcd_kgpm = half_rho_area * s->drag_coefficient;
    k->qcl_kgpm = half_rho_area * s->lift_coefficient;
    k->spin_drag_Nms2 = s->spin_drag_Nms2;
}

/* The air force (fx, fy) at C, its torque about G with spin drag, and the
 * power lost to the air, as jc_loads_at has them. */
static inline void jc_air_loads(const jc_AirConsts *k, double sin_th, double cos_th, double vx, double vy, double w,
                                double *fx_N, double *fy_N, double *torque_Nm, double *air_power_W)
{
    const double speed = vy == 0.0 ? fabs(vx) : sqrt(vx * vx + vy * vy);
    const double rw = k->r_m * w;
    const double spin = k->qcl_kgpm == 0.0 ? 0.0 : (fabs(rw) >= speed ? (w > 0.0) - (w < 0.0) : rw / speed);
    /* The forces per unit speed, and their moment, do not wait for the
     * speed's square root (without lift: with it the spin ratio does);
     * after the root, one product for each force and a product and a
     * difference for the torque d (sin th fy - cos th fx) - k w |w|: the
     * stages each wait for the last one's rates. */
    const double fx1 = -k->qcd_kgpm * vx + k->qcl_kgpm * spin * vy;
    const double fy1 = -k->qcd_kgpm * vy - k->qcl_kgpm * spin * vx;
    const double moment1 = (k->d_m * sin_th) * fy1 - (k->d_m * cos_th) * fx1;
    *fx_N = speed * fx1;
    *fy_N = speed * fy1;
    *torque_Nm = speed * moment1 - k->spin_drag_Nms2 * w * fabs(w);
    *air_power_W = k->qcd_kgpm * speed * speed * speed + k->spin_drag_Nms2 * fabs(w) * w * w;
}

#endif
