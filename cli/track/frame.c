/* A file's tracks put in the incline frame of docs/physics.md §1: which
 * track is the centre and which the mark, the direction of "downhill", the
 * frame times and their gaps and jitter. */
#include "raw.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Case-insensitive: whether name holds word. */
static int has_word(const char *name, const char *word)
{
    const size_t n = strlen(name), w = strlen(word);
    for (size_t i = 0; i + w <= n; ++i) {
        size_t k = 0;
        while (k < w && tolower((unsigned char)name[i + k]) == word[k]) k++;
        if (k == w) return 1;
    }
    return 0;
}

static int find_named(const cli_RawData *raw, const char *name)
{
    for (int i = 0; i < raw->track_count; ++i)
        if (strcmp(raw->tracks[i].name, name) == 0) return i;
    return -1;
}

/* The one track whose name holds one of words, other than skip; -1 if none or several. */
static int find_by_words(const cli_RawData *raw, const char *const *words, int nwords, int skip)
{
    int found = -1;
    for (int i = 0; i < raw->track_count; ++i) {
        if (i == skip) continue;
        int hit = 0;
        for (int w = 0; w < nwords && !hit; ++w) hit = has_word(raw->tracks[i].name, words[w]);
        if (hit) {
            if (found >= 0) return -1;
            found = i;
        }
    }
    return found;
}

static void list_tracks(const cli_RawData *raw, char *buf, size_t len)
{
    buf[0] = '\0';
    size_t used = 0;
    for (int i = 0; i < raw->track_count && used + 4 < len; ++i) {
        const int w = snprintf(buf + used, len - used, "%s'%s'", i ? ", " : "", raw->tracks[i].name);
        if (w < 0) break;
        used += (size_t)w;
        if (used >= len) used = len - 1;
    }
}

static int pick_tracks(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, int *centre,
                       int *mark, char *err, size_t err_len)
{
    static const char *const centre_words[] = {"centre", "center", "axle", "axis", "hub"};
    static const char *const mark_words[] = {"mark", "rod", "dot", "off"};
    char tracks[512];
    list_tracks(raw, tracks, sizeof tracks);
    *centre = *mark = -1;
    if (opt->centre) {
        *centre = find_named(raw, opt->centre);
        if (*centre < 0) {
            snprintf(err, err_len, "%s: no track named '%s' for --centre (tracks: %s)", name, opt->centre, tracks);
            return -1;
        }
    }
    if (opt->mark && opt->mark[0]) {
        *mark = find_named(raw, opt->mark);
        if (*mark < 0) {
            snprintf(err, err_len, "%s: no track named '%s' for --mass (tracks: %s)", name, opt->mark, tracks);
            return -1;
        }
    }
    if (*centre < 0) *centre = find_by_words(raw, centre_words, 5, *mark);
    if (*centre < 0 && raw->track_count == 1) *centre = 0;
    if (*centre < 0 && *mark >= 0 && raw->track_count == 2) *centre = 1 - *mark;
    if (*centre < 0) {
        snprintf(err, err_len, "%s: which track is the centre? give --centre NAME (tracks: %s)", name, tracks);
        return -1;
    }
    if (!opt->mark) {
        *mark = find_by_words(raw, mark_words, 4, *centre);
        if (*mark < 0 && raw->track_count == 2 && find_by_words(raw, centre_words, 5, -1) == *centre)
            *mark = 1 - *centre;
        if (*mark < 0 && raw->track_count > 1) {
            snprintf(err, err_len, "%s: which track is the off-centre mass? give --mass NAME, or --mass '' for none (tracks: %s)",
                     name, tracks);
            return -1;
        }
    }
    if (*mark == *centre) {
        snprintf(err, err_len, "%s: the centre and the mass are the same track '%s'", name, raw->tracks[*centre].name);
        return -1;
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int cli_track_from_raw(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, cli_Track *out,
                       char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    if (!(opt->radius_m > 0) || !(opt->incline_rad >= 0 && opt->incline_rad < CLI_PI / 2)) {
        snprintf(err, err_len, "%s: the radius and incline angle must be given (r > 0, 0 <= incline < 90 deg)", name);
        return -1;
    }
    int ci, mi;
    if (pick_tracks(name, raw, opt, &ci, &mi, err, err_len) != 0) return -1;
    const cli_RawTrack *C = &raw->tracks[ci];
    const cli_RawTrack *K = mi >= 0 ? &raw->tracks[mi] : NULL;
    snprintf(out->format, sizeof out->format, "%s", raw->format);
    out->track_count = raw->track_count;
    for (int i = 0; i < raw->track_count; ++i) {
        memcpy(out->track_names[i], raw->tracks[i].name, CLI_TRACK_NAME_LEN);
        long k = 0;
        for (long f = 0; f < raw->frames; ++f) k += !isnan(raw->tracks[i].x_m[f]);
        out->track_frames[i] = k;
    }
    out->clip_frames = raw->frames;
    out->scale_px_per_m = raw->px_per_m;
    out->scale_varies = raw->scale_varies;
    out->tape_length_m = raw->tape_length_m;
    out->incline_rad = opt->incline_rad;
    out->radius_m = opt->radius_m;
    memcpy(out->centre_name, C->name, CLI_TRACK_NAME_LEN);
    if (K) memcpy(out->mark_name, K->name, CLI_TRACK_NAME_LEN);
    out->has_mark = K != NULL;
    long first = -1, last = -1, kept = 0;
    for (long f = 0; f < raw->frames; ++f)
        if (!isnan(C->x_m[f])) {
            if (first < 0) first = f;
            last = f;
            kept++;
        }
    if (kept < 3) {
        snprintf(err, err_len, "%s: the centre track '%s' has %ld position(s); at least 3 are needed", name, C->name,
                 kept);
        return -1;
    }
    /* The frame duration: the clip's, or the median step of the table's times. */
    double dt = raw->nominal_dt_s;
    if (isnan(dt)) {
        double *d = malloc((size_t)(raw->frames - 1) * sizeof *d);
        if (!d) {
            snprintf(err, err_len, "%s: out of memory", name);
            return -1;
        }
        for (long f = 1; f < raw->frames; ++f) d[f - 1] = raw->t_s[f] - raw->t_s[f - 1];
        qsort(d, (size_t)(raw->frames - 1), sizeof *d, cmp_double);
        const double step = d[(raw->frames - 1) / 2];
        free(d);
        /* The median step, refined: the whole span over the frames it holds
         * (each step a whole number of frames), so that jitter averages out. */
        double frames_spanned = 0;
        for (long f = 1; f < raw->frames; ++f) frames_spanned += fmax(1.0, floor((raw->t_s[f] - raw->t_s[f - 1]) / step + 0.5));
        dt = (raw->t_s[raw->frames - 1] - raw->t_s[0]) / frames_spanned;
    }
    if (!(dt > 0) || !isfinite(1.0 / dt)) {
        snprintf(err, err_len, "%s: the frames have no time step", name);
        return -1;
    }
    out->frame_rate_hz = 1.0 / dt;
    const size_t bytes = (size_t)kept * sizeof(double);
    out->t_s = malloc(bytes);
    out->x_m = malloc(bytes);
    out->y_m = malloc(bytes);
    out->theta_rad = malloc(bytes);
    out->omega_radps = malloc(bytes);
    out->airborne = calloc((size_t)kept, 1);
    if (!out->t_s || !out->x_m || !out->y_m || !out->theta_rad || !out->omega_radps || !out->airborne) {
        cli_track_free(out);
        snprintf(err, err_len, "%s: out of memory", name);
        return -1;
    }
    /* Downhill is where the centre went: Tracker's x may point either way. */
    const double s = C->x_m[last] >= C->x_m[first] ? 1.0 : -1.0;
    double xh[2], nh[2];
    if (opt->axes == CLI_TRACK_AXES_INCLINE) {
        xh[0] = s, xh[1] = 0, nh[0] = 0, nh[1] = 1;
    } else {
        const double ca = cos(opt->incline_rad), sa = sin(opt->incline_rad);
        xh[0] = s * ca, xh[1] = -sa, nh[0] = s * sa, nh[1] = ca;
    }
    const double t0 = raw->t_s[0];
    long n = 0, prev = -1, marks = 0;
    for (long f = first; f <= last; ++f) {
        if (isnan(C->x_m[f])) {
            out->gaps++;
            continue;
        }
        const double wx = C->x_m[f], wy = C->y_m[f];
        out->t_s[n] = raw->t_s[f] - t0;
        out->x_m[n] = wx * xh[0] + wy * xh[1];
        out->y_m[n] = wx * nh[0] + wy * nh[1]; /* the normal coordinate; derive.c makes it a height */
        out->theta_rad[n] = NAN;
        if (K && !isnan(K->x_m[f])) {
            const double dx = K->x_m[f] - wx, dy = K->y_m[f] - wy;
            out->theta_rad[n] = atan2(dx * xh[0] + dy * xh[1], dx * nh[0] + dy * nh[1]);
            out->omega_radps[marks++] = hypot(dx, dy); /* scratch until derive.c */
        }
        if (prev >= 0) {
            const double step = out->t_s[n] - out->t_s[n - 1];
            const double k = fmax(1.0, floor(step / dt + 0.5));
            if (!(k <= (double)CLI_TRACK_MAX_FRAMES)) {
                snprintf(err, err_len, "%s: the time jumps by %g s after %g s, more than %ld frames of %g s", name,
                         step, out->t_s[n - 1], CLI_TRACK_MAX_FRAMES, dt);
                cli_track_free(out);
                return -1;
            }
            const long missing_rows = (long)k - 1 - (f - prev - 1); /* rows a table left out */
            if (missing_rows > 0) out->gaps += missing_rows;
            const double j = fabs(step - k * dt);
            if (j > out->dt_jitter_s) out->dt_jitter_s = j;
        }
        prev = f;
        n++;
    }
    out->n = n;
    out->mark_radius_m = NAN;
    if (marks > 0) {
        qsort(out->omega_radps, (size_t)marks, sizeof(double), cmp_double);
        out->mark_radius_m = out->omega_radps[marks / 2];
    }
    out->x0_m = out->x_m[0];
    out->sigma_m = isnan(raw->px_per_m) ? NAN : 1.0 / raw->px_per_m;
    return 0;
}
