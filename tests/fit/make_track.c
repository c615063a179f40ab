/* A synthetic tracked video as Tracker exports it (a data table, axes laid
 * along the incline): the paper's cylinder on 30° with mu_k 0.4, filmed at
 * FPS and tracked with SIGMA metres of noise (cli/track/synthetic.c). For
 * the tests and the examples of docs/tracker.md.
 *
 * Usage: fit_make_track OUT [SIGMA_M [FPS [SEED]]]   (defaults 1e-3, 60, 1) */
#include "track_fit.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2 || argc > 5) {
        fprintf(stderr, "usage: %s OUT [SIGMA_M [FPS [SEED]]]\n", argv[0]);
        return 2;
    }
    jc_Setup s = jc_paper_setup();
    s.mu_kinetic = 0.4;
    const double mark = 0.055;
    cli_SynthOptions o = {argc > 3 ? atof(argv[3]) : 60.0, argc > 2 ? atof(argv[2]) : 1e-3, 1.5, mark, 0.0,
                          argc > 4 ? strtoull(argv[4], NULL, 10) : 1u, 0};
    cli_Track t;
    char err[256];
    if (cli_track_synthesize(&s, &o, &t, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        cli_track_free(&t);
        return 1;
    }
    /* Tracker's export of two point masses: names above their first column. */
    fprintf(f, "#multi:\ncentre\t\t\tmass\t\nt\tx\ty\tx\ty\n");
    for (long i = 0; i < t.n; ++i)
        fprintf(f, "%.6f\t%.7g\t%.7g\t%.7g\t%.7g\n", t.t_s[i], t.x_m[i], t.y_m[i], t.x_m[i] + mark * sin(t.theta_rad[i]),
                t.y_m[i] + mark * cos(t.theta_rad[i]));
    cli_track_free(&t);
    return fclose(f) == 0 ? 0 : 1;
}
