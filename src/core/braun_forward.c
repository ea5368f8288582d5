/* The forward pass: the ideal (Udwadia–Kalaba) acceleration of the
 * corrected equation of motion as named stages, in the order they run —
 * mass → forces → constraints → factor → ideal — and the energy input rate
 * (power), with the compositions braun__forward, braun_eval and
 * braun_residuals. The corrections (Eqs. 16, 17, 20) are braun_corrections.c.
 * Each stage reads the evaluation point pv->at and what the stages before it
 * left, under the names of braun_internal.h. One file, so the compiler sees
 * the whole pass (the stages are called once per evaluation). */
#include <stdint.h>

#include "braun_internal.h"

/* ================================================================ */
/* Stage mass: M = RᵀR (Eq. 1; the Cholesky factor of Sec. 2.3). */

/* A sparse system's blocks into the dense n x n matrix M. */
static void scatter_mass_blocks(const braun_sparsity *sp, int n, const braun_real *blocks,
                                braun_real *M)
{
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++) M[i] = 0;
    int off = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        const int b = sp->block[k];
        for (int i = 0; i < b; i++)
            for (int j = 0; j < b; j++)
                M[(size_t)(off + i) * (size_t)n + (size_t)(off + j)] = *blocks++;
        off += b;
    }
}

/* Stage mass (Eq. 1, Sec. 2.3): evaluate M at the point and factor
 * M = RᵀR. Skipped when M is constant (factored once, in braun_data_init). */
static int stage_mass(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    if (pv->done & BRAUN_DONE_MASS) return BRAUN_OK;
    const braun_system *s = &d->model->sys;
    const int n = pv->n;
    const braun_real t = pv->at.t;
    braun_real tol = d->model->opt.symmetry_tol > 0 ? d->model->opt.symmetry_tol
                                                   : (braun_real)1e3 * BRAUN_EPS;
    int bi = -1, bj = -1, st;
    braun_real bad = 0;
    /* The callback's output: in the solver's own buffer when it factors in
     * place (the built-in Cholesky), else Mvals. */
    braun_real *out = pv->Mvals ? pv->Mvals : BRAUN_LS_CALL(pv, mass_buffer, pv->ls_state);
    st = BRAUN__CALL(d, s->mass, "mass", t, t, pv->at.q, out, s->user);
    if (st) return st;
    st = braun__check_finite(d, (int)pv->mass_count, out, "mass", pv->sp ? 0 : n, t);
    if (st) return st;
    const braun_real *M = out;
    if (pv->sp && pv->dense_A) {
        /* Dense solver, sparse system: scatter the blocks. */
        braun_real *dst = pv->Mdense ? pv->Mdense : BRAUN_LS_CALL(pv, mass_buffer, pv->ls_state);
        scatter_mass_blocks(pv->sp, n, out, dst);
        M = dst;
    }
    st = BRAUN_LS_CALL(pv, factor_mass, pv->ls_state, M, tol, &bi, &bj, &bad);
    BRAUN__COUNT(d->stats.mass_factorizations);
    if (st) return braun__fail(d, st, "mass", bi, bj, (double)bad, (double)t);
    pv->done |= BRAUN_DONE_MASS;
    return BRAUN_OK;
}

/* BRAUN_MASS_CONSTANT is a claim: M was evaluated and factored once, at
 * t = 0, q = 0 (braun_data_init). A mass matrix that does vary (relative
 * coordinates, a body's inertia in world axes) would be taken as M(0, 0)
 * everywhere, a wrong motion with no other sign. Checked at braun_set_state,
 * at the start of every BRAUN_MASS_CHECK_EVERY-th step or braun_eval
 * (braun__mass_claim_due) and at a driver's last state — a mass callback
 * and n² (block) products, never within a step's stages: the quadratic
 * forms xᵀM(t, q)x and ‖R x‖² of a
 * fixed probe x must agree within sqrt(ε) of Σ|x_i M_ij x_j| (round-off
 * of the factor is about n²ε of it). */
#define CLAIM_FALSE "system declared BRAUN_MASS_CONSTANT but M(t, q) differs from M(0, 0)"

int braun__check_mass_claim(braun_data *d, braun_real t, const braun_real *q)
{
    braun_priv *pv = braun__priv(d);
    if (!pv->R_is_constant || !pv->Mcheck) return BRAUN_OK;
    /* The claim is the model's: found false once, it stays false (another
     * point where M happens to agree does not make it true). */
    if (pv->mass_claim_false)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           CLAIM_FALSE " (found at an earlier call; braun_data_init again with a "
                           "true claim)",
                           -1, -1, pv->mass_claim_diff, (double)t);
    const braun_system *s = &d->model->sys;
    const int n = pv->n;
    const int st = BRAUN__CALL(d, s->mass, "mass", t, t, q, pv->Mcheck, s->user);
    if (st) return st;
    braun_real *x = pv->ce, *rx = pv->tmp;
    for (int i = 0; i < n; i++) x[i] = 1 + (braun_real)((i * 7) % 11) / 16; /* no symmetry of a model */
    braun_real form = 0, scale = 0;
    const braun_real *M = pv->Mcheck;
    /* Diagonal blocks, each row-major (a dense M: one block of n). */
    const int nblocks = pv->sp ? pv->sp->nblocks : 1;
    for (int k = 0, off = 0; k < nblocks; k++) {
        const int b = pv->sp ? pv->sp->block[k] : n;
        for (int i = 0; i < b; i++)
            for (int j = 0; j < b; j++) {
                const braun_real e = x[off + i] * *M++ * x[off + j];
                form += e;
                scale += braun_fabs(e);
            }
        off += b;
    }
    braun__mul_r(pv, x, rx);
    const braun_real diff = braun_fabs(form - braun_dot(n, rx, rx));
    if (diff <= braun_sqrt(BRAUN_EPS) * scale) return BRAUN_OK; /* (not for a NaN) */
    /* Only now is M scanned: a NaN or Inf is named as such (it checks
     * every 64th step: the worst step of a firmware budget pays for it). */
    const int bad = braun__check_finite(d, (int)pv->mass_count, pv->Mcheck, "mass", pv->sp ? 0 : n, t);
    if (bad) return bad;
    pv->mass_claim_false = 1;
    pv->mass_claim_diff = scale > 0 ? (double)(diff / scale) : (double)diff;
    return braun__fail(d, BRAUN_ERR_ARGUMENT, CLAIM_FALSE, -1, -1, pv->mass_claim_diff, (double)t);
}

/* ================================================================ */
/* Stage forces: the applied and inertial forces Q(t, q, v) of Eq. 1 and the
 * unconstrained acceleration a = M⁻¹Q (Eq. 9), kept in weighted form
 * ã = R⁻ᵀQ (a = R⁻¹ã): every later stage works with C = A R⁻¹. */

static int stage_forces(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    int st = BRAUN__CALL(d, s->forces, "forces", pv->at.t, pv->at.t, pv->at.q, pv->at.v, pv->Q, s->user);
    if (st) return st;
    braun__solve_rt(pv, pv->Q, pv->atil);
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage constraints (Sec. 2.2): the callbacks' Jacobians A = [A_q; A_vv]
 * and right-hand sides b_v = [b_qv; b_vv] of the acceleration-level rows
 * (Eq. 5) and, when the corrections need them, the residuals Φ = [Φ_q; Φ_v],
 * b_q (Eq. 4) and the velocity-level error [Φ̇_q; Φ_v] = [A_q v − b_q; Φ_v]. */

static int stage_constraints(braun_data *d, int with_residuals)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int m = pv->m, p = pv->p, rows = pv->rows;
    const braun_real t = pv->at.t, *q = pv->at.q, *v = pv->at.v;
    int st;
    if (m > 0) {
        st = BRAUN__CALL(d, s->holonomic, "holonomic", t, t, q, v, with_residuals ? pv->phi : NULL,
                         braun__A_out(pv, 0), with_residuals ? pv->b : NULL, pv->bv, s->user);
        if (st) return st;
    }
    if (p > 0) {
        st = BRAUN__CALL(d, s->nonholonomic, "nonholonomic", t, t, q, v,
                         with_residuals ? pv->phi + m : NULL, braun__A_out(pv, m), pv->bv + m, s->user);
        if (st) return st;
    }
    if (with_residuals) {
        for (int i = 0; i < m; i++) pv->ev[i] = braun__row_dot(pv, i, v) - pv->b[i];
        for (int i = m; i < rows; i++) pv->ev[i] = pv->phi[i];
        /* A system declared scleronomic has b_q = -∂Φ_q/∂t = 0: checked
         * here, where b_q is computed anyway (the power stage relies on it). */
        if (s->flags & BRAUN_SCLERONOMIC) {
            for (int i = 0; i < m; i++)
                if (pv->b[i] != 0)
                    return braun__fail(d, BRAUN_ERR_ARGUMENT,
                                       "system declared scleronomic (BRAUN_SCLERONOMIC) but b_q != 0",
                                       i, -1, (double)pv->b[i], (double)t);
            /* Its velocity-level rows must be homogeneous in v, Φ_v = A_vv v:
             * a term c(q, t) does work through the row's ideal force,
             * −λᵀc, which the flag skips (a ball rolling on a turntable
             * declared so ran 1 m off, status OK). Equal to the rounding
             * of the row's products. */
            for (int i = m; i < rows; i++) {
                const braun_real w = braun__row_dot(pv, i, v) - pv->phi[i];
                braun_real scale = 0;
                if (pv->sp) {
                    for (int k = pv->sp->row_ptr[i]; k < pv->sp->row_ptr[i + 1]; k++)
                        scale += braun_fabs(pv->Avals[k] * v[pv->sp->col[k]]);
                } else {
                    const braun_real *a = pv->A + (size_t)i * (size_t)pv->n;
                    for (int j = 0; j < pv->n; j++) scale += braun_fabs(a[j] * v[j]);
                }
                if (!(braun_fabs(w) <= 64 * BRAUN_EPS * scale))
                    return braun__fail(d, BRAUN_ERR_ARGUMENT,
                                       "system declared scleronomic (BRAUN_SCLERONOMIC) but a velocity-level "
                                       "row is not A_vv v (Phi_v - A_vv v != 0: it does work)",
                                       i, -1, (double)(-w), (double)t);
            }
        }
    }
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage factor (Sec. 2.3): the weighted constraint matrices C = A R⁻¹ and
 * their rank-revealing factorizations, through the linear solver — C_v of
 * all rows (slot 0) for Eqs. 17 and 20, and C_q of the holonomic rows
 * (slot 1) for Eq. 16 when the system has both kinds of rows and the
 * corrections need it (otherwise C_q = C_v) — and, in the same pass, the
 * residual of Eq. 10 without corrections, r_v = b_v − C_v ã. */

/* A factorization of `rows` rows found this rank: kept for the
 * corrections, counted in the statistics. */
static void record_rank(braun_data *d, int slot, int rank, int rows)
{
    braun__priv(d)->rank[slot] = rank;
    BRAUN__COUNT(d->stats.constraint_factorizations);
    if (rank < rows) BRAUN__COUNT(d->stats.rank_deficient);
}

/* The dense A of a sparse system (entries off the pattern stay zero). */
static void scatter_A(braun_priv *pv)
{
    const braun_sparsity *sp = pv->sp;
    const size_t n = (size_t)pv->n;
    for (int i = 0; i < pv->rows; i++)
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++)
            pv->A[(size_t)i * n + (size_t)sp->col[k]] = pv->Avals[k];
}

static int stage_factor(braun_data *d, int with_residuals)
{
    braun_priv *pv = braun__priv(d);
    const int m = pv->m, rows = BRAUN_ROWS(pv->rows);
    if (pv->sp && pv->dense_A) scatter_A(pv);
    const braun_real *A = pv->dense_A ? pv->A : pv->Avals;
    /* A rank rises only on clear evidence: from one step to the next past
     * sqrt(ε) of the largest pivot (the float default tolerance is above
     * that already), within a step past BRAUN_RANK_TOL_STAGE. */
#ifdef BRAUN_NO_LINSOLVER
    const int has_rule = 1;
#else
    const int has_rule = pv->ls->rank_rule != NULL;
#endif
    if (has_rule) {
        const braun_real tol_new = pv->rule_stage ? BRAUN_RANK_TOL_STAGE : braun_sqrt(BRAUN_EPS);
        BRAUN_LS_CALL(pv, rank_rule, pv->ls_state, 0, pv->rule_keep[0], pv->rule_cap[0], tol_new);
        if (pv->need_fq)
            BRAUN_LS_CALL(pv, rank_rule, pv->ls_state, 1, pv->rule_keep[1], pv->rule_cap[1], tol_new);
    }
    /* A step's later stages keep the first stage's column order and rows
     * set aside (braun_linsolver.h, stage_order; the built-in kernels':
     * braun_dense.h). */
#ifdef BRAUN_NO_LINSOLVER
    braun__dense_stage_order(pv->ls_state, pv->rule_stage);
#else
    if (pv->ls->stage_order) BRAUN_LS_CALL(pv, stage_order, pv->ls_state, pv->rule_stage);
#endif
    if (pv->need_fq && with_residuals) {
        const int rq = BRAUN_LS_CALL(pv, factor_c, pv->ls_state, 1, m, A, braun__rank_tol(d, m), NULL,
                                              NULL);
        if (rq < 0) return braun__fail(d, rq, "linear solver (C_q)", -1, -1, 0, (double)pv->at.t);
        record_rank(d, 1, rq, m);
    }
    for (int i = 0; i < rows; i++) pv->rv[i] = pv->bv[i];
    const int rank = BRAUN_LS_CALL(pv, factor_c, pv->ls_state, 0, rows, A, braun__rank_tol(d, rows),
                                            pv->atil, pv->rv);
    if (rank < 0) return braun__fail(d, rank, "linear solver (C_v)", -1, -1, 0, (double)pv->at.t);
    record_rank(d, 0, rank, rows);
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage ideal: the Udwadia–Kalaba acceleration, Eq. 13 without the
 * corrections (Δ_v = 0, Q0 = 0; footnote 2):
 *   v' = a + R⁻¹C_v⁺(b_v − A_v a) = R⁻¹(ã + u),  u = C_v⁺ r_v,
 * u the weighted ideal constraint force (Eq. 11: Q_c⊥ = Rᵀu). */

/* The constraint callbacks' outputs at pv->at, in evaluation order: A,
 * b_v and, with residuals, Φ and b_q; the first NaN/Inf is recorded and
 * its status returned, else BRAUN_OK. */
static int constraint_culprit(braun_data *d, int with_residuals)
{
    braun_priv *pv = braun__priv(d);
    const int n = pv->n, m = pv->m, rows = pv->rows;
    const braun_real t = pv->at.t;
    if (rows == 0) return BRAUN_OK;
    int st = pv->sp ? braun__check_finite(d, pv->sp->row_ptr[rows], pv->Avals,
                                          "constraint Jacobian (compressed)", 0, t)
                    : braun__check_finite(d, rows * n, pv->A, "constraint Jacobian", n, t);
    if (!st) st = braun__check_finite(d, rows, pv->bv, "constraint b_v", 0, t);
    if (!st && with_residuals) {
        st = braun__check_finite(d, rows, pv->phi, "constraint Φ", 0, t);
        if (!st && m > 0) st = braun__check_finite(d, m, pv->b, "constraint b_q", 0, t);
    }
    return st;
}

/* A result was NaN/Inf: find the callback output that made it (in
 * evaluation order), or blame the arithmetic (overflow). */
static int nonfinite_culprit(braun_data *d, int with_residuals)
{
    braun_priv *pv = braun__priv(d);
    const braun_real t = pv->at.t;
    int st = braun__check_finite(d, pv->n, pv->Q, "forces", 0, t);
    if (!st) st = constraint_culprit(d, with_residuals);
    if (!st) st = braun__fail(d, BRAUN_ERR_NONFINITE, "acceleration (overflow)", -1, -1, 0, (double)t);
    return st;
}

/* The soft-direction filter (options.soft_tol; docs/method.md, "Redundant
 * rows through a singular configuration"). Near a singular configuration
 * C keeps a direction s whose singular value σ is tiny (with redundant
 * rows, one they block at second order). The index-1 flow conserves the velocity-level residual,
 * so a residual e of round-off or of a stage's own error is a velocity
 * e_s/σ along s and an acceleration ≈ σ'·e_s/σ² along it: a rate σ'/σ no
 * explicit stage can follow when it lands within h·σ' of the singular
 * point (the exact flow merely removes that velocity; one RK4 step turned
 * 1e-6 into 1e-2 and stopped the run). The true acceleration along s is
 * smooth through the crossing, so a stage with such a direction takes
 * that component with weight 1 − w, w = λ⁴/(σ⁴ + λ⁴), λ = soft_tol·‖C‖,
 * from its own evaluation and w from the last stage that had none (this
 * step's or the last one's: a crossing lasts far less than a step; with
 * no such stage the stage keeps its own). Without redundant rows the
 * window is 100 times narrower: at a bifurcation the direction is another
 * branch's tangent, and the velocity a replaced component leaves at the
 * next stage costs more than the kick it removes unless σ is far below
 * the stage's residual level (measured on the slider-crank and the
 * four-bar, docs/method.md). Returns 1 when the stage had a soft
 * direction (it is then no reference), else 0. */
static int soft_filter(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n);
    braun_real rel = d->model->opt.soft_tol > 0 ? d->model->opt.soft_tol : BRAUN_SOFT_TOL;
    /* Without redundant rows (a bifurcation) only where the stage's own
     * evaluation is surely worse: a window 100 times narrower. */
    if (pv->rank[0] >= pv->rows) rel *= BRAUN_R(1e-2);
    if (BRAUN_LS_CALL(pv, soft_find, pv->ls_state, 0, rel) <= 0) return 0;
    /* The reference: stage ref_slot's v' (k[ref_slot] + n) of this step
     * (a slot before this stage) or of the last one (a slot from this
     * stage on, not yet overwritten). */
    if (!pv->have_ref || pv->ref_step < d->stats.steps - 1 ||
        (pv->ref_step < d->stats.steps && pv->ref_slot < pv->stage))
        return 1;
    const braun_real *aref = pv->k[pv->ref_slot] + n;
    /* The rate σ' ≈ ‖b_v‖/‖R v‖ (b_qv is −Ȧ_q v): a direction the step can
     * follow (h·σ'/σ small, as in an adaptive step that has shrunk) keeps
     * its own evaluation. */
    braun__mul_r(pv, pv->at.v, pv->tmp);
    const braun_real rv = braun_nrm2(n, pv->tmp);
    const braun_real rate = rv > 0 ? pv->at.h * braun_nrm2(pv->rows, pv->bv) / rv : 0;
    /* u += Σ w s sᵀ(g − u), g = R v'_ref − ã the reference's constraint force. */
    braun__mul_r(pv, aref, pv->tmp);
    for (int i = 0; i < n; i++) pv->tmp[i] -= pv->atil[i] + pv->u[i];
    BRAUN_LS_CALL(pv, soft_project, pv->ls_state, 0, pv->tmp, pv->ce, rate);
    for (int i = 0; i < n; i++) pv->u[i] += pv->ce[i];
    BRAUN__COUNT(d->stats.soft_filtered);
    return 1;
}

static int stage_ideal(braun_data *d, int with_residuals, braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const int n = BRAUN_N(pv->n), m = pv->m, rows = BRAUN_ROWS(pv->rows);
    const int with_rows = rows > 0;
    int soft = 0;
    braun_real z0 = 0; /* Σ z·0, braun_all_finite in the pass that forms z */
    if (with_rows) {
        braun__pinv(pv, 0, pv->rv, pv->u);
        if (pv->soft_on) soft = soft_filter(d);
        for (int i = 0; i < n; i++) {
            pv->z[i] = pv->atil[i] + pv->u[i];
            z0 += pv->z[i] * 0;
        }
    } else {
        for (int i = 0; i < n; i++) {
            pv->z[i] = pv->atil[i];
            z0 += pv->z[i] * 0;
        }
    }
    /* NaN and Inf propagate through every operation above, so one check of
     * the results covers all callback outputs; only on failure are they
     * scanned, to name the culprit. r_v carries the Jacobian: an infinite
     * entry of A makes every QR pivot "small" (rank 0, u = 0, z finite) but
     * not this residual. */
    if (!(z0 == 0) || (with_rows && !braun_all_finite(rows, pv->rv)) ||
        (with_residuals && with_rows &&
         (!braun_all_finite(rows, pv->ev) || !braun_all_finite(m, pv->phi))))
        return nonfinite_culprit(d, with_residuals);
    if (vdot) braun__solve_r(pv, pv->z, vdot);
    if (pv->soft_on && !soft) {
        pv->ref_slot = pv->stage;
        pv->ref_step = d->stats.steps;
        pv->have_ref = 1;
    }
    return BRAUN_OK;
}

/* ================================================================ */
/* Stage power: the energy input rate Ė of Eq. 18 at the point — the
 * system's power() (dampers, motors, applied forces; BRAUN_ENERGY_INPUT)
 * plus the work rate of the moving constraints, unless the system is
 * declared scleronomic (its constraints then do no work). Moving
 * (rheonomic) constraints are accounted for without any flag:
 * docs/method.md, "Work of moving constraints".
 *
 * That rate is λᵀb_q (λ the multipliers, Q_c⊥ = Aᵀλ = Rᵀu): on the
 * velocity manifold it equals Q_c·v = u·(R v), but a stage state is off
 * the manifold by its velocity error e = [A_q v − b_q; Φ_v], and u·(R v)
 * = λᵀ(b_q + e) would count λᵀe as work done — a drift of ∫Ė (and, through
 * the energy force, of E) on a system that does no work at all (a
 * pendulum written without the flag: 3e-6 J over 100 s of RK4 at
 * h = 1e-2). So the velocity is taken on the manifold first: with
 * λ = C⁺ᵀu, λᵀe = u·(C⁺e) and the rate is u·(R v − C⁺e) = λᵀ(A v − e):
 * λᵀb_q for the holonomic rows, λᵀ(A_vv v − Φ_v) for the nonholonomic
 * ones (−λᵀc for Φ_v = A_vv v + c). */

/* u·(R v − C⁺e) (above). Out of line: only systems not declared
 * scleronomic run it. */
static BRAUN_NOINLINE braun_real constraint_work_rate(braun_priv *pv)
{
    const int n = BRAUN_N(pv->n);
    braun__mul_r(pv, pv->at.v, pv->tmp);
    braun__pinv(pv, 0, pv->ev, pv->ce);
    for (int i = 0; i < n; i++) pv->tmp[i] -= pv->ce[i];
    return braun_dot(n, pv->u, pv->tmp);
}

static int stage_power(braun_data *d)
{
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const braun_real t = pv->at.t;
    braun_real Edot = 0;
    if (s->flags & BRAUN_ENERGY_INPUT) {
        int st = BRAUN__CALL(d, s->power, "power", t, t, pv->at.q, pv->at.v, &Edot, s->user);
        if (!st) st = braun__check_finite(d, 1, &Edot, "power", 0, t);
        if (st) return st;
    }
    if (pv->work_rows) {
        Edot += constraint_work_rate(pv);
        /* The residuals' callback outputs enter only here: a NaN among
         * them is named, not integrated. */
        if (!braun_is_finite(Edot)) return nonfinite_culprit(d, 1);
    }
    pv->Edot = Edot;
    return BRAUN_OK;
}

/* ================================================================ */
/* Compositions. */
int braun__stage_mass(braun_data *d) { return stage_mass(d); }
int braun__stage_constraints(braun_data *d, int with_residuals) { return stage_constraints(d, with_residuals); }

int braun__forward(braun_data *d, unsigned with, braun_real *vdot)
{
    braun_priv *pv = braun__priv(d);
    const int res = (with & BRAUN_WITH_RESIDUALS) != 0;
    BRAUN__COUNT(d->stats.rhs_evals);
    /* The work rate of moving constraints needs the velocity error at the
     * point (stage power): the residuals, without C_q's factorization. */
    const int res_rows = res | (pv->work_rows & ((with & BRAUN_WITH_POWER) != 0));
    /* A constant M was factored once (stage mass is then done). */
    int st = pv->done & BRAUN_DONE_MASS ? BRAUN_OK : stage_mass(d);
    if (!st) st = stage_forces(d);
    if (!st && pv->rows > 0) st = stage_constraints(d, res_rows);
    if (!st && pv->rows > 0) st = stage_factor(d, res);
    if (!st) st = stage_ideal(d, res, vdot);
    /* Without energy input and constraint work Ė is 0: no stage to run. */
    if (!st && (with & BRAUN_WITH_POWER)) {
        const braun_system *s = &d->model->sys;
        if ((s->flags & BRAUN_ENERGY_INPUT) || (s->energy && !(s->flags & BRAUN_SCLERONOMIC)))
            st = stage_power(d);
        else
            pv->Edot = 0;
    }
    if (st) return st;
    /* What the corrections may now use at this point. */
    pv->done |= BRAUN_DONE_FORCES | BRAUN_DONE_CONSTRAINTS | BRAUN_DONE_FACTOR | BRAUN_DONE_IDEAL |
                (res ? BRAUN_DONE_RESIDUALS : 0u) |
                (with & BRAUN_WITH_POWER ? BRAUN_DONE_POWER : 0u);
    return BRAUN_OK;
}

static int check_state(braun_data *d, braun_real t, const braun_real *q,
                       const braun_real *v)
{
    const int n = d->model->sys.n;
    if (!braun_is_finite(t))
        return braun__fail(d, BRAUN_ERR_NONFINITE, "state t", -1, -1, (double)t, (double)t);
    int st = braun__check_finite(d, n, q, "state q", 0, t);
    if (!st) st = braun__check_finite(d, n, v, "state v", 0, t);
    return st;
}

/* The arguments of braun_eval, braun_residuals, braun_energy. busy_allowed
 * (braun__check_usable): 1 for the last two, allowed in an output callback,
 * between steps (docs/api.md); none from a system callback while a step's
 * stages run: the call would overwrite the scratch the step is using. */
static int check_call(braun_data *d, const braun_real *q, const braun_real *v, int busy_allowed)
{
    const int st = braun__check_usable(d, busy_allowed);
    if (st) return st;
    if (!q || !v)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, !q ? "state q (NULL)" : "state v (NULL)", -1, -1, 0,
                           (double)d->t);
    return BRAUN_OK;
}

/* The checks and set-up of an evaluation on its own at (t, q, v) — the
 * options, the state, h where a correction needs it (named by what), the
 * mass claim every BRAUN_MASS_CHECK_EVERY evaluations as the drivers'
 * steps — and the point: the plain rank tolerance, the plain
 * Udwadia–Kalaba acceleration (no soft filter), the literal Eq. 20 sized
 * at the point. braun_eval and braun_energy_rate. */
static int point_begin(braun_data *d, braun_real t, const braun_real *q, const braun_real *v,
                       int needs_h, braun_real h, const char *what)
{
    int st = braun__check_options(d);
    if (!st) st = check_state(d, t, q, v);
    if (st) return st;
    if (needs_h && !(h > 0 && braun_is_finite(h)))
        return braun__fail(d, BRAUN_ERR_STEP, what, -1, -1, (double)h, (double)t);
    st = braun__mass_claim_due(d, t, q);
    if (st) return st;
    braun_priv *pv = braun__priv(d);
    braun__at(pv, t, q, v, d->work_in, h);
    braun__rank_rule_plain(pv);
    pv->soft_on = 0;
    pv->energy_end = 0;
    return BRAUN_OK;
}

int braun_eval(braun_data *d, braun_real t, const braun_real *q,
               const braun_real *v, braun_real h, braun_real *qdot,
               braun_real *vdot)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    /* Not from a driver's output callback: the forward pass would replace
     * the factorization, rank and residuals the driver's next step starts
     * from (a run with it differed at round-off); a second braun_data of
     * the same model evaluates anywhere. */
    int st = check_call(d, q, v, 0);
    if (st) return st;
    if (!qdot || !vdot) return braun__fail(d, BRAUN_ERR_ARGUMENT, "braun_eval (NULL output)", -1, -1, 0, (double)t);
    /* The stages read q and v to the end while they write vdot, and qdot is
     * written last from v: outputs that share memory with the inputs (or
     * each other) are refused rather than computed wrong. */
    {
        const uintptr_t bytes = (uintptr_t)d->model->sys.n * sizeof(braun_real);
        const uintptr_t in[2] = {(uintptr_t)q, (uintptr_t)v};
        const uintptr_t out[2] = {(uintptr_t)qdot, (uintptr_t)vdot};
        int overlap = out[0] < out[1] + bytes && out[1] < out[0] + bytes;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) overlap |= out[i] < in[j] + bytes && in[j] < out[i] + bytes;
        if (overlap)
            return braun__fail(d, BRAUN_ERR_ARGUMENT, "braun_eval (outputs overlap the inputs)", -1,
                               -1, 0, (double)t);
    }
    const unsigned corr = d->model->opt.corrections;
    const int n = d->model->sys.n;
    /* The energy force needs E0: before braun_set_state it was left out,
     * the result status OK (vdot up to 1.0 off a pendulum's). */
    if ((corr & BRAUN_CORRECT_ENERGY) && d->model->sys.energy && !d->has_E0)
        return braun__fail(d, BRAUN_ERR_ARGUMENT,
                           "braun_eval with the energy correction before braun_set_state (no E0)", -1,
                           -1, 0, (double)t);
    st = point_begin(d, t, q, v, corr != 0, h, "braun_eval h");
    if (st) return st;
    braun_priv *pv = braun__priv(d);
    st = braun__forward(d, (corr ? BRAUN_WITH_RESIDUALS : 0u) |
                               (corr & BRAUN_CORRECT_ENERGY ? BRAUN_WITH_POWER : 0u),
                        vdot);
    if (st) return st;
    for (int i = 0; i < n; i++) qdot[i] = v[i];
    if (!corr) return BRAUN_OK;
    st = braun__corrections(d, vdot, 0);
    if (st) return st;
    /* Continuous form: the increments are h times the correction terms
     * (with a tiny h they can overflow: say so rather than return Inf). */
    for (int i = 0; i < n; i++) {
        qdot[i] += pv->dq[i] / h;
        vdot[i] += pv->dv[i] / h;
    }
    st = braun__check_finite(d, n, qdot, "braun_eval qdot (the correction over h)", 0, t);
    if (!st) st = braun__check_finite(d, n, vdot, "braun_eval vdot (the correction over h)", 0, t);
    return st;
}

int braun_energy_rate(braun_data *d, braun_real t, const braun_real *q, const braun_real *v,
                      braun_real *Edot)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    /* A forward pass, as braun_eval's (not from a driver's callbacks). */
    int st = check_call(d, q, v, 0);
    if (st) return st;
    if (!Edot)
        return braun__fail(d, BRAUN_ERR_ARGUMENT, "braun_energy_rate (NULL output)", -1, -1, 0, (double)t);
    st = point_begin(d, t, q, v, 0, 0, NULL);
    if (!st) st = braun__forward(d, BRAUN_WITH_POWER, NULL);
    *Edot = st ? (braun_real)NAN : braun__priv(d)->Edot;
    return st;
}

int braun_energy(braun_data *d, braun_real t, const braun_real *q,
                 const braun_real *v, braun_real *E)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = check_call(d, q, v, 1);
    if (st) return st;
    if (!E) return braun__fail(d, BRAUN_ERR_ARGUMENT, "braun_energy (NULL output)", -1, -1, 0, (double)t);
    /* The state as braun_eval and braun_residuals check it: a NaN the
     * energy does not depend on (a coordinate absent from E) is still a
     * state that is no state. */
    st = check_state(d, t, q, v);
    if (st) return st;
    /* Computed, then written: E may share memory with q or v. */
    braun_real e = 0;
    st = braun__energy(d, t, q, v, &e);
    *E = e;
    return st;
}

int braun__energy(braun_data *d, braun_real t, const braun_real *q, const braun_real *v, braun_real *E)
{
    const braun_system *s = &d->model->sys;
    *E = 0;
    if (!s->energy) return BRAUN_OK;
    int st = BRAUN__CALL(d, s->energy, "energy", t, t, q, v, E, NULL, NULL, NULL, s->user);
    if (!st) st = braun__check_finite(d, 1, E, "energy E", 0, t);
    return st;
}

/* A residual norm is NaN or Inf: name the callback output that made it,
 * as a stage does (constraint_culprit), or blame the norm (overflow). */
static BRAUN_NOINLINE int residual_culprit(braun_data *d, braun_real *norm, const char *what)
{
    const int st = constraint_culprit(d, 1);
    return st ? st : braun__check_finite(d, 1, norm, what, 0, braun__priv(d)->at.t);
}

int braun_residuals(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v, braun_real *pos, braun_real *vel,
                    braun_real *energy)
{
    if (!d) return BRAUN_ERR_ARGUMENT;
    int st = check_call(d, q, v, 1);
    if (st) return st;
    braun_priv *pv = braun__priv(d);
    const braun_system *s = &d->model->sys;
    const int m = pv->m, rows = pv->rows;
    st = check_state(d, t, q, v);
    if (st) return st;
    braun__at(pv, t, q, v, d->work_in, 0);
    if (rows > 0) {
        st = stage_constraints(d, 1);
        if (st) return st;
    }
    pv->done |= BRAUN_DONE_CONSTRAINTS | BRAUN_DONE_RESIDUALS;
    /* All computed before any is written: an output may share memory with
     * q or v (the energy residual read a q the position norm overwrote). */
    braun_real rp = 0, rv = 0, re = 0;
    /* Finite rows can still have a norm beyond the largest number. */
    if (pos) {
        rp = m > 0 ? braun_nrm2(m, pv->phi) : 0;
        if (!braun_is_finite(rp)) return residual_culprit(d, &rp, "position residual norm");
    }
    if (vel) {
        rv = rows > 0 ? braun_nrm2(rows, pv->ev) : 0;
        if (!braun_is_finite(rv)) return residual_culprit(d, &rv, "velocity residual norm");
    }
    if (energy && s->energy && d->has_E0) {
        braun_real E = 0;
        st = braun__energy(d, t, q, v, &E);
        if (st) return st;
        re = braun_fabs(E - d->E0 - d->work_in);
        st = braun__check_finite(d, 1, &re, "energy residual", 0, t);
        if (st) return st;
    }
    if (pos) *pos = rp;
    if (vel) *vel = rv;
    if (energy) *energy = re;
    return BRAUN_OK;
}
