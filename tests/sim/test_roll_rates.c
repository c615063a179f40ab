/*
 * The rolling phase's right-hand side with air and rolling resistance
 * (jc_roll_rates, air.h: constants taken once per phase) against the
 * general route it replaces at every stage, jc_loads_at and
 * jc_rolling_accel by way of jc_rolling_at_sc: th'', N, the two loss
 * rates, and F (jc_roll_forces, for the phase's events); and the air loads
 * of flight (jc_air_loads) against jc_loads_at; over random angles, spins and loads, including w = 0 and spins
 * inside the rolling-resistance band. They differ by rounding only.
 */
#include "sim_common.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <stdint.h>

static uint64_t rng_state = 0x9e3779b97f4a7c15ULL;

static double uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) / 9007199254740992.0;
}

static int check_model(const jc_Model *m)
{
    jc_RollConsts k;
    jc_roll_consts(m, &k);
    const double M = m->body.mass_kg, g = m->setup.gravity_mps2, r = m->body.radius_m;
    for (int i = 0; i < 2000; ++i) {
        const double th = uniform(-20.0, 20.0);
        const int dir = uniform(0.0, 1.0) < 0.5 ? -1 : 1;
        const double pick = uniform(0.0, 1.0);
        const double w = pick < 0.1 ? 0.0 : (pick < 0.3 ? uniform(-2e-3, 2e-3) : uniform(-60.0, 60.0));
        const double s = sin(th), c = cos(th);
        double thdd, n, f, thdd2, n2, air, rr, thdd3, n3, f3;
        jc_Loads l;
        jc_rolling_at_sc(m, s, c, w, dir, &thdd, &n, &f, &l);
        jc_roll_rates(&k, s, c, w, dir, &thdd2, &n2, &air, &rr);
        jc_roll_forces(&k, s, c, w, dir, &thdd3, &n3, &f3);
        /* Scales: the gravity's angular acceleration and force, and the power scale M g r |w|. */
        const double acc_scale = M * g * (r + m->body.cm_offset_m) * (1.0 + w * w / g) / m->body.inertia_c_kgm2;
        const double force_scale = M * g + M * m->body.cm_offset_m * w * w + k.qcd_kgpm * r * r * w * w;
        const double power_scale = (force_scale * r + k.spin_drag_Nms2 * w * w) * fabs(w) + 1e-300;
        ENSURE_NEAR(thdd2, thdd, 1e-12 * acc_scale);
        ENSURE_NEAR(n2, n, 1e-12 * force_scale);
        ENSURE_NEAR(thdd3, thdd, 1e-12 * acc_scale);
        ENSURE_NEAR(n3, n, 1e-12 * force_scale);
        ENSURE_NEAR(f3, f, 1e-12 * force_scale);
        ENSURE_NEAR(air, l.air_power_W, 1e-12 * power_scale);
        ENSURE_NEAR(rr, -l.rr_torque_per_N * n * w, 1e-12 * power_scale);
        /* In flight: any velocity. */
        const double vx = uniform(-10.0, 10.0), vy = pick < 0.2 ? 0.0 : uniform(-10.0, 10.0);
        jc_AirConsts a;
        jc_air_consts(m, &a);
        double fx, fy, torque, power;
        jc_air_loads(&a, s, c, vx, vy, w, &fx, &fy, &torque, &power);
        jc_loads_at(m, s, c, vx, vy, w, &l);
        const double v2 = vx * vx + vy * vy + r * r * w * w;
        const double air_force_scale = (k.qcd_kgpm + fabs(k.qcl_kgpm)) * v2 + 1e-300;
        ENSURE_NEAR(fx, l.fx_N, 1e-12 * air_force_scale);
        ENSURE_NEAR(fy, l.fy_N, 1e-12 * air_force_scale);
        ENSURE_NEAR(torque, l.torque_Nm, 1e-12 * (air_force_scale * m->body.cm_offset_m + k.spin_drag_Nms2 * w * w));
        ENSURE_NEAR(power, l.air_power_W, 1e-12 * (air_force_scale * sqrt(v2) + k.spin_drag_Nms2 * fabs(w) * w * w));
    }
    return 0;
}

static int test_random_loads(void)
{
    for (int trial = 0; trial < 50; ++trial) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = uniform(0.0, 1.2);
        s.drag_coefficient = uniform(0.0, 2.0);
        s.lift_coefficient = trial % 3 == 0 ? 0.0 : uniform(-1.0, 1.0);
        s.air_density_kgpm3 = uniform(0.5, 1.5);
        s.length_m = uniform(0.01, 0.5);
        s.spin_drag_Nms2 = trial % 4 == 0 ? 0.0 : uniform(0.0, 1e-4);
        s.rolling_resistance_m = trial % 5 == 0 ? 0.0 : uniform(0.0, 1e-3);
        jc_Model m;
        if (sim_model(&m, &s)) return 1;
        if (check_model(&m)) return 1;
    }
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_random_loads);
    TEST_MAIN_END();
}
