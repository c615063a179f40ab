/* The tool's commands: one entry point per command, called by cli/main.c's
 * dispatch. Each takes the command's arguments (argv[0] the command's name)
 * and returns the exit status (process.h). Also what the track commands
 * share (track_input.c). */
#ifndef JUMPCYL_COMMANDS_H
#define JUMPCYL_COMMANDS_H

#include "figures.h"
#include "inputs.h"

#include <jumpcyl/track.h>

int cmd_paper(int argc, char **argv);    /* paper.c: Table 1 */
int cmd_predict(int argc, char **argv);  /* predict.c: the criterion's prediction */
int cmd_simulate(int argc, char **argv); /* simulate.c: one run */
int cmd_plot(int argc, char **argv);     /* plot.c: figures with gnuplot */
int cmd_animate(int argc, char **argv);  /* animate.c: films with cairo and ffmpeg */
int cmd_sweep(int argc, char **argv);    /* sweep.c: runs over a parameter's values (batch/) */
int cmd_mc(int argc, char **argv);       /* mc.c: Monte Carlo over uncertain values (batch/) */
int cmd_map(int argc, char **argv);      /* map.c: outcomes over two parameters (batch/) */
int cmd_design(int argc, char **argv);   /* design.c: parameters for a wanted outcome (design/) */
int cmd_track(int argc, char **argv);    /* track.c: a video's tracked points (Tracker) */
int cmd_compare(int argc, char **argv);  /* compare.c: a tracked video against the model */
int cmd_fit(int argc, char **argv);      /* fit.c: setup values fitted to a tracked video */
int cmd_params(int argc, char **argv);   /* params.c: the parameter table */

/* paper.c: EXIT_OK when the setup's body is the paper's cylinder, the only body
 * whose jump sites the paper measured (jc_paper_body_is); otherwise
 * EXIT_USAGE after a one-line message naming the option that made another
 * body and the command to use for it instead. what: "" or the kind of
 * output, "--what paper-uncertainty: ". */
int cli_paper_body_only(const char *cmd, const char *what, const char *instead, const cli_SetupArgs *sa,
                        const jc_Setup *s);

/* ---- track_input.c: what track, compare and fit share on the command
 * line: the track file and how to read it (names, axes, the incline given
 * or the video's, the hop threshold), the time window, the mark's angle,
 * the figure's file ---- */

enum {
    CLI_TRACK_OPT_TRACK = 2000, CLI_TRACK_OPT_CENTRE, CLI_TRACK_OPT_MASS, CLI_TRACK_OPT_AXES, CLI_TRACK_OPT_FROM,
    CLI_TRACK_OPT_TO, CLI_TRACK_OPT_OUTPUT, CLI_TRACK_OPT_SETUP_START, CLI_TRACK_OPT_MARK_ANGLE,
    CLI_TRACK_OPT_HOP_SIGMAS, CLI_TRACK_OPT_FIT_TILT
};
/* The options that read a track (track, compare and fit). */
#define CLI_TRACK_READ_OPTIONS                                                                                  \
    {"centre", required_argument, 0, CLI_TRACK_OPT_CENTRE}, {"mass", required_argument, 0, CLI_TRACK_OPT_MASS},  \
        {"axes", required_argument, 0, CLI_TRACK_OPT_AXES},                                                     \
        {"hop-sigmas", required_argument, 0, CLI_TRACK_OPT_HOP_SIGMAS},                                         \
        {"fit-tilt", no_argument, 0, CLI_TRACK_OPT_FIT_TILT}
/* ... and those of compare and fit. */
#define CLI_TRACK_ARG_OPTIONS                                                                                   \
    CLI_TRACK_READ_OPTIONS, {"track", required_argument, 0, CLI_TRACK_OPT_TRACK},                              \
        {"from", required_argument, 0, CLI_TRACK_OPT_FROM}, {"to", required_argument, 0, CLI_TRACK_OPT_TO},     \
        {"output", required_argument, 0, CLI_TRACK_OPT_OUTPUT},                                                 \
        {"from-setup-start", no_argument, 0, CLI_TRACK_OPT_SETUP_START},                                        \
        {"mark-angle", required_argument, 0, CLI_TRACK_OPT_MARK_ANGLE}

typedef struct {
    const char *track, *centre, *mass, *axes, *from, *to, *output, *mark_angle, *hop_sigmas;
    int from_setup_start, fit_tilt;
    /* checked values */
    double from_s, to_s, mark_angle_rad;
    double hop_sigmas_k; /* --hop-sigmas's K, when given */
} cli_TrackArgs;

/* A command's take for these options: CLI_GO_ON when it took the option,
 * EXIT_USAGE after a message (or for an option that is not one of these). */
int cli_track_args_take(const char *cmd, cli_TrackArgs *a, int opt, const char *arg);
/* The help of the reading options; with window 1, those of compare and fit too. */
void cli_track_args_help(int window);
/* Checks the reading options (--axes, --hop-sigmas) and keeps their values;
 * EXIT_OK or EXIT_USAGE after a one-line message. */
int cli_track_args_check_reading(const char *cmd, cli_TrackArgs *a);
/* Checks the options before any work (the reading options, the window, the
 * mark's angle, the figure's name and target, gnuplot); EXIT_OK or the
 * exit status after a one-line message. */
int cli_track_args_check(const char *cmd, cli_TrackArgs *a);
/* Reads the track for the setup's radius and g, with the incline given
 * (--incline, or an experiment file's) or the video's; a's reading options
 * checked first (either check above). EXIT_OK, or the exit status after a
 * one-line message (EXIT_USAGE for a file that cannot be read or an
 * incline the video refuses). */
int cli_track_args_load(const char *cmd, const char *path, const cli_TrackArgs *a, const cli_SetupArgs *sa,
                        const jc_Setup *setup, jc_Track *t);
/* As cli_track_args_load, then what compare and fit need (the centre, the
 * incline), refused with exit 2 and the reason when missing; the setup
 * takes the track's incline. */
int cli_track_args_load_for_model(const char *cmd, const cli_TrackArgs *a, const cli_SetupArgs *sa, jc_Setup *setup,
                                  jc_Track *t);
/* How the reports name the centre's source, by its CLI_CENTRE_* value
 * (track's report and JSON, compare's and fit's head). */
extern const char *const cli_track_centre_sources[JC_TRACK_CENTRE_FROM_MARK + 1];
void cli_track_print_head(const char *file, const jc_Track *t, long first, long count);
/* The frames before the free motion, when a push was found there (nothing otherwise). */
void cli_track_print_launch(const jc_Track *t, const jc_TrackLaunch *L);
/* The model's path every quarter frame from start to t_end_s (for the
 * figure), in the video's frame placed by frame (NULL: none); 0, or -1
 * (the arrays are then to be freed all the same). */
int cli_track_fine_path(const jc_Setup *setup, const jc_Track *t, const jc_State *start,
                        const jc_TrackFitFrame *frame, const jc_SimOptions *o, double t_end_s, double **pt,
                        double **px, double **py, long *n);
/* The last step of compare's and fit's figure: the caller fills f's frames,
 * model values (the mark's angle, not G's), mark radius, sigma, threshold
 * and title; this sets the radius, samples the model's fine path from start
 * to the last frame shown (in the video's frame when frame is not NULL),
 * draws the figure to out and frees the path. EXIT_OK, or an exit status
 * after a message: "CMD: no_path" when the path could not be made. */
int cli_track_figure_draw(const char *cmd, const char *no_path, cli_TrackFigure *f, const jc_Setup *setup,
                          const jc_State *start, const jc_TrackFitFrame *frame, const jc_SimOptions *o, const char *out,
                          int argc, char **argv);

#endif
