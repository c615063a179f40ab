/* Experiment files, written (docs/config.md): a setup as the small INI file
 * that config.c reads back, every parameter under its table's section and
 * key, in its table's unit and in the shortest form that reads back to the
 * same double (jc_param_format). Also the format's sections
 * (inputs.h), which the reader shares. No inih here: the WebAssembly
 * build (web/) compiles this file and not the reader. */
#define _POSIX_C_SOURCE 200809L
#include "inputs.h"

#include <stdio.h>
#include <string.h>

int cli_config_sections(const char *names[CLI_CONFIG_SECTION_MAX])
{
    int n = 0;
    for (int id = 0; id < jc_param_count(); ++id) {
        const char *sec = jc_param_info(id)->section;
        int k = 0;
        while (k < n && strcmp(names[k], sec) != 0) ++k;
        if (k == n && n < CLI_CONFIG_SECTION_MAX) names[n++] = sec;
    }
    return n;
}

int cli_config_written(const jc_ParamInfo *in) { return !(in->flags & JC_PARAM_SHORTCUT); }

/* "key = value unit": the parameter's value in its own unit (jc_param_format). */
static void write_param(FILE *out, const jc_Setup *s, int id)
{
    char text[80];
    double v = 0.0;
    jc_param_get(s, id, &v, NULL, 0);
    jc_param_format(id, v, text, sizeof text);
    fprintf(out, "%s = %s\n", jc_param_info(id)->key, text);
}

/* A section's keys: its numbers, then its names (the impact law). */
static void write_section(FILE *out, const jc_Setup *s, const char *sec)
{
    fprintf(out, "\n[%s]\n", sec);
    for (int names = 0; names < 2; ++names)
        for (int id = 0; id < jc_param_count(); ++id) {
            const jc_ParamInfo *in = jc_param_info(id);
            if (strcmp(in->section, sec) == 0 && cli_config_written(in) && (in->quantity == JC_Q_NAME) == names)
                write_param(out, s, id);
        }
}

/* v (SI) in unit, reading back to v exactly (jc_quantity_format). */
static void write_number(FILE *out, double v, jc_Quantity q, const char *unit)
{
    char text[80];
    jc_quantity_format(v, q, unit, text, sizeof text);
    fprintf(out, "%s\n", text);
}

int cli_config_write(FILE *out, const jc_Setup *s)
{
    const char *sections[CLI_CONFIG_SECTION_MAX];
    const int n = cli_config_sections(sections);
    fputs("# jumpcyl experiment file (docs/config.md): units as a person types them (cm, g,\n"
          "# deg); every number reads back to the same double.\n",
          out);
    write_section(out, s, sections[0]);
    for (int i = 0; i < s->body.part_count && i < JC_MAX_PARTS; ++i) {
        const jc_Part *p = &s->body.parts[i];
        fprintf(out, "\n[part.%d]\nkind = %s\nmass = ", i + 1, jc_part_kind_name(p->kind));
        write_number(out, p->mass_kg, JC_Q_MASS, "g");
        fputs("offset = ", out);
        write_number(out, p->offset_m, JC_Q_LENGTH, "cm");
        fputs("radius = ", out);
        write_number(out, p->radius_m, JC_Q_LENGTH, "cm");
        fputs("angle = ", out);
        write_number(out, p->angle_rad, JC_Q_ANGLE, "deg");
    }
    for (int k = 1; k < n; ++k) write_section(out, s, sections[k]);
    return ferror(out) ? -1 : 0;
}
