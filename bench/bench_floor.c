/* The floor: classic RK4 on a built-in model's minimal-coordinate equation
 * (Eq. 24 for the slider-crank), the cheapest ODE step that simulates the
 * same motion. Kept in its own file so that the calls stay calls (callgrind
 * toggles on these functions by name). */
#include "bench.h"
#include "braun_reference.h"

void bench_floor_rhs(const braun_builtin *b, double t, const double *y, double *dydt)
{
    braun_minimal_find(b->name)->rhs(t, y, dydt, (const braun_link_params *)b->sys.user);
}

void bench_floor_step(const braun_builtin *b, double t, double h, double *y)
{
    /* The same tableau as libbraun's RK4 (src/core/braun_tableau.c), written out. */
    const braun_link_params *prm = (const braun_link_params *)b->sys.user;
    const int d = braun_minimal_find(b->name)->dim;
    double k1[4], k2[4], k3[4], k4[4], w[4];
    braun_minimal_find(b->name)->rhs(t, y, k1, prm);
    for (int i = 0; i < d; i++) w[i] = y[i] + 0.5 * h * k1[i];
    braun_minimal_find(b->name)->rhs(t + 0.5 * h, w, k2, prm);
    for (int i = 0; i < d; i++) w[i] = y[i] + 0.5 * h * k2[i];
    braun_minimal_find(b->name)->rhs(t + 0.5 * h, w, k3, prm);
    for (int i = 0; i < d; i++) w[i] = y[i] + h * k3[i];
    braun_minimal_find(b->name)->rhs(t + h, w, k4, prm);
    for (int i = 0; i < d; i++)
        y[i] += h / 6.0 * k1[i] + h / 3.0 * k2[i] + h / 3.0 * k3[i] + h / 6.0 * k4[i];
}
