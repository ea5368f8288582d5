/* A04, Bricard's mechanism: five rods of 1 m and 1 kg and six revolute
 * joints in a closed loop with the ground; Grübler's count gives 0
 * degrees of freedom, the mobility is 1 (docs/iftomm.md).
 *
 * Initial configuration (at rest, gravity 9.81 m/s² along -y): joints
 * A = (0,0,0) axis y, B = (1,0,0) axis z, C = (1,-1,0) axis x,
 * D = (1,-1,1) axis y, E = (0,-1,1) axis z, F = (0,0,1) axis x; rod k
 * runs from joint k to joint k + 1 and ground closes F-A. Each joint axis
 * is perpendicular to both rods it joins. P3 = C is reported.
 *
 * Coordinates: the five joint angles θ1..θ5 at A..E of the open chain
 * ground-A-B-C-D-E (rotation of rod k relative to rod k-1 about the
 * joint's axis, 0 initially). The loop closes at F: the chain's end is F
 * (3 rows) and rod 5's axis at F stays along x (2 rows: its y and z
 * components). The five rows have rank 4; the model keeps four of them
 * (all but ifm_bricard_params.drop), checked independent along the whole
 * motion in tests/iftomm (σ_min of their Jacobian) and the dropped one
 * checked satisfied along it. */
#include <math.h>
#include <string.h>

#include "ifm.h"

#define BR_G 9.81

typedef struct { ifm_cx x[3]; } v3;
typedef struct { ifm_cx a[3][3]; } m3;

static v3 mk(double x, double y, double z)
{
    v3 r = {{x, y, z}};
    return r;
}

static v3 add(v3 a, v3 b)
{
    for (int i = 0; i < 3; i++) a.x[i] += b.x[i];
    return a;
}

static v3 scale(v3 a, ifm_cx s)
{
    for (int i = 0; i < 3; i++) a.x[i] *= s;
    return a;
}

static v3 cross(v3 a, v3 b)
{
    v3 r = {{a.x[1] * b.x[2] - a.x[2] * b.x[1], a.x[2] * b.x[0] - a.x[0] * b.x[2],
             a.x[0] * b.x[1] - a.x[1] * b.x[0]}};
    return r;
}

static ifm_cx dot(v3 a, v3 b)
{
    return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}

static v3 mul(const m3 *R, v3 a)
{
    v3 r;
    for (int i = 0; i < 3; i++) r.x[i] = R->a[i][0] * a.x[0] + R->a[i][1] * a.x[1] + R->a[i][2] * a.x[2];
    return r;
}

static v3 mul_t(const m3 *R, v3 a)
{
    v3 r;
    for (int i = 0; i < 3; i++) r.x[i] = R->a[0][i] * a.x[0] + R->a[1][i] * a.x[1] + R->a[2][i] * a.x[2];
    return r;
}

static m3 matmul(const m3 *A, const m3 *B)
{
    m3 C;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C.a[i][j] = A->a[i][0] * B->a[0][j] + A->a[i][1] * B->a[1][j] + A->a[i][2] * B->a[2][j];
    return C;
}

/* Rotation by θ about the unit axis k (Rodrigues). */
static m3 rot(v3 k, ifm_cx th)
{
    const ifm_cx c = ccos(th), s = csin(th), t = 1 - c;
    m3 R;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) R.a[i][j] = t * k.x[i] * k.x[j] + (i == j ? c : 0);
    R.a[0][1] -= s * k.x[2];
    R.a[0][2] += s * k.x[1];
    R.a[1][0] += s * k.x[2];
    R.a[1][2] -= s * k.x[0];
    R.a[2][0] -= s * k.x[1];
    R.a[2][1] += s * k.x[0];
    return R;
}

/* Rod k (0-based): its joint axis at its proximal joint, its vector to the
 * distal joint and its axis of symmetry index, all in the initial (world)
 * frame = the rod's own frame. */
static const double axis[6][3] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
static const double span[5][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 1, 0}};
static const int along[5] = {0, 1, 2, 0, 1};

typedef struct chain {
    m3 R[5];       /* rod frames */
    v3 p[6];       /* joints A..F (F: the chain's end) */
    v3 w[5];       /* angular velocities (world) */
    v3 vp[6];      /* joint velocities */
} chain;

static void kinematics(const ifm_cx *q, const ifm_cx *v, chain *c)
{
    m3 prev = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    v3 wprev = mk(0, 0, 0);
    c->p[0] = mk(0, 0, 0);
    c->vp[0] = mk(0, 0, 0);
    for (int k = 0; k < 5; k++) {
        const v3 a = mk(axis[k][0], axis[k][1], axis[k][2]);
        const m3 Rk = rot(a, q[k]);
        c->R[k] = matmul(&prev, &Rk);
        c->w[k] = v ? add(wprev, scale(mul(&prev, a), v[k])) : mk(0, 0, 0);
        const v3 r = mul(&c->R[k], mk(span[k][0], span[k][1], span[k][2]));
        c->p[k + 1] = add(c->p[k], r);
        c->vp[k + 1] = add(c->vp[k], cross(c->w[k], r));
        prev = c->R[k];
        wprev = c->w[k];
    }
}

static void inertia(const ifm_model *md, double *I_axial, double *I_trans)
{
    const ifm_bricard_params *p = md->params;
    const double a = p->thin ? 0.0 : 0.1; /* square cross-section side */
    *I_axial = (a * a + a * a) / 12;
    *I_trans = (1 + a * a) / 12;
}

static ifm_cx kinetic(const ifm_model *md, const ifm_cx *q, const ifm_cx *v)
{
    chain c;
    double Ia, It;
    inertia(md, &Ia, &It);
    kinematics(q, v, &c);
    ifm_cx T = 0;
    for (int k = 0; k < 5; k++) {
        const v3 half = scale(mul(&c.R[k], mk(span[k][0], span[k][1], span[k][2])), 0.5);
        const v3 vc = add(c.vp[k], cross(c.w[k], half));
        const v3 wb = mul_t(&c.R[k], c.w[k]); /* body frame */
        ifm_cx rotT = 0;
        for (int i = 0; i < 3; i++) rotT += (i == along[k] ? Ia : It) * wb.x[i] * wb.x[i];
        T += 0.5 * dot(vc, vc) + 0.5 * rotT; /* m = 1 */
    }
    return T;
}

static ifm_cx potential(const ifm_model *md, const ifm_cx *q)
{
    chain c;
    (void)md;
    kinematics(q, NULL, &c);
    ifm_cx V = 0;
    for (int k = 0; k < 5; k++) V += BR_G * 0.5 * (c.p[k].x[1] + c.p[k + 1].x[1]);
    return V;
}

/* The five closure rows: the end minus F (0..2), rod 5's axis at F along
 * x (3: its y component, 4: its z component). The model keeps four: all
 * but params->drop. */
static int kept(const ifm_model *md, int i)
{
    const ifm_bricard_params *p = md->params;
    return i < p->drop ? i : i + 1;
}

static void all_rows(const ifm_cx *q, const ifm_cx *v, ifm_cx *phi, ifm_cx *psi)
{
    chain c;
    kinematics(q, v, &c);
    const v3 ax = mul(&c.R[4], mk(axis[5][0], axis[5][1], axis[5][2]));
    if (phi) {
        phi[0] = c.p[5].x[0];
        phi[1] = c.p[5].x[1];
        phi[2] = c.p[5].x[2] - 1;
        phi[3] = ax.x[1];
        phi[4] = ax.x[2];
    }
    if (psi) {
        const v3 dax = cross(c.w[4], ax);
        psi[0] = c.vp[5].x[0];
        psi[1] = c.vp[5].x[1];
        psi[2] = c.vp[5].x[2];
        psi[3] = dax.x[1];
        psi[4] = dax.x[2];
    }
}

static void phi(const ifm_model *md, const ifm_cx *q, ifm_cx *out)
{
    ifm_cx r[5];
    all_rows(q, NULL, r, NULL);
    for (int i = 0; i < 4; i++) out[i] = r[kept(md, i)];
}

static void psi(const ifm_model *md, const ifm_cx *q, const ifm_cx *v, ifm_cx *out)
{
    ifm_cx r[5];
    all_rows(q, v, NULL, r);
    for (int i = 0; i < 4; i++) out[i] = r[kept(md, i)];
}

/* P3 = C, the joint between rods 2 and 3. */
static void report(const ifm_model *md, const double *q, const double *v, double *out)
{
    ifm_cx qc[5];
    chain c;
    (void)md;
    (void)v;
    for (int i = 0; i < 5; i++) qc[i] = q[i];
    kinematics(qc, NULL, &c);
    for (int i = 0; i < 3; i++) out[i] = creal(c.p[2].x[i]);
}

void ifm_bricard_model(ifm_model *md, const ifm_bricard_params *p)
{
    *md = (ifm_model){.name = p->thin ? "A04 Bricard, thin rods (joint angles)"
                                      : "A04 Bricard (joint angles)",
                      .n = 5, .m = 4, .kinetic = kinetic, .potential = potential, .phi = phi,
                      .psi = psi, .nreport = 3, .report = report, .params = p};
}

void ifm_bricard_state0(double *q0, double *v0)
{
    for (int i = 0; i < 5; i++) q0[i] = v0[i] = 0;
}

void ifm_bricard_rows(const double *q, double *phi5)
{
    ifm_cx qc[5], r[5];
    for (int i = 0; i < 5; i++) qc[i] = q[i];
    all_rows(qc, NULL, r, NULL);
    for (int i = 0; i < 5; i++) phi5[i] = creal(r[i]);
}
