/* jumpcyl: command dispatch. Data goes to stdout, messages to stderr;
 * exit 0 ok, 1 failure, 2 bad usage or input, 3 a fit whose model does not
 * describe the video. */
#include "commands.h"
#include "inputs.h"
#include "batch.h" /* cli_batch_mpi_begin, cli_batch_mpi_end */

#include <gsl/gsl_errno.h>
#include <signal.h>
#include <string.h>

static int cmd_presets(int argc, char **argv)
{
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        puts("Usage: jumpcyl presets\n"
             "The built-in setups, each with a line on what it is; use one with --preset NAME\n"
             "(and see its every value with 'jumpcyl predict --preset NAME --dump-config').");
        return EXIT_OK;
    }
    if (argc > 1) {
        cli_error("presets: takes no arguments (see 'jumpcyl presets --help')");
        return EXIT_USAGE;
    }
    for (int i = 0; jc_preset_name(i); ++i) printf("%-12s %s\n", jc_preset_name(i), jc_preset_description(i));
    return EXIT_OK;
}

static void usage(FILE *out)
{
    fputs("Usage: jumpcyl [COMMAND] [OPTIONS]\n"
          "Where an off-centre-mass cylinder rolling down an incline loses contact and jumps.\n"
          "\n"
          "Commands:\n"
          "  paper      the seed paper's Table 1 recomputed beside the exact model and the\n"
          "             measurement (the default when no command is given)\n"
          "  predict    the paper's model, the exact rolling model and the full model's first\n"
          "             lift-off for one setup\n"
          "  simulate   the full motion: slip, lift-off, flight, landing, further hops\n"
          "  plot       a figure (gnuplot): the paper's criterion, forces, gap, energy, trajectory, overview\n"
          "  animate    a film of the motion (cairo; ffmpeg for .gif and .mp4)\n"
          "  sweep      the full model over a grid of setup values: one CSV row per case\n"
          "  mc         Monte Carlo: how sure the first lift-off is, given the inputs' uncertainties\n"
          "  map        a regime map (gnuplot): the first lift-off over two setup options\n"
          "  design     the values of one option (rod offset, ...) that make it jump at a chosen place\n"
          "  track      what a video tracked with Tracker (.trk or exported table) tells: the centre\n"
          "             (or one recovered from a mark on the rim), the incline, the noise, hops, theta\n"
          "  compare    a tracked video against the model run from the state its frames show\n"
          "  fit        setup values fitted to a tracked video, what it determines, and a verdict\n"
          "  presets    list the built-in setups\n"
          "  params     list the setup parameters: options, units, ranges, presets' values, file keys\n"
          "\n"
          "  jumpcyl COMMAND --help   options of a command\n"
          "  jumpcyl --version        version\n",
          out);
}

/* A batch command: under mpirun (an MPI build) its processes share the cases. */
static int batch_command(int (*cmd)(int, char **), int argc, char **argv)
{
    cli_batch_mpi_begin(&argc, &argv);
    const int rc = cmd(argc - 1, argv + 1);
    cli_batch_mpi_end();
    return rc;
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        char *args[] = {"paper", NULL};
        return cmd_paper(1, args);
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return EXIT_OK;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("jumpcyl %s\n", jc_version());
        return EXIT_OK;
    }
    if (strcmp(cmd, "paper") == 0) return cmd_paper(argc - 1, argv + 1);
    if (strcmp(cmd, "predict") == 0) return cmd_predict(argc - 1, argv + 1);
    if (strcmp(cmd, "simulate") == 0) return cmd_simulate(argc - 1, argv + 1);
    if (strcmp(cmd, "presets") == 0) return cmd_presets(argc - 1, argv + 1);
    if (strcmp(cmd, "params") == 0) return cmd_params(argc - 1, argv + 1);
    if (strcmp(cmd, "plot") == 0) return cmd_plot(argc - 1, argv + 1);
    if (strcmp(cmd, "animate") == 0) return cmd_animate(argc - 1, argv + 1);
    if (strcmp(cmd, "sweep") == 0) return batch_command(cmd_sweep, argc, argv);
    if (strcmp(cmd, "mc") == 0) return batch_command(cmd_mc, argc, argv);
    if (strcmp(cmd, "map") == 0) return batch_command(cmd_map, argc, argv);
    if (strcmp(cmd, "design") == 0) return cmd_design(argc - 1, argv + 1);
    if (strcmp(cmd, "track") == 0) return cmd_track(argc - 1, argv + 1);
    if (strcmp(cmd, "compare") == 0) return cmd_compare(argc - 1, argv + 1);
    if (strcmp(cmd, "fit") == 0) return cmd_fit(argc - 1, argv + 1);
    if (cmd[0] == '-') { /* "jumpcyl --json" = "jumpcyl paper --json" */
        static char paper_name[] = "paper";
        argv[0] = paper_name;
        return cmd_paper(argc, argv);
    }
    cli_error("unknown command '%s' (allowed: paper, predict, simulate, presets, params, plot, animate, sweep, mc, map, design, track, compare, fit; see 'jumpcyl --help')", cmd);
    return EXIT_USAGE;
}

int main(int argc, char **argv)
{
    /* GSL's default handler aborts; the library checks its own preconditions. */
    gsl_set_error_handler_off();
    cli_signals_install(); /* no half-written file, temporary or child stays behind (signals.c) */
    int rc = dispatch(argc, argv);
    const int sig = cli_stop_requested();
    if (sig) {
        /* Whatever the command was doing, it left every target as it was.
         * paper says itself what it kept; a closed pipe needs no words. */
        const int is_paper = argc < 2 || strcmp(argv[1], "paper") == 0 || argv[1][0] == '-';
        const int is_batch = argc >= 2 && (strcmp(argv[1], "sweep") == 0 || strcmp(argv[1], "mc") == 0 ||
                                           strcmp(argv[1], "map") == 0);
        if (!is_paper && !is_batch && sig != SIGPIPE)
            cli_error("stopped by %s; no output file was written or changed", cli_signal_name(sig));
        fclose(stdout);
        return cli_stop_status();
    }
    /* Help or results that did not reach standard output (a full disk, a
     * closed descriptor) are a failure, not a success. */
    if (rc != EXIT_OK) fclose(stdout); /* the command has said what went wrong */
    else rc = cli_stdout_close();
    return rc;
}
