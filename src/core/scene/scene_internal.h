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
#else
#define braun_scene__hypot hypot
#endif

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
