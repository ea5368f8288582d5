/*
 * Jacobi elliptic functions, elliptic integrals and the closed-form pendulum
 * (src/models/braun_elliptic.c, src/models/braun_pendulum_exact.c).
 * Reference values: mpmath 1.3 at 40 digits, arguments as the doubles below.
 */
#include "test_util.h"

#include "braun_reference.h"

#define PI 3.14159265358979323846

static const double ms[] = {0.0, 1e-10, 0.1, 0.5, 0.9, 0.99, 0.999999,
                            1.0 - 1e-12};
#define NMS ((int)(sizeof ms / sizeof ms[0]))

/* sn² + cn² = 1 and dn² + m sn² = 1 (A&S 16.9.1) on a grid of u and m. */
static void test_identities(void **state)
{
    (void)state;
    double worst1 = 0.0, worst2 = 0.0;
    for (int k = 0; k < NMS; ++k)
        for (double u = -60.0; u <= 60.0; u += 0.0137) {
            double sn, cn, dn;
            braun_jacobi_sncndn(u, ms[k], &sn, &cn, &dn);
            worst1 = fmax(worst1, fabs(sn * sn + cn * cn - 1.0));
            worst2 = fmax(worst2, fabs(dn * dn + ms[k] * sn * sn - 1.0));
        }
    assert_le(worst1, 1e-15);
    assert_le(worst2, 1e-15);
}

static void test_known_values(void **state)
{
    (void)state;
    /* u, m, sn, cn, dn */
    static const double v[][5] = {
        {0.7, 0.3, 0.63230477631086451725, 0.7747197363269297698,
         0.93811363968143021572},
        {2.5, 0.9, 0.9996945384505861342, 0.024714971010898662991,
         0.31709580068626355582},
        {0.3, 0.1, 0.29509812430436883313, 0.95546695234950082526,
         0.99563633406139027243},
        {3.0, 0.999999999999, 0.99505475368697181015, 0.099327927417015305346,
         0.099327927421999362122},
        {1.0, 1e-20, 0.84147098480789650665, 0.5403023058681397174, 1.0},
        /* Large arguments: the period reduction must not cost accuracy. */
        {10000.0, 0.5, 0.73845000106937179969, -0.67430823509775170763,
         0.85284570583448586298},
        {-10000.25, 0.99, -0.14370760266995173097, -0.98962019226310013794,
         0.9897245291925964636},
        {10000.0, 0.978607224, -0.9999465528289461298, 0.010338833856274446063,
         0.14661985124771432749},
    };
    for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i) {
        double sn, cn, dn;
        braun_jacobi_sncndn(v[i][0], v[i][1], &sn, &cn, &dn);
        assert_near(sn, v[i][2], 2e-15);
        assert_near(cn, v[i][3], 2e-15);
        assert_near(dn, v[i][4], 2e-15);
    }
    /* m, K(m) */
    static const double k[][2] = {
        {0.5, 1.8540746773013719184},
        {0.9, 2.5780921133481732927},
        {0.99, 3.6956373629898742386},
        {0.999999, 8.2940514636010622019},
    };
    assert_near(braun_ellip_K(0.0), PI / 2.0, 1e-16);
    for (size_t i = 0; i < sizeof k / sizeof k[0]; ++i)
        assert_near(braun_ellip_K(k[i][0]), k[i][1], 4e-16 * k[i][1]);
    /* phi, m, F(phi|m) */
    static const double f[][3] = {
        {1.2, 0.7, 1.4294484330227633392},
        {10.0, 0.8, 14.145226112695649501},
        {-100.5, 0.95, -186.1026142836412834},
        {1.5707963267948966, 0.3, 1.7138894481787909824},
    };
    for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i)
        assert_near(braun_ellip_F(f[i][0], f[i][1]), f[i][2],
                    1e-15 * fmax(1.0, fabs(f[i][2])));
}

static void test_limits(void **state)
{
    (void)state;
    /* |u| < K(1 - 1e-12) = 15.2: beyond it sn turns back to 0 at 2K. */
    for (double u = -8.0; u <= 8.0; u += 0.0731) {
        double sn, cn, dn;
        /* m = 0: circular functions. */
        braun_jacobi_sncndn(u, 0.0, &sn, &cn, &dn);
        assert_near(sn, sin(u), 1e-15);
        assert_near(cn, cos(u), 1e-15);
        assert_near(dn, 1.0, 0.0);
        /* m -> 1: sn = tanh u + ¼k'²(sinh u cosh u - u) sech²u + O(k'^4)
         * (A&S 16.15), with k'² ≈ 1e-12. */
        double m = 1.0 - 1e-12, kp2 = 1.0 - m, ch = cosh(u);
        braun_jacobi_sncndn(u, m, &sn, &cn, &dn);
        double first = tanh(u) + 0.25 * kp2 * (sinh(u) * ch - u) / (ch * ch);
        /* and cn, dn = sech u ∓ ¼k'²(sinh u cosh u ∓ u) tanh u sech u. */
        double sh = sinh(u), th = tanh(u);
        assert_near(sn, first, 1e-15);
        assert_near(cn, 1.0 / ch - 0.25 * kp2 * (sh * ch - u) * th / ch, 1e-15);
        assert_near(dn, 1.0 / ch + 0.25 * kp2 * (sh * ch + u) * th / ch, 1e-15);
        assert_near(sn, tanh(u), 1e-12);
        /* m = 1 exactly: the limit itself. */
        braun_jacobi_sncndn(u, 1.0, &sn, &cn, &dn);
        assert_near(sn, tanh(u), 1e-16);
        assert_near(dn, 1.0 / ch, 1e-16);
    }
    for (int k = 0; k < NMS; ++k) {
        if (ms[k] >= 1.0 - 1e-9) continue; /* F, K defined for m < 1 */
        double K = braun_ellip_K(ms[k]);
        /* The double nearest π/2 is off by 6e-17 and F' = 1/k' there. */
        double slack = 2e-16 / sqrt(1.0 - ms[k]);
        assert_near(braun_ellip_F(PI / 2.0, ms[k]), K, 2e-15 * K + slack);
        assert_near(braun_ellip_F(-3.0 * PI / 2.0, ms[k]), -3.0 * K,
                    6e-15 * K + 3.0 * slack);
        /* Quarter period: sn(K) = 1, cn(K) = 0, dn(K) = k'. */
        double sn, cn, dn;
        braun_jacobi_sncndn(K, ms[k], &sn, &cn, &dn);
        assert_near(sn, 1.0, 1e-15);
        assert_near(cn, 0.0, 1e-15);
        assert_near(dn, sqrt(1.0 - ms[k]), 1e-15);
    }
    assert_near(braun_ellip_F(0.8, 0.0), 0.8, 1e-16);
    assert_near(braun_ellip_F(-0.8, 0.6), -braun_ellip_F(0.8, 0.6), 0.0);
    /* Outside the domain: NaN, no crash. */
    double sn, cn, dn;
    braun_jacobi_sncndn(1.0, -0.5, &sn, &cn, &dn);
    assert_true(isnan(sn) && isnan(cn) && isnan(dn));
    assert_true(isnan(braun_ellip_K(1.5)));
    assert_true(isnan(braun_ellip_F(1.0, 1.0)));
    /* Outputs may be NULL. */
    braun_jacobi_sncndn(1.0, 0.5, NULL, &cn, NULL);
    assert_near(cn, 0.59597656767214067402, 1e-15);
}

/* am(u), continuous: atan2(sn, cn) unwrapped to πu/(2K), from which it
 * differs by less than π/2. */
static double amplitude(double u, double m)
{
    double sn, cn, dn;
    braun_jacobi_sncndn(u, m, &sn, &cn, &dn);
    double a = atan2(sn, cn);
    double lin = PI * u / (2.0 * braun_ellip_K(m));
    return a + 2.0 * PI * nearbyint((lin - a) / (2.0 * PI));
}

/* F inverts am on the whole real line. am(F(phi)) = phi is well conditioned
 * (am' = dn <= 1); F(am(u)) = u is not: F' = 1/dn reaches 1/k', so an ulp
 * of am costs up to ulp/k' in u. */
static void test_F_inverts_am(void **state)
{
    (void)state;
    double worst_am = 0.0, worst_F = 0.0;
    for (int k = 0; k < NMS; ++k) {
        double m = ms[k];
        if (m >= 1.0 - 1e-9) continue;
        double kp = sqrt(1.0 - m);
        for (double x = -200.0; x <= 200.0; x += 0.731) {
            double phi = amplitude(braun_ellip_F(x, m), m);
            worst_am = fmax(worst_am, fabs(phi - x) / fmax(1.0, fabs(x)));
            double u = braun_ellip_F(amplitude(x, m), m);
            worst_F = fmax(worst_F, fabs(u - x) * kp / fmax(1.0, fabs(x)));
        }
    }
    print_message("am(F(phi)) - phi: worst %.2e relative\n", worst_am);
    print_message("F(am(u)) - u: worst %.2e relative, times k'\n", worst_F);
    assert_le(worst_am, 1e-15);
    assert_le(worst_F, 8e-16);
}

/* d sn/du = cn dn, d cn/du = -sn dn, d dn/du = -m sn cn (A&S 16.16). */
static void test_derivatives(void **state)
{
    (void)state;
    const double h = 1e-5;
    double worst = 0.0;
    for (int k = 0; k < NMS; ++k)
        for (double u = -30.0; u <= 30.0; u += 0.291) {
            double s0, c0, d0, sp, cp, dp, sm, cm, dm;
            braun_jacobi_sncndn(u, ms[k], &s0, &c0, &d0);
            braun_jacobi_sncndn(u + h, ms[k], &sp, &cp, &dp);
            braun_jacobi_sncndn(u - h, ms[k], &sm, &cm, &dm);
            worst = fmax(worst, fabs((sp - sm) / (2 * h) - c0 * d0));
            worst = fmax(worst, fabs((cp - cm) / (2 * h) + s0 * d0));
            worst = fmax(worst, fabs((dp - dm) / (2 * h) + ms[k] * s0 * c0));
        }
    assert_le(worst, 1e-9);
}

/* ----------------------------------------------------------------- pendulum */

typedef struct pend_case {
    double w2, phi0, dphi0;
    const char *what;
} pend_case;

static const pend_case cases[] = {
    {7.0 * 9.81 / 6.0, PI, -1.0, "four-bar: rotation from the top"},
    {9.81, PI / 2.0, 0.0, "pendulum: libration from the horizontal"},
    {1.0, 3.0, 0.1, "libration near the separatrix"},
    {9.81, 2.0 * PI + 0.4, -1.0, "libration about 2π"},
    {1.0, 0.3, 3.0, "rotation, positive"},
    {2.0, -7.0, -2.5, "rotation, negative, phi0 < -2π"},
    {4.0, 0.0, 0.0, "at rest at the bottom"},
};
#define NCASES ((int)(sizeof cases / sizeof cases[0]))

static void pend_rhs(double w2, const double *y, double *f)
{
    f[0] = y[1];
    f[1] = -w2 * sin(y[0]);
}

/* Fine classic RK4 on phi'' = -w2 sin phi with compensated summation, so
 * round-off (5e5 steps) stays below the 1e-12 being tested. */
static void test_pendulum_vs_rk4(void **state)
{
    (void)state;
    const double h = 1e-4, t_end = 50.0;
    const long steps_per_check = 10000; /* every second */
    for (int c = 0; c < NCASES; ++c) {
        double w2 = cases[c].w2;
        double y[2] = {cases[c].phi0, cases[c].dphi0}, comp[2] = {0, 0};
        double worst = 0.0;
        long nsteps = (long)(t_end / h + 0.5);
        for (long i = 1; i <= nsteps; ++i) {
            double k1[2], k2[2], k3[2], k4[2], tmp[2];
            pend_rhs(w2, y, k1);
            for (int j = 0; j < 2; ++j) tmp[j] = y[j] + 0.5 * h * k1[j];
            pend_rhs(w2, tmp, k2);
            for (int j = 0; j < 2; ++j) tmp[j] = y[j] + 0.5 * h * k2[j];
            pend_rhs(w2, tmp, k3);
            for (int j = 0; j < 2; ++j) tmp[j] = y[j] + h * k3[j];
            pend_rhs(w2, tmp, k4);
            for (int j = 0; j < 2; ++j) {
                double add = h / 6.0 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j])
                             - comp[j];
                double sum = y[j] + add;
                comp[j] = (sum - y[j]) - add;
                y[j] = sum;
            }
            if (i % steps_per_check == 0) {
                double phi, dphi;
                assert_int_equal(braun_pendulum_exact(w2, cases[c].phi0,
                                                      cases[c].dphi0, i * h,
                                                      &phi, &dphi),
                                 0);
                worst = fmax(worst, fmax(fabs(phi - y[0]), fabs(dphi - y[1])));
            }
        }
        print_message("%-40s max |exact - RK4| over 50 s: %.2e\n",
                      cases[c].what, worst);
        /* Measured 3.4e-13 at most (near the separatrix). */
        assert_le(worst, 1e-12);
    }
}

/* t = 0 reproduces the initial state (position and sign of velocity), and
 * phi' is the time derivative of phi. */
static void test_pendulum_initial_and_derivative(void **state)
{
    (void)state;
    for (int c = 0; c < NCASES; ++c) {
        double phi, dphi;
        assert_int_equal(braun_pendulum_exact(cases[c].w2, cases[c].phi0,
                                              cases[c].dphi0, 0.0, &phi, &dphi),
                         0);
        assert_near(phi, cases[c].phi0, 4e-15 * fmax(1.0, fabs(cases[c].phi0)));
        assert_near(dphi, cases[c].dphi0, 4e-15 * fmax(1.0, fabs(cases[c].dphi0)));
        for (double t = -3.0; t <= 20.0; t += 0.37) {
            const double h = 1e-5;
            double pp, pm, d0, dummy;
            braun_pendulum_exact(cases[c].w2, cases[c].phi0, cases[c].dphi0,
                                 t + h, &pp, &dummy);
            braun_pendulum_exact(cases[c].w2, cases[c].phi0, cases[c].dphi0,
                                 t - h, &pm, &dummy);
            braun_pendulum_exact(cases[c].w2, cases[c].phi0, cases[c].dphi0, t,
                                 &dummy, &d0);
            assert_near((pp - pm) / (2 * h), d0, 1e-8 * fmax(1.0, fabs(d0)));
        }
    }
}

/* H = ½phi'² - w2 cos phi is constant. The bound is relative to the energy
 * scale |H0| + w2: in the rotating cases phi reaches ~4e3 rad by t = 1000,
 * where one ulp of phi alone moves w2·cos(phi) by ~5e-12 for w2 = 11.4. */
static void test_pendulum_energy(void **state)
{
    (void)state;
    for (int c = 0; c < NCASES; ++c) {
        double w2 = cases[c].w2;
        double H0 = 0.5 * cases[c].dphi0 * cases[c].dphi0
                    - w2 * cos(cases[c].phi0);
        double worst = 0.0;
        for (double t = 0.0; t <= 1000.0; t += 0.0997) {
            double phi, dphi;
            assert_int_equal(braun_pendulum_exact(w2, cases[c].phi0,
                                                  cases[c].dphi0, t, &phi,
                                                  &dphi),
                             0);
            double H = 0.5 * dphi * dphi - w2 * cos(phi);
            worst = fmax(worst, fabs(H - H0));
        }
        print_message("%-40s max |H - H0| over 1000 s: %.2e (scale %.3g)\n",
                      cases[c].what, worst, fabs(H0) + w2);
        assert_le(worst, 1e-12 * (fabs(H0) + w2));
    }
}

/* Rotation: phi is continuous (unwrapped) and monotone in t. */
static void test_pendulum_unwrapped(void **state)
{
    (void)state;
    double w2 = 7.0 * 9.81 / 6.0, prev = PI;
    for (double t = 0.001; t <= 100.0; t += 0.001) {
        double phi, dphi;
        braun_pendulum_exact(w2, PI, -1.0, t, &phi, &dphi);
        assert_true(phi < prev);          /* turns the negative way */
        assert_true(prev - phi < 0.02);   /* no 2π jumps: |phi'| <= 6.9 */
        prev = phi;
    }
}

static void test_pendulum_refuses(void **state)
{
    (void)state;
    double phi, dphi, w2 = 2.0;
    /* Separatrix: from the bottom with exactly the energy to reach the top. */
    assert_true(braun_pendulum_exact(w2, 0.0, 2.0 * sqrt(w2), 1.0, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(w2, PI, 0.0, 1.0, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(0.0, 0.1, 0.0, 1.0, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(-1.0, 0.1, 0.0, 1.0, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(w2, NAN, 0.0, 1.0, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(w2, 0.1, 0.0, INFINITY, &phi, &dphi) < 0);
    assert_true(braun_pendulum_exact(w2, 0.1, 0.0, 1.0, NULL, &dphi) < 0);
    assert_true(braun_pendulum_exact(w2, 0.1, 0.0, 1.0, &phi, NULL) < 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identities),
        cmocka_unit_test(test_known_values),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_F_inverts_am),
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_pendulum_vs_rk4),
        cmocka_unit_test(test_pendulum_initial_and_derivative),
        cmocka_unit_test(test_pendulum_energy),
        cmocka_unit_test(test_pendulum_unwrapped),
        cmocka_unit_test(test_pendulum_refuses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
