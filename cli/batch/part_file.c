/* FILE.part: the rows of a batch job until it is complete, a file that is
 * the tool's own (docs/batch.md, "Stopping and resuming").
 *
 * - It is created with O_CREAT|O_EXCL|O_NOFOLLOW, or, for --resume, opened
 *   with O_NOFOLLOW and accepted only as a regular file of one link owned
 *   by the user: a symlink or a hard link planted under its name is never
 *   written through.
 * - It is locked (flock) from its open to its end: a second job on the
 *   same output is refused while the first runs.
 * - Its first line names the job: the tool's version and a hash of
 *   everything that decides the rows (the study: base setup, fixed values,
 *   parameters, samples and seed, simulation options; and the shard's
 *   cases). Each row carries a checksum keyed by that hash, after a tab.
 * - Rows reach the file whole: a block is written at once, and a failed
 *   write (a full disk) is cut back to the last whole row.
 * - The final FILE is a copy of the rows without the job line and the
 *   checksums, written as every other output (cli_output_begin: a
 *   temporary beside it with the mode of the file it replaces, fsynced,
 *   renamed); then FILE.part is removed.
 * Nothing here truncates a file whose first line is not this job's. */
#define _GNU_SOURCE /* flock */
#include "batch.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#define FSYNC_PERIOD_S 1.0
#define PART_MAGIC "jumpcyl-part 1 "

/* ---- the job's hash and the rows' checksums ---- */

/* FNV-1a, 64 bits: a checksum against rows changed by hand or by a
 * damaged disk, not a signature (the rows computed again on --resume are
 * the check against a forger). */
#define FNV_OFFSET 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

static uint64_t fnv_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * FNV_PRIME;
    return h;
}

/* A number by its value's bytes in a fixed order (little-endian), so that
 * the hash is the same on every host of one architecture family. */
static uint64_t fnv_u64(uint64_t h, uint64_t v)
{
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = (unsigned char)(v >> (8 * i));
    return fnv_bytes(h, b, sizeof b);
}

static uint64_t fnv_double(uint64_t h, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    return fnv_u64(h, bits);
}

static uint64_t fnv_long(uint64_t h, long v) { return fnv_u64(h, (uint64_t)v); }

static uint64_t hash_setup(uint64_t h, const jc_Setup *s)
{
    h = fnv_double(h, s->body.radius_m);
    h = fnv_long(h, s->body.part_count);
    for (int i = 0; i < s->body.part_count && i < JC_MAX_PARTS; ++i) {
        const jc_Part *p = &s->body.parts[i];
        h = fnv_long(h, p->kind);
        h = fnv_double(h, p->mass_kg);
        h = fnv_double(h, p->offset_m);
        h = fnv_double(h, p->angle_rad);
        h = fnv_double(h, p->radius_m);
    }
    const double v[] = {s->incline_rad,       s->gravity_mps2,      s->mu_static,        s->mu_kinetic,
                        s->restitution,       s->theta0_rad,        s->omega0_radps,     s->ramp_length_m,
                        s->paper_cm_offset_m, s->length_m,          s->air_density_kgpm3, s->drag_coefficient,
                        s->lift_coefficient,  s->spin_drag_Nms2,    s->rolling_resistance_m};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i) h = fnv_double(h, v[i]);
    h = fnv_long(h, s->impact_law);
    /* Every row of the parameter table too, so that a setting added to the
     * table later counts without an edit here. */
    for (int id = 0; id < jc_param_count(); ++id) {
        double x = 0.0;
        char err[8];
        h = jc_param_get(s, id, &x, err, sizeof err) == JC_OK ? fnv_double(h, x) : fnv_long(h, -1);
    }
    return h;
}

static uint64_t hash_sim(uint64_t h, const jc_SimOptions *o)
{
    /* sample_dt_s is not used by a study's cases */
    h = fnv_double(h, o->t_max_s);
    h = fnv_long(h, o->max_events);
    h = fnv_long(h, o->max_samples);
    h = fnv_double(h, o->ode_rtol);
    h = fnv_double(h, o->ode_atol);
    h = fnv_double(h, o->event_tol_s);
    return fnv_double(h, o->contact_height_m);
}

uint64_t cli_part_job_hash(const jc_StudyDef *def, long lo, long hi)
{
    const char *version = jc_version();
    uint64_t h = fnv_bytes(FNV_OFFSET, version, strlen(version) + 1);
    h = fnv_long(h, def->kind);
    h = fnv_long(h, lo);
    h = fnv_long(h, hi);
    h = hash_setup(h, &def->base);
    for (int id = 0; id < JC_PARAM_MAX; ++id)
        if (def->fixed.given[id]) h = fnv_double(fnv_long(h, id), def->fixed.value[id]);
    h = fnv_long(h, def->fixed.parts_given);
    h = fnv_long(h, def->param_count);
    for (int j = 0; j < def->param_count && j < JC_STUDY_PARAM_MAX; ++j) {
        const jc_StudyParam *p = &def->params[j];
        h = fnv_long(fnv_long(h, p->id), p->spread);
        if (p->spread == JC_STUDY_VALUES) {
            h = fnv_long(h, p->count);
            for (long k = 0; k < p->count; ++k) h = fnv_double(h, p->values[k]);
        } else {
            h = fnv_double(fnv_double(h, p->a), p->b);
        }
    }
    if (def->kind == JC_STUDY_MONTE_CARLO) h = fnv_u64(fnv_long(h, def->samples), def->seed);
    return hash_sim(h, &def->sim);
}

uint64_t cli_part_row_sum(uint64_t job, const char *row, size_t len)
{
    return fnv_bytes(fnv_u64(FNV_OFFSET, job), row, len);
}

int cli_part_job_line(const char *cmd, uint64_t job, long lo, long hi, char *out, size_t len)
{
    return snprintf(out, len, PART_MAGIC "%s version %s job %016llx cases %ld-%ld\n", cmd, jc_version(),
                    (unsigned long long)job, lo, hi - 1);
}

/* ---- reading ---- */

/* The version a job line names ("?" if it names none). */
static void line_version(const char *line, char *out, size_t len)
{
    const char *v = strstr(line, " version ");
    const size_t n = v ? strcspn(v + 9, " \n") : 0;
    snprintf(out, len, "%.*s", (int)(n ? n : 1), n ? v + 9 : "?");
}

/* The checksum after the tab: the row's length (without it), or -1. */
static long checked_row(const cli_PartReader *rd, const char *line, size_t n)
{
    if (n < 18 || line[n - 1] != '\n' || line[n - 18] != '\t') return -1;
    uint64_t sum = 0;
    for (size_t i = n - 17; i < n - 1; ++i) {
        const char c = line[i];
        const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (d < 0) return -1;
        sum = sum << 4 | (uint64_t)d;
    }
    const size_t row = n - 18;
    return cli_part_row_sum(rd->job, line, row) == sum ? (long)row : -1;
}

/* The first line: 0 this job's, 1 nothing of value (empty, or the start of
 * this job's line cut short), -1 another's (err says whose). */
static int check_job_line(const cli_PartReader *rd, const char *line, size_t n, int at_eof, char *err, size_t err_len)
{
    const size_t want = strlen(rd->job_line);
    if (n == want && memcmp(line, rd->job_line, n) == 0) return 0;
    if (n == 0 || (at_eof && n < want && memcmp(line, rd->job_line, n) == 0)) return 1;
    if (n < strlen(PART_MAGIC) || memcmp(line, PART_MAGIC, strlen(PART_MAGIC)) != 0 || line[n - 1] != '\n') {
        snprintf(err, err_len, "it is not a .part file of jumpcyl (its first line is not \"%.*s...\")",
                 (int)strlen(PART_MAGIC) - 1, PART_MAGIC);
        return -1;
    }
    char theirs[32];
    line_version(line, theirs, sizeof theirs);
    if (strcmp(theirs, jc_version()) != 0)
        snprintf(err, err_len, "it holds the rows of jumpcyl %s, not of this version (%s)", theirs, jc_version());
    else
        snprintf(err, err_len, "it holds the rows of another job (other options, values, samples, seed or shard)");
    return -1;
}

/* One line of at most cap - 1 bytes into buf (NUL-terminated; a NUL inside
 * counts as a byte): its length, '\n' included; a last line without one at
 * the end of the file; 0 at the end; -1 for a line too long to be a row,
 * -2 for a read error. */
static long read_line(FILE *f, char *buf, size_t cap)
{
    size_t n = 0;
    int c = 0;
    while (n + 1 < cap && (c = getc(f)) != EOF) {
        buf[n++] = (char)c;
        if (c == '\n') break;
    }
    buf[n] = '\0';
    if (n > 0 && buf[n - 1] == '\n') return (long)n;
    if (ferror(f)) return -2;
    if (n + 1 >= cap) return -1;
    return (long)n;
}

int cli_part_read(FILE *f, const cli_PartReader *rd, cli_PartRead *out, char *err, size_t err_len)
{
    char line[JC_STUDY_ROW_MAX + 32];
    memset(out, 0, sizeof *out);
    long n = read_line(f, line, sizeof line);
    if (n < 0) {
        snprintf(err, err_len, n == -2 ? "it cannot be read: %s" : "it is not a .part file of jumpcyl (its first line "
                                                                   "is too long)",
                 strerror(errno));
        return -1;
    }
    const int first = check_job_line(rd, line, (size_t)n, n == 0 || line[n - 1] != '\n', err, err_len);
    if (first != 0) return first;
    long line_no = 1;
    off_t end = (off_t)n;
    int want_header = rd->csv_header != NULL;
    while ((n = read_line(f, line, sizeof line)) > 0) {
        ++line_no;
        if (line[n - 1] != '\n') break; /* half written when the job stopped: cut by the caller */
        if (want_header) {
            if ((size_t)n != strlen(rd->csv_header) || memcmp(line, rd->csv_header, (size_t)n) != 0) {
                snprintf(err, err_len, "line 2 is not this job's header of the rows");
                return -1;
            }
            want_header = 0;
            end += (off_t)n;
            continue;
        }
        const long index = rd->first + out->rows;
        const long len = checked_row(rd, line, (size_t)n);
        if (len < 0) {
            snprintf(err, err_len, "line %ld (case %ld): its checksum does not match its text (changed after it was "
                                   "written)", line_no, index);
            return -1;
        }
        cli_CaseResult r;
        if (out->rows >= rd->count || cli_case_from_row(line, (size_t)len, rd->input_columns, &r) != 0 ||
            (rd->row && rd->row(rd->ctx, index, line, (size_t)len, &r) != 0)) {
            snprintf(err, err_len, "line %ld is not case %ld of this job", line_no, index);
            return -1;
        }
        ++out->rows;
        end += (off_t)n;
    }
    if (n == -1) {
        snprintf(err, err_len, "line %ld is too long to be a row", line_no + 1);
        return -1;
    }
    if (n == -2) {
        snprintf(err, err_len, "it cannot be read: %s", strerror(errno));
        return -1;
    }
    out->good_end = end;
    out->header_done = !want_header;
    return 0;
}

/* ---- the open file ---- */

/* The lock, taken without waiting; 0, or -1 after a message. */
static int lock(cli_PartFile *p, const char *cmd)
{
    if (flock(p->fd, LOCK_EX | LOCK_NB) == 0) return 0;
    if (errno == EWOULDBLOCK)
        cli_error("%s: another job is writing %s now (it holds its lock): wait for it to end, or give another --output",
                  cmd, p->path);
    else cli_error("%s: cannot lock %s: %s", cmd, p->path, strerror(errno));
    return -1;
}

/* Whether the name still leads to the file we hold (not removed or
 * replaced between the open and the lock). */
static int still_named(const cli_PartFile *p)
{
    struct stat a, b;
    return fstat(p->fd, &a) == 0 && lstat(p->path, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

static void part_close(cli_PartFile *p)
{
    if (p->fd >= 0) close(p->fd); /* and the lock with it */
    p->fd = -1;
    free(p->buf);
    p->buf = NULL;
    p->len = p->cap = 0;
}

/* A whole buffer at the file's end; 0, or -1 with errno (*done: the bytes
 * written before the failure; may be NULL). */
static int write_all(int fd, const char *buf, size_t len, size_t *done)
{
    size_t at = 0;
    int rc = 0;
    while (at < len) {
        const ssize_t w = write(fd, buf + at, len - at);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            if (w == 0) errno = EIO;
            rc = -1;
            break;
        }
        at += (size_t)w;
    }
    if (done) *done = at;
    return rc;
}

/* What a file that is not a regular one is, for messages. */
static const char *kind_of(mode_t mode)
{
    return S_ISLNK(mode) ? "a symbolic link" : S_ISDIR(mode) ? "a directory" : S_ISFIFO(mode) ? "a FIFO"
           : S_ISSOCK(mode) ? "a socket" : "a device";
}

/* A new FILE.part: EXIT_OK, or an exit status after a message. */
static int create(cli_PartFile *p, const char *cmd)
{
    p->fd = open(p->path, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (p->fd < 0) {
        if (errno != EEXIST) {
            cli_error("%s: cannot create %s: %s", cmd, p->path, strerror(errno));
            return EXIT_FAIL;
        }
        /* Held by a running job, or kept by a stopped one. */
        cli_PartFile other = {.fd = open(p->path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC)};
        memcpy(other.path, p->path, sizeof other.path);
        const int busy = other.fd >= 0 && flock(other.fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
        part_close(&other);
        struct stat st;
        if (lstat(p->path, &st) == 0 && !S_ISREG(st.st_mode))
            cli_error("%s: %s exists and is not a regular file (%s); it is left as it is: remove it or give another "
                      "--output", cmd, p->path, kind_of(st.st_mode));
        else if (busy)
            cli_error("%s: another job is writing %s now (it holds its lock): wait for it to end, or give another "
                      "--output", cmd, p->path);
        else
            cli_error("%s: %s holds the rows of an unfinished job: continue it with --resume, or remove it", cmd,
                      p->path);
        return EXIT_USAGE;
    }
    if (lock(p, cmd) != 0) { /* a resumer took it between the create and here: its job now */
        part_close(p);
        return EXIT_USAGE;
    }
    p->created = 1;
    return EXIT_OK;
}

/* An existing FILE.part for --resume: 1 when there is none (create it),
 * EXIT_OK when it is open and locked, or an exit status after a message. */
static int open_existing(cli_PartFile *p, const char *cmd)
{
    p->fd = open(p->path, O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (p->fd < 0) {
        if (errno == ENOENT) return 1;
        cli_error("%s: cannot open %s: %s%s", cmd, p->path, strerror(errno),
                  errno == ELOOP ? " (it is a symbolic link; it is left as it is)" : "");
        return EXIT_USAGE;
    }
    struct stat st;
    char not_regular[64];
    const int stat_ok = fstat(p->fd, &st) == 0;
    if (stat_ok) snprintf(not_regular, sizeof not_regular, "it is not a regular file (%s)", kind_of(st.st_mode));
    const char *why = !stat_ok ? strerror(errno)
                      : !S_ISREG(st.st_mode)  ? not_regular
                      : st.st_uid != geteuid() ? "it is not owned by you"
                      : st.st_nlink != 1     ? "it has other names (hard links)"
                                              : NULL;
    if (why) {
        cli_error("%s: %s is not a file this tool would have made: %s; it is left as it is", cmd, p->path, why);
        part_close(p);
        return EXIT_USAGE;
    }
    fcntl(p->fd, F_SETFL, fcntl(p->fd, F_GETFL) & ~O_NONBLOCK);
    if (lock(p, cmd) != 0) {
        part_close(p);
        return EXIT_USAGE;
    }
    if (!still_named(p)) {
        cli_error("%s: %s was removed or replaced while it was opened; run the command again", cmd, p->path);
        part_close(p);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* The kept rows read and checked (rd); *done receives their count. EXIT_OK
 * (the file then ends on a whole row, positioned at its end), or an exit
 * status after a message. */
static int resume(cli_PartFile *p, const char *cmd, const cli_PartReader *rd, long *done)
{
    const int fd = dup(p->fd);
    FILE *f = fd >= 0 ? fdopen(fd, "r") : NULL;
    if (!f) {
        cli_error("%s: cannot read %s: %s", cmd, p->path, strerror(errno));
        if (fd >= 0) close(fd);
        return EXIT_FAIL;
    }
    cli_PartRead got;
    char why[256];
    const int st = cli_part_read(f, rd, &got, why, sizeof why);
    fclose(f);
    if (st < 0) {
        cli_error("%s: %s: %s; it is left as it is: remove it to start again", cmd, p->path, why);
        return EXIT_USAGE;
    }
    /* Ours: only a last line cut short is cut off (or, with nothing of
     * value, the start of the job line). */
    p->end = st == 1 ? 0 : got.good_end;
    if (ftruncate(p->fd, p->end) != 0 || lseek(p->fd, p->end, SEEK_SET) < 0) {
        cli_error("%s: cannot cut %s: %s", cmd, p->path, strerror(errno));
        return EXIT_FAIL;
    }
    p->header_done = st == 0 && got.header_done;
    p->job_line_done = st == 0;
    *done = st == 0 ? got.rows : 0;
    return EXIT_OK;
}

int cli_part_begin(cli_PartFile *p, const char *cmd, const char *output, int want_resume, const cli_PartReader *rd,
                   long *done)
{
    memset(p, 0, sizeof *p);
    p->fd = -1;
    *done = 0;
    if (snprintf(p->path, sizeof p->path, "%s.part", output) >= (int)sizeof p->path) {
        cli_error("%s: --output '%s': the name is too long", cmd, output);
        return EXIT_USAGE;
    }
    int st = want_resume ? open_existing(p, cmd) : 1;
    if (st == 1) st = create(p, cmd);
    else if (st == EXIT_OK) st = resume(p, cmd, rd, done);
    if (st != EXIT_OK) {
        part_close(p);
        return st;
    }
    /* The job line and the rows' header, written and synced before any row. */
    char head[2 * JC_STUDY_ROW_MAX + 128];
    size_t n = 0;
    if (!p->job_line_done) n += (size_t)snprintf(head, sizeof head, "%s", rd->job_line);
    if (!p->header_done && rd->csv_header) n += (size_t)snprintf(head + n, sizeof head - n, "%s", rd->csv_header);
    if (n > 0 && (write_all(p->fd, head, n, NULL) != 0 || fsync(p->fd) != 0)) {
        const int err = errno;
        if (ftruncate(p->fd, p->end) != 0) { /* nothing more to do: the message below says it */
        }
        if (p->created) unlink(p->path); /* ours and empty */
        cli_error("%s: cannot write %s: %s", cmd, p->path, strerror(err));
        part_close(p);
        return EXIT_FAIL;
    }
    p->end += (off_t)n;
    p->rows = *done;
    p->job = rd->job;
    p->last_sync_s = cli_now_s();
    return EXIT_OK;
}

int cli_part_add(cli_PartFile *p, const char *row, int row_len)
{
    if (row_len < 1 || row[row_len - 1] != '\n') return -1;
    const size_t need = p->len + (size_t)row_len + 17;
    if (need > p->cap) {
        const size_t cap = need > 2 * p->cap ? need + 65536 : 2 * p->cap;
        char *b = realloc(p->buf, cap);
        if (!b) return -1;
        p->buf = b;
        p->cap = cap;
    }
    const size_t text = (size_t)row_len - 1;
    memcpy(p->buf + p->len, row, text);
    p->len += text;
    p->len += (size_t)snprintf(p->buf + p->len, 19, "\t%016llx", (unsigned long long)cli_part_row_sum(p->job, row, text));
    p->buf[p->len++] = '\n';
    ++p->pending;
    return 0;
}

/* A failed write or sync: the file cut back to its last whole row and the
 * message that says what is kept. */
static void write_failed(cli_PartFile *p, const char *cmd, int err, off_t keep, long rows)
{
    if (ftruncate(p->fd, keep) == 0) {
        p->end = keep;
        p->rows = rows;
        (void)fsync(p->fd);
    }
    if (err == ENOSPC || err == EDQUOT)
        cli_error("%s: no space left; %ld rows kept in %s; free space and run again with --resume", cmd, p->rows,
                  p->path);
    else if (err == EFBIG)
        cli_error("%s: File too large (the limit of ulimit -f); %ld rows kept in %s; raise the limit and run again "
                  "with --resume", cmd, p->rows, p->path);
    else
        cli_error("%s: cannot write %s: %s; %ld rows kept in it; run again with --resume", cmd, p->path,
                  strerror(err), p->rows);
}

int cli_part_flush(cli_PartFile *p, const char *cmd, int final)
{
    if (p->fd < 0) return 0;
    size_t written = 0;
    if (p->len > 0 && write_all(p->fd, p->buf, p->len, &written) != 0) {
        /* The rows that reached the file whole are kept; a row cut short is cut off. */
        const int err = errno;
        size_t whole = 0;
        long rows = 0;
        for (size_t i = 0; i < written; ++i)
            if (p->buf[i] == '\n') {
                whole = i + 1;
                ++rows;
            }
        write_failed(p, cmd, err, p->end + (off_t)whole, p->rows + rows);
        return -1;
    }
    p->end += (off_t)p->len;
    p->rows += p->pending;
    p->len = 0;
    p->pending = 0;
    if (final || cli_now_s() - p->last_sync_s >= FSYNC_PERIOD_S) {
        if (fsync(p->fd) != 0) { /* what the disk holds since the last sync is unknown: keep what was synced */
            write_failed(p, cmd, errno, p->synced_end, p->synced_rows);
            return -1;
        }
        p->synced_end = p->end;
        p->synced_rows = p->rows;
        p->last_sync_s = cli_now_s();
    }
    return 0;
}

int cli_part_each_row(cli_PartFile *p, int has_header, int (*fn)(void *ctx, long i, const char *row, size_t len),
                      void *ctx)
{
    const int fd = dup(p->fd);
    FILE *in = fd >= 0 && lseek(fd, 0, SEEK_SET) == 0 ? fdopen(fd, "r") : NULL;
    if (!in) {
        if (fd >= 0) close(fd);
        return -1;
    }
    char line[JC_STUDY_ROW_MAX + 32];
    long n, line_no = 0, i = 0;
    const long skip = has_header ? 2 : 1;
    int stop = 0;
    while (!stop && (n = read_line(in, line, sizeof line)) > 0)
        if (++line_no > skip && n >= 18) stop = fn(ctx, i++, line, (size_t)n - 18);
    const int bad = ferror(in);
    fclose(in);
    lseek(p->fd, p->end, SEEK_SET);
    return bad ? -1 : 0;
}

/* The rows without the job line and the checksums into FILE (a temporary
 * beside it, renamed over it). 0, or -1 after a message. */
static int publish(cli_PartFile *p, const char *cmd, const char *output, int has_header)
{
    cli_Output o;
    if (cli_output_begin(&o, output, 0) != 0) return -1;
    const int fd = dup(p->fd);
    FILE *in = fd >= 0 && lseek(fd, 0, SEEK_SET) == 0 ? fdopen(fd, "r") : NULL;
    if (!in && fd >= 0) close(fd);
    char line[JC_STUDY_ROW_MAX + 32];
    int err = in ? 0 : errno;
    long n, line_no = 0;
    while (!err && (n = read_line(in, line, sizeof line)) > 0) {
        if (++line_no == 1) continue; /* the job line */
        size_t keep = (size_t)n;
        if (!(has_header && line_no == 2)) {
            keep = (size_t)n - 17; /* the row and its '\n', without the checksum */
            line[keep - 1] = '\n';
        }
        if (fwrite(line, 1, keep, o.f) != keep) err = errno ? errno : EIO;
    }
    if (!err && in && ferror(in)) err = errno ? errno : EIO;
    if (in) fclose(in);
    if (!err && (fflush(o.f) != 0 || fsync(fileno(o.f)) != 0)) err = errno;
    if (err) {
        cli_output_abort(&o);
        if (err == ENOSPC || err == EDQUOT)
            cli_error("%s: no space left; %ld rows kept in %s; free space and run again with --resume", cmd, p->rows,
                      p->path);
        else
            cli_error("%s: cannot write %s: %s; %ld rows kept in %s; run again with --resume", cmd, output,
                      strerror(err), p->rows, p->path);
        return -1;
    }
    return cli_output_commit(&o, CLI_CHECK_WRITES);
}

int cli_part_end(cli_PartFile *p, const char *cmd, const char *output, int complete, int has_header)
{
    if (p->fd < 0) return 0;
    int rc = 0;
    if (complete) {
        rc = publish(p, cmd, output, has_header);
        /* FILE is whole: FILE.part, still ours (we hold its lock), goes. */
        if (rc == 0 && still_named(p) && unlink(p->path) == 0) cli_sync_dir(p->path);
    }
    part_close(p);
    return rc;
}
