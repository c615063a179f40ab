/* The experiment-file format (docs/config.md): its sections and keys are
 * the parameter table's (jc_ParamInfo section and key), sections in the
 * order they first appear there, [part.1] .. [part.N] after [body].
 * Shared by the reader (config.c, with inih) and the writer
 * (config_write.c, which holds the list); the WebAssembly build (web/)
 * compiles only the writer, so the page needs no inih. Private to those
 * two files. */
#ifndef JC_CLI_CONFIG_KEYS_H
#define JC_CLI_CONFIG_KEYS_H

#include "inputs.h"

#include <stddef.h>

/* Named sections at most (the table's, [part.N] aside). */
#define CLI_CONFIG_SECTION_MAX 16

/* The named sections in file order into names; returns how many. The
 * first is [body], which the [part.N] sections follow. */
int cli_config_sections(const char *names[CLI_CONFIG_SECTION_MAX]);

/* Whether the parameter is written by the writer, as a key of its own:
 * not a shortcut for others (mu, disc-mass: the file holds mu_s and mu_k,
 * the parts). */
int cli_config_written(const jc_ParamInfo *in);

#endif
