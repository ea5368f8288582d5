/* Small dense kernels of the harness (cmp_dense.c), independent of
 * libbraun's: Cholesky of M, C = A L⁻ᵀ, and a minimum-norm solution of
 * C x = r through a column-pivoted Householder QR of Cᵀ that drops
 * dependent rows. Used by `projection` (cmp_proj.c) and its reference.
 * Row-major, no allocation after cmp_mnsolve_init. */
#ifndef CMP_DENSE_H
#define CMP_DENSE_H

/* M = L Lᵀ in place of L (n x n, lower triangle written, upper zeroed).
 * 0, or -1 if M is not symmetric positive definite. */
int cmp_chol(int n, const double *M, double *L);
/* x := L⁻¹ x and x := L⁻ᵀ x. */
void cmp_trsv_lower(int n, const double *L, double *x);
void cmp_trsv_lower_t(int n, const double *L, double *x);

/* The factorization of C (rows x n) for minimum-norm solutions. */
typedef struct cmp_mnsolve {
    int n, rows, rank;
    double *qr;    /* Cᵀ factored: n x rows, Householder vectors below R */
    double *tau;   /* rows */
    int *perm;     /* rows: column j of the factored Cᵀ is row perm[j] of C */
    double *work;  /* n + rows */
} cmp_mnsolve;

/* Room for C of up to rows x n. 0 or -1 (out of memory). */
int cmp_mnsolve_init(cmp_mnsolve *s, int n, int rows);
void cmp_mnsolve_free(cmp_mnsolve *s);
/* Factor C (rows x n, row-major, rows <= the room): pivots |R_jj| below
 * rtol·|R_00| count as zero (rtol <= 0: 10·max(n, rows)·ε, MATLAB's pinv
 * rule). Returns the rank. */
int cmp_mnsolve_factor(cmp_mnsolve *s, int rows, const double *C, double rtol);
/* x (n) = the minimum-norm solution of the independent rows of C x = r
 * (r: rows); the dependent rows are dropped (consistent rows: exact). */
void cmp_mnsolve_apply(const cmp_mnsolve *s, const double *r, double *x);

#endif
