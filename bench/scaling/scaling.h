/* braun-scaling (issue 7): cost per step against the number of bodies N for
 * every linear-algebra backend and for IDA+KLU, and cost per simulated second
 * at equal trajectory error at one N (docs/performance.md, "Large systems"). */
#ifndef BRAUN_SCALING_H
#define BRAUN_SCALING_H

#include "braun.h"
#include "braun_backends.h"
#include "braun_scene_file.h"

/* A generated scene (braun gen chain|ladder N) loaded with its sparse system. */
typedef struct sc_scene {
    braun_scene_file *file;
    braun_system sys;        /* sparse callbacks (braun_scene_build_sparse) */
    void *sparse_buf;
    int N;
} sc_scene;

int sc_scene_load(sc_scene *s, const char *path, char *err, size_t errsize);
void sc_scene_free(sc_scene *s);

/* A braun simulation of a scene with one backend (all corrections, RK4). */
typedef struct sc_sim {
    braun_model model;
    braun_data data;
    void *buf;
    const braun_linsolver *ls;
} sc_sim;

int sc_sim_open(sc_sim *m, const sc_scene *s, const char *backend, char *err, size_t errsize);
void sc_sim_close(sc_sim *m);

double sc_cpu_seconds(void);

/* IDA+KLU (compare harness): runs in scaling_ida.c. */
typedef struct sc_ida_result {
    int ok;
    long steps, rhs_evals, jac_evals;
    double cpu_s, t_reached;
} sc_ida_result;

/* Integrate the scene with IDA (GGL, KLU, analytic sparse Jacobian) to T at
 * rtol (atol = rtol; multipliers out of the error test), constraint rows
 * regularised by reg (0: none; redundant rows need it); with samples > 0
 * also store q at t_k = k·T/samples, k = 1..samples, into q_out
 * (samples x n). max_steps: per output interval (0: 100000). CPU time
 * includes IDA's setup. */
int sc_ida_run(const sc_scene *s, double T, double rtol, double reg, long max_steps,
               int samples, double *q_out, sc_ida_result *res);

#endif
