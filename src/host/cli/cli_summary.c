/* Summary of a run as pretty JSON, one key per line. Numbers are the
 * shortest decimals that read back as the same double (0.01, not
 * 0.01000000000000000021); NaN and Inf have no JSON spelling and become
 * null (also the value of quantities that do not exist, e.g. no
 * reference). Options show the value the run used, defaults included, and
 * "defaults" lists those the library chose. Units: docs/cli.md. */
#include <math.h>
#include <string.h>

#include "braun_cli.h"
#include "braun_math.h"

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
    if (isfinite(x)) braun_cli_put_number(f, x);
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
    integer(&j, "soft_filtered", r->stats.soft_filtered);
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
    str(&j, "status", braun_cli_status_name(r->status, status, sizeof status));
    integer(&j, "n", sys->n);
    integer(&j, "m", sys->m);
    integer(&j, "p", sys->p);
    str(&j, "backend", r->backend ? r->backend : "dense");
    key(&j, "sparse");
    fputs(r->sparse ? "true" : "false", f);
    /* Options as set; 0 means the library's default. */
    /* Options as the run used them: a value the library chose (0 given)
     * is shown with its effective value and listed in "defaults". */
    const braun_options *o = &r->model->opt;
    const char *defaulted[12];
    int nd = 0;
    const int rows = sys->m + sys->p;
    if (!(o->rank_tol > 0)) defaulted[nd++] = "rank_tol";
    num(&j, "rank_tol", o->rank_tol > 0 ? (double)o->rank_tol
                                        : (double)braun_default_rank_tol(rows, sys->n));
    if (!(o->energy_max_rel > 0)) defaulted[nd++] = "energy_max_rel";
    num(&j, "energy_max_rel", o->energy_max_rel > 0 ? (double)o->energy_max_rel : 0.01);
    num(&j, "rtol", adaptive ? a->rtol : NAN);
    num(&j, "atol", adaptive ? a->atol : NAN);
    num(&j, "ref_h", mon->ref_h);
    str(&j, "libbraun_version", BRAUN_VERSION);
    if (!(o->symmetry_tol > 0)) defaulted[nd++] = "symmetry_tol";
    num(&j, "symmetry_tol", o->symmetry_tol > 0 ? (double)o->symmetry_tol
                                                : 1e3 * (double)BRAUN_EPS);
    if (!(o->inconsistency_tol > 0)) defaulted[nd++] = "inconsistency_tol";
    num(&j, "inconsistency_tol", o->inconsistency_tol > 0 ? (double)o->inconsistency_tol
                                                          : sqrt((double)BRAUN_EPS));
    if (o->soft_tol == 0) defaulted[nd++] = "soft_tol";
    num(&j, "soft_tol", o->soft_tol < 0 ? NAN : o->soft_tol > 0 ? (double)o->soft_tol : 1e-4);
    /* The accuracy guard: relative value, and the bounds it applied. */
    const braun_cli_bounds *b = &r->stop.bounds;
    if (o->guard == 0) defaulted[nd++] = "guard";
    num(&j, "guard", b->on ? b->guard : NAN);
    num(&j, "guard_position_bound", b->pos);
    num(&j, "guard_velocity_bound", b->vel);
    num(&j, "guard_energy_bound", b->energy);
    num(&j, "guard_position_scale", b->pos_scale);
    num(&j, "guard_velocity_scale", b->vel_scale);
    num(&j, "guard_energy_scale", b->energy_scale);
    /* The state the guard refused (never reported: not in the maxima, the
     * CSV or a plot); the final state is the one before it. */
    num(&j, "refused_state_t", r->stop.dropped ? r->stop.dropped_t : NAN);
    num(&j, "error_t", r->error_t);
    /* The adaptive driver's limits as used (braun_adaptive: 0 selects). */
    const double span = a->t_end;
    if (adaptive) {
        defaulted[nd++] = "h_min";
        defaulted[nd++] = "h_max";
    }
    if (!a->max_steps_given) defaulted[nd++] = "max_steps";
    if (!(a->ref_h > 0) && !isnan(mon->ref_h)) defaulted[nd++] = "ref_h";
    /* The first trial step as used: --dt, at most h_max (it said 1e+300). */
    num(&j, "h0", adaptive ? (a->dt < span ? a->dt : span) : NAN);
    num(&j, "h_min", adaptive ? braun_cli_adaptive_h_min(span) : NAN);
    num(&j, "h_max", adaptive ? span : NAN);
    /* The step limit of both kinds of run (--max-steps): dopri5's
     * attempts, a fixed-step run's steps (checked before it started). */
    integer(&j, "max_steps", a->max_steps);
    integer(&j, "every", a->every);
    num(&j, "cpu_s_monitored", r->cpu_monitored_s);
    str(&j, "cpu_s_note", r->interrupted ? "interrupted: the timing run's time is not this "
                                           "shorter run's; see cpu_s_monitored"
                          : isnan(r->cpu_s) ? "not timed (braun plot): see cpu_s_monitored"
                                            : "integration alone: a second run of the same steps "
                                              "without monitoring or output");
    key(&j, "defaults");
    fputc('[', f);
    for (int i = 0; i < nd; i++) fprintf(f, "%s\"%s\"", i ? ", " : "", defaulted[i]);
    fputc(']', f);
    fputs("\n}\n", f);
    fflush(f);
    return ferror(f) ? -1 : 0;
}
