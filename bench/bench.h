/* make bench (issue 7): what a step of libbraun costs, against baselines
 * measured in the same process. Private to the bench program; see
 * docs/performance.md for what is measured and how the figures are read. */
#ifndef BENCH_H
#define BENCH_H

#include <stdio.h>

#include "braun.h"
#include "braun_models.h"
#include "braun_scene_file.h"

/* Linear-algebra backend the rows were measured with. Only the built-in
 * dense kernels exist today; a LAPACK or SuiteSparse build reports its own
 * name here and the tables gain rows, not columns. */
#ifndef BENCH_BACKEND
#define BENCH_BACKEND "dense"
#endif

/* What one timing block measures. */
typedef enum bench_item {
    BENCH_STEP_NONE = 0, /* braun_step, RK4, corrections off: the ideal index-1 step */
    BENCH_STEP_PV,       /* braun_step, position + velocity corrections */
    BENCH_STEP_ALL,      /* braun_step, every correction the system supports */
    BENCH_STEP_FREE,     /* braun_step on the same bodies with no constraint rows */
    BENCH_STEP_FLOOR,    /* RK4 on the minimal-coordinate equation (floor) */
    BENCH_STEP_SPECIAL,  /* the ideal step written out for the slider-crank (bench_special.c) */
    BENCH_RHS_IDEAL,     /* braun_eval, corrections off (Udwadia–Kalaba) */
    BENCH_RHS_CORR,      /* braun_eval, every correction (Eqs. 16, 17, 20) */
    BENCH_RHS_FLOOR,     /* the minimal equation's right-hand side */
    BENCH_ITEMS
} bench_item;

/* Item names in CSV files and on the command line. */
const char *bench_item_name(bench_item it);
/* "step" or "rhs". */
const char *bench_item_kind(bench_item it);
/* Item from its name; -1 if unknown. */
int bench_item_from_name(const char *name);

/* A mechanism to measure: a system, its initial state and, when it has one,
 * the minimal-coordinate equation of the floor. */
typedef struct bench_target {
    char name[96];               /* as given: built-in name, "andrews" or a path */
    const char *source;          /* "built-in", "record" or "scene" */
    braun_system sys;
    braun_real *q0, *v0;         /* n each (owned) */
    const braun_builtin *minimal;/* minimal equation for the floor, or NULL */
    double h;                    /* step used by every item */
    braun_scene_file *scene;     /* owned, or NULL */
} bench_target;

/* Open a target by name: a built-in model (braun_models.h), "andrews"
 * (braun_scene.h) or a scene file (*.json or a path). Returns 0, or -1 after
 * writing a message to err. */
int bench_target_open(const char *name, bench_target *tg, char *err, size_t errsize);
void bench_target_close(bench_target *tg);

/* Corrections of an item for this system (energy only if it has a law). */
unsigned bench_item_corrections(const bench_target *tg, bench_item it);

/* ---------------------------------------------------------------- runs */
/* Everything one target needs to run every item, set up before timing:
 * one workspace per configuration, recorded states for the right-hand
 * sides, the floor's state. */
typedef struct bench_run bench_run;

/* steps: steps per block (every block starts from the initial state).
 * Returns NULL after writing a message to err. */
bench_run *bench_run_new(const bench_target *tg, long steps, char *err, size_t errsize);
void bench_run_free(bench_run *r);
/* Whether the item exists for this target (the floor needs a minimal
 * equation). */
int bench_run_has(const bench_run *r, bench_item it);
/* How far the specialised floor's trajectory ended from the library's ideal
 * step's over one block (relative to the largest entry of q and v); NaN
 * where it does not apply. */
double bench_run_special_agreement(const bench_run *r);
/* Reset the item's state to the start of a block (not timed). */
void bench_run_reset(bench_run *r, bench_item it);
/* Run one block of the item: `steps` steps or right-hand sides. Returns
 * the number of operations done (fewer if a step failed; *status says why). */
long bench_run_block(bench_run *r, bench_item it, int *status);

/* The floor (bench_floor.c, its own file so that these stay real calls
 * whatever the optimiser does): one classic RK4 step of the minimal
 * equation y' = f(t, y), and one evaluation of f. */
void bench_floor_step(const braun_builtin *b, double t, double h, double *y);
void bench_floor_rhs(const braun_builtin *b, double t, const double *y, double *dydt);

/* The specialised floor (bench_special.c): libbraun's ideal RK4 step of the
 * slider-crank written out by hand, y = (q, v), 12 entries. */
void bench_special_step(const braun_link_params *p, double h, double *y);

/* ---------------------------------------------------------------- timing */
/* Process CPU time in nanoseconds. */
double bench_cpu_ns(void);

/* ---------------------------------------------------------------- flops */
/* Floating-point operations of one RK4 step (per-step corrections) as
 * derived from the code (docs/performance.md gives the formulas), split by
 * component. Written as CSV rows "target,item,component,flops". */
int bench_flops_write(FILE *out, const bench_target *tg);
/* Rank of the constraint rows and flops of one solve with R^T and with R
 * at the initial state. Returns 0, or -1 out of memory. */
int bench_flops_shape(const bench_target *tg, long *rank, long *solve_rt, long *solve_r);

/* ---------------------------------------------------------------- compare */
/* Cost per simulated second at matched trajectory error, from the CSV of
 * make compare (results/compare/runs.csv). Returns 0, 1 if the file is
 * missing (a note is written instead), -1 on a read error. */
int bench_matched_write(FILE *out, const char *runs_csv, const double *levels, int nlevels);

#endif
