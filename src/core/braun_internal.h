/* Private state of libbraun: the scratch carved from the caller's buffer. */
#ifndef BRAUN_INTERNAL_H
#define BRAUN_INTERNAL_H

#include "braun.h"
#include "braun_linalg.h"
#include "braun_linsolver.h"

/* Firmware builds with compile-time sizes run the built-in kernels only:
 * no backend dispatch, not even a branch. */
#if defined(BRAUN_FIXED_N) && !defined(BRAUN_NO_LINSOLVER)
#define BRAUN_NO_LINSOLVER
#endif

#define BRAUN_MAX_STAGES 7

typedef struct braun_priv {
    int n, m, p, rows;
    int need_fq;          /* separate C_q factorization (p > 0 and m > 0) */
    int R_is_constant;    /* R computed once in braun_data_init */
    int state_integrated; /* the state came from a step, not braun_set_state */
    /* Linear algebra: the built-in kernels (ls == NULL: chol, fv, fq below)
     * or a backend's table and state (braun_linsolver.h). */
    const braun_linsolver *ls;
    void *ls_state;
    /* Sparse system (sys.sparsity): the callbacks write compressed values
     * into Avals and Mvals; dense solvers get them scattered into A / M. */
    const braun_sparsity *sp;
    braun_real *Avals;    /* nnz = sp->row_ptr[rows] */
    braun_real *Mvals;    /* mass callback output: mass_count values */
    size_t mass_count;    /* n*n dense, sum of block^2 sparse */
    braun_real *Mdense;   /* n*n: M of a sparse system for a dense backend (else NULL) */
    int dense_A;          /* A holds the dense rows x n Jacobian */
    int rank[2];          /* numerical rank of C_v (slot 0) and C_q (slot 1) */
    braun_chol chol;      /* M = R^T R (R, reciprocal pivots, envelope) */
    braun_real *Q;        /* n forces */
    braun_real *atil;     /* n: R^-T Q, the weighted unconstrained acceleration */
    braun_real *z;        /* n: R q'' (weighted ideal acceleration) */
    braun_real *u;        /* n: C_v^+ (b_v - C_v atil) */
    braun_real *A;        /* rows*n: [A_q; A_vv] from the callbacks */
    braun_real *phi;      /* rows: [Φ_q; Φ_v] */
    braun_real *b;        /* m: b_q */
    braun_real *bv;       /* rows: [b_qv; b_vv], then the residual b_v - C_v atil */
    braun_real *ev;       /* rows: velocity-level error [Φ̇_q; Φ_v] */
    braun_real *ep;       /* m: Φ_q + h Φ̇_q */
    braun_real *dEdq, *dEdv, *ce, *tmp; /* n each */
    braun_qrcp fv;        /* C_v = A_v R^-1 */
    braun_qrcp fq;        /* C_q = A_q R^-1 when need_fq */
    /* Integrator scratch: states of length N = 2n + 1 ([q; v; ∫Ė]). */
    braun_real *y0, *ys, *y1, *yerr;
    braun_real *k[BRAUN_MAX_STAGES];
    braun_real *dq, *dv;  /* correction increments of the step (n each) */
} braun_priv;

/* Flags for braun__eval_ideal: which constraint values are wanted besides
 * the Jacobians and b_v (the corrections need Φ and b_q). */
enum { BRAUN_WANT_PHI = 1 };

/* Ideal (Udwadia–Kalaba) acceleration at (t,q,v): fills R, atil, fv, u, z and
 * vdot = R^-1 z (vdot may be NULL). With BRAUN_WANT_PHI also phi, b, ev. */
int braun__eval_ideal(braun_data *d, braun_real t, const braun_real *q,
                      const braun_real *v, unsigned want, braun_real *vdot);

/* Correction increments h·(Eq. 16 - v) and h·(Eq. 17 - ideal), with Eq. 20,
 * at the state of the last braun__eval_ideal(..., BRAUN_WANT_PHI, vdot):
 * dq, dv (n each), h the step. W is ∫Ė at that state. */
int braun__eval_corrections(braun_data *d, braun_real t, const braun_real *q,
                            const braun_real *v, braun_real W, braun_real h,
                            const braun_real *vdot, braun_real *dq,
                            braun_real *dv);

/* Evaluate and factor M at (t,q) unless it is constant (factored once). */
int braun__mass_update(braun_data *d, braun_real t, const braun_real *q);

/* Ė at a state (0 without BRAUN_ENERGY_INPUT). */
int braun__power(braun_data *d, braun_real t, const braun_real *q,
                 const braun_real *v, braun_real *Edot);

/* Record an error in d->error and return status. */
int braun__fail(braun_data *d, int status, const char *where, int index,
                int index2, double value, double t);

/* Map a callback's return code: 0 ok, > 0 recoverable, < 0 fatal. */
int braun__callback(braun_data *d, int rc, const char *where, braun_real t);

/* Check n outputs of a callback for NaN/Inf. */
int braun__check_finite(braun_data *d, int n, const braun_real *x,
                        const char *where, int cols, braun_real t);

static inline braun_priv *braun__priv(const braun_data *d)
{
    return (braun_priv *)d->priv;
}

/* ---- Linear algebra dispatch: built-in kernels or the backend table ---- */
#ifdef BRAUN_NO_LINSOLVER
#define BRAUN_LS(pv) 0
#else
#define BRAUN_LS(pv) ((pv)->ls != NULL)
#endif

/* x := R^-T b (x may be b). */
static inline void braun__solve_rt(const braun_priv *pv, const braun_real *b, braun_real *x)
{
    if (BRAUN_LS(pv)) pv->ls->solve_rt(pv->ls_state, b, x);
    else braun_chol_solve_rt_to(&pv->chol, b, x);
}
/* x := R^-1 b (x may be b). */
static inline void braun__solve_r(const braun_priv *pv, const braun_real *b, braun_real *x)
{
    if (BRAUN_LS(pv)) pv->ls->solve_r(pv->ls_state, b, x);
    else braun_chol_solve_r_to(&pv->chol, b, x);
}
/* y := R x. */
static inline void braun__mul_r(const braun_priv *pv, const braun_real *x, braun_real *y)
{
    if (BRAUN_LS(pv)) pv->ls->mul_r(pv->ls_state, x, y);
    else braun_chol_mul_r(&pv->chol, x, y);
}
/* slot 0: C_v (pv->fv), slot 1: C_q (pv->fq). */
static inline void braun__pinv(const braun_priv *pv, int slot, const braun_real *r,
                               braun_real *x)
{
    if (BRAUN_LS(pv)) pv->ls->pinv(pv->ls_state, slot, r, x);
    else braun_qrcp_pinv_apply(slot ? &pv->fq : &pv->fv, r, x);
}
static inline void braun__lsq(const braun_priv *pv, int slot, const braun_real *r,
                              braun_real *x, braun_real *resid)
{
    if (BRAUN_LS(pv)) pv->ls->lsq(pv->ls_state, slot, r, x, resid);
    else braun_qrcp_lsq(slot ? &pv->fq : &pv->fv, r, x, resid);
}
static inline void braun__null_project(const braun_priv *pv, int slot, braun_real *z)
{
    if (BRAUN_LS(pv)) pv->ls->null_project(pv->ls_state, slot, z);
    else braun_qrcp_null_project(slot ? &pv->fq : &pv->fv, z);
}

/* Row i of the constraint Jacobian times x (compressed or dense). */
static inline braun_real braun__row_dot(const braun_priv *pv, int i, const braun_real *x)
{
    if (pv->sp) {
        braun_real s = 0;
        for (int k = pv->sp->row_ptr[i]; k < pv->sp->row_ptr[i + 1]; k++)
            s += pv->Avals[k] * x[pv->sp->col[k]];
        return s;
    }
    return braun_dot(BRAUN_N(pv->n), pv->A + (size_t)i * (size_t)BRAUN_N(pv->n), x);
}

/* Scatter the compressed A values into the dense A (entries off the
 * pattern stay the zeros braun_data_init wrote). */
void braun__scatter_A(braun_priv *pv);

/* Where the constraint callbacks write A: row `row`'s first value. */
static inline braun_real *braun__A_out(const braun_priv *pv, int row)
{
    if (pv->sp) return pv->Avals + pv->sp->row_ptr[row];
    return pv->A + (size_t)row * (size_t)pv->n;
}

#endif
