/*
 * Air and rolling resistance (docs/physics.md, "Air and rolling resistance").
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
#include "internal.h"

#include <math.h>

int jc_model_has_resistance(const jc_Model *m) { return jc_model_tables(m)->has_resistance; }

/* jc_loads_at itself is in internal.h, inline: it runs at every stage of
 * every step of the drag runs' phases (measured with callgrind: a drag run
 * 1.318M -> 1.227M instructions once inlined). */
