#!/bin/sh
# Run a comparison study, plot it and write its report (docs/compare.md).
# Usage: sh compare/run.sh --bin build/bin/braun-compare --out DIR
#            [--study default|quick] [--jobs J] [--reps K]
#            [--scenes "a b"] [--methods "x y"] [--no-report]
#        sh compare/run.sh --list [the options above]
#        sh compare/run.sh --merge --bin ... --out DIR [--no-report]
# Every run of the study (a row of runs.csv or ida_probe.csv) is a process of
# its own, after a "prepare" process per scene and horizon that computes the
# reference once (and the rows of references.csv, targets.csv, singular.csv).
# A generated makefile in DIR/.parts schedules them: under `make -jN` (a
# recipe marked `+`) through make's jobserver, N at a time; otherwise J at a
# time (J = 1: one after the other). The parts are merged in the order of the
# serial run, so the CSV files do not depend on J except in their CPU-time
# columns. --no-report: the CSV files and meta.txt only (no plots, no
# report.md).
#
# --list writes the study's steps as self-contained commands, one per line
# (absolute paths, every option spelled out, no environment needed):
# DIR/jobs/prepare.txt (one per scene and horizon: the references) and
# DIR/jobs/runs.txt (one per run), for GNU parallel (also across hosts over
# ssh) or a Slurm array; each writes its part under DIR/.parts. Run the
# prepare lines first (a run line whose reference is not there computes it
# itself: same numbers, more work). --merge then assembles the same CSV files
# and report from the parts.
set -eu
bin=build/bin/braun-compare out=results/compare study=default jobs=2 reps=3
scenes="" methods="" report=1 mode=run
while [ $# -gt 0 ]; do
    case $1 in
    --no-report) report=0; shift; continue ;;
    --list) mode=list; shift; continue ;;
    --merge) mode=merge; shift; continue ;;
    --bin|--out|--study|--jobs|--reps|--scenes|--methods)
        [ $# -ge 2 ] || { echo "compare/run.sh: '$1' needs a value" >&2; exit 2; } ;;
    esac
    case $1 in
    --bin) bin=$2 ;;
    --out) out=$2 ;;
    --study) study=$2 ;;
    --jobs) jobs=$2 ;;
    --reps) reps=$2 ;;
    --scenes) scenes=$2 ;;
    --methods) methods=$2 ;;
    *) echo "compare/run.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
    shift 2
done
here=$(dirname "$0")
case $jobs in ''|*[!0-9]*|0) echo "compare/run.sh: --jobs must be a positive integer" >&2; exit 2 ;; esac
parts="$out/.parts"

# q WORD: WORD quoted for sh.
q() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }

# merge: the parts in plan order, one header each file, then meta.txt, the
# plots and the report.
merge() {
    [ -s "$parts/plan.txt" ] || { echo "compare: no plan in $parts (run --list first)" >&2; exit 1; }
    # shellcheck disable=SC1091
    . "$parts/settings"
    awk '$1 == "prepare" { print "p" $2 } $1 == "job" { print "j" $2 }' "$parts/plan.txt" \
        > "$parts/order.txt"
    for f in $("$bin" files); do
        (cd "$parts" && awk -v name="$f" 'BEGIN {
            while ((getline part < "order.txt") > 0) {
                path = part "/" name; k = 0
                while ((r = (getline line < path)) > 0) if (k++ > 0 || n == 0) print line
                if (r < 0 || k == 0) { print "compare: cannot read " path > "/dev/stderr"; exit 1 }
                close(path); n++
            }
        }') > "$out/$f.tmp"
        mv "$out/$f.tmp" "$out/$f"
    done
    rm -rf "$parts"
    end=$(date +%s)
    {
        echo "study=$study"
        echo "scenes=$scenes"
        echo "methods=${methods:-all}"
        echo "jobs=$jobs"
        echo "reps=$reps"
        echo "run_wall_s=$((end - start))"
        echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
        echo "cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)"
        echo "cores=$(nproc 2>/dev/null || echo '?')"
        echo "sundials=$(dpkg-query -W -f='${Version}' libsundials-dev 2>/dev/null || echo '?')"
        echo "gsl=$(dpkg-query -W -f='${Version}' libgsl-dev 2>/dev/null || echo '?')"
        # The LAPACK Simbody factors with (Debian's alternatives: OpenBLAS or
        # the reference one move its results; docs/compare.md).
        echo "lapack=$(readlink -f "$(ldconfig -p 2>/dev/null | awk '$1 == "liblapack.so.3" { print $NF; exit }')" 2>/dev/null || echo '?')"
        "$bin" versions
    } > "$out/meta.txt"
    if [ $report -eq 0 ]; then
        echo "compare: runs done in $((end - start)) s; CSV files in $out" >&2
        exit 0
    fi
    echo "compare: runs done in $((end - start)) s; plotting" >&2
    sh "$here/plot.sh" "$out"
    end2=$(date +%s)
    echo "plot_wall_s=$((end2 - end))" >> "$out/meta.txt"
    "$bin" report --dir "$out"
    end3=$(date +%s)
    echo "total_wall_s=$((end3 - start))" >> "$out/meta.txt"
    echo "compare: wrote $out/report.md ($((end3 - start)) s in all)" >&2
}

if [ $mode = merge ]; then
    merge
    exit 0
fi

# What the calling make said: -n (print, run nothing), -jN, and whether its
# jobserver reached us (its descriptors are open only in a `+` recipe).
dry=0 jobserver=0 makej="" first=1
set -f
for w in ${MAKEFLAGS:-}; do
    case $w in
    --) break ;;
    --jobserver-auth=fifo:*) [ ! -p "${w#--jobserver-auth=fifo:}" ] || jobserver=1 ;;
    --jobserver-auth=*|--jobserver-fds=*)
        r=${w#*=}; r=${r%%,*}
        [ ! -p "/proc/$$/fd/$r" ] || jobserver=1 ;;
    -j) makej=unlimited ;;
    -j*) makej=${w#-j} ;;
    -*) ;;
    *) if [ $first -eq 1 ]; then case $w in *n*) dry=1 ;; esac; fi ;;
    esac
    first=0
done
set +f
if [ $dry -eq 1 ]; then
    echo "compare/run.sh: make -n: the study is not run" >&2
    exit 0
fi
if [ $mode = list ]; then
    how="exported"
elif [ $jobserver -eq 1 ]; then
    how="make's jobserver (-j$makej)"
    jobs=$makej
else
    # -j without a number has no jobserver: one process per core.
    case $makej in
    unlimited) jobs=$(nproc 2>/dev/null || echo 2) ;;
    1) jobs=1 ;;
    esac
    how="$jobs at a time"
fi

[ -n "$scenes" ] || scenes=$("$bin" scenes "$study")
start=$(date +%s)
mkdir -p "$out"
rm -rf "$parts"
mkdir -p "$parts"
"$bin" plan --study "$study" --scenes "$scenes" --methods "$methods" --reps "$reps" \
    > "$parts/plan.txt"
nrun=$(grep -c '^job ' "$parts/plan.txt" || true)
nprep=$(grep -c '^prepare ' "$parts/plan.txt" || true)
if [ "$nrun" -eq 0 ]; then
    echo "compare: no runs for scenes '$scenes' and methods '${methods:-all}'" >&2
    exit 1
fi
# What merge needs to write meta.txt (read back by --merge).
{
    echo "study=$(q "$study")"
    echo "scenes=$(q "$scenes")"
    echo "methods=$(q "$methods")"
    echo "reps=$(q "$reps")"
    if [ $mode = list ]; then echo "jobs=exported"; else echo "jobs=$(q "$jobs")"; fi
    echo "start=$start"
} > "$parts/settings"

if [ $mode = list ]; then
    # Self-contained commands: the repository (scene files are found
    # relative to it), the binary and the directories as absolute paths.
    repo=$(pwd)
    case $bin in /*) abin=$bin ;; *) abin=$repo/$bin ;; esac
    case $parts in /*) aparts=$parts ;; *) aparts=$repo/$parts ;; esac
    run="mkdir -p $(q "$aparts") && cd $(q "$repo") && $(q "$abin") run --study $(q "$study")"
    run="$run --scenes $(q "$scenes")"
    run="$run --methods $(q "$methods") --reps $(q "$reps") --refdir $(q "$aparts")"
    mkdir -p "$out/jobs"
    awk -v run="$run" -v parts="$aparts" '$1 == "prepare" {
        printf "%s --prepare %s --out \x27%s/p%s\x27 2>> \x27%s/p%s.log\x27\n", run, $2, parts, $2, parts, $2 }' \
        "$parts/plan.txt" > "$out/jobs/prepare.txt"
    awk -v run="$run" -v parts="$aparts" '$1 == "job" {
        printf "%s --job %s --out \x27%s/j%s\x27 2>> \x27%s/j%s.log\x27\n", run, $2, parts, $2, parts, $2 }' \
        "$parts/plan.txt" > "$out/jobs/runs.txt"
    echo "compare: study '$study', scenes: $scenes; methods: ${methods:-all}:" \
         "$nprep references in $out/jobs/prepare.txt, $nrun runs in $out/jobs/runs.txt." >&2
    echo "Run the first list, then the second (e.g. parallel < $out/jobs/prepare.txt &&" \
         "parallel < $out/jobs/runs.txt), then: sh compare/run.sh --merge --bin $bin --out $out" >&2
    exit 0
fi

echo "compare: study '$study', scenes: $scenes; methods: ${methods:-all}; $nrun runs" \
     "($nprep references), one process each, $how; best of $reps" >&2

# The makefile: references first (the runs of a group wait for theirs), then
# the runs in plan order. Names and values reach the recipes through the
# environment, so that nothing in them is expanded by make.
{
    echo "# Generated by compare/run.sh: the steps of one study."
    echo "override RUN := \"\$\$BRAUN_CMP_BIN\" run --study \"\$\$BRAUN_CMP_STUDY\"" \
         "--scenes \"\$\$BRAUN_CMP_SCENES\" --methods \"\$\$BRAUN_CMP_METHODS\"" \
         "--reps \"\$\$BRAUN_CMP_REPS\" --t0 \"\$\$BRAUN_CMP_T0\" --refdir \"\$\$BRAUN_CMP_PARTS\""
    awk '$1 == "prepare" { p = p " p" $2 } $1 == "job" { j = j " j" $2 }
         END { print ".PHONY: all" p j; print "all:" p j }' "$parts/plan.txt"
    awk '$1 == "prepare" { printf "p%s:\n\t@$(RUN) --prepare %s --out \"$$BRAUN_CMP_PARTS/p%s\"\n", $2, $2, $2 }
         $1 == "job" { printf "j%s: p%s\n\t@$(RUN) --job %s --out \"$$BRAUN_CMP_PARTS/j%s\"\n", $2, $3, $2, $2 }' \
        "$parts/plan.txt"
} > "$parts/steps.mk"
BRAUN_CMP_BIN=$bin BRAUN_CMP_STUDY=$study BRAUN_CMP_SCENES=$scenes BRAUN_CMP_METHODS=$methods
BRAUN_CMP_REPS=$reps BRAUN_CMP_T0=$start BRAUN_CMP_PARTS=$parts
export BRAUN_CMP_BIN BRAUN_CMP_STUDY BRAUN_CMP_SCENES BRAUN_CMP_METHODS BRAUN_CMP_REPS \
    BRAUN_CMP_T0 BRAUN_CMP_PARTS
rc=0
if [ $jobserver -eq 1 ]; then
    ${MAKE:-make} --no-print-directory -f "$parts/steps.mk" all || rc=$?
else
    MAKEFLAGS= ${MAKE:-make} --no-print-directory -j"$jobs" -f "$parts/steps.mk" all || rc=$?
fi
if [ $rc -ne 0 ]; then
    echo "compare: a step failed (make exit $rc); its output is above, the parts in $parts" >&2
    exit 1
fi
merge
