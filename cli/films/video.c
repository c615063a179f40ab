/* From numbered PNG frames to the animation the user asked for: a GIF or an
 * MP4 assembled by ffmpeg, or the frames themselves in a directory. The
 * ffmpeg command line is built in one place, so that the one we run and the
 * one we print (when ffmpeg is missing) are the same. */
#define _POSIX_C_SOURCE 200809L
#include "films.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

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
        argv[n++] = "split[a][b];[a]palettegen[p];[b][p]paletteuse=dither=bayer:bayer_scale=5";
        argv[n++] = "-f";
        argv[n++] = "gif";
        return n;
    }
    /* H.264 in yuv420p (what players expect) needs even sizes. The end is
     * held by the frames themselves (animate.c), not by a filter. */
    static char *const mp4[] = {"pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", "-movflags", "+faststart",
                                "-f", "mp4"};
    for (size_t i = 0; i < sizeof mp4 / sizeof mp4[0]; ++i) argv[n++] = mp4[i];
    return n;
}

/* "file:" and the absolute path: ffmpeg then reads the name as a local
 * file whatever it looks like ("tcp://...", "-x", "pipe:"). */
static int file_url(const char *path, char *out, size_t len)
{
    char abs_path[CLI_PATH_MAX];
    if (cli_path_absolute(path, abs_path, sizeof abs_path) != 0) return -1;
    return snprintf(out, len, "file:%s", abs_path) < (int)len ? 0 : -1;
}

/* The frames' directory with each '%' doubled: ffmpeg reads the whole
 * input name as an image2 pattern, where "%%" is a '%' and "%d" a number
 * (a TMPDIR or an output name with a '%'). -1 if it does not fit. */
static int escape_percent(const char *dir, char *out, size_t len)
{
    size_t n = 0;
    for (const char *p = dir; *p; ++p) {
        if (n + 3 > len) return -1;
        if (*p == '%') out[n++] = '%';
        out[n++] = *p;
    }
    if (n + 1 > len) return -1;
    out[n] = '\0';
    return 0;
}

/* The arguments of the ffmpeg command; strings live in cmd. */
static int build_command(vid_Command *cmd, const char *frames_dir, double fps, const char *output, vid_Format f,
                         int quiet)
{
    int n = 0;
    char pattern[CLI_PATH_MAX], dir[CLI_PATH_MAX], abs_dir[CLI_PATH_MAX];
    snprintf(cmd->fps, sizeof cmd->fps, "%g", fps);
    /* Made absolute before the escape: the working directory may hold a '%' too. */
    if (cli_path_absolute(frames_dir, abs_dir, sizeof abs_dir) != 0 || escape_percent(abs_dir, dir, sizeof dir) != 0 ||
        cli_path_join(pattern, sizeof pattern, dir, VID_FRAME_PATTERN) != 0 ||
        file_url(pattern, cmd->input, sizeof cmd->input) != 0 || file_url(output, cmd->output, sizeof cmd->output) != 0)
        return -1;
    cmd->argv[n++] = "ffmpeg";
    cmd->argv[n++] = "-nostdin";
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
    cmd->argv[n++] = cmd->output;
    cmd->argv[n] = NULL;
    return 0;
}

void vid_print_command(FILE *out, const char *frames_dir, double fps, const char *output, vid_Format f)
{
    vid_Command cmd;
    if (build_command(&cmd, frames_dir, fps, output, f, 0) != 0) return;
    fputs("  ", out);
    for (int i = 0; cmd.argv[i]; ++i) {
        if (i) fputc(' ', out);
        cli_shell_word(out, cmd.argv[i]);
    }
    fputc('\n', out);
}

int vid_assemble(const char *work, double fps, const char *output, vid_Format f)
{
    char film[CLI_PATH_MAX], log_path[CLI_PATH_MAX];
    vid_Command cmd;
    if (cli_path_join(film, sizeof film, work, f == VID_GIF ? "film.gif" : "film.mp4") != 0 ||
        cli_path_join(log_path, sizeof log_path, work, "ffmpeg.log") != 0 ||
        build_command(&cmd, work, fps, film, f, 1) != 0) {
        cli_error("animate: scratch path too long: %s", work);
        return EXIT_FAIL;
    }
    /* ffmpeg writes into the scratch directory; the film is moved into
     * place only when ffmpeg succeeded and it is not empty. */
    cli_Progress progress;
    cli_progress_begin(&progress, "animate: ffmpeg is encoding");
    int status;
    const cli_RunEnd end = cli_run_program(cmd.argv, NULL, log_path, cli_progress_tick, &progress, &status);
    cli_progress_end(&progress);
    if (end == CLI_RUN_STOPPED) return cli_stop_status();
    if (end == CLI_RUN_EFBIG) {
        cli_error("cannot write %s: %s (ffmpeg's scratch copy in %s)", output, strerror(EFBIG), work);
        return EXIT_FAIL;
    }
    if (end == CLI_RUN_FAILED) return EXIT_FAIL;
    char why[128];
    if (status != 0 || cli_output_verify(film, CLI_CHECK_NONEMPTY, why, sizeof why) != 0) {
        if (status != 0) cli_error("animate: ffmpeg failed (exit status %d) making %s:", status, output);
        else cli_error("cannot write %s: ffmpeg's film is %s", output, why);
        cli_print_log_tail(log_path);
        return EXIT_FAIL;
    }
    cli_Output o;
    if (cli_output_begin(&o, output, 0) != 0) return EXIT_FAIL;
    if (cli_output_copy_from(&o, film) != 0 || cli_output_commit(&o, CLI_CHECK_NONEMPTY) != 0) {
        cli_output_abort(&o);
        return cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
    }
    return EXIT_OK;
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

int vid_frames_tmpdir(const char *dir, char *tmp, size_t len, int *slot)
{
    *slot = -1;
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/') --n;
    if (snprintf(tmp, len, "%.*s.tmp-XXXXXX", (int)n, dir) >= (int)len) {
        cli_error("cannot write %s: path too long", dir);
        return -1;
    }
    sigset_t old;
    cli_signals_hold(&old); /* made and recorded together: a signal finds it */
    const int made = mkdtemp(tmp) != NULL;
    const int err = errno;
    if (made) *slot = cli_tmpdir_track(tmp);
    cli_signals_release(&old);
    if (!made) {
        cli_error("cannot write %s: %s", dir, strerror(err));
        return -1;
    }
    /* mkdtemp makes it private; the frames directory gets the usual permissions. */
    const mode_t mask = umask(0);
    umask(mask);
    chmod(tmp, 0777 & ~mask);
    return 0;
}
