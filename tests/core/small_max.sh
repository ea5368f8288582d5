#!/bin/sh
# The generic kernels' length dispatch (BRAUN_SMALL_MAX, braun_linalg.h)
# switched off (0) and partial (3: lengths 2-3 dispatched, the rest the
# loop): the core builds warning-free and the linear-algebra and core
# suites pass, test_small_kernels_bitwise comparing every n <= 11 with
# plain loops bit for bit. Prints "ok - NAME" / "not ok - NAME" and a
# closing "N passed, M failed, 0 skipped".
set -u
pass=0; fail=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
root=${1:-build}
for m in 0 3; do
    b=$root/small-max-$m
    mkdir -p "$b"
    if make -s --no-print-directory BUILD="$b" CPPFLAGS="-DBRAUN_SMALL_MAX=$m -Werror" \
            "$b/tests/test_linalg" "$b/tests/test_core" > "$b/build.log" 2>&1; then
        ok "BRAUN_SMALL_MAX=$m: core and suites build with -Werror"
    else
        no "BRAUN_SMALL_MAX=$m: core and suites build with -Werror ($b/build.log)"
        tail -5 "$b/build.log"
        continue
    fi
    for t in test_linalg test_core; do
        if "$b/tests/$t" > "$b/$t.log" 2>&1; then ok "BRAUN_SMALL_MAX=$m: $t"
        else no "BRAUN_SMALL_MAX=$m: $t ($b/$t.log)"; grep -E "FAIL|ERROR" "$b/$t.log" | head -5; fi
    done
done
echo "$pass passed, $fail failed, 0 skipped"
[ "$fail" -eq 0 ]
