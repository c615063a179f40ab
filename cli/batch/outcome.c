/* A case's row read back from the rows' file (--resume, mc --summarize):
 * what the consumers of a batch need, its kind, first lift-off and largest
 * hop, from the columns the library writes (jc_case_column). */
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The n-th comma-separated field of a line (0-based), as a pointer and length. */
static const char *field(const char *line, size_t len, int n, size_t *flen)
{
    const char *p = line, *end = line + len;
    for (int i = 0; i < n; ++i) {
        p = memchr(p, ',', (size_t)(end - p));
        if (!p) return NULL;
        ++p;
    }
    const char *c = memchr(p, ',', (size_t)(end - p));
    *flen = c ? (size_t)(c - p) : (size_t)(end - p);
    return p;
}

static double number_field(const char *line, size_t len, int n)
{
    size_t flen;
    const char *f = field(line, len, n, &flen);
    char buf[64];
    if (!f || flen == 0 || flen >= sizeof buf) return NAN;
    memcpy(buf, f, flen);
    buf[flen] = '\0';
    return strtod(buf, NULL);
}

int cli_case_from_row(const char *line, size_t len, int input_columns, cli_CaseResult *r)
{
    int commas = 0;
    for (size_t i = 0; i < len; ++i) commas += line[i] == ',';
    if (commas != input_columns + JC_CASE_COLUMNS || len == 0 || len >= sizeof r->row) return -1;
    memcpy(r->row, line, len);
    r->row[len] = '\0';
    r->row_len = (int)len;
    memset(&r->outcome, 0, sizeof r->outcome);
    jc_CaseOutcome *o = &r->outcome;
    const int at = 1 + input_columns; /* the first outcome column */
    size_t flen;
    const char *term = field(line, len, at + 10, &flen);
    const char *first = field(line, len, at, &flen);
    o->liftoff_x_m = number_field(line, len, at + 5);
    o->largest_hop_m = number_field(line, len, at + 9);
    if (isnan(o->largest_hop_m)) o->largest_hop_m = 0.0;
    if (term && strncmp(term, "invalid_setup", 13) == 0) o->kind = JC_CASE_INVALID;
    else if (term && strncmp(term, "failed,", 7) == 0) o->kind = JC_CASE_FAILED;
    else if (first && strncmp(first, "slip,", 5) == 0 && number_field(line, len, at + 2) <= JC_CASE_SLIDES_AT_START_M)
        o->kind = JC_CASE_SLIDES_AT_START;
    else o->kind = isnan(o->liftoff_x_m) ? JC_CASE_NO_LIFTOFF : JC_CASE_LIFTOFF;
    return 0;
}
