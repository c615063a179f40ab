/* Fuzz target: tracked-experiment files (cli/track/: Tracker .trk through
 * libxml2, exported data tables), as bytes in memory, through
 * cli_track_parse: the readers, the incline frame and the derived values.
 *
 * The first byte chooses the options (axes, whether names are given, the
 * incline, tilt fitting); the rest is the file.
 *
 * Invariants: a rejected file leaves a one-line message that starts with
 * the file's name and nothing to free; an accepted one has at least 3
 * frames, finite positions at strictly increasing finite times, θ and ω
 * finite or NaN together with the mark, a positive frame rate and noise,
 * airborne frames exactly those above the threshold, and hops counted as
 * their runs. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include "track.h"

#include <math.h>
#include <string.h>

#define MAX_INPUT (256 * 1024)

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

static void check_track(const cli_Track *t)
{
    FUZZ_CHECK(t->n >= 3 && t->t_s && t->x_m && t->y_m && t->theta_rad && t->omega_radps && t->airborne);
    FUZZ_CHECK(isfinite(t->frame_rate_hz) && t->frame_rate_hz > 0);
    FUZZ_CHECK(isfinite(t->sigma_m) && t->sigma_m > 0 && t->gaps >= 0 && t->dt_jitter_s >= 0);
    FUZZ_CHECK(t->track_count >= 1 && t->track_count <= CLI_TRACK_MAX_TRACKS);
    FUZZ_CHECK(memchr(t->centre_name, '\0', sizeof t->centre_name) && !strchr(t->centre_name, '\n'));
    long hops = 0;
    for (long i = 0; i < t->n; ++i) {
        FUZZ_CHECK(isfinite(t->t_s[i]) && isfinite(t->x_m[i]) && isfinite(t->y_m[i]));
        if (i > 0) FUZZ_CHECK(t->t_s[i] > t->t_s[i - 1]);
        if (!t->has_mark) FUZZ_CHECK(isnan(t->theta_rad[i]));
        FUZZ_CHECK(isnan(t->theta_rad[i]) || isfinite(t->theta_rad[i]));
        if (isnan(t->theta_rad[i])) FUZZ_CHECK(isnan(t->omega_radps[i]));
        FUZZ_CHECK(t->airborne[i] == (t->y_m[i] > t->radius_m + t->hop_threshold_m));
        if (t->airborne[i] && (i == 0 || !t->airborne[i - 1])) hops++;
    }
    FUZZ_CHECK(hops == t->hops);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > MAX_INPUT) return 0;
    const unsigned sel = data[0];
    cli_TrackOptions o;
    cli_track_options_default(&o);
    o.axes = sel & 1 ? CLI_TRACK_AXES_INCLINE : CLI_TRACK_AXES_LEVEL;
    o.fit_tilt = (sel >> 1) & 1;
    if (sel & 4) {
        o.centre = "axle";
        o.mark = sel & 8 ? "rod" : "";
    }
    o.incline_rad = (double)((sel >> 4) * 5) * 3.14159265358979323846 / 180.0;
    cli_Track t;
    char err[512] = "";
    if (cli_track_parse("fuzz.trk", (const char *)data + 1, size - 1, &o, &t, err, sizeof err) != 0) {
        FUZZ_CHECK(strncmp(err, "fuzz.trk: ", 10) == 0 && !strchr(err, '\n') && !strchr(err, '\r'));
        FUZZ_CHECK(t.t_s == NULL && t.n == 0);
        return 0;
    }
    check_track(&t);
    cli_track_free(&t);
    return 0;
}
