/* braun-compare: the harness of `make compare` (docs/compare.md).
 *
 *   braun-compare run [--study default|quick] [--scenes LIST] [--methods LIST]
 *                     [--reps K] [--no-probe] [--out DIR]
 *                     [--prepare G | --job K] [--refdir DIR] [--t0 SECONDS]
 *   braun-compare plan [the options of run]
 *   braun-compare report [--dir DIR]
 *   braun-compare list
 *   braun-compare series        the series table (compare/series.tsv) as built in
 *   braun-compare claims        the claims table (compare/cmp_claims.c)
 *   braun-compare files         the CSV files of a study, in merge order
 *   braun-compare versions      the peers built in (MuJoCo, Simbody)
 *
 * LIST: names separated by spaces or commas. plan, --prepare and --job are
 * the steps of compare/run.sh's parallel study (docs/compare.md). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "cmp.h"
#include "cmp_claims.h"
#include "cmp_series.h"
#include "cmp_study.h"

static void usage(FILE *f)
{
    fprintf(f,
            "Usage: braun-compare run [--study default|quick] [--scenes LIST] [--methods LIST]\n"
            "                         [--reps K] [--no-probe] [--out DIR]\n"
            "                         [--prepare G | --job K] [--refdir DIR] [--t0 SECONDS]\n"
            "       braun-compare plan [the options of run]\n"
            "       braun-compare report [--dir DIR]\n"
            "       braun-compare list\n"
            "       braun-compare series\n"
            "       braun-compare claims\n"
            "       braun-compare files | versions\n"
            "\n"
            "run     integrate every scene with every method on the study's grid of step\n"
            "        sizes and tolerances; write DIR/runs.csv, history.csv,\n"
            "        references.csv, ida_probe.csv, singular.csv (default DIR\n"
            "        results/compare); with --prepare G, one (scene, horizon) group's\n"
            "        singular.csv and references.csv rows and its reference saved in\n"
            "        the --refdir; with --job K, run K of the plan against that saved\n"
            "        reference (compare/run.sh runs these as parallel processes)\n"
            "plan    the steps of the study, in the order of the serial run:\n"
            "        'prepare G T' per group, 'job K G' per run\n"
            "report  write DIR/report.md from those files and the plots beside them\n"
            "list    methods and built-in scenes\n"
            "series  the series of the report, plots and bench as this program has them\n"
            "        (compare/series.tsv): key|label|colour|dash|point|in\n"
            "claims  the paper's claims: claim, paper, figure, its arguments, the tests\n"
            "        and the rule as the report states it (tab-separated)\n"
            "files   the CSV files a study writes, in merge order\n"
            "versions  the peers built in (MuJoCo, Simbody)\n"
            "\n"
            "LIST is separated by spaces or commas. Defaults: every shipped scene\n"
            "(braun-compare list); every method; K = 3.\n"
            "See docs/compare.md.\n");
}

/* Split a list in place on spaces and commas. */
static int split(char *s, const char **out, int max)
{
    int n = 0;
    for (char *tok = strtok(s, " ,\t\n"); tok; tok = strtok(NULL, " ,\t\n")) {
        if (n == max) return -1;
        out[n++] = tok;
    }
    return n;
}

/* A whole number 0..max, or -1. */
static long count_arg(const char *s, long max)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    return end != s && *end == '\0' && errno == 0 && v >= 0 && v <= max ? v : -1;
}

/* The options of run and plan into o; 0, or the exit status of an error
 * (-1: help was printed). */
static int parse_run(int argc, char **argv, cmp_study_opts *o)
{
    memset(o, 0, sizeof *o);
    o->study = "default";
    o->reps = 3;
    o->probe = 1;
    o->out_dir = "results/compare";
    o->prepare = o->job = -1;
    char *scenes = NULL, *methods = NULL;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--no-probe") == 0) {
            o->probe = 0;
            continue;
        }
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return -1;
        }
        if (!val) {
            fprintf(stderr, "braun-compare: '%s' needs a value or is unknown\n", a);
            return 2;
        }
        i++;
        if (strcmp(a, "--study") == 0) o->study = val;
        else if (strcmp(a, "--scenes") == 0) scenes = argv[i];
        else if (strcmp(a, "--methods") == 0) methods = argv[i];
        else if (strcmp(a, "--out") == 0) o->out_dir = val;
        else if (strcmp(a, "--refdir") == 0) o->refdir = val;
        else if (strcmp(a, "--reps") == 0) o->reps = atoi(val);
        else if (strcmp(a, "--prepare") == 0 || strcmp(a, "--job") == 0) {
            const long k = count_arg(val, INT_MAX);
            if (k < 0) {
                fprintf(stderr, "braun-compare: %s needs an index, not '%s'\n", a, val);
                return 2;
            }
            if (a[2] == 'p') o->prepare = (int)k;
            else o->job = (int)k;
        } else if (strcmp(a, "--t0") == 0) {
            const long t = count_arg(val, LONG_MAX);
            if (t < 0) {
                fprintf(stderr, "braun-compare: --t0 needs seconds since the epoch\n");
                return 2;
            }
            o->t0 = (double)t;
        } else {
            fprintf(stderr, "braun-compare: unknown option '%s'\n", a);
            return 2;
        }
    }
    if (strcmp(o->study, "default") != 0 && strcmp(o->study, "quick") != 0) {
        fprintf(stderr, "braun-compare: --study must be default or quick\n");
        return 2;
    }
    if (o->reps < 1 || o->reps > 100) {
        fprintf(stderr, "braun-compare: --reps must be 1..100\n");
        return 2;
    }
    if (o->prepare >= 0 && o->job >= 0) {
        fprintf(stderr, "braun-compare: --prepare or --job, not both\n");
        return 2;
    }
    static char defaults[512];
    if (!scenes || !*scenes) {
        snprintf(defaults, sizeof defaults, "%s", cmp_default_scenes(o->study));
        scenes = defaults;
    }
    o->nscenes = split(scenes, o->scenes, CMP_MAX_SCENES);
    if (o->nscenes <= 0) {
        fprintf(stderr, "braun-compare: no scenes\n");
        return 2;
    }
    for (int s = 0; s < o->nscenes; s++) {
        cmp_target tg;
        char err[256];
        if (cmp_target_find(o->scenes[s], &tg, err, sizeof err)) {
            fprintf(stderr, "braun-compare: %s\n", err);
            return 2;
        }
        cmp_target_free(&tg);
    }
    if (methods && *methods) {
        const char *names[CMP_METHOD_COUNT + 1];
        int n = split(methods, names, CMP_METHOD_COUNT + 1);
        if (n < 0) {
            fprintf(stderr, "braun-compare: too many methods\n");
            return 2;
        }
        for (int k = 0; k < n; k++) {
            int m = cmp_method_from_name(names[k]);
            if (m < 0) {
                fprintf(stderr, "braun-compare: unknown method '%s' (braun-compare list)\n",
                        names[k]);
                return 2;
            }
            o->methods[m] = 1;
        }
    } else {
        for (int m = 0; m < CMP_METHOD_COUNT; m++) o->methods[m] = 1;
    }
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    cmp_study_opts o;
    const int st = parse_run(argc, argv, &o);
    if (st) return st < 0 ? 0 : st;
    return cmp_study_run(&o);
}

static int cmd_plan(int argc, char **argv)
{
    cmp_study_opts o;
    const int st = parse_run(argc, argv, &o);
    if (st) return st < 0 ? 0 : st;
    return cmp_study_plan(&o, stdout);
}

static int cmd_report(int argc, char **argv)
{
    const char *dir = "results/compare";
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--dir") == 0 && i + 1 < argc) {
            dir = argv[++i];
        } else {
            fprintf(stderr, "braun-compare: unknown option '%s'\n", argv[i]);
            return 2;
        }
    }
    return cmp_report_write(dir);
}

static int cmd_list(void)
{
    printf("methods:");
    for (int m = 0; m < CMP_METHOD_COUNT; m++) printf(" %s", cmp_method_name((cmp_method_id)m));
    printf("\nbuilt-in models:");
    for (int i = 0; braun_builtin_at(i); i++) printf(" %s", braun_builtin_at(i)->name);
    printf("\ndefault study: %s\nquick study: %s\n", cmp_default_scenes("default"),
           cmp_default_scenes("quick"));
    printf("other targets: andrews, data/NAME.json as NAME, or a path to a .json scene\n");
    return 0;
}

/* `braun-compare scenes STUDY`: the default scene list, for compare/run.sh. */
static int cmd_scenes(int argc, char **argv)
{
    const char *study = argc > 0 ? argv[0] : "default";
    printf("%s\n", cmp_default_scenes(study));
    return 0;
}

int main(int argc, char **argv)
{
    /* GSL returns error codes; the harness reports them, never aborts. */
    gsl_set_error_handler_off();
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "run") == 0) return cmd_run(argc - 2, argv + 2);
    if (strcmp(argv[1], "plan") == 0) return cmd_plan(argc - 2, argv + 2);
    if (strcmp(argv[1], "report") == 0) return cmd_report(argc - 2, argv + 2);
    if (strcmp(argv[1], "list") == 0) return cmd_list();
    if (strcmp(argv[1], "scenes") == 0) return cmd_scenes(argc - 2, argv + 2);
    if (strcmp(argv[1], "files") == 0) {
        /* The CSV files of a study, in merge order (compare/run.sh). */
        printf("%s\n", cmp_study_files);
        return 0;
    }
    if (strcmp(argv[1], "versions") == 0) {
        /* The peers built in (compare/run.sh's meta.txt). */
        const char *mj = cmp_mujoco_version(), *sb = cmp_simbody_version();
        printf("mujoco=%s\nsimbody=%s\n", mj ? mj : "not built", sb ? sb : "not built");
        return 0;
    }
    if (strcmp(argv[1], "series") == 0) {
        cmp_series_print(stdout);
        return 0;
    }
    if (strcmp(argv[1], "claims") == 0) {
        cmp_claims_print(stdout);
        return 0;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "braun-compare: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
