#!/bin/sh
# make install into a temporary DESTDIR, then build the README example
# against it through pkg-config and run it. Prints "ok - NAME" /
# "not ok - NAME" and "N passed, M failed, 0 skipped".
set -u
top=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
# The build under test (make test passes its BUILD).
if make -s -C "$top" install BUILD="${BUILD:-build}" PREFIX=/opt/braun DESTDIR="$tmp" >"$tmp/log" 2>&1; then ok "make install"; else no "make install"; cat "$tmp/log"; fi
for f in include/braun.h include/braun_models.h include/braun_scene.h include/braun_host.h include/braun_reference.h include/braun_scene_file.h lib/libbraun.a lib/libbraun_host.a lib/pkgconfig/braun.pc lib/pkgconfig/braun-host.pc bin/braun; do
    [ -f "$tmp/opt/braun/$f" ] && ok "installed $f" || no "installed $f"
done
pc="$tmp/opt/braun/lib/pkgconfig"
flags=$(PKG_CONFIG_SYSROOT_DIR="$tmp" PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs --static braun 2>&1)
case "$flags" in *"-lbraun"*) ok "pkg-config --libs braun" ;; *) no "pkg-config --libs braun: $flags" ;; esac
if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror "$top/examples/pendulum.c" $flags -o "$tmp/pendulum" 2>"$tmp/cc.log"; then
    ok "README example compiles warning-free against the installed library"
    out=$("$tmp/pendulum"); rc=$?
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
    out=$("$tmp/sel")
    case "$out" in "$want") ok "a program links the installed backends (auto for a dense n = 100: $out)" ;;
    *) no "backend selection output: $out" ;; esac
else
    no "a program links the installed backends"; cat "$tmp/cc2.log"
fi
echo "$pass passed, $fail failed, 0 skipped"
[ "$fail" -eq 0 ]
