/* What docs/api.md promises about the API, checked one statement at a
 * time (issue 15): the output callback's schedule (every = 0), the calls
 * allowed inside it (braun_residuals, braun_energy: they change nothing),
 * the statistics (reset by braun_set_state, accumulated by the drivers),
 * DOPRI5 through braun_step, buffers at any alignment, the rule for a
 * potential that depends on time (Eq. 18), the energy correction on a
 * driven scene, and the order of BRAUN_PER_STAGE. Every reference is
 * independent of libbraun: closed forms (braun_reference.h: Jacobi
 * elliptic functions; here: an oscillator with a ramp force, a particle on
 * a string of prescribed length) or quadrature done here. Bounds are a few
 * times the values measured on x86-64, gcc 12, -O2 (beside each). */
#include <limits.h>

#include "test_util.h"
#include "braun_reference.h"
#include "braun_scene_file.h"
#include "test_systems.h"

/* ------------------------------------------------------------------ */
/* Helpers                                                            */

typedef struct calls {
    int n;
    double t[64];
} calls;

static int record_call(const braun_data *d, void *u)
{
    calls *c = u;
    if (c->n < 64) c->t[c->n] = (double)d->t;
    c->n++;
    return 0;
}

static const braun_builtin *builtin(const char *name)
{
    const braun_builtin *b = braun_builtin_find(name);
    assert_non_null(b);
    return b;
}

static void open_builtin(test_sim *sim, const char *name, unsigned corr)
{
    const braun_builtin *b = builtin(name);
    assert_int_equal(test_sim_open(sim, &b->sys, corr), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim->data, 0, b->q0, b->v0), BRAUN_OK);
}

/* ------------------------------------------------------------------ */
/* api.md, "Integrate": every = 0 (or < 0) reports the start and the end
 * only; every = K every K-th step and the end, the end once. */
static void test_every_zero(void **state)
{
    (void)state;
    const long everies[3] = {0, -3, 3}; /* x 10 steps of 0.01 s */
    for (int e = 0; e < 3; e++) {
        for (int steps = 9; steps <= 10; steps++) {
            test_sim sim;
            calls c = {0, {0}};
            open_builtin(&sim, "pendulum", BRAUN_CORRECT_ALL);
            assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 0.01, 0.1 * steps, everies[e] * 10,
                                             record_call, &c),
                             BRAUN_OK);
            if (everies[e] <= 0) {
                assert_int_equal(c.n, 2);
            } else {
                /* t = 0, 0.3, 0.6, 0.9 and (10 steps) the end 1.0 */
                assert_int_equal(c.n, steps == 9 ? 4 : 5);
                for (int k = 1; k < c.n - 1; k++) assert_near(c.t[k], 0.3 * k, 1e-15);
            }
            assert_true(c.t[0] == 0);
            assert_near(c.t[c.n - 1], 0.1 * steps, 1e-15);
            test_sim_close(&sim);
        }
    }
    /* The adaptive driver: the same rule over accepted steps. */
    for (int e = 0; e < 2; e++) {
        test_sim sim;
        calls c = {0, {0}};
        open_builtin(&sim, "pendulum", BRAUN_CORRECT_ALL);
        braun_adaptive ctl = {1e-6, 1e-8, 0, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 1.0, everies[e], record_call, &c),
                         BRAUN_OK);
        assert_true(sim.data.stats.steps > 2);
        assert_int_equal(c.n, 2);
        assert_true(c.t[0] == 0 && c.t[1] == 1.0);
        test_sim_close(&sim);
    }
}

/* A non-zero return stops the driver with BRAUN_STOPPED, the data at the
 * state the callback saw. */
static int stop_third(const braun_data *d, void *u)
{
    calls *c = u;
    record_call(d, u);
    return c->n == 3;
}

static void test_output_callback_stops(void **state)
{
    (void)state;
    for (int adaptive = 0; adaptive < 2; adaptive++) {
        test_sim sim;
        calls c = {0, {0}};
        open_builtin(&sim, "pendulum", BRAUN_CORRECT_ALL);
        braun_adaptive ctl = {1e-6, 1e-8, 0, 0, 0, 0};
        const int st = adaptive ? braun_integrate_adaptive(&sim.data, &ctl, 1.0, 1, stop_third, &c)
                                : braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 5, stop_third, &c);
        assert_int_equal(st, BRAUN_STOPPED);
        assert_int_equal(c.n, 3);
        assert_true(sim.data.t == c.t[2]);
        assert_true(c.t[2] > 0 && c.t[2] < 1.0);
        if (!adaptive) assert_near(c.t[2], 0.1, 1e-15); /* steps 5 and 10 */
        assert_int_equal(sim.data.stats.steps, adaptive ? 2 : 10);
        test_sim_close(&sim);
    }
}

/* ------------------------------------------------------------------ */
/* api.md, "The output callback": braun_residuals and braun_energy may be
 * called on the data inside it; they change neither the run (the same
 * states, bit for bit) nor its statistics — with the corrections off too,
 * where the adaptive driver takes an accepted step's last stage as the
 * next one's first (first same as last): the residuals kept from that
 * stage were read after the callback, which had overwritten them with the
 * reported state's, and the error test then compared each end with a stale
 * start (a double pendulum stopped STEP_TOO_SMALL at t = 0.35 s). */
typedef struct probe {
    braun_data *d; /* the same data, not const: passed through user */
    int calls;
    double maxpos, maxE;
} probe;

static int probe_out(const braun_data *d, void *u)
{
    probe *p = u;
    braun_real pos, vel, en, E;
    assert_ptr_equal(d, p->d);
    assert_int_equal(braun_residuals(p->d, d->t, d->q, d->v, &pos, &vel, &en), BRAUN_OK);
    assert_int_equal(braun_energy(p->d, d->t, d->q, d->v, &E), BRAUN_OK);
    p->maxpos = fmax(p->maxpos, (double)pos);
    p->maxE = fmax(p->maxE, (double)en);
    p->calls++;
    return 0;
}

static void run_probed(const char *name, unsigned corr, int adaptive, int with_probe, braun_real *q,
                       braun_real *v, braun_stats *stats, probe *p)
{
    test_sim sim;
    open_builtin(&sim, name, corr);
    memset(p, 0, sizeof *p);
    p->d = &sim.data;
    braun_output_fn out = with_probe ? probe_out : NULL;
    if (adaptive) {
        braun_adaptive ctl = {1e-8, 1e-10, 0, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&sim.data, &ctl, 5.0, 1, out, p), BRAUN_OK);
    } else {
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 5.0, 1, out, p), BRAUN_OK);
    }
    for (int i = 0; i < sim.model.sys.n; i++) {
        q[i] = sim.data.q[i];
        v[i] = sim.data.v[i];
    }
    *stats = sim.data.stats;
    test_sim_close(&sim);
}

static void test_residuals_in_output_callback(void **state)
{
    (void)state;
    const char *names[2] = {"slider-crank", "four-bar"};
    const unsigned corrs[2] = {BRAUN_CORRECT_ALL, BRAUN_CORRECT_NONE};
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 2; c++)
        for (int adaptive = 0; adaptive < 2; adaptive++) {
            braun_real q0[8], v0[8], q1[8], v1[8];
            braun_stats s0, s1;
            probe p0, p1;
            run_probed(names[k], corrs[c], adaptive, 0, q0, v0, &s0, &p0);
            run_probed(names[k], corrs[c], adaptive, 1, q1, v1, &s1, &p1);
            print_message("%s, %s, corrections %s: %d callbacks, max |Phi_q| %.3g, |Phi_e| %.3g; "
                          "%ld steps\n",
                          names[k], adaptive ? "dopri5 adaptive" : "rk4", c ? "off" : "on", p1.calls,
                          p1.maxpos, p1.maxE, s1.steps);
            assert_true(p1.calls == s1.steps + 1);
            assert_memory_equal(q0, q1, 6 * sizeof q0[0]);
            assert_memory_equal(v0, v1, 6 * sizeof v0[0]);
            assert_memory_equal(&s0, &s1, sizeof s0);
            /* measured 2.4e-8 (four-bar, rk4); without the corrections the
             * four-bar at h = 1e-2 drifts (0.26), the paper's point */
            if (!c) assert_le(p1.maxpos, 1e-6);
        }
}

/* The right-hand sides counted when the run's first state (t0) is
 * reported. */
static int start_rhs(const braun_data *d, void *u)
{
    long *start = u;
    if (*start < 0) *start = d->stats.rhs_evals;
    return 0;
}

/* ------------------------------------------------------------------ */
/* api.md, "Statistics": braun_set_state starts them from zero (a constant
 * M's one factorization, made by braun_data_init, stays counted); the
 * drivers and braun_step add to them; RK4 takes 4 right-hand sides per
 * step, DOPRI5 stepped by braun_step 6 (its 7th stage, weight 0, serves
 * only the adaptive driver's error estimate). */
static void test_statistics(void **state)
{
    (void)state;
    test_sim sim;
    open_builtin(&sim, "slider-crank", BRAUN_CORRECT_ALL);
    assert_int_equal(sim.data.stats.mass_factorizations, 1); /* constant M: at data_init */
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 1.0, 0, NULL, NULL), BRAUN_OK);
    assert_int_equal(sim.data.stats.steps, 100);
    assert_int_equal(sim.data.stats.rhs_evals, 400);
    assert_int_equal(sim.data.stats.constraint_factorizations, 400);
    /* a second call continues the count */
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 2.0, 0, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_step(&sim.data, BRAUN_DOPRI5, 1e-2), BRAUN_OK);
    assert_int_equal(sim.data.stats.steps, 201);
    assert_int_equal(sim.data.stats.rhs_evals, 806);
    assert_int_equal(sim.data.stats.mass_factorizations, 1);
    /* a new state: a new run */
    const braun_builtin *b = builtin("slider-crank");
    sim.data.work_in = 3;
    assert_int_equal(braun_set_state(&sim.data, 0, b->q0, b->v0), BRAUN_OK);
    const braun_stats zero = {0, 0, 0, 1, 0, 0, 0, 0};
    assert_memory_equal(&sim.data.stats, &zero, sizeof zero);
    assert_true(sim.data.work_in == 0 && sim.data.t == 0);
    /* braun.h: a counter stops at LONG_MAX, never wraps (a long run on a
     * 32-bit target; signed overflow would be undefined: UBSan's run of
     * this test would report it) */
    sim.data.stats.steps = LONG_MAX - 1;
    sim.data.stats.rhs_evals = LONG_MAX - 2;
    sim.data.stats.constraint_factorizations = LONG_MAX;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 0.03, 0, NULL, NULL), BRAUN_OK);
    assert_true(sim.data.stats.steps == LONG_MAX && sim.data.stats.rhs_evals == LONG_MAX &&
                sim.data.stats.constraint_factorizations == LONG_MAX);
    test_sim_close(&sim);

    /* The adaptive driver: 7 per attempt (6 when it repeats a rejected
     * one), and one more for an accepted step whose end is next to a
     * singular configuration (the four-bar passes them; measured over 30 s:
     * 2802 attempts, 3 more). */
    test_sim fb;
    open_builtin(&fb, "four-bar", BRAUN_CORRECT_ALL);
    braun_adaptive ctl = {1e-10, 1e-10, 1e-2, 0, 0, 0};
    assert_int_equal(braun_integrate_adaptive(&fb.data, &ctl, 30.0, 0, NULL, NULL), BRAUN_OK);
    const long attempts = fb.data.stats.steps + fb.data.stats.rejected_steps;
    print_message("four-bar adaptive 30 s: %ld attempts, %ld right-hand sides\n", attempts,
                  fb.data.stats.rhs_evals);
    const long retries = fb.data.stats.rejected_steps; /* each repeats a start: 6 */
    assert_true(fb.data.stats.rhs_evals > 7 * attempts - retries);
    assert_true(fb.data.stats.rhs_evals <= 7 * attempts - retries + fb.data.stats.steps);
    test_sim_close(&fb);

    /* Rejections, each followed by an attempt that keeps its first stage:
     * 7 per attempt less one per rejection (the slider-crank at rtol 1e-8,
     * 20 s: 81 rejections, 8639 -> 8558 right-hand sides; the same steps).
     * With the corrections off, first same as last: 6 per attempt but the
     * first (and a few whose end lost a bit or a rank: at most 1 %). */
    for (int corr = 0; corr < 2; corr++) {
        test_sim sc;
        open_builtin(&sc, "slider-crank", corr ? BRAUN_CORRECT_ALL : 0);
        braun_adaptive c8 = {1e-8, 1e-10, 1e-3, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&sc.data, &c8, 20.0, 0, NULL, NULL), BRAUN_OK);
        const long att = sc.data.stats.steps + sc.data.stats.rejected_steps;
        print_message("slider-crank adaptive 20 s, corrections %s: %ld attempts (%ld rejected), %ld right-hand "
                      "sides\n", corr ? "all" : "off", att, sc.data.stats.rejected_steps, sc.data.stats.rhs_evals);
        assert_true(sc.data.stats.rejected_steps > 10);
        if (corr) {
            assert_true(sc.data.stats.rhs_evals >= 7 * att - sc.data.stats.rejected_steps);
            assert_true(sc.data.stats.rhs_evals <= 7 * att - sc.data.stats.rejected_steps + sc.data.stats.steps / 100);
        } else {
            assert_true(sc.data.stats.rhs_evals >= 6 * att + 1);
            assert_true(sc.data.stats.rhs_evals <= 6 * att + 1 + att / 100);
        }
        test_sim_close(&sc);
    }

    /* A new adaptive run's start: one per point its projection measures
     * (2 on the constraints with the position correction, 1 with the
     * velocity correction alone, none with neither; 5 for the pendulum 1e-3
     * off its rod), seen by the output callback at t0; then the first
     * attempt evaluates the start again. The pendulum has no singular
     * configuration: start + 7 per attempt less one per rejection, exactly
     * (docs said one at the start whatever the corrections). */
    static const unsigned corrs[5] = {BRAUN_CORRECT_ALL, BRAUN_CORRECT_POSITION, BRAUN_CORRECT_VELOCITY, 0,
                                      BRAUN_CORRECT_ALL};
    static const long at_start[5] = {2, 2, 1, 0, 5};
    for (int k = 0; k < 5; k++) {
        test_sim pd;
        const braun_builtin *p = builtin("pendulum");
        assert_int_equal(test_sim_open(&pd, &p->sys, corrs[k]), BRAUN_OK);
        braun_real q[2] = {p->q0[0], p->q0[1]};
        if (k == 4) q[0] *= 1 + 1e-3;
        assert_int_equal(braun_set_state(&pd.data, 0, q, p->v0), BRAUN_OK);
        long start = -1;
        braun_adaptive c8 = {1e-8, 1e-8, 0, 0, 0, 0};
        assert_int_equal(braun_integrate_adaptive(&pd.data, &c8, 1.0, 0, start_rhs, &start), BRAUN_OK);
        const long att = pd.data.stats.steps + pd.data.stats.rejected_steps;
        print_message("pendulum adaptive, corrections %u%s: %ld at the start, %ld attempts (%ld rejected), %ld "
                      "right-hand sides\n", corrs[k], k == 4 ? " (1e-3 off)" : "", start, att,
                      pd.data.stats.rejected_steps, pd.data.stats.rhs_evals);
        assert_int_equal(start, at_start[k]);
        if (corrs[k]) assert_int_equal(pd.data.stats.rhs_evals, start + 7 * att - pd.data.stats.rejected_steps);
        test_sim_close(&pd);
    }

    /* A mass that depends on q (Andrews' mechanism): nothing is factored
     * before the first step, and the count restarts from 0. */
    test_sim an;
    assert_int_equal(test_sim_open(&an, &braun_andrews_system, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&an.data, 0, braun_andrews_q0, braun_andrews_v0), BRAUN_OK);
    assert_int_equal(an.data.stats.mass_factorizations, 0);
    assert_int_equal(braun_step(&an.data, BRAUN_RK4, 1e-5), BRAUN_OK);
    assert_int_equal(an.data.stats.mass_factorizations, 4);
    assert_int_equal(braun_set_state(&an.data, 0, braun_andrews_q0, braun_andrews_v0), BRAUN_OK);
    assert_int_equal(an.data.stats.mass_factorizations, 0);
    assert_int_equal(an.data.stats.steps, 0);
    test_sim_close(&an);
}

/* ------------------------------------------------------------------ */
/* Trajectory error of a built-in model against its closed form, over the
 * state at the end of every step. */
typedef struct against {
    const braun_builtin *model;
    braun_reference ref;
    double worst;
} against;

static void against_check(against *a, const braun_data *d)
{
    double qr[BRAUN_MODEL_MAX_N], vr[BRAUN_MODEL_MAX_N], s = 0;
    assert_int_equal(braun_reference_eval(&a->ref, (double)d->t, qr, vr), 0);
    for (int i = 0; i < a->model->sys.n; i++) s += (d->q[i] - qr[i]) * (d->q[i] - qr[i]);
    a->worst = fmax(a->worst, sqrt(s));
}

static int against_out(const braun_data *d, void *u)
{
    against_check(u, d);
    return 0;
}

/* ------------------------------------------------------------------ */
/* api.md, braun_integrate: N = max(1, ceil(R - a)) steps, R the span over
 * h, a = min(1/2, 1e-9 R) in double; the last ends on t_end exactly, a
 * leftover of at most a steps folded into it (docs said "shortened"). */
typedef struct last_steps {
    double prev, last;
} last_steps;
static int record_last(const braun_data *d, void *u)
{
    last_steps *r = u;
    r->last = (double)d->t - r->prev;
    r->prev = (double)d->t;
    return 0;
}

static void test_last_fixed_step(void **state)
{
    (void)state;
    static const struct {
        double t_end;
        long steps;
        double last;
    } cases[] = {{1 + 1e-10, 100, 0.0100000001}, {1 + 1e-8, 101, 1e-8}, {1 - 1e-10, 100, 0.0099999999},
                 {1, 100, 0.01}};
    for (int k = 0; k < 4; k++) {
        test_sim sim;
        open_builtin(&sim, "pendulum", BRAUN_CORRECT_ALL);
        last_steps r = {0, 0};
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 0.01, cases[k].t_end, 1, record_last, &r), BRAUN_OK);
        print_message("t_end = 1%+.0e: %ld steps, the last %.17g\n", cases[k].t_end - 1, sim.data.stats.steps, r.last);
        assert_int_equal(sim.data.stats.steps, cases[k].steps);
        assert_true(sim.data.t == cases[k].t_end);
        assert_true(fabs(r.last - cases[k].last) < 1e-15);
        test_sim_close(&sim);
    }
}

/* ------------------------------------------------------------------ */
/* api.md, "Step": braun_step takes BRAUN_DOPRI5 (its 5th-order solution,
 * no error control); stepped by hand it converges with order 5. */
static double dopri5_by_hand(const char *name, double h, double T)
{
    test_sim sim;
    against a = {builtin(name), {0}, 0};
    open_builtin(&sim, name, BRAUN_CORRECT_ALL);
    assert_int_equal(braun_reference_init(&a.ref, a.model, 0), 0);
    const long steps = lround(T / h);
    for (long i = 0; i < steps; i++) {
        assert_int_equal(braun_step(&sim.data, BRAUN_DOPRI5, h), BRAUN_OK);
        against_check(&a, &sim.data);
    }
    assert_near(sim.data.t, T, 1e-12);
    assert_int_equal(sim.data.stats.steps, steps);
    /* 6 right-hand sides a step: the 7th stage (weight 0, DOPRI5's
     * first-same-as-last) serves only an error estimate, which braun_step
     * does not make. */
    assert_int_equal(sim.data.stats.rhs_evals, 6 * steps);
    test_sim_close(&sim);
    return a.worst;
}

static void test_dopri5_through_braun_step(void **state)
{
    (void)state;
    const double hs[4] = {0.1, 0.05, 0.025, 0.0125};
    double e[4];
    for (int i = 0; i < 4; i++) e[i] = dopri5_by_hand("pendulum", hs[i], 2.0);
    for (int i = 1; i < 4; i++) {
        const double p = log(e[i - 1] / e[i]) / log(2.0);
        print_message("dopri5 by braun_step, pendulum 2 s: h %.3g error %.3g, order %.2f\n", hs[i],
                      e[i], p);
        /* measured 6.09, 5.67, 6.17 (the slider-crank: 5.7, 5.5, 5.3 from
         * h = 0.025 to 0.003125, tending to 5); the embedded 4th-order
         * solution would give 4 */
        assert_true(p > 4.6 && p < 6.6);
    }
    /* RK4 over the same steps is an order less accurate. */
    test_sim sim;
    against a = {builtin("pendulum"), {0}, 0};
    open_builtin(&sim, "pendulum", BRAUN_CORRECT_ALL);
    assert_int_equal(braun_reference_init(&a.ref, a.model, 0), 0);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 0.025, 2.0, 1, against_out, &a),
                     BRAUN_OK);
    print_message("rk4 at h 0.025: error %.3g\n", a.worst);
    assert_true(a.worst > 100 * e[2]); /* measured 6.8e-6 against 1.1e-8 */
    test_sim_close(&sim);
}

/* ------------------------------------------------------------------ */
/* api.md, "Data": the buffer may start at any address; braun_data_size
 * includes the slack, so exactly that many bytes work at every offset,
 * and the run is the same bit for bit. One byte less is BRAUN_ERR_BUFFER. */
static void test_buffer_alignment(void **state)
{
    (void)state;
    const braun_builtin *b = builtin("slider-crank");
    braun_model model;
    assert_int_equal(braun_model_init(&model, &b->sys), BRAUN_OK);
    const size_t bytes = braun_data_size(&model);
    unsigned char *raw = malloc(bytes + 64);
    assert_non_null(raw);
    /* an address that is a multiple of 32: offsets 0 .. 31 from it */
    unsigned char *base = raw + (32 - (uintptr_t)raw % 32) % 32;
    braun_real q_first[6], v_first[6];
    for (int off = 0; off < 32; off++) {
        braun_data d;
        assert_int_equal(braun_data_init(&d, &model, base + off, bytes - 1), BRAUN_ERR_BUFFER);
        assert_int_equal(braun_data_init(&d, &model, base + off, bytes), BRAUN_OK);
        assert_int_equal(braun_set_state(&d, 0, b->q0, b->v0), BRAUN_OK);
        assert_int_equal(braun_integrate(&d, BRAUN_RK4, 1e-2, 2.0, 0, NULL, NULL), BRAUN_OK);
        if (off == 0) {
            memcpy(q_first, d.q, sizeof q_first);
            memcpy(v_first, d.v, sizeof v_first);
        } else {
            assert_memory_equal(q_first, d.q, sizeof q_first);
            assert_memory_equal(v_first, d.v, sizeof v_first);
        }
        braun_data_release(&d);
    }
    free(raw);
}

/* ------------------------------------------------------------------ */
/* api.md, "Driven and dissipative systems": a potential that depends
 * explicitly on time. Eq. 18 holds on the exact motion only if Ė is the
 * rate of the E the energy callback returns: with V(t, q) in E, dE_dt
 * reports ∂V/∂t and power() returns it too (b_e = −∂E/∂t − (∂E/∂q)v + Ė,
 * Eq. 19, then has it cancel); or V's force is an applied force, outside
 * E, whose power goes into power(). Reporting ∂V/∂t in dE_dt alone makes
 * the energy force pull the motion off the exact one.
 *
 * The system: x'' = −ω² x + c t/m (V = ½kx² − c t x), exact
 * x = x0 cos ωt + (v0 − c/k)/ω sin ωt + c t/k. */
enum { RAMP_IN_E = 0, RAMP_APPLIED = 1, RAMP_DT_ONLY = 2, RAMP_POWER_ONLY = 3 };
typedef struct ramp {
    int how;
} ramp;
static const double rk = 4.0, rm = 1.0, rc = 0.5;

static int ramp_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = rm;
    return 0;
}

static int ramp_forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                       void *u)
{
    (void)v; (void)u;
    Q[0] = -rk * q[0] + rc * t;
    return 0;
}

static int ramp_energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                       braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    const ramp *r = u;
    const int in_e = r->how != RAMP_APPLIED;
    if (E) *E = 0.5 * rm * v[0] * v[0] + 0.5 * rk * q[0] * q[0] - (in_e ? rc * t * q[0] : 0);
    if (dq) dq[0] = rk * q[0] - (in_e ? rc * t : 0);
    if (dv) dv[0] = rm * v[0];
    if (dt) *dt = in_e && r->how != RAMP_POWER_ONLY ? -rc * q[0] : 0; /* ∂E/∂t */
    return 0;
}

static int ramp_power(braun_real t, const braun_real *q, const braun_real *v, braun_real *P,
                      void *u)
{
    const ramp *r = u;
    /* in E: Ė = ∂V/∂t = −c x; applied: the force's power c t v */
    *P = r->how != RAMP_APPLIED ? -rc * q[0] : rc * t * v[0];
    return 0;
}

/* Max |x - exact| over the steps of RK4 h to T with every correction (the
 * energy one included); *status: how the run ended (the accuracy guard
 * on: guard = 0, off: guard < 0). */
static double ramp_run_corr(int how, double h, double T, braun_real guard, int *status,
                           unsigned corr, braun_real *q_end);

static double ramp_run(int how, double h, double T, braun_real guard, int *status)
{
    braun_real q_end;
    return ramp_run_corr(how, h, T, guard, status, BRAUN_CORRECT_ALL, &q_end);
}

static double ramp_run_corr(int how, double h, double T, braun_real guard, int *status,
                           unsigned corr, braun_real *q_end)
{
    ramp r = {how};
    braun_system s = {1, 0, 0, BRAUN_MASS_CONSTANT | (how == RAMP_DT_ONLY ? 0u : BRAUN_ENERGY_INPUT),
                      ramp_mass, ramp_forces, NULL, NULL, ramp_energy,
                      how == RAMP_DT_ONLY ? NULL : ramp_power, &r, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, corr), BRAUN_OK);
    sim.model.opt.guard = guard;
    const double x0 = 1, v0 = 0, w = sqrt(rk / rm);
    const braun_real q0[1] = {x0}, vv0[1] = {v0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, vv0), BRAUN_OK);
    double worst = 0;
    const long steps = lround(T / h);
    *status = BRAUN_OK;
    for (long i = 1; i <= steps && *status == BRAUN_OK; i++) {
        *status = braun_step(&sim.data, BRAUN_RK4, h);
        const double t = (double)sim.data.t;
        const double x = x0 * cos(w * t) + (v0 - rc / rk) / w * sin(w * t) + rc * t / rk;
        worst = fmax(worst, fabs(sim.data.q[0] - x));
    }
    *q_end = sim.data.q[0];
    test_sim_close(&sim);
    return worst;
}

static void test_time_dependent_potential(void **state)
{
    (void)state;
    const double T = 10, h = 1e-2;
    int st_in, st_app, st_dt, st_dt_off;
    const double in_e = ramp_run(RAMP_IN_E, h, T, 0, &st_in);
    const double applied = ramp_run(RAMP_APPLIED, h, T, 0, &st_app);
    (void)ramp_run(RAMP_DT_ONLY, h, T, 0, &st_dt);
    int st_p, st_p_off;
    (void)ramp_run(RAMP_POWER_ONLY, h, T, 0, &st_p);
    const double p_only_off = ramp_run(RAMP_POWER_ONLY, h, T, -1, &st_p_off);
    const double dt_only_off = ramp_run(RAMP_DT_ONLY, h, T, -1, &st_dt_off);
    print_message("ramp force, RK4 h = 1e-2, 10 s, every correction: max |x - exact| with V(t,q) "
                  "in E, dE_dt and power %.3g; as an applied force %.3g; dE_dt without power: "
                  "status %d, guard off %.3g; power without dE_dt: status %d, guard off %.3g\n",
                  in_e, applied, st_dt, dt_only_off, st_p, p_only_off);
    assert_int_equal(st_in, BRAUN_OK);
    assert_int_equal(st_app, BRAUN_OK);
    assert_le(in_e, 5e-8);    /* measured 1.8e-8 */
    assert_le(applied, 5e-8); /* measured 1.8e-8 */
    /* The wrong law: the energy residual grows by -c∫x dt from the first
     * step; the accuracy guard stops the run, and without the guard the
     * energy force drags the motion off. */
    assert_int_equal(st_dt, BRAUN_ERR_ACCURACY);
    assert_int_equal(st_dt_off, BRAUN_OK);
    assert_true(dt_only_off > 0.1); /* measured 0.54 */
    /* ∂V/∂t in power() but not in dE_dt: b_e is off by ∂V/∂t — which a
     * per-step RK4 uses only where the motion is too slow to size its
     * energy force at the step's end (energy_max_rel·g within a few ulps
     * of E: never here). Sized by Φ_e at the ideal end, from E and ∫Ė
     * alone, the run is as accurate as with the whole law (measured
     * 2.5e-8; 1.0e-2 when every step used the prediction at its start). */
    assert_int_equal(st_p, BRAUN_OK);
    assert_int_equal(st_p_off, BRAUN_OK);
    assert_le(p_only_off, 5e-8);
    /* Without the energy correction the law only feeds ∫Ė and |Φ_e|: the
     * motion is the same bit for bit, right or wrong. */
    braun_real q_end[4];
    int st_n;
    for (int how = 0; how < 4; how++) {
        (void)ramp_run_corr(how, h, T, 0, &st_n, BRAUN_CORRECT_NONE, &q_end[how]);
        assert_int_equal(st_n, BRAUN_OK);
        assert_true(q_end[how] == q_end[0]);
    }
}

/* ------------------------------------------------------------------ */
/* api.md and scene-format.md: a driven scene keeps its energy law, the
 * core adds the drive's work to Ė, and the energy correction works on it.
 * A particle on a string whose length is prescribed, L(t) = 1 + 0.2 sin t,
 * no gravity: the string's force is central, so m r² θ' = 1 holds
 * exactly; E = ½(L'² + 1/L²) (m = 1), so the drive's work up to t is
 * E(t) − E(0). */
static const char string_scene[] =
    "{\"name\": \"pulled-string\", \"bodies\": [{\"name\": \"p\", \"type\": \"particle\","
    " \"mass\": 1, \"position\": [1, 0], \"velocity\": [0.2, 1]}],"
    " \"joints\": [{\"type\": \"distance\", \"a\": [0, 0], \"b\": \"p\","
    " \"drive\": {\"type\": \"sine\", \"offset\": 1, \"amplitude\": 0.2, \"omega\": 1, \"phase\": 0}}],"
    " \"effects\": []}";

typedef struct string_watch {
    double worst_h, worst_r;
} string_watch;

static int string_out(const braun_data *d, void *u)
{
    string_watch *w = u;
    const double t = (double)d->t, L = 1 + 0.2 * sin(t);
    const double hh = (double)(d->q[0] * d->v[1] - d->q[1] * d->v[0]);
    w->worst_h = fmax(w->worst_h, fabs(hh - 1));
    w->worst_r = fmax(w->worst_r, fabs(hypot((double)d->q[0], (double)d->q[1]) - L));
    return 0;
}

static void test_energy_correction_on_a_driven_scene(void **state)
{
    (void)state;
    char err[256];
    braun_scene_file *f = braun_scene_load_text("pulled-string.json", string_scene,
                                                sizeof string_scene - 1, err, sizeof err);
    if (!f) print_error("%s\n", err);
    assert_non_null(f);
    assert_non_null(f->sys.energy);
    assert_false(f->sys.flags & BRAUN_SCLERONOMIC);
    assert_false(f->sys.flags & BRAUN_ENERGY_INPUT); /* nothing but the drive does work */
    const unsigned corr[2] = {BRAUN_CORRECT_ALL, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY};
    double worst_h[2];
    for (int k = 0; k < 2; k++) {
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &f->sys, corr[k]), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        string_watch w = {0, 0};
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-2, 20.0, 1, string_out, &w),
                         BRAUN_OK);
        const double T = 20, L = 1 + 0.2 * sin(T), Ld = 0.2 * cos(T);
        const double work = 0.5 * (Ld * Ld + 1 / (L * L)) - 0.5 * (0.04 + 1);
        braun_real pos, vel, en;
        assert_int_equal(braun_residuals(&sim.data, sim.data.t, sim.data.q, sim.data.v, &pos, &vel,
                                         &en),
                         BRAUN_OK);
        print_message("pulled string, %s, RK4 h = 1e-2, 20 s: max |r^2 theta' - 1| %.3g, max |r - L| "
                      "%.3g, int Edot %.6f - drive's work %.6f = %.3g, |Phi_e| %.3g\n",
                      k ? "position,velocity" : "all", w.worst_h, w.worst_r,
                      (double)sim.data.work_in, work, (double)sim.data.work_in - work, (double)en);
        /* measured 3.5e-11 (all), 5.9e-11; max |r - L| 1.3e-12 */
        assert_near(sim.data.work_in, work, 3e-10);
        assert_le(w.worst_r, 1e-11);
        worst_h[k] = w.worst_h;
        test_sim_close(&sim);
    }
    /* measured 4.4e-10 with the energy correction, 2.1e-10 without */
    assert_le(worst_h[0], 2e-9);
    assert_le(worst_h[1], 2e-9);
    braun_scene_free(f);

    /* Every coordinate driven (data/driven-crank.json: 6 rows, 6
     * coordinates): the energy force has no free direction (N_v = 0) and
     * the run is the one without it. */
    braun_scene_file *dc = braun_scene_load("data/driven-crank.json", err, sizeof err);
    if (!dc) print_error("%s\n", err);
    assert_non_null(dc);
    assert_int_equal(dc->scene.n, 6);
    assert_int_equal(dc->scene.m, 6);
    braun_real qf[2][6];
    for (int k = 0; k < 2; k++) {
        test_sim sim;
        assert_int_equal(test_sim_open(&sim, &dc->sys, corr[k]), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, dc->q0, dc->v0), BRAUN_OK);
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 2.0, 0, NULL, NULL), BRAUN_OK);
        memcpy(qf[k], sim.data.q, sizeof qf[k]);
        test_sim_close(&sim);
    }
    assert_memory_equal(qf[0], qf[1], sizeof qf[0]); /* measured: bit for bit */
    braun_scene_free(dc);
}

/* ------------------------------------------------------------------ */
/* api.md, "Options" (discretization), docs/method.md: per stage, RK4 is
 * second order with the position correction (with or without the velocity
 * one), third with the velocity correction alone, first once the energy
 * correction is on; per step it keeps order 4. Pendulum from the
 * horizontal, 1 s, against its closed form. */
static double pendulum_error(unsigned corr, braun_discretization disc, double h)
{
    test_sim sim;
    against a = {builtin("pendulum"), {0}, 0};
    open_builtin(&sim, "pendulum", corr);
    sim.model.opt.discretization = disc;
    assert_int_equal(braun_reference_init(&a.ref, a.model, 0), 0);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, h, 1.0, 1, against_out, &a), BRAUN_OK);
    test_sim_close(&sim);
    return a.worst;
}

static void test_per_stage_order(void **state)
{
    (void)state;
    const struct {
        unsigned corr;
        braun_discretization disc;
        const char *what;
        double lo, hi;
    } cases[] = {
        {BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY, BRAUN_PER_STAGE, "per stage, position+velocity", 1.8, 2.25},
        {BRAUN_CORRECT_POSITION, BRAUN_PER_STAGE, "per stage, position", 1.8, 2.25},
        {BRAUN_CORRECT_VELOCITY, BRAUN_PER_STAGE, "per stage, velocity", 2.7, 3.3},
        {BRAUN_CORRECT_ALL, BRAUN_PER_STAGE, "per stage, all", 0.8, 1.25},
        {BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY, BRAUN_PER_STEP, "per step, position+velocity", 3.7, 4.3},
        {BRAUN_CORRECT_ALL, BRAUN_PER_STEP, "per step, all", 3.7, 4.3},
    };
    const double hs[3] = {1e-2, 5e-3, 2.5e-3};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double e[3];
        for (int i = 0; i < 3; i++) e[i] = pendulum_error(cases[c].corr, cases[c].disc, hs[i]);
        for (int i = 1; i < 3; i++) {
            const double p = log(e[i - 1] / e[i]) / log(2.0);
            print_message("%s: h %.3g error %.3g order %.2f\n", cases[c].what, hs[i], e[i], p);
            assert_true(p > cases[c].lo && p < cases[c].hi);
        }
    }
}

/* braun.h: BRAUN_ENERGY_INPUT without an energy law still integrates
 * ∫Ė into d->work_in (the work of the applied forces) and nothing else
 * uses it. A particle of mass 2 pushed by F = 3 from rest: x = ¾t²,
 * work F·x = (9/4)t², exact for RK4 (polynomials of degree ≤ 4). */
static int push_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = 2;
    return 0;
}
static int push_force(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = 3;
    return 0;
}
static int push_power(braun_real t, const braun_real *q, const braun_real *v, braun_real *Edot, void *u)
{
    (void)t; (void)q; (void)u;
    *Edot = 3 * v[0];
    return 0;
}

static void test_energy_input_without_energy_law(void **state)
{
    (void)state;
    const braun_system s = {1, 0, 0, BRAUN_MASS_CONSTANT | BRAUN_ENERGY_INPUT, push_mass, push_force,
                            NULL, NULL, NULL, push_power, NULL, NULL, NULL};
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, 0), BRAUN_OK);
    const braun_real q0[1] = {0}, v0[1] = {0};
    assert_int_equal(braun_set_state(&sim.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 0.1, 2.0, 0, NULL, NULL), BRAUN_OK);
    assert_near(sim.data.q[0], 3.0, 1e-12);        /* ¾·2² */
    assert_near(sim.data.work_in, 9.0, 1e-12);     /* (9/4)·2² */
    test_sim_close(&sim);
    /* energy correction without the law is refused, not ignored */
    sim.buffer = NULL;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ENERGY), BRAUN_ERR_NO_ENERGY_LAW);
    free(sim.buffer);
}

/* braun_version() and braun_precision(): the library's BRAUN_VERSION and
 * braun_real, asked at run time (docs/api.md, "Version and precision"). */
static void test_version_and_precision(void **state)
{
    (void)state;
    assert_string_equal(braun_version(), BRAUN_VERSION);
    assert_string_equal(braun_precision(), sizeof(braun_real) == sizeof(float) ? "float" : "double");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_zero),
        cmocka_unit_test(test_output_callback_stops),
        cmocka_unit_test(test_residuals_in_output_callback),
        cmocka_unit_test(test_statistics),
        cmocka_unit_test(test_last_fixed_step),
        cmocka_unit_test(test_dopri5_through_braun_step),
        cmocka_unit_test(test_buffer_alignment),
        cmocka_unit_test(test_time_dependent_potential),
        cmocka_unit_test(test_energy_correction_on_a_driven_scene),
        cmocka_unit_test(test_per_stage_order),
        cmocka_unit_test(test_energy_input_without_energy_law),
        cmocka_unit_test(test_version_and_precision),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
