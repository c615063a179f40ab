/* Fuzz target: tracked-experiment files (src/track/: Tracker .trk through
 * libxml2, exported data tables), as bytes in memory, through
 * jc_track_parse: the readers, the incline frame and the derived values.
 *
 * The first byte chooses the options (axes, whether names are given, the
 * incline, tilt fitting); the rest is the file.
 *
 * Invariants: a rejected file leaves a one-line message that starts with
 * the file's name and nothing to free; an accepted one (every readable
 * file: it gives a report) has notes of one line each, strictly increasing
 * finite times, a known centre only with frames, finite or NaN positions,
 * a positive noise where the surface is known, and hops whose frames lie in
 * the track, in order, airborne exactly where they were resolved. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include <jumpcyl/track.h>

#include <math.h>
#include <string.h>

#define MAX_INPUT (256 * 1024)

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

static void check_track(const jc_Track *t)
{
    FUZZ_CHECK(t->n >= 0 && t->track_count >= 1 && t->track_count <= JC_TRACK_MAX_TRACKS);
    FUZZ_CHECK(memchr(t->centre_name, '\0', sizeof t->centre_name) && !strchr(t->centre_name, '\n'));
    for (int q = 0; q < JC_TRACK_Q_COUNT; ++q)
        FUZZ_CHECK(memchr(t->note[q].text, '\0', sizeof t->note[q].text) && !strchr(t->note[q].text, '\n'));
    FUZZ_CHECK(t->centre_source == JC_TRACK_CENTRE_NONE || t->n >= 3);
    FUZZ_CHECK(t->gaps >= 0 && t->dt_jitter_s >= 0);
    for (long i = 0; i < t->n; ++i) {
        FUZZ_CHECK(isfinite(t->t_s[i]));
        if (i > 0) FUZZ_CHECK(t->t_s[i] > t->t_s[i - 1]);
        FUZZ_CHECK(!isinf(t->x_m[i]) && !isinf(t->y_m[i]) && !isinf(t->theta_rad[i]));
        if (!t->has_mark) FUZZ_CHECK(isnan(t->theta_rad[i]));
        if (t->centre_source == JC_TRACK_CENTRE_TRACKED && t->note[JC_TRACK_Q_SURFACE].ok)
            FUZZ_CHECK(isfinite(t->x_m[i]) && isfinite(t->y_m[i]));
    }
    if (t->note[JC_TRACK_Q_SURFACE].ok) FUZZ_CHECK(isfinite(t->sigma_m) && t->sigma_m > 0);
    FUZZ_CHECK(t->hops >= 0 && t->hops <= t->n / 2 + 1);
    long prev = -1;
    for (long k = 0; k < t->hops; ++k) {
        const jc_TrackHop *h = &t->hop[k];
        FUZZ_CHECK(h->first > prev && h->first <= h->last && h->last < t->n && h->peak >= h->first &&
                   h->peak <= h->last);
        for (long i = h->first; i <= h->last; ++i) FUZZ_CHECK(t->airborne[i] == !isnan(h->height_m));
        prev = h->last;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > MAX_INPUT) return 0;
    const unsigned sel = data[0];
    jc_TrackOptions o;
    jc_track_options_default(&o);
    o.axes = sel & 1 ? JC_TRACK_AXES_INCLINE : JC_TRACK_AXES_LEVEL;
    o.fit_tilt = (sel >> 1) & 1;
    if (sel & 4) {
        o.centre = "axle";
        o.mark = sel & 8 ? "rod" : "";
    }
    /* 0: the incline measured; 5 to 75 deg given. */
    o.incline_rad = sel >> 4 ? (double)((sel >> 4) * 5) * 3.14159265358979323846 / 180.0 : NAN;
    jc_Track t;
    char err[512] = "";
    if (jc_track_parse("fuzz.trk", (const char *)data + 1, size - 1, &o, &t, err, sizeof err) != 0) {
        FUZZ_CHECK(strncmp(err, "fuzz.trk: ", 10) == 0 && !strchr(err, '\n') && !strchr(err, '\r'));
        FUZZ_CHECK(t.t_s == NULL && t.n == 0);
        return 0;
    }
    check_track(&t);
    jc_track_free(&t);
    return 0;
}
