/* Experiment files, written (docs/config.md): a setup as the small INI file
 * that config.c reads back, every number in the unit a person types and in
 * the shortest form that reads back to the same double. Also the format's
 * tables (config_keys.h), which the reader shares. No inih here: the
 * WebAssembly build (web/) compiles this file and not the reader. */
#define _POSIX_C_SOURCE 200809L
#include "config_keys.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const cli_config_section_names[SEC_PART_FIRST] = {"body", "incline", "contact", "start", "air", "paper"};

const cli_ConfigScalar cli_config_scalars[CLI_CONFIG_SCALAR_COUNT] = {
    {SEC_BODY, "radius", Q_LENGTH, "cm", offsetof(jc_Setup, body.radius_m)},
    {SEC_BODY, "length", Q_LENGTH, "cm", offsetof(jc_Setup, length_m)},
    {SEC_INCLINE, "angle", Q_ANGLE, "deg", offsetof(jc_Setup, incline_rad)},
    {SEC_INCLINE, "gravity", Q_ACCELERATION, "m/s2", offsetof(jc_Setup, gravity_mps2)},
    {SEC_INCLINE, "ramp_length", Q_LENGTH, "m", offsetof(jc_Setup, ramp_length_m)},
    {SEC_CONTACT, "mu_s", Q_NUMBER, "", offsetof(jc_Setup, mu_static)},
    {SEC_CONTACT, "mu_k", Q_NUMBER, "", offsetof(jc_Setup, mu_kinetic)},
    {SEC_CONTACT, "restitution", Q_NUMBER, "", offsetof(jc_Setup, restitution)},
    {SEC_CONTACT, "rolling_resistance", Q_LENGTH, "mm", offsetof(jc_Setup, rolling_resistance_m)},
    {SEC_START, "theta0", Q_ANGLE, "deg", offsetof(jc_Setup, theta0_rad)},
    {SEC_START, "omega0", Q_ANGULAR_SPEED, "rad/s", offsetof(jc_Setup, omega0_radps)},
    {SEC_AIR, "density", Q_DENSITY, "kg/m3", offsetof(jc_Setup, air_density_kgpm3)},
    {SEC_AIR, "drag_coefficient", Q_NUMBER, "", offsetof(jc_Setup, drag_coefficient)},
    {SEC_AIR, "lift_coefficient", Q_NUMBER, "", offsetof(jc_Setup, lift_coefficient)},
    {SEC_AIR, "spin_drag", Q_SPIN_DRAG, "N m s2", offsetof(jc_Setup, spin_drag_Nms2)},
    {SEC_PAPER, "cm_offset", Q_LENGTH, "cm", offsetof(jc_Setup, paper_cm_offset_m)},
};

/* The shortest decimal that reads back to v exactly (%.17g always does). */
static void shortest(double v, char *buf, size_t len)
{
    for (int prec = 1; prec <= 17; ++prec) {
        snprintf(buf, len, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) return;
    }
}

/* v times 10^shift as a decimal, written by moving the decimal point of
 * v's shortest form: the unit parser applies its power of ten to the
 * decimal exponent, so "3.21 cm" reads back to exactly the double of
 * "0.0321" (docs/config.md). */
static void shifted(double v, int shift, char *buf, size_t len)
{
    char e[40];
    int prec = 0;
    for (; prec < 17; ++prec) {
        snprintf(e, sizeof e, "%.*e", prec, v);
        if (strtod(e, NULL) == v) break;
    }
    /* e: [-]d.ddde[+-]xx: the digits and the exponent of the first one */
    const int neg = e[0] == '-';
    char digits[24];
    int nd = 0;
    const char *p = e + neg;
    for (; *p && *p != 'e'; ++p)
        if (*p >= '0' && *p <= '9' && nd < 23) digits[nd++] = *p;
    digits[nd] = '\0';
    const int exp10 = atoi(p + 1) + shift;
    while (nd > 1 && digits[nd - 1] == '0') digits[--nd] = '\0';
    if (v == 0.0) {
        snprintf(buf, len, "%s", neg ? "-0" : "0"); /* -0 stays -0: the dump is exact to the bit */
    } else if (exp10 >= 0 && exp10 < 15) {
        /* the point after digit exp10 */
        char out[48];
        int o = 0;
        if (neg) out[o++] = '-';
        for (int i = 0; i <= exp10; ++i) out[o++] = i < nd ? digits[i] : '0';
        if (nd > exp10 + 1) {
            out[o++] = '.';
            for (int i = exp10 + 1; i < nd; ++i) out[o++] = digits[i];
        }
        out[o] = '\0';
        snprintf(buf, len, "%s", out);
    } else if (exp10 < 0 && exp10 > -7) {
        snprintf(buf, len, "%s0.%0*d%s", neg ? "-" : "", -exp10 - 1, 0, digits);
        if (exp10 == -1) snprintf(buf, len, "%s0.%s", neg ? "-" : "", digits);
    } else {
        snprintf(buf, len, "%s%c%s%s%se%d", neg ? "-" : "", digits[0], nd > 1 ? "." : "", digits + 1, "", exp10);
    }
}

/* v (SI) in the unit a person would type, reading back to v exactly: cm,
 * mm and g by moving the decimal point, degrees when some decimal in
 * degrees reads back exactly (else radians); other units as SI. */
static void write_number(FILE *out, double v, const char *unit)
{
    char buf[64];
    const char *written = unit;
    if (strcmp(unit, "cm") == 0) shifted(v, 2, buf, sizeof buf);
    else if (strcmp(unit, "mm") == 0 || strcmp(unit, "g") == 0) shifted(v, 3, buf, sizeof buf);
    else if (strcmp(unit, "deg") == 0) {
        written = "rad";
        shortest(v, buf, sizeof buf);
        const double deg = v * (180.0 / CLI_PI);
        for (int decimals = 0; decimals <= 16 && fabs(deg) < 1e15; ++decimals) {
            char d[64], err[128];
            double back;
            snprintf(d, sizeof d, "%.*f", decimals, deg);
            char token[80];
            snprintf(token, sizeof token, "%sdeg", d);
            if (cli_parse_quantity(token, Q_ANGLE, &back, err, sizeof err) == 0 && memcmp(&back, &v, sizeof v) == 0) {
                snprintf(buf, sizeof buf, "%s", d);
                written = "deg";
                break;
            }
        }
    } else shortest(v, buf, sizeof buf);
    fprintf(out, "%s%s%s\n", buf, *written ? " " : "", written);
}

static void write_section_scalars(FILE *out, const jc_Setup *s, int sec)
{
    fprintf(out, "\n[%s]\n", cli_config_section_names[sec]);
    for (int i = 0; i < CLI_CONFIG_SCALAR_COUNT; ++i) {
        if (cli_config_scalars[i].section != sec) continue;
        double v;
        memcpy(&v, (const char *)s + cli_config_scalars[i].offset, sizeof v);
        fprintf(out, "%s = ", cli_config_scalars[i].key);
        write_number(out, v, cli_config_scalars[i].unit);
    }
    if (sec == SEC_CONTACT) fprintf(out, "impact_law = %s\n", jc_impact_law_name(s->impact_law));
}

int cli_config_write(FILE *out, const jc_Setup *s)
{
    fputs("# jumpcyl experiment file (docs/config.md): units as a person types them (cm, g,\n"
          "# deg); every number reads back to the same double.\n",
          out);
    write_section_scalars(out, s, SEC_BODY);
    for (int i = 0; i < s->body.part_count && i < JC_MAX_PARTS; ++i) {
        const jc_Part *p = &s->body.parts[i];
        fprintf(out, "\n[part.%d]\nkind = %s\nmass = ", i + 1, jc_part_kind_name(p->kind));
        write_number(out, p->mass_kg, "g");
        fputs("offset = ", out);
        write_number(out, p->offset_m, "cm");
        fputs("radius = ", out);
        write_number(out, p->radius_m, "cm");
        fputs("angle = ", out);
        write_number(out, p->angle_rad, "deg");
    }
    for (int sec = SEC_INCLINE; sec < SEC_PART_FIRST; ++sec) write_section_scalars(out, s, sec);
    return ferror(out) ? -1 : 0;
}
