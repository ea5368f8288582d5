/* projection (cmp_proj.h): RK4 on the index-1 equation, then coordinate
 * projection onto the constraint manifold after every step. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_dense.h"
#include "cmp_proj.h"

struct cmp_proj {
    const braun_system *sys;
    int n, m, p, mv;
    int mass_ready;
    double *M, *L, *Q, *phi, *A, *b, *bv, *C, *r, *x, *dEdv;
    cmp_mnsolve ms;
    long factorizations, solves, iterations;
};

cmp_proj *cmp_proj_new(const braun_system *sys)
{
    if (sys->sparsity) return NULL;
    cmp_proj *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    p->sys = sys;
    p->n = sys->n;
    p->m = sys->m;
    p->p = sys->p;
    p->mv = sys->m + sys->p;
    const size_t n = (size_t)p->n, rows = (size_t)p->mv + 1;
    p->M = malloc((2 * n * n + n + 3 * rows + 2 * rows * n + rows + 2 * n) * sizeof(double));
    if (!p->M || cmp_mnsolve_init(&p->ms, p->n, (int)rows)) {
        cmp_proj_free(p);
        return NULL;
    }
    p->L = p->M + n * n;
    p->Q = p->L + n * n;
    p->phi = p->Q + n;
    p->b = p->phi + rows;
    p->bv = p->b + rows;
    p->A = p->bv + rows;
    p->C = p->A + rows * n;
    p->r = p->C + rows * n;
    p->x = p->r + rows;
    p->dEdv = p->x + n;
    return p;
}

void cmp_proj_free(cmp_proj *p)
{
    if (!p) return;
    cmp_mnsolve_free(&p->ms);
    free(p->M);
    free(p);
}

void cmp_proj_counts(const cmp_proj *p, long *factorizations, long *solves, long *iterations)
{
    *factorizations = p->factorizations;
    *solves = p->solves;
    *iterations = p->iterations;
}

/* Callback statuses: 0 ok, 1 retry (recoverable), -1 fatal. */
static int cb(int st)
{
    return st > 0 ? 1 : (st < 0 ? -1 : 0);
}

/* M and its Cholesky factor (once for a constant mass matrix). */
static int mass(cmp_proj *p, double t, const double *q)
{
    const braun_system *s = p->sys;
    if (p->mass_ready && (s->flags & BRAUN_MASS_CONSTANT)) return 0;
    int st = cb(s->mass(t, q, p->M, s->user));
    if (st) return st;
    if (cmp_chol(p->n, p->M, p->L)) return -1;
    p->mass_ready = 1;
    return 0;
}

/* Rows 0..rows-1 of A into C = A L⁻ᵀ (row i of C is L⁻¹ a_i), factored. */
static void factor(cmp_proj *p, int rows)
{
    const int n = p->n;
    for (int i = 0; i < rows; i++) {
        memcpy(p->C + (size_t)i * n, p->A + (size_t)i * n, (size_t)n * sizeof(double));
        cmp_trsv_lower(n, p->L, p->C + (size_t)i * n);
    }
    cmp_mnsolve_factor(&p->ms, rows, p->C, 0);
    p->factorizations++;
}

/* dx = L⁻ᵀ C⁺ r: the minimum-M-norm correction with A dx = r. */
static void correction(cmp_proj *p, const double *r, double *dx)
{
    cmp_mnsolve_apply(&p->ms, r, dx);
    cmp_trsv_lower_t(p->n, p->L, dx);
    p->solves++;
}

static double dot(int n, const double *a, const double *b)
{
    double s = 0;
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

static double norm2(int n, const double *a)
{
    return sqrt(dot(n, a, a));
}

/* Φ, A, b (holonomic rows, then nonholonomic), and b_v when want_bv. */
static int rows_at(cmp_proj *p, double t, const double *q, const double *v, int want_bv)
{
    const braun_system *s = p->sys;
    const int n = p->n, m = p->m;
    int st = 0;
    if (m > 0)
        st = cb(s->holonomic(t, q, v, p->phi, p->A, p->b, want_bv ? p->bv : NULL, s->user));
    if (!st && p->p > 0) {
        st = cb(s->nonholonomic(t, q, v, p->phi + m, p->A + (size_t)m * n,
                                want_bv ? p->bv + m : NULL, s->user));
        for (int k = m; k < p->mv; k++) p->b[k] = 0;
    }
    return st;
}

int cmp_proj_accel(cmp_proj *p, double t, const double *q, const double *v, double *a,
                   double *pc)
{
    const braun_system *s = p->sys;
    const int n = p->n, mv = p->mv;
    int st = mass(p, t, q);
    if (!st) st = cb(s->forces(t, q, v, p->Q, s->user));
    if (!st) st = rows_at(p, t, q, v, 1);
    if (st) return st;
    /* ã = L⁻¹Q; u = C⁺(b_v − C ã); a = L⁻ᵀ(ã + u). */
    double *at = p->x;
    memcpy(at, p->Q, (size_t)n * sizeof(double));
    cmp_trsv_lower(n, p->L, at);
    if (mv > 0) {
        factor(p, mv);
        for (int k = 0; k < mv; k++) p->r[k] = p->bv[k] - dot(n, p->C + (size_t)k * n, at);
        cmp_mnsolve_apply(&p->ms, p->r, a);
        p->solves++;
        for (int i = 0; i < n; i++) a[i] += at[i];
    } else {
        memcpy(a, at, (size_t)n * sizeof(double));
    }
    cmp_trsv_lower_t(n, p->L, a);
    if (pc) {
        /* vᵀ(M a − Q) = vᵀAᵀλ: the work of the constraint forces. */
        double w = 0;
        for (int i = 0; i < n; i++) w += v[i] * (dot(n, p->M + (size_t)i * n, a) - p->Q[i]);
        *pc = w;
    }
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i])) return 1;
    return 0;
}

int cmp_proj_power(cmp_proj *p, double t, const double *q, const double *v, double *P)
{
    const braun_system *s = p->sys;
    *P = 0;
    if (!(s->flags & BRAUN_ENERGY_INPUT) || !s->power) return 0;
    return cb(s->power(t, q, v, P, s->user));
}

int cmp_proj_positions(cmp_proj *p, double t, double *q, double *res)
{
    const braun_system *s = p->sys;
    const int n = p->n, m = p->m;
    if (res) *res = 0;
    if (m == 0) return 0;
    double *dx = p->x;
    /* Simplified Gauss–Newton: C at the predicted point, Φ at each iterate. */
    int st = mass(p, t, q);
    if (!st) st = cb(s->holonomic(t, q, NULL, p->phi, p->A, NULL, NULL, s->user));
    if (st) return -1;
    double r = norm2(m, p->phi);
    int it = 0;
    if (r > CMP_PROJ_TOL) factor(p, m);
    while (r > CMP_PROJ_TOL) {
        if (it == CMP_PROJ_MAX_ITER || !isfinite(r)) {
            if (res) *res = r;
            return -1;
        }
        for (int k = 0; k < m; k++) p->r[k] = -p->phi[k];
        correction(p, p->r, dx);
        for (int i = 0; i < n; i++) q[i] += dx[i];
        it++;
        p->iterations++;
        if (cb(s->holonomic(t, q, NULL, p->phi, NULL, NULL, NULL, s->user))) return -1;
        r = norm2(m, p->phi);
    }
    if (res) *res = r;
    return it;
}

int cmp_proj_velocities(cmp_proj *p, double t, const double *q, double *v)
{
    const int n = p->n, m = p->m, mv = p->mv;
    if (mv == 0) return 0;
    double *dv = p->x;
    int it = 0, factored = 0;
    for (;;) {
        if (rows_at(p, t, q, v, 0)) return -1;
        for (int k = 0; k < m; k++) p->r[k] = p->b[k] - dot(n, p->A + (size_t)k * n, v);
        for (int k = m; k < mv; k++) p->r[k] = -p->phi[k];
        const double r = norm2(mv, p->r);
        /* Relative to the speed: round-off of A v is ~ε‖A‖‖v‖. */
        if (r <= CMP_PROJ_TOL * (1.0 + norm2(n, v))) return it;
        if (it == CMP_PROJ_MAX_ITER || !isfinite(r)) return -1;
        if (!factored) {
            factor(p, mv);
            factored = 1;
        }
        correction(p, p->r, dv);
        for (int i = 0; i < n; i++) v[i] += dv[i];
        it++;
        p->iterations++;
    }
}

int cmp_proj_energy_of(cmp_proj *p, double t, const double *q, const double *v, double *E)
{
    const braun_system *s = p->sys;
    if (!s->energy) return -1;
    double dEdt;
    return cb(s->energy(t, q, v, E, NULL, p->dEdv, &dEdt, s->user)) ? -1 : 0;
}

int cmp_proj_energy(cmp_proj *p, double t, const double *q, double *v, double E_target)
{
    const braun_system *s = p->sys;
    const int n = p->n, mv = p->mv;
    if (!s->energy) return -1;
    if (mass(p, t, q)) return -1;
    if (mv > 0 && rows_at(p, t, q, v, 0)) return -1;
    double *dv = p->x;
    int it = 0;
    for (;;) {
        double E, dEdt;
        if (cb(s->energy(t, q, v, &E, NULL, p->dEdv, &dEdt, s->user))) return -1;
        const double e = E - E_target;
        if (fabs(e) <= CMP_PROJ_TOL * fmax(1.0, fabs(E_target)) || it == CMP_PROJ_MAX_ITER)
            return it;
        /* Rows [A; (∂E/∂v)ᵀ] with residual [0; E* − E]: the velocity rows
         * hold, the energy row moves. The energy row is dropped where it
         * depends on the others (no kinetic direction left): stop. */
        memcpy(p->A + (size_t)mv * n, p->dEdv, (size_t)n * sizeof(double));
        factor(p, mv + 1);
        if (p->ms.rank <= (mv > 0 ? mv : 0) && p->ms.rank < mv + 1) {
            int has_energy = 0;
            for (int j = 0; j < p->ms.rank; j++) has_energy |= p->ms.perm[j] == mv;
            if (!has_energy) return it;
        }
        for (int k = 0; k < mv; k++) p->r[k] = 0;
        p->r[mv] = -e;
        correction(p, p->r, dv);
        for (int i = 0; i < n; i++) v[i] += dv[i];
        it++;
        p->iterations++;
    }
}

/* The state of the integrator: q, v and the work integral W. */
static int deriv(cmp_proj *p, int input, double t, const double *q, const double *v, double *a,
                 double *dW)
{
    double pc = 0, P = 0;
    int st = cmp_proj_accel(p, t, q, v, a, input & 2 ? &pc : NULL);
    if (!st && (input & 1)) st = cmp_proj_power(p, t, q, v, &P);
    *dW = P + pc;
    return st;
}

static void fail(cmp_outcome *o, const char *name, double t, const char *what)
{
    snprintf(o->status_name, sizeof o->status_name, "%s", name);
    o->status = -1;
    o->t_reached = t;
    snprintf(o->detail, sizeof o->detail, "at t = %.9g (%s)", t, what);
}

/* "‖Φ_q‖ = 1.2e-3 after the iterations" */
static const char *residual_text(double r, char *buf, size_t size)
{
    snprintf(buf, size, "|Phi_q| = %.3g after %d iterations", r, CMP_PROJ_MAX_ITER);
    return buf;
}

int cmp_proj_integrate(const cmp_target *tg, double h, double T, long every, int energy,
                       cmp_proj_out_fn out, void *user, cmp_outcome *o)
{
    const braun_system *s = &tg->sys;
    const int n = s->n;
    memset(o, 0, sizeof *o);
    cmp_proj *p = cmp_proj_new(s);
    double *buf = malloc(12 * (size_t)n * sizeof(double));
    if (!p || !buf) {
        free(buf);
        cmp_proj_free(p);
        snprintf(o->status_name, sizeof o->status_name, "OUT_OF_MEMORY");
        o->status = -1;
        return -1;
    }
    double *q = buf, *v = q + n, *qs = v + n, *vs = qs + n, *k1 = vs + n, *k2 = k1 + n,
           *k3 = k2 + n, *k4 = k3 + n, *q1 = k4 + n, *v1 = q1 + n, *acc = v1 + n;
    /* Work of the applied forces (bit 1) and of moving constraints (bit 2). */
    const int input = ((s->flags & BRAUN_ENERGY_INPUT) ? 1 : 0) |
                      (!(s->flags & BRAUN_SCLERONOMIC) && s->m + s->p > 0 ? 2 : 0);
    const int use_energy = energy && s->energy;
    memcpy(q, tg->q0, (size_t)n * sizeof(double));
    memcpy(v, tg->v0, (size_t)n * sizeof(double));
    double t = 0, W = 0, E0 = 0, res = 0;
    char why[96];
    int rc = -1;
    if (cmp_proj_positions(p, 0, q, &res) < 0 || cmp_proj_velocities(p, 0, q, v) < 0) {
        fail(o, "PROJECTION_FAILED", 0, residual_text(res, why, sizeof why));
        goto done;
    }
    if (use_energy && cmp_proj_energy_of(p, 0, q, v, &E0)) {
        fail(o, "CALLBACK_FAILED", 0, "energy");
        goto done;
    }
    const long steps = (long)ceil(T / h - 1e-9 * T / h);
    if (cmp_proj_accel(p, t, q, v, acc, NULL)) {
        fail(o, "CALLBACK_FAILED", t, "acceleration");
        goto done;
    }
    if (out && out(t, q, v, acc, user)) {
        rc = 0;
        goto done;
    }
    for (long st = 1; st <= steps; st++) {
        /* t_s = s·h (the last step lands on T), as braun_integrate does. */
        const double t1 = st == steps ? T : (double)st * h, hs = t1 - t;
        double w1, w2, w3, w4;
        /* Stage velocities v2, v3, v4 are also the stages' q'. */
        double *v2 = q1, *v3 = v1, *v4 = vs;
        int bad = deriv(p, input, t, q, v, k1, &w1);
        for (int i = 0; i < n && !bad; i++) {
            qs[i] = q[i] + 0.5 * hs * v[i];
            v2[i] = v[i] + 0.5 * hs * k1[i];
        }
        if (!bad) bad = deriv(p, input, t + 0.5 * hs, qs, v2, k2, &w2);
        for (int i = 0; i < n && !bad; i++) {
            qs[i] = q[i] + 0.5 * hs * v2[i];
            v3[i] = v[i] + 0.5 * hs * k2[i];
        }
        if (!bad) bad = deriv(p, input, t + 0.5 * hs, qs, v3, k3, &w3);
        for (int i = 0; i < n && !bad; i++) {
            qs[i] = q[i] + hs * v3[i];
            v4[i] = v[i] + hs * k3[i];
        }
        if (!bad) bad = deriv(p, input, t1, qs, v4, k4, &w4);
        if (bad) {
            fail(o, bad > 0 ? "DIVERGED" : "CALLBACK_FAILED", t, "a stage of the step");
            goto done;
        }
        for (int i = 0; i < n; i++) {
            q[i] += hs / 6.0 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
            v[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        W += hs / 6.0 * (w1 + 2.0 * w2 + 2.0 * w3 + w4);
        t = t1;
        o->counts.steps++;
        o->counts.rhs_evals += 4;
        int finite = 1;
        for (int i = 0; i < n; i++) finite &= isfinite(q[i]) && isfinite(v[i]);
        if (!finite) {
            fail(o, "DIVERGED", t, "state not finite");
            goto done;
        }
        if (cmp_proj_positions(p, t, q, &res) < 0) {
            fail(o, "PROJECTION_FAILED", t, residual_text(res, why, sizeof why));
            goto done;
        }
        if (cmp_proj_velocities(p, t, q, v) < 0) {
            fail(o, "PROJECTION_FAILED", t, "velocity rows");
            goto done;
        }
        if (use_energy && cmp_proj_energy(p, t, q, v, E0 + W) < 0) {
            fail(o, "CALLBACK_FAILED", t, "energy");
            goto done;
        }
        if (st % every == 0 || st == steps) {
            if (out) {
                if (cmp_proj_accel(p, t, q, v, acc, NULL)) {
                    fail(o, "DIVERGED", t, "acceleration");
                    goto done;
                }
                if (out(t, q, v, acc, user)) break;
            }
        }
    }
    rc = 0;
done:
    if (rc == 0) {
        o->t_reached = t;
        snprintf(o->status_name, sizeof o->status_name, "OK");
    }
    cmp_proj_counts(p, &o->counts.lin_setups, &o->counts.lin_solves, &o->counts.iterations);
    free(buf);
    cmp_proj_free(p);
    return rc;
}

/* The method: samples on the output grid. */
typedef struct sink {
    cmp_traj *tr;
} sink;

static int to_traj(double t, const double *q, const double *v, const double *a, void *user)
{
    (void)a;
    sink *k = user;
    return cmp_traj_push(k->tr, t, q, v) ? 1 : 0;
}

void cmp_run_projection(const cmp_target *tg, const cmp_spec *spec, cmp_traj *tr,
                        cmp_outcome *out)
{
    cmp_traj_clear(tr);
    sink k = {tr};
    cmp_proj_integrate(tg, spec->h, spec->T, cmp_every(spec->dt_out, spec->h),
                       strcmp(spec->variant, "energy") == 0, to_traj, &k, out);
}
