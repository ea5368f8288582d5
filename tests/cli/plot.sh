#!/bin/sh
# Tests of `braun plot` and of what people read from `braun run` (issue 15):
#   sh tests/cli/plot.sh path/to/braun path/to/png_ink
# The SVG is well-formed and draws the bodies where they are (every rod of
# the four-bar drawn 1 m long at the picture's scale, the pivots 1 m apart),
# a frame rendered to PNG (rsvg-convert) is not blank, the animation page
# loads nothing from outside and its script plays (node, or a visible
# skip), the PNG comes from gnuplot, --traj redraws a CSV, built-in models
# draw as their data/ scenes; the progress line and the summary line; shipped
# scenes from any directory. "ok - NAME" / "not ok - NAME" / "ok - NAME # SKIP
# WHY" and "N passed, M failed, K skipped"; exit 1 if anything failed.
BRAUN=${1:?usage: sh tests/cli/plot.sh path/to/braun path/to/png_ink}
INK=${2:?usage: sh tests/cli/plot.sh path/to/braun path/to/png_ink}
case $BRAUN in /*) ;; *) BRAUN=$(pwd)/$BRAUN ;; esac
case $INK in /*) ;; *) INK=$(pwd)/$INK ;; esac
TOP=$(cd "$(dirname "$0")/../.." && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-plot.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "$2" ] || echo "#   $2"; }
check() { name=$1; shift; if "$@"; then ok "$name"; else not_ok "$name"; fi; }
have() { command -v "$1" > /dev/null 2>&1; }

# ink FILE.png MIN_FRACTION: at least that share of the pixels drawn, over
# at least half of the width and a third of the height, in several colours.
ink() {
    out=$("$INK" "$1") || return 1
    echo "$out" | awk -v f="$2" '{ w = $1; h = $2; n = $3
        exit !(n >= f * w * h && $6 - $4 >= w / 2 && $7 - $5 >= h / 3 && $8 >= 3) }'
}

cd "$TMP" || exit 1
cp "$TOP/data/four-bar.json" "$TOP/data/slider-crank.json" .

# ------------------------------------------------------------------ SVG
"$BRAUN" plot four-bar.json --dt 1e-2 --t-end 3 -o four-bar.svg > out.txt 2> err.txt; rc=$?
check "plot four-bar.json --dt 1e-2 --t-end 3 -o four-bar.svg: exit 0, quiet when not a terminal" \
    sh -c '[ "$1" -eq 0 ] && [ -s four-bar.svg ] && [ ! -s out.txt ] && [ ! -s err.txt ]' sh "$rc"
if have xmllint; then
    check "the SVG is well-formed XML" xmllint --noout four-bar.svg
else
    skip "the SVG is well-formed XML" "xmllint not found (libxml2-utils)"
fi
check "the SVG has 12 configurations (the default), each with the 5 rods and 3 moving joints" \
    awk '/<g class="frame"/ { f++; bars = 0; pins = 0 }
         /stroke-width="9"/ { bars++ }
         /r="3.6"/ { pins++ }
         /<\/g>/ && f { if (bars != 5 || pins != 3) bad = 1 }
         END { exit !(f == 12 && !bad) }' four-bar.svg
# Geometry: the three ground pivots (0,0), (1,0), (2,0) are the apexes of
# the ground marks, so they give the scale; every rod is 1 m long.
check "every rod is drawn 1 m long at the picture's scale (pivots 1 m apart), to 0.05 px" \
    awk -F'"' '
        /<polygon points=/ && /fill="#ffffff" stroke="#222222"/ {
            split($2, p, "[ ,]"); gx[++g] = p[1]; gy[g] = p[2] }
        /stroke-width="9"/ { n++; x1[n] = $2; y1[n] = $4; x2[n] = $6; y2[n] = $8 }
        END {
            if (g != 3 || n != 60) exit 1
            s = gx[2] - gx[1]
            if (s < 50 || (gx[3] - gx[2]) - s > 0.02 || (gx[3] - gx[2]) - s < -0.02) exit 1
            if (gy[1] != gy[2] || gy[2] != gy[3]) exit 1
            for (i = 1; i <= n; i++) {
                d = sqrt((x2[i] - x1[i]) ^ 2 + (y2[i] - y1[i]) ^ 2) - s
                if (d > 0.05 || d < -0.05) exit 1
            }
        }' four-bar.svg
if have rsvg-convert; then
    rsvg-convert four-bar.svg -o four-bar-svg.png 2> /dev/null
    check "the SVG rendered by rsvg-convert is not blank ($("$INK" four-bar-svg.png 2>&1))" \
        ink four-bar-svg.png 0.02
else
    skip "the SVG rendered by rsvg-convert is not blank" "rsvg-convert not found (librsvg2-bin)"
fi
"$BRAUN" plot four-bar --dt 1e-2 --t-end 3 -o builtin.svg
check "the built-in four-bar draws exactly as data/four-bar.json" cmp -s builtin.svg four-bar.svg

# The paper's Fig. 1: a stroboscopic view of the slider-crank, h = 5e-2, t in [96.9, 99].
"$BRAUN" plot slider-crank --dt 5e-2 --t-end 99 --from 96.9 --frames 43 --points rod.B -o fig1.svg; rc=$?
check "Fig. 1: 43 configurations of t = 96.9 ... 99 s and the slider's path" sh -c '
    [ "$1" -eq 0 ] && [ "$(grep -c "<g class=\"frame\"" fig1.svg)" -eq 43 ] &&
    grep -q "<g class=\"frame\" data-t=\"96.9" fig1.svg && grep -q "<g class=\"frame\" data-t=\"99\"" fig1.svg &&
    grep -q "<polyline fill=\"none\" stroke=\"#d62728\"" fig1.svg' sh "$rc"
# The slider's path stays on its line y = 0: one screen y for every point.
check "Fig. 1: the path of rod.B is a straight line (the slider's guide)" \
    awk '/<polyline fill="none" stroke="#d62728"/ {
            sub(/.*points="/, ""); sub(/".*/, ""); n = split($0, p, " ")
            split(p[1], a, ","); for (i = 2; i <= n; i++) { split(p[i], b, ","); if (b[2] != a[2]) bad = 1 }
            found = n > 10 }
         END { exit !(found && !bad) }' fig1.svg

# ------------------------------------------------------------------ HTML
"$BRAUN" plot four-bar.json --dt 1e-2 --t-end 3 --points J2 -o four-bar.html; rc=$?
check "-o four-bar.html: exit 0" [ "$rc" -eq 0 ]
check "the page loads nothing from outside (no src, href, url(), @import, link, URL or fetch)" \
    sh -c '! grep -Eiq "src=|href=|url\(|@import|<link|<iframe|<object|<embed|<img|https?:|ftp:|//[a-z0-9]|fetch\(|XMLHttpRequest|import\(" four-bar.html'
check "the page has play/pause, a time slider and one inline script" sh -c '
    grep -q "<button id=\"play\"" four-bar.html && grep -q "<input id=\"slider\" type=\"range\"" four-bar.html &&
    [ "$(grep -c "<script>" four-bar.html)" -eq 1 ] && [ "$(grep -c "<script" four-bar.html)" -eq 1 ]'
check "the page has a configuration per state (301 at h = 1e-2 over 3 s)" \
    [ "$(grep -c '<g data-t=' four-bar.html)" -eq 301 ]
# One configuration of the page, shown, rendered.
awk '/<svg/ { on = 1; sub(/<svg/, "<svg xmlns=\"http://www.w3.org/2000/svg\"") }
     on && /<g data-t="1.5"/ { sub(/ style="display:none"/, "") }
     on { print } /<\/svg>/ { on = 0 }' four-bar.html > page-frame.svg
if have rsvg-convert; then
    rsvg-convert page-frame.svg -o page-frame.png 2> /dev/null
    check "a frame of the page (t = 1.5 s) rendered to PNG is not blank ($("$INK" page-frame.png 2>&1))" \
        ink page-frame.png 0.01
else
    skip "a frame of the page rendered to PNG is not blank" "rsvg-convert not found (librsvg2-bin)"
fi
if have node; then
    node "$TOP/tests/cli/page_check.js" four-bar.html > node.txt 2>&1; rc=$?
    check "the page's script plays, pauses, follows the slider and the speed (node: $(grep -c '^ok' node.txt) checks)" \
        sh -c '[ "$1" -eq 0 ] && ! grep -q "^not ok" node.txt' sh "$rc"
    [ "$rc" -eq 0 ] || cat node.txt
else
    skip "the page's script plays, pauses, follows the slider" "node not found"
fi
if have chromium; then
    timeout 60 chromium --headless --no-sandbox --disable-gpu --window-size=900,700 \
        --screenshot="$TMP/chromium.png" "file://$TMP/four-bar.html" > /dev/null 2>&1
    if [ -s chromium.png ]; then
        check "headless Chromium draws the page ($("$INK" chromium.png 2>&1))" ink chromium.png 0.01
    else
        not_ok "headless Chromium draws the page" "no screenshot"
    fi
else
    skip "headless Chromium draws the page" "chromium not installed"
fi

# ------------------------------------------------------------------ PNG (gnuplot)
if have gnuplot; then
    "$BRAUN" plot four-bar.json --dt 1e-2 --t-end 3 -o four-bar.png; rc=$?
    check "-o four-bar.png through gnuplot: a PNG that is not blank ($("$INK" four-bar.png 2>&1))" \
        sh -c '[ "$1" -eq 0 ] && [ "$(head -c 4 four-bar.png | od -An -c | tr -d " ")" = "211PNG" ] && "$2" four-bar.png > /dev/null' \
        sh "$rc" "$INK"
    ink four-bar.png 0.01 || not_ok "the gnuplot PNG has ink over the picture" "$("$INK" four-bar.png)"
    # A .png that cannot be written (/dev/full): gnuplot exits 0 there, and
    # so did the tool.
    ln -s /dev/full full.png
    "$BRAUN" plot four-bar.json --dt 1e-2 --t-end 1 -o full.png 2> full.err; rc=$?
    check "-o full.png on /dev/full: exit 1, the write error named" sh -c '
        [ "$1" -eq 1 ] && grep -q "error writing .full.png.: No space left on device" full.err' sh "$rc"
else
    skip "-o four-bar.png through gnuplot" "gnuplot not found (gnuplot-nox)"
fi
# A gnuplot that exits 0 and writes nothing (no pngcairo terminal), or is
# killed: exit 1, no empty .png left, a file that existed kept.
mkdir -p fakebin
printf '#!/bin/sh\ncat > /dev/null\nexit 0\n' > fakebin/gnuplot
chmod +x fakebin/gnuplot
echo "old picture" > kept.png
PATH="$TMP/fakebin:$PATH" "$BRAUN" plot four-bar.json --dt 1e-2 --t-end 1 -o none.png 2> none.err; rc=$?
PATH="$TMP/fakebin:$PATH" "$BRAUN" plot four-bar.json --dt 1e-2 --t-end 1 -o kept.png 2> /dev/null; rc2=$?
check "a gnuplot that writes no .png: exit 1, said, no empty file, an old file kept" sh -c '
    [ "$1" -eq 1 ] && [ "$2" -eq 1 ] && grep -q "gnuplot exited 0 but wrote no .png" none.err &&
    [ ! -e none.png ] && [ "$(cat kept.png)" = "old picture" ]' sh "$rc" "$rc2"
printf '#!/bin/sh\nkill -9 $$\n' > fakebin/gnuplot
PATH="$TMP/fakebin:$PATH" "$BRAUN" plot four-bar.json --dt 1e-2 --t-end 1 -o killed.png 2> killed.err; rc=$?
check "a gnuplot killed by a signal: exit 1, the signal named" sh -c '
    [ "$1" -eq 1 ] && grep -q "gnuplot was killed by signal 9" killed.err && [ ! -e killed.png ]' sh "$rc"

# ------------------------------------------------------------------ a point's path and coordinates
"$BRAUN" plot slider-crank.json --dt 1e-2 --t-end 5 --points rod.B --plot x,y,crank.theta -o chart.svg; rc=$?
check "--points rod.B --plot x,y,crank.theta: a chart of three series" sh -c '
    [ "$1" -eq 0 ] && [ "$(grep -c "<polyline" chart.svg)" -eq 3 ] &&
    grep -q ">rod.B.x \[m\]<" chart.svg && grep -q ">crank.theta \[rad\]<" chart.svg' sh "$rc"
if have xmllint; then check "the chart is well-formed XML" xmllint --noout chart.svg; fi
# rod.B.x is 2 cos(theta_1) for the slider-crank (both links 1 m, B on y = 0):
# the chart's x series and 2 cos(crank.theta) from the CSV agree.
"$BRAUN" run slider-crank.json --dt 1e-2 --t-end 5 --out sc.csv --summary /dev/null
# The columns mean what they say: with the links' points at -0.5 and 0.5
# along each body, crank.A = rod.A and rod.B is on y = 0 at every row.
check "the CSV's columns are the bodies' x, y, theta: crank.A = rod.A and rod.B on y = 0, to 1e-7 (max |Phi_q| 2.1e-8 at h = 1e-2)" \
    awk -F, 'NR > 1 { ax = $2 + cos($4) / 2 - ($5 - cos($7) / 2); ay = $3 + sin($4) / 2 - ($6 - sin($7) / 2)
                      by = $6 + sin($7) / 2
                      if (ax > 1e-7 || ax < -1e-7 || ay > 1e-7 || ay < -1e-7 || by > 1e-7 || by < -1e-7) bad = 1; n++ }
             END { exit !(n == 501 && !bad) }' sc.csv

# ------------------------------------------------------------------ --traj
"$BRAUN" plot slider-crank.json --traj sc.csv --points rod.B -o traj.svg; rc=$?
"$BRAUN" plot slider-crank.json --dt 1e-2 --t-end 5 --points rod.B -o run.svg
check "--traj: the CSV of a run draws the same configurations as the run" sh -c '
    [ "$1" -eq 0 ] && grep -v "<title>\|<text" traj.svg > a && grep -v "<title>\|<text" run.svg > b && cmp -s a b' sh "$rc"
# A CSV longer than the 2000 states kept: sampled evenly from its first row
# as the run is (not from -inf, whose spacing was NaN: the first 1999 rows).
"$BRAUN" run slider-crank --dt 1e-3 --t-end 5 --out long.csv --summary /dev/null
"$BRAUN" plot slider-crank --traj long.csv --points rod.B -o long-traj.svg; rc=$?
"$BRAUN" plot slider-crank --dt 1e-3 --t-end 5 --points rod.B -o long-run.svg
check "--traj: a CSV of 5001 rows draws the same configurations and path as its run" sh -c '
    [ "$1" -eq 0 ] && grep -v "<title>\|<text" long-traj.svg > a && grep -v "<title>\|<text" long-run.svg > b && cmp -s a b' sh "$rc"
printf 't [s],x\n0,1\n' > wrong.csv
"$BRAUN" plot slider-crank.json --traj wrong.csv -o w.svg > /dev/null 2> err.txt; rc=$?
check "--traj with the wrong columns: exit 2 naming the column" sh -c '
    [ "$1" -eq 2 ] && grep -q "^braun: --traj wrong.csv:1: column 2 is .x., .slider-crank. has .crank.x. there" err.txt && [ ! -e w.svg ]' sh "$rc"

# ------------------------------------------------------------------ --traj: every shipped scene's CSV
# The round trip run --out -> plot --traj holds for every shipped scene,
# those with reported points (report: NAME.x, NAME.y, NAME.z after the
# other columns) included, and --plot takes those columns too.
rt_bad=""
rt_n=0
for scene in "$TOP"/data/*.json "$TOP"/data/iftomm/*.json; do
    b=$(basename "$scene" .json)
    "$BRAUN" run "$scene" --dt 1e-2 --t-end 0.2 --out "rt-$b.csv" --summary /dev/null 2> /dev/null
    "$BRAUN" plot "$scene" --traj "rt-$b.csv" -o "rt-$b.svg" 2> rt.err || rt_bad="$rt_bad $b($(tr '\n' ' ' < rt.err))"
    [ -s "rt-$b.svg" ] || rt_bad="$rt_bad $b(no svg)"
    rt_n=$((rt_n + 1))
done
check "--traj draws the CSV of run --out for each of the $rt_n shipped scenes (data/, data/iftomm/)" \
    sh -c '[ -z "$1" ] && [ "$2" -ge 15 ]' sh "$rt_bad" "$rt_n"
[ -z "$rt_bad" ] || echo "#   failed:$rt_bad"
check "... spatial-arm's CSV has its reported point's columns tip.x, tip.y, tip.z" \
    sh -c 'head -n 1 rt-spatial-arm.csv | grep -q ",traj_err \[q\],tip.x \[m\],tip.y \[m\],tip.z \[m\]$"'
"$BRAUN" plot "$TOP/data/spatial-arm.json" --dt 1e-2 --t-end 0.2 --plot tip.x,tip.z -o tip-run.svg 2> tip.err; rc=$?
check "--plot tip.x,tip.z: a reported point's CSV columns are charted" sh -c '
    [ "$1" -eq 0 ] && [ "$(grep -c "<polyline" tip-run.svg)" -eq 2 ] &&
    grep -q ">tip.x \[m\]<" tip-run.svg && grep -q ">tip.z \[m\]<" tip-run.svg' sh "$rc"
"$BRAUN" plot "$TOP/data/spatial-arm.json" --traj rt-spatial-arm.csv --plot tip.x,tip.z -o tip-traj.svg; rc=$?
check "... from --traj as from the run" sh -c '
    [ "$1" -eq 0 ] && grep -v "<title>\|<text" tip-traj.svg > a && grep -v "<title>\|<text" tip-run.svg > b && cmp -s a b' sh "$rc"
# tip.x from the chart's scale: its polyline's first and last values are the
# CSV's first and last tip.x (to the 0.01 px the chart is written at).
check "... and the chart's tip.x is the CSV's tip.x (first and last row, to 1e-3 of the range)" \
    awk -F, -v svg=tip-run.svg '
        NR == 1 { for (i = 1; i <= NF; i++) if ($i == "tip.x [m]") c = i; next }
        NR == 2 { first = $c } { last = $c; if (NR > 1 && (lo == "" || $c < lo)) lo = $c; if (NR > 1 && (hi == "" || $c > hi)) hi = $c }
        END {
            while ((getline l < svg) > 0) if (l ~ /<polyline/ && !done) { sub(/.*points="/, "", l); sub(/".*/, "", l); n = split(l, p, " "); done = 1 }
            split(p[1], a, ","); split(p[n], z, ",")
            ymin = 1e9; ymax = -1e9
            for (i = 1; i <= n; i++) { split(p[i], q, ","); if (q[2] < ymin) ymin = q[2]; if (q[2] > ymax) ymax = q[2] }
            # screen y is linear in the value: map the extremes onto lo, hi
            f0 = (ymax - a[2]) / (ymax - ymin) * (hi - lo) + lo
            f1 = (ymax - z[2]) / (ymax - ymin) * (hi - lo) + lo
            d0 = f0 - first; d1 = f1 - last; tol = 1e-3 * (hi - lo)
            exit !(c > 0 && n > 10 && hi > lo && d0 * d0 <= tol * tol && d1 * d1 <= tol * tol) }' rt-spatial-arm.csv

# ------------------------------------------------------------------ --traj: numbers a picture cannot place
# A value that is not finite (nan, inf, 1e999 which reads as inf) is refused
# at its line and column; finite values whose span overflows (1e308 and
# -1e308) would make the scale and every position NaN: refused too, and
# nothing is written, whatever the picture.
cp "$TOP/data/pendulum.json" .
ph='t [s],bob.x [m],bob.y [m],bob.vx [m/s],bob.vy [m/s],pos_err [Phi_q],vel_err [Phi_q/s],energy_err [J],traj_err [q]'
printf '%s\n0,1,0,0,0,0,0,0,\n0.1,nan,0,0,0,0,0,0,\n' "$ph" > nan.csv
printf '%s\n0,1,0,0,0,0,0,0,\n0.1,0,1e999,0,0,0,0,0,\n' "$ph" > over.csv
printf '%s\n0,1,0,0,0,0,0,0,\n0.1,1,0,0,0,0,0,-inf,\n' "$ph" > minf.csv
printf '%s\n0,1,0,0,0,0,0,0,\ninf,1,0,0,0,0,0,0,\n' "$ph" > tinf.csv
printf '%s\n0,1,0,0,0,0,0,0,\nnan,1,0,0,0,0,0,0,\n' "$ph" > tnan.csv
printf '%s\n0,1e308,0,0,0,0,0,0,\n0.1,-1e308,0,0,0,0,0,0,\n' "$ph" > span.csv
printf '%s\n-1e308,1,0,0,0,0,0,0,\n1e308,1,0,0,0,0,0,0,\n' "$ph" > tspan.csv
refused_traj() { name=$1; csv=$2; want=$3; shift 3
    for o in svg html; do
        "$BRAUN" plot pendulum.json --traj "$csv" "$@" -o "nf.$o" > nf.out 2> nf.err; rc=$?
        if [ "$rc" -eq 2 ] && [ ! -e "nf.$o" ] && [ ! -s nf.out ] && [ "$(wc -l < nf.err)" -eq 1 ] &&
            grep -q "^braun: $want" nf.err
        then ok "--traj $name (.$o): exit 2, nothing written ($(cut -c1-100 nf.err))"
        else not_ok "--traj $name (.$o): exit 2, nothing written" "exit $rc: $(cat nf.err); $(grep -c 'nan\|inf' "nf.$o" 2> /dev/null) nan/inf"; fi
        rm -f "nf.$o"
    done
}
refused_traj "a nan" nan.csv "--traj nan.csv:3: column 2 (bob.x) is nan: not a finite number$"
# Decimal numbers only: strtod also read a hexadecimal float.
printf '%s\n0,1,0,0,0,0,0,0,\n0.1,0x1p-1,0,0,0,0,0,0,\n' "$ph" > hex.csv
refused_traj "a hexadecimal float" hex.csv "--traj hex.csv:3: column 2 (bob.x) is not a number"
refused_traj "1e999 (overflows to inf)" over.csv "--traj over.csv:3: column 3 (bob.y) is 1e999: beyond the range of a double$"
refused_traj "-inf in energy_err" minf.csv "--traj minf.csv:3: column 8 (energy_err) is -inf"
refused_traj "the last row's t = inf" tinf.csv "--traj tinf.csv:3: column 1 (t) is inf: not a finite number$"
refused_traj "the last row's t = nan" tnan.csv "--traj tnan.csv:3: column 1 (t) is nan: not a finite number$"
refused_traj "x from 1e308 to -1e308 (a span past a double)" span.csv "the drawing's points span more than the range of a double"
refused_traj "x from 1e308 to -1e308, --plot bob.x" span.csv "--plot: the values .* span more than the range of a double" --plot bob.x
refused_traj "t from -1e308 to 1e308" tspan.csv "--traj tspan.csv: t runs from -1e+308 to 1e+308, a span beyond the range of a double$"
# A run whose states pass but fly apart (two particles at -+1e12 m/s for
# 1.5e296 s: 1.5e308 m each way) cannot be drawn either: exit 1, no file.
printf '{"name": "fly", "bodies": [
  {"name": "a", "type": "particle", "mass": 1, "position": [0, 0], "velocity": [1e12, 0]},
  {"name": "b", "type": "particle", "mass": 1, "position": [0, 0], "velocity": [-1e12, 0]}]}\n' > fly.json
for o in fly.svg fly.html; do
    "$BRAUN" plot fly.json --dt 1e295 --t-end 1.5e296 -o "$o" 2> fly.err; rc=$?
    check "a run whose points span past a double: exit 1, no $o, one message" sh -c '
        [ "$1" -eq 1 ] && [ ! -e "$2" ] && grep -q "^braun: the drawing.s points span more than the range of a double" fly.err' sh "$rc" "$o"
done
"$BRAUN" plot fly.json --dt 1e295 --t-end 1.5e296 --plot a.x,b.x -o flyc.svg 2> fly.err; rc=$?
check "... its chart (--plot a.x,b.x) too: exit 1, no file" sh -c '
    [ "$1" -eq 1 ] && [ ! -e flyc.svg ] && grep -q "^braun: --plot: the values .* span more than the range of a double" fly.err' sh "$rc"
"$BRAUN" plot fly.json --dt 1e295 --t-end 1e295 -o flyok.svg 2> fly.err; rc=$?
check "... while 1e307 m each way is drawn, with no nan or inf in it" sh -c '
    [ "$1" -eq 0 ] && [ -s flyok.svg ] && ! grep -qi "nan\|inf" flyok.svg' sh "$rc"

# ------------------------------------------------------------------ refused
bad() { name=$1; shift
    "$BRAUN" "$@" > bad.out 2> bad.err; rc=$?
    if [ "$rc" -eq 2 ] && [ ! -s bad.out ] && [ "$(wc -l < bad.err)" -eq 1 ] && grep -q "^braun: " bad.err
    then ok "refused: $name ($(cut -c1-90 bad.err))"
    else not_ok "refused: $name" "exit $rc: $(cat bad.err)"; fi
}
bad "no -o" plot four-bar --dt 1e-2 --t-end 1
bad "unknown extension" plot four-bar --dt 1e-2 --t-end 1 -o x.pdf
bad "--traj with run options" plot four-bar --traj sc.csv --dt 1e-2 -o x.svg
bad "unknown body in --points" plot slider-crank --dt 1e-2 --t-end 1 --points arm.A -o x.svg
bad "unknown point in --points" plot slider-crank --dt 1e-2 --t-end 1 --points rod.C -o x.svg
bad "unknown --plot column" plot slider-crank --dt 1e-2 --t-end 1 --plot crank.bogus -o x.svg
bad "x without --points" plot slider-crank --dt 1e-2 --t-end 1 --plot x -o x.svg
bad "a system without a scene to draw" plot andrews --dt 1e-4 --t-end 0.001 -o x.svg
bad "unknown --view" plot four-bar --dt 1e-2 --t-end 1 --view xw -o x.svg
bad "--frames 0" plot four-bar --dt 1e-2 --t-end 1 --frames 0 -o x.svg
bad "-o onto the scene" plot four-bar.json --dt 1e-2 --t-end 1 -o four-bar.json
bad "-o onto the --traj input" plot slider-crank.json --traj sc.csv -o sc.csv
bad "--progress with --quiet" run four-bar --dt 1e-2 --t-end 1 --progress --quiet
check "refused plots leave no file" sh -c '[ ! -e x.svg ] && [ ! -e x.pdf ] && cmp -s four-bar.json "$1/data/four-bar.json"' sh "$TOP"
"$BRAUN" plot andrews --dt 1e-4 --t-end 0.001 --plot 'q[0],v[0]' -o andrews.svg; rc=$?
check "a system defined in C plots its coordinates q[i], v[i] against time" sh -c '
    [ "$1" -eq 0 ] && grep -q ">q\[0\]<" andrews.svg && grep -q ">v\[0\]<" andrews.svg' sh "$rc"

# ------------------------------------------------------------------ CSV and JSON people read
"$BRAUN" run slider-crank --dt 0.05 --t-end 1 --out short.csv --summary short.json
check "CSV: t = 0.1 is written 0.1 (not 0.10000000000000001), the header has units" sh -c '
    [ "$(sed -n 4p short.csv | cut -d, -f1)" = 0.1 ] && [ "$(head -c 27 short.csv)" = "t [s],crank.x [m],crank.y [" ]'
# Shortest round trip, checked with the C library's printf (awk's): each
# number reads back as itself at its own digits and not at one digit less.
check "CSV: every number is the shortest decimal that reads back as its double" \
    awk -F, 'NR > 1 { for (i = 1; i <= NF; i++) { v = $i; if (v == "") continue
                 d = v; sub(/e.*/, "", d); gsub(/[-.]/, "", d); sub(/^0+/, "", d); p = length(d); if (p == 0) p = 1
                 x = v + 0
                 if (sprintf("%.17g", sprintf("%." p "g", x) + 0) != sprintf("%.17g", x)) bad = 1
                 if (p > 1 && sprintf("%.17g", sprintf("%." (p - 1) "g", x) + 0) == sprintf("%.17g", x)) bad = 1
                 n++ } }
             END { exit !(n > 300 && !bad) }' short.csv
check "CSV: the built-in slider-crank names its columns as data/slider-crank.json does" sh -c '
    "$1" run slider-crank.json --dt 0.05 --t-end 1 --out file.csv --summary /dev/null &&
    [ "$(head -n 1 file.csv)" = "$(head -n 1 short.csv)" ]' sh "$BRAUN"
check "JSON: dt 0.05, the effective rank_tol (10 max(m, n) eps = 1.33e-14) and energy_max_rel 0.01" sh -c '
    grep -q "^  \"dt\": 0.05,$" short.json && grep -q "^  \"rank_tol\": 1.3322676295501878e-14,$" short.json &&
    grep -q "^  \"energy_max_rel\": 0.01,$" short.json && grep -q "^  \"guard\": 0.001,$" short.json &&
    grep -q "^  \"defaults\": \[\"rank_tol\", \"energy_max_rel\", \"symmetry_tol\", \"inconsistency_tol\", \"soft_tol\", \"guard\", \"max_steps\", \"ref_h\"\]$" short.json'
check "JSON: the guard's bounds are its relative value times the scales" \
    awk -F': ' '/"guard": / { g = $2 + 0 } /"guard_position_bound"/ { b = $2 + 0 } /"guard_position_scale"/ { s = $2 + 0 }
         END { exit !(g == 0.001 && s > 0 && (b - g * s) ^ 2 < 1e-30) }' short.json
check "JSON: cpu_s says it excludes monitoring" grep -q '"cpu_s_note": "integration alone: a second run of the same steps without monitoring or output"' short.json

# ------------------------------------------------------------------ progress and the summary line
"$BRAUN" run four-bar --dt 1e-3 --t-end 20 --summary /dev/null --progress 2> prog.txt; rc=$?
check "--progress writes progress to stderr when it is not a terminal" sh -c '
    [ "$1" -eq 0 ] && grep -q "^braun: four-bar: t = 20 of 20 s (100%), 20k steps, .* steps/s, 0 s left \[run 2 of 2: monitoring\]$" prog.txt &&
    grep -q "\[run 1 of 2: timing, no monitoring\]$" prog.txt' sh "$rc"
check "--progress: one summary line: status, steps, CPU time and what cpu_s means, errors, guard bounds" \
    sh -c '[ "$(grep -c "^braun: four-bar: BRAUN_OK at t = 20 s, 20000 steps (rk4, h = 0.001), CPU .* s (cpu_s: the integration alone, timed in a run without monitoring; the monitored run took .* s); max |Phi_q| .*, |q - q_ref| .* (guard bounds .*)$" prog.txt)" -eq 1 ]'
"$BRAUN" run four-bar --dt 1e-3 --t-end 2 --summary /dev/null 2> quiet.txt
check "without a terminal nothing is written to stderr by default" [ ! -s quiet.txt ]
if have script; then
    script -qec "$BRAUN run four-bar --dt 1e-3 --t-end 5 --summary /dev/null" /dev/null > tty.txt 2>&1
    check "on a terminal: the progress line is rewritten in place (CR, erase) and the summary line follows" sh -c '
        grep -q "$(printf "\r")braun: four-bar: t = " tty.txt && grep -q "$(printf "\033")\[K" tty.txt &&
        grep -q "braun: four-bar: BRAUN_OK at t = 5 s, 5000 steps" tty.txt'
    script -qec "$BRAUN run four-bar --dt 1e-3 --t-end 5 --summary /dev/null --quiet" /dev/null > ttyq.txt 2>&1
    check "on a terminal, --quiet: no progress and no summary line" sh -c '! grep -q "braun:" ttyq.txt'
else
    skip "progress on a terminal" "script (util-linux) not found"
fi
"$BRAUN" run pendulum --dt 1 --t-end 50 --progress --out pend.csv --summary pend.json 2> pend.txt; rc=$?
check "a run the guard stops: the summary line says which state was refused and which kept" sh -c '
    [ "$1" -eq 1 ] && grep -q "^braun: pendulum: BRAUN_ERR_ACCURACY at t = 1 s (that state refused; kept t = 0 s, the last that passed)" pend.txt' sh "$rc"
check "... and the CSV ends at the state kept (t = 0), the JSON's final_t too" sh -c '
    [ "$(tail -n 1 pend.csv | cut -d, -f1)" = 0 ] && grep -q "^  \"final_t\": 0,$" pend.json &&
    grep -q "^  \"refused_state_t\": 1,$" pend.json'

# ------------------------------------------------------------------ a scene's name is data
# A hostile "name" (ESC [31m, CR, LF and a forged "n: 999") is printed as
# braun check prints it — control bytes as \xNN, a backslash as \\ — on the
# progress line, the summary line and in a picture's titles (XML-escaped
# there too), never raw.
sed 's/"name": "pendulum"/"name": "p\\u001b[31mRED\\u001b[0m\\r\\nn: 999 <\&> \\"q\\" \\\\"/' pendulum.json > hostile.json
want='p\x1B[31mRED\x1B[0m\x0D\x0An: 999 <&> "q" \\'
"$BRAUN" check hostile.json > hcheck.txt 2>&1
check "braun check shows the hostile name escaped (the reference)" sh -c '
    [ "$(sed -n "s/^scene: //p" hcheck.txt)" = "$1" ]' sh "$want"
"$BRAUN" run hostile.json --dt 1e-2 --t-end 0.5 --summary /dev/null --progress 2> hprog.txt; rc=$?
esc=$(printf '\033'); cr=$(printf '\r')
check "run --progress: the progress and summary lines escape the name as check does, no ESC or CR" sh -c '
    [ "$1" -eq 0 ] && ! grep -q "$2\|$3" hprog.txt && [ "$(wc -l < hprog.txt)" -eq 5 ] &&
    [ "$(grep -cF "braun: $4: t = 0.5 of 0.5 s" hprog.txt)" -eq 2 ] &&
    [ "$(grep -cF "braun: $4: BRAUN_OK at t = 0.5 s" hprog.txt)" -eq 1 ] && ! grep -q "^n: 999" hprog.txt' \
    sh "$rc" "$esc" "$cr" "$want"
if have script; then
    script -qec "$BRAUN run $TMP/hostile.json --dt 1e-2 --t-end 0.5 --summary /dev/null" /dev/null > htty.txt 2>&1
    check "on a terminal: the only ESC bytes are the progress line's own erase (ESC [K)" sh -c '
        grep -qF "$2" htty.txt && ! grep -q "$1\[3\|$1\[0m" htty.txt' sh "$esc" "$want"
else
    skip "hostile name on a terminal" "script (util-linux) not found"
fi
xml_want='p\x1B[31mRED\x1B[0m\x0D\x0An: 999 &lt;&amp;&gt; &quot;q&quot; \\'
for o in hostile.svg hostile.html; do
    "$BRAUN" plot hostile.json --dt 1e-2 --t-end 0.5 -o "$o"; rc=$?
    check "$o: the title and caption escape the name (\\xNN, then XML), no control byte in the file" sh -c '
        [ "$1" -eq 0 ] && ! LC_ALL=C tr -d "\n" < "$2" | LC_ALL=C grep -q "[[:cntrl:]]" &&
        grep -qF "<title>$3: rk4" "$2" && grep -qF ">$3: rk4, h = 0.01 s" "$2"' sh "$rc" "$o" "$xml_want"
done
if have xmllint; then
    check "the SVG with the hostile name is well-formed XML" xmllint --noout hostile.svg
fi
"$BRAUN" plot hostile.json --dt 1e-2 --t-end 0.5 --plot bob.x -o hchart.svg; rc=$?
check "the chart's title and caption escape it too" sh -c '
    [ "$1" -eq 0 ] && grep -qF "<title>$2: rk4" hchart.svg && ! LC_ALL=C tr -d "\n" < hchart.svg | LC_ALL=C grep -q "[[:cntrl:]]"' sh "$rc" "$xml_want"

# ------------------------------------------------------------------ from anywhere
mkdir elsewhere && cd elsewhere || exit 1
"$BRAUN" run damped-motor.json --dt 1e-3 --t-end 1 --summary s.json; rc=$?
check "a shipped scene runs by its name from any directory (damped-motor.json)" sh -c '
    [ "$1" -eq 0 ] && grep -q "^  \"scene\": \"damped-motor\",$" s.json' sh "$rc"
"$BRAUN" plot sleigh --dt 1e-2 --t-end 2 -o sleigh.svg; rc=$?
check "... and draws by its name without .json (sleigh)" sh -c '[ "$1" -eq 0 ] && [ -s sleigh.svg ]' sh "$rc"
"$BRAUN" check a01-pendulum > a01.out 2>&1; rc=$?
"$BRAUN" check iftomm/a05-flyball-governor.json > a05.out 2>&1; rc2=$?
"$BRAUN" check iftomm/../four-bar.json > up.out 2>&1; rc3=$?
check "the IFToMM scenes by name (a01-pendulum, iftomm/a05-flyball-governor.json); no .. out of the data directory" sh -c '
    [ "$1" -eq 0 ] && [ "$2" -eq 0 ] && [ "$3" -eq 2 ] && grep -q "^scene: a01-pendulum$" a01.out &&
    grep -q "^file: .*/iftomm/a05-flyball-governor.json$" a05.out' sh "$rc" "$rc2" "$rc3"
# A torque's arrow shows its sense: +1 and -1 drew the same arc, and that
# arc's centre was 15 px off the body's (SVG's large-arc and sweep flags
# chose the other circle). Now both are three quarters of a circle about
# the body's origin, from the right (counter-clockwise, sweep 0) or the left
# (clockwise, sweep 1) to the bottom.
for s in 1 -1; do
    printf '{"name": "tq", "bodies": [{"name": "wheel", "type": "rigid", "mass": 1, "inertia": 0.1,
      "position": [0, 0], "points": {"O": [0, 0], "A": [0.5, 0]}}],
     "joints": [{"type": "revolute", "a": "wheel.O", "b": [0, 0]}],
     "effects": [{"type": "torque", "body": "wheel", "torque": %s}]}\n' "$s" > "tq$s.json"
    "$BRAUN" plot "tq$s.json" --dt 1e-2 --t-end 1 --frames 2 -o "tq$s.svg" 2> /dev/null
done
arc() { grep -o '<path d="M [^"]* A 15.0 15.0 0 1 [01] [^"]*"' "$1" | head -n 1 | sed 's/<path d="M //; s/"$//'; }
check "plot: a torque's arrow turns with its sign, about the body's origin" sh -c '
    a=$1 b=$2; [ -n "$a" ] && [ -n "$b" ] || exit 1
    # M x0 y0 A 15 15 0 1 sweep x1 y1: the end 15 px below the start'"'"'s row, x1 = x0 -+ 15
    echo "$a" | awk "{ exit !(\$8 == 0 && (\$1 - \$9) > 14.99 && (\$1 - \$9) < 15.01 && (\$10 - \$2) > 14.99 && (\$10 - \$2) < 15.01) }" &&
    echo "$b" | awk "{ exit !(\$8 == 1 && (\$9 - \$1) > 14.99 && (\$9 - \$1) < 15.01 && (\$10 - \$2) > 14.99 && (\$10 - \$2) < 15.01) }"' \
    sh "$(arc tq1.svg)" "$(arc tq-1.svg)"

# A torque of 0 has no arrow (it was drawn counter-clockwise).
printf '{"name": "tq", "bodies": [{"name": "wheel", "type": "rigid", "mass": 1, "inertia": 0.1,
  "position": [0, 0], "points": {"O": [0, 0], "A": [0.5, 0]}}],
 "joints": [{"type": "revolute", "a": "wheel.O", "b": [0, 0]}],
 "effects": [{"type": "torque", "body": "wheel", "torque": 0}]}\n' > tq0.json
"$BRAUN" plot tq0.json --dt 1e-2 --t-end 1 --frames 2 -o tq0.svg 2> /dev/null
check "plot: a torque of 0 draws no arrow" sh -c '[ -s tq0.svg ] && [ -z "$1" ] && [ -n "$2" ]' \
    sh "$(grep -o '<path d="M [^"]* A 15.0 15.0 ' tq0.svg | head -n 1)" "$(arc tq1.svg)"
# A planar scene has no z: --view xz drew everything on one line.
"$BRAUN" plot pendulum.json --dt 1e-2 --t-end 1 --view xz -o vxz.svg 2> vxz.err; rc=$?
check "plot --view xz of a planar scene: refused, exit 2, says why" sh -c '
    [ "$1" -eq 2 ] && grep -q "is planar" vxz.err && [ ! -e vxz.svg ]' sh "$rc"
# A picture of a run that stopped says so in itself (only stderr did; its
# caption read like a finished run's).
"$BRAUN" plot four-bar.json --dt 1e-2 --t-end 3 --integrator dopri5 --max-steps 40 -o stop.svg \
    2> /dev/null; rc=$?
check "plot: a run that stopped: exit 1, the caption names the asked end and the status" sh -c '
    [ "$1" -eq 1 ] && grep -q "t = 0 \.\.\. [0-9.]* s (of 3 s: stopped, BRAUN_ERR_TOO_MANY_STEPS)" "$2"' \
    sh "$rc" stop.svg

# A spatial joint's ground point gets its ground mark, as a planar one's
# does (the spatial arm's hinge pivot had a ring and no mark).
"$BRAUN" plot "$TOP/data/spatial-arm.json" --dt 1e-2 --t-end 0.5 --frames 2 --view xz -o sa.svg 2> /dev/null
check "plot: the spatial arm's two ground points (hinge pivot, cord anchor) both have marks" sh -c '
    [ "$(grep -c "fill=\"#ffffff\" stroke=\"#222222\"" "$1")" -eq 2 ]' sh sa.svg

# Frames at the kept states nearest their even times: 0.6 and 1.2 were
# drawn one step late (0.61, 1.21), and 289 frames over 289 states drew
# 282 distinct ones.
"$BRAUN" plot double-pendulum --dt 1e-2 --t-end 2.2 -o f22.svg 2> /dev/null
check "plot: frames at their even times (0.6, not 0.61)" sh -c '
    grep -q "data-t=\"0.6\"" f22.svg && ! grep -q "data-t=\"0.61\"" f22.svg'
"$BRAUN" plot double-pendulum --dt 1e-2 --t-end 2.88 --frames 289 -o d289.svg 2> /dev/null
check "plot: 289 frames over 289 kept states are 289 distinct states" \
    [ "$(grep -o 'data-t="[^"]*"' d289.svg | sort -u | wc -l)" -eq 289 ]
# A run that stops early is drawn from states as dense as it ran, not from
# the few of the grid over the window asked for (11 path points over 4.7 s).
"$BRAUN" plot double-pendulum --dt 1e-3 --t-end 1000 --integrator dopri5 --max-steps 300 \
    --points bob2 -o stop.svg 2> /dev/null
check "plot: a stopped run's path has a point per kept state (>= 200 of its 300 steps)" \
    [ "$(grep -o '<polyline[^>]*points="[^"]*"' stop.svg | head -1 | tr ' ' '\n' | wc -l)" -ge 200 ]
# Kept states 2.35 s apart of a pendulum of period 2.37 s: joined by lines
# they drew 14 slow swings over 470 s where there were 200 (aliasing). The
# chart shades each bin's least to greatest value, which covers the swing
# in every bin (but the last state's own), and says so; the path draws no
# chord across the circle.
"$BRAUN" plot pendulum --dt 1e-2 --t-end 470 --samples 200 --plot bob.x -o alias.svg 2> /dev/null
check "plot: an aliased chart shades the swing's whole range in every bin, and says so" sh -c '
    grep -q "<title>[^<]*shaded: least to greatest" alias.svg &&
    grep -o "<polygon class=\"envelope\"[^>]*points=\"[^\"]*\"" alias.svg | sed "s/.*points=\"//; s/\"//" |
    tr " " "\n" | awk -F, "{ y[++n] = \$2; if (n == 1 || \$2 < lo) lo = \$2; if (n == 1 || \$2 > hi) hi = \$2 }
        END { if (n < 400 || hi - lo < 100) exit 1
              for (i = 1; i <= n / 2 - 2; i++) { d = y[n + 1 - i] - y[i]; if (d < 0) d = -d; if (d < 0.9 * (hi - lo)) exit 1 } }"'
# ... and draws no line across the shaded bins: the line joining the kept
# states, thin over the band, still drew the 14 slow swings.
check "plot: the aliased chart joins no kept states across its shaded bins (no line left)" \
    [ "$(grep -c '<polyline' alias.svg)" -eq 0 ]
"$BRAUN" plot pendulum --dt 1e-2 --t-end 470 --samples 200 --points bob -o chords.svg 2> /dev/null
check "plot: a path of kept states far apart draws no chord inside the swing's circle" sh -c '
    grep -q "<title>[^<]*paths: dots where" chords.svg &&
    { grep -o "<polygon points=\"[^\"]*\" fill=\"#ffffff\" stroke=\"#222222\"" chords.svg | head -1 |
        sed "s/<polygon points=\"//; s/ .*//"
      grep -o "<g class=\"frame\"" chords.svg | head -1 > /dev/null
      grep -o "<circle cx=\"[^\"]*\" cy=\"[^\"]*\" r=\"1.3\"" chords.svg | sed "s/.*cx=\"//; s/\" cy=\"/,/; s/\".*//" | sed "s/^/D /"
      grep -o "<polyline fill=\"none\" stroke=\"#d62728\"[^>]*points=\"[^\"]*\"" chords.svg |
        sed "s/.*points=\"//; s/\"//" | sed "s/^/P /"; } |
    awk "NR == 1 { split(\$0, c, \",\"); px = c[1]; py = c[2]; next }
         { for (i = 2; i <= NF; i++) { split(\$i, c, \",\"); x[i] = c[1]; y[i] = c[2]
               r = sqrt((x[i] - px) ^ 2 + (y[i] - py) ^ 2); if (!R) R = r; pts++
               if (i > 2) { mx = (x[i] + x[i - 1]) / 2 - px; my = (y[i] + y[i - 1]) / 2 - py
                            if (R - sqrt(mx * mx + my * my) > 4) bad++ } } }
         END { exit !(R > 50 && pts >= 199 && !bad) }"'
# Tick labels read apart: four digits drew 999.9 six times and 1000 five
# times on a 0.1 s window at t = 1000, and 1e+08 on every value tick of a
# pendulum pivoted at x = 1e8.
cat > far.json << 'EOF'
{"name": "far", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [100000001, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [100000000, 0], "b": "bob", "length": 1}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" plot pendulum --dt 1e-2 --t-end 1000.1 --from 1000 --plot bob.x -o tail.svg 2> /dev/null
"$BRAUN" plot far.json --dt 1e-3 --t-end 3 --plot bob.x -o far.svg 2> /dev/null
# apart FILE ANCHOR: at least 4 tick labels (end: values; middle: times),
# no two alike.
apart() {
    grep -o "text-anchor=\"$2\">[^<]*<" "$1" | grep -v 't \[s\]' > ticks.txt
    [ "$(wc -l < ticks.txt)" -ge 4 ] && [ "$(sort -u ticks.txt | wc -l)" -eq "$(wc -l < ticks.txt)" ]
}
check "plot: the time ticks of a 0.1 s window at t = 1000 all read apart" apart tail.svg middle
check "plot: the value ticks of a pendulum at x = 1e8 all read apart" apart far.svg end
# A drive's arrow turns with the crank on screen: --view yx mirrors the
# plane, and the arrow kept xy's counter-clockwise arc (sweep flag 0) while
# the crank turned clockwise.
"$BRAUN" plot driven-crank --dt 1e-3 --t-end 0.2 --frames 3 -o dc-xy.svg 2> /dev/null
"$BRAUN" plot driven-crank --dt 1e-3 --t-end 0.2 --frames 3 --view yx -o dc-yx.svg 2> /dev/null
check "plot --view yx: the drive's arrow turns the other way on screen than in xy" sh -c '
    a=$(grep -o "A 15.0 15.0 0 1 [01]" dc-xy.svg | sort -u); b=$(grep -o "A 15.0 15.0 0 1 [01]" dc-yx.svg | sort -u)
    [ "$a" = "A 15.0 15.0 0 1 0" ] && [ "$b" = "A 15.0 15.0 0 1 1" ]'
# The caption stays on the canvas, clear of the scale bar and of the
# chart's "t [s]", with the run's status whole: a 50-letter scene name ran
# it under the bar and off the edge at "stopped, BRAUN_ERR_AC".
cat > longname.json << 'EOF'
{"name": "a-rather-long-but-perfectly-ordinary-scene-name-v2", "bodies": [{"name": "bob", "type": "particle", "mass": 1, "position": [1, 0]}],
 "joints": [{"name": "rod", "type": "distance", "a": [0, 0], "b": "bob", "drive": {"type": "linear", "value": 1, "rate": -0.5}}],
 "effects": [{"type": "gravity", "g": [0, -9.81]}]}
EOF
"$BRAUN" plot longname.json --dt 1e-3 --t-end 3 -o longname.svg 2> /dev/null
"$BRAUN" plot longname.json --dt 1e-3 --t-end 3 --plot bob.x,bob.y -o longname-chart.svg 2> /dev/null
# Text widths at 0.6 em a letter (DejaVu Sans's lower case and digits are
# narrower); the bar's line is the last of stroke-width 2.
check "plot: a long caption stays on the canvas, left of the scale bar, its status whole" sh -c '
    grep -q ">(of 3 s: stopped, BRAUN_ERR_ACCURACY)" longname.svg &&
    { grep -o "<line [^>]*stroke-width=\"2\"/>" longname.svg | tail -1 | sed "s/.*x1=\"\([^\"]*\)\" y1=\"\([^\"]*\)\".*/B \1 \2/"
      grep "<text x=\"28.00\" [^>]*font-size=\"13\">" longname.svg | sed "s/.*x=\"\([^\"]*\)\" y=\"\([^\"]*\)\"[^>]*>\(.*\)<\/text>/T \1 \2 \3/"; } |
    awk "\$1 == \"B\" { bx = \$2; by = \$3; next }
         \$1 == \"T\" { n++; x = \$2; y = \$3; t = \$0; sub(/^T [^ ]* [^ ]* /, \"\", t); e = x + 0.6 * 13 * length(t)
                      if (e > 800 || (y > by - 20 && y < by + 20 && e > bx - 4)) bad = 1 }
         END { exit !(bx > 400 && n >= 1 && !bad) }"'
check "plot: a long chart caption stays on the canvas, under the time axis's label" sh -c '
    grep -q ">(of 3 s: stopped, BRAUN_ERR_ACCURACY)" longname-chart.svg &&
    { grep -o "<text x=\"[^\"]*\" y=\"[^\"]*\"[^>]*>t \[s\]<" longname-chart.svg | sed "s/<text x=\"\([^\"]*\)\" y=\"\([^\"]*\)\".*/L \1 \2/"
      grep "font-size=\"11\"" longname-chart.svg | sed "s/.*x=\"\([^\"]*\)\" y=\"\([^\"]*\)\"[^>]*>\(.*\)<\/text>/T \1 \2 \3/"; } |
    awk "\$1 == \"L\" { ly = \$3; next }
         \$1 == \"T\" { n++; x = \$2; y = \$3; t = \$0; sub(/^T [^ ]* [^ ]* /, \"\", t)
                      if (x + 0.6 * 11 * length(t) > 800 || y < ly + 11) bad = 1 }
         END { exit !(ly > 0 && n >= 1 && !bad) }"'
# A run that stops before --from draws nothing, and says so: only the
# guard's message was printed, and the file stayed as it was.
echo old > before.svg
"$BRAUN" plot pendulum --dt 0.25 --t-end 3 --from 0.3 -o before.svg 2> before.err; rc=$?
check "plot: a run stopped before --from exits 1, says no picture was written and why, file as it was" \
    sh -c '[ "$1" -eq 1 ] && [ "$(cat before.svg)" = old ] &&
           grep -q "no picture written (-o before.svg left as it was): the run stopped at t = 0 s, before --from 0.3" before.err' sh "$rc"
# Series past the eighth have colours of their own (link4.omega took
# link1.theta's red).
"$BRAUN" plot chain-5 --dt 1e-3 --t-end 0.5 --plot link1.theta,link2.theta,link3.theta,link4.theta,link5.theta,link1.omega,link2.omega,link3.omega,link4.omega,link5.omega -o many.svg 2> /dev/null
check "plot: 10 chart series in 10 colours" \
    [ "$(grep -o '<polyline fill="none" stroke="[^"]*"' many.svg | sort -u | wc -l)" -eq 10 ]
# --plot traj_err of a scene with no reference drew an empty chart with
# exit 0 (its column is empty); now a usage error naming the reason. A
# built-in model has one and charts it.
echo old > te.svg
"$BRAUN" plot chain-5 --dt 1e-2 --t-end 0.5 --plot traj_err -o te.svg 2> te.err; rc=$?
check "plot --plot traj_err without a reference: exit 2, says so, file as it was" \
    sh -c '[ "$1" -eq 2 ] && [ "$(cat te.svg)" = old ] && grep -q "has no reference solution" te.err' sh "$rc"
check "plot --plot traj_err of the pendulum (a reference): exit 0" \
    "$BRAUN" plot pendulum --dt 1e-2 --t-end 0.5 --plot traj_err -o te2.svg
# An adaptive run's uneven steps: frames picked as the kept state nearest
# even times repeated three states and skipped three (21 states, "21
# configurations", 18 drawn); now every state once, and a caption that
# counts the configurations drawn.
"$BRAUN" plot pendulum --integrator dopri5 --rtol 1e-3 --atol 1e-3 --dt 1e-3 --t-end 3 --frames 25 -o dpk.svg 2> /dev/null
check "plot dopri5, 21 states, --frames 25: 21 distinct frames" \
    [ "$(grep -o 'data-t="[^"]*"' dpk.svg | sort -u | wc -l)" -eq "$(grep -c 'class="frame"' dpk.svg)" ]
"$BRAUN" plot pendulum --integrator dopri5 --rtol 1e-3 --atol 1e-3 --dt 1e-3 --t-end 3 --frames 20 -o dpk20.svg 2> /dev/null
check "plot dopri5, --frames 20: the caption counts the distinct configurations drawn" \
    [ "$(grep -o '[0-9]* configurations' dpk20.svg | head -1 | cut -d' ' -f1)" -eq "$(grep -o 'data-t="[^"]*"' dpk20.svg | sort -u | wc -l)" ]
# A spatial scene's SVG and HTML say which plane they show (the PNG's axis
# labels did; these did not).
"$BRAUN" plot spatial-arm --dt 1e-3 --t-end 0.2 --view xz -o sa-xz.svg 2> /dev/null
"$BRAUN" plot spatial-arm --dt 1e-3 --t-end 0.2 -o sa.html 2> /dev/null
check "plot spatial-arm: the SVG and HTML captions name the view's plane" \
    sh -c 'grep -q "view xz (x across, z up)" sa-xz.svg && grep -q "view xy (x across, y up)" sa.html'
# Points 1e-310 apart (subnormal): the canvas's scale overflows; the
# message said they spanned "more than the range of a double".
printf 't [s],bob.x [m],bob.y [m],bob.vx [m/s],bob.vy [m/s],pos_err [Phi_q],vel_err [Phi_q/s],energy_err [J],traj_err [q]\n0,1e-310,0,0,0,0,0,0,0\n1,-1e-310,1e-310,0,0,0,0,0,0\n' > tiny310.csv
"$BRAUN" plot pendulum --traj tiny310.csv -o t310.svg 2> t310.err; rc=$?
check "plot --traj of points 1e-310 apart: exit 2, the message names a span below a double's normal range" \
    sh -c '[ "$1" -eq 2 ] && grep -q "span less than a double.s smallest normal number" t310.err' sh "$rc"
# A large scene's animation says how large it is (131 MB for a chain of
# 1000 links at the default 400 frames, silently).
"$BRAUN" gen chain 1000 -o ch1000.json 2> /dev/null
"$BRAUN" plot ch1000.json --sparse --backend suitesparse --dt 1e-3 --t-end 0.4 -o ch1000.html 2> ch1000.err; rc=$?
rm -f ch1000.html
check "plot .html of a 1000-link chain: exit 0 and a note of its size with the way to shrink it" \
    sh -c '[ "$1" -eq 0 ] && grep -q "^braun: note: ch1000.html is [0-9]* MB (400 frames): --frames N makes it smaller" ch1000.err' sh "$rc"
# z of a planar scene is 0 throughout: --view refused it, --plot charted it.
"$BRAUN" plot slider-crank --dt 1e-2 --t-end 1 --plot crank.A.z -o z.svg 2> z.err; rc=$?
check "plot --plot crank.A.z of a planar scene: exit 2, says it is planar" \
    sh -c '[ "$1" -eq 2 ] && grep -q "is planar (no z)" z.err' sh "$rc"
# A slider's rail covers its block's travel: it reached as far as the
# scene's initial size, and the slider-crank's block ran past both ends.
"$BRAUN" plot slider-crank.json --dt 1e-2 --t-end 3 --points rod.B -o rail.svg 2> /dev/null
check "plot: the slider's rail spans the block's path" sh -c '
    path=$(grep -o "<polyline[^>]*points=\"[^\"]*\"" rail.svg | head -1 | sed "s/.*points=\"//; s/\"//" | tr " " "\n" |
           awk -F, "NR == 1 { lo = \$1; hi = \$1 } { if (\$1 < lo) lo = \$1; if (\$1 > hi) hi = \$1 } END { print lo, hi }")
    rail=$(grep -o "<line[^>]*stroke-dasharray[^>]*>" rail.svg | head -1 | sed "s/.*x1=\"\([^\"]*\)\".*x2=\"\([^\"]*\)\".*/\1 \2/")
    echo "$path $rail" | awk "{ exit !(NF == 4 && \$3 < \$1 && \$4 > \$2) }"'
# The animation's time readout tells its frames apart: a 0.03 s run read
# "t = 0.000 s" for its first 13 frames (31 labels for 400 frames). Its
# script run under a minimal DOM (tests/cli/html_labels.js, node).
"$BRAUN" plot a03-andrews --dt 1e-5 --t-end 0.03 -o andrews.html 2> /dev/null
if have node; then
    check "plot .html: 400 frames, 400 distinct time labels" \
        [ "$(node "$TOP/tests/cli/html_labels.js" andrews.html | sort -u | wc -l)" -eq 400 ]
else
    skip "plot .html: 400 frames, 400 distinct time labels" "node not installed"
fi

cd .. || exit 1

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
