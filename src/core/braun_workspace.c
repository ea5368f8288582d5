/* Data block: carve state and scratch from one caller buffer; set state. */
#include <stdint.h>

#include "braun_internal.h"

#define BRAUN_ALIGN 16u

/* The model's backend; none in a build without dispatch (firmware). */
static const braun_linsolver *model_linsolver(const braun_model *model)
{
#ifndef BRAUN_NO_LINSOLVER
    return model->opt.linsolver;
#else
    (void)model;
    return NULL;
#endif
}

/* Walk the layout once: with base == NULL only count bytes. */
static size_t layout(const braun_model *model, unsigned char *base,
                     braun_priv *pv, braun_real **q, braun_real **v)
{
    const braun_system *s = &model->sys;
    const int n = s->n, m = s->m, p = s->p, rows = m + p;
    const int N = 2 * n + 1;
    const int need_fq = p > 0 && m > 0;
    const braun_sparsity *sp = s->sparsity;
    const braun_linsolver *ls = model_linsolver(model);
    /* The built-in kernels and dense backends work on dense A and M. */
    const int dense = !ls || (ls->flags & BRAUN_LS_DENSE);
    const size_t nn = (size_t)n * (size_t)n;
    size_t mass_count = nn, nnz = 0;
    if (sp) {
        mass_count = 0;
        for (int k = 0; k < sp->nblocks; k++) mass_count += (size_t)sp->block[k] * (size_t)sp->block[k];
        nnz = (size_t)sp->row_ptr[rows];
    }
    size_t off = (sizeof(braun_priv) + BRAUN_ALIGN - 1) / BRAUN_ALIGN * BRAUN_ALIGN;
    braun_real *r = base ? (braun_real *)(void *)(base + off) : NULL;
    size_t nr = 0;
#define TAKE(ptr, count)                                   \
    do {                                                   \
        if (base) (ptr) = r + nr;                          \
        nr += (size_t)(count);                             \
    } while (0)
    braun_real *dummy = NULL;
    braun_real *fvr = NULL, *fqr = NULL, *cholr = NULL;
    if (!base) pv = NULL;
#define P(field) (*(pv ? &pv->field : &dummy))
    TAKE(*(q ? q : &dummy), n);
    TAKE(*(v ? v : &dummy), n);
    TAKE(P(Q), n);
    TAKE(P(atil), n);
    TAKE(P(z), n);
    TAKE(P(u), n);
    TAKE(P(A), dense ? (size_t)rows * (size_t)n : 0);
    TAKE(P(Avals), nnz);
    /* Mass callback output: the built-in Cholesky factors in place (in R);
     * a backend, or a sparse system, needs its own buffer. */
    TAKE(P(Mvals), (ls || sp) ? mass_count : 0);
    /* A dense backend given a sparse system gets M scattered here. */
    TAKE(P(Mdense), (ls && dense && sp) ? nn : 0);
    TAKE(P(phi), rows);
    TAKE(P(b), m);
    TAKE(P(bv), rows);
    TAKE(P(ev), rows);
    TAKE(P(ep), m);
    TAKE(P(dEdq), n);
    TAKE(P(dEdv), n);
    TAKE(P(ce), n);
    TAKE(P(tmp), n);
    TAKE(P(y0), N);
    TAKE(P(ys), N);
    TAKE(P(y1), N);
    TAKE(P(yerr), N);
    for (int i = 0; i < BRAUN_MAX_STAGES; i++) TAKE(P(k[i]), N);
    TAKE(P(dq), n);
    TAKE(P(dv), n);
    if (!ls) {
        TAKE(cholr, BRAUN_CHOL_REALS(n));
        TAKE(fvr, braun_qrcp_reals(n, rows));
        if (need_fq) TAKE(fqr, braun_qrcp_reals(n, m));
    }
#undef P
#undef TAKE
    off += nr * sizeof(braun_real);
    off = (off + BRAUN_ALIGN - 1) / BRAUN_ALIGN * BRAUN_ALIGN;
    size_t ni = ls ? 0
                   : BRAUN_CHOL_INTS(n) + braun_qrcp_ints(rows) + (need_fq ? braun_qrcp_ints(m) : 0);
    if (base) {
        int *ints = (int *)(void *)(base + off);
        if (!ls) {
            braun_chol_bind(&pv->chol, n, cholr, ints);
            ints += BRAUN_CHOL_INTS(n);
            braun_qrcp_bind(&pv->fv, n, rows, fvr, ints);
            if (need_fq) braun_qrcp_bind(&pv->fq, n, m, fqr, ints + rows);
        }
        pv->ls = ls;
        pv->ls_state = NULL;
        pv->sp = sp;
        pv->mass_count = mass_count;
        pv->dense_A = dense;
        /* Buffers this configuration does not use point nowhere. */
        pv->Mvals = (ls || sp) ? pv->Mvals : NULL;
        pv->Mdense = (ls && dense && sp) ? pv->Mdense : NULL;
        pv->A = dense ? pv->A : NULL;
        pv->Avals = sp ? pv->Avals : NULL;
        pv->rank[0] = rows;
        pv->rank[1] = m;
        pv->n = n;
        pv->m = m;
        pv->p = p;
        pv->rows = rows;
        pv->need_fq = need_fq;
        pv->R_is_constant = 0;
        pv->state_integrated = 0;
    }
    off += ni * sizeof(int);
    return off;
}

/* Dense kernels index n x n and rows x n arrays: bounded sizes. */
static int dense_size_ok(const braun_model *model)
{
    const braun_system *s = &model->sys;
#ifndef BRAUN_NO_LINSOLVER
    const braun_linsolver *ls = model->opt.linsolver;
    if (ls && !(ls->flags & BRAUN_LS_DENSE)) return 1;
#endif
    return s->n <= BRAUN_MAX_DENSE && s->m + s->p <= 2 * BRAUN_MAX_DENSE;
}

size_t braun_data_size(const braun_model *model)
{
    if (!model || model->sys.n <= 0 || !dense_size_ok(model)) return 0;
    /* + alignment slack: the caller's buffer may start anywhere. */
    return layout(model, NULL, NULL, NULL, NULL) + BRAUN_ALIGN;
}

int braun__fail(braun_data *d, int status, const char *where, int index,
                int index2, double value, double t)
{
    d->error.status = status;
    d->error.where = where;
    d->error.index = index;
    d->error.index2 = index2;
    d->error.value = value;
    d->error.t = t;
    return status;
}

int braun__callback(braun_data *d, int rc, const char *where, braun_real t)
{
    if (rc == 0) return BRAUN_OK;
    return braun__fail(d, rc < 0 ? BRAUN_ERR_CALLBACK : BRAUN_ERR_CALLBACK_RECOVERABLE,
                       where, rc, -1, (double)rc, (double)t);
}

int braun__check_finite(braun_data *d, int n, const braun_real *x,
                        const char *where, int cols, braun_real t)
{
    if (braun_all_finite(n, x)) return BRAUN_OK;
    for (int i = 0; i < n; i++)
        if (!braun_is_finite(x[i]))
            return braun__fail(d, BRAUN_ERR_NONFINITE, where,
                               cols > 0 ? i / cols : i, cols > 0 ? i % cols : -1,
                               (double)x[i], (double)t);
    return BRAUN_OK;
}

/* A sparse system's mass blocks into the dense n x n matrix M. */
static void scatter_mass_blocks(const braun_sparsity *sp, int n, const braun_real *blocks,
                                braun_real *M)
{
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++) M[i] = 0;
    int off = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        const int b = sp->block[k];
        for (int i = 0; i < b; i++)
            for (int j = 0; j < b; j++)
                M[(size_t)(off + i) * (size_t)n + (size_t)(off + j)] = *blocks++;
        off += b;
    }
}

void braun__scatter_A(braun_priv *pv)
{
    const braun_sparsity *sp = pv->sp;
    const size_t n = (size_t)pv->n;
    for (int i = 0; i < pv->rows; i++)
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++)
            pv->A[(size_t)i * n + (size_t)sp->col[k]] = pv->Avals[k];
}

static int factor_mass(braun_data *d, braun_real t, const braun_real *q)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = pv->n;
    braun_real tol = d->model->opt.symmetry_tol > 0 ? d->model->opt.symmetry_tol
                                                   : (braun_real)1e3 * BRAUN_EPS;
    int bi = -1, bj = -1, st;
    braun_real bad = 0;
    /* The callback's output: in place in R (built-in, dense), else Mvals. */
    braun_real *out = pv->Mvals ? pv->Mvals : pv->chol.R;
    st = braun__callback(d, s->mass(t, q, out, s->user), "mass", t);
    if (st) return st;
    st = braun__check_finite(d, (int)pv->mass_count, out, "mass", pv->sp ? 0 : n, t);
    if (st) return st;
    const braun_real *M = out;
    if (pv->sp && pv->dense_A) {
        /* Dense solver, sparse system: scatter the blocks. */
        braun_real *dst = BRAUN_LS(pv) ? pv->Mdense : pv->chol.R;
        scatter_mass_blocks(pv->sp, n, out, dst);
        M = dst;
    }
    if (BRAUN_LS(pv)) st = pv->ls->factor_mass(pv->ls_state, M, tol, &bi, &bj, &bad);
    else st = braun_chol_factor(&pv->chol, M, tol, &bi, &bj, &bad);
    d->stats.mass_factorizations++;
    if (st) return braun__fail(d, st, "mass", bi, bj, (double)bad, (double)t);
    return BRAUN_OK;
}

/* Factor M now if it is constant; otherwise at every evaluation. */
int braun__mass_update(braun_data *d, braun_real t, const braun_real *q)
{
    braun_priv *pv = braun__priv(d);
    if (pv->R_is_constant) return BRAUN_OK;
    return factor_mass(d, t, q);
}

int braun_data_init(braun_data *d, const braun_model *model, void *buffer,
                    size_t bytes)
{
    if (!d || !model || !buffer) return BRAUN_ERR_ARGUMENT;
    size_t need = braun_data_size(model);
    if (need == 0) return BRAUN_ERR_SIZE;
    uintptr_t addr = (uintptr_t)buffer;
    size_t shift = (size_t)((BRAUN_ALIGN - addr % BRAUN_ALIGN) % BRAUN_ALIGN);
    if (bytes < need) return BRAUN_ERR_BUFFER;
    unsigned char *base = (unsigned char *)buffer + shift;
    braun_priv *pv = (braun_priv *)(void *)base;
    d->model = model;
    d->priv = pv;
    d->t = 0;
    d->work_in = 0;
    d->E0 = 0;
    d->has_E0 = 0;
    d->stats = (braun_stats){0, 0, 0, 0, 0, 0, 0};
    d->error = (braun_error_info){BRAUN_OK, NULL, -1, -1, 0, 0};
    layout(model, base, pv, &d->q, &d->v);
    for (int i = 0; i < model->sys.n; i++) d->q[i] = d->v[i] = 0;
    /* Off-pattern entries of a scattered A stay zero from here on. */
    if (pv->sp && pv->dense_A)
        for (size_t i = 0; i < (size_t)pv->rows * (size_t)pv->n; i++) pv->A[i] = 0;
#ifndef BRAUN_NO_LINSOLVER
    if (pv->ls) {
        if ((pv->ls->flags & BRAUN_LS_NEEDS_SPARSITY) && !pv->sp)
            return braun__fail(d, BRAUN_ERR_ARGUMENT, "linear solver needs a sparsity", -1, -1, 0, 0);
        int st = pv->ls->create(&pv->ls_state, model);
        if (st) return braun__fail(d, st, "linear solver create", -1, -1, 0, 0);
    }
#else
    if (model->opt.linsolver)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "linear solver (not in this build)", -1, -1, 0, 0);
#endif
    if ((model->opt.corrections & BRAUN_CORRECT_ENERGY) && !model->sys.energy)
        return braun__fail(d, BRAUN_ERR_NO_ENERGY_LAW, "options", -1, -1, 0, 0);
    if (model->sys.flags & BRAUN_MASS_CONSTANT) {
        int st = factor_mass(d, 0, d->q);
        if (st) return st;
        pv->R_is_constant = 1;
    }
    return BRAUN_OK;
}

void braun_data_release(braun_data *d)
{
    if (!d || !d->priv) return;
    braun_priv *pv = braun__priv(d);
#ifndef BRAUN_NO_LINSOLVER
    if (pv->ls && pv->ls_state) pv->ls->destroy(pv->ls_state);
#endif
    pv->ls_state = NULL;
}

int braun_set_state(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v)
{
    if (!d || !d->priv || !q || !v) return BRAUN_ERR_ARGUMENT;
    const int n = d->model->sys.n;
    if (!braun_is_finite(t)) return braun__fail(d, BRAUN_ERR_NONFINITE, "state t", -1, -1, (double)t, (double)t);
    int st = braun__check_finite(d, n, q, "state q", 0, t);
    if (st) return st;
    st = braun__check_finite(d, n, v, "state v", 0, t);
    if (st) return st;
    for (int i = 0; i < n; i++) {
        d->q[i] = q[i];
        d->v[i] = v[i];
    }
    d->t = t;
    d->work_in = 0;
    braun__priv(d)->state_integrated = 0;
    d->has_E0 = 0;
    d->E0 = 0;
    if (d->model->sys.energy) {
        braun_real E;
        st = braun_energy(d, t, q, v, &E);
        if (st) return st;
        d->E0 = E;
        d->has_E0 = 1;
    }
    return BRAUN_OK;
}
