/* What the peer adapters share with the study and the tests beyond
 * cmp.h's runners (cmp_mujoco.c, cmp_simbody.cpp). */
#ifndef CMP_PEER_H
#define CMP_PEER_H

#include <stddef.h>

#include "cmp.h"
#include "cmp_mech.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The MJCF text of a mechanism (its tree chosen) for run settings sp:
 * *xml malloc'd, *has_clock 1 when a driven angle needs the clock body.
 * 0, or -1 with the reason in why. */
int cmp_mujoco_mjcf(const cmp_mech *m, const cmp_spec *sp, const char *name, char **xml,
                    int *has_clock, char *why, size_t whysize);

/* CPU seconds per step of the peer on the target with settings sp (MuJoCo:
 * mj_step; Simbody: one step of its integrator at a fixed step sp->h),
 * averaged over `steps` steps from the initial state; NaN with why. */
double cmp_mujoco_step_cost(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                            size_t whysize);

/* Simbody (cmp_simbody.cpp): the same cost with its integrator sp->integrator
 * (rk-merson runs become its fixed step) at a fixed step sp->h, from the
 * initial state, `steps` steps; NaN with why. */
double cmp_simbody_step_cost(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                             size_t whysize);

/* Simbody's initial state of a target as libbraun's q, v (n each): the
 * model's mobilizer coordinates set from the links' poses, mapped back
 * through cmp_mech_state (the test that the model starts where the target
 * does). With moved_by and sp: how far Integrator::initialize() with the
 * settings sp moved the mobilizers' q, u (max abs), else NaN. 0, or -1
 * with why (not expressible, a Simbody error, or built without it). */
int cmp_simbody_initial_state(const cmp_target *tg, const cmp_spec *sp, double *q, double *v,
                              double *moved_by, char *why, size_t whysize);

#ifdef __cplusplus
}
#endif
#endif
