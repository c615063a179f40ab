/* A function T0(th) + th T1(th) of src/trigpoly.c evaluated by its
 * definition, with libm's cos(k th) and sin(k th) for each k: the
 * reference the trigonometric-polynomial and rolling tests compare with. */
#ifndef JC_TRIG_DIRECT_H
#define JC_TRIG_DIRECT_H

#include "../src/internal.h"

#include <math.h>

static inline double trig_direct(const jc_TrigLin *p, double th)
{
    double t0 = 0, t1 = 0;
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k) {
        t0 += p->c0[k] * cos(k * th) + p->s0[k] * sin(k * th);
        t1 += p->c1[k] * cos(k * th) + p->s1[k] * sin(k * th);
    }
    return t0 + th * t1;
}

#endif
