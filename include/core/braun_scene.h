/*
 * libbraun scenes: planar mechanisms described as data, built into the
 * callbacks of braun_system (braun.h) with analytic derivatives.
 *
 * A scene is an immutable description — arrays of small structs for bodies,
 * points, rods, joints, knife edges and effects — plus a few sizes that
 * braun_scene_build() derives from it. The system's callbacks loop over the
 * elements; each element type lives in its own file under src/scene/ and
 * contributes rows of Φ_q, A_q, b_q, b_qv (holonomic), Φ_v, A_vv, b_vv
 * (nonholonomic), forces Q, energy E, ∂E/∂q, ∂E/∂v and input power Ė.
 *
 * Coordinates (SI units throughout):
 *   rigid body  x, y, θ   (centre of mass, angle from the x axis), M = diag(m, m, I)
 *   particle    x, y      (a point mass; mass 0 allowed when rods carry it)
 *   rod         none of its own: a uniform rod between two particles or
 *               ground points in natural coordinates; its kinetic energy
 *               (m/6)(|v_a|² + v_a·v_b + |v_b|²) adds blocks m/3, m/6 to M.
 * Every element type has a constant mass matrix, so a built scene always
 * sets BRAUN_MASS_CONSTANT.
 *
 * Only what a scene calls for is computed: no nonholonomic callback when it
 * has no knife edge (p = 0), no power callback (and no BRAUN_ENERGY_INPUT)
 * when nothing puts energy in or takes it out, no holonomic callback when
 * m = 0. A scene with driven (rheonomic) joints keeps its energy law: the
 * prescribed motion does work through the ideal constraint forces, which the
 * core adds to Ė when the system sets BRAUN_CONSTRAINT_WORK.
 *
 * Memory: the builder and the callbacks allocate nothing; the caller owns
 * every array (static, stack or heap). Firmware code may define a scene as
 * static arrays and call braun_scene_build() once at start-up. Core tier:
 * no stdio, no allocator. Scene files (the JSON reader) and the C generator
 * are host tier: braun_scene_file.h.
 */
#ifndef BRAUN_SCENE_H
#define BRAUN_SCENE_H

#include <stddef.h>

#include "braun.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Index of the ground in body references: fixed, no coordinates. */
#define BRAUN_SCENE_GROUND (-1)

/* Largest magnitude accepted for any number of a scene (guards against
 * values that overflow once squared, e.g. a length of 1e200). */
#define BRAUN_SCENE_MAX_ABS 1e12

/* ------------------------------------------------------------------ */
/* Functions of time (drives, applied forces and torques)              */
/* ------------------------------------------------------------------ */
typedef enum braun_scene_fn_kind {
    BRAUN_FN_CONSTANT = 0, /* f = a */
    BRAUN_FN_LINEAR = 1,   /* f = a + b t                  (linear ramp) */
    BRAUN_FN_SINE = 2,     /* f = a + b sin(c t + d)       (c in rad/s) */
    BRAUN_FN_STEP = 3      /* f = a for t < c, b for t >= c (forces only) */
} braun_scene_fn_kind;

typedef struct braun_scene_fn {
    int kind; /* braun_scene_fn_kind */
    braun_real a, b, c, d;
} braun_scene_fn;

/* f(t), f'(t), f''(t) (any output may be NULL). A step has zero
 * derivatives: it is only accepted where no derivative is needed. */
void braun_scene_fn_eval(const braun_scene_fn *f, braun_real t, braun_real *value,
                         braun_real *rate, braun_real *accel);

/* ------------------------------------------------------------------ */
/* Elements                                                            */
/* ------------------------------------------------------------------ */
typedef enum braun_scene_body_kind {
    BRAUN_BODY_RIGID = 0,   /* x, y, θ */
    BRAUN_BODY_PARTICLE = 1 /* x, y */
} braun_scene_body_kind;

typedef struct braun_scene_body {
    int kind;             /* braun_scene_body_kind */
    braun_real mass;      /* kg; > 0 for rigid bodies, >= 0 for particles */
    braun_real inertia;   /* kg m² about the centre of mass (rigid, > 0) */
    braun_real q0[3];     /* initial x, y, θ (θ ignored for particles) */
    braun_real v0[3];     /* initial velocity and angular velocity */
    int iq;               /* set by braun_scene_build: index of x in q */
} braun_scene_body;

/* A point: fixed on a rigid body (body frame), a particle itself, or fixed
 * on the ground (world frame). */
typedef struct braun_scene_point {
    int body;             /* body index or BRAUN_SCENE_GROUND */
    braun_real x, y;      /* body frame; world frame on the ground; 0 on a particle */
} braun_scene_point;

/* Uniform rod between two points that are particles or on the ground;
 * adds its mass to M and one row |P_b - P_a|² - L² = 0. */
typedef struct braun_scene_rod {
    int a, b;             /* point indices */
    braun_real mass;      /* kg, >= 0 */
    braun_real length;    /* m, > 0 */
    int row;              /* set by braun_scene_build */
} braun_scene_rod;

typedef enum braun_scene_joint_type {
    /* a, b points: P_a - P_b = 0 (2 rows). */
    BRAUN_JOINT_REVOLUTE = 0,
    /* a, b points: |P_b - P_a|² - L² = 0 with L = value, or L = f(t) when
     * driven (1 row). */
    BRAUN_JOINT_DISTANCE = 1,
    /* a: the sliding point P; b: a point A on the line, whose body carries
     * the line; axis: its direction in that body's frame (world on ground).
     * n·(P - A) = 0 with n the axis turned by +90° (1 row); when driven
     * also u·(P - A) - f(t) = 0 along the unit axis u (1 more row). */
    BRAUN_JOINT_SLIDER = 2,
    /* A slider whose two bodies also keep their relative angle:
     * θ_P - θ_A - value = 0 (slider rows + 1). P's body must be rigid. */
    BRAUN_JOINT_PRISMATIC = 3,
    /* a, b bodies (rigid or ground): θ_b - θ_a - α = 0 with α = value, or
     * α = f(t) when driven (1 row). */
    BRAUN_JOINT_ANGLE = 4
} braun_scene_joint_type;

typedef struct braun_scene_joint {
    int type;             /* braun_scene_joint_type */
    int a, b;             /* points, or bodies for BRAUN_JOINT_ANGLE */
    braun_real axis[2];   /* slider and prismatic: line direction (non-zero) */
    braun_real value;     /* length, or angle offset; unused when driven (distance, angle) */
    int driven;           /* 1: follows drive (rheonomic) */
    braun_scene_fn drive; /* constant, linear or sine */
    int row;              /* set by braun_scene_build: first row */
} braun_scene_joint;

/* Knife edge (nonholonomic): the velocity of a body-fixed point has no
 * component across a body-fixed direction: n·v_P = 0 (1 row of Φ_v). */
typedef struct braun_scene_knife {
    int body;             /* rigid body */
    braun_real x, y;      /* contact point, body frame */
    braun_real dir[2];    /* blade direction, body frame (non-zero) */
    int row;              /* set by braun_scene_build: row of Φ_v */
} braun_scene_knife;

typedef enum braun_scene_effect_type {
    /* g[2]: uniform gravity on every mass (potential energy). */
    BRAUN_EFFECT_GRAVITY = 0,
    /* a, b points; k, c, rest: linear spring k (N/m, potential) and
     * damper c (N s/m, dissipates) along P_b - P_a. */
    BRAUN_EFFECT_SPRING = 1,
    /* a, b bodies; k, c, rest: rotational spring (N m/rad) and damper
     * (N m s/rad) on θ_b - θ_a. */
    BRAUN_EFFECT_TORSION = 2,
    /* a point; f[0], f[1]: world force components (N) as functions of t. */
    BRAUN_EFFECT_FORCE = 3,
    /* a body, b reaction body or ground; f[0]: torque (N m) on a, -f on b. */
    BRAUN_EFFECT_TORQUE = 4,
    /* a rotor body, b stator body or ground; torque–speed law
     * τ = tau0 (1 - ω/omega0), ω = ω_a - ω_b; τ on a, -τ on b. */
    BRAUN_EFFECT_MOTOR = 5
} braun_scene_effect_type;

typedef struct braun_scene_effect {
    int type;             /* braun_scene_effect_type */
    int a, b;             /* points or bodies, as the type says */
    braun_real g[2];      /* gravity */
    braun_real k, c, rest;/* springs and dampers */
    braun_real tau0, omega0; /* motor: stall torque (N m), no-load speed (rad/s, != 0) */
    braun_scene_fn f[2];  /* force components, or torque in f[0] */
} braun_scene_effect;

/* ------------------------------------------------------------------ */
/* The scene                                                           */
/* ------------------------------------------------------------------ */
typedef struct braun_scene {
    /* Description: arrays owned by the caller. The build writes only the
     * derived fields marked "set by braun_scene_build". */
    int nbodies;   braun_scene_body *bodies;
    int npoints;   braun_scene_point *points;
    int nrods;     braun_scene_rod *rods;
    int njoints;   braun_scene_joint *joints;
    int nknives;   braun_scene_knife *knives;
    int neffects;  braun_scene_effect *effects;
    /* Derived by braun_scene_build. */
    int n, m, p;          /* coordinates, holonomic rows, nonholonomic rows */
    int driven;           /* number of driven joints (then BRAUN_CONSTRAINT_WORK) */
    int energy_input;     /* dampers, forces, torques or motors present */
} braun_scene;

/* What braun_scene_build found wrong (element and index, static text). */
typedef enum braun_scene_element {
    BRAUN_SCENE_ELEM_SCENE = 0,
    BRAUN_SCENE_ELEM_BODY,
    BRAUN_SCENE_ELEM_POINT,
    BRAUN_SCENE_ELEM_ROD,
    BRAUN_SCENE_ELEM_JOINT,
    BRAUN_SCENE_ELEM_KNIFE,
    BRAUN_SCENE_ELEM_EFFECT
} braun_scene_element;

typedef struct braun_scene_error {
    int status;           /* BRAUN_OK or a braun_status */
    int element;          /* braun_scene_element */
    int index;            /* index in that array, -1 for the scene */
    const char *what;     /* static sentence, e.g. "rod end is on a rigid body" */
} braun_scene_error;

/* Validate the description, number the coordinates (bodies in order: 3 for
 * a rigid body, 2 for a particle) and the rows (rods, then joints in order;
 * knife edges in order for Φ_v), and fill sys with the scene's callbacks
 * (sys->user = s: the scene must outlive the system). Rejects dangling
 * indices, non-finite or out-of-range numbers (|x| > BRAUN_SCENE_MAX_ABS),
 * non-positive masses, inertias and lengths, a coordinate without mass,
 * rods ending on rigid bodies, joints of a body with itself, zero axes,
 * step drives and more than one gravity. err may be NULL.
 * Sizes: a scene with rods has at most BRAUN_MAX_DENSE (4096) coordinates
 * and rows; one without rods up to BRAUN_MAX_SPARSE (2^20), since it can be
 * handed out sparse (below) — braun_model_init refuses the dense system of
 * a scene above 4096 with BRAUN_ERR_SIZE.
 * Returns BRAUN_OK, BRAUN_ERR_ARGUMENT (bad description) or BRAUN_ERR_SIZE
 * (no coordinates, or more than those bounds). */
int braun_scene_build(braun_scene *s, braun_system *sys, braun_scene_error *err);

/* ------------------------------------------------------------------ */
/* Sparse systems (large mechanisms)                                   */
/* ------------------------------------------------------------------ */
/* A scene without rods has a block-diagonal M — one block per body, in
 * coordinate order: diag(m, m, I) for a rigid body, diag(m, m) for a
 * particle — and every row of A_q and A_vv belongs to one joint or knife
 * edge that touches at most two bodies. braun_scene_build_sparse hands out
 * that structure as the system's braun_sparsity (braun.h): the pattern of a
 * row is every coordinate of the bodies its element touches, sorted
 * (structural: entries that are 0 at some state are in it), and the
 * callbacks write compressed values. Their cost is O(nonzeros) per call,
 * independent of n·m, and they allocate nothing. A scene with rods has no
 * sparsity (a rod's mass couples the blocks of its ends).
 *
 * The pattern, the block sizes and a scratch of (most rows of one element)
 * x n reals live in one caller buffer, which must outlive the system, as
 * the scene must. The callbacks use the scratch: the callbacks of one
 * sparse system must not run concurrently (two braun_data of the same
 * model, stepped from two threads, need two sparse systems). */
typedef struct braun_scene_sparse braun_scene_sparse; /* private: lives in the buffer */

/* Bytes of buffer braun_scene_build_sparse needs for a built scene
 * (alignment slack included); 0 if the scene has rods or is not built. */
size_t braun_scene_sparse_size(const braun_scene *s);

/* braun_scene_build, then the sparse system: sys gets the same sizes,
 * flags, forces, energy law and power as from braun_scene_build, sparse
 * mass and constraint callbacks, sys->sparsity set, and sys->user = the
 * store in buffer (not s). The dense system of braun_scene_build stays
 * valid alongside. sys is written only on success.
 * Returns BRAUN_OK, braun_scene_build's errors, BRAUN_ERR_ARGUMENT for a
 * scene with rods (err names rod 0) or BRAUN_ERR_BUFFER when buffer is NULL
 * or smaller than braun_scene_sparse_size(s) bytes (any alignment). */
int braun_scene_build_sparse(braun_scene *s, braun_system *sys, void *buffer, size_t bytes,
                             braun_scene_error *err);

/* Initial q and v (n entries each) from the bodies' q0 and v0. */
void braun_scene_initial_state(const braun_scene *s, braun_real *q, braun_real *v);

/* World position of point i at q (xy: 2 entries). */
void braun_scene_point_position(const braun_scene *s, int i, const braun_real *q,
                                braun_real *xy);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_SCENE_H */
