/* Test systems (see test_systems.h). Kept in double: the tests run on the
 * double build. */
#include <math.h>
#include <string.h>

#include "test_systems.h"

/* ---------------- pendulum ---------------- */
static int pend_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    const pendulum_params *p = u;
    (void)t; (void)q;
    M[0] = p->mass; M[1] = 0; M[2] = 0; M[3] = p->mass;
    if (p->bad_mass == 1) M[3] = -p->mass;
    if (p->bad_mass == 2) M[1] = 0.5;
    if (p->bad_mass == 3) M[2] = NAN;
    return 0;
}

static int pend_forces(braun_real t, const braun_real *q, const braun_real *v,
                       braun_real *Q, void *u)
{
    pendulum_params *p = u;
    (void)t; (void)q; (void)v;
    p->calls++;
    if (p->fail_code && p->calls >= p->fail_from && p->calls <= p->fail_to) return p->fail_code;
    Q[0] = 0;
    Q[1] = -p->mass * p->g;
    return 0;
}

static int pend_hol(braun_real t, const braun_real *q, const braun_real *v,
                    braun_real *phi, braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const pendulum_params *p = u;
    (void)t;
    const int m = p->redundancy ? 2 : 1;
    for (int r = 0; r < m; r++) {
        const double s = r == 1 && p->redundancy == 2 ? -3.0 : 1.0;
        if (phi) phi[r] = s * (q[0] * q[0] + q[1] * q[1] - p->L * p->L);
        if (A) { A[2 * r] = s * 2 * q[0]; A[2 * r + 1] = s * 2 * q[1]; }
        if (b) b[r] = 0;
        if (bv) bv[r] = -s * 2 * (v[0] * v[0] + v[1] * v[1]);
    }
    return 0;
}

static int pend_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                       braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    const pendulum_params *p = u;
    (void)t;
    if (E) *E = 0.5 * p->mass * (v[0] * v[0] + v[1] * v[1]) + p->mass * p->g * q[1];
    if (dq) { dq[0] = 0; dq[1] = p->mass * p->g; }
    if (dv) { dv[0] = p->mass * v[0]; dv[1] = p->mass * v[1]; }
    if (dt) *dt = 0;
    return 0;
}

braun_system pendulum_system(pendulum_params *prm)
{
    braun_system s = {2, prm->redundancy ? 2 : 1, 0, 0, pend_mass, pend_forces, pend_hol,
                      NULL, pend_energy, NULL, prm, NULL, NULL};
    if (!prm->bad_mass) s.flags = BRAUN_MASS_CONSTANT;
    return s;
}

/* ---------------- knife edge ---------------- */
static const double knife_m = 2.0, knife_J = 0.3;

static int knife_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    memset(M, 0, 9 * sizeof *M);
    M[0] = M[4] = knife_m;
    M[8] = knife_J;
    return 0;
}

static int zero_forces3(braun_real t, const braun_real *q, const braun_real *v,
                        braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = Q[1] = Q[2] = 0;
    return 0;
}

/* No velocity across the blade: -sinθ ẋ + cosθ ẏ = 0. */
static int knife_nh(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                    braun_real *A, braun_real *bv, void *u)
{
    (void)t; (void)u;
    const double s = sin(q[2]), c = cos(q[2]);
    if (phi) phi[0] = -s * v[0] + c * v[1];
    if (A) { A[0] = -s; A[1] = c; A[2] = 0; }
    if (bv) bv[0] = v[2] * (c * v[0] + s * v[1]);
    return 0;
}

static int knife_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                        braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    (void)t; (void)q; (void)u;
    if (E) *E = 0.5 * (knife_m * (v[0] * v[0] + v[1] * v[1]) + knife_J * v[2] * v[2]);
    if (dq) dq[0] = dq[1] = dq[2] = 0;
    if (dv) { dv[0] = knife_m * v[0]; dv[1] = knife_m * v[1]; dv[2] = knife_J * v[2]; }
    if (dt) *dt = 0;
    return 0;
}

braun_system knife_system(void)
{
    braun_system s = {3, 0, 1, BRAUN_MASS_CONSTANT, knife_mass, zero_forces3, NULL,
                      knife_nh, knife_energy, NULL, NULL, NULL, NULL};
    return s;
}

void knife_exact(double t, const double *q0, const double *v0, double *q, double *v)
{
    const double w = v0[2], th0 = q0[2];
    const double speed = cos(th0) * v0[0] + sin(th0) * v0[1];
    const double th = th0 + w * t;
    q[0] = q0[0] + speed / w * (sin(th) - sin(th0));
    q[1] = q0[1] - speed / w * (cos(th) - cos(th0));
    q[2] = th;
    v[0] = speed * cos(th);
    v[1] = speed * sin(th);
    v[2] = w;
}

/* ---------------- bead on a spinning rod ---------------- */
static int unit_mass2(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = M[3] = 1; M[1] = M[2] = 0;
    return 0;
}

static int zero_forces2(braun_real t, const braun_real *q, const braun_real *v,
                        braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = Q[1] = 0;
    return 0;
}

/* φ = -sin(ωt) x + cos(ωt) y: the bead stays on the rod at angle ωt. */
static int bead_hol(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                    braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const double w = *(const double *)u, s = sin(w * t), c = cos(w * t);
    if (phi) phi[0] = -s * q[0] + c * q[1];
    if (A) { A[0] = -s; A[1] = c; }
    if (b) b[0] = w * (c * q[0] + s * q[1]);
    if (bv) bv[0] = 2 * w * (c * v[0] + s * v[1]) - w * w * (s * q[0] - c * q[1]);
    return 0;
}

static int bead_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                       braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    (void)t; (void)q; (void)u;
    if (E) *E = 0.5 * (v[0] * v[0] + v[1] * v[1]);
    if (dq) dq[0] = dq[1] = 0;
    if (dv) { dv[0] = v[0]; dv[1] = v[1]; }
    if (dt) *dt = 0;
    return 0;
}

/* No power callback: the rod's force is the constraint force, whose power
 * (2 ω² r ṙ) the core adds to Ė itself. */
braun_system bead_system(double *omega)
{
    braun_system s = {2, 1, 0, BRAUN_MASS_CONSTANT, unit_mass2,
                      zero_forces2, bead_hol, NULL, bead_energy, NULL, omega, NULL, NULL};
    return s;
}

/* ---------------- generic 4-coordinate system ---------------- */
static const double GM[16] = {2.0, 0.3, 0.1, 0.0, 0.3, 1.5, 0.2, 0.1,
                              0.1, 0.2, 1.0, 0.3, 0.0, 0.1, 0.3, 0.8};
static const double gen_g = 3.0;

static int gen_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    for (int i = 0; i < 16; i++) M[i] = GM[i];
    return 0;
}

static int gen_forces(braun_real t, const braun_real *q, const braun_real *v,
                      braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = 0; Q[1] = -gen_g; Q[2] = 0; Q[3] = 0;
    return 0;
}

static int gen_hol(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                   braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)u;
    if (phi) { phi[0] = q[0] * q[0] + q[1] * q[1] - 1; phi[1] = q[2] - sin(q[3]); }
    if (A) {
        A[0] = 2 * q[0]; A[1] = 2 * q[1]; A[2] = 0; A[3] = 0;
        A[4] = 0; A[5] = 0; A[6] = 1; A[7] = -cos(q[3]);
    }
    if (b) b[0] = b[1] = 0;
    if (bv) { bv[0] = -2 * (v[0] * v[0] + v[1] * v[1]); bv[1] = -sin(q[3]) * v[3] * v[3]; }
    return 0;
}

static int gen_nh(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                  braun_real *A, braun_real *bv, void *u)
{
    (void)t; (void)u;
    const double s = sin(q[3]), c = cos(q[3]);
    if (phi) phi[0] = -s * v[0] + c * v[1] - 0.5 * v[3];
    if (A) { A[0] = -s; A[1] = c; A[2] = 0; A[3] = -0.5; }
    if (bv) bv[0] = v[3] * (c * v[0] + s * v[1]);
    return 0;
}

static int gen_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                      braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    (void)t; (void)u;
    double Mv[4];
    for (int i = 0; i < 4; i++) {
        Mv[i] = 0;
        for (int j = 0; j < 4; j++) Mv[i] += GM[i * 4 + j] * v[j];
    }
    if (E) *E = 0.5 * (Mv[0] * v[0] + Mv[1] * v[1] + Mv[2] * v[2] + Mv[3] * v[3]) + gen_g * q[1];
    if (dq) { dq[0] = 0; dq[1] = gen_g; dq[2] = 0; dq[3] = 0; }
    if (dv) for (int i = 0; i < 4; i++) dv[i] = Mv[i];
    if (dt) *dt = 0;
    return 0;
}

braun_system generic_system(void)
{
    braun_system s = {4, 2, 1, BRAUN_MASS_CONSTANT, gen_mass, gen_forces, gen_hol, gen_nh,
                      gen_energy, NULL, NULL, NULL, NULL};
    return s;
}

void generic_consistent_state(double *q, double *v)
{
    /* On the circle at angle a, heading b: the circle allows speed w along
     * its tangent, the blade row then fixes v3 = 2 w cos(b - a). */
    const double a = 0.3, b = a + 0.7, w = 0.7;
    q[0] = cos(a); q[1] = sin(a); q[3] = b; q[2] = sin(b);
    v[0] = -sin(a) * w; v[1] = cos(a) * w; v[3] = 2 * w * cos(b - a); v[2] = cos(b) * v[3];
}
