/* The corrections of the equation of motion, as named stages scaled by the
 * step h: the ideal impulse of Eq. 16 (position), the Δ_v term of Eq. 17
 * (velocity) and the nonideal energy force of Eq. 20 (energy), and their
 * composition braun__corrections. They run at the point of a forward pass
 * that computed the residuals (braun_forward.c). */
#include "braun_internal.h"

/* ================================================================ */
/* The accuracy guard (braun.h, options.guard) on the residuals this step's
 * start has computed: the state the last step left. A residual above both
 * its bound and its size at braun_set_state stops the run. */
static void guard_rescale(braun_data *d, int accel);

/* The energy correction applies: asked for, a law, and E0 taken. */
static int energy_corrected(const braun_data *d)
{
    return (d->model->opt.corrections & BRAUN_CORRECT_ENERGY) && d->model->sys.energy && d->has_E0;
}

/* ... and the accuracy guard judges the law: not while E0 waits for a
 * start's error to be removed (stage_energy). */
static int energy_judged(const braun_data *d)
{
    return energy_corrected(d) && braun__priv(d)->e0_pending != 2;
}

BRAUN_FORCE_INLINE int guard_exceeds(const braun_data *d, braun_real r2, braun_real scale, braun_real r0)
{
    const braun_real g = d->model->opt.guard > 0 ? d->model->opt.guard : BRAUN_R(1e-3);
    braun_real bound = g * scale;
    /* The start's own residual, r0 = sqrt(r2) there: squared again it can
     * fall an ulp below r2, and the same start, tried again (an adaptive
     * attempt rejected), "exceeded" a bound equal to itself. */
    if (r0 > bound) bound = r0 * (1 + 4 * BRAUN_EPS);
    return !(r2 <= bound * bound);
}

/* A residual above its bound (the slow path of guard_fails): the scales
 * are the start's; a start at rest with no force yet (a load or a drive
 * that begins at zero, no gravity) has none, and every later round-off
 * would fail. They grow with the motion: measured again at this point,
 * the larger kept, before the residual is judged. */
static int guard_fails_again(braun_data *d, braun_real r2, const braun_real *scale, braun_real r0,
                             int accel, const char *what)
{
    guard_rescale(d, accel);
    if (!guard_exceeds(d, r2, *scale, r0)) return BRAUN_OK;
    return braun__fail(d, BRAUN_ERR_ACCURACY, what, -1, -1, (double)braun_sqrt(r2),
                       (double)braun__priv(d)->at.t);
}

/* r2: the squared residual; scale: its scale in d->guard (the slow path
 * may raise it); r0: its value at the start; accel: a forward pass at the
 * point has ã (the forces' acceleration enters the velocity scale).
 * Inline: the check runs at every step, the slow path almost never. */
BRAUN_FORCE_INLINE int guard_fails(braun_data *d, braun_real r2, const braun_real *scale, braun_real *r0,
                                   int accel, const char *what)
{
    if (!guard_exceeds(d, r2, *scale, *r0)) {
        /* Within its bound without the start's allowance: the corrections
         * have removed the start's error, and the allowance ends (it let a
         * run from a start far off its constraints drift that far for
         * good). */
        if (*r0 > 0 && !guard_exceeds(d, r2, *scale, 0)) *r0 = 0;
        return BRAUN_OK;
    }
    return guard_fails_again(d, r2, scale, *r0, accel, what);
}

/* The energy residual Φ_e of a point against its bound. */
BRAUN_FORCE_INLINE int guard_energy(braun_data *d, braun_real phi_e, int accel)
{
    return guard_fails(d, phi_e * phi_e, &d->guard.energy, &d->guard.energy0, accel,
                       "accuracy guard: energy residual |Phi_e|");
}

/* The start's position error is still being removed: its allowance pos0
 * is in force (not yet ended by a check within guard × scale) and the
 * start is off its constraints, above sqrt(ε) of the position scale (as
 * judge_start judges a start; one on its constraints has pos0 at
 * round-off, and 0 from its first check on). Even a start within the
 * bound moves the velocity rows by its correction: a four-bar whose crank
 * started 0.05 rad off, turning at 5 rad/s, had ‖Φ_q‖ 0.035 of a bound of
 * 0.037 and a velocity residual of 0.16 of 0.094 after its first step. */
static int start_off_positions(const braun_data *d)
{
    const braun_real p0 = d->guard.pos0;
    return p0 > 0 && p0 > braun_sqrt(BRAUN_EPS) * d->guard.pos;
}

/* An allowance in use: the start's residual r0 exceeds guard × scale. */
static int allowance_in_use(const braun_data *d, braun_real r0, braun_real scale)
{
    return r0 > 0 && guard_exceeds(d, r0 * r0, scale, 0);
}

/* A residual norm the guard refused: d->error.index is its largest row,
 * so that a program (the CLI, braun_scene_file) can name the joint whose
 * rows drift. Refused while the allowance of a start off its position
 * constraints is in use (the start's ‖Φ_q‖ above its bound, or a velocity
 * allowance its position corrections made above its own), the cause is
 * that start (too far off for the corrections, or the step too large to
 * remove its error), and the failure says so: `where` names it and
 * d->error.index2 is the start's largest position row. A rare path. */
static int largest_entry(int count, const braun_real *r)
{
    int at = 0;
    for (int i = 1; i < count; i++)
        if (braun_fabs(r[i]) > braun_fabs(r[at])) at = i;
    return at;
}

static BRAUN_NOINLINE int worst_row(braun_data *d, int count, const braun_real *r, int velocity)
{
    braun_priv *pv = braun__priv(d);
    d->error.index = largest_entry(count, r);
    if (allowance_in_use(d, d->guard.pos0, d->guard.pos) ||
        (velocity && pv->vel_induced0 > 0 && allowance_in_use(d, d->guard.vel0, d->guard.vel))) {
        d->error.where = velocity ? "accuracy guard: velocity residual |[dPhi_q; Phi_v]| (a start off its "
                                    "position constraints)"
                                  : "accuracy guard: position residual |Phi_q| (a start off its position "
                                    "constraints)";
        d->error.index2 = pv->start_row;
    }
    return BRAUN_ERR_ACCURACY;
}

BRAUN_FORCE_INLINE int guard_rows(braun_data *d, unsigned corr, int accel)
{
    braun_priv *pv = braun__priv(d);
    int st = BRAUN_OK;
    if ((corr & BRAUN_CORRECT_POSITION) && pv->m > 0) {
        st = guard_fails(d, braun_dot(pv->m, pv->phi, pv->phi), &d->guard.pos, &d->guard.pos0, accel,
                         "accuracy guard: position residual |Phi_q|");
        if (st == BRAUN_ERR_ACCURACY) return worst_row(d, pv->m, pv->phi, 0);
    }
    if (!st && (corr & BRAUN_CORRECT_VELOCITY) && pv->rows > 0) {
        st = guard_fails(d, braun_dot(pv->rows, pv->ev, pv->ev), &d->guard.vel, &d->guard.vel0, accel,
                         "accuracy guard: velocity residual |[dPhi_q; Phi_v]|");
        if (st == BRAUN_ERR_ACCURACY) return worst_row(d, pv->rows, pv->ev, 1);
    }
    return st;
}

int braun__final_checks(braun_data *d)
{
    /* A claim already found false failed this call and reported it (the
     * finding, with its difference, or "found at an earlier call"): checked
     * again it wrote the second over the first. */
    if (braun__priv(d)->mass_claim_false) return BRAUN_ERR_ARGUMENT;
    const int st = braun__check_mass_claim(d, d->t, d->q);
    return st ? st : braun__guard_final(d);
}

/* A driver's last state: no next step starts there to check it, so one
 * evaluation of the residuals does (constraints and energy; no
 * factorization, no right-hand side). */
int braun__guard_final(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    if (d->model->opt.guard < 0 || pv->guard_pending) return BRAUN_OK;
    const unsigned corr = d->model->opt.corrections;
    /* The energy law judged where the steps judge it. */
    const int energy = energy_judged(d);
    braun_real p = 0, v = 0, e = 0;
    int st = braun_residuals(d, d->t, d->q, d->v, &p, &v, energy ? &e : NULL);
    /* A NaN of a callback at a state a step reached is the run's, as in
     * the stages (braun_step.c, diverged_if_integrated). */
    if (st == BRAUN_ERR_NONFINITE && pv->state_integrated) d->error.status = st = BRAUN_ERR_DIVERGED;
    if (st) return st;
    pv->at.t = d->t;
    /* No forward pass here: the scales may grow with q and v only. */
    st = guard_rows(d, corr, 0);
    if (!st && energy) st = guard_energy(d, e, 0);
    return st;
}

/* ================================================================ */
/* Stage position: the ideal impulse of Eq. 16, scaled by h. With
 * Δ_q = Φ_q/h the position correction of one step is
 *   dq = h(q' − v) = R⁻¹C_q⁺(h(b_q − A_q v) − Φ_q) = −R⁻¹C_q⁺(Φ_q + hΦ̇_q),
 * the minimum-norm (in M) displacement that removes the first-order
 * prediction of Φ_q at the end of the step. Dependent rows must agree: a
 * position error outside range(C_q) is one no motion can remove — the
 * constraints have no solution there (e.g. x = 0 and x = 1) — and fails
 * with BRAUN_ERR_INCONSISTENT; only rank-deficient factorizations pay for
 * that check. */

/* The right-hand side of Eq. 16: ep = −(Φ_q + h·Φ̇_q). */
static void position_rhs(braun_priv *pv)
{
    const braun_real h = pv->at.h;
    for (int i = 0; i < pv->m; i++) pv->ep[i] = -(pv->phi[i] + h * pv->ev[i]);
}

/* The failure of dependent rows, naming the two that disagree most: the
 * largest entries of the least-squares residual A·x − sign·r over the
 * first `rows` rows (a rare path: the user's program can name the joints).
 * A second row is named only if its own entry exceeds the tolerance: a row
 * whose gradient depends on the others' while its error does not (a joint
 * started at a singular configuration) is alone in the residual. */
static BRAUN_NOINLINE int disagreeing_rows(braun_data *d, int rows, const braun_real *x,
                                           const braun_real *r, braun_real sign, braun_real resid,
                                           braun_real tol, const char *what)
{
    braun_priv *pv = braun__priv(d);
    int worst = -1, next = -1;
    braun_real rw = -1, rn = -1;
    for (int i = 0; i < rows; i++) {
        const braun_real e = braun_fabs(braun__row_dot(pv, i, x) - sign * r[i]);
        if (e > rw) {
            next = worst;
            rn = rw;
            worst = i;
            rw = e;
        } else if (e > rn) {
            next = i;
            rn = e;
        }
    }
    if (!(rn > tol)) next = -1;
    if (next < 0 && worst >= 0) {
        /* One row alone: a gradient of zero (index2 -2) is named as such,
         * not as one that depends on the others. */
        for (int j = 0; j < pv->n; j++) pv->tmp[j] = 1;
        if (braun__row_abs_dot(pv, worst, pv->tmp) == 0) next = -2;
    }
    return braun__fail(d, BRAUN_ERR_INCONSISTENT, what, worst, next, (double)resid, (double)pv->at.t);
}

/* Eq. 16's dependent rows disagree: A·dq ≠ ep. */
static BRAUN_NOINLINE int inconsistent(braun_data *d, braun_real resid, braun_real tol)
{
    braun_priv *pv = braun__priv(d);
    braun__solve_r(pv, pv->dq, pv->dq);
    return disagreeing_rows(d, pv->m, pv->dq, pv->ep, 1, resid, tol, "holonomic constraints");
}

/* The library's inconsistency tolerance for the first `rows` rows, their
 * residuals computed from x (q or v) and their target r: the option, in
 * the rows' units, when set; by default sqrt(ε) of the rows' own size at
 * the point, the largest Σ_j |A_ij|·|x_j| + |r_i| (the scale of the
 * rounding of a row computed from x, and of its target). An absolute
 * sqrt(ε) was a length in metres (or m² for a distance row): a mechanism
 * of 10 µm whose two distance rows cannot both hold (L and 2L from one
 * anchor) ran BRAUN_OK 58 % off one of them, and a consistent redundant
 * one of 10 km stopped on its round-off, 2e-16·L² (found by an outside
 * client). Scratch: pv->tmp (free where the corrections judge). A rare
 * path: only rank-deficient factorizations judge. */
static braun_real inconsistency_tol(braun_data *d, int rows, const braun_real *x, const braun_real *r)
{
    if (d->model->opt.inconsistency_tol > 0) return d->model->opt.inconsistency_tol;
    braun_priv *pv = braun__priv(d);
    braun_real big = 0;
    for (int j = 0; j < pv->n; j++) pv->tmp[j] = braun_fabs(x[j]);
    for (int i = 0; i < rows; i++) {
        const braun_real sum = braun__row_abs_dot(pv, i, pv->tmp) + braun_fabs(r[i]);
        if (sum > big) big = sum;
    }
    return braun_sqrt(BRAUN_EPS) * big;
}

/* The round-off floor of a correction's right-hand side (braun_linsolver.h
 * rhs_floor; docs/method.md, "The round-off floor of the corrections"): a
 * residual computed from x (Φ from q, [Φ̇_q; Φ_v] from v) carries rounding
 * of about eps·Σ_j |A_ij|·|x_j| in row i, so the part of it outside the
 * range of a rank-deficient C (exactly dependent rows) below
 * BRAUN_RHS_FLOOR·eps times the largest such sum is noise, which a backend
 * that finds the least-squares part by iteration need not chase. The
 * velocity correction passes that floor; the position correction a
 * thousandth of it (BRAUN_RHS_FLOOR_Q): the dependent rows' own position
 * error must still go, since the next factorizations' rank decisions see
 * it, and left at the floor it accumulated. Only for a backend that takes
 * the floor, at a rank-deficient factorization (nothing else leaves an
 * inconsistency): O(nnz(A)). scale 0 restores exact solves. */
#define BRAUN_RHS_FLOOR 4
#define BRAUN_RHS_FLOOR_Q BRAUN_R(1e-3)
static void rhs_floor(braun_priv *pv, int slot, int rows, const braun_real *x,
                      braun_real scale)
{
#ifdef BRAUN_NO_LINSOLVER
    (void)pv, (void)slot, (void)rows, (void)x, (void)scale;
#else
    if (!pv->ls->rhs_floor) return;
    braun_real big = 0;
    if (scale > 0) {
        /* |x| into pv->tmp (free here: the remeasured point is restored
         * before the velocity correction) */
        for (int j = 0; j < pv->n; j++) pv->tmp[j] = braun_fabs(x[j]);
        for (int i = 0; i < rows; i++) {
            const braun_real sum = braun__row_abs_dot(pv, i, pv->tmp);
            if (sum > big) big = sum;
        }
    }
    pv->ls->rhs_floor(pv->ls_state, slot, scale * BRAUN_RHS_FLOOR * BRAUN_EPS * big);
#endif
}

static BRAUN_NOINLINE int velocity_consistent(braun_data *d);
static void velocity_finish(braun_priv *pv);

/* Eq. 16's right-hand side has no least-squares solution: ep = −(Φ + hΦ̇)
 * carries the velocity error too, scaled by h. Rows whose positions agree
 * and whose velocities do not (two drives of one coordinate) fail here
 * first, and were named as positions that disagree by h times the velocity
 * error: judged by Φ alone, such a failure is the velocities', and is
 * reported at velocity level with their own residual. A rare path. */
static BRAUN_NOINLINE int position_failure(braun_data *d, int slot, braun_real resid, braun_real tol)
{
    braun_priv *pv = braun__priv(d);
    braun_real rq = 0;
    for (int i = 0; i < pv->m; i++) pv->ep[i] = -pv->phi[i];
    braun__lsq(pv, slot, pv->ep, pv->dq, &rq);
    if (rq <= tol) {
        braun__pinv(pv, 0, pv->ev, pv->dv);
        velocity_finish(pv);
        const int st = velocity_consistent(d);
        if (st) return st;
    }
    position_rhs(pv);
    braun__lsq(pv, slot, pv->ep, pv->dq, &resid);
    return inconsistent(d, resid, tol);
}

static int stage_position(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int m = pv->m;
    /* C_q is its own factorization (slot 1) when there are nonholonomic
     * rows too; otherwise it is C_v. */
    const int slot = pv->need_fq ? 1 : 0;
    const int deficient = pv->need_fq ? pv->rank[1] < m : pv->rank[0] < pv->rows;
    position_rhs(pv);
    if (deficient) {
        braun_real resid;
        rhs_floor(pv, slot, m, pv->at.q, BRAUN_RHS_FLOOR_Q);
        braun__lsq(pv, slot, pv->ep, pv->dq, &resid);
        rhs_floor(pv, slot, m, pv->at.q, 0);
        const braun_real tol = inconsistency_tol(d, m, pv->at.q, pv->ep);
        if (resid > tol) return position_failure(d, slot, resid, tol);
    } else {
        braun__pinv(pv, slot, pv->ep, pv->dq);
    }
    braun__solve_r(pv, pv->dq, pv->dq);
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage velocity: the velocity-level force of Eq. 17, its Δ_v term scaled
 * by h. With Δ_v = [Φ̇_q; Φ_v]/h,
 *   dv = −h R⁻¹C_v⁺Δ_v = −R⁻¹C_v⁺[Φ̇_q; Φ_v],
 * the minimum-norm (in M) velocity change that removes the velocity-level
 * error of both kinds of rows. The pseudoinverse is linear, so the sign is
 * applied to the result (exactly: IEEE negation is sign-symmetric). */

/* dv := −R⁻¹ dv, dv holding C_v⁺[Φ̇_q; Φ_v]. */
static void velocity_finish(braun_priv *pv)
{
    const int n = BRAUN_N(pv->n);
    braun__solve_r(pv, pv->dv, pv->dv);
    for (int i = 0; i < n; i++) pv->dv[i] = -pv->dv[i];
}

/* First-order consistency, judged once after braun_set_state: dependent
 * velocity-level rows must agree, A·dv = −[Φ̇_q; Φ_v] (two drives of one
 * joint at different rates; a knife across a driven slider). Later the
 * holonomic rows' disagreement shows in Eq. 16 (the positions drift
 * apart), but a nonholonomic row's would only be left uncorrected, and a
 * run would end with status 0 and the rows violated. Rows without a time
 * term cannot trip it: their error A v lies in the range of C = A R⁻¹
 * (up to the dropped pivots, below the plain rank tolerance at a start).
 * Only at the start: within a run the rank rule keeps a row dropped near
 * a singular configuration (pivots up to sqrt(ε)), whose velocity error
 * along the weak direction then stays by design (docs/method.md). */
static BRAUN_NOINLINE int velocity_consistent(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    braun_real r2 = 0;
    for (int i = 0; i < pv->rows; i++) {
        const braun_real e = braun__row_dot(pv, i, pv->dv) + pv->ev[i];
        r2 += e * e;
    }
    const braun_real resid = braun_sqrt(r2), tol = inconsistency_tol(d, pv->rows, pv->at.v, pv->ev);
    if (!(resid > tol)) return BRAUN_OK;
    return disagreeing_rows(d, pv->rows, pv->dv, pv->ev, -1, resid, tol,
                            "velocity-level constraint rows");
}

/* judge: this is the first velocity correction since braun_set_state. */
static int stage_velocity(braun_data *d, int judge)
{
    braun_priv *pv = braun__priv(d);
    const int deficient = pv->rank[0] < pv->rows;
    if (deficient) rhs_floor(pv, 0, pv->rows, pv->at.v, 1);
    braun__pinv(pv, 0, pv->ev, pv->dv);
    if (deficient) rhs_floor(pv, 0, pv->rows, pv->at.v, 0); /* exact again */
    velocity_finish(pv);
    if (judge && deficient) return velocity_consistent(d);
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage energy: the nonideal energy force of Eq. 20, scaled by h and added
 * to dv. The energy law (Eq. 18) Φ_e = E − E0 − ∫Ė is a nonideal
 * nonholonomic constraint; at the acceleration level (Eq. 19) A_e = ∂E/∂v,
 * b_e = −∂E/∂t − (∂E/∂q)v + Ė. Q0 = Rᵀ[C_e N_v]⁺(b_ev − A_ev a − Δ_ev)
 * acts through R⁻¹N_vR⁻ᵀ (Eq. 17): the minimum-norm velocity change
 * tangent to the kinematic constraints (N_v) that removes the first-order
 * prediction of Φ_e at the end of the step, given the ideal acceleration
 * and the velocity correction dv of this step. With x = N_v C_eᵀ the
 * pseudoinverse is x/‖x‖², and ‖x‖² ≈ 2·kinetic energy: at rest or at a
 * turning point it would explode. The guard: the relative change σ of the
 * weighted velocity is saturated at energy_max_rel (docs/method.md). */

/* The saturation of the energy force: the largest relative change of the
 * weighted velocity per step (options.energy_max_rel, default 1 %). */
static braun_real energy_max_rel(const braun_data *d)
{
    return d->model->opt.energy_max_rel > 0 ? d->model->opt.energy_max_rel : BRAUN_R(0.01);
}

static void measure_scales(braun_data *d, int accel, int again, braun_real *pos_out,
                           braun_real *vel_out, braun_real *energy_out);

/* The point's residuals relative to their scales (the guard's, measured
 * here): max(‖Φ_q‖∞ / pos, ‖[Φ̇_q; Φ_v]‖∞ / vel), of those the corrections
 * remove. */
/* The point's residuals against given scales pos and vel. */
static braun_real residual_against(const braun_priv *pv, unsigned corr, braun_real pos, braun_real vel)
{
    braun_real rp = 0, rv = 0;
    /* Only what the corrections remove: with the velocity correction off
     * a velocity residual stays, and E0 waited for it for good. */
    for (int i = 0; (corr & BRAUN_CORRECT_POSITION) && i < pv->m; i++)
        if (braun_fabs(pv->phi[i]) > rp) rp = braun_fabs(pv->phi[i]);
    for (int i = 0; (corr & BRAUN_CORRECT_VELOCITY) && i < pv->rows; i++)
        if (braun_fabs(pv->ev[i]) > rv) rv = braun_fabs(pv->ev[i]);
    const braun_real a = pos > 0 ? rp / pos : 0, b = vel > 0 ? rv / vel : 0;
    return a > b ? a : b;
}

static braun_real relative_residual_of(braun_data *d, unsigned corr)
{
    braun_real pos, vel, energy;
    measure_scales(d, 1, 0, &pos, &vel, &energy);
    return residual_against(braun__priv(d), corr, pos, vel);
}

static braun_real relative_residual(braun_data *d)
{
    return relative_residual_of(d, d->model->opt.corrections);
}

/* A start off the constraints: its first corrections remove the error, and
 * change the energy by what the error held (a velocity along a rod: its
 * kinetic energy). E0 taken at the start would have the energy force put
 * that back into the admissible motion — a pendulum released from the
 * horizontal with a velocity along its rod rose above its pivot, status
 * OK. So a start whose residuals exceed sqrt(ε) of their scales gets no
 * energy force while the corrections remove them, and E0 is re-taken
 * where they have — E0 = E − ∫Ė (docs/api.md, E0): at the first point
 * whose residuals are within sqrt(ε), or, with the ordinary drift of a
 * large step above that, at the first that has not fallen to half of the
 * point before's (the start's error gone, what remains the step's own)
 * and is within 1e-3. A start on the constraints keeps its E0. In a step
 * or driver only (busy): braun_eval is the literal Eq. 20 at any point,
 * with the E0 the data holds. 1: no energy force at this point. */
/* The start judged on (0) or off (2) its constraints, at the point. */
static void judge_start(braun_data *d, braun_real r)
{
    braun_priv *pv = braun__priv(d);
    pv->e0_pending = r > braun_sqrt(BRAUN_EPS) ? 2 : 0;
    pv->e0_last = r;
    pv->e0_t = pv->at.t;
}

/* Φ_e = E − E0 − ∫Ė is a difference of those three: within a few ulps of
 * them it is round-off, which a correction would only feed into the
 * motion (the stages' energy force and the step's end judge by this). */
static braun_real energy_roundoff(const braun_data *d, braun_real E, braun_real W)
{
    return 4 * BRAUN_EPS * (braun_fabs(E) + braun_fabs(d->E0) + braun_fabs(W));
}

static int energy_deferred(braun_data *d, braun_real E)
{
    braun_priv *pv = braun__priv(d);
    if (!pv->e0_pending || !pv->busy) return 0;
    const braun_real r = pv->rows > 0 ? relative_residual(d) : 0, tol = braun_sqrt(BRAUN_EPS);
    if (pv->e0_pending == 1) { /* the start: off its constraints, no force yet */
        judge_start(d, r);
        return r > tol;
    }
    /* The point judged last, again (an adaptive attempt rejected and tried
     * anew from its start): the same residual has not "stopped halving". */
    if (pv->at.t == pv->e0_t) return 1;
    if (r > tol && !(r >= BRAUN_R(0.5) * pv->e0_last && r <= BRAUN_R(1e-3))) {
        pv->e0_last = r;
        pv->e0_t = pv->at.t;
        return 1;
    }
    d->E0 = E - pv->at.W;
    pv->e0_pending = 0;
    return 0;
}

static int stage_energy(braun_data *d, const braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = BRAUN_N(pv->n);
    const braun_real t = pv->at.t, *q = pv->at.q, *v = pv->at.v, h = pv->at.h;
    braun_real E = 0, dEdt = 0;
    int st = BRAUN__CALL(d, s->energy, "energy", t, t, q, v, &E, pv->dEdq, pv->dEdv, &dEdt, s->user);
    if (st) return st;
    /* The outputs' finiteness in one pass (braun_all_finite's test); only
     * a failure scans them one by one, to name the culprit. */
    braun_real z0 = E * 0 + dEdt * 0;
    for (int i = 0; i < n; i++) z0 += pv->dEdq[i] * 0 + pv->dEdv[i] * 0;
    if (!(z0 == 0)) {
        st = braun__check_finite(d, 1, &E, "energy E", 0, t);
        if (!st) st = braun__check_finite(d, n, pv->dEdq, "energy dE/dq", 0, t);
        if (!st) st = braun__check_finite(d, n, pv->dEdv, "energy dE/dv", 0, t);
        if (!st) st = braun__check_finite(d, 1, &dEdt, "energy dE/dt", 0, t);
        if (st) return st;
    }

    if (energy_deferred(d, E)) {
        pv->de_ok = 0; /* nor at the step's end (braun__energy_at_end) */
        return BRAUN_OK;
    }
    /* Eq. 18 and Eq. 19. */
    const braun_real phi_e = E - d->E0 - pv->at.W;
    if (pv->guard_on && pv->guard_first) {
        /* An inconsistent start: the first corrections change the energy
         * by about (∂E/∂q)·dq + (∂E/∂v)·dv + ½|R dv|², which the energy law
         * (E0 taken at the start) then sees as its error: allowed, twice. */
        braun__mul_r(pv, pv->dv, pv->tmp);
        const braun_real e0 = braun_fabs(braun_dot(n, pv->dEdq, pv->dq)) +
                              braun_fabs(braun_dot(n, pv->dEdv, pv->dv)) +
                              BRAUN_R(0.5) * braun_dot(n, pv->tmp, pv->tmp);
        d->guard.energy0 = 2 * e0;
    } else if (pv->guard_on) {
        st = guard_energy(d, phi_e, 1);
        if (st) return st;
    }
    const braun_real b_e = -dEdt - braun_dot(n, pv->dEdq, v) + pv->Edot;
    /* h·(b_ev − A_ev a − Δ_ev) of Eq. 20, written with the ideal
     * acceleration and the velocity correction dv of this step (0 when off):
     *   r = −(Φ_e + h (A_e q''_ideal − b_e) + A_e dv). */
    const braun_real r = -(phi_e + h * (braun_dot(n, pv->dEdv, vdot) - b_e) +
                           braun_dot(n, pv->dEdv, pv->dv));
    /* x = N_v C_eᵀ, C_e = A_e R⁻¹. */
    braun__solve_rt(pv, pv->dEdv, pv->ce);
    /* ‖C_eᵀ‖² = ‖R v‖² = 2T for E = T + V: the motion's own scale. */
    const braun_real cc = braun_dot(n, pv->ce, pv->ce);
    if (pv->rows > 0) braun__null_project(pv, 0, pv->ce);
    const braun_real xx = braun_dot(n, pv->ce, pv->ce);
    /* A free motion at round-off of the motion's own speed (a wheel at rest
     * on a driven turntable, the spin of a driven linkage's coupler) is no
     * direction: saturated at energy_max_rel of that speed, the force fed
     * the energy law's error into it at 1 % per step, and round-off grew
     * to a spin of 3.6e-5 rad/s in 100 s, status OK (found by an outside
     * client). The force waits for a motion (at rest, cc = 0, as before). */
    if (cc > 0 && xx <= BRAUN_EPS * cc) {
        if (pv->energy_end) pv->de_ok = 0;
        return BRAUN_OK;
    }
    const braun_real smax = energy_max_rel(d);
    braun_real sigma;
    /* Φ_e and the step's predicted change within a few ulps of E, E0 and
     * ∫Ė are round-off, as at the step's end (braun__energy_at_end): no
     * force. Sized on them, the force took from a motion starting from
     * rest the kinetic energy its positions, whose first increments h·v
     * fall below their ulp, could not yet turn into a fall: a float
     * slider-crank at h = 1e-5 never moved, status OK (found by an outside
     * client; see also the state's compensated sum, braun_step.c). */
    const int roundoff = braun_fabs(r) <= energy_roundoff(d, E, pv->at.W);
    const int saturated = !roundoff && !(braun_fabs(r) <= smax * xx);
    /* No direction at all where the rows leave no motion free (every
     * coordinate driven): nothing to saturate, no hit (at rest there is a
     * direction, which the motion does not yet have). */
    const int free_motion = pv->rank[0] < n;
    if (roundoff) sigma = 0;
    else if (!saturated) sigma = xx > 0 ? r / xx : 0;
    else sigma = r > 0 ? smax : -smax;
    if (pv->energy_end) {
        /* Sized at the end of the step (braun__energy_at_end): the
         * direction here, and this prediction for a motion too slow to be
         * sized at the end. */
        pv->de_ok = xx > 0;
        pv->sigma0 = sigma;
        pv->sat0 = saturated;
        if (pv->de_ok) braun__solve_r(pv, pv->ce, pv->de);
        else if (saturated && free_motion) BRAUN__COUNT(d->stats.energy_guard_hits); /* at rest */
        return BRAUN_OK;
    }
    if (saturated && (xx > 0 || free_motion)) BRAUN__COUNT(d->stats.energy_guard_hits);
    if (sigma == 0) return BRAUN_OK;
    for (int i = 0; i < n; i++) pv->tmp[i] = sigma * pv->ce[i];
    braun__solve_r(pv, pv->tmp, pv->tmp);
    for (int i = 0; i < n; i++) pv->dv[i] += pv->tmp[i];
    return BRAUN_OK;
}

/* The energy force of a per-step multi-stage step, sized at the step's
 * ideal end z: the velocity change σ·d along the first stage's direction
 * d = R⁻¹N_vC_eᵀ that removes the energy error the step would leave —
 *   Φ_e(z) + ∂E/∂q·dq + ∂E/∂v·dv + ½dvᵀM dv + σ(∂E/∂v + M dv)·d = 0
 * (first order in dq and σ) — the step's own truncation error of the
 * energy law included, which the start's first-order prediction left for
 * the next step (docs/method.md, "The energy force and its guard"). */
int braun__energy_at_end(braun_data *d, braun_real t1, const braun_real *y1)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int n = BRAUN_N(pv->n);
    if (!pv->de_ok) return BRAUN_OK;
    const braun_real *q = y1, *v = y1 + n;
    braun_real E = 0, dEdt = 0;
    int st = BRAUN__CALL(d, s->energy, "energy", t1, t1, q, v, &E, pv->dEdq, pv->dEdv, &dEdt, s->user);
    if (st) return st;
    const braun_real phi_e = E - d->E0 - y1[2 * n];
    /* Kinetic energy is quadratic in v: the velocity correction dv changes
     * E by ∂E/∂v·dv + ½dvᵀM dv exactly (M of the step's start: the
     * difference is O(h·|dv|²)), and the slope along d is taken at v + dv. */
    braun__mul_r(pv, pv->dv, pv->tmp);
    braun__mul_r(pv, pv->de, pv->ce);
    braun_real r = -(phi_e + braun_dot(n, pv->dEdq, pv->dq) + braun_dot(n, pv->dEdv, pv->dv) +
                           BRAUN_R(0.5) * braun_dot(n, pv->tmp, pv->tmp));
    const braun_real g = braun_dot(n, pv->dEdv, pv->de) + braun_dot(n, pv->tmp, pv->ce);
    if (!braun_is_finite(r) || !braun_is_finite(g)) {
        /* A NaN/Inf of E or its gradient reaches r or g (0·Inf is NaN):
         * only then are the callback's outputs scanned, to name it. */
        st = braun__check_finite(d, 1, &E, "energy E", 0, t1);
        if (!st) st = braun__check_finite(d, n, pv->dEdq, "energy dE/dq", 0, t1);
        if (!st) st = braun__check_finite(d, n, pv->dEdv, "energy dE/dv", 0, t1);
        if (!st) st = braun__fail(d, BRAUN_ERR_NONFINITE, "energy force (overflow)", -1, -1, 0, (double)t1);
        return st;
    }
    const braun_real floor_e = energy_roundoff(d, E, y1[2 * n]);
    const braun_real smax = energy_max_rel(d);
    braun_real sigma_end = 0;
    int sat_end = 0;
    if (braun_fabs(r) <= floor_e) {
        /* round-off: sigma_end stays 0 */
    } else if (g > 0 && braun_fabs(r) <= smax * g) {
        sigma_end = r / g;
    } else {
        sigma_end = g > 0 ? (r > 0 ? smax : -smax) : 0;
        sat_end = 1;
    }
    /* Near rest, where even an error at the floor would need more than
     * energy_max_rel (energy_max_rel·g / floor ≲ 1), sizing by Φ_e(z)
     * only kicks the velocity by round-off: the start's prediction takes
     * over, continuously (a switch would turn the round-off difference of
     * two equal runs into a different branch). */
    const braun_real rel = floor_e > 0 ? smax * g / floor_e : BRAUN_R(1e30);
    const braun_real w = rel >= BRAUN_R(1e15) ? 1 : rel * rel / (1 + rel * rel);
    const braun_real sigma = w * sigma_end + (1 - w) * pv->sigma0;
    if (w >= BRAUN_R(0.5) ? sat_end : pv->sat0) BRAUN__COUNT(d->stats.energy_guard_hits);
    if (sigma == 0) return BRAUN_OK;
    for (int i = 0; i < n; i++) pv->dv[i] += sigma * pv->de[i];
    return BRAUN_OK;
}

/* ================================================================ */
/* Composition. */

/* The accuracy guard's scales (braun.h, braun_data.guard) at the point
 * pv->at, from A (and, with accel, ã of a forward pass there): into
 * pos, vel, energy. At the start the energy scale is that of a motion at
 * the velocity scale (the motion to come); later (again) the kinetic
 * energy the motion has — the velocity scale puts every coordinate at the
 * fastest one's speed, and an energy scale grown from that let a chain's
 * energy law drift by 2.2 J before the guard saw it (chain-5, RK4,
 * h = 1e-2). Scratch: pv->ce, pv->tmp (free wherever the guard runs). */
/* The scales from each coordinate's size sq and speed sv (n entries):
 * pos = Σ_i Σ_j |A_ij| sq_j over the holonomic rows, vel the same with sv
 * over all rows, energy = max(e_floor, ½ s_vᵀ M s_v = ½ ‖R s_v‖² — again:
 * ½ vᵀ M v —, |∫Ė|). scratch (n) may be sq: it is written last. */
static void scales_of(braun_data *d, const braun_real *sq, const braun_real *sv, int again,
                      braun_real e_floor, braun_real *scratch, braun_real *pos_out,
                      braun_real *vel_out, braun_real *energy_out)
{
    braun_priv *pv = braun__priv(d);
    braun_real pos = 0, vel = 0;
    for (int i = 0; i < pv->m; i++) pos += braun__row_abs_dot(pv, i, sq);
    for (int i = 0; i < pv->rows; i++) vel += braun__row_abs_dot(pv, i, sv);
    braun__mul_r(pv, again ? pv->at.v : sv, scratch);
    const braun_real T = BRAUN_R(0.5) * braun_dot(pv->n, scratch, scratch);
    braun_real energy = e_floor > T ? e_floor : T;
    if (braun_fabs(pv->at.W) > energy) energy = braun_fabs(pv->at.W);
    *pos_out = pos;
    *vel_out = vel;
    *energy_out = energy > 0 ? energy : BRAUN_R(1e-30);
}

static void measure_scales_sized(braun_data *d, int accel, int again, braun_real *pos_out,
                                 braun_real *vel_out, braun_real *energy_out);

static void measure_scales(braun_data *d, int accel, int again, braun_real *pos_out,
                           braun_real *vel_out, braun_real *energy_out)
{
    if (d->model->sys.q_scale) {
        measure_scales_sized(d, accel, again, pos_out, vel_out, energy_out);
        return;
    }
    braun_priv *pv = braun__priv(d);
    const int n = pv->n, rows = pv->rows;
    const braun_real *q = pv->at.q, *v = pv->at.v;
    braun_real *sq = pv->ce, *sv = pv->tmp;
    braun_real L = BRAUN_R(1e-6), V = 0;
    for (int j = 0; j < n; j++) {
        if (braun_fabs(q[j]) > L) L = braun_fabs(q[j]);
        if (braun_fabs(v[j]) > V) V = braun_fabs(v[j]);
    }
    if (accel) {
        /* a = M⁻¹Q = R⁻¹ã: the unconstrained acceleration (gravity, springs). */
        braun__solve_r(pv, pv->atil, sq);
        braun_real amax = 0;
        for (int j = 0; j < n; j++)
            if (braun_fabs(sq[j]) > amax) amax = braun_fabs(sq[j]);
        if (braun_sqrt(L * amax) > V) V = braun_sqrt(L * amax);
    }
    /* A row's own velocity, c = ev − A v (a drive's rate, −Φ_t), moves its
     * coordinates at |c| / Σ|A_ij|: a body at rest driven at 1 rad/s had
     * velocity and energy scales of 0, its start's residual was not seen
     * and E0 kept the energy of the wrong start. */
    for (int j = 0; j < n; j++) sv[j] = 1; /* row_abs_dot(ones): Σ|A_ij| */
    for (int i = 0; i < rows; i++) {
        const braun_real c = braun_fabs(pv->ev[i] - braun__row_dot(pv, i, v)),
                         a = braun__row_abs_dot(pv, i, sv);
        if (a > 0 && c > V * a) V = c / a;
    }
    for (int j = 0; j < n; j++) {
        sq[j] = braun_fabs(q[j]) > L ? braun_fabs(q[j]) : L;
        sv[j] = braun_fabs(v[j]) > V ? braun_fabs(v[j]) : V;
    }
    /* The energy the scene holds: E0, the kinetic scale, the work done. */
    scales_of(d, sq, sv, again, braun_fabs(d->E0), sq, pos_out, vel_out, energy_out);
}

/* The same with the system's natural sizes s_q = sys.q_scale (braun.h):
 * each coordinate in its own unit, none from where the mechanism is.
 *   pos: Σ_i Σ_j |A_ij| s_q,j — the residual a displacement of each
 *        coordinate by its size makes;
 *   vel: the same with s_v,j = max(|v_j|, W·s_q,j): W one rate (1/s) for
 *        the whole mechanism, each coordinate moving through its size at
 *        it, so that ½ W² s_qᵀ M s_q (in J, whatever the coordinates'
 *        units) is the larger of the kinetic energy ½ vᵀ M v and the work
 *        E_f = ½ |Qᵀ s| of the forces over the sizes (s_j = s_q,j in the
 *        direction Q drives coordinate j: a fall over the mechanism's
 *        size; a torque on a small inertia counts its work over 1 rad,
 *        not its acceleration τ/I); or a drive's rate |c_i| / Σ_j |A_ij|
 *        s_q,j if faster;
 *   energy: max(½ s_vᵀ M s_v, |∫Ė|) (again: ½ vᵀ M v in place of the
 *        first). |E0| is left out: its datum (a potential's zero) is
 *        arbitrary — a pendulum 10 km above it had m·g·10 km.
 * Scratch as measure_scales. */
static void measure_scales_sized(braun_data *d, int accel, int again, braun_real *pos_out,
                                 braun_real *vel_out, braun_real *energy_out)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n, rows = pv->rows;
    const braun_real *q_scale = d->model->sys.q_scale, *v = pv->at.v;
    braun_real *sa = pv->ce, *sv = pv->tmp;
    /* T_q = ½ s_qᵀ M s_q, T = ½ vᵀ M v. */
    braun__mul_r(pv, q_scale, sa);
    const braun_real Tq = BRAUN_R(0.5) * braun_dot(n, sa, sa);
    braun__mul_r(pv, v, sa);
    braun_real E = BRAUN_R(0.5) * braun_dot(n, sa, sa);
    if (accel) {
        /* Qᵀ s = ãᵀ R s, a = R⁻¹ã giving the directions. */
        braun__solve_r(pv, pv->atil, sa);
        for (int j = 0; j < n; j++) sv[j] = sa[j] < 0 ? -q_scale[j] : q_scale[j];
        braun__mul_r(pv, sv, sa);
        const braun_real Ef = BRAUN_R(0.5) * braun_fabs(braun_dot(n, pv->atil, sa));
        if (Ef > E) E = Ef;
    }
    braun_real W = Tq > 0 ? braun_sqrt(E / Tq) : 0;
    for (int i = 0; i < rows; i++) {
        const braun_real c = braun_fabs(pv->ev[i] - braun__row_dot(pv, i, v)),
                         a = braun__row_abs_dot(pv, i, q_scale);
        if (a > 0 && c > W * a) W = c / a;
    }
    for (int j = 0; j < n; j++) sv[j] = braun_fabs(v[j]) > W * q_scale[j] ? braun_fabs(v[j]) : W * q_scale[j];
    scales_of(d, q_scale, sv, again, 0, sa, pos_out, vel_out, energy_out);
}

/* The scales at the state braun_set_state gave (the first step's forward
 * pass: A, the residuals, ã), and the residuals there. */
void braun__guard_scales(braun_data *d, const braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    (void)vdot;
    measure_scales(d, 1, 0, &d->guard.pos, &d->guard.vel, &d->guard.energy);
    d->guard.pos0 = braun_sqrt(braun_dot(pv->m, pv->phi, pv->phi));
    d->guard.vel0 = braun_sqrt(braun_dot(pv->rows, pv->ev, pv->ev));
    d->guard.energy0 = 0; /* Φ_e = 0 where E0 was taken; see stage_energy */
    pv->guard_pending = 0;
    pv->guard_first = 1;
    pv->vel_induced0 = 0;
    pv->start_row = -1;
    pv->start_off = start_off_positions(d);
    if (pv->start_off) pv->start_row = largest_entry(pv->m, pv->phi); /* the row a refusal names */
}

/* The scales measured again at the point, each kept when larger. */
/* A scale measured again: the larger kept, but at most twice the old one.
 * A diverging state raises the scales it is judged by (A, q and v all
 * grow with it): a chain of 500 links at RK4 h = 2e-2 (position and
 * velocity corrections) went from ‖Φ_q‖ 1.6e-3 to 8e4 in two steps with
 * its position scale raised to 3e84, and was never stopped. A motion
 * grows its scales by O(h) per step; a residual that outgrows a doubling
 * per measurement is the run's. A scale with no size yet (0, or the
 * energy's 1e-30: a start at rest with no force) takes the measurement. */
static braun_real grown_scale(braun_real old, braun_real now)
{
    if (!(now > old)) return old;
    if (!(old > BRAUN_R(1e-30))) return now;
    return now < 2 * old ? now : 2 * old;
}

static void guard_rescale(braun_data *d, int accel)
{
    braun_real pos, vel, energy;
    measure_scales(d, accel, 1, &pos, &vel, &energy);
    d->guard.pos = grown_scale(d->guard.pos, pos);
    d->guard.vel = grown_scale(d->guard.vel, vel);
    d->guard.energy = grown_scale(d->guard.energy, energy);
}

/* The guard at a step's start, on its rows: the state braun_set_state
 * gave defines the scales and passes; any later one is checked. */
static int guard_start_rows(braun_data *d, const braun_real *vdot, unsigned corr)
{
    if (braun__priv(d)->guard_pending) {
        braun__guard_scales(d, vdot);
        return BRAUN_OK;
    }
    return guard_rows(d, corr, 1);
}

/* Position (Eq. 16) and velocity (Eq. 17) into pv->dq, pv->dv: a stage that
 * runs writes all of its increment, one that is off leaves it zero. With
 * remeasure (the corrections at a step's end) the velocity-level residual is
 * measured again where the position correction put q: A(q)v − b_q changes
 * with q by ∂(A v − b)/∂q·dq, which the residual at the point does not see
 * (the four-bar, rtol 1e-10: ‖[Φ̇_q; Φ_v]‖ 2.4e-9 after the correction
 * without this). One call of the constraint callbacks; C stays the
 * point's. */
/* The first velocity correction of a run at full rank: a start a little
 * off a redundant set's manifold. Rows dependent on the manifold are
 * dependent off it only to the point's residual, and the plain rank
 * tolerance (10·max(rows, n)·ε) counts them independent at a start placed
 * to 13 digits: the parallelogram with its redundant crank, each angle
 * 1e-13 off, had 12 rows of rank 12 (no motion left), and RK4's first
 * step took all its kinetic energy, status OK (found by an outside
 * client). Its sign: a velocity residual at round-off whose correction
 * removes half the weighted speed or more, ‖R dv‖ > ½‖R v‖ — a tiny
 * residual over a tiny pivot. Then the start's positions are projected
 * with a rank that needs sqrt(ε) (braun__project_positions) and its first
 * step is taken again (rk_stages), once; elsewhere (or twice) the run
 * stops with BRAUN_ERR_INCONSISTENT rather than lose the motion. */
static BRAUN_NOINLINE int start_rank_check(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    braun__mul_r(pv, pv->dv, pv->tmp);
    const braun_real cdv = braun_nrm2(n, pv->tmp);
    braun__mul_r(pv, pv->at.v, pv->tmp);
    const braun_real cv = braun_nrm2(n, pv->tmp);
    if (!(cdv > BRAUN_R(0.5) * cv) || !(cv > 0)) return BRAUN_OK;
    if (!(relative_residual_of(d, BRAUN_CORRECT_VELOCITY) <= BRAUN_R(1e-6))) return BRAUN_OK;
    if (pv->start_retry) return BRAUN__START_AMBIGUOUS;
    return braun__fail(d, BRAUN_ERR_INCONSISTENT,
                       "constraint rows dependent only to the start's residual: the velocity correction "
                       "would take this share of the motion (a redundant set off its manifold: give the "
                       "start to full precision)",
                       -1, -1, (double)(cdv / cv), (double)pv->at.t);
}

static int position_velocity(braun_data *d, unsigned corr, int remeasure)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    const int position = pv->rows > 0 && pv->m > 0 && (corr & BRAUN_CORRECT_POSITION);
    const int velocity = pv->rows > 0 && (corr & BRAUN_CORRECT_VELOCITY);
    /* The first velocity correction since braun_set_state judges the rows'
     * consistency (velocity_consistent) — whichever path it takes: a full
     * rank has nothing to judge, and a later rank-deficient step is no
     * start (a row dropped near a singular configuration keeps its error
     * along the weak direction by design). */
    const int judge = velocity && !pv->vel_judged;
    if (velocity) pv->vel_judged = 1;
    int st = BRAUN_OK;
    if (position && velocity && !remeasure && !pv->need_fq && pv->rank[0] >= pv->rows) {
        /* Eqs. 16 and 17 with one factorization (C_q is C_v, full rank):
         * stage_position and stage_velocity's operations, the two
         * pseudoinverse applies in one walk of the factor. */
        position_rhs(pv);
        braun__pinv2(pv, 0, pv->ep, pv->ev, pv->dq, pv->dv);
        braun__solve_r(pv, pv->dq, pv->dq);
        velocity_finish(pv);
        return judge ? start_rank_check(d) : BRAUN_OK;
    }
    if (position) st = stage_position(d);
    else for (int i = 0; i < n; i++) pv->dq[i] = 0;
    if (!st && remeasure && position && velocity) {
        const braun_real *q1 = pv->at.q;
        for (int i = 0; i < n; i++) pv->tmp[i] = q1[i] + pv->dq[i];
        pv->at.q = pv->tmp;
        st = braun__stage_constraints(d, 1);
        pv->at.q = q1;
    }
    if (!st && velocity) st = stage_velocity(d, judge);
    else for (int i = 0; i < n; i++) pv->dv[i] = 0;
    if (!st && judge && pv->rank[0] >= pv->rows) st = start_rank_check(d);
    return st;
}

/* A start off its position constraints, moving (docs/method.md, "No
 * silent wrong answers"): while its position error is being removed (the
 * allowance pos0 in force), each step's position correction dq (Eq. 16)
 * moves q under a velocity it leaves as it was, and the velocity-level
 * rows at the corrected q see that velocity: [Φ̇_q; Φ_v] changes by
 * ∂(A v − b)/∂q·dq, O(|dq|·|v|) whatever h (a body spinning at 1 rad/s
 * about a driven hinge, started 0.02 rad off its drive: 0.0141 against a
 * bound of 0.0085, BRAUN_ERR_ACCURACY at the first step at every h; found
 * by an outside client). The next step's velocity correction removes it;
 * the guard, judging that step's start, must allow it: measured here, at
 * (t, q + dq, v) against (t, q, v) — one evaluation of the constraints,
 * and one more to restore the point's rows — and allowed twice (the terms
 * of higher order in dq and h), the velocity allowance vel0 raised to it,
 * never above the first step's, and ending as the start's do (at the first
 * check within guard × scale). A start on its constraints never comes
 * here: the trajectory is the same with the guard on or off. */
static BRAUN_NOINLINE int allow_induced_velocity(braun_data *d, unsigned corr)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n), rows = pv->rows;
    if (!(d->guard.pos0 > 0)) {
        pv->start_off = 0; /* the start's position error is gone: for good */
        return BRAUN_OK;
    }
    if (!(corr & BRAUN_CORRECT_POSITION) || !(corr & BRAUN_CORRECT_VELOCITY) || pv->m == 0 || rows == 0 ||
        !start_off_positions(d))
        return BRAUN_OK;
    const braun_real *q = pv->at.q;
    braun_real *ev = pv->enorm; /* scratch: the adaptive error norm is computed after the stages */
    for (int i = 0; i < rows; i++) ev[i] = pv->ev[i];
    for (int i = 0; i < n; i++) pv->tmp[i] = q[i] + pv->dq[i];
    pv->at.q = pv->tmp;
    int st = braun__stage_constraints(d, 1);
    pv->at.q = q;
    if (st) return st;
    braun_real r2 = 0;
    for (int i = 0; i < rows; i++) {
        const braun_real e = pv->ev[i] - ev[i];
        r2 += e * e;
    }
    /* A, Φ, b and the residuals of the point again (the energy force and
     * the scales read them). */
    st = braun__stage_constraints(d, 1);
    if (st) return st;
    braun_real a = 2 * braun_sqrt(r2);
    if (!braun_is_finite(a)) return BRAUN_OK; /* the next step's start will say */
    if (pv->guard_first) pv->vel_induced0 = a;
    else if (a > pv->vel_induced0) a = pv->vel_induced0;
    if (a > d->guard.vel0) d->guard.vel0 = a;
    return BRAUN_OK;
}

int braun__corrections(braun_data *d, const braun_real *vdot, int guard_run)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const int energy = energy_corrected(d);
    const int guard = guard_run && d->model->opt.guard >= 0;
    pv->guard_on = guard;
    /* The forward pass at this point with the residuals (and Ė for the
     * energy force) is what the corrections work on. */
    int st = braun__need(d, BRAUN_DONE_IDEAL | BRAUN_DONE_RESIDUALS |
                                (energy ? BRAUN_DONE_POWER : 0u),
                         "corrections before a forward pass with residuals at the point");
    if (st) return st;
    if (guard) {
        st = guard_start_rows(d, vdot, corr);
        if (st) return st;
    }
    /* The start is judged at the start also while the energy force is off:
     * switched on later (an output callback may), it found E0 still the
     * inconsistent start's and put that energy into the motion (0.5 mJ of
     * a pendulum's velocity along its rod, status OK); now E0 is re-taken
     * where the state has settled. Once per run. */
    if (!energy && pv->e0_pending == 1 && pv->busy && d->model->sys.energy && d->has_E0)
        judge_start(d, pv->rows > 0 ? relative_residual(d) : 0);
    st = position_velocity(d, corr, 0);
    if (!st && energy) st = stage_energy(d, vdot);
    if (guard) {
        /* The velocity residual the position correction of a start off
         * its position constraints creates: allowed. Only such a start
         * pays (one comparison per step otherwise). */
        if (pv->start_off && !st) st = allow_induced_velocity(d, corr);
        pv->guard_first = 0;
    }
    return st;
}

/* A point's corrections at h = 0 (Δ_q = Φ_q, a Gauss–Newton step in the
 * mass metric; Δ_v = [Φ̇_q; Φ_v] measured again where q went): those of
 * corr at y, repeated while the residual of the rows they remove, relative
 * to the guard's scales, exceeds tol and still halves (at most 8 times).
 * plain: the rank by the plain tolerance, else every pivot past sqrt(ε)
 * (the rule of a rising rank). y = [q; v; ∫Ė] changed in place; *moved
 * set when a correction was applied; *r_first and *r_last the residual at
 * the first and the last point. The rank rule is plain again after. */
static int project_at_rest(braun_data *d, braun_real *y, unsigned corr, int plain, braun_real tol, int *moved,
                           braun_real *r_first, braun_real *r_last)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    const int nv = (corr & BRAUN_CORRECT_VELOCITY) ? 2 * n : n; /* what a correction moves */
    braun_real *prev = pv->yerr; /* the last accepted point (free before a step) */
    braun_real last = 0, merit_last = 0, pos0 = 0, vel0 = 0;
    int st = BRAUN_OK, cuts = 0, restored = 0;
    for (int it = 0;;) {
        braun__at(pv, d->t, y, y + n, y[2 * n], 0);
        braun__rank_rule_plain(pv);
        if (!plain) pv->rule_keep[0] = pv->rule_keep[1] = 0;
        pv->soft_on = 0;
        pv->energy_end = 0;
        pv->stage = 0;
        st = braun__forward(d, BRAUN_WITH_RESIDUALS, pv->k[0] + n);
        if (st) break;
        braun_real pos, vel, energy;
        measure_scales(d, 1, 0, &pos, &vel, &energy);
        const braun_real r = *r_last = residual_against(pv, corr, pos, vel);
        if (restored) break;
        if (it == 0 && cuts == 0) {
            *r_first = r;
            pos0 = pos;
            vel0 = vel;
        }
        /* Judged against the first point's scales, fixed: the point's own
         * grow with q, and a Gauss–Newton step far from the manifold that
         * overshot (a particle 0.02 from the pivot of a 1 m distance row,
         * sent to 6.3) looked 1e6 times better by its own scale. It was
         * kept, status OK, 2 m off at the run's end (found by an outside
         * client). A step that does not decrease the residual is halved,
         * back towards the last point, and that point is kept if none does. */
        const braun_real merit = residual_against(pv, corr, pos0, vel0);
        /* Near the manifold (within sqrt(ε)) a step that does not decrease
         * it is at the round-off floor: the iteration ends below, as before. */
        if (it > 0 && !(merit < merit_last) && merit_last > braun_sqrt(BRAUN_EPS)) {
            if (cuts < 40) {
                cuts++;
                for (int i = 0; i < nv; i++) y[i] = prev[i] + BRAUN_R(0.5) * (y[i] - prev[i]);
            } else {
                for (int i = 0; i < nv; i++) y[i] = prev[i];
                restored = 1;
            }
            continue;
        }
        /* A halved step is no sign of the floor: only a full one that did
         * not halve the residual ends the iteration. */
        if (!(r > tol) || (it > 0 && cuts == 0 && !(r < BRAUN_R(0.5) * last)) || it == 8) break;
        last = r;
        merit_last = merit;
        cuts = 0;
        st = position_velocity(d, corr, 1);
        if (st) break;
        for (int i = 0; i < nv; i++) prev[i] = y[i];
        for (int i = 0; i < n; i++) y[i] += pv->dq[i];
        if (corr & BRAUN_CORRECT_VELOCITY)
            for (int i = 0; i < n; i++) y[n + i] += pv->dv[i];
        *moved = 1;
        it++;
    }
    braun__rank_rule_plain(pv);
    return st;
}

/* A new run's start: its positions projected onto the constraints before
 * anything else — the position correction at h = 0 (a Gauss–Newton step in
 * the mass metric), repeated while the position residual, relative to its
 * scale, exceeds 8ε and still halves (at most 8 times), with the rank rule
 * of a rising rank (every pivot past sqrt(ε) of the largest). Rows
 * dependent on the manifold are dependent at a start off it only to the
 * start's residual: a parallelogram with its redundant crank started
 * 1e-13 off (angles to 13 digits) counted 12 rows of rank 12 there, no
 * motion left, and the first step's corrections took all its kinetic
 * energy, status OK (the adaptive driver's projection too). Projected, the
 * start's rank is the manifold's by the plain tolerance, which the run
 * then takes; rows only ill-conditioned keep their pivot there and are
 * counted. y = [q; v; ∫Ė], its q changed in place; *moved: a correction
 * was applied; *r_start: the start's relative position residual. judge:
 * a start moved by more than sqrt(ε) is judged off its constraints (E0
 * re-taken where they settle, energy_deferred). */
int braun__project_positions(braun_data *d, braun_real *y, int *moved, braun_real *r_start, int judge)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections & BRAUN_CORRECT_POSITION;
    braun_real r = 0;
    *moved = 0;
    *r_start = 0;
    if (!corr || pv->m == 0) return BRAUN_OK;
    const int st = project_at_rest(d, y, corr, 0, 8 * BRAUN_EPS, moved, r_start, &r);
    if (!st && judge && *moved && pv->e0_pending == 1 && *r_start > braun_sqrt(BRAUN_EPS))
        judge_start(d, *r_start);
    return st;
}

/* The adaptive driver's start off its constraints (docs/method.md, "Where
 * the corrections are evaluated"): projected onto them before the first
 * step — the position and velocity corrections at h = 0 (Δ_q = Φ_q, a
 * Gauss–Newton step in the mass metric; Δ_v = [Φ̇_q; Φ_v] measured again
 * where q went), repeated while the residuals of the rows they remove,
 * relative to the guard's scales, exceed √ε and still halve (at most 8
 * times) — and E0 re-taken there, E0 = E − ∫Ė. Corrected at the end of its
 * first step instead, the start was integrated uncorrected over the first
 * trial step (1e-3 of the span): a pendulum started with 2 m/s along its
 * rod ended 0.085 m off at rtol 1e-6 and 0.019 m at 1e-12, status OK, its
 * error set by that step and not by the tolerance; E0 depended on t_end.
 * y = [q; v; ∫Ė], changed in place; *moved: a correction was applied. */
int braun__project_start(braun_data *d, braun_real *y, int *moved)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const int n = BRAUN_N(pv->n);
    *moved = 0;
    if (!(corr & (BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY)) || pv->rows == 0) return BRAUN_OK;
    const braun_real tol = braun_sqrt(BRAUN_EPS);
    braun_real r = 0, r0 = 0;
    int moved_both = 0;
    /* The positions first (braun__project_positions), then both. */
    int st = braun__project_positions(d, y, moved, &r0, 0);
    if (!st) st = project_at_rest(d, y, corr, 1, tol, &moved_both, &r0, &r);
    if (st) return st;
    if (moved_both) *moved = 1;
    /* The rows' consistency is judged at the start too: one on its
     * constraints (or projected onto them, the velocity correction having
     * judged it) has rows that agree. Left to the first step's end, the
     * step's own error near a singular start was taken for dependent rows
     * that disagree: the four-bar started flat and exact stopped with
     * BRAUN_ERR_INCONSISTENT at t = 0.001 ("disagree by 2.8e-6"), where
     * RK4 judges at t = 0 and runs (found by an outside client). */
    if ((corr & BRAUN_CORRECT_VELOCITY) && !(r > tol)) pv->vel_judged = 1;
    /* A start on its constraints is judged so here: its first step is
     * corrected at its end, as every later one (braun_adaptive.c). */
    if (!*moved) {
        if (pv->e0_pending == 1) judge_start(d, r);
        return BRAUN_OK;
    }
    /* The energy the start's error held goes with it (as the fixed steps'
     * re-take does), once the state is on its constraints; a projection
     * that did not get there leaves the start judged off them, E0 re-taken
     * where the steps' corrections bring it (energy_deferred). */
    if (!(r > BRAUN_R(1e-3)) && d->model->sys.energy && d->has_E0) {
        braun_real E = 0;
        st = braun__energy(d, d->t, y, y + n, &E);
        if (st) return st;
        d->E0 = E - y[2 * n];
        pv->e0_pending = 0;
    } else {
        judge_start(d, r);
    }
    return BRAUN_OK;
}

/* The accuracy guard alone, at the start of a step whose corrections come
 * at its end (BRAUN__CORR_AT_END): the state the last step left, after the
 * forward pass with residuals there. The energy residual is checked once
 * the first correction has measured what an inconsistent start may change
 * (guard_first): one call of the energy law, no gradient. */
int braun__guard_start(braun_data *d, const braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const braun_system *s = &d->model->sys;
    if (d->model->opt.guard < 0) return BRAUN_OK;
    int st = braun__need(d, BRAUN_DONE_IDEAL | BRAUN_DONE_RESIDUALS,
                         "accuracy guard before a forward pass with residuals at the point");
    if (st) return st;
    /* (Measuring the scales sets guard_first.) */
    st = guard_start_rows(d, vdot, corr);
    if (st || pv->guard_first || !energy_judged(d)) return st;
    const braun_real t = pv->at.t;
    braun_real E = 0;
    st = BRAUN__CALL(d, s->energy, "energy", t, t, pv->at.q, pv->at.v, &E, NULL, NULL, NULL, s->user);
    if (!st) st = braun__check_finite(d, 1, &E, "energy E", 0, t);
    if (st) return st;
    return guard_energy(d, E - d->E0 - pv->at.W, 1);
}

/* Next to a singular configuration: the step's start's corrections, as
 * fixed steps compute them (braun__rk_attempt, BRAUN__CORR_AT_START) — the
 * start's forward pass again, at the rank its first stage found (the same
 * factorization), the energy force sized at the ideal end y1. One more
 * right-hand side, in these steps only. */
static int corrections_from_start(braun_data *d, braun_real *y1, braun_real h)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    const braun_real *y0 = pv->y0;
    for (int slot = 0; slot < 2; slot++) pv->rule_keep[slot] = pv->rule_cap[slot] = pv->step_rank[slot];
    pv->rule_stage = 0;
    braun__at(pv, d->t, y0, y0 + n, y0[2 * n], h);
    pv->stage = 0;
    braun_real *vdot = pv->k[0] + n; /* the first stage's, recomputed */
    int st = braun__forward(d, BRAUN_WITH_RESIDUALS | BRAUN_WITH_POWER, vdot);
    braun__rank_rule_plain(pv);
    if (st) return st;
    pv->energy_end = 1;
    pv->de_ok = 0;
    st = braun__corrections(d, vdot, 1);
    if (!st) st = braun__energy_at_end(d, d->t + h, y1);
    pv->energy_end = 0;
    return st;
}

/* The corrections of an accepted adaptive step of size h
 * (BRAUN__CORR_AT_END, docs/method.md "Where the corrections are
 * evaluated"), after the forward pass with residuals at its end y1 (DOPRI5's
 * last stage): y1 += [dq; dv].
 *
 * Where y1's factorization has no soft direction they are computed at y1
 * and applied there, so they remove the residuals themselves: Δ_q = Φ_q(y1)
 * (h = 0 in Eq. 16: no prediction over a step), Δ_v = [Φ̇_q; Φ_v]
 * re-measured where the position correction put q, and the energy force
 * sized with both (braun__energy_at_end at the same point). Next to a
 * singular configuration (a soft direction at y1, σ < BRAUN_SOFT_TOL·‖C‖)
 * a minimum-norm correction of even a round-off residual is a kick e/σ
 * along the weak direction: there the start's correction is used, as
 * before. vdot: the ideal acceleration at y1. */
int braun__corrections_at_end(braun_data *d, const braun_real *vdot, braun_real *y1, braun_real h)
{
    braun_priv *pv = braun__priv(d);
    const unsigned corr = d->model->opt.corrections;
    const int n = BRAUN_N(pv->n);
    if (!corr) return BRAUN_OK;
    const int energy = energy_corrected(d);
    const int guard = d->model->opt.guard >= 0;
    int st = braun__need(d, BRAUN_DONE_IDEAL | BRAUN_DONE_RESIDUALS |
                                (energy ? BRAUN_DONE_POWER : 0u),
                         "corrections before a forward pass with residuals at the point");
    if (st) return st;
    /* (The driver corrects at the end only with a backend that has soft
     * directions; without, nothing can be tested here.) */
    if (pv->rows > 0 && braun__has_soft(pv) &&
        BRAUN_LS_CALL(pv, soft_find, pv->ls_state, 0, BRAUN_SOFT_TOL) > 0) {
        st = corrections_from_start(d, y1, h);
    } else {
        pv->at.h = 0;
        /* The first correction of a run measures what an inconsistent start
         * may change in energy (stage_energy); no residual is checked here. */
        pv->guard_on = guard && pv->guard_first;
        st = position_velocity(d, corr, 1);
        if (!st && energy) {
            pv->energy_end = 1;
            pv->de_ok = 0;
            st = stage_energy(d, vdot);
            if (!st) st = braun__energy_at_end(d, pv->at.t, y1);
            pv->energy_end = 0;
        }
        if (!st && guard) pv->guard_first = 0;
    }
    /* A NaN/Inf of a callback at the integrated end: the step diverged. */
    if (st == BRAUN_ERR_NONFINITE) d->error.status = st = BRAUN_ERR_DIVERGED;
    if (st) return st;
    for (int i = 0; i < n; i++) {
        y1[i] += pv->dq[i];
        y1[n + i] += pv->dv[i];
    }
    return BRAUN_OK;
}
