/* Zero heap allocations inside a step: every malloc/calloc/realloc/free
 * reaching the library is counted through the linker's --wrap (see the
 * Makefile), and none may happen while integrating. */
#include "test_util.h"
#include "test_systems.h"

#include "heap_count.h"

static void run_counted(const braun_system *s, const double *q0, const double *v0,
                        braun_discretization disc)
{
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, s, s->energy ? BRAUN_CORRECT_ALL
                                                      : BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY),
                     BRAUN_OK);
    sim.model.opt.discretization = disc;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    long before = heap_calls;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 1, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_HEUN, 1e-2), BRAUN_OK);
    braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 2.0, 1, NULL, NULL), BRAUN_OK);
    assert_int_equal(heap_calls - before, 0);
    test_sim_close(&sim);
}

static void test_no_heap_in_steps(void **state)
{
    (void)state;
    /* the counter itself works */
    long before = heap_calls;
    void *volatile blk = malloc(8); /* volatile: the pair must not be elided */
    free(blk);
    assert_int_equal(heap_calls - before, 2);

    braun_system g = generic_system(); /* holonomic + nonholonomic + energy */
    double q[4], v[4];
    generic_consistent_state(q, v);
    run_counted(&g, q, v, BRAUN_PER_STEP);
    run_counted(&g, q, v, BRAUN_PER_STAGE);
    pendulum_params prm = {1.0, 1.0, 9.81, 1, 0, 0, 0, 0, 0}; /* redundant rows */
    braun_system p = pendulum_system(&prm);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    run_counted(&p, q0, v0, BRAUN_PER_STEP);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_heap_in_steps),
    };
    return cmocka_run_group_tests_name("noalloc", tests, NULL, NULL);
}
