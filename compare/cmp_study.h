/* The study driver (cmp_study.c) and the report (cmp_report.c). */
#ifndef CMP_STUDY_H
#define CMP_STUDY_H

#include "cmp.h"

#define CMP_MAX_SCENES 32

typedef struct cmp_study_opts {
    const char *study;                     /* "default" or "quick" */
    const char *scenes[CMP_MAX_SCENES];
    int nscenes;
    int methods[CMP_METHOD_COUNT];         /* 1: run this method */
    int reps;                              /* k of best-of-k CPU time */
    int probe;                             /* 1: the IDA settings probe too */
    const char *out_dir;
    /* One step of a parallel study (compare/run.sh): -1, or the index of a
     * (scene, horizon) group to prepare (singular.csv, references.csv, the
     * reference saved in refdir) or of one run (its rows, the reference
     * loaded from refdir). Indices are those of cmp_study_plan. */
    int prepare, job;
    const char *refdir;
    double t0;                             /* study start (time(NULL)), 0: now */
} cmp_study_opts;

/* The scenes a study runs when none are named (space separated). */
const char *cmp_default_scenes(const char *study);

/* Run the study into out_dir/{runs,history,references,ida_probe,singular}.csv
 * with a progress line per run on stderr; with o->prepare or o->job set, one
 * step of it (the files hold that step's rows). 0 or 1. */
int cmp_study_run(const cmp_study_opts *o);

/* The steps of the study on f, in the order of the serial run: a line
 * "prepare G T" per (scene, horizon) group, then "job K G" per run of it. */
int cmp_study_plan(const cmp_study_opts *o, FILE *f);

/* Column lists (docs/compare.md documents each column). */
extern const char *const cmp_runs_header;
extern const char *const cmp_history_header;
extern const char *const cmp_references_header;
extern const char *const cmp_singular_header;
extern const char *const cmp_targets_header;
extern const char *const cmp_trace_header;
extern const char *const cmp_step_cost_header;
/* The CSV files a study writes, space separated, in merge order. */
extern const char *const cmp_study_files;

/* Write dir/report.md from the CSV files in dir. 0 or 1. */
int cmp_report_write(const char *dir);

#endif
