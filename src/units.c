/* Numbers with units: strict reading ("10cm", "34.2g", "15deg") into SI,
 * and writing back as the shortest text that reads back to the same
 * double. */
#include "internal.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* A unit is a power of ten (applied to the decimal exponent, so that "32.1g"
 * is exactly the double nearest 0.0321, as "0.0321" is) or a factor. */
typedef struct {
    const char *name;
    int pow10;
    double factor;  /* to SI, applied after the power of ten */
    double from_si; /* 1 / factor, as written (180 / pi, not 1 / (pi / 180)) */
} unit;

static const unit length_units[] = {{"m", 0, 1.0, 1.0}, {"cm", -2, 1.0, 1.0}, {"mm", -3, 1.0, 1.0},
                                    {"km", 3, 1.0, 1.0}, {NULL, 0, 0, 0}};
static const unit mass_units[] = {{"kg", 0, 1.0, 1.0}, {"g", -3, 1.0, 1.0}, {"mg", -6, 1.0, 1.0}, {NULL, 0, 0, 0}};
static const unit angle_units[] = {{"deg", 0, PI / 180.0, 180.0 / PI}, {"rad", 0, 1.0, 1.0}, {NULL, 0, 0, 0}};
static const unit angular_speed_units[] = {{"rad/s", 0, 1.0, 1.0}, {"deg/s", 0, PI / 180.0, 180.0 / PI},
                                           {"rpm", 0, 2.0 * PI / 60.0, 60.0 / (2.0 * PI)},
                                           {"rev/s", 0, 2.0 * PI, 1.0 / (2.0 * PI)}, {NULL, 0, 0, 0}};
static const unit acceleration_units[] = {{"m/s2", 0, 1.0, 1.0}, {"m/s^2", 0, 1.0, 1.0}, {"cm/s2", -2, 1.0, 1.0},
                                          {NULL, 0, 0, 0}};
static const unit time_units[] = {{"s", 0, 1.0, 1.0}, {"ms", -3, 1.0, 1.0}, {"us", -6, 1.0, 1.0}, {NULL, 0, 0, 0}};
static const unit density_units[] = {{"kg/m3", 0, 1.0, 1.0}, {"kg/m^3", 0, 1.0, 1.0}, {"g/cm3", 3, 1.0, 1.0},
                                     {NULL, 0, 0, 0}};
static const unit spin_drag_units[] = {{"N m s2", 0, 1.0, 1.0}, {"kg m2", 0, 1.0, 1.0}, {NULL, 0, 0, 0}};
static const unit no_units[] = {{NULL, 0, 0, 0}};

static const unit *units_of(jc_Quantity q)
{
    switch (q) {
    case JC_Q_LENGTH: return length_units;
    case JC_Q_MASS: return mass_units;
    case JC_Q_ANGLE: return angle_units;
    case JC_Q_ANGULAR_SPEED: return angular_speed_units;
    case JC_Q_ACCELERATION: return acceleration_units;
    case JC_Q_TIME: return time_units;
    case JC_Q_DENSITY: return density_units;
    case JC_Q_SPIN_DRAG: return spin_drag_units;
    case JC_Q_NUMBER:
    case JC_Q_NAME: break;
    }
    return no_units;
}

const char *jc_quantity_name(jc_Quantity q)
{
    switch (q) {
    case JC_Q_LENGTH: return "length";
    case JC_Q_MASS: return "mass";
    case JC_Q_ANGLE: return "angle";
    case JC_Q_ANGULAR_SPEED: return "angular speed";
    case JC_Q_ACCELERATION: return "acceleration";
    case JC_Q_NUMBER: return "number";
    case JC_Q_TIME: return "time";
    case JC_Q_DENSITY: return "density";
    case JC_Q_SPIN_DRAG: return "spin drag";
    case JC_Q_NAME: return "name";
    }
    return "";
}

const char *jc_quantity_si_unit(jc_Quantity q)
{
    switch (q) {
    case JC_Q_ANGLE: return "rad";
    case JC_Q_NUMBER:
    case JC_Q_NAME: return "";
    default: return units_of(q)[0].name;
    }
}

const char *jc_quantity_unit(jc_Quantity q, int i, double *to_si)
{
    const unit *u = units_of(q);
    for (int k = 0; k < i; ++k)
        if (!u[k].name) return NULL;
    if (i < 0 || !u[i].name) return NULL;
    if (to_si) *to_si = pow(10.0, u[i].pow10) * u[i].factor;
    return u[i].name;
}

const char *jc_quantity_units_text(jc_Quantity q)
{
    switch (q) {
    case JC_Q_LENGTH: return "m (default), cm, mm, km";
    case JC_Q_MASS: return "kg (default), g, mg";
    case JC_Q_ANGLE: return "deg (default), rad";
    case JC_Q_ANGULAR_SPEED: return "rad/s (default), deg/s, rpm, rev/s";
    case JC_Q_ACCELERATION: return "m/s2 (default), m/s^2, cm/s2";
    case JC_Q_NUMBER: return "none (a plain number)";
    case JC_Q_TIME: return "s (default), ms, us";
    case JC_Q_DENSITY: return "kg/m3 (default), kg/m^3, g/cm3";
    case JC_Q_SPIN_DRAG: return "N m s2 (default), kg m2";
    case JC_Q_NAME: return "a name";
    }
    return "";
}

/* ---- reading ---- */

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

/* The unit after the number: "" (none), or one blank and then the unit
 * ("10 cm", as one quoted argument). Returns it, or NULL for blanks that do
 * not lead to a unit. */
static const char *unit_text(const char *after_number)
{
    if (after_number[0] != ' ') return after_number;
    if (after_number[1] == '\0' || after_number[1] == ' ') return NULL;
    return after_number + 1;
}

/* The forms the tool prints in figures and titles (UTF-8: "30°", "9.78
 * m/s²"), read as the ASCII units they stand for. Not units of their own:
 * the lists above, which jc_quantity_unit enumerates, stay ASCII. */
static const struct {
    const char *printed, *ascii;
} printed_forms[] = {{"\u00b0", "deg"},          {"\u00b0/s", "deg/s"},      {"m/s\u00b2", "m/s2"},
                     {"cm/s\u00b2", "cm/s2"},    {"kg/m\u00b3", "kg/m3"},    {"g/cm\u00b3", "g/cm3"},
                     {"N m s\u00b2", "N m s2"},  {"kg m\u00b2", "kg m2"}};

static const unit *find_unit(jc_Quantity q, const char *name)
{
    for (size_t k = 0; k < sizeof printed_forms / sizeof printed_forms[0]; ++k)
        if (strcmp(name, printed_forms[k].printed) == 0) name = printed_forms[k].ascii;
    for (const unit *u = units_of(q); u->name; ++u)
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
    if (range > 0 || !isfinite(v))
        return jc_fail(err, err_len, JC_EINVAL, "'%s' is too large (allowed: magnitudes up to %.3g in SI units)",
                       text, DBL_MAX);
    if (range < 0 || (v != 0.0 && fabs(v) < DBL_MIN))
        return jc_fail(err, err_len, JC_EINVAL, "'%s' is too small (allowed: 0, or magnitudes from %.3g in SI units)",
                       text, DBL_MIN);
    *out = v;
    return JC_OK;
}

int jc_quantity_parse(const char *text, jc_Quantity q, double *out, char *err, size_t err_len)
{
    if (q == JC_Q_NAME) return jc_fail(err, err_len, JC_EINVAL, "a name is read with jc_param_parse, not as a number");
    if (!text || !*text) return jc_fail(err, err_len, JC_EINVAL, "empty value (expected a number)");
    size_t exp_at = 0;
    const size_t len = scan_decimal(text, &exp_at);
    if (len == 0) return jc_fail(err, err_len, JC_EINVAL, "'%s' is not a number", text);
    if (len > NUMBER_MAX_CHARS)
        return jc_fail(err, err_len, JC_EINVAL, "'%.40s...' is too long for a number (allowed: at most %d characters)",
                       text, NUMBER_MAX_CHARS);
    const char *suffix = unit_text(text + len);
    if (!suffix)
        return jc_fail(err, err_len, JC_EINVAL, "'%s' has stray blanks (allowed: one blank between number and unit)",
                       text);
    const double factor = q == JC_Q_ANGLE ? PI / 180.0 : 1.0; /* plain angles are degrees */
    if (!*suffix) return to_si(text, len, exp_at, 0, factor, out, err, err_len);
    const unit *u = find_unit(q, suffix);
    if (!u) {
        const size_t sign = text[0] == '+' || text[0] == '-';
        const int hex = (suffix[0] == 'x' || suffix[0] == 'X') && len == sign + 1 && text[sign] == '0';
        if (hex) return jc_fail(err, err_len, JC_EINVAL, "'%s' is not a decimal number (hexadecimal is not accepted)", text);
        return jc_fail(err, err_len, JC_EINVAL, "'%s' has an unknown unit '%s' (allowed: %s)", text, suffix,
                       jc_quantity_units_text(q));
    }
    return to_si(text, len, exp_at, u->pow10, u->factor, out, err, err_len);
}

/* ---- writing ---- */

/* The shortest %g form of v that reads back to v exactly (%.17g always does). */
static void shortest(double v, char *buf, size_t len)
{
    for (int prec = 1; prec <= 17; ++prec) {
        snprintf(buf, len, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) return;
    }
}

/* v times 10^shift as a decimal, written by moving the decimal point of
 * v's shortest form: the reader applies a unit's power of ten to the
 * decimal exponent, so "3.21 cm" reads back to exactly the double of
 * "0.0321". */
static void shifted(double v, int shift, char *buf, size_t len)
{
    char e[40];
    int prec = 0;
    for (; prec < 17; ++prec) {
        snprintf(e, sizeof e, "%.*e", prec, v);
        if (strtod(e, NULL) == v) break;
    }
    /* e: [-]d.ddde[+-]xx: the digits and the exponent of the first one */
    const int neg = e[0] == '-';
    char digits[24];
    int nd = 0;
    const char *p = e + neg;
    for (; *p && *p != 'e'; ++p)
        if (*p >= '0' && *p <= '9' && nd < 23) digits[nd++] = *p;
    digits[nd] = '\0';
    const int exp10 = atoi(p + 1) + shift;
    while (nd > 1 && digits[nd - 1] == '0') digits[--nd] = '\0';
    if (v == 0.0) {
        snprintf(buf, len, "%s", neg ? "-0" : "0"); /* -0 stays -0: exact to the bit */
    } else if (exp10 >= 0 && exp10 < 15) {
        /* the point after digit exp10 */
        char out[48];
        int o = 0;
        if (neg) out[o++] = '-';
        for (int i = 0; i <= exp10; ++i) out[o++] = i < nd ? digits[i] : '0';
        if (nd > exp10 + 1) {
            out[o++] = '.';
            for (int i = exp10 + 1; i < nd; ++i) out[o++] = digits[i];
        }
        out[o] = '\0';
        snprintf(buf, len, "%s", out);
    } else if (exp10 < 0 && exp10 > -7) {
        snprintf(buf, len, "%s0.%0*d%s", neg ? "-" : "", -exp10 - 1, 0, digits);
        if (exp10 == -1) snprintf(buf, len, "%s0.%s", neg ? "-" : "", digits);
    } else {
        snprintf(buf, len, "%s%c%s%se%d", neg ? "-" : "", digits[0], nd > 1 ? "." : "", digits + 1, exp10);
    }
}

/* v in a unit that is a factor of the SI unit (deg, rpm): the decimal with
 * the fewest places that reads back exactly; 0 if there is none. */
static int in_factor_unit(double v, jc_Quantity q, const unit *u, char *buf, size_t len)
{
    const double x = v * u->from_si;
    for (int decimals = 0; decimals <= 16 && fabs(x) < 1e15; ++decimals) {
        char d[64], token[80];
        double back;
        snprintf(d, sizeof d, "%.*f", decimals, x);
        snprintf(token, sizeof token, "%s%s", d, u->name);
        if (jc_quantity_parse(token, q, &back, NULL, 0) == JC_OK && memcmp(&back, &v, sizeof v) == 0) {
            snprintf(buf, len, "%s", d);
            return 1;
        }
    }
    return 0;
}

int jc_quantity_format(double v, jc_Quantity q, const char *unit_name, char *buf, size_t len)
{
    if (!buf || len == 0) return JC_EINVAL;
    buf[0] = '\0';
    if (q == JC_Q_NAME) return JC_EINVAL;
    /* "" is the SI unit (none for a number) */
    const unit *u = find_unit(q, unit_name && *unit_name ? unit_name : jc_quantity_si_unit(q));
    if (!u && (units_of(q)[0].name || (unit_name && *unit_name))) return JC_EINVAL;
    char num[64];
    const char *written = u ? u->name : "";
    if (!u || (u->pow10 == 0 && u->factor == 1.0)) shortest(v, num, sizeof num);
    else if (u->factor == 1.0) shifted(v, -u->pow10, num, sizeof num);
    else if (!in_factor_unit(v, q, u, num, sizeof num)) {
        shortest(v, num, sizeof num); /* no decimal in that unit is exact: SI */
        written = jc_quantity_si_unit(q);
    }
    const int n = snprintf(buf, len, "%s%s%s", num, *written ? " " : "", written);
    if (n < 0 || (size_t)n >= len) {
        buf[0] = '\0';
        return JC_EINVAL;
    }
    return JC_OK;
}
