/* A02, the N-four-bar: 2N + 1 uniform rods (1 m, 1 kg), N + 1 cranks from
 * A_i = (i, 0) to B_i and N couplers B_(i-1) B_i; B_i starts at (i, 1)
 * moving at (1, 0) m/s; gravity 9.81 m/s² along -y.
 *
 * Reduction (docs/iftomm.md): the cranks stay parallel (every window is a
 * parallelogram), so one angle ψ of the cranks from the downward vertical
 * places everything: B_i = A_i + (sin ψ, -cos ψ), the couplers translate
 * with B0. Each crank turns about its end (½ (m/3) ψ'²), each coupler
 * translates at |B0'| = ψ' (½ m ψ'²), so
 *   T = ½ J ψ'²,  J = (N + 1)/3 + N,
 *   V = -g G cos ψ,  G = (N + 1)/2 + N (crank centres at half height),
 * and ψ'' = -(g G / J) sin ψ from ψ(0) = π, ψ'(0) = -1: a pendulum that
 * goes over the top. With k = gG/J, e = ½ + k the energy per unit J and
 * parameter m = 2k/(e + k) < 1, ψ/2 = am(w) for w = K(m) - sqrt((e + k)/2) t:
 *   B0 = (2 sn cn, 2 sn² - 1),  B0' = w' (2 dn (cn² - sn²), 4 sn cn dn).
 * The horizontal configurations (ψ = ±π/2), where N windows fold, cost
 * the reduction nothing. */
#include <math.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_ellint.h>
#include <gsl/gsl_sf_elljac.h>

#include "ifm.h"

#define FB_G 9.81

static void inertia(const ifm_fourbar_params *p, double *J, double *G)
{
    *J = (p->N + 1) / 3.0 + p->N;
    *G = (p->N + 1) / 2.0 + p->N;
}

static ifm_cx kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    double J, G;
    (void)q;
    inertia(md->params, &J, &G);
    return 0.5 * J * v[0] * v[0];
}

static ifm_cx potential(const ifm_model *md, const ifm_cx *q)
{
    double J, G;
    inertia(md->params, &J, &G);
    return -FB_G * G * ccos(q[0]);
}

static void report(const ifm_model *md, const double *q, const double *v, double *out)
{
    (void)md;
    out[0] = sin(q[0]);
    out[1] = -cos(q[0]);
    out[2] = cos(q[0]) * v[0];
    out[3] = sin(q[0]) * v[0];
}

void ifm_fourbar_model(ifm_model *md, const ifm_fourbar_params *p)
{
    *md = (ifm_model){.name = "A02 N-four-bar (crank angle)", .n = 1, .m = 0,
                      .kinetic = kinetic, .potential = potential, .nreport = 4,
                      .report = report, .params = p};
}

void ifm_fourbar_state0(double *q0, double *v0)
{
    q0[0] = IFM_PI;
    v0[0] = -1;
}

int ifm_fourbar_exact(const ifm_fourbar_params *p, ifm_series *out)
{
    double J, G;
    inertia(p, &J, &G);
    const double k = FB_G * G / J, e = 0.5 + k, m = 2 * k / (e + k);
    const double rate = -sqrt(0.5 * (e + k));
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    const double K = gsl_sf_ellint_Kcomp(sqrt(m), GSL_PREC_DOUBLE);
    int st = 0;
    snprintf(out->how, sizeof out->how, "closed form (Jacobi sn, cn, dn; GSL)");
    for (long j = 0; j < out->count; j++) {
        double sn, cn, dn;
        /* sn cn, sn² and dn have period 2K in w. */
        const double w = K - fmod(-rate * out->t[j], 2 * K);
        if (gsl_sf_elljac_e(w, m, &sn, &cn, &dn) != GSL_SUCCESS) st = -1;
        double *y = out->y + j * out->width;
        y[0] = 2 * sn * cn;
        y[1] = 2 * sn * sn - 1;
        y[2] = rate * 2 * dn * (cn * cn - sn * sn);
        y[3] = rate * 4 * sn * cn * dn;
    }
    gsl_set_error_handler(old);
    /* Fastest at the bottom: ½ J ψ'² = ½ J + 2 g G. */
    out->max_kinetic = 0.5 * J + 2 * FB_G * G;
    return st;
}
