/* Precision-following math: one spelling for double and float builds. */
#ifndef BRAUN_MATH_H
#define BRAUN_MATH_H

#include <float.h>
#include <math.h>

#include "braun.h"

#ifdef BRAUN_SINGLE
#define BRAUN_EPS FLT_EPSILON
#define BRAUN_MAXREAL FLT_MAX
#define braun_sqrt sqrtf
#define braun_fabs fabsf
#define braun_sin sinf
#define braun_cos cosf
#else
#define BRAUN_EPS DBL_EPSILON
#define BRAUN_MAXREAL DBL_MAX
#define braun_sqrt sqrt
#define braun_fabs fabs
#define braun_sin sin
#define braun_cos cos
#endif

/* x - x is 0 for every finite x and NaN for NaN and ±Inf. */
static inline int braun_is_finite(braun_real x) { return (x - x) == 0; }

#endif
