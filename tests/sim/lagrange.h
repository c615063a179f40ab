/*
 * The contact equations as a generic second formulation (see test_lagrange.c):
 * Newton-Euler for the rigid body with the contact force as a Lagrange
 * multiplier of the contact constraint, solved by LU. Shared by the tests
 * that need the motion computed without src/'s closed forms.
 */
#ifndef JC_TEST_LAGRANGE_H
#define JC_TEST_LAGRANGE_H

#include "sim_common.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

/* Solves A x = b (n x n, row-major) by LU with partial pivoting. */
static inline int solve(int n, double *a, double *b, double *x)
{
    gsl_matrix_view A = gsl_matrix_view_array(a, (size_t)n, (size_t)n);
    gsl_vector_view B = gsl_vector_view_array(b, (size_t)n);
    gsl_vector_view X = gsl_vector_view_array(x, (size_t)n);
    gsl_permutation *p = gsl_permutation_alloc((size_t)n);
    ENSURE(p != NULL);
    int sgn;
    int st = gsl_linalg_LU_decomp(&A.matrix, p, &sgn);
    if (st == GSL_SUCCESS) st = gsl_linalg_LU_solve(&A.matrix, p, &B.vector, &X.vector);
    gsl_permutation_free(p);
    ENSURE_MSG(st == GSL_SUCCESS, "LU: %s", gsl_strerror(st));
    return 0;
}

typedef struct {
    double M, ig, r, d, g, sa, ca;
} body_consts;

static inline body_consts consts_of(const jc_Model *m)
{
    return (body_consts){m->body.mass_kg, m->body.inertia_g_kgm2, m->body.radius_m, m->body.cm_offset_m,
                         m->setup.gravity_mps2, sin(m->setup.incline_rad), cos(m->setup.incline_rad)};
}

/* Sliding in direction s: returns N, th'', x_C'' from the 4x4 system. */
static inline int slide_lm(const body_consts *b, double mu, int s, double th, double w, double *normal, double *thdd,
                    double *xcdd)
{
    const double rx = -b->d * sin(th), ry = -(b->r + b->d * cos(th));
    /* Unknowns: a_Gx, a_Gy, th'', N. F = -mu s N. */
    double a[16] = {
        b->M, 0.0,  0.0,   mu * s,              /* M a_Gx - F = M g sin a   */
        0.0,  b->M, 0.0,   -1.0,                /* M a_Gy - N = -M g cos a  */
        0.0,  0.0,  b->ig, mu * s * ry + rx,    /* I_G th'' - (R_y F - R_x N) = 0 */
        0.0,  1.0,  b->d * sin(th), 0.0,        /* y_C'' = 0 */
    };
    double rhs[4] = {b->M * b->g * b->sa, -b->M * b->g * b->ca, 0.0, -b->d * cos(th) * w * w};
    double x[4];
    if (solve(4, a, rhs, x)) return 1;
    *normal = x[3];
    *thdd = x[2];
    *xcdd = x[0] - b->d * cos(th) * x[2] + b->d * sin(th) * w * w;
    return 0;
}

/* Rolling: returns th'', N, F from the 5x5 system. */
static inline int roll_lm(const body_consts *b, double th, double w, double *thdd, double *normal, double *friction)
{
    const double rx = -b->d * sin(th), ry = -(b->r + b->d * cos(th));
    /* Unknowns: a_Gx, a_Gy, th'', N, F. */
    double a[25] = {
        b->M, 0.0,  0.0,   0.0, -1.0,                      /* M a_Gx - F = M g sin a */
        0.0,  b->M, 0.0,   -1.0, 0.0,                      /* M a_Gy - N = -M g cos a */
        0.0,  0.0,  b->ig, rx,  -ry,                       /* I_G th'' + R_x N - R_y F = 0 */
        0.0,  1.0,  b->d * sin(th), 0.0, 0.0,              /* y_C'' = 0 */
        1.0,  0.0,  -b->d * cos(th) - b->r, 0.0, 0.0,      /* x_C'' - r th'' = 0 */
    };
    double rhs[5] = {b->M * b->g * b->sa, -b->M * b->g * b->ca, 0.0, -b->d * cos(th) * w * w,
                     -b->d * sin(th) * w * w};
    double x[5];
    if (solve(5, a, rhs, x)) return 1;
    *thdd = x[2];
    *normal = x[3];
    *friction = x[4];
    return 0;
}

#endif
