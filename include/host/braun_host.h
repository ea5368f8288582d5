/*
 * libbraun host helpers: conveniences for programs running on an operating
 * system (the CLI, tests, desktop tools). They use the C library's stdio.
 *
 * Host tier (libbraun_host.a): firmware builds compile the core tier
 * (src/core) only, which never calls anything declared here.
 */
#ifndef BRAUN_HOST_H
#define BRAUN_HOST_H

#include <stddef.h>

#include "braun.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One readable sentence (no trailing newline or period) describing
 * d->error: what failed, where (callback, matrix entry, pivot, step) and at
 * which time, e.g.
 *   "mass matrix not positive definite at pivot 3 (value -0.0025) at t = 0"
 *   "callback 'holonomic' failed (returned -1) at t = 2"
 *   "step diverged at t = 13.24 (h = 0.001, v[2] not finite)".
 * The status name itself is not included; braun_status_str() gives it.
 * Works like snprintf: writes at most size bytes including the NUL (buf may
 * be NULL when size is 0) and returns the length the full sentence needs,
 * or -1 if d is NULL. Only meaningful after a call on d returned
 * d->error.status (every failing call records itself, NULL pointers
 * included; only a NULL d cannot be). */
int braun_error_format(const braun_data *d, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_HOST_H */
