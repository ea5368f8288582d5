/* A scene file run from C (braun_scene_file.h, the host tier: link
 * braun::scene, or pkg-config braun-host): load it, integrate it with RK4
 * and every correction it declares, print its final state and residuals.
 *   scene FILE.json [H [T]]      (defaults: H = 1e-3 s, T = 10 s) */
#include <braun.h>
#include <braun_host.h>
#include <braun_scene_file.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 4) {
        fprintf(stderr, "usage: scene FILE.json [H [T]]\n");
        return 2;
    }
    const double h = argc > 2 ? atof(argv[2]) : 1e-3, t_end = argc > 3 ? atof(argv[3]) : 10;
    char err[512];
    braun_scene_file *f = braun_scene_load(argv[1], err, sizeof err);
    if (!f) {
        fprintf(stderr, "%s\n", err); /* FILE:LINE:COLUMN: what is wrong */
        return 2;
    }
    braun_model model;
    braun_data data = {0}; /* read by braun_error_format whatever step failed */
    const char *problem = NULL;
    int st = braun_model_init(&model, &f->sys);
    /* No data yet to hold the reason: braun_system_check names it (a
     * scene beyond BRAUN_MAX_DENSE coordinates, say). */
    if (st) braun_system_check(&f->sys, &problem);
    else model.opt.corrections &= f->corrections; /* what the file asks for */
    const size_t bytes = st ? 0 : braun_data_size(&model);
    void *buffer = bytes ? malloc(bytes) : NULL;
    if (!st && !buffer) {
        st = BRAUN_ERR_BUFFER;
        problem = "out of memory for the data buffer";
    }
    if (!st) st = braun_data_init(&data, &model, buffer, bytes);
    if (!st) st = braun_set_state(&data, 0, f->q0, f->v0);
    if (!st) st = braun_integrate(&data, BRAUN_RK4, (braun_real)h, (braun_real)t_end, 0, NULL, NULL);
    braun_real pos = 0, vel = 0, en = 0;
    if (!st) st = braun_residuals(&data, data.t, data.q, data.v, &pos, &vel, &en);
    if (st) {
        char why[256];
        if (problem) snprintf(why, sizeof why, "%s", problem);
        else braun_error_format(&data, why, sizeof why); /* where and why, one sentence */
        fprintf(stderr, "%s: %s (%s)\n", f->name, why, braun_status_str(st));
    } else {
        printf("%s: t = %g, %ld steps, |Phi_q| = %.1e, |Phi_e| = %.1e, q =", f->name,
               (double)data.t, data.stats.steps, (double)pos, (double)en);
        for (int i = 0; i < f->scene.n; i++) printf(" %.9f", (double)data.q[i]);
        printf("\n");
    }
    free(buffer);
    braun_scene_free(f);
    return st ? 1 : 0;
}
