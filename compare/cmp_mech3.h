/* A spatial target's mechanism as a peer engine sees it (cmp_mech3.c): the
 * spatial counterpart of cmp_mech.h. From a spatial scene (dim 3):
 *   bodies   rigid3d: a rigid body with mass and inertia tensor, its
 *            frame at the centre of mass (libbraun's body frame);
 *            particle3d with mass: a point mass (its frame: the world's
 *            orientation at the start);
 *   joints   spherical, revolute3d and prismatic3d (not driven), weld;
 *            a particle only on spherical joints (which hold it to the
 *            other body's point: a peer welds it there);
 *   effects  gravity, point-to-point spring-damper, torsion3d on a
 *            revolute3d joint of the tree.
 * Anything else (particles, other joints, driven joints, applied torques)
 * is refused with a sentence that names it: the peer's row then says why.
 *
 * The tree (cmp_mech3_tree): joint-coordinate peers (MuJoCo's kinematic
 * tree) need a spanning tree; bodies no joint reaches become free roots,
 * the other joints close loops (the peer's equality constraints).
 *
 * libbraun's coordinates of a rigid3d body are its centre of mass and its
 * Euler parameters p (w, x, y, z), its velocities their time derivatives:
 * ṗ = ½ E(p)ᵀ ω for the world angular velocity ω (cmp_mech3_state); a
 * particle3d's are its position and velocity. */
#ifndef CMP_MECH3_H
#define CMP_MECH3_H

#include <stddef.h>

#include "cmp.h"

typedef struct cmp_body3 {
    char name[40];
    double mass;
    double inertia[6];        /* I_xx, I_yy, I_zz, I_xy, I_xz, I_yz (body frame, kg m²) */
    double pos[3], quat[4];   /* initial centre of mass, orientation (w, x, y, z) */
    double vel[3], omega[3];  /* initial velocity of the centre, world angular velocity */
    int iq;                   /* first coordinate in libbraun's q */
    int point_mass;           /* 1: particle3d (q: x, y, z; no orientation) */
    int parent, joint;        /* the tree: parent body (-1 ground), joint (-1: free root) */
} cmp_body3;

typedef enum cmp_joint3_kind {
    CMP_J3_SPHERICAL = 0,     /* P_a = P_b */
    CMP_J3_REVOLUTE,          /* P_a = P_b, turning about axis (a's frame) = axis_b (b's) */
    CMP_J3_WELD,              /* P_a = P_b, the frames keep their initial relative orientation */
    CMP_J3_PRISMATIC          /* P_a on the line through P_b along axis_b (b's frame); the
                               * frames keep their relative orientation (axis: the same
                               * direction in a's frame) */
} cmp_joint3_kind;

typedef struct cmp_joint3 {
    int kind;
    int a, b;                 /* bodies, -1: ground */
    double pa[3], pb[3];      /* points in their bodies' frames (world on the ground) */
    double axis[3], axis_b[3];/* revolute, prismatic: the unit axis in a's and in b's frame */
    int tree;                 /* set by cmp_mech3_tree: 1 if it is a tree joint */
    char name[40];
} cmp_joint3;

/* Joint J's point and axis on body b's side (b is J->a or J->b): what the
 * peers' tree joints and loop closures put on each body. */
static inline void cmp_joint3_side(const cmp_joint3 *J, int b, const double **p,
                                   const double **axis)
{
    const int is_a = b == J->a;
    *p = is_a ? J->pa : J->pb;
    *axis = is_a ? J->axis : J->axis_b;
}

typedef enum cmp_force3_kind {
    CMP_F3_GRAVITY = 0,       /* g on every mass */
    CMP_F3_SPRING,            /* k (|P_b - P_a| - rest) and c d|P_b - P_a|/dt along P_b - P_a */
    CMP_F3_TORSION            /* on joint `joint`'s angle θ (b relative to a about the axis,
                               * 0 initially): -k (θ - rest) - c θ' */
} cmp_force3_kind;

typedef struct cmp_force3 {
    int kind;
    int a, b;                 /* spring: bodies of the points */
    int joint;                /* torsion */
    double pa[3], pb[3], g[3], k, c, rest;
} cmp_force3;

typedef struct cmp_mech3 {
    int nbodies, njoints, nforces, n;
    cmp_body3 *bodies;
    cmp_joint3 *joints;
    cmp_force3 *forces;
} cmp_mech3;

/* 1 if the target is a spatial scene (its peers need cmp_mech3). */
int cmp_target_is_spatial(const cmp_target *tg);
/* The mechanism of a spatial target. 0, or -1 with the reason in why. */
int cmp_mech3_for_target(const cmp_target *tg, cmp_mech3 *m, char *why, size_t whysize);
void cmp_mech3_free(cmp_mech3 *m);
/* The spanning tree: from the ground, repeatedly the first revolute or
 * prismatic, then weld, then spherical joint that reaches a new body;
 * bodies no joint reaches are free roots. 0 (every other joint closes a
 * loop). */
int cmp_mech3_tree(cmp_mech3 *m, char *why, size_t whysize);
/* Bodies in tree order (parents first), nbodies entries. */
void cmp_mech3_order(const cmp_mech3 *m, int *order);

/* libbraun's q, v (n each) from the bodies' poses: pose[13 b ..] = centre
 * (3), quaternion (4, w first), velocity of the centre (3), world angular
 * velocity (3); a particle's quaternion and ω are ignored. Each quaternion
 * is taken with the sign of the body's
 * entry in q on input (a peer's q and -q are the same rotation; q holds
 * the previous sample). */
void cmp_mech3_state(const cmp_mech3 *m, const double *pose, double *q, double *v);

/* Small rotation helpers (quaternions w, x, y, z). */
void cmp_quat_rotate(const double *p, const double *x, double *y);     /* y = R(p) x */
void cmp_quat_rotate_inv(const double *p, const double *x, double *y); /* y = R(p)ᵀ x */
void cmp_quat_mul(const double *a, const double *b, double *c);        /* c = a b */
/* World position of point p of body b at its initial pose (b = -1: p). */
void cmp_mech3_point0(const cmp_mech3 *m, int b, const double *p, double *P);
/* World velocity of the material point of body b (-1: ground, 0) at world
 * position P, initial. */
void cmp_mech3_velocity0(const cmp_mech3 *m, int b, const double *P, double *v);

#endif
