/*
 * The step size control of DOP853 (dop853_control.c): what the stepper
 * (dop853.c) and each phase's own step (dop853_kernel.h) call after the
 * stages of a step. Internal.
 */
#ifndef JUMPCYL_DOP853_CONTROL_H
#define JUMPCYL_DOP853_CONTROL_H

#include "dop853_state.h"

/* The control's memory at the start of an integration (no error yet). */
void jc_dop853_control_init(jc_Dop853 *d);
/* The step size control after a step of size h with scaled error err
 * (INFINITY: failed), err^2 = err2_num / err2_den: the next step in
 * *h_next; returns err. */
double jc_dop853_control(jc_Dop853 *d, double err, double err2_num, double err2_den, double h, double *h_next);

#endif
