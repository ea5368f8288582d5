/* ode-rk4: the minimal-coordinate equation (Eq. 24; θ'' + (7g/6l)cos θ = 0)
 * with the same fixed-step classic RK4, lifted to q, v by minimal_to_state
 * at the output times (the paper's "ODE solution ... obtained using the
 * same fixed step RK4 solver", Sec. 4.1). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cmp.h"
#include "braun_reference.h"

#define ODE_DIM_MAX 4

void cmp_run_ode(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                 cmp_outcome *out)
{
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    const braun_builtin *b = tg->builtin;
    if (!b || !braun_minimal_find(b->name)->rhs || !braun_minimal_find(b->name)->to_state || braun_minimal_find(b->name)->dim > ODE_DIM_MAX) {
        snprintf(out->status_name, sizeof out->status_name, "NO_MINIMAL_EQUATION");
        out->status = -1;
        return;
    }
    const int k = braun_minimal_find(b->name)->dim, n = tg->sys.n;
    const void *prm = b->sys.user;
    double y[ODE_DIM_MAX], k1[ODE_DIM_MAX], k2[ODE_DIM_MAX], k3[ODE_DIM_MAX],
        k4[ODE_DIM_MAX], w[ODE_DIM_MAX];
    double q[BRAUN_MODEL_MAX_N], v[BRAUN_MODEL_MAX_N];
    for (int i = 0; i < k; i++) y[i] = braun_minimal_find(b->name)->y0[i];
    const double h = spec->h;
    const long steps = (long)ceil(spec->T / h - 1e-9 * spec->T / h);
    const long every = cmp_every(spec->dt_out, h);
    double t = 0;
    braun_minimal_find(b->name)->to_state(y, q, v, prm);
    cmp_traj_push(tr, t, q, v);
    for (long s = 1; s <= steps; s++) {
        /* t_s = s·h (the last step lands on T), as braun_integrate does. */
        const double t1 = s == steps ? spec->T : (double)s * h, hs = t1 - t;
        braun_minimal_find(b->name)->rhs(t, y, k1, prm);
        for (int i = 0; i < k; i++) w[i] = y[i] + 0.5 * hs * k1[i];
        braun_minimal_find(b->name)->rhs(t + 0.5 * hs, w, k2, prm);
        for (int i = 0; i < k; i++) w[i] = y[i] + 0.5 * hs * k2[i];
        braun_minimal_find(b->name)->rhs(t + 0.5 * hs, w, k3, prm);
        for (int i = 0; i < k; i++) w[i] = y[i] + hs * k3[i];
        braun_minimal_find(b->name)->rhs(t1, w, k4, prm);
        for (int i = 0; i < k; i++) y[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        t = t1;
        out->counts.steps++;
        out->counts.rhs_evals += 4;
        int finite = 1;
        for (int i = 0; i < k; i++) finite &= isfinite(y[i]) != 0;
        if (!finite) {
            snprintf(out->status_name, sizeof out->status_name, "DIVERGED");
            out->status = -1;
            out->t_reached = t;
            return;
        }
        if (s % every == 0 || s == steps) {
            braun_minimal_find(b->name)->to_state(y, q, v, prm);
            cmp_traj_push(tr, t, q, v);
        }
    }
    (void)n;
    out->t_reached = t;
    snprintf(out->status_name, sizeof out->status_name, "OK");
}
