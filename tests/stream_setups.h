/* The runs the streaming tests share (tests/sim/test_stream.c,
 * tests/test_sim_json.c).
 *
 * hoop_parts_setup: today's `hoop` preset built from explicit parts, a 10 g
 * hoop of radius 10 cm with a 100 g point mass on its rim, on a floor, mass
 * on top, spun at 0.1 rad/s, mu 0.5, restitution 1: hundreds of slip and
 * stick events. Written out (not jc_preset_setup("hoop")) so that the tests
 * keep their run when the preset changes. */
#ifndef JC_STREAM_SETUPS_H
#define JC_STREAM_SETUPS_H

#include <jumpcyl/jumpcyl.h>

static inline jc_Setup hoop_parts_setup(void)
{
    jc_Setup s = jc_paper_setup();
    s.body = (jc_BodyDef){0};
    s.body.radius_m = 0.10;
    s.body.part_count = 2;
    s.body.parts[0] = (jc_Part){JC_PART_HOOP, 0.010, 0.0, 0.0, 0.10};
    s.body.parts[1] = (jc_Part){JC_PART_POINT, 0.100, 0.10, 0.0, 0.0};
    s.incline_rad = 0.0;
    s.mu_static = s.mu_kinetic = 0.5;
    s.restitution = 1.0;
    s.omega0_radps = 0.1;
    s.theta0_rad = 0.0;
    s.ramp_length_m = 3.0;
    s.paper_cm_offset_m = 0.0;
    return s;
}

/* The paper's cylinder under 1000 m/s^2 with little friction and bouncy
 * impacts on a 30 m ramp: a lift-off, a dozen bounces, and the ramp's end
 * reached in flight (the event that waits behind a held bounce). */
static inline jc_Setup bouncing_setup(void)
{
    jc_Setup s = jc_paper_setup();
    s.gravity_mps2 = 1000.0;
    s.mu_static = s.mu_kinetic = 0.05;
    s.restitution = 0.9;
    s.ramp_length_m = 30.0;
    return s;
}

#endif
