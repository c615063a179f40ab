/*
 * The state of a DOP853 integration: what the step (dop853_kernel.h), its
 * size control (dop853_control.c) and the stepper (dop853.c, whose
 * dop853.h describes the method) share. Internal.
 */
#ifndef JUMPCYL_DOP853_STATE_H
#define JUMPCYL_DOP853_STATE_H

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

/* jc_dop853_try of one right-hand side (dop853_kernel.h makes them). */
typedef double (*jc_DopTry)(jc_Dop853 *d, void *ctx, double h, double *h_next);

#endif
