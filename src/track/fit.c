/* Least squares of the model against a track (GSL's gsl_multifit_nlinear,
 * Levenberg-Marquardt trust region), and what the video determines.
 *
 * The free values live in an unconstrained space u: a bounded value is
 * lo + (hi - lo) sigmoid(u) (mu_s: from mu_k up, so that mu_k <= mu_s);
 * angles, omega0 and x0 as they are. The first lift-off leaps between
 * branches as the values change, so one descent is not enough: a Latin
 * hypercube over the bounded values is screened (one run each), and the
 * best few points and the user's are descended from; minima within a
 * chi2 threshold of the best are reported. The Jacobian is by central
 * differences with steps far above the simulator's own error (1e-11) and
 * far below the values' uncertainties.
 *
 * A value is not determined by the video when it sits on a bound of its
 * range, when its sigma exceeds its range, when the residuals do not change
 * with it, or when it moves with another (|rho| > 0.99): it is held (at the
 * bound, or at its starting value) and the others are fitted again, and a
 * chi2 profile along its range shows why. The verdict judges the best fit:
 * chi2/dof against the noise, the runs of same-sign residuals, and the hops
 * of the video against the model's.
 *
 * The caller's progress callback hears of each descent as it begins and of
 * each of its iterations, with the stage's part of the whole, and may stop
 * the fit: every loop then ends at once and the fit returns JC_ESTOPPED.
 * jc_track_fit_solve starts from a start given or estimated; jc_track_fit
 * (fit_video.c) first finds where the free motion starts (launch.c). */
#include "track_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define START_SPAN 7
#define JAC_STEP 1e-5            /* central-difference step in u, relative to max(1, |u|) */
#define FAILED_RESIDUAL 1e4      /* per residual, for a run the model refuses */
#define MAX_PASSES 10            /* robust reweighting passes */
#define HUBER_K 1.345            /* 95 % efficiency at the normal */
#define CAUCHY_C 2.385
#define EDGE 1e-3                /* a value this close to a bound (of its range) sits on it */
#define CORRELATED 0.99
#define FLAG_ROUNDS 3
#define MISFIT_CHI2_DOF 3.0      /* at the measured noise */
#define MISFIT_RUNS_Z (-4.0)     /* too few runs of one sign: one in 30,000 for independent residuals */
#define CLEAR_HOP_SIGMAS 3.0     /* a hop clearly above the threshold */
#define DEFAULT_DESCENTS 3
#define XTOL 1e-7                /* the descents' tests: step, gradient, chi2 */
#define GTOL 1e-8
#define FTOL 1e-9
#define PROFILE_MAX_ITER 40      /* a profile point's descents: it shows where chi2 rises, not its last digit */
#define GIVE_UP_EVERY 8          /* a descent checked every 8 iterations ... */
#define GIVE_UP_FACTOR 2.0       /* ... stops when its chi2 is above twice the best's (plus n) */
#define START_EDGE 0.02          /* start points at a bound begin this far inside (of the range) */
#define SNAP_NEAR 0.02           /* a value this near a bound is tried on it */
#define MIN_SCREEN 16
#define MAX_SCREEN 64
/* The stages' parts of a fit's progress, from 0 to 1: the search, values
 * near a bound, the fit without the values not determined, the profiles
 * (a fit of a start window has none); rough shares of the time. */
static const double FIT_PARTS[5] = {0.0, 0.6, 0.67, 0.73, 1.0};
static const double START_WINDOW_PARTS[5] = {0.0, 0.8, 0.9, 1.0, 1.0};

typedef struct {
    const jc_Track *t;
    const jc_SimOptions *sim;
    jc_Setup base;             /* the runs' setup (jc_track_setup): held values set in it */
    jc_State start0;           /* the start before the fit: held start values set in it */
    jc_TrackFitFrame frame0;       /* the mark angle and frame before the fit: held ones set in it */
    int mu_s_tied;             /* mu_s held at its bound mu_k: it follows mu_k */
    int np;
    jc_TrackFitParam param[JC_FIT_MAX_PARAMS];
    jc_TrackResiduals res;
    long nres;
    double *x, *y, *th, *sw, *f;
    unsigned char *series;
    jc_TrackSim ts;            /* its sum: the last run's events */
    /* Progress: the caller's callback and the part of its whole this fit
     * covers; the stage, its part of this fit's [0, 1] and the descents it
     * plans; the last fraction reported (it never decreases). */
    jc_TrackFitSpan span;
    const char *stage;
    char stage_text[96];
    int begun;                 /* descents begun in this stage */
    int planned;
    double stage_lo, stage_hi;
    double reported;
    int stopped;               /* the callback asked to stop */
} fit_ctx;

static void stage_begin(fit_ctx *c, const char *stage, double lo, double hi, int planned)
{
    c->stage = stage;
    c->begun = 0;
    c->stage_lo = lo;
    c->stage_hi = hi;
    c->planned = planned > 0 ? planned : 1;
}

/* Tells the callback how far the stage is (within: its part done, [0, 1]). */
static void report(fit_ctx *c, double within)
{
    if (!c->span.fn || c->stopped) return;
    const double stage = c->stage_lo + (c->stage_hi - c->stage_lo) * fmin(fmax(within, 0.0), 1.0);
    c->reported = fmax(c->reported, c->span.lo + (c->span.hi - c->span.lo) * stage);
    const jc_TrackFitProgress p = {c->stage, c->begun, c->reported};
    if (c->span.fn(c->span.ctx, &p) != 0) c->stopped = 1;
}

static double sigmoid(double u) { return 1.0 / (1.0 + exp(-u)); }
static double logit(double p) { return log(p / (1.0 - p)); }

static int bounded(jc_TrackFitParam p)
{
    return p.kind == JC_FIT_MU_S || p.kind == JC_FIT_MU_K || p.kind == JC_FIT_RESTITUTION ||
           p.kind == JC_FIT_PART_OFFSET || p.kind == JC_FIT_PART_MASS;
}

static int index_of(const fit_ctx *c, jc_TrackFitKind k)
{
    for (int i = 0; i < c->np; ++i)
        if (c->param[i].kind == k) return i;
    return -1;
}

/* The range of free value i given mu_k (mu_k <= mu_s): mu_s lies above
 * mu_k (free or held); mu_k lies below a held mu_s, or in its own range
 * when mu_s is free too (mu_s = mu_k + the margin to slip). */
static void range_of(const fit_ctx *c, int i, double mu_k, double *lo, double *hi)
{
    jc_fit_range(&c->base, c->param[i], lo, hi);
    if (c->param[i].kind == JC_FIT_MU_S) *lo = mu_k;
    if (c->param[i].kind == JC_FIT_MU_K && (index_of(c, JC_FIT_MU_S) >= 0 || c->mu_s_tied))
        jc_fit_range(&c->base, (jc_TrackFitParam){JC_FIT_MU_S, -1}, lo, hi);
}

/* u -> the free values (SI); mu_k first, as mu_s's range is above it. */
static void values_of(const fit_ctx *c, const double *u, double *v)
{
    const int kk = index_of(c, JC_FIT_MU_K);
    double mu_k = c->base.mu_kinetic, lo, hi;
    if (kk >= 0) {
        range_of(c, kk, mu_k, &lo, &hi);
        mu_k = v[kk] = lo + (hi - lo) * sigmoid(u[kk]);
    }
    for (int i = 0; i < c->np; ++i) {
        if (i == kk) continue;
        if (!bounded(c->param[i])) {
            v[i] = u[i];
            continue;
        }
        range_of(c, i, mu_k, &lo, &hi);
        v[i] = lo + (hi - lo) * sigmoid(u[i]);
    }
}

/* The free values -> u (values at a bound moved inside it by edge of the range). */
static void u_of(const fit_ctx *c, const double *v, double *u, double edge)
{
    const int kk = index_of(c, JC_FIT_MU_K);
    const double mu_k = kk >= 0 ? v[kk] : c->base.mu_kinetic;
    for (int i = 0; i < c->np; ++i) {
        if (!bounded(c->param[i])) {
            u[i] = v[i];
            continue;
        }
        double lo, hi;
        range_of(c, i, mu_k, &lo, &hi);
        const double q = hi > lo ? (v[i] - lo) / (hi - lo) : 0.5;
        u[i] = logit(fmin(fmax(q, edge), 1.0 - edge));
    }
}

/* The incline was measured: the frame's tilt turns the model's gravity too. */
static int tilt_tilts_gravity(const fit_ctx *c) { return c->t->incline_source == JC_TRACK_INCLINE_MEASURED; }

/* The setup, start and frame (mark angle, tilt, surface) that u describes. */
static void apply(const fit_ctx *c, const double *u, jc_Setup *s, jc_State *start, jc_TrackFitFrame *frame)
{
    double v[JC_FIT_MAX_PARAMS];
    values_of(c, u, v);
    *s = c->base;
    *start = c->start0;
    *frame = c->frame0;
    for (int i = 0; i < c->np; ++i) jc_fit_set(s, start, frame, c->param[i], v[i]);
    /* A measured incline is the video's plus the tilt (a floor stays a
     * floor: the model takes no incline below 0). */
    if (tilt_tilts_gravity(c)) s->incline_rad = fmax(0.0, c->t->incline_rad + frame->tilt_rad);
    if (s->mu_kinetic > s->mu_static || c->mu_s_tied) s->mu_static = s->mu_kinetic;
    if (start->y_m <= s->body.radius_m) start->vx_mps = s->body.radius_m * start->omega_radps; /* rolling */
    s->theta0_rad = start->theta_rad;
    s->omega0_radps = start->omega_radps;
}

/* Runs the model for u; the raw residuals (unweighted) into c->f. 0, or -1
 * when the model refuses the values. */
static int run_u(fit_ctx *c, const double *u)
{
    jc_Setup s;
    jc_State start;
    jc_TrackFitFrame fr;
    apply(c, u, &s, &start, &fr);
    jc_Model m;
    char err[256];
    if (jc_model_init(&m, &s, err, sizeof err) != JC_OK) return -1;
    if (jc_track_sim_run(&c->ts, &m, &start, c->sim, c->t->t_s + c->res.first, c->res.count, c->x, c->y, c->th, err,
                         sizeof err) != 0)
        return -1;
    jc_fit_to_video(&fr, &start, c->x, c->y, c->th, c->res.count);
    c->res.mark_offset = jc_track_mark_offset_rad(&m, fr.mark_angle_rad);
    jc_track_residuals_eval(&c->res, c->x, c->y, c->th, c->f, c->series);
    return 0;
}

static int f_eval(const gsl_vector *u, void *ctx, gsl_vector *f)
{
    fit_ctx *c = ctx;
    if (run_u(c, u->data) != 0) {
        gsl_vector_set_all(f, FAILED_RESIDUAL);
        return GSL_SUCCESS;
    }
    for (long i = 0; i < c->nres; ++i) gsl_vector_set(f, (size_t)i, c->f[i] * c->sw[i]);
    return GSL_SUCCESS;
}

static double step_of(double u) { return JAC_STEP * fmax(1.0, fabs(u)); }

static int df_eval(const gsl_vector *u, void *ctx, gsl_matrix *J)
{
    fit_ctx *c = ctx;
    const size_t n = (size_t)c->nres;
    gsl_vector *fp = gsl_vector_alloc(n), *fm = gsl_vector_alloc(n), *up = gsl_vector_alloc(u->size);
    if (!fp || !fm || !up) {
        gsl_vector_free(fp);
        gsl_vector_free(fm);
        gsl_vector_free(up);
        return GSL_ENOMEM;
    }
    for (size_t j = 0; j < u->size; ++j) {
        const double h = step_of(gsl_vector_get(u, j));
        gsl_vector_memcpy(up, u);
        up->data[j * up->stride] += h;
        f_eval(up, ctx, fp);
        gsl_vector_memcpy(up, u);
        up->data[j * up->stride] -= h;
        f_eval(up, ctx, fm);
        for (size_t i = 0; i < n; ++i) gsl_matrix_set(J, i, j, (gsl_vector_get(fp, i) - gsl_vector_get(fm, i)) / (2 * h));
    }
    gsl_vector_free(fp);
    gsl_vector_free(fm);
    gsl_vector_free(up);
    return GSL_SUCCESS;
}

/* chi2 of the weighted residuals at u (a refused run: FAILED_RESIDUAL each). */
static double cost(fit_ctx *c, const double *u)
{
    if (run_u(c, u) != 0) return (double)c->nres * FAILED_RESIDUAL * FAILED_RESIDUAL;
    double s = 0;
    for (long i = 0; i < c->nres; ++i) s += c->f[i] * c->f[i] * c->sw[i] * c->sw[i];
    return s;
}

/* Robust weights from the residuals at u, on a scale from their median
 * absolute value. Returns the largest change of a weight. */
static double reweight(fit_ctx *c, const double *u, jc_TrackFitLoss loss, double *scratch)
{
    if (run_u(c, u) != 0) return 0.0;
    for (long i = 0; i < c->nres; ++i) scratch[i] = fabs(c->f[i]);
    const double s = fmax(1.4826 * gsl_stats_median(scratch, 1, (size_t)c->nres), 1e-12);
    double change = 0.0;
    for (long i = 0; i < c->nres; ++i) {
        const double r = fabs(c->f[i]) / s;
        const double w = loss == JC_FIT_LOSS_HUBER ? (r <= HUBER_K ? 1.0 : HUBER_K / r) : 1.0 / (1.0 + pow(r / CAUCHY_C, 2));
        change = fmax(change, fabs(w - c->sw[i] * c->sw[i]));
        c->sw[i] = sqrt(w);
    }
    return change;
}

/* One pass of Levenberg-Marquardt from u (in place): at most max_iter
 * iterations, abandoned once its chi2 stays far above give_up (a start in
 * another valley: the search has a better one). The iterations. */
static int lm_pass(fit_ctx *c, gsl_multifit_nlinear_workspace *w, gsl_vector *uv, int max_iter, double give_up)
{
    const size_t n = (size_t)c->nres, p = (size_t)c->np;
    gsl_multifit_nlinear_fdf fdf = {f_eval, df_eval, NULL, n, p, c, 0, 0, 0};
    if (gsl_multifit_nlinear_init(uv, &fdf, w) != GSL_SUCCESS) return 0;
    int it = 0, info = 0;
    for (; it < max_iter; ++it) {
        const int st = gsl_multifit_nlinear_iterate(w);
        if (st != GSL_SUCCESS) break; /* no step lowers chi2 (GSL_ENOPROG): as far as it goes */
        report(c, ((double)c->begun - 1.0 + (double)(it + 1) / max_iter) / c->planned);
        if (c->stopped) {
            ++it;
            break;
        }
        if (gsl_multifit_nlinear_test(XTOL, GTOL, FTOL, &info, w) == GSL_SUCCESS && info != 0) {
            ++it;
            break;
        }
        if ((it + 1) % GIVE_UP_EVERY == 0 && isfinite(give_up)) {
            double chi2;
            gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &chi2);
            if (chi2 > GIVE_UP_FACTOR * give_up + (double)n) {
                ++it;
                break;
            }
        }
    }
    gsl_vector_memcpy(uv, gsl_multifit_nlinear_position(w));
    return it;
}

/* One descent from u (in place), robust passes included. The iterations. */
static int descend(fit_ctx *c, double *u, const jc_TrackFitOptions *o, double *scratch, double give_up)
{
    if (c->np == 0) return 0;
    ++c->begun;
    report(c, ((double)c->begun - 1.0) / c->planned);
    if (c->stopped) return 0;
    const size_t n = (size_t)c->nres, p = (size_t)c->np;
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm; /* no geodesic acceleration: its second derivative
                                             would come from a discontinuous model */
    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, n, p);
    if (!w) return 0;
    gsl_vector_view uv = gsl_vector_view_array(u, p);
    int iters = 0;
    const int passes = o->loss == JC_FIT_LOSS_LINEAR ? 1 : MAX_PASSES;
    /* Each descent from unit weights: its minimum's weights are its own. */
    for (long i = 0; i < c->nres; ++i) c->sw[i] = 1.0;
    for (int pass = 0; pass < passes && !c->stopped; ++pass) {
        iters += lm_pass(c, w, &uv.vector, o->max_iter, pass == 0 ? give_up : INFINITY);
        if (pass + 1 < passes && !c->stopped && reweight(c, u, o->loss, scratch) < 1e-3) break;
    }
    gsl_multifit_nlinear_free(w);
    return iters;
}

/* The covariance of u at u (JᵀJ)⁻¹, scaled by s2; 0, or -1. */
static int covariance_u(fit_ctx *c, const double *u, double s2, gsl_matrix *cu)
{
    const size_t n = (size_t)c->nres, p = (size_t)c->np;
    gsl_matrix *J = gsl_matrix_alloc(n, p);
    if (!J) return -1;
    gsl_vector_const_view uv = gsl_vector_const_view_array(u, p);
    if (df_eval(&uv.vector, c, J) != GSL_SUCCESS) {
        gsl_matrix_free(J);
        gsl_matrix_set_all(cu, NAN);
        return -1;
    }
    gsl_multifit_nlinear_covar(J, 1e-10, cu);
    gsl_matrix_scale(cu, s2);
    gsl_matrix_free(J);
    return 0;
}

/* The values' covariance C_v = T C_u Tᵀ, T = dv/du (differences of the
 * transform: cheap and smooth); sigmas and correlations. */
static void values_covariance(const fit_ctx *c, const double *u, const gsl_matrix *cu,
                              double *sigma, double corr[][JC_FIT_MAX_PARAMS])
{
    const int p = c->np;
    double T[JC_FIT_MAX_PARAMS][JC_FIT_MAX_PARAMS];
    double up[JC_FIT_MAX_PARAMS], um[JC_FIT_MAX_PARAMS], vp[JC_FIT_MAX_PARAMS], vm[JC_FIT_MAX_PARAMS];
    for (int j = 0; j < p; ++j) {
        const double h = 1e-6 * fmax(1.0, fabs(u[j]));
        memcpy(up, u, (size_t)p * sizeof *u);
        memcpy(um, u, (size_t)p * sizeof *u);
        up[j] += h;
        um[j] -= h;
        values_of(c, up, vp);
        values_of(c, um, vm);
        for (int i = 0; i < p; ++i) T[i][j] = (vp[i] - vm[i]) / (2 * h);
    }
    double cov[JC_FIT_MAX_PARAMS][JC_FIT_MAX_PARAMS];
    for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j) {
            double s = 0.0;
            for (int a = 0; a < p; ++a)
                for (int b = 0; b < p; ++b) s += T[i][a] * gsl_matrix_get(cu, (size_t)a, (size_t)b) * T[j][b];
            cov[i][j] = s;
        }
    for (int i = 0; i < p; ++i) sigma[i] = cov[i][i] > 0.0 ? sqrt(cov[i][i]) : NAN;
    for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j) corr[i][j] = cov[i][j] / (sigma[i] * sigma[j]);
}

/* ---- the search: a Latin hypercube screened, the best descended from ---- */

/* The dimensions screened: the bounded values, and θ0 and the mark's
 * angle when nothing in the video tells them. */
static int screened(const fit_ctx *c, int i)
{
    const jc_TrackFitKind k = c->param[i].kind;
    return bounded(c->param[i]) || k == JC_FIT_MARK_ANGLE || (k == JC_FIT_THETA0 && !c->t->has_mark);
}

typedef struct {
    double u[JC_FIT_MAX_PARAMS];
    double chi2;
} point;

static int cmp_point(const void *a, const void *b)
{
    const double x = ((const point *)a)->chi2, y = ((const point *)b)->chi2;
    return (x > y) - (x < y);
}

/* The Latin hypercube: point k's coordinate in dimension d is in stratum
 * perm_d(k) of N, at a Philox-drawn place in it. */
static void hypercube(const fit_ctx *c, const double *u0, int npts, uint64_t seed, point *pts)
{
    int *perm = malloc((size_t)npts * sizeof *perm);
    for (int k = 0; k < npts; ++k) memcpy(pts[k].u, u0, (size_t)c->np * sizeof *u0);
    if (!perm) return;
    for (int i = 0; i < c->np; ++i) {
        if (!screened(c, i)) continue;
        for (int k = 0; k < npts; ++k) perm[k] = k;
        for (int k = npts - 1; k > 0; --k) { /* Fisher-Yates */
            const int j = (int)(jc_random_uniform(seed, (uint64_t)i, (uint32_t)k) * (k + 1));
            const int tmp = perm[k];
            perm[k] = perm[j < k ? j : k];
            perm[j < k ? j : k] = tmp;
        }
        for (int k = 0; k < npts; ++k) {
            const double q = (perm[k] + jc_random_uniform(seed, 1000u + (uint64_t)i, (uint32_t)k)) / npts;
            if (bounded(c->param[i])) {
                pts[k].u[i] = logit(fmin(fmax(q, START_EDGE), 1.0 - START_EDGE));
            } else {
                pts[k].u[i] = -JC_TRACK_PI + 2.0 * JC_TRACK_PI * q;
            }
        }
    }
    free(perm);
}

/* Searches from u0 (the user's values): screens, descends, keeps the
 * minima sorted by chi2 into mins (at most cap). Returns how many. */
static int search(fit_ctx *c, const double *u0, const jc_TrackFitOptions *o, point *mins, int cap, jc_TrackFitResult *out,
                  double *scratch)
{
    int dims = 0;
    for (int i = 0; i < c->np; ++i) dims += screened(c, i);
    int npts = o->starts > 0 ? o->starts : 8 * dims + 8;
    if (o->starts <= 0) npts = npts < MIN_SCREEN ? MIN_SCREEN : npts > MAX_SCREEN ? MAX_SCREEN : npts;
    if (dims == 0) npts = 0;
    point *pts = calloc((size_t)npts + 1, sizeof *pts);
    if (!pts) return 0;
    memcpy(pts[0].u, u0, (size_t)c->np * sizeof *u0);
    hypercube(c, u0, npts, o->seed, pts + 1);
    for (int k = 0; k <= npts; ++k) pts[k].chi2 = cost(c, pts[k].u);
    out->screened = npts + 1;
    /* The user's point and the best screened ones. */
    const int want = o->descents > 0 ? o->descents : DEFAULT_DESCENTS;
    qsort(pts + 1, (size_t)npts, sizeof *pts, cmp_point);
    c->planned = want < npts + 1 ? want : npts + 1;
    if (c->planned > cap) c->planned = cap;
    int m = 0;
    for (int k = 0; k <= npts && m < want && m < cap && !c->stopped; ++k) {
        point q = pts[k];
        out->iterations += descend(c, q.u, o, scratch, m > 0 ? mins[0].chi2 : INFINITY);
        q.chi2 = cost(c, q.u);
        mins[m++] = q;
        /* The best so far first: the next descents give up against it. */
        for (int j = m - 1; j > 0 && mins[j].chi2 < mins[j - 1].chi2; --j) {
            const point tmp = mins[j];
            mins[j] = mins[j - 1];
            mins[j - 1] = tmp;
        }
        out->descents++;
    }
    free(pts);
    qsort(mins, (size_t)m, sizeof *mins, cmp_point);
    return m;
}

/* ---- the fit's results ---- */

/* The first lift-off's x for u; NaN without one. */
static double liftoff_x(fit_ctx *c, const double *u, double *t_s)
{
    if (run_u(c, u) != 0 || c->ts.sum.first_liftoff < 0) return NAN;
    if (t_s) *t_s = c->ts.sum.first_liftoff_state.t_s;
    /* In the video's frame, as the frames are. */
    jc_Setup s;
    jc_State start;
    jc_TrackFitFrame fr;
    apply(c, u, &s, &start, &fr);
    double x = c->ts.sum.first_liftoff_state.x_m - c->ts.shift_m, y = c->ts.sum.first_liftoff_state.y_m;
    jc_fit_to_video(&fr, &start, &x, &y, NULL, 1);
    return x;
}

/* The predicted first lift-off and its standard error by the delta method. */
static void predict_liftoff(fit_ctx *c, const double *u, const gsl_matrix *cu, jc_TrackFitResult *out)
{
    out->liftoff_x_m = liftoff_x(c, u, &out->liftoff_t_s);
    out->has_liftoff = isfinite(out->liftoff_x_m);
    out->liftoff_sigma_m = NAN;
    if (!out->has_liftoff) return;
    double g[JC_FIT_MAX_PARAMS], w[JC_FIT_MAX_PARAMS];
    for (int j = 0; j < c->np; ++j) {
        const double h = step_of(u[j]);
        memcpy(w, u, (size_t)c->np * sizeof *u);
        w[j] = u[j] + h;
        const double xp = liftoff_x(c, w, NULL);
        w[j] = u[j] - h;
        g[j] = (xp - liftoff_x(c, w, NULL)) / (2 * h);
    }
    double var = 0.0;
    for (int i = 0; i < c->np; ++i)
        for (int j = 0; j < c->np; ++j) var += g[i] * gsl_matrix_get(cu, (size_t)i, (size_t)j) * g[j];
    out->liftoff_sigma_m = var >= 0.0 ? sqrt(var) : NAN;
}

/* The index of a free value in the result's list. */
static int slot_of(const jc_TrackFitResult *r, jc_TrackFitParam p)
{
    for (int k = 0; k < r->count; ++k)
        if (jc_fit_param_same(r->param[k], p)) return k;
    return -1;
}

/* Flags the values the video does not determine; the one to hold for a
 * correlated pair is the less determined (sigma over range). Returns how many. */
static int flag_values(const fit_ctx *c, const double *v, const double *sigma, double corr[][JC_FIT_MAX_PARAMS],
                       jc_TrackFitFlag *flag, int *other, double *rho)
{
    const int kk = index_of(c, JC_FIT_MU_K);
    const double mu_k = kk >= 0 ? v[kk] : c->base.mu_kinetic;
    int flagged = 0;
    double rel[JC_FIT_MAX_PARAMS];
    for (int i = 0; i < c->np; ++i) {
        double lo, hi;
        range_of(c, i, mu_k, &lo, &hi);
        const double span = isfinite(hi - lo) && c->param[i].kind != JC_FIT_OMEGA0 ? hi - lo : INFINITY;
        rel[i] = isfinite(span) ? sigma[i] / span : 0.0;
        flag[i] = JC_FIT_DETERMINED;
        other[i] = -1;
        rho[i] = NAN;
        if (bounded(c->param[i]) && (v[i] - lo < EDGE * 1.01 * (hi - lo) || hi - v[i] < EDGE * 1.01 * (hi - lo)))
            flag[i] = JC_FIT_ON_BOUND;
        else if (!(sigma[i] > 0.0) || !isfinite(sigma[i]))
            flag[i] = JC_FIT_NO_EFFECT;
        else if (sigma[i] > span)
            flag[i] = JC_FIT_WIDER_THAN_RANGE;
    }
    for (int i = 0; i < c->np; ++i) {
        if (flag[i] != JC_FIT_DETERMINED) continue;
        for (int j = 0; j < c->np; ++j) {
            if (j == i || flag[j] != JC_FIT_DETERMINED) continue;
            const double r = corr[i][j];
            if (!(fabs(r) > CORRELATED)) continue;
            const int later = i > j; /* of two as little determined, the later one goes */
            const int drop = rel[i] > rel[j] || (rel[i] == rel[j] && later);
            if (drop) {
                flag[i] = JC_FIT_CORRELATED;
                other[i] = j;
                rho[i] = corr[i][j];
                break;
            }
        }
    }
    for (int i = 0; i < c->np; ++i) flagged += flag[i] != JC_FIT_DETERMINED;
    return flagged;
}

/* Holds the flagged values: at the bound a value sits on, else at its
 * starting value; the free list shrinks and u follows it. */
static void hold(fit_ctx *c, double *u, const double *v, const double *v0, const jc_TrackFitFlag *flag)
{
    double lo, hi;
    const int kk = index_of(c, JC_FIT_MU_K);
    const double mu_k = kk >= 0 ? v[kk] : c->base.mu_kinetic;
    int m = 0;
    double keep_v[JC_FIT_MAX_PARAMS];
    for (int i = 0; i < c->np; ++i) {
        if (flag[i] == JC_FIT_DETERMINED) {
            keep_v[m] = v[i];
            c->param[m++] = c->param[i];
            continue;
        }
        range_of(c, i, mu_k, &lo, &hi);
        double at = v0[i];
        if (flag[i] == JC_FIT_ON_BOUND) at = v[i] - lo < hi - v[i] ? lo : hi;
        /* mu_s on mu_k: no margin to slip, whatever mu_k becomes. */
        if (flag[i] == JC_FIT_ON_BOUND && c->param[i].kind == JC_FIT_MU_S && at == lo) c->mu_s_tied = 1;
        jc_fit_set(&c->base, &c->start0, &c->frame0, c->param[i], at);
    }
    /* A mu_s held below a free mu_k would break mu_k <= mu_s: apply() lifts it. */
    c->np = m;
    u_of(c, keep_v, u, EDGE);
}

/* chi2 along a held value's range, the others fitted at each point. */
static void profile(fit_ctx *c, jc_TrackFitParam p, const double *u_best, const jc_TrackFitOptions *o, double *xs, double *chi2,
                    double *scratch)
{
    double lo, hi, v[JC_FIT_MAX_PARAMS];
    jc_fit_range(&c->base, p, &lo, &hi);
    values_of(c, u_best, v);
    const int kk = index_of(c, JC_FIT_MU_K);
    if (p.kind == JC_FIT_MU_S) lo = kk >= 0 ? v[kk] : c->base.mu_kinetic; /* mu_s above mu_k */
    if (!isfinite(lo) || !isfinite(hi) || p.kind == JC_FIT_OMEGA0) {
        for (int k = 0; k < JC_FIT_PROFILE_POINTS; ++k) xs[k] = chi2[k] = NAN;
        return;
    }
    const jc_Setup base = c->base;
    const jc_State s0 = c->start0;
    const jc_TrackFitFrame fr0 = c->frame0;
    const int tied = c->mu_s_tied;
    c->mu_s_tied = 0; /* mu_s goes along its range, not with mu_k */
    jc_TrackFitOptions q = *o;
    q.loss = JC_FIT_LOSS_LINEAR;
    q.max_iter = o->max_iter < PROFILE_MAX_ITER ? o->max_iter : PROFILE_MAX_ITER;
    double v_prev[JC_FIT_MAX_PARAMS];
    for (int k = 0; k < JC_FIT_PROFILE_POINTS && !c->stopped; ++k) {
        xs[k] = lo + (hi - lo) * (k + 0.5) / JC_FIT_PROFILE_POINTS;
        jc_fit_set(&c->base, &c->start0, &c->frame0, p, xs[k]);
        /* From the best values, and from the previous point's (the
         * profile followed along its branch); the lower of the two, in u
         * as the ranges now are (mu_k's top is the held mu_s). */
        double u[JC_FIT_MAX_PARAMS], w[JC_FIT_MAX_PARAMS];
        u_of(c, v, u, EDGE);
        descend(c, u, &q, scratch, INFINITY);
        chi2[k] = cost(c, u);
        if (k > 0) {
            u_of(c, v_prev, w, EDGE);
            descend(c, w, &q, scratch, chi2[k]); /* given up once far above the first */
            const double from_prev = cost(c, w);
            if (from_prev < chi2[k]) chi2[k] = from_prev, memcpy(u, w, sizeof u);
        }
        values_of(c, u, v_prev);
        c->base = base, c->start0 = s0, c->frame0 = fr0;
    }
    c->mu_s_tied = tied;
}

/* Clear hops (above the threshold by 3 of their sigma) of the video and
 * the model in the window; a clear one with no hop of the other over its
 * frames is a disagreement. 1 when they agree; 0 with the first
 * disagreement's text in why. */
static int hops_agree(const fit_ctx *c, const jc_TrackFitResult *r, char *why, size_t len, int *n_video, int *n_model)
{
    const jc_Track *t = c->t;
    jc_TrackHops model;
    jc_track_find_hops(t->t_s + r->first, c->x, c->y, r->frames, t->radius_m, t->hop_threshold_m, &model);
    *n_video = *n_model = 0;
    int ok = 1;
    for (long k = 0; k < t->hops; ++k) {
        const jc_TrackHop *h = &t->hop[k];
        if (h->last < r->first || h->first >= r->first + r->frames || isnan(h->height_m)) continue;
        if (!(h->height_m - t->hop_threshold_m > CLEAR_HOP_SIGMAS * h->height_sigma_m)) continue;
        (*n_video)++;
        int seen = 0;
        for (int m = 0; m < model.hops && m < JC_TRACK_MAX_HOPS; ++m)
            seen |= model.first[m] + r->first <= h->last + 1 && model.last[m] + r->first + 1 >= h->first;
        if (!seen && ok) {
            snprintf(why, len, "the video shows a hop at t = %.3f s (%.1f +- %.1f mm) where the model does not",
                     t->t_s[h->first], h->height_m * 1e3, h->height_sigma_m * 1e3);
            ok = 0;
        }
    }
    for (int m = 0; m < model.hops && m < JC_TRACK_MAX_HOPS; ++m) {
        if (!(model.height_m[m] - t->hop_threshold_m > CLEAR_HOP_SIGMAS * t->sigma_m)) continue;
        (*n_model)++;
        int seen = 0;
        const long a = model.first[m] + r->first, b = model.last[m] + r->first;
        for (long k = 0; k < t->hops; ++k)
            seen |= t->hop[k].first <= b + 1 && t->hop[k].last + 1 >= a;
        /* A mark-only video cannot show a hop below its detection bound. */
        if (!seen && t->centre_source == JC_TRACK_CENTRE_FROM_MARK && model.height_m[m] < t->hop_threshold_m) seen = 1;
        if (!seen && ok) {
            snprintf(why, len, "the model hops at t = %.3f s (%.1f mm) where the video shows none",
                     t->t_s[a], model.height_m[m] * 1e3);
            ok = 0;
        }
    }
    return ok;
}

static void judge(fit_ctx *c, const double *u, jc_TrackFitResult *r)
{
    run_u(c, u);
    const char *which = "";
    r->runs_z = jc_track_residuals_runs_z(c->f, c->series, c->nres, &which);
    char hop_why[200] = "";
    int hops_measured, hops_model;
    const int hops_ok = hops_agree(c, r, hop_why, sizeof hop_why, &hops_measured, &hops_model);
    char why[3][220];
    int k = 0;
    if (r->chi2_dof > MISFIT_CHI2_DOF)
        snprintf(why[k++], sizeof why[0], "chi2/dof = %.3g at the %s noise of %.2f mm (at most %.0f expected)",
                 r->chi2_dof, r->noise_measured ? "measured" : "given", r->sigma_m * 1e3, MISFIT_CHI2_DOF);
    if (r->runs_z < MISFIT_RUNS_Z)
        snprintf(why[k++], sizeof why[0], "the residuals %s run in long stretches of one sign (runs test z = %.1f)",
                 which, r->runs_z);
    if (!hops_ok) snprintf(why[k++], sizeof why[0], "%s", hop_why);
    r->misfit = k > 0;
    if (!r->misfit) {
        snprintf(r->verdict, sizeof r->verdict, "the model describes this video: chi2/dof = %.3g, residuals "
                 "without runs (z = %.1f), %d hop(s) in both", r->chi2_dof, isfinite(r->runs_z) ? r->runs_z : 0.0,
                 hops_measured);
        return;
    }
    int used = snprintf(r->verdict, sizeof r->verdict, "the model does not describe this video: ");
    for (int i = 0; i < k && used < (int)sizeof r->verdict; ++i)
        used += snprintf(r->verdict + used, sizeof r->verdict - (size_t)used, "%s%s", i ? "; " : "", why[i]);
}

/* ---- setting up ---- */

void jc_fit_options_default(jc_TrackFitOptions *o)
{
    memset(o, 0, sizeof *o);
    o->loss = JC_FIT_LOSS_LINEAR;
    o->from_s = o->to_s = NAN;
    o->max_iter = 100;
    o->start = JC_TRACK_START_TRACKED;
    o->seed = 1;
    o->profiles = 1;
}

static int add_param(jc_TrackFitParam *list, int *n, jc_TrackFitParam p)
{
    for (int i = 0; i < *n; ++i)
        if (jc_fit_param_same(list[i], p)) return 0;
    if (*n == JC_FIT_MAX_PARAMS) return -1;
    list[(*n)++] = p;
    return 1;
}

static int prepare(fit_ctx *c, const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o,
                   const jc_State *refined, jc_TrackFitResult *out, char *err, size_t err_len)
{
    c->t = t;
    int st = jc_track_require("the track", t, JC_TRACK_NEED_CENTRE | JC_TRACK_NEED_INCLINE, err, err_len);
    if (st != JC_OK) return st;
    c->base = jc_track_setup(setup, t);
    c->base.incline_rad = t->incline_rad; /* the frames' incline frame */
    c->frame0.mark_angle_rad = o->mark_angle_rad;
    jc_track_window(t, o->from_s, o->to_s, &c->res.first, &c->res.count);
    if (c->res.count < 3) {
        snprintf(err, err_len, "the fit window holds %ld frame(s); at least 3 are needed", c->res.count);
        return JC_EINVAL;
    }
    jc_Model m;
    if ((st = jc_model_init(&m, &c->base, err, err_len)) != JC_OK) return st;
    const double sigma = o->sigma_m > 0.0 ? o->sigma_m : t->sigma_m;
    if (!(sigma > 0.0)) {
        snprintf(err, err_len, "the track gives no position noise; give it with --sigma");
        return JC_EINVAL;
    }
    c->res.t = t;
    c->res.sigma = sigma;
    const double r = m.body.radius_m;
    const long first = c->res.first;
    if (o->start == JC_TRACK_START_SETUP) {
        jc_track_start_setup(t, first, first + c->res.count, r, setup, &c->start0);
    } else if (refined) {
        c->start0 = *refined;
    } else {
        if (jc_track_start_estimate(t, first, START_SPAN, r, setup->theta0_rad, t->hop_threshold_m, &c->start0) != 0) {
            snprintf(err, err_len, "fewer than 3 frames to estimate the first tracked state from");
            return JC_EINVAL;
        }
        if (t->has_mark) c->start0.theta_rad += jc_track_mark_offset_rad(&m, o->mark_angle_rad);
    }
    /* The free list: the values asked for, then the start's. */
    int n = 0;
    for (int k = 0; k < o->free_count; ++k) add_param(c->param, &n, o->free[k]);
    const jc_TrackFitKind extra[5] = {JC_FIT_THETA0, JC_FIT_OMEGA0, JC_FIT_X0, JC_FIT_TILT, JC_FIT_SURFACE};
    for (int k = 0; k < 5; ++k) {
        if (k < 3 ? o->hold_start : o->hold_frame) continue;
        const jc_TrackFitParam p = {extra[k], -1};
        const int added = add_param(c->param, &n, p);
        if (added < 0) {
            snprintf(err, err_len, "more than %d values to fit", JC_FIT_MAX_PARAMS);
            return JC_EINVAL;
        }
        if (added > 0) out->start_value[n - 1] = 1;
    }
    c->np = n;
    out->count = n;
    memcpy(out->param, c->param, sizeof c->param);
    for (int k = 0; k < n; ++k) {
        out->initial[k] = jc_fit_get(&c->base, &c->start0, &c->frame0, c->param[k]);
        jc_fit_range(&c->base, c->param[k], &out->lo[k], &out->hi[k]);
    }
    const double a = t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? t->mark_radius_m : jc_track_mark_radius(t, &m);
    long marks = 0;
    for (long i = 0; i < c->res.count; ++i) marks += t->has_mark && isfinite(t->theta_rad[first + i]);
    c->res.mark_radius = marks > 0 || t->centre_source == JC_TRACK_CENTRE_FROM_MARK ? a : 0.0;
    c->nres = jc_track_residual_count(&c->res);
    if (c->nres <= c->np) {
        snprintf(err, err_len, "%ld residuals cannot fix %d free values", c->nres, c->np);
        return JC_EINVAL;
    }
    const size_t fr = (size_t)c->res.count, nr = (size_t)c->nres;
    c->x = malloc(fr * sizeof *c->x);
    c->y = malloc(fr * sizeof *c->y);
    c->th = malloc(fr * sizeof *c->th);
    c->sw = malloc(nr * sizeof *c->sw);
    c->f = malloc(nr * sizeof *c->f);
    c->series = malloc(nr);
    if (!c->x || !c->y || !c->th || !c->sw || !c->f || !c->series || jc_track_sim_init(&c->ts) != 0) {
        snprintf(err, err_len, "out of memory");
        return JC_ENOMEM;
    }
    for (long i = 0; i < c->nres; ++i) c->sw[i] = 1.0;
    c->ts.shift_m = jc_track_sim_shift(t);
    out->first = first;
    out->frames = c->res.count;
    out->sigma_m = sigma;
    out->noise_measured = !(o->sigma_m > 0.0);
    out->mark_radius_m = c->res.mark_radius;
    return JC_OK;
}

static void release(fit_ctx *c)
{
    free(c->x);
    free(c->y);
    free(c->th);
    free(c->sw);
    free(c->f);
    free(c->series);
    jc_track_sim_free(&c->ts);
}

/* The path's and the mark angle's RMS at u. */
static void rms(fit_ctx *c, const double *u, jc_TrackFitResult *out)
{
    run_u(c, u);
    for (long i = 0; i < c->res.count; ++i) c->th[i] -= c->res.mark_offset; /* G's angle to the mark's */
    jc_track_misfit(c->t, c->res.first, c->res.count, c->x, c->y, c->th, &out->rms_path_m, NULL,
                    &out->rms_theta_rad);
}

/* The estimate at u, whose chi2 is given: the covariance of u in *cv (a
 * view of cu, np x np), scaled by chi2/dof when the noise was measured;
 * the values, their sigmas and correlations. Returns the scale. */
static double estimate(fit_ctx *c, const double *u, double chi2, int noise_measured, gsl_matrix *cu,
                       gsl_matrix_view *cv, double *v, double *sigma, double corr[][JC_FIT_MAX_PARAMS])
{
    const double s2 = noise_measured ? chi2 / (double)(c->nres - c->np) : 1.0;
    const size_t p = (size_t)(c->np > 0 ? c->np : 1);
    *cv = gsl_matrix_submatrix(cu, 0, 0, p, p);
    if (c->np > 0) {
        covariance_u(c, u, s2, &cv->matrix);
        values_of(c, u, v);
        values_covariance(c, u, &cv->matrix, sigma, corr);
    }
    return s2;
}

static int solve(fit_ctx *c, const jc_TrackFitOptions *o, jc_TrackFitResult *out, char *err, size_t err_len)
{
    const size_t p_all = (size_t)c->np;
    double *scratch = malloc((size_t)c->nres * sizeof *scratch);
    gsl_matrix *cu = gsl_matrix_alloc(p_all, p_all);
    point mins[DEFAULT_DESCENTS * 4 + 1];
    if (!scratch || !cu) {
        free(scratch);
        gsl_matrix_free(cu);
        snprintf(err, err_len, "out of memory");
        return JC_ENOMEM;
    }
    /* The stages' parts of the fit's progress: the search most of it. */
    const double *part = o->start_window ? START_WINDOW_PARTS : FIT_PARTS;
    double v0[JC_FIT_MAX_PARAMS], u[JC_FIT_MAX_PARAMS], v[JC_FIT_MAX_PARAMS], sigma[JC_FIT_MAX_PARAMS];
    double corr[JC_FIT_MAX_PARAMS][JC_FIT_MAX_PARAMS];
    for (int i = 0; i < c->np; ++i) v0[i] = jc_fit_get(&c->base, &c->start0, &c->frame0, c->param[i]);
    u_of(c, v0, u, START_EDGE);
    const int cap = (int)(sizeof mins / sizeof mins[0]);
    stage_begin(c, o->start_window ? "the start alone" : "descents from the best start points", part[0], part[1],
                DEFAULT_DESCENTS);
    int nm = search(c, u, o, mins, cap, out, scratch);
    if (nm == 0) {
        mins[0].chi2 = cost(c, u);
        memcpy(mins[0].u, u, sizeof u);
        nm = 1;
    }
    memcpy(u, mins[0].u, sizeof u);
    /* The best minimum's own robust weights (the last descent left its own). */
    if (o->loss != JC_FIT_LOSS_LINEAR) out->iterations += descend(c, u, o, scratch, INFINITY);
    if (c->stopped) goto stopped;
    /* Scale: chi2/dof when the noise was measured. */
    double chi2 = cost(c, u);
    gsl_matrix_view cv;
    const double s2 = estimate(c, u, chi2, out->noise_measured, cu, &cv, v, sigma, corr);
    /* The minima that compete with the best: within the chi2 threshold for
     * the free values' count, and apart from it by more than 2 sigma. */
    out->delta_chi2 = gsl_cdf_chisq_Qinv(0.05, (double)c->np) * fmax(1.0, s2);
    out->minima = 0;
    for (int k = 0; k < nm && out->minima < JC_FIT_MAX_MINIMA; ++k) {
        if (mins[k].chi2 - mins[0].chi2 > out->delta_chi2) break;
        double vk[JC_FIT_MAX_PARAMS];
        values_of(c, mins[k].u, vk);
        /* Apart: by more than 2 sigma in a value whose sigma is known (one
         * the residuals do not see tells no minima apart). */
        int apart = k == 0;
        for (int i = 0; i < c->np && !apart; ++i)
            apart = isfinite(sigma[i]) && fabs(vk[i] - v[i]) > 2.0 * sigma[i];
        for (int j = 0; j < out->minima && apart && k > 0; ++j) {
            int same = 1;
            for (int i = 0; i < c->np && same; ++i)
                same = !isfinite(sigma[i]) ||
                       fabs(vk[i] - out->minimum[j].value[slot_of(out, c->param[i])]) <= 2.0 * sigma[i];
            if (same) apart = 0;
        }
        if (!apart) continue;
        jc_TrackFitMinimum *mm = &out->minimum[out->minima++];
        for (int i = 0; i < out->count; ++i) mm->value[i] = out->initial[i];
        for (int i = 0; i < c->np; ++i) mm->value[slot_of(out, c->param[i])] = vk[i];
        mm->chi2 = mins[k].chi2;
    }
    /* A bounded value the descents left near a bound (its transform makes
     * the bound a limit they only approach) is put on it, the others fitted
     * again, when chi2 is lower there: the flags then hold it there. */
    int snapped = 0, near_bound = 0;
    for (int i = 0; i < c->np; ++i) near_bound += bounded(c->param[i]);
    stage_begin(c, "values near a bound tried on it", part[1], part[2], near_bound);
    for (int i = 0; i < c->np && !c->stopped; ++i) {
        if (!bounded(c->param[i])) continue;
        const double q = sigmoid(u[i]);
        if (q > SNAP_NEAR && q < 1.0 - SNAP_NEAR) continue;
        double us[JC_FIT_MAX_PARAMS];
        memcpy(us, u, sizeof us);
        us[i] = logit(q < 0.5 ? 0.5 * EDGE : 1.0 - 0.5 * EDGE);
        out->iterations += descend(c, us, o, scratch, INFINITY);
        const double at_bound = cost(c, us);
        if (at_bound < chi2 - 1e-9 * (1.0 + chi2)) { /* better, not just as good: a value that changes nothing stays */
            memcpy(u, us, sizeof us);
            chi2 = at_bound;
            snapped = 1;
        }
    }
    if (c->stopped) goto stopped;
    if (snapped) estimate(c, u, chi2, out->noise_measured, cu, &cv, v, sigma, corr);
    /* What the video does not determine: held, and the rest fitted again. */
    stage_begin(c, "fitted again without the values not determined", part[2], part[3], FLAG_ROUNDS);
    for (int round = 0; round < FLAG_ROUNDS && c->np > 0 && !c->stopped; ++round) {
        jc_TrackFitFlag flag[JC_FIT_MAX_PARAMS];
        int other[JC_FIT_MAX_PARAMS];
        double rho[JC_FIT_MAX_PARAMS];
        if (flag_values(c, v, sigma, corr, flag, other, rho) == 0) break;
        double v_init[JC_FIT_MAX_PARAMS];
        for (int i = 0; i < c->np; ++i) {
            const int s = slot_of(out, c->param[i]);
            v_init[i] = out->initial[s];
            if (flag[i] == JC_FIT_DETERMINED) continue;
            out->flag[s] = flag[i];
            out->value[s] = v[i];
            out->sigma[s] = sigma[i];
            out->other[s] = other[i] >= 0 ? slot_of(out, c->param[other[i]]) : -1;
            out->rho[s] = rho[i];
        }
        jc_TrackFitParam held[JC_FIT_MAX_PARAMS];
        int nheld = 0;
        for (int i = 0; i < c->np; ++i)
            if (flag[i] != JC_FIT_DETERMINED) held[nheld++] = c->param[i];
        hold(c, u, v, v_init, flag);
        for (int h = 0; h < nheld; ++h) out->value[slot_of(out, held[h])] =
            jc_fit_get(&c->base, &c->start0, &c->frame0, held[h]);
        out->iterations += descend(c, u, o, scratch, INFINITY);
        chi2 = cost(c, u);
        estimate(c, u, chi2, out->noise_measured, cu, &cv, v, sigma, corr);
    }
    if (c->stopped) goto stopped;
    /* The values fitted at the end, and the correlations between them. */
    for (int i = 0; i < out->count; ++i)
        for (int j = 0; j < out->count; ++j) out->corr[i][j] = i == j ? 1.0 : NAN;
    for (int i = 0; i < c->np; ++i) {
        const int s = slot_of(out, c->param[i]);
        out->value[s] = v[i];
        out->sigma[s] = sigma[i];
        for (int j = 0; j < c->np; ++j) out->corr[s][slot_of(out, c->param[j])] = corr[i][j];
    }
    out->residuals = c->nres;
    out->chi2 = chi2;
    out->dof = c->nres - c->np;
    out->chi2_dof = chi2 / (double)out->dof;
    apply(c, u, &out->setup, &out->start, &out->frame);
    const int kt = index_of(c, JC_FIT_TILT);
    out->incline_sigma_rad = tilt_tilts_gravity(c) && kt >= 0 ? sigma[kt] : 0.0;
    out->setup.ramp_length_m -= JC_TRACK_RAMP_MARGIN_M;
    if (!o->start_window) {
        if (c->np > 0) predict_liftoff(c, u, &cv.matrix, out);
        else {
            out->liftoff_x_m = liftoff_x(c, u, &out->liftoff_t_s);
            out->has_liftoff = isfinite(out->liftoff_x_m);
            out->liftoff_sigma_m = NAN;
        }
        rms(c, u, out);
        judge(c, u, out);
    }
    /* Profiles of the held values' chi2 along their ranges. */
    int held = 0, profiles = 0;
    for (int k = 0; k < out->count; ++k) held += out->flag[k] != JC_FIT_DETERMINED;
    for (int k = 0; o->profiles && !o->start_window && k < out->count && !c->stopped; ++k) {
        if (out->flag[k] == JC_FIT_DETERMINED) continue;
        char name[48];
        jc_fit_param_name(&c->base, out->param[k], name, sizeof name);
        snprintf(c->stage_text, sizeof c->stage_text, "chi2 profile of %s (%d descents)", name,
                 2 * JC_FIT_PROFILE_POINTS - 1);
        const double span = (part[4] - part[3]) / held;
        stage_begin(c, c->stage_text, part[3] + span * profiles, part[3] + span * (profiles + 1),
                    2 * JC_FIT_PROFILE_POINTS - 1);
        profiles++;
        profile(c, out->param[k], u, o, out->profile_x[k], out->profile_chi2[k], scratch);
        out->profiled[k] = isfinite(out->profile_x[k][0]);
    }
    if (c->stopped) goto stopped;
    free(scratch);
    gsl_matrix_free(cu);
    return JC_OK;
stopped:
    free(scratch);
    gsl_matrix_free(cu);
    snprintf(err, err_len, "stopped (the progress callback asked)");
    return JC_ESTOPPED;
}

const char *jc_fit_flag_text(jc_TrackFitFlag f)
{
    switch (f) {
    case JC_FIT_DETERMINED: return "determined";
    case JC_FIT_ON_BOUND: return "it sits on a bound of its range (the best fit is there or beyond)";
    case JC_FIT_WIDER_THAN_RANGE: return "its standard error exceeds its range";
    case JC_FIT_CORRELATED: return "it moves with another value";
    case JC_FIT_NO_EFFECT: return "the residuals do not change with it";
    }
    return "?";
}

const char *jc_fit_loss_name(jc_TrackFitLoss loss)
{
    switch (loss) {
    case JC_FIT_LOSS_LINEAR: return "linear";
    case JC_FIT_LOSS_HUBER: return "huber";
    case JC_FIT_LOSS_CAUCHY: return "cauchy";
    }
    return "?";
}

int jc_fit_loss_parse(const char *name, jc_TrackFitLoss *out)
{
    if (strcmp(name, "linear") == 0) *out = JC_FIT_LOSS_LINEAR;
    else if (strcmp(name, "huber") == 0) *out = JC_FIT_LOSS_HUBER;
    else if (strcmp(name, "cauchy") == 0) *out = JC_FIT_LOSS_CAUCHY;
    else return JC_EINVAL;
    return JC_OK;
}

int jc_fit_options_check(const jc_Setup *setup, const jc_TrackFitOptions *o, char *err, size_t err_len)
{
    if (!(o->max_iter > 0)) {
        snprintf(err, err_len, "the iteration limit must be positive");
        return JC_EINVAL;
    }
    if (o->free_count < 0 || o->free_count > JC_FIT_MAX_PARAMS) {
        snprintf(err, err_len, "%d values to free (allowed: 0 to %d)", o->free_count, JC_FIT_MAX_PARAMS);
        return JC_EINVAL;
    }
    for (int k = 0; k < o->free_count; ++k)
        if (jc_fit_param_check(setup, o->free[k]) != JC_OK) {
            snprintf(err, err_len, "value %d to free (kind %d, part %d) is not one the setup's body has", k,
                     (int)o->free[k].kind, o->free[k].part);
            return JC_EINVAL;
        }
    if (o->loss != JC_FIT_LOSS_LINEAR && o->loss != JC_FIT_LOSS_HUBER && o->loss != JC_FIT_LOSS_CAUCHY) {
        snprintf(err, err_len, "loss %d (allowed: linear, huber, cauchy)", (int)o->loss);
        return JC_EINVAL;
    }
    if (o->start != JC_TRACK_START_TRACKED && o->start != JC_TRACK_START_SETUP) {
        snprintf(err, err_len, "start kind %d (allowed: tracked, setup)", (int)o->start);
        return JC_EINVAL;
    }
    return JC_OK;
}

int jc_track_fit_solve(const jc_Setup *setup, const jc_Track *t, const jc_TrackFitOptions *o,
                       const jc_SimOptions *sim, const jc_State *refined, const jc_TrackFitSpan *span,
                       jc_TrackFitResult *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    int rc = jc_fit_options_check(setup, o, err, err_len);
    if (rc != JC_OK) return rc;
    fit_ctx c;
    memset(&c, 0, sizeof c);
    c.sim = sim;
    if (span) c.span = *span;
    rc = prepare(&c, setup, t, o, refined, out, err, err_len);
    if (rc == JC_OK) rc = solve(&c, o, out, err, err_len);
    release(&c);
    return rc;
}
