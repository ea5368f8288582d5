/* Sparse scenes (braun_scene_build_sparse): for every shipped scene without
 * rods, for chains and ladders written by the generator of `braun gen`
 * (src/host/cli/cli_gen.c, compiled in below) and for a scene with every element
 * type, the sparse callbacks' compressed values scattered into dense
 * matrices equal the dense callbacks' output exactly, at random states and
 * with any outputs left NULL; the pattern is sorted, in range and exactly
 * the coordinates of the bodies of each row's element; the mass blocks are
 * the bodies' blocks. The ladder's redundancy (rank 11N of 12N rows) is
 * measured with libbraun's rank-revealing QR, and sparse and dense systems
 * integrate to the same trajectory. Scenes with rods have no sparsity. */
#define _XOPEN_SOURCE 700 /* opendir, mkstemp; realpath (cli_files.c, included below): with
                           * _POSIX_C_SOURCE alone it was implicitly declared */
#include <dirent.h>
#include <unistd.h>

#include "test_util.h"
#include "braun_linalg.h"
#include "braun_scene_file.h"

/* ------------------------------------------ the generator of `braun gen` */
#include "../src/host/cli/cli_gen.c"
#include "../src/host/cli/cli_option.c"
/* ... which writes its file through cli_files.c (braun gen -o) and reads
 * --angle as every real option is read. */
#include "../src/host/cli/cli_files.c"
#include "../src/host/cli/cli_real.c"

/* What cli_gen.c needs from the rest of the tool. */
int braun_cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("braun: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return BRAUN_CLI_USAGE;
}

/* `braun gen KIND N [--angle DEG] [--rods]` into a temporary file, loaded. */
static braun_scene_file *generate(const char *kind, int count, const char *angle, int rods)
{
    char path[] = "/tmp/braun-test-sparse-XXXXXX", num[16], err[512];
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    snprintf(num, sizeof num, "%d", count);
    char *argv[8] = {(char *)kind, num, "-o", path, NULL, NULL, NULL, NULL};
    int argc = 4;
    if (angle) {
        argv[argc++] = "--angle";
        argv[argc++] = (char *)angle;
    }
    if (rods) argv[argc++] = "--rods";
    assert_int_equal(braun_cli_gen(argc, argv), 0);
    braun_scene_file *f = braun_scene_load(path, err, sizeof err);
    unlink(path);
    if (!f) fail_msg("%s", err);
    return f;
}

/* ------------------------------------------------------------ helpers */
static uint64_t rng = 0x9E3779B97F4A7C15u;
static double uniform(double lo, double hi)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

typedef struct sparse_sys {
    braun_system sys;
    void *buf;
} sparse_sys;

static void open_sparse(braun_scene *s, sparse_sys *sp)
{
    const size_t bytes = braun_scene_sparse_size(s);
    braun_scene_error err;
    assert_true(bytes > 0);
    sp->buf = malloc(bytes);
    assert_non_null(sp->buf);
    const int st = braun_scene_build_sparse(s, &sp->sys, sp->buf, bytes, &err);
    if (st) fail_msg("braun_scene_build_sparse: %s (%d)", err.what ? err.what : "?", st);
}

static int dim_of(const braun_scene *s, int body)
{
    /* Coordinates per body, as docs/scene-format.md gives them. */
    const braun_scene_body_class *k = s->bodies[body].kind;
    if (k == BRAUN_BODY_RIGID) return 3;
    if (k == BRAUN_BODY_PARTICLE) return 2;
    if (k == BRAUN_BODY_RIGID3D) return 7;
    if (k == BRAUN_BODY_PARTICLE3D) return 3;
    fail_msg("body %d: a class this test does not know", body);
    return 0;
}

/* Rows of a joint, as braun_scene.h documents each type. */
static int joint_rows(const braun_scene_joint *j)
{
    const int d = j->driven != 0;
    if (j->type == BRAUN_JOINT_REVOLUTE) return 2;
    if (j->type == BRAUN_JOINT_SLIDER) return 1 + d;
    if (j->type == BRAUN_JOINT_PRISMATIC) return 2 + d;
    if (j->type == BRAUN_JOINT_SPHERICAL) return 3;
    if (j->type == BRAUN_JOINT_REVOLUTE3D) return 5 + d;
    if (j->type == BRAUN_JOINT_PRISMATIC3D) return 5 + d;
    if (j->type == BRAUN_JOINT_CYLINDRICAL) return 4;
    if (j->type == BRAUN_JOINT_UNIVERSAL) return 4;
    if (j->type == BRAUN_JOINT_WELD) return 6;
    if (j->type == BRAUN_JOINT_POINT_LINE) return 2;
    return 1; /* distance, angle, knife, point_plane */
}

/* Bodies of the element that owns each row, from the description alone
 * (-1 for the ground): the pattern must be exactly their coordinates. A
 * rigid3d body's own row (|p|^2 - 1) touches that body alone. */
static void row_bodies(const braun_scene *s, int row, int *b0, int *b1)
{
    *b0 = *b1 = -1;
    const int nonholonomic = row >= s->m;
    if (!nonholonomic)
        for (int k = 0; k < s->nbodies; k++)
            if (s->bodies[k].kind == BRAUN_BODY_RIGID3D && row == s->bodies[k].row) {
                *b0 = k;
                return;
            }
    if (nonholonomic) row -= s->m;
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        const int rows = joint_rows(j);
        if ((j->type == BRAUN_JOINT_KNIFE) != nonholonomic) continue;
        if (row < j->row || row >= j->row + rows) continue;
        if (j->type == BRAUN_JOINT_ANGLE) {
            *b0 = j->a;
            *b1 = j->b;
        } else if (j->type == BRAUN_JOINT_KNIFE) {
            *b0 = s->points[j->a].body;
        } else {
            *b0 = s->points[j->a].body;
            *b1 = s->points[j->b].body;
        }
        return;
    }
    fail_msg("row %d belongs to no element", row);
}

/* The pattern: sorted, in range, each row the coordinates of its element's
 * bodies; the blocks: one per body. The model accepts it. */
static void check_pattern(const char *what, const braun_scene *s, const braun_system *sys)
{
    const braun_sparsity *sp = sys->sparsity;
    const int n = sys->n, rows = sys->m + sys->p;
    assert_non_null(sp);
    assert_int_equal(sp->row_ptr[0], 0);
    int *want = calloc((size_t)n, sizeof *want);
    for (int r = 0; r < rows; r++) {
        int b0, b1, count = 0;
        assert_true(sp->row_ptr[r + 1] >= sp->row_ptr[r]);
        row_bodies(s, r, &b0, &b1);
        for (int i = 0; i < n; i++) want[i] = 0;
        if (b0 >= 0)
            for (int c = 0; c < dim_of(s, b0); c++) want[s->bodies[b0].iq + c] = 1;
        if (b1 >= 0)
            for (int c = 0; c < dim_of(s, b1); c++) want[s->bodies[b1].iq + c] = 1;
        for (int i = 0; i < n; i++) count += want[i];
        if (sp->row_ptr[r + 1] - sp->row_ptr[r] != count)
            fail_msg("%s: row %d has %d entries, its bodies %d coordinates", what, r,
                     sp->row_ptr[r + 1] - sp->row_ptr[r], count);
        for (int k = sp->row_ptr[r]; k < sp->row_ptr[r + 1]; k++) {
            const int c = sp->col[k];
            if (c < 0 || c >= n || !want[c] || (k > sp->row_ptr[r] && c <= sp->col[k - 1]))
                fail_msg("%s: row %d entry %d: column %d out of range, unsorted or not of "
                         "its element's bodies", what, r, k - sp->row_ptr[r], c);
        }
    }
    free(want);
    assert_int_equal(sp->nblocks, s->nbodies);
    int sum = 0;
    for (int k = 0; k < sp->nblocks; k++) {
        assert_int_equal(sp->block[k], dim_of(s, k));
        assert_int_equal(s->bodies[k].iq, sum);
        sum += sp->block[k];
    }
    assert_int_equal(sum, n);
    braun_model model;
    assert_int_equal(braun_model_init(&model, sys), BRAUN_OK);
}

static long mismatches;
static void same(const char *what, const char *term, int i, int j, double dense, double sparse)
{
    if (dense == sparse) return;
    if (mismatches++ < 5)
        print_error("%s: %s[%d][%d] dense %.17g, sparse %.17g\n", what, term, i, j, dense,
                    sparse);
}

/* Compressed rows first..first+rows (value k at k - base) into dense. */
static void scatter(const braun_sparsity *sp, int first, int rows, int n, const double *vals,
                    double *A)
{
    const int base = sp->row_ptr[first];
    for (size_t i = 0; i < (size_t)rows * (size_t)n; i++) A[i] = 0;
    for (int r = 0; r < rows; r++)
        for (int k = sp->row_ptr[first + r]; k < sp->row_ptr[first + r + 1]; k++)
            A[(size_t)r * (size_t)n + (size_t)sp->col[k]] = vals[k - base];
}

/* Every callback of both systems at one state: equal bit for bit. */
static void compare_at(const char *what, const braun_system *d, const braun_system *s,
                       double t, const double *q, const double *v)
{
    const int n = d->n, m = d->m, p = d->p, rows = m + p;
    const braun_sparsity *sp = s->sparsity;
    const int nnz = sp->row_ptr[rows], rmax = rows > 0 ? rows : 1;
    double *Ad = malloc(sizeof(double) * (size_t)rmax * (size_t)n);
    double *As = malloc(sizeof(double) * (size_t)rmax * (size_t)n);
    double *vals = malloc(sizeof(double) * (size_t)(nnz > 0 ? nnz : 1));
    double *vals2 = malloc(sizeof(double) * (size_t)(nnz > 0 ? nnz : 1));
    const int w = rmax > n ? rmax : n; /* vectors of rows or of n entries */
    double *vec = malloc(sizeof(double) * 9 * (size_t)w);
    double *phd = vec, *bd = phd + w, *bvd = bd + w, *phs = bvd + w, *bs = phs + w,
           *bvs = bs + w, *ph2 = bvs + w, *b2 = ph2 + w, *bv2 = b2 + w;
    assert_non_null(Ad);
    assert_non_null(As);
    assert_non_null(vals);
    assert_non_null(vals2);
    assert_non_null(vec);

    /* Mass: the blocks in order, zero elsewhere. */
    double *Md = malloc(sizeof(double) * (size_t)n * (size_t)n);
    double *Ms = malloc(sizeof(double) * (size_t)n * (size_t)n);
    double *blk = malloc(sizeof(double) * 9 * (size_t)n);
    assert_int_equal(d->mass(t, q, Md, d->user), 0);
    assert_int_equal(s->mass(t, q, blk, s->user), 0);
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++) Ms[i] = 0;
    for (int k = 0, off = 0, at = 0; k < sp->nblocks; off += sp->block[k], k++)
        for (int i = 0; i < sp->block[k]; i++)
            for (int j = 0; j < sp->block[k]; j++)
                Ms[(size_t)(off + i) * (size_t)n + (size_t)(off + j)] = blk[at++];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            same(what, "M", i, j, Md[(size_t)i * n + j], Ms[(size_t)i * n + j]);
    free(Md);
    free(Ms);
    free(blk);

    /* Forces, energy law, power: the same vectors through another user. */
    assert_int_equal(d->forces(t, q, v, phd, d->user), 0);
    assert_int_equal(s->forces(t, q, v, phs, s->user), 0);
    for (int i = 0; i < n; i++) same(what, "Q", i, -1, phd[i], phs[i]);
    assert_true((d->energy == NULL) == (s->energy == NULL));
    if (d->energy) {
        double Ed, Es, tdd, tds;
        assert_int_equal(d->energy(t, q, v, &Ed, phd, bd, &tdd, d->user), 0);
        assert_int_equal(s->energy(t, q, v, &Es, phs, bs, &tds, s->user), 0);
        same(what, "E", -1, -1, Ed, Es);
        same(what, "dE/dt", -1, -1, tdd, tds);
        for (int i = 0; i < n; i++) {
            same(what, "dE/dq", i, -1, phd[i], phs[i]);
            same(what, "dE/dv", i, -1, bd[i], bs[i]);
        }
    }
    assert_true((d->power == NULL) == (s->power == NULL));
    if (d->power) {
        double Pd, Ps;
        assert_int_equal(d->power(t, q, v, &Pd, d->user), 0);
        assert_int_equal(s->power(t, q, v, &Ps, s->user), 0);
        same(what, "Edot", -1, -1, Pd, Ps);
    }

    if (m > 0) {
        assert_int_equal(d->holonomic(t, q, v, phd, Ad, bd, bvd, d->user), 0);
        /* Outputs left out, then A alone, then all: the scratch stays clean. */
        assert_int_equal(s->holonomic(t, q, v, NULL, NULL, NULL, NULL, s->user), 0);
        assert_int_equal(s->holonomic(t, q, v, NULL, vals2, NULL, NULL, s->user), 0);
        assert_int_equal(s->holonomic(t, q, v, ph2, NULL, b2, bv2, s->user), 0);
        assert_int_equal(s->holonomic(t, q, v, phs, vals, bs, bvs, s->user), 0);
        scatter(sp, 0, m, n, vals, As);
        for (int i = 0; i < m; i++) {
            same(what, "phi_q", i, -1, phd[i], phs[i]);
            same(what, "b_q", i, -1, bd[i], bs[i]);
            same(what, "b_qv", i, -1, bvd[i], bvs[i]);
            same(what, "phi_q (A NULL)", i, -1, phd[i], ph2[i]);
            same(what, "b_q (A NULL)", i, -1, bd[i], b2[i]);
            same(what, "b_qv (A NULL)", i, -1, bvd[i], bv2[i]);
            for (int j = 0; j < n; j++)
                same(what, "A_q", i, j, Ad[(size_t)i * n + j], As[(size_t)i * n + j]);
        }
        for (int k = 0; k < sp->row_ptr[m]; k++) same(what, "A_q values (A alone)", k, -1, vals[k], vals2[k]);
    }
    if (p > 0) {
        const int base = sp->row_ptr[m], cnt = sp->row_ptr[rows] - base;
        assert_int_equal(d->nonholonomic(t, q, v, phd, Ad, bvd, d->user), 0);
        assert_int_equal(s->nonholonomic(t, q, v, NULL, NULL, NULL, s->user), 0);
        assert_int_equal(s->nonholonomic(t, q, v, NULL, vals2, NULL, s->user), 0);
        assert_int_equal(s->nonholonomic(t, q, v, ph2, NULL, bv2, s->user), 0);
        assert_int_equal(s->nonholonomic(t, q, v, phs, vals, bvs, s->user), 0);
        scatter(sp, m, p, n, vals, As);
        for (int i = 0; i < p; i++) {
            same(what, "phi_v", i, -1, phd[i], phs[i]);
            same(what, "b_vv", i, -1, bvd[i], bvs[i]);
            same(what, "phi_v (A NULL)", i, -1, phd[i], ph2[i]);
            same(what, "b_vv (A NULL)", i, -1, bvd[i], bv2[i]);
            for (int j = 0; j < n; j++)
                same(what, "A_vv", i, j, Ad[(size_t)i * n + j], As[(size_t)i * n + j]);
        }
        for (int k = 0; k < cnt; k++) same(what, "A_vv values (A alone)", k, -1, vals[k], vals2[k]);
    }
    free(Ad);
    free(As);
    free(vals);
    free(vals2);
    free(vec);
}

/* The initial state and `states` random ones around it. */
static void compare_scene(const char *what, braun_scene_file *f, int states)
{
    sparse_sys sp;
    open_sparse(&f->scene, &sp);
    check_pattern(what, &f->scene, &sp.sys);
    const int n = f->sys.n;
    double *q = malloc(sizeof(double) * 2 * (size_t)n), *v = q + n;
    mismatches = 0;
    compare_at(what, &f->sys, &sp.sys, 0, f->q0, f->v0);
    for (int k = 0; k < states; k++) {
        for (int i = 0; i < n; i++) {
            q[i] = f->q0[i] + uniform(-0.7, 0.7);
            v[i] = uniform(-2, 2);
        }
        compare_at(what, &f->sys, &sp.sys, uniform(0, 3), q, v);
    }
    if (mismatches) fail_msg("%s: %ld entries differ", what, mismatches);
    free(q);
    free(sp.buf);
}

/* ---------------------------------------------------------------- tests */
static void shipped_in(const char *folder, int *sparse, int *dense)
{
    DIR *dir = opendir(folder);
    struct dirent *e;
    assert_non_null(dir);
    while ((e = readdir(dir)) != NULL) {
        const size_t len = strlen(e->d_name);
        char path[300], err[512];
        if (len < 6 || strcmp(e->d_name + len - 5, ".json") != 0) continue;
        snprintf(path, sizeof path, "%s/%s", folder, e->d_name);
        braun_scene_file *f = braun_scene_load(path, err, sizeof err);
        if (!f) fail_msg("%s", err);
        if (f->scene.nrods > 0) {
            /* Rods couple mass blocks: no sparsity, and saying so. */
            braun_scene_error berr;
            braun_system sys = f->sys;
            char buf[64];
            assert_int_equal(braun_scene_sparse_size(&f->scene), 0);
            assert_int_equal(braun_scene_build_sparse(&f->scene, &sys, buf, sizeof buf, &berr),
                             BRAUN_ERR_ARGUMENT);
            assert_int_equal(berr.element, BRAUN_SCENE_ELEM_ROD);
            assert_non_null(strstr(berr.what, "rods"));
            assert_ptr_equal(sys.user, f->sys.user); /* untouched */
            (*dense)++;
        } else {
            compare_scene(path, f, 25);
            (*sparse)++;
        }
        braun_scene_free(f);
    }
    closedir(dir);
}

static void test_shipped_scenes(void **state)
{
    (void)state;
    int sparse = 0, dense = 0;
    shipped_in("data", &sparse, &dense);
    shipped_in("data/iftomm", &sparse, &dense);
    print_message("shipped scenes: %d sparse (every callback exact at 26 states), %d with rods "
                  "(no sparsity)\n", sparse, dense);
    assert_true(sparse >= 12);
    assert_true(dense >= 1);
}

static void test_generated_chains(void **state)
{
    (void)state;
    static const int sizes[] = {1, 2, 7, 40};
    static const char *const angles[] = {NULL, "60", "-35.5"};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        for (size_t a = 0; a < sizeof angles / sizeof angles[0]; a++) {
            char what[64];
            braun_scene_file *f = generate("chain", sizes[i], angles[a], 0);
            snprintf(what, sizeof what, "chain %d --angle %s", sizes[i], angles[a] ? angles[a] : "0");
            assert_int_equal(f->sys.n, 3 * sizes[i]);
            assert_int_equal(f->sys.m, 2 * sizes[i]);
            compare_scene(what, f, 10);
            /* Straight and on the constraints at rest. */
            double phi[80];
            assert_int_equal(f->sys.holonomic(0, f->q0, f->v0, phi, NULL, NULL, NULL, f->sys.user), 0);
            for (int r = 0; r < f->sys.m; r++) assert_near(phi[r], 0, 1e-14);
            if (angles[a]) {
                const double phi0 = atof(angles[a]) * PI / 180;
                for (int k = 0; k < sizes[i]; k++) assert_near(f->q0[3 * k + 2], -phi0, 1e-15);
                assert_near(f->q0[1], -0.5 * sin(phi0), 1e-15);
            }
            braun_scene_free(f);
        }
    /* Rods: natural coordinates, no sparsity. */
    braun_scene_file *f = generate("chain", 6, "45", 1);
    assert_int_equal(braun_scene_sparse_size(&f->scene), 0);
    double phi[8];
    assert_int_equal(f->sys.holonomic(0, f->q0, f->v0, phi, NULL, NULL, NULL, f->sys.user), 0);
    for (int r = 0; r < f->sys.m; r++) assert_near(phi[r], 0, 1e-14);
    braun_scene_free(f);
}

/* Rank of A_q at the scene's initial state with libbraun's rank-revealing
 * QR (column pivoting of A^T) at relative tolerance tol. */
static int rank_at_start(const braun_scene_file *f, double tol)
{
    const braun_system *s = &f->sys;
    braun_qrcp qr;
    double *reals = malloc(sizeof(double) * braun_qrcp_reals(s->n, s->m));
    int *ints = malloc(sizeof(int) * braun_qrcp_ints(s->m));
    assert_non_null(reals);
    assert_non_null(ints);
    braun_qrcp_bind(&qr, s->n, s->m, reals, ints);
    assert_int_equal(s->holonomic(0, f->q0, f->v0, NULL, qr.a, NULL, NULL, s->user), 0);
    const int rank = braun_qrcp_factor(&qr, tol);
    free(reals);
    free(ints);
    return rank;
}

static void test_ladders(void **state)
{
    (void)state;
    static const int sizes[] = {1, 2, 5, 12};
    static const char *const angles[] = {NULL, "60", "-20"};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        for (size_t a = 0; a < sizeof angles / sizeof angles[0]; a++) {
            const int N = sizes[i];
            char what[64];
            braun_scene_file *f = generate("ladder", N, angles[a], 0);
            snprintf(what, sizeof what, "ladder %d --angle %s", N, angles[a] ? angles[a] : "30");
            assert_int_equal(f->sys.n, 12 * N);
            assert_int_equal(f->sys.m, 12 * N);
            assert_int_equal(f->sys.p, 0);
            /* Consistent and at rest. */
            braun_real pos, vel;
            test_sim sim;
            assert_int_equal(test_sim_open(&sim, &f->sys, BRAUN_CORRECT_NONE), BRAUN_OK);
            assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
            assert_int_equal(braun_residuals(&sim.data, 0, f->q0, f->v0, &pos, &vel, NULL), 0);
            assert_le(pos, 1e-14 * N);
            assert_le(vel, 0);
            test_sim_close(&sim);
            /* One redundant row per cell: the same rank over seven decades
             * of tolerance, so the gap is clear. */
            const int r_tight = rank_at_start(f, 1e-13), r_loose = rank_at_start(f, 1e-6);
            if (r_tight != 11 * N || r_loose != 11 * N)
                fail_msg("%s: rank %d (tol 1e-13), %d (tol 1e-6), expected %d", what, r_tight,
                         r_loose, 11 * N);
            compare_scene(what, f, 8);
            braun_scene_free(f);
        }
    print_message("ladders N = 1, 2, 5, 12 at 30, 60, -20 degrees: rank 11N of 12N rows, "
                  "sparse callbacks exact\n");
}

/* Every element type but rods, driven joints included, every effect. */
static void test_every_element(void **state)
{
    (void)state;
    static const char text[] =
        "{\"name\": \"all\", \"ground\": {\"points\": {\"O\": [0, 0]}},\n"
        " \"bodies\": [\n"
        "  {\"name\": \"A\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.1, \"position\": [0.5, 0.1],\n"
        "   \"angle\": 0.2, \"velocity\": [0.1, 0.2], \"omega\": 0.3, \"points\": {\"p\": [-0.5, 0], \"q\": [0.5, 0.1]}},\n"
        "  {\"name\": \"P\", \"type\": \"particle\", \"mass\": 0.7, \"position\": [1.2, -0.3]},\n"
        "  {\"name\": \"B\", \"type\": \"rigid\", \"mass\": 2, \"inertia\": 0.3, \"position\": [2, 1],\n"
        "   \"angle\": -0.4, \"points\": {\"r\": [0.2, -0.1]}},\n"
        "  {\"name\": \"C\", \"type\": \"rigid\", \"mass\": 1.5, \"inertia\": 0.2, \"position\": [3, 0.5],\n"
        "   \"angle\": 0.7, \"points\": {\"s\": [0.3, 0.2]}},\n"
        "  {\"name\": \"D\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.05, \"position\": [-1, 2]},\n"
        "  {\"name\": \"S\", \"type\": \"rigid\", \"mass\": 3, \"inertia\": 0.4, \"position\": [4, -1]}\n"
        " ],\n"
        " \"joints\": [\n"
        "  {\"type\": \"revolute\", \"a\": \"A.p\", \"b\": \"ground.O\"},\n"
        "  {\"type\": \"distance\", \"a\": \"A.q\", \"b\": \"P\"},\n"
        "  {\"type\": \"distance\", \"a\": \"P\", \"b\": \"B.r\",\n"
        "   \"drive\": {\"type\": \"sine\", \"offset\": 1, \"amplitude\": 0.1, \"omega\": 2, \"phase\": 0.3}},\n"
        "  {\"type\": \"slider\", \"point\": \"P\", \"line\": \"C.s\", \"axis\": [1, 0.5]},\n"
        "  {\"type\": \"slider\", \"point\": \"B.r\", \"line\": [0, 0], \"axis\": [0.3, 1],\n"
        "   \"drive\": {\"type\": \"linear\", \"value\": 0.5, \"rate\": 0.2}},\n"
        "  {\"type\": \"prismatic\", \"point\": \"D\", \"line\": \"C.s\", \"axis\": [0, 1],\n"
        "   \"drive\": {\"type\": \"sine\", \"offset\": 0, \"amplitude\": 0.2, \"omega\": 1, \"phase\": 0}},\n"
        "  {\"type\": \"prismatic\", \"point\": \"C.s\", \"line\": [1, 1], \"axis\": [1, 0]},\n"
        "  {\"type\": \"angle\", \"a\": \"ground\", \"b\": \"B\"},\n"
        "  {\"type\": \"angle\", \"a\": \"C\", \"b\": \"A\", \"drive\": {\"type\": \"linear\", \"value\": 0, \"rate\": 1}},\n"
        "  {\"type\": \"knife\", \"body\": \"S\", \"at\": [0.2, 0.1], \"direction\": [1, 0.2]},\n"
        "  {\"type\": \"knife\", \"body\": \"D\", \"direction\": [0, 1]}\n"
        " ],\n"
        " \"effects\": [\n"
        "  {\"type\": \"gravity\", \"g\": [0.5, -9.81]},\n"
        "  {\"type\": \"spring\", \"a\": \"A.q\", \"b\": \"S\", \"stiffness\": 3, \"damping\": 0.2},\n"
        "  {\"type\": \"torsion\", \"a\": \"B\", \"b\": \"ground\", \"stiffness\": 2, \"damping\": 0.1},\n"
        "  {\"type\": \"force\", \"point\": \"P\", \"fx\": 1, \"fy\": {\"type\": \"sine\", \"offset\": 0,\n"
        "   \"amplitude\": 1, \"omega\": 3, \"phase\": 0}},\n"
        "  {\"type\": \"torque\", \"body\": \"C\", \"reaction\": \"S\", \"torque\": 0.5},\n"
        "  {\"type\": \"motor\", \"rotor\": \"D\", \"stall_torque\": 1, \"no_load_speed\": 10}\n"
        " ],\n"
        " \"corrections\": [\"position\", \"velocity\"]}\n";
    char err[512];
    braun_scene_file *f = braun_scene_load_text("all.json", text, strlen(text), err, sizeof err);
    if (!f) fail_msg("%s", err);
    assert_int_equal(f->sys.p, 2);
    assert_non_null(f->sys.power);
    compare_scene("every element", f, 40);
    braun_scene_free(f);
}

/* The builder's side: sizes above 4096, buffers, rods, alignment. */
static void test_build_sparse(void **state)
{
    (void)state;
    braun_scene_error err;
    braun_system sys, dense;
    braun_model model;

    /* A chain of 2000 links: n = 6000 > 4096. Built; only sparse runs. */
    braun_scene_file *f = generate("chain", 2000, "10", 0);
    assert_int_equal(f->sys.n, 6000);
    assert_int_equal(braun_model_init(&model, &f->sys), BRAUN_ERR_SIZE);
    const size_t bytes = braun_scene_sparse_size(&f->scene);
    unsigned char *buf = malloc(bytes + 1);
    assert_non_null(buf);
    memset(&sys, 0, sizeof sys);
    assert_int_equal(braun_scene_build_sparse(&f->scene, &sys, buf, bytes - 1, &err),
                     BRAUN_ERR_BUFFER);
    assert_int_equal(sys.n, 0); /* untouched on failure */
    assert_int_equal(braun_scene_build_sparse(&f->scene, &sys, NULL, bytes, &err),
                     BRAUN_ERR_BUFFER);
    /* Any alignment of the buffer. */
    assert_int_equal(braun_scene_build_sparse(&f->scene, &sys, buf + 1, bytes, &err), BRAUN_OK);
    assert_int_equal(braun_model_init(&model, &sys), BRAUN_OK);
    check_pattern("chain 2000", &f->scene, &sys);
    /* 2 rows of 3 at the pivot, 2 of 6 at each hinge; 2000 blocks of 3. */
    assert_int_equal(sys.sparsity->row_ptr[sys.m], 6 + 1999 * 12);
    double *vals = malloc(sizeof(double) * 6 * 4000), *phi = malloc(sizeof(double) * 4000 * 3);
    double *M = malloc(sizeof(double) * 9 * 2000);
    assert_int_equal(sys.holonomic(0.1, f->q0, f->v0, phi, vals, phi + 4000, phi + 8000, sys.user), 0);
    for (int k = 0; k < 6 + 1999 * 12; k++) assert_true(isfinite(vals[k]));
    for (int r = 0; r < sys.m; r++) assert_near(phi[r], 0, 1e-12);
    assert_int_equal(sys.mass(0, f->q0, M, sys.user), 0);
    assert_near(M[9 * 1999 + 8], 1.0 / 12, 1e-17);
    free(vals);
    free(phi);
    free(M);
    free(buf);
    braun_scene_free(f);

    /* A scene with rods stays within 4096: 2049 rods between particles
     * need 4098 coordinates. Point 0 is the ground, point i + 1 particle i. */
    enum { NP = 2049 };
    braun_scene_body *bodies = calloc(NP, sizeof *bodies);
    braun_scene_point *points = calloc(NP + 1, sizeof *points);
    braun_scene_rod *rods = calloc(NP, sizeof *rods);
    points[0].body = BRAUN_SCENE_GROUND;
    for (int i = 0; i < NP; i++) {
        bodies[i].kind = BRAUN_BODY_PARTICLE;
        bodies[i].mass = 1;
        bodies[i].q0[0] = i + 1;
        points[i + 1].body = i;
        rods[i].a = i;
        rods[i].b = i + 1;
        rods[i].mass = 1;
        rods[i].length = 1;
    }
    braun_scene s = {0};
    s.nbodies = NP;
    s.bodies = bodies;
    s.npoints = NP + 1;
    s.points = points;
    s.nrods = NP;
    s.rods = rods;
    assert_int_equal(braun_scene_build(&s, &dense, &err), BRAUN_ERR_SIZE);
    assert_non_null(strstr(err.what, "rods"));
    s.nbodies = s.nrods = 2000; /* n = 4000: fine, dense */
    s.npoints = 2001;
    assert_int_equal(braun_scene_build(&s, &dense, &err), BRAUN_OK);
    assert_null(dense.sparsity);
    assert_int_equal(braun_scene_sparse_size(&s), 0);
    assert_int_equal(braun_scene_build_sparse(&s, &sys, NULL, 0, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.element, BRAUN_SCENE_ELEM_ROD);
    /* An unbuilt scene has no size. */
    braun_scene blank = {0};
    assert_int_equal(braun_scene_sparse_size(&blank), 0);
    assert_int_equal(braun_scene_sparse_size(NULL), 0);
    free(bodies);
    free(points);
    free(rods);
}

/* Integrated through the core, the sparse system (scattered for the
 * built-in kernels) takes the dense system's steps. */
static void test_same_trajectory(void **state)
{
    (void)state;
    braun_scene_file *f = generate("ladder", 3, "40", 0);
    sparse_sys sp;
    test_sim a, b;
    open_sparse(&f->scene, &sp);
    assert_int_equal(test_sim_open(&a, &f->sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(test_sim_open(&b, &sp.sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&a.data, 0, f->q0, f->v0), BRAUN_OK);
    assert_int_equal(braun_set_state(&b.data, 0, f->q0, f->v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&a.data, BRAUN_RK4, 1e-3, 0.5, 1, NULL, NULL), BRAUN_OK);
    assert_int_equal(braun_integrate(&b.data, BRAUN_RK4, 1e-3, 0.5, 1, NULL, NULL), BRAUN_OK);
    double diff = 0;
    for (int i = 0; i < f->sys.n; i++)
        diff = fmax(diff, fmax(fabs(a.data.q[i] - b.data.q[i]), fabs(a.data.v[i] - b.data.v[i])));
    print_message("ladder 3, 500 RK4 steps: sparse and dense systems differ by %.3g; %ld "
                  "rank-deficient factorizations\n", diff, b.data.stats.rank_deficient);
    assert_le(diff, 1e-12);
    assert_int_equal(a.data.stats.steps, b.data.stats.steps);
    assert_true(b.data.stats.rank_deficient > 0);
    braun_data_release(&a.data);
    braun_data_release(&b.data);
    test_sim_close(&a);
    test_sim_close(&b);
    free(sp.buf);
    braun_scene_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_scenes),
        cmocka_unit_test(test_generated_chains),
        cmocka_unit_test(test_ladders),
        cmocka_unit_test(test_every_element),
        cmocka_unit_test(test_build_sparse),
        cmocka_unit_test(test_same_trajectory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
