/* Test helpers shared by the track and fit tests: a synthetic video
 * written as Tracker's exported table, and whether a file exists. */
#ifndef JC_TESTS_SYNTH_TABLE_H
#define JC_TESTS_SYNTH_TABLE_H

#include "raw.h"
#include "track_fit.h"

#include <stdio.h>
#include <sys/stat.h>

/* The run of s filmed as o, written to path; the first track renamed
 * first_name when it is not NULL. 0, or -1. */
static inline int synth_table_write(const char *path, const jc_Setup *s, const cli_SynthOptions *o,
                                    const char *first_name)
{
    cli_RawData raw;
    char err[256];
    if (cli_track_synth_raw(s, o, &raw, err, sizeof err) != 0) return -1;
    if (first_name) snprintf(raw.tracks[0].name, CLI_TRACK_NAME_LEN, "%s", first_name);
    FILE *f = fopen(path, "w");
    const int rc = f ? cli_track_write_table(f, &raw) : -1;
    cli_raw_free(&raw);
    return f && fclose(f) == 0 ? rc : -1;
}

static inline int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

#endif
