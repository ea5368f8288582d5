/* Every spatial element type, one at a time, against finite differences
 * (tests/scene/scene_fd.h): A_q, b_q, b_qv of each joint, the rigid3d
 * body's own row, dE/dq, dE/dv and the energy rate dE/dt = Ė along
 * M v' = Q (which checks the velocity-product forces of the Euler
 * parameters' M(q) and every effect's potential and power). Plus the
 * kinematics the FD checks cannot see: a body point's velocity is ω × (P −
 * r) with ω the class's angular velocity, and the mass block is the
 * kinetic energy's Hessian at a unit quaternion (T = ½ m|v|² + ½ ωᵀIω).
 * The states are random and not on the constraints (the identities hold
 * everywhere), quaternions not unit. */
#include "test_util.h"
#include "braun_scene.h"
#include "scene/scene_fd.h"

typedef struct spatial {
    braun_scene_body bodies[4];
    braun_scene_point points[12];
    braun_scene_joint joints[6];
    braun_scene_effect effects[6];
    braun_scene s;
    braun_system sys;
} spatial;

/* Bodies: two rigid3d bodies, a particle3d; points on each and on the
 * ground. */
enum { B0_P, B0_Q, B1_P, B1_Q, PART, GROUND_P, GROUND_Q, B0_C, B1_C, NPOINTS };

static void spatial_init(spatial *g)
{
    memset(g, 0, sizeof *g);
    braun_scene_body *b = g->bodies;
    b[0].kind = BRAUN_BODY_RIGID3D;
    b[0].mass = 2.0;
    const double t0[6] = {0.3, 0.25, 0.4, 0.02, -0.03, 0.01};
    memcpy(b[0].tensor, t0, sizeof t0);
    const double q0[7] = {0.1, 0.2, -0.3, 0.9, 0.1, -0.3, 0.2};
    memcpy(b[0].q0, q0, sizeof q0);
    b[1].kind = BRAUN_BODY_RIGID3D;
    b[1].mass = 1.5;
    const double t1[6] = {0.2, 0.35, 0.3, 0, 0.01, 0};
    memcpy(b[1].tensor, t1, sizeof t1);
    const double q1[7] = {1.0, -0.3, 0.4, 0.5, -0.5, 0.5, 0.5};
    memcpy(b[1].q0, q1, sizeof q1);
    b[2].kind = BRAUN_BODY_PARTICLE3D;
    b[2].mass = 0.7;
    b[2].q0[0] = 0.5, b[2].q0[1] = 0.5, b[2].q0[2] = 0.2;
    braun_scene_point *p = g->points;
    p[B0_P] = (braun_scene_point){0, 0.3, -0.2, 0.1};
    p[B0_Q] = (braun_scene_point){0, -0.1, 0.25, 0.3};
    p[B1_P] = (braun_scene_point){1, -0.4, 0.1, -0.2};
    p[B1_Q] = (braun_scene_point){1, 0.2, 0.25, 0.15};
    p[PART] = (braun_scene_point){2, 0, 0, 0};
    p[GROUND_P] = (braun_scene_point){BRAUN_SCENE_GROUND, 0.5, 0.7, -0.4};
    p[GROUND_Q] = (braun_scene_point){BRAUN_SCENE_GROUND, -0.3, 0.1, 0.6};
    p[B0_C] = (braun_scene_point){0, 0, 0, 0};
    p[B1_C] = (braun_scene_point){1, 0, 0, 0};
    for (int k = 0; k < 2; k++) { /* unit quaternions, as the builder asks */
        double *qk = b[k].q0 + 3, nn = sqrt(qk[0] * qk[0] + qk[1] * qk[1] + qk[2] * qk[2] + qk[3] * qk[3]);
        for (int c = 0; c < 4; c++) qk[c] /= nn;
    }
    g->s.nbodies = 3;
    g->s.bodies = g->bodies;
    g->s.npoints = NPOINTS;
    g->s.points = g->points;
    g->s.joints = g->joints;
    g->s.effects = g->effects;
}

static const braun_scene_fn SINE = {BRAUN_FN_SINE, 0.2, 0.7, 2.3, 0.4};
static const braun_scene_fn LINEAR = {BRAUN_FN_LINEAR, 0.4, -1.3, 0, 0};
/* A driven length stays above 0 (offset > |amplitude|: the builder refuses
 * a sine length that reaches 0, which the row cannot tell from -L). */
static const braun_scene_fn LENGTH_SINE = {BRAUN_FN_SINE, 0.9, 0.7, 2.3, 0.4};

static braun_scene_joint joint(const braun_scene_joint_class *type, int a, int b,
                               const double *axis, const double *axis_b,
                               const braun_scene_fn *drive)
{
    braun_scene_joint j;
    memset(&j, 0, sizeof j);
    j.type = type;
    j.a = a;
    j.b = b;
    for (int k = 0; k < 3; k++) {
        j.axis[k] = axis ? axis[k] : 0;
        j.axis_b[k] = axis_b ? axis_b[k] : 0;
    }
    if (drive) {
        j.driven = 1;
        j.drive = *drive;
    }
    return j;
}

/* Defaults (frames from the initial state), build, then the checks at
 * three random states. */
static void check_spatial(spatial *g, const char *what)
{
    braun_scene_error err;
    assert_int_equal(braun_scene_defaults(&g->s), BRAUN_OK);
    int st = braun_scene_build(&g->s, &g->sys, &err);
    if (st) fail_msg("%s: build failed: %s (element %d #%d)", what, err.what, err.element,
                     err.index);
    assert_int_equal(g->s.dim, 3);
    assert_false(g->sys.flags & BRAUN_MASS_CONSTANT);
    for (int trial = 0; trial < 3; trial++) {
        double q[FD_NMAX], v[FD_NMAX];
        for (int i = 0; i < g->s.n; i++) {
            q[i] = 1.2 * fd_urand();
            v[i] = 1.5 * fd_urand();
        }
        fd_check_system(what, &g->sys, 0.37 + trial, q, v, 2e-6);
    }
}

static const double AX[3] = {0.3, -0.5, 0.8}, AY[3] = {0, 1, 0}, AZ[3] = {0, 0, 1};

static void test_bodies(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    check_spatial(&g, "rigid3d and particle3d bodies");
    /* q: 7 + 7 + 3; the two quaternion rows come last (after the joints'). */
    assert_int_equal(g.s.n, 17);
    assert_int_equal(g.s.m, 2);
    assert_int_equal(g.bodies[0].row, 0);
    assert_int_equal(g.bodies[1].row, 1);
    assert_int_equal(g.bodies[1].iq, 7);
}

/* P' = ω × (P - r) and the mass block against T at a unit quaternion with
 * p·p' = 0: ½ vᵀMv = ½ m|r'|² + ½ ω'ᵀ J ω' (ω' = Rᵀω). */
static void test_rigid3d_kinematics(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    braun_scene_body *b = &g.bodies[0];
    for (int k = 0; k < 3; k++) b->v0[k] = 0.3 * (k + 1), b->v0[3 + k] = 0.7 - 0.4 * k;
    assert_int_equal(braun_scene_defaults(&g.s), BRAUN_OK);
    assert_int_equal(braun_scene_build(&g.s, &g.sys, NULL), BRAUN_OK);
    double q[17], v[17];
    braun_scene_initial_state(&g.s, q, v);
    const double *p = q + 3, *dp = v + 3;
    assert_near(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3], 1, 1e-15);
    assert_near(p[0] * dp[0] + p[1] * dp[1] + p[2] * dp[2] + p[3] * dp[3], 0, 1e-15);
    double W[3 * 7], w[3] = {0, 0, 0};
    b->kind->omega(b, q, W);
    for (int i = 0; i < 3; i++)
        for (int c = 0; c < 7; c++) w[i] += W[7 * i + c] * v[c];
    for (int i = 0; i < 3; i++) assert_near(w[i], b->v0[3 + i], 1e-14); /* ω as given */
    double pos[3], vel[3];
    braun_scene_point_state(&g.s, B0_P, q, v, pos, vel);
    const double d[3] = {pos[0] - q[0], pos[1] - q[1], pos[2] - q[2]};
    const double wxd[3] = {w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                           w[0] * d[1] - w[1] * d[0]};
    for (int i = 0; i < 3; i++) assert_near(vel[i], v[i] + wxd[i], 1e-14);
    /* |P - r| is the body-frame distance (a rotation). */
    const double s0[3] = {0.3, -0.2, 0.1};
    assert_near(d[0] * d[0] + d[1] * d[1] + d[2] * d[2],
                s0[0] * s0[0] + s0[1] * s0[1] + s0[2] * s0[2], 1e-15);
    /* T from M and from the inertia tensor. */
    double M[17 * 17];
    assert_int_equal(g.sys.mass(0, q, M, g.sys.user), 0);
    double T = 0;
    for (int i = 0; i < 17; i++)
        for (int j = 0; j < 17; j++) T += 0.5 * v[i] * M[i * 17 + j] * v[j];
    /* ω' = Rᵀ ω: R's columns are the world images of the body axes. */
    double wb[3], Jw[3];
    for (int i = 0; i < 3; i++) {
        double e[3] = {0, 0, 0};
        e[i] = 1;
        braun_scene_pt D;
        braun_scene_dir_eval(&g.s, 0, e, q, NULL, &D);
        wb[i] = D.pos[0] * w[0] + D.pos[1] * w[1] + D.pos[2] * w[2];
    }
    const double *t = b->tensor;
    const double J[9] = {t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2]};
    for (int i = 0; i < 3; i++) Jw[i] = J[3 * i] * wb[0] + J[3 * i + 1] * wb[1] + J[3 * i + 2] * wb[2];
    double Tref = 0.5 * b->mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
                  0.5 * (wb[0] * Jw[0] + wb[1] * Jw[1] + wb[2] * Jw[2]);
    Tref += 0.5 * g.bodies[2].mass * 0; /* the particle is at rest */
    assert_near(T, Tref, 1e-14);
    double E;
    assert_int_equal(g.sys.energy(0, q, v, &E, NULL, NULL, NULL, g.sys.user), 0);
    assert_near(E, Tref, 1e-14);
}

/* ------------------------------------------- a rigid3d off the unit sphere */
/* Body 0 of spatial_init alone (n = 7: its own row only), at states off
 * the unit sphere: p = λ p̂ (λ = 1.01, 0.97) and p' = λ p̂' + ρ p (a radial
 * part, ρ = 0.3). Its points move with R = A(p)/|p|² whatever |p|
 * (braun_scene_dir_eval), so its kinetic energy is that of their motion,
 *   T = ½ m|r'|² + ½ ω'ᵀJω' + 2k (pᵀp'/|p|²)²,   ω̃' = RᵀR',  k = tr J/3,
 * with ω' taken from the world images of the body axes and their rates —
 * not from the class's G(p) — and the augmentation that vanishes on the
 * velocity manifold. Until 2026-12-05 the class's T was ½ m|r'|² +
 * 2p'ᵀGᵀJGp' + 2k(pᵀp')², |p|⁴ times this rotational part: the energy
 * the correction held was not that of the points' motion off the sphere. */
typedef struct lone {
    spatial g;
    double q[7], v[7];
} lone;

static void lone_init(lone *L)
{
    spatial_init(&L->g);
    L->g.s.nbodies = 1;
    L->g.s.npoints = 2; /* B0_P, B0_Q */
    assert_int_equal(braun_scene_defaults(&L->g.s), BRAUN_OK);
    assert_int_equal(braun_scene_build(&L->g.s, &L->g.sys, NULL), BRAUN_OK);
    assert_int_equal(L->g.s.n, 7);
    assert_int_equal(L->g.s.m, 1);
}

/* The state at λ, ρ: a unit p̂ with p̂ᵀp̂' = 0 (ω given), then scaled. */
static void lone_state(lone *L, double lambda, double rho)
{
    const braun_scene_body *b = &L->g.bodies[0];
    const double w[3] = {0.9, -2.1, 1.4}; /* world ω at the unit state */
    const double *p = b->q0 + 3;
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double dp[4] = {0.5 * (-e1 * w[0] - e2 * w[1] - e3 * w[2]),
                          0.5 * (e0 * w[0] + e3 * w[1] - e2 * w[2]),
                          0.5 * (-e3 * w[0] + e0 * w[1] + e1 * w[2]),
                          0.5 * (e2 * w[0] - e1 * w[1] + e0 * w[2])};
    const double r[3] = {0.1, 0.2, -0.3}, dr[3] = {0.4, -0.7, 0.25};
    for (int k = 0; k < 3; k++) L->q[k] = r[k], L->v[k] = dr[k];
    for (int c = 0; c < 4; c++) {
        L->q[3 + c] = lambda * p[c];
        L->v[3 + c] = lambda * dp[c] + rho * L->q[3 + c];
    }
}

/* R's columns (world images of the body axes) and their rates at (q, v). */
static void lone_frame(const lone *L, const double *q, const double *v, double c[3][3],
                       double d[3][3])
{
    for (int i = 0; i < 3; i++) {
        double e[3] = {0, 0, 0};
        e[i] = 1;
        braun_scene_pt D;
        braun_scene_dir_eval(&L->g.s, 0, e, q, v, &D);
        for (int k = 0; k < 3; k++) c[i][k] = D.pos[k], d[i][k] = D.vel[k];
    }
}

/* T of the points' motion at (q, v), from the frame (no G(p)). */
static double lone_T(const lone *L, const double *q, const double *v)
{
    const braun_scene_body *b = &L->g.bodies[0];
    double c[3][3], d[3][3];
    lone_frame(L, q, v, c, d);
    /* (RᵀR')_{ij} = c_i·d_j: ω'_x = c_z·d_y, ω'_y = c_x·d_z, ω'_z = c_y·d_x. */
    const double wb[3] = {c[2][0] * d[1][0] + c[2][1] * d[1][1] + c[2][2] * d[1][2],
                          c[0][0] * d[2][0] + c[0][1] * d[2][1] + c[0][2] * d[2][2],
                          c[1][0] * d[0][0] + c[1][1] * d[0][1] + c[1][2] * d[0][2]};
    const double *t = b->tensor;
    const double J[9] = {t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2]};
    double wJw = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) wJw += wb[i] * J[3 * i + j] * wb[j];
    const double *p = q + 3, *dp = v + 3;
    const double s = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    const double u = (p[0] * dp[0] + p[1] * dp[1] + p[2] * dp[2] + p[3] * dp[3]) / s;
    const double k = (t[0] + t[1] + t[2]) / 3;
    return 0.5 * b->mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * wJw + 2 * k * u * u;
}

/* ∂T/∂v at (q, v): T is quadratic in v, so a central difference of step 1
 * is exact (to rounding). */
static void lone_dTdv(const lone *L, const double *q, const double *v, double *g)
{
    for (int j = 0; j < 7; j++) {
        double vp[7], vm[7];
        memcpy(vp, v, sizeof vp);
        memcpy(vm, v, sizeof vm);
        vp[j] += 1;
        vm[j] -= 1;
        g[j] = 0.5 * (lone_T(L, q, vp) - lone_T(L, q, vm));
    }
}

static int lone_failures;
static void lone_check(const char *what, int i, int j, double got, double want, double tol)
{
    if (fabs(got - want) <= tol * (1 + fabs(want))) return;
    print_error("%s[%d][%d]: %.15g, expected %.15g\n", what, i, j, got, want);
    lone_failures++;
}

static void test_rigid3d_off_sphere(void **state)
{
    (void)state;
    static lone L;
    lone_init(&L);
    const braun_system *sys = &L.g.sys;
    const braun_scene_body *b = &L.g.bodies[0];
    const double lambdas[2] = {1.01, 0.97};
    lone_failures = 0;
    for (int l = 0; l < 2; l++) {
        lone_state(&L, lambdas[l], 0.3);
        const double *q = L.q, *v = L.v;
        /* The energy, here and at the normalised state (p/|p|, p'/|p|). */
        const double T = lone_T(&L, q, v);
        double E, dEdq[7], dEdv[7], dEdt, qn[7], vn[7], En;
        assert_int_equal(sys->energy(0, q, v, &E, dEdq, dEdv, &dEdt, sys->user), 0);
        lone_check("E", l, 0, E, T, 1e-14);
        memcpy(qn, q, sizeof qn);
        memcpy(vn, v, sizeof vn);
        for (int c = 3; c < 7; c++) qn[c] /= lambdas[l], vn[c] /= lambdas[l];
        assert_int_equal(sys->energy(0, qn, vn, &En, NULL, NULL, NULL, sys->user), 0);
        lone_check("E normalised", l, 0, En, E, 1e-14);
        /* World ω = W v against R'Rᵀ = Σ_i d_i c_iᵀ. */
        double W[21], c[3][3], d[3][3], w[3] = {0, 0, 0}, wf[3] = {0, 0, 0};
        b->kind->omega(b, q, W);
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 7; k++) w[i] += W[7 * i + k] * v[k];
        lone_frame(&L, q, v, c, d);
        for (int i = 0; i < 3; i++) {
            wf[0] += d[i][2] * c[i][1];
            wf[1] += d[i][0] * c[i][2];
            wf[2] += d[i][1] * c[i][0];
        }
        for (int i = 0; i < 3; i++) lone_check("omega", l, i, w[i], wf[i], 1e-14);
        /* M: T's Hessian in v by polarisation. */
        double M[49], ei[7], ej[7], eij[7];
        assert_int_equal(sys->mass(0, q, M, sys->user), 0);
        for (int i = 0; i < 7; i++)
            for (int j = 0; j < 7; j++) {
                memset(ei, 0, sizeof ei);
                memset(ej, 0, sizeof ej);
                ei[i] = 1;
                ej[j] = 1;
                for (int k = 0; k < 7; k++) eij[k] = ei[k] + ej[k];
                const double Mij = i == j ? 2 * lone_T(&L, q, ei)
                                          : lone_T(&L, q, eij) - lone_T(&L, q, ei) - lone_T(&L, q, ej);
                lone_check("M", i, j, M[7 * i + j], Mij, 1e-13);
            }
        /* ∂E/∂v, ∂E/∂q, and the forces of Lagrange's equations of T at
         * v' = 0: Q = -(∂(∂T/∂v)/∂q) v + ∂T/∂q, first differences in q. */
        double gv[7], Q[7], gp[7], gm[7], qp[7], qm[7];
        const double h = 1e-6;
        lone_dTdv(&L, q, v, gv);
        for (int j = 0; j < 7; j++) lone_check("dE/dv", j, 0, dEdv[j], gv[j], 1e-13);
        assert_int_equal(sys->forces(0, q, v, Q, sys->user), 0);
        for (int k = 0; k < 7; k++) qp[k] = q[k] + h * v[k], qm[k] = q[k] - h * v[k];
        lone_dTdv(&L, qp, v, gp);
        lone_dTdv(&L, qm, v, gm);
        for (int j = 0; j < 7; j++) {
            memcpy(qp, q, sizeof qp);
            memcpy(qm, q, sizeof qm);
            qp[j] += h;
            qm[j] -= h;
            const double dTdq = (lone_T(&L, qp, v) - lone_T(&L, qm, v)) / (2 * h);
            lone_check("dE/dq", j, 0, dEdq[j], dTdq, 1e-8);
            lone_check("Q", j, 0, Q[j], -(gp[j] - gm[j]) / (2 * h) + dTdq, 1e-8);
        }
    }
    if (lone_failures) fail_msg("%d entries differ from those of the points' motion", lone_failures);
}

/* The body's dynamics do not depend on |p|: the Udwadia–Kalaba
 * acceleration (no corrections) at (λp, λp') is (r'', λp'') of the one at
 * (p, p'), for a free body under gravity, a world torque, a body-frame
 * torque and a force at a body point (λ = 1.01, 0.97, with a radial part
 * in p'). Until 2026-12-05 a torque's W = [0 | 2E(p)] and the mass block
 * 4GᵀJG + 4kppᵀ made its share of p'' scale with 1/λ, a point force's with
 * 1/λ³. */
static void test_rigid3d_scale_invariance(void **state)
{
    (void)state;
    static lone L;
    spatial_init(&L.g);
    L.g.s.nbodies = 1;
    L.g.s.npoints = 2;
    braun_scene_effect *e = L.g.effects;
    e[0].type = BRAUN_EFFECT_GRAVITY, e[0].g[0] = 0.3, e[0].g[1] = -9.81, e[0].g[2] = 1.1;
    e[1].type = BRAUN_EFFECT_TORQUE3D, e[1].a = 0, e[1].b = BRAUN_SCENE_GROUND;
    e[1].f[0] = (braun_scene_fn){BRAUN_FN_CONSTANT, 0.8, 0, 0, 0};
    e[1].f[2] = (braun_scene_fn){BRAUN_FN_CONSTANT, -1.3, 0, 0, 0};
    e[2].type = BRAUN_EFFECT_BODY_TORQUE, e[2].a = 0, e[2].b = BRAUN_SCENE_GROUND;
    e[2].f[1] = (braun_scene_fn){BRAUN_FN_CONSTANT, 0.6, 0, 0, 0};
    e[3].type = BRAUN_EFFECT_BODY_FORCE, e[3].a = B0_P;
    e[3].f[0] = (braun_scene_fn){BRAUN_FN_CONSTANT, 2.5, 0, 0, 0};
    e[3].f[2] = (braun_scene_fn){BRAUN_FN_CONSTANT, -1.5, 0, 0, 0};
    L.g.s.neffects = 4;
    assert_int_equal(braun_scene_defaults(&L.g.s), BRAUN_OK);
    assert_int_equal(braun_scene_build(&L.g.s, &L.g.sys, NULL), BRAUN_OK);
    assert_int_equal(L.g.s.n, 7);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &L.g.sys, BRAUN_CORRECT_NONE), BRAUN_OK);
    double qd1[7], a1[7], qdl[7], al[7];
    lone_state(&L, 1, 0.3);
    assert_int_equal(braun_set_state(&sim.data, 0, L.q, L.v), BRAUN_OK);
    assert_int_equal(braun_eval(&sim.data, 0, L.q, L.v, 1e-3, qd1, a1), BRAUN_OK);
    const double lambdas[2] = {1.01, 0.97};
    lone_failures = 0;
    for (int l = 0; l < 2; l++) {
        lone_state(&L, lambdas[l], 0.3);
        assert_int_equal(braun_eval(&sim.data, 0, L.q, L.v, 1e-3, qdl, al), BRAUN_OK);
        for (int k = 0; k < 7; k++) {
            const double want = k < 3 ? a1[k] : lambdas[l] * a1[k];
            lone_check("acceleration", l, k, al[k], want, 1e-13);
        }
    }
    test_sim_close(&sim);
    if (lone_failures) fail_msg("%d accelerations depend on |p|", lone_failures);
}

static void test_spherical(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_SPHERICAL, B0_P, B1_P, NULL, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_SPHERICAL, B1_Q, GROUND_P, NULL, NULL, NULL);
    g.joints[2] = joint(BRAUN_JOINT_SPHERICAL, PART, B0_Q, NULL, NULL, NULL);
    g.s.njoints = 3;
    check_spatial(&g, "spherical");
    assert_int_equal(g.s.m, 9 + 2);
}

static void test_revolute3d(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE3D, B0_P, B1_P, AX, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_REVOLUTE3D, B1_Q, GROUND_P, AY, NULL, &SINE);
    g.joints[2] = joint(BRAUN_JOINT_REVOLUTE3D, GROUND_Q, B0_Q, AZ, AX, &LINEAR);
    g.s.njoints = 3;
    check_spatial(&g, "revolute3d");
    assert_int_equal(g.s.m, 5 + 6 + 6 + 2);
    assert_false(g.sys.flags & BRAUN_SCLERONOMIC);
}

static void test_prismatic3d(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_PRISMATIC3D, B1_P, B0_P, AX, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_PRISMATIC3D, B0_Q, GROUND_P, AY, NULL, &SINE);
    g.s.njoints = 2;
    check_spatial(&g, "prismatic3d");
    assert_int_equal(g.s.m, 5 + 6 + 2);
}

static void test_cylindrical_universal_weld(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    const double perp[3] = {0.8, 0, -0.3}; /* ⊥ AX */
    g.joints[0] = joint(BRAUN_JOINT_CYLINDRICAL, B1_P, B0_P, AX, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_CYLINDRICAL, B0_Q, GROUND_P, AZ, AY, NULL);
    g.joints[2] = joint(BRAUN_JOINT_UNIVERSAL, B0_C, B1_Q, AX, perp, NULL);
    g.joints[3] = joint(BRAUN_JOINT_UNIVERSAL, GROUND_Q, B1_C, AZ, AY, NULL);
    g.joints[4] = joint(BRAUN_JOINT_WELD, B0_P, B1_Q, NULL, NULL, NULL);
    g.joints[5] = joint(BRAUN_JOINT_WELD, GROUND_Q, B1_P, NULL, NULL, NULL);
    g.s.njoints = 6;
    check_spatial(&g, "cylindrical, universal, weld");
    assert_int_equal(g.s.m, 4 + 4 + 4 + 4 + 6 + 6 + 2);
}

static void test_point_line_plane_distance(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_POINT_LINE, PART, B0_P, AX, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_POINT_LINE, B1_Q, GROUND_P, AY, NULL, NULL);
    g.joints[2] = joint(BRAUN_JOINT_POINT_PLANE, PART, B1_P, AX, NULL, NULL);
    g.joints[3] = joint(BRAUN_JOINT_POINT_PLANE, B0_Q, GROUND_Q, AZ, NULL, NULL);
    g.joints[4] = joint(BRAUN_JOINT_DISTANCE, B0_P, B1_Q, NULL, NULL, NULL);
    g.joints[4].value = 0.9;
    g.joints[5] = joint(BRAUN_JOINT_DISTANCE, PART, GROUND_P, NULL, NULL, &LENGTH_SINE);
    g.s.njoints = 6;
    check_spatial(&g, "point_line, point_plane, distance");
    assert_int_equal(g.s.m, 2 + 2 + 1 + 1 + 1 + 1 + 2);
}

static void test_gravity_springs(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_GRAVITY, e[0].g[0] = 0.3, e[0].g[1] = -9.81, e[0].g[2] = 1.1;
    e[1].type = BRAUN_EFFECT_SPRING, e[1].a = B0_P, e[1].b = PART, e[1].k = 30, e[1].rest = 0.5;
    e[2].type = BRAUN_EFFECT_SPRING, e[2].a = GROUND_P, e[2].b = B1_Q, e[2].k = 10;
    g.s.neffects = 3;
    check_spatial(&g, "gravity, springs");
    assert_null(g.sys.power);
    e[1].c = 0.7;
    check_spatial(&g, "gravity, spring-dampers");
    assert_true(g.sys.flags & BRAUN_ENERGY_INPUT);
}

static void test_forces_torques(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_FORCE, e[0].a = B1_P, e[0].f[0] = SINE, e[0].f[1] = LINEAR;
    e[0].f[2] = (braun_scene_fn){BRAUN_FN_CONSTANT, -0.8, 0, 0, 0};
    e[1].type = BRAUN_EFFECT_BODY_FORCE, e[1].a = B0_Q, e[1].f[0] = LINEAR, e[1].f[2] = SINE;
    e[2].type = BRAUN_EFFECT_TORQUE3D, e[2].a = 0, e[2].b = 1, e[2].f[1] = SINE;
    e[2].f[2] = LINEAR;
    e[3].type = BRAUN_EFFECT_TORQUE3D, e[3].a = 1, e[3].b = BRAUN_SCENE_GROUND, e[3].f[0] = SINE;
    e[4].type = BRAUN_EFFECT_BODY_TORQUE, e[4].a = 0, e[4].b = 1, e[4].f[0] = LINEAR;
    e[4].f[1] = SINE;
    e[5].type = BRAUN_EFFECT_BODY_TORQUE, e[5].a = 1, e[5].b = BRAUN_SCENE_GROUND;
    e[5].f[2] = (braun_scene_fn){BRAUN_FN_CONSTANT, 1.5, 0, 0, 0};
    g.s.neffects = 6;
    check_spatial(&g, "force, body_force, torque3d, body_torque");
}

static void test_torsion_motor(void **state)
{
    (void)state;
    spatial g;
    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE3D, B0_P, B1_P, AX, NULL, NULL);
    g.joints[1] = joint(BRAUN_JOINT_CYLINDRICAL, B1_Q, GROUND_P, AY, NULL, NULL);
    g.s.njoints = 2;
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_TORSION3D, e[0].a = 0, e[0].k = 3, e[0].rest = 0.3;
    e[1].type = BRAUN_EFFECT_TORSION3D, e[1].a = 1, e[1].k = 2;
    g.s.neffects = 2;
    check_spatial(&g, "torsion3d springs");
    assert_null(g.sys.power);
    e[0].c = 0.2;
    e[1].c = 0.05;
    check_spatial(&g, "torsion3d dampers");
    e[2].type = BRAUN_EFFECT_MOTOR3D, e[2].a = 0, e[2].tau0 = 2, e[2].omega0 = 15;
    e[3].type = BRAUN_EFFECT_MOTOR3D, e[3].a = 1, e[3].tau0 = -1, e[3].omega0 = -4;
    g.s.neffects = 4;
    check_spatial(&g, "torsion3d and motor3d");
}

/* Planar and spatial do not mix; axes need oriented bodies. */
static void test_refusals(void **state)
{
    (void)state;
    spatial g;
    braun_scene_error err;

    spatial_init(&g);
    g.bodies[3] = (braun_scene_body){BRAUN_BODY_RIGID, 1, 0.1, {0}, {0}, 0, {0}, 0};
    g.s.nbodies = 4;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.element, BRAUN_SCENE_ELEM_BODY);
    assert_int_equal(err.index, 3);

    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE, B0_P, B1_P, NULL, NULL, NULL);
    g.s.njoints = 1;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_string_equal(err.what, "a planar joint in a spatial scene (use its spatial counterpart)");

    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE3D, PART, B1_P, AX, NULL, NULL);
    g.s.njoints = 1;
    assert_int_equal(braun_scene_defaults(&g.s), BRAUN_OK);
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(err.what, "no orientation"));

    spatial_init(&g);
    g.bodies[0].q0[3] = 2; /* not a unit quaternion */
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(err.what, "unit quaternion"));

    spatial_init(&g);
    g.bodies[1].tensor[0] = 0; /* a thin rod without its axial moment */
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.index, 1);

    spatial_init(&g);
    g.bodies[1].tensor[3] = 0.5; /* products make the tensor indefinite */
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(err.what, "positive definite"));

    spatial_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE3D, B0_P, B1_P, AX, NULL, NULL);
    g.s.njoints = 1; /* no defaults: the axis is not a unit vector */
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(err.what, "unit vectors"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bodies),
        cmocka_unit_test(test_rigid3d_kinematics),
        cmocka_unit_test(test_rigid3d_off_sphere),
        cmocka_unit_test(test_rigid3d_scale_invariance),
        cmocka_unit_test(test_spherical),
        cmocka_unit_test(test_revolute3d),
        cmocka_unit_test(test_prismatic3d),
        cmocka_unit_test(test_cylindrical_universal_weld),
        cmocka_unit_test(test_point_line_plane_distance),
        cmocka_unit_test(test_gravity_springs),
        cmocka_unit_test(test_forces_torques),
        cmocka_unit_test(test_torsion_motor),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
