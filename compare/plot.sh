#!/bin/sh
# Plots of a comparison study (docs/compare.md), PNG and SVG, with gnuplot:
#   wp_SCENE_T        trajectory error against CPU time, every method (work-precision)
#   steps_SCENE_T     errors and CPU time against the step size (the paper's Fig. 4)
#   history_SCENE_T   error histories at h = 1e-2 (the paper's Figs. 3 and 7)
#   slider_SCENE      slider position against time at h = 5e-2 (the paper's Fig. 2)
#   fig6_SCENE_T      the observable point against time over a long run (the paper's Fig. 6)
#   tol_SCENE_T       adaptive methods: error and time reached against the tolerance
# Usage: sh compare/plot.sh DIR   (reads DIR/runs.csv, history.csv, targets.csv, trace.csv)
#        sh compare/plot.sh --series   (the series as read: key|label|colour|dash|point|in)
# The series, their legends, styles and which plot shows which: the table
# compare/series.tsv (through compare/series.awk, as the C programs read it).
# Every axis has its unit (targets.csv gives those of Φ_q and q per scene).
# A series with runs that did not reach T says so in its legend entry
# ("— 2 of 6 runs stopped"); the reference's own error (targets.csv) is drawn
# as a floor; an axis is clipped at 1e3 × the largest value of the runs that
# reached T, so that one diverged run cannot flatten the others, and the
# plot says so. DIR/plots.tsv receives one line per plot and note
# (NAME<TAB>NOTE) for the report's captions.
set -eu
here=$(dirname "$0")
series_all=$(awk -f "$here/series.awk" -v out=plot "$here/series.tsv")
if [ "${1:-}" = --series ]; then
    printf '%s\n' "$series_all"
    exit 0
fi
dir=${1:?usage: sh compare/plot.sh DIR}
runs="$dir/runs.csv"
hist="$dir/history.csv"
targets="$dir/targets.csv"
trace="$dir/trace.csv"
notes="$dir/plots.tsv"
[ -s "$runs" ] || { echo "plot.sh: no $runs" >&2; exit 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/braun-plot.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
: > "$notes"

# tagged TAG: the keys of the series whose "in" has TAG, in table order.
tagged() {
    printf '%s\n' "$series_all" | awk -F'|' -v tag="$1" '
        { n = split($6, t, ","); for (i = 1; i <= n; i++) if (t[i] == tag) { printf "%s%s", sep, $1; sep = " " } }
        END { print "" }'
}

# Terminals: PNG for the report, SVG beside it.
png='set terminal pngcairo size 1200,900 font "DejaVu Sans,11" linewidth 1.5 enhanced'
svg='set terminal svg size 1200,900 dynamic font "DejaVu Sans,11" linewidth 1.5 enhanced'

# target_field SCENE T COLUMN: a field of targets.csv ("" if none).
target_field() {
    [ -s "$targets" ] || { echo ""; return; }
    awk -F, -v sc="$1" -v T="$2" -v c="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i; next }
        $1 == sc && $2 == T && k { print $k; exit }' "$targets"
}

# select_runs SCENE T KEY COLS [ok|all]: rows of runs.csv as "x y" lines.
select_runs() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" -v cols="$4" -v which="${5:-ok}" '
        BEGIN { split(key, k, ":"); n = split(cols, c, " ") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        $11 != "NOT_BUILT" && $11 != "UNSUPPORTED" && (which == "all" || $11 == "ok") {
            line = ""
            for (i = 1; i <= n; i++) {
                v = c[i]
                if (v ~ /^\$/) { v = substr(v, 2); val = $(v) }
                else if (v == "frac") val = $12 / $2
                else val = $(v)
                line = line (i > 1 ? " " : "") val
            }
            print line
        }' "$runs"
}

# stopped SCENE T KEY: "k of n" runs of the series that did not reach T
# (peers not built or not able to express the scene do not count), or "".
stopped() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" '
        BEGIN { split(key, k, ":") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        $11 != "NOT_BUILT" && $11 != "UNSUPPORTED" { n++; if ($11 != "ok") f++ }
        END { if (f) printf "%d of %d", f, n }' "$runs"
}

# status_of SCENE T KEY H RTOL: the status of one run ("" if none).
status_of() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" -v h="$4" -v r="$5" '
        BEGIN { split(key, k, ":") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        (($6 != "nan" && $6 + 0 == h + 0) || ($6 == "nan" && $7 + 0 == r + 0)) {
            printf "%s %s", $11, $12; exit }' "$runs"
}

# hist_h SCENE T KEY min|max: the smallest or largest step size with a
# history for this series (h = 1e-2 and 5e-2, scaled with the scene).
hist_h() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" -v which="$4" '
        BEGIN { split(key, k, ":") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] && $6 != "nan" {
            if (m == "" || (which == "min" && $6 + 0 < m + 0) || (which == "max" && $6 + 0 > m + 0)) m = $6
        } END { print (m == "" ? "nan" : m) }' "$hist"
}

# select_hist SCENE T KEY H_OR_RTOL: history rows of one run.
select_hist() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" -v x="$4" '
        BEGIN { split(key, k, ":") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        (($6 != "nan" && $6 + 0 == x + 0) || ($7 != "nan" && $7 + 0 == x + 0)) {
            print $8, $9, $10, $11, $12, $13, $14, $15
        }' "$hist"
}

# exp10 X: "10^{-2}" for 0.01, else X as %g (for titles).
exp10() {
    awk -v x="$1" 'BEGIN { if (x <= 0) { print x; exit }; l = log(x) / log(10); r = int(l + (l < 0 ? -0.5 : 0.5))
        if (l - r < 1e-9 && r - l < 1e-9) printf "10^{%d}\n", r; else printf "%g\n", x }'
}

# legend KEY TITLE SCENE T: the legend entry, with the runs that stopped.
legend() {
    s=$(stopped "$3" "$4" "$1")
    if [ -n "$s" ]; then printf '%s — %s runs stopped' "$2" "$s"; else printf '%s' "$2"; fi
}

# drawn_title KEY SCENE T STATUS: the legend entry of a plot that draws one
# run of the series (histories, Fig. 2), whose status is STATUS ("ok 20",
# "BRAUN_ERR_DIVERGED 13.75"): the label, "— stopped: STATUS at t = …" if
# that run stopped, and how many of the series' other runs stopped, worded
# so that it is not read as the drawn run's. (The count of every run of the
# series, "— 1 of 4 runs stopped", said nothing of the one drawn.)
drawn_title() {
    label=$(printf '%s\n' "$series_all" | awk -F'|' -v k="$1" '$1 == k { print $2 }')
    others=$(awk -F, -v sc="$2" -v T="$3" -v key="$1" -v st="${4% *}" '
        BEGIN { split(key, k, ":") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        $11 != "NOT_BUILT" && $11 != "UNSUPPORTED" { n++; if ($11 != "ok") f++ }
        END { n--; if (st != "ok") f--; if (f > 0) printf "%d of its %d other run%s", f, n, n == 1 ? "" : "s" }' "$runs")
    case $4 in
    "ok "*) printf '%s' "$label"; [ -z "$others" ] || printf ' — reached T' ;;
    *) printf '%s — stopped: %s' "$label" "$(stop_text "${4% *}" "${4#* }")" ;;
    esac
    [ -z "$others" ] || printf ' (%s stopped)' "$others"
}

# plot_cmd FILE_PREFIX USING SCENE T [KEYS]: a gnuplot "plot" list over the
# series whose data file has at least one positive finite value in the
# plotted column (log axes drop the rest; gnuplot stops on an
# all-undefined plot).
plot_cmd() {
    prefix=$1 using=$2 psc=$3 pT=$4 keys=${5:-}
    ycol=${using#*:}
    printf '%s\n' "$series_all" | while IFS='|' read -r key title colour dash pt _; do
        if [ -n "$keys" ]; then
            case " $keys " in *" $key "*) ;; *) continue ;; esac
        fi
        f="$prefix.$(printf '%s' "$key" | tr ':' '_').dat"
        if [ ! -s "$f" ] || ! awk -v c="$ycol" '$c != "nan" && $c + 0 > 0 && $c + 0 < 1e300 { found = 1 } END { exit !found }' "$f"; then
            # Nothing to draw: a series whose every run stopped is named
            # in the legend all the same (an entry without points).
            s=$(stopped "$psc" "$pT" "$key")
            all=$(awk -F, -v sc="$psc" -v T="$pT" -v key="$key" 'BEGIN { split(key, k, ":") }
                NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
                $11 != "NOT_BUILT" && $11 != "UNSUPPORTED" { n++; if ($11 == "ok") ok++ }
                END { if (n && !ok) print n }' "$runs")
            [ -n "$all" ] || continue
            printf 'NaN with linespoints lc rgb "%s" dt %s pt %s ps 1.1 title "%s — all %s runs stopped", ' \
                "$colour" "$dash" "$pt" "$title" "$all"
            continue
        fi
        # A plot of one run per series (histories) names a run that stopped
        # in its own words (FILE.title).
        if [ -s "$f.title" ]; then t=$(cat "$f.title"); else t=$(legend "$key" "$title" "$psc" "$pT"); fi
        printf '"%s" using %s with linespoints lc rgb "%s" dt %s pt %s ps 1.1 title "%s", ' \
            "$f" "$using" "$colour" "$dash" "$pt" "$t"
    done | sed 's/, $//'
}

# ymax_of COL FILES...: 1e3 × the largest positive finite value in column
# COL of the files (those of the runs that reached T), or "" if none.
ymax_of() {
    col=$1; shift
    [ $# -gt 0 ] || { echo ""; return; }
    cat "$@" 2>/dev/null | awk -v c="$col" '$c != "nan" && $c + 0 > 0 && $c + 0 < 1e300 { if ($c + 0 > m) m = $c + 0 }
        END { if (m > 0) printf "%.3g\n", 1e3 * m }'
}

# over COL LIMIT FILES...: how many values exceed LIMIT.
over() {
    col=$1 lim=$2; shift 2
    cat "$@" 2>/dev/null | awk -v c="$col" -v l="$lim" '$c != "nan" && $c + 0 > l + 0 { n++ } END { print n + 0 }'
}

# The panel of a multiplot that carries the shared legend: the one with the
# most series (mostkeyed P1 P2 ...), and the legend line for panel i.
mostkeyed() {
    best=1 bestn=-1 i=1
    for p in "$@"; do
        n=$(printf '%s' "$p" | grep -o ' title "' | wc -l)
        [ "$n" -gt "$bestn" ] && { best=$i; bestn=$n; }
        i=$((i + 1))
    done
    echo "$best"
}
keyfor() { # keyfor PANEL BEST ROWS
    if [ "$1" -eq "$2" ]; then
        echo "set key at screen 0.5,0.005 center bottom vertical maxrows $3 box opaque font \",9\" samplen 3"
    else
        echo "set key off"
    fi
}
# The legend below the plot in two columns: legend_rows for N entries, the
# canvas height that leaves 850 px to the panels, and the bottom margin
# (a fraction of the canvas) that holds the legend.
# A column is as wide as its longest title: two columns of titles over
# about 64 characters do not fit 1400 px, and gnuplot's PNG terminal then
# drew the first column alone (the MuJoCo and Simbody series of four
# work-precision plots had no legend); those legends get one column.
# legend_rows N [PLOT]: PLOT is the plot command whose titles are measured.
legend_rows() {
    if [ -n "${2:-}" ] && [ "$(longest_title "$2")" -gt 64 ]; then echo "$1"
    else echo $(( ($1 + 1) / 2 )); fi
}
longest_title() { printf '%s' "$1" | grep -o ' title "[^"]*"' | awk '{ n = length($0) - 9; if (n > m) m = n } END { print m + 0 }'; }
canvas_height() { echo $(( 850 + 19 * $1 + 30 )); }
bottom_margin() { awk -v r="$1" -v h="$2" 'BEGIN { printf "%.3f\n", (19 * r + 60) / h }'; }
entries() { printf '%s' "$1" | grep -o ' title "' | wc -l; }

# A panel with no data still needs something to plot (an invisible constant).
blank='1 notitle lc rgb "white"'

# render NAME SCRIPT [HEIGHT]: PNG and SVG of one gnuplot script (1400 px
# wide; HEIGHT default 900 px: legends below the panels take more).
render() {
    name=$1 script=$2 height=${3:-900}
    { echo "$png" | sed "s/size 1200,900/size 1400,$height/"; echo "set output '$dir/$name.png'"
      cat "$script"; echo "unset output"
      echo "$svg" | sed "s/size 1200,900/size 1400,$height/"; echo "set output '$dir/$name.svg'"
      cat "$script"; echo "unset output"
    } > "$tmp/$name.gp"
    if ! gnuplot "$tmp/$name.gp" 2> "$tmp/$name.err"; then
        echo "plot.sh: gnuplot failed on $name:" >&2
        cat "$tmp/$name.err" >&2
        exit 1
    fi
    echo "plot.sh: $dir/$name.png, .svg" >&2
}

note() { printf '%s\t%s\n' "$1" "$2" >> "$notes"; }

# stop_text STATUS T: "IDA\\_CONV\\_FAIL at t = 191.6 s" for a legend (gnuplot's
# enhanced text would make the underscores subscripts).
stop_text() {
    printf '%s at t = %s s' "$(printf '%s' "$1" | sed 's/_/\\\\_/g')" "$(awk -v t="$2" 'BEGIN { printf "%.4g", t }')"
}

# variant_text V: a sweep setting in words (as the report's cmp_variant_text).
variant_text() {
    case $1 in
    solimp=0.9) echo "impedance d = 0.9–0.95 (MuJoCo's default)" ;;
    solimp=0.99) echo "impedance d = 0.99–0.999" ;;
    tc=0.02) echo "solref time constant 0.02 s" ;;
    tc=*h) echo "solref time constant ${1#tc=}" ;;
    zeta=*) echo "damping ratio ζ = ${1#zeta=}" ;;
    tol=*) echo "solver tolerance ${1#tol=}, 1000 iterations" ;;
    pgs) echo "PGS solver" ;;
    cg) echo "CG solver" ;;
    ctol=*) echo "constraint tolerance ${1#ctol=}" ;;
    defaults) echo "MuJoCo's default softness" ;;
    *) echo "$1" ;;
    esac
}

common='set grid lw 0.5 lc rgb "#dddddd"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set key outside right top box opaque font ",10"
set datafile missing "nan"'

pairs=$(awk -F, 'NR > 1 { print $1 "," $2 }' "$runs" | sort -u)
# plot_pair SCENE,T: every plot of one scene and horizon (runs in the
# background, PLOT_JOBS at a time: the plots of a pair are its own files).
plot_pair() {
    pair=$1
    sc=${pair%,*} T=${pair#*,}
    base="$tmp/$sc-$T"
    qu=$(target_field "$sc" "$T" q_unit); qu=${qu:-m; rad}
    pu=$(target_field "$sc" "$T" phi_unit); pu=${pu:-m}
    floor=$(target_field "$sc" "$T" floor_traj)
    pfloor=$(target_field "$sc" "$T" floor_point)
    refname=$(target_field "$sc" "$T" reference)
    # A floor line: the reference's own error, when it is known and positive.
    floorline() { # floorline VALUE
        case $1 in ''|nan|-nan|inf|0|0.0*) return ;; esac
        awk -v v="$1" 'BEGIN { exit !(v + 0 > 0) }' || return 0
        printf ', %s with lines lc rgb "#888888" dt 3 lw 2 title "reference'"'"'s own error (%s)"' "$1" "$refname"
    }

    # ---- work-precision (runs that reached T)
    printf '%s\n' "$series_all" | while IFS='|' read -r key rest; do
        select_runs "$sc" "$T" "$key" "13 31" > "$base.wp.$(printf '%s' "$key" | tr ':' '_').dat"
    done
    p=$(plot_cmd "$base.wp" "1:2" "$sc" "$T")
    if [ -n "$p" ]; then
        rows=$(legend_rows $(( $(entries "$p") + 1 )) "$p")
        ht=$(canvas_height "$rows")
        cat > "$base.gp" <<EOF
$common
set title "$sc, T = $T s: trajectory error against CPU time (runs that reached T; the legend names those that stopped)"
set key below vertical maxrows $rows box opaque font ",9" samplen 3
set xlabel "CPU time [s], best of k runs" offset 0,0.6
set ylabel "max_t ‖q(t) − q_{ref}(t)‖_2 [$qu]"
plot $p$(floorline "$floor")
EOF
        render "wp_${sc}_$T" "$base.gp" "$ht"
    fi

    # ---- Fig. 4: against the step size
    fixed=$(tagged steps)
    for key in $fixed; do
        select_runs "$sc" "$T" "$key" "6 25 29 31 13" > "$base.st.$(printf '%s' "$key" | tr ':' '_').dat"
    done
    p1=$(plot_cmd "$base.st" "1:2" "$sc" "$T" "$fixed")
    p2=$(plot_cmd "$base.st" "1:3" "$sc" "$T" "$fixed")
    p3=$(plot_cmd "$base.st" "1:4" "$sc" "$T" "$fixed")
    p4=$(plot_cmd "$base.st" "1:5" "$sc" "$T" "$fixed")
    if [ -n "$p1$p2$p3$p4" ]; then
        k=$(mostkeyed "$p1" "$p2" "$p3" "$p4")
        eval "pk=\$p$k"
        rows=$(legend_rows "$(entries "$pk")" "$pk")
        ht=$(canvas_height "$rows")
        bm=$(bottom_margin "$rows" "$ht")
        p1=${p1:-$blank} p2=${p2:-$blank} p3=${p3:-$blank} p4=${p4:-$blank}
        cat > "$base.gp" <<EOF
$common
set multiplot layout 2,2 title "$sc, T = $T s: maxima over the run against the step size (runs that reached T; paper's Fig. 4)" margins 0.08,0.98,$bm,0.93 spacing 0.08,0.1
set xlabel "step size h [s]"
set ylabel "max ‖Φ_q‖ [$pu]"
$(keyfor 1 "$k" "$rows")
plot $p1
set ylabel "max |Φ_e| [J]"
$(keyfor 2 "$k" "$rows")
plot $p2
set ylabel "max ‖q − q_{ref}‖ [$qu]"
$(keyfor 3 "$k" "$rows")
plot $p3$(floorline "$floor")
set ylabel "CPU time [s]"
$(keyfor 4 "$k" "$rows")
plot $p4
unset multiplot
EOF
        render "steps_${sc}_$T" "$base.gp" "$ht"
    fi

    # ---- adaptive methods against the tolerance
    tolk=$(tagged tol)
    for key in $tolk; do
        k=$(printf '%s' "$key" | tr ':' '_')
        select_runs "$sc" "$T" "$key" "7 31" > "$base.ie.$k.dat"
        select_runs "$sc" "$T" "$key" "7 frac" all > "$base.it.$k.dat"
    done
    p1=$(plot_cmd "$base.ie" "1:2" "$sc" "$T" "$tolk")
    p2=$(plot_cmd "$base.it" "1:2" "$sc" "$T" "$tolk")
    if [ -n "$p2" ]; then
        rows=$(legend_rows "$(entries "$p2")" "$p2")
        ht=$(canvas_height "$rows")
        bm=$(bottom_margin "$rows" "$ht")
        cat > "$base.gp" <<EOF
$common
set multiplot layout 2,1 title "$sc, T = $T s: adaptive methods against their tolerance (rtol = atol)" margins 0.08,0.98,$bm,0.93 spacing 0.08,0.1
set xlabel "rtol (relative tolerance) [–]"
set ylabel "max ‖q − q_{ref}‖ [$qu] (reached T)"
set key off
plot ${p1:-$blank}$(floorline "$floor")
unset logscale y
set format y "%g"
set yrange [0:1.05]
set ylabel "time reached / T [–]"
set key at screen 0.5,0.005 center bottom vertical maxrows $rows box opaque font ",9" samplen 3
plot $p2
unset multiplot
EOF
        render "tol_${sc}_$T" "$base.gp" "$ht"
    fi

    # ---- Figs. 3 and 7: histories at h = 1e-2 (adaptive methods at rtol 1e-8)
    if [ -s "$hist" ]; then
        hk=$(tagged history)
        okfiles="" hstep=""
        for key in $hk; do
            # fixed-step series: the smallest h with a history; the others rtol 1e-8
            x=$(hist_h "$sc" "$T" "$key" min)
            f="$base.h.$(printf '%s' "$key" | tr ':' '_').dat"
            if [ "$x" != nan ]; then
                [ -n "$hstep" ] || hstep=$x
                st=$(status_of "$sc" "$T" "$key" "$x" nan)
            else
                x=1e-08
                st=$(status_of "$sc" "$T" "$key" nan "$x")
            fi
            select_hist "$sc" "$T" "$key" "$x" > "$f"
            case $st in "ok "*) okfiles="$okfiles $f" ;; esac
            [ -z "$st" ] || drawn_title "$key" "$sc" "$T" "$st" > "$f.title"
        done
        p1=$(plot_cmd "$base.h" "1:2" "$sc" "$T" "$hk")
        p3=$(plot_cmd "$base.h" "1:4" "$sc" "$T" "$hk")
        if [ -n "$p1$p3" ]; then
            pcol=6
            if ! awk '$6 != "nan" { found = 1 } END { exit !found }' "$base.h.braun_rk4_-.dat" 2>/dev/null; then
                pcol=5
            fi
            p2=$(plot_cmd "$base.h" "1:3" "$sc" "$T" "$hk")
            p4=$(plot_cmd "$base.h" "1:$pcol" "$sc" "$T" "$hk")
            [ -n "$p4" ] || { pcol=5; p4=$(plot_cmd "$base.h" "1:$pcol" "$sc" "$T" "$hk"); }
            plabel="ε, error of the point [m]"
            pf=$pfloor
            [ $pcol -eq 6 ] || { plabel="‖q − q_{ref}‖ [$qu]"; pf=$floor; }
            k=$(mostkeyed "$p1" "$p2" "$p3" "$p4")
            eval "pk=\$p$k"
            rows=$(legend_rows "$(entries "$pk")" "$pk")
            ht=$(canvas_height "$rows")
            bm=$(bottom_margin "$rows" "$ht")
            # A reference known at one time only (Andrews): points, not lines.
            sparse=$(cat "$base".h.*.dat 2>/dev/null | awk -v c="$pcol" '$c != "nan" && $c + 0 > 0 { n++ } END { print (n < 20) }')
            # Clip each panel at 1e3 × the largest value of the runs that
            # reached T (a run that diverged before it stopped cannot
            # flatten the others).
            yr() { # yr COL: the panel's "set yrange"
                # shellcheck disable=SC2086
                lim=$(ymax_of "$1" $okfiles)
                if [ -n "$lim" ]; then echo "set yrange [*:$lim]"; else echo "set yrange [*:*]"; fi
            }
            y1=$(yr 2) y2=$(yr 3) y3=$(yr 4) y4=$(yr "$pcol")
            clipnote=""
            for c in "2:‖Φ_q‖" "3:‖dΦ_q/dt‖" "4:|Φ_e|" "$pcol:ε"; do
                col=${c%%:*} nm=${c#*:}
                # shellcheck disable=SC2086
                lim=$(ymax_of "$col" $okfiles)
                [ -n "$lim" ] || continue
                n=$(over "$col" "$lim" "$base".h.*.dat)
                [ "$n" -eq 0 ] || clipnote="${clipnote:+$clipnote, }$nm at $lim ($n binned values above)"
            done
            p1=${p1:-$blank} p2=${p2:-$blank} p3=${p3:-$blank} p4=${p4:-$blank}
            [ "$sparse" = 1 ] && p4=$(printf '%s' "$p4" | sed 's/with linespoints/with points/g')
            hs=$(exp10 "${hstep:-0.01}")
            cat > "$base.gp" <<EOF
$common
unset logscale x
set format x "%g"
set xrange [0:$T]
set multiplot layout 2,2 title "$sc, T = $T s: errors along the run, fixed steps h = $hs s, adaptive rtol = 10^{-8} (paper's Figs. 3, 7)" margins 0.08,0.98,$bm,0.93 spacing 0.08,0.1
set xlabel "t [s]"
set ylabel "‖Φ_q‖ [$pu]"
$y1
$(keyfor 1 "$k" "$rows")
plot $p1
set ylabel "‖[dΦ_q/dt; Φ_v]‖ [$pu/s]"
$y2
$(keyfor 2 "$k" "$rows")
plot $p2
set ylabel "|Φ_e| [J]"
$y3
$(keyfor 3 "$k" "$rows")
plot $p3
set ylabel "$plabel"
$y4
$(keyfor 4 "$k" "$rows")
plot $p4$(floorline "$pf")
unset multiplot
EOF
            if [ -n "$clipnote" ]; then
                clipnote="clipped at 10³ × the largest value of the runs that reached T: $clipnote"
                # Drawn with the first panel (a label set after the last plot
                # of a multiplot is never drawn), then taken away.
                awk '{ print }
                    /^set multiplot/ { print "set label 99 \"axes clipped at 10³ × the largest value of the runs that reached T: a run that stopped went above (report: which)\" at screen 0.5,0.957 center font \",10\" tc rgb \"#aa0000\"" }
                    /^plot / && !done { print "unset label 99"; done = 1 }' \
                    "$base.gp" > "$base.gp2" && mv "$base.gp2" "$base.gp"
                note "history_${sc}_$T" "$clipnote"
            fi
            sed -i 's/with linespoints/with lines/g; s/ with lines\( lc rgb "[^"]*" dt [0-9]*\) pt [0-9]* ps 1.1/ with lines\1/g' "$base.gp"
            render "history_${sc}_$T" "$base.gp" "$ht"
        fi
    fi

    # ---- Fig. 2: the slider (the observable point's x) at h = 5e-2
    tmin=$(awk -F, 'NR > 1 && $1 == "slider-crank" { if (m == "" || $2 + 0 < m + 0) m = $2 } END { print m }' "$runs")
    if [ "$sc" = slider-crank ] && [ "$T" = "$tmin" ] && [ -s "$hist" ]; then
        sk=$(tagged slider)
        for key in $sk; do
            x=$(hist_h "$sc" "$T" "$key" max)
            f="$base.s.$(printf '%s' "$key" | tr ':' '_').dat"
            select_hist "$sc" "$T" "$key" "$x" > "$f"
            st=$(status_of "$sc" "$T" "$key" "$x" nan)
            [ -z "$st" ] || drawn_title "$key" "$sc" "$T" "$st" > "$f.title"
        done
        p=$(plot_cmd "$base.s" "1:7" "$sc" "$T" "$sk")
        hs=$(exp10 "$(hist_h "$sc" "$T" braun:rk4:- max)")
        if [ -n "$p" ]; then
            ref="\"$base.s.braun_rk4_-.dat\" using 1:8 with lines lc rgb \"black\" lw 2.5 title \"numerically exact (Eq. 24, rk8pd)\""
            cat > "$base.gp" <<EOF
set grid lw 0.5 lc rgb "#dddddd"
set datafile missing "nan"
set multiplot layout 2,1 title "slider-crank: slider position x_s = x_2 + (l/2) cos θ_2, h = $hs s (paper's Fig. 2)"
set key outside right top font ",9" box opaque
set xlabel "t [s]"
set ylabel "x_s [m]"
set yrange [-2.6:2.6]
set xrange [0:$(awk -v T="$T" 'BEGIN { print T / 10 }')]
plot $ref, $p
set xrange [$(awk -v T="$T" 'BEGIN { print T - T / 10 }'):$T]
plot $ref, $p
unset multiplot
EOF
            sed -i 's/with linespoints/with lines/g; s/ pt [0-9]* ps 1.1//g' "$base.gp"
            render "slider_${sc}" "$base.gp"
        fi
    fi
}

jobs_max=${PLOT_JOBS:-2} pids="" failed_pairs=0
for pair in $pairs; do
    plot_pair "$pair" &
    pids="$pids $!"
    set -- $pids
    if [ $# -ge "$jobs_max" ]; then
        wait "$1" || failed_pairs=$((failed_pairs + 1))
        shift
        pids="$*"
    fi
done
for p in $pids; do wait "$p" || failed_pairs=$((failed_pairs + 1)); done
[ "$failed_pairs" -eq 0 ] || { echo "plot.sh: $failed_pairs scene(s) failed to plot" >&2; exit 1; }

# ---- Fig. 6: the four-bar's x3 against time over the longest horizon, at
# the paper's h = 1e-2 (braun, without energy correction, Baumgarte, the
# minimal ODE, RK4 + projection), and each peer's most accurate run that
# reached T (else the one that got furthest).
if [ -s "$trace" ]; then
    for sc in four-bar; do
        T=$(awk -F, -v sc="$sc" 'NR > 1 && $1 == sc { if ($2 + 0 > m + 0) m = $2 } END { print m }' "$trace")
        [ -n "$T" ] || continue
        base="$tmp/f6-$sc"
        # pick KEY H RTOL LABEL: one trace into a file; the plot entry.
        entries="" n=0
        add_trace() { # add_trace METHOD INTEG VARIANT H RTOL TITLE COLOUR DASH
            n=$((n + 1))
            awk -F, -v sc="$sc" -v T="$T" -v m="$1" -v i="$2" -v v="$3" -v h="$4" -v r="$5" '
                NR > 1 && $1 == sc && $2 == T && $3 == m && $4 == i && $5 == v &&
                (($6 != "nan" && $6 + 0 == h + 0) || ($6 == "nan" && $7 + 0 == r + 0)) { print $8, $9, $10 }' \
                "$trace" > "$base.$n.dat"
            [ -s "$base.$n.dat" ] || return 0
            [ -n "$refdat" ] || refdat="$base.$n.dat"
            entries="$entries, \"$base.$n.dat\" using 1:2 with lines lc rgb \"$7\" dt $8 lw 1.5 title \"$6\""
        }
        refdat="" drawn=""
        # the paper's methods at h = 1e-2, by their series' labels and styles
        for key in braun:rk4:- braun-noenergy:rk4:- baumgarte:rk4:- ode-rk4:rk4:- projection:rk4:-; do
            line=$(printf '%s\n' "$series_all" | awk -F'|' -v k="$key" '$1 == k')
            [ -n "$line" ] || continue
            IFS='|' read -r _ title colour dash _ _ <<EOF
$line
EOF
            m=${key%%:*} rest=${key#*:} i=${rest%%:*} v=${rest#*:}
            st=$(status_of "$sc" "$T" "$key" 0.01 nan)
            case $st in ""|"ok "*) ;; *) title="$title — stopped: $(stop_text "${st% *}" "${st#* }")" ;; esac
            add_trace "$m" "$i" "$v" 0.01 nan "$title" "$colour" "$dash"
            # the title names the methods drawn, not those of the paper
            [ -s "$base.$n.dat" ] || continue
            case $m in braun-noenergy) w=braun ;; baumgarte) w=Baumgarte ;; ode-rk4) w="the ODE" ;;
                       projection) w="RK4 + projection" ;; *) w=$m ;; esac
            case "|$drawn|" in *"|$w|"*) ;; *) drawn="${drawn:+$drawn|}$w" ;; esac
        done
        # "braun, the ODE and RK4 + projection"
        drawn=$(printf '%s' "$drawn" | awk -F'|' '{ s = $1; for (i = 2; i <= NF; i++) s = s (i < NF ? ", " : " and ") $i; print s }')
        # each peer's most accurate run that reached T (else the furthest)
        for peer in mujoco simbody; do
            best=$(awk -F, -v sc="$sc" -v T="$T" -v p="$peer" '
                NR > 1 && $1 == sc && $2 == T && $3 == p && $11 != "NOT_BUILT" && $11 != "UNSUPPORTED" {
                    ok = ($11 == "ok"); e = $31 + 0; tr = $12 + 0
                    if (ok && $31 != "nan" && (!bok || e < be)) { bok = 1; be = e; b = $0 }
                    else if (!bok && (b == "" || tr > bt)) { bt = tr; b = $0 }
                } END { print b }' "$runs")
            [ -n "$best" ] || continue
            m=$(echo "$best" | cut -d, -f3) i=$(echo "$best" | cut -d, -f4) v=$(echo "$best" | cut -d, -f5)
            h=$(echo "$best" | cut -d, -f6) r=$(echo "$best" | cut -d, -f7)
            st=$(echo "$best" | cut -d, -f11) tr=$(echo "$best" | cut -d, -f12) err=$(echo "$best" | cut -d, -f31)
            key="$m:$i:$v"
            line=$(printf '%s\n' "$series_all" | awk -F'|' -v k="$key" '$1 == k')
            if [ -n "$line" ]; then
                IFS='|' read -r _ title colour dash _ _ <<EOF
$line
EOF
            else
                title=$(printf '%s\n' "$series_all" | awk -F'|' -v m="$m" -v i="$i" 'index($1, m ":" i ":") == 1 { print $2; exit }')
                title="${title:-$m $i} — $(variant_text "$v");"
                colour=$(printf '%s\n' "$series_all" | awk -F'|' -v m="$m" 'index($1, m ":") == 1 { print $3; exit }')
                dash=1
            fi
            if [ "$h" != nan ]; then setting="h = $(exp10 "$h") s"; else setting="rtol = $(exp10 "$r")"; fi
            if [ "$st" = ok ]; then what="its most accurate run: $setting, error $(printf '%.2g' "$err")"
            else what="no run reached T; furthest: $setting, $(stop_text "$st" "$tr")"; fi
            case $title in *";") title="$title $what" ;; *) title="$title — $what" ;; esac
            add_trace "$m" "$i" "$v" "$h" "$r" "$title" "${colour:-#999999}" "$dash"
        done
        [ -n "$entries" ] && [ -n "$refdat" ] || continue
        W=$(awk -v T="$T" 'BEGIN { print (T / 2 < 10 ? T / 2 : 10) }')
        rows=$(( n + 1 ))
        ht=$(canvas_height "$rows")
        bm=$(bottom_margin "$rows" "$ht")
        ref="\"$refdat\" using 1:3 with lines lc rgb \"black\" lw 3 title \"numerically exact (closed form)\""
        cat > "$base.gp" <<EOF
set grid lw 0.5 lc rgb "#dddddd"
set datafile missing "nan"
set multiplot layout 2,1 title "$sc: x_3 (joint 3) against time, T = $T s${drawn:+, h = 10^{-2} s for $drawn} (paper's Fig. 6)" margins 0.08,0.98,$bm,0.93 spacing 0.08,0.12
set key at screen 0.5,0.005 center bottom vertical maxrows $rows box opaque font ",9" samplen 3
set xlabel "t [s]"
set ylabel "x_3 [m]"
set yrange [0:4]
set xrange [0:$W]
plot $ref$entries
set key off
set xrange [$(awk -v T="$T" -v W="$W" 'BEGIN { print T - W }'):$T]
plot $ref$entries
unset multiplot
EOF
        render "fig6_${sc}_$T" "$base.gp" "$ht"
    done
fi
