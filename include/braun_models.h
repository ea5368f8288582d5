/*
 * Built-in models of the paper (Sec. 4) and a pendulum, with their
 * minimal-coordinate equations and exact references.
 *
 * Each model is a braun_system plus the paper's initial state, its
 * minimal-coordinate ODE y' = f(t, y) (y = [θ, θ']) and the map from y to
 * the absolute coordinates (q, v). References are computed in double
 * precision whatever braun_real is.
 */
#ifndef BRAUN_MODELS_H
#define BRAUN_MODELS_H

#include "braun.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BRAUN_MODEL_MAX_N 8

/* Physical parameters shared by the built-in models (SI units). */
typedef struct braun_link_params {
    double l;  /* link length [m] */
    double m;  /* link mass [kg] */
    double g;  /* gravity [m/s^2] */
    /* The same in braun_real, for the callbacks: a float build then does
     * no double arithmetic per call (soft-float on a Cortex-M4F). */
    braun_real rl, rm, rmg;  /* l, m, m·g */
} braun_link_params;

typedef struct braun_builtin {
    const char *name;         /* "slider-crank", "four-bar", "pendulum" */
    const char *description;  /* one line */
    braun_system sys;         /* user points at a static braun_link_params */
    const braun_real *q0;     /* paper's initial state, n entries */
    const braun_real *v0;
    /* Minimal-coordinate equation (Eq. 24; θ'' + (7g/6l)cosθ = 0; pendulum). */
    int minimal_dim;                                  /* 2 */
    const double *minimal_y0;                         /* [θ(0), θ'(0)] */
    void (*minimal_rhs)(double t, const double *y, double *dydt,
                        const braun_link_params *prm);
    /* Closed-form solution y(t) of the minimal equation, or NULL if none. */
    int (*minimal_exact)(double t, double *y, const braun_link_params *prm);
    /* Lift y = [θ, θ'] to absolute coordinates q, v (n each). */
    void (*minimal_to_state)(const double *y, double *q, double *v,
                             const braun_link_params *prm);
    /* Coordinates (ix, iy) of the point whose planar error is the paper's ε
     * (four-bar: joint 3, ε3 of Fig. 7); -1 if none. */
    int point_x, point_y;
} braun_builtin;

/* Look up a built-in model by name; NULL if unknown. */
const braun_builtin *braun_builtin_find(const char *name);
/* The i-th built-in model (NULL past the end), for listing. */
const braun_builtin *braun_builtin_at(int i);

/* Exact reference of a built-in model: closed form where one exists, else the
 * minimal-coordinate equation integrated by classic RK4 with small substeps
 * (sub-step <= ref_h) continuing monotonically in t. */
typedef struct braun_reference {
    const braun_builtin *model;
    double t;       /* time of y */
    double y[4];    /* minimal state */
    double ref_h;   /* substep for integrated references */
} braun_reference;

/* Initialise at t = 0 with the model's minimal y0. ref_h <= 0 selects 1e-4. */
int braun_reference_init(braun_reference *ref, const braun_builtin *model,
                         double ref_h);
/* Absolute coordinates of the reference at time t (t must not decrease
 * between calls for integrated references). q, v: n entries each. */
int braun_reference_eval(braun_reference *ref, double t, double *q, double *v);

/* Pendulum phi'' = -w2·sin(phi), closed form via Jacobi elliptic functions
 * (libration and rotation; separatrix excluded). phi0, dphi0 at t = 0;
 * returns phi(t), dphi(t). */
int braun_pendulum_exact(double w2, double phi0, double dphi0, double t,
                         double *phi, double *dphi);

/* Jacobi elliptic functions sn, cn, dn of (u | k^2 = m), 0 <= m < 1. */
void braun_jacobi_sncndn(double u, double m, double *sn, double *cn,
                         double *dn);
/* Complete and incomplete elliptic integrals of the first kind,
 * K(m) and F(phi | m), 0 <= m < 1. */
double braun_ellip_K(double m);
double braun_ellip_F(double phi, double m);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_MODELS_H */
