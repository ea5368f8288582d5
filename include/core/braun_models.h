/*
 * Built-in models: the paper's mechanisms (Sec. 4), a pendulum and Andrews'
 * squeezing mechanism, as braun_system records with their initial states.
 * Core tier (firmware runs them). Their minimal-coordinate equations and
 * exact references are test oracles of the host tier: braun_reference.h.
 */
#ifndef BRAUN_MODELS_H
#define BRAUN_MODELS_H

#include "braun.h"

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_andrews_q0 braun_andrews_q0_float
#define braun_andrews_system braun_andrews_system_float
#define braun_andrews_v0 braun_andrews_v0_float
#define braun_builtin_at braun_builtin_at_float
#define braun_builtin_find braun_builtin_find_float
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define BRAUN_MODEL_MAX_N 8

/* Physical parameters shared by the built-in models (SI units). */
typedef struct braun_link_params {
    double l;  /* link length [m] */
    double m;  /* link mass [kg] */
    double g;  /* gravity [m/s^2] */
    /* The same in braun_real, for the callbacks: a float build then does
     * no double arithmetic per call (soft-float on a Cortex-M4F). */
    braun_real rl, rm, rmg;  /* l, m, m·g */
} braun_link_params;

typedef struct braun_builtin {
    const char *name;         /* "slider-crank", "four-bar", "pendulum" */
    const char *description;  /* one line */
    braun_system sys;         /* user points at a static braun_link_params */
    const braun_real *q0;     /* paper's initial state, n entries */
    const braun_real *v0;
    /* Coordinates (ix, iy) of the point whose planar error is the paper's ε
     * (four-bar: joint 3, ε3 of Fig. 7); -1 if none. */
    int point_x, point_y;
} braun_builtin;

/* Look up a built-in model by name; NULL if unknown. */
const braun_builtin *braun_builtin_find(const char *name);
/* The i-th built-in model (NULL past the end), for listing. */
const braun_builtin *braun_builtin_at(int i);

/* Andrews' squeezing mechanism: the "andrews" problem of the Test Set for
 * IVP Solvers (Mazzia & Magherini, Bari; Hairer & Wanner II, Sec. VII.7) in
 * its index-3 form: 7 angles q = [β, Θ, γ, Φ, δ, Ω, ε], 6 holonomic rows
 * g(q) = 0, its own M(q) (not constant), f(q, v) with the stiff spring
 * c0 = 4530 and the driving torque mom = 0.033, and the energy law
 * T + V_spring with input power mom·β'. Its reference solution is in
 * braun_reference.h (host). */
extern const braun_system braun_andrews_system;
extern const braun_real braun_andrews_q0[7], braun_andrews_v0[7];

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_MODELS_H */
