#!/bin/sh
# make firmware-profile: instructions per function of one RK4 step of the
# slider-crank with every correction on the emulated Cortex-M4F: QEMU logs
# every executed translation block (-d in_asm,exec,nochain) for 1 and for
# 101 steps; the difference / 100 is one step, attributed to functions by
# firmware/tools/qemu-profile.awk. Usage: sh tests/firmware/profile.sh ELF [MODEL [CORR]]
ELF=${1:?usage: sh tests/firmware/profile.sh ELF [MODEL [CORR]]}
MODEL=${2:-slider-crank}; CORR=${3:-all}
QEMU=${QEMU:-qemu-system-arm}
QFLAGS=${FW_QEMU_FLAGS:-"-M mps2-an386 -nographic -semihosting-config enable=on,target=native -icount shift=0"}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/fw-profile.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
for n in 1 101; do
    # shellcheck disable=SC2086
    timeout 600 "$QEMU" $QFLAGS -kernel "$ELF" -append "bench $n $MODEL $CORR" \
        -d in_asm,exec,nochain -D "$TMP/log" > /dev/null 2>&1
    awk -f firmware/tools/qemu-profile.awk "$TMP/log" | sort > "$TMP/p$n"
    rm -f "$TMP/log"
done
echo "# instructions per RK4 step by function: $MODEL, corrections $CORR, $ELF"
join -a2 -e0 -o 0,1.2,2.2 "$TMP/p1" "$TMP/p101" |
    awk '{ d = ($3 - $2) / 100; if (d >= 1) printf "%-32s %9.1f\n", $1, d }' | sort -k2 -nr
