/* Experiment files: a whole setup in a small INI file (docs/config.md), read
 * with inih (config_write.c writes them and holds the format's sections): every
 * key is a parameter of the library's table (jc_ParamInfo section and key,
 * or the parameter's name), read with jc_param_parse and set with
 * jc_param_set, and [part.N] sections.
 *
 * inih splits "key = value" lines and strips blanks and inline comments. It
 * reports neither line numbers nor section headers to the handler (Debian's
 * build), so the lines reach it through our own reader, which counts them,
 * refuses overlong lines and NUL bytes, checks every "[section]" header
 * (unknown and repeated sections, text after the ']') and strips leading
 * blanks, so that no line can continue the previous value. Values are
 * staged while reading and applied afterwards in a fixed order, so that the
 * order of sections and keys in the file does not matter. */
#define _POSIX_C_SOURCE 200809L
#include "inputs.h"

#include <ini.h>

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Longest line, comment included. inih's own buffer holds 200 bytes with the
 * line end; this leaves room and keeps messages short. */
#define LINE_MAX_CHARS 160
/* Largest file: an experiment file is a few hundred bytes. */
#define FILE_MAX_BYTES 65536

/* The keys of a [part.N] section. */
enum { PK_KIND, PK_MASS, PK_OFFSET, PK_RADIUS, PK_ANGLE, PART_KEY_COUNT };
static const char *const part_keys[PART_KEY_COUNT] = {"kind", "mass", "offset", "radius", "angle"};
static const cli_Quantity part_quantities[PART_KEY_COUNT] = {Q_NUMBER, Q_MASS, Q_LENGTH, Q_LENGTH, Q_ANGLE};

#define SEC_NONE (-1)
#define SECTION_SLOTS (CLI_CONFIG_SECTION_MAX + JC_MAX_PARTS)

/* What the file says, before it is applied; a line number 0 means "not given". */
typedef struct {
    double value[JC_PARAM_MAX]; /* by parameter id: SI, a name's index */
    int value_line[JC_PARAM_MAX];
    jc_Part part[JC_MAX_PARTS];
    int part_line[JC_MAX_PARTS][PART_KEY_COUNT];
    int section_line[SECTION_SLOTS];
} staged;

typedef struct {
    const char *name; /* the file, for messages */
    const char *text;
    size_t len, pos;
    int line;         /* of the line handed to inih last */
    int section;      /* the section that line belongs to: a named one, then part.N at part_first + N - 1 */
    const char *sections[CLI_CONFIG_SECTION_MAX]; /* the named sections (cli_config_sections) */
    int part_first;   /* their count: the slot of [part.1] */
    int error_line;   /* of the first error, 0 if none */
    char *err;
    size_t err_len;
    staged st;
} parser;

static void fail(parser *p, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Keeps the first error only: later ones are often its consequences. */
static void fail(parser *p, int line, const char *fmt, ...)
{
    if (p->error_line) return;
    p->error_line = line;
    char msg[384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(p->err, p->err_len, "%s:%d: %s", p->name, line, msg);
}

/* ---- sections ---- */

/* "part.N" with N from 1 to JC_MAX_PARTS written without leading zeros. */
static int part_section(const parser *p, const char *name, size_t len)
{
    if (len < 6 || len > 7 || strncmp(name, "part.", 5) != 0 || name[5] == '0') return SEC_NONE;
    int n = 0;
    for (size_t i = 5; i < len; ++i) {
        if (!isdigit((unsigned char)name[i])) return SEC_NONE;
        n = 10 * n + (name[i] - '0');
    }
    return n >= 1 && n <= JC_MAX_PARTS ? p->part_first + n - 1 : SEC_NONE;
}

static int find_section(const parser *p, const char *name, size_t len)
{
    for (int i = 0; i < p->part_first; ++i)
        if (strlen(p->sections[i]) == len && strncmp(name, p->sections[i], len) == 0) return i;
    return part_section(p, name, len);
}

static void section_label(const parser *p, int sec, char *buf, size_t n)
{
    if (sec >= p->part_first) snprintf(buf, n, "[part.%d]", sec - p->part_first + 1);
    else snprintf(buf, n, "[%s]", p->sections[sec]);
}

/* "body, part.1 to part.16, incline, ..." */
static void allowed_sections(const parser *p, char *buf, size_t n)
{
    snprintf(buf, n, "%s, part.1 to part.%d", p->sections[0], JC_MAX_PARTS);
    for (int i = 1; i < p->part_first; ++i) {
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, ", %s", p->sections[i]);
    }
}

/* A "[name]" line (leading blanks already gone): only blanks or a comment
 * may follow the ']'. */
static void begin_section(parser *p, const char *line, size_t len)
{
    const char *close = memchr(line, ']', len);
    if (!close) {
        fail(p, p->line, "section header without ']' (expected [NAME])");
        return;
    }
    const char *rest = close + 1;
    while (rest < line + len && isspace((unsigned char)*rest)) ++rest;
    if (rest < line + len && *rest != ';' && *rest != '#') {
        fail(p, p->line, "unexpected text after ']' in a section header");
        return;
    }
    const size_t name_len = (size_t)(close - line - 1);
    const int sec = find_section(p, line + 1, name_len);
    if (sec == SEC_NONE) {
        char allowed[256];
        allowed_sections(p, allowed, sizeof allowed);
        fail(p, p->line, "unknown section [%.*s] (allowed: %s)", (int)(name_len > 40 ? 40 : name_len), line + 1,
             allowed);
        return;
    }
    if (p->st.section_line[sec]) {
        char label[24];
        section_label(p, sec, label, sizeof label);
        fail(p, p->line, "section %s given twice (first on line %d)", label, p->st.section_line[sec]);
        return;
    }
    p->st.section_line[sec] = p->line;
    p->section = sec;
}

/* ---- the line reader inih reads through ---- */

/* A line that inih would take for "key = value": it has '=' or ':' before
 * any inline comment (';' after a blank). */
static int is_pair(const char *s, size_t len)
{
    for (size_t i = 0; i < len; ++i) {
        if (s[i] == '=' || s[i] == ':') return 1;
        if (s[i] == ';' && i > 0 && isspace((unsigned char)s[i - 1])) return 0;
    }
    return 0;
}

/* Checks one line and handles section headers; 0 if inih may have it.
 * room: what inih's buffer holds besides the line end. */
static int check_line(parser *p, const char *s, size_t len, size_t room)
{
    if (memchr(s, '\0', len)) {
        fail(p, p->line, "NUL byte (an experiment file is text)");
        return -1;
    }
    if (len > LINE_MAX_CHARS || len > room) {
        fail(p, p->line, "line too long (allowed: at most %d characters)", LINE_MAX_CHARS);
        return -1;
    }
    if (len == 0 || *s == ';' || *s == '#') return 0;
    if (*s == '[') {
        begin_section(p, s, len);
        return p->error_line ? -1 : 0;
    }
    if (!is_pair(s, len)) {
        fail(p, p->line, "expected 'key = value', '[section]' or a comment");
        return -1;
    }
    return 0;
}

/* inih's fgets: one line per call, leading blanks removed, line end kept.
 * After an error it ends the input, so that inih stops. */
static char *read_line(char *buf, int size, void *stream)
{
    parser *p = stream;
    if (p->error_line || p->pos >= p->len) return NULL;
    const char *s = p->text + p->pos;
    const char *nl = memchr(s, '\n', p->len - p->pos);
    size_t len = nl ? (size_t)(nl - s) : p->len - p->pos;
    p->pos += len + (nl != NULL);
    p->line++;
    if (p->line == 1 && len >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0) {
        s += 3; /* a UTF-8 byte order mark */
        len -= 3;
    }
    /* Every blank inih would skip: a line it sees indented would continue
     * the previous value. */
    while (len > 0 && isspace((unsigned char)*s)) {
        ++s;
        --len;
    }
    if (check_line(p, s, len, size > 2 ? (size_t)size - 2 : 0) != 0) return NULL;
    memcpy(buf, s, len);
    buf[len] = '\n';
    buf[len + 1] = '\0';
    return buf;
}

/* ---- keys ---- */

static int parse_value(parser *p, const char *key, const char *value, cli_Quantity q, double *out)
{
    char msg[256];
    if (cli_parse_quantity(value, q, out, msg, sizeof msg) == 0) return 0;
    fail(p, p->line, "%s: %s", key, msg);
    return -1;
}

static int parse_kind(parser *p, const char *value, jc_PartKind *kind)
{
    static const jc_PartKind kinds[] = {JC_PART_DISC, JC_PART_HOOP, JC_PART_ROD, JC_PART_POINT};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
        if (strcmp(value, jc_part_kind_name(kinds[k])) == 0) {
            *kind = kinds[k];
            return 0;
        }
    }
    fail(p, p->line, "kind: unknown part kind '%s' (allowed: disc, hoop, rod, point)", value);
    return -1;
}

/* The parameter a key of a named section names: the table's key, or the
 * parameter's own name (the command line's, '-' written '_') in its
 * section; -1 if none. */
static int param_of_key(const char *section, const char *key)
{
    const int by_name = jc_param_find(key);
    if (by_name >= 0 && strcmp(jc_param_info(by_name)->section, section) == 0) return by_name;
    for (int id = 0; id < jc_param_count(); ++id)
        if (strcmp(jc_param_info(id)->section, section) == 0 && strcmp(jc_param_info(id)->key, key) == 0) return id;
    return -1;
}

/* The option name of a parameter as a key ("air_density"), when it is not the key itself. */
static int alias_key(const jc_ParamInfo *in, char *buf, size_t n)
{
    snprintf(buf, n, "%s", in->name);
    for (char *c = buf; *c; ++c)
        if (*c == '-') *c = '_';
    return strcmp(buf, in->key) != 0;
}

/* "radius, gravity, ..." for a section's messages: the keys written
 * (numbers, then names), the shortcuts, then the option names. */
static void allowed_keys(const parser *p, int sec, char *buf, size_t n)
{
    buf[0] = '\0';
    if (sec >= p->part_first) {
        for (int k = 0; k < PART_KEY_COUNT; ++k) {
            const size_t used = strlen(buf);
            snprintf(buf + used, n - used, "%s%s", used ? ", " : "", part_keys[k]);
        }
        return;
    }
    for (int pass = 0; pass < 4; ++pass)
        for (int id = 0; id < jc_param_count(); ++id) {
            const jc_ParamInfo *in = jc_param_info(id);
            char alias[64];
            const int written = cli_config_written(in), name = in->quantity == JC_Q_NAME;
            const int take = pass == 0 ? written && !name : pass == 1 ? written && name : pass == 2 ? !written : 1;
            if (strcmp(in->section, p->sections[sec]) != 0 || !take || (pass == 3 && !alias_key(in, alias, sizeof alias)))
                continue;
            const size_t used = strlen(buf);
            snprintf(buf + used, n - used, "%s%s", used ? ", " : "", pass == 3 ? alias : in->key);
        }
}

/* 0 if the key was not given before in this section. */
static int first_time(parser *p, int *line_slot, const char *key)
{
    if (*line_slot) {
        char label[24];
        section_label(p, p->section, label, sizeof label);
        fail(p, p->line, "key '%s' given twice in %s (first on line %d)", key, label, *line_slot);
        return -1;
    }
    *line_slot = p->line;
    return 0;
}

static void part_key(parser *p, const char *key, const char *value)
{
    const int i = p->section - p->part_first;
    int k = 0;
    while (k < PART_KEY_COUNT && strcmp(key, part_keys[k]) != 0) ++k;
    if (k == PART_KEY_COUNT) {
        fail(p, p->line, "unknown key '%s' in [part.%d] (allowed: kind, mass, offset, radius, angle)", key, i + 1);
        return;
    }
    if (first_time(p, &p->st.part_line[i][k], key) != 0) return;
    jc_Part *part = &p->st.part[i];
    double *field[PART_KEY_COUNT] = {NULL, &part->mass_kg, &part->offset_m, &part->radius_m, &part->angle_rad};
    if (k == PK_KIND) parse_kind(p, value, &part->kind);
    else parse_value(p, key, value, part_quantities[k], field[k]);
}

/* inih's handler: one "key = value" line of the current section. It
 * answers 1 (inih's "go on") always: the first error is kept in p and
 * the rest of the file is read without effect. */
static int on_pair(void *user, const char *section, const char *key_text, const char *value)
{
    (void)section; /* the reader tracks sections itself, with their lines */
    parser *p = user;
    if (p->error_line) return 1;
    /* ramp-length or ramp_length: as on the command line, or as a C name */
    char key[64];
    snprintf(key, sizeof key, "%s", key_text);
    for (char *c = key; *c; ++c)
        if (*c == '-') *c = '_';
    if (p->section == SEC_NONE) {
        fail(p, p->line, "key '%s' before any section (start with [body], [incline], ...)", key);
        return 1;
    }
    if (p->section >= p->part_first) {
        part_key(p, key, value);
        return 1;
    }
    const int id = param_of_key(p->sections[p->section], key);
    if (id >= 0) {
        char msg[256];
        if (first_time(p, &p->st.value_line[id], key) == 0 &&
            jc_param_parse(id, value, &p->st.value[id], msg, sizeof msg) != JC_OK)
            fail(p, p->line, "%s: %s", key, msg);
        return 1;
    }
    char allowed[256];
    allowed_keys(p, p->section, allowed, sizeof allowed);
    fail(p, p->line, "unknown key '%s' in [%s] (allowed: %s)", key, p->sections[p->section], allowed);
    return 1;
}

/* ---- applying what was read ---- */

/* Parts numbered 1..n without gaps, each with a kind and a mass. Returns n. */
static int check_parts(parser *p)
{
    int n = 0;
    const int *lines = p->st.section_line + p->part_first;
    while (n < JC_MAX_PARTS && lines[n]) ++n;
    for (int i = n; i < JC_MAX_PARTS; ++i) {
        if (!lines[i]) continue;
        fail(p, lines[i], "[part.%d] without [part.%d] (allowed: parts numbered 1, 2, ... without gaps)", i + 1, n + 1);
        return -1;
    }
    for (int i = 0; i < n; ++i) {
        const int *keys = p->st.part_line[i];
        if (!keys[PK_KIND] || !keys[PK_MASS]) {
            fail(p, lines[i], "[part.%d] needs '%s' (e.g. kind = rod, mass = 32.1 g)", i + 1,
                 !keys[PK_KIND] ? "kind" : "mass");
            return -1;
        }
    }
    return n;
}

/* The file's body: its parts replace the preset's; a disc or hoop without a
 * radius fills the rim. Without parts, a new rim radius takes the disc and
 * hoop parts that filled the old rim along. */
static void apply_body(const staged *st, int radius, int parts, jc_Setup *s)
{
    const double old_rim = s->body.radius_m;
    const double rim = st->value_line[radius] ? st->value[radius] : old_rim;
    if (parts > 0) {
        memset(s->body.parts, 0, sizeof s->body.parts);
        s->body.part_count = parts;
        for (int i = 0; i < parts; ++i) {
            jc_Part part = st->part[i];
            const int filled = part.kind == JC_PART_DISC || part.kind == JC_PART_HOOP;
            if (!st->part_line[i][PK_RADIUS]) part.radius_m = filled ? rim : 0.0;
            s->body.parts[i] = part;
        }
    } else if (rim != old_rim) {
        for (int i = 0; i < s->body.part_count; ++i) {
            jc_Part *part = &s->body.parts[i];
            if ((part->kind == JC_PART_DISC || part->kind == JC_PART_HOOP) && part->radius_m == old_rim)
                part->radius_m = rim;
        }
    }
    s->body.radius_m = rim;
}

/* The keys of one kind (body: the shortcuts that set a part, after the
 * parts are in place; or all the others), each with jc_param_set; 0, or -1
 * with the message at the key's line. */
static int apply_keys(parser *p, int body, int radius, jc_Setup *s)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const int line = p->st.value_line[id];
        if (!line || id == radius || ((jc_param_info(id)->flags & JC_PARAM_BODY) != 0) != body) continue;
        char msg[256], key[64];
        if (jc_param_set(s, id, p->st.value[id], msg, sizeof msg) != JC_OK) {
            snprintf(key, sizeof key, "%s", jc_param_info(id)->key);
            fail(p, line, "%s: %s", key, msg);
            return -1;
        }
    }
    return 0;
}

/* The body (parts, rim), the values, then the [body] keys that set a part;
 * the printed d belongs to the paper's body: a file that changes the body
 * without naming the paper model's d gets the body's exact d. */
static int apply(parser *p, int parts, jc_Setup *s)
{
    const int radius = jc_param_find("radius"), paper_d = jc_param_find("paper-d");
    if (p->st.value_line[radius]) { /* the rim's range, checked as jc_param_set checks it */
        jc_Setup probe = *s;
        char msg[256];
        if (jc_param_set(&probe, radius, p->st.value[radius], msg, sizeof msg) != JC_OK) {
            fail(p, p->st.value_line[radius], "%s: %s", jc_param_info(radius)->key, msg);
            return -1;
        }
    }
    apply_body(&p->st, radius, parts, s);
    if (apply_keys(p, 0, radius, s) != 0) return -1;
    int changed = parts > 0 || p->st.value_line[radius];
    if (changed && !p->st.value_line[paper_d]) s->paper_cm_offset_m = 0.0;
    if (apply_keys(p, 1, radius, s) != 0) return -1;
    for (int id = 0; id < jc_param_count(); ++id)
        changed |= id != radius && p->st.value_line[id] && (jc_param_info(id)->flags & JC_PARAM_BODY);
    if (changed && !p->st.value_line[paper_d]) s->paper_cm_offset_m = 0.0;
    return 0;
}

/* A shortcut with a key it sets (mu with mu_s) would be ambiguous. */
static void check_shortcuts(parser *p)
{
    for (int id = 0; id < jc_param_count(); ++id) {
        const jc_ParamInfo *in = jc_param_info(id);
        if (!p->st.value_line[id] || !in->sets) continue;
        char both[128] = "", either[128] = "";
        int clash = 0;
        for (const char *c = in->sets; *c; c += strspn(c, " ")) {
            char name[40];
            const size_t n = strcspn(c, " ");
            snprintf(name, sizeof name, "%.*s", (int)(n < sizeof name ? n : sizeof name - 1), c);
            c += n;
            const int other = jc_param_find(name);
            if (other < 0) continue;
            clash |= p->st.value_line[other] != 0;
            size_t used = strlen(both);
            snprintf(both + used, sizeof both - used, "%s%s", used ? " and " : "", jc_param_info(other)->key);
            used = strlen(either);
            snprintf(either + used, sizeof either - used, "%s%s", used ? "/" : "", jc_param_info(other)->key);
        }
        if (clash) fail(p, p->st.value_line[id], "%s sets %s; give either %s or %s", in->key, both, in->key, either);
    }
}

int cli_config_parse(const char *name, const char *text, size_t len, jc_Setup *setup, char *err, size_t err_len)
{
    parser *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, err_len, "%s: out of memory", name);
        return -1;
    }
    *p = (parser){.name = name, .text = text, .len = len, .section = SEC_NONE, .err = err, .err_len = err_len};
    p->part_first = cli_config_sections(p->sections);
    for (int i = 0; i < JC_MAX_PARTS; ++i) p->st.part[i] = (jc_Part){JC_PART_DISC, 0.0, 0.0, 0.0, 0.0};
    const int ini_line = ini_parse_stream(read_line, p, on_pair, p);
    /* inih's own complaint, for a line our checks let through. */
    if (ini_line > 0 && (!p->error_line || ini_line < p->error_line)) {
        p->error_line = 0;
        fail(p, ini_line, "expected 'key = value', '[section]' or a comment");
    } else if (ini_line < 0 && !p->error_line) {
        snprintf(err, err_len, "%s: could not be parsed (inih status %d)", name, ini_line);
        p->error_line = -1;
    }
    const int parts = p->error_line ? 0 : check_parts(p);
    if (!p->error_line) check_shortcuts(p);
    const int ok = !p->error_line && apply(p, parts, setup) == 0;
    free(p);
    return ok ? 0 : -1;
}

/* Reads at most FILE_MAX_BYTES + 1 bytes: a larger file is refused, and
 * /dev/zero cannot run the reader forever. */
static char *read_file(const char *path, size_t *len, char *err, size_t err_len)
{
    /* O_NONBLOCK: opening a FIFO without a writer would wait forever; fstat
     * then refuses anything but a regular file before a byte is read. */
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        snprintf(err, err_len, "cannot read %s: %s", path, strerror(errno));
        if (fd >= 0) close(fd);
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(err, err_len, "cannot read %s: %s", path,
                 S_ISDIR(st.st_mode) ? strerror(EISDIR)
                 : S_ISFIFO(st.st_mode) ? "not a regular file (a FIFO)" : "not a regular file (a device or socket)");
        close(fd);
        return NULL;
    }
    if (st.st_size > FILE_MAX_BYTES) {
        snprintf(err, err_len, "%s: too large (allowed: at most %d bytes)", path, FILE_MAX_BYTES);
        close(fd);
        return NULL;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        snprintf(err, err_len, "cannot read %s: %s", path, strerror(errno));
        close(fd);
        return NULL;
    }
    char *buf = malloc(FILE_MAX_BYTES + 1);
    const size_t n = buf ? fread(buf, 1, FILE_MAX_BYTES + 1, f) : 0;
    const int bad = !buf || ferror(f);
    const int saved = errno;
    fclose(f);
    if (bad) {
        snprintf(err, err_len, "cannot read %s: %s", path, buf ? strerror(saved) : "out of memory");
        free(buf);
        return NULL;
    }
    if (n > FILE_MAX_BYTES) {
        snprintf(err, err_len, "%s: too large (allowed: at most %d bytes)", path, FILE_MAX_BYTES);
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

int cli_config_load(const char *path, jc_Setup *setup, char *err, size_t err_len)
{
    size_t len = 0;
    char *text = read_file(path, &len, err, err_len);
    if (!text) return -1;
    const int st = cli_config_parse(path, text, len, setup, err, err_len);
    free(text);
    return st;
}
