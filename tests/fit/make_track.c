/* A synthetic tracked video as Tracker exports it (a data table, level
 * axes): a preset's run filmed at FPS and tracked with SIGMA metres of noise
 * (cli/track/synthetic.c), for the tests and docs/tracker.md.
 *
 * Usage: fit_make_track OUT [SIGMA_M [FPS [SEED [PRESET [TRACKS [MU_K [HAND_S]]]]]]]
 *   defaults 1e-3, 60, 1, paper, both, 0.4, 0; TRACKS: both, centre, mark. */
#include "../track/synth_table.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2 || argc > 9) {
        fprintf(stderr, "usage: %s OUT [SIGMA_M [FPS [SEED [PRESET [TRACKS [MU_K [HAND_S]]]]]]]\n", argv[0]);
        return 2;
    }
    jc_Setup s;
    char err[256];
    if (jc_preset_setup(argc > 5 ? argv[5] : "paper", &s, err, sizeof err) != JC_OK) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    s.mu_kinetic = argc > 7 ? atof(argv[7]) : 0.4;
    const char *tracks = argc > 6 ? argv[6] : "both";
    double a = 0;
    for (int i = 0; i < s.body.part_count; ++i) a = fmax(a, s.body.parts[i].offset_m);
    const jc_TrackSynthTracks which = strcmp(tracks, "centre") == 0 ? JC_TRACK_SYNTH_CENTRE_ONLY
                                      : strcmp(tracks, "mark") == 0 ? JC_TRACK_SYNTH_MARK_ONLY
                                                                    : JC_TRACK_SYNTH_BOTH;
    jc_TrackSynthOptions o = synth_camera(argc > 3 ? atof(argv[3]) : 60.0, argc > 2 ? atof(argv[2]) : 1e-3, which,
                                          argc > 4 ? strtoull(argv[4], NULL, 10) : 1u, a);
    o.t_end_s = s.incline_rad > 0 ? 1.5 : 2.5; /* a floor's run is filmed longer */
    o.hand_s = argc > 8 ? atof(argv[8]) : 0.0;
    if (synth_table_write(argv[1], &s, &o, NULL) != 0) {
        fprintf(stderr, "%s: cannot make or write %s\n", argv[0], argv[1]);
        return 1;
    }
    return 0;
}
