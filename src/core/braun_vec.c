/* Small dense vector helpers. */
#include "braun_linalg.h"

braun_real braun_nrm2(int n, const braun_real *x)
{
    /* Scaled to avoid overflow/underflow of the squares (as BLAS dnrm2). */
    braun_real scale = 0, ssq = 1;
    for (int i = 0; i < n; i++) {
        braun_real a = braun_fabs(x[i]);
        if (a == 0) continue;
        if (scale < a) {
            ssq = 1 + ssq * (scale / a) * (scale / a);
            scale = a;
        } else {
            ssq += (a / scale) * (a / scale);
        }
    }
    return scale * braun_sqrt(ssq);
}

void braun_gemv(int rows, int n, const braun_real *A, const braun_real *x,
                braun_real *y)
{
    for (int i = 0; i < rows; i++) y[i] = braun_dot(n, A + i * n, x);
}

