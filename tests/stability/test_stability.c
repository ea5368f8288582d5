/* Stability suite: hard cases stay numerically stable. Compiled twice, for
 * braun_real = double and float (-DBRAUN_SINGLE), with bounds per precision
 * a small factor (2-4) above the values measured on x86-64, gcc 12, -O2,
 * noted beside them as "measured double / float" (docs/robustness.md lists
 * them too). BRAUN_STRESS=1 in the environment selects the long forms (make
 * stress). */
#include "test_util.h"
#include "braun_host.h"
#include "braun_reference.h"

#ifdef BRAUN_SINGLE
#define PREC(d, f) (f)
#else
#define PREC(d, f) (d)
#endif

static int stress(void)
{
    const char *s = getenv("BRAUN_STRESS");
    return s && *s && *s != '0';
}

typedef struct monitor {
    const braun_builtin *model;
    braun_reference ref;
    int with_ref;
    double maxpos, maxvel, maxE, maxtraj, maxpoint;
    int nonfinite;
} monitor;

static int monitor_out(const braun_data *d, void *u)
{
    monitor *mo = u;
    braun_real p, v, e;
    /* A failed residual (Inf energy) is recorded, not fatal: the solver must
     * then report the divergence itself. */
    if (braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, &v, &e) != BRAUN_OK) {
        mo->nonfinite = 1;
        return 0;
    }
    if (!isfinite((double)p) || !isfinite((double)v) || !isfinite((double)e)) mo->nonfinite = 1;
    mo->maxpos = fmax(mo->maxpos, (double)p);
    mo->maxvel = fmax(mo->maxvel, (double)v);
    mo->maxE = fmax(mo->maxE, (double)e);
    if (mo->with_ref) {
        double qr[BRAUN_MODEL_MAX_N], vr[BRAUN_MODEL_MAX_N], s = 0;
        braun_reference_eval(&mo->ref, (double)d->t, qr, vr);
        for (int i = 0; i < mo->model->sys.n; i++)
            s += ((double)d->q[i] - qr[i]) * ((double)d->q[i] - qr[i]);
        mo->maxtraj = fmax(mo->maxtraj, sqrt(s));
        if (mo->model->point_x >= 0) {
            double dx = (double)d->q[mo->model->point_x] - qr[mo->model->point_x];
            double dy = (double)d->q[mo->model->point_y] - qr[mo->model->point_y];
            mo->maxpoint = fmax(mo->maxpoint, sqrt(dx * dx + dy * dy));
        }
    }
    return 0;
}

/* Run a built-in model from (q0, v0) (NULL: the paper's state). */
static int run(const char *name, const braun_real *q0, const braun_real *v0, unsigned corr,
               double h, double T, int with_ref, monitor *mo, braun_stats *stats)
{
    const braun_builtin *b = braun_builtin_find(name);
    assert_non_null(b);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, corr), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0 ? q0 : b->q0, v0 ? v0 : b->v0), BRAUN_OK);
    memset(mo, 0, sizeof *mo);
    mo->model = b;
    mo->with_ref = with_ref;
    if (with_ref) assert_int_equal(braun_reference_init(&mo->ref, b, 1e-4), 0);
    int st = braun_integrate(&sim.data, BRAUN_RK4, (braun_real)h, (braun_real)T, 1, monitor_out, mo);
    if (stats) *stats = sim.data.stats;
    test_sim_close(&sim);
    return st;
}

/* Smaller steps, smaller errors (issue 12): the four-bar through its
 * singular configurations, RK4 at h = 1e-2 ... 2.5e-4 over 100 s (1000 s
 * under stress). The energy law holds to its round-off floor at every h
 * (the energy force is sized at each step's end; sized at its start the
 * max |Phi_e| over 1000 s was 4.3e-7, 2.3e-8, 3.0e-8, 2.9e-8), and the
 * trajectory error against the closed form falls as h does. */
static void test_four_bar_in_h(void **state)
{
    (void)state;
    /* float: 100 s also under stress — at 1000 s a step of 2.5e-4 is 4 ulps
     * of t, beyond the float horizon (BRAUN_ERR_TIME_RESOLUTION) */
    const double T = stress() ? PREC(1e3, 1e2) : 1e2;
    const double hs[4] = {1e-2, 1e-3, 5e-4, 2.5e-4};
    double traj[4];
    for (int i = 0; i < 4; i++) {
        monitor mo;
        assert_int_equal(run("four-bar", NULL, NULL, BRAUN_CORRECT_ALL, hs[i], T, 1, &mo, NULL), BRAUN_OK);
        print_message("four-bar h=%g T=%g: |Phi_q| %.3g |Phi_e| %.3g traj %.3g\n", hs[i], T, mo.maxpos,
                      mo.maxE, mo.maxtraj);
        assert_false(mo.nonfinite);
        /* double: E ~ 70 J, floor 4 eps (|E| + |E0|) ~ 1.2e-13 (measured
         * 5.7e-14 ... 1.1e-13 over 1000 s); float: measured 4.6e-5 */
        assert_le(mo.maxE, PREC(2e-13, 2e-4));
        traj[i] = mo.maxtraj;
#ifndef BRAUN_SINGLE
        /* Over 1000 s (the horizon; measured 5.4e-4, 5.5e-8,
         * 2.8e-8, 1.6e-8); over 100 s it is not monotone: 5.4e-5, 8.7e-9,
         * 1.2e-8 — a velocity-level kick at a singular crossing, not the
         * energy, decides the last digits there (docs/method.md). */
        if (i > 0 && stress()) assert_true(traj[i] < traj[i - 1]);
#else
        (void)traj;
#endif
    }
}

/* The four-bar through its singular configurations (all links horizontal,
 * rank 5 -> 3, twice per revolution): 1000 s (10^4 s under stress). */
static void test_four_bar_long(void **state)
{
    (void)state;
    monitor mo;
    const double T = stress() ? 1e4 : 1e3;
    assert_int_equal(run("four-bar", NULL, NULL, BRAUN_CORRECT_ALL, 1e-2, T, 1, &mo, NULL), BRAUN_OK);
    print_message("four-bar h=1e-2 T=%g: |Phi_q| %.3g |Phi_v| %.3g |Phi_e| %.3g eps3 %.3g\n", T,
                  mo.maxpos, mo.maxvel, mo.maxE, mo.maxpoint);
    assert_false(mo.nonfinite);
    /* measured 1.19e-8 / 5.63e-5, 5.68e-14 / 4.58e-5, 3.14e-4 / 1.13e-3;
     * 10^4 s: 3.9e-8 / 1.6e-4, 6.4e-14 / 4.6e-5, 3.1e-3 / 9.3e-3. With
     * the energy force sized at the step's start |Phi_e| was 1.0e-6 /
     * 2.0e-2: the double bound is the round-off floor of Phi_e (E ~ 70 J). */
    assert_le(mo.maxpos, PREC(4e-7, 2e-4));
    assert_le(mo.maxE, PREC(2e-13, 2e-4));
    assert_le(mo.maxpoint, stress() ? PREC(1e-2, 3e-2) : PREC(1e-3, 3e-3));
}

/* Started exactly at a singular configuration (all links horizontal, rank
 * 3 of 5). The acceleration-level equations cannot tell the branches apart
 * there, so the first step's error is O(h^2) instead of O(h^5) (measured:
 * |Φ_e| 9.5e-5 at h = 1e-2, 1.2e-6 at h = 1e-3); the corrections remove it
 * and the run then holds the same bounds as any other. */
static void test_four_bar_at_singularity(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("four-bar");
    const braun_real q0[6] = {1, 0, 2, 0, 3, 0}, v0[6] = {0, 1, 0, 1, 0, 1};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    const double h = 1e-2;
    braun_real p, v, e;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, (braun_real)h), BRAUN_OK);
    assert_true(sim.data.stats.rank_deficient > 0);
    braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &p, &v, &e);
    print_message("four-bar from y=0, first step: |Phi_q| %.3g |Phi_e| %.3g\n", (double)p, (double)e);
    assert_le(p, PREC(3e-6, 3e-6)); /* measured 1.04e-6 / 9.39e-7 */
    assert_le(e, PREC(8e-9, 2e-6)); /* 1.92e-9 / 5.96e-7 (sized at the start: 9.51e-5) */
    for (int k = 0; k < 10; k++) assert_int_equal(braun_step(&sim.data, BRAUN_RK4, (braun_real)h), BRAUN_OK);
    monitor mo;
    memset(&mo, 0, sizeof mo);
    mo.model = b;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, (braun_real)h, 100, 1, monitor_out, &mo), BRAUN_OK);
    print_message("four-bar from y=0, after 10 steps to 100 s: |Phi_q| %.3g |Phi_e| %.3g rank drops %ld\n",
                  mo.maxpos, mo.maxE, sim.data.stats.rank_deficient);
    assert_false(mo.nonfinite);
    assert_le(mo.maxpos, PREC(2e-9, 1e-4)); /* measured 6.71e-10 / 3.13e-5 */
    assert_le(mo.maxE, PREC(4e-9, 5e-5));   /* 1.42e-9 / 1.53e-5 (before: 7.45e-7 / 3.4e-3) */
    test_sim_close(&sim);
}

/* The slider-crank over 100 s at h = 1e-3 passes its bifurcation point
 * (θ1 = -π/2, slider over the crank pivot) twice per period: the float
 * hard case of the firmware issue. */
static void test_slider_crank_bifurcation(void **state)
{
    (void)state;
    monitor mo;
    assert_int_equal(run("slider-crank", NULL, NULL, BRAUN_CORRECT_ALL, 1e-3, 100.0, 1, &mo, NULL),
                     BRAUN_OK);
    print_message("slider-crank h=1e-3 100 s: |Phi_q| %.3g |Phi_e| %.3g traj %.3g\n", mo.maxpos,
                  mo.maxE, mo.maxtraj);
    assert_false(mo.nonfinite);
    assert_le(mo.maxpos, PREC(1e-11, 2e-6)); /* measured 2.92e-12 / 5.96e-7 */
    assert_le(mo.maxtraj, PREC(1e-8, 1e-2)); /* 3.52e-9 / 4.36e-3 (start-sized: 3.54e-9 / 2.97e-3) */
}

/* Inconsistent start: position error 1e-2 and velocity error 1e-1 on every
 * coordinate of the four-bar: pulled onto the constraints within a few
 * steps; the energy error never exceeds the start's own inconsistency. */
static void test_inconsistent_start(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("four-bar");
    braun_real q0[6], v0[6];
    for (int i = 0; i < 6; i++) {
        q0[i] = b->q0[i] + (braun_real)(i % 2 ? -1e-2 : 1e-2);
        v0[i] = b->v0[i] + (braun_real)(i % 3 ? 1e-1 : -1e-1);
    }
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    braun_real p0, vel0, p, vel, e;
    braun_residuals(&sim.data, 0, q0, v0, &p0, &vel0, NULL);
    for (int k = 0; k < 4; k++) assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &p, &vel, &e);
    print_message("inconsistent four-bar: |Phi_q| %.3g -> %.3g, |Phi_v| %.3g -> %.3g after 4 steps\n",
                  (double)p0, (double)p, (double)vel0, (double)vel);
    assert_true(p0 > 1e-2);
    assert_le(p, PREC(4e-10, 6e-7));  /* measured 1.21e-10 / 2.06e-7 */
    assert_le(vel, PREC(1e-3, 1e-3)); /* 3.76e-4 / 3.76e-4 */
    monitor mo;
    memset(&mo, 0, sizeof mo);
    mo.model = b;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 50.0, 1, monitor_out, &mo), BRAUN_OK);
    assert_false(mo.nonfinite);
    braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &p, &vel, &e);
    print_message("inconsistent four-bar, then 50 s: max |Phi_q| %.3g, final |Phi_e| %.3g\n", mo.maxpos,
                  (double)e);
    assert_le(mo.maxpos, PREC(4e-8, 1e-4)); /* measured 1.18e-8 / 2.88e-5 */
    assert_le(e, PREC(1e-12, 1e-4));        /* 0 / 1.91e-5 (before: 1.9e-8 / 0) */
    test_sim_close(&sim);
}

/* At rest in equilibrium the energy force's pseudoinverse would divide by
 * ||N_v C_e^T||^2 = 0: the state must stay exactly at rest. */
static void test_rest_no_division_by_zero(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("pendulum");
    const braun_real q0[2] = {0, -1}, v0[2] = {0, 0};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    sim.data.E0 += (braun_real)1e-3; /* an energy error that cannot be corrected through v = 0 */
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL), BRAUN_OK);
    assert_true(isfinite((double)sim.data.q[0]) && isfinite((double)sim.data.v[0]));
    assert_true(sim.data.stats.energy_guard_hits > 0);
    /* guarded: the first steps may only scale a zero velocity */
    test_sim_close(&sim);
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 10.0, 0, NULL, NULL), BRAUN_OK);
    assert_near(sim.data.q[0], 0, 1e-12);
    assert_near(sim.data.q[1], -1, PREC(1e-12, 1e-6));
    assert_near(sim.data.v[0], 0, 1e-12);
    test_sim_close(&sim);
}

/* Velocity purely normal to the constraints: kinetic energy > 0 but
 * A_e = Mv is orthogonal to every free direction (N_v C_e^T = 0). */
static void test_energy_gradient_normal_to_motion(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("pendulum");
    const braun_real q0[2] = {0, -1}, v0[2] = {0, (braun_real)0.3};
    monitor mo;
    braun_stats stats;
    assert_int_equal(run("pendulum", q0, v0, BRAUN_CORRECT_ALL, 1e-2, 10.0, 0, &mo, &stats), BRAUN_OK);
    assert_false(mo.nonfinite);
    /* The first step starts with Φ̇ = 0.3: its local error (≈ h²·v²) is the
     * largest constraint error of the run, then the corrections hold. */
    print_message("normal velocity: max |Phi_q| %.3g, energy guard hits %ld\n", mo.maxpos,
                  stats.energy_guard_hits);
    assert_le(mo.maxpos, PREC(2e-5, 2e-5)); /* measured 9.03e-6 / 8.94e-6 */
    (void)b;
}

/* Step sizes: from 1e-6 (no round-off growth from the 1/h terms, either
 * discretisation) to the largest stable step, and beyond it a status,
 * never a NaN trajectory. */
static void test_step_size_range(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("slider-crank");
    for (int disc = 0; disc < 2; disc++) {
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
        sim.model.opt.discretization = (braun_discretization)disc;
        assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
        monitor mo;
        memset(&mo, 0, sizeof mo);
        mo.model = b;
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, (braun_real)1e-6, (braun_real)2e-3, 1, monitor_out, &mo), BRAUN_OK);
        print_message("h=1e-6 %s: |Phi_q| %.3g |Phi_v| %.3g |Phi_e| %.3g\n",
                      disc ? "per-stage" : "per-step", mo.maxpos, mo.maxvel, mo.maxE);
        /* measured 6.9e-16, 5.6e-16 / 1.93e-7 (round-off: floor 1e-14);
         * 6.3e-18, 1.1e-15 / 1.77e-9. The float bounds were 1e-7 and
         * 5e-10, set on 2.98e-8 and 1.64e-10 measured when the float
         * mechanism did not move at this step (its increments h·v below
         * its positions' ulp: test_small_steps_move); moving, its
         * residuals are at float's round-off of the rows, about
         * ε·Σ|A_ij|(|q_j| + ulp) and ε·Σ|A_ij||v_j|. */
        assert_le(mo.maxpos, PREC(1e-14, 3e-7));
        assert_le(mo.maxvel, PREC(5e-15, 4e-9));
        test_sim_close(&sim);
    }
    const double hs[] = {1e-2, 2e-2, 5e-2, 0.1, 0.2, 0.5, 1.0};
    double largest_ok = 0;
    for (size_t i = 0; i < sizeof hs / sizeof hs[0]; i++) {
        monitor mo;
        int st = run("slider-crank", NULL, NULL, BRAUN_CORRECT_ALL, hs[i], 20.0, 0, &mo, NULL);
        /* Either the run completes with finite residuals within the accuracy
         * guard, or it says why it stopped. */
        assert_true(st == BRAUN_OK || st == BRAUN_ERR_DIVERGED || st == BRAUN_ERR_ACCURACY);
        if (st == BRAUN_OK) {
            assert_false(mo.nonfinite);
            if (mo.maxpos < 1e-2) largest_ok = hs[i];
        }
        print_message("h=%g: %s, max|Phi_q| %.3g\n", hs[i], braun_status_str(st), mo.maxpos);
    }
    assert_true(largest_ok >= 5e-2); /* the paper's Fig. 1 step */
}

/* Small steps move the mechanism: released from rest at h = 1e-5, the
 * float slider-crank's increments h·v (1e-9) fell below its positions'
 * ulp (6e-8), and the energy force took back the kinetic energy the
 * stalled positions could not turn into a fall: it never moved (error
 * 1.31 after 0.5 s), status OK (found by an outside client). Now the
 * state's sum is compensated in float and the energy force leaves
 * round-off alone: measured 3.6e-5 (float), 1.3e-12 (double). */
static void test_small_steps_move(void **state)
{
    (void)state;
    monitor mo;
    assert_int_equal(run("slider-crank", NULL, NULL, BRAUN_CORRECT_ALL, 1e-5, 0.5, 1, &mo, NULL), BRAUN_OK);
    print_message("slider-crank h=1e-5 0.5 s: traj %.3g |Phi_q| %.3g\n", mo.maxtraj, mo.maxpos);
    assert_le(mo.maxtraj, PREC(1e-9, 2e-4));
}

/* braun_check_callbacks judges differences by the precision the callbacks
 * compute in: the float build judged float values by double's round-off
 * and failed the built-in models' correct callbacks by 2e-3. Correct ones
 * pass in both; a Jacobian 1 % off is found in both. */
static int rod_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t, (void)q, (void)u;
    M[0] = 1, M[1] = 0, M[2] = 0, M[3] = 1;
    return 0;
}
static int rod_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)t, (void)q, (void)v, (void)u;
    Q[0] = 0, Q[1] = BRAUN_R(-9.81);
    return 0;
}
static int rod_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                         braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const braun_real off = *(const braun_real *)u; /* A_q[0] off by this factor */
    (void)t;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - 1;
    if (A) A[0] = 2 * q[0] * off, A[1] = 2 * q[1];
    if (b) b[0] = 0;
    if (bv) bv[0] = -2 * (v[0] * v[0] + v[1] * v[1]);
    return 0;
}

static void test_callback_check_in_this_precision(void **state)
{
    (void)state;
    braun_callback_report rep;
    const char *names[] = {"pendulum", "slider-crank", "four-bar"};
    for (int i = 0; i < 3; i++) {
        const braun_builtin *b = braun_builtin_find(names[i]);
        assert_non_null(b);
        const int st = braun_check_callbacks(&b->sys, 0, b->q0, b->v0, 0, &rep);
        print_message("%s: %s, worst %s %.3g\n", names[i], braun_status_str(st), rep.worst,
                      rep.worst_value);
        assert_int_equal(st, BRAUN_OK);
    }
    braun_real off = 1;
    braun_system sys = {.n = 2, .m = 1, .flags = BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC,
                        .mass = rod_mass, .forces = rod_forces, .holonomic = rod_holonomic,
                        .user = &off};
    const braun_real q[2] = {BRAUN_R(0.6), BRAUN_R(-0.8)}, v[2] = {BRAUN_R(0.8), BRAUN_R(0.6)};
    assert_int_equal(braun_check_callbacks(&sys, 0, q, v, 0, &rep), BRAUN_OK);
    off = BRAUN_R(1.01);
    assert_int_equal(braun_check_callbacks(&sys, 0, q, v, 0, &rep), BRAUN_ERR_ARGUMENT);
    assert_string_equal(rep.worst, "A_q[0]");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_four_bar_long),
        cmocka_unit_test(test_four_bar_in_h),
        cmocka_unit_test(test_four_bar_at_singularity),
        cmocka_unit_test(test_slider_crank_bifurcation),
        cmocka_unit_test(test_inconsistent_start),
        cmocka_unit_test(test_rest_no_division_by_zero),
        cmocka_unit_test(test_energy_gradient_normal_to_motion),
        cmocka_unit_test(test_step_size_range),
        cmocka_unit_test(test_callback_check_in_this_precision),
        cmocka_unit_test(test_small_steps_move),
    };
#ifdef BRAUN_SINGLE
    return cmocka_run_group_tests_name("stability (float)", tests, NULL, NULL);
#else
    return cmocka_run_group_tests_name("stability (double)", tests, NULL, NULL);
#endif
}
