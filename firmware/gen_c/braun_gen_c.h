/*
 * Scene to C (issue 6, "Scene to C"): write a C99 source that defines a
 * scene statically — its element arrays as initialised data and a function
 * that builds the braun_system at start-up with braun_scene_build() — so
 * that firmware runs a scene with no parser, no file and no allocation.
 * Host only (stdio); the output compiles in double and in float
 * (BRAUN_SINGLE): numbers are written as the exact double the host read,
 * cast to braun_real, which is what the host's own float build does.
 *
 * The generated file defines, for SYMBOL:
 *   #define SYMBOL_N, SYMBOL_M, SYMBOL_P        sizes (for static buffers and
 *                                               BRAUN_FIXED_N/ROWS builds)
 *   extern const unsigned SYMBOL_corrections;   what the scene file asks for
 *   int SYMBOL_build(braun_system *sys, braun_real *q0, braun_real *v0);
 *       braun_scene_build() on the static arrays, then the initial state
 *       (SYMBOL_N entries each; either may be NULL); returns its status.
 */
#ifndef BRAUN_GEN_C_H
#define BRAUN_GEN_C_H

#include <stdio.h>

#include "braun_scene.h"

/* Write the C source of a loaded scene. symbol: a C identifier prefix;
 * source: the file it came from (for the header comment). Returns 0, or -1
 * if the symbol is not an identifier or writing failed. */
int braun_gen_c_write(FILE *out, const braun_scene_file *sf, const char *symbol,
                      const char *source);

#endif
