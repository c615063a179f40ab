/* Strict parsing of numbers with optional units: "10cm", "34.2g", "15deg". */
#include "cli.h"

#include <errno.h>
#include <float.h>
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
static const unit time_units[] = {{"s", 0, 1.0}, {"ms", -3, 1.0}, {"us", -6, 1.0}, {NULL, 0, 0}};
static const unit density_units[] = {{"kg/m3", 0, 1.0}, {"kg/m^3", 0, 1.0}, {"g/cm3", 3, 1.0}, {NULL, 0, 0}};
static const unit spin_drag_units[] = {{"N m s2", 0, 1.0}, {"kg m2", 0, 1.0}, {NULL, 0, 0}};
static const unit no_units[] = {{NULL, 0, 0}};

/* Numbers longer than this are refused: far beyond the 17 significant digits
 * a double holds, and it keeps the rewritten number in a stack buffer. */
#define NUMBER_MAX_CHARS 256

/* Length of the decimal number at the start of text: [+-]digits[.digits]
 * [(e|E)[+-]digits], at least one mantissa digit; 0 if there is none. Our
 * own scan, not strtod's end pointer, so that "inf", "nan", hexadecimal,
 * leading blanks and locale forms can never slip through. *exp_at receives
 * the offset of the 'e' (or the length when there is no exponent). */
static size_t scan_decimal(const char *text, size_t *exp_at)
{
    size_t i = (text[0] == '+' || text[0] == '-') ? 1 : 0, digits = 0;
    for (; text[i] >= '0' && text[i] <= '9'; ++i) ++digits;
    if (text[i] == '.')
        for (++i; text[i] >= '0' && text[i] <= '9'; ++i) ++digits;
    if (digits == 0) return 0;
    *exp_at = i;
    if (text[i] != 'e' && text[i] != 'E') return i;
    size_t j = i + 1;
    if (text[j] == '+' || text[j] == '-') ++j;
    if (!(text[j] >= '0' && text[j] <= '9')) return i; /* "1e" or "5em": the 'e' starts the unit */
    while (text[j] >= '0' && text[j] <= '9') ++j;
    return j;
}

/* The decimal exponent written at text[exp_at, len), saturated far outside
 * the double range so that no digit string can overflow it. */
static long read_exponent(const char *text, size_t exp_at, size_t len)
{
    if (exp_at >= len) return 0;
    size_t i = exp_at + 1;
    const int negative = text[i] == '-';
    if (text[i] == '+' || text[i] == '-') ++i;
    long e = 0;
    for (; i < len; ++i)
        if (e < 100000) e = 10 * e + (text[i] - '0');
    return negative ? -e : e;
}

/* Reads the number text[0, len) with its decimal exponent shifted by p, so
 * that a unit's power of ten is applied exactly ("32.1g" is 32.1e-3).
 * Returns 0, or +1 on overflow, -1 on underflow (a nonzero number that
 * rounds to zero or to a subnormal double). */
static int read_decimal(const char *text, size_t len, size_t exp_at, int p, double *out)
{
    char buf[NUMBER_MAX_CHARS + 32];
    const long e = read_exponent(text, exp_at, len) + p;
    snprintf(buf, sizeof buf, "%.*se%ld", (int)exp_at, text, e);
    errno = 0;
    const double v = strtod(buf, NULL);
    *out = v;
    if (errno == ERANGE && fabs(v) > 1.0) return 1;
    if (errno == ERANGE || (v != 0.0 && fabs(v) < DBL_MIN)) return -1;
    return 0;
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
    case Q_TIME: return time_units;
    case Q_DENSITY: return density_units;
    case Q_SPIN_DRAG: return spin_drag_units;
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
    case Q_TIME: return "s (default), ms, us";
    case Q_DENSITY: return "kg/m3 (default), kg/m^3, g/cm3";
    case Q_SPIN_DRAG: return "N m s2 (default), kg m2";
    }
    return "";
}

/* The unit after the number: "" (none), or one blank and then the unit
 * ("10 cm", as one quoted argument). Returns it, or NULL for blanks that do
 * not lead to a unit. */
static const char *unit_text(const char *after_number)
{
    if (after_number[0] != ' ') return after_number;
    if (after_number[1] == '\0' || after_number[1] == ' ') return NULL;
    return after_number + 1;
}

static const unit *find_unit(cli_Quantity q, const char *name)
{
    for (const unit *u = units_for(q); u->name; ++u)
        if (strcmp(name, u->name) == 0) return u;
    return NULL;
}

/* The number text[0, len) times its unit, into SI, or a message: overflow,
 * and underflow to 0 or to a subnormal, are errors, not silent changes. */
static int to_si(const char *text, size_t len, size_t exp_at, int pow10, double factor, double *out, char *err,
                 size_t err_len)
{
    double v;
    const int range = read_decimal(text, len, exp_at, pow10, &v);
    if (range == 0 && factor != 1.0) v *= factor;
    if (range > 0 || !isfinite(v)) {
        snprintf(err, err_len, "'%s' is too large (allowed: magnitudes up to %.3g in SI units)", text, DBL_MAX);
        return -1;
    }
    if (range < 0 || (v != 0.0 && fabs(v) < DBL_MIN)) {
        snprintf(err, err_len, "'%s' is too small (allowed: 0, or magnitudes from %.3g in SI units)", text, DBL_MIN);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_parse_quantity(const char *text, cli_Quantity q, double *out, char *err, size_t err_len)
{
    if (!text || !*text) {
        snprintf(err, err_len, "empty value (expected a number)");
        return -1;
    }
    size_t exp_at = 0;
    const size_t len = scan_decimal(text, &exp_at);
    if (len == 0 || len > NUMBER_MAX_CHARS) {
        if (len == 0) snprintf(err, err_len, "'%s' is not a number", text);
        else snprintf(err, err_len, "'%.40s...' is too long for a number (allowed: at most %d characters)", text,
                      NUMBER_MAX_CHARS);
        return -1;
    }
    const char *suffix = unit_text(text + len);
    if (!suffix) {
        snprintf(err, err_len, "'%s' has stray blanks (allowed: one blank between number and unit)", text);
        return -1;
    }
    double factor = q == Q_ANGLE ? CLI_PI / 180.0 : 1.0; /* plain angles are degrees */
    if (!*suffix) return to_si(text, len, exp_at, 0, factor, out, err, err_len);
    const unit *u = find_unit(q, suffix);
    if (!u) {
        const size_t sign = text[0] == '+' || text[0] == '-';
        const int hex = (suffix[0] == 'x' || suffix[0] == 'X') && len == sign + 1 && text[sign] == '0';
        if (hex) snprintf(err, err_len, "'%s' is not a decimal number (hexadecimal is not accepted)", text);
        else snprintf(err, err_len, "'%s' has an unknown unit '%s' (allowed: %s)", text, suffix, cli_units_allowed(q));
        return -1;
    }
    return to_si(text, len, exp_at, u->pow10, u->factor, out, err, err_len);
}
