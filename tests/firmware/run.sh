#!/bin/sh
# make firmware-test: the firmware build, the demo on the emulated
# Cortex-M4F (QEMU mps2-an386) against the host build of the same runs, and
# the float study of the issue. Usage: sh tests/firmware/run.sh build/firmware
# Prints "ok - NAME" / "not ok - NAME" per check ("ok - NAME # SKIP WHY" for
# one that cannot run in this configuration) and a closing line "N passed,
# M failed, K skipped"; exit status 1 if anything failed. BRAUN: the host
# tool of the build under test (mk/firmware.mk passes it).
FW=${1:?usage: sh tests/firmware/run.sh BUILD/firmware}
QEMU=${QEMU:-qemu-system-arm}
NM=${FW_NM:-arm-none-eabi-nm}
QFLAGS=${FW_QEMU_FLAGS:-"-M mps2-an386 -nographic -semihosting-config enable=on,target=native -icount shift=0"}
OUT=$FW/test
mkdir -p "$OUT"
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { name=$1; shift; if "$@"; then ok "$name"; else not_ok "$name"; fi; }
# emu ELF OUTFILE WORDS...: run on the emulator; sets rc.
emu() {
    elf=$1; out=$2; shift 2
    # shellcheck disable=SC2086
    timeout 120 "$QEMU" $QFLAGS -kernel "$elf" -append "$*" > "$out" 2>&1
    rc=$?
}
# run_ok FILE MODEL: the demo's run of MODEL in FILE ended with status 0.
run_ok() {
    awk -v m="model=$2" '$1 == "run" && $2 == m { on = 1; next }
        on && $1 == "status" { found = 1; exit !($2 == "code=0") }
        END { if (!found) exit 1 }' "$1"
}
# Value of key=VALUE in the first line starting with TAG.
val() { sed -n "/^$1 /{s/.* $2=\([^ ]*\).*/\1/p;q}" "$3"; }

start=$(date +%s)
for p in double float; do
    # ------------------------------------------------------------ build
    logs=$(find "$FW/$p/obj" -name '*.o.log' -size +0 2>/dev/null | sort)
    check "$p: firmware library and demo compiled without warnings (-Wdouble-promotion -Wconversion ...)" [ -z "$logs" ]
    [ -z "$logs" ] || for f in $logs; do sed 's/^/#   /' "$f" | head -5; done
    # Undefined symbols of the library: nothing of the heap, stdio or abort.
    bad=$("$NM" -u "$FW/$p/libbraun.a" 2>/dev/null | awk '{print $NF}' |
          grep -E '^(malloc|calloc|realloc|free|_malloc_r|_free_r|abort|exit|_exit|_sbrk|printf|fprintf|sprintf|snprintf|vprintf|vfprintf|vsnprintf|puts|putchar|fputs|fwrite)$' | sort -u | tr '\n' ' ')
    check "$p: libbraun.a references no malloc/free/printf/abort (nm -u)${bad:+: $bad}" [ -z "$bad" ]
    # What the library takes from outside itself (libm, libgcc, string.h).
    "$NM" --defined-only "$FW/$p/libbraun.a" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u > "$OUT/$p-defined"
    undef=$("$NM" -u "$FW/$p/libbraun.a" 2>/dev/null | awk 'NF == 2 {print $2}' | sort -u |
            comm -23 - "$OUT/$p-defined" | tr '\n' ' ')
    echo "#   $p: libbraun.a needs from outside: $undef"
    heap=$("$NM" "$FW/$p/demo.elf" | awk '{print $NF}' | grep -E '^(malloc|free|_malloc_r|_sbrk|printf)$' | tr '\n' ' ')
    check "$p: demo image links no allocator or printf${heap:+: $heap}" [ -z "$heap" ]

    # ------------------------------------------------------------ emulator
    emu "$FW/$p/demo.elf" "$OUT/$p-target.txt" test
    check "$p: demo exits with status 0 on the emulator (semihosting SYS_EXIT_EXTENDED)" [ "$rc" -eq 0 ]
    [ "$rc" -eq 0 ] || sed 's/^/#   /' "$OUT/$p-target.txt" | tail -5
    "$FW/host-$p/fw_host" test > "$OUT/$p-host.txt" 2>&1; hrc=$?
    check "$p: host build of the demo exits with status 0" [ "$hrc" -eq 0 ]
    instr=$(val calib instructions "$OUT/$p-target.txt"); ticks=$(val calib ticks "$OUT/$p-target.txt")
    check "$p: timer calibration: 40 instructions per 25 MHz tick under -icount shift=0 ($instr / $ticks)" \
        awk -v i="${instr:-0}" -v t="${ticks:-1}" 'BEGIN { r = i / t; exit !(r > 39.99 && r < 40.01) }'
    check "$p: workspace sizes fixed at build time equal braun_data_size()" \
        grep -q '^sizes_check result=ok' "$OUT/$p-target.txt"
    # Measured 1864 bytes (double), 1624 (float) of the 16 KB reservation.
    used=$(val stack used "$OUT/$p-target.txt"); size=$(val stack size "$OUT/$p-target.txt")
    check "$p: stack high-water mark ${used:-?} of ${size:-?} bytes, at most 4096" sh -c '
        case "$1$2" in ""|*[!0-9]*) exit 1 ;; esac
        [ "$1" -gt 0 ] && [ "$1" -le 4096 ] && [ "$1" -lt "$2" ]' sh "$used" "$size"
    emu "$FW/$p/demo.elf" "$OUT/$p-usage.txt" no-such-command
    check "$p: a failing program's status reaches the host (usage error -> exit 2, got $rc)" [ "$rc" -eq 2 ]
    for v in ideal pv all; do
        emu "$FW/$p/gc-$v.elf" "$OUT/$p-gc-$v.txt" ""
        check "$p: gc-sections image '$v' runs 1000 RK4 steps of a pendulum and stays on its circle (|Phi| < 1e-4)" \
            sh -c '[ "$1" -eq 0 ] && grep -q "^gc demo: ok, stack used [0-9]" "$2"' sh "$rc" "$OUT/$p-gc-$v.txt"
    done
done

# ---------------------------------------------------------------- fixed sizes
# With the core's compile-time sizes (BRAUN_FIXED_N), the float library
# built for n = 6, rows = 5 at -O3 -flto must give the generic float
# library's results bit for bit, and refuse a model of another size.
case " ${FW_CONFIGS:-} " in
*" float-fixed "*)
    logs=$(find "$FW/float-fixed/obj" -name '*.o.log' -size +0 2>/dev/null | sort)
    check "float-fixed: compiled without warnings" [ -z "$logs" ]
    emu "$FW/float-fixed/demo.elf" "$OUT/float-fixed-target.txt" test builtin
    check "float-fixed: demo exits with status 0 on the emulator" [ "$rc" -eq 0 ]
    # The built-in runs (n = 6, rows = 5) of both images.
    records() { awk '/^run model=scene:/ { exit } /^(run|max|final|q|v|stats|status) / { print }' "$1"; }
    records "$OUT/float-fixed-target.txt" > "$OUT/float-fixed.rec"
    records "$OUT/float-target.txt" > "$OUT/float.rec"
    check "float-fixed: every record equal, bit for bit, to the generic float library's" \
        cmp -s "$OUT/float-fixed.rec" "$OUT/float.rec"
    emu "$FW/float-fixed/demo.elf" "$OUT/float-fixed-sizes.txt" sizes
    check "float-fixed: a model of another size (pendulum, n = 2) is refused" \
        grep -q '^sizes model=pendulum .*data_bytes=unsupported' "$OUT/float-fixed-sizes.txt"
    ;;
*)
    for c in "compiled without warnings" "demo exits with status 0 on the emulator" \
        "every record equal, bit for bit, to the generic float library's" \
        "a model of another size (pendulum, n = 2) is refused"; do
        skip "float-fixed: $c" "not configured (the core has no BRAUN_FIXED_N)"
    done ;;
esac

# ---------------------------------------------------------------- scene to C
# The demo ran its scenes from C written by the generator (compiled above,
# warning-free); fw_compare below checks them against the host's runs of
# the same scene files. Every shipped scene must convert and compile.
# (mk/firmware.mk's FW_SCENES: five, two of them spatial; the host build
# reads the same scenes from their files.)
for p in double float; do
    nscenes=$(grep -c '^run model=scene:' "$OUT/$p-target.txt")
    nhost=$(grep -c '^run model=scene:' "$OUT/$p-host.txt")
    check "scene to C ($p): the emulator ran $nscenes scenes from generated C (static data, no parser), as many as the host ($nhost), at least 5" \
        sh -c '[ "$1" -ge 5 ] && [ "$1" -eq "$2" ]' sh "${nscenes:-0}" "${nhost:-0}"
    # The spatial ones (rigid3d bodies in Euler parameters), ended BRAUN_OK.
    for sc in spatial-arm a04-bricard; do
        check "scene to C ($p): spatial scene $sc ran on the emulator and ended BRAUN_OK" \
            run_ok "$OUT/$p-target.txt" "scene:$sc"
    done
done
gen_bad=""
for json in data/*.json data/iftomm/*.json; do
    [ -f "$json" ] || continue
    sym=$(basename "$json" .json | tr -c 'A-Za-z0-9_\n' '_')
    if ! "${BRAUN:-build/bin/braun}" gen-c "$json" --symbol "s_$sym" -o "$OUT/gen-$sym.c" 2> "$OUT/gen-$sym.log"; then
        gen_bad="$gen_bad $json(gen)"; continue
    fi
    for def in "" -DBRAUN_SINGLE; do
        # shellcheck disable=SC2086
        ${FW_CC:-arm-none-eabi-gcc} -std=c99 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
            -Wall -Wextra -Wpedantic -Wdouble-promotion -Wconversion -Werror $def -Iinclude/core \
            -c "$OUT/gen-$sym.c" -o "$OUT/gen-$sym.o" 2>> "$OUT/gen-$sym.log" || gen_bad="$gen_bad $json$def"
    done
done
check "scene to C: every data/*.json and data/iftomm/*.json converts to C that compiles for the M4F, double and float, -Wconversion -Wdouble-promotion -Werror${gen_bad:+:$gen_bad}" [ -z "$gen_bad" ]

# ---------------------------------------------------------------- comparison
# Spatial scenes (docs/firmware.md, "Host and target agree"):
#  - a04-bricard has no transcendental function: float agrees bit for bit.
#    Double does not quite: libgcc's __adddf3 misrounds 1 - b for b in
#    [2^-33, 2^-32) (`dadd` below), the Householder QR meets such sums and
#    the redundant row amplifies them; measured 1.4e-16 (v) after 50 steps,
#    4.1e-14 after 100: bound 1e-13.
#  - spatial-arm (atan2f, sqrtf of newlib and glibc): float target vs host
#    measured 2.9e-6 (v), each within 9.5e-6 of the double run: bounds 1e-5
#    and 5e-5; double 4.7e-15, under the default 2e-14.
#  - a04-bricard float vs double: measured 3.2e-4 (v, relative to a small
#    |v| after 0.05 s from rest; float's rank tolerance 30 sqrt(eps) and
#    energy-guard hits on the redundant row): bound 1e-3.
"$FW/fw_compare" --exact four-bar --exact-float scene:a04-bricard \
    --bound double scene:a04-bricard 1e-13 0 --bound float scene:a04-bricard 0 1e-3 \
    --bound float scene:spatial-arm 1e-5 5e-5 "$OUT/double-target.txt" "$OUT/double-host.txt" \
    "$OUT/float-target.txt" "$OUT/float-host.txt" > "$OUT/compare.txt" 2>&1; crc=$?
cat "$OUT/compare.txt"
p=$(grep -c '^ok - ' "$OUT/compare.txt"); f=$(grep -c '^not ok - ' "$OUT/compare.txt")
passed=$((passed + p)); failed=$((failed + f))
# Its exit status agrees with its lines (a crash or a file it could not read
# is a failure), and it compared every run of both precisions.
runs=$(grep -c '^run ' "$OUT/float-host.txt")
check "fw_compare: exit status $crc, $f failed checks, $p passed" sh -c '
    [ "$1" -gt 0 ] && { { [ "$2" -eq 0 ] && [ "$3" -eq 0 ]; } || { [ "$2" -eq 1 ] && [ "$3" -gt 0 ]; }; }' \
    sh "$p" "$crc" "$f"
# The misrounding behind the double bound above: target count, host none
# (its check is exact: a host result other than 0 means the probe is wrong).
emu "$FW/double/demo.elf" "$OUT/dadd-target.txt" dadd
"$FW/host-double/fw_host" dadd > "$OUT/dadd-host.txt" 2>&1
dt=$(sed -n 's/^dadd .*misrounded=\([0-9]*\).*/\1/p' "$OUT/dadd-target.txt")
dh=$(sed -n 's/^dadd .*misrounded=\([0-9]*\).*/\1/p' "$OUT/dadd-host.txt")
echo "#   double addition 1 + b, b in -[2^-33, 2^-32): target (libgcc __adddf3) misrounds ${dt:-?} of 20000, host ${dh:-?}"
check "dadd probe: the host's double addition rounds all 20000 sums correctly (the probe is exact)" [ "${dh:-x}" = 0 ]
# A fixed-step span of more steps than a 32-bit long holds is refused
# (BRAUN_ERR_TOO_MANY_STEPS, code -13 in braun.h), the state untouched.
TOO_MANY=$(sed -n 's/.*BRAUN_ERR_TOO_MANY_STEPS = \(-[0-9]*\),.*/\1/p' include/core/braun.h)
for p in float double; do
    emu "$FW/$p/demo.elf" "$OUT/limits-$p.txt" limits
    lst=$(sed -n 's/^limits .*status=\([-0-9]*\).*/\1/p' "$OUT/limits-$p.txt")
    lun=$(sed -n 's/^limits .*t_untouched=\([0-9]*\).*/\1/p' "$OUT/limits-$p.txt")
    check "$p: braun_integrate refuses 1e10 fixed steps with a 32-bit step counter (status ${lst:-?}, want $TOO_MANY)" \
        [ "${lst:-x},${lun:-0}" = "$TOO_MANY,1" ]
done
check "fw_compare: compared all $runs runs of each precision" sh -c '
    [ "$1" -gt 0 ] && [ "$(grep -c ": same run header$" "$2")" -eq $((2 * $1)) ]' sh "$runs" "$OUT/compare.txt"

# ---------------------------------------------------------------- no double on the float step path
# On the M4F (single-precision FPU) every double operation is a call to a
# libgcc soft-float helper or a double libm function. Statically
# (firmware/tools/double-path.awk on the disassembly of path.elf, the float
# demo with braun_integrate and braun_integrate_adaptive linked too): every
# function reachable from braun_step (and from each driver) — direct calls,
# and every function whose address the library stores (callbacks, classes,
# the solver table) — calls a double helper only to convert an argument of
# the error record (followed by braun__fail, or, with braun__fail inlined,
# on a source line inside a braun__fail(...) call). Dynamically: runs of
# every model and scene under QEMU -d in_asm translate no double helper at
# all, and every library function first run after the first step's block
# is one the static graph reached.
OBJDUMP=${FW_OBJDUMP:-arm-none-eabi-objdump}
ADDR2LINE=${FW_ADDR2LINE:-arm-none-eabi-addr2line}
# path_check CONFIG ROOT: the static analysis; writes $OUT/CONFIG-path-ROOT.txt
# and $OUT/CONFIG-path-ROOT.bad (violations not inside a braun__fail call:
# "FUNC HELPER FILE:LINE").
path_check() {
    pc=$1; root=$2; img=$FW/$pc/path.elf
    # Disassembled once per build of the image.
    if [ ! -s "$OUT/$pc-path.dis" ] || [ -n "$(find "$img" -newer "$OUT/$pc-path.dis")" ]; then
        "$OBJDUMP" -d --no-show-raw-insn "$img" > "$OUT/$pc-path.dis"
        "$OBJDUMP" -s -j .text -j .data "$img" > "$OUT/$pc-path.words"
    fi
    awk -v roots="$root" -v lib="libbraun.a(" -f firmware/tools/double-path.awk \
        "$FW/$pc/path.map" "$OUT/$pc-path.dis" "$OUT/$pc-path.words" > "$OUT/$pc-path-$root.txt"
    # One addr2line for all the calls; a call is inside a braun__fail(...)
    # call when its line, or a line before it back to the end of the
    # previous statement, names braun__fail(.
    grep '^violation ' "$OUT/$pc-path-$root.txt" > "$OUT/$pc-path-$root.viol"
    awk '{ print "0x" $3 }' "$OUT/$pc-path-$root.viol" | "$ADDR2LINE" -e "$img" |
        sed 's/ (discriminator.*//' | paste -d ' ' "$OUT/$pc-path-$root.viol" - |
        awk -v pwd="$PWD/" '
        function load(f,    x, n) {
            if (f in nl) return
            n = 0
            while ((getline x < f) > 0) src[f, ++n] = x
            close(f)
            nl[f] = n
        }
        {
            loc = $5; line = loc; sub(/^.*:/, "", line); file = loc; sub(/:[^:]*$/, "", file)
            load(file)
            inside = 0
            for (i = line + 0; i > 0 && i > line - 8 && nl[file] > 0; i--) {
                if (i < line && src[file, i] ~ /[;{}][ \t]*$/) break
                if (src[file, i] ~ /braun__fail\(/) { inside = 1; break }
            }
            if (index(loc, pwd) == 1) loc = substr(loc, length(pwd) + 1)
            if (!inside) print $2, $4, loc
        }' > "$OUT/$pc-path-$root.bad"
}
# The float library's link names end in _float (braun.h, "Link names").
path_check float braun_step_float
reach=$(sed -n 's/^reachable //p' "$OUT/float-path-braun_step_float.txt")
roots=$(sed -n 's/^roots //p' "$OUT/float-path-braun_step_float.txt")
conv=$(awk '/^allowed / { s += $4 } END { print s + 0 }' "$OUT/float-path-braun_step_float.txt")
bad=$(sort -u "$OUT/float-path-braun_step_float.bad" | tr '\n' ';')
check "float: no double operation on braun_step's path: $reach functions from $roots roots (drivers, callbacks, classes), double helpers called only to record an error ($conv conversions)${bad:+: $bad}" \
    sh -c '[ -z "$1" ] && [ "${2:-0}" -ge 100 ] && [ "${3:-0}" -ge 20 ] && ! grep -q "^missing-root" "$4"' \
    sh "$bad" "$reach" "$roots" "$OUT/float-path-braun_step_float.txt"
# The drivers' own double arithmetic (src/core/braun_integrate.c: the step
# count, once per call; braun_adaptive.c: the error norm and step-size
# control, every step): known, reported, confined to the driver.
for root in braun_integrate_float braun_integrate_adaptive_float; do
    path_check float "$root"
    own=$(awk -v r="$root" '$1 != r' "$OUT/float-path-$root.bad" | sort -u | tr '\n' ';')
    sites=$(awk '{ print $3 }' "$OUT/float-path-$root.bad" | sort -u | tr '\n' ' ')
    check "float: $root: double operations only in the driver itself (known: ${sites:-none})${own:+; elsewhere: $own}" [ -z "$own" ]
done
# The check can fail: the double build's step path is all double helpers.
path_check double braun_step
n=$(wc -l < "$OUT/double-path-braun_step.bad")
check "double: the same check finds the soft-float calls of the double build ($n)" [ "$n" -ge 50 ]

# Dynamically, under QEMU -d in_asm (each translated block logged once, in
# the order first run): STEPS steps of each model and scene.
awk '/^fn / { print $2 }' "$OUT/float-path-braun_step_float.txt" | sort -u > "$OUT/float-path-reach"
"$NM" --defined-only "$FW/float/libbraun.a" 2>/dev/null | awk '$2 ~ /^[Tt]$/ { print $3 }' | sort -u > "$OUT/float-libfns"
for pc in float float-fixed; do
    case " ${FW_CONFIGS:-} " in *" $pc "*) ;; *) continue ;; esac
    for ms in slider-crank:2000 four-bar:2000 pendulum:500 scene:sleigh:500 scene:damped-motor:500 \
              scene:spatial-arm:500 scene:a04-bricard:50; do
        m=${ms%:*}; k=${ms##*:}
        if [ "$pc" = float-fixed ]; then case $m in slider-crank|four-bar) ;; *) continue ;; esac; fi
        # shellcheck disable=SC2086
        timeout 120 "$QEMU" $QFLAGS -kernel "$FW/$pc/demo.elf" -append "trace $m $k" -d in_asm \
            -D "$OUT/$pc-trace.log" > "$OUT/$pc-trace-$m.txt" 2>&1
        trc=$?
        awk '/^IN: / { if (!($2 in s)) { s[$2] = 1; print $2 } }' "$OUT/$pc-trace.log" > "$OUT/$pc-trace-$m.fns"
        rm -f "$OUT/$pc-trace.log"
        dbl=$(awk 'function d(n) { return n ~ /^__aeabi_(d[a-z0-9]*|[a-z0-9]+2d|cd[a-z]*)$/ || n ~ /df[0-9]$/ ||
                   n ~ /^__(extendsfdf2|truncdfsf2)$/ || n ~ /^__ieee754_[a-z0-9_]*[^f]$/ ||
                   n ~ /^(sqrt|pow|ceil|floor|sin|cos|exp|log|atan2|hypot)$/ } d($1)' "$OUT/$pc-trace-$m.fns" | tr '\n' ' ')
        stats=$(sed -n 's/^trace .* steps=\([0-9]*\) rank_deficient=\([0-9]*\) guard=\([0-9]*\) status=\([-0-9]*\).*/\1 steps, \2 rank-deficient, \3 guard hits, status \4/p' "$OUT/$pc-trace-$m.txt")
        extra=""
        if [ "$pc" = float ]; then
            extra=$(awk -v r="$OUT/float-path-reach" -v l="$OUT/float-libfns" '
                BEGIN { while ((getline x < r) > 0) reach[x] = 1; while ((getline x < l) > 0) lib[x] = 1 }
                $1 == "braun_step_float" { on = 1 }
                on && ($1 in lib) && !($1 in reach) { print $1 }' "$OUT/float-trace-$m.fns" | tr '\n' ' ')
        fi
        check "$pc: $m, $k steps under QEMU (${stats:-no record}): no double helper run${dbl:+: $dbl}${extra:+; library functions the static graph missed: $extra}" \
            sh -c '[ "$1" -eq 0 ] && [ -z "$2" ] && [ -z "$3" ] && grep -q "^trace .* steps=$4 .*status=0" "$5"' \
            sh "$trc" "$dbl" "$extra" "$k" "$OUT/$pc-trace-$m.txt"
    done
done

# ---------------------------------------------------------------- float study
# The issue's criterion, on the emulator: float slider-crank, h = 1e-3,
# 100 s through its bifurcation points (~6 s of emulation). Measured max
# ||Phi_q|| 5.3e-7 .. 6.0e-7 (bound 2e-6; the issue's was 1e-5) and a
# trajectory error 0.61 x that of float RK4 on Eq. 24 (the criterion: 2 x).
emu "$FW/float/demo.elf" "$OUT/float-long.txt" long slider-crank 1e-3 100000 1
"$FW/fw_traj" "$OUT/float-long.txt" 2e-6 2 > "$OUT/float-long-traj.txt" 2>&1; trc=$?
cat "$OUT/float-long-traj.txt"
p=$(grep -c '^ok - ' "$OUT/float-long-traj.txt"); f=$(grep -c '^not ok - ' "$OUT/float-long-traj.txt")
passed=$((passed + p)); failed=$((failed + f))
check "float 100 s study: its three checks, exit status $trc agreeing with them" sh -c '
    [ $(($1 + $2)) -eq 3 ] && { { [ "$3" -eq 0 ] && [ "$2" -eq 0 ]; } || { [ "$3" -ne 0 ] && [ "$2" -gt 0 ]; }; }' \
    sh "$p" "$f" "$trc"

echo "# firmware-test took $(( $(date +%s) - start )) s"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
