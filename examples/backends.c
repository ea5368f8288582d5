/* A chain of 30 pendulum links built as a scene in C (braun_scene.h, no
 * file) and run with the LAPACK backend when it is built in, else with
 * libbraun's own kernels (braun_backends.h: link braun::backends, or
 * pkg-config braun-backends). Prints the backend and the residuals. */
#include <braun.h>
#include <braun_backends.h>
#include <braun_scene.h>
#include <stdio.h>
#include <stdlib.h>

#define LINKS 30

int main(void)
{
    static braun_scene_body bodies[LINKS];
    static braun_scene_point points[2 * LINKS + 1];
    static braun_scene_joint joints[LINKS];
    static braun_scene_effect gravity[1];
    /* Rigid links of 1 m and 1 kg, horizontal, at rest; each has its ends
     * at -0.5 and 0.5; joint k pins link k's left end to link k-1's right
     * end (the first to the origin). */
    for (int k = 0; k < LINKS; k++) {
        bodies[k] = (braun_scene_body){.kind = BRAUN_BODY_RIGID, .mass = 1, .inertia = 1.0 / 12,
                                       .q0 = {(braun_real)(k + 0.5), 0, 0}};
        points[2 * k] = (braun_scene_point){.body = k, .x = -0.5, .y = 0};
        points[2 * k + 1] = (braun_scene_point){.body = k, .x = 0.5, .y = 0};
        joints[k] = (braun_scene_joint){.type = BRAUN_JOINT_REVOLUTE, .a = 2 * k,
                                        .b = k ? 2 * k - 1 : 2 * LINKS};
    }
    points[2 * LINKS] = (braun_scene_point){.body = BRAUN_SCENE_GROUND, .x = 0, .y = 0};
    gravity[0] = (braun_scene_effect){.type = BRAUN_EFFECT_GRAVITY, .g = {0, (braun_real)-9.81}};
    braun_scene s = {.nbodies = LINKS, .bodies = bodies, .npoints = 2 * LINKS + 1, .points = points,
                     .njoints = LINKS, .joints = joints, .neffects = 1, .effects = gravity};
    braun_system sys;
    braun_scene_error err;
    int st = braun_scene_build(&s, &sys, &err);
    if (st) {
        fprintf(stderr, "scene: %s\n", err.what ? err.what : braun_status_str(st));
        return 1;
    }
    const braun_linsolver *ls = NULL;
    const char *why = NULL;
    if (braun_linsolver_select("lapack", &sys, &ls, &why) != BRAUN_OK) ls = NULL; /* not built in */
    braun_model model;
    braun_data data = {0};
    st = braun_model_init(&model, &sys);
    model.opt.linsolver = ls; /* before braun_data_size */
    const size_t bytes = st ? 0 : braun_data_size(&model);
    void *buffer = bytes ? malloc(bytes) : NULL;
    braun_real *q0 = malloc(sizeof *q0 * (size_t)sys.n), *v0 = malloc(sizeof *v0 * (size_t)sys.n);
    if (!st && (!buffer || !q0 || !v0)) st = BRAUN_ERR_BUFFER;
    if (!st) braun_scene_initial_state(&s, q0, v0);
    if (!st) st = braun_data_init(&data, &model, buffer, bytes);
    if (!st) st = braun_set_state(&data, 0, q0, v0);
    if (!st) st = braun_integrate(&data, BRAUN_RK4, (braun_real)1e-3, (braun_real)0.5, 0, NULL, NULL);
    braun_real pos = 0, vel = 0, en = 0;
    if (!st) st = braun_residuals(&data, data.t, data.q, data.v, &pos, &vel, &en);
    if (st) fprintf(stderr, "chain: %s\n", braun_status_str(st));
    else
        printf("chain of %d links (n = %d) with %s: t = %g, |Phi_q| = %.1e, |Phi_e| = %.1e\n", LINKS,
               sys.n, braun_linsolver_name(ls), (double)data.t, (double)pos, (double)en);
    braun_data_release(&data); /* what the backend allocated */
    free(buffer);
    free(q0);
    free(v0);
    return st ? 1 : 0;
}
