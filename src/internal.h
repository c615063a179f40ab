/* Internal helpers shared by the library's source files; not installed. */
#ifndef JUMPCYL_INTERNAL_H
#define JUMPCYL_INTERNAL_H

#include "jumpcyl/jumpcyl.h"

#include <stdarg.h>

/* Writes a formatted message into err (if any) and returns status. */
int jc_fail(char *err, size_t err_len, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* ---- trigpoly.c: f(th) = T0(th) + th T1(th) ---- */

void jc_tl_zero(jc_TrigLin *p);
/* a*cos(k th) or a*sin(k th) added to T0 (lin = 0) or T1 (lin = 1). */
void jc_tl_add_cos(jc_TrigLin *p, int lin, int k, double a);
void jc_tl_add_sin(jc_TrigLin *p, int lin, int k, double a);
/* out = a*x + b*y */
void jc_tl_axpby(jc_TrigLin *out, double a, const jc_TrigLin *x, double b, const jc_TrigLin *y);
/* out = x*y; at most one of them may have a T1 part, and the degrees must add
 * up to at most JC_TRIG_DEGREE (both checked; returns JC_EINVAL if not). */
int jc_tl_mul(jc_TrigLin *out, const jc_TrigLin *x, const jc_TrigLin *y);
/* Value and derivative at th. */
void jc_tl_eval(const jc_TrigLin *p, double th, double *f, double *df);
double jc_tl_value(const jc_TrigLin *p, double th);
/* A bound on |f| (the scale of its rounding noise) for |th| <= th_abs_max. */
double jc_tl_magnitude_bound(const jc_TrigLin *p, double th_abs_max);
/* A bound on |f''| for |th| <= th_abs_max. */
double jc_tl_curvature_bound(const jc_TrigLin *p, double th_abs_max);

/* ---- scan.c: the first place where one of several functions stops being
 * positive, found by steps that cannot cross a root (see scan.c). ---- */

#define JC_SCAN_MAX 8

typedef struct {
    int count;
    const jc_TrigLin *f[JC_SCAN_MAX];
    double sign[JC_SCAN_MAX]; /* watch sign*f, which must be > 0 */
} jc_ScanSet;

typedef struct {
    int index;     /* which function hit zero first; -1: none before th_to */
    double theta;  /* where (th_to when index = -1) */
    int grazing;   /* 1: touched zero without a located sign change */
    int steps;     /* safe steps taken, for benchmarks and tests */
} jc_ScanHit;

/* Scans from th_from to th_to (either direction). Root located to tol_rad. */
int jc_scan_first(const jc_ScanSet *set, double th_from, double th_to, double tol_rad,
                  jc_ScanHit *hit, char *err, size_t err_len);

#endif
