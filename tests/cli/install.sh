#!/bin/sh
# make install into a temporary DESTDIR, then build the README example
# against it through pkg-config and run it; the shared libraries (soname,
# exactly the public API exported), the CMake package, and every example
# built with pkg-config and with CMake, linked statically and dynamically,
# and run (issue 15); programs of one precision do not link with the
# other's libraries, and a tree built in double installs float when asked
# (a scratch build). Prints "ok - NAME" / "not ok - NAME" and
# "N passed, M failed, 0 skipped".
set -u
top=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0; skip=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
skipped() { echo "ok - $1 # SKIP $2"; skip=$((skip + 1)); }
# The build under test (make test passes its BUILD).
if make -s -C "$top" install BUILD="${BUILD:-build}" PREFIX=/opt/braun DESTDIR="$tmp" >"$tmp/log" 2>&1; then ok "make install"; else no "make install"; cat "$tmp/log"; fi
for f in include/braun.h include/braun_models.h include/braun_scene.h include/braun_host.h include/braun_reference.h include/braun_scene_file.h lib/libbraun.a lib/libbraun_host.a lib/pkgconfig/braun.pc lib/pkgconfig/braun-host.pc bin/braun; do
    [ -f "$tmp/opt/braun/$f" ] && ok "installed $f" || no "installed $f"
done
pc="$tmp/opt/braun/lib/pkgconfig"
# needs_braun FILE: 1 if FILE names libbraun*.so in NEEDED.
needs_braun() { readelf -d "$1" 2>/dev/null | grep -q "NEEDED.*libbraun"; }
# A program that asks the library it runs with (braun_version,
# braun_precision) and says what it was compiled against.
cat > "$tmp/ver.c" <<'C'
#include <stdio.h>
#include <braun.h>
int main(void)
{
#ifdef BRAUN_SINGLE
    const char *compiled = "float";
#else
    const char *compiled = "double";
#endif
    printf("%s %s %s %s\n", braun_version(), braun_precision(), BRAUN_VERSION, compiled);
    return 0;
}
C
flags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs --static braun 2>&1)
case "$flags" in *"-lbraun"*) ok "pkg-config --libs braun" ;; *) no "pkg-config --libs braun: $flags" ;; esac
# The DESTDIR flow of the README: -I and -L are the staging directory's
# (the sysroot prefixed once, or not at all to a path already in it).
realdir() { (cd "$1" 2>/dev/null && pwd -P); }
fi_=$(echo "$flags" | tr ' ' '\n' | sed -n 's/^-I//p' | head -1)
fl_=$(echo "$flags" | tr ' ' '\n' | sed -n 's/^-L//p' | head -1)
if [ -n "$fi_" ] && [ "$(realdir "$fi_")" = "$(realdir "$tmp/opt/braun/include")" ] &&
   [ "$(realdir "$fl_")" = "$(realdir "$tmp/opt/braun/lib")" ]; then
    ok "pkg-config under PKG_CONFIG_SYSROOT_DIR: -I and -L are the staging directory's"
else
    no "pkg-config under PKG_CONFIG_SYSROOT_DIR: $flags"
fi
if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$top/examples/pendulum.c" $flags -o "$tmp/pendulum" 2>"$tmp/cc.log"; then
    ok "README example compiles warning-free against the installed library"
    out=$(LD_LIBRARY_PATH="$tmp/opt/braun/lib" "$tmp/pendulum"); rc=$?
    case "$rc:$out" in "0:t = 10 "*) ok "README example runs: $out" ;; *) no "README example (exit $rc) output: $out" ;; esac
    # The same pendulum (released from the horizontal, RK4 h = 1e-3, every
    # correction) as the installed tool's built-in model: the same q at t = 10.
    ref=$("$tmp/opt/braun/bin/braun" run pendulum --dt 1e-3 --t-end 10 2>&1 |
          sed -n 's/^  "final_q": \[\(.*\)\],$/\1/p')
    got=$(echo "$out" | sed -n 's/.* q = (\([^)]*\)).*/\1/p')
    if awk -v a="$got" -v b="$ref" 'BEGIN { n = split(a, x, ","); m = split(b, y, ",")
            if (n != 2 || m != 2) exit 1
            for (i = 1; i <= 2; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 1e-9) exit 1 }
            exit 0 }'; then
        ok "README example: q at t = 10 ($got) is the installed braun's pendulum ($ref)"
    else
        no "README example: q at t = 10 ($got) differs from the installed braun's pendulum ($ref)"
    fi
else
    no "README example compiles"; cat "$tmp/cc.log"
fi
# The backends: their headers, archive and pkg-config file.
for f in include/braun_linsolver.h include/braun_backends.h lib/libbraun_backends.a lib/pkgconfig/braun-backends.pc; do
    [ -f "$tmp/opt/braun/$f" ] && ok "installed $f" || no "installed $f"
done
cat > "$tmp/sel.c" <<'C'
#include <stdio.h>
#include <braun_backends.h>
int main(void)
{
    braun_system s = {0};
    const braun_linsolver *ls = NULL;
    s.n = 100;
    int st = braun_linsolver_select("auto", &s, &ls, NULL);
    printf("%d %s\n", st, braun_linsolver_name(ls));
    return st;
}
C
bflags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs --static braun-backends 2>&1)
if ${CC:-cc} -std=c99 -Wall -Wextra -Werror "$tmp/sel.c" $bflags -o "$tmp/sel" 2>"$tmp/cc2.log"; then
    # auto picks LAPACK for a dense n >= 41 when it is built (the installed
    # tool says whether it is), the built-in kernels otherwise.
    if "$tmp/opt/braun/bin/braun" run slider-crank --dt 1e-3 --t-end 0.01 --backend lapack >/dev/null 2>&1
    then want="0 lapack"; else want="0 dense"; fi
    sel_want=$want
    out=$(LD_LIBRARY_PATH="$tmp/opt/braun/lib" "$tmp/sel")
    case "$out" in "$want") ok "a program links the installed backends (auto for a dense n = 100: $out)" ;;
    *) no "backend selection output: $out" ;; esac
else
    no "a program links the installed backends"; cat "$tmp/cc2.log"
fi

# A static link of the backends: Libs.private lists every library they
# need, transitively (it listed SuiteSparse's and LAPACK's own five, so
# AMD, COLAMD, libgomp, libgfortran, ... were undefined). Fully static
# (-static): what stays undefined must come only from libraries with no
# static archive here (Debian 12: METIS, whose libmetis-dev ships none).
sflags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --static --cflags --libs braun-backends 2>&1)
keep="" noa=""
for f in $sflags; do
    case $f in
    -lbraun*) keep="$keep $f" ;;
    -l*) a=$(${CC:-cc} -print-file-name="lib${f#-l}.a")
         case $a in */*) [ -e "$a" ] && { keep="$keep $f"; continue; } ;; esac
         noa="$noa ${f#-l}" ;;
    *) keep="$keep $f" ;;
    esac
done
if ${CC:-cc} -static -std=c99 "$top/examples/backends.c" $keep -o "$tmp/backends-static" 2> "$tmp/static.log"; then
    out=$("$tmp/backends-static" 2>&1)
    case "$out" in "chain of 30 links"*) ok "a fully static program (-static) links the backends through pkg-config --static and runs ($out)" ;;
    *) no "the fully static backends program: $out" ;; esac
else
    undef=$(grep -o "undefined reference to .[A-Za-z0-9_]*'" "$tmp/static.log" | sed "s/.* .\\(.*\\)'/\\1/" | sort -u)
    # What the libraries named in the .pc without a static archive define
    # may stay undefined.
    defs=""
    for n in $noa; do
        so=$(${CC:-cc} -print-file-name="lib$n.so")
        case $so in */*) defs="$defs $(nm -D --defined-only "$so" | awk '{ print $3 }' | tr '\n' ' ')" ;; esac
    done
    stray=""
    for u in $undef; do case " $defs " in *" $u "*) ;; *) stray="$stray $u" ;; esac; done
    if [ -n "$undef" ] && [ -z "$stray" ]; then
        ok "a fully static link of the backends lacks only what comes from libraries with no static archive here ($noa):$(echo $undef | cut -c1-80)"
    else
        no "a fully static link of the backends: undefined beyond the libraries without an archive ($noa):$(echo $stray | cut -c1-300) $(grep -v "undefined reference\|in function" "$tmp/static.log" | head -3)"
    fi
fi

# The host tier (and the core with it) links fully static.
hsflags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --static --cflags --libs braun-host 2>&1)
if ${CC:-cc} -static -std=c99 "$top/examples/scene.c" $hsflags -o "$tmp/scene-static" 2> "$tmp/hstatic.log" &&
   out=$("$tmp/scene-static" "$top/data/four-bar.json" 1e-3 1 2>&1) && case "$out" in "four-bar: t = 1, 1000 steps"*) true ;; *) false ;; esac; then
    ok "a fully static program (-static) links the host library through pkg-config --static and runs"
else
    no "a fully static host program: $(head -3 "$tmp/hstatic.log") $out"
fi

# ------------------------------------------------------------ shared libraries
P=$tmp/opt/braun
L=$P/lib
ver=$(sed -n 's/^#define BRAUN_VERSION "\(.*\)"/\1/p' "$top/include/core/braun.h")
so=$(echo "$ver" | cut -d. -f1-2)
for l in libbraun libbraun_host libbraun_backends; do
    if [ -f "$L/$l.so.$ver" ] && [ "$(readlink "$L/$l.so.$so")" = "$l.so.$ver" ] &&
        [ "$(readlink "$L/$l.so")" = "$l.so.$so" ] && [ -f "$L/$l.a" ]; then
        ok "installed $l.so.$ver, the links $l.so.$so and $l.so, and $l.a"
    else
        no "installed $l.so.$ver with its links and $l.a"
    fi
    sn=$(readelf -d "$L/$l.so.$ver" 2>/dev/null | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
    [ "$sn" = "$l.so.$so" ] && ok "$l.so has the soname $sn" || no "$l.so soname: '$sn' (want $l.so.$so)"
done
needed=$(readelf -d "$L/libbraun.so.$ver" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' ')
case "$needed" in "libm.so.6 libc.so.6 ") ok "libbraun.so needs libm and libc only ($needed)" ;;
*) no "libbraun.so needs: $needed" ;; esac
readelf -d "$L/libbraun_host.so.$ver" | grep -q "NEEDED.*\[libbraun.so.$so\]" &&
    ok "libbraun_host.so needs libbraun.so.$so" || no "libbraun_host.so does not name libbraun.so.$so"
# Exactly the public API: every exported symbol is declared in a public
# header and versioned BRAUN_<so>; none of the internals (braun__*, the
# dense kernels, the scene builder's helpers, the reader's sj_*).
for l in libbraun libbraun_host libbraun_backends; do
    nm -D --defined-only "$L/$l.so.$ver" | awk '$2 != "A" { sub(/@.*/, "", $3); print $3 }' | sort > "$tmp/$l.exported"
    "$top/tools/export-map" --declared "$top"/include/core/*.h "$top"/include/host/*.h > "$tmp/declared" ||
        no "tools/export-map --declared: the public headers' identifiers"
    extra=$(comm -23 "$tmp/$l.exported" "$tmp/declared" | tr '\n' ' ')
    n=$(wc -l < "$tmp/$l.exported" | tr -d ' ')
    unversioned=$(nm -D --defined-only "$L/$l.so.$ver" | awk '$2 != "A" && $3 !~ /@@BRAUN_'"$so"'$/' | wc -l)
    if [ -z "$extra" ] && [ "$n" -gt 0 ] && [ "$unversioned" -eq 0 ]; then
        ok "$l.so exports $n symbols, each declared in a public header, versioned BRAUN_$so"
    else
        no "$l.so exports beyond the public headers: $extra ($unversioned unversioned)"
    fi
done
cat "$tmp/libbraun.exported" "$tmp/libbraun_host.exported" "$tmp/libbraun_backends.exported" | sort -u > "$tmp/all.exported"
grep -q "^braun_integrate$" "$tmp/libbraun.exported" && grep -q "^braun_scene_build$" "$tmp/libbraun.exported" &&
    ! grep -q "^braun__\|^braun_qrcp_\|^braun_chol_\|^braun_scene__" "$tmp/libbraun.exported" &&
    grep -q "^braun_scene_load$" "$tmp/libbraun_host.exported" && ! grep -q "^sj_" "$tmp/libbraun_host.exported" &&
    ok "braun_integrate, braun_scene_build, braun_scene_load exported; braun__*, braun_qrcp_*, braun_chol_*, sj_* not" ||
    no "exports: the API or the internals"
# The static libraries: every global symbol they define braun_-prefixed
# (the reader's sj_* clashed with a program's own sj_fail at link time).
stray=$(for l in libbraun libbraun_host libbraun_backends; do
    nm --defined-only -g "$L/$l.a" 2>/dev/null | awk 'NF == 3 { print $3 }'; done | grep -v '^braun' | sort -u | tr '\n' ' ')
[ -z "$stray" ] && ok "the static libraries define braun_* globals only" ||
    no "the static libraries define globals without the prefix: $stray"
# The version scripts do not depend on the compiler: tools/export-map
# ran gcc's -fpreprocessed, so `make CC=clang` stopped at libbraun.map
# with a false "defines nothing declared" (clang's own error went to
# /dev/null).
B0=${BUILD:-build}
case $B0 in /*) ;; *) B0=$top/$B0 ;; esac
if command -v gcc > /dev/null 2>&1 && command -v clang > /dev/null 2>&1; then
    for c in gcc clang; do
        CC=$c "$top/tools/export-map" BRAUN_X "$B0/libbraun.a" "$top"/include/core/*.h "$top"/include/host/*.h \
            > "$tmp/map-$c" 2> "$tmp/map-$c.err" || cat "$tmp/map-$c.err"
    done
    [ -s "$tmp/map-gcc" ] && cmp -s "$tmp/map-gcc" "$tmp/map-clang" &&
        ok "tools/export-map: the same version script with CC=gcc and CC=clang ($(grep -c ';' "$tmp/map-gcc") lines)" ||
        no "tools/export-map: CC=gcc and CC=clang give different scripts (or none)"
else
    skipped "tools/export-map with gcc and clang" "gcc or clang not installed"
fi
if CC="${CC:-cc} -fno-such-option-braun" "$top/tools/export-map" BRAUN_X "$B0/libbraun.a" "$top/include/core/braun.h" \
        > /dev/null 2> "$tmp/map-bad.err"; then
    no "tools/export-map with a compiler that fails: exit 0"
elif grep -q "no-such-option-braun" "$tmp/map-bad.err" && ! grep -q "defines nothing" "$tmp/map-bad.err"; then
    ok "tools/export-map with a compiler that fails: exit 1 with the compiler's own message"
else
    no "tools/export-map with a compiler that fails: $(cat "$tmp/map-bad.err")"
fi
for f in lib/cmake/braun/braunConfig.cmake lib/cmake/braun/braunConfigVersion.cmake share/braun/data/four-bar.json \
    share/braun/examples/pendulum.c share/braun/examples/CMakeLists.txt share/doc/braun/README.md share/doc/braun/CHANGELOG.md; do
    [ -f "$P/$f" ] && ok "installed $f" || no "installed $f"
done
"$P/bin/braun" --version > "$tmp/version.txt" 2>&1
grep -q "^braun $ver (libbraun $ver, " "$tmp/version.txt" && ok "braun --version: $(cat "$tmp/version.txt")" ||
    no "braun --version: $(cat "$tmp/version.txt") (want braun $ver (libbraun $ver, ...)"
# ------------------------------------------------------------ one version
# BRAUN_VERSION (include/core/braun.h) is the one place the version is
# written; every other place derives from it and agrees with it (0.1.0's
# ABI changed while all of them said 0.1: tests/abi/check.sh). Here: the
# header, braun --version (above), braun_version() (below), the three .pc
# files, the CMake version file, the sonames and the symbol version node,
# the versions the docs and examples ask for, the CHANGELOG's release.
bad=""
for m in braun braun-host braun-backends; do
    mv_=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --modversion "$m" 2>&1)
    [ "$mv_" = "$ver" ] || bad="$bad $m.pc:$mv_"
done
grep -q "^set(PACKAGE_VERSION \"$ver\")" "$L/cmake/braun/braunConfigVersion.cmake" || bad="$bad braunConfigVersion.cmake"
grep -q "^set(braun_VERSION \"$ver\")" "$L/cmake/braun/braunConfig.cmake" || bad="$bad braunConfig.cmake"
for l in libbraun libbraun_host libbraun_backends; do
    sn=$(readelf -d "$L/$l.so.$ver" 2>/dev/null | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
    [ "$sn" = "$l.so.$so" ] || bad="$bad $l-soname:$sn"
    nodes=$(readelf -V --wide "$L/$l.so.$ver" 2>/dev/null | grep -o 'BRAUN_[0-9][0-9.]*' | sort -u | tr '\n' ' ')
    [ "$nodes" = "BRAUN_$so " ] || bad="$bad $l-version-nodes:$nodes"
done
[ -z "$bad" ] && ok "version $ver everywhere: braun.h, the three .pc files, the CMake files, sonames *.so.$so, symbol version BRAUN_$so" ||
    no "version $ver (braun.h) disagrees with:$bad"
# What the docs and examples ask for and show.
bad=""
for f in README.md docs/api.md examples/CMakeLists.txt; do
    for w in $(grep -o 'find_package(braun [0-9][0-9.]*' "$top/$f" | sed 's/.* //' | sort -u); do
        [ "$w" = "$so" ] || bad="$bad $f:find_package(braun $w)"
    done
done
grep -q "braun $ver (libbraun $ver, " "$top/docs/cli.md" || bad="$bad docs/cli.md:--version"
rel=$(sed -n 's/^## \([0-9][0-9.]*\) .*/\1/p' "$top/CHANGELOG.md" | head -1)
[ "$rel" = "$ver" ] || bad="$bad CHANGELOG.md:latest-release-$rel"
[ -z "$bad" ] && ok "the docs, the examples' find_package and the CHANGELOG's latest release say $ver ($so)" ||
    no "docs and examples disagree with $ver:$bad"
# No other file writes the version itself.
others=$(cd "$top" && grep -rlF "$ver" Makefile mk cmake ./*.pc.in src include tools examples 2>/dev/null | grep -v '^include/core/braun.h$' | tr '\n' ' ')
[ -z "$others" ] && ok "the version $ver is written in include/core/braun.h alone (Makefile, mk, cmake, .pc.in, src, tools, examples derive it)" ||
    no "the version $ver is also written in: $others"
vflags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs braun 2>&1)
if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$tmp/ver.c" $vflags -o "$tmp/ver-d" 2> "$tmp/vd.log" &&
   needs_braun "$tmp/ver-d" && out=$(LD_LIBRARY_PATH="$L" "$tmp/ver-d") && [ "$out" = "$ver double $ver double" ]; then
    ok "a program on libbraun.so.$so: braun_version() $ver, braun_precision() double"
else
    no "braun_version()/braun_precision() on libbraun.so: '$out' $(cat "$tmp/vd.log")"
fi
mkdir -p "$tmp/anywhere"
(cd "$tmp/anywhere" && "$P/bin/braun" run four-bar.json --dt 1e-2 --t-end 1 --summary s.json) &&
    grep -q '"scene": "four-bar"' "$tmp/anywhere/s.json" &&
    ok "the installed braun runs a shipped scene by name from any directory (share/braun/data)" ||
    no "the installed braun runs four-bar.json from another directory"

# ------------------------------------------------------------ the examples
# What each example must print (its own checks decide its exit status).
ref_q=$("$P/bin/braun" run four-bar.json --dt 1e-3 --t-end 10 2>&1 | sed -n 's/^  "final_q": \[\(.*\)\],$/\1/p')
examples_run() { # examples_run DIR HOW: run the four examples built in DIR
    d=$1 how=$2     # (against the installation $EP, whose braun gave ref_q)
    out=$("$d/pendulum" 2>&1); rc=$?
    case "$rc:$out" in "0:t = 10 "*) ok "$how: pendulum runs ($out)" ;; *) no "$how: pendulum (exit $rc) $out" ;; esac
    out=$("$d/driven_crank" 2>&1); rc=$?
    [ "$rc" -eq 0 ] && ok "$how: driven_crank runs within its checks ($(echo "$out" | tr '\n' ';' | cut -c1-150))" ||
        no "$how: driven_crank (exit $rc) $out"
    out=$("$d/scene" "$EP/share/braun/data/four-bar.json" 1e-3 10 2>&1); rc=$?
    got=$(echo "$out" | sed -n 's/.* q = \(.*\)$/\1/p' | tr ' ' ',')
    if [ "$rc" -eq 0 ] && awk -v a="$got" -v b="$ref_q" 'BEGIN { n = split(a, x, ","); m = split(b, y, ",")
            if (n != 6 || m != 6) exit 1
            for (i = 1; i <= 6; i++) { e = x[i] - y[i]; if (e < 0) e = -e; if (e > 1e-8) exit 1 } }'; then
        ok "$how: scene runs the installed four-bar.json to braun's final q"
    else
        no "$how: scene (exit $rc): $out; braun: $ref_q"
    fi
    # A scene the model refuses (n = 4200 > BRAUN_MAX_DENSE): the reason
    # named; the example read an uninitialised braun_data ("unknown status
    # 1512411914", or a crash).
    out=$("$d/scene" "$tmp/chain-1400.json" 1e-3 0.01 2>&1); rc=$?
    case "$rc:$out" in "1:chain-1400: n, m or p above BRAUN_MAX_DENSE (4096"*"(BRAUN_ERR_SIZE"*)
        ok "$how: scene names why the model refuses a 4200-coordinate scene" ;;
    *) no "$how: scene on a 4200-coordinate scene (exit $rc): $out" ;; esac
    out=$("$d/backends" 2>&1); rc=$?
    case "$rc:$out" in "0:chain of 30 links (n = 90) with "*) ok "$how: backends runs ($out)" ;;
    *) no "$how: backends (exit $rc) $out" ;; esac
}
"$P/bin/braun" gen chain 1400 -o "$tmp/chain-1400.json" 2>"$tmp/gen.log" || cat "$tmp/gen.log"
EP=$P

cp -r "$P/share/braun/examples" "$tmp/ex-pc-shared"
cp -r "$P/share/braun/examples" "$tmp/ex-pc-static"
export PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc"
if make -s -C "$tmp/ex-pc-shared" CFLAGS="-std=c99 -O2 -Wall -Wextra -Wpedantic -Werror" > "$tmp/mk1.log" 2>&1; then
    ok "pkg-config, shared: the examples build warning-free (make -C examples)"
    needs_braun "$tmp/ex-pc-shared/pendulum" && needs_braun "$tmp/ex-pc-shared/scene" &&
        ok "pkg-config, shared: the programs load libbraun.so.$so" || no "pkg-config, shared: no libbraun.so in NEEDED"
    export LD_LIBRARY_PATH="$L"
    examples_run "$tmp/ex-pc-shared" "pkg-config, shared"
    unset LD_LIBRARY_PATH
    # A figure beyond its bound: exit 1, and stderr names each figure and
    # its bound (BOUND_SCALE shrinks them all; it once exited 1 in silence).
    if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -DBOUND_SCALE=1e-9 $(pkg-config --cflags braun) \
            "$tmp/ex-pc-shared/driven_crank.c" $(pkg-config --libs braun) -lm -o "$tmp/dc-tight" 2> "$tmp/dct.log"; then
        LD_LIBRARY_PATH="$L" "$tmp/dc-tight" > /dev/null 2> "$tmp/dct.err"; rc=$?
        nb=$(grep -c "^driven_crank: .* = .* is not below its bound .* (double)$" "$tmp/dct.err")
        if [ "$rc" -eq 1 ] && [ "$nb" -eq 5 ] && grep -q "motor: |Phi_q| = " "$tmp/dct.err" &&
           grep -q "prescribed: max |x_B - exact| = " "$tmp/dct.err"; then
            ok "driven_crank beyond its bounds: exit 1, each of the 5 figures named with its bound on stderr"
        else
            no "driven_crank beyond its bounds (exit $rc): $(cat "$tmp/dct.err")"
        fi
    else
        no "driven_crank with BOUND_SCALE builds"; cat "$tmp/dct.log"
    fi
else
    no "pkg-config, shared: the examples build"; cat "$tmp/mk1.log"
fi
if make -s -C "$tmp/ex-pc-static" STATIC=1 LIBDIR="$L" CFLAGS="-std=c99 -O2 -Wall -Wextra -Wpedantic -Werror" > "$tmp/mk2.log" 2>&1; then
    ok "pkg-config, static: the examples build warning-free (make -C examples STATIC=1)"
    ! needs_braun "$tmp/ex-pc-static/pendulum" && ! needs_braun "$tmp/ex-pc-static/backends" &&
        ok "pkg-config, static: the programs need no libbraun*.so" || no "pkg-config, static: libbraun*.so in NEEDED"
    examples_run "$tmp/ex-pc-static" "pkg-config, static"
else
    no "pkg-config, static: the examples build"; cat "$tmp/mk2.log"
fi
unset PKG_CONFIG_SYSROOT_DIR PKG_CONFIG_PATH
if command -v cmake > /dev/null 2>&1; then
    for kind in shared static; do
        flag=OFF; [ "$kind" = static ] && flag=ON
        b="$tmp/ex-cmake-$kind"
        if cmake -S "$P/share/braun/examples" -B "$b" -DCMAKE_PREFIX_PATH="$P" -DBRAUN_USE_STATIC_LIBS=$flag \
                -DCMAKE_C_FLAGS="-Wall -Wextra -Wpedantic -Werror" > "$tmp/cm-$kind.log" 2>&1 &&
            cmake --build "$b" >> "$tmp/cm-$kind.log" 2>&1; then
            ok "CMake, $kind: find_package(braun $so) and braun::braun, braun::scene, braun::backends build the examples"
            if [ "$kind" = shared ]; then
                needs_braun "$b/pendulum" && ok "CMake, shared: the programs load libbraun.so.$so" || no "CMake, shared: no libbraun.so"
            else
                ! needs_braun "$b/pendulum" && ! needs_braun "$b/scene" && ok "CMake, static: no libbraun*.so needed" ||
                    no "CMake, static: libbraun*.so in NEEDED"
            fi
            examples_run "$b" "CMake, $kind"
        else
            no "CMake, $kind: the examples build"; tail -20 "$tmp/cm-$kind.log"
        fi
    done
    # The version file (0.x: the same minor version only): MAJOR.MINOR and
    # the exact version are met; the next minor and major, the previous
    # minors and a later patch are not (all derived from BRAUN_VERSION).
    mkdir -p "$tmp/cmv"
    vmaj=${ver%%.*} vmin=$(echo "$ver" | cut -d. -f2) vpat=$(echo "$ver" | cut -d. -f3)
    refuse="$vmaj.$((vmin + 1)) $((vmaj + 1)).0 $vmaj.$vmin.$((vpat + 1))"
    [ "$vmin" -gt 0 ] && refuse="$refuse $vmaj.$((vmin - 1))"
    [ "$vmin" -gt 1 ] && refuse="$refuse $vmaj.0"
    for want in "$so" "$ver" $refuse; do
        printf 'cmake_minimum_required(VERSION 3.13)\nproject(v NONE)\nfind_package(braun %s REQUIRED)\nmessage(STATUS "braun_VERSION: ${braun_VERSION}")\n' "$want" > "$tmp/cmv/CMakeLists.txt"
        if cmake -S "$tmp/cmv" -B "$tmp/cmv/b-$want" -DCMAKE_PREFIX_PATH="$P" > "$tmp/cmv/$want.log" 2>&1; then r=found; else r=refused; fi
        if [ "$want" = "$so" ] || [ "$want" = "$ver" ]; then expect=found; else expect=refused; fi
        [ "$r" = "$expect" ] && ok "CMake: find_package(braun $want) $r" || no "CMake: find_package(braun $want) $r (want $expect)"
    done
    grep -q "braun_VERSION: $ver\$" "$tmp/cmv/$so.log" && ok "CMake: braun_VERSION is $ver" ||
        no "CMake: braun_VERSION: $(grep braun_VERSION "$tmp/cmv/$so.log")"
    # Components (core, scene, backends; also braun, host): each asked
    # for is checked and sets braun_<c>_FOUND; a missing or unknown one
    # fails when required, naming it. find_package(braun COMPONENTS
    # nonexistent host backends) succeeded: the components were ignored.
    cmc() { # cmc NAME ARGS...: find_package(braun ARGS) in a project of its own; its log in $tmp/cmc/NAME.log
        n=$1; shift
        mkdir -p "$tmp/cmc/$n"
        printf 'cmake_minimum_required(VERSION 3.13)\nproject(c NONE)\nfind_package(braun %s)\n' "$*" > "$tmp/cmc/$n/CMakeLists.txt"
        printf 'message(STATUS "braun_FOUND: ${braun_FOUND}")\nforeach(c core braun scene host backends nonexistent)\n  message(STATUS "found ${c}: ${braun_${c}_FOUND}")\nendforeach()\n' >> "$tmp/cmc/$n/CMakeLists.txt"
        cmake -S "$tmp/cmc/$n" -B "$tmp/cmc/$n/b" -DCMAKE_PREFIX_PATH="${cmc_prefix:-$P}" > "$tmp/cmc/$n.raw" 2>&1
        r=$?
        tr '\n' ' ' < "$tmp/cmc/$n.raw" | tr -s ' ' > "$tmp/cmc/$n.log" # (CMake wraps its messages)
        return $r
    }
    if cmc all REQUIRED COMPONENTS core scene backends && grep -q "found core: TRUE" "$tmp/cmc/all.log" &&
       grep -q "found scene: TRUE" "$tmp/cmc/all.log" && grep -q "found backends: TRUE" "$tmp/cmc/all.log"; then
        ok "CMake: find_package(braun REQUIRED COMPONENTS core scene backends) sets braun_core_FOUND, _scene_, _backends_"
    else
        no "CMake: COMPONENTS core scene backends: $(tail -c 400 "$tmp/cmc/all.log")"
    fi
    cmc alias REQUIRED COMPONENTS braun host && grep -q "found host: TRUE" "$tmp/cmc/alias.log" &&
        ok "CMake: COMPONENTS braun host (the other spellings) found" || no "CMake: COMPONENTS braun host: $(tail -c 400 "$tmp/cmc/alias.log")"
    cmc unknown COMPONENTS nonexistent host backends
    if grep -q "braun_FOUND: 0" "$tmp/cmc/unknown.log" && grep -q "unknown component 'nonexistent'" "$tmp/cmc/unknown.log"; then
        ok "CMake: find_package(braun COMPONENTS nonexistent host backends): not found, 'nonexistent' named"
    else
        no "CMake: COMPONENTS nonexistent host backends: $(tail -c 400 "$tmp/cmc/unknown.log")"
    fi
    if cmc unknown-req REQUIRED COMPONENTS nonexistent; then
        no "CMake: find_package(braun REQUIRED COMPONENTS nonexistent) configures"
    elif grep -q "unknown component 'nonexistent'" "$tmp/cmc/unknown-req.log"; then
        ok "CMake: find_package(braun REQUIRED COMPONENTS nonexistent) stops, naming 'nonexistent'"
    else
        no "CMake: REQUIRED COMPONENTS nonexistent: $(tail -c 400 "$tmp/cmc/unknown-req.log")"
    fi
    cmc optional COMPONENTS core OPTIONAL_COMPONENTS nonexistent && grep -q "found nonexistent: FALSE" "$tmp/cmc/optional.log" &&
        ok "CMake: OPTIONAL_COMPONENTS nonexistent: found, braun_nonexistent_FOUND false" ||
        no "CMake: OPTIONAL_COMPONENTS nonexistent: $(tail -c 400 "$tmp/cmc/optional.log")"
    # An installation without the backends' library (a copy of it).
    cp -r "$P" "$tmp/partial"
    rm -f "$tmp/partial/lib/libbraun_backends.so.$ver"
    cmc_prefix=$tmp/partial
    if cmc partial REQUIRED COMPONENTS backends; then
        no "CMake: COMPONENTS backends found without libbraun_backends.so.$ver"
    elif grep -q "component backends: .*libbraun_backends.so.$ver is missing" "$tmp/cmc/partial.log" &&
         cmc partial-scene REQUIRED COMPONENTS scene; then
        ok "CMake: COMPONENTS backends fails naming the missing libbraun_backends.so.$ver; COMPONENTS scene is found"
    else
        no "CMake: a missing backends library: $(tail -c 400 "$tmp/cmc/partial.log")"
    fi
    unset cmc_prefix
else
    no "CMake: cmake not found (Debian: apt-get install cmake)"
fi

# A program compiled for the other precision (float, -DBRAUN_SINGLE) does
# not link with this double library: it named a precision-less
# braun_data_init and then wrote its model and data at the wrong size.
if ${CC:-cc} -std=c99 -DBRAUN_SINGLE "$top/examples/pendulum.c" $flags -o "$tmp/pend-float" 2>"$tmp/prec.log"; then
    no "a float program links with the double library (it must not: its structs differ)"
elif grep -q 'braun_data_init_float\|braun_data_size_float\|braun_model_init_float' "$tmp/prec.log"; then
    ok "a float program against the double library: a link error naming the precision"
else
    no "a float program against the double library: link error without the precision's name"; cat "$tmp/prec.log"
fi
# Every public function and object carries the precision in a float
# build's link names, not only the three every program calls before a step:
# a double program whose one call was braun_check_callbacks linked with the
# float library and passed a Jacobian entry 50 % wrong (BRAUN_OK); a scene
# file's reader linked across precisions too.
cat > "$tmp/chk_only.c" <<'C'
#include <braun_host.h>
static int mass(braun_real t, const braun_real *q, braun_real *M, void *u)
{
    (void)t; (void)q; (void)u;
    M[0] = 1; M[1] = 0; M[2] = 0; M[3] = 1;
    return 0;
}
static int forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q, void *u)
{
    (void)t; (void)q; (void)v; (void)u;
    Q[0] = 0; Q[1] = BRAUN_R(-9.81);
    return 0;
}
/* A_q[0] 3 q0 where Phi = q0^2 + q1^2 - 1 gives 2 q0: 50 % off. */
static int rod(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
               braun_real *b, braun_real *bv, void *u)
{
    (void)t; (void)u;
    if (phi) phi[0] = q[0] * q[0] + q[1] * q[1] - 1;
    if (A) { A[0] = 3 * q[0]; A[1] = 2 * q[1]; }
    if (b) b[0] = 0;
    if (bv) bv[0] = -2 * (v[0] * v[0] + v[1] * v[1]);
    return 0;
}
int main(void)
{
    braun_system sys = {0};
    braun_real q[2] = {1, 0}, v[2] = {0, 1};
    braun_callback_report rep;
    sys.n = 2; sys.m = 1; sys.mass = mass; sys.forces = forces; sys.holonomic = rod;
    return braun_check_callbacks(&sys, 0, q, v, 0, &rep) == BRAUN_ERR_ARGUMENT ? 0 : 1;
}
C
cat > "$tmp/scene_only.c" <<'C'
#include <braun_scene_file.h>
int main(int argc, char **argv)
{
    char err[256];
    braun_scene_file *sf = argc > 1 ? braun_scene_load(argv[1], err, sizeof err) : 0;
    int ok = sf && sf->scene.n == 6;
    braun_scene_free(sf);
    return ok ? 0 : 1;
}
C
hflags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs --static braun-host 2>&1)
for prog in chk_only:braun_check_callbacks scene_only:braun_scene_load; do
    p=${prog%%:*} fn=${prog#*:}
    if ! ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$tmp/$p.c" $hflags -o "$tmp/$p-d" 2>"$tmp/$p.log" ||
       ! LD_LIBRARY_PATH="$L" "$tmp/$p-d" "$P/share/braun/data/four-bar.json"; then
        no "$p: builds and passes against the installed library of its own precision"; cat "$tmp/$p.log"
    elif ${CC:-cc} -std=c99 -DBRAUN_SINGLE "$tmp/$p.c" $hflags -o "$tmp/$p-f" 2>"$tmp/$p.log"; then
        no "a float program whose one call is $fn links with the double library (it must not)"
    elif grep -q "undefined reference to .${fn}_float'" "$tmp/$p.log"; then
        ok "a float program whose one call is $fn, against the double library: undefined ${fn}_float"
    else
        no "a float program whose one call is $fn against the double library: $(head -3 "$tmp/$p.log")"
    fi
done
# The reverse, a double program against the float libraries (BUILD/float,
# mk/float.mk).
B=${BUILD:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
if make -s -C "$top" BUILD="${BUILD:-build}" "${BUILD:-build}/float/libbraun.a" "${BUILD:-build}/float/libbraun_host.a" \
        > "$tmp/fl.log" 2>&1; then
    for prog in chk_only:braun_check_callbacks scene_only:braun_scene_load; do
        p=${prog%%:*} fn=${prog#*:}
        if ${CC:-cc} -std=c99 -I"$P/include" "$tmp/$p.c" "$B/float/libbraun_host.a" "$B/float/libbraun.a" -ljansson -lm \
                -o "$tmp/$p-mix" 2>"$tmp/$p-mix.log"; then
            no "a double program whose one call is $fn links with the float library (it must not)"
        elif grep -q "undefined reference to .${fn}'" "$tmp/$p-mix.log"; then
            ok "a double program whose one call is $fn, against the float library: undefined $fn"
        else
            no "a double program whose one call is $fn against the float library: $(head -3 "$tmp/$p-mix.log")"
        fi
    done
    # No name the double libraries export is defined by the float ones.
    same=$(nm -g --defined-only "$B/float/libbraun.a" "$B/float/libbraun_host.a" 2>/dev/null |
           awk 'NF == 3 { print $3 }' | sort -u | comm -12 - "$tmp/all.exported" | tr '\n' ' ' | cut -c1-300)
    [ -z "$same" ] && ok "the float archives define none of the $(wc -l < "$tmp/all.exported") names the double libraries export" ||
        no "the float archives define the double libraries' names: $same"
else
    no "the float libraries build"; cat "$tmp/fl.log"
fi
# The class: every name the double libraries export is, in a float
# build's headers, NAME_float (a new public function without it would link
# across precisions again).
{ for h in "$P"/include/*.h; do echo "#include \"$h\""; done; sed 's/.*/@ & @/' "$tmp/all.exported"; } > "$tmp/names.c"
untagged=$(${CC:-cc} -std=c99 -DBRAUN_SINGLE -E -P "$tmp/names.c" 2>&1 | sed -n 's/^@ \(.*\) @$/\1/p' |
           grep -v '_float$' | tr '\n' ' ' | cut -c1-300)
n=$(grep -c . "$tmp/all.exported")
if [ -z "$untagged" ] && [ "$n" -gt 80 ]; then
    ok "in a float build each of the $n names the double libraries export is NAME_float"
else
    no "in a float build these public names keep the double's link name: $untagged"
fi
# ------------------------------------------------------------ precision switch
# `make BRAUN_SINGLE=1` on a tree built in double rebuilt nothing and exited
# 0 (braun --version: double), and `make BRAUN_SINGLE=1 install` then
# installed the double libraries and tool with pkg-config files defining
# BRAUN_SINGLE. A scratch tree (-O0: quick) built in double, then installed
# in float.
sw=$tmp/switch F=$tmp/fi/opt/braunf
if make -s -C "$top" BUILD="$sw" OPT=-O0 all > "$tmp/sw.log" 2>&1 &&
   "$sw/bin/braun" --version | grep -q ", double;" &&
   make -s -C "$top" BUILD="$sw" OPT=-O0 BRAUN_SINGLE=1 install PREFIX=/opt/braunf DESTDIR="$tmp/fi" >> "$tmp/sw.log" 2>&1; then
    ok "a tree built in double: make BRAUN_SINGLE=1 install runs"
    v=$("$F/bin/braun" --version 2>&1)
    case "$v" in *", float;"*) ok "the installed tool is float ($v)" ;; *) no "the installed tool: $v (want float)" ;; esac
    bad=""
    for f in lib/libbraun.a:braun_step lib/libbraun_host.a:braun_scene_load lib/libbraun_backends.a:braun_linsolver_select \
             lib/libbraun.so.$ver:braun_step lib/libbraun_host.so.$ver:braun_scene_load; do
        lib=${f%%:*} fn=${f#*:} o=""
        case $lib in *.so.*) o=-D ;; esac
        syms=$(nm $o -g --defined-only "$F/$lib" 2>/dev/null | awk '{ sub(/@.*/, "", $3); print $3 }')
        echo "$syms" | grep -qx "${fn}_float" && ! echo "$syms" | grep -qx "$fn" || bad="$bad $lib"
    done
    [ -z "$bad" ] && ok "the installed archives and shared libraries are float (braun_step_float, ...; no double names)" ||
        no "installed libraries not float:$bad"
    grep -q "^Cflags:.*-DBRAUN_SINGLE" "$F/lib/pkgconfig/braun.pc" && grep -q BRAUN_SINGLE "$F/lib/cmake/braun/braunConfig.cmake" &&
        ok "the float installation's braun.pc and braunConfig.cmake define BRAUN_SINGLE" ||
        no "the float installation's braun.pc or braunConfig.cmake lacks BRAUN_SINGLE"
    ff=$(PKG_CONFIG_SYSROOT_DIR="$tmp/fi" PKG_CONFIG_PATH="$F/lib/pkgconfig" pkg-config --cflags --libs braun 2>&1)
    if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$top/examples/pendulum.c" $ff -o "$tmp/pend-f" 2> "$tmp/pf.log" &&
       out=$(LD_LIBRARY_PATH="$F/lib" "$tmp/pend-f") && case "$out" in "t = 10 "*) true ;; *) false ;; esac; then
        ok "the README example builds through the float braun.pc and runs ($out)"
    else
        no "the README example through the float braun.pc: $(cat "$tmp/pf.log") $out"
    fi
    if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$tmp/ver.c" $ff -o "$tmp/ver-f" 2> "$tmp/vf.log" &&
       out=$(LD_LIBRARY_PATH="$F/lib" "$tmp/ver-f") && [ "$out" = "$ver float $ver float" ]; then
        ok "a program on the float libbraun.so: braun_version() $ver, braun_precision() float"
    else
        no "braun_version()/braun_precision() on the float libbraun.so: '$out' $(cat "$tmp/vf.log")"
    fi
    # The examples against the float installation: driven_crank's double
    # bounds (3e-12, 5e-14) made it exit 1 there, with no word.
    EP=$F
    ref_q=$("$F/bin/braun" run four-bar.json --dt 1e-3 --t-end 10 2>&1 | sed -n 's/^  "final_q": \[\(.*\)\],$/\1/p')
    cp -r "$F/share/braun/examples" "$tmp/ex-float-pc"
    if PKG_CONFIG_SYSROOT_DIR="$tmp/fi" PKG_CONFIG_PATH="$F/lib/pkgconfig" make -s -C "$tmp/ex-float-pc" \
            CFLAGS="-std=c99 -O2 -Wall -Wextra -Wpedantic -Werror" > "$tmp/mkf.log" 2>&1; then
        ok "float, pkg-config, shared: the examples build warning-free"
        export LD_LIBRARY_PATH="$F/lib"
        examples_run "$tmp/ex-float-pc" "float, pkg-config, shared"
        unset LD_LIBRARY_PATH
    else
        no "float, pkg-config, shared: the examples build"; cat "$tmp/mkf.log"
    fi
    if command -v cmake > /dev/null 2>&1; then
        b="$tmp/ex-float-cmake"
        if cmake -S "$F/share/braun/examples" -B "$b" -DCMAKE_PREFIX_PATH="$F" -DBRAUN_USE_STATIC_LIBS=ON \
                -DCMAKE_C_FLAGS="-Wall -Wextra -Wpedantic -Werror" > "$tmp/cmf.log" 2>&1 &&
           cmake --build "$b" >> "$tmp/cmf.log" 2>&1; then
            ok "float, CMake, static: the examples build warning-free"
            examples_run "$b" "float, CMake, static"
        else
            no "float, CMake, static: the examples build"; tail -20 "$tmp/cmf.log"
        fi
    fi
    # A tree whose objects its stamp does not describe (simulated: the
    # float tree's stamp says double, older than the objects): install
    # refuses before copying anything, naming make clean.
    echo double > "$sw/precision" && touch -t 200001010000 "$sw/precision"
    if make -s -C "$top" BUILD="$sw" OPT=-O0 install PREFIX=/opt/braunm DESTDIR="$tmp/mixed" > "$tmp/mx.log" 2>&1; then
        no "make install of float objects as double: installed"
    elif grep -q "libbraun.a is built in float, this install is double.*make clean" "$tmp/mx.log" &&
         [ -z "$(find "$tmp/mixed" -type f 2>/dev/null)" ]; then
        ok "make install refuses float objects for a double install, installs nothing, names make clean"
    else
        no "make install of float objects as double: $(cat "$tmp/mx.log")"; find "$tmp/mixed" -type f 2>/dev/null | head -3
    fi
    # And back: the objects follow the precision asked for.
    rm -f "$sw/precision"
    if make -s -C "$top" BUILD="$sw" OPT=-O0 "$sw/libbraun.a" > "$tmp/sw3.log" 2>&1 &&
       nm -g --defined-only "$sw/libbraun.a" | grep -q " braun_step$"; then
        ok "make (double) after the float build rebuilds libbraun.a in double"
    else
        no "make (double) after the float build: libbraun.a not double"; cat "$tmp/sw3.log"
    fi
else
    no "a tree built in double: make BRAUN_SINGLE=1 install"; tail -20 "$tmp/sw.log"
fi
# ------------------------------------------------------------ a moved installation
# The .pc files said prefix=/opt/braun: an installation copied elsewhere
# (a relocated package, a staging directory used as it is) gave
# -I/opt/braun/include. Now they find it from their own place.
M=$tmp/moved/somewhere/else
mkdir -p "$(dirname "$M")" && cp -a "$P" "$M"
if grep -q "/opt/braun" "$M"/lib/pkgconfig/*.pc; then
    no "the installed .pc files name the PREFIX: $(grep -h "/opt/braun" "$M"/lib/pkgconfig/*.pc | head -2)"
else
    ok "the installed .pc files name no PREFIX (prefix=\${pcfiledir}/../..)"
fi
mflags=$(PKG_CONFIG_PATH="$M/lib/pkgconfig" pkg-config --cflags --libs braun-backends 2>&1)
mlib=$(PKG_CONFIG_PATH="$M/lib/pkgconfig" pkg-config --variable=libdir braun 2>&1)
if [ "$(cd "$mlib" 2>/dev/null && pwd -P)" = "$(cd "$M/lib" && pwd -P)" ] &&
   ${CC:-cc} -std=c99 -Wall -Wextra -Werror "$tmp/sel.c" $mflags -o "$tmp/sel-moved" 2> "$tmp/mv.log" &&
   out=$(LD_LIBRARY_PATH="$M/lib" "$tmp/sel-moved") && [ "$out" = "${sel_want:-}" ]; then
    ok "a moved installation: pkg-config gives its own paths; a backends program builds and runs ($out)"
else
    no "a moved installation: libdir $mlib, flags $mflags, $(cat "$tmp/mv.log") $out"
fi
# Its examples' Makefile, STATIC=1 without LIBDIR: the archives found through
# pkg-config --variable=libdir.
cp -r "$M/share/braun/examples" "$tmp/ex-moved"
if PKG_CONFIG_PATH="$M/lib/pkgconfig" make -s -C "$tmp/ex-moved" STATIC=1 \
        CFLAGS="-std=c99 -O2 -Wall -Wextra -Wpedantic -Werror" > "$tmp/mvx.log" 2>&1 &&
   out=$("$tmp/ex-moved/pendulum") && case "$out" in "t = 10 "*) true ;; *) false ;; esac; then
    ok "a moved installation: the examples build with STATIC=1 alone and run ($out)"
else
    no "a moved installation: the examples with STATIC=1: $(tail -5 "$tmp/mvx.log") $out"
fi

# PREFIX and DESTDIR with spaces: installed there and removed again, no stray
# directories in the tree (the unquoted paths were split into words).
sp="$tmp/st age"
if make -s -C "$top" install BUILD="${BUILD:-build}" PREFIX="/opt/my braun" DESTDIR="$sp" >"$tmp/sp.log" 2>&1 &&
   [ -f "$sp/opt/my braun/lib/libbraun.a" ] && [ -f "$sp/opt/my braun/include/braun.h" ] &&
   [ -f "$sp/opt/my braun/lib/cmake/braun/braunConfig.cmake" ] && [ -f "$sp/opt/my braun/bin/braun" ]; then
    ok "make install into a PREFIX and DESTDIR with spaces"
else
    no "make install into a PREFIX and DESTDIR with spaces"; cat "$tmp/sp.log"
fi
if make -s -C "$top" uninstall BUILD="${BUILD:-build}" PREFIX="/opt/my braun" DESTDIR="$sp" >"$tmp/su.log" 2>&1 &&
   [ -z "$(find "$sp" -type f)" ] && [ ! -e "$top/age" ] && [ ! -e "$top/braun" ]; then
    ok "make uninstall from a PREFIX and DESTDIR with spaces removes every file"
else
    no "make uninstall from a PREFIX and DESTDIR with spaces"; cat "$tmp/su.log"; find "$sp" -type f
fi

echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
