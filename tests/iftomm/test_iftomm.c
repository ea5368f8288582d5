/* The IFToMM benchmark harness (compare/iftomm, docs/iftomm.md): its
 * references checked against each other, against hand formulas and
 * published values, and the shipped scenes run by libbraun at short
 * horizons against them; the reported-point extraction and its
 * interpolation onto the output grid. Bounds sit a small factor above the
 * measured values (in the comments). */
#include <complex.h>

#include "ifm.h"
#include "ifm_problems.h"
#include "ifm_run.h"
#include "test_util.h"


/* ---------------------------------------------------------------- references */

/* A01: the closed form and rk8pd on θ'' = -(g/L) sin θ agree; the closed
 * form starts at (1, 0) at rest and keeps |P1| = 1. */
static void test_pendulum_closed_form(void **state)
{
    (void)state;
    ifm_series a, b;
    double q0[1], v0[1];
    char why[256] = "";
    assert_int_equal(ifm_series_init(&a, 1001, 2, 0, 0.01), 0);
    assert_int_equal(ifm_series_init(&b, 1001, 2, 1, 0.01), 0);
    assert_int_equal(ifm_pendulum_exact(&a), 0);
    ifm_pendulum_state0(q0, v0);
    assert_int_equal(ifm_minimal_run(&ifm_pendulum_model, 0, q0, v0, 1e-14, &b, why, sizeof why), 0);
    assert_le(ifm_series_maxdiff(&a, &b, 2), 1e-13); /* measured 1.8e-14 */
    assert_near(a.y[0], 1.0, 1e-15);
    assert_near(a.y[1], 0.0, 1e-15);
    for (long j = 0; j < a.count; j++)
        assert_near(hypot(a.y[2 * j], a.y[2 * j + 1]), 1.0, 1e-14);
    /* The period 4K(1/2)/sqrt(g): back at (1, 0) after one. */
    ifm_series c;
    assert_int_equal(ifm_series_init(&c, 2, 2, 0, 4 * 1.8540746773013719 / sqrt(9.81)), 0);
    assert_int_equal(ifm_pendulum_exact(&c), 0);
    assert_near(c.y[2], 1.0, 1e-14);
    assert_near(c.y[3], 0.0, 1e-14);
    assert_le(b.max_energy, 1e-13); /* 2.2e-14 J */
    ifm_series_free(&a);
    ifm_series_free(&b);
    ifm_series_free(&c);
}

/* A02: the closed form of the crank-angle reduction against rk8pd on it,
 * N = 40 over 20 s and N = 2 over 10 s, positions and velocities of B0. */
static void test_fourbar_closed_form(void **state)
{
    (void)state;
    static const int Ns[2] = {40, 2};
    static const double Ts[2] = {20, 10};
    for (int c = 0; c < 2; c++) {
        ifm_fourbar_params p = {Ns[c]};
        ifm_model md;
        ifm_fourbar_model(&md, &p);
        const long count = lround(Ts[c] / 0.05) + 1;
        ifm_series a, b;
        double q0[1], v0[1];
        char why[256] = "";
        assert_int_equal(ifm_series_init(&a, count, 4, 0, 0.05), 0);
        assert_int_equal(ifm_series_init(&b, count, 4, 1, 0.05), 0);
        assert_int_equal(ifm_fourbar_exact(&p, &a), 0);
        ifm_fourbar_state0(q0, v0);
        assert_int_equal(ifm_minimal_run(&md, 0, q0, v0, 1e-14, &b, why, sizeof why), 0);
        assert_le(ifm_series_maxdiff(&a, &b, 4), 1e-10); /* measured 3.4e-11 (N = 40), 1.0e-11 */
        /* B0 starts at (0, 1) moving at (1, 0). */
        assert_near(a.y[0], 0.0, 1e-15);
        assert_near(a.y[1], 1.0, 1e-15);
        assert_near(a.y[2], 1.0, 1e-15);
        assert_near(a.y[3], 0.0, 1e-15);
        assert_le(b.max_energy, 1e-13 * b.max_kinetic); /* 1.6e-14 */
        ifm_series_free(&a);
        ifm_series_free(&b);
    }
}

/* The Test Set's parameters, restated here for the checks of the model. */
static const double m2 = 0.00365, m4 = 0.00706, m6 = 0.00706, m1 = 0.04325, m3 = 0.02373,
                    m5 = 0.07050, m7 = 0.05498;
static const double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                    i6 = 5.667e-7, i7 = 1.912e-5;
static const double da = 115.0e-4, rr = 7.0e-3, ra = 92.0e-5, e = 2.0e-2, ea = 1421.0e-5,
                    zt = 4.0e-2, zf = 2.0e-2, fa = 1421.0e-5, u = 4.0e-2, sa = 1874.0e-5,
                    sb = 1043.0e-5, ta = 2308.0e-5, tb = 916.0e-5, ua = 1228.0e-5, ub = 449.0e-5;

/* A03: M from the model's geometric T equals the test set's printed M(q),
 * and the velocity terms that follow from T by complex steps equal the
 * test set's f. Random states. */
static void test_andrews_mass_and_forces(void **state)
{
    (void)state;
    unsigned long long seed = 3;
    const ifm_model *md = &ifm_andrews_model;
    for (int trial = 0; trial < 20; trial++) {
        double q[7], v[7], zero[7] = {0}, M[49], F[7], F0[7];
        for (int i = 0; i < 7; i++) {
            q[i] = 3 * test_frand(&seed);
            v[i] = 50 * test_frand(&seed);
        }
        ifm_mass(md, q, M);
        const double coth = cos(q[1]), siph = sin(q[3]), siom = sin(q[5]);
        double P[49] = {0};
        P[0] = m1 * ra * ra + m2 * (rr * rr - 2 * da * rr * coth + da * da) + i1 + i2;
        P[1] = P[7] = m2 * (da * da - da * rr * coth) + i2;
        P[8] = m2 * da * da + i2;
        P[16] = m3 * (sa * sa + sb * sb) + i3;
        P[24] = m4 * (e - ea) * (e - ea) + i4;
        P[25] = P[31] = m4 * ((e - ea) * (e - ea) + zt * (e - ea) * siph) + i4;
        P[32] = m4 * (zt * zt + 2 * zt * (e - ea) * siph + (e - ea) * (e - ea)) +
                m5 * (ta * ta + tb * tb) + i4 + i5;
        P[40] = m6 * (zf - fa) * (zf - fa) + i6;
        P[41] = P[47] = m6 * ((zf - fa) * (zf - fa) - u * (zf - fa) * siom) + i6;
        P[48] = m6 * ((zf - fa) * (zf - fa) - 2 * u * (zf - fa) * siom + u * u) +
                m7 * (ua * ua + ub * ub) + i6 + i7;
        for (int k = 0; k < 49; k++) assert_near(M[k], P[k], 1e-19); /* measured 0 .. 2e-21 */
        ifm_forces(md, 0, q, v, F);
        ifm_forces(md, 0, q, zero, F0);
        const double fv[7] = {
            -m2 * da * rr * v[1] * (v[1] + 2 * v[0]) * sin(q[1]),
            m2 * da * rr * v[0] * v[0] * sin(q[1]),
            0,
            m4 * zt * (e - ea) * v[4] * v[4] * cos(q[3]),
            -m4 * zt * (e - ea) * v[3] * (v[3] + 2 * v[4]) * cos(q[3]),
            -m6 * u * (zf - fa) * v[6] * v[6] * cos(q[5]),
            m6 * u * (zf - fa) * v[5] * (v[5] + 2 * v[6]) * cos(q[5])};
        for (int k = 0; k < 7; k++) assert_near(F[k] - F0[k], fv[k], 1e-14); /* ~1e-16 */
    }
}

/* ψ = G v is the rate of φ: complex step of φ along v, every model with
 * constraints, random states. */
static void check_psi(const ifm_model *md, unsigned long long seed, double scale, double tol)
{
    for (int trial = 0; trial < 10; trial++) {
        double q[IFM_MAX_N], v[IFM_MAX_N], psi[IFM_MAX_M];
        ifm_cx qc[IFM_MAX_N], out[IFM_MAX_M];
        for (int i = 0; i < md->n; i++) {
            q[i] = scale * test_frand(&seed);
            v[i] = test_frand(&seed);
            qc[i] = q[i] + I * IFM_CSTEP * v[i];
        }
        ifm_psi(md, q, v, psi);
        md->phi(md, qc, out);
        for (int r = 0; r < md->m; r++) assert_near(psi[r], cimag(out[r]) / IFM_CSTEP, tol);
    }
}

static void test_psi_is_rate_of_phi(void **state)
{
    (void)state;
    ifm_bricard_params bp = {0, IFM_BRICARD_DROP};
    ifm_model bricard;
    ifm_bricard_model(&bricard, &bp);
    check_psi(&ifm_andrews_model, 5, 3, 1e-16);
    check_psi(&bricard, 7, 3, 1e-14);
    check_psi(&ifm_flyball_cart_model, 11, 1, 1e-14);
}

/* A03: the model on β (rk8pd) and IDA on the DAE both reach the test set's
 * published y(0.03) and agree on F. */
static void test_andrews_ivp_reference(void **state)
{
    (void)state;
    double q0[7], v0[7];
    char why[256] = "";
    ifm_andrews_state0(q0, v0);
    ifm_series a, b;
    assert_int_equal(ifm_series_init(&a, 101, 2, 7, 3e-4), 0);
    assert_int_equal(ifm_series_init(&b, 101, 2, 7, 3e-4), 0);
    assert_int_equal(ifm_minimal_run(&ifm_andrews_model, 0, q0, v0, 1e-13, &a, why, sizeof why), 0);
    assert_int_equal(ifm_ida_run(&ifm_andrews_model, q0, v0, 1e-12, 1e-12, &b, why, sizeof why), 0);
    for (int i = 0; i < 7; i++) {
        const double ref = ifm_andrews_ref003[i];
        assert_le(fabs(a.q[100 * 7 + i] - ref), 1e-9 * fabs(ref)); /* measured 2.7e-10 */
        assert_le(fabs(b.q[100 * 7 + i] - ref), 1e-9 * fabs(ref)); /* 1.5e-10 */
    }
    assert_le(ifm_series_maxdiff(&a, &b, 2), 1e-11); /* 3.5e-12 m */
    /* The energy balance E - E0 = mom (β - β0) along both. */
    assert_le(a.max_energy, 1e-13 * a.max_kinetic); /* 2.5e-14 relative */
    assert_le(b.max_energy, 1e-10 * b.max_kinetic); /* 2.5e-11 */
    ifm_series_free(&a);
    ifm_series_free(&b);
}

/* A04: along half a period the four kept closure rows stay independent
 * (σ_min/σ_max of their Jacobian), the dropped fifth stays satisfied, the
 * two references agree and conserve energy; the initial acceleration is
 * the one a symmetric start gives (θ1 = θ3 = θ5 = -θ2 = -θ4). */
static double sigma_ratio_4x5(const double *G)
{
    /* Gram determinant route is fragile; use the smallest eigenvalue of
     * G Gᵀ (4 x 4) by inverse iteration against the largest by power
     * iteration. */
    double A[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 5; k++) s += G[i * 5 + k] * G[j * 5 + k];
            A[i * 4 + j] = s;
        }
    double x[4] = {1, 0.5, 0.25, 0.125}, lmax = 0;
    for (int it = 0; it < 200; it++) {
        double y[4] = {0}, nrm = 0;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) y[i] += A[i * 4 + j] * x[j];
        for (int i = 0; i < 4; i++) nrm += y[i] * y[i];
        nrm = sqrt(nrm);
        lmax = nrm;
        for (int i = 0; i < 4; i++) x[i] = y[i] / nrm;
    }
    /* λ_min = 1/λ_max(A⁻¹): Gaussian elimination for A⁻¹ (SPD). */
    double B[16], Ai[16];
    memcpy(B, A, sizeof B);
    for (int i = 0; i < 16; i++) Ai[i] = i % 5 == 0;
    for (int c = 0; c < 4; c++) {
        const double piv = B[c * 4 + c];
        for (int j = 0; j < 4; j++) {
            B[c * 4 + j] /= piv;
            Ai[c * 4 + j] /= piv;
        }
        for (int r = 0; r < 4; r++)
            if (r != c) {
                const double f = B[r * 4 + c];
                for (int j = 0; j < 4; j++) {
                    B[r * 4 + j] -= f * B[c * 4 + j];
                    Ai[r * 4 + j] -= f * Ai[c * 4 + j];
                }
            }
    }
    double z[4] = {1, -0.5, 0.25, -0.125}, linv = 0;
    for (int it = 0; it < 200; it++) {
        double y[4] = {0}, nrm = 0;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) y[i] += Ai[i * 4 + j] * z[j];
        for (int i = 0; i < 4; i++) nrm += y[i] * y[i];
        nrm = sqrt(nrm);
        linv = nrm;
        for (int i = 0; i < 4; i++) z[i] = y[i] / nrm;
    }
    return sqrt(1 / linv / lmax);
}

static void test_bricard_references(void **state)
{
    (void)state;
    ifm_bricard_params bp = {0, IFM_BRICARD_DROP};
    ifm_model md;
    ifm_bricard_model(&md, &bp);
    double q0[5], v0[5], a0[5];
    char why[256] = "";
    ifm_bricard_state0(q0, v0);
    assert_int_equal(ifm_accel(&md, 0, q0, v0, a0, NULL), 0);
    for (int i = 1; i < 5; i++) assert_near(a0[i], i % 2 ? -a0[0] : a0[0], 1e-12);
    assert_le(1.9, a0[0]); /* 1.958 rad/s² */
    ifm_series a, b;
    assert_int_equal(ifm_series_init(&a, 251, 3, 5, 0.01), 0);
    assert_int_equal(ifm_series_init(&b, 251, 3, 5, 0.01), 0);
    assert_int_equal(ifm_minimal_run(&md, 0, q0, v0, 1e-13, &a, why, sizeof why), 0);
    assert_int_equal(ifm_ida_run(&md, q0, v0, 1e-12, 1e-12, &b, why, sizeof why), 0);
    assert_le(ifm_series_maxdiff(&a, &b, 3), 2e-10); /* 7.6e-11 */
    assert_le(a.max_energy, 2e-14 * a.max_kinetic); /* 3.9e-15 */
    double smin = 1, dropped = 0;
    for (long j = 0; j < a.count; j++) {
        double G[20], rows[5];
        ifm_jacobian(&md, a.q + 5 * j, G);
        smin = fmin(smin, sigma_ratio_4x5(G));
        ifm_bricard_rows(a.q + 5 * j, rows);
        dropped = fmax(dropped, fabs(rows[IFM_BRICARD_DROP]));
    }
    assert_le(0.32, smin);     /* 0.3249 at the start, no smaller along the motion */
    assert_le(dropped, 5e-15); /* 4.7e-16: the fifth row holds where the four do */
    /* Half a period: P3 = (1, -1, 0) -> (-1, -1, 0) at t = 2.5 s. */
    assert_near(a.y[250 * 3 + 0], -1.0, 1e-3);
    ifm_series_free(&a);
    ifm_series_free(&b);
}

/* A05: joint coordinates (rk8pd) against the Cartesian DAE (IDA); s(t)
 * passes the benchmark's reference points as the OpenSim reproduction
 * plots them (read off its figure to ±0.003 m: 0.524 at 0.1 s, 0.585 at
 * 0.2 s, 0.743 at 0.5 s, 0.501 at 1.0 s). */
static void test_flyball_references(void **state)
{
    (void)state;
    double q0[4], v0[4], p0[8], w0[8];
    char why[256] = "";
    ifm_flyball_joint_state0(q0, v0);
    ifm_flyball_cart_state0(p0, w0);
    assert_near(ifm_energy(&ifm_flyball_joint_model, q0, v0),
                ifm_energy(&ifm_flyball_cart_model, p0, w0), 1e-12);
    ifm_series a, b;
    assert_int_equal(ifm_series_init(&a, 11, 3, 4, 0.1), 0);
    assert_int_equal(ifm_series_init(&b, 11, 3, 8, 0.1), 0);
    assert_int_equal(ifm_minimal_run(&ifm_flyball_joint_model, 0, q0, v0, 1e-12, &a, why,
                                     sizeof why), 0);
    assert_int_equal(ifm_ida_run(&ifm_flyball_cart_model, p0, w0, 1e-11, 1e-11, &b, why,
                                 sizeof why), 0);
    assert_le(ifm_series_maxdiff(&a, &b, 3), 1e-9);       /* 2.6e-10 */
    assert_le(a.max_energy, 1e-14 * a.max_kinetic); /* 2.5e-15, the dampers' work balanced */
    assert_near(a.y[1 * 3 + 2], 0.524, 0.003);
    assert_near(a.y[2 * 3 + 2], 0.585, 0.003);
    assert_near(a.y[5 * 3 + 2], 0.743, 0.003);
    assert_near(a.y[10 * 3 + 2], 0.501, 0.003);
    ifm_series_free(&a);
    ifm_series_free(&b);
}

/* ---------------------------------------------------------------- scenes */

static braun_scene_file *load(const char *path)
{
    char err[512] = "";
    braun_scene_file *sf = braun_scene_load(path, err, sizeof err);
    if (!sf) print_error("%s\n", err);
    assert_non_null(sf);
    return sf;
}

static double run_error(const braun_scene_file *sf, const char *point, int dim, int velocity,
                        braun_method method, double h, double T, double dt, const ifm_series *ref,
                        ifm_result *res)
{
    char why[256] = "";
    ifm_setting set = {method, h, 1e-9, 1e-11};
    const int k = ifm_scene_report_index(sf, point);
    assert_true(k >= 0);
    assert_int_equal(ifm_braun_run(sf, k, dim, velocity, &set, T, dt, 1, res, why, sizeof why), 0);
    assert_int_equal(res->status, BRAUN_OK);
    return ifm_series_maxdiff(&res->y, ref, res->y.width);
}

/* A01 scene against the closed form over 10 s. */
static void test_a01_scene(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a01-pendulum.json");
    ifm_series ref;
    ifm_result r;
    assert_int_equal(ifm_series_init(&ref, 1001, 2, 0, 0.01), 0);
    assert_int_equal(ifm_pendulum_exact(&ref), 0);
    assert_le(run_error(sf, "P1", 2, 0, BRAUN_RK4, 1e-3, 10, 0.01, &ref, &r), 2e-10); /* 6.6e-11 */
    assert_le(r.max_pos, 3e-15); /* 6.7e-16 */
    ifm_result_free(&r);
    ifm_series_free(&ref);
    braun_scene_free(sf);
}

/* A02 scene (N = 40) through its first singular (horizontal)
 * configurations against the closed form, B0's position and velocity. */
static void test_a02_scene(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a02-n-four-bar.json");
    ifm_fourbar_params p = {40};
    ifm_series ref;
    ifm_result r;
    assert_int_equal(ifm_series_init(&ref, 21, 4, 0, 0.05), 0);
    assert_int_equal(ifm_fourbar_exact(&p, &ref), 0);
    /* B0 passes y = 0 (every crank horizontal) within the first second. */
    int crossed = 0;
    for (long j = 1; j < ref.count; j++) crossed |= ref.y[4 * j + 1] * ref.y[4 * (j - 1) + 1] < 0;
    assert_true(crossed);
    assert_le(run_error(sf, "B0", 2, 1, BRAUN_RK4, 2.5e-3, 1, 0.05, &ref, &r), 3e-8); /* 8.4e-9 */
    assert_le(r.max_pos, 1e-10); /* 3.3e-11 */
    ifm_result_free(&r);
    ifm_series_free(&ref);
    braun_scene_free(sf);
}

/* A03 scene (absolute coordinates) against the test set's y(0.03) on F. */
static void test_a03_scene(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a03-andrews.json");
    ifm_series ref;
    ifm_result r;
    assert_int_equal(ifm_series_init(&ref, 2, 2, 0, 0.03), 0);
    ref.y[0] = rr * cos(-0.0617138900142764496358948458001);
    ref.y[1] = rr * sin(-0.0617138900142764496358948458001);
    ref.y[2] = rr * cos(ifm_andrews_ref003[0]);
    ref.y[3] = rr * sin(ifm_andrews_ref003[0]);
    assert_le(run_error(sf, "F", 2, 0, BRAUN_RK4, 1e-5, 0.03, 0.03, &ref, &r), 3e-11); /* 1.0e-11 */
    ifm_result_free(&r);
    ifm_series_free(&ref);
    braun_scene_free(sf);
}

/* A04 scene over one second against the minimal-coordinate reference. */
static void test_a04_scene(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a04-bricard.json");
    ifm_refset rs;
    char why[256] = "";
    ifm_problem p = *ifm_problem_find("A04-10s");
    assert_int_equal(ifm_reference(&p, 1.0, &rs, why, sizeof why), 0);
    ifm_result r;
    assert_le(run_error(sf, "P3", 3, 0, BRAUN_RK4, 0.01, 1.0, 0.01, &rs.ref, &r), 2e-7); /* 6.4e-8 */
    assert_le(r.max_pos, 5e-10); /* 1.3e-10 */
    ifm_result_free(&r);
    ifm_refset_free(&rs);
    braun_scene_free(sf);
}

/* A05 scene over 0.2 s against the joint-coordinate reference. */
static void test_a05_scene(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a05-flyball-governor.json");
    ifm_refset rs;
    char why[256] = "";
    ifm_problem p = *ifm_problem_find("A05-10s");
    assert_int_equal(ifm_reference(&p, 0.2, &rs, why, sizeof why), 0);
    ifm_result r;
    assert_le(run_error(sf, "S", 3, 0, BRAUN_RK4, 2.5e-4, 0.2, 0.1, &rs.ref, &r), 5e-8); /* 1.8e-8 */
    ifm_result_free(&r);
    ifm_refset_free(&rs);
    braun_scene_free(sf);
}

/* The extraction: a grid sample at a step end is the reported point of
 * that state bit for bit (the same run sampled on a grid twice as fine
 * gives the same values at the common times), and samples between step
 * ends (Hermite) stay within the interpolation error of the exact
 * solution; the velocity is the point's. */
static void test_extraction(void **state)
{
    (void)state;
    braun_scene_file *sf = load("data/iftomm/a01-pendulum.json");
    char why[256] = "";
    const int k = ifm_scene_report_index(sf, "P1");
    assert_true(k >= 0);
    assert_int_equal(ifm_scene_report_index(sf, "nope"), -1);
    ifm_setting set = {BRAUN_RK4, 0.02, 0, 0};
    ifm_result coarse, fine;
    assert_int_equal(ifm_braun_run(sf, k, 2, 1, &set, 2.0, 0.02, 1, &coarse, why, sizeof why), 0);
    assert_int_equal(ifm_braun_run(sf, k, 2, 1, &set, 2.0, 0.01, 1, &fine, why, sizeof why), 0);
    for (long j = 0; j < coarse.y.count; j++)
        for (int c = 0; c < 4; c++)
            assert_true(coarse.y.y[4 * j + c] == fine.y.y[4 * (2 * j) + c]);
    /* The velocity is the point's: tangent to its unit circle, up to
     * libbraun's velocity-constraint residual at h = 0.02. */
    double pv = 0;
    for (long j = 0; j < coarse.y.count; j++) {
        const double *y = coarse.y.y + 4 * j;
        pv = fmax(pv, fabs(y[0] * y[2] + y[1] * y[3]));
    }
    assert_le(pv, 1.5e-6); /* 4.5e-7 */
    ifm_series ref;
    assert_int_equal(ifm_series_init(&ref, 201, 2, 0, 0.01), 0);
    assert_int_equal(ifm_pendulum_exact(&ref), 0);
    /* Between the steps of 0.02: Hermite error (h⁴/384)|P''''| ~ 4e-8 on
     * top of RK4's own 1e-6 at this step. */
    double err = 0;
    for (long j = 0; j < ref.count; j++)
        for (int c = 0; c < 2; c++) err = fmax(err, fabs(fine.y.y[4 * j + c] - ref.y[2 * j + c]));
    assert_le(err, 8e-6); /* measured 2.6e-6 */
    ifm_series_free(&ref);
    ifm_result_free(&coarse);
    ifm_result_free(&fine);
    braun_scene_free(sf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pendulum_closed_form),
        cmocka_unit_test(test_fourbar_closed_form),
        cmocka_unit_test(test_andrews_mass_and_forces),
        cmocka_unit_test(test_psi_is_rate_of_phi),
        cmocka_unit_test(test_andrews_ivp_reference),
        cmocka_unit_test(test_bricard_references),
        cmocka_unit_test(test_flyball_references),
        cmocka_unit_test(test_a01_scene),
        cmocka_unit_test(test_a02_scene),
        cmocka_unit_test(test_a03_scene),
        cmocka_unit_test(test_a04_scene),
        cmocka_unit_test(test_a05_scene),
        cmocka_unit_test(test_extraction),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
