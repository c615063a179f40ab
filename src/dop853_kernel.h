/*
 * The DOP853 step itself (dop853.c has the rest of the stepper): its
 * stages, error estimate and end rate, written as inline functions of the
 * right-hand side and of the integrated range, so that a phase can make its
 * own instance with its right-hand side inlined into the stages
 * (JC_DOP853_TRY_INSTANCE below). It calls only the step size control
 * (dop853_control.c); the stepper (dop853.c) is built on it, not the other
 * way round. Internal.
 */
#ifndef JUMPCYL_DOP853_KERNEL_H
#define JUMPCYL_DOP853_KERNEL_H

#include "dop853_control.h"
#include "dop853_state.h"

#include <math.h>

/* Nodes c_i of the stages (stage 13 is f at the step's end). */
static const double JC_DOP_C[17] = {
    0.0, 0.0,
    0.526001519587677318785587544488e-01, /* 2 */
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510e+00,
    0.281649658092772603273242802490e+00,
    0.333333333333333333333333333333e+00,
    0.25e+00,
    0.307692307692307692307692307692e+00,
    0.651282051282051282051282051282e+00,
    0.6e+00,
    0.857142857142857142857142857142e+00,
    1.0, 1.0,
    0.1e+00, /* 14 */
    0.2e+00,
    0.777777777777777777777777777778e+00,
};

/* 8th-order weights, on stages 1, 6..12. */
static const double JC_DOP_B[8] = {
    5.42937341165687622380535766363e-2, 4.45031289275240888144113950566e0, 1.89151789931450038304281599044e0,
    -5.8012039600105847814672114227e0,  3.1116436695781989440891606237e-1, -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1, 4.47106157277725905176885569043e-2};
/* The 5th-order error estimate's weights on the same stages. */
static const double JC_DOP_ER[8] = {
    0.1312004499419488073250102996e-01,  -0.1225156446376204440720569753e+01, -0.4957589496572501915214079952e+00,
    0.1664377182454986536961530415e+01,  -0.3503288487499736816886487290e+00, 0.3341791187130174790297318841e+00,
    0.8192320648511571246570742613e-01,  -0.2235530786388629525884427845e-01};
/* The 3rd-order estimate: b-weighted increment minus these on stages 1, 9, 12. */
static const double JC_DOP_BHH[3] = {0.244094488188976377952755905512e+00, 0.733846688281611857341361741547e+00,
                              0.220588235294117647058823529412e-01};

/* The input of stage s, y0 + h sum_j a_sj k_j (k1 = f0, k13 = f1), the
 * Butcher matrix written out row by row so that the coefficients are
 * constants and the loop over components is vectorized (a generic loop
 * over a table of rows was the largest part of a run's work). The
 * last stage's term is added apart, (y0 + h sum_{j<last}) + (h a_s,last)
 * k_last: each stage waits for the one before it, and this way only a
 * multiply and an add lie between that stage's rates and this one's input,
 * where the sum of all the terms, times h, plus y0 put four there. */
/* Inlined into every specialization of stages() in dop853.c and into each
 * phase's instance, where its ranges are constants (GCC otherwise kept one
 * copy out of line with a runtime range). */
#if defined(__GNUC__)
#define JC_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define JC_ALWAYS_INLINE inline
#endif

static JC_ALWAYS_INLINE void jc_dop853_stage_input(const jc_Dop853 *restrict d, int s, double h,
                                                   double *restrict y_all, const int o, const int n)
{
    /* The integrated components [o, o + n) of every vector. */
    double *y = y_all + o;
    const double *y0 = d->y0 + o, *k1 = d->f0 + o, *k13 = d->f1 + o;
    const double *k2 = d->k[2] + o, *k3 = d->k[3] + o, *k4 = d->k[4] + o, *k5 = d->k[5] + o, *k6 = d->k[6] + o;
    const double *k7 = d->k[7] + o, *k8 = d->k[8] + o, *k9 = d->k[9] + o, *k10 = d->k[10] + o;
    const double *k11 = d->k[11] + o, *k12 = d->k[12] + o, *k14 = d->k[14] + o, *k15 = d->k[15] + o;
    switch (s) {
    case 2:
        for (int i = 0; i < n; ++i)
            y[i] = y0[i] + h * (5.26001519587677318785587544488e-2 * k1[i]);
        return;
    case 3:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (1.97250569845378994544595329183e-2 * k1[i]))
                   + (h * 5.91751709536136983633785987549e-2) * k2[i];
        return;
    case 4:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (2.95875854768068491816892993775e-2 * k1[i]))
                   + (h * 8.87627564304205475450678981324e-2) * k3[i];
        return;
    case 5:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (2.41365134159266685502369798665e-1 * k1[i]
                                - 8.84549479328286085344864962717e-1 * k3[i]))
                   + (h * 9.24834003261792003115737966543e-1) * k4[i];
        return;
    case 6:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (3.7037037037037037037037037037e-2 * k1[i]
                                + 1.70828608729473871279604482173e-1 * k4[i]))
                   + (h * 1.25467687566822425016691814123e-1) * k5[i];
        return;
    case 7:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (3.7109375e-2 * k1[i]
                                + 1.70252211019544039314978060272e-1 * k4[i]
                                + 6.02165389804559606850219397283e-2 * k5[i]))
                   - (h * 1.7578125e-2) * k6[i];
        return;
    case 8:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (3.70920001185047927108779319836e-2 * k1[i]
                                + 1.70383925712239993810214054705e-1 * k4[i]
                                + 1.07262030446373284651809199168e-1 * k5[i]
                                - 1.53194377486244017527936158236e-2 * k6[i]))
                   + (h * 8.27378916381402288758473766002e-3) * k7[i];
        return;
    case 9:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (6.24110958716075717114429577812e-1 * k1[i]
                                - 3.36089262944694129406857109825e0 * k4[i]
                                - 8.68219346841726006818189891453e-1 * k5[i]
                                + 2.75920996994467083049415600797e1 * k6[i]
                                + 2.01540675504778934086186788979e1 * k7[i]))
                   - (h * 4.34898841810699588477366255144e1) * k8[i];
        return;
    case 10:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (4.77662536438264365890433908527e-1 * k1[i]
                                - 2.48811461997166764192642586468e0 * k4[i]
                                - 5.90290826836842996371446475743e-1 * k5[i]
                                + 2.12300514481811942347288949897e1 * k6[i]
                                + 1.52792336328824235832596922938e1 * k7[i]
                                - 3.32882109689848629194453265587e1 * k8[i]))
                   - (h * 2.03312017085086261358222928593e-2) * k9[i];
        return;
    case 11:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (-9.3714243008598732571704021658e-1 * k1[i]
                                + 5.18637242884406370830023853209e0 * k4[i]
                                + 1.09143734899672957818500254654e0 * k5[i]
                                - 8.14978701074692612513997267357e0 * k6[i]
                                - 1.85200656599969598641566180701e1 * k7[i]
                                + 2.27394870993505042818970056734e1 * k8[i]
                                + 2.49360555267965238987089396762e0 * k9[i]))
                   - (h * 3.0467644718982195003823669022e0) * k10[i];
        return;
    case 12:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (2.27331014751653820792359768449e0 * k1[i]
                                - 1.05344954667372501984066689879e1 * k4[i]
                                - 2.00087205822486249909675718444e0 * k5[i]
                                - 1.79589318631187989172765950534e1 * k6[i]
                                + 2.79488845294199600508499808837e1 * k7[i]
                                - 2.85899827713502369474065508674e0 * k8[i]
                                - 8.87285693353062954433549289258e0 * k9[i]
                                + 1.23605671757943030647266201528e1 * k10[i]))
                   + (h * 6.43392746015763530355970484046e-1) * k11[i];
        return;
    case 14:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (5.61675022830479523392909219681e-2 * k1[i]
                                + 2.53500210216624811088794765333e-1 * k7[i]
                                - 2.46239037470802489917441475441e-1 * k8[i]
                                - 1.24191423263816360469010140626e-1 * k9[i]
                                + 1.5329179827876569731206322685e-1 * k10[i]
                                + 8.20105229563468988491666602057e-3 * k11[i]
                                + 7.56789766054569976138603589584e-3 * k12[i]))
                   - (h * 8.298e-3) * k13[i];
        return;
    case 15:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (3.18346481635021405060768473261e-2 * k1[i]
                                + 2.83009096723667755288322961402e-2 * k6[i]
                                + 5.35419883074385676223797384372e-2 * k7[i]
                                - 5.49237485713909884646569340306e-2 * k8[i]
                                - 1.08347328697249322858509316994e-4 * k11[i]
                                + 3.82571090835658412954920192323e-4 * k12[i]
                                - 3.40465008687404560802977114492e-4 * k13[i]))
                   + (h * 1.41312443674632500278074618366e-1) * k14[i];
        return;
    case 16:
        for (int i = 0; i < n; ++i)
            y[i] = (y0[i] + h * (-4.28896301583791923408573538692e-1 * k1[i]
                                - 4.69762141536116384314449447206e0 * k6[i]
                                + 7.68342119606259904184240953878e0 * k7[i]
                                + 4.06898981839711007970213554331e0 * k8[i]
                                + 3.56727187455281109270669543021e-1 * k9[i]
                                - 1.39902416515901462129418009734e-3 * k13[i]
                                + 2.9475147891527723389556272149e0 * k14[i]))
                   - (h * 9.15095847217987001081870187138e0) * k15[i];
        return;
    default: return;
    }
}

/* Stages from..to of a step of size h, their input in d->ys (the carried
 * components are there already), for a range [o, o + n) given as
 * constants by stages() in dop853.c or by a phase's instance. */
static JC_ALWAYS_INLINE int jc_dop853_stages(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, int from, int to, double h,
                                             const int o, const int n)
{
    for (int s = from; s <= to; ++s) {
        jc_dop853_stage_input(d, s, h, d->ys, o, n);
        if (rhs(d->t0 + JC_DOP_C[s] * h, d->ys, d->k[s], ctx) != 0) return -1;
    }
    return 0;
}

/* After the stages of a step of size h: y1 and the scaled error estimate
 * (INFINITY when it is not finite); its square as err2[0] / err2[1], for
 * the step size control. */
static JC_ALWAYS_INLINE double jc_dop853_error_sum(jc_Dop853 *d, double h, const int o, const int n, double err2[2])
{
    /* The integrated components [o, o + n) of every vector, from 0. */
    double inc[JC_DOP_MAX_DIM], e5[JC_DOP_MAX_DIM];
    const double *k1 = d->f0 + o, *k6 = d->k[6] + o, *k7 = d->k[7] + o, *k8 = d->k[8] + o, *k9 = d->k[9] + o;
    const double *k10 = d->k[10] + o, *k11 = d->k[11] + o, *k12 = d->k[12] + o;
    const double *y0 = d->y0 + o, *floor_ = d->scale_floor + o;
    double *y1 = d->y1 + o;
    for (int i = 0; i < n; ++i) {
        inc[i] = JC_DOP_B[0] * k1[i] + JC_DOP_B[1] * k6[i] + JC_DOP_B[2] * k7[i] + JC_DOP_B[3] * k8[i] +
                 JC_DOP_B[4] * k9[i] + JC_DOP_B[5] * k10[i] + JC_DOP_B[6] * k11[i] + JC_DOP_B[7] * k12[i];
        e5[i] = JC_DOP_ER[0] * k1[i] + JC_DOP_ER[1] * k6[i] + JC_DOP_ER[2] * k7[i] + JC_DOP_ER[3] * k8[i] +
                JC_DOP_ER[4] * k9[i] + JC_DOP_ER[5] * k10[i] + JC_DOP_ER[6] * k11[i] + JC_DOP_ER[7] * k12[i];
    }
    double err5 = 0.0, err3 = 0.0;
    for (int i = 0; i < n; ++i) {
        y1[i] = y0[i] + h * inc[i];
        const double e3 = inc[i] - JC_DOP_BHH[0] * k1[i] - JC_DOP_BHH[1] * k9[i] - JC_DOP_BHH[2] * k12[i];
        /* The larger magnitude by a comparison, not fmax (a call into libm
         * per component, which GCC does not inline for its NaN rule; a NaN
         * y1 makes the error NaN either way, a rejected step). */
        const double a0 = fabs(y0[i]), a1 = fabs(y1[i]), am = a1 > a0 ? a1 : a0;
        const double sk = d->atol + d->rtol * (am > floor_[i] ? am : floor_[i]);
        err5 += (e5[i] / sk) * (e5[i] / sk);
        err3 += (e3 / sk) * (e3 / sk);
    }
    double deno = err5 + 0.01 * err3;
    if (deno <= 0.0) deno = 1.0;
    const double num = fabs(h) * err5;
    err2[0] = num * num;
    err2[1] = n * deno;
    const double err = num * sqrt(1.0 / (n * deno));
    return isfinite(err) ? err : INFINITY;
}

/* The stages of a step of size h, y1, and the scaled error estimate
 * (INFINITY when a stage failed or is not finite). */
static JC_ALWAYS_INLINE double jc_dop853_error_n(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, const int o,
                                                 const int n, double err2[2])
{
    d->dense_ready = 0;
    if (jc_dop853_stages(d, rhs, ctx, 2, 12, h, o, n) != 0) return INFINITY;
    return jc_dop853_error_sum(d, h, o, n, err2);
}

/* f1 at the step's end; 0 when it and y1 are finite. */
static JC_ALWAYS_INLINE int jc_dop853_end_rate(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, const int o,
                                               const int n)
{
    if (rhs(d->t0 + h, d->y1, d->f1, ctx) != 0) return -1;
    for (int i = o; i < o + n; ++i)
        if (!isfinite(d->y1[i]) || !isfinite(d->f1[i])) return -1;
    d->h = h;
    return 0;
}

/* jc_dop853_try for a range [o, o + n) and a right-hand side known where
 * it is inlined. */
static JC_ALWAYS_INLINE double jc_dop853_try_n(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, double *h_next,
                                               const int o, const int n)
{
    double err2[2] = {0.0, 1.0};
    double err = jc_dop853_error_n(d, rhs, ctx, h, o, n, err2);
    if (err <= 1.0 && jc_dop853_end_rate(d, rhs, ctx, h, o, n) != 0) err = INFINITY;
    return jc_dop853_control(d, err, err2[0], err2[1], h, h_next);
}

/* A phase's own jc_dop853_try, named name, for its right-hand side rhs (a
 * function of the same file) and its range [first, first + dim), the one
 * it gives ode.c (each phase names it once for both): the right-hand side
 * is inlined into the stages, where the generic stepper calls it through a
 * pointer at every stage, and each stage's rates reach the next stage's
 * input in registers, not through a call and memory. The same operations
 * in the same order: the same numbers to the last bit
 * (tests/sim/test_dop853.c). The phases name the range once, for both: a
 * check of the range at each step cost more than the instance saves.
 * In the web page's module no instance is made: the name is a null
 * jc_DopTry, and ode.c steps with the generic stepper (jc_dop853_try), for
 * the page's download size (the instances make the module larger). A null
 * pointer, not a function calling jc_dop853_try, so that this header calls
 * nothing in dop853.c, which includes it. */
#if defined(__EMSCRIPTEN__)
#define JC_DOP853_TRY_INSTANCE(name, rhs, first, dim) static const jc_DopTry name = 0;
#else
/* flatten: everything called inside is inlined. Without it GCC keeps the
 * right-hand side out of line in the stage loop, called through the
 * pointer as by the generic stepper. */
#if defined(__GNUC__)
#define JC_FLATTEN __attribute__((flatten))
#else
#define JC_FLATTEN
#endif
#define JC_DOP853_TRY_INSTANCE(name, rhs, first, dim)                                                             \
    static JC_FLATTEN double name(jc_Dop853 *d, void *ctx, double h, double *h_next)                             \
    {                                                                                                             \
        return jc_dop853_try_n(d, rhs, ctx, h, h_next, first, dim);                                               \
    }
#endif

#endif
