/*
 * The table of sample columns: names with their units, a line each, and
 * how a sample's value reads in each, for every table of samples (the
 * tool's CSV, the page's CSV and columns). One row per field of jc_Sample,
 * in the order of jc_SampleColumnId.
 */
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* Positions, velocities, angles and energies are written with 12
 * significant digits; forces, slip, gap and the losses, which come from
 * differences and integrals, with 9. */
#define DIGITS_STATE 12
#define DIGITS_DERIVED 9

/* The table: X_NUMBER(id, name, unit, description, digits, field of
 * jc_Sample) and X_MODE(id, name, description), in the order of
 * jc_SampleColumnId (checked by tests/test_sample_columns.c). */
#define SAMPLE_COLUMNS(X_NUMBER, X_MODE)                                                                             \
    X_NUMBER(T_S, "t_s", "s", "time since the start", DIGITS_STATE, state.t_s)                                       \
    X_MODE(MODE, "mode", "rolling, sliding or flight")                                                               \
    X_NUMBER(X_M, "x_m", "m", "centre C along the incline from its start", DIGITS_STATE, state.x_m)                  \
    X_NUMBER(Y_M, "y_m", "m", "centre C above the incline", DIGITS_STATE, state.y_m)                                 \
    X_NUMBER(VX_MPS, "vx_mps", "m/s", "velocity of C along the incline", DIGITS_STATE, state.vx_mps)                 \
    X_NUMBER(VY_MPS, "vy_mps", "m/s", "velocity of C along the incline's outward normal", DIGITS_STATE,              \
             state.vy_mps)                                                                                           \
    X_NUMBER(THETA_RAD, "theta_rad", "rad", "angle of C -> G from the incline's outward normal", DIGITS_STATE,       \
             state.theta_rad)                                                                                        \
    X_NUMBER(OMEGA_RADPS, "omega_radps", "rad/s", "angular velocity (positive rolling downhill)", DIGITS_STATE,      \
             state.omega_radps)                                                                                      \
    X_NUMBER(CM_X_M, "cm_x_m", "m", "centre of mass G along the incline", DIGITS_STATE, cm_x_m)                      \
    X_NUMBER(CM_Y_M, "cm_y_m", "m", "centre of mass G above the incline", DIGITS_STATE, cm_y_m)                      \
    X_NUMBER(NORMAL_N, "normal_N", "N", "normal contact force (0 in flight)", DIGITS_DERIVED, normal_N)              \
    X_NUMBER(FRICTION_N, "friction_N", "N", "friction force along the incline (0 in flight)", DIGITS_DERIVED,        \
             friction_N)                                                                                             \
    X_NUMBER(SLIP_MPS, "slip_mps", "m/s", "slip velocity of the contact point, x_C' - r w (0 in flight)",            \
             DIGITS_DERIVED, slip_mps)                                                                               \
    X_NUMBER(GAP_M, "gap_m", "m", "lowest rim point above the incline (0 in contact)", DIGITS_DERIVED, gap_m)        \
    X_NUMBER(KINETIC_J, "kinetic_J", "J", "kinetic energy", DIGITS_STATE, kinetic_J)                                 \
    X_NUMBER(POTENTIAL_J, "potential_J", "J", "potential energy relative to the start", DIGITS_STATE,                \
             potential_J)                                                                                            \
    X_NUMBER(FRICTION_LOSS_J, "friction_loss_J", "J", "energy dissipated by friction so far", DIGITS_DERIVED,        \
             friction_loss_J)                                                                                        \
    X_NUMBER(IMPACT_LOSS_J, "impact_loss_J", "J", "energy lost in impacts so far", DIGITS_DERIVED, impact_loss_J)    \
    X_NUMBER(AIR_LOSS_J, "air_loss_J", "J", "energy lost to the air so far", DIGITS_DERIVED, air_loss_J)             \
    X_NUMBER(ROLLING_RESISTANCE_LOSS_J, "rolling_resistance_loss_J", "J", "energy lost to rolling resistance so far", \
             DIGITS_DERIVED, rolling_resistance_loss_J)

typedef struct {
    jc_SampleColumn info;
    size_t offset; /* of the double in jc_Sample (not for the mode) */
} column;

#define INFO_NUMBER(id, name, unit, what, digits, field) \
    [JC_COL_##id] = {{name, unit, what, 0, digits}, offsetof(jc_Sample, field)},
#define INFO_MODE(id, name, what) [JC_COL_##id] = {{name, "", what, 1, 0}, 0},
static const column columns[JC_SAMPLE_COLUMNS] = {SAMPLE_COLUMNS(INFO_NUMBER, INFO_MODE)};

/* A row's format, ",%.*g,%s,..." (the leading comma skipped), and its
 * arguments: one snprintf per row. */
#define FORMAT_NUMBER(id, name, unit, what, digits, field) ",%.*g"
#define FORMAT_MODE(id, name, what) ",%s"
#define ARGS_NUMBER(id, name, unit, what, digits, field) , digits, s->field
#define ARGS_MODE(id, name, what) , jc_mode_name(s->mode)

int jc_sample_column_count(void)
{
    return JC_SAMPLE_COLUMNS;
}

const jc_SampleColumn *jc_sample_column_info(int col)
{
    return col >= 0 && col < JC_SAMPLE_COLUMNS ? &columns[col].info : NULL;
}

int jc_sample_column_find(const char *name)
{
    for (int c = 0; name && c < JC_SAMPLE_COLUMNS; ++c)
        if (strcmp(columns[c].info.name, name) == 0) return c;
    return -1;
}

double jc_sample_value(const jc_Sample *s, int col)
{
    if (col < 0 || col >= JC_SAMPLE_COLUMNS) return NAN;
    if (columns[col].info.is_mode) return (double)s->mode;
    double v;
    memcpy(&v, (const char *)s + columns[col].offset, sizeof v);
    return v;
}

int jc_sample_format_row(const jc_Sample *s, char *buf, size_t len)
{
    return snprintf(buf, len, &SAMPLE_COLUMNS(FORMAT_NUMBER, FORMAT_MODE)[1] SAMPLE_COLUMNS(ARGS_NUMBER, ARGS_MODE));
}

int jc_sample_format(const jc_Sample *s, int col, char *buf, size_t len)
{
    if (col < 0 || col >= JC_SAMPLE_COLUMNS) return -1;
    if (columns[col].info.is_mode) return snprintf(buf, len, "%s", jc_mode_name(s->mode));
    return snprintf(buf, len, "%.*g", columns[col].info.digits, jc_sample_value(s, col));
}
