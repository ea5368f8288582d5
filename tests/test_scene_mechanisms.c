/* The shipped mechanisms that have an independent solution or balance:
 *   sleigh.json            Chaplygin sleigh vs its reduced equations
 *   damped-motor.json      energy balance |Φ_e| <= 1e-8 with dampers and a motor
 *   driven-crank.json      prescribed crank angle vs exact slider kinematics
 *   parallelogram-redundant.json  rank 11 of 12 rows vs the closed-form pendulum
 *   double-pendulum.json   distance joints vs the angle equations */
#include "test_util.h"
#include "braun_reference.h"
#include "braun_scene_file.h"

#define PI 3.14159265358979323846

static braun_scene_file *load(const char *path)
{
    char err[512];
    braun_scene_file *f = braun_scene_load(path, err, sizeof err);
    if (!f) fail_msg("%s", err);
    return f;
}

/* Maxima of the residuals over a run, from the output callback. */
typedef struct watch {
    double pos, vel, energy;
} watch;

static int watch_out(const braun_data *d, void *u)
{
    watch *w = u;
    braun_real p, v, e;
    assert_int_equal(braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, &v, &e), BRAUN_OK);
    w->pos = fmax(w->pos, p);
    w->vel = fmax(w->vel, v);
    w->energy = fmax(w->energy, e);
    return 0;
}

static void open_scene(test_sim *sim, braun_scene_file *f, unsigned corr)
{
    assert_int_equal(test_sim_open(sim, &f->sys, corr), BRAUN_OK);
    assert_int_equal(braun_set_state(&sim->data, 0, f->q0, f->v0), BRAUN_OK);
}

/* dE/dt along the constrained motion, ∂E/∂q·v + ∂E/∂v·v' with the ideal v'
 * of the library (no corrections), against the input power Ė: ideal
 * constraint forces do no work. */
static void check_energy_rate(const braun_scene_file *f, const braun_data *d)
{
    const braun_system *s = &f->sys;
    const int n = s->n;
    test_sim ev;
    braun_real qd[16], vd[16], E, dEdq[16], dEdv[16], dEdt, P = 0;
    assert_int_equal(test_sim_open(&ev, s, BRAUN_CORRECT_NONE), BRAUN_OK);
    assert_int_equal(braun_eval(&ev.data, d->t, d->q, d->v, 1, qd, vd), BRAUN_OK);
    assert_int_equal(s->energy(d->t, d->q, d->v, &E, dEdq, dEdv, &dEdt, s->user), 0);
    if (s->power) assert_int_equal(s->power(d->t, d->q, d->v, &P, s->user), 0);
    double rate = dEdt, size = 0;
    for (int i = 0; i < n; i++) {
        rate += dEdq[i] * d->v[i] + dEdv[i] * vd[i];
        size += fabs(dEdq[i] * d->v[i]) + fabs(dEdv[i] * vd[i]);
    }
    assert_le(fabs(rate - P), 1e-8 * (1 + size));
    test_sim_close(&ev);
}

/* ------------------------------------------------------------- sleigh */
/* Body frame at the centre of mass, blade point at distance a behind it,
 * u the forward speed, ω the turn rate. The lateral speed of the centre of
 * mass is aω (the blade point does not slip), and with the constraint
 * force λ at the blade (Neimark–Fufaev; Bloch, Nonholonomic Mechanics):
 *   m(u' - aω²) = 0,  m(aω' + uω) = λ,  I ω' = -aλ
 * so u' = aω², ω' = -m a u ω / (I + m a²). The pose follows
 *   x' = u cos θ - aω sin θ,  y' = u sin θ + aω cos θ,  θ' = ω. */
typedef struct sleigh_prm {
    double m, I, a;
} sleigh_prm;

static void sleigh_rhs(const sleigh_prm *p, const double *y, double *dy)
{
    const double th = y[2], u = y[3], w = y[4];
    dy[0] = u * cos(th) - p->a * w * sin(th);
    dy[1] = u * sin(th) + p->a * w * cos(th);
    dy[2] = w;
    dy[3] = p->a * w * w;
    dy[4] = -p->m * p->a * u * w / (p->I + p->m * p->a * p->a);
}

static void sleigh_advance(const sleigh_prm *p, double *y, double T, double h)
{
    const long n = (long)ceil(T / h - 1e-9);
    h = T / (double)n;
    for (long k = 0; k < n; k++) {
        double k1[5], k2[5], k3[5], k4[5], t[5];
        sleigh_rhs(p, y, k1);
        for (int i = 0; i < 5; i++) t[i] = y[i] + 0.5 * h * k1[i];
        sleigh_rhs(p, t, k2);
        for (int i = 0; i < 5; i++) t[i] = y[i] + 0.5 * h * k2[i];
        sleigh_rhs(p, t, k3);
        for (int i = 0; i < 5; i++) t[i] = y[i] + h * k3[i];
        sleigh_rhs(p, t, k4);
        for (int i = 0; i < 5; i++) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
}

static void test_sleigh(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/sleigh.json");
    const braun_scene_body *b = &f->scene.bodies[0];
    const braun_scene_joint *k = &f->scene.joints[0];
    assert_ptr_equal(k->type, BRAUN_JOINT_KNIFE);
    const sleigh_prm prm = {b->mass, b->inertia, -f->scene.points[k->a].x}; /* blade at (-a, 0) */
    assert_int_equal(f->sys.p, 1);
    assert_int_equal(f->sys.m, 0);
    /* Body-frame speeds of the file's initial state: u = 1, aω = 0.5. */
    double y[5] = {f->q0[0], f->q0[1], f->q0[2], 0, f->v0[2]};
    y[3] = cos(f->q0[2]) * f->v0[0] + sin(f->q0[2]) * f->v0[1];

    test_sim sim;
    watch w = {0, 0, 0};
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    double worst = 0;
    for (int sec = 1; sec <= 20; sec++) {
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, sec, 1, watch_out, &w), 0);
        check_energy_rate(f, &sim.data);
        sleigh_advance(&prm, y, 1.0, 1e-4);
        for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(sim.data.q[i] - y[i]));
    }
    print_message("sleigh RK4 h = 1e-3, 20 s: max |q - reduced| %.3g, max |Phi_v| %.3g, "
                  "max |Phi_e| %.3g\n", worst, w.vel, w.energy);
    /* measured 4.6e-11, 5.6e-16, 4.4e-16 (the last two round-off: floor 1e-14) */
    assert_le(worst, 1.5e-10);
    assert_le(w.vel, 1e-14);
    assert_le(w.energy, 1e-14);
    test_sim_close(&sim);
    braun_scene_free(f);
}

/* -------------------------------------------------------- damped motor */
static void test_damped_motor_energy_balance(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/damped-motor.json");
    assert_true(f->sys.flags & BRAUN_ENERGY_INPUT);
    watch with = {0, 0, 0}, without = {0, 0, 0};
    test_sim sim;
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    for (int k = 1; k <= 10; k++) {
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 5e-4, k, 1, watch_out, &with), 0);
        check_energy_rate(f, &sim.data);
    }
    const double work = sim.data.work_in, speed = sim.data.v[2];
    test_sim_close(&sim);
    open_scene(&sim, f, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 5e-4, 10, 1, watch_out, &without), 0);
    test_sim_close(&sim);
    print_message("damped-motor RK4 h = 5e-4, 10 s: max |Phi_e| %.3g with energy correction, "
                  "%.3g without; net work in %.4g J; crank at %.3g rad/s; max |Phi_q| %.3g\n",
                  with.energy, without.energy, work, speed, with.pos);
    assert_le(with.energy, 2e-9); /* measured 5.4e-10 */
    assert_le(with.pos, 5e-12);   /* 1.4e-12 */
    /* The balance is not trivially closed: energy flows in and out. */
    assert_true(without.energy > 10 * with.energy);
    assert_true(fabs(work) > 1.0);
    assert_true(fabs(speed) > 5.0);
    braun_scene_free(f);
}

/* A program's own RK4 over braun_eval on the damped motor: the energy law
 * holds E = E0 + d->work_in, so the program integrates Ė (braun_energy_rate)
 * with q and v and writes it there before each evaluation. Left at 0 (the
 * only way before braun_energy_rate: the docs forbade writing it) the
 * energy correction took the motor's work out of the motion again. Judged
 * against the library's own driver at a tenth of the step. */
static double own_rk4_motor(braun_scene_file *f, int keep_work, double h, double T)
{
    test_sim sim;
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    const int n = f->sys.n;
    double Y[32], K[4][32], Z[32];
    braun_real q[15], v[15], qd[15], vd[15], Edot = 0;
    assert_true(2 * n + 1 <= 32 && n <= 15);
    for (int i = 0; i < n; i++) Y[i] = sim.data.q[i], Y[n + i] = sim.data.v[i];
    Y[2 * n] = 0;
    static const double cc[4] = {0, 0.5, 0.5, 1}, ww[4] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    const long N = lround(T / h);
    for (long s = 0; s < N; s++)
        for (int j = 0; j < 4; j++) {
            for (int i = 0; i <= 2 * n; i++) Z[i] = Y[i] + (j ? cc[j] * h * K[j - 1][i] : 0);
            for (int i = 0; i < n; i++) q[i] = (braun_real)Z[i], v[i] = (braun_real)Z[n + i];
            const braun_real t = (braun_real)((double)s * h + cc[j] * h);
            if (keep_work) sim.data.work_in = (braun_real)Z[2 * n];
            assert_int_equal(braun_energy_rate(&sim.data, t, q, v, &Edot), BRAUN_OK);
            assert_int_equal(braun_eval(&sim.data, t, q, v, (braun_real)h, qd, vd), BRAUN_OK);
            for (int i = 0; i < n; i++) K[j][i] = qd[i], K[j][n + i] = vd[i];
            K[j][2 * n] = Edot;
            if (j == 3)
                for (int i = 0; i <= 2 * n; i++)
                    Y[i] += h * (ww[0] * K[0][i] + ww[1] * K[1][i] + ww[2] * K[2][i] + ww[3] * K[3][i]);
        }
    test_sim_close(&sim);
    return Y[n + 2]; /* the crank's rate */
}

static void test_own_integrator_energy_input(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/damped-motor.json");
    test_sim sim;
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    /* Ė at a moving state (t = 1 s) against the driver's ∫Ė over a tiny step. */
    braun_real Edot = 0;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 1.0, 0, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_energy_rate(&sim.data, sim.data.t, sim.data.q, sim.data.v, &Edot), BRAUN_OK);
    const double w1 = (double)sim.data.work_in;
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-7, 1.0 + 1e-7, 0, NULL, NULL), BRAUN_OK);
    const double slope = ((double)sim.data.work_in - w1) / 1e-7;
    assert_true(fabs(slope) > 1);
    assert_near((double)Edot, slope, 1e-5 * fabs(slope));
    /* The reference: the library's driver at h / 10. */
    assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-4, 2.0, 0, NULL, NULL), BRAUN_OK);
    const double ref = sim.data.v[2];
    test_sim_close(&sim);
    const double kept = own_rk4_motor(f, 1, 1e-3, 2.0), left = own_rk4_motor(f, 0, 1e-3, 2.0);
    print_message("damped-motor, own RK4 on braun_eval h = 1e-3, 2 s: crank %.9g rad/s with "
                  "work_in kept, %.9g left at 0; the driver at 1e-4: %.9g (Edot(0) %.6g, the "
                  "driver's %.6g)\n", kept, left, ref, (double)Edot, slope);
    assert_near(kept, ref, 1e-5 * fabs(ref));
    assert_true(fabs(left - ref) > 100 * fabs(kept - ref));
    braun_scene_free(f);
}

/* ------------------------------------------------------- driven crank */
/* Crank angle θ = 2πt; the slider end of the rod is at
 * x_s = r cos θ + sqrt(L² - r² sin² θ). */
static void test_driven_crank(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/driven-crank.json");
    /* The drive's constraint force does work: the core accounts for it. */
    assert_non_null(f->sys.energy);
    assert_false(f->sys.flags & BRAUN_SCLERONOMIC);
    assert_int_equal(f->corrections, BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY);
    const double r = 0.5, L = 1.5;
    test_sim sim;
    watch w = {0, 0, 0};
    open_scene(&sim, f, f->corrections);
    double worst = 0, worst_v = 0;
    for (int k = 1; k <= 40; k++) {
        const double t = 0.05 * k;
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, t, 1, watch_out, &w), 0);
        const double th = 2 * PI * t, s = sin(th), c = cos(th), root = sqrt(L * L - r * r * s * s);
        const double xs = r * c + root;
        const double vs = -r * s * 2 * PI - r * r * s * c * 2 * PI / root;
        /* Rod centre (x, θ) at q[3], q[5]: the slider end is x + (L/2) cos θ. */
        const double x_end = sim.data.q[3] + 0.5 * L * cos(sim.data.q[5]);
        const double v_end = sim.data.v[3] - 0.5 * L * sin(sim.data.q[5]) * sim.data.v[5];
        worst = fmax(worst, fabs(x_end - xs));
        worst_v = fmax(worst_v, fabs(v_end - vs));
        assert_near(sim.data.q[2], th, 1e-9);
    }
    print_message("driven-crank RK4 h = 1e-3, 2 s: max |x_s - exact| %.3g, |v_s - exact| %.3g, "
                  "max |Phi_q| %.3g, max |Phi_e| %.3g (E = E0 + work of the drive)\n",
                  worst, worst_v, w.pos, w.energy);
    /* measured 1.8e-14, 1.1e-13, 1.4e-14, 7.0e-11 */
    assert_le(worst, 6e-14);
    assert_le(worst_v, 4e-13);
    assert_le(w.pos, 5e-14);
    /* The energy balance closes with the drive's work integrated (the
     * kinetic energy swings by ~1 J per revolution). */
    assert_le(w.energy, 2e-10);
    test_sim_close(&sim);
    braun_scene_free(f);
}

/* ------------------------------------------- redundant parallelogram */
/* The coupler translates; cranks at angle θ with
 * T = ½(3·ml²/3 + 2m l²)θ'²... = ½·3θ'², V = 3.5 g sin θ: θ'' = -(7g/6) cos θ,
 * the four-bar's equation, a pendulum in phi = θ + π/2. */
static void test_parallelogram(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/parallelogram-redundant.json");
    assert_int_equal(f->sys.n, 12);
    assert_int_equal(f->sys.m, 12);
    test_sim sim;
    watch w = {0, 0, 0};
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    const double th0 = f->q0[2];
    double worst = 0;
    for (int k = 1; k <= 10; k++) {
        assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 0.5 * k, 1, watch_out, &w), 0);
        double phi, dphi;
        assert_int_equal(braun_pendulum_exact(7 * 9.81 / 6, th0 + PI / 2, 0, 0.5 * k, &phi, &dphi), 0);
        for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(sim.data.q[3 * c + 2] - (phi - PI / 2)));
        assert_near(sim.data.q[11], 0, 1e-9); /* the coupler does not turn */
    }
    print_message("parallelogram RK4 h = 1e-3, 5 s: max |theta - exact| %.3g, rank-deficient "
                  "factorizations %ld of %ld, max |Phi_q| %.3g, max |Phi_e| %.3g\n", worst,
                  sim.data.stats.rank_deficient, sim.data.stats.constraint_factorizations, w.pos,
                  w.energy);
    assert_le(worst, 5e-11); /* measured 1.8e-11 */
    assert_int_equal(sim.data.stats.rank_deficient, sim.data.stats.constraint_factorizations);
    assert_le(w.pos, 3e-12); /* 8.8e-13 */
    test_sim_close(&sim);
    braun_scene_free(f);
}

/* ---------------------------------------------------- double pendulum */
/* Angles from the downward vertical, m1 = m2 = 1, l1 = l2 = 1:
 *   2 φ1'' + φ2'' cos Δ + φ2'² sin Δ + 2 g sin φ1 = 0
 *   φ2'' + φ1'' cos Δ - φ1'² sin Δ + g sin φ2 = 0,   Δ = φ1 - φ2. */
static void dp_rhs(const double *y, double *dy)
{
    const double g = 9.81, d = y[0] - y[1], c = cos(d), s = sin(d);
    const double r1 = -y[3] * y[3] * s - 2 * g * sin(y[0]);
    const double r2 = y[2] * y[2] * s - g * sin(y[1]);
    const double det = 2 - c * c;
    dy[0] = y[2];
    dy[1] = y[3];
    dy[2] = (r1 - c * r2) / det;
    dy[3] = (2 * r2 - c * r1) / det;
}

static void test_double_pendulum(void **state)
{
    (void)state;
    braun_scene_file *f = load("data/double-pendulum.json");
    double y[4] = {PI / 2, PI / 2, 0, 0};
    const double h = 1e-5;
    for (long k = 0; k < 200000; k++) { /* 2 s */
        double k1[4], k2[4], k3[4], k4[4], t[4];
        dp_rhs(y, k1);
        for (int i = 0; i < 4; i++) t[i] = y[i] + 0.5 * h * k1[i];
        dp_rhs(t, k2);
        for (int i = 0; i < 4; i++) t[i] = y[i] + 0.5 * h * k2[i];
        dp_rhs(t, k3);
        for (int i = 0; i < 4; i++) t[i] = y[i] + h * k3[i];
        dp_rhs(t, k4);
        for (int i = 0; i < 4; i++) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    test_sim sim;
    watch w = {0, 0, 0};
    open_scene(&sim, f, BRAUN_CORRECT_ALL);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-4, 2.0, 1, watch_out, &w), 0);
    const double x2 = sin(y[0]) + sin(y[1]), y2 = -cos(y[0]) - cos(y[1]);
    const double err = hypot(sim.data.q[2] - x2, sim.data.q[3] - y2);
    print_message("double pendulum RK4 h = 1e-4, 2 s: |bob2 - angle equations| %.3g, max |Phi_e| "
                  "%.3g\n", err, w.energy);
    assert_le(err, 5e-14); /* measured 1.2e-14 */
    test_sim_close(&sim);
    braun_scene_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sleigh),
        cmocka_unit_test(test_damped_motor_energy_balance),
        cmocka_unit_test(test_own_integrator_energy_input),
        cmocka_unit_test(test_driven_crank),
        cmocka_unit_test(test_parallelogram),
        cmocka_unit_test(test_double_pendulum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
