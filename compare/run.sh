#!/bin/sh
# Run a comparison study, plot it and write its report (docs/compare.md).
# Usage: sh compare/run.sh --bin build/bin/braun-compare --out DIR
#            [--study default|quick] [--jobs J] [--reps K]
#            [--scenes "a b"] [--methods "x y"]
# Scenes are spread over J processes (round robin); each prints a progress
# line per run on stderr, prefixed with its process number.
set -eu
bin=build/bin/braun-compare out=results/compare study=default jobs=2 reps=3
scenes="" methods=""
while [ $# -gt 0 ]; do
    case $1 in
    --bin) bin=$2 ;;
    --out) out=$2 ;;
    --study) study=$2 ;;
    --jobs) jobs=$2 ;;
    --reps) reps=$2 ;;
    --scenes) scenes=$2 ;;
    --methods) methods=$2 ;;
    *) echo "compare/run.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
    shift 2
done
here=$(dirname "$0")
[ -n "$scenes" ] || scenes=$("$bin" scenes "$study")
case $jobs in ''|*[!0-9]*|0) echo "compare/run.sh: --jobs must be a positive integer" >&2; exit 2 ;; esac

start=$(date +%s)
mkdir -p "$out"
parts="$out/.parts"
rm -rf "$parts"
mkdir -p "$parts"
echo "compare: study '$study', scenes: $scenes; methods: ${methods:-all}; $jobs processes, best of $reps" >&2

# Round robin: scene i goes to process i mod jobs.
i=0
for s in $scenes; do
    g=$((i % jobs))
    eval "group_$g=\"\${group_$g:-} $s\""
    i=$((i + 1))
done
pids=""
g=0
while [ $g -lt "$jobs" ]; do
    eval "list=\${group_$g:-}"
    if [ -n "$list" ]; then
        mkdir -p "$parts/$g"
        ( "$bin" run --study "$study" --scenes "$list" --methods "$methods" --reps "$reps" \
              --out "$parts/$g" 2>&1; echo "exit $?" > "$parts/$g/status" ) |
            sed "s/^/[p$g] /" >&2 &
        pids="$pids $!"
    fi
    g=$((g + 1))
done
for p in $pids; do wait "$p"; done
failed=0
for d in "$parts"/*/; do
    st=$(cat "$d/status" 2>/dev/null || echo "exit 1")
    [ "$st" = "exit 0" ] || { echo "compare: process $(basename "$d") failed ($st)" >&2; failed=1; }
done
[ $failed -eq 0 ] || exit 1

# Merge the parts: one header, then every part's rows.
for f in runs.csv history.csv references.csv ida_probe.csv singular.csv; do
    first=1
    for d in "$parts"/*/; do
        if [ $first -eq 1 ]; then cat "$d/$f"; first=0; else tail -n +2 "$d/$f"; fi
    done > "$out/$f"
done
rm -rf "$parts"
end=$(date +%s)
{
    echo "study=$study"
    echo "scenes=$scenes"
    echo "methods=${methods:-all}"
    echo "jobs=$jobs"
    echo "reps=$reps"
    echo "run_wall_s=$((end - start))"
    echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)"
    echo "cores=$(nproc 2>/dev/null || echo '?')"
    echo "sundials=$(dpkg-query -W -f='${Version}' libsundials-dev 2>/dev/null || echo '?')"
    echo "gsl=$(dpkg-query -W -f='${Version}' libgsl-dev 2>/dev/null || echo '?')"
} > "$out/meta.txt"
echo "compare: runs done in $((end - start)) s; plotting" >&2
sh "$here/plot.sh" "$out"
end2=$(date +%s)
echo "plot_wall_s=$((end2 - end))" >> "$out/meta.txt"
"$bin" report --dir "$out"
end3=$(date +%s)
echo "total_wall_s=$((end3 - start))" >> "$out/meta.txt"
echo "compare: wrote $out/report.md ($((end3 - start)) s in all)" >&2
