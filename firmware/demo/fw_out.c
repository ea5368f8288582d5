/* Buffered output (see fw_out.h). */
#include "fw_out.h"

#include <stdint.h>
#include <string.h>

static char buf[512];
static size_t used;

void fw_flush(void)
{
    if (used) fw_platform_write(buf, used);
    used = 0;
}

void fw_putc(char c)
{
    if (used == sizeof buf) fw_flush();
    buf[used++] = c;
    if (c == '\n' && used > sizeof buf / 2) fw_flush();
}

void fw_puts(const char *s)
{
    while (*s) fw_putc(*s++);
}

void fw_put_ulong(unsigned long x)
{
    char d[24];
    int k = 0;
    do {
        d[k++] = (char)('0' + (int)(x % 10u));
        x /= 10u;
    } while (x);
    while (k) fw_putc(d[--k]);
}

void fw_put_long(long x)
{
    if (x < 0) {
        fw_putc('-');
        /* -(x + 1) + 1 avoids overflow at LONG_MIN. */
        fw_put_ulong((unsigned long)(-(x + 1)) + 1u);
    } else {
        fw_put_ulong((unsigned long)x);
    }
}

static void put_hex_bits(uint64_t bits, int nibbles)
{
    static const char hex[] = "0123456789abcdef";
    fw_puts("0x");
    for (int i = nibbles - 1; i >= 0; i--) fw_putc(hex[(bits >> (4 * i)) & 15u]);
}

void fw_put_hex_double(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    put_hex_bits(bits, 16);
}

void fw_put_hex_real(braun_real x)
{
#ifdef BRAUN_SINGLE
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    put_hex_bits(bits, 8);
#else
    fw_put_hex_double(x);
#endif
}

void fw_put_dec(double x, int digits)
{
    if (x != x) {
        fw_puts("nan");
        return;
    }
    if (x < 0) {
        fw_putc('-');
        x = -x;
    }
    if (x > 1.7e308) {
        fw_puts("inf");
        return;
    }
    if (digits < 1) digits = 1;
    if (digits > 9) digits = 9;
    int e = 0;
    if (x != 0) {
        /* Bring x into [1, 10); at most ~330 iterations either way. */
        while (x >= 10) {
            x /= 10;
            e++;
        }
        while (x < 1) {
            x *= 10;
            e--;
        }
    }
    /* Round to `digits` digits; carry may give 10.0. */
    unsigned long scale = 1;
    for (int i = 1; i < digits; i++) scale *= 10u;
    unsigned long m = (unsigned long)(x * (double)scale + 0.5);
    if (m >= 10u * scale) {
        m /= 10u;
        e++;
    }
    char d[12];
    for (int i = digits - 1; i >= 0; i--) {
        d[i] = (char)('0' + (int)(m % 10u));
        m /= 10u;
    }
    fw_putc(d[0]);
    if (digits > 1) {
        fw_putc('.');
        for (int i = 1; i < digits; i++) fw_putc(d[i]);
    }
    fw_putc('e');
    fw_putc(e < 0 ? '-' : '+');
    if (e < 0) e = -e;
    if (e < 10) fw_putc('0');
    fw_put_long(e);
}

void fw_kv_real(const char *name, braun_real x)
{
    fw_putc(' ');
    fw_puts(name);
    fw_putc('=');
    fw_put_hex_real(x);
}

void fw_kv_long(const char *name, long x)
{
    fw_putc(' ');
    fw_puts(name);
    fw_putc('=');
    fw_put_long(x);
}

void fw_kv_str(const char *name, const char *s)
{
    fw_putc(' ');
    fw_puts(name);
    fw_putc('=');
    fw_puts(s);
}
