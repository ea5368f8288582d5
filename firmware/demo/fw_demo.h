/*
 * The libbraun demo: fixed-step runs of the built-in models with records
 * of their constraint and energy errors, final state and statistics, and
 * per-step cost measurements. Portable C99: the firmware (firmware/board)
 * and the host (tests/firmware/fw_host.c) compile the same file, so the
 * emulator's output and the host's can be compared record by record.
 *
 * Commands (words of the semihosting command line, or argv on the host):
 *   test [builtin|scenes]         the runs of `make firmware-test`
 *   run NAME H STEPS [CORR]       one run of a built-in model or scene
 *                                 ("scene:NAME"), RK4, records as in test
 *   trace NAME STEPS [CORR]       STEPS RK4 steps (h = 1e-3), nothing else:
 *                                 for an instruction trace of the step path
 *   bench STEPS [MODEL [CORR]]    per-step cost, corrections none/pv/all:
 *                                 slider-crank (h = 1e-3) and four-bar
 *                                 (1e-2), or MODEL, any built-in model or
 *                                 scene ("scene:NAME"), at h = 1e-3
 *   long MODEL H STEPS EVERY      trajectory samples (libbraun and RK4 on
 *                                 the minimal equation) for the float study
 *   dadd                          misrounded sums 1 + b of this platform's
 *                                 double addition (libgcc's Arm __adddf3)
 *   sizes                         braun_data_size() per built-in model
 *   sizes-header                  the same as C #defines (build-time table)
 */
#ifndef FW_DEMO_H
#define FW_DEMO_H

#include <stddef.h>

#include "braun.h"

/* Provided by the platform. Ticks of a free-running counter (the target's
 * timer; 0 on the host, where callgrind measures instead). */
unsigned long fw_platform_ticks(void);
/* Name of the platform, e.g. "mps2-an386" or "host". */
extern const char fw_platform_name[];

/* Scenes of this build, provided by the platform: on the target the C
 * sources `braun gen-c` wrote (static data, braun_scene_build at start-up),
 * on the host the same scene files read by the JSON reader. */
/* Coordinates of the largest scene a record holds: IFToMM A04 (Bricard's
 * linkage, five rigid3d bodies in Euler parameters) has n = 35. */
#define FW_SCENE_MAX_N 40
typedef struct fw_scene {
    const char *name;        /* scene file name without .json */
    const char *label;       /* "scene:" name, as the demo's records call it */
    braun_system sys;
    braun_real q0[FW_SCENE_MAX_N], v0[FW_SCENE_MAX_N];
    unsigned corrections;    /* what the scene file asks for */
} fw_scene;
/* The i-th scene (built on first use), or NULL past the end or if it
 * cannot be built. */
const fw_scene *fw_platform_scene_at(int i);

/* Workspace for the runs, provided by the caller (static on the target). */
typedef struct fw_workspace {
    void *buffer;
    size_t bytes;
} fw_workspace;

/* braun_data_size() of a built-in model ("slider-crank") or a scene
 * ("scene:sleigh") with this build's library; 0 if unknown or refused. */
size_t fw_demo_data_size(const char *name);

/* Run a command; returns the exit status (0 ok, 1 a run failed, 2 usage). */
int fw_demo_main(int argc, char **argv, const fw_workspace *ws);

#endif
