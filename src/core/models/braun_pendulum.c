/*
 * Simple pendulum: a point mass m on a massless rod of length l hinged at
 * the origin, q = [x, y], one constraint x² + y² - l² = 0. The smallest
 * constrained system: the test bed of the solver.
 *
 * Minimal coordinate: phi, the angle from the downward vertical,
 * x = l sin phi, y = -l cos phi, phi'' = -(g/l) sin phi, solved in closed
 * form by braun_pendulum_exact.
 */
#include <stddef.h>

#include "braun_models_internal.h"

static const braun_link_params params = {1.0, 1.0, 9.81, BRAUN_R(1.0), BRAUN_R(1.0),
                                          BRAUN_R(1.0) * BRAUN_R(9.81)};

static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_link_params *p = user;
    (void)t;
    (void)q;
    M[0] = M[3] = p->rm;
    M[1] = M[2] = BRAUN_R(0.0);
    return 0;
}

static int forces(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *Q, void *user)
{
    const braun_link_params *p = user;
    (void)t;
    (void)q;
    (void)v;
    Q[0] = BRAUN_R(0.0);
    Q[1] = -p->rmg;
    return 0;
}

/* Φ = x² + y² - l²; quadratic, so b_qv = -2|v|². */
static int holonomic(braun_real t, const braun_real *q, const braun_real *v,
                     braun_real *phi, braun_real *A, braun_real *b,
                     braun_real *bv, void *user)
{
    const braun_link_params *p = user;
    braun_real l = p->rl;
    (void)t;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - l * l;
    if (A) {
        A[0] = BRAUN_R(2.0) * q[0];
        A[1] = BRAUN_R(2.0) * q[1];
    }
    if (b) b[0] = BRAUN_R(0.0);
    if (bv) bv[0] = BRAUN_R(-2.0) * (v[0] * v[0] + v[1] * v[1]);
    return 0;
}

/* E = ½m|v|² + mgy. */
static int energy(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *E, braun_real *dE_dq, braun_real *dE_dv,
                  braun_real *dE_dt, void *user)
{
    const braun_link_params *p = user;
    braun_real m = p->rm;
    braun_real mg = p->rmg;
    (void)t;
    if (E) *E = BRAUN_R(0.5) * m * (v[0] * v[0] + v[1] * v[1]) + mg * q[1];
    if (dE_dq) {
        dE_dq[0] = BRAUN_R(0.0);
        dE_dq[1] = mg;
    }
    if (dE_dv) {
        dE_dv[0] = m * v[0];
        dE_dv[1] = m * v[1];
    }
    if (dE_dt) *dE_dt = BRAUN_R(0.0);
    return 0;
}

static const braun_real q0[2] = {BRAUN_R(1.0), BRAUN_R(0.0)}; /* [l, 0] */
static const braun_real v0[2] = {BRAUN_R(0.0), BRAUN_R(0.0)};

const braun_builtin braun_builtin_pendulum = {
    "pendulum",
    "point mass on a rigid massless rod: 2 coordinates, 1 constraint",
    {2, 1, 0, BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC, mass, forces, holonomic, NULL, energy, NULL,
     /* Callbacks only read the parameters; void * has no const. */
     (void *)&params, NULL, NULL},
    q0,
    v0,
    0,
    1};
