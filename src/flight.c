/*
 * Flight (docs/physics.md §4): no contact; G moves ballistically, w is
 * constant. Everything is closed form. The height of the rim's lowest point
 * above the incline (the gap) is written relative to the flight's start,
 *   gap(t) = gap0 + v0 t + a0 t^2/2 + d R3(th0, w t),
 *   R3(f, u) = cos f (1 - u^2/2 - cos u) + sin f (sin u - u),
 * so that the t^3 growth of the gap right after a lift-off (where gap0, v0
 * and a0 all vanish) is computed to full relative precision. Touchdown is the
 * first root of gap(t), found by the crossing search of scan.c with
 * |gap'''| <= d |w|^3: the search step is bounded by the rotation rate and
 * cannot skip a root.
 */
#include "internal.h"

#include <float.h>
#include <math.h>

/* The remainders of cos and sin after their Taylor terms, without
 * cancellation, from one sincos of u/2 (three separate sines per
 * evaluation made the flight search a large part of a run's time). */
typedef struct {
    double rem2; /* 1 - u^2/2 - cos u */
    double rem1; /* sin u - u */
    double rem0; /* 1 - cos u */
    double sin_u;
} trig_rems;

static trig_rems rems(double u)
{
    double s2, c2;
    jc_sincos(0.5 * u, &s2, &c2);
    trig_rems t;
    t.rem0 = 2.0 * s2 * s2;
    t.sin_u = 2.0 * s2 * c2;
    if (fabs(u) > 0.5) {
        t.rem2 = t.rem0 - 0.5 * u * u;
        t.rem1 = t.sin_u - u;
        return t;
    }
    const double u2 = u * u;
    /* -u^4/4! + u^6/6! - u^8/8! + u^10/10! - u^12/12! + u^14/14! */
    t.rem2 = u2 * u2 * (-1.0 / 24 + u2 * (1.0 / 720 + u2 * (-1.0 / 40320 + u2 * (1.0 / 3628800 +
             u2 * (-1.0 / 479001600 + u2 * (1.0 / 87178291200.0))))));
    t.rem1 = u * u2 * (-1.0 / 6 + u2 * (1.0 / 120 + u2 * (-1.0 / 5040 + u2 * (1.0 / 362880 +
             u2 * (-1.0 / 39916800 + u2 * (1.0 / 6227020800.0))))));
    return t;
}

/* The remainders at the last time asked: the crossing search evaluates the
 * gap, the distance to the ramp's end and to its start at the same time in
 * turn, and they share them. */
typedef struct {
    double t;
    trig_rems q;
} rems_cache;

typedef struct {
    const jc_Model *m;
    rems_cache *cache;
    double th0, w;
    double cos0, sin0; /* of th0 */
    double y0, vy0, ay0; /* of C, relative to r for y */
    double x0, vx0, ax0;
    double ramp_length;
} flight;

static trig_rems rems_at(const flight *f, double t)
{
    if (f->cache->t != t) {
        f->cache->q = rems(f->w * t);
        f->cache->t = t;
    }
    return f->cache->q;
}

static void flight_init(const jc_Model *m, const jc_State *s, rems_cache *cache, flight *f)
{
    cache->t = NAN;
    f->cache = cache;
    const double d = m->body.cm_offset_m, g = m->setup.gravity_mps2, w = s->omega_radps;
    f->m = m;
    f->th0 = s->theta_rad;
    f->w = w;
    f->cos0 = cos(s->theta_rad);
    f->sin0 = sin(s->theta_rad);
    f->y0 = s->y_m - m->body.radius_m;
    f->vy0 = s->vy_mps;
    f->ay0 = -g * m->cos_incline + d * w * w * cos(s->theta_rad);
    f->x0 = s->x_m;
    f->vx0 = s->vx_mps;
    f->ax0 = g * m->sin_incline + d * w * w * sin(s->theta_rad);
    f->ramp_length = m->setup.ramp_length_m;
}

/* gap and its first two time derivatives at t. */
static void gap_eval(const void *ctx, double t, double out[3])
{
    const flight *f = ctx;
    const double d = f->m->body.cm_offset_m, w = f->w;
    const double c = f->cos0, s = f->sin0;
    const trig_rems q = rems_at(f, t);
    const double r3 = c * q.rem2 + s * q.rem1;
    const double r3u = c * q.rem1 - s * q.rem0;
    const double r3uu = -c * q.rem0 - s * q.sin_u;
    out[0] = f->y0 + f->vy0 * t + 0.5 * f->ay0 * t * t + d * r3;
    out[1] = f->vy0 + f->ay0 * t + d * w * r3u;
    out[2] = f->ay0 + d * w * w * r3uu;
}

/* gap', gap'', gap''' (for the largest gap: the roots of gap'). */
static void gap_rate_eval(const void *ctx, double t, double out[3])
{
    const flight *f = ctx;
    double g[3];
    gap_eval(ctx, t, g);
    out[0] = g[1];
    out[1] = g[2];
    /* sin(th0 + w t) = sin th0 (1 - (1 - cos u)) + cos th0 sin u */
    const trig_rems q = rems_at(f, t);
    out[2] = -f->m->body.cm_offset_m * f->w * f->w * f->w * (f->sin0 * (1.0 - q.rem0) + f->cos0 * q.sin_u);
}

/* x of C and its derivatives: S3(f, u) = sin f (1 - u^2/2 - cos u) - cos f (sin u - u). */
static void x_eval(const flight *f, double t, double out[3])
{
    const double d = f->m->body.cm_offset_m, w = f->w;
    const double c = f->cos0, s = f->sin0;
    const trig_rems q = rems_at(f, t);
    const double s3 = s * q.rem2 - c * q.rem1;
    const double s3u = s * q.rem1 + c * q.rem0;
    const double s3uu = -s * q.rem0 + c * q.sin_u;
    out[0] = f->x0 + f->vx0 * t + 0.5 * f->ax0 * t * t + d * s3;
    out[1] = f->vx0 + f->ax0 * t + d * w * s3u;
    out[2] = f->ax0 + d * w * w * s3uu;
}

static void to_end_eval(const void *ctx, double t, double out[3])
{
    const flight *f = ctx;
    x_eval(f, t, out);
    out[0] = f->ramp_length - out[0];
    out[1] = -out[1];
    out[2] = -out[2];
}

static void from_top_eval(const void *ctx, double t, double out[3])
{
    x_eval(ctx, t, out);
    out[0] += JC_RAMP_TOP_SLACK_M;
}

static jc_State flight_state(const flight *f, double t, double t0)
{
    double x[3], g[3];
    x_eval(f, t, x);
    gap_eval(f, t, g);
    jc_State s = {.t_s = t0 + t, .x_m = x[0], .y_m = f->m->body.radius_m + g[0],
                  .vx_mps = x[1], .vy_mps = g[1], .theta_rad = f->th0 + f->w * t, .omega_radps = f->w};
    return s;
}

/* Time after which the gap is surely negative: the centre of mass has fallen
 * below r - d, so no point of the rim can still be above the incline. */
static double fall_bound(const flight *f)
{
    const jc_Model *m = f->m;
    const double d = m->body.cm_offset_m, r = m->body.radius_m;
    const double a = 0.5 * m->setup.gravity_mps2 * m->cos_incline;
    const double yg = r + f->y0 + d * cos(f->th0), vyg = f->vy0 - d * f->w * sin(f->th0);
    const double drop = yg - (r - d) + 1e-3; /* 1 mm past: the root is strictly inside */
    return (vyg + sqrt(vyg * vyg + 4.0 * a * drop)) / (2.0 * a);
}

/* The largest gap over [0, T] by the scan of gap' (the general way, kept
 * where the closed-form pieces below would be too many). */
static int largest_gap_scan(const flight *f, double T, gsl_root_fsolver *brent, double *hop, char *err,
                            size_t err_len)
{
    double g[3];
    gap_eval(f, 0.0, g);
    double best = g[0];
    gap_eval(f, T, g);
    best = fmax(best, g[0]);
    const double d = f->m->body.cm_offset_m, w4 = f->w * f->w * f->w * f->w;
    jc_ScanFn fn = {gap_rate_eval, f, d * w4, 0.0, 1.0, NULL, 1, 0.0};
    double t = 0.0;
    for (int pass = 0; pass < 100000 && t < T; ++pass) {
        double r[3];
        gap_rate_eval(f, t, r);
        if (r[0] == 0.0) { t = nextafter(t, INFINITY) + 1e-15; continue; }
        fn.sign = r[0] > 0.0 ? 1.0 : -1.0;
        jc_ScanHit hit;
        int st = jc_scan_fns_with(&fn, 1, t, T, 1e-13, brent, &hit, err, err_len);
        if (st != JC_OK) return st;
        if (hit.index < 0) break;
        gap_eval(f, hit.theta, g);
        best = fmax(best, g[0]);
        t = hit.theta + 1e-13;
    }
    *hop = best;
    return JC_OK;
}

/* More pieces than this (a fast spin over a long flight): the scan. */
#define GAP_PIECES_MAX 64

/* The root of gap' in (a, b), where gap' > 0 at a, < 0 at b and decreases
 * throughout: Newton's iteration on gap'' kept inside the bracket
 * (bisection where it would leave it), to 1e-13 s as the scan's. */
static double gap_rate_root(const flight *f, double a, double b)
{
    double x = 0.5 * (a + b);
    for (int it = 0; it < 200 && b - a > 1e-13; ++it) {
        double g[3];
        gap_eval(f, x, g);
        if (g[1] == 0.0) return x;
        if (g[1] > 0.0) a = x; else b = x;
        double next = g[2] < 0.0 ? x - g[1] / g[2] : 0.5 * (a + b);
        if (!(next > a && next < b)) next = 0.5 * (a + b);
        if (fabs(next - x) < 0.25e-13) return next;
        x = next;
    }
    return 0.5 * (a + b);
}

/* The largest gap over [0, T]: at the ends or at a maximum inside. Written
 * out, gap'' = -g cos a + d w^2 cos(th0 + w t) vanishes only where
 * cos(th0 + w t) = g cos a / (d w^2) =: k, at the angles +-acos(k) + 2 pi n.
 * Between two of them gap' is monotone: it has at most one root there, a
 * maximum of the gap exactly where gap' goes from + to - across the piece
 * (k >= 1: gap' decreases all along, one piece). Each such root is polished
 * by safeguarded Newton: a few evaluations per piece, where a scan of gap'
 * over the whole flight (safe steps under the bound d w^4 on its third
 * derivative) takes many; the hop heights are the same to 2e-15. The scan
 * stays for flights of more than GAP_PIECES_MAX pieces.
 * tests/sim/test_flight.c holds the hop height to a fine grid of the gap. */
static int largest_gap(const flight *f, double T, gsl_root_fsolver *brent, double *hop, char *err, size_t err_len)
{
    const double d = f->m->body.cm_offset_m, w = f->w, gc = f->m->setup.gravity_mps2 * f->m->cos_incline;
    /* The piece ends in t: th0 + w t = +-c + 2 pi n, c = acos(k). */
    double ends[GAP_PIECES_MAX + 2];
    int n_ends = 0;
    ends[n_ends++] = 0.0;
    const double k = d * w * w > 0.0 ? gc / (d * w * w) : INFINITY;
    if (k < 1.0) {
        const double c = acos(k), two_pi = 6.283185307179586477;
        const double lo = fmin(f->th0, f->th0 + w * T), hi = fmax(f->th0, f->th0 + w * T);
        if ((hi - lo) / two_pi * 2.0 + 4.0 > GAP_PIECES_MAX) return largest_gap_scan(f, T, brent, hop, err, err_len);
        double mid[GAP_PIECES_MAX];
        int n_mid = 0;
        for (double base = two_pi * floor((lo - c) / two_pi); base <= hi + c; base += two_pi) {
            const double cand[2] = {base - c, base + c};
            for (int j = 0; j < 2; ++j) {
                const double t = (cand[j] - f->th0) / w;
                if (t > 0.0 && t < T && n_mid < GAP_PIECES_MAX) mid[n_mid++] = t;
            }
        }
        /* Ascending in t (the angles ascend; w < 0 reverses them). */
        for (int i = 0; i < n_mid; ++i) ends[n_ends++] = mid[w > 0.0 ? i : n_mid - 1 - i];
    }
    ends[n_ends++] = T;
    double g[3];
    gap_eval(f, 0.0, g);
    double best = g[0], rate_a = g[1];
    for (int i = 1; i < n_ends; ++i) {
        const double a = ends[i - 1], b = ends[i];
        gap_eval(f, b, g);
        best = fmax(best, g[0]);
        const double rate_b = g[1];
        if (b > a && rate_a > 0.0 && rate_b < 0.0) {
            double top[3];
            gap_eval(f, gap_rate_root(f, a, b), top);
            best = fmax(best, top[0]);
        }
        rate_a = rate_b;
    }
    *hop = best;
    return JC_OK;
}

static int emit_samples(jc_Sim *sim, const flight *f, double t0, double t_end)
{
    double ts;
    while (jc_record_sample_due(sim, t_end, &ts)) {
        jc_State s = flight_state(f, ts - t0, t0);
        s.t_s = ts; /* the grid time itself: t0 + (ts - t0) may round below it */
        int st = jc_record_sample(sim, &s, JC_MODE_FLIGHT, 0.0, 0.0, jc_flight_gap(f->m, &s));
        if (st != JC_OK) return st;
    }
    return JC_OK;
}

enum { FW_GAP, FW_END, FW_TOP };

/* How many times a flight's search may resume past a place where the gap
 * only came within the event tolerance of zero while opening (each resume
 * at least doubles the searched time or advances it by the tolerance). */
#define FLIGHT_MAX_RESUMES 2000
/* A gap that opens from contact more gently than this (kappa below, the
 * cubic term's coefficient relative to d |w|^3 / 6) is searched from 1 ps. */
#define OPENING_KAPPA_MIN 1e-2

int jc_flight_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len)
{
    /* from_liftoff 2: the same flight goes on after a touch without approach;
     * its largest gap so far is kept. */
    const double hop_before = from_liftoff == 2 ? sim->hop_height_m : 0.0;
    if (jc_model_has_resistance(sim->m)) {
        const int st = jc_flight_air_phase(sim, from_liftoff, end, err, err_len);
        sim->hop_height_m = fmax(sim->hop_height_m, hop_before);
        return st;
    }
    flight f;
    rems_cache cache;
    flight_init(sim->m, &sim->s, &cache, &f);
    const double t0 = sim->s.t_s;
    double t_start = 0.0;
    if (from_liftoff) {
        /* At a lift-off the gap, its rate and its acceleration vanish (the
         * N = 0 condition); drop their rounding residues and let the t^3 term
         * open the gap, which starts the search a picosecond in. After a
         * touch without approach the same holds for the gap and its rate. */
        f.y0 = 0.0;
        f.vy0 = fmax(f.vy0, 0.0);
        f.ay0 = fmax(f.ay0, 0.0);
        t_start = 1e-12;
    }
    const double horizon = fmin(fall_bound(&f), sim->opt->t_max_s - t0);
    const double d = sim->m->body.cm_offset_m, w3 = fabs(f.w * f.w * f.w);
    const double tol = sim->opt->event_tol_s;
    jc_ScanFn fns[3] = {
        {gap_eval, &f, d * w3, 0.0, 1.0, NULL, 1, 0.0},
        {to_end_eval, &f, d * w3, 0.0, 1.0, NULL, 1, 0.0},
        {from_top_eval, &f, d * w3, 0.0, 1.0, NULL, 1, 0.0},
    };
    jc_ScanHit hit = {.index = -1};
    double T = horizon;
    int ramp_hit = 0;
    const double kappa = f.w > 0.0 ? -f.sin0 : (f.w < 0.0 ? f.sin0 : 0.0);
    if (from_liftoff && kappa >= OPENING_KAPPA_MIN) {
        /* The gap opening from contact (gap, rate and acceleration >= 0):
         * gap(t) = vy0 t + ay0 t^2/2 + d R3(th0, u), u = w t, and R3 is minus
         * the remainder of cos(th0 + u) after its quadratic Taylor term, by
         * Lagrange's form -sin th0 u^3/6 - cos(th0 + xi) u^4/24
         * >= kappa |u|^3/6 - u^4/24 with kappa = -sin th0 sgn w: the gap is
         * positive for 0 < |u| < 4 kappa. There the safe steps of the search,
         * bounded by d |w|^3 against a gap that grows like t^3, only grow
         * some fivefold each from 1 ps (15 to 19 steps per lift-off). So up
         * to |u| = 2 kappa, where the gap is at least d kappa^4 2/3 (far
         * above its rounding for kappa >= 1e-2), only the ramp's ends are
         * searched; the gap from there on, which spares the crawl. */
        const double t_open = fmin(2.0 * kappa / fabs(f.w), horizon);
        if (t_open > t_start) {
            int st = jc_scan_fns_with(fns + 1, 2, t_start, t_open, tol, sim->ws->brent, &hit, err, err_len);
            if (st != JC_OK) return st;
            if (hit.index >= 0) {
                hit.index += 1; /* fns + 1: FW_END, FW_TOP */
                T = hit.theta;
                ramp_hit = 1;
            }
            t_start = t_open;
        }
    }
    for (int resume = 0; !ramp_hit && horizon > t_start && resume < FLIGHT_MAX_RESUMES; ++resume) {
        int st = jc_scan_fns_with(fns, 3, t_start, horizon, tol, sim->ws->brent, &hit, err, err_len);
        if (st != JC_OK) return st;
        T = hit.index >= 0 ? hit.theta : horizon;
        /* A "grazing" gap root is only a place where the search's safe step
         * fell below the tolerance. If the gap there is still positive and
         * not closing (the t^3 opening just after a lift-off, whose bound on
         * the third derivative, d w^3, can be far above its true value), the
         * rim has not touched: search on from further in. A touch needs an
         * approach. */
        if (hit.index != FW_GAP || !hit.grazing) break;
        double g[3];
        gap_eval(&f, T, g);
        if (!(g[0] > 0.0 && g[1] >= 0.0)) break;
        t_start = fmax(2.0 * T, T + tol);
        hit.index = -1;
        T = horizon;
    }
    int st = largest_gap(&f, T, sim->ws->brent, &sim->hop_height_m, err, err_len);
    if (st != JC_OK) return st;
    sim->hop_height_m = fmax(sim->hop_height_m, hop_before);
    if ((st = emit_samples(sim, &f, t0, t0 + T)) != JC_OK)
        return jc_fail(err, err_len, st, "out of memory for samples");
    sim->s = flight_state(&f, T, t0);
    switch (hit.index) {
    case FW_GAP:
        sim->s.y_m = sim->m->body.radius_m; /* on the incline, up to the located root */
        *end = PHASE_TOUCHDOWN;
        break;
    case FW_END: *end = PHASE_RAMP_END; break;
    case FW_TOP: *end = PHASE_RAMP_TOP; break;
    default: *end = PHASE_TIME_LIMIT; break; /* the fall bound always lies beyond a touchdown */
    }
    return JC_OK;
}
