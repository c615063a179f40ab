/* Least squares of the model against a track (GSL's gsl_multifit_nlinear,
 * Levenberg-Marquardt trust region). The free values live in an
 * unconstrained space u: mu_s = exp(u) (>= 0), mu_k = mu_s sigmoid(u)
 * (0 <= mu_k <= mu_s), e = sigmoid(u) (0 <= e <= 1); theta0, omega0 and x0
 * (the start at the first frame fitted) as they are. The model is
 * discontinuous in its values where its sequence of events changes, so the
 * Jacobian is by central differences with steps far above the simulator's
 * own error (1e-11) and far below the values' uncertainties. */
#include "track_fit.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define START_SPAN 7
#define HOP_SIGMAS 5.0
#define HOP_MIN_M 1e-4
/* Central-difference step in u, relative to max(1, |u|). */
#define JAC_STEP 1e-5
/* A run the model refuses (a start off the ramp) counts as this many sigma
 * per residual: the trust region then rejects the step. */
#define FAILED_RESIDUAL 1e4
#define MAX_PASSES 10            /* robust reweighting passes */
#define HUBER_K 1.345            /* 95 % efficiency at the normal */
#define CAUCHY_C 2.385
#define SIGMOID_EDGE 1e-3        /* initial values at a bound start this far inside */

static const char *const names[CLI_FIT_PARAMS] = {"mu_s", "mu_k", "restitution", "theta0", "omega0", "x0"};

const char *cli_fit_param_name(cli_FitParam p) { return p < CLI_FIT_PARAMS ? names[p] : "?"; }

int cli_fit_parse_free(const char *text, unsigned *mask, char *err, size_t err_len)
{
    *mask = 0;
    const char *p = text;
    while (*p) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        int found = -1;
        for (int k = 0; k < CLI_FIT_PARAMS; ++k)
            if (strlen(names[k]) == len && strncmp(p, names[k], len) == 0) found = k;
        if (found < 0) {
            snprintf(err, err_len, "--free '%s': '%.*s' is not a value the fit can free (allowed: "
                     "mu_s, mu_k, restitution, theta0, omega0, x0)", text, (int)(len > 40 ? 40 : len), p);
            return -1;
        }
        if (*mask & (1u << found)) {
            snprintf(err, err_len, "--free '%s': %s is named twice", text, names[found]);
            return -1;
        }
        *mask |= 1u << found;
        if (!comma) break;
        p = comma + 1;
        if (!*p) break;
    }
    if (*mask == 0) {
        snprintf(err, err_len, "--free '%s' names no value (allowed: mu_s, mu_k, restitution, theta0, omega0, x0)",
                 text);
        return -1;
    }
    return 0;
}

int cli_fit_parse_loss(const char *text, cli_FitLoss *out)
{
    if (strcmp(text, "linear") == 0) *out = CLI_LOSS_LINEAR;
    else if (strcmp(text, "huber") == 0) *out = CLI_LOSS_HUBER;
    else if (strcmp(text, "cauchy") == 0) *out = CLI_LOSS_CAUCHY;
    else return -1;
    return 0;
}

const char *cli_fit_stop_text(cli_FitStop s)
{
    switch (s) {
    case CLI_FIT_STOP_STEP: return "the step became small (converged)";
    case CLI_FIT_STOP_GRADIENT: return "the gradient became small (converged)";
    case CLI_FIT_STOP_ITERATIONS: return "the iteration limit was reached (not converged)";
    case CLI_FIT_STOP_NO_PROGRESS: return "no step lowered the residual (stalled)";
    }
    return "?";
}

typedef struct {
    const cli_Track *t;
    const jc_SimOptions *sim;
    jc_Setup base;
    jc_State start0;          /* the start before the fit: estimated or the setup's */
    double value0[CLI_FIT_PARAMS]; /* every value, SI: the fixed ones stay */
    int np;
    cli_FitParam param[CLI_FIT_PARAMS];
    long first, count, nres;
    double sigma;             /* metres per sigma */
    double mark_radius;       /* the mark's distance from C; 0 without a mark */
    double mark_offset;
    double *x, *y, *th, *sw;  /* the run at the frames; sqrt of the robust weights */
    cli_TrackSim ts;
} fit_ctx;

static double sigmoid(double u) { return 1.0 / (1.0 + exp(-u)); }
static double logit(double p) { return log(p / (1.0 - p)); }

static int is_free(const fit_ctx *c, cli_FitParam p)
{
    for (int k = 0; k < c->np; ++k)
        if (c->param[k] == p) return k;
    return -1;
}

/* u -> every value (SI). */
static void values_of(const fit_ctx *c, const double *u, double *v)
{
    memcpy(v, c->value0, sizeof c->value0);
    const int ks = is_free(c, CLI_FIT_MU_S), kk = is_free(c, CLI_FIT_MU_K);
    if (ks >= 0 && kk >= 0) {
        v[CLI_FIT_MU_S] = exp(u[ks]);
        v[CLI_FIT_MU_K] = v[CLI_FIT_MU_S] * sigmoid(u[kk]);
    } else if (ks >= 0) {
        v[CLI_FIT_MU_S] = v[CLI_FIT_MU_K] + exp(u[ks]);
    } else if (kk >= 0) {
        v[CLI_FIT_MU_K] = v[CLI_FIT_MU_S] * sigmoid(u[kk]);
    }
    for (int k = 0; k < c->np; ++k) {
        switch (c->param[k]) {
        case CLI_FIT_RESTITUTION: v[CLI_FIT_RESTITUTION] = sigmoid(u[k]); break;
        case CLI_FIT_THETA0:
        case CLI_FIT_OMEGA0:
        case CLI_FIT_X0: v[c->param[k]] = u[k]; break;
        default: break;
        }
    }
}

/* Every value -> u (initial values at a bound moved just inside it). */
static void u_of(const fit_ctx *c, const double *v, double *u)
{
    const int ks = is_free(c, CLI_FIT_MU_S), kk = is_free(c, CLI_FIT_MU_K);
    const double ms = fmax(v[CLI_FIT_MU_S], 1e-6);
    const double ratio = fmin(fmax(v[CLI_FIT_MU_K] / ms, SIGMOID_EDGE), 1.0 - SIGMOID_EDGE);
    if (ks >= 0) u[ks] = kk >= 0 ? log(ms) : log(fmax(v[CLI_FIT_MU_S] - v[CLI_FIT_MU_K], SIGMOID_EDGE * ms));
    if (kk >= 0) u[kk] = logit(ratio);
    for (int k = 0; k < c->np; ++k) {
        const cli_FitParam p = c->param[k];
        if (p == CLI_FIT_RESTITUTION)
            u[k] = logit(fmin(fmax(v[p], SIGMOID_EDGE), 1.0 - SIGMOID_EDGE));
        else if (p == CLI_FIT_THETA0 || p == CLI_FIT_OMEGA0 || p == CLI_FIT_X0)
            u[k] = v[p];
    }
}

/* The setup and start that values describe. */
static void setup_of(const fit_ctx *c, const double *v, jc_Setup *s, jc_State *start)
{
    *s = c->base;
    s->mu_static = v[CLI_FIT_MU_S];
    s->mu_kinetic = fmin(v[CLI_FIT_MU_K], v[CLI_FIT_MU_S]);
    s->restitution = v[CLI_FIT_RESTITUTION];
    s->ramp_length_m += CLI_TRACK_RAMP_MARGIN_M;
    *start = c->start0;
    start->theta_rad = v[CLI_FIT_THETA0];
    start->omega_radps = v[CLI_FIT_OMEGA0];
    start->x_m = v[CLI_FIT_X0];
    if (start->y_m <= s->body.radius_m) start->vx_mps = s->body.radius_m * start->omega_radps; /* rolling */
    s->theta0_rad = start->theta_rad;
    s->omega0_radps = start->omega_radps;
}

/* Runs the model for u into c->x, y, th; 0, or -1 when the model refuses. */
static int run_u(fit_ctx *c, const double *u, jc_RunSummary *sum)
{
    double v[CLI_FIT_PARAMS];
    values_of(c, u, v);
    jc_Setup s;
    jc_State start;
    setup_of(c, v, &s, &start);
    jc_Model m;
    char err[256];
    if (jc_model_init(&m, &s, err, sizeof err) != JC_OK) return -1;
    if (cli_track_sim_run(&c->ts, &m, &start, c->sim, c->t->t_s + c->first, c->count, c->x, c->y, c->th, err,
                          sizeof err) != 0)
        return -1;
    if (sum) *sum = c->ts.sum;
    return 0;
}

/* Residuals in units of sigma, unweighted: x, y per frame, then the mark
 * where it was tracked. The mark's angle is not compared alone: it was
 * measured from the tracked centre, so its error holds the centre's; the
 * mark's own displacement across its radius, a dth + (dx cos th - dy sin th)
 * (the mark's position error along (cos th, -sin th)), is independent of
 * the centre's residuals, with the noise sigma of one tracked point. */
static void raw_residuals(const fit_ctx *c, double *f)
{
    const cli_Track *t = c->t;
    long k = 0;
    for (long i = 0; i < c->count; ++i) {
        const long j = c->first + i;
        f[k++] = (t->x_m[j] - c->x[i]) / c->sigma;
        f[k++] = (t->y_m[j] - c->y[i]) / c->sigma;
    }
    if (c->mark_radius > 0.0)
        for (long i = 0; i < c->count; ++i) {
            const long j = c->first + i;
            const double th = t->theta_rad[j];
            if (!isfinite(th)) continue;
            const double across = c->mark_radius * (th - (c->th[i] - c->mark_offset)) +
                                  (t->x_m[j] - c->x[i]) * cos(th) - (t->y_m[j] - c->y[i]) * sin(th);
            f[k++] = across / c->sigma;
        }
}

static int f_eval(const gsl_vector *u, void *ctx, gsl_vector *f)
{
    fit_ctx *c = ctx;
    if (run_u(c, u->data, NULL) != 0) {
        gsl_vector_set_all(f, FAILED_RESIDUAL);
        return GSL_SUCCESS;
    }
    raw_residuals(c, f->data);
    for (long i = 0; i < c->nres; ++i) f->data[i * f->stride] *= c->sw[i];
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

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Robust weights from the residuals at u, on a scale from their median
 * absolute value (a track's sigma is a pixel, which may not be its noise).
 * Returns the largest change of a weight. */
static double reweight(fit_ctx *c, const double *u, cli_FitLoss loss, double *scratch)
{
    if (run_u(c, u, NULL) != 0) return 0.0;
    raw_residuals(c, scratch);
    double *a = scratch + c->nres;
    for (long i = 0; i < c->nres; ++i) a[i] = fabs(scratch[i]);
    qsort(a, (size_t)c->nres, sizeof *a, cmp_double);
    const double s = fmax(1.4826 * a[c->nres / 2], 1e-12);
    double change = 0.0;
    for (long i = 0; i < c->nres; ++i) {
        const double r = fabs(scratch[i]) / s;
        const double w = loss == CLI_LOSS_HUBER ? (r <= HUBER_K ? 1.0 : HUBER_K / r) : 1.0 / (1.0 + pow(r / CAUCHY_C, 2));
        const double sw = sqrt(w);
        change = fmax(change, fabs(sw * sw - c->sw[i] * c->sw[i]));
        c->sw[i] = sw;
    }
    return change;
}

static int prepare(fit_ctx *c, const jc_Setup *setup, const cli_Track *t, const cli_FitOptions *o, char *err,
                   size_t err_len)
{
    c->t = t;
    c->base = *setup;
    cli_track_window(t, o->from_s, o->to_s, &c->first, &c->count);
    if (c->count < 3) {
        snprintf(err, err_len, "the fit window holds %ld frame(s); at least 3 are needed", c->count);
        return -1;
    }
    jc_Model m;
    if (cli_track_model(setup, &m, err, err_len) != 0) return -1;
    c->sigma = o->sigma_m > 0.0 ? o->sigma_m : t->sigma_m;
    if (!(c->sigma > 0.0)) {
        snprintf(err, err_len, "the track gives no position noise; give it with --sigma");
        return -1;
    }
    const double r = m.body.radius_m, thr = fmax(HOP_SIGMAS * c->sigma, HOP_MIN_M);
    c->mark_offset = cli_track_mark_offset_rad(&m);
    if (o->start == CLI_START_SETUP) {
        memset(&c->start0, 0, sizeof c->start0);
        c->start0.t_s = t->t_s[c->first];
        c->start0.x_m = t->x_m[c->first];
        c->start0.y_m = r;
        c->start0.theta_rad = setup->theta0_rad;
        c->start0.omega_radps = setup->omega0_radps;
    } else {
        if (cli_track_start_estimate(t, c->first, START_SPAN, r, setup->theta0_rad, thr, &c->start0) != 0) {
            snprintf(err, err_len, "fewer than 3 frames to estimate the first tracked state from");
            return -1;
        }
        if (t->has_mark) c->start0.theta_rad += c->mark_offset;
    }
    c->value0[CLI_FIT_MU_S] = setup->mu_static;
    c->value0[CLI_FIT_MU_K] = setup->mu_kinetic;
    c->value0[CLI_FIT_RESTITUTION] = setup->restitution;
    c->value0[CLI_FIT_THETA0] = c->start0.theta_rad;
    c->value0[CLI_FIT_OMEGA0] = c->start0.omega_radps;
    c->value0[CLI_FIT_X0] = c->start0.x_m;
    c->np = 0;
    for (int k = 0; k < CLI_FIT_PARAMS; ++k)
        if (o->free_mask & (1u << k)) c->param[c->np++] = (cli_FitParam)k;
    long marks = 0;
    for (long i = 0; i < c->count; ++i) marks += t->has_mark && isfinite(t->theta_rad[c->first + i]);
    const double a = cli_track_mark_radius(t, &m);
    c->mark_radius = marks > 0 ? a : 0.0;
    c->nres = 2 * c->count + marks;
    if (c->nres <= c->np) {
        snprintf(err, err_len, "%ld residuals cannot fix %d free values", c->nres, c->np);
        return -1;
    }
    const size_t n = (size_t)c->count;
    c->x = malloc(n * sizeof *c->x);
    c->y = malloc(n * sizeof *c->y);
    c->th = malloc(n * sizeof *c->th);
    c->sw = malloc((size_t)c->nres * sizeof *c->sw);
    if (!c->x || !c->y || !c->th || !c->sw || cli_track_sim_init(&c->ts) != 0) {
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    for (long i = 0; i < c->nres; ++i) c->sw[i] = 1.0;
    c->ts.shift_m = cli_track_sim_shift(t);
    return 0;
}

static void release(fit_ctx *c)
{
    free(c->x);
    free(c->y);
    free(c->th);
    free(c->sw);
    cli_track_sim_free(&c->ts);
}

/* The values' covariance: C_v = T C_u T' with T = dv/du (by differences of
 * the transform, which is cheap and smooth). */
static void values_covariance(const fit_ctx *c, const double *u, const gsl_matrix *cu, cli_FitResult *out)
{
    const int p = c->np;
    double T[CLI_FIT_PARAMS][CLI_FIT_PARAMS];
    double up[CLI_FIT_PARAMS], um[CLI_FIT_PARAMS], vp[CLI_FIT_PARAMS], vm[CLI_FIT_PARAMS];
    for (int j = 0; j < p; ++j) {
        const double h = 1e-6 * fmax(1.0, fabs(u[j]));
        memcpy(up, u, (size_t)p * sizeof *u);
        memcpy(um, u, (size_t)p * sizeof *u);
        up[j] += h;
        um[j] -= h;
        values_of(c, up, vp);
        values_of(c, um, vm);
        for (int i = 0; i < p; ++i) T[i][j] = (vp[c->param[i]] - vm[c->param[i]]) / (2 * h);
    }
    for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j) {
            double s = 0.0;
            for (int a = 0; a < p; ++a)
                for (int b = 0; b < p; ++b) s += T[i][a] * gsl_matrix_get(cu, (size_t)a, (size_t)b) * T[j][b];
            out->cov[i][j] = s;
        }
    for (int i = 0; i < p; ++i) {
        out->sigma[i] = out->cov[i][i] > 0.0 ? sqrt(out->cov[i][i]) : NAN;
        if (!(out->cov[i][i] > 0.0)) out->singular = 1;
    }
    for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j) out->corr[i][j] = out->cov[i][j] / (out->sigma[i] * out->sigma[j]);
}

/* The first lift-off's x for u; NaN without one. */
static double liftoff_x(fit_ctx *c, const double *u, double *t_s)
{
    jc_RunSummary sum;
    if (run_u(c, u, &sum) != 0 || sum.first_liftoff < 0) return NAN;
    if (t_s) *t_s = sum.first_liftoff_state.t_s;
    return sum.first_liftoff_state.x_m - c->ts.shift_m;
}

/* Predicted first lift-off and its standard error by the delta method:
 * var = g' C_u g with g its gradient in u (central differences). */
static void predict_liftoff(fit_ctx *c, const double *u, const gsl_matrix *cu, cli_FitResult *out)
{
    out->liftoff_x_m = liftoff_x(c, u, &out->liftoff_t_s);
    out->has_liftoff = isfinite(out->liftoff_x_m);
    out->liftoff_sigma_m = NAN;
    if (!out->has_liftoff) return;
    double g[CLI_FIT_PARAMS], w[CLI_FIT_PARAMS];
    for (int j = 0; j < c->np; ++j) {
        const double h = step_of(u[j]);
        memcpy(w, u, (size_t)c->np * sizeof *u);
        w[j] = u[j] + h;
        const double xp = liftoff_x(c, w, NULL);
        w[j] = u[j] - h;
        const double xm = liftoff_x(c, w, NULL);
        g[j] = (xp - xm) / (2 * h);
    }
    double var = 0.0;
    for (int i = 0; i < c->np; ++i)
        for (int j = 0; j < c->np; ++j) var += g[i] * gsl_matrix_get(cu, (size_t)i, (size_t)j) * g[j];
    out->liftoff_sigma_m = var >= 0.0 ? sqrt(var) : NAN;
}

static void final_state(fit_ctx *c, const double *u, cli_FitResult *out)
{
    double v[CLI_FIT_PARAMS];
    values_of(c, u, v);
    setup_of(c, v, &out->setup, &out->start);
    out->setup.ramp_length_m -= CLI_TRACK_RAMP_MARGIN_M;
    for (int k = 0; k < c->np; ++k) out->value[k] = v[c->param[k]];
    double path = 0.0, th = 0.0;
    long n_th = 0;
    run_u(c, u, NULL);
    for (long i = 0; i < c->count; ++i) {
        const long j = c->first + i;
        path += pow(c->t->x_m[j] - c->x[i], 2) + pow(c->t->y_m[j] - c->y[i], 2);
        if (c->t->has_mark && isfinite(c->t->theta_rad[j])) {
            th += pow(c->t->theta_rad[j] - (c->th[i] - c->mark_offset), 2);
            ++n_th;
        }
    }
    out->rms_path_m = sqrt(path / (double)c->count);
    out->rms_theta_rad = n_th ? sqrt(th / (double)n_th) : NAN;
}

static cli_FitStop stop_of(int status, int info)
{
    if (status == GSL_EMAXITER) return CLI_FIT_STOP_ITERATIONS;
    if (status != GSL_SUCCESS) return CLI_FIT_STOP_NO_PROGRESS;
    return info == 2 ? CLI_FIT_STOP_GRADIENT : CLI_FIT_STOP_STEP;
}

static int solve(fit_ctx *c, const cli_FitOptions *o, cli_FitResult *out, char *err, size_t err_len)
{
    const size_t n = (size_t)c->nres, p = (size_t)c->np;
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm; /* geodesic acceleration off: its second
                                             derivative would come from a discontinuous model */
    gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, n, p);
    gsl_vector *u = gsl_vector_alloc(p);
    gsl_matrix *cu = gsl_matrix_alloc(p, p);
    double *scratch = malloc(2 * n * sizeof *scratch);
    if (!w || !u || !cu || !scratch) {
        gsl_multifit_nlinear_free(w);
        gsl_vector_free(u);
        gsl_matrix_free(cu);
        free(scratch);
        snprintf(err, err_len, "out of memory");
        return -1;
    }
    double u0[CLI_FIT_PARAMS];
    u_of(c, c->value0, u0);
    for (size_t k = 0; k < p; ++k) gsl_vector_set(u, k, u0[k]);
    gsl_multifit_nlinear_fdf fdf = {f_eval, df_eval, NULL, n, p, c, 0, 0, 0};
    int status = GSL_SUCCESS, info = 0;
    const int passes = o->loss == CLI_LOSS_LINEAR ? 1 : MAX_PASSES;
    for (int pass = 0; pass < passes; ++pass) {
        gsl_multifit_nlinear_init(u, &fdf, w);
        status = gsl_multifit_nlinear_driver((size_t)o->max_iter, 1e-8, 1e-8, 0.0, NULL, NULL, &info, w);
        out->iterations += (int)gsl_multifit_nlinear_niter(w);
        out->passes = pass + 1;
        gsl_vector_memcpy(u, gsl_multifit_nlinear_position(w));
        if (status != GSL_SUCCESS && status != GSL_EMAXITER && status != GSL_ENOPROG) break;
        if (pass + 1 < passes && reweight(c, u->data, o->loss, scratch) < 1e-3) break;
    }
    out->stop = stop_of(status, info);
    /* The covariance at the solution, from a fresh Jacobian there. */
    gsl_multifit_nlinear_init(u, &fdf, w);
    gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 1e-10, cu);
    double chi2;
    gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &chi2);
    out->residuals = c->nres;
    out->chi2 = chi2;
    out->chi2_dof = chi2 / (double)(n - p);
    gsl_matrix_scale(cu, out->chi2_dof);
    values_covariance(c, u->data, cu, out);
    predict_liftoff(c, u->data, cu, out);
    final_state(c, u->data, out);
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(u);
    gsl_matrix_free(cu);
    free(scratch);
    return 0;
}

int cli_track_fit(const jc_Setup *setup, const cli_Track *t, const cli_FitOptions *o, const jc_SimOptions *sim,
                  cli_FitResult *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    if (!(o->max_iter > 0)) {
        snprintf(err, err_len, "the iteration limit must be positive");
        return -1;
    }
    fit_ctx c;
    memset(&c, 0, sizeof c);
    c.sim = sim;
    int rc = prepare(&c, setup, t, o, err, err_len);
    if (rc == 0) {
        out->count = c.np;
        memcpy(out->param, c.param, sizeof c.param);
        for (int k = 0; k < c.np; ++k) out->initial[k] = c.value0[c.param[k]];
        out->first = c.first;
        out->frames = c.count;
        out->sigma_m = c.sigma;
        out->mark_radius_m = c.mark_radius;
        rc = solve(&c, o, out, err, err_len);
    }
    release(&c);
    return rc;
}
