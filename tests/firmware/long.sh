#!/bin/sh
# make firmware-long: the float study of the issue on the emulated
# Cortex-M4F and on the host: slider-crank, RK4, h = 1e-3, 100 s, every
# correction, against the exact reference and against float RK4 on the
# minimal-coordinate equation (Eq. 24). Also run by firmware-test.
# Usage: sh tests/firmware/long.sh BUILD/firmware [MODEL H STEPS]
FW=${1:?usage: sh tests/firmware/long.sh BUILD/firmware [MODEL H STEPS]}
MODEL=${2:-slider-crank}; H=${3:-1e-3}; STEPS=${4:-100000}
QEMU=${QEMU:-qemu-system-arm}
QFLAGS=${FW_QEMU_FLAGS:-"-M mps2-an386 -nographic -semihosting-config enable=on,target=native -icount shift=0"}
OUT=$FW/long
mkdir -p "$OUT"
status=0
echo "## emulated Cortex-M4F (float)"
# shellcheck disable=SC2086
timeout 600 "$QEMU" $QFLAGS -kernel "$FW/float/demo.elf" -append "long $MODEL $H $STEPS 1" \
    > "$OUT/float-target.txt" 2>&1
"$FW/fw_traj" "$OUT/float-target.txt" || status=1
echo "## host (float, same code)"
"$FW/host-float/fw_host" long "$MODEL" "$H" "$STEPS" 1 > "$OUT/float-host.txt" 2>&1
"$FW/fw_traj" "$OUT/float-host.txt" || status=1
echo "## host (double, same code)"
"$FW/host-double/fw_host" long "$MODEL" "$H" "$STEPS" 1 > "$OUT/double-host.txt" 2>&1
"$FW/fw_traj" "$OUT/double-host.txt" || status=1
exit $status
