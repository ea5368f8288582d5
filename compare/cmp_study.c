/* The study: which runs `make compare` makes, best-of-k timing, the CSV
 * files (docs/compare.md, "Files and columns") and the progress line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cmp.h"
#include "braun_reference.h"
#include "cmp_study.h"
#include "cmp_peer.h"

/* ------------------------------------------------------------ plans */
static const double H_FULL[] = {1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2};
static const double H_QUICK[] = {5e-3, 1e-2, 2e-2, 5e-2};
static const double R_FULL[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
static const double R_REDUCED[] = {1e-4, 1e-6, 1e-8};
static const double R_PROBE[] = {1e-4, 1e-6, 1e-8, 1e-9, 1e-10};
static const double R_PROBE_QUICK[] = {1e-6, 1e-8};
/* Baumgarte gains α = β = c/h: the default c and the sweep. */
#define BG_C_DEFAULT 0.1
static const double BG_SWEEP[] = {0.03, 0.3, 1.0};
static const double BG_FIXED = 10.0; /* α = β = 10 s⁻¹, independent of h */
static const double H_SWEEP[] = {2e-3, 1e-2, 5e-2};
static const double H_SWEEP_QUICK[] = {1e-2};

#define N_OF(a) ((int)(sizeof(a) / sizeof((a)[0])))

typedef struct plan {
    double T[2];
    int nT;
    double dt_out;
    const double *H, *RD, *RI, *HS;
    int nH, nRD, nRI, nHS;
    const double *RP;   /* IDA probe tolerances (first horizon only) */
    int nRP;
    int quick;          /* the quick study */
} plan;

static const double H_HARD[] = {1e-3, 2e-3, 5e-3, 1e-2, 5e-2};

/* Scale a list of step sizes into buf (the reduced grids of fast scenes). */
static const double *scaled(const double *h, int n, double s, double *buf)
{
    for (int i = 0; i < n; i++) buf[i] = h[i] * s;
    return buf;
}

static void make_plan(const char *study, const cmp_target *tg, plan *p)
{
    memset(p, 0, sizeof *p);
    p->dt_out = 0.05;
    if (strcmp(study, "quick") == 0) {
        p->quick = 1;
        p->T[0] = 20;
        p->nT = 1;
        p->H = H_QUICK, p->nH = N_OF(H_QUICK);
        p->RD = R_REDUCED, p->nRD = N_OF(R_REDUCED);
        p->RI = R_REDUCED, p->nRI = N_OF(R_REDUCED);
        p->HS = H_SWEEP_QUICK, p->nHS = N_OF(H_SWEEP_QUICK);
        if (tg->paper) p->RP = R_PROBE_QUICK, p->nRP = N_OF(R_PROBE_QUICK);
    } else if (tg->paper) {
        /* The paper's two mechanisms: 100 s (Figs. 1-4) and 1000 s (Figs. 6-7). */
        p->T[0] = 100;
        p->T[1] = 1000;
        p->nT = 2;
        p->H = H_FULL, p->nH = N_OF(H_FULL);
        p->RD = R_FULL, p->nRD = N_OF(R_FULL);
        p->RI = R_FULL, p->nRI = N_OF(R_FULL);
        p->HS = H_SWEEP, p->nHS = N_OF(H_SWEEP);
        p->RP = R_PROBE, p->nRP = N_OF(R_PROBE);
    } else {
        /* Other targets (the pendulum, scenes): a reduced grid over the
         * target's own horizon and time scale. */
        static double hbuf[N_OF(H_HARD)], sbuf[1];
        p->T[0] = tg->T_reduced;
        p->nT = 1;
        p->dt_out = tg->dt_out;
        p->H = scaled(H_HARD, N_OF(H_HARD), tg->h_scale, hbuf), p->nH = N_OF(H_HARD);
        p->RD = R_REDUCED, p->nRD = N_OF(R_REDUCED);
        p->RI = R_REDUCED, p->nRI = N_OF(R_REDUCED);
        sbuf[0] = 1e-2 * tg->h_scale;
        p->HS = sbuf, p->nHS = 1;
        p->RP = R_PROBE_QUICK, p->nRP = N_OF(R_PROBE_QUICK);
    }
}

/* IDA settings of the main study and of the probe (docs/compare.md). */
typedef struct ida_setting {
    const char *label;
    cmp_ida_opts o;
} ida_setting;

#define ALG_OFF 1e8 /* λ, μ effectively out of the Newton convergence test */

static const ida_setting IDA_MAIN[] = {
    /* What a user gets with the required settings only (λ, μ algebraic and
     * out of the error test) and SUNDIALS' defaults otherwise. */
    {"", {.linsol = CMP_LS_AUTO}},
    /* The best of the probe on the paper's scenes (docs/compare.md). */
    {"tuned", {.alg_atol = ALG_OFF, .max_order = 2}},
};

static const ida_setting IDA_PROBE[] = {
    {"defaults", {.linsol = CMP_LS_DENSE}},
    {"no-suppressalg", {.no_suppress = 1}},
    {"alg-atol=1e8", {.alg_atol = ALG_OFF}},
    {"alg-atol=1e8;max-step=1e-2", {.alg_atol = ALG_OFF, .max_step = 1e-2}},
    {"alg-atol=1e8;max-order=3", {.alg_atol = ALG_OFF, .max_order = 3}},
    {"alg-atol=1e8;max-order=2", {.alg_atol = ALG_OFF, .max_order = 2}},
    {"alg-atol=1e8;cod", {.alg_atol = ALG_OFF, .linsol = CMP_LS_COD}},
    {"alg-atol=1e8;klu", {.alg_atol = ALG_OFF, .linsol = CMP_LS_KLU}},
    {"alg-atol=1e8;reg=1e-10", {.alg_atol = ALG_OFF, .reg = 1e-10}},
    {"alg-atol=1e8;restart", {.alg_atol = ALG_OFF, .restarts = 100, .restart_h0 = 1e-3}},
};

const char *cmp_default_scenes(const char *study)
{
    if (strcmp(study, "quick") == 0) return "slider-crank four-bar";
#ifdef CMP_HAVE_SCENES
    /* The paper's two, then the hard cases at a reduced grid: redundant
     * rows, nonholonomic, rheonomic, energy input, chaotic (two), stiff,
     * spatial: every shipped scene of data/ (the peers run on those they
     * can express). The peers' Andrews is the IFToMM scene a03-andrews
     * (`--scenes a03-andrews`, about 100 s): in the default study it took
     * it from 13 min 51 s to 17 min 5 s on two cores (2026-12-02). */
    return "slider-crank four-bar pendulum parallelogram-redundant sleigh driven-crank "
           "damped-motor double-pendulum chain-5 andrews spatial-arm";
#else
    return "slider-crank four-bar pendulum";
#endif
}

/* ------------------------------------------------------------ jobs */
/* What a step of the plan does. */
typedef enum job_kind {
    JOB_RUN = 0,       /* integrate and measure: a row of runs.csv or ida_probe.csv */
    JOB_UNSUPPORTED,   /* a peer that cannot express the scene: its row says why */
    JOB_COST           /* cost per step of braun, projection and MuJoCo (step_cost.csv) */
} job_kind;

typedef struct job {
    char scene[64];
    cmp_spec spec;
    job_kind kind;
    int history;   /* write its error history */
    int probe;     /* IDA probe (ida_probe.csv), timed once */
    int once;      /* timed once: a sweep cell, or a run long enough (REPS_MAX_STEPS) */
    int trace;     /* write the observable point at every sample of its trace windows */
    char why[128]; /* JOB_UNSUPPORTED: the peer's reason */
} job;

typedef struct joblist {
    job *v;
    int n, cap;
} joblist;

/* Fixed-step runs of at least this many steps are timed once: their CPU
 * time (seconds) is long against the clock's noise, and repeating them
 * would cost more than the rest of the study. */
#define REPS_MAX_STEPS 2e5

static job *add(joblist *l, const char *scene, const plan *p, double T, cmp_method_id m,
                int integrator)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 256;
        job *v = realloc(l->v, (size_t)cap * sizeof *v);
        if (!v) return NULL;
        l->v = v;
        l->cap = cap;
    }
    job *j = &l->v[l->n++];
    memset(j, 0, sizeof *j);
    snprintf(j->scene, sizeof j->scene, "%s", scene);
    j->spec.method = m;
    j->spec.integrator = integrator;
    j->spec.T = T;
    j->spec.dt_out = p->dt_out;
    return j;
}

/* Histories at h = 1e-2 (Figs. 3, 7) and 5e-2 (Fig. 2), scaled with the target. */
static double hist_scale = 1.0;
static int is_hist_h(double h)
{
    return fabs(h - 1e-2 * hist_scale) < 1e-12 * hist_scale ||
           fabs(h - 5e-2 * hist_scale) < 1e-12 * hist_scale;
}

/* The paper's Fig. 6: traces of the observable point (x3 of the four-bar)
 * of the paper's step h = 1e-2 and of every peer run, on the paper's scenes
 * at the study's longest horizon (trace.csv). */
static double trace_T = 0;
static int trace_scene = 0;

static job *fixed_step(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                       int integ, double h, double alpha, const char *variant, int hist)
{
    job *j = add(l, sc, p, T, m, integ);
    if (!j) return NULL;
    j->spec.h = h;
    j->spec.alpha = j->spec.beta = alpha;
    snprintf(j->spec.variant, sizeof j->spec.variant, "%s", variant);
    j->history = hist && is_hist_h(h);
    j->once = T / h >= REPS_MAX_STEPS;
    j->trace = trace_scene && T == trace_T && hist && fabs(h - 1e-2) < 1e-12;
    return j;
}

static job *tolerance(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                      int integ, double rtol, const ida_setting *s, int probe)
{
    job *j = add(l, sc, p, T, m, integ);
    if (!j) return NULL;
    j->spec.rtol = j->spec.atol = rtol;
    if (s) {
        j->spec.ida = s->o;
        snprintf(j->spec.variant, sizeof j->spec.variant, "%s", s->label);
    }
    j->probe = probe;
    /* Histories of the adaptive methods at one tolerance (Figs. 3, 7). */
    j->history = !probe && fabs(rtol - 1e-8) < 1e-20;
    return j;
}

/* ------------------------------------------------------------ peers */
/* MuJoCo's settings (docs/compare.md, "Peers"). Equalities are soft in
 * MuJoCo: a constraint row is a spring-damper of time constant solref[0]
 * and damping ratio ζ = solref[1] whose force is scaled by the impedance d
 * of solimp (the fraction of the constraint force applied; 1 - d is
 * regularisation). The pilot (the sweep below on the paper's scenes, first
 * horizon, and by hand) found: d decides (0.9 -> 0.9999, MuJoCo's ceiling,
 * cuts the four-bar's error 10-50x), the stiffest time constant 2h is best,
 * the less damping the better for RK4 down to ζ = 0.25 (ζ = 0.1 blows up
 * within 0.1 s) while semi-implicit and implicit Euler blow up at
 * ζ = 0.25 and keep ζ = 1, and the solver's tolerance and iterations do not
 * matter at all (with equalities only, Newton solves the quadratic problem
 * in one iteration). The main series use the best of each integrator. */
#define MJ_TIGHT_IMP {0.9999, 0.9999, 0.001}
static const cmp_peer_opts MJ_BEST = {.timeconst = 0, .dampratio = 1, .solimp = MJ_TIGHT_IMP};
static const cmp_peer_opts MJ_BEST_RK4 = {.timeconst = 0, .dampratio = 0.25, .solimp = MJ_TIGHT_IMP};

/* The main series' settings of a MuJoCo integrator. */
static const cmp_peer_opts *mj_best(int integrator)
{
    return integrator == CMP_MJ_RK4 ? &MJ_BEST_RK4 : &MJ_BEST;
}

typedef struct peer_setting {
    const char *label;
    int integrator;
    double tc_h;        /* > 0: solref's time constant is tc_h·h */
    cmp_peer_opts o;
} peer_setting;

/* MuJoCo's own defaults (solref 0.02 1, solimp 0.9 0.95): what a new user
 * runs. A series over the step grid, with RK4. */
static const peer_setting MJ_DEFAULTS = {"defaults", CMP_MJ_RK4, 0, {.timeconst = -1}};

/* The softness sweep: one setting changed from RK4's main series (solref
 * 2h, ζ = 0.25, d = 0.9999) at a time (RK4, the study's sweep steps, first
 * horizon, timed once). */
#define Z 0.25
static const peer_setting MJ_SWEEP[] = {
    {"solimp=0.9", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = Z}},
    {"solimp=0.99", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = Z, .solimp = {0.99, 0.999, 0.001}}},
    {"tc=0.02", CMP_MJ_RK4, 0, {.timeconst = 0.02, .dampratio = Z, .solimp = MJ_TIGHT_IMP}},
    {"tc=5h", CMP_MJ_RK4, 5, {.dampratio = Z, .solimp = MJ_TIGHT_IMP}},
    {"tc=20h", CMP_MJ_RK4, 20, {.dampratio = Z, .solimp = MJ_TIGHT_IMP}},
    {"zeta=0.1", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = 0.1, .solimp = MJ_TIGHT_IMP}},
    {"zeta=0.5", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = 0.5, .solimp = MJ_TIGHT_IMP}},
    {"zeta=1", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = 1, .solimp = MJ_TIGHT_IMP}},
    {"tol=1e-12", CMP_MJ_RK4, 0,
     {.timeconst = 0, .dampratio = Z, .solimp = MJ_TIGHT_IMP, .tolerance = 1e-12, .iterations = 1000}},
    {"pgs", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = Z, .solimp = MJ_TIGHT_IMP, .solver = 2}},
    {"cg", CMP_MJ_RK4, 0, {.timeconst = 0, .dampratio = Z, .solimp = MJ_TIGHT_IMP, .solver = 1}},
};
#undef Z

/* Simbody: the error-controlled integrators at accuracy rtol with the
 * constraint tolerance Simbody defaults to (= accuracy), RK-Merson at a
 * fixed step (accuracy SB_FIXED_ACCURACY: the constraint tolerance of its
 * projections), and a constraint-tolerance sweep on the first horizon. */
static const int SB_ADAPTIVE[] = {CMP_SB_RKM, CMP_SB_RKF, CMP_SB_RK3, CMP_SB_CPODES};
#define SB_FIXED_ACCURACY 1e-8
static const double SB_SWEEP_RTOL[] = {1e-4, 1e-6, 1e-8};
static const double SB_SWEEP_CTOL[] = {1e-10, 1e-3};

/* A fixed-step run of a peer with settings o (tc_h > 0: solref's time
 * constant tc_h·h). Every peer run of the longest horizon is traced: the
 * report picks each peer's best for Fig. 6 afterwards. */
static job *peer_fixed(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                       int integ, double h, const char *variant, const cmp_peer_opts *o,
                       double tc_h, int hist)
{
    job *j = fixed_step(l, sc, p, T, m, integ, h, 0, variant, hist);
    if (!j) return NULL;
    j->spec.peer = *o;
    if (tc_h > 0) j->spec.peer.timeconst = tc_h * h;
    j->trace = trace_scene && T == trace_T;
    return j;
}

/* One row that says why a peer does not run on a scene. */
static int unsupported(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                       const char *why)
{
    job *j = add(l, sc, p, T, m, m == CMP_MUJOCO ? CMP_MJ_RK4 : CMP_SB_RKM);
    if (!j) return -1;
    j->kind = JOB_UNSUPPORTED;
    snprintf(j->why, sizeof j->why, "%.127s", why);
    return 0;
}

static int plan_mujoco(joblist *l, const cmp_target *tg, const plan *p, double T, int first)
{
    const char *sc = tg->name;
    char why[256];
    if (!cmp_mujoco_version()) {
        /* Not built: one run, which records NOT_BUILT. */
        return add(l, sc, p, T, CMP_MUJOCO, CMP_MJ_RK4) ? 0 : -1;
    }
    if (!cmp_mujoco_supports(tg, why, sizeof why)) return unsupported(l, sc, p, T, CMP_MUJOCO, why);
    static const int integs[] = {CMP_MJ_EULER, CMP_MJ_RK4, CMP_MJ_IMPLICIT};
    int st = 0;
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < p->nH; i++)
            st |= !peer_fixed(l, sc, p, T, CMP_MUJOCO, integs[k], p->H[i], "", mj_best(integs[k]),
                              0, integs[k] == CMP_MJ_RK4);
    /* MuJoCo's defaults on the first horizon only: one horizon shows what
     * a new user gets (the long one costs as much as the main RK4 series). */
    for (int i = 0; first && i < p->nH; i++)
        st |= !peer_fixed(l, sc, p, T, CMP_MUJOCO, MJ_DEFAULTS.integrator, p->H[i],
                          MJ_DEFAULTS.label, &MJ_DEFAULTS.o, 0, 0);
    if (first)
        for (int i = 0; i < p->nHS; i++)
            for (int s = 0; s < N_OF(MJ_SWEEP); s++) {
                job *j = peer_fixed(l, sc, p, T, CMP_MUJOCO, MJ_SWEEP[s].integrator, p->HS[i],
                                    MJ_SWEEP[s].label, &MJ_SWEEP[s].o, MJ_SWEEP[s].tc_h, 0);
                if (!j) return -1;
                j->once = 1;
            }
    return st ? -1 : 0;
}

/* Every Simbody run is timed once: its step costs about 10 times braun's
 * (174 us per RK-Merson step on the four-bar), so a run on the paper's
 * scenes takes 1-7 s of CPU time, long against the clock's noise, and three
 * repetitions made the study exceed its 15 minutes on two cores. */
/* To keep the study within 15 minutes on two cores, RK3 runs only in the
 * first horizon's constraint-tolerance sweep below (in the study of
 * 2026-12-02 it was not Simbody's best setting on either paper scene, and
 * its main series cost 222 s of CPU on their 100 s horizons and 175 s on the
 * slider-crank's 1000 s), and a long horizon (the paper scenes' 1000 s)
 * leaves out the fixed steps below 5e-3 (1e-3 is 10^6 Simbody steps). */
/* The accuracies of RK-Merson and RK-Feldberg (with Simbody's own
 * projection rule) on a long horizon: the loosest and the tightest, 1e-4
 * and 1e-10. At 1000 s every one of them folds the paper's linkages or
 * stops (studies of 2026-12-02: trajectory error 3.46 on the four-bar,
 * 3.9-7.3 on the slider-crank, at each accuracy from 1e-3 to 1e-10; RK-
 * Merson at 1e-10 stops on the four-bar), at 5-70 s of CPU each; 1e-6 and
 * 1e-8 cost 188 s of CPU and took make compare to 14 min 48 s. */
static int sb_long_rtol(double rtol)
{
    static const double keep[] = {1e-4, 1e-10};
    for (int i = 0; i < N_OF(keep); i++)
        if (fabs(rtol - keep[i]) <= 1e-6 * keep[i]) return 1;
    return 0;
}

static int plan_simbody(joblist *l, const cmp_target *tg, const plan *p, double T, int first,
                        int long_horizon)
{
    const char *sc = tg->name;
    char why[256];
    if (!cmp_simbody_version()) return add(l, sc, p, T, CMP_SIMBODY, CMP_SB_RKM) ? 0 : -1;
    if (!cmp_simbody_supports(tg, why, sizeof why))
        return unsupported(l, sc, p, T, CMP_SIMBODY, why);
    for (int k = 0; k < N_OF(SB_ADAPTIVE); k++)
        for (int i = 0; i < p->nRD; i++) {
            if (SB_ADAPTIVE[k] == CMP_SB_RK3) continue; /* the sweep's only */
            /* the long horizon: the explicit pair at 1e-4 and 1e-10 only */
            if (long_horizon && SB_ADAPTIVE[k] != CMP_SB_CPODES && !sb_long_rtol(p->RD[i]))
                continue;
            job *j = tolerance(l, sc, p, T, CMP_SIMBODY, SB_ADAPTIVE[k], p->RD[i], NULL, 0);
            if (!j) return -1;
            j->trace = trace_scene && T == trace_T;
            j->once = 1;
        }
    for (int i = 0; i < p->nH; i++) {
        if (long_horizon && p->H[i] < 5e-3) continue;
        /* A small-step scene (Andrews, h_scale 1e-3) likewise: at 5e-6 its
         * error is already the reference's own (a03: 7.3e-12 against
         * 4.8e-12), and 1e-6 costs 8.5 s. */
        if (tg->h_scale < 1 && p->H[i] < 5e-3 * tg->h_scale) continue;
        cmp_peer_opts o;
        memset(&o, 0, sizeof o);
        job *j = peer_fixed(l, sc, p, T, CMP_SIMBODY, CMP_SB_RKM_FIXED, p->H[i], "", &o, 0, 1);
        if (!j) return -1;
        j->once = 1;
        j->spec.rtol = j->spec.atol = SB_FIXED_ACCURACY;
    }
    /* Projection after every step (setProjectEveryStep): the only Simbody
     * setting that kept the paper's linkages on their branch in the hand
     * measurements of docs/compare.md ("Simbody"), at tight accuracies, so
     * on the paper scenes CPodes and RK-Merson run it there too (once per
     * horizon at 1e-10 and 1e-9 on the long one: a run takes 30 s and
     * more). */
    if (tg->paper && !p->quick) {
        static const double every_rtol[] = {1e-8, 1e-9, 1e-10};
        static const int every_integ[] = {CMP_SB_CPODES, CMP_SB_RKM};
        for (int k = 0; k < N_OF(every_integ); k++)
            for (int i = 0; i < N_OF(every_rtol); i++) {
                if (long_horizon && every_rtol[i] != (every_integ[k] == CMP_SB_CPODES ? 1e-10 : 1e-9))
                    continue;
                job *j = tolerance(l, sc, p, T, CMP_SIMBODY, every_integ[k], every_rtol[i], NULL, 0);
                if (!j) return -1;
                snprintf(j->spec.variant, sizeof j->spec.variant, "every-step");
                j->trace = trace_scene && T == trace_T;
                j->once = 1;
            }
    }
    /* The loose constraint tolerance left the paper's linkages on the
     * folded branch in every run at accuracies 1e-4 and 1e-6 (make compare
     * of 2026-12-02: 16 of 16), so its cell at 1e-8 only cost time (RK3
     * 58 s on the four-bar over 100 s): not run. */
    if (first)
        for (int c = 0; c < N_OF(SB_SWEEP_CTOL); c++)
            for (int k = 0; k < N_OF(SB_ADAPTIVE); k++)
                for (int i = 0; i < N_OF(SB_SWEEP_RTOL); i++) {
                    if (SB_SWEEP_CTOL[c] > 1e-6 && SB_SWEEP_RTOL[i] < 1e-7) continue;
                    job *j = tolerance(l, sc, p, T, CMP_SIMBODY, SB_ADAPTIVE[k], SB_SWEEP_RTOL[i],
                                       NULL, 0);
                    if (!j) return -1;
                    j->spec.peer.ctol = SB_SWEEP_CTOL[c];
                    snprintf(j->spec.variant, sizeof j->spec.variant, "ctol=%g", SB_SWEEP_CTOL[c]);
                    j->once = 1;
                    j->history = 0;
                }
    return 0;
}

static int plan_jobs(joblist *l, const char *study, const cmp_target *tg, const int *methods,
                     int with_probe)
{
    plan p;
    const char *sc = tg->name;
    make_plan(study, tg, &p);
    trace_T = p.T[p.nT - 1];
    trace_scene = tg->paper;
    int st = 0;
    for (int it = 0; it < p.nT; it++) {
        const double T = p.T[it];
        for (int mi = 0; mi < CMP_METHOD_COUNT; mi++) {
            if (!methods[mi]) continue;
            const cmp_method_id m = (cmp_method_id)mi;
            if (m == CMP_BRAUN || m == CMP_BRAUN_NOENERGY) {
                static const int integs[] = {BRAUN_EULER, BRAUN_HEUN, BRAUN_RK4};
                for (int k = 0; k < 3; k++)
                    for (int i = 0; i < p.nH; i++)
                        st |= !fixed_step(l, sc, &p, T, m, integs[k], p.H[i], 0, "",
                                          integs[k] == BRAUN_RK4);
                for (int i = 0; i < p.nRD; i++)
                    st |= !tolerance(l, sc, &p, T, m, BRAUN_DOPRI5, p.RD[i], NULL, 0);
            } else if (m == CMP_BAUMGARTE) {
                char v[32];
                for (int i = 0; i < p.nH; i++)
                    st |= !fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.H[i], BG_C_DEFAULT / p.H[i],
                                      "", 1);
                for (int i = 0; i < p.nHS; i++) {
                    for (int k = 0; k < N_OF(BG_SWEEP); k++) {
                        snprintf(v, sizeof v, "ab=%g/h", BG_SWEEP[k]);
                        st |= !fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.HS[i],
                                          BG_SWEEP[k] / p.HS[i], v, 0);
                    }
                    snprintf(v, sizeof v, "ab=%g", BG_FIXED);
                    st |= !fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.HS[i], BG_FIXED, v, 0);
                }
            } else if (m == CMP_ODE_RK4) {
                if (!tg->builtin || !braun_minimal_find(tg->builtin->name)->rhs) continue;
                for (int i = 0; i < p.nH; i++)
                    st |= !fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.H[i], 0, "", 1);
            } else if (m == CMP_IDA_GGL) {
                for (int s = 0; s < N_OF(IDA_MAIN); s++)
                    for (int i = 0; i < p.nRI; i++)
                        st |= !tolerance(l, sc, &p, T, m, -1, p.RI[i], &IDA_MAIN[s], 0);
                if (with_probe && it == 0)
                    for (int s = 0; s < N_OF(IDA_PROBE); s++)
                        for (int i = 0; i < p.nRP; i++)
                            st |= !tolerance(l, sc, &p, T, m, -1, p.RP[i], &IDA_PROBE[s], 1);
            } else if (m == CMP_IDA_INDEX1) {
                for (int i = 0; i < p.nRI; i++)
                    st |= !tolerance(l, sc, &p, T, m, -1, p.RI[i], &IDA_MAIN[0], 0);
            } else if (m == CMP_PROJECTION) {
                /* Positions and velocities, and onto the energy level too. */
                static const char *const variants[] = {"", "energy"};
                for (int k = 0; k < 2; k++)
                    for (int i = 0; i < p.nH; i++)
                        st |= !fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.H[i], 0, variants[k], 1);
            } else if (m == CMP_MUJOCO) {
                st |= plan_mujoco(l, tg, &p, T, it == 0 && with_probe);
            } else if (m == CMP_SIMBODY) {
                /* The quick study leaves out the constraint-tolerance
                 * sweep (24 Simbody runs per scene, half the study's time). */
                st |= plan_simbody(l, tg, &p, T, it == 0 && with_probe && strcmp(study, "quick"),
                                   it > 0);
            }
        }
        /* The cost of one step of braun, projection and MuJoCo on the
         * same mechanism, in one process (the paper's scenes, first
         * horizon; claim (b) of issue 14). */
        if (tg->paper && it == 0 && methods[CMP_BRAUN]) {
            job *j = add(l, sc, &p, T, CMP_BRAUN, BRAUN_RK4);
            if (!j) return -1;
            j->kind = JOB_COST;
            j->spec.h = 1e-2;
        }
    }
    return st;
}

/* ------------------------------------------------------------ CSV */
const char *const cmp_runs_header =
    "scene,T,method,integrator,variant,h,rtol,atol,alpha,beta,status,t_reached,"
    "cpu_s,cpu_s_max,reps,steps,rejected,rhs_evals,jac_evals,lin_setups,lin_solves,"
    "err_test_fails,conv_fails,restarts,pos_max,pos_final,vel_max,vel_final,"
    "energy_max,energy_final,traj_max,traj_final,point_max,point_final,samples,"
    "sigma_end,pos_median,energy_median,iterations,reference,detail";

static const char *integrator_name(int integ)
{
    return cmp_integrator_name(integ);
}

/* A free-text field without the CSV separator or quotes. */
static void clean(char *s)
{
    for (; *s; s++)
        if (*s == ',' || *s == '"' || *s == '\n' || *s == '\r') *s = ';';
}

/* A run that reached T with its constraints broken by more than this (in
 * the rows' units: metres and radians for the study's mechanisms, all of
 * about 1 m) did not simulate the mechanism. Simbody's fixed-step
 * slider-crank ended "ok" with ‖Φ_q‖ of 26–334 m, counted as having
 * reached T and plotted as valid points; it is FLEW_APART now, a failure
 * like a solver's own. */
#define CMP_APART 0.1

static int flew_apart(const cmp_outcome *o, const cmp_metrics *mt)
{
    return !o->status && mt->pos_max > CMP_APART;
}

/* The status a row, its progress line and a cross-check print: one word. */
static const char *run_status(const cmp_outcome *o, const cmp_metrics *mt)
{
    return o->status ? o->status_name : flew_apart(o, mt) ? "FLEW_APART" : "ok";
}

static void write_row(FILE *f, const job *j, const cmp_outcome *o, double cpu_min,
                      double cpu_max, int reps, const cmp_metrics *mt, double sigma,
                      const char *ref)
{
    const cmp_spec *s = &j->spec;
    char detail[sizeof o->detail];
    if (flew_apart(o, mt) && !o->detail[0])
        snprintf(detail, sizeof detail, "reached T with max |Phi_q| %.3g above %g", mt->pos_max,
                 CMP_APART);
    else snprintf(detail, sizeof detail, "%s", o->detail);
    clean(detail);
    const int fixed = s->h > 0;
    fprintf(f, "%s,%g,%s,%s,%s,", j->scene, s->T, cmp_method_name(s->method),
            integrator_name(s->integrator), s->variant[0] ? s->variant : "-");
    if (fixed) fprintf(f, "%g,nan,nan,", s->h);
    else fprintf(f, "nan,%g,%g,", s->rtol, s->atol);
    if (s->method == CMP_BAUMGARTE) fprintf(f, "%.6g,%.6g,", s->alpha, s->beta);
    else fprintf(f, "nan,nan,");
    fprintf(f, "%s,%.10g,%.6g,%.6g,%d,", run_status(o, mt),
            o->t_reached, cpu_min, cpu_max, reps);
    const cmp_counts *k = &o->counts;
    fprintf(f, "%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,", k->steps, k->rejected, k->rhs_evals,
            k->jac_evals, k->lin_setups, k->lin_solves, k->err_fails, k->conv_fails,
            k->restarts);
    fprintf(f, "%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%ld,%.3e,%.6e,%.6e,%ld,%s,%s\n",
            mt->pos_max, mt->pos_final, mt->vel_max, mt->vel_final, mt->energy_max,
            mt->energy_final, mt->traj_max, mt->traj_final, mt->point_max, mt->point_final,
            mt->samples, sigma, mt->pos_median, mt->energy_median, k->iterations, ref, detail);
}

/* ------------------------------------------------------------ histories */
/* Bins of a history: fine enough for Fig. 2 over 100 s (0.05 s), coarse
 * enough over 1000 s (2.5 s, more than a period of the paper's mechanisms)
 * that the plotted maxima are an envelope rather than a blur. */
#define HIST_BINS 2000
#define HIST_BINS_LONG 400

typedef struct hist {
    double T;
    long nb;
    double *t, *pos, *vel, *energy, *traj, *point, *obs, *obs_ref;
    unsigned char *used;
} hist;

static int hist_init(hist *h, double T, double dt_out)
{
    memset(h, 0, sizeof *h);
    h->T = T;
    /* As many bins as grid times at most (a run that stopped early keeps
     * the bin width of a complete one). */
    const long bins = T > 200 ? HIST_BINS_LONG : HIST_BINS;
    const long grid = (long)floor(T / dt_out + 0.5) + 1;
    h->nb = grid < bins ? grid : bins;
    if (h->nb < 1) h->nb = 1;
    h->t = calloc((size_t)h->nb * 8, sizeof(double));
    h->used = calloc((size_t)h->nb, 1);
    if (!h->t || !h->used) return -1;
    h->pos = h->t + h->nb;
    h->vel = h->pos + h->nb;
    h->energy = h->vel + h->nb;
    h->traj = h->energy + h->nb;
    h->point = h->traj + h->nb;
    h->obs = h->point + h->nb;
    h->obs_ref = h->obs + h->nb;
    return 0;
}

static void hist_free(hist *h)
{
    free(h->t);
    free(h->used);
}

static double maxnan(double a, double b)
{
    return isnan(a) || isnan(b) ? NAN : (a > b ? a : b);
}

/* Each bin keeps the maximum of every error over its samples (the envelope
 * a log plot shows) and the last sample's observable (Fig. 2). */
static void hist_sample(const cmp_sample_err *e, void *user)
{
    hist *h = user;
    long b = (long)floor(e->t / h->T * (double)h->nb);
    if (b >= h->nb) b = h->nb - 1;
    if (b < 0) b = 0;
    if (!h->used[b]) {
        h->used[b] = 1;
        h->pos[b] = e->pos;
        h->vel[b] = e->vel;
        h->energy[b] = e->energy;
        h->traj[b] = e->traj;
        h->point[b] = e->point;
    } else {
        h->pos[b] = maxnan(h->pos[b], e->pos);
        h->vel[b] = maxnan(h->vel[b], e->vel);
        h->energy[b] = maxnan(h->energy[b], e->energy);
        h->traj[b] = maxnan(h->traj[b], e->traj);
        h->point[b] = maxnan(h->point[b], e->point);
    }
    h->t[b] = e->t;
    h->obs[b] = e->obs;
    h->obs_ref[b] = e->obs_ref;
}

const char *const cmp_history_header =
    "scene,T,method,integrator,variant,h,rtol,t,pos,vel,energy,traj,point,obs,obs_ref";

static void hist_write(FILE *f, const hist *h, const job *j)
{
    const cmp_spec *s = &j->spec;
    for (long b = 0; b < h->nb; b++) {
        if (!h->used[b]) continue;
        fprintf(f, "%s,%g,%s,%s,%s,", j->scene, s->T, cmp_method_name(s->method),
                integrator_name(s->integrator), s->variant[0] ? s->variant : "-");
        if (s->h > 0) fprintf(f, "%g,nan,", s->h);
        else fprintf(f, "nan,%g,", s->rtol);
        fprintf(f, "%.6f,%.4e,%.4e,%.4e,%.4e,%.4e,%.10g,%.10g\n", h->t[b], h->pos[b],
                h->vel[b], h->energy[b], h->traj[b], h->point[b], h->obs[b], h->obs_ref[b]);
    }
}

const char *const cmp_singular_header =
    "scene,theta_star,delta,sigma_ratio,lambda_max,force_max";

/* ------------------------------------------------------------ references */
/* rk8pd's tolerance for the references it provides (the closed form wins
 * where there is one). */
#define REF_TOL 1e-13

const char *const cmp_references_header =
    "scene,T,reference,tol,compared_with,tol2,max_q_diff,final_q_diff,max_point_diff,role,note";

/* The projection reference's step and table spacing for a target (scaled
 * like its grid): RK4's error at 2.5e-5 is far below any method's at the
 * grid's smallest step 1e-3 (order 4: (1e-3/2.5e-5)^4 = 2.6e6). */
static double proj_ref_h(const cmp_target *tg)
{
    return 2.5e-5 * tg->h_scale;
}

static double proj_ref_dt(const cmp_target *tg)
{
    return 1e-3 * tg->h_scale;
}

/* What a reference knows of its own error: the difference to the same
 * reference at a looser setting (twice the step, ten times the tolerance;
 * role "own-error" in references.csv). It bounds the error of the looser
 * one, hence of the reference: below it a method's error measures the
 * reference (the report's "floor"). NaN: no estimate. */
typedef struct ref_info {
    double floor_traj, floor_point;
} ref_info;

/* A reference against another, as a metric: max over the grid of
 * ||q_a - q_b||, written as one row of references.csv. */
static void reference_pair(FILE *f, const cmp_target *tg, double T, double dt,
                           const char *name_a, double tol_a, cmp_ref *a, const char *name_b,
                           double tol_b, cmp_ref *b, const char *role, ref_info *ri)
{
    const int n = tg->sys.n;
    double *w = malloc(4 * (size_t)n * sizeof(double));
    if (!a || !b || !w) {
        free(w);
        return;
    }
    double mx = 0, last = 0, pmx = 0;
    const long count = (long)floor(T / dt + 0.5);
    int ok = 1;
    for (long j = 0; j <= count && ok; j++) {
        const double t = (double)j * dt;
        ok = cmp_ref_eval(a, t, w, w + n) == 0 && cmp_ref_eval(b, t, w + 2 * n, w + 3 * n) == 0;
        double s = 0;
        for (int i = 0; i < n; i++) s += (w[i] - w[2 * n + i]) * (w[i] - w[2 * n + i]);
        last = sqrt(s);
        if (last > mx) mx = last;
        if (tg->has_point) {
            double pa[2], pb[2];
            tg->point(tg, w, pa);
            tg->point(tg, w + 2 * n, pb);
            double dd = hypot(pa[0] - pb[0], pa[1] - pb[1]);
            if (dd > pmx) pmx = dd;
        }
    }
    if (!ok) mx = last = pmx = NAN;
    fprintf(f, "%s,%g,%s,%g,%s,%g,%.6e,%.6e,%.6e,%s,-\n", tg->name, T, name_a, tol_a, name_b,
            tol_b, mx, last, tg->has_point ? pmx : NAN, role);
    fflush(f);
    if (ri && !strcmp(role, "own-error")) {
        ri->floor_traj = mx;
        ri->floor_point = tg->has_point ? pmx : NAN;
    }
    free(w);
}

/* Compare two references on the grid: the estimate of the reference's own
 * error printed in the report. */
static void reference_check(FILE *f, const cmp_target *tg, double T, double dt,
                            cmp_ref_kind ka, double ta, cmp_ref_kind kb, double tb,
                            const char *role, ref_info *ri)
{
    cmp_ref *a = cmp_ref_new(tg, ka, ta), *b = cmp_ref_new(tg, kb, tb);
    reference_pair(f, tg, T, dt, cmp_ref_kind_name(ka), ka == CMP_REF_RK8PD ? ta : NAN, a,
                   cmp_ref_kind_name(kb), kb == CMP_REF_RK8PD ? tb : NAN, b, role, ri);
    cmp_ref_free(a);
    cmp_ref_free(b);
}

/* The reference against an independent method up to where that got: IDA
 * GGL at rtol 1e-10 on the harness's own DAE, or RK4 + projection at the
 * projection reference's step (both on the system's callbacks). */
static void cross_check(FILE *rf, const cmp_target *tg, double T, double dt, cmp_ref *ref,
                        const char *name, double tol, cmp_method_id method)
{
    cmp_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.method = method;
    sp.T = T;
    sp.dt_out = dt;
    if (method == CMP_IDA_GGL) {
        sp.integrator = -1;
        sp.rtol = sp.atol = 1e-10;
        sp.ida.alg_atol = ALG_OFF;
    } else {
        sp.integrator = BRAUN_RK4;
        sp.h = proj_ref_h(tg);
    }
    cmp_traj tr;
    cmp_outcome out;
    if (!ref || cmp_traj_init(&tr, tg->sys.n, 1024)) return;
    cmp_run(tg, &sp, &tr, &out);
    cmp_metrics mt;
    cmp_ref_restart(ref);
    cmp_metrics_compute(tg, &tr, ref, &mt, NULL, NULL);
    cmp_ref_restart(ref);
    char detail[sizeof out.detail];
    snprintf(detail, sizeof detail, "%s", out.detail);
    clean(detail);
    fprintf(rf, "%s,%g,%s,%g,%s,%g,%.6e,%.6e,%.6e,cross-check,%s up to t = %g%s%s\n", tg->name,
            T, name, tol, method == CMP_IDA_GGL ? "ida-ggl" : "projection-rk4-fine",
            method == CMP_IDA_GGL ? 1e-10 : sp.h, mt.traj_max, mt.traj_final, mt.point_max,
            run_status(&out, &mt), out.t_reached, out.status ? " " : "",
            out.status ? detail : "");
    cmp_traj_free(&tr);
}

static void cross_ida(FILE *rf, const cmp_target *tg, double T, double dt, cmp_ref *ref,
                      const char *name, double tol)
{
    cross_check(rf, tg, T, dt, ref, name, tol, CMP_IDA_GGL);
}

/* The reference of a target and horizon, and the estimates of its own error
 * (docs/compare.md, "References"): rows of references.csv, the floor in ri. */
static cmp_ref *make_reference(const cmp_target *tg, cmp_ref_kind kind, double T, double dt,
                               FILE *rf, ref_info *ri)
{
    cmp_ref *ref = NULL;
    ri->floor_traj = ri->floor_point = NAN;
    if (kind == CMP_REF_CLOSED || kind == CMP_REF_RK8PD) {
        ref = cmp_ref_new(tg, kind, REF_TOL);
        if (kind == CMP_REF_CLOSED) {
            /* The closed form is exact up to its evaluation: its own error is
             * the difference to a second evaluation (GSL's Jacobi elliptic
             * functions); rk8pd at 1e-12 and 1e-13 converge to it. */
            reference_check(rf, tg, T, dt, CMP_REF_CLOSED, 0, CMP_REF_CLOSED_GSL, 0, "own-error",
                            ri);
            reference_check(rf, tg, T, dt, CMP_REF_CLOSED, 0, CMP_REF_RK8PD, 1e-12, "cross-check",
                            NULL);
            reference_check(rf, tg, T, dt, CMP_REF_CLOSED, 0, CMP_REF_RK8PD, 1e-13, "cross-check",
                            NULL);
            reference_check(rf, tg, T, dt, CMP_REF_RK8PD, 1e-12, CMP_REF_RK8PD, 1e-13,
                            "cross-check", NULL);
        } else {
            reference_check(rf, tg, T, dt, CMP_REF_RK8PD, 1e-12, CMP_REF_RK8PD, 1e-13,
                            "own-error", ri);
        }
        if (tg->minimal && ref) {
            /* The harness's own minimal equation against the scene's DAE:
             * IDA and RK4 + projection, both on the system's callbacks. */
            if (cmp_ref_tabulate(ref, dt, T) == 0) {
                cross_ida(rf, tg, T, dt, ref, "gsl-rk8pd", REF_TOL);
                cross_check(rf, tg, T, dt, ref, "gsl-rk8pd", REF_TOL, CMP_PROJECTION);
            }
        }
    } else if (kind == CMP_REF_PROJ) {
        /* RK4 + projection at a small step, checked against the same at
         * twice the step (the estimate of its own error) and against IDA
         * at a tight tolerance (an independent method). */
        const double h = proj_ref_h(tg);
        char why[256] = "";
        ref = cmp_ref_new_proj(tg, T, h, proj_ref_dt(tg), why, sizeof why);
        if (!ref) fprintf(stderr, "braun-compare: %s: projection reference failed: %s\n", tg->name, why);
        cmp_ref *twice = cmp_ref_new_proj(tg, T, 2 * h, proj_ref_dt(tg), NULL, 0);
        reference_pair(rf, tg, T, dt, "projection-rk4-fine", h, ref, "projection-rk4-fine",
                       2 * h, twice, "own-error", ri);
        cmp_ref_free(twice);
        cross_ida(rf, tg, T, dt, ref, "projection-rk4-fine", h);
        /* A published value (Andrews' test set) checks the reference too. */
        if (ref && tg->ref_q) {
            const int n = tg->sys.n;
            double *w = malloc(2 * (size_t)n * sizeof(double));
            if (w && cmp_ref_eval(ref, tg->ref_t, w, w + n) == 0) {
                double d2 = 0;
                for (int i = 0; i < n; i++) d2 += (w[i] - tg->ref_q[i]) * (w[i] - tg->ref_q[i]);
                fprintf(rf, "%s,%g,projection-rk4-fine,%g,published-point,nan,%.6e,%.6e,nan,"
                            "cross-check,Test Set for IVP Solvers: PSIDE at rtol = atol = 1e-14; "
                            "at t = %g only\n",
                        tg->name, T, h, sqrt(d2), sqrt(d2), tg->ref_t);
            }
            free(w);
        }
    } else if (kind == CMP_REF_POINT) {
        ref = cmp_ref_new(tg, kind, 0);
        fprintf(rf, "%s,%g,published-point,nan,none,nan,nan,nan,nan,-,"
                    "Test Set for IVP Solvers: PSIDE at rtol = atol = 1e-14\n", tg->name, T);
    }
    if (ref && cmp_ref_tabulate(ref, dt, T)) {
        fprintf(stderr, "braun-compare: %s: reference failed\n", tg->name);
        cmp_ref_free(ref);
        ref = NULL;
    }
    if (!ref && kind != CMP_REF_NONE)
        fprintf(stderr, "braun-compare: %s: no reference for T = %g\n", tg->name, T);
    return ref;
}

/* ------------------------------------------------------------ targets.csv */
const char *const cmp_targets_header =
    "scene,T,reference,floor_traj,floor_point,phi_unit,q_unit,point,minimal";

/* One row per scene and horizon: the reference and its floor, the units
 * of the constraint rows and of q, the ε point (plots and report). */
static void target_row(FILE *f, const cmp_target *tg, double T, const cmp_ref *ref,
                       const ref_info *ri)
{
    char phi[32], q[32], point[96], minimal[160];
    cmp_target_units(tg, phi, sizeof phi, q, sizeof q);
    snprintf(point, sizeof point, "%s", tg->has_point ? tg->point_name : "-");
    snprintf(minimal, sizeof minimal, "%s", tg->minimal ? cmp_minimal_name(tg->minimal) : "-");
    clean(point);
    clean(minimal);
    fprintf(f, "%s,%g,%s,%.6e,%.6e,%s,%s,%s,%s\n", tg->name, T,
            ref ? cmp_ref_kind_name(cmp_target_ref_kind(tg)) : "none", ri->floor_traj,
            ri->floor_point, phi, q, point, minimal);
}

/* ------------------------------------------------------------ traces */
/* Fig. 6: the observable point's x at every sample of the windows
 * [0, W] and [T - W, T] of a traced run, W = TRACE_WINDOW. */
#define TRACE_WINDOW 10.0

const char *const cmp_trace_header = "scene,T,method,integrator,variant,h,rtol,t,obs,obs_ref";

typedef struct trace_ctx {
    FILE *f;
    const job *j;
} trace_ctx;

static void trace_sample(const cmp_sample_err *e, void *user)
{
    const trace_ctx *c = user;
    const cmp_spec *s = &c->j->spec;
    const double W = fmin(TRACE_WINDOW, 0.5 * s->T);
    if (e->t > W && e->t < s->T - W) return;
    fprintf(c->f, "%s,%g,%s,%s,%s,", c->j->scene, s->T, cmp_method_name(s->method),
            cmp_integrator_name(s->integrator), s->variant[0] ? s->variant : "-");
    if (s->h > 0) fprintf(c->f, "%g,nan,", s->h);
    else fprintf(c->f, "nan,%g,", s->rtol);
    fprintf(c->f, "%.6f,%.10g,%.10g\n", e->t, e->obs, e->obs_ref);
}

/* Histories and traces from one pass over the samples. */
typedef struct sample_fanout {
    hist *h;
    trace_ctx *tc;
} sample_fanout;

static void fanout(const cmp_sample_err *e, void *user)
{
    sample_fanout *f = user;
    if (f->h) hist_sample(e, f->h);
    if (f->tc) trace_sample(e, f->tc);
}

/* ------------------------------------------------------------ step cost */
const char *const cmp_step_cost_header =
    "scene,method,integrator,variant,h,steps,reps,cpu_per_step_s,cpu_per_step_max_s,detail";

/* CPU seconds per step of a fixed-step run of `steps` steps (braun,
 * projection: their integrators without output; MuJoCo: mj_step). */
static double step_seconds(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                           size_t whysize)
{
    if (sp->method == CMP_MUJOCO) return cmp_mujoco_step_cost(tg, sp, steps, why, whysize);
    cmp_spec s = *sp;
    s.T = (double)steps * sp->h;
    s.dt_out = s.T;
    cmp_traj tr;
    cmp_outcome out;
    if (cmp_traj_init(&tr, tg->sys.n, 4)) return NAN;
    const double c0 = cmp_cpu_seconds();
    cmp_run(tg, &s, &tr, &out);
    const double c = cmp_cpu_seconds() - c0;
    cmp_traj_free(&tr);
    if (out.status) {
        snprintf(why, whysize, "%.40s %.100s", out.status_name, out.detail);
        return NAN;
    }
    return (out.cpu_self > 0 ? out.cpu_self : c) / (double)steps;
}

/* The cost job: braun's corrected RK4 step (all corrections, and without
 * energy), the projection's and MuJoCo's mj_step (its three integrators at
 * the main settings) on the same mechanism at the same h, in this process,
 * interleaved (COST_REPS rounds, best of them). */
#define COST_STEPS 20000
#define COST_REPS 3

static void run_cost(const job *j, const cmp_target *tg, FILE *f)
{
    static const struct {
        cmp_method_id m;
        int integ;
        const char *variant;
    } who[] = {
        {CMP_BRAUN, BRAUN_RK4, ""},          {CMP_BRAUN_NOENERGY, BRAUN_RK4, ""},
        {CMP_PROJECTION, BRAUN_RK4, ""},     {CMP_MUJOCO, CMP_MJ_RK4, ""},
        {CMP_MUJOCO, CMP_MJ_EULER, ""},      {CMP_MUJOCO, CMP_MJ_IMPLICIT, ""},
    };
    enum { NW = sizeof who / sizeof who[0] };
    double best[NW], worst[NW];
    char why[NW][160];
    for (int w = 0; w < NW; w++) {
        best[w] = INFINITY;
        worst[w] = 0;
        why[w][0] = '\0';
    }
    for (int r = 0; r < COST_REPS; r++)
        for (int w = 0; w < NW; w++) {
            cmp_spec s;
            memset(&s, 0, sizeof s);
            s.method = who[w].m;
            s.integrator = who[w].integ;
            s.h = j->spec.h;
            if (s.method == CMP_MUJOCO) s.peer = *mj_best(s.integrator);
            const double c = step_seconds(tg, &s, COST_STEPS, why[w], sizeof why[w]);
            if (isnan(c)) best[w] = worst[w] = NAN;
            if (c < best[w]) best[w] = c;
            if (c > worst[w]) worst[w] = c;
        }
    for (int w = 0; w < NW; w++) {
        clean(why[w]);
        fprintf(f, "%s,%s,%s,%s,%g,%d,%d,%.6e,%.6e,%s\n", tg->name, cmp_method_name(who[w].m),
                cmp_integrator_name(who[w].integ), who[w].variant[0] ? who[w].variant : "-",
                j->spec.h, COST_STEPS, COST_REPS, best[w], worst[w], why[w][0] ? why[w] : "-");
    }
    fflush(f);
}

/* ------------------------------------------------------------ driver */
static FILE *open_csv(const char *dir, const char *name, const char *header)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "braun-compare: cannot write %s\n", path);
        return NULL;
    }
    fprintf(f, "%s\n", header);
    return f;
}

static void fmt_elapsed(double s, char *buf, size_t size)
{
    int m = (int)(s / 60);
    snprintf(buf, size, "%dm%02ds", m, (int)(s - 60 * m));
}

/* The CSV files of a study, or of one step of it (compare/run.sh merges
 * the steps' files in this order: cmp_study_files). */
typedef struct outs {
    FILE *runs, *hist, *refs, *probe, *sing, *targets, *trace, *cost;
} outs;

const char *const cmp_study_files =
    "runs.csv history.csv references.csv ida_probe.csv singular.csv targets.csv trace.csv "
    "step_cost.csv";

static int outs_close(outs *f)
{
    FILE **all[] = {&f->runs, &f->hist, &f->refs, &f->probe, &f->sing, &f->targets, &f->trace,
                    &f->cost};
    int rc = 0;
    for (int k = 0; k < N_OF(all); k++) {
        if (*all[k] && fclose(*all[k])) rc = -1;
        *all[k] = NULL;
    }
    return rc;
}

static int outs_open(outs *f, const char *dir)
{
    memset(f, 0, sizeof *f);
    if (cmp_mkdir_p(dir)) {
        fprintf(stderr, "braun-compare: cannot create %s\n", dir);
        return -1;
    }
    f->runs = open_csv(dir, "runs.csv", cmp_runs_header);
    f->hist = open_csv(dir, "history.csv", cmp_history_header);
    f->refs = open_csv(dir, "references.csv", cmp_references_header);
    f->probe = open_csv(dir, "ida_probe.csv", cmp_runs_header);
    f->sing = open_csv(dir, "singular.csv", cmp_singular_header);
    f->targets = open_csv(dir, "targets.csv", cmp_targets_header);
    f->trace = open_csv(dir, "trace.csv", cmp_trace_header);
    f->cost = open_csv(dir, "step_cost.csv", cmp_step_cost_header);
    if (f->runs && f->hist && f->refs && f->probe && f->sing && f->targets && f->trace && f->cost)
        return 0;
    outs_close(f);
    return -1;
}

/* The runs of a study in the order of the serial run, in groups of one
 * scene and horizon (one reference each). */
typedef struct study {
    joblist l;
    int *group;  /* l.n: the group of each run */
    int *first;  /* ng + 1: the first run of each group, then l.n */
    int ng;
} study;

static void study_free(study *st)
{
    free(st->l.v);
    free(st->group);
    free(st->first);
}

static int study_plan(const cmp_study_opts *o, study *st)
{
    memset(st, 0, sizeof *st);
    for (int s = 0; s < o->nscenes; s++) {
        cmp_target t;
        char err[512];
        if (cmp_target_find(o->scenes[s], &t, err, sizeof err)) {
            fprintf(stderr, "braun-compare: %s\n", err);
            study_free(st);
            return 1;
        }
        hist_scale = t.h_scale;
        int bad = plan_jobs(&st->l, o->study, &t, o->methods, o->probe);
        cmp_target_free(&t);
        if (bad) {
            fprintf(stderr, "braun-compare: out of memory\n");
            study_free(st);
            return 1;
        }
    }
    const joblist *l = &st->l;
    st->group = malloc(((size_t)l->n + 1) * sizeof(int));
    st->first = malloc(((size_t)l->n + 1) * sizeof(int));
    if (!st->group || !st->first) {
        fprintf(stderr, "braun-compare: out of memory\n");
        study_free(st);
        return 1;
    }
    /* A new group where the scene or the horizon changes. */
    for (int i = 0; i < l->n; i++) {
        if (i == 0 || strcmp(l->v[i].scene, l->v[i - 1].scene) != 0 ||
            l->v[i].spec.T != l->v[i - 1].spec.T)
            st->first[st->ng++] = i;
        st->group[i] = st->ng - 1;
    }
    st->first[st->ng] = l->n;
    return 0;
}

/* The first group of its scene (the one that writes singular.csv). */
static int new_scene(const study *st, int g)
{
    const int i = st->first[g];
    return i == 0 || strcmp(st->l.v[i].scene, st->l.v[i - 1].scene) != 0;
}

static double elapsed(const cmp_study_opts *o, double wall0)
{
    if (o->t0 > 0) return difftime(time(NULL), (time_t)o->t0);
    return cmp_wall_seconds() - wall0;
}

/* Singular configurations (first horizon of a scene) and the reference of
 * group g with the estimates of its own error (references.csv) and its
 * targets.csv row; f NULL: the reference only (a run without its saved
 * reference, compare/run.sh --list). NULL: no reference. */
static cmp_ref *prepare_group(const study *st, int g, const cmp_target *tg, const outs *f)
{
    FILE *refs = f ? f->refs : tmpfile();
    if (f && new_scene(st, g)) {
        cmp_singularity_scan(tg, f->sing);
        fflush(f->sing);
    }
    const job *j = &st->l.v[st->first[g]];
    ref_info ri;
    cmp_ref *ref = refs ? make_reference(tg, cmp_target_ref_kind(tg), j->spec.T, j->spec.dt_out,
                                         refs, &ri)
                        : NULL;
    if (f) {
        fflush(f->refs);
        target_row(f->targets, tg, j->spec.T, ref, &ri);
        fflush(f->targets);
    } else if (refs) {
        fclose(refs);
    }
    return ref;
}

/* Run i of the study: timed reps times, measured against ref, its row (and
 * history) written to f, a progress line on stderr. The reference's
 * off-grid evaluator restarts first, so that the run's numbers do not
 * depend on the runs before it in the same process. */
static void run_one(const cmp_study_opts *o, const study *st, int i, const cmp_target *tg,
                    cmp_ref *ref, cmp_traj *tr, const outs *f, double wall0)
{
    const job *j = &st->l.v[i];
    const cmp_ref_kind kind = cmp_target_ref_kind(tg);
    cmp_ref_restart(ref);
    char el[32], what[64], line[512];

    if (j->kind == JOB_COST) {
        const double c0 = cmp_cpu_seconds();
        run_cost(j, tg, f->cost);
        fmt_elapsed(elapsed(o, wall0), el, sizeof el);
        snprintf(line, sizeof line, "[%4d/%d %s] %s: cost per step at h = %g, cpu=%.3gs\n", i + 1,
                 st->l.n, el, tg->name, j->spec.h, cmp_cpu_seconds() - c0);
        fputs(line, stderr);
        return;
    }

    /* Best of k: every repetition samples the same grid (a copy of the
     * state per output time, no metric work), so each is a full run. A
     * peer's runner times its integration itself (cpu_self), without
     * building its model and converting its samples. */
    const int reps = j->kind == JOB_UNSUPPORTED ? 0
                     : j->probe || j->once      ? 1
                                                : (o->reps < 1 ? 1 : o->reps);
    cmp_outcome out, first;
    memset(&first, 0, sizeof first);
    memset(&out, 0, sizeof out);
    double cmin = reps ? INFINITY : 0, cmax = 0;
    if (j->kind == JOB_UNSUPPORTED) {
        cmp_traj_clear(tr);
        out.status = -1;
        snprintf(out.status_name, sizeof out.status_name, "UNSUPPORTED");
        snprintf(out.detail, sizeof out.detail, "at t = 0 (%s)", j->why);
    }
    for (int r = 0; r < reps; r++) {
        const double c0 = cmp_cpu_seconds();
        cmp_run(tg, &j->spec, tr, &out);
        const double c = out.cpu_self > 0 ? out.cpu_self : cmp_cpu_seconds() - c0;
        if (c < cmin) cmin = c;
        if (c > cmax) cmax = c;
        if (r == 0) first = out;
        else if (out.counts.steps != first.counts.steps || out.status != first.status)
            fprintf(stderr, "braun-compare: warning: repetition %d of %s %s differs\n",
                    r + 1, tg->name, cmp_method_name(j->spec.method));
    }
    cmp_metrics mt;
    hist h;
    trace_ctx tc = {f->trace, j};
    const int want_hist = j->history && hist_init(&h, j->spec.T, j->spec.dt_out) == 0;
    sample_fanout fo = {want_hist ? &h : NULL, j->trace && tg->has_point ? &tc : NULL};
    cmp_metrics_compute(tg, tr, ref, &mt, fo.h || fo.tc ? fanout : NULL, &fo);
    /* How close to a singular configuration the run ended: at the
     * reference's state at t_reached, else at the run's last sample. */
    double sigma = NAN;
    {
        double *qs = malloc(2 * (size_t)tg->sys.n * sizeof(double));
        if (qs) {
            if (ref && cmp_ref_eval(ref, out.t_reached, qs, qs + tg->sys.n) == 0)
                sigma = cmp_target_sigma(tg, out.t_reached, qs);
            else if (tr->count > 0)
                sigma = cmp_target_sigma(tg, tr->t[tr->count - 1],
                                         tr->q + (size_t)(tr->count - 1) * tg->sys.n);
            free(qs);
        }
    }
    write_row(j->probe ? f->probe : f->runs, j, &out, cmin, cmax, reps, &mt, sigma,
              ref ? cmp_ref_kind_name(kind) : "none");
    if (want_hist) {
        hist_write(f->hist, &h, j);
        hist_free(&h);
    }
    fflush(j->probe ? f->probe : f->runs);
    fflush(f->hist);
    fflush(f->trace);

    /* One write per line: lines of parallel processes do not mix. */
    fmt_elapsed(elapsed(o, wall0), el, sizeof el);
    if (j->spec.h > 0) snprintf(what, sizeof what, "h=%g", j->spec.h);
    else snprintf(what, sizeof what, "rtol=%g", j->spec.rtol);
    snprintf(line, sizeof line, "[%4d/%d %s] %s T=%g %s %s%s%s %s: %s%s traj=%.2e cpu=%.3gs\n",
             i + 1, st->l.n, el, tg->name, j->spec.T, cmp_method_name(j->spec.method),
             integrator_name(j->spec.integrator), j->spec.variant[0] ? " " : "",
             j->spec.variant, what, run_status(&out, &mt),
             j->probe ? " (probe)" : "", mt.traj_max, cmin);
    fputs(line, stderr);
}

/* The whole study in this process. */
static int run_all(const cmp_study_opts *o, const study *st)
{
    outs f;
    if (outs_open(&f, o->out_dir)) return 1;
    const double wall0 = cmp_wall_seconds();
    cmp_target tg;
    int have_tg = 0, rc = 0;
    cmp_traj tr;
    memset(&tg, 0, sizeof tg);
    memset(&tr, 0, sizeof tr);
    for (int g = 0; g < st->ng && !rc; g++) {
        const job *j = &st->l.v[st->first[g]];
        /* Targets change only between scenes. */
        if (!have_tg || new_scene(st, g)) {
            char err[256];
            if (have_tg) cmp_target_free(&tg);
            have_tg = cmp_target_find(j->scene, &tg, err, sizeof err) == 0;
            if (!have_tg) {
                fprintf(stderr, "braun-compare: %s\n", err);
                rc = 1;
                break;
            }
            cmp_traj_free(&tr);
            if (cmp_traj_init(&tr, tg.sys.n, 4096)) {
                rc = 1;
                break;
            }
        }
        cmp_ref *ref = prepare_group(st, g, &tg, &f);
        for (int i = st->first[g]; i < st->first[g + 1]; i++)
            run_one(o, st, i, &tg, ref, &tr, &f, wall0);
        cmp_ref_free(ref);
    }
    if (have_tg) cmp_target_free(&tg);
    cmp_traj_free(&tr);
    if (outs_close(&f)) rc = 1;
    return rc;
}

static void ref_path(char *buf, size_t size, const char *refdir, int g)
{
    snprintf(buf, size, "%s/ref-%d.bin", refdir, g);
}

static int load_target(const char *scene, cmp_target *tg)
{
    char err[256];
    if (cmp_target_find(scene, tg, err, sizeof err) == 0) return 0;
    fprintf(stderr, "braun-compare: %s\n", err);
    return -1;
}

/* Step "prepare G": group G's singular.csv and references.csv rows, and its
 * reference saved for the runs of the group. */
static int run_prepare(const cmp_study_opts *o, const study *st)
{
    const int g = o->prepare;
    if (g < 0 || g >= st->ng) {
        fprintf(stderr, "braun-compare: --prepare %d: the plan has %d groups\n", g, st->ng);
        return 1;
    }
    const double wall0 = cmp_wall_seconds();
    const job *j = &st->l.v[st->first[g]];
    cmp_target tg;
    if (load_target(j->scene, &tg)) return 1;
    outs f;
    if (outs_open(&f, o->out_dir)) {
        cmp_target_free(&tg);
        return 1;
    }
    cmp_ref *ref = prepare_group(st, g, &tg, &f);
    char path[1024];
    ref_path(path, sizeof path, o->refdir, g);
    int rc = 0;
    if (cmp_mkdir_p(o->refdir) || cmp_ref_save(ref, path)) {
        fprintf(stderr, "braun-compare: cannot write %s\n", path);
        rc = 1;
    }
    if (outs_close(&f)) rc = 1;
    char el[32], line[512];
    fmt_elapsed(elapsed(o, wall0), el, sizeof el);
    snprintf(line, sizeof line, "[ref %d/%d %s] %s T=%g: %s%s\n", g + 1, st->ng, el, tg.name,
             j->spec.T, ref ? cmp_ref_kind_name(cmp_target_ref_kind(&tg)) : "no reference",
             new_scene(st, g) ? ", singular configurations" : "");
    fputs(line, stderr);
    cmp_ref_free(ref);
    cmp_target_free(&tg);
    return rc;
}

/* Step "job K": run K against its group's saved reference. A missing
 * file (a run list's line run before or without its "prepare" line,
 * compare/run.sh --list) is computed here instead: the same reference, bit
 * for bit, at the cost of computing it. */
static int run_job(const cmp_study_opts *o, const study *st)
{
    const int i = o->job;
    if (i < 0 || i >= st->l.n) {
        fprintf(stderr, "braun-compare: --job %d: the plan has %d runs\n", i, st->l.n);
        return 1;
    }
    const double wall0 = cmp_wall_seconds();
    cmp_target tg;
    if (load_target(st->l.v[i].scene, &tg)) return 1;
    char path[1024];
    ref_path(path, sizeof path, o->refdir, st->group[i]);
    cmp_ref *ref = NULL;
    cmp_traj tr;
    outs f;
    int rc = 1, loaded = -1;
    FILE *probe = fopen(path, "rb");
    if (probe) {
        fclose(probe);
        loaded = cmp_ref_load(&tg, path, &ref);
    } else {
        fprintf(stderr, "braun-compare: %s not there: computing the reference of run %d\n", path,
                i);
        ref = st->l.v[i].kind == JOB_COST ? NULL : prepare_group(st, st->group[i], &tg, NULL);
        loaded = 0;
    }
    if (loaded) {
        fprintf(stderr, "braun-compare: cannot read the reference %s\n", path);
    } else if (cmp_traj_init(&tr, tg.sys.n, 4096) == 0) {
        if (outs_open(&f, o->out_dir) == 0) {
            run_one(o, st, i, &tg, ref, &tr, &f, wall0);
            rc = outs_close(&f) ? 1 : 0;
        }
        cmp_traj_free(&tr);
    }
    cmp_ref_free(ref);
    cmp_target_free(&tg);
    return rc;
}

int cmp_study_run(const cmp_study_opts *o)
{
    study st;
    if (study_plan(o, &st)) return 1;
    int rc;
    if ((o->prepare >= 0 || o->job >= 0) && !o->refdir) {
        fprintf(stderr, "braun-compare: --prepare and --job need --refdir\n");
        rc = 1;
    } else if (o->prepare >= 0) {
        rc = run_prepare(o, &st);
    } else if (o->job >= 0) {
        rc = run_job(o, &st);
    } else {
        rc = run_all(o, &st);
    }
    study_free(&st);
    return rc;
}

int cmp_study_plan(const cmp_study_opts *o, FILE *f)
{
    study st;
    if (study_plan(o, &st)) return 1;
    for (int g = 0; g < st.ng; g++) {
        fprintf(f, "prepare %d %g\n", g, st.l.v[st.first[g]].spec.T);
        for (int i = st.first[g]; i < st.first[g + 1]; i++) fprintf(f, "job %d %d\n", i, g);
    }
    study_free(&st);
    return fflush(f) || ferror(f) ? 1 : 0;
}
