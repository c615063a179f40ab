/* A track's memory. */
#include "track.h"

#include <stdlib.h>
#include <string.h>

void cli_track_free(cli_Track *t)
{
    if (!t) return;
    free(t->t_s);
    free(t->x_m);
    free(t->y_m);
    free(t->theta_rad);
    memset(t, 0, sizeof *t);
}
