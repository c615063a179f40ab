/* What the tool writes (cli/outputs/): the setup line and JSON helpers
 * (report.c), JSON text with exact numbers (json_text.c), `simulate
 * --json` (sim_json.c), the simulation as commands run it, stopped by a
 * signal (record.c), every output file written whole or not at all
 * (safe_output.c), and progress on long work (progress.c).
 * Below it only the process layer (process.h) and the library. */
#ifndef JUMPCYL_OUTPUTS_H
#define JUMPCYL_OUTPUTS_H

#include "process.h"

#include <jumpcyl/jumpcyl.h>

#include <stddef.h>
#include <stdio.h>

/* ---- report.c ---- */

#define CLI_PI 3.14159265358979323846
double cli_deg(double rad);
/* v as printf shows it with that many decimals, without a negative zero:
 * values that round to zero become +0. */
double cli_shown(double v, int decimals);
void cli_print_setup(FILE *out, const jc_Model *m, int show_incline);
/* A word as the shell reads it: single-quoted unless plainly safe; control
 * characters shown as '?', so that it stays on one line (and a comment line
 * of a script never ends in a backslash). */
void cli_shell_word(FILE *out, const char *s);
/* A kept script's name as gnuplot is to be given it: gnuplot reads a file
 * argument that begins with '<' or '|' as a shell command to run, and one
 * that begins with '-' as an option, so such a name gets "./" in front. */
const char *cli_gnuplot_load_prefix(const char *path);

/* JSON helpers (cJSON). */
struct cJSON;
/* {"theta": rad, "x": m, "omega": rad/s, "normal": N, "friction": N, "grazing": bool} or null */
struct cJSON *cli_json_crossing(const jc_RollingCrossing *c);
/* The setup: the body, then every parameter with a json_key (jc_ParamInfo). */
struct cJSON *cli_json_setup(const jc_Model *m);
/* The parameter table, as `jumpcyl params --json` prints it and the web
 * page reads it: {"presets": [...], "params": [{"name", "quantity", "unit",
 * "min", "max", ..., "defaults": {preset: SI or null}}, ...]}. */
struct cJSON *cli_json_params(void);
struct cJSON *cli_json_event(const jc_Event *e);
struct cJSON *cli_json_energy(const jc_EnergyReport *e);
/* Prints the document on stdout (cli_json_text) and frees it; EXIT_FAIL if
 * that fails (after a message, but none for a closed pipe). */
int cli_json_print(struct cJSON *doc);

/* ---- json_text.c: JSON text whose numbers read back bit for bit ---- */

#define CLI_JSON_NUMBER_MAX 32
/* v as JSON: the shortest of its %.15g, %.16g and %.17g forms that reads
 * back to v bit for bit (-0 as "-0"; of equal lengths the fewer digits),
 * with '.' for the decimal point; "null" for NaN and infinities (JSON has
 * none), as cJSON writes them. Returns the length. */
int cli_json_number(double v, char out[CLI_JSON_NUMBER_MAX]);
/* doc printed by cJSON, formatted (cJSON_Print) or not
 * (cJSON_PrintUnformatted), with every number as cli_json_number writes
 * it: the number nodes of doc become raw nodes holding that text, so print
 * doc once, then delete it. Every JSON document the tool and the page
 * write is printed here. NULL for a NULL doc or when memory ran out; free
 * the text with free. */
char *cli_json_text(struct cJSON *doc, int formatted);

/* ---- sim_json.c: `simulate --json`, whole or streamed (the same text) ---- */

struct cJSON *cli_sim_json_doc(const jc_Model *m, const jc_Run *run);
int cli_sim_json_begin(FILE *out, const jc_Model *m); /* 0, or -1 (a write or memory failed) */
int cli_sim_json_event(FILE *out, const jc_Event *e, int index);
int cli_sim_json_end(FILE *out, const jc_Model *m, const jc_Run *run, const jc_RunSummary *sum);

/* ---- record.c: the simulation, stopped by a signal; library statuses as exit statuses ---- */

/* What a library call was given, which decides whose fault its failure is. */
typedef enum {
    CLI_INPUTS_GIVEN,   /* the user's values as given: JC_EINVAL is bad input (EXIT_USAGE), the rest EXIT_FAIL */
    CLI_INPUTS_CHECKED, /* values already checked, or made by the tool: every failure is EXIT_FAIL */
    CLI_INPUTS_VIDEO    /* a tracked video: one the library cannot read or follow is bad input (EXIT_USAGE) */
} cli_Inputs;
/* The exit status of a library status (JC_OK, JC_E*): the one place where
 * they become exit statuses. JC_OK is EXIT_OK; JC_ESTOPPED after a stop
 * signal is cli_stop_status(); any other failure as inputs says. Prints
 * nothing: the caller has said what failed. */
int cli_exit_status(int jc_status, cli_Inputs inputs);

/* Runs the full model into run's arrays; prints the library's message on
 * failure (nothing for a stop by a signal). Returns a status (JC_OK, ...,
 * JC_ESTOPPED after a signal). The caller frees the run. */
int cli_simulate(const jc_Model *m, const jc_SimOptions *o, jc_Run *run, const char *cmd);
/* The same without keeping events or samples: for the run's end and counts. */
int cli_simulate_probe(const jc_Model *m, const jc_SimOptions *o, jc_Run *run, const char *cmd);
/* Runs the full model into a caller's recorder; a signal stops it. No
 * message for JC_ESTOPPED (a signal, or the recorder's own stop). */
int cli_simulate_stream(const jc_Model *m, const jc_SimOptions *o, const jc_Recorder *rec, jc_Run *run,
                        const char *cmd);

/* ---- safe_output.c: files written whole or not at all ---- */

/* Every file the tool hands to the user (figure, film, CSV, kept script)
 * goes through here: it is made under a private temporary name beside its
 * target (or copied there from the scratch directory where gnuplot or
 * ffmpeg made it), checked for completeness, fsynced, and only then renamed
 * over the target, whose directory is fsynced too. Any failure, and any
 * signal before the rename, leaves the target as it was and no temporary
 * file behind. "-" means standard output (no rename: written in place). */

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
/* An output that cannot go to standard output (a figure, a film, a
 * directory of frames): "-" refused with "CMD: --OPTION -: WHAT cannot go
 * to standard output; ..." (-1, EXIT_USAGE's case); 0 for any other name. */
int cli_output_file_only(const char *cmd, const char *option, const char *target, const char *what);
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

/* A JSON document into target, "-" being standard output (cli_json_print),
 * a file written whole or not at all otherwise; frees it. EXIT_OK, or
 * EXIT_FAIL after a message. */
int cli_json_write(struct cJSON *doc, const char *target);

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
 * message (a full disk, a closed descriptor); quietly the stop status when
 * its reader went away (cli_pipe_closed). */
int cli_stdout_close(void);
/* Flushes standard output: EXIT_OK, or EXIT_FAIL after a message; quietly
 * the stop status when its reader went away. */
int cli_stdout_finish(void);

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
/* cli_progress_update(progress, 0, 0), as a cli_WaitTick (process.h) for
 * the wait on a child program. */
void cli_progress_tick(void *progress);

#endif
