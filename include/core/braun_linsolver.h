/*
 * libbraun — the linear-algebra backend table.
 *
 * Every evaluation of Eqs. 16, 17 and 20 needs the same few operations:
 * factor M = R^T R, solve with R and R^T, factor the weighted constraint
 * matrix C = A R^-1 with a rank-revealing method, and apply C^+ (minimum-norm
 * least squares) and the null-space projector N = I - C^+ C. libbraun's own
 * dense kernels are one such table (model.opt.linsolver == NULL selects
 * them, the default: allocation-free, libm only, state in the data block).
 * A backend is a table of those operations, so LAPACK or SuiteSparse can
 * take over for large mechanisms without the core depending on either: they
 * live in separate archives (libbraun_backends.a, built with BRAUN_LAPACK=1 /
 * BRAUN_SUITESPARSE=1) and are selected through braun_backends.h.
 *
 * Conventions (all vectors braun_real, lengths as stated):
 *  - A backend owns its state: either create() allocates it (host backends
 *    do) and destroy() frees it — braun_data_init calls create, after every
 *    check that can fail, and braun_data_release calls destroy — or, with
 *    create == NULL, it lives in the caller's data block: braun_data_size
 *    adds state_bytes(model) and braun_data_init calls bind on that memory
 *    (16-byte aligned).
 *  - "dense" backends (BRAUN_LS_DENSE) always see dense row-major A
 *    (rows x n) and M (n x n): the core scatters a sparse system's
 *    compressed values for them. Other backends see the system's own format:
 *    compressed A (sys.sparsity->row_ptr / col order) and, with a sparsity,
 *    block-diagonal M values (block after block, each row-major).
 *  - slot 0 is C_v = [A_q; A_vv] R^-1 (all m + p rows), slot 1 is
 *    C_q = A_q R^-1 (first m rows; only used when m > 0 and p > 0).
 */
#ifndef BRAUN_LINSOLVER_H
#define BRAUN_LINSOLVER_H

#include "braun.h"

#ifdef __cplusplus
extern "C" {
#endif

enum braun_linsolver_flags {
    BRAUN_LS_DENSE = 1u << 0,        /* wants dense A and M */
    BRAUN_LS_NEEDS_SPARSITY = 1u << 1 /* refuses systems without sys.sparsity */
};

struct braun_linsolver {
    const char *name; /* "lapack", "suitesparse", ... */
    unsigned flags;   /* braun_linsolver_flags */
    /* Allocate the state for this model (sizes, sparsity, options).
     * BRAUN_OK or an error status (BRAUN_ERR_ARGUMENT, BRAUN_ERR_BUFFER for
     * out of memory, BRAUN_ERR_SIZE). */
    int (*create)(void **state, const braun_model *model);
    void (*destroy)(void *state);
    /* Factor M (format above) = R^T R. Status as braun_chol_factor:
     * BRAUN_ERR_MASS_NOT_SYMMETRIC (|M_ij - M_ji| > sym_tol·sqrt(|M_ii M_jj|)) or
     * BRAUN_ERR_MASS_NOT_SPD (a pivot j not above n·ε·|M_jj|, its own
     * diagonal entry: a verdict no change of a coordinate's unit changes),
     * with the entry in *bad_i, *bad_j, *bad_value (coordinates of the full
     * matrix). */
    int (*factor_mass)(void *state, const braun_real *M, braun_real sym_tol,
                       int *bad_i, int *bad_j, braun_real *bad_value);
    /* x := R^-T b, x := R^-1 b, y := R x (n entries; x may alias b, y not x). */
    void (*solve_rt)(void *state, const braun_real *b, braun_real *x);
    void (*solve_r)(void *state, const braun_real *b, braun_real *x);
    void (*mul_r)(void *state, const braun_real *x, braun_real *y);
    /* Form C = A R^-1 from the first `rows` rows of A (format above) and
     * factor it with relative rank tolerance tol (a direction whose pivot or
     * singular-value estimate is <= tol times the largest counts as
     * dependent). If atil and resid are not NULL: resid[i] -= (C atil)_i.
     * Returns the numerical rank (>= 0) or an error status (< 0). */
    int (*factor_c)(void *state, int slot, int rows, const braun_real *A,
                    braun_real tol, const braun_real *atil, braun_real *resid);
    /* x[n] := C^+ r (r: rows entries, not modified). */
    void (*pinv)(void *state, int slot, const braun_real *r, braun_real *x);
    /* The same and *resid_norm := ||r - C C^+ r||_2. */
    void (*lsq)(void *state, int slot, const braun_real *r, braun_real *x,
                braun_real *resid_norm);
    /* z[n] := z - C^+ C z. */
    void (*null_project)(void *state, int slot, braun_real *z);
    /* Optional (NULL when create is used): state in the data block. */
    size_t (*state_bytes)(const braun_model *model);
    int (*bind)(void **state, void *memory, const braun_model *model);
    /* Optional: where the mass callback may write M (dense format) for
     * factor_mass to factor in place; NULL: the core keeps its own copy. */
    braun_real *(*mass_buffer)(void *state);
    /* Optional: the rank rule of the next factor_c of a slot (docs/method.md,
     * "Rank decisions near singular configurations"): beyond its first
     * `keep` pivots a factorization counts a direction only when its pivot
     * (or singular-value estimate) also exceeds tol_new times the largest,
     * and it counts at most `cap` (keep = cap = rows: the plain tolerance).
     * The core keeps a rank across a step's stages (cap) and lets it rise
     * from one step to the next only on clear evidence (keep, tol_new), so
     * that rows that are exactly dependent on the constraint manifold, but
     * not quite at states the stages reach off it, keep being dropped.
     * NULL: the backend decides by tol alone. */
    void (*rank_rule)(void *state, int slot, int keep, int cap, braun_real tol_new);
    /* Optional: soft directions of slot's last factorization (docs/method.md,
     * "Redundant rows through a singular configuration"): soft_find finds
     * the right singular vectors s_c of C whose singular values σ_c are kept
     * by the rank decision but below 10λ, λ = rel·‖C‖, and returns their
     * number (0: none, the common case — it should then cost next to
     * nothing); soft_project then sets y := Σ_c w_c s_c (s_cᵀ x) (n
     * entries, y not aliasing x) with w_c = λ⁴/(σ_c⁴ + λ⁴) · z⁴/(1 + z⁴),
     * z = rate/σ_c (the second factor 1 when rate <= 0). NULL: the core
     * does without them. */
    int (*soft_find)(void *state, int slot, braun_real rel);
    void (*soft_project)(void *state, int slot, const braun_real *x, braun_real *y,
                         braun_real rate);
    /* Optional: the round-off floor of the slot's next pinv and lsq
     * right-hand sides (docs/method.md, "The round-off floor of the
     * corrections"): an absolute level (>= 0) below which their
     * inconsistency, the part of r outside the range of C that only
     * rank-deficient factorizations leave, is the rounding of the
     * computation that produced r, not data. A backend that computes the
     * least-squares part of C^+ r by iteration may stop there; the
     * consistent part stays exact. factor_c resets it to 0 (every solve
     * exact), as does a call with 0. The core sets it around the position
     * correction's lsq and the velocity correction's pinv at a
     * rank-deficient factorization, and only there.
     * NULL: the backend's solves are exact anyway (the built-in kernels,
     * LAPACK: a complete orthogonal decomposition). */
    void (*rhs_floor)(void *state, int slot, braun_real floor);
    /* Optional: the next factor_c calls are a step's later stages (later =
     * 1) or a first stage (0). At a later stage a rank-deficient
     * factorization should set aside the rows the slot's first-stage one set
     * aside, while the others stay clearly independent (their pivots above
     * the rank rule's tol_new): the stages, off the manifold by the step's
     * own error, find those rows dependent only to that error, and another
     * choice of rows takes another rank-k approximation of C, one that
     * differs by that error, so the integrator loses its order
     * (docs/method.md, "Rank decisions near singular configurations").
     * NULL: the backend keeps no order (SuiteSparse's fixed row order keeps
     * the rows anyway). */
    void (*stage_order)(void *state, int later);
};

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_LINSOLVER_H */
