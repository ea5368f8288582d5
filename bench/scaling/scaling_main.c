/* braun-scaling: the measurements behind `make scaling` (bench/scaling/run.sh).
 *
 *   braun-scaling step SCENE BACKEND [--h H] [--reps R] [--budget S]
 *       CPU ns per corrected RK4 step (median of R blocks) from the scene's
 *       initial state; one CSV row (header with --header).
 *   braun-scaling ida-step SCENE [--T T] [--rtol R] [--reg EPS] [--max-steps K]
 *       IDA+KLU (GGL, analytic sparse Jacobian) to T: CPU ns per step.
 *   braun-scaling matched SCENE BACKEND --T T --h "H1 H2 ..." --rtol "R1 ..."
 *       [--href H] [--samples S]
 *       trajectory error against a reference (braun RK4 at href, checked
 *       against braun DOPRI5 at rtol 1e-11) and CPU seconds per simulated
 *       second, for braun RK4 at each h and IDA at each rtol.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scaling.h"

static int usage(void)
{
    fprintf(stderr, "usage: braun-scaling step SCENE BACKEND [--h H] [--reps R] [--budget S]\n"
                    "       braun-scaling ida-step SCENE [--T T] [--rtol R] [--reg EPS]\n"
                    "       braun-scaling matched SCENE BACKEND --T T --h LIST --rtol LIST "
                    "[--href H] [--samples S]\n");
    return 2;
}

static const char *opt(int argc, char **argv, const char *name, const char *def)
{
    for (int i = 0; i + 1 < argc; i++)
        if (strcmp(argv[i], name) == 0) return argv[i + 1];
    return def;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---------------------------------------------------------------- step */
static int cmd_step(int argc, char **argv)
{
    if (argc < 2) return usage();
    const char *path = argv[0], *backend = argv[1];
    const double h = atof(opt(argc, argv, "--h", "1e-3"));
    const int reps = atoi(opt(argc, argv, "--reps", "5"));
    const double budget = atof(opt(argc, argv, "--budget", "1.0"));
    char err[512];
    sc_scene s;
    if (sc_scene_load(&s, path, err, sizeof err)) {
        fprintf(stderr, "braun-scaling: %s\n", err);
        return 1;
    }
    const int n = s.sys.n, rows = s.sys.m + s.sys.p;
    sc_sim m;
    int st = sc_sim_open(&m, &s, backend, err, sizeof err);
    if (st) {
        /* Not runnable at this size: a row that says so. */
        printf("%s,%d,%d,%s,nan,nan,0,0,skipped: %s\n", path, n, rows, backend, err);
        sc_scene_free(&s);
        return 0;
    }
    /* First step: factorizations' symbolic phases, page faults. */
    double c0 = sc_cpu_seconds();
    st = braun_step(&m.data, BRAUN_RK4, h);
    double first = sc_cpu_seconds() - c0;
    /* Steps per block: about budget / reps seconds each, at least 1. */
    long per = (long)(budget / reps / (first > 1e-7 ? first : 1e-7));
    if (per < 1) per = 1;
    if (per > 100000) per = 100000;
    double *t = calloc((size_t)reps, sizeof *t);
    int done = 0;
    for (int r = 0; r < reps && !st; r++) {
        c0 = sc_cpu_seconds();
        for (long k = 0; k < per && !st; k++) st = braun_step(&m.data, BRAUN_RK4, h);
        t[r] = (sc_cpu_seconds() - c0) / (double)per;
        done++;
    }
    qsort(t, (size_t)done, sizeof *t, cmp_double);
    const double med = done ? t[done / 2] : NAN, best = done ? t[0] : NAN;
    const double rd = m.data.stats.constraint_factorizations
                          ? (double)m.data.stats.rank_deficient /
                                (double)m.data.stats.constraint_factorizations
                          : 0;
    printf("%s,%d,%d,%s,%.1f,%.1f,%ld,%.3f,%s\n", path, n, rows, braun_linsolver_name(m.ls),
           1e9 * med, 1e9 * best, per * done, rd, st ? braun_status_str(st) : "ok");
    free(t);
    sc_sim_close(&m);
    sc_scene_free(&s);
    return st ? 1 : 0;
}

/* ---------------------------------------------------------------- ida-step */
static int cmd_ida_step(int argc, char **argv)
{
    if (argc < 1) return usage();
    const char *path = argv[0];
    const double T = atof(opt(argc, argv, "--T", "0.1"));
    const double rtol = atof(opt(argc, argv, "--rtol", "1e-6"));
    const double reg = atof(opt(argc, argv, "--reg", "0"));
    const long max_steps = atol(opt(argc, argv, "--max-steps", "20000"));
    char err[512];
    sc_scene s;
    if (sc_scene_load(&s, path, err, sizeof err)) {
        fprintf(stderr, "braun-scaling: %s\n", err);
        return 1;
    }
    sc_ida_result r;
    sc_ida_run(&s, T, rtol, reg, max_steps, 0, NULL, &r);
    /* A failed run's cost per step is not the cost of a step of the
     * problem (it is stuck at t ≈ 0 with tiny steps): not reported. */
    printf("%s,%d,%d,ida-klu,%.1f,%.1f,%ld,%.3g,%s%.3g\n", path, s.sys.n, s.sys.m + s.sys.p,
           r.ok && r.steps ? 1e9 * r.cpu_s / (double)r.steps : NAN, NAN, r.steps, r.t_reached,
           r.ok ? "ok" : "failed at t = ", r.ok ? 0.0 : r.t_reached);
    sc_scene_free(&s);
    return 0;
}

/* ---------------------------------------------------------------- matched */
/* braun RK4 (or DOPRI5 when h <= 0, at rtol) through the sample times. */
static int braun_samples(const sc_scene *s, const char *backend, double T, double h,
                         double rtol, int samples, double *q_out, double *cpu)
{
    char err[512];
    sc_sim m;
    int st = sc_sim_open(&m, s, backend, err, sizeof err);
    if (st) {
        fprintf(stderr, "braun-scaling: %s\n", err);
        return st;
    }
    const int n = s->sys.n;
    double c0 = sc_cpu_seconds();
    for (int k = 1; k <= samples && !st; k++) {
        const double tk = T * k / samples;
        if (h > 0) {
            st = braun_integrate(&m.data, BRAUN_RK4, h, tk, 0, NULL, NULL);
        } else {
            braun_adaptive ctl = {rtol, rtol, 0, 0, 0, 0};
            st = braun_integrate_adaptive(&m.data, &ctl, tk, 0, NULL, NULL);
        }
        memcpy(q_out + (size_t)(k - 1) * (size_t)n, m.data.q, sizeof(double) * (size_t)n);
    }
    *cpu = sc_cpu_seconds() - c0;
    sc_sim_close(&m);
    return st;
}

/* Max over samples and coordinates of |q - q_ref| (positions and angles). */
static double traj_error(int n, int samples, const double *q, const double *ref)
{
    double e = 0;
    for (size_t i = 0; i < (size_t)n * (size_t)samples; i++) {
        double d = fabs(q[i] - ref[i]);
        if (!(d <= e)) e = d; /* NaN wins */
    }
    return e;
}

static int cmd_matched(int argc, char **argv)
{
    if (argc < 2) return usage();
    const char *path = argv[0], *backend = argv[1];
    const double T = atof(opt(argc, argv, "--T", "1"));
    const double href = atof(opt(argc, argv, "--href", "1.25e-4"));
    const int samples = atoi(opt(argc, argv, "--samples", "20"));
    char hs[512], rs[512];
    snprintf(hs, sizeof hs, "%s", opt(argc, argv, "--h", "2e-3 1e-3"));
    snprintf(rs, sizeof rs, "%s", opt(argc, argv, "--rtol", "1e-5 1e-6 1e-7"));
    char err[512];
    sc_scene s;
    if (sc_scene_load(&s, path, err, sizeof err)) {
        fprintf(stderr, "braun-scaling: %s\n", err);
        return 1;
    }
    const int n = s.sys.n;
    const size_t size = (size_t)n * (size_t)samples;
    double *ref = malloc(size * sizeof *ref), *chk = malloc(size * sizeof *chk),
           *q = malloc(size * sizeof *q);
    double cpu;
    int st = braun_samples(&s, backend, T, href, 0, samples, ref, &cpu);
    if (st) {
        fprintf(stderr, "braun-scaling: reference failed: %s\n", braun_status_str(st));
        return 1;
    }
    st = braun_samples(&s, backend, T, 0, 1e-11, samples, chk, &cpu);
    /* The reference's own error estimate: two different methods. */
    /* Its error column: |RK4 at href - DOPRI5 at rtol 1e-11|. */
    printf("%s,%d,reference-vs-dopri5,rk4,%g,1e-11,%.3e,nan,%s\n", path, n, href,
           st ? NAN : traj_error(n, samples, chk, ref), st ? braun_status_str(st) : "ok");
    for (char *tok = strtok(hs, " ,"); tok; tok = strtok(NULL, " ,")) {
        double h = atof(tok);
        st = braun_samples(&s, backend, T, h, 0, samples, q, &cpu);
        printf("%s,%d,braun-%s,rk4,%g,nan,%.3e,%.4g,%s\n", path, n, backend, h,
               st ? NAN : traj_error(n, samples, q, ref), cpu / T, st ? braun_status_str(st) : "ok");
        fflush(stdout);
    }
    for (char *tok = strtok(rs, " ,"); tok; tok = strtok(NULL, " ,")) {
        double rtol = atof(tok);
        sc_ida_result r;
        sc_ida_run(&s, T, rtol, 0, 0, samples, q, &r);
        printf("%s,%d,ida-klu,bdf,nan,%g,%.3e,%.4g,%s\n", path, n, rtol,
               r.ok ? traj_error(n, samples, q, ref) : NAN, r.cpu_s / T,
               r.ok ? "ok" : "failed");
        fflush(stdout);
    }
    free(ref);
    free(chk);
    free(q);
    sc_scene_free(&s);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) return usage();
    if (strcmp(argv[1], "step") == 0) {
        if (argc > 2 && strcmp(argv[2], "--header") == 0) {
            printf("scene,n,rows,backend,ns_step,ns_step_min,steps,rank_deficient,status\n");
            return 0;
        }
        return cmd_step(argc - 2, argv + 2);
    }
    if (strcmp(argv[1], "ida-step") == 0) return cmd_ida_step(argc - 2, argv + 2);
    if (strcmp(argv[1], "matched") == 0) {
        if (argc > 2 && strcmp(argv[2], "--header") == 0) {
            printf("scene,n,method,integrator,h,rtol,traj_err,cpu_per_sim_s,status\n");
            return 0;
        }
        return cmd_matched(argc - 2, argv + 2);
    }
    return usage();
}
