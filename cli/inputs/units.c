/* Numbers with units on the command line: the library's reader
 * (jc_quantity_parse, src/units.c) under the tool's names. */
#include "inputs.h"

int cli_parse_quantity(const char *text, cli_Quantity q, double *out, char *err, size_t err_len)
{
    return jc_quantity_parse(text, q, out, err, err_len) == JC_OK ? 0 : -1;
}

const char *cli_units_allowed(cli_Quantity q) { return jc_quantity_units_text(q); }
