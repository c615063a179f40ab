/* Counter-based random numbers: Random123's Philox4x32-10 (Salmon et al.,
 * SC'11) keyed by the seed, with the sample index and the draw number as
 * the counter. A number is a pure function of (seed, sample, draw), so it
 * does not depend on the thread, the shard, the MPI rank or the order in
 * which samples are computed. The Monte Carlo's draws (src/study/case.c),
 * the fit's Latin hypercube and the synthetic videos' noise (src/track/). */
#include "jumpcyl/study.h"

#include <Random123/philox.h>
#include <math.h>

#define PI 3.14159265358979323846

static philox4x32_ctr_t block(uint64_t seed, uint64_t sample, uint32_t draw)
{
    const philox4x32_key_t key = {{(uint32_t)seed, (uint32_t)(seed >> 32)}};
    const philox4x32_ctr_t ctr = {{(uint32_t)sample, (uint32_t)(sample >> 32), draw, 0x6a63u /* "jc" */}};
    return philox4x32(ctr, key);
}

/* 53 random bits as a double strictly inside (0, 1): (k + 1/2) 2^-53. */
static double open01(uint32_t hi, uint32_t lo)
{
    const uint64_t k = ((uint64_t)hi << 21) ^ (uint64_t)(lo >> 11);
    return ((double)k + 0.5) * 0x1p-53;
}

double jc_random_uniform(uint64_t seed, uint64_t sample, uint32_t draw)
{
    const philox4x32_ctr_t r = block(seed, sample, draw);
    return open01(r.v[0], r.v[1]);
}

/* Box-Muller on the block's two uniforms: exact, and one block per normal. */
double jc_random_normal(uint64_t seed, uint64_t sample, uint32_t draw)
{
    const philox4x32_ctr_t r = block(seed, sample, draw);
    const double u1 = open01(r.v[0], r.v[1]), u2 = open01(r.v[2], r.v[3]);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PI * u2);
}
