/* Private to the braun command-line tool: what the files of src/cli share. */
#ifndef BRAUN_CLI_H
#define BRAUN_CLI_H

#include <stdio.h>

#include "braun.h"
#include "braun_models.h"

/* Exit statuses: the solver failed at run time / the command line is wrong. */
enum { BRAUN_CLI_FAILED = 1, BRAUN_CLI_USAGE = 2 };

/* Print "braun: <message>" on stderr as one line; returns BRAUN_CLI_USAGE
 * so argument errors read `return braun_cli_error(...)`. */
int braun_cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* ---------------------------------------------------------- usage (cli_usage.c) */
void braun_cli_usage(FILE *f);

/* ---------------------------------------------------- options (cli_args.c) */
typedef struct braun_cli_run_args {
    const char *model;          /* MODEL argument, as given */
    double dt, t_end;           /* required; dt is h0 for dopri5 */
    braun_method method;        /* default rk4 */
    int corrections_default;    /* 1: what the model supports (--corrections all) */
    unsigned corrections;       /* braun_corrections bits otherwise */
    braun_discretization discretization;
    double rank_tol;            /* 0: library default */
    double energy_max_rel;      /* 0: library default */
    double rtol, atol;          /* dopri5 only */
    double ref_h;               /* 0: reference default */
    const char *out_path;       /* CSV trajectory, NULL for none; "-" stdout */
    long every;                 /* CSV row every K steps */
    const char *summary_path;   /* "-" for stdout */
} braun_cli_run_args;

/* Parse the arguments after "run". Returns 0 to run, -1 when --help was
 * asked (usage already printed), else BRAUN_CLI_USAGE after one message. */
int braun_cli_parse_run(int argc, char **argv, braun_cli_run_args *a);

/* Comma list of the correction names in bits ("none" for 0); buf >= 32. */
const char *braun_cli_corrections_str(unsigned bits, char *buf, size_t size);

/* ------------------------------------------------------ models (cli_model.c) */
/* The one place that maps MODEL to a system: built-in names today, scene
 * files later. Returns 0, or prints why and returns BRAUN_CLI_USAGE. */
int braun_cli_find_model(const char *arg, const braun_builtin **out);

/* `braun list`. */
int braun_cli_list(void);

/* ---------------------------------------------------- metrics (cli_metrics.c) */
/* Residuals and errors at one state, and their maxima over the run.
 * NaN where a quantity does not exist (no reference, no point). */
typedef struct braun_cli_errors {
    double pos, vel, energy; /* ||Φ_q||, ||[Φ̇_q; Φ_v]||, |Φ_e| */
    double traj;             /* ||q - q_ref||_2 */
    double point;            /* planar distance of the model's point */
} braun_cli_errors;

typedef struct braun_cli_monitor {
    braun_data scratch;        /* own workspace: never disturbs the run's */
    const braun_builtin *builtin;
    braun_reference ref;
    int has_ref, has_point;
    double ref_h;              /* effective reference substep, NaN if none */
    braun_cli_errors cur;      /* at the last sampled state */
    braun_cli_errors max;      /* over every sampled state */
    long samples;
} braun_cli_monitor;

/* buffer: braun_data_size(model) bytes for the monitor's own scratch. */
int braun_cli_monitor_init(braun_cli_monitor *mon, const braun_model *model,
                           const braun_builtin *builtin, double ref_h,
                           void *buffer, size_t bytes);
/* Measure the state of d (the run's data); 0 or a braun status/-1. */
int braun_cli_monitor_sample(braun_cli_monitor *mon, const braun_data *d);

/* --------------------------------------------------------- CSV (cli_csv.c) */
int braun_cli_csv_header(FILE *f, int n);
int braun_cli_csv_row(FILE *f, int n, double t, const double *q,
                      const double *v, const braun_cli_errors *e, int has_ref);

/* ----------------------------------------------- summary JSON (cli_summary.c) */
typedef struct braun_cli_result {
    const braun_cli_run_args *args;
    const braun_model *model;
    const char *scene;
    const char *method;        /* braun, braun-noenergy, braun-custom */
    braun_stats stats;
    double cpu_s;
    const braun_cli_monitor *mon;
    double final_t;
    const double *final_q, *final_v;
    int status;
} braun_cli_result;

/* Pretty JSON, one key per line; returns 0 or -1 on a write error. */
int braun_cli_write_summary(FILE *f, const braun_cli_result *r);

/* ------------------------------------------------------- timing (cli_clock.c) */
/* CPU time of this process in seconds (CLOCK_PROCESS_CPUTIME_ID). */
double braun_cli_cpu_seconds(void);

/* ------------------------------------------------------------ run (cli_run.c) */
int braun_cli_run(const braun_cli_run_args *a);

#endif /* BRAUN_CLI_H */
