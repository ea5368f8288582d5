/* Private to the braun command-line tool: what the files of src/cli share. */
#ifndef BRAUN_CLI_H
#define BRAUN_CLI_H

#include <stdio.h>

#include "braun.h"
#include "braun_reference.h"
#include "braun_scene_file.h"

/* Exit statuses: the solver failed at run time / the command line is wrong. */
enum { BRAUN_CLI_FAILED = 1, BRAUN_CLI_USAGE = 2 };

/* Print "braun: <message>" on stderr as one line; returns BRAUN_CLI_USAGE
 * so argument errors read `return braun_cli_error(...)`. */
int braun_cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* ---------------------------------------------------------- files (cli_files.c) */
/* A file's identity (device, inode) when it is a regular file. */
typedef struct braun_cli_id {
    int valid;                    /* a regular file */
    unsigned long long dev, ino;
} braun_cli_id;

/* Identity of the file at path (stat), invalid if none or not regular. */
void braun_cli_path_id(const char *path, braun_cli_id *id);
/* Both regular and the same file. */
int braun_cli_same_file(const braun_cli_id *a, const braun_cli_id *b);
/* "a directory", "a FIFO", ... for an st_mode. */
const char *braun_cli_file_kind(unsigned long mode);

/* An output of a command: "-" is stdout; otherwise a regular file (made if
 * missing) or a character device (/dev/null). Opened without blocking and
 * without truncating; FIFOs, sockets, directories and block devices are
 * refused. what names the option in messages ("--out"). */
typedef struct braun_cli_output {
    FILE *f;
    const char *path, *what;
    int created;                  /* made by this command: removed if abandoned */
    int err;                      /* errno of the first failed write, 0 if none seen */
    braun_cli_id id;
} braun_cli_output;

/* 0, or BRAUN_CLI_USAGE after one message. */
int braun_cli_output_open(braun_cli_output *o, const char *path, const char *what);
/* Refuse (BRAUN_CLI_USAGE, one message) two outputs that are one file, or
 * an output that is the input (either output may be NULL or unopened). */
int braun_cli_output_distinct(braun_cli_output *a, braun_cli_output *b,
                              const braun_cli_id *input, const char *input_path);
/* After the checks: truncate a regular file. 0 or BRAUN_CLI_USAGE. */
int braun_cli_output_begin(braun_cli_output *o);
/* After a write that returned an error: keep errno for the message. */
void braun_cli_output_failed(braun_cli_output *o);
/* Flush and close; 1 after "error writing 'FILE': reason", else 0. */
int braun_cli_output_close(braun_cli_output *o);
/* Close without writing; remove the file if this command made it. */
void braun_cli_output_abandon(braun_cli_output *o);

/* ---------------------------------------------------------- usage (cli_usage.c) */
void braun_cli_usage(FILE *f);

/* ---------------------------------------------------- options (cli_args.c) */
typedef struct braun_cli_run_args {
    const char *model;          /* MODEL argument, as given */
    double dt, t_end;           /* required; dt is h0 for dopri5 */
    braun_method method;        /* default rk4 */
    int corrections_mode;       /* BRAUN_CLI_CORR_* */
    unsigned corrections;       /* braun_corrections bits when given as a list */
    braun_discretization discretization;
    double rank_tol;            /* 0: library default */
    double energy_max_rel;      /* 0: library default */
    double rtol, atol;          /* dopri5 only */
    double ref_h;               /* 0: reference default */
    const char *out_path;       /* CSV trajectory, NULL for none; "-" stdout */
    long every;                 /* CSV row every K steps */
    int every_given;            /* --every was given (it needs --out) */
    const char *summary_path;   /* "-" for stdout */
    const char *backend;        /* --backend: dense | lapack | suitesparse | auto */
    int sparse;                 /* --sparse: the scene's sparsity (braun_scene_build_sparse) */
} braun_cli_run_args;

/* Where the corrections of a run come from. */
enum {
    BRAUN_CLI_CORR_TARGET = 0, /* no option: what the model or scene declares */
    BRAUN_CLI_CORR_ALL = 1,    /* --corrections all: every one it supports */
    BRAUN_CLI_CORR_LIST = 2    /* --corrections LIST or none */
};

/* --ref-h: the integrated references may take at most this many substeps
 * (t_end / ref_h). */
#define BRAUN_CLI_MAX_REF_STEPS 1e9

/* Parse the arguments after "run". Returns 0 to run, -1 when --help was
 * asked (usage already printed), else BRAUN_CLI_USAGE after one message. */
int braun_cli_parse_run(int argc, char **argv, braun_cli_run_args *a);

/* Comma list of the correction names in bits ("none" for 0); buf >= 32. */
const char *braun_cli_corrections_str(unsigned bits, char *buf, size_t size);

/* ---------------------------------------------------- guard (cli_guard.c) */
/* A scene's callbacks wrapped so that a failure can be traced to its
 * element: every call passes through; a failed one (non-zero, or a
 * non-finite output at a finite state) records which joint or effect
 * fails there (braun_scene_file_diagnose) and when. */
typedef struct braun_cli_guard {
    braun_system inner;             /* the scene's own callbacks */
    const braun_scene_file *scene;
    int have;                       /* what and t are set */
    double t;                       /* time of the failed call */
    char what[320];                 /* "effect 'sp' (spring): its forces hook returns 1 ..." */
} braun_cli_guard;

/* *out: sys with every callback through g (sys itself when scene is NULL).
 * g must outlive out. */
void braun_cli_guard_wrap(braun_cli_guard *g, const braun_system *sys,
                          const braun_scene_file *scene, braun_system *out);
/* The element that failed at time t (the core's d->error.t), or NULL. */
const char *braun_cli_guard_element(const braun_cli_guard *g, double t);

/* ------------------------------------------------------ models (cli_model.c) */
/* What a run simulates: a system with its initial state, a name, an
 * optional reference and the corrections it asks for. It comes from a
 * built-in model or from a scene file. */
typedef struct braun_cli_target {
    const char *name;             /* "scene" of the summary */
    const char *source;           /* the scene file, or NULL for a built-in */
    const char *description;
    braun_system sys;
    const braun_real *q0, *v0;
    const braun_builtin *reference; /* minimal-coordinate reference (same q), or NULL */
    unsigned corrections;         /* declared default corrections */
    braun_scene_file *scene;      /* owned when loaded from a file */
    braun_cli_id id;              /* the scene file's identity (outputs must differ) */
} braun_cli_target;

/* The one place that maps MODEL to a target: a built-in name (braun list)
 * or a scene file (a name ending in .json or containing '/'). Returns 0, or
 * prints why ("braun: FILE:LINE:COL: ...") and returns BRAUN_CLI_USAGE. */
int braun_cli_target_open(const char *arg, braun_cli_target *t);
void braun_cli_target_close(braun_cli_target *t);

/* Built-in models of this tool beyond braun_models.h (Andrews). */
int braun_cli_extra_count(void);
const braun_cli_target *braun_cli_extra_at(int i);

/* `braun list`. */
int braun_cli_list(void);

/* `braun check SCENE` (cli_check.c): sizes, rank and residuals at t = 0. */
int braun_cli_check(int argc, char **argv);

/* `braun gen chain N [--rods] [--angle DEG] [-o FILE]`,
 * `braun gen ladder N [--angle DEG] [-o FILE]` (cli_gen.c). */
int braun_cli_gen(int argc, char **argv);

/* braun gen-c SCENE [--symbol NAME] [-o FILE] (cli_gen_c.c). */
int braun_cli_gen_c(int argc, char **argv);

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
    const braun_builtin *builtin; /* whose reference, or NULL */
    braun_reference ref;
    int has_ref, has_point;
    double ref_h;              /* effective reference substep, NaN if none */
    braun_cli_errors cur;      /* at the last sampled state */
    braun_cli_errors max;      /* over every sampled state */
    long samples;
} braun_cli_monitor;

/* buffer: braun_data_size(model) bytes for the monitor's own scratch;
 * builtin: the model whose exact reference the run is compared to, or NULL. */
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
    const char *backend;       /* linear solver used (braun_linsolver_name) */
    int sparse;                /* the system had a sparsity */
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
