#!/bin/sh
# Scene files on the command line: sh tests/cli/scenes.sh path/to/braun
# (run from the top of the tree). braun run / check on every shipped scene,
# the reader's error messages through the tool, corrections declared by a
# scene and overridden on the command line, braun gen, Andrews at t = 0.03.
# Prints "ok - NAME" / "not ok - NAME" and a closing "N passed, M failed".
BRAUN=${1:?usage: sh tests/cli/scenes.sh path/to/braun}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-scenes.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0

ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { # check NAME COMMAND...: passes when COMMAND succeeds
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
json_value() { sed -n "s/^  \"$1\": \(.*\)$/\1/p" "$2" | sed 's/,$//; s/^"//; s/"$//'; }
key_value() { sed -n "s/^$1: //p" "$2"; }
num_le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a != "null" && a + 0 <= b + 0) }'; }

# ------------------------------------------------- every shipped scene runs
for f in data/*.json; do
    # (not "name": check() sets that one)
    scene=$(sed -n 's/^  "name": "\(.*\)",$/\1/p' "$f")
    "$BRAUN" check "$f" > "$TMP/check.out" 2> "$TMP/check.err"; rc=$?
    check "check $f exits 0 and names the scene" \
        sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ] && grep -q "^scene: $3$" "$4"' sh "$rc" \
        "$TMP/check.err" "$scene" "$TMP/check.out"
    "$BRAUN" run "$f" --dt 1e-3 --t-end 1 > "$TMP/run.json" 2> "$TMP/run.err"; rc=$?
    v=$(json_value max_position_constraint_error "$TMP/run.json")
    if [ "$rc" -eq 0 ] && [ ! -s "$TMP/run.err" ] && [ "$(json_value status "$TMP/run.json")" = BRAUN_OK ] &&
        [ "$(json_value scene "$TMP/run.json")" = "$scene" ] && num_le "$v" 1e-8; then
        ok "run $f: BRAUN_OK, max |Phi_q| = $v"
    else
        not_ok "run $f" "exit $rc, status $(json_value status "$TMP/run.json"), |Phi_q| $v, $(head -c 200 "$TMP/run.err")"
    fi
done

# ------------------------------------------------------------ braun check
sizes() { # sizes FILE "n m p rank redundant dof"
    "$BRAUN" check "$1" > "$TMP/sz.out" 2>&1 || return 1
    got="$(key_value n "$TMP/sz.out") $(key_value m "$TMP/sz.out") $(key_value p "$TMP/sz.out")"
    got="$got $(key_value rank "$TMP/sz.out") $(key_value redundant "$TMP/sz.out") $(key_value dof "$TMP/sz.out")"
    [ "$got" = "$2" ] || { echo "#   $1: got '$got', expected '$2'"; return 1; }
}
check "check slider-crank: n 6 m 5 p 0, rank 5, 1 dof" sizes data/slider-crank.json "6 5 0 5 0 1"
check "check four-bar: n 6 m 5 p 0, rank 5, 1 dof" sizes data/four-bar.json "6 5 0 5 0 1"
check "check parallelogram: 12 rows of rank 11, 1 redundant" \
    sizes data/parallelogram-redundant.json "12 12 0 11 1 1"
check "check sleigh: p 1, 2 dof" sizes data/sleigh.json "3 0 1 1 0 2"
check "check driven-crank: no dof left" sizes data/driven-crank.json "6 6 0 6 0 0"
check "check chain-5: n 15 m 10" sizes data/chain-5.json "15 10 0 10 0 5"
check "check andrews (built-in): n 7 m 6" sizes andrews "7 6 0 6 0 1"
"$BRAUN" check data/driven-crank.json > "$TMP/dc.out"
check "check driven-crank: energy law (drive work counted), corrections position,velocity" sh -c '
    grep -q "^energy_law: yes$" "$1" && grep -q "^corrections: position,velocity$" "$1"' sh "$TMP/dc.out"
"$BRAUN" check data/damped-motor.json > "$TMP/dm.out"
check "check damped-motor: energy input, constant mass matrix" sh -c '
    grep -q "^energy_input: yes$" "$1" && grep -q "^mass_matrix: constant$" "$1"' sh "$TMP/dm.out"
"$BRAUN" check data/slider-crank.json > "$TMP/sc.out"
v=$(key_value position_residual "$TMP/sc.out")
check "check slider-crank: initial residual $v <= 1e-15, reference slider-crank" sh -c '
    awk -v a="$1" "BEGIN { exit !(a + 0 <= 1e-15) }" && grep -q "^reference: slider-crank$" "$2"' \
    sh "$v" "$TMP/sc.out"

# ------------------------------------------- bad scenes: the reader's message
# Each must exit 2, print nothing on stdout and exactly "braun: " + the
# expected message of tests/scene/NAME.err.
for f in tests/scene/*.json; do
    expect="braun: $(cat "${f%.json}.err")"
    for cmd in check run; do
        if [ "$cmd" = run ]; then set -- run "$f" --dt 1e-3 --t-end 1; else set -- check "$f"; fi
        "$BRAUN" "$@" > "$TMP/bad.out" 2> "$TMP/bad.err"; rc=$?
        if [ "$rc" -eq 2 ] && [ ! -s "$TMP/bad.out" ] && [ "$(cat "$TMP/bad.err")" = "$expect" ]; then
            ok "$cmd $f: exit 2, $(cut -c1-60 "$TMP/bad.err")..."
        else
            not_ok "$cmd $f" "exit $rc, stderr: $(head -c 300 "$TMP/bad.err")"
        fi
    done
done
"$BRAUN" check > /dev/null 2> "$TMP/e1"; rc=$?
check "check without SCENE: exit 2, one line" sh -c '[ "$1" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ]' sh "$rc" "$TMP/e1"
"$BRAUN" check a.json b.json > /dev/null 2> "$TMP/e2"; rc=$?
check "check with two scenes: exit 2" [ "$rc" -eq 2 ]

# ------------------------------------------------------------ corrections
"$BRAUN" run data/driven-crank.json --dt 1e-3 --t-end 0.5 > "$TMP/dc.json"
check "driven-crank: declared corrections position,velocity, method braun-noenergy" sh -c '
    [ "$(sed -n "s/^  \"corrections\": \"\(.*\)\",$/\1/p" "$1")" = position,velocity ] &&
    grep -q "^  \"method\": \"braun-noenergy\",$" "$1"' sh "$TMP/dc.json"
"$BRAUN" run data/driven-crank.json --dt 1e-3 --t-end 0.5 --corrections energy > /dev/null 2> "$TMP/dce"; rc=$?
check "driven-crank --corrections energy: runs (the drive's work is in the law)" sh -c '
    [ "$1" -eq 0 ] && [ ! -s "$2" ]' sh "$rc" "$TMP/dce"
"$BRAUN" run data/sleigh.json --dt 1e-2 --t-end 1 --corrections position,velocity > "$TMP/sl.json"
check "sleigh --corrections position,velocity: overrides the scene, braun-noenergy" sh -c '
    grep -q "^  \"corrections\": \"position,velocity\",$" "$1" &&
    grep -q "^  \"method\": \"braun-noenergy\",$" "$1"' sh "$TMP/sl.json"
"$BRAUN" run data/sleigh.json --dt 1e-2 --t-end 1 > "$TMP/sl2.json"
check "sleigh: p 1 in the summary, all corrections" sh -c '
    grep -q "^  \"p\": 1,$" "$1" && grep -q "^  \"corrections\": \"position,velocity,energy\",$" "$1"' \
    sh "$TMP/sl2.json"

# ------------------------------------------------- references of paper scenes
"$BRAUN" run data/slider-crank.json --dt 1e-3 --t-end 2 > "$TMP/scr.json"
v=$(json_value max_trajectory_error "$TMP/scr.json")
if num_le "$v" 1e-8; then ok "slider-crank.json against Eq. 24: max trajectory error $v"
else not_ok "slider-crank.json against Eq. 24" "got $v"; fi
"$BRAUN" run data/four-bar.json --dt 1e-3 --t-end 2 > "$TMP/fbr.json"
v=$(json_value max_point_error "$TMP/fbr.json")
if num_le "$v" 1e-8; then ok "four-bar.json against the closed form: max point error $v"
else not_ok "four-bar.json against the closed form" "got $v"; fi
"$BRAUN" run slider-crank --dt 1e-3 --t-end 2 > "$TMP/scb.json"
check "slider-crank.json and the built-in model: the same final state to 1e-10" \
    awk -v a="$(json_value final_q "$TMP/scr.json")" -v b="$(json_value final_q "$TMP/scb.json")" 'BEGIN {
        gsub(/[][ ]/, "", a); gsub(/[][ ]/, "", b); n = split(a, x, ","); split(b, y, ",")
        for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 1e-10) exit 1 }
        exit n != 6 }'

# --------------------------------------------------------------- braun gen
"$BRAUN" gen chain 5 > "$TMP/chain5.json"; rc=$?
check "gen chain 5 reproduces data/chain-5.json" sh -c '[ "$1" -eq 0 ] && cmp -s "$2" data/chain-5.json' \
    sh "$rc" "$TMP/chain5.json"
"$BRAUN" gen chain 12 --rods -o "$TMP/rods12.json"; rc=$?
check "gen chain 12 --rods -o FILE: n 24, m 12" sh -c '[ "$1" -eq 0 ]' sh "$rc"
check "gen chain 12 --rods: sizes" sizes "$TMP/rods12.json" "24 12 0 12 0 12"
"$BRAUN" gen chain 30 -o "$TMP/chain30.json"
"$BRAUN" run "$TMP/chain30.json" --dt 1e-3 --t-end 0.2 > "$TMP/c30.json"; rc=$?
v=$(json_value max_position_constraint_error "$TMP/c30.json")
check "gen chain 30 runs: n 90, BRAUN_OK, |Phi_q| $v" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"n\": 90,$" "$2" && grep -q "\"status\": \"BRAUN_OK\"" "$2"' \
    sh "$rc" "$TMP/c30.json"
for bad in "chain 0" "chain 1001" "chain x" "chain" "ring 5" "chain 5 -o" "chain 5 6" "chain 5 --bogus"; do
    # shellcheck disable=SC2086
    "$BRAUN" gen $bad > "$TMP/g.out" 2> "$TMP/g.err"; rc=$?
    check "gen $bad: exit 2, one line" sh -c '[ "$1" -eq 2 ] && [ ! -s "$2" ] && [ "$(wc -l < "$3")" -eq 1 ]' \
        sh "$rc" "$TMP/g.out" "$TMP/g.err"
done

# ---------------------------------------------------------------- Andrews
"$BRAUN" run andrews --dt 1e-4 --t-end 0.03 > "$TMP/andrews.json"; rc=$?
check "andrews at t = 0.03 within 1e-6 relative of the test set (h = 1e-4)" \
    awk -v a="$(json_value final_q "$TMP/andrews.json")" 'BEGIN {
        split("15.81077119629904 -15.75637105984298 0.04082224013073101 -0.5347301163226948 " \
              "0.5244099658805304 0.5347301163226948 1.048080741042263", r, " ")
        gsub(/[][ ]/, "", a); n = split(a, x, ",")
        for (i = 1; i <= 7; i++) { d = (x[i] - r[i]) / r[i]; if (d < 0) d = -d; if (d > 1e-6) exit 1 }
        exit n != 7 }'

# ------------------------------------------------------------ gen-c
"$BRAUN" gen-c data/sleigh.json -o "$TMP/sleigh.c"; rc=$?
check "gen-c sleigh: exit 0, defines sleigh_build and SLEIGH_N 3" sh -c '
    [ "$1" -eq 0 ] && grep -q "^int sleigh_build(" "$2" && grep -q "^#define SLEIGH_N 3$" "$2"' \
    sh "$rc" "$TMP/sleigh.c"
check "gen-c output compiles warning-free (double, -Werror)" \
    ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude -c "$TMP/sleigh.c" -o "$TMP/sleigh.o"
"$BRAUN" gen-c data/sleigh.json --symbol 9bad > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c --symbol 9bad: exit 2, one line" sh -c '[ "$1" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ]' sh "$rc" "$TMP/gce"
"$BRAUN" gen-c data/no-such.json > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c of a missing file: exit 2, names the file" sh -c '[ "$1" -eq 2 ] && grep -q "no-such.json" "$2"' sh "$rc" "$TMP/gce"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
