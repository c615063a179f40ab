/* From numbered PNG frames to the animation the user asked for: a GIF or an
 * MP4 assembled by ffmpeg, or the frames themselves in a directory. The
 * ffmpeg command line is built in one place, so that the one we run and the
 * one we print (when ffmpeg is missing) are the same. */
#define _POSIX_C_SOURCE 200809L
#include "video.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

/* Videos hold the last frame this long, so the end can be seen (and a GIF
 * does not jump straight back to the start). */
#define HOLD_END_S "0.5"

int vid_format_from_path(const char *path, vid_Format *f)
{
    const size_t n = strlen(path);
    const char *ext = cli_path_ext(path);
    if (n > 0 && path[n - 1] == '/') *f = VID_FRAMES;
    else if (!*ext) *f = VID_FRAMES;
    else if (strcasecmp(ext, "gif") == 0) *f = VID_GIF;
    else if (strcasecmp(ext, "mp4") == 0) *f = VID_MP4;
    else return -1;
    return 0;
}

int vid_frame_path(char *out, size_t len, const char *dir, int index)
{
    char name[32];
    snprintf(name, sizeof name, VID_FRAME_NAME, index);
    return cli_path_join(out, len, dir, name);
}

/* The filter and encoder arguments for the format; returns the new count. */
static int codec_args(char **argv, int n, vid_Format f)
{
    argv[n++] = "-vf";
    if (f == VID_GIF) {
        /* One palette made for the whole clip keeps the colours clean; ordered
         * (Bayer) dithering encodes about twice as fast as the default. */
        argv[n++] = "tpad=stop_mode=clone:stop_duration=" HOLD_END_S
                    ",split[a][b];[a]palettegen[p];[b][p]paletteuse=dither=bayer:bayer_scale=5";
        argv[n++] = "-f";
        argv[n++] = "gif";
        return n;
    }
    /* H.264 in yuv420p (what players expect) needs even sizes. */
    static char *const mp4[] = {"tpad=stop_mode=clone:stop_duration=" HOLD_END_S ",pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", "-movflags", "+faststart",
                                "-f", "mp4"};
    for (size_t i = 0; i < sizeof mp4 / sizeof mp4[0]; ++i) argv[n++] = mp4[i];
    return n;
}

/* The arguments of the ffmpeg command; strings live in cmd. */
static int build_command(vid_Command *cmd, const char *frames_dir, double fps, const char *output, vid_Format f,
                         int quiet)
{
    int n = 0;
    snprintf(cmd->fps, sizeof cmd->fps, "%g", fps);
    if (cli_path_join(cmd->input, sizeof cmd->input, frames_dir, VID_FRAME_PATTERN) != 0) return -1;
    cmd->argv[n++] = "ffmpeg";
    cmd->argv[n++] = "-y";
    if (quiet) {
        cmd->argv[n++] = "-loglevel";
        cmd->argv[n++] = "error";
    }
    cmd->argv[n++] = "-framerate";
    cmd->argv[n++] = cmd->fps;
    cmd->argv[n++] = "-i";
    cmd->argv[n++] = cmd->input;
    n = codec_args(cmd->argv, n, f);
    cmd->argv[n++] = (char *)output;
    cmd->argv[n] = NULL;
    return 0;
}

/* A word as the shell reads it: quoted unless it is plainly safe. */
static void shell_word(FILE *out, const char *s)
{
    if (*s && s[strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./:+=%,")] == '\0') {
        fputs(s, out);
        return;
    }
    fputc('\'', out);
    for (; *s; ++s) {
        if (*s == '\'') fputs("'\\''", out);
        else fputc(*s, out);
    }
    fputc('\'', out);
}

void vid_print_command(FILE *out, const char *frames_dir, double fps, const char *output, vid_Format f)
{
    vid_Command cmd;
    if (build_command(&cmd, frames_dir, fps, output, f, 0) != 0) return;
    fputs("  ", out);
    for (int i = 0; cmd.argv[i]; ++i) {
        if (i) fputc(' ', out);
        shell_word(out, cmd.argv[i]);
    }
    fputc('\n', out);
}

int vid_assemble(const char *frames_dir, double fps, const char *output, vid_Format f, const char *log_path)
{
    char tmp[CLI_PATH_MAX];
    if (snprintf(tmp, sizeof tmp, "%s.tmp-XXXXXX", output) >= (int)sizeof tmp) {
        cli_error("cannot write %s: path too long", output);
        return EXIT_FAIL;
    }
    int slot;
    const int fd = cli_tmpfile_create(tmp, &slot);
    if (fd < 0) {
        cli_error("cannot write %s: %s", output, strerror(errno));
        return EXIT_FAIL;
    }
    const mode_t mask = umask(0); /* mkstemp's 0600 must not stay on the video */
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    close(fd);
    vid_Command cmd;
    int rc = build_command(&cmd, frames_dir, fps, tmp, f, 1) == 0 ? EXIT_OK : EXIT_FAIL;
    cli_Progress progress;
    cli_progress_begin(&progress, "animate: ffmpeg is encoding");
    const int st = rc == EXIT_OK ? cli_run_program(cmd.argv, log_path, &progress) : -1;
    cli_progress_end(&progress);
    struct stat sb;
    if (st != 0 || stat(tmp, &sb) != 0 || sb.st_size == 0) {
        if (st > 0) cli_error("animate: ffmpeg failed (exit status %d) making %s:", st, output);
        else if (st == 0) cli_error("animate: ffmpeg wrote nothing for %s:", output);
        cli_print_log_tail(log_path);
        rc = EXIT_FAIL;
    }
    if (cli_tmpfile_finish(slot, tmp, rc == EXIT_OK ? output : NULL) != 0 && rc == EXIT_OK) {
        cli_error("cannot write %s: %s", output, strerror(errno));
        rc = EXIT_FAIL;
    }
    return rc;
}

/* Removes the frames an earlier run left in dir (frame-NNNNN.png only). */
static void remove_old_frames(const char *dir)
{
    char path[CLI_PATH_MAX];
    for (int i = 0; i < VID_MAX_FRAMES; ++i) {
        if (vid_frame_path(path, sizeof path, dir, i) != 0 || unlink(path) != 0) break;
    }
}

int vid_publish_frames(const char *tmp_dir, const char *dir, int count)
{
    struct stat st;
    if (stat(dir, &st) != 0) {
        if (rename(tmp_dir, dir) == 0) return EXIT_OK;
        cli_error("cannot write %s: %s", dir, strerror(errno));
        return EXIT_FAIL;
    }
    if (!S_ISDIR(st.st_mode)) {
        cli_error("cannot write %s: it exists and is not a directory", dir);
        return EXIT_FAIL;
    }
    /* An existing directory: its old frames are replaced, other files stay. */
    remove_old_frames(dir);
    char from[CLI_PATH_MAX], to[CLI_PATH_MAX];
    for (int i = 0; i < count; ++i) {
        if (vid_frame_path(from, sizeof from, tmp_dir, i) != 0 || vid_frame_path(to, sizeof to, dir, i) != 0 ||
            rename(from, to) != 0) {
            cli_error("cannot write %s: %s", dir, strerror(errno));
            return EXIT_FAIL;
        }
    }
    rmdir(tmp_dir);
    return EXIT_OK;
}

int vid_frames_tmpdir(const char *dir, char *tmp, size_t len)
{
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/') --n;
    if (snprintf(tmp, len, "%.*s.tmp-XXXXXX", (int)n, dir) >= (int)len) {
        cli_error("cannot write %s: path too long", dir);
        return -1;
    }
    if (!mkdtemp(tmp)) {
        cli_error("cannot write %s: %s", dir, strerror(errno));
        return -1;
    }
    /* mkdtemp makes it private; the frames directory gets the usual permissions. */
    const mode_t mask = umask(0);
    umask(mask);
    chmod(tmp, 0777 & ~mask);
    return 0;
}
