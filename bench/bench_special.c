/* The specialised floor: libbraun's ideal RK4 step of the slider-crank
 * written out by hand, with every size, every zero and one of A, and the
 * model's callbacks known to the compiler, and none of the library's
 * checks, rank decisions or glue (docs/performance.md, "The specialised
 * floor").
 *
 * Why: issue 16 asks for a corrected step of 0.5 µs with compile-time
 * sizes and a tenth of MuJoCo's step; this is what the method's own
 * arithmetic costs on this machine when nothing else is left — the same
 * Udwadia–Kalaba acceleration on the Gram path as the library's stages
 * (src/core/braun_qrcp_gram.c): C = A R⁻¹ with R = M^½ (M is diagonal),
 * G = C Cᵀ = L D Lᵀ, w = G⁻¹ (b_v − C ã), q̈ = R⁻¹ (ã + Cᵀ w), ã = R⁻ᵀ Q.
 * No correction: a lower bound of the corrected step, which adds to it.
 *
 * Not a library feature: bench_run_new checks it against the library's
 * ideal step (the same trajectory to round-off) before it is timed. Its own
 * file, so that the step stays a call under -flto as the library's does. */
#include <math.h>

#include "bench.h"

/* (q, v) of the slider-crank: n = 6, 5 rows (src/core/models/braun_slider_crank.c). */
static void special_accel(const braun_link_params *p, const double *q, const double *v,
                          double *qdd)
{
    const double m = p->m, l = p->l, hl = 0.5 * l, J = m * l * l / 12.0, mg = m * p->g;
    const double s1 = sin(q[2]), c1 = cos(q[2]), s2 = sin(q[5]), c2 = cos(q[5]);
    const double rm = 1 / sqrt(m), rj = 1 / sqrt(J); /* R⁻¹ = M^-½ */
    const double rd[6] = {rm, rm, rj, rm, rm, rj};
    const double A[5][6] = {{1, 0, hl * s1, 0, 0, 0},
                            {0, 1, -hl * c1, 0, 0, 0},
                            {1, 0, -hl * s1, -1, 0, -hl * s2},
                            {0, 1, hl * c1, 0, -1, hl * c2},
                            {0, 0, 0, 0, 1, hl * c2}};
    const double w1 = v[2] * v[2], w2 = v[5] * v[5];
    const double bv[5] = {-hl * c1 * w1, -hl * s1 * w1, hl * (c1 * w1 + c2 * w2),
                          hl * (s1 * w1 + s2 * w2), hl * s2 * w2};
    const double Q[6] = {0, -mg, 0, 0, -mg, 0};
    double at[6], C[5][6], r[5], G[5][5], L[5][5], dinv[5] = {0};
    for (int j = 0; j < 6; j++) at[j] = Q[j] * rd[j];
    for (int i = 0; i < 5; i++) {
        double s = 0;
        for (int j = 0; j < 6; j++) {
            C[i][j] = A[i][j] * rd[j];
            s += C[i][j] * at[j];
        }
        r[i] = bv[i] - s;
    }
    for (int i = 0; i < 5; i++)
        for (int j = 0; j <= i; j++) {
            double s = 0;
            for (int k = 0; k < 6; k++) s += C[i][k] * C[j][k];
            G[i][j] = s;
        }
    for (int i = 0; i < 5; i++) {
        double t[5], d = G[i][i];
        for (int j = 0; j < i; j++) {
            double s = G[i][j];
            for (int k = 0; k < j; k++) s -= t[k] * L[j][k];
            t[j] = s;
        }
        for (int j = 0; j < i; j++) {
            L[i][j] = t[j] * dinv[j];
            d -= t[j] * L[i][j];
        }
        dinv[i] = 1 / d;
    }
    for (int i = 0; i < 5; i++) {
        double s = r[i];
        for (int j = 0; j < i; j++) s -= L[i][j] * r[j];
        r[i] = s;
    }
    for (int i = 0; i < 5; i++) r[i] *= dinv[i];
    for (int i = 4; i >= 0; i--) {
        double s = r[i];
        for (int j = i + 1; j < 5; j++) s -= L[j][i] * r[j];
        r[i] = s;
    }
    for (int k = 0; k < 6; k++) {
        double s = at[k];
        for (int i = 0; i < 5; i++) s += C[i][k] * r[i];
        qdd[k] = s * rd[k];
    }
}

#if defined(__GNUC__)
__attribute__((noinline))
#endif
void bench_special_step(const braun_link_params *p, double h, double *y)
{
    /* The classic RK4 tableau, as libbraun's (src/core/braun_tableau.c). */
    double k[4][12], ys[12];
    for (int s = 0; s < 4; s++) {
        const double c = s == 0 ? 0 : s == 3 ? h : 0.5 * h;
        for (int i = 0; i < 12; i++) ys[i] = s ? y[i] + c * k[s - 1][i] : y[i];
        for (int i = 0; i < 6; i++) k[s][i] = ys[6 + i];
        special_accel(p, ys, ys + 6, k[s] + 6);
    }
    for (int i = 0; i < 12; i++)
        y[i] += h / 6.0 * k[0][i] + h / 3.0 * k[1][i] + h / 3.0 * k[2][i] + h / 6.0 * k[3][i];
}
