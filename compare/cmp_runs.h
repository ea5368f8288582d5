/* The rows of runs.csv (or ida_probe.csv) as the report reads them, and the
 * look-ups its sections and claims share (cmp_report.c, cmp_claims.c). */
#ifndef CMP_RUNS_H
#define CMP_RUNS_H

#include "cmp_csv.h"
#include "cmp_series.h"

typedef struct cmp_row {
    const char *scene, *method, *integ, *variant, *status, *detail;
    double T, h, rtol, alpha, t_reached, cpu, pos, vel, en, traj, point, sigma;
    double pos_median, en_median;      /* medians over the run's samples */
    long steps, rhs, jac, lsolves;
    int ok;                            /* status "ok" */
    int notrun;                        /* a peer not built, or unable to express the scene */
} cmp_row;

/* One row of step_cost.csv: CPU seconds per step of a method on a scene. */
typedef struct cmp_cost {
    const char *scene, *method, *integ;
    double h, per_step;                /* NaN: failed (detail says why) */
} cmp_cost;

/* One row of targets.csv: a scene's reference, its own error and units. */
typedef struct cmp_tgt {
    const char *scene, *reference, *phi_unit, *q_unit, *point, *minimal;
    double T, floor_traj, floor_point;
} cmp_tgt;

typedef struct cmp_rows {
    cmp_row *r;
    long n;
    /* Optional (cmp_rows_load_extra): step_cost.csv and targets.csv. */
    cmp_cost *cost;
    long ncost;
    cmp_tgt *tgt;
    long ntgt;
} cmp_rows;

/* Read a runs.csv into csv (which owns the strings) and d (free d->r and
 * csv). 0, or -1 if the file cannot be read. */
int cmp_rows_load(const char *path, cmp_csv *csv, cmp_rows *d);

/* step_cost.csv and targets.csv of dir into d (their strings owned by
 * cost_csv, tgt_csv; free d->cost, d->tgt). Missing files leave them
 * empty. */
void cmp_rows_load_extra(const char *dir, cmp_csv *cost_csv, cmp_csv *tgt_csv, cmp_rows *d);
/* The targets.csv row of scene, T, or NULL. */
const cmp_tgt *cmp_rows_target(const cmp_rows *d, const char *scene, double T);
/* CPU seconds per step of method:integ on scene (step_cost.csv), NaN if none. */
double cmp_rows_cost(const cmp_rows *d, const char *scene, const char *method, const char *integ);
/* A variant of a sweep in words ("damping ratio ζ = 0.5", "constraint
 * tolerance 1e-10"); "" for "-". */
const char *cmp_variant_text(const char *variant);

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
