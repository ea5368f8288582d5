/* A01, the simple pendulum: a point mass m = 1 kg on a massless rod of
 * L = 1 m, gravity 9.81 m/s² along -y, released at rest from P1 = (1, 0).
 *
 * One coordinate, the angle θ of the rod from the downward vertical:
 * P1 = L (sin θ, -cos θ), T = ½ m L² θ'², V = -m g L cos θ, so
 * θ'' = -(g/L) sin θ with θ(0) = π/2, θ'(0) = 0. Its closed form
 * (docs/iftomm.md): with k = sin(θ0/2), parameter k², ω = sqrt(g/L) and
 * u = ω t + K(k²), sin(θ/2) = k sn u and cos(θ/2) = dn u, hence
 *   P1 = L (2k sn u dn u, 2k² sn² u - 1). */
#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_ellint.h>
#include <gsl/gsl_sf_elljac.h>

#include "ifm.h"

#define PEND_M 1.0
#define PEND_L 1.0
#define PEND_G 9.81

static ifm_cx kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    (void)md;
    (void)q;
    return 0.5 * PEND_M * PEND_L * PEND_L * v[0] * v[0];
}

static ifm_cx potential(const ifm_model *md, const ifm_cx *q)
{
    (void)md;
    return -PEND_M * PEND_G * PEND_L * ccos(q[0]);
}

static void report(const ifm_model *md, const double *q, const double *v, double *out)
{
    (void)md;
    (void)v;
    out[0] = PEND_L * sin(q[0]);
    out[1] = -PEND_L * cos(q[0]);
}

const ifm_model ifm_pendulum_model = {
    .name = "A01 pendulum (angle)", .n = 1, .m = 0, .kinetic = kinetic,
    .potential = potential, .nreport = 2, .report = report};

void ifm_pendulum_state0(double *q0, double *v0)
{
    q0[0] = 0.5 * IFM_PI;
    v0[0] = 0;
}

int ifm_pendulum_exact(ifm_series *out)
{
    const double theta0 = 0.5 * IFM_PI, k = sin(0.5 * theta0), m = k * k;
    const double w = sqrt(PEND_G / PEND_L);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    const double K = gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE);
    int st = 0;
    snprintf(out->how, sizeof out->how, "closed form (Jacobi sn, dn; GSL)");
    for (long j = 0; j < out->count; j++) {
        double sn, cn, dn;
        /* sn, dn have period 4K in u: reduce first (the phase of a long
         * run then carries the round-off of K alone). */
        const double u = fmod(w * out->t[j], 4 * K) + K;
        if (gsl_sf_elljac_e(u, m, &sn, &cn, &dn) != GSL_SUCCESS) st = -1;
        out->y[j * out->width + 0] = PEND_L * 2 * k * sn * dn;
        out->y[j * out->width + 1] = PEND_L * (2 * k * k * sn * sn - 1);
    }
    gsl_set_error_handler(old);
    out->max_kinetic = PEND_M * PEND_G * PEND_L; /* at the bottom */
    return st;
}
