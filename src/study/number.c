/* printf's "%.*g" of a double, the same bytes, without printf: the rows of
 * a study are mostly numbers, and glibc's printf of a double (exact
 * multi-precision arithmetic) costs a large share of a Monte Carlo
 * sample's work (docs/performance.md). The decimal digits are found exactly in 128-bit integers
 * (a double is m 2^e, m < 2^53) and rounded half to even, as printf rounds
 * in the default rounding mode; values whose digits do not fit 128 bits
 * (beyond about 1e-22 .. 1e27) go to snprintf. */
#include "study_internal.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 u128;

/* 10^k for k in 0..38 (10^38 < 2^128). */
static u128 pow10_u128(int k)
{
    static const uint64_t small[20] = {1ull,
                                       10ull,
                                       100ull,
                                       1000ull,
                                       10000ull,
                                       100000ull,
                                       1000000ull,
                                       10000000ull,
                                       100000000ull,
                                       1000000000ull,
                                       10000000000ull,
                                       100000000000ull,
                                       1000000000000ull,
                                       10000000000000ull,
                                       100000000000000ull,
                                       1000000000000000ull,
                                       10000000000000000ull,
                                       100000000000000000ull,
                                       1000000000000000000ull,
                                       10000000000000000000ull};
    return k < 20 ? (u128)small[k] : (u128)small[19] * small[k - 19];
}

/* m 2^e2 / 10^k truncated into *q, and whether rounding it half to even
 * goes up (*up); 0, or -1 when it does not fit the integers here. */
static int scaled_digits(uint64_t m, int e2, int k, u128 *q, int *up)
{
    u128 num, den;
    if (k <= 0) {
        if (k < -22) return -1; /* 10^22 m < 2^126 */
        num = (u128)m * pow10_u128(-k);
        if (e2 >= 0) {
            if (e2 > 40) return -1;
            *q = num << e2; /* exact: no remainder */
            *up = 0;
            return 0;
        }
        if (e2 < -126) return -1;
        const int s = -e2;
        const u128 rem = num & (((u128)1 << s) - 1), half = (u128)1 << (s - 1);
        *q = num >> s;
        *up = rem > half || (rem == half && (*q & 1));
        return 0;
    }
    if (k > 27 || e2 > 74 || e2 < -126) return -1; /* 10^27 < 2^90; m 2^74 < 2^127 */
    if (e2 >= 0) {
        num = (u128)m << e2;
        den = pow10_u128(k);
    } else {
        /* m / (10^k 2^-e2): the denominator must fit as well */
        if (k > 22 || -e2 > 126 - 74) return -1;
        num = m;
        den = pow10_u128(k) << (-e2);
    }
    const u128 rem = num % den;
    *q = num / den;
    *up = 2 * rem > den || (2 * rem == den && (*q & 1));
    return 0;
}

/* The digits of |v| rounded to p significant ones into digits (p chars), and
 * the decimal exponent of the first (after rounding: 9.99 to two digits is
 * 10); 0, or -1 when they do not fit here. */
static int digits_of(double a, int p, char *digits, int *exp10)
{
    int e;
    const double f = frexp(a, &e); /* a = f 2^e, f in [0.5, 1) */
    const uint64_t m = (uint64_t)ldexp(f, 53);
    const int e2 = e - 53;
    int x = (int)floor(log10(a)); /* may be one off near a power of ten: corrected below */
    const u128 lo = pow10_u128(p - 1), hi = lo * 10;
    for (int tries = 0; tries < 4; ++tries) {
        u128 q;
        int up;
        /* the exponent is the one whose truncated digits are p long: 10^x <= a < 10^(x+1) */
        if (scaled_digits(m, e2, x - p + 1, &q, &up) != 0) return -1;
        if (q >= hi) {
            ++x;
            continue;
        }
        if (q < lo) {
            --x;
            continue;
        }
        q += (u128)up;
        if (q == hi) { /* 99..9 rounded up: 10..0, one place higher */
            q = lo;
            ++x;
        }
        uint64_t d = (uint64_t)q; /* p <= 19 digits: 64 bits, divided fast */
        for (int i = p - 1; i >= 0; --i) {
            digits[i] = (char)('0' + (int)(d % 10));
            d /= 10;
        }
        *exp10 = x;
        return 0;
    }
    return -1;
}

int jc_format_g(double v, int precision, char *out)
{
    const int p = precision < 1 ? 1 : precision;
    char digits[40];
    int x = 0, n = 0;
    if (!isfinite(v) || v == 0.0 || p > 19 || digits_of(fabs(v), p, digits, &x) != 0)
        return snprintf(out, JC_NUMBER_MAX, "%.*g", precision, v);
    if (signbit(v)) out[n++] = '-';
    int nd = p; /* %g drops trailing zeros of the fraction */
    if (x < -4 || x >= p) {
        while (nd > 1 && digits[nd - 1] == '0') --nd;
        out[n++] = digits[0];
        if (nd > 1) {
            out[n++] = '.';
            memcpy(out + n, digits + 1, (size_t)(nd - 1));
            n += nd - 1;
        }
        const int ax = x < 0 ? -x : x;
        out[n++] = 'e';
        out[n++] = x < 0 ? '-' : '+';
        if (ax >= 100) out[n++] = (char)('0' + ax / 100);
        out[n++] = (char)('0' + ax / 10 % 10);
        out[n++] = (char)('0' + ax % 10);
    } else if (x >= 0) {
        while (nd > x + 1 && digits[nd - 1] == '0') --nd;
        memcpy(out + n, digits, (size_t)(x + 1));
        n += x + 1;
        if (nd > x + 1) {
            out[n++] = '.';
            memcpy(out + n, digits + x + 1, (size_t)(nd - x - 1));
            n += nd - x - 1;
        }
    } else {
        while (nd > 1 && digits[nd - 1] == '0') --nd;
        out[n++] = '0';
        out[n++] = '.';
        for (int i = 0; i < -x - 1; ++i) out[n++] = '0';
        memcpy(out + n, digits, (size_t)nd);
        n += nd;
    }
    out[n] = '\0';
    return n;
}
#else
int jc_format_g(double v, int precision, char *out)
{
    return snprintf(out, JC_NUMBER_MAX, "%.*g", precision, v);
}
#endif
