/* A pendulum in Cartesian coordinates: x² + y² = L², simulated for 10 s. */
#include <braun.h>
#include <stdio.h>

static const braun_real L = 1, m = 1, g = 9.81;

static int mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{ (void)t; (void)q; (void)u; M[0] = m; M[1] = M[2] = 0; M[3] = m; return 0; }

static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{ (void)t; (void)q; (void)v; (void)u; Q[0] = 0; Q[1] = -m * g; return 0; }

static int rod(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
               braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)u;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - L * L;     /* Φ_q */
    if (A) { A[0] = 2 * q[0]; A[1] = 2 * q[1]; }             /* A_q = ∂Φ_q/∂q */
    if (b) b[0] = 0;                                         /* b_q = -∂Φ_q/∂t */
    if (bv) bv[0] = -2 * (v[0] * v[0] + v[1] * v[1]);        /* b_qv */
    return 0;
}

static int energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                  braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    (void)t; (void)u;
    if (E) *E = 0.5 * m * (v[0] * v[0] + v[1] * v[1]) + m * g * q[1];
    if (dq) { dq[0] = 0; dq[1] = m * g; }
    if (dv) { dv[0] = m * v[0]; dv[1] = m * v[1]; }
    if (dt) *dt = 0;
    return 0;
}

int main(void)
{
    /* Nothing is driven: BRAUN_SCLERONOMIC (checked: b_q != 0 is refused)
     * saves the work rate of the constraints, zero here; without it the
     * result is the same up to round-off. */
    braun_system sys = {.n = 2, .m = 1, .p = 0, .flags = BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC,
                        .mass = mass, .forces = forces, .holonomic = rod, .energy = energy};
    braun_model model;
    braun_data data = {0};
    static unsigned char buffer[4096];           /* no allocation anywhere */
    const braun_real q0[2] = {L, 0}, v0[2] = {0, 0};
    int st = braun_model_init(&model, &sys);     /* all corrections by default */
    if (!st && braun_data_size(&model) > sizeof buffer) st = BRAUN_ERR_BUFFER;
    if (!st) st = braun_data_init(&data, &model, buffer, sizeof buffer);
    if (!st) st = braun_set_state(&data, 0, q0, v0);
    if (!st) st = braun_integrate(&data, BRAUN_RK4, 1e-3, 10.0, 0, NULL, NULL);
    braun_real pos, vel, en;
    if (!st) st = braun_residuals(&data, data.t, data.q, data.v, &pos, &vel, &en);
    if (st) { fprintf(stderr, "pendulum: %s\n", braun_status_str(st)); return 1; }
    printf("t = %g  q = (%.9f, %.9f)  |Phi_q| = %.1e  |Phi_e| = %.1e\n",
           (double)data.t, (double)data.q[0], (double)data.q[1], (double)pos, (double)en);
    return 0;
}
