# Tables of make scaling (markdown): cost per step, slopes, equal error.
# Input files: step.csv, slopes.csv, [matched.csv] (in that order).
BEGIN { FS = "," }
FNR == 1 { file++; next }
file == 1 {
    key = $1 SUBSEP $2; kinds[$1] = 1; Ns[$1, $2] = 1; backends[$6] = 1
    cell[$1, $2, $6] = ($7 == "nan" || $7 == "") ? ($11 ~ /skipped/ ? "–" : "fails") : sprintf("%.3g", $7 / 1000)
    if ($11 ~ /^failed/) why[$1, $6] = $6 " " $11 " (N = " $2 ")"
    if ($11 ~ /^skipped: no /) why[$1, $6] = $6 " " substr($11, 10)
    if ($4 != "") { nn[$1, $2] = $4; rows[$1, $2] = $5 }
    if ($10 > 0) rd[$1, $2] = 1
}
file == 2 {
    # several ranges per (kind, backend): listed in the order of slopes.csv
    ns = ++nsl[$1, $2]; slope[$1, $2, ns] = $3; pts[$1, $2, ns] = $4 " points, N " $5 "–" $6
}
file == 1 && $7 != "nan" && $7 != "" { ns_step[$1, $2, $6] = $7 }
file == 3 {
    mrow[++nm] = $0
    if ($7 != "nan" && $7 > 0 && $9 == "ok") {
        g = ($3 ~ /^braun/) ? "braun" : ($3 == "ida-klu" ? "ida" : "")
        if (g != "") { k = ++np[g]; perr[g, k] = $7; pcost[g, k] = $8 }
    }
}
END {
    nb = split("dense lapack suitesparse ida-klu", order, " ")
    nk = split("chain ladder spatial-chain", korder, " ")
    for (ki = 1; ki <= nk; ki++) {
        k = korder[ki]
        if (!(k in kinds)) continue
        printf "\n**%s**: CPU µs per step (corrected RK4 step for braun's backends; one BDF step for IDA+KLU)\n\n", k
        printf "| N | n | rows |"
        for (i = 1; i <= nb; i++) if (order[i] in backends) printf " %s |", order[i]
        printf "\n|---|---|---|"
        for (i = 1; i <= nb; i++) if (order[i] in backends) printf "---|"
        printf "\n"
        # N in numeric order
        m = 0
        for (x in Ns) { split(x, p, SUBSEP); if (p[1] == k) list[++m] = p[2] + 0 }
        for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (list[j] < list[i]) { t = list[i]; list[i] = list[j]; list[j] = t }
        for (i = 1; i <= m; i++) {
            N = list[i]
            printf "| %d | %s | %s |", N, nn[k, N], rows[k, N]
            for (j = 1; j <= nb; j++) if (order[j] in backends) printf " %s |", ((k, N, order[j]) in cell) ? cell[k, N, order[j]] : ""
            printf "\n"
        }
        delete list
        for (j = 1; j <= nb; j++)
            if ((k, order[j]) in why)
                printf "\n%s%s.\n", why[k, order[j]], why[k, order[j]] ~ /failed/ ? "; larger N not tried" : ": not run"
        printf "\nSlope of log(cost per step) on log(N), from N = 100%s:", k == "spatial-chain" ? " and from N = 10" : ""
        for (j = 1; j <= nb; j++)
            for (r = 1; r <= nsl[k, order[j]]; r++)
                printf " %s **%s** (%s);", order[j], slope[k, order[j], r], pts[k, order[j], r]
        printf "\n"
        # Cost per body against the planar chain's at the same N (suitesparse).
        per = (k == "ladder") ? 4 : (k == "spatial-chain" ? 1 : 0)
        if (per > 0) {
            line = ""
            for (i = 1; i <= m2; i++) delete list2[i]
            m2 = 0
            for (x in Ns) { split(x, p, SUBSEP); if (p[1] == k) list2[++m2] = p[2] + 0 }
            for (i = 1; i <= m2; i++) for (j = i + 1; j <= m2; j++) if (list2[j] < list2[i]) { t = list2[i]; list2[i] = list2[j]; list2[j] = t }
            for (i = 1; i <= m2; i++) {
                N = list2[i]
                if ((k, N, "suitesparse") in ns_step && ("chain", N, "suitesparse") in ns_step)
                    line = line sprintf(" N = %d: **%.2f**;", N, ns_step[k, N, "suitesparse"] / per / ns_step["chain", N, "suitesparse"])
            }
            if (line != "")
                printf "\n%s against the chain, cost per body on SuiteSparse (%s):%s\n", k,
                    per == 4 ? "4 bodies per cell" : "one bar against one link", line
        }
    }
    if (nm > 0) {
        printf "\n**Chain, N = 1000, equal error**: max trajectory error against CPU seconds per simulated second\n\n"
        printf "| method | h | rtol | error | CPU s per simulated s | status |\n|---|---|---|---|---|---|\n"
        for (i = 1; i <= nm; i++) {
            split(mrow[i], f, ",")
            printf "| %s | %s | %s | %s | %s | %s |\n", f[3], f[5], f[6], f[7], f[8], f[9]
        }
        printf "\nCost at equal error (log-log interpolation between the measured runs; – outside a method's range):\n\n"
        printf "| error | braun (suitesparse, RK4): CPU s per simulated s | IDA+KLU | IDA / braun |\n|---|---|---|---|\n"
        ne = split("1e-4 3e-5 1e-5 3e-6 1e-6", lv, " ")
        for (i = 1; i <= ne; i++) {
            e = lv[i] + 0
            cb = interp("braun", e); ci = interp("ida", e)
            printf "| %s | %s | %s | %s |\n", lv[i], cb < 0 ? "–" : sprintf("%.3g", cb),
                ci < 0 ? "–" : sprintf("%.3g", ci), (cb > 0 && ci > 0) ? sprintf("**%.2f**", ci / cb) : "–"
        }
    }
}

# Cost of method g at error e: linear in log-log between the closest pair of
# runs whose errors bracket e (the cheaper one less accurate); -1 if none.
function interp(g, e,    i, j, a, b, t, best, bi, bj) {
    best = -1
    for (i = 1; i <= np[g]; i++)
        for (j = 1; j <= np[g]; j++) {
            a = perr[g, i]; b = perr[g, j]
            if (a >= e && b <= e && a > b && pcost[g, j] >= pcost[g, i] &&
                (best < 0 || log(a) - log(b) < best)) { best = log(a) - log(b); bi = i; bj = j }
        }
    if (best < 0) return -1
    a = perr[g, bi]; b = perr[g, bj]
    t = (log(e) - log(a)) / (log(b) - log(a))
    return exp(log(pcost[g, bi]) + t * (log(pcost[g, bj]) - log(pcost[g, bi])))
}
