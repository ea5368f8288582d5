/* baumgarte: Baumgarte's stabilisation (1972) with the ideal constraint
 * force, integrated by fixed-step classic RK4.
 *
 * The acceleration-level constraints A_v q'' = b_v are replaced by
 *     A_q q'' = b_qv - 2α Φ̇_q - β² Φ_q      (Φ̇_q = A_q v - b_q)
 *     A_vv q'' = b_vv - α Φ_v               (first-order rows: rate α)
 * so the constraint errors obey Φ̈ + 2αΦ̇ + β²Φ = 0 and Φ̇_v + αΦ_v = 0.
 * The wrapper below hands these right-hand sides to libbraun as the
 * system's b_qv, b_vv; braun_eval with every correction off then returns
 * the ideal (Udwadia–Kalaba, minimum M⁻¹-norm) acceleration that satisfies
 * them — the same pseudoinverse the paper uses, so redundant rows and
 * singular configurations are treated alike by both methods. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

static int bg_holonomic(braun_real t, const braun_real *q, const braun_real *v,
                        braun_real *phi, braun_real *A, braun_real *b, braun_real *bv,
                        void *user)
{
    cmp_baumgarte_sys *bs = user;
    const int n = bs->inner.n, m = bs->inner.m;
    braun_real *Aw = A ? A : bs->A;
    int st = bs->inner.holonomic(t, q, v, bs->phi, Aw, bs->b, bv, bs->inner.user);
    if (st) return st;
    if (phi) memcpy(phi, bs->phi, (size_t)m * sizeof *phi);
    if (b) memcpy(b, bs->b, (size_t)m * sizeof *b);
    if (bv)
        for (int i = 0; i < m; i++) {
            double dphi = -bs->b[i];
            for (int j = 0; j < n; j++) dphi += Aw[(size_t)i * n + j] * v[j];
            bv[i] -= 2.0 * bs->alpha * dphi + bs->beta * bs->beta * bs->phi[i];
        }
    return 0;
}

static int bg_nonholonomic(braun_real t, const braun_real *q, const braun_real *v,
                           braun_real *phi, braun_real *A, braun_real *bv, void *user)
{
    cmp_baumgarte_sys *bs = user;
    const int p = bs->inner.p;
    braun_real *phiv = bs->phi + bs->inner.m;
    int st = bs->inner.nonholonomic(t, q, v, phiv, A, bv, bs->inner.user);
    if (st) return st;
    if (phi) memcpy(phi, phiv, (size_t)p * sizeof *phi);
    if (bv)
        for (int i = 0; i < p; i++) bv[i] -= bs->alpha * phiv[i];
    return 0;
}

/* The other callbacks pass through with the inner user pointer. */
static int bg_mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    cmp_baumgarte_sys *bs = user;
    return bs->inner.mass(t, q, M, bs->inner.user);
}

static int bg_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                     void *user)
{
    cmp_baumgarte_sys *bs = user;
    return bs->inner.forces(t, q, v, Q, bs->inner.user);
}

static int bg_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                     braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    cmp_baumgarte_sys *bs = user;
    return bs->inner.energy(t, q, v, E, dE_dq, dE_dv, dE_dt, bs->inner.user);
}

static int bg_power(braun_real t, const braun_real *q, const braun_real *v, braun_real *P,
                    void *user)
{
    cmp_baumgarte_sys *bs = user;
    return bs->inner.power(t, q, v, P, bs->inner.user);
}

int cmp_baumgarte_wrap(cmp_baumgarte_sys *bs, const braun_system *inner, double alpha,
                       double beta, braun_system *out)
{
    memset(bs, 0, sizeof *bs);
    bs->inner = *inner;
    bs->alpha = alpha;
    bs->beta = beta;
    const size_t n = (size_t)inner->n, m = (size_t)inner->m, p = (size_t)inner->p;
    bs->phi = malloc((2 * m + p + m * n + 1) * sizeof(double));
    if (!bs->phi) return -1;
    bs->b = bs->phi + m + p;
    bs->A = bs->b + m;
    *out = *inner;
    out->user = bs;
    out->mass = bg_mass;
    out->forces = bg_forces;
    out->holonomic = inner->holonomic ? bg_holonomic : NULL;
    out->nonholonomic = inner->nonholonomic ? bg_nonholonomic : NULL;
    out->energy = inner->energy ? bg_energy : NULL;
    out->power = inner->power ? bg_power : NULL;
    return 0;
}

void cmp_baumgarte_free(cmp_baumgarte_sys *bs)
{
    free(bs->phi);
    bs->phi = bs->b = bs->A = NULL;
}

/* y' = [v, ideal acceleration of the wrapped system]. */
static int rhs(braun_data *d, double t, const double *y, double *dy, int n)
{
    int st = braun_eval(d, t, y, y + n, 1.0, dy, dy + n);
    if (st) return st;
    memcpy(dy, y + n, (size_t)n * sizeof(double));
    return 0;
}

void cmp_run_baumgarte(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                       cmp_outcome *out)
{
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    const int n = tg->sys.n, N = 2 * n;
    cmp_baumgarte_sys bs;
    braun_system wrapped;
    braun_model model;
    braun_data d;
    void *buf = NULL;
    double *work = NULL;
    int st = cmp_baumgarte_wrap(&bs, &tg->sys, spec->alpha, spec->beta, &wrapped);
    if (st) {
        snprintf(out->status_name, sizeof out->status_name, "OUT_OF_MEMORY");
        out->status = -1;
        return;
    }
    st = braun_model_init(&model, &wrapped);
    model.opt.corrections = BRAUN_CORRECT_NONE;
    size_t bytes = st ? 0 : braun_data_size(&model);
    if (!st && (!(buf = malloc(bytes)) || !(work = malloc(6 * (size_t)N * sizeof(double)))))
        st = BRAUN_ERR_BUFFER;
    if (!st) st = braun_data_init(&d, &model, buf, bytes);
    if (!st) st = braun_set_state(&d, 0, tg->q0, tg->v0);
    if (st) {
        cmp_status_from_braun(out, st);
        goto done;
    }
    double *y = work, *k1 = y + N, *k2 = k1 + N, *k3 = k2 + N, *k4 = k3 + N, *w = k4 + N;
    memcpy(y, tg->q0, (size_t)n * sizeof(double));
    memcpy(y + n, tg->v0, (size_t)n * sizeof(double));
    const double h = spec->h;
    const long steps = (long)ceil(spec->T / h - 1e-9 * spec->T / h);
    const long every = cmp_every(spec->dt_out, h);
    double t = 0;
    cmp_traj_push(tr, t, y, y + n);
    for (long s = 1; s <= steps; s++) {
        const double t1 = s == steps ? spec->T : (double)s * h, hs = t1 - t;
        st = rhs(&d, t, y, k1, n);
        for (int i = 0; i < N && !st; i++) w[i] = y[i] + 0.5 * hs * k1[i];
        if (!st) st = rhs(&d, t + 0.5 * hs, w, k2, n);
        for (int i = 0; i < N && !st; i++) w[i] = y[i] + 0.5 * hs * k2[i];
        if (!st) st = rhs(&d, t + 0.5 * hs, w, k3, n);
        for (int i = 0; i < N && !st; i++) w[i] = y[i] + hs * k3[i];
        if (!st) st = rhs(&d, t1, w, k4, n);
        if (st) {
            /* A non-finite stage state is a diverged step, as in libbraun. */
            cmp_status_from_braun(out, st == BRAUN_ERR_NONFINITE ? BRAUN_ERR_DIVERGED : st);
            break;
        }
        int finite = 1;
        for (int i = 0; i < N; i++) {
            y[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            finite &= isfinite(y[i]) != 0;
        }
        if (!finite) {
            cmp_status_from_braun(out, BRAUN_ERR_DIVERGED);
            break;
        }
        t = t1;
        out->counts.steps++;
        if (s % every == 0 || s == steps) cmp_traj_push(tr, t, y, y + n);
    }
    if (!out->status) cmp_status_from_braun(out, BRAUN_OK);
    else snprintf(out->detail, sizeof out->detail, "at t = %.9g", t);
    out->t_reached = t;
    out->counts.rhs_evals = d.stats.rhs_evals;
    out->counts.lin_setups = d.stats.constraint_factorizations;
    out->counts.lin_solves = d.stats.rhs_evals;
done:
    free(work);
    free(buf);
    cmp_baumgarte_free(&bs);
}
