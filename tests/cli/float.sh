#!/bin/sh
# What the float build answers differently from the double one, checked on
# both tools side by side: sh tests/cli/float.sh FLOAT_BRAUN DOUBLE_BRAUN
# (make test builds the float tool into BUILD/float, mk/float.mk). The
# float tool was tested nowhere: its summary gave double's dopri5 minimum
# step and its --help double's rank tolerance. Also BRAUN_R in both
# precisions, and the float tolerances docs/cli.md gives dopri5. Prints
# "ok - NAME" / "not ok - NAME" and "N passed, M failed, K skipped"; exit
# status 1 if anything failed.
FB=${1:?usage: sh tests/cli/float.sh FLOAT_BRAUN DOUBLE_BRAUN}
DB=${2:?usage: sh tests/cli/float.sh FLOAT_BRAUN DOUBLE_BRAUN}
TOP=$(cd "$(dirname "$0")/../.." && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-float.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0

ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { name=$1; shift; if "$@"; then ok "$name"; else not_ok "$name"; fi; }
json_value() { sed -n "s/^  \"$1\": \(.*\)$/\1/p" "$2" | sed 's/,$//; s/^"//; s/"$//'; }

check "the float tool says float: $("$FB" --version 2>&1)" sh -c '"$1" --version | grep -q ", float;"' sh "$FB"
check "the double tool says double: $("$DB" --version 2>&1)" sh -c '"$1" --version | grep -q ", double;"' sh "$DB"

# ------------------------------------------------------------ dopri5's minimum step
# The summary's h_min is the minimum the run used: 1e-12 of the span, but
# at least 16 eps t_end, which in float always decides (16 * 2^-23 * 100 =
# 1.9073486328125e-4 here). The float summary said 1e-10 while the same
# run's error said the step fell below its minimum at h = 1.35e-4.
fb="four-bar --dt 1e-3 --t-end 100 --integrator dopri5"
# shellcheck disable=SC2086
"$FB" run $fb --rtol 1e-6 --atol 1e-8 --quiet --summary "$TMP/f6.json" > /dev/null 2> "$TMP/f6.err"
hmin=$(json_value h_min "$TMP/f6.json")
h=$(sed -n 's/.*fell below its minimum (h = \([^)]*\)).*/\1/p' "$TMP/f6.err")
check "float dopri5, t_end 100: h_min $hmin = 16 eps t_end, above the h the error names ($h)" \
    awk -v m="$hmin" -v h="$h" 'BEGIN { exit !(m == 1.9073486328125e-4 && h != "" && h + 0 < m + 0) }'
# shellcheck disable=SC2086
"$DB" run $fb --rtol 1e-6 --atol 1e-8 --quiet --summary "$TMP/d6.json" > /dev/null 2>&1
check "double dopri5, t_end 100: h_min $(json_value h_min "$TMP/d6.json") = 1e-12 of the span" \
    awk -v m="$(json_value h_min "$TMP/d6.json")" 'BEGIN { exit !(m == 1e-10) }'
# A first step below the float minimum is refused as double refuses one
# below its own (the float tool used double's eps there and ran).
# shellcheck disable=SC2086
"$FB" run four-bar --dt 1e-5 --t-end 100 --integrator dopri5 --rtol 1e-4 > /dev/null 2> "$TMP/dt.err"; rc=$?
check "float dopri5 --dt 1e-5 --t-end 100: exit 2, the float minimum and the way out named" sh -c '
    [ "$1" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ] &&
    grep -q "^braun: --dt 1e-05 is below the adaptive step.s minimum 0.000190735 at --t-end 100 (16 eps of the span in this float build).*--t-end <= 5.24288 or --dt >= 0.000190735$" "$2"' \
    sh "$rc" "$TMP/dt.err"

# ------------------------------------------------------------ float tolerances (docs/cli.md)
# The four-bar over 100 s in float: rtol 1e-6 stops at t = 0 and 1e-5
# before t_end (BRAUN_ERR_STEP_TOO_SMALL; measured 10.9 s); 1e-4 with atol
# 1e-6 completes, with a trajectory error of 2.0e-2 (measured). The docs
# advised "1e-5 or above".
e6=$(json_value error_t "$TMP/f6.json")
check "float dopri5 rtol 1e-6 atol 1e-8: BRAUN_ERR_STEP_TOO_SMALL at t = $e6" sh -c '
    [ "$(sed -n "s/^  \"status\": \"\(.*\)\",$/\1/p" "$1")" = BRAUN_ERR_STEP_TOO_SMALL ] && [ "$2" = 0 ]' sh "$TMP/f6.json" "$e6"
# shellcheck disable=SC2086
"$FB" run $fb --rtol 1e-5 --atol 1e-7 --quiet --summary "$TMP/f5.json" > /dev/null 2>&1
e5=$(json_value error_t "$TMP/f5.json")
check "float dopri5 rtol 1e-5 atol 1e-7: BRAUN_ERR_STEP_TOO_SMALL before t_end (t = $e5)" sh -c '
    [ "$(sed -n "s/^  \"status\": \"\(.*\)\",$/\1/p" "$1")" = BRAUN_ERR_STEP_TOO_SMALL ] &&
    awk -v t="$2" "BEGIN { exit !(t != \"null\" && t + 0 > 0 && t + 0 < 100) }"' sh "$TMP/f5.json" "$e5"
# shellcheck disable=SC2086
"$FB" run $fb --rtol 1e-4 --atol 1e-6 --quiet --summary "$TMP/f4.json" > /dev/null 2>&1
e4=$(json_value max_trajectory_error "$TMP/f4.json")
check "float dopri5 rtol 1e-4 atol 1e-6: BRAUN_OK over 100 s, trajectory error $e4 (2.0e-2 measured; at most 4e-2)" sh -c '
    [ "$(sed -n "s/^  \"status\": \"\(.*\)\",$/\1/p" "$1")" = BRAUN_OK ] &&
    awk -v e="$2" "BEGIN { exit !(e != \"\" && e + 0 > 0 && e + 0 <= 4e-2) }"' sh "$TMP/f4.json" "$e4"

# ------------------------------------------------------------ --rank-tol's default
# --help gives this build's default: 30 sqrt(eps) = 0.0104 in float, the
# rank_tol its summary reports (it gave double's 10*max(rows, n)*eps).
"$FB" --help > "$TMP/fhelp" 2>&1
ft=$(json_value rank_tol "$TMP/f6.json")
check "float --help: --rank-tol default 30*sqrt(eps) = 0.0104, the summary's rank_tol $ft" sh -c '
    grep -A2 "^  --rank-tol X" "$1" | tr -s " \n" " " | grep -q "(default 0: 30\*sqrt(eps) = 0.0104 in this float build)" &&
    [ "$(awk -v t="$2" "BEGIN { printf \"%.3g\", t }")" = 0.0104 ]' sh "$TMP/fhelp" "$ft"
"$DB" --help > "$TMP/dhelp" 2>&1
check "double --help: --rank-tol default 10*max(rows, n)*eps" sh -c '
    grep -A1 "^  --rank-tol X" "$1" | grep -q "(default 0: 10\*max(rows, n)\*eps)$" && ! grep -q sqrt "$1"' sh "$TMP/dhelp"

# ------------------------------------------------------------ BRAUN_R
# BRAUN_R(1) did not compile in float (1##f: "invalid suffix f on integer
# constant") and was the int 1 in double (BRAUN_R(1) / BRAUN_R(3) == 0);
# BRAUN_R(MACRO) pasted the macro's name. Now a cast to braun_real, a
# constant expression in both.
cat > "$TMP/lit.c" <<'C'
#include "braun.h"
#define HALF 0.5
static const braun_real third = BRAUN_R(1) / BRAUN_R(3);
static const braun_real table[3] = {BRAUN_R(1), BRAUN_R(HALF), BRAUN_R(-2)};
int main(void)
{
    if (!(third > BRAUN_R(0.33) && third < BRAUN_R(0.34))) return 1;
    if (table[0] != BRAUN_R(1.0) || table[1] != BRAUN_R(0.5) || table[2] != BRAUN_R(-2.0)) return 2;
    if (sizeof(BRAUN_R(1)) != sizeof(braun_real)) return 3;
#ifdef BRAUN_SINGLE
    if (BRAUN_R(0.1) != 0.1f) return 4;
#else
    if (BRAUN_R(0.1) != 0.1) return 4;
#endif
    return 0;
}
C
for prec in double float; do
    def=""; [ "$prec" = float ] && def=-DBRAUN_SINGLE
    # shellcheck disable=SC2086
    if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Wconversion -Wdouble-promotion -Werror $def -I"$TOP/include/core" \
            "$TMP/lit.c" -o "$TMP/lit-$prec" 2> "$TMP/lit-$prec.err"; then
        "$TMP/lit-$prec"; rc=$?
        check "BRAUN_R in $prec: integer literals, a macro, static initialisers; BRAUN_R(1) / BRAUN_R(3) is a third (exit $rc)" \
            [ "$rc" -eq 0 ]
    else
        not_ok "BRAUN_R in $prec compiles warning-free" "$(head -c 300 "$TMP/lit-$prec.err")"
    fi
done

echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
