/* The Simbody adapter as a plugin (compare/cmp_simbody.cpp, built as
 * $(BUILD)/lib/cmp_simbody.so) and its host side in the harness
 * (compare/cmp_simbody_host.c).
 *
 * Why a plugin: Simbody 3.7's CPodes carries its own copy of an old
 * SUNDIALS (N_VSpace, N_VClone, DenseGETRF, ... 101 C symbols of
 * libSimTKmath.so), and the harness links SUNDIALS 6 for IDA. In one link
 * the first definition wins for everyone: with SUNDIALS first, CPodes
 * calls SUNDIALS 6's N_VSpace on its own vectors and aborts on an
 * assertion (nvector_SimTK.h:84, `!treatAsConst`); with Simbody first,
 * IDA would run on Simbody's old vector operations. So the harness does
 * not link Simbody: the host dlopen()s the plugin with RTLD_DEEPBIND, which
 * puts the plugin's own dependencies (libSimTK*) ahead of the global scope
 * for the symbols they look up, and both SUNDIALS copies work side by side.
 *
 * The plugin calls the harness only through the table below (the harness
 * exports none of its symbols); the host builds the mechanism
 * (cmp_mech_for_target, which needs the scene library) and frees it. */
#ifndef CMP_SIMBODY_PLUGIN_H
#define CMP_SIMBODY_PLUGIN_H

#include <stddef.h>

#include "cmp.h"
#include "cmp_mech.h"
#include "cmp_mech3.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CMP_SB_PLUGIN_VERSION 2
#define CMP_SB_PLUGIN_SYMBOL "cmp_simbody_plugin_v2"

/* What the plugin may call in the harness. */
typedef struct cmp_sb_host {
    int version; /* CMP_SB_PLUGIN_VERSION */
    int (*mech_tree)(cmp_mech *m, unsigned closable, const char *peer, char *why,
                     size_t whysize);
    void (*mech_order)(const cmp_mech *m, int *order);
    int (*mech_hinge)(const cmp_mech *m, int a, int b, int *child, int *sign);
    void (*mech_state)(const cmp_mech *m, const double *pose, double *q, double *v);
    double (*mech_unwrap)(double prev, double th);
    int (*traj_push)(cmp_traj *tr, double t, const double *q, const double *v);
    double (*cpu_seconds)(void);
    int (*fn_eval)(const braun_scene_fn *f, braun_real t, braun_real *value, braun_real *rate,
                    braun_real *accel);
    /* Spatial mechanisms (m->spatial set): cmp_mech3.h. */
    int (*mech3_tree)(cmp_mech3 *m, char *why, size_t whysize);
    void (*mech3_order)(const cmp_mech3 *m, int *order);
    void (*mech3_state)(const cmp_mech3 *m, const double *pose, double *q, double *v);
    void (*mech3_velocity0)(const cmp_mech3 *m, int b, const double *P, double *v);
} cmp_sb_host;

/* What the plugin provides: the adapter's functions on a target's
 * mechanism m (built by the host, its tree chosen by the plugin; the host
 * frees it; a spatial target's is m->spatial). n: libbraun's coordinates. Semantics as in cmp.h and
 * cmp_peer.h. */
typedef struct cmp_sb_plugin {
    int version; /* CMP_SB_PLUGIN_VERSION */
    const char *(*version_string)(void);
    int (*supports)(cmp_mech *m, char *why, size_t whysize);
    void (*run)(cmp_mech *m, int n, const cmp_spec *sp, cmp_traj *tr, cmp_outcome *out);
    int (*initial_state)(cmp_mech *m, const cmp_spec *sp, double *q, double *v,
                         double *moved_by, char *why, size_t whysize);
    double (*step_cost)(cmp_mech *m, const cmp_spec *sp, long steps, char *why,
                        size_t whysize);
} cmp_sb_plugin;

/* The plugin's one exported symbol (CMP_SB_PLUGIN_SYMBOL): its table, or
 * NULL if the host's version differs. */
typedef const cmp_sb_plugin *(*cmp_sb_plugin_fn)(const cmp_sb_host *host);

#ifdef __cplusplus
}
#endif
#endif
