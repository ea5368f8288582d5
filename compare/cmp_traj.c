/* Sampled trajectories: growable arrays of (t, q, v). */
#include <stdlib.h>
#include <string.h>

#include "cmp.h"

int cmp_traj_init(cmp_traj *tr, int n, long cap)
{
    memset(tr, 0, sizeof *tr);
    tr->n = n;
    if (cap < 16) cap = 16;
    tr->t = malloc((size_t)cap * sizeof(double));
    tr->q = malloc((size_t)cap * (size_t)n * sizeof(double));
    tr->v = malloc((size_t)cap * (size_t)n * sizeof(double));
    if (!tr->t || !tr->q || !tr->v) {
        cmp_traj_free(tr);
        return -1;
    }
    tr->cap = cap;
    return 0;
}

void cmp_traj_clear(cmp_traj *tr)
{
    tr->count = 0;
}

void cmp_traj_free(cmp_traj *tr)
{
    free(tr->t);
    free(tr->q);
    free(tr->v);
    tr->t = tr->q = tr->v = NULL;
    tr->count = tr->cap = 0;
}

static int grow(cmp_traj *tr)
{
    long cap = tr->cap * 2;
    const size_t n = (size_t)tr->n;
    double *t = realloc(tr->t, (size_t)cap * sizeof(double));
    if (!t) return -1;
    tr->t = t;
    double *q = realloc(tr->q, (size_t)cap * n * sizeof(double));
    if (!q) return -1;
    tr->q = q;
    double *v = realloc(tr->v, (size_t)cap * n * sizeof(double));
    if (!v) return -1;
    tr->v = v;
    tr->cap = cap;
    return 0;
}

int cmp_traj_push(cmp_traj *tr, double t, const double *q, const double *v)
{
    if (tr->count == tr->cap && grow(tr)) return -1;
    const size_t n = (size_t)tr->n, k = (size_t)tr->count;
    tr->t[k] = t;
    memcpy(tr->q + k * n, q, n * sizeof(double));
    memcpy(tr->v + k * n, v, n * sizeof(double));
    tr->count++;
    return 0;
}
