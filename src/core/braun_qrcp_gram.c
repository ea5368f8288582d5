/* C⁺ through the Gram matrix G = C Cᵀ = L D Lᵀ, for the stages that are
 * far from every rank decision (braun_linalg.h, braun_qrcp_factor_gram;
 * the dense backend's choice: braun_dense.h, braun__dense_factor_c).
 *
 * Why: at the sizes of a mechanism (C of 5 x 6 on the slider-crank) the
 * Householder QR of Cᵀ is a chain of dependent operations — per column a
 * norm, its square root, a division, then reflections whose dot products
 * wait for it — and that chain, not the flop count, sets a step's time
 * (docs/performance.md, "Where the time goes"). G's entries are
 * independent dot products, its LDLᵀ needs one division per row and no
 * square root, and the solves are two short triangular sweeps.
 *
 * What it costs in accuracy: the normal equations square the condition
 * number, so the solves carry ≈ ε·κ(C)² instead of the QR's ε·κ(C). The
 * factorization is accepted only when every pivot d_i (= |R_ii|², R the
 * triangle an unpivoted QR of Cᵀ would give) exceeds gate²·max_i ‖c_i‖²:
 * the test the ordered QR applies to its pivots, a heuristic as the
 * pivoted QR's own rank estimate is (pivots do not bound σ_min in general),
 * and in practice κ(C) ≲ √rows/gate (docs/method.md, "The Gram path").
 * The order is C's own: no permutation to follow (−9 % instructions per
 * step on the Cortex-M4F against the last pivoted order), and LDLᵀ of an
 * SPD matrix is stable without pivoting.
 *
 * Layout while f->gram is set: f->a holds C itself, f->s the unit lower
 * triangle L (row-major, rows x rows), f->stau the reciprocal pivots
 * 1/d_i; f->work and f->tau are the solves' scratch. */
#include "braun_linalg.h"

/* Row i of C. */
#define CROW(f, i, n) ((f)->a + (size_t)(i) * (size_t)(n))

/* The largest factor kept in local arrays (registers) while it is formed. */
#define BRAUN_GRAM_LOCAL 8

int braun_qrcp_factor_gram(braun_qrcp *f, braun_real gate, braun_real rel_gate)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
    braun_real *norm2 = f->work, *L = f->s, *dinv = f->stau, *t = f->tau;
    if (rows > n || rows == 0 || f->rank != rows || !(gate < 1) || !(rel_gate < 1)) return -1;
    /* The rows' squared norms are G's diagonal (the sums the pivoted
     * factorization takes too: on refusal they stay given for it). */
    if (!(BRAUN_FUSED_NORMS && f->norms_given)) {
        BRAUN_UNROLL
        for (int j = 0; j < rows; j++) norm2[j] = braun_dot(n, CROW(f, j, n), CROW(f, j, n));
        f->norms_given = BRAUN_FUSED_NORMS;
    }
    braun_real big = 0;
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++)
        if (norm2[j] > big) big = norm2[j];
    const braun_real floor2 = gate * gate * big, rel2 = rel_gate * rel_gate;
    /* G's strict lower triangle: independent dot products, one dispatch
     * on n. */
#define GRAM_BODY(N, UNROLL)                                                            \
    BRAUN_UNROLL for (int i = 1; i < rows; i++) {                                       \
        const braun_real *restrict ci = CROW(f, i, n);                                  \
        BRAUN_UNROLL for (int j = 0; j < i; j++) {                                      \
            const braun_real *restrict cj = CROW(f, j, n);                              \
            braun_real s = 0;                                                           \
            UNROLL for (int k = 0; k < (N); k++) s += ci[k] * cj[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            L[(size_t)i * (size_t)rows + (size_t)j] = s;                                \
        }                                                                               \
    }
    BRAUN_SMALL_DISPATCH(n, GRAM_BODY)
#undef GRAM_BODY
    /* L D Lᵀ row by row: t_j = L_ij d_j, then L_ij, then d_i. At the
     * dispatched sizes on local arrays the compiler keeps in registers:
     * every pivot waits for the ones before it, and a store and a reload
     * of t, L or 1/d would add its forwarding latency to that chain. The
     * factor is written out once, for the solves. */
    braun_real dmin2 = 0;
    int ill = 0; /* a pivot below rel_gate² of its row's G_ii */
#define LDL_BODY(R, UNROLL)                                                             \
    {                                                                                   \
    braun_real Lloc[BRAUN_GRAM_LOCAL * BRAUN_GRAM_LOCAL], tloc[BRAUN_GRAM_LOCAL], dloc[BRAUN_GRAM_LOCAL]; \
    const int local_ = BRAUN_CONSTANT_P(R) && (R) <= BRAUN_GRAM_LOCAL;                  \
    braun_real *Lw = local_ ? Lloc : L, *tw = local_ ? tloc : t, *dw = local_ ? dloc : dinv; \
    UNROLL for (int i = 0; i < (R); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        braun_real *li = Lw + (size_t)i * (size_t)(R);                                  \
        const braun_real *gi = L + (size_t)i * (size_t)(R); /* G's row */               \
        UNROLL for (int j = 0; j < i; j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            const braun_real *lj = Lw + (size_t)j * (size_t)(R);                        \
            braun_real s = gi[j];                                                       \
            UNROLL for (int k = 0; k < j; k++) s -= tw[k] * lj[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            tw[j] = s;                                                                  \
        }                                                                               \
        const braun_real gii = norm2[i];                                             \
        braun_real d = gii;                                                        \
        UNROLL for (int j = 0; j < i; j++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            const braun_real l = tw[j] * dw[j];                                         \
            li[j] = l;                                                                  \
            d -= tw[j] * l;                                                             \
        }                                                                               \
        if (!(d > floor2)) return -1; /* NaN too; C and its norms stay */              \
        if (!(d > rel2 * gii)) ill = 1;                                                 \
        dw[i] = 1 / d;                                                                  \
        if (i == 0 || d < dmin2) dmin2 = d;                                             \
    }                                                                                   \
    if (local_) {                                                                       \
        UNROLL for (int i = 0; i < (R); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            dinv[i] = dw[i];                                                            \
            UNROLL for (int j = 0; j < i; j++) /* NOLINT(bugprone-macro-parentheses): a pragma */ \
                L[(size_t)i * (size_t)(R) + (size_t)j] = Lw[(size_t)i * (size_t)(R) + (size_t)j]; \
        }                                                                               \
    }                                                                                   \
    }
    BRAUN_SMALL_DISPATCH(rows, LDL_BODY)
#undef LDL_BODY
    if (ill) return -2;
    f->norms_given = 0;
    f->gram = 1;
    f->nsoft = 0;
    f->rank = rows;
    f->dmin = braun_sqrt(dmin2);
    f->r00 = braun_sqrt(big);
    return rows;
}

/* w := G⁻¹ w, and the same for w2 when not NULL:
 * forward with L, the pivots, back with Lᵀ. */
static void gram_solve(const braun_qrcp *f, braun_real *restrict w, braun_real *restrict w2)
{
    const int rows = BRAUN_ROWS(f->rows);
    const braun_real *restrict L = f->s, *restrict dinv = f->stau;
#define SOLVE_BODY(R, UNROLL, W)                                                        \
    UNROLL for (int i = 0; i < (R); i++) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        const braun_real *restrict li = L + (size_t)i * (size_t)(R);                    \
        braun_real s = (W)[i];                                                          \
        UNROLL for (int j = 0; j < i; j++) s -= li[j] * (W)[j]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        (W)[i] = s;                                                                     \
    }                                                                                   \
    UNROLL for (int i = 0; i < (R); i++) (W)[i] *= dinv[i]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
    UNROLL for (int i = (R) - 1; i >= 0; i--) { /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        braun_real s = (W)[i];                                                          \
        UNROLL for (int j = i + 1; j < (R); j++) /* NOLINT(bugprone-macro-parentheses): a pragma */ \
            s -= L[(size_t)j * (size_t)(R) + (size_t)i] * (W)[j];                       \
        (W)[i] = s;                                                                     \
    }
#define SOLVE1(R, UNROLL) SOLVE_BODY(R, UNROLL, w)
#define SOLVE2(R, UNROLL) SOLVE_BODY(R, UNROLL, w) SOLVE_BODY(R, UNROLL, w2)
    if (w2) {
        BRAUN_SMALL_DISPATCH(rows, SOLVE2)
    } else {
        BRAUN_SMALL_DISPATCH(rows, SOLVE1)
    }
#undef SOLVE1
#undef SOLVE2
#undef SOLVE_BODY
}

/* x[n] := Cᵀ w. */
static void gram_ct(const braun_qrcp *f, const braun_real *restrict w, braun_real *restrict x)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
#define CT_BODY(N, UNROLL)                                                              \
    {                                                                                   \
        const braun_real *restrict c0 = CROW(f, 0, n);                                  \
        UNROLL for (int k = 0; k < (N); k++) x[k] = w[0] * c0[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        BRAUN_UNROLL for (int j = 1; j < rows; j++) {                                   \
            const braun_real *restrict cj = CROW(f, j, n);                              \
            const braun_real wj = w[j];                                                 \
            UNROLL for (int k = 0; k < (N); k++) x[k] += wj * cj[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
        }                                                                               \
    }
    BRAUN_SMALL_DISPATCH(n, CT_BODY)
#undef CT_BODY
}

void braun_qrcp_gram_lsq(const braun_qrcp *f, const braun_real *r, braun_real *x, braun_real *resid)
{
    const int rows = BRAUN_ROWS(f->rows);
    braun_real *w = f->work;
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++) w[j] = r[j];
    gram_solve(f, w, NULL);
    gram_ct(f, w, x);
    if (resid) *resid = 0; /* full row rank: every r is reached */
}

void braun_qrcp_gram_pinv2(const braun_qrcp *f, const braun_real *r1, const braun_real *r2,
                           braun_real *x1, braun_real *x2)
{
    const int rows = BRAUN_ROWS(f->rows);
    braun_real *w = f->work, *w2 = f->tau;
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++) {
        w[j] = r1[j];
        w2[j] = r2[j];
    }
    gram_solve(f, w, w2);
    gram_ct(f, w, x1);
    gram_ct(f, w2, x2);
}

void braun_qrcp_gram_null_project(const braun_qrcp *f, braun_real *z)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
    braun_real *w = f->work;
    if (rows == n) {
        /* Square and of full rank: no null space. Exactly 0, as the QR's
         * projector gives (a fully driven mechanism has no free direction
         * for the energy force). */
        for (int k = 0; k < n; k++) z[k] = 0;
        return;
    }
    BRAUN_UNROLL
    for (int j = 0; j < rows; j++) w[j] = braun_dot(n, CROW(f, j, n), z);
    gram_solve(f, w, NULL);
    /* z −= Cᵀw, one dispatch on n. */
#define NP_BODY(N, UNROLL)                                                              \
    BRAUN_UNROLL for (int j = 0; j < rows; j++) {                                       \
        const braun_real *restrict cj = CROW(f, j, n), wj = w[j];                       \
        UNROLL for (int k = 0; k < (N); k++) z[k] -= wj * cj[k]; /* NOLINT(bugprone-macro-parentheses): a pragma */ \
    }
    BRAUN_SMALL_DISPATCH(n, NP_BODY)
#undef NP_BODY
}
