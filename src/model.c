/*
 * jc_Model: a validated setup with everything the models read precomputed.
 * Built once, then only read: any number of predictions and runs may share it.
 *
 * The rolling quantities are stored as the exact functions of th they are
 * (docs/physics.md §2), cleared of the positive factor I_P(th): the rolling
 * law of rolling_law.h without loads (th'', N, F at a state), times I_P^2,
 * with w^2 from the energy integral, so that rolling from a start is a set
 * of functions of th alone, which the crossing search (scan.c) needs:
 *   P(th)      = I_P w^2        = e - 2 U(th),  e = I_P(th0) w0^2 + 2 U(th0)
 *   Z(th)      = I_P^2 th''     = M g Q I_P + M r d sin(th) P
 *   N I_P^2    = M [ g cos(a) I_P^2 - d sin(th) Z - d cos(th) P I_P ]
 *   F I_P^2    = M [ (r + d cos th) Z - d sin(th) P I_P - g sin(a) I_P^2 ]
 * N I_P^2 and F I_P^2 are affine in the energy constant e; the model keeps
 * both parts, and no start: rolling is built from any state when it starts
 * (rolling.c), so that one model serves runs from any state.
 * with I_P = I_C + M r^2 + 2 M r d cos th,
 *      U   = M g [ (r + d cos th) cos a - (r th + d sin th) sin a ],
 *      Q   = (r + d cos th) sin a + d sin th cos a.
 * The model also keeps the rolling law's constants, with its resistances
 * and without them (jc_RollConsts).
 */
#include "internal.h"

#include <math.h>
#include <string.h>

static void tl_const(jc_TrigLin *p, double c)
{
    jc_tl_zero(p);
    jc_tl_add_cos(p, 0, 0, c);
}

/* a + b cos th + c sin th */
static void tl_first_order(jc_TrigLin *p, double a, double b, double c)
{
    tl_const(p, a);
    jc_tl_add_cos(p, 0, 1, b);
    jc_tl_add_sin(p, 0, 1, c);
}

static int build_rolling(const jc_Model *m, jc_ModelTables *tb)
{
    const double M = m->body.mass_kg, d = m->body.cm_offset_m, r = m->body.radius_m;
    const double g = m->setup.gravity_mps2, sa = m->sin_incline, ca = m->cos_incline;

    jc_TrigLin ip, u, q, sin1, cos1, rdc, t1, t2, t3;
    tl_first_order(&ip, m->body.inertia_c_kgm2 + M * r * r, 2.0 * M * r * d, 0.0);
    tl_first_order(&u, M * g * r * ca, M * g * d * ca, -M * g * d * sa);
    jc_tl_add_cos(&u, 1, 0, -M * g * r * sa);
    tl_first_order(&q, r * sa, d * sa, d * ca);
    tl_first_order(&sin1, 0.0, 0.0, 1.0);
    tl_first_order(&cos1, 0.0, 1.0, 0.0);
    tl_first_order(&rdc, r, d, 0.0);
    tb->inertia_p_poly = ip;
    tb->potential_poly = u;

    /* With P = I_P w^2 = e - 2 U:  N I_P^2 = n0 + P n1,  F I_P^2 = f0 + P f1. */
    int st = 0;
    jc_TrigLin qip, ip2, n0, n1, f0, f1, sin2, sinip, cosip;
    st |= jc_tl_mul(&qip, &q, &ip);
    st |= jc_tl_mul(&ip2, &ip, &ip);
    st |= jc_tl_mul(&sin2, &sin1, &sin1);
    st |= jc_tl_mul(&sinip, &sin1, &ip);
    st |= jc_tl_mul(&cosip, &cos1, &ip);
    st |= jc_tl_mul(&t1, &sin1, &qip);                 /* sin Q I_P */
    jc_tl_axpby(&n0, M * g * ca, &ip2, -M * M * g * d, &t1);
    jc_tl_axpby(&n1, -M * M * r * d * d, &sin2, -M * d, &cosip);
    st |= jc_tl_mul(&t2, &rdc, &qip);                  /* (r + d cos) Q I_P */
    jc_tl_axpby(&f0, M * M * g, &t2, -M * g * sa, &ip2);
    st |= jc_tl_mul(&t3, &rdc, &sin1);                 /* (r + d cos) sin */
    jc_tl_axpby(&f1, M * M * r * d, &t3, -M * d, &sinip);

    /* Fold P = e - 2U in: part_a = x0 - 2 U x1, part_b = x1. */
    st |= jc_tl_mul(&t1, &u, &n1);
    jc_tl_axpby(&tb->roll_normal_a, 1.0, &n0, -2.0, &t1);
    tb->roll_normal_b = n1;
    st |= jc_tl_mul(&t1, &u, &f1);
    jc_tl_axpby(&tb->roll_friction_a, 1.0, &f0, -2.0, &t1);
    tb->roll_friction_b = f1;
    return st ? JC_ENUMERIC : JC_OK;
}

/* The paper's Eq. 9 cleared of denominators:
 *   f = 2 M d cos(th) num - cos(a) den,
 *   num = d (1 - cos th) cos a + r th sin a,
 *   den = M1 r^2 / 2 + M (r^2 + d^2 + 2 r d cos th);
 * for cos th > 0, f > 0 exactly when th'^2/g > cos(a) / (d cos th). */
static int build_paper(const jc_Model *m, jc_ModelTables *tb)
{
    const double M = m->body.mass_kg, r = m->body.radius_m, M1 = m->body.disc_mass_kg;
    const double d = m->paper_d_m, sa = m->sin_incline, ca = m->cos_incline;
    jc_TrigLin num, den, cos1, t;
    tl_first_order(&num, d * ca, -d * ca, 0.0);
    jc_tl_add_cos(&num, 1, 0, r * sa);
    tl_first_order(&den, 0.5 * M1 * r * r + M * (r * r + d * d), 2.0 * M * r * d, 0.0);
    tl_first_order(&cos1, 0.0, 1.0, 0.0);
    if (jc_tl_mul(&t, &cos1, &num) != JC_OK) return JC_ENUMERIC;
    jc_tl_axpby(&tb->paper_poly, 2.0 * M * d, &t, -ca, &den);
    return JC_OK;
}

int jc_model_init(jc_Model *model, const jc_Setup *setup, char *err, size_t err_len)
{
    int st = jc_setup_validate(setup, err, err_len);
    if (st != JC_OK) return st;
    memset(model, 0, sizeof *model);
    model->setup = *setup;
    st = jc_body_compute(&setup->body, &model->body, err, err_len);
    if (st != JC_OK) return st;
    model->sin_incline = sin(setup->incline_rad);
    model->cos_incline = cos(setup->incline_rad);
    model->theta_end_rad = setup->theta0_rad + setup->ramp_length_m / model->body.radius_m;
    model->paper_d_m = setup->paper_cm_offset_m > 0.0 ? setup->paper_cm_offset_m
                                                      : model->body.cm_offset_m;
    _Static_assert(sizeof(jc_ModelTables) <= sizeof model->internal.reserved, "jc_Model's private room is too small");
    jc_ModelTables *tb = (jc_ModelTables *)(void *)model->internal.reserved;
    tb->has_resistance = jc_setup_has_resistance(setup);
    jc_roll_consts(model, 1, &tb->roll);
    jc_roll_consts(model, 0, &tb->roll_bare);
    tb->inv_mass_per_kg = 1.0 / model->body.mass_kg;
    tb->inv_inertia_g = 1.0 / model->body.inertia_g_kgm2;
    if (build_rolling(model, tb) != JC_OK || build_paper(model, tb) != JC_OK)
        return jc_fail(err, err_len, JC_ENUMERIC, "internal error: polynomial degree exceeded");
    return JC_OK;
}
