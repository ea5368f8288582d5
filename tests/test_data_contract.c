/* The data block's contract with its caller (docs/api.md, braun.h): the
 * system may not change after braun_data_init (a change is refused, never
 * followed into a buffer sized for the old one); braun_set_state changes
 * nothing unless it succeeds; a callback may not call back into a driver
 * running on the same data (refused, the driver's run goes on); an output
 * callback may read residuals and energy between steps. The system: a
 * particle of mass 1 on the unit circle under gravity (n = 2, m = 1), with
 * an energy law whose callback can be made to fail and a forces callback
 * that can call into the data. */
#include <math.h>

#include "test_util.h"
#include "braun_host.h" /* braun_error_format */
#include "braun_scene_file.h"

typedef struct ring {
    braun_data *d;       /* the data the callbacks call into, or NULL */
    int fail_energy;     /* energy() returns -1 */
    int inner_status;    /* what the call from forces() returned */
    int inner_calls;
    double nan_phi_after; /* > 0: Φ is NaN for t above it */
} ring;

static int ring_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = M[3] = 1;
    M[1] = M[2] = 0;
    return 0;
}
static int ring_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    ring *r = u;
    (void)t; (void)q; (void)v;
    Q[0] = 0;
    Q[1] = -9.81;
    if (r->d && r->inner_calls == 0) {
        r->inner_calls++;
        r->inner_status = braun_step(r->d, BRAUN_RK4, 1e-3);
    }
    return 0;
}
static int ring_holonomic(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                          braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const ring *r = u;
    if (phi) phi[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] - 1);
    if (phi && r->nan_phi_after > 0 && t > r->nan_phi_after) phi[0] = NAN;
    if (A) { A[0] = q[0]; A[1] = q[1]; }
    if (b) b[0] = 0;
    if (bv) bv[0] = -(v[0] * v[0] + v[1] * v[1]);
    return 0;
}
static int ring_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                       braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    const ring *r = u;
    (void)t;
    if (r->fail_energy) return -1;
    if (E) *E = 0.5 * (v[0] * v[0] + v[1] * v[1]) + 9.81 * q[1];
    if (dq) { dq[0] = 0; dq[1] = 9.81; }
    if (dv) { dv[0] = v[0]; dv[1] = v[1]; }
    if (dt) *dt = 0;
    return 0;
}

static braun_system ring_system(ring *r)
{
    braun_system s = {2, 1, 0, BRAUN_MASS_CONSTANT | BRAUN_SCLERONOMIC, ring_mass, ring_forces,
                      ring_holonomic, NULL, ring_energy, NULL, r, NULL, NULL};
    return s;
}

static const braun_real q0[2] = {1, 0}, v0[2] = {0, 0};

/* A data for the ring with every correction (no state yet). */
static void open_ring(test_sim *sim, ring *r)
{
    const braun_system s = ring_system(r);
    assert_int_equal(test_sim_open(sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
}

/* Sizes, flags or a required callback changed after braun_data_init: every
 * entry refuses, naming it, and the state is untouched; put back, it runs. */
static void test_system_changed_after_init(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_OK);
    const braun_real qa = sim.data.q[0];

    sim.model.sys.n = 3; /* the buffers are for n = 2 */
    braun_real big[3] = {1, 0, 0}, out[3], E;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "changed after braun_data_init"));
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_set_state(&sim.data, 0, big, big), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_eval(&sim.data, 0, big, big, 1e-3, out, out + 1), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_residuals(&sim.data, 0, big, big, &E, NULL, NULL), BRAUN_ERR_ARGUMENT);
    sim.model.sys.n = 2;
    sim.model.sys.m = -1;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    sim.model.sys.m = 1;
    sim.model.sys.flags |= BRAUN_ENERGY_INPUT;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    sim.model.sys.flags = ring_system(&r).flags;
    sim.model.sys.holonomic = NULL;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_MISSING_CALLBACK);
    assert_string_equal(sim.data.error.where, "holonomic is NULL but m > 0");
    sim.model.sys.holonomic = ring_holonomic;
    sim.model.sys.mass = NULL;
    assert_int_equal(braun_energy(&sim.data, 0, q0, v0, &E), BRAUN_ERR_MISSING_CALLBACK);
    sim.model.sys.mass = ring_mass;
    assert_true(sim.data.q[0] == qa && sim.data.stats.steps == 1);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_OK);
    test_sim_close(&sim);
}

/* A model filled in by hand, never given to braun_model_init: its system is
 * checked by braun_data_init all the same. */
static void test_hand_filled_model(void **state)
{
    (void)state;
    ring r = {0};
    braun_model model;
    memset(&model, 0, sizeof model);
    model.sys = ring_system(&r);
    model.sys.p = -1;
    static unsigned char buf[1 << 14];
    braun_data d;
    assert_int_equal(braun_data_init(&d, &model, buf, sizeof buf), BRAUN_ERR_SIZE);
    assert_string_equal(d.error.where, "m or p < 0");
    model.sys.p = 0;
    model.sys.forces = NULL;
    assert_int_equal(braun_data_init(&d, &model, buf, sizeof buf), BRAUN_ERR_MISSING_CALLBACK);
    assert_string_equal(d.error.where, "forces is NULL");
    model.sys.forces = ring_forces;
    assert_int_equal(braun_data_init(&d, &model, buf, sizeof buf), BRAUN_OK); /* options all 0: defaults */
    braun_data_release(&d);
}

/* braun_set_state whose energy cannot be evaluated changes nothing: the
 * last run goes on; a data that never had a state still refuses to step. */
static void test_failed_set_state_changes_nothing(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    r.fail_energy = 1;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_ERR_CALLBACK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT); /* no state */
    r.fail_energy = 0;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 0.5, 0, NULL, NULL), BRAUN_OK);
    const braun_real t = sim.data.t, q = sim.data.q[1], E0 = sim.data.E0;
    const long steps = sim.data.stats.steps;
    const braun_real other[2] = {0, -1};
    r.fail_energy = 1;
    assert_int_equal(braun_set_state(&sim.data, 0, other, v0), BRAUN_ERR_CALLBACK);
    r.fail_energy = 0;
    assert_true(sim.data.t == t && sim.data.q[1] == q && sim.data.E0 == E0 && sim.data.has_E0);
    assert_int_equal(sim.data.stats.steps, steps);
    /* ... and it continues with its energy law */
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 1.0, 0, NULL, NULL), BRAUN_OK);
    braun_real pos, vel, en;
    assert_int_equal(braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &pos, &vel, &en),
                     BRAUN_OK);
    assert_true(en < 1e-12);
    test_sim_close(&sim);
}

/* A system callback that calls braun_step on the data whose step is
 * running: refused (the running step's scratch is in use); the outer step
 * completes as if nothing happened. */
static void test_reentry_from_system_callback(void **state)
{
    (void)state;
    ring r = {0}, plain = {0};
    const braun_system s = ring_system(&r), s2 = ring_system(&plain);
    test_sim sim, ref;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(test_sim_open(&ref, &s2, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_set_state(&ref.data, 0, q0, v0), BRAUN_OK);
    r.d = &sim.data;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    assert_int_equal(r.inner_calls, 1);
    assert_int_equal(r.inner_status, BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_step(&ref.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    assert_true(sim.data.t == ref.data.t && sim.data.stats.steps == 1);
    assert_memory_equal(sim.data.q, ref.data.q, 2 * sizeof(braun_real));
    assert_memory_equal(sim.data.v, ref.data.v, 2 * sizeof(braun_real));
    test_sim_close(&sim);
    test_sim_close(&ref);
}

/* An output callback: braun_set_state, the drivers and braun_eval refused
 * (a run in progress: braun_eval's forward pass would replace the
 * factorization the next step starts from), braun_residuals and
 * braun_energy allowed. */
typedef struct watcher {
    int calls, set_state, step, adaptive, eval, residuals, energy;
} watcher;

static int watch(const braun_data *cd, void *u)
{
    watcher *w = u;
    braun_data *d = (braun_data *)cd; /* what a careless program might do */
    braun_real p, E;
    const braun_adaptive ctl = {1e-8, 1e-8, 0, 0, 0, 0};
    w->calls++;
    w->set_state |= braun_set_state(d, 0, q0, v0) != BRAUN_ERR_ARGUMENT;
    w->step |= braun_step(d, BRAUN_RK4, 1e-3) != BRAUN_ERR_ARGUMENT;
    w->adaptive |= braun_integrate_adaptive(d, &ctl, 100, 0, NULL, NULL) != BRAUN_ERR_ARGUMENT;
    braun_real qd[2], vd[2];
    w->eval |= braun_eval(d, d->t, d->q, d->v, 1e-3, qd, vd) != BRAUN_ERR_ARGUMENT ||
               !strstr(d->error.where, "re-entrant");
    w->residuals |= braun_residuals(d, d->t, d->q, d->v, &p, NULL, NULL) != BRAUN_OK;
    w->energy |= braun_energy(d, d->t, d->q, d->v, &E) != BRAUN_OK;
    return 0;
}

static void test_reentry_from_output_callback(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    for (int adaptive = 0; adaptive < 2; adaptive++) {
        watcher w = {0};
        assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
        const braun_adaptive ctl = {1e-8, 1e-8, 0, 0, 0, 0};
        const int st = adaptive ? braun_integrate_adaptive(&sim.data, &ctl, 1.0, 10, watch, &w)
                                : braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 10, watch, &w);
        assert_int_equal(st, BRAUN_OK);
        assert_true(sim.data.t == 1.0);
        assert_true(w.calls > 2);
        assert_int_equal(w.set_state + w.step + w.adaptive + w.eval + w.residuals + w.energy, 0);
    }
    /* After the run the data is free again. */
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_OK);
    test_sim_close(&sim);
}

/* What an output callback may not do to the data or the model a driver
 * runs on: release it (refused, the run goes on), re-initialise it, null a
 * required callback or set an invalid option (the driver stops with
 * BRAUN_ERR_ARGUMENT after the callback returns, never runs on them). An
 * outside client's crashes and silent runs, stop 32. */
typedef struct meddler {
    test_sim *sim;
    int what;    /* 1 release, 2 data_init, 3 holonomic NULL, 4 corrections 99,
                  * 5 rank_tol NaN, 6 guard scale Inf, 7 the state pointer q */
    int calls;
    int release_status;
    braun_real *q_saved;
} meddler;

static int meddle(const braun_data *cd, void *u)
{
    meddler *m = u;
    braun_data *d = (braun_data *)cd;
    if (++m->calls != 3) return 0;
    braun_model *model = &m->sim->model;
    switch (m->what) {
    case 1: m->release_status = braun_data_release(d); break;
    case 2: (void)braun_data_init(d, model, m->sim->buffer, braun_data_size(model)); break;
    case 3: model->sys.holonomic = NULL; break;
    case 4: model->opt.corrections = 99; break;
    case 5: model->opt.rank_tol = NAN; break;
    case 6: d->guard.pos = INFINITY; break;
    default: m->q_saved = d->q, d->q = NULL; break;
    }
    return 0;
}

static void test_output_callback_meddling(void **state)
{
    (void)state;
    for (int what = 1; what <= 7; what++)
        for (int adaptive = 0; adaptive < 2; adaptive++) {
            ring r = {0};
            test_sim sim;
            open_ring(&sim, &r);
            meddler m = {&sim, what, 0, 0, NULL};
            assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
            const braun_adaptive ctl = {1e-8, 1e-8, 0, 0, 0, 0};
            const int st = adaptive ? braun_integrate_adaptive(&sim.data, &ctl, 1.0, 1, meddle, &m)
                                    : braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 1, meddle, &m);
            if (what == 1) {
                /* Refused, nothing released: the run completes. */
                assert_int_equal(m.release_status, BRAUN_ERR_ARGUMENT);
                assert_int_equal(st, BRAUN_OK);
                assert_true(sim.data.t == 1.0);
            } else {
                assert_int_equal(st, what == 3 ? BRAUN_ERR_MISSING_CALLBACK : BRAUN_ERR_ARGUMENT);
                assert_true(sim.data.t < 1.0);
            }
            if (what == 2) assert_non_null(strstr(sim.data.error.where, "re-initialised"));
            if (what == 3) assert_non_null(strstr(sim.data.error.where, "holonomic"));
            if (what == 4) assert_non_null(strstr(sim.data.error.where, "options.corrections"));
            if (what == 5) assert_non_null(strstr(sim.data.error.where, "options.rank_tol"));
            if (what == 6) assert_non_null(strstr(sim.data.error.where, "guard.pos"));
            if (what == 7) {
                assert_non_null(strstr(sim.data.error.where, "state pointer q"));
                sim.data.q = m.q_saved;
            }
            sim.model.sys.holonomic = ring_holonomic;
            test_sim_close(&sim);
        }
}

/* braun_data_release from a system callback while the stages run: refused
 * (the stages would go on without their scratch). */
static int release_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                          void *u)
{
    ring *r = u;
    (void)t; (void)q; (void)v;
    Q[0] = 0;
    Q[1] = -9.81;
    if (r->d && r->inner_calls == 0) {
        r->inner_calls++;
        r->inner_status = braun_data_release(r->d);
    }
    return 0;
}

static void test_release_from_system_callback(void **state)
{
    (void)state;
    ring r = {0};
    braun_system s = ring_system(&r);
    s.forces = release_forces;
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    r.d = &sim.data;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    assert_int_equal(r.inner_status, BRAUN_ERR_ARGUMENT);
    assert_non_null(sim.data.priv);
    r.d = NULL;
    /* Outside a run release succeeds, and twice. */
    assert_int_equal(braun_data_release(&sim.data), BRAUN_OK);
    assert_int_equal(braun_data_release(&sim.data), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_ARGUMENT);
    free(sim.buffer);
}

/* A time written into the data that is not finite, and a guard scale a
 * program set to NaN: refused, named. */
static void test_written_fields_checked(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    sim.data.guard.vel0 = NAN;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "guard.vel0"));
    sim.data.guard.vel0 = 0;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    const braun_real t = sim.data.t;
    sim.data.t = NAN;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "state t"));
    sim.data.t = t;
    /* The state's pointers are the library's: a program that wrote one
     * (NULL here) is refused by every call, never written through. */
    braun_real *const q = sim.data.q;
    sim.data.q = NULL;
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "state pointer q"));
    sim.data.q = q;
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-2), BRAUN_OK);
    test_sim_close(&sim);
}

/* Φ turns NaN at a state a step reached: every driver says
 * BRAUN_ERR_DIVERGED naming "constraint Φ" (braun_integrate's final check
 * of the kept state said BRAUN_ERR_NONFINITE, "position residual norm"). */
static void test_nan_phi_named_by_every_driver(void **state)
{
    (void)state;
    for (int drv = 0; drv < 3; drv++) {
        ring r = {0};
        r.nan_phi_after = 0.503;
        test_sim sim;
        open_ring(&sim, &r);
        assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
        int st = BRAUN_OK;
        const braun_adaptive ctl = {1e-8, 1e-8, 0, 0, 0, 0};
        if (drv == 0)
            for (int k = 0; k < 300 && !st; k++) st = braun_step(&sim.data, BRAUN_RK4, 1e-2);
        else if (drv == 1)
            st = braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 3, 0, NULL, NULL);
        else
            st = braun_integrate_adaptive(&sim.data, &ctl, 3, 0, NULL, NULL);
        assert_int_equal(st, BRAUN_ERR_DIVERGED);
        assert_string_equal(sim.data.error.where, "constraint Φ");
        assert_int_equal(sim.data.error.index, 0);
        assert_true(sim.data.t <= 0.503 + 1e-2);
        test_sim_close(&sim);
    }
}

/* The adaptive driver's limits: a maximum set below the default minimum
 * is refused (it ran steps below h_min), and a bad atol is named as atol
 * (it was reported as rtol, with rtol's value). */
static void test_adaptive_limits_named(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    braun_adaptive ctl = {1e-6, 1e-8, 0, 0, 1e-14, 0};
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "h_max"));
    assert_true(sim.data.t == 0 && sim.data.stats.steps == 0);
    ctl.h_min = 1e-15; /* both the program's: a valid pair */
    ctl.max_steps = 10;
    assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1, 0, NULL, NULL),
                     BRAUN_ERR_TOO_MANY_STEPS);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    const braun_adaptive bad_atol = {1e-6, INFINITY, 0, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&sim.data, &bad_atol, 1, 0, NULL, NULL),
                     BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "atol"));
    assert_true(isinf(sim.data.error.value));
    test_sim_close(&sim);
}

/* braun_eval at a state off the constraints with a tiny h: the corrections
 * over h overflow — an error, not Inf with BRAUN_OK. */
static void test_eval_overflow_refused(void **state)
{
    (void)state;
    ring r = {0};
    test_sim sim;
    open_ring(&sim, &r);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    const braun_real off[2] = {1.01, 0};
    braun_real qd[2], vd[2];
    assert_int_equal(braun_eval(&sim.data, 0, off, v0, 4.9e-324, qd, vd), BRAUN_ERR_NONFINITE);
    assert_non_null(strstr(sim.data.error.where, "braun_eval"));
    assert_int_equal(braun_eval(&sim.data, 0, off, v0, 1e-3, qd, vd), BRAUN_OK);
    test_sim_close(&sim);
}

/* A data never initialised, one whose init failed, one released: every
 * call refuses it, saying so; a short buffer's message gives both sizes. */
static void test_unready_data_named(void **state)
{
    (void)state;
    ring r = {0};
    braun_data zero;
    memset(&zero, 0, sizeof zero);
    assert_int_equal(braun_step(&zero, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(zero.error.where, "not initialised"));
    test_sim sim;
    open_ring(&sim, &r);
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    braun_data_release(&sim.data);
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT);
    assert_non_null(strstr(sim.data.error.where, "released"));
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 1, 0, NULL, NULL), BRAUN_ERR_ARGUMENT);
    braun_data_release(&sim.data); /* twice: safe */
    const size_t need = braun_data_size(&sim.model);
    assert_int_equal(braun_data_init(&sim.data, &sim.model, sim.buffer, need - 1), BRAUN_ERR_BUFFER);
    char what[256], want[64];
    braun_error_format(&sim.data, what, sizeof what);
    snprintf(want, sizeof want, "of %zu bytes is smaller than braun_data_size() = %zu", need - 1, need);
    assert_non_null(strstr(what, want));
    assert_int_equal(braun_step(&sim.data, BRAUN_RK4, 1e-3), BRAUN_ERR_ARGUMENT); /* failed init */
    free(sim.buffer);
}

/* The scene helpers a program calls refuse what does not exist — a
 * point or body index out of range, no function, an unknown kind — with a
 * status or NaN, instead of reading past the arrays. */
static void test_scene_helpers_refuse(void **state)
{
    (void)state;
    static const char text[] =
        "{\"name\": \"p\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": 1,"
        " \"position\": [1, 0]}], \"joints\": [{\"type\": \"distance\", \"a\": [0, 0], \"b\": \"b\"}]}";
    char err[256];
    braun_scene_file *f = braun_scene_load_text("inline.json", text, sizeof text - 1, err, sizeof err);
    assert_non_null(f);
    const braun_scene *sc = &f->scene;
    braun_real q[2] = {1, 0}, v[2] = {0, 0}, pos[3], xy[2];
    assert_int_equal(braun_scene_point_state(sc, 0, q, v, pos, NULL), BRAUN_OK);
    assert_int_equal(braun_scene_point_state(sc, sc->npoints, q, v, pos, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_point_state(sc, -1, q, v, pos, NULL), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_point_position(sc, 5, q, xy), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_point_position(NULL, 0, q, xy), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_initial_point(sc, 1000, pos), BRAUN_ERR_ARGUMENT);
    assert_true(isnan(braun_scene_initial_distance(sc, 0, 1000)));
    assert_true(isnan(braun_scene_initial_angle(sc, 7)));
    assert_true(braun_scene_initial_angle(sc, -1) == 0); /* the ground */
    assert_true(isnan(braun_scene_initial_angle(sc, -2)));   /* it gave 0 */
    /* A body past the last: body_angle read beyond the bodies (a crash). */
    braun_real th = 0, om = 0;
    assert_int_equal(braun_scene_body_angle(sc, sc->nbodies, q, v, &th, &om), BRAUN_ERR_ARGUMENT);
    assert_true(isnan(th) && isnan(om));
    assert_int_equal(braun_scene_body_angle(sc, 100000000, q, v, &th, &om), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_body_angle(sc, -2, q, v, &th, &om), BRAUN_ERR_ARGUMENT);
    assert_true(isnan(th));
    assert_int_equal(braun_scene_body_angle(NULL, 0, q, v, &th, &om), BRAUN_ERR_ARGUMENT);
    assert_int_equal(braun_scene_body_angle(sc, -1, q, v, &th, &om), -1); /* the ground: no angle */
    assert_true(th == 0 && om == 0);
    assert_int_equal(braun_scene_initial_state(sc, q, v), BRAUN_OK);
    assert_int_equal(braun_scene_initial_state(sc, NULL, v), BRAUN_ERR_ARGUMENT);
    braun_scene unbuilt;
    memset(&unbuilt, 0, sizeof unbuilt);
    assert_int_equal(braun_scene_initial_state(&unbuilt, q, v), BRAUN_ERR_ARGUMENT);
    braun_real x = 0, dx = 0;
    assert_int_equal(braun_scene_fn_eval(NULL, 0, &x, &dx, NULL), BRAUN_ERR_ARGUMENT);
    assert_true(isnan(x) && isnan(dx));
    braun_scene_fn odd;
    memset(&odd, 0, sizeof odd);
    odd.kind = (braun_scene_fn_kind)99;
    x = 0;
    assert_int_equal(braun_scene_fn_eval(&odd, 0, &x, NULL, NULL), BRAUN_ERR_ARGUMENT);
    assert_true(isnan(x));
    odd.kind = BRAUN_FN_CONSTANT;
    odd.a = 2.5;
    assert_int_equal(braun_scene_fn_eval(&odd, 0, &x, NULL, NULL), BRAUN_OK);
    assert_true(x == 2.5);
    braun_scene_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_system_changed_after_init),
        cmocka_unit_test(test_hand_filled_model),
        cmocka_unit_test(test_failed_set_state_changes_nothing),
        cmocka_unit_test(test_reentry_from_system_callback),
        cmocka_unit_test(test_reentry_from_output_callback),
        cmocka_unit_test(test_output_callback_meddling),
        cmocka_unit_test(test_release_from_system_callback),
        cmocka_unit_test(test_written_fields_checked),
        cmocka_unit_test(test_nan_phi_named_by_every_driver),
        cmocka_unit_test(test_adaptive_limits_named),
        cmocka_unit_test(test_eval_overflow_refused),
        cmocka_unit_test(test_unready_data_named),
        cmocka_unit_test(test_scene_helpers_refuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
