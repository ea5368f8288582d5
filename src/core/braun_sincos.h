/* sin and cos of one angle with one argument reduction, for the float
 * build (braun_math.h, braun_sincos).
 *
 * Why: the callbacks of a planar mechanism take cos θ and sin θ of every
 * body angle at every stage. On the Cortex-M4F newlib's sinf and cosf each
 * reduce the argument modulo π/2 on their own: measured on the corrected
 * slider-crank (float, compile-time sizes), a step took about 9 700
 * instructions while its crank angles stayed within ±π/4 and 10 850 once
 * they left it (docs/performance.md, Optimisations, item 17). Here the
 * reduction is done once for both, without a call. (The double build on
 * glibc needs none of this: GCC already fuses sin and cos of one argument
 * into one sincos call.)
 *
 * How: n = nearest integer to x·2/π, r = x − n·π/2 by Cody and Waite's
 * method with π/2 split into P1 + P2 + P3, P1 and P2 of 11 significant bits
 * so that n·P1 and n·P2 are exact for |n| < 2^11 (|x| < BRAUN_SINCOS_MAX),
 * and x − n·P1 exact by Sterbenz's lemma; then the Taylor polynomials of
 * sin and cos on |r| ≤ π/4 (+ the rounding of n), truncated where the
 * next term is below 3 % of an ulp (sin: to r⁹, cos: to r¹⁰), and the
 * quadrant n mod 4. Error: at most 2.4 ulp of the result (newlib's sinf
 * and cosf: below 1), and ~1e-13 absolute within 1e-4 of a zero, where
 * n·P3's rounding is what remains of the cancelled reduction (test_sincosf
 * sweeps ±BRAUN_SINCOS_MAX against the double sin and cos). Beyond
 * BRAUN_SINCOS_MAX, and for NaN and ±Inf, sinf and cosf. Float only: not
 * one double operation. */
#ifndef BRAUN_SINCOS_H
#define BRAUN_SINCOS_H

#include <math.h>

#define BRAUN_SINCOS_MAX 3000.0f

static inline void braun_sincosf(float x, float *s, float *c)
{
    if (!(fabsf(x) < BRAUN_SINCOS_MAX)) { /* NaN too */
        *s = sinf(x);
        *c = cosf(x);
        return;
    }
    const float two_over_pi = 0x1.45f306p-1f;
    const float p1 = 0x1.922p+0f, p2 = -0x1.2aep-18f, p3 = -0x1.de974p-31f;
    const int n = (int)(x * two_over_pi + (x < 0 ? -0.5f : 0.5f));
    const float fn = (float)n;
    const float r = ((x - fn * p1) - fn * p2) - fn * p3;
    const float z = r * r;
    const float sr = r + r * z * (-1.0f / 6 + z * (1.0f / 120 + z * (-1.0f / 5040 + z * (1.0f / 362880))));
    const float cr =
        1 + z * (-0.5f + z * (1.0f / 24 + z * (-1.0f / 720 + z * (1.0f / 40320 + z * (-1.0f / 3628800)))));
    switch (n & 3) {
    case 0: *s = sr; *c = cr; break;
    case 1: *s = cr; *c = -sr; break;
    case 2: *s = -sr; *c = -cr; break;
    default: *s = -cr; *c = sr; break;
    }
}

#endif
