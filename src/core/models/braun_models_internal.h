/*
 * Private to src/models: the built-in model records (one per file) and the
 * precision-following math the callbacks use.
 */
#ifndef BRAUN_MODELS_INTERNAL_H
#define BRAUN_MODELS_INTERNAL_H

#include "braun.h"
#include "braun_models.h"
/* braun_sin, braun_cos, braun_sqrt: sinf/sin etc. chosen by BRAUN_SINGLE.
 * Shared with the core so there is one spelling of each. */
#include "braun_math.h"

/* π in double; C99 has no M_PI. */
#define BRAUN_PI_D 3.14159265358979323846

/* Model records, collected by braun_builtin_table.c. */
extern const braun_builtin braun_builtin_slider_crank;
extern const braun_builtin braun_builtin_four_bar;
extern const braun_builtin braun_builtin_pendulum;

#endif
