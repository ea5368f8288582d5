#!/bin/sh
# The report and the plots say what the study ran, on made-up CSV files
# (found by an outside client on studies of one scene or of 20 s):
# a claim whose rule needs both paper scenes (or every scene and horizon)
# is not confirmed from one of them; a claim not tested says what it needs
# and which runs the study has, never a value it did not measure (0, nan)
# or "no Simbody run ran" when Simbody ran; the summary says "no run within
# this CPU time" when runs reached T but took longer, "no run reached T"
# when none did; a plot that draws one run per series (Fig. 2, histories)
# says in its legend how the drawn run ended, not how many of the series'
# runs stopped; Fig. 6's title names only the methods it draws.
# Usage: sh tests/compare/evidence.sh build/bin/braun-compare
# Prints "ok - NAME" / "not ok - NAME" and a closing "N passed, M failed,
# K skipped".
BIN=${1:?usage: sh tests/compare/evidence.sh path/to/braun-compare}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-compare-evidence.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok - $1"; }
not_ok() { failed=$((failed + 1)); echo "not ok - $1"; [ -z "${2:-}" ] || echo "#   $2"; }
check() { # check NAME COMMAND...
    name=$1; shift
    if "$@"; then ok "$name"; else not_ok "$name"; fi
}
hdr="scene,T,method,integrator,variant,h,rtol,atol,alpha,beta,status,t_reached,cpu_s,cpu_s_max,reps,steps,rejected,rhs_evals,jac_evals,lin_setups,lin_solves,err_test_fails,conv_fails,restarts,pos_max,pos_final,vel_max,vel_final,energy_max,energy_final,traj_max,traj_final,point_max,point_final,samples,sigma_end,pos_median,energy_median,iterations,reference,detail"
# row SCENE T METHOD INTEG VARIANT H RTOL STATUS T_REACHED CPU TRAJ POS ENERGY
row() {
    printf '%s,%s,%s,%s,%s,%s,%s,%s,nan,nan,%s,%s,%s,%s,1,1000,0,4000,0,0,0,0,0,0,%s,%s,1e-8,1e-8,%s,%s,%s,%s,%s,%s,401,0.5,%s,%s,0,closed-form,-\n' \
        "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$7" "$8" "$9" "${10}" "${10}" "${12}" "${12}" \
        "${13}" "${13}" "${11}" "${11}" "${11}" "${11}" "${12}" "${13}"
}
# claim PATTERN FILE: the claims table's row of the claim whose text matches.
claim() { grep -E "^\| [^|]*$1" "$2" | head -n 1; }

# ---- 1. The four-bar alone over 100 and 1000 s: every figure finds its
# cases there, with values that hold every rule, and none on the
# slider-crank. Only the four-bar's own claims may be confirmed.
one="$TMP/one"
mkdir -p "$one"
{
    echo "$hdr"
    for T in 100 1000; do
        row four-bar $T braun rk4 - 0.001 nan ok $T 0.2 1e-8 1e-9 1e-14
        row four-bar $T braun rk4 - 0.01 nan ok $T 0.1 1e-4 1e-9 1e-14
        row four-bar $T braun rk4 - 0.05 nan ok $T 0.06 0.01 1e-9 1e-14
        row four-bar $T braun-noenergy rk4 - 0.001 nan ok $T 0.18 1e-8 1e-9 1e-3
        row four-bar $T braun-noenergy rk4 - 0.01 nan ok $T 0.09 0.1 1e-9 1e-3
        row four-bar $T braun-noenergy rk4 - 0.05 nan ok $T 0.055 1 1e-9 1e-3
        row four-bar $T ode-rk4 rk4 - 0.001 nan ok $T 0.02 1e-8 1e-9 1e-9
        row four-bar $T ode-rk4 rk4 - 0.01 nan ok $T 0.01 0.1 1e-9 1e-9
        row four-bar $T ode-rk4 rk4 - 0.05 nan ok $T 0.005 1 1e-9 1e-9
        row four-bar $T projection rk4 - 0.05 nan ok $T 0.05 1 1e-9 1e-9
    done
} > "$one/runs.csv"
"$BIN" report --dir "$one" 2> "$TMP/one.log"
check "report of the four-bar alone written" [ -s "$one/report.md" ]
check "Fig. 4d (both scenes' rule) is not confirmed from the four-bar alone" sh -c \
    'claim() { grep -E "^\| [^|]*$1" "$2" | head -n 1; }
     r=$(claim "With small steps the error" "$1"); [ -n "$r" ] && echo "$r" | grep -q "| not tested |" &&
     echo "$r" | grep -q "slider-crank"' sh "$one/report.md"
check "no claim over both scenes or every scene and horizon is confirmed from one scene" sh -c \
    "! grep -E '^\\| .*\\*\\*confirmed\\*\\*.*(both|every paper scene|every scene)' '$one/report.md' | sed 's/^/#   /' | grep ."
check "the four-bar's own claim (singular passage) is still judged" sh -c \
    'grep -E "^\| The integration stays accurate through kinematic singularities" "$1" | grep -q "confirmed"' \
    sh "$one/report.md"

# ---- 2. Both paper scenes over 20 s only (the quick study's horizon):
# the claims (100 and 1000 s) find no case; Simbody, MuJoCo and the
# projection ran.
q="$TMP/q"
mkdir -p "$q"
{
    echo "$hdr"
    for sc in slider-crank four-bar; do
        row $sc 20 braun rk4 - 0.01 nan ok 20 0.01 1e-5 1e-9 1e-14
        row $sc 20 braun rk4 - 0.005 nan ok 20 0.02 1e-6 1e-9 1e-14
        row $sc 20 braun-noenergy rk4 - 0.01 nan ok 20 0.009 1e-4 1e-9 1e-3
        row $sc 20 ida-ggl bdf - nan 1e-6 ok 20 0.5 1e-3 1e-9 1e-6
        row $sc 20 ida-index1 bdf - nan 1e-6 IDA_CONV_FAIL 3 0.5 1e-3 1e-9 1e-6
        row $sc 20 mujoco mj-rk4 - 0.01 nan ok 20 0.02 0.01 1e-3 1e-3
        row $sc 20 projection rk4 - 0.01 nan ok 20 0.03 1e-5 1e-9 1e-9
        row $sc 20 simbody rk-merson - nan 1e-6 ok 20 1.5 3 1e-9 1e-9
        row $sc 20 simbody rk-merson-fixed - 0.02 nan ok 20 0.5 0.02 1e-9 1e-9
    done
} > "$q/runs.csv"
"$BIN" report --dir "$q" 2> "$TMP/q.log"
check "report of the 20 s study written" [ -s "$q/report.md" ]
sb=$(claim "Simbody's best setting" "$q/report.md")
check "the Simbody claim does not say that no Simbody run ran" sh -c \
    '[ -n "$1" ] && ! echo "$1" | grep -q "no Simbody run ran"' sh "$sb"
check "... it names the Simbody runs the study has" sh -c \
    'echo "$1" | grep -q "Simbody: slider-crank 20 s (2 runs, 2 reached T), four-bar 20 s (2 runs"' sh "$sb"
check "the MuJoCo and projection claims name their runs" sh -c \
    'claim() { grep -E "^\| [^|]*$1" "$2" | head -n 1; }
     claim "MuJoCo.s best setting" "$1" | grep -q "MuJoCo: slider-crank 20 s" &&
     claim "RK4 with coordinate projection" "$1" | grep -q "RK4 + projection: slider-crank 20 s"' sh "$q/report.md"
check "no claim not tested shows a value (0, nan) or an empty list" sh -c \
    "! grep '| not tested |' '$q/report.md' | grep -E ': 0( |;|\$)|: 0 \\(|nan|\\(\\)|— +\\(| over 0 pairs' | sed 's/^/#   /' | grep ."
check "a claim not tested says what it needs" sh -c \
    '[ "$(grep -c "| not tested | not measured: it needs " "$1")" -eq "$(grep -c "| not tested |" "$1")" ]' \
    sh "$q/report.md"
# The summary (four-bar over 20 s, braun RK4 h = 1e-2 in 0.01 s): IDA GGL
# reached T in 0.5 s (over the budget), IDA index-1 never reached T.
check "summary: IDA GGL reached T, but not within braun's CPU time" sh -c \
    'grep "^| IDA GGL |" "$1" | grep -q "| no run that reached T within this CPU time |"' sh "$q/report.md"
check "summary: IDA index-1 never reached T" sh -c \
    'grep "^| IDA index-1 |" "$1" | grep -q "| no run reached T |"' sh "$q/report.md"

# ---- 3. Plots of one run per series: Fig. 2 draws each series' largest
# step (h = 0.05), where Baumgarte diverged at 13.75 s; the histories draw
# the smallest (h = 0.01), where Baumgarte reached T and its runs at 0.02
# and 0.05 stopped.
p="$TMP/p"
mkdir -p "$p"
{
    echo "$hdr"
    for h in 0.01 0.02 0.05; do
        row slider-crank 20 braun rk4 - $h nan ok 20 0.01 1e-5 1e-9 1e-14
    done
    row slider-crank 20 baumgarte rk4 - 0.01 nan ok 20 0.01 1e-4 1e-6 1e-6
    row slider-crank 20 baumgarte rk4 - 0.02 nan BRAUN_ERR_DIVERGED 7.34 0.01 1 1 1
    row slider-crank 20 baumgarte rk4 - 0.05 nan BRAUN_ERR_DIVERGED 13.75 0.01 1 1 1
} > "$p/runs.csv"
awk -v OFS=, 'BEGIN {
    print "scene,T,method,integrator,variant,h,rtol,t,pos,vel,energy,traj,point,obs,obs_ref"
    n = split("0.01 0.02 0.05", hs, " ")
    for (i = 1; i <= n; i++) for (k = 0; k <= 400; k++) { t = k * 0.05
        print "slider-crank", 20, "braun", "rk4", "-", hs[i], "nan", t, 1e-9, 1e-8, 1e-14, 1e-5, 1e-5, cos(t), cos(t)
        if ((hs[i] == 0.05 && t > 13.75) || (hs[i] == 0.02 && t > 7.34)) continue
        print "slider-crank", 20, "baumgarte", "rk4", "-", hs[i], "nan", t, 1e-6, 1e-6, 1e-6, 1e-4, 1e-4, cos(t), cos(t) }
}' > "$p/history.csv"
sh compare/plot.sh "$p" 2> "$TMP/p.log"; rc=$?
check "plot.sh draws the one-run plots (exit 0)" [ "$rc" -eq 0 ]
titles() { grep -o '<title>[^<]*</title>' "$1" | sed 's/<title>//; s/<\/title>//' | sort -u; }
titles "$p/slider_slider-crank.svg" > "$TMP/slider.titles" 2> /dev/null
titles "$p/history_slider-crank_20.svg" > "$TMP/history.titles" 2> /dev/null
check "Fig. 2: the drawn Baumgarte run says it stopped, with its status and time" \
    grep -q '^Baumgarte .* — stopped: BRAUN.*DIVERGED at t = 13.75 s' "$TMP/slider.titles"
check "histories: the drawn Baumgarte run reached T, the legend does not say it stopped" sh -c \
    'grep "^Baumgarte" "$1" | grep -q " — reached T" && ! grep "^Baumgarte" "$1" | grep -q -e " — stopped" -e " — [0-9]* of [0-9]* runs stopped"' \
    sh "$TMP/history.titles"
check "... and counts the other runs that stopped as other runs" \
    grep -q '^Baumgarte .* — reached T (2 of its 2 other runs stopped)$' "$TMP/history.titles"

# ---- 4. Fig. 6 of a study without Baumgarte names the methods it draws.
f6="$TMP/f6"
mkdir -p "$f6"
{
    echo "$hdr"
    row four-bar 20 braun rk4 - 0.01 nan ok 20 0.01 1e-5 1e-9 1e-14
    row four-bar 20 ode-rk4 rk4 - 0.01 nan ok 20 0.001 1e-5 1e-9 1e-9
} > "$f6/runs.csv"
awk -v OFS=, 'BEGIN {
    print "scene,T,method,integrator,variant,h,rtol,t,obs,obs_ref"
    for (k = 0; k <= 400; k++) { t = k * 0.05
        print "four-bar", 20, "braun", "rk4", "-", 0.01, "nan", t, 2 + cos(t), 2 + cos(t)
        print "four-bar", 20, "ode-rk4", "rk4", "-", 0.01, "nan", t, 2 + cos(t), 2 + cos(t) }
}' > "$f6/trace.csv"
sh compare/plot.sh "$f6" 2> "$TMP/f6.log"
check "Fig. 6 drawn" [ -s "$f6/fig6_four-bar_20.svg" ]
check "Fig. 6's title names braun and the ODE, not Baumgarte nor the projection" sh -c \
    'grep -q "for braun and the ODE" "$1" && ! grep -q -e Baumgarte -e "RK4 + projection" "$1"' \
    sh "$f6/fig6_four-bar_20.svg"

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
