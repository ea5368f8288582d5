/* A reference's samples on its output grid. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ifm.h"

int ifm_series_init(ifm_series *s, long count, int width, int n, double dt)
{
    memset(s, 0, sizeof *s);
    s->count = count;
    s->width = width;
    s->n = n;
    s->dt = dt;
    s->t = calloc((size_t)count, sizeof *s->t);
    s->y = calloc((size_t)count * (size_t)width, sizeof *s->y);
    if (n > 0) {
        s->q = calloc((size_t)count * (size_t)n, sizeof *s->q);
        s->v = calloc((size_t)count * (size_t)n, sizeof *s->v);
    }
    if (!s->t || !s->y || (n > 0 && (!s->q || !s->v))) {
        ifm_series_free(s);
        return -1;
    }
    for (long j = 0; j < count; j++) s->t[j] = (double)j * dt;
    return 0;
}

void ifm_series_free(ifm_series *s)
{
    free(s->t);
    free(s->y);
    free(s->q);
    free(s->v);
    s->t = s->y = s->q = s->v = NULL;
}

double ifm_series_maxdiff(const ifm_series *a, const ifm_series *b, int width)
{
    const long count = a->count < b->count ? a->count : b->count;
    double e = 0;
    for (long j = 0; j < count; j++)
        for (int k = 0; k < width; k++) {
            const double d = fabs(a->y[j * a->width + k] - b->y[j * b->width + k]);
            if (!(d <= e)) e = d; /* NaN propagates */
        }
    return e;
}
