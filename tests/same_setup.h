/* Two setups compared bit for bit, field by field (the padding inside the
 * structs is no part of a setup, so memcmp of the whole is unreliable);
 * *what names the first field that differs. For the tests of setups,
 * parameters and experiment files. */
#ifndef JC_TESTS_SAME_SETUP_H
#define JC_TESTS_SAME_SETUP_H

#include <jumpcyl/jumpcyl.h>

#include <string.h>

static inline int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static inline int same_setup(const jc_Setup *a, const jc_Setup *b, const char **what)
{
    *what = "body";
    if (!same_double(a->body.radius_m, b->body.radius_m) || a->body.part_count != b->body.part_count) return 0;
    for (int i = 0; i < a->body.part_count; ++i) {
        const jc_Part *p = &a->body.parts[i], *q = &b->body.parts[i];
        *what = "a part";
        if (p->kind != q->kind || !same_double(p->mass_kg, q->mass_kg) || !same_double(p->offset_m, q->offset_m) ||
            !same_double(p->angle_rad, q->angle_rad) || !same_double(p->radius_m, q->radius_m))
            return 0;
    }
    *what = "impact law";
    if (a->impact_law != b->impact_law) return 0;
    const struct {
        const char *name;
        double a, b;
    } f[] = {
        {"incline", a->incline_rad, b->incline_rad}, {"gravity", a->gravity_mps2, b->gravity_mps2},
        {"mu_s", a->mu_static, b->mu_static}, {"mu_k", a->mu_kinetic, b->mu_kinetic},
        {"restitution", a->restitution, b->restitution}, {"theta0", a->theta0_rad, b->theta0_rad},
        {"omega0", a->omega0_radps, b->omega0_radps}, {"ramp", a->ramp_length_m, b->ramp_length_m},
        {"paper d", a->paper_cm_offset_m, b->paper_cm_offset_m}, {"length", a->length_m, b->length_m},
        {"density", a->air_density_kgpm3, b->air_density_kgpm3}, {"C_d", a->drag_coefficient, b->drag_coefficient},
        {"C_L", a->lift_coefficient, b->lift_coefficient}, {"spin drag", a->spin_drag_Nms2, b->spin_drag_Nms2},
        {"rolling resistance", a->rolling_resistance_m, b->rolling_resistance_m},
    };
    for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i) {
        *what = f[i].name;
        if (!same_double(f[i].a, f[i].b)) return 0;
    }
    return 1;
}

#endif
