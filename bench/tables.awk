# The markdown tables of make bench from its CSV files (bench/bench.sh).
# Usage: awk -f bench/tables.awk -v out=DIR -v meta=FILE [-v series=FILE]
#        targets.csv time.csv instructions.csv flops.csv profile.csv
#        matched_error.csv variants.csv
# Writes DIR/{steps,instructions,rhs,flops,components,profile,matched,
# variants,meta,summary}.md. series: the series table as `braun-bench
# series` prints it (key|label|...), for the labels of matched_error.csv's
# series keys (compare/series.tsv).
BEGIN {
    FS = ","
    baseline = "braun:rk4:-"
    if (series != "") {
        while ((getline line < series) > 0) {
            split(line, sf, "|")
            if (sf[1] != "") label[sf[1]] = sf[2]
        }
        close(series)
    }
}
function label_of(key) { return (key in label) ? label[key] : key }
FNR == 1 { file++; next }

# targets.csv: target,source,n,m,p,rank,energy_law,minimal,h,...
file == 1 {
    T[++nt] = $1; src[$1] = $2; n[$1] = $3; m[$1] = $4; p[$1] = $5; rank[$1] = $6
    law[$1] = $7; minimal[$1] = $8; h[$1] = $9
    next
}
# time.csv: ...,steps(9),item(10),kind,corrections,status(13),rounds,ops(15),
# ns_median(16),ns_q1,ns_q3,ratio_ideal(19),ratio_floor,ratio_free,ns_min(22)
file == 2 {
    k = $1 SUBSEP $10
    ns[k] = $16; q1[k] = $17; q3[k] = $18; ri[k] = $19; rf[k] = $20; rfree[k] = $21
    status[k] = $13; done[k] = $15; steps[k] = $9; nsmin[k] = $22
    next
}
# instructions.csv: target,backend,item,ops,instr_per_op,flops_per_op,core_instr,core_flops,
# fp_other
file == 3 {
    k = $1 SUBSEP $3
    ir[k] = $5; fl[k] = $6; irc[k] = $7; flc[k] = $8
    next
}
# flops.csv: target,item,component,flops
file == 4 {
    fo[$1, $2, $3] = $4
    if (!(($3) in compseen)) { compseen[$3] = 1; comp[++ncomp] = $3 }
    next
}
# profile.csv: target,item,function,group,ops,instructions,flops,fp_other
file == 5 {
    k = $1 SUBSEP $2
    np[k]++
    pf[k, np[k]] = $3; pg[k, np[k]] = $4; pi[k, np[k]] = $6 / ($5 > 0 ? $5 : 1)
    pfl[k, np[k]] = $7 / ($5 > 0 ? $5 : 1)
    next
}
# matched_error.csv: scene,T,error_level,method (a series key),cpu_s,cpu_per_sim_s,ratio,how,runs
file == 6 {
    key = $1 SUBSEP $2 SUBSEP $3
    if (!(key in mseen)) { mseen[key] = 1; mk[++nm] = key }
    if (!(($4) in mmseen)) { mmseen[$4] = 1; mm[++nmm] = $4 }
    mc[key, $4] = $6; mr[key, $4] = $7; mh[key, $4] = $8; mb[key, $4] = $10
    next
}
# variants.csv: variant,flags,item,ns_median,ratio_ideal,instr_per_op,ns_min
file == 7 {
    if (!(($1) in vseen)) { vseen[$1] = 1; vv[++nv] = $1; vflags[$1] = $2 }
    vns[$1, $3] = $4; vri[$1, $3] = $5; vir[$1, $3] = $6; vmin[$1, $3] = $7
    next
}

function num(x) { return x != "" && x != "nan" && x != "-nan" && x != "inf" }
function f0(x) { return num(x) ? sprintf("%.0f", x) : "–" }
function f2(x) { return num(x) ? sprintf("%.2f", x) : "–" }
function f1(x) { return num(x) ? sprintf("%.1f", x) : "–" }
function ratio(a, b) { return (num(a) && num(b) && b > 0) ? a / b : "nan" }
function short(t) { s = t; sub(/^data\//, "", s); return s }
function sz(t) { return n[t] "/" m[t] "/" p[t] (rank[t] < m[t] + p[t] ? " (rank " rank[t] ")" : "") }
function time_cell(k) {
    if (!num(ns[k])) return "–"
    if (status[k] == "ok" || status[k] == "") return f0(ns[k])
    return f0(ns[k]) " (" status[k] " after " done[k] " of " steps[k] " steps)"
}
function sig(x) {
    if (!num(x)) return "–"
    if (x >= 100) return sprintf("%.0f", x)
    if (x >= 10) return sprintf("%.1f", x)
    if (x >= 1) return sprintf("%.2f", x)
    return sprintf("%.3g", x)
}

END {
    while ((getline line < meta) > 0) {
        split(line, kv, "=")
        mv[kv[1]] = substr(line, length(kv[1]) + 2)
    }
    # ------------------------------------------------------------ steps (time)
    f = out "/steps.md"
    print "| target | n/m/p | floor | free | none (ideal) | pos+vel | all | pos+vel / none | all / none | all / floor | all / free |" > f
    print "|---|---|---|---|---|---|---|---|---|---|---|" > f
    for (i = 1; i <= nt; i++) {
        t = T[i]
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | **%s** | %s | %s |\n", short(t), sz(t),
            time_cell(t SUBSEP "step-floor"), time_cell(t SUBSEP "step-free"),
            time_cell(t SUBSEP "step-none"), time_cell(t SUBSEP "step-pv"), time_cell(t SUBSEP "step-all"),
            f2(ri[t, "step-pv"]), f2(ri[t, "step-all"]), f1(rf[t, "step-all"]),
            f2(rfree[t, "step-all"]) > f
    }
    close(f)

    # ------------------------------------------------------------ steps (instructions)
    f = out "/instructions.md"
    print "| target | floor | free | none (ideal) | pos+vel | all | pos+vel / none | all / none | all / floor | all / free |" > f
    print "|---|---|---|---|---|---|---|---|---|---|" > f
    for (i = 1; i <= nt; i++) {
        t = T[i]
        a = ir[t, "step-all"]; z = ir[t, "step-none"]
        printf "| %s | %s | %s | %s | %s | %s | %s | **%s** | %s | %s |\n", short(t),
            f0(ir[t, "step-floor"]), f0(ir[t, "step-free"]), f0(z), f0(ir[t, "step-pv"]), f0(a),
            f2(ratio(ir[t, "step-pv"], z)), f2(ratio(a, z)), f1(ratio(a, ir[t, "step-floor"])),
            f2(ratio(a, ir[t, "step-free"])) > f
    }
    close(f)

    # ------------------------------------------------------------ rhs
    f = out "/rhs.md"
    print "| target | ns floor | ns ideal | ns corrected | corrected / ideal | ideal / floor | instr floor | instr ideal | instr corrected | corrected / ideal |" > f
    print "|---|---|---|---|---|---|---|---|---|---|" > f
    for (i = 1; i <= nt; i++) {
        t = T[i]
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", short(t),
            time_cell(t SUBSEP "rhs-floor"), time_cell(t SUBSEP "rhs-ideal"),
            time_cell(t SUBSEP "rhs-corrected"), f2(ri[t, "rhs-corrected"]), f1(rf[t, "rhs-ideal"]),
            f0(ir[t, "rhs-floor"]), f0(ir[t, "rhs-ideal"]), f0(ir[t, "rhs-corrected"]),
            f2(ratio(ir[t, "rhs-corrected"], ir[t, "rhs-ideal"])) > f
    }
    close(f)

    # ------------------------------------------------------------ flops
    f = out "/flops.md"
    print "| target | step | flops (formula) | of which checks | core flops (measured) | callbacks + libm flops | instr / step | instr / flop (all) | core instr / core flop | ns / step | ns / flop |" > f
    print "|---|---|---|---|---|---|---|---|---|---|---|" > f
    for (i = 1; i <= nt; i++) {
        t = T[i]
        for (j = 1; j <= 2; j++) {
            it = j == 1 ? "step-none" : "step-all"
            k = t SUBSEP it
            printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", short(t),
                j == 1 ? "none" : "all", f0(fo[t, it, "total"]), f0(fo[t, it, "checks"]),
                f0(flc[k]), f0(fl[k] - flc[k]), f0(ir[k]), f1(ratio(ir[k], fl[k])),
                f1(ratio(irc[k], flc[k])), f0(ns[k]), sig(ratio(ns[k], fl[k])) > f
        }
    }
    close(f)

    # ------------------------------------------------------------ components
    f = out "/components.md"
    line = "| target | step"
    sep = "|---|---"
    for (c = 1; c <= ncomp; c++) {
        if (comp[c] == "total_without_checks") continue
        line = line " | " comp[c]; sep = sep "|---"
    }
    print line " |" > f
    print sep "|" > f
    for (i = 1; i <= nt; i++) {
        t = T[i]
        if (n[t] + m[t] + p[t] > 16) continue
        for (j = 1; j <= 3; j++) {
            it = j == 1 ? "step-none" : (j == 2 ? "step-pv" : "step-all")
            line = "| " short(t) " | " (j == 1 ? "none" : (j == 2 ? "pos+vel" : "all"))
            for (c = 1; c <= ncomp; c++) {
                if (comp[c] == "total_without_checks") continue
                v = fo[t, it, comp[c]]
                line = line " | " (comp[c] == "total" ? "**" v "**" : v)
            }
            print line " |" > f
        }
    }
    close(f)

    # ------------------------------------------------------------ profile
    f = out "/profile.md"
    t = "slider-crank"
    print "| function | group | instr / step (none) | instr / step (all) | share (all) | flops / step (all) | instr / flop (all) |" > f
    print "|---|---|---|---|---|---|---|" > f
    ka = t SUBSEP "step-all"; kn = t SUBSEP "step-none"
    for (j = 1; j <= np[kn]; j++) noneir[pf[kn, j]] = pi[kn, j]
    tot = 0
    for (j = 1; j <= np[ka]; j++) tot += pi[ka, j]
    shown = 0
    for (j = 1; j <= np[ka]; j++) {
        if (pi[ka, j] < 0.005 * tot) { rest += pi[ka, j]; restf += pfl[ka, j]; continue }
        cell = "–"
        if (pfl[ka, j] > 0) cell = f1(pi[ka, j] / pfl[ka, j])
        printf "| `%s` | %s | %s | %s | %.1f %% | %s | %s |\n", pf[ka, j], pg[ka, j],
            f0(noneir[pf[ka, j]]), f0(pi[ka, j]), 100 * pi[ka, j] / tot, f0(pfl[ka, j]), cell > f
    }
    if (rest > 0) printf "| (others) | | | %s | %.1f %% | %s | |\n", f0(rest), 100 * rest / tot, f0(restf) > f
    printf "| **total** | | %s | %s | 100 %% | %s | %s |\n", f0(ir[kn]), f0(tot), f0(fl[ka]), f1(ratio(tot, fl[ka])) > f
    close(f)

    # ------------------------------------------------------------ matched
    f = out "/matched.md"
    if (nm == 0) {
        print "Not available: `" mv["compare_csv"] "` did not exist or had no runs when `make bench` ran (run `make compare` first)." > f
    } else {
        line = "| scene | T [s] | error level"
        sep = "|---|---|---"
        for (c = 1; c <= nmm; c++) { line = line " | " label_of(mm[c]); sep = sep "|---" }
        print line " |" > f
        print sep "|" > f
        for (i = 1; i <= nm; i++) {
            split(mk[i], kk, SUBSEP)
            line = "| " kk[1] " | " kk[2] " | " kk[3]
            for (c = 1; c <= nmm; c++) {
                key = mk[i] SUBSEP mm[c]
                if (!(key in mh)) { line = line " | "; continue }
                if (mh[key] == "not-reached") { line = line " | not reached (best " mb[key] ")"; continue }
                cell = (mh[key] == "cheapest-run" ? "≤ " : "") sig(1e3 * mc[key])
                if (mm[c] != baseline && num(mr[key])) cell = cell " (×" sig(mr[key]) ")"
                line = line " | " cell
            }
            print line " |" > f
        }
        print "" > f
        print "CPU milliseconds per simulated second (× " label_of(baseline) ") from `" mv["matched_from"] "`; ≤: the cheapest run is already below the level (an upper bound); not reached: no run that reached T got there (best maximum error in brackets)." > f
    }
    close(f)

    # ------------------------------------------------------------ variants
    f = out "/variants.md"
    if (nv == 0) {
        print "Not run (`BENCH_VARIANTS=0`)." > f
    } else {
        print "| build | flags | instr / step none | instr / step all | instr all vs O2 | ns / step all: median | fastest round | fastest vs O2 | all / none (same process) |" > f
        print "|---|---|---|---|---|---|---|---|---|" > f
        for (i = 1; i <= nv; i++) {
            v = vv[i]
            printf "| %s | `%s` | %s | %s | %s | %s | %s | %s | %s |\n", v, vflags[v],
                f0(vir[v, "step-none"]), f0(vir[v, "step-all"]),
                f2(ratio(vir[v, "step-all"], vir["O2", "step-all"])),
                f0(vns[v, "step-all"]), f0(vmin[v, "step-all"]),
                f2(ratio(vmin[v, "step-all"], vmin["O2", "step-all"])), f2(vri[v, "step-all"]) > f
        }
    }
    close(f)

    # ------------------------------------------------------------ meta, summary
    f = out "/meta.md"
    printf "Measured %s on %s (%s cores; load average %s at the start, %s at the end), %s, %s rounds of %s steps; `make bench` took %s s.\n", \
        mv["date"], mv["cpu"], mv["cores"], mv["load_at_start"], mv["load_at_end"], mv["compiler"], mv["rounds"], mv["steps"], mv["wall_s"] > f
    close(f)

    f = out "/summary.md"
    t = "slider-crank"
    if (!((t SUBSEP "step-all") in ns)) {
        print "The slider-crank was not among the targets of this run." > f
        close(f)
        exit
    }
    k = t SUBSEP "step-all"; kn = t SUBSEP "step-none"
    print "| slider-crank, RK4, h = 1e-3, all corrections | measured | target (issue 7) | |" > f
    print "|---|---|---|---|" > f
    printf "| corrected / ideal step, time (median of per-round ratios) | **%s** | ≤ 1.5 | %s |\n", f2(ri[k]), (num(ri[k]) && ri[k] <= 1.5 ? "met" : "not met") > f
    printf "| corrected / ideal step, instructions (callgrind) | **%s** | ≤ 1.5 | %s |\n", f2(ratio(ir[k], ir[kn])), (ratio(ir[k], ir[kn]) <= 1.5 ? "met" : "not met") > f
    printf "| ns per corrected step (median, CPU time) | **%s** (quartiles %s–%s) | < 1000 | %s |\n", f0(ns[k]), f0(q1[k]), f0(q3[k]), (num(ns[k]) && ns[k] < 1000 ? "met" : sprintf("not met: ×%.2f over", ns[k] / 1000)) > f
    printf "| ns per corrected step, fastest of the rounds | %s | | load only adds time |\n", f0(nsmin[k]) > f
    printf "| ns per ideal step (median; fastest) | %s; %s | | |\n", f0(ns[kn]), f0(nsmin[kn]) > f
    printf "| instructions per corrected / ideal step | %s / %s | | |\n", f0(ir[k]), f0(ir[kn]) > f
    printf "| flops per corrected step (all / core) | %s / %s | | %s instructions and %s ns per flop |\n", f0(fl[k]), f0(flc[k]), f1(ratio(ir[k], fl[k])), sig(ratio(ns[k], fl[k])) > f
    printf "| corrected step / minimal-coordinate RK4 step (floor) | %s (time), %s (instructions) | | |\n", f1(rf[k]), f1(ratio(ir[k], ir[t, "step-floor"])) > f
    ks = t SUBSEP "step-special"
    if (ks in ns) {
        printf "| ideal step written out by hand (`bench/bench_special.c`, the specialised floor; its trajectory ends %s from the ideal step's) | %s ns (median; fastest %s), %s instructions | | %s of the ideal step's time |\n", special_agreement, f0(ns[ks]), f0(nsmin[ks]), f0(ir[ks]), f2(ri[ks]) > f
        v = "fixed-O3-lto"
        if ((v SUBSEP "step-special") in vns)
            printf "| fixed sizes `-O3 -flto`: written-out ideal / ideal / corrected step, medians | %s / %s / %s ns | corrected ≤ 500 (issue 16) | %s |\n", f0(vns[v, "step-special"]), f0(vns[v, "step-none"]), f0(vns[v, "step-all"]), (num(vns[v, "step-all"]) && vns[v, "step-all"] <= 500 ? "met" : "not met") > f
    }
    close(f)
}
