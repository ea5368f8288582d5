/* The IFToMM problems as braun-iftomm runs them (ifm_problems.c). */
#ifndef IFM_PROBLEMS_H
#define IFM_PROBLEMS_H

#include "ifm.h"

typedef enum ifm_ref_kind {
    IFM_REF_PENDULUM, /* closed form; check: rk8pd on the angle */
    IFM_REF_FOURBAR,  /* closed form; check: rk8pd on the crank angle */
    IFM_REF_ANDREWS,  /* rk8pd on β; check: IDA on the test set's DAE; and its y(0.03) */
    IFM_REF_BRICARD,  /* rk8pd on θ1; check: IDA on the joint-angle DAE */
    IFM_REF_FLYBALL   /* rk8pd on joint coordinates; check: IDA, Cartesian DAE */
} ifm_ref_kind;

typedef struct ifm_problem {
    const char *id;        /* summary.csv's problem: "A01", "A01-10s", ... */
    const char *title;
    const char *scene;     /* a path, or "@/NAME": NAME in the output directory */
    const char *point;     /* the reported point (scene "report" name) */
    int dim;               /* 2 planar, 3 spatial */
    int velocity;          /* the benchmark reports the point's velocity too */
    double T, dt_out;      /* duration and output grid */
    double opensim_s;      /* OpenSim 3.2 CPU time published for this variant; 0: none */
    ifm_ref_kind ref;
    int N;                 /* A02: four-bar windows */
    double h_coarse;       /* the RK4 sweep's largest step (h = dt_out/k) */
    double rtol_loose;     /* the DOPRI5 sweep's loosest rtol */
    double atol_scale;     /* atol = rtol x this (the size of the coordinates) */
    const char *settings_from; /* a long problem runs the settings chosen on this one */
    /* A long run's drift targets (issue 13: A04 over 600 s): max ||Phi_q|| and
     * max |Phi_e| over the reference's largest kinetic energy; its sweep goes on
     * to finer settings until one holds both. 0: none. */
    double drift_pos, drift_energy;
} ifm_problem;

extern const ifm_problem ifm_problems[];
extern const int ifm_nproblems;
const ifm_problem *ifm_problem_find(const char *id);

/* A problem's reference on its grid over [0, T], and an independent check. */
typedef struct ifm_refset {
    ifm_series ref, check;
    double agreement;      /* max |ref - check| over the grid */
    int ivp_checked;       /* A03 at 0.03 s: */
    double ivp_rel;        /* max relative difference of ref's q from the test set's y(0.03) */
} ifm_refset;

int ifm_reference(const ifm_problem *p, double T, ifm_refset *rs, char *why, size_t whysize);
void ifm_refset_free(ifm_refset *rs);

#endif
