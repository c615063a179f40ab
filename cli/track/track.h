/* Tracked experiments (docs/tracker.md): positions tracked in a video with
 * Tracker (Open Source Physics), read from its .trk files or exported data
 * tables, converted to the incline frame of docs/physics.md §1, and compared
 * with or fitted by the model. */
#ifndef JUMPCYL_TRACK_H
#define JUMPCYL_TRACK_H

#include "cli.h"

/* One tracked experiment in the incline frame, frame by frame. Frames where
 * the centre is missing are left out; t_s strictly increases. */
typedef struct {
    long n;                /* frames kept */
    double *t_s;           /* time of each frame (s), the clip's first frame at 0 */
    double *x_m, *y_m;     /* centre C: along the incline (downhill) from where
                              the first frame has it plus x0_m, and height above
                              the incline's surface (r in contact) */
    /* The tracked off-centre mark: its angle as θ of docs/physics.md (from the
     * incline's normal, growing as the body rolls downhill), unwrapped; NaN in
     * every frame where the mark is missing, or all NaN when no mark is tracked.
     * The mark need not be G: G's angle is theta + the setup's offset between
     * the mark and G (0 for the paper's cylinder, whose rod is its only
     * off-centre part). */
    double *theta_rad;
    int has_mark;          /* a mark track was found and used */
    double x0_m;           /* where the centre starts along the incline (m) */
    double sigma_m;        /* a pixel in metres: the position noise to expect */
    double frame_rate_hz;  /* nominal */
    double dt_jitter_s;    /* largest |dt - nominal| between kept frames */
    long gaps;             /* missing frames of the centre track */
    char centre_name[64], mark_name[64];
} cli_Track;

void cli_track_free(cli_Track *t);

#endif /* JUMPCYL_TRACK_H */
