/* Fuzz target: the command line. The input is a command selector byte and
 * NUL-separated arguments; they go through the shared option parser
 * (cli_parse_args), the setup and simulator option builders, and each one
 * through the unit parser for every quantity.
 *
 * Invariants: a parsed quantity is finite and not subnormal, parses the
 * same way twice, and its shortest decimal form reads back to the same
 * double; a built setup passes jc_setup_validate; built simulator options
 * pass jc_sim_options_validate; a rejected token leaves a message. */
#include "fuzz.h"

#include "inputs.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define MAX_ARGS 64
#define MAX_INPUT 4096

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    /* --dump-config prints whole setups: of no interest here, and slow. */
    if (!freopen("/dev/null", "w", stdout)) return 0;
    return 0;
}

static void check_quantity(const char *token, cli_Quantity q)
{
    double v = 0.0, again = 0.0;
    char err[512] = "", err2[512] = "";
    const int st = cli_parse_quantity(token, q, &v, err, sizeof err);
    FUZZ_CHECK(st == cli_parse_quantity(token, q, &again, err2, sizeof err2));
    if (st != 0) {
        FUZZ_CHECK(st == -1 && err[0] != '\0');
        return;
    }
    FUZZ_CHECK(isfinite(v) && (v == 0.0 || fabs(v) >= DBL_MIN));
    FUZZ_CHECK(memcmp(&v, &again, sizeof v) == 0);
    /* SI values written the way --dump-config writes them read back exactly. */
    char si[64];
    snprintf(si, sizeof si, "%.17g%s", v, q == Q_ANGLE ? "rad" : "");
    double back = 0.0;
    FUZZ_CHECK(cli_parse_quantity(si, q, &back, err, sizeof err) == 0);
    FUZZ_CHECK(memcmp(&v, &back, sizeof v) == 0);
}

/* --config reads a file: the config target covers that format, and a
 * path chosen by the fuzzer could name a FIFO or a terminal and block. */
static int names_config(const char *arg)
{
    const size_t len = strcspn(arg, "=");
    return len >= 3 && len <= 8 && strncmp(arg, "--config", len) == 0;
}

/* The command's own options, as the real commands define them. */
static const struct option own[] = {{"json", no_argument, 0, 'j'},
                                    {"csv", required_argument, 0, 'c'},
                                    {"help", no_argument, 0, 'h'}};

static int own_take(int opt, const char *arg, void *ctx)
{
    (void)arg;
    int *taken = ctx;
    if (opt == 'h') return EXIT_OK; /* help printed: the command ends */
    if (opt == 'j' || opt == 'c') {
        ++*taken;
        return CLI_GO_ON;
    }
    return EXIT_USAGE;
}

static void check_command_line(int argc, char **argv, int simulate)
{
    cli_SetupArgs sa;
    cli_SimArgs sim;
    int taken = 0;
    const int st = cli_parse_args(argc, argv, own, simulate ? 3 : 2, own_take, &taken, &sa, simulate ? &sim : NULL);
    FUZZ_CHECK(st == CLI_GO_ON || st == EXIT_OK || st == EXIT_USAGE || st == EXIT_FAIL);
    if (st != CLI_GO_ON) return;
    char err[512];
    jc_Setup setup;
    if (cli_setup_build(&sa, &setup, err, sizeof err) == 0) FUZZ_CHECK(jc_setup_validate(&setup, err, sizeof err) == JC_OK);
    else FUZZ_CHECK(err[0] != '\0');
    jc_SimOptions opts;
    if (simulate && cli_sim_build(&sim, &opts, err, sizeof err) == 0)
        FUZZ_CHECK(jc_sim_options_validate(&opts, err, sizeof err) == JC_OK);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > MAX_INPUT) return 0;
    static const char *const commands[] = {"simulate", "predict", "paper"};
    char *text = malloc(size);
    if (!text) return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    char *argv[MAX_ARGS + 2];
    int argc = 0, skip = 0;
    argv[argc++] = (char *)commands[data[0] % 3];
    for (char *p = text; p < text + size - 1 && argc < MAX_ARGS; p += strlen(p) + 1) {
        argv[argc++] = p;
        skip |= names_config(p);
    }
    argv[argc] = NULL;
    static const cli_Quantity qs[] = {Q_LENGTH, Q_MASS, Q_ANGLE, Q_ANGULAR_SPEED, Q_ACCELERATION,
                                      Q_NUMBER, Q_TIME, Q_DENSITY, Q_SPIN_DRAG};
    for (int i = 1; i < argc; ++i)
        for (size_t k = 0; k < sizeof qs / sizeof qs[0]; ++k) check_quantity(argv[i], qs[k]);
    if (!skip) check_command_line(argc, argv, data[0] % 3 == 0);
    free(text);
    return 0;
}
