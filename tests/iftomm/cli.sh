#!/bin/sh
# The IFToMM scenes on the command line: sh tests/iftomm/cli.sh path/to/braun
# (run from the top of the tree). braun gen n-four-bar writes the shipped
# A02 scene and any N with its sizes, and refuses what does not apply;
# every data/iftomm scene loads with the sizes docs/iftomm.md gives.
# Prints "ok - NAME" / "not ok - NAME" and "N passed, M failed".
BRAUN=${1:?usage: sh tests/iftomm/cli.sh path/to/braun}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-iftomm.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; }
check() { name=$1; shift; if "$@"; then ok "$name"; else not_ok "$name"; fi; }
key_value() { sed -n "s/^$1: //p" "$2"; }
sizes() { # sizes SCENE "n m rank redundant dof"
    "$BRAUN" check "$1" > "$TMP/check.out" 2>&1 || return 1
    got="$(key_value n "$TMP/check.out") $(key_value m "$TMP/check.out") $(key_value rank "$TMP/check.out") $(key_value redundant "$TMP/check.out") $(key_value dof "$TMP/check.out")"
    [ "$got" = "$2" ] || { echo "#   $1: n m rank redundant dof = $got, expected $2"; return 1; }
}

"$BRAUN" gen n-four-bar 40 > "$TMP/a02.json"; rc=$?
check "gen n-four-bar 40 reproduces data/iftomm/a02-n-four-bar.json" \
    sh -c '[ "$1" -eq 0 ] && cmp -s "$2" data/iftomm/a02-n-four-bar.json' sh "$rc" "$TMP/a02.json"
"$BRAUN" gen n-four-bar 3 -o "$TMP/nfb3.json"
check "gen n-four-bar 3: n 8, m 7, rank 7, 1 dof" sizes "$TMP/nfb3.json" "8 7 7 0 1"
check "gen n-four-bar 1: n 4, m 3, rank 3, 1 dof" sh -c '"$1" gen n-four-bar 1 -o "$2" && exit 0' sh "$BRAUN" "$TMP/nfb1.json"
check "  and its sizes" sizes "$TMP/nfb1.json" "4 3 3 0 1"
for bad in "n-four-bar 0" "n-four-bar 2001" "n-four-bar 2 --rods" "n-four-bar 2 --angle 10" "n-four-bar"; do
    # shellcheck disable=SC2086
    "$BRAUN" gen $bad > "$TMP/bad.out" 2> "$TMP/bad.err"; rc=$?
    check "gen $bad: refused with a message (exit 2)" \
        sh -c '[ "$1" -eq 2 ] && [ ! -s "$2" ] && grep -q "^braun: " "$3"' sh "$rc" "$TMP/bad.out" "$TMP/bad.err"
done

check "a01-pendulum: n 2, m 1, 1 dof" sizes data/iftomm/a01-pendulum.json "2 1 1 0 1"
check "a02-n-four-bar: n 82, m 81, rank 81, 1 dof" sizes data/iftomm/a02-n-four-bar.json "82 81 81 0 1"
check "a03-andrews: n 21, m 20, rank 20, 1 dof" sizes data/iftomm/a03-andrews.json "21 20 20 0 1"
check "a04-bricard: n 35, m 35, rank 34, 1 redundant, 1 dof" sizes data/iftomm/a04-bricard.json "35 35 34 1 1"
check "a05-flyball-governor: n 34, m 30, rank 30, 4 dof" sizes data/iftomm/a05-flyball-governor.json "34 30 30 0 4"

# Reported points on the trajectory CSV: A01 and A02 report a particle
# under its own name ({"P1": "P1"}), whose P1.x, P1.y are the body's own
# columns: written once (they were repeated at the end, same values), and
# read back by plot --traj; A03 (F, a point of a rigid body) keeps its own.
for s in a01-pendulum:P1:2 a02-n-four-bar:B0:82; do
    scn=${s%%:*} rest=${s#*:}; pt=${rest%%:*} n=${rest#*:}
    "$BRAUN" run "data/iftomm/$scn.json" --dt 1e-3 --t-end 1e-3 --out "$TMP/$scn.csv" --summary /dev/null; rc=$?
    check "$scn --out: no column twice, $pt.x once, 1 + 2n + 4 = $((1 + 2 * n + 4)) columns" sh -c '
        [ "$1" -eq 0 ] && [ "$(head -n 1 "$2" | tr , "\n" | sort | uniq -d | wc -l)" -eq 0 ] &&
        [ "$(head -n 1 "$2" | tr , "\n" | grep -c "^$3.x \[m\]$")" -eq 1 ] &&
        awk -F, -v c="$4" "{ if (NF != c) bad = 1 } END { exit bad }" "$2"' \
        sh "$rc" "$TMP/$scn.csv" "$pt" $((1 + 2 * n + 4))
    "$BRAUN" plot "data/iftomm/$scn.json" --traj "$TMP/$scn.csv" --points "$pt" -o "$TMP/$scn.svg" 2> "$TMP/traj.err"
    check "$scn: plot --traj reads that CSV back and traces $pt" sh -c '[ "$1" -eq 0 ] && [ -s "$2" ]' sh "$?" "$TMP/$scn.svg"
done
"$BRAUN" run data/iftomm/a03-andrews.json --dt 1e-5 --t-end 1e-5 --out "$TMP/a03.csv" --summary /dev/null
check "a03-andrews --out: its reported point F keeps its columns F.x, F.y, last" \
    sh -c 'head -n 1 "$1" | grep -q ",traj_err \[q\],F.x \[m\],F.y \[m\]$"' sh "$TMP/a03.csv"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
