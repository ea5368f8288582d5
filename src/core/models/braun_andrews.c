/*
 * Andrews' squeezing mechanism, exactly as the "andrews" problem of the
 * Test Set for IVP Solvers (F. Mazzia, C. Magherini, Univ. of Bari;
 * andrews.f, index-3 form; Hairer & Wanner, Solving ODEs II, Sec. VII.7):
 * seven rigid bodies with frictionless joints, driven by the torque mom,
 * one stiff spring c0 = 4530 N/m. Coordinates are the test set's angles
 *   q = [β, Θ, γ, Φ, δ, Ω, ε]
 * with its M(q) (depends on Θ, Φ, Ω), f(q, v), g(q) (6 rows) and
 * G = ∂g/∂q; the test set writes M q'' = f - Gᵀλ, 0 = g.
 *
 * What we add for the corrected equation (all derived from the same data):
 *   b_qv = -(∂(G v)/∂q) v: every row of g is a sum of a·cos φ and a·sin φ
 *          with φ a sum of angles, whose velocity products are
 *          -a·cos φ φ'² and -a·sin φ φ'²;
 *   E    = ½ vᵀM(q)v + ½ c0 (L - l0)²  and  Ė = mom·β'.
 * f is Lagrangian: its velocity terms are -(M'v - ½ ∂(vᵀMv)/∂q) and its
 * spring term -∂V/∂γ (checked in tests/test_scene_andrews.c), so E is the
 * mechanism's energy balance. The test set's reference solution is an
 * oracle of the host tier (src/host/reference/braun_andrews_ref.c).
 */
#include "braun_models_internal.h"

/* Test set parameters (andrews.f, andpar), written with a leading 0. */
static const braun_real m1 = BRAUN_R(0.04325), m2 = BRAUN_R(0.00365), m3 = BRAUN_R(0.02373),
                        m4 = BRAUN_R(0.00706), m5 = BRAUN_R(0.07050), m6 = BRAUN_R(0.00706),
                        m7 = BRAUN_R(0.05498);
static const braun_real xa = BRAUN_R(-0.06934), ya = BRAUN_R(-0.00227), xb = BRAUN_R(-0.03635),
                        yb = BRAUN_R(0.03273), xc = BRAUN_R(0.014), yc = BRAUN_R(0.072),
                        c0 = BRAUN_R(4530.0);
static const braun_real i1 = BRAUN_R(2.194e-6), i2 = BRAUN_R(4.410e-7), i3 = BRAUN_R(5.255e-6),
                        i4 = BRAUN_R(5.667e-7), i5 = BRAUN_R(1.169e-5), i6 = BRAUN_R(5.667e-7),
                        i7 = BRAUN_R(1.912e-5);
static const braun_real d = BRAUN_R(28.0e-3), da = BRAUN_R(115.0e-4), e = BRAUN_R(2.0e-2),
                        ea = BRAUN_R(1421.0e-5), rr = BRAUN_R(7.0e-3), ra = BRAUN_R(92.0e-5),
                        l0 = BRAUN_R(7785.0e-5);
static const braun_real ss = BRAUN_R(35.0e-3), sa = BRAUN_R(1874.0e-5), sb = BRAUN_R(1043.0e-5),
                        sc = BRAUN_R(18.0e-3), sd = BRAUN_R(2.0e-2), ta = BRAUN_R(2308.0e-5),
                        tb = BRAUN_R(916.0e-5);
static const braun_real u = BRAUN_R(4.0e-2), ua = BRAUN_R(1228.0e-5), ub = BRAUN_R(449.0e-5),
                        zf = BRAUN_R(2.0e-2), zt = BRAUN_R(4.0e-2), fa = BRAUN_R(1421.0e-5),
                        mom = BRAUN_R(33.0e-3);

static int mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_real coth = braun_cos(q[1]), siph = braun_sin(q[3]), siom = braun_sin(q[5]);
    (void)t;
    (void)user;
    for (int i = 0; i < 49; i++) M[i] = 0;
    M[0 * 7 + 0] = m1 * ra * ra + m2 * (rr * rr - 2 * da * rr * coth + da * da) + i1 + i2;
    M[1 * 7 + 0] = M[0 * 7 + 1] = m2 * (da * da - da * rr * coth) + i2;
    M[1 * 7 + 1] = m2 * da * da + i2;
    M[2 * 7 + 2] = m3 * (sa * sa + sb * sb) + i3;
    M[3 * 7 + 3] = m4 * (e - ea) * (e - ea) + i4;
    M[4 * 7 + 3] = M[3 * 7 + 4] = m4 * ((e - ea) * (e - ea) + zt * (e - ea) * siph) + i4;
    M[4 * 7 + 4] = m4 * (zt * zt + 2 * zt * (e - ea) * siph + (e - ea) * (e - ea)) +
                   m5 * (ta * ta + tb * tb) + i4 + i5;
    M[5 * 7 + 5] = m6 * (zf - fa) * (zf - fa) + i6;
    M[6 * 7 + 5] = M[5 * 7 + 6] = m6 * ((zf - fa) * (zf - fa) - u * (zf - fa) * siom) + i6;
    M[6 * 7 + 6] = m6 * ((zf - fa) * (zf - fa) - 2 * u * (zf - fa) * siom + u * u) +
                   m7 * (ua * ua + ub * ub) + i6 + i7;
    return 0;
}

/* The spring from D (on body 3, angle γ) to the fixed point C:
 * generalized force on γ, and its potential ½ c0 (L - l0)². */
static braun_real spring(const braun_real *q, braun_real *f3)
{
    braun_real siga, coga;
    braun_sincos(q[2], &siga, &coga);
    const braun_real xd = sd * coga + sc * siga + xb, yd = sd * siga - sc * coga + yb;
    const braun_real lang = braun_sqrt((xd - xc) * (xd - xc) + (yd - yc) * (yd - yc));
    const braun_real force = -c0 * (lang - l0) / lang;
    const braun_real fx = force * (xd - xc), fy = force * (yd - yc);
    if (f3) *f3 = fx * (sc * coga - sd * siga) + fy * (sd * coga + sc * siga);
    return BRAUN_R(0.5) * c0 * (lang - l0) * (lang - l0);
}

static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *f,
                  void *user)
{
    const braun_real sith = braun_sin(q[1]), coph = braun_cos(q[3]), coom = braun_cos(q[5]);
    const braun_real bep = v[0], thp = v[1], php = v[3], dep = v[4], omp = v[5], epp = v[6];
    (void)t;
    (void)user;
    f[0] = mom - m2 * da * rr * thp * (thp + 2 * bep) * sith;
    f[1] = m2 * da * rr * bep * bep * sith;
    spring(q, &f[2]);
    f[3] = m4 * zt * (e - ea) * dep * dep * coph;
    f[4] = -m4 * zt * (e - ea) * php * (php + 2 * dep) * coph;
    f[5] = -m6 * u * (zf - fa) * epp * epp * coom;
    f[6] = m6 * u * (zf - fa) * omp * (omp + 2 * epp) * coom;
    return 0;
}

static int holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *g,
                     braun_real *G, braun_real *b, braun_real *bv, void *user)
{
    braun_real sibe, cobe, siga, coga, side, code, siep, coep;
    braun_real sibeth, cobeth, siphde, cophde, siomep, coomep;
    braun_sincos(q[0], &sibe, &cobe);
    braun_sincos(q[2], &siga, &coga);
    braun_sincos(q[4], &side, &code);
    braun_sincos(q[6], &siep, &coep);
    braun_sincos(q[0] + q[1], &sibeth, &cobeth);
    braun_sincos(q[3] + q[4], &siphde, &cophde);
    braun_sincos(q[5] + q[6], &siomep, &coomep);
    (void)t;
    (void)user;
    if (g) {
        g[0] = rr * cobe - d * cobeth - ss * siga - xb;
        g[1] = rr * sibe - d * sibeth + ss * coga - yb;
        g[2] = rr * cobe - d * cobeth - e * siphde - zt * code - xa;
        g[3] = rr * sibe - d * sibeth + e * cophde - zt * side - ya;
        g[4] = rr * cobe - d * cobeth - zf * coomep - u * siep - xa;
        g[5] = rr * sibe - d * sibeth - zf * siomep + u * coep - ya;
    }
    if (G) {
        for (int i = 0; i < 42; i++) G[i] = 0;
        G[0 * 7 + 0] = -rr * sibe + d * sibeth;
        G[0 * 7 + 1] = d * sibeth;
        G[0 * 7 + 2] = -ss * coga;
        G[1 * 7 + 0] = rr * cobe - d * cobeth;
        G[1 * 7 + 1] = -d * cobeth;
        G[1 * 7 + 2] = -ss * siga;
        G[2 * 7 + 0] = -rr * sibe + d * sibeth;
        G[2 * 7 + 1] = d * sibeth;
        G[2 * 7 + 3] = -e * cophde;
        G[2 * 7 + 4] = -e * cophde + zt * side;
        G[3 * 7 + 0] = rr * cobe - d * cobeth;
        G[3 * 7 + 1] = -d * cobeth;
        G[3 * 7 + 3] = -e * siphde;
        G[3 * 7 + 4] = -e * siphde - zt * code;
        G[4 * 7 + 0] = -rr * sibe + d * sibeth;
        G[4 * 7 + 1] = d * sibeth;
        G[4 * 7 + 5] = zf * siomep;
        G[4 * 7 + 6] = zf * siomep - u * coep;
        G[5 * 7 + 0] = rr * cobe - d * cobeth;
        G[5 * 7 + 1] = -d * cobeth;
        G[5 * 7 + 5] = -zf * coomep;
        G[5 * 7 + 6] = -zf * coomep - u * siep;
    }
    if (b)
        for (int i = 0; i < 6; i++) b[i] = 0;
    if (bv) {
        /* Squared rates of the angles that appear in g. */
        const braun_real w1 = v[0] * v[0], w3 = v[2] * v[2], w5 = v[4] * v[4],
                         w7 = v[6] * v[6];
        const braun_real w12 = (v[0] + v[1]) * (v[0] + v[1]);
        const braun_real w45 = (v[3] + v[4]) * (v[3] + v[4]);
        const braun_real w67 = (v[5] + v[6]) * (v[5] + v[6]);
        /* The crank part shared by every row: rr cos β - d cos(β+Θ) and
         * rr sin β - d sin(β+Θ). */
        const braun_real cx = rr * cobe * w1 - d * cobeth * w12;
        const braun_real cy = rr * sibe * w1 - d * sibeth * w12;
        bv[0] = cx - ss * siga * w3;
        bv[1] = cy + ss * coga * w3;
        bv[2] = cx - e * siphde * w45 - zt * code * w5;
        bv[3] = cy + e * cophde * w45 - zt * side * w5;
        bv[4] = cx - zf * coomep * w67 - u * siep * w7;
        bv[5] = cy - zf * siomep * w67 + u * coep * w7;
    }
    return 0;
}

static int energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                  braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    braun_real M[49], Mv[7], f3;
    mass(t, q, M, user);
    for (int i = 0; i < 7; i++) {
        Mv[i] = 0;
        for (int k = 0; k < 7; k++) Mv[i] += M[i * 7 + k] * v[k];
    }
    const braun_real V = spring(q, &f3);
    if (E) {
        braun_real T = 0;
        for (int i = 0; i < 7; i++) T += v[i] * Mv[i];
        *E = BRAUN_R(0.5) * T + V;
    }
    if (dE_dq) {
        /* ½ vᵀ(∂M/∂q_j)v for the three angles M depends on, and ∂V/∂γ. */
        const braun_real k2 = m2 * da * rr * braun_sin(q[1]);
        const braun_real k4 = m4 * zt * (e - ea) * braun_cos(q[3]);
        const braun_real k6 = -m6 * u * (zf - fa) * braun_cos(q[5]);
        for (int i = 0; i < 7; i++) dE_dq[i] = 0;
        dE_dq[1] = k2 * (v[0] * v[0] + v[0] * v[1]);
        dE_dq[2] = -f3;
        dE_dq[3] = k4 * (v[3] * v[4] + v[4] * v[4]);
        dE_dq[5] = k6 * (v[5] * v[6] + v[6] * v[6]);
    }
    if (dE_dv)
        for (int i = 0; i < 7; i++) dE_dv[i] = Mv[i];
    if (dE_dt) *dE_dt = 0;
    return 0;
}

/* The driving torque works on β. */
static int power(braun_real t, const braun_real *q, const braun_real *v, braun_real *Edot,
                 void *user)
{
    (void)t;
    (void)q;
    (void)user;
    *Edot = mom * v[0];
    return 0;
}

const braun_system braun_andrews_system = {7, 6, 0, BRAUN_ENERGY_INPUT | BRAUN_SCLERONOMIC, mass,
                                           forces, holonomic, NULL, energy,             power,
                                           NULL,   NULL, NULL};

/* andrews.f, init: a consistent state at rest. */
const braun_real braun_andrews_q0[7] = {
    BRAUN_R(-0.0617138900142764496358948458001), BRAUN_R(0.0),
    BRAUN_R(0.455279819163070380255912382449),   BRAUN_R(0.222668390165885884674473185609),
    BRAUN_R(0.487364979543842550225598953530),   BRAUN_R(-0.222668390165885884674473185609),
    BRAUN_R(1.23054744454982119249735015568)};
const braun_real braun_andrews_v0[7] = {0};
