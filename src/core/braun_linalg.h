/*
 * Private dense linear-algebra kernels of libbraun (no allocation; all
 * scratch is passed in). Matrices are row-major unless stated otherwise.
 */
#ifndef BRAUN_LINALG_H
#define BRAUN_LINALG_H

#include "braun.h"
#include "braun_math.h"

/* ---- Compile-time sizes (firmware builds) --------------------------------
 * An image that runs one model may build the library with
 * -DBRAUN_FIXED_N=n (coordinates) and -DBRAUN_FIXED_ROWS=m+p (constraint
 * rows): the sizes of the small dense kernels become constants the compiler
 * unrolls (best with -O3 -flto). Same results bit for bit; measured on the
 * emulated Cortex-M4F in docs/firmware.md. braun_model_init refuses every
 * other size with BRAUN_ERR_SIZE. */
#ifdef BRAUN_FIXED_N
#define BRAUN_N(n) (BRAUN_FIXED_N)
#else
#define BRAUN_N(n) (n)
#endif
#ifdef BRAUN_FIXED_ROWS
#define BRAUN_ROWS(rows) (BRAUN_FIXED_ROWS)
#else
#define BRAUN_ROWS(rows) (rows)
#endif

/* In a build with compile-time sizes the loops of the small kernels have
 * constant trip counts once the outer ones are unrolled: BRAUN_UNROLL asks
 * GCC to unroll them completely, which turns a 6 x 5 factorization into
 * straight-line code (docs/performance.md: −23 % instructions per step on
 * the host, −17 % on the Cortex-M4F). The generic build is unchanged
 * (unrolling loops of run-time length only adds code); clang decides by
 * itself (its full-unroll hint warns where a loop has an early exit). */
#if defined(BRAUN_FIXED_N) && defined(__GNUC__) && !defined(__clang__)
#define BRAUN_UNROLL _Pragma("GCC unroll 16")
#else
#define BRAUN_UNROLL
#endif

/* ---- Cholesky: M = R^T R with R upper triangular (src/braun_chol.c) ---- */
typedef struct braun_chol {
    int n;
    braun_real *R;    /* n x n row-major, upper triangle (strict lower zeroed) */
    braun_real *dinv; /* n: 1 / R_ii */
    int *first;       /* n: first nonzero row of column j (envelope) */
    int *last;        /* n: last nonzero column of row i */
    int diagonal;     /* R is diagonal: the solves are one scaling */
} braun_chol;

/* Reals: n*n + n; ints: 2n. */
#define BRAUN_CHOL_REALS(n) ((size_t)(n) * (size_t)(n) + (size_t)(n))
#define BRAUN_CHOL_INTS(n) (2 * (size_t)(n))
void braun_chol_bind(braun_chol *c, int n, braun_real *reals, int *ints);

/* Factor the n x n row-major SPD matrix M into c (M may alias c->R).
 * Returns BRAUN_OK, BRAUN_ERR_MASS_NOT_SYMMETRIC (|M_ij - M_ji| >
 * sym_tol·sqrt(|M_ii M_jj|)) or BRAUN_ERR_MASS_NOT_SPD (pivot j <= n·ε·|M_jj|: its own
 * diagonal entry, so the verdict does not depend on the coordinates' units).
 * On error *bad_i, *bad_j, *bad_value (may be NULL) name the entry. */
int braun_chol_factor(braun_chol *c, const braun_real *M, braun_real sym_tol,
                      int *bad_i, int *bad_j, braun_real *bad_value);
/* x := R^-T x (forward substitution with the lower triangle R^T). */
void braun_chol_solve_rt(const braun_chol *c, braun_real *x);
/* x := R^-1 x (back substitution). */
void braun_chol_solve_r(const braun_chol *c, braun_real *x);
/* x := R^-T b and x := R^-1 b (x may be b): the solves without a copy. */
void braun_chol_solve_rt_to(const braun_chol *c, const braun_real *b, braun_real *x);
void braun_chol_solve_r_to(const braun_chol *c, const braun_real *b, braun_real *x);
/* y := R x (y and x distinct). */
void braun_chol_mul_r(const braun_chol *c, const braun_real *x, braun_real *y);
/* Both solves when R is diagonal (c->diagonal): one scaling by the
 * reciprocal pivots; inline, so that hot callers skip the call. */
static inline void braun_chol_solve_diag(const braun_chol *c, const braun_real *b, braun_real *x)
{
    const int n = BRAUN_N(c->n);
    for (int i = 0; i < n; i++) x[i] = b[i] * c->dinv[i];
}

/* y := R x when R is diagonal: the loop of braun_chol_mul_r with one term
 * per row (0 + r_ii x_i: the same result, signed zeros included). */
static inline void braun_chol_mul_diag(const braun_chol *c, const braun_real *x, braun_real *y)
{
    const int n = BRAUN_N(c->n);
    for (int i = 0; i < n; i++) y[i] = (braun_real)0 + c->R[(size_t)i * (size_t)(n + 1)] * x[i];
}

/* ---- Rank-revealing pseudoinverse of a wide matrix C (rows x n) ---------
 * Householder QR with column pivoting of C^T (n x rows):
 *     C^T P = Q [R11 R12; 0 R22],   R22 dropped when |r_kk| <= tol·|r_00|,
 * so C ≈ P S Q1^T with S = [R11 R12]^T (rows x k, full column rank k) and
 *     C^+ r = Q1 S^+ P^T r,    N z = (I - C^+ C) z = z - Q1 Q1^T z.
 * When k < rows (redundant rows or a singular configuration) S^+ is a
 * least-squares solve through a second Householder QR of S: together a
 * complete orthogonal decomposition, as LAPACK's xGELSY.
 * No explicit inverse is ever formed. (src/braun_qrcp.c) */
typedef struct braun_qrcp {
    int n, rows;       /* C is rows x n */
    int rank;          /* k */
    braun_real *a;     /* rows columns of length n, contiguous (= C row-major);
                          after factoring, column j of the factor (R above/on
                          the diagonal, its Householder vector below) is
                          stored where row perm[j] of C was: pivoting moves
                          indices, not data */
    braun_real *tau;   /* rows */
    int *perm;         /* rows: column j of the factor is row perm[j] of C */
    braun_real *s;     /* rows x rows scratch: QR of S when rank < rows */
    braun_real *stau;  /* rows */
    braun_real *work;  /* max(n, rows) */
    braun_real *soft;  /* BRAUN_QRCP_SOFT_REALS(n, rows): soft directions */
    int nsoft;         /* soft directions found by braun_qrcp_soft_find */
    braun_real dmin;   /* smallest |diagonal entry| of the triangle the solves use
                          (set by the factorization: the soft directions' gate) */
    braun_real soft_lam; /* λ of the soft directions found */
    braun_real r00;    /* the scale of the rank decisions and the gates:
                          |r_00| of the pivoted QR (the largest column norm
                          of Cᵀ) or of the ordered one (its first column's),
                          the largest row norm of C on the Gram path */
    int gram;          /* the last factorization is G = C Cᵀ = L D Lᵀ
                          (braun_qrcp_factor_gram): f->a still holds C */
    int norms_given;   /* work[0..rows) holds the rows' squared norms, summed
                          in order while C was formed: the next factorization
                          takes them instead of a pass of its own (and clears
                          this) */
} braun_qrcp;

/* The dense backend forms those norms with C (braun_dense.h): −2 % of a
 * generic step, −0.6 % with compile-time sizes (once C is formed with its
 * scales in registers; before that the factorization's own unrolled pass
 * was cheaper). */
#define BRAUN_FUSED_NORMS 1

/* Soft directions (src/braun_qrcp_soft.c): at most BRAUN_SOFT_MAX at a
 * time, below BRAUN_SOFT_GATE·λ. */
#define BRAUN_SOFT_MAX 3
#define BRAUN_SOFT_GATE 10
#define BRAUN_QRCP_SOFT_REALS(n, rows) \
    ((size_t)BRAUN_SOFT_MAX * (size_t)(rows) + BRAUN_SOFT_MAX + (size_t)(rows) + (size_t)(n))

/* The generic build dispatches the short lengths of the small kernels
 * (2..8, a planar or spatial mechanism's n - k) to bodies with a constant
 * trip count, unrolled: the loop overhead of run-time lengths was a fifth
 * of a step (docs/performance.md). Same operations in the same order: the
 * results are bit for bit those of the loop. A build with compile-time
 * sizes unrolls the loops themselves. */
/* A helper whose length argument must fold into a dispatched body. */
#if defined(__GNUC__)
#define BRAUN_FORCE_INLINE static inline __attribute__((always_inline))
/* Kept out of its (hot) caller: a rare path that would crowd its registers. */
#define BRAUN_NOINLINE __attribute__((noinline))
#else
#define BRAUN_FORCE_INLINE static inline
#define BRAUN_NOINLINE
#endif
/* BRAUN_SMALL_MAX (default 8, at most 8): the largest length with a body of
 * its own. Each one costs code: the dispatched bodies take a small
 * Cortex-M4F float image from 32 to 81 KB (docs/firmware.md, "Flash and
 * RAM"); -DBRAUN_SMALL_MAX=0 builds the loops alone, the smallest image. */
#ifndef BRAUN_SMALL_MAX
#define BRAUN_SMALL_MAX 8
#endif
#ifdef BRAUN_FIXED_N
#define BRAUN_SMALL_DISPATCH(len, BODY) BODY(len, BRAUN_UNROLL);
#else
#if defined(__GNUC__) && !defined(__clang__)
#define BRAUN_UNROLL_SMALL _Pragma("GCC unroll 8")
#else
#define BRAUN_UNROLL_SMALL
#endif
#define BRAUN__SMALL_CASE(L, BODY) \
    case L: BODY(L, BRAUN_UNROLL_SMALL); break;
#if BRAUN_SMALL_MAX >= 2
#define BRAUN__SMALL_CASE2(BODY) BRAUN__SMALL_CASE(2, BODY)
#else
#define BRAUN__SMALL_CASE2(BODY)
#endif
#if BRAUN_SMALL_MAX >= 3
#define BRAUN__SMALL_CASE3(BODY) BRAUN__SMALL_CASE(3, BODY)
#else
#define BRAUN__SMALL_CASE3(BODY)
#endif
#if BRAUN_SMALL_MAX >= 4
#define BRAUN__SMALL_CASE4(BODY) BRAUN__SMALL_CASE(4, BODY)
#else
#define BRAUN__SMALL_CASE4(BODY)
#endif
#if BRAUN_SMALL_MAX >= 5
#define BRAUN__SMALL_CASE5(BODY) BRAUN__SMALL_CASE(5, BODY)
#else
#define BRAUN__SMALL_CASE5(BODY)
#endif
#if BRAUN_SMALL_MAX >= 6
#define BRAUN__SMALL_CASE6(BODY) BRAUN__SMALL_CASE(6, BODY)
#else
#define BRAUN__SMALL_CASE6(BODY)
#endif
#if BRAUN_SMALL_MAX >= 7
#define BRAUN__SMALL_CASE7(BODY) BRAUN__SMALL_CASE(7, BODY)
#else
#define BRAUN__SMALL_CASE7(BODY)
#endif
#if BRAUN_SMALL_MAX >= 8
#define BRAUN__SMALL_CASE8(BODY) BRAUN__SMALL_CASE(8, BODY)
#else
#define BRAUN__SMALL_CASE8(BODY)
#endif
#define BRAUN_SMALL_DISPATCH(len, BODY) \
    switch (len) {                      \
    BRAUN__SMALL_CASE2(BODY)            \
    BRAUN__SMALL_CASE3(BODY)            \
    BRAUN__SMALL_CASE4(BODY)            \
    BRAUN__SMALL_CASE5(BODY)            \
    BRAUN__SMALL_CASE6(BODY)            \
    BRAUN__SMALL_CASE7(BODY)            \
    BRAUN__SMALL_CASE8(BODY)            \
    default: BODY(len, ); break;        \
    }
#endif

/* A length the compiler knows (a dispatched body's, a fixed-size build's)
 * and short enough for a body unrolled whole: the dense kernels below
 * choose it over their loops. Other compilers take the loops. */
#if defined(__GNUC__)
#define BRAUN_CONSTANT_P(x) __builtin_constant_p(x)
#else
#define BRAUN_CONSTANT_P(x) 0
#endif
#define BRAUN_SMALL_CONST(len) (BRAUN_CONSTANT_P(len) && (len) <= BRAUN_SMALL_MAX)

/* x := R⁻ᵀ b over the whole triangle of a Cholesky factor, unrolled (N a
 * length the compiler knows, BRAUN_SMALL_CONST; x may be b): the short
 * lengths of braun_chol_solve_rt_to and the dense backend's rows of
 * C = A R⁻¹ (braun_dense.h). The zeros an envelope loop would skip add
 * exact zeros: the same values. */
#define BRAUN_CHOL_RT_WHOLE(N, UNROLL, R, dinv, b, x)                                   \
    UNROLL for (int i_ = 0; i_ < (N); i_++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        braun_real s_ = (b)[i_];                                                        \
        UNROLL for (int k_ = 0; k_ < i_; k_++) s_ -= (R)[k_ * (N) + i_] * (x)[k_]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        (x)[i_] = s_ * (dinv)[i_];                                                      \
    }

/* y[0..len) := (I - tau v v^T) y with v = (1, vtail[0..len-1)): one
 * Householder reflector of the factorization (vtail, another column or
 * another array, never overlaps y). */
#define BRAUN_REFLECT_BODY(L, UNROLL)                                          \
    do {                                                                       \
        braun_real w_ = y[0];                                                  \
        UNROLL /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        for (int i_ = 1; i_ < (L); i_++) w_ += vtail[i_ - 1] * y[i_];          \
        w_ *= tau;                                                             \
        y[0] -= w_;                                                            \
        UNROLL /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        for (int i_ = 1; i_ < (L); i_++) y[i_] -= w_ * vtail[i_ - 1];          \
    } while (0)
static inline void braun_qrcp__reflect(int len, const braun_real *restrict vtail, braun_real tau,
                                       braun_real *restrict y)
{
    if (tau == 0) return;
    BRAUN_SMALL_DISPATCH(len, BRAUN_REFLECT_BODY)
}

/* Bytes of the reals and ints a braun_qrcp of this size needs. */
size_t braun_qrcp_reals(int n, int rows);
size_t braun_qrcp_ints(int rows);
/* Point the factorization at caller memory (reals, ints sized as above). */
void braun_qrcp_bind(braun_qrcp *f, int n, int rows, braun_real *reals,
                     int *ints);
/* Factor the matrix stored in f->a (row i of C at f->a + i·n) with the
 * relative rank tolerance tol. Returns the rank. */
int braun_qrcp_factor(braun_qrcp *f, braun_real tol);
/* The same under a rank rule (braun_linsolver.h, rank_rule): a pivot beyond
 * the first `keep` counts only above tol_new·|r_00| too, and at most `cap`
 * pivots count. same_rows (a step's later stages): when the last
 * factorization had rank keep < rows, the rows it set aside are set aside
 * again while the others' pivots clear tol_new·|r_00|. */
int braun_qrcp_factor_rule(braun_qrcp *f, braun_real tol, braun_real tol_new, int keep, int cap, int same_rows);
/* The same matrix shape factored again in the last factorization's column
 * order, without pivoting, when that one had full rank rows <= n: accepted
 * only if every pivot exceeds gate·r00 (r00 the largest column norm), else
 * -1 and f->a is spent (form C again and call braun_qrcp_factor_rule). */
int braun_qrcp_factor_ordered(braun_qrcp *f, braun_real gate);
/* The matrix in f->a factored through its Gram matrix G = C Cᵀ = L D Lᵀ
 * in C's row order (src/braun_qrcp_gram.c), when the last factorization
 * had full rank rows <= n: accepted only if every pivot d_i exceeds both
 * gate²·max_j G_jj (far from the rank decisions) and rel_gate²·G_ii (the
 * row-equilibrated G well conditioned; gate, rel_gate < 1). Then f->gram
 * is set, the rank is rows, and the solves below (braun_qrcp_lsq,
 * _pinv_apply, _pinv2, _null_project) go through G, C staying in f->a. Else -1 (a pivot below the first gate, a NaN, or not
 * applicable) or -2 (every pivot above the first gate, some below the
 * second: the rank is full, an ordered QR can take it), with C and its
 * norms left for braun_qrcp_factor_ordered or braun_qrcp_factor_rule. */
int braun_qrcp_factor_gram(braun_qrcp *f, braun_real gate, braun_real rel_gate);
void braun_qrcp_gram_lsq(const braun_qrcp *f, const braun_real *r, braun_real *x, braun_real *resid);
void braun_qrcp_gram_pinv2(const braun_qrcp *f, const braun_real *r1, const braun_real *r2,
                           braun_real *x1, braun_real *x2);
void braun_qrcp_gram_null_project(const braun_qrcp *f, braun_real *z);
/* The solves, through whichever factorization f holds (f->gram: the
 * Gram path's, src/braun_qrcp_gram.c; else the QR's, src/braun_qrcp.c).
 * One dispatch here, inline, so that no caller can apply the QR's solves
 * to a Gram factor. */
void braun_qrcp__qr_lsq(const braun_qrcp *f, const braun_real *r, braun_real *x, braun_real *resid);
void braun_qrcp__qr_pinv2(const braun_qrcp *f, const braun_real *r1, const braun_real *r2,
                          braun_real *x1, braun_real *x2);
void braun_qrcp__qr_null_project(const braun_qrcp *f, braun_real *z);
/* x[n] := C^+ r, r[rows] (r is not modified), and *resid :=
 * ||r - C C^+ r||_2 (resid may be NULL), the part of r no x can reach (0
 * when the rows are independent). */
static inline void braun_qrcp_lsq(const braun_qrcp *f, const braun_real *r, braun_real *x,
                                  braun_real *resid)
{
    if (f->gram) braun_qrcp_gram_lsq(f, r, x, resid);
    else braun_qrcp__qr_lsq(f, r, x, resid);
}
/* The same without the residual. */
static inline void braun_qrcp_pinv_apply(const braun_qrcp *f, const braun_real *r, braun_real *x)
{
    braun_qrcp_lsq(f, r, x, NULL);
}
/* x1 := C^+ r1 and x2 := C^+ r2 in one walk of the factor (full row rank;
 * else two braun_qrcp_lsq calls): bit for bit the two applies. */
static inline void braun_qrcp_pinv2(const braun_qrcp *f, const braun_real *r1, const braun_real *r2,
                                    braun_real *x1, braun_real *x2)
{
    if (f->gram) braun_qrcp_gram_pinv2(f, r1, r2, x1, x2);
    else braun_qrcp__qr_pinv2(f, r1, r2, x1, x2);
}
/* z[n] := N z = z - C^+ C z (projection onto the null space of C). */
static inline void braun_qrcp_null_project(const braun_qrcp *f, braun_real *z)
{
    if (f->gram) braun_qrcp_gram_null_project(f, z);
    else braun_qrcp__qr_null_project(f, z);
}
/* The soft directions of the last factorization: the right singular
 * vectors s_c of C whose singular values σ_c are below BRAUN_SOFT_GATE·λ,
 * λ = rel·|r_00| (rel > 0), found by inverse iteration on the factor.
 * Returns their number (0 when the factor's smallest diagonal entry is
 * above the gate: then it costs one compare). */
int braun_qrcp_soft_find(braun_qrcp *f, braun_real rel);
/* y[n] := Σ_c w_c s_c (s_cᵀ x): the weighted part of x[n] along the soft
 * directions found (0 when there are none), w_c = λ⁴/(σ_c⁴ + λ⁴), times
 * z⁴/(1 + z⁴), z = rate/σ_c, when rate > 0. y must not alias x. */
void braun_qrcp_soft_project(const braun_qrcp *f, const braun_real *x, braun_real *y,
                             braun_real rate);

/* ---- small vector helpers (inline: n is small and the calls are hot) ---- */
static inline braun_real braun_dot(int n, const braun_real *x, const braun_real *y)
{
    braun_real s = 0;
    for (int i = 0; i < n; i++) s += x[i] * y[i];
    return s;
}

/* x·0 is 0 for finite x and NaN for NaN and ±Inf: one branch-free pass
 * (vectorisable), no overflow, whatever the magnitudes. */
static inline int braun_all_finite(int n, const braun_real *x)
{
    braun_real s = 0;
    for (int i = 0; i < n; i++) s += x[i] * 0;
    return s == 0;
}

/* (src/braun_vec.c) */
braun_real braun_nrm2(int n, const braun_real *x);
/* y := A x, A rows x n row-major. */
void braun_gemv(int rows, int n, const braun_real *A, const braun_real *x,
                braun_real *y);

#endif
