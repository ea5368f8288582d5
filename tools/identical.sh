#!/bin/sh
# Results unchanged, bit for bit, across a change of the code (issue 11):
# every shipped scene and built-in model, both discretisations, each
# correction set, every integrator, the adaptive driver, the backends, the
# scene-to-C generator, `braun check`, and the firmware demo's records on the
# emulated Cortex-M4F and on the host.
#
#   sh tools/identical.sh record DIR     outputs of the current build into DIR
#   sh tools/identical.sh compare DIR    the current build against DIR
#
# Record before the change (from a checkout of the old commit, with
# `make all firmware-test` run there), compare after. Only timings are left
# out (the summaries' cpu_s fields); everything else is compared byte for byte.
# Environment: BRAUN (default build/bin/braun), FW (build/firmware; its test/
# outputs come from `make firmware-test`), QUICK=1 (shorter runs).
set -u
mode=${1:?usage: sh tools/identical.sh record|compare DIR}
dir=${2:?usage: sh tools/identical.sh record|compare DIR}
BRAUN=${BRAUN:-build/bin/braun}
FW=${FW:-build/firmware}
case $mode in
record) out=$dir ;;
compare) out=$(mktemp -d) ; trap 'rm -rf "$out"' EXIT ;;
*) echo "usage: sh tools/identical.sh record|compare DIR" >&2; exit 2 ;;
esac
mkdir -p "$out"
T=${QUICK:+0.5}

# run TAG MODEL ARGS...: trajectory CSV (every 7th step) and summary without cpu_s.
run() {
    rt=$1; shift
    "$BRAUN" run "$@" --out "$out/$rt.csv" --every 7 --summary "$out/$rt.json.raw" \
        > "$out/$rt.stdout" 2> "$out/$rt.stderr"
    echo "exit $?" >> "$out/$rt.stdout"
    grep -v '"cpu_s' "$out/$rt.json.raw" > "$out/$rt.json" 2>/dev/null
    rm -f "$out/$rt.json.raw"
}

models="slider-crank four-bar pendulum andrews"
for f in data/*.json; do models="$models $f"; done
for mdl in $models; do
    tag=$(echo "$mdl" | sed 's|data/||; s|\.json$||; s|[^A-Za-z0-9]|_|g')
    case $mdl in andrews) h=1e-4; te=${T:-0.03} ;; *) h=1e-3; te=${T:-3} ;; esac
    run "$tag-rk4" "$mdl" --dt $h --t-end "$te"
    run "$tag-rk4-stage" "$mdl" --dt $h --t-end "$te" --discretization per-stage
    run "$tag-rk4-pv" "$mdl" --dt $h --t-end "$te" --corrections position,velocity
    run "$tag-rk4-none" "$mdl" --dt $h --t-end "$te" --corrections none
    run "$tag-rk4-all" "$mdl" --dt $h --t-end "$te" --corrections all
    run "$tag-euler" "$mdl" --dt $h --t-end "$te" --integrator euler
    run "$tag-heun-stage" "$mdl" --dt $h --t-end "$te" --integrator heun --discretization per-stage
    run "$tag-dopri5" "$mdl" --dt $h --t-end "$te" --integrator dopri5 --rtol 1e-8 --atol 1e-10
    run "$tag-dopri5-loose" "$mdl" --dt $h --t-end "$te" --integrator dopri5 --rtol 1e-5 --atol 1e-7
    "$BRAUN" check "$mdl" > "$out/$tag.check" 2>&1
    echo "exit $?" >> "$out/$tag.check"
done
# Long runs through the paper's singular configurations.
run four-bar-long four-bar --dt 1e-2 --t-end "${T:-200}"
run slider-crank-long slider-crank --dt 5e-3 --t-end "${T:-100}"
run parallelogram-long data/parallelogram-redundant.json --dt 1e-2 --t-end "${T:-100}"
# Backends and sparse systems.
for be in lapack suitesparse auto; do
    run "chain-5-$be" data/chain-5.json --dt 1e-3 --t-end "${T:-2}" --backend $be
    run "sleigh-$be" data/sleigh.json --dt 1e-3 --t-end "${T:-2}" --backend $be
done
run four-bar-lapack four-bar --dt 1e-2 --t-end "${T:-50}" --backend lapack
run chain-5-sparse-dense data/chain-5.json --dt 1e-3 --t-end "${T:-2}" --sparse
# Generated scenes at one fixed path: messages name it.
gen=/tmp/braun-identical-scenes
mkdir -p $gen
"$BRAUN" gen chain 30 --angle 20 -o $gen/chain-30.json
"$BRAUN" gen ladder 5 -o $gen/ladder-5.json
cp $gen/chain-30.json $gen/ladder-5.json "$out/"
run chain-30-suitesparse $gen/chain-30.json --dt 1e-3 --t-end "${T:-1}" --backend suitesparse
run ladder-5-suitesparse $gen/ladder-5.json --dt 1e-3 --t-end "${T:-1}" --backend suitesparse
run ladder-5-dense $gen/ladder-5.json --dt 1e-3 --t-end "${T:-1}"
# Scene to C.
for f in data/*.json; do
    b=$(basename "$f" .json)
    "$BRAUN" gen-c "$f" --symbol "s_$(echo "$b" | tr -c 'A-Za-z0-9_\n' '_')" -o "$out/gen-$b.c" \
        > /dev/null 2>&1 || echo "gen-c failed" > "$out/gen-$b.c"
done
# Firmware records (make firmware-test's outputs): every run of the demo.
for f in "$FW"/test/*-target.txt "$FW"/test/*-host.txt "$FW"/test/float-long.txt; do
    [ -f "$f" ] || continue
    awk '/^(run|max|final|q|v|stats|status|sizes) /' "$f" > "$out/fw-$(basename "$f")"
done

if [ "$mode" = record ]; then
    echo "recorded $(ls "$out" | wc -l) files in $out"
    exit 0
fi
# compare: the same files, the same bytes.
pass=0; fail=0; seen=""
for f in "$dir"/* "$out"/*; do
    b=$(basename "$f")
    case " $seen " in *" $b "*) continue ;; esac
    seen="$seen $b"
    if cmp -s "$dir/$b" "$out/$b"; then pass=$((pass + 1)); else
        fail=$((fail + 1)); echo "not ok - $b differs"
        diff "$dir/$b" "$out/$b" 2>&1 | head -6 | sed 's/^/#   /'
    fi
done
echo "ok - $pass files identical"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
