/* braun check SCENE: read and build a scene (or name a built-in model) and
 * report its sizes, the rank of its constraint rows at the initial state
 * (redundant rows and degrees of freedom) and its initial residuals.
 * Output: one "key: value" per line, for people and scripts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"
#include "braun_host.h"
#include "braun_math.h"

static int min_norm_solve(int rows, int n, double *C, double *b, double *x, double tol);

/* Rank of the rows of C (rows x n, row-major, destroyed) by Householder QR
 * with column pivoting of Cᵀ, pivots counted as zero below tol·|r_00| — the
 * rule of the library's pseudoinverse (docs/method.md, "Rank tolerance"):
 * min_norm_solve's factorization without its solve. */
static int rank_of_rows(int rows, int n, double *C, double tol)
{
    return min_norm_solve(rows, n, C, NULL, NULL, tol);
}

/* The least-squares residual e = b − C x* of C x = b, C (rows x n,
 * row-major, destroyed) of rank r: r steps of Householder QR with column
 * pivoting give an orthonormal basis of range(C), and e is the part of b
 * outside it (b is overwritten by e). Returns ‖e‖, or -1 out of memory. */
static double lsq_residual(int rows, int n, double *C, int r, double *b)
{
    double *norm = calloc((size_t)(n > 0 ? n : 1), sizeof(double));
    double *vv = calloc((size_t)(r > 0 ? r : 1), sizeof(double));
    int done = 0;
    if (!norm || !vv) {
        free(norm);
        free(vv);
        return -1;
    }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < rows; i++) norm[j] += C[(size_t)i * n + j] * C[(size_t)i * n + j];
    for (int k = 0; k < r && k < n && k < rows; k++) {
        int p = k;
        for (int j = k + 1; j < n; j++)
            if (norm[j] > norm[p]) p = j;
        if (p != k) {
            for (int i = 0; i < rows; i++) {
                const double t = C[(size_t)i * n + k];
                C[(size_t)i * n + k] = C[(size_t)i * n + p];
                C[(size_t)i * n + p] = t;
            }
            const double t = norm[k];
            norm[k] = norm[p];
            norm[p] = t;
        }
        /* Reflect entries k..rows-1 of column k onto e_k; v stays there. */
        double s = 0;
        for (int i = k; i < rows; i++) s += C[(size_t)i * n + k] * C[(size_t)i * n + k];
        if (!(s > 0)) break;
        const double x = C[(size_t)k * n + k], alpha = x > 0 ? -sqrt(s) : sqrt(s);
        C[(size_t)k * n + k] = x - alpha;
        for (int i = k; i < rows; i++) vv[k] += C[(size_t)i * n + k] * C[(size_t)i * n + k];
        for (int j = k + 1; j < n; j++) {
            double d = 0;
            for (int i = k; i < rows; i++) d += C[(size_t)i * n + k] * C[(size_t)i * n + j];
            d = 2 * d / vv[k];
            norm[j] = 0;
            for (int i = k; i < rows; i++) {
                C[(size_t)i * n + j] -= d * C[(size_t)i * n + k];
                if (i > k) norm[j] += C[(size_t)i * n + j] * C[(size_t)i * n + j];
            }
        }
        double d = 0;
        for (int i = k; i < rows; i++) d += C[(size_t)i * n + k] * b[i];
        d = 2 * d / vv[k];
        for (int i = k; i < rows; i++) b[i] -= d * C[(size_t)i * n + k];
        done = k + 1;
    }
    /* Qᵀb's first entries are in range(C); the rest, reflected back, is e. */
    double e = 0;
    for (int i = 0; i < done; i++) b[i] = 0;
    for (int i = done; i < rows; i++) e += b[i] * b[i];
    for (int k = done - 1; k >= 0; k--) {
        double d = 0;
        for (int i = k; i < rows; i++) d += C[(size_t)i * n + k] * b[i];
        d = 2 * d / vv[k];
        for (int i = k; i < rows; i++) b[i] -= d * C[(size_t)i * n + k];
    }
    free(norm);
    free(vv);
    return sqrt(e);
}

/* The upper Cholesky factor R of M (M = RᵀR, n x n, row-major). Returns 0,
 * or -1 if M is not positive definite. */
static int cholesky_upper(int n, const double *M, double *R)
{
    memcpy(R, M, sizeof(double) * (size_t)n * n);
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < j; i++) {
            double s = R[(size_t)i * n + j];
            for (int k = 0; k < i; k++) s -= R[(size_t)k * n + i] * R[(size_t)k * n + j];
            R[(size_t)i * n + j] = s / R[(size_t)i * n + i];
        }
        double s = R[(size_t)j * n + j];
        for (int k = 0; k < j; k++) s -= R[(size_t)k * n + j] * R[(size_t)k * n + j];
        if (!(s > 0)) return -1;
        R[(size_t)j * n + j] = sqrt(s);
    }
    return 0;
}

/* Each of the rows rows of A (n wide) := row R⁻¹ (Rᵀ c = a). */
static void rows_times_rinv(int rows, int n, const double *R, double *A)
{
    for (int r = 0; r < rows; r++) {
        double *c = A + (size_t)r * n;
        for (int i = 0; i < n; i++) {
            double s = c[i];
            for (int k = 0; k < i; k++) s -= R[(size_t)k * n + i] * c[k];
            c[i] = s / R[(size_t)i * n + i];
        }
    }
}

/* The minimum-norm solution x (n) of C_S x = b_S, S the rows a Householder
 * QR of Cᵀ with column pivoting keeps (pivots below tol·|r_00| end it):
 * Cᵀ P = Q R gives C_S = R_Sᵀ Qᵀ, so x = Q [R_S⁻ᵀ b_S; 0]. C (rows x n,
 * row-major) and b (rows) destroyed; b and x NULL: the rank alone.
 * Returns the rank, or -1 out of memory. */
static int min_norm_solve(int rows, int n, double *C, double *b, double *x, double tol)
{
    double *norm = calloc((size_t)(rows > 0 ? rows : 1), sizeof(double));
    double *alpha = calloc((size_t)(rows > 0 ? rows : 1), sizeof(double));
    double *vv = calloc((size_t)(rows > 0 ? rows : 1), sizeof(double));
    int rank = 0;
    double r00 = 0;
    if (!norm || !alpha || !vv) {
        free(norm);
        free(alpha);
        free(vv);
        return -1;
    }
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < n; i++) norm[j] += C[(size_t)j * n + i] * C[(size_t)j * n + i];
    for (int k = 0; k < rows && k < n; k++) {
        int p = k;
        for (int j = k + 1; j < rows; j++)
            if (norm[j] > norm[p]) p = j;
        if (p != k) {
            for (int i = 0; i < n; i++) {
                const double t = C[(size_t)k * n + i];
                C[(size_t)k * n + i] = C[(size_t)p * n + i];
                C[(size_t)p * n + i] = t;
            }
            double t = norm[k];
            norm[k] = norm[p];
            norm[p] = t;
            if (b) {
                t = b[k];
                b[k] = b[p];
                b[p] = t;
            }
        }
        double *v = C + (size_t)k * n, s = 0;
        for (int i = k; i < n; i++) s += v[i] * v[i];
        const double a = v[k] > 0 ? -sqrt(s) : sqrt(s);
        if (k == 0) r00 = fabs(a);
        if (!(fabs(a) > tol * r00) || r00 == 0) break;
        alpha[k] = a;
        v[k] -= a;
        for (int i = k; i < n; i++) vv[k] += v[i] * v[i];
        rank++;
        for (int j = k + 1; j < rows; j++) {
            double *y = C + (size_t)j * n, d = 0;
            for (int i = k; i < n; i++) d += v[i] * y[i];
            d = vv[k] > 0 ? 2 * d / vv[k] : 0;
            for (int i = k; i < n; i++) y[i] -= d * v[i];
            norm[j] = 0;
            for (int i = k + 1; i < n; i++) norm[j] += y[i] * y[i];
        }
    }
    if (!b || !x) goto done;
    /* R_S's entries: R_kk = alpha_k, R_kj (k < j) = entry k of row j. */
    for (int i = 0; i < n; i++) x[i] = 0;
    for (int j = 0; j < rank; j++) {
        double s = b[j];
        for (int k = 0; k < j; k++) s -= C[(size_t)j * n + k] * x[k];
        x[j] = s / alpha[j];
    }
    for (int k = rank - 1; k >= 0; k--) {
        const double *v = C + (size_t)k * n;
        double d = 0;
        for (int i = k; i < n; i++) d += v[i] * x[i];
        d = vv[k] > 0 ? 2 * d / vv[k] : 0;
        for (int i = k; i < n; i++) x[i] -= d * v[i];
    }
done:
    free(norm);
    free(alpha);
    free(vv);
    return rank;
}

/* Each coordinate's scale s_j (n entries), in its own unit: how far it
 * moves when the mechanism does, or its own size where that is larger (the
 * size of its rounding). A length (a body's position): max(|q_j|, l), l
 * the diagonal of the box around the scene's points and bodies at q0, the
 * mechanism's size; an angle, a quaternion's or a unit vector's entry:
 * max(|q_j|, 1). Σ_j |A_ij|·s_j (row_scales) then has row i's own unit,
 * and a residual over it is one number in m, mm or km: one scale for all
 * coordinates, max_k |q_k|, was the angles' 1 rad on a 1 µm mechanism. A
 * system without a scene to say which coordinate is which (a built-in
 * model in its own coordinates: Andrews' angles) keeps that one scale,
 * max(|q_j|, ‖q‖∞, 1e-6). */
static void coordinate_scales(const braun_cli_target *tg, double *s)
{
    const int n = tg->sys.n;
    const braun_scene *sc = tg->drawing ? &tg->drawing->scene : NULL;
    if (!sc || sc->n != n) {
        double big = 1e-6;
        for (int j = 0; j < n; j++)
            if (fabs((double)tg->q0[j]) > big) big = fabs((double)tg->q0[j]);
        for (int j = 0; j < n; j++) s[j] = big;
        return;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < sc->npoints; i++) {
        braun_real pos[3];
        if (braun_scene_point_state(sc, i, tg->q0, NULL, pos, NULL) != BRAUN_OK) continue;
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], (double)pos[k]);
            hi[k] = fmax(hi[k], (double)pos[k]);
        }
    }
    for (int b = 0; b < sc->nbodies; b++) {
        const braun_scene_body *body = &sc->bodies[b];
        for (int k = 0; k < body->kind->dim && k < body->kind->dof && k < 3; k++) {
            if (k == body->kind->angle) continue;
            const double x = (double)tg->q0[body->iq + k];
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
        }
    }
    double l2 = 0;
    for (int k = 0; k < 3; k++)
        if (hi[k] >= lo[k]) l2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    const double size = isfinite(sqrt(l2)) ? sqrt(l2) : 0;
    for (int j = 0; j < n; j++) s[j] = 1; /* (every coordinate is a body's) */
    for (int b = 0; b < sc->nbodies; b++) {
        const braun_scene_body *body = &sc->bodies[b];
        for (int k = 0; k < body->kind->dof; k++)
            s[body->iq + k] = k < body->kind->dim && k != body->kind->angle ? size : 1;
    }
    for (int j = 0; j < n; j++) s[j] = fmax(s[j], fabs((double)tg->q0[j]));
}

/* Row i's scale S_i = Σ_j |A_ij|·s_j (A: rows x n): the residual a
 * displacement of the mechanism's size gives it, in the row's own unit (m
 * for a revolute, m² for a distance, 1 for an angle joint). A row without
 * one (its gradient zero, or every coordinate it reads 0 in a scene of no
 * size) takes the largest row's, or 1. */
static void row_scales(int rows, int n, const braun_real *A, const double *s, double *S)
{
    double big = 0;
    for (int i = 0; i < rows; i++) {
        S[i] = 0;
        for (int j = 0; j < n; j++) S[i] += fabs((double)A[(size_t)i * n + j]) * s[j];
        if (!isfinite(S[i])) S[i] = 0;
        if (S[i] > big) big = S[i];
    }
    for (int i = 0; i < rows; i++)
        if (!(S[i] > 0)) S[i] = big > 0 ? big : 1;
}

/* ‖(Φ_i / S_i)‖: a residual relative to its rows' scales. */
static double scaled_norm(int rows, const braun_real *phi, const double *S)
{
    double r2 = 0;
    for (int i = 0; i < rows; i++) r2 += ((double)phi[i] / S[i]) * ((double)phi[i] / S[i]);
    return sqrt(r2);
}

/* A start off its holonomic constraints may still be one no motion can
 * reach (a distance joint longer than the mechanism stretches): first-order
 * consistency cannot tell, and a run only fails later, on its accuracy
 * guard. The assembly search tells: Gauss–Newton from q0 in the mass metric
 * (each step the minimum-norm dq = −R⁻¹C⁺Φ_q, as the position correction
 * of Eq. 16 takes it), halving a step until ‖Φ_q/S‖ decreases — the rows
 * relative to their scales S (row_scales at q0). It ends `reached` when
 * ‖Φ_q/S‖ ≤ ASSEMBLY_TOL_REL·m (the old rule ‖Φ_q‖ ≤ ASSEMBLY_TOL_REL·Σ_i S_i
 * where the rows' scales are equal; far above Φ_q's rounding, which s_j's
 * |q_j| covers) or stalled, where no halving decreases it or after
 * ASSEMBLY_STEPS steps. Each row against its own scale, it ends where it
 * would in any units: against one scale for all, Σ_ij |A_ij|·max_k |q_k|,
 * the angles' 1 rad let a 1 µm parallelogram 2 % off its third pivot be
 * "reached" 0.13 % off it. Local: a stall says no assembly near q0 was
 * found, and a mechanism whose constraints meet farther away (another
 * branch) must be started there. */
#define ASSEMBLY_STEPS 60
#define ASSEMBLY_HALVINGS 40
#define ASSEMBLY_TOL_REL 1e-10

static int consistent_rows(int m, int n, const double *C, const double *phi, const double *S,
                           double *T, double *e, double *resid, double *rel, int *rank_q);

typedef struct assembly {
    int reached;  /* 1 reached, 2 stalled where the rows agree to first
                   * order (a run's rule: round-off), 0 stalled, -1 out of
                   * memory or a callback failed */
    int steps;    /* Gauss–Newton steps taken */
    double resid; /* ‖Φ_q‖ at the end */
    double rel;   /* ‖Φ_q/S‖ there, relative to the rows' scales */
    double tol;   /* the ‖Φ_q/S‖ that counts as reached */
    double dist;  /* ‖R (q_end − q0)‖: the distance moved in the mass metric */
    int damped;   /* steps that needed halving, or whose full length did not
                   * decrease ‖Φ_q‖: a run's position correction, one
                   * undamped step per time step judged by its accuracy
                   * guard on ‖Φ_q‖, may not converge */
} assembly;

/* Φ_q and A_q at q, *res = ‖Φ_q/S‖ and *plain = ‖Φ_q‖. */
static int holonomic_at(const braun_system *s, const braun_real *q, const braun_real *v,
                        braun_real *phi, braun_real *A, braun_real *b, braun_real *bv,
                        const double *S, double *res, double *plain)
{
    for (size_t i = 0; i < (size_t)s->m * s->n; i++) A[i] = 0;
    if (s->holonomic(0, q, v, phi, A, b, bv, s->user) != 0) return -1;
    double r2 = 0;
    for (int i = 0; i < s->m; i++) r2 += (double)phi[i] * (double)phi[i];
    *plain = sqrt(r2);
    *res = scaled_norm(s->m, phi, S);
    return isfinite(*res) && isfinite(*plain) ? 0 : -1;
}

/* R: the upper Cholesky factor of M(q0) (the metric of every step); S
 * (m): the rows' scales; phi_end (m): Φ_q/S where the search ended — the
 * rows that cannot all be met share its residual (relative to their
 * scales: a distance's m² beside revolutes' m at 1 µm). */
static void assemble(const braun_system *s, const braun_real *q0, const braun_real *v0,
                     const double *R, const double *S, assembly *out, double *phi_end)
{
    const int n = s->n, m = s->m;
    const size_t mn = (size_t)m * n;
    braun_real *q = calloc((size_t)n, sizeof(braun_real)), *qt = calloc((size_t)n, sizeof(braun_real));
    braun_real *phi = calloc((size_t)m, sizeof(braun_real)), *A = calloc(mn, sizeof(braun_real));
    braun_real *phit = calloc((size_t)m, sizeof(braun_real)), *At = calloc(mn, sizeof(braun_real));
    braun_real *b = calloc((size_t)m, sizeof(braun_real)), *bv = calloc((size_t)m, sizeof(braun_real));
    double *C = calloc(mn, sizeof(double)), *rhs = calloc((size_t)m, sizeof(double));
    double *x = calloc((size_t)n, sizeof(double)), *dq = calloc((size_t)n, sizeof(double));
    memset(out, 0, sizeof *out);
    out->reached = -1;
    if (!q || !qt || !phi || !A || !phit || !At || !b || !bv || !C || !rhs || !x || !dq) goto done;
    for (int j = 0; j < n; j++) q[j] = q0[j];
    double res, plain;
    if (holonomic_at(s, q, v0, phi, A, b, bv, S, &res, &plain)) goto done;
    out->tol = ASSEMBLY_TOL_REL * m;
    const double rank_tol = (double)braun_default_rank_tol(m, n);
    int steps = 0, stalled = 0;
    while (res > out->tol && steps < ASSEMBLY_STEPS && !stalled) {
        for (size_t i = 0; i < mn; i++) C[i] = (double)A[i];
        for (int i = 0; i < m; i++) rhs[i] = -(double)phi[i];
        rows_times_rinv(m, n, R, C);
        if (min_norm_solve(m, n, C, rhs, x, rank_tol) < 0) goto done;
        /* dq = R⁻¹ x */
        for (int i = n - 1; i >= 0; i--) {
            double acc = x[i];
            for (int k = i + 1; k < n; k++) acc -= R[(size_t)i * n + k] * dq[k];
            dq[i] = acc / R[(size_t)i * n + i];
        }
        double rest = 0, plaint = 0;
        /* Damped: the full step is not taken, or it does not decrease
         * ‖Φ_q‖ — what a run's accuracy guard judges its correction by. */
        int damped = 1;
        stalled = 1;
        for (int h = 0; h < ASSEMBLY_HALVINGS && stalled; h++) {
            const double step = ldexp(1.0, -h); /* 1, 1/2, 1/4, ... */
            for (int j = 0; j < n; j++) qt[j] = (braun_real)((double)q[j] + step * dq[j]);
            /* (a failure: outside the callbacks' domain) */
            if (holonomic_at(s, qt, v0, phit, At, b, bv, S, &rest, &plaint)) continue;
            if (h == 0 && plaint < plain) damped = 0;
            if (rest < res) stalled = 0;
        }
        if (stalled) break;
        out->damped += damped;
        steps++;
        res = rest;
        plain = plaint;
        memcpy(q, qt, sizeof(braun_real) * (size_t)n);
        memcpy(phi, phit, sizeof(braun_real) * (size_t)m);
        memcpy(A, At, sizeof(braun_real) * mn);
    }
    out->reached = res <= out->tol;
    if (!out->reached) {
        /* Stalled: rows that cannot all be met, or dependent rows that
         * disagree by no more than a run takes for round-off (its first-
         * order rule, sqrt(ε) of the rows' scales, at the point where the
         * search ended: two pins 1e-8 m apart on a 1 m pendulum ran
         * BRAUN_OK while check said "consistent: no"). The run carries
         * that residual; the check says so. */
        double *T = calloc(mn, sizeof(double)), *e = calloc((size_t)m, sizeof(double));
        double *ph = calloc((size_t)m, sizeof(double));
        double r_abs, r_rel;
        int rk;
        if (!T || !e || !ph) {
            free(T);
            free(e);
            free(ph);
            goto done;
        }
        for (size_t i = 0; i < mn; i++) C[i] = (double)A[i];
        rows_times_rinv(m, n, R, C);
        for (int i = 0; i < m; i++) ph[i] = (double)phi[i];
        const int agree = consistent_rows(m, n, C, ph, S, T, e, &r_abs, &r_rel, &rk);
        free(T);
        free(e);
        free(ph);
        if (agree < 0) goto done;
        if (agree == 1 && rk < m) out->reached = 2;
    }
    out->steps = steps;
    out->rel = res;
    out->resid = plain;
    for (int i = 0; i < m; i++) phi_end[i] = (double)phi[i] / S[i];
    /* ‖R (q − q0)‖ */
    double d2 = 0;
    for (int i = 0; i < n; i++) {
        double acc = 0;
        for (int k = i; k < n; k++) acc += R[(size_t)i * n + k] * ((double)q[k] - (double)q0[k]);
        d2 += acc * acc;
    }
    out->dist = sqrt(d2);
done:
    free(q);
    free(qt);
    free(phi);
    free(A);
    free(phit);
    free(At);
    free(b);
    free(bv);
    free(C);
    free(rhs);
    free(x);
    free(dq);
}

/* Whether m rows can all hold at the initial state, to first order: the
 * least-squares residual of C x = −phi (C = A R⁻¹, the rows as the solver
 * weighs them; T: m x n doubles, destroyed). Rows of full rank always can;
 * dependent rows must agree, as the library's position correction requires
 * (braun_corrections.c: above options.inconsistency_tol, default sqrt(ε), a
 * run fails with BRAUN_ERR_INCONSISTENT). Called with the holonomic rows
 * and phi = Φ_q (positions), then with all rows [A_q; A_vv] and their
 * velocity error phi = [A_q v − b_q; Φ_v] (velocities). *resid: ‖e‖; e:
 * the residual vector (m), whose largest entries are the rows that
 * disagree; *rank_q: the rows' rank. With the rows' scales S (m; NULL:
 * none), the verdict is on the rows relative to them instead, as the
 * assembly search judges them: *rel, the least-squares residual of C's
 * rows and phi over S_i (the same range), <= sqrt(ε), a verdict no unit
 * changes (against sqrt(ε) in the rows' units a parallelogram 2 % off its
 * third pivot was inconsistent at 1 m and consistent at 1 µm). Returns 1
 * consistent, 0 not, -1 out of memory. */
static int consistent_rows(int m, int n, const double *C, const double *phi, const double *S,
                           double *T, double *e, double *resid, double *rel, int *rank_q)
{
    *resid = *rel = 0;
    *rank_q = 0;
    if (m == 0) return 1;
    memcpy(T, C, sizeof(double) * (size_t)m * n);
    const int rank = *rank_q = rank_of_rows(m, n, T, (double)braun_default_rank_tol(m, n));
    if (rank < 0) return -1;
    if (rank == m) return 1;
    memcpy(T, C, sizeof(double) * (size_t)m * n);
    for (int i = 0; i < m; i++) e[i] = -phi[i];
    *resid = *rel = lsq_residual(m, n, T, rank, e);
    if (*resid < 0) return -1;
    if (!S) return *resid <= sqrt((double)BRAUN_EPS);
    /* (e keeps the rows' own residual: it names them, as it did.) */
    double *w = malloc(sizeof(double) * (size_t)m);
    if (!w) return -1;
    for (size_t i = 0; i < (size_t)m * n; i++) T[i] = C[i] / S[i / (size_t)n];
    for (int i = 0; i < m; i++) w[i] = -phi[i] / S[i];
    *rel = lsq_residual(m, n, T, rank, w);
    free(w);
    if (*rel < 0) return -1;
    return *rel <= sqrt((double)BRAUN_EPS);
}

/* "joint 'left' (revolute) and joint 'right' (revolute)" (a built-in
 * model: "rows 0 and 2"): the elements whose rows have the largest
 * entries of the residual e (m), at most four, each named once. */
static int name_disagreeing(const braun_cli_target *tg, int m, const double *e, char *buf,
                            size_t size)
{
    enum { MOST = 4 };
    char names[MOST][160];
    int rows[MOST] = {0}, count = 0, more = 0;
    double emax = 0;
    for (int i = 0; i < m; i++)
        if (fabs(e[i]) > emax) emax = fabs(e[i]);
    /* Rows in order of |e_i|, down to a thousandth of the largest. */
    for (double above = INFINITY; emax > 0 && !more;) {
        int best = -1;
        for (int i = 0; i < m; i++)
            if (fabs(e[i]) < above && fabs(e[i]) >= 1e-3 * emax &&
                (best < 0 || fabs(e[i]) > fabs(e[best])))
                best = i;
        if (best < 0) break;
        above = fabs(e[best]);
        /* Rows of equal |e_i|: every one of them, in row order. */
        for (int i = best; i < m; i++) {
            if (fabs(e[i]) != above) continue;
            char own[160];
            const char *o = braun_cli_row_owner(tg->scene, i, own, sizeof own);
            if (!o) snprintf(own, sizeof own, "row %d", i), o = own;
            int seen = 0;
            for (int k = 0; k < count && !seen; k++) seen = strcmp(names[k], o) == 0;
            if (seen) continue;
            if (count == MOST) {
                more = 1;
                continue;
            }
            snprintf(names[count], sizeof names[count], "%s", o);
            rows[count++] = i;
        }
    }
    size_t len = 0;
    buf[0] = '\0';
    for (int k = 0; k < count && len < size; k++) {
        const char *sep = k == 0 ? "" : k == count - 1 && !more ? " and " : ", ";
        int w = tg->scene ? snprintf(buf + len, size - len, "%s%s (row %d)", sep, names[k], rows[k])
                          : snprintf(buf + len, size - len, "%s%s", sep, names[k]);
        if (w < 0) break;
        len += (size_t)w;
    }
    if (more && len < size) snprintf(buf + len, size - len, " and more");
    return count + more;
}

/* The message of rows that cannot all hold (e: their least-squares
 * residual, count rows; vel: at the velocity level; rel: the positions'
 * residual relative to the rows' scales, on which check judges them). One
 * element alone: its rows' gradients depend on others' here while its
 * error does not (a joint started at a singular configuration). */
static void say_unsolvable(const braun_cli_target *tg, int count, const double *e, double resid,
                           double rel, int vel)
{
    char who[800], why[400];
    const double tol = sqrt((double)BRAUN_EPS);
    const char *what = vel ? "the constraints' velocities" : "the constraints";
    const char *run = vel ? "braun run stops with BRAUN_ERR_INCONSISTENT at its first step when the "
                            "velocity correction is on"
                          : "braun run stops with BRAUN_ERR_INCONSISTENT";
    /* Judged to first order, where the rows lose rank: at a singular
     * configuration a solution can lie off it, out of the local search's
     * reach (three links closed straight to a point 1e-4 short of their
     * reach: the chain sags 0.01 m and runs). */
    const char *hint = vel ? ""
                           : "; judged to first order where the rows lose rank: at a singular "
                             "configuration (a chain closed straight to a point within its reach) a "
                             "solution can lie off it, beyond the assembly search: start there";
    /* Both judged relative to the rows' own size, as the run judges them
     * (its default inconsistency tolerance: docs/api.md, Options). */
    snprintf(why, sizeof why, "%.3g of the rows' own scale, above sqrt(eps) = %.3g of it, in any units: %s",
             rel, tol, run);
    if (name_disagreeing(tg, count, e, who, sizeof who) == 1)
        braun_cli_error("%s: %s have no solution at the initial state: %s cannot be met (its gradient "
                        "depends on the other rows' here, its %serror does not; least-squares "
                        "residual %.3g, %s)%s",
                        tg->name, what, who, vel ? "velocity " : "", resid, why, hint);
    else
        braun_cli_error("%s: %s have no solution at the initial state: %s disagree (%s %.3g%s is "
                        "%s)%s",
                        tg->name, what, who,
                        vel ? "the least-squares residual of their velocity error," :
                              "their least-squares residual",
                        resid, vel ? "," : "", why, hint);
}

/* A text of the scene on one "key: value" line (braun_cli_put_text), so a
 * name or description with a newline cannot add a line (a forged "n:
 * 999") to what scripts read. */
static void text_value(const char *key, const char *s)
{
    printf("%s: ", key);
    braun_cli_put_text(stdout, s);
    putchar('\n');
}

static int report(const braun_cli_target *tg)
{
    const braun_system *s = &tg->sys;
    const int n = s->n, m = s->m, p = s->p, rows = m + p;
    braun_model model;
    int st = braun_model_init(&model, s);
    if (st == BRAUN_ERR_SIZE && !s->sparsity && n > 0 && n <= BRAUN_MAX_SPARSE &&
        rows <= BRAUN_MAX_SPARSE) {
        /* check ranks dense matrices: say so instead of a bare size error. */
        braun_cli_error("'%s' has n = %d, m + p = %d: beyond the dense check's limit (%d); "
                        "run it with braun run --backend suitesparse", tg->name, n, rows,
                        BRAUN_MAX_DENSE);
        return BRAUN_CLI_FAILED;
    }
    if (st) {
        braun_cli_error("model '%s' is invalid: %s", tg->name, braun_status_str(st));
        return BRAUN_CLI_FAILED;
    }
    const size_t bytes = braun_data_size(&model);
    const size_t nn = (size_t)n * n, rn = (size_t)(rows > 0 ? rows : 1) * n;
    /* calloc: every entry starts defined, whatever the callbacks skip. */
    void *buf = malloc(bytes);
    braun_real *M = calloc(nn, sizeof(braun_real)), *A = calloc(rn, sizeof(braun_real));
    braun_real *scratch = calloc(3 * (size_t)rows + 3, sizeof(braun_real));
    double *Md = calloc(nn, sizeof(double)), *Ad = calloc(rn, sizeof(double));
    /* The holonomic rows' consistency: Φ_q, the residual, and m x n doubles
     * of work (Md's once it is spent, when they fit). */
    double *phi = calloc((size_t)m + 1, sizeof(double)), *e = calloc((size_t)m + 1, sizeof(double));
    /* ... and of the velocity rows: [A_q v − b_q; Φ_v], then its residual. */
    double *ev = calloc((size_t)rows + 1, sizeof(double)), *scratch_v = calloc((size_t)rows + 1, sizeof(double));
    double *T = rows > n ? calloc((size_t)rows * n, sizeof(double)) : NULL;
    double *Rm = NULL; /* M's Cholesky factor */
    double *pend = calloc((size_t)m + 1, sizeof(double)); /* Φ_q/S where the assembly search ended */
    /* The coordinates' scales and the holonomic rows' (coordinate_scales,
     * row_scales): what the start's residual is judged against. */
    double *sq = calloc((size_t)n + 1, sizeof(double)), *S = calloc((size_t)m + 1, sizeof(double));
    int rc = BRAUN_CLI_FAILED;
    if (!buf || !M || !A || !scratch || !Md || !Ad || !phi || !e || !ev || !scratch_v || !pend || !sq || !S ||
        (rows > n && !T)) {
        braun_cli_error("out of memory");
        goto done;
    }
    braun_data d;
    braun_real pos = 0, vel = 0;
    st = braun_data_init(&d, &model, buf, bytes);
    if (!st) st = braun_set_state(&d, 0, tg->q0, tg->v0);
    if (!st) st = braun_residuals(&d, 0, tg->q0, tg->v0, &pos, &vel, NULL);
    if (st) {
        char what[256] = "";
        if (d.error.status == st) braun_error_format(&d, what, sizeof what);
        braun_cli_error("%s at the initial state: %s (%s)", tg->name, what, braun_status_str(st));
        goto done;
    }
    /* Rank of A_v = [A_q; A_vv] weighted by R^-1, as the solver sees it. */
    if (s->mass(0, tg->q0, M, s->user) != 0) {
        braun_cli_error("%s: the mass callback failed at the initial state", tg->name);
        goto done;
    }
    for (size_t i = 0; i < rn; i++) A[i] = 0;
    if (m > 0 && s->holonomic(0, tg->q0, tg->v0, scratch, A, scratch + rows, scratch + 2 * rows,
                              s->user) != 0) {
        braun_cli_error("%s: the holonomic callback failed at the initial state", tg->name);
        goto done;
    }
    for (int i = 0; i < m; i++) {
        phi[i] = (double)scratch[i];
        double dphi = -(double)scratch[rows + i]; /* Φ̇_q = A_q v − b_q */
        for (int k = 0; k < n; k++) dphi += (double)A[(size_t)i * n + k] * (double)tg->v0[k];
        ev[i] = dphi;
    }
    if (p > 0 && s->nonholonomic(0, tg->q0, tg->v0, scratch, A + (size_t)m * n,
                                 scratch + 2 * rows, s->user) != 0) {
        braun_cli_error("%s: the nonholonomic callback failed at the initial state", tg->name);
        goto done;
    }
    for (int i = 0; i < p; i++) ev[m + i] = (double)scratch[i];
    for (size_t i = 0; i < nn; i++) Md[i] = (double)M[i];
    for (size_t i = 0; i < rn; i++) Ad[i] = (double)A[i];
    int rank = 0, consistent = 1, vconsistent = 1, vrank = 0, loose_rank = -1;
    double resid = 0, rel = 0, vresid = 0, vrel = 0;
    assembly asm_ = {.reached = 1};
    /* Off its constraints: ‖Φ_q/S‖ above sqrt(ε), each row relative to its
     * own scale, so at any size of the mechanism (‖Φ_q‖ > sqrt(ε) in the
     * rows' units skipped the search of a particle 100 µm across that no
     * motion can put on its two distance joints: "consistent: yes"). The
     * search costs O(m n²) per Gauss–Newton step: up to the size from
     * which check says it is slow. */
    coordinate_scales(tg, sq);
    row_scales(m, n, A, sq, S);
    double pos_rel = 0;
    for (int i = 0; i < m; i++) pos_rel += (phi[i] / S[i]) * (phi[i] / S[i]);
    const int off = m > 0 && sqrt(pos_rel) > sqrt((double)BRAUN_EPS);
    const int search = off && n < BRAUN_CLI_DENSE_NOTE_N;
    if (rows > 0) {
        /* C = A R⁻¹, the rows as the solver weighs them (M = RᵀR). */
        if (!(Rm = calloc(nn, sizeof(double)))) {
            braun_cli_error("out of memory");
            goto done;
        }
        if (cholesky_upper(n, Md, Rm)) {
            braun_cli_error("%s: the mass matrix is not positive definite", tg->name);
            goto done;
        }
        rows_times_rinv(rows, n, Rm, Ad);
        /* The holonomic rows are Ad's first m: all of them without
         * nonholonomic rows, whose rank is then the one to print. */
        consistent = consistent_rows(m, n, Ad, phi, S, T ? T : Md, e, &resid, &rel, &rank);
        /* All rows, at the velocity level; their rank is the one to print
         * (the holonomic rows' alone without nonholonomic rows). ev
         * becomes its residual. */
        /* The velocity rows as the run judges them (braun_corrections.c,
         * inconsistency_tol): relative to their own size, max_i Σ_j
         * |A_ij|·|v_j| + |ev_i|, one scale for all (against sqrt(ε) in
         * m/s a knife across a slider driven at 10 nm/s read consistent:
         * yes, which the run refuses). 0 (at rest, no drive): ev is 0. */
        double vs = 0;
        for (int i = 0; i < rows; i++) {
            double sum = fabs(ev[i]);
            for (int k = 0; k < n; k++) sum += fabs((double)A[(size_t)i * n + k]) * fabs((double)tg->v0[k]);
            if (sum > vs) vs = sum;
        }
        for (int i = 0; i < rows; i++) scratch_v[i] = vs;
        vconsistent = consistent_rows(rows, n, Ad, ev, vs > 0 ? scratch_v : NULL, T ? T : Md, ev, &vresid,
                                      &vrel, &vrank);
        if (p > 0) rank = vrank;
        if (consistent < 0 || vconsistent < 0 || rank < 0) {
            braun_cli_error("out of memory");
            goto done;
        }
        /* A start off its rows: rows dependent on the manifold are
         * dependent there only to its residual, and may count as
         * independent (the parallelogram's redundant crank 1e-13 off:
         * rank 12, no dof). The rank a run takes after projecting such a
         * start (pivots past sqrt(ε), docs/robustness.md). */
        if (pos > 0) {
            const int nr = p > 0 ? rows : m;
            double *W = T ? T : Md;
            memcpy(W, Ad, sizeof(double) * (size_t)nr * (size_t)n);
            loose_rank = rank_of_rows(nr, n, W, sqrt((double)BRAUN_EPS));
        }
        /* Rows that agree to first order at a start off them: can they be
         * met at all near it? */
        /* Rows that disagree to first order may still be met near the start
         * (a singular configuration): the search tells that too. Its Φ_q
         * goes to pend, e holding the least-squares residual. */
        if (search) assemble(s, tg->q0, tg->v0, Rm, S, &asm_, pend);
    }
    char corr[64];
    const unsigned supported = model.opt.corrections;
    text_value("scene", tg->name);
    text_value("file", tg->source ? tg->source : "(built-in)");
    text_value("description", tg->description ? tg->description : "");
    printf("n: %d\nm: %d\np: %d\n", n, m, p);
    printf("rank: %d\nredundant: %d\ndof: %d\n", rank, rows - rank, n - rank);
    if (loose_rank >= 0 && loose_rank < rank)
        printf("rank_note: %d of these pivots are below sqrt(eps) of the largest: rows dependent only to "
               "the start's residual; on them (a run's projected start) the rank is %d, dof %d "
               "(docs/robustness.md)\n",
               rank - loose_rank, loose_rank, n - loose_rank);
    printf("position_residual: %.3g\n", (double)pos);
    /* A start off its constraints: which row, and whose. An infeasible
     * joint (a distance longer than the mechanism reaches) is consistent
     * to first order and fails only in the run, on the energy guard, which
     * has no row to name. */
    if (off) {
        /* The row furthest off relative to its own scale. */
        int worst = 0;
        for (int i = 1; i < m; i++)
            if (fabs(phi[i]) / S[i] > fabs(phi[worst]) / S[worst]) worst = i;
        char owner[160];
        const char *who = braun_cli_row_owner(tg->scene, worst, owner, sizeof owner);
        printf("position_residual_largest: %.3g (row %d%s", fabs(phi[worst]), worst, who ? ", " : "");
        if (who) braun_cli_put_text(stdout, who);
        printf(")\n");
    }
    if (off && consistent && !search)
        printf("assembly: not searched (n = %d; the dense search is for n < %d)\n", n,
               BRAUN_CLI_DENSE_NOTE_N);
    if (search) {
        if (asm_.reached < 0)
            printf("assembly: not searched (a holonomic callback failed or gave NaN near the "
                   "initial state, or out of memory)\n");
        else if (asm_.reached == 2)
            printf("assembly: reached to round-off (Gauss-Newton stalls at residual %.3g after %d "
                   "step%s where dependent rows disagree by no more than sqrt(eps) of their scales: "
                   "a run takes them to agree and carries the residual)\n",
                   asm_.resid, asm_.steps, asm_.steps == 1 ? "" : "s");
        else if (asm_.reached)
            printf("assembly: reached (residual %.2g after %d Gauss-Newton step%s, %d damped, %.3g "
                   "from the initial state in the mass metric)\n",
                   asm_.resid, asm_.steps, asm_.steps == 1 ? "" : "s", asm_.damped, asm_.dist);
        else
            printf("assembly: none found (Gauss-Newton stalls at residual %.3g after %d step%s)\n",
                   asm_.resid, asm_.steps, asm_.steps == 1 ? "" : "s");
    }
    printf("velocity_residual: %.3g\n", (double)vel);
    const int assembled = asm_.reached != 0;
    /* Off the constraints with no search (n >= 600): first order says
     * nothing of whether they can be met — a chain closed to a ground point
     * beyond its reach read "yes" at n = 600 and "no" at 597. */
    const int unknown = off && consistent && vconsistent && !search;
    printf("consistent: %s\n", unknown ? "unknown" : consistent && vconsistent && assembled ? "yes" : "no");
    printf("mass_matrix: %s\n", s->flags & BRAUN_MASS_CONSTANT ? "constant" : "varies");
    printf("energy_law: %s\n", s->energy ? "yes" : "no");
    printf("energy_input: %s\n", s->flags & BRAUN_ENERGY_INPUT ? "yes" : "no");
    printf("corrections: %s\n",
           braun_cli_corrections_str(tg->corrections & supported, corr, sizeof corr));
    printf("reference: %s\n", tg->reference ? tg->reference->name : "none");
    /* The callbacks against their own finite differences at the initial
     * state (braun_check_callbacks): a wrong Jacobian, b-term or energy
     * gradient, which a run's corrections would hide. */
    braun_callback_report cb;
    /* A scene's steps follow its own lengths (a 1 µm spatial-arm was
     * stepped by 6e-6 m and failed); a built-in model's are 1 (metres). */
    braun_real *size = tg->scene ? malloc(sizeof *size * (size_t)(n > 0 ? n : 1)) : NULL;
    if (size && braun_scene_coordinate_sizes(&tg->scene->scene, tg->q0, size) != BRAUN_OK) {
        free(size);
        size = NULL;
    }
    const int cst = braun_check_callbacks_sized(s, 0, tg->q0, tg->v0, size, 0, &cb);
    free(size);
    if (cst == BRAUN_OK || cst == BRAUN_ERR_ARGUMENT)
        printf("callbacks: %s (largest difference %.2g%s%s)\n", cst ? "no" : "yes", cb.worst_value,
               cb.worst[0] ? ", " : "", cb.worst);
    else
        printf("callbacks: not checked (%s)\n", braun_status_str(cst));
    rc = fflush(stdout) == 0 ? 0 : BRAUN_CLI_FAILED;
    if ((cst == BRAUN_OK || cst == BRAUN_ERR_ARGUMENT) && cb.note[0])
        fprintf(stderr, "braun: note: %s: %s: a kink of the model there (as a torsion3d's "
                        "potential where the joint's angle is its rest angle +- pi), not held "
                        "against the callback\n", tg->name, cb.note);
    if (cst == BRAUN_ERR_ARGUMENT) {
        braun_cli_error("%s: a callback disagrees with the finite differences of its own outputs at "
                        "the initial state: %s off by %.3g of its scale (braun_check_callbacks)",
                        tg->name, cb.worst, cb.worst_value);
        rc = BRAUN_CLI_FAILED;
    }
    if (consistent && asm_.reached > 0 && asm_.damped > 0)
        fprintf(stderr, "braun: note: %s: the start is %.3g from a configuration that meets its "
                        "constraints, far enough that Gauss-Newton had to damp %d of its %d steps; a "
                        "run's position correction takes one undamped step per time step and may "
                        "fail from here (its accuracy guard): start the mechanism nearer\n",
                tg->name, asm_.dist, asm_.damped, asm_.steps);
    if (consistent && !assembled) {
        /* Where the search stalls the residual is spread over the rows that
         * cannot all hold: those are named, not the largest alone. */
        char who[800];
        name_disagreeing(tg, m, pend, who, sizeof who);
        braun_cli_error("%s: the constraints have no solution near the initial state: %s cannot all "
                        "be met (Gauss-Newton from the initial state, in the mass metric, stalls at "
                        "residual %.3g after %d step%s: no configuration near it meets them: "
                        "a joint longer than the mechanism reaches?); braun run with the position "
                        "correction cannot meet them: its accuracy guard stops it where the "
                        "residual grows, and a residual no larger than the start's, which the "
                        "guard allows, is carried through a motion of the mechanism the rows "
                        "nearly describe",
                        tg->name, who, asm_.resid, asm_.steps, asm_.steps == 1 ? "" : "s");
        rc = BRAUN_CLI_FAILED;
    }
    if (unknown) {
        braun_cli_error("%s: the initial state is off its constraints (position residual %.3g) and "
                        "n = %d is too large for the assembly search (n < %d): whether they can be "
                        "met near it is not known; put the start on them, or see whether braun run "
                        "passes its first steps (its accuracy guard stops a start that cannot be "
                        "assembled)", tg->name, (double)pos, n, BRAUN_CLI_DENSE_NOTE_N);
        rc = BRAUN_CLI_FAILED;
    }
    if (!consistent || !vconsistent) {
        /* What a run would meet at its first step, said before it: the
         * positions first; positions that hold with velocities that cannot
         * (two drives of one joint at different rates) drift apart from
         * t = 0 on. */
        const int velocities = consistent;
        say_unsolvable(tg, velocities ? rows : m, velocities ? ev : e, velocities ? vresid : resid,
                       velocities ? vrel : rel, velocities);
        if (!velocities && asm_.reached > 0)
            fprintf(stderr, "braun: note: %s: they disagree to first order only: a configuration %.3g "
                            "from the start (mass metric) meets them (Gauss-Newton, residual %.2g; the "
                            "assembly line): the start is a singular configuration of these rows, "
                            "from which the run's position correction cannot move; start the "
                            "mechanism there\n",
                    tg->name, asm_.dist, asm_.resid);
        rc = BRAUN_CLI_FAILED;
    }
done:
    free(buf);
    free(M);
    free(A);
    free(scratch);
    free(Md);
    free(Ad);
    free(phi);
    free(e);
    free(ev);
    free(scratch_v);
    free(T);
    free(Rm);
    free(pend);
    free(sq);
    free(S);
    return rc;
}

int braun_cli_check(int argc, char **argv)
{
    const char *scene = NULL;
    int options_end = 0;
    for (int i = 0; i < argc; i++) {
        /* "--" ends the options, as run's: a file named "-x.json" after it. */
        if (!options_end && strcmp(argv[i], "--") == 0) {
            options_end = 1;
            continue;
        }
        /* check takes no option: one given is named, as run names its
         * unknown ones ("check needs exactly one SCENE" blamed the scene
         * count). "-" alone is a name, as run reads it. */
        if (!options_end && argv[i][0] == '-' && argv[i][1] != '\0') {
            char name[32];
            int rc = braun_cli_option(argc, argv, &i, name, sizeof name, NULL);
            if (rc) return rc;
            return braun_cli_error("unknown option '%s' (check takes none; see braun --help)", name);
        }
        if (scene) return braun_cli_error("unexpected argument '%s' (one SCENE only)", argv[i]);
        scene = argv[i];
    }
    if (!scene) return braun_cli_error("check needs exactly one SCENE (a .json file or a "
                                       "built-in model)");
    braun_cli_target tg;
    int rc = braun_cli_target_open(scene, &tg);
    if (rc) return rc;
    /* check's rank, consistency and callback analyses are dense (O(n³)):
     * a large scene takes minutes (a 1000-link chain, n = 3000: about two),
     * which the user is told before the silence. */
    if (tg.sys.n >= BRAUN_CLI_DENSE_NOTE_N && tg.sys.n <= BRAUN_MAX_DENSE &&
        tg.sys.m + tg.sys.p <= BRAUN_MAX_DENSE) /* beyond, report refuses at once */
        fprintf(stderr, "braun: note: '%s' has n = %d; check's analyses are dense (O(n^3)): this "
                        "takes a while\n", tg.name, tg.sys.n);
    rc = report(&tg);
    braun_cli_target_close(&tg);
    return rc;
}
