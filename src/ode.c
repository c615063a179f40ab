/*
 * A phase integrated with GSL's rk8pd, ended by the first of its events.
 *
 * Every phase that has no closed form (sliding; rolling and flight when air
 * or rolling resistance is on) supplies a right-hand side and event
 * functions, positive while the phase goes on. After each step an event is found by a sign change, or by a
 * dip below zero between two positive ends (the cubic Hermite interpolant of
 * the event function, checked against a real step); steps turn the body by
 * at most MAX_ROTATION_PER_STEP, the scale on which event functions vary.
 * The event is then located by a safeguarded Newton iteration on single
 * steps of the same method from the step's start, so the event state has
 * the integrator's accuracy.
 */
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <math.h>

/* rad: measured, results are the same to 12 digits for caps 0.1 to 1 rad. */
#define MAX_ROTATION_PER_STEP 0.3
/* Integrator steps per RUN, not per phase: phases that each stop short of a
 * per-phase bound (a flight's apexes, rolling turns, many events) would
 * multiply it into hours. A run that reaches it ends with step_limit. */
#define ODE_MAX_STEPS 10000000L

void jc_state_to_y(const jc_Sim *sim, double y[JC_Y_DIM])
{
    const jc_State *s = &sim->s;
    y[JC_Y_X] = s->x_m;
    y[JC_Y_Y] = s->y_m;
    y[JC_Y_TH] = s->theta_rad;
    y[JC_Y_VX] = s->vx_mps;
    y[JC_Y_VY] = s->vy_mps;
    y[JC_Y_W] = s->omega_radps;
    y[JC_Y_FRICTION] = sim->friction_loss_J;
    y[JC_Y_AIR] = sim->air_loss_J;
    y[JC_Y_RR] = sim->rr_loss_J;
}

void jc_y_to_state(const double y[JC_Y_DIM], double t, jc_State *s)
{
    *s = (jc_State){t, y[JC_Y_X], y[JC_Y_Y], y[JC_Y_VX], y[JC_Y_VY], y[JC_Y_TH], y[JC_Y_W]};
}

static int all_finite(const double y[JC_Y_DIM])
{
    for (int i = 0; i < JC_Y_DIM; ++i)
        if (!isfinite(y[i])) return 0;
    return 1;
}

static void y_to_sim(jc_Sim *sim, const double y[JC_Y_DIM], double t)
{
    jc_y_to_state(y, t, &sim->s);
    sim->friction_loss_J = y[JC_Y_FRICTION];
    sim->air_loss_J = y[JC_Y_AIR];
    sim->rr_loss_J = y[JC_Y_RR];
}

/* Event values and their rates along the flow, d/dt ev(y(t)) = grad ev . f(y),
 * by a central difference over a time step far below the rotation period:
 * accurate to ~1e-9, ample for Newton's iteration and the dip check. */
static void eval_events(const jc_OdePhase *p, const double y[JC_Y_DIM], double ev[], double dev[])
{
    p->events(p->ctx, y, ev);
    double f[JC_Y_DIM], yp[JC_Y_DIM], ym[JC_Y_DIM], evp[JC_ODE_MAX_EVENTS], evm[JC_ODE_MAX_EVENTS];
    p->rhs(0.0, y, f, p->ctx);
    const double h = 1e-6 / fmax(fabs(y[JC_Y_W]), 1.0);
    for (int i = 0; i < JC_Y_DIM; ++i) {
        yp[i] = y[i] + h * f[i];
        ym[i] = y[i] - h * f[i];
    }
    p->events(p->ctx, yp, evp);
    p->events(p->ctx, ym, evm);
    for (int k = 0; k < p->event_count; ++k) dev[k] = (evp[k] - evm[k]) / (2.0 * h);
}

typedef struct {
    jc_Sim *sim;
    const jc_OdePhase *p;
    const gsl_odeiv2_system *sys;
    double t0;
    const double *y0;
    int which;
} event_at;

/* y at t0 + tau, by one step of the integrator from (t0, y0). */
static void step_to(const event_at *ea, double tau, double y[JC_Y_DIM])
{
    double yerr[JC_Y_DIM];
    for (int i = 0; i < JC_Y_DIM; ++i) y[i] = ea->y0[i];
    if (tau > 0.0) gsl_odeiv2_step_apply(ea->sim->ode_step, ea->t0, tau, y, yerr, NULL, NULL, ea->sys);
}

static void event_at_tau(const event_at *ea, double tau, double *f, double *df)
{
    double y[JC_Y_DIM], ev[JC_ODE_MAX_EVENTS], dev[JC_ODE_MAX_EVENTS];
    step_to(ea, tau, y);
    if (df) {
        eval_events(ea->p, y, ev, dev);
        *df = dev[ea->which];
    } else {
        ea->p->events(ea->p->ctx, y, ev);
    }
    *f = ev[ea->which];
}

/* Root in (0, hi] of an event positive at 0 (value f0, rate d0) and <= 0 at
 * hi. Newton with the event's rate, kept inside the bracket (bisection
 * when it would leave it): measured, 3 to 4 integrator steps per event
 * against 10 to 14 for GSL's Brent solver, each step being 13 stages. */
static double locate(event_at *ea, double hi, double f0, double d0)
{
    double lo = 0.0, f_hi;
    event_at_tau(ea, hi, &f_hi, NULL);
    if (f_hi == 0.0) return hi;
    double tau = hi * f0 / (f0 - f_hi);
    if (d0 < 0.0 && -f0 / d0 < tau) tau = -f0 / d0;
    /* An event at exactly 0 where the step starts (the apex event of a
     * flight that starts at vy = 0) would be "found" there again and again
     * without time advancing (found by fuzzing: 10^5 apexes at t = 0 and a
     * step_limit). Its root at the start is not the crossing: search inside. */
    if (!(tau > 0.0 && tau < hi)) tau = 0.5 * hi;
    const double tol = 0.5 * ea->sim->opt->event_tol_s;
    for (int it = 0; it < 60 && hi - lo > tol; ++it) {
        double f, df;
        event_at_tau(ea, tau, &f, &df);
        if (f == 0.0) return tau;
        if (f > 0.0) lo = tau;
        else hi = tau;
        double next = df != 0.0 ? tau - f / df : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (fabs(next - tau) < tol) {
            /* Converged: return a time at which the event has happened. */
            const double t_hit = fmin(next + tol, hi);
            event_at_tau(ea, t_hit, &f, NULL);
            return f <= 0.0 ? t_hit : hi;
        }
        tau = next;
    }
    return hi; /* the event has happened there: its function is <= 0 */
}

/* Where the cubic Hermite interpolant of a positive-ended event function dips
 * lowest, if it dips markedly; -1 otherwise. */
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

static int emit_samples(event_at *ea, double t_end)
{
    double ts;
    while (jc_sim_sample_due(ea->sim, t_end, &ts)) {
        double y[JC_Y_DIM];
        step_to(ea, ts - ea->t0, y);
        int st = ea->p->sample(ea->sim, ea->p->ctx, ts, y);
        if (st != JC_OK) return st;
    }
    return JC_OK;
}

/* The earliest event inside the step just taken from (t0, y0) to t. */
static int first_event_in_step(event_at *ea, double h, const double ev0[], const double dev0[],
                               const double ev1[], const double dev1[], double *tau_hit)
{
    int which = -1;
    *tau_hit = INFINITY;
    for (int k = 0; k < ea->p->event_count; ++k) {
        ea->which = k;
        double hi = -1.0;
        if (ev1[k] <= 0.0) {
            hi = h;
        } else if (dev0[k] < 0.0 && dev1[k] > 0.0) {
            const double tau = hermite_min_tau(ev0[k], dev0[k], ev1[k], dev1[k], h);
            double f;
            if (tau > 0.0) {
                event_at_tau(ea, tau, &f, NULL);
                if (f <= 0.0) hi = tau;
            }
        }
        if (hi > 0.0) {
            const double tau = locate(ea, hi, ev0[k], dev0[k]);
            if (tau < *tau_hit) { *tau_hit = tau; which = k; }
        }
    }
    return which;
}

int jc_ode_run(jc_Sim *sim, const jc_OdePhase *p, int *which, char *err, size_t err_len)
{
    gsl_odeiv2_system sys = {p->rhs, NULL, JC_Y_DIM, p->ctx};
    double y[JC_Y_DIM], t = sim->s.t_s, h = 1e-4;
    jc_state_to_y(sim, y);
    const double t_max = sim->opt->t_max_s;
    gsl_odeiv2_evolve_reset(sim->ode_evolve);
    gsl_odeiv2_step_reset(sim->ode_step);
    double ev0[JC_ODE_MAX_EVENTS], dev0[JC_ODE_MAX_EVENTS];
    eval_events(p, y, ev0, dev0);
    *which = JC_ODE_TIME_LIMIT;
    while (sim->run->ode_steps < ODE_MAX_STEPS) {
        if (t >= t_max) {
            y_to_sim(sim, y, t);
            return JC_OK;
        }
        double y0[JC_Y_DIM];
        for (int i = 0; i < JC_Y_DIM; ++i) y0[i] = y[i];
        const double t0 = t;
        const double h_rot = MAX_ROTATION_PER_STEP / fmax(fabs(y[JC_Y_W]), 1e-3);
        if (h > h_rot) h = h_rot;
        int st = gsl_odeiv2_evolve_apply(sim->ode_evolve, sim->ode_control, sim->ode_step, &sys, &t, t_max, &h, y);
        sim->run->ode_steps++;
        if (st != GSL_SUCCESS)
            return jc_fail(err, err_len, JC_ENUMERIC, "integration failed at t = %.9g s (%s)", t0, gsl_strerror(st));
        if (!all_finite(y)) {
            /* GSL accepts a step whose error estimate is NaN (a stage that
             * overflowed: a stiff spin drag on a tiny inertia, found by
             * fuzzing). Take it back and retry a tenth as long; a step
             * that cannot be made finite is a reported failure. */
            const double tried = t - t0;
            for (int i = 0; i < JC_Y_DIM; ++i) y[i] = y0[i];
            t = t0;
            h = 0.1 * tried;
            gsl_odeiv2_evolve_reset(sim->ode_evolve);
            if (!(h > 1e-12 * fmax(fabs(t0), 1e-3)))
                return jc_fail(err, err_len, JC_ENUMERIC,
                               "integration diverged at t = %.9g s (no finite step; the setup is too stiff)", t0);
            continue;
        }
        double ev1[JC_ODE_MAX_EVENTS], dev1[JC_ODE_MAX_EVENTS];
        eval_events(p, y, ev1, dev1);
        event_at ea = {sim, p, &sys, t0, y0, 0};
        double tau;
        const int k = first_event_in_step(&ea, t - t0, ev0, dev0, ev1, dev1, &tau);
        if (k >= 0) {
            double yh[JC_Y_DIM];
            step_to(&ea, tau, yh);
            if ((st = emit_samples(&ea, t0 + tau)) != JC_OK) return jc_fail(err, err_len, st, "out of memory for samples");
            y_to_sim(sim, yh, t0 + tau);
            *which = k;
            return JC_OK;
        }
        if ((st = emit_samples(&ea, t)) != JC_OK) return jc_fail(err, err_len, st, "out of memory for samples");
        for (int i = 0; i < p->event_count; ++i) { ev0[i] = ev1[i]; dev0[i] = dev1[i]; }
    }
    y_to_sim(sim, y, t);
    *which = JC_ODE_STEP_LIMIT;
    return JC_OK;
}
