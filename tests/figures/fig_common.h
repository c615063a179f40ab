/* Helpers for the figure and animation tests: run the built jumpcyl as a
 * process (optionally with another PATH), scratch directories, files. All
 * static inline, so that a test that does not use one does not warn. */
#ifndef JC_FIG_COMMON_H
#define JC_FIG_COMMON_H

#define _POSIX_C_SOURCE 200809L
#include "../test.h"

#include <dirent.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct {
    int status; /* exit status; -1 if it did not exit normally (a crash) */
    char *out, *err;
} fig_run_result;

static inline char *fig_slurp(FILE *f)
{
    size_t cap = 4096, len = 0, n;
    char *buf = malloc(cap);
    while (buf && (n = fread(buf + len, 1, cap - len - 1, f)) > 0) {
        len += n;
        if (cap - len < 2) {
            char *bigger = realloc(buf, cap *= 2);
            if (!bigger) free(buf);
            buf = bigger;
        }
    }
    if (buf) buf[len] = '\0';
    return buf;
}

/* Runs "'cli' ARGS" with stdout and stderr captured; with path_env, PATH is
 * set to it for jumpcyl (so that gnuplot or ffmpeg can be made missing). */
static inline fig_run_result fig_run(const char *cli, const char *path_env, const char *args)
{
    fig_run_result r = {-1, NULL, NULL};
    char err_path[] = "/tmp/jc_fig_test_err_XXXXXX";
    const int fd = mkstemp(err_path);
    if (fd < 0) return r;
    close(fd);
    char cmd[8192];
    if (path_env) snprintf(cmd, sizeof cmd, "env PATH='%s' '%s' %s 2>'%s'", path_env, cli, args, err_path);
    else snprintf(cmd, sizeof cmd, "'%s' %s 2>'%s'", cli, args, err_path);
    FILE *p = popen(cmd, "r");
    if (p) {
        r.out = fig_slurp(p);
        const int ws = pclose(p);
        r.status = ws != -1 && WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
    }
    FILE *e = fopen(err_path, "r");
    if (e) {
        r.err = fig_slurp(e);
        fclose(e);
    }
    remove(err_path);
    return r;
}

static inline void fig_run_free(fig_run_result *r)
{
    free(r->out);
    free(r->err);
}

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

static inline int fig_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
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

#endif
