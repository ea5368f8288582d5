# Instructions per function from a QEMU log written with
#   -d in_asm,exec,nochain -D LOG
# (every executed translation block is logged; `nochain` makes chained
# blocks visible too). Usage: awk -f qemu-profile.awk LOG | sort -k2 -nr
# Prints "function instructions executions". Inclusive of nothing: each
# instruction counts for the function it belongs to.
/^IN: / { fn = $2; inblk = 1; cnt = 0; next }
inblk && /^0x[0-9a-f]+:/ { if (cnt == 0) start = $1; cnt++; next }
inblk && /^$/ { if (cnt > 0) { sub(":", "", start); pending = 1 }; inblk = 0; next }
/^Trace / {
    # Trace 0: host [flags/pc/cs_base/tbflags] name
    split($4, f, "/"); key = f[2] "/" f[4]; sub(/^\[/, "", key)
    if (pending) { size[key] = cnt; pending = 0 }
    n = size[key]; name = $5
    ins[name] += n; exe[name]++; total += n
    next
}
END {
    for (k in ins) printf "%s %d %d\n", k, ins[k], exe[k]
    printf "TOTAL %d 0\n", total
}
