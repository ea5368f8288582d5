/* IDA+KLU for the scaling study: the compare harness's GGL form with the
 * analytic sparse Jacobian from the scene's structure (cmp_ida_klu_run). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "scaling.h"

int sc_ida_run(const sc_scene *s, double T, double rtol, double reg, long max_steps,
               int samples, double *q_out, sc_ida_result *res)
{
    memset(res, 0, sizeof *res);
    const braun_system *dense = &s->file->sys;
    cmp_ida_problem pb = {dense, s->file->q0, s->file->v0, &s->file->scene};
    cmp_ida_run_opts o;
    memset(&o, 0, sizeof o);
    o.t_end = T;
    o.rtol = o.atol = rtol;
    o.jac = CMP_JAC_ANALYTIC;
    /* The multipliers out of the error test (their Newton test only): with
     * λ, μ held to q's absolute tolerance IDA fails at t = 0 from N = 30 on
     * the tilted chain (docs/compare.md, the "tuned" setting). */
    o.alg_atol = 1e8;
    /* Redundant rows make the Newton matrix singular: Φ - ελ then. */
    o.reg = reg;
    o.max_steps = max_steps;
    double *t_out = NULL;
    if (samples > 0) {
        t_out = malloc((size_t)samples * sizeof *t_out);
        if (!t_out) return -1;
        for (int k = 1; k <= samples; k++) t_out[k - 1] = T * k / samples;
        o.n_out = samples;
        o.t_out = t_out;
        o.q_out = q_out;
    }
    cmp_ida_run_result r;
    int st = cmp_ida_klu_run(&pb, &o, &r);
    res->ok = st == 0 && r.success;
    if (!res->ok)
        fprintf(stderr, "braun-scaling: IDA: %s at t = %g: %s\n", r.status, r.t_reached, r.detail);
    res->steps = r.steps;
    res->rhs_evals = r.res_evals;
    res->jac_evals = r.jac_evals;
    /* Setup (pattern, consistent values) is counted: it is part of a run. */
    res->cpu_s = r.cpu_setup_s + r.cpu_solve_s;
    res->t_reached = r.t_reached;
    free(t_out);
    return res->ok ? 0 : -1;
}
