#!/bin/sh
# Observed order of convergence of the slider-crank trajectory error (100 s)
# for RK4 under both discretisations of the 1/h terms (docs/method.md).
# Usage: tools/convergence.sh build/bin/braun [T]
set -eu
braun=${1:-build/bin/braun}
T=${2:-100}
get() { sed -n "s/^  \"$1\": \([^,]*\),*$/\1/p"; }
printf '| h | per-step max traj. error | order | max ‖Φ_q‖ | per-stage max traj. error | order | max ‖Φ_q‖ |\n'
printf '|---|---|---|---|---|---|---|\n'
prev_h=""; prev_a=""; prev_b=""
for h in 2e-2 1e-2 5e-3 2e-3 1e-3; do
    a_json=$("$braun" run slider-crank --dt "$h" --t-end "$T" --discretization per-step)
    b_json=$("$braun" run slider-crank --dt "$h" --t-end "$T" --discretization per-stage)
    a=$(printf '%s\n' "$a_json" | get max_trajectory_error)
    b=$(printf '%s\n' "$b_json" | get max_trajectory_error)
    pa=$(printf '%s\n' "$a_json" | get max_position_constraint_error)
    pb=$(printf '%s\n' "$b_json" | get max_position_constraint_error)
    if [ -n "$prev_h" ]; then
        oa=$(awk -v e1="$prev_a" -v e2="$a" -v h1="$prev_h" -v h2="$h" 'BEGIN{printf "%.2f", log(e1/e2)/log(h1/h2)}')
        ob=$(awk -v e1="$prev_b" -v e2="$b" -v h1="$prev_h" -v h2="$h" 'BEGIN{printf "%.2f", log(e1/e2)/log(h1/h2)}')
    else
        oa="–"; ob="–"
    fi
    printf '| %s | %.3g | %s | %.2g | %.3g | %s | %.2g |\n' "$h" "$a" "$oa" "$pa" "$b" "$ob" "$pb"
    prev_h=$h; prev_a=$a; prev_b=$b
done
