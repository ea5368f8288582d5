/* The harness's own dense linear algebra (GSL), independent of libbraun's:
 * minimum-M-norm corrections and constrained accelerations with
 * multipliers, both through the pseudoinverse of C = A R⁻¹ (M = RᵀR), so
 * redundant rows and singular configurations are handled the same way the
 * paper does (Sec. 2.4). Used for consistent initial values of IDA and by
 * the tests as an independent check. Small systems only: C⁺ is formed. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>

#include "cmp.h"

/* L (lower Cholesky factor of M, M = L Lᵀ, R = Lᵀ), C = A L⁻ᵀ and the
 * pseudoinverse P = C⁺ (n x rows). */
typedef struct wsys {
    int n, rows;
    gsl_matrix *L, *C, *P;
} wsys;

static void wsys_free(wsys *w)
{
    if (w->L) gsl_matrix_free(w->L);
    if (w->C) gsl_matrix_free(w->C);
    if (w->P) gsl_matrix_free(w->P);
}

/* Pseudoinverse of a (r x c) matrix with r >= c via SVD: a = U S Vᵀ,
 * a⁺ = V S⁺ Uᵀ (c x r). Singular values below 10·max(r,c)·ε·s_max count
 * as zero (the same rule as libbraun's default rank tolerance). */
static int pinv_tall(const gsl_matrix *a, gsl_matrix *out)
{
    const size_t r = a->size1, c = a->size2;
    gsl_matrix *U = gsl_matrix_alloc(r, c), *V = gsl_matrix_alloc(c, c);
    gsl_vector *S = gsl_vector_alloc(c), *work = gsl_vector_alloc(c);
    int st = -1;
    if (!U || !V || !S || !work) goto done;
    gsl_matrix_memcpy(U, a);
    if (gsl_linalg_SV_decomp(U, V, S, work)) goto done;
    const double smax = gsl_vector_get(S, 0);
    const double tol = 10.0 * (double)(r > c ? r : c) * DBL_EPSILON * smax;
    gsl_matrix_set_zero(out);
    for (size_t k = 0; k < c; k++) {
        const double s = gsl_vector_get(S, k);
        if (!(s > tol)) continue;
        for (size_t i = 0; i < c; i++)
            for (size_t j = 0; j < r; j++)
                out->data[i * out->tda + j] +=
                    gsl_matrix_get(V, i, k) * gsl_matrix_get(U, j, k) / s;
    }
    st = 0;
done:
    if (U) gsl_matrix_free(U);
    if (V) gsl_matrix_free(V);
    if (S) gsl_vector_free(S);
    if (work) gsl_vector_free(work);
    return st;
}

static int wsys_init(wsys *w, int n, int rows, const double *M, const double *A)
{
    w->n = n;
    w->rows = rows;
    w->L = gsl_matrix_alloc((size_t)n, (size_t)n);
    w->C = rows > 0 ? gsl_matrix_alloc((size_t)rows, (size_t)n) : NULL;
    w->P = rows > 0 ? gsl_matrix_alloc((size_t)n, (size_t)rows) : NULL;
    if (!w->L || (rows > 0 && (!w->C || !w->P))) return -1;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) gsl_matrix_set(w->L, (size_t)i, (size_t)j, M[i * n + j]);
    if (gsl_linalg_cholesky_decomp1(w->L)) return -1;
    if (rows == 0) return 0;
    /* Row i of C is (L⁻¹ a_i)ᵀ. */
    for (int i = 0; i < rows; i++) {
        gsl_vector_view ci = gsl_matrix_row(w->C, (size_t)i);
        for (int j = 0; j < n; j++) gsl_vector_set(&ci.vector, (size_t)j, A[i * n + j]);
        gsl_blas_dtrsv(CblasLower, CblasNoTrans, CblasNonUnit, w->L, &ci.vector);
    }
    if (rows >= n) return pinv_tall(w->C, w->P);
    /* Wide C: C⁺ = ((Cᵀ)⁺)ᵀ. */
    gsl_matrix *Ct = gsl_matrix_alloc((size_t)n, (size_t)rows);
    gsl_matrix *Pt = gsl_matrix_alloc((size_t)rows, (size_t)n);
    int st = -1;
    if (Ct && Pt) {
        gsl_matrix_transpose_memcpy(Ct, w->C);
        st = pinv_tall(Ct, Pt);
        if (!st) gsl_matrix_transpose_memcpy(w->P, Pt);
    }
    if (Ct) gsl_matrix_free(Ct);
    if (Pt) gsl_matrix_free(Pt);
    return st;
}

int cmp_min_norm_step(int n, int rows, const double *M, const double *A,
                      const double *r, double *dx)
{
    wsys w = {0, 0, NULL, NULL, NULL};
    int st = wsys_init(&w, n, rows, M, A);
    if (!st) {
        /* dx = L⁻ᵀ C⁺ r. */
        gsl_vector_view x = gsl_vector_view_array(dx, (size_t)n);
        gsl_vector_const_view rv = gsl_vector_const_view_array(r, (size_t)rows);
        if (rows > 0)
            gsl_blas_dgemv(CblasNoTrans, 1.0, w.P, &rv.vector, 0.0, &x.vector);
        else
            gsl_vector_set_zero(&x.vector);
        gsl_blas_dtrsv(CblasLower, CblasTrans, CblasNonUnit, w.L, &x.vector);
    }
    wsys_free(&w);
    return st;
}

int cmp_kkt_accel(int n, int rows, const double *M, const double *Q,
                  const double *A, const double *b, double *acc, double *lambda)
{
    wsys w = {0, 0, NULL, NULL, NULL};
    int st = wsys_init(&w, n, rows, M, A);
    gsl_vector *at = gsl_vector_alloc((size_t)n), *u = gsl_vector_alloc((size_t)n);
    gsl_vector *res = rows > 0 ? gsl_vector_alloc((size_t)rows) : NULL;
    if (!at || !u || (rows > 0 && !res)) st = -1;
    if (!st) {
        /* ã = L⁻¹Q; u = C⁺(b - Cã); a = L⁻ᵀ(ã + u); λ = (C⁺)ᵀu, the
         * minimum-norm multipliers of A M⁻¹Aᵀλ = b - A M⁻¹Q. */
        for (int i = 0; i < n; i++) gsl_vector_set(at, (size_t)i, Q[i]);
        gsl_blas_dtrsv(CblasLower, CblasNoTrans, CblasNonUnit, w.L, at);
        gsl_vector_set_zero(u);
        if (rows > 0) {
            for (int i = 0; i < rows; i++) gsl_vector_set(res, (size_t)i, b[i]);
            gsl_blas_dgemv(CblasNoTrans, -1.0, w.C, at, 1.0, res);
            gsl_blas_dgemv(CblasNoTrans, 1.0, w.P, res, 0.0, u);
            if (lambda) {
                gsl_vector_view lv = gsl_vector_view_array(lambda, (size_t)rows);
                gsl_blas_dgemv(CblasTrans, 1.0, w.P, u, 0.0, &lv.vector);
            }
        }
        gsl_vector_add(u, at);
        gsl_blas_dtrsv(CblasLower, CblasTrans, CblasNonUnit, w.L, u);
        for (int i = 0; i < n; i++) acc[i] = gsl_vector_get(u, (size_t)i);
    }
    if (at) gsl_vector_free(at);
    if (u) gsl_vector_free(u);
    if (res) gsl_vector_free(res);
    wsys_free(&w);
    return st;
}

double cmp_sigma_ratio(int n, int rows, const double *M, const double *A)
{
    wsys w = {0, 0, NULL, NULL, NULL};
    double ratio = NAN;
    if (rows > 0 && wsys_init(&w, n, rows, M, A) == 0) {
        /* Singular values of C (or Cᵀ when wide): GSL wants rows >= cols. */
        const int tall = rows >= n;
        const size_t r = (size_t)(tall ? rows : n), c = (size_t)(tall ? n : rows);
        gsl_matrix *U = gsl_matrix_alloc(r, c), *V = gsl_matrix_alloc(c, c);
        gsl_vector *S = gsl_vector_alloc(c), *work = gsl_vector_alloc(c);
        if (U && V && S && work) {
            if (tall) gsl_matrix_memcpy(U, w.C);
            else gsl_matrix_transpose_memcpy(U, w.C);
            if (gsl_linalg_SV_decomp(U, V, S, work) == 0 && gsl_vector_get(S, 0) > 0)
                ratio = gsl_vector_get(S, c - 1) / gsl_vector_get(S, 0);
        }
        if (U) gsl_matrix_free(U);
        if (V) gsl_matrix_free(V);
        if (S) gsl_vector_free(S);
        if (work) gsl_vector_free(work);
    }
    wsys_free(&w);
    return ratio;
}
