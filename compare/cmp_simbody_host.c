/* simbody, the harness's side: loads the Simbody adapter plugin
 * ($(BUILD)/lib/cmp_simbody.so, compare/cmp_simbody.cpp) with
 * RTLD_DEEPBIND on first use and forwards cmp.h's and cmp_peer.h's Simbody
 * functions to it (why a plugin: compare/cmp_simbody_plugin.h). The
 * feature macro (dlopen's RTLD_DEEPBIND) is confined to this file.
 *
 * The plugin's path: the environment's CMP_SIMBODY_PLUGIN, else the one
 * the build wrote in (CMP_SIMBODY_PLUGIN_PATH). Without it every Simbody
 * run is a failed row NOT_BUILT whose detail says why (dlerror()). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_mech.h"
#include "cmp_mech3.h"
#include "cmp_peer.h"
#include "cmp_simbody_plugin.h"

#if defined(CMP_HAVE_SIMBODY) && !defined(CMP_SIMBODY_PLUGIN_PATH)
#define CMP_SIMBODY_PLUGIN_PATH "build/lib/cmp_simbody.so"
#endif

/* AddressSanitizer refuses RTLD_DEEPBIND (it ends the process): a
 * sanitizer build does not load the plugin, its Simbody rows say why. */
#if defined(__SANITIZE_ADDRESS__)
#define CMP_SB_NO_DEEPBIND 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CMP_SB_NO_DEEPBIND 1
#endif
#endif

#ifdef CMP_HAVE_SIMBODY
static const cmp_sb_host host = {
    CMP_SB_PLUGIN_VERSION, cmp_mech_tree,  cmp_mech_order,  cmp_mech_hinge, cmp_mech_state,
    cmp_mech_unwrap,       cmp_traj_push, cmp_cpu_seconds, braun_scene_fn_eval,
    cmp_mech3_tree,        cmp_mech3_order, cmp_mech3_state, cmp_mech3_velocity0,
};

static const cmp_sb_plugin *plugin;
static char load_error[160];

/* The plugin, loaded once; NULL with load_error set. */
static const cmp_sb_plugin *load(void)
{
    if (plugin || load_error[0]) return plugin;
#ifdef CMP_SB_NO_DEEPBIND
    snprintf(load_error, sizeof load_error,
             "no Simbody plugin: it needs dlopen(RTLD_DEEPBIND), which AddressSanitizer refuses");
    return NULL;
#endif
    const char *path = getenv("CMP_SIMBODY_PLUGIN");
    if (!path || !*path) path = CMP_SIMBODY_PLUGIN_PATH;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (!h) {
        const char *e = dlerror();
        snprintf(load_error, sizeof load_error, "no Simbody plugin: %s", e ? e : path);
        return NULL;
    }
    void *sym = dlsym(h, CMP_SB_PLUGIN_SYMBOL);
    cmp_sb_plugin_fn fn = NULL;
    if (sym) memcpy(&fn, &sym, sizeof fn);
    const cmp_sb_plugin *p = fn ? fn(&host) : NULL;
    if (!p || p->version != CMP_SB_PLUGIN_VERSION) {
        snprintf(load_error, sizeof load_error, "%s: not a Simbody plugin of version %d", path,
                 CMP_SB_PLUGIN_VERSION);
        dlclose(h);
        return NULL;
    }
    plugin = p;
    return plugin;
}
#endif

/* The plugin and the target's mechanism; NULL with why. */
static const cmp_sb_plugin *begin(const cmp_target *tg, cmp_mech *m, char *why, size_t whysize)
{
    memset(m, 0, sizeof *m);
#ifdef CMP_HAVE_SIMBODY
    const cmp_sb_plugin *p = load();
    if (!p) {
        snprintf(why, whysize, "%s", load_error);
        return NULL;
    }
    if (cmp_target_is_spatial(tg)) {
        m->spatial = calloc(1, sizeof *m->spatial);
        if (!m->spatial) {
            snprintf(why, whysize, "out of memory");
            return NULL;
        }
        if (cmp_mech3_for_target(tg, m->spatial, why, whysize)) {
            cmp_mech_free(m);
            return NULL;
        }
        m->n = m->spatial->n;
        return p;
    }
    if (cmp_mech_for_target_ex(tg, CMP_MECH_TORQUE, m, why, whysize)) return NULL;
    return p;
#else
    (void)tg;
    snprintf(why, whysize, "built without Simbody");
    return NULL;
#endif
}

void cmp_run_simbody(const cmp_target *tg, const cmp_spec *sp, cmp_traj *tr, cmp_outcome *out)
{
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    cmp_mech m;
    char why[sizeof out->detail - 12] = ""; /* room for "at t = 0 (...)" */
    const cmp_sb_plugin *p = begin(tg, &m, why, sizeof why);
    if (!p) {
#ifdef CMP_HAVE_SIMBODY
        const int built = load() != NULL;
#else
        const int built = 0;
#endif
        snprintf(out->status_name, sizeof out->status_name, "%s",
                 built ? "UNSUPPORTED" : "NOT_BUILT");
        snprintf(out->detail, sizeof out->detail, "at t = 0 (%s)", why);
        out->status = -1;
        return;
    }
    p->run(&m, tg->sys.n, sp, tr, out);
    cmp_mech_free(&m);
}

int cmp_simbody_supports(const cmp_target *tg, char *why, size_t whysize)
{
    cmp_mech m;
    const cmp_sb_plugin *p = begin(tg, &m, why, whysize);
    if (!p) return 0;
    const int ok = p->supports(&m, why, whysize);
    cmp_mech_free(&m);
    return ok;
}

const char *cmp_simbody_version(void)
{
#ifdef CMP_HAVE_SIMBODY
    const cmp_sb_plugin *p = load();
    return p ? p->version_string() : NULL;
#else
    return NULL;
#endif
}

int cmp_simbody_initial_state(const cmp_target *tg, const cmp_spec *sp, double *q, double *v,
                              double *moved_by, char *why, size_t whysize)
{
    cmp_mech m;
    const cmp_sb_plugin *p = begin(tg, &m, why, whysize);
    if (!p) return -1;
    const int rc = p->initial_state(&m, sp, q, v, moved_by, why, whysize);
    cmp_mech_free(&m);
    return rc;
}

double cmp_simbody_step_cost(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                             size_t whysize)
{
    cmp_mech m;
    const cmp_sb_plugin *p = begin(tg, &m, why, whysize);
    if (!p) return NAN;
    const double c = p->step_cost(&m, sp, steps, why, whysize);
    cmp_mech_free(&m);
    return c;
}
