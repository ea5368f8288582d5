/* A target's mechanism as a peer engine sees it (cmp_mech.c): rigid links
 * with mass and inertia, joints between points of links, applied forces,
 * and how libbraun's coordinates q, v follow from the links' poses. MuJoCo
 * (cmp_mujoco.c) and Simbody (cmp_simbody.cpp) build their models from it,
 * so both get the same mechanism from the same scene file.
 *
 * From a planar scene (braun_scene): a rigid body is a link; a particle
 * with mass a point-mass link; a rod a uniform link between its ends
 * (natural coordinates become rigid bodies); a massless particle where
 * rods meet is the end of the first of them, the others pinned to it.
 * Joints: revolute, distance, slider (line on any link or the ground),
 * angle (a relative angle, fixed or driven), knife edge. Effects:
 * gravity, point-to-point spring-damper, rotational spring-damper, motor.
 * Anything else (spatial scenes, prismatic joints, forces of time) is
 * refused with a sentence that names it: the peer's row then says why.
 *
 * The tree (cmp_mech_tree): peers with joint coordinates (MuJoCo's
 * kinematic tree, Simbody's mobilizers) need a spanning tree of the links;
 * the other joints close loops, as the peer's equality constraints. */
#ifndef CMP_MECH_H
#define CMP_MECH_H

#include <stddef.h>

#include "cmp.h"

typedef struct cmp_link {
    char name[40];
    double mass, inertia;       /* kg; kg m² about the centre of mass (0: a point mass) */
    double x, y, th;            /* initial pose of the centre-of-mass frame */
    double vx, vy, w;           /* initial velocity of the centre of mass, angular velocity */
    int point_mass;             /* 1: a particle (no rotational degree of freedom) */
    /* The tree (cmp_mech_tree): parent link (-1: ground) and the joint to
     * it (-1: a free planar root). */
    int parent, joint;
} cmp_link;

typedef enum cmp_mjoint_kind {
    CMP_MJ_REVOLUTE = 0, /* P_a = P_b */
    CMP_MJ_SLIDER,       /* P_a (on link a) on the line through P_b along axis (link b's frame) */
    CMP_MJ_DISTANCE,     /* |P_b - P_a| = length */
    CMP_MJ_ANGLE,        /* θ_b - θ_a = value, or drive(t) when driven */
    CMP_MJ_KNIFE         /* velocity of P_a across axis (link a's frame) is 0 */
} cmp_mjoint_kind;

typedef struct cmp_mjoint {
    int kind;
    int a, b;                   /* links, -1: ground */
    double pa[2], pb[2];        /* points in their links' frames (world on the ground) */
    double axis[2];             /* unit: slider line (b's frame), knife blade (a's frame) */
    double length;              /* distance */
    double value;               /* angle: θ_b - θ_a when not driven */
    int driven;
    braun_scene_fn drive;       /* angle: θ_b - θ_a = drive(t) */
    int tree;                   /* set by cmp_mech_tree: the tree joint of link `b`
                                 * (revolute, distance) or `a` (slider), or 0 */
    char name[40];
} cmp_mjoint;

typedef enum cmp_mforce_kind {
    CMP_MF_GRAVITY = 0,  /* g on every mass */
    CMP_MF_SPRING,       /* k (|P_b - P_a| - rest) and c d|P_b - P_a|/dt along P_b - P_a */
    CMP_MF_TORSION,      /* k (θ_b - θ_a - rest), c (ω_b - ω_a), on b, minus on a */
    CMP_MF_MOTOR,        /* τ = tau0 (1 - (ω_a - ω_b)/omega0) on a (rotor), -τ on b */
    CMP_MF_TORQUE        /* τ = f(t) on a, -τ on b: a constant f always, any other
                          * only with CMP_MECH_TORQUE (cmp_mech_for_target_ex);
                          * MuJoCo's adapter takes the constant one (an actuator) */
} cmp_mforce_kind;

typedef struct cmp_mforce {
    int kind;
    int a, b;
    double pa[2], pb[2];
    double g[2], k, c, rest, tau0, omega0;
    braun_scene_fn f;           /* torque: τ(t) */
} cmp_mforce;

/* Coordinate i of libbraun's q: x or y of a point fixed on a link (its
 * centre: p = 0), or a link's angle plus an offset. */
typedef enum cmp_mout_kind { CMP_OUT_X = 0, CMP_OUT_Y, CMP_OUT_ANGLE } cmp_mout_kind;
typedef struct cmp_mout {
    int kind, link;
    double p[2], offset;
} cmp_mout;

struct cmp_mech3;

typedef struct cmp_mech {
    int nlinks, njoints, nforces, n;
    cmp_link *links;
    cmp_mjoint *joints;
    cmp_mforce *forces;
    cmp_mout *out;              /* n */
    /* A spatial target's mechanism instead (cmp_mech3.h; nothing above is
     * set but n): what the Simbody host hands its plugin. Freed with m. */
    struct cmp_mech3 *spatial;
} cmp_mech;

/* The mechanism of a target: its scene file (built-in models: the scene
 * file data/NAME.json that reproduces them, checked to start from the same
 * state). 0, or -1 with the reason in why (what cannot be expressed). */
int cmp_mech_for_target(const cmp_target *tg, cmp_mech *m, char *why, size_t whysize);
void cmp_mech_free(cmp_mech *m);
/* As cmp_mech_for_target, with elements beyond those every peer takes
 * (flags; 0: exactly cmp_mech_for_target): CMP_MECH_TORQUE, an applied
 * torque of time (scene effect "torque") as CMP_MF_TORQUE (Simbody). */
#define CMP_MECH_TORQUE 1u
int cmp_mech_for_target_ex(const cmp_target *tg, unsigned flags, cmp_mech *m, char *why,
                           size_t whysize);

/* Which joint kinds a peer can use to close a loop (bits 1 << kind). */
#define CMP_MJ_BIT(kind) (1u << (kind))
/* Choose the spanning tree: from the ground, repeatedly the first joint of
 * the highest priority (slider, revolute, distance) that reaches a new link
 * (a slider: from its line's link to its point's); links no joint reaches
 * become free planar roots. Every other joint must be of a kind in
 * `closable` (angle joints: on a link's revolute tree joint; knife edges:
 * closable). 0, or -1 with the joint that cannot be expressed in why. */
int cmp_mech_tree(cmp_mech *m, unsigned closable, const char *peer, char *why, size_t whysize);
/* Links in tree order (parents first), nlinks entries. */
void cmp_mech_order(const cmp_mech *m, int *order);
/* Items 0..n-1 with each after its parent (-1: a root), n entries; the
 * parent of item i is the int at (const char *)parent + i·stride (a field
 * of an array of structs: cmp_mech_order, cmp_mech3_order). */
void cmp_parents_first(int n, const int *parent, size_t stride, int *order);

/* The revolute tree joint between links a and b (-1: ground): its index,
 * its child link and the sign of θ_b - θ_a in the hinge's coordinate
 * (child angle - parent angle); -1 if there is none. */
int cmp_mech_hinge(const cmp_mech *m, int a, int b, int *child, int *sign);

/* libbraun's q, v (n each) from the links' poses: pose[6 l ..] = x, y, θ,
 * vx, vy, ω of link l's centre of mass (θ continuous: see cmp_mech_unwrap). */
void cmp_mech_state(const cmp_mech *m, const double *pose, double *q, double *v);
/* The angle th + 2πk nearest to prev (a peer's angle from a rotation). */
double cmp_mech_unwrap(double prev, double th);
/* World position of point p of link l at pose (l = -1: p itself). */
void cmp_mech_point(const double *pose, int l, const double *p, double *xy);

#endif
