/* Equations of motion of a reference model from its T, V, φ and ψ
 * (ifm.h), by complex steps: every derivative is exact to round-off, none
 * is written by hand. Lagrange's equations with multipliers,
 *   d/dt ∂T/∂v - ∂T/∂q + ∂V/∂q = Q + Gᵀλ,  φ(q) = 0,
 * with ∂T/∂v = M(q) v, so M a = -Ṁv + ∂T/∂q - ∂V/∂q + Q + Gᵀλ. */
#include <math.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "ifm.h"

/* M(q) w for complex q and w: T is quadratic in v, so
 * T(w + e_j) - T(w - e_j) = 2 e_jᵀ M w exactly. */
static void mass_times(const ifm_model *md, const ifm_cx *q, const ifm_cx *w, ifm_cx *out)
{
    ifm_cx wp[IFM_MAX_N];
    const int n = md->n;
    for (int j = 0; j < n; j++) {
        memcpy(wp, w, (size_t)n * sizeof *wp);
        wp[j] = w[j] + 1;
        const ifm_cx tp = md->kinetic(md, q, wp);
        wp[j] = w[j] - 1;
        const ifm_cx tm = md->kinetic(md, q, wp);
        out[j] = 0.5 * (tp - tm);
    }
}

static void to_cx(int n, const double *x, ifm_cx *z)
{
    for (int i = 0; i < n; i++) z[i] = x[i];
}

void ifm_mass(const ifm_model *md, const double *q, double *M)
{
    const int n = md->n;
    ifm_cx qc[IFM_MAX_N], e[IFM_MAX_N], Me[IFM_MAX_N];
    to_cx(n, q, qc);
    for (int k = 0; k < n; k++) {
        for (int i = 0; i < n; i++) e[i] = i == k;
        mass_times(md, qc, e, Me);
        for (int j = 0; j < n; j++) M[j * n + k] = creal(Me[j]);
    }
    /* Symmetric by construction up to round-off: make it exactly so. */
    for (int j = 0; j < n; j++)
        for (int k = j + 1; k < n; k++) {
            const double s = 0.5 * (M[j * n + k] + M[k * n + j]);
            M[j * n + k] = M[k * n + j] = s;
        }
}

void ifm_forces(const ifm_model *md, double t, const double *q, const double *v, double *F)
{
    const int n = md->n;
    const double h = IFM_CSTEP;
    ifm_cx qc[IFM_MAX_N] = {0}, vc[IFM_MAX_N] = {0}, Mv[IFM_MAX_N];
    to_cx(n, v, vc);
    /* Ṁv = d/dε [M(q + εv) v]: one complex step along v. */
    for (int i = 0; i < n; i++) qc[i] = q[i] + I * h * v[i];
    mass_times(md, qc, vc, Mv);
    for (int i = 0; i < n; i++) F[i] = -cimag(Mv[i]) / h;
    /* ∂T/∂q_k and -∂V/∂q_k. */
    for (int k = 0; k < n; k++) {
        to_cx(n, q, qc);
        qc[k] += I * h;
        F[k] += cimag(md->kinetic(md, qc, vc)) / h;
        if (md->potential) F[k] -= cimag(md->potential(md, qc)) / h;
    }
    if (md->nonconservative) {
        double Q[IFM_MAX_N];
        md->nonconservative(md, t, q, v, Q);
        for (int i = 0; i < n; i++) F[i] += Q[i];
    }
}

void ifm_phi(const ifm_model *md, const double *q, double *phi)
{
    ifm_cx qc[IFM_MAX_N], out[IFM_MAX_M];
    to_cx(md->n, q, qc);
    md->phi(md, qc, out);
    for (int i = 0; i < md->m; i++) phi[i] = creal(out[i]);
}

void ifm_psi(const ifm_model *md, const double *q, const double *v, double *psi)
{
    ifm_cx qc[IFM_MAX_N], vc[IFM_MAX_N], out[IFM_MAX_M];
    to_cx(md->n, q, qc);
    to_cx(md->n, v, vc);
    md->psi(md, qc, vc, out);
    for (int i = 0; i < md->m; i++) psi[i] = creal(out[i]);
}

/* G's columns: ψ is linear in v. */
void ifm_jacobian(const ifm_model *md, const double *q, double *G)
{
    const int n = md->n, m = md->m;
    ifm_cx qc[IFM_MAX_N], e[IFM_MAX_N], out[IFM_MAX_M];
    to_cx(n, q, qc);
    for (int k = 0; k < n; k++) {
        for (int i = 0; i < n; i++) e[i] = i == k;
        md->psi(md, qc, e, out);
        for (int r = 0; r < m; r++) G[r * n + k] = creal(out[r]);
    }
}

/* c = (∂ψ/∂q) v = d/dε ψ(q + εv, v). */
void ifm_gamma(const ifm_model *md, const double *q, const double *v, double *c)
{
    const int n = md->n;
    const double h = IFM_CSTEP;
    ifm_cx qc[IFM_MAX_N], vc[IFM_MAX_N], out[IFM_MAX_M];
    for (int i = 0; i < n; i++) {
        qc[i] = q[i] + I * h * v[i];
        vc[i] = v[i];
    }
    md->psi(md, qc, vc, out);
    for (int r = 0; r < md->m; r++) c[r] = cimag(out[r]) / h;
}

double ifm_kinetic(const ifm_model *md, const double *q, const double *v)
{
    ifm_cx qc[IFM_MAX_N], vc[IFM_MAX_N];
    to_cx(md->n, q, qc);
    to_cx(md->n, v, vc);
    return creal(md->kinetic(md, qc, vc));
}

double ifm_energy(const ifm_model *md, const double *q, const double *v)
{
    ifm_cx qc[IFM_MAX_N];
    to_cx(md->n, q, qc);
    return ifm_kinetic(md, q, v) + (md->potential ? creal(md->potential(md, qc)) : 0.0);
}

double ifm_power(const ifm_model *md, double t, const double *q, const double *v)
{
    if (!md->nonconservative) return 0;
    double Q[IFM_MAX_N], P = 0;
    md->nonconservative(md, t, q, v, Q);
    for (int i = 0; i < md->n; i++) P += Q[i] * v[i];
    return P;
}

/* Solve the square system A x = b (k x k, row-major, overwritten) by LU
 * with partial pivoting; 0 or -1 if singular. */
static int solve_square(int k, double *A, double *b, double *x)
{
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)k, (size_t)k);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)k);
    gsl_vector_view xv = gsl_vector_view_array(x, (size_t)k);
    gsl_permutation *p = gsl_permutation_alloc((size_t)k);
    int sgn = 0, st = -1;
    if (!p) return -1;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    if (gsl_linalg_LU_decomp(&Av.matrix, p, &sgn) == 0) {
        double pivmax = 0, pivmin = INFINITY;
        for (int i = 0; i < k; i++) {
            const double d = fabs(A[i * k + i]);
            if (d > pivmax) pivmax = d;
            if (d < pivmin) pivmin = d;
        }
        if (pivmin > 1e-14 * pivmax && gsl_linalg_LU_solve(&Av.matrix, p, &bv.vector, &xv.vector) == 0)
            st = 0;
    }
    gsl_set_error_handler(old);
    gsl_permutation_free(p);
    return st;
}

int ifm_accel(const ifm_model *md, double t, const double *q, const double *v, double *a,
              double *lambda)
{
    const int n = md->n, m = md->m, k = n + m;
    double K[(IFM_MAX_N + IFM_MAX_M) * (IFM_MAX_N + IFM_MAX_M)];
    double rhs[IFM_MAX_N + IFM_MAX_M], x[IFM_MAX_N + IFM_MAX_M];
    double M[IFM_MAX_N * IFM_MAX_N], G[IFM_MAX_M * IFM_MAX_N];
    ifm_mass(md, q, M);
    ifm_forces(md, t, q, v, rhs);
    if (m > 0) {
        ifm_jacobian(md, q, G);
        ifm_gamma(md, q, v, rhs + n);
        for (int r = 0; r < m; r++) rhs[n + r] = -rhs[n + r];
    }
    /* [M  -Gᵀ; G  0] [a; λ] = [F; -c] */
    for (int i = 0; i < k * k; i++) K[i] = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) K[i * k + j] = M[i * n + j];
    for (int r = 0; r < m; r++)
        for (int j = 0; j < n; j++) {
            K[(n + r) * k + j] = G[r * n + j];
            K[j * k + n + r] = -G[r * n + j];
        }
    if (solve_square(k, K, rhs, x)) return -1;
    memcpy(a, x, (size_t)n * sizeof *a);
    if (lambda) memcpy(lambda, x + n, (size_t)m * sizeof *lambda);
    return 0;
}

/* Minimum-norm (fixed < 0) or fixed-coordinate solution of G dx = r. */
static int constrained_step(const ifm_model *md, int fixed, const double *G, const double *r,
                            double *dx)
{
    const int n = md->n, m = md->m;
    double A[IFM_MAX_N * IFM_MAX_N], b[IFM_MAX_N], y[IFM_MAX_N];
    if (fixed >= 0) {
        /* m equations in the n - 1 other coordinates: square when the rows
         * are independent and the coordinate is a good choice. */
        if (m != n - 1) return -1;
        for (int row = 0; row < m; row++) {
            int c = 0;
            for (int j = 0; j < n; j++)
                if (j != fixed) A[row * m + c++] = G[row * n + j];
            b[row] = r[row];
        }
        if (solve_square(m, A, b, y)) return -1;
        for (int j = 0, c = 0; j < n; j++) dx[j] = j == fixed ? 0.0 : y[c++];
        return 0;
    }
    /* dx = Gᵀ (G Gᵀ)⁻¹ r */
    for (int i = 0; i < m; i++) {
        for (int j = 0; j < m; j++) {
            double s = 0;
            for (int k = 0; k < n; k++) s += G[i * n + k] * G[j * n + k];
            A[i * m + j] = s;
        }
        b[i] = r[i];
    }
    if (solve_square(m, A, b, y)) return -1;
    for (int k = 0; k < n; k++) {
        double s = 0;
        for (int i = 0; i < m; i++) s += G[i * n + k] * y[i];
        dx[k] = s;
    }
    return 0;
}

int ifm_project(const ifm_model *md, int fixed, double *q, double *v, double tol)
{
    const int n = md->n, m = md->m;
    double G[IFM_MAX_M * IFM_MAX_N], phi[IFM_MAX_M], dx[IFM_MAX_N];
    if (m == 0) return 0;
    /* Converged at |φ| <= tol, or where Newton stops gaining (round-off)
     * within 100 tol. */
    int converged = 0;
    double prev = INFINITY;
    for (int it = 0; it < 60; it++) {
        ifm_phi(md, q, phi);
        double norm = 0;
        for (int r = 0; r < m; r++) norm = fmax(norm, fabs(phi[r]));
        if (norm <= tol || (it >= 2 && norm > 0.5 * prev && norm <= 100 * tol)) {
            converged = 1;
            break;
        }
        prev = norm;
        ifm_jacobian(md, q, G);
        for (int r = 0; r < m; r++) phi[r] = -phi[r];
        if (constrained_step(md, fixed, G, phi, dx)) return -1;
        for (int j = 0; j < n; j++) q[j] += dx[j];
    }
    if (!converged) return -1;
    if (v) {
        double psi[IFM_MAX_M];
        ifm_jacobian(md, q, G);
        ifm_psi(md, q, v, psi);
        for (int r = 0; r < m; r++) psi[r] = -psi[r];
        if (constrained_step(md, fixed, G, psi, dx)) return -1;
        for (int j = 0; j < n; j++) v[j] += dx[j];
    }
    return 0;
}
