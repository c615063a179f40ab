/* Output files are written under a temporary name beside the target and
 * renamed into place when complete: a failed or interrupted run never leaves
 * a partial file, and never truncates an existing one. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cli_atomic_open(cli_AtomicFile *af, const char *path)
{
    memset(af, 0, sizeof *af);
    if (!path || !*path) {
        cli_error("empty output file name");
        return -1;
    }
    if (snprintf(af->tmp_path, sizeof af->tmp_path, "%s.tmp-XXXXXX", path) >= (int)sizeof af->tmp_path) {
        cli_error("output path too long: %s", path);
        return -1;
    }
    af->final_path = path;
    int fd = mkstemp(af->tmp_path);
    if (fd < 0) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    af->f = fdopen(fd, "w");
    if (!af->f) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        close(fd);
        unlink(af->tmp_path);
        return -1;
    }
    return 0;
}

void cli_atomic_abort(cli_AtomicFile *af)
{
    if (af->f) fclose(af->f);
    af->f = NULL;
    if (af->tmp_path[0]) unlink(af->tmp_path);
    af->tmp_path[0] = '\0';
}

int cli_atomic_commit(cli_AtomicFile *af)
{
    int bad = ferror(af->f) || fflush(af->f) != 0 || fsync(fileno(af->f)) != 0;
    const int saved = errno;
    if (fclose(af->f) != 0) bad = 1;
    af->f = NULL;
    if (bad || rename(af->tmp_path, af->final_path) != 0) {
        cli_error("cannot write %s: %s", af->final_path, strerror(bad ? saved : errno));
        unlink(af->tmp_path);
        af->tmp_path[0] = '\0';
        return -1;
    }
    af->tmp_path[0] = '\0';
    return 0;
}
