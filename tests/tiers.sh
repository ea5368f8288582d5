#!/bin/sh
# The two tiers stay apart (docs/architecture.md): no file of the core tier
# (src/core, include/core) includes <stdio.h> or another I/O or process
# header, calls an allocator or stdio, or includes a host header; the host
# and firmware builds of libbraun.a are made of the same objects.
# Usage: sh tests/tiers.sh [BUILD]
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" when no
# firmware library was built to compare) and "N passed, M failed, K skipped".
set -u
build=${1:-build}
pass=0; fail=0; skipped=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
skip() { echo "ok - $1 # SKIP $2"; skipped=$((skipped + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); [ -z "${2:-}" ] || echo "$2" | sed 's/^/#   /'; }

core=$(find src/core include/core -name '*.[ch]' | sort)
[ -n "$core" ] && ok "the core tier has $(echo "$core" | wc -l) files" || no "no core files found"

# Comments stripped (a comment may name stdio), then the forbidden spellings.
strip() { sed -e 's://.*$::' "$1" | awk 'BEGIN{c=0} { line=$0; out="";
    while (length(line)) { if (c) { i=index(line,"*/"); if (!i) { line=""; break } line=substr(line,i+2); c=0 }
      else { i=index(line,"/*"); if (!i) { out=out line; break } out=out substr(line,1,i-1); line=substr(line,i+2); c=1 } }
    print out }'; }
hits_inc=""; hits_alloc=""; hits_io=""; hits_host=""
for f in $core; do
    body=$(strip "$f")
    echo "$body" | grep -qE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<(stdio|stdlib|unistd|time|signal|errno|fcntl|pthread)\.h>' &&
        hits_inc="$hits_inc $f"
    echo "$body" | grep -qE '\b(malloc|calloc|realloc|free|aligned_alloc|alloca)[[:space:]]*\(' && hits_alloc="$hits_alloc $f"
    echo "$body" | grep -qE '\b(printf|fprintf|sprintf|snprintf|vsnprintf|puts|fputs|fopen|fwrite|fread|exit|abort|getenv)[[:space:]]*\(' &&
        hits_io="$hits_io $f"
    for h in include/host/*.h; do
        echo "$body" | grep -qE "#[[:space:]]*include[[:space:]]*\"$(basename "$h")\"" && hits_host="$hits_host $f:$(basename "$h")"
    done
done
[ -z "$hits_inc" ] && ok "no core file includes <stdio.h>, <stdlib.h> or another OS header" || no "core files include OS headers:$hits_inc"
[ -z "$hits_alloc" ] && ok "no core file calls an allocator" || no "core files call an allocator:$hits_alloc"
[ -z "$hits_io" ] && ok "no core file calls stdio, exit, abort or getenv" || no "core files do I/O:$hits_io"
[ -z "$hits_host" ] && ok "no core file includes a host header" || no "core files include host headers:$hits_host"

# The archive: one object per core source, nothing else.
if [ -f "$build/libbraun.a" ]; then
    want=$(for f in $(find src/core -name '*.c'); do basename "$f" .c; done | sort | tr '\n' ' ')
    have=$(ar t "$build/libbraun.a" | sed 's/\.o$//' | sort | tr '\n' ' ')
    if [ -n "$want" ] && [ "$want" = "$have" ]; then ok "libbraun.a holds exactly the core tier's objects"
    else no "libbraun.a objects differ from src/core" "want: $want
have: $have"; fi
    nfw=0
    for fw in "$build"/firmware/*/libbraun.a; do
        [ -f "$fw" ] || continue
        nfw=$((nfw + 1))
        fwhave=$(ar t "$fw" | sed 's/\.o$//' | sort | tr '\n' ' ')
        if [ "$fwhave" = "$have" ]; then ok "$fw holds the same objects as the host libbraun.a"
        else no "$fw differs from the host libbraun.a" "$fwhave"; fi
    done
    # make test builds them (firmware-test runs first); alone, there may be none.
    [ "$nfw" -gt 0 ] || skip "the firmware libbraun.a hold the same objects as the host one" \
        "no $build/firmware/*/libbraun.a built (make firmware)"
else
    no "$build/libbraun.a exists"
fi
# No global mutable state (docs/api.md, "Threads": a braun_data per thread
# needs no lock): no object of the three archives lives in a writable
# section (.data, .bss, thread-local, common); constant tables with
# pointers are in .data.rel.ro, written once by the loader.
for a in libbraun libbraun_host libbraun_backends; do
    [ -f "$build/$a.a" ] || { no "$build/$a.a exists"; continue; }
    w=$(objdump -t "$build/$a.a" | awk '$0 ~ / O / && $0 ~ / (\.data|\.bss|\.tdata|\.tbss|\*COM\*)([. \t]|$)/ &&
                                        $0 !~ /\.data\.rel\.ro/ { print $NF }' | sort -u | tr '\n' ' ')
    [ -z "$w" ] && ok "$a.a has no writable static data (no global mutable state)" ||
        no "$a.a has writable static data: $w"
done
echo "$pass passed, $fail failed, $skipped skipped"
[ "$fail" -eq 0 ]
