/*
 * Text output of the demo, without printf or allocation: the same code
 * runs on the target (semihosting) and on the host (stdout), so both print
 * byte-comparable records.
 *
 * Reals are printed as their exact IEEE-754 bit pattern in hexadecimal
 * (0x%08x for float, 0x%016x for double): no decimal conversion on the
 * target, and the host comparison sees every bit. fw_put_dec gives an
 * approximate decimal for people.
 */
#ifndef FW_OUT_H
#define FW_OUT_H

#include <stddef.h>

#include "braun.h"

/* Provided by the platform: write len bytes (target: semihosting). */
void fw_platform_write(const char *s, size_t len);

void fw_puts(const char *s);
void fw_putc(char c);
void fw_put_long(long x);
void fw_put_ulong(unsigned long x);
/* Exact bits of a braun_real / a double, "0x..." */
void fw_put_hex_real(braun_real x);
void fw_put_hex_double(double x);
/* Approximate decimal, `digits` significant digits, e.g. 1.2346e-07. */
void fw_put_dec(double x, int digits);
/* " name=<hex bits>" and " name=<integer>" */
void fw_kv_real(const char *name, braun_real x);
void fw_kv_long(const char *name, long x);
void fw_kv_str(const char *name, const char *s);
/* Send what is buffered. */
void fw_flush(void);

#endif
