/* Render in scratch, verify, move into place: the one implementation for
 * every output kind (outputs.h). */
#define _POSIX_C_SOURCE 200809L
#include "outputs.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The directory holding path ("." if none); -1 if it does not fit. */
static int dir_of(const char *path, char *dir, size_t len)
{
    const char *slash = strrchr(path, '/');
    int w;
    if (!slash) w = snprintf(dir, len, ".");
    else if (slash == path) w = snprintf(dir, len, "/");
    else w = snprintf(dir, len, "%.*s", (int)(slash - path), path);
    return w < 0 || (size_t)w >= len ? -1 : 0;
}

int cli_output_file_only(const char *cmd, const char *option, const char *target, const char *what)
{
    if (!target || strspn(target, "-") != 1 || target[1 + strspn(target + 1, "/")] != '\0') return 0; /* -, -/ */
    cli_error("%s: --%s %s: %s cannot go to standard output; give a file name (./- for a file named '-')", cmd,
              option, target, what);
    return -1;
}

int cli_output_check_target(const char *target)
{
    if (!target || !*target) {
        cli_error("empty output file name");
        return -1;
    }
    /* "-" is standard output wherever it is allowed (cli_output_begin); a
     * file that cannot go there is never made under that name. */
    if (strcmp(target, "-") == 0) {
        cli_error("cannot write '-': it means standard output, which cannot take this file; give a file name "
                  "(./- for a file named '-')");
        return -1;
    }
    const size_t n = strlen(target);
    if (target[n - 1] == '/') {
        cli_error("cannot write %s: it names a directory", target);
        return -1;
    }
    char dir[CLI_PATH_MAX];
    struct stat st;
    if (n >= CLI_PATH_MAX - 32 || dir_of(target, dir, sizeof dir) != 0) {
        cli_error("cannot write %s: %s", target, strerror(ENAMETOOLONG));
        return -1;
    }
    const int dir_err = stat(dir, &st) != 0 ? errno : !S_ISDIR(st.st_mode) ? ENOTDIR : 0;
    if (dir_err) {
        cli_error("cannot write %s: %s (directory %s)", target, strerror(dir_err), dir);
        return -1;
    }
    if (stat(target, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            cli_error("cannot write %s: it is a directory", target);
            return -1;
        }
        /* Mode bits, not access(): root may write anything, yet a file
         * marked read-only is not to be replaced behind its owner's back. */
        if (S_ISREG(st.st_mode) && ((st.st_mode & 0222) == 0 || access(target, W_OK) != 0)) {
            cli_error("cannot write %s: the file is read-only (Permission denied); remove it or make it writable",
                      target);
            return -1;
        }
        if (!S_ISREG(st.st_mode)) return 0; /* a device or FIFO: written in place */
    }
    if (access(dir, W_OK | X_OK) != 0) {
        cli_error("cannot write %s: %s", target, strerror(errno));
        return -1;
    }
    return 0;
}

/* The mode a new file gets (0666 less the umask), or the replaced file's:
 * mkstemp's 0600 must not leak into the result. */
static mode_t final_mode(const char *target)
{
    struct stat st;
    if (stat(target, &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 07777;
    const mode_t mask = umask(0);
    umask(mask);
    return 0666 & ~mask;
}

int cli_output_begin(cli_Output *o, const char *target, int allow_stdout)
{
    memset(o, 0, sizeof *o);
    o->slot = -1;
    o->target = target;
    if (allow_stdout && target && strcmp(target, "-") == 0) {
        o->f = stdout;
        o->in_place = o->is_stdout = 1;
        return 0;
    }
    if (cli_output_check_target(target) != 0) return -1;
    struct stat st;
    if (stat(target, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* A FIFO without a reader is an error, not a hang. */
        char why[128];
        if (!(o->f = cli_fopen_nowait(target, "w", O_WRONLY, 0, why, sizeof why))) {
            cli_error("cannot write %s: %s", target, why);
            return -1;
        }
        o->in_place = 1;
        return 0;
    }
    char dir[CLI_PATH_MAX];
    dir_of(target, dir, sizeof dir);
    /* A short name of our own: the user's name may already be as long as a
     * name can be. */
    if (cli_path_join(o->tmp, sizeof o->tmp, dir, "jumpcyl.tmp-XXXXXX") != 0) {
        cli_error("cannot write %s: %s", target, strerror(ENAMETOOLONG));
        o->tmp[0] = '\0';
        return -1;
    }
    const int fd = cli_tmpfile_create(o->tmp, &o->slot);
    if (fd < 0) {
        cli_error("cannot write %s: %s", target, strerror(errno));
        o->tmp[0] = '\0';
        return -1;
    }
    if (fchmod(fd, final_mode(target)) != 0 || !(o->f = fdopen(fd, "w"))) {
        cli_error("cannot write %s: %s", target, strerror(errno));
        close(fd);
        cli_output_abort(o);
        return -1;
    }
    return 0;
}

int cli_output_copy_from(cli_Output *o, const char *path)
{
    FILE *in = fopen(path, "rb");
    if (!in) {
        cli_error("cannot write %s: reading %s: %s", o->target, path, strerror(errno));
        return -1;
    }
    char buf[65536];
    size_t n;
    int bad = 0;
    while (!bad && (n = fread(buf, 1, sizeof buf, in)) > 0) bad = fwrite(buf, 1, n, o->f) != n;
    const int err = errno;
    bad |= ferror(in);
    fclose(in);
    if (bad) {
        cli_error("cannot write %s: %s", o->target, strerror(err ? err : EIO));
        return -1;
    }
    return 0;
}

void cli_output_abort(cli_Output *o)
{
    if (o->f && !o->is_stdout) fclose(o->f);
    o->f = NULL;
    if (o->tmp[0]) cli_tmpfile_finish(o->slot, o->tmp, NULL);
    o->tmp[0] = '\0';
}

/* The last bytes of a file (at most len - 1), NUL-terminated; their count, or -1. */
static long tail_of(FILE *f, char *buf, size_t len, long *size)
{
    if (fseek(f, 0, SEEK_END) != 0 || (*size = ftell(f)) < 0) return -1;
    const long n = *size < (long)len - 1 ? *size : (long)len - 1;
    if (fseek(f, *size - n, SEEK_SET) != 0 || fread(buf, 1, (size_t)n, f) != (size_t)n) return -1;
    buf[n] = '\0';
    return n;
}

/* Trailing blanks, which the formats allow after their end marker. */
static long trim(const char *buf, long n)
{
    while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == '\r' || buf[n - 1] == ' ' || buf[n - 1] == '\t')) --n;
    return n;
}

static int ends_with(const char *buf, long n, const char *end)
{
    const long k = (long)strlen(end);
    return n >= k && memcmp(buf + n - k, end, (size_t)k) == 0;
}

int cli_output_verify(const char *path, cli_Check check, char *why, size_t why_len)
{
    if (check == CLI_CHECK_WRITES) return 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, why_len, "%s", strerror(errno));
        return -1;
    }
    char head[64] = {0}, tail[64];
    const size_t h = fread(head, 1, sizeof head - 1, f);
    long size = 0;
    const long n = tail_of(f, tail, sizeof tail, &size);
    fclose(f);
    int ok = n >= 0 && size > 0;
    const char *what = "empty";
    if (ok && check == CLI_CHECK_PNG) {
        static const char iend[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', (char)0xae, 0x42, 0x60, (char)0x82};
        ok = h >= 8 && memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0 && n >= 12 && memcmp(tail + n - 12, iend, 12) == 0;
        what = "not a complete PNG file (no IEND chunk at its end)";
    } else if (ok && check == CLI_CHECK_PDF) {
        ok = h >= 5 && memcmp(head, "%PDF-", 5) == 0 && ends_with(tail, trim(tail, n), "%%EOF");
        what = "not a complete PDF file (no %%EOF at its end)";
    } else if (ok && check == CLI_CHECK_SVG) {
        ok = (strncmp(head, "<?xml", 5) == 0 || strncmp(head, "<svg", 4) == 0) && ends_with(tail, trim(tail, n), "</svg>");
        what = "not a complete SVG file (its root element is not closed)";
    }
    if (!ok) snprintf(why, why_len, "%s", n < 0 ? strerror(errno) : what);
    return ok ? 0 : -1;
}

/* fsync of the directory that holds path: the rename itself reaches the disk. */
void cli_sync_dir(const char *path)
{
    char dir[CLI_PATH_MAX];
    if (dir_of(path, dir, sizeof dir) != 0) return;
    const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    fsync(fd); /* some file systems refuse it on directories: nothing more to do then */
    close(fd);
}

int cli_output_finish(cli_Output *o, cli_Check check)
{
    /* An earlier write failed and stdio lost its errno: the likely reason. */
    int err = ferror(o->f) ? cli_lost_write_errno(fileno(o->f)) : EIO;
    int bad = ferror(o->f);
    if (fflush(o->f) != 0) {
        bad = 1;
        err = errno;
    }
    /* A device or FIFO takes no fsync (EINVAL): only the regular file is synced. */
    if (!bad && !o->in_place && fsync(fileno(o->f)) != 0) {
        bad = 1;
        err = errno;
    }
    if (!o->is_stdout) {
        if (fclose(o->f) != 0 && !bad) {
            bad = 1;
            err = errno;
        }
        o->f = NULL;
    }
    if (bad) {
        if (!(o->is_stdout && cli_pipe_closed(err)) && !(o->in_place && cli_write_stopped(err)))
            cli_error("cannot write %s: %s", o->is_stdout ? "standard output" : o->target, strerror(err));
        cli_output_abort(o);
        return -1;
    }
    char why[128];
    if (!o->in_place && cli_output_verify(o->tmp, check, why, sizeof why) != 0) {
        cli_error("cannot write %s: %s", o->target, why);
        cli_output_abort(o);
        return -1;
    }
    return 0;
}

int cli_output_publish(cli_Output *o)
{
    if (o->in_place) return 0;
    /* Interrupted before this point: the target keeps its old content. */
    if (cli_stop_requested()) {
        cli_output_abort(o);
        return -1;
    }
    if (cli_tmpfile_finish(o->slot, o->tmp, o->target) != 0) {
        cli_error("cannot write %s: %s", o->target, strerror(errno));
        o->tmp[0] = '\0';
        return -1;
    }
    o->tmp[0] = '\0';
    cli_sync_dir(o->target);
    return 0;
}

int cli_output_commit(cli_Output *o, cli_Check check)
{
    return cli_output_finish(o, check) == 0 && cli_output_publish(o) == 0 ? 0 : -1;
}

void cli_safe_name(const char *name, char *out, size_t len)
{
    if (len == 0) return;
    size_t n = 0;
    const unsigned char first = (unsigned char)name[0];
    const int starts_plain = (first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z') ||
                             (first >= '0' && first <= '9');
    if (!starts_plain && n + 1 < len) out[n++] = 'f';
    for (const unsigned char *p = (const unsigned char *)name; *p && n + 1 < len; ++p) {
        const int plain = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
                          *p == '.' || *p == '_' || *p == '+' || *p == '-';
        out[n++] = plain ? (char)*p : '_';
    }
    out[n] = '\0';
}

/* A write to standard output failed with err: EXIT_FAIL after a message,
 * but quietly for a closed pipe (cli_pipe_closed), whose stop status main.c
 * returns after SIGPIPE. */
static int stdout_failed(int err)
{
    if (!cli_pipe_closed(err) && !cli_write_stopped(err)) cli_error("cannot write standard output: %s", strerror(err));
    return cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
}

int cli_stdout_finish(void)
{
    int err = ferror(stdout) ? cli_lost_write_errno(fileno(stdout)) : EIO;
    int bad = ferror(stdout);
    if (fflush(stdout) != 0) {
        bad = 1;
        err = errno;
    }
    return bad ? stdout_failed(err) : EXIT_OK;
}

int cli_stdout_close(void)
{
    int rc = cli_stdout_finish();
    /* The close reports what the flush could not (a descriptor closed by the caller). */
    if (fclose(stdout) != 0 && rc == EXIT_OK) rc = stdout_failed(errno);
    return rc;
}

/* ---- JSON documents into a file or standard output ---- */

int cli_json_write(cJSON *doc, const char *target)
{
    if (strcmp(target, "-") == 0) return cli_json_print(doc);
    char *text = cli_json_text(doc, 1);
    cJSON_Delete(doc);
    if (!text) {
        cli_error("could not format the JSON output (out of memory)");
        return EXIT_FAIL;
    }
    cli_Output o;
    int rc = cli_output_begin(&o, target, 0) == 0 ? EXIT_OK : EXIT_FAIL;
    if (rc == EXIT_OK) {
        fputs(text, o.f);
        fputc('\n', o.f);
        if (cli_output_commit(&o, CLI_CHECK_WRITES) != 0) rc = EXIT_FAIL;
    }
    free(text);
    return rc;
}
