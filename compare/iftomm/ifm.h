/*
 * braun-iftomm: the IFToMM multibody benchmark problems A01-A05
 * (docs/iftomm.md) run with libbraun and judged against references that
 * libbraun never computes.
 *
 * References are models written here in their own coordinates: a model
 * gives its kinetic energy T(q, v), potential V(q), constraints φ(q) and
 * their rate ψ(q, v) = G(q) v in complex arithmetic, and everything the
 * equations of motion need follows from them exactly by complex-step
 * differentiation (ifm_lagrange.c): M from the polarisation of T, the
 * velocity-product terms from one complex step of M(q) v along v, G and
 * the acceleration term (∂ψ/∂q) v likewise. No derivative is typed by
 * hand, so a misprint in a source cannot enter twice. Models are then
 * integrated by SUNDIALS IDA (ifm_ida.c, a stabilised index-2 DAE) and by
 * GSL's Prince-Dormand 8(9) on minimal coordinates (ifm_minimal.c), and
 * A01, A02 also in closed form (Jacobi elliptic functions).
 *
 * The harness links SUNDIALS and GSL (GPL-3); libbraun.a never does.
 */
#ifndef IFM_H
#define IFM_H

#include <complex.h>
#include <stddef.h>
#include <stdio.h>

typedef double complex ifm_cx;

#define IFM_MAX_N 16 /* coordinates of a reference model */
#define IFM_MAX_M 16 /* its constraint rows */

/* ------------------------------------------------------------ models */
typedef struct ifm_model ifm_model;
struct ifm_model {
    const char *name;
    int n, m;       /* coordinates; independent constraint rows */
    /* T(q, v): quadratic in v, holomorphic in q (complex steps go into q
     * and into v). */
    ifm_cx (*kinetic)(const ifm_model *md, const ifm_cx *q, const ifm_cx *v);
    /* V(q): potential of the conservative forces (NULL: none). */
    ifm_cx (*potential)(const ifm_model *md, const ifm_cx *q);
    /* φ(q) (m rows) and ψ(q, v) = G(q) v (m rows); NULL when m = 0. */
    void (*phi)(const ifm_model *md, const ifm_cx *q, ifm_cx *out);
    void (*psi)(const ifm_model *md, const ifm_cx *q, const ifm_cx *v, ifm_cx *out);
    /* Nonconservative generalised forces Q(t, q, v) (n; NULL: none); their
     * power Qᵀv is the model's energy input. */
    void (*nonconservative)(const ifm_model *md, double t, const double *q, const double *v,
                            double *Q);
    /* The benchmark's reported quantity at (q, v): up to 6 numbers
     * (positions, then velocities when the benchmark reports them). */
    int nreport;
    void (*report)(const ifm_model *md, const double *q, const double *v, double *out);
    const void *params; /* the model's own data */
};

/* Complex step (Squire & Trapp 1998): f'(x) = Im f(x + i h) / h to round-off. */
#define IFM_CSTEP 1e-30

#define IFM_PI 3.14159265358979323846

/* What the equations of motion need at (q, v), all exact to round-off:
 *   M(q) a = F(t, q, v) + G(q)ᵀ λ,   G(q) a = -c(q, v)
 * F = -Ṁv + ∂T/∂q - ∂V/∂q + Q, c = (∂ψ/∂q) v. */
void ifm_mass(const ifm_model *md, const double *q, double *M);
void ifm_forces(const ifm_model *md, double t, const double *q, const double *v, double *F);
void ifm_jacobian(const ifm_model *md, const double *q, double *G);   /* m x n, from ψ */
void ifm_gamma(const ifm_model *md, const double *q, const double *v, double *c);
void ifm_phi(const ifm_model *md, const double *q, double *phi);
void ifm_psi(const ifm_model *md, const double *q, const double *v, double *psi);
double ifm_energy(const ifm_model *md, const double *q, const double *v);  /* T + V */
double ifm_kinetic(const ifm_model *md, const double *q, const double *v);
double ifm_power(const ifm_model *md, double t, const double *q, const double *v);
/* The acceleration and multipliers from the KKT system (full row rank G).
 * 0, or -1 if the system is singular. lambda may be NULL. */
int ifm_accel(const ifm_model *md, double t, const double *q, const double *v, double *a,
              double *lambda);
/* Newton on φ(q) = 0 over the coordinates other than fixed (-1: none,
 * minimum-norm steps over all), from q; then v projected onto G v = 0
 * keeping v[fixed]. 0, or -1 if Newton did not converge to tol. */
int ifm_project(const ifm_model *md, int fixed, double *q, double *v, double tol);

/* ------------------------------------------------------------ reference runs */
/* A reference on an output grid t_j = j·dt, j = 0..count-1: the reported
 * quantity, the model's residuals and its energy balance. */
typedef struct ifm_series {
    long count;
    int width;       /* reported numbers per sample */
    double dt;
    double *t;       /* count */
    double *y;       /* count x width */
    double *q, *v;   /* count x n (NULL for closed forms) */
    int n;
    double max_phi;     /* max |φ| over the samples */
    double max_energy;  /* max |E - E0 - W| over the samples */
    double max_kinetic; /* max T: the energy scale */
    char how[96];       /* "IDA GGL rtol 1e-12", ... */
    double cpu_s;
} ifm_series;

int ifm_series_init(ifm_series *s, long count, int width, int n, double dt);
void ifm_series_free(ifm_series *s);
/* max_j |a_j - b_j| over the common samples and the first width numbers. */
double ifm_series_maxdiff(const ifm_series *a, const ifm_series *b, int width);

/* SUNDIALS IDA on the GGL form of a model (q' = v - Gᵀμ, M v' = F + Gᵀλ,
 * ψ = 0, φ = 0), dense direct solver, from the consistent (q0, v0); the
 * work of the nonconservative forces integrated alongside. 0, or -1 with
 * why. */
int ifm_ida_run(const ifm_model *md, const double *q0, const double *v0, double rtol,
                double atol, ifm_series *out, char *why, size_t whysize);

/* The same model on one minimal coordinate q[indep] (a model with one
 * degree of freedom): the others from φ = 0 by Newton at every evaluation,
 * the velocities from ψ = 0, the acceleration from the KKT system; the
 * state (s, s', W) integrated by GSL rk8pd at rtol = atol = tol. Also for
 * unconstrained models (m = 0, indep ignored): rk8pd on (q, v, W). */
int ifm_minimal_run(const ifm_model *md, int indep, const double *q0, const double *v0,
                    double tol, ifm_series *out, char *why, size_t whysize);

/* ------------------------------------------------------------ the models */
/* A01: the pendulum in its angle from the vertical, and its closed form. */
extern const ifm_model ifm_pendulum_model;
void ifm_pendulum_state0(double *q0, double *v0);
int ifm_pendulum_exact(ifm_series *out);

/* A02: the N-four-bar reduced to its crank angle (all cranks parallel),
 * and its closed form; B0's position and velocity are reported. */
typedef struct ifm_fourbar_params { int N; } ifm_fourbar_params;
void ifm_fourbar_model(ifm_model *md, const ifm_fourbar_params *p);
void ifm_fourbar_state0(double *q0, double *v0);
int ifm_fourbar_exact(const ifm_fourbar_params *p, ifm_series *out);

/* A03: Andrews' squeezing mechanism as the Test Set for IVP Solvers
 * states it (seven relative angles, six constraint rows), point F reported. */
extern const ifm_model ifm_andrews_model;
void ifm_andrews_state0(double *q0, double *v0);
extern const double ifm_andrews_ref003[7]; /* the test set's y(0.03) */

/* A04: Bricard's mechanism as a chain of five revolute joint angles closed
 * at the sixth joint; P3 reported. thin: rods without cross-section
 * (the pre-2015 description), else the 0.1 m square section. */
typedef struct ifm_bricard_params {
    int thin;  /* 1: rods without cross-section */
    int drop;  /* the closure row left out (0..4; IFM_BRICARD_DROP) */
} ifm_bricard_params;
#define IFM_BRICARD_DROP 4
/* All five closure rows at q (the dropped one included). */
void ifm_bricard_rows(const double *q, double *phi5);
void ifm_bricard_model(ifm_model *md, const ifm_bricard_params *p);
void ifm_bricard_state0(double *q0, double *v0);

/* A05: the stiff flyball governor, (a) in joint coordinates (shaft angle,
 * slider height, two rod angles; no constraints) and (b) in the Cartesian
 * coordinates of the point masses with four constraint rows. s reported. */
extern const ifm_model ifm_flyball_joint_model, ifm_flyball_cart_model;
void ifm_flyball_joint_state0(double *q0, double *v0);
void ifm_flyball_cart_state0(double *q0, double *v0);

#endif
