/*
 * The headline numbers of `jumpcyl paper`, pinned against a second
 * formulation computed here, so that a change that moves them fails:
 *
 * - Eq. 9's first intersection at 15, 30 and 45 deg: the paper's equation
 *   transcribed from the seed's TeX (as in tests/test_paper_model.c), its
 *   first sign change found by a dense scan and bisection, against
 *   jc_paper_solve.
 * - The full model's first lift-off at 15, 30 and 45 deg (mu 0.5, e 0.3):
 *   the motion integrated here with the Lagrange-multiplier equations of
 *   lagrange.h (rolling 5x5, sliding 4x4; no closed form of src/) by fixed
 *   RK4 steps, slip, stick and N = 0 located by bisection on single steps,
 *   against the first lift-off event of jc_simulate.
 */
#include "lagrange.h"

#define RK_DT 2e-5
#define MAX_T 3.0

/* ---- Eq. 9 ---- */

typedef struct {
    double M, M1, r, d, a;
} eq9;

static double eq9_diff(const eq9 *e, double th)
{
    const double lhs = 2 * e->M * (e->d * (1 - cos(th)) * cos(e->a) + e->r * th * sin(e->a)) /
                       (0.5 * e->M1 * e->r * e->r + e->M * (e->r * e->r + e->d * e->d + 2 * e->r * e->d * cos(th)));
    return lhs - cos(e->a) / (e->d * cos(th));
}

/* First th in (0, th_end] where lhs - rhs changes sign with cos th > 0. */
static double eq9_first_root(const eq9 *e, double th_end)
{
    const double h = 1e-5;
    double a = h, fa = eq9_diff(e, a);
    for (double b = 2 * h; b <= th_end; b += h) {
        const double fb = eq9_diff(e, b);
        /* a sign change with cos th > 0 on both ends (not the pole at cos th = 0) */
        if (cos(a) > 0 && cos(b) > 0 && (fa > 0) != (fb > 0)) {
            for (int it = 0; it < 200; ++it) {
                const double mid = 0.5 * (a + b), fm = eq9_diff(e, mid);
                if ((fm > 0) == (fa > 0)) a = mid, fa = fm;
                else b = mid;
            }
            return 0.5 * (a + b);
        }
        a = b;
        fa = fb;
    }
    return NAN;
}

/* ---- the full model, second formulation ---- */

typedef struct {
    const body_consts *b;
    double mu_s, mu_k;
    int sliding, s; /* mode and slip direction */
} motion;

/* y = (x_C, th, vx_C, w); derivative, and N and F of the mode */
static int deriv(const motion *mo, const double y[4], double dy[4], double *normal, double *friction)
{
    double thdd, xcdd;
    if (mo->sliding) {
        if (slide_lm(mo->b, mo->mu_k, mo->s, y[1], y[3], normal, &thdd, &xcdd)) return 1;
        *friction = -mo->mu_k * mo->s * *normal;
    } else {
        if (roll_lm(mo->b, y[1], y[3], &thdd, normal, friction)) return 1;
        xcdd = mo->b->r * thdd;
    }
    dy[0] = y[2];
    dy[1] = y[3];
    dy[2] = xcdd;
    dy[3] = thdd;
    return 0;
}

static int rk4(const motion *mo, const double y0[4], double h, double y[4])
{
    double k1[4], k2[4], k3[4], k4[4], t[4], n, f;
    if (deriv(mo, y0, k1, &n, &f)) return 1;
    for (int i = 0; i < 4; ++i) t[i] = y0[i] + 0.5 * h * k1[i];
    if (deriv(mo, t, k2, &n, &f)) return 1;
    for (int i = 0; i < 4; ++i) t[i] = y0[i] + 0.5 * h * k2[i];
    if (deriv(mo, t, k3, &n, &f)) return 1;
    for (int i = 0; i < 4; ++i) t[i] = y0[i] + h * k3[i];
    if (deriv(mo, t, k4, &n, &f)) return 1;
    for (int i = 0; i < 4; ++i) y[i] = y0[i] + h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    return 0;
}

/* The watched quantities of the mode, positive while it goes on:
 * rolling: N and mu_s N - |F|; sliding: N and s (vx - r w). */
static void watch(const motion *mo, const double y[4], double ev[2])
{
    double dy[4], n, f;
    deriv(mo, y, dy, &n, &f);
    ev[0] = n;
    ev[1] = mo->sliding ? mo->s * (y[2] - mo->b->r * y[3]) : mo->mu_s * n - fabs(f);
}

/* First lift-off x_C and th from rest at th = 0; *events counts mode changes. */
static int first_liftoff(const jc_Model *m, double *x_out, double *th_out, int *changes)
{
    const body_consts b = consts_of(m);
    motion mo = {&b, m->setup.mu_static, m->setup.mu_kinetic, 0, 0};
    double y[4] = {0.0, 0.0, 0.0, 0.0};
    int fresh = 1; /* the first step of a mode: its watched slip starts at 0 */
    *changes = 0;
    for (double t = 0.0; t < MAX_T;) {
        double y1[4], ev0[2], ev1[2];
        watch(&mo, y, ev0);
        ENSURE(rk4(&mo, y, RK_DT, y1) == 0);
        watch(&mo, y1, ev1);
        int which = -1;
        for (int k = 0; k < 2; ++k)
            if (ev1[k] <= 0.0 && !(fresh && k == 1 && mo.sliding)) which = which < 0 ? k : which;
        if (which < 0) {
            memcpy(y, y1, sizeof y);
            t += RK_DT;
            fresh = 0;
            continue;
        }
        /* bisection on the step length: the first event of either kind */
        double lo = 0.0, hi = RK_DT;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            double ym[4], em[2];
            ENSURE(rk4(&mo, y, mid, ym) == 0);
            watch(&mo, ym, em);
            int hit = em[0] <= 0.0 || (em[1] <= 0.0 && !(fresh && mo.sliding));
            if (hit) hi = mid;
            else lo = mid;
        }
        double yh[4], eh[2];
        ENSURE(rk4(&mo, y, hi, yh) == 0);
        watch(&mo, yh, eh);
        memcpy(y, yh, sizeof y);
        t += hi;
        fresh = 1;
        if (eh[0] <= 0.0) {
            *x_out = y[0];
            *th_out = y[1];
            return 0;
        }
        ++*changes;
        if (!mo.sliding) {
            /* slip: against the friction rolling needed */
            double dy[4], n, f;
            deriv(&mo, y, dy, &n, &f);
            mo.sliding = 1;
            mo.s = f > 0.0 ? -1 : 1;
        } else {
            /* stick: roll if the cone holds the rolling friction */
            y[2] = b.r * y[3];
            mo.sliding = 0;
            double dy[4], n, f;
            deriv(&mo, y, dy, &n, &f);
            ENSURE_MSG(fabs(f) <= mo.mu_s * n, "stick at th %g does not hold", y[1]);
        }
    }
    ENSURE_MSG(0, "no lift-off within %g s", MAX_T);
    return 1;
}

static int test_pins(void)
{
    const double inclines[3] = {15.0, 30.0, 45.0};
    for (int i = 0; i < 3; ++i) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = inclines[i] * DEG;
        jc_Model m;
        if (sim_model(&m, &s)) return 1;

        /* Eq. 9: the paper's M, M1 (the disc), printed d */
        eq9 e = {m.body.mass_kg, m.body.disc_mass_kg, m.body.radius_m, s.paper_cm_offset_m, s.incline_rad};
        jc_PaperResult pr;
        char err[256] = "";
        ENSURE_OK(jc_paper_solve(&m, &pr, err, sizeof err), err);
        const double root = eq9_first_root(&e, s.ramp_length_m / s.body.radius_m);
        ENSURE(pr.first >= 0);
        ENSURE_NEAR(pr.theta_rad[pr.first], root, 1e-9);

        /* the full model's first lift-off */
        jc_SimOptions o = jc_default_sim_options();
        jc_Run run;
        if (sim_run(&m, &o, &run)) return 1;
        jc_RunSummary sum;
        jc_run_summarize(&run, &sum);
        double lib_x = NAN, lib_th = NAN;
        if (sum.first_liftoff >= 0) {
            lib_x = run.events[sum.first_liftoff].state.x_m;
            lib_th = run.events[sum.first_liftoff].state.theta_rad;
        }
        const int lib_changes = sum.first_liftoff;
        jc_run_free(&run);
        double x, th;
        int changes;
        if (first_liftoff(&m, &x, &th, &changes)) return 1;
        printf("  %2.0f deg: Eq. 9 first root %.10f rad (library %.10f); first lift-off x %.9f m, th %.9f rad "
               "after %d slip/stick (library %.9f m, %.9f rad, %d)\n",
               inclines[i], root, pr.theta_rad[pr.first], x, th, changes, lib_x, lib_th, lib_changes);
        ENSURE_MSG(changes == lib_changes, "mode changes before the lift-off: %d here, %d in the library", changes,
                   lib_changes);
        ENSURE_NEAR(lib_x, x, 1e-7);
        ENSURE_NEAR(lib_th, th, 1e-6);
    }
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_pins);
    TEST_MAIN_END();
}
