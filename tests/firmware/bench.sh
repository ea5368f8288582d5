#!/bin/sh
# make firmware-bench: instructions per RK4 step (braun_step) on the emulated
# Cortex-M4F and on the host (callgrind), float and double, corrections
# none / position+velocity / all, for the slider-crank (h = 1e-3) and the
# four-bar (h = 1e-2). Usage: sh tests/firmware/bench.sh BUILD/firmware [STEPS]
# Writes BUILD/firmware/bench.md (the table of docs/firmware.md).
FW=${1:?usage: sh tests/firmware/bench.sh BUILD/firmware [STEPS]}
STEPS=${2:-2000}
QEMU=${QEMU:-qemu-system-arm}
QFLAGS=${FW_QEMU_FLAGS:-"-M mps2-an386 -nographic -semihosting-config enable=on,target=native -icount shift=0"}
OUT=$FW/bench
mkdir -p "$OUT"
val() { echo "$1" | sed -n "s/.* $2=\([^ ]*\).*/\1/p"; }

CONFIGS=${FW_CONFIGS:-"double float"}
for p in $CONFIGS; do
    # A run that fails (status != 0 in its record: e.g. the uncorrected
    # float four-bar diverges) is reported in the table, not fatal here.
    # shellcheck disable=SC2086
    timeout 600 "$QEMU" $QFLAGS -kernel "$FW/$p/demo.elf" -append "bench $STEPS" > "$OUT/$p-target.txt" 2>&1
    grep -q '^bench ' "$OUT/$p-target.txt" ||
        { echo "bench: emulator run failed ($p)" >&2; cat "$OUT/$p-target.txt" >&2; exit 1; }
done

# Instructions per tick from the calibration (40 under -icount shift=0).
ipt=$(sed -n 's/^calib instructions=\([0-9]*\) ticks=\([0-9]*\).*/\1 \2/p' "$OUT/float-target.txt" |
      awk '{ printf "%.4f", $1 / $2 }')

{
echo "| model | precision | corrections | M4F instr/step mean | min | max | host x86-64 instr/step (callgrind) | steps/s at 168 MHz (M4F mean, 1 instr/cycle) | steps done |"
echo "|---|---|---|---|---|---|---|---|---|"
for model in slider-crank four-bar; do
    for p in float float-fixed double; do
        case " $CONFIGS " in *" $p "*) ;; *) continue ;; esac
        for c in none pv all; do
            line=$(grep "^bench model=$model precision=[a-z]* corrections=$c " "$OUT/$p-target.txt")
            sum=$(val "$line" ticks_sum); tmin=$(val "$line" ticks_min); tmax=$(val "$line" ticks_max)
            done_=$(val "$line" steps); st=$(val "$line" status)
            ir=0; hn=0
            if [ -x "$FW/host-$p/fw_host" ]; then
                cg="$OUT/callgrind-$model-$p-$c.out"
                valgrind --tool=callgrind --callgrind-out-file="$cg" --toggle-collect=braun_step \
                    "$FW/host-$p/fw_host" bench "$STEPS" "$model" "$c" > "$cg.txt" 2>&1
                hn=$(val "$(grep '^bench ' "$cg.txt")" steps)
                ir=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$cg" | head -n 1)
                [ -n "$ir" ] || ir=$(sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$cg" | head -n 1)
            fi
            awk -v m="$model" -v p="$p" -v c="$c" -v s="$sum" -v lo="$tmin" -v hi="$tmax" \
                -v n="$done_" -v st="$st" -v ipt="$ipt" -v ir="${ir:-0}" -v hn="${hn:-1}" 'BEGIN {
                mean = s * ipt / n
                host = hn > 0 ? sprintf("%.0f", ir / hn) : "–"
                printf "| %s | %s | %s | %.0f | %.0f | %.0f | %s | %.0f | %d%s |\n",
                       m, p, c == "pv" ? "position+velocity" : c, mean, lo * ipt, hi * ipt,
                       host, 168e6 / mean, n, st == 0 ? "" : " (then status " st ")" }'
        done
    done
done
} > "$FW/bench.md"
cat "$FW/bench.md"
echo "# $STEPS steps per run from the paper's initial state; emulator: QEMU $($QEMU --version | head -n 1 | sed 's/.*version //'), -icount shift=0, $ipt instructions per timer tick"
