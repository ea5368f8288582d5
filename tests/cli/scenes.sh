#!/bin/sh
# Scene files on the command line: sh tests/cli/scenes.sh path/to/braun
# (run from the top of the tree). braun run / check on every shipped scene,
# the reader's error messages through the tool, corrections declared by a
# scene and overridden on the command line, braun gen, Andrews at t = 0.03.
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" for a check
# of a backend this build does not have) and a closing "N passed, M failed,
# K skipped".
BRAUN=${1:?usage: sh tests/cli/scenes.sh path/to/braun}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-scenes.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0

ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
check() { # check NAME COMMAND...: passes when COMMAND succeeds
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
json_value() { sed -n "s/^  \"$1\": \(.*\)$/\1/p" "$2" | sed 's/,$//; s/^"//; s/"$//'; }
key_value() { sed -n "s/^$1: //p" "$2"; }
num_le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a != "null" && a + 0 <= b + 0) }'; }

# ------------------------------------------------- every shipped scene runs
# max |Phi_q| over 1 s at h = 1e-3, a small factor above the value measured
# for each scene (x86-64, gcc 12, -O2; floor 1e-14 for round-off-level
# values); a scene not listed here gets 1e-10 (5x the largest measured).
phi_bound() {
    case $1 in
    data/chain-5.json) echo 5e-11 ;;                 # measured 1.90e-11
    data/damped-motor.json) echo 5e-11 ;;            # 1.84e-11
    data/double-pendulum.json) echo 1e-12 ;;         # 4.28e-13
    data/driven-crank.json) echo 5e-14 ;;            # 1.43e-14
    data/four-bar.json) echo 3e-13 ;;                # 1.03e-13
    data/parallelogram-redundant.json) echo 2e-12 ;; # 8.81e-13
    data/pendulum.json) echo 1e-14 ;;                # 5.55e-16
    data/sleigh.json) echo 1e-14 ;;                  # 0 (no holonomic rows)
    data/slider-crank.json) echo 5e-13 ;;            # 2.37e-13
    *) echo 1e-10 ;;
    esac
}
for f in data/*.json; do
    # (not "name": check() sets that one)
    scene=$(sed -n 's/^  "name": "\(.*\)",$/\1/p' "$f")
    "$BRAUN" check "$f" > "$TMP/check.out" 2> "$TMP/check.err"; rc=$?
    check "check $f exits 0 and names the scene" \
        sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ] && grep -q "^scene: $3$" "$4"' sh "$rc" \
        "$TMP/check.err" "$scene" "$TMP/check.out"
    "$BRAUN" run "$f" --dt 1e-3 --t-end 1 > "$TMP/run.json" 2> "$TMP/run.err"; rc=$?
    v=$(json_value max_position_constraint_error "$TMP/run.json")
    bound=$(phi_bound "$f")
    if [ "$rc" -eq 0 ] && [ ! -s "$TMP/run.err" ] && [ "$(json_value status "$TMP/run.json")" = BRAUN_OK ] &&
        [ "$(json_value scene "$TMP/run.json")" = "$scene" ] && num_le "$v" "$bound"; then
        ok "run $f: BRAUN_OK, max |Phi_q| = $v <= $bound"
    else
        not_ok "run $f" "exit $rc, status $(json_value status "$TMP/run.json"), |Phi_q| $v (bound $bound), $(head -c 200 "$TMP/run.err")"
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

# Constraints with no solution: a particle pinned at x = 0 by one joint and
# at x = 1 by another; two distances from one anchor (1 and 2). check says
# so (consistent: no), names the joints whose rows disagree and exits 1;
# run names them too (the core's rows of d->error.index/index2).
cat > "$TMP/pinned.json" <<'EOF'
{"name": "pinned", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [0.5, 0]}],
 "joints": [{"type": "distance", "a": [0, 3], "b": "b"},
            {"name": "left", "type": "revolute", "a": [0, 0], "b": "b"},
            {"name": "right", "type": "revolute", "a": [1, 0], "b": "b"}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" check "$TMP/pinned.json" > "$TMP/pin.out" 2> "$TMP/pin.err"; rc=$?
check "check: pinned at x = 0 and x = 1: consistent: no, exit 1, joints 'left' and 'right' named" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" && grep -q "^rank: 2$" "$2" && [ "$(wc -l < "$3")" -eq 1 ] &&
    grep -q "^braun: pinned: the constraints have no solution at the initial state: joint .left. (revolute) (row 1) and joint .right. (revolute) (row 3) disagree (their least-squares residual 0.707 is 0.224 of the rows. own scale, above sqrt(eps) = 1.49e-08 of it, in any units: braun run stops with BRAUN_ERR_INCONSISTENT)" "$3"' \
    sh "$rc" "$TMP/pin.out" "$TMP/pin.err"
# Three links closed straight to a point 1e-4 m within their reach: the rows
# lose rank and disagree to first order, the local search stalls, but the
# chain sagged 0.01 m meets them. The message said only "no solution".
cat > "$TMP/sag.json" <<'EOF'
{"name": "sag", "bodies": [{"name": "p1", "type": "particle", "mass": 1, "position": [1, 0]},
                           {"name": "p2", "type": "particle", "mass": 1, "position": [2, 0]}],
 "joints": [{"name": "l1", "type": "distance", "a": [0, 0], "b": "p1", "length": 1},
            {"name": "l2", "type": "distance", "a": "p1", "b": "p2", "length": 1},
            {"name": "l3", "type": "distance", "a": "p2", "b": [2.9999, 0], "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" check "$TMP/sag.json" > /dev/null 2> "$TMP/sag.err"; rc=$?
check "check: a chain closed straight within its reach: exit 1, the message says first order and where a solution may lie" sh -c '
    [ "$1" -eq 1 ] && grep -q "judged to first order where the rows lose rank: at a singular configuration" "$2"' \
    sh "$rc" "$TMP/sag.err"
"$BRAUN" run "$TMP/pinned.json" --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/pinr.err"; rc=$?
check "run: the same scene stops at once, exit 1, names the joints of the rows that disagree" sh -c '
    [ "$1" -eq 1 ] && [ "$(wc -l < "$2")" -eq 1 ] &&
    grep -q "(rows 1 and 3 disagree most) at t = 0; row 1 is joint .left. (revolute), row 3 is joint .right. (revolute) (BRAUN_ERR_INCONSISTENT" "$2"' \
    sh "$rc" "$TMP/pinr.err"
cat > "$TMP/circles.json" <<'EOF'
{"name": "circles", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1.5, 0]}],
 "joints": [{"type": "distance", "a": [0, 0], "b": "b", "length": 1},
            {"name": "long", "type": "distance", "a": [0, 0], "b": "b", "length": 2}]}
EOF
"$BRAUN" check "$TMP/circles.json" > "$TMP/circ.out" 2> "$TMP/circ.err"; rc=$?
check "check: two distances 1 and 2 from one anchor: consistent: no, both joints named" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" &&
    grep -q "joint #1 (distance) (row 0) and joint .long. (distance) (row 1) disagree" "$3"' \
    sh "$rc" "$TMP/circ.out" "$TMP/circ.err"
sed 's/"B": \[2, 0\]/"B": [2.2, 0]/' data/parallelogram-redundant.json > "$TMP/par.json"
"$BRAUN" check "$TMP/par.json" > "$TMP/par.out" 2> "$TMP/par.err"; rc=$?
check "check: the parallelogram's third crank 0.2 m off: consistent: no, its joints named first" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" &&
    grep -q "joint .pivot2. (revolute) (row 3), joint .pin2. (revolute) (row 9), .* and more disagree" "$3"' \
    sh "$rc" "$TMP/par.out" "$TMP/par.err"
# One joint alone: a universal joint started with its axes parallel (its
# row needs them perpendicular; its gradient vanishes there).
cat > "$TMP/unipar.json" <<'EOF'
{"name": "unipar", "bodies": [{"name": "b", "type": "rigid3d", "mass": 1, "inertia": [0.1, 0.1, 0.1],
  "position": [0, 0, -0.5], "points": {"top": [0, 0, 0.5]}}],
 "joints": [{"name": "h", "type": "universal", "a": "b.top", "b": [0, 0, 0], "axis": [1, 0, 0], "axis_b": [1, 0, 0]}]}
EOF
"$BRAUN" check "$TMP/unipar.json" > "$TMP/uni.out" 2> "$TMP/uni.err"; rc=$?
"$BRAUN" run "$TMP/unipar.json" --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/unir.err"; rc2=$?
check "check and run: a universal joint started with parallel axes cannot be met: one joint named, alone" sh -c '
    [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "^consistent: no$" "$3" &&
    grep -q "joint .h. (universal) (row 3) cannot be met (its gradient depends on the other rows" "$4" &&
    grep -q "(row 3: its gradient is zero here, its error is not) at t = 0; row 3 is joint .h. (universal)" "$5"' \
    sh "$rc" "$rc2" "$TMP/uni.out" "$TMP/uni.err" "$TMP/unir.err"
# Positions that agree, velocities that do not: a knife edge across a
# driven slider; two drives of one crank at different rates. check says so
# and names them; run stops at its first step (before, the knife's run
# ended with exit 0 and the knife violated throughout).
cat > "$TMP/knife-drive.json" <<'EOF'
{"name": "knife-drive",
 "bodies": [{"name": "sled", "type": "rigid", "mass": 1, "inertia": 0.1, "position": [0, 0]}],
 "joints": [{"name": "rail", "type": "slider", "point": "sled", "line": [0, 0], "axis": [1, 0],
             "drive": {"type": "linear", "value": 0, "rate": 1}},
            {"name": "turn", "type": "angle", "a": "ground", "b": "sled", "angle": 0},
            {"name": "blade", "type": "knife", "body": "sled", "direction": [0, 1]}]}
EOF
"$BRAUN" check "$TMP/knife-drive.json" > "$TMP/kd.out" 2> "$TMP/kd.err"; rc=$?
"$BRAUN" run "$TMP/knife-drive.json" --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/kdr.err"; rc2=$?
check "check and run: a knife across a driven slider: consistent: no, exit 1, slider and knife named" sh -c '
    [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "^consistent: no$" "$3" && [ "$(wc -l < "$4")" -eq 1 ] &&
    grep -q "^braun: knife-drive: the constraints. velocities have no solution at the initial state: joint .rail. (slider) (row 1) and joint .blade. (knife) (row 3) disagree (the least-squares residual of their velocity error, 0.707," "$4" &&
    grep -q "dependent velocity-level constraint rows disagree by 0.707.* at t = 0; row [13] is joint .[a-z]*. ([a-z]*), row [13] is joint .[a-z]*. ([a-z]*) (BRAUN_ERR_INCONSISTENT" "$5" &&
    grep -q "joint .blade. (knife)" "$5"' \
    sh "$rc" "$rc2" "$TMP/kd.out" "$TMP/kd.err" "$TMP/kdr.err"
sed 's|"rate": 6.283185307179586}}|&,\
    {"name": "drive2", "type": "angle", "a": "ground", "b": "crank", "drive": {"type": "linear", "value": 0, "rate": 6.2831863}}|' \
    data/driven-crank.json > "$TMP/double-drive.json"
"$BRAUN" check "$TMP/double-drive.json" > "$TMP/dd.out" 2> "$TMP/dd.err"; rc=$?
"$BRAUN" run "$TMP/double-drive.json" --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/ddr.err"; rc2=$?
check "check and run: two drives of one crank, rates 1e-6 rad/s apart: consistent: no, both named, run stops at t = 0" sh -c '
    [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "^consistent: no$" "$3" && grep -q "^rank: 6$" "$3" &&
    grep -q "joint .drive2*. (angle) (row [56]) and joint .drive2*. (angle) (row [56]) disagree (the least-squares residual of their velocity error, 7.0" "$4" &&
    grep -q "velocity-level constraint rows disagree by 7.0.* at t = 0; row [56] is joint .drive2*. (angle), row [56] is joint .drive2*. (angle)" "$5"' \
    sh "$rc" "$rc2" "$TMP/dd.out" "$TMP/dd.err" "$TMP/ddr.err"
# Every shipped scene's callbacks agree with their own finite differences
# at the initial state (braun_check_callbacks); the line is the last one.
for f in data/*.json data/iftomm/*.json slider-crank four-bar pendulum andrews; do
    "$BRAUN" check "$f" > "$TMP/cb.out" 2>&1; rc=$?
    check "check $f: callbacks: yes, the last line" sh -c '
        [ "$1" -eq 0 ] && tail -n 1 "$2" | grep -q "^callbacks: yes (largest difference "' sh "$rc" "$TMP/cb.out"
done
# The same callbacks at other scales: the spatial-arm with its lengths
# times L (masses times M, within the scene limits) and a rigid3d on a
# spring at its rest length. Differenced by 6e-6 m whatever the scene's
# size, the arm at 1 um failed at dE_dq[7] and the spring at 100 nm at
# dE_dq[0] (exit 1) while their runs matched the unit ones to 1e-13.
scaled_arm() { # scaled_arm L M: data/spatial-arm.json, lengths x L, masses x M
    awk -v L="$1" -v M="$2" 'BEGIN { I = M * L * L; printf "{\"name\": \"arm\", \"ground\": {\"points\": {\"pivot\": [0, 0, 0], \"anchor\": [%.17g, %.17g, %.17g]}}, \"bodies\": [{\"name\": \"arm\", \"type\": \"rigid3d\", \"mass\": %.17g, \"inertia\": [%.17g, %.17g, %.17g], \"position\": [%.17g, 0, 0], \"points\": {\"root\": [%.17g, 0, 0], \"tip\": [%.17g, 0, 0]}}, {\"name\": \"bob\", \"type\": \"rigid3d\", \"mass\": %.17g, \"inertia\": [%.17g, %.17g, %.17g], \"position\": [%.17g, %.17g, 0], \"orientation\": [0.70710678118654757, 0, 0, -0.70710678118654757], \"velocity\": [0, 0, %.17g], \"omega\": [-2, 0, 0], \"points\": {\"top\": [%.17g, 0, 0], \"end\": [%.17g, 0, 0]}}], \"joints\": [{\"name\": \"hinge\", \"type\": \"revolute3d\", \"a\": \"arm.root\", \"b\": \"ground.pivot\", \"axis\": [0, 0, 1]}, {\"name\": \"ball\", \"type\": \"spherical\", \"a\": \"arm.tip\", \"b\": \"bob.top\"}], \"effects\": [{\"type\": \"gravity\", \"g\": [0, %.17g, 0]}, {\"name\": \"cord\", \"type\": \"spring\", \"a\": \"bob.end\", \"b\": \"ground.anchor\", \"stiffness\": %.17g, \"damping\": %.17g}, {\"name\": \"coil\", \"type\": \"torsion3d\", \"joint\": \"hinge\", \"stiffness\": %.17g, \"damping\": %.17g}]}\n",
        1.5 * L, -L, 0.5 * L, M, 0.0016666666666666668 * I, 0.084166666666666667 * I, 0.084166666666666667 * I,
        0.5 * L, -0.5 * L, 0.5 * L, 0.5 * M, 0.00083333333333333339 * I, 0.042083333333333334 * I,
        0.042083333333333334 * I, L, -0.5 * L, L, -0.5 * L, 0.5 * L, -9.81 * L, 20 * M, 0.1 * M, 5 * I, 0.2 * I }'
}
spring3d() { # spring3d L: a rigid3d of 1 kg on a spring at its rest length, lengths x L
    awk -v L="$1" 'BEGIN { printf "{\"name\": \"spring3d\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid3d\", \"mass\": 1, \"inertia\": [%.17g, %.17g, %.17g], \"position\": [%.17g, %.17g, %.17g], \"velocity\": [%.17g, %.17g, %.17g], \"points\": {\"e\": [%.17g, 0, 0]}}], \"effects\": [{\"type\": \"spring\", \"a\": [0, 0, 0], \"b\": \"b.e\", \"stiffness\": 10, \"damping\": 0.5}, {\"type\": \"gravity\", \"g\": [0, %.17g, 0]}]}\n",
        0.1 * L * L, 0.1 * L * L, 0.1 * L * L, 0.6 * L, 0.8 * L, 0.3 * L, 0.3 * L, -0.2 * L, 0.1 * L, 0.5 * L, -9.81 * L }'
}
for s in "arm 1e-6 1" "arm 1e-6 1e-18" "arm 1e6 1e-6" "spring3d 1e-7" "spring3d 1e6"; do
    set -- $s
    if [ "$1" = arm ]; then scaled_arm "$2" "$3" > "$TMP/scaled.json"; else spring3d "$2" > "$TMP/scaled.json"; fi
    "$BRAUN" check "$TMP/scaled.json" > "$TMP/scaled.out" 2> "$TMP/scaled.err"; rc=$?
    check "check $s (lengths x $2): callbacks: yes, exit 0" sh -c '
        [ "$1" -eq 0 ] && grep -q "^callbacks: yes (largest difference " "$2" && [ ! -s "$3" ]' \
        sh "$rc" "$TMP/scaled.out" "$TMP/scaled.err"
done
# dopri5's atol is absolute (docs/cli.md): the pendulum at 1 um keeps the
# unit run's steps and answer only with atol scaled by 1e-6 too (at the
# default 1e-10 it took 31 steps, not 146, and ended 5.2e-5 rad off).
cat > "$TMP/pend-1um.json" << 'EOF'
{"name": "pendulum-1um", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [1e-6, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob", "length": 1e-6}],
 "effects": [{"type": "gravity", "g": [0, -9.81e-6]}]}
EOF
"$BRAUN" run data/pendulum.json --dt 1e-3 --t-end 3 --integrator dopri5 --quiet > "$TMP/p1m.sum"
"$BRAUN" run "$TMP/pend-1um.json" --dt 1e-3 --t-end 3 --integrator dopri5 --quiet > "$TMP/p1u.sum"
"$BRAUN" run "$TMP/pend-1um.json" --dt 1e-3 --t-end 3 --integrator dopri5 --atol 1e-16 --quiet > "$TMP/p1us.sum"
check "dopri5, the pendulum at 1 um: the unit run's steps and angle (to 1e-9) with --atol 1e-16, not at the default" \
    awk -v s1="$(json_value steps "$TMP/p1m.sum")" -v su="$(json_value steps "$TMP/p1u.sum")" \
    -v ss="$(json_value steps "$TMP/p1us.sum")" -v a="$(sed -n 's/^  "final_q": \[\(.*\), \(.*\)\],$/\1 \2/p' "$TMP/p1m.sum")" \
    -v b="$(sed -n 's/^  "final_q": \[\(.*\), \(.*\)\],$/\1 \2/p' "$TMP/p1us.sum")" \
    -v c="$(sed -n 's/^  "final_q": \[\(.*\), \(.*\)\],$/\1 \2/p' "$TMP/p1u.sum")" '
    BEGIN { split(a, x, " "); split(b, y, " "); split(c, z, " "); a0 = atan2(x[1], -x[2]);
            d = a0 - atan2(y[1], -y[2]); e = a0 - atan2(z[1], -z[2]);
            exit !(s1 == ss && su < s1 && d * d < 1e-18 && e * e > 1e-10) }'
for f in data/parallelogram-redundant.json data/iftomm/a04-bricard.json four-bar; do
    "$BRAUN" check "$f" > "$TMP/cons.out" 2>&1; rc=$?
    check "check $f (redundant rows that agree, or none): consistent: yes" sh -c '
        [ "$1" -eq 0 ] && grep -q "^consistent: yes$" "$2"' sh "$rc" "$TMP/cons.out"
done

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
# Every coordinate driven: the energy force has no direction, and a step
# is no saturation (it counted one per step: 500 here).
"$BRAUN" run data/driven-crank.json --dt 1e-3 --t-end 0.5 --corrections all > "$TMP/dca.json"
check "driven-crank --corrections all: no energy guard hits (no motion free)" \
    [ "$(json_value energy_guard_hits "$TMP/dca.json")" = 0 ]
"$BRAUN" run data/sleigh.json --dt 1e-2 --t-end 1 --corrections position,velocity > "$TMP/sl.json"
check "sleigh --corrections position,velocity: overrides the scene, braun-noenergy" sh -c '
    grep -q "^  \"corrections\": \"position,velocity\",$" "$1" &&
    grep -q "^  \"method\": \"braun-noenergy\",$" "$1"' sh "$TMP/sl.json"
"$BRAUN" run data/sleigh.json --dt 1e-2 --t-end 1 > "$TMP/sl2.json"
check "sleigh: p 1 in the summary, all corrections" sh -c '
    grep -q "^  \"p\": 1,$" "$1" && grep -q "^  \"corrections\": \"position,velocity,energy\",$" "$1"' \
    sh "$TMP/sl2.json"

# A guard stop while the adaptive driver crawls (steps of 6e-10): the time
# of the failing state and of the one kept printed alike at 10 digits.
"$BRAUN" run four-bar --backend lapack --integrator dopri5 --rtol 1e-4 --atol 1e-6 --t-end 50 --dt 1e-3 \
    > /dev/null 2> "$TMP/crawl.err"
check "guard stop: the failing and the kept state's times print differently" sh -c '
    n=$(grep -o "at t = [0-9.e+-]*" "$1" | sort -u | wc -l); [ "$n" -ge 2 ]' sh "$TMP/crawl.err"

# ------------------------------------------------- references of paper scenes
# RK4 h = 1e-3 over 2 s, measured: slider-crank trajectory error 8.10e-11,
# four-bar point error 5.24e-11.
"$BRAUN" run data/slider-crank.json --dt 1e-3 --t-end 2 > "$TMP/scr.json"
v=$(json_value max_trajectory_error "$TMP/scr.json")
if num_le "$v" 2e-10; then ok "slider-crank.json against Eq. 24: max trajectory error $v <= 2e-10"
else not_ok "slider-crank.json against Eq. 24: max trajectory error <= 2e-10" "got $v"; fi
"$BRAUN" run data/four-bar.json --dt 1e-3 --t-end 2 > "$TMP/fbr.json"
v=$(json_value max_point_error "$TMP/fbr.json")
if num_le "$v" 2e-10; then ok "four-bar.json against the closed form: max point error $v <= 2e-10"
else not_ok "four-bar.json against the closed form: max point error <= 2e-10" "got $v"; fi
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
"$BRAUN" gen chain 12 --rods -o "$TMP/rods12.json" > "$TMP/rods12.out"; rc=$?
check "gen chain 12 --rods -o FILE: exit 0, nothing on stdout" sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' \
    sh "$rc" "$TMP/rods12.out"
check "gen chain 12 --rods: n 24, m 12, rank 12, 12 dof" sizes "$TMP/rods12.json" "24 12 0 12 0 12"
"$BRAUN" gen chain 30 -o "$TMP/chain30.json"
"$BRAUN" run "$TMP/chain30.json" --dt 1e-3 --t-end 0.2 > "$TMP/c30.json"; rc=$?
v=$(json_value max_position_constraint_error "$TMP/c30.json")
# |Phi_q| measured 4.39e-14.
check "gen chain 30 runs: n 90, BRAUN_OK, |Phi_q| $v <= 2e-13" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"n\": 90,$" "$2" && grep -q "\"status\": \"BRAUN_OK\"" "$2" &&
    awk -v a="$3" "BEGIN { exit !(a != \"\" && a + 0 <= 2e-13) }"' \
    sh "$rc" "$TMP/c30.json" "$v"
"$BRAUN" gen chain 5 --angle 0 > "$TMP/chain5a.json"
check "gen chain 5 --angle 0 is the default (data/chain-5.json)" cmp -s "$TMP/chain5a.json" data/chain-5.json
"$BRAUN" gen chain 4 --angle 60 -o "$TMP/chain4-60.json" > "$TMP/chain4-60.out"; rc=$?
check "gen chain 4 --angle 60 -o FILE: exit 0, nothing on stdout" sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' \
    sh "$rc" "$TMP/chain4-60.out"
check "gen chain 4 --angle 60: n 12 m 8, rank 8, 4 dof" sizes "$TMP/chain4-60.json" "12 8 0 8 0 4"
"$BRAUN" check "$TMP/chain4-60.json" > "$TMP/c460.out"
v=$(key_value position_residual "$TMP/c460.out")
check "gen chain 4 --angle 60: on its constraints ($v), hangs at -60 degrees" sh -c '
    awk -v a="$1" "BEGIN { exit !(a + 0 <= 1e-15) }" &&
    grep -q "\"angle\": -1.0471975511965976," "$2"' sh "$v" "$TMP/chain4-60.json"
"$BRAUN" gen chain 6 --rods --angle 30 -o "$TMP/rods6.json"
check "gen chain 6 --rods --angle 30: sizes" sizes "$TMP/rods6.json" "12 6 0 6 0 6"
"$BRAUN" gen chain 2000 -o "$TMP/chain2000.json"; rc=$?
check "gen chain 2000 (the new limit) exits 0 and writes scene chain-2000" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"name\": \"chain-2000\",$" "$2"' sh "$rc" "$TMP/chain2000.json"
for bad in "chain 0" "chain 2001" "chain x" "chain" "ring 5" "chain 5 -o" "chain 5 6" "chain 5 --bogus" \
    "chain 5 --angle" "chain 5 --angle x" "chain 5 --angle 181" "chain 5 --angle nan" \
    "ladder" "ladder 0" "ladder 2001" "ladder 2.5" "ladder 3 --rods" "ladder 3 --angle -200" \
    "ladder 3 4"; do
    # shellcheck disable=SC2086
    "$BRAUN" gen $bad > "$TMP/g.out" 2> "$TMP/g.err"; rc=$?
    check "gen $bad: exit 2, one line" sh -c '[ "$1" -eq 2 ] && [ ! -s "$2" ] && [ "$(wc -l < "$3")" -eq 1 ]' \
        sh "$rc" "$TMP/g.out" "$TMP/g.err"
done

# ------------------------------------------------------------- braun gen ladder
# Three rails of N links and N rungs pinned at both ends and the middle: every
# cell a double parallelogram, one redundant row each (rank 11N of 12N).
"$BRAUN" gen ladder 4 -o "$TMP/ladder4.json" > "$TMP/ladder4.out"; rc=$?
check "gen ladder 4 -o FILE: exit 0, nothing on stdout" sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' \
    sh "$rc" "$TMP/ladder4.out"
check "gen ladder 4: n 48 m 48, rank 44, 4 redundant, 4 dof" sizes "$TMP/ladder4.json" "48 48 0 44 4 4"
"$BRAUN" gen ladder 3 --angle 60 -o "$TMP/ladder3.json"
check "gen ladder 3 --angle 60: rank 33 of 36" sizes "$TMP/ladder3.json" "36 36 0 33 3 3"
"$BRAUN" check "$TMP/ladder3.json" > "$TMP/l3.out"
v=$(key_value position_residual "$TMP/l3.out")
check "gen ladder 3 --angle 60: on its constraints at rest ($v)" sh -c '
    awk -v a="$1" "BEGIN { exit !(a + 0 <= 1e-14) }" && grep -q "^velocity_residual: 0$" "$2"' \
    sh "$v" "$TMP/l3.out"
"$BRAUN" gen ladder 1 > "$TMP/ladder1.json"
check "gen ladder 1 (the parallelogram with a third crank): rank 11 of 12" \
    sizes "$TMP/ladder1.json" "12 12 0 11 1 1"
"$BRAUN" run "$TMP/ladder4.json" --dt 1e-3 --t-end 0.5 > "$TMP/l4.json"; rc=$?
v=$(json_value max_position_constraint_error "$TMP/l4.json")
check "run ladder 4: BRAUN_OK, |Phi_q| $v, rank-deficient factorizations, backend dense" sh -c '
    [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2" &&
    awk -v a="$3" "BEGIN { exit !(a + 0 <= 1e-8) }" && ! grep -q "^  \"rank_deficient\": 0,$" "$2" &&
    grep -q "^  \"backend\": \"dense\",$" "$2" && grep -q "^  \"sparse\": false,$" "$2"' \
    sh "$rc" "$TMP/l4.json" "$v"

# ------------------------------------------------------- --sparse, --backend
same_final() { # same_final A.json B.json TOL: final_q of both runs within TOL
    awk -v a="$(json_value final_q "$1")" -v b="$(json_value final_q "$2")" -v tol="$3" 'BEGIN {
        gsub(/[][ ]/, "", a); gsub(/[][ ]/, "", b); n = split(a, x, ","); m = split(b, y, ",")
        if (n != m || n == 0) exit 1
        for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > tol) exit 1 }
        exit 0 }'
}
"$BRAUN" run "$TMP/ladder4.json" --dt 1e-3 --t-end 0.5 --sparse > "$TMP/l4s.json"; rc=$?
check "run ladder 4 --sparse: exit 0, sparse true, backend dense" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"sparse\": true,$" "$2" && grep -q "^  \"backend\": \"dense\",$" "$2"' \
    sh "$rc" "$TMP/l4s.json"
check "run ladder 4 --sparse: same final q as dense" same_final "$TMP/l4.json" "$TMP/l4s.json" 0
"$BRAUN" run data/sleigh.json --dt 1e-2 --t-end 1 --sparse > "$TMP/sls.json"; rc=$?
check "run sleigh --sparse (a knife edge, p 1): exit 0, sparse true" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"sparse\": true,$" "$2"' sh "$rc" "$TMP/sls.json"
check "run sleigh --sparse: same final q" same_final "$TMP/sl2.json" "$TMP/sls.json" 0
"$BRAUN" run "$TMP/ladder4.json" --dt 1e-3 --t-end 0.5 --backend auto > "$TMP/l4a.json"; rc=$?
check "run ladder 4 --backend auto: uses the sparsity, BRAUN_OK" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"sparse\": true,$" "$2" && grep -q "\"status\": \"BRAUN_OK\"" "$2"' \
    sh "$rc" "$TMP/l4a.json"
"$BRAUN" run data/four-bar.json --dt 1e-3 --t-end 0.5 --backend auto > "$TMP/fba.json"; rc=$?
check "run four-bar.json --backend auto: rods, dense system, BRAUN_OK" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"sparse\": false,$" "$2"' sh "$rc" "$TMP/fba.json"
# A backend counts as absent only when the tool says exactly that (exit 2,
# one line "braun: --backend NAME: backend 'NAME' not built ..."): then its
# checks are counted as skipped. Any other failure of a run with it (a
# backend built but failing) is a failure.
# Final q against the dense kernels after 500 steps of the redundant ladder:
# measured 6.2e-15 (lapack), 2.9e-15 (suitesparse) with the reference BLAS;
# the bound leaves room for another BLAS's summation order.
not_built() { # not_built BACKEND ERRFILE RC
    [ "$3" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ] && grep -q "^braun: --backend $1: backend '$1' not built" "$2"
}
ss_built=0
for be in lapack suitesparse; do
    "$BRAUN" run "$TMP/ladder4.json" --dt 1e-3 --t-end 0.5 --backend $be > "$TMP/l4b.json" 2> "$TMP/l4b.err"; rc=$?
    if not_built "$be" "$TMP/l4b.err" "$rc"; then
        skip "run ladder 4 --backend $be: BRAUN_OK, named in the summary" "$be not built: $(cat "$TMP/l4b.err")"
        skip "run ladder 4 --backend $be: final q within 5e-14 of dense" "$be not built"
        [ "$be" = suitesparse ] && ss_built=0
    else
        check "run ladder 4 --backend $be: BRAUN_OK, named in the summary" sh -c '
            [ "$1" -eq 0 ] && grep -q "^  \"backend\": \"$3\",$" "$2" &&
            grep -q "\"status\": \"BRAUN_OK\"" "$2"' sh "$rc" "$TMP/l4b.json" "$be"
        check "run ladder 4 --backend $be: final q within 5e-14 of dense" same_final "$TMP/l4.json" "$TMP/l4b.json" 5e-14
        [ "$be" = suitesparse ] && ss_built=1
    fi
done
# The parallelogram with its redundant crank, every body's angle 1e-10 off
# (its 12 rows of rank 11 are of rank 12 there, the 12th pivot about
# 1e-10): the adaptive driver's start projection took all its velocity
# away (the velocity correction at rank 12), status OK, crank angle -4.785
# at t = 2 s for 6.580 (RK4 of the minimal equation, and the exact start),
# and so did RK4's first step. The adaptive driver now projects its
# positions first, with a rank that needs sqrt(eps); a fixed step finds the
# velocity correction taking the motion away at a residual at round-off,
# projects the start so and takes its first step again.
cat > "$TMP/pg-off.json" <<'EOF'
{"name":"pg-ang1e-10","description":"parallelogram linkage with a third, redundant crank: 12 revolute rows of rank 11 everywhere (1 dof), released at 60 degrees","ground":{"points":{"A":[0,0],"E":[1,0],"B":[2,0]}},"bodies":[{"name":"crank1","type":"rigid","mass":1,"inertia":0.08333333333333333,"position":[0.2701511529340699,0.42073549240394825],"angle":1.0000000000909297,"points":{"base":[-0.5,0],"tip":[0.5,0]},"velocity":[-0.8414709848078965,0.5403023058681398],"omega":2.0},{"name":"crank2","type":"rigid","mass":1,"inertia":0.08333333333333333,"position":[1.2701511529340699,0.42073549240394825],"angle":0.9999999999041076,"points":{"base":[-0.5,0],"tip":[0.5,0]},"velocity":[-0.8414709848078965,0.5403023058681398],"omega":2.0},{"name":"crank3","type":"rigid","mass":1,"inertia":0.08333333333333333,"position":[2.27015115293407,0.42073549240394825],"angle":1.0000000000989357,"points":{"base":[-0.5,0],"tip":[0.5,0]},"velocity":[-0.8414709848078965,0.5403023058681398],"omega":2.0},{"name":"coupler","type":"rigid","mass":2,"inertia":0.6666666666666666,"position":[1.5403023058681398,0.8414709848078965],"angle":-9.999902065507035e-11,"points":{"left":[-1,0],"mid":[0,0],"right":[1,0]},"velocity":[-1.682941969615793,1.0806046117362795]}],"joints":[{"name":"pivot1","type":"revolute","a":"crank1.base","b":"ground.A"},{"name":"pivot2","type":"revolute","a":"crank2.base","b":"ground.E"},{"name":"pivot3","type":"revolute","a":"crank3.base","b":"ground.B"},{"name":"pin1","type":"revolute","a":"crank1.tip","b":"coupler.left"},{"name":"pin2","type":"revolute","a":"crank2.tip","b":"coupler.mid"},{"name":"pin3","type":"revolute","a":"crank3.tip","b":"coupler.right"}],"effects":[{"type":"gravity","g":[0,-9.81]}]}
EOF
"$BRAUN" check "$TMP/pg-off.json" > "$TMP/pgoff.check" 2>&1; rc=$?
check "check parallelogram started 1e-10 off: rank 12 at the start, rank_note names rank 11, dof 1 on its rows" sh -c '
    [ "$1" -eq 0 ] && grep -q "^rank: 12$" "$2" &&
    grep -q "^rank_note: 1 of these pivots .* the rank is 11, dof 1 " "$2"' sh "$rc" "$TMP/pgoff.check"
# Heun's own error at h = 1e-3 is 8.6e-6 rad there; its first step, taken
# again from the projected start, had lost the energy force sized at its
# end (1.1e-7 J).
for integ in dopri5 rk4 heun; do
    "$BRAUN" run "$TMP/pg-off.json" --integrator $integ --dt 1e-3 --t-end 2 > "$TMP/pgoff.json" 2>/dev/null; rc=$?
    tol=1e-5; [ $integ = heun ] && tol=2e-5
    check "run parallelogram started 1e-10 off, $integ: BRAUN_OK, crank angle 6.580149 at t = 2 (within $tol), |Phi_e| <= 1e-12" sh -c '
        [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2" &&
        sed -n "s/^  \"max_energy_error\": \(.*\),$/\1/p" "$2" | awk "{ exit !(NF == 1 && \$1 <= 1e-12) }" &&
        sed -n "s/^  \"final_q\": \[[^,]*, [^,]*, \([^,]*\),.*/\1/p" "$2" |
        awk -v tol="$3" "{ d = \$1 - 6.580149007; exit !(NF == 1 && d < tol && d > -tol) }"' sh "$rc" "$TMP/pgoff.json" "$tol"
done
# A torsion3d rest_angle of 1e12 (within the format's 1e12): its angle was
# wrapped into (-pi, pi] by a loop of 2 pi subtractions, and check did not
# finish in 5 minutes (1e9: 35 s); th - 1e12 also kept th to 1e-4 rad, so
# the energy's finite differences failed. Now at once, the rest angle
# wrapped first.
sed 's/"damping": 0.2}/"damping": 0.2, "rest_angle": 1e12}/' data/spatial-arm.json > "$TMP/coil-far.json"
timeout 60 "$BRAUN" check "$TMP/coil-far.json" > "$TMP/coil-far.out" 2>&1; rc=$?
check "check spatial-arm with a torsion3d rest_angle of 1e12: finishes, callbacks: yes" sh -c '
    [ "$1" -eq 0 ] && grep -q "^callbacks: yes" "$2"' sh "$rc" "$TMP/coil-far.out"
# The four-bar started exactly at its flat (singular) configuration, moving:
# the adaptive driver judged its rows' consistency at the end of its first
# step, where the step's own error near the singularity looked like rows
# that disagree (BRAUN_ERR_INCONSISTENT at t = 0.001, "disagree by
# 2.8e-06"); RK4, judging at t = 0, ran. Now judged at the start.
cat > "$TMP/fb-flat.json" <<'EOF'
{"name":"fbflat","description":"double four-bar linkage of Sec. 4.2 (Fig. 5): five uniform rods l = 1 m, m = 1 kg in natural coordinates; reproduces the built-in model","bodies":[{"name":"J1","type":"particle","mass":0,"position":[1.0,0.0],"velocity":[0.0,1.0]},{"name":"J2","type":"particle","mass":0,"position":[2.0,0.0],"velocity":[0.0,1.0]},{"name":"J3","type":"particle","mass":0,"position":[3.0,0.0],"velocity":[0.0,1.0]}],"rods":[{"name":"crank1","a":[0,0],"b":"J1","mass":1,"length":1},{"name":"crank2","a":[1,0],"b":"J2","mass":1,"length":1},{"name":"crank3","a":[2,0],"b":"J3","mass":1,"length":1},{"name":"coupler12","a":"J1","b":"J2","mass":1,"length":1},{"name":"coupler23","a":"J2","b":"J3","mass":1,"length":1}],"effects":[{"type":"gravity","g":[0,-9.81]}]}
EOF
"$BRAUN" run "$TMP/fb-flat.json" --integrator dopri5 --rtol 1e-9 --atol 1e-8 --dt 1e-3 --t-end 10 > "$TMP/fbflat-a.json" 2>/dev/null; rc=$?
"$BRAUN" run "$TMP/fb-flat.json" --dt 1e-3 --t-end 10 > "$TMP/fbflat-r.json" 2>/dev/null
check "run four-bar started flat, dopri5: BRAUN_OK" sh -c '
    [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2"' sh "$rc" "$TMP/fbflat-a.json"
check "run four-bar started flat, dopri5: final q within 1e-6 of RK4 h = 1e-3 (measured 1e-9)" \
    same_final "$TMP/fbflat-a.json" "$TMP/fbflat-r.json" 1e-6
# A start far off its constraints, projected by the adaptive driver: the
# Gauss-Newton step from a particle 0.02 from the pivot of a 1 m distance
# row overshot to x = 25, which its own (grown) scale judged better; it
# was kept (t0 reported at x = 6.30, |Phi_q| 38.7) and the run ended
# BRAUN_OK with |Phi_q| 2.1 at t = 2 ms. A revolute3d drive started 0.985
# off went to 10.1 (quaternion norm 1.51 at the end), status OK (found by
# an outside client). Steps that do not decrease the residual are halved.
cat > "$TMP/pin-inside.json" <<'EOF'
{"name":"pin","bodies":[{"name":"bob","type":"particle","mass":1,"position":[0.02,0]}],
 "joints":[{"name":"rod","type":"distance","a":[0,0],"b":"bob","length":1}],
 "effects":[{"type":"gravity","g":[0,-9.81]}]}
EOF
cat > "$TMP/rev3d-off.json" <<'EOF'
{"name": "rd", "bodies": [{"name": "b", "type": "rigid3d", "mass": 1, "inertia": [0.1, 0.2, 0.3], "position": [0.5, 0, 0], "points": {"c": [-0.5, 0, 0]}}], "joints": [{"name": "h", "type": "revolute3d", "a": [0, 0, 0], "b": "b.c", "axis": [0, 0, 1], "drive": {"type": "linear", "value": 1.4, "rate": 0.1}}], "effects": []}
EOF
# The inconsistency tolerance follows the rows' own size: an absolute
# sqrt(eps) was a length (m² for a distance row). Distance rows L and 2L
# from one anchor ran BRAUN_OK at L = 10 um (58 % off one of them); a
# knife across a slider driven at 10 nm/s ran BRAUN_OK at half the drive's
# rate; a consistent redundant parallelogram of 10 km rods stopped on its
# round-off (2e-8) at t = 0.1 (found by an outside client).
cat > "$TMP/twodist-10um.json" <<'EOF'
{"name":"twodist","bodies":[{"name":"b","type":"particle","mass":1,"position":[1.5e-05,0]}],
 "joints":[{"name":"short","type":"distance","a":[0,0],"b":"b","length":1e-05},
           {"name":"long","type":"distance","a":[0,0],"b":"b","length":2e-05}],
 "effects":[{"type":"gravity","g":[0,-9.81e-05]}]}
EOF
cat > "$TMP/knife-slow.json" <<'EOF'
{"name":"knife-slow","bodies":[{"name":"cart","type":"rigid","mass":1,"inertia":1e-13,"position":[0,0],"velocity":[1e-08,0],"points":{"c":[0,0]}}],
 "joints":[{"name":"rail","type":"slider","point":"cart.c","line":[0,0],"axis":[1,0],"drive":{"type":"linear","rate":1e-08}},
           {"name":"lock","type":"angle","a":"ground","b":"cart","angle":0},
           {"name":"blade","type":"knife","body":"cart","direction":[0,1]}]}
EOF
cat > "$TMP/rodpar-10km.json" <<'EOF'
{"name":"rodpar","bodies":[{"name":"J1","type":"particle","mass":0,"position":[5000,8660.254037844386]},
  {"name":"J2","type":"particle","mass":0,"position":[15000,8660.254037844386]},
  {"name":"J3","type":"particle","mass":0,"position":[25000,8660.254037844386]}],
 "rods":[{"name":"c1","a":[0,0],"b":"J1","mass":1,"length":10000},{"name":"c2","a":[10000,0],"b":"J2","mass":1,"length":10000},
  {"name":"c3","a":[20000,0],"b":"J3","mass":1,"length":10000},{"name":"k12","a":"J1","b":"J2","mass":1,"length":10000},
  {"name":"k23","a":"J2","b":"J3","mass":1,"length":10000}],
 "joints":[{"name":"k13","type":"distance","a":"J1","b":"J3","length":20000}],
 "effects":[{"type":"gravity","g":[0,-9.81]}]}
EOF
"$BRAUN" run "$TMP/twodist-10um.json" --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/td.err"; rc=$?
check "run: distance rows 10 um and 20 um from one anchor: BRAUN_ERR_INCONSISTENT at t = 0, both joints named" sh -c '
    [ "$1" -eq 1 ] && grep -q "disagree" "$2" && grep -q "at t = 0;" "$2" && grep -q "short" "$2" && grep -q "long" "$2"' \
    sh "$rc" "$TMP/td.err"
"$BRAUN" run "$TMP/knife-slow.json" --dt 0.1 --t-end 100 > /dev/null 2> "$TMP/ks.err"; rc=$?
check "run: a knife across a slider driven at 10 nm/s: BRAUN_ERR_INCONSISTENT at t = 0, rail and blade named" sh -c '
    [ "$1" -eq 1 ] && grep -q "velocity-level constraint rows disagree" "$2" && grep -q "rail" "$2" && grep -q "blade" "$2"' \
    sh "$rc" "$TMP/ks.err"
"$BRAUN" check "$TMP/knife-slow.json" > "$TMP/ks.chk" 2> "$TMP/ks.chkerr"; rc=$?
check "check: the same knife at 10 nm/s: consistent: no, exit 1, the velocity rows named (as the run judges them)" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" && grep -q "velocities have no solution" "$3" &&
    grep -q "rail" "$3" && grep -q "blade" "$3"' sh "$rc" "$TMP/ks.chk" "$TMP/ks.chkerr"
"$BRAUN" run "$TMP/rodpar-10km.json" --dt 0.1 --t-end 30 > "$TMP/rp.out" 2> /dev/null; rc=$?
check "run: a redundant parallelogram of 10 km rods: BRAUN_OK (its round-off is no inconsistency)" sh -c '
    [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2"' sh "$rc" "$TMP/rp.out"
# A diverging run raised the guard's scales it was judged by (A, q and v
# grow with it): a pendulum on a stiff spring at RK4 h = 5e-2 with the
# guard at 1 ran on to |Phi_q| 7e302 (BRAUN_ERR_DIVERGED at t = 3.5 s); a
# chain of 500 links at h = 2e-2 went from 1.6e-3 to 8e4 with its position
# scale raised to 3e84. A scale measured again now grows at most twice.
cat > "$TMP/stiffpend.json" <<'EOF'
{"name": "stiffpend", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "b", "length": 1}],
 "effects": [{"type": "spring", "a": [1, 1], "b": "b", "stiffness": 1e4, "rest_length": 0.5}]}
EOF
"$BRAUN" run "$TMP/stiffpend.json" --dt 5e-2 --t-end 5 --guard 1 --corrections position,velocity > "$TMP/sp.out" 2> /dev/null; rc=$?
check "run: a diverging pendulum, guard 1: BRAUN_ERR_ACCURACY, the states kept within |Phi_q| <= 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "\"status\": \"BRAUN_ERR_ACCURACY\"" "$2" &&
    sed -n "s/^  \"max_position_constraint_error\": \(.*\),$/\1/p" "$2" | awk "{ exit !(NF == 1 && \$1 <= 1) }"' \
    sh "$rc" "$TMP/sp.out"
for sc in pin-inside rev3d-off; do
    "$BRAUN" run "$TMP/$sc.json" --integrator dopri5 --dt 1e-3 --t-end 0.05 --out "$TMP/$sc.csv" > "$TMP/$sc.out" 2>/dev/null; rc=$?
    check "run $sc (a start far off), dopri5: BRAUN_OK, |Phi_q| <= 1e-12 at t0 and over the run" sh -c '
        [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2" &&
        sed -n "s/^  \"max_position_constraint_error\": \(.*\),$/\1/p" "$2" | awk "{ exit !(NF == 1 && \$1 <= 1e-12) }"' \
        sh "$rc" "$TMP/$sc.out"
done
# A wheel at rest on a free bearing, coaxial with a turntable driven at
# 2 pi rad/s: nothing turns it. With the energy correction the wheel's spin,
# round-off along the one free direction, took the energy law's error at
# energy_max_rel (1 %) per step and grew from 1e-43 to a turn of 7e-5 rad
# by t = 20 s, status OK (found by an outside client). Now a free motion at
# round-off of the motion's own speed gets no energy force.
cat > "$TMP/turntable.json" <<'EOF'
{"name":"turntable","description":"driven turntable (revolute3d, 1 rev/s) with a free coaxial wheel on a revolute3d bearing, wheel at rest: it must stay at rest","bodies":[{"name":"table","type":"rigid3d","mass":2,"inertia":[0.05,0.05,0.1],"position":[0,0,0],"omega":[0,0,6.283185307179586],"points":{"c":[0,0,0],"top":[0,0,0.1]}},{"name":"wheel","type":"rigid3d","mass":0.5,"inertia":[0.01,0.01,0.02],"position":[0,0,0.1],"points":{"c":[0,0,0]}}],"joints":[{"name":"motor","type":"revolute3d","a":[0,0,0],"b":"table.c","axis":[0,0,1],"drive":{"type":"linear","rate":6.283185307179586}},{"name":"bearing","type":"revolute3d","a":"table.top","b":"wheel.c","axis":[0,0,1]}],"effects":[{"type":"gravity","g":[0,0,-9.81]}]}
EOF
"$BRAUN" run "$TMP/turntable.json" --dt 1e-3 --t-end 20 --every 20000 --out "$TMP/tt.csv" > "$TMP/tt.json" 2>/dev/null; rc=$?
check "run turntable with a free wheel at rest: the wheel stays at rest (quaternion z <= 1e-12 at t = 20)" sh -c '
    [ "$1" -eq 0 ] && head -1 "$2" | cut -d, -f15 | grep -q "^wheel.q\[6\]" &&
    tail -1 "$2" | cut -d, -f15 | awk "{ z = \$1 < 0 ? -\$1 : \$1; exit !(NF == 1 && z <= 1e-12) }"' sh "$rc" "$TMP/tt.csv"
# Bricard's linkage (IFToMM A04: 35 rows of rank 34) with no corrections:
# RK4's energy error falls as h^4 on every backend. A step's later stages,
# O(h^2) off the manifold, must set aside the row the first stage set aside
# (braun_linsolver.h, stage_order); the built-in kernels and LAPACK dropped
# another row at stage 2 from t = 0.43 s to 0.83 s, and the error fell as
# h^2 (2.1e-7 at h = 1e-3, 8.3e-7 at 2e-3; SuiteSparse 2.9e-12, 4.6e-11).
# Measured now: 2.1e-12 and 3.3e-11 on both.
for be in dense lapack suitesparse; do
    "$BRAUN" run data/iftomm/a04-bricard.json --corrections none --dt 1e-3 --t-end 1 --backend $be \
        > "$TMP/brk1.json" 2> "$TMP/brk.err"; rc1=$?
    if not_built "$be" "$TMP/brk.err" "$rc1"; then
        skip "run a04-bricard --corrections none --backend $be: RK4 energy error order >= 3.3, <= 1e-10 at h = 1e-3" "$be not built"
        continue
    fi
    "$BRAUN" run data/iftomm/a04-bricard.json --corrections none --dt 2e-3 --t-end 1 --backend $be \
        > "$TMP/brk2.json" 2> "$TMP/brk.err"; rc2=$?
    e1=$(json_value max_energy_error "$TMP/brk1.json"); e2=$(json_value max_energy_error "$TMP/brk2.json")
    check "run a04-bricard --corrections none --backend $be: RK4 energy error order >= 3.3, <= 1e-10 at h = 1e-3" \
        sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 0 ] && awk -v a="$3" -v b="$4" "BEGIN { exit !(a + 0 > 0 && a + 0 <= 1e-10 && b + 0 >= 10 * (a + 0)) }"' \
        sh "$rc1" "$rc2" "$e1" "$e2"
done
if [ "$ss_built" -eq 1 ]; then
    "$BRAUN" run "$TMP/chain2000.json" --dt 1e-3 --t-end 0.005 --backend suitesparse > "$TMP/c2000.json"; rc=$?
    check "run chain 2000 (n 6000) --backend suitesparse: BRAUN_OK, sparse" sh -c '
        [ "$1" -eq 0 ] && grep -q "^  \"n\": 6000,$" "$2" && grep -q "^  \"sparse\": true,$" "$2" &&
        grep -q "\"status\": \"BRAUN_OK\"" "$2"' sh "$rc" "$TMP/c2000.json"
else
    skip "run chain 2000 (n 6000) --backend suitesparse: BRAUN_OK, sparse" "suitesparse not built"
fi
# Each must exit 2 with exactly this one line (and nothing on stdout).
refused() { # refused NAME EXPECTED ARGS...
    name=$1; expect=$2; shift 2
    "$BRAUN" "$@" > "$TMP/r.out" 2> "$TMP/r.err"; rc=$?
    if [ "$rc" -eq 2 ] && [ ! -s "$TMP/r.out" ] && [ "$(cat "$TMP/r.err")" = "$expect" ]; then ok "$name"
    else not_ok "$name" "exit $rc, stderr: $(head -c 300 "$TMP/r.err")"; fi
}
refused "chain 2000 without --sparse: too large for a dense system, names the backend that runs it" \
    "braun: 'chain-2000' has n = 6000, m = 4000, p = 0: more than a dense system allows (4096); run it with --backend suitesparse (or auto)" \
    run "$TMP/chain2000.json" --dt 1e-3 --t-end 0.01
# --sparse keeps the core's own kernels, which stop at 4096 too: the advice
# was "--sparse", which then failed with "invalid sizes", exit 1.
refused "chain 2000 --sparse on the core's kernels: the same line, exit 2" \
    "braun: 'chain-2000' has n = 6000, m = 4000, p = 0: more than a dense system allows (4096); run it with --backend suitesparse (or auto)" \
    run "$TMP/chain2000.json" --dt 1e-3 --t-end 0.01 --sparse
# A 200-link chain (n = 600) closed to a ground point beyond its reach:
# the assembly search is skipped from n = 600, and check read
# "consistent: yes", exit 0 (at n = 597 it searched and said no). Off its
# constraints and not searched is "unknown" now, with exit 1.
"$BRAUN" gen chain 200 --angle 30 -o "$TMP/cfar.json" 2> /dev/null &&
    sed 's|{"name": "hinge200", "type": "revolute", "a": "link199.b", "b": "link200.a"}|&, {"name": "far", "type": "distance", "a": "link200.b", "b": [0, -600], "length": 1}|' \
        "$TMP/cfar.json" > "$TMP/cfar2.json"
"$BRAUN" check "$TMP/cfar2.json" > "$TMP/cfar.out" 2> "$TMP/cfar.err"; rc=$?
check "check, n = 600 off its constraints (no assembly search): consistent unknown, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: unknown$" "$2" &&
    grep -q "far-200\|is off its constraints .* whether they can be met near it is not known" "$3"' \
    sh "$rc" "$TMP/cfar.out" "$TMP/cfar.err"
refused "--sparse on four-bar.json: rods have no sparsity" \
    "braun: --sparse: 'four-bar': a scene with rods has no sparsity (a rod couples the mass blocks of its ends)" \
    run data/four-bar.json --dt 1e-3 --t-end 0.01 --sparse
refused "--sparse on a built-in model" \
    "braun: --sparse: 'slider-crank': a built-in model has no sparsity (scene files without rods have one)" \
    run slider-crank --dt 1e-3 --t-end 0.01 --sparse
# A reported point named as a body would give the CSV two bob.x columns:
# refused at the report's key, for run and check alike, no CSV written.
printf '{"name": "dup", "bodies": [
  {"name": "bob", "type": "particle", "mass": 1, "position": [1, 0]},
  {"name": "arm", "type": "rigid", "mass": 1, "inertia": 1, "position": [0, 1]}],
 "joints": [{"type": "distance", "a": [0, 0], "b": "bob", "length": 1}],
 "report": {"end": [1, 1],
            "bob": [5, 5]}}\n' > "$TMP/dup.json"
refused "report named as a body (bob): FILE:LINE:COLUMN at the key, naming the clash" \
    "braun: $TMP/dup.json:6:13: reported point 'bob': body 0 is named 'bob' too: the trajectory CSV's columns bob.x, bob.y would name both; give the point a name no body has" \
    run "$TMP/dup.json" --dt 1e-2 --t-end 0.1 --out "$TMP/dup.csv"
check "... and no CSV written" test ! -e "$TMP/dup.csv"
sed 's/"bob": \[5, 5\]/"arm": "bob"/' "$TMP/dup.json" > "$TMP/dup2.json"
refused "report named as a rigid body (arm), braun check" \
    "braun: $TMP/dup2.json:6:13: reported point 'arm': body 1 is named 'arm' too: the trajectory CSV's columns arm.x, arm.y would name both; give the point a name no body has" \
    check "$TMP/dup2.json"
# In a spatial scene the body's columns are NAME.q[k]: the reason given is
# the plot's (it named planar columns that a spatial CSV has not).
printf '{"name": "dup3d", "bodies": [
  {"name": "b", "type": "rigid3d", "mass": 1, "inertia": [1, 1, 1], "position": [0, 0, -1]}],
 "joints": [{"type": "spherical", "a": "b", "b": [0, 0, 0]}],
 "report": {"b": [1, 1, 1]}}\n' > "$TMP/dup3d.json"
refused "report named as a spatial body: the reason is the plot's, not planar columns" \
    "braun: $TMP/dup3d.json:4:13: reported point 'b': body 0 is named 'b' too: --points and --plot b.x would mean either; give the point a name no body has" \
    run "$TMP/dup3d.json" --dt 1e-2 --t-end 0.1
sed 's/"bob": \[5, 5\]/"tip": "bob"/' "$TMP/dup.json" > "$TMP/dup3.json"
"$BRAUN" run "$TMP/dup3.json" --dt 1e-2 --t-end 0.1 --out "$TMP/dup3.csv" --summary /dev/null; rc=$?
check "a report name no body has still runs, each CSV column once" sh -c '
    [ "$1" -eq 0 ] && [ "$(head -n 1 "$2" | tr , "\n" | sort | uniq -d | wc -l)" -eq 0 ] &&
    head -n 1 "$2" | grep -q ",end.x \[m\],end.y \[m\],tip.x \[m\],tip.y \[m\]$"' sh "$rc" "$TMP/dup3.csv"

"$BRAUN" run data/four-bar.json --dt 1e-3 --t-end 0.01 --backend suitesparse > "$TMP/r.out" 2> "$TMP/r.err"; rc=$?
if [ "$ss_built" -eq 1 ]; then
    check "--backend suitesparse on four-bar.json (rods): exit 2, one line naming why" sh -c '
        [ "$1" -eq 2 ] && [ ! -s "$2" ] && [ "$(wc -l < "$3")" -eq 1 ] &&
        grep -q "needs a system with a sparsity pattern.*rods" "$3"' sh "$rc" "$TMP/r.out" "$TMP/r.err"
else
    check "--backend suitesparse on four-bar.json (not built): exit 2, says not built" sh -c '
        [ "$1" -eq 2 ] && [ ! -s "$2" ] && [ "$(wc -l < "$3")" -eq 1 ] &&
        grep -q "^braun: --backend suitesparse: backend .suitesparse. not built" "$3"' \
        sh "$rc" "$TMP/r.out" "$TMP/r.err"
fi

# ---------------------------------------------------------------- Andrews
# Measured: 3.5e-7 relative (the largest of the seven angles).
"$BRAUN" run andrews --dt 1e-4 --t-end 0.03 > "$TMP/andrews.json"; rc=$?
check "andrews at t = 0.03 within 1e-6 relative of the test set (h = 1e-4)" \
    awk -v rc="$rc" -v a="$(json_value final_q "$TMP/andrews.json")" 'BEGIN {
        if (rc != 0) exit 1
        split("15.81077119629904 -15.75637105984298 0.04082224013073101 -0.5347301163226948 " \
              "0.5244099658805304 0.5347301163226948 1.048080741042263", r, " ")
        gsub(/[][ ]/, "", a); n = split(a, x, ",")
        for (i = 1; i <= 7; i++) { d = (x[i] - r[i]) / r[i]; if (d < 0) d = -d; if (d > 1e-6) exit 1 }
        exit n != 7 }'

# braun check's callback comparison at extreme but correct scenes: a
# velocity of 1e6 m/s (the steps in v are 1e6 times those in q: E's
# round-off in dE_dq's differences was judged with v's step) and a drive of
# 1e12 rad/s (6e-6 s spans 1e6 of its periods: the differences must be
# refined). Both said "callbacks: no" and exited 1 for the library's own
# classes.
cat > "$TMP/fast.json" <<'EOF'
{"name": "fast", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 0], "velocity": [0, 1e6]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "b", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
cat > "$TMP/drive.json" <<'EOF'
{"name": "drive", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [0.8, 0]}],
 "joints": [{"name": "s", "type": "slider", "point": "b", "line": [0, 0], "axis": [1, 0],
             "drive": {"type": "sine", "offset": 0.8, "amplitude": 1e12, "omega": 1e12}}]}
EOF
for sc in fast drive; do
    "$BRAUN" check "$TMP/$sc.json" > "$TMP/$sc.out" 2>&1; rc=$?
    check "check $sc: the library's own callbacks pass (exit 0, callbacks: yes)" sh -c '
        [ "$1" -eq 0 ] && grep -q "^callbacks: yes" "$2"' sh "$rc" "$TMP/$sc.out"
done

# A body whose name holds a control byte (a JSON "\t"): run's CSV writes
# it as '?', and plot --traj reads that CSV back (it compared the raw name).
cat > "$TMP/tab.json" <<'EOF'
{"name": "tab", "bodies": [{"name": "a\tb", "type": "particle", "mass": 1, "position": [1, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "a\tb", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" run "$TMP/tab.json" --dt 1e-2 --t-end 0.1 --out "$TMP/tab.csv" --summary /dev/null 2> /dev/null
"$BRAUN" plot "$TMP/tab.json" --traj "$TMP/tab.csv" -o "$TMP/tab.svg" 2> "$TMP/tab.err"; rc=$?
check "plot --traj reads back run's CSV of a body named with a tab" sh -c '[ "$1" -eq 0 ] && [ -s "$2" ]' \
    sh "$rc" "$TMP/tab.svg"

# A torsion3d whose joint starts at its rest angle + pi: its potential has a
# kink there (the wrap), the central differences give the mean of its two
# slopes. check said "callbacks: no (dE_dq[6])" and exit 1; the callback
# gives one of the one-sided slopes, so yes, with a note naming the entry.
sed 's/"damping": 0.2}/"damping": 0.2, "rest_angle": 3.141592653589793}/' data/spatial-arm.json \
    > "$TMP/kink.json"
"$BRAUN" check "$TMP/kink.json" > "$TMP/kink.out" 2> "$TMP/kink.err"; rc=$?
check "check: a torsion3d at its rest angle + pi is a kink, noted, not a wrong callback" sh -c '
    [ "$1" -eq 0 ] && grep -q "^callbacks: yes" "$2" &&
    grep -q "note: .*dE_dq\[6\] is not differentiable at this state" "$3"' \
    sh "$rc" "$TMP/kink.out" "$TMP/kink.err"

# A start off the constraints with the energy correction on: a pendulum
# released from the horizontal with 3 m/s along its rod. The first
# corrections remove that velocity and its 4.5 J; E0 taken at the start had
# the energy force put them back into the swing, and the bob rose 0.46 m
# above its pivot, status OK (RK4, DOPRI5 and per-stage alike). E0 is now
# re-taken where the state is back on the constraints: the swing stays
# below the pivot, as released at rest.
cat > "$TMP/radial.json" <<'EOF'
{"name": "radial", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [1, 0],
  "velocity": [3, 0]}], "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob",
  "length": 1}], "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
for how in "--dt 1e-3" "--integrator dopri5 --dt 1e-3 --rtol 1e-8" "--dt 1e-3 --discretization per-stage"; do
    # shellcheck disable=SC2086
    "$BRAUN" run "$TMP/radial.json" $how --t-end 5 --out "$TMP/radial.csv" --summary /dev/null \
        2> /dev/null; rc=$?
    check "a start with a velocity along the rod ($how): the swing stays below the pivot" sh -c '
        [ "$1" -eq 0 ] && awk -F, "NR > 1 && \$1 > 0.01 { if (m == \"\" || \$3 > m) m = \$3 }
            END { exit !(m != \"\" && m < 1e-3) }" "$2"' sh "$rc" "$TMP/radial.csv"
done

# The same start off its rod by 0.5 m and moving off it, at a step so
# large that the ordinary drift stays above sqrt(eps): E0 is re-taken once
# the start's error is gone (the residual stops halving), so the energy
# correction still acts (it waited for good, and the energy drifted 1.4 J,
# caught only at the end); and the guard's allowance for the start's
# residuals ends there, so the summary's bounds are guard x scale again.
cat > "$TMP/off3.json" <<'EOF'
{"name": "off3", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [1.5, 0],
  "velocity": [0.5, 0.5]}], "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob",
  "length": 1}], "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" run "$TMP/off3.json" --dt 0.115 --t-end 50 --quiet > "$TMP/off3.out" 2> /dev/null; rc=$?
small=0
num_le "$(json_value final_energy_error "$TMP/off3.out")" 1e-3 &&
    num_le "$(json_value guard_position_bound "$TMP/off3.out")" 0.01 && small=1
check "a start off its rod at a large step: energy corrected after it, the start's allowance ended" \
    sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 1 ]' sh "$rc" "$small"

# Off its rod by 5 cm with --corrections position,energy: the velocity
# residual the start leaves stays (no velocity correction), and E0 waited
# for it for good — no energy force, no energy check in the run, and the
# final check refused the last state alone. Only the rows the enabled
# corrections remove decide when the start's error is gone.
cat > "$TMP/poff.json" <<'EOF'
{"name": "poff", "bodies": [{"name": "bob", "type": "particle", "mass": 1,
  "position": [0.9214616899848914, -0.5033968155344132], "velocity": [0.479425538604203, 0.8775825618903728]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" run "$TMP/poff.json" --dt 1e-3 --t-end 3 --corrections position,energy --quiet > "$TMP/poff.out" \
    2> /dev/null; rc=$?
small=0
num_le "$(json_value final_energy_error "$TMP/poff.out")" 1e-9 && small=1
check "a start off its rod, corrections position,energy: the energy law holds after it, exit 0" \
    sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 1 ]' sh "$rc" "$small"

# A start off its position constraints and moving: the first position
# correction moves q under the velocity the start had, and the velocity
# rows at the corrected q see it, O(offset x speed) whatever the step. The
# guard refused the next step's start with BRAUN_ERR_ACCURACY, naming the
# body's own row (found by an outside client): a body spinning at 1 rad/s
# about a driven revolute3d, its velocity the drive's, started 0.02 rad off
# the drive f = 0.02 + t (0.0141 against 0.0085 at t = h, for h = 1e-3 ...
# 1e-5); the spatial-arm with its bob 0.05 m off; a planar four-bar whose
# crank starts 0.05 rad off, turning at 4.9 rad/s (its velocities those of
# the rows at the start). That residual is the start's, allowed while the
# corrections remove it (docs/robustness.md): each runs, on its constraints
# after the first steps, the drive's angle 0.02 + t.
cat > "$TMP/drvoff.json" <<'EOF'
{"name": "drvoff", "ground": {"points": {"O": [0, 0, 0]}},
 "bodies": [{"name": "b", "type": "rigid3d", "mass": 1, "inertia": [0.1, 0.2, 0.25], "position": [0.5, 0, 0],
             "omega": [0, 0, 1], "velocity": [0, 0.5, 0], "points": {"p": [-0.5, 0, 0]}}],
 "joints": [{"name": "h", "type": "revolute3d", "a": "ground.O", "b": "b.p", "axis": [0, 0, 1],
             "drive": {"type": "linear", "value": 0.02, "rate": 1}}]}
EOF
# The body's angle about z, 2 atan2(q6, q3), against the drive from t = 5 ms.
drive_gap() {
    awk -F, 'NR > 1 && $1 >= 0.005 { d = 2 * atan2($8, $5) - (0.02 + $1); if (d < 0) d = -d; if (d > m) m = d }
        END { print m + 0 }' "$1"
}
for h in 1e-3 1e-4 1e-5; do
    every=$(awk -v h="$h" 'BEGIN { printf "%d", 1e-3 / h + 0.5 }')
    "$BRAUN" run "$TMP/drvoff.json" --dt "$h" --t-end 1 --every "$every" --out "$TMP/drvoff.csv" --quiet \
        > "$TMP/drvoff.out" 2> "$TMP/drvoff.err"; rc=$?
    small=0
    num_le "$(json_value final_position_constraint_error "$TMP/drvoff.out")" 1e-14 &&
        num_le "$(json_value final_velocity_constraint_error "$TMP/drvoff.out")" 1e-14 &&
        num_le "$(drive_gap "$TMP/drvoff.csv")" 1e-11 && small=1
    check "run: a revolute3d spinning, started 0.02 rad off its drive, h = $h: BRAUN_OK, on the drive 0.02 + t from 5 ms, residuals at round-off" \
        sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 1 ] && [ ! -s "$3" ]' sh "$rc" "$small" "$TMP/drvoff.err"
done
"$BRAUN" run "$TMP/drvoff.json" --dt 1e-3 --t-end 1 --corrections position,velocity --quiet > "$TMP/drvoff.out" \
    2> /dev/null; rc=$?
check "run: the same, --corrections position,velocity: BRAUN_OK" sh -c '
    [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2"' sh "$rc" "$TMP/drvoff.out"
# The guard only judges: the run is the one with the guard off, state for
# state (which stopped at t = 0 where the guard refused it).
"$BRAUN" run "$TMP/drvoff.json" --dt 1e-3 --t-end 0.2 --out "$TMP/drvoff-on.csv" --summary /dev/null 2> /dev/null
"$BRAUN" run "$TMP/drvoff.json" --dt 1e-3 --t-end 0.2 --guard -1 --out "$TMP/drvoff-off.csv" --summary /dev/null \
    2> /dev/null
check "run: the same start with the guard on and off: the same trajectory" \
    cmp -s "$TMP/drvoff-on.csv" "$TMP/drvoff-off.csv"
sed 's/"position": \[1, -0.5, 0\]/"position": [1, -0.5, 0.05]/' data/spatial-arm.json > "$TMP/arm-off.json"
"$BRAUN" run "$TMP/arm-off.json" --dt 1e-3 --t-end 1 --quiet > "$TMP/arm-off.out" 2> "$TMP/arm-off.err"; rc=$?
small=0
num_le "$(json_value final_position_constraint_error "$TMP/arm-off.out")" 1e-10 &&
    num_le "$(json_value final_velocity_constraint_error "$TMP/arm-off.out")" 1e-9 && small=1
check "run: the spatial-arm with its bob 0.05 m off its ball joint: BRAUN_OK, on its constraints" \
    sh -c '! cmp -s "$1" data/spatial-arm.json && [ "$2" -eq 0 ] && [ "$3" -eq 1 ] && [ ! -s "$4" ]' \
    sh "$TMP/arm-off.json" "$rc" "$small" "$TMP/arm-off.err"
cat > "$TMP/fourbar-off.json" <<'EOF'
{"name": "fourbar-off", "bodies": [
  {"name": "crank", "type": "rigid", "mass": 1, "inertia": 0.08333333333333333,
   "position": [0.2701511529340699, 0.42073549240394825], "angle": 1.05,
   "velocity": [-2.120964588709915, 1.216627065136846], "omega": 4.890264694639551,
   "points": {"O": [-0.5, 0], "A": [0.5, 0]}},
  {"name": "coupler", "type": "rigid", "mass": 1, "inertia": 0.5208333333333334,
   "position": [1.6919804421480489, 1.3274107654544651], "angle": 0.3992764692845797,
   "velocity": [-4.121256577350228, 2.1472598616089296], "omega": -0.24832829341504065,
   "points": {"A": [-1.25, 0], "B": [1.25, 0]}},
  {"name": "rocker", "type": "rigid", "mass": 1, "inertia": 0.3333333333333333,
   "position": [2.4218292892139788, 0.9066752730505169], "angle": 1.1353343721513196,
   "velocity": [-2.0002919893898365, 0.930632798342713], "omega": 2.2061834526683763,
   "points": {"O": [-1.0, 0], "B": [1.0, 0]}}],
 "joints": [
  {"name": "pivot1", "type": "revolute", "a": "crank.O", "b": [0, 0]},
  {"name": "knee1", "type": "revolute", "a": "crank.A", "b": "coupler.A"},
  {"name": "knee2", "type": "revolute", "a": "coupler.B", "b": "rocker.B"},
  {"name": "pivot2", "type": "revolute", "a": "rocker.O", "b": [2.0, 0]}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" run "$TMP/fourbar-off.json" --dt 1e-3 --t-end 1 --out "$TMP/fb-on.csv" > "$TMP/fb-off.out" \
    2> "$TMP/fb-off.err"; rc=$?
"$BRAUN" run "$TMP/fourbar-off.json" --dt 1e-3 --t-end 1 --guard -1 --out "$TMP/fb-noguard.csv" \
    --summary /dev/null 2> /dev/null
small=0
num_le "$(json_value final_position_constraint_error "$TMP/fb-off.out")" 1e-9 &&
    num_le "$(json_value final_velocity_constraint_error "$TMP/fb-off.out")" 1e-8 && small=1
check "run: a planar four-bar, its crank 0.05 rad off and turning: BRAUN_OK, on its constraints, the run without the guard" \
    sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 1 ] && [ ! -s "$3" ] && cmp -s "$4" "$5"' \
    sh "$rc" "$small" "$TMP/fb-off.err" "$TMP/fb-on.csv" "$TMP/fb-noguard.csv"
# Still refused: a start the corrections cannot bring onto its constraints
# (the drive 1.4 rad off: the undamped correction overshoots, the position
# residual grows), the start named as the cause with the joint of its
# largest position row; and a diverging run (a stiff spring at RK4
# h = 5e-2) from a start off its rod, within the guard's bound at --guard 1
# (the step, not the start, is named) and above it at the default.
sed 's/"value": 0.02/"value": 1.4/' "$TMP/drvoff.json" > "$TMP/drvfar.json"
"$BRAUN" run "$TMP/drvfar.json" --dt 1e-3 --t-end 1 --summary /dev/null 2> "$TMP/drvfar.err"; rc=$?
check "run: a revolute3d started 1.4 rad off its drive: BRAUN_ERR_ACCURACY at t = 0, the start's position error named" \
    sh -c '[ "$1" -eq 1 ] && grep -q "at t = 0.001; the state kept is the last one that passed, at t = 0" "$2" &&
    grep -q "the cause is the start.s position error" "$2" &&
    grep -q "the start.s largest position error is row [0-9]*, joint .h. (revolute3d)" "$2"' sh "$rc" "$TMP/drvfar.err"
cat > "$TMP/stiffoff.json" <<'EOF'
{"name": "stiffoff", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1.05, 0], "velocity": [0, 1]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "b", "length": 1}],
 "effects": [{"type": "spring", "a": [1, 1], "b": "b", "stiffness": 1e4, "rest_length": 0.5}]}
EOF
"$BRAUN" run "$TMP/stiffoff.json" --dt 5e-2 --t-end 5 --guard 1 --corrections position,velocity --summary /dev/null \
    2> "$TMP/so1.err"; rc1=$?
"$BRAUN" run "$TMP/stiffoff.json" --dt 5e-2 --t-end 5 --summary /dev/null 2> "$TMP/so2.err"; rc2=$?
check "run: a diverging run from a start off its rod: BRAUN_ERR_ACCURACY (guard 1: the start within it, not named; default: named)" \
    sh -c '[ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "BRAUN_ERR_ACCURACY" "$3" && ! grep -q "the start" "$3" &&
    grep -q "the cause is the start.s position error" "$4"' sh "$rc1" "$rc2" "$TMP/so1.err" "$TMP/so2.err"

# A drive that starts its body at rest, no gravity: every velocity of the
# start was 0, so were the guard's velocity and energy scales, the start's
# residual (the drive's 2 rad/s) was not seen, E0 stayed the energy at rest,
# and the energy force took the 0.2 J the drive gave the arm out of the
# bob's free swing (1.2 m off at t = 5, status OK). A row's own velocity
# (the drive's rate) is a velocity scale now: the motion is the one of the
# position and velocity corrections alone (their difference is the energy
# correction's O(h^4) effect), and the energy law holds.
cat > "$TMP/drvrest.json" <<'EOF'
{"name": "drvrest",
 "bodies": [{"name": "arm", "type": "rigid", "mass": 1, "inertia": 0.1, "position": [0.5, 0],
             "points": {"root": [-0.5, 0], "tip": [0.5, 0]}},
            {"name": "bob", "type": "particle", "mass": 1, "position": [1.5, 0.8]}],
 "joints": [{"name": "pin", "type": "revolute", "a": "arm.root", "b": [0, 0]},
            {"name": "drv", "type": "angle", "a": "ground", "b": "arm",
             "drive": {"type": "linear", "value": 0, "rate": 2}},
            {"name": "rod", "type": "distance", "a": "arm.tip", "b": "bob"}]}
EOF
"$BRAUN" run "$TMP/drvrest.json" --dt 1e-3 --t-end 5 --quiet > "$TMP/drvrest.all" 2> /dev/null; rc=$?
"$BRAUN" run "$TMP/drvrest.json" --dt 1e-3 --t-end 5 --corrections position,velocity --quiet \
    > "$TMP/drvrest.pv" 2> /dev/null
printf '%s|%s\n' "$(json_value final_q "$TMP/drvrest.all")" "$(json_value final_q "$TMP/drvrest.pv")" |
    tr -d '[] ' > "$TMP/drvrest.q"
check "a drive that starts its body at rest: the motion of the position/velocity corrections" sh -c '
    [ "$1" -eq 0 ] && awk -F"|" "{ n = split(\$1, x, \",\"); split(\$2, y, \",\"); m = 0
        for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > m) m = d }
        exit !(n == 5 && m < 1e-6) }" "$2"' sh "$rc" "$TMP/drvrest.q"
small=0
num_le "$(json_value final_energy_error "$TMP/drvrest.all")" 1e-12 && small=1
check "... and its energy law holds (final_energy_error <= 1e-12)" [ "$small" -eq 1 ]
# A body alone, driven from rest: the energy error read 0.05 J (the
# kinetic energy the drive gives it) for the whole run, status OK.
printf '{"name": "spin", "bodies": [{"name": "b", "type": "rigid", "mass": 1, "inertia": 0.1,
  "position": [1, 0]}], "joints": [{"name": "d", "type": "angle", "a": "ground", "b": "b",
  "drive": {"type": "linear", "value": 0, "rate": 1}}]}\n' > "$TMP/spin.json"
"$BRAUN" run "$TMP/spin.json" --dt 1e-2 --t-end 1 --quiet > "$TMP/spin.out" 2> /dev/null; rc=$?
small=0
num_le "$(json_value max_energy_error "$TMP/spin.out")" 1e-12 && small=1
check "a body alone driven from rest: no energy error after its start (was 0.05 J)" \
    sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 1 ]' sh "$rc" "$small"

# A scene naming a built-in reference with a force switched on at t = 2:
# the reference check sampled t = 0 ... 1 s and let it through, and the run
# measured a trajectory error against a model the scene is not. The models
# do not depend on time: a field that does is refused, named.
cat > "$TMP/reftime.json" <<'EOF'
{"name": "pendulum", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [1, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}, {"name": "push", "type": "force", "point": "bob",
   "fx": {"type": "step", "before": 0, "after": 100, "time": 2}, "fy": 0}], "reference": "pendulum"}
EOF
"$BRAUN" run "$TMP/reftime.json" --dt 1e-2 --t-end 3 --summary /dev/null 2> "$TMP/reftime.err"; rc=$?
check "a reference scene with a force that varies with time: refused, the effect named" sh -c '
    [ "$1" -eq 2 ] && grep -q "effect .push. (force): its .fx. varies with time" "$2"' \
    sh "$rc" "$TMP/reftime.err"

# Names that the CSV header would write alike: two bodies whose names differ
# only in a control byte (both written 'a?'), and a name longer than a
# column name keeps (its columns were cut to the same 159 bytes). run wrote
# a header with repeated column names and exit 0; now every command refuses
# the scene and names the columns.
cat > "$TMP/ctl2.json" <<'EOF'
{"name": "ctl2", "bodies": [{"name": "a\u0001", "type": "particle", "mass": 1, "position": [1, 0]},
  {"name": "a\u0002", "type": "particle", "mass": 1, "position": [2, 0]}],
 "joints": [{"type": "distance", "a": "a\u0001", "b": [0, 0], "length": 1},
  {"type": "distance", "a": "a\u0002", "b": "a\u0001", "length": 1}]}
EOF
"$BRAUN" run "$TMP/ctl2.json" --dt 1e-2 --t-end 0.1 --out "$TMP/ctl2.csv" --summary /dev/null \
    2> "$TMP/ctl2.err"; rc=$?
check "run refuses bodies whose CSV columns would share a name (a control byte apart)" sh -c '
    [ "$1" -eq 2 ] && [ ! -e "$2" ] &&
    grep -q "columns 2 and 4 of the trajectory CSV would both be named .a?\.x." "$3"' \
    sh "$rc" "$TMP/ctl2.csv" "$TMP/ctl2.err"
long=$(printf '%0170d' 0)
sed "s/a\\\\u0001/${long}1/g; s/a\\\\u0002/${long}2/g" "$TMP/ctl2.json" > "$TMP/long.json"
"$BRAUN" run "$TMP/long.json" --dt 1e-2 --t-end 0.1 --out "$TMP/long.csv" --summary /dev/null \
    2> "$TMP/long.err"; rc=$?
check "run refuses a body name too long for a CSV column, naming the column" sh -c '
    [ "$1" -eq 2 ] && [ ! -e "$2" ] && grep -q "column 2 of the trajectory CSV would be named" "$3" &&
    grep -q "longer than the 158 bytes" "$3"' sh "$rc" "$TMP/long.csv" "$TMP/long.err"

# A start off a joint that the mechanism cannot reach (a distance of 5 m
# between points at most 2 m apart): consistent to first order, so check
# names the largest row of the position residual and its joint.
cat > "$TMP/far.json" <<'EOF'
{"name": "far", "bodies": [
  {"name": "crank", "type": "rigid", "mass": 1, "inertia": 0.083333333333333329,
   "position": [0.35355339059327379, 0.35355339059327379], "angle": 0.78539816339744828,
   "points": {"O": [-0.5, 0], "A": [0.5, 0]}},
  {"name": "rod", "type": "rigid", "mass": 1, "inertia": 0.083333333333333329,
   "position": [1.0606601717798214, 0.35355339059327379], "angle": -0.78539816339744828,
   "points": {"A": [-0.5, 0], "B": [0.5, 0]}}],
 "joints": [
  {"name": "pivot", "type": "revolute", "a": "crank.O", "b": [0, 0]},
  {"name": "knee", "type": "revolute", "a": "crank.A", "b": "rod.A"},
  {"name": "far", "type": "distance", "a": "crank.O", "b": "rod.B", "length": 5}]}
EOF
"$BRAUN" check "$TMP/far.json" > "$TMP/far.out" 2> "$TMP/far.err"; rc=$?
check "check: a joint the mechanism cannot reach is named by the largest position residual" sh -c '
    grep -q "^position_residual_largest: 23 (row 4, joint .far. (distance))$" "$1"' sh "$TMP/far.out"
# ... and consistent to first order, but the assembly search (Gauss-Newton
# from the start) stalls: consistent: no, exit 1, the joints named.
check "check: no assembly of an unreachable joint: consistent: no, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "^assembly: none found (Gauss-Newton stalls at residual" "$2" &&
    grep -q "^consistent: no$" "$2"' sh "$rc" "$TMP/far.out"
check "check: the unreachable joint is named among the rows that cannot all be met" sh -c '
    grep -q "no solution near the initial state: .*joint .far. (distance) (row 4).* cannot all be met" "$1"' \
    sh "$TMP/far.err"
# Dependent rows that held for the steps before and drift apart (Bricard's
# linkage at dopri5 rtol 1e-2): the message says the motion drifted off
# them, not that the constraints have no solution.
"$BRAUN" run a04-bricard --dt 1e-3 --t-end 10 --integrator dopri5 --rtol 1e-2 --atol 1e-2 \
    > /dev/null 2> "$TMP/bricard.err"; rc=$?
check "run: dependent rows that drift apart after steps that held them are said to have drifted (exit 1)" sh -c '
    [ "$1" -eq 1 ] && grep -q "disagree by .* after [0-9]* steps that held them: the motion drifted off them" "$2" &&
    ! grep -q "disagree by [0-9.e-]*: the constraints have no solution here" "$2"' sh "$rc" "$TMP/bricard.err"
# check and run agree on dependent rows that disagree by round-off: two
# pins of one point 1e-8 m apart on a 1 m pendulum (a run takes them to
# agree, sqrt(eps) of the rows' size, and runs BRAUN_OK) read "consistent:
# no" with exit 1; 1.1e-8 m apart both refuse. At 1 m and 1 km.
for L in 1 1000; do
    for k in 1e-8 1.1e-8; do
        awk -v L="$L" -v k="$k" 'BEGIN { printf "{\"name\": \"pins\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": %.17g, \"position\": [%.17g, 0], \"angle\": 0, \"points\": {\"P\": [%.17g, 0]}}], \"joints\": [{\"name\": \"pin1\", \"type\": \"revolute\", \"a\": \"b.P\", \"b\": [0, 0]}, {\"name\": \"pin2\", \"type\": \"revolute\", \"a\": \"b.P\", \"b\": [%.17g, 0]}], \"effects\": [{\"type\": \"gravity\", \"g\": [0, -9.81]}]}\n", 0.1 * L * L, 0.5 * L, -0.5 * L, k * L }' > "$TMP/pins.json"
        "$BRAUN" check "$TMP/pins.json" > "$TMP/pins.out" 2> /dev/null; crc=$?
        "$BRAUN" run "$TMP/pins.json" --dt 1e-3 --t-end 0.1 > "$TMP/pins.run" 2> /dev/null; rrc=$?
        if [ "$k" = 1e-8 ]; then
            check "check and run: pins $k x $L m apart: consistent: yes, exit 0, and the run BRAUN_OK" sh -c '
                [ "$1" -eq 0 ] && [ "$2" -eq 0 ] && grep -q "^consistent: yes$" "$3" &&
                grep -q "^assembly: reached to round-off" "$3"' sh "$crc" "$rrc" "$TMP/pins.out"
        else
            check "check and run: pins $k x $L m apart: consistent: no, exit 1, and the run INCONSISTENT" sh -c '
                [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "^consistent: no$" "$3" &&
                grep -q "BRAUN_ERR_INCONSISTENT" "$4"' sh "$crc" "$rrc" "$TMP/pins.out" "$TMP/pins.run"
        fi
    done
done
# A driven revolute3d whose drive starts pi/2 or more from the joint's
# initial angle (0): the row sin(theta - f) would hold theta = f - pi, the
# arm half a turn off the drive with exit 0. Refused at load; 1 rad off is
# on the drive's branch and runs onto it.
cat > "$TMP/drv3.json" <<'EOF'
{"name": "drv", "bodies": [{"name": "arm", "type": "rigid3d", "mass": 1,
  "inertia": [0.0016666666666666668, 0.08416666666666667, 0.08416666666666667],
  "position": [0.5, 0, 0], "points": {"a": [-0.5, 0, 0], "b": [0.5, 0, 0]}}],
 "joints": [{"name": "hinge", "type": "revolute3d", "a": "arm.a", "b": [0, 0, 0], "axis": [0, 0, 1],
  "drive": {"type": "constant", "value": 3.0}}],
 "report": {"tip": "arm.b"}}
EOF
"$BRAUN" check "$TMP/drv3.json" > /dev/null 2> "$TMP/drv3.err"; rc=$?
check "a revolute3d drive with f(0) = 3 (theta(0) = 0) is refused at load, naming the joint" sh -c '
    [ "$1" -eq 2 ] && grep -q "joint .hinge.: drive: f(0) is pi/2 or more from the joint.s initial angle" "$2"' \
    sh "$rc" "$TMP/drv3.err"
sed 's/"value": 3.0/"value": 1.0/' "$TMP/drv3.json" > "$TMP/drv1.json"
"$BRAUN" run "$TMP/drv1.json" --dt 1e-3 --t-end 1 --out "$TMP/drv1.csv" --summary /dev/null 2> /dev/null; rc=$?
# theta is b's angle (the ground) relative to a's (the arm): the arm turns
# by -1 rad about z, its tip to (cos 1, -sin 1, 0).
check "a revolute3d drive with f(0) = 1 runs onto theta = 1 (the tip at (cos 1, -sin 1))" sh -c '
    [ "$1" -eq 0 ] && tail -n 1 "$2" | awk -F, -v h="$(head -n 1 "$2")" "
      BEGIN { n = split(h, c, \",\"); for (i = 1; i <= n; i++) { if (c[i] ~ /^tip.x/) x = i; if (c[i] ~ /^tip.y/) y = i } }
      { dx = \$x - cos(1); dy = \$y + sin(1); exit !(x && y && dx * dx + dy * dy < 1e-12) }"' \
    sh "$rc" "$TMP/drv1.csv"
# The rule is cos f(0) > 0, the angle taken modulo a full turn (the docs
# said |f(0)| >= pi/2 is refused): f(0) = 1 + 2 pi runs onto the same
# tip, f(0) = 3 + 2 pi is refused.
sed 's/"value": 3.0/"value": 7.283185307179586/' "$TMP/drv3.json" > "$TMP/drv7.json"
"$BRAUN" run "$TMP/drv7.json" --dt 1e-3 --t-end 1 --out "$TMP/drv7.csv" --summary /dev/null 2> /dev/null; rc=$?
check "a revolute3d drive with f(0) = 1 + 2 pi runs onto theta = 1 (a turn on, the same tip)" sh -c '
    [ "$1" -eq 0 ] && tail -n 1 "$2" | awk -F, -v h="$(head -n 1 "$2")" "
      BEGIN { n = split(h, c, \",\"); for (i = 1; i <= n; i++) { if (c[i] ~ /^tip.x/) x = i; if (c[i] ~ /^tip.y/) y = i } }
      { dx = \$x - cos(1); dy = \$y + sin(1); exit !(x && y && dx * dx + dy * dy < 1e-12) }"' \
    sh "$rc" "$TMP/drv7.csv"
sed 's/"value": 3.0/"value": 9.283185307179586/' "$TMP/drv3.json" > "$TMP/drv9.json"
"$BRAUN" check "$TMP/drv9.json" > /dev/null 2> "$TMP/drv9.err"; rc=$?
check "a revolute3d drive with f(0) = 3 + 2 pi is refused at load (cos f(0) <= 0)" sh -c '
    [ "$1" -eq 2 ] && grep -q "joint .hinge.: drive: f(0) is pi/2 or more" "$2"' sh "$rc" "$TMP/drv9.err"
# A function of time's value, offset and phase are 0 when left out, in
# every type ({"type": "constant"} was refused, a linear without its value
# and a sine without offset or phase accepted); the shape is required.
full='"drive": {"type": "linear", "value": 0, "rate": 6.283185307179586}'
fn_same() { # fn_same NAME GIVEN LEFT-OUT: the two drives run alike
    sed "s/$full/\"drive\": $2/" data/driven-crank.json > "$TMP/fn-a.json"
    sed "s/$full/\"drive\": $3/" data/driven-crank.json > "$TMP/fn-b.json"
    "$BRAUN" run "$TMP/fn-a.json" --dt 1e-3 --t-end 0.2 --out "$TMP/fn-a.csv" --summary /dev/null 2> /dev/null; ra=$?
    "$BRAUN" run "$TMP/fn-b.json" --dt 1e-3 --t-end 0.2 --out "$TMP/fn-b.csv" --summary /dev/null 2> "$TMP/fn-b.err"; rb=$?
    check "$1" sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 0 ] && ! grep -q "$3" "$4" && cmp -s "$5" "$6"' \
        sh "$ra" "$rb" "$full" "$TMP/fn-b.json" "$TMP/fn-a.csv" "$TMP/fn-b.csv"
}
fn_same "a constant drive without its value is 0" '{"type": "constant", "value": 0}' '{"type": "constant"}'
fn_same "a linear drive without its value starts at 0" \
    '{"type": "linear", "value": 0, "rate": 6.283185307179586}' '{"type": "linear", "rate": 6.283185307179586}'
fn_same "a sine drive without offset and phase has them 0" \
    '{"type": "sine", "offset": 0, "amplitude": 0.5, "omega": 2, "phase": 0}' '{"type": "sine", "amplitude": 0.5, "omega": 2}'
sed "s/$full/\"drive\": {\"type\": \"sine\", \"offset\": 0, \"amplitude\": 0.5}/" data/driven-crank.json > "$TMP/fn-c.json"
"$BRAUN" check "$TMP/fn-c.json" > /dev/null 2> "$TMP/fn-c.err"; rc=$?
check "a sine drive without its omega (the shape) is refused" sh -c '
    [ "$1" -eq 2 ] && grep -q "field .drive.: missing field .omega." "$2"' sh "$rc" "$TMP/fn-c.err"
# A straight two-bar chain closed to a point within reach: a singular
# start whose rows disagree to first order (consistent: no, the run stops
# at once) though a configuration 0.21 away meets them: check says so.
cat > "$TMP/stretch.json" <<'EOF'
{"name":"stretch","bodies":[{"name":"b1","type":"rigid3d","mass":1,"inertia":[0.0016666666666666668,0.08416666666666667,0.08416666666666667],"position":[0.5,0,0],"points":{"a":[-0.5,0,0],"b":[0.5,0,0]}},{"name":"b2","type":"rigid3d","mass":1,"inertia":[0.0016666666666666668,0.08416666666666667,0.08416666666666667],"position":[1.5,0,0],"points":{"a":[-0.5,0,0],"b":[0.5,0,0]}}],"joints":[{"name":"p","type":"spherical","a":"b1.a","b":[0,0,0]},{"name":"m","type":"spherical","a":"b1.b","b":"b2.a"},{"name":"close","type":"spherical","a":"b2.b","b":[1.9,0.1,0]}]}
EOF
"$BRAUN" check "$TMP/stretch.json" > "$TMP/stretch.out" 2> "$TMP/stretch.err"; rc=$?
check "check: a singular start inconsistent to first order, yet assembled near it: both said, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" && grep -q "^assembly: reached " "$2" &&
    grep -q "note: stretch: they disagree to first order only: a configuration 0.211 from the start" "$3"' \
    sh "$rc" "$TMP/stretch.out" "$TMP/stretch.err"
# A hinge whose axis_b starts 65 degrees off its axis: assembled, but only
# with damped Gauss-Newton steps, where a run's undamped correction fails
# at its first step: check warns (exit 0, consistent).
cat > "$TMP/axisb.json" <<'EOF'
{"name":"axisb","bodies":[{"name":"arm","type":"rigid3d","mass":1,"inertia":[0.0016666666666666668,0.08416666666666667,0.08416666666666667],"position":[0.5,0,0],"points":{"a":[-0.5,0,0],"b":[0.5,0,0]}}],"joints":[{"name":"hinge","type":"revolute3d","a":"arm.a","b":[0,0,0],"axis":[0,0,1],"axis_b":[0,0.9063077870366499,0.42261826174069944]}],"effects":[{"type":"gravity","g":[0,-9.81,0]}]}
EOF
"$BRAUN" check "$TMP/axisb.json" > "$TMP/axisb.out" 2> "$TMP/axisb.err"; rc=$?
"$BRAUN" run "$TMP/axisb.json" --dt 1e-3 --t-end 0.01 --summary /dev/null 2> /dev/null; rrc=$?
check "check: a start assembled only by damped steps is noted (and the run indeed fails)" sh -c '
    [ "$1" -eq 0 ] && [ "$2" -eq 1 ] && grep -q "^assembly: reached (.*, [1-9][0-9]* damped, " "$3" &&
    grep -q "note: axisb: .*had to damp" "$4"' sh "$rc" "$rrc" "$TMP/axisb.out" "$TMP/axisb.err"
# The same start with a length the mechanism reaches (1.5 m): off its
# constraints, assembled in a few steps, consistent.
sed 's/"length": 5/"length": 1.5/' "$TMP/far.json" > "$TMP/near.json"
"$BRAUN" check "$TMP/near.json" > "$TMP/near.out" 2>&1; rc=$?
check "check: a start off a joint the mechanism reaches assembles: consistent: yes" sh -c '
    [ "$1" -eq 0 ] && grep -q "^position_residual_largest: 0.25 (row 4" "$2" &&
    grep -q "^assembly: reached (residual [0-9.e+-]* after [1-9] Gauss-Newton steps\{0,1\}, " "$2" &&
    grep -q "^consistent: yes$" "$2"' sh "$rc" "$TMP/near.out"
check "check: a start on its constraints prints no position_residual_largest" sh -c '
    ! grep -q "^position_residual_largest" "$1"' sh "$TMP/sc.out"

# The accuracy guard's position or velocity stop names the element of the
# residual's largest row.
"$BRAUN" run data/pendulum.json --dt 1 --t-end 5 > /dev/null 2> "$TMP/gl.err"; rc=$?
check "guard stop: exit 1, names the joint of the residual's largest row" sh -c '
    [ "$1" -eq 1 ] && grep -q "position residual .*; its largest row, 0, is joint .rod. (distance) (BRAUN_ERR_ACCURACY" "$2"' \
    sh "$rc" "$TMP/gl.err"

# ------------------------------------------------------------ gen-c
"$BRAUN" gen-c data/sleigh.json -o "$TMP/sleigh.c"; rc=$?
check "gen-c sleigh: exit 0, defines sleigh_build and SLEIGH_N 3" sh -c '
    [ "$1" -eq 0 ] && grep -q "^int sleigh_build(" "$2" && grep -q "^#define SLEIGH_N 3$" "$2"' \
    sh "$rc" "$TMP/sleigh.c"
check "gen-c output compiles warning-free (double, -Werror)" \
    ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude/core -c "$TMP/sleigh.c" -o "$TMP/sleigh.o"
# --header: the declarations for the program's other files. A second file
# uses SLEIGH_N and sleigh_build through it alone, with one output NULL
# (q0 was left unwritten when v0 was NULL); built with the library next to
# the tool (build/libbraun.a), warning-free, and the header also as C++.
"$BRAUN" gen-c data/sleigh.json -o "$TMP/sleigh.c" --header "$TMP/sleigh.h"; rc=$?
cat > "$TMP/use_sleigh.c" <<'XCODE'
#include <stdio.h>
#include "sleigh.h"
int main(void)
{
    braun_system sys;
    braun_real q[SLEIGH_N], v[SLEIGH_N], q1[SLEIGH_N], v1[SLEIGH_N];
    for (int i = 0; i < SLEIGH_N; i++) q1[i] = v1[i] = -999;
    if (sleigh_build(&sys, q, v) || sleigh_build(&sys, q1, NULL) || sleigh_build(&sys, NULL, v1)) return 1;
    for (int i = 0; i < SLEIGH_N; i++)
        if (q1[i] != q[i] || v1[i] != v[i]) return 2;
    printf("n %d p %d corrections %u\n", sys.n, sys.p, sleigh_corrections);
    return sys.n == SLEIGH_N && sys.p == SLEIGH_P ? 0 : 3;
}
XCODE
lib=$(dirname "$BRAUN")/../libbraun.a
check "gen-c --header: another file builds on it alone (-Werror) and both outputs are written with one NULL" sh -c '
    [ "$1" -eq 0 ] && grep -q "^#define SLEIGH_N 3$" "$2/sleigh.h" &&
    ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude/core -I"$2" "$2/use_sleigh.c" "$2/sleigh.c" \
        "$3" -lm -o "$2/use_sleigh" && "$2/use_sleigh" > "$2/use.out" && grep -q "^n 3 p 1 corrections" "$2/use.out"' \
    sh "$rc" "$TMP" "$lib"
if command -v ${CXX:-g++} > /dev/null 2>&1; then
    printf '#include "sleigh.h"\nint main() { return SLEIGH_N == 3 ? 0 : 1; }\n' > "$TMP/use.cc"
    check "gen-c --header compiles as C++ too (-Werror)" \
        ${CXX:-g++} -std=c++11 -Wall -Wextra -pedantic -Werror -Iinclude/core -I"$TMP" -c "$TMP/use.cc" -o "$TMP/use_cc.o"
else
    skip "gen-c --header compiles as C++ too" "no C++ compiler"
fi
"$BRAUN" gen-c data/sleigh.json -o "$TMP/s2.c" --header - > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c --header -: exit 2 (stdout is the source's), one line" sh -c '
    [ "$1" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ] && grep -q "header" "$2"' sh "$rc" "$TMP/gce"
"$BRAUN" gen-c data/sleigh.json -o "$TMP/s3.c" --header "$TMP/s3.c" > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c --header the same file as -o: exit 2, names both" sh -c '
    [ "$1" -eq 2 ] && grep -q "same file" "$2"' sh "$rc" "$TMP/gce"
# A value a float cannot hold (1e-100 m): gen-c writes it RD(), which a
# double build takes and a BRAUN_SINGLE build refuses (the cast made it 0
# in silence).
cat > "$TMP/tiny.json" <<'EOF'
{"name": "tiny", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 1e-100]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "b"}]}
EOF
"$BRAUN" gen-c "$TMP/tiny.json" -o "$TMP/tiny.c"
check "gen-c: a value outside float's range compiles in double, not in float" sh -c '
    grep -q "RD(1e-100)" "$1" && ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude/core -c "$1" -o "$2" &&
    ! ${CC:-cc} -std=c99 -DBRAUN_SINGLE -Iinclude/core -c "$1" -o "$2" 2> /dev/null' sh "$TMP/tiny.c" "$TMP/tiny.o"
"$BRAUN" gen-c data/sleigh.json --symbol 9bad > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c --symbol 9bad: exit 2, one line" sh -c '[ "$1" -eq 2 ] && [ "$(wc -l < "$2")" -eq 1 ]' sh "$rc" "$TMP/gce"
"$BRAUN" gen-c data/no-such.json > /dev/null 2> "$TMP/gce"; rc=$?
check "gen-c of a missing file: exit 2, names the file" sh -c '[ "$1" -eq 2 ] && grep -q "no-such.json" "$2"' sh "$rc" "$TMP/gce"

# ------------------------------------------------- the same mechanism in any units
# slider_crank L [D]: data/slider-crank.json with every length L times its
# own (inertias L^2 times, g L times: the same motion in the same time, with
# the lengths among q L times the 1 m run's); with D, a distance joint
# 'far' of length D L from crank.O to rod.B (1.41 L at the start).
slider_crank() {
    awk -v L="$1" -v D="${2:-0}" 'BEGIN {
        a = 0.35355339059327379; c = 1.0606601717798214; I = 0.083333333333333329
        printf "{\"name\": \"slider-crank-%s\",\n \"bodies\": [\n", L
        printf "  {\"name\": \"crank\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": %.17g, \"position\": [%.17g, %.17g], \"angle\": 0.78539816339744828, \"points\": {\"O\": [%.17g, 0], \"A\": [%.17g, 0]}},\n", I*L*L, a*L, a*L, -0.5*L, 0.5*L
        printf "  {\"name\": \"rod\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": %.17g, \"position\": [%.17g, %.17g], \"angle\": -0.78539816339744828, \"points\": {\"A\": [%.17g, 0], \"B\": [%.17g, 0]}}],\n", I*L*L, c*L, a*L, -0.5*L, 0.5*L
        printf " \"joints\": [{\"name\": \"pivot\", \"type\": \"revolute\", \"a\": \"crank.O\", \"b\": [0, 0]},\n"
        printf "  {\"name\": \"knee\", \"type\": \"revolute\", \"a\": \"crank.A\", \"b\": \"rod.A\"},\n"
        printf "  {\"name\": \"slide\", \"type\": \"slider\", \"point\": \"rod.B\", \"line\": [0, 0], \"axis\": [1, 0]}"
        if (D > 0) printf ",\n  {\"name\": \"far\", \"type\": \"distance\", \"a\": \"crank.O\", \"b\": \"rod.B\", \"length\": %.17g}", D*L
        printf "],\n \"effects\": [{\"type\": \"gravity\", \"g\": [0, %.17g]}]}\n", -9.81*L }'
}
# The mass matrix's pivots against their own diagonal entries: the
# slider-crank with 100 nm links (inertias 8.3e-16 kg m^2 beside masses of
# 1 kg) was refused at load, "M would be singular to working precision";
# it loads, checks and moves as the 1 m one.
slider_crank 1 > "$TMP/sc-1.json"
slider_crank 1e-7 > "$TMP/sc-100nm.json"
"$BRAUN" check "$TMP/sc-100nm.json" > "$TMP/sc7.out" 2> "$TMP/sc7.err"; rc=$?
check "check: the slider-crank with 100 nm links loads: consistent, callbacks yes, exit 0" sh -c '
    [ "$1" -eq 0 ] && [ ! -s "$3" ] && grep -q "^consistent: yes$" "$2" && grep -q "^callbacks: yes" "$2"' \
    sh "$rc" "$TMP/sc7.out" "$TMP/sc7.err"
"$BRAUN" run "$TMP/sc-1.json" --dt 1e-3 --t-end 1 > "$TMP/sc-1.run" 2> /dev/null; rc1=$?
"$BRAUN" run "$TMP/sc-100nm.json" --dt 1e-3 --t-end 1 > "$TMP/sc-100nm.run" 2> /dev/null; rc2=$?
check "run: the slider-crank with 100 nm links ends where the 1 m one does (q/L, angles) to 1e-10" sh -c '
    [ "$1" -eq 0 ] && [ "$2" -eq 0 ] && { sed -n "s/^  \"final_q\": \[\(.*\)\],$/\1/p" "$3"; sed -n "s/^  \"final_q\": \[\(.*\)\],$/\1/p" "$4"; } |
    awk -F", " "NR == 1 { for (i = 1; i <= NF; i++) a[i] = \$i; n = NF; next }
        { d = 0; for (i = 1; i <= n; i++) { s = (i == 3 || i == 6) ? 1 : 1e-7; e = \$i / s - a[i]; if (e < 0) e = -e; if (e > d) d = e }
          ok = NF == 6 && n == 6 && d <= 1e-10 }
        END { exit !ok }"' sh "$rc1" "$rc2" "$TMP/sc-1.run" "$TMP/sc-100nm.run"

# braun check judges a start's residual relative to each row's own scale
# (Σ_j |A_ij| s_j: lengths by the mechanism's size, angles by 1 rad), so a
# mechanism reads the same in m, mm or um. With sqrt(eps) in the rows'
# units the assembly search was skipped below ~100 um ("consistent: yes",
# exit 0, for mechanisms no motion can assemble), and with one scale for
# all coordinates (the angles' 1 rad) a 1 um parallelogram 2 % off its
# third pivot was "reached" 0.13 % off it and read consistent.
# reach L: a particle on two distance joints of 0.3 L from anchors L apart.
reach() {
    awk -v L="$1" 'BEGIN {
        printf "{\"name\": \"reach\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": 1, \"position\": [%.17g, %.17g]}],\n", 0.5*L, -0.2*L
        printf " \"joints\": [{\"name\": \"left\", \"type\": \"distance\", \"a\": [0, 0], \"b\": \"b\", \"length\": %.17g},\n", 0.3*L
        printf "  {\"name\": \"right\", \"type\": \"distance\", \"a\": [%.17g, 0], \"b\": \"b\", \"length\": %.17g}],\n", L, 0.3*L
        printf " \"effects\": [{\"type\": \"gravity\", \"g\": [0, %.17g]}]}\n", -9.81*L }'
}
# para_off L: data/parallelogram-redundant.json, lengths L times, its third
# ground pivot at 2.02 L (2 % off).
para_off() {
    awk -v L="$1" 'BEGIN {
        I = 0.083333333333333329; y = 0.4330127018922193; th = 1.0471975511965976
        printf "{\"name\": \"para-off\", \"ground\": {\"points\": {\"A\": [0, 0], \"E\": [%.17g, 0], \"B\": [%.17g, 0]}},\n \"bodies\": [\n", L, 2.02*L
        for (k = 1; k <= 3; k++)
            printf "  {\"name\": \"crank%d\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": %.17g, \"position\": [%.17g, %.17g], \"angle\": %.17g, \"points\": {\"base\": [%.17g, 0], \"tip\": [%.17g, 0]}},\n", k, I*L*L, (k - 0.75)*L, y*L, th, -0.5*L, 0.5*L
        printf "  {\"name\": \"coupler\", \"type\": \"rigid\", \"mass\": 2, \"inertia\": %.17g, \"position\": [%.17g, %.17g], \"angle\": 0, \"points\": {\"left\": [%.17g, 0], \"mid\": [0, 0], \"right\": [%.17g, 0]}}],\n", 0.66666666666666663*L*L, 1.5*L, 2*y*L, -L, L
        printf " \"joints\": [{\"name\": \"pivot1\", \"type\": \"revolute\", \"a\": \"crank1.base\", \"b\": \"ground.A\"},\n"
        printf "  {\"name\": \"pivot2\", \"type\": \"revolute\", \"a\": \"crank2.base\", \"b\": \"ground.E\"},\n"
        printf "  {\"name\": \"pivot3\", \"type\": \"revolute\", \"a\": \"crank3.base\", \"b\": \"ground.B\"},\n"
        printf "  {\"name\": \"pin1\", \"type\": \"revolute\", \"a\": \"crank1.tip\", \"b\": \"coupler.left\"},\n"
        printf "  {\"name\": \"pin2\", \"type\": \"revolute\", \"a\": \"crank2.tip\", \"b\": \"coupler.mid\"},\n"
        printf "  {\"name\": \"pin3\", \"type\": \"revolute\", \"a\": \"crank3.tip\", \"b\": \"coupler.right\"}],\n"
        printf " \"effects\": [{\"type\": \"gravity\", \"g\": [0, %.17g]}]}\n", -9.81*L }'
}
# circles L: a particle at 1.5 L on two distance joints of L and 2 L from
# one anchor.
circles() {
    awk -v L="$1" 'BEGIN {
        printf "{\"name\": \"circles\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": 1, \"position\": [%.17g, 0]}],\n", 1.5*L
        printf " \"joints\": [{\"name\": \"short\", \"type\": \"distance\", \"a\": [0, 0], \"b\": \"b\", \"length\": %.17g},\n", L
        printf "  {\"name\": \"long\", \"type\": \"distance\", \"a\": [0, 0], \"b\": \"b\", \"length\": %.17g}]}\n", 2*L }'
}
for L in 1 1e-3 1e-4 1e-6; do
    reach "$L" > "$TMP/reach.json"
    "$BRAUN" check "$TMP/reach.json" > "$TMP/reach.out" 2> "$TMP/reach.err"; rc=$?
    check "check: a particle on two 0.3 L joints from anchors L apart, L = $L m: no assembly, consistent: no, exit 1" sh -c '
        [ "$1" -eq 1 ] && grep -q "^position_residual_largest: .* (row 0, joint .left. (distance))$" "$2" &&
        grep -q "^assembly: none found (Gauss-Newton stalls at residual [0-9.e+-]* after 3 steps)$" "$2" &&
        grep -q "^consistent: no$" "$2" &&
        grep -q "joint .left. (distance) (row 0) and joint .right. (distance) (row 1) cannot all be met" "$3"' \
        sh "$rc" "$TMP/reach.out" "$TMP/reach.err"
done
for L in 1 1e-6; do
    para_off "$L" > "$TMP/para-off.json"
    "$BRAUN" check "$TMP/para-off.json" > "$TMP/po-$L.out" 2> "$TMP/po.err"; rc=$?
    check "check: the parallelogram 2 % off its third pivot, links $L m: consistent: no (first order), assembled near, exit 1" sh -c '
        [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" && grep -q "^assembly: reached " "$2" &&
        grep -q "^braun: para-off: the constraints have no solution at the initial state: .* disagree (their least-squares residual " "$3" &&
        grep -q "note: para-off: they disagree to first order only" "$3"' sh "$rc" "$TMP/po-$L.out" "$TMP/po.err"
    # ... and a run refuses it at both sizes (the run's default tolerance
    # is relative to the rows' own coordinates: ‖q‖∞, an angle's 1 rad,
    # would let the 1 um one pass, as the absolute sqrt(eps) did).
    "$BRAUN" run "$TMP/para-off.json" --dt 1e-3 --t-end 0.01 > /dev/null 2> "$TMP/po-run.err"; rc=$?
    check "run: the parallelogram 2 % off its third pivot, links $L m: BRAUN_ERR_INCONSISTENT at t = 0" sh -c '
        [ "$1" -eq 1 ] && grep -q "disagree" "$2" && grep -q "at t = 0;" "$2"' sh "$rc" "$TMP/po-run.err"
done
check "check: ... at 1 um the message gives the residual relative to the rows' own scale" sh -c '
    grep -q "their least-squares residual 2.89e-09 is 0.000621 of the rows. own scale, above sqrt(eps) = 1.49e-08 of it, in any units" "$1"' \
    sh "$TMP/po.err"
check "check: ... and the assembly search takes the same steps at 1 m and 1 um" sh -c '
    a=$(sed -n "s/^assembly: reached (residual [0-9.e+-]* \(after [0-9]* Gauss-Newton steps, [0-9]* damped\), .*/\1/p" "$1")
    b=$(sed -n "s/^assembly: reached (residual [0-9.e+-]* \(after [0-9]* Gauss-Newton steps, [0-9]* damped\), .*/\1/p" "$2")
    [ -n "$a" ] && [ "$a" = "$b" ]' sh "$TMP/po-1.out" "$TMP/po-1e-6.out"
circles 1e-5 > "$TMP/circles-10um.json"
"$BRAUN" check "$TMP/circles-10um.json" > "$TMP/c5.out" 2> "$TMP/c5.err"; rc=$?
check "check: two distances of 10 um and 20 um from one anchor: consistent: no, both joints named, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "^consistent: no$" "$2" && grep -q "^assembly: none found " "$2" &&
    grep -q "joint .short. (distance) (row 0) and joint .long. (distance) (row 1) disagree" "$3"' \
    sh "$rc" "$TMP/c5.out" "$TMP/c5.err"
# Rows of two units (revolutes in m, a distance in m^2) at 1 um: a distance
# the slider-crank cannot reach (5 L) is found so, one it reaches (1.5 L)
# assembles.
slider_crank 1e-6 5 > "$TMP/far-1um.json"
"$BRAUN" check "$TMP/far-1um.json" > "$TMP/f6.out" 2> "$TMP/f6.err"; rc=$?
check "check: the slider-crank at 1 um with a distance it cannot reach: no assembly, consistent: no, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "^position_residual_largest: .* (row 5, joint .far. (distance))$" "$2" &&
    grep -q "^assembly: none found " "$2" && grep -q "^consistent: no$" "$2" &&
    grep -q "no solution near the initial state: .*joint .far. (distance) (row 5).* cannot all be met" "$3"' \
    sh "$rc" "$TMP/f6.out" "$TMP/f6.err"
slider_crank 1e-6 1.5 > "$TMP/near-1um.json"
"$BRAUN" check "$TMP/near-1um.json" > "$TMP/n6.out" 2> "$TMP/n6.err"; rc=$?
check "check: the slider-crank at 1 um with a distance it reaches: assembled, consistent: yes, exit 0" sh -c '
    [ "$1" -eq 0 ] && grep -q "^position_residual_largest: .* (row 5, joint .far. (distance))$" "$2" &&
    grep -q "^assembly: reached (residual [0-9.e+-]* after [1-9] Gauss-Newton steps\{0,1\}, " "$2" &&
    grep -q "^consistent: yes$" "$2"' sh "$rc" "$TMP/n6.out"

# ------------------------------------------- the accuracy guard's scales
# A scene gives the guard each coordinate's natural size (braun_scene.q_scale:
# lengths the mechanism's size, angles 1): its scales no longer mix the
# units, nor follow where the mechanism is. Andrews' mechanism as IFToMM's
# A03 (x, y, theta per body, a torque on a small inertia) had an energy
# scale of 7.1e4 J for a 2 J motion, and RK4 at h = 2e-3 ended BRAUN_OK
# with the crank 3 rad off; it is stopped now, h = 1e-4 still runs.
for hv in "2e-3 0.03" "1.5e-3 0.05"; do
    set -- $hv
    "$BRAUN" run a03-andrews --dt "$1" --t-end "$2" > "$TMP/a03g.json" 2> "$TMP/a03g.err"
    check "run: a03-andrews RK4 h = $1 to $2 s is stopped by the accuracy guard (3 rad off otherwise)" \
        sh -c '[ "$(sed -n "s/^  \"status\": \"\(.*\)\",$/\1/p" "$1")" = BRAUN_ERR_ACCURACY ]' sh "$TMP/a03g.json"
done
"$BRAUN" run a03-andrews --dt 1e-4 --t-end 0.03 > "$TMP/a03g.json" 2> "$TMP/a03g.err"
check "run: a03-andrews RK4 h = 1e-4 runs BRAUN_OK, energy scale below 20 J (a 2 J motion)" sh -c '
    [ "$(sed -n "s/^  \"status\": \"\(.*\)\",$/\1/p" "$1")" = BRAUN_OK ] &&
    awk -v e="$(sed -n "s/^  \"guard_energy_scale\": \(.*\),$/\1/p" "$1")" "BEGIN { exit !(e > 1 && e < 20) }"' \
    sh "$TMP/a03g.json"
# Translation invariance: the pendulum of data/pendulum.json moved 10 km
# (along x, and up: gravity's datum) gets the scales and verdicts it gets
# at the origin. Before, its scales grew with |q| (position 2.6e4 for a
# 1 m rod) and RK4 at h = 0.3 ended BRAUN_OK 0.9 rad off, where at the
# origin it is stopped at its first step.
pendulum_at() { # pendulum_at X Y: data/pendulum.json with its pivot at (X, Y)
    cat <<EOF
{"name": "pendulum", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [$(awk -v x="$1" 'BEGIN { print x + 1 }'), $2]}],
 "joints": [{"name": "rod", "type": "distance", "a": [$1, $2], "b": "bob", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
}
pendulum_at 0 0 > "$TMP/pend-0.json"
pendulum_at 10000 0 > "$TMP/pend-x.json"
pendulum_at 0 10000 > "$TMP/pend-y.json"
for hv in "0.3 3" "0.01 3"; do
    set -- $hv
    for w in 0 x y; do
        "$BRAUN" run "$TMP/pend-$w.json" --integrator rk4 --dt "$1" --t-end "$2" > "$TMP/pg-$w.json" 2> /dev/null
        grep -E '^  "(status|final_t|guard_(position|velocity|energy)_scale)"' "$TMP/pg-$w.json" > "$TMP/pg-$w.txt"
    done
    if [ "$1" = 0.3 ]; then want=BRAUN_ERR_ACCURACY; else want=BRAUN_OK; fi
    check "run: the pendulum moved 10 km (x, y) gets the guard's verdict ($want at RK4 h = $1) and scales it has at the origin" sh -c '
        grep -q "\"status\": \"$4\"" "$1" && cmp -s "$1" "$2" && cmp -s "$1" "$3"' \
        sh "$TMP/pg-0.txt" "$TMP/pg-x.txt" "$TMP/pg-y.txt" "$want"
done

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
