/* Model: validate a system description and set default options. */
#include "braun_internal.h"

int braun_model_init(braun_model *model, const braun_system *sys)
{
    if (!model || !sys) return BRAUN_ERR_ARGUMENT;
    /* Bounded sizes keep every index product inside int on a 32-bit target. */
    if (sys->n <= 0 || sys->m < 0 || sys->p < 0 || sys->n > 4096 ||
        sys->m > 4096 || sys->p > 4096)
        return BRAUN_ERR_SIZE;
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
    if (sys->flags & ~(unsigned)(BRAUN_MASS_CONSTANT | BRAUN_ENERGY_INPUT | BRAUN_CONSTRAINT_WORK))
        return BRAUN_ERR_ARGUMENT;
    model->sys = *sys;
    model->opt.corrections = BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY |
                             (sys->energy ? BRAUN_CORRECT_ENERGY : 0u);
    model->opt.discretization = BRAUN_PER_STEP;
    model->opt.rank_tol = 0;
    model->opt.energy_max_rel = 0;
    model->opt.symmetry_tol = 0;
    model->opt.inconsistency_tol = 0;
    return BRAUN_OK;
}
