/*
 * The seed paper's model, exactly as printed: its Eq. 9,
 *   2 M [d (1 - cos th) cos a + r th sin a] / [M1 r^2/2 + M (r^2 + d^2 + 2 r d cos th)]
 *       = cos a / (d cos th),
 * the left side being th'^2/g from its Eqs. 1, 5 and 6. Kept as its own model
 * so that the printed table can be recomputed line by line; docs/physics.md §5
 * lists where it departs from the exact rolling model.
 */
#include "internal.h"

#include <math.h>

#define PAPER_ROOT_TOL_RAD 1e-12

static const jc_PaperTableRow paper_table[] = {
    {15.0, 18.01, 1.801, 1.850, 0.050},
    {30.0, 11.46, 1.146, 1.150, 0.050},
    {45.0, 5.34, 0.534, 0.550, 0.050},
};

int jc_paper_table(const jc_PaperTableRow **rows)
{
    *rows = paper_table;
    return (int)(sizeof paper_table / sizeof paper_table[0]);
}

int jc_paper_body_is(const jc_BodyDef *body)
{
    const jc_BodyDef p = jc_paper_setup().body;
    if (body->radius_m != p.radius_m || body->part_count != p.part_count) return 0;
    for (int i = 0; i < p.part_count; ++i) {
        const jc_Part *a = &body->parts[i], *b = &p.parts[i];
        if (a->kind != b->kind || a->mass_kg != b->mass_kg || a->offset_m != b->offset_m ||
            a->angle_rad != b->angle_rad || a->radius_m != b->radius_m)
            return 0;
    }
    return 1;
}

double jc_paper_lhs(const jc_Model *m, double th)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, M1 = m->body.disc_mass_kg;
    const double d = m->paper_d_m;
    const double num = d * (1.0 - cos(th)) * m->cos_incline + r * th * m->sin_incline;
    const double den = 0.5 * M1 * r * r + M * (r * r + d * d + 2.0 * r * d * cos(th));
    return 2.0 * M * num / den;
}

double jc_paper_rhs(const jc_Model *m, double th)
{
    return m->cos_incline / (m->paper_d_m * cos(th));
}

int jc_paper_solve(const jc_Model *m, jc_PaperResult *out, char *err, size_t err_len)
{
    *out = (jc_PaperResult){.first = -1,
                            .cm_offset_m = m->paper_d_m,
                            .disc_mass_kg = m->body.disc_mass_kg};
    if (!(m->paper_d_m > 0.0)) return JC_OK; /* d = 0: the right side is infinite */

    const double th_end = m->setup.ramp_length_m / m->body.radius_m; /* x = r th from 0 */
    jc_ScanSet set = {.count = 1, .f = {&jc_model_tables(m)->paper_poly}, .sign = {1.0}};
    double th = 0.0, skip = PAPER_ROOT_TOL_RAD;
    /* Each pass finds one sign change; past it the sign flips (or not, after a touch). */
    for (int pass = 0; pass < 4 * JC_PAPER_MAX_ROOTS && th < th_end; ++pass) {
        double f = jc_tl_value(&jc_model_tables(m)->paper_poly, th);
        if (f == 0.0) { th += skip; skip *= 2.0; continue; }
        set.sign[0] = f > 0.0 ? 1.0 : -1.0;
        jc_ScanHit hit;
        int st = jc_scan_first(&set, th, th_end, PAPER_ROOT_TOL_RAD, &hit, err, err_len);
        if (st != JC_OK) return st;
        if (hit.index < 0) return JC_OK;
        if (cos(hit.theta) > 0.0) {
            if (out->root_count == JC_PAPER_MAX_ROOTS) { out->truncated = 1; return JC_OK; }
            out->theta_rad[out->root_count] = hit.theta;
            out->x_m[out->root_count] = m->body.radius_m * hit.theta;
            if (out->first < 0) out->first = out->root_count;
            out->root_count++;
        }
        skip = PAPER_ROOT_TOL_RAD;
        th = hit.theta + skip;
    }
    return JC_OK;
}
