#!/bin/sh
# make bench (issue 7; docs/performance.md). Drives build/bin/braun-bench:
#   1. targets.csv      sizes, rank, energy law, minimal equation, step
#   2. time.csv         ns per step / rhs: median over rounds, one process,
#                       ratios to the baselines of the same round
#   3. instructions.csv callgrind instruction counts and executed flops per
#                       step / rhs (static binary, --dump-instr, bench/flops.awk)
#      profile.csv      the same per function (every target and item)
#   4. flops.csv        derived flop counts by component (braun-bench flops)
#   5. matched_error.csv cost per simulated second at matched error, from
#                       make compare's results/compare/runs.csv when present
#   6. variants.csv     the slider-crank built with other compiler flags
#   7. *.md             the tables; copied into docs/performance.md between
#                       its <!-- bench:NAME --> and <!-- /bench:NAME --> lines
# Usage: sh bench/bench.sh --bin BIN --static BIN --out DIR [--rounds R]
#        [--steps K] [--jobs J] [--variants 0|1] [--docs FILE] [--build DIR]
#        [--targets "T1 T2 ..."] [--compare CSV]
set -eu

# One callgrind run (the script calls itself through xargs).
if [ "${1:-}" = "--cg-one" ]; then
    dir=$2 bin=$3 steps=$4 target=$5 item=$6
    safe=$(echo "$target" | tr '/.' '__')
    out="$dir/$safe.$item"
    # bench_run_block: one block of the item and nothing else (its loop adds
    # a few instructions per operation).
    valgrind --tool=callgrind --callgrind-out-file="$out.cg" --toggle-collect=bench_run_block \
        --dump-instr=yes --compress-pos=no --compress-strings=no \
        "$bin" run "$target" "$item" --steps "$steps" > "$out.txt" 2> "$out.log" ||
        { echo "bench: callgrind failed: $target $item (see $out.log)" >&2; exit 1; }
    awk -f bench/flops.awk "$dir/objdump.txt" "$out.cg" > "$out.fn.csv"
    rm -f "$out.cg"
    exit 0
fi

BIN='' STATIC='' OUT=results/bench ROUNDS=31 STEPS=2000 JOBS=2 VARIANTS=1 DOCS='' BUILD=build
TARGETS="slider-crank four-bar pendulum andrews"
COMPARE=results/compare/runs.csv
while [ $# -gt 0 ]; do
    case $1 in
        --bin) BIN=$2 ;;
        --static) STATIC=$2 ;;
        --out) OUT=$2 ;;
        --rounds) ROUNDS=$2 ;;
        --steps) STEPS=$2 ;;
        --jobs) JOBS=$2 ;;
        --variants) VARIANTS=$2 ;;
        --docs) DOCS=$2 ;;
        --build) BUILD=$2 ;;
        --targets) TARGETS=$2 ;;
        --compare) COMPARE=$2 ;;
        *) echo "bench.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift 2
done
if [ ! -x "$BIN" ] || [ ! -x "$STATIC" ]; then
    echo "bench.sh: --bin and --static are required" >&2
    exit 2
fi

START=$(date +%s)
ROOT=$(pwd -P)
CG="$OUT/callgrind"
mkdir -p "$OUT" "$CG"
rm -f "$CG"/*.fn.csv "$CG"/*.txt "$CG"/*.log
# shellcheck disable=SC2086
"$BIN" info $TARGETS > "$OUT/targets.csv"
# Load when we started: other builds and studies share the machine.
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")

# ---------------------------------------------------------------- 2. timing
echo "bench: timing ($ROUNDS rounds of $STEPS steps per item and target)" >&2
# shellcheck disable=SC2086
"$BIN" time --rounds "$ROUNDS" --steps "$STEPS" $TARGETS > "$OUT/time.csv"

# ---------------------------------------------------------------- 3. callgrind
echo "bench: callgrind instruction and flop counts" >&2
objdump -d --no-show-raw-insn "$STATIC" > "$CG/objdump.txt"
: > "$CG/jobs.txt"
for t in $TARGETS; do
    minimal=$(awk -F, -v t="$t" '$1 == t { print $8 }' "$OUT/targets.csv")
    for item in step-none step-pv step-all step-free step-floor step-special rhs-ideal rhs-corrected rhs-floor; do
        case $item in *-floor) [ "$minimal" = "-" ] && continue ;; esac
        # The specialised floor is the built-in slider-crank's (bench/bench_special.c).
        [ "$item" = step-special ] && [ "$t" != slider-crank ] && continue
        echo "$t $item" >> "$CG/jobs.txt"
    done
done
xargs -P "$JOBS" -L 1 sh "$0" --cg-one "$CG" "$STATIC" "$STEPS" < "$CG/jobs.txt"

# Per function: target,item,function,file,group,ops,instructions,flops,fp_other
{
    echo "target,item,function,group,ops,instructions,flops,fp_other"
    while read -r t item; do
        safe=$(echo "$t" | tr '/.' '__')
        ops=$(sed -n 's/^ops=\([0-9]*\).*/\1/p' "$CG/$safe.$item.txt")
        awk -F, -v t="$t" -v it="$item" -v ops="$ops" '{
            g = "libc/libm"
            if ($2 ~ /\/src\/core\/(models|scene)\//) g = "model"
            else if ($2 ~ /\/src\/core\//) g = "core"
            else if ($2 ~ /\/bench\//) g = "bench"
            printf "%s,%s,%s,%s,%.0f,%.0f,%.0f,%.0f\n", t, it, $1, g, ops, $3, $4, $5
        }' "$CG/$safe.$item.fn.csv" | sort -t, -k6,6nr
    done < "$CG/jobs.txt"
} > "$OUT/profile.csv"

# Per target and item: instructions, flops (all, core) per operation.
awk -F, 'FNR == NR { if (FNR > 1) backend[$1] = $12; next }
FNR > 1 {
    k = $1 "," backend[$1] "," $2; if (!(k in ops)) { order[++n] = k; ops[k] = $5 }
    ir[k] += $6; fl[k] += $7; ot[k] += $8
    if ($4 == "core") { irc[k] += $6; flc[k] += $7 }
}
END {
    print "target,backend,item,ops,instr_per_op,flops_per_op,core_instr_per_op,core_flops_per_op,fp_other_per_op"
    for (i = 1; i <= n; i++) {
        k = order[i]; o = ops[k] > 0 ? ops[k] : 1
        printf "%s,%.0f,%.1f,%.1f,%.1f,%.1f,%.1f\n", k, ops[k], ir[k] / o, fl[k] / o,
               irc[k] / o, flc[k] / o, ot[k] / o
    }
}' "$OUT/targets.csv" "$OUT/profile.csv" > "$OUT/instructions.csv"
rm -f "$CG/objdump.txt"

# ---------------------------------------------------------------- 4. flop formulas
# shellcheck disable=SC2086
"$BIN" flops $TARGETS > "$OUT/flops.csv"

# ---------------------------------------------------------------- 5. matched error
if [ -f "$COMPARE" ]; then
    "$BIN" matched "$COMPARE" 1e-3 1e-6 > "$OUT/matched_error.csv"
    MATCHED_FROM="$COMPARE ($(sed -n 's/^date=//p' "$(dirname "$COMPARE")/meta.txt" 2>/dev/null || echo "date unknown"))"
else
    echo "scene,T,error_level,method,cpu_s,cpu_per_sim_s,ratio_to_braun_rk4,how,runs,best_error" > "$OUT/matched_error.csv"
    MATCHED_FROM=
fi

# ---------------------------------------------------------------- 6. variants
# The slider-crank built other ways: compiler flags, compile-time sizes, and
# the proposed core patches of bench/patches/ applied to a copy of the tree.
# Separate programs cannot share a process: the variants run in 15
# interleaved passes and are compared by their fastest round (load only
# ever adds time); the instruction counts (callgrind) are exact.
# name|OPT|CPPFLAGS|AR|patch
echo "variant,flags,item,ns_median,ratio_ideal,instr_per_op,ns_min" > "$OUT/variants.csv"
if [ "$VARIANTS" = 1 ]; then
    echo "bench: the slider-crank built other ways (variants)" >&2
    FIX="-DBRAUN_FIXED_N=6 -DBRAUN_FIXED_ROWS=5"
    VLIST="O2|-O2 -g|||
O3|-O3 -g||ar|
O3-lto|-O3 -g -flto||gcc-ar|
O3-native|-O3 -g -march=native||ar|
fixed-O3-lto|-O3 -g -flto|$FIX|gcc-ar|"
    : > "$CG/variants.txt"
    echo "$VLIST" | while IFS='|' read -r name opt cpp ar pat; do
        vb="$BUILD/bench-variants/$name"
        if [ "$name" = O2 ]; then
            echo "$name|$opt|$BIN|$STATIC" >> "$CG/variants.txt"
            continue
        fi
        src=.
        if [ -n "$pat" ]; then
            # A copy of what the build needs, patched; a patch that no longer
            # applies (already in src/?) is skipped with a note.
            src="$vb/tree"
            rm -rf "$src"
            mkdir -p "$src"
            cp -R src include mk bench compare data tools Makefile "$src"/
            if ! (cd "$src" && patch -p1 -s --dry-run < "$ROOT/$pat" > /dev/null 2>&1); then
                echo "bench: $pat does not apply to src/ (applied already?): variant $name skipped" >&2
                continue
            fi
            (cd "$src" && patch -p1 -s < "$ROOT/$pat")
            vb="$src/build"
        fi
        if ! make -s --no-print-directory -C "$src" BUILD="$(cd "$src" && pwd -P)/${vb#"$src"/}" \
                OPT="$opt" CPPFLAGS="$cpp" AR="$ar" bench-bin > "$CG/variant-$name.log" 2>&1; then
            # -C src with BUILD relative to it: vb is under src when patched.
            echo "bench: variant $name failed to build (see $CG/variant-$name.log)" >&2
            continue
        fi
        echo "$name|$(echo "$opt $cpp" | sed 's/ *$//')|$vb/bin/braun-bench|$vb/bin/braun-bench-static" >> "$CG/variants.txt"
    done
    # Many short passes: the load of a shared machine drifts on the scale
    # of seconds, and every variant should see the same drift.
    PASSES=15
    VR=3
    : > "$CG/variants-time.csv"
    pass=1
    while [ $pass -le $PASSES ]; do
        while IFS='|' read -r name flags vbin vstatic; do
            "$vbin" time --rounds "$VR" --steps "$STEPS" slider-crank |
                awk -F, -v nm="$name" -v ps="$pass" 'NR > 1 { print nm "," ps "," $10 "," $16 "," $19 "," $22 }' \
                >> "$CG/variants-time.csv"
        done < "$CG/variants.txt"
        pass=$((pass + 1))
    done
    while IFS='|' read -r name flags vbin vstatic; do
        for item in step-none step-all step-special; do
            ir=
            if valgrind --tool=callgrind --callgrind-out-file="$CG/variant.cg" \
                    --toggle-collect=bench_run_block "$vstatic" run slider-crank "$item" \
                    --steps "$STEPS" > /dev/null 2> "$CG/variant-$name.$item.log"; then
                ir=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$CG/variant.cg")
            fi
            rm -f "$CG/variant.cg"
            # (valgrind 3.19 does not decode AVX-512: -march=native may have no count)
            awk -F, -v nm="$name" -v fl="$flags" -v it="$item" -v ir="$ir" -v st="$STEPS" '
                function med(v, n,   i, j, t) {
                    for (i = 2; i <= n; i++) for (j = i; j > 1 && v[j - 1] > v[j]; j--) {
                        t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
                    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
                }
                $1 == nm && $3 == it { a[++n] = $4; b[n] = $5; if (n == 1 || $6 < lo) lo = $6 }
                END {
                    if (n == 0) exit
                    x = med(a, n); y = med(b, n)
                    printf "%s,%s,%s,%.1f,%.4f,%s,%.1f\n", nm, fl, it, x, y,
                           ir == "" ? "nan" : sprintf("%.1f", ir / st), lo
                }' "$CG/variants-time.csv" >> "$OUT/variants.csv"
        done
    done < "$CG/variants.txt"
fi

# ---------------------------------------------------------------- 7. tables
END_=$(date +%s)
WALL=$((END_ - START))
CPU=$(sed -n 's/^model name[^:]*: *//p' /proc/cpuinfo 2>/dev/null | head -n 1)
{
    echo "study=bench"
    echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "cpu=$CPU"
    echo "cores=$(nproc 2>/dev/null || echo ?)"
    echo "load_at_start=$LOAD0"
    echo "load_at_end=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo ?)"
    echo "compiler=$(${CC:-cc} --version | head -n 1)"
    echo "rounds=$ROUNDS"
    echo "steps=$STEPS"
    echo "wall_s=$WALL"
    echo "matched_from=$MATCHED_FROM"
    echo "compare_csv=$COMPARE"
} > "$OUT/meta.txt"

# The labels of the series (compare/series.tsv) as braun-bench has them.
"$BIN" series > "$OUT/series.txt"
# How far the specialised floor's trajectory ends from the library's ideal
# step (braun-bench run ... step-special; it is not timed above 1e-9).
AGREE=$(sed -n 's/.*agreement=\([^ ]*\).*/\1/p' "$CG/slider-crank.step-special.txt" 2>/dev/null)
awk -f bench/tables.awk -v out="$OUT" -v meta="$OUT/meta.txt" -v series="$OUT/series.txt" \
    -v special_agreement="${AGREE:-?}" \
    "$OUT/targets.csv" "$OUT/time.csv" "$OUT/instructions.csv" "$OUT/flops.csv" \
    "$OUT/profile.csv" "$OUT/matched_error.csv" "$OUT/variants.csv"

if [ -n "$DOCS" ] && [ -f "$DOCS" ]; then
    # Replace each marked block with its table; everything else stays.
    awk -v out="$OUT" '
        /^<!-- bench:[a-z-]+ -->$/ {
            print; name = $0; sub(/^<!-- bench:/, "", name); sub(/ -->$/, "", name)
            f = out "/" name ".md"
            while ((getline line < f) > 0) print line
            close(f); skip = 1; next
        }
        /^<!-- \/bench:[a-z-]+ -->$/ { skip = 0 }
        !skip { print }' "$DOCS" > "$DOCS.tmp" && mv "$DOCS.tmp" "$DOCS"
    echo "bench: tables written into $DOCS" >&2
fi
echo "bench: done in ${WALL} s; results in $OUT/" >&2
cat "$OUT/summary.md"
