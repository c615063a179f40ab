#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
/* A tracked experiment from a file, its bytes or its arrays (docs/tracker.md):
 * the file read whole within a size bound, its format told by its content
 * (trk.c, table.c), then the incline frame (frame.c) and the derived
 * quantities (derive.c). */
#include "track_internal.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int jc_track_from_raw(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, jc_Track *out,
                      char *err, size_t err_len)
{
    int rc = jc_track_frame_raw(name, raw, opt, jc_track_frame_angle(opt), out, err, err_len);
    if (rc == JC_OK) rc = jc_track_derive(name, raw, opt, out, err, err_len);
    if (rc != JC_OK) jc_track_free(out);
    return rc;
}

/* Messages quote the file's bytes (fields, names) and the user's: control
 * characters become '?', so that a message is always one line. */
static void one_line(char *err)
{
    for (char *p = err; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f) *p = '?';
}

static long size_bound(const jc_TrackOptions *opt)
{
    return opt->max_bytes > 0 && opt->max_bytes < JC_TRACK_MAX_BYTES ? opt->max_bytes : JC_TRACK_MAX_BYTES;
}

static int parse(const char *name, const char *data, size_t len, const jc_TrackOptions *opt, jc_Track *out,
                 char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    const long max = size_bound(opt);
    if (len > (size_t)max) {
        snprintf(err, err_len, "%s: larger than %ld bytes", name, max);
        return JC_EINVAL;
    }
    size_t bom = 0;
    if (len >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) bom = 3; /* a UTF-8 byte order mark */
    size_t i = bom;
    while (i < len && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) i++;
    jc_TrackRaw raw;
    /* XML starts with '<'; a table may start with a tab (its name row). */
    const int st = i < len && data[i] == '<' ? jc_track_trk_parse(name, data, len, &raw, err, err_len)
                                             : jc_track_table_parse(name, data + bom, len - bom, &raw, err, err_len);
    if (st != JC_OK) return st;
    const int rc = jc_track_from_raw(name, &raw, opt, out, err, err_len);
    jc_track_raw_free(&raw);
    return rc;
}

int jc_track_parse(const char *name, const char *data, size_t len, const jc_TrackOptions *opt, jc_Track *out,
                   char *err, size_t err_len)
{
    const int st = parse(name, data, len, opt, out, err, err_len);
    if (st != JC_OK && err_len > 0) one_line(err);
    return st;
}

/* A path's bytes into *buf (malloc'd, *len of them), refused beyond max. */
static int slurp(const char *path, long max, char **buf, size_t *len, char *err, size_t err_len)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, err_len, "%s: cannot open: %s", path, strerror(errno));
        return JC_EINVAL;
    }
    /* A regular file's size is known: refused before reading. Others (a pipe)
     * are read whole, at most max + 1 bytes: refused however they grow. */
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > (off_t)max) {
        fclose(f);
        snprintf(err, err_len, "%s: larger than %ld bytes", path, max);
        return JC_EINVAL;
    }
    size_t cap = 65536, n = 0;
    char *b = malloc(cap);
    int st = b ? JC_OK : JC_ENOMEM;
    while (st == JC_OK) {
        if (n == cap) {
            if (cap > (size_t)max) break;
            size_t bigger = cap * 2;
            if (bigger > (size_t)max + 1) bigger = (size_t)max + 1;
            char *p = realloc(b, bigger);
            if (!p) {
                st = JC_ENOMEM;
                break;
            }
            b = p;
            cap = bigger;
        }
        const size_t got = fread(b + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    const int read_error = ferror(f);
    fclose(f);
    if (st != JC_OK || read_error) {
        snprintf(err, err_len, "%s: %s", path, st != JC_OK ? "out of memory" : "read error");
        free(b);
        return st != JC_OK ? st : JC_EINVAL;
    }
    if (n > (size_t)max) {
        snprintf(err, err_len, "%s: larger than %ld bytes", path, max);
        free(b);
        return JC_EINVAL;
    }
    *buf = b;
    *len = n;
    return JC_OK;
}

int jc_track_read_file(const char *path, const jc_TrackOptions *opt, jc_Track *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    char *buf;
    size_t len;
    int st = slurp(path, size_bound(opt), &buf, &len, err, err_len);
    if (st != JC_OK) {
        if (err_len > 0) one_line(err);
        return st;
    }
    st = jc_track_parse(path, buf, len, opt, out, err, err_len);
    free(buf);
    return st;
}

int jc_track_require(const char *name, const jc_Track *t, unsigned needs, char *err, size_t err_len)
{
    if ((needs & JC_TRACK_NEED_CENTRE) &&
        (t->centre_source == JC_TRACK_CENTRE_NONE || !t->note[JC_TRACK_Q_SURFACE].ok)) {
        const jc_TrackNote *n = t->centre_source == JC_TRACK_CENTRE_NONE ? &t->note[JC_TRACK_Q_CENTRE]
                                                                          : &t->note[JC_TRACK_Q_SURFACE];
        snprintf(err, err_len, "%s: the centre's path is %s", name, n->text);
        return JC_EINVAL;
    }
    if ((needs & JC_TRACK_NEED_INCLINE) && t->uphill) {
        snprintf(err, err_len, "%s: the body went up a slope (%s); the model's inclines run downhill from the start",
                 name, t->note[JC_TRACK_Q_SURFACE].text);
        return JC_EINVAL;
    }
    if ((needs & JC_TRACK_NEED_INCLINE) && isnan(t->incline_rad)) {
        snprintf(err, err_len, "%s: the incline's angle is not known: Tracker's axes lie along the incline, so the "
                 "video does not show it; give --incline ANGLE", name);
        return JC_EINVAL;
    }
    return JC_OK;
}
