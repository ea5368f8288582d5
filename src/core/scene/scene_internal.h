/*
 * Private to src/core/scene: helpers shared by the class files (one file
 * per body, joint and effect type) and the generic parts (builder,
 * callbacks, sparse system). The class interface itself is public
 * (braun_scene.h): a class defined outside libbraun uses the same.
 *
 * Conventions of every row function: the output pointers are already
 * offset to the element's first row (phi[0], A[0..n-1], b[0], bv[0]); an
 * output is NULL when the library does not want it at this call. A is
 * zeroed by the caller and the rows are added into, so a point that meets
 * the same body twice still gets the sum of its columns.
 */
#ifndef BRAUN_SCENE_INTERNAL_H
#define BRAUN_SCENE_INTERNAL_H

#include "braun_math.h"
#include "braun_scene.h"

#ifdef BRAUN_SINGLE
#define braun_scene__hypot hypotf
#define braun_scene__atan2 atan2f
#else
#define braun_scene__hypot hypot
#define braun_scene__atan2 atan2
#endif

#define BRAUN_SCENE__PI BRAUN_R(3.14159265358979323846)

/* How far |x|² of a direction given as a unit vector (or x·y of two given
 * as perpendicular) may be from 1 (0): 1e-9 in double; in float a unit
 * vector rounded to float is off by a few ε (a skew axis by 6e-8). */
#define BRAUN_SCENE__UNIT_TOL \
    (BRAUN_EPS > BRAUN_R(1e-10) ? BRAUN_R(16.0) * BRAUN_EPS : BRAUN_R(1e-9))

/* Internal spelling of the public point kinematics (scene_point.c). */
typedef braun_scene_pt scene_pt;
#define braun_scene__point braun_scene_pt_eval
#define braun_scene__angle braun_scene_body_angle

/* row += (gx, gy)·J_P: the gradient of g·P with respect to q. */
static inline void braun_scene__add_grad(const scene_pt *P, braun_real gx, braun_real gy,
                                         braun_real *row)
{
    const braun_real g[3] = {gx, gy, 0};
    braun_scene_pt_grad(P, g, row);
}

/* Record a build error in err (may be NULL) and return status. */
int braun_scene__fail(braun_scene_error *err, int status, int element, int index,
                      const char *what);

/* Offset of entry (row, col) of a row-major matrix with n columns. */
static inline size_t braun_scene__at(int row, int col, int n)
{
    return (size_t)row * (size_t)n + (size_t)col;
}

/* ------------------------------------------------------ references */
static inline int braun_scene__body_of(const braun_scene *s, int point)
{
    return s->points[point].body;
}

/* The refusal of a joint or spring whose two ends lie on one body (NULL if
 * they do not): on the ground it constrains nothing or pulls at nothing
 * and is named so — "connects a body to itself" read as a modelling slip
 * of a body. body_a, body_b: the ends' bodies (-1 the ground); spring: 0 a
 * joint, 1 a spring, 2 a rotational spring. */
static inline const char *braun_scene__same_body(int body_a, int body_b, int spring)
{
    static const char *const ground[3] = {"joint has both ends on the ground",
                                          "spring has both ends on the ground",
                                          "rotational spring has both ends on the ground"};
    static const char *const body[3] = {"joint connects a body to itself", "spring connects a body to itself",
                                        "rotational spring connects a body to itself"};
    if (body_a != body_b) return NULL;
    return body_a < 0 ? ground[spring] : body[spring];
}

/* The same for an element given by its two points. */
static inline const char *braun_scene__same_body_points(const braun_scene *s, int point_a, int point_b,
                                                        int spring)
{
    return braun_scene__same_body(braun_scene__body_of(s, point_a), braun_scene__body_of(s, point_b), spring);
}

/* A body index in range (not the ground). */
static inline int braun_scene__is_body(const braun_scene *s, int body)
{
    return body >= 0 && body < s->nbodies;
}

/* A body with an angle (a planar rigid body). */
static inline int braun_scene__is_rigid(const braun_scene *s, int body)
{
    return braun_scene__is_body(s, body) && s->bodies[body].kind &&
           s->bodies[body].kind->angle >= 0;
}

static inline int braun_scene__ok_body_ref(const braun_scene *s, int body)
{
    return body == BRAUN_SCENE_GROUND || braun_scene__is_body(s, body);
}

static inline int braun_scene__ok_point_ref(const braun_scene *s, int point)
{
    return point >= 0 && point < s->npoints;
}

/* Column of θ of body i, -1 for the ground (or a body without angle). */
static inline int braun_scene__theta_col(const braun_scene *s, int body)
{
    return body >= 0 && s->bodies[body].kind->angle >= 0
               ? s->bodies[body].iq + s->bodies[body].kind->angle
               : -1;
}

/* Bodies of the planar translational kind (rigid bodies and particles):
 * weight m g at x, y, and its potential -m g·r (scene_rigid.c,
 * scene_particle.c). */
static inline void braun_scene__weight_xy(const braun_scene_body *b, const braun_real *g,
                                          braun_real *Q)
{
    Q[0] += b->mass * g[0];
    Q[1] += b->mass * g[1];
}

static inline braun_real braun_scene__gravity_potential_xy(const braun_scene_body *b,
                                                           const braun_real *g,
                                                           const braun_real *q)
{
    return -(b->mass * (g[0] * q[0] + g[1] * q[1]));
}

/* ------------------------------------------------------ 3-vectors */
static inline braun_real braun_scene__dot3(const braun_real *a, const braun_real *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* x is a unit vector to BRAUN_SCENE__UNIT_TOL. */
static inline int braun_scene__is_unit3(const braun_real *x)
{
    return braun_fabs(braun_scene__dot3(x, x) - 1) <= BRAUN_SCENE__UNIT_TOL;
}

static inline void braun_scene__cross3(const braun_real *a, const braun_real *b, braun_real *c)
{
    const braun_real x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
                     z = a[0] * b[1] - a[1] * b[0];
    c[0] = x;
    c[1] = y;
    c[2] = z;
}

/* x / |x| in place; returns |x| (0: left as it is). */
static inline braun_real braun_scene__normalize3(braun_real *x)
{
    const braun_real n = braun_sqrt(braun_scene__dot3(x, x));
    if (n > 0)
        for (int k = 0; k < 3; k++) x[k] /= n;
    return n;
}

/* A body with the class hooks spatial joints need for axes (a direction
 * hook), or the ground. */
static inline int braun_scene__has_frame(const braun_scene *s, int body)
{
    return body < 0 || (body < s->nbodies && s->bodies[body].kind->direction != NULL);
}

/* ----------------------------------------------- spatial rows (scene_frames.c) */
/* A world vector x(q) that a spatial row is built from: a point P1, the
 * difference P1 - P2 of two points, or a body-fixed direction (P1 from
 * braun_scene_dir_eval); x, x' and the velocity product cc of x''. */
typedef struct scene_vec {
    const scene_pt *p1, *p2; /* p2 NULL: x = p1 */
    braun_real x[3], dx[3], cc[3];
} scene_vec;

void braun_scene__vec(scene_vec *x, const scene_pt *p1, const scene_pt *p2);
/* row += scale · gᵀ ∂x/∂q */
void braun_scene__vec_grad(const scene_vec *x, const braun_real *g, braun_real scale,
                           braun_real *row);
/* Φ = x·y - f(t): phi, A (added), b = f', bv = -(cc_x·y + 2x'·y' + x·cc_y) + f''
 * (f NULL: 0). Any output may be NULL. */
void braun_scene__dot_row(const scene_vec *x, const scene_vec *y, const braun_scene_fn *f,
                          braun_real t, braun_real *phi, braun_real *A, braun_real *b,
                          braun_real *bv);
/* The rows P_a - P_b = 0 (3). */
void braun_scene__coincide_rows(const braun_scene *s, int a, int b, const braun_real *q,
                                const braun_real *v, braun_real *phi, braun_real *A,
                                braun_real *b_q, braun_real *bv);

/* The two frames of a spatial joint: on body1 the axis u1 (j->axis), the
 * reference r1 (j->ref_a) and w1 = u1 × r1; on body2 u2 (j->axis_b), r2
 * (j->ref_b), w2 = u2 × r2 (all body-fixed, evaluated at q, v). */
typedef struct scene_frames {
    scene_pt u1, r1, w1, u2, r2, w2;
} scene_frames;
void braun_scene__frames(const braun_scene *s, const braun_scene_joint *j, int body1, int body2,
                         const braun_real *q, const braun_real *v, scene_frames *F);
/* Rows of the axes kept parallel: r1·u2 = 0, w1·u2 = 0 (2). */
void braun_scene__parallel_rows(const scene_frames *F, braun_real *phi, braun_real *A, int n,
                                braun_real *b, braun_real *bv);
/* Rows of the relative orientation kept: u1·r2, r1·w2, w1·u2 = 0 (3). */
void braun_scene__orient_rows(const scene_frames *F, braun_real *phi, braun_real *A, int n,
                              braun_real *b, braun_real *bv);
/* The drive row cos f (w1·r2) - sin f (r1·r2) = 0 of a driven revolute. */
void braun_scene__drive_row(const scene_frames *F, const braun_scene_fn *f, braun_real t,
                            braun_real *phi, braun_real *A, braun_real *b, braun_real *bv);
/* The joint's angle θ = atan2(w1·r2, r1·r2) (0 in the initial
 * configuration), its rate θ' (v may be NULL: 0) and, when grad is not
 * NULL, grad += scale · ∂θ/∂q. */
void braun_scene__joint_angle(const braun_scene *s, const braun_scene_joint *j,
                              const braun_real *q, const braun_real *v, braun_real *theta,
                              braun_real *rate, braun_real scale, braun_real *grad);
/* P (point a) on the line through A (point b) along u1: r1·(P - A) = 0,
 * w1·(P - A) = 0; with parallel first the two parallel rows (cylindrical). */
void braun_scene__line_rows(const braun_scene *s, const braun_scene_joint *j, int parallel,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv);
/* Bodies carrying frame 1 and frame 2 of joint j (ground -1). */
void braun_scene__frame_bodies(const braun_scene *s, const braun_scene_joint *j, int *body1,
                               int *body2);

/* Defaults and checks the spatial joints share (scene_frames.c): axis
 * normalised; ref_a a unit vector ⊥ axis; axis_b (when not given) and ref_b
 * the images of axis and ref_a in body2's frame at the initial state. */
void braun_scene__frame_defaults(const braun_scene *s, braun_scene_joint *j, int body1,
                                 int body2, int axis_b_given);
/* NULL, or what is wrong: bodies without frames, vectors not unit or not
 * perpendicular. need_b: axis_b is used. */
const char *braun_scene__frame_check(const braun_scene *s, const braun_scene_joint *j,
                                     int body1, int body2, int need_b);
/* R(q0) d of a body at its initial state (the ground: d). */
void braun_scene__initial_dir(const braun_scene *s, int body, const braun_real *d,
                              braun_real *out);
/* R(q0)ᵀ x: a world vector in the body's frame at its initial state. */
void braun_scene__initial_dir_inverse(const braun_scene *s, int body, const braun_real *x,
                                      braun_real *out);

/* --------------------------------------------------------------- rods */
void braun_scene__rod_mass(const braun_scene *s, const braun_scene_rod *r, braun_real *M);
braun_real braun_scene__rod_kinetic(const braun_scene *s, const braun_scene_rod *r,
                                    const braun_real *v, braun_real *dEdv);
void braun_scene__rod_rows(const braun_scene *s, const braun_scene_rod *r, const braun_real *q,
                           const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                           braun_real *bv);

/* ------------------------------------------------------------- joints */
/* The angle row θ_b - θ_a - α(t) (scene_angle.c), also the prismatic
 * joint's third row. */
void braun_scene__angle_rows(const braun_scene *s, int body_a, int body_b,
                             const braun_scene_fn *alpha, braun_real t, const braun_real *q,
                             const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                             braun_real *bv);
/* Slider rows (scene_slider.c); lock: also the angle row (prismatic). */
void braun_scene__slider_rows(const braun_scene *s, const braun_scene_joint *j, int lock,
                              braun_real t, const braun_real *q, const braun_real *v,
                              braun_real *phi, braun_real *A, braun_real *b, braun_real *bv);
/* The checks and defaults slider and prismatic joints share. */
const char *braun_scene__slider_check(const braun_scene *s, const braun_scene_joint *j);

/* The two bodies every row of joint j may touch (ground -1): its class's
 * bodies hook, or those of its reference fields (scene_build.c). */
void braun_scene__joint_bodies(const braun_scene *s, const braun_scene_joint *j, int body[2]);

/* The system of a built scene with its dense callbacks (scene_build.c). */
void braun_scene__system(braun_scene *s, braun_system *sys);

/* Callbacks of a built scene (scene_system.c). */
int braun_scene__mass(braun_real t, const braun_real *q, braun_real *M, void *user);
int braun_scene__forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                        void *user);
int braun_scene__holonomic(braun_real t, const braun_real *q, const braun_real *v,
                           braun_real *phi, braun_real *A, braun_real *b, braun_real *bv,
                           void *user);
int braun_scene__nonholonomic(braun_real t, const braun_real *q, const braun_real *v,
                              braun_real *phi, braun_real *A, braun_real *bv, void *user);
int braun_scene__energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                        braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user);
int braun_scene__power(braun_real t, const braun_real *q, const braun_real *v,
                       braun_real *Edot, void *user);

/* Pointer to row r of an output, or NULL when the output is not wanted. */
#define BRAUN_SCENE__AT(x, r) ((x) ? (x) + (r) : NULL)
#define BRAUN_SCENE__ROW(A, r, n) ((A) ? (A) + braun_scene__at(r, 0, n) : NULL)

#endif
