/* projection: the textbook explicit competitor (Eich 1993; Hairer & Wanner
 * II, Sec. VII.2): classic RK4 on the index-1 equation of motion
 *     M a = Q + Aᵀλ,  A a = b            (A = [A_q; A_vv], b = [b_qv; b_vv])
 * followed after every step by a mass-orthogonal projection of q onto
 * Φ_q = 0 (simplified Gauss–Newton, Jacobian at the predicted point, to a
 * tolerance, iterations counted) and of v onto A_q v = b_q, Φ_v = 0; the
 * variant `energy` then also projects v onto the energy level
 * E(t, q, v) = E0 + ∫Ė dτ (the work integral integrated with the state).
 * The harness's own linear algebra (cmp_dense.c): nothing of libbraun's
 * method, only the system's callbacks. Also the trajectory reference of
 * scenes without a minimal-coordinate equation (cmp_reference.c). */
#ifndef CMP_PROJ_H
#define CMP_PROJ_H

#include "cmp.h"

/* Position tolerance ‖Φ_q‖₂ of the projection and its iteration limit. */
#define CMP_PROJ_TOL 1e-12
#define CMP_PROJ_MAX_ITER 20

typedef struct cmp_proj cmp_proj;

/* A workspace for sys (dense callbacks). NULL if out of memory or sparse. */
cmp_proj *cmp_proj_new(const braun_system *sys);
void cmp_proj_free(cmp_proj *p);

/* The index-1 acceleration a (n) at (t, q, v), and the power of the
 * constraint forces vᵀ(M a − Q) in *pc (may be NULL). 0, 1 (a callback
 * asked to retry, or a non-finite value) or -1. */
int cmp_proj_accel(cmp_proj *p, double t, const double *q, const double *v, double *a,
                   double *pc);
/* The input rate Ė of the applied forces (0 without BRAUN_ENERGY_INPUT). */
int cmp_proj_power(cmp_proj *p, double t, const double *q, const double *v, double *P);
/* Project q onto Φ_q(t, q) = 0: the iterations taken (>= 0), or -1 when
 * ‖Φ_q‖ stays above CMP_PROJ_TOL after CMP_PROJ_MAX_ITER iterations or a
 * callback fails. *res: the final ‖Φ_q‖ (may be NULL). */
int cmp_proj_positions(cmp_proj *p, double t, double *q, double *res);
/* Project v onto A_q v = b_q, Φ_v = 0 at (t, q): iterations or -1. */
int cmp_proj_velocities(cmp_proj *p, double t, const double *q, double *v);
/* Project v onto E(t, q, v) = E_target as well, keeping the velocity
 * rows: iterations (0 when it could not move: no kinetic direction), or
 * -1 on a callback failure. */
int cmp_proj_energy(cmp_proj *p, double t, const double *q, double *v, double E_target);
/* E(t, q, v) (the system's energy law); -1 if it has none. */
int cmp_proj_energy_of(cmp_proj *p, double t, const double *q, const double *v, double *E);
/* Work done so far: factorizations of C, minimum-norm solves, projection
 * iterations (positions, velocities and energy together). */
void cmp_proj_counts(const cmp_proj *p, long *factorizations, long *solves, long *iterations);

/* One integration: RK4 at step h from (q0, v0) at t = 0 (projected first)
 * to T; out(t, q, v, a, user) at every step that is a multiple of every
 * (and at the last), returning nonzero to stop. energy: 1 for the energy
 * variant. On failure *status_name gets its name and *t_fail the time;
 * returns 0 if T was reached. */
typedef int (*cmp_proj_out_fn)(double t, const double *q, const double *v, const double *a,
                               void *user);
int cmp_proj_integrate(const cmp_target *tg, double h, double T, long every, int energy,
                       cmp_proj_out_fn out, void *user, cmp_outcome *outcome);

#endif
