/* The sparse system of a scene without rods (braun_scene_build_sparse).
 *
 * Structure. Every body's mass block is its own (its class's mass hook:
 * diag(m, m, I) or diag(m, m); rigid3d's 7 x 7 block at q): M is block
 * diagonal, one block per body in coordinate order. Every row of A_q and
 * A_vv belongs to one joint that touches at most two bodies (its class's
 * bodies hook, or the bodies of its reference fields), or to one body (its
 * own rows: a unit quaternion); its pattern is all the coordinates of those
 * bodies,
 * sorted — structural, not value-based, so an entry that happens to be 0 at
 * some state (the y column of a revolute joint's x row) is in it. Rods are
 * excluded: a rod's kinetic energy couples the blocks of its two ends.
 *
 * Values. The joint classes' eval hooks (scene_revolute.c, ...) write dense rows
 * with stride n. The sparse callbacks let each element write its rows into
 * a scratch block of rows_max x n held by the sparse store — all zero
 * between calls — then gather the element's pattern columns into the
 * compressed values and re-zero exactly those columns: O(nnz) per call,
 * never O(n·m), and nothing allocated.
 *
 * Memory: one caller buffer of braun_scene_sparse_size() bytes holds the
 * store (the pattern, the block sizes, the scratch); the system's user
 * pointer is the store, which points to the scene. */
#include <stdint.h>

#include "scene_internal.h"

struct braun_scene_sparse {
    braun_scene *scene;
    braun_sparsity sparsity; /* points into row_ptr, col, block below */
    int rows_max;            /* most rows of one element: rows of scratch */
    braun_real *scratch;     /* rows_max x n, zero between calls */
    int *row_ptr, *col, *block;
};

/* Alignment of the store's parts (pointers, reals, ints): 16 bytes, as
 * the core's workspace (a multiple of every scalar's alignment). */
#define SP_ALIGN ((size_t)16)

static size_t round_up(size_t x) { return (x + SP_ALIGN - 1) / SP_ALIGN * SP_ALIGN; }

static int body_dim(const braun_scene *s, int body)
{
    return s->bodies[body].kind->dof;
}

/* The bodies an element touches, ground dropped, in coordinate order
 * (bodies are numbered in order); returns how many (0..2). */
static int sorted_bodies(int a, int b, int out[2])
{
    int k = 0;
    if (a >= 0) out[k++] = a;
    if (b >= 0 && b != a) out[k++] = b;
    if (k == 2 && out[0] > out[1]) {
        const int t = out[0];
        out[0] = out[1];
        out[1] = t;
    }
    return k;
}

static int joint_bodies(const braun_scene *s, const braun_scene_joint *j, int out[2])
{
    int body[2];
    braun_scene__joint_bodies(s, j, body);
    return sorted_bodies(body[0], body[1], out);
}

/* Entries of one row of an element that touches these bodies. */
static int row_count(const braun_scene *s, const int *bodies, int nb)
{
    int c = 0;
    for (int i = 0; i < nb; i++) c += body_dim(s, bodies[i]);
    return c;
}

/* Sizes of the store of a built scene: rows_max, nnz. */
static void measure(const braun_scene *s, int *rows_max, long *nnz)
{
    int bodies[2], rmax = 0;
    long total = 0;
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        const int rows = j->type->rows(j);
        const int nb = joint_bodies(s, j, bodies);
        total += (long)rows * row_count(s, bodies, nb);
        if (rows > rmax) rmax = rows;
    }
    for (int k = 0; k < s->nbodies; k++) {
        const int rows = s->bodies[k].kind->rows;
        total += (long)rows * body_dim(s, k);
        if (rows > rmax) rmax = rows;
    }
    *rows_max = rmax;
    *nnz = total;
}

/* A built scene: sizes set and consistent with the description. */
static int is_built(const braun_scene *s)
{
    if (!s || s->n <= 0 || s->nbodies <= 0 || !s->bodies) return 0;
    long n = 0, p = 0;
    for (int k = 0; k < s->nbodies; k++) {
        if (!s->bodies[k].kind || s->bodies[k].iq != n) return 0;
        n += s->bodies[k].kind->dof;
    }
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (!j->type) return 0;
        if (j->type->nonholonomic) p += j->type->rows(j);
    }
    return n == s->n && s->p == p;
}

static size_t bytes_for(const braun_scene *s, int rows_max, long nnz)
{
    const size_t rows = (size_t)s->m + (size_t)s->p;
    const size_t ints = rows + 1 + (size_t)nnz + (size_t)s->nbodies;
    return SP_ALIGN - 1 + round_up(sizeof(braun_scene_sparse)) +
           round_up((size_t)rows_max * (size_t)s->n * sizeof(braun_real)) + ints * sizeof(int);
}

size_t braun_scene_sparse_size(const braun_scene *s)
{
    if (!is_built(s) || s->nrods > 0) return 0;
    int rows_max;
    long nnz;
    measure(s, &rows_max, &nnz);
    return bytes_for(s, rows_max, nnz);
}

/* ------------------------------------------------------------ callbacks */
/* Scratch rows [0, nrows) hold rows first.. of one element: gather the
 * pattern's values (into vals, indexed from base) and re-zero them. */
static void gather(braun_scene_sparse *sp, int first, int nrows, braun_real *vals, int base)
{
    const size_t n = (size_t)sp->scene->n;
    for (int k = 0; k < nrows; k++) {
        braun_real *row = sp->scratch + (size_t)k * n;
        const int r = first + k;
        for (int i = sp->row_ptr[r]; i < sp->row_ptr[r + 1]; i++) {
            vals[i - base] = row[sp->col[i]];
            row[sp->col[i]] = 0;
        }
    }
}

#define AT(x, r) ((x) ? (x) + (r) : NULL)

static int mass_sparse(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_scene *s = ((const braun_scene_sparse *)user)->scene;
    (void)t;
    /* Each body's block, row-major, as its class writes it into zeros. */
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        const int d = bd->kind->dof;
        for (int i = 0; i < d * d; i++) M[i] = 0;
        if (bd->kind->mass_at) bd->kind->mass_at(bd, q + bd->iq, M, d);
        else bd->kind->mass(bd, M, d);
        M += d * d;
    }
    return 0;
}

/* The rows of every joint of one kind (holonomic or not): evaluated into
 * the scratch, gathered into the compressed values from base. */
static int rows_sparse(braun_scene_sparse *sp, int nonholonomic, int first, int base,
                       braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                       braun_real *A, braun_real *b, braun_real *bv)
{
    const braun_scene *s = sp->scene;
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (j->type->nonholonomic != nonholonomic) continue;
        const int st = j->type->eval(s, j, t, q, v, AT(phi, j->row), A ? sp->scratch : NULL,
                                     AT(b, j->row), AT(bv, j->row));
        if (st) return st;
        if (A) gather(sp, first + j->row, j->type->rows(j), A, base);
    }
    if (nonholonomic) return 0;
    /* The bodies' own rows (after the joints'), b_q = 0. */
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        const int rows = bd->kind->rows;
        if (rows == 0) continue;
        bd->kind->constraint(bd, q + bd->iq, v ? v + bd->iq : NULL, AT(phi, bd->row),
                             A ? sp->scratch + bd->iq : NULL, s->n, v ? AT(bv, bd->row) : NULL);
        if (b)
            for (int r = 0; r < rows; r++) b[bd->row + r] = 0;
        if (A) gather(sp, bd->row, rows, A, base);
    }
    return 0;
}

static int holonomic_sparse(braun_real t, const braun_real *q, const braun_real *v,
                            braun_real *phi, braun_real *A, braun_real *b, braun_real *bv,
                            void *user)
{
    return rows_sparse(user, 0, 0, 0, t, q, v, phi, A, b, bv);
}

static int nonholonomic_sparse(braun_real t, const braun_real *q, const braun_real *v,
                               braun_real *phi, braun_real *A, braun_real *bv, void *user)
{
    braun_scene_sparse *sp = user;
    const int m = sp->scene->m;
    return rows_sparse(sp, 1, m, sp->row_ptr[m], t, q, v, phi, A, NULL, bv);
}

/* Vectors are the same as the dense system's; only user differs. */
static int forces_sparse(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                         void *user)
{
    return braun_scene__forces(t, q, v, Q, ((braun_scene_sparse *)user)->scene);
}

static int energy_sparse(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                         braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    return braun_scene__energy(t, q, v, E, dE_dq, dE_dv, dE_dt,
                               ((braun_scene_sparse *)user)->scene);
}

static int power_sparse(braun_real t, const braun_real *q, const braun_real *v,
                        braun_real *Edot, void *user)
{
    return braun_scene__power(t, q, v, Edot, ((braun_scene_sparse *)user)->scene);
}

/* ---------------------------------------------------------------- build */
/* Pattern of the rows of one element: its bodies' coordinates, sorted. */
static int fill_rows(const braun_scene *s, braun_scene_sparse *sp, int first, int rows,
                     const int *bodies, int nb, int at)
{
    for (int r = first; r < first + rows; r++) {
        sp->row_ptr[r] = at;
        for (int i = 0; i < nb; i++)
            for (int c = 0; c < body_dim(s, bodies[i]); c++)
                sp->col[at++] = s->bodies[bodies[i]].iq + c;
    }
    return at;
}

/* Pattern of the bodies' own rows (numbered after the holonomic joints'):
 * the body's coordinates. */
static int body_rows(const braun_scene *s, braun_scene_sparse *sp, int at)
{
    for (int k = 0; k < s->nbodies; k++) {
        const int body[1] = {k};
        at = fill_rows(s, sp, s->bodies[k].row, s->bodies[k].kind->rows, body, 1, at);
    }
    return at;
}

int braun_scene_build_sparse(braun_scene *s, braun_system *sys, void *buffer, size_t bytes,
                             braun_scene_error *err)
{
    const int S = BRAUN_SCENE_ELEM_SCENE;
    braun_system dense;
    int st = braun_scene_build(s, &dense, err);
    if (st) return st;
    if (s->nrods > 0)
        return braun_scene__fail(err, BRAUN_ERR_ARGUMENT, BRAUN_SCENE_ELEM_ROD, 0,
                    "a scene with rods has no sparsity (a rod couples the mass blocks of its "
                    "ends)");
    int rows_max;
    long nnz;
    measure(s, &rows_max, &nnz);
    if (!buffer || bytes < bytes_for(s, rows_max, nnz))
        return braun_scene__fail(err, BRAUN_ERR_BUFFER, S, -1,
                    "buffer smaller than braun_scene_sparse_size() bytes");

    /* Carve: the store, the scratch, the ints. */
    const uintptr_t addr = (uintptr_t)buffer;
    unsigned char *base = (unsigned char *)buffer + (SP_ALIGN - addr % SP_ALIGN) % SP_ALIGN;
    braun_scene_sparse *sp = (braun_scene_sparse *)(void *)base;
    base += round_up(sizeof *sp);
    sp->scene = s;
    sp->rows_max = rows_max;
    sp->scratch = (braun_real *)(void *)base;
    const size_t scratch = (size_t)rows_max * (size_t)s->n;
    for (size_t i = 0; i < scratch; i++) sp->scratch[i] = 0;
    base += round_up(scratch * sizeof(braun_real));
    sp->row_ptr = (int *)(void *)base;
    sp->col = sp->row_ptr + s->m + s->p + 1;
    sp->block = sp->col + nnz;

    /* Rows in order: holonomic joints (rows are numbered joints in order
     * when there are no rods), then nonholonomic ones. */
    int at = 0, bodies[2];
    for (int pass = 0; pass < 2; pass++) {
        for (int k = 0; k < s->njoints; k++) {
            const braun_scene_joint *j = &s->joints[k];
            if (j->type->nonholonomic != pass) continue;
            const int nb = joint_bodies(s, j, bodies);
            at = fill_rows(s, sp, (pass ? s->m : 0) + j->row, j->type->rows(j), bodies, nb, at);
        }
        if (pass == 0) at = body_rows(s, sp, at); /* the last rows of Φ_q */
    }
    sp->row_ptr[s->m + s->p] = at;
    for (int k = 0; k < s->nbodies; k++) sp->block[k] = body_dim(s, k);
    sp->sparsity.row_ptr = sp->row_ptr;
    sp->sparsity.col = sp->col;
    sp->sparsity.nblocks = s->nbodies;
    sp->sparsity.block = sp->block;

    dense.mass = mass_sparse;
    dense.forces = forces_sparse;
    dense.holonomic = s->m > 0 ? holonomic_sparse : NULL;
    dense.nonholonomic = s->p > 0 ? nonholonomic_sparse : NULL;
    dense.energy = dense.energy ? energy_sparse : NULL;
    dense.power = dense.power ? power_sparse : NULL;
    dense.user = sp;
    dense.sparsity = &sp->sparsity;
    *sys = dense;
    return BRAUN_OK;
}
