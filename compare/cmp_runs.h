/* The rows of runs.csv (or ida_probe.csv) as the report reads them, and the
 * look-ups its sections and claims share (cmp_report.c, cmp_claims.c). */
#ifndef CMP_RUNS_H
#define CMP_RUNS_H

#include "cmp_csv.h"
#include "cmp_series.h"

typedef struct cmp_row {
    const char *scene, *method, *integ, *variant, *status, *detail;
    double T, h, rtol, alpha, t_reached, cpu, pos, vel, en, traj, point, sigma;
    long steps, rhs, jac, lsolves;
    int ok;                            /* status "ok" */
} cmp_row;

typedef struct cmp_rows {
    cmp_row *r;
    long n;
} cmp_rows;

/* Read a runs.csv into csv (which owns the strings) and d (free d->r and
 * csv). 0, or -1 if the file cannot be read. */
int cmp_rows_load(const char *path, cmp_csv *csv, cmp_rows *d);

/* 1 if the run is of this scene and horizon. */
int cmp_row_at(const cmp_row *r, const char *scene, double T);
/* 1 if the run belongs to the series. */
int cmp_row_in(const cmp_row *r, const cmp_series *s);
/* The run of scene, T, method, integrator, variant at step h, or NULL. */
const cmp_row *cmp_rows_fixed(const cmp_rows *d, const char *scene, double T, const char *method,
                              const char *integ, const char *variant, double h);
/* Smallest trajectory error of a series' (s) or of a method's (any
 * integrator and variant) runs that reached T within a CPU budget
 * (budget <= 0: any); NaN if none. *which: that run or NULL. */
double cmp_rows_best_series(const cmp_rows *d, const char *scene, double T, const cmp_series *s,
                            double budget, const cmp_row **which);
double cmp_rows_best_method(const cmp_rows *d, const char *scene, double T, const char *method,
                            double budget, const cmp_row **which);
/* 1 if some run of scene, T has this method. */
int cmp_rows_has(const cmp_rows *d, const char *scene, double T, const char *method);

/* Numbers as the report writes them, into buf (24 bytes): cmp_fmt_e two
 * significant digits ("1e-5", "0.012", "–" for NaN); cmp_fmt_g all that %g
 * gives ("1e-6", "0.05", "100"; for thresholds). */
const char *cmp_fmt_e(double x, char *buf);
const char *cmp_fmt_g(double x, char *buf);
/* A run as "h = 0.01" or "rtol = 1e-8", into buf (48 bytes). */
const char *cmp_fmt_param(const cmp_row *r, char *buf);

#endif
