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
