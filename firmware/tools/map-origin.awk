# Bytes of code and read-only data per origin (library archive or object) in
# a GNU ld map file: awk -f map-origin.awk IMAGE.map
# Counts the input sections .text*, .rodata* that were kept (after
# --gc-sections the "Discarded input sections" part of the map is skipped).
/^Discarded input sections/ { skip = 1 }
/^Memory Configuration/ { skip = 0 }
/^Linker script and memory map/ { skip = 0; inmap = 1 }
!inmap || skip { next }
/^ \.(text|rodata)/ {
    if (NF >= 4) { add($3, $4) } else { pending = 1 }
    next
}
pending && NF >= 3 && $1 ~ /^0x/ { add($2, $3); pending = 0; next }
{ pending = 0 }
function add(size, file,   s) {
    s = strtonum_hex(size)
    sub(/^.*\//, "", file)
    sub(/\(.*$/, "", file)
    bytes[file] += s
}
function strtonum_hex(h,   i, c, v) {
    h = tolower(h); sub(/^0x/, "", h); v = 0
    for (i = 1; i <= length(h); i++) { c = index("0123456789abcdef", substr(h, i, 1)) - 1; v = v * 16 + c }
    return v
}
END { for (f in bytes) if (bytes[f] > 0) printf "%7d %s\n", bytes[f], f }
