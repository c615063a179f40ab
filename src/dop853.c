/*
 * DOP853 (see dop853.h). The coefficients are those of Hairer's dop853.f;
 * the stepper checks its own order in tests/sim/test_dop853.c, and GSL's
 * rk8pd stays there as the cross-check on 1,000 random sliding phases.
 */
#include "dop853.h"
#include "dop853_kernel.h"

#include <math.h>
#include <string.h>

/* Continuous extension: rows 4..7 of the interpolant's coefficients, on
 * stages 1, 6..12 and 13..16. */
static const int D_STAGE[12] = {1, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
static const double D[4][12] = {
    {-0.84289382761090128651353491142e+01, 0.56671495351937776962531783590e+00,
     -0.30689499459498916912797304727e+01, 0.23846676565120698287728149680e+01,
     0.21170345824450282767155149946e+01, -0.87139158377797299206789907490e+00,
     0.22404374302607882758541771650e+01, 0.63157877876946881815570249290e+00,
     -0.88990336451333310820698117400e-01, 0.18148505520854727256656404962e+02,
     -0.91946323924783554000451984436e+01, -0.44360363875948939664310572000e+01},
    {0.10427508642579134603413151009e+02, 0.24228349177525818288430175319e+03,
     0.16520045171727028198505394887e+03, -0.37454675472269020279518312152e+03,
     -0.22113666853125306036270938578e+02, 0.77334326684722638389603898808e+01,
     -0.30674084731089398182061213626e+02, -0.93321305264302278729567221706e+01,
     0.15697238121770843886131091075e+02, -0.31139403219565177677282850411e+02,
     -0.93529243588444783865713862664e+01, 0.35816841486394083752465898540e+02},
    {0.19985053242002433820987653617e+02, -0.38703730874935176555105901742e+03,
     -0.18917813819516756882830838328e+03, 0.52780815920542364900561016686e+03,
     -0.11573902539959630126141871134e+02, 0.68812326946963000169666922661e+01,
     -0.10006050966910838403183860980e+01, 0.77771377980534432092869265740e+00,
     -0.27782057523535084065932004339e+01, -0.60196695231264120758267380846e+02,
     0.84320405506677161018159903784e+02, 0.11992291136182789328035130030e+02},
    {-0.25693933462703749003312586129e+02, -0.15418974869023643374053993627e+03,
     -0.23152937917604549567536039109e+03, 0.35763911791061412378285349910e+03,
     0.93405324183624310003907691704e+02, -0.37458323136451633156875139351e+02,
     0.10409964950896230045147246184e+03, 0.29840293426660503123344363579e+02,
     -0.43533456590011143754432175058e+02, 0.96324553959188282948394950600e+02,
     -0.39177261675615439165231486172e+02, -0.14972683625798562581422125276e+03},
};

static const double *stage(const jc_Dop853 *d, int j)
{
    return j == 1 ? d->f0 : j == 13 ? d->f1 : d->k[j];
}

/* The weighted sum of stages, per component: the stage pointers are looked
 * up once per row, not per component. */
static void combine(const jc_Dop853 *d, int count, const int *stages, const double *w, double *out)
{
    const double *ks[12];
    for (int q = 0; q < count; ++q) ks[q] = stage(d, stages[q]);
    for (int i = d->first; i < d->first + d->dim; ++i) {
        double acc = 0.0;
        for (int q = 0; q < count; ++q) acc += w[q] * ks[q][i];
        out[i] = acc;
    }
}

/* The stages with the phases' ranges as constants ([0, 7): sliding,
 * [0, 9): sliding with resistance, [2, 9): rolling with resistance,
 * [0, 11): flight with air), so that each sum is unrolled over the
 * components without alias checks (the same numbers); any other range by
 * the general loop. Chosen once per step, not per stage, and the carried
 * components not copied per stage. */
static int stages(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, int from, int to, double h)
{
    switch (d->first * 16 + d->dim) {
    case 7: return jc_dop853_stages(d, rhs, ctx, from, to, h, 0, 7);
    case 9: return jc_dop853_stages(d, rhs, ctx, from, to, h, 0, 9);
    case 11: return jc_dop853_stages(d, rhs, ctx, from, to, h, 0, 11);
    case 2 * 16 + 7: return jc_dop853_stages(d, rhs, ctx, from, to, h, 2, 7);
    default: return jc_dop853_stages(d, rhs, ctx, from, to, h, d->first, d->dim);
    }
}

/* The components not integrated, at their start values. */
static void carry(const jc_Dop853 *d, double y[])
{
    for (int i = 0; i < d->first; ++i) y[i] = d->y0[i];
    for (int i = d->first + d->dim; i < d->full_dim; ++i) y[i] = d->y0[i];
}

void jc_dop853_init(jc_Dop853 *d, int dim, int full_dim, double rtol, double atol)
{
    jc_dop853_init_range(d, 0, dim, full_dim, rtol, atol);
}

void jc_dop853_init_range(jc_Dop853 *d, int first, int dim, int full_dim, double rtol, double atol)
{
    d->first = first;
    d->dim = dim;
    d->full_dim = full_dim;
    d->rtol = rtol;
    d->atol = atol;
    d->h = 0.0;
    d->dense_ready = 0;
    jc_dop853_control_init(d);
    for (int i = 0; i < JC_DOP_MAX_DIM; ++i) d->scale_floor[i] = 0.0;
}

int jc_dop853_start(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double t, const double y[])
{
    d->t0 = t;
    d->h = 0.0;
    d->dense_ready = 0;
    d->rejected_last = 0;
    for (int i = 0; i < d->full_dim; ++i) d->y0[i] = d->y1[i] = d->ys[i] = y[i];
    return rhs(t, d->y0, d->f0, ctx);
}

/* The stages of a step of size h, y1, and the scaled error estimate
 * (INFINITY when a stage failed or is not finite). */
static double step_error(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, double err2[2])
{
    d->dense_ready = 0;
    if (stages(d, rhs, ctx, 2, 12, h) != 0) return INFINITY;
    return jc_dop853_error_sum(d, h, d->first, d->dim, err2);
}

static int end_rate(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h)
{
    return jc_dop853_end_rate(d, rhs, ctx, h, d->first, d->dim);
}

double jc_dop853_try(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, double *h_next)
{
    double err2[2] = {0.0, 1.0};
    double err = step_error(d, rhs, ctx, h, err2);
    if (err <= 1.0 && end_rate(d, rhs, ctx, h) != 0) err = INFINITY;
    return jc_dop853_control(d, err, err2[0], err2[1], h, h_next);
}

double jc_dop853_initial_step(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h_max)
{
    /* Hairer, Norsett, Wanner, section II.4, and HINIT of their dop853.f. */
    const int lo = d->first, hi = lo + d->dim;
    double dnf = 0.0, dny = 0.0;
    for (int i = lo; i < hi; ++i) {
        const double sk = d->atol + d->rtol * fmax(fabs(d->y0[i]), d->scale_floor[i]);
        dnf += (d->f0[i] / sk) * (d->f0[i] / sk);
        dny += (d->y0[i] / sk) * (d->y0[i] / sk);
    }
    double h = dnf <= 1e-10 || dny <= 1e-10 ? 1e-6 : 0.01 * sqrt(dny / dnf);
    h = fmin(h, h_max);
    /* An explicit Euler step; its rate change estimates the second derivative. */
    double y[JC_DOP_MAX_DIM];
    for (int i = lo; i < hi; ++i) y[i] = d->y0[i] + h * d->f0[i];
    carry(d, y);
    double *f1 = d->k[2];
    if (rhs(d->t0 + h, y, f1, ctx) != 0) return h;
    double der2 = 0.0;
    for (int i = lo; i < hi; ++i) {
        const double sk = d->atol + d->rtol * fmax(fabs(d->y0[i]), d->scale_floor[i]);
        der2 += ((f1[i] - d->f0[i]) / sk) * ((f1[i] - d->f0[i]) / sk);
    }
    der2 = sqrt(der2) / h;
    const double der12 = fmax(fabs(der2), sqrt(dnf));
    const double h1 = der12 <= 1e-15 ? fmax(1e-6, h * 1e-3) : pow(0.01 / der12, 1.0 / 8.0);
    const double h_new = fmin(fmin(100.0 * h, h1), h_max);
    return isfinite(h_new) && h_new > 0.0 ? h_new : h;
}

int jc_dop853_step(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h)
{
    double err2[2] = {0.0, 1.0};
    return isfinite(step_error(d, rhs, ctx, h, err2)) && end_rate(d, rhs, ctx, h) == 0 ? 0 : -1;
}

void jc_dop853_advance(jc_Dop853 *d)
{
    d->t0 += d->h;
    /* Whole arrays, a fixed size the compiler copies inline (full_dim
     * values were two calls of memcpy per step; entries past full_dim are
     * unused). */
    memcpy(d->y0, d->y1, sizeof d->y0);
    memcpy(d->f0, d->f1, sizeof d->f0);
    d->h = 0.0;
    d->dense_ready = 0;
}

int jc_dop853_dense(jc_Dop853 *d, jc_DopRhs rhs, void *ctx)
{
    if (d->dense_ready) return 0;
    const double h = d->h;
    if (stages(d, rhs, ctx, 14, 16, h) != 0) return -1;
    double dr[4][JC_DOP_MAX_DIM];
    for (int r = 0; r < 4; ++r) combine(d, 12, D_STAGE, D[r], dr[r]);
    for (int i = d->first; i < d->first + d->dim; ++i) {
        const double dy = d->y1[i] - d->y0[i], bspl = h * d->f0[i] - dy;
        d->cont[0][i] = d->y0[i];
        d->cont[1][i] = dy;
        d->cont[2][i] = bspl;
        d->cont[3][i] = dy - h * d->f1[i] - bspl;
        for (int r = 0; r < 4; ++r) d->cont[4 + r][i] = h * dr[r][i];
    }
    d->dense_ready = 1;
    d->dense_h = h;
    return 0;
}

void jc_dop853_eval(const jc_Dop853 *d, double tau, double y[])
{
    const double s = d->dense_h > 0.0 ? tau / d->dense_h : 0.0, s1 = 1.0 - s;
    for (int i = d->first; i < d->first + d->dim; ++i) {
        const double (*c)[JC_DOP_MAX_DIM] = d->cont;
        y[i] = c[0][i] + s * (c[1][i] + s1 * (c[2][i] + s * (c[3][i] + s1 * (c[4][i] + s * (c[5][i] +
               s1 * (c[6][i] + s * c[7][i]))))));
    }
    carry(d, y);
}
