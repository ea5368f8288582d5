/* The rows of runs.csv for the report (cmp_runs.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_runs.h"

int cmp_rows_load(const char *path, cmp_csv *csv, cmp_rows *d)
{
    memset(d, 0, sizeof *d);
    if (cmp_csv_read(path, csv)) return -1;
    d->r = calloc((size_t)(csv->nrows ? csv->nrows : 1), sizeof *d->r);
    if (!d->r) return -1;
#define COL(name) cmp_csv_col(csv, name)
    const int c_scene = COL("scene"), c_T = COL("T"), c_m = COL("method"),
              c_i = COL("integrator"), c_v = COL("variant"), c_h = COL("h"),
              c_r = COL("rtol"), c_a = COL("alpha"), c_st = COL("status"),
              c_t = COL("t_reached"), c_cpu = COL("cpu_s"), c_steps = COL("steps"),
              c_rhs = COL("rhs_evals"), c_jac = COL("jac_evals"), c_ls = COL("lin_solves"),
              c_pos = COL("pos_max"), c_vel = COL("vel_max"), c_en = COL("energy_max"),
              c_traj = COL("traj_max"), c_pt = COL("point_max"), c_sig = COL("sigma_end"),
              c_det = COL("detail");
#undef COL
    for (long k = 0; k < csv->nrows; k++) {
        cmp_row *r = &d->r[d->n++];
        r->scene = cmp_csv_str(csv, k, c_scene);
        r->method = cmp_csv_str(csv, k, c_m);
        r->integ = cmp_csv_str(csv, k, c_i);
        r->variant = cmp_csv_str(csv, k, c_v);
        r->status = cmp_csv_str(csv, k, c_st);
        r->detail = cmp_csv_str(csv, k, c_det);
        r->T = cmp_csv_num(csv, k, c_T);
        r->h = cmp_csv_num(csv, k, c_h);
        r->rtol = cmp_csv_num(csv, k, c_r);
        r->alpha = cmp_csv_num(csv, k, c_a);
        r->t_reached = cmp_csv_num(csv, k, c_t);
        r->cpu = cmp_csv_num(csv, k, c_cpu);
        r->steps = (long)cmp_csv_num(csv, k, c_steps);
        r->rhs = (long)cmp_csv_num(csv, k, c_rhs);
        r->jac = (long)cmp_csv_num(csv, k, c_jac);
        r->lsolves = (long)cmp_csv_num(csv, k, c_ls);
        r->pos = cmp_csv_num(csv, k, c_pos);
        r->vel = cmp_csv_num(csv, k, c_vel);
        r->en = cmp_csv_num(csv, k, c_en);
        r->traj = cmp_csv_num(csv, k, c_traj);
        r->point = cmp_csv_num(csv, k, c_pt);
        r->sigma = cmp_csv_num(csv, k, c_sig);
        r->ok = strcmp(r->status, "ok") == 0;
    }
    return 0;
}

int cmp_row_at(const cmp_row *r, const char *scene, double T)
{
    return strcmp(r->scene, scene) == 0 && r->T == T;
}

int cmp_row_in(const cmp_row *r, const cmp_series *s)
{
    return cmp_series_is(s, r->method, r->integ, r->variant);
}

const cmp_row *cmp_rows_fixed(const cmp_rows *d, const char *scene, double T, const char *method,
                              const char *integ, const char *variant, double h)
{
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (cmp_row_at(r, scene, T) && strcmp(r->method, method) == 0 &&
            strcmp(r->integ, integ) == 0 && strcmp(r->variant, variant) == 0 &&
            fabs(r->h - h) <= 1e-12 * h)
            return r;
    }
    return NULL;
}

/* The smallest error of the runs of series s, or (s NULL) of the method. */
static double best_of(const cmp_rows *d, const char *scene, double T, const cmp_series *s,
                      const char *method, double budget, const cmp_row **which)
{
    double best = NAN;
    if (which) *which = NULL;
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (!cmp_row_at(r, scene, T) || !r->ok || !isfinite(r->traj)) continue;
        if (s ? !cmp_row_in(r, s) : strcmp(r->method, method) != 0) continue;
        if (budget > 0 && r->cpu > budget) continue;
        if (isnan(best) || r->traj < best) {
            best = r->traj;
            if (which) *which = r;
        }
    }
    return best;
}

double cmp_rows_best_series(const cmp_rows *d, const char *scene, double T, const cmp_series *s,
                            double budget, const cmp_row **which)
{
    return best_of(d, scene, T, s, NULL, budget, which);
}

double cmp_rows_best_method(const cmp_rows *d, const char *scene, double T, const char *method,
                            double budget, const cmp_row **which)
{
    return best_of(d, scene, T, NULL, method, budget, which);
}

int cmp_rows_has(const cmp_rows *d, const char *scene, double T, const char *method)
{
    for (long k = 0; k < d->n; k++)
        if (cmp_row_at(&d->r[k], scene, T) && strcmp(d->r[k].method, method) == 0) return 1;
    return 0;
}

/* 1e-05 -> 1e-5, 1e+02 -> 1e2. */
static const char *short_exponent(char *buf)
{
    char *p = strstr(buf, "e-0");
    if (p) memmove(p + 2, p + 3, strlen(p + 3) + 1);
    p = strstr(buf, "e+0");
    if (p) memmove(p + 2, p + 3, strlen(p + 3) + 1);
    p = strstr(buf, "e+");
    if (p) memmove(p + 1, p + 2, strlen(p + 2) + 1);
    return buf;
}

const char *cmp_fmt_e(double x, char *buf)
{
    if (isnan(x)) return "–";
    snprintf(buf, 24, "%.2g", x);
    return short_exponent(buf);
}

const char *cmp_fmt_g(double x, char *buf)
{
    if (isnan(x)) return "–";
    snprintf(buf, 24, "%g", x);
    return short_exponent(buf);
}

const char *cmp_fmt_param(const cmp_row *r, char *buf)
{
    char t[24];
    if (!isnan(r->h)) snprintf(buf, 48, "h = %s", cmp_fmt_e(r->h, t));
    else snprintf(buf, 48, "rtol = %s", cmp_fmt_e(r->rtol, t));
    return buf;
}
