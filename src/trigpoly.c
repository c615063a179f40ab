/*
 * Functions of the form f(th) = T0(th) + th T1(th), where T0 and T1 are
 * trigonometric polynomials of low degree.
 *
 * Why this exists: on the rolling solution, I_P w^2, N I_P^2 and F I_P^2 are
 * exactly of this form (the energy integral is linear in th through the
 * r th sin(alpha) descent), and so is the paper's Eq. 9 cleared of its
 * denominators. Holding them as coefficients gives exact derivatives and a
 * cheap, rigorous bound on |f''| over a range of th, which is what lets the
 * crossing search in scan.c take large steps and still never step over a
 * root.
 */
#include "internal.h"

#include <math.h>
#include <string.h>

void jc_tl_zero(jc_TrigLin *p) { memset(p, 0, sizeof *p); }

void jc_tl_add_cos(jc_TrigLin *p, int lin, int k, double a)
{
    if (k < 0) k = -k; /* cos(-k th) = cos(k th) */
    (lin ? p->c1 : p->c0)[k] += a;
}

void jc_tl_add_sin(jc_TrigLin *p, int lin, int k, double a)
{
    if (k == 0) return;
    if (k < 0) { k = -k; a = -a; } /* sin(-k th) = -sin(k th) */
    (lin ? p->s1 : p->s0)[k] += a;
}

void jc_tl_axpby(jc_TrigLin *out, double a, const jc_TrigLin *x, double b, const jc_TrigLin *y)
{
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k) {
        out->c0[k] = a * x->c0[k] + b * y->c0[k];
        out->s0[k] = a * x->s0[k] + b * y->s0[k];
        out->c1[k] = a * x->c1[k] + b * y->c1[k];
        out->s1[k] = a * x->s1[k] + b * y->s1[k];
    }
}

static int degree_of(const double *c, const double *s)
{
    int deg = -1;
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k)
        if (c[k] != 0.0 || s[k] != 0.0) deg = k;
    return deg;
}

static int has_lin(const jc_TrigLin *p) { return degree_of(p->c1, p->s1) >= 0; }

static int degree(const jc_TrigLin *p)
{
    int d0 = degree_of(p->c0, p->s0), d1 = degree_of(p->c1, p->s1);
    return d0 > d1 ? d0 : d1;
}

/* Adds (xc, xs) * (yc, ys) into (oc, os), by product-to-sum, for the terms
 * up to degrees dx and dy, dx + dy <= JC_TRIG_DEGREE. The loops stop at the
 * degrees rather than skipping zero products: with an infinite or NaN
 * coefficient a "zero" product is NaN, and i + j would index past the
 * arrays (found by fuzzing: a 1e308 kg part overflowed the model). */
static void mul_into(double *oc, double *os, const double *xc, const double *xs, int dx,
                     const double *yc, const double *ys, int dy)
{
    for (int i = 0; i <= dx; ++i) {
        for (int j = 0; j <= dy; ++j) {
            double cc = xc[i] * yc[j], ss = xs[i] * ys[j];
            double sc = xs[i] * yc[j], cs = xc[i] * ys[j];
            if (cc == 0.0 && ss == 0.0 && sc == 0.0 && cs == 0.0) continue;
            int sum = i + j, dif = i - j;
            /* cos a cos b = (cos(a-b) + cos(a+b))/2; sin a sin b = (cos(a-b) - cos(a+b))/2 */
            oc[dif < 0 ? -dif : dif] += 0.5 * (cc + ss);
            oc[sum] += 0.5 * (cc - ss);
            /* sin a cos b = (sin(a+b) + sin(a-b))/2; cos a sin b = (sin(a+b) - sin(a-b))/2 */
            if (sum > 0) os[sum] += 0.5 * (sc + cs);
            if (dif > 0) os[dif] += 0.5 * (sc - cs);
            else if (dif < 0) os[-dif] -= 0.5 * (sc - cs);
        }
    }
}

int jc_tl_mul(jc_TrigLin *out, const jc_TrigLin *x, const jc_TrigLin *y)
{
    const int dx = degree(x), dy = degree(y);
    if ((has_lin(x) && has_lin(y)) || dx + dy > JC_TRIG_DEGREE)
        return JC_EINVAL;
    jc_TrigLin r;
    jc_tl_zero(&r);
    mul_into(r.c0, r.s0, x->c0, x->s0, dx, y->c0, y->s0, dy);
    mul_into(r.c1, r.s1, x->c1, x->s1, dx, y->c0, y->s0, dy);
    mul_into(r.c1, r.s1, x->c0, x->s0, dx, y->c1, y->s1, dy);
    *out = r;
    return JC_OK;
}

void jc_tl_eval(const jc_TrigLin *p, double th, double *f, double *df)
{
    /* cos(k th), sin(k th) by the angle-addition recurrence: one sincos call. */
    double c1, s1;
    jc_sincos(th, &s1, &c1);
    double ck = 1.0, sk = 0.0;
    double t0 = 0.0, d0 = 0.0, t1 = 0.0, d1 = 0.0;
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k) {
        t0 += p->c0[k] * ck + p->s0[k] * sk;
        d0 += k * (p->s0[k] * ck - p->c0[k] * sk);
        t1 += p->c1[k] * ck + p->s1[k] * sk;
        d1 += k * (p->s1[k] * ck - p->c1[k] * sk);
        double cn = ck * c1 - sk * s1;
        sk = sk * c1 + ck * s1;
        ck = cn;
    }
    *f = t0 + th * t1;
    if (df) *df = d0 + t1 + th * d1;
}

double jc_tl_value(const jc_TrigLin *p, double th)
{
    double f;
    jc_tl_eval(p, th, &f, NULL);
    return f;
}

double jc_tl_magnitude_bound(const jc_TrigLin *p, double th_abs_max)
{
    double b0 = 0.0, b1 = 0.0;
    for (int k = 0; k <= JC_TRIG_DEGREE; ++k) {
        b0 += fabs(p->c0[k]) + fabs(p->s0[k]);
        b1 += fabs(p->c1[k]) + fabs(p->s1[k]);
    }
    return b0 + th_abs_max * b1;
}

double jc_tl_curvature_bound(const jc_TrigLin *p, double th_abs_max)
{
    /* f'' = T0'' + 2 T1' + th T1'', and |d^n/dth^n (a cos k th + b sin k th)| <= k^n (|a|+|b|). */
    double b0 = 0.0, b1 = 0.0, b2 = 0.0;
    for (int k = 1; k <= JC_TRIG_DEGREE; ++k) {
        double kk = (double)k * k;
        b0 += kk * (fabs(p->c0[k]) + fabs(p->s0[k]));
        b1 += k * (fabs(p->c1[k]) + fabs(p->s1[k]));
        b2 += kk * (fabs(p->c1[k]) + fabs(p->s1[k]));
    }
    /* 1 + 1e-12: covers rounding in the sums above. */
    return (b0 + 2.0 * b1 + th_abs_max * b2) * (1.0 + 1e-12);
}

void jc_tl_basis(jc_TrigBasis *b, double th)
{
    double c1, s1;
    jc_sincos(th, &s1, &c1);
    b->th = th;
    b->c[0] = 1.0;
    b->s[0] = 0.0;
    for (int k = 1; k <= JC_TRIG_DEGREE; ++k) {
        b->c[k] = b->c[k - 1] * c1 - b->s[k - 1] * s1;
        b->s[k] = b->s[k - 1] * c1 + b->c[k - 1] * s1;
    }
}

int jc_tl_degree(const jc_TrigLin *p)
{
    return degree(p);
}

void jc_tl_eval3_basis(const jc_TrigLin *p, const jc_TrigBasis *b, double out[3])
{
    jc_tl_eval3_basis_upto(p, b, JC_TRIG_DEGREE, out);
}

void jc_tl_eval3_basis_upto(const jc_TrigLin *p, const jc_TrigBasis *b, int deg, double out[3])
{
    static const double kd[JC_TRIG_DEGREE + 1] = {0, 1, 2, 3, 4}, k2[JC_TRIG_DEGREE + 1] = {0, 1, 4, 9, 16};
    double t0 = 0.0, d0 = 0.0, e0 = 0.0, t1 = 0.0, d1 = 0.0, e1 = 0.0;
    for (int k = 0; k <= deg; ++k) {
        const double ck = b->c[k], sk = b->s[k];
        const double a0 = p->c0[k] * ck + p->s0[k] * sk, a1 = p->c1[k] * ck + p->s1[k] * sk;
        t0 += a0;
        d0 += kd[k] * (p->s0[k] * ck - p->c0[k] * sk);
        e0 -= k2[k] * a0;
        t1 += a1;
        d1 += kd[k] * (p->s1[k] * ck - p->c1[k] * sk);
        e1 -= k2[k] * a1;
    }
    const double th = b->th;
    out[0] = t0 + th * t1;
    out[1] = d0 + t1 + th * d1;
    out[2] = e0 + 2.0 * d1 + th * e1;
}

void jc_tl_eval3(const jc_TrigLin *p, double th, double out[3])
{
    jc_TrigBasis b;
    jc_tl_basis(&b, th);
    jc_tl_eval3_basis(p, &b, out);
}

/* The amplitude of a cos(k th) + b sin(k th), sqrt(a^2 + b^2): it and its
 * n-th derivatives (times k^n) never exceed it. Up to sqrt 2 below |a| + |b|,
 * the simpler bound: the crossing search's safe steps grow like M3^(-1/3),
 * so the tighter bound takes fewer of them. Where a^2 could underflow (both
 * below 1e-150): |a| + |b|, still a bound. */
static double amplitude(double a, double b)
{
    const double sum = fabs(a) + fabs(b);
    if (!(sum > 1e-150)) return sum;
    const double amp = sqrt(a * a + b * b);
    return amp < sum ? amp : sum; /* sum when a^2 overflows (amp infinite) */
}

void jc_tl_bounds(const jc_TrigLin *p, jc_TrigBounds *out)
{
    /* f''' = T0''' + 3 T1'' + th T1''', term by term of amplitude k^3 A0,
     * 3 k^2 A1 and |th| k^3 A1. 1 + 1e-12 covers the rounding of the sums. */
    double b0 = 0.0, b1 = 0.0, b2 = 0.0, m0 = fabs(p->c0[0]), m1 = fabs(p->c1[0]);
    /* The degree first: the terms above it add nothing (the energy is of
     * degree 1 in a field of 4). */
    int deg = JC_TRIG_DEGREE;
    while (deg > 0 && p->c0[deg] == 0.0 && p->s0[deg] == 0.0 && p->c1[deg] == 0.0 && p->s1[deg] == 0.0) --deg;
    if (deg == 0 && p->c0[0] == 0.0 && p->c1[0] == 0.0) deg = -1;
    for (int k = 1; k <= deg; ++k) {
        const double kk = (double)k * k, kkk = kk * k;
        const double a0 = amplitude(p->c0[k], p->s0[k]), a1 = amplitude(p->c1[k], p->s1[k]);
        b0 += kkk * a0;
        b1 += kk * a1;
        b2 += kkk * a1;
        m0 += fabs(p->c0[k]) + fabs(p->s0[k]);
        m1 += fabs(p->c1[k]) + fabs(p->s1[k]);
    }
    out->degree = deg;
    out->third0 = (b0 + 3.0 * b1) * (1.0 + 1e-12);
    out->third_slope = b2 * (1.0 + 1e-12);
    out->mag0 = m0;
    out->mag1 = m1;
}

double jc_tl_third_bound(const jc_TrigLin *p, double th_abs_max)
{
    jc_TrigBounds b;
    jc_tl_bounds(p, &b);
    return b.third0 + th_abs_max * b.third_slope;
}

double jc_tl_third_slope(const jc_TrigLin *p)
{
    jc_TrigBounds b;
    jc_tl_bounds(p, &b);
    return b.third_slope;
}
