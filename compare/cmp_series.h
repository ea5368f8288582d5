/* The series of the comparison (compare/series.tsv, its comment says what
 * the columns are): one row per method:integrator:variant, with its label
 * and plot style and where it appears. The table is compiled in from the
 * file (compare/series.awk at build time), so braun-compare's report,
 * braun-bench's cost at matched error and compare/plot.sh read the same
 * rows. No SUNDIALS or GSL here: braun-bench links this file too. */
#ifndef CMP_SERIES_H
#define CMP_SERIES_H

#include <stdio.h>

typedef struct cmp_series {
    const char *key;                   /* "method:integrator:variant" */
    const char *method, *integ, *variant;
    const char *label;                 /* legend, report row, bench column */
    const char *colour;                /* gnuplot rgb, "#rrggbb" */
    int dash, point;                   /* gnuplot dt, pt */
    const char *in;                    /* tags: "steps,history,...", "-": none */
} cmp_series;

extern const cmp_series cmp_series_table[];
extern const int cmp_series_count;

/* 1 if the series is method:integ:variant. */
int cmp_series_is(const cmp_series *s, const char *method, const char *integ, const char *variant);
/* The series of a run, or NULL. */
const cmp_series *cmp_series_of(const char *method, const char *integ, const char *variant);
/* The series with this key, or NULL. */
const cmp_series *cmp_series_find(const char *key);
/* 1 if tag (steps, tol, history, slider, bench) is in the series' "in". */
int cmp_series_in(const cmp_series *s, const char *tag);
/* The table as compare/series.awk -v out=plot writes it:
 * key|label|colour|dash|point|in per line. */
void cmp_series_print(FILE *f);

#endif
