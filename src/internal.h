/* Internal helpers shared by the library's source files; not installed. */
#ifndef JUMPCYL_INTERNAL_H
#define JUMPCYL_INTERNAL_H

#include "jumpcyl/jumpcyl.h"
#include "rolling_law.h"
#include "sincos.h"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>
#include <stdarg.h>

/* ---- trigpoly.c: functions of th of the form T0(th) + th T1(th), T0 and T1
 * trigonometric polynomials of degree <= JC_TRIG_DEGREE. Every quantity of
 * the rolling and paper models, multiplied by a positive factor, has this
 * form; that is what makes the first-crossing search provable (scan.c). ---- */
#define JC_TRIG_DEGREE 4
typedef struct {
    double c0[JC_TRIG_DEGREE + 1], s0[JC_TRIG_DEGREE + 1]; /* T0: cos k th, sin k th */
    double c1[JC_TRIG_DEGREE + 1], s1[JC_TRIG_DEGREE + 1]; /* T1 */
} jc_TrigLin;

/* ---- model.c: what jc_Model keeps in its private room ---- */
typedef struct {
    /* Rolling from any start, with e = I_P w^2 + 2 U at that start:
     * N I_P^2 = roll_normal_a + e roll_normal_b, likewise F. */
    jc_TrigLin roll_normal_a, roll_normal_b, roll_friction_a, roll_friction_b;
    jc_TrigLin potential_poly; /* U(th), up to a constant */
    jc_TrigLin inertia_p_poly; /* I_P(th) */
    /* The paper's Eq. 9 as (LHS - RHS) * d cos th * den, > 0 on the jump side. */
    jc_TrigLin paper_poly;
    /* The rolling law's constants (rolling_law.h): with the model's
     * resistances, and without them (the exact rolling model). */
    jc_RollConsts roll, roll_bare;
    int has_resistance;        /* air or rolling resistance on */
    double inv_mass_per_kg;    /* 1 / M */
    double inv_inertia_g;      /* 1 / I_G, 1/(kg m^2) */
} jc_ModelTables;

static inline const jc_ModelTables *jc_model_tables(const jc_Model *m)
{
    return (const jc_ModelTables *)(const void *)m->internal.reserved;
}
/* Whether air or rolling resistance is on; inline: asked at every stage of
 * the drag runs' rolling. */
static inline int jc_model_has_resistance(const jc_Model *m) { return jc_model_tables(m)->has_resistance; }

/* Writes a formatted message into err (if any) and returns status. */
int jc_fail(char *err, size_t err_len, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))

#endif
    ;

/* ---- trigpoly.c ---- */

void jc_tl_zero(jc_TrigLin *p);
/* a*cos(k th) or a*sin(k th) added to T0 (lin = 0) or T1 (lin = 1). */
void jc_tl_add_cos(jc_TrigLin *p, int lin, int k, double a);
void jc_tl_add_sin(jc_TrigLin *p, int lin, int k, double a);
/* out = a*x + b*y */
void jc_tl_axpby(jc_TrigLin *out, double a, const jc_TrigLin *x, double b, const jc_TrigLin *y);
/* out = x*y; at most one of them may have a T1 part, and the degrees must add
 * up to at most JC_TRIG_DEGREE (both checked; returns JC_EINVAL if not). */
int jc_tl_mul(jc_TrigLin *out, const jc_TrigLin *x, const jc_TrigLin *y);
/* cos(k th), sin(k th) for k = 0..JC_TRIG_DEGREE: shared by every function
 * evaluated at the same th. */
typedef struct {
    double th;
    double c[JC_TRIG_DEGREE + 1], s[JC_TRIG_DEGREE + 1];
} jc_TrigBasis;
void jc_tl_basis(jc_TrigBasis *b, double th);
void jc_tl_eval3_basis(const jc_TrigLin *p, const jc_TrigBasis *b, double out[3]);
/* The same, summing only up to degree deg (>= the polynomial's degree). */
void jc_tl_eval3_basis_upto(const jc_TrigLin *p, const jc_TrigBasis *b, int deg, double out[3]);
/* Highest k with a nonzero coefficient (-1 for the zero polynomial). */
int jc_tl_degree(const jc_TrigLin *p);
/* f, f', f'' at th. */
void jc_tl_eval3(const jc_TrigLin *p, double th, double out[3]);
/* A bound on |f'''| for |th| <= th_abs_max. */
double jc_tl_third_bound(const jc_TrigLin *p, double th_abs_max);
/* How that bound grows with th_abs_max: |f'''| <= jc_tl_third_bound(p, 0)
 * + jc_tl_third_slope(p) |th| at every th. */
double jc_tl_third_slope(const jc_TrigLin *p);
/* All of a function's bounds in one pass over its coefficients (the
 * crossing search needs them at every scan's start): its degree; |f'''| <=
 * third0 + third_slope |th| at every th (as the two above); |f| <= mag0 +
 * mag1 |th| (as jc_tl_magnitude_bound). */
typedef struct {
    int degree;
    double third0, third_slope, mag0, mag1;
} jc_TrigBounds;
void jc_tl_bounds(const jc_TrigLin *p, jc_TrigBounds *b);
/* Value and derivative at th. */
void jc_tl_eval(const jc_TrigLin *p, double th, double *f, double *df);
double jc_tl_value(const jc_TrigLin *p, double th);
/* A bound on |f| (the scale of its rounding noise) for |th| <= th_abs_max. */
double jc_tl_magnitude_bound(const jc_TrigLin *p, double th_abs_max);
/* A bound on |f''| for |th| <= th_abs_max. */
double jc_tl_curvature_bound(const jc_TrigLin *p, double th_abs_max);

/* ---- scan.c: the first place where one of several functions stops being
 * positive, found by steps that cannot cross a root (see scan.c). ---- */

#define JC_SCAN_MAX 8

/* A watched function of the scan variable u: eval writes f, f', f'' at u;
 * third_bound bounds |f'''| over the whole scanned range; noise is the size
 * of rounding in f (values within it count as zero). */
typedef struct {
    void (*eval)(const void *ctx, double u, double out[3]);
    const void *ctx;
    double third_bound;
    double noise;
    double sign; /* watch sign * f, which must stay > 0 */
    /* f alone at u, for root polishing; NULL: from eval. */
    double (*value)(const void *ctx, double u);
    /* 1: polish a root by Newton's iteration on eval's f' inside the
     * bracket, not by Brent's method on f. */
    int newton;
    /* > 0: third_bound + third_slope |u| bounds |f'''| at u (third_bound
     * alone then bounds it only at u = 0); the search bounds it over each
     * step's window, not over the whole range. */
    double third_slope;
} jc_ScanFn;

typedef struct {
    int count;
    const jc_TrigLin *f[JC_SCAN_MAX];
    double sign[JC_SCAN_MAX]; /* watch sign*f, which must be > 0 */
} jc_ScanSet;

typedef struct {
    int index;     /* which function hit zero first; -1: none before th_to */
    double theta;  /* where (th_to when index = -1) */
    int grazing;   /* 1: touched zero without a located sign change */
    int steps;     /* safe steps taken, for benchmarks and tests */
} jc_ScanHit;

/* Scans from th_from to th_to (either direction). Root located to tol_rad. */
int jc_scan_first(const jc_ScanSet *set, double th_from, double th_to, double tol_rad,
                  jc_ScanHit *hit, char *err, size_t err_len);

/* The general form: scans from u_from to u_to (either direction) for the
 * first u where one of the functions stops being positive; root to tol. */
int jc_scan_fns(const jc_ScanFn *fns, int count, double u_from, double u_to, double tol,
                jc_ScanHit *hit, char *err, size_t err_len);
/* The smallest positive root of x^3 + a x^2 + b x + c, or INFINITY. */
double jc_cubic_first_positive(double a, double b, double c);
/* The same polishing roots with the caller's Brent solver (a run's
 * workspace: no allocation), or making one when it is NULL. */
int jc_scan_fns_with(const jc_ScanFn *fns, int count, double u_from, double u_to, double tol,
                     gsl_root_fsolver *brent, jc_ScanHit *hit, char *err, size_t err_len);
/* The sets' roots are polished by Halley's iteration (scan.c says why):
 * brent is not used, and kept for the callers. */
int jc_scan_first_with(const jc_ScanSet *set, double th_from, double th_to, double tol_rad, gsl_root_fsolver *brent,
                       jc_ScanHit *hit, char *err, size_t err_len);
/* A set prepared once for several scans (its bounds computed once): the
 * rolling prediction scans its path again past the slip with fewer
 * functions. active: bit i for set->f[i]; hit->index is the place in set. */
typedef struct {
    int count;
    const jc_TrigLin *f[JC_SCAN_MAX];
    double sign[JC_SCAN_MAX];
    jc_TrigBounds bounds[JC_SCAN_MAX];
} jc_TrigScan;
void jc_trig_scan_init(jc_TrigScan *s, const jc_ScanSet *set);
int jc_trig_scan_run(const jc_TrigScan *s, unsigned active, double th_from, double th_to, double tol_rad,
                     jc_ScanHit *hit, char *err, size_t err_len);


/* ---- the simulator's shared pieces (simulate.c and one file per phase) ---- */

#include "dop853.h"

typedef enum {
    PHASE_SLIP,        /* rolling: the friction cone is reached */
    PHASE_LIFTOFF,     /* contact: N = 0 */
    PHASE_SLIP_ZERO,   /* sliding: the slip velocity returned to 0 */
    PHASE_TOUCHDOWN,   /* flight: the rim meets the incline */
    PHASE_RAMP_END,
    PHASE_RAMP_TOP,
    PHASE_PAINLEVE,
    PHASE_TIME_LIMIT,
    PHASE_AT_REST,
    PHASE_STEP_LIMIT
} jc_PhaseEnd;

/* workspace.c: a run's allocated helpers, made once and reused by any
 * number of runs (one at a time). */
#define JC_QUAD_INTERVALS 200 /* subintervals of the adaptive rolling-time quadrature */
struct jc_Workspace {
    gsl_integration_workspace *quad; /* rolling time (rolling_phase.c) */
    gsl_root_fsolver *brent;         /* root polishing (scan.c, rolling_phase.c) */
};

/* record.c: what a run has pushed to its recorder, and what it holds back. */
#define JC_HELD_MAX 4
typedef struct {
    const jc_Recorder *rec;        /* where events and samples go */
    long long sample_k;            /* the next fixed sample is at sample_k * sample_dt_s */
    double last_sample_t;          /* time of the last sample pushed (-INFINITY before the first) */
    int samples_made;              /* samples pushed */
    int sample_limit_hit;          /* max_samples reached: no more samples, the run ends */
    /* Events made but not yet pushed: the open flight's lift-off (or bounce)
     * and what follows it until the flight closes (a ramp end, a time limit). */
    jc_Event held[JC_HELD_MAX];
    int held_count;
    int flight_event;              /* index in held of the event whose flight is under way, or -1 */
    int events_made;               /* events created (pushed or held): what max_events counts */
} jc_Trace;

/* A run in progress: the driver (simulate.c) owns it, the phases advance it. */
typedef struct jc_Sim {
    const jc_Model *m;
    const jc_SimOptions *opt;
    jc_Run *run;
    jc_State s;
    jc_Mode mode;
    int slip_dir;                  /* sliding: sign of the slip velocity */
    double friction_loss_J, impact_loss_J, air_loss_J, rr_loss_J;
    double energy0_J;              /* K + U at the start */
    jc_Trace trace;
    double hop_height_m;           /* the last flight's largest gap */
    long micro_slips;              /* cone excursions rolled through (rolling.c, physics.md §4a, micro-slips) */
    double periodic_period_s;      /* > 0: rolling found periodic and whole periods were skipped */
    double periodic_th_lo_rad, periodic_th_hi_rad; /* its turning points */
    jc_Workspace *ws;
    jc_Dop853 dop;                 /* the integrator of phases without a closed form */
    double ode_h_s;                /* its last accepted step: the next phase starts there */
} jc_Sim;

/* ode.c: phases without a closed form, integrated with DOP853 and ended by
 * the first event. The state vector is the same in every mode; it carries
 * cos th and sin th (cos' = -w sin, sin' = w cos), so that no right-hand side
 * computes a sine. */
/* Ordered so that a phase integrates a range of the vector and carries the
 * rest unchanged, fewer components being less work per stage: sliding
 * without resistance the first 7 (y, vy are constant in contact), with it
 * the first 9, rolling with resistance th to rr (x and vx follow from th
 * and w), flight all. */
enum { JC_Y_X, JC_Y_VX, JC_Y_TH, JC_Y_W, JC_Y_COS, JC_Y_SIN, JC_Y_FRICTION, JC_Y_AIR, JC_Y_RR, JC_Y_Y, JC_Y_VY,
       JC_Y_DIM };
#define JC_ODE_MAX_EVENTS 8
#define JC_ODE_TIME_LIMIT (-1)
#define JC_ODE_STEP_LIMIT (-2)
typedef struct {
    int (*rhs)(double t, const double y[], double dydt[], void *ctx);
    /* Event functions, positive while the phase goes on. */
    void (*events)(void *ctx, const double y[], double ev[]);
    int event_count;
    int (*sample)(jc_Sim *sim, void *ctx, double t, const double y[]);
    void *ctx;
    int dim; /* components integrated: the first dim; the others keep their start values */
    /* The events' rates along the flow at y, f = f(y) given, in closed form;
     * NULL: by a central difference of events. */
    void (*event_rates)(void *ctx, const double y[], const double f[], double dev[]);
    /* jc_dop853_try with rhs inlined (JC_DOP853_TRY_INSTANCE), for the
     * phase's range; NULL: jc_dop853_try itself. */
    jc_DopTry try_step;
} jc_OdePhase;
void jc_state_to_y(const jc_Sim *sim, double y[JC_Y_DIM]);
void jc_y_to_state(const double y[JC_Y_DIM], double t, jc_State *s);
/* Runs from sim->s to the first event (its index in *which) or a limit
 * (JC_ODE_TIME_LIMIT, JC_ODE_STEP_LIMIT); sim->s and the losses advance. */
int jc_ode_run(jc_Sim *sim, const jc_OdePhase *p, int *which, char *err, size_t err_len);
/* Event k at (t, y), found on the continuous extension: 1 if the phase
 * passes through it (it may change its event functions) and the
 * integration goes on, 0 if it ends the phase. */
typedef int (*jc_OdePass)(jc_Sim *sim, void *ctx, int k, double t, const double y[]);
/* What some phases add to jc_ode_run. */
typedef struct {
    int first;       /* integrated: [first, first + dim) (0: the first dim, as jc_ode_run) */
    jc_OdePass pass; /* events the phase may pass through; NULL: every event ends it */
} jc_OdeExtras;
int jc_ode_run_with(jc_Sim *sim, const jc_OdePhase *p, const jc_OdeExtras *x, int *which, char *err,
                    size_t err_len);

/* run.c: jc_kinetic_energy and jc_potential_energy of a state whose th has
 * sine sn and cosine cs (the same values). */
void jc_energies_sc(const jc_Model *m, const jc_State *s, double sn, double cs, double *kinetic_J,
                    double *potential_J);

/* record.c: pushes a trajectory sample: the contact force and, in
 * flight, the gap (jc_flight_gap) given by the phase, the other derived
 * fields computed here. */
int jc_record_sample(jc_Sim *sim, const jc_State *s, jc_Mode mode, double normal_N, double friction_N,
                     double gap_m);
/* The sample with the losses carried in y (ode phases). */
int jc_record_sample_y(jc_Sim *sim, const jc_State *s, const double y[], jc_Mode mode, double normal_N,
                       double friction_N, double gap_m);
/* Whether a fixed-step sample falls in (.., t_end]; its time in *t. A 1
 * takes that sample off the schedule (the counter advances): the caller
 * records it with jc_record_sample, so the loop always moves on. */
int jc_record_sample_due(jc_Sim *sim, double t_end, double *t);
/* Makes an event at the current state (forces and slip those just before)
 * and holds it until it is complete: *out (if not NULL) may still be
 * filled in until the next event. Pushes the earlier held ones that are. */
int jc_record_event(jc_Sim *sim, jc_EventKind kind, jc_Mode before, double normal, double friction, double slip,
                    jc_Event **out);
/* The event just made starts a flight: it waits for jc_record_close_flight. */
void jc_record_open_flight(jc_Sim *sim);
void jc_record_close_flight(jc_Sim *sim, int landed);
/* Pushes the held events that are complete. */
int jc_record_push(jc_Sim *sim);

#include "air.h"

/* rolling.c: the rolling law (rolling_law.h) at th of the model's exact
 * rolling model, without loads (sin and cos from libm). */
void jc_rolling_forces(const jc_Model *m, double th, double w, double *thdd, double *normal, double *friction);
/* The same with the model's resistances when it has any; dir is the
 * direction for rolling resistance when w = 0. */
void jc_rolling_at(const jc_Model *m, double th, double w, int dir, double *thdd, double *normal, double *friction);
/* I_P at th given by its cosine. */
static inline double jc_rolling_inertia_p(const jc_Model *m, double cos_th)
{
    return jc_roll_inertia_p(&jc_model_tables(m)->roll_bare, cos_th);
}
/* The rolling path from a state (th, w): its functions of th for the state's
 * energy, cleared of positive factors: I_P w^2, N I_P^2, F I_P^2 and
 * mu_s N -/+ F (times I_P^2). Rolling holds while normal, slip_pos and
 * slip_neg are > 0; energy = 0 is a turning point. */
typedef struct {
    jc_TrigLin energy, normal, friction, slip_pos, slip_neg;
    const jc_TrigLin *inertia;
} jc_RollingPath;
void jc_rolling_path_init(const jc_Model *m, double th, double w, jc_RollingPath *p);
/* rolling_phase.c */
int jc_rolling_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len);

/* sliding.c */
typedef struct {
    double normal_N, friction_N, theta_acc, x_acc, denominator;
} jc_SlidingForces;
/* Contact forces and accelerations; loads NULL for none. */
/* At angle th given by its sine s and cosine c. */
void jc_sliding_accel(const jc_Model *m, double s, double c, double w, int dir, const jc_Loads *loads, jc_SlidingForces *f);
void jc_sliding_forces(const jc_Model *m, double th, double w, int slip_dir, jc_SlidingForces *f); /* no loads */
/* At a state, with the loads there when the model has any. */
void jc_sliding_at(const jc_Model *m, const jc_State *s, int dir, jc_SlidingForces *f, jc_Loads *loads);
int jc_sliding_phase(jc_Sim *sim, jc_PhaseEnd *end, char *err, size_t err_len);

/* flight.c */
/* The gap: the rim's lowest point above the incline (inline: the flight
 * phases and the driver give it to the recorder with each sample). */
static inline double jc_flight_gap(const jc_Model *m, const jc_State *s) { return s->y_m - m->body.radius_m; }
int jc_flight_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len);
/* flight_air.c: the same with air or rolling resistance on (an ODE), called by jc_flight_phase. */
int jc_flight_air_phase(jc_Sim *sim, int from_liftoff, jc_PhaseEnd *end, char *err, size_t err_len);

/* impact.c */
/* The contact point's velocity before an impact and the inverse effective
 * mass K at it (docs/physics.md §4), with the law's parameters. */
typedef struct {
    double vt, vn;           /* contact point velocity, vn < 0 approaching */
    double ktt, ktn, knn;    /* K, symmetric positive definite */
    double mu_static, mu_kinetic, restitution;
    jc_ImpactLaw law;        /* JC_IMPACT_STRONGE or JC_IMPACT_POISSON for jc_impact_solve */
    double slip_tol;         /* |vt| <= slip_tol before the impact counts as no slip */
} jc_ImpactInput;
typedef struct {
    double pt, pn;           /* the impulse */
    double vt, vn;           /* contact point velocity after */
    double pn_compression;   /* pn at the end of compression (vn = 0) */
    double work_compression, work_restitution; /* normal impulse's work in each phase */
    int slip_stopped;        /* vt reached 0 during the impulse */
    int sticks, reversed;    /* and then stuck, or slid the other way */
    int inconsistent;        /* no piece ends: not possible for K positive definite */
} jc_ImpulseOut;
/* Darboux-Keller integration in pn, piece by piece in closed form. */
int jc_impact_solve(const jc_ImpactInput *in, jc_ImpulseOut *out);
/* The input at a state touching the incline (restitution left 0). */
void jc_impact_input(const jc_Model *m, const jc_State *s, jc_ImpactInput *in);

typedef struct {
    double impulse_normal_Ns, impulse_tangent_Ns;
    double approach_speed_mps;   /* normal speed of the contact point before, >= 0 */
    double rebound_speed_mps;    /* after */
    int sticks;                  /* tangential slip stopped by the impulse and stayed 0 */
    int reversed;                /* tangential slip reversed during the impulse */
    int painleve;                /* Newton's sliding impulse with no consistent solution */
} jc_ImpactResult;
/* Applies an impact law at a state touching the incline, with restitution e.
 * No impulse when the contact point does not approach (vn >= 0). */
void jc_impact_apply_law(const jc_Model *m, jc_State *s, jc_ImpactLaw law, double e, jc_ImpactResult *out);
/* The same with the setup's law. */
void jc_impact_apply(const jc_Model *m, jc_State *s, double e, jc_ImpactResult *out);

/* The ramp's top counts as passed 1 nm uphill of the start, in every mode,
 * so that a start exactly at x = 0 (or a body rocking back to rest there)
 * is not an event. */
#define JC_RAMP_TOP_SLACK_M 1e-9

/* Slip speeds below this are no slip (mode.c, impact.c): 1 nm/s, far below
 * anything a ramp experiment resolves, far above the rounding of a located
 * stick event or of a state's velocities. */
#define JC_NO_SLIP_MPS 1e-9

/* A touchdown whose contact point approaches slower than this is not an
 * impact (no impulse): 1 nm/s, far above the normal velocity's error at a
 * touchdown located to the event tolerance, far below any measurable speed. */
#define JC_APPROACH_MPS 1e-9

/* mode.c */
/* The free (contact-force-free) normal acceleration of the rim's lowest
 * point: -g cos a + d w^2 cos th, plus the air's share. */
double jc_free_gap_accel(const jc_Model *m, const jc_State *s);
typedef enum { CHOICE_ROLL, CHOICE_SLIDE, CHOICE_FLY, CHOICE_PAINLEVE, CHOICE_REST } jc_ModeChoice;
/* The contact mode consistent with the forces at a state on the incline
 * (y = r, vy = 0); *slip_dir for CHOICE_SLIDE. allow_roll = 0 where the
 * rolling path was just found to leave the friction cone: on the cone's edge
 * rounding must not put the body back into rolling. */
jc_ModeChoice jc_mode_choose(const jc_Model *m, const jc_State *s, int allow_roll, int *slip_dir);


#endif
