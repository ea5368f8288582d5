#!/bin/sh
# Tests of the braun command-line tool: sh tests/cli/run.sh path/to/braun
# Prints "ok - NAME" / "not ok - NAME" per check ("ok - NAME # SKIP WHY" for
# one that cannot run here) and a closing line "N passed, M failed, K
# skipped"; exit status 1 if anything failed.
BRAUN=${1:?usage: sh tests/cli/run.sh path/to/braun}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-cli.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0

ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { # check NAME COMMAND...: passes when COMMAND succeeds
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}

# Value of "key" in a summary written by braun (one key per line).
json_value() { sed -n "s/^  \"$1\": \(.*\)$/\1/p" "$2" | sed 's/,$//; s/^"//; s/"$//'; }
# Awk does the float comparisons: POSIX sh has integers only.
num_le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a != "null" && a + 0 <= b + 0) }'; }
num_lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a != "null" && a + 0 < b + 0) }'; }
num_eq() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 == b + 0) }'; }
lines() { wc -l < "$1" | tr -d ' '; }
# await_rows FILE: until the CSV a background run writes has a few rows
# (the timing run writes nothing), at most 60 s.
await_rows() {
    i=0
    while [ $i -lt 600 ] && ! { [ -s "$1" ] && [ "$(lines "$1")" -gt 3 ]; }; do
        sleep 0.1; i=$((i + 1))
    done
}

if command -v python3 > /dev/null 2>&1; then HAVE_PY=1; else HAVE_PY=0; fi
json_parses() { python3 -c 'import json,sys; json.load(sys.stdin)' < "$1" 2> /dev/null; }

# ------------------------------------------------------------ help, version, list
"$BRAUN" --help > "$TMP/help" 2>&1; rc=$?
check "--help exits 0" [ "$rc" -eq 0 ]
check "--help shows the run usage" grep -q "braun run MODEL" "$TMP/help"
check "--help says how cpu_s is measured" \
    grep -q "cpu_s is the integration alone, measured in a separate run without" "$TMP/help"
"$BRAUN" --version > "$TMP/version" 2>&1; rc=$?
check "--version exits 0 and names braun" \
    sh -c '[ "$1" -eq 0 ] && grep -q "^braun [0-9]" "$2"' sh "$rc" "$TMP/version"
"$BRAUN" list > "$TMP/list" 2>&1; rc=$?
check "list exits 0" [ "$rc" -eq 0 ]
for model in slider-crank four-bar pendulum andrews; do
    check "list shows $model" grep -q "^$model " "$TMP/list"
done
check "list has one line per model, then the shipped scenes" sh -c '
    [ "$(sed -n "/^\$/q;p" "$1" | wc -l)" -eq 4 ] && grep -q "^shipped scenes (" "$1" &&
    grep -q "^four-bar.json  *n=6 m=5 p=0" "$1" && grep -q "^damped-motor.json " "$1" &&
    grep -q "^iftomm/a05-flyball-governor.json n=34 m=30 p=0" "$1"' sh "$TMP/list"

# ----------------------------------------------------------------- bad arguments
# Each must exit 2, print nothing on stdout and exactly one "braun: " line on stderr.
bad() { # bad NAME ARGS...
    name=$1; shift
    "$BRAUN" "$@" > "$TMP/bad.out" 2> "$TMP/bad.err"; rc=$?
    if [ "$rc" -eq 2 ] && [ ! -s "$TMP/bad.out" ] && [ "$(lines "$TMP/bad.err")" -eq 1 ] &&
        grep -q "^braun: " "$TMP/bad.err"; then
        ok "bad argument: $name"
    else
        not_ok "bad argument: $name" "exit $rc, stderr: $(head -c 300 "$TMP/bad.err")"
    fi
}
run="run slider-crank --t-end 1"
bad "no arguments"
bad "unknown command" frobnicate
bad "unknown option" $run --dt 1e-3 --bogus 1
bad "unknown single-dash option" $run --dt 1e-3 -x
bad "missing value at the end" $run --dt
bad "missing value before an option" run slider-crank --dt --t-end 1
bad "non-numeric dt" $run --dt abc
bad "dt with trailing garbage" $run --dt 1e-3s
bad "dt = 0" $run --dt 0
bad "dt < 0" $run --dt -1e-3
bad "dt = inf" $run --dt inf
bad "dt = nan" $run --dt nan
bad "t-end = 0" run slider-crank --dt 1e-3 --t-end 0
bad "t-end < 0" run slider-crank --dt 1e-3 --t-end -5
bad "missing --dt" $run
bad "missing MODEL" run --dt 1e-3 --t-end 1
bad "two models" run slider-crank four-bar --dt 1e-3 --t-end 1
bad "unknown model" run no-such-model --dt 1e-3 --t-end 1
bad "unknown integrator" $run --dt 1e-3 --integrator rk45
bad "unknown correction" $run --dt 1e-3 --corrections position,friction
bad "empty correction item" $run --dt 1e-3 --corrections position,,velocity
bad "unknown discretization" $run --dt 1e-3 --discretization per-week
bad "every = 0" $run --dt 1e-3 --out "$TMP/x.csv" --every 0
bad "every not an integer" $run --dt 1e-3 --out "$TMP/x.csv" --every 2.5
bad "negative rank-tol" $run --dt 1e-3 --rank-tol -1
bad "both tolerances 0" $run --dt 1e-3 --integrator dopri5 --rtol 0 --atol 0
bad "rtol >= 1" $run --dt 1e-3 --integrator dopri5 --rtol 2
bad "per-stage with dopri5" $run --dt 1e-3 --integrator dopri5 --discretization per-stage
bad "csv and summary both on stdout" $run --dt 1e-3 --out -
bad "unwritable summary" $run --dt 1e-3 --summary "$TMP/no/such/dir/s.json"
bad "unknown backend" $run --dt 1e-3 --backend cuda
bad "backend without a value" $run --dt 1e-3 --backend
bad "empty backend" $run --dt 1e-3 --backend=
bad "--sparse with a value" $run --dt 1e-3 --sparse=yes
bad "--sparse on a built-in model" $run --dt 1e-3 --sparse
bad "--backend suitesparse on a built-in model" $run --dt 1e-3 --backend suitesparse
# bad_msg NAME PATTERN ARGS...: as bad, within 10 s, the line matching PATTERN (grep -E).
bad_msg() {
    name=$1 pattern=$2; shift 2
    timeout 10 "$BRAUN" "$@" > "$TMP/bad.out" 2> "$TMP/bad.err"; rc=$?
    if [ "$rc" -eq 2 ] && [ ! -s "$TMP/bad.out" ] && [ "$(lines "$TMP/bad.err")" -eq 1 ] &&
        grep -Eq -- "$pattern" "$TMP/bad.err"; then
        ok "bad argument: $name"
    else
        not_ok "bad argument: $name" "exit $rc, stderr: $(head -c 300 "$TMP/bad.err")"
    fi
}
# --max-steps bounds a fixed-step run too, before it starts (the default,
# 1e8, is the adaptive driver's): --dt 1e-12 to 1 s would run for hours.
bad_msg "fixed-step run of 1e12 steps: refused at once, count, limit and option named" \
    "^braun: --dt 1e-12 to --t-end 1 is a fixed-step run of [0-9]+ steps \(T/H = 1e\+12\), more than --max-steps 100000000 allows" \
    run pendulum --dt 1e-12 --t-end 1
bad_msg "plot: the same limit" "more than --max-steps 100000000 allows" \
    plot pendulum --dt 1e-10 --t-end 1 -o "$TMP/ms.svg"
bad_msg "--max-steps 999 for 1000 steps: refused" \
    "^braun: --dt 0.001 to --t-end 1 is a fixed-step run of 1000 steps \(T/H = 1000\), more than --max-steps 999" \
    run pendulum --dt 1e-3 --t-end 1 --max-steps 999
# The library's count: 1/1e-9 is 999999999.9999999 in double, a whole
# number up to round-off (the allowance is capped at half a step): 1e9
# steps, as braun_integrate takes them (the tool said 999999999).
bad_msg "--dt 1e-9 to 1 s counts 1000000000 steps, as the library" \
    "^braun: --dt 1e-09 to --t-end 1 is a fixed-step run of 1000000000 steps" \
    run pendulum --dt 1e-9 --t-end 1
# An option given twice, tolerances to a fixed-step run, a reference
# coarser than the run: refused, not settled in silence (the last --dt won,
# --rtol was ignored, --ref-h 10 at --dt 1e-3 made the trajectory error the
# reference's).
bad_msg "--dt given twice: refused" "^braun: option --dt given twice: give it once$" \
    run pendulum --dt 1e-3 --t-end 1 --dt 1e-2
bad_msg "--out given twice: refused" "^braun: option --out given twice" \
    run pendulum --dt 1e-3 --t-end 1 --out "$TMP/a.csv" --out "$TMP/b.csv"
bad_msg "--rtol with rk4: refused" "^braun: --rtol and --atol apply to --integrator dopri5 only" \
    run pendulum --dt 1e-3 --t-end 1 --rtol 1e-6
bad_msg "--ref-h not finer than --dt: refused" "^braun: --ref-h 10: the reference's substep must be finer than --dt 0.001" \
    run slider-crank --dt 1e-3 --t-end 5 --ref-h 10
# ... and the default keeps the same rule: dt/10 below --dt 1e-3 (the
# default 1e-4 at --dt 1e-5 was the run's own step, which --ref-h 1e-4 is
# refused for).
"$BRAUN" run slider-crank --dt 1e-5 --t-end 0.01 --quiet > "$TMP/refh.json" 2> /dev/null
check "the default reference substep at --dt 1e-5 is finer than the step (1e-6)" sh -c '
    awk -v h="$1" "BEGIN { exit !(h != \"\" && h + 0 < 1e-5 && h + 0 > 9.9e-7) }"' \
    sh "$(json_value ref_h "$TMP/refh.json")"
# Numbers are decimal, as docs/cli.md says: strtod also took a hexadecimal
# float and leading blanks.
bad_msg "--dt 0x1p-10: not a decimal number" "^braun: --dt: '0x1p-10' is not a decimal number" \
    run pendulum --dt 0x1p-10 --t-end 1
bad_msg "--dt ' 1e-3': not a decimal number" "^braun: --dt: ' 1e-3' is not a decimal number" \
    run pendulum --dt " 1e-3" --t-end 1
# ... and integers as strictly (strtol took leading blanks: gen chain ' 3'
# made a chain of 3).
bad_msg "gen chain ' 3': not an integer" "^braun: N must be an integer in \[1, 2000\] \(got ' 3'\)" \
    gen chain " 3"
bad_msg "--every ' 2': not an integer" "^braun: --every must be an integer >= 1 \(got ' 2'\)" \
    run pendulum --dt 1e-3 --t-end 1 --out "$TMP/e.csv" --every " 2"
bad_msg "--max-steps ' 5': not a decimal number" "^braun: --max-steps: ' 5' is not a decimal number" \
    run pendulum --integrator dopri5 --dt 1e-3 --t-end 1 --max-steps " 5"
bad_msg "plot --frames ' 3': not an integer" "^braun: --frames must be an integer from 1 to 1000 \(got ' 3'\)" \
    plot pendulum --dt 1e-3 --t-end 1 -o "$TMP/f.svg" --frames " 3"
# dopri5's first step below its default minimum (1e-12 of the span): the
# run stopped with exit 1, BRAUN_ERR_STEP_TOO_SMALL (h = 100) at t = 0.
bad_msg "dopri5 --dt 1 --t-end 1e15: below the minimum step, said with the numbers" \
    "^braun: --dt 1 is below the adaptive step's minimum 1000 at --t-end 1e\+15 .*--t-end <= 1e\+12 or --dt >= 1000$" \
    run pendulum --integrator dopri5 --dt 1 --t-end 1e15
bad_msg "--every beyond a long: too large, not 'an integer >= 1'" "^braun: --every 99999999999999999999 is too large" \
    run pendulum --dt 1e-3 --t-end 1 --out "$TMP/e.csv" --every 99999999999999999999
bad_msg "gen-c of a built-in model without a scene file: says so" \
    "^braun: gen-c: 'andrews' is a built-in model with no scene file" gen-c andrews
for v in 0 -3; do bad_msg "--max-steps $v" "^braun: --max-steps must be >= 1 \(got $v\)$" $run --dt 1e-3 --max-steps $v; done
bad_msg "--max-steps 2.5" "^braun: --max-steps must be a whole number of steps" $run --dt 1e-3 --max-steps 2.5
for v in 1e19 99999999999999999999999; do
    bad_msg "--max-steps $v: beyond a long" "^braun: --max-steps $v: more than the library's step limit can hold" \
        $run --dt 1e-3 --max-steps $v
done
for v in inf nan abc; do bad_msg "--max-steps $v" "^braun: --max-steps: '$v' is not" $run --dt 1e-3 --max-steps $v; done
"$BRAUN" run pendulum --dt 1e-3 --t-end 1 --max-steps 1e3 > "$TMP/ms.json" 2> "$TMP/ms.err"; rc=$?
check "--max-steps 1e3 for 1000 steps: runs them, the summary's max_steps 1000" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"steps\": 1000,$" "$2" && grep -q "^  \"max_steps\": 1000,$" "$2" &&
    ! grep -q "^  \"defaults\": .*max_steps" "$2"' sh "$rc" "$TMP/ms.json"
"$BRAUN" run pendulum --dt 1e-3 --t-end 1 > "$TMP/ms.json"
check "a fixed-step run's summary: max_steps 100000000, the default" sh -c '
    grep -q "^  \"max_steps\": 100000000,$" "$1" && grep -q "^  \"defaults\": .*\"max_steps\"" "$1"' \
    sh "$TMP/ms.json"
"$BRAUN" run pendulum --dt 1e-3 --t-end 1 --integrator dopri5 --max-steps 5 > "$TMP/ms.json" 2> "$TMP/ms.err"; rc=$?
check "dopri5 --max-steps 5: stops after 5 attempts, exit 1, BRAUN_ERR_TOO_MANY_STEPS" sh -c '
    [ "$1" -eq 1 ] && grep -q "^  \"status\": \"BRAUN_ERR_TOO_MANY_STEPS\",$" "$2" &&
    grep -q "^  \"max_steps\": 5,$" "$2" && grep -q "^  \"steps\": 5,$" "$2"' sh "$rc" "$TMP/ms.json"

# --help and --version take nothing more: a word after them is a mistake,
# refused (exit 2) rather than ignored; so is every command's --help.
bad "--help with an extra argument" --help extra
bad "-h with an extra argument" -h extra
bad "help with an extra argument" help extra
bad "--version with an extra argument" --version extra
for cmd in run plot check gen gen-c list; do
    bad "$cmd --help with an extra argument" $cmd --help extra
    bad "$cmd -h after an argument" $cmd extra -h
    "$BRAUN" $cmd --help > "$TMP/chelp" 2>&1; rc=$?
    check "$cmd --help alone: exit 0, the usage" sh -c '[ "$1" -eq 0 ] && grep -q "^Usage: braun run" "$2"' \
        sh "$rc" "$TMP/chelp"
done
"$BRAUN" run scene.json --dt 1e-3 --t-end 1 > /dev/null 2> "$TMP/scene.err"; rc=$?
check "missing scene file: exit 2 and 'cannot open'" \
    sh -c '[ "$1" -eq 2 ] && [ "$(cat "$2")" = "braun: scene.json: cannot open: No such file or directory" ]' \
    sh "$rc" "$TMP/scene.err"

# ---------------------------------------------------------------- a short run
"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 > "$TMP/short.json" 2> "$TMP/short.err"; rc=$?
check "run slider-crank --dt 1e-3 --t-end 1 exits 0" [ "$rc" -eq 0 ]
check "a successful run prints nothing on stderr" [ ! -s "$TMP/short.err" ]
if [ "$HAVE_PY" -eq 1 ]; then
    check "summary is valid JSON" json_parses "$TMP/short.json"
else
    skip "summary is valid JSON" "python3 not found"
fi
missing=""
for key in scene method corrections discretization integrator dt t_end steps rhs_evals \
    rejected_steps mass_factorizations constraint_factorizations rank_deficient \
    energy_guard_hits cpu_s max_position_constraint_error max_velocity_constraint_error \
    max_energy_error max_trajectory_error max_point_error final_position_constraint_error \
    final_velocity_constraint_error final_energy_error final_trajectory_error final_t \
    final_q final_v status n m p backend sparse rank_tol libbraun_version; do
    grep -q "^  \"$key\": " "$TMP/short.json" || missing="$missing $key"
done
if [ -z "$missing" ]; then ok "summary has every key"; else not_ok "summary has every key" "missing:$missing"; fi
check "summary: scene, method, status, steps" sh -c '
    [ "$(sed -n "s/^  \"scene\": \"\(.*\)\",$/\1/p" "$1")" = slider-crank ] &&
    grep -q "^  \"method\": \"braun\",$" "$1" &&
    grep -q "^  \"corrections\": \"position,velocity,energy\",$" "$1" &&
    grep -q "^  \"status\": \"BRAUN_OK\",$" "$1" &&
    grep -q "^  \"steps\": 1000,$" "$1"' sh "$TMP/short.json"
check "summary: default backend dense, no sparsity" sh -c '
    grep -q "^  \"backend\": \"dense\",$" "$1" && grep -q "^  \"sparse\": false,$" "$1"' sh "$TMP/short.json"
"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 --backend auto > "$TMP/auto.json"; rc=$?
check "run slider-crank --backend auto: a built-in model (n 6) stays on the dense kernels" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"backend\": \"dense\",$" "$2"' sh "$rc" "$TMP/auto.json"
"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 --backend=dense > "$TMP/dense.json"; rc=$?
check "run slider-crank --backend=dense: the default's final state" sh -c '
    [ "$1" -eq 0 ] && [ "$(grep final_q "$2")" = "$(grep final_q "$3")" ]' sh "$rc" "$TMP/dense.json" "$TMP/short.json"
check "summary: no point error for the slider-crank is null" \
    [ "$(json_value max_point_error "$TMP/short.json")" = null ]

"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 --corrections position,velocity \
    --summary "$TMP/noen.json" > "$TMP/noen.out" 2>&1; rc=$?
check "--summary FILE: exit 0, stdout empty" sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' sh "$rc" "$TMP/noen.out"
check "energy off: method braun-noenergy" [ "$(json_value method "$TMP/noen.json")" = braun-noenergy ]

# ------------------------------------------------------------------ trajectory CSV
header="t [s],crank.x [m],crank.y [m],crank.theta [rad],rod.x [m],rod.y [m],rod.theta [rad],crank.vx [m/s],crank.vy [m/s],crank.omega [rad/s],rod.vx [m/s],rod.vy [m/s],rod.omega [rad/s],pos_err [Phi_q],vel_err [Phi_q/s],energy_err [J],traj_err [q]"
"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 --out "$TMP/k1.csv" --summary "$TMP/k1.json"; rc=$?
check "--out: exit 0" [ "$rc" -eq 0 ]
check "--out: header" [ "$(head -n 1 "$TMP/k1.csv")" = "$header" ]
check "--out: 1/1e-3 + 1 rows" [ "$(lines "$TMP/k1.csv")" -eq $((1000 + 1 + 1)) ]
"$BRAUN" run slider-crank --dt 1e-3 --t-end 1 --out "$TMP/k10.csv" --every 10 --summary /dev/null; rc=$?
check "--every 10: 1/1e-3/10 + 1 rows" \
    sh -c '[ "$1" -eq 0 ] && [ "$(wc -l < "$2")" -eq 102 ]' sh "$rc" "$TMP/k10.csv"
check "--every 10: first row at t = 0, last at t = 1" \
    sh -c '[ "$(sed -n 2p "$1" | cut -d, -f1)" = 0 ] && [ "$(tail -n 1 "$1" | cut -d, -f1)" = 1 ]' \
    sh "$TMP/k10.csv"
check "--every 10: 17 columns, traj_err filled" \
    awk -F, 'NR > 1 && (NF != 17 || $17 == "") { bad = 1 } END { exit bad }' "$TMP/k10.csv"

# ------------------------------------------------------------------ issue targets
"$BRAUN" run slider-crank --dt 1e-3 --t-end 100 --integrator rk4 --discretization per-step \
    --summary "$TMP/long.json"; rc=$?
check "slider-crank RK4 dt 1e-3 to t = 100 exits 0" [ "$rc" -eq 0 ]
# Bounds a small factor above the measured values (x86-64, gcc 12, -O2):
# |Phi_q| 2.92e-12, trajectory 3.54e-9 (the issue's acceptance figures were
# 1e-9 and 1e-6: 300x slack, which an order-3 RK4 passed).
v=$(json_value max_position_constraint_error "$TMP/long.json")
if num_le "$v" 1e-11; then ok "max_position_constraint_error <= 1e-11 ($v)"
else not_ok "max_position_constraint_error <= 1e-11" "got $v"; fi
v=$(json_value max_trajectory_error "$TMP/long.json")
if num_le "$v" 1e-8; then ok "max_trajectory_error <= 1e-8 ($v)"
else not_ok "max_trajectory_error <= 1e-8" "got $v"; fi

# --------------------------------------------------------------- runtime failure
# Without corrections the slider-crank drifts off its constraints and the step
# diverges near the singular configuration long before t = 100.
"$BRAUN" run slider-crank --dt 1e-3 --t-end 100 --corrections none --out "$TMP/none.csv" \
    --every 7 --summary "$TMP/none.json" 2> "$TMP/none.err"; rc=$?
check "--corrections none to t = 100 exits 1" [ "$rc" -eq 1 ]
check "failure: one 'braun: ' line on stderr naming the status" sh -c '
    [ "$(wc -l < "$1")" -eq 1 ] && grep -q "^braun: .* at t = .*(BRAUN_ERR_" "$1"' sh "$TMP/none.err"
st=$(json_value status "$TMP/none.json")
check "failure: summary written, status not BRAUN_OK ($st)" \
    sh -c '[ -n "$1" ] && [ "$1" != BRAUN_OK ]' sh "$st"
check "failure: method braun-custom, corrections none" sh -c '
    grep -q "^  \"method\": \"braun-custom\",$" "$1" &&
    grep -q "^  \"corrections\": \"none\",$" "$1"' sh "$TMP/none.json"
ft=$(json_value final_t "$TMP/none.json")
last=$(tail -n 1 "$TMP/none.csv" | cut -d, -f1)
if num_lt "$ft" 100 && num_eq "$last" "$ft"; then ok "failure: CSV ends at final_t = $ft < 100"
else not_ok "failure: CSV ends at final_t < 100" "final_t $ft, last CSV t $last"; fi
if [ "$HAVE_PY" -eq 1 ]; then
    check "failure: summary is valid JSON" json_parses "$TMP/none.json"
else
    skip "failure: summary is valid JSON" "python3 not found"
fi

# --------------------------------------------------------------- other integrators
# Adaptive dopri5 (default tolerances): point error measured 8.97e-9.
"$BRAUN" run four-bar --dt 1e-2 --t-end 2 --integrator dopri5 --summary "$TMP/dp.json"; rc=$?
v=$(json_value max_point_error "$TMP/dp.json")
check "four-bar dopri5 exits 0 with a point error <= 3e-8 ($v)" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"integrator\": \"dopri5\",$" "$2" &&
    awk -v a="$3" "BEGIN { exit !(a != \"\" && a != \"null\" && a + 0 <= 3e-8) }"' sh "$rc" "$TMP/dp.json" "$v"
# Trajectory error at h = 1e-3 over 1 s, measured: euler 1.11e-2, heun 8.0e-6.
for m in euler:3e-2 heun:2e-5; do
    bound=${m#*:} m=${m%%:*}
    "$BRAUN" run pendulum --dt 1e-3 --t-end 1 --integrator $m --summary "$TMP/$m.json"; rc=$?
    v=$(json_value max_trajectory_error "$TMP/$m.json")
    check "pendulum $m exits 0, BRAUN_OK, trajectory error <= $bound ($v)" sh -c '
        [ "$1" -eq 0 ] && grep -q "\"status\": \"BRAUN_OK\"" "$2" &&
        awk -v a="$3" -v b="$4" "BEGIN { exit !(a != \"\" && a != \"null\" && a + 0 <= b + 0) }"' \
        sh "$rc" "$TMP/$m.json" "$v" "$bound"
done

# ------------------------------------------------------------ interruption
# SIGTERM (or Ctrl-C's SIGINT) during the monitored run: it stops at its
# next reported state; the CSV keeps every row up to it, each whole, the
# summary says BRAUN_STOPPED; exit 128 + 15. Run 1 (timing, about 1 s here)
# writes nothing, so the signal is sent once the CSV has rows.
"$BRAUN" run pendulum --dt 1e-5 --t-end 20 --out "$TMP/int.csv" --summary "$TMP/int.json" \
    2> "$TMP/int.err" & pid=$!
await_rows "$TMP/int.csv"
kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
check "run: SIGTERM in the monitored run exits 143 and says where it stopped" sh -c '
    [ "$1" -eq 143 ] && grep -q "^braun: interrupted by SIGTERM at t = [0-9.e+-]*: the run stopped there" "$2"' \
    sh "$rc" "$TMP/int.err"
check "run: SIGTERM: every CSV row whole, the last ends with a newline" sh -c '
    awk -F, "NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || NR < 3 }" "$1" &&
    [ "$(tail -c 1 "$1" | od -An -c | tr -d " ")" = "\\n" ]' sh "$TMP/int.csv"
t_last=$(tail -n 1 "$TMP/int.csv" | cut -d, -f1)
check "run: SIGTERM: the summary says BRAUN_STOPPED at the CSV's last time" sh -c '
    grep -q "\"status\": \"BRAUN_STOPPED\"" "$1" && grep -q "\"cpu_s\": null" "$1" &&
    awk -v a="$2" -v b="$3" "BEGIN { exit !(a != \"\" && a + 0 == b + 0) }"' \
    sh "$TMP/int.json" "$(json_value final_t "$TMP/int.json")" "$t_last"
# ... and in the timing run: nothing kept, the files it created removed.
"$BRAUN" run pendulum --dt 1e-5 --t-end 900 --out "$TMP/int1.csv" --summary "$TMP/int1.json" \
    2> "$TMP/int1.err" & pid=$!
sleep 1
kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
check "run: SIGTERM in the timing run exits 143, keeps nothing, removes what it created" sh -c '
    [ "$1" -eq 143 ] && grep -q "^braun: interrupted by SIGTERM during the timing run" "$2" &&
    [ ! -e "$3" ] && [ ! -e "$4" ]' sh "$rc" "$TMP/int1.err" "$TMP/int1.csv" "$TMP/int1.json"
# ... files that existed stay as they were (they were left empty).
echo "old rows" > "$TMP/int2.csv"; echo "old summary" > "$TMP/int2.json"
"$BRAUN" run pendulum --dt 1e-5 --t-end 900 --out "$TMP/int2.csv" --summary "$TMP/int2.json" \
    2> "$TMP/int2.err" & pid=$!
sleep 1
kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
check "run: SIGTERM in the timing run leaves files that existed as they were" sh -c '
    [ "$1" -eq 143 ] && [ "$(cat "$2")" = "old rows" ] && [ "$(cat "$3")" = "old summary" ]' \
    sh "$rc" "$TMP/int2.csv" "$TMP/int2.json"
# The same signal twice at once (GNU timeout signals the tool, then its
# process group): one request. The copy found the default disposition
# (signal() resets it) and killed the tool mid-row, the summary empty.
"$BRAUN" run pendulum --dt 1e-5 --t-end 20 --out "$TMP/int3.csv" --summary "$TMP/int3.json" \
    2> "$TMP/int3.err" & pid=$!
await_rows "$TMP/int3.csv"
kill -TERM $pid 2> /dev/null; kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
check "run: two SIGTERMs at once are one request: rows whole, summary BRAUN_STOPPED, exit 143" sh -c '
    [ "$1" -eq 143 ] && grep -q "^braun: interrupted by SIGTERM at t = " "$2" &&
    awk -F, "NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || NR < 3 }" "$3" &&
    grep -q "\"status\": \"BRAUN_STOPPED\"" "$4"' \
    sh "$rc" "$TMP/int3.err" "$TMP/int3.csv" "$TMP/int3.json"

# An interrupted plot draws what it has (it wrote nothing, and said so,
# where the docs promised the picture up to the stop).
"$BRAUN" plot four-bar --dt 1e-3 --t-end 100000 -o "$TMP/int4.svg" 2> "$TMP/int4.err" & pid=$!
sleep 1
kill -TERM $pid 2> /dev/null; wait $pid; rc=$?
check "plot: SIGTERM draws the picture up to the stop, exit 143" sh -c '
    [ "$1" -eq 143 ] && grep -q "the picture is drawn up to that state" "$2" &&
    grep -q "<title>four-bar: rk4, h = 0.001 s, t = 0 \.\.\. [0-9.e+]* s" "$3" && grep -q "</svg>" "$3"' \
    sh "$rc" "$TMP/int4.err" "$TMP/int4.svg"

# A run that overflows where the library has no check of its own (Heun,
# no corrections: the monitor's energy is +Inf first) said BRAUN_STOPPED,
# which means a signal or a callback stopped it; the status is the
# monitor's, with its time.
"$BRAUN" run slider-crank --dt 2.5e-4 --t-end 10 --integrator heun --corrections none --quiet \
    > "$TMP/ovf.json" 2> "$TMP/ovf.err"; rc=$?
check "run: an overflow caught by the monitoring is BRAUN_ERR_NONFINITE, not BRAUN_STOPPED, exit 1" sh -c '
    [ "$1" -eq 1 ] && grep -q "\"status\": \"BRAUN_ERR_NONFINITE\"" "$2" &&
    ! grep -q "BRAUN_STOPPED" "$2" && grep -q "monitoring failed after t = " "$3"' \
    sh "$rc" "$TMP/ovf.json" "$TMP/ovf.err"
# Its summary agrees with itself: the state the monitoring failed on is not
# kept (the CSV and final_t end before it), nor counted in steps, and
# error_t is its time, the stderr line's "at t = ". A particle on a 1e6 N/m
# spring, Euler at 0.01 s: the energy is +Inf at the 153rd state; the
# summary said steps 153, final_t 1.52, error_t 1.52 (RK4's divergence of
# the same scene: steps 58, final_t 0.58, error_t 0.59).
cat > "$TMP/stiff.json" << 'EOF'
{"name": "stiff", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1.1, 0]}],
 "joints": [{"name": "rail", "type": "slider", "point": "b", "line": [0, 0], "axis": [1, 0]}],
 "effects": [{"type": "spring", "a": [0, 0], "b": "b", "stiffness": 1e6, "rest_length": 1}]}
EOF
"$BRAUN" run "$TMP/stiff.json" --dt 0.01 --t-end 10 --integrator euler --guard -1 --out "$TMP/stiff.csv" \
    > "$TMP/stiff.sum" 2> "$TMP/stiff.err"; rc=$?
check "run: monitoring failure: steps count the states kept, error_t the failing state's (153rd, t = 1.53)" sh -c '
    [ "$1" -eq 1 ] && [ "$2" = "BRAUN_ERR_NONFINITE 152 1.52 1.53" ] &&
    grep -q "^braun: monitoring failed after t = 1.52: energy E\[0\] is +Inf at t = 1.53 " "$3" &&
    [ "$(tail -n 1 "$4" | cut -d, -f1)" = 1.52 ] && [ "$(wc -l < "$4")" -eq 154 ]' \
    sh "$rc" "$(json_value status "$TMP/stiff.sum") $(json_value steps "$TMP/stiff.sum") $(json_value final_t \
    "$TMP/stiff.sum") $(json_value error_t "$TMP/stiff.sum")" "$TMP/stiff.err" "$TMP/stiff.csv"
# The same rule on the slider-crank's overflow above (Heun, 2.5e-4 s):
# final_t is steps x dt, error_t one step later.
check "run: monitoring failure (slider-crank, Heun): final_t = steps x dt, error_t = final_t + dt" \
    awk -v n="$(json_value steps "$TMP/ovf.json")" -v t="$(json_value final_t "$TMP/ovf.json")" \
    -v e="$(json_value error_t "$TMP/ovf.json")" -v h=2.5e-4 \
    'BEGIN { exit !(n > 0 && (n * h - t) ^ 2 < 1e-20 && (t + h - e) ^ 2 < 1e-20) }'

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
