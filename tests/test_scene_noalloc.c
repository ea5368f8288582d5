/* A built scene allocates nothing while it is simulated: every heap call
 * is counted through the linker's --wrap (mk/scenes.mk), and stepping the
 * shipped scenes — every element type among them — makes none. Loading a
 * file allocates (host only); building a scene from caller arrays does
 * not. */
#include "test_util.h"
#include "braun_scene_file.h"

#include "heap_count.h"

static void test_no_heap_in_scene_steps(void **state)
{
    (void)state;
    const char *files[] = {"data/damped-motor.json", "data/sleigh.json", "data/driven-crank.json",
                           "data/parallelogram-redundant.json", "data/four-bar.json"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char err[256];
        const long loading = heap_calls;
        braun_scene_file *f = braun_scene_load(files[i], err, sizeof err);
        if (!f) fail_msg("%s", err);
        assert_true(heap_calls > loading); /* the counter sees the reader's arrays */
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &f->sys, f->corrections), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        const long before = heap_calls;
        /* Building again from the same arrays: no allocation either. */
        braun_system again;
        assert_int_equal(braun_scene_build(&f->scene, &again, NULL), BRAUN_OK);
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 0.5, 1, NULL, NULL), 0);
        braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1.0, 1, NULL, NULL), 0);
        assert_int_equal(heap_calls - before, 0);
        test_sim_close(&sim);
        braun_scene_free(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_heap_in_scene_steps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
