/* Bad input gets a status that names the problem and the place; a failed
 * step leaves the last good state in place. */
#include "test_util.h"
#include "braun_models.h"
#include "test_systems.h"
#include "braun_host.h" /* braun_error_format */

static pendulum_params pend(int bad_mass)
{
    pendulum_params p = {1.0, 1.0, 9.81, 0, bad_mass, 0, 0, 0, 0};
    return p;
}

static void test_model_validation(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    braun_system s = pendulum_system(&prm);
    braun_model m;
    assert_int_equal(braun_model_init(NULL, &s), BRAUN_ERR_ARGUMENT);
    braun_system bad = s;
    bad.n = 0;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_SIZE);
    bad = s;
    bad.m = -1;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_SIZE);
    bad = s;
    bad.holonomic = NULL;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_MISSING_CALLBACK);
    bad = s;
    bad.p = 1;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_MISSING_CALLBACK);
    bad = s;
    bad.flags |= BRAUN_ENERGY_INPUT;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_MISSING_CALLBACK);
    bad = s;
    bad.flags = 1u << 7;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_ERR_ARGUMENT);
    /* energy correction without a law */
    bad = s;
    bad.energy = NULL;
    assert_int_equal(braun_model_init(&m, &bad), BRAUN_OK);
    assert_int_equal(m.opt.corrections & BRAUN_CORRECT_ENERGY, 0);
    m.opt.corrections = BRAUN_CORRECT_ALL;
    size_t bytes = braun_data_size(&m);
    void *buf = malloc(bytes);
    braun_data d;
    assert_int_equal(braun_data_init(&d, &m, buf, bytes), BRAUN_ERR_NO_ENERGY_LAW);
    /* buffer too small */
    m.opt.corrections = 0;
    assert_int_equal(braun_data_init(&d, &m, buf, bytes - 1), BRAUN_ERR_BUFFER);
    assert_int_equal(braun_data_init(&d, &m, buf, bytes), BRAUN_OK);
    free(buf);
}

/* braun_system_check: braun_model_init's status, and a constant string
 * naming the field and the rule (a docs-only client found only the status
 * text, "a callback the sizes require is NULL", which does not say which). */
static void test_system_check_names_the_problem(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    const braun_system s = pendulum_system(&prm);
    const char *why = "x";
    assert_int_equal(braun_system_check(&s, &why), BRAUN_OK);
    assert_null(why);
    assert_int_equal(braun_system_check(NULL, &why), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(why, "NULL"));
    struct { braun_system sys; int status; const char *names; } cases[9];
    for (int i = 0; i < 9; i++) cases[i].sys = s;
    cases[0].sys.n = 0, cases[0].status = BRAUN_ERR_SIZE, cases[0].names = "n <= 0";
    cases[1].sys.m = -1, cases[1].status = BRAUN_ERR_SIZE, cases[1].names = "m or p < 0";
    cases[2].sys.n = 5000, cases[2].status = BRAUN_ERR_SIZE, cases[2].names = "BRAUN_MAX_DENSE";
    cases[3].sys.mass = NULL, cases[3].status = BRAUN_ERR_MISSING_CALLBACK, cases[3].names = "mass";
    cases[4].sys.forces = NULL, cases[4].status = BRAUN_ERR_MISSING_CALLBACK, cases[4].names = "forces";
    cases[5].sys.holonomic = NULL, cases[5].status = BRAUN_ERR_MISSING_CALLBACK, cases[5].names = "holonomic";
    cases[6].sys.p = 1, cases[6].status = BRAUN_ERR_MISSING_CALLBACK, cases[6].names = "nonholonomic";
    cases[7].sys.flags |= BRAUN_ENERGY_INPUT, cases[7].status = BRAUN_ERR_MISSING_CALLBACK,
        cases[7].names = "power";
    cases[8].sys.flags = 1u << 7, cases[8].status = BRAUN_ERR_ARGUMENT, cases[8].names = "flags";
    for (int i = 0; i < 9; i++) {
        braun_model m;
        assert_int_equal(braun_system_check(&cases[i].sys, &why), cases[i].status);
        assert_int_equal(braun_model_init(&m, &cases[i].sys), cases[i].status);
        print_message("case %d: %s\n", i, why);
        assert_non_null(why);
        assert_non_null(strstr(why, cases[i].names));
    }
    /* a sparsity that does not tile M */
    braun_sparsity sp = {NULL, NULL, 0, NULL};
    braun_system sparse = s;
    sparse.sparsity = &sp;
    assert_int_equal(braun_system_check(&sparse, &why), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(why, "sparsity"));
    assert_int_equal(braun_system_check(&s, NULL), BRAUN_OK);
    /* q_scale: every entry a size, positive and finite; refused by
     * braun_model_init too, with the field named. */
    const braun_real bad[4] = {0, -1, (braun_real)NAN, (braun_real)INFINITY};
    for (int i = 0; i < 4; i++) {
        braun_real sizes[8] = {1, 1, 1, 1, 1, 1, 1, 1};
        sizes[s.n - 1] = bad[i];
        braun_system sized = s;
        sized.q_scale = sizes;
        braun_model m;
        assert_int_equal(braun_system_check(&sized, &why), BRAUN_ERR_ARGUMENT);
        assert_non_null(strstr(why, "q_scale"));
        assert_int_equal(braun_model_init(&m, &sized), BRAUN_ERR_ARGUMENT);
        sizes[s.n - 1] = 0.5;
        assert_int_equal(braun_system_check(&sized, &why), BRAUN_OK);
        assert_int_equal(braun_model_init(&m, &sized), BRAUN_OK);
    }
}

/* Misaligned buffers are fine: the data is carved from an aligned offset. */
static void test_misaligned_buffer(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    braun_system s = pendulum_system(&prm);
    braun_model m;
    assert_int_equal(braun_model_init(&m, &s), BRAUN_OK);
    size_t bytes = braun_data_size(&m);
    unsigned char *raw = malloc(bytes + 1);
    braun_data d;
    assert_int_equal(braun_data_init(&d, &m, raw + 1, bytes), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&d, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&d, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL), BRAUN_OK);
    free(raw);
}

static void expect_mass_error(int bad_mass, int status, int i, int j)
{
    pendulum_params prm = pend(bad_mass);
    braun_system s = pendulum_system(&prm);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), status);
    assert_string_equal(sim.data.error.where, "mass");
    assert_int_equal(sim.data.error.index, i);
    assert_int_equal(sim.data.error.index2, j);
    assert_true(sim.data.t == 0); /* nothing advanced */
    test_sim_close(&sim);
}

static void test_bad_mass_matrices(void **state)
{
    (void)state;
    expect_mass_error(1, BRAUN_ERR_MASS_NOT_SPD, 1, 1);
    expect_mass_error(2, BRAUN_ERR_MASS_NOT_SYMMETRIC, 0, 1);
    expect_mass_error(3, BRAUN_ERR_NONFINITE, 1, 0);
}

static void test_bad_state_and_steps(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    braun_system s = pendulum_system(&prm);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0}, qn[2] = {1, NAN}, vi[2] = {INFINITY, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, qn, v0), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "state q");
    assert_int_equal(sim.data.error.index, 1);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, vi), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "state v");
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 0), BRAUN_ERR_STEP);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, -1e-3), BRAUN_ERR_STEP);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, NAN), BRAUN_ERR_STEP);
    assert_int_equal(braun_step(&sim.data, (braun_method)42, 1e-3), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 0.0, 1, NULL, NULL), BRAUN_ERR_TIME);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, -1.0, 1, NULL, NULL), BRAUN_ERR_TIME);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, INFINITY, 1, NULL, NULL), BRAUN_ERR_TIME);
    braun_real qd[2], vd[2];
    assert_int_equal(braun_eval(&sim.data, 0, q0, v0, 0, qd, vd), BRAUN_ERR_STEP);
    assert_int_equal(braun_eval(&sim.data, 0, qn, v0, 1e-3, qd, vd), BRAUN_ERR_NONFINITE);
    assert_int_equal(braun_eval(NULL, 0, q0, v0, 1e-3, qd, vd), BRAUN_ERR_ARGUMENT);
    /* braun_energy checks the state as braun_eval does, also where E does
     * not depend on the entry (the pendulum's potential has no x): it
     * returned BRAUN_OK with a finite E before. */
    braun_real E = 0;
    const double qx[2] = {NAN, 0};
    assert_int_equal(braun_energy(&sim.data, 0, qx, v0, &E), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "state q");
    assert_int_equal(sim.data.error.index, 0);
    assert_int_equal(braun_energy(&sim.data, NAN, q0, v0, &E), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "state t");
    assert_int_equal(braun_energy(&sim.data, 0, q0, v0, &E), BRAUN_OK);
    test_sim_close(&sim);
}

/* SUNDIALS convention: < 0 fatal, > 0 recoverable. Fixed-step drivers
 * cannot retry; the adaptive driver retries with a smaller step. Either way
 * the state stays at the last good step. */
static void test_callback_failures(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    prm.fail_from = 41; /* 4 RK4 stages per step: fails inside step 11 */
    prm.fail_to = 1000000;
    prm.fail_code = -3;
    braun_system s = pendulum_system(&prm);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 1, NULL, NULL),
                     BRAUN_ERR_CALLBACK);
    assert_string_equal(sim.data.error.where, "forces");
    assert_int_equal(sim.data.error.index, -3);
    assert_int_equal(sim.data.stats.steps, 10);
    assert_near(sim.data.t, 0.1, 1e-15);
    assert_true(isfinite(sim.data.q[0]) && isfinite(sim.data.v[1]));

    prm.calls = 0;
    prm.fail_code = 2;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 1, NULL, NULL),
                     BRAUN_ERR_CALLBACK_RECOVERABLE);

    /* Adaptive: one recoverable failure is retried and the run completes. */
    prm.calls = 0;
    prm.fail_from = prm.fail_to = 30;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
    long rejected0 = sim.data.stats.rejected_steps;
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1.0, 1, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.stats.rejected_steps > rejected0);
    assert_near(sim.data.t, 1.0, 0);

    /* A callback that fails for good, far from t = 0 (t0 = 1e9: the time
     * resolution is 1.2e-7): the driver shrinks its step to the default
     * h_min and reports the callback. The default was 1e-12 of the span,
     * below the resolution, and the run ended BRAUN_ERR_TIME_RESOLUTION
     * ("the float horizon"), as every float run with such a callback did. */
    prm.calls = 0;
    prm.fail_from = 30;
    prm.fail_to = 1000000000;
    assert_int_equal(braun_set_state(&sim.data, 1e9, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1e9 + 1, 1, NULL, NULL),
                     BRAUN_ERR_CALLBACK_RECOVERABLE);
    assert_string_equal(sim.data.error.where, "forces");
    assert_true(sim.data.t >= 1e9 && sim.data.t < 1e9 + 1 && isfinite(sim.data.q[0]));
    /* A span of a subnormal: the default first step, 1e-3 of it, is 0; the
     * run takes the span in one step instead of reporting h = 0. */
    prm.calls = 0;
    prm.fail_from = prm.fail_to = -1;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 4.9e-324, 1, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.t == 4.9e-324);
    test_sim_close(&sim);
}

/* A stiff unconstrained oscillator with a step far beyond RK4's stability
 * limit: the overflow is reported as divergence, never a NaN trajectory. */
static int osc_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = 1;
    return 0;
}
static int osc_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                      void *u)
{
    (void)t; (void)v; (void)u;
    Q[0] = -1e6 * q[0];
    return 0;
}

static int count_out(const braun_data *d, void *u)
{
    (void)d;
    ++*(long *)u;
    return 0;
}

static void test_divergence_is_reported(void **state)
{
    (void)state;
    braun_system s = {1, 0, 0, BRAUN_MASS_CONSTANT, osc_mass, osc_forces, NULL, NULL, NULL,
                      NULL, NULL, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY),
                     BRAUN_OK);
    const double q0[1] = {1}, v0[1] = {0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    long outputs = 0;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 0.1, 1e6, 1, count_out, &outputs),
                     BRAUN_ERR_DIVERGED);
    assert_true(isfinite(sim.data.q[0]) && isfinite(sim.data.v[0]));
    assert_true(sim.data.t > 0);
    /* the error names the stage time inside the failed step */
    assert_true(sim.data.error.t >= sim.data.t && sim.data.error.t <= sim.data.t + 0.1 + 1e-12);
    assert_int_equal(outputs, sim.data.stats.steps + 1); /* every good step was seen */
    test_sim_close(&sim);
}

/* A mass matrix defined for |x| < sqrt(2) only: M = 2 − x². From x = 1 at
 * rest a spring keeps the motion within |x| <= 1, but a trial step of 10 s
 * throws a stage state far out, where M has no positive pivot. That is the
 * solution leaving the model's domain — BRAUN_ERR_DIVERGED, which the
 * adaptive driver retries smaller — not a bad model: the run used to stop
 * with BRAUN_ERR_MASS_NOT_SPD at its first trial step (a05's flyball
 * governor at --dt 0.1). */
static int shrinking_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)u;
    M[0] = 2 - q[0] * q[0];
    return 0;
}
static int spring_force(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                        void *u)
{
    (void)t; (void)v; (void)u;
    Q[0] = -q[0];
    return 0;
}

static void test_mass_lost_at_a_stage_is_divergence(void **state)
{
    (void)state;
    braun_system s = {1, 0, 0, 0, shrinking_mass, spring_force, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    const double q0[1] = {1}, v0[1] = {0};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_NONE), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    const braun_adaptive ctl = {1e-8, 1e-10, 10, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 5.0, 0, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.t == 5.0 && sim.data.stats.rejected_steps > 0);
    assert_true(fabs(sim.data.q[0]) <= 1 + 1e-6);
    /* A fixed step that large: diverged, naming the mass pivot; the state
     * stays at the start. */
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 10), BRAUN_ERR_DIVERGED);
    assert_string_equal(sim.data.error.where, "mass");
    assert_true(sim.data.q[0] == 1 && sim.data.t == 0);
    /* At a state given by the caller it is the model's: not positive
     * definite (the first step's first stage, where M is first needed). */
    const double far[1] = {3};
    assert_int_equal(braun_set_state(&sim.data, 0, far, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_MASS_NOT_SPD);
    test_sim_close(&sim);
}

/* Contradictory constraints (x = 0 and x = 1, on one coordinate): no
 * state satisfies both; the step says so instead of drifting to a
 * least-squares compromise. */
static int line_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = M[3] = 1;
    M[1] = M[2] = 0;
    return 0;
}
static int line_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                       void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = Q[1] = 0;
    return 0;
}
static int contradict(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                      braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const double gap = *(const double *)u;
    (void)t; (void)v;
    if (phi) { phi[0] = q[0]; phi[1] = q[0] - gap; }
    if (A) { A[0] = 1; A[1] = 0; A[2] = 1; A[3] = 0; }
    if (b) b[0] = b[1] = 0;
    if (bv) bv[0] = bv[1] = 0;
    return 0;
}

/* A Jacobian entry of +Inf: every QR pivot then compares "small" against
 * the infinite first one (rank 0, no constraint force, finite z), so only
 * the residual b_v - C_v atil shows it. The step must still fail, naming A,
 * and not silently drop the constraint. */
static int infinite_row(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                        braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    if (phi) phi[0] = 0;
    if (A) { A[0] = INFINITY; A[1] = 0; }
    if (b) b[0] = 0;
    if (bv) bv[0] = 0;
    return 0;
}

static void test_infinite_jacobian_is_named(void **state)
{
    (void)state;
    braun_system s = {2, 1, 0, BRAUN_MASS_CONSTANT, line_mass, line_forces, infinite_row, NULL,
                      NULL, NULL, NULL, NULL, NULL};
    const double q0[2] = {0, 0}, v0[2] = {0, 0};
    for (unsigned corr = 0; corr <= BRAUN_CORRECT_VELOCITY; corr += BRAUN_CORRECT_VELOCITY) {
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &s, corr), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
        assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_NONFINITE);
        assert_string_equal(sim.data.error.where, "constraint Jacobian");
        assert_true(sim.data.t == 0);
        test_sim_close(&sim);
    }
}

static void test_inconsistent_constraints(void **state)
{
    (void)state;
    double gap = 1.0;
    braun_system s = {2, 2, 0, BRAUN_MASS_CONSTANT, line_mass, line_forces, contradict, NULL,
                      NULL, NULL, &gap, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY),
                     BRAUN_OK);
    const double q0[2] = {0.5, 0}, v0[2] = {0, 1};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
    assert_string_equal(sim.data.error.where, "holonomic constraints");
    assert_near(sim.data.error.value, sqrt(0.5), 1e-12); /* |(Φ1 - Φ2)|/sqrt(2) */
    /* the two rows that disagree are named, for the program to name its joints */
    assert_true((sim.data.error.index == 0 && sim.data.error.index2 == 1) ||
                (sim.data.error.index == 1 && sim.data.error.index2 == 0));
    {
        char what[256];
        braun_error_format(&sim.data, what, sizeof what);
        assert_non_null(strstr(what, "rows"));
    }
    assert_true(sim.data.t == 0);
    /* the same rows agreeing (gap 0) are merely redundant: fine */
    gap = 0;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL), BRAUN_OK);
    assert_near(sim.data.q[0], 0, 1e-12);
    test_sim_close(&sim);
}

/* Three rows, x = 0, y = 0 and x = gap: rows 0 and 2 disagree, row 1
 * is consistent and independent — the error names 0 and 2, not 1. */
static int contradict3(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                       braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const double gap = *(const double *)u;
    (void)t; (void)v;
    if (phi) { phi[0] = q[0]; phi[1] = q[1]; phi[2] = q[0] - gap; }
    if (A) { A[0] = 1; A[1] = 0; A[2] = 0; A[3] = 1; A[4] = 1; A[5] = 0; }
    if (b) b[0] = b[1] = b[2] = 0;
    if (bv) bv[0] = bv[1] = bv[2] = 0;
    return 0;
}

static void test_inconsistent_rows_named(void **state)
{
    (void)state;
    double gap = 0.25;
    braun_system s = {2, 3, 0, BRAUN_MASS_CONSTANT, line_mass, line_forces, contradict3, NULL,
                      NULL, NULL, &gap, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_POSITION), BRAUN_OK);
    const double q0[2] = {0.1, 0.3}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
    const int a = sim.data.error.index, b = sim.data.error.index2;
    assert_true((a == 0 && b == 2) || (a == 2 && b == 0));
    char what[256];
    braun_error_format(&sim.data, what, sizeof what);
    assert_true(strstr(what, "rows 0 and 2") || strstr(what, "rows 2 and 0"));
    test_sim_close(&sim);
}

/* x = 0 and y² = 0.01 started at y = 0: the second row's gradient
 * vanishes while its error does not — one row that cannot be met, not two
 * that disagree: index 1, index2 -2 (its gradient is zero: the message
 * said it "depends on the other rows'"). */
static int singular_row(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                        braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)u;
    if (phi) { phi[0] = q[0]; phi[1] = q[1] * q[1] - 0.01; }
    if (A) { A[0] = 1; A[1] = 0; A[2] = 0; A[3] = 2 * q[1]; }
    if (b) b[0] = b[1] = 0;
    if (bv) { bv[0] = 0; bv[1] = -2 * v[1] * v[1]; }
    return 0;
}

static void test_inconsistent_single_row(void **state)
{
    (void)state;
    braun_system s = {2, 2, 0, BRAUN_MASS_CONSTANT, line_mass, line_forces, singular_row, NULL,
                      NULL, NULL, NULL, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_POSITION), BRAUN_OK);
    const double q0[2] = {0.2, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
    assert_int_equal(sim.data.error.index, 1);
    assert_int_equal(sim.data.error.index2, -2);
    char what[256];
    braun_error_format(&sim.data, what, sizeof what);
    assert_non_null(strstr(what, "(row 1: its gradient is zero here"));
    test_sim_close(&sim);
}

/* A drive x = r·t (holonomic, rheonomic: b_q = r) and a knife forbidding
 * x motion (nonholonomic, Φ_v = v_x): dependent rows whose positions agree
 * at t = 0 and whose velocities cannot (Φ̇_q = v_x − r, Φ_v = v_x) unless
 * r = 0. Before, the velocity correction took the least-squares compromise
 * and a run ended with status 0 and the knife violated. */
static int drive_x(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                   braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const double r = *(const double *)u;
    (void)v;
    if (phi) phi[0] = q[0] - r * t;
    if (A) { A[0] = 1; A[1] = 0; }
    if (b) b[0] = r;
    if (bv) bv[0] = 0;
    return 0;
}
static int knife_x(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                   braun_real *A, braun_real *bv, void *u)
{
    (void)t; (void)q; (void)u;
    if (phi) phi[0] = v[0];
    if (A) { A[0] = 1; A[1] = 0; }
    if (bv) bv[0] = 0;
    return 0;
}

/* Two holonomic drives of one coordinate, x = t and x = 2t: their
 * positions agree at t = 0, their velocities cannot. Eq. 16's right-hand
 * side −(Φ + hΦ̇) carries the velocity error scaled by h, so the position
 * correction failed first and named positions that "disagree by" h times
 * it (0.00707 at h = 1e-2): now reported at velocity level, 0.707. */
static int two_drives(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                      braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)v; (void)u;
    if (phi) { phi[0] = q[0] - t; phi[1] = q[0] - 2 * t; }
    if (A) { A[0] = 1; A[1] = 0; A[2] = 1; A[3] = 0; }
    if (b) { b[0] = 1; b[1] = 2; }
    if (bv) bv[0] = bv[1] = 0;
    return 0;
}

/* Open sim on s with the position and velocity corrections, start at
 * (0, q0, v0): the first RK4 step is refused as inconsistent at `where`. */
static void first_step_inconsistent(test_sim *sim, const braun_system *s, const double *q0,
                                    const double *v0, const char *where)
{
    assert_int_equal(test_sim_open(sim, s, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim->data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim->data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
    assert_string_equal(sim->data.error.where, where);
}

static void test_inconsistent_velocities(void **state)
{
    {
        braun_system s2 = {2, 2, 0, BRAUN_MASS_CONSTANT, line_mass, line_forces, two_drives, NULL,
                           NULL, NULL, NULL, NULL, NULL};
        const double q0[2] = {0, 0}, v0[2] = {1.5, 0};
        test_sim sim;
        first_step_inconsistent(&sim, &s2, q0, v0, "velocity-level constraint rows");
        assert_near(sim.data.error.value, sqrt(0.5), 1e-12);
        /* Positions that disagree (at t = 1: x = 1 and x = 2) are still
         * the positions' failure. */
        const double q1[2] = {1, 0};
        assert_int_equal(braun_set_state(&sim.data, 1, q1, v0), BRAUN_OK);
        assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
        assert_string_equal(sim.data.error.where, "holonomic constraints");
        test_sim_close(&sim);
    }

    (void)state;
    double rate = 1.0;
    braun_system s = {2, 1, 1, BRAUN_MASS_CONSTANT, line_mass, line_forces, drive_x, knife_x,
                      NULL, NULL, &rate, NULL, NULL};
    const double q0[2] = {0, 0}, v0[2] = {0.5, 1};
    test_sim sim;
    first_step_inconsistent(&sim, &s, q0, v0, "velocity-level constraint rows");
    assert_near(sim.data.error.value, sqrt(0.5), 1e-12); /* |(−0.5) − 0.5|/sqrt(2) */
    assert_true((sim.data.error.index == 0 && sim.data.error.index2 == 1) ||
                (sim.data.error.index == 1 && sim.data.error.index2 == 0));
    assert_true(sim.data.t == 0 && sim.data.q[0] == 0 && sim.data.v[0] == 0.5);
    {
        char what[256];
        braun_error_format(&sim.data, what, sizeof what);
        assert_non_null(strstr(what, "velocity-level constraint rows disagree by 0.707"));
    }
    /* Rates that agree (r = 0, the knife's v_x = 0): merely redundant. */
    rate = 0;
    const double v1[2] = {0.5, 1}; /* both rows' velocity error 0.5: removed */
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v1), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL), BRAUN_OK);
    assert_near(sim.data.v[0], 0, 1e-12);
    assert_near(sim.data.q[1], 1, 1e-12);
    /* A new braun_set_state is judged again. */
    rate = 1;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_INCONSISTENT);
    test_sim_close(&sim);
    /* Only the start is judged: the four-bar starts with rows of full rank
     * (no judgement to make) and, with a coarse rank tolerance, drops a
     * row near its singular configuration at t = 1.23, where the dropped
     * direction keeps its velocity error by design. A first version judged
     * the first rank-deficient correction instead and stopped this run. */
    const braun_builtin *fb = braun_builtin_find("four-bar");
    assert_int_equal(test_sim_open(&sim, &fb->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    sim.model.opt.rank_tol = 1e-3;
    assert_int_equal(braun_set_state(&sim.data, 0, fb->q0, fb->v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 5.0, 0, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.stats.rank_deficient > 0);
    test_sim_close(&sim);
}

/* M = diag(1 + x², 1 + t) declared BRAUN_MASS_CONSTANT: the library
 * factored M(0, 0) = I once and would use it everywhere. The claim is
 * checked at braun_set_state, at the start of every 64th step
 * (BRAUN_MASS_CHECK_EVERY) and at a driver's last state. */
static int varying_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    const int *which = u; /* 0: M(x), 1: M(t), 2: NaN away from x = 0 */
    M[0] = *which == 2 ? (q[0] != 0 ? NAN : 1) : 1 + (*which == 0 ? q[0] * q[0] : 0);
    M[3] = 1 + (*which == 1 ? t : 0);
    M[1] = M[2] = 0;
    return 0;
}

static void test_mass_constant_claim_checked(void **state)
{
    (void)state;
    int which = 0;
    braun_system s = {2, 0, 0, BRAUN_MASS_CONSTANT, varying_mass, line_forces, NULL, NULL, NULL,
                      NULL, &which, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_NONE), BRAUN_OK);
    /* A fresh data block: a refused claim refuses every later call. */
#define REOPEN_SIM()                                                                    \
    do {                                                                                \
        test_sim_close(&sim);                                                           \
        assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_NONE), BRAUN_OK);        \
    } while (0)
    /* M(q) at the start differs: refused, nothing set. */
    const double q1[2] = {0.5, 0}, q0[2] = {0, 0}, v0[2] = {1, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q1, v0), BRAUN_ERR_ARGUMENT);
    assert_string_equal(sim.data.error.where,
                        "system declared BRAUN_MASS_CONSTANT but M(t, q) differs from M(0, 0)");
    assert_true(sim.data.error.value > 0.05);
    /* The claim is the model's: found false, it stays false. A start where
     * M happens to agree is refused too, until braun_data_init. */
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "found at an earlier call"));
    REOPEN_SIM();
    /* Where M(q) equals M(0, 0) the start passes; the motion leaves it
     * (x = t): the 64th step's start says so, t = 0.63, and the run keeps
     * the state there. A first version checked a driver's last state only
     * (t = 1 here) and a braun_step loop never. */
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL),
                     BRAUN_ERR_ARGUMENT);
    assert_near(sim.data.error.t, 0.63, 1e-12);
    assert_near(sim.data.t, 0.63, 1e-12);
    assert_near(sim.data.q[0], 0.63, 1e-12);
    assert_int_equal(sim.data.stats.steps, 63);
    /* The finding's report, with its difference: the driver's check of the
     * kept state repeated it as "found at an earlier call", value 0. */
    assert_string_equal(sim.data.error.where,
                        "system declared BRAUN_MASS_CONSTANT but M(t, q) differs from M(0, 0)");
    assert_true(sim.data.error.value > 0.05);
    /* A braun_step loop: the 64th call refuses and changes nothing. */
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    int calls = 0, st = BRAUN_OK;
    while (calls < 1000 && (st = braun_step(&sim.data, BRAUN_RK4, 1e-2)) == BRAUN_OK) calls++;
    assert_int_equal(st, BRAUN_ERR_ARGUMENT);
    assert_int_equal(calls, 63);
    assert_string_equal(sim.data.error.where,
                        "system declared BRAUN_MASS_CONSTANT but M(t, q) differs from M(0, 0)");
    assert_near(sim.data.t, 0.63, 1e-12);
    assert_near(sim.data.q[0], 0.63, 1e-12);
    /* It stays refused, at any point. */
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_ARGUMENT);
    assert_near(sim.data.t, 0.63, 1e-12);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_ERR_ARGUMENT);
    assert_near(sim.data.t, 0.63, 1e-12);
    /* braun_eval, the right-hand side of the caller's own integrator: the
     * 64th evaluation since braun_set_state, here at x = 0.64. */
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    {
        double qe[2] = {0, 0}, qd[2], vd[2];
        int evals = 0;
        st = BRAUN_OK;
        while (evals < 1000 && st == BRAUN_OK) {
            qe[0] = 0.01 * (evals + 1);
            st = braun_eval(&sim.data, qe[0], qe, v0, 1e-2, qd, vd);
            if (st == BRAUN_OK) evals++;
        }
        assert_int_equal(st, BRAUN_ERR_ARGUMENT);
        assert_int_equal(evals, 63);
        assert_near(sim.data.error.t, 0.64, 1e-12);
    }
    /* The adaptive driver reports the finding too, with its difference. */
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    {
        braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 100.0, 0, NULL, NULL),
                         BRAUN_ERR_ARGUMENT);
        assert_string_equal(sim.data.error.where,
                            "system declared BRAUN_MASS_CONSTANT but M(t, q) differs from M(0, 0)");
        assert_true(sim.data.error.value > 0.05);
    }
    /* M(t): the same at the end of the span. */
    which = 1;
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 0.5, 0, NULL, NULL),
                     BRAUN_ERR_ARGUMENT);
    braun_adaptive ctl = {1e-6, 1e-8, 0, 0, 0, 0};
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 0.5, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    /* A NaN in the check's M is named as such (M is scanned once the
     * quadratic forms disagree), not reported as a varying M. */
    which = 2;
    REOPEN_SIM();
    assert_int_equal(braun_set_state(&sim.data, 0, q1, v0), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "mass");
    assert_int_equal(sim.data.error.index, 0);
    test_sim_close(&sim);
#undef REOPEN_SIM
    /* A mass matrix that is constant passes everywhere (the built-in
     * models, the scenes: every test that runs them). */
}

/* A NaN from a callback at the user's state is named with its entry. The
 * library checks only the results and scans the outputs on failure. */
static int nan_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                      void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = 0;
    Q[1] = NAN;
    return 0;
}
static int nan_rod(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                   braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)v; (void)u;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - 1;
    if (A) { A[0] = 2 * q[0]; A[1] = INFINITY; }
    if (b) b[0] = 0;
    if (bv) bv[0] = 0;
    return 0;
}

static void test_nonfinite_callback_outputs_are_named(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    braun_system s = pendulum_system(&prm);
    s.forces = nan_forces;
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "forces");
    assert_int_equal(sim.data.error.index, 1);
    test_sim_close(&sim);
    s = pendulum_system(&prm);
    s.holonomic = nan_rod;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_NONFINITE);
    assert_string_equal(sim.data.error.where, "constraint Jacobian");
    assert_int_equal(sim.data.error.index, 0);
    assert_int_equal(sim.data.error.index2, 1);
    test_sim_close(&sim);
}

/* braun_error_format names what braun_system_check found for a
 * missing callback or bad sizes: it said "a callback the sizes n, m, p
 * require is NULL" for a NULL power (required by a flag) and "invalid
 * sizes n, m, p" for n above the dense limit. */
static void test_format_names_missing_callback_and_sizes(void **state)
{
    (void)state;
    pendulum_params prm = pend(0);
    static unsigned char buf[1 << 14];
    struct {
        int what, status;
        const char *says;
    } cases[] = {
        {0, BRAUN_ERR_MISSING_CALLBACK, "power is NULL but flags has BRAUN_ENERGY_INPUT"},
        {1, BRAUN_ERR_MISSING_CALLBACK, "holonomic is NULL but m > 0"},
        {2, BRAUN_ERR_SIZE, "n, m or p above BRAUN_MAX_DENSE"},
        {3, BRAUN_ERR_SIZE, "m or p < 0"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        braun_model m;
        memset(&m, 0, sizeof m); /* filled in by hand: braun_data_init checks it */
        m.sys = pendulum_system(&prm);
        if (cases[k].what == 0) m.sys.flags |= BRAUN_ENERGY_INPUT;
        if (cases[k].what == 1) m.sys.holonomic = NULL;
        if (cases[k].what == 2) m.sys.n = 5000;
        if (cases[k].what == 3) m.sys.p = -1;
        braun_data d;
        assert_int_equal(braun_data_init(&d, &m, buf, sizeof buf), cases[k].status);
        char what[300];
        braun_error_format(&d, what, sizeof what);
        if (!strstr(what, cases[k].says)) {
            print_error("case %d: '%s' does not name '%s'\n", cases[k].what, what, cases[k].says);
            fail();
        }
    }
}

static void test_status_names(void **state)
{
    (void)state;
    for (int st = -16; st <= 1; st++) {
        const char *s = braun_status_str(st);
        assert_non_null(s);
        assert_true(strncmp(s, "BRAUN_", 6) == 0);
        assert_null(strstr(s, "UNKNOWN"));
    }
    assert_non_null(strstr(braun_status_str(99), "UNKNOWN"));
    /* BRAUN_ERR_ARGUMENT is also a false claim found by a check (a wrong
     * callback, BRAUN_MASS_CONSTANT, BRAUN_SCLERONOMIC): its text said
     * "NULL pointer or invalid option" only. */
    assert_non_null(strstr(braun_status_str(BRAUN_ERR_ARGUMENT), "claim"));
    assert_non_null(strstr(braun_status_str(BRAUN_ERR_ARGUMENT), "braun_error_format"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_model_validation),
        cmocka_unit_test(test_system_check_names_the_problem),
        cmocka_unit_test(test_misaligned_buffer),
        cmocka_unit_test(test_bad_mass_matrices),
        cmocka_unit_test(test_bad_state_and_steps),
        cmocka_unit_test(test_callback_failures),
        cmocka_unit_test(test_divergence_is_reported),
        cmocka_unit_test(test_inconsistent_constraints),
        cmocka_unit_test(test_inconsistent_rows_named),
        cmocka_unit_test(test_inconsistent_single_row),
        cmocka_unit_test(test_inconsistent_velocities),
        cmocka_unit_test(test_mass_constant_claim_checked),
        cmocka_unit_test(test_mass_lost_at_a_stage_is_divergence),
        cmocka_unit_test(test_infinite_jacobian_is_named),
        cmocka_unit_test(test_nonfinite_callback_outputs_are_named),
        cmocka_unit_test(test_format_names_missing_callback_and_sizes),
        cmocka_unit_test(test_status_names),
    };
    return cmocka_run_group_tests_name("errors", tests, NULL, NULL);
}
