/* The tracks' containers: a jc_TrackRaw's arrays made and freed, a
 * jc_Track's freed, the reading options' defaults. The bottom of
 * src/track: every other file may call these, these call none of them. */
#include "track_internal.h"

#include <stdlib.h>
#include <string.h>

void jc_track_options_default(jc_TrackOptions *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->incline_rad = NAN;
    opt->radius_m = 0.10;
    opt->gravity_mps2 = 9.81;
    opt->axes = JC_TRACK_AXES_LEVEL;
    opt->hop_sigmas = 5.0;
    opt->max_bytes = JC_TRACK_MAX_BYTES;
}

void jc_track_raw_init(jc_TrackRaw *raw)
{
    memset(raw, 0, sizeof *raw);
    raw->px_per_m = raw->tape_length_m = raw->nominal_dt_s = NAN;
    memcpy(raw->format, "arrays", sizeof "arrays");
}

int jc_track_raw_alloc(jc_TrackRaw *raw, long frames, int track_count)
{
    if (frames < 0 || track_count < 0 || track_count > JC_TRACK_MAX_TRACKS) return JC_EINVAL;
    raw->frames = frames;
    raw->track_count = track_count;
    const size_t bytes = (size_t)(frames > 0 ? frames : 1) * sizeof(double);
    raw->t_s = malloc(bytes);
    int ok = raw->t_s != NULL;
    for (int i = 0; i < track_count; ++i) {
        raw->tracks[i].x_m = malloc(bytes);
        raw->tracks[i].y_m = malloc(bytes);
        ok = ok && raw->tracks[i].x_m && raw->tracks[i].y_m;
    }
    if (!ok) {
        jc_track_raw_free(raw);
        return JC_ENOMEM;
    }
    for (long f = 0; f < frames; ++f) {
        raw->t_s[f] = NAN;
        for (int i = 0; i < track_count; ++i) raw->tracks[i].x_m[f] = raw->tracks[i].y_m[f] = NAN;
    }
    return JC_OK;
}

void jc_track_raw_free(jc_TrackRaw *raw)
{
    free(raw->t_s);
    raw->t_s = NULL;
    for (int i = 0; i < JC_TRACK_MAX_TRACKS; ++i) {
        free(raw->tracks[i].x_m);
        free(raw->tracks[i].y_m);
        raw->tracks[i].x_m = raw->tracks[i].y_m = NULL;
    }
    raw->track_count = 0;
    raw->frames = 0;
}

void jc_track_free(jc_Track *t)
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
