/*
 * sin and cos of one angle, inline, for the hot paths (the rolling path's
 * basis of cos k th, sin k th, the rolling time's integrand, the flight's
 * gap). Why not libm's sincos: it is a call through the PLT that saves and
 * restores the floating-point environment at every call, and it was the
 * largest single cost of a run (docs/performance.md). This one reduces the
 * angle by pi/2 in parts (Cody and Waite: three of at most 33 bits, whose
 * products with n are exact for |n| < 2^20, and the residue), then evaluates
 * the minimax polynomials of fdlibm's __kernel_sin and __kernel_cos on
 * [-pi/4, pi/4]. Outside |x| < 1e6 (where n could reach 2^20) and for NaN
 * or infinities it is libm's. tests/test_sincos.c holds it to libm.
 */
#ifndef JUMPCYL_SINCOS_H
#define JUMPCYL_SINCOS_H

#include <math.h>

static inline void jc_sincos(double x, double *sin_x, double *cos_x)
{
    if (!(fabs(x) < 1e6)) {
        *sin_x = sin(x);
        *cos_x = cos(x);
        return;
    }
    /* pi/2 = P1 + P2 + P3 + P4, the first three with 33 significant bits
     * or fewer (their products with n are exact), P4 the residue. */
    const double inv_pio2 = 6.36619772367581382433e-01;
    const double P1 = 1.57079632673412561417e+00, P2 = 6.07710050630396597660e-11,
                 P3 = 2.02226624871116645580e-21, P4 = 8.47842766036889956997e-32;
    const long long n = (long long)(x * inv_pio2 + (x >= 0.0 ? 0.5 : -0.5));
    const double fn = (double)n;
    const double r = (((x - fn * P1) - fn * P2) - fn * P3) - fn * P4;
    const double z = r * r, w = z * z;
    /* fdlibm's __kernel_sin (x + x^3 (S1 + z R)) and __kernel_cos (1 - z/2
     * with the rounding of 1 - z/2 carried) with no tail of the reduced angle. */
    const double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                 S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                 S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
    const double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                 C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                 C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
    const double sr = r + z * r * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    const double cq = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    const double hz = 0.5 * z, one_hz = 1.0 - hz;
    const double cr = one_hz + (((1.0 - one_hz) - hz) + z * cq);
    /* The quadrant: x = n pi/2 + r. */
    const int q = (int)(n & 3);
    const double s1 = (q & 1) ? cr : sr, c1 = (q & 1) ? -sr : cr;
    *sin_x = (q & 2) ? -s1 : s1;
    *cos_x = (q & 2) ? -c1 : c1;
}

#endif
