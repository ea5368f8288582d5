/*
 * Exact reference of a built-in model (Sec. 4: the "numerically exact"
 * solution of the minimal-coordinate equation). Closed form where the model
 * has one; otherwise classic RK4 on the minimal equation with substeps
 * <= ref_h, continued from the last time asked for, so a monotone sequence
 * of queries costs one pass. Double precision throughout.
 */
#include <math.h>
#include <stddef.h>

#include "braun_reference.h"

#define REF_H_DEFAULT 1e-4
#define REF_DIM_MAX 4

int braun_reference_init(braun_reference *ref, const braun_builtin *model,
                         double ref_h)
{
    return braun_reference_init_minimal(ref, model, model ? braun_minimal_find(model->name) : NULL,
                                        ref_h);
}

int braun_reference_init_minimal(braun_reference *ref, const braun_builtin *model,
                                 const braun_minimal *mn, double ref_h)
{
    if (!ref || !model || !mn || !mn->to_state || !mn->y0 || mn->dim < 1 || mn->dim > REF_DIM_MAX
        || (!mn->exact && !mn->rhs) || isnan(ref_h) || isinf(ref_h))
        return BRAUN_ERR_ARGUMENT;
    ref->model = model;
    ref->minimal = mn;
    ref->t = 0.0;
    for (int i = 0; i < REF_DIM_MAX; ++i)
        ref->y[i] = i < mn->dim ? mn->y0[i] : 0.0;
    ref->ref_h = ref_h > 0.0 ? ref_h : REF_H_DEFAULT;
    return BRAUN_OK;
}

/* One classic RK4 step of the minimal equation. The increment is returned
 * separately so the caller can sum it with compensation: over 10^7 substeps
 * plain summation would lose ~1e-12. */
static void rk4_increment(const braun_minimal *b, const braun_link_params *p,
                          double t, const double *y, double h, double *dy)
{
    int n = b->dim;
    double k1[REF_DIM_MAX], k2[REF_DIM_MAX], k3[REF_DIM_MAX], k4[REF_DIM_MAX];
    double tmp[REF_DIM_MAX];
    b->rhs(t, y, k1, p);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    b->rhs(t + 0.5 * h, tmp, k2, p);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    b->rhs(t + 0.5 * h, tmp, k3, p);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * k3[i];
    b->rhs(t + h, tmp, k4, p);
    for (int i = 0; i < n; ++i)
        dy[i] = h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

int braun_reference_eval(braun_reference *ref, double t, double *q, double *v)
{
    if (!ref || !ref->model || !ref->minimal || !q || !v || !isfinite(t))
        return BRAUN_ERR_ARGUMENT;
    const braun_minimal *b = ref->minimal;
    const braun_link_params *p = ref->model->sys.user;
    int n = b->dim;

    if (b->exact) {
        double y[REF_DIM_MAX];
        int st = b->exact(t, y, p);
        if (st < 0) return BRAUN_ERR_ARGUMENT;
        for (int i = 0; i < n; ++i) ref->y[i] = y[i];
        ref->t = t;
    } else {
        if (t < ref->t) return BRAUN_ERR_TIME;
        double span = t - ref->t;
        /* A count a long holds (and a run could finish): beyond it the
         * conversion would be undefined. */
        const double want = ceil(span / ref->ref_h);
        if (!(want <= 1e15)) return BRAUN_ERR_TOO_MANY_STEPS;
        long steps = (long)want;
        /* Equal substeps landing exactly on t; each substep's start is
         * t0 + i·h, never an accumulated sum. */
        double t0 = ref->t, h = steps > 0 ? span / (double)steps : 0.0;
        double comp[REF_DIM_MAX] = {0.0};
        for (long i = 0; i < steps; i++) {
            double dy[REF_DIM_MAX];
            rk4_increment(b, p, t0 + (double)i * h, ref->y, h, dy);
            for (int k = 0; k < n; ++k) { /* Kahan summation */
                double add = dy[k] - comp[k];
                double sum = ref->y[k] + add;
                comp[k] = (sum - ref->y[k]) - add;
                ref->y[k] = sum;
            }
        }
        ref->t = t;
    }
    b->to_state(ref->y, q, v, p);
    return BRAUN_OK;
}
