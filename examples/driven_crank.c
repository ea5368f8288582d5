/* A slider-crank driven two ways, written from docs/api.md ("Driven and
 * dissipative systems"): the paper's absolute coordinates q = [x1, y1, θ1,
 * x2, y2, θ2] (crank of l1 = 0.5 m, m1 = 0.5 kg; rod of l2 = 1.5 m,
 * m2 = 1 kg; the crank pinned at the origin, the rod's end B sliding on
 * y = 0; gravity).
 *
 *   motor      a motor on the crank, τ = τ0 (1 − ω/ω0), against a damper c
 *              on the slider. Applied forces that put energy in and take it
 *              out: their power τω − c v_B² is the power() callback, with
 *              BRAUN_ENERGY_INPUT. Checked: the energy balance
 *              E(t) − E(0) − ∫P dt, with ∫P integrated here by Simpson's
 *              rule over pairs of steps (independent of libbraun's own ∫Ė).
 *   prescribed the crank turned at ω = 2π rad/s by a rheonomic row
 *              θ1 − ωt = 0 (b_q = ω). No flag and no power term: libbraun
 *              accounts for the work of the moving constraint itself.
 *              Checked: the slider's position against the exact kinematics
 *              x_B = l1 cos ωt + sqrt(l2² − l1² sin² ωt).
 *
 * Prints one line per case; exits 1 if a check is beyond its bound, and
 * then says on stderr which figure left which bound (tests/cli/install.sh
 * builds and runs it against an installed libbraun, double and float). */
#include <braun.h>
#include <math.h>
#include <stdio.h>

/* The bounds, about 5 to 20 times the figures measured on x86-64 (beside
 * each: the same with gcc 12 and clang 14, -O0 and -O2, libbraun shared and
 * static, built with either compiler). Float's are float's own: |Phi_q| at
 * its round-off of the coordinates (eps 1.2e-7), |Phi_e| and the balance
 * at its round-off of E, which the balance sums in double from float
 * states; float holds the slider to 3e-7 m where double holds it to 2e-14. */
#ifdef BRAUN_SINGLE
#define PRECISION "float"
#define MOTOR_PHI_Q 7.5e-7      /* 1.5e-7: |Phi_q| at 5 s */
#define MOTOR_BALANCE 6.5e-5    /* 1.3e-5: E - E0 - int P dt, Simpson */
#define MOTOR_PHI_E 3e-5        /* 5.7e-6: libbraun's |Phi_e| at 5 s */
#define SLIDER_ERROR 1.5e-6     /* 3.1e-7: max |x_B - exact| over 2 s */
#define PRESCRIBED_PHI_E 6e-7   /* 1.2e-7: |Phi_e| at 2 s */
#else
#define PRECISION "double"
#define MOTOR_PHI_Q 3e-12       /* 3.2e-13 */
#define MOTOR_BALANCE 3e-7      /* 5.4e-8: Simpson's own error (3.4e-9 at h = 5e-4: h^4) */
#define MOTOR_PHI_E 5e-14       /* 2.7e-15 */
#define SLIDER_ERROR 2e-13      /* 1.9e-14 */
#define PRESCRIBED_PHI_E 1e-14  /* 6.3e-16 (the bound was 1e-12, for 6.7e-14 once) */
#endif

/* -DBOUND_SCALE=1e-9 makes every figure leave its bound: how
 * tests/cli/install.sh sees the messages. */
#ifndef BOUND_SCALE
#define BOUND_SCALE 1
#endif

/* 1 when value is below bound; otherwise 0, and stderr says which figure
 * left which bound (NaN is not below any bound). */
static int within(const char *run, const char *figure, double value, double bound)
{
    bound *= BOUND_SCALE;
    if (value < bound) return 1;
    fprintf(stderr, "driven_crank: %s: %s = %.2g is not below its bound %.2g (%s)\n", run, figure, value,
            bound, PRECISION);
    return 0;
}

static const double l1 = 0.5, l2 = 1.5, m1 = 0.5, m2 = 1.0, g = 9.81;
static const double I1 = 0.5 * 0.5 * 0.5 / 12, I2 = 1.0 * 1.5 * 1.5 / 12;
static const double tau0 = 5, omega0 = 20, c = 2; /* motor: N m, rad/s; damper: N s/m */
static const double drive = 6.283185307179586;     /* prescribed: rad/s */

typedef struct crank {
    int prescribed; /* the sixth row θ1 − ωt = 0 */
} crank;

static int mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    const double d[6] = {m1, m1, I1, m2, m2, I2};
    for (int i = 0; i < 36; i++) M[i] = 0;
    for (int i = 0; i < 6; i++) M[7 * i] = (braun_real)d[i];
    return 0;
}

/* The slider's velocity along x: B = (x2 + l2/2 cos θ2, ...). */
static double slider_speed(const braun_real *q, const braun_real *v)
{
    return v[3] - 0.5 * l2 * sin(q[5]) * v[5];
}

static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    const crank *k = (const crank *)u;
    (void)t;
    for (int i = 0; i < 6; i++) Q[i] = 0;
    Q[1] = (braun_real)(-m1 * g);
    Q[4] = (braun_real)(-m2 * g);
    if (!k->prescribed) {
        Q[2] += (braun_real)(tau0 * (1 - v[2] / omega0));   /* motor torque on θ1 */
        const double F = -c * slider_speed(q, v);          /* damper on B, along x */
        Q[3] += (braun_real)F;                             /* F ∂B_x/∂x2 */
        Q[5] += (braun_real)(F * -0.5 * l2 * sin(q[5]));   /* F ∂B_x/∂θ2 */
    }
    return 0;
}

/* Φ_q, A_q, b_q = −∂Φ_q/∂t, b_qv with Φ̈_q = A_q v' − b_qv (braun.h). */
static int rows(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    const crank *k = (const crank *)u;
    const int m = k->prescribed ? 6 : 5;
    const double c1 = cos(q[2]), s1 = sin(q[2]), c2 = cos(q[5]), s2 = sin(q[5]);
    const double w1 = v[2], w2 = v[5], h1 = 0.5 * l1, h2 = 0.5 * l2;
    if (phi) {
        phi[0] = (braun_real)(q[0] - h1 * c1);                       /* crank end O at the origin */
        phi[1] = (braun_real)(q[1] - h1 * s1);
        phi[2] = (braun_real)(q[0] + h1 * c1 - q[3] + h2 * c2);      /* crank tip = rod's end A */
        phi[3] = (braun_real)(q[1] + h1 * s1 - q[4] + h2 * s2);
        phi[4] = (braun_real)(q[4] + h2 * s2);                       /* B on y = 0 */
        if (m == 6) phi[5] = (braun_real)(q[2] - drive * t);          /* θ1 = ωt */
    }
    if (A) {
        const double a[6][6] = {{1, 0, h1 * s1, 0, 0, 0},
                                {0, 1, -h1 * c1, 0, 0, 0},
                                {1, 0, -h1 * s1, -1, 0, -h2 * s2},
                                {0, 1, h1 * c1, 0, -1, h2 * c2},
                                {0, 0, 0, 0, 1, h2 * c2},
                                {0, 0, 1, 0, 0, 0}};
        for (int i = 0; i < m; i++)
            for (int j = 0; j < 6; j++) A[6 * i + j] = (braun_real)a[i][j];
    }
    if (b) {
        for (int i = 0; i < m; i++) b[i] = 0;
        if (m == 6) b[5] = (braun_real)drive; /* −∂Φ/∂t of θ1 − ωt */
    }
    if (bv) {
        bv[0] = (braun_real)(-h1 * c1 * w1 * w1);
        bv[1] = (braun_real)(-h1 * s1 * w1 * w1);
        bv[2] = (braun_real)(h1 * c1 * w1 * w1 + h2 * c2 * w2 * w2);
        bv[3] = (braun_real)(h1 * s1 * w1 * w1 + h2 * s2 * w2 * w2);
        bv[4] = (braun_real)(h2 * s2 * w2 * w2);
        if (m == 6) bv[5] = 0;
    }
    return 0;
}

/* E = T + V (kinetic energy and gravity); nothing depends on t. */
static int energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                  braun_real *dq, braun_real *dv, braun_real *dt, void *u)
{
    const double d[6] = {m1, m1, I1, m2, m2, I2};
    (void)t; (void)u;
    if (E) {
        double T = 0;
        for (int i = 0; i < 6; i++) T += 0.5 * d[i] * v[i] * v[i];
        *E = (braun_real)(T + m1 * g * q[1] + m2 * g * q[4]);
    }
    if (dq) {
        for (int i = 0; i < 6; i++) dq[i] = 0;
        dq[1] = (braun_real)(m1 * g);
        dq[4] = (braun_real)(m2 * g);
    }
    if (dv) for (int i = 0; i < 6; i++) dv[i] = (braun_real)(d[i] * v[i]);
    if (dt) *dt = 0;
    return 0;
}

/* Power of the applied forces that are not in E: the motor and the damper. */
static double applied_power(const braun_real *q, const braun_real *v)
{
    const double vb = slider_speed(q, v);
    return tau0 * (1 - v[2] / omega0) * v[2] - c * vb * vb;
}

static int power(braun_real t, const braun_real *q, const braun_real *v, braun_real *P, void *u)
{
    (void)t; (void)u;
    *P = (braun_real)applied_power(q, v);
    return 0;
}

/* The motor case's output, every step: E, and ∫P by Simpson's rule over
 * each pair of steps (equal steps of h), the balance checked at the end of
 * every pair. braun_energy on the output callback's data is allowed: it
 * changes neither the state nor the run (docs/api.md, section 4). */
typedef struct balance {
    double t0, P0, P1, work, E0, worst;
    long k;
} balance;

static int on_step(const braun_data *d, void *user)
{
    balance *b = (balance *)user;
    braun_real E;
    const double P = applied_power(d->q, d->v);
    if (braun_energy((braun_data *)d, d->t, d->q, d->v, &E)) return 1;
    if (b->k == 0) b->E0 = (double)E;
    if (b->k % 2 == 1) {
        b->P1 = P;
    } else {
        if (b->k > 0) {
            b->work += ((double)d->t - b->t0) / 6 * (b->P0 + 4 * b->P1 + P);
            const double err = fabs((double)E - b->E0 - b->work);
            if (err > b->worst) b->worst = err;
        }
        b->t0 = (double)d->t;
        b->P0 = P;
    }
    b->k++;
    return 0;
}

static int run(int prescribed, double h, double t_end, braun_output_fn out, void *user,
               braun_data *data, braun_model *model, unsigned char *buffer, size_t bytes,
               crank *k)
{
    const double th1 = prescribed ? 0 : 1.5707963267948966;
    const double s2 = -l1 * sin(th1) / l2, th2 = asin(s2), c2 = cos(th2);
    /* Crank centre, rod centre at the state the rows describe. */
    const braun_real q0[6] = {(braun_real)(0.5 * l1 * cos(th1)), (braun_real)(0.5 * l1 * sin(th1)),
                              (braun_real)th1,
                              (braun_real)(l1 * cos(th1) + 0.5 * l2 * c2),
                              (braun_real)(l1 * sin(th1) + 0.5 * l2 * s2), (braun_real)th2};
    /* Prescribed: the velocities the drive imposes at θ1 = 0 (A moves up
     * at l1 ω, B stays on y = 0); motor: at rest. */
    const double w = prescribed ? drive : 0;
    const braun_real v0[6] = {0, (braun_real)(0.5 * l1 * w), (braun_real)w, 0,
                              (braun_real)(0.5 * l1 * w), (braun_real)(-l1 * w / l2)};
    k->prescribed = prescribed;
    braun_system sys = {.n = 6, .m = prescribed ? 6 : 5, .p = 0,
                        .flags = BRAUN_MASS_CONSTANT | (prescribed ? 0u : BRAUN_ENERGY_INPUT),
                        .mass = mass, .forces = forces, .holonomic = rows, .energy = energy,
                        .power = prescribed ? NULL : power, .user = k};
    int st = braun_model_init(model, &sys); /* every correction: position, velocity, energy */
    if (!st && braun_data_size(model) > bytes) st = BRAUN_ERR_BUFFER;
    if (!st) st = braun_data_init(data, model, buffer, bytes);
    if (!st) st = braun_set_state(data, 0, q0, v0);
    if (!st) st = braun_integrate(data, BRAUN_RK4, (braun_real)h, (braun_real)t_end, 1, out, user);
    return st;
}

/* Prescribed case: the slider against its exact position at every step. */
typedef struct kinematics {
    double worst;
} kinematics;

static int on_slide(const braun_data *d, void *user)
{
    kinematics *k = (kinematics *)user;
    const double t = (double)d->t, s = l1 * sin(drive * t);
    const double exact = l1 * cos(drive * t) + sqrt(l2 * l2 - s * s);
    const double xb = (double)d->q[3] + 0.5 * l2 * cos((double)d->q[5]);
    if (fabs(xb - exact) > k->worst) k->worst = fabs(xb - exact);
    return 0;
}

int main(void)
{
    static unsigned char buffer[16384]; /* braun_data_size() is about 5 KB here */
    braun_model model;
    braun_data data = {0};
    crank k;
    braun_real pos, vel, en;
    int bad = 0;

    balance b = {0, 0, 0, 0, 0, 0, 0};
    int st = run(0, 1e-3, 5.0, on_step, &b, &data, &model, buffer, sizeof buffer, &k);
    if (!st) st = braun_residuals(&data, data.t, data.q, data.v, &pos, &vel, &en);
    if (st) {
        fprintf(stderr, "driven_crank: motor: %s\n", braun_status_str(st));
        return 1;
    }
    printf("motor:      t = %g s  crank %.4f rad/s  |Phi_q| %.1e  |Phi_e| %.1e  "
           "E - E0 - int P dt (Simpson) %.1e\n",
           (double)data.t, (double)data.v[2], (double)pos, (double)en, b.worst);
    /* The balance's error is Simpson's rule's, while libbraun's own |Phi_e|
     * is at round-off (the bounds above). */
    bad |= !within("motor", "|Phi_q|", (double)pos, MOTOR_PHI_Q);
    bad |= !within("motor", "E - E0 - int P dt", b.worst, MOTOR_BALANCE);
    bad |= !within("motor", "|Phi_e|", (double)en, MOTOR_PHI_E);

    kinematics kin = {0};
    st = run(1, 1e-3, 2.0, on_slide, &kin, &data, &model, buffer, sizeof buffer, &k);
    if (!st) st = braun_residuals(&data, data.t, data.q, data.v, &pos, &vel, &en);
    if (st) {
        fprintf(stderr, "driven_crank: prescribed: %s\n", braun_status_str(st));
        return 1;
    }
    printf("prescribed: t = %g s  max |x_B - exact| %.1e  |Phi_q| %.1e  |Phi_e| %.1e\n",
           (double)data.t, kin.worst, (double)pos, (double)en);
    bad |= !within("prescribed", "max |x_B - exact|", kin.worst, SLIDER_ERROR);
    bad |= !within("prescribed", "|Phi_e|", (double)en, PRESCRIBED_PHI_E);
    return bad;
}
