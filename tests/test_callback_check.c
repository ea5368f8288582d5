/* braun_check_callbacks (host tier): the built-in models pass at their
 * initial states and along their motion; a misprint in each checked
 * quantity is found and named. The misprints are the kind the corrections
 * hide: the library runs them with status 0. */
#include <math.h>
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builtins_pass),
        cmocka_unit_test(test_andrews_passes),
        cmocka_unit_test(test_scenes_pass),
        cmocka_unit_test(test_misprints_found),
        cmocka_unit_test(test_kink_noted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
