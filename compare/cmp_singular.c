/* Where IDA fails, and why: kinematic singularities of a target and the
 * size of the Lagrange multipliers near them (docs/compare.md, "IDA near
 * singular configurations"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cmp.h"
#include "braun_reference.h"

#define PI 3.14159265358979323846

/* M, A_q, Q, b_qv at (q, v) into the caller's arrays. */
static int rows_at(const cmp_target *tg, double t, const double *q, const double *v, double *M,
                   double *A, double *Q, double *bv)
{
    const braun_system *s = &tg->sys;
    if (s->m < 1 || !s->holonomic) return -1;
    double *phi = malloc(2 * (size_t)s->m * sizeof(double));
    if (!phi) return -1;
    int st = s->mass(t, q, M, s->user);
    if (!st && Q) st = s->forces(t, q, v, Q, s->user);
    if (!st) st = s->holonomic(t, q, v, phi, A, phi + s->m, bv, s->user);
    free(phi);
    return st;
}

double cmp_target_sigma(const cmp_target *tg, double t, const double *q)
{
    const int n = tg->sys.n, m = tg->sys.m;
    if (m < 1) return NAN;
    double *M = malloc(((size_t)n * n + (size_t)m * n + n) * sizeof(double));
    if (!M) return NAN;
    double *A = M + (size_t)n * n, *v = A + (size_t)m * n;
    for (int i = 0; i < n; i++) v[i] = 0;
    double r = rows_at(tg, t, q, v, M, A, NULL, NULL) ? NAN : cmp_sigma_ratio(n, m, M, A);
    free(M);
    return r;
}

int cmp_singularity_scan(const cmp_target *tg, FILE *f)
{
    const braun_builtin *b = tg->builtin;
    const int n = tg->sys.n, m = tg->sys.m;
    if (!b || !braun_minimal_find(b->name)->to_state || braun_minimal_find(b->name)->dim != 2 || m < 1) return -1;
    const size_t sz = (size_t)n * n + (size_t)m * n + 4 * (size_t)n + 2 * (size_t)m;
    double *M = malloc(sz * sizeof(double));
    if (!M) return -1;
    double *A = M + (size_t)n * n, *q = A + (size_t)m * n, *v = q + n, *Q = v + n,
           *acc = Q + n, *bv = acc + n, *lam = bv + m;
    enum { STEPS = 3600 };
    double prev2 = NAN, prev = NAN;
    int found = 0;
    for (int k = 0; k <= STEPS + 1; k++) {
        const double th = -PI + 2.0 * PI * (double)k / STEPS;
        double y[2] = {th, 0.0};
        braun_minimal_find(b->name)->to_state(y, q, v, b->sys.user);
        double r = rows_at(tg, 0, q, v, M, A, NULL, NULL) ? NAN : cmp_sigma_ratio(n, m, M, A);
        /* A local minimum of the ratio at the previous angle: refine it by
         * golden-section search, then look at the multipliers beside it. */
        if (k >= 2 && prev < prev2 && prev <= r && prev < 1e-3) {
            double lo = th - 2.0 * (2.0 * PI / STEPS), hi = th;
            for (int it = 0; it < 80; it++) {
                double a = lo + 0.381966 * (hi - lo), c = hi - 0.381966 * (hi - lo);
                double ya[2] = {a, 0}, yc[2] = {c, 0};
                braun_minimal_find(b->name)->to_state(ya, q, v, b->sys.user);
                rows_at(tg, 0, q, v, M, A, NULL, NULL);
                double ra = cmp_sigma_ratio(n, m, M, A);
                braun_minimal_find(b->name)->to_state(yc, q, v, b->sys.user);
                rows_at(tg, 0, q, v, M, A, NULL, NULL);
                double rc = cmp_sigma_ratio(n, m, M, A);
                if (ra < rc) hi = c;
                else lo = a;
            }
            const double star = 0.5 * (lo + hi);
            found++;
            for (int e = 1; e <= 7; e++) {
                const double delta = pow(10.0, -e);
                /* θ' = 1 rad/s: the multipliers' growth is what matters. */
                double ys[2] = {star + delta, 1.0};
                braun_minimal_find(b->name)->to_state(ys, q, v, b->sys.user);
                if (rows_at(tg, 0, q, v, M, A, Q, bv)) continue;
                const double sr = cmp_sigma_ratio(n, m, M, A);
                if (cmp_kkt_accel(n, m, M, Q, A, bv, acc, lam)) continue;
                double lmax = 0, fmx = 0;
                for (int i = 0; i < m; i++) lmax = fmax(lmax, fabs(lam[i]));
                for (int j = 0; j < n; j++) {
                    double fj = 0;
                    for (int i = 0; i < m; i++) fj += A[(size_t)i * n + j] * lam[i];
                    fmx = fmax(fmx, fabs(fj));
                }
                fprintf(f, "%s,%.12g,%.1e,%.6e,%.6e,%.6e\n", tg->name, star, delta, sr, lmax,
                        fmx);
            }
        }
        prev2 = prev;
        prev = r;
    }
    free(M);
    return found;
}
