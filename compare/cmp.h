/*
 * braun-compare: the comparison harness of `make compare` (docs/compare.md).
 *
 * Every method is driven from the same target: a braun_system with its
 * initial state and, where one exists, a minimal-coordinate reference.
 * The harness links SUNDIALS IDA and GSL (GPL-3); libbraun.a never does.
 *
 * Layers: target (cmp_target.c) -> reference (cmp_reference.c) ->
 * methods (cmp_braun.c, cmp_baumgarte.c, cmp_ida.c, cmp_ode.c), each filling
 * a trajectory sampled on a common output grid -> metrics (cmp_metrics.c)
 * -> study (cmp_study.c: runs, best-of-k timing, CSV) -> report (cmp_report.c).
 */
#ifndef CMP_H
#define CMP_H

#include <stddef.h>
#include <stdio.h>

#include "braun.h"
#include "braun_reference.h"
#include "braun_scene_file.h"

#ifdef BRAUN_SINGLE
#error "braun-compare measures errors down to 1e-12: build it with braun_real = double"
#endif

/* ------------------------------------------------------------ targets */
/* Where a target's reference comes from. */
typedef enum cmp_ref_kind {
    CMP_REF_NONE = 0,   /* no reference: trajectory errors are NaN */
    CMP_REF_CLOSED,     /* closed form of the minimal equation (minimal_exact) */
    CMP_REF_RK8PD,      /* GSL rk8pd on the minimal equation, rtol = atol = tol */
    CMP_REF_TRAJ,       /* braun RK4 at a small step (not for references any more:
                         * braun does not judge braun; kept for the tests) */
    CMP_REF_POINT,      /* published values at one time (Andrews at t = 0.03) */
    CMP_REF_PROJ,       /* the harness's RK4 + projection at a small step (cmp_proj.c),
                         * tabulated with q, v, a and interpolated (quintic Hermite) */
    CMP_REF_CLOSED_GSL  /* the same closed form as CMP_REF_CLOSED evaluated with GSL's
                         * Jacobi elliptic functions (cmp_pendulum_gsl): the closed
                         * form's own error is the difference of the two */
} cmp_ref_kind;

/* A target: a system, its initial state, optionally a minimal-coordinate
 * model (equation, closed form, lift to q, v) and an observable point. */
typedef struct cmp_target {
    char name[64];
    braun_system sys;
    double *q0, *v0;                    /* n entries each, owned */
    /* Minimal-coordinate model (NULL builtin: none). */
    const braun_builtin *builtin;
    /* The point whose planar error is the paper's ε (slider end of Fig. 2,
     * joint 3 of Fig. 7); has_point = 0 if none. */
    int has_point;
    const char *point_name;
    void (*point)(const struct cmp_target *tg, const double *q, double *xy);
    /* How the study treats it: the paper's grid, or a reduced one over
     * [0, T_reduced] sampled every dt_out with steps scaled by h_scale. */
    int paper;
    double T_reduced, dt_out, h_scale;
    /* Preferred reference when there is no minimal-coordinate model. */
    cmp_ref_kind ref_kind;
    double ref_t;                       /* CMP_REF_POINT: its time ... */
    const double *ref_q;                /* ... and q there (n entries) */
    void *scene_file;                   /* braun_scene_file *, owned */
    struct cmp_minimal *minimal;        /* the harness's minimal equation of a scene
                                         * (cmp_minimal.c), owned, or NULL */
    int scene_point;                    /* scene point of ε, -1 if none */
} cmp_target;

/* Fill tg for a name: a built-in model, or (later) a scene file. Returns 0,
 * or -1 with a message in err. */
int cmp_target_find(const char *name, cmp_target *tg, char *err, size_t errsize);
void cmp_target_free(cmp_target *tg);
/* Units of the constraint rows Φ_q ("m", "m²", "m; m²", "rad", ...) and of
 * q ("m", "m; rad") for axis labels (no commas: they go into CSV fields). */
void cmp_target_units(const cmp_target *tg, char *phi, size_t phisize, char *q, size_t qsize);

/* Kind of reference the target supports best: closed form, else rk8pd on the
 * minimal equation, else the target's own (trajectory or published point). */
cmp_ref_kind cmp_target_ref_kind(const cmp_target *tg);

/* ------------------------------------------------------------ minimal equations
 * of scenes (cmp_minimal.c): open chains and parallelograms, written by the
 * harness from the scene's mechanism (never libbraun's method). The state
 * is y = [α, α'] (dim = 2k entries). */
#define CMP_MINIMAL_MAX 8
typedef struct cmp_minimal cmp_minimal;
/* The minimal equation of a scene target, or NULL with the reason in why. */
cmp_minimal *cmp_minimal_new(const cmp_target *tg, char *why, size_t whysize);
void cmp_minimal_free(cmp_minimal *mm);
int cmp_minimal_dim(const cmp_minimal *mm);
const double *cmp_minimal_y0(const cmp_minimal *mm);
const char *cmp_minimal_name(const cmp_minimal *mm);
/* dy = f(t, y); 0, or -1 (singular mass matrix, not finite). */
int cmp_minimal_rhs(const cmp_minimal *mm, double t, const double *y, double *dy);
/* libbraun's q, v (n each) of minimal state y. */
void cmp_minimal_state(cmp_minimal *mm, const double *y, double *q, double *v);

/* ------------------------------------------------------------ references */
typedef struct cmp_ref cmp_ref;

/* The pendulum φ'' = −w2 sin φ from (φ0, φ0') in closed form with GSL's
 * Jacobi elliptic functions and elliptic integrals (an implementation
 * independent of libbraun's braun_pendulum_exact): rotation and libration,
 * not the separatrix. 0, or -1. */
int cmp_pendulum_gsl(double w2, double phi0, double dphi0, double t, double *phi, double *dphi);

/* A reference evaluator: closed form (any t) or rk8pd (t non-decreasing
 * between calls). tol: rk8pd rtol = atol (ignored for the closed form).
 * NULL if the target has no such reference. */
cmp_ref *cmp_ref_new(const cmp_target *tg, cmp_ref_kind kind, double tol);
/* A trajectory reference: braun (all corrections the system supports) with
 * fixed-step RK4 of step h from 0 to T, tabulated every dt_tab (a multiple
 * of h) and interpolated by cubic Hermite polynomials in q (v linear).
 * NULL if the run fails. */
cmp_ref *cmp_ref_new_traj(const cmp_target *tg, double T, double h, double dt_tab);
/* A projection reference: cmp_proj_integrate (RK4 + projection, positions
 * and velocities) at step h from 0 to T, tabulated every dt_tab (a
 * multiple of h) with q, v, a: q by quintic, v by cubic Hermite
 * interpolation. Its work integral is E(ref(t)) - E0 (the energy law holds
 * along the exact solution). NULL if the run fails (*why: its status). */
cmp_ref *cmp_ref_new_proj(const cmp_target *tg, double T, double h, double dt_tab,
                          char *why, size_t whysize);
/* q, v at time t (n each); 0, 1 if the reference does not know this time
 * (CMP_REF_POINT), or -1 if it failed. */
int cmp_ref_eval(cmp_ref *r, double t, double *q, double *v);
/* ∫Ė dτ from 0 to t along a trajectory reference (CMP_REF_TRAJ: libbraun's
 * work integral, constraint work included); 0, or -1 if r has none. */
int cmp_ref_work(cmp_ref *r, double t, double *W);
void cmp_ref_free(cmp_ref *r);
/* Evaluate r once on t_j = j·dt, 0 <= t_j <= T, and answer those times from
 * the table from now on (other times: a private evaluator of the same kind
 * and tolerance). 0, or -1 if the reference failed. */
int cmp_ref_tabulate(cmp_ref *r, double dt, double T);
const char *cmp_ref_kind_name(cmp_ref_kind kind);
/* A tabulated reference to a binary file (r NULL: "no reference") and back,
 * for the same target in another process of the same binary: the same
 * table bit for bit; other times go to a fresh private evaluator. 0 or -1
 * (load: *out NULL for "no reference"). */
int cmp_ref_save(const cmp_ref *r, const char *path);
int cmp_ref_load(const cmp_target *tg, const char *path, cmp_ref **out);
/* Drop the private off-grid evaluator, so that a run sees the reference as
 * freshly loaded whatever ran before it (compare/run.sh's processes). */
void cmp_ref_restart(cmp_ref *r);

/* ------------------------------------------------------------ trajectories */
/* States sampled by a run: on the common grid t_j = j·dt_out for the fixed-
 * step methods and IDA; at each accepted step for the adaptive braun driver. */
typedef struct cmp_traj {
    int n;
    long count, cap;
    double *t, *q, *v;   /* count, count·n, count·n */
} cmp_traj;

int cmp_traj_init(cmp_traj *tr, int n, long cap);
void cmp_traj_clear(cmp_traj *tr);
void cmp_traj_free(cmp_traj *tr);
/* Append a sample (grows the arrays if needed); 0 or -1 out of memory. */
int cmp_traj_push(cmp_traj *tr, double t, const double *q, const double *v);

/* ------------------------------------------------------------ methods */
typedef enum cmp_method_id {
    CMP_BRAUN = 0,       /* Eqs. 16, 17, 20: all corrections */
    CMP_BRAUN_NOENERGY,  /* Eqs. 16, 17: position and velocity corrections */
    CMP_BAUMGARTE,       /* ideal acceleration with -2αΦ̇ - β²Φ, RK4 */
    CMP_IDA_GGL,         /* SUNDIALS IDA, stabilised index-2 (GGL) */
    CMP_IDA_INDEX1,      /* SUNDIALS IDA, acceleration-level index-1 */
    CMP_ODE_RK4,         /* minimal-coordinate equation, RK4 */
    CMP_PROJECTION,      /* RK4 on the index-1 equation + coordinate projection */
    CMP_MUJOCO,          /* MuJoCo 2.2.2 (cmp_mujoco.c), from generated MJCF */
    CMP_SIMBODY,         /* Simbody 3.7 (cmp_simbody.cpp) */
    CMP_METHOD_COUNT
} cmp_method_id;

const char *cmp_method_name(cmp_method_id m);
int cmp_method_from_name(const char *name); /* -1 if unknown */

/* IDA's linear solver. */
typedef enum cmp_linsol {
    CMP_LS_AUTO = 0,   /* dense below CMP_KLU_MIN_N unknowns, KLU from there */
    CMP_LS_DENSE,      /* SUNLinSol_Dense: LU with partial pivoting */
    CMP_LS_KLU,        /* SUNLinSol_KLU, sparse Jacobian (cmp_ida_opts.jac) */
    CMP_LS_COD         /* the harness's rank-revealing solver (cmp_ida_cod.c) */
} cmp_linsol;

/* Unknowns from which CMP_LS_AUTO picks KLU (the paper's mechanisms have 22). */
#define CMP_KLU_MIN_N 200

/* IDA settings under investigation (docs/compare.md, "IDA"). */
typedef struct cmp_ida_opts {
    double alg_atol;     /* absolute tolerance of λ, μ (Newton test only); 0: atol */
    double max_step;     /* IDASetMaxStep, 0: none */
    cmp_linsol linsol;
    double cod_rtol;     /* CMP_LS_COD rank tolerance relative to max|R_ii|; 0: GSL default */
    double reg;          /* ε of the regularised constraint rows (0 = Φ - ελ); 0: none */
    int restarts;        /* after a failed step: re-project the last good state and
                          * restart IDA (IDAReInit) up to this many times; 0: never */
    double restart_h0;   /* first step after a restart [s] */
    int no_suppress;     /* 1: keep λ, μ in the error test */
    int max_order;       /* IDASetMaxOrd, 0: default 5 */
    double nl_conv_coef; /* IDASetNonlinConvCoef, 0: default 0.33 */
    /* KLU only (cmp_ida_jac.c): the Newton matrix J = ∂F/∂y + c_j ∂F/∂y'
     * and the residual it belongs to. 0 (AUTO) for both: a target whose
     * scene the harness can differentiate (cmp_ggl_new) gets the scene's
     * sparse GGL residual and its analytic Jacobian, any other the
     * callbacks' residual and colored finite differences. */
    int jac;             /* cmp_jac_kind */
    int residual;        /* cmp_res_kind */
} cmp_ida_opts;

/* How the KLU path forms J (cmp_ida_opts.jac). */
typedef enum cmp_jac_kind {
    CMP_JAC_AUTO = 0,    /* analytic when the scene provider exists, else colored */
    CMP_JAC_ANALYTIC,    /* scene provider only (setup fails without one) */
    CMP_JAC_COLORED,     /* Curtis-Powell-Reid: one residual per column color */
    CMP_JAC_COLUMN       /* one residual per column (the harness before issue 7) */
} cmp_jac_kind;

/* Which residual the KLU path integrates (cmp_ida_opts.residual). */
typedef enum cmp_res_kind {
    CMP_RES_AUTO = 0,    /* the scene's when the provider exists, else callbacks */
    CMP_RES_CALLBACKS,   /* cmp_dae_residual: the braun_system callbacks (dense) */
    CMP_RES_SCENE        /* cmp_ggl_residual: O(n) from the scene structure */
} cmp_res_kind;

/* Integrators of the peers (cmp_spec.integrator of mujoco and simbody runs;
 * names: cmp_integrator_name). */
enum cmp_peer_integrator {
    CMP_MJ_EULER = 100,  /* MuJoCo's semi-implicit Euler */
    CMP_MJ_RK4,          /* MuJoCo's classic RK4 */
    CMP_MJ_IMPLICIT,     /* MuJoCo's implicit-in-velocity Euler */
    CMP_SB_RKM = 110,    /* Simbody RungeKuttaMersonIntegrator (4(5), error control) */
    CMP_SB_RKF,          /* RungeKuttaFeldbergIntegrator */
    CMP_SB_RK3,          /* RungeKutta3Integrator */
    CMP_SB_CPODES,       /* CPodesIntegrator (BDF, Newton) */
    CMP_SB_RKM_FIXED     /* RungeKuttaMerson at a fixed step (setFixedStepSize) */
};
/* "rk4", "dopri5", "bdf", "mj-rk4", "rk-merson", ... */
const char *cmp_integrator_name(int integrator);
int cmp_integrator_from_name(const char *name); /* -2 if unknown */

/* Settings of a peer run (docs/compare.md, "Peers"); zero: the peer's default. */
typedef struct cmp_peer_opts {
    /* MuJoCo: solref (time constant [s], damping ratio) of every equality,
     * timeconst < 0: MuJoCo's default 0.02; 0: 2·h, the stiffest it allows;
     * > 0 as given (multiples of h are in the variant). */
    double timeconst, dampratio;
    double solimp[3];    /* dmin, dmax, width; all 0: MuJoCo's 0.9, 0.95, 0.001 */
    int solver;          /* 0 Newton, 1 CG, 2 PGS */
    double tolerance;    /* constraint solver tolerance; 0: 1e-8 */
    int iterations;      /* solver iterations; 0: 100 */
    /* Simbody: the integrator's accuracy is rtol; constraint tolerance
     * (0: = accuracy, Simbody's default). */
    double ctol;
} cmp_peer_opts;

/* One run: a method, its integrator and its step size or tolerance. */
typedef struct cmp_spec {
    cmp_method_id method;
    int integrator;      /* braun_method (explicit methods); -1: IDA's BDF */
    double h;            /* fixed step; 0 for adaptive methods */
    double rtol, atol;   /* adaptive methods and IDA; 0 for fixed-step */
    double alpha, beta;  /* Baumgarte gains [1/s] */
    char variant[32];    /* "" or a label such as "ab=0.3/h", "atol_alg=1e+06" */
    cmp_ida_opts ida;
    cmp_peer_opts peer;
    double T;            /* end time */
    double dt_out;       /* output grid */
} cmp_spec;

/* Work done by a run (docs/compare.md lists what each counts per method). */
typedef struct cmp_counts {
    long steps, rejected, rhs_evals, jac_evals, lin_setups, lin_solves;
    long err_fails, conv_fails;
    long restarts;       /* IDA restarts after failures (cmp_ida_opts.restarts) */
    long iterations;     /* projection: Gauss–Newton iterations; MuJoCo: constraint
                          * solver iterations; Simbody: projections */
} cmp_counts;

/* Outcome of a run. status 0: reached T; otherwise t_reached < T and
 * status_name says why (a libbraun or IDA return flag name). */
typedef struct cmp_outcome {
    int status;
    char status_name[48];
    char detail[160];
    double t_reached;
    cmp_counts counts;
    /* > 0: the CPU time [s] of the integration itself, measured by the
     * runner (peers: without building the model and without converting
     * their samples to q, v); 0: the caller times the whole run. */
    double cpu_self;
} cmp_outcome;

/* Integrate tg per spec, sampling into tr (cleared first). Never aborts:
 * failures are returned in out. */
void cmp_run(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
             cmp_outcome *out);

/* Per-method runners (cmp_run dispatches). */
void cmp_run_braun(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                   cmp_outcome *out);
void cmp_run_baumgarte(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                       cmp_outcome *out);
void cmp_run_ida(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                 cmp_outcome *out);
void cmp_run_ode(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                 cmp_outcome *out);
void cmp_run_projection(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                        cmp_outcome *out);
/* Peers (cmp_mujoco.c, cmp_simbody.cpp). Without the package the run
 * fails with status NOT_BUILT. */
void cmp_run_mujoco(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                    cmp_outcome *out);
void cmp_run_simbody(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                     cmp_outcome *out);
/* 1 if the peer can express the target (its mechanism and tree), else 0
 * with the reason in why. */
int cmp_mujoco_supports(const cmp_target *tg, char *why, size_t whysize);
int cmp_simbody_supports(const cmp_target *tg, char *why, size_t whysize);
/* The peers' versions ("2.2.2", "3.7"), or NULL if not built in. */
const char *cmp_mujoco_version(void);
const char *cmp_simbody_version(void);

/* Baumgarte: a system whose b_qv, b_vv carry the stabilisation terms
 * (b_qv - 2αΦ̇_q - β²Φ_q, b_vv - 2αΦ_v), so that the ideal acceleration of
 * the wrapped system (braun_eval, corrections off) is Baumgarte's. */
typedef struct cmp_baumgarte_sys {
    braun_system inner;
    double alpha, beta;
    double *phi, *b, *A; /* scratch: m, m, m·n */
} cmp_baumgarte_sys;
int cmp_baumgarte_wrap(cmp_baumgarte_sys *bs, const braun_system *inner,
                       double alpha, double beta, braun_system *out);
void cmp_baumgarte_free(cmp_baumgarte_sys *bs);

/* IDA residuals, exposed for the tests. Unknowns y = [q, v, λ, μ] (GGL, N =
 * 2n + m + p + m) or [q, v, λ] (index-1, N = 2n + m + p). */
typedef struct cmp_dae cmp_dae;
cmp_dae *cmp_dae_new(const cmp_target *tg, int index1);
/* Regularise the constraint rows: each algebraic row r_k gets -ε·y_k (y_k its
 * multiplier), a damped-least-squares version of the KKT system. */
void cmp_dae_set_reg(cmp_dae *dae, double eps);
void cmp_dae_free(cmp_dae *dae);
int cmp_dae_size(const cmp_dae *dae);
int cmp_dae_residual(cmp_dae *dae, double t, const double *y, const double *yp,
                     double *r);
/* Consistent y, yp from (q0, v0): q projected on Φ_q = 0, v on the velocity
 * constraints, v' and λ from the constrained equations, μ = 0. */
int cmp_dae_consistent(cmp_dae *dae, double t, const double *q0, const double *v0,
                       double *y, double *yp);

/* Sparsity pattern of J = ∂F/∂y + c_j ∂F/∂y' (every c_j), compressed
 * sparse columns with the diagonal included; *colptr (N + 1) and *rowind
 * (the returned nnz) are malloc'd, rows increasing within a column.
 * Returns nnz, or -1.
 *   _probe: the union of nonzeros of forward-difference columns at y0, y0'
 *     and three random perturbations of them (4N residuals: exact for what
 *     the callbacks compute, O(N) residuals and O(N²) work);
 *   _struct: from the structure of the callbacks: A and M at those four
 *     states, the Hessian of each holonomic row within its own support,
 *     and forces, non-constant mass and nonholonomic rows probed
 *     coordinate by coordinate (O(n) callback calls, no residual);
 *   cmp_dae_pattern: _probe up to CMP_PATTERN_PROBE_MAX unknowns, _struct
 *     above. */
#define CMP_PATTERN_PROBE_MAX 2000
int cmp_dae_pattern_probe(cmp_dae *dae, const double *y0, const double *yp0, int **colptr,
                          int **rowind);
int cmp_dae_pattern_struct(cmp_dae *dae, const double *y0, const double *yp0, int **colptr,
                           int **rowind);
int cmp_dae_pattern(cmp_dae *dae, const double *y0, const double *yp0, int **colptr,
                    int **rowind);

/* ------------------------------------------------------------ sparse Jacobians
 * (cmp_ida_jac.c) */
/* A growing list of (row, col) pairs (a pattern as it is found); failed is
 * set when an allocation failed (pushes are then ignored). */
typedef struct cmp_pairs {
    long n, cap;
    int *r, *c;
    int failed;
} cmp_pairs;
void cmp_pairs_push(cmp_pairs *P, int r, int c);
void cmp_pairs_free(cmp_pairs *P);

/* Compressed sparse columns of an N x N pattern from nt (row, col) pairs
 * (duplicates merged, rows sorted); map (nt entries, may be NULL) receives
 * the position of each pair in rowind. Returns nnz, or -1. */
int cmp_csc_from_pairs(int N, long nt, const int *row, const int *col, int **colptr,
                       int **rowind, int *map);

/* Finite-difference Jacobian on a known pattern. Columns that share no row
 * get one color (greedy Curtis-Powell-Reid in column order) and one
 * residual evaluation per color perturbs them together; colored = 0 gives
 * every column its own color (N residuals). The increment of column j is
 * sqrt(ε)·max(|y_j|, 1) in y_j and c_j times that in y'_j, as IDA's dense
 * difference quotient; the values equal those of one-column differences
 * wherever the pattern holds every nonzero. */
typedef int (*cmp_res_fn)(void *user, double t, const double *y, const double *yp,
                          double *r);
typedef struct cmp_fdjac cmp_fdjac;
/* colptr, rowind are copied. NULL on failure. */
cmp_fdjac *cmp_fdjac_new(int N, const int *colptr, const int *rowind, int colored);
void cmp_fdjac_free(cmp_fdjac *fd);
int cmp_fdjac_colors(const cmp_fdjac *fd);
/* val (nnz, in pattern order) at (t, y, y') with r0 = F(t, y, y'); 0, or
 * the residual's nonzero status. Residual calls are added to *nres. */
int cmp_fdjac_eval(cmp_fdjac *fd, cmp_res_fn res, void *user, double t, double cj,
                   const double *y, const double *yp, const double *r0, double *val,
                   long *nres);

/* The analytic Jacobian provider: the GGL form of a built scene (cmp_dae.c's
 * rows, reg included) evaluated from the scene's structure in O(n) — sparse
 * M, A(q), and the second-derivative terms ∂(A_qᵀμ)/∂q, ∂(A_qᵀλ)/∂q,
 * ∂(A_q v)/∂q — with its pattern built once. Scenes of rigid bodies,
 * particles, rods, revolute joints and gravity (what `braun gen chain`
 * writes); anything else (other joints, knife edges, other effects) is
 * refused and the harness falls back to colored finite differences of the
 * callbacks. Without the scene library cmp_ggl_new always refuses. */
struct braun_scene;
typedef struct cmp_ggl cmp_ggl;
/* scene: built by braun_scene_build (coordinates and rows numbered), and
 * must outlive the provider. NULL if refused; *why (may be NULL) then says
 * why (static text). */
cmp_ggl *cmp_ggl_new(const struct braun_scene *scene, const char **why);
void cmp_ggl_free(cmp_ggl *g);
int cmp_ggl_size(const cmp_ggl *g);              /* N = 2n + 2m */
int cmp_ggl_n(const cmp_ggl *g);
void cmp_ggl_set_reg(cmp_ggl *g, double eps);    /* as cmp_dae_set_reg */
int cmp_ggl_residual(cmp_ggl *g, double t, const double *y, const double *yp, double *r);
/* The pattern (CSC, diagonal included; owned by g). Returns nnz. */
int cmp_ggl_pattern(const cmp_ggl *g, const int **colptr, const int **rowind);
/* J = ∂F/∂y + c_j ∂F/∂y' at (t, y, y') into val (nnz, pattern order). */
int cmp_ggl_jacobian(cmp_ggl *g, double t, double cj, const double *y, const double *yp,
                     double *val);
/* As cmp_dae_consistent, with sparse KKT solves (KLU) instead of GSL's SVD:
 * full-rank rows only (returns -1 on redundant rows). */
int cmp_ggl_consistent(cmp_ggl *g, double t, const double *q0, const double *v0, double *y,
                       double *yp);
/* The scene of a target, or NULL (built-in models, Andrews). */
const struct braun_scene *cmp_target_scene(const cmp_target *tg);

/* ------------------------------------------------------------ IDA + KLU for
 * scaling studies (cmp_ida.c) */
/* The mechanism: a braun_system with q0, v0 and, for the analytic
 * Jacobian and the O(n) residual, the scene it was built from. sys may be
 * NULL when the scene is given and cmp_ggl_new accepts it. */
typedef struct cmp_ida_problem {
    const braun_system *sys;
    const double *q0, *v0;              /* n each */
    const struct braun_scene *scene;    /* or NULL: callbacks, colored FD */
} cmp_ida_problem;

typedef struct cmp_ida_run_opts {
    double t_end, rtol, atol;
    double alg_atol;     /* λ, μ absolute tolerance (Newton test only); 0: atol */
    int jac;             /* cmp_jac_kind (AUTO: analytic if the scene allows) */
    int residual;        /* cmp_res_kind */
    int max_order;       /* 0: IDA's 5 */
    long max_steps;      /* per output interval; 0: 100000 */
    double reg;          /* ε of regularised constraint rows Φ - ελ (cmp_dae_set_reg);
                          * 0: none. Redundant rows make J singular without it. */
    /* Optional samples: n_out increasing times in (0, t_end]; q_out, v_out
     * (n_out·n each, caller-owned) receive IDA's interpolant there. */
    int n_out;
    const double *t_out;
    double *q_out, *v_out;
    /* Optional final state (n each, caller-owned; the state at t_reached). */
    double *q_end, *v_end;
} cmp_ida_run_opts;

typedef struct cmp_ida_run_result {
    int success;         /* 1: reached t_end */
    char status[48];     /* IDA_SUCCESS or IDA's flag name (SETUP_FAILED, ...) */
    char detail[160];
    double t_reached;
    int N, nnz, colors;  /* unknowns, nonzeros of J, FD colors (0: analytic) */
    int jac, residual;   /* what was used (cmp_jac_kind, cmp_res_kind) */
    long steps, res_evals;   /* res_evals: IDA's residual calls (no Jacobian) */
    long jac_evals, jac_res_evals; /* Jacobians; residual calls made by them */
    long lin_setups, nl_iters, err_fails, conv_fails;
    double cpu_setup_s;  /* pattern, coloring, consistent values, IDA setup */
    double cpu_solve_s;  /* IDASolve calls (KLU factorizations included) */
} cmp_ida_run_result;

/* IDA (GGL form, IDASetStopTime(t_end), λ, μ algebraic and out of the error
 * test) with SUNLinSol_KLU, from consistent values of (q0, v0). Returns 0 if
 * t_end was reached, else -1 with status and detail set. */
int cmp_ida_klu_run(const cmp_ida_problem *pb, const cmp_ida_run_opts *o,
                    cmp_ida_run_result *res);
/* `braun-ida-run SCENE.json T RTOL [options]` (compare/tools/ida_run.c):
 * prints the result as key = value lines. Returns a process exit status. */
int cmp_ida_run_cli(int argc, char **argv);

/* A SUNDIALS linear solver (direct, dense SUNMatrix) that solves each Newton
 * system in the least-squares minimum-norm sense through GSL's complete
 * orthogonal decomposition, dropping pivots below rtol·max|R_ii| (rtol <= 0:
 * GSL's default 20(M+N)ε). Returns NULL on failure. */
struct _generic_SUNLinearSolver;
struct _SUNContext;
struct _generic_SUNLinearSolver *cmp_sunlinsol_cod(int N, double rtol,
                                                   struct _SUNContext *ctx);
/* Rank-deficient factorizations seen by a solver from cmp_sunlinsol_cod. */
long cmp_sunlinsol_cod_deficient(struct _generic_SUNLinearSolver *S);

/* Minimum-M-norm solutions with the harness's own linear algebra (GSL SVD):
 *   dx = M⁻¹Aᵀ (A M⁻¹ Aᵀ)⁺ r       (rows x n matrix A)
 * and the constrained acceleration with multipliers (KKT, pseudoinverse):
 *   M a = Q + Aᵀ λ,  A a = b. */
int cmp_min_norm_step(int n, int rows, const double *M, const double *A,
                      const double *r, double *dx);
int cmp_kkt_accel(int n, int rows, const double *M, const double *Q,
                  const double *A, const double *b, double *acc, double *lambda);
/* σ_min/σ_max of C = A R⁻¹: how close the rows are to losing rank
 * (0 at a kinematic singularity or with redundant rows). NaN on failure. */
double cmp_sigma_ratio(int n, int rows, const double *M, const double *A);

/* Kinematic singularities of a target with a minimal-coordinate model: scan
 * the minimal angle over one turn, find where σ_min/σ_max of C_q has a local
 * minimum below 1e-3, and near each such angle θ* write the minimum-norm
 * multipliers max|λ| and the constraint force max|A_qᵀλ| at θ* + δ
 * (δ = 1e-1 .. 1e-7). Rows: scene,theta_star,delta,sigma_ratio,lambda_max,
 * force_max. Returns the number of singular angles found, -1 if none can
 * be looked for. */
int cmp_singularity_scan(const cmp_target *tg, FILE *f);
/* σ_min/σ_max of C_q at configuration q (NaN without holonomic rows). */
double cmp_target_sigma(const cmp_target *tg, double t, const double *q);

/* ------------------------------------------------------------ metrics */
typedef struct cmp_metrics {
    double pos_max, pos_final;       /* ||Φ_q||_2 */
    double vel_max, vel_final;       /* ||[Φ̇_q; Φ_v]||_2 */
    double energy_max, energy_final; /* |Φ_e| */
    double traj_max, traj_final;     /* ||q - q_ref||_2 (NaN without reference) */
    double point_max, point_final;   /* planar distance of the observable point */
    /* Medians over the samples (a maximum can be one spike's, a median
     * cannot): ||Φ_q||_2 and |Φ_e|. NaN without samples. */
    double pos_median, energy_median;
    long samples;
} cmp_metrics;

/* One sample's errors, for histories (Figs. 3 and 7). */
typedef struct cmp_sample_err {
    double t, pos, vel, energy, traj, point;
    double obs, obs_ref;  /* x of the observable point (Fig. 2) and its reference */
} cmp_sample_err;

typedef void (*cmp_sample_fn)(const cmp_sample_err *e, void *user);

/* Metrics of a trajectory against a reference (ref may be NULL). Samples
 * must be in non-decreasing time (rk8pd references). each, if not NULL, is
 * called for every sample. Returns 0 or -1 (residual or reference failure). */
int cmp_metrics_compute(const cmp_target *tg, const cmp_traj *tr, cmp_ref *ref,
                        cmp_metrics *mt, cmp_sample_fn each, void *user);

/* ------------------------------------------------------------ utilities */
/* Sampling interval in steps: dt_out/h when that is a whole number, else 1. */
long cmp_every(double dt_out, double h);
/* Outcome status from a libbraun status (name without its meaning). */
void cmp_status_from_braun(cmp_outcome *out, int st);
/* mkdir -p; 0 or -1 (cmp_posix.c). */
int cmp_mkdir_p(const char *path);
/* CPU time of this process in seconds (cmp_posix.c). */
double cmp_cpu_seconds(void);
/* Wall clock in seconds. */
double cmp_wall_seconds(void);

#endif
