/* The table of libbraun's own dense kernels (braun_dense.h), and its
 * state in the data block. */
#include "braun_dense.h"

#define DENSE_ALIGN 16u

static size_t round_up(size_t x) { return (x + DENSE_ALIGN - 1) / DENSE_ALIGN * DENSE_ALIGN; }

static int has_fq(const braun_model *model) { return model->sys.m > 0 && model->sys.p > 0; }

/* The struct, then the reals, then the ints. */
static size_t dense_reals(const braun_model *model)
{
    const int n = model->sys.n, m = model->sys.m, rows = m + model->sys.p;
    return BRAUN_CHOL_REALS(n) + braun_qrcp_reals(n, rows) +
           (has_fq(model) ? braun_qrcp_reals(n, m) : 0);
}

static size_t dense_ints(const braun_model *model)
{
    const int n = model->sys.n, m = model->sys.m, rows = m + model->sys.p;
    return BRAUN_CHOL_INTS(n) + braun_qrcp_ints(rows) + (has_fq(model) ? braun_qrcp_ints(m) : 0);
}

static size_t dense_state_bytes(const braun_model *model)
{
    return round_up(sizeof(braun_dense)) + round_up(dense_reals(model) * sizeof(braun_real)) +
           dense_ints(model) * sizeof(int);
}

/* memory: dense_state_bytes(model) bytes, DENSE_ALIGN-aligned. */
static int dense_bind(void **state, void *memory, const braun_model *model)
{
    const int n = model->sys.n, m = model->sys.m, rows = m + model->sys.p;
    unsigned char *base = memory;
    braun_dense *s = (braun_dense *)(void *)base;
    braun_real *r = (braun_real *)(void *)(base + round_up(sizeof *s));
    int *ints = (int *)(void *)(base + round_up(sizeof *s) +
                                round_up(dense_reals(model) * sizeof(braun_real)));
    s->n = n;
    s->stage_order = 0;
    for (int k = 0; k < 2; k++) {
        s->keep[k] = s->cap[k] = k ? m : rows; /* the plain tolerance */
        s->tol_new[k] = 0;
        s->tol[k] = 0;
    }
    braun_chol_bind(&s->chol, n, r, ints);
    r += BRAUN_CHOL_REALS(n);
    ints += BRAUN_CHOL_INTS(n);
    braun_qrcp_bind(&s->fv, n, rows, r, ints);
    if (has_fq(model))
        braun_qrcp_bind(&s->fq, n, m, r + braun_qrcp_reals(n, rows), ints + braun_qrcp_ints(rows));
    *state = s;
    return BRAUN_OK;
}

const braun_linsolver braun__dense_linsolver = {
    "dense",
    BRAUN_LS_DENSE,
    NULL, /* create: the state is in the data block */
    NULL, /* destroy: nothing allocated */
    braun__dense_factor_mass,
    braun__dense_solve_rt,
    braun__dense_solve_r,
    braun__dense_mul_r,
    braun__dense_factor_c,
    braun__dense_pinv,
    braun__dense_lsq,
    braun__dense_null_project,
    dense_state_bytes,
    dense_bind,
    braun__dense_mass_buffer,
    braun__dense_rank_rule,
    braun__dense_soft_find,
    braun__dense_soft_project,
    NULL, /* rhs_floor: the QRCP's C^+ r is exact */
    braun__dense_stage_order,
};
