/* src/body.c: mass properties of composite bodies, checked against sums done
 * by hand here, and every validation path of jc_body_compute. */
#include "test.h"
#include "bad_values.h"

#include <jumpcyl/jumpcyl.h>

#define PI 3.14159265358979323846

/* Sums of a handful of products: a few ulps of relative rounding, so 1e-14. */
#define SUM_TOL 1e-14

static jc_BodyDef paper_body(void) { return jc_paper_setup().body; }

/* A 50 g disc filling a 10 cm rim plus one more part. */
static jc_BodyDef disc_plus(jc_Part p)
{
    jc_BodyDef b = {0};
    b.radius_m = 0.10;
    b.part_count = 2;
    b.parts[0] = (jc_Part){JC_PART_DISC, 0.050, 0.0, 0.0, 0.10};
    b.parts[1] = p;
    return b;
}

/* Computes `def` into `b`; a failure ends the test with the library's message. */
#define BODY_OK(def, b)                                                                        \
    do {                                                                                       \
        char body_err_[256] = "";                                                              \
        ENSURE_OK(jc_body_compute(&(def), &(b), body_err_, sizeof body_err_), body_err_);      \
    } while (0)

static int test_paper_body_by_hand(void)
{
    jc_BodyDef def = paper_body();
    jc_Body b;
    BODY_OK(def, b);
    /* The paper: disc 34.2 g r = 10 cm; rod 32.1 g at 5.50 cm, diameter 9.50 mm. */
    const double M = 0.0663, d = 32.1 * 5.5 / 66.3 * 1e-2;
    const double ic = 0.5 * 0.0342 * 0.1 * 0.1 + 0.0321 * (0.055 * 0.055 + 0.5 * 0.00475 * 0.00475);
    ENSURE_REL(b.mass_kg, M, SUM_TOL);
    ENSURE_REL(b.cm_offset_m, d, SUM_TOL);
    ENSURE_NEAR(b.cm_offset_m * 100, 2.663, 0.0005); /* physics.md prints d = 2.663 cm (3 decimals) */
    ENSURE_REL(b.inertia_c_kgm2, ic, SUM_TOL);
    /* I_G = I_C - M d^2 loses ~1 digit to cancellation (M d^2 is 18% of I_C). */
    ENSURE_REL(b.inertia_g_kgm2, ic - M * d * d, 1e-13);
    ENSURE_NEAR(b.cm_angle_rad, 0.0, 0.0); /* the rod sits at angle 0 exactly */
    ENSURE_REL(b.disc_mass_kg, 0.0342, 0.0);
    ENSURE(b.radius_m == 0.100);
    return 0;
}

static int test_hoop_inertia(void)
{
    /* A 20 g hoop of radius 3 cm, its axis 6 cm off C: I = m R^2 + m a^2. */
    jc_BodyDef def = disc_plus((jc_Part){JC_PART_HOOP, 0.020, 0.06, 0.0, 0.03});
    jc_Body b;
    BODY_OK(def, b);
    const double ic = 0.5 * 0.050 * 0.01 + (0.020 * 0.03 * 0.03 + 0.020 * 0.06 * 0.06);
    ENSURE_REL(b.inertia_c_kgm2, ic, SUM_TOL);
    ENSURE_REL(b.cm_offset_m, 0.020 * 0.06 / 0.070, SUM_TOL);
    ENSURE_REL(b.disc_mass_kg, 0.050, 0.0); /* a hoop is not a disc */

    /* A lone centred hoop: I_C = I_G = m r^2, d = 0. */
    jc_BodyDef h = {.radius_m = 0.1, .part_count = 1};
    h.parts[0] = (jc_Part){JC_PART_HOOP, 0.3, 0.0, 0.0, 0.1};
    BODY_OK(h, b);
    ENSURE_REL(b.inertia_c_kgm2, 0.3 * 0.01, SUM_TOL);
    ENSURE_REL(b.inertia_g_kgm2, 0.3 * 0.01, SUM_TOL);
    ENSURE(b.cm_offset_m == 0.0 && b.cm_angle_rad == 0.0 && b.disc_mass_kg == 0.0);
    return 0;
}

static int test_point_and_rod_inertia(void)
{
    jc_Body b;
    /* Point: I = m a^2. */
    jc_BodyDef def = disc_plus((jc_Part){JC_PART_POINT, 0.030, 0.08, 0.0, 0.0});
    BODY_OK(def, b);
    ENSURE_REL(b.inertia_c_kgm2, 0.5 * 0.050 * 0.01 + 0.030 * 0.08 * 0.08, SUM_TOL);
    ENSURE_REL(b.mass_kg, 0.080, SUM_TOL);
    /* Line-mass rod (radius 0) is a point in cross-section. */
    jc_BodyDef line = disc_plus((jc_Part){JC_PART_ROD, 0.030, 0.08, 0.0, 0.0});
    jc_Body bl;
    BODY_OK(line, bl);
    ENSURE_REL(bl.inertia_c_kgm2, b.inertia_c_kgm2, 0.0);
    /* Rod with its own radius rho: I = m a^2 + m rho^2 / 2. */
    jc_BodyDef rod = disc_plus((jc_Part){JC_PART_ROD, 0.030, 0.08, 0.0, 0.01});
    BODY_OK(rod, b);
    ENSURE_REL(b.inertia_c_kgm2, 0.5 * 0.050 * 0.01 + 0.030 * (0.08 * 0.08 + 0.5 * 0.01 * 0.01), SUM_TOL);
    /* A smaller off-centre disc: I = m R^2/2 + m a^2; disc_mass counts both discs. */
    jc_BodyDef dd = disc_plus((jc_Part){JC_PART_DISC, 0.010, 0.05, 1.0, 0.02});
    BODY_OK(dd, b);
    ENSURE_REL(b.inertia_c_kgm2, 0.5 * 0.050 * 0.01 + 0.010 * (0.5 * 0.02 * 0.02 + 0.05 * 0.05), SUM_TOL);
    ENSURE_REL(b.disc_mass_kg, 0.060, SUM_TOL);
    return 0;
}

static int test_disc_mass_sums_discs_only(void)
{
    jc_BodyDef def = {.radius_m = 0.1, .part_count = 5};
    def.parts[0] = (jc_Part){JC_PART_DISC, 0.040, 0.0, 0.0, 0.1};
    def.parts[1] = (jc_Part){JC_PART_HOOP, 0.015, 0.0, 0.0, 0.1};
    def.parts[2] = (jc_Part){JC_PART_DISC, 0.007, 0.06, 2.0, 0.03};
    def.parts[3] = (jc_Part){JC_PART_ROD, 0.020, 0.05, -1.0, 0.004};
    def.parts[4] = (jc_Part){JC_PART_POINT, 0.005, 0.09, 0.5, 0.0};
    jc_Body b;
    BODY_OK(def, b);
    ENSURE_REL(b.disc_mass_kg, 0.047, SUM_TOL);
    ENSURE_REL(b.mass_kg, 0.087, SUM_TOL);
    /* The full hand sum, CM as a vector sum in the body frame (sin, cos). */
    double mx = 0, my = 0, ic = 0;
    for (int i = 0; i < def.part_count; ++i) {
        const jc_Part *p = &def.parts[i];
        const double own = p->kind == JC_PART_HOOP ? p->mass_kg * p->radius_m * p->radius_m
                                                   : 0.5 * p->mass_kg * p->radius_m * p->radius_m;
        mx += p->mass_kg * p->offset_m * sin(p->angle_rad);
        my += p->mass_kg * p->offset_m * cos(p->angle_rad);
        ic += own + p->mass_kg * p->offset_m * p->offset_m;
    }
    ENSURE_REL(b.cm_offset_m, sqrt(mx * mx + my * my) / 0.087, SUM_TOL);
    ENSURE_NEAR(b.cm_angle_rad, atan2(mx, my), 1e-14); /* |angle| ~ 1: a few ulps */
    ENSURE_REL(b.inertia_c_kgm2, ic, SUM_TOL);
    ENSURE_REL(b.inertia_g_kgm2, ic - 0.087 * b.cm_offset_m * b.cm_offset_m, 1e-13);
    return 0;
}

static int test_opposite_points_cancel(void)
{
    const double phis[] = {0.0, 0.3, 1.0, PI / 2, 2.5, -2.0};
    for (size_t i = 0; i < sizeof phis / sizeof phis[0]; ++i) {
        jc_BodyDef def = disc_plus((jc_Part){JC_PART_POINT, 0.025, 0.07, phis[i], 0.0});
        def.parts[2] = (jc_Part){JC_PART_POINT, 0.025, 0.07, phis[i] + PI, 0.0};
        def.part_count = 3;
        jc_Body b;
        BODY_OK(def, b);
        /* d is zero up to the rounding of sin/cos (phi + pi is not exact): ~1e-16 * a. */
        ENSURE_NEAR(b.cm_offset_m, 0.0, 1e-15 * 0.07);
        ENSURE_REL(b.inertia_c_kgm2, 0.5 * 0.050 * 0.01 + 2 * 0.025 * 0.07 * 0.07, SUM_TOL);
        ENSURE_REL(b.inertia_g_kgm2, b.inertia_c_kgm2, SUM_TOL);
    }
    return 0;
}

static int test_cm_angle_direction(void)
{
    /* A single offset part at angle phi puts G at angle phi: d = m a / M. */
    const double phis[] = {0.0, 0.1, 1.0, PI / 2, 2.0, 3.0, -0.5, -2.5, -PI / 2};
    for (size_t i = 0; i < sizeof phis / sizeof phis[0]; ++i) {
        jc_BodyDef def = disc_plus((jc_Part){JC_PART_ROD, 0.030, 0.05, phis[i], 0.002});
        jc_Body b;
        BODY_OK(def, b);
        ENSURE_REL(b.cm_offset_m, 0.030 * 0.05 / 0.080, SUM_TOL);
        ENSURE_NEAR(b.cm_angle_rad, phis[i], 1e-14); /* atan2 of sin, cos: a few ulps of pi */
    }
    /* Angles wrap: 2 pi + phi is phi. */
    jc_BodyDef def = disc_plus((jc_Part){JC_PART_ROD, 0.030, 0.05, 2 * PI + 0.7, 0.0});
    jc_Body b;
    BODY_OK(def, b);
    ENSURE_NEAR(b.cm_angle_rad, 0.7, 1e-14);
    return 0;
}

static int test_part_touching_rim_allowed(void)
{
    /* offset + radius == r exactly, and with rounding (0.07 + 0.03 != 0.1 in binary). */
    jc_BodyDef def = disc_plus((jc_Part){JC_PART_ROD, 0.01, 0.07, 0.0, 0.03});
    jc_Body b;
    BODY_OK(def, b);
    def = disc_plus((jc_Part){JC_PART_POINT, 0.01, 0.10, 0.0, 0.0});
    BODY_OK(def, b);
    ENSURE(strcmp(jc_part_kind_name(JC_PART_DISC), "disc") == 0);
    ENSURE(strcmp(jc_part_kind_name(JC_PART_HOOP), "hoop") == 0);
    ENSURE(strcmp(jc_part_kind_name(JC_PART_ROD), "rod") == 0);
    ENSURE(strcmp(jc_part_kind_name(JC_PART_POINT), "point") == 0);
    return 0;
}

/* ---- validation: every path returns JC_EINVAL and names the field and value ---- */

typedef struct {
    const char *what;
    jc_BodyDef def;
    const char *key;   /* a word of the field the message must contain */
    const char *value; /* the value as the message prints it (NULL: not checked) */
} bad_case;

static int check_bad(const bad_case *c)
{
    jc_Body b;
    char err[512] = "";
    const int st = jc_body_compute(&c->def, &b, err, sizeof err);
    ENSURE_MSG(st == JC_EINVAL, "%s: status %d, message '%s'", c->what, st, err);
    ENSURE_MSG(strstr(err, c->key) != NULL, "%s: '%s' does not name '%s'", c->what, err, c->key);
    ENSURE_MSG(!c->value || strstr(err, c->value), "%s: '%s' does not show '%s'", c->what, err, c->value);
    ENSURE_MSG(strchr(err, '\n') == NULL, "%s: message is not one line", c->what);
    return 0;
}

/* A case from the paper's body (a disc, part 1, and a rod, part 2). */
#define PAPER_BODY ((bad_case){.def = paper_body()})

static int test_invalid_parts(void)
{
    BAD_VALUES(PAPER_BODY, def.parts[1].mass_kg, "mass", {-0.01, "-0.01"}, {NAN, "nan"}, {INFINITY, "inf"});
    BAD_VALUES(PAPER_BODY, def.parts[1].offset_m, "offset", {-0.02, "-0.02"}, {NAN, "nan"}, {INFINITY, "inf"});
    BAD_VALUES(PAPER_BODY, def.parts[1].angle_rad, "angle", {NAN, "nan"}, {-INFINITY, "inf"});
    BAD_VALUES(PAPER_BODY, def.parts[1].radius_m, "radius", {NAN, "nan"}, {INFINITY, "inf"}, {-0.001, "-0.001"});
    BAD_VALUES(PAPER_BODY, def.parts[1].offset_m, "rim", {0.098, "0.098"} /* the rod outside the rim */);
    /* The message says which part: the rod is part 2. */
    BAD_VALUES(PAPER_BODY, def.parts[1].mass_kg, "part 2", {-1.0, NULL});
    BAD_VALUES(PAPER_BODY, def.parts[0].radius_m, "radius", {0.0, "0"}, {-0.05, "-0.05"});
    BAD_VALUES(PAPER_BODY, def.parts[0].radius_m, "rim", {0.11, "0.11"} /* the disc larger than the rim */);

    bad_case c = {"unknown kind", paper_body(), "kind", "7"};
    c.def.parts[1].kind = (jc_PartKind)7;
    if (check_bad(&c)) return 1;
    c = (bad_case){"hoop radius 0", disc_plus((jc_Part){JC_PART_HOOP, 0.01, 0.0, 0.0, 0.0}), "radius", NULL};
    if (check_bad(&c)) return 1;
    c = (bad_case){"point with a radius", disc_plus((jc_Part){JC_PART_POINT, 0.01, 0.05, 0.0, 0.002}),
                   "radius", "0.002"};
    if (check_bad(&c)) return 1;
    c = (bad_case){"point outside the rim", disc_plus((jc_Part){JC_PART_POINT, 0.01, 0.1001, 0.0, 0.0}),
                   "rim", "0.1001"};
    if (check_bad(&c)) return 1;
    return 0;
}

static int test_invalid_body(void)
{
    BAD_VALUES(PAPER_BODY, def.radius_m, "radius", {0.0, "0"}, {-0.1, "-0.1"}, {NAN, "nan"}, {INFINITY, "inf"});

    bad_case c = {"no parts", paper_body(), "parts", "0"};
    c.def.part_count = 0;
    if (check_bad(&c)) return 1;
    c.what = "negative part count", c.def.part_count = -3, c.value = "-3";
    if (check_bad(&c)) return 1;
    c.what = "too many parts", c.def.part_count = JC_MAX_PARTS + 1, c.value = "17";
    if (check_bad(&c)) return 1;

    c = (bad_case){"zero total mass", paper_body(), "total mass", "0"};
    c.def.parts[0].mass_kg = 0.0;
    c.def.parts[1].mass_kg = 0.0;
    if (check_bad(&c)) return 1;
    /* Finite masses whose sum (and the model's products) would overflow:
     * each part's mass is bounded, so the total cannot overflow. */
    c = (bad_case){"huge masses", paper_body(), "part 1 (disc): mass", "1.5e+308 kg is out of range (allowed: [0, 1e+06] kg)"};
    c.def.parts[0].mass_kg = 1.5e308;
    c.def.parts[1].mass_kg = 1.5e308;
    if (check_bad(&c)) return 1;
    /* A lone point at the centre. */
    c = (bad_case){"point at the centre", {.radius_m = 0.1, .part_count = 1}, "inertia", NULL};
    c.def.parts[0] = (jc_Part){JC_PART_POINT, 0.1, 0.0, 0.0, 0.0};
    if (check_bad(&c)) return 1;
    return 0;
}

static int test_single_point_mass_has_no_inertia(void)
{
    /* A lone point mass has I_G = m a^2 - M d^2 = 0 exactly, whatever m, a and
     * the angle; it must always be rejected, not only when the rounding of
     * I_C - M d^2 happens to land on <= 0. */
    int rejected = 0, total = 0;
    for (int im = 1; im <= 9; ++im) {
        for (int ia = 1; ia <= 9; ++ia) {
            for (int iphi = 0; iphi < 8; ++iphi) {
                bad_case c = {"single point mass", {.radius_m = 0.1, .part_count = 1}, "inertia", NULL};
                c.def.parts[0] = (jc_Part){JC_PART_POINT, 0.0137 * im, 0.0109 * ia, 0.77 * iphi, 0.0};
                jc_Body b;
                char err[512] = "";
                ++total;
                if (jc_body_compute(&c.def, &b, err, sizeof err) == JC_EINVAL && strstr(err, "inertia"))
                    ++rejected;
                else if (total - rejected == 1)
                    fprintf(stderr, "accepted: point m = %.17g kg, a = %.17g m, angle %.17g rad, I_G = %g\n",
                            c.def.parts[0].mass_kg, c.def.parts[0].offset_m, c.def.parts[0].angle_rad,
                            b.inertia_g_kgm2);
            }
        }
    }
    ENSURE_MSG(rejected == total, "%d of %d single point masses accepted", total - rejected, total);
    /* Two point masses at the same place are one point mass too. */
    bad_case c = {"two coincident points", {.radius_m = 0.1, .part_count = 2}, "inertia", NULL};
    c.def.parts[0] = (jc_Part){JC_PART_POINT, 0.1426, 0.0607, 0.1024, 0.0};
    c.def.parts[1] = (jc_Part){JC_PART_POINT, 0.0500, 0.0607, 0.1024, 0.0};
    return check_bad(&c);
}

static int test_error_buffer_optional(void)
{
    jc_BodyDef def = paper_body();
    def.parts[1].mass_kg = -1.0;
    jc_Body b;
    ENSURE(jc_body_compute(&def, &b, NULL, 0) == JC_EINVAL);
    char small[8];
    memset(small, 'x', sizeof small);
    ENSURE(jc_body_compute(&def, &b, small, sizeof small) == JC_EINVAL);
    ENSURE(memchr(small, '\0', sizeof small) != NULL); /* truncated, terminated */
    return 0;
}

int main(void)
{
    RUN_TEST(test_paper_body_by_hand);
    RUN_TEST(test_hoop_inertia);
    RUN_TEST(test_point_and_rod_inertia);
    RUN_TEST(test_disc_mass_sums_discs_only);
    RUN_TEST(test_opposite_points_cancel);
    RUN_TEST(test_cm_angle_direction);
    RUN_TEST(test_part_touching_rim_allowed);
    RUN_TEST(test_invalid_parts);
    RUN_TEST(test_invalid_body);
    RUN_TEST(test_single_point_mass_has_no_inertia);
    RUN_TEST(test_error_buffer_optional);
    TEST_MAIN_END();
}
