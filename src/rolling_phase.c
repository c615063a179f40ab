/*
 * The simulator's rolling phase (docs/physics.md §2, §4a): the closed-form
 * path of rolling.c followed from the phase's start state to its first
 * event, the time along it by quadrature, trajectory samples, micro-slips
 * rolled through and periodic rocking skipped; with air or rolling
 * resistance, an ODE phase instead (no energy integral).
 */
#include "internal.h"
#include "dop853_kernel.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>

#define ROLL_ROOT_TOL_RAD 1e-12

#define ROLL_MAX_SWINGS 1000000L
/* m: a rolling swing shorter than this (contact point travel) is rest. */
#define ROLL_REST_SWING_M 1e-9

/* dt/du for th = anchor + sigma u^2: 2 u / |w(th)|, finite at a turning
 * point, with P = I_P w^2 taken from the anchor by the exact potential
 * change U(anchor + delta) - U(anchor) (near a turning point P itself is a
 * small difference of large numbers; this keeps the integrand accurate to
 * rounding). The change is written without cancellation for small delta:
 * cos(a + delta) - cos a = -2 sin(a + delta/2) sin(delta/2), likewise for
 * sin; every angle is built from sin and cos of the anchor (kept) and of
 * delta/2: one sincos per point, the integrand's main cost. */
typedef struct {
    double sigma;        /* th = anchor + sigma u^2 */
    double sin_a, cos_a; /* of the anchor */
    double p0, p1;       /* P and sigma * P' at the anchor */
    int linear;          /* 1: th = anchor + sigma u instead, dt/du = 1 / |w| */
    /* The model's products the integrand uses, formed once per piece, not
     * at every point (the same values: each is a leading product of the
     * expression it stands in): I_P = ip0 + ip1 cos th; U's change is mg
     * (dca dcos - sin a (r delta + d dsin)). */
    double ip0, ip1, mg, dca, sin_inc, r, d;
} time_integrand;

static time_integrand time_integrand_at(const jc_Model *m, double sigma, double anchor, double p0, double p1,
                                        int linear)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m;
    double sa, ca;
    jc_sincos(anchor, &sa, &ca); /* inline: libm's sin and cos are calls through the PLT */
    const jc_RollConsts *k = &jc_model_tables(m)->roll_bare;
    return (time_integrand){sigma,
                            sa,
                            ca,
                            p0,
                            p1,
                            linear,
                            k->ip0_kgm2,
                            k->mrd2_kgm2,
                            M * m->setup.gravity_mps2,
                            d * m->cos_incline,
                            m->sin_incline,
                            r,
                            d};
}

static double dt_du(double u, void *params)
{
    const time_integrand *ti = params;
    const double delta = ti->sigma * (ti->linear ? u : u * u);
    double sh, ch;
    jc_sincos(0.5 * delta, &sh, &ch);
    const double s_mid = ti->sin_a * ch + ti->cos_a * sh, c_mid = ti->cos_a * ch - ti->sin_a * sh;
    const double c_th = c_mid * ch - s_mid * sh; /* cos(anchor + delta) */
    const double ip = ti->ip0 + ti->ip1 * c_th;  /* jc_roll_inertia_p */
    if (u == 0.0 && !ti->linear) return ti->p0 > 0.0 || ti->p1 <= 0.0 ? 0.0 : 2.0 / sqrt(ti->p1 / ip);
    const double dcos = -2.0 * s_mid * sh, dsin = 2.0 * c_mid * sh;
    const double du = ti->mg * (ti->dca * dcos - ti->sin_inc * (ti->r * delta + ti->d * dsin));
    const double p = ti->p0 - 2.0 * du;
    if (ti->linear) return p > 0.0 ? 1.0 / sqrt(p / ip) : 0.0;
    return p > 0.0 ? 2.0 * u / sqrt(p / ip) : 0.0;
}

/* Where neither end is near a turning point (P at each end at least a
 * quarter of P at the other), 1/|w| is smooth in th itself: one
 * Gauss-Kronrod rule over [th_a, th_b] (21 points; the sample walk tries
 * 15 first), accepted when its error estimate meets what
 * gsl_integration_qng asks of the same rule (1e-13 of the result, or
 * rounding); 1 if it did, with the time in *dt. One rule over the piece
 * instead of one from each end: half the integrand values, the same time
 * to 1e-16 s. (roll_time takes this case by qng, whose first rule is the
 * same.) */
typedef void gk_rule(const gsl_function *f, double a, double b, double *result, double *abserr, double *resabs,
                     double *resasc);

/* Neither end of a piece near a turning point: I_P w^2 positive at both,
 * each at least a quarter of the other. */
static int smooth_between(double p_a, double p_b)
{
    return p_a > 0.0 && p_b > 0.0 && fmin(p_a, p_b) >= 0.25 * fmax(p_a, p_b);
}

static int roll_time_one_piece_with(gk_rule *rule, const jc_Model *m, double th_a, double p_a, double th_b,
                                    double p_b, double *dt)
{
    if (!smooth_between(p_a, p_b)) return 0;
    time_integrand ti = time_integrand_at(m, th_b > th_a ? 1.0 : -1.0, th_a, p_a, 0.0, 1);
    gsl_function fn = {dt_du, &ti};
    double result, abserr, resabs, resasc;
    rule(&fn, 0.0, fabs(th_b - th_a), &result, &abserr, &resabs, &resasc);
    if (!(isfinite(result) && (abserr < 1e-13 * fabs(result) || abserr < 50.0 * DBL_EPSILON * resabs))) return 0;
    *dt = result;
    return 1;
}

static int roll_time_one_piece(const jc_Model *m, double th_a, double p_a, double th_b, double p_b, double *dt)
{
    return roll_time_one_piece_with(gsl_integration_qk21, m, th_a, p_a, th_b, p_b, dt);
}

/* An end where P is negligible against P' over a piece of len rad: a
 * turning point up to rounding. */
static int is_turning(double p, double dp, double len) { return p <= 1e-12 * fabs(dp) * len; }

/* The time over len rad from an end (P = p, P' = dp there) toward sigma:
 * th = end + sigma u^2 (the end may be a turning point), or linear in th
 * (the end is not one). */
static int roll_piece_with(jc_Sim *sim, double end, double p, double dp, double sigma, double len, int linear,
                           int qng_only, double *part, char *err, size_t err_len)
{
    /* An end where P is negligible against P' over the piece is a turning
     * point up to rounding: take P = 0 there exactly. */
    if (!linear && is_turning(p, dp, len)) p = 0.0;
    time_integrand ti = time_integrand_at(sim->m, sigma, end, p, sigma * dp, linear);
    gsl_function fn = {dt_du, &ti};
    const double upper = linear ? len : sqrt(len);
    double abserr;
    size_t evals;
    /* GSL's nested Gauss-Kronrod-Patterson rule first (21, 43, 87 points,
     * each reusing the last): the integrand is smooth after the u^2
     * substitution, and most ends settle at 21 or 43 points, fewer than
     * the adaptive rule takes; the adaptive rule takes the rest. */
    int st = gsl_integration_qng(&fn, 0.0, upper, 0.0, 1e-13, part, &abserr, &evals);
    if (qng_only) return st == GSL_SUCCESS ? JC_OK : JC_ENUMERIC; /* the caller has another way */
    if (st != GSL_SUCCESS)
        st = gsl_integration_qag(&fn, 0.0, upper, 0.0, 1e-13, JC_QUAD_INTERVALS, GSL_INTEG_GAUSS21, sim->ws->quad,
                                 part, &abserr);
    /* Rounding can stop qag short of 1e-13; what events need is an error
     * within their tolerance or 1e-11 of the time itself. */
    if (st != GSL_SUCCESS && abserr > fmax(sim->opt->event_tol_s, 1e-11 * fabs(*part)))
        return jc_fail(err, err_len, JC_ENUMERIC,
                       "rolling time quadrature failed from th = %.9g rad over %.9g rad (%s; %.3g s +- %.3g s)", end,
                       sigma * len, gsl_strerror(st), *part, abserr);
    return JC_OK;
}

static int roll_piece(jc_Sim *sim, double end, double p, double dp, double sigma, double len, int linear,
                      double *part, char *err, size_t err_len)
{
    return roll_piece_with(sim, end, p, dp, sigma, len, linear, 0, part, err, err_len);
}

/* With one end near a turning point and the other not, the u^2 piece from
 * the turning end covers this fraction of the range and a piece linear in
 * th, from the other end, the rest: only near the turning point is 1/|w|
 * singular. 0.1 takes the fewest integrand values on the paper's runs from
 * rest of the fractions tried (docs/performance.md); the times agree with
 * halves' to 1e-16 s. */
#define TURN_PIECE 0.1
/* rad: the longest range taken by one u^2 piece from a turning point (see
 * roll_time). On longer ranges u^2 crowds the path's oscillation in th
 * (cos th, sin th terms of P) into the far end: the paper's 12.5 rad swing
 * from rest needed the adaptive fallback. */
#define WHOLE_U2_MAX_RAD 1.5707963267948966

/* Time to roll from th_a to th_b (either may be a turning point). p_a is
 * I_P w^2 at th_a as known exactly (the phase's start state); taking it from
 * the energy polynomial instead, e - 2U(th_a), loses it to cancellation when
 * the body starts almost at rest. */
static int roll_time(jc_Sim *sim, const jc_RollingPath *path, double th_a, double p_a, double th_b, double *dt,
                     char *err, size_t err_len)
{
    *dt = 0.0;
    if (th_a == th_b) return JC_OK;
    double p[2], dp[2];
    jc_tl_eval(&path->energy, th_a, &p[0], &dp[0]);
    jc_tl_eval(&path->energy, th_b, &p[1], &dp[1]);
    p[0] = p_a;
    const double ends[2] = {th_a, th_b}, len = fabs(th_b - th_a);
    const double sig[2] = {th_b > th_a ? 1.0 : -1.0, th_b > th_a ? -1.0 : 1.0}; /* from each end inward */
    /* Neither end near a turning point: roll_time_one_piece's case, by qng
     * linear in th, whose first 21 points are the same Gauss-Kronrod rule
     * with the same test, and which goes on to 43 and 87 points reusing
     * them where the 21 fall short, instead of dropping them for the
     * halves (a 3.2 rad swing of the paper's runs took 21 + 43 + 21
     * integrand values that way). */
    if (smooth_between(p[0], p[1])) {
        if (roll_piece_with(sim, th_a, p[0], dp[0], sig[0], len, 1, 1, dt, NULL, 0) == JC_OK) return JC_OK;
        *dt = 0.0;
    }
    /* One end near a turning point, the other not: a short u^2 piece and a long linear one. */
    const int turn = p[0] < 0.25 * p[1] ? 0 : (p[1] < 0.25 * p[0] ? 1 : -1);
    double part;
    int st;
    if (turn >= 0) {
        const int other = 1 - turn;
        if (len <= WHOLE_U2_MAX_RAD && is_turning(p[turn], dp[turn], len) && !is_turning(p[other], dp[other], len)) {
            /* A turning point at one end only: th = end + sigma u^2 over the
             * whole range. With P = 0 at the end, 2 u / |w| is analytic in u
             * up to the other end (no pole near [0, sqrt(len)]), while the
             * split's linear piece, ending 0.1 of the range short of the
             * turning point, has one close by: fewer integrand values over
             * the paper's runs from rest, the times within 4e-16 of a
             * 64-piece 21-point reference (qng's own estimate failed the
             * 12.5 rad swing, hence WHOLE_U2_MAX_RAD). Where the other end is
             * near a turning point too (a creep, P small at both ends), qng
             * fails: then the split (found in tests/sim/test_random_setups.c). */
            if (roll_piece_with(sim, ends[turn], p[turn], dp[turn], sig[turn], len, 0, 1, dt, NULL, 0) == JC_OK)
                return JC_OK;
            *dt = 0.0;
        }
        if ((st = roll_piece(sim, ends[turn], p[turn], dp[turn], sig[turn], TURN_PIECE * len, 0, &part, err,
                             err_len)) != JC_OK)
            return st;
        *dt += part;
        if ((st = roll_piece(sim, ends[other], p[other], dp[other], sig[other], (1.0 - TURN_PIECE) * len, 1, &part,
                             err, err_len)) != JC_OK)
            return st;
        *dt += part;
        return JC_OK;
    }
    /* Otherwise halves, each with u^2 at its end. */
    for (int k = 0; k < 2; ++k) {
        if ((st = roll_piece(sim, ends[k], p[k], dp[k], sig[k], 0.5 * len, 0, &part, err, err_len)) != JC_OK)
            return st;
        *dt += part;
    }
    return JC_OK;
}

typedef struct {
    jc_Sim *sim;
    const jc_RollingPath *path;
    double th_a, p_a, target;
    int status;
} time_target;

static double time_minus_target(double th, void *params)
{
    time_target *tt = params;
    double dt = 0.0;
    if (roll_time(tt->sim, tt->path, tt->th_a, tt->p_a, th, &dt, NULL, 0) != JC_OK) tt->status = JC_ENUMERIC;
    return dt - tt->target;
}

/* The th between th_a and th_b reached dt after th_a. */
static int roll_theta_at(jc_Sim *sim, const jc_RollingPath *path, double th_a, double p_a, double th_b, double dt,
                         double *th, char *err, size_t err_len)
{
    time_target tt = {sim, path, th_a, p_a, dt, JC_OK};
    gsl_function fn = {time_minus_target, &tt};
    const double lo = fmin(th_a, th_b), hi = fmax(th_a, th_b);
    const double flo = time_minus_target(lo, &tt), fhi = time_minus_target(hi, &tt);
    if (flo == 0.0) { *th = lo; return JC_OK; }
    if (fhi == 0.0) { *th = hi; return JC_OK; }
    if (flo * fhi > 0.0) {
        *th = fabs(flo) < fabs(fhi) ? lo : hi;
        return JC_OK;
    }
    gsl_root_fsolver *s = sim->ws->brent;
    gsl_root_fsolver_set(s, &fn, lo, hi);
    int status = GSL_CONTINUE;
    for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
        gsl_root_fsolver_iterate(s);
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-13, 0.0);
    }
    *th = gsl_root_fsolver_root(s);
    if (tt.status != JC_OK) return jc_fail(err, err_len, JC_ENUMERIC, "rolling time inversion failed");
    return JC_OK;
}

/* I_P w^2 of a state, directly. */
static double start_p(const jc_Model *m, const jc_State *s)
{
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    return jc_rolling_inertia_p(m, cs) * s->omega_radps * s->omega_radps;
}

/* The state on the rolling path at th. */
static jc_State roll_state_at(const jc_Model *m, const jc_RollingPath *path, const jc_State *start,
                              double th, int dir)
{
    const double r = m->body.radius_m;
    const double p = fmax(jc_tl_value(&path->energy, th), 0.0);
    const double w = dir * sqrt(p / jc_tl_value(path->inertia, th));
    jc_State s = *start;
    s.theta_rad = th;
    s.omega_radps = w;
    s.x_m = start->x_m + r * (th - start->theta_rad);
    s.y_m = r;
    s.vx_mps = r * w;
    s.vy_mps = 0.0;
    return s;
}

/* th' = w, th'' = a and th''' = j at th on the path, where I_P w^2 = p
 * (w of sign dir): a from the rolling law without loads, I_P a = T(th) +
 * k sin th w^2 (physics.md §2, k = M r d, T = M g Q), and j from it
 * differentiated along the motion (I_P' = -2 k sin th):
 * I_P j = w (T'(th) + k (cos th w^2 + 4 sin th a)). */
static void roll_derivs(const jc_Model *m, double th, double p, int dir, double d[3])
{
    const jc_RollConsts *k = &jc_model_tables(m)->roll_bare;
    double s, c;
    jc_sincos(th, &s, &c);
    const double ip = jc_roll_inertia_p(k, c);
    const double w = dir * sqrt(p / ip), w2 = w * w;
    jc_RollForces f;
    jc_roll_law(k, s, c, w, dir, &f);
    const double a = f.thdd_radps2;
    const double dtorque = k->mg_N * k->d_m * (c * k->cos_a - s * k->sin_a);
    d[0] = w;
    d[1] = a;
    d[2] = w * (dtorque + k->mrd_kgm2 * (c * w2 + 4.0 * s * a)) / ip;
}

/* I_P w^2 at th from the swing's start (p0 there) by the exact potential
 * change, written as in dt_du: the same function of th the quadrature from
 * the start integrates (the energy polynomial's value differs from it by the
 * rounding of its large terms). */
static double path_p(const jc_Model *m, const jc_State *start, double p0, double th)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, d = m->body.cm_offset_m;
    const double delta = th - start->theta_rad;
    double sh, ch, sa, ca;
    jc_sincos(0.5 * delta, &sh, &ch);
    jc_sincos(start->theta_rad, &sa, &ca);
    const double s_mid = sa * ch + ca * sh, c_mid = ca * ch - sa * sh;
    const double dcos = -2.0 * s_mid * sh, dsin = 2.0 * c_mid * sh;
    const double du = M * m->setup.gravity_mps2 * (d * m->cos_incline * dcos - m->sin_incline * (r * delta + d * dsin));
    return fmax(p0 - 2.0 * du, 0.0);
}

/* An anchor of the sample walk along one swing: an angle whose time after
 * the swing's start is known by quadrature (not taken from a sample time). */
typedef struct {
    double th, tau; /* angle, and its time after the swing's start */
    double p;       /* I_P w^2 there */
    double d[3];    /* w, a, j there */
} roll_anchor;

static void anchor_at_start(const jc_Model *m, const jc_State *start, int dir,
                            roll_anchor *an)
{
    an->th = start->theta_rad;
    an->tau = 0.0;
    an->p = start_p(m, start);
    roll_derivs(m, an->th, an->p, dir, an->d);
    an->d[0] = start->omega_radps; /* the state's own, exact */
}

/* roll_time_one_piece's rule for the short step between two samples: 15
 * Gauss-Kronrod points, which mostly meet the test on so short a step, or
 * its 21 when they do not. */
static int walk_piece(const jc_Model *m, double th_a, double p_a, double th_b, double p_b, double *dt)
{
    return roll_time_one_piece_with(gsl_integration_qk15, m, th_a, p_a, th_b, p_b, dt) ||
           roll_time_one_piece(m, th_a, p_a, th_b, p_b, dt);
}

/* The time after the swing's start at th: from the last anchor by one
 * short Gauss-Kronrod rule where 1/|w| is smooth between the two
 * (walk_piece, with I_P w^2 at th by the exact potential change), else by
 * the quadrature from the swing's start, which takes 21 to 87 integrand
 * values, or two pieces, at every sample. Not where P is below
 * JC_WALK_P_FLOOR of its scale (near a turning point): chained there too,
 * the times drifted from the whole swing's quadrature by up to 2e-8 of it;
 * with the floor at 1e-3, by up to 2.6e-12 of it, which put an event
 * 1.1e-11 rad off the ODE from the last sample before it; at 1e-2 the worst
 * over eight seeds of tests/sim/test_rolling_samples.c is 0.31 of that
 * test's bound (0.1: 0.07, at more cost). p_th: I_P w^2 at th (path_p). 1
 * when the time is known. */
#define JC_WALK_P_FLOOR 1e-2
static int roll_time_from_anchor(jc_Sim *sim, const jc_RollingPath *path, const jc_State *start, double p_start,
                                 int dir, const roll_anchor *an, double th, double p_th, double *tau)
{
    const jc_Model *m = sim->m;
    const double p_floor = JC_WALK_P_FLOOR * (p_start + 2.0 * m->body.mass_kg * m->setup.gravity_mps2 *
                                                          (m->body.radius_m + m->body.cm_offset_m));
    double piece;
    if (an->p >= p_floor && p_th >= p_floor && walk_piece(m, an->th, an->p, th, p_th, &piece)) {
        *tau = an->tau + ((th - an->th) * dir >= 0.0 ? piece : -piece);
        return 1;
    }
    return roll_time(sim, path, start->theta_rad, p_start, th, tau, NULL, 0) == JC_OK;
}

#define SAMPLE_WALK_MAX_ITER 8
/* rad: the estimated remainder of the last Taylor step a sample accepts. */
#define SAMPLE_WALK_TOL_RAD 1e-16

/* The th reached dt after the swing's start, dt <= dt_end (the swing's end
 * th_b): the third-order Taylor step in time from the last anchor (the last
 * sample's) predicts th, the quadrature from the swing's start to it (the
 * same t(th) as the swing's end time and roll_theta_at; from the last
 * anchor where the path is smooth: roll_time_from_anchor) gives its time,
 * which makes it the next anchor; the Taylor step from that anchor over the
 * small remaining time gives th (th(t) is smooth through a turning point,
 * where t(th) is not). One quadrature a sample where the root search took a
 * dozen.
 * Repeated while the estimated remainder of that last step (the predictor's
 * own correction times the fourth power of the ratio of the two steps)
 * exceeds SAMPLE_WALK_TOL_RAD; falls back to the root search over the
 * quadrature from the start (roll_theta_at) if it does not settle. */
static int roll_theta_walk(jc_Sim *sim, const jc_RollingPath *path, const jc_State *start, double th_b,
                           double dt_end, int dir, roll_anchor *an, double dt, double *th, char *err, size_t err_len)
{
    const jc_Model *m = sim->m;
    const double lo = fmin(start->theta_rad, th_b), hi = fmax(start->theta_rad, th_b);
    const double p_start = start_p(m, start);
    for (int it = 0; it < SAMPLE_WALK_MAX_ITER; ++it) {
        const double h = dt - an->tau;
        const double pred = fmin(fmax(an->th + h * (an->d[0] + h * (0.5 * an->d[1] + h * an->d[2] / 6.0)), lo), hi);
        const double p_pred = path_p(m, start, p_start, pred); /* once: the time and the anchor both use it */
        roll_anchor next;
        next.th = pred;
        if (pred == th_b) {
            next.tau = dt_end;
        } else if (pred == an->th) {
            next.tau = an->tau;
        } else if (!roll_time_from_anchor(sim, path, start, p_start, dir, an, pred, p_pred, &next.tau)) {
            break;
        }
        if (pred == start->theta_rad)
            anchor_at_start(m, start, dir, &next);
        else {
            next.p = p_pred;
            roll_derivs(m, pred, next.p, dir, next.d);
        }
        const double e = dt - next.tau;
        const double corr = e * (next.d[0] + e * (0.5 * next.d[1] + e * next.d[2] / 6.0));
        const double q = h != 0.0 ? e / h : (e == 0.0 ? 0.0 : 1.0);
        *an = next;
        if (fabs(corr) * q * q * q * q <= SAMPLE_WALK_TOL_RAD && pred + corr >= lo && pred + corr <= hi) {
            *th = pred + corr;
            return JC_OK;
        }
    }
    /* Not settled: the root search from the start, and the anchor back there. */
    anchor_at_start(m, start, dir, an);
    return roll_theta_at(sim, path, start->theta_rad, an->p, th_b, dt, th, err, err_len);
}

/* The fixed-time samples of a swing from start to th_end (reached at t_end),
 * walked in time order (roll_theta_walk). */
static int emit_samples(jc_Sim *sim, const jc_RollingPath *path, const jc_State *start, double th_end,
                        int dir, double t_end, char *err, size_t err_len)
{
    double ts;
    roll_anchor an;
    int have_anchor = 0;
    while (jc_record_sample_due(sim, t_end, &ts)) {
        if (!have_anchor) {
            anchor_at_start(sim->m, start, dir, &an);
            have_anchor = 1;
        }
        double th;
        int st = roll_theta_walk(sim, path, start, th_end, t_end - start->t_s, dir, &an, ts - start->t_s, &th, err,
                                 err_len);
        if (st != JC_OK) return st;
        jc_State s = roll_state_at(sim->m, path, start, th, dir);
        s.t_s = ts;
        double thdd, n, f;
        jc_rolling_forces(sim->m, th, s.omega_radps, &thdd, &n, &f);
        if ((st = jc_record_sample(sim, &s, JC_MODE_ROLLING, n, f, 0.0)) != JC_OK)
            return jc_fail(err, err_len, st, "out of memory for samples");
    }
    return JC_OK;
}

enum { RW_NORMAL, RW_SLIP_POS, RW_SLIP_NEG, RW_ENERGY };

/* ---- rolling with air or rolling resistance: no energy integral, an ODE ---- */

typedef struct {
    const jc_Model *m;
    int dir;   /* sign of w during the phase */
    int armed; /* 1: watch for w falling into the rolling-resistance band */
    int hold;  /* 1: watch for the full lever coming to hold the body (hold_margin) */
    double x0_m, th0_rad; /* at the start of the integration: x = x0 + r (th - th0) */
    jc_RollConsts k;      /* the rolling law's constants, with the model's resistances */
    /* N and F at the last state the events were evaluated at (sin, cos, w):
     * their rates start from there. */
    double at_sin, at_cos, at_w, at_n, at_f;
} roll_ode;

/* Only th, w, cos th, sin th and the losses are integrated (friction's is
 * carried with them, unchanged): x and vx follow from th and w exactly,
 * x = x0 + r (th - th0) and vx = r w, and integrating them was a third of
 * the stages' work. */
static double roll_ode_x(const roll_ode *c, double th)
{
    return c->x0_m + c->m->body.radius_m * (th - c->th0_rad);
}

/* rad/s: rolling resistance ramps to 0 below 1 mrad/s (JC_RR_BAND_RADPS), which lets a
 * body creep toward equilibrium for ever instead of stopping. Where the spin
 * falls below this and the resistance can hold the body at rest (rest
 * direction 0), it has come to rest: the run ends with termination rest.
 * Between a turn (or a rest check that failed) and the spin's leaving twice
 * the band, the spin stays below that; where the full lever comes to hold
 * the body there (hold_margin reaching 0), it has come to rest too: the ramp
 * alone lets a body started barely beyond the static angle creep with w
 * decaying for ever. */
#define ROLL_REST_BAND_RADPS 1e-3

/* The law the phase integrates, at y: rolling resistance by its ramp alone,
 * b_s = b clamp(w / band), 0 at w = 0 (direction 0 to jc_roll_law). The
 * full lever against the direction about to be taken at w = 0 is the static
 * question (rest_direction), not the motion's: after a turn the phase starts
 * at w = 0 exactly, and a right-hand side that jumps from b dir there to ~0
 * at the next stage makes every step's error estimate linear in its length,
 * so the integrator cannot step past the turn. */
static void roll_ode_law(const roll_ode *c, const double y[], jc_RollForces *rf)
{
    jc_roll_law(&c->k, y[JC_Y_SIN], y[JC_Y_COS], y[JC_Y_W], 0, rf);
}

/* The acceleration in the direction of motion of a body at rest at th (sine
 * s, cosine cs) starting that way against the full lever (rest_direction's):
 * > 0 while rolling resistance cannot hold it that way. */
static double hold_margin(const roll_ode *c, double s, double cs)
{
    jc_RollForces rf;
    jc_roll_law(&c->k, s, cs, 0.0, c->dir, &rf);
    return c->dir * rf.thdd_radps2;
}

static void roll_ode_forces(const roll_ode *c, const double y[], double *thdd, double *n, double *f)
{
    jc_RollForces rf;
    roll_ode_law(c, y, &rf);
    *thdd = rf.thdd_radps2;
    *n = rf.normal_N;
    *f = rf.friction_N;
}

static int roll_ode_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const roll_ode *c = params;
    const double w = y[JC_Y_W];
    jc_RollForces rf;
    roll_ode_law(c, y, &rf);
    const double r = c->k.r_m, thdd = rf.thdd_radps2;
    dydt[JC_Y_X] = r * w;
    dydt[JC_Y_Y] = 0.0;
    dydt[JC_Y_TH] = w;
    dydt[JC_Y_VX] = r * thdd;
    dydt[JC_Y_VY] = 0.0;
    dydt[JC_Y_W] = thdd;
    dydt[JC_Y_FRICTION] = 0.0;
    dydt[JC_Y_AIR] = jc_roll_air_power(&c->k, w);
    dydt[JC_Y_RR] = rf.rr_m * rf.normal_N * w;
    dydt[JC_Y_COS] = -w * y[JC_Y_SIN];
    dydt[JC_Y_SIN] = w * y[JC_Y_COS];
    return 0;
}

/* The range integrated, given once to the step's instance and to ode.c. */
enum { ROLL_ODE_FIRST = JC_Y_TH, ROLL_ODE_DIM = JC_Y_RR + 1 - JC_Y_TH };
JC_DOP853_TRY_INSTANCE(roll_ode_try, roll_ode_rhs, ROLL_ODE_FIRST, ROLL_ODE_DIM)

enum { RE_NORMAL, RE_SLIP_POS, RE_SLIP_NEG, RE_TURN, RE_END, RE_TOP, RE_SLOW, RE_HOLD, RE_COUNT };

static void roll_ode_events(void *params, const double y[], double ev[])
{
    roll_ode *c = params;
    double thdd, n, f;
    roll_ode_forces(c, y, &thdd, &n, &f);
    c->at_sin = y[JC_Y_SIN];
    c->at_cos = y[JC_Y_COS];
    c->at_w = y[JC_Y_W];
    c->at_n = n;
    c->at_f = f;
    const double mu = c->m->setup.mu_static;
    ev[RE_NORMAL] = n;
    ev[RE_SLIP_POS] = mu * n - f;
    ev[RE_SLIP_NEG] = mu * n + f;
    ev[RE_TURN] = c->dir * y[JC_Y_W];
    const double x = roll_ode_x(c, y[JC_Y_TH]);
    ev[RE_END] = c->m->setup.ramp_length_m - x;
    ev[RE_TOP] = x + JC_RAMP_TOP_SLACK_M;
    /* Armed: w falls into the band. Not armed: w leaves twice the band (then armed). */
    ev[RE_SLOW] = c->armed ? c->dir * y[JC_Y_W] - ROLL_REST_BAND_RADPS : 2.0 * ROLL_REST_BAND_RADPS - c->dir * y[JC_Y_W];
    ev[RE_HOLD] = c->hold ? hold_margin(c, y[JC_Y_SIN], y[JC_Y_COS]) : 1.0;
}

/* The events' rates along the flow at y (f = f(y)): those of w and x in
 * closed form, those of N and F by a forward difference from y (whose
 * forces the events just computed) over a time far below the rotation
 * period, accurate to ~1e-6 of the rate, ample for the dip check that
 * uses them. ode.c's central difference takes two more evaluations of all
 * events per step. */
static void roll_ode_event_rates(void *params, const double y[], const double f[], double dev[])
{
    roll_ode *c = params;
    if (!(c->at_sin == y[JC_Y_SIN] && c->at_cos == y[JC_Y_COS] && c->at_w == y[JC_Y_W])) {
        double ev[RE_COUNT];
        roll_ode_events(c, y, ev);
    }
    const double n0 = c->at_n, f0 = c->at_f;
    const double aw = fabs(y[JC_Y_W]), h = 1e-6 / (aw > 1.0 ? aw : 1.0); /* no libm call: a NaN w gives h NaN either way */
    double yp[JC_Y_DIM];
    yp[JC_Y_SIN] = y[JC_Y_SIN] + h * f[JC_Y_SIN];
    yp[JC_Y_COS] = y[JC_Y_COS] + h * f[JC_Y_COS];
    yp[JC_Y_W] = y[JC_Y_W] + h * f[JC_Y_W];
    double thdd, n, fr;
    roll_ode_forces(c, yp, &thdd, &n, &fr);
    const double dn = (n - n0) / h, df = (fr - f0) / h, mu = c->m->setup.mu_static;
    const double dx = c->m->body.radius_m * f[JC_Y_TH];
    dev[RE_NORMAL] = dn;
    dev[RE_SLIP_POS] = mu * dn - df;
    dev[RE_SLIP_NEG] = mu * dn + df;
    dev[RE_TURN] = c->dir * f[JC_Y_W];
    dev[RE_END] = -dx;
    dev[RE_TOP] = dx;
    dev[RE_SLOW] = c->armed ? c->dir * f[JC_Y_W] : -c->dir * f[JC_Y_W];
    dev[RE_HOLD] = c->hold ? (hold_margin(c, yp[JC_Y_SIN], yp[JC_Y_COS]) - hold_margin(c, y[JC_Y_SIN], y[JC_Y_COS])) / h
                           : 0.0;
}

static int roll_ode_sample(jc_Sim *sim, void *params, double t, const double y[])
{
    const roll_ode *c = params;
    double thdd, n, f;
    roll_ode_forces(c, y, &thdd, &n, &f);
    double ys[JC_Y_DIM];
    for (int i = 0; i < JC_Y_DIM; ++i) ys[i] = y[i];
    ys[JC_Y_X] = roll_ode_x(c, y[JC_Y_TH]);
    ys[JC_Y_VX] = c->m->body.radius_m * y[JC_Y_W];
    jc_State s;
    jc_y_to_state(ys, t, &s);
    return jc_record_sample_y(sim, &s, ys, JC_MODE_ROLLING, n, f, 0.0);
}

/* Direction in which a body at rest (w = 0) starts to roll, 0 if rolling
 * resistance (or equilibrium) holds it. */
static int rest_direction(const jc_Model *m, double th)
{
    double thdd, n, f;
    jc_rolling_at(m, th, 0.0, 1, &thdd, &n, &f);
    if (thdd > 0.0) return 1;
    jc_rolling_at(m, th, 0.0, -1, &thdd, &n, &f);
    return thdd < 0.0 ? -1 : 0;
}

#define ROLL_ODE_MAX_TURNS 100000L

static int roll_ode_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len)
{
    const double w0 = sim->s.omega_radps;
    roll_ode ctx = {.m = sim->m,
                    .dir = w0 > 0.0 ? 1 : (w0 < 0.0 ? -1 : rest_direction(sim->m, sim->s.theta_rad)),
                    .armed = fabs(w0) > ROLL_REST_BAND_RADPS,
                    .at_sin = NAN};
    ctx.k = jc_model_tables(sim->m)->roll;
    for (long turn = 0; turn < ROLL_ODE_MAX_TURNS; ++turn) {
        if (ctx.dir == 0) {
            *end = PHASE_AT_REST;
            return JC_OK;
        }
        const jc_OdePhase phase = {roll_ode_rhs, roll_ode_events, RE_COUNT, roll_ode_sample, &ctx,
                                   ROLL_ODE_DIM, roll_ode_event_rates, roll_ode_try};
        const jc_OdeExtras range = {ROLL_ODE_FIRST, NULL};
        ctx.x0_m = sim->s.x_m;
        ctx.th0_rad = sim->s.theta_rad;
        ctx.hold = 0; /* armed, or no rolling resistance (air alone holds nothing) */
        if (!ctx.armed && ctx.k.rr_m > 0.0) {
            double sn, cs;
            jc_sincos(sim->s.theta_rad, &sn, &cs);
            ctx.hold = hold_margin(&ctx, sn, cs) > 0.0;
        }
        int which;
        int st = jc_ode_run_with(sim, &phase, &range, &which, err, err_len);
        if (st != JC_OK) return st;
        sim->s.x_m = roll_ode_x(&ctx, sim->s.theta_rad);
        sim->s.y_m = sim->m->body.radius_m;
        sim->s.vy_mps = 0.0;
        sim->s.vx_mps = sim->m->body.radius_m * sim->s.omega_radps;
        switch (which) {
        case RE_NORMAL: *end = PHASE_LIFTOFF; return JC_OK;
        case RE_SLIP_POS:
        case RE_SLIP_NEG: *end = PHASE_SLIP; return JC_OK;
        case RE_TURN:
            sim->s.omega_radps = sim->s.vx_mps = 0.0;
            ctx.dir = rest_direction(sim->m, sim->s.theta_rad);
            ctx.armed = 0;
            continue;
        case RE_SLOW:
            if (ctx.armed && rest_direction(sim->m, sim->s.theta_rad) == 0) {
                /* The last crawl's kinetic energy (w <= 1 mrad/s) goes to
                 * rolling resistance, so the balance still closes. */
                sim->rr_loss_J += jc_kinetic_energy(sim->m, &sim->s);
                sim->s.omega_radps = sim->s.vx_mps = 0.0;
                *end = PHASE_AT_REST;
                return JC_OK;
            }
            ctx.armed = !ctx.armed;
            continue;
        case RE_HOLD:
            if (rest_direction(sim->m, sim->s.theta_rad) == 0) {
                /* w < 2 mrad/s here: its kinetic energy goes to rolling
                 * resistance, as at RE_SLOW. */
                sim->rr_loss_J += jc_kinetic_energy(sim->m, &sim->s);
                sim->s.omega_radps = sim->s.vx_mps = 0.0;
                *end = PHASE_AT_REST;
                return JC_OK;
            }
            continue; /* the margin is <= 0 now: not watched again (see the start) */
        case RE_END: *end = PHASE_RAMP_END; return JC_OK;
        case RE_TOP: *end = PHASE_RAMP_TOP; return JC_OK;
        case JC_ODE_TIME_LIMIT: *end = PHASE_TIME_LIMIT; return JC_OK;
        default: *end = PHASE_STEP_LIMIT; return JC_OK;
        }
    }
    *end = PHASE_STEP_LIMIT;
    return JC_OK;
}

/* ---- micro-slips and periodic rocking (docs/physics.md §4a, "Micro-slips") ---- */

/* The contact point's tangential inverse mass with the normal held: the
 * slip acceleration per newton of friction the cone cannot supply,
 * det K / K_nn with K of the impact law (physics.md §4). */
static double tangential_compliance(const jc_Model *m, double th)
{
    const jc_State at = {.theta_rad = th, .y_m = m->body.radius_m};
    jc_ImpactInput k;
    jc_impact_input(m, &at, &k);
    return (k.ktt * k.knn - k.ktn * k.ktn) / k.knn;
}

/* Samples of the excess over the cone along an excursion: enough to find
 * its peak to a few per cent, which is all a scale estimate needs. */
#define EXCURSION_SAMPLES 32
/* m of rolling (contact point travel): an excursion beyond the cone longer
 * than this is not taken for a micro-slip (the rocking hoop's last ones
 * span 0.2 mm). */
#define MICRO_SPAN_M 1e-3

/* Whether the excursion of the rolling path beyond the friction cone that
 * starts at `at` on slip function k is a micro-slip: one whose slip scale,
 * k_t dF_max tau^2 (the slip speed the missing friction dF_max builds over
 * the excursion's duration tau, times tau), stays below the contact height
 * (sim options, 1 um by default): the same scale below which a rebound
 * counts as contact. A real contact takes such a tangential displacement
 * elastically (its tangential compliance) instead of slipping. Sets *micro. */
static int micro_excursion(jc_Sim *sim, const jc_RollingPath *path, const jc_State *at, int k, double th_lim,
                           int *micro, char *err, size_t err_len)
{
    const jc_Model *m = sim->m;
    *micro = 0;
    if (!(sim->opt->contact_height_m > 0.0)) return JC_OK;
    const jc_TrigLin *g = k == RW_SLIP_POS ? &path->slip_pos : &path->slip_neg;
    /* Only an excursion within MICRO_SPAN_M of rolling is a candidate: this
     * keeps the look-ahead short on the common path (a real slip), and can
     * only err toward the exact Coulomb model (a slip). */
    const double span = MICRO_SPAN_M / m->body.radius_m;
    const double th_to = th_lim > at->theta_rad ? fmin(th_lim, at->theta_rad + span)
                                                : fmax(th_lim, at->theta_rad - span);
    /* Beyond the cone -g > 0: its next zero is where the path re-enters it. */
    jc_ScanSet set = {2, {&path->energy, g}, {1, -1}};
    jc_ScanHit hit;
    int st = jc_scan_first_with(&set, at->theta_rad, th_to, ROLL_ROOT_TOL_RAD, sim->ws->brent, &hit, err, err_len);
    if (st != JC_OK) return st;
    /* Longer than the span, off the ramp, or no excursion at all (a touch of
     * the cone's edge). */
    if (hit.index < 0 || fabs(hit.theta - at->theta_rad) <= ROLL_ROOT_TOL_RAD) return JC_OK;
    double dt;
    if ((st = roll_time(sim, path, at->theta_rad, start_p(m, at), hit.theta, &dt, err, err_len)) != JC_OK)
        return st;
    /* Through a turning point the path comes back the same way: twice the time. */
    const double tau = hit.index == 0 ? 2.0 * dt : dt;
    double peak = 0.0; /* k_t dF, m/s^2 */
    for (int i = 0; i <= EXCURSION_SAMPLES; ++i) {
        const double th = at->theta_rad + (hit.theta - at->theta_rad) * i / EXCURSION_SAMPLES;
        const double w = sqrt(fmax(jc_tl_value(&path->energy, th), 0.0) / jc_tl_value(path->inertia, th));
        double thdd, n, f;
        jc_rolling_forces(m, th, w, &thdd, &n, &f);
        peak = fmax(peak, tangential_compliance(m, th) * (fabs(f) - m->setup.mu_static * n));
    }
    *micro = peak * tau * tau < sim->opt->contact_height_m;
    return JC_OK;
}

/* s: two turning points this close in time are one (rounding of a turn). */
#define PERIOD_MIN_S 1e-9

int jc_rolling_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len)
{
    if (jc_model_has_resistance(sim->m)) return roll_ode_phase(sim, end, err, err_len);
    const jc_Model *m = sim->m;
    const double r = m->body.radius_m, L = m->setup.ramp_length_m;
    jc_RollingPath path;
    jc_rolling_path_init(m, sim->s.theta_rad, sim->s.omega_radps, &path);
    double thdd, n, f;
    jc_rolling_forces(m, sim->s.theta_rad, sim->s.omega_radps, &thdd, &n, &f);
    int dir = sim->s.omega_radps != 0.0 ? (sim->s.omega_radps > 0.0 ? 1 : -1) : (thdd > 0.0) - (thdd < 0.0);
    if (dir == 0) {
        *end = PHASE_AT_REST;
        return JC_OK;
    }
    /* Slip functions the path is rolling through (a micro-slip excursion):
     * watched with the opposite sign, so their next zero is the re-entry. */
    int through[2] = {0, 0};
    /* The last two turning points: a third at the same angle, with the same
     * excursions, closes a period of a motion that repeats for ever. */
    double turn_t[2] = {0.0, 0.0}, turn_th[2] = {0.0, 0.0};
    int turn_through[2] = {0, 0};
    long turns = 0;
    const int may_skip = !(sim->opt->sample_dt_s > 0.0); /* fixed samples need every period */
    for (long swing = 0; swing < ROLL_MAX_SWINGS; ++swing) {
        const jc_State start = sim->s;
        /* Uphill, the start counts as passed 1 nm beyond it (as in sliding and
         * flight), so that a body rocking back to rest at its start turns there. */
        const double th_lim = dir > 0 ? start.theta_rad + (L - start.x_m) / r
                                      : start.theta_rad - (start.x_m + JC_RAMP_TOP_SLACK_M) / r;
        jc_ScanSet set = {4, {&path.normal, &path.slip_pos, &path.slip_neg, &path.energy},
                          {1, through[0] ? -1 : 1, through[1] ? -1 : 1, 1}};
        jc_ScanHit hit;
        int st = jc_scan_first_with(&set, start.theta_rad, th_lim, ROLL_ROOT_TOL_RAD, sim->ws->brent, &hit, err,
                                    err_len);
        if (st != JC_OK) return st;
        const int tiny_swing = hit.index == RW_ENERGY && r * fabs(hit.theta - start.theta_rad) < ROLL_REST_SWING_M;
        if (tiny_swing && start.omega_radps == 0.0) {
            /* From rest, a swing to a turning point less than 1 nm away: the
             * body rocks about a stable equilibrium by less than any ramp's
             * roughness: it is at rest here, now. */
            *end = PHASE_AT_REST;
            return JC_OK;
        }
        double dt;
        const double p_start = start_p(m, &start);
        if (tiny_swing) {
            /* A moving body that turns within 1 nm (a faint spin against the
             * slope) is not at rest: it turns and rolls back, and the next
             * swing decides. So short a swing is uniform deceleration to
             * rounding (the time quadrature of it would be all rounding):
             * the angle falls by half the start's w times the time. */
            dt = 2.0 * fabs(hit.theta - start.theta_rad) / fabs(start.omega_radps);
        } else if ((st = roll_time(sim, &path, start.theta_rad, p_start, hit.theta, &dt, err, err_len)) != JC_OK) {
            return st;
        }
        const double t_max = sim->opt->t_max_s;
        double th_end = hit.theta;
        if (start.t_s + dt > t_max) {
            if ((st = roll_theta_at(sim, &path, start.theta_rad, p_start, hit.theta, t_max - start.t_s, &th_end, err,
                                    err_len)))
                return st;
            dt = t_max - start.t_s;
        }
        if ((st = emit_samples(sim, &path, &start, th_end, dir, start.t_s + dt, err, err_len)) != JC_OK) return st;
        sim->s = roll_state_at(m, &path, &start, th_end, dir);
        sim->s.t_s = start.t_s + dt;
        if (th_end != hit.theta) {
            *end = PHASE_TIME_LIMIT;
            return JC_OK;
        }
        switch (hit.index) {
        case RW_NORMAL: *end = PHASE_LIFTOFF; return JC_OK;
        case RW_SLIP_POS:
        case RW_SLIP_NEG: {
            const int k = hit.index - RW_SLIP_POS;
            if (through[k]) { /* back inside the cone */
                through[k] = 0;
                continue;
            }
            int micro = 0;
            if ((st = micro_excursion(sim, &path, &sim->s, hit.index, th_lim, &micro, err, err_len)) != JC_OK)
                return st;
            if (micro) {
                through[k] = 1;
                sim->micro_slips++;
                continue;
            }
            *end = PHASE_SLIP;
            return JC_OK;
        }
        case RW_ENERGY: {
            /* A turning point: roll back the other way (not a mode change). */
            sim->s.omega_radps = 0.0;
            sim->s.vx_mps = 0.0;
            dir = -dir;
            const int sig = through[0] | through[1] << 1;
            const int older = (int)(turns % 2);
            if (may_skip && turns >= 2 && turn_through[older] == sig &&
                fabs(sim->s.theta_rad - turn_th[older]) <= 8.0 * ROLL_ROOT_TOL_RAD) {
                /* Energy is conserved on the path and nothing happened over a
                 * whole period: the motion repeats for ever. Skip whole periods
                 * to within one of the time limit. */
                const double period = sim->s.t_s - turn_t[older];
                if (period > PERIOD_MIN_S) {
                    const double skip = floor((t_max - sim->s.t_s) / period) - 1.0;
                    if (skip > 0.0) {
                        sim->s.t_s += skip * period;
                        sim->periodic_period_s = period;
                        sim->periodic_th_lo_rad = fmin(sim->s.theta_rad, turn_th[1 - older]);
                        sim->periodic_th_hi_rad = fmax(sim->s.theta_rad, turn_th[1 - older]);
                    }
                }
            }
            turn_t[older] = sim->s.t_s;
            turn_th[older] = sim->s.theta_rad;
            turn_through[older] = sig;
            turns++;
            continue;
        }
        default:
            *end = dir > 0 ? PHASE_RAMP_END : PHASE_RAMP_TOP;
            return JC_OK;
        }
    }
    *end = PHASE_STEP_LIMIT;
    return JC_OK;
}
