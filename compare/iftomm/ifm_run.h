/*
 * braun-iftomm's libbraun side: a shipped scene run with RK4 or DOPRI5, its
 * reported point sampled on the benchmark's output grid, the problems and
 * their settings, and what `make iftomm` writes. The references (ifm.h)
 * include nothing of libbraun.
 */
#ifndef IFM_RUN_H
#define IFM_RUN_H

#include "braun.h"
#include "braun_scene_file.h"
#include "ifm.h"

/* ------------------------------------------------------------ a scene run */
typedef struct ifm_setting {
    braun_method method;   /* BRAUN_RK4 (h) or BRAUN_DOPRI5 (rtol, atol) */
    double h;
    double rtol, atol;
} ifm_setting;

typedef struct ifm_result {
    int status;             /* BRAUN_OK, a libbraun error, or -1 (harness) */
    char status_name[48];
    double t_reached;
    double cpu_s;           /* the integration alone, best of the repetitions */
    long steps, rejected, rhs_evals;
    double max_pos;         /* max ||Φ_q||_2 over the output grid */
    double max_energy_abs;  /* max |Φ_e| (J) over the output grid */
    ifm_series y;           /* the reported quantity on the grid (NaN past a failure) */
} ifm_result;

/* The reported point `name` of a loaded scene: its index in
 * sf->report_points, or -1. */
int ifm_scene_report_index(const braun_scene_file *sf, const char *name);

/* Run sf from its initial state to T, sampling the reported point (its
 * position, and its velocity when velocity is set: width = dim or 2 dim)
 * on the grid t_j = j dt_out: every step records the point's position and
 * velocity, and grid times between two step ends take the cubic Hermite
 * interpolant of them (a grid time that is a step end takes the step's own
 * value: RK4 with h dividing dt_out interpolates nothing). The residuals
 * are taken at the step ends that reach a new output interval. The run is
 * repeated while the repetitions together take less than 0.5 s, at most
 * reps times; the fastest counts (recording included). Returns 0 (the run
 * itself may have failed: res->status), or -1 with why on a harness
 * failure. */
int ifm_braun_run(const braun_scene_file *sf, int report, int dim, int velocity,
                  const ifm_setting *set, double T, double dt_out, int reps, ifm_result *res,
                  char *why, size_t whysize);
void ifm_result_free(ifm_result *res);

/* CPU time of this process [s]; mkdir -p. */
double ifm_cpu_seconds(void);
int ifm_mkdir_p(const char *path);

#endif
