/* The study's RK4 + projection reference as the compare tests build it
 * (test_compare.c, test_simbody.c): over [0, T], its step 2.5e-5·h_scale
 * but at most dt/20 and dividing the output interval dt; the caller
 * tabulates it (cmp_ref_tabulate). NULL with err when the run fails. */
#ifndef TEST_PROJ_REF_H
#define TEST_PROJ_REF_H

#include <math.h>
#include <stddef.h>

#include "cmp.h"

static inline cmp_ref *test_proj_ref_new(const cmp_target *tg, double T, double dt, char *err,
                                         size_t errsize)
{
    const double h = fmin(2.5e-5 * tg->h_scale, dt / 20);
    return cmp_ref_new_proj(tg, T, dt / ceil(dt / h - 1e-9), dt, err, errsize);
}

#endif
