#!/bin/sh
# make scaling (mk/scaling.mk; docs/performance.md, "Large systems").
#   1. scenes: braun gen chain N (rigid links, revolute joints),
#      braun gen ladder N (three rails, rungs: one redundant row per cell)
#      and braun gen spatial-chain N (rigid3d bars on spherical joints)
#   2. step.csv:   CPU ns per corrected RK4 step for each backend and N, and
#                  per IDA+KLU step (GGL, analytic sparse Jacobian)
#   3. slopes.csv: least-squares slope of log(cost) on log(N), N >= 100
#                  (and for the spatial chain also N >= 10: issue 13's range)
#   4. matched.csv: chain N = 1000, trajectory error vs CPU s per simulated
#                  second for braun (suitesparse, RK4 at several h) and IDA+KLU
#                  (several rtol); cost at equal error by log-log interpolation
#   5. pairs.csv:  the ladder against the chain per body on SuiteSparse at the
#                  largest N both have, from SCALING_PAIRS (3) back-to-back
#                  chain/ladder pairs: the ratio within a pair, whose two
#                  runs share the machine's state (a single point of each,
#                  in separate minutes, varied 2.4-4.3 on one day)
#   6. scaling.png/svg, scaling.md (copied into docs/performance.md between
#      <!-- scaling:tables --> and <!-- /scaling:tables -->)
set -eu
BIN='' BRAUN='' OUT=results/scaling NS="10 20 50 100 200 500 1000 2000" LNS="10 30 100 300 1000 2000"
SNS="10 20 50 100 200 500 1000"
BACKENDS="dense lapack suitesparse" MATCHED=1 DOCS=''
MAX_STEP_S=${SCALING_MAX_STEP_S:-3}   # skip a backend's larger N beyond this per step
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BIN=$2 ;; --braun) BRAUN=$2 ;; --out) OUT=$2 ;; --n) NS=$2 ;; --ladder-n) LNS=$2 ;;
    --spatial-n) SNS=$2 ;;
    --backends) BACKENDS=$2 ;; --matched) MATCHED=$2 ;; --docs) DOCS=$2 ;;
    *) echo "scaling: unknown option $1" >&2; exit 2 ;;
    esac
    shift 2
done
start=$(date +%s)
mkdir -p "$OUT/scenes"
for N in $NS; do "$BRAUN" gen chain "$N" --angle 30 -o "$OUT/scenes/chain-$N.json"; done
for N in $LNS; do "$BRAUN" gen ladder "$N" -o "$OUT/scenes/ladder-$N.json"; done
for N in $SNS; do "$BRAUN" gen spatial-chain "$N" -o "$OUT/scenes/spatial-chain-$N.json"; done

# 2. cost per step. A backend whose last step cost more than MAX_STEP_S,
# extrapolated with its worst case (N^3 dense), is not run at larger N.
step="$OUT/step.csv"
{ printf 'kind,N,'; "$BIN" step --header; } > "$step"
run_kind() {
    kind=$1; shift
    ida=ida
    # The compare harness's analytic IDA Jacobian knows planar rigid bodies
    # and particles only (compare/cmp_ida_jac.c): no IDA for rigid3d bars.
    if [ "$kind" = spatial-chain ]; then
        ida=''
        for N in "$@"; do
            echo "$kind,$N,$OUT/scenes/$kind-$N.json,,,ida-klu,nan,nan,0,0,skipped: no analytic IDA Jacobian for rigid3d bodies in the harness" >> "$step"
        done
    fi
    for b in $BACKENDS $ida; do
        last_ns=0 last_N=0
        for N in "$@"; do
            f="$OUT/scenes/$kind-$N.json"
            if [ "$last_ns" != 0 ]; then
                skip=$(awk -v ns="$last_ns" -v n0="$last_N" -v n1="$N" -v b="$b" -v max="$MAX_STEP_S" \
                    'BEGIN { p = (b == "dense" || b == "lapack") ? 3 : 1.5;
                             print (ns * 1e-9 * (n1 / n0) ^ p > max) ? 1 : 0 }')
                if [ "$skip" = 1 ]; then
                    echo "$kind,$N,$f,,,$b,nan,nan,0,0,skipped: over ${MAX_STEP_S} s per step" >> "$step"
                    continue
                fi
            fi
            if [ "$b" = ida ]; then
                # The ladder's redundant rows: regularised Φ - ελ for IDA.
                reg=0; [ "$kind" = ladder ] && reg=1e-10
                row=$("$BIN" ida-step "$f" --T 0.05 --rtol 1e-6 --reg $reg) || row="$f,,,ida-klu,nan,nan,0,0,failed"
            else
                row=$("$BIN" step "$f" "$b" --budget 1 --reps 5) || true
            fi
            echo "$kind,$N,$row" >> "$step"
            echo "scaling: $kind N=$N $b: $(echo "$row" | cut -d, -f5) ns/step" >&2
            ns=$(echo "$row" | cut -d, -f5)
            case $ns in nan|'') ;; *) last_ns=$ns last_N=$N ;; esac
            # A method that failed at this N is not tried at larger ones.
            case $row in *,failed*) failed_at=$N ;; *) failed_at='' ;; esac
            if [ -n "$failed_at" ]; then
                for M in "$@"; do
                    [ "$M" -gt "$N" ] && echo "$kind,$M,$OUT/scenes/$kind-$M.json,,,$b,nan,nan,0,0,skipped: failed at N = $N" >> "$step"
                done
                break
            fi
        done
    done
}
run_kind chain $NS
run_kind ladder $LNS
run_kind spatial-chain $SNS

# 3. slopes over N >= 100 (issue 7's range: 100 to 2000), and for the
# spatial chain also over N >= 10 (issue 13: N = 10 ... 1000).
slopes() {
    awk -F, -v from="$1" -v only="$2" 'NR > 1 && $7 != "nan" && $7 != "" && $2 >= from &&
            (only == "" || $1 == only) {
            k = $1 "," $6; x = log($2); y = log($7);
            n[k]++; sx[k] += x; sy[k] += y; sxx[k] += x * x; sxy[k] += x * y;
            if (!(k in lo) || $2 < lo[k]) lo[k] = $2; if ($2 > hi[k]) hi[k] = $2 }
        END { for (k in n) if (n[k] >= 2) {
                  d = n[k] * sxx[k] - sx[k] * sx[k];
                  printf "%s,%.2f,%d,%d,%d\n", k, (n[k] * sxy[k] - sx[k] * sy[k]) / d, n[k], lo[k], hi[k] } }' \
        "$step"
}
{ slopes 100 ''; slopes 10 spatial-chain; } | sort -u > "$OUT/slopes.tmp"
{ echo "kind,backend,slope,points,N_min,N_max"; cat "$OUT/slopes.tmp"; } > "$OUT/slopes.csv"
rm -f "$OUT/slopes.tmp"

# 4. equal error at N = 1000.
if [ "$MATCHED" = 1 ] && [ -f "$OUT/scenes/chain-1000.json" ]; then
    "$BIN" matched --header > "$OUT/matched.csv"
    "$BIN" matched "$OUT/scenes/chain-1000.json" suitesparse --T "${SCALING_T:-0.5}" \
        --h "${SCALING_H:-8e-3 4e-3 2e-3 1e-3 5e-4}" --rtol "${SCALING_RTOL:-1e-4 1e-5 1e-6 1e-7 1e-8}" \
        --href "${SCALING_HREF:-1.25e-4}" >> "$OUT/matched.csv"
fi

# 5. ladder/chain per body at the largest common N, from back-to-back pairs
# (4 bodies per ladder cell, as tables.awk counts them).
pn=''
for N in $NS; do case " $LNS " in *" $N "*) pn=$N ;; esac; done
pairs="$OUT/pairs.csv"
echo "N,pair,chain_ns,ladder_ns,ratio_per_body" > "$pairs"
case " $BACKENDS " in *" suitesparse "*) ;; *) pn='' ;; esac
if [ -n "$pn" ]; then
    p=1
    while [ "$p" -le "${SCALING_PAIRS:-3}" ]; do
        c=$("$BIN" step "$OUT/scenes/chain-$pn.json" suitesparse --budget 1 --reps 5 | cut -d, -f5) || c=nan
        l=$("$BIN" step "$OUT/scenes/ladder-$pn.json" suitesparse --budget 1 --reps 5 | cut -d, -f5) || l=nan
        awk -v N="$pn" -v p="$p" -v c="$c" -v l="$l" 'BEGIN {
            r = (c + 0 > 0 && l + 0 > 0) ? sprintf("%.3f", l / 4 / c) : "nan"
            printf "%s,%s,%s,%s,%s\n", N, p, c, l, r }' >> "$pairs"
        echo "scaling: pair $p at N = $pn: chain $c, ladder $l ns/step" >&2
        p=$((p + 1))
    done
fi

# 6. plot and tables.
sh "$(dirname "$0")/plot.sh" "$OUT"
awk -f "$(dirname "$0")/tables.awk" -v out="$OUT" "$OUT/step.csv" "$OUT/slopes.csv" \
    $( [ -f "$OUT/matched.csv" ] && echo "$OUT/matched.csv" ) > "$OUT/scaling.md"
# The pairs' median, after the tables (bench/headline.sh reads this line).
awk -F, 'NR > 1 && $5 != "nan" { r[++n] = $5 + 0; N = $1; s = s (s == "" ? "" : " / ") $5 }
    END { if (n == 0) exit
          for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (r[j] < r[i]) { t = r[i]; r[i] = r[j]; r[j] = t }
          m = (n % 2) ? r[(n + 1) / 2] : (r[n / 2] + r[n / 2 + 1]) / 2
          printf "\nLadder against the chain per body on SuiteSparse at N = %s, back-to-back pairs (pairs.csv; the median of the ratios within each pair, which share the machine'"'"'s state): **%.2f** (%s).\n", N, m, s }' \
    "$pairs" >> "$OUT/scaling.md"
if [ -n "$DOCS" ] && [ -f "$DOCS" ] && grep -q '<!-- scaling:tables -->' "$DOCS"; then
    awk -v f="$OUT/scaling.md" '
        /<!-- scaling:tables -->/ { print; while ((getline l < f) > 0) print l; skip = 1; next }
        /<!-- \/scaling:tables -->/ { skip = 0 }
        !skip' "$DOCS" > "$DOCS.tmp" && mv "$DOCS.tmp" "$DOCS"
fi
echo "scaling: wrote $OUT/scaling.md in $(( $(date +%s) - start )) s" >&2
