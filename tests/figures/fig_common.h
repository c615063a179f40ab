/* Helpers for the figure and animation tests: scratch directories, files
 * (the tool runs through ../cli_run.h, cli_run_line). All static inline, so
 * that a test that does not use one does not warn. */
#ifndef JC_FIG_COMMON_H
#define JC_FIG_COMMON_H

#define _POSIX_C_SOURCE 200809L
#include "../test.h"
#include "../cli_run.h"

#include <gsl/gsl_errno.h>

#include <dirent.h>
#include <errno.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* A fresh scratch directory; the test removes it with fig_rmtree. */
static inline int fig_tmpdir(char *path, size_t len, const char *name)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(path, len, "%s/jc_fig_%s_XXXXXX", tmp && *tmp ? tmp : "/tmp", name);
    return mkdtemp(path) ? 0 : -1;
}

/* Removes a directory tree of files and directories (one level of nesting is
 * all the tests make, but any depth works). */
static inline void fig_rmtree(const char *path)
{
    DIR *d = opendir(path);
    if (!d) {
        remove(path);
        return;
    }
    struct dirent *e;
    char child[4096];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        if (snprintf(child, sizeof child, "%s/%s", path, e->d_name) >= (int)sizeof child) continue;
        struct stat st;
        if (lstat(child, &st) == 0 && S_ISDIR(st.st_mode)) fig_rmtree(child);
        else remove(child);
    }
    closedir(d);
    rmdir(path);
}

static inline long fig_file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* The first n bytes of a file; 0 on success. */
static inline int fig_head(const char *path, unsigned char *buf, size_t n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    const size_t got = fread(buf, 1, n, f);
    fclose(f);
    return got == n ? 0 : -1;
}

/* Width and height from a PNG's IHDR; 0 on success. */
static inline int fig_png_size(const char *path, int *w, int *h)
{
    unsigned char b[24];
    if (fig_head(path, b, sizeof b) != 0 || memcmp(b, "\x89PNG\r\n\x1a\n", 8) != 0 || memcmp(b + 12, "IHDR", 4) != 0)
        return -1;
    *w = (b[16] << 24) | (b[17] << 16) | (b[18] << 8) | b[19];
    *h = (b[20] << 24) | (b[21] << 16) | (b[22] << 8) | b[23];
    return 0;
}

/* Number of entries in a directory (not counting . and ..); -1 if none. */
static inline int fig_count_entries(const char *path)
{
    DIR *d = opendir(path);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) ++n;
    closedir(d);
    return n;
}

/* An empty directory to use as PATH: no gnuplot, no ffmpeg. */
static inline int fig_empty_path(char *path, size_t len, const char *tmpdir)
{
    snprintf(path, len, "%s/empty-bin", tmpdir);
    return mkdir(path, 0755);
}

/* The tool run with args and an empty PATH (no gnuplot, no ffmpeg): exit 1,
 * a message that holds need and also (when not NULL), on one line when
 * one_line, and no file out. */
static inline int fig_without_tools(const char *cli, const char *dir, const char *args, const char *out,
                                    const char *need, const char *also, int one_line)
{
    char empty[1100];
    if (fig_empty_path(empty, sizeof empty, dir) != 0 && errno != EEXIST) return 1;
    cli_result r = cli_run_line(cli, empty, args);
    const int ok = r.status == 1 && r.err && strstr(r.err, need) && (!also || strstr(r.err, also)) &&
                   (!one_line || cli_one_line(r.err));
    if (!ok) fprintf(stderr, "'%s' without tools: status %d, stderr: %s\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE_MSG(!cli_file_exists(out), "%s was written", out);
    return 0;
}

/* The start of a figure test's main: the tool's path from argv[1], GSL's
 * aborting error handler off (docs/api.md) and a scratch directory named
 * for the test. 0, or the exit status 2 after a message. */
static inline int fig_main_begin(int argc, char **argv, const char *name, const char **cli, char *dir, size_t dir_len)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH-TO-jumpcyl\n", argv[0]);
        return 2;
    }
    *cli = argv[1];
    gsl_set_error_handler_off();
    return fig_tmpdir(dir, dir_len, name) != 0 ? 2 : 0;
}

/* The end: the scratch directory removed, or kept for a look after a failure. */
static inline void fig_main_end(const char *dir)
{
    if (jc_test_failed_count == 0) fig_rmtree(dir);
    else fprintf(stderr, "files kept in %s\n", dir);
}

#endif
