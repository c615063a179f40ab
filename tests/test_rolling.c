/* src/rolling.c (and the polynomials of src/model.c): the exact rolling model.
 *
 * The reference here is a second formulation written in this file: Newton-
 * Euler for the rigid body with the rolling constraint, solved as a 4x4 linear
 * system for (a_C, th'', N, F), the energy of the body computed from the
 * positions and velocities of its centre of mass, and a trajectory integrated
 * with GSL's rk8pd whose finite differences give the contact force. */
#include "test.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_odeiv2.h>

#include "internal.h" /* jc_rolling_path_init: the polynomials of the rolling path */
#include "trig_direct.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

typedef struct {
    double M, r, d, IG, g, sa, ca, th0, w0;
} dyn;

static dyn dyn_of(const jc_Model *m)
{
    const jc_Setup *s = &m->setup;
    return (dyn){m->body.mass_kg, m->body.radius_m, m->body.cm_offset_m, m->body.inertia_g_kgm2,
                 s->gravity_mps2, sin(s->incline_rad), cos(s->incline_rad), s->theta0_rad, s->omega0_radps};
}

/* Centre of mass: C travels r (th - th0) downhill at height r; G = C + d (sin, cos). */
static double xg(const dyn *D, double th) { return D->r * (th - D->th0) + D->d * sin(th); }
static double yg(const dyn *D, double th) { return D->r + D->d * cos(th); }
/* Gravity g (sin a, -cos a): U = -M g . G */
static double pot(const dyn *D, double th) { return D->M * D->g * (yg(D, th) * D->ca - xg(D, th) * D->sa); }

/* Kinetic energy from the CM's velocity, v_G = ((r + d cos th) w, -d sin th w). */
static double kinetic(const dyn *D, double th, double w)
{
    const double vx = (D->r + D->d * cos(th)) * w, vy = -D->d * sin(th) * w;
    return 0.5 * D->M * (vx * vx + vy * vy) + 0.5 * D->IG * w * w;
}

/* w^2 at th from the conservation of that energy (I_P w^2 = 2 KE at w = 1). */
static double omega2(const dyn *D, double th)
{
    const double e0 = kinetic(D, D->th0, D->w0) + pot(D, D->th0);
    return (e0 - pot(D, th)) / kinetic(D, th, 1.0);
}

/* Newton-Euler with rolling. Unknowns (a_C, th'', N, F); th is clockwise in
 * (x downhill, y normal), so I_G th'' = -(torque of the contact force about G)_z,
 * with R = P - G = (-d sin th, -(r + d cos th)):
 *   M (a_C + d cos th th'' - d sin th w^2) = F + M g sin a
 *   M (-d sin th th'' - d cos th w^2)      = N - M g cos a
 *   I_G th''                               = d sin th N - (r + d cos th) F
 *   a_C                                    = r th''                            */
typedef struct {
    double ac, alpha, N, F;
} forces;

static forces newton_euler(const dyn *D, double th, double w2)
{
    const double s = sin(th), c = cos(th), M = D->M, d = D->d, r = D->r;
    double A[16] = {M, M * d * c, 0, -1,
                    0, -M * d * s, -1, 0,
                    0, D->IG, -d * s, r + d * c,
                    1, -r, 0, 0};
    double b[4] = {M * D->g * D->sa + M * d * s * w2, -M * D->g * D->ca + M * d * c * w2, 0, 0};
    double x[4];
    size_t perm_data[4];
    gsl_permutation perm = {4, perm_data};
    gsl_matrix_view Av = gsl_matrix_view_array(A, 4, 4);
    gsl_vector_view bv = gsl_vector_view_array(b, 4), xv = gsl_vector_view_array(x, 4);
    int sign;
    gsl_linalg_LU_decomp(&Av.matrix, &perm, &sign);
    gsl_linalg_LU_solve(&Av.matrix, &perm, &bv.vector, &xv.vector);
    return (forces){x[0], x[1], x[2], x[3]};
}


/* The size of the terms N and F are sums of: rounding is relative to it. */
static double force_scale(const dyn *D, double w2, double alpha)
{
    return D->M * (D->g + D->d * fabs(w2) + (D->r + D->d) * fabs(alpha));
}

static int init(jc_Model *m, const jc_Setup *s)
{
    char err[256] = "";
    ENSURE_OK(jc_model_init(m, s, err, sizeof err), err);
    return 0;
}

static jc_Setup paper_at(double deg, double mu)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = deg * DEG;
    s.mu_static = s.mu_kinetic = mu;
    return s;
}

static jc_Setup preset(const char *name)
{
    jc_Setup s;
    char err[256];
    if (jc_preset_setup(name, &s, err, sizeof err) != JC_OK) s = jc_paper_setup();
    return s;
}

/* Paper body started mid-turn and spinning, on a steeper incline. */
static jc_Setup spinning(void)
{
    jc_Setup s = paper_at(45, 0.8);
    s.theta0_rad = 1.0;
    s.omega0_radps = 3.0;
    return s;
}

/* A heavy point mass near the rim of a light disc, 60 deg. */
static jc_Setup lopsided(void)
{
    jc_Setup s = paper_at(60, 0.9);
    s.body.part_count = 2;
    s.body.parts[0] = (jc_Part){JC_PART_DISC, 0.040, 0.0, 0.0, 0.10};
    s.body.parts[1] = (jc_Part){JC_PART_POINT, 0.060, 0.085, 0.0, 0.0};
    s.paper_cm_offset_m = 0.0;
    return s;
}

/* Paper body on 2 deg, CM at the bottom at rest: it rocks. */
static jc_Setup rocking(void)
{
    jc_Setup s = paper_at(2, 0.5);
    s.theta0_rad = PI;
    return s;
}

/* ---- (a) uniform disc ---- */

static int test_uniform_disc(void)
{
    jc_Setup discs[3];
    discs[0] = preset("disc");
    discs[0].mu_static = discs[0].mu_kinetic = 1e6;
    discs[1] = discs[0]; /* a smaller single disc in a 10 cm rim, 50 deg, spinning */
    discs[1].body.parts[0] = (jc_Part){JC_PART_DISC, 0.2, 0.0, 0.0, 0.07};
    discs[1].incline_rad = 50 * DEG;
    discs[1].omega0_radps = 5.0;
    discs[2] = discs[0]; /* a floor: rolls on at constant speed */
    discs[2].incline_rad = 0.0;
    discs[2].omega0_radps = 2.0;
    for (int k = 0; k < 3; ++k) {
        jc_Model m;
        if (init(&m, &discs[k])) return 1;
        ENSURE(m.body.cm_offset_m == 0.0);
        jc_RollingResult res;
        char err[256] = "";
        ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
        ENSURE(!res.liftoff.found && !res.slip.found);
        ENSURE(res.end == JC_ROLLING_END_RAMP_END);
        ENSURE_REL(res.end_x_m, m.setup.ramp_length_m, 1e-14); /* r (L/r): two roundings */
        const double M = m.body.mass_kg, r = m.body.radius_m, ic = m.body.inertia_c_kgm2;
        const double g = m.setup.gravity_mps2, a = m.setup.incline_rad;
        for (double th = 0; th < m.theta_end_rad; th += 0.37) {
            jc_RollingState st;
            ENSURE_OK(jc_rolling_state(&m, th, &st, err, sizeof err), err);
            /* Closed forms with a handful of operations: 1e-12 relative; on the
             * floor both are 0 (up to the rounding of sin(0) terms: 1e-15 g). */
            const double alpha = g * sin(a) / (r * (1 + ic / (M * r * r)));
            const double F = -M * g * sin(a) * ic / (ic + M * r * r);
            if (a > 0) {
                ENSURE_REL(st.alpha_radps2, alpha, 1e-12);
                ENSURE_REL(st.friction_N, F, 1e-12);
            } else {
                ENSURE_NEAR(st.alpha_radps2, 0.0, 1e-15 * g / r);
                ENSURE_NEAR(st.friction_N, 0.0, 1e-15 * M * g);
            }
            ENSURE_REL(st.normal_N, M * g * cos(a), 1e-12);
        }
    }
    return 0;
}

/* A setup's model, its dynamics as written here, and the library's rolling
 * prediction. */
static int predicted(const jc_Setup *s, jc_Model *m, dyn *D, jc_RollingResult *res)
{
    if (init(m, s)) return 1;
    *D = dyn_of(m);
    char err[256] = "";
    ENSURE_OK(jc_rolling_predict(m, res, err, sizeof err), err);
    return 0;
}

/* The rolling setups the pointwise tests walk along, from the start to the
 * end of the rolling path. */
#define PATH_SETUPS 5

/* Setup k's model, its dynamics as written here, and its path's end. */
static int path_model(size_t k, jc_Model *m, dyn *D, double *th_end)
{
    const jc_Setup setups[PATH_SETUPS] = {paper_at(30, 0.5), spinning(), preset("rocking-hoop"), lopsided(),
                                          rocking()};
    jc_RollingResult res;
    if (predicted(&setups[k], m, D, &res)) return 1;
    *th_end = res.end_theta_rad;
    return 0;
}

/* One point of a walk along a rolling path: the library's state at th, the
 * i-th of n + 1 evenly spaced angles of setup k's path. */
typedef int (*path_visit)(void *ctx, size_t k, const jc_Model *m, const dyn *D, int i, int n, double th,
                          const jc_RollingState *st);

/* Visits n + 1 points of every setup's path; stops at the first failure. */
static int walk_paths(int n, path_visit visit, void *ctx)
{
    for (size_t k = 0; k < PATH_SETUPS; ++k) {
        jc_Model m;
        dyn D;
        double th_end;
        if (path_model(k, &m, &D, &th_end)) return 1;
        for (int i = 0; i <= n; ++i) {
            char err[256] = "";
            const double th = D.th0 + (th_end - D.th0) * i / (double)n;
            jc_RollingState st;
            ENSURE_OK(jc_rolling_state(&m, th, &st, err, sizeof err), err);
            if (visit(ctx, k, &m, &D, i, n, th, &st)) return 1;
        }
    }
    return 0;
}

/* ---- (b) energy ---- */

typedef struct {
    double e0, scale, worst;
} energy_walk;

static int visit_energy(void *ctx, size_t k, const jc_Model *m, const dyn *D, int i, int n, double th,
                        const jc_RollingState *st)
{
    (void)m;
    energy_walk *w = ctx;
    const double ke = kinetic(D, th, st->omega_radps), u = pot(D, th);
    if (i == 0) *w = (energy_walk){ke + u, D->M * D->g * (D->r + D->d), 0.0};
    w->scale = fmax(w->scale, ke + fabs(u - pot(D, D->th0)));
    w->worst = fmax(w->worst, fabs(ke + u - w->e0));
    /* The library's own energies are the same quantities. */
    ENSURE_NEAR(st->kinetic_J, ke, 1e-12 * w->scale);
    ENSURE_NEAR(st->potential_J, u - pot(D, D->th0), 1e-12 * w->scale);
    ENSURE_NEAR(st->x_m, D->r * (th - D->th0), 1e-15 * D->r * (1 + fabs(th)));
    /* 1e-12 of the energies involved: rounding of ~20 operations. */
    if (i == n)
        ENSURE_MSG(w->worst <= 1e-12 * w->scale, "setup %zu: energy drifts by %.3g J of %.3g J", k, w->worst,
                   w->scale);
    return 0;
}

static int test_energy_identity(void)
{
    energy_walk w;
    return walk_paths(2000, visit_energy, &w);
}

/* ---- second formulation, pointwise: th'', N, F and the model's polynomials ---- */

static int visit_newton_euler(void *ctx, size_t k, const jc_Model *m, const dyn *D, int i, int n, double th,
                              const jc_RollingState *st)
{
    (void)ctx, (void)k, (void)i, (void)n;
    const double w2 = fmax(omega2(D, th), 0.0);
    const forces f = newton_euler(D, th, w2);
    const double fs = force_scale(D, w2, f.alpha);
    /* Two formulations of the same equations: 1e-11 of the force terms
     * (LU on a 4x4 system with entries from 1e-4 to 1). */
    ENSURE_NEAR(st->omega_radps * st->omega_radps, w2, 1e-11 * (fabs(w2) + D->g / D->r));
    ENSURE_NEAR(st->alpha_radps2, f.alpha, 1e-11 * fs / (D->M * D->r));
    ENSURE_NEAR(st->normal_N, f.N, 1e-11 * fs);
    ENSURE_NEAR(st->friction_N, f.F, 1e-11 * fs);
    /* The path from the start: energy = I_P w^2, normal = N I_P^2, friction = F I_P^2. */
    jc_RollingPath path;
    jc_rolling_path_init(m, D->th0, D->w0, &path);
    const double ip = 2 * kinetic(D, th, 1.0);
    ENSURE_NEAR(trig_direct(&path.energy, th), ip * w2, 1e-11 * ip * (fabs(w2) + D->g / D->r));
    ENSURE_NEAR(trig_direct(&path.normal, th), f.N * ip * ip, 1e-11 * fs * ip * ip);
    ENSURE_NEAR(trig_direct(&path.friction, th), f.F * ip * ip, 1e-11 * fs * ip * ip);
    return 0;
}

static int test_newton_euler_pointwise(void) { return walk_paths(500, visit_newton_euler, NULL); }

/* ---- (c) forces from finite differences of an integrated trajectory ---- */

static int ode_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const dyn *D = params;
    dydt[0] = y[1];
    dydt[1] = newton_euler(D, y[0], y[1] * y[1]).alpha;
    return GSL_SUCCESS;
}

static int check_trajectory(const jc_Setup *s, double *worst_rel, double *worst_w)
{
    jc_Model m;
    if (init(&m, s)) return 1;
    dyn D = dyn_of(&m);
    gsl_odeiv2_system sys = {ode_rhs, NULL, 2, &D};
    /* rk8pd with 1e-14 tolerances: position noise ~1e-14 m. */
    gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-14, 1e-14);
    double t = 0, y[2] = {D.th0, D.w0};
    int samples = 0, bad = 0;
    for (int k = 1; k <= 1000 && !bad; ++k) {
        /* 5-point second difference: truncation h^4/90 |x^(6)|, and x^(6) grows
         * like d w^6 (faster for the hoop, whose w changes 20-fold per turn);
         * h ~ 1/(200 w) keeps that and the rounding (eps |x| / h^2) near 1e-8. */
        const double h = fmin(2e-3, 0.005 / (fabs(y[1]) + 1.0));
        const double tk = t + 0.01;
        double th[5], w[5];
        for (int j = 0; j < 5 && !bad; ++j) {
            bad = gsl_odeiv2_driver_apply(drv, &t, tk + (j - 2) * h, y) != GSL_SUCCESS;
            th[j] = y[0];
            w[j] = y[1];
        }
        if (bad || th[4] > m.theta_end_rad || w[2] <= 0) break;
        double ax = 0, ay = 0;
        const double c5[5] = {-1, 16, -30, 16, -1};
        for (int j = 0; j < 5; ++j) {
            ax += c5[j] * xg(&D, th[j]);
            ay += c5[j] * yg(&D, th[j]);
        }
        ax /= 12 * h * h;
        ay /= 12 * h * h;
        jc_RollingState st;
        char err[256] = "";
        if (jc_rolling_state(&m, th[2], &st, err, sizeof err) != JC_OK) {
            fprintf(stderr, "%s\n", err);
            bad = 1;
            break;
        }
        const double fs = force_scale(&D, w[2] * w[2], st.alpha_radps2);
        *worst_rel = fmax(*worst_rel, fabs(D.M * (ay + D.g * D.ca) - st.normal_N) / fs);
        *worst_rel = fmax(*worst_rel, fabs(D.M * (ax - D.g * D.sa) - st.friction_N) / fs);
        /* The energy integral vs the integrated w: integration error only. */
        *worst_w = fmax(*worst_w, fabs(st.omega_radps - w[2]) / fabs(w[2]));
        ++samples;
        t = tk + 2 * h;
    }
    gsl_odeiv2_driver_free(drv);
    ENSURE(!bad);
    ENSURE_MSG(samples >= 20, "only %d samples", samples);
    return 0;
}

static int test_forces_from_trajectory(void)
{
    const jc_Setup setups[] = {paper_at(30, 0.5), spinning(), preset("rocking-hoop"), lopsided()};
    for (size_t k = 0; k < sizeof setups / sizeof setups[0]; ++k) {
        double worst = 0, worst_w = 0;
        if (check_trajectory(&setups[k], &worst, &worst_w)) return 1;
        /* w from the energy integral vs the integrated w: integration error, ~1e-12. */
        ENSURE_MSG(worst_w <= 1e-9, "setup %zu: w differs by %.3g relative", k, worst_w);
        /* Finite differences of a numerically integrated trajectory: truncation
         * and ODE noise (~1e-14 m / h^2) give up to ~2e-8 of the force scale;
         * 1e-6 leaves room, and is far below any missing or wrong term
         * (dropping -M d sin th th'' from N, as the paper does, is ~1e-1). */
        ENSURE_MSG(worst <= 1e-6, "setup %zu: N, F from the trajectory differ by %.3g of the force scale", k,
                   worst);
    }
    return 0;
}

/* ---- (d), (e): the reported crossings are crossings, and the first ones ---- */

typedef struct {
    double N, F, w2;
} contact;

static contact contact_at(const dyn *D, double th)
{
    const double w2 = omega2(D, th);
    const forces f = newton_euler(D, th, fmax(w2, 0.0));
    return (contact){f.N, f.F, w2};
}

static int check_crossings(const jc_Setup *s, jc_RollingResult *res)
{
    jc_Model m;
    if (init(&m, s)) return 1;
    const dyn D = dyn_of(&m);
    const double mu = s->mu_static, Mg = D.M * D.g;
    char err[256] = "";
    ENSURE_OK(jc_rolling_predict(&m, res, err, sizeof err), err);
    const double end = res->end_theta_rad;
    /* Crossings are located to 1e-12 rad; N and F change by O(10 M g) per rad
     * at most here, so the residuals are < 1e-10 M g: 1e-9 M g. */
    if (res->slip.found) {
        const contact c = contact_at(&D, res->slip.state.theta_rad);
        ENSURE_NEAR(fabs(c.F), mu * c.N, 1e-9 * Mg);
        ENSURE(res->slip.state.theta_rad >= D.th0 && res->slip.state.theta_rad <= end);
    }
    if (res->liftoff.found) {
        const contact c = contact_at(&D, res->liftoff.state.theta_rad);
        ENSURE_NEAR(c.N, 0.0, 1e-9 * Mg);
        ENSURE(res->liftoff.state.theta_rad >= D.th0 && res->liftoff.state.theta_rad <= end);
    }
    /* Dense samples from th0 up to each crossing (or the whole path when there
     * is none): rolling holds strictly before it. */
    const double slip_to = res->slip.found ? res->slip.state.theta_rad : end;
    const double lift_to = res->liftoff.found ? res->liftoff.state.theta_rad : end;
    for (int i = 0; i < 10000; ++i) {
        const double th_s = D.th0 + (slip_to - D.th0) * i / 10000.0;
        const double th_l = D.th0 + (lift_to - D.th0) * i / 10000.0;
        const contact cs = contact_at(&D, th_s), cl = contact_at(&D, th_l);
        ENSURE_MSG(slip_to == D.th0 || (cs.N > 0 && fabs(cs.F) < mu * cs.N),
                   "rolling fails at th = %.12g before the reported slip %.12g: N %g F %g", th_s, slip_to,
                   cs.N, cs.F);
        ENSURE_MSG(lift_to == D.th0 || cl.N > 0, "N = %g at th = %.12g before the reported N = 0 at %.12g",
                   cl.N, th_l, lift_to);
        if (res->end == JC_ROLLING_END_TURN_BACK && i > 0) {
            const double th_e = D.th0 + (end - D.th0) * i / 10000.0;
            ENSURE_MSG(omega2(&D, th_e) > 0, "w^2 <= 0 at %.12g before the turning point %.12g", th_e, end);
        }
    }
    return 0;
}

static int test_crossings_are_first(void)
{
    const jc_Setup setups[] = {paper_at(15, 0.5), paper_at(30, 0.5), paper_at(45, 0.5), paper_at(30, 0.2),
                               paper_at(30, 1e6), spinning(), preset("rocking-hoop"), lopsided(), rocking()};
    int slips = 0, liftoffs = 0;
    for (size_t k = 0; k < sizeof setups / sizeof setups[0]; ++k) {
        jc_RollingResult res;
        if (check_crossings(&setups[k], &res)) {
            fprintf(stderr, "in setup %zu\n", k);
            return 1;
        }
        slips += res.slip.found;
        liftoffs += res.liftoff.found;
    }
    ENSURE(slips >= 6 && liftoffs >= 5); /* the checks above were not vacuous */
    return 0;
}

/* The first th along the path from th0 to th_end where g(th) <= 0, by a
 * brute-force search independent of the library's: n samples, then
 * bisection to rounding between the last two. NAN where g stays > 0. */
typedef double (*path_fn)(const dyn *D, double mu, double th);
static double n_of(const dyn *D, double mu, double th)
{
    (void)mu;
    return contact_at(D, th).N;
}
static double cone_of(const dyn *D, double mu, double th)
{
    const contact c = contact_at(D, th);
    return mu * c.N - fabs(c.F);
}
static double brute_first_root(path_fn g, const dyn *D, double mu, double th_end, int n)
{
    double prev = D->th0;
    if (g(D, mu, prev) <= 0.0) return prev;
    for (int i = 1; i <= n; ++i) {
        const double th = D->th0 + (th_end - D->th0) * i / n;
        if (g(D, mu, th) > 0.0) {
            prev = th;
            continue;
        }
        double pos = prev, neg = th;
        for (int k = 0; k < 200 && fabs(neg - pos) > 0.0; ++k) {
            const double mid = 0.5 * (pos + neg);
            if (mid == pos || mid == neg) break;
            if (g(D, mu, mid) > 0.0) pos = mid;
            else neg = mid;
        }
        return 0.5 * (pos + neg);
    }
    return NAN;
}

/* The predicted slip and N = 0 against a brute-force search with the
 * Newton-Euler forces above: the same places to 2e-12 rad (each is located
 * to 1e-12 rad; the scan's steps and polishing changed, not its answers). */
static int test_crossings_match_brute_force(void)
{
    const jc_Setup setups[] = {paper_at(15, 0.5), paper_at(30, 0.5), paper_at(45, 0.5), paper_at(30, 0.2),
                               paper_at(30, 1e6), spinning(), lopsided(), rocking()};
    int compared = 0;
    for (size_t k = 0; k < sizeof setups / sizeof setups[0]; ++k) {
        jc_Model m;
        if (init(&m, &setups[k])) return 1;
        const dyn D = dyn_of(&m);
        const double mu = setups[k].mu_static;
        jc_RollingResult res;
        char err[256] = "";
        ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
        const double end = res.end_theta_rad;
        const double slip = brute_first_root(cone_of, &D, mu, end, 20000);
        const double lift = brute_first_root(n_of, &D, mu, end, 20000);
        ENSURE_MSG(res.slip.found == !isnan(slip), "setup %zu: slip found %d, brute force %.17g", k,
                   res.slip.found, slip);
        ENSURE_MSG(res.liftoff.found == !isnan(lift), "setup %zu: N = 0 found %d, brute force %.17g", k,
                   res.liftoff.found, lift);
        if (res.slip.found) {
            ENSURE_MSG(fabs(res.slip.state.theta_rad - slip) <= 2e-12, "setup %zu: slip at %.17g, brute force %.17g",
                       k, res.slip.state.theta_rad, slip);
            ++compared;
        }
        if (res.liftoff.found) {
            ENSURE_MSG(fabs(res.liftoff.state.theta_rad - lift) <= 2e-12,
                       "setup %zu: N = 0 at %.17g, brute force %.17g", k, res.liftoff.state.theta_rad, lift);
            ++compared;
        }
    }
    ENSURE(compared >= 10);
    return 0;
}

/* ---- (f) the paper's setup: slip comes first, and F != 0 where N = 0 ---- */

static int test_paper_slips_before_n_zero(void)
{
    const double mus[] = {0.5, 1e6};
    for (int k = 0; k < 2; ++k) {
        const jc_Setup s = paper_at(30, mus[k]);
        jc_Model m;
        dyn D;
        jc_RollingResult res;
        if (predicted(&s, &m, &D, &res)) return 1;
        ENSURE(res.slip.found && res.liftoff.found && !res.slip.grazing && !res.liftoff.grazing);
        ENSURE(res.slip.state.theta_rad < res.liftoff.state.theta_rad);
        /* At N = 0 the rolling friction is finite, here about 9% of M g. */
        const contact c = contact_at(&D, res.liftoff.state.theta_rad);
        ENSURE_MSG(fabs(c.F) > 0.01 * D.M * D.g, "F at N = 0 is %g N", c.F);
        ENSURE_REL(res.liftoff.state.friction_N, c.F, 1e-9); /* located to 1e-12 rad */
    }
    return 0;
}

/* ---- (g) starts and ends ---- */

/* Starts that cannot roll: the crossing is at the start itself. */
static int test_starts_out_of_rolling(void)
{
    /* The hoop spun fast with its mass on top: d w0^2 > g, N < 0 at once. */
    jc_Setup flying = preset("rocking-hoop");
    flying.omega0_radps = 20.0;
    const struct {
        jc_Setup s;
        int slips; /* 1: |F| > mu_s N at the start; 0: N < 0 there */
    } cases[] = {
        {paper_at(80, 0.01), 1}, /* 80 deg, mu 0.01: |F|/N = tan(80) I_G / I_P(0) ~ 1 at the start */
        {flying, 0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        jc_Model m;
        dyn D;
        jc_RollingResult res;
        if (predicted(&cases[k].s, &m, &D, &res)) return 1;
        const contact c = contact_at(&D, D.th0);
        /* The premise, computed here. */
        ENSURE(cases[k].slips ? fabs(c.F) > cases[k].s.mu_static * c.N : c.N < 0);
        const jc_RollingCrossing *x = cases[k].slips ? &res.slip : &res.liftoff;
        ENSURE(x->found);
        ENSURE_NEAR(x->state.theta_rad, D.th0, 1e-12);
    }
    return 0;
}

static int test_at_rest(void)
{
    /* The hoop on a floor, mass on top, not spinning: equilibrium. */
    jc_Setup s = preset("rocking-hoop");
    s.omega0_radps = 0.0;
    jc_Model m;
    if (init(&m, &s)) return 1;
    jc_RollingResult res;
    char err[256] = "";
    ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
    ENSURE(res.end == JC_ROLLING_END_AT_REST);
    ENSURE(res.end_theta_rad == s.theta0_rad && res.end_x_m == 0.0);
    ENSURE(!res.slip.found && !res.liftoff.found);
    return 0;
}

static int test_rocks_and_turns_back(void)
{
    const jc_Setup s = rocking();
    jc_Model m;
    dyn D;
    jc_RollingResult res;
    if (predicted(&s, &m, &D, &res)) return 1;
    ENSURE(res.end == JC_ROLLING_END_TURN_BACK);
    ENSURE(!res.slip.found && !res.liftoff.found);
    /* The turning point: U(th) = U(th0) past th0, bisected here. U - U0 < 0 just
     * past pi (the torque rolls it on) and > 0 at pi + 0.5 (the CM has risen). */
    double lo = PI + 1e-3, hi = PI + 0.5;
    ENSURE(pot(&D, lo) < pot(&D, D.th0) && pot(&D, hi) > pot(&D, D.th0));
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (pot(&D, mid) < pot(&D, D.th0)) lo = mid; else hi = mid;
    }
    /* The slope of U there is ~M g (r - d) sin a ~ 2e-3 N: rounding of U
     * (~1e-18 J) moves the root by ~1e-15; both are located to ~1e-12. */
    ENSURE_NEAR(res.end_theta_rad, 0.5 * (lo + hi), 1e-10);
    ENSURE_REL(res.end_x_m, D.r * (res.end_theta_rad - D.th0), 1e-15);
    /* w^2 = 0 there: kinetic energy from the energy balance, relative to M g r. */
    ENSURE_NEAR(pot(&D, D.th0) - pot(&D, res.end_theta_rad), 0.0, 1e-12 * D.M * D.g * D.r);
    jc_RollingState st;
    char err[256] = "";
    ENSURE_OK(jc_rolling_state(&m, res.end_theta_rad, &st, err, sizeof err), err);
    ENSURE_NEAR(st.kinetic_J, 0.0, 1e-12 * D.M * D.g * D.r);
    /* Past the turning point the rolling motion never gets there. */
    ENSURE(jc_rolling_state(&m, res.end_theta_rad + 0.05, &st, err, sizeof err) == JC_EINVAL);
    ENSURE(strstr(err, "reach") != NULL);
    ENSURE(jc_rolling_state(&m, NAN, &st, err, sizeof err) == JC_EINVAL);

    /* Started with the CM on top instead, 2 deg does not rock: U(th) < U(0)
     * for all th > 0 (the CM starts at its highest), so it rolls to the end. */
    jc_Setup top = s;
    top.theta0_rad = 0.0;
    if (init(&m, &top)) return 1;
    ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
    ENSURE(res.end == JC_ROLLING_END_RAMP_END);
    return 0;
}

static int test_rolls_uphill(void)
{
    jc_Setup s = paper_at(30, 0.5);
    s.omega0_radps = -10.0;
    jc_Model m;
    if (init(&m, &s)) return 1;
    jc_RollingResult res;
    char err[256] = "";
    ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
    ENSURE(res.end == JC_ROLLING_END_RAMP_TOP && res.end_x_m == 0.0);
    jc_RollingState st;
    ENSURE_OK(jc_rolling_state(&m, -0.1, &st, err, sizeof err), err);
    ENSURE(st.omega_radps < 0);

    ENSURE(strcmp(jc_rolling_end_name(JC_ROLLING_END_RAMP_END), "ramp_end") == 0);
    ENSURE(strcmp(jc_rolling_end_name(JC_ROLLING_END_TURN_BACK), "turn_back") == 0);
    ENSURE(strcmp(jc_rolling_end_name(JC_ROLLING_END_RAMP_TOP), "ramp_top") == 0);
    ENSURE(strcmp(jc_rolling_end_name(JC_ROLLING_END_AT_REST), "at_rest") == 0);
    return 0;
}

static int test_at_rest_rolling_uphill(void)
{
    /* At rest but with th'' < 0 at the start (CM far behind C on 5 deg): it
     * starts uphill, like omega0 < 0; jc_rolling_state takes the sign of that th''. */
    jc_Setup b = paper_at(5, 0.5);
    b.theta0_rad = -1.5;
    jc_Model m;
    if (init(&m, &b)) return 1;
    const dyn D = dyn_of(&m);
    ENSURE(newton_euler(&D, D.th0, 0.0).alpha < 0); /* the premise, computed here */
    jc_RollingState st;
    jc_RollingResult res;
    char err[256] = "";
    ENSURE_OK(jc_rolling_state(&m, D.th0 - 0.01, &st, err, sizeof err), err);
    ENSURE(st.omega_radps < 0);
    ENSURE_OK(jc_rolling_predict(&m, &res, err, sizeof err), err);
    ENSURE_MSG(res.end == JC_ROLLING_END_RAMP_TOP, "at rest, rolling uphill: end '%s', expected 'ramp_top'",
               jc_rolling_end_name(res.end));
    ENSURE(res.end_x_m == 0.0);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_uniform_disc);
    RUN_TEST(test_energy_identity);
    RUN_TEST(test_newton_euler_pointwise);
    RUN_TEST(test_forces_from_trajectory);
    RUN_TEST(test_crossings_are_first);
    RUN_TEST(test_crossings_match_brute_force);
    RUN_TEST(test_paper_slips_before_n_zero);
    RUN_TEST(test_starts_out_of_rolling);
    RUN_TEST(test_at_rest);
    RUN_TEST(test_rocks_and_turns_back);
    RUN_TEST(test_rolls_uphill);
    RUN_TEST(test_at_rest_rolling_uphill);
    TEST_MAIN_END();
}
