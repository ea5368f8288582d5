# Double-precision operations reachable from the step path of a firmware
# image (tests/firmware/run.sh; docs/firmware.md, "No double on the float
# step path").
#
#   awk -v roots="braun_step ..." -v lib="libbraun.a(" -f double-path.awk \
#       IMAGE.map DIS WORDS
#   DIS:   arm-none-eabi-objdump -d --no-show-raw-insn IMAGE
#   WORDS: arm-none-eabi-objdump -s -j .text -j .data IMAGE
#
# On a Cortex-M4F (fpv4-sp-d16) every double operation is a call: libgcc's
# soft-float helpers (__aeabi_dadd, __aeabi_f2d, __adddf3, ...) or a double
# libm function (sqrt, pow, ceil, __ieee754_*), so the call graph tells.
# It is read from the disassembly: direct calls and tail calls (bl, b to
# another function's first instruction). The calls through pointers (model
# callbacks, the scene element classes, the linear-solver table) are
# covered by taking as roots, besides the named ones, every function whose
# address (with the Thumb bit) is stored in the library's part of the image
# — its code's literal pools, its read-only and initialised data, per the
# link map's origin `lib` — more than a step can reach, never less.
#
# In every function reachable from the roots, each call to a double helper
# must be the conversion of an argument of the error record: the code after
# it, up to the next branch (unconditional jumps inside the function are
# followed), calls nothing but more double helpers and then braun__fail
# (bl, or b as a tail call) — `return braun__fail(d, ..., (double)h,
# (double)t)` converts only when the step fails. Any other double call is
# printed as a violation (the caller classifies those whose source line is
# inside a braun__fail(...) call: an inlined braun__fail).
#
# Output: "roots N", "fn NAME" per reachable function, "allowed FUNC HELPER
# COUNT" per function with error-record conversions, "violation FUNC ADDR
# HELPER" per other double call, "reachable N".
function is_double(n) {
    if (n ~ /^__aeabi_(d[a-z0-9]*|[a-z0-9]+2d|cd[a-z]*)$/) return 1
    if (n ~ /^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord)df[0-9]$/) return 1
    if (n ~ /^__(extendsfdf2|truncdfsf2|fix(uns)?df[a-z]+|float(un)?[a-z]+df)$/) return 1
    if (n ~ /^__ieee754_[a-z0-9_]+$/ && n !~ /f$/) return 1
    if (n ~ /^__kernel_(sin|cos|tan|rem_pio2|standard)$/) return 1
    if (n ~ /^(sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|exp|exp2|expm1|log|log2|log10|log1p|pow|sqrt|cbrt|hypot|ceil|floor|trunc|round|lround|fmod|remainder|ldexp|frexp|modf|scalbn|copysign|nextafter|fmin|fmax)$/) return 1
    return 0
}
# The error recorder: its double arguments are converted just before.
function is_recorder(n) { return n == "braun__fail" }
function is_branch(mn, op) {
    if (mn ~ /^(b|bl|blx|bx)(eq|ne|cs|cc|hs|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al)?(\.[nw])?$/) return 1
    if (mn ~ /^(cbz|cbnz|tbb|tbh)$/) return 1
    if (mn ~ /^(pop|ldm)/ && op ~ /pc/) return 1
    if (mn ~ /^(ldr|mov)/ && op ~ /^pc,/) return 1
    return 0
}
# Name in a branch operand "1234 <name>" (a function's first instruction);
# "" for "<name+0x10>" (inside a function) or a register.
function target(op,    t) {
    if (op !~ /<[^>+]*>$/) return ""
    t = op
    sub(/^.*</, "", t)
    sub(/>$/, "", t)
    return t
}
# Address in a branch operand "1234 <fn+0x10>" (hex, lower case).
function label_addr(op,    a) {
    a = op
    sub(/ .*$/, "", a)
    return tolower(a)
}
function hexval(h,    i, v) {
    h = tolower(h)
    sub(/^0x/, "", h)
    v = 0
    for (i = 1; i <= length(h); i++) v = v * 16 + index("0123456789abcdef", substr(h, i, 1)) - 1
    return v
}
FNR == 1 { nfile++ }
# ---------------------------------------------------------------- link map
nfile == 1 && /^Discarded input sections/ { skip = 1 }
nfile == 1 && /^Linker script and memory map/ { skip = 0; inmap = 1 }
nfile == 1 && inmap && !skip && /^ \.(text|rodata|data)/ {
    secname = $1
    if (NF >= 4) { range($2, $3, $4) } else { pending = 1 }
    next
}
nfile == 1 && pending && NF >= 3 && $1 ~ /^0x/ { range($1, $2, $3); pending = 0; next }
nfile == 1 { pending = 0; next }
# String-literal sections (.rodata.str1.4, .rodata.FN.str1.4: mergeable
# strings, no relocations) hold no address: their words are text, and
# "at\0\0" read as a word once named braun_integrate (0x7461) a root.
function range(a, s, origin) {
    if (index(origin, lib) == 0) return
    if (secname ~ /\.str[0-9]/) return
    nr++
    rs[nr] = hexval(a)
    re[nr] = rs[nr] + hexval(s)
}
# ---------------------------------------------------------------- disassembly
nfile == 2 && /^[0-9a-f]+ <[^>]+>:$/ {
    cur = $2
    sub(/^</, "", cur)
    sub(/>:$/, "", cur)
    if (!(cur in addr)) addr[cur] = $1
    nins[cur] += 0
    next
}
nfile == 2 && /^ +[0-9a-f]+:\t/ && cur != "" {
    n = split($0, f, "\t")
    a = f[1]
    gsub(/[ :]/, "", a)
    k = ++nins[cur]
    imn[cur, k] = f[2]
    iop[cur, k] = n >= 3 ? f[3] : ""
    iad[cur, k] = a
    at[cur, a] = k
    if (f[2] != ".word" && f[2] != ".short" && f[2] != ".byte" && f[2] !~ /^\./) code[cur] = 1
    next
}
# ---------------------------------------------------------------- words (objdump -s)
nfile == 3 && /^ [0-9a-f]+ [0-9a-f]/ {
    base = hexval($1)
    for (i = 2; i <= 5; i++) {
        if (length($i) != 8 || $i !~ /^[0-9a-f]+$/) continue
        wa = base + 4 * (i - 2)
        # inside a section of the library (ranges and words both ascend)
        while (ri <= nr && (ri == 0 || re[ri] <= wa)) ri++
        if (ri > nr || wa < rs[ri]) continue
        w = substr($i, 7, 2) substr($i, 5, 2) substr($i, 3, 2) substr($i, 1, 2)
        words[w] = 1
    }
}
END {
    hexd = "0123456789abcdef"
    for (fn in addr) {
        if (!code[fn]) continue
        h = addr[fn]
        while (length(h) < 8) h = "0" h
        # with the Thumb bit: a function starts at an even address
        last = index(hexd, substr(h, 8, 1)) - 1
        if ((substr(h, 1, 7) substr(hexd, last + 2, 1)) in words) taken[fn] = 1
    }
    nroots = 0
    n = split(roots, r, " ")
    for (i = 1; i <= n; i++)
        if (r[i] in addr) { queue[++qn] = r[i]; seen[r[i]] = 1; nroots++ }
        else print "missing-root " r[i]
    for (fn in taken)
        if (!(fn in seen) && !is_double(fn)) { queue[++qn] = fn; seen[fn] = 1; nroots++ }
    print "roots " nroots
    head = 1
    while (head <= qn) {
        fn = queue[head++]
        nreach++
        print "fn " fn
        for (k = 1; k <= nins[fn]; k++) {
            if (!is_branch(imn[fn, k], iop[fn, k])) continue
            t = target(iop[fn, k])
            if (t == "" || t == fn) continue
            if (is_double(t)) {
                ok = 0
                j = k + 1
                for (steps = 0; steps < 400 && j <= nins[fn]; steps++) {
                    m2 = imn[fn, j]
                    if (m2 ~ /^\./) break
                    if (!is_branch(m2, iop[fn, j])) { j++; continue }
                    t2 = target(iop[fn, j])
                    if (m2 == "bl" && is_double(t2)) { j++; continue }
                    if (m2 ~ /^(bl|b|b\.w|b\.n)$/ && is_recorder(t2)) ok = 1
                    else if (m2 ~ /^(b|b\.w|b\.n)$/ && t2 == "" && (fn SUBSEP label_addr(iop[fn, j])) in at) {
                        j = at[fn, label_addr(iop[fn, j])]
                        continue
                    }
                    break
                }
                if (ok) allowed[fn " " t]++
                else print "violation " fn " " iad[fn, k] " " t
                continue
            }
            if (!(t in seen) && (t in addr)) { queue[++qn] = t; seen[t] = 1 }
        }
    }
    for (key in allowed) print "allowed " key " " allowed[key]
    print "reachable " nreach
}
