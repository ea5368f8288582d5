/* The spatial mechanisms of the coordinate study (docs/method.md,
 * "Spatial rigid bodies"), written once for any spatial rigid body class
 * with rigid3d's description (q0 = position and quaternion, v0 = velocity
 * and world angular velocity, tensor): Euler parameters (the built-in
 * rigid3d) or natural coordinates (nc_body.h).
 *   bricard   Bricard's orthogonal 6R linkage: five bars 1 m x 0.1 m x
 *             0.1 m of 1 kg on the edges of the unit cube, six revolute
 *             joints, gravity -y: 30 rows of rank 29, one degree of freedom
 *             (the IFToMM A04 type of redundancy)
 *   governor  a flyball governor: a vertical shaft on a revolute joint, two
 *             arms hinged at its top with 5 kg point masses at their ends,
 *             a slider on the shaft tied to the arms' middles by stiff
 *             spring-dampers (k = 8e5 N/m, c = 4e4 N s/m, the IFToMM A05
 *             type of stiffness), spinning at 2π rad/s
 *   chain     N bars 1 m x 0.1 m x 0.1 m of 1 kg on spherical joints,
 *             straight along x from a ground pivot, turning about y at
 *             1 rad/s, gravity -y
 *   hinge-chain  the same on revolute joints about z, turning about z */
#ifndef BENCH_SPATIAL_MODELS_H
#define BENCH_SPATIAL_MODELS_H

#include "braun_scene.h"

typedef struct spatial_model {
    braun_scene scene;
    braun_scene_body *bodies;
    braun_scene_point *points;
    braun_scene_joint *joints;
    braun_scene_effect *effects;
    int tracked;            /* bodies whose centres the error measure follows */
} spatial_model;

/* 0, or -1 (out of memory, a build error: printed). N is used by chain. */
int spatial_model_make(spatial_model *m, const char *name, int N,
                       const braun_scene_body_class *rigid, braun_system *sys);
void spatial_model_free(spatial_model *m);

#endif
