/* Cost per simulated second at matched trajectory error, from make
 * compare's runs.csv (docs/compare.md lists its columns). For each scene,
 * horizon and series the runs that reached T form an error–cost curve;
 * its Pareto front (no run both cheaper and more accurate) is interpolated
 * linearly in log(error)–log(CPU time) at each error level. The series are
 * those of compare/series.tsv marked "bench", in its order; the method
 * column is the series' key, ratios are to braun:rk4:-. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "cmp_series.h"

#define MAX_FIELDS 64
#define MAX_RUNS 4096

typedef struct run_row {
    char scene[64], method[32], integrator[16], variant[32];
    double T, err, cpu;
    int ok;
} run_row;

/* The baseline of the ratios. */
#define BASELINE "braun:rk4:-"

/* Split one CSV line in place (double quotes allowed around a field). */
static int split(char *line, char **f)
{
    int n = 0;
    char *p = line;
    while (n < MAX_FIELDS) {
        if (*p == '"') {
            f[n++] = ++p;
            while (*p && !(*p == '"' && (p[1] == ',' || p[1] == '\0' || p[1] == '\n'))) p++;
            if (*p) *p++ = '\0';
        } else {
            f[n++] = p;
            while (*p && *p != ',' && *p != '\n') p++;
        }
        if (*p == ',') {
            *p++ = '\0';
            continue;
        }
        *p = '\0';
        break;
    }
    return n;
}

static int col(char **hdr, int nh, const char *name)
{
    for (int i = 0; i < nh; i++)
        if (strcmp(hdr[i], name) == 0) return i;
    return -1;
}

static int by_cpu(const void *a, const void *b)
{
    const run_row *x = a, *y = b;
    return (x->cpu > y->cpu) - (x->cpu < y->cpu);
}

/* Cost at error level L on the Pareto front of pts (sorted by cpu).
 * *how: "interpolated", "cheapest-run" (the cheapest run is already below
 * L: an upper bound) or "not-reached". */
static double cost_at(const run_row *pts, int np, double L, const char **how)
{
    const run_row *front[MAX_RUNS];
    int nf = 0;
    for (int i = 0; i < np; i++)
        if (nf == 0 || pts[i].err < front[nf - 1]->err) front[nf++] = &pts[i];
    *how = "not-reached";
    if (nf == 0 || front[nf - 1]->err > L) return NAN;
    if (front[0]->err <= L) {
        *how = "cheapest-run";
        return front[0]->cpu;
    }
    for (int i = 0; i + 1 < nf; i++) {
        const double e0 = front[i]->err, e1 = front[i + 1]->err;
        if (e0 >= L && e1 <= L) {
            const double u = (log(L) - log(e0)) / (log(e1) - log(e0));
            *how = "interpolated";
            return exp(log(front[i]->cpu) + u * (log(front[i + 1]->cpu) - log(front[i]->cpu)));
        }
    }
    return NAN;
}

/* The cost of series s at error level L on the scene and horizon of row
 * at; *np: its runs that reached T (0: none, the rest is not set), *best:
 * their smallest error. pts: room for MAX_RUNS rows. */
static double curve_cost(const run_row *rows, int nr, const run_row *at, const cmp_series *s,
                         double L, run_row *pts, int *np, double *best, const char **how)
{
    *np = 0;
    for (int j = 0; j < nr; j++) {
        const run_row *r = &rows[j];
        if (!r->ok || strcmp(r->scene, at->scene) != 0 || r->T != at->T) continue;
        if (!cmp_series_is(s, r->method, r->integrator, r->variant)) continue;
        pts[(*np)++] = *r;
    }
    *how = "not-reached";
    *best = NAN;
    if (*np == 0) return NAN;
    qsort(pts, (size_t)*np, sizeof pts[0], by_cpu);
    *best = pts[0].err;
    for (int j = 1; j < *np; j++)
        if (pts[j].err < *best) *best = pts[j].err;
    return cost_at(pts, *np, L, how);
}

int bench_matched_write(FILE *out, const char *runs_csv, const double *levels, int nlevels)
{
    fprintf(out, "scene,T,error_level,method,cpu_s,cpu_per_sim_s,ratio_to_braun_rk4,how,runs,"
                 "best_error\n");
    FILE *f = fopen(runs_csv, "r");
    if (!f) return 1;
    static char line[8192];
    char *hdr[MAX_FIELDS], hline[8192];
    if (!fgets(hline, sizeof hline, f)) {
        fclose(f);
        return -1;
    }
    const int nh = split(hline, hdr);
    const int c_scene = col(hdr, nh, "scene"), c_T = col(hdr, nh, "T"),
              c_method = col(hdr, nh, "method"), c_int = col(hdr, nh, "integrator"),
              c_var = col(hdr, nh, "variant"), c_status = col(hdr, nh, "status"),
              c_reached = col(hdr, nh, "t_reached"), c_cpu = col(hdr, nh, "cpu_s"),
              c_err = col(hdr, nh, "traj_max");
    if (c_scene < 0 || c_T < 0 || c_method < 0 || c_int < 0 || c_var < 0 || c_status < 0 ||
        c_reached < 0 || c_cpu < 0 || c_err < 0) {
        fclose(f);
        return -1;
    }
    run_row *rows = malloc(MAX_RUNS * sizeof *rows);
    run_row *pts = malloc(MAX_RUNS * sizeof *pts);
    int nr = 0;
    if (!rows || !pts) {
        free(rows);
        free(pts);
        fclose(f);
        return -1;
    }
    while (nr < MAX_RUNS && fgets(line, sizeof line, f)) {
        char *fl[MAX_FIELDS];
        int n = split(line, fl);
        if (n < nh) continue;
        run_row *r = &rows[nr];
        snprintf(r->scene, sizeof r->scene, "%s", fl[c_scene]);
        snprintf(r->method, sizeof r->method, "%s", fl[c_method]);
        snprintf(r->integrator, sizeof r->integrator, "%s", fl[c_int]);
        snprintf(r->variant, sizeof r->variant, "%s", fl[c_var]);
        r->T = strtod(fl[c_T], NULL);
        r->cpu = strtod(fl[c_cpu], NULL);
        r->err = strtod(fl[c_err], NULL);
        r->ok = strcmp(fl[c_status], "ok") == 0 &&
                strtod(fl[c_reached], NULL) >= r->T * (1 - 1e-9) &&
                isfinite(r->err) && r->cpu > 0;
        nr++;
    }
    fclose(f);

    /* Scenes and horizons in file order. */
    const cmp_series *baseline = cmp_series_find(BASELINE);
    for (int i = 0; i < nr; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(rows[j].scene, rows[i].scene) == 0 && rows[j].T == rows[i].T;
        if (seen) continue;
        for (int l = 0; l < nlevels; l++) {
            const char *how;
            int np;
            double best;
            const double base = baseline ? curve_cost(rows, nr, &rows[i], baseline, levels[l], pts,
                                                      &np, &best, &how)
                                         : NAN;
            for (int k = 0; k < cmp_series_count; k++) {
                const cmp_series *s = &cmp_series_table[k];
                if (!cmp_series_in(s, "bench")) continue;
                const double c =
                    curve_cost(rows, nr, &rows[i], s, levels[l], pts, &np, &best, &how);
                if (np == 0) continue;
                fprintf(out, "%s,%g,%g,%s,%.6g,%.6g,%.4g,%s,%d,%.3g\n", rows[i].scene, rows[i].T,
                        levels[l], s->key, c, c / rows[i].T, c / base, how, np, best);
            }
        }
    }
    free(rows);
    free(pts);
    return 0;
}
