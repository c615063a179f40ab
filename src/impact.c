/*
 * The impact law (docs/physics.md §4). An impulse p = (pt, pn) at the contact
 * point P, with R = P - G = (-d sin th, -(r + d cos th)), changes v_G by p/M
 * and w by (Rn pt - Rt pn)/I_G, so the contact point's velocity changes by
 * K p, K = [[Ktt, Ktn], [Ktn, Knn]] symmetric positive definite.
 *
 * Default: Darboux-Keller integration in the normal impulse pn with Stronge's
 * energetic restitution. pn only grows, so it is the impact's clock; while
 * the slip direction s is fixed (or the contact sticks), v is linear in pn,
 * so every piece (slide, stick, slide after reversal) ends at a closed-form
 * root. There are at most two pieces: a slide that brings vt to 0, then stick
 * or reversed slide, which never end (vt stays 0 or grows). Normal work in
 * compression W_c = int vn dpn < 0; restitution stops when its work is
 * -e^2 W_c (Stronge) or when pn = (1 + e) pc (Poisson). The kinetic energy
 * changes by the friction work (<= 0) plus the normal work -(1 - e^2)|W_c|
 * under Stronge's law, so that law never creates energy.
 *
 * Newton's law (v_n after = -e v_n before, sticking if the cone holds the
 * sticking impulse) is kept as it was, a named alternative: it can gain
 * energy when the contact sticks.
 */
#include "internal.h"

#include <math.h>
#include <string.h>

const char *jc_impact_law_name(jc_ImpactLaw law)
{
    switch (law) {
    case JC_IMPACT_STRONGE: return "stronge";
    case JC_IMPACT_POISSON: return "poisson";
    case JC_IMPACT_NEWTON: return "newton";
    }
    return "unknown";
}

int jc_impact_law_parse(const char *name, jc_ImpactLaw *out)
{
    static const jc_ImpactLaw laws[] = {JC_IMPACT_STRONGE, JC_IMPACT_POISSON, JC_IMPACT_NEWTON};
    for (size_t i = 0; name && i < sizeof laws / sizeof laws[0]; ++i) {
        if (strcmp(name, jc_impact_law_name(laws[i])) == 0) {
            *out = laws[i];
            return JC_OK;
        }
    }
    return JC_EINVAL;
}

/* One piece of the impulse: vt, vn and pt change linearly with pn. */
typedef struct {
    int stick;      /* 1: vt held at 0 */
    double s;       /* slide direction (sgn vt), when not sticking */
    double at, an;  /* dvt/dpn, dvn/dpn */
    double ft;      /* dpt/dpn */
} piece;

static piece slide_piece(const jc_ImpactInput *in, double s)
{
    const double mu = in->mu_kinetic;
    return (piece){0, s, in->ktn - mu * s * in->ktt, in->knn - mu * s * in->ktn, -mu * s};
}

/* At vt = 0: stick when the cone holds the impulse ratio that keeps vt = 0,
 * |Ktn|/Ktt <= mu_s; otherwise slip grows in the direction sgn(Ktn) (with
 * mu_k <= mu_s, which jc_setup_validate enforces, that slide is consistent:
 * |Ktn| > mu_k Ktt). Also the start's direction when vt = 0 before the impact. */
static piece zero_slip_piece(const jc_ImpactInput *in)
{
    if (fabs(in->ktn) <= in->mu_static * in->ktt) {
        const double det = in->ktt * in->knn - in->ktn * in->ktn;
        return (piece){1, 0.0, 0.0, det / in->ktt, -in->ktn / in->ktt};
    }
    return slide_piece(in, in->ktn > 0.0 ? 1.0 : -1.0);
}

/* The x >= 0 at which the work of a piece, x v + a x^2 / 2 (v >= 0), reaches
 * rem >= 0: the quadratic's root, written without cancellation. */
static double work_root(double v, double a, double rem)
{
    const double disc = v * v + 2.0 * a * rem;
    if (rem <= 0.0) return 0.0;
    if (disc < 0.0) return INFINITY; /* a < 0: the work never reaches rem */
    return 2.0 * rem / (v + sqrt(disc));
}

int jc_impact_solve(const jc_ImpactInput *in, jc_ImpulseOut *out)
{
    memset(out, 0, sizeof *out);
    double vt = in->vt, vn = in->vn, pn = 0.0, pt = 0.0;
    if (!(vn < 0.0)) {
        out->vt = vt;
        out->vn = vn;
        return JC_OK; /* no approach, no impulse */
    }
    /* A slip within rounding of zero is none: the direction of a rounding
     * residue must not decide between sticking and sliding. */
    if (fabs(vt) <= in->slip_tol) vt = 0.0;
    piece pc = vt != 0.0 ? slide_piece(in, vt > 0.0 ? 1.0 : -1.0) : zero_slip_piece(in);
    double work_c = 0.0, work_r = 0.0, pn_c = 0.0;
    int compressing = 1;
    const double e = in->restitution;
    /* At most: slide to vt = 0, stick or reversed slide to vn = 0, then
     * restitution; 8 leaves room for the phases' coincidences. */
    for (int k = 0; k < 8; ++k) {
        const double x_slip = !pc.stick && pc.s * pc.at < 0.0 ? -vt / pc.at : INFINITY;
        double x_end;
        if (compressing) {
            x_end = pc.an > 0.0 ? -vn / pc.an : INFINITY;
        } else if (in->law == JC_IMPACT_POISSON) {
            x_end = fmax((1.0 + e) * pn_c - pn, 0.0);
        } else {
            x_end = work_root(vn, pc.an, -e * e * work_c - work_r);
        }
        const int slip_first = x_slip < x_end;
        const double x = slip_first ? x_slip : x_end;
        if (!isfinite(x)) {
            out->inconsistent = 1; /* cannot happen with K positive definite */
            return JC_ENUMERIC;
        }
        const double w = x * (vn + 0.5 * pc.an * x);
        if (compressing) work_c += w;
        else work_r += w;
        pn += x;
        pt += pc.ft * x;
        vn += pc.an * x;
        vt = pc.stick ? 0.0 : vt + pc.at * x;
        if (slip_first) {
            vt = 0.0;
            out->slip_stopped = 1;
            pc = zero_slip_piece(in);
            out->sticks = pc.stick;
            out->reversed = !pc.stick;
            continue;
        }
        if (compressing) {
            vn = 0.0;
            compressing = 0;
            pn_c = pn;
            out->work_compression = work_c;
            if (e == 0.0) break;
            continue;
        }
        break;
    }
    out->pn = pn;
    out->pt = pt;
    out->pn_compression = pn_c;
    out->work_restitution = work_r;
    out->vt = (vt == 0.0 && fabs(in->vt) <= in->slip_tol ? 0.0 : in->vt) + in->ktt * pt + in->ktn * pn;
    out->vn = in->vn + in->ktn * pt + in->knn * pn;
    return JC_OK;
}

void jc_impact_input(const jc_Model *m, const jc_State *s, jc_ImpactInput *in)
{
    const double M = m->body.mass_kg, ig = m->body.inertia_g_kgm2;
    const double r = m->body.radius_m, d = m->body.cm_offset_m;
    const double w = s->omega_radps;
    /* The inline sincos, not libm's sin and cos (each a call through the
     * PLT). */
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs);
    const double rx = -d * sn, ry = -(r + d * cs);
    /* Velocity of G and of the contact point (w is clockwise-positive). */
    const double vgx = s->vx_mps + d * cs * w, vgy = s->vy_mps - d * sn * w;
    in->vt = vgx + w * ry;
    in->vn = vgy - w * rx;
    in->ktt = 1.0 / M + ry * ry / ig;
    in->knn = 1.0 / M + rx * rx / ig;
    in->ktn = -rx * ry / ig;
    in->mu_static = m->setup.mu_static;
    in->mu_kinetic = m->setup.mu_kinetic;
    in->law = m->setup.impact_law;
    in->restitution = 0.0;
    in->slip_tol = JC_NO_SLIP_MPS;
}

/* Newton's law: the sticking impulse if the cone holds it, else a slide in the
 * direction of the slip (of the friction sticking needed, when there is no slip). */
static void newton_solve(const jc_ImpactInput *in, double e, double *jt_out, double *jn_out, int *sticks,
                         int *painleve)
{
    const double want_t = -in->vt, want_n = -(1.0 + e) * in->vn;
    const double det = in->ktt * in->knn - in->ktn * in->ktn;
    double jt = (in->knn * want_t - in->ktn * want_n) / det;
    double jn = (in->ktt * want_n - in->ktn * want_t) / det;
    *sticks = fabs(jt) <= in->mu_static * jn;
    *painleve = 0;
    if (!*sticks) {
        const double dir = in->vt != 0.0 ? (in->vt > 0.0 ? 1.0 : -1.0) : (jt < 0.0 ? 1.0 : -1.0);
        const double den = in->knn - in->mu_kinetic * dir * in->ktn;
        if (den <= 0.0) {
            *painleve = 1;
            jt = jn = 0.0;
        } else {
            jn = want_n / den;
            jt = -in->mu_kinetic * dir * jn;
        }
    }
    *jt_out = jt;
    *jn_out = jn;
}

void jc_impact_apply_law(const jc_Model *m, jc_State *s, jc_ImpactLaw law, double e, jc_ImpactResult *out)
{
    const double ig = m->body.inertia_g_kgm2, M = m->body.mass_kg;
    const double r = m->body.radius_m, d = m->body.cm_offset_m;
    double sn, cs;
    jc_sincos(s->theta_rad, &sn, &cs); /* inline, as in jc_impact_input */
    const double rx = -d * sn, ry = -(r + d * cs);
    jc_ImpactInput in;
    jc_impact_input(m, s, &in);
    in.law = law;
    in.restitution = e;
    *out = (jc_ImpactResult){0};
    out->approach_speed_mps = in.vn < 0.0 ? -in.vn : 0.0;
    double jt = 0.0, jn = 0.0;
    if (in.vn < 0.0) {
        if (law == JC_IMPACT_NEWTON) {
            newton_solve(&in, e, &jt, &jn, &out->sticks, &out->painleve);
            if (out->painleve) return;
        } else {
            jc_ImpulseOut o;
            if (jc_impact_solve(&in, &o) != JC_OK) {
                out->painleve = 1;
                return;
            }
            jt = o.pt;
            jn = o.pn;
            out->sticks = o.sticks;
            out->reversed = o.reversed;
        }
    }
    const double w = s->omega_radps;
    const double vgx = s->vx_mps + d * cs * w, vgy = s->vy_mps - d * sn * w;
    const double w1 = w + (ry * jt - rx * jn) / ig;
    const double vgx1 = vgx + jt / M, vgy1 = vgy + jn / M;
    s->omega_radps = w1;
    s->vx_mps = vgx1 - d * cs * w1;
    s->vy_mps = vgy1 + d * sn * w1;
    out->impulse_normal_Ns = jn;
    out->impulse_tangent_Ns = jt;
    out->rebound_speed_mps = vgy1 - w1 * rx;
}

void jc_impact_apply(const jc_Model *m, jc_State *s, double e, jc_ImpactResult *out)
{
    jc_impact_apply_law(m, s, m->setup.impact_law, e, out);
}
