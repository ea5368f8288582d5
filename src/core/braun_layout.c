/* The data block's memory layout: every buffer of braun_priv carved from the
 * caller's one buffer, in one list. A buffer's size is the only place that
 * says when it exists: a size of 0 leaves its pointer NULL. */
#include <stdint.h>

#include "braun_internal.h"

#define BRAUN_ALIGN 16u

static size_t align_up(size_t x) { return (x + BRAUN_ALIGN - 1) / BRAUN_ALIGN * BRAUN_ALIGN; }

const braun_linsolver *braun__model_linsolver(const braun_model *model)
{
#ifndef BRAUN_NO_LINSOLVER
    if (model->opt.linsolver) return model->opt.linsolver;
#endif
    (void)model;
    return &braun__dense_linsolver;
}

/* What the sizes depend on. */
typedef struct shape {
    size_t n, m, rows, N, nn;
    size_t nnz;        /* compressed A values (sparse systems) */
    size_t mass_count; /* mass callback values: n*n dense, sum of block^2 sparse */
    int dense;         /* the solver wants dense A and M */
    int sparse;        /* the system has a sparsity */
    int in_place;      /* the solver takes M in its own buffer (mass_buffer) */
    int mass_constant; /* BRAUN_MASS_CONSTANT: the claim is checked (Mcheck) */
} shape;

/* The buffers: field of braun_priv, reals. */
#define BRAUN_BUFFERS(X, s)                                                          \
    X(Q, (s).n)                                                                      \
    X(atil, (s).n)                                                                   \
    X(z, (s).n)                                                                      \
    X(u, (s).n)                                                                      \
    X(A, (s).dense ? (s).rows * (s).n : 0)                                           \
    X(Avals, (s).sparse ? (s).nnz : 0)                                               \
    /* the mass callback's output, unless the solver takes it in place */            \
    X(Mvals, !(s).in_place || (s).sparse ? (s).mass_count : 0)                       \
    /* a dense solver without its own M buffer, given a sparse system */             \
    X(Mdense, (s).dense && (s).sparse && !(s).in_place ? (s).nn : 0)                 \
    /* M(t, q) against the constant M's factor (braun__check_mass_claim) */          \
    X(Mcheck, (s).mass_constant ? (s).mass_count : 0)                                \
    X(phi, (s).rows)                                                                 \
    X(b, (s).m)                                                                      \
    X(bv, (s).rows)                                                                  \
    X(ev, (s).rows)                                                                  \
    X(rv, (s).rows)                                                                  \
    X(ep, (s).m)                                                                     \
    X(dEdq, (s).n)                                                                   \
    X(dEdv, (s).n)                                                                   \
    X(ce, (s).n)                                                                     \
    X(tmp, (s).n)                                                                    \
    X(y0, (s).N)                                                                     \
    X(ys, (s).N)                                                                     \
    X(y1, (s).N)                                                                     \
    X(yerr, (s).N)                                                                   \
    X(ylo, BRAUN_COMPENSATED_STATE ? (s).N : 0)                                      \
    X(ylo1, BRAUN_COMPENSATED_STATE ? (s).N : 0)                                     \
    X(dq, (s).n)                                                                     \
    X(dv, (s).n)                                                                     \
    X(de, (s).n)                                                                     \
    X(phi0, (s).rows)                                                                \
    X(ev0, (s).rows)                                                                 \
    X(enorm, (s).rows)                                                               \
    X(yprev, (s).N)

static shape shape_of(const braun_model *model, const braun_linsolver *ls)
{
    const braun_system *sys = &model->sys;
    const braun_sparsity *sp = sys->sparsity;
    shape s;
    s.n = (size_t)sys->n;
    s.m = (size_t)sys->m;
    s.rows = (size_t)sys->m + (size_t)sys->p;
    s.N = 2 * s.n + 1;
    s.nn = s.n * s.n;
    s.dense = (ls->flags & BRAUN_LS_DENSE) != 0;
    s.sparse = sp != NULL;
    s.in_place = ls->mass_buffer != NULL;
    s.mass_constant = (sys->flags & BRAUN_MASS_CONSTANT) != 0;
    s.nnz = 0;
    s.mass_count = s.nn;
    if (sp) {
        s.mass_count = 0;
        for (int k = 0; k < sp->nblocks; k++)
            s.mass_count += (size_t)sp->block[k] * (size_t)sp->block[k];
        s.nnz = (size_t)sp->row_ptr[sys->m + sys->p];
    }
    return s;
}

size_t braun__layout(const braun_model *model, unsigned char *base, braun_priv *pv,
                     braun_real **q, braun_real **v)
{
    const braun_linsolver *ls = braun__model_linsolver(model);
    const shape s = shape_of(model, ls);
    size_t off = align_up(sizeof(braun_priv));
    braun_real *r = base ? (braun_real *)(void *)(base + off) : NULL;
    size_t nr = 0;
    /* Point the field at the next `count` reals (NULL for none). */
#define TAKE(ptr, count)                                     \
    do {                                                     \
        const size_t c_ = (count);                           \
        if (base) (ptr) = c_ ? r + nr : NULL;                \
        nr += c_;                                            \
    } while (0)
#define TAKE_FIELD(field, count) TAKE(pv->field, count);
    braun_real *unused = NULL;
    TAKE(*(q ? q : &unused), s.n);
    TAKE(*(v ? v : &unused), s.n);
    if (base) {
        BRAUN_BUFFERS(TAKE_FIELD, s)
        for (int i = 0; i < BRAUN_MAX_STAGES; i++) TAKE(pv->k[i], s.N);
    } else {
        /* Count only: the same list with a dummy target. */
#define COUNT_FIELD(field, count) nr += (size_t)(count);
        BRAUN_BUFFERS(COUNT_FIELD, s)
#undef COUNT_FIELD
        nr += (size_t)BRAUN_MAX_STAGES * s.N;
    }
#undef TAKE_FIELD
#undef TAKE
    off = align_up(off + nr * sizeof(braun_real));
    /* A backend whose state lives in the data block gets it last. */
    const size_t state_bytes = ls->state_bytes ? ls->state_bytes(model) : 0;
    if (base) {
        pv->ls = ls;
        pv->ls_state = NULL;
        pv->ls_owned = 0;
        if (state_bytes) ls->bind(&pv->ls_state, base + off, model);
        pv->sp = model->sys.sparsity;
        pv->mass_count = s.mass_count;
        pv->dense_A = s.dense;
    }
    return off + state_bytes;
}
