/* The sample experiments of examples/tracker/ (docs/tracker.md), made from
 * known runs and filmed as a phone would at 30 frames/s, tracked with
 * 1.5 mm of noise:
 *
 *   incline.trk, incline.txt  the paper's cylinder on 30 deg (mu_s 0.5, mu_k
 *                             0.4, e 0.3), the axle and the rod tracked; the
 *                             .trk as Tracker saves it (camera rolled 1.5 deg,
 *                             its axes set level), the table as it exports it
 *   floor.trk, floor.txt      the preset hoop on a floor (a 10 g hoop, 100 g
 *                             on its rim, rolled at 8 rad/s with the mass on
 *                             top: it slides, hops 81 mm and rocks), the axle
 *                             and the mass tracked
 *   floor-led.txt             a loaded ring (100 g hoop, 100 g at its rim)
 *                             rolled along a floor at 18 rad/s, mass down: it
 *                             rolls over and over and never hops; only an LED
 *                             at the mass tracked
 *
 *   make_examples DIR    writes the five files into DIR */
#define _POSIX_C_SOURCE 200809L
#include "synth.h"
#include <jumpcyl/track.h>
#include "synth_table.h"

#include <gsl/gsl_errno.h>

#define FPS 30.0
#define NOISE_M 1.5e-3
#define PX_PER_M 400.0

static syn_Camera phone(uint64_t seed, double mark_m)
{
    return (syn_Camera){
        .fps = FPS,
        .stepsize = 1,
        .startframe = 12,
        .px_per_m = PX_PER_M,
        .roll_deg = 1.5,
        .cx_px = 120,
        .cy_px = 140,
        .noise_px = NOISE_M * PX_PER_M,
        .mark_offset_m = mark_m,
        .seed = seed,
    };
}

static int film(const char *dir, const char *stem, const jc_Setup *s, const syn_Camera *c, const char *centre,
                const char *mark)
{
    syn_Experiment e;
    if (syn_make(s, c, &e) != 0) return -1;
    char trk[512], txt[512];
    snprintf(trk, sizeof trk, "%s/%s.trk", dir, stem);
    snprintf(txt, sizeof txt, "%s/%s.txt", dir, stem);
    const int rc = syn_write_trk(trk, c, &e, centre, mark) == 0 && syn_write_table(txt, c, &e, centre, mark, '\t', 0) == 0
                       ? 0
                       : -1;
    syn_free(&e);
    return rc;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    char err[256];
    jc_Setup paper = jc_paper_setup();
    paper.mu_kinetic = 0.4;
    const syn_Camera on_incline = phone(2601, 0.055);
    if (film(argv[1], "incline", &paper, &on_incline, "axle", "rod") != 0) return 1;

    jc_Setup hoop;
    if (jc_preset_setup("hoop", &hoop, err, sizeof err) != JC_OK) return 1;
    const syn_Camera on_floor = phone(2602, 0.10);
    if (film(argv[1], "floor", &hoop, &on_floor, "axle", "mass") != 0) return 1;

    const jc_Setup ring = synth_loaded_ring();
    const jc_TrackSynthOptions o = synth_camera(FPS, NOISE_M, JC_TRACK_SYNTH_MARK_ONLY, 2603, 0.10);
    char led[512];
    snprintf(led, sizeof led, "%s/floor-led.txt", argv[1]);
    if (synth_table_write(led, &ring, &o, NULL) != 0) {
        fprintf(stderr, "%s: cannot be written\n", led);
        return 1;
    }
    return 0;
}
