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
    double *Avals, *Mvals;            /* compressed outputs of a sparse system */
};

#ifdef BRAUN_MAX_SPARSE
/* A system with a sparsity (braun.h) writes compressed A and block M; the
 * DAE keeps dense copies (scattered), so every row below reads the same. */
static size_t sparse_A_count(const braun_system *s)
{
    return s->sparsity ? (size_t)s->sparsity->row_ptr[s->m + s->p] : 0;
}

static size_t sparse_M_count(const braun_system *s)
{
    size_t c = 0;
    if (s->sparsity)
        for (int k = 0; k < s->sparsity->nblocks; k++)
            c += (size_t)s->sparsity->block[k] * (size_t)s->sparsity->block[k];
    return c;
}

/* Rows r0..r1-1 of the compressed values (vals starts at row r0) into A,
 * whose first row is row r0. */
static void scatter_A(const braun_sparsity *sp, int n, int r0, int r1, const double *vals,
                      double *A)
{
    const int base = sp->row_ptr[r0];
    for (int k = r0; k < r1; k++) {
        double *row = A + (size_t)(k - r0) * n;
        for (int j = 0; j < n; j++) row[j] = 0;
        for (int e = sp->row_ptr[k]; e < sp->row_ptr[k + 1]; e++) row[sp->col[e]] += vals[e - base];
    }
}

static void scatter_M(const braun_sparsity *sp, int n, const double *vals, double *M)
{
    for (size_t i = 0; i < (size_t)n * n; i++) M[i] = 0;
    int off = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        const int b = sp->block[k];
        for (int i = 0; i < b; i++)
            for (int j = 0; j < b; j++) M[(size_t)(off + i) * n + off + j] = *vals++;
        off += b;
    }
}
#endif

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
#ifdef BRAUN_MAX_SPARSE
    if (tg->sys.sparsity) {
        d->Avals = malloc((sparse_A_count(&tg->sys) + sparse_M_count(&tg->sys) + 1) *
                          sizeof(double));
        if (!d->Avals) {
            free(d->M);
            free(d);
            return NULL;
        }
        d->Mvals = d->Avals + sparse_A_count(&tg->sys);
    }
#endif
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
    free(d->Avals);
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
    /* Dense callbacks write straight into M and A; a sparse system into
     * the compressed buffers, scattered afterwards. */
    double *Mout = d->Mvals ? d->Mvals : d->M, *Aq = d->A, *Avv = d->A + (size_t)m * n;
#ifdef BRAUN_MAX_SPARSE
    const braun_sparsity *sp = s->sparsity;
    if (sp) {
        Aq = d->Avals;
        Avv = d->Avals + sp->row_ptr[m];
    }
#endif
    if (!d->mass_ready || !(s->flags & BRAUN_MASS_CONSTANT)) {
        st = cb(s->mass(t, q, Mout, s->user));
        if (st) return st;
#ifdef BRAUN_MAX_SPARSE
        if (sp) scatter_M(sp, n, d->Mvals, d->M);
#endif
        d->mass_ready = 1;
    }
    st = cb(s->forces(t, q, v, d->Q, s->user));
    if (st) return st;
    if (m > 0) {
        st = cb(s->holonomic(t, q, v, d->phi, Aq, d->b, want_bv ? d->bv : NULL, s->user));
        if (st) return st;
#ifdef BRAUN_MAX_SPARSE
        if (sp) scatter_A(sp, n, 0, m, Aq, d->A);
#endif
    }
    if (p > 0) {
        st = cb(s->nonholonomic(t, q, v, d->phi + m, Avv, want_bv ? d->bv + m : NULL,
                                s->user));
        if (st) return st;
#ifdef BRAUN_MAX_SPARSE
        if (sp) scatter_A(sp, n, m, m + p, Avv, d->A + (size_t)m * n);
#endif
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

/* ------------------------------------------------------------ patterns */
/* The probe's four states: trial 0 is (y0, y0'), trials 1-3 random
 * perturbations of ±10 % (of max(|y0_i|, 1) in y, absolute in y'). The
 * generator runs through every trial so that each is reproducible. */
static void probe_states(int N, const double *y0, const double *yp0, double *Y)
{
    unsigned long seed = 12345;
    for (int trial = 0; trial < 4; trial++) {
        double *y = Y + (size_t)trial * 2 * N, *yp = y + N;
        for (int i = 0; i < N; i++) {
            seed = seed * 6364136223846793005UL + 1442695040888963407UL;
            double u = trial ? (double)(seed >> 11) / 9007199254740992.0 - 0.5 : 0.0;
            y[i] = y0[i] + 0.2 * u * fmax(fabs(y0[i]), 1.0);
            yp[i] = yp0[i] + 0.2 * u;
        }
    }
}

static int cmp_int(const void *a, const void *b)
{
    const int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

int cmp_dae_pattern_probe(cmp_dae *d, const double *y0, const double *yp0, int **colptr,
                          int **rowind)
{
    const int N = d->N;
    double *Y = malloc((size_t)N * 13 * sizeof(double));
    int *stamp = malloc((size_t)N * sizeof(int));
    int *cp = malloc(((size_t)N + 1) * sizeof(int));
    cmp_pairs P = {0, 0, NULL, NULL, 0};
    int nnz = -1;
    *colptr = *rowind = NULL;
    if (!Y || !stamp || !cp) goto done;
    double *R0 = Y + (size_t)N * 8, *r1 = R0 + (size_t)N * 4;
    probe_states(N, y0, yp0, Y);
    for (int trial = 0; trial < 4; trial++)
        if (cmp_dae_residual(d, 0.0, Y + (size_t)trial * 2 * N, Y + (size_t)trial * 2 * N + N,
                             R0 + (size_t)trial * N))
            goto done;
    for (int i = 0; i < N; i++) stamp[i] = -1;
    for (int j = 0; j < N; j++) {
        cp[j] = (int)P.n;
        for (int trial = 0; trial < 4; trial++) {
            double *y = Y + (size_t)trial * 2 * N, *yp = y + N;
            const double *r0 = R0 + (size_t)trial * N;
            const double yj = y[j], ypj = yp[j];
            /* One forward-difference column (c_j = 1), as IDA's own. */
            const double dj = 1.4901161193847656e-08 * fmax(fabs(yj), 1.0);
            y[j] += dj;
            yp[j] += dj;
            int st = cmp_dae_residual(d, 0.0, y, yp, r1);
            y[j] = yj;
            yp[j] = ypj;
            if (st) goto done;
            for (int i = 0; i < N; i++)
                if ((r1[i] - r0[i]) / dj != 0.0 && stamp[i] != j) {
                    stamp[i] = j;
                    cmp_pairs_push(&P, i, j);
                }
        }
        if (stamp[j] != j) cmp_pairs_push(&P, j, j); /* c_j on the diagonal */
        if (P.failed) goto done;
        qsort(P.r + cp[j], (size_t)(P.n - cp[j]), sizeof(int), cmp_int);
    }
    cp[N] = (int)P.n;
    nnz = (int)P.n;
    *colptr = cp;
    *rowind = P.r;
    cp = NULL;
    P.r = NULL;
done:
    free(Y);
    free(stamp);
    free(cp);
    cmp_pairs_free(&P);
    return nnz;
}

/* Non-constant M at q into Md (dense n x n), scattered for sparse systems. */
static int mass_dense(cmp_dae *d, double t, const double *q, double *Md)
{
    const braun_system *s = d->sys;
#ifdef BRAUN_MAX_SPARSE
    if (s->sparsity) {
        int st = cb(s->mass(t, q, d->Mvals, s->user));
        if (!st) scatter_M(s->sparsity, d->n, d->Mvals, Md);
        return st;
    }
#endif
    return cb(s->mass(t, q, Md, s->user));
}

/* Nonholonomic rows at (q, v): Φ_v, A_vv (dense p x n) and b_vv. */
static int nonholonomic_dense(cmp_dae *d, double t, const double *q, const double *v,
                              double *phi, double *A, double *bv)
{
    const braun_system *s = d->sys;
#ifdef BRAUN_MAX_SPARSE
    if (s->sparsity) {
        double *vals = d->Avals + s->sparsity->row_ptr[d->m];
        int st = cb(s->nonholonomic(t, q, v, phi, vals, bv, s->user));
        if (!st) scatter_A(s->sparsity, d->n, d->m, d->m + d->p, vals, A);
        return st;
    }
#endif
    return cb(s->nonholonomic(t, q, v, phi, A, bv, s->user));
}

static int differs(int k, const double *a, const double *b)
{
    for (int i = 0; i < k; i++)
        if (a[i] != b[i]) return 1;
    return 0;
}

int cmp_dae_pattern_struct(cmp_dae *d, const double *y0, const double *yp0, int **colptr,
                           int **rowind)
{
    const int n = d->n, m = d->m, p = d->p, mv = d->mv, N = d->N;
    const size_t nn = (size_t)n * n;
    const int varM = !(d->sys->flags & BRAUN_MASS_CONSTANT);
    const braun_system *s = d->sys;
    double *Y = malloc((size_t)N * 8 * sizeof(double));
    unsigned char *Amark = calloc((size_t)mv * n + nn + 1, 1);
    /* Scratch: Q twice, and for p > 0 or a varying M the callbacks' outputs
     * at the base and at a perturbed state. */
    const size_t nh = p > 0 ? 2 * ((size_t)p * n + 2 * (size_t)p) : 0;
    double *W = malloc((2 * (size_t)n + nh + (varM ? 2 * nn : 0) + 1) * sizeof(double));
    int *S = malloc(((size_t)n + 1) * sizeof(int));
    cmp_pairs P = {0, 0, NULL, NULL, 0};
    int nnz = -1;
    *colptr = *rowind = NULL;
    if (!Y || !Amark || !W || !S) goto done;
    unsigned char *Mmark = Amark + (size_t)mv * n;
    double *Q0 = W, *Q1 = W + n, *nb = Q1 + n, *np = nb + nh / 2, *M0 = W + 2 * n + nh,
           *M1 = M0 + nn;
    probe_states(N, y0, yp0, Y);
    for (int trial = 0; trial < 4; trial++) {
        double *q = Y + (size_t)trial * 2 * N, *v = q + n;
        d->mass_ready = 0;
        if (evaluate(d, 0.0, q, v, 1)) goto done;
        for (size_t e = 0; e < (size_t)mv * n; e++)
            if (d->A[e] != 0.0) Amark[e] = 1;
        for (size_t e = 0; e < nn; e++)
            if (d->M[e] != 0.0) Mmark[e] = 1;
        /* ∂Q/∂q, ∂Q/∂v: one coordinate at a time. */
        memcpy(Q0, d->Q, (size_t)n * sizeof(double));
        for (int j = 0; j < 2 * n; j++) {
            double *x = j < n ? q + j : v + (j - n);
            const double x0 = *x;
            *x += 1e-6 * fmax(fabs(x0), 1.0);
            int st = cb(s->forces(0.0, q, v, Q1, s->user));
            *x = x0;
            if (st) goto done;
            for (int i = 0; i < n; i++)
                if (Q1[i] != Q0[i]) cmp_pairs_push(&P, n + i, j);
        }
        /* ∂(M v')/∂q of a varying mass matrix. */
        if (varM) {
            if (mass_dense(d, 0.0, q, M0)) goto done;
            for (int j = 0; j < n; j++) {
                const double x0 = q[j];
                q[j] += 1e-6 * fmax(fabs(x0), 1.0);
                int st = mass_dense(d, 0.0, q, M1);
                q[j] = x0;
                if (st) goto done;
                for (int i = 0; i < n; i++)
                    if (differs(n, M0 + (size_t)i * n, M1 + (size_t)i * n)) cmp_pairs_push(&P, n + i, j);
            }
        }
        /* Nonholonomic rows: Φ_v (GGL), A_vv v' - b_vv (index-1) and
         * A_vvᵀλ (both) against each q_j and v_j. */
        if (p > 0) {
            double *phi0 = nb, *A0 = nb + p, *bv0 = A0 + (size_t)p * n;
            double *phi1 = np, *A1 = np + p, *bv1 = A1 + (size_t)p * n;
            if (nonholonomic_dense(d, 0.0, q, v, phi0, A0, bv0)) goto done;
            for (int j = 0; j < 2 * n; j++) {
                double *x = j < n ? q + j : v + (j - n);
                const double x0 = *x;
                *x += 1e-6 * fmax(fabs(x0), 1.0);
                int st = nonholonomic_dense(d, 0.0, q, v, phi1, A1, bv1);
                *x = x0;
                if (st) goto done;
                for (int k = 0; k < p; k++) {
                    const double *a0 = A0 + (size_t)k * n, *a1 = A1 + (size_t)k * n;
                    const int row = 2 * n + m + k;
                    if (d->index1 ? differs(n, a0, a1) || bv0[k] != bv1[k] : phi0[k] != phi1[k])
                        cmp_pairs_push(&P, row, j);
                    for (int i = 0; i < n; i++)
                        if (a0[i] != a1[i]) cmp_pairs_push(&P, n + i, j);
                }
            }
        }
        if (P.failed) goto done;
    }
    /* What follows from A's support S_k: a holonomic row's Hessian lives in
     * S_k x S_k (∂A_ki/∂q_j = ∂A_kj/∂q_i), and so do ∂b_q/∂q and b_qv's
     * derivatives. */
    for (int i = 0; i < n; i++) {
        cmp_pairs_push(&P, i, n + i);
        for (int j = 0; j < n; j++)
            if (Mmark[(size_t)i * n + j]) cmp_pairs_push(&P, n + i, n + j);
    }
    for (int k = 0; k < mv; k++) {
        int ns = 0;
        for (int j = 0; j < n; j++)
            if (Amark[(size_t)k * n + j]) S[ns++] = j;
        const int hol = k < m;
        for (int a = 0; a < ns; a++) {
            const int i = S[a];
            cmp_pairs_push(&P, n + i, 2 * n + k);                 /* -A_vᵀλ */
            cmp_pairs_push(&P, 2 * n + k, n + i);                 /* A v (GGL), A v' (index-1) */
            if (!hol) continue;
            cmp_pairs_push(&P, 2 * n + k, i);                     /* ∂(A_q v - b_q)/∂q */
            for (int b = 0; b < ns; b++) cmp_pairs_push(&P, n + i, S[b]); /* ∂(A_qᵀλ)/∂q */
            if (d->index1) continue;
            cmp_pairs_push(&P, i, 2 * n + mv + k);                /* A_qᵀμ */
            cmp_pairs_push(&P, 2 * n + mv + k, i);                /* Φ_q */
            for (int b = 0; b < ns; b++) cmp_pairs_push(&P, i, S[b]); /* ∂(A_qᵀμ)/∂q */
        }
        if (P.failed) goto done;
    }
    for (int i = 0; i < N; i++) cmp_pairs_push(&P, i, i);
    if (P.failed) goto done;
    nnz = cmp_csc_from_pairs(N, P.n, P.r, P.c, colptr, rowind, NULL);
done:
    d->mass_ready = 0;
    free(Y);
    free(Amark);
    free(W);
    free(S);
    cmp_pairs_free(&P);
    return nnz;
}

int cmp_dae_pattern(cmp_dae *d, const double *y0, const double *yp0, int **colptr,
                    int **rowind)
{
    if (d->N <= CMP_PATTERN_PROBE_MAX) return cmp_dae_pattern_probe(d, y0, yp0, colptr, rowind);
    return cmp_dae_pattern_struct(d, y0, yp0, colptr, rowind);
}
