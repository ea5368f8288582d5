# The series table compare/series.tsv, checked and written out for its
# readers (the table's own comment says what the columns are):
#   awk -f compare/series.awk -v out=plot compare/series.tsv
#       key|label|colour|dash|point|in, one line per series (compare/plot.sh)
#   awk -f compare/series.awk -v out=c compare/series.tsv
#       the initializers of cmp_series_table[] (compare/cmp_series.c, built
#       into braun-compare and braun-bench by mk/compare.mk, mk/bench.mk)
# A malformed line stops it with FILE:LINE: what is wrong, and exit status 1.
BEGIN {
    FS = "\t+"
    if (out != "plot" && out != "c") { print "series.awk: -v out=plot or -v out=c" > "/dev/stderr"; exit 2 }
    split("steps tol history slider bench", t, " ")
    for (i in t) known[t[i]] = 1
}
function bad(msg) {
    printf "%s:%d: %s\n", FILENAME, FNR, msg > "/dev/stderr"
    failed = 1
    exit 1
}
/^#/ || /^[ \t]*$/ { next }
{
    if (NF != 6) bad("expected 6 tab-separated fields (key, label, colour, dash, point, in), got " NF)
    key = $1; label = $2; colour = $3; dash = $4; pt = $5; tags = $6
    if (split(key, k, ":") != 3 || k[1] == "" || k[2] == "" || k[3] == "")
        bad("key '" key "' is not method:integrator:variant")
    if (key ~ /[ ,|"\\]/) bad("key '" key "' has a space, comma, | or quote")
    if (key in seen) bad("key '" key "' repeated (line " seen[key] ")")
    seen[key] = FNR
    if (label ~ /["|\\]/ || label ~ /^ | $/) bad("label '" label "' has a quote, | or backslash, or blanks at an end")
    if (colour !~ /^#[0-9a-fA-F][0-9a-fA-F][0-9a-fA-F][0-9a-fA-F][0-9a-fA-F][0-9a-fA-F]$/)
        bad("colour '" colour "' is not #rrggbb")
    if (dash !~ /^[0-9]+$/ || pt !~ /^[0-9]+$/) bad("dash and point must be whole numbers")
    if (tags != "-") {
        n = split(tags, tg, ",")
        for (i = 1; i <= n; i++)
            if (!(tg[i] in known)) bad("'" tg[i] "' is not one of steps, tol, history, slider, bench (or -)")
    }
    rows++
    if (out == "plot") {
        print key "|" label "|" colour "|" dash "|" pt "|" tags
    } else {
        printf "{\"%s\", \"%s\", \"%s\", \"%s\", \"%s\", \"%s\", %d, %d, \"%s\"},\n",
            key, k[1], k[2], k[3], label, colour, dash, pt, tags
    }
}
END {
    if (failed) exit 1
    if (!rows) { printf "%s: no series\n", FILENAME > "/dev/stderr"; exit 1 }
}
