#!/bin/sh
# Plots of a comparison study (docs/compare.md), PNG and SVG, with gnuplot:
#   wp_SCENE_T        trajectory error against CPU time, every method (work-precision)
#   steps_SCENE_T     errors and CPU time against the step size (the paper's Fig. 4)
#   history_SCENE_T   error histories at h = 1e-2 (the paper's Figs. 3 and 7)
#   slider_SCENE      slider position against time at h = 5e-2 (the paper's Fig. 2)
#   ida_SCENE_T       IDA: error and time reached against the tolerance
# Usage: sh compare/plot.sh DIR   (reads DIR/runs.csv and DIR/history.csv)
#        sh compare/plot.sh --series   (the series as read: key|label|colour|dash|point|in)
# The series, their legends, styles and which plot shows which: the table
# compare/series.tsv (through compare/series.awk, as the C programs read it).
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
[ -s "$runs" ] || { echo "plot.sh: no $runs" >&2; exit 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/braun-plot.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

# tagged TAG: the keys of the series whose "in" has TAG, in table order.
tagged() {
    printf '%s\n' "$series_all" | awk -F'|' -v tag="$1" '
        { n = split($6, t, ","); for (i = 1; i <= n; i++) if (t[i] == tag) { printf "%s%s", sep, $1; sep = " " } }
        END { print "" }'
}

# Terminals: PNG for the report, SVG beside it.
png='set terminal pngcairo size 1200,800 font "DejaVu Sans,11" linewidth 1.5'
svg='set terminal svg size 1200,800 dynamic font "DejaVu Sans,11" linewidth 1.5'

# select_runs SCENE T KEY COLS [ok|all]: rows of runs.csv as "x y" lines.
select_runs() {
    awk -F, -v sc="$1" -v T="$2" -v key="$3" -v cols="$4" -v which="${5:-ok}" '
        BEGIN { split(key, k, ":"); n = split(cols, c, " ") }
        NR > 1 && $1 == sc && $2 == T && $3 == k[1] && $4 == k[2] && $5 == k[3] &&
        (which == "all" || $11 == "ok") {
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

# plot_cmd FILE_PREFIX USING [KEYS]: a gnuplot "plot" list over the series
# whose data file has at least one positive finite value in the plotted
# column (log axes drop the rest; gnuplot stops on an all-undefined plot).
plot_cmd() {
    prefix=$1 using=$2 keys=${3:-}
    ycol=${using#*:}
    printf '%s\n' "$series_all" | while IFS='|' read -r key title colour dash pt _; do
        if [ -n "$keys" ]; then
            case " $keys " in *" $key "*) ;; *) continue ;; esac
        fi
        f="$prefix.$(printf '%s' "$key" | tr ':' '_').dat"
        [ -s "$f" ] || continue
        awk -v c="$ycol" '$c != "nan" && $c + 0 > 0 && $c + 0 < 1e300 { found = 1 } END { exit !found }' "$f" || continue
        printf '"%s" using %s with linespoints lc rgb "%s" dt %s pt %s ps 1.1 title "%s", ' \
            "$f" "$using" "$colour" "$dash" "$pt" "$title"
    done | sed 's/, $//'
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
        echo "set key at screen 0.5,0.005 center bottom vertical maxrows $3 box opaque font \",10\" samplen 3"
    else
        echo "set key off"
    fi
}

# A panel with no data still needs something to plot (an invisible constant).
blank='1 notitle lc rgb "white"'

# render NAME SCRIPT: PNG and SVG of one gnuplot script.
render() {
    name=$1 script=$2
    { echo "$png"; echo "set output '$dir/$name.png'"; cat "$script"; echo "unset output"
      echo "$svg"; echo "set output '$dir/$name.svg'"; cat "$script"; echo "unset output"
    } > "$tmp/$name.gp"
    if ! gnuplot "$tmp/$name.gp" 2> "$tmp/$name.err"; then
        echo "plot.sh: gnuplot failed on $name:" >&2
        cat "$tmp/$name.err" >&2
        exit 1
    fi
    echo "plot.sh: $dir/$name.png, .svg" >&2
}

common='set grid lw 0.5 lc rgb "#dddddd"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set key outside right top box opaque font ",10"
set datafile missing "nan"'

pairs=$(awk -F, 'NR > 1 { print $1 "," $2 }' "$runs" | sort -u)
for pair in $pairs; do
    sc=${pair%,*} T=${pair#*,}
    base="$tmp/$sc-$T"

    # ---- work-precision
    printf '%s\n' "$series_all" | while IFS='|' read -r key rest; do
        select_runs "$sc" "$T" "$key" "13 31" > "$base.wp.$(printf '%s' "$key" | tr ':' '_').dat"
    done
    p=$(plot_cmd "$base.wp" "1:2")
    if [ -n "$p" ]; then
        cat > "$tmp/s.gp" <<EOF
$common
set title "$sc, T = $T s: trajectory error against CPU time (only runs that reached T)"
set xlabel "CPU time [s], best of k runs"
set ylabel "max_t ||q(t) - q_{ref}(t)||_2"
plot $p
EOF
        render "wp_${sc}_$T" "$tmp/s.gp"
    fi

    # ---- Fig. 4: against the step size
    fixed=$(tagged steps)
    for key in $fixed; do
        select_runs "$sc" "$T" "$key" "6 25 29 31 13" > "$base.st.$(printf '%s' "$key" | tr ':' '_').dat"
    done
    p1=$(plot_cmd "$base.st" "1:2" "$fixed")
    p2=$(plot_cmd "$base.st" "1:3" "$fixed")
    p3=$(plot_cmd "$base.st" "1:4" "$fixed")
    p4=$(plot_cmd "$base.st" "1:5" "$fixed")
    if [ -n "$p1$p2$p3$p4" ]; then
        k=$(mostkeyed "$p1" "$p2" "$p3" "$p4")
        p1=${p1:-$blank} p2=${p2:-$blank} p3=${p3:-$blank} p4=${p4:-$blank}
        cat > "$tmp/s.gp" <<EOF
$common
set multiplot layout 2,2 title "$sc, T = $T s: maxima over the run against the step size (paper's Fig. 4)" margins 0.08,0.98,0.16,0.93 spacing 0.08,0.1
set xlabel "step size h [s]"
set ylabel "max ||Phi_q||"
$(keyfor 1 "$k" 2)
plot $p1
set ylabel "max |Phi_e| [J]"
$(keyfor 2 "$k" 2)
plot $p2
set ylabel "max ||q - q_{ref}||"
$(keyfor 3 "$k" 2)
plot $p3
set ylabel "CPU time [s]"
$(keyfor 4 "$k" 2)
plot $p4
unset multiplot
EOF
        render "steps_${sc}_$T" "$tmp/s.gp"
    fi

    # ---- IDA against the tolerance
    idak=$(tagged tol)
    for key in $idak; do
        k=$(printf '%s' "$key" | tr ':' '_')
        select_runs "$sc" "$T" "$key" "7 31" > "$base.ie.$k.dat"
        select_runs "$sc" "$T" "$key" "7 frac" all > "$base.it.$k.dat"
    done
    p1=$(plot_cmd "$base.ie" "1:2" "$idak")
    p2=$(plot_cmd "$base.it" "1:2" "$idak")
    if [ -n "$p2" ]; then
        cat > "$tmp/s.gp" <<EOF
$common
set multiplot layout 2,1 title "$sc, T = $T s: IDA against its tolerance (rtol = atol on q, v)" margins 0.08,0.98,0.12,0.93 spacing 0.08,0.1
set xlabel "rtol"
set ylabel "max ||q - q_{ref}|| (runs that reached T)"
set key off
plot ${p1:-$blank}
unset logscale y
set format y "%g"
set yrange [0:1.05]
set ylabel "time reached / T"
set key at screen 0.5,0.005 center bottom vertical maxrows 1 box opaque font ",10" samplen 3
plot $p2
unset multiplot
EOF
        render "ida_${sc}_$T" "$tmp/s.gp"
    fi

    # ---- Figs. 3 and 7: histories at h = 1e-2 (IDA and DOPRI5 at rtol 1e-8)
    [ -s "$hist" ] || continue
    hk=$(tagged history)
    for key in $hk; do
        # fixed-step series: the smallest h with a history; the others rtol 1e-8
        x=$(hist_h "$sc" "$T" "$key" min)
        [ "$x" != nan ] || x=1e-08
        select_hist "$sc" "$T" "$key" "$x" > "$base.h.$(printf '%s' "$key" | tr ':' '_').dat"
    done
    p1=$(plot_cmd "$base.h" "1:2" "$hk")
    p3=$(plot_cmd "$base.h" "1:4" "$hk")
    if [ -n "$p1$p3" ]; then
        pcol=6
        if ! awk '$6 != "nan" { found = 1 } END { exit !found }' "$base.h.braun_rk4_-.dat" 2>/dev/null; then
            pcol=5
        fi
        p2=$(plot_cmd "$base.h" "1:3" "$hk")
        p3=$(plot_cmd "$base.h" "1:4" "$hk")
        p4=$(plot_cmd "$base.h" "1:$pcol" "$hk")
        [ -n "$p4" ] || { pcol=5; p4=$(plot_cmd "$base.h" "1:$pcol" "$hk"); }
        plabel="point error epsilon [m]"
        [ $pcol -eq 6 ] || plabel="||q - q_{ref}||"
        k=$(mostkeyed "$p1" "$p2" "$p3" "$p4")
        # A reference known at one time only (Andrews): points, not lines.
        sparse=$(cat "$base".h.*.dat 2>/dev/null | awk -v c="$pcol" '$c != "nan" && $c + 0 > 0 { n++ } END { print (n < 20) }')
        p1=${p1:-$blank} p2=${p2:-$blank} p3=${p3:-$blank} p4=${p4:-$blank}
        [ "$sparse" = 1 ] && p4=$(printf '%s' "$p4" | sed 's/with linespoints/with points/g')
        cat > "$tmp/s.gp" <<EOF
$common
unset logscale x
set format x "%g"
set xrange [0:$T]
set multiplot layout 2,2 title "$sc, T = $T s: errors along the run, h = 1e-2 (IDA, DOPRI5: rtol 1e-8) (paper's Figs. 3, 7)" margins 0.08,0.98,0.16,0.93 spacing 0.08,0.1
set xlabel "t [s]"
set ylabel "||Phi_q||"
$(keyfor 1 "$k" 2)
plot $p1
set ylabel "||[dPhi_q/dt; Phi_v]||"
$(keyfor 2 "$k" 2)
plot $p2
set ylabel "|Phi_e| [J]"
$(keyfor 3 "$k" 2)
plot $p3
set ylabel "$plabel"
$(keyfor 4 "$k" 2)
plot $p4
unset multiplot
EOF
        sed -i 's/with linespoints/with lines/g; s/ with lines\( lc rgb "[^"]*" dt [0-9]*\) pt [0-9]* ps 1.1/ with lines\1/g' "$tmp/s.gp"
        render "history_${sc}_$T" "$tmp/s.gp"
    fi

    # ---- Fig. 2: the slider (the observable point's x) at h = 5e-2
    tmin=$(awk -F, 'NR > 1 && $1 == "slider-crank" { if (m == "" || $2 + 0 < m + 0) m = $2 } END { print m }' "$runs")
    if [ "$sc" = slider-crank ] && [ "$T" = "$tmin" ]; then
        sk=$(tagged slider)
        for key in $sk; do
            select_hist "$sc" "$T" "$key" "$(hist_h "$sc" "$T" "$key" max)" > "$base.s.$(printf '%s' "$key" | tr ':' '_').dat"
        done
        p=$(plot_cmd "$base.s" "1:7" "$sk")
        if [ -n "$p" ]; then
            ref="\"$base.s.braun_rk4_-.dat\" using 1:8 with lines lc rgb \"black\" lw 2.5 title \"numerically exact (Eq. 24, rk8pd)\""
            cat > "$tmp/s.gp" <<EOF
set grid lw 0.5 lc rgb "#dddddd"
set datafile missing "nan"
set multiplot layout 2,1 title "slider-crank: slider position x_s = x_2 + (l/2) cos(theta_2), h = 5e-2 (paper's Fig. 2)"
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
            sed -i 's/with linespoints/with lines/g; s/ pt [0-9]* ps 1.1//g' "$tmp/s.gp"
            render "slider_${sc}" "$tmp/s.gp"
        fi
    fi
done
