/* The centre recovered from a mark on the body (an LED on the rim, a dot on
 * a spoke) when the axle was not tracked. While the body rolls, the mark is
 * at C + a (sin θ, cos θ) with C = (x0 + r θ, h): its path is a trochoid
 * about a line, and the whole path follows from θ(t), the line and a. θ(t)
 * is a cubic B-spline (GSL) in each stretch of rolling; the line's tilt and
 * height, a, each stretch's x0 and the spline's coefficients are fitted
 * together by least squares (gsl_multifit_nlinear, analytic Jacobian).
 * Frames the rolling fit cannot explain for two frames or more are
 * departures from rolling (a hop or a slip); a flight (a parabola under
 * gravity with a constant spin) is fitted to each once the caller has
 * decided the incline (jc_track_rim_flights), and its height is a hop's when it
 * fits. */
#include "track_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_bspline.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_sort_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A frame whose mark lies farther than this many sigma from the rolling
 * path is not explained by it (the distance of a 2-D Gaussian exceeds 4.5
 * sigma once in 25,000 frames). */
#define OUTLIER_SIGMAS 4.5
#define MIN_STRETCH 5            /* frames of rolling a stretch needs for its own x0 and spline */
#define KNOT_FRAMES 2.0          /* spline knots every 2 frames ... */
#define KNOT_MIN_S 0.06          /* ... and at least 60 ms apart */
#define ROUNDS 12                /* fit, flag, split, fit again */
#define FIT_ITER 60
#define FLIGHT_MIN_FRAMES 3      /* a flight's 6 values need 3 frames of the mark */
#define FLIGHT_CHI2_DOF 4.0      /* a flight that fits this badly is not one */
#define NP_GLOBAL 3              /* tilt, line height, a */
#define MIN_RADIUS_R 0.02        /* a mark on the body: between 0.02 r and 1.3 r from C ... */
#define MAX_RADIUS_R 1.3
#define MAX_TURN_RAD 0.5         /* ... its line within 30 deg of where it went ... */
#define MIN_ROLLING 0.25         /* ... and rolling in a quarter of the frames at least */
#define CAUCHY_SIGMAS 3.0        /* the robust rounds' weights: Cauchy's at this many sigma */

typedef struct {
    long first, last;  /* frames (inclusive) */
    int ncoef, coef0;  /* the spline's coefficients in the parameter vector */
    int x0;            /* x0's index */
} stretch;

typedef struct {
    const double *t, *xd, *yd;
    long n;
    double r, sigma, floor; /* floor: the noise is not taken below it */
    unsigned char *use;   /* frames the fit uses */
    double *w;            /* their weights' square roots (robust rounds; 1 in the last fit) */
    int *st_of;           /* stretch of each frame, -1 outside */
    double *B, *dB;       /* the 4 non-zero basis values and derivatives per frame */
    int *b0;              /* index of the first of them in the parameter vector */
    stretch *st;
    int nst, p;
    long nres;
} rim_ctx;

static double theta_of(const rim_ctx *c, const double *p, long i)
{
    const double *b = c->B + 4 * i, *q = p + c->b0[i];
    return b[0] * q[0] + b[1] * q[1] + b[2] * q[2] + b[3] * q[3];
}

static double omega_of(const rim_ctx *c, const double *p, long i)
{
    const double *b = c->dB + 4 * i, *q = p + c->b0[i];
    return b[0] * q[0] + b[1] * q[1] + b[2] * q[2] + b[3] * q[3];
}

/* The mark on the rolling path at frame i, in the data's frame. */
static void mark_at(const rim_ctx *c, const double *p, long i, double *qx, double *qy, double *th)
{
    *th = theta_of(c, p, i);
    const double px = p[c->st[c->st_of[i]].x0] + c->r * *th + p[2] * sin(*th), py = p[1] + p[2] * cos(*th);
    const double cf = cos(p[0]), sf = sin(p[0]);
    *qx = px * cf - py * sf;
    *qy = px * sf + py * cf;
}

static int f_eval(const gsl_vector *pv, void *ctx, gsl_vector *f)
{
    const rim_ctx *c = ctx;
    long k = 0;
    for (long i = 0; i < c->n; ++i) {
        if (!c->use[i]) continue;
        double qx, qy, th;
        mark_at(c, pv->data, i, &qx, &qy, &th);
        gsl_vector_set(f, (size_t)k++, c->w[i] * (qx - c->xd[i]) / c->sigma);
        gsl_vector_set(f, (size_t)k++, c->w[i] * (qy - c->yd[i]) / c->sigma);
    }
    return GSL_SUCCESS;
}

static int df_eval(const gsl_vector *pv, void *ctx, gsl_matrix *J)
{
    const rim_ctx *c = ctx;
    const double *p = pv->data, cf = cos(p[0]), sf = sin(p[0]), a = p[2];
    gsl_matrix_set_zero(J);
    long k = 0;
    for (long i = 0; i < c->n; ++i) {
        if (!c->use[i]) continue;
        const double s = c->sigma / c->w[i];
        const double th = theta_of(c, p, i), st = sin(th), ct = cos(th);
        const int x0 = c->st[c->st_of[i]].x0;
        const double px = p[x0] + c->r * th + a * st, py = p[1] + a * ct;
        const size_t rx = (size_t)k, ry = (size_t)k + 1;
        /* d/d tilt */
        gsl_matrix_set(J, rx, 0, (-px * sf - py * cf) / s);
        gsl_matrix_set(J, ry, 0, (px * cf - py * sf) / s);
        /* d/dh: P moves along (0, 1) */
        gsl_matrix_set(J, rx, 1, -sf / s);
        gsl_matrix_set(J, ry, 1, cf / s);
        /* d/da: along (sin th, cos th) */
        gsl_matrix_set(J, rx, 2, (st * cf - ct * sf) / s);
        gsl_matrix_set(J, ry, 2, (st * sf + ct * cf) / s);
        /* d/dx0: along (1, 0) */
        gsl_matrix_set(J, rx, (size_t)x0, cf / s);
        gsl_matrix_set(J, ry, (size_t)x0, sf / s);
        /* d/d theta: along (r + a cos th, -a sin th), times each basis value */
        const double dx = c->r + a * ct, dy = -a * st;
        const double gx = (dx * cf - dy * sf) / s, gy = (dx * sf + dy * cf) / s;
        for (int j = 0; j < 4; ++j) {
            const double b = c->B[4 * i + j];
            gsl_matrix_set(J, rx, (size_t)(c->b0[i] + j), gx * b);
            gsl_matrix_set(J, ry, (size_t)(c->b0[i] + j), gy * b);
        }
        k += 2;
    }
    return GSL_SUCCESS;
}

/* The major axis of the points' spread: the rolling line's direction. */
static double major_axis(const double *x, const double *y, long n, double *xm, double *ym)
{
    double sx = 0, sy = 0;
    for (long i = 0; i < n; ++i) sx += x[i], sy += y[i];
    *xm = sx / (double)n, *ym = sy / (double)n;
    double cxx = 0, cyy = 0, cxy = 0;
    for (long i = 0; i < n; ++i) {
        const double u = x[i] - *xm, v = y[i] - *ym;
        cxx += u * u, cyy += v * v, cxy += u * v;
    }
    return 0.5 * atan2(2 * cxy, cxx - cyy);
}


/* θ at every frame by the most likely path over a grid of angles (Viterbi):
 * the mark's height across the line tells cos θ (a cos θ + h), and its step
 * along the line between two frames tells the step of θ while rolling
 * (r Δθ + a Δ sin θ). Rolling either way (a hoop rocking) and any spin up
 * to a quarter turn per frame are followed; the grid's spacing is a first
 * guess's accuracy, refined by the least squares after. */
#define GRID_STEP 0.04
#define VITERBI_CELLS 5e6 /* frames x grid angles at most (20 to 40 MB of back-pointers) */
static int viterbi(const double *u, const double *v, long n, double h, double a, double r, double noise,
                   double *theta)
{
    double umin = INFINITY, umax = -INFINITY;
    for (long i = 0; i < n; ++i) umin = fmin(umin, u[i]), umax = fmax(umax, u[i]);
    const double reach = (umax - umin + 2.0 * a) / r + JC_TRACK_PI;
    /* The grid at GRID_STEP, coarser where the frames and the reach would
     * make the back-pointers too many (a first guess only). */
    const double step = fmax(GRID_STEP, 2.0 * reach * (double)n / VITERBI_CELLS);
    const long g = (long)ceil(2.0 * reach / step) + 1;
    const long jump = (long)ceil(0.5 * JC_TRACK_PI / step); /* steps of up to a quarter turn per frame */
    if (g < 8 || (double)g * (double)n > 2.0 * VITERBI_CELLS) return -1;
    double *cost = malloc((size_t)g * sizeof *cost), *next = malloc((size_t)g * sizeof *next);
    double *sn = malloc((size_t)g * sizeof *sn), *cs = malloc((size_t)g * sizeof *cs);
    int *from = malloc((size_t)(n * g) * sizeof *from);
    if (!cost || !next || !sn || !cs || !from) {
        free(cost), free(next), free(sn), free(cs), free(from);
        return -1;
    }
    const double sv = noise, su = noise * 1.4142;
#define ANGLE(k) (-reach + step * (double)(k))
    for (long k = 0; k < g; ++k) sn[k] = sin(ANGLE(k)), cs[k] = cos(ANGLE(k));
    for (long k = 0; k < g; ++k) {
        const double e = (v[0] - h - a * cs[k]) / sv;
        /* The first frame's angle within a turn of 0: the path's turns count from it. */
        cost[k] = fabs(ANGLE(k)) <= JC_TRACK_PI ? 0.5 * e * e : INFINITY;
    }
    for (long i = 1; i < n; ++i) {
        const double du = u[i] - u[i - 1];
        for (long k = 0; k < g; ++k) {
            const double e = (v[i] - h - a * cs[k]) / sv;
            double best = INFINITY;
            int arg = -1;
            const long lo = k - jump > 0 ? k - jump : 0, hi = k + jump < g - 1 ? k + jump : g - 1;
            for (long q = lo; q <= hi; ++q) {
                if (!(cost[q] < best)) continue;
                const double d = (du - r * step * (double)(k - q) - a * (sn[k] - sn[q])) / su;
                const double c = cost[q] + 0.5 * d * d;
                if (c < best) best = c, arg = (int)q;
            }
            next[k] = best + 0.5 * e * e;
            from[i * g + k] = arg;
        }
        memcpy(cost, next, (size_t)g * sizeof *cost);
    }
    long k = 0;
    for (long q = 1; q < g; ++q)
        if (cost[q] < cost[k]) k = q;
    for (long i = n - 1; i >= 0; --i) {
        theta[i] = ANGLE(k);
        if (i > 0) k = from[i * g + k] >= 0 ? from[i * g + k] : k;
    }
#undef ANGLE
    free(cost), free(next), free(sn), free(cs), free(from);
    return 0;
}

/* First guesses: the tilt from the spread's major axis (level when the
 * body hardly travelled), h and a from the extremes of the height across
 * it, θ by viterbi(). */
static void first_guess(const rim_ctx *c, double *tilt, double *h, double *a, double *theta)
{
    double xm, ym;
    *tilt = major_axis(c->xd, c->yd, c->n, &xm, &ym);
    double *u = malloc((size_t)c->n * sizeof *u), *v = malloc((size_t)c->n * sizeof *v);
    double *w = malloc((size_t)c->n * sizeof *w);
    *h = ym, *a = c->r;
    for (long i = 0; i < c->n; ++i) theta[i] = 0.0;
    if (!u || !v || !w) {
        free(u), free(v), free(w);
        return;
    }
    for (int pass = 0; pass < 2; ++pass) {
        const double cf = cos(*tilt), sf = sin(*tilt);
        double umin = INFINITY, umax = -INFINITY;
        for (long i = 0; i < c->n; ++i) {
            jc_track_turn(c->xd[i], c->yd[i], cf, sf, &u[i], &v[i]);
            umin = fmin(umin, u[i]), umax = fmax(umax, u[i]);
            w[i] = v[i];
        }
        gsl_sort(w, 1, (size_t)c->n);
        const double lo = w[(long)(0.02 * (double)(c->n - 1))], hi = w[(long)(0.98 * (double)(c->n - 1))];
        *h = 0.5 * (hi + lo);
        *a = fmin(fmax(0.5 * (hi - lo), 0.1 * c->r), 1.2 * c->r);
        /* A body that hardly travelled: the spread tells no direction. */
        if (pass == 0 && umax - umin < 2.0 * (hi - lo)) *tilt = 0.0;
        else break;
    }
    if (viterbi(u, v, c->n, *h, *a, c->r, fmax(2e-3, 0.03 * *a), theta) != 0)
        for (long i = 0; i < c->n; ++i) theta[i] = 0.0;
    free(u), free(v), free(w);
}

static double knot_step(const rim_ctx *c)
{
    const double dt = (c->t[c->n - 1] - c->t[0]) / (double)(c->n > 1 ? c->n - 1 : 1);
    return fmax(KNOT_FRAMES * dt, KNOT_MIN_S);
}

/* The stretches' splines: basis values at every frame of each, and the
 * parameter vector's layout. -1 out of memory. */
static int layout(rim_ctx *c)
{
    int p = NP_GLOBAL;
    const double step = knot_step(c);
    for (int s = 0; s < c->nst; ++s) {
        stretch *S = &c->st[s];
        const double span = c->t[S->last] - c->t[S->first];
        const long nbreak = span > 0 ? (long)ceil(span / step) + 1 : 2;
        S->x0 = p++;
        S->coef0 = p;
        S->ncoef = (int)(nbreak < 2 ? 2 : nbreak) + 2;
        p += S->ncoef;
        gsl_bspline_workspace *w = gsl_bspline_alloc(4, (size_t)(S->ncoef - 2));
        gsl_matrix *dB = gsl_matrix_alloc(4, 2);
        if (!w || !dB) {
            if (w) gsl_bspline_free(w);
            gsl_matrix_free(dB);
            return -1;
        }
        const double t0 = c->t[S->first], t1 = span > 0 ? c->t[S->last] : t0 + 1e-3;
        gsl_bspline_knots_uniform(t0, t1, w);
        for (long i = S->first; i <= S->last; ++i) {
            size_t is, ie;
            const double ti = fmin(fmax(c->t[i], t0), t1);
            gsl_bspline_deriv_eval_nonzero(ti, 1, dB, &is, &ie, w);
            for (int j = 0; j < 4; ++j) {
                c->B[4 * i + j] = gsl_matrix_get(dB, (size_t)j, 0);
                c->dB[4 * i + j] = gsl_matrix_get(dB, (size_t)j, 1);
            }
            c->b0[i] = S->coef0 + (int)is;
            c->st_of[i] = s;
        }
        gsl_bspline_free(w);
        gsl_matrix_free(dB);
    }
    c->p = p;
    return 0;
}

/* Each stretch's coefficients by linear least squares on the frames' θ
 * (the spline nearest to them), and its x0. */
static void init_params(const rim_ctx *c, const double *theta, double a, double *p)
{
    for (int s = 0; s < c->nst; ++s) {
        const stretch *S = &c->st[s];
        const long m = S->last - S->first + 1;
        gsl_matrix *X = gsl_matrix_calloc((size_t)m, (size_t)S->ncoef);
        gsl_vector *y = gsl_vector_alloc((size_t)m), *cf = gsl_vector_alloc((size_t)S->ncoef);
        gsl_matrix *cov = gsl_matrix_alloc((size_t)S->ncoef, (size_t)S->ncoef);
        gsl_multifit_linear_workspace *w = gsl_multifit_linear_alloc((size_t)m, (size_t)S->ncoef);
        double chi2, *x0s = malloc((size_t)m * sizeof *x0s);
        if (X && y && cf && cov && w && x0s) {
            for (long i = S->first; i <= S->last; ++i) {
                for (int j = 0; j < 4; ++j)
                    gsl_matrix_set(X, (size_t)(i - S->first), (size_t)(c->b0[i] - S->coef0 + j), c->B[4 * i + j]);
                gsl_vector_set(y, (size_t)(i - S->first), theta[i]);
            }
            size_t rank;
            gsl_multifit_linear_tsvd(X, y, 1e-12, cf, cov, &chi2, &rank, w);
            for (int j = 0; j < S->ncoef; ++j) p[S->coef0 + j] = gsl_vector_get(cf, (size_t)j);
            /* x0: where the along-line coordinate puts the centre at θ = 0. */
            const double cfi = cos(p[0]), sfi = sin(p[0]);
            for (long i = S->first; i <= S->last; ++i) {
                const double u = c->xd[i] * cfi + c->yd[i] * sfi;
                x0s[i - S->first] = u - c->r * theta[i] - a * sin(theta[i]);
            }
            p[S->x0] = jc_track_median(x0s, m);
        }
        gsl_matrix_free(X);
        gsl_vector_free(y);
        gsl_vector_free(cf);
        gsl_matrix_free(cov);
        if (w) gsl_multifit_linear_free(w);
        free(x0s);
    }
}

/* Least squares from p; its covariance (scaled to the residuals) into cov
 * when not NULL. 0, or -1 when GSL fails. */
static int solve(rim_ctx *c, double *p, gsl_matrix *cov)
{
    c->nres = 0;
    for (long i = 0; i < c->n; ++i) c->nres += 2 * c->use[i];
    if (c->nres <= c->p) return -1;
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;
    gsl_multifit_nlinear_workspace *w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, (size_t)c->nres, (size_t)c->p);
    if (!w) return -1;
    gsl_vector_view pv = gsl_vector_view_array(p, (size_t)c->p);
    gsl_multifit_nlinear_fdf fdf = {f_eval, df_eval, NULL, (size_t)c->nres, (size_t)c->p, c, 0, 0, 0};
    int info = 0, rc = -1;
    if (gsl_multifit_nlinear_init(&pv.vector, &fdf, w) == GSL_SUCCESS) {
        const int st = gsl_multifit_nlinear_driver(FIT_ITER, 1e-10, 1e-10, 0.0, NULL, NULL, &info, w);
        if (st == GSL_SUCCESS || st == GSL_EMAXITER || st == GSL_ENOPROG) {
            gsl_vector_memcpy(&pv.vector, gsl_multifit_nlinear_position(w));
            rc = 0;
            if (cov) {
                double chi2;
                gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &chi2);
                gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 1e-12, cov);
                gsl_matrix_scale(cov, chi2 / (double)(c->nres - c->p));
            }
        }
    }
    gsl_multifit_nlinear_free(w);
    return rc;
}

/* A negative a is the same path with θ half a turn on: a made positive
 * (B-splines sum to 1, so adding to every coefficient adds to θ). */
static void normalize(const rim_ctx *c, double *p)
{
    if (p[2] >= 0) return;
    p[2] = -p[2];
    for (int s = 0; s < c->nst; ++s) {
        p[c->st[s].x0] -= c->r * JC_TRACK_PI;
        for (int j = 0; j < c->st[s].ncoef; ++j) p[c->st[s].coef0 + j] += JC_TRACK_PI;
    }
}

/* The stretches: runs of frames outside departures (a single mis-click,
 * bad 1, stays in its stretch, unused), at least MIN_STRETCH long. */
static int split(rim_ctx *c, const unsigned char *bad)
{
    c->nst = 0;
    long run = 0;
    for (long i = 0; i <= c->n; ++i) {
        if (i < c->n) c->st_of[i] = -1;
        if (i < c->n && bad[i] != 2) {
            run++;
            continue;
        }
        if (run >= MIN_STRETCH) {
            c->st[c->nst].first = i - run;
            c->st[c->nst].last = i - 1;
            c->nst++;
        }
        run = 0;
    }
    for (int s = 0; s < c->nst; ++s)
        for (long i = c->st[s].first; i <= c->st[s].last; ++i) c->st_of[i] = s;
    return c->nst;
}

/* Frames the path does not explain: runs of at least 2 beyond
 * OUTLIER_SIGMAS are departures (bad = 2), single ones mis-clicks (bad = 1).
 * The noise: the RMS of the residuals' components over the frames kept. */
static void flag(rim_ctx *c, const double *p, unsigned char *bad, double *noise, double *work)
{
    double *d = work;
    long m = 0;
    for (long i = 0; i < c->n; ++i) {
        d[i] = NAN;
        if (c->st_of[i] < 0) continue;
        double qx, qy, th;
        mark_at(c, p, i, &qx, &qy, &th);
        d[i] = hypot(qx - c->xd[i], qy - c->yd[i]);
        work[c->n + m++] = d[i];
    }
    /* The scale from the lowest quarter of the distances (a 2-D Gaussian's
     * first quartile is 0.7585 sigma): rolling need explain only a quarter
     * of the frames for the others to be told from it. */
    double s = c->sigma;
    if (m > 0) {
        gsl_sort(work + c->n, 1, (size_t)m);
        s = fmax(work[c->n + m / 4] / 0.7585, c->floor);
    }
    double ss = 0;
    long kept = 0;
    for (long i = 0; i < c->n; ++i) {
        const int far = !(d[i] <= OUTLIER_SIGMAS * s) || bad[i] == 2;
        const int far_prev = i > 0 && (!(d[i - 1] <= OUTLIER_SIGMAS * s) || bad[i - 1] == 2);
        const int far_next = i + 1 < c->n && (!(d[i + 1] <= OUTLIER_SIGMAS * s) || bad[i + 1] == 2);
        bad[i] = !far ? 0 : (far_prev || far_next) ? 2 : 1;
        /* Cauchy's weight for the next round: frames far from the path pull less. */
        c->w[i] = isfinite(d[i]) ? 1.0 / sqrt(1.0 + pow(d[i] / (CAUCHY_SIGMAS * s), 2)) : 1.0;
        if (!bad[i] && isfinite(d[i])) ss += d[i] * d[i], kept++;
    }
    /* The noise per coordinate: the fit took p of the 2 kept residuals a frame. */
    const double dof = 2.0 * (double)kept - (double)c->p;
    *noise = dof > 0 ? sqrt(ss / dof) : s;
}

/* ---- a flight fitted to a departure's frames ---- */

typedef struct {
    const double *t, *mx, *my; /* the mark in the surface frame (y from the surface) */
    long first, last;
    double a, sigma, gx, gy;   /* gravity's components in the incline frame */
} flight_ctx;

static void flight_at(const flight_ctx *f, const double *q, double t, double *cx, double *cy, double *th)
{
    const double u = t - f->t[f->first];
    *cx = q[0] + q[2] * u + 0.5 * f->gx * u * u;
    *cy = q[1] + q[3] * u + 0.5 * f->gy * u * u;
    *th = q[4] + q[5] * u;
}

static int flight_f(const gsl_vector *qv, void *ctx, gsl_vector *r)
{
    const flight_ctx *f = ctx;
    size_t k = 0;
    for (long i = f->first; i <= f->last; ++i) {
        double cx, cy, th;
        flight_at(f, qv->data, f->t[i], &cx, &cy, &th);
        gsl_vector_set(r, k++, (cx + f->a * sin(th) - f->mx[i]) / f->sigma);
        gsl_vector_set(r, k++, (cy + f->a * cos(th) - f->my[i]) / f->sigma);
    }
    return GSL_SUCCESS;
}

/* The centre's highest point above the surface over [t0, t1] for values q. */
static double flight_peak(const flight_ctx *f, const double *q, double t0, double t1, double r)
{
    double best = -INFINITY;
    const double u0 = t0 - f->t[f->first], u1 = t1 - f->t[f->first];
    double us[3] = {u0, u1, f->gy < 0 ? -q[3] / f->gy : u0};
    for (int k = 0; k < 3; ++k) {
        const double u = fmin(fmax(us[k], u0), u1);
        best = fmax(best, q[1] + q[3] * u + 0.5 * f->gy * u * u - r);
    }
    return best;
}

/* Fits a flight to the mark's frames [f->first, f->last] from the first
 * guess start (q: the centre's x and y, their rates, θ and ω at the first
 * frame). 0 when it explains them: q_out the values, *height the centre's
 * highest point above contact over [t_lo, t_hi] and *sigma its standard
 * error (delta method); -1 with fewer than 3 frames, or a fit that fails
 * or fits badly. */
static int fit_flight(flight_ctx *f, double r, const double start[6], double t_lo, double t_hi, double *height,
                      double *sigma, double *q_out)
{
    const long nf = f->last - f->first + 1;
    const size_t n = (size_t)(2 * nf), p = 6;
    if (nf < FLIGHT_MIN_FRAMES) return -1;
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;
    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, n, p);
    gsl_matrix *cov = gsl_matrix_alloc(p, p);
    double q[6];
    memcpy(q, start, sizeof q);
    gsl_vector_view qv = gsl_vector_view_array(q, p);
    gsl_multifit_nlinear_fdf fdf = {flight_f, NULL, NULL, n, p, f, 0, 0, 0};
    int rc = -1, info;
    if (w && cov && gsl_multifit_nlinear_init(&qv.vector, &fdf, w) == GSL_SUCCESS) {
        const int st = gsl_multifit_nlinear_driver(100, 1e-10, 1e-10, 0.0, NULL, NULL, &info, w);
        double chi2;
        gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &chi2);
        const double dof = (double)(n - p);
        if ((st == GSL_SUCCESS || st == GSL_EMAXITER || st == GSL_ENOPROG) && (dof <= 0 || chi2 / dof < FLIGHT_CHI2_DOF)) {
            gsl_vector_memcpy(&qv.vector, gsl_multifit_nlinear_position(w));
            gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 1e-12, cov);
            if (dof > 0) gsl_matrix_scale(cov, fmax(chi2 / dof, 1.0));
            *height = flight_peak(f, q, t_lo, t_hi, r);
            double g[6], var = 0;
            for (int j = 0; j < 6; ++j) {
                double qq[6];
                memcpy(qq, q, sizeof qq);
                const double h = 1e-6 * fmax(1.0, fabs(q[j]));
                qq[j] += h;
                const double up = flight_peak(f, qq, t_lo, t_hi, r);
                qq[j] -= 2 * h;
                g[j] = (up - flight_peak(f, qq, t_lo, t_hi, r)) / (2 * h);
            }
            for (int i = 0; i < 6; ++i)
                for (int j = 0; j < 6; ++j) var += g[i] * gsl_matrix_get(cov, (size_t)i, (size_t)j) * g[j];
            *sigma = sqrt(fmax(var, 0.0));
            memcpy(q_out, q, sizeof q);
            rc = 0;
        }
    }
    if (w) gsl_multifit_nlinear_free(w);
    gsl_matrix_free(cov);
    return rc;
}

/* ---- the whole recovery ---- */

static int alloc_ctx(rim_ctx *c, long n)
{
    c->use = malloc((size_t)n);
    c->w = malloc((size_t)n * sizeof *c->w);
    c->st_of = malloc((size_t)n * sizeof *c->st_of);
    c->B = malloc((size_t)n * 4 * sizeof *c->B);
    c->dB = malloc((size_t)n * 4 * sizeof *c->dB);
    c->b0 = malloc((size_t)n * sizeof *c->b0);
    c->st = malloc((size_t)(n / MIN_STRETCH + 2) * sizeof *c->st);
    if (c->w)
        for (long i = 0; i < n; ++i) c->w[i] = 1.0;
    return c->use && c->w && c->st_of && c->B && c->dB && c->b0 && c->st ? 0 : -1;
}

static void free_ctx(rim_ctx *c)
{
    free(c->use);
    free(c->w);
    free(c->st_of);
    free(c->B);
    free(c->dB);
    free(c->b0);
    free(c->st);
}

/* The per-frame results of a fitted rolling path. */
static void fill_rolling(const rim_ctx *c, const double *p, const gsl_matrix *cov, const unsigned char *bad,
                         jc_TrackRimResult *out)
{
    const double cf = cos(p[0]), sf = sin(p[0]);
    const double var_h = gsl_matrix_get(cov, 1, 1);
    long m = 0;
    for (long i = 0; i < c->n; ++i) {
        /* Every frame in the surface frame: turned by the tilt, the surface at y = 0. */
        double across;
        jc_track_turn(c->xd[i], c->yd[i], cf, sf, &out->mark_x[i], &across);
        out->mark_y[i] = across - p[1] + c->r;
        out->cx[i] = out->cy[i] = out->c_sigma[i] = out->theta[i] = out->omega[i] = NAN;
        out->rolling[i] = 0;
        const int s = c->st_of[i];
        if (s < 0) continue;
        const double th = theta_of(c, p, i);
        out->theta[i] = th;
        out->omega[i] = omega_of(c, p, i);
        out->cx[i] = p[c->st[s].x0] + c->r * th;
        out->cy[i] = c->r;
        out->rolling[i] = bad[i] == 0;
        /* var(x0 + r Σ B c) from the covariance of x0 and the 4 coefficients. */
        const int idx[5] = {c->st[s].x0, c->b0[i], c->b0[i] + 1, c->b0[i] + 2, c->b0[i] + 3};
        const double g[5] = {1.0, c->r * c->B[4 * i], c->r * c->B[4 * i + 1], c->r * c->B[4 * i + 2], c->r * c->B[4 * i + 3]};
        double var = var_h;
        for (int a = 0; a < 5; ++a)
            for (int b = 0; b < 5; ++b) var += g[a] * gsl_matrix_get(cov, (size_t)idx[a], (size_t)idx[b]) * g[b];
        out->c_sigma[i] = sqrt(fmax(var, 0.0));
        m++;
    }
    out->rolling_frames = m;
}

/* Departures: runs of frames outside the rolling stretches or flagged as
 * departures, each with what the mark alone allows of its height (the
 * flights are fitted after, by jc_track_rim_flights). */
static void departures(const rim_ctx *c, const double *p, const unsigned char *bad, jc_TrackRimResult *out)
{
    out->departures = 0;
    const double a = p[2];
    long i = 0;
    while (i < c->n) {
        const int off = c->st_of[i] < 0 || bad[i] == 2;
        if (!off) {
            i++;
            continue;
        }
        long j = i;
        while (j + 1 < c->n && (c->st_of[j + 1] < 0 || bad[j + 1] == 2)) j++;
        if (j > i || c->st_of[i] < 0) {
            jc_TrackHop *h = &out->dep[out->departures++];
            memset(h, 0, sizeof *h);
            h->first = i, h->last = j, h->peak = i;
            h->height_m = h->height_sigma_m = NAN;
            /* What the mark alone allows: the centre is within a of it, and not below r. */
            double bound = 0;
            for (long k = i; k <= j; ++k) {
                bound = fmax(bound, out->mark_y[k] + a - c->r);
                if (out->mark_y[k] > out->mark_y[h->peak]) h->peak = k;
            }
            h->bound_m = bound;
        }
        i = j + 1;
    }
}

/* A flight under gravity (gx, gy) fitted to the departure h; when it fits,
 * its height is h's and its centre, θ and ω the frames'. */
static void fit_departure(const jc_TrackRimInput *in, double gx, double gy, jc_TrackHop *h, jc_TrackRimResult *out)
{
    const double *t = in->t_s, r = in->radius_m;
    const long n = in->n, i = h->first, j = h->last;
    flight_ctx f = {t, out->mark_x, out->mark_y, i, j, out->a_m, out->noise_m, gx, gy};
    /* From the rolling state just before (the frame before a departure lies
     * in a rolling stretch): the centre, its velocity, θ and ω. */
    const long b = i > 0 && !isnan(out->theta[i - 1]) ? i - 1 : -1;
    const double w0 = b >= 0 ? out->omega[b] : 0.0, th0 = b >= 0 ? out->theta[b] : 0.0;
    const double dt = t[i] - (b >= 0 ? t[b] : t[i]);
    const double span = t[j] - t[i] + 2.0 * (t[n - 1] - t[0]) / (double)(n - 1);
    /* Up at the speed that brings it down after span, from half its peak height. */
    const double vy0 = -0.5 * gy * span, y0 = r + vy0 * 0.5 * span / 2.0;
    const double q0[6] = {b >= 0 ? out->cx[b] + r * w0 * dt : out->mark_x[i], y0, r * w0, vy0, th0 + w0 * dt, w0};
    double q[6];
    const double t_lo = b >= 0 ? t[b] : t[i], t_hi = j + 1 < n ? t[j + 1] : t[j];
    if (fit_flight(&f, r, q0, t_lo, t_hi, &h->height_m, &h->height_sigma_m, q) != 0) return;
    h->fitted_flight = 1;
    for (long k = i; k <= j; ++k) {
        double cx, cy, th;
        flight_at(&f, q, t[k], &cx, &cy, &th);
        out->cx[k] = cx, out->cy[k] = cy, out->theta[k] = th, out->omega[k] = q[5];
        out->c_sigma[k] = h->height_sigma_m;
    }
}

void jc_track_rim_flights(const jc_TrackRimInput *in, double incline_rad, jc_TrackRimResult *out)
{
    const double gx = in->gravity_mps2 * sin(incline_rad), gy = -in->gravity_mps2 * cos(incline_rad);
    if (!isfinite(gx)) return;
    for (long k = 0; k < out->departures; ++k) fit_departure(in, gx, gy, &out->dep[k], out);
}

int jc_track_rim_recover(const jc_TrackRimInput *in, jc_TrackRimResult *out)
{
    const long n = in->n;
    out->departures = 0;
    if (n < 2 * MIN_STRETCH || n > JC_TRACK_RIM_MAX_FRAMES || !(in->radius_m > 0)) return -1;
    rim_ctx c;
    memset(&c, 0, sizeof c);
    c.t = in->t_s, c.xd = in->x_m, c.yd = in->y_m, c.n = n, c.r = in->radius_m;
    c.sigma = in->sigma_floor_m > 0 ? in->sigma_floor_m : 1e-3;
    c.floor = c.sigma;
    unsigned char *bad = calloc((size_t)n, 1), *before = malloc((size_t)n);
    double *theta = malloc((size_t)n * sizeof *theta), *work = malloc((size_t)(2 * n) * sizeof *work);
    double *p = NULL;
    gsl_matrix *cov = NULL;
    int rc = -1;
    if (!bad || !before || !theta || !work || alloc_ctx(&c, n) != 0) goto done;
    double tilt, h, a;
    first_guess(&c, &tilt, &h, &a, theta);
    const double tilt0 = tilt;
    double noise = c.sigma;
    for (int round = 0; round < ROUNDS; ++round) {
        if (split(&c, bad) == 0) break;
        free(p);
        p = NULL;
        if (layout(&c) != 0 || !(p = calloc((size_t)c.p, sizeof *p))) break;
        p[0] = tilt, p[1] = h, p[2] = a;
        init_params(&c, theta, a, p);
        for (long i = 0; i < n; ++i) c.use[i] = c.st_of[i] >= 0 && bad[i] == 0;
        if (solve(&c, p, NULL) != 0) break;
        normalize(&c, p);
        tilt = p[0], h = p[1], a = p[2];
        /* Frames that turn bad keep this round's θ as the next one's first guess. */
        for (long i = 0; i < n; ++i)
            if (c.st_of[i] >= 0) theta[i] = theta_of(&c, p, i);
        memcpy(before, bad, (size_t)n);
        flag(&c, p, bad, &noise, work);
        c.sigma = fmax(noise, in->sigma_floor_m);
        rc = 0;
        if (memcmp(before, bad, (size_t)n) == 0) break;
    }
    if (rc != 0 || !p) goto done;
    /* The final fit on the final stretches, with its covariance. */
    split(&c, bad);
    free(p);
    p = NULL;
    if (c.nst == 0 || layout(&c) != 0 || !(p = calloc((size_t)c.p, sizeof *p)) ||
        !(cov = gsl_matrix_alloc((size_t)c.p, (size_t)c.p))) {
        rc = -1;
        goto done;
    }
    p[0] = tilt, p[1] = h, p[2] = a;
    init_params(&c, theta, a, p);
    for (long i = 0; i < n; ++i) c.use[i] = c.st_of[i] >= 0 && bad[i] == 0, c.w[i] = 1.0;
    if (solve(&c, p, cov) != 0) {
        rc = -1;
        goto done;
    }
    normalize(&c, p);
    double sig_tmp;
    flag(&c, p, bad, &sig_tmp, work);
    /* A path rolling does not explain: a mark off the body, a turn of the
     * line away from where the mark went, or rolling in too few frames. */
    long rolling = 0;
    for (long i = 0; i < n; ++i) rolling += c.st_of[i] >= 0 && bad[i] == 0;
    if (!(p[2] > MIN_RADIUS_R * c.r && p[2] < MAX_RADIUS_R * c.r) || fabs(p[0] - tilt0) > MAX_TURN_RAD ||
        (double)rolling < MIN_ROLLING * (double)n) {
        rc = -1;
        goto done;
    }
    out->noise_m = fmax(sig_tmp, in->sigma_floor_m);
    out->tilt_rad = p[0];
    out->tilt_sigma_rad = sqrt(gsl_matrix_get(cov, 0, 0));
    out->a_m = p[2];
    out->a_sigma_m = sqrt(gsl_matrix_get(cov, 2, 2));
    out->line_sigma_m = sqrt(gsl_matrix_get(cov, 1, 1));
    fill_rolling(&c, p, cov, bad, out);
    departures(&c, p, bad, out);
    rc = 0;
done:
    free(bad);
    free(before);
    free(theta);
    free(work);
    free(p);
    gsl_matrix_free(cov);
    free_ctx(&c);
    return rc;
}
