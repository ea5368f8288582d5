/* A system's callbacks against finite differences of themselves, at one
 * state (braun_check_callbacks, braun_host.h). The library takes every
 * Jacobian, b-term and energy gradient as given and its corrections hide a
 * wrong one: a misprinted b_qv is removed step by step as "drift", a law
 * that disagrees with the forces is enforced (docs/api.md, section 6).
 * Five-point differences in double, step cbrt(ε)·max(s, |x|) with s the
 * coordinate's typical size (1 unless the caller gives them); each figure is
 * the largest difference beyond the differences' own round-off, over the
 * quantity's scale (so a quantity at rest is not judged by noise), each
 * entry made unit-free by its row's and column's sizes (judge). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_host.h"
#include "braun_c_locale.h"

typedef struct work {
    const braun_system *s;
    int n, m, p;
    braun_real *q, *v, *phi, *A, *b, *bv, *M, *Q, *dq, *dv; /* callback buffers */
    braun_real *Avals; /* a sparse system's compressed rows (else A itself) */
    double *f0, *fp;                                       /* scratch values */
    double *dir; /* ALONG_MOTION's direction in (t, q): n + 1 entries */
    double *size; /* the coordinates' typical sizes (the caller's, or 1 each) */
    braun_callback_report *rep;
    double tol;
    int named_fail; /* rep->worst names a figure above tol: the first one in
                     * the order checked (A_q before b_qv, whose differences
                     * go through A_q; the gradient before the rate) */
} work;

/* The precision the callbacks compute in: a float build's differences of
 * float values were judged by double's round-off, and correct callbacks
 * (the built-in models' too) failed by 2e-3. */
#ifdef BRAUN_SINGLE
#define REAL_EPS ((double)FLT_EPSILON)
#define DEFAULT_TOL 1e-3 /* what float differences resolve */
#else
#define REAL_EPS DBL_EPSILON
#define DEFAULT_TOL 1e-6
#endif

/* Coordinate k's typical size: the caller's, else 1 (a metre, a radian):
 * a 1 µm mechanism stepped by 6e-6 m was never resolved (a spring at its
 * rest length gave dE_dq off by 1 of its scale). Its velocity's: the same
 * number per second. */
static double size_of(const work *w, int k) { return w->size[k]; }

/* A step that resolves what varies on the coordinate's size and keeps its
 * own rounding (ε|x|) at ε^(2/3) of itself. */
static double fd_step(double x, double size)
{
    return cbrt(REAL_EPS) * (fabs(x) > size ? fabs(x) : size);
}

/* Time's own step: what a callback does in t varies on its own scale (a
 * drive's period), not on |t|'s — t = 1e6 gave steps of 6 s, across which
 * a sine drive of 1 rad/s is not resolved, and an error of 1e-2 in b_q hid
 * in the differences' spread. t's rounding (ε|t| in the callback's
 * arguments) sets the step instead: the rounding is (ε|t|)^(2/3) of it. */
static double time_step(double t) { return cbrt(REAL_EPS * (fabs(t) > 1 ? fabs(t) : 1)); }

/* Round-off of a central difference of values of size mag at step tau (a
 * bound, with room for cancellation inside the callback). */
static double roundoff(double mag, double tau) { return 1e2 * REAL_EPS * mag / tau; }

/* One figure: analytic x[k] against finite differences d[k] (rows x cols),
 * each difference with its round-off noise[k] (roundoff: its column's step,
 * its row's values — one bound for all, the smallest step's with the
 * largest values, took a 1 µm arm's Euler parameters' noise into its
 * lengths' columns and rows, and a misprint of 1e-4 there passed) and its
 * allowance (deriv_best; NULL: none). The scale is the largest entry
 * once each is made a number of one unit: times its column's size
 * col_size[j] (a coordinate's), over its row's size row_size[i] (NULL:
 * 1) — against the largest entry as given, a 1e6 m arm's Euler-parameter
 * columns (1e6 m) hid a misprint of 1e-4 in its lengths' (1). The worst
 * is kept in *fig and, when it is the report's worst so far, named. */
static void judge(work *w, double *fig, const char *name, int rows, int cols, const double *x,
                  const double *d, const double *allow, const double *noise, const double *row_size,
                  const double *col_size)
{
    const int count = rows * cols;
    double scale = 0, worst = 0;
    int at = -1;
#define WEIGHT(k) ((col_size ? col_size[(k) % cols] : 1) / (row_size ? row_size[(k) / cols] : 1))
    for (int k = 0; k < count; k++) {
        const double wk = WEIGHT(k);
        if (fabs(x[k]) * wk > scale) scale = fabs(x[k]) * wk;
        if (fabs(d[k]) * wk > scale) scale = fabs(d[k]) * wk;
    }
    for (int k = 0; k < count; k++) {
        /* What the differences cannot resolve is not held against the
         * callback: their round-off, and their allowance (deriv_best). */
        const double wk = WEIGHT(k), noise0 = noise[k];
        const double limit = noise0 + (allow ? allow[k] : 0);
        const double diff = fabs(x[k] - d[k]);
        const double e = (diff > limit ? diff - limit : (diff == diff ? 0 : diff)) * wk /
                         (scale + noise0 * wk + DBL_MIN);
        if (e > worst || (e != e)) {
            worst = e;
            at = k;
        }
    }
#undef WEIGHT
    if (worst > *fig || worst != worst) *fig = worst;
    const int fails = !(worst <= w->tol);
    if (at >= 0 && !w->named_fail && (fails || worst > w->rep->worst_value)) {
        w->rep->worst_value = worst;
        w->named_fail = fails;
        if (rows > 1 && cols > 1)
            snprintf(w->rep->worst, sizeof w->rep->worst, "%s[%d][%d]", name, at / cols, at % cols);
        else snprintf(w->rep->worst, sizeof w->rep->worst, "%s[%d]", name, at);
    }
}

/* A callback refused a point of the differences (or the state): named. */
static int failed(work *w, const char *which, int rc, double t)
{
    braun__c_snprintf(w->rep->worst, sizeof w->rep->worst, "%s callback returned %d at t = %.6g", which, rc, t);
    return -1;
}

/* The first entry of an output that is not finite (count entries; cols > 1:
 * a matrix of that many columns, named [row][col]): named in rep->worst as
 * "A_vv[0][1] is +Inf (nonholonomic callback at t = 0)". 0: all finite. */
static int nonfinite(work *w, const char *which, const char *name, const braun_real *x, int count,
                     int cols, double t)
{
    for (int k = 0; k < count; k++) {
        const double y = (double)x[k];
        if (isfinite(y)) continue;
        char entry[48];
        if (cols > 1) snprintf(entry, sizeof entry, "%s[%d][%d]", name, k / cols, k % cols);
        else snprintf(entry, sizeof entry, "%s[%d]", name, k);
        snprintf(w->rep->worst, sizeof w->rep->worst, "%s is %s (%s callback at t = %.6g)", entry,
                 y != y ? "NaN" : y > 0 ? "+Inf" : "-Inf", which, t);
        return 1;
    }
    return 0;
}

/* A sparse system's compressed rows (first..first+count−1 of the
 * structure): the first entry that is not finite, named by its row and
 * column in the dense matrix. */
static int nonfinite_sparse(work *w, const char *which, const char *name, int first, int count, double t)
{
    const braun_sparsity *sp = w->s->sparsity;
    const int base = sp->row_ptr[first];
    for (int i = 0; i < count; i++)
        for (int k = sp->row_ptr[first + i]; k < sp->row_ptr[first + i + 1]; k++) {
            const double y = (double)w->Avals[k - base];
            if (isfinite(y)) continue;
            snprintf(w->rep->worst, sizeof w->rep->worst, "%s[%d][%d] is %s (%s callback at t = %.6g)",
                     name, i, sp->col[k], y != y ? "NaN" : y > 0 ? "+Inf" : "-Inf", which, t);
            return 1;
        }
    return 0;
}

/* Every output of every callback at the state, before any difference: a
 * NaN or Inf is named as such (the differences of one gave a NaN figure
 * under some other entry's name, or none: an Inf column of A_vv read as
 * "within the round-off"), whatever the system's flags. */
static int check_finite(work *w, double t, const braun_real *q, const braun_real *v)
{
    const braun_system *s = w->s;
    const int n = w->n, m = w->m, p = w->p;
    const braun_real tt = (braun_real)t;
    const size_t nnz_q = s->sparsity ? (size_t)s->sparsity->row_ptr[m] : (size_t)m * n;
    const size_t nnz_v = s->sparsity ? (size_t)(s->sparsity->row_ptr[m + p] - s->sparsity->row_ptr[m])
                                     : (size_t)p * n;
    int rc;
    if (m > 0) {
        for (int i = 0; i < m; i++) w->phi[i] = w->b[i] = w->bv[i] = 0;
        for (size_t k = 0; k < nnz_q; k++) w->Avals[k] = 0;
        if ((rc = s->holonomic(tt, q, v, w->phi, w->Avals, w->b, w->bv, s->user)) != 0)
            return failed(w, "holonomic", rc, t), BRAUN_ERR_CALLBACK;
        if (nonfinite(w, "holonomic", "Phi_q", w->phi, m, 1, t) ||
            (s->sparsity ? nonfinite_sparse(w, "holonomic", "A_q", 0, m, t)
                         : nonfinite(w, "holonomic", "A_q", w->Avals, m * n, n, t)) ||
            nonfinite(w, "holonomic", "b_q", w->b, m, 1, t) ||
            nonfinite(w, "holonomic", "b_qv", w->bv, m, 1, t))
            return BRAUN_ERR_NONFINITE;
    }
    if (p > 0) {
        for (int i = 0; i < p; i++) w->phi[i] = w->bv[i] = 0;
        for (size_t k = 0; k < nnz_v; k++) w->Avals[k] = 0;
        if ((rc = s->nonholonomic(tt, q, v, w->phi, w->Avals, w->bv, s->user)) != 0)
            return failed(w, "nonholonomic", rc, t), BRAUN_ERR_CALLBACK;
        if (nonfinite(w, "nonholonomic", "Phi_v", w->phi, p, 1, t) ||
            (s->sparsity ? nonfinite_sparse(w, "nonholonomic", "A_vv", m, p, t)
                         : nonfinite(w, "nonholonomic", "A_vv", w->Avals, p * n, n, t)) ||
            nonfinite(w, "nonholonomic", "b_vv", w->bv, p, 1, t))
            return BRAUN_ERR_NONFINITE;
    }
    /* M: one block of n (dense), or the diagonal blocks one after another,
     * each named by its entry in the whole M. */
    if ((rc = s->mass(tt, q, w->M, s->user)) != 0) return failed(w, "mass", rc, t), BRAUN_ERR_CALLBACK;
    const int nblocks = s->sparsity ? s->sparsity->nblocks : 1;
    const braun_real *Mb = w->M;
    for (int k = 0, off = 0; k < nblocks; k++) {
        const int bsz = s->sparsity ? s->sparsity->block[k] : n;
        for (int i = 0; i < bsz * bsz; i++, Mb++) {
            const double y = (double)*Mb;
            if (isfinite(y)) continue;
            snprintf(w->rep->worst, sizeof w->rep->worst, "M[%d][%d] is %s (mass callback at t = %.6g)",
                     off + i / bsz, off + i % bsz, y != y ? "NaN" : y > 0 ? "+Inf" : "-Inf", t);
            return BRAUN_ERR_NONFINITE;
        }
        off += bsz;
    }
    if ((rc = s->forces(tt, q, v, w->Q, s->user)) != 0) return failed(w, "forces", rc, t), BRAUN_ERR_CALLBACK;
    if (nonfinite(w, "forces", "Q", w->Q, n, 1, t)) return BRAUN_ERR_NONFINITE;
    if (s->energy) {
        braun_real e = 0, dt = 0;
        if ((rc = s->energy(tt, q, v, &e, w->dq, w->dv, &dt, s->user)) != 0)
            return failed(w, "energy", rc, t), BRAUN_ERR_CALLBACK;
        if (nonfinite(w, "energy", "E", &e, 1, 1, t) || nonfinite(w, "energy", "dE_dq", w->dq, n, 1, t) ||
            nonfinite(w, "energy", "dE_dv", w->dv, n, 1, t) || nonfinite(w, "energy", "dE_dt", &dt, 1, 1, t))
            return BRAUN_ERR_NONFINITE;
    }
    if ((s->flags & BRAUN_ENERGY_INPUT) && s->power) {
        braun_real P = 0;
        if ((rc = s->power(tt, q, v, &P, s->user)) != 0) return failed(w, "power", rc, t), BRAUN_ERR_CALLBACK;
        if (nonfinite(w, "power", "P", &P, 1, 1, t)) return BRAUN_ERR_NONFINITE;
    }
    return BRAUN_OK;
}

/* A sparse system's compressed values of rows first..first+count−1 into
 * the first count rows of the dense w->A. */
static void scatter(work *w, int first, int count)
{
    const braun_sparsity *sp = w->s->sparsity;
    if (!sp) return;
    for (size_t k = 0; k < (size_t)count * w->n; k++) w->A[k] = 0;
    const int base = sp->row_ptr[first];
    for (int i = 0; i < count; i++)
        for (int k = sp->row_ptr[first + i]; k < sp->row_ptr[first + i + 1]; k++)
            w->A[(size_t)i * w->n + sp->col[k]] = w->Avals[k - base];
}

/* Φ_q (into out, m doubles) at (t, q); A_q, b_q, b_qv stay in w. */
/* phi_only: the differences of Φ_q need Φ_q alone — asked for alone, as the
 * library asks for what it needs (NULL outputs): a dense A of m·n entries
 * written at every point made the differences of a 1000-link chain O(n³)
 * (170 s; now a few). */
static int holonomic(work *w, double t, const braun_real *q, const braun_real *v, double *out, int phi_only)
{
    const int m = w->m;
    for (int i = 0; i < m; i++) w->phi[i] = w->b[i] = w->bv[i] = 0;
    const int rc = phi_only ? w->s->holonomic((braun_real)t, q, v, w->phi, NULL, NULL, NULL, w->s->user)
                            : w->s->holonomic((braun_real)t, q, v, w->phi, w->Avals, w->b, w->bv, w->s->user);
    if (rc) return failed(w, "holonomic", rc, t);
    if (!phi_only) scatter(w, 0, m);
    for (int i = 0; i < m; i++) out[i] = (double)w->phi[i];
    return 0;
}

/* g = A_q v − b_q at (t, q) for the velocity v: its derivative along
 * (1, v) in (t, q) at v̇ = 0 is −b_qv. */
static int hol_rate(work *w, double t, const braun_real *q, const braun_real *v, double *g)
{
    if (holonomic(w, t, q, v, g, 0)) return -1;
    for (int i = 0; i < w->m; i++) {
        double s = -(double)w->b[i];
        for (int j = 0; j < w->n; j++) s += (double)w->A[(size_t)i * w->n + j] * (double)v[j];
        g[i] = s;
    }
    return 0;
}

static int nonholonomic(work *w, double t, const braun_real *q, const braun_real *v, double *out)
{
    for (int i = 0; i < w->p; i++) w->phi[i] = w->bv[i] = 0;
    const int rc = w->s->nonholonomic((braun_real)t, q, v, w->phi, w->Avals, w->bv, w->s->user);
    if (rc) return failed(w, "nonholonomic", rc, t);
    scatter(w, w->m, w->p);
    for (int i = 0; i < w->p; i++) out[i] = (double)w->phi[i];
    return 0;
}

static int energy(work *w, double t, const braun_real *q, const braun_real *v, double *E)
{
    braun_real e = 0, dt = 0;
    const int rc = w->s->energy((braun_real)t, q, v, &e, w->dq, w->dv, &dt, w->s->user);
    if (rc) return failed(w, "energy", rc, t);
    *E = (double)e;
    return 0;
}

/* What is differenced, and along which line through (t0, q0, v0). */
enum quantity { PHI_Q, RATE_Q, PHI_V, ENERGY };
enum direction { ALONG_T, ALONG_Q, ALONG_V, ALONG_MOTION }; /* MOTION: w->dir, v fixed */

/* The quantity (count values into out) at parameter s on the line. */
static int value_at(work *w, enum quantity f, enum direction dir, int j, double s, double t0,
              const braun_real *q0, const braun_real *v0, double *out)
{
    const int n = w->n;
    double t = t0;
    memcpy(w->q, q0, sizeof(braun_real) * n);
    memcpy(w->v, v0, sizeof(braun_real) * n);
    switch (dir) {
    case ALONG_T: t += s; break;
    case ALONG_Q: w->q[j] = (braun_real)((double)q0[j] + s); break;
    case ALONG_V: w->v[j] = (braun_real)((double)v0[j] + s); break;
    case ALONG_MOTION:
        t += s * w->dir[0];
        for (int k = 0; k < n; k++)
            if (w->dir[1 + k] != 0) w->q[k] = (braun_real)((double)q0[k] + s * w->dir[1 + k]);
        break;
    }
    /* q and v are work copies: the callbacks get them, not the caller's. */
    braun_real *q = w->q, *v = w->v;
    switch (f) {
    case PHI_Q: return holonomic(w, t, q, v, out, 1);
    case RATE_Q: return hol_rate(w, t, q, v0, out);
    case PHI_V: return nonholonomic(w, t, q, v, out);
    case ENERGY: return energy(w, t, q, v, out);
    }
    return -1;
}

/* The derivative of the quantity along the line at s = 0: the five-point
 * stencil (f(−τ) − 8f(−τ/2) + 8f(τ/2) − f(τ))/(6τ), exact to O(τ⁴) —
 * a curvature on a length ℓ ≪ 1 leaves (τ/ℓ)⁴, not (τ/ℓ)². mag (count
 * entries): each entry's largest |f| seen, for its round-off bound (rows
 * in different units — a point's in m, a unit quaternion's in 1 — each by
 * its own: one bound for all hid a 1 µm arm's misprints in its point
 * rows behind its quaternion rows' values). spread (count entries, or
 * NULL): |that estimate − the same stencil at τ/2|, about its truncation
 * error — a quantity that varies on a scale below τ (a drive of 1e12 rad/s
 * against τ = 6e-6 s) is not resolved by the differences, and judge() does
 * not hold that against the callback. */
static int deriv(work *w, enum quantity f, enum direction dir, int j, double tau, double t0,
                 const braun_real *q0, const braun_real *v0, int count, double *out, double *spread,
                 double *mag)
{
    /* Points ±τ, ±τ/2 (the stencil at τ) and ±τ/4 (with ±τ/2, at τ/2). */
    static const double step[6] = {1, -1, 0.5, -0.5, 0.25, -0.25};
    static const double weight[6] = {-1, 1, 8, -8, 0, 0}, weight2[6] = {0, 0, -1, 1, 8, -8};
    const int points = spread ? 6 : 4;
    for (int i = 0; i < count; i++) {
        out[i] = 0;
        if (spread) spread[i] = 0;
    }
    for (int k = 0; k < points; k++) {
        if (value_at(w, f, dir, j, step[k] * tau, t0, q0, v0, w->fp)) return BRAUN_ERR_CALLBACK;
        for (int i = 0; i < count; i++) {
            out[i] += weight[k] * w->fp[i];
            if (spread) spread[i] += weight2[k] * w->fp[i];
            if (fabs(w->fp[i]) > mag[i]) mag[i] = fabs(w->fp[i]);
        }
    }
    for (int i = 0; i < count; i++) {
        out[i] /= 6 * tau;
        if (spread) spread[i] = fabs(out[i] - spread[i] / (3 * tau));
    }
    return BRAUN_OK;
}

/* The differences' points are rounded: t0 + s carries up to ε|t0|/2, and so
 * does every argument the callback forms from t (ωt + φ), so a difference
 * in t is no better than 3ε|t0|/τ of the derivative (the stencil's weights
 * 18/6) — at t = 1e9, τ = 6e-3, 1e-4 of it, which read as a wrong b_q of
 * 3e-2 once a finer step's noise was taken for a resolved estimate. The
 * same for a coordinate (ε|x|/τ of its move). The part of |out| allowed. */
static double rounding(const work *w, enum direction dir, int j, double t0, const braun_real *q0,
                       const braun_real *v0, double tau)
{
    double r = 0;
    switch (dir) {
    case ALONG_T: r = fabs(t0); break;
    case ALONG_Q: r = fabs((double)q0[j]); break;
    case ALONG_V: r = fabs((double)v0[j]); break;
    case ALONG_MOTION:
        r = w->dir[0] != 0 ? fabs(t0) : 0;
        for (int k = 0; k < w->n; k++)
            if (w->dir[1 + k] != 0 && fabs((double)q0[k] / w->dir[1 + k]) > r)
                r = fabs((double)q0[k] / w->dir[1 + k]);
        break;
    }
    return 4 * REAL_EPS * r / tau;
}

/* How an entry of deriv_best's estimates is named in the report: name[i]
 * (col < 0; i + offset) or name[i][col]. */
typedef struct entry_label {
    const char *name;
    int col, offset;
} entry_label;

/* An entry the central differences cannot judge because the callback is
 * not differentiable at the state — a kink, as a torsion3d's potential at
 * its wrap θ0 ± π, where the central difference gives the mean of the two
 * slopes: the one-sided differences (second order, step τ, each side's
 * points on that side) disagree with each other, and the analytic value x
 * is one of them. Then x is taken (*est = x) and the report's note names
 * the entry; 0 when it is not such a kink. */
static int kink(work *w, double x, double sign, double f0, double fp1, double fp2, double fm1,
                double fm2, double tau, double mag, const entry_label *lab, int i, double *est)
{
    const double up = sign * (-3 * f0 + 4 * fp1 - fp2) / tau, down = sign * (3 * f0 - 4 * fm1 + fm2) / tau;
    const double scale = fmax(fabs(x), fmax(fabs(up), fabs(down)));
    const double allow = 1e3 * REAL_EPS * mag / tau + w->tol * scale;
    if (!(fabs(up - down) > 100 * allow)) return 0;
    if (!(fabs(x - up) <= allow || fabs(x - down) <= allow)) return 0;
    *est = x;
    if (!w->rep->note[0]) {
        char entry[40];
        if (lab->col >= 0) snprintf(entry, sizeof entry, "%s[%d][%d]", lab->name, i, lab->col);
        else snprintf(entry, sizeof entry, "%s[%d]", lab->name, i + lab->offset);
        braun__c_snprintf(w->rep->note, sizeof w->rep->note,
                 "%s is not differentiable at this state (one-sided differences: from below "
                 "%.6g, from above %.6g; the callback gives %.6g)", entry, down, up, x);
    }
    return 1;
}

/* Some entry of sign·out disagrees with the callback's x beyond its
 * allowance and the tolerance. */
static int any_open(const work *w, int count, const double *x, int stride, double sign, const double *out,
                    const double *allow)
{
    for (int i = 0; i < count; i++) {
        const double xi = x[(size_t)i * stride], di = sign * out[i];
        const double scale = fabs(xi) > fabs(di) ? fabs(xi) : fabs(di);
        if (fabs(xi - di) - allow[i] > w->tol * scale) return 1;
    }
    return 0;
}

/* Each entry takes the estimate alt at `step` (its spread alt_spread,
 * magnitudes m, rounding rnd) where that one's allowance is the smaller
 * part of itself. */
static void take_better(int count, const double *alt, const double *alt_spread, const double *m, double step,
                        double rnd, double *out, double *allow)
{
    for (int i = 0; i < count; i++) {
        const double allow_alt = 2 * alt_spread[i] + roundoff(m[i], step) + rnd * fabs(alt[i]);
        if (allow_alt / (fabs(alt[i]) + DBL_MIN) < allow[i] / (fabs(out[i]) + DBL_MIN)) {
            out[i] = alt[i];
            allow[i] = allow_alt;
        }
    }
}

/* deriv at τ, its count entries compared with the analytic x[i·stride]
 * (as sign·out). Each estimate carries an allowance: twice its spread (the
 * stencil's truncation error at τ is 16/15 of it) plus the round-off at τ.
 * An entry that disagrees beyond it is tried again at τ/16, up to eight
 * times, and takes the estimate whose allowance is the smallest part of
 * itself — the one the differences resolve best. A quantity that varies on
 * a scale far below τ (a drive of 1e12 rad/s: τ = 6e-6 s spans 1e6 of its
 * periods) gives an estimate as large as its own spread, and a finer step
 * resolves it; a wrong callback disagrees with the resolved estimate (the
 * finer ones have more round-off: they are not taken). allow: each entry's
 * allowance, for judge(). */
static int deriv_best(work *w, enum quantity f, enum direction dir, int j, double tau, double t0,
                      const braun_real *q0, const braun_real *v0, int count, const double *x, int stride,
                      double sign, double *out, double *allow, double *mag, const entry_label *lab)
{
    double *alt = calloc(3 * (size_t)count + 1, sizeof(double)), *alt_spread = alt ? alt + count : NULL;
    if (!alt) return BRAUN_ERR_BUFFER;
    double *m = alt_spread + count; /* an estimate's magnitudes */
    int st = deriv(w, f, dir, j, tau, t0, q0, v0, count, out, allow, mag);
    const double rnd = rounding(w, dir, j, t0, q0, v0, tau);
    for (int i = 0; i < count && !st; i++)
        allow[i] = 2 * allow[i] + roundoff(mag[i], tau) + rnd * fabs(out[i]);
    double step = tau;
    for (int level = 0; level < 8 && !st; level++) {
        if (!any_open(w, count, x, stride, sign, out, allow)) break;
        step /= 16;
        memcpy(m, mag, sizeof *m * (size_t)count);
        st = deriv(w, f, dir, j, step, t0, q0, v0, count, alt, alt_spread, m);
        if (!st) take_better(count, alt, alt_spread, m, step, rounding(w, dir, j, t0, q0, v0, step), out, allow);
    }
    /* ... and at steps up to 16⁴ the first: a callback whose output moves
     * in quanta larger than the step (a drive's angle 1e12 + t: its ulp is
     * 1.2e-4, and at t ± 6e-6 every value is the same, a difference of 0
     * against a b_q of 1) is resolved only by a larger one. Taken as
     * above, by its allowance; a point the callback refuses (or its value
     * not finite) ends the search, not the check. */
    step = tau;
    for (int level = 0; level < 4 && !st; level++) {
        if (!any_open(w, count, x, stride, sign, out, allow)) break;
        step *= 16;
        memcpy(m, mag, sizeof *m * (size_t)count);
        char said[sizeof w->rep->worst];
        memcpy(said, w->rep->worst, sizeof said);
        if (deriv(w, f, dir, j, step, t0, q0, v0, count, alt, alt_spread, m)) {
            memcpy(w->rep->worst, said, sizeof said);
            break;
        }
        take_better(count, alt, alt_spread, m, step, rounding(w, dir, j, t0, q0, v0, step), out, allow);
    }
    /* Entries the differences still do not resolve: a kink at the state? */
    if (!st && any_open(w, count, x, stride, sign, out, allow)) {
        /* f(0), f(τ/2), f(τ), f(−τ/2), f(−τ) into alt-sized scratch. */
        double *v5 = calloc(5 * (size_t)count + 1, sizeof(double));
        if (!v5) {
            free(alt);
            return BRAUN_ERR_BUFFER;
        }
        static const double at[5] = {0, 0.5, 1, -0.5, -1};
        for (int k = 0; k < 5 && !st; k++) {
            if (value_at(w, f, dir, j, at[k] * tau, t0, q0, v0, w->fp)) st = BRAUN_ERR_CALLBACK;
            for (int i = 0; i < count && !st; i++) {
                v5[(size_t)k * count + i] = w->fp[i];
                if (fabs(w->fp[i]) > mag[i]) mag[i] = fabs(w->fp[i]);
            }
        }
        for (int i = 0; i < count && !st; i++) {
            const double xi = x[(size_t)i * stride], di = sign * out[i];
            const double scale = fabs(xi) > fabs(di) ? fabs(xi) : fabs(di);
            double est;
            if (fabs(xi - di) - allow[i] > w->tol * scale &&
                kink(w, xi, sign, v5[i], v5[count + i], v5[2 * (size_t)count + i],
                     v5[3 * (size_t)count + i], v5[4 * (size_t)count + i], tau, mag[i], lab, i, &est))
                out[i] = sign * est;
        }
        free(v5);
    }
    free(alt);
    return st;
}

/* The derivative along the motion (t, q) → (t + s, q + s v0), with each
 * coordinate moved by its own step: coordinate k wants s·|v_k| =
 * fd_step(q_k, its size), time s = time_step(t). One s for all (the largest
 * coordinate's) moved a bob at 10 m by 6 m when an unrelated body sat at
 * 1e6 m, and a sine drive's time by 6 s; the smallest for all rounds a
 * large coordinate's move (1e6 + 3e-6). So the direction is split into
 * groups whose steps lie within a factor 64 of each other, time one of
 * them, each differenced at its smallest step (its rounding at most 64
 * times the usual ε^(2/3)), and the derivative is their sum — one group
 * plus time for most states. A group's estimate is refined (deriv_best) against
 * the analytic value less the other groups' estimates. allow, out: as
 * deriv_best's; *tau_min: the smallest step. */
static int deriv_motion(work *w, enum quantity f, double t0, const braun_real *q0, const braun_real *v0,
                        int count, const double *x, double sign, double *out, double *allow, double *mag,
                        const entry_label *lab, double *tau_min)
{
    const int n = w->n;
    double *nat = calloc((size_t)(n + 1) * 3 + 1 + 3 * (size_t)count + 1, sizeof(double));
    if (!nat) return BRAUN_ERR_BUFFER;
    double *sorted = nat + n + 1, *lows = sorted + n + 1, *est = lows + n + 2, *spr = est + count,
           *xg = spr + count;
    /* Each one's natural step (0: it does not move). Time is a group of its
     * own: a drive whose output moves in quanta larger than the step (an
     * angle 1e12 + t) gives 0 in t, which the coordinates' share of the
     * same differences made look resolved; alone, deriv_best takes it to a
     * larger step. */
    int k = 0;
    nat[0] = time_step(t0);
    for (int i = 0; i < n; i++) {
        const double vi = fabs((double)v0[i]), si = vi > 0 ? fd_step((double)q0[i], size_of(w, i)) / vi : 0;
        nat[1 + i] = si > 0 && si < 1e300 ? si : 0; /* a motion below what differences see */
        if (nat[1 + i] > 0) sorted[k++] = nat[1 + i];
    }
    for (int a = 1; a < k; a++) /* insertion sort: n is small next to the differences' cost */
        for (int b = a; b > 0 && sorted[b] < sorted[b - 1]; b--) {
            const double tmp = sorted[b];
            sorted[b] = sorted[b - 1];
            sorted[b - 1] = tmp;
        }
    /* The groups' lower ends into lows[0..groups); group 0 is time's. */
    int groups = 0;
    lows[groups++] = nat[0];
    for (int a = 0; a < k;) {
        const double lo = sorted[a];
        lows[groups++] = lo;
        while (a < k && sorted[a] <= 64 * lo) a++;
    }
    *tau_min = groups > 1 && lows[1] < nat[0] ? lows[1] : nat[0];
    for (int i = 0; i < count; i++) out[i] = allow[i] = 0;
    int st = BRAUN_OK;
    for (int pass = 0; pass < 2 && !st; pass++) {
        if (pass == 1 && groups == 1) break;
        for (int g = 0; g < groups && !st; g++) {
            const double lo = lows[g], hi = g + 1 < groups ? lows[g + 1] : HUGE_VAL;
            w->dir[0] = g == 0;
            for (int i = 1; i <= n; i++)
                w->dir[i] = g > 0 && nat[i] >= lo && nat[i] < hi ? (double)v0[i - 1] : 0;
            /* Pass 0: every group's plain estimate (one group: refined at
             * once); pass 1: each refined against the rest. */
            if (pass == 0 && groups > 1) {
                st = deriv(w, f, ALONG_MOTION, 0, lo, t0, q0, v0, count, est, spr, mag);
                for (int i = 0; i < count && !st; i++) {
                    out[i] += est[i];
                    allow[i] += 2 * spr[i] + roundoff(mag[i], lo);
                }
                continue;
            }
            /* This group's share of out and allow, taken out and refined. */
            if (groups > 1) {
                st = deriv(w, f, ALONG_MOTION, 0, lo, t0, q0, v0, count, est, spr, mag);
                for (int i = 0; i < count && !st; i++) {
                    out[i] -= est[i];
                    allow[i] -= 2 * spr[i] + roundoff(mag[i], lo);
                    if (allow[i] < 0) allow[i] = 0;
                }
            }
            for (int i = 0; i < count && !st; i++) xg[i] = x[i] - sign * out[i];
            if (!st) st = deriv_best(w, f, ALONG_MOTION, 0, lo, t0, q0, v0, count, xg, 1, sign, est, spr,
                                     mag, lab);
            for (int i = 0; i < count && !st; i++) {
                out[i] += est[i];
                allow[i] += spr[i];
            }
        }
    }
    free(nat);
    return st;
}

/* The rows of one kind: the Jacobian (holonomic in q, nonholonomic in v),
 * b_q (holonomic: −∂Φ_q/∂t) and the acceleration term (−d/dt of
 * A_q v − b_q, resp. of Φ_v, along the motion at v̇ = 0). */
static int check_rows(work *w, int nonholo, double t, const braun_real *q0, const braun_real *v0)
{
    const int n = w->n, r = nonholo ? w->p : w->m;
    const enum quantity f = nonholo ? PHI_V : PHI_Q;
    double *A = calloc((size_t)r * n * 4 + 10 * (size_t)r + 1, sizeof(double));
    if (!A) return BRAUN_ERR_BUFFER;
    double *fd = A + (size_t)r * n, *b = fd + (size_t)r * n, *bv = b + r, *col = bv + r, *g0 = col + r;
    double *spread = g0 + r, *spcol = spread + (size_t)r * n, *noise = spcol + r;
    double *row_size = noise + (size_t)r * n, *row_term = row_size + r, *mag = row_term + r,
           *mj = mag + r, *m2 = mj + r;
    int st = nonholo ? nonholonomic(w, t, q0, v0, g0) : holonomic(w, t, q0, v0, g0, 0);
    if (st) st = BRAUN_ERR_CALLBACK;
    if (!st) {
        for (size_t k = 0; k < (size_t)r * n; k++) A[k] = (double)w->A[k];
        for (int i = 0; i < r; i++) {
            b[i] = nonholo ? 0 : (double)w->b[i];
            bv[i] = (double)w->bv[i];
        }
    }
    /* Each row's size, Σ_j |A_ij| s_j, and its largest term |A_ij| x_j
     * (x_j: |q_j|, or |v_j|, or s_j if larger; in the row's own unit: m for
     * a point's row, 1 for a unit quaternion's): its entries are judged
     * over its size (a row with none: the largest), and its largest term is
     * what the callback's sum may cancel (a point row is 0 at the state,
     * its round-off that of its points' positions). */
    double largest = 0;
    for (int i = 0; i < r; i++) {
        double sum = 0, term = 0;
        for (int j = 0; j < n; j++) {
            const double a = fabs(A[(size_t)i * n + j]);
            const double x = fabs(nonholo ? (double)v0[j] : (double)q0[j]);
            sum += a * size_of(w, j);
            term = fmax(term, a * fmax(x, size_of(w, j)));
        }
        row_size[i] = sum;
        row_term[i] = term;
        largest = fmax(largest, sum);
        mag[i] = fabs(g0[i]) + term;
    }
    for (int i = 0; i < r; i++)
        if (!(row_size[i] > 0)) row_size[i] = largest > 0 ? largest : 1;
    /* Each difference's round-off at its column's own step, from the
     * values its row saw there and the row's largest term (the largest step
     * let the noise of a small coordinate's column count as a callback's
     * error; the smallest for all, with every row's values, hid a misprint
     * in a 1 µm mechanism's lengths). mag: each row's largest value in any
     * column (b_q starts from it). */
    for (int j = 0; j < n && !st; j++) {
        const double x = nonholo ? (double)v0[j] : (double)q0[j], tau = fd_step(x, size_of(w, j));
        const entry_label lab = {nonholo ? "A_vv" : "A_q", j, 0};
        for (int i = 0; i < r; i++) mj[i] = fabs(g0[i]) + row_term[i];
        st = deriv_best(w, f, nonholo ? ALONG_V : ALONG_Q, j, tau, t, q0, v0, r, A + j, n, 1, col, spcol,
                        mj, &lab);
        for (int i = 0; i < r && !st; i++) {
            fd[(size_t)i * n + j] = col[i];
            spread[(size_t)i * n + j] = spcol[i];
            noise[(size_t)i * n + j] = roundoff(mj[i], tau);
            mag[i] = fmax(mag[i], mj[i]);
        }
    }
    if (!st)
        judge(w, nonholo ? &w->rep->jacobian_v : &w->rep->jacobian_q, nonholo ? "A_vv" : "A_q", r, n,
              A, fd, spread, noise, row_size, w->size);
    if (!st && !nonholo) {
        const double tt = time_step(t);
        memcpy(m2, mag, sizeof *m2 * (size_t)r);
        const entry_label lab = {"b_q", -1, 0};
        st = deriv_best(w, PHI_Q, ALONG_T, 0, tt, t, q0, v0, r, b, 1, -1, col, spcol, m2, &lab);
        for (int i = 0; i < r && !st; i++) {
            col[i] = -col[i];
            noise[i] = roundoff(m2[i], tt);
        }
        if (!st) judge(w, &w->rep->b_q, "b_q", r, 1, b, col, spcol, noise, row_size, NULL);
    }
    if (!st) {
        double tv = 0, *gmag = m2; /* each row's terms of A v − b (Φ_v) */
        for (int i = 0; i < r; i++) {
            double terms = fabs(b[i]) + fabs(g0[i]);
            for (int j = 0; j < n; j++) terms += fabs(A[(size_t)i * n + j] * (double)v0[j]);
            gmag[i] = terms;
        }
        const entry_label lab = {nonholo ? "b_vv" : "b_qv", -1, 0};
        st = deriv_motion(w, nonholo ? PHI_V : RATE_Q, t, q0, v0, r, bv, -1, col, spcol, gmag, &lab, &tv);
        for (int i = 0; i < r && !st; i++) {
            col[i] = -col[i];
            noise[i] = roundoff(gmag[i], tv);
        }
        if (!st) judge(w, nonholo ? &w->rep->b_vv : &w->rep->b_qv, nonholo ? "b_vv" : "b_qv", r, 1, bv,
                       col, spcol, noise, row_size, NULL);
    }
    free(A);
    return st;
}

/* BRAUN_SCLERONOMIC promises that the ideal constraint forces do no work;
 * a nonholonomic row's force λ·A_vv does λ(A_vv v − Φ_v) — zero only for a
 * row homogeneous in v, Φ_v = A_vv v. A row with a term c(q) (a ball on a
 * turntable: v − Rω + W×r) passed every difference while the flag dropped
 * that work and its energy law ran the ball 1 m wrong. At the state:
 * |Φ_v − A_vv v| over its terms' magnitudes, each row. */
static int check_homogeneous(work *w, double t, const braun_real *q, const braun_real *v)
{
    const int n = w->n, p = w->p;
    double *g = calloc((size_t)p + 1, sizeof(double));
    if (!g) return BRAUN_ERR_BUFFER;
    if (nonholonomic(w, t, q, v, g)) {
        free(g);
        return BRAUN_ERR_CALLBACK;
    }
    double worst = 0, value = 0;
    int at = -1;
    for (int i = 0; i < p; i++) {
        double r = g[i], scale = fabs(g[i]);
        for (int j = 0; j < n; j++) {
            const double a = (double)w->A[(size_t)i * n + j] * (double)v[j];
            r -= a;
            scale += fabs(a);
        }
        /* Round-off of the sum: a few ε of its terms (as the figures). */
        const double e = fabs(r) > 1e2 * REAL_EPS * scale ? fabs(r) / (scale + DBL_MIN) : 0;
        if (e > worst) {
            worst = e;
            value = r;
            at = i;
        }
    }
    free(g);
    w->rep->homogeneous_v = worst;
    const int fails = !(worst <= w->tol);
    if (at >= 0 && !w->named_fail && (fails || worst > w->rep->worst_value)) {
        w->rep->worst_value = worst;
        w->named_fail = fails;
        if (fails)
            snprintf(w->rep->worst, sizeof w->rep->worst,
                     "Phi_v[%d] - A_vv[%d] v = %.6g at this state: BRAUN_SCLERONOMIC needs each "
                     "nonholonomic row homogeneous in v", at, at, value);
        else snprintf(w->rep->worst, sizeof w->rep->worst, "Phi_v[%d] - A_vv[%d] v", at, at);
    }
    return BRAUN_OK;
}

/* dE_dq, dE_dv, dE_dt against differences of E. */
static int check_energy_gradient(work *w, double t, const braun_real *q0, const braun_real *v0)
{
    const int n = w->n;
    double *g = calloc(8 * (size_t)n + 4, sizeof(double));
    if (!g) return BRAUN_ERR_BUFFER;
    double *fd = g + 2 * n + 1, *spread = fd + 2 * n + 1, *taus = spread + 2 * n + 1, E0 = 0;
    braun_real e = 0, dt = 0;
    const int rc = w->s->energy((braun_real)t, q0, v0, &e, w->dq, w->dv, &dt, w->s->user);
    int st = rc ? (failed(w, "energy", rc, t), BRAUN_ERR_CALLBACK) : BRAUN_OK;
    if (!st) {
        E0 = (double)e;
        for (int j = 0; j < n; j++) {
            g[j] = (double)w->dq[j];
            g[n + j] = (double)w->dv[j];
        }
        g[2 * n] = (double)dt;
    }
    /* Each entry's step sets its round-off bound (check_rows): with the
     * smallest over q and v together, a velocity of 1e6 made the steps in v
     * 1e6 times those in q, and E's round-off in dE_dq's differences read
     * as a wrong gradient; with the smallest over q, a 1 µm arm's lengths
     * set its Euler parameters'. E's values: the largest any saw. */
    double mag = fabs(E0);
    for (int j = 0; j < 2 * n && !st; j++) {
        const int in_v = j >= n, k = in_v ? j - n : j;
        const double tau = fd_step(in_v ? (double)v0[k] : (double)q0[k], size_of(w, k));
        taus[j] = tau;
        const entry_label lab = {in_v ? "dE_dv" : "dE_dq", -1, k};
        st = deriv_best(w, ENERGY, in_v ? ALONG_V : ALONG_Q, k, tau, t, q0, v0, 1, g + j, 1, 1, fd + j,
                        spread + j, &mag, &lab);
    }
    const double tt = time_step(t);
    double mt = mag;
    const entry_label lab_t = {"dE_dt", -1, 0};
    if (!st)
        st = deriv_best(w, ENERGY, ALONG_T, 0, tt, t, q0, v0, 1, g + 2 * n, 1, 1, fd + 2 * n,
                        spread + 2 * n, &mt, &lab_t);
    if (!st) {
        for (int j = 0; j < 2 * n; j++) taus[j] = roundoff(mag, taus[j]);
        taus[2 * n] = roundoff(mt, tt);
        judge(w, &w->rep->energy_gradient, "dE_dq", 1, n, g, fd, spread, taus, NULL, w->size);
        judge(w, &w->rep->energy_gradient, "dE_dv", 1, n, g + n, fd + n, spread + n, taus + n, NULL, w->size);
        judge(w, &w->rep->energy_gradient, "dE_dt", 1, 1, g + 2 * n, fd + 2 * n, spread + 2 * n, taus + 2 * n,
              NULL, NULL);
    }
    free(g);
    return st;
}

/* The sizes the residuals are judged against: ‖Σ_j |A_ij| max(|q_j|, s_j)‖
 * over the holonomic rows, and ‖Σ_j |A_ij| max(|v_j|, s_j) + |b_i|‖ over
 * them and the nonholonomic rows (|Φ_v,i| in b's place), s_j the
 * coordinates' sizes (per second for v) — each in its rows' units. An
 * absolute 1e-8 (1 + max|q|) judged a 1 µm pendulum 1e-3 off its rod (its
 * residual 2e-14 m²) as on it. */
static int row_terms(work *w, double t, const braun_real *q, const braun_real *v, double *pos,
                     double *vel)
{
    const int n = w->n;
    double p2 = 0, v2 = 0;
    for (int kind = 0; kind < 2; kind++) {
        const int r = kind ? w->p : w->m;
        if (r == 0) continue;
        double *g = calloc((size_t)r + 1, sizeof(double));
        if (!g) return BRAUN_ERR_BUFFER;
        const int rc = kind ? nonholonomic(w, t, q, v, g) : holonomic(w, t, q, v, g, 0);
        for (int i = 0; i < r && !rc; i++) {
            double tq = 0, tv = kind ? fabs(g[i]) : fabs((double)w->b[i]);
            for (int j = 0; j < n; j++) {
                const double a = fabs((double)w->A[(size_t)i * n + j]), sz = size_of(w, j);
                tq += a * fmax(fabs((double)q[j]), sz);
                tv += a * fmax(fabs((double)v[j]), sz);
            }
            if (!kind) p2 += tq * tq;
            v2 += tv * tv;
        }
        free(g);
        if (rc) return BRAUN_ERR_CALLBACK;
    }
    *pos = sqrt(p2);
    *vel = sqrt(v2);
    return BRAUN_OK;
}

/* dE/dt along the ideal motion against Ė = power + Q_c·v (the library's
 * input rate on the constraints), at a state on the constraints:
 * |∂E/∂q·v + ∂E/∂v·v̇ + ∂E/∂t − P − Q_c·v| over the sum of the terms'
 * magnitudes, Q_c = M v̇ − Q. */
static int check_energy_rate(work *w, double t, const braun_real *q0, const braun_real *v0)
{
    const braun_system *s = w->s;
    const int n = w->n;
    braun_model model;
    int st = braun_model_init(&model, s);
    if (st) return st;
    model.opt.corrections = BRAUN_CORRECT_NONE;
    model.opt.guard = -1;
    const size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes);
    braun_real *vdot = calloc(2 * (size_t)n, sizeof(braun_real));
    braun_data d;
    if (!buf || !vdot) st = BRAUN_ERR_BUFFER;
    if (!st) st = braun_data_init(&d, &model, buf, bytes);
    int inited = !st;
    braun_real pos = 0, vel = 0;
    if (!st) st = braun_set_state(&d, (braun_real)t, q0, v0);
    if (!st) st = braun_residuals(&d, (braun_real)t, q0, v0, &pos, &vel, NULL);
    if (!st) st = braun_eval(&d, (braun_real)t, q0, v0, 0, vdot + n, vdot);
    /* The library's own refusal (a BRAUN_MASS_CONSTANT that does not
     * hold, a non-SPD M, ...): its sentence. */
    if (st && inited && !w->named_fail) braun_error_format(&d, w->rep->worst, sizeof w->rep->worst);
    if (inited) braun_data_release(&d);
    double pos_terms = 0, vel_terms = 0;
    if (!st) st = row_terms(w, t, q0, v0, &pos_terms, &vel_terms);
    w->rep->state_residual = (double)pos + (double)vel;
    const double on = 1e-8 * sqrt(REAL_EPS / DBL_EPSILON); /* 1e-8 in double, 2.3e-4 in float */
    if (!st && ((double)pos > on * pos_terms || (double)vel > on * vel_terms)) {
        /* Off the constraints the identity does not hold: not judged. */
        w->rep->energy_rate = NAN;
        free(buf);
        free(vdot);
        return BRAUN_OK;
    }
    braun_real P = 0, e = 0, dt = 0;
    int rc = 0;
    if (!st && (rc = s->mass((braun_real)t, q0, w->M, s->user)) != 0)
        st = (failed(w, "mass", rc, t), BRAUN_ERR_CALLBACK);
    if (!st && (rc = s->forces((braun_real)t, q0, v0, w->Q, s->user)) != 0)
        st = (failed(w, "forces", rc, t), BRAUN_ERR_CALLBACK);
    if (!st && (s->flags & BRAUN_ENERGY_INPUT) && (rc = s->power((braun_real)t, q0, v0, &P, s->user)) != 0)
        st = (failed(w, "power", rc, t), BRAUN_ERR_CALLBACK);
    if (!st && (rc = s->energy((braun_real)t, q0, v0, &e, w->dq, w->dv, &dt, s->user)) != 0)
        st = (failed(w, "energy", rc, t), BRAUN_ERR_CALLBACK);
    if (!st) {
        double delta = (double)dt - (double)P, scale = fabs((double)dt) + fabs((double)P);
        /* Q_c = M v̇ − Q over M's diagonal blocks, each row-major (a dense
         * M: one block of n). */
        const braun_real *Mb = w->M;
        const int nblocks = s->sparsity ? s->sparsity->nblocks : 1;
        for (int k = 0, off = 0; k < nblocks; k++) {
            const int bsz = s->sparsity ? s->sparsity->block[k] : n;
            for (int i = 0; i < bsz; i++) {
                double qc = -(double)w->Q[off + i];
                for (int j = 0; j < bsz; j++) qc += (double)*Mb++ * (double)vdot[off + j];
                w->f0[off + i] = qc;
            }
            off += bsz;
        }
        for (int i = 0; i < n; i++) {
            const double a = (double)w->dq[i] * (double)v0[i], b = (double)w->dv[i] * (double)vdot[i],
                         c = w->f0[i] * (double)v0[i];
            delta += a + b - c;
            scale += fabs(a) + fabs(b) + fabs(c);
        }
        const double r = scale > 0 ? fabs(delta) / scale : 0;
        w->rep->energy_rate = r;
        if (!w->named_fail && (r > w->rep->worst_value || !(r <= w->tol))) {
            w->rep->worst_value = r;
            w->named_fail = !(r <= w->tol);
            snprintf(w->rep->worst, sizeof w->rep->worst, "energy rate");
        }
    }
    free(buf);
    free(vdot);
    return st;
}

int braun_check_callbacks(const braun_system *sys, braun_real t, const braun_real *q,
                          const braun_real *v, double tol, braun_callback_report *rep)
{
    return braun_check_callbacks_sized(sys, t, q, v, NULL, tol, rep);
}

int braun_check_callbacks_sized(const braun_system *sys, braun_real t, const braun_real *q,
                                const braun_real *v, const braun_real *size, double tol,
                                braun_callback_report *rep)
{
    if (!rep) return BRAUN_ERR_ARGUMENT;
    memset(rep, 0, sizeof *rep);
    rep->energy_rate = NAN;
    /* rep->worst always says what failed, a NULL argument too. */
    if (!sys || !q || !v) {
        snprintf(rep->worst, sizeof rep->worst, "%s (NULL)", !sys ? "system" : !q ? "state q" : "state v");
        return BRAUN_ERR_ARGUMENT;
    }
    /* A size steps by itself: positive and finite. */
    for (int i = 0; size && i < sys->n; i++)
        if (!((double)size[i] > 0) || !isfinite((double)size[i])) {
            snprintf(rep->worst, sizeof rep->worst, "size[%d] (must be finite and > 0)", i);
            return BRAUN_ERR_ARGUMENT;
        }
    /* A state the differences can use: finite. */
    if (!isfinite((double)t)) {
        snprintf(rep->worst, sizeof rep->worst, "state t");
        return BRAUN_ERR_NONFINITE;
    }
    for (int i = 0; i < sys->n; i++)
        if (!isfinite((double)q[i]) || !isfinite((double)v[i])) {
            snprintf(rep->worst, sizeof rep->worst, "state %s[%d]", isfinite((double)q[i]) ? "v" : "q", i);
            return BRAUN_ERR_NONFINITE;
        }
    const char *problem = NULL;
    int st = braun_system_check(sys, &problem);
    if (st) {
        snprintf(rep->worst, sizeof rep->worst, "%s", problem ? problem : "invalid system");
        return st;
    }
    work w = {0};
    w.s = sys;
    w.n = sys->n;
    w.m = sys->m;
    w.p = sys->p;
    w.rep = rep;
    w.tol = tol > 0 ? tol : DEFAULT_TOL;
    const int n = sys->n, rows = sys->m + sys->p + 1;
    const size_t mass = sys->sparsity ? 0 : (size_t)n * n;
    size_t mblocks = 0;
    if (sys->sparsity)
        for (int k = 0; k < sys->sparsity->nblocks; k++)
            mblocks += (size_t)sys->sparsity->block[k] * (size_t)sys->sparsity->block[k];
    const size_t nnz = sys->sparsity ? (size_t)sys->sparsity->row_ptr[sys->m + sys->p] : 0;
    braun_real *r = calloc(4 * (size_t)n + 3 * (size_t)rows + (size_t)rows * n + mass + mblocks +
                               (size_t)n + nnz + 1,
                           sizeof(braun_real));
    double *f = calloc(2 * (size_t)(rows + n) + 2 * (size_t)n + 2, sizeof(double)); /* f0, fp, dir, size */
    if (!r || !f) {
        free(r);
        free(f);
        return BRAUN_ERR_BUFFER;
    }
    w.q = r;
    w.v = w.q + n;
    w.dq = w.v + n;
    w.dv = w.dq + n;
    w.phi = w.dv + n;
    w.b = w.phi + rows;
    w.bv = w.b + rows;
    w.A = w.bv + rows;
    w.M = w.A + (size_t)rows * n;
    w.Q = w.M + mass + mblocks;
    w.Avals = sys->sparsity ? w.Q + n : w.A;
    w.f0 = f;
    w.fp = f + rows + n;
    w.dir = w.fp + rows + n;
    w.size = w.dir + n + 1;
    for (int i = 0; i < n; i++) w.size[i] = size ? (double)size[i] : 1;
    st = check_finite(&w, (double)t, q, v);
    if (!st && sys->m > 0) st = check_rows(&w, 0, (double)t, q, v);
    if (!st && sys->p > 0) st = check_rows(&w, 1, (double)t, q, v);
    if (!st && sys->p > 0 && (sys->flags & BRAUN_SCLERONOMIC)) st = check_homogeneous(&w, (double)t, q, v);
    if (!st && sys->energy) st = check_energy_gradient(&w, (double)t, q, v);
    if (!st && sys->energy) st = check_energy_rate(&w, (double)t, q, v);
    free(r);
    free(f);
    if (st) {
        if (st == BRAUN_ERR_CALLBACK && !strstr(rep->worst, "callback"))
            snprintf(rep->worst, sizeof rep->worst, "a callback failed");
        return st;
    }
    /* Every difference exactly 0 names no entry: say so, not "". */
    if (!rep->worst[0]) snprintf(rep->worst, sizeof rep->worst, "none (every difference within the round-off of the differences)");
    return w.named_fail ? BRAUN_ERR_ARGUMENT : BRAUN_OK;
}
