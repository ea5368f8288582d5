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
     * rows, nonholonomic, rheonomic, energy input, chaotic, stiff. */
    return "slider-crank four-bar pendulum parallelogram-redundant sleigh driven-crank "
           "damped-motor double-pendulum andrews";
#else
    return "slider-crank four-bar pendulum";
#endif
}

/* ------------------------------------------------------------ jobs */
typedef struct job {
    char scene[64];
    cmp_spec spec;
    int history;   /* write its error history */
    int probe;     /* IDA probe (ida_probe.csv), timed once */
} job;

typedef struct joblist {
    job *v;
    int n, cap;
} joblist;

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

static int fixed_step(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                      int integ, double h, double alpha, const char *variant, int hist)
{
    job *j = add(l, sc, p, T, m, integ);
    if (!j) return -1;
    j->spec.h = h;
    j->spec.alpha = j->spec.beta = alpha;
    snprintf(j->spec.variant, sizeof j->spec.variant, "%s", variant);
    j->history = hist && is_hist_h(h);
    return 0;
}

static int tolerance(joblist *l, const char *sc, const plan *p, double T, cmp_method_id m,
                     int integ, double rtol, const ida_setting *s, int probe)
{
    job *j = add(l, sc, p, T, m, integ);
    if (!j) return -1;
    j->spec.rtol = j->spec.atol = rtol;
    if (s) {
        j->spec.ida = s->o;
        snprintf(j->spec.variant, sizeof j->spec.variant, "%s", s->label);
    }
    j->probe = probe;
    /* Histories of the adaptive methods at one tolerance (Figs. 3, 7). */
    j->history = !probe && fabs(rtol - 1e-8) < 1e-20;
    return 0;
}

static int plan_jobs(joblist *l, const char *study, const cmp_target *tg, const int *methods,
                     int with_probe)
{
    plan p;
    const char *sc = tg->name;
    make_plan(study, tg, &p);
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
                        st |= fixed_step(l, sc, &p, T, m, integs[k], p.H[i], 0, "",
                                         integs[k] == BRAUN_RK4);
                for (int i = 0; i < p.nRD; i++)
                    st |= tolerance(l, sc, &p, T, m, BRAUN_DOPRI5, p.RD[i], NULL, 0);
            } else if (m == CMP_BAUMGARTE) {
                char v[32];
                for (int i = 0; i < p.nH; i++)
                    st |= fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.H[i], BG_C_DEFAULT / p.H[i],
                                     "", 1);
                for (int i = 0; i < p.nHS; i++) {
                    for (int k = 0; k < N_OF(BG_SWEEP); k++) {
                        snprintf(v, sizeof v, "ab=%g/h", BG_SWEEP[k]);
                        st |= fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.HS[i],
                                         BG_SWEEP[k] / p.HS[i], v, 0);
                    }
                    snprintf(v, sizeof v, "ab=%g", BG_FIXED);
                    st |= fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.HS[i], BG_FIXED, v, 0);
                }
            } else if (m == CMP_ODE_RK4) {
                if (!tg->builtin || !braun_minimal_find(tg->builtin->name)->rhs) continue;
                for (int i = 0; i < p.nH; i++)
                    st |= fixed_step(l, sc, &p, T, m, BRAUN_RK4, p.H[i], 0, "", 1);
            } else if (m == CMP_IDA_GGL) {
                for (int s = 0; s < N_OF(IDA_MAIN); s++)
                    for (int i = 0; i < p.nRI; i++)
                        st |= tolerance(l, sc, &p, T, m, -1, p.RI[i], &IDA_MAIN[s], 0);
                if (with_probe && it == 0)
                    for (int s = 0; s < N_OF(IDA_PROBE); s++)
                        for (int i = 0; i < p.nRP; i++)
                            st |= tolerance(l, sc, &p, T, m, -1, p.RP[i], &IDA_PROBE[s], 1);
            } else if (m == CMP_IDA_INDEX1) {
                for (int i = 0; i < p.nRI; i++)
                    st |= tolerance(l, sc, &p, T, m, -1, p.RI[i], &IDA_MAIN[0], 0);
            }
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
    "sigma_end,reference,detail";

static const char *integrator_name(int integ)
{
    return integ < 0 ? "bdf" : braun_method_name((braun_method)integ);
}

/* A free-text field without the CSV separator or quotes. */
static void clean(char *s)
{
    for (; *s; s++)
        if (*s == ',' || *s == '"' || *s == '\n' || *s == '\r') *s = ';';
}

static void write_row(FILE *f, const job *j, const cmp_outcome *o, double cpu_min,
                      double cpu_max, int reps, const cmp_metrics *mt, double sigma,
                      const char *ref)
{
    const cmp_spec *s = &j->spec;
    char detail[sizeof o->detail];
    snprintf(detail, sizeof detail, "%s", o->detail);
    clean(detail);
    const int fixed = s->h > 0;
    fprintf(f, "%s,%g,%s,%s,%s,", j->scene, s->T, cmp_method_name(s->method),
            integrator_name(s->integrator), s->variant[0] ? s->variant : "-");
    if (fixed) fprintf(f, "%g,nan,nan,", s->h);
    else fprintf(f, "nan,%g,%g,", s->rtol, s->atol);
    if (s->method == CMP_BAUMGARTE) fprintf(f, "%.6g,%.6g,", s->alpha, s->beta);
    else fprintf(f, "nan,nan,");
    fprintf(f, "%s,%.10g,%.6g,%.6g,%d,", o->status ? o->status_name : "ok", o->t_reached,
            cpu_min, cpu_max, reps);
    const cmp_counts *k = &o->counts;
    fprintf(f, "%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,", k->steps, k->rejected, k->rhs_evals,
            k->jac_evals, k->lin_setups, k->lin_solves, k->err_fails, k->conv_fails,
            k->restarts);
    fprintf(f, "%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%ld,%.3e,%s,%s\n",
            mt->pos_max, mt->pos_final, mt->vel_max, mt->vel_final, mt->energy_max,
            mt->energy_final, mt->traj_max, mt->traj_final, mt->point_max, mt->point_final,
            mt->samples, sigma, ref, detail);
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
    "scene,T,reference,tol,compared_with,tol2,max_q_diff,final_q_diff,max_point_diff,note";

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

/* A reference against another, as a metric: max over the grid of
 * ||q_a - q_b||, written as one row of references.csv. */
static void reference_pair(FILE *f, const cmp_target *tg, double T, double dt,
                           const char *name_a, double tol_a, cmp_ref *a, const char *name_b,
                           double tol_b, cmp_ref *b)
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
    fprintf(f, "%s,%g,%s,%g,%s,%g,%.6e,%.6e,%.6e,-\n", tg->name, T, name_a, tol_a, name_b,
            tol_b, mx, last, tg->has_point ? pmx : NAN);
    fflush(f);
    free(w);
}

/* Compare two references on the grid: the estimate of the reference's own
 * error printed in the report. */
static void reference_check(FILE *f, const cmp_target *tg, double T, double dt,
                            cmp_ref_kind ka, double ta, cmp_ref_kind kb, double tb)
{
    cmp_ref *a = cmp_ref_new(tg, ka, ta), *b = cmp_ref_new(tg, kb, tb);
    reference_pair(f, tg, T, dt, cmp_ref_kind_name(ka), ka == CMP_REF_RK8PD ? ta : NAN, a,
                   cmp_ref_kind_name(kb), kb == CMP_REF_RK8PD ? tb : NAN, b);
    cmp_ref_free(a);
    cmp_ref_free(b);
}


/* The reference of a target and horizon, and the estimates of its own error
 * (docs/compare.md, "References"). */
static cmp_ref *make_reference(const cmp_target *tg, cmp_ref_kind kind, double T, double dt,
                               FILE *rf)
{
    cmp_ref *ref = NULL;
    if (kind == CMP_REF_CLOSED || kind == CMP_REF_RK8PD) {
        ref = cmp_ref_new(tg, kind, REF_TOL);
        if (kind == CMP_REF_CLOSED) {
            reference_check(rf, tg, T, dt, CMP_REF_CLOSED, 0, CMP_REF_RK8PD, 1e-12);
            reference_check(rf, tg, T, dt, CMP_REF_CLOSED, 0, CMP_REF_RK8PD, 1e-13);
        }
        reference_check(rf, tg, T, dt, CMP_REF_RK8PD, 1e-12, CMP_REF_RK8PD, 1e-13);
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
                       2 * h, twice);
        cmp_ref_free(twice);
        cmp_spec sp;
        memset(&sp, 0, sizeof sp);
        sp.method = CMP_IDA_GGL;
        sp.integrator = -1;
        sp.rtol = sp.atol = 1e-10;
        sp.ida.alg_atol = ALG_OFF;
        sp.T = T;
        sp.dt_out = dt;
        cmp_traj tr;
        cmp_outcome out;
        if (ref && cmp_traj_init(&tr, tg->sys.n, 1024) == 0) {
            cmp_run(tg, &sp, &tr, &out);
            cmp_metrics mt;
            cmp_metrics_compute(tg, &tr, ref, &mt, NULL, NULL);
            fprintf(rf, "%s,%g,projection-rk4-fine,%g,ida-ggl,1e-10,%.6e,%.6e,%.6e,%s up to t = %g\n",
                    tg->name, T, h, mt.traj_max, mt.traj_final, mt.point_max,
                    out.status ? out.status_name : "ok", out.t_reached);
            cmp_traj_free(&tr);
        }
        /* A published value (Andrews' test set) checks the reference too. */
        if (ref && tg->ref_q) {
            const int n = tg->sys.n;
            double *w = malloc(2 * (size_t)n * sizeof(double));
            if (w && cmp_ref_eval(ref, tg->ref_t, w, w + n) == 0) {
                double d2 = 0;
                for (int i = 0; i < n; i++) d2 += (w[i] - tg->ref_q[i]) * (w[i] - tg->ref_q[i]);
                fprintf(rf, "%s,%g,projection-rk4-fine,%g,published-point,nan,%.6e,%.6e,nan,"
                            "Test Set for IVP Solvers: PSIDE at rtol = atol = 1e-14; at t = %g only\n",
                        tg->name, T, h, sqrt(d2), sqrt(d2), tg->ref_t);
            }
            free(w);
        }
    } else if (kind == CMP_REF_POINT) {
        ref = cmp_ref_new(tg, kind, 0);
        fprintf(rf, "%s,%g,published-point,nan,none,nan,nan,nan,nan,"
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

/* The five CSV files of a study, or of one step of it. */
typedef struct outs {
    FILE *runs, *hist, *refs, *probe, *sing;
} outs;

static int outs_close(outs *f)
{
    FILE **all[] = {&f->runs, &f->hist, &f->refs, &f->probe, &f->sing};
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
    if (f->runs && f->hist && f->refs && f->probe && f->sing) return 0;
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
 * group g with the estimates of its own error. NULL: no reference. */
static cmp_ref *prepare_group(const study *st, int g, const cmp_target *tg, const outs *f)
{
    if (new_scene(st, g)) {
        cmp_singularity_scan(tg, f->sing);
        fflush(f->sing);
    }
    const job *j = &st->l.v[st->first[g]];
    cmp_ref *ref = make_reference(tg, cmp_target_ref_kind(tg), j->spec.T, j->spec.dt_out, f->refs);
    fflush(f->refs);
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

    /* Best of k: every repetition samples the same grid (a copy of the
     * state per output time, no metric work), so each is a full run. */
    const int reps = j->probe ? 1 : (o->reps < 1 ? 1 : o->reps);
    cmp_outcome out, first;
    memset(&first, 0, sizeof first);
    double cmin = INFINITY, cmax = 0;
    for (int r = 0; r < reps; r++) {
        const double c0 = cmp_cpu_seconds();
        cmp_run(tg, &j->spec, tr, &out);
        const double c = cmp_cpu_seconds() - c0;
        if (c < cmin) cmin = c;
        if (c > cmax) cmax = c;
        if (r == 0) first = out;
        else if (out.counts.steps != first.counts.steps || out.status != first.status)
            fprintf(stderr, "braun-compare: warning: repetition %d of %s %s differs\n",
                    r + 1, tg->name, cmp_method_name(j->spec.method));
    }
    cmp_metrics mt;
    hist h;
    int want_hist = j->history && hist_init(&h, j->spec.T, j->spec.dt_out) == 0;
    cmp_metrics_compute(tg, tr, ref, &mt, want_hist ? hist_sample : NULL,
                        want_hist ? &h : NULL);
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

    /* One write per line: lines of parallel processes do not mix. */
    char el[32], what[64], line[512];
    fmt_elapsed(elapsed(o, wall0), el, sizeof el);
    if (j->spec.h > 0) snprintf(what, sizeof what, "h=%g", j->spec.h);
    else snprintf(what, sizeof what, "rtol=%g", j->spec.rtol);
    snprintf(line, sizeof line, "[%4d/%d %s] %s T=%g %s %s%s%s %s: %s%s traj=%.2e cpu=%.3gs\n",
             i + 1, st->l.n, el, tg->name, j->spec.T, cmp_method_name(j->spec.method),
             integrator_name(j->spec.integrator), j->spec.variant[0] ? " " : "",
             j->spec.variant, what, out.status ? out.status_name : "ok",
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

/* Step "job K": run K against its group's saved reference. */
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
    int rc = 1;
    if (cmp_ref_load(&tg, path, &ref)) {
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
