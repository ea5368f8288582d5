/*
 * libbraun — optional linear-algebra backends (host only; libbraun_backends.a).
 *
 *   lapack       dense: dpotrf for M, dgeqp3 + dtzrzf (complete orthogonal
 *                decomposition, as dgelsy) for C = A R^-1. Built with
 *                BRAUN_LAPACK=1 (the default when liblapack is installed).
 *   suitesparse  sparse (needs sys.sparsity): block Cholesky of M, CHOLMOD
 *                for A M^-1 A^T while C has full rank, SPQR (rank-revealing
 *                sparse QR of C^T) when it has not. Built with
 *                BRAUN_SUITESPARSE=1.
 *
 * libbraun.a itself never links them: a program that uses this header links
 * libbraun_backends.a and the libraries it was built with.
 */
#ifndef BRAUN_BACKENDS_H
#define BRAUN_BACKENDS_H

#include "braun.h"
#include "braun_linsolver.h"

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_linsolver_lapack braun_linsolver_lapack_float
#define braun_linsolver_name braun_linsolver_name_float
#define braun_linsolver_select braun_linsolver_select_float
#define braun_linsolver_suitesparse braun_linsolver_suitesparse_float
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The backends compiled into this libbraun_backends.a (NULL when not). */
const braun_linsolver *braun_linsolver_lapack(void);
const braun_linsolver *braun_linsolver_suitesparse(void);

/* Choose by name: "dense" (libbraun's kernels: *out = NULL), "lapack",
 * "suitesparse", or "auto" (by size and sparsity, docs/performance.md:
 * the built-in kernels for small systems, SuiteSparse for large sparse ones,
 * LAPACK for large dense ones; whatever is compiled in).
 * BRAUN_OK, BRAUN_ERR_SIZE for sizes braun_model_init refuses whatever the
 * backend (n < 1, m or p < 0, n, m or p above BRAUN_MAX_DENSE without a
 * sparsity, above BRAUN_MAX_SPARSE with one), or BRAUN_ERR_ARGUMENT for an
 * unknown name or a backend not built into this library or unable to take
 * this system (the built-in kernels: n <= BRAUN_MAX_DENSE, m + p <= twice
 * it; lapack: n, m, p <= BRAUN_MAX_DENSE each; suitesparse: a sparsity)
 * (message, with the limit, in *why, a static string, when why is not
 * NULL). A system select accepts is one braun_data_init accepts for that
 * backend, as far as its sizes go. */
int braun_linsolver_select(const char *name, const braun_system *sys,
                           const braun_linsolver **out, const char **why);

/* "dense" for NULL, else the backend's name. */
const char *braun_linsolver_name(const braun_linsolver *ls);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_BACKENDS_H */
