/*
 * The impact law (docs/physics.md §4): an impulse J = (Jt, Jn) at the contact
 * point P, with R = P - G = (-d sin th, -(r + d cos th)), changes v_G by J/M
 * and w by (Ry Jt - Rx Jn)/I_G. Newton restitution on the normal velocity of
 * P; Coulomb friction in impulse form: stick if the sticking impulse lies in
 * the cone mu_s Jn, else slide with Jt = -mu_k sgn(vt) Jn.
 */
#include "internal.h"

#include <math.h>

void jc_impact_apply(const jc_Model *m, jc_State *s, double e, jc_ImpactResult *out)
{
    const double M = m->body.mass_kg, ig = m->body.inertia_g_kgm2;
    const double r = m->body.radius_m, d = m->body.cm_offset_m;
    const double th = s->theta_rad, w = s->omega_radps;
    const double rx = -d * sin(th), ry = -(r + d * cos(th));
    /* Velocity of G and of the contact point (w is clockwise-positive). */
    const double vgx = s->vx_mps + d * cos(th) * w, vgy = s->vy_mps - d * sin(th) * w;
    const double vt = vgx + w * ry, vn = vgy - w * rx;

    /* dv_P = K J, K the inverse effective mass at P. */
    const double ktt = 1.0 / M + ry * ry / ig, knn = 1.0 / M + rx * rx / ig, ktn = -rx * ry / ig;
    const double want_t = -vt, want_n = -(1.0 + e) * vn;
    const double det = ktt * knn - ktn * ktn;
    double jt = (knn * want_t - ktn * want_n) / det;
    double jn = (ktt * want_n - ktn * want_t) / det;
    *out = (jc_ImpactResult){0};
    out->approach_speed_mps = vn < 0.0 ? -vn : 0.0;
    out->sticks = fabs(jt) <= m->setup.mu_static * jn;
    if (!out->sticks) {
        const double dir = vt > 0.0 ? 1.0 : -1.0;
        const double den = knn - m->setup.mu_kinetic * dir * ktn;
        if (den <= 0.0) {
            out->painleve = 1;
            return;
        }
        jn = want_n / den;
        jt = -m->setup.mu_kinetic * dir * jn;
    }
    const double dw = (ry * jt - rx * jn) / ig;
    const double w1 = w + dw;
    const double vgx1 = vgx + jt / M, vgy1 = vgy + jn / M;
    s->omega_radps = w1;
    s->vx_mps = vgx1 - d * cos(th) * w1;
    s->vy_mps = vgy1 + d * sin(th) * w1;
    out->impulse_normal_Ns = jn;
    out->impulse_tangent_Ns = jt;
    out->rebound_speed_mps = vgy1 - w1 * rx;
}
