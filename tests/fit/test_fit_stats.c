/* The fit's coverage (issue 26, item 8): synthetic round trips with known
 * truth. The paper's cylinder on 30° (mu_s 0.5, mu_k 0.4, e 0.3: it slips at
 * 0.53 s, lifts off at 1.19 m and bounces three times) is filmed with Tracker's
 * level axes at 30 to 240 frames/s and tracked with 0.5 to 3 mm of noise,
 * read back as a file is (the incline measured, the noise measured from the
 * frames in contact), and fitted as `jumpcyl fit --free mu_s,mu_k,restitution`
 * fits (the start x0, theta0, omega0 with them, the default search).
 *
 * The values the fit determines must hold the truth within 2 of their
 * reported sigma in 90 to 99 % of the intervals, all values pooled (a
 * 2-sigma interval of an honest estimator: 95.45 %), and each value in 85
 * to 99.5 % of its trials (seeds 16 to 18: mu_k 95-96.5 %, restitution
 * 89-91.5 %, theta0, omega0, x0 and the frame's tilt 92-96.5 %, mu_s 96-99 %
 * of the trials it is determined in). A value the fit flags as not
 * determined is not counted (mu_s, in about 30 % of these videos: its
 * slip margin is flat in chi2); mu_k, e and the start never are. The verdict must say that the model
 * describes each video (the model is the truth here) in at least 97 % of
 * the trials: its thresholds are not crossed by chance.
 *
 * Environment: JC_FIT_TRIALS (default 200; below 100 the figures are printed
 * and not judged), JC_TEST_SEED (default 16). */
#include <jumpcyl/study.h>
#include <jumpcyl/track.h>
#include "../test.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_TRIALS 200
#define DEFAULT_SEED 16u
#define COVERAGE_MIN 0.90       /* all values pooled */
#define COVERAGE_MAX 0.99
#define VALUE_COVERAGE_MIN 0.85 /* each value: 200 trials spread 1.5 % */
/* e's sigma runs about 20 % small (its coverage 84.5-92 %, mean 88.5 %,
 * over seeds 16-27; docs/tracker.md): this bound records that known gap
 * so that it cannot grow unseen; it is not the goal. */
#define E_COVERAGE_MIN 0.80
#define VALUE_COVERAGE_MAX 0.995
#define VERDICT_OK_MIN 0.97

static jc_Setup truth(void)
{
    jc_Setup s = jc_paper_setup();
    s.mu_static = 0.5;
    s.mu_kinetic = 0.4;
    s.restitution = 0.3;
    return s;
}

/* Trial i's camera: noise log-uniform in [0.5, 3] mm, frame rate 30, 60,
 * 120 or 240 per second in turn. */
static jc_TrackSynthOptions synth(uint64_t seed, int i)
{
    jc_TrackSynthOptions o;
    memset(&o, 0, sizeof o);
    static const double fps[4] = {30, 60, 120, 240};
    o.fps_hz = fps[i % 4];
    o.sigma_m = 0.5e-3 * pow(6.0, jc_random_uniform(seed, (uint64_t)i, 1000u));
    o.t_end_s = 1.5;
    o.mark_radius_m = 0.055;
    o.seed = seed;
    o.trial = (uint64_t)i;
    o.tracks = JC_TRACK_SYNTH_BOTH;
    return o;
}

enum { V_MU_S, V_MU_K, V_E, V_THETA0, V_OMEGA0, V_X0, V_TILT, NV };
static const char *const vname[NV] = {"mu_s", "mu_k", "restitution", "theta0", "omega0", "x0", "tilt"};

/* The truth of each value. The video's frame is turned onto the measured
 * incline; the fit's tilt is the truth's incline less that, and the start
 * (the centre r above the contact point, released at rest with G straight
 * up) is seen from the video's frame: x0 turned by the tilt about the
 * contact point, theta0 in the model's own frame. */
static double true_value(int v, const jc_Track *t)
{
    const jc_Setup s = truth();
    const double d = s.incline_rad - t->incline_rad;
    switch (v) {
    case V_MU_S: return s.mu_static;
    case V_MU_K: return s.mu_kinetic;
    case V_E: return s.restitution;
    case V_THETA0: return 0.0;
    case V_OMEGA0: return 0.0;
    case V_X0: return s.body.radius_m * sin(d);
    default: return d;
    }
}

static int slot(const jc_TrackFitResult *r, int v)
{
    static const jc_TrackFitKind kind[NV] = {JC_FIT_MU_S,   JC_FIT_MU_K,   JC_FIT_RESTITUTION, JC_FIT_THETA0,
                                         JC_FIT_OMEGA0, JC_FIT_X0,     JC_FIT_TILT};
    for (int k = 0; k < r->count; ++k)
        if (r->param[k].kind == kind[v]) return k;
    return -1;
}

typedef struct {
    int rc;
    jc_TrackFitResult r;
    double truth[NV];
    double fps, sigma, measured_sigma;
    long contact;
} trial;

static int run_trials(int trials, uint64_t seed)
{
    printf("seed %llu, %d trials (JC_TEST_SEED, JC_FIT_TRIALS)\n", (unsigned long long)seed, trials);
    /* The user's guess: the paper preset's values (mu_k = mu_s = 0.5). */
    const jc_Setup guess = jc_paper_setup();
    jc_TrackFitOptions fo;
    jc_fit_options_default(&fo);
    fo.free[0] = (jc_TrackFitParam){JC_FIT_MU_S, -1};
    fo.free[1] = (jc_TrackFitParam){JC_FIT_MU_K, -1};
    fo.free[2] = (jc_TrackFitParam){JC_FIT_RESTITUTION, -1};
    fo.free_count = 3;
    fo.profiles = 0;
    const jc_SimOptions so = jc_default_sim_options();
    trial *tr = calloc((size_t)trials, sizeof *tr);
    ENSURE(tr);
    /* The trials are independent (a fit keeps no state outside its own
     * memory): on every core. */
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < trials; ++i) {
        jc_Track t;
        char err[256];
        const jc_TrackSynthOptions o = synth(seed, i);
        const jc_Setup ts = truth();
        tr[i].fps = o.fps_hz;
        tr[i].sigma = o.sigma_m;
        tr[i].rc = jc_track_synthesize(&ts, &o, &t, err, sizeof err) != 0 ? 1
                   : jc_track_fit(&guess, &t, &fo, &so, &tr[i].r, err, sizeof err) != 0 ? 2 : 0;
        if (tr[i].rc != 1) {
            for (int v = 0; v < NV; ++v) tr[i].truth[v] = true_value(v, &t);
            tr[i].measured_sigma = t.sigma_m;
            tr[i].contact = t.contact_frames;
            jc_track_free(&t);
        }
        if (tr[i].rc) fprintf(stderr, "trial %d (seed %llu): %s\n", i, (unsigned long long)seed, err);
    }
    int inside[NV] = {0}, counted[NV] = {0}, flagged[NV] = {0}, described = 0;
    for (int i = 0; i < trials; ++i) {
        if (tr[i].rc != 0) {
            free(tr);
            ENSURE_MSG(0, "trial %d failed (seed %llu)", i, (unsigned long long)seed);
        }
        const jc_TrackFitResult *r = &tr[i].r;
        described += !r->misfit;
        if (getenv("JC_FIT_VERBOSE")) {
            printf("T %3d fps %3.0f sigma %.2f mm (measured %.2f, %ld frames) chi2/dof %.3f z %.1f misfit %d |", i,
                   tr[i].fps, tr[i].sigma * 1e3, tr[i].measured_sigma * 1e3, tr[i].contact, r->chi2_dof, r->runs_z,
                   r->misfit);
            for (int v = 0; v < NV; ++v) {
                const int k = slot(r, v);
                if (k < 0) printf(" %s not fitted", vname[v]);
                else if (r->flag[k] != JC_FIT_DETERMINED)
                    printf(" %s held (%s)", vname[v], jc_fit_flag_text(r->flag[k]));
                else printf(" %+.2f", (r->value[k] - tr[i].truth[v]) / r->sigma[k]);
            }
            printf("\n");
        }
        for (int v = 0; v < NV; ++v) {
            const int k = slot(r, v);
            if (k < 0) continue;
            if (r->flag[k] != JC_FIT_DETERMINED) {
                flagged[v]++;
                continue;
            }
            counted[v]++;
            inside[v] += fabs(r->value[k] - tr[i].truth[v]) <= 2.0 * r->sigma[k];
        }
    }
    free(tr);
    int all_in = 0, all_n = 0, bad = 0;
    for (int v = 0; v < NV; ++v) {
        const double cover = counted[v] ? (double)inside[v] / counted[v] : NAN;
        printf("  %-12s within 2 sigma in %5.1f %% of %d trials (%d held as not determined)\n", vname[v],
               100.0 * cover, counted[v], flagged[v]);
        all_in += inside[v];
        all_n += counted[v];
        /* A value determined in too few trials to judge is not judged alone. */
        const double lowest = v == V_E ? E_COVERAGE_MIN : VALUE_COVERAGE_MIN;
        if (counted[v] >= trials / 4 && !(cover >= lowest && cover <= VALUE_COVERAGE_MAX)) bad = 1;
    }
    const double pooled = (double)all_in / all_n;
    printf("  all values: within 2 sigma in %.1f %% of %d intervals; the verdict 'describes' in %d of %d\n",
           100.0 * pooled, all_n, described, trials);
    if (trials < 100) return 0; /* too few to judge a coverage by */
    /* mu_k, e and the start (theta0, omega0, x0) are always determined by these videos. */
    ENSURE_MSG(flagged[V_MU_K] == 0 && flagged[V_E] == 0 && flagged[V_THETA0] == 0 && flagged[V_OMEGA0] == 0 &&
               flagged[V_X0] == 0,
               "a value these videos determine was held (seed %llu)", (unsigned long long)seed);
    ENSURE_MSG(pooled >= COVERAGE_MIN && pooled <= COVERAGE_MAX, "pooled coverage %.3f (seed %llu)", pooled,
               (unsigned long long)seed);
    ENSURE_MSG(!bad, "a value's coverage is outside [%.3f, %.3f] (e's: from %.3f) (seed %llu)", VALUE_COVERAGE_MIN,
               VALUE_COVERAGE_MAX, E_COVERAGE_MIN, (unsigned long long)seed);
    ENSURE_MSG(described >= VERDICT_OK_MIN * trials, "the verdict called %d of %d true models a misfit (seed %llu)",
               trials - described, trials, (unsigned long long)seed);
    return 0;
}

static unsigned long long env_number(const char *name, unsigned long long dflt)
{
    const char *v = getenv(name);
    return v && *v ? strtoull(v, NULL, 10) : dflt;
}

static int test_fit_coverage(void)
{
    return run_trials((int)env_number("JC_FIT_TRIALS", DEFAULT_TRIALS), env_number("JC_TEST_SEED", DEFAULT_SEED));
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_fit_coverage);
    TEST_MAIN_END();
}
