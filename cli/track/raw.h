/* What a track file holds before it is put in the incline frame: positions
 * in Tracker's world axes (metres), one row per frame. Shared by the
 * readers (trk.c, table.c), the conversion (frame.c) and derive.c. */
#ifndef JUMPCYL_TRACK_RAW_H
#define JUMPCYL_TRACK_RAW_H

#include "track.h"

typedef struct {
    char name[CLI_TRACK_NAME_LEN];
    double *x_m, *y_m; /* world axes, metres; NaN where the frame has no position */
} cli_RawTrack;

typedef struct {
    long frames;          /* rows: clip steps or table rows */
    double *t_s;          /* time of each row */
    int track_count;
    cli_RawTrack tracks[CLI_TRACK_MAX_TRACKS];
    double px_per_m;      /* scale of the first frame; NaN for a table */
    int scale_varies;     /* origin, angle or scale differ between frames */
    double tape_length_m; /* NaN without a calibration tape */
    double nominal_dt_s;  /* the clip's frame duration; NaN for a table */
    char format[8];
} cli_RawData;

/* Each reader fills raw (zeroed first) or returns -1 with "NAME: message". */
int cli_trk_parse(const char *name, const char *data, size_t len, cli_RawData *raw, char *err, size_t err_len);
int cli_table_parse(const char *name, const char *data, size_t len, cli_RawData *raw, char *err, size_t err_len);
/* Allocates frames rows for the times and track_count tracks (NaN filled). 0 or -1. */
int cli_raw_alloc(cli_RawData *raw, long frames, int track_count);
void cli_raw_free(cli_RawData *raw);

/* frame.c: the chosen tracks put in the incline frame, into out (whose
 * report fields are set here); 0 or -1 with a message. */
int cli_track_from_raw(const char *name, const cli_RawData *raw, const cli_TrackOptions *opt, cli_Track *out,
                       char *err, size_t err_len);
/* derive.c: θ unwrapped, ω, the surface, heights and hops, the noise. 0 or -1. */
int cli_track_derive(const char *name, const cli_TrackOptions *opt, cli_Track *t, char *err, size_t err_len);

#endif
