/* `jumpcyl animate`: numbered PNG frames and what becomes of them (video.c). */
#ifndef JUMPCYL_VIDEO_H
#define JUMPCYL_VIDEO_H

#include "figures.h"

typedef enum { VID_GIF, VID_MP4, VID_FRAMES } vid_Format;

#define VID_FRAME_NAME "frame-%05d.png"
#define VID_FRAME_PATTERN "frame-%05d.png" /* ffmpeg's image2 pattern: the same text */
#define VID_MAX_FRAMES 100000              /* five digits */

/* .gif, .mp4, or a directory: a name ending in '/' or without extension.
 * -1 for any other extension. */
int vid_format_from_path(const char *path, vid_Format *f);
/* dir/frame-NNNNN.png; -1 if it does not fit. */
int vid_frame_path(char *out, size_t len, const char *dir, int index);

typedef struct {
    char *argv[32];
    char fps[32];
    char input[CLI_PATH_MAX + 8];  /* file:/abs/frame-%05d.png */
    char output[CLI_PATH_MAX + 8]; /* file:/abs/name */
} vid_Command;

/* Runs ffmpeg on the frames in the scratch directory work; ffmpeg writes
 * the film there (given as "file:" and an absolute path), and it is moved
 * to output (safe_output.h) when ffmpeg exited 0 and the film is not empty.
 * EXIT_OK, EXIT_FAIL after a message, or cli_stop_status() after a signal. */
int vid_assemble(const char *work, double fps, const char *output, vid_Format f);
/* The ffmpeg command line that does the same by hand, shell-quoted. */
void vid_print_command(FILE *out, const char *frames_dir, double fps, const char *output, vid_Format f);

/* A new directory beside dir (dir.tmp-XXXXXX) to render frames into,
 * recorded for signals (*slot: release with cli_tmpdir_untrack). */
int vid_frames_tmpdir(const char *dir, char *tmp, size_t len, int *slot);
/* Moves count frames rendered in tmp_dir to dir: a rename when dir does not
 * exist; into it, replacing its older frames, when it does. */
int vid_publish_frames(const char *tmp_dir, const char *dir, int count);

#endif
