/* Scratch directories for the data, scripts and frames that figures are made
 * from, and the few file-name operations they need. */
#define _POSIX_C_SOURCE 200809L
#include "process.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_workdir_make(cli_WorkDir *w, const char *cmd)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !*tmp) tmp = "/tmp";
    if (snprintf(w->path, sizeof w->path, "%s/jumpcyl-%s-XXXXXX", tmp, cmd) >= (int)sizeof w->path) {
        cli_error("%s: TMPDIR is too long", cmd);
        return -1;
    }
    /* Created with signals held, so that a signal always finds it recorded. */
    sigset_t old;
    cli_signals_hold(&old);
    const int made = mkdtemp(w->path) != NULL;
    const int err = errno;
    w->slot = made ? cli_tmpdir_track(w->path) : -1;
    cli_signals_release(&old);
    if (!made) {
        cli_error("%s: cannot create a scratch directory in %s: %s", cmd, tmp, strerror(err));
        w->path[0] = '\0';
        return -1;
    }
    return 0;
}

int cli_remove_flat_dir(const char *path)
{
    DIR *d = opendir(path);
    if (!d) return -1;
    const struct dirent *e;
    char file[CLI_PATH_MAX];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        if (cli_path_join(file, sizeof file, path, e->d_name) == 0) unlink(file);
    }
    closedir(d);
    return rmdir(path);
}

void cli_workdir_remove(cli_WorkDir *w)
{
    if (w->path[0]) cli_remove_flat_dir(w->path);
    cli_tmpdir_untrack(w->slot);
    w->slot = -1;
    w->path[0] = '\0';
}

const char *cli_path_ext(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    /* ".hidden" has no extension. */
    return dot && dot != base ? dot + 1 : "";
}

int cli_path_split(const char *path, char *dir, size_t dir_len, char *stem, size_t stem_len)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const size_t dn = slash ? (size_t)(slash - path) : 0;
    int w = slash ? snprintf(dir, dir_len, "%.*s", (int)(dn ? dn : 1), dn ? path : "/")
                  : snprintf(dir, dir_len, ".");
    if (w < 0 || (size_t)w >= dir_len) return -1;
    const char *ext = cli_path_ext(path);
    const size_t sn = strlen(base) - (*ext ? strlen(ext) + 1 : 0);
    w = snprintf(stem, stem_len, "%.*s", (int)sn, base);
    return w < 0 || (size_t)w >= stem_len ? -1 : 0;
}

int cli_path_absolute(const char *path, char *out, size_t len)
{
    if (path[0] == '/') return snprintf(out, len, "%s", path) < (int)len ? 0 : -1;
    char cwd[CLI_PATH_MAX];
    if (!getcwd(cwd, sizeof cwd)) return -1;
    return cli_path_join(out, len, cwd, path);
}

int cli_path_join(char *out, size_t len, const char *dir, const char *name)
{
    const size_t n = strlen(dir);
    const int w = snprintf(out, len, "%s%s%s", dir, n && dir[n - 1] == '/' ? "" : "/", name);
    return w < 0 || (size_t)w >= len ? -1 : 0;
}

int cli_check_output_dir(const char *path)
{
    char trimmed[CLI_PATH_MAX], dir[CLI_PATH_MAX], stem[CLI_PATH_MAX];
    /* "frames/" names the directory frames, whose parent must exist. */
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/') --n;
    if (snprintf(trimmed, sizeof trimmed, "%.*s", (int)n, path) >= (int)sizeof trimmed ||
        cli_path_split(trimmed, dir, sizeof dir, stem, sizeof stem) != 0) {
        cli_error("cannot write %s: path too long", path);
        return -1;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        cli_error("cannot write %s: directory %s does not exist", path, dir);
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}
