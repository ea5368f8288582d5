/*
 * Private dense linear-algebra kernels of libbraun (no allocation; all
 * scratch is passed in). Matrices are row-major unless stated otherwise.
 */
#ifndef BRAUN_LINALG_H
#define BRAUN_LINALG_H

#include "braun.h"
#include "braun_math.h"

/* ---- Cholesky: M = R^T R with R upper triangular (src/braun_chol.c) ---- */

/* Factor the n x n row-major SPD matrix M into R (upper triangle of R; the
 * strict lower triangle is set to zero). M and R may alias. Returns BRAUN_OK,
 * BRAUN_ERR_MASS_NOT_SYMMETRIC (|M_ij - M_ji| > sym_tol·max_i M_ii) or
 * BRAUN_ERR_MASS_NOT_SPD (pivot <= 0 or below n·ε·max diagonal). On error
 * *bad_i, *bad_j (may be NULL) name the entry. */
int braun_chol_factor(int n, const braun_real *M, braun_real *R,
                      braun_real sym_tol, int *bad_i, int *bad_j,
                      braun_real *bad_value);
/* x := R^-T x (forward substitution with the lower triangle R^T). */
void braun_chol_solve_rt(int n, const braun_real *R, braun_real *x);
/* x := R^-1 x (back substitution). */
void braun_chol_solve_r(int n, const braun_real *R, braun_real *x);

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
    braun_real *a;     /* rows columns of length n, contiguous (= C row-major):
                          R above/on the diagonal, Householder vectors below */
    braun_real *tau;   /* rows */
    int *perm;         /* rows: column j of the factor is row perm[j] of C */
    braun_real *s;     /* rows x rows scratch: QR of S when rank < rows */
    braun_real *stau;  /* rows */
    braun_real *work;  /* max(n, rows) */
} braun_qrcp;

/* Bytes of the reals and ints a braun_qrcp of this size needs. */
size_t braun_qrcp_reals(int n, int rows);
size_t braun_qrcp_ints(int rows);
/* Point the factorization at caller memory (reals, ints sized as above). */
void braun_qrcp_bind(braun_qrcp *f, int n, int rows, braun_real *reals,
                     int *ints);
/* Factor the matrix stored in f->a (row i of C at f->a + i·n) with the
 * relative rank tolerance tol. Returns the rank. */
int braun_qrcp_factor(braun_qrcp *f, braun_real tol);
/* x[n] := C^+ r, r[rows] (r is not modified). */
void braun_qrcp_pinv_apply(const braun_qrcp *f, const braun_real *r,
                           braun_real *x);
/* z[n] := N z = z - C^+ C z (projection onto the null space of C). */
void braun_qrcp_null_project(const braun_qrcp *f, braun_real *z);

/* ---- small vector helpers (src/braun_vec.c) ---- */
braun_real braun_dot(int n, const braun_real *x, const braun_real *y);
braun_real braun_nrm2(int n, const braun_real *x);
/* y := A x, A rows x n row-major. */
void braun_gemv(int rows, int n, const braun_real *A, const braun_real *x,
                braun_real *y);
int braun_all_finite(int n, const braun_real *x);

#endif
