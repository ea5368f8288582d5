/* The DAE forms given to SUNDIALS IDA, built from the same braun_system
 * callbacks as every other method.
 *
 * ida-ggl, the stabilised index-2 formulation of Gear, Gupta & Leimkuhler
 * (1985), unknowns y = [q, v, λ, μ]:
 *     q' = v - A_qᵀ μ                 (μ = 0 on the exact solution)
 *     M v' = Q + A_vᵀ λ               (A_v = [A_q; A_vv], Eq. 5)
 *     0 = A_q v - b_q,  0 = Φ_v       (velocity level, Eq. 4 and Eq. 2)
 *     0 = Φ_q                         (position level, Eq. 2)
 * ida-index1, the acceleration-level formulation, unknowns y = [q, v, λ]:
 *     q' = v,  M v' = Q + A_vᵀ λ,  0 = A_v v' - b_v
 * which IDA integrates without looking at Φ_q or Φ̇_q: they drift.
 * Residuals are written as F(t, y, y') = 0 in that order of rows. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

struct cmp_dae {
    const cmp_target *tg;
    const braun_system *sys;
    int n, m, p, mv, N, index1;
    int mass_ready;
    double reg;
    double *M, *Q, *phi, *A, *b, *bv; /* holonomic rows first, then nonholonomic */
};

cmp_dae *cmp_dae_new(const cmp_target *tg, int index1)
{
    cmp_dae *d = calloc(1, sizeof *d);
    if (!d) return NULL;
    d->tg = tg;
    d->sys = &tg->sys;
    d->n = tg->sys.n;
    d->m = tg->sys.m;
    d->p = tg->sys.p;
    d->mv = d->m + d->p;
    d->index1 = index1;
    d->N = 2 * d->n + d->mv + (index1 ? 0 : d->m);
    const size_t n = (size_t)d->n, mv = (size_t)d->mv;
    d->M = malloc((n * n + n + 3 * mv + mv * n + 1) * sizeof(double));
    if (!d->M) {
        free(d);
        return NULL;
    }
    d->Q = d->M + n * n;
    d->phi = d->Q + n;
    d->b = d->phi + mv;
    d->bv = d->b + mv;
    d->A = d->bv + mv;
    return d;
}

void cmp_dae_set_reg(cmp_dae *d, double eps)
{
    d->reg = eps;
}

void cmp_dae_free(cmp_dae *d)
{
    if (!d) return;
    free(d->M);
    free(d);
}

int cmp_dae_size(const cmp_dae *d)
{
    return d->N;
}

/* SUNDIALS convention: 0 ok, > 0 recoverable, < 0 fatal. */
static int cb(int st)
{
    return st > 0 ? 1 : (st < 0 ? -1 : 0);
}

/* M, Q, Φ, A_v, b_q and (want_bv) b_v at (t, q, v). */
static int evaluate(cmp_dae *d, double t, const double *q, const double *v, int want_bv)
{
    const braun_system *s = d->sys;
    const int n = d->n, m = d->m, p = d->p;
    int st = 0;
    if (!d->mass_ready || !(s->flags & BRAUN_MASS_CONSTANT)) {
        st = cb(s->mass(t, q, d->M, s->user));
        if (st) return st;
        d->mass_ready = 1;
    }
    st = cb(s->forces(t, q, v, d->Q, s->user));
    if (st) return st;
    if (m > 0) {
        st = cb(s->holonomic(t, q, v, d->phi, d->A, d->b, want_bv ? d->bv : NULL, s->user));
        if (st) return st;
    }
    if (p > 0) {
        st = cb(s->nonholonomic(t, q, v, d->phi + m, d->A + (size_t)m * n,
                                want_bv ? d->bv + m : NULL, s->user));
        if (st) return st;
        for (int k = m; k < m + p; k++) d->b[k] = 0;
    }
    for (int i = 0; i < n; i++)
        if (!isfinite(d->Q[i])) return 1;
    return 0;
}

static double dot(int n, const double *a, const double *b)
{
    double s = 0;
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

int cmp_dae_residual(cmp_dae *d, double t, const double *y, const double *yp, double *r)
{
    const int n = d->n, m = d->m, mv = d->mv;
    const double *q = y, *v = y + n, *lam = y + 2 * n;
    const double *qp = yp, *vp = yp + n;
    int st = evaluate(d, t, q, v, d->index1);
    if (st) return st;

    /* Kinematic rows: q' - v (+ A_qᵀμ for GGL). */
    for (int i = 0; i < n; i++) r[i] = qp[i] - v[i];
    if (!d->index1) {
        const double *mu = y + 2 * n + mv;
        for (int k = 0; k < m; k++)
            for (int i = 0; i < n; i++) r[i] += d->A[(size_t)k * n + i] * mu[k];
    }
    /* Dynamic rows: M v' - Q - A_vᵀλ. */
    for (int i = 0; i < n; i++) r[n + i] = dot(n, d->M + (size_t)i * n, vp) - d->Q[i];
    for (int k = 0; k < mv; k++)
        for (int i = 0; i < n; i++) r[n + i] -= d->A[(size_t)k * n + i] * lam[k];
    /* Constraint rows. */
    double *rc = r + 2 * n;
    if (d->index1) {
        for (int k = 0; k < mv; k++) rc[k] = dot(n, d->A + (size_t)k * n, vp) - d->bv[k];
    } else {
        for (int k = 0; k < m; k++) rc[k] = dot(n, d->A + (size_t)k * n, v) - d->b[k];
        for (int k = m; k < mv; k++) rc[k] = d->phi[k];
        for (int k = 0; k < m; k++) rc[mv + k] = d->phi[k];
    }
    if (d->reg > 0)
        for (int i = 2 * n; i < d->N; i++) r[i] -= d->reg * y[i];
    for (int i = 0; i < d->N; i++)
        if (!isfinite(r[i])) return 1;
    return 0;
}

/* ||x||_2 */
static double norm2(int k, const double *x)
{
    return sqrt(dot(k, x, x));
}

int cmp_dae_consistent(cmp_dae *d, double t, const double *q0, const double *v0,
                       double *y, double *yp)
{
    const int n = d->n, m = d->m, mv = d->mv;
    double *q = y, *v = y + n;
    double *r = malloc((size_t)(mv + n) * sizeof(double));
    if (!r) return -1;
    double *dx = r + mv;
    int st = 0;
    memcpy(q, q0, (size_t)n * sizeof(double));
    memcpy(v, v0, (size_t)n * sizeof(double));

    /* 1. Positions: Gauss-Newton with minimum-M-norm steps on Φ_q = 0. */
    for (int it = 0; it < 50 && m > 0; it++) {
        if ((st = evaluate(d, t, q, v, 0))) goto done;
        if (norm2(m, d->phi) <= 1e-15) break;
        for (int k = 0; k < m; k++) r[k] = -d->phi[k];
        if ((st = cmp_min_norm_step(n, m, d->M, d->A, r, dx))) goto done;
        for (int i = 0; i < n; i++) q[i] += dx[i];
    }
    /* 2. Velocities: A_q v = b_q and Φ_v(q, v) = 0 (Newton: Φ_v may be
     * nonlinear in v; ∂Φ_v/∂v = A_vv). */
    for (int it = 0; it < 50 && mv > 0; it++) {
        if ((st = evaluate(d, t, q, v, 0))) goto done;
        for (int k = 0; k < m; k++) r[k] = d->b[k] - dot(n, d->A + (size_t)k * n, v);
        for (int k = m; k < mv; k++) r[k] = -d->phi[k];
        if (norm2(mv, r) <= 1e-15) break;
        if ((st = cmp_min_norm_step(n, mv, d->M, d->A, r, dx))) goto done;
        for (int i = 0; i < n; i++) v[i] += dx[i];
    }
    /* 3. v' and λ from M v' = Q + A_vᵀλ, A_v v' = b_v; μ = 0. */
    if ((st = evaluate(d, t, q, v, 1))) goto done;
    for (int i = 0; i < n; i++) yp[i] = v[i];
    if ((st = cmp_kkt_accel(n, mv, d->M, d->Q, d->A, d->bv, yp + n, y + 2 * n))) goto done;
    for (int i = 2 * n + mv; i < d->N; i++) y[i] = 0;
    for (int i = 2 * n; i < d->N; i++) yp[i] = 0;
done:
    free(r);
    return st;
}
