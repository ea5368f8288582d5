#!/bin/sh
# Plots of make scaling: cost per step against N (log-log, fitted slopes in
# the legend) and, if measured, error against cost at N = 1000.
set -eu
OUT=$1
png='set terminal pngcairo size 1600,800 font "DejaVu Sans,11" linewidth 1.5'
svg='set terminal svg size 1600,800 dynamic font "DejaVu Sans,11" linewidth 1.5'
# One data file per (kind, backend): N, µs per step.
series=""
for k in chain ladder spatial-chain; do
    for b in $(awk -F, -v k="$k" 'NR > 1 && $1 == k { print $6 }' "$OUT/step.csv" | sort -u); do
        f="$OUT/.$k-$b.dat"
        awk -F, -v k="$k" -v b="$b" 'NR > 1 && $1 == k && $6 == b && $7 != "nan" && $7 != "" { print $2, $7 / 1000 }' \
            "$OUT/step.csv" > "$f"
        [ -s "$f" ] || continue
        # the slope over the widest range (the spatial chain's from N = 10)
        sl=$(awk -F, -v k="$k" -v b="$b" '$1 == k && $2 == b { print $5, $3 }' "$OUT/slopes.csv" | sort -n | head -n 1)
        slope=${sl#* } nmin=${sl%% *}
        failN=$(awk -F, -v k="$k" -v b="$b" '$1 == k && $6 == b && $11 ~ /^failed/ { print $2; exit }' "$OUT/step.csv")
        dash=1 pt0=4; [ "$k" = ladder ] && dash=2; [ "$k" = spatial-chain ] && dash=4 pt0=8
        case $b in dense) c=1 ;; lapack) c=2 ;; suitesparse) c=3 ;; *) c=4 ;; esac
        series="$series${series:+, }'$f' using 1:2 with linespoints dt $dash lc $c pt $((c + pt0)) title '$k, $b${slope:+ (slope $slope for N >= $nmin)}${failN:+ (fails at N = $failN)}'"
    done
done
# The N^1.3 line through the sparse backend's chain cost at N = 100.
y100=$(awk -F, '$1 == "chain" && $2 == 100 && $6 == "suitesparse" && $7 != "nan" { print $7 / 1000 }' "$OUT/step.csv")
y100=${y100:-100}
for term in png svg; do
    eval "t=\$$term"
    gnuplot <<GP
$t
set output '$OUT/scaling.$term'
set logscale xy
set grid
set key outside right top box
set xlabel 'N (chain: links; ladder: cells of 4 bodies; spatial chain: rigid3d bars)'
set xrange [8:3000]
set ylabel 'CPU time per step (µs)'
set title 'Cost per step against N: corrected RK4 step (braun, each backend) and IDA+KLU step (GGL, analytic Jacobian)'
plot $series, [100:2000] $y100*(x/100)**1.3 with lines dt 3 lc rgb 'gray' title 'N^{1.3} through the chain, suitesparse at N = 100 (the bound)'
GP
done
if [ -f "$OUT/matched.csv" ]; then
    awk -F, 'NR > 1 && $3 ~ /^braun/ && $7 != "nan" { print $8, $7 }' "$OUT/matched.csv" > "$OUT/.m-braun.dat"
    awk -F, 'NR > 1 && $3 == "ida-klu" && $7 != "nan" { print $8, $7 }' "$OUT/matched.csv" > "$OUT/.m-ida.dat"
    refe=$(awk -F, '$3 ~ /^reference/ { print $7 }' "$OUT/matched.csv")
    refe=${refe:-1e-12}
    for term in png svg; do
        eval "t=\$$term"
        gnuplot <<GP
$t
set output '$OUT/matched.$term'
set logscale xy
set grid
set xlabel 'CPU seconds per simulated second'
set ylabel 'max trajectory error |q - q_{ref}| over the run'
set title 'Chain, N = 1000: error against cost (braun RK4 + suitesparse at several h; IDA+KLU at several rtol)'
plot '$OUT/.m-braun.dat' using 1:2 with linespoints pt 7 title 'braun RK4, suitesparse', \
     '$OUT/.m-ida.dat' using 1:2 with linespoints pt 5 title 'IDA+KLU (GGL, analytic Jacobian)', \
     $refe with lines dt 3 lc rgb 'gray' title 'reference: RK4 at h = 1.25e-4 against DOPRI5 at rtol 1e-11'
GP
    done
fi
rm -f "$OUT"/.*.dat
