/* Tests of the Simbody peer adapter (compare/cmp_simbody.cpp): a simple
 * pendulum against its exact solution, the map from Simbody's initial
 * state to the target's q0, v0, a failure as a recorded row, refusals with
 * a sentence, forces and drives against the harness's own reference.
 *
 * With arguments it is also the driver of the hand measurements of
 * docs/compare.md ("Simbody"):
 *   test_simbody run TARGET T[:DT] SETTING...
 * SETTING: INTEGRATOR:VALUE[:VARIANT[:CTOL]] with INTEGRATOR rkm, rkf, rk3,
 * cpodes (VALUE: the accuracy) or fixed (VALUE: the step h; accuracy
 * Simbody's default), VARIANT the adapter's words joined by '+' ("-":
 * none). DT: the output grid (default: the target's dt_out). One line per
 * setting: status, CPU time, counts, errors against the study's reference
 * of the target. */
#include "test_util.h"

#include <gsl/gsl_errno.h>

#include "cmp.h"
#include "cmp_mech.h"
#include "cmp_peer.h"
#include "test_proj_ref.h"

/* ------------------------------------------------------------ helpers */
static void target(const char *name, cmp_target *tg)
{
    char err[512];
    if (cmp_target_find(name, tg, err, sizeof err)) {
        print_error("%s\n", err);
        fail();
    }
}

static cmp_spec spec_of(int integrator, double acc, double h, double T, double dt_out)
{
    cmp_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.method = CMP_SIMBODY;
    sp.integrator = integrator;
    sp.rtol = acc;
    sp.h = h;
    sp.T = T;
    sp.dt_out = dt_out;
    return sp;
}

/* Max over the trajectory of ||q - q_ref||_2 (and ||v - v_ref|| in *verr). */
static double traj_error(cmp_ref *ref, const cmp_traj *tr, double *verr)
{
    const int n = tr->n;
    double q[64], v[64], eq = 0, ev = 0;
    for (long j = 0; j < tr->count; j++) {
        if (cmp_ref_eval(ref, tr->t[j], q, v) != 0) return NAN;
        double sq = 0, sv = 0;
        for (int i = 0; i < n; i++) {
            sq += pow(tr->q[j * n + i] - q[i], 2);
            sv += pow(tr->v[j * n + i] - v[i], 2);
        }
        eq = fmax(eq, sqrt(sq));
        ev = fmax(ev, sqrt(sv));
    }
    if (verr) *verr = ev;
    return eq;
}

/* ------------------------------------------------------------ the pendulum */
/* data/pendulum.json: a point mass on a 1 m distance joint released from
 * the horizontal, the built-in `pendulum` whose exact solution (Jacobi
 * elliptic functions, braun_pendulum_exact) is the closed-form reference.
 * Simbody models it as a Pin at the pivot swinging the mass. */
static double pendulum_error(int integrator, double acc, double h, double T, double *verr,
                             cmp_outcome *out_keep)
{
    cmp_target tg;
    target("pendulum", &tg);
    cmp_ref *ref = cmp_ref_new(&tg, CMP_REF_CLOSED, 0);
    assert_non_null(ref);
    cmp_spec sp = spec_of(integrator, acc, h, T, 0.05);
    cmp_traj tr;
    assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 256), 0);
    cmp_outcome out;
    cmp_run(&tg, &sp, &tr, &out);
    if (out.status) print_error("%s: %s\n", out.status_name, out.detail);
    assert_int_equal(out.status, 0);
    assert_string_equal(out.status_name, "OK");
    assert_true(out.t_reached == T);
    assert_int_equal(tr.count, (long)floor(T / 0.05 + 0.5) + 1);
    assert_true(tr.t[tr.count - 1] == T);
    assert_true(out.cpu_self > 0);
    assert_true(out.counts.steps > 0);
    const double e = traj_error(ref, &tr, verr);
    if (out_keep) *out_keep = out;
    cmp_traj_free(&tr);
    cmp_ref_free(ref);
    cmp_target_free(&tg);
    return e;
}

static void test_pendulum_exact(void **state)
{
    (void)state;
    /* Runge–Kutta–Merson at accuracy 1e-8 over 5 s (about 1.4 periods):
     * measured 3.0e-8 in q, 1.3e-7 in v; the bounds are a small factor
     * above. */
    double ev;
    cmp_outcome out;
    const double e8 = pendulum_error(CMP_SB_RKM, 1e-8, 0, 5.0, &ev, &out);
    print_message("pendulum rk-merson 1e-8: |q - q_exact| = %.3g, |v - v_exact| = %.3g, "
                  "%ld steps\n", e8, ev, out.counts.steps);
    assert_le(e8, 1e-7);
    assert_le(ev, 5e-7);
    /* A looser accuracy gives a larger error (the figure follows the
     * setting: the run is Simbody's, not a copy of the reference):
     * measured 4.1e-6 at 1e-5. */
    const double e5 = pendulum_error(CMP_SB_RKM, 1e-5, 0, 5.0, NULL, NULL);
    print_message("pendulum rk-merson 1e-5: %.3g\n", e5);
    assert_true(e5 > 10 * e8);
    assert_le(e5, 2e-5);
    /* The other error-controlled integrators at 1e-8 (measured: RKF
     * 2.4e-7, RK3 8.1e-8, CPodes 1.4e-6). */
    const int others[] = {CMP_SB_RKF, CMP_SB_RK3, CMP_SB_CPODES};
    const char *const names[] = {"rk-feldberg", "rk3", "cpodes"};
    const double bound[] = {1e-6, 3e-7, 5e-6};
    for (int k = 0; k < 3; k++) {
        const double e = pendulum_error(others[k], 1e-8, 0, 5.0, NULL, NULL);
        print_message("pendulum %s 1e-8: %.3g\n", names[k], e);
        assert_le(e, bound[k]);
    }
    /* Fixed step: RKM's 4th order at h = 1e-2 and 5e-3: measured 8.9e-9
     * and 5.7e-10, the error falling by about 2^4. */
    const double f1 = pendulum_error(CMP_SB_RKM_FIXED, 0, 1e-2, 5.0, NULL, NULL);
    const double f2 = pendulum_error(CMP_SB_RKM_FIXED, 0, 5e-3, 5.0, NULL, NULL);
    print_message("pendulum fixed h = 1e-2: %.3g, 5e-3: %.3g (ratio %.3g)\n", f1, f2, f1 / f2);
    assert_le(f1, 3e-8);
    assert_true(f1 / f2 > 8 && f1 / f2 < 32);
}

/* ------------------------------------------------------------ spatial */
/* spatial-arm (cmp_simbody3.cpp: a Pin and a Ball in the tree, a spring,
 * a torsion spring on the Pin) against the harness's RK4 + projection
 * reference over 2 s: RK-Merson's fixed step at fourth order (the
 * mobilizers' quaternions included), and at accuracy 1e-8. */
static double spatial_error(int integrator, double acc, double h)
{
    cmp_target tg;
    target("spatial-arm", &tg);
    const double T = 2, dt = 0.05;
    char err[256];
    cmp_ref *ref = test_proj_ref_new(&tg, T, dt, err, sizeof err);
    assert_non_null(ref);
    assert_int_equal(cmp_ref_tabulate(ref, dt, T), 0);
    cmp_spec sp = spec_of(integrator, acc, h, T, dt);
    cmp_traj tr;
    assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 64), 0);
    cmp_outcome out;
    cmp_run(&tg, &sp, &tr, &out);
    if (out.status) print_error("%s: %s\n", out.status_name, out.detail);
    assert_int_equal(out.status, 0);
    cmp_metrics mt;
    assert_int_equal(cmp_metrics_compute(&tg, &tr, ref, &mt, NULL, NULL), 0);
    assert_true(mt.pos_max < 1e-13); /* joint coordinates: on the constraints by construction */
    cmp_traj_free(&tr);
    cmp_ref_free(ref);
    cmp_target_free(&tg);
    return mt.traj_max;
}

static void test_spatial(void **state)
{
    (void)state;
    const double f1 = spatial_error(CMP_SB_RKM_FIXED, 0, 1e-2);
    const double f2 = spatial_error(CMP_SB_RKM_FIXED, 0, 5e-3);
    const double e8 = spatial_error(CMP_SB_RKM, 1e-8, 0);
    print_message("spatial-arm fixed h = 1e-2: %.3g, 5e-3: %.3g (ratio %.3g); rk-merson 1e-8: %.3g\n",
                  f1, f2, f1 / f2, e8);
    /* Measured 8.9e-7 and 5.8e-8 (ratio 15.4), and 1.5e-8 at 1e-8. */
    assert_true(f1 / f2 > 8 && f1 / f2 < 32);
    assert_le(f1, 1.5e-6);
    assert_le(e8, 5e-8);
}

/* ------------------------------------------------------------ the state map */
/* Simbody's initial state (mobilizer q, u set from the links' poses) maps
 * back to the target's q0, v0 through cmp_mech_state (cmp_mech3_state for
 * the spatial scenes: quaternions and ω), for every shipped scene Simbody
 * can express; and Integrator::initialize() leaves it where it is (the
 * scenes start on their constraints). */
static void test_initial_state(void **state)
{
    (void)state;
    static const char *const names[] = {
        "pendulum", "double-pendulum", "slider-crank", "four-bar", "chain-5",
        "parallelogram-redundant", "driven-crank", "damped-motor", "sleigh",
        "data/iftomm/a01-pendulum.json", "data/iftomm/a02-n-four-bar.json",
        "data/iftomm/a03-andrews.json", "spatial-arm", "data/iftomm/a04-bricard.json",
        "data/iftomm/a05-flyball-governor.json",
    };
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        cmp_target tg;
        target(names[k], &tg);
        char why[256] = "";
        if (!cmp_simbody_supports(&tg, why, sizeof why)) {
            print_error("%s: refused: %s\n", names[k], why);
            fail();
        }
        const int n = tg.sys.n;
        double q[128], v[128], moved = NAN;
        assert_true(n <= 128);
        cmp_spec sp = spec_of(CMP_SB_RKM, 1e-6, 0, 1, 0.05);
        if (cmp_simbody_initial_state(&tg, &sp, q, v, &moved, why, sizeof why)) {
            print_error("%s: %s\n", names[k], why);
            fail();
        }
        double dq = 0, dv = 0;
        for (int i = 0; i < n; i++) {
            dq = fmax(dq, fabs(q[i] - tg.q0[i]));
            dv = fmax(dv, fabs(v[i] - tg.v0[i]));
        }
        print_message("%-32s n = %2d  |q - q0| = %.2g  |v - v0| = %.2g  initialize moved %.2g\n",
                      names[k], n, dq, dv, moved);
        assert_le(dq, 1e-12);
        assert_le(dv, 1e-12);
        assert_le(moved, 1e-12);
        /* The run's first sample is that state too. */
        cmp_traj tr;
        cmp_outcome out;
        assert_int_equal(cmp_traj_init(&tr, n, 8), 0);
        sp.T = 0.05;
        cmp_run(&tg, &sp, &tr, &out);
        assert_int_equal(out.status, 0);
        assert_true(tr.count >= 1 && tr.t[0] == 0);
        for (int i = 0; i < n; i++) {
            assert_near(tr.q[i], tg.q0[i], 1e-12);
            assert_near(tr.v[i], tg.v0[i], 1e-12);
        }
        cmp_traj_free(&tr);
        cmp_target_free(&tg);
    }
}

/* ------------------------------------------------------------ failures */
/* A failure is a recorded row, through cmp_run (the study's path): status
 * not 0, a name and a message, the time it happened, and the trajectory
 * kept up to the last good sample. */
static void check_failed(const cmp_outcome *out, const cmp_traj *tr, double T)
{
    print_message("failed: %s %s (t_reached %.6g, %ld samples)\n", out->status_name, out->detail,
                  out->t_reached, tr->count);
    assert_int_not_equal(out->status, 0);
    assert_true(strlen(out->status_name) > 0);
    assert_true(strcmp(out->status_name, "OK") != 0);
    assert_true(strlen(out->detail) > 10);
    assert_true(strncmp(out->detail, "at t = ", 7) == 0);
    assert_true(out->t_reached < T);
    assert_true(tr->count >= 1);
    /* Every sample is at or before the failure and finite. */
    assert_true(tr->t[tr->count - 1] <= out->t_reached + 1e-12);
    for (long j = 0; j < tr->count * tr->n; j++) {
        assert_true(isfinite(tr->q[j]));
        assert_true(isfinite(tr->v[j]));
    }
}

static void test_failure_is_a_row(void **state)
{
    (void)state;
    cmp_target tg;
    target("pendulum", &tg);
    cmp_traj tr;
    cmp_outcome out;
    assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 64), 0);
    /* An accuracy no step can meet: CPodes' first step ends in a NaN state,
     * a Simbody exception at t = 0. (Runge–Kutta–Merson
     * does not fail there: it shrinks its step until its error estimate
     * is exactly 0 and grinds on.) */
    cmp_spec sp = spec_of(CMP_SB_CPODES, 1e-300, 0, 2.0, 0.05);
    cmp_run(&tg, &sp, &tr, &out);
    check_failed(&out, &tr, sp.T);
    assert_true(out.t_reached == 0);
    assert_int_equal(tr.count, 1);
    /* RK3 at that accuracy shrinks its steps until their error estimate
     * rounds to zero and would grind on (1.9 million steps for 2 s): the
     * adapter stops it after 5000 steps in one output interval. */
    sp = spec_of(CMP_SB_RK3, 1e-300, 0, 2.0, 0.05);
    cmp_run(&tg, &sp, &tr, &out);
    check_failed(&out, &tr, sp.T);
    assert_string_equal(out.status_name, "SB_TOO_MUCH_WORK");
    assert_true(out.t_reached < 0.05);
    assert_true(out.counts.steps >= 5000 && out.counts.steps < 5100);
    cmp_traj_free(&tr);
    cmp_target_free(&tg);
    /* A fixed step too large for the motor's damping (τ0/ω0 on a light
     * crank): the run goes unstable. How the blow-up surfaces depends on
     * the BLAS Debian's alternatives select (make bench's dependencies
     * install OpenBLAS, which then takes over): with the reference BLAS
     * and LAPACK Simbody's integrator throws StepFailed (a NaN inertia) at
     * t = 72.75 after 1456 good samples; with OpenBLAS the state turns
     * non-finite first and the adapter stops the run at 72.9 (DIVERGED).
     * Either way the failure is a row with the samples before it. */
    target("damped-motor", &tg);
    assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 64), 0);
    sp = spec_of(CMP_SB_RKM_FIXED, 0, 0.05, 100.0, 0.05);
    cmp_run(&tg, &sp, &tr, &out);
    check_failed(&out, &tr, sp.T);
    if (strcmp(out.status_name, "SB_STEP_FAILED") == 0)
        assert_non_null(strstr(out.detail, "step failed"));
    else
        assert_string_equal(out.status_name, "DIVERGED");
    assert_true(out.t_reached > 10 && out.t_reached < 100);
    assert_true(tr.count > 200);
    assert_near(tr.t[tr.count - 1], out.t_reached, 1e-9);
    cmp_traj_free(&tr);
    cmp_target_free(&tg);
}

/* The fixed step is h: on an output grid that is not a multiple of h (h =
 * 0.02, dt_out = 0.05) the run reports at its steps, as MuJoCo and braun
 * do. It stepped to each grid time, and the step that landed on one was
 * shortened: 0.02, 0.02, 0.01, 120 steps over 2 s instead of 100. */
static void test_fixed_step_is_h(void **state)
{
    (void)state;
    cmp_target tg;
    target("pendulum", &tg);
    cmp_spec sp = spec_of(CMP_SB_RKM_FIXED, 0, 0.02, 2.0, 0.05);
    cmp_traj tr;
    assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 256), 0);
    cmp_outcome out;
    cmp_run(&tg, &sp, &tr, &out);
    assert_string_equal(out.status_name, "OK");
    print_message("fixed h = 0.02 over 2 s on the 0.05 s grid: %ld steps, %ld samples\n",
                  out.counts.steps, tr.count);
    assert_int_equal(out.counts.steps, 100);
    assert_int_equal(tr.count, 101);
    for (long j = 0; j < tr.count; j++) assert_near(tr.t[j], 0.02 * (double)j, 1e-12);
    /* A grid that is a multiple of h keeps the grid: h = 0.01, every 5th. */
    sp = spec_of(CMP_SB_RKM_FIXED, 0, 0.01, 2.0, 0.05);
    cmp_traj_clear(&tr);
    cmp_run(&tg, &sp, &tr, &out);
    assert_string_equal(out.status_name, "OK");
    assert_int_equal(out.counts.steps, 200);
    assert_int_equal(tr.count, 41);
    cmp_traj_free(&tr);
    cmp_target_free(&tg);
}

/* ------------------------------------------------------------ refusals */
static void test_refusals(void **state)
{
    (void)state;
    /* A universal joint has no counterpart (yet). */
    static const char *const names[] = {"tests/compare/universal-arm.json"};
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        cmp_target tg;
        target(names[k], &tg);
        char why[256] = "";
        assert_int_equal(cmp_simbody_supports(&tg, why, sizeof why), 0);
        print_message("%s: %s\n", names[k], why);
        assert_true(strlen(why) > 20);
        assert_non_null(strstr(why, "universal"));
        /* And a run says so in its row instead of running. */
        cmp_traj tr;
        cmp_outcome out;
        assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 8), 0);
        cmp_spec sp = spec_of(CMP_SB_RKM, 1e-6, 0, 1.0, 0.05);
        cmp_run(&tg, &sp, &tr, &out);
        assert_int_not_equal(out.status, 0);
        assert_string_equal(out.status_name, "UNSUPPORTED");
        assert_non_null(strstr(out.detail, "universal"));
        assert_int_equal(tr.count, 0);
        cmp_traj_free(&tr);
        cmp_target_free(&tg);
    }
    /* A constant torque (Andrews' mechanism) is in the mechanism every peer
     * gets (MuJoCo: an actuator); a torque of time only with
     * CMP_MECH_TORQUE (Simbody's Force::Custom), so MuJoCo's adapter says
     * so instead of dropping it. */
    cmp_target tg;
    target("tests/compare/torque-of-time.json", &tg);
    cmp_mech m;
    char why[256] = "";
    assert_int_equal(cmp_mech_for_target(&tg, &m, why, sizeof why), -1);
    assert_non_null(strstr(why, "torque"));
    assert_int_equal(cmp_mech_for_target_ex(&tg, CMP_MECH_TORQUE, &m, why, sizeof why), 0);
    cmp_mech_free(&m);
    assert_int_equal(cmp_simbody_supports(&tg, why, sizeof why), 1);
    cmp_target_free(&tg);
    target("data/iftomm/a03-andrews.json", &tg);
    assert_int_equal(cmp_mech_for_target(&tg, &m, why, sizeof why), 0);
    int torques = 0;
    for (int i = 0; i < m.nforces; i++) torques += m.forces[i].kind == CMP_MF_TORQUE;
    assert_int_equal(torques, 1);
    cmp_mech_free(&m);
    assert_int_equal(cmp_simbody_supports(&tg, why, sizeof why), 1);
    cmp_target_free(&tg);
    assert_non_null(cmp_simbody_version());
    assert_string_equal(cmp_simbody_version(), "3.7");
}

/* ------------------------------------------------------------ elements */
/* Scenes with the other elements against the harness's RK4 + projection
 * at a small step (cmp_proj.c, not libbraun): the driven crank (a
 * prescribed Motion), the motor, spring-damper and bearing damper of
 * damped-motor, the knife edge of the sleigh, the slider-crank's Slider +
 * Pin tree. */
static void test_elements(void **state)
{
    (void)state;
    /* Measured at accuracy 1e-10: 1.2e-11, 8.4e-10, 2.3e-10, 3.4e-11,
     * 9.8e-10, and Andrews 2.9e-9 (its torque and stiff spring). */
    static const struct {
        const char *name;
        double T, dt, bound;
    } cases[] = {
        {"driven-crank", 1.0, 0.05, 1e-9},
        {"damped-motor", 1.0, 0.05, 5e-9},
        {"sleigh", 2.0, 0.05, 1e-9},
        {"double-pendulum", 1.0, 0.05, 1e-9},
        {"parallelogram-redundant", 1.0, 0.05, 5e-9},
        {"data/iftomm/a03-andrews.json", 0.01, 1e-4, 2e-8},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        cmp_target tg;
        target(cases[k].name, &tg);
        char why[256] = "";
        const double dt = cases[k].dt, h = dt / ceil(dt / 2.5e-5 - 1e-9);
        cmp_ref *ref = cmp_ref_new_proj(&tg, cases[k].T, fmin(h, dt / 20), dt, why, sizeof why);
        if (!ref) print_error("%s: reference: %s\n", cases[k].name, why);
        assert_non_null(ref);
        cmp_spec sp = spec_of(CMP_SB_RKM, 1e-10, 0, cases[k].T, dt);
        cmp_traj tr;
        cmp_outcome out;
        assert_int_equal(cmp_traj_init(&tr, tg.sys.n, 64), 0);
        cmp_run(&tg, &sp, &tr, &out);
        if (out.status) print_error("%s: %s %s\n", cases[k].name, out.status_name, out.detail);
        assert_int_equal(out.status, 0);
        double ev;
        const double e = traj_error(ref, &tr, &ev);
        print_message("%-24s rk-merson 1e-10 over %g s: |q - q_ref| = %.3g, |v - v_ref| = %.3g\n",
                      cases[k].name, cases[k].T, e, ev);
        assert_le(e, cases[k].bound);
        assert_le(ev, 20 * cases[k].bound);
        cmp_traj_free(&tr);
        cmp_ref_free(ref);
        cmp_target_free(&tg);
    }
}

/* ------------------------------------------------------------ step cost */
/* The per-step cost probe (cmp_peer.h): a fixed step of the chosen
 * integrator, finite and positive; NaN with a reason when refused. */
static void test_step_cost(void **state)
{
    (void)state;
    cmp_target tg;
    target("four-bar", &tg);
    char why[256] = "";
    cmp_spec sp = spec_of(CMP_SB_RKM, 1e-6, 1e-3, 1.0, 0.05);
    const double c = cmp_simbody_step_cost(&tg, &sp, 200, why, sizeof why);
    print_message("four-bar: %.3g s per rk-merson step (h = 1e-3)\n", c);
    assert_true(isfinite(c) && c > 0 && c < 1e-2);
    sp.h = 0;
    assert_true(isnan(cmp_simbody_step_cost(&tg, &sp, 200, why, sizeof why)));
    assert_true(strlen(why) > 10);
    cmp_target_free(&tg);
    target("spatial-arm", &tg);
    sp.h = 1e-3;
    why[0] = '\0';
    const double c3 = cmp_simbody_step_cost(&tg, &sp, 200, why, sizeof why);
    print_message("spatial-arm: %.3g s per rk-merson step (h = 1e-3)\n", c3);
    assert_true(isfinite(c3) && c3 > 0 && c3 < 1e-2);
    cmp_target_free(&tg);
    target("tests/compare/universal-arm.json", &tg);
    assert_true(isnan(cmp_simbody_step_cost(&tg, &sp, 200, why, sizeof why)));
    assert_non_null(strstr(why, "universal"));
    cmp_target_free(&tg);
}

/* ------------------------------------------------------------ the driver */
static int integrator_of(const char *s)
{
    if (strcmp(s, "rkm") == 0) return CMP_SB_RKM;
    if (strcmp(s, "rkf") == 0) return CMP_SB_RKF;
    if (strcmp(s, "rk3") == 0) return CMP_SB_RK3;
    if (strcmp(s, "cpodes") == 0) return CMP_SB_CPODES;
    if (strcmp(s, "fixed") == 0) return CMP_SB_RKM_FIXED;
    return -1;
}

/* The driver's optional history: every sample's errors (CMP_SB_HISTORY;
 * CMP_SB_STATES: every sample's t and q). */
static void history_row(const cmp_sample_err *e, void *user)
{
    fprintf((FILE *)user, "%.9g %.6e %.6e %.6e %.6e %.9g %.9g\n", e->t, e->traj, e->pos, e->vel,
            e->energy, e->obs, e->obs_ref);
}

static int drive(int argc, char **argv)
{
    /* CMP_SB_HISTORY=FILE: append each run's samples (t, |q - q_ref|, |Φ_q|,
     * |Φ̇|, |Φ_e|, x of the observed point and its reference) to FILE. */
    const char *hist_path = getenv("CMP_SB_HISTORY");
    FILE *hist = hist_path && *hist_path ? fopen(hist_path, "a") : NULL;
    const char *states_path = getenv("CMP_SB_STATES");
    FILE *states = states_path && *states_path ? fopen(states_path, "a") : NULL;
    if (argc < 3) {
        fprintf(stderr,
                "usage: test_simbody run TARGET T[:DT] INTEGRATOR:VALUE[:VARIANT[:CTOL]]...\n");
        return 2;
    }
    cmp_target tg;
    char err[512];
    if (cmp_target_find(argv[0], &tg, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    /* T, or T:DT to sample every DT instead of the target's dt_out. */
    const double T = atof(argv[1]);
    const char *colon = strchr(argv[1], ':');
    const double dt = colon ? atof(colon + 1) : tg.dt_out;
    cmp_ref_kind kind = cmp_target_ref_kind(&tg);
    cmp_ref *ref = NULL;
    err[0] = '\0';
    if (kind == CMP_REF_CLOSED || kind == CMP_REF_RK8PD) ref = cmp_ref_new(&tg, kind, 1e-13);
    else if (kind == CMP_REF_PROJ) {
        /* The study's RK4 + projection reference, tabulated on the output
         * grid. */
        ref = test_proj_ref_new(&tg, T, dt, err, sizeof err);
    }
    if (ref && cmp_ref_tabulate(ref, dt, T)) {
        cmp_ref_free(ref);
        ref = NULL;
    }
    printf("# %s T = %g dt_out = %g reference %s%s%s\n", tg.name, T, dt,
           ref ? cmp_ref_kind_name(kind) : "none", !ref && kind == CMP_REF_PROJ ? ": " : "",
           !ref && kind == CMP_REF_PROJ ? err : "");
    printf("%-8s %8s %-12s %8s %-16s %12s %9s %8s %7s %8s %7s %10s %10s %10s %10s %s\n",
           "integ", "value", "variant", "ctol", "status", "t_reached", "cpu_s", "steps", "rej",
           "realiz", "proj", "traj_max", "traj_end", "pos_max", "energy_max", "detail");
    for (int k = 2; k < argc; k++) {
        char buf[256];
        snprintf(buf, sizeof buf, "%s", argv[k]);
        char *f[4] = {buf, NULL, NULL, NULL};
        for (int i = 1; i < 4; i++) {
            char *c = f[i - 1] ? strchr(f[i - 1], ':') : NULL;
            if (c) {
                *c = '\0';
                f[i] = c + 1;
            }
        }
        const int integ = integrator_of(f[0]);
        if (integ < 0 || !f[1]) {
            fprintf(stderr, "test_simbody: bad setting '%s'\n", argv[k]);
            return 2;
        }
        const double value = atof(f[1]);
        cmp_spec sp = spec_of(integ, integ == CMP_SB_RKM_FIXED ? 0 : value,
                              integ == CMP_SB_RKM_FIXED ? value : 0, T, dt);
        if (f[2] && strcmp(f[2], "-") != 0) snprintf(sp.variant, sizeof sp.variant, "%s", f[2]);
        if (f[3]) sp.peer.ctol = atof(f[3]);
        cmp_traj tr;
        cmp_outcome out;
        cmp_metrics mt;
        cmp_traj_init(&tr, tg.sys.n, 1024);
        cmp_run(&tg, &sp, &tr, &out);
        if (ref) cmp_ref_restart(ref);
        if (states) {
            /* CMP_SB_STATES=FILE: t and q of every sample. */
            fprintf(states, "# %s %s T = %g\n", tg.name, argv[k], T);
            for (long j = 0; j < tr.count; j++) {
                fprintf(states, "%.9g", tr.t[j]);
                for (int i = 0; i < tr.n; i++) fprintf(states, " %.9g", tr.q[j * tr.n + i]);
                fprintf(states, "\n");
            }
            fprintf(states, "\n\n");
        }
        if (hist) fprintf(hist, "# %s %s T = %g\n", tg.name, argv[k], T);
        if (cmp_metrics_compute(&tg, &tr, ref, &mt, hist ? history_row : NULL, hist))
            memset(&mt, 0, sizeof mt);
        if (hist) fprintf(hist, "\n\n");
        printf("%-8s %8.2g %-12s %8.2g %-16s %12.6g %9.4g %8ld %7ld %8ld %7ld %10.3e %10.3e "
               "%10.3e %10.3e %s\n",
               f[0], value, sp.variant[0] ? sp.variant : "-", sp.peer.ctol,
               out.status ? out.status_name : "ok", out.t_reached, out.cpu_self,
               out.counts.steps, out.counts.rejected, out.counts.rhs_evals,
               out.counts.iterations, mt.traj_max, mt.traj_final, mt.pos_max, mt.energy_max,
               out.detail);
        fflush(stdout);
        cmp_traj_free(&tr);
    }
    cmp_ref_free(ref);
    cmp_target_free(&tg);
    if (hist) fclose(hist);
    if (states) fclose(states);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc > 1 && strcmp(argv[1], "run") == 0) return drive(argc - 2, argv + 2);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pendulum_exact),
        cmocka_unit_test(test_spatial),
        cmocka_unit_test(test_initial_state),
        cmocka_unit_test(test_failure_is_a_row),
        cmocka_unit_test(test_fixed_step_is_h),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_elements),
        cmocka_unit_test(test_step_cost),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
