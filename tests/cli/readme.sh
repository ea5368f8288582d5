#!/bin/sh
# The README as a new user follows it (issue 15):
#   sh tests/cli/readme.sh path/to/braun
# From a directory outside the repository, with braun's directory on PATH
# as the README says: every `braun ...` line of the README runs with exit
# status 0; the SVG and the HTML animation it writes are well-formed and
# show the mechanism, the point's path is drawn; the headline figures are
# what the quoted commands give; every make target the README names exists
# (make -n); every file it names exists; its install commands are the ones
# tests/cli/install.sh runs (which builds and runs them: not repeated here).
# docs/scene-format.md's C program compiles with -Werror and prints what
# the text quotes. tests/cli/plot.sh checks the pictures in depth. "ok - NAME" / "not ok -
# NAME" / "ok - NAME # SKIP WHY" and "N passed, M failed, K skipped".
BRAUN=${1:?usage: sh tests/cli/readme.sh path/to/braun}
case $BRAUN in /*) ;; *) BRAUN=$(pwd)/$BRAUN ;; esac
TOP=$(cd "$(dirname "$0")/../.." && pwd)
README=$TOP/README.md
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-readme.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { name=$1; shift; if "$@"; then ok "$name"; else not_ok "$name"; fi; }
have() { command -v "$1" > /dev/null 2>&1; }

# ------------------------------------------------------------------ braun lines
# The README's command lines: code lines (indented) that start with
# "braun ", without their trailing "# comment".
sed -n 's/^ \{4,\}\(braun .*\)$/\1/p' "$README" | sed 's/  *#.*$//; s/ *$//' > "$TMP/commands"
n=$(wc -l < "$TMP/commands" | tr -d ' ')
check "the README shows braun commands ($n)" [ "$n" -ge 10 ]
for cmd in list run plot check gen gen-c --help --version; do
    check "the README runs 'braun $cmd'" grep -q "^braun $cmd\( \|$\)" "$TMP/commands"
done

mkdir "$TMP/user" && cd "$TMP/user" || exit 1
PATH=$(dirname "$BRAUN"):$PATH
export PATH
[ "$(command -v braun)" = "$BRAUN" ] && ok "braun on PATH is the build's ($BRAUN)" ||
    not_ok "braun on PATH is $(command -v braun), not $BRAUN"
i=0
while IFS= read -r cmd; do
    i=$((i + 1))
    sh -c "$cmd" > "out.$i" 2> "err.$i" < /dev/null; rc=$?
    if [ "$rc" -eq 0 ]; then
        ok "from $TMP/user: $cmd"
    else
        not_ok "from $TMP/user: $cmd (exit $rc)" "$(head -c 300 "err.$i")"
    fi
done < "$TMP/commands"

# What `run` prints on success, as the README says.
i=$(grep -n "^braun run four-bar --dt 1e-2 --t-end 10 --out four-bar.csv$" "$TMP/commands" | cut -d: -f1)
check "run prints a JSON summary with \"status\": \"BRAUN_OK\" and the error maxima" sh -c '
    [ -n "$1" ] && grep -q "^  \"status\": \"BRAUN_OK\",$" "out.$1" &&
    grep -q "^  \"max_position_constraint_error\": " "out.$1" && grep -q "^  \"cpu_s\": " "out.$1" &&
    [ ! -s "err.$1" ]' sh "$i"
check "... and its CSV: a header with units and 1001 rows" sh -c '
    head -n 1 four-bar.csv | grep -q "^t \[s\]," && [ "$(wc -l < four-bar.csv)" -eq 1002 ]'

# ------------------------------------------------------------------ pictures
check "four-bar.svg, four-bar.html and crank-path.svg were written" \
    sh -c '[ -s four-bar.svg ] && [ -s four-bar.html ] && [ -s crank-path.svg ]'
if have xmllint; then
    check "four-bar.svg is well-formed XML" xmllint --noout four-bar.svg
    check "crank-path.svg is well-formed XML" xmllint --noout crank-path.svg
    # The page's drawing, as plot.sh cuts it out: one inline SVG.
    awk '/<svg/ { on = 1 } on { print } /<\/svg>/ { on = 0 }' four-bar.html > page.svg
    check "the animation's inline SVG is well-formed XML" xmllint --noout page.svg
else
    skip "the SVG files are well-formed XML" "xmllint not found (libxml2-utils)"
fi
check "four-bar.svg draws 12 configurations" sh -c '[ "$(grep -c "<g class=\"frame\"" four-bar.svg)" -eq 12 ]'
check "four-bar.html is one page: a script, play/pause, a slider, 300+ configurations" sh -c '
    [ "$(grep -c "<script" four-bar.html)" -eq 1 ] && grep -q "<button id=\"play\"" four-bar.html &&
    grep -q "<input id=\"slider\" type=\"range\"" four-bar.html &&
    [ "$(grep -c "<g data-t=" four-bar.html)" -ge 300 ] && grep -q "</html>" four-bar.html'
# The path of crank.A, the crank's end: a polyline of many points on an
# arc of a circle (the crank turns about its pivot). The circle through
# three of them; every point on it to 0.5 % (the SVG's 2 decimals).
check "crank-path.svg draws the path of crank.A: an arc of a circle" awk '
    /<polyline fill="none" stroke="#d62728"/ {
        s = $0; sub(/.*points="/, "", s); sub(/".*/, "", s)
        n = split(s, p, " ")
        if (n < 100) exit 1
        for (k = 1; k <= n; k++) { split(p[k], c, ","); x[k] = c[1]; y[k] = c[2] }
        a = 1; b = int(n / 3); e = int(2 * n / 3)
        d = 2 * (x[a] * (y[b] - y[e]) + x[b] * (y[e] - y[a]) + x[e] * (y[a] - y[b]))
        if (d == 0) exit 1
        sa = x[a] ^ 2 + y[a] ^ 2; sb = x[b] ^ 2 + y[b] ^ 2; se = x[e] ^ 2 + y[e] ^ 2
        ux = (sa * (y[b] - y[e]) + sb * (y[e] - y[a]) + se * (y[a] - y[b])) / d
        uy = (sa * (x[e] - x[b]) + sb * (x[a] - x[e]) + se * (x[b] - x[a])) / d
        r = sqrt((x[a] - ux) ^ 2 + (y[a] - uy) ^ 2)
        if (r < 10) exit 1
        for (k = 1; k <= n; k++) { dd = sqrt((x[k] - ux) ^ 2 + (y[k] - uy) ^ 2)
            if (dd < 0.995 * r || dd > 1.005 * r) exit 1 }
        found = 1 }
    END { exit !found }' crank-path.svg

# ------------------------------------------------------------------ the headline
# The figures the README quotes, against the commands it quotes (the paper
# test, tests/test_paper.c, bounds them too).
figure() { sed -n "s/^  \"$1\": \([^,]*\),*$/\1/p"; }
w=$(braun run four-bar --dt 1e-2 --t-end 1000 --out headline.csv --every 10 | figure max_point_error)
wo=$(braun run four-bar --dt 1e-2 --t-end 1000 --corrections position,velocity | figure max_point_error)
check "headline: joint 3 within the README's 3.1e-4 m with the energy correction (got $w)" sh -c '
    grep -q "within \*\*3.1e-4 m\*\*" "$2" && awk -v a="$1" "BEGIN { exit !(a >= 3.1e-4 && a < 3.2e-4) }"' sh "$w" "$README"
check "headline: the README's 1.29 m without it (got $wo)" sh -c '
    grep -q "\*\*1.29 m\*\* off" "$2" && awk -v a="$1" "BEGIN { exit !(a >= 1.285 && a < 1.295) }"' sh "$wo" "$README"
# The cranks' turns: the angle of joint 1 about the pivot (0, 0), unwrapped
# (every 10 steps: about 20 samples a turn).
turns=$(awk -F, 'NR > 1 { a = atan2($3, $2); if (NR > 2) { d = a - p
        if (d > 3.14159265) d -= 6.28318531; if (d < -3.14159265) d += 6.28318531; s += d }
        p = a } END { printf "%.0f", (s < 0 ? -s : s) / 6.28318531 }' headline.csv)
check "headline: the README's 515 turns (got $turns)" sh -c '
    grep -q "515 turns of its cranks" "$2" && [ "$1" = 515 ]' sh "$turns" "$README"
check "... of joint 1, the first column pair of the CSV" sh -c 'head -n 1 headline.csv | grep -q "^t \[s\],J1.x \[m\],J1.y \[m\],"'


# ------------------------------------------------------------------ make targets
# Every `make TARGET` the README names (options and -C DIR aside) exists.
grep -o '`make[^`]*`' "$README" | tr -d '`' | awk '{
        for (k = 2; k <= NF; k++) { w = $k
            if (w ~ /^-[CfI]$/) { k++; continue }
            if (w ~ /^-/ || w ~ /=/) continue
            if (w ~ /^[a-z][a-z0-9-]*$/) print w
            break } }' | sort -u > "$TMP/targets"
sed -n 's/^ \{4,\}make \([a-z][a-z0-9-]*\).*/\1/p' "$README" >> "$TMP/targets"
sort -u "$TMP/targets" -o "$TMP/targets"
nt=$(wc -l < "$TMP/targets" | tr -d ' ')
check "the README names make targets ($nt)" [ "$nt" -ge 25 ]
if make -n -C "$TOP" BUILD="${BUILD:-build}" $(cat "$TMP/targets") > "$TMP/make-n.log" 2>&1; then
    ok "make -n knows every target the README names: $(tr '\n' ' ' < "$TMP/targets")"
else
    # name the ones it does not know
    missing=""
    for t in $(cat "$TMP/targets"); do
        make -n -C "$TOP" BUILD="${BUILD:-build}" "$t" > /dev/null 2>&1 || missing="$missing $t"
    done
    not_ok "make -n: targets the README names do not exist:$missing" "$(tail -n 3 "$TMP/make-n.log")"
fi

# ------------------------------------------------------------------ files
# (a path in the repository: not the tail of another path, /tmp/examples/...)
grep -o '\(^\|[^A-Za-z0-9_./-]\)\(docs\|examples\|data\|tests\|tools\|include\|src\|mk\)/[A-Za-z0-9_./-]*[A-Za-z0-9_]' "$README" |
    sed 's|^[^a-z]||' | sort -u > "$TMP/files"
missing=""
for f in $(cat "$TMP/files"); do [ -e "$TOP/$f" ] || missing="$missing $f"; done
check "every file the README names exists ($(wc -l < "$TMP/files" | tr -d ' ') names)${missing:+: missing$missing}" \
    [ -z "$missing" ]
check "the README gives the paper's DOI 10.1115/1.4005572" grep -q "10\.1115/1\.4005572" "$README"

# ------------------------------------------------------------------ install
# The README's install and build commands are the ones install.sh runs:
# the same options and flags in both.
for frag in "make install" "PREFIX=/opt/braun DESTDIR=" "PKG_CONFIG_SYSROOT_DIR=" "PKG_CONFIG_PATH=" \
    "pkg-config --cflags --libs --static braun" "-std=c99" "examples/pendulum.c" "LD_LIBRARY_PATH=" \
    "cmake -S " "share/braun/examples" "-DCMAKE_PREFIX_PATH=" "cmake --build " \
    "-DBRAUN_USE_STATIC_LIBS=" "STATIC=1 LIBDIR="; do
    if grep -qF -- "$frag" "$README" && grep -qF -- "$frag" "$TOP/tests/cli/install.sh"; then
        ok "README and tests/cli/install.sh both use: $frag"
    else
        not_ok "README and tests/cli/install.sh disagree on: $frag"
    fi
done
check "the README's example output is what install.sh expects of pendulum ('t = 10 ')" sh -c '
    grep -q "./pendulum .*# t = 10 " "$1" && grep -q "\"0:t = 10 \"" "$2"' sh "$README" "$TOP/tests/cli/install.sh"

# ------------------------------------------------------------------ docs' C
# docs/scene-format.md's "Scenes in C" is a whole program: it compiles
# with -Wall -Wextra -Wpedantic -Werror against the build's libbraun.a and
# prints what the docs say (its positional initialisers stopped early:
# -Wmissing-field-initializers, and its statements stood at file scope).
LIB=$(dirname "$(dirname "$BRAUN")")/libbraun.a
awk '/^## Scenes in C/ { on = 1 } on && /^```c$/ { code = 1; next } code && /^```$/ { exit } code' \
    "$TOP/docs/scene-format.md" > "$TMP/scene_c.c"
if [ ! -f "$LIB" ] || ! braun --version | grep -q ", double;"; then
    skip "docs/scene-format.md's Scenes in C compiles and runs" "no double libbraun.a beside $BRAUN"
elif ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -I"$TOP/include/core" "$TMP/scene_c.c" "$LIB" -lm \
        -o "$TMP/scene_c" 2> "$TMP/scene_c.err"; then
    out=$("$TMP/scene_c" 2>&1)
    # The figure the text before it quotes (over two lines: joined first).
    want=$(awk '/^## Scenes in C/ { on = 1 } on && /^```c$/ { exit } on' "$TOP/docs/scene-format.md" |
        tr '\n' ' ' | sed -n 's/.*ends at, `\(t = 10  q = ([^`]*)\)`.*/\1/p' | sed 's/( /(/; s/, */, /')
    check "docs/scene-format.md's Scenes in C compiles -Werror and prints what the docs quote ($out)" \
        sh -c '[ -n "$2" ] && [ "$1" = "$2" ]' sh "$out" "$want"
else
    not_ok "docs/scene-format.md's Scenes in C compiles with -Wall -Wextra -Wpedantic -Werror" \
        "$(head -c 300 "$TMP/scene_c.err")"
fi

# The same program in float, -Wconversion: its literals are BRAUN_R(x)
# (9.81 and 1e-3 were doubles converted to float, which -Wconversion flags).
if ${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Wconversion -Werror -DBRAUN_SINGLE -I"$TOP/include/core" \
        -c "$TMP/scene_c.c" -o "$TMP/scene_c_float.o" 2> "$TMP/scene_cf.err"; then
    ok "docs/scene-format.md's Scenes in C compiles in float with -Wconversion -Werror"
else
    not_ok "docs/scene-format.md's Scenes in C in float with -Wconversion" "$(head -c 300 "$TMP/scene_cf.err")"
fi

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
