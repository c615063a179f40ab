/*
 * The table of sample columns (src/sample_columns.c): every column against
 * the jc_Sample field it must read (listed here by hand), names that carry
 * their units, the text forms against printf with the stated digits, rows
 * against their cells, and the layout `simulate --csv` has always written.
 */
#include "test.h"

#include <jumpcyl/jumpcyl.h>

#include <stdlib.h>

/* Each column's field, written out independently of the library's table. */
static double *field(jc_Sample *s, const char *name)
{
    static const char *const names[] = {"t_s", "x_m", "y_m", "vx_mps", "vy_mps", "theta_rad", "omega_radps",
                                        "cm_x_m", "cm_y_m", "normal_N", "friction_N", "slip_mps", "gap_m",
                                        "kinetic_J", "potential_J", "friction_loss_J", "impact_loss_J",
                                        "air_loss_J", "rolling_resistance_loss_J"};
    double *const fields[] = {&s->state.t_s, &s->state.x_m, &s->state.y_m, &s->state.vx_mps, &s->state.vy_mps,
                              &s->state.theta_rad, &s->state.omega_radps, &s->cm_x_m, &s->cm_y_m, &s->normal_N,
                              &s->friction_N, &s->slip_mps, &s->gap_m, &s->kinetic_J, &s->potential_J,
                              &s->friction_loss_J, &s->impact_loss_J, &s->air_loss_J,
                              &s->rolling_resistance_loss_J};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (strcmp(names[i], name) == 0) return fields[i];
    return NULL;
}

/* A sample whose fields all differ: field k holds 1000 + k + k / 7. */
static jc_Sample distinct_sample(void)
{
    jc_Sample s;
    memset(&s, 0, sizeof s);
    s.mode = JC_MODE_SLIDING;
    for (int c = 0; c < jc_sample_column_count(); ++c) {
        double *f = field(&s, jc_sample_column_info(c)->name);
        if (f) *f = 1000.0 + c + c / 7.0;
    }
    return s;
}

/* The layout of the tool's CSV since it was first written: the order and
 * the names every table of samples keeps. */
#define CSV_HEADER                                                                                              \
    "t_s,mode,x_m,y_m,vx_mps,vy_mps,theta_rad,omega_radps,cm_x_m,cm_y_m,normal_N,friction_N,slip_mps,gap_m,"     \
    "kinetic_J,potential_J,friction_loss_J,impact_loss_J,air_loss_J,rolling_resistance_loss_J"

static int test_layout(void)
{
    ENSURE(jc_sample_column_count() == JC_SAMPLE_COLUMNS);
    ENSURE(JC_SAMPLE_COLUMNS == 20);
    char header[1024] = "";
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        if (c) strcat(header, ",");
        strcat(header, jc_sample_column_info(c)->name);
    }
    ENSURE_MSG(strcmp(header, CSV_HEADER) == 0, "%s", header);
    /* The enum names the same columns. */
    ENSURE(strcmp(jc_sample_column_info(JC_COL_MODE)->name, "mode") == 0);
    ENSURE(strcmp(jc_sample_column_info(JC_COL_GAP_M)->name, "gap_m") == 0);
    ENSURE(strcmp(jc_sample_column_info(JC_COL_ROLLING_RESISTANCE_LOSS_J)->name, "rolling_resistance_loss_J") == 0);
    ENSURE(jc_sample_column_info(-1) == NULL && jc_sample_column_info(JC_SAMPLE_COLUMNS) == NULL);
    return 0;
}

/* Every name ends with its unit's suffix; every column has a description. */
static int test_names_carry_units(void)
{
    static const struct { const char *unit, *suffix; } suffixes[] = {
        {"s", "_s"}, {"m", "_m"}, {"m/s", "_mps"}, {"rad", "_rad"}, {"rad/s", "_radps"}, {"N", "_N"}, {"J", "_J"}};
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        const jc_SampleColumn *in = jc_sample_column_info(c);
        ENSURE(in->description && strlen(in->description) > 5);
        if (in->is_mode) {
            ENSURE(c == JC_COL_MODE && strcmp(in->unit, "") == 0);
            continue;
        }
        const char *suffix = NULL;
        for (size_t k = 0; k < sizeof suffixes / sizeof suffixes[0]; ++k)
            if (strcmp(in->unit, suffixes[k].unit) == 0) suffix = suffixes[k].suffix;
        ENSURE_MSG(suffix != NULL, "%s: unit '%s'", in->name, in->unit);
        const size_t n = strlen(in->name), k = strlen(suffix);
        ENSURE_MSG(n > k && strcmp(in->name + n - k, suffix) == 0, "%s: unit %s", in->name, in->unit);
        ENSURE(in->digits == 9 || in->digits == 12);
        for (int d = 0; d < c; ++d) ENSURE(strcmp(jc_sample_column_info(d)->name, in->name) != 0);
    }
    return 0;
}

static int test_values_and_find(void)
{
    jc_Sample s = distinct_sample();
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        const char *name = jc_sample_column_info(c)->name;
        ENSURE(jc_sample_column_find(name) == c);
        if (c == JC_COL_MODE) {
            ENSURE(jc_sample_value(&s, c) == (double)JC_MODE_SLIDING);
            continue;
        }
        double *f = field(&s, name);
        ENSURE_MSG(f != NULL, "%s", name);
        ENSURE_MSG(jc_sample_value(&s, c) == *f, "%s: %.17g vs %.17g", name, jc_sample_value(&s, c), *f);
    }
    ENSURE(jc_sample_column_find("x") == -1 && jc_sample_column_find("") == -1 && jc_sample_column_find(NULL) == -1);
    ENSURE(isnan(jc_sample_value(&s, -1)) && isnan(jc_sample_value(&s, JC_SAMPLE_COLUMNS)));
    return 0;
}

/* A third in each column: 12 significant digits for the state and the
 * energies, 9 for forces, slip, gap and losses (what the CSV always had). */
static int test_text_forms(void)
{
    jc_Sample s;
    memset(&s, 0, sizeof s);
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        double *f = field(&s, jc_sample_column_info(c)->name);
        if (f) *f = 1.0 / 3.0;
    }
    static const char *const nine[] = {"normal_N", "friction_N", "slip_mps", "gap_m", "friction_loss_J",
                                       "impact_loss_J", "air_loss_J", "rolling_resistance_loss_J"};
    char cell[64];
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        const char *name = jc_sample_column_info(c)->name;
        const int n = jc_sample_format(&s, c, cell, sizeof cell);
        ENSURE(n == (int)strlen(cell));
        if (c == JC_COL_MODE) {
            ENSURE(strcmp(cell, "rolling") == 0);
            continue;
        }
        int short_form = 0;
        for (size_t k = 0; k < sizeof nine / sizeof nine[0]; ++k) short_form |= strcmp(nine[k], name) == 0;
        ENSURE_MSG(strcmp(cell, short_form ? "0.333333333" : "0.333333333333") == 0, "%s: %s", name, cell);
    }
    s.mode = JC_MODE_FLIGHT;
    ENSURE(jc_sample_format(&s, JC_COL_MODE, cell, sizeof cell) == 6 && strcmp(cell, "flight") == 0);
    ENSURE(jc_sample_format(&s, JC_SAMPLE_COLUMNS, cell, sizeof cell) == -1);
    /* Truncated as snprintf truncates, with the length it needed. */
    ENSURE(jc_sample_format(&s, JC_COL_T_S, cell, 4) == 14 && strcmp(cell, "0.3") == 0);
    return 0;
}

/* A row is the cells joined by commas, for random samples of every mode,
 * and the longest row fits JC_SAMPLE_ROW_MAX. */
static int test_rows(void)
{
    uint64_t rng = 0x5eed5a3c01u;
    char row[JC_SAMPLE_ROW_MAX], joined[JC_SAMPLE_ROW_MAX * 2], cell[64];
    for (int trial = 0; trial < 3000; ++trial) {
        jc_Sample s;
        memset(&s, 0, sizeof s);
        s.mode = (jc_Mode)(trial % 3);
        for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
            double *f = field(&s, jc_sample_column_info(c)->name);
            if (!f) continue;
            const double mag = pow(10.0, test_uniform(&rng, -320.0, 308.0));
            *f = trial % 97 == 0 ? -1.2345678901234567e-308 : (test_uniform(&rng, -1.0, 1.0) * mag);
            if (trial % 101 == 0) *f = c % 2 ? NAN : -INFINITY;
        }
        joined[0] = '\0';
        for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
            jc_sample_format(&s, c, cell, sizeof cell);
            if (c) strcat(joined, ",");
            strcat(joined, cell);
        }
        const int n = jc_sample_format_row(&s, row, sizeof row);
        ENSURE_MSG(n < JC_SAMPLE_ROW_MAX && n == (int)strlen(joined), "%d bytes", n);
        ENSURE_MSG(strcmp(row, joined) == 0, "\n%s\n%s", row, joined);
    }
    return 0;
}

int main(void)
{
    RUN_TEST(test_layout);
    RUN_TEST(test_names_carry_units);
    RUN_TEST(test_values_and_find);
    RUN_TEST(test_text_forms);
    RUN_TEST(test_rows);
    TEST_MAIN_END();
}
