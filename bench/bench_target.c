/* Targets of the bench: the one place that maps a name to a system. */
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "braun_reference.h"
#include "braun_scene_file.h"

static const char *const item_names[BENCH_ITEMS] = {
    "step-none", "step-pv", "step-all", "step-free", "step-floor", "step-special",
    "rhs-ideal", "rhs-corrected", "rhs-floor"};

const char *bench_item_name(bench_item it)
{
    return (unsigned)it < BENCH_ITEMS ? item_names[it] : "?";
}

const char *bench_item_kind(bench_item it)
{
    return it >= BENCH_RHS_IDEAL ? "rhs" : "step";
}

int bench_item_from_name(const char *name)
{
    for (int i = 0; i < BENCH_ITEMS; i++)
        if (strcmp(name, item_names[i]) == 0) return i;
    return -1;
}

unsigned bench_item_corrections(const bench_target *tg, bench_item it)
{
    const unsigned pv = BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY;
    const unsigned all = tg->sys.energy ? BRAUN_CORRECT_ALL : pv;
    switch (it) {
    case BENCH_STEP_PV: return pv;
    case BENCH_STEP_ALL:
    case BENCH_RHS_CORR: return all;
    default: return BRAUN_CORRECT_NONE;
    }
}

static int copy_state(bench_target *tg, const braun_real *q0, const braun_real *v0)
{
    const int n = tg->sys.n;
    tg->q0 = malloc(2 * (size_t)n * sizeof *tg->q0);
    if (!tg->q0) return -1;
    tg->v0 = tg->q0 + n;
    memcpy(tg->q0, q0, (size_t)n * sizeof *q0);
    memcpy(tg->v0, v0, (size_t)n * sizeof *v0);
    return 0;
}

int bench_target_open(const char *name, bench_target *tg, char *err, size_t errsize)
{
    memset(tg, 0, sizeof *tg);
    snprintf(tg->name, sizeof tg->name, "%s", name);
    /* One step for every target: 1 ms, as the paper's finest grid and the
     * firmware bench; Andrews' stiff spring needs 1 µs (compare's scale). */
    tg->h = 1e-3;
    const braun_builtin *b = braun_builtin_find(name);
    if (b) {
        tg->source = "built-in";
        tg->sys = b->sys;
        tg->minimal = braun_minimal_find(b->name)->rhs ? b : NULL;
        if (copy_state(tg, b->q0, b->v0)) goto oom;
        return 0;
    }
    if (strcmp(name, "andrews") == 0) {
        tg->source = "record";
        tg->sys = braun_andrews_system;
        tg->h = 1e-6;
        if (copy_state(tg, braun_andrews_q0, braun_andrews_v0)) goto oom;
        return 0;
    }
    size_t len = strlen(name);
    if (!((len >= 5 && strcmp(name + len - 5, ".json") == 0) || strchr(name, '/'))) {
        snprintf(err, errsize, "unknown target '%s' (a built-in model, andrews, or a scene file)",
                 name);
        return -1;
    }
    char why[512];
    braun_scene_file *f = braun_scene_load(name, why, sizeof why);
    if (!f) {
        snprintf(err, errsize, "%s", why);
        return -1;
    }
    tg->source = "scene";
    tg->scene = f;
    tg->sys = f->sys;
    /* A scene that reproduces a built-in model has its minimal equation. */
    const braun_builtin *ref = f->reference ? braun_builtin_find(f->reference) : NULL;
    tg->minimal = ref && braun_minimal_find(ref->name)->rhs ? ref : NULL;
    if (copy_state(tg, f->q0, f->v0)) goto oom;
    return 0;
oom:
    snprintf(err, errsize, "out of memory");
    bench_target_close(tg);
    return -1;
}

void bench_target_close(bench_target *tg)
{
    free(tg->q0);
    tg->q0 = tg->v0 = NULL;
    braun_scene_free(tg->scene);
    tg->scene = NULL;
}
