/* results/compare/report.md: the study's plots with what they show, in
 * sentences computed from the CSV files beside them (docs/compare.md,
 * "The report"). Nothing here is written by hand about the results: every
 * number and every verdict comes from runs.csv, ida_probe.csv,
 * references.csv, targets.csv, step_cost.csv, singular.csv, plots.tsv and
 * meta.txt.
 *
 * Order: a one-page summary (the four-bar over 1000 s against every
 * method at braun's CPU time, the cost per step against MuJoCo, the most
 * accurate method within each CPU budget per scene), the paper's claims,
 * the work-precision plots with every method, the paper's Fig. 6, the
 * peers, IDA, scene by scene, references, braun's own failures, and the
 * probes in an appendix. Errors below the reference's own error (its
 * "floor", targets.csv) are marked † and never enter an observed order. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_claims.h"
#include "cmp_runs.h"
#include "cmp_series.h"
#include "cmp_study.h"

/* The label of a run: its series' (compare/series.tsv); a sweep cell's is
 * its method and integrator with the setting that differs from the main
 * series, in words. */
static const char *label_of(const cmp_row *r)
{
    const cmp_series *s = cmp_series_of(r->method, r->integ, r->variant);
    if (s) return s->label;
    static char buf[192];
    if (!strcmp(r->method, "baumgarte") && !strncmp(r->variant, "ab=", 3))
        snprintf(buf, sizeof buf, "Baumgarte (α = β = %s), RK4", r->variant + 3);
    else if (!strcmp(r->method, "mujoco"))
        snprintf(buf, sizeof buf, "MuJoCo 2.2.2 %s, %s (else as the main series)",
                 !strcmp(r->integ, "mj-rk4") ? "RK4" : r->integ, cmp_variant_text(r->variant));
    else if (!strcmp(r->method, "simbody"))
        snprintf(buf, sizeof buf, "Simbody 3.7 %s, %s", r->integ, cmp_variant_text(r->variant));
    else if (!strcmp(r->method, "braun-noenergy"))
        snprintf(buf, sizeof buf, "braun without energy correction, %s%s%s", r->integ,
                 strcmp(r->variant, "-") ? ", " : "", cmp_variant_text(r->variant));
    else
        snprintf(buf, sizeof buf, "%s, %s%s%s", r->method, r->integ,
                 strcmp(r->variant, "-") ? ", " : "", cmp_variant_text(r->variant));
    return buf;
}

/* Free text in a table cell: '|' would end the cell. */
static const char *cell(const char *text)
{
    static char buf[4][512];
    static int k;
    char *b = buf[k = (k + 1) % 4];
    size_t n = 0;
    for (const char *p = text; *p && n + 3 < sizeof buf[0]; p++) {
        if (*p == '|') b[n++] = '\\';
        b[n++] = *p;
    }
    b[n] = '\0';
    return b;
}

/* ------------------------------------------------------------ meta */
typedef struct meta {
    char study[32], date[40], cpu[128], cores[16], sundials[48], gsl[48], reps[8], jobs[16];
    char mujoco[48], simbody[48], lapack[160];
    double run_wall, plot_wall;
} meta;

static void read_meta(const char *dir, meta *m)
{
    char path[1024], line[512];
    memset(m, 0, sizeof *m);
    m->run_wall = m->plot_wall = NAN;
    snprintf(path, sizeof path, "%s/meta.txt", dir);
    FILE *f = fopen(path, "r");
    if (!f) return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        char *eq = strchr(line, '=');
        if (!eq) continue;
        *eq = '\0';
        const char *k = line, *v = eq + 1;
        if (!strcmp(k, "study")) snprintf(m->study, sizeof m->study, "%s", v);
        else if (!strcmp(k, "date")) snprintf(m->date, sizeof m->date, "%s", v);
        else if (!strcmp(k, "cpu")) snprintf(m->cpu, sizeof m->cpu, "%s", v);
        else if (!strcmp(k, "cores")) snprintf(m->cores, sizeof m->cores, "%s", v);
        else if (!strcmp(k, "sundials")) snprintf(m->sundials, sizeof m->sundials, "%s", v);
        else if (!strcmp(k, "gsl")) snprintf(m->gsl, sizeof m->gsl, "%s", v);
        else if (!strcmp(k, "mujoco")) snprintf(m->mujoco, sizeof m->mujoco, "%s", v);
        else if (!strcmp(k, "simbody")) snprintf(m->simbody, sizeof m->simbody, "%s", v);
        else if (!strcmp(k, "lapack")) snprintf(m->lapack, sizeof m->lapack, "%s", v);
        else if (!strcmp(k, "reps")) snprintf(m->reps, sizeof m->reps, "%s", v);
        else if (!strcmp(k, "jobs")) snprintf(m->jobs, sizeof m->jobs, "%s", v);
        else if (!strcmp(k, "run_wall_s")) m->run_wall = atof(v);
        else if (!strcmp(k, "plot_wall_s")) m->plot_wall = atof(v);
    }
    fclose(f);
}

/* ------------------------------------------------------------ pairs */
typedef struct pair {
    const char *scene;
    double T;
} pair;

static int pairs_of(const cmp_rows *d, pair *out, int max)
{
    int n = 0;
    for (long k = 0; k < d->n; k++) {
        int seen = 0;
        for (int i = 0; i < n; i++) seen |= cmp_row_at(&d->r[k], out[i].scene, out[i].T);
        if (!seen && n < max) {
            out[n].scene = d->r[k].scene;
            out[n].T = d->r[k].T;
            n++;
        }
    }
    return n;
}

/* Index of a scene's first horizon in pr. */
static int first_index(const pair *pr, int np, const char *scene)
{
    for (int i = 0; i < np; i++)
        if (!strcmp(pr[i].scene, scene)) return i;
    return -1;
}

static int file_exists(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (f) fclose(f);
    return f != NULL;
}

/* The notes plot.sh left for a plot (plots.tsv: NAME<TAB>NOTE), as a
 * sentence. */
static void plot_notes(FILE *md, const char *dir, const char *name)
{
    char path[1024], line[2048];
    snprintf(path, sizeof path, "%s/plots.tsv", dir);
    FILE *f = fopen(path, "r");
    if (!f) return;
    const size_t len = strlen(name);
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        if (!strncmp(line, name, len) && line[len] == '\t')
            fprintf(md, "*Axes:* %s.\n\n", line + len + 1);
    }
    fclose(f);
}

static int figure(FILE *md, const char *dir, const char *name, const char *alt)
{
    char png[256];
    snprintf(png, sizeof png, "%s.png", name);
    if (file_exists(dir, png)) {
        fprintf(md, "![%s](%s) ([SVG](%s.svg))\n\n", alt, png, name);
        plot_notes(md, dir, name);
        return 1;
    }
    fprintf(md, "*(%s: no plot — no runs of this kind)*\n\n", alt);
    return 0;
}

/* ------------------------------------------------------------ floors */
/* The reference's own error on a scene and horizon (NaN: unknown). */
static double floor_of(const cmp_rows *d, const char *scene, double T)
{
    const cmp_tgt *t = cmp_rows_target(d, scene, T);
    return t ? t->floor_traj : NAN;
}

/* An error as the tables print it: two digits, and † when it is below the
 * reference's own error (it then measures the reference). */
static const char *fmt_err(const cmp_rows *d, const char *scene, double T, double x, char *buf)
{
    char t[24];
    const double fl = floor_of(d, scene, T);
    if (!isnan(x) && !isnan(fl) && x < fl) snprintf(buf, 32, "*%s*†", cmp_fmt_e(x, t));
    else snprintf(buf, 32, "%s", cmp_fmt_e(x, t));
    return buf;
}

static const char *q_unit(const cmp_rows *d, const char *scene, double T)
{
    const cmp_tgt *t = cmp_rows_target(d, scene, T);
    return t && *t->q_unit ? t->q_unit : "m; rad";
}

/* ------------------------------------------------------------ sections */
#define ACCURATE 1e-2 /* "accurate": max ||q - q_ref|| of 1 cm on 1 m links */

static const double BUDGETS[] = {1e-3, 1e-2, 1e-1, 1.0, 10.0};
#define NBUDGETS ((int)(sizeof BUDGETS / sizeof BUDGETS[0]))

/* The most accurate run of any method that reached T within a budget:
 * its label and error, or NULL. */
static const cmp_row *best_within(const cmp_rows *d, const char *scene, double T, double budget,
                                  const cmp_row *skip_method_of)
{
    const cmp_row *best = NULL;
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (!cmp_row_at(r, scene, T) || !r->ok || !isfinite(r->traj) || r->cpu > budget) continue;
        if (skip_method_of && !strcmp(r->method, skip_method_of->method)) continue;
        if (!best || r->traj < best->traj) best = r;
    }
    return best;
}

/* Most accurate series within each CPU budget. */
static void winners(FILE *md, const cmp_rows *d, const char *scene, double T)
{
    char b[32], c[48], e[24];
    fprintf(md, "| CPU budget | most accurate | its error | runner-up (another method) | its error |\n");
    fprintf(md, "|---|---|---|---|---|\n");
    for (int k = 0; k < NBUDGETS; k++) {
        const cmp_row *w1 = best_within(d, scene, T, BUDGETS[k], NULL);
        if (!w1) continue;
        const cmp_row *w2 = best_within(d, scene, T, BUDGETS[k], w1);
        fprintf(md, "| %s s | %s (%s) | %s |", cmp_fmt_e(BUDGETS[k], e), label_of(w1),
                cmp_fmt_param(w1, c), fmt_err(d, scene, T, w1->traj, b));
        if (w2)
            fprintf(md, " %s (%s) | %s |\n", label_of(w2), cmp_fmt_param(w2, c),
                    fmt_err(d, scene, T, w2->traj, b));
        else
            fprintf(md, " – | – |\n");
    }
    fprintf(md, "\n");
}

/* Every series: its best error, the cost of it, and where it breaks down. */
static void series_summary(FILE *md, const cmp_rows *d, const char *scene, double T)
{
    char a[32], b[24], c[48];
    fprintf(md, "| method | best error (reached T) | at | CPU [s] | steps | runs that did not reach T |\n");
    fprintf(md, "|---|---|---|---|---|---|\n");
    for (int s = 0; s < cmp_series_count; s++) {
        int count = 0, failed = 0;
        char fails[512] = "";
        size_t fl = 0;
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, scene, T) || !cmp_row_in(r, &cmp_series_table[s]) || r->notrun)
                continue;
            count++;
            if (!r->ok) {
                failed++;
                if (fl < sizeof fails - 96)
                    fl += (size_t)snprintf(fails + fl, sizeof fails - fl, "%s%s: %s at t = %.4g",
                                           failed > 1 ? "; " : "", cmp_fmt_param(r, c), r->status,
                                           r->t_reached);
            }
        }
        if (!count) continue;
        const cmp_row *w;
        double e = cmp_rows_best_series(d, scene, T, &cmp_series_table[s], 0, &w);
        fprintf(md, "| %s | %s | %s | %s | %ld | %s |\n", cmp_series_table[s].label,
                fmt_err(d, scene, T, e, a), w ? cmp_fmt_param(w, c) : "–",
                w ? cmp_fmt_e(w->cpu, b) : "–", w ? w->steps : 0L, failed ? fails : "none");
    }
    fprintf(md, "\nErrors marked † are below the reference's own error (%s): they measure the "
                "reference, not the method.\n\n",
            cmp_fmt_e(floor_of(d, scene, T), a));
}

/* Largest step size at which a fixed-step series stays accurate. */
static double largest_accurate_h(const cmp_rows *d, const char *scene, double T,
                                 const cmp_series *s)
{
    double best = NAN;
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (!cmp_row_at(r, scene, T) || !cmp_row_in(r, s) || !r->ok || isnan(r->h)) continue;
        if (r->traj <= ACCURATE && (isnan(best) || r->h > best)) best = r->h;
    }
    return best;
}

/* Observed order of a fixed-step series from its two smallest step sizes
 * whose errors are both at least ORDER_FLOOR times the reference's own
 * error (below that the error is the reference's) and at most ORDER_CEIL
 * (above it the run did not simulate the mechanism: a "fit" of 7.3 and
 * 78.6 m, or of 3.7e4 and 3.8e4, printed orders 3.4 and 0.0). NaN if there
 * are no two such runs; *r1, *r2 the pair used. */
#define ORDER_FLOOR 10.0
#define ORDER_CEIL 0.1 /* the rows' units: the study's mechanisms are about 1 m */
static double observed_order(const cmp_rows *d, const char *scene, double T, const cmp_series *s,
                             int *below, int *above, const cmp_row **p1, const cmp_row **p2)
{
    const double fl = floor_of(d, scene, T);
    const cmp_row *r1 = NULL, *r2 = NULL;
    *below = *above = 0;
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (!cmp_row_at(r, scene, T) || !cmp_row_in(r, s) || !r->ok || isnan(r->h)) continue;
        if (!isnan(fl) && !(r->traj > ORDER_FLOOR * fl)) {
            (*below)++;
            continue;
        }
        if (!(r->traj <= ORDER_CEIL)) {
            (*above)++;
            continue;
        }
        if (!r1 || r->h < r1->h) {
            r2 = r1;
            r1 = r;
        } else if (!r2 || r->h < r2->h) {
            r2 = r;
        }
    }
    *p1 = r1;
    *p2 = r2;
    if (!r1 || !r2 || !(r1->traj > 0) || !(r2->traj > 0)) return NAN;
    return log(r2->traj / r1->traj) / log(r2->h / r1->h);
}

static void breakdown(FILE *md, const cmp_rows *d, const char *scene, double T)
{
    char a[24], b[24];
    /* The fixed-step series: those the table shows against h ("steps"). */
    for (int i = 0; i < cmp_series_count; i++) {
        const cmp_series *s = &cmp_series_table[i];
        if (!cmp_series_in(s, "steps")) continue;
        int any = 0;
        for (long k = 0; k < d->n; k++)
            any |= cmp_row_at(&d->r[k], scene, T) && cmp_row_in(&d->r[k], s) && !d->r[k].notrun;
        if (!any) continue;
        int below = 0, above = 0;
        const cmp_row *r1, *r2;
        const double h = largest_accurate_h(d, scene, T, s);
        const double p = observed_order(d, scene, T, s, &below, &above, &r1, &r2);
        /* (One buffer per number: a shared one printed "up to h = 0.01"
         * for every series, whatever its step.) */
        if (isnan(h))
            fprintf(md, "- %s: no step size of the grid keeps the error below %s.", s->label,
                    cmp_fmt_e(ACCURATE, a));
        else
            fprintf(md, "- %s: the largest step with an error below %s: h = %s.", s->label,
                    cmp_fmt_e(ACCURATE, a), cmp_fmt_e(h, b));
        if (!isnan(p) && p >= 0.5 && p <= 8)
            fprintf(md, " Observed order between the two smallest steps whose errors lie between "
                        "%g× the reference's own error and %g: %.1f.", ORDER_FLOOR, ORDER_CEIL, p);
        else if (!isnan(p))
            fprintf(md, " No observed order: between its two smallest steps in that range the "
                        "error does not fall as a power of h (%s at h = %g, %s at h = %g).",
                    cmp_fmt_e(r1->traj, a), r1->h, cmp_fmt_e(r2->traj, b), r2->h);
        else if (below || above)
            fprintf(md, " No observed order: of its runs that reached T, %d are within %g× the "
                        "reference's own error (%s) and %d above %g (not the mechanism's motion).",
                    below, ORDER_FLOOR, cmp_fmt_e(floor_of(d, scene, T), b), above, ORDER_CEIL);
        fprintf(md, "\n");
    }
    fprintf(md, "\n");
}

/* ------------------------------------------------------------ IDA */
static void ida_section(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    char a[24], b[24], c[48], e[24];
    fprintf(md, "## IDA: best achievable error, its cost, and where it fails\n\n");
    fprintf(md, "Every IDA run of the study (both variants of `ida-ggl`, and `ida-index1`), "
                "by scene and horizon. *Best* is the smallest trajectory error of a run that "
                "reached T; failures list the return flag, the time reached and "
                "σ_min/σ_max of C_q = A_q R⁻¹ at the reference's configuration at that time "
                "(0 at a kinematic singularity).\n\n");
    for (int i = 0; i < np; i++) {
        const char *sc = pr[i].scene;
        const double T = pr[i].T;
        static const char *const ms[] = {"ida-ggl", "ida-index1"};
        int any = 0;
        for (long k = 0; k < d->n; k++)
            any |= cmp_row_at(&d->r[k], sc, T) && !strncmp(d->r[k].method, "ida", 3);
        if (!any) continue;
        fprintf(md, "**%s, T = %g s.** ", sc, T);
        for (int m = 0; m < 2; m++) {
            const cmp_row *w;
            double best = cmp_rows_best_method(d, sc, T, ms[m], 0, &w);
            int nf = 0, nrun = 0, at0 = 0, ontrack = 0, near = 0;
            for (long k = 0; k < d->n; k++) {
                const cmp_row *r = &d->r[k];
                if (!cmp_row_at(r, sc, T) || strcmp(r->method, ms[m]) != 0) continue;
                nrun++;
                if (r->ok) continue;
                nf++;
                if (!(r->t_reached > 1e-6 * T)) {
                    at0++;
                    continue;
                }
                /* σ at the reference's configuration says where the run was
                 * only while it followed the reference. */
                if (r->traj < 0.1) {
                    ontrack++;
                    near += r->sigma < 1e-2;
                }
            }
            if (!nrun) continue;
            if (w)
                fprintf(md,
                        "%s: best error %s (%s%s, %s s CPU, %ld steps, %ld residual "
                        "evaluations, %ld Jacobians); ",
                        ms[m], cmp_fmt_e(best, a), strcmp(w->variant, "-") ? "tuned, " : "",
                        cmp_fmt_param(w, c), cmp_fmt_e(w->cpu, b), w->steps, w->rhs, w->jac);
            else
                fprintf(md, "%s: no run reached T; ", ms[m]);
            fprintf(md, "%d of %d runs failed", nf, nrun);
            if (nf) {
                fprintf(md, " (%d at the start, t < 1e-6·T", at0);
                if (ontrack)
                    fprintf(md, "; of the %d that failed later while still on the reference "
                                "(error < 0.1), %d stopped within σ_min/σ_max < 0.01 of a "
                                "singular configuration", ontrack, near);
                fprintf(md, ")");
            }
            fprintf(md, ". ");
        }
        fprintf(md, "\n\n");
        fprintf(md, "| variant | rtol | status | t reached | σ_min/σ_max there | max ‖q−q_ref‖ | CPU [s] |\n");
        fprintf(md, "|---|---|---|---|---|---|---|\n");
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, sc, T) || strncmp(r->method, "ida", 3) != 0) continue;
            fprintf(md, "| %s%s | %s | %s | %.6g | %s | %s | %s |\n", r->method,
                    strcmp(r->variant, "-") ? " tuned" : "", cmp_fmt_e(r->rtol, a), r->status,
                    r->t_reached, cmp_fmt_e(r->sigma, b), cmp_fmt_e(r->traj, c),
                    cmp_fmt_e(r->cpu, e));
        }
        fprintf(md, "\n");
    }
}

static void probe_section(FILE *md, const char *dir)
{
    char path[1024], a[24], b[24], c[24];
    cmp_csv csv;
    cmp_rows d;
    snprintf(path, sizeof path, "%s/ida_probe.csv", dir);
    if (cmp_rows_load(path, &csv, &d) || d.n == 0) {
        free(d.r);
        cmp_csv_free(&csv);
        return;
    }
    fprintf(md, "### IDA: the settings probe\n\n");
    fprintf(md, "Each setting of `ida-ggl` on each scene's first horizon (one timing). A cell "
                "is the max trajectory error if the run reached T, else the flag and the time "
                "it stopped. *defaults*: λ, μ algebraic and out of the error test, their "
                "absolute tolerance equal to atol; *alg-atol=1e8*: λ, μ effectively out of the "
                "Newton convergence test too; *max-step*, *max-order*: IDASetMaxStep, "
                "IDASetMaxOrd; *cod*: the harness's rank-revealing linear solver "
                "(minimum-norm Newton corrections); *klu*: KLU with a sparse "
                "finite-difference Jacobian; *reg*: constraint rows regularised to Φ − ελ; "
                "*restart*: re-project and restart after a failure (≤ 100 times).\n\n");
    pair pr[64];
    int np = pairs_of(&d, pr, 64);
    for (int i = 0; i < np; i++) {
        double tols[16];
        int nt = 0;
        for (long k = 0; k < d.n; k++) {
            const cmp_row *r = &d.r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T)) continue;
            int seen = 0;
            for (int j = 0; j < nt; j++) seen |= tols[j] == r->rtol;
            if (!seen && nt < 16) tols[nt++] = r->rtol;
        }
        fprintf(md, "**%s, T = %g s**\n\n| setting |", pr[i].scene, pr[i].T);
        for (int j = 0; j < nt; j++) fprintf(md, " rtol %s |", cmp_fmt_e(tols[j], a));
        fprintf(md, "\n|---|");
        for (int j = 0; j < nt; j++) fprintf(md, "---|");
        fprintf(md, "\n");
        const char *last = "";
        for (long k = 0; k < d.n; k++) {
            const cmp_row *r = &d.r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T) || !strcmp(r->variant, last)) continue;
            last = r->variant;
            fprintf(md, "| %s |", r->variant);
            for (int j = 0; j < nt; j++) {
                const cmp_row *x = NULL;
                for (long q = 0; q < d.n; q++)
                    if (cmp_row_at(&d.r[q], pr[i].scene, pr[i].T) &&
                        !strcmp(d.r[q].variant, r->variant) && d.r[q].rtol == tols[j])
                        x = &d.r[q];
                if (!x) fprintf(md, " – |");
                else if (x->ok)
                    fprintf(md, " %s |", cmp_fmt_e(x->traj, b));
                else
                    fprintf(md, " %s at %s |", x->status, cmp_fmt_e(x->t_reached, c));
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
    free(d.r);
    cmp_csv_free(&csv);
}

/* Singular configurations and the multipliers beside them. */
static void singular_section(FILE *md, const char *dir)
{
    char path[1024], a[24], b[24], c[24], d[24];
    cmp_csv s;
    snprintf(path, sizeof path, "%s/singular.csv", dir);
    if (cmp_csv_read(path, &s) || s.nrows == 0) {
        cmp_csv_free(&s);
        return;
    }
    const int cs = cmp_csv_col(&s, "scene"), ct = cmp_csv_col(&s, "theta_star"),
              cd = cmp_csv_col(&s, "delta"), cl = cmp_csv_col(&s, "lambda_max"),
              cf = cmp_csv_col(&s, "force_max"), cr = cmp_csv_col(&s, "sigma_ratio");
    fprintf(md, "### Why: the multipliers at the singular configurations\n\n");
    fprintf(md, "The harness scans each paper scene's minimal angle over one turn for "
                "configurations where the constraint rows lose rank, and evaluates the "
                "minimum-norm Lagrange multipliers λ (θ' = 1 rad/s) at distance δ from them. "
                "The slope is d log max|λ| / d log δ between δ = 1e-3 and 1e-6 (−1: a pole "
                "λ ~ 1/δ).\n\n");
    fprintf(md, "| scene | θ* [rad] | σ_min/σ_max at δ = 1e-6 | max|λ| at δ = 1e-3 | at δ = 1e-6 | slope | max|A_qᵀλ| at δ = 1e-6 |\n");
    fprintf(md, "|---|---|---|---|---|---|---|\n");
    for (long k = 0; k < s.nrows; k++) {
        if (fabs(cmp_csv_num(&s, k, cd) - 1e-3) > 1e-9) continue;
        long k6 = -1;
        for (long j = k; j < s.nrows && j < k + 7; j++)
            if (fabs(cmp_csv_num(&s, j, cd) - 1e-6) < 1e-12 &&
                !strcmp(cmp_csv_str(&s, j, cs), cmp_csv_str(&s, k, cs)))
                k6 = j;
        if (k6 < 0) continue;
        double l3 = cmp_csv_num(&s, k, cl), l6 = cmp_csv_num(&s, k6, cl);
        double slope = log(l6 / l3) / log(1e-6 / 1e-3);
        fprintf(md, "| %s | %.6f | %s | %s | %s | %.2f | %s |\n", cmp_csv_str(&s, k, cs),
                cmp_csv_num(&s, k, ct), cmp_fmt_e(cmp_csv_num(&s, k6, cr), a), cmp_fmt_e(l3, b),
                cmp_fmt_e(l6, c), slope, cmp_fmt_e(cmp_csv_num(&s, k6, cf), d));
    }
    fprintf(md, "\nWhere the slope is near −1 the multipliers have a pole at the singular "
                "configuration while the constraint force A_qᵀλ stays finite: any formulation "
                "that carries λ as an unknown (GGL, index-1) asks IDA's Newton iteration and "
                "step-size control to follow a function that goes to infinity, and the "
                "corrector fails once the steps come close to it — the tighter the "
                "tolerance, the closer. Where λ stays bounded (slope near 0) the rows still "
                "lose rank, the Newton matrix is singular at θ*, and the failures are the "
                "linear algebra's. The pseudoinverse of Eqs. 16-17 needs neither λ nor a "
                "nonsingular matrix.\n\n");
    cmp_csv_free(&s);
}


/* ------------------------------------------------------------ Baumgarte */
static void baumgarte_section(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    char a[24], b[24], c[24];
    int any = 0, rows_ranked = 0, rows_none = 0, default_best = 0, default_tied = 0;
    for (long k = 0; k < d->n; k++) any |= !strcmp(d->r[k].method, "baumgarte") && strcmp(d->r[k].variant, "-");
    if (!any) return;
    fprintf(md, "### Baumgarte: the gains\n\n");
    fprintf(md, "The study's Baumgarte uses α = β (critical damping of Φ̈ + 2αΦ̇ + β²Φ = 0, "
                "the error decays as e^{−αt}) with α = 0.1/h (how it fares against the other "
                "gains is counted below the table). Ascher, Chin & Reich (1994) show the gains must scale with "
                "the step of an explicit method: α·h of order one or less, inside RK4's "
                "stability interval. The sweep: α = β = c/h for c = 0.03, 0.1 (default), 0.3, "
                "1, and α = β = 10 s⁻¹ fixed.\n\n");
    fprintf(md, "| scene | T | h | c = 0.03 | 0.1 | 0.3 | 1 | α = 10 |\n|---|---|---|---|---|---|---|---|\n");
    static const char *const vs[] = {"ab=0.03/h", "-", "ab=0.3/h", "ab=1/h", "ab=10"};
    for (int i = 0; i < np; i++) {
        double hs[8];
        int nh = 0;
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T) || strcmp(r->method, "baumgarte") ||
                !strcmp(r->variant, "-"))
                continue;
            int seen = 0;
            for (int j = 0; j < nh; j++) seen |= hs[j] == r->h;
            if (!seen && nh < 8) hs[nh++] = r->h;
        }
        for (int j = 0; j < nh; j++) {
            fprintf(md, "| %s | %g | %s |", pr[i].scene, pr[i].T, cmp_fmt_e(hs[j], a));
            /* The most accurate gain of the row (of the runs that reached T),
             * in bold; the default's standing is counted, not asserted. */
            const cmp_row *rv[5];
            double best = INFINITY;
            for (int v = 0; v < 5; v++) {
                rv[v] = cmp_rows_fixed(d, pr[i].scene, pr[i].T, "baumgarte", "rk4", vs[v], hs[j]);
                if (rv[v] && rv[v]->ok && rv[v]->traj < best) best = rv[v]->traj;
            }
            int top[5], ntop = 0; /* within 1 % of the row's best */
            for (int v = 0; v < 5; v++) {
                top[v] = rv[v] && rv[v]->ok && isfinite(best) && rv[v]->traj <= 1.01 * best;
                ntop += top[v];
            }
            for (int v = 0; v < 5; v++) {
                const cmp_row *r = rv[v];
                if (!r) fprintf(md, " – |");
                else if (r->ok)
                    fprintf(md, top[v] ? " **%s** |" : " %s |", cmp_fmt_e(r->traj, b));
                else
                    fprintf(md, " %s at t = %s |", r->status, cmp_fmt_e(r->t_reached, c));
            }
            fprintf(md, "\n");
            if (!isfinite(best)) {
                rows_none++;
                continue;
            }
            rows_ranked++;
            if (top[1]) { /* the default, 0.1/h */
                if (ntop == 1) default_best++;
                else default_tied++;
            }
        }
    }
    fprintf(md, "\nCells: max ‖q − q_ref‖ of runs that reached T, else how they stopped; in "
                "bold the most accurate of each row (within 1 %%).\n\n");
    fprintf(md, "The default, α = β = 0.1/h, is the most accurate gain alone in %d of the %d "
                "rows where a gain reached T and tied for it in %d; in the other %d a gain the "
                "comparison does not use is more accurate, so the main tables show Baumgarte at "
                "a gain that is not its best there.",
            default_best, rows_ranked, default_tied, rows_ranked - default_best - default_tied);
    if (rows_none) fprintf(md, " In %d row%s every gain failed.", rows_none, rows_none == 1 ? "" : "s");
    fprintf(md, "\n\n");
}

/* ------------------------------------------------------------ summary */
/* The methods of the comparison in the order of the tables, then any other
 * method of the series table. */
static int methods_of(const char **ms, int max)
{
    static const char *const order[] = {"braun",      "braun-noenergy", "baumgarte", "ida-ggl",
                                        "ida-index1", "ode-rk4",        "projection", "mujoco",
                                        "simbody"};
    int nm = 0;
    for (size_t m = 0; m < sizeof order / sizeof order[0] && nm < max; m++) ms[nm++] = order[m];
    for (int i = 0; i < cmp_series_count && nm < max; i++) {
        int seen = 0;
        for (int m = 0; m < nm; m++) seen |= !strcmp(ms[m], cmp_series_table[i].method);
        if (!seen) ms[nm++] = cmp_series_table[i].method;
    }
    return nm;
}

static const char *method_words(const char *m)
{
    static const struct {
        const char *m, *w;
    } w[] = {
        {"braun", "braun (Eqs. 16, 17, 20)"},
        {"braun-noenergy", "braun without energy correction"},
        {"baumgarte", "Baumgarte (gain sweep)"},
        {"ida-ggl", "IDA GGL"},
        {"ida-index1", "IDA index-1"},
        {"ode-rk4", "minimal-coordinate ODE, RK4"},
        {"projection", "RK4 + coordinate projection"},
        {"mujoco", "MuJoCo 2.2.2 (every setting)"},
        {"simbody", "Simbody 3.7 (every setting)"},
    };
    for (size_t i = 0; i < sizeof w / sizeof w[0]; i++)
        if (!strcmp(w[i].m, m)) return w[i].w;
    return m;
}

/* Why a method has no run on a scene: "not built", "cannot express it: …". */
static const char *notrun_reason(const cmp_rows *d, const char *scene, double T, const char *m)
{
    static char buf[192];
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (!cmp_row_at(r, scene, T) || strcmp(r->method, m) || !r->notrun) continue;
        if (!strcmp(r->status, "NOT_BUILT")) return "not built into this harness";
        /* detail: "at t = 0 (REASON)" */
        const char *p = strchr(r->detail, '(');
        snprintf(buf, sizeof buf, "cannot express this scene: %.150s", p ? p + 1 : r->detail);
        const size_t l = strlen(buf);
        if (p && l && buf[l - 1] == ')') buf[l - 1] = '\0';
        return buf;
    }
    return NULL;
}

/* The headline: the four-bar over 1000 s, every method within braun's CPU
 * time (RK4, h = 1e-2) and at any cost. */
static void headline(FILE *md, const cmp_rows *d, const char *sc, double T)
{
    char a[32], b[24], c[48], e[32], g[24];
    const cmp_row *ref = cmp_rows_fixed(d, sc, T, "braun", "rk4", "-", 1e-2);
    if (!ref) return;
    const double B = ref->cpu;
    fprintf(md, "**%s over %g s.** braun with RK4 at the paper's h = 1e-2 takes %s s of CPU and "
                "%s with a maximum trajectory error of %s [%s]. The smallest error each "
                "method reaches on a run that gets to %g s, within that CPU time and at any "
                "cost (the reference's own error is %s; † marks errors below it):\n\n",
            sc, T, cmp_fmt_e(B, b), ref->ok ? "reaches T" : ref->status,
            fmt_err(d, sc, T, ref->traj, a), q_unit(d, sc, T), T,
            cmp_fmt_e(floor_of(d, sc, T), g));
    fprintf(md, "| method | best error within %s s | that run | CPU [s] | best error at any cost "
                "| that run | CPU [s] |\n|---|---|---|---|---|---|---|\n",
            cmp_fmt_e(B, b));
    const char *ms[64];
    const int nm = methods_of(ms, 64);
    for (int m = 0; m < nm; m++) {
        int any = 0;
        for (long k = 0; k < d->n; k++)
            any |= cmp_row_at(&d->r[k], sc, T) && !strcmp(d->r[k].method, ms[m]);
        if (!any) continue;
        const char *why = notrun_reason(d, sc, T, ms[m]);
        int ran = 0;
        for (long k = 0; k < d->n; k++)
            ran |= cmp_row_at(&d->r[k], sc, T) && !strcmp(d->r[k].method, ms[m]) && !d->r[k].notrun;
        if (!ran) {
            fprintf(md, "| %s | – (%s) | | | | | |\n", method_words(ms[m]), why ? why : "no run");
            continue;
        }
        const cmp_row *w, *wa;
        const double eb = cmp_rows_best_method(d, sc, T, ms[m], B * 1.0001, &w);
        const double ea = cmp_rows_best_method(d, sc, T, ms[m], 0, &wa);
        char p1[48], p2[48], l1[200], l2[200];
        if (w) snprintf(l1, sizeof l1, "%s, %s", label_of(w), cmp_fmt_param(w, p1));
        if (wa) snprintf(l2, sizeof l2, "%s, %s", label_of(wa), cmp_fmt_param(wa, p2));
        /* No run within the budget: say why — none reached T, or those
         * that did took longer than braun. */
        fprintf(md, "| %s | %s | %s | %s | %s | %s | %s |\n", method_words(ms[m]),
                w    ? fmt_err(d, sc, T, eb, a)
                : wa ? "no run that reached T within this CPU time"
                     : "no run reached T",
                w ? l1 : "",
                w ? cmp_fmt_e(w->cpu, b) : "", wa ? fmt_err(d, sc, T, ea, e) : "no run reached T",
                wa ? l2 : "", wa ? cmp_fmt_e(wa->cpu, g) : "");
    }
    fprintf(md, "\n");
    (void)c;
}

/* Cost per step against MuJoCo (step_cost.csv). */
static void cost_table(FILE *md, const cmp_rows *d, int brief)
{
    if (!d->ncost) return;
    const char *scenes[8];
    int ns = 0;
    for (long k = 0; k < d->ncost && ns < 8; k++) {
        int seen = 0;
        for (int i = 0; i < ns; i++) seen |= !strcmp(scenes[i], d->cost[k].scene);
        if (!seen) scenes[ns++] = d->cost[k].scene;
    }
    if (brief) {
        fprintf(md, "**Cost per step against MuJoCo** (one process, h = 1e-2, best of three "
                    "rounds of 20000 steps each): ");
        for (int i = 0; i < ns; i++) {
            const double b = cmp_rows_cost(d, scenes[i], "braun", "rk4"),
                         m = cmp_rows_cost(d, scenes[i], "mujoco", "mj-rk4");
            fprintf(md, "%s%s: braun's corrected RK4 step %.3g µs, MuJoCo's RK4 mj_step %.3g µs "
                        "(braun / MuJoCo = %.2g)",
                    i ? "; " : "", scenes[i], 1e6 * b, 1e6 * m, b / m);
        }
        fprintf(md, ".\n\n");
        return;
    }
    fprintf(md, "| scene | method | integrator | h [s] | CPU per step [µs] |\n|---|---|---|---|---|\n");
    for (long k = 0; k < d->ncost; k++) {
        const cmp_cost *c = &d->cost[k];
        const char *who = !strcmp(c->method, "mujoco") ? "MuJoCo 2.2.2 mj_step (the main series' settings)"
                          : !strcmp(c->method, "projection") ? "RK4 + coordinate projection"
                                                              : method_words(c->method);
        fprintf(md, "| %s | %s | %s | %g | %.3g |\n", c->scene, who, c->integ, c->h,
                1e6 * c->per_step);
    }
    fprintf(md, "\n");
}

/* Most accurate method within each CPU budget, every scene: one table. */
static void budgets_table(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    char a[32], c[48], e[24];
    fprintf(md, "**Most accurate method within each CPU budget** (runs that reached T; † below "
                "the reference's own error):\n\n| scene, T |");
    for (int k = 0; k < NBUDGETS; k++) fprintf(md, " ≤ %s s |", cmp_fmt_e(BUDGETS[k], e));
    fprintf(md, "\n|---|");
    for (int k = 0; k < NBUDGETS; k++) fprintf(md, "---|");
    fprintf(md, "\n");
    for (int i = 0; i < np; i++) {
        fprintf(md, "| %s, %g s |", pr[i].scene, pr[i].T);
        for (int k = 0; k < NBUDGETS; k++) {
            const cmp_row *w = best_within(d, pr[i].scene, pr[i].T, BUDGETS[k], NULL);
            if (!w) fprintf(md, " – |");
            else
                fprintf(md, " %s (%s): %s |", label_of(w), cmp_fmt_param(w, c),
                        fmt_err(d, pr[i].scene, pr[i].T, w->traj, a));
        }
        fprintf(md, "\n");
    }
    fprintf(md, "\n");
}

/* braun's own runs that stopped: counted for the summary. */
static int braun_failures(const cmp_rows *d, int *adaptive)
{
    int n = 0;
    *adaptive = 0;
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (strncmp(r->method, "braun", 5) != 0 || r->ok) continue;
        n++;
        *adaptive += !strcmp(r->integ, "dopri5");
    }
    return n;
}

static void summary(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    fprintf(md, "## Summary\n\n");
    /* The headline: the longest horizon of the four-bar (the paper's
     * Figs. 6-7), else of the first scene. */
    const char *sc = "four-bar";
    double T = 0;
    for (int i = 0; i < np; i++)
        if (!strcmp(pr[i].scene, sc) && pr[i].T > T) T = pr[i].T;
    if (T > 0) headline(md, d, sc, T);
    cost_table(md, d, 1);
    budgets_table(md, d, pr, np);
    int confirmed = 0, refuted = 0, open = 0;
    char refuted_list[1024] = "";
    for (int i = 0; i < cmp_nclaims; i++) {
        cmp_fig f;
        char evidence[2048];
        const int v = cmp_claim_eval(&cmp_claims[i], d, &f, evidence, sizeof evidence);
        confirmed += v > 0;
        open += v == 0;
        if (v < 0) {
            refuted++;
            const size_t l = strlen(refuted_list);
            snprintf(refuted_list + l, sizeof refuted_list - l, "%s“%s”", l ? "; " : "",
                     cmp_claims[i].claim);
        }
    }
    fprintf(md, "**The claims** (section below): %d confirmed, %d refuted, %d not tested%s%s%s\n\n",
            confirmed, refuted, open, refuted ? ". Refuted: " : ".", refuted_list,
            refuted ? "." : "");
    int adaptive = 0;
    const int nf = braun_failures(d, &adaptive);
    if (nf)
        fprintf(md, "**braun's own failures:** %d runs of libbraun did not reach T (%d of them "
                    "with the adaptive DOPRI5 driver); each is listed in “braun's own failures” "
                    "below.\n\n",
                nf, adaptive);
    else
        fprintf(md, "**braun's own failures:** none — every libbraun run reached T.\n\n");
}

/* ------------------------------------------------------------ work-precision */
/* What a work-precision plot leaves out: per series, the runs that did not
 * reach T; the peers that did not run. */
static void wp_caption(FILE *md, const cmp_rows *d, const char *sc, double T)
{
    char a[24], b[24];
    int any = 0;
    for (int s = 0; s < cmp_series_count; s++) {
        int n = 0, f = 0;
        char first[160] = "";
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, sc, T) || !cmp_row_in(r, &cmp_series_table[s]) || r->notrun) continue;
            n++;
            if (r->ok) continue;
            if (!f++) {
                char p[48];
                snprintf(first, sizeof first, "%s: %s at t = %s s", cmp_fmt_param(r, p), r->status,
                         cmp_fmt_g(r->t_reached, a));
            }
        }
        if (!f) continue;
        fprintf(md, "%s%s: %d of %d (first: %s)", any++ ? "; " : "*Not drawn — runs that did not "
                                                                 "reach T:* ",
                cmp_series_table[s].label, f, n, first);
    }
    if (any) fprintf(md, ".");
    const char *ms[] = {"mujoco", "simbody"};
    for (int m = 0; m < 2; m++) {
        const char *why = notrun_reason(d, sc, T, ms[m]);
        int ran = 0;
        for (long k = 0; k < d->n; k++)
            ran |= cmp_row_at(&d->r[k], sc, T) && !strcmp(d->r[k].method, ms[m]) && !d->r[k].notrun;
        if (why && !ran) fprintf(md, " %s: %s.", method_words(ms[m]), why);
    }
    const double fl = floor_of(d, sc, T);
    if (!isnan(fl))
        fprintf(md, " Dotted grey line: the reference's own error (%s, %s).",
                cmp_rows_target(d, sc, T)->reference, cmp_fmt_e(fl, b));
    fprintf(md, "\n\n");
}

/* The IFToMM benchmark's section (issue 13): make iftomm writes it beside
 * this directory (results/iftomm/report-section.md, its image paths
 * relative to results/compare/ as well); the report includes what is there. */
static void iftomm_section(FILE *md, const char *dir)
{
    char path[1024], buf[4096];
    snprintf(path, sizeof path, "%s/../iftomm/report-section.md", dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(md, "## IFToMM benchmark problems A01-A05\n\n"
                    "Not in this report: `make iftomm` (tens of minutes) writes "
                    "results/iftomm/report-section.md, and the next report includes it.\n\n");
        return;
    }
    size_t k;
    while ((k = fread(buf, 1, sizeof buf, f)) > 0) fwrite(buf, 1, k, md);
    fclose(f);
    fprintf(md, "\n");
}

static void wp_section(FILE *md, const char *dir, const cmp_rows *d, const pair *pr, int np)
{
    fprintf(md, "## Work–precision: every method on every scene\n\n"
                "Trajectory error max_t ‖q − q_ref‖ against CPU time for every method and "
                "setting series, the peers included; each point is a run that reached T, its CPU "
                "time the best of k repetitions in one process (peers: their integration alone). "
                "The legend names the series with runs that stopped; the caption lists them.\n\n");
    for (int i = 0; i < np; i++) {
        char name[160];
        fprintf(md, "### %s, T = %g s\n\n", pr[i].scene, pr[i].T);
        snprintf(name, sizeof name, "wp_%s_%g", pr[i].scene, pr[i].T);
        figure(md, dir, name, "work-precision: trajectory error against CPU time");
        wp_caption(md, d, pr[i].scene, pr[i].T);
    }
}

/* ------------------------------------------------------------ Fig. 6 */
static void fig6_section(FILE *md, const char *dir, const cmp_rows *d, const pair *pr, int np)
{
    double T = 0;
    for (int i = 0; i < np; i++)
        if (!strcmp(pr[i].scene, "four-bar") && pr[i].T > T) T = pr[i].T;
    char name[96], a[128], b[32];
    snprintf(name, sizeof name, "fig6_four-bar_%g", T);
    snprintf(a, sizeof a, "%s.png", name);
    if (T <= 0 || !file_exists(dir, a)) return;
    (void)b;
    fprintf(md, "## The paper's Fig. 6: the four-bar over %g s\n\n", T);
    figure(md, dir, name, "x3 of the four-bar against time (the paper's Fig. 6)");
    fprintf(md, "x₃ of joint 3 over the first and the last 10 s (or halves of shorter runs), "
                "against the closed form. At h = 1e-2: ");
    static const char *const keys[][3] = {{"braun", "rk4", "-"},
                                          {"braun-noenergy", "rk4", "-"},
                                          {"baumgarte", "rk4", "-"},
                                          {"ode-rk4", "rk4", "-"},
                                          {"projection", "rk4", "-"}};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        const cmp_row *r = cmp_rows_fixed(d, "four-bar", T, keys[k][0], keys[k][1], keys[k][2], 1e-2);
        if (!r) continue;
        const cmp_series *s = cmp_series_of(keys[k][0], keys[k][1], keys[k][2]);
        fprintf(md, "%s%s ", k ? "; " : "", s ? s->label : keys[k][0]);
        if (r->ok)
            fprintf(md, "max ε = %s m", cmp_fmt_e(r->point, a));
        else
            fprintf(md, "**stopped** (%s at t = %s s)", r->status, cmp_fmt_g(r->t_reached, a));
    }
    fprintf(md, ". The peers: each one's most accurate run that reached T (if none did, the one "
                "that got furthest) — the legend says which setting.\n\n");
}

/* ------------------------------------------------------------ peers */
/* Which scenes each peer ran on, and why not on the others. */
static void coverage(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    /* Every scene and horizon: one row per scene showed its first horizon
     * only, and hid the 1000 s runs that stopped (Simbody 4 of 18). */
    fprintf(md, "| scene | T [s] | MuJoCo 2.2.2 | Simbody 3.7 | RK4 + projection |\n"
                "|---|---|---|---|---|\n");
    for (int i = 0; i < np; i++) {
        fprintf(md, "| %s | %g |", pr[i].scene, pr[i].T);
        const char *ms[] = {"mujoco", "simbody", "projection"};
        for (int m = 0; m < 3; m++) {
            int n = 0, ok = 0, ran = 0;
            for (long k = 0; k < d->n; k++) {
                const cmp_row *r = &d->r[k];
                if (!cmp_row_at(r, pr[i].scene, pr[i].T) || strcmp(r->method, ms[m])) continue;
                n++;
                ran += !r->notrun;
                ok += r->ok;
            }
            const char *why = notrun_reason(d, pr[i].scene, pr[i].T, ms[m]);
            if (!n) fprintf(md, " not run |");
            else if (!ran) fprintf(md, " %s |", why ? why : "–");
            else fprintf(md, " %d runs, %d reached T |", ran, ok);
        }
        fprintf(md, "\n");
    }
    fprintf(md, "\n");
}

/* A sweep table: rows are settings (variant), columns step sizes, one per
 * scene and horizon where the method ran its sweep. */
static void sweep_table(FILE *md, const cmp_rows *d, const pair *pr, int np, const char *method,
                        const char *integ)
{
    char a[32], c[24];
    for (int i = 0; i < np; i++) {
        double hs[8];
        int nh = 0, nv = 0;
        const char *vars[32];
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T) || strcmp(r->method, method) ||
                strcmp(r->integ, integ) || r->notrun || isnan(r->h))
                continue;
            int seen = 0;
            for (int v = 0; v < nv; v++) seen |= !strcmp(vars[v], r->variant);
            if (!seen && nv < 32) vars[nv++] = r->variant;
            if (!strcmp(r->variant, "-") || !strcmp(r->variant, "defaults")) continue;
            seen = 0;
            for (int j = 0; j < nh; j++) seen |= hs[j] == r->h;
            if (!seen && nh < 8) hs[nh++] = r->h;
        }
        if (!nh || nv < 3) continue;
        fprintf(md, "**%s, T = %g s** (max ‖q − q_ref‖ [%s] of runs that reached T, else how they "
                    "stopped)\n\n| setting |",
                pr[i].scene, pr[i].T, q_unit(d, pr[i].scene, pr[i].T));
        for (int j = 0; j < nh; j++) fprintf(md, " h = %s |", cmp_fmt_e(hs[j], c));
        fprintf(md, "\n|---|");
        for (int j = 0; j < nh; j++) fprintf(md, "---|");
        fprintf(md, "\n");
        for (int v = 0; v < nv; v++) {
            fprintf(md, "| %s |", strcmp(vars[v], "-") ? cmp_variant_text(vars[v])
                                                      : "the main series: solref 2h, ζ = 0.25, d = 0.9999");
            for (int j = 0; j < nh; j++) {
                const cmp_row *r = cmp_rows_fixed(d, pr[i].scene, pr[i].T, method, integ, vars[v], hs[j]);
                if (!r) fprintf(md, " – |");
                else if (r->ok) fprintf(md, " %s |", fmt_err(d, pr[i].scene, pr[i].T, r->traj, a));
                else fprintf(md, " %s at t = %s |", r->status, cmp_fmt_g(r->t_reached, c));
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
}

/* Simbody: each integrator against the accuracy, per scene and horizon. */
static void simbody_table(FILE *md, const cmp_rows *d, const pair *pr, int np)
{
    char a[32], c[24];
    for (int i = 0; i < np; i++) {
        int any = 0;
        for (long k = 0; k < d->n; k++)
            any |= cmp_row_at(&d->r[k], pr[i].scene, pr[i].T) && !strcmp(d->r[k].method, "simbody") &&
                   !d->r[k].notrun;
        if (!any) continue;
        double tols[16];
        int nt = 0;
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T) || strcmp(r->method, "simbody") || isnan(r->rtol) ||
                !isnan(r->h))
                continue;
            int seen = 0;
            for (int j = 0; j < nt; j++) seen |= tols[j] == r->rtol;
            if (!seen && nt < 16) tols[nt++] = r->rtol;
        }
        fprintf(md, "**%s, T = %g s**\n\n| integrator, setting |", pr[i].scene, pr[i].T);
        for (int j = 0; j < nt; j++) fprintf(md, " accuracy %s |", cmp_fmt_e(tols[j], c));
        fprintf(md, "\n|---|");
        for (int j = 0; j < nt; j++) fprintf(md, "---|");
        fprintf(md, "\n");
        const char *last_i = "", *last_v = "";
        for (long k = 0; k < d->n; k++) {
            const cmp_row *r = &d->r[k];
            if (!cmp_row_at(r, pr[i].scene, pr[i].T) || strcmp(r->method, "simbody") || !isnan(r->h) ||
                (!strcmp(r->integ, last_i) && !strcmp(r->variant, last_v)))
                continue;
            last_i = r->integ;
            last_v = r->variant;
            fprintf(md, "| %s%s%s |", r->integ, strcmp(r->variant, "-") ? ", " : "",
                    cmp_variant_text(r->variant));
            for (int j = 0; j < nt; j++) {
                const cmp_row *x = NULL;
                for (long q = 0; q < d->n; q++) {
                    const cmp_row *y = &d->r[q];
                    if (cmp_row_at(y, pr[i].scene, pr[i].T) && !strcmp(y->method, "simbody") &&
                        !strcmp(y->integ, r->integ) && !strcmp(y->variant, r->variant) &&
                        y->rtol == tols[j] && isnan(y->h))
                        x = y;
                }
                if (!x) fprintf(md, " – |");
                else if (x->ok) fprintf(md, " %s |", fmt_err(d, pr[i].scene, pr[i].T, x->traj, a));
                else fprintf(md, " %s at t = %s |", x->status, cmp_fmt_g(x->t_reached, c));
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
}

static void peers_section(FILE *md, const cmp_rows *d, const pair *pr, int np, const meta *m)
{
    fprintf(md, "## The peers: what a user would pick instead\n\n");
    fprintf(md, "**MuJoCo** %s (Debian `libmujoco-dev`) through its C API, on an MJCF model the "
                "harness writes from the scene (a kinematic tree of hinge and slide joints, loops "
                "closed by `connect` and `tendon` equalities; `compare/cmp_mujoco.c`); its "
                "equalities are soft: solref (time constant, damping ratio ζ) and the impedance "
                "d of solimp set them. **Simbody** 3.7 (`libsimbody-dev`) through a C++ adapter "
                "(`compare/cmp_simbody.cpp`; in this build: %s). **RK4 + coordinate projection** (Eich 1993; "
                "Hairer–Wanner II §VII.2): RK4 on the index-1 equation, then a mass-orthogonal "
                "Gauss–Newton projection of q onto Φ_q = 0 and of v onto the velocity rows "
                "after every step (`compare/cmp_proj.c`). Each starts from the same q0, v0 and is "
                "measured on the same grid against the same reference.\n\n",
            m->mujoco[0] ? m->mujoco : "2.2.2", m->simbody[0] ? m->simbody : "?");
    fprintf(md, "### What each can express\n\n");
    coverage(md, d, pr, np);
    fprintf(md, "### Cost per step\n\n");
    cost_table(md, d, 0);
    fprintf(md, "### Simbody: integrators against accuracy\n\n");
    int any = 0;
    for (long k = 0; k < d->n; k++) any |= !strcmp(d->r[k].method, "simbody") && !d->r[k].notrun;
    int rows = 0;
    for (long k = 0; k < d->n; k++) rows += !strcmp(d->r[k].method, "simbody");
    if (any) simbody_table(md, d, pr, np);
    else if (!rows) /* not asked for (--methods) */
        fprintf(md, "This study ran no Simbody run (not among its methods).\n\n");
    else
        fprintf(md, "No Simbody run ran: every row says `%s`. The study plans Simbody's sweep "
                    "(RK-Merson, RK-Feldberg, RK3, CPodes at each accuracy of the grid; "
                    "RK-Merson at each fixed step; constraint tolerances 1e-10 and 1e-3 on the "
                    "first horizon) as soon as the adapter runs.\n\n",
                notrun_reason(d, pr[0].scene, pr[0].T, "simbody") ? "NOT_BUILT" : "–");
}

/* ------------------------------------------------------------ references */
static void references_section(FILE *md, const char *dir, const cmp_rows *d)
{
    char path[1024], a[24], b[24], c[24];
    cmp_csv s;
    fprintf(md, "## References and their own error\n\n");
    fprintf(md, "No reference is computed with libbraun. The paper's scenes (and the pendulum) "
                "are compared with the closed form of their minimal equation (Jacobi elliptic "
                "functions) or GSL's rk8pd on it at rtol = atol = 1e-13; scenes the harness can "
                "write a minimal equation for (open chains, the parallelogram: "
                "`compare/cmp_minimal.c`) with rk8pd on it; the others with the harness's RK4 + "
                "projection at a step of 2.5e-5 (scaled with the scene). Each reference's own "
                "error is estimated by the same reference at a looser setting (row *own-error*: "
                "rk8pd at 1e-12, the projection at twice its step); it is the floor of the plots "
                "and the † of the tables. Cross-checks against independent methods (IDA GGL at "
                "rtol 1e-10 on the harness's DAE, RK4 + projection, the test set's published "
                "point) are listed too.\n\n");
    if (d->ntgt) {
        fprintf(md, "| scene | T | reference | its own error max ‖Δq‖ [q's units] | of the point "
                    "[m] | minimal equation |\n|---|---|---|---|---|---|\n");
        for (long k = 0; k < d->ntgt; k++) {
            const cmp_tgt *t = &d->tgt[k];
            fprintf(md, "| %s | %g | %s | %s | %s | %s |\n", t->scene, t->T, t->reference,
                    cmp_fmt_e(t->floor_traj, a), cmp_fmt_e(t->floor_point, b),
                    strcmp(t->minimal, "-") ? t->minimal : "");
        }
        fprintf(md, "\n");
    }
    snprintf(path, sizeof path, "%s/references.csv", dir);
    if (cmp_csv_read(path, &s)) return;
    fprintf(md, "| scene | T | reference | compared with | max ‖Δq‖ | role | note |\n"
                "|---|---|---|---|---|---|---|\n");
    const int c0 = cmp_csv_col(&s, "scene"), c1 = cmp_csv_col(&s, "T"),
              c2 = cmp_csv_col(&s, "reference"), c3 = cmp_csv_col(&s, "tol"),
              c4 = cmp_csv_col(&s, "compared_with"), c5 = cmp_csv_col(&s, "tol2"),
              c6 = cmp_csv_col(&s, "max_q_diff"), c7 = cmp_csv_col(&s, "note"),
              c8 = cmp_csv_col(&s, "role");
    for (long k = 0; k < s.nrows; k++) {
        double t1 = cmp_csv_num(&s, k, c3), t2 = cmp_csv_num(&s, k, c5);
        fprintf(md, "| %s | %s | %s%s%s | %s%s%s | %s | %s | %s |\n", cmp_csv_str(&s, k, c0),
                cmp_csv_str(&s, k, c1), cmp_csv_str(&s, k, c2), isnan(t1) ? "" : " ",
                isnan(t1) ? "" : cmp_fmt_e(t1, a), cmp_csv_str(&s, k, c4), isnan(t2) ? "" : " ",
                isnan(t2) ? "" : cmp_fmt_e(t2, b), cmp_fmt_e(cmp_csv_num(&s, k, c6), c),
                cmp_csv_str(&s, k, c8),
                strcmp(cmp_csv_str(&s, k, c7), "-") ? cell(cmp_csv_str(&s, k, c7)) : "");
    }
    fprintf(md, "\n");
    cmp_csv_free(&s);
}

/* ------------------------------------------------------------ failures */
static void library_failures(FILE *md, const cmp_rows *d)
{
    int n = 0;
    fprintf(md, "## braun's own failures\n\n");
    for (long k = 0; k < d->n; k++) {
        const cmp_row *r = &d->r[k];
        if (strncmp(r->method, "braun", 5) != 0 || r->ok) continue;
        if (!n++)
            fprintf(md, "Every run of libbraun that did not reach T. Each is a failure of the "
                        "run, whatever the method: a fixed-step run that diverged (`DIVERGED`, "
                        "`ACCURACY`: the accuracy guard stopped it) or an adaptive run whose "
                        "step size collapsed (`STEP_TOO_SMALL`). σ_min/σ_max of the reference's "
                        "configuration where it stopped tells whether that was near a kinematic "
                        "singularity (0: singular).\n\n"
                        "| scene | T | run | status | t reached [s] | σ_min/σ_max there | max "
                        "‖q−q_ref‖ until then | where |\n|---|---|---|---|---|---|---|---|\n");
        char c[48], a[24], b[24];
        fprintf(md, "| %s | %g | %s, %s | **%s** | %.6g | %s | %s | %s |\n", r->scene, r->T,
                label_of(r), cmp_fmt_param(r, c), r->status, r->t_reached, cmp_fmt_e(r->sigma, a),
                cmp_fmt_e(r->traj, b), strcmp(r->detail, "-") ? cell(r->detail) : "");
    }
    if (!n) fprintf(md, "None: every libbraun run of the study reached T.\n");
    fprintf(md, "\n");
}

/* ------------------------------------------------------------ main */
int cmp_report_write(const char *dir)
{
    char path[1024];
    cmp_csv csv, cost_csv, tgt_csv;
    cmp_rows d;
    snprintf(path, sizeof path, "%s/runs.csv", dir);
    if (cmp_rows_load(path, &csv, &d)) {
        fprintf(stderr, "braun-compare: cannot read %s\n", path);
        free(d.r);
        return 1;
    }
    cmp_rows_load_extra(dir, &cost_csv, &tgt_csv, &d);
    meta m;
    read_meta(dir, &m);
    snprintf(path, sizeof path, "%s/report.md", dir);
    FILE *md = fopen(path, "w");
    if (!md) {
        fprintf(stderr, "braun-compare: cannot write %s\n", path);
        free(d.r);
        free(d.cost);
        free(d.tgt);
        cmp_csv_free(&csv);
        cmp_csv_free(&cost_csv);
        cmp_csv_free(&tgt_csv);
        return 1;
    }
    pair pr[64];
    const int np = pairs_of(&d, pr, 64);

    fprintf(md, "# libbraun against what users would pick instead\n\n");
    fprintf(md, "Generated by `make compare` (`braun-compare report`) from the CSV files in "
                "this directory; every number below is computed from them. Study `%s`, %s; "
                "CPU time is the best of %s repetitions in one process (runs of 2·10⁵ steps and "
                "more, and sweep cells, once); one process per run, %s%s, on %s (%s "
                "cores); SUNDIALS %s, GSL %s, MuJoCo %s, Simbody %s (its LAPACK: %s). The runs took %.0f s of wall "
                "time, the plots %.0f s. What each method and column is: docs/compare.md.\n\n",
            m.study[0] ? m.study : "?", m.date[0] ? m.date : "?", m.reps[0] ? m.reps : "?",
            m.jobs[0] ? m.jobs : "?",
            !strcmp(m.jobs, "exported") ? " as a run list (compare/run.sh --list)" : " at a time",
            m.cpu[0] ? m.cpu : "?", m.cores[0] ? m.cores : "?",
            m.sundials[0] ? m.sundials : "?", m.gsl[0] ? m.gsl : "?",
            m.mujoco[0] ? m.mujoco : "?", m.simbody[0] ? m.simbody : "?",
            m.lapack[0] ? m.lapack : "not recorded", m.run_wall, m.plot_wall);
    if (csv.bad_rows) fprintf(md, "Warning: %ld malformed rows of runs.csv were skipped.\n\n", csv.bad_rows);
    fprintf(md, "Methods: **braun** — Eqs. 16, 17, 20 (libbraun; Euler, Heun, RK4, adaptive "
                "DOPRI5); **braun without energy correction** — Eqs. 16, 17; **Baumgarte** — "
                "ideal constraint force with −2αΦ̇ − β²Φ, RK4; **IDA GGL** — SUNDIALS IDA on "
                "the stabilised index-2 formulation (*defaults*; *tuned*: λ, μ out of the Newton "
                "test and BDF order ≤ 2); **IDA index-1**; **minimal ODE** — the scene's "
                "minimal-coordinate equation with RK4; **RK4 + coordinate projection**; "
                "**MuJoCo** and **Simbody** (section “The peers”). Error: max over the output "
                "grid of ‖q − q_ref‖₂.\n\n");

    summary(md, &d, pr, np);
    cmp_claims_section(md, &d);
    wp_section(md, dir, &d, pr, np);
    fig6_section(md, dir, &d, pr, np);
    peers_section(md, &d, pr, np, &m);
    ida_section(md, &d, pr, np);

    fprintf(md, "## Scene by scene\n\n");
    for (int i = 0; i < np; i++) {
        const char *sc = pr[i].scene;
        const double T = pr[i].T;
        char name[160];
        fprintf(md, "### %s, T = %g s\n\n", sc, T);
        fprintf(md, "Most accurate method within each CPU budget (runs that reached T):\n\n");
        winners(md, &d, sc, T);
        series_summary(md, &d, sc, T);
        breakdown(md, &d, sc, T);
        snprintf(name, sizeof name, "steps_%s_%g", sc, T);
        figure(md, dir, name, "errors and CPU time against the step size (Fig. 4)");
        snprintf(name, sizeof name, "history_%s_%g", sc, T);
        figure(md, dir, name, "error histories at the paper's h = 1e-2 scaled with the scene "
                              "(Andrews: 1e-5; the plot's title gives it) (Figs. 3 and 7)");
        snprintf(name, sizeof name, "tol_%s_%g", sc, T);
        figure(md, dir, name, "adaptive methods: error and time reached against the tolerance");
        if (!strcmp(sc, "slider-crank") && i == first_index(pr, np, sc))
            figure(md, dir, "slider_slider-crank", "slider position against time, h = 5e-2 (Fig. 2)");
    }
    references_section(md, dir, &d);
    library_failures(md, &d);
    iftomm_section(md, dir);

    fprintf(md, "## Appendix: the probes\n\n");
    fprintf(md, "### MuJoCo: the softness sweep\n\n"
                "One setting changed from the main series' at a time (RK4, the sweep's step "
                "sizes, first horizon, one timing each), and MuJoCo's defaults. Which of these "
                "matter decided the main series (docs/compare.md, “Peers”).\n\n");
    sweep_table(md, &d, pr, np, "mujoco", "mj-rk4");
    baumgarte_section(md, &d, pr, np);
    probe_section(md, dir);
    singular_section(md, dir);

    int bad = ferror(md) != 0;
    if (fclose(md)) bad = 1;
    free(d.r);
    free(d.cost);
    free(d.tgt);
    cmp_csv_free(&csv);
    cmp_csv_free(&cost_csv);
    cmp_csv_free(&tgt_csv);
    if (bad) {
        fprintf(stderr, "braun-compare: error writing %s/report.md\n", dir);
        return 1;
    }
    fprintf(stderr, "braun-compare: wrote %s/report.md\n", dir);
    return 0;
}
