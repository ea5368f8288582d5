/* The explicit methods against their published Butcher tableaus, written
 * out in this file: on an unconstrained system (m = p = 0, no corrections)
 * a braun_step is the method's step on q' = v, v' = M⁻¹Q(t, q, v), so 20
 * steps of each method from a time-dependent, nonlinear, velocity-dependent
 * start must give what this file's own explicit Runge–Kutta loop gives with
 * the textbook coefficients, to round-off. Any coefficient of
 * src/core/braun_tableau.c off by more than ~1e-12 (an order-3 "RK4" made
 * by moving a_31, a_32, a_41, a_42 by 1e-3, which the end-to-end bounds
 * cannot see at h = 1e-3) fails here; so does a stage that reads the wrong
 * stage or time. */
#include "test_util.h"

#define N 2
#define MAXS 7

/* M = diag(2, 3); Q nonlinear in q and v and explicitly time dependent, so
 * that every a_ij, b_i and c_i of a tableau matters. */
static int mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t, (void)q, (void)u;
    M[0] = 2.0, M[1] = 0.0, M[2] = 0.0, M[3] = 3.0;
    return 0;
}

static void own_forces(double t, const double *q, const double *v, double *Q)
{
    Q[0] = -4.0 * q[0] - q[0] * q[0] * q[0] - 0.3 * v[0] + 0.5 * cos(1.7 * t) + 0.2 * q[1] * v[1];
    Q[1] = -2.0 * sin(q[1]) - 0.1 * v[1] * v[1] * v[1] + 0.4 * q[0] + sin(2.3 * t);
}

static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)u;
    double qd[N] = {q[0], q[1]}, vd[N] = {v[0], v[1]}, Qd[N];
    own_forces(t, qd, vd, Qd);
    Q[0] = Qd[0];
    Q[1] = Qd[1];
    return 0;
}

/* y = (q, v): y' = (v, M⁻¹Q). */
static void own_rhs(double t, const double *y, double *f)
{
    double Q[N];
    own_forces(t, y, y + N, Q);
    f[0] = y[2];
    f[1] = y[3];
    f[2] = Q[0] / 2.0;
    f[3] = Q[1] / 3.0;
}

typedef struct tableau {
    const char *name;
    braun_method method;
    int s;
    double c[MAXS], a[MAXS][MAXS], b[MAXS];
} tableau;

/* Euler; Heun (explicit trapezoid); classic RK4 (Kutta 1901); Dormand &
 * Prince (1980) 5(4), its 5th-order weights (Hairer, Nørsett & Wanner,
 * Table II.5.2). */
static const tableau tableaus[] = {
    {"euler", BRAUN_EULER, 1, {0}, {{0}}, {1}},
    {"heun", BRAUN_HEUN, 2, {0, 1}, {{0}, {1}}, {0.5, 0.5}},
    {"rk4", BRAUN_RK4, 4, {0, 0.5, 0.5, 1}, {{0}, {0.5}, {0, 0.5}, {0, 0, 1}},
     {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}},
    {"dopri5", BRAUN_DOPRI5, 7, {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1},
     {{0},
      {1.0 / 5},
      {3.0 / 40, 9.0 / 40},
      {44.0 / 45, -56.0 / 15, 32.0 / 9},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
      {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}},
     {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}},
};

static void own_step(const tableau *tb, double t, double h, double *y)
{
    double k[MAXS][2 * N], ys[2 * N];
    for (int i = 0; i < tb->s; i++) {
        for (int j = 0; j < 2 * N; j++) {
            ys[j] = y[j];
            for (int l = 0; l < i; l++) ys[j] += h * tb->a[i][l] * k[l][j];
        }
        own_rhs(t + tb->c[i] * h, ys, k[i]);
    }
    for (int j = 0; j < 2 * N; j++)
        for (int i = 0; i < tb->s; i++) y[j] += h * tb->b[i] * k[i][j];
}

static void test_steps_are_the_tableaus(void **state)
{
    (void)state;
    const braun_system sys = {.n = N, .m = 0, .p = 0, .flags = BRAUN_MASS_CONSTANT,
                              .mass = mass, .forces = forces};
    const double t0 = 0.3, h = 0.05;
    const braun_real q0[N] = {0.7, -0.4}, v0[N] = {0.3, 0.9};
    for (size_t m = 0; m < sizeof tableaus / sizeof tableaus[0]; m++) {
        const tableau *tb = &tableaus[m];
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &sys, BRAUN_CORRECT_NONE), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, t0, q0, v0), BRAUN_OK);
        double y[2 * N] = {q0[0], q0[1], v0[0], v0[1]}, t = t0, worst = 0, moved = 0;
        for (int k = 0; k < 20; k++) {
            assert_int_equal(braun_step(&sim.data, tb->method, h), BRAUN_OK);
            own_step(tb, t, h, y);
            t = t0 + (k + 1) * h;
            for (int j = 0; j < N; j++) {
                worst = fmax(worst, fabs(sim.data.q[j] - y[j]));
                worst = fmax(worst, fabs(sim.data.v[j] - y[N + j]));
            }
        }
        for (int j = 0; j < N; j++) moved = fmax(moved, fabs(y[j] - q0[j]));
        print_message("%-7s 20 steps of h = %g: max |braun - own tableau| %.3g (state moved %.3g)\n",
                      tb->name, h, worst, moved);
        assert_true(moved > 0.1);
        /* Round-off of 20 steps: measured 5.6e-16 .. 7.8e-16. */
        assert_le(worst, 3e-15);
        assert_near(sim.data.t, t, 1e-14);
        test_sim_close(&sim);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steps_are_the_tableaus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
