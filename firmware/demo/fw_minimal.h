/*
 * Classic RK4 on the minimal-coordinate equation of a built-in model, in
 * braun_real (float in float builds): the baseline of the float
 * criterion ("trajectory error within 2x that of float RK4 on the
 * minimal-coordinate equation"). The host's oracles (braun_reference.h) are double
 * only; this is the same equation evaluated in working precision.
 *   slider-crank (Eq. 24): θ'' = -3 (sin 2θ θ'² + (g/l) cos θ) / (5 - 3 cos 2θ)
 *   four-bar (Fig. 6):     θ'' = -(7g / 6l) cos θ
 *   pendulum:              as in braun_pendulum.c
 */
#ifndef FW_MINIMAL_H
#define FW_MINIMAL_H

#include "braun.h"
#include "braun_models.h"

typedef struct fw_minimal {
    int kind;          /* 0 slider-crank, 1 four-bar, 2 pendulum */
    braun_real g_l;    /* g / l */
    braun_real y[2];   /* θ, θ' */
} fw_minimal;

/* Start at the model's minimal initial state; returns 0, or -1 for an unknown model. */
int fw_minimal_init(fw_minimal *s, const braun_builtin *b);
/* One RK4 step of size h. */
void fw_minimal_step(fw_minimal *s, braun_real h);

#endif
