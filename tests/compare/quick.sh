#!/bin/sh
# `make compare-quick` produces well-formed CSV files, plots and a report.
# Runs the quick study (compare/run.sh --study quick) into a temporary
# directory and checks what it wrote.
# Usage: sh tests/compare/quick.sh build/bin/braun-compare
# Prints "ok - NAME" / "not ok - NAME" ("ok - NAME # SKIP WHY" for a check
# that cannot run here) and a closing "N passed, M failed, K skipped".
BIN=${1:?usage: sh tests/compare/quick.sh path/to/braun-compare}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/braun-compare-quick.XXXXXX") || exit 1
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

out="$TMP/out"
sh compare/run.sh --bin "$BIN" --out "$out" --study quick --reps 1 > "$TMP/log" 2>&1; rc=$?
check "compare-quick exits 0" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || sed 's/^/#   /' "$TMP/log" | tail -n 20
check "progress lines on stderr" grep -q '^\[ *1/' "$TMP/log"

# well_formed FILE HEADER: the header as given and every row with its field count.
well_formed() {
    [ -s "$1" ] || return 1
    [ "$(head -n 1 "$1")" = "$2" ] || { echo "#   header of $1: $(head -n 1 "$1")"; return 1; }
    awk -F, -v n="$(printf '%s' "$2" | awk -F, '{ print NF }')" \
        'NF != n { print "#   " FILENAME ":" NR ": " NF " fields"; bad = 1 } END { exit bad }' "$1"
}
runs_hdr="scene,T,method,integrator,variant,h,rtol,atol,alpha,beta,status,t_reached,cpu_s,cpu_s_max,reps,steps,rejected,rhs_evals,jac_evals,lin_setups,lin_solves,err_test_fails,conv_fails,restarts,pos_max,pos_final,vel_max,vel_final,energy_max,energy_final,traj_max,traj_final,point_max,point_final,samples,sigma_end,pos_median,energy_median,iterations,reference,detail"
check "runs.csv well formed" well_formed "$out/runs.csv" "$runs_hdr"
check "ida_probe.csv well formed" well_formed "$out/ida_probe.csv" "$runs_hdr"
check "history.csv well formed" well_formed "$out/history.csv" \
    "scene,T,method,integrator,variant,h,rtol,t,pos,vel,energy,traj,point,obs,obs_ref"
check "references.csv well formed" well_formed "$out/references.csv" \
    "scene,T,reference,tol,compared_with,tol2,max_q_diff,final_q_diff,max_point_diff,role,note"
check "targets.csv well formed" well_formed "$out/targets.csv" \
    "scene,T,reference,floor_traj,floor_point,phi_unit,q_unit,point,minimal"
check "trace.csv well formed" well_formed "$out/trace.csv" "scene,T,method,integrator,variant,h,rtol,t,obs,obs_ref"
check "step_cost.csv well formed" well_formed "$out/step_cost.csv" \
    "scene,method,integrator,variant,h,steps,reps,cpu_per_step_s,cpu_per_step_max_s,detail"
check "singular.csv well formed" well_formed "$out/singular.csv" \
    "scene,theta_star,delta,sigma_ratio,lambda_max,force_max"

# Numbers where numbers belong (nan allowed), a status everywhere.
numeric() {
    awk -F, 'NR > 1 {
        for (i = 1; i <= NF; i++) if (i == 2 || (i >= 6 && i <= 10) || (i >= 12 && i <= 39)) {
            if ($i !~ /^-?(nan|inf|[0-9.]+([eE][-+]?[0-9]+)?)$/) { print "#   row " NR " col " i ": " $i; bad = 1 }
        }
        if ($11 == "") { print "#   row " NR ": empty status"; bad = 1 }
    } END { exit bad }' "$1"
}
check "runs.csv fields are numbers" numeric "$out/runs.csv"
for m in braun braun-noenergy baumgarte ida-ggl ida-index1 ode-rk4 projection mujoco simbody; do
    check "runs.csv has $m on both scenes" sh -c \
        "[ \$(awk -F, -v m=$m 'NR > 1 && \$3 == m { print \$1 }' '$out/runs.csv' | sort -u | wc -l) -eq 2 ]"
done
# The peers and the projection on both paper scenes: runs that ran (MuJoCo,
# the projection), or a recorded row that says why not (Simbody today:
# NOT_BUILT), never nothing.
check "mujoco ran on both paper scenes" sh -c \
    "[ \$(awk -F, 'NR > 1 && \$3 == \"mujoco\" && \$11 == \"ok\" { print \$1 }' '$out/runs.csv' | sort -u | wc -l) -eq 2 ]"
check "projection ran on both paper scenes" sh -c \
    "[ \$(awk -F, 'NR > 1 && \$3 == \"projection\" && \$11 == \"ok\" { print \$1 }' '$out/runs.csv' | sort -u | wc -l) -eq 2 ]"
check "every simbody row has a status and, if it did not run, a reason" sh -c \
    "awk -F, 'NR > 1 && \$3 == \"simbody\" { n++; if (\$11 == \"\" || (\$11 != \"ok\" && \$11 != \"NOT_BUILT\" && \$41 == \"-\")) bad = 1 } END { exit bad || !n }' '$out/runs.csv'"
check "the cost per step of braun and MuJoCo on both paper scenes" sh -c \
    "[ \$(awk -F, 'NR > 1 && (\$2 == \"braun\" || \$2 == \"mujoco\") && \$8 + 0 > 0 { print \$1 }' '$out/step_cost.csv' | sort -u | wc -l) -eq 2 ]"
check "every reference has its own error (targets.csv floor)" sh -c \
    "awk -F, 'NR > 1 && !(\$4 + 0 > 0) { bad = 1 } END { exit bad || NR < 3 }' '$out/targets.csv'"
check "no reference is libbraun's (braun-rk4-fine)" sh -c \
    "! grep -q braun-rk4-fine '$out/runs.csv' '$out/references.csv' '$out/targets.csv'"
check "every fixed-step RK4 braun run reached T" sh -c \
    "awk -F, 'NR > 1 && \$3 == \"braun\" && \$4 == \"rk4\" && \$11 != \"ok\" { bad = 1 } END { exit bad }' '$out/runs.csv'"
check "failed runs keep their row and time reached" sh -c \
    "awk -F, 'FNR > 1 && \$11 != \"ok\" && \$11 != \"FLEW_APART\" && !(\$12 + 0 < \$2 + 0) { bad = 1 } END { exit bad }' '$out/runs.csv' '$out/ida_probe.csv'"
# A run that reached T with its constraints broken by more than 0.1 is
# FLEW_APART, not ok (Simbody's fixed-step slider-crank: 26-334 m, "ok").
check "no run that reached T as ok has max |Phi_q| above 0.1; FLEW_APART ones have" sh -c \
    "awk -F, 'NR > 1 && \$11 == \"ok\" && \$25 + 0 > 0.1 { bad = 1 } NR > 1 && \$11 == \"FLEW_APART\" && !(\$25 + 0 > 0.1) { bad = 1 } END { exit bad }' '$out/runs.csv'"
# The progress lines say what the rows say (they said "ok" for FLEW_APART).
check "progress lines and runs.csv agree on every status" sh -c '
    a=$(grep -v "(probe)" "$1" | sed -n "s/^\[.*: \([A-Za-z_]*\)  *traj=.*/\1/p" | sort | uniq -c)
    b=$(awk -F, "NR > 1 { print \$11 }" "$2" | sort | uniq -c)
    [ -n "$a" ] && [ "$a" = "$b" ] || { echo "#   progress: $a"; echo "#   runs.csv: $b"; exit 1; }' \
    sh "$TMP/log" "$out/runs.csv"
# braun RK4 over 20 s, trajectory error (traj_max) measured at h = 0.01:
# four-bar 1.02e-5, slider-crank 7.28e-6 (the bound was 1e-3); at h = 0.005
# 6.3e-7 and 4.5e-7: observed order 4.01 on both.
traj_at() { # traj_at SCENE H: traj_max of braun RK4
    awk -F, -v s="$1" -v h="$2" 'NR > 1 && $1 == s && $3 == "braun" && $4 == "rk4" && $6 == h { print $31 }' \
        "$out/runs.csv"
}
for sb in four-bar:3e-5 slider-crank:2e-5; do
    sc=${sb%%:*} bound=${sb#*:}
    e1=$(traj_at "$sc" 0.01); e2=$(traj_at "$sc" 0.005)
    check "braun RK4 at h = 0.01 on the $sc: trajectory error $e1 <= $bound" \
        awk -v a="$e1" -v b="$bound" 'BEGIN { exit !(a != "" && a + 0 <= b + 0) }'
    check "braun RK4 on the $sc: observed order in (3.8, 4.2) from h = 0.01 to 0.005 ($e1, $e2)" \
        awk -v a="$e1" -v b="$e2" 'BEGIN { if (!(a > 0 && b > 0)) exit 1; p = log(a / b) / log(2)
            exit !(p > 3.8 && p < 4.2) }'
done

# Plots: PNG and SVG of every kind.
for sc in four-bar slider-crank; do
    for kind in wp steps history tol; do
        f="$out/${kind}_${sc}_20"
        check "$kind plot of $sc is a PNG" sh -c "[ \"\$(head -c 8 '$f.png' | od -An -tx1 | tr -d ' \n')\" = 89504e470d0a1a0a ]"
        check "$kind plot of $sc is an SVG" grep -q "<svg" "$f.svg"
    done
done
check "slider plot (Fig. 2)" sh -c "[ -s '$out/slider_slider-crank.png' ] && grep -q '<svg' '$out/slider_slider-crank.svg'"
check "the four-bar's Fig. 6" sh -c "[ -s '$out/fig6_four-bar_20.png' ] && grep -q '<svg' '$out/fig6_four-bar_20.svg'"
check "the work-precision plots show MuJoCo and the projection" sh -c \
    "grep -q 'MuJoCo 2.2.2 RK4' '$out/wp_four-bar_20.svg' && grep -q 'RK4 + coordinate projection' '$out/wp_four-bar_20.svg'"
# Every axis label plot.sh writes names a unit in brackets ([m], [s], [–]).
check "every axis label has a unit" sh -c \
    "! grep -E 'set [xy]label|plabel=' compare/plot.sh | grep -v '\\[' | grep -v 'ylabel \"\\\$plabel\"' | sed 's/^/#   /' | grep ."

# Legends and the report's rows come from the series table (compare/series.tsv,
# tests/compare/series.sh checks the rest): every legend entry but the
# references' is a label (with " — k of n runs stopped" or, in Fig. 6, the
# run's setting after it), and each series that ran has a row in the report
# under its label.
"$BIN" series > "$TMP/series"
cut -d'|' -f2 "$TMP/series" | sort > "$TMP/labels"
for f in "$out"/*.svg; do grep -o '<title>[^<]*</title>' "$f"; done | sed 's/<title>//; s/<\/title>//' |
    grep -v '^Gnuplot$' | grep -v '^numerically exact' | grep -v "^reference's own error" |
    sed 's/ — .*//; s/&amp;/\&/g' | sort -u > "$TMP/legends"
check "every plot legend entry is a series label" sh -c \
    "comm -23 '$TMP/legends' '$TMP/labels' | sed 's/^/#   not a label: /' | grep . && exit 1; exit 0"
check "a series whose runs stopped says so in its legend" sh -c \
    "grep -h -o '<title>[^<]*runs stopped</title>' '$out'/wp_*.svg | grep -q ."
check "the report names every series that ran by its label" sh -c \
    "awk -F, 'NR > 1 && \$11 != \"NOT_BUILT\" && \$11 != \"UNSUPPORTED\" { print \$3 \":\" \$4 \":\" \$5 }' '$out/runs.csv' | sort -u > '$TMP/ran'
     awk -F'|' 'FNR == NR { ran[\$1] = 1; next } (\$1 in ran) { print \$2 }' '$TMP/ran' '$TMP/series' |
     while IFS= read -r l; do grep -qF \"| \$l | \" '$out/report.md' || { echo \"#   no row: \$l\"; exit 1; }; done"

# The report embeds the plots and states verdicts.
check "report.md written" [ -s "$out/report.md" ]
check "report embeds every PNG" sh -c \
    "for p in '$out'/*.png; do grep -q \"(\$(basename \"\$p\"))\" '$out/report.md' || exit 1; done"
check "report has the claims table" grep -q "^## The paper's claims" "$out/report.md"
check "report starts with its summary" sh -c \
    "[ \"\$(grep -m 1 '^## ' '$out/report.md')\" = '## Summary' ]"
check "report has the peers, Fig. 6 and braun's own failures" sh -c \
    "grep -q '^## The peers' '$out/report.md' && grep -q \"^## The paper's Fig. 6\" '$out/report.md' &&
     grep -q \"^## braun's own failures\" '$out/report.md'"
check "report has the probes in an appendix, after everything else" sh -c \
    "awk '/^## / { last = \$0 } END { exit last != \"## Appendix: the probes\" }' '$out/report.md'"
check "report has the IDA section" grep -q "^## IDA: best achievable error" "$out/report.md"
check "report states verdicts" grep -q "claims confirmed, [0-9]* refuted" "$out/report.md"

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
