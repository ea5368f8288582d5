#!/bin/sh
# libbraun.a depends on libm alone: no LAPACK, BLAS, SuiteSparse or GSL
# symbol may be referenced or defined by it, whatever backends are built.
set -u
lib=${1:-build/libbraun.a}
pass=0; fail=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
if [ ! -f "$lib" ]; then no "$lib exists"; echo "$pass passed, $fail failed"; exit 1; fi
syms=$(nm -A "$lib" 2>/dev/null)
bad=$(echo "$syms" | grep -E ' [UTDB] (cholmod_|SuiteSparseQR|spqr_|klu_|d[a-z]{4,5}_$|s[a-z]{4,5}_$|gsl_|cblas_|dgeqp3|dpotrf)' || true)
if [ -z "$bad" ]; then ok "libbraun.a references no LAPACK/BLAS/SuiteSparse/GSL symbol"
else no "libbraun.a references backend symbols:"; echo "$bad" | head; fi
und=$(echo "$syms" | awk '$2 == "U" { print $3 }' | sort -u |
      grep -vE '^(braun_|sin|cos|sqrt|fabs|atan2|exp|log|pow|floor|ceil|fmod|hypot|memcpy|memset|memmove|memcmp|strcmp|strlen|strncmp|_GLOBAL_OFFSET_TABLE_|__stack_chk_fail|acos|asin|atan|tan|sinh|cosh|tanh|cbrt|round|trunc|isnan|isinf|fmax|fmin|copysign|ldexp|frexp|nextafter|fma|log1p|expm1|__.*)$' || true)
# The host helpers (braun_error_format) may use snprintf; the allocation-free
# core may not use the heap.
heap=$(echo "$und" | grep -E '^(malloc|calloc|realloc|free)$' || true)
if [ -z "$heap" ]; then ok "libbraun.a calls no allocator"; else no "libbraun.a calls: $heap"; fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
