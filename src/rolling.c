/*
 * The exact rolling model (docs/physics.md §2): one degree of freedom, and the
 * energy integral gives w^2(th) in closed form, so N and F are functions of th
 * alone. The first N = 0 and the first |F| = mu_s N are found along th by the
 * provable crossing search of scan.c on the polynomial forms built in model.c.
 */
#include "internal.h"

#include <math.h>

#define ROLL_ROOT_TOL_RAD 1e-12

const char *jc_rolling_end_name(jc_RollingEnd end)
{
    switch (end) {
    case JC_ROLLING_END_RAMP_END: return "ramp_end";
    case JC_ROLLING_END_TURN_BACK: return "turn_back";
    case JC_ROLLING_END_RAMP_TOP: return "ramp_top";
    case JC_ROLLING_END_AT_REST: return "at_rest";
    }
    return "unknown";
}

/* U at th given by its sine and cosine. */
static double potential(const jc_Model *m, double th, double s, double c)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m;
    return M * m->setup.gravity_mps2 * ((r + d * c) * m->cos_incline - (r * th + d * s) * m->sin_incline);
}

/* The rolling law (rolling_law.h) of model m, with its resistances when
 * loaded is 1, at th given by its sine and cosine. */
static void law_at(const jc_Model *m, int loaded, double s, double c, double w, int dir, double *thdd,
                   double *normal, double *friction)
{
    const jc_ModelTables *tb = jc_model_tables(m);
    jc_RollForces f;
    jc_roll_law(loaded ? &tb->roll : &tb->roll_bare, s, c, w, dir, &f);
    *thdd = f.thdd_radps2;
    *normal = f.normal_N;
    *friction = f.friction_N;
}

/* Direction of motion along th at the start (th0 given by its sine and
 * cosine); 0 if at rest in equilibrium. */
static int start_direction(const jc_Model *m, double s0, double c0)
{
    const double w0 = m->setup.omega0_radps;
    if (w0 != 0.0) return w0 > 0.0 ? 1 : -1;
    double a0, n, f;
    law_at(m, 0, s0, c0, 0.0, 0, &a0, &n, &f);
    return a0 > 0.0 ? 1 : (a0 < 0.0 ? -1 : 0);
}

void jc_rolling_forces(const jc_Model *m, double th, double w, double *thdd, double *normal, double *friction)
{
    law_at(m, 0, sin(th), cos(th), w, 0, thdd, normal, friction);
}

void jc_rolling_at(const jc_Model *m, double th, double w, int dir, double *thdd, double *normal, double *friction)
{
    double s, c;
    jc_sincos(th, &s, &c);
    law_at(m, jc_model_has_resistance(m), s, c, w, dir, thdd, normal, friction);
}

int jc_rolling_state(const jc_Model *m, double th, jc_RollingState *out, char *err, size_t err_len)
{
    if (!isfinite(th))
        return jc_fail(err, err_len, JC_EINVAL, "angle %g rad is not a finite number", th);
    const double th0 = m->setup.theta0_rad, w0 = m->setup.omega0_radps;
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m;
    const double g = m->setup.gravity_mps2;
    /* One inline sincos for th and one for th0, shared by every term below. */
    double s, c, s0, c0;
    jc_sincos(th, &s, &c);
    jc_sincos(th0, &s0, &c0);
    const double ip = jc_rolling_inertia_p(m, c), ip0 = jc_rolling_inertia_p(m, c0);
    const double u0 = potential(m, th0, s0, c0), u = potential(m, th, s, c);
    double two_ke = ip0 * w0 * w0 + 2.0 * (u0 - u);
    /* Tolerate rounding at a turning point, where w^2 is exactly 0. */
    const double slack = 1e-12 * (ip0 * w0 * w0 + 2.0 * M * g * (r + d) * (1.0 + fabs(th - th0)));
    if (two_ke < -slack)
        return jc_fail(err, err_len, JC_EINVAL,
                       "angle %g rad is out of reach of the rolling motion (w^2 = %g rad^2/s^2 < 0 there)",
                       th, two_ke / ip);
    if (two_ke < 0.0) two_ke = 0.0;
    const double w2 = two_ke / ip;
    out->theta_rad = th;
    out->omega_radps = start_direction(m, s0, c0) * sqrt(w2);
    law_at(m, 0, s, c, out->omega_radps, 0, &out->alpha_radps2, &out->normal_N, &out->friction_N);
    out->x_m = r * (th - th0);
    out->kinetic_J = 0.5 * two_ke;
    out->potential_J = u - u0;
    return JC_OK;
}

static int fill_crossing(const jc_Model *m, const jc_ScanHit *hit, jc_RollingCrossing *c,
                         char *err, size_t err_len)
{
    c->found = 1;
    c->grazing = hit->grazing;
    return jc_rolling_state(m, hit->theta, &c->state, err, err_len);
}

enum { WATCH_NORMAL, WATCH_SLIP_POS, WATCH_SLIP_NEG, WATCH_ENERGY, WATCH_COUNT };

int jc_rolling_predict(const jc_Model *m, jc_RollingResult *out, char *err, size_t err_len)
{
    *out = (jc_RollingResult){0};
    const double th0 = m->setup.theta0_rad;
    double s0, c0;
    jc_sincos(th0, &s0, &c0);
    const int dir = start_direction(m, s0, c0);

    /* N, mu_s N -/+ F and I_P w^2, all cleared of I_P^2: rolling holds while all are > 0. */
    jc_RollingPath path;
    jc_rolling_path_init(m, th0, m->setup.omega0_radps, &path);
    const jc_TrigLin *watch[WATCH_COUNT] = {&path.normal, &path.slip_pos, &path.slip_neg, &path.energy};
    /* The turning point is watched only along a path that goes downhill. */
    int active[WATCH_COUNT] = {1, 1, 1, dir > 0};

    /* Uphill or at rest, the path is only the start point. */
    double th_end = dir > 0 ? m->theta_end_rad : th0;
    out->end = dir > 0 ? JC_ROLLING_END_RAMP_END : (dir < 0 ? JC_ROLLING_END_RAMP_TOP : JC_ROLLING_END_AT_REST);
    out->end_theta_rad = th_end;

    /* One prepared set for both scans (to the first event, then on past a
     * slip for the lift-off): its bounds are computed once. */
    jc_ScanSet set = {WATCH_COUNT, {watch[0], watch[1], watch[2], watch[3]}, {1.0, 1.0, 1.0, 1.0}};
    jc_TrigScan scan;
    jc_trig_scan_init(&scan, &set);
    double th = th0;
    while (active[WATCH_NORMAL] || active[WATCH_SLIP_POS]) {
        unsigned mask = 0;
        for (int i = 0; i < WATCH_COUNT; ++i) mask |= active[i] ? 1u << i : 0u;
        jc_ScanHit hit;
        int st = jc_trig_scan_run(&scan, mask, th, th_end, ROLL_ROOT_TOL_RAD, &hit, err, err_len);
        if (st != JC_OK) return st;
        if (hit.index < 0) break;
        th = hit.theta;
        switch (hit.index) {
        case WATCH_NORMAL:
            active[WATCH_NORMAL] = 0;
            st = fill_crossing(m, &hit, &out->liftoff, err, err_len);
            break;
        case WATCH_SLIP_POS:
        case WATCH_SLIP_NEG:
            active[WATCH_SLIP_POS] = active[WATCH_SLIP_NEG] = 0;
            st = fill_crossing(m, &hit, &out->slip, err, err_len);
            break;
        case WATCH_ENERGY:
            out->end = JC_ROLLING_END_TURN_BACK;
            out->end_theta_rad = th;
            active[WATCH_NORMAL] = active[WATCH_SLIP_POS] = 0;
            break;
        }
        if (st != JC_OK) return st;
    }
    out->end_x_m = m->body.radius_m * (out->end_theta_rad - th0);
    return JC_OK;
}

/* A polynomial of degree 1 at th given by its sine and cosine: the sums of
 * jc_tl_value, term for term (its higher terms add exact zeros). */
static double value_deg1(const jc_TrigLin *p, double th, double s, double c)
{
    const double t0 = p->c0[0] + (p->c0[1] * c + p->s0[1] * s);
    const double t1 = p->c1[0] + (p->c1[1] * c + p->s1[1] * s);
    return t0 + th * t1;
}

void jc_rolling_path_init(const jc_Model *m, double th, double w, jc_RollingPath *p)
{
    const jc_ModelTables *tb = jc_model_tables(m);
    /* I_P and U (both of degree 1, model.c) from one inline sincos, where
     * jc_tl_value made one each; the same sums, the same e. */
    double s, c;
    jc_sincos(th, &s, &c);
    const double e = value_deg1(&tb->inertia_p_poly, th, s, c) * w * w +
                     2.0 * value_deg1(&tb->potential_poly, th, s, c);
    /* energy = e - 2 U(th) */
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k) {
        p->energy.c0[k] = -2.0 * tb->potential_poly.c0[k];
        p->energy.s0[k] = -2.0 * tb->potential_poly.s0[k];
        p->energy.c1[k] = -2.0 * tb->potential_poly.c1[k];
        p->energy.s1[k] = -2.0 * tb->potential_poly.s1[k];
    }
    p->energy.c0[0] += e;
    jc_tl_axpby(&p->normal, 1.0, &tb->roll_normal_a, e, &tb->roll_normal_b);
    jc_tl_axpby(&p->friction, 1.0, &tb->roll_friction_a, e, &tb->roll_friction_b);
    jc_tl_axpby(&p->slip_pos, m->setup.mu_static, &p->normal, -1.0, &p->friction);
    jc_tl_axpby(&p->slip_neg, m->setup.mu_static, &p->normal, 1.0, &p->friction);
    p->inertia = &tb->inertia_p_poly;
}
