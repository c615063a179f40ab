/* Test helpers shared by the track and fit tests: a synthetic video
 * written as Tracker's exported table. */
#ifndef JC_TESTS_SYNTH_TABLE_H
#define JC_TESTS_SYNTH_TABLE_H

#include <jumpcyl/track.h>

#include <stdio.h>
#include <string.h>

#define SYNTH_PI 3.14159265358979323846

/* A camera of fps frames/s tracking with sigma_m of noise for 1.5 s,
 * the mark (if tracked) mark_m from the centre. */
static inline jc_TrackSynthOptions synth_camera(double fps, double sigma_m, jc_TrackSynthTracks tracks, uint64_t seed,
                                                double mark_m)
{
    jc_TrackSynthOptions o;
    memset(&o, 0, sizeof o);
    o.fps_hz = fps;
    o.sigma_m = sigma_m;
    o.t_end_s = 1.5;
    o.mark_radius_m = mark_m;
    o.seed = seed;
    o.tracks = tracks;
    return o;
}

/* A loaded ring: the hoop preset as a 100 g hoop with 100 g at its rim,
 * rolled at 18 rad/s with the mass at the bottom along a floor; it rolls
 * over and over, never hopping (mu 0.8). */
static inline jc_Setup synth_loaded_ring(void)
{
    jc_Setup s;
    char err[128];
    jc_preset_setup("hoop", &s, err, sizeof err);
    s.body.parts[0].mass_kg = 0.1;
    s.body.parts[1].mass_kg = 0.1;
    s.omega0_radps = 18.0;
    s.theta0_rad = SYNTH_PI;
    s.mu_static = s.mu_kinetic = 0.8;
    s.ramp_length_m = 10.0;
    return s;
}

/* The run of s filmed as o, written to path; the first track renamed
 * first_name when it is not NULL. 0, or -1. */
static inline int synth_table_write(const char *path, const jc_Setup *s, const jc_TrackSynthOptions *o,
                                    const char *first_name)
{
    jc_TrackRaw raw;
    char err[256];
    if (jc_track_synth_raw(s, o, &raw, err, sizeof err) != 0) return -1;
    if (first_name) snprintf(raw.tracks[0].name, JC_TRACK_NAME_LEN, "%s", first_name);
    FILE *f = fopen(path, "w");
    if (f) jc_track_write_table(f, &raw);
    const int rc = f && !ferror(f) ? 0 : -1;
    jc_track_raw_free(&raw);
    return f && fclose(f) == 0 ? rc : -1;
}

#endif
