#!/bin/sh
# The three readers of the series table compare/series.tsv see the same
# series: braun-compare (the report), compare/plot.sh (the legends) and
# braun-bench (the cost at matched error). On a made-up runs.csv with two
# runs of every series: the report's rows, the plots' legends and bench's
# columns are the table's labels and keys, nothing else; a malformed table
# is refused.
# Usage: sh tests/compare/series.sh build/bin/braun-compare [build/bin/braun-bench]
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" for a check
# that cannot run here) and a closing "N passed, M failed, K skipped".
BIN=${1:?usage: sh tests/compare/series.sh path/to/braun-compare [path/to/braun-bench]}
BENCH=${2:-}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-compare-series.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
skip() { skipped=$((skipped + 1)); echo "ok - $1 # SKIP $2"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "${2:-}" ] || echo "#   $2"; }
check() { # check NAME COMMAND...
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
same() { # same A B: files equal, else the first differences
    cmp -s "$1" "$2" && return 0
    diff "$1" "$2" | head -n 6 | sed 's/^/#   /'
    return 1
}

# The table as each reader has it.
awk -f compare/series.awk -v out=plot compare/series.tsv > "$TMP/table" 2> "$TMP/awk.err"
check "series.tsv is well formed" sh -c "[ -s '$TMP/table' ] && [ ! -s '$TMP/awk.err' ]"
sh compare/plot.sh --series > "$TMP/plot"
"$BIN" series > "$TMP/compare"
check "plot.sh reads the table" same "$TMP/table" "$TMP/plot"
check "braun-compare was built from the table" same "$TMP/table" "$TMP/compare"
if [ -n "$BENCH" ]; then
    "$BENCH" series > "$TMP/bench"
    check "braun-bench was built from the table" same "$TMP/table" "$TMP/bench"
else
    skip "braun-bench was built from the table" "no braun-bench given"
fi
cut -d'|' -f2 "$TMP/table" | sort > "$TMP/labels"
tagged() { awk -F'|' -v t="$1" '{ n = split($6, a, ","); for (i = 1; i <= n; i++) if (a[i] == t) print $1 }' "$TMP/table"; }

# Two runs of every series on one scene: fixed-step series (tag steps, or
# an RK4-like key) at h = 0.01 and 0.005, the others at rtol 1e-4, 1e-6.
out="$TMP/study"
mkdir -p "$out"
hdr="scene,T,method,integrator,variant,h,rtol,atol,alpha,beta,status,t_reached,cpu_s,cpu_s_max,reps,steps,rejected,rhs_evals,jac_evals,lin_setups,lin_solves,err_test_fails,conv_fails,restarts,pos_max,pos_final,vel_max,vel_final,energy_max,energy_final,traj_max,traj_final,point_max,point_final,samples,sigma_end,pos_median,energy_median,iterations,reference,detail"
awk -F'|' -v hdr="$hdr" 'BEGIN { print hdr }
    {
        split($1, k, ":"); fixed = ("," $6 ",") ~ /,steps,/ || k[2] ~ /^(rk4|heun|euler)$/
        for (j = 1; j <= 2; j++) {
            h = fixed ? (j == 1 ? 0.01 : 0.005) : "nan"; r = fixed ? "nan" : (j == 1 ? 1e-4 : 1e-6)
            e = 1e-3 * NR / j
            printf "four-bar,20,%s,%s,%s,%s,%s,%s,nan,nan,ok,20,%g,%g,1,%d,0,%d,0,0,0,0,0,0,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,401,0.5,1e-10,1e-7,0,closed-form,-\n",
                k[1], k[2], k[3], h, r, r, 0.01 * NR * j, 0.01 * NR * j, 2000 * j, 8000 * j,
                1e-9 * NR, 1e-9, 1e-8, 1e-8, 1e-6 * NR, 1e-6, e, e, e, e
        }
    }' "$TMP/table" > "$out/runs.csv"

# The report: one row per series in the per-scene table, by its label.
"$BIN" report --dir "$out" 2> "$TMP/report.log"; rc=$?
check "report written (exit 0)" sh -c '[ "$1" -eq 0 ] && [ -s "$2" ]' sh "$rc" "$out/report.md"
awk '/^\| method \| best error \(reached T\)/ { on = 1; next } on && /^\|---/ { next }
     on && /^\| / { split($0, f, " \\| "); sub(/^\| /, "", f[1]); print f[1]; next } on { exit }' \
    "$out/report.md" | sort > "$TMP/report.labels"
check "the report's rows are the table's labels" same "$TMP/labels" "$TMP/report.labels"

# The plots: every series in the work-precision legend, each tagged series
# in its plot, and no legend entry that is not a label.
sh compare/plot.sh "$out" 2> "$TMP/plot.log"; rc=$?
check "compare/plot.sh exits 0" [ "$rc" -eq 0 ]
titles() { grep -o '<title>[^<]*</title>' "$1" | sed 's/<title>//; s/<\/title>//' | grep -v '^Gnuplot$' | sort -u; }
check "work-precision plot written" [ -s "$out/wp_four-bar_20.svg" ]
titles "$out/wp_four-bar_20.svg" > "$TMP/wp.labels"
check "the work-precision legend is the table's labels" same "$TMP/labels" "$TMP/wp.labels"
for pair in steps:steps tol:tol; do
    tag=${pair%%:*} plot=${pair#*:}
    for key in $(tagged "$tag"); do
        grep -F "$key|" "$TMP/table" | cut -d'|' -f2
    done | sort > "$TMP/want.$tag"
    titles "$out/${plot}_four-bar_20.svg" > "$TMP/got.$tag"
    check "the $plot plot shows the series tagged $tag, by label" same "$TMP/want.$tag" "$TMP/got.$tag"
done
check "every legend entry of every plot is a label" sh -c \
    "for f in '$out'/*.svg; do grep -o '<title>[^<]*</title>' \"\$f\"; done | sed 's/<title>//; s/<\/title>//' |
     grep -v '^Gnuplot\$' | sort -u | comm -23 - '$TMP/labels' | grep -q . && exit 1; exit 0"

# Bench: one column per series tagged bench, by key, in table order.
if [ -n "$BENCH" ]; then
    "$BENCH" matched "$out/runs.csv" 1e-3 > "$TMP/matched.csv"
    tagged bench > "$TMP/want.bench"
    awk -F, 'NR > 1 { print $4 }' "$TMP/matched.csv" > "$TMP/got.bench"
    check "bench's methods are the series tagged bench" same "$TMP/want.bench" "$TMP/got.bench"
    check "bench's ratios are to braun:rk4:-" sh -c \
        "awk -F, 'NR > 1 && \$4 == \"braun:rk4:-\" && \$7 != 1 { bad = 1 } END { exit bad }' '$TMP/matched.csv'"
else
    skip "bench's methods are the series tagged bench" "no braun-bench given"
    skip "bench's ratios are to braun:rk4:-" "no braun-bench given"
fi

# One diverged run cannot flatten a history plot: a run that stopped after
# reaching 1e140 is clipped at 1e3 x the largest value of the runs that
# reached T, the plot and plots.tsv say so, and its legend says it stopped.
clip="$TMP/clip"
mkdir -p "$clip"
{
    echo "$hdr"
    echo "four-bar,20,braun,rk4,-,0.01,nan,nan,nan,nan,ok,20,0.1,0.1,1,2000,0,8000,0,0,0,0,0,0,1e-8,1e-8,1e-7,1e-7,1e-6,1e-6,1e-5,1e-5,1e-5,1e-5,401,0.5,1e-9,1e-7,0,closed-form,-"
    echo "four-bar,20,baumgarte,rk4,-,0.01,nan,nan,10,10,BRAUN_ERR_DIVERGED,5,0.1,0.1,1,500,0,2000,0,0,0,0,0,0,1e140,1e140,1e140,1e140,1e140,1e140,1e140,1e140,1e140,1e140,101,0.5,1e-3,1e-3,0,closed-form,-"
} > "$clip/runs.csv"
awk -v OFS=, 'BEGIN {
    print "scene,T,method,integrator,variant,h,rtol,t,pos,vel,energy,traj,point,obs,obs_ref"
    for (k = 0; k <= 400; k++) { t = k * 0.05
        print "four-bar", 20, "braun", "rk4", "-", 0.01, "nan", t, 1e-8, 1e-7, 1e-6, 1e-5, 1e-5, 2, 2 }
    for (k = 0; k <= 100; k++) { t = k * 0.05; e = 10 ^ (1.4 * k)
        print "four-bar", 20, "baumgarte", "rk4", "-", 0.01, "nan", t, e, e, e, e, e, 2, 2 }
}' > "$clip/history.csv"
sh compare/plot.sh "$clip" 2> "$TMP/clip.log"; rc=$?
check "plot.sh draws a history with a diverged run (exit 0)" [ "$rc" -eq 0 ]
check "... clips its axes and notes it in plots.tsv" grep -q "^history_four-bar_20	.*clipped at" "$clip/plots.tsv"
check "... and in the plot" grep -q "clipped at" "$clip/history_four-bar_20.svg"
check "... whose legend says the run stopped" grep -q "stopped: BRAUN" "$clip/history_four-bar_20.svg"

# The report's sentences per fixed-step series, on made-up runs: the
# largest step with an error below 0.01 (a shared buffer printed
# "h = 0.01" for every series), and an observed order only from errors
# between 10x the reference's and 0.1 (MuJoCo's 7.3 m and 78.6 m gave
# "order 3.4"; 3.7e4 and 3.8e4 "order 0.0").
words="$TMP/words"
mkdir -p "$words"
{
    echo "$hdr"
    for r in "braun rk4 - 0.02 5e-3" "braun rk4 - 0.01 3.2e-4" "braun rk4 - 0.005 2e-5" \
             "braun heun - 0.01 0.17" "braun heun - 0.005 0.043" "braun heun - 0.002 6.8e-3" \
             "braun heun - 0.001 1.7e-3" \
             "mujoco mj-euler - 0.002 78.6" "mujoco mj-euler - 0.001 7.3"; do
        set -- $r
        printf 'four-bar,20,%s,%s,%s,%s,nan,nan,nan,nan,ok,20,0.1,0.1,1,100,0,400,0,0,0,0,0,0,1e-9,1e-9,1e-8,1e-8,1e-6,1e-6,%s,%s,%s,%s,401,0.5,1e-10,1e-7,0,closed-form,-\n' \
            "$1" "$2" "$3" "$4" "$5" "$5" "$5" "$5"
    done
} > "$words/runs.csv"
"$BIN" report --dir "$words" 2> "$TMP/words.log"
check "report: braun RK4's largest step with an error below 0.01 is 0.02, order 4.0" \
    grep -q '^- braun, RK4: the largest step with an error below 0.01: h = 0.02\. Observed order .*: 4\.0\.$' "$words/report.md"
check "report: braun Heun's is 0.002, not 0.01" \
    grep -q '^- braun, Heun: the largest step with an error below 0.01: h = 0.002\.' "$words/report.md"
check "report: no order from MuJoCo's errors of 7.3 and 78.6 m" sh -c '
    grep "^- MuJoCo 2.2.2 semi-implicit Euler" "$1" | grep -q "No observed order: .* 2 above 0.1" &&
    ! grep "^- MuJoCo 2.2.2 semi-implicit Euler" "$1" | grep -q "Observed order"' sh "$words/report.md"

# A malformed table is refused with its line.
printf 'braun:rk4\tbraun, RK4\t#1f4e9c\t1\t7\tsteps\n' > "$TMP/bad.tsv"
check "a key without a variant is refused" sh -c \
    "! awk -f compare/series.awk -v out=c '$TMP/bad.tsv' > /dev/null 2> '$TMP/bad.err' && grep -q 'bad.tsv:1:' '$TMP/bad.err'"
printf 'braun:rk4:-\tbraun, RK4\t#1f4e9c\t1\t7\tstep\n' > "$TMP/bad.tsv"
check "an unknown tag is refused" sh -c \
    "! awk -f compare/series.awk -v out=plot '$TMP/bad.tsv' > /dev/null 2>&1"

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
