/* A spatial rigid body in natural coordinates (García de Jalón): q = (r,
 * u, v, w), the centre of mass and the three body axes in the world, 12
 * coordinates kept a rigid frame by 6 rows of its own. Not a built-in class:
 * the measurement behind the choice of rigid3d's Euler parameters
 * (docs/method.md, "Spatial rigid bodies") uses it through the same class
 * interface (braun_scene.h), which is all another formulation needs. Its
 * description is rigid3d's (q0: position and quaternion, v0: velocity and
 * world angular velocity, tensor), so one scene runs with either class. */
#ifndef BENCH_NC_BODY_H
#define BENCH_NC_BODY_H

#include "braun_scene.h"

extern const braun_scene_body_class bench_body_nc;

#endif
