/* Opening and reading files without waiting for ever: an open never blocks
 * (a FIFO without a reader or a writer), and a read that waits for a pipe
 * is ended by the first stop signal (signals.c installs its handlers
 * without SA_RESTART, and poll is never restarted anyway). */
#define _POSIX_C_SOURCE 200809L
#include "process.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void set_why(char *why, size_t len, const char *text)
{
    if (why && len) snprintf(why, len, "%s", text);
}

int cli_open_nowait(const char *path, int flags, mode_t mode, int regular_only, char *why, size_t why_len)
{
    set_why(why, why_len, "");
    const int writes = (flags & O_ACCMODE) != O_RDONLY;
    const int fd = open(path, flags | O_NONBLOCK | O_CLOEXEC | O_NOCTTY, mode);
    if (fd < 0) {
        const int err = errno;
        /* For a writer, ENXIO is the FIFO with nobody reading it. */
        if (err == ENXIO && writes) snprintf(why, why_len, "%s (a FIFO without a reader)", strerror(err));
        else set_why(why, why_len, strerror(err));
        errno = err;
        return -1;
    }
    struct stat st;
    const char *refused = NULL;
    if (fstat(fd, &st) != 0) refused = strerror(errno);
    else if (S_ISDIR(st.st_mode)) refused = strerror(EISDIR);
    else if (regular_only && !S_ISREG(st.st_mode))
        refused = S_ISFIFO(st.st_mode) ? "not a regular file (a FIFO)" : "not a regular file (a device or socket)";
    /* Reads and writes wait as usual from here; a stop signal ends them. */
    if (!refused && fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0) refused = strerror(errno);
    if (refused) {
        set_why(why, why_len, refused);
        close(fd);
        errno = EINVAL;
        return -1;
    }
    return fd;
}

FILE *cli_fopen_nowait(const char *path, const char *stdio_mode, int flags, int regular_only, char *why,
                       size_t why_len)
{
    const int fd = cli_open_nowait(path, flags, 0666, regular_only, why, why_len);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, stdio_mode);
    if (!f) {
        set_why(why, why_len, strerror(errno));
        close(fd);
    }
    return f;
}

/* Waits until fd can be read (or is at its end); 0, 1 when a stop signal
 * came, -1 (errno). */
static int wait_readable(int fd)
{
    struct pollfd p = {fd, POLLIN, 0};
    for (;;) {
        if (cli_stop_requested()) return 1;
        const int n = poll(&p, 1, -1);
        if (n > 0) return 0;
        if (n < 0 && errno != EINTR) return -1;
    }
}

int cli_read_all(int fd, long max, char **buf, size_t *len, char *why, size_t why_len)
{
    *buf = NULL;
    *len = 0;
    size_t cap = 65536, n = 0;
    char *b = malloc(cap);
    if (!b) {
        set_why(why, why_len, "out of memory");
        return -1;
    }
    for (;;) {
        if (n == cap) {
            if (cap > (size_t)max) break; /* past the bound: refused below */
            size_t bigger = cap * 2 > (size_t)max + 1 ? (size_t)max + 1 : cap * 2;
            char *p = realloc(b, bigger);
            if (!p) {
                free(b);
                set_why(why, why_len, "out of memory");
                return -1;
            }
            b = p;
            cap = bigger;
        }
        const int w = wait_readable(fd);
        if (w != 0) {
            free(b);
            if (w < 0) set_why(why, why_len, strerror(errno));
            return w > 0 ? 1 : -1;
        }
        const ssize_t got = read(fd, b + n, cap - n);
        if (got == 0) break;
        if (got < 0) {
            if (errno == EINTR || errno == EAGAIN) continue; /* the stop is seen by wait_readable */
            set_why(why, why_len, strerror(errno));
            free(b);
            return -1;
        }
        n += (size_t)got;
    }
    if (n > (size_t)max) {
        free(b);
        snprintf(why, why_len, "larger than %ld bytes", max);
        return -1;
    }
    *buf = b;
    *len = n;
    return 0;
}
