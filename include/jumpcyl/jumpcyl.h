/*
 * jumpcyl — an off-centre-mass cylinder rolling on an incline: where it loses
 * contact and jumps.
 *
 * Conventions (docs/physics.md): x along the incline pointing downhill, y along
 * the outward normal; the cylinder's centre C is at height r while in contact;
 * the centre of mass G = C + d (sin th, cos th), so th = 0 puts G on the
 * outward normal through C, and th grows while the cylinder rolls downhill.
 * SI units everywhere; angles in radians. Degrees only appear at the edges
 * (command line, files).
 *
 * Habits: value-type definitions with defaults (jc_paper_setup()), an
 * immutable jc_Model built once and read by any number of computations, int
 * status codes with a caller-provided message buffer. The library keeps no
 * global mutable state, never prints and never exits: it is thread-safe as
 * long as each thread writes only to its own outputs.
 *
 * GSL: the library uses GSL (root finding, quadrature, ODE stepping) and
 * reports its failures as JC_ENUMERIC. GSL's default error handler aborts the
 * program instead; call gsl_set_error_handler_off() once at the start of a
 * program that links jumpcyl (the jumpcyl tool does). The library does not
 * change that process-wide setting itself.
 */
#ifndef JUMPCYL_JUMPCYL_H
#define JUMPCYL_JUMPCYL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define JC_VERSION_MAJOR 0
#define JC_VERSION_MINOR 1
#define JC_VERSION_PATCH 0
#define JC_VERSION_STRING "0.1.0"

/* Marks the documented API: the shared library is built with hidden
 * visibility, so these are its only exported symbols (tests/test_exports.sh
 * checks the list against this header). */
#if defined(__GNUC__)
#define JC_API __attribute__((visibility("default")))
#else
#define JC_API
#endif

/* Status codes returned by every fallible function. */
enum {
    JC_OK = 0,
    JC_EINVAL = 1,   /* an input is out of its allowed range; see the message */
    JC_ELIMIT = 2,   /* a bounded loop hit its bound before finishing */
    JC_ENUMERIC = 3, /* a numerical method failed (reported, never hidden) */
    JC_ENOMEM = 4,
    JC_ESTOPPED = 5  /* a recorder (jc_simulate_stream) asked the run to stop */
};

/* The library's version string, for callers linked against a shared build. */
JC_API const char *jc_version(void);

/* Short text for a status code ("ok", "invalid input", …). */
JC_API const char *jc_status_text(int status);

/* ------------------------------------------------------------------------ */
/* Body: a rigid cylinder built from parts (src/body.c)                      */
/* ------------------------------------------------------------------------ */

typedef enum {
    JC_PART_DISC,  /* uniform disc of radius radius_m, I = m R^2/2 about its own axis */
    JC_PART_HOOP,  /* thin hoop of radius radius_m, I = m R^2 about its own axis */
    JC_PART_ROD,   /* rod parallel to the axis, own radius radius_m (0 = line mass) */
    JC_PART_POINT  /* point mass; radius_m must be 0 */
} jc_PartKind;

/* One part, placed in the body frame: its own axis sits offset_m from the
 * cylinder's axis C, at angle_rad measured from the body's reference
 * direction in the direction of rolling. Each part is a full-length prism:
 * only the cross-section matters in this planar model. */
typedef struct {
    jc_PartKind kind;
    double mass_kg;   /* >= 0 */
    double offset_m;  /* >= 0, distance of the part's axis from C */
    double angle_rad; /* any finite value */
    double radius_m;  /* disc, hoop: > 0; rod: >= 0; point: 0 */
} jc_Part;

#define JC_MAX_PARTS 16

typedef struct {
    double radius_m; /* rim radius r, > 0: the surface that touches the incline */
    int part_count;  /* 1 .. JC_MAX_PARTS */
    jc_Part parts[JC_MAX_PARTS];
} jc_BodyDef;

/* What the dynamics needs of a body. */
typedef struct {
    double radius_m;        /* r */
    double mass_kg;         /* M = sum of m */
    double cm_offset_m;     /* d = |sum m a| / M */
    double cm_angle_rad;    /* direction of G in the body frame (0 when d = 0) */
    double inertia_c_kgm2;  /* I_C, about the cylinder's axis */
    double inertia_g_kgm2;  /* I_G = I_C - M d^2, about the centre of mass */
    double disc_mass_kg;    /* sum of the disc parts' masses (the paper's M1) */
} jc_Body;

/* Name of a part kind: "disc", "hoop", "rod", "point". */
JC_API const char *jc_part_kind_name(jc_PartKind kind);

/* Mass properties of a body. Checks every part: finite numbers, masses >= 0,
 * total > 0, radii in range, every part inside the rim. */
JC_API int jc_body_compute(const jc_BodyDef *def, jc_Body *out, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* Setup: body + incline + contact + start (src/setup.c)                     */
/* ------------------------------------------------------------------------ */

/* The impact law (docs/physics.md §4). Stronge's law never creates kinetic
 * energy; Poisson's and Newton's can, with sticking or slip reversal during
 * the impulse, and are kept as named alternatives whose gains are counted. */
typedef enum {
    JC_IMPACT_STRONGE = 0, /* Darboux-Keller in the normal impulse, energetic restitution (default) */
    JC_IMPACT_POISSON,     /* the same integration, restitution impulse = e times compression impulse */
    JC_IMPACT_NEWTON       /* algebraic: v_n after = -e v_n before, sticking if the cone holds it */
} jc_ImpactLaw;

/* "stronge", "poisson", "newton". */
JC_API const char *jc_impact_law_name(jc_ImpactLaw law);
/* The law of a name; JC_EINVAL for an unknown name. */
JC_API int jc_impact_law_parse(const char *name, jc_ImpactLaw *out);

typedef struct {
    jc_BodyDef body;
    double incline_rad;        /* [0, pi/2); 0 is a horizontal floor */
    double gravity_mps2;       /* > 0 */
    double mu_static;          /* >= 0, friction coefficient for sticking */
    double mu_kinetic;         /* [0, mu_static], friction coefficient while sliding
                                * (mu_k > mu_s is refused: docs/physics.md §4) */
    double restitution;        /* [0, 1], normal restitution at impacts */
    jc_ImpactLaw impact_law;   /* default (0): JC_IMPACT_STRONGE */
    double theta0_rad;         /* initial CM angle from the outward normal */
    double omega0_radps;       /* initial angular velocity, > 0 rolls downhill */
    double ramp_length_m;      /* > 0: from the start contact point to the lower end */
    /* Centre-of-mass offset the paper's model uses; 0 means the body's exact d.
     * The paper preset sets the printed, rounded 2.65 cm. */
    double paper_cm_offset_m;
    /* Air and rolling resistance (docs/physics.md, "Air and rolling
     * resistance"). All coefficients 0 (the default) switch them off, and then
     * every result is that of the resistance-free model, bit for bit. */
    double length_m;             /* cylinder length along its axis, >= 0; frontal area 2 r L */
    double air_density_kgpm3;    /* [0, 100], default 1.204 (dry air, 20 C, 101.325 kPa) */
    double drag_coefficient;     /* C_d >= 0: drag 1/2 rho C_d A |v| v on the centre, against v */
    /* C_L (Magnus): force 1/2 rho C_L A |v|^2 perpendicular to the centre's
     * velocity; C_L > 0 pushes a forward-rolling (topspinning) cylinder into
     * the incline, as a real spinning cylinder is pushed. */
    double lift_coefficient;
    double spin_drag_Nms2;       /* k >= 0: torque -k w |w| on the spin, N m s^2 */
    double rolling_resistance_m; /* b in [0, r/2]: lever arm of N against the rolling direction */
} jc_Setup;

/* Bounds checked by jc_setup_validate, shared with the edges for messages. */
#define JC_MAX_INCLINE_RAD 1.5707963267948966 /* exclusive */
#define JC_MAX_RAMP_TURNS 1.0e5 /* ramp_length / (2 pi r) */

/* The paper's experiment: Styrofoam disc (r 10.0 cm, 34.2 g) with a brass rod
 * (32.1 g, diameter 9.50 mm) at 5.50 cm, g 9.78 m/s^2, ramp 3.20 m, at rest
 * with the CM on the outward normal, on a 30 degree incline. */
JC_API jc_Setup jc_paper_setup(void);

/* A built-in setup by name. Names: see jc_preset_name(). */
JC_API int jc_preset_setup(const char *name, jc_Setup *out, char *err, size_t err_len);

/* The i-th preset's name and one-line description; NULL past the end. */
JC_API const char *jc_preset_name(int i);
JC_API const char *jc_preset_description(int i);

/* Whether a setup has any air or rolling resistance switched on. */
JC_API int jc_setup_has_resistance(const jc_Setup *setup);

/* Checks every field; the message names the field, its value and the range. */
JC_API int jc_setup_validate(const jc_Setup *setup, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* Quantities with units (src/units.c)                                       */
/* ------------------------------------------------------------------------ */

/* What a number measures, and so which units it may carry. */
typedef enum {
    JC_Q_LENGTH,        /* m (a plain number is metres); cm, mm, km */
    JC_Q_MASS,          /* kg; g, mg */
    JC_Q_ANGLE,         /* rad, but a plain number is DEGREES; deg, rad */
    JC_Q_ANGULAR_SPEED, /* rad/s; deg/s, rpm, rev/s */
    JC_Q_ACCELERATION,  /* m/s2; m/s^2, cm/s2 */
    JC_Q_NUMBER,        /* dimensionless: no unit */
    JC_Q_TIME,          /* s; ms, us */
    JC_Q_DENSITY,       /* kg/m3; kg/m^3, g/cm3 */
    JC_Q_SPIN_DRAG,     /* N m s2 (= kg m2) */
    JC_Q_NAME           /* not a number: a name from a parameter's choices */
} jc_Quantity;

/* "length", "mass", "angle", "angular speed", ..., "name". */
JC_API const char *jc_quantity_name(jc_Quantity q);
/* The SI unit values are held in: "m", "kg", "rad", "rad/s", ...; "" for
 * numbers and names. */
JC_API const char *jc_quantity_si_unit(jc_Quantity q);
/* The i-th unit a value of q may carry ("cm"), with *to_si (may be NULL) the
 * SI value of one of it (0.01); NULL past the last. */
JC_API const char *jc_quantity_unit(jc_Quantity q, int i, double *to_si);
/* The units of q for messages: "m (default), cm, mm, km". */
JC_API const char *jc_quantity_units_text(jc_Quantity q);
/* Reads a whole token "number[unit]" (or "number unit", one blank) into SI:
 * "10cm", "34.2g", "15deg", "0.3rad", "120rpm"; a plain number is SI, but
 * degrees for an angle. Decimal numbers only (no hexadecimal, inf or nan);
 * a unit that is a power of ten moves the decimal point, so that "32.1g"
 * is exactly the double of "0.0321". JC_OK, or JC_EINVAL with a one-line
 * message naming the token and what is allowed (overflow and underflow to
 * zero or a subnormal are errors). */
JC_API int jc_quantity_parse(const char *text, jc_Quantity q, double *out_si, char *err, size_t err_len);
/* v_si written in unit (one of q's units, or "" for a number) as the
 * shortest text that jc_quantity_parse reads back to exactly v_si: "3.21
 * cm", "30 deg", "9.78 m/s2", "0.3". A unit that is not a power of ten of
 * the SI unit (deg, rpm) is used when some decimal in it reads back
 * exactly, else the value is written in the SI unit ("0.5235987755982988
 * rad"). JC_OK, or JC_EINVAL (no such unit for q, or buf too small; buf
 * then holds ""). 64 bytes always suffice. */
JC_API int jc_quantity_format(double v_si, jc_Quantity q, const char *unit, char *buf, size_t len);

/* ------------------------------------------------------------------------ */
/* The setup's parameters by name (src/param.c)                              */
/* ------------------------------------------------------------------------ */

/* Every single-valued setup parameter, described once: the command line's
 * --NAME options, experiment files, batch parameter names, the JSON echo
 * and the web page's controls are all made from this table. Parameters are
 * numbered 0 .. jc_param_count() - 1; look them up by name. */
#define JC_PARAM_MAX 64 /* jc_param_count() is at most this: arrays by parameter id */

/* The parameter changes the body (the printed paper d no longer applies). */
#define JC_PARAM_BODY 1u
/* The parameter sets what other rows hold (mu: mu-s and mu-k): files and
 * echoes show those instead. */
#define JC_PARAM_SHORTCUT 2u

typedef struct {
    const char *name;        /* "rod-offset": the option --rod-offset, the name in sweeps and requests */
    const char *label;       /* "rod offset": words for messages and controls */
    const char *help;        /* one line, what it is and does */
    jc_Quantity quantity;
    const char *si_unit;     /* the unit of the value: "m", "rad"; "" for numbers and names */
    const char *unit;        /* the unit people read and write: files, help, tables ("cm", "deg") */
    double min, max;         /* the range, SI; max = HUGE_VAL: no upper end of its own */
    int min_open, max_open;  /* 1: that end itself is outside the range */
    const char *bound;       /* a bound that depends on other values (checked by jc_setup_validate), or NULL */
    const char *const *choices; /* JC_Q_NAME: the names, NULL-terminated; the value is the name's index */
    const char *sets;        /* JC_PARAM_SHORTCUT: the names of the rows it sets, blank-separated; else NULL */
    unsigned flags;          /* JC_PARAM_BODY, JC_PARAM_SHORTCUT */
    const char *section;     /* experiment file: [section] key */
    const char *key;
    const char *json_key;    /* member of the setup in JSON outputs, NULL if not there; a key
                              * ending in "_deg" holds degrees, the others SI */
    double typical_min, typical_max; /* SI: a span a slider or a first sweep covers */
} jc_ParamInfo;

/* How many parameters there are. */
JC_API int jc_param_count(void);
/* The i-th parameter's description; NULL out of range. */
JC_API const jc_ParamInfo *jc_param_info(int id);
/* A parameter's id by name, -1 if none; "mu-k" and "mu_k" are the same name. */
JC_API int jc_param_find(const char *name);
/* 1 if row shortcut_id is a shortcut that sets row id (mu sets mu-s and
 * mu-k: its info's sets), else 0 (ids out of range included). */
JC_API int jc_param_sets(int shortcut_id, int id);
/* Sets a parameter in a setup: value_si in SI (a name's index for
 * JC_Q_NAME). JC_EINVAL with a one-line message, the setup unchanged, for
 * a value outside the row's range (NaN and infinities included) or a body
 * without the part a body parameter acts on. Bounds that depend on other
 * values are jc_setup_validate's. What each does:
 *  - radius sets the rim radius; the body's first disc, when it fills the
 *    rim (its radius is the rim's), grows with it;
 *  - disc-mass, rod-mass, rod-offset, rod-radius act on the body's first
 *    part of that kind;
 *  - mu sets mu_s and mu_k;
 *  - the others set the one field they name. */
JC_API int jc_param_set(jc_Setup *setup, int id, double value_si, char *err, size_t err_len);
/* A parameter's value in a setup (mu: mu_s; a name: its index). JC_OK, or
 * JC_EINVAL with a message (no such parameter, a body without that part). */
JC_API int jc_param_get(const jc_Setup *setup, int id, double *value_si, char *err, size_t err_len);
/* Reads a value as the command line and files give it: a number with units
 * (jc_quantity_parse of the row's quantity), or one of the row's choices
 * ("newton"). The range is not checked here (jc_param_set does). JC_OK, or
 * JC_EINVAL with a one-line message naming the text and what is allowed. */
JC_API int jc_param_parse(int id, const char *text, double *value_si, char *err, size_t err_len);
/* A value as text in the row's own unit (jc_quantity_format), or the
 * choice's name: jc_param_parse reads it back to exactly value_si. JC_OK, or
 * JC_EINVAL (no such parameter or choice, buf too small). */
JC_API int jc_param_format(int id, double value_si, char *buf, size_t len);

/* ------------------------------------------------------------------------ */
/* Model: the immutable, validated, precomputed form of a setup (src/model.c) */
/* ------------------------------------------------------------------------ */

/* Room for what the model precomputes (src/internal.h, jc_ModelTables: the
 * rolling and paper models as exact functions of th, and constants the
 * integrators read). Private: its layout may change in any release. */
#define JC_MODEL_PRIVATE_DOUBLES 192

typedef struct {
    jc_Setup setup;
    jc_Body body;
    double sin_incline, cos_incline;
    double theta_end_rad; /* th at which the rolling contact point reaches the ramp end (from the setup's start) */
    double paper_d_m;     /* the d the paper's model uses */
    struct {
        double reserved[JC_MODEL_PRIVATE_DOUBLES];
    } internal;
} jc_Model;

/* Validates the setup and precomputes everything the models read. */
JC_API int jc_model_init(jc_Model *model, const jc_Setup *setup, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* The paper's model: Eq. 9 as printed (src/paper_model.c)                   */
/* ------------------------------------------------------------------------ */

#define JC_PAPER_MAX_ROOTS 256

typedef struct {
    int root_count;                       /* intersections with cos th > 0 */
    double theta_rad[JC_PAPER_MAX_ROOTS]; /* ascending, from 0 to the ramp end */
    double x_m[JC_PAPER_MAX_ROOTS];       /* r th: where the paper puts the jump */
    int first;                            /* index of the prediction, -1 if none */
    int truncated;                        /* 1 if more roots exist than fit */
    double cm_offset_m;                   /* d used (printed 2.65 cm for the paper) */
    double disc_mass_kg;                  /* M1 used in I_CM = M1 r^2 / 2 */
} jc_PaperResult;

/* One column of the paper's Table 1: what it printed and what it measured.
 * These are the only numbers of the paper that jumpcyl holds as data. */
typedef struct {
    double incline_deg;
    double printed_theta_rad;  /* "theoretical jumping angle" */
    double printed_x_m;        /* "theoretical jumping position" */
    double measured_x_m;       /* "experimental jumping position" */
    double measured_error_m;   /* its stated maximum error */
} jc_PaperTableRow;

/* The rows of Table 1 (15, 30, 45 degrees); returns their count. */
JC_API int jc_paper_table(const jc_PaperTableRow **rows);

/* 1 if body is the paper's cylinder (jc_paper_setup's body, part by part,
 * exactly), the only body whose jump sites Table 1 measured; 0 otherwise. */
JC_API int jc_paper_body_is(const jc_BodyDef *body);

/* Both sides of Eq. 9: th'^2/g (Eqs. 1, 5, 6) and cos(alpha)/(d cos th).
 * The model always starts at th = 0 at rest, as the paper assumes. */
JC_API double jc_paper_lhs(const jc_Model *model, double theta_rad);
JC_API double jc_paper_rhs(const jc_Model *model, double theta_rad);

/* Every intersection of the two sides with cos th > 0, th in (0, r-ramp end]. */
JC_API int jc_paper_solve(const jc_Model *model, jc_PaperResult *out, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* The exact rolling model: closed form while rolling (src/rolling.c)        */
/* ------------------------------------------------------------------------ */

typedef struct {
    double theta_rad;
    double omega_radps;     /* sign of the motion times sqrt(w^2) */
    double alpha_radps2;    /* th'' */
    double x_m;             /* centre's travel along the incline, r (th - th0) */
    double normal_N;        /* N, contact force along +y */
    double friction_N;      /* F, contact force along +x (downhill) */
    double kinetic_J, potential_J; /* potential relative to the start */
} jc_RollingState;

/* State on the rolling solution at th (w from the energy integral, taken
 * with the sign of omega0, or of the initial th'' when omega0 = 0).
 * JC_EINVAL if th is out of reach (w^2 < 0 there). */
JC_API int jc_rolling_state(const jc_Model *model, double theta_rad, jc_RollingState *out,
                     char *err, size_t err_len);

typedef struct {
    int found;          /* 0: does not happen before the rolling path ends */
    int grazing;        /* 1: the quantity touched zero without a clean sign change */
    jc_RollingState state; /* at the crossing */
} jc_RollingCrossing;

typedef enum {
    JC_ROLLING_END_RAMP_END,  /* reached the lower end of the ramp */
    JC_ROLLING_END_TURN_BACK, /* w = 0: rolls back (and rocks, if it started at rest) */
    JC_ROLLING_END_RAMP_TOP,  /* starts by rolling uphill, off the start of the ramp */
    JC_ROLLING_END_AT_REST    /* starts at rest in equilibrium */
} jc_RollingEnd;

typedef struct {
    /* First rolling N = 0. A DIAGNOSTIC, not the physical jump: with any finite
     * friction the cylinder slips first, and at this point F != 0. */
    jc_RollingCrossing liftoff;
    /* First |F| = mu_s N: where rolling without slipping ends. */
    jc_RollingCrossing slip;
    jc_RollingEnd end;          /* how the rolling path ends if nothing else happens */
    double end_theta_rad;    /* where it ends */
    double end_x_m;
} jc_RollingResult;

JC_API const char *jc_rolling_end_name(jc_RollingEnd end);

/* Follows the rolling solution from the start; finds the first N = 0 and the
 * first slip onset, each to ~1e-12 rad, by a search that cannot step over a
 * root window. */
JC_API int jc_rolling_predict(const jc_Model *model, jc_RollingResult *out, char *err, size_t err_len);

/* ------------------------------------------------------------------------ */
/* The full motion: rolling, sliding, flight, impacts (src/simulate.c)        */
/* ------------------------------------------------------------------------ */

typedef enum {
    JC_MODE_ROLLING, /* contact without slip: closed form (energy integral) */
    JC_MODE_SLIDING, /* contact with slip: ODE (DOP853) */
    JC_MODE_FLIGHT   /* no contact: ballistic, closed form */
} jc_Mode;

typedef enum {
    JC_EVENT_SLIP,          /* rolling -> sliding: |F| reached mu_s N */
    JC_EVENT_STICK,         /* sliding -> rolling: slip velocity 0, friction fits the cone */
    JC_EVENT_SLIP_REVERSAL, /* sliding -> sliding the other way */
    JC_EVENT_LIFTOFF,       /* contact -> flight: N = 0 */
    JC_EVENT_TOUCHDOWN,     /* impact that ends in contact */
    JC_EVENT_BOUNCE,        /* impact that ends in flight again */
    JC_EVENT_RAMP_END,      /* the centre passed the ramp's lower end */
    JC_EVENT_RAMP_TOP,      /* the centre went uphill past the start */
    JC_EVENT_PAINLEVE,      /* no consistent contact mode (stops the run, docs/physics.md §4a) */
    JC_EVENT_COUNT
} jc_EventKind;

typedef enum {
    JC_END_RAMP_END,   /* reached the lower end of the ramp */
    JC_END_RAMP_TOP,   /* went uphill past the start */
    JC_END_TIME_LIMIT, /* simulated time reached t_max_s */
    JC_END_EVENT_LIMIT,/* max_events events recorded */
    JC_END_PAINLEVE,   /* no consistent contact mode (Painleve): a physical end, not a failure */
    JC_END_REST,       /* at rest: in equilibrium, or stopped by rolling resistance */
    JC_END_STEP_LIMIT, /* a phase hit its bound on integration steps */
    JC_END_SAMPLE_LIMIT /* max_samples trajectory samples recorded */
} jc_Termination;
#define JC_END_AT_REST JC_END_REST /* the former name */

/* The body's state. C is the geometric centre, G the centre of mass. */
typedef struct {
    double t_s;
    double x_m, y_m;       /* centre C: along the incline from its start, height above the incline */
    double vx_mps, vy_mps; /* velocity of C */
    double theta_rad, omega_radps;
} jc_State;

typedef struct {
    jc_EventKind kind;
    jc_Mode mode_before, mode_after;
    jc_State state;            /* at the event (after the impulse, for impacts) */
    double slip_mps;           /* contact-point slip velocity x_C' - r w (before) */
    double normal_N, friction_N; /* contact force just before (0 in flight) */
    /* liftoff: */
    double flight_time_s;      /* until the next impact (or the end of the run) */
    double hop_height_m;       /* largest gap between rim and incline during the flight */
    double landing_x_m;        /* centre's x at the next impact (NaN if none) */
    /* touchdown, bounce: */
    double impact_speed_mps;   /* normal approach speed of the contact point */
    double impulse_normal_Ns, impulse_tangent_Ns;
} jc_Event;

typedef struct {
    jc_State state;
    jc_Mode mode;
    double cm_x_m, cm_y_m;           /* centre of mass G */
    double normal_N, friction_N;     /* contact force (0 in flight) */
    double slip_mps;                 /* x_C' - r w while in contact */
    double gap_m;                    /* lowest rim point above the incline (0 in contact) */
    double kinetic_J, potential_J;   /* potential relative to the start */
    double friction_loss_J, impact_loss_J; /* dissipated so far */
    double air_loss_J, rolling_resistance_loss_J;
} jc_Sample;

typedef struct {
    double kinetic_J, potential_J, friction_loss_J, impact_loss_J;
    double air_loss_J;              /* drag on the centre and on the spin */
    double rolling_resistance_loss_J;
    double balance_error_J; /* (K + U + losses) - (K0 + U0): integrator error */
} jc_EnergyReport;

typedef struct {
    double t_max_s;         /* simulated time limit, > 0 (default 60 s) */
    int max_events;         /* > 0 (default 10000) */
    /* Trajectory sample spacing: 0 (samples only at events) or [1e-9, 1e6] s.
     * The k-th fixed sample is at exactly k * sample_dt_s (an integer
     * counter, never an accumulated time), so their times strictly increase. */
    double sample_dt_s;
    /* Samples recorded at most (default 10^6); reaching it ends the run
     * with JC_END_SAMPLE_LIMIT, never silently. */
    int max_samples;
    double ode_rtol;        /* sliding integrator tolerances (default 1e-11, 1e-13) */
    double ode_atol;
    double event_tol_s;     /* event location tolerance in time (default 1e-12 s) */
    /* An impact whose rebound would rise less than this ends in contact:
     * the physical threshold that ends Zeno bounce sequences (default 1 um,
     * below the roughness of a real ramp). */
    double contact_height_m;
} jc_SimOptions;

JC_API jc_SimOptions jc_default_sim_options(void);
JC_API int jc_sim_options_validate(const jc_SimOptions *o, char *err, size_t err_len);

typedef struct {
    jc_Event *events;
    int event_count;
    jc_Sample *samples;
    int sample_count;
    jc_Termination termination;
    char termination_detail[160];
    jc_State final_state;
    jc_Mode final_mode;
    jc_EnergyReport energy;
    long ode_steps;          /* integrator steps taken (phases without a closed form) */
    /* Newton's and Poisson's laws can add kinetic energy at an impact of an
     * off-centre body when the contact sticks or its slip reverses during the
     * impulse (docs/physics.md §4); Stronge's law (the default) never does.
     * Such impacts are counted, not hidden; impact_loss_J includes their gains. */
    int energy_gaining_impacts;
    double largest_impact_gain_J;
    /* Excursions of the rolling path beyond the friction cone too small to
     * slip (docs/physics.md §4a, "Micro-slips"): rolled through as sticking, not events. */
    long micro_slips;
    /* > 0: the run ended in rolling that repeats for ever (no event over a
     * whole period); whole periods were skipped to the time limit. */
    double rocking_period_s;
} jc_Run;

/* A run's working memory (the rolling-time quadrature's and the root
 * polisher's): made once, then lent to any number of runs, one at a time,
 * so that a run allocates nothing (sweeps, fits, Monte Carlo). A thread
 * keeps its own. */
typedef struct jc_Workspace jc_Workspace;
JC_API jc_Workspace *jc_workspace_new(void); /* NULL when out of memory */
JC_API void jc_workspace_free(jc_Workspace *ws);

/* The setup's own start: at rest or rolling at theta0 with omega0, the
 * centre at x = 0 and height r. */
JC_API jc_State jc_start_state(const jc_Model *model);

/* Checks a state for jc_simulate_from: finite numbers, on the ramp
 * (0 <= x <= ramp length), not below the incline (y >= r), and not moving
 * into it from contact (vy >= 0 at y = r); t in [0, the time limit). */
JC_API int jc_start_validate(const jc_Model *model, const jc_State *start, const jc_SimOptions *options, char *err,
                             size_t err_len);

JC_API const char *jc_mode_name(jc_Mode mode);
JC_API const char *jc_event_name(jc_EventKind kind);
JC_API const char *jc_termination_name(jc_Termination t);

/* Simulates the setup from its start until a termination condition, keeping
 * every event and sample in memory (out->events, out->samples): for runs of
 * moderate length. *out is owned by the caller: free it with jc_run_free,
 * also after errors. The same as jc_simulate_stream with a recorder that
 * appends to the two arrays. */
JC_API int jc_simulate(const jc_Model *model, const jc_SimOptions *options, jc_Run *out,
                char *err, size_t err_len);
JC_API void jc_run_free(jc_Run *run);

/* Streaming: the simulation pushes each event and each trajectory sample to
 * a recorder as soon as it is complete, so memory does not grow with the
 * length of the run. Events arrive in time order and are never changed
 * after they are pushed: a lift-off (or a bounce into flight) is held back
 * until its flight has ended, so that its flight_time_s, hop_height_m and
 * landing_x_m are final; events that happen during that flight (a ramp end)
 * follow it. Samples arrive in time order, independently of events.
 *
 * Each callback returns JC_OK to go on; any other value stops the run, and
 * jc_simulate_stream returns it (JC_ESTOPPED for "stopped for the caller's
 * own reason", e.g. a failed write; values that are not status codes are
 * returned as JC_ESTOPPED). A NULL callback means "not wanted": with
 * sample == NULL no sample is even computed. */
typedef struct {
    void *ctx;
    int (*event)(void *ctx, const jc_Event *e);
    int (*sample)(void *ctx, const jc_Sample *s);
} jc_Recorder;

/* Like jc_simulate, but events and samples go to rec instead of arrays:
 * out->events and out->samples stay NULL, out->event_count and
 * out->sample_count count what was pushed, and every other field of *out is
 * set as by jc_simulate (identical results). */
JC_API int jc_simulate_stream(const jc_Model *model, const jc_SimOptions *options, const jc_Recorder *rec,
                       jc_Run *out, char *err, size_t err_len);
/* Simulates from any state of the body (a restart, a branch, a step of a
 * fit), streaming as jc_simulate_stream. In contact (y = r, vy = 0) the
 * run starts in the mode consistent with the forces (rolling when the
 * contact point does not slip and the cone holds, else sliding, or flight);
 * above the incline it starts in flight. The energies of its samples and
 * report are those of jc_kinetic_energy and jc_potential_energy (potential
 * relative to the setup's start); the balance is taken from this start.
 * ws: a workspace to use (no allocation in the run), or NULL to make one
 * for this run. With a recorder that does not allocate, a run with a
 * workspace allocates nothing. */
JC_API int jc_simulate_from(const jc_Model *model, const jc_State *start, const jc_SimOptions *options,
                            const jc_Recorder *rec, jc_Workspace *ws, jc_Run *out, char *err, size_t err_len);
/* The recorder jc_simulate uses: it appends to arrays->events and
 * arrays->samples (and their counts), which start zeroed and are freed with
 * jc_run_free. Wrap it to add checks of your own (a stop request). */
JC_API jc_Recorder jc_run_recorder(jc_Run *arrays);

/* What a run amounts to: its hops. A hop starts at a lift-off; bounces
 * continue it. */
typedef struct {
    int liftoffs;            /* lift-off events (hops) */
    int bounces;             /* impacts that ended in flight again */
    int first_liftoff;       /* event index, -1 if none */
    int largest_hop;         /* event index (lift-off or bounce) of the highest flight, -1 if none */
    double largest_hop_m;    /* its largest gap under the rim */
    double flight_time_s;    /* total time in flight */
    jc_State first_liftoff_state; /* the state at the first lift-off (zero if none) */
    int first_event;         /* index of the run's first event, -1 if none */
    jc_EventKind first_event_kind; /* its kind (JC_EVENT_COUNT if none) */
    int first_slip;          /* event index of the first slip (rolling -> sliding), -1 if none */
    jc_State first_slip_state; /* the state there (zero if none) */
} jc_RunSummary;

JC_API void jc_run_summarize(const jc_Run *run, jc_RunSummary *out);
/* The same accumulated event by event, without the array (streaming):
 * jc_summary_init, then jc_summary_add for each event with its index. */
JC_API void jc_summary_init(jc_RunSummary *out);
JC_API void jc_summary_add(jc_RunSummary *out, const jc_Event *e, int index);

/* Energies of a state (potential relative to the setup's start). */
JC_API double jc_kinetic_energy(const jc_Model *model, const jc_State *s);
JC_API double jc_potential_energy(const jc_Model *model, const jc_State *s);

/* ------------------------------------------------------------------------ */
/* Sample columns: one table for every table of samples (src/sample_columns.c) */
/* ------------------------------------------------------------------------ */

/* The columns of a trajectory sample (jc_Sample), in the order every table
 * of samples has them: the tool's `simulate --csv`, the page's CSV
 * download and its columns. Each name carries its unit's suffix. Column
 * JC_COL_MODE is the mode, a name (jc_mode_name); the others are numbers in
 * SI units. */
typedef enum {
    JC_COL_T_S, JC_COL_MODE, JC_COL_X_M, JC_COL_Y_M, JC_COL_VX_MPS, JC_COL_VY_MPS, JC_COL_THETA_RAD,
    JC_COL_OMEGA_RADPS, JC_COL_CM_X_M, JC_COL_CM_Y_M, JC_COL_NORMAL_N, JC_COL_FRICTION_N, JC_COL_SLIP_MPS,
    JC_COL_GAP_M, JC_COL_KINETIC_J, JC_COL_POTENTIAL_J, JC_COL_FRICTION_LOSS_J, JC_COL_IMPACT_LOSS_J,
    JC_COL_AIR_LOSS_J, JC_COL_ROLLING_RESISTANCE_LOSS_J,
    JC_SAMPLE_COLUMNS /* their number */
} jc_SampleColumnId;

typedef struct {
    const char *name;        /* "t_s", "mode", "x_m", ..., "rolling_resistance_loss_J" */
    const char *unit;        /* "s", "m", "m/s", "rad", "rad/s", "N", "J"; "" for the mode */
    const char *description; /* one line */
    int is_mode;             /* 1 for the mode column: a name, not a number */
    int digits;              /* significant digits of its text form (jc_sample_format) */
} jc_SampleColumn;

/* JC_SAMPLE_COLUMNS, for callers that read the table at run time. */
JC_API int jc_sample_column_count(void);
/* The column's row of the table; NULL when col is not a column. */
JC_API const jc_SampleColumn *jc_sample_column_info(int col);
/* The column named name ("normal_N"), or -1. */
JC_API int jc_sample_column_find(const char *name);
/* A sample's value in a column, SI; the mode column gives the jc_Mode as a
 * number. NaN when col is not a column. */
JC_API double jc_sample_value(const jc_Sample *s, int col);
/* A sample's value in a column as text: the mode's name, or the number
 * printed with the column's significant digits (%.*g). snprintf's return
 * (the length the text needs), or -1 when col is not a column. */
JC_API int jc_sample_format(const jc_Sample *s, int col, char *buf, size_t len);
/* Every column's text form in order, separated by commas: a CSV row
 * without its line end (the header: the names, separated by commas).
 * snprintf's return; JC_SAMPLE_ROW_MAX bytes always suffice. */
#define JC_SAMPLE_ROW_MAX 512
JC_API int jc_sample_format_row(const jc_Sample *s, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* JUMPCYL_JUMPCYL_H */
