/* Every file the tool hands to the user (figure, film, CSV, kept script)
 * goes through here: it is made under a private temporary name beside its
 * target (or copied there from the scratch directory where gnuplot or
 * ffmpeg made it), checked for completeness, fsynced, and only then renamed
 * over the target, whose directory is fsynced too. Any failure, and any
 * signal before the rename, leaves the target as it was and no temporary
 * file behind. "-" means standard output (no rename: written in place). */
#ifndef JUMPCYL_SAFE_OUTPUT_H
#define JUMPCYL_SAFE_OUTPUT_H

#include <stddef.h>
#include <stdio.h>

#ifndef CLI_PATH_MAX
#define CLI_PATH_MAX 4096
#endif

/* What a finished file must look like before it may replace anything. */
typedef enum {
    CLI_CHECK_WRITES,   /* our own writer: every write and the close succeeded */
    CLI_CHECK_PNG,      /* PNG signature ... IEND chunk at the very end */
    CLI_CHECK_PDF,      /* %PDF- ... %%EOF at the end */
    CLI_CHECK_SVG,      /* <?xml or <svg ... </svg> at the end */
    CLI_CHECK_NONEMPTY  /* a film: ffmpeg exited 0 and wrote something */
} cli_Check;

typedef struct {
    FILE *f;                   /* write here (NULL until cli_output_begin succeeded) */
    const char *target;        /* the user's name, for messages and the rename */
    char tmp[CLI_PATH_MAX];    /* the temporary file beside the target; "" if none */
    int slot;                  /* its record in signals.c */
    int in_place;              /* "-" or an existing non-regular file (/dev/null, a FIFO) */
    int is_stdout;
} cli_Output;

/* Checks the target before any work (its directory exists and is writable;
 * an existing target is a writable regular file, or a device or FIFO; a
 * read-only one is refused as cp refuses it) and opens the temporary file.
 * 0, or -1 after a one-line message naming the target. allow_stdout: "-"
 * means standard output. */
int cli_output_begin(cli_Output *o, const char *target, int allow_stdout);
/* Only the checks of cli_output_begin, for commands that work long before
 * they write (plot, animate): 0, or -1 after a message. */
int cli_output_check_target(const char *target);
/* Appends the file at path (made in the scratch directory) to o->f. */
int cli_output_copy_from(cli_Output *o, const char *path);
/* Closes the temporary file after checking every write, fsyncs it, checks
 * its content (check), and renames it over the target. 0, or -1 after a
 * message; on failure the target is untouched and the temporary removed. */
int cli_output_commit(cli_Output *o, cli_Check check);
/* Two-step form for outputs that must appear together (a figure and its
 * kept script): finish every one, then publish every one. */
int cli_output_finish(cli_Output *o, cli_Check check);
int cli_output_publish(cli_Output *o);
/* Removes the temporary file; the target stays as it was. Safe to repeat. */
void cli_output_abort(cli_Output *o);

/* fsync of the directory that holds path, so that a rename in it reaches the disk. */
void cli_sync_dir(const char *path);

/* Whether the file at path is complete as check says; 0, or -1 with the
 * reason in why. */
int cli_output_verify(const char *path, cli_Check check, char *why, size_t why_len);

/* A file name made from name that no program reads as anything but a plain
 * name: bytes other than letters, digits, '.', '_', '+' and '-' become '_',
 * and a name not starting with a letter or digit gets "f" in front (so no
 * leading '-', '.', '<' or '|'). At most len - 1 bytes; "" becomes "f". */
void cli_safe_name(const char *name, char *out, size_t len);

/* Standard output flushed and closed at exit: EXIT_OK, or EXIT_FAIL after a
 * message (a full disk, a closed descriptor). */
int cli_stdout_close(void);

#endif
