/* Private state of libbraun: the data block's scratch and the stages of the
 * corrected equation of motion (docs/architecture.md).
 *
 * An evaluation at one point (t, q, v, ∫Ė; h for the 1/h terms) runs named
 * stages in order, MuJoCo-style. The point is stored once, in pv->at; every
 * stage reads it and what the stages before it left under the names below,
 * writes its own outputs, and marks itself done in pv->done. A stage whose
 * inputs are not done at this point fails (BRAUN_ERR_ARGUMENT "stage
 * order"): no stage can use what an evaluation at another point left.
 *
 *   stage         equation                         reads            writes
 *   mass          M = RᵀR (Eq. 1, Sec. 2.3)        t, q             R (linear solver)
 *   forces        a = M⁻¹Q kept as ã = R⁻ᵀQ        t, q, v, R       Q, atil
 *   constraints   Φ, A, b, b_v (Sec. 2.2, Eqs.4-5) t, q, v          phi, A, b, bv, ev
 *   factor        C = A R⁻¹, rank-revealing;       A, R, atil, bv   C_v (slot 0), C_q
 *                 r_v = b_v − C_v ã (Eq. 10)                        (slot 1), rank, rv
 *   ideal         Udwadia–Kalaba (Eq. 13, Δ = 0,   atil, rv, C_v    u, z, vdot
 *                 Q0 = 0): v' = R⁻¹(ã + C_v⁺ r_v)
 *   power         Ė = power() + Q_c·v              t, q, v, u, R    Edot
 *   position      Eq. 16 × h: dq = R⁻¹C_q⁺         phi, ev, C_q     dq
 *                 (h b_q − h A_q v − Φ_q)
 *   velocity      Δ_v of Eq. 17 × h:               ev, C_v          dv
 *                 dv = −R⁻¹C_v⁺[Φ̇_q; Φ_v]
 *   energy        Eq. 20 × h with its guard        t, q, v, W, vdot, dv += ...
 *                                                  Edot, C_v, dv
 *
 * Compositions (braun_forward.c): braun__forward = mass → forces →
 * constraints → factor → ideal; braun__corrections = position → velocity →
 * energy. The Runge–Kutta stepper, the drivers, braun_eval and
 * braun_residuals are short compositions of stages.
 */
#ifndef BRAUN_INTERNAL_H
#define BRAUN_INTERNAL_H

#include <limits.h>
#include <math.h> /* ceil: braun__fixed_step_count */
#include "braun.h"
#include "braun_dense.h"
#include "braun_linalg.h"
#include "braun_linsolver.h"

/* One more in a braun_stats counter, stopping at LONG_MAX (a long is 32
 * bits on a Cortex-M: a controller calling braun_step for days reaches it;
 * signed overflow would be undefined). */
#define BRAUN__COUNT(c) ((void)((c) += (c) < LONG_MAX))

/* Firmware builds with compile-time sizes run the built-in kernels only:
 * no backend dispatch, not even an indirect call. */
#if defined(BRAUN_FIXED_N) && !defined(BRAUN_NO_LINSOLVER)
#define BRAUN_NO_LINSOLVER
#endif

#define BRAUN_MAX_STAGES 7

/* Within a step a rank rises only from a pivot of this fraction of the
 * largest (docs/method.md, "Rank decisions near singular configurations"):
 * the later stages are off the manifold by the method's own error, where
 * rows exactly dependent on it are not quite (measured: the redundant
 * parallelogram's dependent pivot reaches 3.4e-5 at the stages of an RK4 step
 * of 1e-2), while a direction a mechanism gains on leaving a singular
 * configuration is clear at once (the four-bar started flat: ~1e-2 at the
 * first step's last stage). */
#define BRAUN_RANK_TOL_STAGE BRAUN_R(1e-3)

/* The default of options.soft_tol (docs/method.md). */
#define BRAUN_SOFT_TOL BRAUN_R(1e-4)

/* The evaluation point every stage reads (set by braun__at). */
typedef struct braun_point {
    braun_real t;
    const braun_real *q, *v; /* n each */
    braun_real W;            /* ∫_0^t Ė dτ at the point (Eq. 18) */
    braun_real h;            /* step the 1/h terms meet (corrections) */
} braun_point;

/* Stages done at the current point (pv->done). */
enum braun_stage_bits {
    BRAUN_DONE_MASS = 1u << 0,
    BRAUN_DONE_FORCES = 1u << 1,
    BRAUN_DONE_CONSTRAINTS = 1u << 2, /* A, b_v */
    BRAUN_DONE_RESIDUALS = 1u << 3,   /* Φ, b_q, [Φ̇_q; Φ_v]: asked for by the corrections */
    BRAUN_DONE_FACTOR = 1u << 4,      /* C_v (and C_q when the residuals are wanted) */
    BRAUN_DONE_IDEAL = 1u << 5,
    BRAUN_DONE_POWER = 1u << 6
};

typedef struct braun_priv {
    int n, m, p, rows;
    int need_fq;          /* separate C_q factorization (p > 0 and m > 0) */
    int work_rows;        /* rows whose work rate stage power adds (not scleronomic, a law or input) */
    int R_is_constant;    /* R computed once in braun_data_init */
    int state_integrated; /* the state came from a step, not braun_set_state */
    int vel_judged;       /* the first velocity correction since braun_set_state ran (rows' consistency) */
    int start_retry;      /* a new run's first step may project its start and start again (start_rank_check) */
    int e0_pending;       /* 1: the start not yet judged on or off the constraints; 2: off, E0
                           * re-taken once the corrections have brought the state onto them
                           * (stage_energy) */
    braun_real e0_last;   /* the relative residual where that was last judged */
    braun_real e0_t;      /* the time of that point (a rejected attempt's start is judged once) */
    braun_real guard_prev[6]; /* d->guard at the kept state (braun__commit), for a rollback */
    int mass_check_in;    /* steps to the next check of BRAUN_MASS_CONSTANT (braun__mass_claim_due) */
    int mass_claim_false; /* a check found M(t, q) != M(0, 0): every later call is refused */
    double mass_claim_diff; /* the relative difference it found */
    braun_real *q_home, *v_home; /* where braun_data_init put d->q and d->v */
    const braun_data *owner;    /* the braun_data braun_data_init made (a struct copy is not it) */
    int state_set;        /* braun_set_state was called */
    unsigned flags;       /* sys.flags at braun_data_init (braun__check_system) */
    /* A driver runs on this data (1: braun_step, braun_integrate or
     * braun_integrate_adaptive, its output callback included), or a step's
     * stages call the system's callbacks (2). Calls that would change the
     * state or the scratch under it are refused (braun__check_usable). */
    int busy;
    /* Where the stages are. */
    braun_point at;
    unsigned done;        /* braun_stage_bits at `at` */
    /* Linear algebra: a backend's table and state (braun_linsolver.h). The
     * built-in dense kernels are a backend too (braun_dense.c), whose state
     * lives in this buffer. */
    const braun_linsolver *ls;
    void *ls_state;
    int ls_owned;         /* ls_state was created (allocated) by ls->create */
    /* Sparse system (sys.sparsity): the callbacks write compressed values
     * into Avals and Mvals; dense solvers get them scattered into A / M. */
    const braun_sparsity *sp;
    braun_real *Avals;    /* nnz = sp->row_ptr[rows] */
    braun_real *Mcheck;   /* BRAUN_MASS_CONSTANT: M(t, q) of the claim's check */
    braun_real *Mvals;    /* mass callback output when the solver does not
                             take it in place: mass_count values */
    size_t mass_count;    /* n*n dense, sum of block^2 sparse */
    braun_real *Mdense;   /* n*n: M of a sparse system for a dense solver (else NULL) */
    int dense_A;          /* A holds the dense rows x n Jacobian */
    int rank[2];          /* numerical rank of C_v (slot 0) and C_q (slot 1) */
    /* The rank rule of the next factorizations (braun_linsolver.h,
     * rank_rule): a run keeps the rank of a step's first stage over its
     * other stages (cap) and raises it from one step to the next only past
     * tol_new (keep = the last step's first-stage rank). Outside a step both
     * are the row counts: the plain tolerance. */
    int rule_keep[2], rule_cap[2];
    int rule_stage;       /* a step's later stages: a rank rises only past BRAUN_RANK_TOL_STAGE */
    int step_rank[2];     /* the last step's first-stage rank (the rows: none yet) */
    /* The soft-direction filter (braun_forward.c, soft_filter): on for the
     * stages of a fixed step (stage: the one being evaluated, its v' at
     * k[stage] + n); the reference is the v' of the last stage that had no
     * soft direction, stage ref_slot of step ref_step (have_ref: one). */
    int soft_on, have_ref, stage, ref_slot;
    long ref_step;
    /* Stage outputs, one meaning each (see the table above). */
    braun_real *Q;        /* n: forces */
    braun_real *atil;     /* n: ã = R⁻ᵀQ, the weighted unconstrained acceleration */
    braun_real *A;        /* rows*n: [A_q; A_vv] from the callbacks (dense) */
    braun_real *phi;      /* rows: [Φ_q; Φ_v] */
    braun_real *b;        /* m: b_q */
    braun_real *bv;       /* rows: [b_qv; b_vv] */
    braun_real *ev;       /* rows: velocity-level error [Φ̇_q; Φ_v] */
    braun_real *rv;       /* rows: r_v = b_v − C_v ã */
    braun_real *u;        /* n: C_v⁺ r_v, the weighted ideal constraint force */
    braun_real *z;        /* n: R q'' = ã + u (weighted ideal acceleration) */
    braun_real Edot;      /* energy input rate at the point */
    braun_real *ep;       /* m: −(Φ_q + h Φ̇_q), the position target of Eq. 16 */
    braun_real *dEdq, *dEdv, *ce, *tmp; /* n each: energy stage scratch */
    braun_real *dq, *dv;  /* n each: h × the correction terms (Eqs. 16, 17, 20) */
    braun_real *de;       /* n: the energy force's direction R⁻¹N_vC_eᵀ of the step (end mode) */
    int energy_end;       /* the energy force is sized at the ideal end of the step */
    int de_ok;            /* de holds a direction for this step */
    braun_real sigma0;    /* the force's size predicted at the start (used near rest) */
    int sat0;             /* sigma0 was saturated at energy_max_rel */
    braun_real *phi0, *ev0; /* rows each: Φ and [Φ̇_q; Φ_v] at the step's start (adaptive) */
    /* The last state before the current one ([q; v; ∫Ė] and t), for the
     * accuracy guard: a run it stops goes back to the last state that passed. */
    braun_real *yprev;
    braun_real tprev, tprev_lo;
    int has_prev;
    /* The clock is compensated (Kahan): d->t + t_lo is the sum of the steps
     * to about eps^2, so a fixed step h integrates exactly h and d->t stays
     * within half an ulp of t0 + i h, also in float. */
    braun_real t_lo;
    int guard_pending;    /* the guard's scales are still to be measured */
    int guard_first;      /* this step measured them (its own residuals pass) */
    /* A start off its position constraints (d->guard.pos0 above sqrt(ε) of
     * its scale): the velocity residual its first position correction
     * created, twice (the ceiling of the velocity allowance later
     * corrections may add; 0: none), and its largest position row
     * (d->error.index2 of a refusal its allowance was in use for; -1:
     * none). braun_corrections.c, allow_induced_velocity. */
    braun_real vel_induced0;
    int start_row;
    int start_off;        /* such a start, pos0 maybe still in force (cleared once it ends) */
    int guard_on;         /* the corrections being computed belong to a run */
    braun_real *enorm;    /* rows: the normal error of an adaptive step */
    /* Integrator scratch: states of length N = 2n + 1 ([q; v; ∫Ė]). */
    braun_real *y0, *ys, *y1, *yerr;
    /* The state's compensation (Kahan): the part of [q; v; ∫Ė] that the
     * last step's sum y0 + Σ b h k lost to rounding, added to the next
     * step's sum. Zero after braun_set_state and a guard rollback. ylo1:
     * the step being taken's, kept by braun__commit. */
    braun_real *ylo, *ylo1;
    braun_real *k[BRAUN_MAX_STAGES];
} braun_priv;

static inline braun_priv *braun__priv(const braun_data *d)
{
    return (braun_priv *)d->priv;
}

/* ------------------------------------------------------------ errors */
/* Record an error in d->error and return status (braun_error.c). */
int braun__fail(braun_data *d, int status, const char *where, int index,
                int index2, double value, double t);
/* Map a callback's return code: 0 ok, > 0 recoverable, < 0 fatal. */
int braun__callback_failed(braun_data *d, int rc, const char *where, braun_real t);
static inline int braun__callback(braun_data *d, int rc, const char *where, braun_real t)
{
    return rc == 0 ? BRAUN_OK : braun__callback_failed(d, rc, where, t);
}
/* A system callback made NULL while a step ran (a callback that changed
 * the model): refused with BRAUN_ERR_MISSING_CALLBACK, never called (a
 * crash before). The model is checked whole at every driver call and
 * output callback (braun__check_system); this is the call itself. */
int braun__callback_missing(braun_data *d, const char *where, braun_real t);
#define BRAUN__CALL(d, fn, where, t, ...)                                               \
    ((fn) ? braun__callback((d), (fn)(__VA_ARGS__), (where), (t))                      \
          : braun__callback_missing((d), (where), (t)))
/* Check n outputs of a callback for NaN/Inf. */
int braun__check_finite(braun_data *d, int n, const braun_real *x,
                        const char *where, int cols, braun_real t);
/* A step from t to t_new was asked as h: refuse one that does not advance
 * time, or advances it by more than 10 % off h (the precision cannot
 * resolve t + h: the float horizon, docs/robustness.md). `last`: the final
 * step of a driver, which may be shorter. */
static inline int braun__time_step_ok(braun_data *d, braun_real t, braun_real t_new, braun_real h,
                                      int last)
{
    const braun_real adv = t_new - t;
    if (adv > 0 && (last ? adv <= h + h / 10 : (adv - h <= h / 10 && h - adv <= h / 10)))
        return BRAUN_OK;
    return braun__fail(d, BRAUN_ERR_TIME_RESOLUTION, "time (t + h)", -1, -1, (double)h, (double)t);
}

/* The options of d's model are valid (braun_options.c). */
int braun__check_options(braun_data *d);
/* The data block is usable: initialised, not busy beyond busy_allowed
 * (braun_priv.busy: 0 for the drivers and braun_set_state, 1 for calls
 * allowed in an output callback) and made for model->sys as it is
 * (braun__check_system). BRAUN_OK or an error recorded in d->error. */
int braun__check_usable(braun_data *d, int busy_allowed);
/* ... and a driver may run: a state is set, the options are valid. */
int braun__check_ready(braun_data *d);
/* A driver's output callback at d's state (busy 1): BRAUN_STOPPED when it
 * asks to stop; then d is checked again as every call checks it, since
 * the callback is the program's code running between two steps — d still
 * initialised and not re-initialised, the system as braun_data_init saw
 * it, the options valid. */
int braun__output(braun_data *d, braun_output_fn out, void *user);
/* After the program's code ran inside a driver or a step (busy 1 or 2): d
 * still holds pv and pv is still that busy — braun_data_init there resets
 * it. Out of line: the callbacks can change what the caller set. */
int braun__data_intact(const braun_data *d, const braun_priv *pv, int busy);
/* E(t, q, v) from the energy callback (0 without one), checked finite; no
 * argument checks (braun_energy's are the caller's). */
int braun__energy(braun_data *d, braun_real t, const braun_real *q, const braun_real *v, braun_real *E);

/* Steps of braun_integrate for a span of `ratio` steps of h: a span that
 * is a whole number of steps up to round-off takes exactly that many (the
 * last one h plus that leftover, up to 1e-9 of the span in double),
 * otherwise one more, the last shortened to land on t_end. The round-off
 * allowed is relative (h carries the working precision's rounding: a
 * float h makes the ratio off by ~1e-7 relative) but never a whole step:
 * at 1e12 steps a relative 1e-9 would make the last step 1000 h long. */
static inline long braun__fixed_step_count(double ratio)
{
    const double slack = 8.0 * (double)BRAUN_EPS > 1e-9 ? 8.0 * (double)BRAUN_EPS : 1e-9;
    double allowance = slack * ratio;
    if (allowance > 0.5) allowance = 0.5;
    const long steps = (long)ceil(ratio - allowance);
    return steps < 1 ? 1 : steps;
}
/* The system the data was made for is still model->sys: sizes, flags,
 * sparsity and the callbacks they require (a few compares per call). */
int braun__check_system(braun_data *d);
/* braun__check_system and braun__check_options after a driver's step (braun_step.c). */
int braun__check_unchanged(braun_data *d);

/* ------------------------------------------------------------ stages */
/* Store the evaluation point; no stage is done there yet. */
static inline void braun__at(braun_priv *pv, braun_real t, const braun_real *q,
                             const braun_real *v, braun_real W, braun_real h)
{
    pv->at.t = t;
    pv->at.q = q;
    pv->at.v = v;
    pv->at.W = W;
    pv->at.h = h;
    pv->done = pv->R_is_constant ? BRAUN_DONE_MASS : 0u;
}

/* The stages are static functions of two files — braun_forward.c (mass,
 * forces, constraints, factor, ideal, power) and braun_corrections.c
 * (position, velocity, energy) — so the compiler sees each pass whole.
 * Each returns BRAUN_OK or an error recorded in d->error. */

/* The accuracy guard's scales from a forward pass with residuals at the
 * state braun_set_state gave (the first step's start); vdot its output. */
void braun__guard_scales(braun_data *d, const braun_real *vdot);
/* A driver's step failed with BRAUN_ERR_ACCURACY: back to the last state
 * that passed (one step back), statistics with it. */
void braun__guard_rollback(braun_data *d);
/* The guard on a driver's last state (one residual evaluation). */
int braun__guard_final(braun_data *d);

/* Stage mass alone (braun_data_init factors a constant M with it). */
int braun__stage_mass(braun_data *d);
/* BRAUN_MASS_CONSTANT checked at a state: M(t, q) must be the M factored
 * at braun_data_init (braun_set_state, braun__mass_claim_due, a driver's
 * last state). */
int braun__check_mass_claim(braun_data *d, braun_real t, const braun_real *q);
/* A driver's last state: the mass claim, then the guard. */
int braun__final_checks(braun_data *d);

/* Steps (or braun_eval calls) between two checks of BRAUN_MASS_CONSTANT
 * within a run. A mass matrix that varies but equals M(0, 0) where the
 * run starts (relative coordinates at zero angles) passes braun_set_state;
 * a braun_step loop never reaches a driver's last state, and braun_eval
 * in the caller's own integrator no last state at all. One check costs a
 * mass callback and n² products (~720 instructions on the Cortex-M4F for
 * the slider-crank; with the countdown, +21 per step in the 100 s mean),
 * and a false claim stops the run within 64 steps of the first one that
 * saw it. The step that checks is the dearest of a real-time budget: a
 * firmware build whose M is known constant may define it 0 (no check
 * within a run; braun_set_state and the drivers' last state still check). */
#ifndef BRAUN_MASS_CHECK_EVERY
#define BRAUN_MASS_CHECK_EVERY 64
#endif

/* The mass claim at a step's start (d->t, d->q) or at a braun_eval's
 * point, every BRAUN_MASS_CHECK_EVERY steps or evaluations since
 * braun_set_state; a countdown otherwise. The countdown restarts only after
 * a check that passed: once refused, every later call is refused too.
 * Where it runs the scratch it uses (pv->ce, pv->tmp) is free. */
static inline int braun__mass_claim_due(braun_data *d, braun_real t, const braun_real *q)
{
    braun_priv *pv = (braun_priv *)d->priv;
    if (BRAUN_MASS_CHECK_EVERY <= 0 || !pv->R_is_constant || --pv->mass_check_in > 0) return 0;
    const int st = braun__check_mass_claim(d, t, q);
    /* Refused: 0, so that the next call checks again (and the count does
     * not run down however many refusals follow). */
    pv->mass_check_in = st ? 0 : BRAUN_MASS_CHECK_EVERY;
    return st;
}
/* Stage constraints alone at pv->at: A, b_v and, with residuals, Φ, b_q
 * and [Φ̇_q; Φ_v] (the corrections at a step's end re-measure the
 * velocity-level residual at the corrected position). */
int braun__stage_constraints(braun_data *d, int with_residuals);

/* What braun__forward computes besides the ideal acceleration. */
enum {
    BRAUN_WITH_RESIDUALS = 1u << 0, /* Φ, b_q, [Φ̇_q; Φ_v]: the corrections need them */
    BRAUN_WITH_POWER = 1u << 1      /* Ė (pv->Edot) */
};
/* The forward pass at pv->at: mass → forces → constraints → factor →
 * ideal (→ power); the ideal acceleration into vdot (may be NULL). */
int braun__forward(braun_data *d, unsigned with, braun_real *vdot);
/* h × the correction terms at pv->at into pv->dq, pv->dv (zero for the
 * corrections that are off): position → velocity → energy. After
 * braun__forward(d, BRAUN_WITH_RESIDUALS | BRAUN_WITH_POWER, vdot). */
int braun__corrections(braun_data *d, const braun_real *vdot, int guard);
int braun__energy_at_end(braun_data *d, braun_real t1, const braun_real *y1);
/* The accuracy guard alone at a step's start whose corrections come at
 * its end, and the corrections of an accepted adaptive step of size h,
 * applied to its end y1: both after braun__forward with residuals at the
 * point (src/core/braun_corrections.c). */
int braun__guard_start(braun_data *d, const braun_real *vdot);
int braun__corrections_at_end(braun_data *d, const braun_real *vdot, braun_real *y1, braun_real h);
/* The adaptive driver's start off its constraints, projected onto them
 * (braun_corrections.c); y = [q; v; ∫Ė] in place. */
/* Internal: a new run's first step found its start's rank ambiguous
 * (braun_corrections.c, start_rank_check); rk_stages projects it and
 * starts the step again. Never returned to a caller. */
#define BRAUN__START_AMBIGUOUS 0x4000
int braun__project_start(braun_data *d, braun_real *y, int *moved);
int braun__project_positions(braun_data *d, braun_real *y, int *moved, braun_real *r_start, int judge);

/* The state's carried rounding (ylo) cleared: a new run, or a state the
 * guard took back. Read only by a step's sum, after braun_set_state. */
static inline void braun__clear_compensation(braun_priv *pv)
{
    for (int i = 0; BRAUN_COMPENSATED_STATE && i < 2 * pv->n + 1; i++) pv->ylo[i] = 0;
}

/* A stage's inputs are done at this point, else BRAUN_ERR_ARGUMENT. */
static inline int braun__need(braun_data *d, unsigned bits, const char *stage)
{
    if ((braun__priv(d)->done & bits) == bits) return BRAUN_OK;
    return braun__fail(d, BRAUN_ERR_ARGUMENT, stage, -1, -1, 0, (double)braun__priv(d)->at.t);
}

/* ------------------------------------------------- linear-solver calls */
/* Through the backend table; the built-in dense kernels (braun_dense.h, the
 * default) are called directly — the same functions the table holds — and
 * a build without dispatch (firmware, compile-time sizes) knows no other. */
extern const braun_linsolver braun__dense_linsolver;
#ifdef BRAUN_NO_LINSOLVER
#define BRAUN_LS_CALL(pv, op, ...) braun__dense_##op(__VA_ARGS__)
#else
#define BRAUN_LS_CALL(pv, op, ...)                                                  \
    ((pv)->ls == &braun__dense_linsolver ? braun__dense_##op(__VA_ARGS__)           \
                                         : (pv)->ls->op(__VA_ARGS__))
#endif

/* The linear solver finds soft directions (braun_linsolver.h, soft_find). */
static inline int braun__has_soft(const braun_priv *pv)
{
#ifdef BRAUN_NO_LINSOLVER
    (void)pv;
    return 1;
#else
    return pv->ls->soft_find != NULL && pv->ls->soft_project != NULL;
#endif
}

/* x := R^-T b, x := R^-1 b (x may be b), y := R x. */
static inline void braun__solve_rt(const braun_priv *pv, const braun_real *b, braun_real *x)
{
    BRAUN_LS_CALL(pv, solve_rt, pv->ls_state, b, x);
}
static inline void braun__solve_r(const braun_priv *pv, const braun_real *b, braun_real *x)
{
    BRAUN_LS_CALL(pv, solve_r, pv->ls_state, b, x);
}
static inline void braun__mul_r(const braun_priv *pv, const braun_real *x, braun_real *y)
{
    BRAUN_LS_CALL(pv, mul_r, pv->ls_state, x, y);
}
/* slot 0: C_v, slot 1: C_q. */
static inline void braun__pinv(const braun_priv *pv, int slot, const braun_real *r,
                               braun_real *x)
{
    BRAUN_LS_CALL(pv, pinv, pv->ls_state, slot, r, x);
}
/* Two right-hand sides: the dense kernels walk the factor once; another
 * backend is called twice (the table has no such entry). */
static inline void braun__pinv2(const braun_priv *pv, int slot, const braun_real *r1,
                                const braun_real *r2, braun_real *x1, braun_real *x2)
{
#ifdef BRAUN_NO_LINSOLVER
    braun__dense_pinv2(pv->ls_state, slot, r1, r2, x1, x2);
#else
    if (pv->ls == &braun__dense_linsolver) {
        braun__dense_pinv2(pv->ls_state, slot, r1, r2, x1, x2);
    } else {
        pv->ls->pinv(pv->ls_state, slot, r1, x1);
        pv->ls->pinv(pv->ls_state, slot, r2, x2);
    }
#endif
}
static inline void braun__lsq(const braun_priv *pv, int slot, const braun_real *r,
                              braun_real *x, braun_real *resid)
{
    BRAUN_LS_CALL(pv, lsq, pv->ls_state, slot, r, x, resid);
}
static inline void braun__null_project(const braun_priv *pv, int slot, braun_real *z)
{
    BRAUN_LS_CALL(pv, null_project, pv->ls_state, slot, z);
}

/* Row i of the constraint Jacobian times x (compressed or dense). */
static inline braun_real braun__row_dot(const braun_priv *pv, int i, const braun_real *x)
{
    if (pv->sp) {
        braun_real s = 0;
        for (int k = pv->sp->row_ptr[i]; k < pv->sp->row_ptr[i + 1]; k++)
            s += pv->Avals[k] * x[pv->sp->col[k]];
        return s;
    }
    return braun_dot(BRAUN_N(pv->n), pv->A + (size_t)i * (size_t)BRAUN_N(pv->n), x);
}

/* Row i of the Jacobian, in absolute value, times s ≥ 0 (compressed or
 * dense): the scale of the row's round-off at that point. */
static inline braun_real braun__row_abs_dot(const braun_priv *pv, int i, const braun_real *s)
{
    braun_real sum = 0;
    if (pv->sp) {
        for (int k = pv->sp->row_ptr[i]; k < pv->sp->row_ptr[i + 1]; k++)
            sum += braun_fabs(pv->Avals[k]) * s[pv->sp->col[k]];
        return sum;
    }
    const braun_real *a = pv->A + (size_t)i * (size_t)pv->n;
    for (int j = 0; j < pv->n; j++) sum += braun_fabs(a[j]) * s[j];
    return sum;
}

/* The rank rule outside a step: both slots at their row counts (the plain
 * tolerance), no stage rule. */
static inline void braun__rank_rule_plain(braun_priv *pv)
{
    pv->rule_keep[0] = pv->rule_cap[0] = pv->rows;
    pv->rule_keep[1] = pv->rule_cap[1] = pv->m;
    pv->rule_stage = 0;
}

/* Where the constraint callbacks write A: row `row`'s first value. */
static inline braun_real *braun__A_out(const braun_priv *pv, int row)
{
    if (pv->sp) return pv->Avals + pv->sp->row_ptr[row];
    return pv->A + (size_t)row * (size_t)pv->n;
}

/* Relative rank tolerance of a factorization of `rows` rows. */
static inline braun_real braun__rank_tol(const braun_data *d, int rows)
{
    const braun_real t = d->model->opt.rank_tol;
    return t > 0 ? t : braun_default_rank_tol(rows, d->model->sys.n);
}

/* ------------------------------------------------------------ layout */
/* Bytes of the data block (base == NULL), or carve it (braun_layout.c). */
size_t braun__layout(const braun_model *model, unsigned char *base, braun_priv *pv,
                     braun_real **q, braun_real **v);
/* The model's linear solver: the built-in kernels unless a backend is set. */
const braun_linsolver *braun__model_linsolver(const braun_model *model);

#endif
