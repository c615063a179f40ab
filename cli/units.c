/* Strict parsing of numbers with optional units: "10cm", "34.2g", "15deg". */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A unit is a power of ten (applied to the decimal exponent, so that "32.1g"
 * is exactly the double nearest 0.0321, as "0.0321" is) or a factor. */
typedef struct {
    const char *name;
    int pow10;
    double factor; /* to SI, applied after the power of ten */
} unit;

static const unit length_units[] = {{"m", 0, 1.0}, {"cm", -2, 1.0}, {"mm", -3, 1.0}, {"km", 3, 1.0}, {NULL, 0, 0}};
static const unit mass_units[] = {{"kg", 0, 1.0}, {"g", -3, 1.0}, {"mg", -6, 1.0}, {NULL, 0, 0}};
static const unit angle_units[] = {{"deg", 0, CLI_PI / 180.0}, {"rad", 0, 1.0}, {NULL, 0, 0}};
static const unit angular_speed_units[] = {{"rad/s", 0, 1.0}, {"deg/s", 0, CLI_PI / 180.0},
                                           {"rpm", 0, 2.0 * CLI_PI / 60.0}, {"rev/s", 0, 2.0 * CLI_PI},
                                           {NULL, 0, 0}};
static const unit acceleration_units[] = {{"m/s2", 0, 1.0}, {"m/s^2", 0, 1.0}, {"cm/s2", -2, 1.0}, {NULL, 0, 0}};
static const unit no_units[] = {{NULL, 0, 0}};

/* Re-reads the number text[0, len) with its decimal exponent shifted by p. */
static double shift_decimal(const char *text, size_t len, int p)
{
    char buf[128];
    if (len >= 96) return NAN;
    memcpy(buf, text, len);
    buf[len] = '\0';
    char *e = strpbrk(buf, "eE");
    long exp10 = 0;
    if (e) {
        exp10 = strtol(e + 1, NULL, 10);
        *e = '\0';
    }
    if (exp10 > 100000 || exp10 < -100000) return exp10 > 0 ? HUGE_VAL : 0.0;
    snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "e%ld", exp10 + p);
    return strtod(buf, NULL);
}

static const unit *units_for(cli_Quantity q)
{
    switch (q) {
    case Q_LENGTH: return length_units;
    case Q_MASS: return mass_units;
    case Q_ANGLE: return angle_units;
    case Q_ANGULAR_SPEED: return angular_speed_units;
    case Q_ACCELERATION: return acceleration_units;
    case Q_NUMBER: return no_units;
    }
    return no_units;
}

const char *cli_units_allowed(cli_Quantity q)
{
    switch (q) {
    case Q_LENGTH: return "m (default), cm, mm, km";
    case Q_MASS: return "kg (default), g, mg";
    case Q_ANGLE: return "deg (default), rad";
    case Q_ANGULAR_SPEED: return "rad/s (default), deg/s, rpm, rev/s";
    case Q_ACCELERATION: return "m/s2 (default), m/s^2, cm/s2";
    case Q_NUMBER: return "none (a plain number)";
    }
    return "";
}

int cli_parse_quantity(const char *text, cli_Quantity q, double *out, char *err, size_t err_len)
{
    if (!text || !*text) {
        snprintf(err, err_len, "empty value (expected a number)");
        return -1;
    }
    /* strtod would skip leading blanks and accept "nan", "inf" and hex; the
     * token must start like a decimal number. */
    const char c0 = text[0];
    const char c1 = (c0 == '+' || c0 == '-') ? text[1] : c0;
    if (!((c1 >= '0' && c1 <= '9') || c1 == '.')) {
        snprintf(err, err_len, "'%s' is not a number", text);
        return -1;
    }
    const char *digits = (c0 == '+' || c0 == '-') ? text + 1 : text;
    if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
        snprintf(err, err_len, "'%s' is not a decimal number", text);
        return -1;
    }
    errno = 0;
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text) {
        snprintf(err, err_len, "'%s' is not a number", text);
        return -1;
    }
    if (errno == ERANGE && fabs(v) > 1.0) {
        snprintf(err, err_len, "'%s' is too large", text);
        return -1;
    }
    if (!isfinite(v)) {
        snprintf(err, err_len, "'%s' is not a finite number", text);
        return -1;
    }
    const char *suffix = end;
    if (*suffix == ' ') suffix++; /* "10 cm" as one quoted argument */
    double factor = 1.0;
    if (q == Q_ANGLE) factor = CLI_PI / 180.0; /* plain angles are degrees */
    if (*suffix) {
        const unit *u = units_for(q);
        for (; u->name; ++u)
            if (strcmp(suffix, u->name) == 0) break;
        if (!u->name) {
            snprintf(err, err_len, "'%s' has an unknown unit '%s' (allowed: %s)", text, suffix,
                     cli_units_allowed(q));
            return -1;
        }
        factor = u->factor;
        if (u->pow10 != 0) v = shift_decimal(text, (size_t)(end - text), u->pow10);
    }
    *out = factor == 1.0 ? v : v * factor;
    if (!isfinite(*out)) {
        snprintf(err, err_len, "'%s' is too large", text);
        return -1;
    }
    return 0;
}
