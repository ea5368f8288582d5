# Floating-point operations actually executed, per function, from
#   1. `objdump -d --no-show-raw-insn BIN` (address -> mnemonic, operands)
#   2. a callgrind profile of BIN taken with --dump-instr=yes
#      --compress-pos=no --compress-strings=no (address -> times executed).
# Usage: awk -f bench/flops.awk objdump.txt callgrind.out
# Prints "function,file,instructions,flops,fp_other" per function with
# instructions collected, sorted by instructions.
#
# flops: IEEE add, sub, mul, div, sqrt, times lanes (sd/ss 1; xmm pd 2,
# ps 4; ymm twice that); a fused multiply-add counts 2. fp_other: compares,
# min/max, sign and abs masks (xorpd/andpd), conversions — floating-point
# instructions that are not flops. Moves and loads count in neither.

function lanes(mn, ops,   w) {
    w = (ops ~ /%ymm/) ? 2 : 1
    if (mn ~ /pd$/) return 2 * w
    if (mn ~ /ps$/) return 4 * w
    return 1
}

function classify(mn, ops,   base) {
    base = mn
    sub(/^v/, "", base)
    if (base ~ /^f(n)?m(add|sub)(sub|add)?[0-9]*(sd|ss|pd|ps)$/) return 2 * lanes(base, ops)
    if (base ~ /^(add|sub|mul|div|sqrt)(sd|ss|pd|ps)$/) return lanes(base, ops)
    return 0
}

function is_other(mn,   base) {
    base = mn
    sub(/^v/, "", base)
    return base ~ /^(u?comis[sd]|cmp[a-z]*(sd|ss|pd|ps)|(max|min)(sd|ss|pd|ps)|(and|andn|or|xor)p[sd]|cvt[a-z0-9]*|round(sd|ss|pd|ps))$/
}

# objdump: "  4136f0:\tmulsd  %xmm1,%xmm0"
FNR == NR {
    if (match($0, /^ *[0-9a-f]+:\t/)) {
        addr = $0
        sub(/^ */, "", addr)
        sub(/:.*/, "", addr)
        rest = $0
        sub(/^ *[0-9a-f]+:\t/, "", rest)
        n = split(rest, w, /[ \t]+/)
        mn = w[1]
        if (mn ~ /^(rep|repz|repnz|lock|notrack|bnd)$/ && n > 1) mn = w[2]
        ops = (n > 1) ? w[n] : ""
        f = classify(mn, ops)
        if (f > 0) flop[addr] = f
        else if (is_other(mn)) other[addr] = 1
    }
    next
}

# callgrind
/^fl=/ { file = substr($0, 4); next }
/^fn=/ { fn = substr($0, 4); fnfile[fn] = file; next }
/^(fi|fe)=/ { next }
/^calls=/ { skip = 1; next }
/^0x[0-9a-f]+ / {
    if (skip) { skip = 0; next }
    a = substr($1, 3)
    sub(/^0+/, "", a)
    c = $3 + 0
    ir[fn] += c
    if (a in flop) fl[fn] += c * flop[a]
    if (a in other) ot[fn] += c
    next
}
{ skip = 0 }

END {
    for (f in ir) printf "%s,%s,%.0f,%.0f,%.0f\n", f, fnfile[f], ir[f], fl[f], ot[f]
}
