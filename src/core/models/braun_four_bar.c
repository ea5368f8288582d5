/*
 * Double four-bar linkage of Sec. 4.2 (Fig. 5): five uniform rods of length
 * l and mass m. Three cranks turn about the ground pivots (0,0), (l,0),
 * (2l,0) and end in the moving joints 1, 2, 3; two couplers join 1–2 and
 * 2–3. Coordinates are the joint positions q = [x1, y1, x2, y2, x3, y3].
 *
 * Mass matrix: a crank with one fixed end has T = ½(m/3)|v_i|², a coupler
 * T = (m/6)(|v_i|² + v_i·v_j + |v_j|²); summed this is the printed M.
 *
 * Potential: each rod's centre is at the mean height of its ends, so
 *   V = mg(y1/2 + y2/2 + y3/2 + (y1+y2)/2 + (y2+y3)/2) = mg(y1 + 3/2 y2 + y3),
 * as in the printed energy law. The printed force vector
 * [0, -mg, 0, +3/2 mg, 0, -mg] has a sign misprint in its fourth entry:
 * Q = -∂V/∂q = [0, -mg, 0, -3/2 mg, 0, -mg]. With +3/2 mg the constrained
 * motion no longer matches θ'' + (7g/6l) cos θ = 0 (tests/test_models.c).
 *
 * Minimal coordinate: the cranks stay parallel at angle θ, joint i at
 * ((i-1)l + l cos θ, l sin θ), all joints with velocity lθ'(-sin θ, cos θ).
 * Then T = ½(3m)l²θ'² (sum of all entries of one 3x3 block of M) and
 * V = (7/2)mgl sin θ, so 3ml²θ'' + (7/2)mgl cos θ = 0 (Fig. 6 caption).
 * With phi = θ + π/2 this is the pendulum phi'' = -(7g/6l) sin phi.
 *
 * Whenever y1 = y2 = y3 = 0 the five constraint rows lose rank (kinematic
 * singularity); the model states them as printed.
 */
#include <stddef.h>

#include "braun_models_internal.h"

static const braun_link_params params = {1.0, 1.0, 9.81, BRAUN_R(1.0), BRAUN_R(1.0),
                                          BRAUN_R(1.0) * BRAUN_R(9.81)};

static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_link_params *p = user;
    braun_real d = BRAUN_R(2.0) / BRAUN_R(3.0) * p->rm;
    braun_real o = p->rm / BRAUN_R(6.0);
    braun_real mid = p->rm;
    (void)t;
    (void)q;
    for (int i = 0; i < 36; ++i) M[i] = BRAUN_R(0.0);
    for (int k = 0; k < 2; ++k) { /* x block (k = 0) and y block (k = 1) */
        int i1 = k, i2 = 2 + k, i3 = 4 + k;
        M[i1 * 6 + i1] = d;
        M[i2 * 6 + i2] = mid;
        M[i3 * 6 + i3] = d;
        M[i1 * 6 + i2] = M[i2 * 6 + i1] = o;
        M[i2 * 6 + i3] = M[i3 * 6 + i2] = o;
    }
    return 0;
}

/* Q = -∂V/∂q; the paper prints +3/2 mg for the fourth entry (misprint). */
static int forces(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *Q, void *user)
{
    const braun_link_params *p = user;
    braun_real mg = p->rmg;
    (void)t;
    (void)q;
    (void)v;
    Q[0] = BRAUN_R(0.0);
    Q[1] = -mg;
    Q[2] = BRAUN_R(0.0);
    Q[3] = BRAUN_R(-1.5) * mg;
    Q[4] = BRAUN_R(0.0);
    Q[5] = -mg;
    return 0;
}

/* Rod r between points a and b (a ground pivot for the cranks): row
 * |b - a|² - l². Quadratic, so b_qv = -2|v_b - v_a|². Rows: cranks to
 * joints 1, 2, 3 (ground pivots at (0,0), (l,0), (2l,0)), couplers 1–2,
 * 2–3. Straight-line, every entry of A written once, zeros included: the
 * callback runs at every stage (a loop over the rods with a zeroing pass
 * took 240 instructions a call, this a fifth of it). */
static int holonomic(braun_real t, const braun_real *q, const braun_real *v,
                     braun_real *phi, braun_real *A, braun_real *b,
                     braun_real *bv, void *user)
{
    const braun_link_params *p = user;
    const braun_real l = p->rl;
    /* (dx, dy) of each rod, from its first point to its second. */
    const braun_real dx0 = q[0] - BRAUN_R(0.0) * l, dy0 = q[1] - BRAUN_R(0.0);
    const braun_real dx1 = q[2] - BRAUN_R(1.0) * l, dy1 = q[3] - BRAUN_R(0.0);
    const braun_real dx2 = q[4] - BRAUN_R(2.0) * l, dy2 = q[5] - BRAUN_R(0.0);
    const braun_real dx3 = q[2] - q[0], dy3 = q[3] - q[1];
    const braun_real dx4 = q[4] - q[2], dy4 = q[5] - q[3];
    (void)t;
    if (phi) {
        phi[0] = dx0 * dx0 + dy0 * dy0 - l * l;
        phi[1] = dx1 * dx1 + dy1 * dy1 - l * l;
        phi[2] = dx2 * dx2 + dy2 * dy2 - l * l;
        phi[3] = dx3 * dx3 + dy3 * dy3 - l * l;
        phi[4] = dx4 * dx4 + dy4 * dy4 - l * l;
    }
    if (A) {
        const braun_real o = BRAUN_R(0.0), two = BRAUN_R(2.0), mtwo = BRAUN_R(-2.0);
        braun_real *r = A;
        r[0] = two * dx0;  r[1] = two * dy0;  r[2] = o;          r[3] = o;          r[4] = o;          r[5] = o;
        r += 6;
        r[0] = o;          r[1] = o;          r[2] = two * dx1;  r[3] = two * dy1;  r[4] = o;          r[5] = o;
        r += 6;
        r[0] = o;          r[1] = o;          r[2] = o;          r[3] = o;          r[4] = two * dx2;  r[5] = two * dy2;
        r += 6;
        r[0] = mtwo * dx3; r[1] = mtwo * dy3; r[2] = two * dx3;  r[3] = two * dy3;  r[4] = o;          r[5] = o;
        r += 6;
        r[0] = o;          r[1] = o;          r[2] = mtwo * dx4; r[3] = mtwo * dy4; r[4] = two * dx4;  r[5] = two * dy4;
    }
    if (b)
        for (int i = 0; i < 5; ++i) b[i] = BRAUN_R(0.0);
    if (bv) {
        const braun_real ux3 = v[2] - v[0], uy3 = v[3] - v[1];
        const braun_real ux4 = v[4] - v[2], uy4 = v[5] - v[3];
        bv[0] = BRAUN_R(-2.0) * (v[0] * v[0] + v[1] * v[1]);
        bv[1] = BRAUN_R(-2.0) * (v[2] * v[2] + v[3] * v[3]);
        bv[2] = BRAUN_R(-2.0) * (v[4] * v[4] + v[5] * v[5]);
        bv[3] = BRAUN_R(-2.0) * (ux3 * ux3 + uy3 * uy3);
        bv[4] = BRAUN_R(-2.0) * (ux4 * ux4 + uy4 * uy4);
    }
    return 0;
}

/* E = ½vᵀMv + mg(y1 + 3/2 y2 + y3), with M's pattern (mass above: the
 * same entries, the products with its zeros left out). */
static int energy(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *E, braun_real *dE_dq, braun_real *dE_dv,
                  braun_real *dE_dt, void *user)
{
    const braun_link_params *p = user;
    const braun_real mg = p->rmg;
    const braun_real d = BRAUN_R(2.0) / BRAUN_R(3.0) * p->rm, o = p->rm / BRAUN_R(6.0), mid = p->rm;
    braun_real Mv[6];
    (void)t;
    for (int k = 0; k < 2; ++k) { /* x (k = 0) and y (k = 1) */
        Mv[k] = d * v[k] + o * v[2 + k];
        Mv[2 + k] = o * v[k] + mid * v[2 + k] + o * v[4 + k];
        Mv[4 + k] = o * v[2 + k] + d * v[4 + k];
    }
    if (E) {
        braun_real T = BRAUN_R(0.0);
        for (int i = 0; i < 6; ++i) T += v[i] * Mv[i];
        *E = BRAUN_R(0.5) * T + mg * (q[1] + BRAUN_R(1.5) * q[3] + q[5]);
    }
    if (dE_dq) {
        for (int i = 0; i < 6; ++i) dE_dq[i] = BRAUN_R(0.0);
        dE_dq[1] = mg;
        dE_dq[3] = BRAUN_R(1.5) * mg;
        dE_dq[5] = mg;
    }
    if (dE_dv)
        for (int i = 0; i < 6; ++i) dE_dv[i] = Mv[i];
    if (dE_dt) *dE_dt = BRAUN_R(0.0);
    return 0;
}

static const braun_real q0[6] = {BRAUN_R(0.0), BRAUN_R(1.0), BRAUN_R(1.0),
                                 BRAUN_R(1.0), BRAUN_R(2.0), BRAUN_R(1.0)};
static const braun_real v0[6] = {BRAUN_R(1.0), BRAUN_R(0.0), BRAUN_R(1.0),
                                 BRAUN_R(0.0), BRAUN_R(1.0), BRAUN_R(0.0)};

const braun_builtin braun_builtin_four_bar = {
    "four-bar",
    "double four-bar linkage of Sec. 4.2: 6 joint coordinates, 5 constraints",
    {6, 5, 0, BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC, mass, forces, holonomic, NULL, energy, NULL,
     /* Callbacks only read the parameters; void * has no const. */
     (void *)&params, NULL, NULL},
    q0,
    v0,
    4, /* joint 3: ε3 of Fig. 7 */
    5};
