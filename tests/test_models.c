/*
 * Built-in models (src/models): callbacks against finite differences, the
 * paper's initial states against the constraints, the minimal-coordinate
 * equations against the constrained dynamics, and the references.
 * Needs only src/models, not the solver.
 */
#include "test_util.h"

#include "braun_reference.h"

#define PI 3.14159265358979323846
#define NMAX BRAUN_MODEL_MAX_N
#define KMAX (2 * BRAUN_MODEL_MAX_N) /* n + m of the KKT system */

/* Callbacks compute in braun_real: float builds get float tolerances. */
#ifdef BRAUN_SINGLE
#define TOL_EXACT 1e-6  /* a quantity that is zero up to rounding */
#define FD_STEP 1e-2    /* central differences: error h² vs ε/h */
#define TOL_FD 1e-3
#define TOL_DYN 1e-3    /* KKT vs minimal acceleration */
#define TOL_ENERGY_REF 4e-4
#define TOL_CONSTRAINT_REF 1e-9
#define EL_STEP 1e-2    /* Euler–Lagrange check: differences of J, V */
#define TOL_EL 1e-2
#else
#define TOL_EXACT 1e-12
#define FD_STEP 1e-6
#define TOL_FD 1e-6
/* Central differences of 1e-6 (error ~1e-12 + round-off 1e-16/1e-6):
 * measured 2.8e-11, 4.1e-11, 1.7e-11 (slider-crank, four-bar, pendulum). */
#define TOL_DYN 1.5e-10
/* The model's energy law and constraints along the references over 10 s:
 * measured |E - E0| 1.2e-13, 1.4e-13, 6.5e-15; constraints 1.1e-15,
 * 3.6e-15, 8.9e-16. */
#define TOL_ENERGY_REF 5e-13
#define TOL_CONSTRAINT_REF 1e-14
#define EL_STEP 1e-5
/* Measured 3.5e-11, 3.2e-11, 2.4e-11. */
#define TOL_EL 1e-10
#endif

/* ------------------------------------------------------------ helpers */

static unsigned long rng_state = 12345u;

/* Uniform in [-1, 1], deterministic (LCG of Numerical Recipes). */
static double urand(void)
{
    rng_state = (1664525u * rng_state + 1013904223u) & 0xffffffffu;
    return 2.0 * (double)rng_state / 4294967295.0 - 1.0;
}

static void to_real(int n, const double *x, braun_real *y)
{
    for (int i = 0; i < n; ++i) y[i] = (braun_real)x[i];
}

static void to_double(int n, const braun_real *x, double *y)
{
    if (y)
        for (int i = 0; i < n; ++i) y[i] = (double)x[i];
}

static void call_mass(const braun_builtin *b, const double *q, double *M)
{
    int n = b->sys.n;
    braun_real qr[NMAX] = {0}, Mr[NMAX * NMAX];
    to_real(n, q, qr);
    assert_int_equal(b->sys.mass(0, qr, Mr, b->sys.user), 0);
    to_double(n * n, Mr, M);
}

static void call_forces(const braun_builtin *b, const double *q,
                        const double *v, double *Q)
{
    int n = b->sys.n;
    braun_real qr[NMAX] = {0}, vr[NMAX] = {0}, Qr[NMAX];
    to_real(n, q, qr);
    to_real(n, v, vr);
    assert_int_equal(b->sys.forces(0, qr, vr, Qr, b->sys.user), 0);
    to_double(n, Qr, Q);
}

/* Any output may be NULL: the callback must then not write it. */
static void call_holonomic(const braun_builtin *b, const double *q,
                           const double *v, double *phi, double *A, double *bq,
                           double *bv)
{
    int n = b->sys.n, m = b->sys.m;
    braun_real qr[NMAX] = {0}, vr[NMAX] = {0}, pr[NMAX], Ar[NMAX * NMAX],
        br[NMAX], bvr[NMAX];
    to_real(n, q, qr);
    to_real(n, v, vr);
    assert_int_equal(b->sys.holonomic(0, qr, vr, phi ? pr : NULL,
                                         A ? Ar : NULL, bq ? br : NULL,
                                         bv ? bvr : NULL, b->sys.user),
                     0);
    if (phi) to_double(m, pr, phi);
    if (A) to_double(m * n, Ar, A);
    if (bq) to_double(m, br, bq);
    if (bv) to_double(m, bvr, bv);
}

static void call_energy(const braun_builtin *b, const double *q,
                        const double *v, double *E, double *dq, double *dv,
                        double *dt)
{
    int n = b->sys.n;
    braun_real qr[NMAX] = {0}, vr[NMAX] = {0}, Er, dqr[NMAX], dvr[NMAX], dtr;
    to_real(n, q, qr);
    to_real(n, v, vr);
    assert_int_equal(b->sys.energy(0, qr, vr, E ? &Er : NULL,
                                      dq ? dqr : NULL, dv ? dvr : NULL,
                                      dt ? &dtr : NULL, b->sys.user),
                     0);
    if (E) *E = (double)Er;
    if (dq) to_double(n, dqr, dq);
    if (dv) to_double(n, dvr, dv);
    if (dt) *dt = (double)dtr;
}

static double scalar_energy(const braun_builtin *b, const double *q,
                            const double *v)
{
    double E;
    call_energy(b, q, v, &E, NULL, NULL, NULL);
    return E;
}

/* |fd - an| <= TOL_FD (1 + |an|), reported with the entry. */
static void check_fd(const char *model, const char *what, int i, int j,
                     double fd, double an)
{
    if (!(fabs(fd - an) <= TOL_FD * (1.0 + fabs(an)))) {
        print_error("%s: %s[%d][%d] analytic %.12g, finite difference %.12g\n",
                    model, what, i, j, an, fd);
        fail();
    }
}

/* Solve the dense k x k system K x = r by Gaussian elimination with partial
 * pivoting (K, r overwritten). Returns 0, or -1 if singular. */
static int gauss_solve(int k, double *K, double *r, double *x)
{
    for (int c = 0; c < k; ++c) {
        int piv = c;
        for (int i = c + 1; i < k; ++i)
            if (fabs(K[i * k + c]) > fabs(K[piv * k + c])) piv = i;
        if (fabs(K[piv * k + c]) < 1e-300) return -1;
        if (piv != c) {
            for (int j = 0; j < k; ++j) {
                double t = K[c * k + j];
                K[c * k + j] = K[piv * k + j];
                K[piv * k + j] = t;
            }
            double t = r[c];
            r[c] = r[piv];
            r[piv] = t;
        }
        for (int i = c + 1; i < k; ++i) {
            double f = K[i * k + c] / K[c * k + c];
            for (int j = c; j < k; ++j) K[i * k + j] -= f * K[c * k + j];
            r[i] -= f * r[c];
        }
    }
    for (int i = k - 1; i >= 0; --i) {
        double s = r[i];
        for (int j = i + 1; j < k; ++j) s -= K[i * k + j] * x[j];
        x[i] = s / K[i * k + i];
    }
    return 0;
}

/* Ideal constrained acceleration: [M Aᵀ; A 0][a; λ] = [Q; b_qv]. Q may be
 * given (to try a different force vector), else the model's. */
static int kkt_acceleration(const braun_builtin *b, const double *q,
                            const double *v, const double *Q_in, double *a)
{
    int n = b->sys.n, m = b->sys.m, k = n + m;
    double M[NMAX * NMAX], Q[NMAX], A[NMAX * NMAX], bv[NMAX];
    double K[KMAX * KMAX], r[KMAX], x[KMAX];
    call_mass(b, q, M);
    if (Q_in)
        for (int i = 0; i < n; ++i) Q[i] = Q_in[i];
    else
        call_forces(b, q, v, Q);
    call_holonomic(b, q, v, NULL, A, NULL, bv);
    for (int i = 0; i < k * k; ++i) K[i] = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) K[i * k + j] = M[i * n + j];
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j)
            K[(n + i) * k + j] = K[j * k + n + i] = A[i * n + j];
    for (int i = 0; i < n; ++i) r[i] = Q[i];
    for (int i = 0; i < m; ++i) r[n + i] = bv[i];
    if (gauss_solve(k, K, r, x) != 0) return -1;
    for (int i = 0; i < n; ++i) a[i] = x[i];
    return 0;
}

/* d/dt of the lifted velocity along y' = f(y): the acceleration the minimal
 * equation implies for the absolute coordinates (central difference). */
static void minimal_acceleration(const braun_builtin *b, const double *y,
                                 double *a)
{
    const braun_link_params *p = b->sys.user;
    int n = b->sys.n, d = braun_minimal_find(b->name)->dim;
    double f[4], yp[4], ym[4], q[NMAX], vp[NMAX], vm[NMAX];
    const double h = 1e-6;
    braun_minimal_find(b->name)->rhs(0.0, y, f, p);
    for (int i = 0; i < d; ++i) {
        yp[i] = y[i] + h * f[i];
        ym[i] = y[i] - h * f[i];
    }
    braun_minimal_find(b->name)->to_state(yp, q, vp, p);
    braun_minimal_find(b->name)->to_state(ym, q, vm, p);
    for (int i = 0; i < n; ++i) a[i] = (vp[i] - vm[i]) / (2.0 * h);
}

static double max_abs(int n, const double *x)
{
    double r = 0.0;
    for (int i = 0; i < n; ++i) r = fmax(r, fabs(x[i]));
    return r;
}

/* ------------------------------------------------------------- tests */

static void test_table(void **state)
{
    (void)state;
    int count = 0;
    for (const braun_builtin *b; (b = braun_builtin_at(count)) != NULL; ++count) {
        assert_ptr_equal(braun_builtin_find(b->name), b);
        assert_non_null(b->description);
        assert_true(b->sys.n > 0 && b->sys.n <= NMAX);
        assert_true(b->sys.m >= 0 && b->sys.m <= NMAX && b->sys.p == 0);
        assert_true(b->sys.flags & BRAUN_MASS_CONSTANT);
        assert_true(!(b->sys.flags & BRAUN_ENERGY_INPUT));
        assert_non_null(b->sys.mass);
        assert_non_null(b->sys.forces);
        assert_non_null(b->sys.holonomic);
        assert_non_null(b->sys.energy);
        assert_non_null(b->sys.user);
        assert_int_equal(braun_minimal_find(b->name)->dim, 2);
        assert_non_null(braun_minimal_find(b->name)->rhs);
        assert_non_null(braun_minimal_find(b->name)->to_state);
        assert_true((b->point_x < 0 && b->point_y < 0)
                    || (b->point_x < b->sys.n && b->point_y < b->sys.n));
    }
    assert_int_equal(count, 3);
    assert_null(braun_builtin_at(-1));
    assert_null(braun_builtin_find("no-such-model"));
    assert_null(braun_builtin_find(NULL));
    assert_non_null(braun_builtin_find("slider-crank"));
    assert_non_null(braun_builtin_find("four-bar"));
    assert_non_null(braun_builtin_find("pendulum"));
    assert_null(braun_minimal_find("slider-crank")->exact);
    assert_non_null(braun_minimal_find("four-bar")->exact);
    assert_int_equal(braun_builtin_find("four-bar")->point_x, 4); /* x3 */
    assert_int_equal(braun_builtin_find("four-bar")->point_y, 5); /* y3 */
}

/* The paper's initial state satisfies Φ_q = 0 and A_q v0 = b_q, and it is
 * the lift of the minimal initial state. */
static void test_initial_state(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n, m = b->sys.m;
        double q[NMAX], v[NMAX], phi[NMAX], A[NMAX * NMAX], bq[NMAX];
        to_double(n, b->q0, q);
        to_double(n, b->v0, v);
        call_holonomic(b, q, v, phi, A, bq, NULL);
        for (int i = 0; i < m; ++i) {
            double Av = 0.0;
            for (int j = 0; j < n; ++j) Av += A[i * n + j] * v[j];
            assert_near(phi[i], 0.0, TOL_EXACT);
            assert_near(Av, bq[i], TOL_EXACT);
        }
        double ql[NMAX], vl[NMAX];
        braun_minimal_find(b->name)->to_state(braun_minimal_find(b->name)->y0, ql, vl, b->sys.user);
        for (int j = 0; j < n; ++j) {
            assert_near(ql[j], q[j], TOL_EXACT);
            assert_near(vl[j], v[j], TOL_EXACT);
        }
    }
}

/* A random state near the initial one (off the constraint manifold), or
 * the initial state itself for trial 0. */
static void trial_state(const braun_builtin *b, int trial, double *q,
                        double *v)
{
    for (int j = 0; j < b->sys.n; ++j) {
        q[j] = (double)b->q0[j] + (trial ? 0.1 * urand() : 0.0);
        v[j] = (double)b->v0[j] + (trial ? urand() : 0.0);
    }
}

/* A_q = ∂Φ_q/∂q and b_qv = -(∂(A_q v)/∂q) v, the latter as the derivative
 * of A_q(q + εv) v in ε; b_q = 0 (scleronomic). */
static void test_constraint_derivatives(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n, m = b->sys.m;
        for (int trial = 0; trial < 4; ++trial) {
            double q[NMAX], v[NMAX], A[NMAX * NMAX], bq[NMAX], bv[NMAX];
            trial_state(b, trial, q, v);
            call_holonomic(b, q, v, NULL, A, bq, bv);
            for (int i = 0; i < m; ++i) assert_near(bq[i], 0.0, 0.0);
            for (int j = 0; j < n; ++j) {
                double qp[NMAX], qm[NMAX], pp[NMAX], pm[NMAX];
                for (int i = 0; i < n; ++i) qp[i] = qm[i] = q[i];
                qp[j] += FD_STEP;
                qm[j] -= FD_STEP;
                call_holonomic(b, qp, v, pp, NULL, NULL, NULL);
                call_holonomic(b, qm, v, pm, NULL, NULL, NULL);
                for (int i = 0; i < m; ++i)
                    check_fd(b->name, "A_q", i, j,
                             (pp[i] - pm[i]) / (2 * FD_STEP), A[i * n + j]);
            }
            double qp[NMAX], qm[NMAX], Ap[NMAX * NMAX], Am[NMAX * NMAX];
            for (int i = 0; i < n; ++i) {
                qp[i] = q[i] + FD_STEP * v[i];
                qm[i] = q[i] - FD_STEP * v[i];
            }
            call_holonomic(b, qp, v, NULL, Ap, NULL, NULL);
            call_holonomic(b, qm, v, NULL, Am, NULL, NULL);
            for (int i = 0; i < m; ++i) {
                double dAv = 0.0;
                for (int j = 0; j < n; ++j)
                    dAv += (Ap[i * n + j] - Am[i * n + j]) * v[j];
                check_fd(b->name, "b_qv", i, 0, -dAv / (2 * FD_STEP), bv[i]);
            }
        }
    }
}

/* dE/dq, dE/dv (= A_e), dE/dt against E; M symmetric positive definite;
 * Q = -∂V/∂q with V = E(q, 0): the forces and the energy law agree. */
static void test_energy_and_mass(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n;
        for (int trial = 0; trial < 4; ++trial) {
            double q[NMAX], v[NMAX], E, dq[NMAX], dv[NMAX], dt;
            trial_state(b, trial, q, v);
            call_energy(b, q, v, &E, dq, dv, &dt);
            assert_near(dt, 0.0, 0.0);
            for (int j = 0; j < n; ++j) {
                double xp[NMAX], xm[NMAX];
                for (int i = 0; i < n; ++i) xp[i] = xm[i] = q[i];
                xp[j] += FD_STEP;
                xm[j] -= FD_STEP;
                check_fd(b->name, "dE_dq", j, 0,
                         (scalar_energy(b, xp, v) - scalar_energy(b, xm, v))
                             / (2 * FD_STEP),
                         dq[j]);
                for (int i = 0; i < n; ++i) xp[i] = xm[i] = v[i];
                xp[j] += FD_STEP;
                xm[j] -= FD_STEP;
                check_fd(b->name, "dE_dv", j, 0,
                         (scalar_energy(b, q, xp) - scalar_energy(b, q, xm))
                             / (2 * FD_STEP),
                         dv[j]);
            }
            /* Forces are conservative with the energy law's potential. */
            double zero[NMAX] = {0}, Q[NMAX], dV[NMAX];
            call_forces(b, q, v, Q);
            call_energy(b, q, zero, NULL, dV, NULL, NULL);
            for (int j = 0; j < n; ++j) assert_near(Q[j], -dV[j], TOL_EXACT);
            /* E = ½vᵀMv + V: the law's kinetic part is the mass matrix's. */
            double M[NMAX * NMAX], T = 0.0;
            call_mass(b, q, M);
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) T += 0.5 * v[i] * M[i * n + j] * v[j];
            assert_near(E - scalar_energy(b, q, zero), T,
                        TOL_EXACT * (1.0 + fabs(E)));
            /* Symmetric, and Cholesky succeeds with positive pivots. */
            double L[NMAX * NMAX];
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    assert_near(M[i * n + j], M[j * n + i], 0.0);
                    L[i * n + j] = M[i * n + j];
                }
            for (int j = 0; j < n; ++j) {
                double d = L[j * n + j];
                for (int c = 0; c < j; ++c) d -= L[j * n + c] * L[j * n + c];
                assert_true(d > 1e-3 * M[j * n + j]);
                L[j * n + j] = sqrt(d);
                for (int i = j + 1; i < n; ++i) {
                    double s = L[i * n + j];
                    for (int c = 0; c < j; ++c) s -= L[i * n + c] * L[j * n + c];
                    L[i * n + j] = s / L[j * n + j];
                }
            }
        }
    }
}

/* Outputs passed as NULL are not wanted: each output alone equals the same
 * output computed together with the others. */
static void test_null_outputs(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n, m = b->sys.m;
        double q[NMAX], v[NMAX];
        trial_state(b, 1, q, v);
        double phi[NMAX], A[NMAX * NMAX], bq[NMAX], bv[NMAX];
        double phi1[NMAX], A1[NMAX * NMAX], bq1[NMAX], bv1[NMAX];
        call_holonomic(b, q, v, phi, A, bq, bv);
        call_holonomic(b, q, v, phi1, NULL, NULL, NULL);
        call_holonomic(b, q, v, NULL, A1, NULL, NULL);
        call_holonomic(b, q, v, NULL, NULL, bq1, NULL);
        call_holonomic(b, q, v, NULL, NULL, NULL, bv1);
        for (int i = 0; i < m; ++i) {
            assert_near(phi1[i], phi[i], 0.0);
            assert_near(bq1[i], bq[i], 0.0);
            assert_near(bv1[i], bv[i], 0.0);
            for (int j = 0; j < n; ++j) assert_near(A1[i * n + j], A[i * n + j], 0.0);
        }
        double E, dq[NMAX], dv[NMAX], dt, E1, dq1[NMAX], dv1[NMAX], dt1;
        call_energy(b, q, v, &E, dq, dv, &dt);
        call_energy(b, q, v, &E1, NULL, NULL, NULL);
        call_energy(b, q, v, NULL, dq1, NULL, NULL);
        call_energy(b, q, v, NULL, NULL, dv1, NULL);
        call_energy(b, q, v, NULL, NULL, NULL, &dt1);
        assert_near(E1, E, 0.0);
        assert_near(dt1, dt, 0.0);
        for (int j = 0; j < n; ++j) {
            assert_near(dq1[j], dq[j], 0.0);
            assert_near(dv1[j], dv[j], 0.0);
        }
    }
}

/* Along the exact (or fine) minimal solution, lifted to q, v, the model's
 * own constraints hold and its energy law is constant. */
static void test_energy_along_reference(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n, m = b->sys.m;
        braun_reference ref;
        assert_int_equal(braun_reference_init(&ref, b, 0.0), BRAUN_OK);
        double q[NMAX], v[NMAX], E0 = 0.0, worst = 0.0, worst_c = 0.0;
        for (int i = 0; i <= 1000; ++i) {
            double t = 0.01 * i;
            assert_int_equal(braun_reference_eval(&ref, t, q, v), BRAUN_OK);
            double E = scalar_energy(b, q, v);
            if (i == 0) E0 = E;
            worst = fmax(worst, fabs(E - E0));
            double phi[NMAX], A[NMAX * NMAX];
            call_holonomic(b, q, v, phi, A, NULL, NULL);
            for (int r = 0; r < m; ++r) {
                double Av = 0.0;
                for (int j = 0; j < n; ++j) Av += A[r * n + j] * v[j];
                worst_c = fmax(worst_c, fmax(fabs(phi[r]), fabs(Av)));
            }
        }
        print_message("%-13s reference over 10 s: |E - E0| <= %.2e, "
                      "constraints <= %.2e\n",
                      b->name, worst, worst_c);
        assert_le(worst, TOL_ENERGY_REF);
        assert_le(worst_c, TOL_CONSTRAINT_REF);
    }
}

/* The minimal equation is the constrained dynamics: at lifted states the
 * KKT (Udwadia–Kalaba) acceleration equals d/dt of the lifted velocity. */
static void test_minimal_matches_kkt(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        int n = b->sys.n;
        /* θ away from the four-bar's singular horizontal positions. */
        static const double thetas[] = {0.3, 1.0, 2.0, -0.7, -2.5, 4.0};
        double worst = 0.0;
        for (int s = 0; s < 6; ++s) {
            double y[2] = {thetas[s], s == 0 ? 0.0 : 2.0 * urand()};
            if (s == 1) {
                y[0] = braun_minimal_find(b->name)->y0[0];
                y[1] = braun_minimal_find(b->name)->y0[1];
            }
            double q[NMAX], v[NMAX], a_kkt[NMAX], a_min[NMAX];
            braun_minimal_find(b->name)->to_state(y, q, v, b->sys.user);
            assert_int_equal(kkt_acceleration(b, q, v, NULL, a_kkt), 0);
            minimal_acceleration(b, y, a_min);
            double scale = 1.0 + max_abs(n, a_min);
            for (int j = 0; j < n; ++j)
                worst = fmax(worst, fabs(a_kkt[j] - a_min[j]) / scale);
        }
        print_message("%-13s max |a_KKT - a_minimal| / (1 + |a|) = %.2e\n",
                      b->name, worst);
        assert_le(worst, TOL_DYN);
    }
}

/* The four-bar force vector as printed in Sec. 4.2 has +3/2 mg in its
 * fourth entry. The check above must reject it. */
static void test_four_bar_printed_force_is_wrong(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("four-bar");
    const braun_link_params *p = b->sys.user;
    double y[2] = {1.0, -1.0}, q[NMAX], v[NMAX], a_kkt[NMAX], a_min[NMAX];
    double Q_printed[6] = {0, -p->m * p->g, 0, 1.5 * p->m * p->g, 0,
                           -p->m * p->g};
    braun_minimal_find(b->name)->to_state(y, q, v, p);
    assert_int_equal(kkt_acceleration(b, q, v, Q_printed, a_kkt), 0);
    minimal_acceleration(b, y, a_min);
    double worst = 0.0;
    for (int j = 0; j < 6; ++j) worst = fmax(worst, fabs(a_kkt[j] - a_min[j]));
    print_message("four-bar with the printed +3/2 mg: |a_KKT - a_minimal| = %.3g\n",
                  worst);
    assert_true(worst > 1.0);
}

/* The minimal equation is the Euler–Lagrange equation of the Lagrangian
 * the model's energy law implies on the manifold: with T = ½J(θ)θ'² and
 * V(θ) from E(lift(θ, θ')), θ'' = -(½J'θ'² + V')/J. */
static void test_minimal_is_euler_lagrange(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); ++k) {
        const braun_builtin *b = braun_builtin_at(k);
        const braun_link_params *p = b->sys.user;
        double worst = 0.0;
        for (double th = -3.0; th <= 3.0; th += 0.37) {
            /* J(θ) = 2 T(θ, 1); V(θ) = E(θ, 0). Computed in double from the
             * lift and M (not through braun_real). */
            double Jv[3], Vv[3];
            const double h = EL_STEP;
            for (int s = 0; s < 3; ++s) {
                double y[2] = {th + (s - 1) * h, 1.0}, q[NMAX], v[NMAX];
                double M[NMAX * NMAX], zero[NMAX] = {0};
                int n = b->sys.n;
                braun_minimal_find(b->name)->to_state(y, q, v, p);
                call_mass(b, q, M);
                double T = 0.0;
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) T += 0.5 * v[i] * M[i * n + j] * v[j];
                Jv[s] = 2.0 * T;
                Vv[s] = scalar_energy(b, q, zero);
            }
            double J = Jv[1], dJ = (Jv[2] - Jv[0]) / (2 * h);
            double dV = (Vv[2] - Vv[0]) / (2 * h);
            for (double w = -2.0; w <= 2.0; w += 1.0) {
                double y[2] = {th, w}, f[2];
                braun_minimal_find(b->name)->rhs(0.0, y, f, p);
                double el = -(0.5 * dJ * w * w + dV) / J;
                worst = fmax(worst, fabs(f[1] - el) / (1.0 + fabs(el)));
                assert_near(f[0], w, 0.0);
            }
        }
        print_message("%-13s minimal rhs vs Euler-Lagrange: %.2e\n", b->name,
                      worst);
        assert_le(worst, TOL_EL);
    }
}

/* The closed forms quoted in the comments: slider-crank
 * T = ½ml²(5/3 - cos 2θ)θ'², V = mgl sin θ (Eq. 24); four-bar
 * T = ½(3m)l²θ'², V = (7/2)mgl sin θ. */
static void test_minimal_energies(void **state)
{
    (void)state;
    const braun_builtin *sc = braun_builtin_find("slider-crank");
    const braun_builtin *fb = braun_builtin_find("four-bar");
    const braun_link_params *p = sc->sys.user;
    double l = p->l, m = p->m, g = p->g;
    for (double th = -4.0; th <= 4.0; th += 0.29) {
        double y[2] = {th, 0.8}, q[NMAX], v[NMAX];
        braun_minimal_find(sc->name)->to_state(y, q, v, p);
        double E = scalar_energy(sc, q, v);
        double want = 0.5 * m * l * l * (5.0 / 3.0 - cos(2 * th)) * 0.64
                      + m * g * l * sin(th);
        assert_near(E, want, TOL_EXACT * 100);
        braun_minimal_find(fb->name)->to_state(y, q, v, fb->sys.user);
        E = scalar_energy(fb, q, v);
        want = 0.5 * 3.0 * m * l * l * 0.64 + 3.5 * m * g * l * sin(th);
        assert_near(E, want, TOL_EXACT * 100);
    }
}

/* ------------------------------------------- references, independently
 * The references (src/host/reference: the four-bar and the pendulum in
 * closed form through Jacobi elliptic functions, the slider-crank's Eq. 24
 * integrated by RK4 substeps) are checked here against what shares none of
 * their code: the minimal equations, the parallelogram's and the crank's
 * geometry and the paper's parameters written out below, integrated by this
 * file's own RK4; the energy each equation conserves; and, for the closed
 * forms, the period from the complete elliptic integral K (by the AGM, here)
 * and from the period integral (trapezoidal rule, here). */

/* The paper's parameters (Sec. 4): l = 1 m, m = 1 kg, g = 9.81 m/s². */
#define PAPER_L 1.0
#define PAPER_M 1.0
#define PAPER_G 9.81

typedef double (*accel_fn)(double th, double w);

/* Fig. 6 caption: θ'' + (7g/6l) cos θ = 0. */
static double four_bar_accel(double th, double w)
{
    (void)w;
    return -7.0 * PAPER_G / (6.0 * PAPER_L) * cos(th);
}

/* phi'' = -(g/l) sin phi. */
static double pendulum_accel(double th, double w)
{
    (void)w;
    return -PAPER_G / PAPER_L * sin(th);
}

/* Eq. 24: (5 - 3 cos 2θ) θ'' = -3 (sin 2θ θ'² + (g/l) cos θ). */
static double slider_crank_accel(double th, double w)
{
    return -3.0 * (sin(2.0 * th) * w * w + PAPER_G / PAPER_L * cos(th))
           / (5.0 - 3.0 * cos(2.0 * th));
}

/* One classic RK4 step of θ'' = f(θ, θ') with compensated sums (this file's
 * own; the references have theirs, the core its tableau). */
static void own_rk4(accel_fn f, double h, double *y, double *comp)
{
    double k1[2], k2[2], k3[2], k4[2];
    k1[0] = y[1];
    k1[1] = f(y[0], y[1]);
    k2[0] = y[1] + 0.5 * h * k1[1];
    k2[1] = f(y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]);
    k3[0] = y[1] + 0.5 * h * k2[1];
    k3[1] = f(y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]);
    k4[0] = y[1] + h * k3[1];
    k4[1] = f(y[0] + h * k3[0], y[1] + h * k3[1]);
    for (int j = 0; j < 2; ++j) {
        double add = h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]) - comp[j];
        double sum = y[j] + add;
        comp[j] = (sum - y[j]) - add;
        y[j] = sum;
    }
}

/* Geometry (Sec. 4, Figs. 1 and 5), written out: the four-bar's joints i at
 * ((i-1)l + l cos θ, l sin θ); the pendulum's bob at (l sin phi, -l cos phi);
 * the slider-crank's crank centre (l/2 cos θ, l/2 sin θ, θ) and connecting
 * rod centre (3l/2 cos θ, l/2 sin θ, -θ). */
static void own_lift(const char *model, const double *y, double *q, double *v)
{
    const double c = cos(y[0]), s = sin(y[0]), w = y[1], l = PAPER_L;
    if (strcmp(model, "four-bar") == 0) {
        for (int i = 0; i < 3; ++i) {
            q[2 * i] = i * l + l * c;
            q[2 * i + 1] = l * s;
            v[2 * i] = -l * s * w;
            v[2 * i + 1] = l * c * w;
        }
    } else if (strcmp(model, "pendulum") == 0) {
        q[0] = l * s;
        q[1] = -l * c;
        v[0] = l * c * w;
        v[1] = l * s * w;
    } else {
        const double h = 0.5 * l;
        const double qq[6] = {h * c, h * s, y[0], 3 * h * c, h * s, -y[0]};
        const double vv[6] = {-h * s * w, h * c * w, w, -3 * h * s * w, h * c * w, -w};
        memcpy(q, qq, sizeof qq);
        memcpy(v, vv, sizeof vv);
    }
}

/* K(k) = π / (2 AGM(1, k')), k' = √(1 - k²) given directly (A&S 17.6). */
static double own_K(double kprime)
{
    long double a = 1.0L, b = kprime;
    for (int i = 0; i < 60 && fabsl(a - b) > 1e-19L * a; ++i) {
        long double an = 0.5L * (a + b);
        b = sqrtl(a * b);
        a = an;
    }
    return (double)(PI / (2.0L * a));
}

/* The paper's references against this file's RK4 of the equation written
 * above (h = 2e-5 with compensated sums: its error ~1e-14), through this
 * file's lift, every 0.1 s over 20 s, and the paper's parameters and initial
 * states: four-bar θ = π/2, θ' = -1 (Fig. 5), pendulum released at rest from
 * the horizontal, slider-crank at rest with the crank at 45° (Fig. 1). */
static void test_references_vs_own_integration(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        accel_fn f;
        double y0[2], bound;
    } cases[] = {
        /* max |q, v - own| measured 6.0e-13, 5.7e-14, 3.8e-13 */
        {"four-bar", four_bar_accel, {PI / 2.0, -1.0}, 2e-12},
        {"pendulum", pendulum_accel, {PI / 2.0, 0.0}, 2e-13},
        {"slider-crank", slider_crank_accel, {PI / 4.0, 0.0}, 1e-12},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const braun_builtin *b = braun_builtin_find(cases[c].name);
        const braun_link_params *p = b->sys.user;
        const int n = b->sys.n;
        assert_near(p->l, PAPER_L, 0.0);
        assert_near(p->m, PAPER_M, 0.0);
        assert_near(p->g, PAPER_G, 0.0);
        braun_reference ref;
        assert_int_equal(braun_reference_init(&ref, b, 0.0), BRAUN_OK);
        double y[2] = {cases[c].y0[0], cases[c].y0[1]}, comp[2] = {0, 0}, worst = 0.0;
        const double h = 2e-5;
        const long per_sample = 5000; /* 0.1 s */
        for (long i = 0; i <= 200 * per_sample; ++i) {
            if (i % per_sample == 0) {
                double q[NMAX], v[NMAX], qo[NMAX], vo[NMAX];
                assert_int_equal(braun_reference_eval(&ref, (double)i * h, q, v), BRAUN_OK);
                own_lift(b->name, y, qo, vo);
                for (int j = 0; j < n; ++j) {
                    worst = fmax(worst, fmax(fabs(q[j] - qo[j]), fabs(v[j] - vo[j])));
                    if (i == 0) {
                        /* The model starts where the paper does. */
                        assert_near(b->q0[j], qo[j], 1e-15);
                        assert_near(b->v0[j], vo[j], 1e-15);
                    }
                }
            }
            own_rk4(cases[c].f, h, y, comp);
        }
        print_message("%-13s reference vs this file's RK4 of its equation, 20 s: %.2e\n", b->name,
                      worst);
        assert_le(worst, cases[c].bound);
    }
}

/* The minimal state behind a reference's absolute coordinates, by the
 * geometry: the four-bar's first joint is at l(cos θ, sin θ), the
 * pendulum's bob at l(sin phi, -cos phi), the slider-crank's crank angle
 * is q[2]. */
static void own_unlift(const char *model, const double *q, const double *v, double *y)
{
    if (strcmp(model, "four-bar") == 0) {
        y[0] = atan2(q[1], q[0]);
        y[1] = (q[0] * v[1] - q[1] * v[0]) / (PAPER_L * PAPER_L);
    } else if (strcmp(model, "pendulum") == 0) {
        y[0] = atan2(q[0], -q[1]);
        y[1] = (-q[1] * v[0] + q[0] * v[1]) / (PAPER_L * PAPER_L);
    } else {
        y[0] = q[2];
        y[1] = v[2];
    }
}

/* Energy per unit mass of each minimal equation, written out: four-bar
 * T = ½(3m)l²θ'², V = (7/2)mgl sin θ; pendulum ½l²phi'² - gl cos phi;
 * slider-crank (Eq. 24) T = ½ml²(5/3 - cos 2θ)θ'², V = mgl sin θ. */
static double own_energy(const char *model, const double *y)
{
    const double l = PAPER_L, m = PAPER_M, g = PAPER_G, w = y[1];
    if (strcmp(model, "four-bar") == 0)
        return 0.5 * 3.0 * m * l * l * w * w + 3.5 * m * g * l * sin(y[0]);
    if (strcmp(model, "pendulum") == 0) return 0.5 * m * l * l * w * w - m * g * l * cos(y[0]);
    return 0.5 * m * l * l * (5.0 / 3.0 - cos(2.0 * y[0])) * w * w + m * g * l * sin(y[0]);
}

/* The energy of the equation written above is constant along each
 * reference over 1000 s (the integrated one: 100 s). */
static void test_references_conserve_energy(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        double T, bound;
    } cases[] = {
        /* max |E - E0| measured 1.65e-11 (the closed form's phase reaches
         * ~3000 rad by 1000 s: an ulp of it moves E by ~1e-11), 1.0e-14,
         * 1.7e-13 (E0 35.8, 0, 6.9) */
        {"four-bar", 1000.0, 5e-11},
        {"pendulum", 1000.0, 3e-14},
        {"slider-crank", 100.0, 5e-13},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const braun_builtin *b = braun_builtin_find(cases[c].name);
        braun_reference ref;
        assert_int_equal(braun_reference_init(&ref, b, 0.0), BRAUN_OK);
        double E0 = 0.0, worst = 0.0;
        for (int i = 0; i <= 10000; ++i) {
            double q[NMAX], v[NMAX], y[2];
            assert_int_equal(braun_reference_eval(&ref, cases[c].T * i / 10000.0, q, v), BRAUN_OK);
            own_unlift(b->name, q, v, y);
            double E = own_energy(b->name, y);
            if (i == 0) E0 = E;
            worst = fmax(worst, fabs(E - E0));
        }
        print_message("%-13s reference over %g s: |E - E0| of its equation <= %.2e (E0 %.4g)\n",
                      b->name, cases[c].T, worst, E0);
        assert_le(worst, cases[c].bound);
    }
}

/* The closed forms return to their initial state after one period, which
 * this file computes twice, independently of the Jacobi functions behind
 * the references:
 *   four-bar, phi = θ + π/2 rotating from phi = π, phi' = -1 with
 *   w2 = 7g/6l: phi'² = 1 + 4w2 cos²(phi/2), so the time of one turn is
 *   T = ∫_0^2π dphi / √(1 + 4w2 cos²(phi/2)) = 4K(k)/√(1 + 4w2),
 *   k² = 4w2/(1 + 4w2); half a turn later the linkage passes the bottom
 *   (θ = -π/2) at its highest speed √(1 + 4w2);
 *   pendulum released at rest from phi0 = π/2: T = 4K(sin(phi0/2))/√w2
 *   (w2 = g/l); at T/4 the bottom at speed √(2w2), at T/2 the other side
 *   at rest.
 * K by the AGM, the period integral by the trapezoidal rule (exact to
 * round-off for a smooth periodic integrand with 20000 points). */
static double trapezoid_period(double w2, double e0, int rotation)
{
    /* Rotation with energy e0 = ½phi'² - w2 cos phi: ∫_0^2π dphi/|phi'|,
     * phi'² = 2(e0 + w2 cos phi). Libration from rest at phi0 (e0 = -w2 cos
     * phi0): 4∫_0^{π/2} du/√(w2 (1 - k² sin² u)), sin(phi/2) = k sin u,
     * k² = sin²(phi0/2). */
    const int N = 20000;
    double s = 0.0;
    if (rotation) {
        for (int j = 0; j < N; ++j)
            s += 1.0 / sqrt(2.0 * (e0 + w2 * cos(2.0 * PI * j / N)));
        return 2.0 * PI * s / N;
    }
    const double k2 = 0.5 * (1.0 + e0 / w2); /* sin²(phi0/2) = (1 - cos phi0)/2 */
    for (int j = 0; j < N; ++j) {
        const double u = 2.0 * PI * j / N, sn = sin(u);
        s += 1.0 / sqrt(w2 * (1.0 - k2 * sn * sn));
    }
    /* T = 4∫_0^{π/2} = ∫_0^2π for this even, π-periodic integrand. */
    return 2.0 * PI * s / N;
}

static void test_closed_forms_periodic(void **state)
{
    (void)state;
    double q[NMAX], v[NMAX], y[2], w2, T, T2, worst = 0.0;
    braun_reference ref;

    /* Four-bar. */
    const braun_builtin *fb = braun_builtin_find("four-bar");
    w2 = 7.0 * PAPER_G / (6.0 * PAPER_L);
    T = 4.0 * own_K(1.0 / sqrt(1.0 + 4.0 * w2)) / sqrt(1.0 + 4.0 * w2);
    T2 = trapezoid_period(w2, 0.5 + w2, 1);
    print_message("four-bar: one turn T = %.17g (AGM), %.17g (period integral)\n", T, T2);
    assert_near(T, T2, 1e-14 * T);
    assert_int_equal(braun_reference_init(&ref, fb, 0.0), BRAUN_OK);
    for (int k = 1; k <= 500; ++k) {
        /* Bottom at (k - 1/2) T, back at the top at k T: q = q0, v = v0. */
        assert_int_equal(braun_reference_eval(&ref, (k - 0.5) * T, q, v), BRAUN_OK);
        own_unlift("four-bar", q, v, y);
        worst = fmax(worst, fabs(remainder(y[0] + PI / 2.0, 2.0 * PI)) / k);
        worst = fmax(worst, fabs(y[1] + sqrt(1.0 + 4.0 * w2)) / k);
        assert_int_equal(braun_reference_eval(&ref, k * T, q, v), BRAUN_OK);
        for (int j = 0; j < 6; ++j) {
            worst = fmax(worst, fabs(q[j] - fb->q0[j]) / k);
            worst = fmax(worst, fabs(v[j] - fb->v0[j]) / k);
        }
    }
    print_message("four-bar closed form after k turns (k <= 500, ~%.0f s): error / k <= %.2e\n",
                  500 * T, worst);
    /* Measured 1.1e-14: round-off, not drift (divided by k). */
    assert_le(worst, 3e-14);

    /* Pendulum. */
    const braun_builtin *pe = braun_builtin_find("pendulum");
    w2 = PAPER_G / PAPER_L;
    T = 4.0 * own_K(sqrt(0.5)) / sqrt(w2); /* k = sin(π/4), k' = cos(π/4) */
    T2 = trapezoid_period(w2, 0.0, 0);
    print_message("pendulum: period T = %.17g (AGM), %.17g (period integral)\n", T, T2);
    assert_near(T, T2, 1e-14 * T);
    assert_int_equal(braun_reference_init(&ref, pe, 0.0), BRAUN_OK);
    worst = 0.0;
    for (int k = 1; k <= 500; ++k) {
        const double quarter[3][2] = {{0.0, -sqrt(2.0 * w2)}, {-PI / 2.0, 0.0}, {0.0, sqrt(2.0 * w2)}};
        for (int s = 0; s < 3; ++s) {
            assert_int_equal(braun_reference_eval(&ref, (k - 1 + 0.25 * (s + 1)) * T, q, v), BRAUN_OK);
            own_unlift("pendulum", q, v, y);
            worst = fmax(worst, fabs(y[0] - quarter[s][0]) / k);
            worst = fmax(worst, fabs(y[1] - quarter[s][1]) / k);
        }
        assert_int_equal(braun_reference_eval(&ref, k * T, q, v), BRAUN_OK);
        for (int j = 0; j < 2; ++j) {
            worst = fmax(worst, fabs(q[j] - pe->q0[j]) / k);
            worst = fmax(worst, fabs(v[j] - pe->v0[j]) / k);
        }
    }
    print_message("pendulum closed form after k periods (k <= 500, ~%.0f s): error / k <= %.2e\n",
                  500 * T, worst);
    /* Measured 7.0e-15. */
    assert_le(worst, 2e-14);
}

/* The integrated reference: querying in pieces continues the integration
 * (the same numbers as one pass), going back is refused; ref_h = 1e-4 and
 * 5e-5 agree at 10 s as RK4's order says (the accuracy itself is checked
 * against this file's integration above). */
static void test_reference_integrated(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("slider-crank");
    braun_reference r1, r2, r3;
    double q1[NMAX], v1[NMAX], q2[NMAX], v2[NMAX], q3[NMAX], v3[NMAX];
    assert_int_equal(braun_reference_init(&r1, b, 1e-4), BRAUN_OK);
    assert_int_equal(braun_reference_init(&r2, b, 5e-5), BRAUN_OK);
    assert_int_equal(braun_reference_init(&r3, b, -1.0), BRAUN_OK);
    assert_near(r3.ref_h, 1e-4, 0.0);
    assert_int_equal(braun_reference_eval(&r1, 10.0, q1, v1), BRAUN_OK);
    assert_int_equal(braun_reference_eval(&r2, 10.0, q2, v2), BRAUN_OK);
    for (int i = 1; i <= 1000; ++i) /* output every 0.01 s, as a solver run */
        assert_int_equal(braun_reference_eval(&r3, 0.01 * i, q3, v3), BRAUN_OK);
    double d12 = 0.0, d13 = 0.0;
    for (int j = 0; j < 6; ++j) {
        d12 = fmax(d12, fmax(fabs(q1[j] - q2[j]), fabs(v1[j] - v2[j])));
        d13 = fmax(d13, fmax(fabs(q1[j] - q3[j]), fabs(v1[j] - v3[j])));
    }
    print_message("slider-crank at 10 s: |ref(1e-4) - ref(5e-5)| = %.2e, "
                  "|one pass - 1000 pieces| = %.2e\n", d12, d13);
    /* Measured 9.2e-14 and 8.5e-13. */
    assert_le(d12, 3e-13);
    assert_le(d13, 3e-12);
    assert_near(r1.t, 10.0, 0.0);
    assert_int_equal(braun_reference_eval(&r1, 9.0, q1, v1), BRAUN_ERR_TIME);
    assert_int_equal(braun_reference_eval(&r1, 10.0, q1, v1), BRAUN_OK);
    for (int j = 0; j < 6; ++j) assert_near(q1[j], q3[j], 3e-12);
    /* Bad arguments. */
    assert_int_equal(braun_reference_init(NULL, b, 0.0), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_reference_init(&r1, NULL, 0.0), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_reference_eval(&r1, NAN, q1, v1), BRAUN_ERR_ARGUMENT);
}

/* Closed-form references against the RK4 reference of the same model with
 * its closed form removed (the two code paths of braun_reference_eval), and
 * going back in time is fine for a closed form. */
static void test_reference_closed_form_vs_integrated(void **state)
{
    (void)state;
    static const char *names[2] = {"four-bar", "pendulum"};
    /* measured 1.3e-11, 4.6e-12 over 20 s (RK4 substeps of 1e-4) */
    static const double bounds[2] = {4e-11, 2e-11};
    for (int c = 0; c < 2; ++c) {
        const braun_builtin *b = braun_builtin_find(names[c]);
        braun_minimal integrated = *braun_minimal_find(b->name);
        integrated.exact = NULL;
        braun_reference re, ri;
        assert_int_equal(braun_reference_init(&re, b, 0.0), BRAUN_OK);
        assert_int_equal(braun_reference_init_minimal(&ri, b, &integrated, 0.0), BRAUN_OK);
        double worst = 0.0;
        for (int i = 0; i <= 200; ++i) {
            double t = 0.1 * i, qe[NMAX], ve[NMAX], qi[NMAX], vi[NMAX];
            assert_int_equal(braun_reference_eval(&re, t, qe, ve), BRAUN_OK);
            assert_int_equal(braun_reference_eval(&ri, t, qi, vi), BRAUN_OK);
            for (int j = 0; j < b->sys.n; ++j)
                worst = fmax(worst, fmax(fabs(qe[j] - qi[j]), fabs(ve[j] - vi[j])));
            if (i == 100) assert_int_equal(braun_reference_eval(&re, 1.0, qe, ve), BRAUN_OK);
        }
        print_message("%-13s closed form vs RK4(1e-4) reference over 20 s: %.2e\n", b->name, worst);
        assert_le(worst, bounds[c]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_initial_state),
        cmocka_unit_test(test_constraint_derivatives),
        cmocka_unit_test(test_energy_and_mass),
        cmocka_unit_test(test_null_outputs),
        cmocka_unit_test(test_energy_along_reference),
        cmocka_unit_test(test_minimal_matches_kkt),
        cmocka_unit_test(test_four_bar_printed_force_is_wrong),
        cmocka_unit_test(test_minimal_is_euler_lagrange),
        cmocka_unit_test(test_minimal_energies),
        cmocka_unit_test(test_references_vs_own_integration),
        cmocka_unit_test(test_references_conserve_energy),
        cmocka_unit_test(test_closed_forms_periodic),
        cmocka_unit_test(test_reference_integrated),
        cmocka_unit_test(test_reference_closed_form_vs_integrated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
