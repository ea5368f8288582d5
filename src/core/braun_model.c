/* Model: validate a system description and set default options. */
#include "braun_internal.h"

/* The pattern must index inside the matrix, rows sorted; the blocks must
 * tile the diagonal. NULL, or what is wrong. */
static const char *sparsity_problem(const braun_system *sys)
{
    const braun_sparsity *sp = sys->sparsity;
    const int rows = sys->m + sys->p;
    if (!sp->row_ptr || (rows > 0 && !sp->col) || !sp->block)
        return "sparsity: row_ptr, col or block is NULL";
    if (sp->nblocks <= 0) return "sparsity: nblocks <= 0";
    if (sp->row_ptr[0] != 0) return "sparsity: row_ptr[0] != 0";
    for (int i = 0; i < rows; i++) {
        if (sp->row_ptr[i + 1] < sp->row_ptr[i] || sp->row_ptr[i + 1] - sp->row_ptr[i] > sys->n)
            return "sparsity: row_ptr decreasing, or a row with more than n entries";
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++)
            if (sp->col[k] < 0 || sp->col[k] >= sys->n ||
                (k > sp->row_ptr[i] && sp->col[k] <= sp->col[k - 1]))
                return "sparsity: a column index outside 0..n-1, or a row's columns not increasing";
    }
    long sum = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        if (sp->block[k] <= 0) return "sparsity: a mass block of size <= 0";
        sum += sp->block[k];
        if (sum > sys->n) return "sparsity: the mass blocks add up to more than n";
    }
    return sum == sys->n ? NULL : "sparsity: the mass blocks add up to less than n";
}

int braun_system_check(const braun_system *sys, const char **problem)
{
    const char *why = NULL;
    int st = BRAUN_OK;
    /* Bounded sizes keep every index product inside int on a 32-bit target
     * (dense) and every nonzero count inside int (sparse). */
    const int max = sys && sys->sparsity ? BRAUN_MAX_SPARSE : BRAUN_MAX_DENSE;
#define BRAUN__REFUSE(status, text) \
    do {                             \
        st = (status);               \
        why = (text);                \
    } while (0)
    if (!sys) BRAUN__REFUSE(BRAUN_ERR_ARGUMENT, "system is NULL");
    else if (sys->n <= 0) BRAUN__REFUSE(BRAUN_ERR_SIZE, "n <= 0");
    else if (sys->m < 0 || sys->p < 0) BRAUN__REFUSE(BRAUN_ERR_SIZE, "m or p < 0");
    else if (sys->n > max || sys->m > max || sys->p > max)
        BRAUN__REFUSE(BRAUN_ERR_SIZE, sys->sparsity ? "n, m or p above BRAUN_MAX_SPARSE (2^20)"
                                                    : "n, m or p above BRAUN_MAX_DENSE (4096; "
                                                      "larger systems need a sparsity)");
    else if (sys->sparsity && (why = sparsity_problem(sys)) != NULL) st = BRAUN_ERR_ARGUMENT;
#ifdef BRAUN_FIXED_N
    /* A library built for one size (braun_linalg.h) runs only that size. */
    else if (sys->n != BRAUN_FIXED_N) BRAUN__REFUSE(BRAUN_ERR_SIZE, "n is not this build's BRAUN_FIXED_N");
#endif
#ifdef BRAUN_FIXED_ROWS
    /* ... and one row count; the separate C_q factorization of a system with
     * both kinds of rows has m rows, so such a system cannot use it. */
    else if (sys->m + sys->p != BRAUN_FIXED_ROWS || (sys->m > 0 && sys->p > 0))
        BRAUN__REFUSE(BRAUN_ERR_SIZE, "m + p is not this build's BRAUN_FIXED_ROWS (or both m, p > 0)");
#endif
    else if (!sys->mass) BRAUN__REFUSE(BRAUN_ERR_MISSING_CALLBACK, "mass is NULL");
    else if (!sys->forces) BRAUN__REFUSE(BRAUN_ERR_MISSING_CALLBACK, "forces is NULL");
    else if (sys->m > 0 && !sys->holonomic)
        BRAUN__REFUSE(BRAUN_ERR_MISSING_CALLBACK, "holonomic is NULL but m > 0");
    else if (sys->p > 0 && !sys->nonholonomic)
        BRAUN__REFUSE(BRAUN_ERR_MISSING_CALLBACK, "nonholonomic is NULL but p > 0");
    else if ((sys->flags & BRAUN_ENERGY_INPUT) && !sys->power)
        BRAUN__REFUSE(BRAUN_ERR_MISSING_CALLBACK, "power is NULL but flags has BRAUN_ENERGY_INPUT");
    else if (sys->flags & ~(unsigned)(BRAUN_MASS_CONSTANT | BRAUN_ENERGY_INPUT | BRAUN_CONSTRAINT_WORK |
                                      BRAUN_SCLERONOMIC))
        BRAUN__REFUSE(BRAUN_ERR_ARGUMENT, "flags has a bit that is no BRAUN_* system flag");
    /* Contradictory: constraints that do work and do none. */
    else if ((sys->flags & BRAUN_CONSTRAINT_WORK) && (sys->flags & BRAUN_SCLERONOMIC))
        BRAUN__REFUSE(BRAUN_ERR_ARGUMENT, "flags has both BRAUN_CONSTRAINT_WORK and BRAUN_SCLERONOMIC");
    else if (sys->q_scale) {
        /* The guard divides by these sizes' products: each must be a size. */
        for (int j = 0; j < sys->n; j++)
            if (!(sys->q_scale[j] > 0) || !(sys->q_scale[j] <= BRAUN_MAXREAL)) {
                BRAUN__REFUSE(BRAUN_ERR_ARGUMENT, "q_scale has an entry that is not positive and finite");
                break;
            }
    }
#undef BRAUN__REFUSE
    if (problem) *problem = why;
    return st;
}

int braun_model_init(braun_model *model, const braun_system *sys)
{
    if (!model || !sys) return BRAUN_ERR_ARGUMENT;
    const int st = braun_system_check(sys, NULL);
    if (st) return st;
    model->sys = *sys;
    model->opt.corrections = BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY |
                             (sys->energy ? BRAUN_CORRECT_ENERGY : 0u);
    model->opt.discretization = BRAUN_PER_STEP;
    model->opt.rank_tol = 0;
    model->opt.energy_max_rel = 0;
    model->opt.symmetry_tol = 0;
    model->opt.inconsistency_tol = 0;
    model->opt.guard = 0;
    model->opt.soft_tol = 0;
    model->opt.linsolver = NULL;
    return BRAUN_OK;
}
