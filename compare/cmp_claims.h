/* The paper's claims as data (cmp_claims.c): each row of cmp_claims[] is
 * the paper's sentence, a figure (a named function that measures one or
 * two quantities over the runs: one value per scene, horizon, pair of
 * runs or cell) and a rule (tests "statistic of the values, compared with
 * a threshold"), and one loop judges every row the same way. The
 * thresholds live in the table only. docs/compare.md, "The report". */
#ifndef CMP_CLAIMS_H
#define CMP_CLAIMS_H

#include <stddef.h>
#include <stdio.h>

#include "cmp_runs.h"

#define CMP_FIG_MAX 256 /* values per quantity */
#define CMP_FIG_QUANTITIES 2
#define CMP_CLAIM_TESTS 3
#define CMP_NPAPER 2   /* the paper's scenes: slider-crank, four-bar */
#define CMP_NHORIZON 2 /* their horizons: 100 s, 1000 s */

/* Over a quantity's values: the largest, the median, the smallest, the
 * mean. A maximum can be decided by one spike, a median cannot. */
typedef enum cmp_stat { CMP_MAX, CMP_MEDIAN, CMP_MIN, CMP_MEAN } cmp_stat;
/* CMP_NONE: no test (the rest of the row's tests are unused). */
typedef enum cmp_op { CMP_NONE, CMP_LT, CMP_LE, CMP_GE, CMP_GT } cmp_op;

/* One test of a rule: stat(values of quantity q) op threshold. */
typedef struct cmp_test {
    int q;
    cmp_stat stat;
    cmp_op op;
    double threshold;
} cmp_test;

/* What a figure measured: the values of its quantities and the evidence
 * the report prints (text, then the rule, then note). */
typedef struct cmp_fig {
    int cases; /* scenes, horizons, pairs or cells found; 0: not tested */
    unsigned scenes; /* bit i: a case on paper scene i (slider-crank, four-bar) */
    unsigned cells;  /* bit i * CMP_NHORIZON + t: a case on scene i at horizon t */
    int n[CMP_FIG_QUANTITIES];
    double v[CMP_FIG_QUANTITIES][CMP_FIG_MAX];
    char text[1024];
    char note[512];
    int hide_rule; /* runs missing: the evidence says so, without the rule */
} cmp_fig;

/* What a rule quantifies over: a claim judged "on both paper scenes" or
 * "on every paper scene and horizon" is not tested while a scene (or a
 * horizon of one) has no case, whatever the others show. */
typedef enum cmp_need { CMP_NEED_CASE, CMP_NEED_SCENES, CMP_NEED_CELLS } cmp_need;

struct cmp_claim;
typedef void cmp_figure_fn(const cmp_rows *d, const struct cmp_claim *c, cmp_fig *f);

typedef struct cmp_claim {
    const char *claim;        /* the paper's sentence */
    const char *paper;        /* where the paper makes it */
    cmp_figure_fn *figure;    /* what is measured */
    const char *figure_name;
    double arg[2];            /* the figure's own parameters (see the figure) */
    cmp_test test[CMP_CLAIM_TESTS]; /* confirmed if every test holds */
    const char *rule;         /* the rule as the report states it; %1, %2, %3:
                                 the thresholds of tests 0, 1, 2. NULL: the
                                 evidence states it */
    cmp_need need;            /* the cases the rule needs all of */
    const char *needs;        /* the runs the figure reads, in words */
    const char *methods;      /* their methods (runs.csv), space-separated: a
                                 claim not tested lists the runs of these
                                 that the study has */
} cmp_claim;

extern const cmp_claim cmp_claims[];
extern const int cmp_nclaims;

/* The statistic of n values. Any NaN gives NaN (a test then fails). No
 * values: max 0, min +inf, median and mean NaN. */
double cmp_stat_of(const double *x, int n, cmp_stat s);
const char *cmp_stat_name(cmp_stat s);

/* Judge one claim: 1 confirmed, -1 refuted (a test does not hold), 0 not
 * tested (the figure found no cases, or not every scene or horizon its
 * rule needs: the evidence says which are missing and what ran). f gets the figure, evidence (size
 * bytes) the report's evidence cell: the figure's text, the rule with its
 * thresholds, the note. */
int cmp_claim_eval(const cmp_claim *c, const cmp_rows *d, cmp_fig *f, char *evidence, size_t size);

/* The report's section: every row of cmp_claims[] with its verdict. */
void cmp_claims_section(FILE *md, const cmp_rows *d);
/* The table, one row per line: claim, paper, figure, tests, the rule as
 * stated; tab-separated (braun-compare claims). */
void cmp_claims_print(FILE *f);

#endif
