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
              c_det = COL("detail"), c_pmed = COL("pos_median"), c_emed = COL("energy_median");
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
        r->pos_median = c_pmed >= 0 ? cmp_csv_num(csv, k, c_pmed) : NAN;
        r->en_median = c_emed >= 0 ? cmp_csv_num(csv, k, c_emed) : NAN;
        r->ok = strcmp(r->status, "ok") == 0;
        r->notrun = !strcmp(r->status, "NOT_BUILT") || !strcmp(r->status, "UNSUPPORTED");
    }
    return 0;
}

void cmp_rows_load_extra(const char *dir, cmp_csv *cost_csv, cmp_csv *tgt_csv, cmp_rows *d)
{
    char path[1024];
    memset(cost_csv, 0, sizeof *cost_csv);
    memset(tgt_csv, 0, sizeof *tgt_csv);
    snprintf(path, sizeof path, "%s/step_cost.csv", dir);
    if (cmp_csv_read(path, cost_csv) == 0 && cost_csv->nrows > 0) {
        d->cost = calloc((size_t)cost_csv->nrows, sizeof *d->cost);
        const int cs = cmp_csv_col(cost_csv, "scene"), cm = cmp_csv_col(cost_csv, "method"),
                  ci = cmp_csv_col(cost_csv, "integrator"), ch = cmp_csv_col(cost_csv, "h"),
                  cc = cmp_csv_col(cost_csv, "cpu_per_step_s");
        for (long k = 0; d->cost && k < cost_csv->nrows; k++) {
            cmp_cost *c = &d->cost[d->ncost++];
            c->scene = cmp_csv_str(cost_csv, k, cs);
            c->method = cmp_csv_str(cost_csv, k, cm);
            c->integ = cmp_csv_str(cost_csv, k, ci);
            c->h = cmp_csv_num(cost_csv, k, ch);
            c->per_step = cmp_csv_num(cost_csv, k, cc);
        }
    }
    snprintf(path, sizeof path, "%s/targets.csv", dir);
    if (cmp_csv_read(path, tgt_csv) == 0 && tgt_csv->nrows > 0) {
        d->tgt = calloc((size_t)tgt_csv->nrows, sizeof *d->tgt);
        const int cs = cmp_csv_col(tgt_csv, "scene"), cT = cmp_csv_col(tgt_csv, "T"),
                  cr = cmp_csv_col(tgt_csv, "reference"), cf = cmp_csv_col(tgt_csv, "floor_traj"),
                  cp = cmp_csv_col(tgt_csv, "floor_point"), cu = cmp_csv_col(tgt_csv, "phi_unit"),
                  cq = cmp_csv_col(tgt_csv, "q_unit"), cpt = cmp_csv_col(tgt_csv, "point"),
                  cmin = cmp_csv_col(tgt_csv, "minimal");
        for (long k = 0; d->tgt && k < tgt_csv->nrows; k++) {
            cmp_tgt *t = &d->tgt[d->ntgt++];
            t->scene = cmp_csv_str(tgt_csv, k, cs);
            t->T = cmp_csv_num(tgt_csv, k, cT);
            t->reference = cmp_csv_str(tgt_csv, k, cr);
            t->floor_traj = cmp_csv_num(tgt_csv, k, cf);
            t->floor_point = cmp_csv_num(tgt_csv, k, cp);
            t->phi_unit = cmp_csv_str(tgt_csv, k, cu);
            t->q_unit = cmp_csv_str(tgt_csv, k, cq);
            t->point = cmp_csv_str(tgt_csv, k, cpt);
            t->minimal = cmp_csv_str(tgt_csv, k, cmin);
        }
    }
}

const cmp_tgt *cmp_rows_target(const cmp_rows *d, const char *scene, double T)
{
    for (long k = 0; k < d->ntgt; k++)
        if (!strcmp(d->tgt[k].scene, scene) && d->tgt[k].T == T) return &d->tgt[k];
    return NULL;
}

double cmp_rows_cost(const cmp_rows *d, const char *scene, const char *method, const char *integ)
{
    for (long k = 0; k < d->ncost; k++) {
        const cmp_cost *c = &d->cost[k];
        if (!strcmp(c->scene, scene) && !strcmp(c->method, method) && !strcmp(c->integ, integ))
            return c->per_step;
    }
    return NAN;
}

const char *cmp_variant_text(const char *v)
{
    static char buf[96];
    if (!strcmp(v, "-") || !*v) return "";
    if (!strcmp(v, "defaults")) return "MuJoCo's default softness (solref 0.02 s, d = 0.9–0.95)";
    if (!strcmp(v, "solimp=0.9")) return "impedance d = 0.9–0.95 (MuJoCo's default)";
    if (!strcmp(v, "solimp=0.99")) return "impedance d = 0.99–0.999";
    if (!strcmp(v, "tc=0.02")) return "solref time constant 0.02 s (MuJoCo's default)";
    if (!strncmp(v, "tc=", 3)) snprintf(buf, sizeof buf, "solref time constant %s", v + 3);
    else if (!strncmp(v, "zeta=", 5)) snprintf(buf, sizeof buf, "damping ratio ζ = %s", v + 5);
    else if (!strncmp(v, "tol=", 4)) snprintf(buf, sizeof buf, "solver tolerance %s, 1000 iterations", v + 4);
    else if (!strcmp(v, "pgs")) return "PGS solver";
    else if (!strcmp(v, "cg")) return "CG solver";
    else if (!strncmp(v, "ctol=", 5)) snprintf(buf, sizeof buf, "constraint tolerance %s", v + 5);
    else if (!strncmp(v, "ab=", 3)) snprintf(buf, sizeof buf, "α = β = %s", v + 3);
    else if (!strcmp(v, "tuned")) return "tuned";
    else if (!strcmp(v, "energy")) return "and the energy level";
    else snprintf(buf, sizeof buf, "%s", v);
    return buf;
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
