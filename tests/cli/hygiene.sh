#!/bin/sh
# Input hygiene (issue 12, item 7): sh tests/cli/hygiene.sh path/to/braun
# (run from the top of the tree). Hostile names and paths in gen-c's output,
# the loader's time against the scene's size, FIFOs and other special files,
# numbers the simulation cannot work with, messages that name what failed,
# outputs that would overwrite each other or the input. Every case here
# failed before the fix. Prints "ok - NAME" / "not ok - NAME" and a closing
# "N passed, M failed".
BRAUN=${1:?usage: sh tests/cli/hygiene.sh path/to/braun}
CC=${CC:-cc}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-hygiene.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0

ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { # check NAME COMMAND...: passes when COMMAND succeeds
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
# expect NAME RC PATTERN ARGS...: braun ARGS exits RC within 20 s, prints
# nothing on stdout (unless RC is 0) and one stderr line matching PATTERN
# (grep -E; empty: nothing on stderr).
expect() {
    name=$1 want=$2 pattern=$3; shift 3
    timeout 20 "$BRAUN" "$@" > "$TMP/x.out" 2> "$TMP/x.err" < /dev/null; rc=$?
    lines=$(wc -l < "$TMP/x.err" | tr -d ' ')
    if [ "$rc" -ne "$want" ]; then
        not_ok "$name" "exit $rc (want $want), stderr: $(head -c 300 "$TMP/x.err")"
    elif [ -n "$pattern" ] && { [ "$lines" -ne 1 ] || ! grep -Eq -- "$pattern" "$TMP/x.err"; }; then
        not_ok "$name" "stderr ($lines lines): $(head -c 300 "$TMP/x.err")"
    elif [ -z "$pattern" ] && [ -s "$TMP/x.err" ]; then
        not_ok "$name" "stderr: $(head -c 300 "$TMP/x.err")"
    elif [ "$want" -ne 0 ] && [ -s "$TMP/x.out" ]; then
        not_ok "$name" "stdout not empty"
    else
        ok "$name"
    fi
}
now_ms() { date +%s%N | cut -c1-13; } # milliseconds (GNU date)

# ------------------------------------------------------------ gen-c: texts
# Every text of the scene lands inside a comment: the output compiles with
# -Werror (trigraphs on) under gcc and clang, defines nothing but the
# scene's own symbols, and is printable ASCII with lines < 4096 characters.
cat > "$TMP/hostile.json" <<'EOF'
{"name": "x*/ int evil_name; /*",
 "description": "a */ int evil_desc; /* ??/ ??= \\ /* \n*/ int evil_nl; /* caf\u00e9 \u202e\u2028 \u0001 \\",
 "bodies": [{"name": "b*/ int evil_body; /*", "type": "particle", "mass": 1, "position": [1, 0]},
            {"name": "??/", "type": "particle", "mass": 1, "position": [2, 0]}],
 "joints": [{"name": "j\\", "type": "distance", "a": [0, 0], "b": "b*/ int evil_body; /*"},
            {"name": "\n*/ int evil_joint; //", "type": "distance", "a": "b*/ int evil_body; /*", "b": "??/"}],
 "effects": [{"name": "g\u00fc\u00df */ int evil_effect; /* \ud83d\ude00", "type": "gravity", "g": [0, -9.81]}]}
EOF
mkdir -p "$TMP/src*" && cp "$TMP/hostile.json" "$TMP/src*/h.json"
"$BRAUN" gen-c "$TMP/src*/h.json" --symbol hostile -o "$TMP/hostile.c" 2> "$TMP/gc.err" || rm -f "$TMP/hostile.c"
for cc in gcc clang; do
    command -v $cc > /dev/null 2>&1 || continue
    tri=; [ $cc = gcc ] && tri=-trigraphs
    check "gen-c hostile output compiles with $cc -std=c99 -Wall -Wextra -Wpedantic -Werror $tri" \
        $cc -std=c99 $tri -Wall -Wextra -Wpedantic -Werror -Iinclude/core -c "$TMP/hostile.c" -o "$TMP/hostile-$cc.o"
done
[ -f "$TMP/hostile-gcc.o" ] || $CC -std=c99 -Iinclude/core -c "$TMP/hostile.c" -o "$TMP/hostile-gcc.o" 2> /dev/null
check "gen-c hostile output: no injected definition (nm shows no evil_*)" sh -c '
    [ -f "$1" ] && ! nm "$1" | grep -q evil_' sh "$TMP/hostile-gcc.o"
check "gen-c hostile output: printable ASCII only" sh -c '! LC_ALL=C grep -q "[^ -~]" "$1"' sh "$TMP/hostile.c"
check "gen-c hostile output: no trigraph, no line splice" sh -c '
    ! grep -q "??" "$1" && ! grep -q "\\\\$" "$1"' sh "$TMP/hostile.c"
# The same scene with plain names: with the comments stripped
# (tools/strip-comments: gcc's -fpreprocessed, which clang lacks), the two
# outputs are the same code.
cat > "$TMP/plain.json" <<'EOF'
{"name": "x", "description": "d",
 "bodies": [{"name": "b1", "type": "particle", "mass": 1, "position": [1, 0]},
            {"name": "b2", "type": "particle", "mass": 1, "position": [2, 0]}],
 "joints": [{"name": "j1", "type": "distance", "a": [0, 0], "b": "b1"},
            {"name": "j2", "type": "distance", "a": "b1", "b": "b2"}],
 "effects": [{"name": "g", "type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" gen-c "$TMP/plain.json" --symbol hostile -o "$TMP/plain.c"
strip_comments() { CC=$CC tools/strip-comments "$1" | grep -v '^ *$'; }
strip_comments "$TMP/hostile.c" > "$TMP/hostile.code"
strip_comments "$TMP/plain.c" > "$TMP/plain.code"
check "gen-c hostile output: the same code as for plain names, once comments are stripped" sh -c '
    [ -s "$1" ] && cmp -s "$1" "$2"' sh "$TMP/hostile.code" "$TMP/plain.code"

# A name of 100 000 characters: lines stay within C99's 4095.
awk 'BEGIN { s = ""; for (i = 0; i < 100000; i++) s = s "n";
    printf "{\"name\": \"long\", \"description\": \"%s\", \"bodies\": [{\"name\": \"%s\", \"type\": \"particle\", \"mass\": 1, \"position\": [1, 0]}], \"joints\": [{\"type\": \"distance\", \"a\": [0, 0], \"b\": \"%s\"}]}\n", s, s, s }' > "$TMP/long.json"
"$BRAUN" gen-c "$TMP/long.json" --symbol longname -o "$TMP/long.c"; rc=$?
check "gen-c of 100 000-character names: every line < 4096 characters, compiles" sh -c '
    [ "$1" -eq 0 ] && awk "length(\$0) > 4095 { bad = 1 } END { exit bad }" "$2" &&
    $3 -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude/core -c "$2" -o "$2.o"' \
    sh "$rc" "$TMP/long.c" "$CC"

# braun list shows a data directory's file names as check does (an ESC and
# a newline in a name reached the terminal raw), and says when the
# directory is not there (an empty list, without a word).
mkdir -p "$TMP/dd"
cp data/pendulum.json "$TMP/dd/$(printf 'evil\033[31m\nname.json')"
BRAUN_DATA_DIR="$TMP/dd" "$BRAUN" list > "$TMP/list.out" 2> /dev/null
check "list: a file name's control bytes as \\xNN, on one line" sh -c '
    grep -q "^evil\\\\x1B\[31m\\\\x0Aname.json n=2" "$1" && ! LC_ALL=C grep -q "$(printf "\033")" "$1"' \
    sh "$TMP/list.out"
BRAUN_DATA_DIR="$TMP/nonexistent" "$BRAUN" list > /dev/null 2> "$TMP/list.err"; rc=$?
check "list: a data directory that is not there is noted" sh -c '
    [ "$1" -eq 0 ] && grep -q "note: the data directory .*nonexistent. is not a directory" "$2"' \
    sh "$rc" "$TMP/list.err"

# ------------------------------------------------------- gen-c: symbols, files
abs_braun_early=$(cd "$(dirname "$BRAUN")" && pwd)/$(basename "$BRAUN")
# gen and gen-c parse their options as run does: each once, "--name=VALUE"
# too (the last of two won in silence; --angle=30 was an unknown option).
expect "gen-c -o twice refused" 2 "option -o given twice" gen-c data/pendulum.json -o "$TMP/a.c" -o "$TMP/b.c"
expect "gen-c --symbol twice refused" 2 "option --symbol given twice" \
    gen-c data/pendulum.json --symbol a --symbol b
expect "gen chain --angle twice refused" 2 "option --angle given twice" gen chain 2 --angle 30 --angle 40
expect "run --quiet twice refused, as every option" 2 "option --quiet given twice" \
    run pendulum --dt 1e-2 --t-end 1 --quiet --quiet
expect "run --sparse twice refused" 2 "option --sparse given twice" \
    run data/chain-5.json --dt 1e-2 --t-end 1 --sparse --sparse
expect "gen chain -o and --out refused (one option)" 2 "option --out given twice" \
    gen chain 2 -o "$TMP/a.json" --out "$TMP/b.json"
expect "gen chain --angle=30 as --angle 30" 0 "" gen chain 2 --angle=30 -o "$TMP/eq.json"
expect "gen-c --symbol=p --out=FILE" 0 "" gen-c data/pendulum.json --symbol=p --out="$TMP/eq.c"
expect "gen chain --rods=1 refused" 2 "option --rods takes no value" gen chain 2 --rods=1
expect "gen chain -1: N out of range, not an unknown option" 2 "N must be an integer in \\[1, 2000\\] \\(got '-1'\\)" gen chain -1
# A value that begins with "--" is a forgotten value in every command (gen-c
# wrote its C to a file named "--symbol"; run refused it already).
(cd "$TMP" && "$abs_braun_early" gen-c "$OLDPWD/data/pendulum.json" -o --symbol p) 2> "$TMP/fv.err"; rc=$?
check "gen-c -o --symbol: a forgotten value, no file '--symbol'" sh -c '
    [ "$1" -eq 2 ] && grep -q "option -o needs a value" "$2" && [ ! -e "$3/--symbol" ]' \
    sh "$rc" "$TMP/fv.err" "$TMP"
expect "gen chain -o --angle 30: a forgotten value" 2 "option -o needs a value" gen chain 2 -o --angle 30
expect "plot -o --dt: a forgotten value" 2 "option -o needs a value" plot data/pendulum.json -o --dt 1e-2 --t-end 1
# check takes no option: one given is named as run names its unknown ones
# (check said "needs exactly one SCENE" beside exactly one scene).
expect "check four-bar --quiet: the option named" 2 "^braun: unknown option '--quiet' \\(check takes none" \
    check four-bar --quiet
expect "check --quiet four-bar: the option named" 2 "^braun: unknown option '--quiet' \\(check takes none" \
    check --quiet four-bar
expect "check four-bar --dt 1: the option named" 2 "^braun: unknown option '--dt' \\(check takes none" \
    check four-bar --dt 1
expect "check four-bar pendulum: the second scene named" 2 "^braun: unexpected argument 'pendulum' \\(one SCENE only\\)" \
    check four-bar pendulum
expect "check with no scene: still the count" 2 "^braun: check needs exactly one SCENE" check
# "--" ends the options: a scene named "-x.json" after it (run called it an
# unknown option, check read it).
cp data/pendulum.json "$TMP/-x.json"
abs_braun=$(cd "$(dirname "$BRAUN")" && pwd)/$(basename "$BRAUN")
(cd "$TMP" && "$abs_braun" run --dt 1e-2 --t-end 0.1 --summary /dev/null -- -x.json &&
    "$abs_braun" check -- -x.json > /dev/null &&
    "$abs_braun" gen-c --symbol p -o /dev/null -- -x.json) 2> "$TMP/dash.err"; rc=$?
check "run, check, gen-c take a scene named -x.json after --" sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' \
    sh "$rc" "$TMP/dash.err"
# Symbols that differ only in case give one set of macros (ARM_N): the
# headers shared their guard, the second was skipped in silence and a
# program sized the second scene's buffers with the first one's ARM_N. Now
# each has its own guard and the second stops at its sizes' check; one
# scene's source with its own header still compiles.
"$BRAUN" gen-c data/pendulum.json --symbol arm -o "$TMP/arm.c" --header "$TMP/arm.h"
"$BRAUN" gen-c data/chain-5.json --symbol ARM -o "$TMP/ARM.c" --header "$TMP/ARM.h"
printf '#include "arm.h"\n#include "ARM.h"\nint main(void) { return ARM_N; }\n' > "$TMP/both.c"
printf '#include "arm.c"\n#include "arm.h"\n' > "$TMP/same.c"
check "gen-c: headers whose symbols differ only in case stop the compile, naming the clash" sh -c '
    ! $1 -std=c99 -I"$2" -Iinclude/core -c "$2/both.c" -o "$2/both.o" 2> "$2/both.err" &&
    grep -q "error: \\(#error \\)\\{0,1\\}ARM_N, ARM_M or ARM_P defined already" "$2/both.err" &&
    $1 -std=c99 -Wall -Wextra -Wpedantic -Werror -I"$2" -Iinclude/core -c "$2/same.c" -o "$2/same.o"' \
    sh "$CC" "$TMP"
# The default symbol: the file name without .json when it is a C
# identifier; '-' and '.' become '_', said on stderr; anything else
# refused, asking for --symbol. my scene.json, é.json and --.json gave
# my_scene, s___, s___ in silence, and names cut at 48 characters gave one
# symbol (one include guard: the second header was skipped in silence).
mkdir -p "$TMP/sym"
long=mechanism_assembly_left_front_suspension_linkage
for f in plain my-scene "my scene" "$(printf '\303\251')" -- 2link ${long}_v1; do
    cp data/pendulum.json "$TMP/sym/$f.json"
done
expect "gen-c default symbol: the file name as it is, nothing said" 0 "" \
    gen-c "$TMP/sym/plain.json" -o "$TMP/sym/plain.c"
expect "gen-c default symbol from my-scene.json: my_scene, noted with a hint to --symbol" 0 \
    "^braun: note: gen-c: symbol 'my_scene' from the file name .*--symbol NAME to choose" \
    gen-c "$TMP/sym/my-scene.json" -o "$TMP/sym/my-scene.c"
check "gen-c default symbol my_scene defines my_scene_build" grep -q "^int my_scene_build" "$TMP/sym/my-scene.c"
expect "gen-c default symbol: a space in the file name refused, asks for --symbol" 2 \
    "^braun: gen-c: no symbol from the file name '.*my scene.json' \(it has characters other than .*\): give --symbol NAME$" \
    gen-c "$TMP/sym/my scene.json" -o "$TMP/sym/space.c"
expect "gen-c default symbol: a non-ASCII first letter refused" 2 "does not start with an ASCII letter\): give --symbol" \
    gen-c "$TMP/sym/$(printf '\303\251').json" -o /dev/null
expect "gen-c default symbol: --.json refused" 2 "does not start with an ASCII letter\): give --symbol" \
    gen-c -o /dev/null -- "$TMP/sym/--.json"
expect "gen-c default symbol: 2link.json refused (not s2link)" 2 "does not start with an ASCII letter" \
    gen-c "$TMP/sym/2link.json" -o /dev/null
expect "gen-c default symbol: a file name over 48 characters refused (not cut)" 2 \
    "more than the symbol's 48 characters: cut, it could be another file's symbol\): give --symbol NAME$" \
    gen-c "$TMP/sym/${long}_v1.json" -o /dev/null
check "gen-c default symbol refused: no file written" [ ! -e "$TMP/sym/space.c" ]
expect "gen-c --symbol braun_scene refused (braun_scene_build is libbraun's)" 2 \
    "symbol must not start with 'braun_'" gen-c data/pendulum.json --symbol braun_scene
expect "gen-c --symbol of 49 characters refused" 2 "longer than 48" \
    gen-c data/pendulum.json --symbol aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa
expect "gen-c --symbol _x refused (reserved)" 2 "must not start with '_'" \
    gen-c data/pendulum.json --symbol _x
expect "gen-c --symbol with a non-ASCII letter refused" 2 "must be a C identifier" \
    gen-c data/pendulum.json --symbol "$(printf 'caf\303\251')"
expect "gen-c -o /dev/full: exit 1, names the I/O error (not 'a C identifier?')" 1 \
    "^braun: error writing '/dev/full': No space left on device$" gen-c data/pendulum.json -o /dev/full
# One of the two files cannot be written: the other, which this run
# created, goes too (a complete-looking source was left without its header).
expect "gen-c --header /dev/full: exit 1, names it" 1 \
    "^braun: error writing '/dev/full': No space left on device$" \
    gen-c data/pendulum.json -o "$TMP/gh.c" --header /dev/full
check "gen-c --header /dev/full: the source it created is removed" [ ! -e "$TMP/gh.c" ]
cp data/pendulum.json "$TMP/in.json"
expect "gen-c -o onto its input scene: refused" 2 "is the input" gen-c "$TMP/in.json" -o "$TMP/./in.json"
check "gen-c -o onto its input scene: the scene is unchanged" cmp -s data/pendulum.json "$TMP/in.json"
# Outputs written whole (gen-c, gen, plot -o): a write that fails leaves a
# file that existed as it was. They were written in place: under a file
# size limit (or beside a --header that could not be written) an existing
# source was cut off mid-token or replaced, though the command exited 1.
mkdir -p "$TMP/whole"
printf 'OLD %.0s' $(seq 900) > "$TMP/whole/old.ref"
for f in old.c old.h old.json old.svg; do cp "$TMP/whole/old.ref" "$TMP/whole/$f"; done
limited() { (trap '' XFSZ; ulimit -f 1; exec "$BRAUN" "$@") > /dev/null 2> "$TMP/whole/err"; }
limited gen-c data/pendulum.json -o "$TMP/whole/old.c"; rc=$?
check "gen-c -o an existing file, write fails (ulimit -f): exit 1, the file as it was" sh -c '
    [ "$1" -eq 1 ] && grep -q "error writing .*old.c.: File too large" "$2/err" && cmp -s "$2/old.ref" "$2/old.c"' \
    sh "$rc" "$TMP/whole"
"$BRAUN" gen-c data/pendulum.json -o "$TMP/whole/old.c" --header /dev/full 2> /dev/null; rc=$?
"$BRAUN" gen-c data/pendulum.json -o /dev/full --header "$TMP/whole/old.h" 2> /dev/null; rc2=$?
check "gen-c: the source or the header cannot be written: exit 1, the other file as it was" sh -c '
    [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && cmp -s "$3/old.ref" "$3/old.c" && cmp -s "$3/old.ref" "$3/old.h"' \
    sh "$rc" "$rc2" "$TMP/whole"
limited gen chain 50 -o "$TMP/whole/old.json"; rc=$?
check "gen -o an existing file, write fails: exit 1, the file as it was" sh -c '
    [ "$1" -eq 1 ] && cmp -s "$2/old.ref" "$2/old.json"' sh "$rc" "$TMP/whole"
limited plot data/pendulum.json --dt 1e-2 --t-end 1 --quiet -o "$TMP/whole/old.svg"; rc=$?
check "plot -o an existing file, write fails: exit 1, the file as it was" sh -c '
    [ "$1" -eq 1 ] && cmp -s "$2/old.ref" "$2/old.svg"' sh "$rc" "$TMP/whole"
check "outputs written whole: no temporary file left behind" sh -c '
    [ "$(ls -A "$1" | sort | tr "\n" " ")" = "err old.c old.h old.json old.ref old.svg " ]' sh "$TMP/whole"
# Written whole and put in place: the file's permissions kept, a symbolic
# link still a link to the file it named.
chmod 640 "$TMP/whole/old.c"
ln -s old.h "$TMP/whole/link.h"
"$BRAUN" gen-c data/pendulum.json --symbol p -o "$TMP/whole/old.c" --header "$TMP/whole/link.h"; rc=$?
check "gen-c over existing files: written, mode 640 kept, the link still a link to the header" sh -c '
    [ "$1" -eq 0 ] && grep -q "int p_build" "$2/old.c" && [ "$(stat -c %a "$2/old.c")" = 640 ] &&
    [ -L "$2/link.h" ] && grep -q "BRAUN_GEN_p_H" "$2/old.h"' sh "$rc" "$TMP/whole"
mkfifo "$TMP/fifo"
expect "gen-c -o FIFO: refused at once (no reader needed)" 2 "is a FIFO" gen-c data/pendulum.json -o "$TMP/fifo"
expect "gen -o FIFO: refused at once" 2 "is a FIFO" gen chain 3 -o "$TMP/fifo"

# Every kind named as what it is: a socket was "a FIFO" (as an output) or
# "cannot open: No such device or address" (as a scene), since open fails
# on both with ENXIO; a directory output was "cannot open ... Is a directory".
if command -v python3 > /dev/null 2>&1 &&
    python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$TMP/sock"; then
    expect "gen-c -o socket: refused as a socket" 2 "^braun: gen-c -o '.*sock' is a socket \(not a regular file\): refused$" \
        gen-c data/pendulum.json -o "$TMP/sock"
    expect "gen-c --header socket: refused as a socket" 2 "^braun: gen-c --header '.*sock' is a socket" \
        gen-c data/pendulum.json -o "$TMP/sock.c" --header "$TMP/sock"
    expect "gen -o socket: refused as a socket" 2 "^braun: gen -o '.*sock' is a socket" gen chain 3 -o "$TMP/sock"
    expect "run --out socket: refused as a socket" 2 "^braun: --out '.*sock' is a socket" \
        run four-bar --dt 1e-2 --t-end 1 --out "$TMP/sock"
    expect "check a socket: refused as a socket" 2 "sock: is a socket, not a scene file" check "$TMP/sock"
    expect "plot --traj a socket: refused as a socket" 2 "sock: is a socket, not a regular file" \
        plot pendulum --traj "$TMP/sock" -o "$TMP/sock.svg"
else
    echo "ok - output socket # SKIP no python3 to make a socket"
fi
mkdir -p "$TMP/adir"
expect "gen-c -o a directory: refused as a directory" 2 "^braun: gen-c -o '.*adir' is a directory \(not a regular file\): refused$" \
    gen-c data/pendulum.json -o "$TMP/adir"
expect "run --summary a directory: refused as a directory" 2 "^braun: --summary '.*adir' is a directory" \
    run four-bar --dt 1e-2 --t-end 1 --summary "$TMP/adir"
# A block device without a driver (open: ENXIO): where mknod is allowed.
if mknod "$TMP/blk" b 250 250 2> /dev/null; then
    expect "gen-c -o a block device: refused as a block device" 2 "^braun: gen-c -o '.*blk' is a block device" \
        gen-c data/pendulum.json -o "$TMP/blk"
    expect "check a block device: refused as a block device" 2 "blk: is a block device, not a scene file" check "$TMP/blk"
else
    echo "ok - block device # SKIP mknod not allowed"
fi

# --------------------------------------------------------- special files in
expect "run FIFO: refused at once (never waits for a writer)" 2 "is a FIFO" \
    run "$TMP/fifo" --dt 1e-3 --t-end 1
expect "check FIFO: refused at once" 2 "is a FIFO" check "$TMP/fifo"
expect "gen-c FIFO: refused at once" 2 "is a FIFO" gen-c "$TMP/fifo"
expect "check a directory: refused as a directory" 2 "is a directory" check "$TMP/"
expect "check /dev/zero: refused as a character device (never read)" 2 "is a character device" check /dev/zero

# ---------------------------------------------------- loading time vs size
# A chain of N rigid links whose last joint names an unknown body: the
# message comes in O(N log N) (it took O(N^2): 63 s at N = 200 000).
chain() { # chain N BAD FILE: BAD body | point
    awk -v N="$1" -v BAD="$2" 'BEGIN {
        print "{\"name\": \"big\", \"bodies\": ["
        for (i = 1; i <= N; i++)
            printf "{\"name\": \"link%d\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.08, \"position\": [%d.5, 0], \"points\": {\"a\": [-0.5, 0], \"b\": [0.5, 0]}}%s\n", i, i - 1, (i < N ? "," : "")
        print "], \"joints\": [{\"type\": \"revolute\", \"a\": \"link1.a\", \"b\": [0, 0]},"
        for (i = 2; i <= N; i++) printf "{\"type\": \"revolute\", \"a\": \"link%d.b\", \"b\": \"link%d.a\"},\n", i - 1, i
        printf "{\"name\": \"last\", \"type\": \"revolute\", \"a\": \"link%d.b\", \"b\": \"%s\"}]}\n", N, BAD == "body" ? "nosuch.a" : "link1.nosuch" }' > "$3"
}
chain 20000 body "$TMP/c20k.json"
chain 200000 body "$TMP/c200k.json"
chain 200000 point "$TMP/p200k.json"
t0=$(now_ms); timeout 60 "$BRAUN" check "$TMP/c20k.json" > /dev/null 2> "$TMP/c20k.err"
t1=$(now_ms); expect "200 000 links, unknown body at the end: exit 2 within 20 s, named" 2 \
    "c200k.json:400002:[0-9]+: joint 'last' refers to unknown body 'nosuch'" check "$TMP/c200k.json"
t2=$(now_ms); expect "200 000 links, unknown point at the end: exit 2 within 20 s, named" 2 \
    "joint 'last' refers to unknown point 'link1.nosuch'" check "$TMP/p200k.json"
small=$((t1 - t0)) large=$((t2 - t1))
check "loading is O(N log N): 200 000 links ${large} ms, 20 000 ${small} ms (ratio < 20, < 19.5 s)" sh -c '
    grep -q "c20k.json:40002:[0-9]*: joint .last. refers to unknown body .nosuch.$" "$3" &&
    awk -v a="$1" -v b="$2" "BEGIN { exit !(a < 19500 && a < 20 * (b > 100 ? b : 100)) }"' \
    sh "$large" "$small" "$TMP/c20k.err"
rm -f "$TMP/c20k.json" "$TMP/c200k.json" "$TMP/p200k.json"

# ---------------------------------------------------- numbers the reader takes
scene() { # scene FILE BODY [JOINT]: one particle body on an optional joint
    printf '{"name": "s", "bodies": [%s], "joints": [%s], "effects": [{"type": "gravity", "g": [0, -9.81]}]}\n' "$2" "$3" > "$1"
}
scene "$TMP/m320.json" '{"name": "b", "type": "particle", "mass": 1e-320, "position": [1, 0]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "mass 1e-320 (subnormal): refused at load, names the field" 2 \
    "m320.json:1:[0-9]+: body 'b': field 'mass' underflows: 1e-320 is below the smallest normal" \
    run "$TMP/m320.json" --dt 1e-3 --t-end 1
# Below a double's range jansson reads 0 without an error: "1e-400" must
# not become a particle without mass, nor a position, a drive's phase or a
# gravity entry of 0. Refused at the field, saying it underflows and what
# the field takes at least (a field with a domain: BRAUN_SCENE_MIN_SCALE).
scene "$TMP/m400.json" '{"name": "b", "type": "particle", "mass": 1e-400, "position": [1, 0]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "mass 1e-400 (reads as 0): refused at load as an underflow, with the least mass" 2 \
    "m400.json:1:68: body 'b': field 'mass' underflows: 1e-400 is below the smallest normal number 2.22507e-308 and would read as 0; the least nonzero magnitude it accepts is 1e-150 \(BRAUN_SCENE_MIN_SCALE" \
    run "$TMP/m400.json" --dt 1e-3 --t-end 1
scene "$TMP/p400.json" '{"name": "b", "type": "particle", "mass": 1, "position": [1, -1E-400]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "position entry -1E-400: refused at load, FILE:LINE and the key" 2 \
    "p400.json:1:[0-9]+: body 'b': field 'position' underflows: -1E-400 is below .* the least nonzero magnitude it accepts is 2.22507e-308 \(BRAUN_SCENE_MIN_NORMAL\)" \
    check "$TMP/p400.json"
scene "$TMP/ph400.json" '{"name": "b", "type": "particle", "mass": 1, "position": [1, 0]}' \
    '{"name": "rod", "type": "distance", "a": [0, 0], "b": "b", "drive": {"type": "sine", "offset": 1, "amplitude": 0.1, "omega": 1, "phase": 0.1e-399}}'
expect "a drive's phase 0.1e-399: refused at load" 2 \
    "ph400.json:1:[0-9]+: joint 'rod', field 'drive': field 'phase' underflows: 0.1e-399" check "$TMP/ph400.json"
scene "$TMP/z400.json" '{"name": "b", "type": "particle", "mass": 1, "position": [1, 0.0], "velocity": [0e-400, -0.000e-999]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "zeros written as 0.0, 0e-400, -0.000e-999: still zeros, the scene loads" 0 "" check "$TMP/z400.json"
scene "$TMP/m999.json" '{"name": "b", "type": "particle", "mass": 1e999, "position": [1, 0]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "mass 1e999 (overflow): refused at load, FILE:LINE and the key" 2 \
    "m999.json:1:68: at bodies\[0\].mass: real number overflow" check "$TMP/m999.json"
scene "$TMP/axis.json" '{"name": "b", "type": "particle", "mass": 1, "position": [0, 0]}' \
    '{"type": "slider", "point": "b", "line": [0, 0], "axis": [1e-300, 0]}'
expect "slider axis of length 1e-300: refused at load (its square underflows)" 2 \
    "axis.json:1:[0-9]+: joint #1: field 'axis' is too small \(length 1e-300; the limit is 1e-150" \
    run "$TMP/axis.json" --dt 1e-3 --t-end 1
scene "$TMP/len.json" '{"name": "b", "type": "particle", "mass": 1, "position": [1e-200, 0]}' \
    '{"type": "distance", "a": [0, 0], "b": "b"}'
expect "distance of 1e-200 taken from the initial state: refused at load" 2 \
    "joint #1: field 'length' \(left out: taken from the initial state\) is too small" \
    check "$TMP/len.json"
# Beyond the range: the builder's "joint parameters are not finite numbers
# in range" or "rod length must be a finite number > 0" named neither the
# length nor the limit.
far='{"name": "b", "type": "particle", "mass": 1, "position": [6e11, 0]}'
scene "$TMP/far.json" "$far" '{"name": "cord", "type": "distance", "a": [-6e11, 0], "b": "b"}'
expect "distance of 1.2e12 taken from the initial state: refused naming the length and the limit" 2 \
    "far.json:1:[0-9]+: joint 'cord': field 'length' \(left out: taken from the initial state\) is 1.2e\+12, beyond the limit \|x\| <= 1e\+12" \
    check "$TMP/far.json"
printf '{"name": "s", "bodies": [%s], "rods": [{"name": "r", "a": [-6e11, 0], "b": "b", "mass": 1}]}\n' "$far" > "$TMP/farrod.json"
expect "rod of 1.2e12 taken from the initial state: refused naming the length and the limit" 2 \
    "farrod.json:1:[0-9]+: rod 'r': field 'length' \(left out: taken from the initial state\) is 1.2e\+12, beyond the limit" \
    check "$TMP/farrod.json"
printf '{"name": "s", "bodies": [%s], "effects": [{"name": "k", "type": "spring", "a": [-6e11, 0], "b": "b", "stiffness": 1}]}\n' "$far" > "$TMP/farspring.json"
expect "spring rest length of 1.2e12 taken from the initial state: refused naming it and the limit" 2 \
    "farspring.json:1:[0-9]+: effect 'k': field 'rest_length' \(left out: taken from the initial state\) is 1.2e\+12, beyond the limit" \
    check "$TMP/farspring.json"
scene "$TMP/fardrive.json" '{"name": "b", "type": "particle", "mass": 1, "position": [0, 1e12]}' \
    '{"name": "cord", "type": "distance", "a": [0, -9], "b": "b", "drive": {"type": "sine", "offset": 1, "amplitude": 0.5, "omega": 1, "phase": 0}}'
expect "driven distance 1e12 + 9 apart: the unused length is named with its value and the limit" 2 \
    "fardrive.json:1:[0-9]+: joint 'cord': field 'length' \(left out: taken from the initial state, though 'drive' is used\) is 1000000000009, beyond the limit" \
    check "$TMP/fardrive.json"
scene "$TMP/step.json" '{"name": "b", "type": "particle", "mass": 1, "position": [1, 0]}' \
    '{"type": "distance", "a": [0, 0], "b": "b", "drive": {"type": "sine", "amplitude": 1, "omega": 1e-310}}'
expect "a drive's omega of 1e-310 (subnormal): refused at load" 2 "field 'omega' underflows: 1e-310" \
    check "$TMP/step.json"
# The mass matrix's pivots are judged against their own diagonal entries,
# which no choice of units changes (they were against the largest one, an
# inertia against a mass): a rigid body whose radius of gyration is 1e-10 m
# and a particle 1e-20 times as heavy as its neighbour load and run (both
# were refused at load); a body whose own block is singular to working
# precision still is refused, at its size and at 2^-66 of it.
printf '{"name": "s", "bodies": [{"name": "b", "type": "rigid", "mass": 1, "inertia": 1e-20, "position": [0.5, 0], "points": {"o": [-0.5, 0]}}], "joints": [{"type": "revolute", "a": "b.o", "b": [0, 0]}]}\n' > "$TMP/inertia.json"
expect "inertia 1e-20 beside mass 1 (radius of gyration 1e-10 m): loads and runs" 0 "" \
    run "$TMP/inertia.json" --dt 1e-3 --t-end 1
printf '{"name": "s", "bodies": [{"name": "b1", "type": "particle", "mass": 1, "position": [1, 0]}, {"name": "b2", "type": "particle", "mass": 1e-20, "position": [2, 0]}], "joints": [{"type": "distance", "a": [0, 0], "b": "b1"}, {"type": "distance", "a": "b1", "b": "b2"}]}\n' > "$TMP/ratio.json"
expect "masses 1 and 1e-20 in one scene: loads, consistent" 0 "" check "$TMP/ratio.json"
printf '{"name": "s", "bodies": [{"name": "b", "type": "rigid3d", "mass": 1, "inertia": [1, 1, 2], "products": [0.99999999999999989, 0, 0], "position": [0, 0, -0.5], "points": {"top": [0, 0, 0.5]}}], "joints": [{"type": "spherical", "a": "b.top", "b": [0, 0, 0]}]}\n' > "$TMP/tensor.json"
expect "a rigid3d tensor singular to working precision: refused at load, the pivot against its own entry" 2 \
    "tensor.json:1:[0-9]+: body 'b': its inertia gives the mass matrix a pivot of 8.88178e-16, not above n\\*eps\\*M_jj = 6.21725e-15 \\(n = 7, its diagonal entry M_jj = 4\\): M would be singular to working precision" \
    check "$TMP/tensor.json"
printf '{"name": "s", "bodies": [{"name": "b", "type": "rigid3d", "mass": 1, "inertia": [1.3552527156068805e-20, 1.3552527156068805e-20, 2.7105054312137611e-20], "products": [1.3552527156068804e-20, 0, 0], "position": [0, 0, -0.5], "points": {"top": [0, 0, 0.5]}}], "joints": [{"type": "spherical", "a": "b.top", "b": [0, 0, 0]}]}\n' > "$TMP/tensor-small.json"
expect "the same tensor 2^-66 times as large: refused too (the same verdict in any units)" 2 \
    "tensor-small.json:1:[0-9]+: body 'b': its inertia gives the mass matrix a pivot of 1.20371e-35, not above n\\*eps\\*M_jj = 8.42594e-35 \\(n = 7, its diagonal entry M_jj = 5.42101e-20\\)" \
    check "$TMP/tensor-small.json"
printf '{"name": "s", "bodies": [{"name": "b", "type": "rigid", "mass": 1, "inertia": 1, "position": [0, 0]}], "joints": [{"type": "knife", "body": "b", "direction": [1, 0]}, {"type": "revolute", "a": "b..", "b": [0, 0]}]}\n' > "$TMP/own.json"
expect "a reference 'b..' does not reach a knife edge's own contact point" 2 \
    "refers to unknown point 'b..'" check "$TMP/own.json"

# ------------------------------------------------- zero-length spring, named
printf '{"name": "zs", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [0, 0]}],\n "effects": [{"name": "sp", "type": "spring", "a": [0, 0], "b": "b", "stiffness": 10}]}\n' > "$TMP/zs.json"
expect "spring of length 0 at the initial state: refused at load, names the spring" 2 \
    "zs.json:2:14: effect 'sp' \(spring\) cannot be evaluated at the initial state: its forces hook returns 1 at t = 0, where its points 'a' and 'b' coincide" \
    run "$TMP/zs.json" --dt 1e-3 --t-end 1
printf '{"name": "zs2", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 0], "velocity": [-1, 0]}],\n "effects": [{"name": "sp", "type": "spring", "a": [0, 0], "b": "b", "stiffness": 0, "rest_length": 0}]}\n' > "$TMP/zs2.json"
"$BRAUN" run "$TMP/zs2.json" --dt 0.5 --t-end 2 > "$TMP/zs2.out" 2> "$TMP/zs2.err"; rc=$?
check "spring reaching length 0 at t = 1: exit 1, the message names effect 'sp'" sh -c '
    [ "$1" -eq 1 ] && [ "$(wc -l < "$2")" -eq 1 ] &&
    grep -q "^braun: effect '\''sp'\'' (spring): its forces hook returns 1 at t = 1, where its points '\''a'\'' and '\''b'\'' coincide: callback '\''forces'\''" "$2"' \
    sh "$rc" "$TMP/zs2.err"

# --------------------------------------------------- texts in the tool's output
printf '{"name": "a\\nn: 7", "description": "x\\nn: 999", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 0]}], "joints": [{"type": "distance", "a": [0, 0], "b": "b"}]}\n' > "$TMP/forge.json"
"$BRAUN" check "$TMP/forge.json" > "$TMP/forge.out" 2>&1
check "check: a name or description with a newline cannot forge a 'key: value' line" sh -c '
    [ "$(grep -c "^n: " "$1")" -eq 1 ] && grep -q "^n: 2$" "$1" &&
    grep -q "^description: x\\\\x0An: 999$" "$1"' sh "$TMP/forge.out"
# A C1 control (U+009B, a CSI to terminals that take 8-bit controls) in a
# name reached the terminal raw: shown as \u009B.
printf '{"name": "a\\u009b31mred", "bodies": [{"name": "b", "type": "particle", "mass": 1, "position": [1, 0]}], "joints": [{"type": "distance", "a": [0, 0], "b": "b"}]}\n' > "$TMP/c1.json"
"$BRAUN" check "$TMP/c1.json" > "$TMP/c1.out" 2>&1
check "check: a C1 control in a name is shown as \\u009B, not passed to the terminal" sh -c '
    grep -q "^scene: a\\\\u009B31mred$" "$1" && ! LC_ALL=C grep -q "$(printf "\302\233")" "$1"' sh "$TMP/c1.out"
expect "an error message naming a path with a newline stays one line" 2 "cannot open '.*nl\?x/y' for writing" \
    gen chain 3 -o "$TMP/nl
x/y"

# ------------------------------------------------------ options of braun run
expect "--rank-tol 1: refused as an argument (exit 2), not run" 2 "^braun: --rank-tol must be < 1 \(got 1\)" \
    run four-bar --dt 1e-2 --t-end 1 --rank-tol 1
expect "--rank-tol 0.5: the message says what the tolerance did" 1 \
    "constraint[a-z -]* disagree.*with --rank-tol 0.5, rows whose pivot is below 0.5 times the largest count as dependent" \
    run data/four-bar.json --dt 1e-2 --t-end 1 --rank-tol 0.5 --summary /dev/null
expect "--dt 1e-310: underflows, not 'not a finite number'" 2 "^braun: --dt: '1e-310' underflows: it is below the smallest normal double" \
    run four-bar --dt 1e-310 --t-end 1
# A value below a double's range reads as 0 (strtod's ERANGE): refused,
# in every real option, as an underflow.
for opt in --dt --t-end --rtol --atol --rank-tol --energy-max-rel --guard --soft-tol --ref-h; do
    expect "$opt 1e-400: refused as an underflow (it would read as 0)" 2 \
        "^braun: $opt: '1e-400' underflows: it is below the smallest normal double, 2.22507e-308, and would read as 0" \
        run four-bar --dt 1e-2 --t-end 1 --integrator dopri5 "$opt" 1e-400
done
expect "plot --from -1e-400: refused as an underflow" 2 "^braun: --from: '-1e-400' underflows" \
    plot four-bar --dt 1e-2 --t-end 1 --from -1e-400 -o "$TMP/from.svg"
expect "gen --angle 1e-400: refused as an underflow, not 'a number of degrees'" 2 \
    "^braun: --angle: '1e-400' underflows" gen chain 2 --angle 1e-400
"$BRAUN" run pendulum --dt 1e-2 --t-end 0.05 --out "$TMP/u.csv" --summary /dev/null
sed '3s/^\([^,]*\),[^,]*,/\1,1e-400,/' "$TMP/u.csv" > "$TMP/u400.csv"
expect "plot --traj: a CSV value 1e-400 (reads as 0) is refused at CSV:LINE, its column" 2 \
    "^braun: --traj .*u400.csv:3: column 2 \(bob.x\) is 1e-400: it underflows" \
    plot pendulum --traj "$TMP/u400.csv" -o "$TMP/u.svg"
expect "--dt 1e999: out of range, not 'not a finite number'" 2 "^braun: --dt: '1e999' is out of range" \
    run four-bar --dt 1e999 --t-end 1
expect "--dt 1e-17 with --t-end 1: below the time resolution" 2 "below the time resolution" \
    run four-bar --dt 1e-17 --t-end 1
expect "--ref-h 1e-300: refused (1e300 reference substeps)" 2 "^braun: --ref-h 1e-300: the reference would take" \
    run slider-crank --dt 1e-2 --t-end 1 --ref-h 1e-300
expect "--every without --out: an error" 2 "^braun: --every 10 without --out" \
    run four-bar --dt 1e-2 --t-end 1 --every 10

# ---------------------------------------------------------- outputs of run
expect "--out and --summary one file: refused" 2 "are the same file" \
    run four-bar --dt 1e-2 --t-end 1 --out "$TMP/one" --summary "$TMP/./one"
check "--out and --summary one file: nothing left behind" [ ! -e "$TMP/one" ]
cp data/pendulum.json "$TMP/p.json"
expect "--out onto the input scene: refused" 2 "^braun: --out '.*p.json' is the input" \
    run "$TMP/p.json" --dt 1e-2 --t-end 1 --out "$TMP/p.json"
expect "--summary onto the input scene (another spelling): refused" 2 "is the input" \
    run "$TMP/p.json" --dt 1e-2 --t-end 1 --summary "$TMP/../$(basename "$TMP")/p.json"
ln -s "$TMP/p.json" "$TMP/link.csv"
expect "--out through a symbolic link to the input scene: refused" 2 "is the input" \
    run "$TMP/p.json" --dt 1e-2 --t-end 1 --out "$TMP/link.csv"
check "the input scene is unchanged" cmp -s data/pendulum.json "$TMP/p.json"
"$BRAUN" run four-bar --dt 1e-2 --t-end 1 --out "$TMP/same.csv" > "$TMP/same.csv" 2> "$TMP/same.err"; rc=$?
check "--out FILE with stdout (the summary) redirected to FILE: refused" sh -c '
    [ "$1" -eq 2 ] && grep -q "are the same file" "$2"' sh "$rc" "$TMP/same.err"
expect "--out FIFO: refused at once" 2 "^braun: --out '.*fifo' is a FIFO" \
    run four-bar --dt 1e-2 --t-end 1 --out "$TMP/fifo"
expect "--summary FIFO: refused at once" 2 "^braun: --summary '.*fifo' is a FIFO" \
    run four-bar --dt 1e-2 --t-end 1 --summary "$TMP/fifo"
expect "--summary /dev/full: exit 1, names the I/O error" 1 \
    "^braun: error writing '/dev/full': No space left on device$" \
    run four-bar --dt 1e-2 --t-end 1 --summary /dev/full
expect "--out /dev/full: exit 1, names the I/O error" 1 \
    "^braun: error writing '/dev/full': No space left on device$" \
    run four-bar --dt 1e-2 --t-end 1 --out /dev/full --summary /dev/null

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
