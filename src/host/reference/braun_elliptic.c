/*
 * Jacobi elliptic functions sn, cn, dn and the elliptic integral of the
 * first kind, for the closed-form pendulum references. Always double: they
 * serve the references, whatever braun_real is.
 *
 * sn, cn: descending Landen transformation driven by the arithmetic-geometric
 * mean (Abramowitz & Stegun 16.4; DLMF 22.20(ii)). F: Carlson's R_F
 * (Carlson 1995, DLMF 19.25.5, 19.36.1).
 *
 * Both reduce their argument by the period first. The period is computed
 * in long double: reducing u by j·2K costs |u|·ε(K) absolutely, so with a
 * double K the result at u ~ 1e4 would only be good to ~1e-12. Where long
 * double is double this degrades gracefully to that.
 */
#include <float.h>
#include <math.h>

#include "braun_reference.h"

/* π in double; C99 has no M_PI. */
#define BRAUN_PI_D 3.14159265358979323846

#define PI_L 3.141592653589793238462643383279502884L

/* The AGM converges quadratically: about 10 steps even for 1 - m = 2^-53. */
#define AGM_MAX 40

/* K(m) = π / (2 AGM(1, √(1-m)))  (A&S 17.6.1), in long double. */
static long double ellip_K_long(double m)
{
    long double a = 1.0L;
    long double b = sqrtl(1.0L - (long double)m);
    for (int i = 0; i < AGM_MAX && fabsl(a - b) > LDBL_EPSILON * a; ++i) {
        long double an = 0.5L * (a + b);
        b = sqrtl(a * b);
        a = an;
    }
    return PI_L / (a + b);
}

double braun_ellip_K(double m)
{
    if (!(m >= 0.0 && m < 1.0)) return m == 1.0 ? HUGE_VAL : (double)NAN;
    return (double)ellip_K_long(m);
}

void braun_jacobi_sncndn(double u, double m, double *sn, double *cn,
                         double *dn)
{
    double s, c, d;
    if (!(m >= 0.0 && m <= 1.0) || !isfinite(u)) {
        s = c = d = (double)NAN;
    } else if (m == 1.0) {
        /* Limit m -> 1: sn = tanh, cn = dn = sech (A&S 16.6). */
        s = tanh(u);
        c = d = 1.0 / cosh(u);
    } else {
        /* Reduce by the half period 2K: sn, cn change sign, dn does not
         * (A&S 16.8), leaving |u_r| <= K. */
        long double K2 = 2.0L * ellip_K_long(m);
        double j = nearbyint((double)((long double)u / K2));
        double ur = (double)((long double)u - (long double)j * K2);
        double flip = fmod(j, 2.0) == 0.0 ? 1.0 : -1.0;

        /* AGM from (a0, b0) = (1, k'), c_n = (a_{n-1} - b_{n-1})/2 taken as
         * c_{n-1}² / (4 a_n) to avoid the cancellation. */
        double a[AGM_MAX + 1], bb[AGM_MAX + 1], cc[AGM_MAX + 1];
        int n = 0;
        a[0] = 1.0;
        bb[0] = sqrt(1.0 - m);
        cc[0] = sqrt(m);
        double twon = 1.0;
        while (n < AGM_MAX && cc[n] > DBL_EPSILON * a[n]) {
            a[n + 1] = 0.5 * (a[n] + bb[n]);
            bb[n + 1] = sqrt(a[n] * bb[n]);
            cc[n + 1] = cc[n] * cc[n] / (4.0 * a[n + 1]);
            ++n;
            twon *= 2.0;
        }
        /* Descend: φ_{n-1} = (φ_n + asin(c_n sin φ_n / a_n)) / 2, φ_0 = am u.
         * asin is ill conditioned where its argument nears ±1 (m near 1:
         * c_1/a_1 -> 1), so it is taken as atan2 with the cosine
         * √(a² cos²φ + b² sin²φ)/a, exact by a_n² - c_n² = b_n². */
        double phi = twon * a[n] * ur;
        for (; n > 0; --n) {
            double sp = sin(phi), cp = cos(phi);
            double num = cc[n] * sp;
            double den = sqrt(a[n] * a[n] * cp * cp + bb[n] * bb[n] * sp * sp);
            phi = 0.5 * (phi + atan2(num, den));
        }
        s = flip * sin(phi);
        c = flip * cos(phi);
        /* dn² = k'² + m cn²: a sum of non-negative terms, accurate where
         * dn is small (m near 1, u near K), unlike cos φ_0 / cos(φ_1 - φ_0). */
        d = sqrt((1.0 - m) + m * c * c);
    }
    if (sn) *sn = s;
    if (cn) *cn = c;
    if (dn) *dn = d;
}

/* Carlson's R_F(x, y, z) for x, y, z >= 0, at most one zero (Carlson 1995,
 * Algorithm 1; relative error about r = 1e-16). */
static double carlson_rf(double x0, double y0, double z0)
{
    /* (3r)^(-1/6) for r = 1e-16, rounded up. */
    const double q_scale = 400.0;
    double x = x0, y = y0, z = z0;
    double A0 = (x + y + z) / 3.0;
    double A = A0;
    double Q = q_scale * fmax(fabs(A0 - x), fmax(fabs(A0 - y), fabs(A0 - z)));
    double f = 1.0; /* 4^-n */
    for (int i = 0; i < 64 && f * Q >= fabs(A); ++i) {
        double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
        double lam = sx * sy + sx * sz + sy * sz;
        x = 0.25 * (x + lam);
        y = 0.25 * (y + lam);
        z = 0.25 * (z + lam);
        A = 0.25 * (A + lam);
        f *= 0.25;
    }
    double X = (A0 - x0) * f / A;
    double Y = (A0 - y0) * f / A;
    double Z = -(X + Y);
    double E2 = X * Y - Z * Z;
    double E3 = X * Y * Z;
    return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0)
           / sqrt(A);
}

/* F(φ|m) = sin φ R_F(cos²φ, 1 - m sin²φ, 1) for |φ| <= π/2 (DLMF 19.25.5),
 * extended by quasi-periodicity F(φ + jπ) = F(φ) + 2jK. */
double braun_ellip_F(double phi, double m)
{
    if (!(m >= 0.0 && m < 1.0) || !isfinite(phi)) return (double)NAN;
    double j = nearbyint(phi / BRAUN_PI_D);
    double pr = (double)((long double)phi - (long double)j * PI_L);
    double s = sin(pr), c = cos(pr);
    /* 1 - m sin²φ as cos²φ + (1-m) sin²φ: no cancellation near φ = ±π/2
     * when m is near 1. */
    double F = s * carlson_rf(c * c, c * c + (1.0 - m) * s * s, 1.0);
    if (j != 0.0)
        F = (double)((long double)F + 2.0L * (long double)j * ellip_K_long(m));
    return F;
}
