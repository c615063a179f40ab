/* jumpcyl params: the library's parameter table (jc_param_info), as text or
 * JSON: every setup option, experiment-file key and batch parameter name. */
#include "commands.h"
#include "inputs.h"

#include <math.h>
#include <string.h>

static void help(void)
{
    puts("Usage: jumpcyl params [--json FILE]\n"
         "Every setup parameter: its option --NAME, its quantity and unit, its range, each\n"
         "preset's value, what it does and its experiment-file key ([section] key). The\n"
         "same names vary in sweep --vary, mc --sigma/--range, map --x/--y and design --free.\n"
         "\n"
         "  --json FILE     the table as JSON into FILE (- or no FILE: standard output, in place\n"
         "                  of the text; SI values; null where a preset has no value, e.g.\n"
         "                  rod-mass of the hoop, and for a range without an upper end)\n"
         "  -h, --help      this help");
}

/* "[0, 90) deg", ">= 0 m": in SI, angles in degrees. */
static void range_text(const jc_ParamInfo *in, char *buf, size_t len)
{
    const int angle = in->quantity == JC_Q_ANGLE;
    const double k = angle ? 180.0 / CLI_PI : 1.0;
    const char *unit = angle ? "deg" : in->si_unit;
    const char *blank = *unit ? " " : "";
    if (isinf(in->max))
        snprintf(buf, len, "%s %g%s%s", in->min_open ? ">" : ">=", in->min * k, blank, unit);
    else
        snprintf(buf, len, "%s%g, %g%s%s%s", in->min_open ? "(" : "[", in->min * k, in->max * k,
                 in->max_open ? ")" : "]", blank, unit);
}

#define COLUMN 20

static void print_row(int id)
{
    const jc_ParamInfo *in = jc_param_info(id);
    char line[256];
    if (in->quantity == JC_Q_NAME) {
        int n = snprintf(line, sizeof line, "name:");
        for (int k = 0; in->choices[k] && n > 0 && (size_t)n < sizeof line; ++k)
            n += snprintf(line + n, sizeof line - (size_t)n, "%s %s", k ? "," : "", in->choices[k]);
    } else {
        char range[96];
        range_text(in, range, sizeof range);
        if (*in->unit)
            snprintf(line, sizeof line, "%s in %s (SI: %s); range %s%s%s", jc_quantity_name(in->quantity), in->unit,
                     in->si_unit, range, in->bound ? ", " : "", in->bound ? in->bound : "");
        else
            snprintf(line, sizeof line, "number; range %s%s%s", range, in->bound ? ", " : "", in->bound ? in->bound : "");
    }
    /* the name, then at least two blanks (what 'jumpcyl params' readers split on) */
    const int pad = (int)strlen(in->name) < COLUMN - 2 ? COLUMN - (int)strlen(in->name) : 2;
    printf("%s%*s%s\n", in->name, pad, "", line);
    printf("%*s%s\n", COLUMN, "", in->help);
    printf("%*s[%s] %s;", COLUMN, "", in->section, in->key);
    for (int k = 0; jc_preset_name(k); ++k) {
        jc_Setup s;
        double v;
        char text[80];
        const int has = jc_preset_setup(jc_preset_name(k), &s, NULL, 0) == JC_OK &&
                        jc_param_get(&s, id, &v, NULL, 0) == JC_OK && jc_param_format(id, v, text, sizeof text) == JC_OK;
        printf("%s %s %s", k ? "," : "", jc_preset_name(k), has ? text : "-");
    }
    putchar('\n');
}

int cmd_params(int argc, char **argv)
{
    static const struct option own[] = {CLI_JSON_OPTION('j'), {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
    const char *json = NULL;
    /* Its own options only: the setup options mean nothing here. */
    opterr = 0;
    optind = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":h", own, NULL)) != -1) {
        if (c == 'h') {
            help();
            return EXIT_OK;
        }
        if (c != 'j') {
            cli_error("params: unknown option '%s' (see 'jumpcyl params --help')", argv[optind - 1]);
            return EXIT_USAGE;
        }
        if (json) {
            cli_error("params: --json given twice");
            return EXIT_USAGE;
        }
        json = cli_output_optarg(argc, argv);
    }
    if (optind < argc) {
        cli_error("params: unexpected argument '%s' (see 'jumpcyl params --help')", argv[optind]);
        return EXIT_USAGE;
    }
    if (json) {
        const int rc = cli_json_write(cli_json_params(), json);
        if (rc != EXIT_OK || strcmp(json, "-") == 0) return rc;
    }
    printf("Setup parameters. Each is an option (--NAME VALUE), an experiment-file key\n"
           "([section] key) and a name for sweep --vary, mc --sigma/--range, map --x/--y and\n"
           "design --free. A plain number is SI, an angle degrees; a value may carry a unit.\n"
           "Each: its quantity and unit, range, what it does, its file key and each preset's value.\n\n");
    for (int id = 0; id < jc_param_count(); ++id) print_row(id);
    if (json) printf("JSON written to %s\n", json);
    return EXIT_OK;
}
