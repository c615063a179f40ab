/* Tracker's exported data tables (File > Export > Data), as Tracker 6
 * writes them (ExportDataDialog): a "#multi:" line when several tracks are
 * exported, a row of track names (each above its first column), a header
 * row ("t", then each track's columns: x, y, ...), then one row per frame,
 * an empty field where the track has no position. The delimiter is a tab,
 * a comma or a semicolon (the user's choice); numbers follow the user's
 * locale, so a decimal comma appears with tab or semicolon delimiters.
 * Hand-made tables are read too: no name row, units in the header
 * ("t (s)", "x (cm)"), blank fields or spaces as the delimiter. Tables
 * are written as Tracker exports them too (jc_track_write_table: the
 * synthetic experiments of the tests and examples). */
#include "track_internal.h"

#include <stdio.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TABLE_MAX_FIELDS 256
#define TABLE_FIELD_LEN 64

typedef struct {
    const char *file;
    char *err;
    size_t err_len;
    char delim;        /* '\t', ';', ',' or ' ' (runs of spaces) */
    int decimal_comma; /* ',' in a number is its decimal point */
} table_ctx;

/* One line split into fields (trimmed), at most TABLE_MAX_FIELDS. */
typedef struct {
    int n;
    char f[TABLE_MAX_FIELDS][TABLE_FIELD_LEN];
    int too_long; /* a field was cut */
} table_row;

static void split(const table_ctx *c, const char *s, size_t len, table_row *r)
{
    r->n = 0;
    r->too_long = 0;
    size_t i = 0;
    while (r->n < TABLE_MAX_FIELDS) {
        if (c->delim == ' ')
            while (i < len && (s[i] == ' ' || s[i] == '\t')) i++;
        size_t j = i;
        while (j < len && (c->delim == ' ' ? !(s[j] == ' ' || s[j] == '\t') : s[j] != c->delim)) j++;
        size_t a = i, b = j;
        while (a < b && isspace((unsigned char)s[a])) a++;
        while (b > a && isspace((unsigned char)s[b - 1])) b--;
        if (b - a >= TABLE_FIELD_LEN) {
            r->too_long = 1;
            b = a + TABLE_FIELD_LEN - 1;
        }
        memcpy(r->f[r->n], s + a, b - a);
        r->f[r->n][b - a] = '\0';
        r->n++;
        if (j >= len) break;
        i = j + 1;
        if (c->delim == ' ' && i >= len) break;
    }
}

/* A field as a finite number: 1; 0 if empty; -1 if not a number. */
static int number(const table_ctx *c, const char *field, double *out)
{
    if (!field[0]) return 0;
    char buf[TABLE_FIELD_LEN];
    size_t n = strlen(field);
    for (size_t i = 0; i <= n; ++i) {
        const char ch = field[i];
        /* Only digits, signs, a decimal mark and an exponent: no "nan", "inf" or hex. */
        if (ch && !isdigit((unsigned char)ch) && !strchr("+-.eE,", ch)) return -1;
        buf[i] = (ch == ',' && c->decimal_comma) ? '.' : ch;
    }
    char *end = NULL;
    errno = 0;
    const double v = strtod(buf, &end);
    if (end == buf || *end != '\0' || !isfinite(v) || errno == ERANGE) return -1;
    *out = v;
    return 1;
}

/* A header field: its name and unit factor to SI ("x (cm)" -> "x", 0.01). */
static int header_name(const char *field, char *name, size_t len, double *to_si, int is_time)
{
    size_t n = 0;
    while (field[n] && field[n] != '(' && field[n] != '[' && field[n] != ' ') n++;
    if (n >= len) n = len - 1;
    memcpy(name, field, n);
    name[n] = '\0';
    for (char *p = name; *p; ++p) *p = (char)tolower((unsigned char)*p);
    const char *u = field + n;
    while (*u == ' ' || *u == '(' || *u == '[') u++;
    char unit[16] = "";
    size_t k = 0;
    while (u[k] && u[k] != ')' && u[k] != ']' && k + 1 < sizeof unit) {
        unit[k] = u[k];
        k++;
    }
    unit[k] = '\0';
    *to_si = 1.0;
    if (!unit[0]) return 0;
    if (is_time) {
        if (strcmp(unit, "s") == 0) return 0;
        if (strcmp(unit, "ms") == 0) { *to_si = 1e-3; return 0; }
    } else {
        if (strcmp(unit, "m") == 0) return 0;
        if (strcmp(unit, "cm") == 0) { *to_si = 1e-2; return 0; }
        if (strcmp(unit, "mm") == 0) { *to_si = 1e-3; return 0; }
    }
    return -1;
}

/* The next line: [*pos, end of line) without its line break. 0 at the end. */
static int next_line(const char *data, size_t len, size_t *pos, const char **line, size_t *line_len)
{
    if (*pos >= len) return 0;
    size_t i = *pos;
    while (i < len && data[i] != '\n') i++;
    *line = data + *pos;
    *line_len = i - *pos;
    if (*line_len > 0 && (*line)[*line_len - 1] == '\r') (*line_len)--;
    *pos = i < len ? i + 1 : len;
    return 1;
}

static int blank(const char *s, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!isspace((unsigned char)s[i])) return 0;
    return 1;
}

static char pick_delim(const char *s, size_t n)
{
    if (memchr(s, '\t', n)) return '\t';
    if (memchr(s, ';', n)) return ';';
    if (memchr(s, ',', n)) return ',';
    return ' ';
}

/* Whether a header row starts with the time column. */
static int is_time_header(const char *field)
{
    char name[16];
    double f;
    if (header_name(field, name, sizeof name, &f, 1) != 0) return 1; /* a bad unit: said later */
    return strcmp(name, "t") == 0 || strcmp(name, "time") == 0;
}

typedef struct {
    int x_col, y_col;
    double x_si, y_si;
    char name[JC_TRACK_NAME_LEN];
} table_group;

static int fail(const table_ctx *c, long line, const char *msg, const char *detail)
{
    if (line > 0) snprintf(c->err, c->err_len, "%s: line %ld: %s%s", c->file, line, msg, detail);
    else snprintf(c->err, c->err_len, "%s: %s%s", c->file, msg, detail);
    return -1;
}

static void clean_name(char *s)
{
    for (char *p = s; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f) *p = '?';
}

/* The columns: which are x and y of which track. Returns the group count or -1. */
static int read_header(table_ctx *c, const table_row *names, const table_row *head, long head_line,
                       table_group *g, double *t_si)
{
    char name[16];
    if (header_name(head->f[0], name, sizeof name, t_si, 1) != 0)
        return fail(c, head_line, "the time column's unit is not s or ms: ", head->f[0]);
    int ng = 0;
    for (int j = 1; j < head->n; ++j) {
        const char *nm = names && j < names->n ? names->f[j] : "";
        double si = 1.0;
        const int bad = header_name(head->f[j], name, sizeof name, &si, 0);
        const int is_x = strcmp(name, "x") == 0, is_y = strcmp(name, "y") == 0;
        if ((is_x || is_y) && bad) return fail(c, head_line, "a length unit other than m, cm or mm: ", head->f[j]);
        const int start = nm[0] || (is_x && (ng == 0 || g[ng - 1].x_col >= 0)) || (is_y && ng == 0);
        if (start) {
            if (ng == JC_TRACK_MAX_TRACKS) return fail(c, head_line, "more than 16 tracks", "");
            g[ng].x_col = g[ng].y_col = -1;
            snprintf(g[ng].name, sizeof g[ng].name, "%s", nm);
            ng++;
        }
        if (ng == 0) continue;
        if (is_x && g[ng - 1].x_col < 0) { g[ng - 1].x_col = j; g[ng - 1].x_si = si; }
        if (is_y && g[ng - 1].y_col < 0) { g[ng - 1].y_col = j; g[ng - 1].y_si = si; }
    }
    /* The older single-track form: the track's name alone on the first line. */
    if (names && ng > 0 && !g[0].name[0] && names->n >= 1 && names->f[0][0])
        snprintf(g[0].name, sizeof g[0].name, "%s", names->f[0]);
    int kept = 0;
    for (int i = 0; i < ng; ++i) {
        if (g[i].x_col < 0 && g[i].y_col < 0) continue; /* a track exported without positions */
        if (g[i].x_col < 0 || g[i].y_col < 0) {
            char what[JC_TRACK_NAME_LEN + 96];
            snprintf(what, sizeof what, "track '%s' has %s but no %s", g[i].name[0] ? g[i].name : "?",
                     g[i].x_col < 0 ? "y" : "x", g[i].x_col < 0 ? "x" : "y");
            return fail(c, head_line, what, "");
        }
        if (!g[i].name[0]) snprintf(g[i].name, sizeof g[i].name, "mass %c", 'A' + kept);
        clean_name(g[i].name);
        g[kept++] = g[i];
    }
    if (kept == 0) return fail(c, head_line, "no x and y columns in the header", "");
    return kept;
}

/* 0, -1 with a message, or JC_ENOMEM. */
static int parse(const char *name, const char *data, size_t len, jc_TrackRaw *raw, char *err, size_t err_len)
{
    memset(raw, 0, sizeof *raw);
    raw->px_per_m = raw->tape_length_m = raw->nominal_dt_s = NAN;
    strcpy(raw->format, "table");
    table_ctx c = {name, err, err_len, '\t', 0};
    if (memchr(data, '\0', len)) return fail(&c, 0, "a binary file (NUL bytes), not a data table", "");
    size_t pos = 0;
    const char *line = NULL;
    size_t ll = 0;
    long line_no = 0;
    /* Comment lines ("#multi:") and blank lines before the table. */
    int have = 0;
    while ((have = next_line(data, len, &pos, &line, &ll)) != 0) {
        line_no++;
        if (!blank(line, ll) && line[0] != '#') break;
    }
    if (!have) return fail(&c, 0, "empty: no header row (t, x, y)", "");
    table_row *names = malloc(sizeof *names), *head = malloc(sizeof *head), *row = malloc(sizeof *row);
    table_group *g = malloc(JC_TRACK_MAX_TRACKS * sizeof *g);
    int st = -1;
    if (!names || !head || !row || !g) {
        fail(&c, 0, "out of memory", "");
        st = JC_ENOMEM;
        goto done;
    }
    c.delim = pick_delim(line, ll);
    split(&c, line, ll, head);
    long head_line = line_no;
    int has_names = 0;
    if (!is_time_header(head->f[0])) {
        /* A name row: the header is the next line, whose delimiter splits both. */
        const char *name_line = line;
        const size_t name_len = ll;
        has_names = 1;
        if (!next_line(data, len, &pos, &line, &ll)) {
            fail(&c, 0, "no header row (t, x, y) after the track names", "");
            goto done;
        }
        line_no++;
        c.delim = pick_delim(line, ll);
        split(&c, line, ll, head);
        split(&c, name_line, name_len, names);
        head_line = line_no;
        if (!is_time_header(head->f[0])) {
            fail(&c, head_line, "no header row: the first column must be the time t, not ", head->f[0]);
            goto done;
        }
    }
    if (head->too_long) {
        fail(&c, head_line, "a header field is too long", "");
        goto done;
    }
    c.decimal_comma = c.delim != ',';
    double t_si = 1.0;
    const int ng = read_header(&c, has_names ? names : NULL, head, head_line, g, &t_si);
    if (ng < 0) goto done;
    /* Rows: counted first, so that the arrays are made once. */
    long rows = 0;
    for (size_t q = pos; q < len; ++q)
        if (data[q] == '\n') rows++;
    if (len > 0 && data[len - 1] != '\n') rows++;
    if (rows > JC_TRACK_MAX_FRAMES) {
        fail(&c, 0, "too many rows", "");
        goto done;
    }
    if (rows < 1) rows = 1;
    if (jc_track_raw_alloc(raw, rows, ng) != JC_OK) {
        fail(&c, 0, "out of memory", "");
        st = JC_ENOMEM;
        goto done;
    }
    for (int i = 0; i < ng; ++i) snprintf(raw->tracks[i].name, sizeof raw->tracks[i].name, "%s", g[i].name);
    long n = 0;
    while (next_line(data, len, &pos, &line, &ll)) {
        line_no++;
        if (blank(line, ll)) continue;
        split(&c, line, ll, row);
        double t = NAN;
        if (row->too_long || number(&c, row->f[0], &t) != 1) {
            fail(&c, line_no, "the time is not a number: ", row->f[0]);
            goto done;
        }
        t *= t_si;
        if (n > 0 && !(t > raw->t_s[n - 1])) {
            fail(&c, line_no, "time does not increase: ", row->f[0]);
            goto done;
        }
        raw->t_s[n] = t;
        for (int i = 0; i < ng; ++i) {
            const int cols[2] = {g[i].x_col, g[i].y_col};
            double *dst[2] = {&raw->tracks[i].x_m[n], &raw->tracks[i].y_m[n]};
            const double si[2] = {g[i].x_si, g[i].y_si};
            double v[2] = {NAN, NAN};
            int got[2];
            for (int k = 0; k < 2; ++k) {
                got[k] = cols[k] < row->n ? number(&c, row->f[cols[k]], &v[k]) : 0;
                if (got[k] < 0) {
                    fail(&c, line_no, "not a number: ", row->f[cols[k]]);
                    goto done;
                }
            }
            if (got[0] != got[1]) {
                fail(&c, line_no, "x without y (or y without x) for track ", g[i].name);
                goto done;
            }
            if (got[0]) {
                *dst[0] = v[0] * si[0];
                *dst[1] = v[1] * si[1];
            }
        }
        n++;
    }
    if (n < 1) {
        fail(&c, 0, "no rows of data", "");
        goto done;
    }
    raw->frames = n;
    st = 0;
done:
    free(names);
    free(head);
    free(row);
    free(g);
    if (st != 0) jc_track_raw_free(raw);
    return st;
}

int jc_track_table_parse(const char *name, const char *data, size_t len, jc_TrackRaw *raw, char *err, size_t err_len)
{
    const int st = parse(name, data, len, raw, err, err_len);
    return st == 0 ? JC_OK : st == JC_ENOMEM ? JC_ENOMEM : JC_EINVAL;
}

/* A number as Tracker exports it "as formatted" at full precision, or an
 * empty field for a missing point. */
static void field(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, "\t%.7g", v);
    else fputc('\t', f);
}

void jc_track_write_table(FILE *f, const jc_TrackRaw *raw)
{
    /* Tracker's export of point masses: the names above their first column. */
    fputs("#multi:\n", f);
    for (int k = 0; k < raw->track_count; ++k) fprintf(f, "\t%s\t", raw->tracks[k].name);
    fputs("\nt", f);
    for (int k = 0; k < raw->track_count; ++k) fputs("\tx\ty", f);
    fputc('\n', f);
    for (long i = 0; i < raw->frames; ++i) {
        fprintf(f, "%.6f", raw->t_s[i]);
        for (int k = 0; k < raw->track_count; ++k) {
            field(f, raw->tracks[k].x_m[i]);
            field(f, raw->tracks[k].y_m[i]);
        }
        fputc('\n', f);
    }
}
