/*
 * Air and rolling resistance (docs/physics.md, "Air and rolling resistance").
 * All optional; with every coefficient 0 the simulator keeps its closed forms
 * and these loads are never evaluated.
 *
 * - Drag through the centre C, against its velocity v: -1/2 rho C_d A |v| v,
 *   A = 2 r L (diameter times length, the frontal area in cross-flow).
 * - Magnus force perpendicular to v: 1/2 rho C_L A |v| sgn(w) (vy, -vx).
 *   For a cylinder rolling downhill (w > 0, v along +x) this is (0, -...):
 *   C_L > 0 pushes it into the incline, as topspin pushes a real cylinder.
 *   It does no work.
 * - Spin drag: a torque -k w |w| on the rotation.
 * - Rolling resistance: the normal force acts a lever b ahead of the contact
 *   point in the rolling direction, a torque -b sgn(w) N against the rolling.
 */
#include "internal.h"

#include <math.h>

int jc_model_has_resistance(const jc_Model *m) { return jc_setup_has_resistance(&m->setup); }

void jc_loads_at(const jc_Model *m, double th, double vx, double vy, double w, jc_Loads *out)
{
    const jc_Setup *s = &m->setup;
    const double d = m->body.cm_offset_m;
    const double sw = (w > 0.0) - (w < 0.0);
    const double speed = hypot(vx, vy);
    const double q = 0.5 * s->air_density_kgpm3 * 2.0 * m->body.radius_m * s->length_m * speed;
    const double cd = s->drag_coefficient, cl = s->lift_coefficient;
    out->fx_N = q * (-cd * vx + cl * sw * vy);
    out->fy_N = q * (-cd * vy - cl * sw * vx);
    /* Torque about G in the th sense (clockwise-positive): the moment of the
     * air force acting at C, R = C - G = -d (sin th, cos th), plus spin drag. */
    out->torque_Nm = d * sin(th) * out->fy_N - d * cos(th) * out->fx_N - s->spin_drag_Nms2 * w * fabs(w);
    out->rr_torque_per_N = -s->rolling_resistance_m * sw;
    /* Power lost to the air: drag on the centre and spin drag (Magnus does no work). */
    out->air_power_W = q * cd * speed * speed + s->spin_drag_Nms2 * fabs(w) * w * w;
}
