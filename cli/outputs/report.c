/* Output helpers shared by the commands. */
#include "outputs.h"

#include <math.h>
#include <stdarg.h>
#include <string.h>

double cli_deg(double rad) { return rad * 180.0 / CLI_PI; }

double cli_shown(double v, int decimals)
{
    /* A value that rounds to zero at this many decimals prints as 0, never
     * as -0 (a normal force of -1e-17 N at a lift-off is zero). */
    return fabs(v) < 0.5 * pow(10.0, -decimals) ? 0.0 : v;
}

void cli_shell_word(FILE *out, const char *s)
{
    if (*s && s[strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./:+=%,")] == '\0') {
        fputs(s, out);
        return;
    }
    fputc('\'', out);
    for (; *s; ++s) {
        if (*s == '\'') fputs("'\\''", out);
        else fputc((unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s, out);
    }
    fputc('\'', out);
}

void cli_print_setup(FILE *out, const jc_Model *m, int show_incline)
{
    const jc_Setup *s = &m->setup;
    const jc_Body *b = &m->body;
    fprintf(out, "Body:  r = %.2f cm, M = %.2f g, d = %.4f cm, I_C = %.4e kg m2, I_G = %.4e kg m2 (",
            b->radius_m * 100, b->mass_kg * 1e3, b->cm_offset_m * 100, b->inertia_c_kgm2, b->inertia_g_kgm2);
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_Part *p = &s->body.parts[i];
        fprintf(out, "%s%s %.4g g", i ? ", " : "", jc_part_kind_name(p->kind), p->mass_kg * 1e3);
        if (p->offset_m > 0) fprintf(out, " at %.4g cm", p->offset_m * 100);
        if (p->kind != JC_PART_POINT && p->radius_m > 0)
            fprintf(out, " radius %.4g cm", p->radius_m * 100);
    }
    fprintf(out, ")\n");
    if (show_incline) fprintf(out, "Setup: incline %.2f deg, ", cli_deg(s->incline_rad));
    else fprintf(out, "Setup: incline per column, ");
    fprintf(out, "g = %.4g m/s2, mu_s = %.3g, mu_k = %.3g, e = %.3g, "
                 "theta0 = %.4g deg, omega0 = %.4g rad/s, ramp %.3f m\n",
            s->gravity_mps2, s->mu_static, s->mu_kinetic, s->restitution,
            cli_deg(s->theta0_rad), s->omega0_radps, s->ramp_length_m);
}

#include <cjson/cJSON.h>
#include <stdlib.h>

cJSON *cli_json_crossing(const jc_RollingCrossing *c)
{
    if (!c->found) return cJSON_CreateNull();
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "theta", c->state.theta_rad);
    cJSON_AddNumberToObject(o, "x", c->state.x_m);
    cJSON_AddNumberToObject(o, "omega", c->state.omega_radps);
    cJSON_AddNumberToObject(o, "normal", c->state.normal_N);
    cJSON_AddNumberToObject(o, "friction", c->state.friction_N);
    cJSON_AddBoolToObject(o, "grazing", c->grazing);
    return o;
}

cJSON *cli_json_setup(const jc_Model *m)
{
    const jc_Setup *s = &m->setup;
    cJSON *o = cJSON_CreateObject();
    cJSON *body = cJSON_AddObjectToObject(o, "body");
    cJSON_AddNumberToObject(body, "radius", m->body.radius_m);
    cJSON_AddNumberToObject(body, "mass", m->body.mass_kg);
    cJSON_AddNumberToObject(body, "cm_offset", m->body.cm_offset_m);
    cJSON_AddNumberToObject(body, "inertia_c", m->body.inertia_c_kgm2);
    cJSON_AddNumberToObject(body, "inertia_g", m->body.inertia_g_kgm2);
    cJSON *parts = cJSON_AddArrayToObject(body, "parts");
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_Part *p = &s->body.parts[i];
        cJSON *q = cJSON_CreateObject();
        cJSON_AddStringToObject(q, "kind", jc_part_kind_name(p->kind));
        cJSON_AddNumberToObject(q, "mass", p->mass_kg);
        cJSON_AddNumberToObject(q, "offset", p->offset_m);
        cJSON_AddNumberToObject(q, "angle", p->angle_rad);
        cJSON_AddNumberToObject(q, "radius", p->radius_m);
        cJSON_AddItemToArray(parts, q);
    }
    cJSON_AddNumberToObject(o, "incline_deg", cli_deg(s->incline_rad));
    cJSON_AddNumberToObject(o, "g", s->gravity_mps2);
    cJSON_AddNumberToObject(o, "mu_s", s->mu_static);
    cJSON_AddNumberToObject(o, "mu_k", s->mu_kinetic);
    cJSON_AddNumberToObject(o, "restitution", s->restitution);
    cJSON_AddNumberToObject(o, "theta0", s->theta0_rad);
    cJSON_AddNumberToObject(o, "omega0", s->omega0_radps);
    cJSON_AddNumberToObject(o, "ramp_length", s->ramp_length_m);
    cJSON_AddNumberToObject(o, "length", s->length_m);
    cJSON_AddNumberToObject(o, "air_density", s->air_density_kgpm3);
    cJSON_AddNumberToObject(o, "drag_coefficient", s->drag_coefficient);
    cJSON_AddNumberToObject(o, "lift_coefficient", s->lift_coefficient);
    cJSON_AddNumberToObject(o, "spin_drag", s->spin_drag_Nms2);
    cJSON_AddNumberToObject(o, "rolling_resistance", s->rolling_resistance_m);
    return o;
}

int cli_json_print(cJSON *doc)
{
    char *text = doc ? cJSON_Print(doc) : NULL;
    cJSON_Delete(doc);
    if (!text) {
        cli_error("could not format the JSON output (out of memory)");
        return EXIT_FAIL;
    }
    int ok = puts(text) >= 0;
    free(text);
    if (!ok || fflush(stdout) != 0) {
        cli_error("could not write to standard output");
        return EXIT_FAIL;
    }
    return EXIT_OK;
}

cJSON *cli_json_event(const jc_Event *e)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "kind", jc_event_name(e->kind));
    cJSON_AddStringToObject(o, "mode_before", jc_mode_name(e->mode_before));
    cJSON_AddStringToObject(o, "mode_after", jc_mode_name(e->mode_after));
    cJSON_AddNumberToObject(o, "t", e->state.t_s);
    cJSON_AddNumberToObject(o, "x", e->state.x_m);
    cJSON_AddNumberToObject(o, "y", e->state.y_m);
    cJSON_AddNumberToObject(o, "theta", e->state.theta_rad);
    cJSON_AddNumberToObject(o, "omega", e->state.omega_radps);
    cJSON_AddNumberToObject(o, "vx", e->state.vx_mps);
    cJSON_AddNumberToObject(o, "vy", e->state.vy_mps);
    cJSON_AddNumberToObject(o, "slip", e->slip_mps);
    cJSON_AddNumberToObject(o, "normal", e->normal_N);
    cJSON_AddNumberToObject(o, "friction", e->friction_N);
    if (e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT)) {
        cJSON_AddNumberToObject(o, "flight_time", e->flight_time_s);
        cJSON_AddNumberToObject(o, "hop_height", e->hop_height_m);
        if (isnan(e->landing_x_m)) cJSON_AddNullToObject(o, "landing_x");
        else cJSON_AddNumberToObject(o, "landing_x", e->landing_x_m);
    }
    if (e->kind == JC_EVENT_TOUCHDOWN || e->kind == JC_EVENT_BOUNCE) {
        cJSON_AddNumberToObject(o, "impact_speed", e->impact_speed_mps);
        cJSON_AddNumberToObject(o, "impulse_normal", e->impulse_normal_Ns);
        cJSON_AddNumberToObject(o, "impulse_tangent", e->impulse_tangent_Ns);
    }
    return o;
}

cJSON *cli_json_energy(const jc_EnergyReport *e)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "kinetic", e->kinetic_J);
    cJSON_AddNumberToObject(o, "potential", e->potential_J);
    cJSON_AddNumberToObject(o, "friction_loss", e->friction_loss_J);
    cJSON_AddNumberToObject(o, "impact_loss", e->impact_loss_J);
    cJSON_AddNumberToObject(o, "air_loss", e->air_loss_J);
    cJSON_AddNumberToObject(o, "rolling_resistance_loss", e->rolling_resistance_loss_J);
    cJSON_AddNumberToObject(o, "balance_error", e->balance_error_J);
    return o;
}
