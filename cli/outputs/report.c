/* Output helpers shared by the commands. */
#include "outputs.h"

#include <errno.h>
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

const char *cli_gnuplot_load_prefix(const char *path)
{
    return path[0] == '<' || path[0] == '|' || path[0] == '-' ? "./" : "";
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
    /* Then every parameter that has a member (jc_ParamInfo json_key), in the table's order. */
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        double v;
        if (!in->json_key || jc_param_get(s, id, &v, NULL, 0) != JC_OK) continue;
        const size_t n = strlen(in->json_key);
        const int degrees = n > 4 && strcmp(in->json_key + n - 4, "_deg") == 0;
        cJSON_AddNumberToObject(o, in->json_key, degrees ? cli_deg(v) : v);
    }
    return o;
}

/* A number, or null for an infinite one (JSON has none). */
static void add_number_or_null(cJSON *o, const char *key, double v)
{
    if (isfinite(v)) cJSON_AddNumberToObject(o, key, v);
    else cJSON_AddNullToObject(o, key);
}

static void add_string_or_null(cJSON *o, const char *key, const char *v)
{
    if (v) cJSON_AddStringToObject(o, key, v);
    else cJSON_AddNullToObject(o, key);
}

/* One parameter: its description and every preset's value. */
static cJSON *json_param(int id)
{
    const jc_ParamInfo *in = jc_param_info(id);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", in->name);
    cJSON_AddStringToObject(o, "label", in->label);
    cJSON_AddStringToObject(o, "help", in->help);
    cJSON_AddStringToObject(o, "quantity", jc_quantity_name(in->quantity));
    cJSON_AddStringToObject(o, "si_unit", in->si_unit);
    cJSON_AddStringToObject(o, "unit", in->unit);
    cJSON *units = cJSON_AddArrayToObject(o, "units");
    double to_si;
    for (int k = 0; jc_quantity_unit(in->quantity, k, &to_si); ++k) {
        cJSON *u = cJSON_CreateObject();
        cJSON_AddStringToObject(u, "name", jc_quantity_unit(in->quantity, k, NULL));
        cJSON_AddNumberToObject(u, "si", to_si);
        cJSON_AddItemToArray(units, u);
    }
    add_number_or_null(o, "min", in->min);
    add_number_or_null(o, "max", in->max);
    cJSON_AddBoolToObject(o, "min_open", in->min_open);
    cJSON_AddBoolToObject(o, "max_open", in->max_open);
    add_string_or_null(o, "bound", in->bound);
    if (in->choices) {
        cJSON *c = cJSON_AddArrayToObject(o, "choices");
        for (int k = 0; in->choices[k]; ++k) cJSON_AddItemToArray(c, cJSON_CreateString(in->choices[k]));
    } else {
        cJSON_AddNullToObject(o, "choices");
    }
    add_string_or_null(o, "sets", in->sets);
    cJSON_AddBoolToObject(o, "body", (in->flags & JC_PARAM_BODY) != 0);
    cJSON_AddBoolToObject(o, "shortcut", (in->flags & JC_PARAM_SHORTCUT) != 0);
    cJSON_AddStringToObject(o, "section", in->section);
    cJSON_AddStringToObject(o, "key", in->key);
    add_string_or_null(o, "json_key", in->json_key);
    cJSON_AddNumberToObject(o, "typical_min", in->typical_min);
    cJSON_AddNumberToObject(o, "typical_max", in->typical_max);
    cJSON *defaults = cJSON_AddObjectToObject(o, "defaults");
    cJSON *texts = cJSON_AddObjectToObject(o, "defaults_text");
    for (int k = 0; jc_preset_name(k); ++k) {
        jc_Setup s;
        double v;
        char text[80];
        const int has = jc_preset_setup(jc_preset_name(k), &s, NULL, 0) == JC_OK && jc_param_get(&s, id, &v, NULL, 0) == JC_OK &&
                        jc_param_format(id, v, text, sizeof text) == JC_OK;
        if (has) {
            cJSON_AddNumberToObject(defaults, jc_preset_name(k), v);
            cJSON_AddStringToObject(texts, jc_preset_name(k), text);
        } else {
            cJSON_AddNullToObject(defaults, jc_preset_name(k));
            cJSON_AddNullToObject(texts, jc_preset_name(k));
        }
    }
    return o;
}

cJSON *cli_json_params(void)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON *presets = cJSON_AddArrayToObject(doc, "presets");
    for (int k = 0; jc_preset_name(k); ++k) cJSON_AddItemToArray(presets, cJSON_CreateString(jc_preset_name(k)));
    cJSON *params = cJSON_AddArrayToObject(doc, "params");
    for (int id = 0; id < jc_param_count(); ++id) cJSON_AddItemToArray(params, json_param(id));
    return doc;
}

int cli_json_print(cJSON *doc)
{
    char *text = cli_json_text(doc, 1);
    cJSON_Delete(doc);
    if (!text) {
        cli_error("could not format the JSON output (out of memory)");
        return EXIT_FAIL;
    }
    const int ok = puts(text) >= 0 && fflush(stdout) == 0;
    const int err = errno;
    free(text);
    if (ok) return EXIT_OK;
    /* A reader that went away is not told (main.c returns SIGPIPE's status). */
    if (err != EPIPE) cli_error("cannot write standard output: %s", strerror(err));
    return EXIT_FAIL;
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
