/* Reference ("numerically exact") solutions, Sec. 4: the minimal-coordinate
 * equation of a target in closed form (minimal_exact: Jacobi elliptic
 * functions for the four-bar and the pendulum) or integrated with GSL's
 * Prince–Dormand 8(9) pair at rtol = atol = tol, lifted to q, v by
 * minimal_to_state. GSL is GPL-3 and is linked into the harness only. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_ellint.h>
#include <gsl/gsl_sf_elljac.h>

#include "cmp.h"
#include "cmp_proj.h"
#include "braun_reference.h"

#define REF_DIM_MAX (2 * CMP_MINIMAL_MAX)

struct cmp_ref {
    const cmp_target *tg;
    cmp_ref_kind kind;
    double tol;
    /* Tabulated on t_j = j·dt (cmp_ref_tabulate); other times go to a
     * private evaluator, restarted if asked to go back in time. */
    double dt;
    long count;
    double *table;     /* count x width: q, v (and W for CMP_REF_TRAJ) */
    int width;
    cmp_ref *offgrid;
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double t, y[REF_DIM_MAX];
    int failed;
};

/* Cubic Hermite interpolation of q (nodes q, v every dt) and linear of v. */
static int traj_eval(cmp_ref *r, double t, double *q, double *v)
{
    const int n = r->tg->sys.n;
    const double x = t / r->dt;
    long j = (long)floor(x);
    if (j < 0 || x > (double)(r->count - 1) * (1.0 + 1e-12)) return -1;
    if (j >= r->count - 1) j = r->count - 2;
    const double s = x - (double)j, h = r->dt;
    const double *a = r->table + (size_t)j * (size_t)r->width, *b = a + r->width;
    const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    for (int i = 0; i < n; i++) {
        q[i] = h00 * a[i] + h10 * h * a[n + i] + h01 * b[i] + h11 * h * b[n + i];
        v[i] = (1 - s) * a[n + i] + s * b[n + i];
    }
    return 0;
}

/* Quintic Hermite interpolation of q (nodes q, v, a every dt) and cubic
 * of v (nodes v, a): the projection reference's table. */
static int proj_eval(cmp_ref *r, double t, double *q, double *v)
{
    const int n = r->tg->sys.n;
    const double x = t / r->dt;
    long j = (long)floor(x);
    if (j < 0 || x > (double)(r->count - 1) * (1.0 + 1e-12)) return -1;
    if (j >= r->count - 1) j = r->count - 2;
    const double s = x - (double)j, h = r->dt, s2 = s * s, s3 = s2 * s, s4 = s3 * s,
                 s5 = s4 * s;
    const double *a = r->table + (size_t)j * (size_t)r->width, *b = a + r->width;
    const double h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, h1 = s - 6 * s3 + 8 * s4 - 3 * s5,
                 h2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), h3 = 10 * s3 - 15 * s4 + 6 * s5,
                 h4 = -4 * s3 + 7 * s4 - 3 * s5, h5 = 0.5 * (s3 - 2 * s4 + s5);
    const double c0 = (1 + 2 * s) * (1 - s) * (1 - s), c1 = s * (1 - s) * (1 - s),
                 c2 = s2 * (3 - 2 * s), c3 = s2 * (s - 1);
    for (int i = 0; i < n; i++) {
        q[i] = h0 * a[i] + h * (h1 * a[n + i] + h * h2 * a[2 * n + i]) + h3 * b[i] +
               h * (h4 * b[n + i] + h * h5 * b[2 * n + i]);
        v[i] = c0 * a[n + i] + c1 * h * a[2 * n + i] + c2 * b[n + i] + c3 * h * b[2 * n + i];
    }
    return 0;
}

typedef struct proj_sink {
    cmp_ref *r;
    long calls;
} proj_sink;

static int proj_out(double t, const double *q, const double *v, const double *a, void *user)
{
    (void)t;
    proj_sink *k = user;
    const int n = k->r->tg->sys.n;
    if (k->calls >= k->r->count) return 1;
    double *row = k->r->table + (size_t)k->calls * (size_t)k->r->width;
    memcpy(row, q, (size_t)n * sizeof(double));
    memcpy(row + n, v, (size_t)n * sizeof(double));
    memcpy(row + 2 * n, a, (size_t)n * sizeof(double));
    k->calls++;
    return 0;
}

cmp_ref *cmp_ref_new_proj(const cmp_target *tg, double T, double h, double dt_tab, char *why,
                          size_t whysize)
{
    const int n = tg->sys.n;
    const long every = cmp_every(dt_tab, h);
    cmp_ref *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    r->tg = tg;
    r->kind = CMP_REF_PROJ;
    r->tol = h;
    r->dt = (double)every * h;
    r->count = (long)floor(T / r->dt + 0.5) + 1;
    r->width = 3 * n;
    r->table = malloc((size_t)r->count * (size_t)r->width * sizeof(double));
    proj_sink k = {r, 0};
    cmp_outcome o;
    if (!r->table || cmp_proj_integrate(tg, h, T, every, 0, proj_out, &k, &o) ||
        k.calls != r->count) {
        if (why) snprintf(why, whysize, "%s %s", r->table ? o.status_name : "OUT_OF_MEMORY",
                          r->table ? o.detail : "");
        cmp_ref_free(r);
        return NULL;
    }
    return r;
}

typedef struct traj_sink {
    cmp_ref *r;
    long every, calls;
} traj_sink;

static int traj_out(const braun_data *d, void *user)
{
    traj_sink *k = user;
    const int n = k->r->tg->sys.n;
    if (k->calls >= k->r->count) return 1;
    double *row = k->r->table + (size_t)k->calls * (size_t)k->r->width;
    for (int i = 0; i < n; i++) {
        row[i] = (double)d->q[i];
        row[n + i] = (double)d->v[i];
    }
    /* ∫Ė dτ along the reference, with the constraint work libbraun counts. */
    row[2 * n] = (double)d->work_in;
    k->calls++;
    return 0;
}

cmp_ref *cmp_ref_new_traj(const cmp_target *tg, double T, double h, double dt_tab)
{
    const int n = tg->sys.n;
    const long every = cmp_every(dt_tab, h);
    cmp_ref *r = calloc(1, sizeof *r);
    braun_model model;
    braun_data d;
    void *buf = NULL;
    if (!r) return NULL;
    r->tg = tg;
    r->kind = CMP_REF_TRAJ;
    r->tol = h;
    r->dt = (double)every * h;
    r->count = (long)floor(T / r->dt + 0.5) + 1;
    r->width = 2 * n + 1;
    r->table = malloc((size_t)r->count * (size_t)r->width * sizeof(double));
    int st = r->table ? braun_model_init(&model, &tg->sys) : -1;
    if (!st) {
        size_t bytes = braun_data_size(&model);
        buf = malloc(bytes);
        st = buf ? braun_data_init(&d, &model, buf, bytes) : -1;
    }
    if (!st) st = braun_set_state(&d, 0, tg->q0, tg->v0);
    traj_sink k = {r, every, 0};
    if (!st) st = braun_integrate(&d, BRAUN_RK4, h, T, every, traj_out, &k);
    free(buf);
    if (st || k.calls != r->count) {
        cmp_ref_free(r);
        return NULL;
    }
    return r;
}

/* GSL calls this: the model's minimal right-hand side (a built-in model's,
 * or the harness's equation of a scene, cmp_minimal.c). */
static int minimal_rhs(double t, const double y[], double dydt[], void *params)
{
    const cmp_target *tg = params;
    if (tg->minimal)
        return cmp_minimal_rhs(tg->minimal, t, y, dydt) ? GSL_EBADFUNC : GSL_SUCCESS;
    braun_minimal_find(tg->builtin->name)->rhs(t, y, dydt, tg->builtin->sys.user);
    for (int i = 0; i < braun_minimal_find(tg->builtin->name)->dim; i++)
        if (!isfinite(dydt[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

#define PI_D 3.14159265358979323846

/* am(u | m), continuous: am(u + 2K) = am(u) + π. */
static double amplitude(double u, double m, double K, double *dn)
{
    const double n = floor(u / (2 * K) + 0.5), r = u - 2 * K * n;
    double sn, cn;
    if (gsl_sf_elljac_e(r, m, &sn, &cn, dn) != GSL_SUCCESS) return NAN;
    return n * PI_D + atan2(sn, cn);
}

int cmp_pendulum_gsl(double w2, double phi0, double dphi0, double t, double *phi, double *dphi)
{
    const double w = sqrt(w2), E = 0.5 * dphi0 * dphi0 - w2 * cos(phi0);
    gsl_sf_result K, F;
    if (E > w2) {
        /* Rotation: φ = 2 am(c ± w t / k | k²), k² = 2w²/(E + w²). */
        const double m = 2 * w2 / (E + w2), k = sqrt(m), s = dphi0 >= 0 ? 1.0 : -1.0;
        if (gsl_sf_ellint_Kcomp_e(k, GSL_PREC_DOUBLE, &K) ||
            gsl_sf_ellint_F_e(0.5 * phi0 - PI_D * floor(0.5 * phi0 / PI_D + 0.5), k,
                              GSL_PREC_DOUBLE, &F))
            return -1;
        /* am(c) = φ0/2, c in the period of φ0/2's branch. */
        const double turns = floor(0.5 * phi0 / PI_D + 0.5);
        const double c = F.val + 2 * K.val * turns;
        double dn;
        const double a = amplitude(c + s * w * t / k, m, K.val, &dn);
        *phi = 2 * a;
        *dphi = s * 2 * w / k * dn;
        return isfinite(*phi) ? 0 : -1;
    }
    if (E < w2) {
        /* Libration: sin(φ/2) = k sn(w t + c | k²), k² = (E + w²)/(2w²). */
        const double m = (E + w2) / (2 * w2), k = sqrt(m);
        if (gsl_sf_ellint_Kcomp_e(k, GSL_PREC_DOUBLE, &K)) return -1;
        /* c from sn(c) = sin(φ0/2)/k and cn(c), which the velocity gives
         * well conditioned even at a turning point (where asin is not):
         * φ0' = 2kw cn dn / cos(φ0/2). The amplitude ψ = atan2(sn, cn). */
        const double sn0 = fmax(-1.0, fmin(1.0, sin(0.5 * phi0) / k));
        const double dn0 = sqrt(fmax(0.0, 1.0 - m * sn0 * sn0));
        const double cn0 = dphi0 * cos(0.5 * phi0) / (2 * k * w * dn0);
        const double psi = atan2(sn0, cn0);
        double c;
        if (fabs(psi) <= 0.5 * PI_D) {
            if (gsl_sf_ellint_F_e(psi, k, GSL_PREC_DOUBLE, &F)) return -1;
            c = F.val;
        } else {
            /* F(ψ) = ±2K − F(±π − ψ) beyond ±π/2. */
            const double sg = psi > 0 ? 1.0 : -1.0;
            if (gsl_sf_ellint_F_e(sg * PI_D - psi, k, GSL_PREC_DOUBLE, &F)) return -1;
            c = sg * 2 * K.val - F.val;
        }
        double sn, cn, dn;
        if (gsl_sf_elljac_e(w * t + c, m, &sn, &cn, &dn) != GSL_SUCCESS) return -1;
        *phi = 2 * asin(k * sn);
        *dphi = 2 * k * w * cn; /* ½φ'² = E + w² cos φ = 2w²k² cn² */
        return 0;
    }
    return -1;
}

/* The closed form by GSL for the built-in models that have one: the
 * four-bar's θ'' + (7g/6l) cos θ = 0 is the pendulum in φ = θ + π/2. */
static int closed_gsl(const cmp_target *tg, double t, double *y)
{
    const braun_builtin *b = tg->builtin;
    const braun_link_params *p = b->sys.user;
    const braun_minimal *mm = braun_minimal_find(b->name);
    double w2, shift;
    if (!strcmp(b->name, "four-bar")) {
        w2 = 7.0 * p->g / (6.0 * p->l);
        shift = PI_D / 2;
    } else if (!strcmp(b->name, "pendulum")) {
        w2 = p->g / p->l;
        shift = 0;
    } else {
        return -1;
    }
    if (cmp_pendulum_gsl(w2, mm->y0[0] + shift, mm->y0[1], t, &y[0], &y[1])) return -1;
    y[0] -= shift;
    return 0;
}

cmp_ref *cmp_ref_new(const cmp_target *tg, cmp_ref_kind kind, double tol)
{
    const braun_builtin *b = tg->builtin;
    if (kind == CMP_REF_POINT) {
        if (!tg->ref_q) return NULL;
        cmp_ref *r = calloc(1, sizeof *r);
        if (r) {
            r->tg = tg;
            r->kind = kind;
        }
        return r;
    }
    if (tg->minimal && kind == CMP_REF_RK8PD) {
        /* The harness's minimal equation of a scene. */
        const int dim = cmp_minimal_dim(tg->minimal);
        if (dim > REF_DIM_MAX) return NULL;
        cmp_ref *r = calloc(1, sizeof *r);
        if (!r) return NULL;
        r->tg = tg;
        r->kind = kind;
        r->tol = tol;
        memcpy(r->y, cmp_minimal_y0(tg->minimal), (size_t)dim * sizeof(double));
        gsl_set_error_handler_off();
        r->sys.function = minimal_rhs;
        r->sys.jacobian = NULL;
        r->sys.dimension = (size_t)dim;
        r->sys.params = (void *)tg;
        r->drv = gsl_odeiv2_driver_alloc_y_new(&r->sys, gsl_odeiv2_step_rk8pd, 1e-6, tol, tol);
        if (!r->drv) {
            free(r);
            return NULL;
        }
        return r;
    }
    if (!b || !braun_minimal_find(b->name)->to_state || braun_minimal_find(b->name)->dim > REF_DIM_MAX) return NULL;
    if (kind == CMP_REF_CLOSED && !braun_minimal_find(b->name)->exact) return NULL;
    if (kind == CMP_REF_RK8PD && !braun_minimal_find(b->name)->rhs) return NULL;
    if (kind == CMP_REF_CLOSED_GSL) {
        double y[2];
        if (closed_gsl(tg, 0, y)) return NULL;
    } else if (kind != CMP_REF_CLOSED && kind != CMP_REF_RK8PD) {
        return NULL;
    }
    cmp_ref *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    r->tg = tg;
    r->kind = kind;
    r->tol = tol;
    for (int i = 0; i < braun_minimal_find(b->name)->dim; i++) r->y[i] = braun_minimal_find(b->name)->y0[i];
    if (kind == CMP_REF_RK8PD) {
        /* Errors are returned, never aborted on. */
        gsl_set_error_handler_off();
        r->sys.function = minimal_rhs;
        r->sys.jacobian = NULL;
        r->sys.dimension = (size_t)braun_minimal_find(b->name)->dim;
        r->sys.params = (void *)tg;
        r->drv = gsl_odeiv2_driver_alloc_y_new(&r->sys, gsl_odeiv2_step_rk8pd, 1e-6, tol,
                                               tol);
        if (!r->drv) {
            free(r);
            return NULL;
        }
    }
    return r;
}

int cmp_ref_eval(cmp_ref *r, double t, double *q, double *v)
{
    const braun_builtin *b = r->tg->builtin;
    double y[REF_DIM_MAX];
    if (r->failed || !isfinite(t)) return -1;
    if (r->kind == CMP_REF_POINT) {
        const cmp_target *tg = r->tg;
        if (fabs(t - tg->ref_t) > 1e-12 * fmax(1.0, fabs(tg->ref_t))) return 1;
        for (int i = 0; i < tg->sys.n; i++) {
            q[i] = tg->ref_q[i];
            v[i] = NAN;
        }
        return 0;
    }
    if (r->kind == CMP_REF_TRAJ) return traj_eval(r, t, q, v);
    if (r->kind == CMP_REF_PROJ) return proj_eval(r, t, q, v);
    if (r->table) {
        const double x = t / r->dt;
        const long j = (long)floor(x + 0.5);
        if (j >= 0 && j < r->count && fabs(x - (double)j) <= 1e-9 * (1.0 + fabs(x))) {
            const int n = r->tg->sys.n;
            const double *row = r->table + (size_t)j * (size_t)r->width;
            for (int i = 0; i < n; i++) {
                q[i] = row[i];
                v[i] = row[n + i];
            }
            return 0;
        }
        if (r->offgrid && r->kind == CMP_REF_RK8PD && t < r->offgrid->t) {
            cmp_ref_free(r->offgrid);
            r->offgrid = NULL;
        }
        if (!r->offgrid) r->offgrid = cmp_ref_new(r->tg, r->kind, r->tol);
        return r->offgrid ? cmp_ref_eval(r->offgrid, t, q, v) : -1;
    }
    if (r->kind == CMP_REF_CLOSED) {
        if (braun_minimal_find(b->name)->exact(t, y, b->sys.user) < 0) return -1;
    } else if (r->kind == CMP_REF_CLOSED_GSL) {
        if (closed_gsl(r->tg, t, y)) return -1;
    } else {
        if (t < r->t) return -1;
        if (t > r->t) {
            /* The driver lands exactly on t; successive calls continue. */
            int st = gsl_odeiv2_driver_apply(r->drv, &r->t, t, r->y);
            if (st != GSL_SUCCESS) {
                r->failed = 1;
                return -1;
            }
        }
        if (r->tg->minimal) {
            cmp_minimal_state(r->tg->minimal, r->y, q, v);
            return 0;
        }
        for (int i = 0; i < braun_minimal_find(b->name)->dim; i++) y[i] = r->y[i];
    }
    braun_minimal_find(b->name)->to_state(y, q, v, b->sys.user);
    return 0;
}

int cmp_ref_tabulate(cmp_ref *r, double dt, double T)
{
    /* Trajectory and point references are tables already. */
    if (r->kind == CMP_REF_TRAJ || r->kind == CMP_REF_POINT || r->kind == CMP_REF_PROJ)
        return 0;
    /* Tabulated once already (the same grid: a study's group). */
    if (r->table) return fabs(r->dt - dt) <= 1e-12 * dt && r->count == (long)floor(T / dt + 0.5) + 1 ? 0 : -1;
    const int n = r->tg->sys.n;
    const long count = (long)floor(T / dt + 0.5) + 1;
    double *table = malloc((size_t)count * 2 * (size_t)n * sizeof(double));
    if (!table) return -1;
    for (long j = 0; j < count; j++) {
        double *row = table + (size_t)j * 2 * (size_t)n;
        if (cmp_ref_eval(r, (double)j * dt, row, row + n)) {
            free(table);
            return -1;
        }
    }
    r->table = table;
    r->width = 2 * n;
    r->dt = dt;
    r->count = count;
    return 0;
}

/* E(t, q, v) of the target's energy law; -1 without one. */
static int energy_at(const cmp_target *tg, double t, const double *q, const double *v, double *E)
{
    const braun_system *s = &tg->sys;
    if (!s->energy) return -1;
    double *g = malloc(2 * (size_t)s->n * sizeof(double)), dEdt;
    if (!g) return -1;
    const int st = s->energy(t, q, v, E, g, g + s->n, &dEdt, s->user);
    free(g);
    return st ? -1 : 0;
}

int cmp_ref_work(cmp_ref *r, double t, double *W)
{
    if (r && r->kind == CMP_REF_PROJ && r->table) {
        /* Along the exact solution E(t) - E0 is the work put in. */
        const int n = r->tg->sys.n;
        double *w = malloc(2 * (size_t)n * sizeof(double)), E, E0;
        int st = !w || proj_eval(r, t, w, w + n) ||
                 energy_at(r->tg, t, w, w + n, &E) ||
                 energy_at(r->tg, 0, r->table, r->table + n, &E0);
        free(w);
        if (st) return -1;
        *W = E - E0;
        return 0;
    }
    if (!r || r->kind != CMP_REF_TRAJ || !r->table) return -1;
    const int n = r->tg->sys.n;
    const double x = t / r->dt;
    long j = (long)floor(x);
    if (j < 0 || x > (double)(r->count - 1) * (1.0 + 1e-12)) return -1;
    if (j >= r->count - 1) j = r->count - 2;
    const double s = x - (double)j;
    const double *a = r->table + (size_t)j * (size_t)r->width, *b = a + r->width;
    *W = (1 - s) * a[2 * n] + s * b[2 * n];
    return 0;
}

void cmp_ref_restart(cmp_ref *r)
{
    if (!r) return;
    cmp_ref_free(r->offgrid);
    r->offgrid = NULL;
}

/* The file of a tabulated reference: this header, then count x width
 * doubles as they are in memory (the file is read back by the same binary
 * on the same machine, compare/run.sh's parts directory). */
#define REF_FILE_MAGIC "braunref"
#define REF_FILE_VERSION 1

typedef struct ref_file_header {
    char magic[8];
    int32_t version, kind, n, width;
    double tol, dt;
    int64_t count;
} ref_file_header;

int cmp_ref_save(const cmp_ref *r, const char *path)
{
    ref_file_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, REF_FILE_MAGIC, sizeof h.magic);
    h.version = REF_FILE_VERSION;
    h.kind = r ? (int32_t)r->kind : (int32_t)CMP_REF_NONE;
    if (r) {
        h.n = r->tg->sys.n;
        h.tol = r->tol;
        /* A reference not tabulated (published point) is saved as its kind. */
        if (r->table) {
            h.width = r->width;
            h.dt = r->dt;
            h.count = r->count;
        }
    }
    /* Written beside and renamed: a run that loads it (another process,
     * another host of a run list) sees the whole file or none. */
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) return -1;
    const size_t cells = (size_t)h.count * (size_t)h.width;
    int bad = fwrite(&h, sizeof h, 1, f) != 1;
    if (!bad && cells) bad = fwrite(r->table, sizeof(double), cells, f) != cells;
    if (fclose(f)) bad = 1;
    if (!bad && rename(tmp, path)) bad = 1;
    if (bad) remove(tmp);
    return bad ? -1 : 0;
}

int cmp_ref_load(const cmp_target *tg, const char *path, cmp_ref **out)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    ref_file_header h;
    cmp_ref *r = NULL;
    int bad = fread(&h, sizeof h, 1, f) != 1 ||
              memcmp(h.magic, REF_FILE_MAGIC, sizeof h.magic) != 0 ||
              h.version != REF_FILE_VERSION || h.count < 0 || h.width < 0;
    if (!bad && h.kind != CMP_REF_NONE) {
        bad = h.n != tg->sys.n;
        if (!bad && h.kind == CMP_REF_POINT) {
            r = cmp_ref_new(tg, CMP_REF_POINT, 0);
            bad = r == NULL;
        } else if (!bad && (h.kind == CMP_REF_CLOSED || h.kind == CMP_REF_RK8PD ||
                            h.kind == CMP_REF_TRAJ || h.kind == CMP_REF_PROJ)) {
            const int want = h.kind == CMP_REF_TRAJ   ? 2 * h.n + 1
                             : h.kind == CMP_REF_PROJ ? 3 * h.n
                                                      : 2 * h.n;
            const size_t cells = (size_t)h.count * (size_t)h.width;
            r = calloc(1, sizeof *r);
            bad = !r || h.width != want || h.count < 2 || !(h.dt > 0);
            if (!bad) {
                r->tg = tg;
                r->kind = (cmp_ref_kind)h.kind;
                r->tol = h.tol;
                r->dt = h.dt;
                r->count = (long)h.count;
                r->width = h.width;
                r->table = malloc(cells * sizeof(double));
                bad = !r->table || fread(r->table, sizeof(double), cells, f) != cells;
            }
        } else {
            bad = 1;
        }
    }
    /* Nothing may follow the table. */
    if (!bad && fgetc(f) != EOF) bad = 1;
    fclose(f);
    if (bad) {
        cmp_ref_free(r);
        return -1;
    }
    *out = r;
    return 0;
}

void cmp_ref_free(cmp_ref *r)
{
    if (!r) return;
    free(r->table);
    cmp_ref_free(r->offgrid);
    if (r->drv) gsl_odeiv2_driver_free(r->drv);
    free(r);
}

const char *cmp_ref_kind_name(cmp_ref_kind kind)
{
    switch (kind) {
    case CMP_REF_CLOSED: return "closed-form";
    case CMP_REF_RK8PD: return "gsl-rk8pd";
    case CMP_REF_TRAJ: return "braun-rk4-fine";
    case CMP_REF_POINT: return "published-point";
    case CMP_REF_PROJ: return "projection-rk4-fine";
    case CMP_REF_CLOSED_GSL: return "closed-form-gsl";
    default: return "none";
    }
}
