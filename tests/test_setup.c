/* src/setup.c (presets, jc_setup_validate), with src/model.c's jc_model_init
 * and src/status.c: the paper's numbers as physics.md states them, every
 * validation path, and what the model precomputes. */
#include "test.h"
#include "same_setup.h"
#include "bad_values.h"

#include <jumpcyl/jumpcyl.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static int test_paper_setup_values(void)
{
    /* physics.md §1 and §5: r 10.0 cm, disc 34.2 g, rod 32.1 g at 5.50 cm with
     * diameter 9.50 mm, g 9.78, ramp 3.20 m, at rest with G on the normal, 30 deg,
     * the paper's model with the printed d = 2.65 cm. Decimal constants: exact match. */
    const jc_Setup s = jc_paper_setup();
    ENSURE(s.body.radius_m == 0.100 && s.body.part_count == 2);
    ENSURE(s.body.parts[0].kind == JC_PART_DISC && s.body.parts[0].mass_kg == 0.0342);
    ENSURE(s.body.parts[0].radius_m == 0.100 && s.body.parts[0].offset_m == 0.0);
    ENSURE(s.body.parts[1].kind == JC_PART_ROD && s.body.parts[1].mass_kg == 0.0321);
    ENSURE(s.body.parts[1].offset_m == 0.0550);
    ENSURE_NEAR(2 * s.body.parts[1].radius_m, 9.50e-3, 1e-18); /* 0.5 * 9.5e-3: exact halving */
    ENSURE_NEAR(s.incline_rad, 30 * DEG, 1e-16);
    ENSURE(s.gravity_mps2 == 9.78 && s.ramp_length_m == 3.20);
    ENSURE(s.theta0_rad == 0.0 && s.omega0_radps == 0.0);
    ENSURE(s.paper_cm_offset_m == 0.0265);
    char err[256] = "";
    ENSURE_OK(jc_setup_validate(&s, err, sizeof err), err);
    return 0;
}

static int test_presets(void)
{
    char err[256] = "";
    int n = 0;
    for (; jc_preset_name(n); ++n) {
        jc_Setup s;
        ENSURE(jc_preset_description(n) != NULL && strlen(jc_preset_description(n)) > 0);
        ENSURE_OK(jc_preset_setup(jc_preset_name(n), &s, err, sizeof err), err);
        ENSURE_OK(jc_setup_validate(&s, err, sizeof err), err);
    }
    ENSURE(n >= 3);
    ENSURE(jc_preset_name(-1) == NULL && jc_preset_description(n) == NULL);

    jc_Setup s;
    ENSURE_OK(jc_preset_setup("paper", &s, err, sizeof err), err);
    const jc_Setup p = jc_paper_setup();
    const char *what;
    ENSURE_MSG(same_setup(&s, &p, &what), "%s differs", what);

    /* disc: the paper's size and mass with d = 0. */
    jc_Model m;
    ENSURE_OK(jc_preset_setup("disc", &s, err, sizeof err), err);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE(m.body.cm_offset_m == 0.0);
    ENSURE_REL(m.body.mass_kg, 0.0663, 1e-15);    /* one part: no sum */
    ENSURE_REL(m.body.radius_m, 0.100, 0.0);

    /* hoop: on a floor, a point mass on the rim on top, a small spin. */
    ENSURE_OK(jc_preset_setup("rocking-hoop", &s, err, sizeof err), err);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE(s.incline_rad == 0.0 && s.theta0_rad == 0.0 && s.omega0_radps > 0.0);
    ENSURE_REL(m.body.cm_offset_m, 0.100 * 0.10 / 0.110, 1e-14); /* m a / M, two ops */

    ENSURE(jc_preset_setup("pendulum", &s, err, sizeof err) == JC_EINVAL);
    ENSURE(strstr(err, "pendulum") != NULL);
    ENSURE(jc_preset_setup(NULL, &s, err, sizeof err) == JC_EINVAL);
    return 0;
}

/* ---- validation ---- */

typedef struct {
    const char *what;
    jc_Setup s;
    const char *key, *value;
} bad_case;

static int check_bad(const bad_case *c)
{
    char err[512] = "";
    int st = jc_setup_validate(&c->s, err, sizeof err);
    ENSURE_MSG(st == JC_EINVAL, "%s: status %d, message '%s'", c->what, st, err);
    ENSURE_MSG(strstr(err, c->key) != NULL, "%s: '%s' does not name '%s'", c->what, err, c->key);
    ENSURE_MSG(!c->value || strstr(err, c->value), "%s: '%s' does not show '%s'", c->what, err, c->value);
    /* jc_model_init refuses the same setup with the same message. */
    jc_Model m;
    char err2[512] = "";
    ENSURE_MSG(jc_model_init(&m, &c->s, err2, sizeof err2) == JC_EINVAL, "%s: model_init accepted it", c->what);
    ENSURE_MSG(strcmp(err, err2) == 0, "%s: '%s' vs '%s'", c->what, err, err2);
    return 0;
}

/* A case from the paper's setup. */
#define PAPER ((bad_case){.s = jc_paper_setup()})

static int test_invalid_setups(void)
{
    BAD_VALUES(PAPER, s.incline_rad, "incline", {-0.01, NULL}, {PI / 2, "90"}, {100 * DEG, "100"}, {NAN, "nan"},
               {INFINITY, "inf"});
    BAD_VALUES(PAPER, s.gravity_mps2, "gravity", {0.0, "0"}, {-9.8, "-9.8"}, {NAN, "nan"}, {INFINITY, "inf"});
    BAD_VALUES(PAPER, s.mu_static, "static friction", {-0.1, "-0.1"}, {NAN, "nan"}, {INFINITY, "inf"});
    BAD_VALUES(PAPER, s.mu_kinetic, "kinetic friction", {-0.2, "-0.2"}, {NAN, "nan"});
    BAD_VALUES(PAPER, s.restitution, "restitution", {-0.1, "-0.1"}, {1.5, "1.5"}, {NAN, "nan"});
    BAD_VALUES(PAPER, s.theta0_rad, "initial angle", {NAN, "nan"}, {-INFINITY, "inf"});
    BAD_VALUES(PAPER, s.omega0_radps, "angular velocity", {NAN, "nan"}, {INFINITY, "inf"});
    BAD_VALUES(PAPER, s.ramp_length_m, "ramp length", {0.0, "0"}, {-1.0, "-1"}, {NAN, "nan"}, {INFINITY, "inf"},
               {2 * PI * 0.1 * JC_MAX_RAMP_TURNS * 1.01, NULL} /* beyond the turn limit */);
    BAD_VALUES(PAPER, s.paper_cm_offset_m, "CM offset", {-0.01, "-0.01"}, {NAN, "nan"},
               {0.2, "0.2"} /* beyond the rim */);
    /* Body errors come through with the body's message. */
    BAD_VALUES(PAPER, s.body.parts[1].mass_kg, "mass", {-0.5, "-0.5"});
    bad_case c = PAPER;
    c.what = "body: no parts", c.key = "parts";
    c.s.body.part_count = 0;
    if (check_bad(&c)) return 1;
    return 0;
}

static int test_valid_edges(void)
{
    char err[256] = "";
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 0.0; /* a floor */
    s.mu_static = s.mu_kinetic = 0.0;
    s.restitution = 1.0;
    ENSURE_OK(jc_setup_validate(&s, err, sizeof err), err);
    s.restitution = 0.0;
    s.incline_rad = 89.9 * DEG;
    s.omega0_radps = -3.0;
    s.theta0_rad = -2.0;
    s.mu_static = 1e6; /* "huge" friction is inside the range */
    ENSURE_OK(jc_setup_validate(&s, err, sizeof err), err);
    return 0;
}

static int test_model_init_precomputes(void)
{
    char err[256] = "";
    jc_Setup s = jc_paper_setup();
    s.incline_rad = 0.4;
    s.theta0_rad = 0.25;
    jc_Model m;
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    const char *what;
    ENSURE_MSG(same_setup(&m.setup, &s, &what), "the model's setup: %s differs", what);
    ENSURE_REL(m.sin_incline, sin(0.4), 0.0);
    ENSURE_REL(m.cos_incline, cos(0.4), 0.0);
    /* The contact point travels r (th - th0): the ramp ends at th0 + L / r. */
    ENSURE_REL(m.theta_end_rad, 0.25 + 3.20 / 0.100, 1e-15);
    ENSURE(m.paper_d_m == 0.0265); /* the printed d */
    s.paper_cm_offset_m = 0.0;      /* 0: the body's exact d */
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    ENSURE_REL(m.paper_d_m, 32.1 * 5.5 / 66.3 * 1e-2, 1e-14);
    return 0;
}

static int test_status_and_version(void)
{
    ENSURE(strcmp(jc_version(), JC_VERSION_STRING) == 0);
    const int codes[] = {JC_OK, JC_EINVAL, JC_ELIMIT, JC_ENUMERIC, JC_ENOMEM, 99};
    for (int i = 0; i < 6; ++i) {
        ENSURE(jc_status_text(codes[i]) && *jc_status_text(codes[i]));
        for (int j = 0; j < i; ++j) ENSURE(strcmp(jc_status_text(codes[i]), jc_status_text(codes[j])) != 0);
    }
    ENSURE(strcmp(jc_status_text(JC_OK), "ok") == 0);
    return 0;
}

int main(void)
{
    RUN_TEST(test_paper_setup_values);
    RUN_TEST(test_presets);
    RUN_TEST(test_invalid_setups);
    RUN_TEST(test_valid_edges);
    RUN_TEST(test_model_init_precomputes);
    RUN_TEST(test_status_and_version);
    TEST_MAIN_END();
}
