/*
 * The rolling law (src/rolling_law.h), with loads, against Newton-Euler for
 * the rigid body written here from docs/physics.md §2.1 and §9.1: the loads
 * computed from their definitions, the contact force (F, N) acting a lever
 * b_s ahead of the contact point, M a_G = M g + (F + F_x, N + F_y) and
 * I_G th'' = the moments about G; the law's th'', N and F must satisfy all
 * three equations to rounding, over random setups, angles and spins
 * (w = 0 with either direction, spins inside the rolling-resistance band).
 * Without loads the law must be the closed form of physics.md §2.5 and
 * §2.6 to the last bit (the resistance-free outputs depend on it). And the
 * air loads of flight (jc_air_loads) against jc_loads_at.
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

/* A spin: 0, inside the rolling-resistance band, or anything. */
static double random_spin(void)
{
    const double pick = uniform(0.0, 1.0);
    return pick < 0.1 ? 0.0 : (pick < 0.3 ? uniform(-2e-3, 2e-3) : uniform(-60.0, 60.0));
}

/* The residuals of Newton-Euler for the law's answer at (th, w), relative to
 * the scale of the forces and moments involved. */
static int check_newton_euler(const jc_Model *m, double th, double w, int dir)
{
    const jc_Setup *st = &m->setup;
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m, ig = m->body.inertia_g_kgm2;
    const double g = st->gravity_mps2, sa = sin(st->incline_rad), ca = cos(st->incline_rad);
    const double s = sin(th), c = cos(th);
    /* physics.md §9.1 at v = (r w, 0): spin ratio 1 */
    const double area = 2.0 * r * st->length_m, v = r * w, q = 0.5 * st->air_density_kgpm3 * area * fabs(v);
    const double spin = (w > 0.0) - (w < 0.0);
    const double fx = -q * st->drag_coefficient * v;
    const double fy = -q * st->lift_coefficient * spin * v;
    const double ramp = w == 0.0 ? dir : fmax(-1.0, fmin(1.0, w / 1e-3));
    const double bs = st->rolling_resistance_m * ramp;
    const double couple = -st->spin_drag_Nms2 * w * fabs(w);

    const jc_RollConsts *k = &jc_model_tables(m)->roll;
    jc_RollForces f;
    jc_roll_law(k, s, c, w, dir, &f);
    const double a = f.thdd_radps2, N = f.normal_N, F = f.friction_N;
    /* a_G from the rolling constraint (§2.1) */
    const double agx = a * (r + d * c) - w * w * d * s, agy = -a * d * s - w * w * d * c;
    const double res_x = M * agx - (M * g * sa + F + fx);
    const double res_y = M * agy - (-M * g * ca + N + fy);
    /* Moments about G, th sense (clockwise): of (F, N) at P + (b_s, 0), of
     * the air force at C, and spin drag. */
    const double res_m = ig * a - ((d * s - bs) * N - (r + d * c) * F + d * s * fy - d * c * fx + couple);
    const double force_scale = M * g + M * d * w * w + fabs(fx) + fabs(fy) + M * (r + d) * fabs(a);
    ENSURE_NEAR(res_x, 0.0, 1e-13 * force_scale);
    ENSURE_NEAR(res_y, 0.0, 1e-13 * force_scale);
    ENSURE_NEAR(res_m, 0.0, 1e-13 * (force_scale * (r + d) + fabs(couple) + ig * fabs(a)));
    /* What the law reports of its loads, and rolling.c's route to it. */
    ENSURE_NEAR(f.fx_N, fx, 1e-14 * (fabs(fx) + 1e-300));
    ENSURE_NEAR(f.rr_m, bs, 1e-15 * st->rolling_resistance_m);
    double a2, n2, f2;
    jc_rolling_at(m, th, w, dir, &a2, &n2, &f2);
    ENSURE_NEAR(a2, a, 1e-13 * (fabs(a) + force_scale * (r + d) / ig));
    ENSURE_NEAR(n2, N, 1e-13 * force_scale);
    ENSURE_NEAR(f2, F, 1e-13 * force_scale);
    return 0;
}

/* The closed form of physics.md §2.5 and §2.6, written as printed. */
static void closed_form(const jc_Model *m, double s, double c, double w, double *a, double *n, double *fr)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m, g = m->setup.gravity_mps2;
    const double sa = m->sin_incline, ca = m->cos_incline, w2 = w * w;
    const double ip = m->body.inertia_c_kgm2 + M * r * r + 2.0 * M * r * d * c;
    const double q = (r + d * c) * sa + d * s * ca;
    *a = (M * g * q + M * r * d * s * w2) / ip;
    *n = M * (g * ca - d * s * *a - d * c * w2);
    *fr = M * ((r + d * c) * *a - d * s * w2 - g * sa);
}

static int check_closed_form(const jc_Model *m, double th, double w, int dir)
{
    const double s = sin(th), c = cos(th);
    double a, n, fr;
    closed_form(m, s, c, w, &a, &n, &fr);
    jc_RollForces f;
    jc_roll_law(&jc_model_tables(m)->roll_bare, s, c, w, dir, &f);
    /* to the last bit: the numbers themselves, not within a tolerance */
    ENSURE(f.thdd_radps2 == a && f.normal_N == n && f.friction_N == fr);
    double a2, n2, f2;
    jc_rolling_forces(m, th, w, &a2, &n2, &f2);
    ENSURE(a2 == a && n2 == n && f2 == fr);
    return 0;
}

static int check_air_loads(const jc_Model *m, double th, double w, double pick)
{
    const double s = sin(th), c = cos(th), r = m->body.radius_m;
    const double vx = uniform(-10.0, 10.0), vy = pick < 0.2 ? 0.0 : uniform(-10.0, 10.0);
    jc_AirConsts a;
    jc_air_consts(m, &a);
    double fx, fy, torque, power;
    jc_air_loads(&a, s, c, vx, vy, w, &fx, &fy, &torque, &power);
    jc_Loads l;
    jc_loads_at(m, s, c, vx, vy, w, &l);
    const double v2 = vx * vx + vy * vy + r * r * w * w;
    const double air_force_scale = (a.qcd_kgpm + fabs(a.qcl_kgpm)) * v2 + 1e-300;
    ENSURE_NEAR(fx, l.fx_N, 1e-12 * air_force_scale);
    ENSURE_NEAR(fy, l.fy_N, 1e-12 * air_force_scale);
    ENSURE_NEAR(torque, l.torque_Nm, 1e-12 * (air_force_scale * m->body.cm_offset_m + a.spin_drag_Nms2 * w * w));
    ENSURE_NEAR(power, l.air_power_W, 1e-12 * (air_force_scale * sqrt(v2) + a.spin_drag_Nms2 * fabs(w) * w * w));
    return 0;
}

static jc_Setup random_setup(int trial)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = uniform(0.0, 1.2);
    s.drag_coefficient = uniform(0.0, 2.0);
    s.lift_coefficient = trial % 3 == 0 ? 0.0 : uniform(-1.0, 1.0);
    s.air_density_kgpm3 = uniform(0.5, 1.5);
    s.length_m = uniform(0.01, 0.5);
    s.spin_drag_Nms2 = trial % 4 == 0 ? 0.0 : uniform(0.0, 1e-4);
    s.rolling_resistance_m = trial % 5 == 0 ? 0.0 : uniform(0.0, 1e-3);
    return s;
}

/* A law's check at 2000 random states of each of 50 random setups; with
 * bare_odd, every other setup has no resistances (the resistance-free law
 * of a model with resistances, and of one without). pick is uniform in
 * [0, 1): the check's own choice. */
typedef int state_check(const jc_Model *m, double th, double w, double pick);

static int over_random_states(int bare_odd, state_check *check)
{
    for (int trial = 0; trial < 50; ++trial) {
        jc_Setup s = random_setup(trial);
        if (bare_odd && trial % 2)
            s.drag_coefficient = s.lift_coefficient = s.spin_drag_Nms2 = s.rolling_resistance_m = 0.0;
        jc_Model m;
        if (sim_model(&m, &s)) return 1;
        for (int i = 0; i < 2000; ++i) {
            const double th = uniform(-20.0, 20.0), w = random_spin();
            if (check(&m, th, w, uniform(0.0, 1.0))) return 1;
        }
    }
    return 0;
}

static int newton_euler_either_way(const jc_Model *m, double th, double w, double pick)
{
    return check_newton_euler(m, th, w, pick < 0.5 ? -1 : 1);
}

static int closed_form_either_way(const jc_Model *m, double th, double w, double pick)
{
    return check_closed_form(m, th, w, pick < 0.5 ? -1 : 1);
}

static int test_law_with_loads(void) { return over_random_states(0, newton_euler_either_way); }

static int test_law_without_loads(void) { return over_random_states(1, closed_form_either_way); }

static int test_air_loads(void) { return over_random_states(0, check_air_loads); }

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_law_with_loads);
    RUN_TEST(test_law_without_loads);
    RUN_TEST(test_air_loads);
    TEST_MAIN_END();
}
