/*
 * A phase integrated with DOP853 (dop853.c), ended by the first of its events.
 *
 * Every phase that has no closed form (sliding; rolling and flight when air
 * or rolling resistance is on) supplies a right-hand side and event
 * functions, positive while the phase goes on. After each accepted step an
 * event is found by a sign change at the step's end, or by a dip below zero
 * between two positive ends (the cubic Hermite interpolant of the event
 * function, confirmed on the step's continuous extension); steps turn the
 * body by at most MAX_ROTATION_PER_STEP, the scale on which event functions
 * vary. The event is then located on the continuous extension (no
 * re-stepping) and the state there is made by one real step of the method
 * from the step's start, checked to be past the event: the event state has
 * the integrator's own accuracy.
 */
#include "internal.h"

#include <math.h>
#include <string.h>

/* rad: measured, results are the same to 12 digits for caps 0.1 to 1 rad. */
#define MAX_ROTATION_PER_STEP 0.3
/* Integrator steps per RUN, not per phase: phases that each stop short of a
 * per-phase bound (a flight's apexes, rolling turns, many events) would
 * multiply it into hours. A run that reaches it ends with step_limit. */
#define ODE_MAX_STEPS 10000000L

/* The smaller and larger of two numbers that are not NaN, inline: libm's
 * fmin and fmax are calls (GCC keeps them for their NaN rule), and the
 * step's own bound sits on the path each step waits for. */
static inline double min_d(double a, double b) { return b < a ? b : a; }
static inline double max_d(double a, double b) { return b > a ? b : a; }

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
    y[JC_Y_COS] = cos(s->theta_rad);
    y[JC_Y_SIN] = sin(s->theta_rad);
}

void jc_y_to_state(const double y[JC_Y_DIM], double t, jc_State *s)
{
    *s = (jc_State){t, y[JC_Y_X], y[JC_Y_Y], y[JC_Y_VX], y[JC_Y_VY], y[JC_Y_TH], y[JC_Y_W]};
}

static void y_to_sim(jc_Sim *sim, const double y[JC_Y_DIM], double t)
{
    jc_y_to_state(y, t, &sim->s);
    sim->friction_loss_J = y[JC_Y_FRICTION];
    sim->air_loss_J = y[JC_Y_AIR];
    sim->rr_loss_J = y[JC_Y_RR];
}

/* Event values and their rates along the flow, d/dt ev(y(t)) = grad ev . f,
 * from the phase's closed form, or by a central difference over a time step
 * far below the rotation period: accurate to ~1e-9, ample for the dip
 * check. f = f(y) is given. */
static void eval_events(const jc_OdePhase *p, const double y[JC_Y_DIM], const double f[JC_Y_DIM], double ev[],
                        double dev[])
{
    p->events(p->ctx, y, ev);
    if (p->event_rates) {
        p->event_rates(p->ctx, y, f, dev);
        return;
    }
    double yp[JC_Y_DIM], ym[JC_Y_DIM], evp[JC_ODE_MAX_EVENTS], evm[JC_ODE_MAX_EVENTS];
    const double h = 1e-6 / fmax(fabs(y[JC_Y_W]), 1.0);
    for (int i = 0; i < JC_Y_DIM; ++i) {
        yp[i] = y[i] + h * f[i];
        ym[i] = y[i] - h * f[i];
    }
    p->events(p->ctx, yp, evp);
    p->events(p->ctx, ym, evm);
    for (int k = 0; k < p->event_count; ++k) dev[k] = (evp[k] - evm[k]) / (2.0 * h);
}

/* Event k on the continuous extension at t0 + tau. */
static double dense_event(const jc_Sim *sim, const jc_OdePhase *p, int k, double tau)
{
    double y[JC_Y_DIM], ev[JC_ODE_MAX_EVENTS];
    jc_dop853_eval(&sim->dop, tau, y);
    p->events(p->ctx, y, ev);
    return ev[k];
}

/* Root of event k on the continuous extension in (lo, hi], where it is > 0
 * (or 0) at lo and <= 0 at hi: the Illinois variant of regula falsi, which
 * keeps the bracket and converges superlinearly. Returns the bracket's
 * right end, a time at which the event has happened on the interpolant
 * (never lo: a phase always advances). */
static double locate_dense(const jc_Sim *sim, const jc_OdePhase *p, int k, double lo, double f0, double hi,
                           double tol)
{
    double a = lo, fa = fmax(f0, 0.0), b = hi, fb = dense_event(sim, p, k, hi);
    int side = 0;
    for (int it = 0; it < 200 && b - a > tol && fb < 0.0; ++it) {
        /* fa = 0 only at the start, where the event function starts at zero
         * (a sliding phase from a slip onset): the secant through that zero
         * returns the start itself, or, rounded, a point a few ulps past it
         * where the function is still zero, which would end the phase
         * without advancing it (found: 41000 phases at one instant in a
         * random setup). Bisect instead. */
        double c = fa > 0.0 && fa - fb != 0.0 ? b - fb * (b - a) / (fb - fa) : 0.5 * (a + b);
        if (!(c > a && c < b)) c = 0.5 * (a + b);
        const double fc = dense_event(sim, p, k, c);
        if (fc > 0.0) {
            a = c;
            fa = fc;
            if (side == 1) fb *= 0.5;
            side = 1;
        } else {
            b = c;
            fb = fc;
            if (side == -1) fa *= 0.5;
            side = -1;
        }
    }
    return b;
}

/* Where the cubic Hermite interpolant of a positive-ended event function dips
 * lowest, if it dips markedly; -1 otherwise. */
static double hermite_min_tau(double f0, double d0, double f1, double d1, double h)
{
    double best_tau = -1.0, best = min_d(f0, f1);
    for (int k = 1; k < 16; ++k) {
        const double s = k / 16.0, s2 = s * s, s3 = s2 * s;
        const double v = (2 * s3 - 3 * s2 + 1) * f0 + (s3 - 2 * s2 + s) * h * d0 +
                         (-2 * s3 + 3 * s2) * f1 + (s3 - s2) * h * d1;
        if (v < best) { best = v; best_tau = s * h; }
    }
    return best < 0.5 * min_d(f0, f1) ? best_tau : -1.0;
}

/* The earliest event inside the accepted step after lo (its start, or a
 * passed event; ev0, dev0 there), continuous extension ready when needed,
 * its time after the step's start in *tau_hit; -1 for none. */
static int first_event_in_step(jc_Sim *sim, const jc_OdePhase *p, double lo, const double ev0[],
                               const double dev0[], const double ev1[], const double dev1[], double *tau_hit, int *st)
{
    const double h = sim->dop.h, tol = 0.5 * sim->opt->event_tol_s;
    int which = -1;
    *tau_hit = INFINITY;
    for (int k = 0; k < p->event_count; ++k) {
        double hi = -1.0;
        const double dip = ev1[k] > 0.0 && dev0[k] < 0.0 && dev1[k] > 0.0
                               ? hermite_min_tau(ev0[k], dev0[k], ev1[k], dev1[k], h - lo) : -1.0;
        if (ev1[k] > 0.0 && !(dip > 0.0)) continue;
        if ((*st = jc_dop853_dense(&sim->dop, p->rhs, p->ctx)) != 0) return -1;
        if (ev1[k] <= 0.0) hi = h;
        else if (dense_event(sim, p, k, lo + dip) <= 0.0) hi = lo + dip;
        if (hi > 0.0) {
            const double tau = locate_dense(sim, p, k, lo, ev0[k], hi, tol);
            if (tau < *tau_hit) { *tau_hit = tau; which = k; }
        }
    }
    return which;
}

/* A phase's events that it passes through (p->pass) without ending, per
 * step: past this many, the next ends the phase the ordinary way. */
#define MAX_PASSES_PER_STEP 8

/* The first event in the accepted step that ends the phase (-1 for none;
 * its time in *tau_hit): those the phase passes through are handed to it
 * at their state on the continuous extension and the search goes on from
 * there, in the same step. ev0, dev0 are those at the step's start, and
 * are overwritten; ev1, dev1 at its end are refreshed after a pass (which
 * may change the event functions). */
static int first_ending_event(jc_Sim *sim, const jc_OdePhase *p, jc_OdePass pass, double ev0[], double dev0[], double ev1[],
                              double dev1[], double *tau_hit, int *st)
{
    jc_Dop853 *d = &sim->dop;
    double lo = 0.0;
    for (int passes = 0;; ++passes) {
        const int k = first_event_in_step(sim, p, lo, ev0, dev0, ev1, dev1, tau_hit, st);
        if (k < 0 || *st != 0 || !pass || passes >= MAX_PASSES_PER_STEP) return k;
        double y[JC_Y_DIM], f[JC_Y_DIM];
        jc_dop853_eval(d, *tau_hit, y);
        if (!pass(sim, p->ctx, k, d->t0 + *tau_hit, y)) return k;
        if ((*st = p->rhs(d->t0 + *tau_hit, y, f, p->ctx)) != 0) return -1;
        eval_events(p, y, f, ev0, dev0);
        eval_events(p, d->y1, d->f1, ev1, dev1);
        lo = *tau_hit;
    }
}

/* The state at the located event by a real step from the step's start,
 * corrected by Newton's iteration on real steps until the event has
 * happened on it, by no more than the tolerance: the event state carries
 * the method's accuracy, not the interpolant's. (The interpolant is good to
 * the tolerance where the right-hand side is smooth; at a kink, such as the
 * Magnus force's spin ratio at zero slip, only a real step ending at the
 * event is.) Returns the step taken (no longer than the accepted one). */
static double event_state(jc_Sim *sim, const jc_OdePhase *p, int k, double tau, double y[JC_Y_DIM])
{
    jc_Dop853 *d = &sim->dop;
    const double h_acc = d->h, tol = sim->opt->event_tol_s;
    double t_try = fmin(tau + 0.5 * tol, h_acc);
    double happened_at = -1.0; /* the last step length at which the event had happened */
    for (int attempt = 0; attempt < 8; ++attempt) {
        double ev[JC_ODE_MAX_EVENTS], dev[JC_ODE_MAX_EVENTS];
        if (jc_dop853_step(d, p->rhs, p->ctx, t_try) != 0) break;
        for (int i = 0; i < JC_Y_DIM; ++i) y[i] = d->y1[i];
        eval_events(p, y, d->f1, ev, dev);
        const double lag = dev[k] < 0.0 ? ev[k] / -dev[k] : (ev[k] > 0.0 ? tol : 0.0); /* time to the root */
        if (ev[k] <= 0.0) {
            happened_at = t_try;
            if (-lag <= tol || t_try <= 0.5 * tol) return t_try; /* past the root by at most tol */
        } else if (t_try >= h_acc) {
            return t_try;
        }
        t_try = fmin(fmax(t_try + lag + 0.5 * tol, 0.5 * tol), h_acc);
    }
    if (happened_at > 0.0 && jc_dop853_step(d, p->rhs, p->ctx, happened_at) == 0) {
        for (int i = 0; i < JC_Y_DIM; ++i) y[i] = d->y1[i];
        return happened_at;
    }
    /* Not finite at a time the accepted step passed: keep the interpolant's. */
    jc_dop853_eval(d, tau, y);
    return tau;
}

static int emit_samples(jc_Sim *sim, const jc_OdePhase *p, double t_end)
{
    double ts;
    while (jc_record_sample_due(sim, t_end, &ts)) {
        if (jc_dop853_dense(&sim->dop, p->rhs, p->ctx) != 0) return JC_ENUMERIC;
        double y[JC_Y_DIM];
        jc_dop853_eval(&sim->dop, ts - sim->dop.t0, y);
        const int st = p->sample(sim, p->ctx, ts, y);
        if (st != JC_OK) return st;
    }
    return JC_OK;
}

static int sample_failure(int st, char *err, size_t err_len)
{
    return st == JC_ENUMERIC ? jc_fail(err, err_len, st, "the integrator's right-hand side failed")
                             : jc_fail(err, err_len, st, "out of memory for samples");
}

int jc_ode_run_with(jc_Sim *sim, const jc_OdePhase *p, const jc_OdeExtras *x, int *which, char *err,
                    size_t err_len)
{
    const jc_OdePass pass = x->pass;
    jc_Dop853 *d = &sim->dop;
    double y[JC_Y_DIM];
    jc_state_to_y(sim, y);
    const double t_max = sim->opt->t_max_s;
    jc_dop853_init_range(d, x->first, p->dim, JC_Y_DIM, sim->opt->ode_rtol, sim->opt->ode_atol);
    /* cos th and sin th are measured on the unit circle's scale, not their
     * own (near a zero of either, relative error asked for th far below
     * th's own tolerance). The losses are measured on the energy the run
     * converts, the kinetic energy now plus M g (r + d + L sin a), the
     * accuracy to which K + U themselves are known: on their own size, a
     * loss starting at 0 held every sliding step to the absolute
     * tolerance, with steps the motion did not need (first lift-off the
     * same to 2e-13 s with either scale). */
    const jc_Model *m = sim->m;
    double energy_scale_J =
        jc_kinetic_energy(m, &sim->s) +
        m->body.mass_kg * m->setup.gravity_mps2 *
            (m->body.radius_m + m->body.cm_offset_m + m->setup.ramp_length_m * m->sin_incline);
    if (!(energy_scale_J < INFINITY)) energy_scale_J = 0.0; /* then on their own size */
    d->scale_floor[JC_Y_COS] = d->scale_floor[JC_Y_SIN] = 1.0;
    /* The centre's velocity components on the body's speed (the centre's
     * and the rim's), not on their own size: vy passes through 0 at every
     * apex of a flight, where its own size held the steps of the drag runs'
     * flights (it limited most of them). */
    const double speed_scale_mps =
        sqrt(sim->s.vx_mps * sim->s.vx_mps + sim->s.vy_mps * sim->s.vy_mps) +
        m->body.radius_m * fabs(sim->s.omega_radps);
    d->scale_floor[JC_Y_VX] = d->scale_floor[JC_Y_VY] = speed_scale_mps < INFINITY ? speed_scale_mps : 0.0;
    d->scale_floor[JC_Y_FRICTION] = d->scale_floor[JC_Y_AIR] = d->scale_floor[JC_Y_RR] = energy_scale_J;
    if (jc_dop853_start(d, p->rhs, p->ctx, sim->s.t_s, y) != 0)
        return jc_fail(err, err_len, JC_ENUMERIC, "integration failed at t = %.9g s", sim->s.t_s);
    double h = sim->ode_h_s;
    if (!(h > 0.0))
        h = jc_dop853_initial_step(d, p->rhs, p->ctx, MAX_ROTATION_PER_STEP / fmax(fabs(d->y0[JC_Y_W]), 1e-3));
    /* Whole arrays, zeroed past the phase's events: copied from the step's
     * end to its start at a fixed size (a copy of event_count values was
     * two calls of memcpy per step). */
    double ev0[JC_ODE_MAX_EVENTS] = {0}, dev0[JC_ODE_MAX_EVENTS] = {0};
    double ev1[JC_ODE_MAX_EVENTS] = {0}, dev1[JC_ODE_MAX_EVENTS] = {0};
    eval_events(p, d->y0, d->f0, ev0, dev0);
    *which = JC_ODE_TIME_LIMIT;
    while (sim->run->ode_steps < ODE_MAX_STEPS) {
        const double t0 = d->t0;
        if (t0 >= t_max) {
            y_to_sim(sim, d->y0, t0);
            return JC_OK;
        }
        /* y0 is finite here (the last step's end passed end_rate) */
        const double h_rot = MAX_ROTATION_PER_STEP / max_d(fabs(d->y0[JC_Y_W]), 1e-3);
        h = min_d(h, h_rot);
        const int last = t0 + h >= t_max;
        if (last) h = t_max - t0;
        double h_next;
        const double e =
            p->try_step ? p->try_step(d, p->ctx, h, &h_next) : jc_dop853_try(d, p->rhs, p->ctx, h, &h_next);
        sim->run->ode_steps++;
        if (!(e <= 1.0)) {
            /* Rejected, or a stage that overflowed (a stiff spin drag on a
             * tiny inertia, found by fuzzing): retry shorter; a step that
             * cannot be made finite is a reported failure. */
            if (!(h_next > 1e-12 * fmax(fabs(t0), 1e-3)))
                return jc_fail(err, err_len, JC_ENUMERIC,
                               "integration diverged at t = %.9g s (no finite step; the setup is too stiff)", t0);
            h = h_next;
            continue;
        }
        if (!last) sim->ode_h_s = h; /* a step cut by the time limit says nothing of the next phase */
        eval_events(p, d->y1, d->f1, ev1, dev1);
        double tau;
        int st = 0;
        const int k = first_ending_event(sim, p, pass, ev0, dev0, ev1, dev1, &tau, &st);
        if (st != 0) return jc_fail(err, err_len, JC_ENUMERIC, "integration failed at t = %.9g s", t0);
        if (k >= 0) {
            if ((st = emit_samples(sim, p, t0 + tau)) != JC_OK) return sample_failure(st, err, err_len);
            double yh[JC_Y_DIM];
            const double t_event = t0 + event_state(sim, p, k, tau, yh);
            y_to_sim(sim, yh, t_event);
            *which = k;
            return JC_OK;
        }
        if ((st = emit_samples(sim, p, t0 + d->h)) != JC_OK) return sample_failure(st, err, err_len);
        jc_dop853_advance(d);
        if (last) d->t0 = t_max;
        memcpy(ev0, ev1, sizeof ev0);
        memcpy(dev0, dev1, sizeof dev0);
        h = h_next;
    }
    y_to_sim(sim, d->y0, d->t0);
    *which = JC_ODE_STEP_LIMIT;
    return JC_OK;
}

int jc_ode_run(jc_Sim *sim, const jc_OdePhase *p, int *which, char *err, size_t err_len)
{
    const jc_OdeExtras none = {0, NULL};
    return jc_ode_run_with(sim, p, &none, which, err, err_len);
}
