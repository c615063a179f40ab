/*
 * DOP853: the explicit Runge-Kutta pair 8(5,3) of Dormand and Prince with
 * its 7th-order continuous extension (Hairer, Norsett, Wanner, "Solving
 * Ordinary Differential Equations I", 2nd ed., section II.10). Internal.
 *
 * Why not GSL's rk8pd (kept as the cross-check in tests/sim/test_dop853.c):
 * rk8pd has no dense output, so every event search and every sample
 * re-stepped the integrator from the step's start (3 to 6 extra 13-stage
 * steps per event). With the continuous extension an event is found on a
 * polynomial and the state there costs 3 extra stages per step, and the
 * stepper keeps its workspace in fixed arrays (no allocation per run).
 * Measured (make bench, the paper's three runs): a full run took 85 us with
 * rk8pd and 49 us with this stepper, before the other speedups of the
 * same work (docs/architecture.md has the figure now). The step itself is
 * in dop853_kernel.h, from which each ODE phase makes its own instance.
 */
#ifndef JUMPCYL_DOP853_H
#define JUMPCYL_DOP853_H

/* Largest system: x, y, th, vx, vy, w, three losses, cos th, sin th. */
#define JC_DOP_MAX_DIM 12

/* The same signature as GSL's gsl_odeiv2_system function, so that one
 * right-hand side drives both integrators (the cross-check test). */
typedef int (*jc_DopRhs)(double t, const double y[], double dydt[], void *ctx);

typedef struct {
    int first;    /* components integrated: [first, first + dim) */
    int dim;
    int full_dim; /* components carried: the others below full_dim keep their start values */
    double rtol, atol;
    /* Component i's error is measured against atol + rtol max(|y_i|,
     * scale_floor[i]): a component whose own size says nothing of its
     * scale (a cosine passing through 0, a loss that starts at 0) gets
     * the caller's scale. 0 after jc_dop853_init: Hairer's norm. */
    double scale_floor[JC_DOP_MAX_DIM];
    /* The last accepted step, [t0, t0 + h]: y0 -> y1, f0 = f(y0), f1 = f(y1). */
    double t0, h;
    double y0[JC_DOP_MAX_DIM], y1[JC_DOP_MAX_DIM];
    double f0[JC_DOP_MAX_DIM], f1[JC_DOP_MAX_DIM];
    /* The stages' input: its components not integrated hold their start
     * values from jc_dop853_start on (set once, not per stage). */
    double ys[JC_DOP_MAX_DIM];
    /* Stages 2..16 (k[0] is unused: stage 1 is f0). */
    double k[17][JC_DOP_MAX_DIM];
    /* Continuous extension of the last accepted step, once prepared. */
    double cont[8][JC_DOP_MAX_DIM];
    double dense_h; /* the step it extends (kept when a later step overwrites h) */
    int dense_ready;
    /* Step size control. */
    int rejected_last;
    double log2_err_old; /* log2 of the last accepted step's error (PI control) */
} jc_Dop853;

void jc_dop853_init(jc_Dop853 *d, int dim, int full_dim, double rtol, double atol);
/* The same integrating components [first, first + dim) only: a phase whose
 * other components follow from these (rolling: x and vx from th and w). */
void jc_dop853_init_range(jc_Dop853 *d, int first, int dim, int full_dim, double rtol, double atol);
/* Starts at (t, y), y of full_dim components: evaluates f0. */
int jc_dop853_start(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double t, const double y[]);
/* One attempted step of size h from the current start. Returns the scaled
 * error (<= 1: accepted, then y1/f1 hold the new point and the next start
 * is y1) and the proposed next step in *h_next. A non-finite error is
 * returned as INFINITY (rejected). */
double jc_dop853_try(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, double *h_next);
/* The step size control of jc_dop853_try after a step with scaled error
 * err (INFINITY: failed), err^2 = err2_num / err2_den: the next step in
 * *h_next; returns err. */
double jc_dop853_control(jc_Dop853 *d, double err, double err2_num, double err2_den, double h, double *h_next);
/* jc_dop853_try of one right-hand side (dop853_kernel.h makes them). */
typedef double (*jc_DopTry)(jc_Dop853 *d, void *ctx, double h, double *h_next);
/* One step of size h with no error control (y1, f1 at t0 + h): for a step
 * no longer than an accepted one. 0, or -1 if it is not finite. */
int jc_dop853_step(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h);
/* A first step for the current start (after jc_dop853_start), by Hairer's
 * HINIT: the step whose Euler-step error estimate meets the tolerances,
 * no longer than h_max. One evaluation of rhs. */
double jc_dop853_initial_step(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h_max);
/* Moves the start to the end of the accepted step. */
void jc_dop853_advance(jc_Dop853 *d);
/* Prepares the continuous extension of the last accepted step (3 stages). */
int jc_dop853_dense(jc_Dop853 *d, jc_DopRhs rhs, void *ctx);
/* The interpolated state at t0 + tau, 0 <= tau <= h, on the last prepared
 * continuous extension (after jc_dop853_dense). */
void jc_dop853_eval(const jc_Dop853 *d, double tau, double y[]);

#endif
