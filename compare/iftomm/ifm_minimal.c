/* A reference model on minimal coordinates, integrated by GSL's
 * Prince-Dormand 8(9) pair (rk8pd) at rtol = atol = tol.
 *
 * One degree of freedom (m = n - 1): the state is (s, s', W) with s =
 * q[indep]; every evaluation rebuilds q from φ(q) = 0 by Newton (from the
 * last q: a warm start), v from ψ(q, v) = 0 with v[indep] = s', and takes
 * s'' from the KKT acceleration. That is Lagrange's equation on the one
 * coordinate (coordinate partitioning), an ODE with nothing to drift.
 * No constraints (m = 0): rk8pd on (q, v, W) directly. */
#include <math.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "ifm.h"

#define NEWTON_TOL 1e-15

typedef struct min_ctx {
    const ifm_model *md;
    int indep;
    double q[IFM_MAX_N], v[IFM_MAX_N]; /* last rebuilt state (warm start) */
    int failed;
} min_ctx;

/* Full (q, v) from the minimal state y. */
static int lift(min_ctx *c, const double *y)
{
    const ifm_model *md = c->md;
    if (md->m == 0) {
        memcpy(c->q, y, (size_t)md->n * sizeof *y);
        memcpy(c->v, y + md->n, (size_t)md->n * sizeof *y);
        return 0;
    }
    c->q[c->indep] = y[0];
    c->v[c->indep] = y[1];
    return ifm_project(md, c->indep, c->q, c->v, NEWTON_TOL);
}

static int rhs(double t, const double y[], double f[], void *u)
{
    min_ctx *c = u;
    const ifm_model *md = c->md;
    const int n = md->n;
    double a[IFM_MAX_N];
    if (lift(c, y) || ifm_accel(md, t, c->q, c->v, a, NULL)) {
        c->failed = 1;
        return GSL_EBADFUNC;
    }
    if (md->m == 0) {
        memcpy(f, y + n, (size_t)n * sizeof *f);
        memcpy(f + n, a, (size_t)n * sizeof *f);
        f[2 * n] = ifm_power(md, t, c->q, c->v);
    } else {
        f[0] = y[1];
        f[1] = a[c->indep];
        f[2] = ifm_power(md, t, c->q, c->v);
    }
    return GSL_SUCCESS;
}

int ifm_minimal_run(const ifm_model *md, int indep, const double *q0, const double *v0,
                    double tol, ifm_series *out, char *why, size_t whysize)
{
    const int n = md->n, m = md->m;
    const clock_t c0 = clock();
    min_ctx c;
    memset(&c, 0, sizeof c);
    c.md = md;
    c.indep = indep;
    if (m != 0 && m != n - 1) {
        snprintf(why, whysize, "%s: %d rows in %d coordinates is not one degree of freedom",
                 md->name, m, n);
        return -1;
    }
    memcpy(c.q, q0, (size_t)n * sizeof *q0);
    memcpy(c.v, v0, (size_t)n * sizeof *v0);
    const int dim = m == 0 ? 2 * n + 1 : 3;
    double y[2 * IFM_MAX_N + 1];
    if (m == 0) {
        memcpy(y, q0, (size_t)n * sizeof *y);
        memcpy(y + n, v0, (size_t)n * sizeof *y);
        y[2 * n] = 0;
    } else {
        y[0] = q0[indep];
        y[1] = v0[indep];
        y[2] = 0;
    }
    snprintf(out->how, sizeof out->how, "%s, GSL rk8pd rtol = atol = %.0e",
             m == 0 ? "joint coordinates" : "one minimal coordinate", tol);
    out->max_phi = out->max_energy = out->max_kinetic = 0;
    gsl_odeiv2_system sys = {rhs, NULL, (size_t)dim, &c};
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, tol, tol);
    if (!drv) {
        snprintf(why, whysize, "%s: out of memory", md->name);
        return -1;
    }
    gsl_odeiv2_driver_set_nmax(drv, 0);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    const double E0 = ifm_energy(md, q0, v0);
    double t = 0;
    int st = 0;
    for (long j = 0; j < out->count; j++) {
        if (j > 0) {
            const int s = gsl_odeiv2_driver_apply(drv, &t, out->t[j], y);
            if (s != GSL_SUCCESS) {
                snprintf(why, whysize, "%s: rk8pd failed at t = %.9g (%s)", md->name, t,
                         c.failed ? "no configuration closes the loop there" : gsl_strerror(s));
                st = -1;
                break;
            }
        }
        if (lift(&c, y)) {
            snprintf(why, whysize, "%s: Newton failed at t = %.9g", md->name, t);
            st = -1;
            break;
        }
        if (out->q) memcpy(out->q + j * n, c.q, (size_t)n * sizeof *c.q);
        if (out->v) memcpy(out->v + j * n, c.v, (size_t)n * sizeof *c.v);
        md->report(md, c.q, c.v, out->y + j * out->width);
        if (m > 0) {
            double phi[IFM_MAX_M];
            ifm_phi(md, c.q, phi);
            for (int r = 0; r < m; r++) out->max_phi = fmax(out->max_phi, fabs(phi[r]));
        }
        out->max_kinetic = fmax(out->max_kinetic, ifm_kinetic(md, c.q, c.v));
        out->max_energy =
            fmax(out->max_energy, fabs(ifm_energy(md, c.q, c.v) - E0 - y[dim - 1]));
    }
    gsl_set_error_handler(old);
    gsl_odeiv2_driver_free(drv);
    out->cpu_s = (double)(clock() - c0) / CLOCKS_PER_SEC;
    return st;
}
