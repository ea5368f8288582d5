/* The built-in classes, in the order the scene format documents them: the
 * scene-file reader looks types up here (and in a program's own classes,
 * braun_scene_load_ex), and lists these names when a type is unknown. A
 * new built-in type is a file of its own (scene_revolute.c, ...) and one
 * line here. Planar classes first, then the spatial ones. */
#include "scene_internal.h"

const braun_scene_body_class *const braun_scene_body_classes[] = {
    &braun_scene_body_rigid, &braun_scene_body_particle, &braun_scene_body_rigid3d,
    &braun_scene_body_particle3d, NULL};

const braun_scene_joint_class *const braun_scene_joint_classes[] = {
    &braun_scene_joint_revolute,    &braun_scene_joint_distance,   &braun_scene_joint_slider,
    &braun_scene_joint_prismatic,   &braun_scene_joint_angle,      &braun_scene_joint_knife,
    &braun_scene_joint_spherical,   &braun_scene_joint_revolute3d, &braun_scene_joint_prismatic3d,
    &braun_scene_joint_cylindrical, &braun_scene_joint_universal,  &braun_scene_joint_weld,
    &braun_scene_joint_point_line,  &braun_scene_joint_point_plane, NULL};

const braun_scene_effect_class *const braun_scene_effect_classes[] = {
    &braun_scene_effect_gravity,    &braun_scene_effect_spring,    &braun_scene_effect_torsion,
    &braun_scene_effect_force,      &braun_scene_effect_torque,    &braun_scene_effect_motor,
    &braun_scene_effect_body_force, &braun_scene_effect_torque3d,  &braun_scene_effect_body_torque,
    &braun_scene_effect_torsion3d,  &braun_scene_effect_motor3d,   NULL};
