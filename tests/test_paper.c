/* The paper's mechanisms (Sec. 4) against their exact solutions, and the
 * observed order of RK4 under both discretisations of the 1/h terms. The
 * bounds are a small factor (2-4) above the values measured on x86-64, gcc
 * 12, -O2 (beside each): the core issue's acceptance figures (1e-9, 1e-6,
 * 1e-2, ...) had up to 300x slack, enough for an order-3 RK4 to pass. */
#include "test_util.h"
#include "braun_reference.h"

typedef struct monitor {
    const braun_builtin *model;
    braun_reference ref;
    double maxpos, maxvel, maxE, maxtraj, maxpoint;
} monitor;

static int monitor_out(const braun_data *d, void *u)
{
    monitor *mo = u;
    braun_real p, v, e;
    double qr[BRAUN_MODEL_MAX_N], vr[BRAUN_MODEL_MAX_N];
    assert_int_equal(braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, &v, &e), BRAUN_OK);
    mo->maxpos = fmax(mo->maxpos, p);
    mo->maxvel = fmax(mo->maxvel, v);
    mo->maxE = fmax(mo->maxE, e);
    assert_int_equal(braun_reference_eval(&mo->ref, d->t, qr, vr), 0);
    double s = 0;
    for (int i = 0; i < mo->model->sys.n; i++) s += (d->q[i] - qr[i]) * (d->q[i] - qr[i]);
    mo->maxtraj = fmax(mo->maxtraj, sqrt(s));
    if (mo->model->point_x >= 0) {
        double dx = d->q[mo->model->point_x] - qr[mo->model->point_x];
        double dy = d->q[mo->model->point_y] - qr[mo->model->point_y];
        mo->maxpoint = fmax(mo->maxpoint, sqrt(dx * dx + dy * dy));
    }
    return 0;
}

/* Run a built-in model from its paper state; fills the monitor. */
static int run_model(const char *name, unsigned corr, braun_discretization disc,
                     braun_method method, double h, double T, monitor *mo)
{
    const braun_builtin *b = braun_builtin_find(name);
    assert_non_null(b);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, corr), BRAUN_OK);
    sim.model.opt.discretization = disc;
    assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
    memset(mo, 0, sizeof *mo);
    mo->model = b;
    assert_int_equal(braun_reference_init(&mo->ref, b, 1e-4), 0);
    int st = braun_integrate(&sim.data, method, h, T, 1, monitor_out, mo);
    test_sim_close(&sim);
    return st;
}

/* Core issue: slider-crank, RK4, h = 1e-3, 100 s, all corrections. */
static void test_slider_crank_accuracy(void **state)
{
    (void)state;
    monitor mo;
    assert_int_equal(run_model("slider-crank", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_RK4,
                               1e-3, 100.0, &mo),
                     BRAUN_OK);
    print_message("slider-crank h=1e-3 100 s: max|Phi_q| %.3g  max traj %.3g  max|Phi_e| %.3g\n",
                  mo.maxpos, mo.maxtraj, mo.maxE);
    assert_le(mo.maxpos, 1e-11);  /* measured 2.92e-12 (issue: 1e-9) */
    assert_le(mo.maxtraj, 1e-8);  /* 3.54e-9 (issue: 1e-6) */
    assert_le(mo.maxE, 1e-10);    /* 2.71e-11 */
}

/* Core issue: four-bar, RK4, h = 1e-2, 1000 s through its singular
 * configurations: with energy correction ε3 <= 1e-2 and |Φ_e| <= 1e-5;
 * without it the error is visibly larger. */
static void test_four_bar_long_run(void **state)
{
    (void)state;
    monitor with, without;
    assert_int_equal(run_model("four-bar", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_RK4, 1e-2,
                               1000.0, &with),
                     BRAUN_OK);
    assert_int_equal(run_model("four-bar", BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY,
                               BRAUN_PER_STEP, BRAUN_RK4, 1e-2, 1000.0, &without),
                     BRAUN_OK);
    print_message("four-bar h=1e-2 1000 s: with energy eps3 %.3g |Phi_e| %.3g |Phi_q| %.3g;"
                  " without eps3 %.3g |Phi_e| %.3g\n",
                  with.maxpoint, with.maxE, with.maxpos, without.maxpoint, without.maxE);
    assert_le(with.maxpoint, 1e-3); /* measured 3.16e-4 (issue: 1e-2) */
    assert_le(with.maxE, 3e-6);     /* 1.01e-6 (issue: 1e-5) */
    assert_le(with.maxpos, 4e-7);   /* 1.28e-7 */
    /* without: eps3 1.29, |Phi_e| 4.0e-3 */
    assert_true(without.maxpoint > 1000 * with.maxpoint);
    assert_true(without.maxE > 1000 * with.maxE);
}

/* Observed order p = log(e(h1)/e(h2)) / log(h1/h2) over 100 s. RK4 keeps
 * order 4 with the per-step discretisation; the literal per-stage form,
 * where Φ/h meets every stage, drops to about 1. */
static void test_rk4_order(void **state)
{
    (void)state;
    const double hs[4] = {2e-2, 1e-2, 5e-3, 2e-3};
    double e_step[4], e_stage[4];
    monitor mo;
    for (int i = 0; i < 4; i++) {
        assert_int_equal(run_model("slider-crank", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_RK4,
                                   hs[i], 100.0, &mo),
                         BRAUN_OK);
        e_step[i] = mo.maxtraj;
        assert_int_equal(run_model("slider-crank", BRAUN_CORRECT_ALL, BRAUN_PER_STAGE, BRAUN_RK4,
                                   hs[i], 100.0, &mo),
                         BRAUN_OK);
        e_stage[i] = mo.maxtraj;
    }
    for (int i = 1; i < 4; i++) {
        double p1 = log(e_step[i - 1] / e_step[i]) / log(hs[i - 1] / hs[i]);
        double p2 = log(e_stage[i - 1] / e_stage[i]) / log(hs[i - 1] / hs[i]);
        print_message("h %.0e -> %.0e: per-step error %.3g order %.2f | per-stage error %.3g order %.2f\n",
                      hs[i - 1], hs[i], e_step[i], p1, e_stage[i], p2);
        /* measured 4.09, 4.04, 3.99 and 1.15, 1.04, 0.99 */
        assert_true(p1 > 3.9 && p1 < 4.2);
        assert_true(p2 > 0.8 && p2 < 1.3);
    }
    assert_le(e_step[3], 1.5e-7); /* measured 5.67e-8 at h = 2e-3 */
}

/* Euler: the per-step scheme is the paper's equation itself, so both
 * discretisations give the same numbers. */
static void test_euler_schemes_coincide(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("slider-crank");
    double qf[2][6];
    for (int disc = 0; disc < 2; disc++) {
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
        sim.model.opt.discretization = (braun_discretization)disc;
        assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
        assert_int_equal(braun_integrate(&sim.data, BRAUN_EULER, 1e-3, 2.0, 0, NULL, NULL), BRAUN_OK);
        for (int i = 0; i < 6; i++) qf[disc][i] = sim.data.q[i];
        test_sim_close(&sim);
    }
    double dmax = 0;
    for (int i = 0; i < 6; i++) dmax = fmax(dmax, fabs(qf[0][i] - qf[1][i]));
    print_message("euler per-step vs per-stage, 2 s: max |dq| %.3g\n", dmax);
    for (int i = 0; i < 6; i++) assert_near(qf[0][i], qf[1][i], 2e-14); /* measured 6e-15 */
}

/* Heun is second order, Euler first, on the same problem (per-step). */
static void test_low_order_methods(void **state)
{
    (void)state;
    monitor a, b;
    assert_int_equal(run_model("pendulum", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_HEUN, 2e-3, 5.0, &a), BRAUN_OK);
    assert_int_equal(run_model("pendulum", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_HEUN, 1e-3, 5.0, &b), BRAUN_OK);
    double p = log(a.maxtraj / b.maxtraj) / log(2.0);
    print_message("heun order %.2f (errors %.3g, %.3g)\n", p, a.maxtraj, b.maxtraj);
    assert_true(p > 1.9 && p < 2.1);   /* measured 2.00 */
    assert_le(b.maxtraj, 1e-4);         /* 4.17e-5 at h = 1e-3 */
    assert_int_equal(run_model("pendulum", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_EULER, 2e-3, 5.0, &a), BRAUN_OK);
    assert_int_equal(run_model("pendulum", BRAUN_CORRECT_ALL, BRAUN_PER_STEP, BRAUN_EULER, 1e-3, 5.0, &b), BRAUN_OK);
    p = log(a.maxtraj / b.maxtraj) / log(2.0);
    print_message("euler order %.2f (errors %.3g, %.3g)\n", p, a.maxtraj, b.maxtraj);
    assert_true(p > 0.75 && p < 1.25); /* measured 0.85 (not yet asymptotic) */
    assert_le(b.maxtraj, 4e-2);         /* 1.6e-2 at h = 1e-3 */
    /* Euler's constraint error is its local error, O(h^2): halving h
     * divides it by about 4 (no accumulation). */
    double ratio = a.maxpos / b.maxpos;
    print_message("euler max|Phi_q| %.3g (h=2e-3), %.3g (h=1e-3): ratio %.2f\n", a.maxpos,
                  b.maxpos, ratio);
    assert_true(ratio > 3.8 && ratio < 4.2); /* measured 4.00 */
}

/* The four-bar started exactly at a singular configuration (all links
 * horizontal, y = 0): the rank drop is detected and the motion follows the
 * exact solution through it. */
static void test_four_bar_from_singularity(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("four-bar");
    const double q0[6] = {1, 0, 2, 0, 3, 0}, v0[6] = {0, 1, 0, 1, 0, 1};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    monitor mo;
    memset(&mo, 0, sizeof mo);
    mo.model = b;
    /* Exact: the parallelogram motion θ'' = -(7g/6l) cos θ from θ = 0, θ' = 1. */
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 20.0, 1, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.stats.rank_deficient > 0);
    double phi, dphi, w2 = 7 * 9.81 / 6;
    assert_int_equal(braun_pendulum_exact(w2, 3.14159265358979324 / 2, 1.0, 20.0, &phi, &dphi), 0);
    const double th = phi - 3.14159265358979324 / 2;
    braun_real p, v, e;
    braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &p, &v, &e);
    print_message("four-bar from y = 0, 20 s: |x3 - exact| %.3g |y3 - exact| %.3g |Phi_q| %.3g |Phi_e| %.3g\n",
                  fabs(sim.data.q[4] - (2 + cos(th))), fabs(sim.data.q[5] - sin(th)), p, e);
    /* measured 2.7e-9, 6.4e-8, 2.7e-11, 8.7e-9 */
    assert_near(sim.data.q[4], 2 + cos(th), 2e-7);
    assert_near(sim.data.q[5], sin(th), 2e-7);
    assert_le(p, 1e-10);
    assert_le(e, 3e-8);
    test_sim_close(&sim);
}

/* A built-in model from its paper position and the velocity v0 under the
 * adaptive driver at rtol = atol = 1e-10 to T, every step monitored
 * against the reference; its statistics into *stats. */
static void run_adaptive_tight(const braun_builtin *b, const double *v0, double T, monitor *mo,
                               braun_stats *stats)
{
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &b->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, b->q0, v0), BRAUN_OK);
    memset(mo, 0, sizeof *mo);
    mo->model = b;
    assert_int_equal(braun_reference_init(&mo->ref, b, 1e-4), 0);
    braun_adaptive ctl = {1e-10, 1e-10, 1e-2, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, T, 1, monitor_out, mo), BRAUN_OK);
    *stats = sim.data.stats;
    test_sim_close(&sim);
}

/* The adaptive driver through singular configurations at a tight
 * tolerance: its error test sees only the error along the manifold (the
 * normal part is the corrections' job), so the step does not collapse at
 * the small pivots. Before, the four-bar stopped with
 * BRAUN_ERR_STEP_TOO_SMALL at t = 102.2 s and the slider-crank at 145.6 s.
 * The corrections at each accepted end (the start's next to a singular
 * configuration) leave ‖Φ_q‖ at 6.1e-12 and 3.9e-16 (3.7e-11 and 1.0e-11
 * when they were all the start's). */
static void test_adaptive_through_singularities(void **state)
{
    (void)state;
    const char *names[2] = {"four-bar", "slider-crank"};
    /* measured max traj 3.28e-8, 1.43e-8; max |Phi_q| 6.1e-12, 3.9e-16;
     * max |[dPhi_q; Phi_v]| 9.3e-12, 1.8e-15 */
    const double traj_bound[2] = {1.5e-7, 2.5e-8}, pos_bound[2] = {2e-11, 2e-11};
    for (int i = 0; i < 2; i++) {
        const braun_builtin *b = braun_builtin_find(names[i]);
        monitor mo;
        braun_stats st;
        run_adaptive_tight(b, b->v0, 200.0, &mo, &st);
        print_message("%s dopri5 rtol 1e-10, 200 s: %ld steps, %ld rejected, max traj %.3g, max|Phi_q| %.3g, "
                      "max|[dPhi_q; Phi_v]| %.3g\n",
                      names[i], st.steps, st.rejected_steps, mo.maxtraj, mo.maxpos, mo.maxvel);
        assert_le(mo.maxtraj, traj_bound[i]);
        assert_le(mo.maxpos, pos_bound[i]);
        assert_le(mo.maxvel, pos_bound[i]);
    }
}

/* Where an adaptive step lands next to a singular configuration is a
 * matter of round-off: the four-bar's initial velocity a few ulps apart
 * gives runs that pass the singular configurations at different distances
 * (smallest pivot down to 2e-5 of the largest). A correction computed
 * there at a step's start and added at its end — a velocity e/σ along a
 * weak direction that turns fast — was a new error at the end: over these
 * runs ‖Φ_q‖ reached 2.8e-10 and ‖[Φ̇_q; Φ_v]‖ 5.3e-8 for several steps
 * at rtol 1e-10 (-4 ulps, t = 24.05 s). Computed and applied at the end
 * (the start's kept where the end is next to the singular configuration),
 * with the velocity residual re-measured where the position correction put
 * q, both stay below 1e-11 whatever the landing. */
static void test_adaptive_landing_near_singularity(void **state)
{
    (void)state;
    const braun_builtin *b = braun_builtin_find("four-bar");
    const int ulps[4] = {-4, -1, 1, 3};
    for (int k = 0; k < 4; k++) {
        double v0[BRAUN_MODEL_MAX_N];
        for (int i = 0; i < b->sys.n; i++) v0[i] = b->v0[i];
        for (int u = 0; u < abs(ulps[k]); u++) v0[0] = nextafter(v0[0], ulps[k] > 0 ? 2.0 : 0.0);
        monitor mo;
        braun_stats st;
        run_adaptive_tight(b, v0, 30.0, &mo, &st);
        print_message("four-bar v0[0] %+d ulps, dopri5 rtol 1e-10, 30 s: %ld rejected, max traj %.3g, "
                      "max|Phi_q| %.3g, max|[dPhi_q; Phi_v]| %.3g\n",
                      ulps[k], st.rejected_steps, mo.maxtraj, mo.maxpos, mo.maxvel);
        /* measured: max|Phi_q| 6.1e-12, max velocity residual <= 9.2e-12 */
        assert_le(mo.maxpos, 2e-11);
        assert_le(mo.maxvel, 2e-11);
        assert_le(mo.maxtraj, 1.5e-7);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slider_crank_accuracy),
        cmocka_unit_test(test_four_bar_long_run),
        cmocka_unit_test(test_rk4_order),
        cmocka_unit_test(test_euler_schemes_coincide),
        cmocka_unit_test(test_low_order_methods),
        cmocka_unit_test(test_four_bar_from_singularity),
        cmocka_unit_test(test_adaptive_through_singularities),
        cmocka_unit_test(test_adaptive_landing_near_singularity),
    };
    return cmocka_run_group_tests_name("paper", tests, NULL, NULL);
}
