#!/bin/sh
# The ABI of the public headers (tools/abi-record: every public type's
# size and alignment, every public function's prototype, double and
# float) is the one recorded for this version's soname,
# tests/abi/abi-MAJOR.MINOR.txt. In 0.x every minor version may change the
# ABI and a patch version may not (CHANGELOG.md): a change here without a
# new minor version is what let a program built against 0.1.0 load the
# next libbraun.so.0.1 and pass every struct at the wrong size
# (braun_model 136 -> 144 bytes, braun_data 208 -> 216, braun_linsolver
# 128 -> 160). After a new minor version: make abi-record. abi-0.1.txt is
# 0.1.0's (the headers of commit 4e063e4), kept to compare with.
# Usage: sh tests/abi/check.sh   (from the top directory or anywhere)
set -u
top=$(cd "$(dirname "$0")/../.." && pwd)
pass=0; fail=0; skip=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
no() { echo "not ok - $1"; fail=$((fail + 1)); }
skipped() { echo "ok - $1 # SKIP $2"; skip=$((skip + 1)); }
ver=$(sed -n 's/^#define BRAUN_VERSION "\(.*\)"/\1/p' "$top/include/core/braun.h")
so=$(echo "$ver" | cut -d. -f1-2)
rec=$top/tests/abi/abi-$so.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ "$(uname -m)" != x86_64 ] || ! command -v gcc > /dev/null 2>&1; then
    skipped "the public ABI is libbraun.so.$so's record" "the records are of x86-64, made with gcc"
elif [ ! -f "$rec" ]; then
    no "no record of libbraun.so.$so's ABI: tests/abi/abi-$so.txt (make abi-record, once the version is right)"
elif ! CC=gcc "$top/tools/abi-record" "$top/include/core" "$top/include/host" > "$tmp/now" 2> "$tmp/err"; then
    no "tools/abi-record: $(head -5 "$tmp/err")"
elif cmp -s "$rec" "$tmp/now"; then
    ok "the public ABI is libbraun.so.$so's record ($(grep -c ' size ' "$rec") type sizes, $(grep -c ' proto ' "$rec") prototypes, double and float)"
else
    no "the public ABI is not libbraun.so.$so's record, yet BRAUN_VERSION is still $ver: a new minor version is due (0.x), then make abi-record. Differences (< record, > headers):"
    diff "$rec" "$tmp/now" | grep '^[<>]' | head -20 | sed 's/^/#   /'
fi
echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
