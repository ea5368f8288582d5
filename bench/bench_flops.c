/* Floating-point operations of one step, derived from the code of the core
 * (src/core/braun_forward.c, braun_corrections.c, braun_step.c, braun_chol.c,
 * braun_qrcp.c). One flop is
 * one IEEE add, subtract, multiply, divide or square root; sign flips,
 * fabs, comparisons, copies and conversions are not flops. The finiteness
 * checks (braun_all_finite: s += x·0) are flops of their own component,
 * "checks", because they are instructions the method does not need.
 *
 * The formulas assume a step that meets no cancellation in the pivoted QR
 * (a column norm recomputed: rare, data dependent) and the rank of C_v at
 * the initial state; bench.sh checks them against the floating-point
 * instructions callgrind counts per function. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* Sizes that decide the counts. */
typedef struct shape {
    long n, m, p, r;  /* coordinates, rows */
    long k, kq;       /* rank of C_v, of C_q (when factored separately) */
    long st, sr;      /* flops of x := R^-T x and x := R^-1 x */
    long mulr;        /* flops of y := R x */
    long chol;        /* flops of one factorization of M (with its checks) */
    int mass_constant, need_fq, energy_input, constraint_work, energy;
} shape;

/* Rank of the rows x n matrix A (row-major, destroyed) by modified
 * Gram–Schmidt with row pivoting; tol relative to the largest row norm. */
static long rank_of(long rows, long n, double *A, double tol)
{
    double big = 0;
    for (long i = 0; i < rows; i++) {
        double s = 0;
        for (long j = 0; j < n; j++) s += A[i * n + j] * A[i * n + j];
        if (s > big) big = s;
    }
    big = sqrt(big);
    long rank = 0;
    for (long row = 0; row < rows; row++) {
        long best = -1;
        double bn = 0;
        for (long i = row; i < rows; i++) {
            double s = 0;
            for (long j = 0; j < n; j++) s += A[i * n + j] * A[i * n + j];
            if (s > bn) bn = s, best = i;
        }
        if (best < 0 || sqrt(bn) <= tol * big) break;
        for (long j = 0; j < n; j++) {
            double t = A[row * n + j];
            A[row * n + j] = A[best * n + j];
            A[best * n + j] = t;
        }
        double nn = sqrt(bn);
        for (long j = 0; j < n; j++) A[row * n + j] /= nn;
        for (long i = row + 1; i < rows; i++) {
            double d = 0;
            for (long j = 0; j < n; j++) d += A[i * n + j] * A[row * n + j];
            for (long j = 0; j < n; j++) A[i * n + j] -= d * A[row * n + j];
        }
        rank++;
    }
    return rank;
}

/* Sizes, the envelope of R (= the profile of M: Cholesky fills no zero
 * above the first nonzero of a column) and the ranks at the initial state. */
static int shape_of(const bench_target *tg, shape *s)
{
    const braun_system *sys = &tg->sys;
    const long n = sys->n, m = sys->m, p = sys->p, r = m + p;
    memset(s, 0, sizeof *s);
    s->n = n, s->m = m, s->p = p, s->r = r;
    s->mass_constant = (sys->flags & BRAUN_MASS_CONSTANT) != 0;
    s->energy_input = (sys->flags & BRAUN_ENERGY_INPUT) != 0;
    s->constraint_work = !(sys->flags & BRAUN_SCLERONOMIC) && sys->energy && r > 0;
    s->need_fq = m > 0 && p > 0;
    s->energy = sys->energy != NULL;
    braun_real *M = calloc((size_t)(n * n), sizeof *M);
    braun_real *A = calloc((size_t)(r * n + 1), sizeof *A);
    braun_real *phi = calloc((size_t)(r + 1), sizeof *phi);
    braun_real *b = calloc((size_t)(r + 1), sizeof *b);
    braun_real *bv = calloc((size_t)(r + 1), sizeof *bv);
    long *first = calloc((size_t)n, sizeof *first);
    double *Ad = calloc((size_t)(r * n + 1), sizeof *Ad);
    if (!M || !A || !phi || !b || !bv || !first || !Ad) {
        free(M), free(A), free(phi), free(b), free(bv), free(first), free(Ad);
        return -1;
    }
    sys->mass(0, tg->q0, M, sys->user);
    /* The solves skip exact zeros of R outside its envelope (first nonzero
     * row of each column, last nonzero column of each row), as
     * braun_chol_factor records them: factor M here the same way. */
    for (long i = 0; i < n; i++) {
        for (long k = 0; k < i; k++) M[i * n + i] -= M[k * n + i] * M[k * n + i];
        const braun_real rii = (braun_real)sqrt((double)M[i * n + i]);
        M[i * n + i] = rii;
        for (long j = i + 1; j < n; j++) {
            for (long k = 0; k < i; k++) M[i * n + j] -= M[k * n + i] * M[k * n + j];
            M[i * n + j] /= rii;
        }
        for (long j = 0; j < i; j++) M[i * n + j] = 0;
    }
    long e = 0, ep = 0;
    for (long j = 0; j < n; j++) {
        long i = 0;
        while (i < j && M[i * n + j] == 0) i++;
        first[j] = i;
        e += j - i;
    }
    for (long i = 0; i < n; i++) {
        long j = n - 1;
        while (j > i && M[i * n + j] == 0) j--;
        ep += j - i;
    }
    s->st = 2 * e + n;
    s->sr = 2 * ep + n;
    s->mulr = 2 * ep + 2 * n;
    /* One factorization (src/core/braun_chol.c braun_chol_factor): symmetry
     * n(n-1)/2 subtractions (the tolerance product is loop invariant, 1);
     * per pivot 2i, the SPD test's product, sqrt, reciprocal; per
     * off-diagonal entry 2i + 1. The finite scan of M (2n², in
     * src/core/braun_forward.c) is counted with the checks. */
    long chol = n * (n - 1) / 2 + 1;
    for (long i = 0; i < n; i++) chol += 2 * i + 3 + (n - 1 - i) * (2 * i + 1);
    s->chol = chol;
    if (m > 0) sys->holonomic(0, tg->q0, tg->v0, phi, A, b, bv, sys->user);
    if (p > 0) sys->nonholonomic(0, tg->q0, tg->v0, phi + m, A + m * n, bv + m, sys->user);
    for (long i = 0; i < r * n; i++) Ad[i] = (double)A[i];
    s->k = r > 0 ? rank_of(r, n, Ad, 1e-10) : 0;
    for (long i = 0; i < m * n; i++) Ad[i] = (double)A[i];
    s->kq = s->need_fq ? rank_of(m, n, Ad, 1e-10) : s->k;
    free(M), free(A), free(phi), free(b), free(bv), free(first), free(Ad);
    return 0;
}

/* Euclidean norm with scaling (braun_nrm2): about 3 flops per entry. */
static long f_nrm2(long len) { return len > 0 ? 3 * len + 2 : 0; }

/* Householder reflector of length len (house): scaling len-1, alpha-beta,
 * its reciprocal, tau = (beta-alpha)/beta. */
static long f_house(long len) { return len + 3; }

/* y := (I - tau v v^T) y, length len (reflect). */
static long f_reflect(long len) { return 4 * len - 2; }

/* braun_qrcp_factor of C^T (n x rows) with rank k. */
static long f_qr(long n, long rows, long k)
{
    const long kmax = n < rows ? n : rows;
    long f = 2 * n * rows; /* initial squared column norms */
    for (long j = 0; j < k; j++) {
        /* pivot norm, sqrt, tol·r00; reflector; each later column:
         * reflection, downdate (2), cancellation test (1). */
        f += 2 * (n - j) + 1 + 1 + f_house(n - j);
        f += (rows - 1 - j) * (f_reflect(n - j) + 3);
    }
    if (k < kmax) f += 2 * (n - k) + 1 + 1; /* the pivot that stops it */
    if (k > 0 && k < rows) {
        /* Second stage: Householder QR of S (rows x k). */
        for (long j = 0; j < k; j++) {
            f += f_nrm2(rows - j) + f_house(rows - j);
            f += (k - 1 - j) * f_reflect(rows - j);
        }
    }
    return f;
}

/* braun_qrcp_pinv_apply / braun_qrcp_lsq: S^+ P^T r then Q1 w. */
static long f_pinv(long n, long rows, long k, int resid)
{
    long f = 0;
    if (k == 0) return resid ? f_nrm2(rows) : 0;
    if (k == rows) {
        f += k * k; /* forward substitution with R11^T */
    } else {
        for (long j = 0; j < k; j++) f += f_reflect(rows - j);
        if (resid) f += f_nrm2(rows - k);
        f += k * k; /* back substitution with T */
    }
    for (long j = 0; j < k; j++) f += f_reflect(n - j);
    return f;
}

/* braun_qrcp_null_project: Q1^T, zero, Q1. */
static long f_null(long n, long k)
{
    long f = 0;
    for (long j = 0; j < k; j++) f += 2 * f_reflect(n - j);
    return f;
}

/* Component totals of one item. */
enum {
    C_SOLVE_RT, C_SOLVE_R, C_MUL_R, C_CHOL, C_QR, C_PINV, C_NULL, C_DOTS, C_RK, C_SCALAR,
    C_CHECKS, C_COUNT
};
static const char *const cname[C_COUNT] = {
    "chol_solve_rt", "chol_solve_r", "chol_mul_r", "chol_factor", "qrcp_factor",
    "pinv_apply", "null_project", "dots_axpys", "rk_combination", "scalars", "checks"};

/* The forward pass (braun__forward) at one state; wphi: Φ, b_q and the velocity error too. */
static void eval_ideal(const shape *s, int wphi, long *c)
{
    const long n = s->n, m = s->m, r = s->r;
    if (!s->mass_constant) {
        c[C_CHOL] += s->chol;
        c[C_CHECKS] += 2 * n * n;
    }
    c[C_SOLVE_RT] += s->st; /* atil = R^-T Q */
    if (r > 0) {
        if (wphi) c[C_DOTS] += m * (2 * n + 1); /* Φ̇_q = A_q v - b_q */
        c[C_SOLVE_RT] += r * s->st;            /* rows of C */
        c[C_DOTS] += r * (2 * n + 1);          /* b_v - C atil */
        if (s->need_fq && wphi) {
            c[C_QR] += f_qr(n, m, s->kq);
            c[C_SCALAR] += 2; /* default rank tolerance */
        }
        c[C_QR] += f_qr(n, r, s->k);
        c[C_SCALAR] += 2;
        c[C_PINV] += f_pinv(n, r, s->k, 0);
        c[C_DOTS] += n; /* z += u */
    }
    c[C_CHECKS] += 2 * n;
    if (wphi && r > 0) c[C_CHECKS] += 2 * r + 2 * m;
    c[C_SOLVE_R] += s->sr; /* vdot = R^-1 z */
}

/* braun__power at one state. */
static void power(const shape *s, long *c)
{
    if (s->energy_input) c[C_CHECKS] += 2;
    if (s->constraint_work) {
        c[C_MUL_R] += s->mulr;
        c[C_DOTS] += 2 * s->n + 1;
    }
}

/* The corrections (braun__corrections) with the given bits. */
static void corrections(const shape *s, unsigned corr, long *c)
{
    const long n = s->n, m = s->m, r = s->r;
    if (r > 0 && (corr & BRAUN_CORRECT_POSITION) && m > 0) {
        const long rows = s->need_fq ? m : r, k = s->need_fq ? s->kq : s->k;
        c[C_DOTS] += 2 * m; /* ep = -(Φ + h Φ̇) */
        c[C_PINV] += f_pinv(n, rows, k, k < rows);
        c[C_SOLVE_R] += s->sr;
    }
    if (r > 0 && (corr & BRAUN_CORRECT_VELOCITY)) {
        c[C_PINV] += f_pinv(n, r, s->k, 0);
        c[C_SOLVE_R] += s->sr;
    }
    if ((corr & BRAUN_CORRECT_ENERGY) && s->energy) {
        c[C_CHECKS] += 4 * n + 4; /* E, dE/dq, dE/dv, dE/dt */
        power(s, c);
        c[C_SCALAR] += 2 + 2 + 4 + 1 + 1; /* Φ_e, b_e, r, guard, σ */
        c[C_DOTS] += 2 * n + 4 * n + 2 * n; /* dE/dq·v, dE/dv·(q'', dv), ||x||² */
        c[C_SOLVE_RT] += s->st;             /* R^-T A_e^T */
        if (r > 0) c[C_NULL] += f_null(n, s->k);
        c[C_DOTS] += n + n; /* σ x, dv += */
        c[C_SOLVE_R] += s->sr;
    }
}

/* One RK4 step of braun_step with per-step corrections. */
static void step(const shape *s, unsigned corr, long *c)
{
    const long n = s->n, N = 2 * n + 1;
    for (int stage = 0; stage < 4; stage++) {
        eval_ideal(s, corr && stage == 0, c);
        power(s, c);
    }
    if (corr) corrections(s, corr, c);
    /* Stage states: a·h (1+2+3), one axpy of length N per later stage;
     * stage times t + c·h (4 x 2); weights b·h (4) and four axpys; the
     * correction increments (2n); t + h in braun__commit. */
    c[C_RK] += 6 + 3 * 2 * N + 8 + 4 + 4 * 2 * N + (corr ? 2 * n : 0) + 1;
    c[C_CHECKS] += 1; /* braun_step: h finite (h - h) */
    c[C_CHECKS] += 3 * 2 * N + 2 * N; /* stage states, result */
}

/* One braun_eval: state checks, the ideal part, the corrections / h. */
static void rhs(const shape *s, unsigned corr, long *c)
{
    const long n = s->n;
    c[C_CHECKS] += 1 + 4 * n + (corr ? 1 : 0);
    eval_ideal(s, corr != 0, c);
    if (corr) {
        corrections(s, corr, c);
        c[C_RK] += 4 * n; /* qdot += dq/h, vdot += dv/h */
    }
}

int bench_flops_write(FILE *out, const bench_target *tg)
{
    shape s;
    if (shape_of(tg, &s)) return -1;
    static const bench_item items[] = {BENCH_STEP_NONE, BENCH_STEP_PV, BENCH_STEP_ALL,
                                       BENCH_RHS_IDEAL, BENCH_RHS_CORR};
    for (size_t i = 0; i < sizeof items / sizeof items[0]; i++) {
        long c[C_COUNT] = {0};
        const unsigned corr = bench_item_corrections(tg, items[i]);
        if (items[i] >= BENCH_RHS_IDEAL)
            rhs(&s, corr, c);
        else
            step(&s, corr, c);
        long total = 0;
        for (int j = 0; j < C_COUNT; j++) {
            total += c[j];
            fprintf(out, "%s,%s,%s,%ld\n", tg->name, bench_item_name(items[i]), cname[j], c[j]);
        }
        fprintf(out, "%s,%s,total,%ld\n", tg->name, bench_item_name(items[i]), total);
        fprintf(out, "%s,%s,total_without_checks,%ld\n", tg->name, bench_item_name(items[i]),
                total - c[C_CHECKS]);
    }
    return 0;
}

int bench_flops_shape(const bench_target *tg, long *rank, long *solve_rt, long *solve_r)
{
    shape s;
    if (shape_of(tg, &s)) return -1;
    *rank = s.k;
    *solve_rt = s.st;
    *solve_r = s.sr;
    return 0;
}
