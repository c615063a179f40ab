/* The default spreads of a Monte Carlo. The paper states its tolerances
 * (docs/physics.md §5.1): r, masses and the rod's offset to the last digit
 * it printed (± 0.05 cm, ± 0.05 g), the initial angle to about ± 3
 * degrees; each is taken as one standard deviation of a normal. It did not
 * measure friction or restitution: Styrofoam on wood lies between mu 0.3
 * and 1.0 for any surface finish, and a foam cylinder on a wooden ramp
 * bounces with e between 0.1 and 0.6, so both are uniform over those
 * ranges. The values are written as a user writes them and read by the
 * parameter table (jc_param_parse), as `jumpcyl mc --sigma` reads its. */
#include "study_internal.h"

static const struct {
    const char *name;
    jc_StudySpread spread;
    const char *a, *b; /* normal: sigma (b unused); uniform: lo, hi */
    const char *why;
} defaults[] = {
    {"radius", JC_STUDY_NORMAL, "0.05cm", NULL, "paper: r +- 0.05 cm"},
    {"disc-mass", JC_STUDY_NORMAL, "0.05g", NULL, "paper: masses +- 0.05 g"},
    {"rod-mass", JC_STUDY_NORMAL, "0.05g", NULL, "paper: masses +- 0.05 g"},
    {"rod-offset", JC_STUDY_NORMAL, "0.05cm", NULL, "paper: offset +- 0.05 cm"},
    {"theta0", JC_STUDY_NORMAL, "3", NULL, "paper: initial angle about +- 3 deg"},
    {"mu", JC_STUDY_UNIFORM, "0.3", "1.0", "not measured: foam on wood"},
    {"restitution", JC_STUDY_UNIFORM, "0.1", "0.6", "not measured: foam on wood"},
};

int jc_study_default_spreads(const jc_Setup *nominal, jc_StudyParam *out, const char **why, int cap)
{
    int n = 0;
    for (size_t k = 0; k < sizeof defaults / sizeof defaults[0]; ++k) {
        const int id = jc_param_find(defaults[k].name);
        double value, a, b = 0.0;
        /* A body without the part (a hoop has no rod) has no such input. */
        if (jc_param_get(nominal, id, &value, NULL, 0) != JC_OK) continue;
        if (jc_param_parse(id, defaults[k].a, &a, NULL, 0) != JC_OK ||
            (defaults[k].b && jc_param_parse(id, defaults[k].b, &b, NULL, 0) != JC_OK))
            continue;
        if (n < cap) {
            if (out) {
                const int normal = defaults[k].spread == JC_STUDY_NORMAL;
                out[n] = (jc_StudyParam){id, defaults[k].spread, NULL, 0, normal ? value : a, normal ? a : b};
            }
            if (why) why[n] = defaults[k].why;
        }
        ++n;
    }
    return n;
}
