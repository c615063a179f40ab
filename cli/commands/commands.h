/* The tool's commands: one entry point per command, called by cli/main.c's
 * dispatch. Each takes the command's arguments (argv[0] the command's name)
 * and returns the exit status (process.h). */
#ifndef JUMPCYL_COMMANDS_H
#define JUMPCYL_COMMANDS_H

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

#endif
