/*
 * DOP853 (see dop853.h). The coefficients are those of Hairer's dop853.f;
 * the stepper checks its own order in tests/sim/test_dop853.c, and GSL's
 * rk8pd stays there as the cross-check on 1,000 random sliding phases.
 */
#include "dop853.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* Nodes c_i of the stages (stage 13 is f at the step's end). */
static const double C[17] = {
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
static const double B[8] = {
    5.42937341165687622380535766363e-2, 4.45031289275240888144113950566e0, 1.89151789931450038304281599044e0,
    -5.8012039600105847814672114227e0,  3.1116436695781989440891606237e-1, -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1, 4.47106157277725905176885569043e-2};
/* The 5th-order error estimate's weights on the same stages. */
static const double ER[8] = {
    0.1312004499419488073250102996e-01,  -0.1225156446376204440720569753e+01, -0.4957589496572501915214079952e+00,
    0.1664377182454986536961530415e+01,  -0.3503288487499736816886487290e+00, 0.3341791187130174790297318841e+00,
    0.8192320648511571246570742613e-01,  -0.2235530786388629525884427845e-01};
/* The 3rd-order estimate: b-weighted increment minus these on stages 1, 9, 12. */
static const double BHH[3] = {0.244094488188976377952755905512e+00, 0.733846688281611857341361741547e+00,
                              0.220588235294117647058823529412e-01};

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

/* Step size control (Hairer's defaults for DOP853). */
#define SAFETY 0.9
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

/* The step size controller's powers err^(1/8 - 0.2 beta) / err_old^beta
 * by log2 and exp2 of our own, good to 1e-9 (a step size needs no more:
 * the factor only steers it), where libm's pow was two calls of ~125
 * instructions each per step, plus calls of fmin and fmax. Callgrind: a
 * drag run 1.154M -> 1.121M instructions, the paper's run 228.1k ->
 * 228.1k (the same steps in both). */
static double log2_pos(double x)
{
    /* x = m 2^e with m in [sqrt(1/2), sqrt(2)); x positive and normal. */
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    int e = (int)(b >> 52) - 1023;
    b = (b & 0xfffffffffffffULL) | 0x3ff0000000000000ULL;
    double m;
    memcpy(&m, &b, sizeof m);
    if (m > 1.4142135623730951) {
        m *= 0.5;
        e += 1;
    }
    /* ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.172: the series to s^9. */
    const double s = (m - 1.0) / (m + 1.0), s2 = s * s, s4 = s2 * s2;
    /* Estrin's grouping, here and in exp2_small: the next step's size waits
     * on these chains (measured with make bench, alternated with Horner's
     * form: a drag run 70.4 -> 69.1 us median of 7, the paper's 21.8 -> 21.3). */
    const double ln_m = 2.0 * s * ((1.0 + s2 * (1.0 / 3)) + s4 * ((1.0 / 5 + s2 * (1.0 / 7)) + s4 * (1.0 / 9)));
    return e + ln_m * 1.4426950408889634074;
}

/* 2^y for |y| < 1000. */
static double exp2_small(double y)
{
    const int n = (int)(y + 1024.5) - 1024; /* nearest integer: truncation of a positive number */
    const double f = (y - n) * 0.69314718055994530942; /* |f| <= ln 2 / 2: Taylor to f^9 */
    const double f2 = f * f, f4 = f2 * f2, f8 = f4 * f4;
    const double p = ((1.0 + f) + f2 * (1.0 / 2 + f * (1.0 / 6))) +
                     f4 * ((1.0 / 24 + f * (1.0 / 120)) + f2 * (1.0 / 720 + f * (1.0 / 5040))) +
                     f8 * (1.0 / 40320 + f * (1.0 / 362880));
    const uint64_t b = (uint64_t)(n + 1023) << 52;
    double scale;
    memcpy(&scale, &b, sizeof scale);
    return p * scale;
}

static double min2(double a, double b) { return a < b ? a : b; }
static double max2(double a, double b) { return a > b ? a : b; }

static const double *stage(const jc_Dop853 *d, int j)
{
    return j == 1 ? d->f0 : j == 13 ? d->f1 : d->k[j];
}

/* The weighted sum of stages, per component: the stage pointers are looked
 * up once per row, not per component (measured: the lookups inside the
 * component loop made this 22 % of a run's time). */
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

/* The input of stage s, y0 + h sum_j a_sj k_j (k1 = f0, k13 = f1), the
 * Butcher matrix written out row by row so that the coefficients are
 * constants and the loop over components is vectorized (measured: a
 * generic loop over a table of rows took 40 % of a run's instructions;
 * written out, the run takes 23 % fewer). The last stage's term is added
 * apart, (y0 + h sum_{j<last}) + (h a_s,last) k_last: each stage waits for
 * the one before it, and this way only a multiply and an add lie between
 * that stage's rates and this one's input, where the sum of all the terms,
 * times h, plus y0 put four there (measured with make bench, alternated
 * with the build before: a drag run 72.2-72.7 -> 69.4-69.7 us; the same
 * instructions, rounding moved by an ulp). */
/* Inlined into every specialization of stages() below, where its ranges
 * are constants (GCC otherwise kept one copy out of line with a runtime
 * range: callgrind, the paper's run 223k -> 237k instructions). */
#if defined(__GNUC__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

static ALWAYS_INLINE void stage_input_n(const jc_Dop853 *restrict d, int s, double h, double *restrict y_all, const int o,
                                 const int n)
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
 * constants by stages() below. */
static ALWAYS_INLINE int stages_n(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, int from, int to, double h, const int o,
                           const int n)
{
    for (int s = from; s <= to; ++s) {
        stage_input_n(d, s, h, d->ys, o, n);
        if (rhs(d->t0 + C[s] * h, d->ys, d->k[s], ctx) != 0) return -1;
    }
    return 0;
}

/* The stages with the phases' ranges as constants ([0, 7): sliding,
 * [0, 9): sliding with resistance, [2, 9): rolling with resistance,
 * [0, 11): flight with air), so that each sum is unrolled over the
 * components without alias checks; any other range by the general loop.
 * Measured with callgrind: a paper run 231.1k -> 223.8k instructions, a
 * drag run 1.206M -> 1.150M, the same numbers; in wall time no difference
 * above the noise (the stages wait on one another). Chosen once per step,
 * not per stage, and the carried components not copied per stage
 * (callgrind, with the rolling range below: a drag run 1.061M -> 0.995M
 * instructions, the paper's run 228.1k -> 223.1k). */
static int stages(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, int from, int to, double h)
{
    switch (d->first * 16 + d->dim) {
    case 7: return stages_n(d, rhs, ctx, from, to, h, 0, 7);
    case 9: return stages_n(d, rhs, ctx, from, to, h, 0, 9);
    case 11: return stages_n(d, rhs, ctx, from, to, h, 0, 11);
    case 2 * 16 + 7: return stages_n(d, rhs, ctx, from, to, h, 2, 7);
    default: return stages_n(d, rhs, ctx, from, to, h, d->first, d->dim);
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
    d->rejected_last = 0;
    d->log2_err_old = LOG2_ERR_MIN;
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
static double step_error(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h)
{
    const int n = d->dim, o = d->first;
    d->dense_ready = 0;
    if (stages(d, rhs, ctx, 2, 12, h) != 0) return INFINITY;
    /* The integrated components [o, o + n) of every vector, from 0. */
    double inc[JC_DOP_MAX_DIM], e5[JC_DOP_MAX_DIM];
    const double *k1 = d->f0 + o, *k6 = d->k[6] + o, *k7 = d->k[7] + o, *k8 = d->k[8] + o, *k9 = d->k[9] + o;
    const double *k10 = d->k[10] + o, *k11 = d->k[11] + o, *k12 = d->k[12] + o;
    const double *y0 = d->y0 + o, *floor_ = d->scale_floor + o;
    double *y1 = d->y1 + o;
    for (int i = 0; i < n; ++i) {
        inc[i] = B[0] * k1[i] + B[1] * k6[i] + B[2] * k7[i] + B[3] * k8[i] + B[4] * k9[i] + B[5] * k10[i] +
                 B[6] * k11[i] + B[7] * k12[i];
        e5[i] = ER[0] * k1[i] + ER[1] * k6[i] + ER[2] * k7[i] + ER[3] * k8[i] + ER[4] * k9[i] + ER[5] * k10[i] +
                ER[6] * k11[i] + ER[7] * k12[i];
    }
    double err5 = 0.0, err3 = 0.0;
    for (int i = 0; i < n; ++i) {
        y1[i] = y0[i] + h * inc[i];
        const double e3 = inc[i] - BHH[0] * k1[i] - BHH[1] * k9[i] - BHH[2] * k12[i];
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
    const double err = fabs(h) * err5 * sqrt(1.0 / (n * deno));
    return isfinite(err) ? err : INFINITY;
}

/* f1 at the step's end; 0 when it and y1 are finite. */
static int end_rate(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h)
{
    if (rhs(d->t0 + h, d->y1, d->f1, ctx) != 0) return -1;
    for (int i = d->first; i < d->first + d->dim; ++i)
        if (!isfinite(d->y1[i]) || !isfinite(d->f1[i])) return -1;
    d->h = h;
    return 0;
}

double jc_dop853_try(jc_Dop853 *d, jc_DopRhs rhs, void *ctx, double h, double *h_next)
{
    double err = step_error(d, rhs, ctx, h);
    if (err <= 1.0 && end_rate(d, rhs, ctx, h) != 0) err = INFINITY;
    if (!isfinite(err)) {
        *h_next = 0.1 * h;
        d->rejected_last = 1;
        return INFINITY;
    }
    const double log2_err = log2_pos(err > ERR_TINY ? err : ERR_TINY);
    const double expo = 0.125 - 0.2 * PI_BETA;
    if (err <= 1.0) {
        /* err^expo / err_old^beta / SAFETY */
        const double fac = exp2_small(expo * log2_err - PI_BETA * d->log2_err_old) / SAFETY;
        *h_next = h / max2(1.0 / FAC_MAX, min2(1.0 / FAC_MIN, fac));
        if (d->rejected_last) *h_next = min2(*h_next, h);
        d->rejected_last = 0;
        d->log2_err_old = max2(log2_err, LOG2_ERR_MIN);
    } else {
        *h_next = h / min2(1.0 / FAC_MIN, exp2_small(expo * log2_err) / SAFETY);
        d->rejected_last = 1;
    }
    return err;
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
    return isfinite(step_error(d, rhs, ctx, h)) && end_rate(d, rhs, ctx, h) == 0 ? 0 : -1;
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
