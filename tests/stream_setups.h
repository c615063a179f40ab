/* The runs the streaming tests share (tests/sim/test_stream.c,
 * tests/test_sim_json.c).
 *
 * rocking_hoop_setup: the `rocking-hoop` preset (a 10 g hoop of radius
 * 10 cm with a 100 g point mass on its rim, on a floor, mass on top, spun
 * at 0.1 rad/s, mu 0.5) with restitution 1: hundreds of slip and stick
 * events. */
#ifndef JC_STREAM_SETUPS_H
#define JC_STREAM_SETUPS_H

#include <jumpcyl/jumpcyl.h>

static inline jc_Setup rocking_hoop_setup(void)
{
    jc_Setup s = jc_paper_setup();
    if (jc_preset_setup("rocking-hoop", &s, NULL, 0) != JC_OK) return s; /* the caller's run then fails its checks */
    s.restitution = 1.0;
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
