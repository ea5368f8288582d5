/* Small dense kernels of the harness (cmp_dense.h). The minimum-norm solve
 * works on Cᵀ, whose column-major storage is C's row-major one: column j of
 * Cᵀ is row j of C, and column pivoting picks the most independent rows. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_dense.h"

int cmp_chol(int n, const double *M, double *L)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            if (j > i) {
                L[i * n + j] = 0;
                continue;
            }
            double s = M[i * n + j];
            for (int k = 0; k < j; k++) s -= L[i * n + k] * L[j * n + k];
            if (i == j) {
                if (!(s > 0) || fabs(M[i * n + j] - M[j * n + i]) > 1e-12 * fabs(M[i * n + i]))
                    return -1;
                L[i * n + i] = sqrt(s);
            } else {
                L[i * n + j] = s / L[j * n + j];
            }
        }
    return 0;
}

void cmp_trsv_lower(int n, const double *L, double *x)
{
    for (int i = 0; i < n; i++) {
        double s = x[i];
        for (int k = 0; k < i; k++) s -= L[i * n + k] * x[k];
        x[i] = s / L[i * n + i];
    }
}

void cmp_trsv_lower_t(int n, const double *L, double *x)
{
    for (int i = n - 1; i >= 0; i--) {
        double s = x[i];
        for (int k = i + 1; k < n; k++) s -= L[k * n + i] * x[k];
        x[i] = s / L[i * n + i];
    }
}

int cmp_mnsolve_init(cmp_mnsolve *s, int n, int rows)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->rows = rows;
    const size_t r = rows > 0 ? (size_t)rows : 1;
    s->qr = malloc(((size_t)n * r + r + (size_t)n + r) * sizeof(double));
    s->perm = malloc(r * sizeof(int));
    if (!s->qr || !s->perm) {
        cmp_mnsolve_free(s);
        return -1;
    }
    s->tau = s->qr + (size_t)n * r;
    s->work = s->tau + r;
    return 0;
}

void cmp_mnsolve_free(cmp_mnsolve *s)
{
    free(s->qr);
    free(s->perm);
    s->qr = s->tau = s->work = NULL;
    s->perm = NULL;
}

int cmp_mnsolve_factor(cmp_mnsolve *s, int rows, const double *C, double rtol)
{
    const int n = s->n;
    double *a = s->qr, *norm = s->work;
    s->rows = rows;
    memcpy(a, C, (size_t)rows * (size_t)n * sizeof(double));
    for (int j = 0; j < rows; j++) {
        s->perm[j] = j;
        double q = 0;
        for (int i = 0; i < n; i++) q += a[j * n + i] * a[j * n + i];
        norm[j] = q;
    }
    if (rtol <= 0) rtol = 10.0 * (double)(n > rows ? n : rows) * DBL_EPSILON;
    const int kmax = n < rows ? n : rows;
    double r00 = 0;
    int rank = 0;
    for (int k = 0; k < kmax; k++) {
        /* The remaining column of largest norm. */
        int p = k;
        for (int j = k + 1; j < rows; j++)
            if (norm[j] > norm[p]) p = j;
        if (p != k) {
            for (int i = 0; i < n; i++) {
                const double t = a[k * n + i];
                a[k * n + i] = a[p * n + i];
                a[p * n + i] = t;
            }
            const int ti = s->perm[k];
            s->perm[k] = s->perm[p];
            s->perm[p] = ti;
            const double tn = norm[k];
            norm[k] = norm[p];
            norm[p] = tn;
        }
        double *x = a + k * n;
        double ss = 0;
        for (int i = k; i < n; i++) ss += x[i] * x[i];
        const double sn = sqrt(ss);
        if (k == 0) r00 = sn;
        if (!(sn > rtol * r00) || sn == 0) break;
        /* Householder reflector H = I - τ v vᵀ with v_k = 1, H x = β e_k. */
        const double alpha = x[k], beta = alpha >= 0 ? -sn : sn;
        const double scale = 1.0 / (alpha - beta);
        for (int i = k + 1; i < n; i++) x[i] *= scale;
        s->tau[k] = (beta - alpha) / beta;
        x[k] = beta;
        for (int j = k + 1; j < rows; j++) {
            double *y = a + j * n;
            double w = y[k];
            for (int i = k + 1; i < n; i++) w += x[i] * y[i];
            w *= s->tau[k];
            y[k] -= w;
            double q = 0;
            for (int i = k + 1; i < n; i++) {
                y[i] -= w * x[i];
                q += y[i] * y[i];
            }
            norm[j] = q;
        }
        rank++;
    }
    s->rank = rank;
    return rank;
}

void cmp_mnsolve_apply(const cmp_mnsolve *s, const double *r, double *x)
{
    const int n = s->n, k = s->rank;
    const double *a = s->qr;
    /* Rᵀ z = (Pᵀ r)[0:k], R(i, j) = a[j·n + i] for i <= j. */
    for (int i = 0; i < n; i++) x[i] = 0;
    for (int i = 0; i < k; i++) {
        double t = r[s->perm[i]];
        for (int j = 0; j < i; j++) t -= a[i * n + j] * x[j];
        x[i] = t / a[i * n + i];
    }
    /* x = H_0 ... H_{k-1} [z; 0]. */
    for (int j = k - 1; j >= 0; j--) {
        const double *v = a + j * n;
        double w = x[j];
        for (int i = j + 1; i < n; i++) w += v[i] * x[i];
        w *= s->tau[j];
        x[j] -= w;
        for (int i = j + 1; i < n; i++) x[i] -= w * v[i];
    }
}
