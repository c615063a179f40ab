/*
 * Newton's impact law (physics.md §4, the named alternative
 * JC_IMPACT_NEWTON), checked against impulses derived here by hand, in a
 * different form from src/impact.c. (Stronge's law, the default, has its own
 * property test: test_impact_law.c.)
 *
 * Notation: rho = G - P = (d sin th, r + d cos th) from the contact point P
 * to the centre of mass G; w clockwise-positive; the velocity of the body
 * point at P is v_P = v_G + w (-rho_y, rho_x) (for a disc, rho = (0, r):
 * v_P = (v_x - r w, v_y)). The impulse J = (Jt, Jn) acts at P.
 *
 * Instead of the library's 2x2 system in (Jt, Jn), the derivation here uses
 * the angular momentum about the contact point, L_P = I_G w + M (rho_y v_Gx -
 * rho_x v_Gy), which no impulse through P changes:
 *
 * Sticking (v_Pt' = 0, v_Pn' = -e v_Pn): v_Gx' = rho_y w', v_Gy' = -e v_Pn -
 * rho_x w', and L_P' = L_P gives
 *   w' = (L_P - M e rho_x v_Pn) / (I_G + M |rho|^2),
 * and then J = M (v_G' - v_G); sticking is the law's answer iff |Jt| <= mu_s Jn.
 *
 * Sliding (Jt = -mu_k s Jn, s = sgn v_Pt): v_G' = v_G + J / M, and L_P' = L_P
 * gives w' = w + Jn (rho_x + mu_k s rho_y) / I_G; restitution on v_Pn gives
 *   Jn = -(1 + e) v_Pn / (1/M + rho_x (rho_x + mu_k s rho_y) / I_G),
 * a Painleve case when the denominator is <= 0.
 *
 * For a uniform disc (rho = (0, r), I_G = M r^2 / 2) this is the textbook
 *   Jn = -(1 + e) M v_y,  stick iff |v_x - r w| <= 3 mu_s (1 + e) |v_y|,
 *   stick: v_x' = r w' = (2 v_x + r w) / 3,
 *   slide: v_x' = v_x - mu_k s Jn / M, w' = w + 2 mu_k s Jn / (M r).
 */
#include "sim_common.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <stdint.h>

/* Post-impact velocities are sums of a few products of O(1..30) numbers: the
 * two computations differ by rounding, ~1e-15 of the largest term. 1e-12 (the
 * brief's tolerance), relative to the speed scale of the case. */
#define VEL_TOL 1e-12

typedef struct {
    double vgx, vgy, w;    /* after */
    double jt, jn;
    int sticks, painleve;
    double cond;           /* sliding: |terms| / |denominator|, 1 when sticking */
} hand_impact;

/* The hand derivation above, for a state touching the incline. */
static void impact_by_hand(const jc_Model *m, const jc_State *s, double e, hand_impact *h)
{
    const double M = m->body.mass_kg, ig = m->body.inertia_g_kgm2, d = m->body.cm_offset_m;
    const double r = m->body.radius_m, th = s->theta_rad, w = s->omega_radps;
    const double rx = d * sin(th), ry = r + d * cos(th); /* rho = G - P */
    double vgx, vgy;
    cm_velocity(m, s, &vgx, &vgy);
    const double vpt = vgx - w * ry, vpn = vgy + w * rx;
    const double lp = ig * w + M * (ry * vgx - rx * vgy);
    *h = (hand_impact){0};
    /* Sticking candidate. */
    const double w1 = (lp - M * e * rx * vpn) / (ig + M * (rx * rx + ry * ry));
    const double vgx1 = ry * w1, vgy1 = -e * vpn - rx * w1;
    const double jt = M * (vgx1 - vgx), jn = M * (vgy1 - vgy);
    if (fabs(jt) <= m->setup.mu_static * jn) {
        *h = (hand_impact){vgx1, vgy1, w1, jt, jn, 1, 0, 1.0};
        return;
    }
    const double sgn = vpt > 0.0 ? 1.0 : -1.0, mu = m->setup.mu_kinetic;
    const double den = 1.0 / M + rx * (rx + mu * sgn * ry) / ig;
    h->cond = (1.0 / M + fabs(rx * (rx + mu * sgn * ry) / ig)) / fabs(den);
    if (den <= 0.0) {
        h->painleve = 1;
        return;
    }
    const double jn2 = -(1.0 + e) * vpn / den, jt2 = -mu * sgn * jn2;
    *h = (hand_impact){vgx + jt2 / M, vgy + jn2 / M, w + jn2 * (rx + mu * sgn * ry) / ig, jt2, jn2, 0, 0, h->cond};
}

static jc_State touching(const jc_Model *m, double th, double vx, double vy, double w)
{
    return (jc_State){.t_s = 0.0, .x_m = 0.1, .y_m = m->body.radius_m, .vx_mps = vx, .vy_mps = vy,
                      .theta_rad = th, .omega_radps = w};
}

/* jc_impact_apply against the hand solution; *sticks reports the outcome. */
static int compare_impact(const jc_Model *m, const jc_State *before, double e, int *sticks, double *dk)
{
    hand_impact h;
    impact_by_hand(m, before, e, &h);
    jc_State s = *before;
    jc_ImpactResult res;
    jc_impact_apply_law(m, &s, JC_IMPACT_NEWTON, e, &res);
    ENSURE_MSG(res.painleve == h.painleve, "painleve: library %d, hand %d (th %g, v %g %g, w %g)", res.painleve,
               h.painleve, before->theta_rad, before->vx_mps, before->vy_mps, before->omega_radps);
    *sticks = h.sticks;
    *dk = 0.0;
    if (h.painleve) return 0;
    ENSURE_MSG(res.sticks == h.sticks, "sticks: library %d, hand %d (th %g, v %g %g, w %g, |Jt| %g, Jn %g)",
               res.sticks, h.sticks, before->theta_rad, before->vx_mps, before->vy_mps, before->omega_radps,
               fabs(h.jt), h.jn);
    const double d = m->body.cm_offset_m, th = before->theta_rad;
    /* The library reports the centre C: v_C = v_G - d w (cos th, -sin th). */
    const double vcx = h.vgx - d * h.w * cos(th), vcy = h.vgy + d * h.w * sin(th);
    /* 1e-12 of the speed scale of the case, plus, near a Painleve case
     * (sliding denominator den -> 0+), the rounding of den amplified by its
     * condition number |terms| / |den|, relative to the (then large) result:
     * ~100 ulp times cond. */
    const double scale = 1.0 + fabs(before->vx_mps) + fabs(before->vy_mps) +
                         (m->body.radius_m + d) * fabs(before->omega_radps) +
                         1e-2 * h.cond * (fabs(h.vgx) + fabs(h.vgy) + (m->body.radius_m + d) * fabs(h.w));
    ENSURE_NEAR(s.vx_mps, vcx, VEL_TOL * scale);
    ENSURE_NEAR(s.vy_mps, vcy, VEL_TOL * scale);
    ENSURE_NEAR(s.omega_radps, h.w, VEL_TOL * scale / m->body.radius_m);
    const double jscale = m->body.mass_kg * scale;
    ENSURE_NEAR(res.impulse_tangent_Ns, h.jt, VEL_TOL * jscale);
    ENSURE_NEAR(res.impulse_normal_Ns, h.jn, VEL_TOL * jscale);
    ENSURE(res.impulse_normal_Ns >= 0.0);
    /* Position and angle do not jump. */
    ENSURE(s.x_m == before->x_m && s.y_m == before->y_m && s.theta_rad == before->theta_rad);
    /* Contact point: approach speed before, rebound e times it after. */
    double vgx, vgy;
    cm_velocity(m, before, &vgx, &vgy);
    const double vpn = vgy + before->omega_radps * d * sin(th);
    ENSURE_NEAR(res.approach_speed_mps, -vpn, VEL_TOL * scale);
    ENSURE_NEAR(res.rebound_speed_mps, -e * vpn, VEL_TOL * scale);
    *dk = my_kinetic(m, &s) - my_kinetic(m, before);
    return 0;
}

static int disc_model(jc_Model *m, double mu_s, double mu_k)
{
    jc_Setup s;
    char err[256] = "";
    ENSURE_OK(jc_preset_setup("disc", &s, err, sizeof err), err);
    s.incline_rad = 0.0;
    s.mu_static = mu_s;
    s.mu_kinetic = mu_k;
    return sim_model(m, &s);
}

/* (a) A uniform disc dropped with spin, by the textbook formulas. */
static int test_disc_stick_and_slide(void)
{
    jc_Model m;
    if (disc_model(&m, 0.5, 0.4)) return 1;
    const double M = m.body.mass_kg, r = m.body.radius_m, e = 0.3;

    /* Stick: u_t = 0.5 - 0.3 = 0.2 <= 3 * 0.5 * 1.3 * 1.0 = 1.95. */
    jc_State s = touching(&m, 0.7, 0.5, -1.0, 3.0);
    jc_ImpactResult res;
    const jc_State before = s;
    jc_impact_apply(&m, &s, e, &res);
    ENSURE(res.sticks && !res.painleve);
    ENSURE_NEAR(s.vx_mps, (2.0 * 0.5 + r * 3.0) / 3.0, VEL_TOL);
    ENSURE_NEAR(s.omega_radps, (2.0 * 0.5 / r + 3.0) / 3.0, VEL_TOL / r);
    ENSURE_NEAR(s.vy_mps, 0.3, VEL_TOL);
    ENSURE_NEAR(res.impulse_normal_Ns, 1.3 * M, VEL_TOL * M);
    ENSURE_NEAR(res.impulse_tangent_Ns, -M * 0.2 / 3.0, VEL_TOL * M);
    ENSURE_MSG(my_kinetic(&m, &s) <= my_kinetic(&m, &before), "sticking impact gained energy");

    /* Slide: u_t = 2 + 1 = 3 > 3 * 0.5 * 1.3 * 1.0; Jt = -0.4 Jn. */
    s = touching(&m, 2.0, 2.0, -1.0, -10.0);
    jc_impact_apply(&m, &s, e, &res);
    const double jn = 1.3 * M;
    ENSURE(!res.sticks && !res.painleve);
    ENSURE_NEAR(s.vx_mps, 2.0 - 0.4 * jn / M, VEL_TOL);
    ENSURE_NEAR(s.omega_radps, -10.0 + 2.0 * 0.4 * jn / (M * r), VEL_TOL / r);
    ENSURE_NEAR(s.vy_mps, 0.3, VEL_TOL);

    /* Slide the other way: u_t = -1 - 0.5 = -1.5 (vy -0.2: 3 mu (1+e) |vy| = 0.39). */
    s = touching(&m, 0.0, -1.0, -0.2, 5.0);
    jc_impact_apply(&m, &s, e, &res);
    const double jn3 = 1.3 * 0.2 * M;
    ENSURE(!res.sticks);
    ENSURE_NEAR(s.vx_mps, -1.0 + 0.4 * jn3 / M, VEL_TOL);
    ENSURE_NEAR(s.omega_radps, 5.0 - 2.0 * 0.4 * jn3 / (M * r), VEL_TOL / r);
    return 0;
}

/* Deterministic pseudo-random numbers (xorshift64*), uniform in [lo, hi). */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(double lo, double hi) { return test_uniform(&rng_state, lo, hi); }

/* A random approaching state: v_Pn < 0. */
static jc_State random_approach(const jc_Model *m)
{
    for (;;) {
        const jc_State s = touching(m, uniform(0.0, 2.0 * PI), uniform(-3.0, 3.0), uniform(-3.0, 1.0),
                                    uniform(-40.0, 40.0));
        double vgx, vgy;
        cm_velocity(m, &s, &vgx, &vgy);
        if (vgy + s.omega_radps * m->body.cm_offset_m * sin(s.theta_rad) < -1e-3) return s;
    }
}

/* (a') the disc against the hand solution over random states and e. */
static int test_disc_random(void)
{
    const double es[] = {0.0, 0.3, 0.5, 1.0};
    int stick = 0, slide = 0;
    for (int k = 0; k < 4; ++k) {
        jc_Model m;
        const double mu_s = uniform(0.0, 1.5);
        if (disc_model(&m, mu_s, uniform(0.0, mu_s))) return 1;
        for (int i = 0; i < 2000; ++i) {
            const jc_State s = random_approach(&m);
            int sticks;
            double dk;
            if (compare_impact(&m, &s, es[i % 4], &sticks, &dk)) return 1;
            if (sticks) {
                /* For a disc the sticking impact never adds energy: with K
                 * diagonal, 2 dK = -(M/3) u_t^2 - M (1 - e^2) v_y^2 <= 0. */
                ENSURE_MSG(dk <= 1e-15, "disc sticking impact gained %g J", dk);
                stick++;
            } else {
                slide++;
            }
        }
    }
    ENSURE_MSG(stick > 500 && slide > 500, "stick %d, slide %d cases", stick, slide);
    return 0;
}

/* (b) An eccentric body (the paper's) against the hand solution. */
static int test_eccentric_random(void)
{
    const double es[] = {0.0, 0.3, 0.5, 1.0};
    int stick = 0, slide = 0, painleve = 0, gained = 0;
    double worst_gain = 0.0;
    for (int k = 0; k < 8; ++k) {
        jc_Setup su = paper_at(0.0, 0.5);
        su.mu_static = uniform(0.0, 2.0);
        su.mu_kinetic = k % 2 ? su.mu_static : uniform(0.0, su.mu_static);
        jc_Model m;
        if (sim_model(&m, &su)) return 1;
        for (int i = 0; i < 2000; ++i) {
            const jc_State s = random_approach(&m);
            const double e = es[i % 4];
            int sticks;
            double dk;
            hand_impact h;
            impact_by_hand(&m, &s, e, &h);
            if (compare_impact(&m, &s, e, &sticks, &dk)) return 1;
            if (h.painleve) {
                painleve++;
                continue;
            }
            if (!sticks) {
                slide++;
                continue;
            }
            stick++;
            const double k0 = my_kinetic(&m, &s);
            if (e == 0.0) {
                /* Plastic and sticking: the contact point stops, and the
                 * kinetic energy drops by v_P^T K^-1 v_P / 2 >= 0. */
                ENSURE_MSG(dk <= 1e-14 * k0, "plastic sticking impact gained %g J of %g J", dk, k0);
            } else if (dk > 1e-14 * k0) {
                gained++;
                worst_gain = fmax(worst_gain, dk / k0);
            }
        }
    }
    printf("  eccentric: %d stick, %d slide, %d Painleve; sticking impacts with e > 0 that gained energy: %d "
           "(largest gain %.3g of K)\n", stick, slide, painleve, gained, worst_gain);
    ENSURE_MSG(stick > 500 && slide > 500, "stick %d, slide %d cases", stick, slide);
    return 0;
}

/* Newton restitution with a sticking tangential impulse on an eccentric
 * body: 2 dK = -(A u_t^2 + 2 B u_t u_n + C (1 - e^2) u_n^2) with
 * [[A, B], [B, C]] = K^-1 the effective mass at P. With e > 0 and B != 0
 * this can be positive: a known property of the Newton + Coulomb impact law
 * (the energetic inconsistency noted by Kane and by Stronge), not of the
 * code. The test documents it: the library's sticking result for such a
 * state equals the hand solution and gains exactly the predicted energy. */
static int test_sticking_energy_gain_is_the_law(void)
{
    jc_Setup su = paper_at(0.0, 2.0);
    jc_Model m;
    if (sim_model(&m, &su)) return 1;
    const double M = m.body.mass_kg, ig = m.body.inertia_g_kgm2, d = m.body.cm_offset_m, r = m.body.radius_m;
    const double th = PI / 2, e = 1.0;
    const double rx = d * sin(th), ry = r + d * cos(th);
    /* K (dv_P = K J): dv_G = J / M, dw = (rho_x Jn - rho_y Jt) / I_G, so
     * K = [[1/M + rho_y^2/I_G, -rho_x rho_y/I_G], [-rho_x rho_y/I_G, 1/M + rho_x^2/I_G]],
     * inverted by hand. */
    const double ktt = 1.0 / M + ry * ry / ig, knn = 1.0 / M + rx * rx / ig, ktn = -rx * ry / ig;
    const double det = ktt * knn - ktn * ktn;
    const double A = knn / det, B = -ktn / det;
    /* u_n = -1, u_t chosen to maximise the gain: u_t = -B u_n / A. */
    const double un = -1.0, ut = -B * un / A;
    /* Build the state with these contact velocities and w = 0. */
    const jc_State s = touching(&m, th, ut, un, 0.0);
    int sticks;
    double dk;
    if (compare_impact(&m, &s, e, &sticks, &dk)) return 1;
    ENSURE(sticks);
    const double predicted = -0.5 * (A * ut * ut + 2.0 * B * ut * un + 0.0 * un * un);
    ENSURE_REL(dk, predicted, 1e-9);
    printf("  paper body, th = 90 deg, e = 1, u_t = %.4f m/s, u_n = -1 m/s: sticking impact changes K by %+.6g J "
           "(predicted %+.6g J, K before %.6g J)\n", ut, dk, predicted, my_kinetic(&m, &s));
    /* The same approach under the Darboux-Keller laws: Stronge's loses
     * energy, as it must (physics.md §4); Poisson's, here, too. */
    const double k0 = my_kinetic(&m, &s);
    const jc_ImpactLaw laws[2] = {JC_IMPACT_STRONGE, JC_IMPACT_POISSON};
    double other[2];
    for (int i = 0; i < 2; ++i) {
        jc_State t = s;
        jc_ImpactResult res;
        jc_impact_apply_law(&m, &t, laws[i], e, &res);
        other[i] = my_kinetic(&m, &t) - k0;
    }
    printf("  the same impact: dK/K newton %+.4f, stronge %+.4f, poisson %+.4f\n", dk / k0, other[0] / k0,
           other[1] / k0);
    ENSURE(dk > 0.01 * k0 && other[0] <= 1e-12 * k0);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_disc_stick_and_slide);
    RUN_TEST(test_disc_random);
    RUN_TEST(test_eccentric_random);
    RUN_TEST(test_sticking_energy_gain_is_the_law);
    TEST_MAIN_END();
}
