/* libbraun's own dense kernels as a linear-solver backend
 * (braun_linsolver.h): Cholesky M = RᵀR (braun_chol.c) and the
 * rank-revealing pseudoinverse of C = A R⁻¹ by column-pivoted QR of Cᵀ
 * (braun_qrcp.c). The default backend: allocation-free, its state lives in
 * the data block, and the mass callback writes M straight into R, factored
 * in place. Its operations are inline here so that the core calls them
 * directly when the model uses this backend (BRAUN_LS_CALL in
 * braun_internal.h); the table in braun_dense.c holds the same functions. */
#ifndef BRAUN_DENSE_H
#define BRAUN_DENSE_H

#include "braun_linalg.h"
#include "braun_linsolver.h"

typedef struct braun_dense {
    int n;
    braun_chol chol; /* M = R^T R */
    braun_qrcp fv;   /* slot 0: C_v = A_v R^-1, all rows */
    braun_qrcp fq;   /* slot 1: C_q = A_q R^-1 when m > 0 and p > 0 */
    /* The rank rule of each slot's next factorization (rank_rule). */
    int keep[2], cap[2];
    braun_real tol_new[2];
    braun_real tol[2]; /* the last factor_c's tolerance */
    int stage_order; /* a step's later stages: try the last column order */
} braun_dense;

static inline braun_dense *braun__dense(void *state) { return (braun_dense *)state; }
static inline braun_qrcp *braun__dense_slot(void *state, int slot)
{
    return slot ? &braun__dense(state)->fq : &braun__dense(state)->fv;
}

/* A new run (braun_set_state): no last factorization to follow, as after
 * braun_data_init. A run's first step took the Gram path, or the last
 * run's column order, from the factorization the run before left, and a
 * fresh data the pivoted QR: the same run differed in its rounding from
 * its first step (the four-bar, RK4 h = 1e-2; docs/robustness.md promises
 * the same trajectory for the same input). */
static inline void braun__dense_new_run(void *state)
{
    braun_dense *s = braun__dense(state);
    braun_qrcp *slots[2] = {&s->fv, &s->fq};
    for (int k = 0; k < 2; k++) {
        slots[k]->rank = 0;
        slots[k]->nsoft = 0;
        slots[k]->dmin = 0;
        slots[k]->soft_lam = 0;
        slots[k]->r00 = 0;
        slots[k]->gram = 0;
        slots[k]->norms_given = 0;
    }
    s->stage_order = 0;
}

static inline braun_real *braun__dense_mass_buffer(void *state) { return braun__dense(state)->chol.R; }

static inline int braun__dense_factor_mass(void *state, const braun_real *M, braun_real sym_tol, int *bad_i,
                             int *bad_j, braun_real *bad_value)
{
    return braun_chol_factor(&braun__dense(state)->chol, M, sym_tol, bad_i, bad_j, bad_value);
}

/* A diagonal R (diagonal M) is solved inline, without the call. */
static inline void braun__dense_solve_rt(void *state, const braun_real *b, braun_real *x)
{
    const braun_chol *c = &braun__dense(state)->chol;
    if (c->diagonal) braun_chol_solve_diag(c, b, x);
    else braun_chol_solve_rt_to(c, b, x);
}

static inline void braun__dense_solve_r(void *state, const braun_real *b, braun_real *x)
{
    const braun_chol *c = &braun__dense(state)->chol;
    if (c->diagonal) braun_chol_solve_diag(c, b, x);
    else braun_chol_solve_r_to(c, b, x);
}

static inline void braun__dense_mul_r(void *state, const braun_real *x, braun_real *y)
{
    const braun_chol *c = &braun__dense(state)->chol;
    if (c->diagonal) braun_chol_mul_diag(c, x, y);
    else braun_chol_mul_r(c, x, y);
}

/* Rows up to this length have their column scales and ã in locals. */
#define BRAUN_FORM_LOCAL 16

/* C = A R^-1 row by row (row_i(C) = R^-T A_i^T), resid -= C atil and the
 * rows' squared norms (the factorization's first pass, f->norms_given)
 * fused into the same pass. */
static inline void braun__dense_form_c(braun_dense *s, braun_qrcp *f, int rows, const braun_real *A,
                                       const braun_real *atil, braun_real *resid)
{
    const int n = BRAUN_N(s->n);
    braun_real *C = f->a;
    if (s->chol.diagonal) {
        /* Diagonal M (point masses, centroidal frames): C = A R^-1 is a
         * column scaling, the same products as the solve without its calls. */
        const braun_real *restrict dinv = s->chol.dinv;
        if (resid) {
            /* Distinct arrays: the caller's scratch, never each other. */
            const braun_real *restrict at = atil;
            braun_real *restrict rs = resid, *restrict nw = f->work;
            /* braun_dot(n, ci, atil) and the row's squared norm (the
             * factorization's first pass) in the same pass; one dispatch on
             * n for all rows (braun_linalg.h). */
#define FORM_ROWS(N, UNROLL, DINV, ATIL)                         \
    for (int i = 0; i < rows; i++) {                             \
        braun_real *restrict ci = C + (size_t)i * (size_t)(N);   \
        const braun_real *restrict ai = A + (size_t)i * (size_t)(N); \
        braun_real dot = 0, nn = 0;                              \
        UNROLL for (int j = 0; j < (N); j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            ci[j] = ai[j] * (DINV)[j];                           \
            dot += ci[j] * (ATIL)[j];                            \
            if (BRAUN_FUSED_NORMS) nn += ci[j] * ci[j];          \
        }                                                        \
        rs[i] -= dot;                                            \
        if (BRAUN_FUSED_NORMS) nw[i] = nn;                       \
    }
/* Short rows (every dispatched length): the scales and ã copied to locals
 * first, which the compiler keeps in registers for all rows (through the
 * pointers it loads them again after every store: −280 instructions per
 * corrected slider-crank step on the M4F). */
#define FORM_BODY(N, UNROLL)                                     \
    if ((N) <= BRAUN_FORM_LOCAL) {                               \
        braun_real dl_[BRAUN_FORM_LOCAL], al_[BRAUN_FORM_LOCAL]; \
        UNROLL for (int j = 0; j < (N); j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            dl_[j] = dinv[j];                                    \
            al_[j] = at[j];                                      \
        }                                                        \
        FORM_ROWS(N, UNROLL, dl_, al_)                           \
    } else {                                                     \
        FORM_ROWS(N, UNROLL, dinv, at)                           \
    }
            BRAUN_SMALL_DISPATCH(n, FORM_BODY)
#undef FORM_BODY
#undef FORM_ROWS
        } else {
            for (int i = 0; i < rows; i++)
                braun_chol_solve_diag(&s->chol, A + (size_t)i * (size_t)n, C + (size_t)i * (size_t)n);
        }
    } else {
        /* Each row c_i = R⁻ᵀ a_i: at a short length the compiler knows, the
         * triangle unrolled in place (BRAUN_CHOL_RT_WHOLE, as braun_chol.c's
         * solve), with the row's dot product and squared norm. */
        const braun_real *restrict R = s->chol.R, *restrict rdinv = s->chol.dinv;
#define FORM_M_BODY(N, UNROLL)                                                          \
    for (int i = 0; i < rows; i++) {                                                    \
        braun_real *restrict ci = C + (size_t)i * (size_t)(N);                          \
        const braun_real *restrict ai = A + (size_t)i * (size_t)(N);                    \
        if (BRAUN_SMALL_CONST(N)) {                                                     \
            BRAUN_CHOL_RT_WHOLE(N, UNROLL, R, rdinv, ai, ci)                            \
        } else {                                                                        \
            braun_chol_solve_rt_to(&s->chol, ai, ci);                                   \
        }                                                                               \
        if (resid) {                                                                    \
            braun_real dot = 0, nn = 0;                                                 \
            UNROLL for (int j = 0; j < (N); j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
                dot += ci[j] * atil[j];                                                 \
                if (BRAUN_FUSED_NORMS) nn += ci[j] * ci[j];                             \
            }                                                                           \
            resid[i] -= dot;                                                            \
            if (BRAUN_FUSED_NORMS) f->work[i] = nn;                                     \
        }                                                                               \
    }
        BRAUN_SMALL_DISPATCH(n, FORM_M_BODY)
#undef FORM_M_BODY
    }
    if (BRAUN_FUSED_NORMS) f->norms_given = resid != NULL;
}

/* C, then its factorization. Where the slot's last factorization (this
 * step's stage before, or the last step's) had full rank and no pivot
 * below the gate — BRAUN_ORDER_GATE of the largest column norm, or 10
 * rank tolerances if that is larger: far from every rank and
 * soft-direction decision — the rank is known and C is factored without
 * pivoting, accepted if every pivot clears that gate again:
 *   1. through its Gram matrix G = C Cᵀ = L D Lᵀ (braun_qrcp_factor_gram,
 *      src/core/braun_qrcp_gram.c) where, besides, every pivot is above
 *      BRAUN_GRAM_GATE² of its row's G_ii: independent dot products and
 *      one division per row instead of the QR's chain of norms, square
 *      roots and reflections (−30 % time per corrected slider-crank step on
 *      the host; docs/performance.md, Optimisations, item 16);
 *   2. else, at a step's later stages, by QR in the last column order
 *      (braun_qrcp_factor_ordered) where only that second test failed;
 * else C (formed again if 2 spent it) by the pivoted QR with the rank rule.
 * Between singular neighbourhoods that is every stage but a few. */
#define BRAUN_ORDER_GATE BRAUN_R(1e-2)
/* The Gram path squares the condition number of the row-equilibrated C,
 * κ̃ (docs/method.md, "The Gram path"): a pivot above gate² of its row's
 * G_ii keeps κ̃ ≲ √rows/gate, and the solves within ≈ ε·κ̃² of C⁺ — a
 * factor ≲ 20 above the QR's ε·κ̃ at the slider-crank's 5 rows. */
#ifndef BRAUN_GRAM_GATE
#define BRAUN_GRAM_GATE BRAUN_R(1e-1)
#endif
/* The rank rule's tolerance for a new pivot: never below the plain one. */
static inline braun_real braun__dense_tol_new(const braun_dense *s, int slot, braun_real tol)
{
    return s->tol_new[slot] > tol ? s->tol_new[slot] : tol;
}

static inline int braun__dense_factor_c(void *state, int slot, int rows, const braun_real *A, braun_real tol,
                          const braun_real *atil, braun_real *resid)
{
    braun_dense *s = braun__dense(state);
    braun_qrcp *f = braun__dense_slot(state, slot);
    const braun_real tol_new = braun__dense_tol_new(s, slot, tol);
    const braun_real gate = 10 * tol_new > BRAUN_ORDER_GATE ? 10 * tol_new : BRAUN_ORDER_GATE;
    s->tol[slot] = tol;
    /* The last factorization (read before C overwrites it) had full rank
     * and its smallest pivot cleared the gate too. */
    const int known = s->cap[slot] >= rows && f->rank == rows && f->dmin > gate * f->r00;
    braun__dense_form_c(s, f, rows, A, atil, resid);
    if (known) {
        const int gram = braun_qrcp_factor_gram(f, gate, BRAUN_GRAM_GATE);
        if (gram >= 0) return rows;
        if (gram == -2 && s->stage_order) {
            const int rank = braun_qrcp_factor_ordered(f, gate);
            if (rank >= 0) return rank;
            braun__dense_form_c(s, f, rows, A, NULL, NULL);
        }
    }
    return braun_qrcp_factor_rule(f, tol, tol_new, s->keep[slot], s->cap[slot], s->stage_order);
}

/* The next factorizations are a step's later stages (1) or its first (0). */
static inline void braun__dense_stage_order(void *state, int later)
{
    braun__dense(state)->stage_order = later;
}

static inline void braun__dense_rank_rule(void *state, int slot, int keep, int cap,
                                          braun_real tol_new)
{
    braun_dense *s = braun__dense(state);
    s->keep[slot] = keep;
    s->cap[slot] = cap;
    s->tol_new[slot] = tol_new;
}

static inline void braun__dense_pinv(void *state, int slot, const braun_real *r, braun_real *x)
{
    braun_qrcp_pinv_apply(braun__dense_slot(state, slot), r, x);
}

static inline void braun__dense_pinv2(void *state, int slot, const braun_real *r1, const braun_real *r2,
                                      braun_real *x1, braun_real *x2)
{
    braun_qrcp_pinv2(braun__dense_slot(state, slot), r1, r2, x1, x2);
}

static inline void braun__dense_lsq(void *state, int slot, const braun_real *r, braun_real *x,
                      braun_real *resid_norm)
{
    braun_qrcp_lsq(braun__dense_slot(state, slot), r, x, resid_norm);
}

static inline int braun__dense_soft_find(void *state, int slot, braun_real rel)
{
    braun_qrcp *f = braun__dense_slot(state, slot);
    /* The common case inline: no diagonal entry below the gate. */
    if (f->rank == 0 || !(f->dmin < BRAUN_SOFT_GATE * rel * f->r00)) {
        f->nsoft = 0;
        return 0;
    }
    /* A Gram factorization is never this close to a rank decision with the
     * default soft_tol; with a larger one, C (still in f->a) is factored
     * by QR for the search. */
    if (f->gram) {
        const braun_dense *s = braun__dense(state);
        (void)braun_qrcp_factor_rule(f, s->tol[slot], braun__dense_tol_new(s, slot, s->tol[slot]),
                                     s->keep[slot], s->cap[slot], 0);
    }
    return braun_qrcp_soft_find(f, rel);
}

static inline void braun__dense_soft_project(void *state, int slot, const braun_real *x, braun_real *y,
                                             braun_real rate)
{
    braun_qrcp_soft_project(braun__dense_slot(state, slot), x, y, rate);
}

static inline void braun__dense_null_project(void *state, int slot, braun_real *z)
{
    braun_qrcp_null_project(braun__dense_slot(state, slot), z);
}

#endif
