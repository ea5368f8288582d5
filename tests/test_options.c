/* Options are validated where they are used, a failed braun_data_init
 * leaves nothing to release, every failing call records itself in
 * d->error, and the adaptive driver's step limit counts the attempts of the
 * current call (issue 11). Each test fails on the code before it. */
#include "test_util.h"
#include "braun_linsolver.h"
#include "braun_internal.h" /* braun__fixed_step_count */
#include "test_systems.h"

static pendulum_params pend(void)
{
    pendulum_params p = {1.0, 1.0, 9.81, 0, 0, 0, 0, 0, 0};
    return p;
}

static const double q0[2] = {1, 0}, v0[2] = {0, 0};

/* Data ready to integrate, with the given options edit applied before init. */
typedef struct fixture {
    pendulum_params prm;
    braun_system sys;
    braun_model model;
    braun_data d;
    unsigned char buf[8192];
} fixture;

static void open_fixture(fixture *f)
{
    f->prm = pend();
    f->sys = pendulum_system(&f->prm);
    assert_int_equal(braun_model_init(&f->model, &f->sys), BRAUN_OK);
    assert_true(braun_data_size(&f->model) <= sizeof f->buf);
}

/* An option value no code path knows is refused, by braun_data_init and by
 * every driver after the options were changed. */
static void test_unknown_options_refused(void **state)
{
    (void)state;
    fixture f;
    for (int k = 0; k < 7; k++) {
        open_fixture(&f);
        braun_options *o = &f.model.opt;
        switch (k) {
        case 0: o->corrections = 1u << 5; break;           /* an unknown bit */
        case 1: o->discretization = (braun_discretization)7; break;
        case 2: o->rank_tol = (braun_real)NAN; break;
        case 3: o->rank_tol = 1; break;                    /* every pivot "zero" */
        case 4: o->energy_max_rel = (braun_real)INFINITY; break;
        case 5: o->symmetry_tol = (braun_real)NAN; break;
        default: o->inconsistency_tol = (braun_real)-INFINITY; break;
        }
        const braun_options bad = *o;
        int st = braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf);
        assert_int_equal(st, BRAUN_ERR_ARGUMENT);
        assert_int_equal(f.d.error.status, BRAUN_ERR_ARGUMENT);
        assert_non_null(f.d.error.where);
        assert_non_null(strstr(f.d.error.where, "options"));
        assert_null(f.d.priv); /* nothing to use, nothing to release */

        /* The same value set after braun_data_init: every driver refuses. */
        open_fixture(&f);
        assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_OK);
        assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
        braun_options good = f.model.opt;
        f.model.opt = bad;
        double qd[2], vd[2];
        braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
        assert_int_equal(braun_step(&f.d, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
        assert_int_equal(braun_integrate(&f.d, BRAUN_RK4, 1e-3, 0.1, 0, NULL, NULL),
                         BRAUN_ERR_ARGUMENT);
        assert_int_equal(braun_integrate_adaptive(&f.d, &ctl, 0.1, 0, NULL, NULL),
                         BRAUN_ERR_ARGUMENT);
        assert_int_equal(braun_eval(&f.d, 0, q0, v0, 1e-3, qd, vd), BRAUN_ERR_ARGUMENT);
        assert_non_null(strstr(f.d.error.where, "options"));
        assert_true(f.d.t == 0); /* nothing moved */
        /* Valid options again: honoured. */
        f.model.opt = good;
        assert_int_equal(braun_step(&f.d, BRAUN_RK4, 1e-3), BRAUN_OK);
        braun_data_release(&f.d);
    }
}

/* A counting backend: the dense kernels' operations with create/destroy
 * that allocate, so that a leak or a missing destroy shows. */
static int creates, destroys;
static int fake_create(void **state, const braun_model *model)
{
    (void)model;
    *state = malloc(16);
    creates++;
    return *state ? BRAUN_OK : BRAUN_ERR_BUFFER;
}
static void fake_destroy(void *state)
{
    free(state);
    destroys++;
}
static int fake_factor_mass(void *s, const braun_real *M, braun_real tol, int *i, int *j,
                            braun_real *v)
{
    (void)s; (void)M; (void)tol;
    *i = 0;
    *j = 0;
    *v = -1;
    return BRAUN_ERR_MASS_NOT_SPD; /* always fails: after create */
}

/* The operations this test never reaches (braun_data_init refuses a table
 * without them). */
static void fake_vec(void *s, const braun_real *b, braun_real *x) { (void)s; (void)b; (void)x; }
static int fake_factor_c(void *s, int slot, int rows, const braun_real *A, braun_real tol,
                         const braun_real *atil, braun_real *resid)
{
    (void)s; (void)slot; (void)rows; (void)A; (void)tol; (void)atil; (void)resid;
    return 0;
}
static void fake_pinv(void *s, int slot, const braun_real *r, braun_real *x)
{
    (void)s; (void)slot; (void)r; (void)x;
}
static void fake_lsq(void *s, int slot, const braun_real *r, braun_real *x, braun_real *res)
{
    (void)s; (void)slot; (void)r; (void)x; (void)res;
}
static void fake_null(void *s, int slot, braun_real *z) { (void)s; (void)slot; (void)z; }

/* A failed braun_data_init leaves nothing to release: options are checked
 * before the backend's state is created, and a failure after it (factoring
 * a constant M) destroys it again. */
static void test_failed_init_releases(void **state)
{
    (void)state;
    static braun_linsolver fake = {"fake", BRAUN_LS_DENSE, fake_create, fake_destroy,
                                   fake_factor_mass, fake_vec, fake_vec, fake_vec, fake_factor_c,
                                   fake_pinv, fake_lsq, fake_null, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    /* A table without an operation the core calls is refused, naming it. */
    static braun_linsolver partial = {"partial", BRAUN_LS_DENSE, fake_create, fake_destroy,
                                      fake_factor_mass, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                                      NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    fixture f;
    open_fixture(&f);
    f.model.opt.linsolver = &partial;
    creates = destroys = 0;
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "solve_rt"));
    assert_int_equal(creates, 0);
    f.model.opt.linsolver = &fake;
    f.model.opt.rank_tol = (braun_real)NAN; /* invalid: refused before create */
    creates = destroys = 0;
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_ERR_ARGUMENT);
    assert_int_equal(creates, 0);
    /* Valid options; the constant M fails to factor after create. */
    f.model.opt.rank_tol = 0;
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf),
                     BRAUN_ERR_MASS_NOT_SPD);
    assert_int_equal(creates, 1);
    assert_int_equal(destroys, 1);
    assert_null(f.d.priv);
    braun_data_release(&f.d); /* safe, and nothing happens */
    assert_int_equal(destroys, 1);
}

/* Every failing call records itself: a buffer failure after an earlier
 * error names the buffer, not the earlier failure. */
static void test_failures_record_themselves(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_OK);
    assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
    /* An earlier, different error. */
    assert_int_equal(braun_step(&f.d, BRAUN_RK4, -1), BRAUN_ERR_STEP);
    assert_int_equal(f.d.error.status, BRAUN_ERR_STEP);
    /* Buffer too small: the record says so. */
    const size_t need = braun_data_size(&f.model);
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, need - 1), BRAUN_ERR_BUFFER);
    assert_int_equal(f.d.error.status, BRAUN_ERR_BUFFER);
    assert_non_null(strstr(f.d.error.where, "buffer"));
    assert_true(f.d.error.value == (double)(need - 1));
    /* NULL buffer. */
    assert_int_equal(braun_data_init(&f.d, &f.model, NULL, need), BRAUN_ERR_ARGUMENT);
    assert_int_equal(f.d.error.status, BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "buffer"));
    /* NULL arguments of the state and the evaluation. */
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_OK);
    assert_int_equal(braun_set_state(&f.d, 0, NULL, v0), BRAUN_ERR_ARGUMENT);
    assert_int_equal(f.d.error.status, BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "state q"));
    double qd[2];
    assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_eval(&f.d, 0, q0, v0, 1e-3, qd, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(f.d.error.status, BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "braun_eval"));
    braun_adaptive *none = NULL;
    assert_int_equal(braun_integrate_adaptive(&f.d, none, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "adaptive"));
}

/* Integrating before braun_set_state is a status, not a run from zeros. */
static void test_no_state_refused(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_OK);
    assert_int_equal(braun_step(&f.d, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(f.d.error.where, "braun_set_state"));
    assert_int_equal(braun_integrate(&f.d, BRAUN_RK4, 1e-3, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
}

/* The same adaptive call from the same state behaves the same, however many
 * calls came before: the step limit counts this call's attempts. */
static void test_adaptive_repeatable(void **state)
{
    (void)state;
    fixture f;
    open_fixture(&f);
    assert_int_equal(braun_data_init(&f.d, &f.model, f.buf, sizeof f.buf), BRAUN_OK);
    braun_adaptive ctl = {1e-9, 1e-11, 0, 0, 0, 0};
    /* A limit just above what one call from this state needs. */
    assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate_adaptive(&f.d, &ctl, 2.0, 0, NULL, NULL), BRAUN_OK);
    const long needed = f.d.stats.steps + f.d.stats.rejected_steps;
    assert_true(f.d.stats.rejected_steps > 0); /* the limit must see rejections */
    double qa[2] = {f.d.q[0], f.d.q[1]};
    ctl.max_steps = needed;
    for (int rep = 0; rep < 3; rep++) {
        assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
        assert_int_equal(braun_integrate_adaptive(&f.d, &ctl, 2.0, 0, NULL, NULL), BRAUN_OK);
        assert_true(f.d.q[0] == qa[0] && f.d.q[1] == qa[1]);
    }
    /* One attempt fewer fails, every time. */
    ctl.max_steps = needed - 1;
    for (int rep = 0; rep < 2; rep++) {
        assert_int_equal(braun_set_state(&f.d, 0, q0, v0), BRAUN_OK);
        assert_int_equal(braun_integrate_adaptive(&f.d, &ctl, 2.0, 0, NULL, NULL),
                         BRAUN_ERR_TOO_MANY_STEPS);
    }
}

/* braun_integrate's step count (braun_internal.h): a whole number of steps
 * up to round-off takes that many, never fewer by a whole step — at 1e12
 * steps a relative allowance of 1e-9 made the last step 1000 h long. */
static void test_fixed_step_count(void **state)
{
    (void)state;
    assert_int_equal(braun__fixed_step_count(2.0), 2);
    assert_int_equal(braun__fixed_step_count(0.2), 1);
    assert_int_equal(braun__fixed_step_count(1000.0000000001), 1000);
    assert_int_equal(braun__fixed_step_count(1000.3), 1001);
    assert_true(braun__fixed_step_count(1e9 + 0.75) == 1000000001L);
    if (sizeof(long) >= 8) {
        assert_true(braun__fixed_step_count(1e12) == 1000000000000L);
        assert_true(braun__fixed_step_count(1e12 + 0.75) == 1000000000001L);
        assert_true(braun__fixed_step_count(1e12 * (1 + 1e-15)) == 1000000000000L); /* round-off: 1e12 */
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unknown_options_refused),
        cmocka_unit_test(test_failed_init_releases),
        cmocka_unit_test(test_failures_record_themselves),
        cmocka_unit_test(test_no_state_refused),
        cmocka_unit_test(test_adaptive_repeatable),
        cmocka_unit_test(test_fixed_step_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
