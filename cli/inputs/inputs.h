/* The header of inputs/: what a command is given, read into the library's
 * types: unit parsing (units.c), experiment files (config.c, config_write.c),
 * the setup and simulation options (setup_args.c) and a command's arguments
 * (options.c). Below the commands and the batch jobs, which both build their
 * inputs here. The tool is a thin client of the library. */
#ifndef JUMPCYL_INPUTS_H
#define JUMPCYL_INPUTS_H

#include "outputs.h" /* and process.h: exit statuses, cli_error */

#include <jumpcyl/jumpcyl.h>

#include <getopt.h>
#include <stdint.h>
#include <stdio.h>

/* ---- units.c: the library's numbers with units (jc_quantity_parse) ---- */
typedef jc_Quantity cli_Quantity;
#define Q_LENGTH JC_Q_LENGTH               /* m; plain number = m */
#define Q_MASS JC_Q_MASS                   /* kg; plain number = kg */
#define Q_ANGLE JC_Q_ANGLE                 /* rad; plain number = DEGREES */
#define Q_ANGULAR_SPEED JC_Q_ANGULAR_SPEED /* rad/s; plain number = rad/s */
#define Q_ACCELERATION JC_Q_ACCELERATION   /* m/s2 */
#define Q_NUMBER JC_Q_NUMBER               /* dimensionless, no unit */
#define Q_TIME JC_Q_TIME                   /* s; plain number = s */
#define Q_DENSITY JC_Q_DENSITY             /* kg/m3; plain number = kg/m3 */
#define Q_SPIN_DRAG JC_Q_SPIN_DRAG         /* N m s2 (= kg m2); plain number = N m s2 */

/* Parses a whole token "number[unit]" into SI (jc_quantity_parse). 0 on
 * success; otherwise -1 and a one-line message naming the token and what is
 * allowed. */
int cli_parse_quantity(const char *text, cli_Quantity q, double *out, char *err, size_t err_len);
const char *cli_units_allowed(cli_Quantity q);

/* ---- config.c: experiment files (docs/config.md) ---- */
/* Reads an experiment file over *setup, which holds the values the file
 * starts from. 0, or -1 with a one-line message "FILE:LINE: ..." (a file
 * that cannot be read, too large, bad syntax, an unknown or repeated section
 * or key, a bad value). The setup is not validated here. */
int cli_config_load(const char *path, jc_Setup *setup, char *err, size_t err_len);
/* The same for text in memory; name stands for the file in messages. */
int cli_config_parse(const char *name, const char *text, size_t len, jc_Setup *setup, char *err, size_t err_len);
/* Writes a setup in that format: SI values with their units, each number in
 * the shortest form that reads back to the same double. 0, or -1 if out
 * reported an error. */
int cli_config_write(FILE *out, const jc_Setup *setup);
/* The format's sections and keys are the parameter table's (jc_ParamInfo
 * section and key), sections in the order they first appear there,
 * [part.1] .. [part.N] after [body]. The reader and the writer share them;
 * config_write.c holds them, as the WebAssembly build (web/) compiles only
 * the writer, so that the page needs no inih. */
#define CLI_CONFIG_SECTION_MAX 16 /* named sections at most (the table's, [part.N] aside) */
/* The named sections in file order into names; returns how many. The
 * first is [body], which the [part.N] sections follow. */
int cli_config_sections(const char *names[CLI_CONFIG_SECTION_MAX]);
/* Whether the parameter is written by the writer, as a key of its own:
 * not a shortcut for others (mu, disc-mass: the file holds mu_s and mu_k,
 * the parts). */
int cli_config_written(const jc_ParamInfo *in);

/* ---- setup_args.c (the options as text, built without files) and options.c (argv, files) ---- */
/* The setup options: their own (--preset, --part, --config, --dump-config),
 * then --NAME for every parameter of the library's table (jc_param_info),
 * getopt values CLI_SETUP_OPT_BASE + CLI_OPT_PARAMS + id. */
#define CLI_SETUP_OPT_BASE 1000
enum { CLI_OPT_PRESET, CLI_OPT_PART, CLI_OPT_CONFIG, CLI_OPT_DUMP_CONFIG, CLI_OPT_PARAMS };
#define CLI_SETUP_OPTION_MAX (CLI_OPT_PARAMS + JC_PARAM_MAX)
/* The setup options' getopt table into dst (room for cap entries, at least
 * CLI_SETUP_OPTION_MAX); returns how many. */
int cli_setup_option_table(struct option *dst, int cap);

/* Setup options, collected first and applied in a fixed order (preset,
 * parts, then single values) so that their order on the line does not matter. */
typedef struct {
    const char *preset;
    const char *config;
    int dump_config;
    int part_count;
    const char *part_text[JC_MAX_PARTS];
    const char *value[JC_PARAM_MAX]; /* by parameter id (jc_param_find), NULL if absent */
} cli_SetupArgs;

/* The single-valued options as values, each read once from its text: what
 * the cases of a batch job set over (cli_case_setup), no text read per case.
 * The library's jc_ParamValues (parts_given: --part bodies, whose radii
 * --radius leaves as given). */
#include <jumpcyl/study.h>
typedef jc_ParamValues cli_SetupValues;

/* What cli_setup_take and cli_sim_take did with an option. They print
 * nothing (the web page shares them): a refusal's message is in err. */
typedef enum {
    CLI_OPTION_REFUSED = -1, /* one of theirs, refused: repeated, or too many parts */
    CLI_OPTION_NOT_OURS = 0, /* not one of theirs: the caller's to take */
    CLI_OPTION_TAKEN = 1     /* recorded */
} cli_OptionTake;
/* A setup option (opt: its getopt val) recorded. */
cli_OptionTake cli_setup_take(cli_SetupArgs *args, int opt, const char *optarg_text, char *err, size_t err_len);
/* The setup's builders below print nothing: each returns 0, or -1 with a
 * one-line message in err. */
/* Builds and validates the setup: cli_setup_base, then cli_setup_apply
 * (options.c). */
int cli_setup_build(const cli_SetupArgs *args, jc_Setup *out, char *err, size_t err_len);
/* The preset, the experiment file and the parts: where the single-valued
 * options start from (made once for the many cases of a sweep; options.c). */
int cli_setup_base(const cli_SetupArgs *args, jc_Setup *out, char *err, size_t err_len);
/* The preset's setup (the paper's without --preset), and the --part bodies
 * over a setup: cli_setup_base's steps before and after the file. */
int cli_setup_preset(const cli_SetupArgs *args, jc_Setup *out, char *err, size_t err_len);
int cli_setup_parts(const cli_SetupArgs *args, jc_Setup *s, char *err, size_t err_len);
/* cli_setup_build without an experiment file, for a caller that reads none
 * (the web page): the preset, the parts, the single values and the check;
 * --config is refused. */
int cli_setup_from_options(const cli_SetupArgs *args, jc_Setup *out, char *err, size_t err_len);
/* The single-valued options over a base setup, then the setup's check:
 * cli_setup_values, then cli_setup_apply_values. */
int cli_setup_apply(const cli_SetupArgs *args, jc_Setup *s, char *err, size_t err_len);
/* The single-valued options' texts read into values (jc_param_parse). 0, or
 * -1 with "--NAME: message". */
int cli_setup_values(const cli_SetupArgs *args, cli_SetupValues *out, char *err, size_t err_len);
/* The values over a base setup in the table's order (the body's first, the
 * printed paper d dropped when the body changes), then the setup's check
 * (jc_setup_validate). 0, or -1 with a one-line message. */
int cli_setup_apply_values(const cli_SetupValues *v, jc_Setup *s, char *err, size_t err_len);
/* Whether a setup option was given, by long name ("incline", "config", "part"). */
int cli_setup_given(const cli_SetupArgs *args, const char *long_name);
/* Help text for the setup options, from the parameter table. */
void cli_setup_help(FILE *out);

/* Builds an option table: command options followed by the setup options. */
void cli_merge_options(struct option *dst, int dst_cap, const struct option *cmd, int cmd_count);

/* The answer of a step that reads the command line (an option's take, the
 * parse) when the command goes on. Any other answer is the exit status the
 * command returns at once: EXIT_OK after --help or --dump-config printed
 * what was asked, EXIT_USAGE after a one-line message. Not an exit status
 * (they are >= 0); docs/architecture.md, "Return values". */
#define CLI_GO_ON (-1)

/* Parses a command's arguments: its own options (handled by own_take: for
 * option opt with its value arg, CLI_GO_ON when it took it, or the exit
 * status) and the setup options. CLI_GO_ON, or the exit status (EXIT_OK
 * when --dump-config printed the setup). Commands call it through
 * cli_command_parse. */
typedef int (*cli_own_take_fn)(int opt, const char *arg, void *ctx);
struct cli_SimArgs_s;
int cli_parse_args(int argc, char **argv, const struct option *own, int own_count,
                   cli_own_take_fn own_take, void *ctx, cli_SetupArgs *setup_args,
                   struct cli_SimArgs_s *sim_args);

/* A command's own options: the table (with {"help", no_argument, 0, 'h'}),
 * take for each of them but --help (CLI_GO_ON, or the exit status), and the
 * command's part of the help. */
typedef struct {
    const struct option *own;
    int own_count;
    cli_own_take_fn take;
    void (*help)(void);
} cli_Command;
/* cli_parse_args for a command: --help prints its help, then the shared
 * options' (the simulation options' too when sim_args is not NULL).
 * CLI_GO_ON, or the exit status: EXIT_OK after --help or --dump-config. */
int cli_command_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, cli_SetupArgs *setup_args,
                      struct cli_SimArgs_s *sim_args);
/* Output options. Every option that names an output file takes FILE, and
 * "-" is standard output (docs/cli.md, "Output files"); an output that
 * cannot go there (a figure, a film) refuses "-". --json alone, followed by
 * another option or by nothing, is --json - (what it was before it took a
 * FILE): such an option is optional_argument in the getopt table, and the
 * parse hands its take "-" or the FILE that follows ("--json out.json",
 * "--json=out.json"). A word that starts with '-' is taken for an option,
 * not a FILE: "--json=-x.json" or "--json ./-x.json". */
#define CLI_JSON_OPTION(val) {"json", optional_argument, 0, (val)}
/* Whether next, the word after such an option (NULL: none), is its FILE. */
int cli_output_value_follows(const char *next);
/* The value of such an option getopt_long has just returned: optarg
 * ("--json=FILE"), the FILE that follows (optind moves past it), or "-". */
const char *cli_output_optarg(int argc, char **argv);
/* cli_command_parse for a command whose one own option is --json (paper,
 * predict); *json is set to its FILE ("-": standard output) when it is
 * given. CLI_GO_ON, or the exit status. */
int cli_json_command_parse(int argc, char **argv, void (*help)(void), const char **json, cli_SetupArgs *setup_args);

/* Simulator options (--t-max, --sample-dt, ...), for commands that simulate. */
#define CLI_SIM_OPTION_COUNT 7
#define CLI_SIM_OPT_BASE 1100
extern const struct option cli_sim_options[CLI_SIM_OPTION_COUNT];
typedef struct cli_SimArgs_s {
    const char *value[CLI_SIM_OPTION_COUNT];
} cli_SimArgs;
/* A simulation option recorded, as cli_setup_take. */
cli_OptionTake cli_sim_take(cli_SimArgs *args, int opt, const char *text, char *err, size_t err_len);
/* The simulation options built and checked: 0, or -1 with a one-line message in err. */
int cli_sim_build(const cli_SimArgs *args, jc_SimOptions *out, char *err, size_t err_len);
/* Whether a simulation option (by long name) was given. */
int cli_sim_given(const cli_SimArgs *args, const char *long_name);
/* A command's inputs, built and checked: the setup, the simulation options
 * (when sim_args is not NULL) and the model (when model is not NULL). On a
 * bad value prints "CMD: message" and returns the exit status (EXIT_USAGE
 * for a value out of range); EXIT_OK when all is well. */
int cli_build_inputs(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_Setup *setup,
                     jc_SimOptions *sim, jc_Model *model);
/* cli_build_inputs for a command that needs no jc_Setup of its own (the
 * model holds it): the model, and the simulation options when sim_args and
 * sim are not NULL. The exit status, as cli_build_inputs. */
int cli_build_model(const char *cmd, const cli_SetupArgs *sa, const cli_SimArgs *sim_args, jc_SimOptions *sim,
                    jc_Model *model);
/* The shared inputs of a command that runs one simulation (simulate, plot,
 * animate): the setup and simulation options as given, then the model and
 * the simulation options built from them. */
typedef struct {
    cli_SetupArgs args;
    cli_SimArgs sim_args;
    jc_SimOptions sim;
    jc_Model model;
} cli_RunInputs;
/* cli_command_parse into in's options: CLI_GO_ON, or the exit status. */
int cli_run_inputs_parse(int argc, char **argv, const cli_Command *cmd, void *ctx, cli_RunInputs *in);
/* cli_build_model from in's options into in's model and simulation
 * options: EXIT_OK, or the exit status after a message. */
int cli_run_inputs_build(const char *cmd, cli_RunInputs *in);
/* A single-valued option's take: stores arg in *slot and returns
 * CLI_GO_ON, or refuses a second value (EXIT_USAGE after a message). */
int cli_take_once(const char *cmd, const char **slot, const char *name, const char *arg);
/* A --seed value: a whole number from 0 to 2^64 - 1, no sign (mc, fit).
 * EXIT_OK, or EXIT_USAGE after a one-line message. */
int cli_parse_seed(const char *cmd, const char *text, uint64_t *seed);
void cli_sim_help(FILE *out);
/* The help of the shared options: simulation options (with_sim) and setup options. */
void cli_options_help(FILE *out, int with_sim);

#endif
