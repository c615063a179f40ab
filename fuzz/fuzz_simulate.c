/* Fuzz target: the simulator fed arbitrary setups. The input bytes decode
 * into a jc_Setup and jc_SimOptions: mostly values spread over physical
 * ranges, sometimes the edges, zero, NaN, infinities or raw doubles, so
 * that validation is exercised as well as the simulator. The simulated
 * time and the event count are capped so that every input runs fast.
 *
 * Invariants: every call returns a known status with a message when it
 * fails; a run that succeeds says why it stopped, stays within its event,
 * sample and time bounds, records events and samples in time order with
 * finite states, and ends with a finite energy balance. */
#include "fuzz.h"

#include <jumpcyl/jumpcyl.h>

#include <float.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <string.h>

/* Caps that keep one input well under a second. */
#define FUZZ_T_MAX_S 2.0
#define FUZZ_MAX_EVENTS 64
/* Samples are the slow part of a short run (each one in rolling solves for
 * its angle): a few dozen cover the sampling code. */
#define FUZZ_MAX_SAMPLES 48

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    gsl_set_error_handler_off(); /* as every program using the full model must (docs/api.md) */
    return 0;
}

typedef struct {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned byte_of(reader *r)
{
    if (r->n == 0) return 0;
    r->n--;
    return *r->p++;
}

/* A value in [lo, hi] most of the time; otherwise an edge or a value no
 * setup should accept. */
static double value_in(reader *r, double lo, double hi)
{
    const unsigned sel = byte_of(r);
    if (sel < 232) {
        const unsigned hi8 = byte_of(r); /* two statements: the order of the reads matters */
        const unsigned u = hi8 << 8 | byte_of(r);
        return lo + (hi - lo) * (double)u / 65535.0;
    }
    switch (sel) {
    case 232: return lo;
    case 233: return hi;
    case 234: return 0.0;
    case 235: return -0.0;
    case 236: return NAN;
    case 237: return INFINITY;
    case 238: return -INFINITY;
    case 239: return DBL_MIN;
    case 240: return DBL_MAX;
    case 241: return -1.0;
    case 242: return nextafter(hi, INFINITY);
    case 243: return nextafter(lo, -INFINITY);
    case 244: return 1e-300;
    case 245: return -hi;
    default: {
        uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) bits = bits << 8 | byte_of(r);
        double v;
        memcpy(&v, &bits, sizeof v);
        return v;
    }
    }
}

static void decode_body(reader *r, jc_BodyDef *b)
{
    memset(b, 0, sizeof *b);
    b->radius_m = value_in(r, 1e-3, 1.0);
    const double rim = isfinite(b->radius_m) && b->radius_m > 0 ? b->radius_m : 0.1;
    const unsigned count = byte_of(r);
    b->part_count = count < 250 ? 1 + (int)(count % JC_MAX_PARTS) : (int)count - 252; /* -2 .. 3: also invalid counts */
    for (int i = 0; i < JC_MAX_PARTS; ++i) {
        jc_Part *p = &b->parts[i];
        const unsigned kind = byte_of(r);
        p->kind = (jc_PartKind)(kind < 250 ? kind % 4 : kind - 245); /* 5 .. 10: unknown kinds */
        p->mass_kg = value_in(r, 0.0, 1.0);
        p->offset_m = value_in(r, 0.0, rim);
        p->radius_m = p->kind == JC_PART_POINT ? 0.0 : value_in(r, 0.0, rim - (isfinite(p->offset_m) ? p->offset_m : 0.0));
        p->angle_rad = value_in(r, -10.0, 10.0);
    }
}

static void decode(reader *r, jc_Setup *s, jc_SimOptions *o)
{
    *s = jc_paper_setup();
    if (byte_of(r) & 1) decode_body(r, &s->body);
    const double rim = s->body.radius_m;
    s->incline_rad = value_in(r, 0.0, 1.5707963267948966);
    s->gravity_mps2 = value_in(r, 0.1, 100.0);
    s->mu_static = value_in(r, 0.0, 2.0);
    s->mu_kinetic = byte_of(r) & 1 ? s->mu_static : value_in(r, 0.0, 2.0);
    s->restitution = value_in(r, 0.0, 1.0);
    s->theta0_rad = value_in(r, -7.0, 7.0);
    s->omega0_radps = value_in(r, -50.0, 50.0);
    s->ramp_length_m = value_in(r, 1e-3, 20.0);
    s->paper_cm_offset_m = value_in(r, 0.0, rim);
    if (byte_of(r) & 1) { /* air and rolling resistance */
        s->length_m = value_in(r, 0.0, 0.3);
        s->air_density_kgpm3 = value_in(r, 0.0, 2.0);
        s->drag_coefficient = value_in(r, 0.0, 2.0);
        s->lift_coefficient = value_in(r, -1.0, 1.0);
        s->spin_drag_Nms2 = value_in(r, 0.0, 1e-4);
        s->rolling_resistance_m = value_in(r, 0.0, 0.5 * rim);
    }
    *o = jc_default_sim_options();
    o->t_max_s = value_in(r, 1e-4, FUZZ_T_MAX_S);
    if (isfinite(o->t_max_s) && o->t_max_s > FUZZ_T_MAX_S) o->t_max_s = FUZZ_T_MAX_S;
    const unsigned ev = byte_of(r);
    o->max_events = ev < 250 ? 1 + (int)(ev % FUZZ_MAX_EVENTS) : (int)ev - 252; /* -2 .. 3 */
    o->sample_dt_s = byte_of(r) & 1 ? value_in(r, 0.02, 0.5) : 0.0;
    o->max_samples = FUZZ_MAX_SAMPLES;
    o->ode_rtol = value_in(r, 1e-10, 1e-6);
    o->ode_atol = value_in(r, 1e-12, 1e-8);
    o->event_tol_s = value_in(r, 1e-12, 1e-6);
    o->contact_height_m = value_in(r, 0.0, 1e-3);
}

static int known_status(int st) { return st >= JC_OK && st <= JC_ENOMEM; }

/* Air drag and spin drag on a tiny body are stiff: the explicit integrator
 * then needs about t_max * rate steps, up to the run's bound of 10^7 (15 s,
 * a minute under the sanitizers: bounded and reported, known-issues/).
 * Such setups are skipped, so that the campaign keeps its pace; the rates
 * are those of the loads at a speed the run can reach. */
#define FUZZ_MAX_STIFF_STEPS 1e5

static int too_stiff(const jc_Model *m, const jc_SimOptions *o)
{
    const jc_Setup *s = &m->setup;
    const jc_Body *b = &m->body;
    if (!jc_setup_has_resistance(s)) return 0;
    const double r = b->radius_m, i_g = b->inertia_g_kgm2;
    const double v = fabs(s->omega0_radps) * r + sqrt(2.0 * s->gravity_mps2 * s->ramp_length_m) + 1.0;
    const double w = v / r + fabs(s->omega0_radps);
    const double q = s->air_density_kgpm3 * 2.0 * r * s->length_m * (s->drag_coefficient + fabs(s->lift_coefficient));
    double rate = 2.0 * s->spin_drag_Nms2 * w / i_g;           /* spin drag on w */
    rate = fmax(rate, q * v / b->mass_kg);                     /* drag and lift on the centre's speed */
    rate = fmax(rate, b->cm_offset_m * q * v * v / (i_g * w)); /* their torque about G, on w */
    /* Rolling resistance ramps over |w| < 1 mrad/s (JC_RR_BAND_RADPS, src/air.h):
     * near rest it damps w at b N / (I_G 1e-3 rad/s). */
    rate = fmax(rate, s->rolling_resistance_m * b->mass_kg * s->gravity_mps2 / (i_g * 1e-3));
    return !(rate * o->t_max_s <= FUZZ_MAX_STIFF_STEPS);
}

static int finite_state(const jc_State *s)
{
    return isfinite(s->t_s) && isfinite(s->x_m) && isfinite(s->y_m) && isfinite(s->vx_mps) && isfinite(s->vy_mps) &&
           isfinite(s->theta_rad) && isfinite(s->omega_radps);
}

static void check_run(const jc_Run *run, const jc_SimOptions *o)
{
    /* Why it stopped: finish() always writes the reason. */
    FUZZ_CHECK(run->termination >= JC_END_RAMP_END && run->termination <= JC_END_SAMPLE_LIMIT);
    FUZZ_CHECK(run->termination_detail[0] != '\0');
    /* A step may record a few events past the check of the limit. */
    FUZZ_CHECK(run->event_count >= 0 && run->event_count <= o->max_events + 4);
    FUZZ_CHECK(run->sample_count >= 0 && run->sample_count <= o->max_samples);
    const double t_end = run->final_state.t_s;
    FUZZ_CHECK(finite_state(&run->final_state) && t_end >= 0.0 && t_end <= o->t_max_s * (1.0 + 1e-9) + 1e-9);
    double t = 0.0;
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        FUZZ_CHECK(e->kind >= 0 && e->kind < JC_EVENT_COUNT);
        FUZZ_CHECK(finite_state(&e->state));
        FUZZ_CHECK(e->state.t_s >= t && e->state.t_s <= t_end);
        t = e->state.t_s;
    }
    t = 0.0;
    for (int i = 0; i < run->sample_count; ++i) {
        const jc_Sample *p = &run->samples[i];
        FUZZ_CHECK(finite_state(&p->state) && p->state.t_s >= t);
        t = p->state.t_s;
    }
    const jc_EnergyReport *e = &run->energy;
    FUZZ_CHECK(isfinite(e->kinetic_J) && isfinite(e->potential_J) && isfinite(e->friction_loss_J) &&
               isfinite(e->impact_loss_J) && isfinite(e->air_loss_J) && isfinite(e->rolling_resistance_loss_J) &&
               isfinite(e->balance_error_J));
}

/* The two predictions read the same model; they must not crash on any. */
static void check_predictions(const jc_Model *m)
{
    char err[512] = "";
    jc_PaperResult paper;
    int st = jc_paper_solve(m, &paper, err, sizeof err);
    FUZZ_CHECK(known_status(st) && (st == JC_OK || err[0]));
    if (st == JC_OK) FUZZ_CHECK(paper.root_count >= 0 && paper.root_count <= JC_PAPER_MAX_ROOTS);
    jc_RollingResult rolling;
    err[0] = '\0';
    st = jc_rolling_predict(m, &rolling, err, sizeof err);
    FUZZ_CHECK(known_status(st) && (st == JC_OK || err[0]));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = {data, size};
    jc_Setup setup;
    jc_SimOptions opts;
    decode(&r, &setup, &opts);
    static jc_Model model; /* large: off the stack */
    char err[512] = "";
    int st = jc_model_init(&model, &setup, err, sizeof err);
    FUZZ_CHECK(known_status(st) && (st == JC_OK || err[0]));
    if (st != JC_OK) return 0;
    check_predictions(&model);
    if (too_stiff(&model, &opts)) return 0;
    jc_Run run;
    err[0] = '\0';
    st = jc_simulate(&model, &opts, &run, err, sizeof err);
    FUZZ_CHECK(known_status(st) && (st == JC_OK || err[0]));
    if (st == JC_OK) check_run(&run, &opts);
    jc_run_free(&run);
    return 0;
}
