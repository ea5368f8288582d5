/* Scenes and simulations of the scaling study. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scaling.h"
#include "braun_scene_file.h"

double sc_cpu_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return -1.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sc_scene_load(sc_scene *s, const char *path, char *err, size_t errsize)
{
    memset(s, 0, sizeof *s);
    s->file = braun_scene_load(path, err, errsize);
    if (!s->file) return -1;
    size_t bytes = braun_scene_sparse_size(&s->file->scene);
    s->sparse_buf = bytes ? malloc(bytes) : NULL;
    braun_scene_error e;
    if (!s->sparse_buf ||
        braun_scene_build_sparse(&s->file->scene, &s->sys, s->sparse_buf, bytes, &e) != BRAUN_OK) {
        snprintf(err, errsize, "%s: no sparse system (scene with rods?)", path);
        sc_scene_free(s);
        return -1;
    }
    return 0;
}

void sc_scene_free(sc_scene *s)
{
    if (s->file) braun_scene_free(s->file);
    free(s->sparse_buf);
    memset(s, 0, sizeof *s);
}

int sc_sim_open(sc_sim *m, const sc_scene *s, const char *backend, char *err, size_t errsize)
{
    memset(m, 0, sizeof *m);
    const char *why = NULL;
    int st = braun_linsolver_select(backend, &s->sys, &m->ls, &why);
    if (st) {
        snprintf(err, errsize, "backend %s: %s", backend, why ? why : braun_status_str(st));
        return st;
    }
    st = braun_model_init(&m->model, &s->sys);
    if (st) {
        snprintf(err, errsize, "braun_model_init: %s", braun_status_str(st));
        return st;
    }
    m->model.opt.corrections = BRAUN_CORRECT_ALL;
    m->model.opt.linsolver = m->ls;
    size_t bytes = braun_data_size(&m->model);
    if (bytes == 0) {
        snprintf(err, errsize, "%s cannot take n = %d (dense limit %d)", backend, s->sys.n,
                 BRAUN_MAX_DENSE);
        return BRAUN_ERR_SIZE;
    }
    m->buf = malloc(bytes);
    if (!m->buf) {
        snprintf(err, errsize, "out of memory (%zu bytes)", bytes);
        return BRAUN_ERR_BUFFER;
    }
    st = braun_data_init(&m->data, &m->model, m->buf, bytes);
    if (!st) st = braun_set_state(&m->data, 0, s->file->q0, s->file->v0);
    if (st) {
        snprintf(err, errsize, "braun_data_init: %s (%s)", braun_status_str(st),
                 m->data.error.where ? m->data.error.where : "?");
        sc_sim_close(m);
        return st;
    }
    return 0;
}

void sc_sim_close(sc_sim *m)
{
    if (m->buf) braun_data_release(&m->data);
    free(m->buf);
    m->buf = NULL;
}
