/* A file's tracks put in a frame turned by a given angle from Tracker's
 * axes: which track is the centre and which the mark, the direction of
 * "downhill", the frame times and their gaps and jitter. derive.c then
 * finds the surface and turns the frame onto it. */
#include "track_internal.h"

#include <ctype.h>
#include <gsl/gsl_sort_double.h>
#include <math.h>
#include <stdio.h>
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

static int find_named(const jc_TrackRaw *raw, const char *name)
{
    for (int i = 0; i < raw->track_count; ++i)
        if (strcmp(raw->tracks[i].name, name) == 0) return i;
    return -1;
}

static const char *const centre_words[] = {"centre", "center", "axle", "axis", "hub"};
static const char *const mark_words[] = {"mark", "rod", "dot", "off", "led", "rim", "light", "lamp", "spot"};
#define N_CENTRE_WORDS (int)(sizeof centre_words / sizeof centre_words[0])
#define N_MARK_WORDS (int)(sizeof mark_words / sizeof mark_words[0])

static int named_like(const char *name, const char *const *words, int nwords)
{
    for (int w = 0; w < nwords; ++w)
        if (has_word(name, words[w])) return 1;
    return 0;
}

int jc_track_named_centre(const char *name)
{
    return named_like(name, centre_words, N_CENTRE_WORDS);
}

/* The one track whose name holds one of words, other than skip; -1 if none or several. */
static int find_by_words(const jc_TrackRaw *raw, const char *const *words, int nwords, int skip)
{
    int found = -1;
    for (int i = 0; i < raw->track_count; ++i) {
        if (i == skip || !named_like(raw->tracks[i].name, words, nwords)) continue;
        if (found >= 0) return -1;
        found = i;
    }
    return found;
}

void jc_track_list_names(const jc_TrackRaw *raw, char *buf, size_t len)
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

/* Two tracks, neither named: the centre is the one whose frames keep to a
 * line (the surface, r below) for runs of contact; a mark on the body
 * swings across any line by its distance from the centre. The one with at
 * least three times the other's frames in contact is the centre; -1: not
 * told. */
static long contact_frames_of(const jc_TrackPoints *k, const jc_TrackRaw *raw, double dt)
{
    const long n = raw->frames;
    double *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y), *w = malloc((size_t)(2 * n) * sizeof *w);
    unsigned char *keep = malloc((size_t)n);
    long m = 0, contact = 0;
    if (x && y && w && keep) {
        for (long f = 0; f < n; ++f)
            if (!isnan(k->x_m[f])) x[m] = k->x_m[f], y[m] = k->y_m[f], m++;
        jc_TrackSurfaceLine L;
        if (jc_track_surface_fit(x, y, m, dt > 0 ? 1.0 / dt : NAN, JC_TRACK_NOISE_FLOOR_M,
                                 jc_track_frame_noise(x, y, m, w), keep, &L) == 0)
            contact = L.contact;
    }
    free(x), free(y), free(w), free(keep);
    return contact;
}

static int centre_by_motion(const jc_TrackRaw *raw, double dt)
{
    const long c0 = contact_frames_of(&raw->tracks[0], raw, dt), c1 = contact_frames_of(&raw->tracks[1], raw, dt);
    if (c0 >= 3 && c0 >= 3 * c1) return 0;
    if (c1 >= 3 && c1 >= 3 * c0) return 1;
    return -1;
}

/* Picks the tracks. The centre is -1 when the file has only a mark (a
 * single track named as one, told by derive.c's rolling fit otherwise) or
 * when it cannot be told (t->centre_ambiguous). -1 with a message only for
 * a name the caller gave that is not in the file. */
static int pick_tracks(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, double dt, int *centre,
                       int *mark, int *ambiguous, char *err, size_t err_len)
{
    char tracks[512];
    jc_track_list_names(raw, tracks, sizeof tracks);
    *centre = *mark = -1;
    *ambiguous = 0;
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
    if (*mark >= 0 && *mark == *centre) {
        snprintf(err, err_len, "%s: --centre and --mass name the same track '%s'", name, raw->tracks[*mark].name);
        return -1;
    }
    const int no_mark = opt->mark && !opt->mark[0];
    if (*centre < 0) *centre = find_by_words(raw, centre_words, N_CENTRE_WORDS, *mark);
    if (*centre < 0 && raw->track_count == 1 && !opt->mark) {
        /* A single track: a centre, unless it is named as a mark (derive.c
         * tells an unnamed one by its motion). */
        if (named_like(raw->tracks[0].name, mark_words, N_MARK_WORDS)) *mark = 0;
        else *centre = 0;
        return 0;
    }
    if (*centre < 0 && raw->track_count == 1 && no_mark) *centre = 0;
    if (*centre < 0 && *mark >= 0 && raw->track_count == 2) *centre = 1 - *mark;
    if (*centre < 0 && raw->track_count == 2 && !opt->mark && !opt->centre) {
        *centre = centre_by_motion(raw, dt);
        if (*centre >= 0) *mark = 1 - *centre;
    }
    if (*centre < 0 && *mark >= 0 && raw->track_count == 1) return 0; /* a mark named alone: mark only */
    if (*centre < 0) {
        *ambiguous = 1;
        return 0;
    }
    if (*mark < 0 && !no_mark && !opt->mark) {
        *mark = find_by_words(raw, mark_words, N_MARK_WORDS, *centre);
        if (*mark < 0 && raw->track_count == 2) *mark = 1 - *centre;
    }
    return 0;
}

/* The frame duration: the clip's, or the median step of the table's times
 * refined over the whole span (each step a whole number of frames, so that
 * jitter averages out). NaN when the rows have no time step. */
static double frame_step(const jc_TrackRaw *raw)
{
    if (!isnan(raw->nominal_dt_s)) return raw->nominal_dt_s;
    if (raw->frames < 2) return NAN;
    double *d = malloc((size_t)(raw->frames - 1) * sizeof *d);
    if (!d) return NAN;
    for (long f = 1; f < raw->frames; ++f) d[f - 1] = raw->t_s[f] - raw->t_s[f - 1];
    /* The middle step (the upper of the middle two for an even count, not
     * their mean: it only sets the unit the steps are rounded to). */
    gsl_sort(d, 1, (size_t)(raw->frames - 1));
    const double step = d[(raw->frames - 1) / 2];
    free(d);
    if (!(step > 0)) return NAN;
    double frames_spanned = 0;
    for (long f = 1; f < raw->frames; ++f)
        frames_spanned += fmax(1.0, floor((raw->t_s[f] - raw->t_s[f - 1]) / step + 0.5));
    return (raw->t_s[raw->frames - 1] - raw->t_s[0]) / frames_spanned;
}

static int alloc_frames(jc_Track *t, long n)
{
    const size_t bytes = (size_t)(n > 0 ? n : 1) * sizeof(double);
    double **arrays[] = {&t->t_s, &t->x_m, &t->y_m, &t->centre_sigma_m, &t->mark_x_m, &t->mark_y_m, &t->theta_rad,
                         &t->omega_radps};
    int ok = 1;
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) ok = (*arrays[k] = malloc(bytes)) && ok;
    t->contact = calloc((size_t)(n > 0 ? n : 1), 1);
    t->airborne = calloc((size_t)(n > 0 ? n : 1), 1);
    return ok && t->contact && t->airborne ? 0 : -1;
}

static void copy_report(const jc_TrackRaw *raw, const jc_TrackOptions *opt, jc_Track *out)
{
    snprintf(out->format, sizeof out->format, "%s", raw->format);
    out->track_count = raw->track_count;
    for (int i = 0; i < raw->track_count; ++i) {
        memcpy(out->track_names[i], raw->tracks[i].name, JC_TRACK_NAME_LEN);
        long k = 0;
        for (long f = 0; f < raw->frames; ++f) k += !isnan(raw->tracks[i].x_m[f]);
        out->track_frames[i] = k;
    }
    out->clip_frames = raw->frames;
    out->scale_px_per_m = raw->px_per_m;
    out->scale_varies = raw->scale_varies;
    out->tape_length_m = raw->tape_length_m;
    out->radius_m = opt->radius_m;
    out->given_incline_rad = opt->incline_rad;
    out->axes = opt->axes;
    out->hop_sigmas = opt->hop_sigmas >= 1 ? opt->hop_sigmas : 5.0;
    out->incline_rad = out->incline_sigma_rad = NAN;
    out->mark_radius_m = out->mark_radius_sigma_m = out->centre_sigma_median_m = NAN;
    out->centre_sigma_max_m = NAN;
    out->surface_tilt_rad = out->surface_tilt_sigma_rad = out->surface_sigma_m = NAN;
    out->sigma_m = out->x0_m = out->hop_threshold_m = NAN;
}

/* The frames of the primary track (the centre, or the mark without one),
 * in the frame turned by angle_rad from Tracker's axes (level axes) or in
 * Tracker's own (incline axes), x pointing where the primary track went.
 * -1 when the time jumps by more frames than a clip may hold, -2 for a
 * position beyond JC_TRACK_MAX_COORD_M. */
static int convert(const jc_TrackRaw *raw, const jc_TrackPoints *P, const jc_TrackPoints *K, long first, long last,
                   double dt, double angle_rad, jc_Track *out)
{
    const double s = P->x_m[last] >= P->x_m[first] ? 1.0 : -1.0;
    double xh[2], nh[2];
    if (out->axes == JC_TRACK_AXES_INCLINE) {
        xh[0] = s, xh[1] = 0, nh[0] = 0, nh[1] = 1;
    } else {
        const double ca = cos(angle_rad), sa = sin(angle_rad);
        xh[0] = s * ca, xh[1] = -sa, nh[0] = s * sa, nh[1] = ca;
    }
    const double t0 = raw->t_s[0];
    const int primary_is_centre = out->centre_source == JC_TRACK_CENTRE_TRACKED;
    long n = 0, prev = -1;
    for (long f = first; f <= last; ++f) {
        if (isnan(P->x_m[f])) {
            out->gaps++;
            continue;
        }
        out->t_s[n] = raw->t_s[f] - t0;
        out->x_m[n] = out->y_m[n] = out->mark_x_m[n] = out->mark_y_m[n] = NAN;
        out->theta_rad[n] = out->omega_radps[n] = out->centre_sigma_m[n] = NAN;
        const jc_TrackPoints *C = primary_is_centre ? P : NULL, *M = primary_is_centre ? K : P;
        if (C) {
            out->x_m[n] = C->x_m[f] * xh[0] + C->y_m[f] * xh[1];
            out->y_m[n] = C->x_m[f] * nh[0] + C->y_m[f] * nh[1];
        }
        if (M && !isnan(M->x_m[f])) {
            out->mark_x_m[n] = M->x_m[f] * xh[0] + M->y_m[f] * xh[1];
            out->mark_y_m[n] = M->x_m[f] * nh[0] + M->y_m[f] * nh[1];
        }
        /* Positions a ramp could have: far ones would lose every digit in
         * the sums that follow (NaN, no position, passes). */
        if (fabs(out->x_m[n]) > JC_TRACK_MAX_COORD_M || fabs(out->y_m[n]) > JC_TRACK_MAX_COORD_M ||
            fabs(out->mark_x_m[n]) > JC_TRACK_MAX_COORD_M || fabs(out->mark_y_m[n]) > JC_TRACK_MAX_COORD_M)
            return -2;
        if (prev >= 0) {
            const double step = out->t_s[n] - out->t_s[n - 1];
            const double k = fmax(1.0, floor(step / dt + 0.5));
            if (!(k <= (double)JC_TRACK_MAX_FRAMES)) return -1;
            const long missing_rows = (long)k - 1 - (f - prev - 1); /* rows a table left out */
            if (missing_rows > 0) out->gaps += missing_rows;
            const double j = fabs(step - k * dt);
            if (j > out->dt_jitter_s) out->dt_jitter_s = j;
        }
        prev = f;
        n++;
    }
    out->n = n;
    return 0;
}

int jc_track_frame_raw(const char *name, const jc_TrackRaw *raw, const jc_TrackOptions *opt, double angle_rad,
                       jc_Track *out, char *err, size_t err_len)
{
    memset(out, 0, sizeof *out);
    if (!(opt->radius_m > 0) || !(isnan(opt->incline_rad) || (opt->incline_rad >= 0 && opt->incline_rad < JC_TRACK_PI / 2))) {
        snprintf(err, err_len, "%s: the radius must be > 0 and the incline angle in [0, 90) deg", name);
        return JC_EINVAL;
    }
    copy_report(raw, opt, out);
    int ci, mi, ambiguous;
    const double dt = frame_step(raw);
    if (pick_tracks(name, raw, opt, dt, &ci, &mi, &ambiguous, err, err_len) != 0) return JC_EINVAL;
    out->centre_ambiguous = ambiguous;
    out->centre_source = ci >= 0 ? JC_TRACK_CENTRE_TRACKED : mi >= 0 ? JC_TRACK_CENTRE_FROM_MARK : JC_TRACK_CENTRE_NONE;
    if (ci >= 0) memcpy(out->centre_name, raw->tracks[ci].name, JC_TRACK_NAME_LEN);
    if (mi >= 0) memcpy(out->mark_name, raw->tracks[mi].name, JC_TRACK_NAME_LEN);
    out->has_mark = mi >= 0;
    out->frame_rate_hz = dt > 0 && isfinite(1.0 / dt) ? 1.0 / dt : NAN;
    const jc_TrackPoints *P = ci >= 0 ? &raw->tracks[ci] : mi >= 0 ? &raw->tracks[mi] : NULL;
    long first = -1, last = -1, kept = 0;
    for (long f = 0; P && f < raw->frames; ++f)
        if (!isnan(P->x_m[f])) {
            if (first < 0) first = f;
            last = f;
            kept++;
        }
    if (alloc_frames(out, kept) != 0) {
        jc_track_free(out);
        snprintf(err, err_len, "%s: out of memory", name);
        return JC_ENOMEM;
    }
    if (kept == 0 || !(dt > 0)) {
        out->centre_source = ambiguous ? JC_TRACK_CENTRE_NONE : out->centre_source;
        return JC_OK;
    }
    const int conv = convert(raw, P, mi >= 0 && ci >= 0 ? &raw->tracks[mi] : NULL, first, last, dt, angle_rad, out);
    if (conv != 0) {
        if (conv == -2)
            snprintf(err, err_len, "%s: a position %g m or more from the origin (allowed: within %g m)", name,
                     JC_TRACK_MAX_COORD_M, JC_TRACK_MAX_COORD_M);
        else
            snprintf(err, err_len, "%s: the time jumps by more than %ld frames of %g s", name, JC_TRACK_MAX_FRAMES, dt);
        jc_track_free(out);
        return JC_EINVAL;
    }
    return JC_OK;
}
