/* Backend names and the automatic choice by size and sparsity. */
#include <string.h>

#include "braun_backends.h"

/* Measured crossovers (docs/performance.md, "Backends"; OpenBLAS serial):
 * on the chain the SuiteSparse backend is as fast as the built-in kernels
 * at n = 15 (11 vs 9.6 µs per RK4 step) and 2x faster at n = 30; on dense
 * random systems LAPACK overtakes the built-in kernels at n ≈ 30-45 (with the
 * reference BLAS only at n ≈ 300). */
#define AUTO_SPARSE_MIN_N 21
#define AUTO_LAPACK_MIN_N 41

#ifndef BRAUN_WITH_LAPACK
const braun_linsolver *braun_linsolver_lapack(void) { return NULL; }
#endif
#ifndef BRAUN_WITH_SUITESPARSE
const braun_linsolver *braun_linsolver_suitesparse(void) { return NULL; }
#endif

const char *braun_linsolver_name(const braun_linsolver *ls)
{
    return ls ? ls->name : "dense";
}

static int fail(const char **why, const char *msg)
{
    if (why) *why = msg;
    return BRAUN_ERR_ARGUMENT;
}

int braun_linsolver_select(const char *name, const braun_system *sys,
                           const braun_linsolver **out, const char **why)
{
    if (why) *why = NULL;
    if (!name || !sys || !out) return fail(why, "NULL argument");
    *out = NULL;
    /* Sizes no backend can take (n = -3 was "OK"). Only the sizes: a
     * system filled in as far as n to ask which backend suits it is fine. */
    if (sys->n <= 0 || sys->m < 0 || sys->p < 0) {
        if (why) *why = "invalid sizes n, m, p (n >= 1, m, p >= 0)";
        return BRAUN_ERR_SIZE;
    }
    /* What braun_model_init refuses whatever the backend (braun_model.c,
     * braun_system_check): a dense m = 4220 system was "dense" here. */
    if (!sys->sparsity &&
        (sys->n > BRAUN_MAX_DENSE || sys->m > BRAUN_MAX_DENSE || sys->p > BRAUN_MAX_DENSE)) {
        if (why) *why = "n, m or p above BRAUN_MAX_DENSE (4096; larger systems need a sparsity)";
        return BRAUN_ERR_SIZE;
    }
    if (sys->sparsity &&
        (sys->n > BRAUN_MAX_SPARSE || sys->m > BRAUN_MAX_SPARSE || sys->p > BRAUN_MAX_SPARSE)) {
        if (why) *why = "n, m or p above BRAUN_MAX_SPARSE (2^20)";
        return BRAUN_ERR_SIZE;
    }
    /* LAPACK's create (braun_lapack.c) takes n, m and p up to
     * BRAUN_MAX_DENSE each, fewer rows than the built-in kernels: a sparse
     * m = 4098 system was "OK" here and then failed braun_data_init with
     * "invalid sizes: linear solver create". */
    const int beyond_lapack =
        sys->n > BRAUN_MAX_DENSE || sys->m > BRAUN_MAX_DENSE || sys->p > BRAUN_MAX_DENSE;
    /* The dense kernels (built-in or LAPACK's) stop where braun_data_size
     * does (braun_data.c, dense_size_ok: n <= BRAUN_MAX_DENSE, m + p <= twice
     * it): a larger sparse system was "OK" here and then failed
     * braun_data_init with "invalid sizes". */
    const int beyond_dense = sys->n > BRAUN_MAX_DENSE || sys->m + sys->p > 2 * BRAUN_MAX_DENSE;
    const int dense_only = strcmp(name, "dense") == 0 || strcmp(name, "lapack") == 0;
    if (dense_only && beyond_dense)
        return fail(why, sys->sparsity ? "beyond the dense kernels' 4096 coordinates (8192 rows): use "
                                         "'suitesparse' (or 'auto')"
                                       : "beyond the dense kernels' 4096 coordinates (8192 rows; a "
                                         "system with a sparsity pattern can use 'suitesparse')");
    if (strcmp(name, "dense") == 0) return BRAUN_OK;
    if (strcmp(name, "lapack") == 0) {
        if (!(*out = braun_linsolver_lapack()))
            return fail(why, "backend 'lapack' not built (make BRAUN_LAPACK=1)");
        if (beyond_lapack) {
            *out = NULL;
            return fail(why, sys->sparsity
                                 ? "beyond backend 'lapack''s 4096 coordinates and 4096 rows of "
                                   "each kind (m, p): use 'suitesparse', 'dense' or 'auto'"
                                 : "beyond backend 'lapack''s 4096 coordinates and 4096 rows of "
                                   "each kind (m, p)");
        }
        return BRAUN_OK;
    }
    if (strcmp(name, "suitesparse") == 0) {
        if (!(*out = braun_linsolver_suitesparse()))
            return fail(why, "backend 'suitesparse' not built (make BRAUN_SUITESPARSE=1)");
        if (!sys->sparsity) {
            *out = NULL;
            return fail(why, "backend 'suitesparse' needs a system with a sparsity pattern");
        }
        return BRAUN_OK;
    }
    if (strcmp(name, "auto") != 0)
        return fail(why, "unknown backend (dense, lapack, suitesparse, auto)");
    if (beyond_dense && !(sys->sparsity && braun_linsolver_suitesparse()))
        return fail(why, "beyond the dense kernels' 4096 coordinates (8192 rows), and no sparse "
                         "backend for it (a sparsity pattern and 'suitesparse')");
    if (sys->sparsity && sys->n >= AUTO_SPARSE_MIN_N && braun_linsolver_suitesparse()) {
        *out = braun_linsolver_suitesparse();
        return BRAUN_OK;
    }
    if (sys->n >= AUTO_LAPACK_MIN_N && !beyond_lapack && braun_linsolver_lapack())
        *out = braun_linsolver_lapack();
    return BRAUN_OK;
}
