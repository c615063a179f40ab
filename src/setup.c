/* Setups: presets and validation of everything a model is built from. */
#include "internal.h"

#include <math.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

/* A body of a 10 cm rim from its first n parts of a, b (n = 1 or 2). */
static jc_BodyDef rim_body(int n, jc_Part a, jc_Part b)
{
    jc_BodyDef body = {.radius_m = 0.100, .part_count = n, .parts = {a, b}};
    if (n < 2) body.parts[1] = (jc_Part){0};
    return body;
}

/* The paper's: Styrofoam disc and brass rod. */
static jc_BodyDef paper_body(void)
{
    return rim_body(2, (jc_Part){JC_PART_DISC, 0.0342, 0.0, 0.0, 0.100},
                    (jc_Part){JC_PART_ROD, 0.0321, 0.0550, 0.0, 0.5 * 9.50e-3});
}

/* The paper's setup with another body, and no printed CM offset. */
static jc_Setup paper_with(jc_BodyDef body)
{
    jc_Setup s = jc_paper_setup();
    s.body = body;
    s.paper_cm_offset_m = 0.0;
    return s;
}

jc_Setup jc_paper_setup(void)
{
    jc_Setup s = {0};
    s.body = paper_body();
    s.incline_rad = 30.0 * DEG;
    s.gravity_mps2 = 9.78;
    /* Friction is not given in the paper; docs/physics.md explains the 0.5. */
    s.mu_static = 0.5;
    s.mu_kinetic = 0.5;
    s.restitution = 0.3;
    s.theta0_rad = 0.0;
    s.omega0_radps = 0.0;
    s.ramp_length_m = 3.20;
    s.paper_cm_offset_m = 0.0265; /* printed, rounded from 2.663 cm */
    s.length_m = 0.0555;          /* "high h = 5.55 cm" */
    s.air_density_kgpm3 = 1.204;  /* resistances stay off: coefficients 0 */
    return s;
}

/* A light hoop with a heavy point mass on its rim, on a floor, started with
 * the mass on top and a small spin: it never hops. It rocks about the mass's
 * lowest position, slipping near each turn while the turning point lies
 * beyond the angle where friction can hold it at rest, so its swing tends to
 * that angle (about 32 deg past the bottom for mu 0.5): a pure-rolling
 * oscillation that goes on for ever without rolling resistance
 * (docs/physics.md §4a). */
static jc_Setup rocking_hoop_setup(void)
{
    jc_Setup s = paper_with(rim_body(2, (jc_Part){JC_PART_HOOP, 0.010, 0.0, 0.0, 0.10},
                                     (jc_Part){JC_PART_POINT, 0.100, 0.10, 0.0, 0.0}));
    s.incline_rad = 0.0;
    s.mu_static = s.mu_kinetic = 0.5;
    s.omega0_radps = 0.1;
    s.ramp_length_m = 3.0;
    return s;
}

/* The classic hopping hoop (Littlewood's problem; Tokieda, "The hopping
 * hoop", Am. Math. Monthly 104 (1997); Theron and Maritz's analysis of the
 * loaded hoop with friction): the same light hoop and heavy mass, rolled at
 * 8 rad/s with the mass on top. Why 8 rad/s: the rim's lowest point leaves
 * the floor where d w^2 cos th >= g (docs/physics.md §4a). With the mass on
 * top that needs w >= sqrt(g/d) = 10.4 rad/s (d = 9.09 cm), which rolling from
 * 8 rad/s never reaches on top; but as the mass comes up again behind the
 * centre the spin is larger (the mass's fall has fed it) and cos th is still
 * large: d w^2 cos th reaches g about 55 deg before the top, after a slip,
 * and the hoop hops (about 8 cm), then bounces. At 6.5 rad/s the criterion
 * is never met and the hoop only rolls and rocks (measured: 7 rad/s hops). */
static jc_Setup hoop_setup(void)
{
    jc_Setup s = rocking_hoop_setup();
    s.omega0_radps = 8.0;
    return s;
}

static jc_Setup disc_setup(void)
{
    const jc_Part disc = {JC_PART_DISC, 0.0663, 0.0, 0.0, 0.10};
    return paper_with(rim_body(1, disc, disc));
}

static const struct {
    const char *name, *description;
    jc_Setup (*make)(void);
} presets[] = {
    {"paper", "the seed paper's Styrofoam disc with a brass rod, 30 deg incline, 3.20 m ramp", jc_paper_setup},
    {"hoop", "hopping hoop: light hoop (10 g), 100 g point mass on its rim, on a floor, mass on top, 8 rad/s", hoop_setup},
    {"rocking-hoop", "the same hoop at 0.1 rad/s: it never hops, it rocks (slipping near each turn) for ever",
     rocking_hoop_setup},
    {"disc", "uniform disc of the paper's size and mass (d = 0), 30 deg incline", disc_setup},
};
#define PRESET_COUNT ((int)(sizeof presets / sizeof presets[0]))

const char *jc_preset_name(int i) { return i >= 0 && i < PRESET_COUNT ? presets[i].name : NULL; }
const char *jc_preset_description(int i) { return i >= 0 && i < PRESET_COUNT ? presets[i].description : NULL; }

int jc_preset_setup(const char *name, jc_Setup *out, char *err, size_t err_len)
{
    for (int i = 0; i < PRESET_COUNT; ++i) {
        if (name && strcmp(name, presets[i].name) == 0) {
            *out = presets[i].make();
            return JC_OK;
        }
    }
    return jc_fail(err, err_len, JC_EINVAL, "unknown preset '%s' (allowed: paper, hoop, rocking-hoop, disc)", name ? name : "(null)");
}

static int check_range(const char *what, const char *unit, double v, double lo, int lo_open,
                       double hi, int hi_open, char *err, size_t err_len)
{
    int ok = isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (ok) return JC_OK;
    /* "restitution 2 is ..." and "gravity 0 m/s2 is ... (0, 1000] m/s2)": a
     * blank before the unit only when there is one. */
    const char *blank = *unit ? " " : "";
    return jc_fail(err, err_len, JC_EINVAL, "%s %g%s%s is out of range (allowed: %s%g, %g%s%s%s)",
                   what, v, blank, unit, lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]", blank, unit);
}

int jc_setup_has_resistance(const jc_Setup *s)
{
    const int air = (s->drag_coefficient != 0.0 || s->lift_coefficient != 0.0) &&
                    s->air_density_kgpm3 != 0.0 && s->length_m != 0.0;
    return air || s->spin_drag_Nms2 != 0.0 || s->rolling_resistance_m != 0.0;
}

int jc_setup_validate(const jc_Setup *s, char *err, size_t err_len)
{
    jc_Body body;
    int st = jc_body_compute(&s->body, &body, err, err_len);
    if (st != JC_OK) return st;
    if (!isfinite(s->incline_rad) || s->incline_rad < 0.0 || s->incline_rad >= JC_MAX_INCLINE_RAD)
        return jc_fail(err, err_len, JC_EINVAL, "incline %g deg is out of range (allowed: [0, 90) deg)", s->incline_rad / DEG);
    /* From a micro-g up: a subnormal g (2e-322) made a flight's time -inf
     * and its state NaN (found by fuzzing). */
    if ((st = check_range("gravity", "m/s2", s->gravity_mps2, 1e-6, 0, 1e3, 0, err, err_len))) return st;
    if ((st = check_range("static friction", "", s->mu_static, 0.0, 0, 1e6, 0, err, err_len))) return st;
    if ((st = check_range("kinetic friction", "", s->mu_kinetic, 0.0, 0, 1e6, 0, err, err_len))) return st;
    /* mu_k > mu_s has no consistent frictional impulse when an impact's slip
     * stops with mu_s Ktt < |Ktn| <= mu_k Ktt (neither sticking nor sliding
     * either way fits), nor a consistent contact mode at the same edge in
     * sliding: refused rather than resolved by a choice (docs/physics.md §4). */
    if (s->mu_kinetic > s->mu_static)
        return jc_fail(err, err_len, JC_EINVAL,
                       "kinetic friction %g is larger than static friction %g (allowed: mu_k <= mu_s)",
                       s->mu_kinetic, s->mu_static);
    if ((st = check_range("restitution", "", s->restitution, 0.0, 0, 1.0, 0, err, err_len))) return st;
    if (s->impact_law != JC_IMPACT_STRONGE && s->impact_law != JC_IMPACT_POISSON && s->impact_law != JC_IMPACT_NEWTON)
        return jc_fail(err, err_len, JC_EINVAL, "impact law %d is unknown (allowed: stronge, poisson, newton)",
                       (int)s->impact_law);
    if ((st = check_range("initial angle", "rad", s->theta0_rad, -1e4, 0, 1e4, 0, err, err_len))) return st;
    if ((st = check_range("initial angular velocity", "rad/s", s->omega0_radps, -1e4, 0, 1e4, 0, err, err_len))) return st;
    const double max_ramp = JC_MAX_RAMP_TURNS * 2.0 * 3.14159265358979323846 * s->body.radius_m;
    if ((st = check_range("ramp length", "m", s->ramp_length_m, 0.0, 1, max_ramp, 0, err, err_len))) return st;
    if ((st = check_range("paper-model CM offset", "m", s->paper_cm_offset_m, 0.0, 0, s->body.radius_m, 0, err, err_len))) return st;
    if ((st = check_range("length", "m", s->length_m, 0.0, 0, 1e3, 0, err, err_len))) return st;
    if ((st = check_range("air density", "kg/m3", s->air_density_kgpm3, 0.0, 0, 100.0, 0, err, err_len))) return st;
    if ((st = check_range("drag coefficient", "", s->drag_coefficient, 0.0, 0, 100.0, 0, err, err_len))) return st;
    if ((st = check_range("lift coefficient", "", s->lift_coefficient, -100.0, 0, 100.0, 0, err, err_len))) return st;
    if ((st = check_range("spin drag", "N m s2", s->spin_drag_Nms2, 0.0, 0, 1e3, 0, err, err_len))) return st;
    if ((st = check_range("rolling resistance", "m", s->rolling_resistance_m, 0.0, 0, 0.5 * s->body.radius_m, 0, err, err_len))) return st;
    if ((s->drag_coefficient > 0.0 || s->lift_coefficient != 0.0) && !(s->length_m > 0.0 && s->air_density_kgpm3 > 0.0))
        return jc_fail(err, err_len, JC_EINVAL,
                       "drag or lift needs a length > 0 m and an air density > 0 kg/m3 (length %g m, density %g kg/m3)",
                       s->length_m, s->air_density_kgpm3);
    return JC_OK;
}
