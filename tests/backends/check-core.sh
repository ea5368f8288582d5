#!/bin/sh
# libbraun.a depends on libm alone: no LAPACK, BLAS, SuiteSparse or GSL
# symbol may be referenced or defined by it, whatever backends are built,
# and what it takes from outside itself is libm, string.h and the
# compiler's own helpers. Prints "ok - NAME" / "not ok - NAME" and a
# closing "N passed, M failed, 0 skipped".
set -u
lib=${1:-build/libbraun.a}
pass=0; fail=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
if [ ! -f "$lib" ]; then no "$lib exists"; echo "$pass passed, $fail failed, 0 skipped"; exit 1; fi
syms=$(nm -A "$lib" 2>/dev/null)
[ -n "$syms" ] && ok "nm reads $lib" || no "nm reads $lib"
bad=$(echo "$syms" | grep -E ' [UTDB] (cholmod_|SuiteSparseQR|spqr_|klu_|d[a-z]{4,5}_$|s[a-z]{4,5}_$|gsl_|cblas_|dgeqp3|dpotrf)' || true)
if [ -z "$bad" ]; then ok "libbraun.a references no LAPACK/BLAS/SuiteSparse/GSL symbol"
else no "libbraun.a references backend symbols:"; echo "$bad" | head; fi
# Undefined in some object and defined in none: what the archive needs.
defined=$(nm --defined-only "$lib" 2>/dev/null | awk 'NF == 3 { print $3 }' | sort -u)
und=$(nm -u "$lib" 2>/dev/null | awk 'NF == 2 { print $2 }' | sort -u |
      while IFS= read -r s; do echo "$defined" | grep -qxF "$s" || echo "$s"; done)
heap=$(echo "$und" | grep -xE 'malloc|calloc|realloc|free|aligned_alloc|posix_memalign' || true)
if [ -z "$heap" ]; then ok "libbraun.a calls no allocator"; else no "libbraun.a calls: $(echo $heap)"; fi
other=$(echo "$und" | grep -vxE '(a?sinh?|a?cosh?|a?tanh?|atan2|sincos|sqrt|cbrt|hypot|exp|expm1|log|log1p|pow|floor|ceil|round|trunc|fmod|fabs|fmax|fmin|fma|copysign|ldexp|frexp|nextafter)f?|mem(cpy|set|move|cmp)|str(cmp|ncmp|len)|_GLOBAL_OFFSET_TABLE_|__.*' || true)
other=$(echo $other)
if [ -z "$other" ]; then ok "libbraun.a needs nothing but libm and string.h from outside ($(echo $und))"
else no "libbraun.a needs from outside libm and string.h: $other"; fi
echo "$pass passed, $fail failed, 0 skipped"
[ "$fail" -eq 0 ]
