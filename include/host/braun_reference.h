/*
 * Exact references of the built-in models (host tier: test oracles, never
 * in the firmware library). Each model of braun_models.h that has one gets
 * its minimal-coordinate equation y' = f(t, y), y = [θ, θ'] (Eq. 24 for the
 * slider-crank; θ'' + (7g/6l)cos θ = 0 for the four-bar, Fig. 6; the
 * pendulum), a closed form where one exists (Jacobi elliptic functions), and
 * the map from y to the model's absolute coordinates. Double precision
 * whatever braun_real is. Also the IVP test set's reference of Andrews'
 * mechanism.
 */
#ifndef BRAUN_REFERENCE_H
#define BRAUN_REFERENCE_H

#include "braun_models.h"

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_andrews_q_ref braun_andrews_q_ref_float
#define braun_ellip_F braun_ellip_F_float
#define braun_ellip_K braun_ellip_K_float
#define braun_jacobi_sncndn braun_jacobi_sncndn_float
#define braun_minimal_find braun_minimal_find_float
#define braun_pendulum_exact braun_pendulum_exact_float
#define braun_reference_eval braun_reference_eval_float
#define braun_reference_init braun_reference_init_float
#define braun_reference_init_minimal braun_reference_init_minimal_float
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Minimal-coordinate equation of a built-in model. */
typedef struct braun_minimal {
    const char *name;                                 /* the model's name */
    int dim;                                          /* 2 */
    const double *y0;                                 /* [θ(0), θ'(0)] */
    void (*rhs)(double t, const double *y, double *dydt, const braun_link_params *prm);
    /* Closed-form solution y(t), or NULL if none. */
    int (*exact)(double t, double *y, const braun_link_params *prm);
    /* Lift y = [θ, θ'] to absolute coordinates q, v (n each). */
    void (*to_state)(const double *y, double *q, double *v, const braun_link_params *prm);
} braun_minimal;

/* The minimal equation of a built-in model (by its name); NULL if none. */
const braun_minimal *braun_minimal_find(const char *name);

/* Exact reference of a built-in model: closed form where one exists, else the
 * minimal-coordinate equation integrated by classic RK4 with small substeps
 * (sub-step <= ref_h) continuing monotonically in t. */
typedef struct braun_reference {
    const braun_builtin *model;
    const braun_minimal *minimal;
    double t;       /* time of y */
    double y[4];    /* minimal state */
    double ref_h;   /* substep for integrated references */
} braun_reference;

/* Initialise at t = 0 with the model's minimal y0. ref_h <= 0 selects 1e-4.
 * BRAUN_ERR_ARGUMENT for a model without a minimal equation. */
int braun_reference_init(braun_reference *ref, const braun_builtin *model,
                         double ref_h);
/* The same with a given minimal equation (e.g. one whose closed form is
 * removed, to compare the integrated reference with it). */
int braun_reference_init_minimal(braun_reference *ref, const braun_builtin *model,
                                 const braun_minimal *minimal, double ref_h);
/* Absolute coordinates of the reference at time t (t must not decrease
 * between calls for integrated references). q, v: n entries each.
 * BRAUN_ERR_TOO_MANY_STEPS when an integrated reference would need more
 * than 1e15 substeps to reach t. */
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

/* Andrews' mechanism: the test set's reference angles at t = 0.03 (PSIDE,
 * rtol = atol = 1e-14). */
#define BRAUN_ANDREWS_T_REF 0.03
extern const double braun_andrews_q_ref[7];

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_REFERENCE_H */
