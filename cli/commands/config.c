/* Experiment files: a whole setup in a small INI file (docs/config.md), read
 * with inih (config_write.c writes them, config_keys.h is the format).
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
#include "config_keys.h"

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

/* The table entry of a field, for the keys that act on others. */
static int scalar_index(size_t offset)
{
    for (int i = 0; i < CLI_CONFIG_SCALAR_COUNT; ++i)
        if (cli_config_scalars[i].offset == offset) return i;
    return -1;
}

/* The keys of a [part.N] section. */
enum { PK_KIND, PK_MASS, PK_OFFSET, PK_RADIUS, PK_ANGLE, PART_KEY_COUNT };
static const char *const part_keys[PART_KEY_COUNT] = {"kind", "mass", "offset", "radius", "angle"};
static const cli_Quantity part_quantities[PART_KEY_COUNT] = {Q_NUMBER, Q_MASS, Q_LENGTH, Q_LENGTH, Q_ANGLE};

/* What the file says, before it is applied; a line number 0 means "not given". */
typedef struct {
    double value[CLI_CONFIG_SCALAR_COUNT];
    int value_line[CLI_CONFIG_SCALAR_COUNT];
    jc_Part part[JC_MAX_PARTS];
    int part_line[JC_MAX_PARTS][PART_KEY_COUNT];
    int section_line[SECTION_COUNT];
    jc_ImpactLaw impact_law; /* [contact] impact_law, a name */
    int impact_law_line;
    double mu;               /* [contact] mu: both coefficients, as --mu */
    int mu_line;
    double shortcut[4];      /* [body] disc_mass, rod_mass, rod_offset, rod_radius, as the options */
    int shortcut_line[4];
} staged;

/* The command line's option names, each accepted in its section as well:
 * a file and the options speak one vocabulary (docs/config.md). */
static const struct {
    int section;
    const char *key, *same_as;
} option_names[] = {
    {SEC_INCLINE, "incline", "angle"}, {SEC_INCLINE, "g", "gravity"}, {SEC_AIR, "air_density", "density"},
    {SEC_PAPER, "paper_d", "cm_offset"},
};
/* [body] keys that set a part, as --disc-mass, --rod-mass, --rod-offset, --rod-radius do. */
static const struct {
    const char *key;
    jc_PartKind kind;
    int field; /* 0 mass, 1 offset, 2 radius */
} body_shortcuts[4] = {{"disc_mass", JC_PART_DISC, 0}, {"rod_mass", JC_PART_ROD, 0}, {"rod_offset", JC_PART_ROD, 1},
                       {"rod_radius", JC_PART_ROD, 2}};

typedef struct {
    const char *name; /* the file, for messages */
    const char *text;
    size_t len, pos;
    int line;         /* of the line handed to inih last */
    int section;      /* the section that line belongs to */
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
static int part_section(const char *name, size_t len)
{
    if (len < 6 || len > 7 || strncmp(name, "part.", 5) != 0 || name[5] == '0') return SEC_NONE;
    int n = 0;
    for (size_t i = 5; i < len; ++i) {
        if (!isdigit((unsigned char)name[i])) return SEC_NONE;
        n = 10 * n + (name[i] - '0');
    }
    return n >= 1 && n <= JC_MAX_PARTS ? SEC_PART_FIRST + n - 1 : SEC_NONE;
}

static int find_section(const char *name, size_t len)
{
    for (int i = 0; i < SEC_PART_FIRST; ++i)
        if (strlen(cli_config_section_names[i]) == len && strncmp(name, cli_config_section_names[i], len) == 0)
            return i;
    return part_section(name, len);
}

static void section_label(int sec, char *buf, size_t n)
{
    if (sec >= SEC_PART_FIRST) snprintf(buf, n, "[part.%d]", sec - SEC_PART_FIRST + 1);
    else snprintf(buf, n, "[%s]", cli_config_section_names[sec]);
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
    const int sec = find_section(line + 1, name_len);
    if (sec == SEC_NONE) {
        fail(p, p->line, "unknown section [%.*s] (allowed: body, part.1 to part.%d, incline, contact, start, air, paper)",
             (int)(name_len > 40 ? 40 : name_len), line + 1, JC_MAX_PARTS);
        return;
    }
    if (p->st.section_line[sec]) {
        char label[24];
        section_label(sec, label, sizeof label);
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

/* "radius, gravity, ..." for a section's messages. */
static void allowed_keys(int sec, char *buf, size_t n)
{
    buf[0] = '\0';
    for (int i = 0; i < CLI_CONFIG_SCALAR_COUNT; ++i) {
        if (cli_config_scalars[i].section != sec) continue;
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, "%s%s", used ? ", " : "", cli_config_scalars[i].key);
    }
    if (sec == SEC_CONTACT) {
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, "%simpact_law, mu", used ? ", " : "");
    }
    for (size_t k = 0; k < sizeof option_names / sizeof option_names[0]; ++k) {
        if (option_names[k].section != sec) continue;
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, ", %s", option_names[k].key);
    }
    for (int k = 0; sec == SEC_BODY && k < 4; ++k) {
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, ", %s", body_shortcuts[k].key);
    }
    for (int k = 0; sec >= SEC_PART_FIRST && k < PART_KEY_COUNT; ++k) {
        const size_t used = strlen(buf);
        snprintf(buf + used, n - used, "%s%s", used ? ", " : "", part_keys[k]);
    }
}

/* 0 if the key was not given before in this section. */
static int first_time(parser *p, int *line_slot, const char *key)
{
    if (*line_slot) {
        char label[24];
        section_label(p->section, label, sizeof label);
        fail(p, p->line, "key '%s' given twice in %s (first on line %d)", key, label, *line_slot);
        return -1;
    }
    *line_slot = p->line;
    return 0;
}

static void part_key(parser *p, const char *key, const char *value)
{
    const int i = p->section - SEC_PART_FIRST;
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

/* inih's handler: one "key = value" line of the current section. */
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
    if (p->section != SEC_NONE && p->section < SEC_PART_FIRST) {
        for (size_t k = 0; k < sizeof option_names / sizeof option_names[0]; ++k)
            if (option_names[k].section == p->section && strcmp(key, option_names[k].key) == 0)
                snprintf(key, sizeof key, "%s", option_names[k].same_as);
        if (p->section == SEC_CONTACT && strcmp(key, "mu") == 0) {
            if (first_time(p, &p->st.mu_line, key) == 0) parse_value(p, key, value, Q_NUMBER, &p->st.mu);
            return 1;
        }
        for (int k = 0; p->section == SEC_BODY && k < 4; ++k) {
            if (strcmp(key, body_shortcuts[k].key) != 0) continue;
            if (first_time(p, &p->st.shortcut_line[k], key) == 0)
                parse_value(p, key, value, body_shortcuts[k].field == 0 ? Q_MASS : Q_LENGTH, &p->st.shortcut[k]);
            return 1;
        }
    }
    if (p->section == SEC_NONE) {
        fail(p, p->line, "key '%s' before any section (start with [body], [incline], ...)", key);
        return 1;
    }
    if (p->section >= SEC_PART_FIRST) {
        part_key(p, key, value);
        return 1;
    }
    if (p->section == SEC_CONTACT && strcmp(key, "impact_law") == 0) {
        if (first_time(p, &p->st.impact_law_line, key) == 0 && jc_impact_law_parse(value, &p->st.impact_law) != JC_OK)
            fail(p, p->line, "impact_law: unknown impact law '%s' (allowed: stronge, poisson, newton)", value);
        return 1;
    }
    for (int i = 0; i < CLI_CONFIG_SCALAR_COUNT; ++i) {
        if (cli_config_scalars[i].section != p->section || strcmp(cli_config_scalars[i].key, key) != 0) continue;
        if (first_time(p, &p->st.value_line[i], key) == 0)
            parse_value(p, key, value, cli_config_scalars[i].q, &p->st.value[i]);
        return 1;
    }
    char allowed[256];
    allowed_keys(p->section, allowed, sizeof allowed);
    fail(p, p->line, "unknown key '%s' in [%s] (allowed: %s)", key, cli_config_section_names[p->section], allowed);
    return 1;
}

/* ---- applying what was read ---- */

/* Parts numbered 1..n without gaps, each with a kind and a mass. Returns n. */
static int check_parts(parser *p)
{
    int n = 0;
    while (n < JC_MAX_PARTS && p->st.section_line[SEC_PART_FIRST + n]) ++n;
    for (int i = n; i < JC_MAX_PARTS; ++i) {
        if (!p->st.section_line[SEC_PART_FIRST + i]) continue;
        fail(p, p->st.section_line[SEC_PART_FIRST + i], "[part.%d] without [part.%d] (allowed: parts numbered 1, 2, ... without gaps)",
             i + 1, n + 1);
        return -1;
    }
    for (int i = 0; i < n; ++i) {
        const int *lines = p->st.part_line[i];
        if (!lines[PK_KIND] || !lines[PK_MASS]) {
            fail(p, p->st.section_line[SEC_PART_FIRST + i], "[part.%d] needs '%s' (e.g. kind = rod, mass = 32.1 g)", i + 1,
                 !lines[PK_KIND] ? "kind" : "mass");
            return -1;
        }
    }
    return n;
}

/* The file's body: its parts replace the preset's; a disc or hoop without a
 * radius fills the rim. Without parts, a new rim radius takes the disc and
 * hoop parts that filled the old rim along (as --radius does). */
static void apply_body(const staged *st, int parts, jc_Setup *s)
{
    const int r = scalar_index(offsetof(jc_Setup, body.radius_m));
    const double old_rim = s->body.radius_m;
    const double rim = st->value_line[r] ? st->value[r] : old_rim;
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

static void apply(const staged *st, int parts, jc_Setup *s)
{
    apply_body(st, parts, s);
    for (int i = 0; i < CLI_CONFIG_SCALAR_COUNT; ++i)
        if (st->value_line[i]) memcpy((char *)s + cli_config_scalars[i].offset, &st->value[i], sizeof(double));
    if (st->impact_law_line) s->impact_law = st->impact_law;
    /* The printed d belongs to the paper's body: a file that changes the body
     * without naming the paper model's d gets the body's exact d. */
    const int radius_given = st->value_line[scalar_index(offsetof(jc_Setup, body.radius_m))];
    const int paper_d_given = st->value_line[scalar_index(offsetof(jc_Setup, paper_cm_offset_m))];
    if ((parts > 0 || radius_given) && !paper_d_given) s->paper_cm_offset_m = 0.0;
}

/* mu sets both coefficients: with mu_s or mu_k it would be ambiguous. */
static void check_mu(parser *p)
{
    const int s = scalar_index(offsetof(jc_Setup, mu_static)), k = scalar_index(offsetof(jc_Setup, mu_kinetic));
    if (p->st.mu_line && (p->st.value_line[s] || p->st.value_line[k]))
        fail(p, p->st.mu_line, "mu sets both mu_s and mu_k; give either mu or mu_s/mu_k");
}

/* [contact] mu, and the [body] keys that set a part (after the parts are
 * in place); 0, or -1 with the message. */
static int apply_shortcuts(parser *p, jc_Setup *s)
{
    if (p->st.mu_line) s->mu_static = s->mu_kinetic = p->st.mu;
    int changed = 0;
    for (int k = 0; k < 4; ++k) {
        if (!p->st.shortcut_line[k]) continue;
        jc_Part *part = NULL;
        for (int i = s->body.part_count - 1; i >= 0; --i)
            if (s->body.parts[i].kind == body_shortcuts[k].kind) part = &s->body.parts[i];
        if (!part) {
            fail(p, p->st.shortcut_line[k], "%s needs a body with a %s part", body_shortcuts[k].key,
                 jc_part_kind_name(body_shortcuts[k].kind));
            return -1;
        }
        const int f = body_shortcuts[k].field;
        *(f == 0 ? &part->mass_kg : f == 1 ? &part->offset_m : &part->radius_m) = p->st.shortcut[k];
        changed = 1;
    }
    /* The printed d belongs to the paper's body, as with the options. */
    if (changed && !p->st.value_line[scalar_index(offsetof(jc_Setup, paper_cm_offset_m))]) s->paper_cm_offset_m = 0.0;
    return 0;
}

int cli_config_parse(const char *name, const char *text, size_t len, jc_Setup *setup, char *err, size_t err_len)
{
    parser *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, err_len, "%s: out of memory", name);
        return -1;
    }
    *p = (parser){.name = name, .text = text, .len = len, .section = SEC_NONE, .err = err, .err_len = err_len};
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
    if (!p->error_line) check_mu(p);
    const int ok = !p->error_line;
    if (ok) apply(&p->st, parts, setup);
    if (ok && apply_shortcuts(p, setup) != 0) {
        free(p);
        return -1;
    }
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
