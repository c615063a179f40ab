/* jc_format_g (src/study/number.c) against printf's own "%.*g": the same
 * bytes for doubles of every bit pattern, for the magnitudes rows hold,
 * for exact ties (rounded half to even), powers of ten and their
 * neighbours, at every precision from 1 to 17. */
#include "../test.h"
#include "study/study_internal.h"

#include <float.h>
#include <stdlib.h>

static int same_as_printf(double v, int precision)
{
    char want[64], got[JC_NUMBER_MAX];
    snprintf(want, sizeof want, "%.*g", precision, v);
    const int n = jc_format_g(v, precision, got);
    ENSURE_MSG(strcmp(want, got) == 0 && n == (int)strlen(want), "%a with %%.%dg: printf '%s', here '%s'", v,
               precision, want, got);
    return 0;
}

static uint64_t next(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}

static int test_every_bit_pattern(void)
{
    uint64_t state = 0x243f6a8885a308d3ull;
    for (int k = 0; k < 300000; ++k) {
        const uint64_t bits = next(&state);
        double v;
        memcpy(&v, &bits, sizeof v);
        if (isnan(v)) continue;
        if (same_as_printf(v, 12) || same_as_printf(v, 3) || same_as_printf(v, 1 + (int)(bits % 17))) return 1;
    }
    return 0;
}

/* What rows hold: 1e-20 .. 1e6, both signs, and short decimals. */
static int test_row_magnitudes(void)
{
    uint64_t state = 7;
    for (int k = 0; k < 300000; ++k) {
        const double u = (double)(next(&state) >> 11) * (1.0 / 9007199254740992.0);
        const double mag = pow(10.0, -20.0 + 26.0 * u) * ((next(&state) & 1) ? -1.0 : 1.0);
        const double decimal = (double)(long)(u * 1e6) / 1e3; /* 3 decimals: many exact ties at small precision */
        if (same_as_printf(mag, 12) || same_as_printf(mag, 3) || same_as_printf(decimal, 12) ||
            same_as_printf(decimal, 4) || same_as_printf(decimal, 2))
            return 1;
    }
    return 0;
}

static int test_ties_and_edges(void)
{
    const double cases[] = {0.0,     -0.0,    0.5,    1.5,     2.5,      0.125,     0.375,  1.25,     2.675,
                            1e-5,    1e-4,    9.9999e-5, 0.0001, 123456.5, 999999.5, 9.5,    99.95,    1e11,
                            1e12,    1e15,    1e16,   1e17,    1e22,     1e23,      1e27,   1e28,     1e300,
                            1e-300,  DBL_MIN, DBL_MAX, DBL_TRUE_MIN, 4.9e-324, 3.2, 1.0 / 3.0, 2.0 / 3.0, 0.1 + 0.2,
                            INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        for (int p = 1; p <= 17; ++p) {
            if (same_as_printf(cases[i], p)) return 1;
            if (isfinite(cases[i]) && cases[i] != 0.0 &&
                (same_as_printf(nextafter(cases[i], INFINITY), p) || same_as_printf(nextafter(cases[i], 0.0), p)))
                return 1;
        }
    /* powers of ten and their neighbours, where the first digit's exponent is decided */
    for (int e = -25; e <= 30; ++e) {
        const double t = pow(10.0, e);
        for (int p = 1; p <= 17; ++p)
            if (same_as_printf(t, p) || same_as_printf(nextafter(t, 0.0), p) || same_as_printf(nextafter(t, INFINITY), p) ||
                same_as_printf(t * (1.0 - 0.5e-12), p) || same_as_printf(-t * 9.9999999999995, p))
                return 1;
    }
    /* integers with a 5 after the precision's last digit: exact ties */
    for (long n = 1; n < 2000000; n += 7919) {
        const double v = (double)n * 10.0 + 5.0;
        for (int p = 1; p <= 8; ++p)
            if (same_as_printf(v, p) || same_as_printf(v / 1024.0, p)) return 1;
    }
    return 0;
}

int main(void)
{
    RUN_TEST(test_every_bit_pattern);
    RUN_TEST(test_row_magnitudes);
    RUN_TEST(test_ties_and_edges);
    TEST_MAIN_END();
}
