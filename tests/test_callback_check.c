/* braun_check_callbacks (host tier): the built-in models pass at their
 * initial states and along their motion; a misprint in each checked
 * quantity is found and named. The misprints are the kind the corrections
 * hide: the library runs them with status 0. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "braun_host.h"
#include "braun_models.h"
#include "braun_scene_file.h"

/* The built-in models, at the start and after 0.37 s and 1.3 s of corrected
 * RK4 (states on the constraints, moving). */
static void test_builtins_pass(void **state)
{
    (void)state;
    for (int k = 0; braun_builtin_at(k); k++) {
        const braun_builtin *b = braun_builtin_at(k);
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL & (b->sys.energy ? 7u : 3u)),
                         BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
        const double at[3] = {0, 0.37, 1.3};
        for (int s = 0; s < 3; s++) {
            if (at[s] > 0)
                assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, at[s], 0, NULL, NULL),
                                 BRAUN_OK);
            braun_callback_report rep;
            const int st = braun_check_callbacks(&b->sys, sim.data.t, sim.data.q, sim.data.v, 0, &rep);
            print_message("%s t = %.2f: A_q %.1e b_q %.1e b_qv %.1e A_vv %.1e b_vv %.1e dE %.1e "
                          "rate %.1e (residual %.1e) worst %s\n",
                          b->name, (double)sim.data.t, rep.jacobian_q, rep.b_q, rep.b_qv,
                          rep.jacobian_v, rep.b_vv, rep.energy_gradient, rep.energy_rate,
                          rep.state_residual, rep.worst);
            assert_int_equal(st, BRAUN_OK);
            assert_true(rep.worst_value < 1e-7);
            if (b->sys.energy) assert_false(isnan(rep.energy_rate));
        }
        test_sim_close(&sim);
    }
}

/* Andrews' squeezing mechanism (stiff, a driving torque: energy input) at
 * its start and after 1 ms. */
static void test_andrews_passes(void **state)
{
    (void)state;
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &braun_andrews_system, BRAUN_CORRECT_POSITION |
                                                                    BRAUN_CORRECT_VELOCITY),
                     BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, braun_andrews_q0, braun_andrews_v0), BRAUN_OK);
    for (int s = 0; s < 2; s++) {
        if (s) assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-5, 1e-3, 0, NULL, NULL), BRAUN_OK);
        braun_callback_report rep;
        const int st = braun_check_callbacks(&braun_andrews_system, sim.data.t, sim.data.q, sim.data.v,
                                             0, &rep);
        print_message("andrews t = %.3f: A_q %.1e b_qv %.1e dE %.1e rate %.1e (residual %.1e) worst %s\n",
                      (double)sim.data.t, rep.jacobian_q, rep.b_qv, rep.energy_gradient,
                      rep.energy_rate, rep.state_residual, rep.worst);
        assert_int_equal(st, BRAUN_OK);
    }
    test_sim_close(&sim);
}

/* Every shipped scene (sparse systems among them: their compressed rows
 * scattered), at its start and after 0.37 s of the run the file asks for. */
static void test_scenes_pass(void **state)
{
    (void)state;
    static const char *const files[] = {
        "data/chain-5.json", "data/damped-motor.json", "data/double-pendulum.json",
        "data/driven-crank.json", "data/four-bar.json", "data/parallelogram-redundant.json",
        "data/pendulum.json", "data/sleigh.json", "data/slider-crank.json", "data/spatial-arm.json",
        "data/iftomm/a01-pendulum.json", "data/iftomm/a02-n-four-bar.json",
        "data/iftomm/a04-bricard.json", "data/iftomm/a05-flyball-governor.json"};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        char err[512];
        braun_scene_file *f = braun_scene_load(files[k], err, sizeof err);
        if (!f) fail_msg("%s", err);
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &f->sys, f->corrections), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        for (int s = 0; s < 2; s++) {
            if (s) assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-4, 0.37, 0, NULL, NULL), BRAUN_OK);
            braun_callback_report rep;
            const int st = braun_check_callbacks(&f->sys, sim.data.t, sim.data.q, sim.data.v, 0, &rep);
            print_message("%s t = %.2f: %s %.1e (energy rate %.1e, residual %.1e)\n", files[k],
                          (double)sim.data.t, rep.worst[0] ? rep.worst : "-", rep.worst_value,
                          rep.energy_rate, rep.state_residual);
            assert_int_equal(st, BRAUN_OK);
        }
        test_sim_close(&sim);
        braun_scene_free(f);
    }
}

/* The spatial scenes off the unit sphere of their Euler parameters: each
 * rigid3d's p scaled by λ = 1.01 and 0.97 and p' by λ, plus a radial part
 * 0.2 λ p, at the state after 0.37 s — where the corrections leave |p|² - 1
 * near round-off, the Runge–Kutta stages are off it by O(h²). M, the
 * forces' velocity products and dE/dq, dE/dv of the body's T (that of its
 * points' motion, homogeneous of degree 0 in (p, p')) pass there too. The
 * energy rate is judged on the constraints only (NaN here). */
static void test_spatial_off_sphere(void **state)
{
    (void)state;
    static const char *const files[] = {"data/spatial-arm.json", "data/iftomm/a04-bricard.json",
                                        "data/iftomm/a05-flyball-governor.json"};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        char err[512];
        braun_scene_file *f = braun_scene_load(files[k], err, sizeof err);
        if (!f) fail_msg("%s", err);
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &f->sys, f->corrections), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-4, 0.37, 0, NULL, NULL), BRAUN_OK);
        const braun_scene *sc = &f->scene;
        const double lambdas[2] = {1.01, 0.97};
        for (int l = 0; l < 2; l++) {
            double q[128], v[128];
            assert_true(sc->n <= 128);
            memcpy(q, sim.data.q, sizeof(double) * (size_t)sc->n);
            memcpy(v, sim.data.v, sizeof(double) * (size_t)sc->n);
            int scaled = 0;
            for (int b = 0; b < sc->nbodies; b++) {
                if (sc->bodies[b].kind != BRAUN_BODY_RIGID3D) continue;
                double *p = q + sc->bodies[b].iq + 3, *dp = v + sc->bodies[b].iq + 3;
                for (int c = 0; c < 4; c++) {
                    p[c] *= lambdas[l];
                    dp[c] = lambdas[l] * dp[c] + 0.2 * p[c];
                }
                scaled++;
            }
            assert_true(scaled > 0);
            braun_callback_report rep;
            const int st = braun_check_callbacks(&f->sys, sim.data.t, q, v, 0, &rep);
            print_message("%s off the sphere (%g): %s %.1e (dE %.1e)\n", files[k], lambdas[l],
                          rep.worst[0] ? rep.worst : "-", rep.worst_value, rep.energy_gradient);
            assert_int_equal(st, BRAUN_OK);
        }
        test_sim_close(&sim);
        braun_scene_free(f);
    }
}

/* The slider-crank with one quantity misprinted at a time (mode). */
static braun_system base;
static int mode;
static double factor;
static double sim_q0; /* q[0] of the checked state */

static int bad_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                         braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    if (mode == 6 && q[0] > sim_q0 + 1e-9) return -3; /* refuses the differences' points */
    int r = base.holonomic(t, q, v, phi, A, b, bv, u);
    if (mode == 1 && A) A[2 * 6 + 2] *= factor;   /* an entry of A_q */
    if (mode == 2 && bv) bv[2] *= factor;         /* the acceleration term */
    if (mode == 3 && b) b[4] = 0.5;               /* a b_q of a row without time */
    return r;
}

static int bad_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                      braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    int r = base.energy(t, q, v, E, dq, dv, dt, u);
    if (mode == 4 && dq) dq[4] *= factor;               /* a gradient entry */
    if (mode == 5) {                                    /* the law: V scaled, forces not */
        if (E) *E += (factor - 1) * 9.81 * (q[1] + q[4]);
        if (dq) { dq[1] *= factor; dq[4] *= factor; }
    }
    return r;
}

static void test_misprints_found(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("slider-crank");
    base = b->sys;
    braun_system s = base;
    s.holonomic = bad_holonomic;
    s.energy = bad_energy;
    /* A moving state on the constraints. */
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &base, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 0.37, 0, NULL, NULL), BRAUN_OK);
    const char *expect[6] = {NULL, "A_q[2][2]", "b_qv[2]", "b_q[4]", "dE_dq[4]", "energy rate"};
    sim_q0 = sim.data.q[0];
    const double slips[2] = {1e-2, 1e-4};
    for (int k = 0; k < 2; k++) {
        factor = 1 - slips[k];
        for (mode = 1; mode <= 5; mode++) {
            braun_callback_report rep;
            const int st = braun_check_callbacks(&s, sim.data.t, sim.data.q, sim.data.v, 0, &rep);
            print_message("slip %.0e, misprint %d: worst %s %.2e\n", slips[k], mode, rep.worst,
                          rep.worst_value);
            assert_int_equal(st, BRAUN_ERR_ARGUMENT);
            assert_string_equal(rep.worst, expect[mode]);
            assert_true(rep.worst_value > 0.1 * slips[k]);
        }
    }
    /* None: the same state passes. */
    mode = 0;
    braun_callback_report rep;
    assert_int_equal(braun_check_callbacks(&s, sim.data.t, sim.data.q, sim.data.v, 0, &rep), BRAUN_OK);
    /* Off the constraints the energy rate is not judged. */
    braun_real q[6];
    memcpy(q, sim.data.q, sizeof q);
    q[0] += 1e-3;
    assert_int_equal(braun_check_callbacks(&s, sim.data.t, q, sim.data.v, 0, &rep), BRAUN_OK);
    assert_true(isnan(rep.energy_rate) && rep.state_residual > 1e-4);
    /* A state that is not finite; a callback that refuses a point. */
    q[2] = NAN;
    assert_int_equal(braun_check_callbacks(&s, 0, q, sim.data.v, 0, &rep), BRAUN_ERR_NONFINITE);
    assert_string_equal(rep.worst, "state q[2]");
    q[2] = 0.3;
    mode = 6;
    assert_int_equal(braun_check_callbacks(&s, 0, q, sim.data.v, 0, &rep), BRAUN_ERR_CALLBACK);
    assert_non_null(strstr(rep.worst, "holonomic callback returned -3"));
    mode = 0;
    /* Bad arguments: rep->worst says which (it was left unwritten). */
    memset(&rep, 0x55, sizeof rep);
    assert_int_equal(braun_check_callbacks(NULL, 0, q, q, 0, &rep), BRAUN_ERR_ARGUMENT);
    assert_string_equal(rep.worst, "system (NULL)");
    memset(&rep, 0x55, sizeof rep);
    assert_int_equal(braun_check_callbacks(&s, 0, NULL, q, 0, &rep), BRAUN_ERR_ARGUMENT);
    assert_string_equal(rep.worst, "state q (NULL)");
    assert_int_equal(braun_check_callbacks(&s, 0, q, NULL, 0, &rep), BRAUN_ERR_ARGUMENT);
    assert_string_equal(rep.worst, "state v (NULL)");
    assert_int_equal(braun_check_callbacks(&s, 0, q, q, 0, NULL), BRAUN_ERR_ARGUMENT);
    test_sim_close(&sim);
}

/* A V-shaped potential c|q| (one coordinate, unit mass): at q = 0 its
 * gradient jumps from −c to c, as a torsion3d's at its rest angle ± π. The
 * callback gives the slope from above there (kink_slope = 1), which the
 * check takes with a note; a slope that is neither side (0.5) is still a
 * wrong callback. check said "no (dE_dq[6])" for the torsion3d. */
static double kink_slope = 1;
static int kink_mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    (void)t; (void)q; (void)user;
    M[0] = 1;
    return 0;
}
static int kink_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *user)
{
    (void)t; (void)v; (void)user;
    Q[0] = -3 * (q[0] >= 0 ? 1 : -1);
    return 0;
}
static int kink_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                       braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    (void)t; (void)user;
    *E = 0.5 * v[0] * v[0] + 3 * fabs(q[0]);
    if (!dE_dq) return 0; /* the energy alone (docs/api.md) */
    dE_dq[0] = q[0] == 0 ? 3 * kink_slope : 3 * (q[0] > 0 ? 1 : -1);
    dE_dv[0] = v[0];
    *dE_dt = 0;
    return 0;
}

static void test_kink_noted(void **state)
{
    (void)state;
    braun_system s = {0};
    s.n = 1;
    s.flags = BRAUN_MASS_CONSTANT;
    s.mass = kink_mass;
    s.forces = kink_forces;
    s.energy = kink_energy;
    const braun_real q0[1] = {0}, v0[1] = {0}, q1[1] = {0.5};
    braun_callback_report rep;
    kink_slope = 1;
    assert_int_equal(braun_check_callbacks(&s, 0, q0, v0, 0, &rep), BRAUN_OK);
    print_message("kink: %s\n", rep.note);
    assert_non_null(strstr(rep.note, "dE_dq[0] is not differentiable at this state"));
    assert_non_null(strstr(rep.note, "from below -3, from above 3; the callback gives 3"));
    kink_slope = -1; /* the other side: a kink too */
    assert_int_equal(braun_check_callbacks(&s, 0, q0, v0, 0, &rep), BRAUN_OK);
    assert_true(rep.note[0] != '\0');
    kink_slope = 0.5; /* neither side: wrong */
    assert_int_equal(braun_check_callbacks(&s, 0, q0, v0, 0, &rep), BRAUN_ERR_ARGUMENT);
    assert_string_equal(rep.worst, "dE_dq[0]");
    assert_true(rep.note[0] == '\0');
    /* Away from the kink: no note. */
    kink_slope = 1;
    assert_int_equal(braun_check_callbacks(&s, 0, q1, v0, 0, &rep), BRAUN_OK);
    assert_true(rep.note[0] == '\0');
}


/* Callback outputs that are not finite at the state: each named as such,
 * output and entry, with BRAUN_ERR_NONFINITE, with or without an energy law
 * (without one an Inf column of A_vv passed as "within the round-off", a
 * NaN Φ_v was reported as A_vv[2] with BRAUN_ERR_ARGUMENT). A knife edge
 * (n = 3, p = 1) and a rod (n = 2, m = 1). */
static int bad_out; /* which output is spoilt (0: none) */
static double bad_value;
static int nf_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    memset(M, 0, 9 * sizeof *M);
    M[0] = M[4] = 1;
    M[8] = 0.1;
    if (bad_out == 7) M[4] = bad_value;
    return 0;
}
static int nf_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = Q[1] = Q[2] = 0;
    if (bad_out == 8) Q[2] = bad_value;
    return 0;
}
static int nf_knife(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                    braun_real *A, braun_real *bv, void *u)
{
    (void)t; (void)u;
    const double c = cos(q[2]), s = sin(q[2]);
    if (phi) phi[0] = -s * v[0] + c * v[1] - 0.5 * v[2];
    if (A) { A[0] = -s; A[1] = c; A[2] = -0.5; }
    if (bv) bv[0] = (c * v[0] + s * v[1]) * v[2];
    if (bad_out == 1 && phi) phi[0] = bad_value;
    if (bad_out == 2 && A) A[1] = bad_value;
    if (bad_out == 3 && bv) bv[0] = bad_value;
    return 0;
}
static int nf_rod(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                  braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)u;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - 1;
    if (A) { A[0] = 2 * q[0]; A[1] = 2 * q[1]; A[2] = 0; }
    if (b) b[0] = 0;
    if (bv) bv[0] = -2 * (v[0] * v[0] + v[1] * v[1]);
    if (bad_out == 4 && A) A[1] = bad_value;
    if (bad_out == 5 && b) b[0] = bad_value;
    if (bad_out == 6 && phi) phi[0] = bad_value;
    return 0;
}
static int nf_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                     braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    (void)t; (void)q; (void)u;
    const double Md[3] = {1, 1, 0.1};
    double e = 0;
    for (int i = 0; i < 3; i++) {
        e += 0.5 * Md[i] * v[i] * v[i];
        if (dv) dv[i] = Md[i] * v[i];
        if (dq) dq[i] = 0;
    }
    if (E) *E = e;
    if (dt) *dt = 0;
    if (bad_out == 9 && dq) dq[1] = bad_value;
    return 0;
}

static void test_nonfinite_named(void **state)
{
    (void)state;
    static const char *const expect[10] = {
        NULL, "Phi_v[0] is %s (nonholonomic callback at t = 0)",
        "A_vv[0][1] is %s (nonholonomic callback at t = 0)", "b_vv[0] is %s (nonholonomic callback at t = 0)",
        "A_q[0][1] is %s (holonomic callback at t = 0)", "b_q[0] is %s (holonomic callback at t = 0)",
        "Phi_q[0] is %s (holonomic callback at t = 0)", "M[1][1] is %s (mass callback at t = 0)",
        "Q[2] is %s (forces callback at t = 0)", "dE_dq[1] is %s (energy callback at t = 0)"};
    static const double values[3] = {INFINITY, -INFINITY, NAN};
    static const char *const said[3] = {"+Inf", "-Inf", "NaN"};
    const braun_real q0[3] = {0.6, -0.8, 0.3}, v0[3] = {1, 0.5, 1};
    for (int law = 0; law < 2; law++)
        for (bad_out = 1; bad_out <= 9; bad_out++)
            for (int k = 0; k < 3; k++) {
                if (bad_out == 9 && !law) continue;
                bad_value = values[k];
                /* Rows of both kinds: the knife on the plane, the rod's row
                 * on q[0], q[1]. */
                braun_system s = {0};
                s.n = 3;
                s.m = 1;
                s.p = 1;
                s.flags = BRAUN_MASS_CONSTANT;
                s.mass = nf_mass;
                s.forces = nf_forces;
                s.holonomic = nf_rod;
                s.nonholonomic = nf_knife;
                s.energy = law ? nf_energy : NULL;
                braun_callback_report rep;
                const int st = braun_check_callbacks(&s, 0, q0, v0, 0, &rep);
                char want[160];
                snprintf(want, sizeof want, expect[bad_out], said[k]);
                print_message("law %d, output %d = %s: %d %s\n", law, bad_out, said[k], st, rep.worst);
                assert_int_equal(st, BRAUN_ERR_NONFINITE);
                assert_string_equal(rep.worst, want);
            }
    bad_out = 0;
}


/* A ball (radius 0.2 m) rolling on a turntable turning at W: the contact
 * rows v − Rω + W×r have a term without v, whose ideal force does work.
 * Declared BRAUN_SCLERONOMIC that work is dropped and the energy law is
 * wrong (the run went 1 m astray): the check names the row and the value
 * of Φ_v − A_vv v. Without the flag, or with W = 0, it passes. */
static double table_w;
static int ball_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    const double I = 0.4 * 1.5 * 0.04;
    memset(M, 0, 25 * sizeof *M);
    M[0] = M[6] = 1.5;
    M[12] = M[18] = M[24] = I;
    return 0;
}
static int ball_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    for (int i = 0; i < 5; i++) Q[i] = 0;
    return 0;
}
static int ball_rows(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                     braun_real *A, braun_real *bv, void *u)
{
    (void)t; (void)u;
    const double R = 0.2, W = table_w;
    if (phi) {
        phi[0] = v[0] - R * v[3] + W * q[1];
        phi[1] = v[1] + R * v[2] - W * q[0];
    }
    if (A) {
        const double a[10] = {1, 0, 0, -R, 0, 0, 1, R, 0, 0};
        for (int i = 0; i < 10; i++) A[i] = a[i];
    }
    if (bv) {
        bv[0] = -W * v[1];
        bv[1] = W * v[0];
    }
    return 0;
}

static void test_scleronomic_homogeneous(void **state)
{
    (void)state;
    braun_system s = {0};
    s.n = 5;
    s.p = 2;
    s.mass = ball_mass;
    s.forces = ball_forces;
    s.nonholonomic = ball_rows;
    const braun_real q0[5] = {0.5, 0.1, 0, 0, 0};
    braun_callback_report rep;
    for (int k = 0; k < 2; k++) {
        table_w = k ? 0 : 3;
        /* On the constraints: ω from the contact rows. */
        const braun_real v0[5] = {0.3, -0.4, (table_w * 0.5 + 0.4) / 0.2, (0.3 + table_w * 0.1) / 0.2, 2};
        s.flags = BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC;
        const int st = braun_check_callbacks(&s, 0, q0, v0, 0, &rep);
        print_message("turntable W = %g, scleronomic: %d %s (%.3g)\n", table_w, st, rep.worst,
                      rep.homogeneous_v);
        if (table_w > 0) {
            assert_int_equal(st, BRAUN_ERR_ARGUMENT);
            assert_string_equal(rep.worst, "Phi_v[1] - A_vv[1] v = -1.5 at this state: BRAUN_SCLERONOMIC "
                                           "needs each nonholonomic row homogeneous in v");
            assert_true(rep.homogeneous_v > 0.5 && rep.worst_value == rep.homogeneous_v);
        } else {
            assert_int_equal(st, BRAUN_OK);
            assert_true(rep.homogeneous_v == 0);
        }
        /* Without the flag the term is the core's to account for. */
        s.flags = BRAUN_MASS_CONSTANT;
        assert_int_equal(braun_check_callbacks(&s, 0, q0, v0, 0, &rep), BRAUN_OK);
        assert_true(rep.homogeneous_v == 0);
    }
}


/* Correct scenes where something is large — an unrelated body far away, a
 * bob far from its cord's anchor, a drive's phase or angle of 1e12, the
 * time — pass; the same scenes with b_q or b_qv off by slip are still
 * caught. The step along the motion was the largest coordinate's for all
 * coordinates and time (a particle at 1e6 m moved the bob and the sine
 * drive's time by 6: "b_qv[0] off by 0.81"), and the differences in t were
 * never larger than time's own step (an angle 1e12 + t is the same at
 * t ± 6e-6: "b_q[5] off by 1"). */
static braun_system far_base;
static int far_which, far_row; /* 1: b_q, 2: b_qv of far_row, off by far_slip */
static double far_slip;
static int far_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                         braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const int r = far_base.holonomic(t, q, v, phi, A, b, bv, u);
    if (far_which == 1 && b) b[far_row] *= 1 - far_slip;
    if (far_which == 2 && bv) bv[far_row] *= 1 - far_slip;
    return r;
}

static void test_large_scales(void **state)
{
    (void)state;
    static const char *const rev3d =
        "{\"name\": \"arm\", \"ground\": {\"points\": {\"pivot\": [0, 0, 0], \"anchor\": [1.5, -1, 0.5]}},"
        " \"bodies\": [{\"name\": \"arm\", \"type\": \"rigid3d\", \"mass\": 1, \"inertia\": [0.0017, 0.084,"
        " 0.084], \"position\": [0.5, 0, 0], \"points\": {\"root\": [-0.5, 0, 0], \"tip\": [0.5, 0, 0]}},"
        " {\"name\": \"bob\", \"type\": \"rigid3d\", \"mass\": 0.5, \"inertia\": [0.0008, 0.042, 0.042],"
        " \"position\": [1, -0.5, 0], \"orientation\": [0.7071067811865476, 0, 0, -0.7071067811865476],"
        " \"velocity\": [0, 0, 1], \"omega\": [-2, 0, 0], \"points\": {\"top\": [-0.5, 0, 0], \"end\":"
        " [0.5, 0, 0]}}], \"joints\": [{\"name\": \"hinge\", \"type\": \"revolute3d\", \"a\": \"arm.root\","
        " \"b\": \"ground.pivot\", \"axis\": [0, 0, 1], \"drive\": {\"type\": \"linear\", \"value\": %s,"
        " \"rate\": 1}}, {\"name\": \"ball\", \"type\": \"spherical\", \"a\": \"arm.tip\", \"b\": \"bob.top\"}],"
        " \"effects\": [{\"type\": \"gravity\", \"g\": [0, -9.81, 0]}, {\"type\": \"spring\", \"a\":"
        " \"bob.end\", \"b\": \"ground.anchor\", \"stiffness\": 20, \"damping\": 0.1}]}";
    static const char *const cord =
        "{\"name\": \"far\", \"bodies\": [{\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1,"
        " \"position\": [0, %s], \"velocity\": [%s, -0.5]}, {\"name\": \"free\", \"type\": \"particle\","
        " \"mass\": 1, \"position\": [%s, 0]}], \"joints\": [{\"name\": \"cord\", \"type\": \"distance\","
        " \"a\": [0, -9], \"b\": \"bob\", \"drive\": {\"type\": \"sine\", \"offset\": 1, \"amplitude\":"
        " 0.5, \"omega\": 1, \"phase\": %s}}]}";
    static const struct {
        const char *bob_y, *free_x, *phase, *angle; /* angle: the rev3d scene */
        const char *vx;
        double t;
        int row;
        double catch_b, catch_bv; /* the smallest slip of b_q, b_qv caught (0: none can be:
                                   * the bob 1e6 from its anchor, Φ's rounding beyond
                                   * the drive's change; t = 1e12, resolved to 1e-4 s) */
    } cases[] = {
        {"-10", "1e3", "0", NULL, "0.3", 0, 0, 1e-4, 1e-4},   {"-10", "1e6", "0", NULL, "0.3", 0, 0, 1e-4, 1e-4},
        {"-10", "1e9", "0", NULL, "0.3", 0, 0, 1e-4, 1e-4},   {"-10", "1e12", "0", NULL, "0.3", 0, 0, 1e-4, 1e-4},
        {"1e6", "0", "0", NULL, "0.3", 0, 0, 0, 0},           {"-10", "0", "1e12", NULL, "0.3", 0, 0, 1e-2, 0},
        {"-10", "1e6", "0", NULL, "0.3", 1e6, 0, 1e-4, 1e-4}, {"-10", "0", "0", NULL, "0.3", 1e9, 0, 1e-2, 1e-4},
        {"-10", "1e6", "0.3", NULL, "0.3", 1e12, 0, 0, 0},    {NULL, NULL, NULL, "1e12", "0.3", 0, 5, 1e-2, 1e-2},
        {NULL, NULL, NULL, "1e6", "0.3", 0, 5, 1e-4, 1e-4},   {NULL, NULL, NULL, "0", "0.3", 1e9, 5, 1e-2, 1e-2},
        /* as found: the bob moving along its cord, b_qv 0 there */
        {"-10", "1e6", "0", NULL, "0", 0, 0, 1e-4, 0}, {"1e6", "0", "0", NULL, "0", 0, 0, 0, 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char text[2048], err[512];
        if (cases[c].angle) snprintf(text, sizeof text, rev3d, cases[c].angle);
        else snprintf(text, sizeof text, cord, cases[c].bob_y, cases[c].vx, cases[c].free_x, cases[c].phase);
        braun_scene_file *f = braun_scene_load_text(NULL, text, strlen(text), err, sizeof err);
        if (!f) fail_msg("case %zu: %s", c, err);
        far_base = f->sys;
        braun_system s = f->sys;
        s.holonomic = far_holonomic;
        far_row = cases[c].row;
        for (far_which = 0; far_which <= 2; far_which++) {
            const double slips[2] = {1e-2, 1e-4};
            for (int k = 0; k < (far_which ? 2 : 1); k++) {
                far_slip = slips[k];
                braun_callback_report rep;
                const int st = braun_check_callbacks(&s, (braun_real)cases[c].t, f->q0, f->v0, 0, &rep);
                print_message("case %zu (t = %g), %s off by %g: %d %s %.2e\n", c, cases[c].t,
                              far_which == 0 ? "nothing" : far_which == 1 ? "b_q" : "b_qv",
                              far_which ? far_slip : 0, st, rep.worst, rep.worst_value);
                const double catch_at = far_which == 1 ? cases[c].catch_b : cases[c].catch_bv;
                if (far_which == 0) assert_int_equal(st, BRAUN_OK);
                else if (catch_at > 0 && far_slip >= catch_at) {
                    char want[16];
                    snprintf(want, sizeof want, "%s[%d]", far_which == 1 ? "b_q" : "b_qv", far_row);
                    assert_int_equal(st, BRAUN_ERR_ARGUMENT);
                    assert_string_equal(rep.worst, want);
                }
            }
        }
        braun_scene_free(f);
    }
    far_which = 0;
}

/* Small mechanisms: the steps follow the scene's own lengths
 * (braun_scene_coordinate_sizes). Stepped by 6e-6 m (a floor of 1 m), the
 * shipped spatial-arm scaled to 1e-6 m failed at dE_dq[7] and a rigid3d on
 * a spring at its rest length at 1e-7 m at dE_dq[0] ("off by 1"), while
 * their runs matched the unit ones to 1e-13. Scaled by L (masses by M, so
 * that every number is within the scene limits) they pass at the start
 * and moving; a misprint of 1e-4 is caught at every scale; the sizes of
 * the lengths are L times those at 1 m, the Euler parameters' 1. */
static braun_system small_base;
/* Off by small_slip: 1 A_q's column 7 (bob's x), 2 b_qv[6] (a point row),
 * 3 b_qv[9] (the bob's unit quaternion row), 4 A_q[5][small_col] (a point
 * row, the bob's largest Euler-parameter column there), 5 dE_dq[8] (bob's
 * y), 6 dE_dq[10] (its e0). */
static int small_which, small_col;
static double small_slip;
static int small_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                           braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const int r = small_base.holonomic(t, q, v, phi, A, b, bv, u);
    for (int i = 0; i < small_base.m && small_which == 1 && A; i++) A[(size_t)i * small_base.n + 7] *= 1 - small_slip;
    if (small_which == 2 && bv) bv[6] *= 1 - small_slip;
    if (small_which == 3 && bv) bv[9] *= 1 - small_slip;
    if (small_which == 4 && A) A[5 * small_base.n + small_col] *= 1 - small_slip;
    return r;
}
static int small_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                        braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    const int r = small_base.energy(t, q, v, E, dq, dv, dt, u);
    if (small_which == 5 && dq) dq[8] *= 1 - small_slip;
    if (small_which == 6 && dq) dq[10] *= 1 - small_slip;
    return r;
}

/* The spatial-arm (data/spatial-arm.json) with lengths times L, masses
 * times M. */
static braun_scene_file *scaled_arm(double L, double M)
{
    char text[3072], err[512];
    const double I = M * L * L;
    snprintf(text, sizeof text,
             "{\"name\": \"arm\", \"ground\": {\"points\": {\"pivot\": [0, 0, 0], \"anchor\": [%.17g, %.17g, "
             "%.17g]}}, \"bodies\": [{\"name\": \"arm\", \"type\": \"rigid3d\", \"mass\": %.17g, \"inertia\": "
             "[%.17g, %.17g, %.17g], \"position\": [%.17g, 0, 0], \"points\": {\"root\": [%.17g, 0, 0], "
             "\"tip\": [%.17g, 0, 0]}}, {\"name\": \"bob\", \"type\": \"rigid3d\", \"mass\": %.17g, "
             "\"inertia\": [%.17g, %.17g, %.17g], \"position\": [%.17g, %.17g, 0], \"orientation\": "
             "[0.70710678118654757, 0, 0, -0.70710678118654757], \"velocity\": [0, 0, %.17g], \"omega\": "
             "[-2, 0, 0], \"points\": {\"top\": [%.17g, 0, 0], \"end\": [%.17g, 0, 0]}}], \"joints\": "
             "[{\"name\": \"hinge\", \"type\": \"revolute3d\", \"a\": \"arm.root\", \"b\": \"ground.pivot\", "
             "\"axis\": [0, 0, 1]}, {\"name\": \"ball\", \"type\": \"spherical\", \"a\": \"arm.tip\", \"b\": "
             "\"bob.top\"}], \"effects\": [{\"type\": \"gravity\", \"g\": [0, %.17g, 0]}, {\"name\": "
             "\"cord\", \"type\": \"spring\", \"a\": \"bob.end\", \"b\": \"ground.anchor\", \"stiffness\": "
             "%.17g, \"damping\": %.17g}, {\"name\": \"coil\", \"type\": \"torsion3d\", \"joint\": "
             "\"hinge\", \"stiffness\": %.17g, \"damping\": %.17g}]}",
             1.5 * L, -L, 0.5 * L, M, 0.0016666666666666668 * I, 0.084166666666666667 * I,
             0.084166666666666667 * I, 0.5 * L, -0.5 * L, 0.5 * L, 0.5 * M, 0.00083333333333333339 * I,
             0.042083333333333334 * I, 0.042083333333333334 * I, L, -0.5 * L, L, -0.5 * L, 0.5 * L,
             -9.81 * L, 20 * M, 0.1 * M, 5 * I, 0.2 * I);
    braun_scene_file *f = braun_scene_load_text(NULL, text, strlen(text), err, sizeof err);
    if (!f) fail_msg("arm at L = %g: %s", L, err);
    return f;
}

static void test_small_scales(void **state)
{
    (void)state;
    static const double scale[4][2] = {{1, 1}, {1e-6, 1}, {1e-6, 1e-18}, {1e6, 1e-6}};
    braun_real size1[14];
    double figure1[2][7]; /* at 1 m: the same at every scale */
    for (int c = 0; c < 4; c++) {
        const double L = scale[c][0];
        braun_scene_file *f = scaled_arm(L, scale[c][1]);
        assert_int_equal(f->sys.n, 14);
        braun_real size[14];
        assert_int_equal(braun_scene_coordinate_sizes(&f->scene, f->q0, size), BRAUN_OK);
        if (c == 0) memcpy(size1, size, sizeof size);
        for (int k = 0; k < 14; k++) {
            /* x, y, z of each body are lengths; its Euler parameters are not. */
            const double want = k % 7 < 3 ? L * (double)size1[k] : 1;
            assert_true(fabs((double)size[k] - want) <= 1e-12 * want);
        }
        small_base = f->sys;
        braun_system s = f->sys;
        s.holonomic = small_holonomic;
        s.energy = small_energy;
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &f->sys, f->corrections), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        for (int at = 0; at < 2; at++) {
            if (at) assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-4, 0.37, 0, NULL, NULL), BRAUN_OK);
            assert_int_equal(braun_scene_coordinate_sizes(&f->scene, sim.data.q, size), BRAUN_OK);
            braun_real phi[10], A[140] = {0}, bq[10], bv[10]; /* A: the callback adds into it */
            assert_int_equal(f->sys.holonomic(sim.data.t, sim.data.q, sim.data.v, phi, A, bq, bv, f->sys.user), 0);
            small_col = 10;
            for (int k = 11; k < 14; k++)
                if (fabs((double)A[5 * 14 + k]) > fabs((double)A[5 * 14 + small_col])) small_col = k;
            char entry[16];
            snprintf(entry, sizeof entry, "A_q[5][%d]", small_col);
            for (small_which = 0; small_which <= 6; small_which++) {
                small_slip = 1e-4;
                braun_callback_report rep;
                const int st = braun_check_callbacks_sized(&s, sim.data.t, sim.data.q, sim.data.v, size, 0, &rep);
                print_message("arm L = %g, M = %g, t = %.2f, misprint %d: %d %s %.2e\n", L, scale[c][1],
                              (double)sim.data.t, small_which, st, rep.worst, rep.worst_value);
                if (small_which == 0) {
                    assert_int_equal(st, BRAUN_OK);
                    assert_false(isnan(rep.energy_rate));
                    continue;
                }
                const char *const named[7] = {NULL, "A_q[", "b_qv[6]", "b_qv[9]", entry, "dE_dq[8]", "dE_dq[10]"};
                assert_int_equal(st, BRAUN_ERR_ARGUMENT);
                assert_true(strncmp(rep.worst, named[small_which], strlen(named[small_which])) == 0);
                if (c == 0) figure1[at][small_which] = rep.worst_value;
                assert_true(fabs(rep.worst_value / figure1[at][small_which] - 1) < 0.01);
                /* (dE_dq[10] is small beside the gradient's lengths.) */
                assert_true(rep.worst_value > (small_which == 6 ? 1e-3 : 0.1) * small_slip);
            }
        }
        small_which = 0;
        test_sim_close(&sim);
        braun_scene_free(f);
    }
    /* A rigid3d on a spring at its rest length, 1e-7 m and 1 m. */
    for (int c = 0; c < 2; c++) {
        const double L = c ? 1 : 1e-7;
        char text[1024], err[512];
        snprintf(text, sizeof text,
                 "{\"name\": \"spring3d\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid3d\", \"mass\": 1, "
                 "\"inertia\": [%.17g, %.17g, %.17g], \"position\": [%.17g, %.17g, %.17g], \"velocity\": "
                 "[%.17g, %.17g, %.17g], \"points\": {\"e\": [%.17g, 0, 0]}}], \"effects\": [{\"type\": "
                 "\"spring\", \"a\": [0, 0, 0], \"b\": \"b.e\", \"stiffness\": 10, \"damping\": 0.5}, "
                 "{\"type\": \"gravity\", \"g\": [0, %.17g, 0]}]}",
                 0.1 * L * L, 0.1 * L * L, 0.1 * L * L, 0.6 * L, 0.8 * L, 0.3 * L, 0.3 * L, -0.2 * L, 0.1 * L,
                 0.5 * L, -9.81 * L);
        braun_scene_file *f = braun_scene_load_text(NULL, text, strlen(text), err, sizeof err);
        if (!f) fail_msg("spring3d at L = %g: %s", L, err);
        braun_real size[7];
        assert_int_equal(braun_scene_coordinate_sizes(&f->scene, f->q0, size), BRAUN_OK);
        braun_callback_report rep;
        const int st = braun_check_callbacks_sized(&f->sys, 0, f->q0, f->v0, size, 0, &rep);
        print_message("spring3d L = %g: %d %s %.2e (size %g, %g)\n", L, st, rep.worst, rep.worst_value,
                      (double)size[0], (double)size[3]);
        assert_int_equal(st, BRAUN_OK);
        /* A size that is no size is refused, named. */
        size[3] = 0;
        assert_int_equal(braun_check_callbacks_sized(&f->sys, 0, f->q0, f->v0, size, 0, &rep), BRAUN_ERR_ARGUMENT);
        assert_string_equal(rep.worst, "size[3] (must be finite and > 0)");
        braun_scene_free(f);
    }
    braun_real q[1] = {0}, out[1];
    assert_int_equal(braun_scene_coordinate_sizes(NULL, q, out), BRAUN_ERR_ARGUMENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builtins_pass),
        cmocka_unit_test(test_andrews_passes),
        cmocka_unit_test(test_scenes_pass),
        cmocka_unit_test(test_spatial_off_sphere),
        cmocka_unit_test(test_misprints_found),
        cmocka_unit_test(test_kink_noted),
        cmocka_unit_test(test_nonfinite_named),
        cmocka_unit_test(test_scleronomic_homogeneous),
        cmocka_unit_test(test_large_scales),
        cmocka_unit_test(test_small_scales),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
