# Tables of make scaling (markdown): cost per step, slopes, equal error.
# Input files: step.csv, slopes.csv, [matched.csv] (in that order).
BEGIN { FS = "," }
FNR == 1 { file++; next }
file == 1 {
    key = $1 SUBSEP $2; kinds[$1] = 1; Ns[$1, $2] = 1; backends[$6] = 1
    cell[$1, $2, $6] = ($7 == "nan" || $7 == "") ? ($11 ~ /skipped/ ? "–" : "fail") : sprintf("%.3g", $7 / 1000)
    nn[$1, $2] = $4; rows[$1, $2] = $5
    if ($10 > 0) rd[$1, $2] = 1
}
file == 2 { slope[$1, $2] = $3; pts[$1, $2] = $4 " points, N " $5 "–" $6 }
file == 3 { mrow[++nm] = $0 }
END {
    nb = split("dense lapack suitesparse ida-klu", order, " ")
    for (k in kinds) {
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
        printf "\nSlope of log(cost per step) on log(N), N ≥ 100:"
        for (j = 1; j <= nb; j++) if ((k, order[j]) in slope) printf " %s **%s** (%s);", order[j], slope[k, order[j]], pts[k, order[j]]
        printf "\n"
    }
    if (nm > 0) {
        printf "\n**Chain, N = 1000, equal error**: max trajectory error against CPU seconds per simulated second\n\n"
        printf "| method | h | rtol | error | CPU s per simulated s | status |\n|---|---|---|---|---|---|\n"
        for (i = 1; i <= nm; i++) {
            split(mrow[i], f, ",")
            printf "| %s | %s | %s | %s | %s | %s |\n", f[3], f[5], f[6], f[7], f[8], f[9]
        }
    }
}
