#!/bin/sh
# The headline figures of make bench (issue 16), one row per figure:
#   OUT/headline.csv   figure,measured,target,met
#   OUT/headline.md    the same as the table of docs/performance.md
# from what the other parts of make bench measured in this run:
#   OUT/time.csv, OUT/variants.csv      bench.sh (host, slider-crank)
#   MJ/step_cost.csv                    braun-compare's cost job: braun's
#                                       corrected RK4 step and MuJoCo's RK4
#                                       mj_step in one process
#   FW/bench.csv                        make firmware-bench (the 100 s runs)
#   SC/scaling.md, SC/slopes.csv        make scaling
# A figure whose source did not run is "not measured" (met: no).
# With DOCS, its <!-- bench:headline --> block gets the table.
# Usage: sh bench/headline.sh OUT MJ_DIR FW_DIR SCALING_DIR [DOCS]
OUT=${1:?usage: headline.sh OUT MJ_DIR FW_DIR SCALING_DIR [DOCS]}
MJ=${2:-}
FW=${3:-}
SC=${4:-}
DOCS=${5:-}
CSV=$OUT/headline.csv
MD=$OUT/headline.md

row() { # figure measured target met
    # The figure and the measured value may hold commas: quoted (RFC 4180;
    # neither holds a double quote).
    echo "\"$1\",\"$2\",$3,$4" >> "$CSV"
    echo "| $1 | $2 | $3 | $4 |" >> "$MD"
}
# met when a <= b (numbers); "no" when not measured.
le() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || a == "not measured") print "no";
                                         else print (a + 0 <= b + 0) ? "yes" : "no" }'; }

echo "figure,measured,target,met" > "$CSV"
{
    echo "| figure | measured | target | met |"
    echo "|---|---|---|---|"
} > "$MD"

# Host: the corrected slider-crank RK4 step (median ns, generic build and
# the fixed-size -O3 -flto build), with its ratio to the ideal step.
gen=$(awk -F, '$1 == "slider-crank" && $10 == "step-all" { print $16; exit }' "$OUT/time.csv" 2>/dev/null)
gen_r=$(awk -F, '$1 == "slider-crank" && $10 == "step-all" { print $19; exit }' "$OUT/time.csv" 2>/dev/null)
spec=$(awk -F, '$1 == "fixed-O3-lto" && $3 == "step-all" { print $4; exit }' "$OUT/variants.csv" 2>/dev/null)
spec_r=$(awk -F, '$1 == "fixed-O3-lto" && $3 == "step-all" { print $5; exit }' "$OUT/variants.csv" 2>/dev/null)
row "host: corrected slider-crank RK4 step, generic build [ns] (corrected/ideal ${gen_r:-?})" \
    "${gen:-not measured}" "<= 1000" "$(le "$gen" 1000)"
row "host: corrected slider-crank RK4 step, fixed sizes -O3 -flto [ns] (corrected/ideal ${spec_r:-?})" \
    "${spec:-not measured}" "<= 500" "$(le "$spec" 500)"

# Against MuJoCo: braun's corrected RK4 step / MuJoCo's RK4 mj_step.
for scene in four-bar slider-crank; do
    r=""
    if [ -f "$MJ/step_cost.csv" ]; then
        r=$(awk -F, -v s="$scene" '$1 == s && $2 == "braun" && $3 == "rk4" { b = $8 }
                                   $1 == s && $2 == "mujoco" && $3 == "mj-rk4" { m = $8 }
                                   END { if (b > 0 && m > 0) printf "%.3g", b / m }' "$MJ/step_cost.csv")
    fi
    row "braun corrected RK4 step / MuJoCo RK4 mj_step, $scene (one process)" \
        "${r:-not measured}" "<= 0.1" "$(le "$r" 0.1)"
done

# Cortex-M4F (QEMU -icount): instructions per corrected slider-crank step
# over 100 s, mean and worst case; no double operation on the float path is
# make test's check (tests/firmware/run.sh), not a figure here.
for p in float float-fixed; do
    t=15000
    [ "$p" = float-fixed ] && t=10000
    mean="" max=""
    if [ -f "$FW/bench.csv" ]; then
        mean=$(awk -F, -v p="$p" '$1 == "slider-crank" && $2 == p && $3 == "all" && $4 >= 100000 { print $6 }' "$FW/bench.csv" | tail -n 1)
        max=$(awk -F, -v p="$p" '$1 == "slider-crank" && $2 == p && $3 == "all" && $4 >= 100000 { print $8 }' "$FW/bench.csv" | tail -n 1)
    fi
    row "M4F $p: instructions per corrected slider-crank step, mean over 100 s" \
        "${mean:-not measured}" "<= $t" "$(le "$mean" "$t")"
    row "M4F $p: instructions of the worst step over 100 s" "${max:-not measured}" \
        "reported (<= $t)" "$(le "$max" "$t")"
done

# Large mechanisms: the redundant ladder against the chain per body on
# SuiteSparse at the largest N — the median of make scaling's back-to-back
# pairs (bench/scaling/run.sh, pairs.csv), else its one point per run —
# and its slope.
lr=""
ls=""
if [ -f "$SC/scaling.md" ]; then
    lr=$(sed -n 's/^Ladder against the chain per body on SuiteSparse at N = \([0-9]*\), back-to-back pairs.*: \*\*\([0-9.]*\)\*\* (\(.*\))\.$/\2 (N = \1; pairs \3)/p' "$SC/scaling.md" | head -n 1)
    [ -n "$lr" ] ||
        lr=$(sed -n 's/^ladder against the chain, cost per body on SuiteSparse.*N = \([0-9]*\): \*\*\([0-9.]*\)\*\*;$/\2 (N = \1)/p' "$SC/scaling.md" | head -n 1)
fi
[ -f "$SC/slopes.csv" ] && ls=$(awk -F, '$1 == "ladder" && $2 == "suitesparse" { print $3; exit }' "$SC/slopes.csv")
row "redundant ladder / chain, cost per body on SuiteSparse" "${lr:-not measured}" "<= 3" \
    "$(le "${lr%% *}" 3)"
row "redundant ladder on SuiteSparse, slope of cost per step against N" "${ls:-not measured}" \
    "<= 1.3" "$(le "$ls" 1.3)"

echo "bench: wrote $CSV" >&2
if [ -n "$DOCS" ] && [ -f "$DOCS" ] && grep -q '^<!-- bench:headline -->$' "$DOCS"; then
    awk -v f="$MD" '
        /^<!-- bench:headline -->$/ { print; while ((getline l < f) > 0) print l; skip = 1; next }
        /^<!-- \/bench:headline -->$/ { skip = 0 }
        !skip { print }' "$DOCS" > "$DOCS.tmp" && mv "$DOCS.tmp" "$DOCS"
    echo "bench: headline table written into $DOCS" >&2
fi
cat "$MD"
