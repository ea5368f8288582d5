/* Tests of IDA's sparse Jacobians (compare/cmp_ida_jac.c, issue 7): the
 * scene provider's residual equals the callbacks' GGL residual, its
 * analytic Jacobian equals central differences of both residuals on every
 * entry of the dense N x N matrix (so its pattern misses nothing), colored
 * finite differences equal column-by-column ones, the patterns found from
 * the callbacks hold every nonzero, the sparse consistent values equal the
 * dense ones, and IDA with KLU gives the same motion with every Jacobian.
 * Mechanisms: rigid-link chains, a chain of rods between particles, and a
 * ladder of parallelograms with a redundant rail (rank-deficient rows). */
#include "test_util.h"

#include <gsl/gsl_errno.h>

#include "braun_scene.h"
#include "cmp.h"

/* ------------------------------------------------------------ scenes */
#define MAXB 64
typedef struct test_scene {
    braun_scene s;
    braun_system sys;
    braun_scene_body bodies[MAXB];
    braun_scene_point points[4 * MAXB];
    braun_scene_rod rods[MAXB];
    braun_scene_joint joints[2 * MAXB];
    braun_scene_effect effects[1];
    double q0[3 * MAXB], v0[3 * MAXB];
} test_scene;

static int add_body(test_scene *t, int rigid, double mass, double x, double y, double th)
{
    braun_scene_body *b = &t->bodies[t->s.nbodies];
    memset(b, 0, sizeof *b);
    b->kind = rigid ? BRAUN_BODY_RIGID : BRAUN_BODY_PARTICLE;
    b->mass = mass;
    b->inertia = rigid ? mass / 12.0 : 0;
    b->q0[0] = x;
    b->q0[1] = y;
    b->q0[2] = th;
    return t->s.nbodies++;
}

static int add_point(test_scene *t, int body, double x, double y)
{
    braun_scene_point *p = &t->points[t->s.npoints];
    p->body = body;
    p->x = x;
    p->y = y;
    return t->s.npoints++;
}

static void add_revolute(test_scene *t, int a, int b)
{
    braun_scene_joint *j = &t->joints[t->s.njoints++];
    memset(j, 0, sizeof *j);
    j->type = BRAUN_JOINT_REVOLUTE;
    j->a = a;
    j->b = b;
}

static void finish(test_scene *t)
{
    memset(t->effects, 0, sizeof t->effects);
    t->effects[0].type = BRAUN_EFFECT_GRAVITY;
    t->effects[0].g[1] = -9.81;
    t->s.bodies = t->bodies;
    t->s.points = t->points;
    t->s.rods = t->rods;
    t->s.joints = t->joints;
    t->s.effects = t->effects;
    t->s.neffects = 1;
    braun_scene_error err;
    assert_int_equal(braun_scene_build(&t->s, &t->sys, &err), BRAUN_OK);
    braun_scene_initial_state(&t->s, t->q0, t->v0);
}

/* N rigid links of 1 m hanging from the origin at angle th0 (as `braun gen
 * chain`, which has th0 = 0). */
static void make_chain(test_scene *t, int N, double th0)
{
    memset(t, 0, sizeof *t);
    int prev = add_point(t, BRAUN_SCENE_GROUND, 0, 0);
    const double c = cos(th0), s = sin(th0);
    for (int i = 0; i < N; i++) {
        int b = add_body(t, 1, 1.0, (i + 0.5) * c, (i + 0.5) * s, th0);
        add_revolute(t, add_point(t, b, -0.5, 0), prev);
        prev = add_point(t, b, 0.5, 0);
    }
    finish(t);
}

/* N uniform rods between particles (natural coordinates, `--rods`), and
 * a rigid link pinned to the last particle (a revolute joint with a
 * particle end). */
static void make_rod_chain(test_scene *t, int N)
{
    memset(t, 0, sizeof *t);
    int prev = add_point(t, BRAUN_SCENE_GROUND, 0, 0);
    for (int i = 0; i < N; i++) {
        int b = add_body(t, 0, i == 1 ? 0.3 : 0.0, 0.8 * (i + 1), 0.6 * (i + 1), 0);
        int p = add_point(t, b, 0, 0);
        braun_scene_rod *r = &t->rods[t->s.nrods++];
        r->a = prev;
        r->b = p;
        r->mass = 1.0;
        r->length = 1.0;
        prev = p;
    }
    int b = add_body(t, 1, 0.7, 0.8 * N + 0.3, 0.6 * N - 0.4, -0.9);
    add_revolute(t, add_point(t, b, -0.3, 0.4), prev);
    finish(t);
}

/* A ladder of L parallelogram levels with three rails: each level has three
 * parallel rail links (1 m, at 60°) and a rung (2 m) pinned to all three;
 * the third rail is redundant (12 rows of rank 11 per level). */
static void make_ladder(test_scene *t, int L)
{
    memset(t, 0, sizeof *t);
    const double a = 1.0471975511965976, ux = cos(a), uy = sin(a);
    int below[3];
    for (int i = 0; i < 3; i++) below[i] = add_point(t, BRAUN_SCENE_GROUND, i, 0);
    for (int k = 1; k <= L; k++) {
        int tips[3];
        for (int i = 0; i < 3; i++) {
            int b = add_body(t, 1, 1.0, i + (k - 0.5) * ux, (k - 0.5) * uy, a);
            add_revolute(t, add_point(t, b, -0.5, 0), below[i]);
            tips[i] = add_point(t, b, 0.5, 0);
        }
        int rung = add_body(t, 1, 2.0, 1 + k * ux, k * uy, 0);
        for (int i = 0; i < 3; i++) {
            below[i] = add_point(t, rung, i - 1.0, 0);
            add_revolute(t, tips[i], below[i]);
        }
    }
    finish(t);
}

/* A target for cmp_dae on a test scene (no reference, not freed). */
static cmp_target as_target(test_scene *t)
{
    cmp_target tg;
    memset(&tg, 0, sizeof tg);
    snprintf(tg.name, sizeof tg.name, "test-scene");
    tg.sys = t->sys;
    tg.q0 = t->q0;
    tg.v0 = t->v0;
    tg.scene_point = -1;
    return tg;
}

/* A reproducible state: every unknown and derivative random, of order 1. */
static void random_state(int N, unsigned seed, double *y, double *yp)
{
    unsigned long x = seed * 2654435761UL + 1;
    for (int i = 0; i < 2 * N; i++) {
        x = x * 6364136223846793005UL + 1442695040888963407UL;
        double u = (double)(x >> 11) / 9007199254740992.0 * 2 - 1;
        if (i < N) y[i] = u;
        else yp[i - N] = u;
    }
}

/* Dense N x N Jacobian by central differences of a residual. */
typedef int (*res_fn)(void *u, double t, const double *y, const double *yp, double *r);

static int dae_res(void *u, double t, const double *y, const double *yp, double *r)
{
    return cmp_dae_residual(u, t, y, yp, r);
}

static int ggl_res(void *u, double t, const double *y, const double *yp, double *r)
{
    return cmp_ggl_residual(u, t, y, yp, r);
}

static double *central_jacobian(res_fn f, void *u, int N, double cj, const double *y0,
                                const double *yp0)
{
    double *J = malloc((size_t)N * N * sizeof(double));
    double *y = malloc(4 * (size_t)N * sizeof(double));
    assert_non_null(J);
    assert_non_null(y);
    double *yp = y + N, *rp = yp + N, *rm = rp + N;
    memcpy(y, y0, (size_t)N * sizeof(double));
    memcpy(yp, yp0, (size_t)N * sizeof(double));
    for (int j = 0; j < N; j++) {
        const double h = 1e-6 * fmax(fabs(y0[j]), 1.0);
        y[j] = y0[j] + h;
        yp[j] = yp0[j] + cj * h;
        assert_int_equal(f(u, 0.0, y, yp, rp), 0);
        y[j] = y0[j] - h;
        yp[j] = yp0[j] - cj * h;
        assert_int_equal(f(u, 0.0, y, yp, rm), 0);
        y[j] = y0[j];
        yp[j] = yp0[j];
        for (int i = 0; i < N; i++) J[(size_t)i * N + j] = (rp[i] - rm[i]) / (2 * h);
    }
    free(y);
    return J;
}

/* Scatter a CSC matrix into a dense row-major one. */
static double *dense_of(int N, const int *cp, const int *ri, const double *val)
{
    double *D = calloc((size_t)N * N, sizeof(double));
    assert_non_null(D);
    for (int j = 0; j < N; j++)
        for (int e = cp[j]; e < cp[j + 1]; e++) D[(size_t)ri[e] * N + j] = val[e];
    return D;
}

/* max |A - B| / max(1, max |B|) over every entry. */
static double rel_diff(int N, const double *A, const double *B)
{
    double d = 0, s = 1;
    for (size_t k = 0; k < (size_t)N * N; k++) {
        d = fmax(d, fabs(A[k] - B[k]));
        s = fmax(s, fabs(B[k]));
    }
    return d / s;
}

/* Every entry of the pattern (sub) is in the pattern (sup). */
static void assert_contains(int N, const int *cp, const int *ri, const int *scp, const int *sri)
{
    for (int j = 0; j < N; j++)
        for (int e = scp[j]; e < scp[j + 1]; e++) {
            int found = 0;
            for (int f = cp[j]; f < cp[j + 1] && !found; f++) found = ri[f] == sri[e];
            if (!found) {
                print_error("entry (%d, %d) missing from the pattern\n", sri[e], j);
                fail();
            }
        }
}

/* The provider against the callbacks on one scene: residuals, analytic J
 * against central differences of both residuals (dense, every entry), the
 * colored forward differences, and the probe's pattern. */
static void check_provider(test_scene *t)
{
    cmp_target tg = as_target(t);
    const char *why = NULL;
    cmp_ggl *g = cmp_ggl_new(&t->s, &why);
    assert_non_null(g);
    cmp_dae *dae = cmp_dae_new(&tg, 0);
    assert_non_null(dae);
    const int N = cmp_ggl_size(g);
    assert_int_equal(N, cmp_dae_size(dae));
    double *y = malloc(4 * (size_t)N * sizeof(double));
    assert_non_null(y);
    double *yp = y + N, *r1 = yp + N, *r2 = r1 + N;
    const int *cp, *ri;
    const int nnz = cmp_ggl_pattern(g, &cp, &ri);
    double *val = malloc((size_t)nnz * sizeof(double)), *fdv = malloc((size_t)nnz * sizeof(double));
    assert_non_null(val);
    assert_non_null(fdv);
    for (unsigned seed = 1; seed <= 3; seed++) {
        random_state(N, seed, y, yp);
        /* Residuals: the same rows to round-off. */
        assert_int_equal(cmp_ggl_residual(g, 0.0, y, yp, r1), 0);
        assert_int_equal(cmp_dae_residual(dae, 0.0, y, yp, r2), 0);
        for (int i = 0; i < N; i++) assert_near(r1[i], r2[i], 1e-13 * (1 + fabs(r2[i])));
        /* Analytic J against central differences (error ~1e-10). */
        const double cj = 3.7 * seed;
        assert_int_equal(cmp_ggl_jacobian(g, 0.0, cj, y, yp, val), 0);
        double *Ja = dense_of(N, cp, ri, val);
        double *Jg = central_jacobian(ggl_res, g, N, cj, y, yp);
        double *Jd = central_jacobian(dae_res, dae, N, cj, y, yp);
        assert_le(rel_diff(N, Ja, Jg), 1e-8);
        assert_le(rel_diff(N, Ja, Jd), 1e-8);
        /* Colored forward differences on the pattern (error ~sqrt(ε)). */
        cmp_fdjac *fd = cmp_fdjac_new(N, cp, ri, 1);
        assert_non_null(fd);
        assert_true(cmp_fdjac_colors(fd) < N);
        long nres = 0;
        assert_int_equal(cmp_fdjac_eval(fd, ggl_res, g, 0.0, cj, y, yp, r1, fdv, &nres), 0);
        assert_int_equal(nres, cmp_fdjac_colors(fd));
        double *Jf = dense_of(N, cp, ri, fdv);
        assert_le(rel_diff(N, Jf, Ja), 1e-6);
        if (seed == 1)
            print_message("N = %d, nnz = %d, colors = %d: |J - central| %.1e (scene), %.1e "
                          "(callbacks), |J - colored forward| %.1e (relative)\n",
                          N, nnz, cmp_fdjac_colors(fd), rel_diff(N, Ja, Jg), rel_diff(N, Ja, Jd),
                          rel_diff(N, Jf, Ja));
        cmp_fdjac_free(fd);
        free(Ja);
        free(Jg);
        free(Jd);
        free(Jf);
    }
    /* What the callbacks' probe sees is inside the scene's pattern. */
    int *pcp, *pri;
    random_state(N, 7, y, yp);
    assert_true(cmp_dae_pattern_probe(dae, y, yp, &pcp, &pri) > 0);
    assert_contains(N, cp, ri, pcp, pri);
    free(pcp);
    free(pri);
    free(val);
    free(fdv);
    free(y);
    cmp_dae_free(dae);
    cmp_ggl_free(g);
}

static void test_provider_chain(void **state)
{
    (void)state;
    test_scene *t = malloc(sizeof *t);
    make_chain(t, 4, -0.7);
    check_provider(t);
    free(t);
}

static void test_provider_rods(void **state)
{
    (void)state;
    test_scene *t = malloc(sizeof *t);
    make_rod_chain(t, 4);
    check_provider(t);
    free(t);
}

static void test_provider_ladder(void **state)
{
    (void)state;
    test_scene *t = malloc(sizeof *t);
    make_ladder(t, 2);
    assert_int_equal(t->sys.n, 24);
    assert_int_equal(t->sys.m, 24);
    check_provider(t);
    free(t);
}

/* The provider refuses what it cannot differentiate (knife edges, driven
 * joints, motors, distance joints) and takes `braun gen chain`'s scenes. */
static void test_provider_refuses(void **state)
{
    (void)state;
    const char *names[] = {"sleigh", "driven-crank", "damped-motor", "double-pendulum"};
    for (int k = 0; k < 4; k++) {
        cmp_target tg;
        char err[256];
        assert_int_equal(cmp_target_find(names[k], &tg, err, sizeof err), 0);
        const char *why = NULL;
        assert_null(cmp_ggl_new(cmp_target_scene(&tg), &why));
        assert_non_null(why);
        cmp_target_free(&tg);
    }
    const char *why = NULL;
    assert_null(cmp_ggl_new(NULL, &why));
    cmp_target tg;
    char err[256];
    assert_int_equal(cmp_target_find("chain-5", &tg, err, sizeof err), 0);
    cmp_ggl *g = cmp_ggl_new(cmp_target_scene(&tg), &why);
    assert_non_null(g);
    cmp_ggl_free(g);
    cmp_target_free(&tg);
}

/* Every target the study knows: the structural pattern holds the probe's,
 * and colored differences equal one-column differences on the probe's. */
static void test_callback_patterns(void **state)
{
    (void)state;
    const char *names[] = {"four-bar", "slider-crank", "pendulum", "andrews",
                           "sleigh", "driven-crank", "damped-motor", "double-pendulum",
                           "parallelogram-redundant", "chain-5"};
    for (int k = 0; k < (int)(sizeof names / sizeof names[0]); k++) {
        cmp_target tg;
        char err[256];
        assert_int_equal(cmp_target_find(names[k], &tg, err, sizeof err), 0);
        for (int index1 = 0; index1 <= 1; index1++) {
            cmp_dae *dae = cmp_dae_new(&tg, index1);
            assert_non_null(dae);
            const int N = cmp_dae_size(dae);
            double *y = malloc(5 * (size_t)N * sizeof(double));
            assert_non_null(y);
            double *yp = y + N, *r0 = yp + N;
            if (cmp_dae_consistent(dae, 0.0, tg.q0, tg.v0, y, yp) != 0) random_state(N, 3, y, yp);
            int *pcp, *pri, *scp, *sri;
            const int pn = cmp_dae_pattern_probe(dae, y, yp, &pcp, &pri);
            const int sn = cmp_dae_pattern_struct(dae, y, yp, &scp, &sri);
            assert_true(pn > 0);
            assert_true(sn >= pn);
            assert_contains(N, scp, sri, pcp, pri);
            /* Colored = column on the probe's pattern (same increments). */
            cmp_fdjac *fc = cmp_fdjac_new(N, pcp, pri, 1), *f1 = cmp_fdjac_new(N, pcp, pri, 0);
            assert_non_null(fc);
            assert_non_null(f1);
            assert_int_equal(cmp_fdjac_colors(f1), N);
            assert_true(cmp_fdjac_colors(fc) <= N);
            double *vc = malloc(2 * (size_t)pn * sizeof(double)), *v1 = vc + pn;
            assert_non_null(vc);
            assert_int_equal(cmp_dae_residual(dae, 0.0, y, yp, r0), 0);
            assert_int_equal(cmp_fdjac_eval(fc, dae_res, dae, 0.0, 2.5, y, yp, r0, vc, NULL), 0);
            assert_int_equal(cmp_fdjac_eval(f1, dae_res, dae, 0.0, 2.5, y, yp, r0, v1, NULL), 0);
            for (int e = 0; e < pn; e++) assert_near(vc[e], v1[e], 1e-12 * (1 + fabs(v1[e])));
            free(vc);
            cmp_fdjac_free(fc);
            cmp_fdjac_free(f1);
            free(pcp);
            free(pri);
            free(scp);
            free(sri);
            free(y);
            cmp_dae_free(dae);
        }
        cmp_target_free(&tg);
    }
}

/* Sparse consistent values (KLU) equal the dense ones (GSL SVD), from a
 * start off the constraints; redundant rows are refused. */
static void consistent_pair(test_scene *t, double dq, double tol)
{
    for (int i = 0; i < t->sys.n; i++) {
        t->q0[i] += dq * sin(3.0 * i);
        t->v0[i] = 0.5 * cos(2.0 * i);
    }
    cmp_target tg = as_target(t);
    cmp_ggl *g = cmp_ggl_new(&t->s, NULL);
    cmp_dae *dae = cmp_dae_new(&tg, 0);
    assert_non_null(g);
    assert_non_null(dae);
    const int N = cmp_ggl_size(g);
    double *y = malloc(5 * (size_t)N * sizeof(double));
    assert_non_null(y);
    double *yp = y + N, *y2 = yp + N, *yp2 = y2 + N, *r = yp2 + N;
    assert_int_equal(cmp_ggl_consistent(g, 0.0, t->q0, t->v0, y, yp), 0);
    assert_int_equal(cmp_dae_consistent(dae, 0.0, t->q0, t->v0, y2, yp2), 0);
    for (int i = 0; i < N; i++) {
        assert_near(y[i], y2[i], tol * (1 + fabs(y2[i])));
        assert_near(yp[i], yp2[i], tol * (1 + fabs(yp2[i])));
    }
    assert_int_equal(cmp_ggl_residual(g, 0.0, y, yp, r), 0);
    for (int i = 0; i < N; i++) assert_near(r[i], 0.0, 1e-10);
    free(y);
    cmp_dae_free(dae);
    cmp_ggl_free(g);
}

/* Sparse consistent values (KLU) equal the dense ones (GSL SVD), from a
 * start off the constraints; with redundant rows (the ladder) through the
 * proximal iteration, down to the minimum-norm multipliers. (The ladder
 * starts on its constraints: off them, Φ leaves the range of A and the two
 * Gauss-Newton paths may end at different points of the manifold.) */
static void test_consistent(void **state)
{
    (void)state;
    test_scene *t = malloc(sizeof *t);
    make_chain(t, 6, -0.4);
    consistent_pair(t, 1e-3, 1e-9);
    make_ladder(t, 3);
    consistent_pair(t, 0.0, 1e-7);
    free(t);
}

/* IDA with KLU: every Jacobian gives the same motion; colored and column
 * differences the same steps exactly; the analytic one no residual calls. */
static void test_ida_klu_runs(void **state)
{
    (void)state;
    test_scene *t = malloc(sizeof *t);
    make_chain(t, 8, 0.3);
    const int n = t->sys.n;
    double qe[4][3 * MAXB], tq[2] = {0.1, 0.2}, qs[2 * 3 * MAXB];
    cmp_ida_problem pb = {&t->sys, t->q0, t->v0, &t->s};
    cmp_ida_run_result r[4];
    const int jac[4] = {CMP_JAC_ANALYTIC, CMP_JAC_COLORED, CMP_JAC_COLUMN, CMP_JAC_COLORED};
    const int res[4] = {CMP_RES_AUTO, CMP_RES_AUTO, CMP_RES_AUTO, CMP_RES_CALLBACKS};
    for (int k = 0; k < 4; k++) {
        cmp_ida_run_opts o;
        memset(&o, 0, sizeof o);
        o.t_end = 0.5;
        o.rtol = o.atol = 1e-7;
        o.jac = jac[k];
        o.residual = res[k];
        o.q_end = qe[k];
        if (k == 0) {
            o.n_out = 2;
            o.t_out = tq;
            o.q_out = qs;
        }
        assert_int_equal(cmp_ida_klu_run(&pb, &o, &r[k]), 0);
        assert_true(r[k].success);
        assert_near(r[k].t_reached, 0.5, 0);
        assert_int_equal(r[k].jac, jac[k]);
        assert_int_equal(r[k].N, 2 * n + 2 * t->sys.m);
        assert_true(r[k].steps > 10);
    }
    assert_int_equal(r[0].residual, CMP_RES_SCENE);
    assert_int_equal(r[3].residual, CMP_RES_CALLBACKS);
    assert_int_equal(r[0].jac_res_evals, 0);
    assert_int_equal(r[1].jac_res_evals, (long)r[1].colors * r[1].jac_evals);
    assert_int_equal(r[2].jac_res_evals, (long)r[2].N * r[2].jac_evals);
    assert_true(r[1].colors < r[1].N / 4);
    /* Colored and column: the same Jacobians, the same run. */
    assert_int_equal(r[1].steps, r[2].steps);
    for (int i = 0; i < n; i++) {
        assert_near(qe[1][i], qe[2][i], 1e-12);
        assert_near(qe[0][i], qe[1][i], 1e-4);
        assert_near(qe[3][i], qe[1][i], 1e-4);
    }
    /* Samples: the state at 0.2 is on the constraints. */
    cmp_ggl *g = cmp_ggl_new(&t->s, NULL);
    const int N = cmp_ggl_size(g);
    double *y = calloc(3 * (size_t)N, sizeof(double));
    assert_non_null(y);
    memcpy(y, qs + n, (size_t)n * sizeof(double));
    assert_int_equal(cmp_ggl_residual(g, 0.0, y, y + N, y + 2 * N), 0);
    for (int k = 0; k < t->sys.m; k++) assert_near(y[2 * N + N - t->sys.m + k], 0.0, 1e-5);
    free(y);
    cmp_ggl_free(g);

    /* The redundant ladder: a clean failure, not a crash. */
    make_ladder(t, 2);
    cmp_ida_problem pl = {&t->sys, t->q0, t->v0, &t->s};
    cmp_ida_run_opts o;
    memset(&o, 0, sizeof o);
    o.t_end = 0.1;
    o.rtol = 1e-6;
    cmp_ida_run_result rl;
    assert_int_equal(cmp_ida_klu_run(&pl, &o, &rl), -1);
    assert_false(rl.success);
    free(t);
}

/* The study's path: a scene target with KLU gets the analytic Jacobian and
 * follows the dense run. */
static void test_study_klu(void **state)
{
    (void)state;
    cmp_target tg;
    char err[256];
    assert_int_equal(cmp_target_find("chain-5", &tg, err, sizeof err), 0);
    cmp_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.method = CMP_IDA_GGL;
    sp.integrator = -1;
    sp.rtol = sp.atol = 1e-8;
    sp.T = 1.0;
    sp.dt_out = 0.05;
    cmp_traj a, b;
    cmp_outcome oa, ob;
    assert_int_equal(cmp_traj_init(&a, tg.sys.n, 32), 0);
    assert_int_equal(cmp_traj_init(&b, tg.sys.n, 32), 0);
    sp.ida.linsol = CMP_LS_DENSE;
    cmp_run_ida(&tg, &sp, &a, &oa);
    sp.ida.linsol = CMP_LS_KLU;
    cmp_run_ida(&tg, &sp, &b, &ob);
    assert_int_equal(oa.status, 0);
    assert_int_equal(ob.status, 0);
    assert_int_equal(a.count, 21);
    assert_int_equal(b.count, 21);
    for (long k = 0; k < a.count * tg.sys.n; k++) assert_near(a.q[k], b.q[k], 1e-5);
    cmp_traj_free(&a);
    cmp_traj_free(&b);
    cmp_target_free(&tg);
}

static void test_csc_pairs(void **state)
{
    (void)state;
    const int r[] = {2, 0, 2, 1, 0, 2}, c[] = {0, 1, 0, 1, 1, 2};
    int map[6], *cp, *ri;
    assert_int_equal(cmp_csc_from_pairs(3, 6, r, c, &cp, &ri, map), 4);
    const int ecp[] = {0, 1, 3, 4}, eri[] = {2, 0, 1, 2}, emap[] = {0, 1, 0, 2, 1, 3};
    for (int j = 0; j <= 3; j++) assert_int_equal(cp[j], ecp[j]);
    for (int k = 0; k < 4; k++) assert_int_equal(ri[k], eri[k]);
    for (int k = 0; k < 6; k++) assert_int_equal(map[k], emap[k]);
    free(cp);
    free(ri);
}

#ifdef BRAUN_MAX_SPARSE
/* A system with a sparsity (compressed A, block M) reads as the dense one. */
static const braun_builtin *fb;
static int fb_mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)u;
    double D[BRAUN_MODEL_MAX_N * BRAUN_MODEL_MAX_N];
    int st = fb->sys.mass(t, q, D, fb->sys.user);
    const int n = fb->sys.n;
    for (int i = 0; i < n * n; i++) M[i] = D[i]; /* one block of size n */
    return st;
}
static int sp_rowptr[64], sp_col[1024], sp_block[1];
static int fb_hol(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                  braun_real *A, braun_real *b, braun_real *bv, void *u)
{
    (void)u;
    const int n = fb->sys.n, m = fb->sys.m;
    double D[64 * BRAUN_MODEL_MAX_N];
    int st = fb->sys.holonomic(t, q, v, phi, A ? D : NULL, b, bv, fb->sys.user);
    if (A)
        for (int k = 0; k < m; k++)
            for (int e = sp_rowptr[k]; e < sp_rowptr[k + 1]; e++) A[e] = D[k * n + sp_col[e]];
    return st;
}

static void test_dae_sparse_system(void **state)
{
    (void)state;
    cmp_target tg;
    char err[256];
    assert_int_equal(cmp_target_find("four-bar", &tg, err, sizeof err), 0);
    fb = tg.builtin;
    const int n = tg.sys.n, m = tg.sys.m;
    /* Pattern: the nonzeros of A at q0 and a perturbed q. */
    double A1[64 * BRAUN_MODEL_MAX_N], A2[64 * BRAUN_MODEL_MAX_N], phi[64], q[BRAUN_MODEL_MAX_N];
    assert_int_equal(tg.sys.holonomic(0, tg.q0, tg.v0, phi, A1, NULL, NULL, tg.sys.user), 0);
    for (int i = 0; i < n; i++) q[i] = tg.q0[i] + 0.1 * sin(i + 1.0);
    assert_int_equal(tg.sys.holonomic(0, q, tg.v0, phi, A2, NULL, NULL, tg.sys.user), 0);
    int e = 0;
    for (int k = 0; k < m; k++) {
        sp_rowptr[k] = e;
        for (int j = 0; j < n; j++)
            if (A1[k * n + j] != 0 || A2[k * n + j] != 0) sp_col[e++] = j;
    }
    sp_rowptr[m] = e;
    sp_block[0] = n;
    braun_sparsity sp = {sp_rowptr, sp_col, 1, sp_block};
    cmp_target ts = tg;
    ts.sys.mass = fb_mass;
    ts.sys.holonomic = fb_hol;
    ts.sys.sparsity = &sp;
    cmp_dae *d1 = cmp_dae_new(&tg, 0), *d2 = cmp_dae_new(&ts, 0);
    const int N = cmp_dae_size(d1);
    double y[64], yp[64], r1[64], r2[64];
    random_state(N, 5, y, yp);
    assert_int_equal(cmp_dae_residual(d1, 0, y, yp, r1), 0);
    assert_int_equal(cmp_dae_residual(d2, 0, y, yp, r2), 0);
    for (int i = 0; i < N; i++) assert_near(r1[i], r2[i], 0);
    cmp_dae_free(d1);
    cmp_dae_free(d2);
    cmp_target_free(&tg);
}
#endif

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_csc_pairs),
        cmocka_unit_test(test_provider_chain),
        cmocka_unit_test(test_provider_rods),
        cmocka_unit_test(test_provider_ladder),
        cmocka_unit_test(test_provider_refuses),
        cmocka_unit_test(test_callback_patterns),
        cmocka_unit_test(test_consistent),
        cmocka_unit_test(test_ida_klu_runs),
        cmocka_unit_test(test_study_klu),
#ifdef BRAUN_MAX_SPARSE
        cmocka_unit_test(test_dae_sparse_system),
#endif
    };
    return cmocka_run_group_tests_name("compare-ida-jac", tests, NULL, NULL);
}
