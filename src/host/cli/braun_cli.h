/* Private to the braun command-line tool: what the files of src/cli share. */
#ifndef BRAUN_CLI_H
#define BRAUN_CLI_H

#include <stdio.h>

#include "braun.h"
#include "braun_reference.h"
#include "braun_scene_file.h"

/* Exit statuses: the solver failed at run time / the command line is wrong. */
enum { BRAUN_CLI_FAILED = 1, BRAUN_CLI_USAGE = 2 };

/* s starts as a decimal number does: an optional sign, then a digit or
 * '.', and not "0x" (cli_real.c). */
int braun_cli_decimal(const char *s);
/* s starts with a blank or is a hexadecimal number ("0x", "-0X"): what
 * strtod takes and a decimal number is not. */
int braun_cli_hex_or_blank(const char *s);
/* s is a decimal integer and nothing else: an optional sign, then digits
 * (cli_real.c). strtol alone also takes leading blanks (gen chain ' 3'),
 * which a real option refuses. */
int braun_cli_integer_text(const char *s);

/* A built-in model's name (the library's or the tool's own: andrews). */
int braun_cli_is_model_name(const char *arg);

/* From this many coordinates on, run (on the dense kernels) and check say
 * on stderr that a step or the analysis costs O(n³): a 500-link chain
 * takes about 2 s per dense step, against milliseconds with --sparse
 * --backend suitesparse. */
#define BRAUN_CLI_DENSE_NOTE_N 600

/* Print "braun: <message>" on stderr as one line; returns BRAUN_CLI_USAGE
 * so argument errors read `return braun_cli_error(...)`. */
int braun_cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* ------------------------------------------------------ numbers (cli_number.c) */
/* The shortest decimal that reads back as the same double ("0.1", not
 * "0.10000000000000001"); "nan", "inf", "-inf" for the others. buf:
 * BRAUN_CLI_NUMBER_SIZE bytes. Returns buf. */
#define BRAUN_CLI_NUMBER_SIZE 32
const char *braun_cli_number(double x, char *buf);
void braun_cli_put_number(FILE *f, double x);

/* ------------------------------------------------------------ texts (cli_text.c) */
/* A scene's text (name, description) as printed on a line people or
 * scripts read: control bytes as \xNN, a backslash as \\ (what braun check
 * prints); braun_cli_text_byte: one byte so escaped into buf (5 bytes). */
void braun_cli_put_text(FILE *f, const char *s);
const char *braun_cli_text_byte(unsigned char c, char *buf);
/* Control bytes of s as '?', in place: one line, as error messages and the
 * trajectory CSV's header write a scene's names (cli_error.c, cli_csv.c). */
void braun_cli_mask_controls(char *s);
/* "BRAUN_ERR_DIVERGED" out of braun_status_str's "BRAUN_ERR_DIVERGED: ...":
 * into buf, which it returns. */
const char *braun_cli_status_name(int status, char *buf, size_t size);

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
typedef struct braun_cli_output braun_cli_output;
struct braun_cli_output {
    FILE *f;
    const char *path, *what;
    int created;                  /* made by this command: removed if abandoned */
    int err;                      /* errno of the first failed write, 0 if none seen */
    braun_cli_id id;
    int whole;                    /* written to tmp, renamed onto final when complete */
    int committed;                /* closed or put in place: abandon leaves it */
    char *tmp, *final;            /* while written whole: the temporary file, its target */
};

/* Option argv[*i] of the commands with their own parsers (gen, gen-c), as
 * run's: its name ("--symbol" of "--symbol=x") into name; with val, its
 * value — after '=' or the next argument (*i moves on) — and "needs a
 * value" when there is none; without, the name alone. 0, or
 * BRAUN_CLI_USAGE after one message. */
int braun_cli_option(int argc, char **argv, int *i, char *name, size_t size, const char **val);
/* An option given twice is refused, as run refuses it: canon (its one
 * name, "-o" for "--out" too) against the seen[] so far (cap entries). */
int braun_cli_option_once(const char *canon, const char *name, const char **seen, int *nseen,
                          int cap);

/* 0, or BRAUN_CLI_USAGE after one message. */
int braun_cli_output_open(braun_cli_output *o, const char *path, const char *what);
/* The same for an output written whole (gen, gen-c, plot -o): a regular
 * file is written to a temporary file in its directory (begin) and renamed
 * onto it when complete (close, or complete then commit), so a failed
 * write leaves the file as it was (removed if this command made it). A
 * directory that takes no new file: written in place. */
int braun_cli_output_open_whole(braun_cli_output *o, const char *path, const char *what);
/* Refuse (BRAUN_CLI_USAGE, one message) two outputs that are one file, or
 * an output that is the input (either output may be NULL or unopened). */
int braun_cli_output_distinct(braun_cli_output *a, braun_cli_output *b,
                              const braun_cli_id *input, const char *input_path);
/* After the checks: truncate a regular file, or make the temporary file
 * of one written whole. 0, BRAUN_CLI_USAGE, or BRAUN_CLI_FAILED when no
 * temporary file can be made (after one message). */
int braun_cli_output_begin(braun_cli_output *o);
/* After a write that returned an error: keep errno for the message. */
void braun_cli_output_failed(braun_cli_output *o);
/* Flush and close; 1 after "error writing 'FILE': reason", else 0. An
 * output written whole is then renamed into place, or on an error left as
 * it was. */
int braun_cli_output_close(braun_cli_output *o);
/* close in two halves, for outputs that are kept together (gen-c's source
 * and header): complete flushes and closes the file (1 after the message,
 * and the caller abandons), commit puts one written whole in place (1
 * after a message if it cannot). */
int braun_cli_output_complete(braun_cli_output *o);
int braun_cli_output_commit(braun_cli_output *o);
/* Close without writing; remove the temporary file, and the file if this
 * command made it. */
void braun_cli_output_abandon(braun_cli_output *o);

/* A regular file's text (NUL-terminated, *len bytes) of at most max
 * bytes, opened without blocking; NULL with one line "FILE: why" in err. */
char *braun_cli_read_file(const char *path, size_t max, size_t *len, char *err, size_t size);

/* ---------------------------------------------------------- usage (cli_usage.c) */
void braun_cli_usage(FILE *f);
/* --help or -h among the arguments after command cmd: alone, the usage on
 * stdout and -1; beside any other argument a usage error (BRAUN_CLI_USAGE
 * after one message); 0 when not asked. */
int braun_cli_help_asked(const char *cmd, int argc, char **argv);

/* ------------------------------------------------ real values (cli_real.c) */
/* A real option's value: a finite double filling s, neither beyond a
 * double's range nor nonzero below its smallest normal value (it would
 * underflow). 0, or BRAUN_CLI_USAGE after one message naming opt. */
int braun_cli_parse_real(const char *opt, const char *s, double *out);

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
    long max_steps;             /* --max-steps: dopri5's attempts; a fixed-step run's steps */
    int max_steps_given;
    double ref_h;               /* 0: reference default */
    const char *out_path;       /* CSV trajectory, NULL for none; "-" stdout */
    long every;                 /* CSV row every K steps */
    int every_given;            /* --every was given (it needs --out) */
    const char *summary_path;   /* "-" for stdout */
    const char *backend;        /* --backend: dense | lapack | suitesparse | auto */
    int sparse;                 /* --sparse: the scene's sparsity (braun_scene_build_sparse) */
    double guard;               /* --guard: 0 library default (1e-3), < 0 off */
    double soft_tol;            /* --soft-tol: 0 library default (1e-4), < 0 off */
    int progress;               /* -1: when stderr is a terminal; 0: --quiet; 1: --progress */
    int timing;                 /* run the timed run (cpu_s); braun plot does not */
    int run_given;              /* an option of the simulation was given (plot --traj refuses) */
    struct braun_cli_output *plot_output; /* braun plot's -o, to keep outputs distinct */
    /* braun plot only (cli_plot.c). */
    const char *plot_path;      /* -o FILE: .svg, .html or .png */
    const char *traj_path;      /* --traj CSV: draw this trajectory instead of running */
    const char *points;         /* --points A,B: paths of these points */
    const char *plot_columns;   /* --plot x,y: coordinates against time */
    long frames;                /* --frames K: configurations of a stroboscopic view */
    double from;                /* --from T: draw from this time on (NaN: the start) */
    long samples;               /* --samples N: states kept for paths and animations */
    const char *view;           /* --view PLANE: xy (default), xz, yz, ... */
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

/* --max-steps' default: the adaptive driver's own (braun_adaptive), which
 * bounds a fixed-step run too (checked before it starts). */
#define BRAUN_CLI_MAX_STEPS 100000000L

/* dopri5's minimum step from t = 0 to t_end as braun_integrate_adaptive
 * takes it by default: 1e-12 t_end, at least 16 eps t_end (float: the
 * latter). */
double braun_cli_adaptive_h_min(double t_end);

/* The steps braun_integrate takes from t = 0 to t_end with step h. */
double braun_cli_fixed_steps(double h, double t_end);

/* Parse the arguments after "run" (plot = 0) or "plot" (plot = 1: also
 * the plot options; --dt and --t-end not needed with --traj; --help is the
 * caller's, braun_cli_help_asked). Returns 0 to run, else BRAUN_CLI_USAGE
 * after one message. */
int braun_cli_parse_run(int argc, char **argv, braun_cli_run_args *a, int plot);

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

/* ------------------------------------------------------- rows (cli_rows.c) */
/* The element of a scene file that owns row `row` of [Φ_q; Φ_v] (the
 * nonholonomic rows after the m holonomic ones), as its file names it:
 * "joint 'knee' (revolute)", "joint #3 (distance)", "rod #2",
 * "body 'b' (rigid3d: its own constraint)", "joint 'blade' (knife)"; NULL
 * without a scene or past its rows. */
const char *braun_cli_row_owner(const braun_scene_file *sf, int row, char *buf, size_t size);

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
    /* The scene that names and draws the coordinates: the scene itself, or
     * the equivalent scene of a built-in model (slider-crank, four-bar,
     * pendulum: braun_cli_builtin_scene), or NULL (q[i]). */
    braun_scene_file *drawing;
    const char *drawing_text;     /* a built-in's scene text (for its point names), or NULL */
    braun_cli_id id;              /* the scene file's identity (outputs must differ) */
    char path_buf[4096];          /* a shipped scene found by name (braun_cli_data_file) */
    /* The scene's reported points that have CSV columns of their own, by
     * index into its report_names (braun_cli_report_columns). */
    int *reports;
    int nreports;
} braun_cli_target;

/* The one place that maps MODEL to a target: a built-in name (braun list)
 * or a scene file (a name ending in .json or containing '/'). Returns 0, or
 * prints why ("braun: FILE:LINE:COL: ...") and returns BRAUN_CLI_USAGE. */
int braun_cli_target_open(const char *arg, braun_cli_target *t);
void braun_cli_target_close(braun_cli_target *t);

/* The JSON text of a built-in model's equivalent scene, or NULL
 * (cli_builtin_scenes.c). */
const char *braun_cli_builtin_scene(const char *name);

/* The shipped scenes' directory (cli_datadir.c): $BRAUN_DATA_DIR, else
 * share/braun/data beside the executable's bin/; NULL if there is none. */
const char *braun_cli_data_dir(void);
/* 1 and its path when NAME (or NAME.json) is a shipped scene, else 0. */
int braun_cli_data_file(const char *name, char *path, size_t size);
/* Calls fn for each shipped scene, in name order; returns how many. */
/* 1 if path is a directory this process can list. */
int braun_cli_is_directory(const char *path);
int braun_cli_data_each(void (*fn)(const char *path, void *user), void *user);

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

/* Residuals beside the monitored run: measure a state, then accept it (its
 * errors join the maxima) once it is known to have passed the guard. */
int braun_cli_monitor_measure(braun_cli_monitor *mon, const braun_data *d, braun_cli_errors *e);
void braun_cli_monitor_accept(braun_cli_monitor *mon, const braun_cli_errors *e);

/* ---------------------------------------------------- columns (cli_columns.c) */
/* Name of coordinate i (velocity: its velocity) of a target: "crank.x",
 * "crank.vx", "q[3]", with its unit ("m", "rad/s", NULL if unknown). */
const char *braun_cli_coord_name(const braun_cli_target *t, int i, int velocity, char *name,
                                 size_t size, const char **unit);
/* Columns of the trajectory CSV: t, q (n), v (n), pos_err, vel_err,
 * energy_err, traj_err (braun_cli_column_count: the state's columns, what
 * braun plot keeps), then a scene's reported points NAME.x, NAME.y (NAME.z
 * when spatial; braun_cli_report_dim: 0 without any). Name and unit of
 * column j (NULL past the end). */
int braun_cli_column_count(int n);
int braun_cli_csv_column_count(const braun_cli_target *t, int n);
int braun_cli_report_dim(const braun_cli_target *t);
const char *braun_cli_column_name(const braun_cli_target *t, int n, int j, char *name,
                                  size_t size, const char **unit);
/* Set t->reports: every reported point of t's scene but those that are a
 * body itself under the body's own name ({"P1": "P1"}, as the IFToMM
 * scenes report their particle), whose NAME.x, NAME.y are the body's own
 * columns already, with the same values. 0, or -1 out of memory. */
int braun_cli_report_columns(braun_cli_target *t);
/* A column name's buffer: every column of a scene's CSV fits it whole
 * (braun_cli_columns_distinct refuses a scene whose names do not). */
#define BRAUN_CLI_COLUMN_NAME 160
/* 0 when every column of t's trajectory CSV has a name of its own, as the
 * header writes it and whole; else the message (braun_cli_error), naming
 * the columns. */
int braun_cli_columns_distinct(const braun_cli_target *t);
/* Index of the state column called want (its " [unit]" optional), or -1;
 * reported points are not among them (braun plot draws them as points). */
int braun_cli_column_find(const braun_cli_target *t, int n, const char *want);

/* --------------------------------------------------------- CSV (cli_csv.c) */
/* Both return -1 when the stream has failed so far. They do not flush (a
 * flush per row is a write per row): what is still buffered fails at
 * braun_cli_output_complete, which flushes and reports it. */
int braun_cli_csv_header(FILE *f, const braun_cli_target *t, int n);
/* tg: for the scene's reported points (NAME.x, NAME.y, NAME.z after the
 * other columns), may be NULL. */
int braun_cli_csv_row(FILE *f, const braun_cli_target *tg, int n, double t, const double *q,
                      const double *v, const braun_cli_errors *e, int has_ref);

/* ------------------------------------------- accuracy guard (cli_accuracy.c) */
/* The bounds the core's accuracy guard applied in a run (read after it):
 * NaN where a residual is not checked (its correction off, or the guard). */
typedef struct braun_cli_bounds {
    int on;                            /* options.guard >= 0 */
    double guard;                      /* the relative guard (default 1e-3) */
    double pos, vel, energy;           /* bounds on the three residuals */
    double pos_scale, vel_scale, energy_scale; /* braun_data.guard */
} braun_cli_bounds;
void braun_cli_guard_bounds(const braun_data *d, braun_cli_bounds *b);

/* How a monitored run ended, beyond its status. */
typedef struct braun_cli_stop {
    braun_cli_bounds bounds;
    int dropped;              /* the guard refused a state (BRAUN_ERR_ACCURACY) ... */
    double dropped_t;         /* ... at this time: never reported, not in the CSV */
} braun_cli_stop;

/* ----------------------------------------------- summary JSON (cli_summary.c) */
typedef struct braun_cli_result {
    const braun_cli_run_args *args;
    const braun_cli_target *target;
    const braun_model *model;
    const char *scene;
    const char *method;        /* braun, braun-noenergy, braun-custom */
    braun_stats stats;
    double cpu_s;              /* the timed run (no monitoring); NaN if not timed */
    int interrupted;           /* the signal that stopped the monitored run, or 0 */
    double cpu_monitored_s;    /* the monitored run, monitoring and output included */
    const braun_cli_monitor *mon;
    const char *backend;       /* linear solver used (braun_linsolver_name) */
    int sparse;                /* the system had a sparsity */
    double final_t;            /* the last state that passed */
    const double *final_q, *final_v;
    int status;
    double error_t;            /* time of the failing evaluation (d->error.t), or NaN */
    braun_cli_stop stop;
} braun_cli_result;

/* Pretty JSON, one key per line; returns 0 or -1 on a write error. */
int braun_cli_write_summary(FILE *f, const braun_cli_result *r);
/* The one line for people (cli_human.c): status, time reached, steps, CPU
 * time, the largest errors and the guard's bounds. */
void braun_cli_write_human(FILE *f, const braun_cli_result *r);

/* -------------------------------------------------- progress (cli_progress.c) */
typedef struct braun_cli_progress {
    int enabled, terminal, shown;
    const char *name, *phase;
    double t0, t_end, wall0, last;
} braun_cli_progress;
int braun_cli_stderr_is_terminal(void);
void braun_cli_progress_begin(braun_cli_progress *p, int enabled, const char *name,
                              const char *phase, double t0, double t_end);
void braun_cli_progress_update(braun_cli_progress *p, double t, long steps);
void braun_cli_progress_end(braun_cli_progress *p, double t, long steps);

/* ------------------------------------------ interruption (cli_interrupt.c) */
/* Catch SIGINT and SIGTERM (unless ignored) for a run; restore them. */
void braun_cli_interrupt_begin(void);
void braun_cli_interrupt_end(void);
/* The signal caught since braun_cli_interrupt_begin, or 0. */
int braun_cli_interrupted(void);
/* "SIGINT", "SIGTERM". */
const char *braun_cli_signal_name(int sig);

/* ------------------------------------------------------- timing (cli_clock.c) */
/* CPU time of this process in seconds (CLOCK_PROCESS_CPUTIME_ID). */
double braun_cli_cpu_seconds(void);

/* ------------------------------------------------------------ run (cli_run.c) */
/* What else sees a monitored run: every state that passed, in order, and
 * the result at the end (non-zero return: the command fails). */
typedef struct braun_cli_observer {
    void (*state)(void *user, double t, const double *q, const double *v,
                  const braun_cli_errors *e);
    int (*done)(void *user, const braun_cli_result *r);
    void *user;
} braun_cli_observer;

int braun_cli_run(const braun_cli_run_args *a);
/* The run of an open target; obs may be NULL. */
int braun_cli_run_target(const braun_cli_run_args *a, const braun_cli_target *tg,
                         const braun_cli_observer *obs);

/* `braun plot` (cli_plot.c). */
int braun_cli_plot(int argc, char **argv);

#endif /* BRAUN_CLI_H */
