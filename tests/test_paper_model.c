/* src/paper_model.c: the seed paper's Eq. 9 as printed. Both sides against a
 * transcription made here, every reported root against the equation, and the
 * root set against a dense brute-force sign scan. */
#include "test.h"

#include <jumpcyl/jumpcyl.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Eq. 9 of the paper, transcribed from the seed's TeX:
 *   2M [d(1 - cos th) cos a + r th sin a] / [M1 r^2/2 + M(r^2 + d^2 + 2rd cos th)]
 *     = cos a / (d cos th)                                                       */
typedef struct {
    double M, M1, r, d, a;
} eq9;

static double eq9_lhs(const eq9 *e, double th)
{
    return 2 * e->M * (e->d * (1 - cos(th)) * cos(e->a) + e->r * th * sin(e->a)) /
           (0.5 * e->M1 * e->r * e->r + e->M * (e->r * e->r + e->d * e->d + 2 * e->r * e->d * cos(th)));
}
static double eq9_rhs(const eq9 *e, double th) { return cos(e->a) / (e->d * cos(th)); }
static double eq9_diff(const eq9 *e, double th) { return eq9_lhs(e, th) - eq9_rhs(e, th); }

/* The paper's inputs for a setup, read from the setup (not from the model):
 * M the total mass, M1 the disc parts, d the printed offset if set. */
static eq9 eq9_of(const jc_Setup *s)
{
    eq9 e = {0, 0, s->body.radius_m, 0, s->incline_rad};
    double mx = 0, my = 0;
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_Part *p = &s->body.parts[i];
        e.M += p->mass_kg;
        if (p->kind == JC_PART_DISC) e.M1 += p->mass_kg;
        mx += p->mass_kg * p->offset_m * sin(p->angle_rad);
        my += p->mass_kg * p->offset_m * cos(p->angle_rad);
    }
    e.d = s->paper_cm_offset_m > 0 ? s->paper_cm_offset_m : sqrt(mx * mx + my * my) / e.M;
    return e;
}

static jc_Setup paper_at(double incline_deg)
{
    jc_Setup s = jc_paper_setup();
    s.incline_rad = incline_deg * DEG;
    return s;
}

/* A different body: disc with a point mass and a rod, exact d, steeper, longer ramp. */
static jc_Setup other_setup(void)
{
    jc_Setup s = jc_paper_setup();
    s.body.radius_m = 0.15;
    s.body.part_count = 3;
    s.body.parts[0] = (jc_Part){JC_PART_DISC, 0.200, 0.0, 0.0, 0.15};
    s.body.parts[1] = (jc_Part){JC_PART_POINT, 0.050, 0.12, 0.3, 0.0};
    s.body.parts[2] = (jc_Part){JC_PART_ROD, 0.080, 0.10, -0.4, 0.01};
    s.incline_rad = 40 * DEG;
    s.ramp_length_m = 6.0;
    s.paper_cm_offset_m = 0.0;
    return s;
}

static int test_sides_match_eq9(void)
{
    const jc_Setup setups[] = {paper_at(15), paper_at(30), paper_at(45), other_setup()};
    for (size_t i = 0; i < sizeof setups / sizeof setups[0]; ++i) {
        jc_Model m;
        char err[256] = "";
        ENSURE_OK(jc_model_init(&m, &setups[i], err, sizeof err), err);
        const eq9 e = eq9_of(&setups[i]);
        for (double th = 0.0; th < 40.0; th += 0.0137) {
            /* The same formula in a different order: a few ulps, 1e-14. */
            ENSURE_REL(jc_paper_lhs(&m, th), eq9_lhs(&e, th), 1e-14);
            /* 1/cos th: relative rounding grows like eps |tan th|; none of these samples is within 1e-5 of pi/2. */
            ENSURE_REL(jc_paper_rhs(&m, th), eq9_rhs(&e, th), 1e-14 * (1 + fabs(tan(th))));
        }
    }
    return 0;
}

static int test_paper_inputs(void)
{
    jc_Model m;
    jc_PaperResult p;
    char err[256] = "";
    const jc_Setup s = paper_at(30);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE_OK(jc_paper_solve(&m, &p, err, sizeof err), err);
    ENSURE(p.cm_offset_m == 0.0265);  /* the printed, rounded 2.65 cm */
    ENSURE(p.disc_mass_kg == 0.0342); /* M1 read as the disc's mass */
    return 0;
}

/* Every root: lhs = rhs, cos th > 0, ascending, inside the ramp, x = r th. */
static int check_roots(const jc_Model *m, const jc_PaperResult *p, const eq9 *e)
{
    const double th_end = m->setup.ramp_length_m / m->body.radius_m;
    ENSURE(p->first == (p->root_count > 0 ? 0 : -1));
    for (int i = 0; i < p->root_count; ++i) {
        const double th = p->theta_rad[i];
        ENSURE(cos(th) > 0.0);
        ENSURE(th > 0.0 && th <= th_end * (1 + 1e-15));
        ENSURE(i == 0 || th > p->theta_rad[i - 1]);
        /* Roots are polished to ~1e-12 rad; both sides change by O(10) per rad: 1e-9. */
        ENSURE_REL(eq9_lhs(e, th), eq9_rhs(e, th), 1e-9);
        ENSURE_REL(p->x_m[i], e->r * th, 1e-15);
    }
    return 0;
}

static int test_roots_against_brute_force(void)
{
    const jc_Setup setups[] = {paper_at(15), paper_at(30), paper_at(45), paper_at(10),
                               paper_at(60), other_setup()};
    for (size_t i = 0; i < sizeof setups / sizeof setups[0]; ++i) {
        jc_Model m;
        jc_PaperResult p;
        char err[256] = "";
        ENSURE_OK(jc_model_init(&m, &setups[i], err, sizeof err), err);
        ENSURE_OK(jc_paper_solve(&m, &p, err, sizeof err), err);
        const eq9 e = eq9_of(&setups[i]);
        if (check_roots(&m, &p, &e)) return 1;
        ENSURE(!p.truncated);

        /* Brute force: sign of lhs - rhs every 1e-4 rad from 0 to L / r, only
         * between neighbours that both have cos th > 0 (rhs has poles). */
        const double th_end = setups[i].ramp_length_m / setups[i].body.radius_m, step = 1e-4;
        const long n = (long)ceil(th_end / step);
        int count = 0;
        double prev_th = 0.0, prev_f = eq9_diff(&e, 0.0);
        for (long j = 1; j <= n; ++j) {
            const double th = j < n ? (double)j * step : th_end;
            const double f = eq9_diff(&e, th);
            const int both = cos(th) > 0 && cos(prev_th) > 0;
            if (both && (f > 0) != (prev_f > 0)) {
                ENSURE_MSG(count < p.root_count, "%zu: brute force finds a root in [%.6f, %.6f] beyond the %d reported",
                           i, prev_th, th, p.root_count);
                /* The reported root lies in this bracket (1e-12: its polish tolerance). */
                const double root = p.theta_rad[count];
                ENSURE_MSG(root >= prev_th - 1e-12 && root <= th + 1e-12,
                           "%zu: root #%d %.12f is not in the brute-force bracket [%.6f, %.6f]", i, count, root,
                           prev_th, th);
                /* Bisect the bracket here and compare: both stop at ~1e-12 rad; the
                 * slope of lhs - rhs at these roots is >= ~0.1 per rad, so f's
                 * rounding (~1e-14) moves them by < 1e-12; 1e-10 has room. */
                double lo = prev_th, hi = th;
                for (int it = 0; it < 100; ++it) {
                    const double mid = 0.5 * (lo + hi);
                    if ((eq9_diff(&e, mid) > 0) == (prev_f > 0)) lo = mid; else hi = mid;
                }
                ENSURE_NEAR(root, 0.5 * (lo + hi), 1e-10);
                ++count;
            }
            prev_th = th;
            prev_f = f;
        }
        ENSURE_MSG(count == p.root_count, "%zu: brute force %d roots, jc_paper_solve %d", i, count, p.root_count);
    }
    return 0;
}

static int test_no_roots(void)
{
    char err[256] = "";
    jc_Model m;
    jc_PaperResult p;
    /* d = 0 (uniform disc): the right side is infinite, nothing to intersect. */
    jc_Setup s;
    ENSURE_OK(jc_preset_setup("disc", &s, err, sizeof err), err);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE_OK(jc_paper_solve(&m, &p, err, sizeof err), err);
    ENSURE(p.root_count == 0 && p.first == -1 && !p.truncated);
    /* 2 deg: th'^2/g stays below cos a / (d cos th) on the whole 3.2 m ramp.
     * Checked here: max over th of lhs - rhs where cos th > 0 is negative. */
    s = paper_at(2);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE_OK(jc_paper_solve(&m, &p, err, sizeof err), err);
    const eq9 e = eq9_of(&s);
    double worst = -INFINITY;
    for (double th = 0; th <= 32.0; th += 1e-4)
        if (cos(th) > 0) worst = fmax(worst, eq9_diff(&e, th));
    ENSURE(worst < 0);
    ENSURE(p.root_count == 0 && p.first == -1);
    return 0;
}

static int test_truncation(void)
{
    /* A 200 m ramp at 30 deg: two intersections per turn once th'^2 is large,
     * hundreds in all, more than JC_PAPER_MAX_ROOTS. */
    jc_Setup s = paper_at(30);
    s.ramp_length_m = 200.0;
    jc_Model m;
    jc_PaperResult p;
    char err[256] = "";
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE_OK(jc_paper_solve(&m, &p, err, sizeof err), err);
    ENSURE(p.truncated == 1 && p.root_count == JC_PAPER_MAX_ROOTS);
    const eq9 e = eq9_of(&s);
    return check_roots(&m, &p, &e);
}

static int test_table(void)
{
    /* physics.md §5, Table 1. */
    const jc_PaperTableRow *rows = NULL;
    ENSURE(jc_paper_table(&rows) == 3 && rows);
    const double want[3][5] = {{15, 18.01, 1.801, 1.850, 0.050},
                               {30, 11.46, 1.146, 1.150, 0.050},
                               {45, 5.34, 0.534, 0.550, 0.050}};
    for (int i = 0; i < 3; ++i) {
        ENSURE(rows[i].incline_deg == want[i][0]);
        ENSURE(rows[i].printed_theta_rad == want[i][1]);
        ENSURE(rows[i].printed_x_m == want[i][2]);
        ENSURE(rows[i].measured_x_m == want[i][3]);
        ENSURE(rows[i].measured_error_m == want[i][4]);
        /* The printed position is the printed angle times r = 10.0 cm (to print rounding). */
        ENSURE_NEAR(rows[i].printed_x_m, 0.100 * rows[i].printed_theta_rad, 1e-12);
    }
    return 0;
}

int main(void)
{
    RUN_TEST(test_sides_match_eq9);
    RUN_TEST(test_paper_inputs);
    RUN_TEST(test_roots_against_brute_force);
    RUN_TEST(test_no_roots);
    RUN_TEST(test_truncation);
    RUN_TEST(test_table);
    TEST_MAIN_END();
}
