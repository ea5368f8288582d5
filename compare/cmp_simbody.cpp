// simbody: placeholder until the adapter lands (see below).
extern "C" {
#include "cmp.h"
#include "cmp_mech.h"
#include "cmp_peer.h"
}
#include <cmath>
#include <cstdio>
#include <cstring>

extern "C" void cmp_run_simbody(const cmp_target *tg, const cmp_spec *sp, cmp_traj *tr,
                                cmp_outcome *out)
{
    (void)tg;
    (void)sp;
    std::memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    std::snprintf(out->status_name, sizeof out->status_name, "NOT_BUILT");
    out->status = -1;
}

extern "C" int cmp_simbody_supports(const cmp_target *tg, char *why, size_t whysize)
{
    (void)tg;
    std::snprintf(why, whysize, "built without Simbody");
    return 0;
}

extern "C" const char *cmp_simbody_version(void)
{
    return nullptr;
}
