/*
 * The smallest application of libbraun on the target, built in three
 * variants to show what --gc-sections keeps (docs/firmware.md, "Flash and
 * RAM"): a planar pendulum in Cartesian coordinates (n = 2, m = 1,
 * p = 0, constant mass), stepped with RK4 from a static workspace.
 *   FW_GC_CORRECTIONS=0  the ideal (Udwadia–Kalaba) step, no energy law
 *   FW_GC_CORRECTIONS=3  + position and velocity corrections (Eqs. 16, 17)
 *   FW_GC_CORRECTIONS=7  + energy law and energy correction (Eq. 20)
 * Only braun_model_init, braun_data_size/init, braun_set_state and
 * braun_step are called: no drivers, no built-in models, no status strings.
 * Exit status 0 if 1000 steps of 1 ms keep the pendulum on its circle.
 */
#include <stdint.h>

#include "board.h"
#include "braun.h"
#include "semihost.h"

#ifndef FW_GC_CORRECTIONS
#define FW_GC_CORRECTIONS 7
#endif

#define L BRAUN_R(1.0)
#define G BRAUN_R(9.81)

static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    (void)t, (void)q, (void)user;
    M[0] = M[3] = BRAUN_R(1.0);
    M[1] = M[2] = BRAUN_R(0.0);
    return 0;
}

static int forces(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *Q, void *user)
{
    (void)t, (void)q, (void)v, (void)user;
    Q[0] = BRAUN_R(0.0);
    Q[1] = -G;
    return 0;
}

/* Φ = x² + y² - L², A = 2[x y], b = 0, b_qv = -2|v|². */
static int holonomic(braun_real t, const braun_real *q, const braun_real *v,
                     braun_real *phi, braun_real *A, braun_real *b,
                     braun_real *bv, void *user)
{
    (void)t, (void)user;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - L * L;
    if (A) {
        A[0] = BRAUN_R(2.0) * q[0];
        A[1] = BRAUN_R(2.0) * q[1];
    }
    if (b) b[0] = BRAUN_R(0.0);
    if (bv) bv[0] = BRAUN_R(-2.0) * (v[0] * v[0] + v[1] * v[1]);
    return 0;
}

#if FW_GC_CORRECTIONS & 4
/* E = ½|v|² + g y. */
static int energy(braun_real t, const braun_real *q, const braun_real *v,
                  braun_real *E, braun_real *dE_dq, braun_real *dE_dv,
                  braun_real *dE_dt, void *user)
{
    (void)t, (void)user;
    if (E) *E = BRAUN_R(0.5) * (v[0] * v[0] + v[1] * v[1]) + G * q[1];
    if (dE_dq) {
        dE_dq[0] = BRAUN_R(0.0);
        dE_dq[1] = G;
    }
    if (dE_dv) {
        dE_dv[0] = v[0];
        dE_dv[1] = v[1];
    }
    if (dE_dt) *dE_dt = BRAUN_R(0.0);
    return 0;
}
#define ENERGY energy
#else
#define ENERGY NULL
#endif

static union {
    unsigned char bytes[2048];
    double align;
} workspace;

int fw_board_main(void)
{
    static const braun_system sys = {2, 1, 0, BRAUN_MASS_CONSTANT, mass, forces,
                                     holonomic, NULL, ENERGY, NULL, NULL, NULL, NULL};
    static const braun_real q0[2] = {BRAUN_R(1.0), BRAUN_R(0.0)};
    static const braun_real v0[2] = {BRAUN_R(0.0), BRAUN_R(0.0)};
    braun_model model;
    braun_data d;
    int st = braun_model_init(&model, &sys);
    model.opt.corrections = FW_GC_CORRECTIONS;
    if (!st && braun_data_size(&model) > sizeof workspace.bytes) st = BRAUN_ERR_BUFFER;
    if (!st) st = braun_data_init(&d, &model, workspace.bytes, sizeof workspace.bytes);
    if (!st) st = braun_set_state(&d, BRAUN_R(0.0), q0, v0);
    for (int i = 0; i < 1000 && !st; i++) st = braun_step(&d, BRAUN_RK4, BRAUN_R(1e-3));
    if (!st) {
        const braun_real r2 = d.q[0] * d.q[0] + d.q[1] * d.q[1];
        const braun_real e = r2 > L * L ? r2 - L * L : L * L - r2;
        if (!(e < BRAUN_R(1e-4))) st = 1;
    }
    /* Stack high-water mark in bytes, printed without printf. */
    char msg[64] = "gc demo: ok, stack used ", *p = msg + 24;
    uint32_t used = fw_board_stack_size() - fw_board_stack_unused(), div = 10000;
    while (div > used && div > 1) div /= 10;
    for (; div; div /= 10) *p++ = (char)('0' + (int)(used / div % 10));
    *p++ = '\n';
    *p = 0;
    fw_semihost_write0(st ? "gc demo: failed\n" : msg);
    return st ? 1 : 0;
}
