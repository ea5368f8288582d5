/* MuJoCo on spatial mechanisms (cmp_mujoco3.c), and what it shares with
 * the planar writer (cmp_mujoco.c). Only with CMP_HAVE_MUJOCO. */
#ifndef CMP_MUJOCO3_H
#define CMP_MUJOCO3_H

#include <stddef.h>

#include "cmp.h"
#include "cmp_mech3.h"
#include "cmp_text.h"

#ifdef CMP_HAVE_MUJOCO
#include <mujoco/mujoco.h>

/* cmp_mujoco.c: the opening of a model (<mujoco>, compiler, options with
 * gravity g[3]) and an equality's softness (solref, solimp) from sp. */
void cmp_mujoco_header(cmp_text *t, const cmp_spec *sp, const char *name, const double *g);
void cmp_mujoco_solparams(cmp_text *t, const cmp_spec *sp);
/* The sites of tendons (springs, distance closures): a point of a body
 * (-1: the world) in its frame, collected before the bodies are written;
 * add returns its index (its name S<index>) or -1 when full; put writes
 * the sites of one body. dim: 2 (z = 0) or 3 coordinates in p. */
#define CMP_MJ_MAX_SITES 256
typedef struct cmp_mj_sites {
    int body[CMP_MJ_MAX_SITES];
    double p[CMP_MJ_MAX_SITES][3];
    int n;
} cmp_mj_sites;
int cmp_mujoco_add_site(cmp_mj_sites *S, int body, const double *p, int dim);
void cmp_mujoco_put_sites(cmp_text *t, const cmp_mj_sites *S, int body, int indent);

/* The spatial mechanism of a target, its tree chosen, checked against what
 * the MJCF writer takes. 0, or -1 with why. */
int cmp_mujoco3_prepare(const cmp_target *tg, cmp_mech3 *m, char *why, size_t whysize);
/* Its MJCF text (malloc'd) for settings sp. 0, or -1 with why. */
int cmp_mujoco3_mjcf(const cmp_mech3 *m, const cmp_spec *sp, const char *name, char **xml,
                     char *why, size_t whysize);
/* qvel of the tree's joints from the bodies' initial velocities. */
void cmp_mujoco3_qvel(const cmp_mech3 *m, const mjModel *mm, mjData *d);
/* pose (13 per body, cmp_mech3_state) of every body from d (kinematics and
 * velocities computed here); body[b]: MuJoCo's id of body b. */
void cmp_mujoco3_pose(const cmp_mech3 *m, const mjModel *mm, mjData *d, const int *body,
                      double *pose);
#endif

#endif
