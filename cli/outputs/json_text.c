/* JSON text with every number exact: each finite double written in the
 * shortest of its %.15g, %.16g and %.17g forms that reads back to the same
 * double bit for bit. cJSON alone keeps %.15g when it reads back within a
 * relative DBL_EPSILON, which can lose the last bit. Every JSON document the
 * tool and the web page write goes through cli_json_text (the page's
 * sample columns come as raw text already, exact with %.17g: web/jc_web.c). */
#include "outputs.h"

#include <cjson/cJSON.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Whether text (in the current locale, as printf wrote it) reads back to v
 * bit for bit: -0 stays -0. */
static int reads_back(const char *text, double v)
{
    const double back = strtod(text, NULL);
    return memcmp(&back, &v, sizeof v) == 0;
}

int cli_json_number(double v, char out[CLI_JSON_NUMBER_MAX])
{
    if (!isfinite(v)) { /* JSON has no NaN or infinity: null, as cJSON writes them */
        memcpy(out, "null", 5);
        return 4;
    }
    /* Fewer digits are never longer, except where %.15g or %.16g switch to
     * an exponent that %.17g does not need (1e15 <= |v| < 1e17): there every
     * form is tried and the shortest kept. */
    const int all = fabs(v) >= 1e15 && fabs(v) < 1e17;
    char tmp[CLI_JSON_NUMBER_MAX];
    int len = -1;
    for (int digits = 15; digits <= 17; ++digits) {
        const int n = snprintf(tmp, sizeof tmp, "%.*g", digits, v);
        if (n <= 0 || n >= (int)sizeof tmp) continue;
        if (digits < 17 && !reads_back(tmp, v)) continue; /* %.17g always reads back */
        if (len < 0 || n < len) {
            memcpy(out, tmp, (size_t)n + 1);
            len = n;
        }
        if (!all) break;
    }
    /* The locale's decimal point as JSON's '.', as cJSON does. */
    const char point = localeconv()->decimal_point[0];
    if (point != '.')
        for (char *c = out; *c; ++c)
            if (*c == point) *c = '.';
    return len;
}

/* Every number node under item (and item itself) made a raw node holding
 * its exact text, which cJSON's printer copies as it is. 0, or -1 when
 * memory ran out. */
static int exact_numbers(cJSON *item)
{
    for (; item; item = item->next) {
        if (cJSON_IsNumber(item)) {
            char text[CLI_JSON_NUMBER_MAX];
            const int n = cli_json_number(item->valuedouble, text);
            char *copy = cJSON_malloc((size_t)n + 1);
            if (!copy) return -1;
            memcpy(copy, text, (size_t)n + 1);
            /* A number holds no string or child: what cJSON_Delete frees of
             * a raw node is only this copy (and the key, as before). */
            item->valuestring = copy;
            item->type = cJSON_Raw | (item->type & cJSON_StringIsConst);
        } else if (item->child && exact_numbers(item->child) != 0) {
            return -1;
        }
    }
    return 0;
}

char *cli_json_text(cJSON *doc, int formatted)
{
    if (!doc) return NULL;
    /* Only the document itself, not the siblings it may have in a tree. */
    cJSON *next = doc->next;
    doc->next = NULL;
    const int ok = exact_numbers(doc) == 0;
    doc->next = next;
    if (!ok) return NULL;
    return formatted ? cJSON_Print(doc) : cJSON_PrintUnformatted(doc);
}
