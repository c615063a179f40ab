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
 * stepper keeps its workspace in fixed arrays (no allocation per run). The
 * step itself is in dop853_kernel.h, from which each ODE phase makes its
 * own instance.
 */
#ifndef JUMPCYL_DOP853_H
#define JUMPCYL_DOP853_H

#include "dop853_state.h"

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
