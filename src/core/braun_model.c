/* Model: validate a system description and set default options. */
#include "braun_internal.h"

/* The pattern must index inside the matrix, rows sorted; the blocks must
 * tile the diagonal. BRAUN_ERR_ARGUMENT otherwise. */
static int check_sparsity(const braun_system *sys)
{
    const braun_sparsity *sp = sys->sparsity;
    const int rows = sys->m + sys->p;
    if (!sp->row_ptr || (rows > 0 && !sp->col) || !sp->block || sp->nblocks <= 0 ||
        sp->row_ptr[0] != 0)
        return BRAUN_ERR_ARGUMENT;
    for (int i = 0; i < rows; i++) {
        if (sp->row_ptr[i + 1] < sp->row_ptr[i] || sp->row_ptr[i + 1] - sp->row_ptr[i] > sys->n)
            return BRAUN_ERR_ARGUMENT;
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++)
            if (sp->col[k] < 0 || sp->col[k] >= sys->n ||
                (k > sp->row_ptr[i] && sp->col[k] <= sp->col[k - 1]))
                return BRAUN_ERR_ARGUMENT;
    }
    long sum = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        if (sp->block[k] <= 0) return BRAUN_ERR_ARGUMENT;
        sum += sp->block[k];
        if (sum > sys->n) return BRAUN_ERR_ARGUMENT;
    }
    return sum == sys->n ? BRAUN_OK : BRAUN_ERR_ARGUMENT;
}

int braun_model_init(braun_model *model, const braun_system *sys)
{
    if (!model || !sys) return BRAUN_ERR_ARGUMENT;
    /* Bounded sizes keep every index product inside int on a 32-bit target
     * (dense) and every nonzero count inside int (sparse). */
    const int max = sys->sparsity ? BRAUN_MAX_SPARSE : BRAUN_MAX_DENSE;
    if (sys->n <= 0 || sys->m < 0 || sys->p < 0 || sys->n > max || sys->m > max || sys->p > max)
        return BRAUN_ERR_SIZE;
    if (sys->sparsity) {
        int st = check_sparsity(sys);
        if (st) return st;
    }
#ifdef BRAUN_FIXED_N
    /* A library built for one size (braun_linalg.h) runs only that size. */
    if (sys->n != BRAUN_FIXED_N) return BRAUN_ERR_SIZE;
#endif
#ifdef BRAUN_FIXED_ROWS
    /* ... and one row count; the separate C_q factorization of a system with
     * both kinds of rows has m rows, so such a system cannot use it. */
    if (sys->m + sys->p != BRAUN_FIXED_ROWS || (sys->m > 0 && sys->p > 0))
        return BRAUN_ERR_SIZE;
#endif
    if (!sys->mass || !sys->forces) return BRAUN_ERR_MISSING_CALLBACK;
    if (sys->m > 0 && !sys->holonomic) return BRAUN_ERR_MISSING_CALLBACK;
    if (sys->p > 0 && !sys->nonholonomic) return BRAUN_ERR_MISSING_CALLBACK;
    if ((sys->flags & BRAUN_ENERGY_INPUT) && !sys->power)
        return BRAUN_ERR_MISSING_CALLBACK;
    if (sys->flags & ~(unsigned)(BRAUN_MASS_CONSTANT | BRAUN_ENERGY_INPUT | BRAUN_CONSTRAINT_WORK |
                                 BRAUN_SCLERONOMIC))
        return BRAUN_ERR_ARGUMENT;
    /* Contradictory: constraints that do work and do none. */
    if ((sys->flags & BRAUN_CONSTRAINT_WORK) && (sys->flags & BRAUN_SCLERONOMIC))
        return BRAUN_ERR_ARGUMENT;
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
