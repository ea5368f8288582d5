/* A05, the stiff flyball governor (docs/iftomm.md). A vertical shaft
 * (1 m x 0.01 m x 0.01 m, density 3000 kg/m³) turns freely about the world
 * z axis on the ground pivot (0, 0, 0), starting at 2π rad/s; a slider
 * (0.1 m cube, 3000 kg/m³) slides on it (turning with it), its centre at
 * height s, s(0) = 0.5 m; two rods (as the shaft) hang from pins at
 * (±0.05, 0, 1) in the shaft frame, axes along the shaft frame's y, each
 * with a 5 kg point mass at its far end, α(0) = 30° below the horizontal;
 * the coupler rods of Watt's governor are spring-dampers (k = 8e5 N/m,
 * c = 4e4 N s/m, rest length 0.5 m) from the slider points (±0.05, 0, s)
 * to the rods' centres. Gravity 9.81 m/s² along -z. s is reported.
 *
 * Two models in different coordinates, compared with each other:
 *  (a) joint coordinates q = [φ, s, α1, α2], no constraints: a point at
 *      distance λ along rod i moves at |v|² = λ²α'² + (0.05 + λ cos α)² φ'²,
 *      the rod turns at ω = φ' e_z + α' e_t (ω·d = -φ' sin α);
 *  (b) Cartesian: q = [φ, s, r1, r2] with r_i the point masses, four rows
 *      |r_i - P_i(φ)|² = 1, (r_i - P_i(φ))·e_t(φ) = 0; the rod's spin about
 *      its own axis d is φ' d_z and the rest of its turning d × d'. */
#include <math.h>
#include <string.h>

#include "ifm.h"

#define FG_G 9.81
#define FG_RHO 3000.0
#define FG_PIN 0.05      /* pin and spring offsets from the shaft axis */
#define FG_K 8e5
#define FG_C 4e4
#define FG_REST 0.5
#define FG_MP 5.0

static const double m_rod = FG_RHO * 1.0 * 0.01 * 0.01;          /* 0.3 kg, also the shaft */
static const double I_long = FG_RHO * 1.0 * 0.01 * 0.01 * (0.01 * 0.01 + 0.01 * 0.01) / 12;
static const double I_trans = FG_RHO * 1.0 * 0.01 * 0.01 * (1.0 + 0.01 * 0.01) / 12;
static const double m_slider = FG_RHO * 0.1 * 0.1 * 0.1;          /* 3 kg */
static const double I_slider = FG_RHO * 0.1 * 0.1 * 0.1 * (0.1 * 0.1 + 0.1 * 0.1) / 12;
static const double sigma[2] = {1, -1}; /* the rods' sides */

/* ---------------------------------------------------------------- (a) joint */
enum { PHI, S, A1, A2 };

static ifm_cx joint_kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    (void)md;
    ifm_cx T = 0.5 * (I_long + I_slider) * v[PHI] * v[PHI] + 0.5 * m_slider * v[S] * v[S];
    for (int i = 0; i < 2; i++) {
        const ifm_cx ca = ccos(q[A1 + i]), sa = csin(q[A1 + i]), wa = v[A1 + i];
        const ifm_cx rc = FG_PIN + 0.5 * ca, re = FG_PIN + ca; /* radii: centre, end */
        T += 0.5 * m_rod * (0.25 * wa * wa + rc * rc * v[PHI] * v[PHI]);
        T += 0.5 * (I_trans * wa * wa + (I_trans * ca * ca + I_long * sa * sa) * v[PHI] * v[PHI]);
        T += 0.5 * FG_MP * (wa * wa + re * re * v[PHI] * v[PHI]);
    }
    return T;
}

/* Spring i: from the slider point to the rod's centre, in the shaft's
 * plane: (½ cos α, 1 - ½ sin α - s). */
static ifm_cx joint_spring_length(const ifm_cx *q, int i)
{
    const ifm_cx h = 1 - 0.5 * csin(q[A1 + i]) - q[S], r = 0.5 * ccos(q[A1 + i]);
    return csqrt(r * r + h * h);
}

static ifm_cx joint_potential(const ifm_model *md, const ifm_cx *q)
{
    (void)md;
    ifm_cx V = m_slider * FG_G * q[S];
    for (int i = 0; i < 2; i++) {
        const ifm_cx sa = csin(q[A1 + i]), L = joint_spring_length(q, i);
        V += FG_G * (m_rod * (1 - 0.5 * sa) + FG_MP * (1 - sa));
        V += 0.5 * FG_K * (L - FG_REST) * (L - FG_REST);
    }
    return V;
}

/* Dampers: Q = -c L' ∂L/∂q, ∂L/∂q by complex steps. */
static void damper_forces(const ifm_model *md, const double *q, const double *v, double *Q,
                          ifm_cx (*length)(const ifm_cx *q, int i))
{
    const int n = md->n;
    ifm_cx qc[IFM_MAX_N];
    for (int k = 0; k < n; k++) Q[k] = 0;
    for (int i = 0; i < 2; i++) {
        double dL[IFM_MAX_N], Ldot = 0;
        for (int k = 0; k < n; k++) {
            for (int j = 0; j < n; j++) qc[j] = q[j];
            qc[k] += I * IFM_CSTEP;
            dL[k] = cimag(length(qc, i)) / IFM_CSTEP;
            Ldot += dL[k] * v[k];
        }
        for (int k = 0; k < n; k++) Q[k] -= FG_C * Ldot * dL[k];
    }
}

static void joint_nonconservative(const ifm_model *md, double t, const double *q,
                                  const double *v, double *Q)
{
    (void)t;
    damper_forces(md, q, v, Q, joint_spring_length);
}

static void joint_report(const ifm_model *md, const double *q, const double *v, double *out)
{
    (void)md;
    (void)v;
    out[0] = 0;
    out[1] = 0;
    out[2] = q[S];
}

const ifm_model ifm_flyball_joint_model = {
    .name = "A05 flyball governor (joint coordinates)", .n = 4, .m = 0,
    .kinetic = joint_kinetic, .potential = joint_potential,
    .nonconservative = joint_nonconservative, .nreport = 3, .report = joint_report};

#define FG_ALPHA0 (30.0 * IFM_PI / 180.0)
#define FG_OMEGA0 (2 * IFM_PI)

void ifm_flyball_joint_state0(double *q0, double *v0)
{
    q0[PHI] = 0;
    q0[S] = 0.5;
    q0[A1] = q0[A2] = FG_ALPHA0;
    v0[PHI] = FG_OMEGA0;
    v0[S] = v0[A1] = v0[A2] = 0;
}

/* ---------------------------------------------------------------- (b) Cartesian */
enum { CPHI, CS, R1 = 2, R2 = 5 };

/* The pin of rod i at (q, v): P_i = σ 0.05 e_r(φ) + e_z and its velocity. */
static void pin(const ifm_cx *q, const ifm_cx *v, int i, ifm_cx *P, ifm_cx *Pd)
{
    const ifm_cx c = ccos(q[CPHI]), s = csin(q[CPHI]);
    P[0] = sigma[i] * FG_PIN * c;
    P[1] = sigma[i] * FG_PIN * s;
    P[2] = 1;
    if (Pd) {
        Pd[0] = -sigma[i] * FG_PIN * s * v[CPHI];
        Pd[1] = sigma[i] * FG_PIN * c * v[CPHI];
        Pd[2] = 0;
    }
}

static ifm_cx cart_kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    (void)md;
    ifm_cx T = 0.5 * (I_long + I_slider) * v[CPHI] * v[CPHI] + 0.5 * m_slider * v[CS] * v[CS];
    for (int i = 0; i < 2; i++) {
        const ifm_cx *r = q + (i ? R2 : R1), *rd = v + (i ? R2 : R1);
        ifm_cx P[3], Pd[3], d[3], dd[3], cd[3];
        pin(q, v, i, P, Pd);
        for (int k = 0; k < 3; k++) {
            d[k] = r[k] - P[k];
            dd[k] = rd[k] - Pd[k];
            cd[k] = 0.5 * (Pd[k] + rd[k]);
        }
        const ifm_cx w[3] = {d[1] * dd[2] - d[2] * dd[1], d[2] * dd[0] - d[0] * dd[2],
                             d[0] * dd[1] - d[1] * dd[0]};
        T += 0.5 * FG_MP * (rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2]);
        T += 0.5 * m_rod * (cd[0] * cd[0] + cd[1] * cd[1] + cd[2] * cd[2]);
        T += 0.5 * I_trans * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        T += 0.5 * I_long * v[CPHI] * v[CPHI] * d[2] * d[2];
    }
    return T;
}

/* Spring i from the slider point σ 0.05 e_r + s e_z to the rod's centre. */
static ifm_cx cart_spring_length(const ifm_cx *q, int i)
{
    const ifm_cx *r = q + (i ? R2 : R1);
    ifm_cx P[3];
    pin(q, NULL, i, P, NULL);
    const ifm_cx dx = 0.5 * (P[0] + r[0]) - P[0], dy = 0.5 * (P[1] + r[1]) - P[1];
    const ifm_cx dz = 0.5 * (P[2] + r[2]) - q[CS];
    return csqrt(dx * dx + dy * dy + dz * dz);
}

static ifm_cx cart_potential(const ifm_model *md, const ifm_cx *q)
{
    (void)md;
    ifm_cx V = m_slider * FG_G * q[CS];
    for (int i = 0; i < 2; i++) {
        const ifm_cx *r = q + (i ? R2 : R1);
        const ifm_cx L = cart_spring_length(q, i);
        V += FG_G * (FG_MP * r[2] + m_rod * 0.5 * (1 + r[2]));
        V += 0.5 * FG_K * (L - FG_REST) * (L - FG_REST);
    }
    return V;
}

static void cart_phi(const ifm_model *md, const ifm_cx *q, ifm_cx *out)
{
    (void)md;
    const ifm_cx et[3] = {-csin(q[CPHI]), ccos(q[CPHI]), 0};
    for (int i = 0; i < 2; i++) {
        const ifm_cx *r = q + (i ? R2 : R1);
        ifm_cx P[3], d[3];
        pin(q, NULL, i, P, NULL);
        for (int k = 0; k < 3; k++) d[k] = r[k] - P[k];
        out[2 * i] = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1;
        out[2 * i + 1] = d[0] * et[0] + d[1] * et[1];
    }
}

static void cart_psi(const ifm_model *md, const ifm_cx *q, const ifm_cx *v, ifm_cx *out)
{
    (void)md;
    const ifm_cx c = ccos(q[CPHI]), s = csin(q[CPHI]);
    const ifm_cx et[2] = {-s, c}, etd[2] = {-c * v[CPHI], -s * v[CPHI]};
    for (int i = 0; i < 2; i++) {
        const ifm_cx *r = q + (i ? R2 : R1), *rd = v + (i ? R2 : R1);
        ifm_cx P[3], Pd[3], d[3], dd[3];
        pin(q, v, i, P, Pd);
        for (int k = 0; k < 3; k++) {
            d[k] = r[k] - P[k];
            dd[k] = rd[k] - Pd[k];
        }
        out[2 * i] = 2 * (d[0] * dd[0] + d[1] * dd[1] + d[2] * dd[2]);
        out[2 * i + 1] = dd[0] * et[0] + dd[1] * et[1] + d[0] * etd[0] + d[1] * etd[1];
    }
}

static void cart_nonconservative(const ifm_model *md, double t, const double *q,
                                 const double *v, double *Q)
{
    (void)t;
    damper_forces(md, q, v, Q, cart_spring_length);
}

static void cart_report(const ifm_model *md, const double *q, const double *v, double *out)
{
    (void)md;
    (void)v;
    out[0] = 0;
    out[1] = 0;
    out[2] = q[CS];
}

const ifm_model ifm_flyball_cart_model = {
    .name = "A05 flyball governor (Cartesian point masses)", .n = 8, .m = 4,
    .kinetic = cart_kinetic, .potential = cart_potential, .phi = cart_phi, .psi = cart_psi,
    .nonconservative = cart_nonconservative, .nreport = 3, .report = cart_report};

void ifm_flyball_cart_state0(double *q0, double *v0)
{
    memset(q0, 0, 8 * sizeof *q0);
    memset(v0, 0, 8 * sizeof *v0);
    q0[CS] = 0.5;
    v0[CPHI] = FG_OMEGA0;
    for (int i = 0; i < 2; i++) {
        double *r = q0 + (i ? R2 : R1), *rd = v0 + (i ? R2 : R1);
        r[0] = sigma[i] * (FG_PIN + cos(FG_ALPHA0));
        r[1] = 0;
        r[2] = 1 - sin(FG_ALPHA0);
        rd[1] = FG_OMEGA0 * r[0]; /* ω e_z x r */
    }
}
