/* cli_track_load: a tracked experiment from a file (docs/tracker.md): the
 * file read whole within a size bound, its format told by its content,
 * then the incline frame (frame.c) and the derived quantities (derive.c). */
#include "raw.h"

#include <stdio.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void cli_track_options_default(cli_TrackOptions *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->incline_rad = NAN;
    opt->radius_m = 0.10;
    opt->gravity_mps2 = 9.81;
    opt->axes = CLI_TRACK_AXES_LEVEL;
    opt->hop_sigmas = 5.0;
    opt->max_bytes = CLI_TRACK_MAX_BYTES;
}

int cli_track_from_raw_data(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, cli_Track *out,
                            char *err, size_t err_len)
{
    int rc = cli_track_from_raw(name, raw, opt, cli_track_frame_angle(opt), out, err, err_len);
    if (rc == 0) rc = cli_track_derive(name, raw, opt, out, err, err_len);
    if (rc != 0) cli_track_free(out);
    return rc;
}

int cli_raw_alloc(cli_RawData *raw, long frames, int track_count)
{
    raw->frames = frames;
    raw->track_count = track_count;
    raw->t_s = malloc((size_t)frames * sizeof(double));
    int ok = raw->t_s != NULL;
    for (int i = 0; i < track_count; ++i) {
        raw->tracks[i].x_m = malloc((size_t)frames * sizeof(double));
        raw->tracks[i].y_m = malloc((size_t)frames * sizeof(double));
        ok = ok && raw->tracks[i].x_m && raw->tracks[i].y_m;
    }
    if (!ok) {
        cli_raw_free(raw);
        return -1;
    }
    for (long f = 0; f < frames; ++f) {
        raw->t_s[f] = NAN;
        for (int i = 0; i < track_count; ++i) raw->tracks[i].x_m[f] = raw->tracks[i].y_m[f] = NAN;
    }
    return 0;
}

void cli_raw_free(cli_RawData *raw)
{
    free(raw->t_s);
    raw->t_s = NULL;
    for (int i = 0; i < CLI_TRACK_MAX_TRACKS; ++i) {
        free(raw->tracks[i].x_m);
        free(raw->tracks[i].y_m);
        raw->tracks[i].x_m = raw->tracks[i].y_m = NULL;
    }
    raw->track_count = 0;
    raw->frames = 0;
}

/* Messages quote the file's bytes (fields, names) and the user's: control
 * characters become '?', so that a message is always one line. */
static void one_line(char *err)
{
    for (char *p = err; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f) *p = '?';
}

static int parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                 char *err, size_t err_len);

int cli_track_parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                    char *err, size_t err_len)
{
    const int st = parse(name, data, len, opt, out, err, err_len);
    if (st != 0 && err_len > 0) one_line(err);
    return st;
}

static int parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                 char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    const long max = opt->max_bytes > 0 && opt->max_bytes < CLI_TRACK_MAX_BYTES ? opt->max_bytes : CLI_TRACK_MAX_BYTES;
    if (len > (size_t)max) {
        snprintf(err, err_len, "%s: larger than %ld bytes", name, max);
        return -1;
    }
    size_t bom = 0;
    if (len >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) bom = 3; /* a UTF-8 byte order mark */
    size_t i = bom;
    while (i < len && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) i++;
    cli_RawData raw;
    /* XML starts with '<'; a table may start with a tab (its name row). */
    const int st = i < len && data[i] == '<' ? cli_trk_parse(name, data, len, &raw, err, err_len)
                                             : cli_table_parse(name, data + bom, len - bom, &raw, err, err_len);
    if (st != 0) return -1;
    const int rc = cli_track_from_raw_data(name, &raw, opt, out, err, err_len);
    cli_raw_free(&raw);
    return rc;
}

int cli_track_load(const char *path, const cli_TrackOptions *opt, cli_Track *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    const long max = opt->max_bytes > 0 && opt->max_bytes < CLI_TRACK_MAX_BYTES ? opt->max_bytes : CLI_TRACK_MAX_BYTES;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, err_len, "%s: cannot open: %s", path, strerror(errno));
        one_line(err);
        return -1;
    }
    /* A regular file's size is known: refused before reading. Others (a pipe)
     * are read whole, at most max + 1 bytes: refused however they grow. */
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > (off_t)max) {
        fclose(f);
        snprintf(err, err_len, "%s: larger than %ld bytes", path, max);
        one_line(err);
        return -1;
    }
    size_t cap = 65536, len = 0;
    char *buf = malloc(cap);
    int st = buf ? 0 : -1;
    while (st == 0) {
        if (len == cap) {
            if (cap > (size_t)max) break;
            size_t bigger = cap * 2;
            if (bigger > (size_t)max + 1) bigger = (size_t)max + 1;
            char *p = realloc(buf, bigger);
            if (!p) { st = -1; break; }
            buf = p;
            cap = bigger;
        }
        const size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    const int read_error = ferror(f);
    fclose(f);
    if (st != 0 || read_error) {
        snprintf(err, err_len, "%s: %s", path, st != 0 ? "out of memory" : "read error");
        one_line(err);
        free(buf);
        return -1;
    }
    if (len > (size_t)max) {
        snprintf(err, err_len, "%s: larger than %ld bytes", path, max);
        one_line(err);
        free(buf);
        return -1;
    }
    st = cli_track_parse(path, buf, len, opt, out, err, err_len);
    free(buf);
    return st;
}

int cli_track_require(const char *name, const cli_Track *t, unsigned needs, char *err, size_t err_len)
{
    if ((needs & CLI_NEED_CENTRE) && (t->centre_source == CLI_CENTRE_NONE || !t->note[CLI_Q_SURFACE].ok)) {
        const cli_TrackNote *n = t->centre_source == CLI_CENTRE_NONE ? &t->note[CLI_Q_CENTRE] : &t->note[CLI_Q_SURFACE];
        snprintf(err, err_len, "%s: the centre's path is %s", name, n->text);
        return -1;
    }
    if ((needs & CLI_NEED_INCLINE) && t->uphill) {
        snprintf(err, err_len, "%s: the body went up a slope (%s); the model's inclines run downhill from the start",
                 name, t->note[CLI_Q_SURFACE].text);
        return -1;
    }
    if ((needs & CLI_NEED_INCLINE) && isnan(t->incline_rad)) {
        snprintf(err, err_len, "%s: the incline's angle is not known: Tracker's axes lie along the incline, so the "
                 "video does not show it; give --incline ANGLE", name);
        return -1;
    }
    return 0;
}

void cli_track_free(cli_Track *t)
{
    if (!t) return;
    double *arrays[] = {t->t_s, t->x_m, t->y_m, t->centre_sigma_m, t->mark_x_m, t->mark_y_m, t->theta_rad,
                        t->omega_radps};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) free(arrays[k]);
    free(t->contact);
    free(t->airborne);
    free(t->hop);
    memset(t, 0, sizeof *t);
}
