/*
 * Slider-crank mechanism of Sec. 4.1 (Fig. 1): two uniform links of length
 * l and mass m; the crank turns about the origin, the slider end of the
 * second link stays on y = 0. Absolute coordinates
 *   q = [x1, y1, θ1, x2, y2, θ2]   (link centres and angles from horizontal).
 *
 * Minimal coordinate θ = θ1. On the constraint manifold θ2 = -θ and
 *   x1 = (l/2)c, y1 = (l/2)s, x2 = (3l/2)c, y2 = (l/2)s   (c, s of θ),
 * so the kinetic and potential energies are
 *   T = ½m(l²/4 θ'² + 9l²/4 s²θ'² + l²/4 c²θ'²) + 2·½(ml²/12)θ'²
 *     = ½ml²(2/3 + 2s²)θ'² = ½ml²(5/3 - cos 2θ)θ'² = ½J(θ)θ'²,
 *   V = mg(y1 + y2) = mgl s.
 * Lagrange: J θ'' + ½J'θ'² + V' = 0 with J' = 2ml² sin 2θ, V' = mgl c:
 *   ml²(5/3 - cos 2θ)θ'' + ml² sin 2θ θ'² + mgl c = 0,
 * which is Eq. 24 after multiplying by 3/(ml²). (Checked numerically in
 * tests/test_models.c.)
 */
#include <stddef.h>

#include "braun_models_internal.h"

static const braun_link_params params = {1.0, 1.0, 9.81, BRAUN_R(1.0), BRAUN_R(1.0),
                                          BRAUN_R(1.0) * BRAUN_R(9.81)};

/* Eq. 21: M = diag(m, m, ml²/12, m, m, ml²/12). */
static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_link_params *p = user;
    braun_real m = p->rm, l = p->rl;
    braun_real J = m * l * l / BRAUN_R(12.0);
    (void)t;
    (void)q;
    for (int i = 0; i < 36; ++i) M[i] = BRAUN_R(0.0);
    M[0 * 6 + 0] = m;
    M[1 * 6 + 1] = m;
    M[2 * 6 + 2] = J;
    M[3 * 6 + 3] = m;
    M[4 * 6 + 4] = m;
    M[5 * 6 + 5] = J;
    return 0;
}

/* Eq. 21: gravity on both link centres. */
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
    Q[3] = BRAUN_R(0.0);
    Q[4] = -mg;
    Q[5] = BRAUN_R(0.0);
    return 0;
}

/* Eq. 22 and its derivatives. Scleronomic, so b_q = 0 and
 * b_qv = -(∂(A_q v)/∂q) v = -(d/dt A_q) v. */
static int holonomic(braun_real t, const braun_real *q, const braun_real *v,
                     braun_real *phi, braun_real *A, braun_real *b,
                     braun_real *bv, void *user)
{
    const braun_link_params *p = user;
    braun_real h = BRAUN_R(0.5) * p->rl;
    braun_real c1, s1, c2, s2;
    braun_sincos(q[2], &s1, &c1);
    braun_sincos(q[5], &s2, &c2);
    (void)t;
    if (phi) {
        phi[0] = q[0] - h * c1;
        phi[1] = q[1] - h * s1;
        phi[2] = q[0] + h * c1 - q[3] + h * c2;
        phi[3] = q[1] + h * s1 - q[4] + h * s2;
        phi[4] = q[4] + h * s2;
    }
    if (A) {
        /* Every entry written once, zeros included: no zeroing pass (a
         * memset call per evaluation on a Cortex-M). */
        const braun_real o = BRAUN_R(0.0), e = BRAUN_R(1.0);
        braun_real *r = A;
        r[0] = e; r[1] = o; r[2] = h * s1;  r[3] = o;  r[4] = o;  r[5] = o;
        r += 6;
        r[0] = o; r[1] = e; r[2] = -h * c1; r[3] = o;  r[4] = o;  r[5] = o;
        r += 6;
        r[0] = e; r[1] = o; r[2] = -h * s1; r[3] = -e; r[4] = o;  r[5] = -h * s2;
        r += 6;
        r[0] = o; r[1] = e; r[2] = h * c1;  r[3] = o;  r[4] = -e; r[5] = h * c2;
        r += 6;
        r[0] = o; r[1] = o; r[2] = o;       r[3] = o;  r[4] = e;  r[5] = h * c2;
    }
    if (b)
        for (int i = 0; i < 5; ++i) b[i] = BRAUN_R(0.0);
    if (bv) {
        braun_real w1 = v[2] * v[2], w2 = v[5] * v[5];
        bv[0] = -h * c1 * w1;
        bv[1] = -h * s1 * w1;
        bv[2] = h * (c1 * w1 + c2 * w2);
        bv[3] = h * (s1 * w1 + s2 * w2);
        bv[4] = h * s2 * w2;
    }
    return 0;
}

/* Eq. 23: E = ½vᵀMv + mg(y1 + y2). Straight-line (M = diag(m, m, J, m,
 * m, J)): the callback runs twice a corrected step. */
static int energy(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *E, braun_real *dE_dq, braun_real *dE_dv,
                  braun_real *dE_dt, void *user)
{
    const braun_link_params *p = user;
    const braun_real m = p->rm, l = p->rl;
    const braun_real mg = p->rmg;
    const braun_real J = m * l * l / BRAUN_R(12.0);
    (void)t;
    if (E) {
        braun_real T = BRAUN_R(0.0);
        T += m * v[0] * v[0];
        T += m * v[1] * v[1];
        T += J * v[2] * v[2];
        T += m * v[3] * v[3];
        T += m * v[4] * v[4];
        T += J * v[5] * v[5];
        *E = BRAUN_R(0.5) * T + mg * (q[1] + q[4]);
    }
    if (dE_dq) {
        dE_dq[0] = BRAUN_R(0.0);
        dE_dq[1] = mg;
        dE_dq[2] = BRAUN_R(0.0);
        dE_dq[3] = BRAUN_R(0.0);
        dE_dq[4] = mg;
        dE_dq[5] = BRAUN_R(0.0);
    }
    if (dE_dv) {
        dE_dv[0] = m * v[0];
        dE_dv[1] = m * v[1];
        dE_dv[2] = J * v[2];
        dE_dv[3] = m * v[3];
        dE_dv[4] = m * v[4];
        dE_dv[5] = J * v[5];
    }
    if (dE_dt) *dE_dt = BRAUN_R(0.0);
    return 0;
}

static const braun_real q0[6] = {
    BRAUN_R(0.35355339059327379),  /* x1 = √2/4 */
    BRAUN_R(0.35355339059327379),  /* y1 = √2/4 */
    BRAUN_R(0.78539816339744828),  /* θ1 = π/4 */
    BRAUN_R(1.0606601717798214),   /* x2 = 3√2/4 */
    BRAUN_R(0.35355339059327379),  /* y2 = √2/4 */
    BRAUN_R(-0.78539816339744828)  /* θ2 = -π/4 */
};
static const braun_real v0[6] = {0};

const braun_builtin braun_builtin_slider_crank = {
    "slider-crank",
    "slider-crank of Sec. 4.1: 6 absolute coordinates, 5 constraints (Eq. 22)",
    {6, 5, 0, BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC, mass, forces, holonomic, NULL, energy, NULL,
     /* Callbacks only read the parameters; void * has no const. */
     (void *)&params, NULL, NULL},
    q0,
    v0,
    /* The paper plots the slider end (Fig. 2), which is no single coordinate
     * of q (it is x2 + (l/2)cos θ2); no ε point. */
    -1,
    -1};
