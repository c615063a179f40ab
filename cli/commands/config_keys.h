/* The experiment-file format (docs/config.md): its sections and the keys
 * that are one number of the setup, with the unit each is written in.
 * Shared by the reader (config.c, with inih) and the writer
 * (config_write.c, which holds the tables); the WebAssembly build (web/)
 * compiles only the writer, so the page needs no inih. Private to those
 * two files. */
#ifndef JC_CLI_CONFIG_KEYS_H
#define JC_CLI_CONFIG_KEYS_H

#include "cli.h"

#include <stddef.h>

enum { SEC_BODY, SEC_INCLINE, SEC_CONTACT, SEC_START, SEC_AIR, SEC_PAPER, SEC_PART_FIRST };
#define SECTION_COUNT (SEC_PART_FIRST + JC_MAX_PARTS)
#define SEC_NONE (-1)
extern const char *const cli_config_section_names[SEC_PART_FIRST];

/* The keys that are one number of the setup. */
typedef struct {
    int section;
    const char *key;
    cli_Quantity q;
    const char *unit; /* written by cli_config_write; "" for a plain number */
    size_t offset;    /* of the double in jc_Setup */
} cli_ConfigScalar;

#define CLI_CONFIG_SCALAR_COUNT 16
extern const cli_ConfigScalar cli_config_scalars[CLI_CONFIG_SCALAR_COUNT];

#endif
