/*
 * Sliding in contact (docs/physics.md §3): two degrees of freedom, x_C and th,
 * with y_C = r held by N and kinetic friction F = -mu_k s N, s = sgn(v_s),
 * v_s = x_C' - r w. With k = mu_k s (r + d cos th) + d sin th - b sgn(w)
 * (b the rolling-resistance lever, 0 without it), and an air force (Fx, Fy)
 * at C with torque T about G (0 without air):
 *   N     = [M (g cos a - d cos th w^2) - Fy - M d sin th T / I_G] / D,
 *   D     = 1 + M d sin th k / I_G,
 *   th''  = (N k + T) / I_G
 *   x_C'' = g sin a + (F + Fx)/M - d cos th th'' + d sin th w^2
 * D <= 0 is the Painleve condition: no contact force is consistent; it is
 * reported, never divided through. Integrated by ode.c.
 */
#include "internal.h"
#include "dop853_kernel.h"

#include <math.h>

/* D -> 0+ with N's numerator > 0 makes N ~ 1/D grow without bound (the
 * dynamic jam of Painleve's paradox): no step of the integrator reaches
 * D = 0 itself (found: GSL failed with D = 4e-12, N ~ 1e9 N). Where D falls
 * to 1e-3, N is a thousand times its scale: the run ends there as Painleve.
 * (At 1e-6 the friction work's integration error in such runs reached
 * 2e-9 of the energy; at 1e-3 the 10^4 random setups of
 * tests/sim/test_random_setups.c all close to 2e-10.) */
#define PAINLEVE_D_MIN 1e-3

/* The body of jc_sliding_accel, inlined into the right-hand sides. */
static inline void sliding_accel(const jc_Model *m, double s, double c, double w, int dir, const jc_Loads *l,
                                 jc_SlidingForces *f)
{
    /* Reciprocals from the model: this runs at every stage of every step,
     * and its four divisions were its largest cost. */
    const jc_ModelTables *tb = jc_model_tables(m);
    const double M = m->body.mass_kg, inv_ig = tb->inv_inertia_g, inv_m = tb->inv_mass_per_kg;
    const double r = m->body.radius_m, d = m->body.cm_offset_m;
    const double g = m->setup.gravity_mps2, mu = m->setup.mu_kinetic;
    const double fx = l ? l->fx_N : 0.0, fy = l ? l->fy_N : 0.0, torque = l ? l->torque_Nm : 0.0;
    const double k = mu * dir * (r + d * c) + d * s + (l ? l->rr_torque_per_N : 0.0);
    const double mds_ig = M * d * s * inv_ig, w2 = w * w;
    /* 1/D and the terms that do not wait for the air's loads first: the
     * right-hand sides' stages each wait for the last one's rates. */
    f->denominator = 1.0 + mds_ig * k;
    const double inv_d = 1.0 / f->denominator;
    const double free_x = g * m->sin_incline + d * s * w2;
    f->normal_N = ((M * (g * m->cos_incline - d * c * w2) - fy) - mds_ig * torque) * inv_d;
    f->friction_N = -mu * dir * f->normal_N;
    f->theta_acc = (f->normal_N * k + torque) * inv_ig;
    f->x_acc = (free_x + (f->friction_N + fx) * inv_m) - d * c * f->theta_acc;
}

void jc_sliding_accel(const jc_Model *m, double s, double c, double w, int dir, const jc_Loads *l, jc_SlidingForces *f)
{
    sliding_accel(m, s, c, w, dir, l, f);
}

void jc_sliding_forces(const jc_Model *m, double th, double w, int dir, jc_SlidingForces *f)
{
    double sn, cs;
    jc_sincos(th, &sn, &cs);
    jc_sliding_accel(m, sn, cs, w, dir, NULL, f);
}

/* Sliding at state (th, w, vx): the loads there (none when switched off). */
void jc_sliding_at(const jc_Model *m, const jc_State *s, int dir, jc_SlidingForces *f, jc_Loads *loads)
{
    jc_Loads l = {0};
    /* The inline sincos, not libm's sin and cos (calls through the PLT). */
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    if (jc_model_has_resistance(m)) jc_loads_at(m, sn, cs, s->vx_mps, 0.0, s->omega_radps, &l);
    jc_sliding_accel(m, sn, cs, s->omega_radps, dir, &l, f);
    if (loads) *loads = l;
}

/* Without loads, the phase's constants of slide_rhs_free: k = a + b cos th +
 * d sin th, D = 1 + mdig sin th k, N D = mgc - md cos th w^2. */
typedef struct {
    double a, b, d, mdig, mgc, md, inv_ig, gs, fm, mu_dir, r;
} slide_consts;

typedef struct {
    const jc_Model *m;
    int dir;
    int loaded; /* air or rolling resistance on */
    slide_consts q;
} slide_ctx;

/* Forces at a state vector, with th's sine and cosine taken from it. */
static void forces_y(const slide_ctx *c, const double y[], jc_SlidingForces *f, jc_Loads *l)
{
    if (!c->loaded) {
        if (l) *l = (jc_Loads){0};
        sliding_accel(c->m, y[JC_Y_SIN], y[JC_Y_COS], y[JC_Y_W], c->dir, NULL, f);
        return;
    }
    jc_Loads none = {0};
    if (!l) l = &none;
    jc_loads_at(c->m, y[JC_Y_SIN], y[JC_Y_COS], y[JC_Y_VX], 0.0, y[JC_Y_W], l);
    sliding_accel(c->m, y[JC_Y_SIN], y[JC_Y_COS], y[JC_Y_W], c->dir, l, f);
}

static int slide_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const slide_ctx *c = params;
    jc_SlidingForces f;
    jc_Loads l;
    forces_y(c, y, &f, &l);
    const double slip = y[JC_Y_VX] - c->m->body.radius_m * y[JC_Y_W];
    dydt[JC_Y_X] = y[JC_Y_VX];
    dydt[JC_Y_Y] = 0.0;
    dydt[JC_Y_TH] = y[JC_Y_W];
    dydt[JC_Y_VX] = f.x_acc;
    dydt[JC_Y_VY] = 0.0;
    dydt[JC_Y_W] = f.theta_acc;
    /* dir * slip, not |slip|: the same while the phase lasts, and smooth where
     * the integrator steps past the slip's zero (|slip| made the step
     * control reject 10 steps in a row before each stick event). */
    dydt[JC_Y_FRICTION] = c->m->setup.mu_kinetic * f.normal_N * c->dir * slip;
    dydt[JC_Y_AIR] = l.air_power_W;
    dydt[JC_Y_RR] = -l.rr_torque_per_N * f.normal_N * y[JC_Y_W];
    dydt[JC_Y_COS] = -y[JC_Y_W] * y[JC_Y_SIN];
    dydt[JC_Y_SIN] = y[JC_Y_W] * y[JC_Y_COS];
    return 0;
}

/* The same without air or rolling resistance, written for the shortest
 * chain of dependent operations (each stage of a step waits for the last
 * one's rates; the division by D is on that chain whatever the order):
 * th'' = N (k / I_G), x'' = (g sin a + d sin th w^2) - mu_k s N / M - d cos th
 * th'', the phase's products folded into constants. The same equations as
 * jc_sliding_accel, rounded in another order. */
static int slide_rhs_free(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const slide_ctx *c = params;
    const slide_consts *q = &c->q;
    const double cs = y[JC_Y_COS], sn = y[JC_Y_SIN], w = y[JC_Y_W], w2 = w * w;
    const double k = q->a + q->b * cs + q->d * sn;
    const double den = 1.0 + q->mdig * sn * k;
    const double n = (q->mgc - q->md * cs * w2) / den;
    const double thdd = n * (k * q->inv_ig);
    dydt[JC_Y_X] = y[JC_Y_VX];
    dydt[JC_Y_Y] = 0.0;
    dydt[JC_Y_TH] = w;
    dydt[JC_Y_VX] = (q->gs + q->d * sn * w2) - q->fm * n - q->d * cs * thdd;
    dydt[JC_Y_VY] = 0.0;
    dydt[JC_Y_W] = thdd;
    dydt[JC_Y_FRICTION] = q->mu_dir * n * (y[JC_Y_VX] - q->r * w);
    dydt[JC_Y_AIR] = 0.0;
    dydt[JC_Y_RR] = 0.0;
    dydt[JC_Y_COS] = -w * sn;
    dydt[JC_Y_SIN] = w * cs;
    return 0;
}

/* The ranges integrated, [0, dim), given once to the steps' instances and to ode.c. */
enum { SLIDE_DIM = JC_Y_RR + 1, SLIDE_DIM_FREE = JC_Y_FRICTION + 1 };
JC_DOP853_TRY_INSTANCE(slide_try, slide_rhs, 0, SLIDE_DIM)
JC_DOP853_TRY_INSTANCE(slide_try_free, slide_rhs_free, 0, SLIDE_DIM_FREE)

enum { EV_SLIP, EV_LIFT, EV_PAINLEVE, EV_END, EV_TOP, EV_COUNT };

static void slide_events(void *params, const double y[], double ev[])
{
    const slide_ctx *c = params;
    jc_SlidingForces f;
    forces_y(c, y, &f, NULL);
    ev[EV_SLIP] = c->dir * (y[JC_Y_VX] - c->m->body.radius_m * y[JC_Y_W]);
    ev[EV_LIFT] = f.normal_N * f.denominator; /* N's numerator: N > 0 while D > 0 */
    ev[EV_PAINLEVE] = f.denominator - PAINLEVE_D_MIN;
    ev[EV_END] = c->m->setup.ramp_length_m - y[JC_Y_X];
    ev[EV_TOP] = y[JC_Y_X] + JC_RAMP_TOP_SLACK_M;
}

/* The events' rates without loads, in closed form: with k = mu_k s (r + d
 * cos th) + d sin th, N D = M (g cos a - d cos th w^2) and D = 1 + M d sin th
 * k / I_G; cos th' = -w sin th, sin th' = w cos th (f carries both). They
 * replace the central difference of ode.c (two more evaluations of the
 * events per step), with which they agree to 1e-9 (its accuracy) on the
 * paper's runs. */
static void slide_event_rates(void *params, const double y[], const double f[], double dev[])
{
    const slide_ctx *c = params;
    const jc_Model *m = c->m;
    const double d = m->body.cm_offset_m, r = m->body.radius_m, mu_dir = m->setup.mu_kinetic * c->dir;
    const double s = y[JC_Y_SIN], w = y[JC_Y_W], mdig = m->body.mass_kg * d * jc_model_tables(m)->inv_inertia_g;
    const double k = mu_dir * (r + d * y[JC_Y_COS]) + d * s, dk = mu_dir * d * f[JC_Y_COS] + d * f[JC_Y_SIN];
    dev[EV_SLIP] = c->dir * (f[JC_Y_VX] - r * f[JC_Y_W]);
    dev[EV_LIFT] = -m->body.mass_kg * d * (f[JC_Y_COS] * w * w + 2.0 * y[JC_Y_COS] * w * f[JC_Y_W]);
    dev[EV_PAINLEVE] = mdig * (f[JC_Y_SIN] * k + s * dk);
    dev[EV_END] = -f[JC_Y_X];
    dev[EV_TOP] = f[JC_Y_X];
}

static int slide_sample(jc_Sim *sim, void *params, double t, const double y[])
{
    const slide_ctx *c = params;
    jc_SlidingForces f;
    forces_y(c, y, &f, NULL);
    jc_State s;
    jc_y_to_state(y, t, &s);
    return jc_record_sample_y(sim, &s, y, JC_MODE_SLIDING, f.normal_N, f.friction_N, 0.0);
}

int jc_sliding_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len)
{
    const jc_Model *m = sim->m;
    const double mu_dir = m->setup.mu_kinetic * sim->slip_dir, d = m->body.cm_offset_m, M = m->body.mass_kg;
    const jc_ModelTables *tb = jc_model_tables(m);
    slide_ctx ctx = {m, sim->slip_dir, jc_model_has_resistance(m),
                     {mu_dir * m->body.radius_m, mu_dir * d, d, M * d * tb->inv_inertia_g,
                      M * m->setup.gravity_mps2 * m->cos_incline, M * d, tb->inv_inertia_g,
                      m->setup.gravity_mps2 * m->sin_incline, mu_dir * tb->inv_mass_per_kg, mu_dir,
                      m->body.radius_m}};
    const jc_OdePhase phase = {ctx.loaded ? slide_rhs : slide_rhs_free, slide_events, EV_COUNT, slide_sample, &ctx,
                               ctx.loaded ? SLIDE_DIM : SLIDE_DIM_FREE, ctx.loaded ? NULL : slide_event_rates,
                               ctx.loaded ? slide_try : slide_try_free};
    int which;
    int st = jc_ode_run(sim, &phase, &which, err, err_len);
    if (st != JC_OK) return st;
    sim->s.y_m = sim->m->body.radius_m;
    sim->s.vy_mps = 0.0;
    switch (which) {
    case EV_SLIP:
        /* The slip velocity is 0 here up to the location tolerance: make it exact. */
        sim->s.vx_mps = sim->m->body.radius_m * sim->s.omega_radps;
        *end = PHASE_SLIP_ZERO;
        break;
    case EV_LIFT: *end = PHASE_LIFTOFF; break;
    case EV_PAINLEVE: *end = PHASE_PAINLEVE; break;
    case EV_END: *end = PHASE_RAMP_END; break;
    case EV_TOP: *end = PHASE_RAMP_TOP; break;
    case JC_ODE_TIME_LIMIT: *end = PHASE_TIME_LIMIT; break;
    default: *end = PHASE_STEP_LIMIT; break;
    }
    return JC_OK;
}
