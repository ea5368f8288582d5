/*
 * Closed-form solution of the pendulum equation phi'' = -w2 sin(phi)
 * (Lawden, "Elliptic Functions and Applications", Sec. 5.2). Reference of
 * the four-bar (θ'' + (7g/6l) cos θ = 0 with phi = θ + π/2, Sec. 4.2) and of
 * the simple pendulum.
 *
 * With ω = √w2 the energy ½phi'² + 2w2 sin²(phi/2) fixes
 *   κ² = sin²(phi0/2) + phi0'² / (4 w2).
 *   κ < 1, libration:  sin(phi/2) = κ sn(ωt + u0 | κ²),  cos(phi/2) = dn,
 *                      phi' = 2κω cn(ωt + u0 | κ²).
 *   κ > 1, rotation:   phi/2 = s am(ρt/2 + u0 | 1/κ²),  ρ = 2κω = |phi'| at
 *                      the bottom, s = sign(phi0'),  phi' = s ρ dn(...).
 * κ = 1 (the separatrix, phi -> π as t -> ∞) is not periodic and is refused.
 */
#include <math.h>

#include "braun_reference.h"

/* π in double; C99 has no M_PI. */
#define BRAUN_PI_D 3.14159265358979323846

/* Closer to the separatrix than this the periods blow up. */
#define SEPARATRIX_TOL 1e-12

int braun_pendulum_exact(double w2, double phi0, double dphi0, double t,
                         double *phi, double *dphi)
{
    if (!phi || !dphi || !(w2 > 0.0) || !isfinite(w2) || !isfinite(phi0)
        || !isfinite(dphi0) || !isfinite(t))
        return -1;
    const double pi = BRAUN_PI_D;
    double omega = sqrt(w2);
    double sh = sin(0.5 * phi0);
    double kappa2 = sh * sh + dphi0 * dphi0 / (4.0 * w2);
    double kappa = sqrt(kappa2);
    if (fabs(kappa - 1.0) <= SEPARATRIX_TOL) return -1;

    double sn, cn, dn;
    if (kappa < 1.0) {
        /* Libration about the nearest bottom 2πn; |phi - 2πn| < π. */
        double n = nearbyint(phi0 / (2.0 * pi));
        double p0 = phi0 - 2.0 * pi * n;
        /* am(u0) has sn = sin(p0/2)/κ and cn = phi0'/(2κω): both the
         * position and the sign of the velocity are matched (also κ = 0). */
        double u0 = braun_ellip_F(atan2(sin(0.5 * p0), dphi0 / (2.0 * omega)),
                                  kappa2);
        braun_jacobi_sncndn(omega * t + u0, kappa2, &sn, &cn, &dn);
        /* atan2 rather than asin: well conditioned at the turning points. */
        *phi = 2.0 * atan2(kappa * sn, dn) + 2.0 * pi * n;
        *dphi = 2.0 * kappa * omega * cn;
    } else {
        double m = 1.0 / kappa2;
        double rho = 2.0 * kappa * omega;
        double s = dphi0 > 0.0 ? 1.0 : -1.0;
        /* F inverts am on the whole real line, so phi(0) = phi0 exactly
         * (e.g. phi0 = π, phi0' = -1 gives u0 = -K). */
        double u0 = braun_ellip_F(s * 0.5 * phi0, m);
        double u = 0.5 * rho * t + u0;
        braun_jacobi_sncndn(u, m, &sn, &cn, &dn);
        /* Continuous am: am(u) = jπ + am(u - 2jK) with am(u - 2jK) in
         * [-π/2, π/2] and sn, cn of u - 2jK equal to (-1)^j sn, cn. */
        double j = nearbyint(u / (2.0 * braun_ellip_K(m)));
        double flip = fmod(j, 2.0) == 0.0 ? 1.0 : -1.0;
        double am = j * pi + atan2(flip * sn, flip * cn);
        *phi = 2.0 * s * am;
        *dphi = s * rho * dn;
    }
    return 0;
}
