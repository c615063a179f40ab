/* Output files are written under a temporary name beside the target and
 * renamed into place when complete: a failed or interrupted run never leaves
 * a partial file, and never truncates an existing one. A target that exists
 * and is not a regular file (/dev/stdout, /dev/full, a FIFO) cannot be
 * replaced by a rename; it is written in place. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The mode a new file would get (0666 less the umask), or the mode of the
 * file being replaced: mkstemp's 0600 must not leak into the result. */
static mode_t final_mode(const struct stat *existing, int exists)
{
    if (exists) return existing->st_mode & 07777;
    const mode_t mask = umask(0);
    umask(mask);
    return 0666 & ~mask;
}

static int open_direct(cli_AtomicFile *af, const char *path)
{
    af->direct = 1;
    af->f = fopen(path, "w");
    if (!af->f) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}

int cli_atomic_open(cli_AtomicFile *af, const char *path)
{
    memset(af, 0, sizeof *af);
    af->slot = -1;
    if (!path || !*path) {
        cli_error("empty output file name");
        return -1;
    }
    af->final_path = path;
    struct stat st;
    const int exists = stat(path, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) return open_direct(af, path);
    if (snprintf(af->tmp_path, sizeof af->tmp_path, "%s.tmp-XXXXXX", path) >= (int)sizeof af->tmp_path) {
        cli_error("cannot write %s: path too long (allowed: %d bytes)", path, CLI_PATH_MAX - 16);
        af->tmp_path[0] = '\0';
        return -1;
    }
    const int fd = cli_tmpfile_create(af->tmp_path, &af->slot);
    if (fd < 0) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        af->tmp_path[0] = '\0';
        return -1;
    }
    if (fchmod(fd, final_mode(&st, exists)) != 0 || !(af->f = fdopen(fd, "w"))) {
        cli_error("cannot write %s: %s", path, strerror(errno));
        close(fd);
        cli_atomic_abort(af);
        return -1;
    }
    return 0;
}

void cli_atomic_abort(cli_AtomicFile *af)
{
    if (af->f) fclose(af->f);
    af->f = NULL;
    if (af->tmp_path[0]) cli_tmpfile_finish(af->slot, af->tmp_path, NULL);
    af->tmp_path[0] = '\0';
}

/* Everything written reached the file (and, for a regular file, the disk). */
static int flush_all(FILE *f, int regular, int *err)
{
    int bad = ferror(f);
    if (fflush(f) != 0 || (regular && fsync(fileno(f)) != 0)) {
        bad = 1;
        *err = errno;
    }
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        *err = errno;
    }
    return bad;
}

int cli_atomic_commit(cli_AtomicFile *af)
{
    int err = EIO; /* an earlier write failed and its errno is gone */
    const int bad = flush_all(af->f, !af->direct, &err);
    af->f = NULL;
    if (af->direct) {
        if (bad) cli_error("cannot write %s: %s", af->final_path, strerror(err));
        return bad ? -1 : 0;
    }
    if (bad) {
        cli_error("cannot write %s: %s", af->final_path, strerror(err));
        cli_atomic_abort(af);
        return -1;
    }
    if (cli_tmpfile_finish(af->slot, af->tmp_path, af->final_path) != 0) {
        cli_error("cannot write %s: %s", af->final_path, strerror(errno));
        af->tmp_path[0] = '\0';
        return -1;
    }
    af->tmp_path[0] = '\0';
    return 0;
}

int cli_stdout_finish(void)
{
    int err = EIO;
    int bad = ferror(stdout);
    if (fflush(stdout) != 0) {
        bad = 1;
        err = errno;
    }
    if (bad) cli_error("cannot write standard output: %s", strerror(err));
    return bad ? EXIT_FAIL : EXIT_OK;
}
