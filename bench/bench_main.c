/* braun-bench: the program behind make bench (bench/bench.sh drives it).
 *
 *   braun-bench time [--rounds R] [--steps K] TARGET...   ns per step / rhs (CSV)
 *   braun-bench run TARGET ITEM [--steps K]               one block, for callgrind
 *   braun-bench flops TARGET...                           derived flop counts (CSV)
 *   braun-bench info TARGET...                            sizes (CSV)
 *   braun-bench matched RUNS_CSV [LEVEL...]               cost at matched error (CSV)
 *   braun-bench series                                    the series table it uses
 *
 * Timing: every round runs one block of every item of a target, in an order
 * that rotates from round to round, with process CPU time around each
 * block; a block is K steps (or right-hand sides) from the same start.
 * Reported: the median over rounds of ns per operation, its quartiles, and
 * the median over rounds of the ratio to the baselines measured in the same
 * round — the ratios are what noise from other processes disturbs least. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "cmp_series.h"

static int usage(void)
{
    fprintf(stderr,
            "usage: braun-bench time [--rounds R] [--steps K] TARGET...\n"
            "       braun-bench run TARGET ITEM [--steps K]\n"
            "       braun-bench flops TARGET...\n"
            "       braun-bench info TARGET...\n"
            "       braun-bench matched RUNS_CSV [LEVEL...]\n"
            "       braun-bench series\n"
            "items: step-none step-pv step-all step-free step-floor step-special rhs-ideal rhs-corrected "
            "rhs-floor\n");
    return 2;
}

static const char *corr_str(unsigned c)
{
    switch (c) {
    case 0: return "none";
    case BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY: return "position+velocity";
    case BRAUN_CORRECT_ALL: return "position+velocity+energy";
    default: return "other";
    }
}

/* "BRAUN_ERR_DIVERGED" from "BRAUN_ERR_DIVERGED: meaning". */
static const char *status_name(int st)
{
    static char buf[64];
    const char *s = braun_status_str(st);
    size_t i = 0;
    while (s[i] && s[i] != ':' && i + 1 < sizeof buf) {
        buf[i] = s[i];
        i++;
    }
    buf[i] = '\0';
    return buf;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Quantile q of v[0..n) (sorted copy; linear interpolation), NaNs dropped. */
static double quantile(const double *v, int n, double q)
{
    double *s = malloc((size_t)(n > 0 ? n : 1) * sizeof *s);
    int k = 0;
    if (!s) return NAN;
    for (int i = 0; i < n; i++)
        if (!isnan(v[i])) s[k++] = v[i];
    double r = NAN;
    if (k > 0) {
        qsort(s, (size_t)k, sizeof *s, cmp_double);
        const double pos = q * (k - 1);
        const int i = (int)pos;
        r = i + 1 < k ? s[i] + (pos - i) * (s[i + 1] - s[i]) : s[i];
    }
    free(s);
    return r;
}

/* Options after the command: --rounds R, --steps K; the rest are targets. */
static int parse_opts(int argc, char **argv, long *rounds, long *steps, char **rest, int *nrest)
{
    *nrest = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
            *rounds = strtol(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
            *steps = strtol(argv[++i], NULL, 10);
        } else if (argv[i][0] == '-' && argv[i][1] == '-') {
            return -1;
        } else {
            rest[(*nrest)++] = argv[i];
        }
    }
    return (*rounds > 0 && *steps > 0) ? 0 : -1;
}

static int cmd_time(int argc, char **argv)
{
    long rounds = 31, steps = 2000;
    char **names = malloc((size_t)(argc + 1) * sizeof *names);
    int nt;
    if (!names || parse_opts(argc, argv, &rounds, &steps, names, &nt) || nt == 0) {
        free(names);
        return usage();
    }
    double *ns = malloc((size_t)rounds * BENCH_ITEMS * sizeof *ns);
    double *ratio = malloc((size_t)rounds * sizeof *ratio);
    int rc = 0;
    if (!ns || !ratio) {
        rc = 1;
        goto done;
    }
    printf("target,source,backend,n,m,p,rank,h,steps,item,kind,corrections,status,rounds,"
           "ops,ns_median,ns_q1,ns_q3,ratio_ideal,ratio_floor,ratio_free,ns_min\n");
    for (int t = 0; t < nt; t++) {
        char err[600];
        bench_target tg;
        if (bench_target_open(names[t], &tg, err, sizeof err)) {
            fprintf(stderr, "braun-bench: %s\n", err);
            rc = 1;
            goto done;
        }
        bench_run *r = bench_run_new(&tg, steps, err, sizeof err);
        if (!r) {
            fprintf(stderr, "braun-bench: %s\n", err);
            bench_target_close(&tg);
            rc = 1;
            goto done;
        }
        long rank = 0, srt = 0, sr = 0;
        bench_flops_shape(&tg, &rank, &srt, &sr);
        int status[BENCH_ITEMS] = {0};
        long done[BENCH_ITEMS];
        for (int i = 0; i < BENCH_ITEMS; i++) done[i] = steps;
        /* Warm-up: caches, branch predictors, recorded states. */
        for (int i = 0; i < BENCH_ITEMS; i++) {
            int st;
            bench_run_reset(r, (bench_item)i);
            bench_run_block(r, (bench_item)i, &st);
        }
        for (long k = 0; k < rounds; k++)
            for (int j = 0; j < BENCH_ITEMS; j++) {
                const bench_item it = (bench_item)((j + k) % BENCH_ITEMS);
                double *x = &ns[k * BENCH_ITEMS + it];
                *x = NAN;
                if (!bench_run_has(r, it)) continue;
                int st;
                bench_run_reset(r, it);
                const double t0 = bench_cpu_ns();
                const long ops = bench_run_block(r, it, &st);
                const double t1 = bench_cpu_ns();
                if (st && !status[it]) status[it] = st;
                if (ops < done[it]) done[it] = ops;
                if (ops > 0) *x = (t1 - t0) / (double)ops;
            }
        for (int i = 0; i < BENCH_ITEMS; i++) {
            const bench_item it = (bench_item)i;
            if (!bench_run_has(r, it)) continue;
            const int is_rhs = it >= BENCH_RHS_IDEAL;
            const bench_item base[3] = {is_rhs ? BENCH_RHS_IDEAL : BENCH_STEP_NONE,
                                        is_rhs ? BENCH_RHS_FLOOR : BENCH_STEP_FLOOR,
                                        is_rhs ? BENCH_ITEMS : BENCH_STEP_FREE};
            double rq[3];
            for (int b = 0; b < 3; b++) {
                for (long k = 0; k < rounds; k++)
                    ratio[k] = base[b] < BENCH_ITEMS
                                   ? ns[k * BENCH_ITEMS + it] / ns[k * BENCH_ITEMS + base[b]]
                                   : NAN;
                rq[b] = quantile(ratio, (int)rounds, 0.5);
            }
            for (long k = 0; k < rounds; k++) ratio[k] = ns[k * BENCH_ITEMS + it];
            const double med = quantile(ratio, (int)rounds, 0.5),
                         q1 = quantile(ratio, (int)rounds, 0.25),
                         q3 = quantile(ratio, (int)rounds, 0.75),
                         lo = quantile(ratio, (int)rounds, 0.0);
            printf("%s,%s,%s,%d,%d,%d,%ld,%g,%ld,%s,%s,%s,%s,%ld,%ld,%.1f,%.1f,%.1f,%.4f,%.4f,%.4f,"
                   "%.1f\n",
                   tg.name, tg.source, BENCH_BACKEND, tg.sys.n, tg.sys.m, tg.sys.p, rank, tg.h,
                   steps, bench_item_name(it), bench_item_kind(it),
                   it == BENCH_STEP_FLOOR || it == BENCH_RHS_FLOOR
                       ? "minimal"
                       : (it == BENCH_STEP_FREE ? "unconstrained"
                                                : corr_str(bench_item_corrections(&tg, it))),
                   status[it] ? status_name(status[it]) : "ok", rounds, done[it],
                   med, q1, q3, rq[0], rq[1], rq[2], lo);
        }
        fflush(stdout);
        bench_run_free(r);
        bench_target_close(&tg);
    }
done:
    free(ns);
    free(ratio);
    free(names);
    return rc;
}

static int cmd_run(int argc, char **argv)
{
    long rounds = 1, steps = 2000;
    char *rest[8];
    int nrest;
    if (argc > 8 || parse_opts(argc, argv, &rounds, &steps, rest, &nrest) || nrest != 2)
        return usage();
    const int it = bench_item_from_name(rest[1]);
    if (it < 0) return usage();
    char err[600];
    bench_target tg;
    if (bench_target_open(rest[0], &tg, err, sizeof err)) {
        fprintf(stderr, "braun-bench: %s\n", err);
        return 1;
    }
    bench_run *r = bench_run_new(&tg, steps, err, sizeof err);
    if (!r) {
        fprintf(stderr, "braun-bench: %s\n", err);
        return 1;
    }
    long ops = 0;
    int st = 0;
    if (bench_run_has(r, (bench_item)it)) {
        bench_run_reset(r, (bench_item)it);
        ops = bench_run_block(r, (bench_item)it, &st);
    }
    if (it == BENCH_STEP_SPECIAL)
        printf("ops=%ld status=%d agreement=%.3g\n", ops, st, bench_run_special_agreement(r));
    else
        printf("ops=%ld status=%d\n", ops, st);
    bench_run_free(r);
    bench_target_close(&tg);
    return 0;
}

static int cmd_flops(int argc, char **argv)
{
    printf("target,item,component,flops\n");
    for (int i = 0; i < argc; i++) {
        char err[600];
        bench_target tg;
        if (bench_target_open(argv[i], &tg, err, sizeof err)) {
            fprintf(stderr, "braun-bench: %s\n", err);
            return 1;
        }
        if (bench_flops_write(stdout, &tg)) return 1;
        bench_target_close(&tg);
    }
    return 0;
}

static int cmd_info(int argc, char **argv)
{
    printf("target,source,n,m,p,rank,energy_law,minimal,h,solve_rt_flops,solve_r_flops,backend\n");
    for (int i = 0; i < argc; i++) {
        char err[600];
        bench_target tg;
        long rank = 0, srt = 0, sr = 0;
        if (bench_target_open(argv[i], &tg, err, sizeof err)) {
            fprintf(stderr, "braun-bench: %s\n", err);
            return 1;
        }
        bench_flops_shape(&tg, &rank, &srt, &sr);
        printf("%s,%s,%d,%d,%d,%ld,%s,%s,%g,%ld,%ld,%s\n", tg.name, tg.source, tg.sys.n,
               tg.sys.m, tg.sys.p, rank, tg.sys.energy ? "yes" : "no",
               tg.minimal ? tg.minimal->name : "-", tg.h, srt, sr, BENCH_BACKEND);
        bench_target_close(&tg);
    }
    return 0;
}

static int cmd_matched(int argc, char **argv)
{
    double levels[16] = {1e-3, 1e-6};
    int nl = 2;
    if (argc < 1) return usage();
    if (argc > 1) {
        nl = 0;
        for (int i = 1; i < argc && nl < 16; i++) levels[nl++] = strtod(argv[i], NULL);
    }
    int st = bench_matched_write(stdout, argv[0], levels, nl);
    if (st < 0) fprintf(stderr, "braun-bench: cannot read %s\n", argv[0]);
    return st < 0 ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) return usage();
    const char *cmd = argv[1];
    if (strcmp(cmd, "time") == 0) return cmd_time(argc - 2, argv + 2);
    if (strcmp(cmd, "run") == 0) return cmd_run(argc - 2, argv + 2);
    if (strcmp(cmd, "flops") == 0) return cmd_flops(argc - 2, argv + 2);
    if (strcmp(cmd, "info") == 0) return cmd_info(argc - 2, argv + 2);
    if (strcmp(cmd, "matched") == 0) return cmd_matched(argc - 2, argv + 2);
    if (strcmp(cmd, "series") == 0) {
        cmp_series_print(stdout); /* compare/series.tsv, as built in */
        return 0;
    }
    return usage();
}
