/*
 * libbraun host helpers: conveniences for programs running on an operating
 * system (the CLI, tests, desktop tools). They use the C library's stdio.
 *
 * Host tier (libbraun_host.a): firmware builds compile the core tier
 * (src/core) only, which never calls anything declared here.
 */
#ifndef BRAUN_HOST_H
#define BRAUN_HOST_H

#include <stddef.h>

#include "braun.h"

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_check_callbacks braun_check_callbacks_float
#define braun_check_callbacks_sized braun_check_callbacks_sized_float
#define braun_error_format braun_error_format_float
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* One readable sentence (no trailing newline or period) describing
 * d->error: what failed, where (callback, matrix entry, pivot, step) and at
 * which time, e.g.
 *   "mass matrix not positive definite at pivot 3 (value -0.0025) at t = 0"
 *   "callback 'holonomic' failed (returned -1) at t = 2"
 *   "step diverged at t = 13.24 (h = 0.001, v[2] not finite)".
 * The status name itself is not included; braun_status_str() gives it.
 * Works like snprintf: writes at most size bytes including the NUL (buf may
 * be NULL when size is 0) and returns the length the full sentence needs,
 * or -1 if d is NULL. Only meaningful after a call on d returned
 * d->error.status (every failing call records itself, NULL pointers
 * included; only a NULL d cannot be). */
int braun_error_format(const braun_data *d, char *buf, size_t size);

/* Your callbacks against finite differences of themselves at one state
 * (t, q, v) — the Jacobians and b-terms the library takes as given, and
 * whose mistakes its corrections hide (a wrong b_qv is removed step by step
 * as drift; a law that disagrees with the forces is enforced). Each figure
 * is the largest difference over the quantity's scale (0 where the system
 * has no such rows or law):
 *   jacobian_q  A_q against ∂Φ_q/∂q
 *   b_q         against −∂Φ_q/∂t
 *   b_qv        against −d/dt(A_q v − b_q) along (t, q) → (t + τ, q + τv)
 *   jacobian_v  A_vv against ∂Φ_v/∂v
 *   b_vv        against −d/dt Φ_v along the same line
 *   energy_gradient  dE_dq, dE_dv, dE_dt against differences of E
 *   energy_rate |dE/dt along the ideal motion − Ė| over its terms, with
 *               Ė = power (BRAUN_ENERGY_INPUT) + the constraint force's
 *               work rate: judged only at a state on the constraints
 *               (state_residual, ‖Φ_q‖ + ‖[Φ̇_q; Φ_v]‖, each below 1e-8 of
 *               its rows' terms: Σ_j |A_ij| max(|q_j|, s_j), resp.
 *               Σ_j |A_ij| max(|v_j|, s_j) + |b_i|, with the sizes s),
 *               NaN elsewhere.
 *   homogeneous_v  with BRAUN_SCLERONOMIC: |Φ_v − A_vv v| over its terms,
 *               the largest row — the flag needs Φ_v = A_vv v (no term
 *               without v, whose ideal force does work the flag drops);
 *               rep->worst "Phi_v[1] - A_vv[1] v = -1.5 at this state:
 *               BRAUN_SCLERONOMIC needs ..." above tol.
 * Every output of every callback is first checked finite at the state:
 * BRAUN_ERR_NONFINITE, rep->worst "A_vv[0][1] is +Inf (nonholonomic
 * callback at t = 0)" (names Phi_q, A_q, b_q, b_qv, Phi_v, A_vv, b_vv, M,
 * Q, E, dE_dq, dE_dv, dE_dt, P), whatever the system's flags.
 * Steps: each coordinate's own (cbrt(ε)·max(s, |x|), s its typical size: 1
 * here, given to braun_check_callbacks_sized; the same s per second for
 * its velocity), and time's own
 * (cbrt(ε·max(1, |t|)): a drive varies on its period, not on |t|); along
 * the motion time and groups of coordinates of like step separately, so a
 * body far away or a large t does not set the others' step. An entry
 * that disagrees is also differenced at steps up to 16⁴ the first (an
 * angle 1e12 + t moves in quanta of 1.2e-4). What the differences cannot
 * resolve is not judged (t = 1e12: b_q to about 1e-2 only).
 * Central differences in double (about 1e-10 of a smooth callback's
 * scale), each with an allowance for its own round-off and truncation; an
 * entry that disagrees is differenced again at steps down to 16⁻⁸ of the
 * first, and judged by the estimate the differences resolve best (a drive
 * of 1e12 rad/s; a velocity of 1e6 m/s). Returns BRAUN_OK when every figure is at most tol (≤ 0: 1e-6;
 * 1e-3 in a float build, whose differences resolve no better),
 * BRAUN_ERR_ARGUMENT when one is above it (rep->worst names the entry of
 * the first such figure in the order above, e.g. "A_q[2][2]", "b_qv[3]",
 * "energy rate" — a wrong A_q also shows in b_qv; rep->worst_value its
 * figure; with none above tol, the largest's entry, or "none (every
 * difference 0)"), or the status of
 * what failed, rep->worst saying what (a NULL sys, q or v:
 * BRAUN_ERR_ARGUMENT, "state q (NULL)"; rep NULL: BRAUN_ERR_ARGUMENT
 * alone; a state that is not finite:
 * BRAUN_ERR_NONFINITE; a callback's refusal: BRAUN_ERR_CALLBACK; a system
 * the library refuses; BRAUN_ERR_BUFFER). Sparse
 * systems too (their compressed rows are scattered). Check a few states,
 * moving ones included: at rest the velocity terms are not exercised. */
typedef struct braun_callback_report {
    double jacobian_q, b_q, b_qv, jacobian_v, b_vv, energy_gradient, energy_rate;
    double homogeneous_v; /* BRAUN_SCLERONOMIC: the largest |Φ_v − A_vv v|
                           * over its terms' magnitudes (0 without p or
                           * the flag) */
    double state_residual;
    double worst_value;
    char worst[160]; /* the entry, or what failed ("state q[2]", "holonomic
                      * callback returned -3 at t = 0.1", the library's
                      * sentence for a system it refuses) */
    char note[200];  /* "" or the first entry where the callback is not
                      * differentiable at the state — a kink, as a
                      * torsion3d's potential at θ0 ± π: its one-sided
                      * differences disagree and the callback gives one of
                      * them, which is then not held against it ("dE_dq[6]
                      * is not differentiable at this state (one-sided
                      * differences: from below -15.7, from above 15.7;
                      * the callback gives 15.7)") */
} braun_callback_report;
int braun_check_callbacks(const braun_system *sys, braun_real t, const braun_real *q,
                          const braun_real *v, double tol, braun_callback_report *rep);
/* The same with each coordinate's typical size (size: n entries, finite
 * and > 0, else BRAUN_ERR_ARGUMENT "size[k] ..."; NULL: 1 each, as
 * braun_check_callbacks): the steps' floor, in the coordinates' own units.
 * A floor of 1 is 1 m: a spatial mechanism of 1 µm (the shipped
 * spatial-arm scaled down) failed at dE_dq, stepped 6e-6 m through it. A
 * scene's: braun_scene_coordinate_sizes (braun_scene.h). */
int braun_check_callbacks_sized(const braun_system *sys, braun_real t, const braun_real *q,
                                const braun_real *v, const braun_real *size, double tol,
                                braun_callback_report *rep);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_HOST_H */
