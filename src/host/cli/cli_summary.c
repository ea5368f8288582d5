/* Summary of a run as pretty JSON, one key per line. Numbers are %.17g so
 * they read back exactly; NaN and Inf have no JSON spelling and become null
 * (also the value of quantities that do not exist, e.g. no reference). */
#include <math.h>
#include <string.h>

#include "braun_cli.h"

typedef struct json {
    FILE *f;
    int keys; /* written so far: decides the comma before the next one */
} json;

static void key(json *j, const char *k)
{
    fprintf(j->f, "%s\n  \"%s\": ", j->keys++ ? "," : "", k);
}

static void write_number(FILE *f, double x)
{
    if (isfinite(x)) fprintf(f, "%.17g", x);
    else fputs("null", f);
}

static void num(json *j, const char *k, double x)
{
    key(j, k);
    write_number(j->f, x);
}

static void integer(json *j, const char *k, long x)
{
    key(j, k);
    fprintf(j->f, "%ld", x);
}

static void str(json *j, const char *k, const char *s)
{
    key(j, k);
    fputc('"', j->f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\') fprintf(j->f, "\\%c", *p);
        else if (*p < 0x20) fprintf(j->f, "\\u%04x", *p);
        else fputc(*p, j->f);
    }
    fputc('"', j->f);
}

static void array(json *j, const char *k, const double *x, int n)
{
    key(j, k);
    fputc('[', j->f);
    for (int i = 0; i < n; i++) {
        if (i) fputs(", ", j->f);
        write_number(j->f, x[i]);
    }
    fputc(']', j->f);
}

/* "BRAUN_ERR_DIVERGED" out of "BRAUN_ERR_DIVERGED: the solution left ...". */
static const char *status_name(int status, char *buf, size_t size)
{
    const char *s = braun_status_str(status);
    size_t len = strcspn(s, ":");
    if (len >= size) len = size - 1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    return buf;
}

static const char *discretization_name(braun_discretization d)
{
    return d == BRAUN_PER_STAGE ? "per-stage" : "per-step";
}

int braun_cli_write_summary(FILE *f, const braun_cli_result *r)
{
    const braun_cli_run_args *a = r->args;
    const braun_system *sys = &r->model->sys;
    const braun_cli_monitor *mon = r->mon;
    const int adaptive = a->method == BRAUN_DOPRI5;
    char corr[64], status[64];
    json j = {f, 0};

    fputc('{', f);
    str(&j, "scene", r->scene);
    str(&j, "method", r->method);
    str(&j, "corrections", braun_cli_corrections_str(r->model->opt.corrections, corr, sizeof corr));
    str(&j, "discretization", discretization_name(r->model->opt.discretization));
    str(&j, "integrator", braun_method_name(a->method));
    num(&j, "dt", a->dt);
    num(&j, "t_end", a->t_end);
    integer(&j, "steps", r->stats.steps);
    integer(&j, "rhs_evals", r->stats.rhs_evals);
    integer(&j, "rejected_steps", r->stats.rejected_steps);
    integer(&j, "mass_factorizations", r->stats.mass_factorizations);
    integer(&j, "constraint_factorizations", r->stats.constraint_factorizations);
    integer(&j, "rank_deficient", r->stats.rank_deficient);
    integer(&j, "energy_guard_hits", r->stats.energy_guard_hits);
    num(&j, "cpu_s", r->cpu_s);
    num(&j, "max_position_constraint_error", mon->max.pos);
    num(&j, "max_velocity_constraint_error", mon->max.vel);
    num(&j, "max_energy_error", mon->max.energy);
    num(&j, "max_trajectory_error", mon->max.traj);
    num(&j, "max_point_error", mon->max.point);
    num(&j, "final_position_constraint_error", mon->cur.pos);
    num(&j, "final_velocity_constraint_error", mon->cur.vel);
    num(&j, "final_energy_error", mon->cur.energy);
    num(&j, "final_trajectory_error", mon->cur.traj);
    num(&j, "final_point_error", mon->cur.point);
    num(&j, "final_t", r->final_t);
    array(&j, "final_q", r->final_q, sys->n);
    array(&j, "final_v", r->final_v, sys->n);
    str(&j, "status", status_name(r->status, status, sizeof status));
    integer(&j, "n", sys->n);
    integer(&j, "m", sys->m);
    integer(&j, "p", sys->p);
    str(&j, "backend", r->backend ? r->backend : "dense");
    key(&j, "sparse");
    fputs(r->sparse ? "true" : "false", f);
    /* Options as set; 0 means the library's default. */
    num(&j, "rank_tol", (double)r->model->opt.rank_tol);
    num(&j, "energy_max_rel", (double)r->model->opt.energy_max_rel);
    num(&j, "rtol", adaptive ? a->rtol : NAN);
    num(&j, "atol", adaptive ? a->atol : NAN);
    num(&j, "ref_h", mon->ref_h);
    str(&j, "libbraun_version", BRAUN_VERSION);
    fputs("\n}\n", f);
    fflush(f);
    return ferror(f) ? -1 : 0;
}
