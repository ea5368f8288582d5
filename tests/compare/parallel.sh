#!/bin/sh
# A study whose runs are processes of their own (compare/run.sh) writes the
# same CSV files whether the runs go one at a time (COMPARE_JOBS=1), two at
# a time through the jobserver of `make -j2`, or all in one process with one
# reference per scene and horizon (braun-compare run): byte for byte except
# the CPU-time columns cpu_s, cpu_s_max. A subset of the quick study: the
# paper's slider-crank (rk8pd reference, looked up off its table by the
# adaptive runs), the four-bar (closed form) and, where scenes are built,
# driven-crank (braun RK4 reference with its work integral).
# Usage: sh tests/compare/parallel.sh build/bin/braun-compare
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" for a check
# that cannot run here) and a closing "N passed, M failed, K skipped".
BIN=${1:?usage: sh tests/compare/parallel.sh path/to/braun-compare}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-compare-parallel.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "${2:-}" ] || echo "#   $2"; }
check() { # check NAME COMMAND...
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
# This test makes its own jobservers, whatever make runs it.
unset MAKEFLAGS MFLAGS MAKELEVEL

case $BIN in /*) ;; *) BIN=$(pwd)/$BIN ;; esac
scenes="slider-crank four-bar"
# driven-crank is a scene file: only a harness built without the scene
# library (it says so) leaves it out, counted as a skip. Any other failure to
# plan it is a failure.
"$BIN" plan --study quick --scenes driven-crank > /dev/null 2> "$TMP/plan.err"; rc=$?
if [ "$rc" -eq 0 ]; then
    scenes="$scenes driven-crank"
    ok "driven-crank (a scene file) is in the study"
elif grep -q "scenes need the scene library" "$TMP/plan.err"; then
    skip "driven-crank (a scene file) is in the study" "braun-compare built without scenes"
else
    not_ok "driven-crank (a scene file) is in the study" "plan: exit $rc, $(head -c 200 "$TMP/plan.err")"
fi
methods="braun baumgarte ida-ggl"
set -- --bin "$BIN" --study quick --reps 1 --scenes "$scenes" --methods "$methods" --no-report

# One at a time.
sh compare/run.sh "$@" --jobs 1 --out "$TMP/serial" > "$TMP/serial.log" 2>&1; rc=$?
check "serial study (--jobs 1) exits 0" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || sed 's/^/#   /' "$TMP/serial.log" | tail -n 20

# Two at a time through make's jobserver: run.sh from a `+` recipe, as in
# mk/compare.mk. --jobs 1 would make it serial if the jobserver did not
# reach it.
q() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }
args=""
for a in "$@"; do args="$args $(q "$a")"; done
{
    printf 'all:\n'
    printf '\t+@sh compare/run.sh%s --jobs 1 --out %s\n' "$args" "$(q "$TMP/par")" |
        sed 's/\$/$$/g'
} > "$TMP/study.mk"
make -j2 --no-print-directory -f "$TMP/study.mk" > "$TMP/par.log" 2>&1; rc=$?
check "study under make -j2 exits 0" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || sed 's/^/#   /' "$TMP/par.log" | tail -n 20
check "make -j2: the runs took part in its jobserver" grep -q "make's jobserver (-j2)" "$TMP/par.log"
check "serial: one at a time" grep -q "1 at a time" "$TMP/serial.log"

# All in one process, one reference per scene and horizon kept in memory.
"$BIN" run --study quick --reps 1 --scenes "$scenes" --methods "$methods" \
    --out "$TMP/one" > "$TMP/one.log" 2>&1; rc=$?
check "single-process study exits 0" [ "$rc" -eq 0 ]

# One reference per scene and horizon, one progress line per run.
ngroups=$(echo "$scenes" | wc -w)
nruns=$("$BIN" plan --study quick --scenes "$scenes" --methods "$methods" | grep -c '^job ')
check "the plan has runs ($nruns)" [ "$nruns" -gt 0 ]
check "one reference process per scene ($ngroups)" \
    [ "$(grep -c '^\[ref ' "$TMP/par.log")" -eq "$ngroups" ]
check "one progress line per run ($nruns)" \
    [ "$(grep -c '^\[ *[0-9]*/[0-9]* ' "$TMP/par.log")" -eq "$nruns" ]
check "no parts left behind" [ ! -e "$TMP/par/.parts" ]

# The files with their CPU-time columns blanked: cpu_s, cpu_s_max (13, 14)
# of runs.csv and ida_probe.csv, cpu_per_step_s, cpu_per_step_max_s (8, 9)
# of step_cost.csv.
blank() {
    case $1 in
    */runs.csv|*/ida_probe.csv) c1=13 c2=14 ;;
    */step_cost.csv) c1=8 c2=9 ;;
    *) cat "$1"; return ;;
    esac
    awk -F, -v OFS=, -v a="$c1" -v b="$c2" 'NR > 1 { if ($a == "" || $b == "") bad = 1; $a = $b = "" } { print }
                                             END { exit bad }' "$1"
}
same() { # same FILE DIR_A DIR_B
    [ -s "$2/$1" ] && [ -s "$3/$1" ] || { echo "#   $1 missing"; return 1; }
    blank "$2/$1" > "$TMP/a" || { echo "#   $2/$1: empty CPU column"; return 1; }
    blank "$3/$1" > "$TMP/b" || { echo "#   $3/$1: empty CPU column"; return 1; }
    cmp -s "$TMP/a" "$TMP/b" && return 0
    diff "$TMP/a" "$TMP/b" | head -n 6 | sed 's/^/#   /'
    return 1
}
files=$("$BIN" files)
check "the study writes its files (${files})" [ -n "$files" ]
for f in $files; do
    check "$f: make -j2 = serial" same "$f" "$TMP/serial" "$TMP/par"
    check "$f: one process = serial" same "$f" "$TMP/one" "$TMP/serial"
done
rows() { echo $(($(wc -l < "$1") - 1)); }
# Every run is a row of runs.csv or ida_probe.csv, but the cost-per-step
# jobs (one per paper scene: their rows are in step_cost.csv).
ncost=$(awk -F, 'NR > 1 { print $1 }' "$TMP/par/step_cost.csv" | sort -u | wc -l)
check "runs.csv has every run" [ "$(($(rows "$TMP/par/runs.csv") + $(rows "$TMP/par/ida_probe.csv") + ncost))" -eq "$nruns" ]
check "one row per run" sh -c \
    "[ \"\$(cut -d, -f1-7 '$TMP/par/runs.csv' | sort -u | wc -l)\" -eq \$(wc -l < '$TMP/par/runs.csv') ]"
check "references.csv has rows" [ "$(rows "$TMP/par/references.csv")" -ge "$ngroups" ]
check "singular.csv has rows" [ "$(rows "$TMP/par/singular.csv")" -ge 1 ]

# A step that fails fails the study, and no merged file pretends otherwise.
cat > "$TMP/failing" <<EOF
#!/bin/sh
case " \$* " in *" --job 2 "*) echo "failing on purpose" >&2; exit 1 ;; esac
exec '$BIN' "\$@"
EOF
chmod +x "$TMP/failing"
sh compare/run.sh --bin "$TMP/failing" --study quick --reps 1 --scenes four-bar --methods ode-rk4 \
    --no-report --jobs 2 --out "$TMP/fail" > "$TMP/fail.log" 2>&1; rc=$?
check "a failing run fails the study" [ "$rc" -ne 0 ]
check "... and writes no runs.csv" [ ! -e "$TMP/fail/runs.csv" ]

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
