/* Precision-following math: one spelling for double and float builds. */
#ifndef BRAUN_MATH_H
#define BRAUN_MATH_H

#include <float.h>
#include <math.h>

#include "braun.h"

/* The state's sum compensated (Kahan: braun_step.c, rk_stages) in float,
 * where a small step's increments fall below the state's ulp (a float
 * slider-crank from rest at h = 1e-5 never moved; at h = 1e-3 its error
 * fell from 7.4e-5 to 7e-7). Not in double: measured, no gain, and the
 * slider-crank's largest position residual over 100 s (RK4, h = 1e-3)
 * rose from 7.0e-12 to 1.7e-11 (RMS 8.5e-14 to 1.3e-13): the carried
 * rounding enters a step after its corrections were computed. */
#ifndef BRAUN_COMPENSATED_STATE
#ifdef BRAUN_SINGLE
#define BRAUN_COMPENSATED_STATE 1
#else
#define BRAUN_COMPENSATED_STATE 0
#endif
#endif

#ifdef BRAUN_SINGLE
#define BRAUN_EPS FLT_EPSILON
#define BRAUN_MAXREAL FLT_MAX
#define braun_sqrt sqrtf
#define braun_fabs fabsf
#define braun_floor floorf
#define braun_sin sinf
#define braun_cos cosf
#else
#define BRAUN_EPS DBL_EPSILON
#define BRAUN_MAXREAL DBL_MAX
#define braun_sqrt sqrt
#define braun_fabs fabs
#define braun_floor floor
#define braun_sin sin
#define braun_cos cos
#endif

/* *s = sin x, *c = cos x: in the float build with one argument reduction
 * (braun_sincos.h); in double sin and cos, which GCC fuses into one sincos
 * call where the C library has it (glibc). */
#ifdef BRAUN_SINGLE
#include "braun_sincos.h"
#define braun_sincos braun_sincosf
#else
static inline void braun_sincos(double x, double *s, double *c)
{
    *s = sin(x);
    *c = cos(x);
}
#endif

/* Default relative rank tolerance of the pseudoinverses (docs/method.md,
 * "Rank tolerance"). Double: MATLAB's pinv max(rows,n)·ε with a margin of
 * 10 (QR pivots of exactly dependent rows come out a few ε·||C||). Float:
 * near a bifurcation the round-off ν ~ ε in Φ is divided by the small pivot
 * σ and kicks the state toward the other branch, which lies ~σ away: kicks
 * win below σ ~ sqrt(ε). In double that window (1.5e-8) is so narrow that a
 * wider tolerance costs more than it saves; in float (3.4e-4) it is not, and
 * 30·sqrt(ε) ≈ 1e-2 is what the slider-crank and four-bar need (measured). */
static inline braun_real braun_default_rank_tol(int rows, int n)
{
#ifdef BRAUN_SINGLE
    (void)rows;
    (void)n;
    return BRAUN_R(30.0) * braun_sqrt(BRAUN_EPS);
#else
    return BRAUN_R(10.0) * (braun_real)(rows > n ? rows : n) * BRAUN_EPS;
#endif
}

/* x - x is 0 for every finite x and NaN for NaN and ±Inf. */
static inline int braun_is_finite(braun_real x) { return (x - x) == 0; }

#endif
