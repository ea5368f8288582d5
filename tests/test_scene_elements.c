/* Every element type of the scene builder, one at a time, against finite
 * differences: A_q, b_q, b_qv (holonomic), A_vv, b_vv (nonholonomic),
 * dE/dq, dE/dv and the energy rate dE/dt = Ė (tests/scene/scene_fd.h).
 * Plus the builder's choices: which callbacks exist, flags, row numbering,
 * refusals, and callbacks that write nothing when an output is NULL. */
#include "test_util.h"
#include "braun_scene.h"
#include "scene/scene_fd.h"

/* A playground: two rigid bodies, two particles, points on each and on
 * the ground. Each test adds the elements it checks. */
typedef struct playground {
    braun_scene_body bodies[4];
    braun_scene_point points[10];
    braun_scene_rod rods[4];
    braun_scene_joint joints[6];
    braun_scene_effect effects[6];
    braun_scene s;
    braun_system sys;
} playground;

enum { B0_P = 0, B1_P, PART2, PART3, GROUND_P, B0_C, B1_Q, B1_C, B1_R };

static void playground_init(playground *g)
{
    memset(g, 0, sizeof *g);
    g->bodies[0] = (braun_scene_body){BRAUN_BODY_RIGID, 2.0, 0.3, {0.1, 0.2, 0.3}, {0}, 0, {0}, 0};
    g->bodies[1] = (braun_scene_body){BRAUN_BODY_RIGID, 1.5, 0.2, {1.0, -0.3, -0.7}, {0}, 0, {0}, 0};
    g->bodies[2] = (braun_scene_body){BRAUN_BODY_PARTICLE, 0.7, 0, {0.5, 0.5, 0}, {0}, 0, {0}, 0};
    g->bodies[3] = (braun_scene_body){BRAUN_BODY_PARTICLE, 0.4, 0, {1.2, 0.9, 0}, {0}, 0, {0}, 0};
    g->points[B0_P] = (braun_scene_point){0, 0.3, -0.2, 0};
    g->points[B1_P] = (braun_scene_point){1, -0.4, 0.1, 0};
    g->points[PART2] = (braun_scene_point){2, 0, 0, 0};
    g->points[PART3] = (braun_scene_point){3, 0, 0, 0};
    g->points[GROUND_P] = (braun_scene_point){BRAUN_SCENE_GROUND, 0.5, 0.7, 0};
    g->points[B0_C] = (braun_scene_point){0, 0, 0, 0};
    g->points[B1_Q] = (braun_scene_point){1, 0.2, 0.25, 0};
    g->points[B1_C] = (braun_scene_point){1, 0, 0, 0};
    g->points[B1_R] = (braun_scene_point){1, -0.5, 0.2, 0};
    g->s.nbodies = 4;
    g->s.bodies = g->bodies;
    g->s.npoints = 9;
    g->s.points = g->points;
    g->s.rods = g->rods;
    g->s.joints = g->joints;
    g->s.effects = g->effects;
}

static const braun_scene_fn SINE = {BRAUN_FN_SINE, 0.2, 0.7, 2.3, 0.4};
static const braun_scene_fn LINEAR = {BRAUN_FN_LINEAR, 0.4, -1.3, 0, 0};
/* A driven length stays above 0 (offset > |amplitude|: the builder refuses
 * a sine length that reaches 0, which the row cannot tell from -L). */
static const braun_scene_fn LENGTH_SINE = {BRAUN_FN_SINE, 0.9, 0.7, 2.3, 0.4};

static braun_scene_joint joint(const braun_scene_joint_class *type, int a, int b, double ax,
                               double ay, double value, const braun_scene_fn *drive)
{
    braun_scene_joint j;
    memset(&j, 0, sizeof j);
    j.type = type;
    j.a = a;
    j.b = b;
    j.axis[0] = ax;
    j.axis[1] = ay;
    j.value = value;
    if (drive) {
        j.driven = 1;
        j.drive = *drive;
    }
    return j;
}

/* Build, then check at three random states (not on the constraints: the
 * identities hold everywhere). */
static void check_playground(playground *g, const char *what)
{
    braun_scene_error err;
    int st = braun_scene_build(&g->s, &g->sys, &err);
    if (st) fail_msg("%s: build failed: %s", what, err.what);
    for (int trial = 0; trial < 3; trial++) {
        double q[FD_NMAX], v[FD_NMAX];
        for (int i = 0; i < g->s.n; i++) {
            q[i] = 1.5 * fd_urand();
            v[i] = 2.0 * fd_urand();
        }
        fd_check_system(what, &g->sys, 0.37 + trial, q, v, 2e-6);
    }
}

static void test_rods(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.rods[0] = (braun_scene_rod){PART2, PART3, 1.2, 0.9, 0};
    g.rods[1] = (braun_scene_rod){GROUND_P, PART2, 0.5, 1.1, 0};
    g.s.nrods = 2;
    check_playground(&g, "rods");
    assert_int_equal(g.s.m, 2);
    /* Mass blocks m/3 and m/6 (natural coordinates). */
    double M[100];
    g.sys.mass(0, NULL, M, g.sys.user);
    const int n = g.s.n, i2 = g.bodies[2].iq, i3 = g.bodies[3].iq;
    assert_near(M[i2 * n + i2], 0.7 + 1.2 / 3 + 0.5 / 3, 1e-15);
    assert_near(M[i3 * n + i3], 0.4 + 1.2 / 3, 1e-15);
    assert_near(M[i2 * n + i3], 1.2 / 6, 1e-15);
    assert_near(M[(i2 + 1) * n + i3 + 1], 1.2 / 6, 1e-15);
    assert_near(M[i2 * n + i3 + 1], 0, 0);
}

static void test_revolute(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE, B0_P, B1_P, 0, 0, 0, NULL);
    g.joints[1] = joint(BRAUN_JOINT_REVOLUTE, B0_P, GROUND_P, 0, 0, 0, NULL);
    g.joints[2] = joint(BRAUN_JOINT_REVOLUTE, PART2, B1_Q, 0, 0, 0, NULL);
    g.s.njoints = 3;
    check_playground(&g, "revolute");
    assert_int_equal(g.s.m, 6);
    assert_int_equal(g.joints[2].row, 4);
}

static void test_distance(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_DISTANCE, B0_P, B1_P, 0, 0, 0.8, NULL);
    g.joints[1] = joint(BRAUN_JOINT_DISTANCE, PART2, B1_Q, 0, 0, 0, &LENGTH_SINE);
    g.joints[2] = joint(BRAUN_JOINT_DISTANCE, GROUND_P, PART3, 0, 0, 0, &LINEAR);
    g.s.njoints = 3;
    check_playground(&g, "distance");
    /* driven: the energy law stays, the core adds the drive's work (the
     * system is not declared scleronomic) */
    assert_non_null(g.sys.energy);
    assert_false(g.sys.flags & BRAUN_SCLERONOMIC);
}

static void test_slider(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    /* A line on a moving body, a line on the ground, and a driven one. */
    g.joints[0] = joint(BRAUN_JOINT_SLIDER, B1_P, B0_P, 0.6, 0.8, 0, NULL);
    g.joints[1] = joint(BRAUN_JOINT_SLIDER, PART2, GROUND_P, 1.0, 2.0, 0, NULL);
    g.joints[2] = joint(BRAUN_JOINT_SLIDER, PART3, B0_C, -0.3, 1.0, 0, &SINE);
    g.s.njoints = 3;
    check_playground(&g, "slider");
    assert_int_equal(g.s.m, 4);
}

static void test_prismatic(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_PRISMATIC, B1_P, B0_P, 0.6, 0.8, 0.25, NULL);
    g.joints[1] = joint(BRAUN_JOINT_PRISMATIC, B0_C, GROUND_P, 1.0, -0.5, -0.1, &LINEAR);
    g.s.njoints = 2;
    check_playground(&g, "prismatic");
    assert_int_equal(g.s.m, 5);
}

static void test_angle(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_ANGLE, 0, 1, 0, 0, 0.3, NULL);
    g.joints[1] = joint(BRAUN_JOINT_ANGLE, BRAUN_SCENE_GROUND, 1, 0, 0, 0, &SINE);
    g.joints[2] = joint(BRAUN_JOINT_ANGLE, 0, BRAUN_SCENE_GROUND, 0, 0, 0, &LINEAR);
    g.s.njoints = 3;
    check_playground(&g, "angle");
}

static void test_knife(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    /* Knife edges are nonholonomic joints: a the contact point, axis the
     * blade, both in the body frame. */
    g.joints[0] = joint(BRAUN_JOINT_KNIFE, B0_P, 0, 0.8, 0.6, 0, NULL);
    g.joints[1] = joint(BRAUN_JOINT_KNIFE, B1_C, 0, 1, 0, 0, NULL);
    g.joints[2] = joint(BRAUN_JOINT_KNIFE, B1_R, 0, -0.2, 1.0, 0, NULL);
    g.s.njoints = 3;
    check_playground(&g, "knife");
    assert_int_equal(g.joints[2].row, 2);
    assert_int_equal(g.s.p, 3);
    assert_int_equal(g.s.m, 0);
    assert_null(g.sys.holonomic);
    assert_non_null(g.sys.nonholonomic);
}

static void test_gravity(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.rods[0] = (braun_scene_rod){PART2, PART3, 1.2, 0.9, 0};
    g.rods[1] = (braun_scene_rod){GROUND_P, PART2, 0.5, 1.1, 0};
    g.s.nrods = 2;
    g.effects[0].type = BRAUN_EFFECT_GRAVITY;
    g.effects[0].g[0] = 0.3;
    g.effects[0].g[1] = -9.81;
    g.s.neffects = 1;
    check_playground(&g, "gravity");
    assert_false(g.sys.flags & BRAUN_ENERGY_INPUT);
    assert_null(g.sys.power);
}

static void test_springs(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_SPRING, e[0].a = B0_P, e[0].b = PART2, e[0].k = 30, e[0].rest = 0.5;
    e[1].type = BRAUN_EFFECT_SPRING, e[1].a = GROUND_P, e[1].b = B1_Q, e[1].k = 10;
    g.s.neffects = 2;
    check_playground(&g, "spring");
    assert_null(g.sys.power); /* no damping: nothing put in or taken out */
    e[0].c = 0.7;
    check_playground(&g, "spring-damper");
    assert_true(g.sys.flags & BRAUN_ENERGY_INPUT);
}

static void test_torsion(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_TORSION, e[0].a = 0, e[0].b = 1, e[0].k = 3, e[0].rest = 0.3;
    e[1].type = BRAUN_EFFECT_TORSION, e[1].a = BRAUN_SCENE_GROUND, e[1].b = 0, e[1].k = 2;
    g.s.neffects = 2;
    check_playground(&g, "torsion spring");
    assert_null(g.sys.power);
    e[0].c = 0.2;
    e[1].c = 0.05;
    check_playground(&g, "torsion damper");
}

static void test_forces_torques_motors(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    braun_scene_effect *e = g.effects;
    e[0].type = BRAUN_EFFECT_FORCE, e[0].a = B1_P, e[0].f[0] = SINE, e[0].f[1] = LINEAR;
    e[1].type = BRAUN_EFFECT_FORCE, e[1].a = PART2;
    e[1].f[0] = (braun_scene_fn){BRAUN_FN_CONSTANT, 1.5, 0, 0, 0};
    e[1].f[1] = (braun_scene_fn){BRAUN_FN_STEP, -1, 2, 5, 0}; /* jumps at t = 5 */
    e[2].type = BRAUN_EFFECT_TORQUE, e[2].a = 0, e[2].b = 1, e[2].f[0] = SINE;
    e[3].type = BRAUN_EFFECT_TORQUE, e[3].a = 1, e[3].b = BRAUN_SCENE_GROUND, e[3].f[0] = LINEAR;
    e[4].type = BRAUN_EFFECT_MOTOR, e[4].a = 0, e[4].b = 1, e[4].tau0 = 2, e[4].omega0 = 15;
    e[5].type = BRAUN_EFFECT_MOTOR, e[5].a = 1, e[5].b = BRAUN_SCENE_GROUND, e[5].tau0 = -1;
    e[5].omega0 = -4;
    g.s.neffects = 6;
    check_playground(&g, "forces, torques, motors");
    assert_true(g.sys.flags & BRAUN_ENERGY_INPUT);
}

/* Time functions: values and derivatives by finite differences. */
static void test_functions(void **state)
{
    (void)state;
    const braun_scene_fn fns[] = {{BRAUN_FN_CONSTANT, 1.5, 0, 0, 0}, LINEAR, SINE};
    for (size_t k = 0; k < sizeof fns / sizeof fns[0]; k++)
        for (double t = -1; t < 3; t += 0.7) {
            double x, dx, ddx, xp, xm, dp, dm;
            braun_scene_fn_eval(&fns[k], t, &x, &dx, &ddx);
            braun_scene_fn_eval(&fns[k], t + FD_H, &xp, &dp, NULL);
            braun_scene_fn_eval(&fns[k], t - FD_H, &xm, &dm, NULL);
            assert_near(dx, (xp - xm) / (2 * FD_H), 1e-8);
            assert_near(ddx, (dp - dm) / (2 * FD_H), 1e-8);
        }
    const braun_scene_fn step = {BRAUN_FN_STEP, -1, 2, 5, 0};
    double x;
    braun_scene_fn_eval(&step, 4.999, &x, NULL, NULL);
    assert_near(x, -1, 0);
    braun_scene_fn_eval(&step, 5, &x, NULL, NULL);
    assert_near(x, 2, 0);
}

/* Everything at once, with every output NULL but one: nothing is written
 * where the library did not ask (braun.h), and the values agree. */
static void test_null_outputs(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    g.rods[0] = (braun_scene_rod){PART2, PART3, 1.2, 0.9, 0};
    g.s.nrods = 1;
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE, B0_P, B1_P, 0, 0, 0, NULL);
    g.joints[1] = joint(BRAUN_JOINT_SLIDER, PART2, B0_P, 1, 1, 0, &SINE);
    g.s.njoints = 2;
    g.joints[2] = joint(BRAUN_JOINT_KNIFE, B1_C, 0, 1, 0, 0, NULL);
    g.s.njoints = 3;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, NULL), BRAUN_OK);
    assert_int_equal(g.joints[2].row, 0); /* the first row of Φ_v */
    const int n = g.s.n, m = g.s.m;
    double q[FD_NMAX], v[FD_NMAX], phi[8], A[8 * FD_NMAX], b[8], bv[8], phi2[8], bv2[8];
    for (int i = 0; i < n; i++) q[i] = fd_urand(), v[i] = fd_urand();
    assert_int_equal(g.sys.holonomic(1, q, v, phi, A, b, bv, g.sys.user), 0);
    assert_int_equal(g.sys.holonomic(1, q, v, phi2, NULL, NULL, NULL, g.sys.user), 0);
    assert_int_equal(g.sys.holonomic(1, q, v, NULL, NULL, NULL, bv2, g.sys.user), 0);
    for (int i = 0; i < m; i++) {
        assert_near(phi[i], phi2[i], 0);
        assert_near(bv[i], bv2[i], 0);
    }
    assert_int_equal(g.sys.nonholonomic(1, q, v, NULL, NULL, bv2, g.sys.user), 0);
    assert_false(g.sys.flags & BRAUN_SCLERONOMIC); /* driven slider */
}

/* The builder refuses what cannot be simulated, naming the element. */
static void test_builder_refuses(void **state)
{
    (void)state;
    playground g;
    braun_scene_error err;

    playground_init(&g);
    g.bodies[3].mass = 0; /* a massless particle, no rod carries it */
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.element, BRAUN_SCENE_ELEM_BODY);
    assert_int_equal(err.index, 3);
    assert_string_equal(err.what, "particle has no mass (none of its own and no rod with mass at it)");

    playground_init(&g);
    g.rods[0] = (braun_scene_rod){B0_P, PART2, 1, 1, 0};
    g.s.nrods = 1;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.element, BRAUN_SCENE_ELEM_ROD);
    assert_non_null(strstr(err.what, "rigid body"));

    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_ANGLE, 0, 1, 0, 0, 0, NULL);
    g.joints[0].driven = 1;
    g.joints[0].drive = (braun_scene_fn){BRAUN_FN_STEP, 0, 1, 1, 0};
    g.s.njoints = 1;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_string_equal(err.what, "a drive must be smooth (constant, linear or sine)");

    playground_init(&g);
    g.joints[0] = joint(BRAUN_JOINT_REVOLUTE, B0_P, B0_C, 0, 0, 0, NULL);
    g.s.njoints = 1;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_string_equal(err.what, "joint connects a body to itself");

    playground_init(&g);
    g.bodies[0].inertia = NAN;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.index, 0);

    playground_init(&g);
    g.bodies[1].q0[0] = 1e300;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_string_equal(err.what, "initial state is not a finite number in range");

    playground_init(&g);
    g.effects[0].type = BRAUN_EFFECT_GRAVITY;
    g.effects[1].type = BRAUN_EFFECT_GRAVITY;
    g.s.neffects = 2;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.index, 1);

    playground_init(&g);
    g.s.nbodies = 0;
    g.s.npoints = 0;
    assert_int_equal(braun_scene_build(&g.s, &g.sys, &err), BRAUN_ERR_SIZE);
}

/* Only what the scene calls for: the callbacks and flags of each kind. */
static void test_callbacks_follow_the_scene(void **state)
{
    (void)state;
    playground g;
    playground_init(&g);
    assert_int_equal(braun_scene_build(&g.s, &g.sys, NULL), BRAUN_OK);
    assert_int_equal(g.sys.n, 10);
    /* no drive: scleronomic, so the core skips the constraints' power */
    assert_int_equal(g.sys.flags, BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC);
    assert_null(g.sys.holonomic);
    assert_null(g.sys.nonholonomic);
    assert_null(g.sys.power);
    assert_non_null(g.sys.energy);
    assert_ptr_equal(g.sys.user, &g.s);
    /* Coordinates by body order: 3 per rigid body, 2 per particle. */
    assert_int_equal(g.bodies[1].iq, 3);
    assert_int_equal(g.bodies[2].iq, 6);
    assert_int_equal(g.bodies[3].iq, 8);
    double q[10], v[10];
    braun_scene_initial_state(&g.s, q, v);
    assert_near(q[5], -0.7, 0);
    assert_near(q[8], 1.2, 0);
    double xy[2];
    braun_scene_point_position(&g.s, B0_P, q, xy);
    assert_near(xy[0], 0.1 + cos(0.3) * 0.3 + sin(0.3) * 0.2, 1e-15);
    assert_near(xy[1], 0.2 + sin(0.3) * 0.3 - cos(0.3) * 0.2, 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rods),
        cmocka_unit_test(test_revolute),
        cmocka_unit_test(test_distance),
        cmocka_unit_test(test_slider),
        cmocka_unit_test(test_prismatic),
        cmocka_unit_test(test_angle),
        cmocka_unit_test(test_knife),
        cmocka_unit_test(test_gravity),
        cmocka_unit_test(test_springs),
        cmocka_unit_test(test_torsion),
        cmocka_unit_test(test_forces_torques_motors),
        cmocka_unit_test(test_functions),
        cmocka_unit_test(test_null_outputs),
        cmocka_unit_test(test_builder_refuses),
        cmocka_unit_test(test_callbacks_follow_the_scene),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
