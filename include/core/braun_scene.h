/*
 * libbraun scenes: planar and spatial mechanisms described as data, built
 * into the callbacks of braun_system (braun.h) with analytic derivatives.
 *
 * A scene is an immutable description — arrays of small structs for bodies,
 * points, rods, joints (holonomic ones and knife edges) and effects — plus a
 * few sizes that braun_scene_build() derives from it. Each body, joint and
 * effect names its class (below: "Elements and their classes"), one file
 * per type under src/core/scene/, which contributes its rows of Φ_q, A_q,
 * b_q, b_qv (holonomic), Φ_v, A_vv, b_vv (nonholonomic), forces Q, energy
 * E, ∂E/∂q, ∂E/∂v and input power Ė; the system's callbacks loop over the
 * elements and dispatch through their classes.
 *
 * Coordinates (SI units throughout):
 *   rigid body  x, y, θ   (centre of mass, angle from the x axis), M = diag(m, m, I)
 *   particle    x, y      (a point mass; mass 0 allowed when rods carry it)
 *   rod         none of its own: a uniform rod between two particles or
 *               ground points in natural coordinates; its kinetic energy
 *               (m/6)(|v_a|² + v_a·v_b + |v_b|²) adds blocks m/3, m/6 to M.
 *   rigid3d     x, y, z, e0, e1, e2, e3 (centre of mass, Euler parameters:
 *               a unit quaternion, kept unit by one row of Φ_q of the body's
 *               own); M(q) = diag(m I, (4GᵀJG + 4k ppᵀ)/|p|⁴), the
 *               kinetic energy of its points' motion whatever |p|
 *               (docs/method.md, "Spatial rigid bodies")
 *   particle3d  x, y, z
 * The planar classes have a constant mass matrix, so a planar scene sets
 * BRAUN_MASS_CONSTANT; a scene with a body class whose mass depends on q
 * (rigid3d) does not, and its forces carry the velocity-product terms.
 *
 * Only what a scene calls for is computed: no nonholonomic callback when it
 * has no knife edge (p = 0), no power callback (and no BRAUN_ENERGY_INPUT)
 * when nothing puts energy in or takes it out, no holonomic callback when
 * m = 0. A scene with driven (rheonomic) joints keeps its energy law: the
 * prescribed motion does work through the ideal constraint forces, which the
 * core adds to Ė by itself; a scene without one declares BRAUN_SCLERONOMIC.
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

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_scene_body_angle braun_scene_body_angle_float
#define braun_scene_body_classes braun_scene_body_classes_float
#define braun_scene_body_particle braun_scene_body_particle_float
#define braun_scene_body_particle3d braun_scene_body_particle3d_float
#define braun_scene_body_rigid braun_scene_body_rigid_float
#define braun_scene_body_rigid3d braun_scene_body_rigid3d_float
#define braun_scene_build braun_scene_build_float
#define braun_scene_coordinate_sizes braun_scene_coordinate_sizes_float
#define braun_scene_natural_sizes braun_scene_natural_sizes_float
#define braun_scene_build_sparse braun_scene_build_sparse_float
#define braun_scene_defaults braun_scene_defaults_float
#define braun_scene_dir_eval braun_scene_dir_eval_float
#define braun_scene_effect_body_force braun_scene_effect_body_force_float
#define braun_scene_effect_body_torque braun_scene_effect_body_torque_float
#define braun_scene_effect_classes braun_scene_effect_classes_float
#define braun_scene_effect_force braun_scene_effect_force_float
#define braun_scene_effect_gravity braun_scene_effect_gravity_float
#define braun_scene_effect_motor braun_scene_effect_motor_float
#define braun_scene_effect_motor3d braun_scene_effect_motor3d_float
#define braun_scene_effect_spring braun_scene_effect_spring_float
#define braun_scene_effect_torque braun_scene_effect_torque_float
#define braun_scene_effect_torque3d braun_scene_effect_torque3d_float
#define braun_scene_effect_torsion braun_scene_effect_torsion_float
#define braun_scene_effect_torsion3d braun_scene_effect_torsion3d_float
#define braun_scene_fn_eval braun_scene_fn_eval_float
#define braun_scene_initial_angle braun_scene_initial_angle_float
#define braun_scene_initial_distance braun_scene_initial_distance_float
#define braun_scene_initial_point braun_scene_initial_point_float
#define braun_scene_initial_state braun_scene_initial_state_float
#define braun_scene_joint_angle braun_scene_joint_angle_float
#define braun_scene_joint_classes braun_scene_joint_classes_float
#define braun_scene_joint_cylindrical braun_scene_joint_cylindrical_float
#define braun_scene_joint_distance braun_scene_joint_distance_float
#define braun_scene_joint_knife braun_scene_joint_knife_float
#define braun_scene_joint_point_line braun_scene_joint_point_line_float
#define braun_scene_joint_point_plane braun_scene_joint_point_plane_float
#define braun_scene_joint_prismatic braun_scene_joint_prismatic_float
#define braun_scene_joint_prismatic3d braun_scene_joint_prismatic3d_float
#define braun_scene_joint_revolute braun_scene_joint_revolute_float
#define braun_scene_joint_revolute3d braun_scene_joint_revolute3d_float
#define braun_scene_joint_slider braun_scene_joint_slider_float
#define braun_scene_joint_spherical braun_scene_joint_spherical_float
#define braun_scene_joint_universal braun_scene_joint_universal_float
#define braun_scene_joint_weld braun_scene_joint_weld_float
#define braun_scene_point_position braun_scene_point_position_float
#define braun_scene_point_state braun_scene_point_state_float
#define braun_scene_pt_eval braun_scene_pt_eval_float
#define braun_scene_pt_grad braun_scene_pt_grad_float
#define braun_scene_sparse_size braun_scene_sparse_size_float
#endif

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
 * derivatives: it is only accepted where no derivative is needed. Returns
 * BRAUN_OK, or BRAUN_ERR_ARGUMENT (outputs NaN) for a NULL f or a kind that
 * is none of the above. */
int braun_scene_fn_eval(const braun_scene_fn *f, braun_real t, braun_real *value,
                        braun_real *rate, braun_real *accel);

/* ------------------------------------------------------------------ */
/* Elements and their classes                                          */
/* ------------------------------------------------------------------ */
/* Every body, joint and effect names its class: a constant struct of data
 * and functions (as Chipmunk2D's cpConstraintClass) that says what the
 * element's fields mean and computes its share of M, T, the rows, Q, V
 * and Ė. The builder, the system's callbacks, the sparse pattern, the
 * scene-file reader and `braun gen-c` know no element type: they go
 * through the class. The built-in classes are one file each under
 * src/core/scene/ (scene_revolute.c, ...); a program may define its own
 * (below, "Writing a class", and tests/test_scene_toy_joint.c) and use it
 * in a C scene or, through braun_scene_load_ex (braun_scene_file.h), in a
 * scene file. Rods are not a class: they are the scene's natural-coordinate
 * mass elements, with a mass coupling that no body class expresses.
 *
 * The enumerator names of earlier versions are kept as macros for the
 * built-in classes' addresses, so `.type = BRAUN_JOINT_REVOLUTE` reads as
 * before (and is an address constant: static initialisers keep working). */
typedef struct braun_scene braun_scene;
typedef struct braun_scene_body braun_scene_body;
typedef struct braun_scene_point braun_scene_point;
typedef struct braun_scene_joint braun_scene_joint;
typedef struct braun_scene_effect braun_scene_effect;
typedef struct braun_scene_body_class braun_scene_body_class;
typedef struct braun_scene_joint_class braun_scene_joint_class;
typedef struct braun_scene_effect_class braun_scene_effect_class;

/* Most coordinates of one body (the size of braun_scene_body's q0, v0):
 * 3 for the planar rigid body, 7 for rigid3d (a position and a
 * quaternion), 12 for a body in natural coordinates (a point and three
 * unit vectors: the class a program may define, as bench/spatial does). */
#define BRAUN_SCENE_MAX_DOF 12

/* Partials of a point with respect to its body's coordinates that a body
 * class may keep in braun_scene_pt.jac (room for 3 x 4). */
#define BRAUN_SCENE_PT_PARTIALS 12

/* ---------------------------------------------------- field descriptors */
/* A class describes its scene-file fields as data: a table of descriptors,
 * ended by one with key NULL. The reader (host) and the C generator (host)
 * interpret them generically; the core's builder uses them to validate
 * references. Each descriptor stores into the element struct at `offset`
 * (offsetof(braun_scene_joint, a), ...):
 *   BRAUN_FIELD_POINT       int: a point reference — "body.point", "body"
 *                           (a rigid body's centre, the particle itself),
 *                           "ground.NAME" or [x, y] (a new ground point);
 *                           left out (optional), -1: no point, which the
 *                           builder refuses
 *   BRAUN_FIELD_BODY        int: a body by name, or "ground"
 *                           (BRAUN_SCENE_GROUND) with BRAUN_FIELD_GROUND;
 *                           left out (optional), it is the ground
 *   BRAUN_FIELD_BODY_POINT  int: a body by name; the element gets a new
 *                           point of its own on that body, at the body's
 *                           origin moved by a BRAUN_FIELD_OFFSET field with
 *                           the same offset (a knife edge's contact point)
 *   BRAUN_FIELD_OFFSET      `count` (2) reals: the body-frame offset of the
 *                           point of the BRAUN_FIELD_BODY_POINT field at
 *                           `offset` (0 when left out; after that field)
 *   BRAUN_FIELD_REAL        braun_real[count]: a number (count 1) or an
 *                           array of count numbers (2: a planar vector, 3 a
 *                           spatial one, 4 a quaternion)
 *   BRAUN_FIELD_FN          braun_scene_fn: a number (a constant) or a
 *                           function object
 *   BRAUN_FIELD_POINTS      bodies only: named points {"NAME": [x, y], ...}
 *                           in the body frame (count coordinates each: 2
 *                           planar, 3 spatial)
 *   BRAUN_FIELD_JOINT       int: a joint by its name (an effect on a
 *                           joint's axis: torsion3d, motor3d)
 * A REAL field with BRAUN_FIELD_DIMVEC (count 3) is a vector of the
 * scene's dimension: 2 entries in a planar scene (the third is 0), 3 in a
 * spatial one (gravity's g). */
typedef enum braun_scene_field_kind {
    BRAUN_FIELD_POINT = 1,
    BRAUN_FIELD_BODY = 2,
    BRAUN_FIELD_BODY_POINT = 3,
    BRAUN_FIELD_OFFSET = 4,
    BRAUN_FIELD_REAL = 5,
    BRAUN_FIELD_FN = 6,
    BRAUN_FIELD_POINTS = 7,
    BRAUN_FIELD_JOINT = 8
} braun_scene_field_kind;

/* Flags of a descriptor. */
#define BRAUN_FIELD_REQUIRED 0x01u /* missing is an error */
#define BRAUN_FIELD_GROUND 0x02u   /* BODY: "ground" is accepted */
#define BRAUN_FIELD_ANGLE 0x04u    /* BODY, BODY_POINT: the body has an angle (rigid) */
#define BRAUN_FIELD_POSITIVE 0x08u /* REAL: every entry > 0 */
#define BRAUN_FIELD_NONNEG 0x10u   /* REAL: every entry >= 0 */
#define BRAUN_FIELD_NONZERO 0x20u  /* REAL: not 0 (count 1), not the zero vector */
#define BRAUN_FIELD_SMOOTH 0x40u   /* FN: constant, linear or sine, not a step (a drive) */
#define BRAUN_FIELD_DIMVEC 0x80u   /* REAL (count 3): 2 entries in a planar scene */
#define BRAUN_FIELD_UNIT 0x100u    /* REAL vector: normalised on load (axes, directions) */

typedef struct braun_scene_field {
    const char *key;      /* scene-file key; NULL ends the table */
    int kind;             /* braun_scene_field_kind */
    int count;            /* REAL, OFFSET, POINTS: reals per value (0 means 1) */
    size_t offset;        /* offsetof(element struct, member) */
    unsigned flags;       /* BRAUN_FIELD_* */
    const char *excludes; /* key that may not be given with this one, or NULL
                           * ("give 'length' or 'drive', not both") */
} braun_scene_field;

/* The given mask of a defaults hook: bit i set when field i of the class's
 * table was in the scene file (so a table has at most 32 fields). */
#define BRAUN_FIELD_GIVEN(mask, i) (((mask) >> (i)) & 1u)

/* ------------------------------------------------------- point kinematics */
/* A point at a state, computed by its body's class (braun_scene_pt_eval):
 *   P' = J_P v,  P'' = J_P v' + cc,
 * with J_P = ∂P/∂q nonzero only at the body's columns col .. col + dof - 1.
 * A joint or effect reads pos, vel and cc and reaches J_P only through
 * braun_scene_pt_grad, so it works on any body class, planar or spatial.
 * Planar classes leave the third entries 0. The same struct carries a
 * body-fixed direction d (braun_scene_dir_eval: pos = R(q) d, no
 * translation; `direction` set), which spatial joints and effects use for
 * axes. */
typedef struct braun_scene_pt {
    const braun_scene_body *body; /* its body, NULL on the ground (fixed) */
    int col;                      /* column of the body's first coordinate, -1 on the ground */
    braun_real pos[3];            /* world position */
    braun_real vel[3];            /* P' (0 when v was NULL) */
    braun_real cc[3];             /* velocity product of P'' (0 when v was NULL) */
    braun_real jac[BRAUN_SCENE_PT_PARTIALS]; /* the body class's partials, its own layout */
    int direction;                /* 1: a body-fixed direction (grad skips the translation) */
} braun_scene_pt;

/* Point i of scene s at (q, v), both of n entries (v may be NULL). */
void braun_scene_pt_eval(const braun_scene *s, int i, const braun_real *q, const braun_real *v,
                         braun_scene_pt *P);

/* row += gᵀ J_P: the gradient of g·P with respect to q (row: n entries;
 * g: world components, the first dim of them read). Nothing for a ground
 * point. */
void braun_scene_pt_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row);

/* The body-fixed direction d (3 entries, body frame; world on the ground,
 * body BRAUN_SCENE_GROUND) of body `body` at (q, v): pos = R(q) d, vel, cc
 * and the partials, as for a point; braun_scene_pt_grad adds gᵀ ∂(Rd)/∂q.
 * Only for bodies whose class has a direction hook (spatial bodies). */
void braun_scene_dir_eval(const braun_scene *s, int body, const braun_real *d,
                          const braun_real *q, const braun_real *v, braun_scene_pt *D);

/* World position and velocity of point i of a built scene at (q, v)
 * (pos, vel: 3 entries, z = 0 in a planar scene; v and vel may be NULL):
 * what a reported point (docs/scene-format.md, "Reported points") holds.
 * BRAUN_ERR_ARGUMENT for no such point (or NULL s, q, pos). */
int braun_scene_point_state(const braun_scene *s, int i, const braun_real *q,
                            const braun_real *v, braun_real *pos, braun_real *vel);

/* Each coordinate's typical size at q (size: n entries) in the scene's own
 * unit of length: for a coordinate that moves its body's origin (x, y, z
 * of a body or particle) the body's smallest length — its points' distances
 * from its origin and the lengths (largest distance between their points)
 * of the rods, joints and effects with a point on it, lengths below 1e-6 of
 * its largest left out as coinciding points —, divided by the origin's
 * speed per unit of the coordinate (1); a body with none takes the scene's
 * smallest, a scene with none 1. A coordinate that does not move the origin
 * (an angle, an Euler parameter) has size 1. The same numbers per second
 * are the velocities' sizes. What braun_check_callbacks_sized (braun_host.h)
 * steps by: scaled by L, a scene's sizes are L times. A built scene;
 * BRAUN_ERR_ARGUMENT for a NULL argument or a scene not built. */
int braun_scene_coordinate_sizes(const braun_scene *s, const braun_real *q, braun_real *size);

/* Each coordinate's natural size at q (size: n entries), what the
 * accuracy guard's scales are measured by (braun_system.q_scale): a
 * coordinate of a body's position (the first `dim` of its class's
 * coordinates, the planar angle excepted) the mechanism's size — the
 * diagonal of the box around the scene's points and the bodies' positions,
 * 1 if that is 0 —, an angle or an Euler parameter 1. Independent of where
 * the mechanism is: the same scene moved by 10 km has the same sizes.
 * BRAUN_ERR_ARGUMENT for a NULL argument or a scene not built. */
int braun_scene_natural_sizes(const braun_scene *s, const braun_real *q, braun_real *size);

/* Angle θ and angular velocity ω of a body that has one (0 for the ground
 * or a body without angle; omega 0 when v is NULL); returns θ's column, or
 * -1 when the body has none. theta and omega may be NULL. A body that does
 * not exist (an index other than BRAUN_SCENE_GROUND and 0 … nbodies − 1),
 * or a NULL q where the body has an angle: BRAUN_ERR_ARGUMENT (−1) and NaN
 * in theta and omega. */
int braun_scene_body_angle(const braun_scene *s, int body, const braun_real *q,
                           const braun_real *v, braun_real *theta, braun_real *omega);

/* Before or after the build, for defaults hooks: the world position of
 * point i at the bodies' initial state q0 (pos: 3 entries), the distance
 * between two points there, and a body's initial angle (0 for the ground
 * and bodies without angle). */
int braun_scene_initial_point(const braun_scene *s, int i, braun_real *pos);
braun_real braun_scene_initial_distance(const braun_scene *s, int a, int b);
braun_real braun_scene_initial_angle(const braun_scene *s, int body);
/* (A point or body that does not exist: BRAUN_ERR_ARGUMENT, and NaN for
 * the distance and the angle.) */

/* -------------------------------------------------------------- bodies */
/* A body class: its coordinates, mass block, kinetic energy, weight and
 * point kinematics. Every hook gets the body's own slice of q and v (dof
 * entries, starting at the body's iq) and writes only its own entries.
 *   mass     add the body's constant dof x dof mass block into M: entry
 *            (i, j) at M[i·ld + j], M pointing at the block's (0, 0). The
 *            sparse system hands the block out as it is (a zeroed block
 *            plus this hook), so it is also the sparsity's block. NULL when
 *            the class has mass_at.
 *   kinetic  T = ½ vᵀ M_b v; adds ∂T/∂v into dEdv (NULL: not wanted).
 *            NULL when the class has kinetic_at.
 *   point    kinematics of point pt of the body: P has body and col set
 *            and vel, cc zeroed; write pos (all 3 entries: a planar class
 *            writes pos[2] = 0), when v is not NULL vel and cc, and
 *            whatever jac the grad hook needs. Also called on q0 before
 *            the build (braun_scene_initial_point).
 *   grad     row[k] += (gᵀ J_P)_k for the body's columns (row points at the
 *            body's first column).
 *   weight   uniform gravity g (world): Q[k] += (m gᵀ ∂r_c/∂q)_k.
 *   gravity_potential   -m g·r_c at q (the weight's potential).
 *   check    NULL or a static sentence on what is wrong with b (the builder
 *            has checked every number is finite and in range).
 * Optional hooks (NULL for planar bodies; positional initialisers of older
 * classes leave them NULL), for spatial bodies:
 *   mass_at     the mass block at q, when it depends on q (Euler
 *               parameters); then the scene does not set
 *               BRAUN_MASS_CONSTANT.
 *   kinetic_at  T(q, v); adds ∂T/∂q into dEdq and ∂T/∂v into dEdv (either
 *               NULL: not wanted).
 *   inertial    Q += the velocity-product (Coriolis, centrifugal,
 *               gyroscopic) forces -Ṁv + ∂T/∂q of a q-dependent mass block.
 *   rows, constraint   rows of Φ_q on the body's own coordinates (a unit
 *               quaternion's |p|² - 1 = 0): phi[r], A row r at A + r·ld
 *               (pointing at the body's first column; add into it), bv[r]
 *               (b_q = 0: scleronomic); any output may be NULL.
 *   direction   kinematics of the body-fixed direction d (body frame), as
 *               point with the translation left out: P->direction is set.
 *   omega       W (3 x dof, row-major): the world angular velocity is
 *               ω = W v (torques: Q += Wᵀτ, power τ·ω).
 *   initial     the body's coordinates and velocities from its q0 and v0
 *               (which then describe the state: position, quaternion,
 *               velocity, angular velocity); NULL: copied.
 *   defaults    scene files: after the body's fields are read (a quaternion
 *               normalised). */
#define BRAUN_BODY_CLASS_POINT_MASS 0x01u /* a point mass whose coordinates are
                                           * its position: rods may end on it,
                                           * its points carry no offset */

struct braun_scene_body_class {
    const char *name;   /* scene-file "type" ("rigid") */
    const char *c_name; /* what braun gen-c writes ("BRAUN_BODY_RIGID"; a
                         * user class: "&symbol", declared extern by gen-c) */
    int dof;            /* coordinates (and velocities): 1..BRAUN_SCENE_MAX_DOF */
    int dim;            /* world dimension of its points: 2 (planar) or 3 */
    int angle;          /* index of the planar angle θ among its coordinates, -1: none */
    unsigned flags;     /* BRAUN_BODY_CLASS_* */
    const braun_scene_field *fields; /* mass, inertia, position, ... */
    const char *(*check)(const braun_scene *s, const braun_scene_body *b);
    void (*mass)(const braun_scene_body *b, braun_real *M, int ld);
    braun_real (*kinetic)(const braun_scene_body *b, const braun_real *v, braun_real *dEdv);
    void (*point)(const braun_scene_body *b, const braun_scene_point *pt, const braun_real *q,
                  const braun_real *v, braun_scene_pt *P);
    void (*grad)(const braun_scene_pt *P, const braun_real *g, braun_real *row);
    void (*weight)(const braun_scene_body *b, const braun_real *g, braun_real *Q);
    braun_real (*gravity_potential)(const braun_scene_body *b, const braun_real *g,
                                    const braun_real *q);
    /* Spatial bodies (optional, see above). */
    void (*mass_at)(const braun_scene_body *b, const braun_real *q, braun_real *M, int ld);
    braun_real (*kinetic_at)(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                             braun_real *dEdq, braun_real *dEdv);
    void (*inertial)(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                     braun_real *Q);
    int rows;
    void (*constraint)(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                       braun_real *phi, braun_real *A, int ld, braun_real *bv);
    void (*direction)(const braun_scene_body *b, const braun_real *d, const braun_real *q,
                      const braun_real *v, braun_scene_pt *P);
    void (*omega)(const braun_scene_body *b, const braun_real *q, braun_real *W);
    void (*initial)(const braun_scene_body *b, braun_real *q, braun_real *v);
    void (*defaults)(braun_scene_body *b, unsigned given);
};

extern const braun_scene_body_class braun_scene_body_rigid;    /* x, y, θ; M = diag(m, m, I) */
extern const braun_scene_body_class braun_scene_body_particle; /* x, y; M = diag(m, m), m >= 0 */
/* Spatial rigid body in Euler parameters: q = (x, y, z, e0, e1, e2, e3),
 * one row |p|² - 1 = 0; q0 = (position, quaternion [w, x, y, z]), v0 =
 * (velocity, world angular velocity), tensor = (I_xx, I_yy, I_zz, I_xy,
 * I_xz, I_yz) about the centre of mass in the body frame. */
extern const braun_scene_body_class braun_scene_body_rigid3d;
/* Spatial point mass: x, y, z; M = diag(m, m, m), m >= 0. */
extern const braun_scene_body_class braun_scene_body_particle3d;
#define BRAUN_BODY_RIGID (&braun_scene_body_rigid)
#define BRAUN_BODY_PARTICLE (&braun_scene_body_particle)
#define BRAUN_BODY_RIGID3D (&braun_scene_body_rigid3d)
#define BRAUN_BODY_PARTICLE3D (&braun_scene_body_particle3d)

struct braun_scene_body {
    const braun_scene_body_class *kind;
    braun_real mass;      /* kg; > 0 for rigid bodies, >= 0 for particles */
    braun_real inertia;   /* kg m² about the centre of mass (rigid, > 0) */
    braun_real q0[BRAUN_SCENE_MAX_DOF]; /* initial coordinates: x, y, θ (θ unused by particles);
                                          * rigid3d: x, y, z, then the quaternion w, x, y, z */
    braun_real v0[BRAUN_SCENE_MAX_DOF]; /* initial velocity and angular velocity (rigid3d:
                                          * vx, vy, vz, then ω in the world frame) */
    int iq;               /* set by braun_scene_build: index of its first coordinate in q */
    braun_real tensor[6]; /* rigid3d: I_xx, I_yy, I_zz, I_xy, I_xz, I_yz (kg m², body frame,
                           * about the centre of mass; I_xy = -∫xy dm) */
    int row;              /* set by braun_scene_build: its first own row of Φ_q (class rows) */
};

/* A point: fixed on a rigid body (body frame), a particle itself, or fixed
 * on the ground (world frame). z is 0 in a planar scene. */
struct braun_scene_point {
    int body;             /* body index or BRAUN_SCENE_GROUND */
    braun_real x, y;      /* body frame; world frame on the ground; 0 on a particle */
    braun_real z;         /* spatial scenes */
};

/* Uniform rod between two points that are particles or on the ground;
 * adds its mass to M and one row |P_b - P_a|² - L² = 0. */
typedef struct braun_scene_rod {
    int a, b;             /* point indices */
    braun_real mass;      /* kg, >= 0 */
    braun_real length;    /* m, > 0 */
    int row;              /* set by braun_scene_build */
} braun_scene_rod;

/* -------------------------------------------------------------- joints */
/* A joint class: rows of Φ_q (holonomic) or of Φ_v (nonholonomic).
 *   rows     its number of rows (may depend on the joint: a driven slider
 *            has one more); at least 1.
 *   eval     its rows at (t, q, v). Every output is offset to the joint's
 *            first row and may be NULL (not wanted at this call): phi[r],
 *            A (row r at A + r·n, n = s->n; zeroed by the caller: add into
 *            it, e.g. with braun_scene_pt_grad, so a point that meets the
 *            same body twice gets the sum of its columns), b[r], bv[r].
 *            Holonomic: phi = Φ_q, A = A_q = ∂Φ_q/∂q, b = b_q = -∂Φ_q/∂t,
 *            bv = b_qv with Φ_q'' = A_q v' - b_qv (Sec. 2.2).
 *            Nonholonomic: phi = Φ_v, A = A_vv = ∂Φ_v/∂v, b is NULL,
 *            bv = b_vv with Φ_v' = A_vv v' - b_vv.
 *            A row may only have entries at the columns of the bodies the
 *            bodies hook names. Returns 0, or 1 (recoverable: the adaptive
 *            driver retries with a smaller step) or < 0 (an error).
 *   bodies   the two bodies (ground: BRAUN_SCENE_GROUND, twice the same is
 *            fine) every row of the joint may touch, for the sparse
 *            pattern; NULL: the bodies of its POINT, BODY and BODY_POINT
 *            fields, in table order (at most two such fields).
 *   check    NULL or a static sentence (as the builder's messages: "joint
 *            connects a body to itself"). It runs after the builder has
 *            checked the numbers (finite, in range) and that the reference
 *            fields of the table are in range; after it, the builder checks
 *            drives (driven: a valid function, not a step) and the fields'
 *            GROUND and ANGLE flags.
 *   defaults scene files only (the reader calls it once the fields are
 *            read; C scenes give every value): values derived from the
 *            initial state of the fields left out, e.g. a distance joint's
 *            length = the initial distance, and `driven` from whether the
 *            drive was given. s holds the bodies (with q0) and points read
 *            so far; `given` has bit i set for field i that was given.
 * A joint is driven (rheonomic) when its `driven` is non-zero: the scene
 * then leaves BRAUN_SCLERONOMIC unset (the core adds the drive's work). */
struct braun_scene_joint_class {
    const char *name;         /* scene-file "type" ("revolute") */
    const char *c_name;       /* what braun gen-c writes ("BRAUN_JOINT_REVOLUTE") */
    int nonholonomic;         /* 0: rows of Φ_q, 1: rows of Φ_v */
    const braun_scene_field *fields;
    void (*defaults)(const braun_scene *s, braun_scene_joint *j, unsigned given);
    const char *(*check)(const braun_scene *s, const braun_scene_joint *j);
    int (*rows)(const braun_scene_joint *j);
    void (*bodies)(const braun_scene *s, const braun_scene_joint *j, int body[2]);
    int (*eval)(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                braun_real *b, braun_real *bv);
    int dim;                  /* scenes it belongs in: 2 planar, 3 spatial, 0 both */
};

/* a, b points: P_a - P_b = 0 (2 rows). */
extern const braun_scene_joint_class braun_scene_joint_revolute;
/* a, b points: |P_b - P_a|² - L² = 0 with L = value, or L = f(t) when
 * driven (1 row). */
extern const braun_scene_joint_class braun_scene_joint_distance;
/* a: the sliding point P; b: a point A on the line, whose body carries the
 * line; axis: its direction in that body's frame (world on the ground).
 * n·(P - A) = 0 with n the axis turned by +90° (1 row); when driven also
 * u·(P - A) - f(t) = 0 along the unit axis u (1 more row). */
extern const braun_scene_joint_class braun_scene_joint_slider;
/* A slider whose two bodies also keep their relative angle:
 * θ_P - θ_A - value = 0 (slider rows + 1). P's body must be rigid. */
extern const braun_scene_joint_class braun_scene_joint_prismatic;
/* a, b bodies (rigid or ground): θ_b - θ_a - α = 0 with α = value, or
 * α = f(t) when driven (1 row). */
extern const braun_scene_joint_class braun_scene_joint_angle;
/* Knife edge (nonholonomic): a is the contact point, a point of the scene
 * on a rigid body; axis is the blade direction in the body frame. The
 * contact point's velocity has no component across the blade:
 * n·v_P = 0 (1 row of Φ_v). */
extern const braun_scene_joint_class braun_scene_joint_knife;
#define BRAUN_JOINT_REVOLUTE (&braun_scene_joint_revolute)
#define BRAUN_JOINT_DISTANCE (&braun_scene_joint_distance)
#define BRAUN_JOINT_SLIDER (&braun_scene_joint_slider)
#define BRAUN_JOINT_PRISMATIC (&braun_scene_joint_prismatic)
#define BRAUN_JOINT_ANGLE (&braun_scene_joint_angle)
#define BRAUN_JOINT_KNIFE (&braun_scene_joint_knife)

/* Spatial joints (docs/scene-format.md, "Spatial joints"). Directions are
 * body-fixed unit vectors: axis in the frame of the first point's body,
 * axis_b in the second's; ref_a ⊥ axis and ref_b ⊥ axis_b are reference
 * directions that coincide in the initial configuration (scene files fill
 * axis_b, ref_a, ref_b from the initial state; C scenes call
 * braun_scene_defaults() or give them). With w = axis × ref on each body:
 *   spherical    a, b: P_a - P_b = 0 (3)
 *   revolute3d   spherical rows, ref_a·axis_b = 0, w_a·axis_b = 0 (5);
 *                driven: cos f (w_a·ref_b) - sin f (ref_a·ref_b) = 0 (+1)
 *   prismatic3d  a the point P, b the line point A: axis·ref_b = 0,
 *                ref_a·w_b = 0, w_a·axis_b = 0 (orientation, 3), then
 *                ref_a·(P - A) = 0, w_a·(P - A) = 0 (2); driven:
 *                axis·(P - A) - f(t) = 0 (+1)
 *   cylindrical  a the point P, b the line point A: ref_a·axis_b = 0,
 *                w_a·axis_b = 0, ref_a·(P - A) = 0, w_a·(P - A) = 0 (4)
 *   universal    spherical rows, axis·axis_b = 0 (4)
 *   weld         spherical rows and the orientation rows (6)
 *   point_line   a the point P, b the line point A: the last two
 *                cylindrical rows (2)
 *   point_plane  a the point P, b the plane point A: axis·(P - A) = 0 (1)
 * Here "axis" and "ref_a" are on the body of point b (the line's, the
 * plane's) for prismatic3d, cylindrical, point_line and point_plane, as
 * the planar slider has its line on b. */
extern const braun_scene_joint_class braun_scene_joint_spherical;
extern const braun_scene_joint_class braun_scene_joint_revolute3d;
extern const braun_scene_joint_class braun_scene_joint_prismatic3d;
extern const braun_scene_joint_class braun_scene_joint_cylindrical;
extern const braun_scene_joint_class braun_scene_joint_universal;
extern const braun_scene_joint_class braun_scene_joint_weld;
extern const braun_scene_joint_class braun_scene_joint_point_line;
extern const braun_scene_joint_class braun_scene_joint_point_plane;
#define BRAUN_JOINT_SPHERICAL (&braun_scene_joint_spherical)
#define BRAUN_JOINT_REVOLUTE3D (&braun_scene_joint_revolute3d)
#define BRAUN_JOINT_PRISMATIC3D (&braun_scene_joint_prismatic3d)
#define BRAUN_JOINT_CYLINDRICAL (&braun_scene_joint_cylindrical)
#define BRAUN_JOINT_UNIVERSAL (&braun_scene_joint_universal)
#define BRAUN_JOINT_WELD (&braun_scene_joint_weld)
#define BRAUN_JOINT_POINT_LINE (&braun_scene_joint_point_line)
#define BRAUN_JOINT_POINT_PLANE (&braun_scene_joint_point_plane)

struct braun_scene_joint {
    const braun_scene_joint_class *type;
    int a, b;             /* points, or bodies (angle joints), as the class says */
    braun_real axis[3];   /* slider, prismatic: line direction; knife: blade (non-zero);
                           * spatial joints: the axis (a unit vector) */
    braun_real value;     /* length, or angle offset; unused when driven (distance, angle) */
    int driven;           /* 1: follows drive (rheonomic) */
    braun_scene_fn drive; /* constant, linear or sine */
    int row;              /* set by braun_scene_build: its first row (of Φ_q, or of Φ_v
                           * for a nonholonomic joint) */
    braun_real axis_b[3]; /* spatial joints: unit vectors in the bodies' frames (above) */
    braun_real ref_a[3], ref_b[3];
};

/* ------------------------------------------------------------- effects */
/* An effect class: applied forces, and their share of the energy law.
 *   forces    Q += the generalized force at (t, q, v) (Q: n entries).
 *   potential NULL if none: *V = its potential energy at q (independent of
 *             t: the scene's ∂E/∂t is 0) and dVdq += ∂V/∂q (NULL: not
 *             wanted). Conservative forces must equal -∂V/∂q.
 *   power     NULL if none: *P = the power its non-conservative forces put
 *             in (negative: dissipate), the input rate Ė of the energy law.
 *   inputs    whether an instance puts energy in or out (a damper only
 *             when c != 0); NULL: every instance of a class with power.
 *             The scene has a power callback (BRAUN_ENERGY_INPUT) only when
 *             one does, and calls power only for those.
 *   check, defaults  as for joints.
 * forces, potential and power return 0, or 1 (recoverable: a spring whose
 * two points coincide has no direction), or < 0 (an error). */
struct braun_scene_effect_class {
    const char *name;         /* scene-file "type" ("gravity") */
    const char *c_name;       /* what braun gen-c writes ("BRAUN_EFFECT_GRAVITY") */
    const braun_scene_field *fields;
    void (*defaults)(const braun_scene *s, braun_scene_effect *e, unsigned given);
    const char *(*check)(const braun_scene *s, const braun_scene_effect *e);
    int (*forces)(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                  const braun_real *q, const braun_real *v, braun_real *Q);
    int (*potential)(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                     braun_real *V, braun_real *dVdq);
    int (*power)(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                 const braun_real *q, const braun_real *v, braun_real *P);
    int (*inputs)(const braun_scene_effect *e);
    int dim;                  /* scenes it belongs in: 2 planar, 3 spatial, 0 both */
};

/* g: uniform gravity on every mass (potential energy; at most one); g[2]
 * is 0 in a planar scene. */
extern const braun_scene_effect_class braun_scene_effect_gravity;
/* a, b points; k, c, rest: linear spring k (N/m, potential) and damper c
 * (N s/m, dissipates) along P_b - P_a. */
extern const braun_scene_effect_class braun_scene_effect_spring;
/* a, b bodies; k, c, rest: rotational spring (N m/rad) and damper
 * (N m s/rad) on θ_b - θ_a. */
extern const braun_scene_effect_class braun_scene_effect_torsion;
/* a point; f[0], f[1], f[2]: world force components (N) as functions of
 * t (f[2] = 0 in a planar scene). */
extern const braun_scene_effect_class braun_scene_effect_force;
/* a body, b reaction body or ground; f[0]: torque (N m) on a, -f on b. */
extern const braun_scene_effect_class braun_scene_effect_torque;
/* a rotor body, b stator body or ground; torque–speed law
 * τ = tau0 (1 - ω/omega0), ω = ω_a - ω_b; τ on a, -τ on b. */
extern const braun_scene_effect_class braun_scene_effect_motor;
#define BRAUN_EFFECT_GRAVITY (&braun_scene_effect_gravity)
#define BRAUN_EFFECT_SPRING (&braun_scene_effect_spring)
#define BRAUN_EFFECT_TORSION (&braun_scene_effect_torsion)
#define BRAUN_EFFECT_FORCE (&braun_scene_effect_force)
#define BRAUN_EFFECT_TORQUE (&braun_scene_effect_torque)
#define BRAUN_EFFECT_MOTOR (&braun_scene_effect_motor)

/* Spatial effects. body_force: a point, f[0..2] its components in the
 * frame of the point's body. torque3d, body_torque: a body, b reaction
 * body or ground, f[0..2] the torque's world (torque3d) or body-frame
 * (body_torque) components; τ on a, -τ on b. torsion3d: a the index of a
 * revolute3d or cylindrical joint; k, c, rest on its angle θ (0 in the
 * initial configuration, taken within π of rest). motor3d: a the joint;
 * τ = tau0 (1 - θ'/omega0) about its axis on the body of its point b,
 * -τ on that of a. θ is b's body's turn relative to a's for revolute3d;
 * for cylindrical it is the point P's body's relative to the line's (its a
 * relative to its b): the motor's τ acts on P's body, -τ on the line's. */
extern const braun_scene_effect_class braun_scene_effect_body_force;
extern const braun_scene_effect_class braun_scene_effect_torque3d;
extern const braun_scene_effect_class braun_scene_effect_body_torque;
extern const braun_scene_effect_class braun_scene_effect_torsion3d;
extern const braun_scene_effect_class braun_scene_effect_motor3d;
#define BRAUN_EFFECT_BODY_FORCE (&braun_scene_effect_body_force)
#define BRAUN_EFFECT_TORQUE3D (&braun_scene_effect_torque3d)
#define BRAUN_EFFECT_BODY_TORQUE (&braun_scene_effect_body_torque)
#define BRAUN_EFFECT_TORSION3D (&braun_scene_effect_torsion3d)
#define BRAUN_EFFECT_MOTOR3D (&braun_scene_effect_motor3d)

struct braun_scene_effect {
    const braun_scene_effect_class *type;
    int a, b;             /* points or bodies, as the class says */
    braun_real g[3];      /* gravity */
    braun_real k, c, rest;/* springs and dampers */
    braun_real tau0, omega0; /* motor: stall torque (N m), no-load speed (rad/s, != 0) */
    braun_scene_fn f[3];  /* force or torque components (planar torque: f[0]) */
};

/* The built-in classes, each list ended by NULL, in the order the scene
 * format documents them (the reader's "unknown type" messages list them). */
extern const braun_scene_body_class *const braun_scene_body_classes[];
extern const braun_scene_joint_class *const braun_scene_joint_classes[];
extern const braun_scene_effect_class *const braun_scene_effect_classes[];

/* Writing a class (tests/test_scene_toy_joint.c is a complete one):
 *   static int toy_rows(const braun_scene_joint *j) { (void)j; return 1; }
 *   static int toy_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
 *                       const braun_real *q, const braun_real *v, braun_real *phi,
 *                       braun_real *A, braun_real *b, braun_real *bv)
 *   {
 *       braun_scene_pt P;
 *       braun_scene_pt_eval(s, j->a, q, v, &P);   // pos, vel, cc of point a
 *       if (phi) phi[0] = ...;
 *       if (A) { const braun_real g[2] = {...}; braun_scene_pt_grad(&P, g, A); }
 *       if (b) b[0] = 0;
 *       if (bv) bv[0] = ...;                        // uses P.vel and P.cc
 *       return 0;
 *   }
 *   static const braun_scene_field toy_fields[] = {
 *       {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a), BRAUN_FIELD_REQUIRED, NULL},
 *       {"radius", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_joint, value),
 *        BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
 *       {NULL, 0, 0, 0, 0, NULL}};
 *   const braun_scene_joint_class toy = {"toy", "&toy", 0, toy_fields, NULL, NULL,
 *                                        toy_rows, NULL, toy_eval, 0};
 * then {.type = &toy, .a = 3, .value = 0.5} in a scene's joints. */

/* ------------------------------------------------------------------ */
/* The scene                                                           */
/* ------------------------------------------------------------------ */
struct braun_scene {
    /* Description: arrays owned by the caller. The build writes only the
     * derived fields marked "set by braun_scene_build". */
    int nbodies;   braun_scene_body *bodies;
    int npoints;   braun_scene_point *points;
    int nrods;     braun_scene_rod *rods;
    int njoints;   braun_scene_joint *joints;   /* holonomic and nonholonomic */
    int neffects;  braun_scene_effect *effects;
    /* Derived by braun_scene_build. */
    int n, m, p;          /* coordinates, holonomic rows, nonholonomic rows */
    int driven;           /* number of driven joints (0: BRAUN_SCLERONOMIC) */
    int energy_input;     /* an effect puts energy in or takes it out */
    int dim;              /* 2: planar bodies, 3: spatial bodies */
    /* Optional storage of the caller's, n entries (the sum of the bodies'
     * dof): braun_scene_build fills it with braun_scene_natural_sizes at
     * the initial state and points sys->q_scale at it, so that the
     * accuracy guard judges each coordinate by its own unit (braun.h,
     * braun_system.q_scale). NULL: sys->q_scale = NULL (the guard's scales
     * from the state alone). The scene file reader provides it. */
    braun_real *q_scale;
};

/* What braun_scene_build found wrong (element and index, static text). */
typedef enum braun_scene_element {
    BRAUN_SCENE_ELEM_SCENE = 0,
    BRAUN_SCENE_ELEM_BODY,
    BRAUN_SCENE_ELEM_POINT,
    BRAUN_SCENE_ELEM_ROD,
    BRAUN_SCENE_ELEM_JOINT,
    BRAUN_SCENE_ELEM_EFFECT
} braun_scene_element;

typedef struct braun_scene_error {
    int status;           /* BRAUN_OK or a braun_status */
    int element;          /* braun_scene_element */
    int index;            /* index in that array, -1 for the scene */
    const char *what;     /* static sentence, e.g. "rod end is on a rigid body" */
} braun_scene_error;

/* Validate the description, number the coordinates (bodies in order, each
 * its class's dof: 3 for a rigid body, 2 for a particle, 7 for rigid3d)
 * and the rows (of Φ_q: rods, then holonomic joints in order, then the
 * bodies' own rows (a rigid3d's unit quaternion) in body order; of Φ_v:
 * nonholonomic joints — knife edges — in order), and fill sys with the
 * scene's callbacks
 * (sys->user = s: the scene must outlive the system). With s->q_scale
 * (the caller's n entries) it writes the coordinates' natural sizes there
 * (braun_scene_natural_sizes at the initial state) and sets sys->q_scale
 * to it, for the accuracy guard; else sys->q_scale = NULL. Rejects dangling
 * indices, non-finite or out-of-range numbers (|x| > BRAUN_SCENE_MAX_ABS),
 * non-positive masses, inertias and lengths, a coordinate without mass,
 * rods ending on rigid bodies, joints of a body with itself, zero axes,
 * step drives and more than one gravity; planar and spatial bodies in one
 * scene, an element of the other dimension, a point of a planar scene off
 * z = 0; a NULL class or a class without its required hooks (joints:
 * rows, eval; bodies: mass or mass_at, kinetic or kinetic_at, point, grad,
 * weight, gravity_potential, constraint when rows > 0). err may be NULL.
 * Sizes: a scene with rods has at most BRAUN_MAX_DENSE (4096) coordinates
 * and rows; one without rods up to BRAUN_MAX_SPARSE (2^20), since it can be
 * handed out sparse (below) — braun_model_init refuses the dense system of
 * a scene above 4096 with BRAUN_ERR_SIZE.
 * Returns BRAUN_OK, BRAUN_ERR_ARGUMENT (bad description) or BRAUN_ERR_SIZE
 * (no coordinates, or more than those bounds). */
int braun_scene_build(braun_scene *s, braun_system *sys, braun_scene_error *err);

/* For C scenes: the values a scene file leaves to the initial state, filled
 * in where the description holds 0 — every joint and effect class's
 * defaults hook called with the fields that are non-zero as "given" (a
 * distance of length 0 gets the initial distance, a spatial joint its
 * axis_b and reference directions, a spring of rest length 0 its initial
 * length; axes normalised). Call it once before braun_scene_build; a
 * scene file has had it done by its reader. Returns BRAUN_OK, or
 * BRAUN_ERR_ARGUMENT when a reference is out of range (nothing changed
 * then). */
int braun_scene_defaults(braun_scene *s);

/* ------------------------------------------------------------------ */
/* Sparse systems (large mechanisms)                                   */
/* ------------------------------------------------------------------ */
/* A scene without rods has a block-diagonal M — one block per body, in
 * coordinate order: diag(m, m, I) for a rigid body, diag(m, m) for a
 * particle (the body class's mass block) — and every row of A_q and A_vv
 * belongs to one joint that touches at most two bodies (its class's bodies
 * hook). braun_scene_build_sparse hands out
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
/* BRAUN_ERR_ARGUMENT for NULL arguments, a body without a class, or a
 * scene not built (s->n = 0). */
int braun_scene_initial_state(const braun_scene *s, braun_real *q, braun_real *v);

/* World position of point i at q (xy: 2 entries); BRAUN_ERR_ARGUMENT for
 * no such point. */
int braun_scene_point_position(const braun_scene *s, int i, const braun_real *q, braun_real *xy);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_SCENE_H */
