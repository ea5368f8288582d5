/* Which scene element made a callback fail. The core knows callbacks, not
 * elements: its error record says "callback 'forces' failed recoverably
 * (returned 1) at t = 1". A scene's system is run through these wrappers,
 * which pass every call on and, when one fails (returns non-zero, or
 * writes a non-finite value at a finite state), ask the scene which
 * element fails there (braun_scene_file_diagnose) and keep the answer with
 * the time of the call. The cost is one indirect call per callback, and
 * the monitored run alone uses them (cpu_s is measured without). */
#include <math.h>
#include <string.h>

#include "braun_cli.h"

static int finite(const braun_real *x, int count)
{
    for (int i = 0; x && i < count; i++)
        if (!isfinite((double)x[i])) return 0;
    return 1;
}

/* After a failed call at (t, q, v): the element, if the state is finite. */
static void failed(braun_cli_guard *g, braun_real t, const braun_real *q, const braun_real *v)
{
    const int n = g->inner.n;
    if (!finite(q, n) || !finite(v, n) || !finite(&t, 1)) return;
    if (braun_scene_file_diagnose(g->scene, t, q, v, g->what, sizeof g->what) == 1) {
        g->t = (double)t;
        g->have = 1;
    }
}

static int g_mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    return g->inner.mass(t, q, M, g->inner.user);
}

static int g_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                    void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    const int rc = g->inner.forces(t, q, v, Q, g->inner.user);
    if (rc || !finite(Q, g->inner.n)) failed(g, t, q, v);
    return rc;
}

static int g_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                       braun_real *A, braun_real *b, braun_real *bv, void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    const int rc = g->inner.holonomic(t, q, v, phi, A, b, bv, g->inner.user);
    const int m = g->inner.m;
    if (rc || !finite(phi, m) || !finite(b, m) || !finite(bv, m)) failed(g, t, q, v);
    return rc;
}

static int g_nonholonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                          braun_real *A, braun_real *bv, void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    const int rc = g->inner.nonholonomic(t, q, v, phi, A, bv, g->inner.user);
    const int p = g->inner.p;
    if (rc || !finite(phi, p) || !finite(bv, p)) failed(g, t, q, v);
    return rc;
}

static int g_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                    braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    const int rc = g->inner.energy(t, q, v, E, dE_dq, dE_dv, dE_dt, g->inner.user);
    if (rc || !finite(E, 1)) failed(g, t, q, v);
    return rc;
}

static int g_power(braun_real t, const braun_real *q, const braun_real *v, braun_real *Edot,
                   void *user)
{
    braun_cli_guard *g = (braun_cli_guard *)user;
    const int rc = g->inner.power(t, q, v, Edot, g->inner.user);
    if (rc || !finite(Edot, 1)) failed(g, t, q, v);
    return rc;
}

void braun_cli_guard_wrap(braun_cli_guard *g, const braun_system *sys,
                          const braun_scene_file *scene, braun_system *out)
{
    memset(g, 0, sizeof *g);
    g->inner = *sys;
    g->scene = scene;
    *out = *sys;
    if (!scene) return;
    out->user = g;
    out->mass = sys->mass ? g_mass : NULL;
    out->forces = sys->forces ? g_forces : NULL;
    out->holonomic = sys->holonomic ? g_holonomic : NULL;
    out->nonholonomic = sys->nonholonomic ? g_nonholonomic : NULL;
    out->energy = sys->energy ? g_energy : NULL;
    out->power = sys->power ? g_power : NULL;
}

const char *braun_cli_guard_element(const braun_cli_guard *g, double t)
{
    return g->have && g->t == t ? g->what : NULL;
}
