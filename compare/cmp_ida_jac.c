/* Sparse Jacobians for IDA with KLU (issue 7): patterns in compressed
 * sparse columns, Curtis-Powell-Reid colored finite differences, and the
 * analytic provider of the GGL form for scenes of rigid bodies, particles,
 * rods, revolute joints and gravity (a table keyed by class pointer says
 * what it knows of each class: "the classes it knows" below).
 *
 * The provider (cmp_ggl) evaluates exactly the rows of cmp_dae.c's GGL
 * residual, unknowns y = [q, v, λ, μ] (n, n, m, m):
 *     r_q  = q' - v + A_qᵀμ
 *     r_v  = M v' - Q - A_qᵀλ
 *     r_c1 = A_q v - b_q          (b_q = 0: every supported row is scleronomic)
 *     r_c2 = Φ_q
 * and the Newton matrix J = ∂F/∂y + c_j ∂F/∂y':
 *     r_q : c_j I + Σ_k μ_k H_k (q),  -I (v),  A_qᵀ (μ)
 *     r_v : -Σ_k λ_k H_k (q),  c_j M (v),  -A_qᵀ (λ)      (∂Q/∂q = ∂Q/∂v = 0: gravity)
 *     r_c1: (H_k v)ᵀ (q),  A_q (v)
 *     r_c2: A_q (q)
 * with H_k = ∂²Φ_k/∂q², which is where the rows' second derivatives enter
 * (revolute_h, and the rods in rows_eval).
 * The pattern of J is built once, by emitting every entry in a fixed
 * order ("pattern mode") and recording where each lands in the compressed
 * columns; a Jacobian evaluation emits the same sequence with values. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <klu.h>

#include "cmp.h"
#ifdef CMP_HAVE_SCENES
#include "braun_scene_file.h"
#endif


/* A growing list of (row, col) pairs: the entries of a pattern as found. */
void cmp_pairs_push(cmp_pairs *P, int r, int c)
{
    if (P->failed) return;
    if (P->n == P->cap) {
        long cap = P->cap ? 2 * P->cap : 1024;
        int *nr = realloc(P->r, (size_t)cap * sizeof(int));
        if (!nr) {
            P->failed = 1;
            return;
        }
        P->r = nr;
        int *nc = realloc(P->c, (size_t)cap * sizeof(int));
        if (!nc) {
            P->failed = 1;
            return;
        }
        P->c = nc;
        P->cap = cap;
    }
    P->r[P->n] = r;
    P->c[P->n] = c;
    P->n++;
}

void cmp_pairs_free(cmp_pairs *P)
{
    free(P->r);
    free(P->c);
    P->r = P->c = NULL;
    P->n = P->cap = 0;
}

/* ------------------------------------------------------------ patterns */
int cmp_csc_from_pairs(int N, long nt, const int *row, const int *col, int **colptr,
                       int **rowind, int *map)
{
    int *cp = calloc((size_t)N + 2, sizeof(int));
    long *order = malloc(((size_t)nt + 1) * sizeof(long));
    int *last = malloc(((size_t)N + 1) * sizeof(int));
    int *ri = NULL, nnz = -1;
    *colptr = *rowind = NULL;
    if (!cp || !order || !last) goto done;
    /* Bucket the pairs by column (stable), then by row within each column
     * with a second bucket pass over rows (two counting sorts: O(nt + N)). */
    long *byrow = malloc(((size_t)nt + 1) * sizeof(long));
    int *rc = calloc((size_t)N + 2, sizeof(int));
    if (!byrow || !rc) {
        free(byrow);
        free(rc);
        goto done;
    }
    for (long t = 0; t < nt; t++) rc[row[t] + 1]++;
    for (int i = 0; i < N; i++) rc[i + 1] += rc[i];
    for (long t = 0; t < nt; t++) byrow[rc[row[t]]++] = t;
    for (long t = 0; t < nt; t++) cp[col[t] + 1]++;
    for (int j = 0; j < N; j++) cp[j + 1] += cp[j];
    /* Pairs in row order dropped into their columns: rows come out sorted. */
    for (long u = 0; u < nt; u++) {
        const long t = byrow[u];
        order[cp[col[t]]++] = t;
    }
    free(byrow);
    free(rc);
    /* cp[j] now holds the end of column j: rebuild the starts. */
    for (int j = N; j > 0; j--) cp[j] = cp[j - 1];
    cp[0] = 0;
    ri = malloc(((size_t)nt + 1) * sizeof(int));
    if (!ri) goto done;
    int k = 0;
    for (int i = 0; i < N; i++) last[i] = -1;
    int *out_cp = malloc(((size_t)N + 1) * sizeof(int));
    if (!out_cp) goto done;
    for (int j = 0; j < N; j++) {
        out_cp[j] = k;
        for (int e = cp[j]; e < cp[j + 1]; e++) {
            const long t = order[e];
            const int i = row[t];
            if (last[i] < out_cp[j]) { /* first time in this column */
                last[i] = k;
                ri[k++] = i;
            }
            if (map) map[t] = last[i];
        }
    }
    out_cp[N] = k;
    nnz = k;
    *colptr = out_cp;
    *rowind = ri;
    ri = NULL;
done:
    free(cp);
    free(order);
    free(last);
    free(ri);
    return nnz;
}

/* ------------------------------------------------------------ colored FD */
struct cmp_fdjac {
    int N, ncolors;
    int *colptr, *rowind;
    int *gptr, *gcol;   /* columns of each color */
    double *yw, *ypw, *r1, *dj;
};

void cmp_fdjac_free(cmp_fdjac *f)
{
    if (!f) return;
    free(f->colptr);
    free(f->rowind);
    free(f->gptr);
    free(f->gcol);
    free(f->yw);
    free(f);
}

cmp_fdjac *cmp_fdjac_new(int N, const int *colptr, const int *rowind, int colored)
{
    cmp_fdjac *f = calloc(1, sizeof *f);
    if (!f) return NULL;
    const int nnz = colptr[N];
    f->N = N;
    f->colptr = malloc(((size_t)N + 1) * sizeof(int));
    f->rowind = malloc(((size_t)nnz + 1) * sizeof(int));
    f->gptr = malloc(((size_t)N + 2) * sizeof(int));
    f->gcol = malloc(((size_t)N + 1) * sizeof(int));
    f->yw = malloc(4 * ((size_t)N + 1) * sizeof(double));
    int *color = malloc(((size_t)N + 1) * sizeof(int));
    int *forbid = malloc(((size_t)N + 1) * sizeof(int));
    int *rp = NULL, *rj = NULL;
    if (!f->colptr || !f->rowind || !f->gptr || !f->gcol || !f->yw || !color || !forbid)
        goto fail;
    memcpy(f->colptr, colptr, ((size_t)N + 1) * sizeof(int));
    memcpy(f->rowind, rowind, (size_t)nnz * sizeof(int));
    f->ypw = f->yw + N + 1;
    f->r1 = f->ypw + N + 1;
    f->dj = f->r1 + N + 1;
    if (colored) {
        /* Rows of the pattern (the transpose), for the columns that share a
         * row with column j. */
        rp = calloc((size_t)N + 2, sizeof(int));
        rj = malloc(((size_t)nnz + 1) * sizeof(int));
        if (!rp || !rj) goto fail;
        for (int e = 0; e < nnz; e++) rp[rowind[e] + 1]++;
        for (int i = 0; i < N; i++) rp[i + 1] += rp[i];
        for (int j = 0; j < N; j++)
            for (int e = colptr[j]; e < colptr[j + 1]; e++) rj[rp[rowind[e]]++] = j;
        for (int i = N; i > 0; i--) rp[i] = rp[i - 1];
        rp[0] = 0;
        /* Greedy: the smallest color no column sharing a row already has. */
        for (int c = 0; c <= N; c++) forbid[c] = -1;
        f->ncolors = 0;
        for (int j = 0; j < N; j++) {
            for (int e = colptr[j]; e < colptr[j + 1]; e++) {
                const int i = rowind[e];
                for (int a = rp[i]; a < rp[i + 1]; a++) {
                    const int jj = rj[a];
                    if (jj < j) forbid[color[jj]] = j;
                }
            }
            int c = 0;
            while (forbid[c] == j) c++;
            color[j] = c;
            if (c + 1 > f->ncolors) f->ncolors = c + 1;
        }
    } else {
        for (int j = 0; j < N; j++) color[j] = j;
        f->ncolors = N;
    }
    /* Group the columns by color (column order within a color). */
    for (int c = 0; c <= f->ncolors; c++) f->gptr[c] = 0;
    for (int j = 0; j < N; j++) f->gptr[color[j] + 1]++;
    for (int c = 0; c < f->ncolors; c++) f->gptr[c + 1] += f->gptr[c];
    for (int j = 0; j < N; j++) f->gcol[f->gptr[color[j]]++] = j;
    for (int c = f->ncolors; c > 0; c--) f->gptr[c] = f->gptr[c - 1];
    f->gptr[0] = 0;
    free(color);
    free(forbid);
    free(rp);
    free(rj);
    return f;
fail:
    free(color);
    free(forbid);
    free(rp);
    free(rj);
    cmp_fdjac_free(f);
    return NULL;
}

int cmp_fdjac_colors(const cmp_fdjac *f)
{
    return f->ncolors;
}

int cmp_fdjac_eval(cmp_fdjac *f, cmp_res_fn res, void *user, double t, double cj,
                   const double *y, const double *yp, const double *r0, double *val,
                   long *nres)
{
    const int N = f->N;
    memcpy(f->yw, y, (size_t)N * sizeof(double));
    memcpy(f->ypw, yp, (size_t)N * sizeof(double));
    for (int c = 0; c < f->ncolors; c++) {
        for (int g = f->gptr[c]; g < f->gptr[c + 1]; g++) {
            const int j = f->gcol[g];
            const double dj = 1.4901161193847656e-08 * fmax(fabs(y[j]), 1.0);
            f->dj[j] = dj;
            f->yw[j] += dj;
            f->ypw[j] += cj * dj;
        }
        int st = res(user, t, f->yw, f->ypw, f->r1);
        if (nres) (*nres)++;
        for (int g = f->gptr[c]; g < f->gptr[c + 1]; g++) {
            const int j = f->gcol[g];
            f->yw[j] = y[j];
            f->ypw[j] = yp[j];
            if (st) continue;
            for (int e = f->colptr[j]; e < f->colptr[j + 1]; e++) {
                const int i = f->rowind[e];
                val[e] = (f->r1[i] - r0[i]) / f->dj[j];
            }
        }
        if (st) return st;
    }
    return 0;
}

/* ------------------------------------------------------------ the scene provider */
#ifdef CMP_HAVE_SCENES

/* Entries per row at most: A 4 (revolute: x or y and θ of each end; rod:
 * x, y of each end), Hessian 8 (rod). */
#define ROW_A 4
#define ROW_H 8

struct cmp_ggl {
    const braun_scene *s;
    int n, m, N;
    double reg;
    /* Constant M (compressed columns, symmetric) and Q (gravity). */
    int *mp, *mi;
    double *mx, *Q;
    /* Rows at the last q: Φ; A and the Hessians as per-row lists. */
    double *phi;
    int *ap, *aj, *hp, *hi, *hj;
    double *ax, *hx;
    /* J: pattern and where each emitted entry goes. */
    int nnz, *colptr, *rowind;
    long ne;
    int *map;
    /* KKT [M Aᵀ; A 0] for the consistent values (KLU). */
    int knnz, *kp, *ki, *kmap;
    long kne;
    double *kx, *rhs;
    klu_symbolic *sym;
    klu_common common;
};

/* ------------------------------------------------ the classes it knows */
/* What the provider knows of each element class it supports, keyed by the
 * class (braun_scene.h) — the one place the harness names element types:
 * a body class's planar layout, a joint class's rows with their second
 * derivatives, an effect class's (constant) generalized force. A scene
 * with any other class is refused (supported()). */
typedef struct ggl_body {
    const braun_scene_body_class *cls;
    int theta;              /* column of θ within the body, -1: none */
} ggl_body;

static const ggl_body ggl_bodies[] = {{BRAUN_BODY_RIGID, 2}, {BRAUN_BODY_PARTICLE, -1}};

/* A point at q: position, ∂P/∂θ = R's and R s (rigid), columns. */
typedef struct gpt {
    int ix, th;             /* column of x (-1: ground), of θ (-1: none) */
    double pos[2], jt[2], rs[2];
} gpt;

static const ggl_body *body_of_class(const braun_scene_body_class *c)
{
    for (size_t k = 0; k < sizeof ggl_bodies / sizeof ggl_bodies[0]; k++)
        if (ggl_bodies[k].cls == c) return &ggl_bodies[k];
    return NULL;
}

static void point_at(const braun_scene *s, int i, const double *q, gpt *P)
{
    const braun_scene_point *pt = &s->points[i];
    P->ix = P->th = -1;
    P->jt[0] = P->jt[1] = P->rs[0] = P->rs[1] = 0;
    if (pt->body < 0) {
        P->pos[0] = pt->x;
        P->pos[1] = pt->y;
        return;
    }
    const braun_scene_body *bd = &s->bodies[pt->body];
    P->ix = bd->iq;
    P->pos[0] = q[bd->iq];
    P->pos[1] = q[bd->iq + 1];
    const int theta = body_of_class(bd->kind)->theta;
    if (theta < 0) return;
    const double c = cos(q[bd->iq + theta]), sn = sin(q[bd->iq + theta]);
    const double rx = c * pt->x - sn * pt->y, ry = sn * pt->x + c * pt->y;
    P->th = bd->iq + theta;
    P->pos[0] += rx;
    P->pos[1] += ry;
    P->jt[0] = -ry;
    P->jt[1] = rx;
    P->rs[0] = rx;
    P->rs[1] = ry;
}

/* Rows of one element: Φ, A and the Hessian's entries per row, appended
 * at *ka, *kh (g->aj/ax, g->hi/hj/hx). */
#define PUT_A(c, v) (g->aj[*ka] = (c), g->ax[*ka] = (v), (*ka)++)
#define PUT_H(i, j, v) (g->hi[*kh] = (i), g->hj[*kh] = (j), g->hx[*kh] = (v), (*kh)++)

/* Revolute (P_a - P_b, P = r + R(θ)s): ∂²P/∂θ² = -R(θ)s, so row k has
 * -(R s_a)_k at (θ_a, θ_a) and +(R s_b)_k at (θ_b, θ_b), nothing else. */
static void revolute_h(cmp_ggl *g, const braun_scene_joint *j, const double *q, int *ka, int *kh)
{
    gpt Pa, Pb;
    point_at(g->s, j->a, q, &Pa);
    point_at(g->s, j->b, q, &Pb);
    for (int c = 0; c < 2; c++) {
        const int row = j->row + c;
        g->phi[row] = Pa.pos[c] - Pb.pos[c];
        g->ap[row] = *ka;
        g->hp[row] = *kh;
        if (Pa.ix >= 0) PUT_A(Pa.ix + c, 1.0);
        if (Pa.th >= 0) PUT_A(Pa.th, Pa.jt[c]);
        if (Pb.ix >= 0) PUT_A(Pb.ix + c, -1.0);
        if (Pb.th >= 0) PUT_A(Pb.th, -Pb.jt[c]);
        if (Pa.th >= 0) PUT_H(Pa.th, Pa.th, -Pa.rs[c]);
        if (Pb.th >= 0) PUT_H(Pb.th, Pb.th, Pb.rs[c]);
    }
}

typedef struct ggl_joint {
    const braun_scene_joint_class *cls;
    int rows;               /* rows per joint (scleronomic: not driven) */
    void (*eval)(cmp_ggl *g, const braun_scene_joint *j, const double *q, int *ka, int *kh);
} ggl_joint;

static const ggl_joint ggl_joints[] = {{BRAUN_JOINT_REVOLUTE, 2, revolute_h}};

static const ggl_joint *joint_of_class(const braun_scene_joint_class *c)
{
    for (size_t k = 0; k < sizeof ggl_joints / sizeof ggl_joints[0]; k++)
        if (ggl_joints[k].cls == c) return &ggl_joints[k];
    return NULL;
}

/* Gravity: the generalized weight (scene_gravity.c), constant. */
static void gravity_q(cmp_ggl *g, const braun_scene_effect *e)
{
    const braun_scene *s = g->s;
    const double *gv = e->g;
    for (int b = 0; b < s->nbodies; b++) {
        g->Q[s->bodies[b].iq] += s->bodies[b].mass * gv[0];
        g->Q[s->bodies[b].iq + 1] += s->bodies[b].mass * gv[1];
    }
    for (int r = 0; r < s->nrods; r++) {
        const int ends[2] = {s->rods[r].a, s->rods[r].b};
        for (int u = 0; u < 2; u++) {
            const int b = s->points[ends[u]].body;
            if (b < 0) continue;
            g->Q[s->bodies[b].iq] += 0.5 * s->rods[r].mass * gv[0];
            g->Q[s->bodies[b].iq + 1] += 0.5 * s->rods[r].mass * gv[1];
        }
    }
}

typedef struct ggl_effect {
    const braun_scene_effect_class *cls;
    void (*forces)(cmp_ggl *g, const braun_scene_effect *e); /* Q += constant forces */
} ggl_effect;

static const ggl_effect ggl_effects[] = {{BRAUN_EFFECT_GRAVITY, gravity_q}};

static const ggl_effect *effect_of_class(const braun_scene_effect_class *c)
{
    for (size_t k = 0; k < sizeof ggl_effects / sizeof ggl_effects[0]; k++)
        if (ggl_effects[k].cls == c) return &ggl_effects[k];
    return NULL;
}

/* Φ, A and the Hessians at q, row by row in the scene's row order (rods,
 * then joints). The structure (columns) is the same at every q. Rods
 * (|P_b - P_a|² - L², particle ends): 2 on the diagonal of each end's x,
 * y and -2 between the ends' x (and y). */
static void rows_eval(cmp_ggl *g, const double *q)
{
    const braun_scene *s = g->s;
    int kav = 0, khv = 0, *ka = &kav, *kh = &khv;
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        gpt Pa, Pb;
        point_at(s, r->a, q, &Pa);
        point_at(s, r->b, q, &Pb);
        const double dx = Pb.pos[0] - Pa.pos[0], dy = Pb.pos[1] - Pa.pos[1];
        const int row = r->row;
        g->phi[row] = dx * dx + dy * dy - r->length * r->length;
        g->ap[row] = kav;
        g->hp[row] = khv;
        if (Pa.ix >= 0) {
            PUT_A(Pa.ix, -2.0 * dx);
            PUT_A(Pa.ix + 1, -2.0 * dy);
        }
        if (Pb.ix >= 0) {
            PUT_A(Pb.ix, 2.0 * dx);
            PUT_A(Pb.ix + 1, 2.0 * dy);
        }
        for (int u = 0; u < 2; u++) {
            if (Pa.ix >= 0) PUT_H(Pa.ix + u, Pa.ix + u, 2.0);
            if (Pb.ix >= 0) PUT_H(Pb.ix + u, Pb.ix + u, 2.0);
            if (Pa.ix >= 0 && Pb.ix >= 0) {
                PUT_H(Pa.ix + u, Pb.ix + u, -2.0);
                PUT_H(Pb.ix + u, Pa.ix + u, -2.0);
            }
        }
    }
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        joint_of_class(j->type)->eval(g, j, q, ka, kh);
    }
    g->ap[g->m] = kav;
    g->hp[g->m] = khv;
}
#undef PUT_A
#undef PUT_H

/* The entries of J in their fixed order: pattern mode pushes (row, col),
 * value mode adds into val through map. */
typedef struct emitter {
    cmp_pairs *P;        /* pattern mode */
    const int *map;      /* value mode ... */
    double *val;
    long e;
} emitter;

static void put(emitter *E, int r, int c, double v)
{
    if (E->P) cmp_pairs_push(E->P, r, c);
    else E->val[E->map[E->e]] += v;
    E->e++;
}

static void emit_jacobian(cmp_ggl *g, emitter *E, double cj, const double *y)
{
    const int n = g->n, m = g->m, N = g->N;
    const double *v = y + n, *lam = y + 2 * n, *mu = y + 2 * n + m;
    for (int i = 0; i < N; i++) put(E, i, i, i < n ? cj : (i < 2 * n ? 0.0 : -g->reg));
    for (int i = 0; i < n; i++) put(E, i, n + i, -1.0);
    for (int j = 0; j < n; j++)
        for (int e = g->mp[j]; e < g->mp[j + 1]; e++) put(E, n + g->mi[e], n + j, cj * g->mx[e]);
    for (int k = 0; k < m; k++)
        for (int e = g->ap[k]; e < g->ap[k + 1]; e++) {
            const int j = g->aj[e];
            const double a = g->ax[e];
            put(E, j, 2 * n + m + k, a);      /* r_q:  A_qᵀμ */
            put(E, n + j, 2 * n + k, -a);     /* r_v: -A_qᵀλ */
            put(E, 2 * n + k, n + j, a);      /* r_c1: A_q v */
            put(E, 2 * n + m + k, j, a);      /* r_c2: Φ_q */
        }
    for (int k = 0; k < m; k++)
        for (int e = g->hp[k]; e < g->hp[k + 1]; e++) {
            const int i = g->hi[e], j = g->hj[e];
            const double h = g->hx[e];
            put(E, i, j, mu[k] * h);          /* ∂(A_qᵀμ)_i/∂q_j */
            put(E, n + i, j, -lam[k] * h);    /* -∂(A_qᵀλ)_i/∂q_j */
            put(E, 2 * n + k, j, v[i] * h);   /* ∂(A_q v)_k/∂q_j */
        }
}

/* KKT entries: M, then A and Aᵀ, then -δ on the multipliers' diagonal. */
static void emit_kkt(cmp_ggl *g, emitter *E, double delta)
{
    const int n = g->n;
    for (int j = 0; j < n; j++)
        for (int e = g->mp[j]; e < g->mp[j + 1]; e++) put(E, g->mi[e], j, g->mx[e]);
    for (int k = 0; k < g->m; k++)
        for (int e = g->ap[k]; e < g->ap[k + 1]; e++) {
            put(E, n + k, g->aj[e], g->ax[e]);
            put(E, g->aj[e], n + k, g->ax[e]);
        }
    for (int k = 0; k < g->m; k++) put(E, n + k, n + k, -delta);
}

static const char *supported(const braun_scene *s)
{
    if (s->n <= 0) return "the scene is not built";
    if (s->p > 0) return "knife edges (nonholonomic rows)";
    for (int k = 0; k < s->nbodies; k++)
        if (!body_of_class(s->bodies[k].kind)) return "bodies other than rigid bodies and particles";
    int row = 0;
    for (int k = 0; k < s->nrods; k++, row++)
        if (s->rods[k].row != row) return "unexpected row numbering";
    for (int k = 0; k < s->njoints; k++) {
        const ggl_joint *jc = joint_of_class(s->joints[k].type);
        if (!jc || s->joints[k].driven) return "joints other than revolute";
        if (s->joints[k].row != row) return "unexpected row numbering";
        row += jc->rows;
    }
    if (row != s->m) return "unexpected row count";
    for (int k = 0; k < s->neffects; k++)
        if (!effect_of_class(s->effects[k].type)) return "effects other than gravity";
    return NULL;
}

void cmp_ggl_free(cmp_ggl *g)
{
    if (!g) return;
    if (g->sym) klu_free_symbolic(&g->sym, &g->common);
    free(g->mp);
    free(g->mi);
    free(g->mx);
    free(g->Q);
    free(g->phi);
    free(g->ap);
    free(g->aj);
    free(g->ax);
    free(g->hp);
    free(g->hi);
    free(g->hj);
    free(g->hx);
    free(g->colptr);
    free(g->rowind);
    free(g->map);
    free(g->kp);
    free(g->ki);
    free(g->kmap);
    free(g->kx);
    free(g->rhs);
    free(g);
}

cmp_ggl *cmp_ggl_new(const struct braun_scene *scene, const char **why)
{
    const char *no = scene ? supported(scene) : "no scene";
    if (why) *why = no;
    if (no) return NULL;
    const braun_scene *s = scene;
    cmp_ggl *g = calloc(1, sizeof *g);
    cmp_pairs P = {0, 0, NULL, NULL, 0};
    if (!g) goto oom;
    g->s = s;
    g->n = s->n;
    g->m = s->m;
    g->N = 2 * s->n + 2 * s->m;
    const int n = g->n, m = g->m;
    g->Q = calloc((size_t)n, sizeof(double));
    g->phi = malloc(((size_t)m + 1) * sizeof(double));
    g->ap = malloc(((size_t)m + 1) * sizeof(int));
    g->hp = malloc(((size_t)m + 1) * sizeof(int));
    g->aj = malloc(((size_t)m * ROW_A + 1) * sizeof(int));
    g->ax = malloc(((size_t)m * ROW_A + 1) * sizeof(double));
    g->hi = malloc(((size_t)m * ROW_H + 1) * sizeof(int));
    g->hj = malloc(((size_t)m * ROW_H + 1) * sizeof(int));
    g->hx = malloc(((size_t)m * ROW_H + 1) * sizeof(double));
    g->rhs = malloc(((size_t)n + m + 1) * sizeof(double));
    if (!g->Q || !g->phi || !g->ap || !g->hp || !g->aj || !g->ax || !g->hi || !g->hj ||
        !g->hx || !g->rhs)
        goto oom;

    /* M: bodies' diagonal blocks (their classes' mass hooks) and rods'
     * blocks (scene_rod.c). */
    double blk[BRAUN_SCENE_MAX_DOF * BRAUN_SCENE_MAX_DOF];
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        for (int i = 0; i < bd->kind->dof; i++) cmp_pairs_push(&P, bd->iq + i, bd->iq + i);
    }
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const int ba = s->points[r->a].body, bb = s->points[r->b].body;
        const int ia = ba < 0 ? -1 : s->bodies[ba].iq, ib = bb < 0 ? -1 : s->bodies[bb].iq;
        for (int c = 0; c < 2; c++) {
            if (ia >= 0) cmp_pairs_push(&P, ia + c, ia + c);
            if (ib >= 0) cmp_pairs_push(&P, ib + c, ib + c);
            if (ia >= 0 && ib >= 0) {
                cmp_pairs_push(&P, ia + c, ib + c);
                cmp_pairs_push(&P, ib + c, ia + c);
            }
        }
    }
    if (P.failed) goto oom;
    int *mmap = malloc(((size_t)P.n + 1) * sizeof(int));
    if (!mmap) goto oom;
    int mnnz = cmp_csc_from_pairs(n, P.n, P.r, P.c, &g->mp, &g->mi, mmap);
    g->mx = calloc((size_t)mnnz + 1, sizeof(double));
    if (mnnz < 0 || !g->mx) {
        free(mmap);
        goto oom;
    }
    long e = 0;
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        const int d = bd->kind->dof;
        for (int i = 0; i < d * d; i++) blk[i] = 0;
        bd->kind->mass(bd, blk, d);
        for (int i = 0; i < d; i++) g->mx[mmap[e++]] += blk[i * d + i];
    }
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const int ba = s->points[r->a].body, bb = s->points[r->b].body;
        const double d = r->mass / 3.0, o = r->mass / 6.0;
        for (int c = 0; c < 2; c++) {
            if (ba >= 0) g->mx[mmap[e++]] += d;
            if (bb >= 0) g->mx[mmap[e++]] += d;
            if (ba >= 0 && bb >= 0) {
                g->mx[mmap[e++]] += o;
                g->mx[mmap[e++]] += o;
            }
        }
    }
    free(mmap);
    cmp_pairs_free(&P);

    /* Q: the effects' constant forces. */
    for (int k = 0; k < s->neffects; k++) effect_of_class(s->effects[k].type)->forces(g, &s->effects[k]);

    /* The rows' structure (at any q: here the zero vector). */
    double *q = calloc((size_t)n, sizeof(double));
    if (!q) goto oom;
    rows_eval(g, q);
    free(q);

    /* J's pattern. */
    double *y = calloc((size_t)g->N, sizeof(double));
    if (!y) goto oom;
    emitter E = {&P, NULL, NULL, 0};
    emit_jacobian(g, &E, 1.0, y);
    free(y);
    if (P.failed) goto oom;
    g->ne = P.n;
    g->map = malloc(((size_t)P.n + 1) * sizeof(int));
    if (!g->map) goto oom;
    g->nnz = cmp_csc_from_pairs(g->N, P.n, P.r, P.c, &g->colptr, &g->rowind, g->map);
    if (g->nnz < 0) goto oom;
    cmp_pairs_free(&P);

    /* The KKT matrix's pattern. */
    E = (emitter){&P, NULL, NULL, 0};
    emit_kkt(g, &E, 0.0);
    if (P.failed) goto oom;
    g->kne = P.n;
    g->kmap = malloc(((size_t)P.n + 1) * sizeof(int));
    if (!g->kmap) goto oom;
    g->knnz = cmp_csc_from_pairs(n + m, P.n, P.r, P.c, &g->kp, &g->ki, g->kmap);
    g->kx = malloc(((size_t)g->knnz + 1) * sizeof(double));
    if (g->knnz < 0 || !g->kx) goto oom;
    cmp_pairs_free(&P);
    klu_defaults(&g->common);
    return g;
oom:
    if (why) *why = "out of memory";
    cmp_pairs_free(&P);
    cmp_ggl_free(g);
    return NULL;
}

int cmp_ggl_size(const cmp_ggl *g)
{
    return g->N;
}

int cmp_ggl_n(const cmp_ggl *g)
{
    return g->n;
}

void cmp_ggl_set_reg(cmp_ggl *g, double eps)
{
    g->reg = eps;
}

int cmp_ggl_pattern(const cmp_ggl *g, const int **colptr, const int **rowind)
{
    *colptr = g->colptr;
    *rowind = g->rowind;
    return g->nnz;
}

int cmp_ggl_residual(cmp_ggl *g, double t, const double *y, const double *yp, double *r)
{
    const int n = g->n, m = g->m, N = g->N;
    const double *q = y, *v = y + n, *lam = y + 2 * n, *mu = y + 2 * n + m;
    const double *qp = yp, *vp = yp + n;
    (void)t;
    rows_eval(g, q);
    for (int i = 0; i < n; i++) {
        r[i] = qp[i] - v[i];
        r[n + i] = 0;
    }
    /* M v' by columns (M is symmetric), then - Q, then the multipliers. */
    for (int j = 0; j < n; j++)
        for (int e = g->mp[j]; e < g->mp[j + 1]; e++) r[n + g->mi[e]] += g->mx[e] * vp[j];
    for (int i = 0; i < n; i++) r[n + i] -= g->Q[i];
    double *rc = r + 2 * n;
    for (int k = 0; k < m; k++) {
        double av = 0;
        for (int e = g->ap[k]; e < g->ap[k + 1]; e++) {
            const int j = g->aj[e];
            const double a = g->ax[e];
            r[j] += a * mu[k];
            r[n + j] -= a * lam[k];
            av += a * v[j];
        }
        rc[k] = av;
        rc[m + k] = g->phi[k];
    }
    if (g->reg > 0)
        for (int i = 2 * n; i < N; i++) r[i] -= g->reg * y[i];
    for (int i = 0; i < N; i++)
        if (!isfinite(r[i])) return 1;
    return 0;
}

int cmp_ggl_jacobian(cmp_ggl *g, double t, double cj, const double *y, const double *yp,
                     double *val)
{
    (void)t;
    (void)yp;
    rows_eval(g, y);
    memset(val, 0, (size_t)g->nnz * sizeof(double));
    emitter E = {NULL, g->map, val, 0};
    emit_jacobian(g, &E, cj, y);
    for (int e = 0; e < g->nnz; e++)
        if (!isfinite(val[e])) return 1;
    return 0;
}

/* Factor [M Aᵀ; A -δI] at the last rows_eval. NULL if KLU failed or, with
 * δ = 0, the matrix is singular (rcond below 1e-13: redundant rows). */
static klu_numeric *kkt_factor(cmp_ggl *g, double delta)
{
    memset(g->kx, 0, (size_t)g->knnz * sizeof(double));
    emitter E = {NULL, g->kmap, g->kx, 0};
    emit_kkt(g, &E, delta);
    if (!g->sym) g->sym = klu_analyze(g->n + g->m, g->kp, g->ki, &g->common);
    if (!g->sym) return NULL;
    klu_numeric *num = klu_factor(g->kp, g->ki, g->kx, g->sym, &g->common);
    if (!num) return NULL;
    if (g->common.status != KLU_OK || !klu_rcond(g->sym, num, &g->common) ||
        (delta == 0 && !(g->common.rcond > 1e-13))) {
        klu_free_numeric(&num, &g->common);
        return NULL;
    }
    return num;
}

static double norm2(int k, const double *x)
{
    double s = 0;
    for (int i = 0; i < k; i++) s += x[i] * x[i];
    return sqrt(s);
}

/* The KKT system of the consistent values,
 *     M x + Aᵀ w = top,   A x = bot,
 * solved into x (n) and w (m) at the last rows_eval. Full-rank rows: one
 * solve with δ = 0. Redundant rows (the δ = 0 factorization is singular):
 * the proximal iteration [M Aᵀ; A -δI] [x; w_k+1] = [top; bot - δ w_k]
 * from w_0 = 0, whose fixed point solves the system with the
 * minimum-norm w, each step contracting the rest by δ/(σ² + δ) (σ the
 * nonzero singular values of A M^-1/2); δ = 1e-8 · max_k Σ_j A_kj²/M_jj.
 * xw: n + m, top and bot in, x and w out. 0, or -1. */
static int kkt_solve(cmp_ggl *g, double *xw)
{
    const int n = g->n, m = g->m;
    klu_numeric *num = kkt_factor(g, 0.0);
    if (num) {
        int ok = klu_solve(g->sym, num, n + m, 1, xw, &g->common);
        klu_free_numeric(&num, &g->common);
        return ok ? 0 : -1;
    }
    double scale = 0;
    for (int k = 0; k < m; k++) {
        double sk = 0;
        for (int e = g->ap[k]; e < g->ap[k + 1]; e++) {
            const int j = g->aj[e];
            double mjj = 0;
            for (int f = g->mp[j]; f < g->mp[j + 1]; f++)
                if (g->mi[f] == j) mjj = g->mx[f];
            if (mjj > 0) sk += g->ax[e] * g->ax[e] / mjj;
        }
        scale = fmax(scale, sk);
    }
    const double delta = 1e-8 * (scale > 0 ? scale : 1.0);
    if (!(num = kkt_factor(g, delta))) return -1;
    double *rhs = malloc(2 * ((size_t)n + m) * sizeof(double));
    if (!rhs) {
        klu_free_numeric(&num, &g->common);
        return -1;
    }
    double *w = rhs + n + m;
    memcpy(rhs, xw, ((size_t)n + m) * sizeof(double)); /* top, bot */
    double size = 1;
    for (int i = 0; i < n + m; i++) size = fmax(size, fabs(rhs[i]));
    for (int k = 0; k < m; k++) w[k] = 0;
    int st = -1;
    double prev = INFINITY;
    for (int it = 0; it < 200; it++) {
        memcpy(xw, rhs, (size_t)n * sizeof(double));
        for (int k = 0; k < m; k++) xw[n + k] = rhs[n + k] - delta * w[k];
        if (!klu_solve(g->sym, num, n + m, 1, xw, &g->common)) break;
        double dw = 0;
        for (int k = 0; k < m; k++) {
            dw = fmax(dw, fabs(xw[n + k] - w[k]));
            w[k] = xw[n + k];
        }
        /* A x - bot = δ (w_k+1 - w_k): stop at round-off, which the
         * conditioning (~1/δ) puts at ~ε/δ in w. */
        const double res = delta * dw;
        if (res <= 1e-15 * size || (res <= 1e-12 * size && dw > 0.5 * prev)) {
            st = 0;
            break;
        }
        prev = dw;
    }
    klu_free_numeric(&num, &g->common);
    free(rhs);
    return st;
}

int cmp_ggl_consistent(cmp_ggl *g, double t, const double *q0, const double *v0, double *y,
                       double *yp)
{
    const int n = g->n, m = g->m, N = g->N;
    double *q = y, *v = y + n, *x = g->rhs;
    (void)t;
    memcpy(q, q0, (size_t)n * sizeof(double));
    memcpy(v, v0, (size_t)n * sizeof(double));
    /* 1. Positions: Gauss-Newton with minimum-M-norm steps,
     *    [M Aᵀ; A 0] [dq; w] = [0; -Φ], until ||Φ|| <= 1e-15 or round-off
     *    stops it from decreasing. */
    double prev = INFINITY;
    for (int it = 0; it < 50 && m > 0; it++) {
        rows_eval(g, q);
        const double nr = norm2(m, g->phi);
        if (nr <= 1e-15 || (nr > 0.5 * prev && nr < 1e-10)) break;
        prev = nr;
        for (int i = 0; i < n; i++) x[i] = 0;
        for (int k = 0; k < m; k++) x[n + k] = -g->phi[k];
        if (kkt_solve(g, x)) return -1;
        for (int i = 0; i < n; i++) q[i] += x[i];
    }
    /* 2. Velocities on A_q v = b_q = 0 (minimum-M-norm corrections). */
    rows_eval(g, q);
    prev = INFINITY;
    for (int it = 0; it < 50 && m > 0; it++) {
        for (int i = 0; i < n; i++) x[i] = 0;
        for (int k = 0; k < m; k++) {
            double av = 0;
            for (int e = g->ap[k]; e < g->ap[k + 1]; e++) av += g->ax[e] * v[g->aj[e]];
            x[n + k] = -av;
        }
        const double nr = norm2(m, x + n);
        if (nr <= 1e-15 || (nr > 0.5 * prev && nr < 1e-10)) break;
        prev = nr;
        if (kkt_solve(g, x)) return -1;
        for (int i = 0; i < n; i++) v[i] += x[i];
    }
    /* 3. v' and λ: [M Aᵀ; A 0] [v'; -λ] = [Q; b_qv], b_qv = -Σ v_i H_k,ij v_j. */
    for (int i = 0; i < n; i++) x[i] = g->Q[i];
    for (int k = 0; k < m; k++) {
        double bv = 0;
        for (int e = g->hp[k]; e < g->hp[k + 1]; e++) bv -= v[g->hi[e]] * g->hx[e] * v[g->hj[e]];
        x[n + k] = bv;
    }
    if (m > 0) {
        if (kkt_solve(g, x)) return -1;
    } else {
        /* No rows: M v' = Q (M is diagonal without rods). */
        for (int j = 0; j < n; j++)
            for (int e = g->mp[j]; e < g->mp[j + 1]; e++)
                if (g->mi[e] == j) x[j] = g->Q[j] / g->mx[e];
    }
    for (int i = 0; i < n; i++) {
        yp[i] = v[i];
        yp[n + i] = x[i];
    }
    for (int k = 0; k < m; k++) y[2 * n + k] = -x[n + k];
    for (int i = 2 * n + m; i < N; i++) y[i] = 0;
    for (int i = 2 * n; i < N; i++) yp[i] = 0;
    for (int i = 0; i < N; i++)
        if (!isfinite(y[i]) || !isfinite(yp[i])) return -1;
    return 0;
}

const struct braun_scene *cmp_target_scene(const cmp_target *tg)
{
    const braun_scene_file *f = tg->scene_file;
    return f ? &f->scene : NULL;
}
#else /* !CMP_HAVE_SCENES: no scene, no provider */
cmp_ggl *cmp_ggl_new(const struct braun_scene *scene, const char **why)
{
    (void)scene;
    if (why) *why = "the harness was built without the scene library";
    return NULL;
}
void cmp_ggl_free(cmp_ggl *g)
{
    (void)g;
}
int cmp_ggl_size(const cmp_ggl *g)
{
    (void)g;
    return 0;
}
int cmp_ggl_n(const cmp_ggl *g)
{
    (void)g;
    return 0;
}
void cmp_ggl_set_reg(cmp_ggl *g, double eps)
{
    (void)g;
    (void)eps;
}
int cmp_ggl_pattern(const cmp_ggl *g, const int **colptr, const int **rowind)
{
    (void)g;
    *colptr = *rowind = NULL;
    return 0;
}
int cmp_ggl_residual(cmp_ggl *g, double t, const double *y, const double *yp, double *r)
{
    (void)g, (void)t, (void)y, (void)yp, (void)r;
    return -1;
}
int cmp_ggl_jacobian(cmp_ggl *g, double t, double cj, const double *y, const double *yp,
                     double *val)
{
    (void)g, (void)t, (void)cj, (void)y, (void)yp, (void)val;
    return -1;
}
int cmp_ggl_consistent(cmp_ggl *g, double t, const double *q0, const double *v0, double *y,
                       double *yp)
{
    (void)g, (void)t, (void)q0, (void)v0, (void)y, (void)yp;
    return -1;
}
const struct braun_scene *cmp_target_scene(const cmp_target *tg)
{
    (void)tg;
    return NULL;
}
#endif

/* ------------------------------------------------------------ CLI */
static const char *const JAC_NAMES[] = {"auto", "analytic", "colored", "column"};
static const char *const RES_NAMES[] = {"auto", "callbacks", "scene"};

static int name_index(const char *s, const char *const *names, int count)
{
    for (int i = 0; i < count; i++)
        if (strcmp(s, names[i]) == 0) return i;
    return -1;
}

static void cli_usage(FILE *f)
{
    fprintf(f,
            "Usage: braun-ida-run SCENE T RTOL [--atol A] [--alg-atol A]\n"
            "                     [--jac auto|analytic|colored|column]\n"
            "                     [--residual auto|scene|callbacks] [--max-order K]\n"
            "                     [--max-steps S] [--reg EPS] [--reps K]\n"
            "IDA (GGL form) with KLU on a scene from t = 0 to T (docs/compare.md,\n"
            "\"IDA with KLU for large mechanisms\"). SCENE: data/NAME.json as NAME, a\n"
            "path to a .json scene, or a built-in model. Prints key = value lines;\n"
            "--reps K repeats the run and reports the least CPU time.\n");
}

int cmp_ida_run_cli(int argc, char **argv)
{
    cmp_ida_run_opts o;
    memset(&o, 0, sizeof o);
    const char *pos[3] = {NULL, NULL, NULL};
    int npos = 0, reps = 1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            cli_usage(stdout);
            return 0;
        }
        if (a[0] == '-' && a[1] == '-') {
            if (!val) {
                fprintf(stderr, "braun-ida-run: %s needs a value\n", a);
                return 2;
            }
            i++;
            if (strcmp(a, "--atol") == 0) o.atol = atof(val);
            else if (strcmp(a, "--alg-atol") == 0) o.alg_atol = atof(val);
            else if (strcmp(a, "--max-order") == 0) o.max_order = atoi(val);
            else if (strcmp(a, "--max-steps") == 0) o.max_steps = atol(val);
            else if (strcmp(a, "--reg") == 0) o.reg = atof(val);
            else if (strcmp(a, "--reps") == 0) reps = atoi(val);
            else if (strcmp(a, "--jac") == 0) o.jac = name_index(val, JAC_NAMES, 4);
            else if (strcmp(a, "--residual") == 0) o.residual = name_index(val, RES_NAMES, 3);
            else {
                fprintf(stderr, "braun-ida-run: unknown option '%s'\n", a);
                return 2;
            }
            if (o.jac < 0 || o.residual < 0) {
                fprintf(stderr, "braun-ida-run: unknown value '%s' of %s\n", val, a);
                return 2;
            }
            continue;
        }
        if (npos == 3) {
            fprintf(stderr, "braun-ida-run: unexpected argument '%s'\n", a);
            return 2;
        }
        pos[npos++] = a;
    }
    if (npos != 3) {
        cli_usage(stderr);
        return 2;
    }
    o.t_end = atof(pos[1]);
    o.rtol = atof(pos[2]);
    if (!(o.t_end > 0) || !(o.rtol > 0) || reps < 1) {
        fprintf(stderr, "braun-ida-run: T and RTOL must be positive, --reps >= 1\n");
        return 2;
    }
    cmp_target tg;
    char err[512];
    if (cmp_target_find(pos[0], &tg, err, sizeof err)) {
        fprintf(stderr, "braun-ida-run: %s\n", err);
        return 2;
    }
    const int n = tg.sys.n;
    double *qe = malloc(2 * (size_t)n * sizeof(double));
    if (!qe) {
        cmp_target_free(&tg);
        return 1;
    }
    o.q_end = qe;
    o.v_end = qe + n;
    cmp_ida_problem pb = {&tg.sys, tg.q0, tg.v0, cmp_target_scene(&tg)};
    cmp_ida_run_result r, best;
    memset(&best, 0, sizeof best);
    for (int k = 0; k < reps; k++) {
        cmp_ida_klu_run(&pb, &o, &r);
        if (k == 0 || r.cpu_solve_s + r.cpu_setup_s < best.cpu_solve_s + best.cpu_setup_s)
            best = r;
    }
    r = best;
    printf("scene = %s\nn = %d\nm = %d\nN = %d\nnnz = %d\n", tg.name, n, tg.sys.m, r.N, r.nnz);
    printf("jacobian = %s\nresidual = %s\ncolors = %d\n",
           r.jac >= 0 && r.jac < 4 ? JAC_NAMES[r.jac] : "?",
           r.residual >= 0 && r.residual < 3 ? RES_NAMES[r.residual] : "?", r.colors);
    printf("T = %g\nrtol = %g\natol = %g\n", o.t_end, o.rtol, o.atol > 0 ? o.atol : o.rtol);
    printf("status = %s\nsuccess = %d\nt_reached = %.10g\n", r.status, r.success, r.t_reached);
    if (r.detail[0]) printf("detail = %s\n", r.detail);
    printf("steps = %ld\nres_evals = %ld\njac_evals = %ld\njac_res_evals = %ld\n", r.steps,
           r.res_evals, r.jac_evals, r.jac_res_evals);
    printf("lin_setups = %ld\nnl_iters = %ld\nerr_fails = %ld\nconv_fails = %ld\n", r.lin_setups,
           r.nl_iters, r.err_fails, r.conv_fails);
    printf("reps = %d\ncpu_setup_s = %.6g\ncpu_solve_s = %.6g\n", reps, r.cpu_setup_s,
           r.cpu_solve_s);
    printf("cpu_per_step_s = %.6g\ncpu_per_sim_s = %.6g\n",
           r.steps ? r.cpu_solve_s / (double)r.steps : NAN,
           r.t_reached > 0 ? r.cpu_solve_s / r.t_reached : NAN);
    printf("q_end_last =");
    for (int i = n >= 3 ? n - 3 : 0; i < n; i++) printf(" %.12g", qe[i]);
    printf("\n");
    free(qe);
    cmp_target_free(&tg);
    return r.success ? 0 : 1;
}
