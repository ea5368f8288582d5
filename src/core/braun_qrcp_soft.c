/* Soft directions of a rank-revealing factorization (braun_linalg.h): the
 * right singular vectors of C whose singular values are kept by the rank
 * decision but are below a threshold — near a singular configuration, the
 * directions in which the index-1 flow turns a velocity error into a stiff
 * acceleration (docs/method.md, "Redundant rows through a singular
 * configuration"). Found only when the factor's diagonal says one may
 * exist — a scan of k numbers otherwise.
 *
 * The factorization is C = P M Q1ᵀ with M the k x k triangle the solves
 * use: M = R11ᵀ (lower) when every row counts, M = T (upper, the QR of
 * S = [R11 R12]ᵀ) when some are dependent. C's singular values are M's;
 * its right singular vectors are Q1 times M's. */
#include "braun_linalg.h"

/* Column j of the factor, as in braun_qrcp.c. */
#define COL(a, f, j, n) ((a) + (size_t)(f)->perm[j] * (size_t)(n))

/* M(i, j) of the triangle the solves use (0 outside it). */
static braun_real tri(const braun_qrcp *f, int i, int j)
{
    const int n = BRAUN_N(f->n), rows = BRAUN_ROWS(f->rows);
    if (f->rank == rows) /* M = R11ᵀ: M(i, j) = R(j, i), j <= i */
        return j <= i ? COL(f->a, f, i, n)[j] : 0;
    return i <= j ? f->s[(size_t)j * (size_t)rows + (size_t)i] : 0; /* M = T */
}

/* y := M⁻¹ b (trans 0) or M⁻ᵀ b (trans 1); y may be b. */
static void tri_solve(const braun_qrcp *f, int trans, const braun_real *b, braun_real *y)
{
    const int k = f->rank, lower = f->rank == BRAUN_ROWS(f->rows);
    /* The system's own triangle is lower for (lower, no transpose) and for
     * (upper, transpose): forward substitution; otherwise backward. */
    if (lower != trans) {
        for (int i = 0; i < k; i++) {
            braun_real sum = b[i];
            for (int j = 0; j < i; j++) sum -= (trans ? tri(f, j, i) : tri(f, i, j)) * y[j];
            y[i] = sum / tri(f, i, i);
        }
    } else {
        for (int i = k - 1; i >= 0; i--) {
            braun_real sum = b[i];
            for (int j = i + 1; j < k; j++) sum -= (trans ? tri(f, j, i) : tri(f, i, j)) * y[j];
            y[i] = sum / tri(f, i, i);
        }
    }
}

/* ‖M x‖². */
static braun_real tri_norm2(const braun_qrcp *f, const braun_real *x)
{
    const int k = f->rank;
    braun_real s = 0;
    for (int i = 0; i < k; i++) {
        braun_real y = 0;
        for (int j = 0; j < k; j++) y += tri(f, i, j) * x[j];
        s += y * y;
    }
    return s;
}

/* Orthonormalize the p columns of V (k x p, column-major; modified
 * Gram–Schmidt). */
static void orthonormalize(int k, int p, braun_real *V)
{
    for (int c = 0; c < p; c++) {
        braun_real *v = V + (size_t)c * (size_t)k;
        for (int e = 0; e < c; e++) {
            const braun_real *w = V + (size_t)e * (size_t)k;
            const braun_real d = braun_dot(k, v, w);
            for (int i = 0; i < k; i++) v[i] -= d * w[i];
        }
        const braun_real nv = braun_nrm2(k, v);
        for (int i = 0; i < k; i++) v[i] = nv > 0 ? v[i] / nv : (braun_real)(i == c);
    }
}

int braun_qrcp_soft_find(braun_qrcp *f, braun_real rel)
{
    const int k = f->rank;
    f->nsoft = 0;
    if (k == 0 || !(rel > 0)) return 0;
    /* λ relative to the first pivot (the largest row norm of C: within a
     * factor sqrt(rows) of ‖C‖). A triangle's singular values lie below its
     * smallest diagonal entry, so none is below the threshold unless some
     * |M_ii| is; pivoting puts those last. */
    const braun_real lam = rel * braun_fabs(COL(f->a, f, 0, BRAUN_N(f->n))[0]);
    const braun_real thresh = BRAUN_SOFT_GATE * lam;
    if (!(f->dmin < thresh)) return 0; /* the common case: one compare */
    int cand[BRAUN_SOFT_MAX], p = 0;
    for (int i = k - 1; i >= 0 && p < BRAUN_SOFT_MAX; i--)
        if (braun_fabs(tri(f, i, i)) < thresh) cand[p++] = i;
    if (p == 0) return 0;

    /* Subspace inverse iteration on (MᵀM)⁻¹ = M⁻¹M⁻ᵀ from the unit vectors
     * of the small diagonal entries: the soft directions are separated
     * from the rest by the factor (σ_soft/σ_next)² per sweep. */
    braun_real *V = f->soft, *sig = V + (size_t)BRAUN_SOFT_MAX * (size_t)k,
               *y = sig + BRAUN_SOFT_MAX;
    for (int c = 0; c < p; c++)
        for (int i = 0; i < k; i++) V[(size_t)c * (size_t)k + (size_t)i] = (braun_real)(i == cand[c]);
    for (int sweep = 0; sweep < 3; sweep++) {
        for (int c = 0; c < p; c++) {
            braun_real *v = V + (size_t)c * (size_t)k;
            tri_solve(f, 1, v, y);
            tri_solve(f, 0, y, v);
            /* scale before the next sweep: 1/σ² can be 1e30 */
            const braun_real nv = braun_nrm2(k, v);
            if (nv > 0 && braun_is_finite(nv))
                for (int i = 0; i < k; i++) v[i] /= nv;
        }
        orthonormalize(k, p, V);
    }
    /* Rayleigh–Ritz on span(V): with p <= BRAUN_SOFT_MAX the small
     * symmetric eigenproblem of B = (MV)ᵀ(MV) is solved by Jacobi
     * rotations applied to V directly. */
    for (int sweep = 0; sweep < 8 && p > 1; sweep++) {
        braun_real off = 0;
        for (int a = 0; a < p; a++)
            for (int b = a + 1; b < p; b++) {
                braun_real *va = V + (size_t)a * (size_t)k, *vb = V + (size_t)b * (size_t)k;
                for (int i = 0; i < k; i++) y[i] = va[i] + vb[i];
                const braun_real baa = tri_norm2(f, va), bbb = tri_norm2(f, vb);
                const braun_real bab = (tri_norm2(f, y) - baa - bbb) / 2;
                if (bab == 0) continue;
                off += braun_fabs(bab);
                const braun_real z = (bbb - baa) / (2 * bab);
                const braun_real t = (z >= 0 ? 1 : -1) / (braun_fabs(z) + braun_sqrt(1 + z * z));
                const braun_real cs = 1 / braun_sqrt(1 + t * t), sn = cs * t;
                for (int i = 0; i < k; i++) {
                    const braun_real x1 = va[i], x2 = vb[i];
                    va[i] = cs * x1 - sn * x2;
                    vb[i] = sn * x1 + cs * x2;
                }
            }
        if (off == 0) break;
    }
    /* Keep the directions whose singular value is below the threshold. */
    int kept = 0;
    for (int c = 0; c < p; c++) {
        const braun_real *v = V + (size_t)c * (size_t)k;
        const braun_real s = braun_sqrt(tri_norm2(f, v));
        if (!(s < thresh)) continue;
        braun_real *dst = V + (size_t)kept * (size_t)k;
        for (int i = 0; i < k && dst != v; i++) dst[i] = v[i];
        sig[kept++] = s;
    }
    f->soft_lam = lam;
    f->nsoft = kept;
    return kept;
}

void braun_qrcp_soft_project(const braun_qrcp *f, const braun_real *x, braun_real *y,
                             braun_real rate)
{
    const int n = BRAUN_N(f->n), k = f->rank, p = f->nsoft;
    const braun_real *V = f->soft;
    braun_real *xw = (braun_real *)(V + (size_t)BRAUN_SOFT_MAX * (size_t)k + BRAUN_SOFT_MAX) + k;
    const braun_real *sig = V + (size_t)BRAUN_SOFT_MAX * (size_t)k;
    /* The weights: w = λ⁴/(σ⁴ + λ⁴) (1 for σ << λ, 1e-4 at the gate: the
     * operator is smooth where directions come and go), times z⁴/(1 + z⁴)
     * with z = rate/σ when a rate is given: nothing where the direction is
     * not stiff for the step. */
    braun_real w[BRAUN_SOFT_MAX];
    const braun_real l4 = f->soft_lam * f->soft_lam * f->soft_lam * f->soft_lam;
    for (int c = 0; c < p; c++) {
        const braun_real s2 = sig[c] * sig[c], s4 = s2 * s2;
        w[c] = l4 / (s4 + l4);
        if (rate > 0) {
            const braun_real r2 = rate * rate, r4 = r2 * r2;
            w[c] *= r4 / (r4 + s4);
        }
    }
    /* xw = Q1ᵀ x (the reflectors in order, the first k entries); then
     * y = Q1 Σ w_c v_c (v_cᵀ xw). */
    for (int i = 0; i < n; i++) xw[i] = x[i];
    for (int j = 0; j < k && p > 0; j++)
        braun_qrcp__reflect(n - j, COL(f->a, f, j, n) + j + 1, f->tau[j], xw + j);
    for (int i = 0; i < n; i++) y[i] = 0;
    for (int c = 0; c < p; c++) {
        const braun_real *v = V + (size_t)c * (size_t)k;
        const braun_real a = w[c] * braun_dot(k, v, xw);
        for (int i = 0; i < k; i++) y[i] += a * v[i];
    }
    for (int j = k - 1; j >= 0 && p > 0; j--)
        braun_qrcp__reflect(n - j, COL(f->a, f, j, n) + j + 1, f->tau[j], y + j);
}
