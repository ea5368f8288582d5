/* Spatial rigid body in Euler parameters (docs/method.md, "Spatial rigid
 * bodies"): q = (r, p), r the centre of mass, p = (e0, e1, e2, e3) a unit
 * quaternion kept unit by the body's own row |p|² - 1 = 0.
 *
 * Kinematics of a body-frame point s: A(p) the quadratic rotation matrix
 * (= |p|² R(p/|p|)) and P = r + A(p) s / |p|², the rotation that p stands
 * for whatever its length (body_vector: the partials and velocity product
 * are exact off the unit sphere too).
 * Angular velocities (of that rotation, any |p|; s = |p|²): body frame
 * ω' = 2 G(p) p'/s, world ω = 2 E(p) p'/s (rigid3d_omega), with
 *   G = [-e, e0 I - ẽ],  E = [-e, e0 I + ẽ],  A = E Gᵀ,  G p = E p = 0.
 *
 * Kinetic energy: that of the motion of the body's points, which move with
 * the rotation p stands for, so it depends on p/|p| and p'/|p| only (it is
 * homogeneous of degree 0 under p → λp, p' → λp'). With s = |p|² the body
 * angular velocity is ω' = 2 G(p) p'/s; ½ ω'ᵀJω' is singular along p
 * (G p = 0), so the body's Lagrangian carries the augmentation
 * 2k (pᵀp'/s)² = 2k (d ln|p|/dt)², k = tr J/3, which vanishes on the
 * velocity manifold (pᵀp' = 0 is the derivative of the body's row) and
 * makes the block positive definite:
 *   T = ½ m |r'|² + (2 p'ᵀGᵀJG p' + 2k (pᵀp')²)/s² = ½ m |r'|² + ½ p'ᵀM0 p'/s²,
 *   M0 = 4GᵀJG + 4k ppᵀ,  M = diag(m I, M0/s²)
 *   (eigenvalues 4 J_i/s and 4k/s: 4 J_i and 4k at |p| = 1).
 * Velocity-product forces (Lagrange's equations of T, exact on R⁷:
 * Q = -Ṁp' + ½∂_p(p'ᵀMp')), with F0 = -4 G(p')ᵀJ (2Gp') - 4k |p'|² p those
 * of ½ p'ᵀM0 p' alone and ṡ = 2pᵀp':
 *   Q_p = F0/s² + 2ṡ M0 p'/s³ - 2 (p'ᵀM0 p') p/s³;
 * in the terms the code uses (ω' = 2Gp'/s, u = pᵀp'/s, T_p = ½ω'ᵀJω' + 2k u²):
 *   ∂T/∂p' = 2GᵀJω'/s + 4k u p/s,
 *   ∂T/∂p  = -2 G(p')ᵀJω'/s + 4k u p'/s - 4 T_p p/s,
 *   Q_p    = -4 G(p')ᵀJω'/s - 4k |p'|² p/s² + 4u ∂T/∂p' - 4 T_p p/s.
 * (Until 2026-12-05 T was ½ m|r'|² + ½ p'ᵀM0 p', the same on the unit sphere
 * but not the energy of the points' motion off it: between corrections,
 * |p|² - 1 ~ 1e-7, a fast top's physical energy drifted by 2 T_p (|p|² - 1)
 * while the law the energy correction holds stayed exact.) */
#include "scene_internal.h"

/* The inertia tensor J of b as a symmetric 3 x 3 (row-major). */
static void tensor(const braun_scene_body *b, braun_real *J)
{
    const braun_real *t = b->tensor;
    J[0] = t[0], J[4] = t[1], J[8] = t[2];
    J[1] = J[3] = t[3];
    J[2] = J[6] = t[4];
    J[5] = J[7] = t[5];
}

/* k of the augmentation: the mean principal moment. */
static braun_real aug(const braun_scene_body *b)
{
    return (b->tensor[0] + b->tensor[1] + b->tensor[2]) / 3;
}

/* y = A(p) s (the quadratic form). */
static void rotate(const braun_real *p, const braun_real *s, braun_real *y)
{
    const braun_real e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const braun_real x = s[0], yy = s[1], z = s[2];
    y[0] = (e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3) * x + 2 * (e1 * e2 - e0 * e3) * yy +
           2 * (e1 * e3 + e0 * e2) * z;
    y[1] = 2 * (e1 * e2 + e0 * e3) * x + (e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3) * yy +
           2 * (e2 * e3 - e0 * e1) * z;
    y[2] = 2 * (e1 * e3 - e0 * e2) * x + 2 * (e2 * e3 + e0 * e1) * yy +
           (e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3) * z;
}

/* J = ∂(A(p)s)/∂p, 3 x 4 row-major. */
static void rotate_jac(const braun_real *p, const braun_real *s, braun_real *J)
{
    const braun_real e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const braun_real x = s[0], y = s[1], z = s[2];
    const braun_real a = 2 * (e0 * x - e3 * y + e2 * z); /* recurring combinations */
    const braun_real c = 2 * (e1 * x + e2 * y + e3 * z);
    const braun_real d = 2 * (-e2 * x + e1 * y + e0 * z);
    const braun_real f = 2 * (e3 * x + e0 * y - e1 * z);
    J[0] = a, J[1] = c, J[2] = d, J[3] = -f;
    J[4] = f, J[5] = -d, J[6] = c, J[7] = a;
    J[8] = d, J[9] = f, J[10] = -a, J[11] = c;
}

/* y = G(p) x (3 entries), x 4 entries. */
static void g_times(const braun_real *p, const braun_real *x, braun_real *y)
{
    const braun_real e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    y[0] = -e1 * x[0] + e0 * x[1] + e3 * x[2] - e2 * x[3];
    y[1] = -e2 * x[0] - e3 * x[1] + e0 * x[2] + e1 * x[3];
    y[2] = -e3 * x[0] + e2 * x[1] - e1 * x[2] + e0 * x[3];
}

/* y = G(p)ᵀ x (4 entries), x 3 entries. */
static void gt_times(const braun_real *p, const braun_real *x, braun_real *y)
{
    const braun_real e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    y[0] = -e1 * x[0] - e2 * x[1] - e3 * x[2];
    y[1] = e0 * x[0] - e3 * x[1] + e2 * x[2];
    y[2] = e3 * x[0] + e0 * x[1] - e1 * x[2];
    y[3] = -e2 * x[0] + e1 * x[1] + e0 * x[2];
}

static braun_real dot4(const braun_real *a, const braun_real *c)
{
    return a[0] * c[0] + a[1] * c[1] + a[2] * c[2] + a[3] * c[3];
}

static void mat3_vec(const braun_real *J, const braun_real *x, braun_real *y)
{
    for (int i = 0; i < 3; i++) y[i] = J[3 * i] * x[0] + J[3 * i + 1] * x[1] + J[3 * i + 2] * x[2];
}

static const char *rigid3d_check(const braun_scene *s, const braun_scene_body *b)
{
    (void)s;
    if (!(b->mass > 0)) return "a rigid3d body needs a mass > 0";
    const braun_real *t = b->tensor;
    if (!(t[0] > 0) || !(t[1] > 0) || !(t[2] > 0))
        return "a rigid3d body needs principal moments of inertia > 0 (a thin rod needs its "
               "cross-section's moment about its axis)";
    /* Positive definite: leading minors (Sylvester) of the tensor. */
    const braun_real m2 = t[0] * t[1] - t[3] * t[3];
    const braun_real m3 = t[0] * (t[1] * t[2] - t[5] * t[5]) - t[3] * (t[3] * t[2] - t[5] * t[4]) +
                          t[4] * (t[3] * t[5] - t[1] * t[4]);
    if (!(m2 > 0) || !(m3 > 0)) return "the inertia tensor of a rigid3d body is not positive definite";
    /* A mass distribution's tensor J = tr(S) I − S, S = ∫ r rᵀ dm ⪰ 0: its
     * principal moments satisfy I_a + I_b >= I_c (the flat plate is the
     * equality). S = ½ tr(J) I − J must be positive semidefinite — all its
     * principal minors >= 0, taken with a shift of 64 ε tr(J) for the
     * plate's round-off. [1, 1, 3] is no body: refused, as MuJoCo does. */
    {
        const braun_real tr = t[0] + t[1] + t[2], shift = 64 * BRAUN_EPS * tr;
        const braun_real d0 = tr / 2 - t[0] + shift, d1 = tr / 2 - t[1] + shift, d2 = tr / 2 - t[2] + shift;
        const braun_real s01 = -t[3], s02 = -t[4], s12 = -t[5];
        const braun_real det = d0 * (d1 * d2 - s12 * s12) - s01 * (s01 * d2 - s12 * s02) +
                               s02 * (s01 * s12 - d1 * s02);
        if (!(d0 >= 0) || !(d1 >= 0) || !(d2 >= 0) || !(d0 * d1 - s01 * s01 >= 0) ||
            !(d0 * d2 - s02 * s02 >= 0) || !(d1 * d2 - s12 * s12 >= 0) || !(det >= 0))
            return "the inertia of a rigid3d body breaks the triangle inequality of its principal "
                   "moments (I_a + I_b >= I_c): no mass distribution has it";
    }
    const braun_real *p = b->q0 + 3;
    const braun_real nn = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    /* In float a normalised quaternion is off by a few ε (2·0.70710677f² − 1 = −6e-8). */
    if (!(braun_fabs(nn - 1) <= (BRAUN_EPS > BRAUN_R(1e-10) ? BRAUN_R(16.0) * BRAUN_EPS : BRAUN_R(2e-9))))
        return "the orientation of a rigid3d body must be a unit quaternion (a scene file's "
               "is normalised if |q| is within 1e-6 of 1; braun_scene_build itself needs |q| "
               "within 1e-9 of 1, 1e-6 in float)";
    return NULL;
}

static void rigid3d_mass_at(const braun_scene_body *b, const braun_real *q, braun_real *M, int ld)
{
    const braun_real *p = q + 3;
    braun_real J[9], k = aug(b);
    const braun_real is = 1 / dot4(p, p), is2 = is * is; /* M_pp = M0/s² */
    tensor(b, J);
    for (int i = 0; i < 3; i++) M[braun_scene__at(i, i, ld)] += b->mass;
    /* Column c of G is g_c; (GᵀJG)_{cd} = g_cᵀ J g_d. */
    braun_real G[12]; /* 3 x 4 */
    for (int c = 0; c < 4; c++) {
        braun_real e[4] = {0, 0, 0, 0}, col[3];
        e[c] = 1;
        g_times(p, e, col);
        for (int i = 0; i < 3; i++) G[4 * i + c] = col[i];
    }
    for (int c = 0; c < 4; c++) {
        const braun_real gc[3] = {G[c], G[4 + c], G[8 + c]};
        braun_real Jg[3];
        mat3_vec(J, gc, Jg);
        for (int d = 0; d < 4; d++) {
            const braun_real gd = G[d] * Jg[0] + G[4 + d] * Jg[1] + G[8 + d] * Jg[2];
            M[braun_scene__at(3 + d, 3 + c, ld)] += (4 * gd + 4 * k * p[c] * p[d]) * is2;
        }
    }
}

/* The rotational terms at (p, p'): ω' = 2Gp'/s into w, J ω' into Jw,
 * u = pᵀp'/s, 1/s; returns T_p = ½ω'ᵀJω' + 2k u². */
static braun_real rotational(const braun_scene_body *b, const braun_real *p, const braun_real *dp,
                             braun_real *w, braun_real *Jw, braun_real *u, braun_real *is)
{
    braun_real J[9];
    const braun_real k = aug(b);
    tensor(b, J);
    *is = 1 / dot4(p, p);
    g_times(p, dp, w);
    for (int i = 0; i < 3; i++) w[i] *= 2 * *is; /* ω' = 2 G p'/s */
    mat3_vec(J, w, Jw);
    *u = dot4(p, dp) * *is;
    return BRAUN_R(0.5) * braun_scene__dot3(w, Jw) + 2 * k * *u * *u;
}

static braun_real rigid3d_kinetic_at(const braun_scene_body *b, const braun_real *q,
                                     const braun_real *v, braun_real *dEdq, braun_real *dEdv)
{
    const braun_real *p = q + 3, *dp = v + 3;
    braun_real w[3], Jw[3], u, is;
    const braun_real k = aug(b), Tp = rotational(b, p, dp, w, Jw, &u, &is);
    const braun_real T = BRAUN_R(0.5) * b->mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + Tp;
    if (dEdv) {
        braun_real y[4];
        for (int i = 0; i < 3; i++) dEdv[i] += b->mass * v[i];
        gt_times(p, Jw, y); /* ∂T/∂p' = 2GᵀJω'/s + 4k u p/s */
        for (int c = 0; c < 4; c++) dEdv[3 + c] += (2 * y[c] + 4 * k * u * p[c]) * is;
    }
    if (dEdq) {
        braun_real y[4];
        gt_times(dp, Jw, y); /* ∂T/∂p = -2G(p')ᵀJω'/s + 4k u p'/s - 4 T_p p/s */
        for (int c = 0; c < 4; c++) dEdq[3 + c] += (-2 * y[c] + 4 * k * u * dp[c] - 4 * Tp * p[c]) * is;
    }
    return T;
}

/* Q_p = -4G(p')ᵀJω'/s - 4k|p'|² p/s² + 4u ∂T/∂p' - 4 T_p p/s (header). */
static void rigid3d_inertial(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                             braun_real *Q)
{
    const braun_real *p = q + 3, *dp = v + 3;
    braun_real w[3], Jw[3], y[4], z[4], u, is;
    const braun_real k = aug(b), Tp = rotational(b, p, dp, w, Jw, &u, &is);
    gt_times(dp, Jw, y);
    gt_times(p, Jw, z);
    const braun_real dd = dot4(dp, dp);
    for (int c = 0; c < 4; c++)
        Q[3 + c] += (-4 * y[c] - 4 * k * dd * is * p[c] + 4 * u * (2 * z[c] + 4 * k * u * p[c]) -
                     4 * Tp * p[c]) * is;
}

/* Shared by points and directions: the rotation of s by the unit
 * quaternion p/|p|, pos += R s = A(p)s/N with N = |p|², so that a body
 * stays rigid off the unit sphere too (its points move only with the
 * orientation p stands for: a joint row never sees |p|, and rows that are
 * exactly dependent on the manifold — a Bricard linkage's — stay so at the
 * Runge–Kutta stages off it). With g = A(p)s (quadratic), N' = 2pᵀp':
 *   jac = ∂(g/N)/∂p = J_g/N - g (2pᵀ)/N²
 *   cc  = g''/N - 2 g' N'/N² - g N''/N² + 2 g N'²/N³,
 *         g' = J_g p', g'' = 2A(p')s, N'' = 2|p'|². */
static void body_vector(const braun_real *p, const braun_real *s, const braun_real *v,
                        braun_scene_pt *P)
{
    braun_real g[3], Jg[12];
    rotate(p, s, g);
    rotate_jac(p, s, Jg);
    const braun_real N = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    const braun_real iN = 1 / N;
    for (int i = 0; i < 3; i++) {
        P->pos[i] += g[i] * iN;
        for (int c = 0; c < 4; c++) P->jac[4 * i + c] = (Jg[4 * i + c] - 2 * g[i] * p[c] * iN) * iN;
    }
    if (v) {
        const braun_real *dp = v + 3;
        braun_real gdd[3];
        rotate(dp, s, gdd);
        const braun_real dN = 2 * (p[0] * dp[0] + p[1] * dp[1] + p[2] * dp[2] + p[3] * dp[3]);
        const braun_real ddN = 2 * (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2] + dp[3] * dp[3]);
        for (int i = 0; i < 3; i++) {
            const braun_real gd = Jg[4 * i] * dp[0] + Jg[4 * i + 1] * dp[1] +
                                  Jg[4 * i + 2] * dp[2] + Jg[4 * i + 3] * dp[3];
            P->vel[i] += (gd - g[i] * dN * iN) * iN;
            P->cc[i] = (2 * gdd[i] - 2 * gd * dN * iN - g[i] * ddN * iN + 2 * g[i] * dN * dN * iN * iN) * iN;
        }
    }
}

static void rigid3d_point(const braun_scene_body *b, const braun_scene_point *pt,
                          const braun_real *q, const braun_real *v, braun_scene_pt *P)
{
    const braun_real s[3] = {pt->x, pt->y, pt->z};
    (void)b;
    for (int i = 0; i < 3; i++) {
        P->pos[i] = q[i];
        if (v) P->vel[i] = v[i];
    }
    body_vector(q + 3, s, v, P);
}

static void rigid3d_direction(const braun_scene_body *b, const braun_real *d, const braun_real *q,
                              const braun_real *v, braun_scene_pt *P)
{
    (void)b;
    for (int i = 0; i < 3; i++) P->pos[i] = 0;
    P->direction = 1;
    body_vector(q + 3, d, v, P);
}

static void rigid3d_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row)
{
    if (!P->direction)
        for (int i = 0; i < 3; i++) row[i] += g[i];
    for (int c = 0; c < 4; c++)
        row[3 + c] += g[0] * P->jac[c] + g[1] * P->jac[4 + c] + g[2] * P->jac[8 + c];
}

static void rigid3d_weight(const braun_scene_body *b, const braun_real *g, braun_real *Q)
{
    for (int i = 0; i < 3; i++) Q[i] += b->mass * g[i];
}

static braun_real rigid3d_gravity_potential(const braun_scene_body *b, const braun_real *g,
                                            const braun_real *q)
{
    return -(b->mass * (g[0] * q[0] + g[1] * q[1] + g[2] * q[2]));
}

/* |p|² - 1 = 0: A = 2pᵀ, Φ'' = 2pᵀp'' + 2|p'|², so b_qv = -2|p'|². */
static void rigid3d_constraint(const braun_scene_body *b, const braun_real *q, const braun_real *v,
                               braun_real *phi, braun_real *A, int ld, braun_real *bv)
{
    const braun_real *p = q + 3;
    (void)b;
    (void)ld;
    if (phi) phi[0] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1;
    if (A)
        for (int c = 0; c < 4; c++) A[3 + c] += 2 * p[c];
    if (bv) {
        const braun_real *dp = v + 3;
        bv[0] = -2 * (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2] + dp[3] * dp[3]);
    }
}

/* W = [0 | 2E(p)/|p|²]: ω = 2 E(p) p'/|p|², the world angular velocity
 * of the rotation the points move with (R = A(p)/|p|², ω̃ = R'Rᵀ; E(p) p =
 * 0), whatever |p|: a torque's generalized force Wᵀτ and its power τ·ω are
 * those of the true ω. */
static void rigid3d_omega(const braun_scene_body *b, const braun_real *q, braun_real *W)
{
    const braun_real e0 = q[3], e1 = q[4], e2 = q[5], e3 = q[6];
    const braun_real E[12] = {-e1, e0, -e3, e2, -e2, e3, e0, -e1, -e3, -e2, e1, e0};
    const braun_real two_is = 2 / dot4(q + 3, q + 3);
    (void)b;
    for (int i = 0; i < 3; i++) {
        for (int c = 0; c < 3; c++) W[7 * i + c] = 0;
        for (int c = 0; c < 4; c++) W[7 * i + 3 + c] = two_is * E[4 * i + c];
    }
}

/* q = (r, p/|p|), v = (r', p') with p' = ½ E(p)ᵀ ω (so pᵀp' = 0 and
 * 2E p' = ω for a unit p). */
static void rigid3d_initial(const braun_scene_body *b, braun_real *q, braun_real *v)
{
    const braun_real *p0 = b->q0 + 3, *w = b->v0 + 3;
    const braun_real nn = braun_sqrt(p0[0] * p0[0] + p0[1] * p0[1] + p0[2] * p0[2] + p0[3] * p0[3]);
    for (int i = 0; i < 3; i++) {
        q[i] = b->q0[i];
        v[i] = b->v0[i];
    }
    for (int c = 0; c < 4; c++) q[3 + c] = nn > 0 ? p0[c] / nn : p0[c];
    const braun_real e0 = q[3], e1 = q[4], e2 = q[5], e3 = q[6];
    /* Eᵀω: rows of Eᵀ are the columns of E. */
    v[3] = BRAUN_R(0.5) * (-e1 * w[0] - e2 * w[1] - e3 * w[2]);
    v[4] = BRAUN_R(0.5) * (e0 * w[0] + e3 * w[1] - e2 * w[2]);
    v[5] = BRAUN_R(0.5) * (-e3 * w[0] + e0 * w[1] + e1 * w[2]);
    v[6] = BRAUN_R(0.5) * (e2 * w[0] - e1 * w[1] + e0 * w[2]);
}

enum { F_MASS, F_INERTIA, F_PRODUCTS, F_POSITION, F_ORIENTATION, F_VELOCITY, F_OMEGA, F_POINTS };

/* Scene files: the identity when no orientation is given; a quaternion
 * within 1e-6 of unit length normalised (so six printed digits work), any
 * other left for the check to refuse. */
static void rigid3d_defaults(braun_scene_body *b, unsigned given)
{
    braun_real *p = b->q0 + 3;
    if (!BRAUN_FIELD_GIVEN(given, F_ORIENTATION)) {
        p[0] = 1;
        p[1] = p[2] = p[3] = 0;
        return;
    }
    const braun_real nn = braun_sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    if (braun_fabs(nn - 1) <= BRAUN_R(1e-6))
        for (int c = 0; c < 4; c++) p[c] /= nn;
}

static const braun_scene_field rigid3d_fields[] = {
    [F_MASS] = {"mass", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, mass),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    [F_INERTIA] = {"inertia", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, tensor),
                   BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    [F_PRODUCTS] = {"products", BRAUN_FIELD_REAL, 3,
                    offsetof(braun_scene_body, tensor) + 3 * sizeof(braun_real), 0, NULL},
    [F_POSITION] = {"position", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, q0),
                    BRAUN_FIELD_REQUIRED, NULL},
    [F_ORIENTATION] = {"orientation", BRAUN_FIELD_REAL, 4,
                       offsetof(braun_scene_body, q0) + 3 * sizeof(braun_real),
                       BRAUN_FIELD_NONZERO, NULL},
    [F_VELOCITY] = {"velocity", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, v0), 0, NULL},
    [F_OMEGA] = {"omega", BRAUN_FIELD_REAL, 3,
                 offsetof(braun_scene_body, v0) + 3 * sizeof(braun_real), 0, NULL},
    [F_POINTS] = {"points", BRAUN_FIELD_POINTS, 3, 0, 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_body_class braun_scene_body_rigid3d = {
    "rigid3d", "BRAUN_BODY_RIGID3D", 7, 3, -1, 0u, rigid3d_fields, rigid3d_check,
    NULL, NULL, rigid3d_point, rigid3d_grad, rigid3d_weight, rigid3d_gravity_potential,
    rigid3d_mass_at, rigid3d_kinetic_at, rigid3d_inertial, 1, rigid3d_constraint,
    rigid3d_direction, rigid3d_omega, rigid3d_initial, rigid3d_defaults};
