/* A03, Andrews' squeezing mechanism, in the coordinates of the Test Set
 * for IVP Solvers (Mazzia, Magherini, Iavernaro; problem "andrews",
 * after Hairer & Wanner, Solving ODEs II, Sec. VII.7, and Schiehlen 1990):
 * seven relative angles q = [β, Θ, γ, Φ, δ, Ω, ε], six loop-closure rows,
 * no gravity, a torque mom on the crank and a spring c0 from D to C.
 *
 * T is written from the geometry (the centres of mass as functions of the
 * angles), not copied from the test set's M(q): tests/iftomm checks that
 * the two agree, so the test set's printed mass matrix and this geometry
 * confirm each other. The velocity-product terms come from T by complex
 * steps (ifm_lagrange.c), not from the test set's f.
 *
 * Points (origin O): F = rr (cos β, sin β) on the crank; E = F - d e(β+Θ)
 * with e(φ) = (cos φ, sin φ); E = B + ss (sin γ, -cos γ) on the triangle;
 * G = A + zt e(δ), E = G + e (sin(Φ+δ), -cos(Φ+δ)); H = A + u (sin ε,
 * -cos ε), E = H + zf e(Ω+ε). Point B is x = -0.03635: with +0.03635 the
 * test set's initial angles miss the first row by 0.073 m (docs/iftomm.md). */
#include <math.h>

#include "ifm.h"

/* The test set's parameters (andrews.f). */
static const double m1 = 0.04325, m2 = 0.00365, m3 = 0.02373, m4 = 0.00706, m5 = 0.07050,
                    m6 = 0.00706, m7 = 0.05498;
static const double xa = -0.06934, ya = -0.00227, xb = -0.03635, yb = 0.03273, xc = 0.014,
                    yc = 0.072, c0 = 4530.0;
static const double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                    i6 = 5.667e-7, i7 = 1.912e-5;
static const double d = 28.0e-3, da = 115.0e-4, e = 2.0e-2, ea = 1421.0e-5, rr = 7.0e-3,
                    ra = 92.0e-5, l0 = 7785.0e-5;
static const double ss = 35.0e-3, sa = 1874.0e-5, sb = 1043.0e-5, sc = 18.0e-3, sd = 2.0e-2,
                    ta = 2308.0e-5, tb = 916.0e-5;
static const double u = 4.0e-2, ua = 1228.0e-5, ub = 449.0e-5, zf = 2.0e-2, zt = 4.0e-2,
                    fa = 1421.0e-5, mom = 33.0e-3;

enum { BE, TH, GA, PH, DE, OM, EP };

/* ½ m |(x, y)|² */
static ifm_cx half_m_sq(double m, ifm_cx x, ifm_cx y)
{
    return 0.5 * m * (x * x + y * y);
}

static ifm_cx kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    (void)md;
    const ifm_cx b = q[BE], bt = q[BE] + q[TH], pd = q[PH] + q[DE], oe = q[OM] + q[EP];
    const ifm_cx wb = v[BE], wbt = v[BE] + v[TH], wpd = v[PH] + v[DE], woe = v[OM] + v[EP];
    /* 1: crank about O, centre ra e(β). */
    ifm_cx T = half_m_sq(m1, -ra * csin(b) * wb, ra * ccos(b) * wb) + 0.5 * i1 * wb * wb;
    /* 2: rod F-E, centre F - da e(β+Θ). */
    T += half_m_sq(m2, -rr * csin(b) * wb + da * csin(bt) * wbt,
                   rr * ccos(b) * wb - da * ccos(bt) * wbt) +
         0.5 * i2 * wbt * wbt;
    /* 3: triangle about B (its centre at sqrt(sa² + sb²) from B). */
    T += 0.5 * (m3 * (sa * sa + sb * sb) + i3) * v[GA] * v[GA];
    /* 4: link G-E, centre G + (e - ea)(sin(Φ+δ), -cos(Φ+δ)). */
    T += half_m_sq(m4, -zt * csin(q[DE]) * v[DE] + (e - ea) * ccos(pd) * wpd,
                   zt * ccos(q[DE]) * v[DE] + (e - ea) * csin(pd) * wpd) +
         0.5 * i4 * wpd * wpd;
    /* 5: link A-G about A. */
    T += 0.5 * (m5 * (ta * ta + tb * tb) + i5) * v[DE] * v[DE];
    /* 6: link H-E, centre H + (zf - fa) e(Ω+ε). */
    T += half_m_sq(m6, u * ccos(q[EP]) * v[EP] - (zf - fa) * csin(oe) * woe,
                   u * csin(q[EP]) * v[EP] + (zf - fa) * ccos(oe) * woe) +
         0.5 * i6 * woe * woe;
    /* 7: link A-H about A. */
    T += 0.5 * (m7 * (ua * ua + ub * ub) + i7) * v[EP] * v[EP];
    return T;
}

/* The spring from D on the triangle, B + (sd cos γ + sc sin γ, sd sin γ - sc cos γ),
 * to the ground point C. */
static ifm_cx potential(const ifm_model *md, const ifm_cx *q)
{
    (void)md;
    const ifm_cx xd = sd * ccos(q[GA]) + sc * csin(q[GA]) + xb;
    const ifm_cx yd = sd * csin(q[GA]) - sc * ccos(q[GA]) + yb;
    const ifm_cx L = csqrt((xd - xc) * (xd - xc) + (yd - yc) * (yd - yc));
    return 0.5 * c0 * (L - l0) * (L - l0);
}

/* E reached through the crank and rod, minus E reached through each of the
 * three other paths (the test set's g). */
static void phi(const ifm_model *md, const ifm_cx *q, ifm_cx *g)
{
    (void)md;
    const ifm_cx ex = rr * ccos(q[BE]) - d * ccos(q[BE] + q[TH]);
    const ifm_cx ey = rr * csin(q[BE]) - d * csin(q[BE] + q[TH]);
    const ifm_cx pd = q[PH] + q[DE], oe = q[OM] + q[EP];
    g[0] = ex - ss * csin(q[GA]) - xb;
    g[1] = ey + ss * ccos(q[GA]) - yb;
    g[2] = ex - e * csin(pd) - zt * ccos(q[DE]) - xa;
    g[3] = ey + e * ccos(pd) - zt * csin(q[DE]) - ya;
    g[4] = ex - zf * ccos(oe) - u * csin(q[EP]) - xa;
    g[5] = ey - zf * csin(oe) + u * ccos(q[EP]) - ya;
}

static void psi(const ifm_model *md, const ifm_cx *q, const ifm_cx *v, ifm_cx *g)
{
    (void)md;
    const ifm_cx bt = q[BE] + q[TH], wbt = v[BE] + v[TH];
    const ifm_cx pd = q[PH] + q[DE], wpd = v[PH] + v[DE], oe = q[OM] + q[EP],
                 woe = v[OM] + v[EP];
    const ifm_cx ex = -rr * csin(q[BE]) * v[BE] + d * csin(bt) * wbt;
    const ifm_cx ey = rr * ccos(q[BE]) * v[BE] - d * ccos(bt) * wbt;
    g[0] = ex - ss * ccos(q[GA]) * v[GA];
    g[1] = ey - ss * csin(q[GA]) * v[GA];
    g[2] = ex - e * ccos(pd) * wpd + zt * csin(q[DE]) * v[DE];
    g[3] = ey - e * csin(pd) * wpd - zt * ccos(q[DE]) * v[DE];
    g[4] = ex + zf * csin(oe) * woe - u * ccos(q[EP]) * v[EP];
    g[5] = ey - zf * ccos(oe) * woe - u * csin(q[EP]) * v[EP];
}

static void nonconservative(const ifm_model *md, double t, const double *q, const double *v,
                            double *Q)
{
    (void)md;
    (void)t;
    (void)q;
    (void)v;
    for (int i = 0; i < 7; i++) Q[i] = 0;
    Q[BE] = mom;
}

/* Point F, the crank's end. */
static void report(const ifm_model *md, const double *q, const double *v, double *out)
{
    (void)md;
    (void)v;
    out[0] = rr * cos(q[BE]);
    out[1] = rr * sin(q[BE]);
}

const ifm_model ifm_andrews_model = {
    .name = "A03 Andrews (test set angles)", .n = 7, .m = 6, .kinetic = kinetic,
    .potential = potential, .phi = phi, .psi = psi, .nonconservative = nonconservative,
    .nreport = 2, .report = report};

void ifm_andrews_state0(double *q0, double *v0)
{
    static const double y0[7] = {-0.0617138900142764496358948458001, 0.0,
                                 0.455279819163070380255912382449,
                                 0.222668390165885884674473185609,
                                 0.487364979543842550225598953530,
                                 -0.222668390165885884674473185609,
                                 1.23054744454982119249735015568};
    for (int i = 0; i < 7; i++) {
        q0[i] = y0[i];
        v0[i] = 0;
    }
}

/* The test set's reference solution y(1..7) at t = 0.03 (andrews.f, solut). */
const double ifm_andrews_ref003[7] = {0.1581077119629904e+2, -0.1575637105984298e+2,
                                      0.4082224013073101e-1, -0.5347301163226948e+0,
                                      0.5244099658805304e+0, 0.5347301163226948e+0,
                                      0.1048080741042263e+1};
