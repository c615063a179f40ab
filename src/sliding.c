/*
 * Sliding in contact (docs/physics.md §3): two degrees of freedom, x_C and th,
 * with y_C = r held by N and kinetic friction F = -mu_k s N, s = sgn(v_s),
 * v_s = x_C' - r w. With k = mu_k s (r + d cos th) + d sin th:
 *   N     = M (g cos a - d cos th w^2) / D,   D = 1 + M d sin th k / I_G
 *   th''  = N k / I_G
 *   x_C'' = g sin a + F/M - d cos th th'' + d sin th w^2
 * D <= 0 is the Painleve condition: no contact force is consistent; it is
 * reported, never divided through.
 *
 * Integrated with GSL's rk8pd; events are located on the step by a
 * safeguarded Newton iteration on a single step of the same method from the
 * step's start, so the event state has the integrator's accuracy.
 */
#include "internal.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>

/* Rotation per step at most this (rad): event functions vary on the rotation
 * scale, so no root window can hide inside a step. */
#define MAX_ROTATION_PER_STEP 0.3
#define SLIDE_MAX_STEPS 10000000L
/* The ramp top counts as passed 1 nm uphill of the start, so that a start
 * exactly at x = 0 is not an event. */
#define RAMP_TOP_SLACK_M 1e-9

void jc_slide_forces(const jc_Model *m, double th, double w, int dir, jc_SlideForces *f)
{
    const double M = m->body.mass_kg, ig = m->body.inertia_g_kgm2;
    const double r = m->body.radius_m, d = m->body.cm_offset_m;
    const double g = m->setup.gravity_mps2, mu = m->setup.mu_kinetic;
    const double s = sin(th), c = cos(th);
    const double k = mu * dir * (r + d * c) + d * s;
    f->denominator = 1.0 + M * d * s * k / ig;
    f->normal_N = M * (g * m->cos_incline - d * c * w * w) / f->denominator;
    f->friction_N = -mu * dir * f->normal_N;
    f->theta_acc = f->normal_N * k / ig;
    f->x_acc = g * m->sin_incline + f->friction_N / M - d * c * f->theta_acc + d * s * w * w;
}

enum { Y_X, Y_TH, Y_VX, Y_W, Y_LOSS, Y_DIM };
enum { EV_SLIP, EV_LIFT, EV_PAINLEVE, EV_END, EV_TOP, EV_COUNT };

typedef struct {
    const jc_Model *m;
    int dir;
} slide_ctx;

static int slide_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const slide_ctx *c = params;
    jc_SlideForces f;
    jc_slide_forces(c->m, y[Y_TH], y[Y_W], c->dir, &f);
    dydt[Y_X] = y[Y_VX];
    dydt[Y_TH] = y[Y_W];
    dydt[Y_VX] = f.x_acc;
    dydt[Y_W] = f.theta_acc;
    dydt[Y_LOSS] = c->m->setup.mu_kinetic * f.normal_N * fabs(y[Y_VX] - c->m->body.radius_m * y[Y_W]);
    return GSL_SUCCESS;
}

/* Event functions, each positive while sliding goes on, and their time derivatives. */
static void events(const slide_ctx *c, const double y[], double ev[EV_COUNT], double dev[EV_COUNT])
{
    const jc_Model *m = c->m;
    const double r = m->body.radius_m, d = m->body.cm_offset_m, M = m->body.mass_kg;
    const double th = y[Y_TH], w = y[Y_W], s = sin(th), co = cos(th);
    jc_SlideForces f;
    jc_slide_forces(m, th, w, c->dir, &f);
    ev[EV_SLIP] = c->dir * (y[Y_VX] - r * w);
    ev[EV_LIFT] = m->setup.gravity_mps2 * m->cos_incline - d * co * w * w; /* N's numerator */
    ev[EV_PAINLEVE] = f.denominator;
    ev[EV_END] = m->setup.ramp_length_m - y[Y_X];
    ev[EV_TOP] = y[Y_X] + RAMP_TOP_SLACK_M;
    if (!dev) return;
    const double mu = m->setup.mu_kinetic;
    dev[EV_SLIP] = c->dir * (f.x_acc - r * f.theta_acc);
    dev[EV_LIFT] = d * s * w * w * w - 2.0 * d * co * w * f.theta_acc;
    dev[EV_PAINLEVE] = M * d / m->body.inertia_g_kgm2 * w *
                       (co * (mu * c->dir * (r + d * co) + d * s) + s * (-mu * c->dir * d * s + d * co));
    dev[EV_END] = -y[Y_VX];
    dev[EV_TOP] = y[Y_VX];
}

/* y at t0 + tau, by one step of the integrator from (t0, y0). */
static void step_to(jc_Sim *sim, const gsl_odeiv2_system *sys, double t0, const double y0[Y_DIM],
                    double tau, double y[Y_DIM])
{
    double yerr[Y_DIM];
    for (int i = 0; i < Y_DIM; ++i) y[i] = y0[i];
    if (tau > 0.0) gsl_odeiv2_step_apply(sim->ode_step, t0, tau, y, yerr, NULL, NULL, sys);
}

typedef struct {
    jc_Sim *sim;
    const gsl_odeiv2_system *sys;
    const slide_ctx *ctx;
    double t0;
    const double *y0;
    int which;
} event_at;

static void event_at_tau(const event_at *ea, double tau, double *f, double *df)
{
    double y[Y_DIM], ev[EV_COUNT], dev[EV_COUNT];
    step_to(ea->sim, ea->sys, ea->t0, ea->y0, tau, y);
    events(ea->ctx, y, ev, dev);
    *f = ev[ea->which];
    if (df) *df = dev[ea->which];
}

static double event_value(double tau, void *params)
{
    double f;
    event_at_tau(params, tau, &f, NULL);
    return f;
}

/* Root in (0, hi] of event `which`, positive at 0 and <= 0 at hi, f0 and d0
 * its value and rate at 0. Newton on the event function of one integrator
 * step, kept inside the bracket (bisection when it would leave it). Each
 * evaluation is a full rk8pd step, and the event's exact rate is at hand:
 * measured, 3 to 4 steps per event against 10 to 14 for GSL's Brent solver. */
static double locate(event_at *ea, double hi, double f0, double d0)
{
    double lo = 0.0, f_hi;
    event_at_tau(ea, hi, &f_hi, NULL);
    if (f_hi == 0.0) return hi;
    /* Start where the chord meets zero, or Newton from 0 if that is closer. */
    double tau = hi * f0 / (f0 - f_hi);
    if (d0 < 0.0 && -f0 / d0 < tau) tau = -f0 / d0;
    const double tol = 0.5 * ea->sim->opt->event_tol_s;
    for (int it = 0; it < 60 && hi - lo > tol; ++it) {
        double f, df;
        event_at_tau(ea, tau, &f, &df);
        if (f > 0.0) lo = tau;
        else hi = tau;
        if (f == 0.0) return tau;
        double next = df != 0.0 ? tau - f / df : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (fabs(next - tau) < tol) {
            /* Converged: make sure the event has happened at the returned time. */
            const double t_hit = fmin(next + tol, hi);
            return event_value(t_hit, ea) <= 0.0 ? t_hit : hi;
        }
        tau = next;
    }
    /* The upper end: the event has happened there (its function is <= 0). */
    return hi;
}

/* A dip below zero inside a step whose ends are both positive: where the
 * cubic Hermite interpolant of the event function has its minimum. */
static double hermite_min_tau(double f0, double d0, double f1, double d1, double h)
{
    double best_tau = -1.0, best = fmin(f0, f1);
    for (int k = 1; k < 16; ++k) {
        const double s = k / 16.0, s2 = s * s, s3 = s2 * s;
        const double v = (2 * s3 - 3 * s2 + 1) * f0 + (s3 - 2 * s2 + s) * h * d0 +
                         (-2 * s3 + 3 * s2) * f1 + (s3 - s2) * h * d1;
        if (v < best) { best = v; best_tau = s * h; }
    }
    return best < 0.5 * fmin(f0, f1) ? best_tau : -1.0;
}

static jc_PhaseEnd event_end(int which)
{
    switch (which) {
    case EV_SLIP: return PHASE_SLIP_ZERO;
    case EV_LIFT: return PHASE_LIFTOFF;
    case EV_PAINLEVE: return PHASE_PAINLEVE;
    case EV_END: return PHASE_RAMP_END;
    default: return PHASE_RAMP_TOP;
    }
}

static void state_from_y(const jc_Model *m, const double y[Y_DIM], double t, jc_State *s)
{
    s->t_s = t;
    s->x_m = y[Y_X];
    s->y_m = m->body.radius_m;
    s->vx_mps = y[Y_VX];
    s->vy_mps = 0.0;
    s->theta_rad = y[Y_TH];
    s->omega_radps = y[Y_W];
}

static int sample_step(jc_Sim *sim, const gsl_odeiv2_system *sys, const slide_ctx *ctx, double t0,
                       const double y0[Y_DIM], double t_end)
{
    double ts;
    while (jc_sim_sample_due(sim, t_end, &ts)) {
        double y[Y_DIM];
        jc_State s;
        step_to(sim, sys, t0, y0, ts - t0, y);
        state_from_y(sim->m, y, ts, &s);
        jc_SlideForces f;
        jc_slide_forces(sim->m, s.theta_rad, s.omega_radps, ctx->dir, &f);
        const double loss = sim->friction_loss_J;
        sim->friction_loss_J = y[Y_LOSS];
        int st = jc_sim_sample(sim, &s, JC_MODE_SLIDING, f.normal_N, f.friction_N);
        sim->friction_loss_J = loss;
        if (st != JC_OK) return st;
    }
    return JC_OK;
}

int jc_slide_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len)
{
    slide_ctx ctx = {sim->m, sim->slip_dir};
    gsl_odeiv2_system sys = {slide_rhs, NULL, Y_DIM, &ctx};
    double y[Y_DIM] = {sim->s.x_m, sim->s.theta_rad, sim->s.vx_mps, sim->s.omega_radps, sim->friction_loss_J};
    double t = sim->s.t_s, h = 1e-4;
    const double t_max = sim->opt->t_max_s;
    gsl_odeiv2_evolve_reset(sim->ode_evolve);
    gsl_odeiv2_step_reset(sim->ode_step);

    double ev0[EV_COUNT], dev0[EV_COUNT];
    events(&ctx, y, ev0, dev0);
    for (long n = 0; n < SLIDE_MAX_STEPS; ++n) {
        if (t >= t_max) {
            state_from_y(sim->m, y, t, &sim->s);
            sim->friction_loss_J = y[Y_LOSS];
            *end = PHASE_TIME_LIMIT;
            return JC_OK;
        }
        double y0[Y_DIM];
        for (int i = 0; i < Y_DIM; ++i) y0[i] = y[i];
        const double t0 = t;
        const double h_rot = MAX_ROTATION_PER_STEP / fmax(fabs(y[Y_W]), 1e-3);
        if (h > h_rot) h = h_rot;
        int st = gsl_odeiv2_evolve_apply(sim->ode_evolve, sim->ode_control, sim->ode_step, &sys, &t, t_max, &h, y);
        sim->run->ode_steps++;
        if (st != GSL_SUCCESS)
            return jc_fail(err, err_len, JC_ENUMERIC, "sliding integration failed at t = %.9g s (%s)", t0,
                           gsl_strerror(st));
        double ev1[EV_COUNT], dev1[EV_COUNT];
        events(&ctx, y, ev1, dev1);
        /* The earliest event in the step: a sign change, or a dip between two positive ends. */
        int which = -1;
        double tau_hit = INFINITY;
        event_at ea = {sim, &sys, &ctx, t0, y0, 0};
        for (int k = 0; k < EV_COUNT; ++k) {
            ea.which = k;
            double hi = -1.0;
            if (ev1[k] <= 0.0) {
                hi = t - t0;
            } else if (dev0[k] < 0.0 && dev1[k] > 0.0) {
                const double tau = hermite_min_tau(ev0[k], dev0[k], ev1[k], dev1[k], t - t0);
                if (tau > 0.0 && event_value(tau, &ea) <= 0.0) hi = tau;
            }
            if (hi > 0.0) {
                const double tau = locate(&ea, hi, ev0[k], dev0[k]);
                if (tau < tau_hit) { tau_hit = tau; which = k; }
            }
        }
        if (which >= 0) {
            double yh[Y_DIM];
            step_to(sim, &sys, t0, y0, tau_hit, yh);
            if ((st = sample_step(sim, &sys, &ctx, t0, y0, t0 + tau_hit)) != JC_OK)
                return jc_fail(err, err_len, st, "out of memory for samples");
            state_from_y(sim->m, yh, t0 + tau_hit, &sim->s);
            sim->friction_loss_J = yh[Y_LOSS];
            *end = event_end(which);
            if (which == EV_SLIP) {
                /* The slip velocity is 0 here up to the location tolerance: make it exact. */
                sim->s.vx_mps = sim->m->body.radius_m * sim->s.omega_radps;
            }
            return JC_OK;
        }
        if ((st = sample_step(sim, &sys, &ctx, t0, y0, t)) != JC_OK)
            return jc_fail(err, err_len, st, "out of memory for samples");
        for (int k = 0; k < EV_COUNT; ++k) { ev0[k] = ev1[k]; dev0[k] = dev1[k]; }
    }
    state_from_y(sim->m, y, t, &sim->s);
    sim->friction_loss_J = y[Y_LOSS];
    *end = PHASE_STEP_LIMIT;
    return JC_OK;
}
