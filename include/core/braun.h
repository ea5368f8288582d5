/*
 * libbraun — constrained mechanical systems with explicit ODE solvers.
 *
 * Implements the corrected equation of motion of Braun & Goldfarb,
 * "Simulation of Constrained Mechanical Systems — Part I" (J. Appl. Mech. 2012):
 *   Eq. 16  q' = v + R^-1 C_q^+ (b_q - A_q v - Δ_q)                 (position impulse)
 *   Eq. 17  v' = a + R^-1 C_v^+ (b_v - A_v a - Δ_v) + R^-1 N_v R^-T Q0 (velocity force)
 *   Eq. 20  Q0 = R^T [C_e N_v]^+ (b_ev - A_ev a - Δ_ev)               (energy force)
 * with M = R^T R (Cholesky), C_* = A_* R^-1, N_v = I - C_v^+ C_v.
 *
 * Layers (GSL-like): braun_eval (corrected right-hand side, no time advance)
 *   -> braun_step (one explicit step) -> braun_integrate (driver to t_end).
 * An evaluation is a list of named stages (MuJoCo-like; docs/architecture.md):
 * mass -> forces -> constraints -> factor -> ideal (Udwadia–Kalaba) ->
 * position (Eq. 16) -> velocity (Eq. 17) -> energy (Eq. 20).
 *
 * Memory (CMSIS-like): a braun_model (sizes, callbacks, options) is immutable
 * while simulating; a braun_data holds state, statistics and all scratch,
 * carved out of one caller-provided buffer of braun_data_size() bytes.
 * Nothing is allocated inside a step.
 *
 * Status convention: 0 is success, > 0 informational, < 0 an error. Every
 * call that fails on a braun_data records what failed, where and when in
 * d->error (braun_error_format() in braun_host.h makes it a sentence) —
 * argument and buffer checks included; only a NULL d itself cannot be.
 * Callbacks follow SUNDIALS: return 0 on success, > 0 for a recoverable
 * failure (the adaptive driver retries with a smaller step), < 0 fatal.
 */
#ifndef BRAUN_H
#define BRAUN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* Scalar type: double, or float with -DBRAUN_SINGLE.                  */
/* ------------------------------------------------------------------ */
#ifdef BRAUN_SINGLE
typedef float braun_real;
#else
typedef double braun_real;
#endif
/* A literal (or any constant) as a braun_real, a constant expression.
 * A cast, not x##f: that failed in float on an integer (BRAUN_R(1)) or a
 * macro's name, and left BRAUN_R(1) an int in double (BRAUN_R(1) /
 * BRAUN_R(3) was 0). In float a decimal goes to double, then to float,
 * which is what gen-c's R() and the float scene reader do (every literal
 * of the library comes out as with the f suffix). */
#define BRAUN_R(x) ((braun_real)(x))

/* The one place the version is written: the Makefile derives the .pc
 * files' and CMake package's versions, the sonames (libbraun.so.MAJOR.MINOR)
 * and the symbol version node (BRAUN_MAJOR.MINOR) from it; braun_version()
 * and braun --version print it (tests/cli/install.sh checks they agree,
 * tests/abi/check.sh that the ABI is this minor version's record). */
#define BRAUN_VERSION "0.2.0"

/* Link names. A program compiled for one precision and linked with a
 * library built for the other would hand every struct and array over at
 * the wrong size (a crash, or worse, a plausible status). So in a float
 * build every public function and object of every public header carries
 * the precision in its link name (this header's here, each other's at its
 * top): whichever call a program makes, a mismatch fails to link,
 * "undefined reference to braun_step_float" (a float program, a double
 * library) or "to braun_step" (the reverse). Only braun_model_init,
 * braun_data_size and braun_data_init did once, and a double program whose
 * one call was braun_check_callbacks linked with the float library and
 * passed a Jacobian 50 % wrong. A float installation's pkg-config and
 * CMake files define BRAUN_SINGLE. */
#ifdef BRAUN_SINGLE
#define braun_data_init braun_data_init_float
#define braun_data_release braun_data_release_float
#define braun_data_size braun_data_size_float
#define braun_energy braun_energy_float
#define braun_energy_rate braun_energy_rate_float
#define braun_eval braun_eval_float
#define braun_integrate braun_integrate_float
#define braun_integrate_adaptive braun_integrate_adaptive_float
#define braun_method_from_name braun_method_from_name_float
#define braun_method_name braun_method_name_float
#define braun_model_init braun_model_init_float
#define braun_residuals braun_residuals_float
#define braun_set_state braun_set_state_float
#define braun_status_str braun_status_str_float
#define braun_step braun_step_float
#define braun_system_check braun_system_check_float
#define braun_version braun_version_float
#define braun_precision braun_precision_float
#endif

/* The library a program runs with, asked at run time (BRAUN_VERSION and
 * BRAUN_SINGLE say what it was compiled against): braun_version() is the
 * library's BRAUN_VERSION, "MAJOR.MINOR.PATCH"; braun_precision() its braun_real,
 * "double" or "float". Static strings, never NULL. Linked to a shared
 * libbraun, the version may be a later patch of the header's (the soname,
 * libbraun.so.MAJOR.MINOR, admits no other); the precision is the
 * program's own, since a program of the other precision does not link
 * (the link names above). */
const char *braun_version(void);
const char *braun_precision(void);

/* ------------------------------------------------------------------ */
/* Status codes                                                        */
/* ------------------------------------------------------------------ */
typedef enum braun_status {
    BRAUN_OK = 0,
    BRAUN_ERR_ARGUMENT = -1,      /* NULL pointer, unknown option or enum value, no state set;
                                     also a false claim: BRAUN_MASS_CONSTANT, BRAUN_SCLERONOMIC,
                                     a callback braun_check_callbacks finds wrong */
    BRAUN_ERR_SIZE = -2,          /* negative or inconsistent n, m, p */
    BRAUN_ERR_BUFFER = -3,        /* buffer smaller than braun_data_size() (any alignment
                                     is fine), or a backend could not allocate */
    BRAUN_ERR_NONFINITE = -4,     /* NaN/Inf in a state given to a call, or in a callback's
                                     output at it (at a state a step reached: DIVERGED) */
    BRAUN_ERR_MASS_NOT_SYMMETRIC = -5,
    BRAUN_ERR_MASS_NOT_SPD = -6,  /* Cholesky pivot j not above n·ε·M_jj (its own
                                     diagonal entry), at a state given to a call (at
                                     one a step reached: DIVERGED) */
    BRAUN_ERR_CALLBACK = -7,      /* a callback returned < 0 (fatal) */
    BRAUN_ERR_CALLBACK_RECOVERABLE = -8, /* callback returned > 0 and no retry possible */
    BRAUN_ERR_STEP = -9,          /* step size not finite and positive */
    BRAUN_ERR_TIME = -10,         /* t_end not after the current time */
    BRAUN_ERR_DIVERGED = -11,     /* state left the finite range during a step, or a
                                     callback's output was NaN/Inf, or M not positive
                                     definite, at a state a step reached (its stage or
                                     the next step's start): the solution left where the
                                     model is defined (the adaptive driver retries
                                     smaller); d->error names the output and entry, or
                                     the mass pivot */
    BRAUN_ERR_STEP_TOO_SMALL = -12, /* adaptive step fell below its minimum */
    BRAUN_ERR_TOO_MANY_STEPS = -13,
    BRAUN_ERR_MISSING_CALLBACK = -14, /* m > 0 without holonomic(), ... */
    BRAUN_ERR_NO_ENERGY_LAW = -15,    /* energy correction asked, system has none */
    BRAUN_ERR_INCONSISTENT = -16,     /* dependent constraint rows disagree: no solution */
    BRAUN_ERR_TIME_RESOLUTION = -17,  /* t + h is not t + h in this precision: the step
                                         cannot advance time as asked (float horizon) */
    BRAUN_ERR_ACCURACY = -18,         /* residuals beyond the accuracy guard (braun_guard);
                                         error.index: the largest row of a position or
                                         velocity residual, -1 for the energy's */
    BRAUN_STOPPED = 1             /* the output callback asked to stop */
} braun_status;

/* Name and one-line meaning of a status code (static string, never NULL). */
const char *braun_status_str(int status);

/* ------------------------------------------------------------------ */
/* The system: callbacks in the paper's notation (Sec. 2)              */
/* ------------------------------------------------------------------ */
/* All matrices are dense, row-major. Outputs passed as NULL are not wanted
 * by the library at that call and must not be written; every other output
 * must be written whole (the library does not fill it first). */

/* M(t,q), n x n symmetric positive definite (Eq. 1). */
typedef int (*braun_mass_fn)(braun_real t, const braun_real *q, braun_real *M,
                             void *user);

/* Q(t,q,v), n: Coriolis/centrifugal terms and applied forces (Eq. 1). */
typedef int (*braun_force_fn)(braun_real t, const braun_real *q,
                              const braun_real *v, braun_real *Q, void *user);

/* Holonomic constraints Φ_q(t,q) = 0, m rows (Sec. 2.2):
 *   phi[m]  = Φ_q(t,q)
 *   A[m*n]  = A_q = ∂Φ_q/∂q
 *   b[m]    = b_q = -∂Φ_q/∂t                      (0 for scleronomic)
 *   bv[m]   = b_qv = -(∂(A_q v)/∂q) v - 2 (∂A_q/∂t) v - ∂²Φ_q/∂t²
 * so that Φ̇_q = A_q v - b_q and Φ̈_q = A_q v' - b_qv. */
typedef int (*braun_holonomic_fn)(braun_real t, const braun_real *q,
                                  const braun_real *v, braun_real *phi,
                                  braun_real *A, braun_real *b, braun_real *bv,
                                  void *user);

/* Nonholonomic constraints Φ_v(t,q,v) = 0, p rows (Sec. 2.2):
 *   phi[p]  = Φ_v(t,q,v)
 *   A[p*n]  = A_vv = ∂Φ_v/∂v
 *   bv[p]   = b_vv = -(∂Φ_v/∂q) v - ∂Φ_v/∂t
 * so that Φ̇_v = A_vv v' - b_vv. */
typedef int (*braun_nonholonomic_fn)(braun_real t, const braun_real *q,
                                     const braun_real *v, braun_real *phi,
                                     braun_real *A, braun_real *bv, void *user);

/* Energy-type law (Sec. 2.5, Eq. 18): Φ_e = E(t,q,v) - E0 - ∫Ė dτ.
 *   E       = E(t,q,v)
 *   dE_dq[n], dE_dv[n] (= A_e), dE_dt = ∂E/∂t (0 unless E depends on t
 *   explicitly, e.g. a potential V(t, q))
 * The library forms b_e = -dE_dt - dE_dq·v + Ė (Eq. 19). Φ_e is 0 on the
 * exact motion only if Ė is the rate of this E (braun_power_fn). */
typedef int (*braun_energy_fn)(braun_real t, const braun_real *q,
                               const braun_real *v, braun_real *E,
                               braun_real *dE_dq, braun_real *dE_dv,
                               braun_real *dE_dt, void *user);

/* Energy input rate Ė(t,q,v): the rate at which E changes along the exact
 * motion, less the power of the ideal constraint forces (the library adds
 * that itself; see BRAUN_SCLERONOMIC). That is the power of every applied
 * force that is not in E (dampers, motors, external forces and torques:
 * Q_applied·v) plus ∂E/∂t when E depends on t explicitly: a potential
 * V(t, q) in E has its ∂V/∂t both in dE_dt and here (they cancel in b_e,
 * while ∫Ė keeps Φ_e = 0); alternatively leave it out of E, and its force
 * is an applied force whose power −(∂V/∂q)·v goes here (docs/api.md,
 * "Driven and dissipative systems"). Only called when the system sets
 * BRAUN_ENERGY_INPUT; ∫Ė dτ is part of the integrated state. Without an
 * energy law the flag is still allowed: ∫Ė is integrated into d->work_in
 * (the work the applied forces did) and used for nothing else. */
typedef int (*braun_power_fn)(braun_real t, const braun_real *q,
                              const braun_real *v, braun_real *Edot, void *user);

enum braun_system_flags {
    BRAUN_MASS_CONSTANT = 1u << 0, /* M called and factored once */
    BRAUN_ENERGY_INPUT = 1u << 1,  /* Ė not identically zero: power() used */
    /* Kept for old code: the constraint work below is always accounted for
     * now, with or without this flag (it may not be set with SCLERONOMIC). */
    BRAUN_CONSTRAINT_WORK = 1u << 2,
    /* No constraint depends on time and every velocity-level row is
     * homogeneous in v (Φ_v = A_vv v, no c(q) term): the ideal constraint
     * forces do no work.
     * Without it, a system with an energy law has the work rate of its
     * ideal constraint forces Q_c = Aᵀλ, λᵀb_q (holonomic rows) and
     * λᵀ(A_vv v − Φ_v) (nonholonomic rows), added to Ė at every stage, so a
     * driven (rheonomic) mechanism keeps its energy law without any flag or
     * power term for its drives; for a scleronomic one that rate is 0 up to
     * round-off, so the result is right either way. With it the library
     * skips that work (a solve per stage), and checks the claim: a
     * holonomic row with b_q ≠ 0 (∂Φ_q/∂t ≠ 0), or a velocity-level row
     * with Φ_v ≠ A_vv v beyond the rounding of its products (a term c(q)
     * or c(t), as a ball on a turntable's W×r, does work λᵀ(A_vv v − Φ_v)),
     * at the start of a step stops the run with BRAUN_ERR_ARGUMENT ("system
     * declared scleronomic"); braun_check_callbacks reports such a row. */
    BRAUN_SCLERONOMIC = 1u << 3
};

/* Sparse structure of a large mechanism (optional; NULL: dense callbacks).
 * With a sparsity the callbacks write compressed values instead of dense
 * matrices:
 *   holonomic/nonholonomic: A as the values of the pattern below, in order
 *     (holonomic writes row_ptr[m] values, nonholonomic row_ptr[m+p] -
 *     row_ptr[m], starting at its own first row);
 *   mass: the diagonal blocks, one after another, each row-major
 *     (sum of block[k]^2 values).
 * Every linear solver accepts it: libbraun's dense kernels scatter the
 * values, the SuiteSparse backend (braun_linsolver.h) works on them
 * directly. The arrays must outlive the model. */
typedef struct braun_sparsity {
    const int *row_ptr; /* m + p + 1 entries, row_ptr[0] = 0, nondecreasing */
    const int *col;     /* row_ptr[m + p] column indices, increasing within a row */
    int nblocks;        /* block-diagonal M: nblocks blocks ... */
    const int *block;   /* ... of these sizes (sum = n) */
} braun_sparsity;

typedef struct braun_system {
    int n;                /* coordinates */
    int m;                /* holonomic constraint rows (may be redundant) */
    int p;                /* nonholonomic constraint rows */
    unsigned flags;       /* braun_system_flags */
    braun_mass_fn mass;               /* required */
    braun_force_fn forces;            /* required */
    braun_holonomic_fn holonomic;     /* required iff m > 0 */
    braun_nonholonomic_fn nonholonomic; /* required iff p > 0 */
    braun_energy_fn energy;           /* optional conservation law */
    braun_power_fn power;             /* required iff BRAUN_ENERGY_INPUT */
    void *user;                       /* passed to every callback */
    const braun_sparsity *sparsity;   /* NULL: dense A and M (the default) */
    /* Optional: each coordinate's natural size (n entries, each positive
     * and finite, in the coordinate's own unit; the array must outlive the
     * model; braun_model_init refuses another with BRAUN_ERR_ARGUMENT,
     * "q_scale has an entry that is not positive and finite"): what the
     * accuracy guard measures its scales by (braun_data.guard) — a length
     * coordinate the mechanism's size, an angle or an Euler parameter 1.
     * A scene fills it (braun_scene.q_scale, braun_scene_natural_sizes).
     * NULL (the built-in models): the guard's scales from the state alone
     * (every coordinate at least max(|q_j|, ‖q‖∞), which mixes a length's
     * unit with an angle's and grows with where the mechanism is). Read
     * only where the scales are measured (the first step, a residual above
     * its bound), never in a step. */
    const braun_real *q_scale;
} braun_system;

/* ------------------------------------------------------------------ */
/* Options                                                             */
/* ------------------------------------------------------------------ */
enum braun_corrections {
    BRAUN_CORRECT_NONE = 0,
    BRAUN_CORRECT_POSITION = 1u << 0, /* ideal impulse, Eq. 16 */
    BRAUN_CORRECT_VELOCITY = 1u << 1, /* Δ_v term of Eq. 17 */
    BRAUN_CORRECT_ENERGY = 1u << 2,   /* nonideal force, Eq. 20 */
    BRAUN_CORRECT_ALL = 7u
};

/* How the 1/h correction terms meet a multi-stage integrator
 * (docs/method.md, "Discretisation"). */
typedef enum braun_discretization {
    /* Default. The ideal (Udwadia–Kalaba) flow is advanced by the integrator;
     * the correction terms are evaluated once, at the step's start, and
     * added with weight h, so h·Φ/h cancels exactly. Keeps RK order. */
    BRAUN_PER_STEP = 0,
    /* Eqs. 16, 17, 20 evaluated at every stage with Δ = Φ/h: the literal
     * right-hand side. Identical to PER_STEP for Euler; for RK4 the 1/h
     * terms act as a stiff term and cost the method its order: measured
     * order 2 with the position correction (with or without the velocity
     * one), 3 with the velocity correction alone, 1 once the energy
     * correction is on (tests/test_api_docs.c). Fixed steps only. */
    BRAUN_PER_STAGE = 1
} braun_discretization;

/* A linear-algebra backend (braun_linsolver.h). */
typedef struct braun_linsolver braun_linsolver;

/* Options: braun_model_init sets the defaults; change them before
 * braun_data_init or between calls. They are checked where they are used:
 * braun_data_init refuses invalid values before it creates anything, and
 * braun_eval, braun_step, braun_integrate and braun_integrate_adaptive
 * check them again at every call (a few compares), so a change after
 * braun_data_init is honoured, or refused with BRAUN_ERR_ARGUMENT naming
 * the option: unknown correction bits or discretization, a NaN or infinite
 * tolerance, rank_tol >= 1, soft_tol >= 1, or another linsolver than the
 * data was made for. An output callback may change them between two steps
 * of a driver: the driver checks them after it returns, as a call would. */
typedef struct braun_options {
    unsigned corrections;   /* braun_corrections bits; default ALL (ENERGY only if a law exists) */
    braun_discretization discretization; /* default BRAUN_PER_STEP */
    /* Relative rank tolerance of the pseudoinverses: a pivot |r_kk| of the
     * column-pivoted QR of C^T counts as zero when |r_kk| <= rank_tol·|r_00|.
     * <= 0 selects the default: in double 10·max(rows, n)·ε (MATLAB's pinv
     * tolerance with a margin of 10, because pivots of exactly dependent rows
     * are a few ε·||C|| after round-off); in float 30·sqrt(ε) ≈ 1e-2, because
     * float round-off divided by a pivot below ~sqrt(ε) pushes the state onto
     * the other branch at a bifurcation. docs/method.md has the measurements. */
    braun_real rank_tol;
    /* Guard of the energy force (Eq. 20): its pseudoinverse divides by
     * ||N_v C_e^T||² ≈ 2·kinetic energy. One step's energy correction may scale
     * the velocity by at most this fraction (dimensionless); beyond it the
     * correction is saturated and the remainder is left for later steps.
     * <= 0 selects the default 0.01. */
    braun_real energy_max_rel;
    /* Mass-matrix symmetry tolerance, relative to the largest diagonal entry.
     * <= 0 selects the default 1e3·ε. */
    braun_real symmetry_tol;
    /* When the holonomic rows are dependent (rank-deficient factorization),
     * the part of the position error Φ_q + hΦ̇_q outside the range of C_q
     * cannot be removed by any motion: above this (absolute, constraint
     * units) the step fails with BRAUN_ERR_INCONSISTENT. The same bound
     * holds for the velocity-level rows [A_q; A_vv] at the first velocity
     * correction after braun_set_state: the part of [Φ̇_q; Φ_v] outside
     * the range of C_v (two drives of one joint at different rates, a
     * knife across a driven slider). <= 0: sqrt(ε) of the rows' own size
     * at the point, max_i Σ_j |A_ij|·|x_j| + |r_i| (x = q or v, r the
     * correction's target): the same answer in any unit of length. */
    braun_real inconsistency_tol;
    /* Accuracy guard (docs/robustness.md, "The accuracy guard"): a step
     * whose start finds a residual above its bound stops the run with
     * BRAUN_ERR_ACCURACY, the state back at the last step that passed and
     * d->error naming the residual, its value, the bound and the time. The
     * bounds are this relative value times the system's scales, measured at
     * the first step (braun_data.guard) and raised to the motion's at a
     * state whose residual exceeds them: ‖Φ_q‖ <= guard·S_pos,
     * ‖[Φ̇_q; Φ_v]‖ <= guard·S_vel, |Φ_e| <= guard·S_energy; a residual no
     * larger than it was at braun_set_state (an inconsistent start the
     * corrections are still removing) passes, and so does, after a start
     * off its position constraints, the velocity residual the position
     * correction creates (the start's velocity seen at the corrected
     * positions, measured while that error is removed: braun_data.guard's
     * vel0); a start the corrections cannot bring onto its constraints
     * (its position residual grows) is refused, d->error naming it. Each
     * residual is checked where the corrections compute it, at no extra
     * evaluation (but for that measurement, at a start off its positions'
     * first steps): position with the position correction on, velocity
     * with the velocity correction, energy with the energy correction.
     * The guard only judges: a run it passes is the run with it off, bit
     * for bit. 0 selects the default 1e-3; < 0 turns the guard off. */
    braun_real guard;
    /* The soft-direction filter (docs/method.md, "Redundant rows through a
     * singular configuration"): near a singular configuration C keeps a
     * direction whose singular value σ is tiny, and the index-1 flow turns
     * any velocity error in it into an acceleration ≈ σ'·e/σ² that no
     * explicit stage can follow. Within a step, a stage with such a
     * direction (σ below 10λ, λ = soft_tol·‖C‖) takes the component of its
     * ideal acceleration along it with weight λ⁴/(σ⁴ + λ⁴) from the last
     * stage (this step's or the last one's) that had none (less where the
     * step could follow the direction's rate). Fixed steps only: the
     * adaptive driver shrinks its step there instead. Without
     * redundant rows (a full-rank factorization: a bifurcation) λ is 100
     * times smaller. 0 selects the default 1e-4; < 0 turns it off (the
     * plain Udwadia–Kalaba acceleration at every stage, as braun_eval
     * always computes it). Counted in braun_stats.soft_filtered. Backends
     * without it (LAPACK, SuiteSparse) ignore it. */
    braun_real soft_tol;
    /* Linear algebra (braun_linsolver.h): NULL is libbraun's own dense
     * kernels (allocation-free); LAPACK and SuiteSparse come from
     * braun_backends.h. Set before braun_data_init. */
    const braun_linsolver *linsolver;
} braun_options;

typedef struct braun_model {
    braun_system sys;
    braun_options opt;
} braun_model;

/* Largest n, m, p: dense systems 4096; with a sparsity 2^20. */
#define BRAUN_MAX_DENSE 4096
#define BRAUN_MAX_SPARSE (1 << 20)

/* Copy the system, validate sizes and callbacks, set default options.
 * Returns BRAUN_OK, BRAUN_ERR_ARGUMENT, BRAUN_ERR_SIZE or BRAUN_ERR_MISSING_CALLBACK
 * (braun_system_check names the problem). */
int braun_model_init(braun_model *model, const braun_system *sys);
/* The validation of braun_model_init, with its status; *problem (when not
 * NULL) is NULL or a constant string naming the field and the rule broken
 * ("holonomic is NULL but m > 0", "sparsity: row_ptr[0] != 0", ...). */
int braun_system_check(const braun_system *sys, const char **problem);

/* ------------------------------------------------------------------ */
/* Data: state, statistics, scratch                                    */
/* ------------------------------------------------------------------ */
/* Counts since braun_set_state (which starts them from zero; a constant
 * M's one factorization at braun_data_init stays counted): braun_step and
 * the drivers add to them, call after call. Each stops at LONG_MAX, never
 * wraps: on a 32-bit target that is 2^31 − 1, which rhs_evals of RK4 at
 * 1 kHz reach after about 6 days of braun_step calls. */
typedef struct braun_stats {
    long steps;             /* accepted steps */
    long rejected_steps;    /* adaptive driver only */
    long rhs_evals;         /* evaluations of the (ideal or corrected) right-hand side */
    long mass_factorizations;
    long constraint_factorizations; /* QR factorizations of C^T */
    long rank_deficient;    /* factorizations whose rank < rows (redundancy or singularity) */
    long energy_guard_hits; /* energy corrections saturated by energy_max_rel (none where no motion is free) */
    long soft_filtered;     /* stages whose soft directions the filter took from continuity
                             * (options.soft_tol) */
} braun_stats;

/* Where an error happened, for braun_error_format() and the CLI. */
typedef struct braun_error_info {
    int status;
    const char *where;  /* static string: "mass", "forces", "state q", ... */
    int index;          /* row/entry involved, or -1; BRAUN_ERR_CALLBACK and
                         * _RECOVERABLE: the callback's return code (value too) */
    int index2;         /* column, or -1; BRAUN_ERR_ACCURACY refused while
                         * the allowance of a start off its position
                         * constraints was in use (`where` then ends "(a
                         * start off its position constraints)"): that
                         * start's largest position row;
                         * BRAUN_ERR_INCONSISTENT: index and
                         * index2 are the two rows that disagree most
                         * (largest least-squares residual; holonomic rows,
                         * or rows of [A_q; A_vv] when `where` says
                         * "velocity-level"); index2 is
                         * -1 when no other row's residual exceeds the
                         * tolerance (one row that cannot be met alone),
                         * -2 when that row's gradient is zero there */
    double value;       /* offending value (pivot, asymmetry, ...) */
    double t;           /* time of the failing evaluation */
} braun_error_info;

typedef struct braun_data {
    const braun_model *model;
    /* State. q and v point into the buffer (n entries each). */
    braun_real t;
    braun_real *q;
    braun_real *v;
    braun_real work_in;   /* ∫_0^t Ė dτ (Eq. 18) */
    braun_real E0;        /* energy at braun_set_state(); a start off the
                           * constraints, energy correction on: re-taken
                           * (E − ∫Ė) once the corrections have brought the
                           * state onto them (docs/api.md) */
    int has_E0;
    braun_stats stats;
    /* The last failure recorded: read it after a call returned a failure
     * status. It is not cleared on success, so after BRAUN_OK it may hold
     * an earlier call's failure, or one the adaptive driver recovered from
     * (a step retried smaller after a recoverable status). */
    braun_error_info error;
    /* The accuracy guard's scales (options.guard), measured at the first
     * step's state (and again at a state whose residual exceeds its bound,
     * each kept when larger: the motion may start from rest), in the
     * residuals' own units:
     *   pos    = Σ_i Σ_j |A_ij| s_q,j over the holonomic rows, s_q,j =
     *            max(|q_j|, L) with L = max(‖q‖_∞, 1e-6): the size of Φ_q a
     *            displacement of the whole mechanism's size would make;
     *   vel    = the same with s_v,j = max(|v_j|, V), over all rows, V =
     *            max(‖v‖_∞, sqrt(L·‖M⁻¹Q‖_∞)): the speed of the motion or
     *            of a fall over L;
     *   energy = max(|E0|, ½ s_vᵀ M s_v, |∫Ė|, 1e-30) (measured again:
     *            ½ vᵀ M v in place of ½ s_vᵀ M s_v);
     * with sys.q_scale (a scene's natural sizes) each coordinate in its own
     * unit instead, none from where the mechanism is:
     *   pos    = Σ_i Σ_j |A_ij| s_q,j, s_q,j = q_scale[j];
     *   vel    = the same with s_v,j = max(|v_j|, W·s_q,j), W one rate
     *            (1/s) for the mechanism: ½ W² s_qᵀ M s_q is the larger of
     *            ½ vᵀ M v and ½ |Qᵀ s| (the forces' work over the sizes,
     *            s_j = ±s_q,j in the direction Q drives coordinate j), or a
     *            drive's rate |c_i| / Σ_j |A_ij| s_q,j if faster;
     *   energy = max(½ s_vᵀ M s_v, |∫Ė|, 1e-30) (measured again: ½ vᵀ M v),
     *            in J whatever the units; |E0| is left out, its datum (a
     *            potential's zero) being arbitrary;
     * and the residuals at the initial state (pos0, vel0, energy0: the
     * allowance of a start off the constraints, set to 0 once the residual
     * comes within guard × scale). A start off its position constraints
     * (pos0 above sqrt(ε)·pos) raises vel0, at each step until pos0 ends,
     * to twice the velocity residual that step's position correction dq
     * creates, ‖[Φ̇_q; Φ_v](t, q + dq, v) − [Φ̇_q; Φ_v](t, q, v)‖ (measured:
     * two more evaluations of the constraints, at such steps only; never
     * above the first step's). A program may set its own scales after
     * braun_set_state. */
    struct {
        braun_real pos, vel, energy;
        braun_real pos0, vel0, energy0;
    } guard;
    /* Private scratch (src/core/braun_internal.h, braun_layout.c). */
    void *priv;
} braun_data;

/* Bytes of buffer braun_data_init() needs for this model. They include 16
 * bytes of slack: the buffer may start at any address (braun_data_init
 * carves the data from its first 16-byte boundary). */
size_t braun_data_size(const braun_model *model);

/* Carve the data out of buffer; no allocation. If M is constant it is
 * evaluated and factored here, once. There is no state until
 * braun_set_state() (the drivers refuse to run before it). With a backend
 * (opt.linsolver) its state is created here, after every check (it may
 * allocate): release it with braun_data_release. On failure nothing is left
 * to release (d->priv is NULL) and d->error says why. Returns BRAUN_OK,
 * BRAUN_ERR_ARGUMENT (NULL model or buffer, an invalid option),
 * BRAUN_ERR_SIZE (beyond the dense limit), BRAUN_ERR_BUFFER (bytes <
 * braun_data_size()), BRAUN_ERR_NO_ENERGY_LAW, a backend's creation status,
 * or the mass matrix statuses for a constant M. */
int braun_data_init(braun_data *d, const braun_model *model, void *buffer,
                    size_t bytes);

/* Free what a backend allocated (nothing for the built-in kernels). The
 * buffer stays the caller's; d->q and d->v still show the last state, but
 * every call refuses d until braun_data_init. Safe to call twice
 * (BRAUN_OK). Call it before braun_data_init is called again on a d whose
 * model has a backend: braun_data_init cannot know whether d held one
 * (nothing else is lost). Refused (BRAUN_ERR_ARGUMENT, "re-entrant call",
 * nothing released) from a callback while a driver or a step runs on d. */
int braun_data_release(braun_data *d);

/* Set time and state, check it is finite, reset ∫Ė and take E0 = E(t,q,v):
 * a new run. The statistics start from zero (braun_stats) and the accuracy
 * guard's scales are measured again at the next step's start. */
int braun_set_state(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v);

/* ------------------------------------------------------------------ */
/* Evaluation (no time advance)                                        */
/* ------------------------------------------------------------------ */
/* The corrected equation of motion, Eqs. 16, 17, 20, with Δ = Φ/h, at the
 * given state (∫Ė taken from d->work_in: a program's own integrator keeps
 * it there, braun_energy_rate). Eq. 20's energy force is the literal one
 * except where options.energy_max_rel saturates it (a relative change of
 * the weighted velocity per h above it, default 0.01: near rest its
 * pseudoinverse divides by ≈ 2·kinetic energy), as in the drivers; a
 * saturated call counts in d->stats.energy_guard_hits. Corrections as in
 * the model options;
 * with none (or at an exact state) vdot is the Udwadia–Kalaba acceleration
 * and qdot = v. qdot, vdot: n entries each. Refused (BRAUN_ERR_ARGUMENT,
 * "re-entrant call") while a driver runs on d, from its output callback
 * too: its forward pass would replace the factorization the next step
 * starts from. A second braun_data of the same model evaluates anywhere. */
int braun_eval(braun_data *d, braun_real t, const braun_real *q,
               const braun_real *v, braun_real h, braun_real *qdot,
               braun_real *vdot);

/* Constraint and energy residuals at a state: ||Φ_q||_2, ||[Φ̇_q; Φ_v]||_2, |Φ_e|
 * (any output may be NULL; energy is 0 without a law or E0). */
int braun_residuals(braun_data *d, braun_real t, const braun_real *q,
                    const braun_real *v, braun_real *pos, braun_real *vel,
                    braun_real *energy);

/* Total energy E(t,q,v) (0 without a law). */
int braun_energy(braun_data *d, braun_real t, const braun_real *q,
                 const braun_real *v, braun_real *E);

/* Ė of the energy law (Eq. 18) at a state: the power callback's input plus
 * the work rate of moving constraints, as the drivers integrate it into
 * d->work_in. A program that steps braun_eval with its own integrator and
 * corrects the energy integrates Ė along with q and v and writes the
 * integral into d->work_in before each braun_eval (its energy law is then
 * E = E0 + ∫Ė; left at 0, a motor's or a drive's work is taken out of the
 * motion again). 0 for a system without energy input or moving
 * constraints. Refused where braun_eval is (a forward pass). */
int braun_energy_rate(braun_data *d, braun_real t, const braun_real *q,
                      const braun_real *v, braun_real *Edot);

/* ------------------------------------------------------------------ */
/* Integrators                                                         */
/* ------------------------------------------------------------------ */
typedef enum braun_method {
    BRAUN_EULER = 0,
    BRAUN_HEUN = 1,
    BRAUN_RK4 = 2,
    /* Dormand–Prince 5(4): the adaptive driver, or fixed steps through
     * braun_step and braun_integrate (its 5th-order solution, no error
     * control; 6 right-hand sides per step: the 7th stage, of weight 0,
     * serves only the adaptive driver's error estimate, 7 per attempt) */
    BRAUN_DOPRI5 = 3
} braun_method;

/* Name ("euler", "heun", "rk4", "dopri5") <-> method; -1 if unknown. */
const char *braun_method_name(braun_method method);
int braun_method_from_name(const char *name);

/* One fixed step of size h from d->t. On any error the state is left as it
 * was before the step — except BRAUN_ERR_ACCURACY, refused at this step's
 * start, which is the state the last step left: the state is then the one
 * before that step (the last that passed the guard: options.guard,
 * docs/robustness.md). BRAUN_DOPRI5 takes its 5th-order solution. */
int braun_step(braun_data *d, braun_method method, braun_real h);

/* Output callback: called at the start, every `every` steps and at the end
 * (every <= 0: the start and the end only; the end once). A state is
 * reported once the next step's start has passed the accuracy guard, so
 * it sees only states that passed. It may read d and call braun_residuals
 * and braun_energy on it (through a non-const pointer of its own, e.g. in
 * out_user): that changes neither the run nor d->stats. It must not
 * change the state; braun_eval, braun_set_state, braun_step and the
 * drivers on d are refused there (accelerations at the reported state:
 * braun_eval on a second braun_data of the same model). Return non-zero to stop: the driver returns
 * BRAUN_STOPPED with d at the state the callback saw. */
typedef int (*braun_output_fn)(const braun_data *d, void *user);

/* Fixed-step driver from d->t to t_end. Step i ends at t0 + i·h (no
 * accumulated round-off in t) but the last, which ends on t_end exactly:
 * N = max(1, ceil(R - a)) steps, R = (t_end - t0)/h, a = min(1/2,
 * max(8ε, 1e-9)·R), so the last is h less a shortfall or h plus a leftover
 * of at most a steps (1e-9 of the span in double): h = 0.01 to
 * t_end = 1 + 1e-10 is 100 steps, the last 0.0100000001. */
int braun_integrate(braun_data *d, braun_method method, braun_real h,
                    braun_real t_end, long every, braun_output_fn out,
                    void *out_user);

typedef struct braun_adaptive {
    braun_real rtol, atol;  /* mixed error test on q, v: 0 <= rtol < 1, atol >= 0 and
                             * finite, not both 0 (else BRAUN_ERR_ARGUMENT); atol is
                             * absolute, in q's and v's units: scale it with the
                             * mechanism (docs/api.md) */
    braun_real h0;          /* first trial step (<= 0: 1e-3·(t_end - t), the span if
                             * that is 0) */
    braun_real h_min, h_max;/* <= 0: 1e-12·|span| but at least 16ε·max(|t|, |t_end|),
                             * where t + h still advances t by h, and the span; every
                             * step but the last in [h_min, h_max]; not finite or
                             * h_min > h_max: refused */
    long max_steps;         /* attempts (accepted + rejected steps) of one call;
                               <= 0: 10^8. Counted per call: the same call from
                               the same state always behaves the same. */
} braun_adaptive;

/* Adaptive Dormand–Prince 5(4) driver; corrections applied once per accepted
 * step (BRAUN_PER_STEP whatever the option says: with a varying h the literal
 * Δ = Φ/h form is ill-posed). The output callback sees every `every`-th
 * accepted step and the last. */
int braun_integrate_adaptive(braun_data *d, const braun_adaptive *ctl,
                             braun_real t_end, long every, braun_output_fn out,
                             void *out_user);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_H */
