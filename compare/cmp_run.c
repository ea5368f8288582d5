/* Method names and the dispatcher. */
#include <stdio.h>
#include <string.h>

#include "cmp.h"

static const char *const names[CMP_METHOD_COUNT] = {
    "braun", "braun-noenergy", "baumgarte", "ida-ggl", "ida-index1", "ode-rk4",
    "projection", "mujoco", "simbody",
};

const char *cmp_method_name(cmp_method_id m)
{
    return m >= 0 && m < CMP_METHOD_COUNT ? names[m] : "?";
}

int cmp_method_from_name(const char *name)
{
    for (int i = 0; i < CMP_METHOD_COUNT; i++)
        if (strcmp(name, names[i]) == 0) return i;
    return -1;
}

void cmp_run(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr, cmp_outcome *out)
{
    switch (spec->method) {
    case CMP_BRAUN:
    case CMP_BRAUN_NOENERGY: cmp_run_braun(tg, spec, tr, out); break;
    case CMP_BAUMGARTE: cmp_run_baumgarte(tg, spec, tr, out); break;
    case CMP_IDA_GGL:
    case CMP_IDA_INDEX1: cmp_run_ida(tg, spec, tr, out); break;
    case CMP_ODE_RK4: cmp_run_ode(tg, spec, tr, out); break;
    case CMP_PROJECTION: cmp_run_projection(tg, spec, tr, out); break;
    case CMP_MUJOCO: cmp_run_mujoco(tg, spec, tr, out); break;
    case CMP_SIMBODY: cmp_run_simbody(tg, spec, tr, out); break;
    default:
        memset(out, 0, sizeof *out);
        snprintf(out->status_name, sizeof out->status_name, "UNKNOWN_METHOD");
        out->status = -1;
        cmp_traj_clear(tr);
    }
}

/* The peers' integrators by name (cmp_peer_integrator), as runs.csv writes them. */
static const struct {
    int id;
    const char *name;
} peer_integrators[] = {
    {CMP_MJ_EULER, "mj-euler"},       {CMP_MJ_RK4, "mj-rk4"},
    {CMP_MJ_IMPLICIT, "mj-implicit"}, {CMP_SB_RKM, "rk-merson"},
    {CMP_SB_RKF, "rk-feldberg"},      {CMP_SB_RK3, "rk3"},
    {CMP_SB_CPODES, "cpodes"},        {CMP_SB_RKM_FIXED, "rk-merson-fixed"},
};
#define N_PEER_INTEG ((int)(sizeof peer_integrators / sizeof peer_integrators[0]))

const char *cmp_integrator_name(int integrator)
{
    if (integrator < 0) return "bdf";
    for (int i = 0; i < N_PEER_INTEG; i++)
        if (peer_integrators[i].id == integrator) return peer_integrators[i].name;
    return braun_method_name((braun_method)integrator);
}

int cmp_integrator_from_name(const char *name)
{
    if (strcmp(name, "bdf") == 0) return -1;
    for (int i = 0; i < N_PEER_INTEG; i++)
        if (strcmp(peer_integrators[i].name, name) == 0) return peer_integrators[i].id;
    const int m = braun_method_from_name(name);
    return m >= 0 ? m : -2;
}
