/* The value of a real option (--dt, --rtol, --from, gen --angle, ...):
 * one rule for every command, so that no number a double cannot hold
 * becomes another one on the way in. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "braun_cli.h"

/* "0x" after an optional sign: a hexadecimal number, which strtod reads. */
static int hexadecimal(const char *s)
{
    const char *p = (*s == '+' || *s == '-') ? s + 1 : s;
    return p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
}

/* A decimal number as the docs promise (digits, '.', an exponent, a
 * sign): strtod alone also takes leading blanks and hexadecimal floats
 * ("0x1p-10"), which the tool then read without a word. */
int braun_cli_decimal(const char *s)
{
    const char *p = (*s == '+' || *s == '-') ? s + 1 : s;
    return ((*p >= '0' && *p <= '9') || *p == '.') && !hexadecimal(s);
}

int braun_cli_hex_or_blank(const char *s)
{
    return *s == ' ' || *s == '\t' || hexadecimal(s);
}

int braun_cli_integer_text(const char *s)
{
    const char *p = (*s == '+' || *s == '-') ? s + 1 : s;
    if (!(*p >= '0' && *p <= '9')) return 0;
    while (*p >= '0' && *p <= '9') p++;
    return *p == '\0';
}

/* A real number filling the whole argument. NaN and Inf are never
 * meaningful here; nor are numbers a double cannot hold: beyond its range,
 * or nonzero below its smallest normal value (strtod's ERANGE: "1e-400"
 * would read as 0, "1e-310" as a subnormal of a few bits). Each is
 * refused with what is wrong with it. */
int braun_cli_parse_real(const char *opt, const char *s, double *out)
{
    char *end;
    errno = 0;
    if (!braun_cli_decimal(s))
        return braun_cli_error("%s: '%s' is not a decimal number", opt, s);
    double x = strtod(s, &end);
    if (end == s || *end != '\0') return braun_cli_error("%s: '%s' is not a number", opt, s);
    if (!isfinite(x) && errno != ERANGE) return braun_cli_error("%s: '%s' is not finite", opt, s);
    if (errno == ERANGE && (isinf(x) || fabs(x) > 1))
        return braun_cli_error("%s: '%s' is out of range (beyond %g)", opt, s, DBL_MAX);
    if (errno == ERANGE || (x != 0 && fabs(x) < DBL_MIN))
        return braun_cli_error("%s: '%s' underflows: it is below the smallest normal double, %g, "
                               "and would read as %s (write 0 or a larger value)", opt, s, DBL_MIN,
                               x == 0 ? "0" : "a subnormal of a few bits");
    *out = x;
    return 0;
}
