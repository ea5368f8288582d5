/* Finite-difference checks of a braun_system's analytic derivatives, for
 * the scene tests (tests/test_scene_*.c). Every check uses first
 * differences only (central, step FD_H), so the truncation error is
 * O(FD_H²) and the comparison tolerance can be tight:
 *   A_q   = ∂Φ_q/∂q
 *   b_q   = -∂Φ_q/∂t
 *   b_qv  = -d/dε[A_q(t+ε, q+εv) v] + d/dε[b_q(t+ε, q+εv)]
 *           (= -(∂(A_q v)/∂q)v - 2(∂A_q/∂t)v - ∂²Φ_q/∂t², Sec. 2.2)
 *   A_vv  = ∂Φ_v/∂v,  b_vv = -d/dε[Φ_v(t+ε, q+εv, v)]
 *   dE/dq, dE/dv, dE/dt against E
 * and the energy rate dE/dt = Ė along the unconstrained flow M v' = Q at
 * any state (from the checked gradients, to round-off): the forces are
 * exactly Lagrangian (-∂V/∂q, Coriolis terms of M(q)) plus the terms whose
 * power the system reports. */
#ifndef SCENE_FD_H
#define SCENE_FD_H

#include "test_util.h"

#define FD_H 1e-6
#define FD_NMAX 40

/* |fd - an| <= tol·(1 + |an|), with the entry named on failure. */
static int fd_failures;
static void fd_check(const char *what, const char *term, int i, int j, double fd, double an,
                     double tol)
{
    if (fabs(fd - an) <= tol * (1.0 + fabs(an))) return;
    print_error("%s: %s[%d][%d] analytic %.12g, finite difference %.12g\n", what, term, i, j,
                an, fd);
    fd_failures++;
}

typedef struct fd_rows {
    double phi[FD_NMAX], A[FD_NMAX * FD_NMAX], b[FD_NMAX], bv[FD_NMAX];
} fd_rows;

static void fd_hol(const braun_system *s, double t, const double *q, const double *v, fd_rows *r)
{
    assert_int_equal(s->holonomic(t, q, v, r->phi, r->A, r->b, r->bv, s->user), 0);
}

static void fd_non(const braun_system *s, double t, const double *q, const double *v, fd_rows *r)
{
    assert_int_equal(s->nonholonomic(t, q, v, r->phi, r->A, r->bv, s->user), 0);
}

/* All checks at (t, q, v); tol relative. */
static void fd_check_system(const char *what, const braun_system *s, double t, const double *q,
                            const double *v, double tol)
{
    const int n = s->n, m = s->m, p = s->p;
    double qp[FD_NMAX], qm[FD_NMAX], vp[FD_NMAX], vm[FD_NMAX];
    fd_rows r0, rp, rm;
    assert_true(n <= FD_NMAX && m <= FD_NMAX && p <= FD_NMAX);
    fd_failures = 0;
    if (m > 0) {
        fd_hol(s, t, q, v, &r0);
        for (int j = 0; j < n; j++) {
            memcpy(qp, q, sizeof(double) * n);
            memcpy(qm, q, sizeof(double) * n);
            qp[j] += FD_H;
            qm[j] -= FD_H;
            fd_hol(s, t, qp, v, &rp);
            fd_hol(s, t, qm, v, &rm);
            for (int i = 0; i < m; i++)
                fd_check(what, "A_q", i, j, (rp.phi[i] - rm.phi[i]) / (2 * FD_H), r0.A[i * n + j],
                         tol);
        }
        fd_hol(s, t + FD_H, q, v, &rp);
        fd_hol(s, t - FD_H, q, v, &rm);
        for (int i = 0; i < m; i++)
            fd_check(what, "b_q", i, 0, -(rp.phi[i] - rm.phi[i]) / (2 * FD_H), r0.b[i], tol);
        for (int k = 0; k < n; k++) {
            qp[k] = q[k] + FD_H * v[k];
            qm[k] = q[k] - FD_H * v[k];
        }
        fd_hol(s, t + FD_H, qp, v, &rp);
        fd_hol(s, t - FD_H, qm, v, &rm);
        for (int i = 0; i < m; i++) {
            double dAv = 0;
            for (int k = 0; k < n; k++) dAv += (rp.A[i * n + k] - rm.A[i * n + k]) * v[k];
            const double db = rp.b[i] - rm.b[i];
            fd_check(what, "b_qv", i, 0, (-dAv + db) / (2 * FD_H), r0.bv[i], tol);
        }
    }
    if (p > 0) {
        fd_non(s, t, q, v, &r0);
        for (int j = 0; j < n; j++) {
            memcpy(vp, v, sizeof(double) * n);
            memcpy(vm, v, sizeof(double) * n);
            vp[j] += FD_H;
            vm[j] -= FD_H;
            fd_non(s, t, q, vp, &rp);
            fd_non(s, t, q, vm, &rm);
            for (int i = 0; i < p; i++)
                fd_check(what, "A_vv", i, j, (rp.phi[i] - rm.phi[i]) / (2 * FD_H),
                         r0.A[i * n + j], tol);
        }
        for (int k = 0; k < n; k++) {
            qp[k] = q[k] + FD_H * v[k];
            qm[k] = q[k] - FD_H * v[k];
        }
        fd_non(s, t + FD_H, qp, v, &rp);
        fd_non(s, t - FD_H, qm, v, &rm);
        for (int i = 0; i < p; i++)
            fd_check(what, "b_vv", i, 0, -(rp.phi[i] - rm.phi[i]) / (2 * FD_H), r0.bv[i], tol);
    }
    if (s->energy) {
        double E, Ep, Em, dEdq[FD_NMAX], dEdv[FD_NMAX], dEdt;
        assert_int_equal(s->energy(t, q, v, &E, dEdq, dEdv, &dEdt, s->user), 0);
        for (int j = 0; j < n; j++) {
            memcpy(qp, q, sizeof(double) * n);
            memcpy(qm, q, sizeof(double) * n);
            qp[j] += FD_H;
            qm[j] -= FD_H;
            assert_int_equal(s->energy(t, qp, v, &Ep, NULL, NULL, NULL, s->user), 0);
            assert_int_equal(s->energy(t, qm, v, &Em, NULL, NULL, NULL, s->user), 0);
            fd_check(what, "dE/dq", j, 0, (Ep - Em) / (2 * FD_H), dEdq[j], tol);
            memcpy(vp, v, sizeof(double) * n);
            memcpy(vm, v, sizeof(double) * n);
            vp[j] += FD_H;
            vm[j] -= FD_H;
            assert_int_equal(s->energy(t, q, vp, &Ep, NULL, NULL, NULL, s->user), 0);
            assert_int_equal(s->energy(t, q, vm, &Em, NULL, NULL, NULL, s->user), 0);
            fd_check(what, "dE/dv", j, 0, (Ep - Em) / (2 * FD_H), dEdv[j], tol);
        }
        assert_int_equal(s->energy(t + FD_H, q, v, &Ep, NULL, NULL, NULL, s->user), 0);
        assert_int_equal(s->energy(t - FD_H, q, v, &Em, NULL, NULL, NULL, s->user), 0);
        fd_check(what, "dE/dt", 0, 0, (Ep - Em) / (2 * FD_H), dEdt, tol);

        /* Energy rate along the unconstrained flow M v' = Q from (q, v):
         * dE/dt = ∂E/∂q·v + ∂E/∂v·a + ∂E/∂t with a = M^-1 Q, using the
         * gradients just checked against E; it must equal Ė. */
        double M[FD_NMAX * FD_NMAX], Q[FD_NMAX], a[FD_NMAX], Edot = 0, rate = dEdt;
        assert_int_equal(s->mass(t, q, M, s->user), 0);
        assert_int_equal(s->forces(t, q, v, Q, s->user), 0);
        /* a = M^-1 Q by Gaussian elimination (small n, M positive definite). */
        for (int i = 0; i < n; i++) a[i] = Q[i];
        for (int k = 0; k < n; k++)
            for (int i = k + 1; i < n; i++) {
                const double f = M[i * n + k] / M[k * n + k];
                for (int j = k; j < n; j++) M[i * n + j] -= f * M[k * n + j];
                a[i] -= f * a[k];
            }
        for (int i = n - 1; i >= 0; i--) {
            for (int j = i + 1; j < n; j++) a[i] -= M[i * n + j] * a[j];
            a[i] /= M[i * n + i];
        }
        /* The terms cancel (power is small beside them): compare with the
         * size of the terms, not of the sum. */
        double size = fabs(dEdt);
        for (int k = 0; k < n; k++) {
            rate += dEdq[k] * v[k] + dEdv[k] * a[k];
            size += fabs(dEdq[k] * v[k]) + fabs(dEdv[k] * a[k]);
        }
        if (s->flags & BRAUN_ENERGY_INPUT) assert_int_equal(s->power(t, q, v, &Edot, s->user), 0);
        else assert_null(s->power);
        if (!(fabs(rate - Edot) <= 1e-12 * (1 + size))) {
            print_error("%s: energy rate %.15g, input power %.15g (terms of size %.3g)\n", what,
                        rate, Edot, size);
            fd_failures++;
        }
    }
    if (fd_failures) fail_msg("%s: %d derivative checks failed", what, fd_failures);
}

/* Deterministic pseudo-random numbers in [-1, 1]. */
static double fd_urand(void)
{
    static unsigned long x = 88172645463325252ul;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return (double)(x % 2000001ul) / 1000000.0 - 1.0;
}

#endif
