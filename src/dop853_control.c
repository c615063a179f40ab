/*
 * The step size control of DOP853 (Hairer's PI control, with his defaults
 * for DOP853), shared by the stepper (dop853.c) and each phase's own step
 * (dop853_kernel.h). Internal.
 */
#include "dop853_control.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* Step size control (Hairer's defaults for DOP853). The safety factor
 * 0.9 enters only as its log2. */
#define LOG2_SAFETY (-0.15200309344504995)
#define FAC_MIN 0.333 /* the step shrinks to at most this */
#define FAC_MAX 6.0   /* and grows by at most this */
#ifndef PI_BETA
#define PI_BETA 0.04
#endif
/* The smallest error the PI control remembers, 1e-4 (Hairer's), as log2. */
#define LOG2_ERR_MIN (-13.287712379549449)
/* Errors below this are taken as it: every factor is then clamped to
 * 1/FAC_MAX already (below ~4e-9), and log2 stays on normal numbers. */
#define ERR_TINY 1e-20
#define LOG2_ERR_TINY (-66.43856189774725) /* log2(ERR_TINY) */

/* The step size controller's powers err^(1/8 - 0.2 beta) / err_old^beta
 * by log2 and exp2 of our own, good to 1e-9 (a step size needs no more:
 * the factor only steers it), where libm's pow would be two calls per
 * step, plus calls of fmin and fmax. */
static double log2_pos(double x)
{
    /* x = m 2^e with m in [sqrt(1/2), sqrt(2)), x positive and normal, by
     * integer operations alone: the bits of x shifted by those of
     * sqrt(1/2) carry into the exponent exactly when x's mantissa is at
     * least sqrt(2)'s (the reduction of musl's log). A comparison there
     * was a branch taken about every other step, on the chain each next
     * step waits for. */
    const uint64_t sqrt_half = 0x3fe6a09e667f3bcdULL;
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    b += 0x3ff0000000000000ULL - sqrt_half;
    const int e = (int)(b >> 52) - 1023;
    b = (b & 0xfffffffffffffULL) + sqrt_half;
    double m;
    memcpy(&m, &b, sizeof m);
    /* ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.172: the series to s^9. */
    const double s = (m - 1.0) / (m + 1.0), s2 = s * s, s4 = s2 * s2;
    /* Estrin's grouping, here and in exp2_small, not Horner's: the next
     * step's size waits on these chains, and Estrin's are shorter. */
    const double ln_m = 2.0 * s * ((1.0 + s2 * (1.0 / 3)) + s4 * ((1.0 / 5 + s2 * (1.0 / 7)) + s4 * (1.0 / 9)));
    return e + ln_m * 1.4426950408889634074;
}

/* 2^y for |y| < 1000. */
static double exp2_small(double y)
{
    /* n, the nearest integer to y, by adding and taking away 1.5 2^52 (the
     * sum's last bits are n): two additions where a conversion to an
     * integer and back were four operations on the chain. */
    const double shifter = 6755399441055744.0;
    const double t = y + shifter, n = t - shifter;
    uint64_t tb;
    memcpy(&tb, &t, sizeof tb);
    const int64_t ni = (int64_t)(int32_t)(uint32_t)tb;
    const double f = (y - n) * 0.69314718055994530942; /* |f| <= ln 2 / 2: Taylor to f^9 */
    const double f2 = f * f, f4 = f2 * f2, f8 = f4 * f4;
    const double p = ((1.0 + f) + f2 * (1.0 / 2 + f * (1.0 / 6))) +
                     f4 * ((1.0 / 24 + f * (1.0 / 120)) + f2 * (1.0 / 720 + f * (1.0 / 5040))) +
                     f8 * (1.0 / 40320 + f * (1.0 / 362880));
    const uint64_t b = (uint64_t)(ni + 1023) << 52;
    double scale;
    memcpy(&scale, &b, sizeof scale);
    return p * scale;
}

static double min2(double a, double b) { return a < b ? a : b; }
static double max2(double a, double b) { return a > b ? a : b; }
void jc_dop853_control_init(jc_Dop853 *d)
{
    d->rejected_last = 0;
    d->log2_err_old = LOG2_ERR_MIN;
}

double jc_dop853_control(jc_Dop853 *d, double err, double err2_num, double err2_den, double h, double *h_next)
{
    if (!isfinite(err)) {
        *h_next = 0.1 * h;
        d->rejected_last = 1;
        return INFINITY;
    }
    /* log2 err from the two factors of err^2, each by its own log2 side by
     * side, not from err itself: err's division and square root are then
     * off the chain that each next step waits for, and so are the
     * divisions by the safety factor and of h (the factor is formed as the
     * step's growth, 1 / the factor of Hairer's code, and multiplies h).
     * The same steps as from err itself, the numbers the same to 1e-13. */
    const double log2_err =
        err2_num > (ERR_TINY * ERR_TINY) * err2_den ? 0.5 * (log2_pos(err2_num) - log2_pos(err2_den)) : LOG2_ERR_TINY;
    const double expo = 0.125 - 0.2 * PI_BETA;
    if (err <= 1.0) {
        /* 0.9 err^-expo err_old^beta */
        const double grow = exp2_small((LOG2_SAFETY + PI_BETA * d->log2_err_old) - expo * log2_err);
        *h_next = h * min2(FAC_MAX, max2(FAC_MIN, grow));
        if (d->rejected_last) *h_next = min2(*h_next, h);
        d->rejected_last = 0;
        d->log2_err_old = max2(log2_err, LOG2_ERR_MIN);
    } else {
        *h_next = h * max2(FAC_MIN, exp2_small(LOG2_SAFETY - expo * log2_err));
        d->rejected_last = 1;
    }
    return err;
}
