/*
 * Host build of the firmware demo (firmware/demo): the same runs, printed
 * the same way, for the comparison with the emulated Cortex-M4 in
 * `make firmware-test` and for callgrind (`make firmware-bench`).
 * Usage: fw_host COMMAND ...   (see firmware/demo/fw_demo.h)
 */
#include <stdio.h>
#include <stdlib.h>

#include "braun_scene_file.h"
#include "fw_demo.h"
#include "fw_out.h"

/* The scenes the target runs from generated C, read here from their files
 * by the JSON reader (build/firmware/gen/fw_scene_list.h lists them, with
 * their paths below data/). */
#ifdef FW_HAVE_SCENE_LIST
#include "fw_scene_list.h"
#endif
#ifndef FW_SCENES
#define FW_SCENES
#endif
#ifndef FW_DATA_DIR
#define FW_DATA_DIR "data"
#endif

const char fw_platform_name[] = "host";

void fw_platform_write(const char *s, size_t len) { fwrite(s, 1, len, stdout); }

/* No cycle counter here: the host cost is measured by callgrind. */
unsigned long fw_platform_ticks(void) { return 0; }

const fw_scene *fw_platform_scene_at(int i)
{
    static const char *const names[] = {
#define FW_SCENE(sym, name, path) name,
        FW_SCENES
#undef FW_SCENE
        NULL};
    static const char *const labels[] = {
#define FW_SCENE(sym, name, path) "scene:" name,
        FW_SCENES
#undef FW_SCENE
        NULL};
    /* The scene file below the data directory, without .json. */
    static const char *const paths[] = {
#define FW_SCENE(sym, name, path) path,
        FW_SCENES
#undef FW_SCENE
        NULL};
    static fw_scene scenes[sizeof names / sizeof names[0]];
    static int state[sizeof names / sizeof names[0]];
    if (i < 0) return NULL;
    for (int k = 0; k <= i; k++)
        if (!names[k]) return NULL; /* past the end */
    if (state[i] == 0) {
        char path[512], err[512];
        const char *dir = getenv("FW_DATA_DIR") ? getenv("FW_DATA_DIR") : FW_DATA_DIR;
        state[i] = -1;
        snprintf(path, sizeof path, "%s/%s.json", dir, paths[i]);
        /* Kept for the life of the program: sys.user points into it. */
        braun_scene_file *sf = braun_scene_load(path, err, sizeof err);
        if (!sf) {
            fprintf(stderr, "fw_host: %s\n", err);
        } else if (sf->scene.n > FW_SCENE_MAX_N) {
            fprintf(stderr, "fw_host: %s: n = %d coordinates, more than FW_SCENE_MAX_N = %d\n",
                    path, sf->scene.n, FW_SCENE_MAX_N);
        } else {
            fw_scene *s = &scenes[i];
            s->name = names[i];
            s->label = labels[i];
            s->sys = sf->sys;
            s->corrections = sf->corrections;
            for (int k = 0; k < sf->scene.n; k++) {
                s->q0[k] = sf->q0[k];
                s->v0[k] = sf->v0[k];
            }
            state[i] = 1;
        }
    }
    return state[i] > 0 ? &scenes[i] : NULL;
}

static union {
    unsigned char bytes[1 << 16];
    double align;
} workspace;

int main(int argc, char **argv)
{
    fw_workspace ws = {workspace.bytes, sizeof workspace.bytes};
    int rc = fw_demo_main(argc - 1, argv + 1, &ws);
    fflush(stdout);
    return rc;
}
