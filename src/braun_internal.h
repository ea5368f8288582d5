/* Private state of libbraun: the scratch carved from the caller's buffer. */
#ifndef BRAUN_INTERNAL_H
#define BRAUN_INTERNAL_H

#include "braun.h"
#include "braun_linalg.h"

#define BRAUN_MAX_STAGES 7

typedef struct braun_priv {
    int n, m, p, rows;
    int need_fq;          /* separate C_q factorization (p > 0 and m > 0) */
    int R_is_constant;    /* R computed once in braun_data_init */
    int state_integrated; /* the state came from a step, not braun_set_state */
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

#endif
