/* Helpers shared by `jumpcyl plot` and `jumpcyl animate`: progress on a
 * terminal, external programs (gnuplot, ffmpeg), scratch directories, file
 * names. The drawing of a frame has its own header, draw.h. */
#ifndef JUMPCYL_FIGURES_H
#define JUMPCYL_FIGURES_H

#include "cli.h"

#include <stddef.h>

#ifndef CLI_PATH_MAX
#define CLI_PATH_MAX 4096
#endif

/* ---- paper_row.c: the paper's Table 1 beside the model ---- */

/* The row of Table 1 for the setup: the paper's cylinder on one of the
 * table's inclines (friction, restitution and the start may differ, as the
 * paper's model has none of them); NULL for any other setup. */
const jc_PaperTableRow *cli_paper_row(const jc_Setup *s);

/* ---- progress.c: "frame 120/264, ETA 3 s" on stderr ---- */

/* Shown only when stderr is a terminal, and only once the job has taken
 * more than a second, so quick jobs and pipelines stay silent. */
typedef struct {
    char label[96];
    int enabled;     /* stderr is a terminal */
    int shown;       /* a line is on the screen and must be cleared */
    double start_s;  /* monotonic clock at begin */
    double last_s;   /* last redraw, to redraw at most ~10 times a second */
} cli_Progress;

double cli_now_s(void);
void cli_progress_begin(cli_Progress *p, const char *label);
/* done of total; total <= 0 means unknown (elapsed time only). */
void cli_progress_update(cli_Progress *p, long done, long total);
void cli_progress_end(cli_Progress *p);

/* ---- spawn.c: external programs ---- */

/* Full path of an executable named name found in $PATH; 0, or -1 if none. */
int cli_find_program(const char *name, char *path, size_t len);
/* Runs argv (argv[0] looked up in $PATH) in the directory cwd (NULL: ours)
 * with stdin from /dev/null and stdout and stderr appended to log_path
 * (NULL: inherited), waits for it, updating progress (may be NULL)
 * meanwhile. Returns its exit status; -1 after a message if it could not
 * start or was killed by a signal; CLI_RUN_STOPPED (no message) when a stop
 * signal came (the child was ended and reaped); CLI_RUN_EFBIG when a write
 * of the child crossed the file size limit (ulimit -f). */
#define CLI_RUN_STOPPED (-2)
#define CLI_RUN_EFBIG (-3)
int cli_run_program(char *const argv[], const char *cwd, const char *log_path, cli_Progress *progress);
/* Copies the last lines of a program's log to stderr, indented. */
void cli_print_log_tail(const char *log_path);

/* ---- workdir.c: scratch directories and file names ---- */

typedef struct {
    char path[CLI_PATH_MAX];
    int slot; /* its record in signals.c: a signal that ends the process removes it */
} cli_WorkDir;

/* A new private directory under $TMPDIR (or /tmp); 0, or -1 after a message. */
int cli_workdir_make(cli_WorkDir *w, const char *cmd);
/* Removes the directory and the files in it (it holds no subdirectories). */
void cli_workdir_remove(cli_WorkDir *w);
/* Removes a directory's regular files and the directory; 0, or -1. */
int cli_remove_flat_dir(const char *path);

/* The extension of the file name in path, without the dot ("" if none). */
const char *cli_path_ext(const char *path);
/* Splits path into its directory ("." if none) and its base name without
 * the extension. -1 if a part does not fit. */
int cli_path_split(const char *path, char *dir, size_t dir_len, char *stem, size_t stem_len);
/* path made absolute against the working directory; 0, or -1. */
int cli_path_absolute(const char *path, char *out, size_t len);
/* Whether the directory that will hold path exists and is writable, so that
 * a command fails before its work, not after; 0, or -1 after a message. */
int cli_check_output_dir(const char *path);
/* dir/name; -1 if it does not fit. */
int cli_path_join(char *out, size_t len, const char *dir, const char *name);

#endif
