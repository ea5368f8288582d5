/* Andrews' squeezing mechanism (Test Set for IVP Solvers, index-3 form):
 * its G, b_qv and energy law against finite differences, its initial
 * acceleration against the test set's consistent initial values, and the
 * state at t = 0.03 against the test set's reference solution. */
#include "test_util.h"
#include "braun_scene.h"
#include "braun_reference.h"
#include "scene/scene_fd.h"

static void test_derivatives(void **state)
{
    (void)state;
    const braun_system *s = &braun_andrews_system;
    for (int trial = 0; trial < 4; trial++) {
        double q[7], v[7];
        for (int i = 0; i < 7; i++) {
            q[i] = braun_andrews_q0[i] + (trial ? 0.5 * fd_urand() : 0);
            v[i] = trial ? 50 * fd_urand() : 0;
        }
        /* The energy rate check also proves f Lagrangian: its velocity
         * terms are those of M(q), its spring term -∂V/∂γ, and the
         * remaining power is mom·β'. */
        fd_check_system("andrews", s, 0, q, v, 1e-6);
    }
}

/* andrews.f, init: q'' at t = 0 (and λ) of the consistent initial state. */
static void test_initial_acceleration(void **state)
{
    (void)state;
    test_sim sim;
    braun_real qd[7], vd[7];
    assert_int_equal(test_sim_open(&sim, &braun_andrews_system, BRAUN_CORRECT_NONE), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, braun_andrews_q0, braun_andrews_v0), BRAUN_OK);
    assert_int_equal(braun_eval(&sim.data, 0, braun_andrews_q0, braun_andrews_v0, 1, qd, vd), 0);
    const double ref[7] = {14222.4439199541138705911625887, -10666.8329399655854029433719415,
                           0, 0, 0, 0, 0};
    for (int i = 0; i < 7; i++) assert_near(vd[i], ref[i], 1e-10 * 14222.4);
    braun_real pos;
    assert_int_equal(braun_residuals(&sim.data, 0, braun_andrews_q0, braun_andrews_v0, &pos, NULL,
                                     NULL),
                     0);
    assert_le(pos, 1e-15);
    test_sim_close(&sim);
}

static double run_to_reference(double h, double *pos_err)
{
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &braun_andrews_system, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, braun_andrews_q0, braun_andrews_v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, h, BRAUN_ANDREWS_T_REF, 1, NULL, NULL),
                     BRAUN_OK);
    assert_near(sim.data.t, BRAUN_ANDREWS_T_REF, 1e-15);
    double worst = 0;
    for (int i = 0; i < 7; i++)
        worst = fmax(worst, fabs(sim.data.q[i] - braun_andrews_q_ref[i]) /
                                fabs(braun_andrews_q_ref[i]));
    braun_real pos;
    assert_int_equal(braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &pos, NULL,
                                     NULL),
                     0);
    *pos_err = pos;
    test_sim_close(&sim);
    return worst;
}

/* The figure: every angle at t = 0.03 within 1e-6 relative of the
 * test set's reference, RK4 with all corrections. h = 1e-4 is the largest
 * step tried that meets it (1.5e-4 gives 2.1e-6). */
static void test_reference_solution(void **state)
{
    (void)state;
    const double steps[] = {1e-4, 1e-5};
    /* measured 3.5e-7, 3.2e-10 (the 1e-6 for h = 1e-4) and |Phi_q|
     * 3.7e-9, 3.7e-14 */
    const double rel_bound[] = {1e-6, 1e-9}, pos_bound[] = {1e-8, 1.5e-13};
    for (int k = 0; k < 2; k++) {
        double pos, rel = run_to_reference(steps[k], &pos);
        print_message("andrews RK4 h = %g (%g steps): max relative error at t = 0.03 %.3g, "
                      "|Phi_q| %.3g\n", steps[k], 0.03 / steps[k], rel, pos);
        assert_le(rel, rel_bound[k]);
        assert_le(pos, pos_bound[k]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_initial_acceleration),
        cmocka_unit_test(test_reference_solution),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
