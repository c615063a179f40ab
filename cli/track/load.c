/* cli_track_load: a tracked experiment from a file (docs/tracker.md). */
#include "track.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void cli_track_options_default(cli_TrackOptions *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->incline_rad = 30.0 * CLI_PI / 180.0;
    opt->radius_m = 0.10;
    opt->axes = CLI_TRACK_AXES_LEVEL;
    opt->hop_sigmas = 5.0;
    opt->max_bytes = CLI_TRACK_MAX_BYTES;
}

int cli_track_parse(const char *name, const char *data, size_t len, const cli_TrackOptions *opt, cli_Track *out,
                    char *err, size_t err_len)
{
    (void)data;
    (void)len;
    (void)opt;
    memset(out, 0, sizeof *out);
    snprintf(err, err_len, "%s: reading tracks is not implemented yet", name);
    return -1;
}

int cli_track_load(const char *path, const cli_TrackOptions *opt, cli_Track *out, char *err, size_t err_len)
{
    return cli_track_parse(path, NULL, 0, opt, out, err, err_len);
}

void cli_track_free(cli_Track *t)
{
    if (!t) return;
    free(t->t_s);
    free(t->x_m);
    free(t->y_m);
    free(t->theta_rad);
    free(t->omega_radps);
    free(t->airborne);
    memset(t, 0, sizeof *t);
}
