/* Small systems with known solutions, defined for the tests only:
 *   pendulum  — point mass on a rod in Cartesian coordinates; the constraint
 *               row may be duplicated or duplicated with a scale (redundant);
 *   knife     — knife edge / sleigh at its centre of mass (nonholonomic);
 *               exact: constant turn rate and speed along a circle;
 *   bead      — bead on a rod spinning at ω (rheonomic); exact:
 *               r = r0 cosh ωt; the rod does work Ė = 2 ω² r ṙ, which the
 *               core accounts for (no power callback);
 *   generic   — 4 coordinates, full constant M, 2 holonomic + 1 nonholonomic
 *               rows: for the geometric invariants. */
#ifndef TEST_SYSTEMS_H
#define TEST_SYSTEMS_H
#include "braun.h"

typedef struct pendulum_params {
    double mass, L, g;
    int redundancy; /* 0: one row, 1: row duplicated, 2: duplicate scaled by -3 */
    int bad_mass;   /* 1: indefinite M, 2: non-symmetric M, 3: NaN in M */
    int fail_from, fail_to; /* forces() calls numbered in [fail_from, fail_to] */
    int fail_code;          /* ... return this code (0: never fail) */
    int calls;
} pendulum_params;

braun_system pendulum_system(pendulum_params *prm);
braun_system knife_system(void);
void knife_exact(double t, const double *q0, const double *v0, double *q, double *v);
braun_system bead_system(double *omega);
braun_system generic_system(void);
/* A consistent state of the generic system (q, v: 4 entries). */
void generic_consistent_state(double *q, double *v);

#endif
