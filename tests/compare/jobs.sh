#!/bin/sh
# A study exported as a run list (compare/run.sh --list, `make compare-jobs`)
# and run by GNU parallel, then merged (compare/run.sh --merge), writes the
# same CSV files as the study in one process, byte for byte except the
# CPU-time columns; every line of the list is a self-contained command (run
# alone, from another directory, before its reference exists, it writes the
# same row). A part of the quick study: the four-bar with braun (and its
# cost-per-step job), RK4 + projection and MuJoCo (about 60 runs).
# Usage: sh tests/compare/jobs.sh build/bin/braun-compare
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" for a check
# that cannot run here) and a closing "N passed, M failed, K skipped".
BIN=${1:?usage: sh tests/compare/jobs.sh path/to/braun-compare}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-compare-jobs.XXXXXX") || exit 1
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
unset MAKEFLAGS MFLAGS MAKELEVEL
case $BIN in /*) ;; *) BIN=$(pwd)/$BIN ;; esac
scenes="four-bar"
methods="braun projection mujoco"
set -- --bin "$BIN" --study quick --reps 1 --scenes "$scenes" --methods "$methods"

# The list.
out="$TMP/list"   # absolute: TMP is
sh compare/run.sh --list "$@" --out "$out" > "$TMP/list.log" 2>&1; rc=$?
check "compare/run.sh --list exits 0" [ "$rc" -eq 0 ]
nprep=$("$BIN" plan --study quick --scenes "$scenes" --methods "$methods" | grep -c '^prepare ')
nrun=$("$BIN" plan --study quick --scenes "$scenes" --methods "$methods" | grep -c '^job ')
check "one reference line per scene and horizon ($nprep)" \
    [ "$(wc -l < "$out/jobs/prepare.txt")" -eq "$nprep" ]
check "one line per run ($nrun)" [ "$(wc -l < "$out/jobs/runs.txt")" -eq "$nrun" ]
check "every line is self-contained: its directories, the repository, the binary by absolute paths" \
    sh -c "! grep -v \"^mkdir -p '$out/.parts' && cd '$(pwd)' && '$BIN' run \" '$out/jobs/prepare.txt' '$out/jobs/runs.txt' | grep -q ."
check "no line needs the environment" sh -c "! grep -q 'BRAUN_CMP' '$out/jobs/runs.txt'"

# GNU parallel: the references, then the runs, two at a time; then merge.
if command -v parallel > /dev/null 2>&1; then
    (cd / && parallel --will-cite -j2 --halt now,fail=1 < "$out/jobs/prepare.txt" &&
        parallel --will-cite -j2 --halt now,fail=1 < "$out/jobs/runs.txt") > "$TMP/par.log" 2>&1; rc=$?
    check "GNU parallel runs both lists (exit 0)" [ "$rc" -eq 0 ]
    [ "$rc" -eq 0 ] || sed 's/^/#   /' "$TMP/par.log" | tail -n 10
    # Keep one run's line and the merged files' rows for the self-contained check.
    line=$(sed -n '3p' "$out/jobs/runs.txt")
    sh compare/run.sh --merge --bin "$BIN" --out "$out" --no-report > "$TMP/merge.log" 2>&1; rc=$?
    check "compare/run.sh --merge exits 0" [ "$rc" -eq 0 ]
    check "merge leaves no parts" [ ! -e "$out/.parts" ]
    check "meta.txt says the study ran as a list" grep -q '^jobs=exported' "$out/meta.txt"
else
    skip "GNU parallel runs both lists (exit 0)" "no GNU parallel (Debian package parallel)"
fi

# The same study in one process.
"$BIN" run --study quick --reps 1 --scenes "$scenes" --methods "$methods" --out "$TMP/one" \
    > "$TMP/one.log" 2>&1; rc=$?
check "single-process study exits 0" [ "$rc" -eq 0 ]

blank() { # the CPU-time columns of a file emptied
    case $1 in
    */runs.csv|*/ida_probe.csv) c1=13 c2=14 ;;
    */step_cost.csv) c1=8 c2=9 ;;
    *) cat "$1"; return ;;
    esac
    awk -F, -v OFS=, -v a="$c1" -v b="$c2" 'NR > 1 { $a = $b = "" } { print }' "$1"
}
if [ -s "$out/runs.csv" ]; then
    for f in $("$BIN" files); do
        blank "$out/$f" > "$TMP/a"
        blank "$TMP/one/$f" > "$TMP/b"
        if cmp -s "$TMP/a" "$TMP/b"; then ok "$f: GNU parallel + merge = one process (but the CPU columns)"
        else not_ok "$f: GNU parallel + merge = one process (but the CPU columns)" \
            "$(diff "$TMP/a" "$TMP/b" | head -n 4 | tr '\n' ' ')"; fi
    done
    check "runs.csv has the peers' and the projection's rows" sh -c \
        "awk -F, '\$3 == \"mujoco\" { m++ } \$3 == \"projection\" { p++ } END { exit !(m && p) }' '$out/runs.csv'"

    # One line alone, from another directory, with no reference prepared:
    # it computes the reference itself and writes the same row.
    k=$(printf '%s\n' "$line" | sed -n 's/.* --job \([0-9]*\) .*/\1/p')
    (cd / && sh -c "$line") > "$TMP/alone.log" 2>&1; rc=$?
    check "a run line alone exits 0" [ "$rc" -eq 0 ]
    part=$(dirname "$out/.parts/j$k/runs.csv")
    check "... computing its reference itself" grep -q "computing the reference of run $k" \
        "$out/.parts/j$k.log"
    row=$(blank "$part/runs.csv" | tail -n 1)
    check "... and writing the row of the merged study" sh -c \
        "blank() { awk -F, -v OFS=, 'NR > 1 { \$13 = \$14 = \"\" } { print }' \"\$1\"; }
         blank '$out/runs.csv' | grep -qxF '$row'"
fi

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
