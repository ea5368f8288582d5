/*
 * Private to src/scene: point kinematics shared by the element files, and
 * the entry points of each element type (one file per type).
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

/* A point at a state: where it is, how it moves, and how it depends on q.
 *   P = r + R(θ) p      (rigid),  P = (x, y)  (particle),  fixed (ground)
 *   ∂P/∂(x, y) = I,  ∂P/∂θ = jt = R'(θ) p = (-Rp_y, Rp_x)
 *   P' = J v,  P'' = J v' + cc  with  cc = -R p ω²  (velocity product). */
typedef struct scene_pt {
    int ix;               /* column of x, -1 on the ground */
    int rigid;            /* θ column at ix + 2 */
    braun_real pos[2];
    braun_real vel[2];
    braun_real jt[2];     /* ∂P/∂θ (rigid) */
    braun_real cc[2];     /* -R p ω² (rigid) */
    braun_real w;         /* angular velocity of its body (0 if none) */
} scene_pt;

/* Kinematics of point i at (q, v); v may be NULL (then vel, cc, w are 0). */
void braun_scene__point(const braun_scene *s, int i, const braun_real *q, const braun_real *v,
                        scene_pt *P);

/* row += (gx, gy)·J_P: the gradient of g·P with respect to q. */
void braun_scene__add_grad(const scene_pt *P, braun_real gx, braun_real gy, braun_real *row);

/* Angle and angular velocity of body i (0 for the ground); column of θ
 * (-1 on the ground). */
int braun_scene__angle(const braun_scene *s, int body, const braun_real *q, const braun_real *v,
                       braun_real *theta, braun_real *omega);

/* ------------------------------------------------------------- bodies */
/* Diagonal blocks m, m, I (rigid) or m, m (particle) into M (n x n). */
void braun_scene__body_mass(const braun_scene *s, const braun_scene_body *bd, braun_real *M);
/* Kinetic energy ½ vᵀM_b v; adds M_b v to dEdv (may be NULL). */
braun_real braun_scene__body_kinetic(const braun_scene_body *bd, const braun_real *v,
                                     braun_real *dEdv);

/* --------------------------------------------------------------- rods */
void braun_scene__rod_mass(const braun_scene *s, const braun_scene_rod *r, braun_real *M);
braun_real braun_scene__rod_kinetic(const braun_scene *s, const braun_scene_rod *r,
                                    const braun_real *v, braun_real *dEdv);
void braun_scene__rod_rows(const braun_scene *s, const braun_scene_rod *r, const braun_real *q,
                           const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                           braun_real *bv);

/* ------------------------------------------------------------- joints */
int braun_scene__joint_rows(const braun_scene_joint *j);

/* Record a build error in err (may be NULL) and return status. */
int braun_scene__fail(braun_scene_error *err, int status, int element, int index,
                      const char *what);
void braun_scene__revolute_rows(const braun_scene *s, const braun_scene_joint *j,
                                const braun_real *q, const braun_real *v, braun_real *phi,
                                braun_real *A, braun_real *b, braun_real *bv);
void braun_scene__distance_rows(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                                const braun_real *q, const braun_real *v, braun_real *phi,
                                braun_real *A, braun_real *b, braun_real *bv);
void braun_scene__slider_rows(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                              const braun_real *q, const braun_real *v, braun_real *phi,
                              braun_real *A, braun_real *b, braun_real *bv);
void braun_scene__angle_rows(const braun_scene *s, int body_a, int body_b,
                             const braun_scene_fn *alpha, braun_real t, const braun_real *q,
                             const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                             braun_real *bv);

/* -------------------------------------------------------- knife edges */
void braun_scene__knife_rows(const braun_scene *s, const braun_scene_knife *k,
                             const braun_real *q, const braun_real *v, braun_real *phi,
                             braun_real *A, braun_real *bv);

/* ------------------------------------------------------------ effects */
/* Each effect: generalized force into Q, potential V (returned) with
 * ∂V/∂q into dVdq (may be NULL), input power (returned). Springs return a
 * recoverable 1 through *st when their two points coincide. */
void braun_scene__gravity_forces(const braun_scene *s, const braun_scene_effect *e,
                                 const braun_real *q, braun_real *Q);
braun_real braun_scene__gravity_potential(const braun_scene *s, const braun_scene_effect *e,
                                          const braun_real *q, braun_real *dVdq);

int braun_scene__spring_forces(const braun_scene *s, const braun_scene_effect *e,
                               const braun_real *q, const braun_real *v, braun_real *Q);
int braun_scene__spring_potential(const braun_scene *s, const braun_scene_effect *e,
                                  const braun_real *q, braun_real *V, braun_real *dVdq);
int braun_scene__spring_power(const braun_scene *s, const braun_scene_effect *e,
                              const braun_real *q, const braun_real *v, braun_real *P);

void braun_scene__torsion_forces(const braun_scene *s, const braun_scene_effect *e,
                                 const braun_real *q, const braun_real *v, braun_real *Q);
braun_real braun_scene__torsion_potential(const braun_scene *s, const braun_scene_effect *e,
                                          const braun_real *q, braun_real *dVdq);
braun_real braun_scene__torsion_power(const braun_scene *s, const braun_scene_effect *e,
                                      const braun_real *q, const braun_real *v);

void braun_scene__force_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                               const braun_real *q, braun_real *Q);
braun_real braun_scene__force_power(const braun_scene *s, const braun_scene_effect *e,
                                    braun_real t, const braun_real *q, const braun_real *v);

void braun_scene__torque_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                                braun_real *Q);
braun_real braun_scene__torque_power(const braun_scene *s, const braun_scene_effect *e,
                                     braun_real t, const braun_real *q, const braun_real *v);

void braun_scene__motor_forces(const braun_scene *s, const braun_scene_effect *e,
                               const braun_real *q, const braun_real *v, braun_real *Q);
braun_real braun_scene__motor_power(const braun_scene *s, const braun_scene_effect *e,
                                    const braun_real *q, const braun_real *v);

/* Offset of entry (row, col) of a row-major matrix with n columns. */
static inline size_t braun_scene__at(int row, int col, int n)
{
    return (size_t)row * (size_t)n + (size_t)col;
}

/* Column of θ of body i, -1 for the ground (or a particle). */
static inline int braun_scene__theta_col(const braun_scene *s, int body)
{
    return body >= 0 && s->bodies[body].kind == BRAUN_BODY_RIGID ? s->bodies[body].iq + 2 : -1;
}

/* Rows of joint j into phi, A, b, bv (offset to its first row, any may be
 * NULL; A with row stride s->n). 0, or -1 for an unknown joint type. */
int braun_scene__joint_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv);

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

#endif
